"""MkDocs hook: the validation chapter's tables, computed at this build.

Each line `<!-- validation: NAME -->` of docs/guide/validation.md becomes a table that puts the
published numbers beside whipple's and their difference, with the command that reproduces
whipple's. The published numbers come from their one Python home,
crates/whipple-py/tests/reference.py (the Python tests compare against the same), and from
BicycleParameters' own results kept with the test data (reference.json); whipple's come from
running the commands shown, by the binary in $WHIPPLE_GUIDE_BIN (docs/build-guide builds it),
and, for the numbers the command line does not print (Basu-Mandal's accelerations, the
leaning rider's state matrices, the measurement pipeline's every σ), from the installed Python
package. The comparisons with BicycleParameters and yeadon running beside whipple (Moore 2012's
leaning rider, the measurement pipeline, add_rider) are set up as the Python tests set them up,
by crates/whipple-py/tests/crosscheck.py; both come from docs/requirements.txt (tools of the
build, never dependencies). Nothing here computes dynamics: it reads, subtracts and formats.
An unknown name, a table left out or a command that fails fails the build.
"""

import importlib.util
import json
import math
import os
import re
import shlex
import subprocess
from pathlib import Path

from mkdocs.exceptions import PluginError

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "crates" / "whipple" / "tests" / "data"
CHAPTER = "guide/validation.md"
MARKER = re.compile(r"^<!-- validation: ([a-z0-9-]+) -->[ \t]*$", re.M)
TIMEOUT = 600


def _reference():
    path = ROOT / "crates" / "whipple-py" / "tests" / "reference.py"
    spec = importlib.util.spec_from_file_location("whipple_published_reference", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _crosscheck():
    """crates/whipple-py/tests/crosscheck.py, and BicycleParameters (imported)."""
    try:
        import bicycleparameters
        import yeadon  # noqa: F401 - add_rider's body model
    except ImportError as error:
        raise PluginError(f"{CHAPTER}: BicycleParameters and yeadon run beside whipple here "
                          f"({error}); docs/requirements.txt pins them")
    path = ROOT / "crates" / "whipple-py" / "tests" / "crosscheck.py"
    spec = importlib.util.spec_from_file_location("whipple_crosscheck", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module, bicycleparameters


def _json(command, cwd=None):
    """whipple's JSON answer to `command` (as shown in the chapter)."""
    binary = os.environ.get("WHIPPLE_GUIDE_BIN")
    if not binary or not Path(binary).is_file():
        raise PluginError("the validation chapter runs whipple: set WHIPPLE_GUIDE_BIN to a built "
                          "whipple binary (docs/build-guide does)")
    words = shlex.split(command)
    try:
        run = subprocess.run([binary, *words[1:]], cwd=cwd, capture_output=True, text=True,
                             timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        raise PluginError(f"{CHAPTER}: `{command}` gave no answer in {TIMEOUT} s")
    if run.returncode != 0:
        raise PluginError(f"{CHAPTER}: `{command}` failed ({run.returncode}): {run.stderr.strip()}")
    return json.loads(run.stdout)


def _num(x):
    """A number as its shortest round-trip form (the published ones as printed)."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        raise PluginError(f"{CHAPTER}: a number to show is {x}")
    return repr(float(x))


def _sci(x):
    """A small number in two digits: 4.4e-15, or 0."""
    if x == 0:
        return "0"
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _diff(a, b):
    return _sci(abs(a - b))


def _table(head, rows, command, note="", how=None):
    worst = max((abs(p - o) for *_, p, o in rows), default=0.0)
    lines = [f"Reproduce: {how or f'`{command}`'}", ""]
    lines.append("| " + " | ".join([*head, "published", "whipple", "difference"]) + " |")
    lines.append("|" + "---|" * (len(head) + 3))
    for *labels, published, ours in rows:
        lines.append("| " + " | ".join([*labels, _num(published), _num(ours), _diff(published, ours)])
                     + " |")
    lines += ["", f"Largest difference: {_sci(worst)}{note}.", ""]
    return "\n".join(lines)


def _matrices(ref):
    command = "whipple matrices --bike benchmark --format json"
    ours = _json(command)
    rows = []
    for name in ("M", "C1", "K0", "K2"):
        for i in range(2):
            for j in range(2):
                rows.append((f"{name}[{i + 1},{j + 1}]", getattr(ref, name)[i][j], ours[name][i][j]))
    return _table(["entry"], rows, command, " (the published entries are rounded to 14 decimals)")


def _table_2(ref):
    command = "whipple eig --bike benchmark --speeds 0:10:1 --format json"
    ours = {round(r["v"], 9): r["eigenvalues"] for r in _json(command)["rows"]}
    rows = []
    at_rest = sorted((e["re"] for e in ours[0.0]), reverse=True)
    for k, (published, mine) in enumerate(zip(ref.AT_REST, at_rest)):
        rows.append(("0", f"real eigenvalue {k + 1}", published, mine))
    for v, weave_re, weave_im, capsize, castering in ref.TABLE_2:
        found = ours[round(v, 9)]
        weave = next(e for e in found if e["mode"] == "weave" and e["im"] > 0)
        cap = next(e for e in found if e["mode"] == "capsize")
        cas = next(e for e in found if e["mode"] == "castering")
        label = f"{v:g}"
        rows += [(label, "weave, real part", weave_re, weave["re"]),
                 (label, "weave, imaginary part", weave_im, weave["im"]),
                 (label, "capsize", capsize, cap["re"]),
                 (label, "castering", castering, cas["re"])]
    return _table(["v [m/s]", "eigenvalue [1/s]"], rows, command,
                  " (Table 2 carries round-off of up to about 6e-13)")


def _speeds(ref):
    command = "whipple speeds --bike benchmark --format json"
    ours = _json(command)
    pair = next(c for c in ours["crossings"] if c["kind"] == "pair")
    rows = [("double-root speed v_d [m/s]", ref.DOUBLE_ROOT_SPEED, ours["double_root_speed"]),
            ("double eigenvalue at v_d [1/s]", ref.DOUBLE_ROOT_EIGENVALUE,
             ours["double_root_eigenvalue"]),
            ("weave speed v_w [m/s]", ref.WEAVE_SPEED, ours["weave_speed"]),
            ("weave frequency at v_w [rad/s]", ref.WEAVE_FREQUENCY, pair["frequency"]),
            ("capsize speed v_c [m/s]", ref.CAPSIZE_SPEED, ours["capsize_speed"])]
    return _table(["quantity"], rows, command)


def _basu_mandal(ref):
    import whipple

    ours, out = ref.basu_mandal_accelerations(whipple.Bicycle.preset("benchmark"))
    rows = [(name, p, o) for name, p, o in zip(ref.BASU_MANDAL_NAMES, ref.BASU_MANDAL_OUTPUT, ours)]
    how = ("in Python, `whipple.Bicycle.preset(\"benchmark\").accelerations(...)` at the "
           "paper's state, converted to its conventions by `basu_mandal_accelerations` of "
           "crates/whipple-py/tests/reference.py")
    text = _table(["acceleration (their names and senses)"], rows, None,
                  " (the published values carry 13 significant digits)", how=how)
    residuals = (f"The state lies on the constraints: largest holonomic residual "
                 f"{_sci(out['holonomic_residual'])} m, velocity residual "
                 f"{_sci(out['velocity_residual'])} m/s.")
    return text + "\n" + residuals + "\n"


def _dressel(ref):
    command = "whipple validate --bike schwinn-crown --speeds 0:10:0.01 --format json"
    ours = _json(command)
    peaks = {}
    for method in ("fd", "ad"):
        worst = max(ours["rows"], key=lambda r: r["methods"][method]["max_abs_diff"])
        peaks[method] = (worst["methods"][method]["max_abs_diff"], worst["v"])
    fd, ad = peaks["fd"], peaks["ad"]
    v_c = ours["capsize_speed"]
    return "\n".join([
        f"Reproduce: `{command}`",
        "",
        "| largest eigenvalue difference, non-linear against linear, 0–10 m/s | the study | whipple |",
        "|---|---|---|",
        f"| finite differences over the full state (the study's method) | just under "
        f"{_sci(ref.DRESSEL_FD_PEAK)}, near v_c | {_sci(fd[0])} at {fd[1]:.2f} m/s (v_c = {v_c:.3f} m/s) |",
        f"| exact derivatives, reduced to lean and steer | — | {_sci(ad[0])} at {ad[1]:.2f} m/s |",
        "",
    ])


def _bicycleparameters(ref):
    reference = json.loads((DATA / "bicycleparameters" / "reference.json").read_text())
    version = reference["bicycleparameters"]
    lines = ["Reproduce, in `crates/whipple/tests/data` of a clone: "
             "`whipple speeds --bike FILE --range 0:20 --format json`", "",
             f"| file | BicycleParameters {version} | whipple | difference |", "|---|---|---|---|"]
    worst, compared = 0.0, 0

    def show(ranges):
        return "; ".join(f"{a:.12g} .. {b:.12g}" for a, b in ranges)

    for name, entry in sorted(reference["files"].items()):
        if "bicycleparameters_error" in entry:
            mine = _json(f"whipple speeds --bike {name} --range 0:20 --format json", cwd=DATA)
            lines.append(f"| `{name}` | fails: {entry['bicycleparameters_error']} | "
                         f"{show(mine['stable_speed_ranges'])} | — |")
            continue
        mine = _json(f"whipple speeds --bike {name} --range 0:20 --format json", cwd=DATA)
        theirs, ours = entry["stable_speed_ranges"], mine["stable_speed_ranges"]
        if len(theirs) != len(ours):
            raise PluginError(f"{CHAPTER}: {name}: {len(ours)} stable ranges, BicycleParameters "
                              f"{len(theirs)}")
        difference = max((abs(a - b) for t, o in zip(theirs, ours) for a, b in zip(t, o)),
                         default=0.0)
        worst, compared = max(worst, difference), compared + 1
        lines.append(f"| `{name}` | {show(theirs)} | {show(ours)} | {_sci(difference)} |")
    lines += ["", f"{compared} files compared; largest difference {_sci(worst)} m/s (the ends "
              "printed to 12 significant digits; BicycleParameters' ends are its root finder's, "
              "to 1e-14; 20 m/s is the end of the range searched, not a critical speed).", ""]
    return "\n".join(lines)


def _humancontrol(ref):
    folder = DATA / "humancontrol"
    table = "gains/BenchmarkSteerGains.txt"
    names = ("kDelta", "kPhiDot", "kPhi", "kPsi", "kY")
    rows = [line.split(",") for line in (folder / table).read_text().split()[1:]]
    lines = ["Reproduce, in `crates/whipple/tests/data/humancontrol` of a clone: "
             f"`whipple control hess --bike BenchmarkPar.txt --gains {table} --speed V --format json`"
             " (HumanControl's gains closed by whipple) and `... --rules ...` (whipple's gains)", "",
             "| v [m/s] | HumanControl's gains kδ, kφ̇, kφ, kψ, ky | whipple's by the rules | "
             "largest relative difference (kδ, kφ̇) | crossovers of HumanControl's gains: φ, ψ, y "
             "[rad/s] | closed loop |", "|---|---|---|---|---|---|"]
    found = []
    for v, *published in rows:
        published = [float(k) for k in published]
        closed = _json(f"whipple control hess --bike BenchmarkPar.txt --gains {table} --speed {v} "
                       "--format json", cwd=folder)
        rules = _json(f"whipple control hess --bike BenchmarkPar.txt --rules --speed {v} "
                      "--format json", cwd=folder)
        if closed["extrapolated"] or [closed["gains"][n] for n in names] != published:
            raise PluginError(f"{CHAPTER}: {table} at {v} m/s was not used as tabulated")
        ours = [rules["gains"][n] for n in names]
        inner = max(abs(o - p) / abs(p) for o, p in zip(ours[:2], published[:2]))
        crossings = {l["loop"]: [c["frequency"] for c in l["crossovers"]] for l in closed["loops"]}
        once = all(len(crossings[name]) == 1 for name in ("phi", "psi", "y"))
        off = max(abs(crossings[name][0] - w) / w for name, w in (("phi", 2.0), ("psi", 1.0),
                                                                   ("y", 0.5))) if once else None
        found.append((float(v), inner, off, closed["stable"]))
        shown = "; ".join(", ".join(f"{w:.3f}" for w in crossings[name]) or "none"
                          for name in ("phi", "psi", "y"))
        lines.append(f"| {v} | {', '.join(f'{k:g}' for k in published)} | "
                     f"{', '.join(f'{k:.4g}' for k in ours)} | {inner:.1%} | {shown} | "
                     f"{'stable' if closed['stable'] else 'UNSTABLE'} |")
    near = [row for row in found if row[1] < 0.01]
    tuned = [row for row in found if row[2] is not None]
    if not near or not tuned:
        raise PluginError(f"{CHAPTER}: no row of {table} agrees with the rules")
    lines += ["", "The rules fix the steer and roll-rate loops by their closed-loop damping (0.1289, "
              "0.0855) and the φ, ψ and y loops by their crossover (2, 1, 0.5 rad/s), as "
              "HumanControl's `exact_gains` does. HumanControl's README says its table mixes gains "
              "its software found with gains chosen by hand. Its outer gains, closed by whipple, "
              f"cross over at the rules' frequencies within {max(r[2] for r in tuned):.1%} at every "
              f"speed but {', '.join(f'{r[0]:g}' for r in found if r[2] is None)} m/s (there a loop "
              "crosses 1 more than once: every crossing is shown, certified, none missed). "
              "Its inner gains are the damping rules' solution only at "
              f"{' and '.join(f'{r[0]:g} m/s (within {r[1]:.2%})' for r in near)}; elsewhere they differ "
              "by up to " + f"{max(r[1] for r in found):.0%}" + ", while whipple's own gains meet "
              "the damping rules (its tests check the closed-loop damping at 5 m/s to 1e-9). "
              f"Every row's closed loop is {'stable' if all(r[3] for r in found) else 'NOT stable'}.",
              ""]
    return "\n".join(lines)


def _bmd2016(ref):
    folder = DATA / "humancontrol"
    lines = ["Reproduce, in `crates/whipple/tests/data/humancontrol` of a clone: "
             "`whipple control hqm --bike BIKE --gains GAINS --speed V --format json`", "",
             "| bicycle | design speed [m/s] | its peak HQM, at ω [rad/s] | the benchmark's, at ω "
             "[rad/s] | the benchmark's gains | lower, as published |", "|---|---|---|---|---|---|"]
    lower = 0
    for nn in ref.BMD2016_DESIGN_SPEEDS:
        bike = f"Optimal{nn:02d}Par.txt"
        bike = bike if (folder / bike).is_file() else f"optimal/{bike}"
        mine = _json(f"whipple control hqm --bike {bike} --gains gains/Optimal{nn:02d}SteerGains.txt "
                     f"--speed {nn} --format json", cwd=folder)
        bench = _json(f"whipple control hqm --bike BenchmarkPar.txt --gains gains/BenchmarkSteerGains.txt "
                      f"--speed {nn} --format json", cwd=folder)
        if not mine["roll_loop_stable"]:
            raise PluginError(f"{CHAPTER}: Optimal{nn:02d}'s roll loop is unstable with its gains")
        is_lower = mine["peak"]["magnitude"] < bench["peak"]["magnitude"]
        lower += is_lower
        note = bench["gains_lookup"] + ("" if bench["roll_loop_stable"] else " (its roll loop unstable)")
        lines.append(f"| Optimal{nn:02d} | {nn} | {mine['peak']['magnitude']:.3f}, "
                     f"{mine['peak']['frequency']:.3f} | {bench['peak']['magnitude']:.3f}, "
                     f"{bench['peak']['frequency']:.3f} | {note} | {'yes' if is_lower else 'NO'} |")
    n = len(ref.BMD2016_DESIGN_SPEEDS)
    lines += ["", f"{lower} of {n} optimal bicycles handle better than the benchmark at their "
              "design speed by this measure (each peak certified: the maximum over every "
              "frequency, not a sampled one).", ""]
    return "\n".join(lines)


def _pydy(ref):
    """The non-linear model against independent trajectories (sympy/PyDy, Kane's method,
    scipy's DOP853 at 1e-13; bench/trajectory_references.py), at each run's last time."""
    reference = json.loads((DATA / "references.json").read_text())
    bikes = {"benchmark": "benchmark", "Schwinn Crown": "schwinn-crown"}
    quantities = ["lean", "steer", "lean_rate", "steer_rate", "yaw", "x", "y", "front_x",
                  "front_y", "speed"]
    out, worst = [], 0.0
    for run in reference["trajectories"]:
        bike = next(v for k, v in bikes.items() if run["name"].startswith(k))
        last = run["samples"][-1]
        initial = run["initial"]
        args = [f"--bike {bike}", f"--speed {initial['speed']!r}",
                f"--duration {last['t']!r}", "--integrator adaptive --rtol 1e-12"]
        for name in ("lean", "steer"):
            if initial[name]:
                args.append(f"--{name} {math.degrees(initial[name])!r}")
        for name in ("lean_rate", "steer_rate"):
            if initial[name]:
                args.append(f"--{name.replace('_', '-')} {initial[name]!r}")
        for name, expression in (run.get("torques") or {}).items():
            args.append(f"--{name}-torque '{expression}'")
        command = "whipple simulate " + " ".join(args) + " --format json"
        mine = _json(command)
        end = mine["samples"][-1]
        if abs(end["t"] - last["t"]) > 1e-12:
            raise PluginError(f"{CHAPTER}: `{command}` ended at t = {end['t']}, not {last['t']}")
        rows = [(q, last[q], end[q]) for q in quantities]
        worst = max([worst] + [abs(a - b) for _, a, b in rows])
        out.append(f"**{run['name']}**, at t = {last['t']:g} s " + ("(before the fall)" if
                   run.get("fall_angle") else "") + "\n")
        out.append(_table(["quantity (rad, rad/s, m, m/s)"], rows, command).replace(
            "| published |", "| PyDy |"))
    return "\n".join(out)


def _rider_lean(ref):
    cc, bp = _crosscheck()
    from bicycleparameters.parameter_dicts import mooreriderlean2012_browser_jason as jason
    lines = ["Reproduce, in Python: `whipple.RiderLean.from_moore_rider_lean2012(par)"
             ".linearize(V)` with `par` BicycleParameters' `mooreriderlean2012_browser_jason` "
             "(and k9, c9); BicycleParameters "
             f"{bp.__version__}'s `MooreRiderLean2012Model(...).form_state_space_matrices(v=V)` "
             "beside it. Every entry of A (6 × 6) and B (6 × 3) on the six states both keep, its "
             "difference against max(1, |Moore's entry|):", "",
             "| speed [m/s] | hinge free: A | B | hinge k₉ = 128 N m/rad, c₉ = 50 N m s/rad: A | B |",
             "|---|---|---|---|---|"]
    pairs = [cc.rider_lean_pair(dict(jason, k9=k9, c9=c9)) for k9, c9 in cc.RIDER_LEAN_HINGES]
    worst = 0.0
    for v in cc.RIDER_LEAN_SPEEDS:
        row = []
        for theirs, ours in pairs:
            da, db, ignorable = cc.rider_lean_differences(theirs, ours, v)
            if ignorable > 1e-12:
                raise PluginError(f"{CHAPTER}: Moore's ignorable coordinates enter at {v} m/s")
            row += [_sci(da), _sci(db)]
            worst = max(worst, da, db)
        lines.append(f"| {v:g} | " + " | ".join(row) + " |")
    lines += ["", f"Largest difference {_sci(worst)} (Moore's equations were generated from his "
              "dissertation's Autolev source; whipple's from its own model of the hinged upper "
              "body).", ""]
    return "\n".join(lines)


def _measured(ref):
    import tempfile
    cc, bp = _crosscheck()
    lines = ["Reproduce, in `crates/whipple/tests/data/measured` of a clone: "
             "`whipple measure --raw NAMEMeasured.txt --format json`; BicycleParameters "
             f"{bp.__version__}'s `Bicycle(NAME, forceRawCalc=True)` beside it, its tilt λ's σ "
             "made exact (it gives λ its starting guess's σ, and says so in its source; the "
             "values are its own):", "",
             "| bicycle | parameters | largest relative difference: values | σ |",
             "|---|---|---|---|"]
    worst_v = worst_s = 0.0
    with tempfile.TemporaryDirectory() as scratch:
        data_dir = cc.bicycleparameters_layout(scratch, cc.MEASURED)
        for name in cc.MEASURED:
            differences, ours_keys, their_keys = cc.measured_differences(
                cc.measured_theirs(bp, data_dir, name), cc.measured_ours(name))
            if ours_keys != their_keys:
                raise PluginError(f"{CHAPTER}: {name}: whipple computes {sorted(ours_keys)}, "
                                  f"BicycleParameters {sorted(their_keys)}")
            dv = max(d for d, _ in differences.values())
            ds = max(s for _, s in differences.values())
            worst_v, worst_s = max(worst_v, dv), max(worst_s, ds)
            lines.append(f"| {name} | {len(differences)} | {_sci(dv)} | {_sci(ds)} |")
    lines += ["", f"{len(cc.MEASURED)} bicycles (every one of the data set with raw data but "
              f"Silver, whose file lacks dF: both refuse it); largest differences {_sci(worst_v)} "
              f"(values) and {_sci(worst_s)} (σ).", ""]
    return "\n".join(lines)


def _add_rider(ref):
    import tempfile
    cc, bp = _crosscheck()
    lines = ["Reproduce, in `crates/whipple/tests/data` of a clone: `whipple measure --raw "
             "measured/BIKEMeasured.txt --rider yeadon/RIDERYeadonMeas.txt --configuration "
             "yeadon/RIDERBIKEYeadonCFG.txt --format json`; BicycleParameters "
             f"{bp.__version__}'s `add_rider` beside it, with yeadon's three corrections "
             "(`crates/whipple/tests/data/yeadon/expected.py`) and its joint-angle solve "
             "tightened to xtol = 1e-14:", "",
             "| bicycle | rider | largest relative difference: the bicycle with its rider | "
             "the rider alone |", "|---|---|---|---|"]
    worst = 0.0
    cases = cc.RIDDEN
    with tempfile.TemporaryDirectory() as scratch:
        data_dir = cc.bicycleparameters_layout(scratch, sorted({b for b, _ in cases}), cases)
        for bike, rider in cases:
            expected, expected_rider, _ = cc.add_rider_theirs(bp, data_dir, bike, rider)
            got = cc.add_rider_ours(bike, rider)
            whole = max(cc.worst(got.bicycle.to_dict(), expected, cc.whipple.BENCHMARK_KEYS).values())
            alone = max(cc.worst(cc.rider_values(got), expected_rider,
                                 [k for k in cc.RIDER_KEYS if k != "yB"]).values())
            worst = max(worst, whole, alone)
            lines.append(f"| {bike} | {rider} | {_sci(whole)} | {_sci(alone)} |")
    lines += ["", f"Largest difference {_sci(worst)} (the rider's lateral mass centre, zero up to "
              "round-off in both, left out). On Stratos Jason cannot reach the handlebar: whipple "
              "refuses, naming the distance; BicycleParameters' solve does not converge.", ""]
    return "\n".join(lines)


TABLES = {
    "meijaard2007-matrices": _matrices,
    "meijaard2007-table-2": _table_2,
    "meijaard2007-speeds": _speeds,
    "basu-mandal2007-table-1": _basu_mandal,
    "dressel-study": _dressel,
    "bicycleparameters": _bicycleparameters,
    "hmh2012-humancontrol": _humancontrol,
    "bmd2016-handling": _bmd2016,
    "pydy-trajectories": _pydy,
    "moore2012-rider-lean": _rider_lean,
    "bicycleparameters-measured": _measured,
    "bicycleparameters-add-rider": _add_rider,
}


def on_page_markdown(markdown, page, config, files):
    if page.file.src_uri != CHAPTER:
        if MARKER.search(markdown):
            raise PluginError(f"docs/{page.file.src_uri}: validation tables belong in {CHAPTER}")
        return markdown
    ref = _reference()
    found = MARKER.findall(markdown)
    unknown = sorted(set(found) - set(TABLES))
    missing = sorted(set(TABLES) - set(found))
    if unknown or missing:
        raise PluginError(f"docs/{CHAPTER}: unknown tables {unknown}, tables left out {missing}")
    return MARKER.sub(lambda m: TABLES[m.group(1)](ref), markdown)
