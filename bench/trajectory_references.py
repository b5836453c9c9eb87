"""Independent references pinned in `cargo test` (crates/whipple/tests/data/references.json).

Everything here is computed without whipple's code:

- trajectories of the non-linear Whipple bicycle from the sympy/PyDy model of
  bench/pydy_whipple.py (Moore's formulation, Kane's method, PyDy's Cython right-hand side),
  integrated by scipy's DOP853 at rtol = atol = 1e-13, sampled at fixed times, with the time at
  which |lean| first reaches 30 degrees located by solve_ivp's event finder;
- the Schwinn Crown's benchmark parameters converted by hand from its JBike6 bodies (the rules
  of README.md: masses added, mass-weighted centres, R(a) diag(I11, I22) R(a)^T moved by the
  parallel-axis theorem) so that one trajectory also checks the conversion;
- the two-mass-skate's canonical matrices M, C1, K0, K2 (Meijaard et al. 2007, Appendix A,
  transcribed here by hand) checked against BicycleParameters' `benchmark_par_to_canonical`
  when it is installed, and its weave speed by bisection on the largest real part of numpy's
  eigenvalues of A(v).

Run it once in throw-away virtual environments, from the repository root:

    python3 -m venv /tmp/pydyvenv
    /tmp/pydyvenv/bin/pip install pydy sympy numpy scipy cython
    python3 -m venv /tmp/bpvenv && /tmp/bpvenv/bin/pip install bicycleparameters
    /tmp/pydyvenv/bin/python bench/trajectory_references.py \
        --bicycleparameters /tmp/bpvenv/bin/python \
        crates/whipple/tests/data/references.json

It takes a few minutes (the derivation and the Cython build dominate). The output is JSON:
each scenario with its bicycle's benchmark parameters, initial conditions, rider torques (as
the test must apply them), sample times and the sampled quantities in whipple's names and
signs (radians, metres, seconds; benchmark signs, z down; pitch of the rear frame from upright,
nose down positive as whipple's; x, y the rear contact, front_x, front_y the front contact).
"""

import json
import math
import subprocess
import sys

import numpy as np
from pydy.codegen.ode_function_generators import generate_ode_function
from scipy.integrate import solve_ivp

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import pydy_whipple as pw  # noqa: E402

# Dressel's study / JBike6: the Schwinn Crown, JBike6's default bicycle (its .m listing).
CROWN = {
    "wheelbase": 1.016, "head_angle": 1.23879599, "trail": 0.090968, "gravity": 9.80665,
    "rear_wheel": {"D": 0.6858, "m": 1.818182, "I": [0.085513, 0.085513, 0.171026]},
    "front_wheel": {"D": 0.6858, "m": 1.818182, "I": [0.085513, 0.085513, 0.171026]},
    "rider": {"m": 80.0, "x": 0.3, "y": 1.2, "I": [10.531129, 2.468871, 12.0],
              "alpha": -0.25957299},
    "frame": {"m": 2.5, "x": 0.3, "y": 0.5, "I": [0.058579, 0.341421, 0.4],
              "alpha": 0.39269899},
    "rack": {"m": 2.0, "x": -0.1, "y": 0.8, "I": [0.02, 0.02, 0.02], "alpha": 0.0},
    "fork": {"m": 1.5, "u": 0.0, "v": 0.6858, "I": [0.05879, 0.000588, 0.05879],
             "alpha": 0.332},
    "basket": {"m": 1.5, "u": 0.15, "v": 0.8, "I": [0.01, 0.01, 0.01], "alpha": 0.0},
}

# Kooijman et al. 2011 (Science 332:339-342), the two-mass-skate, digits as transcribed in
# BicycleParameters.
TWO_MASS_SKATE = {
    "w": 1.0, "c": 0.0, "lam": math.radians(5.0), "g": 9.81,
    "rR": 0.0, "mR": 0.0, "IRxx": 0.0, "IRyy": 0.0,
    "xB": 1.2, "zB": -0.4, "mB": 10.0, "IBxx": 0.0, "IByy": 0.0, "IBzz": 0.0, "IBxz": 0.0,
    "xH": 1.02, "zH": -0.2, "mH": 1.0, "IHxx": 0.0, "IHyy": 0.0, "IHzz": 0.0, "IHxz": 0.0,
    "rF": 0.0, "mF": 0.0, "IFxx": 0.0, "IFyy": 0.0,
}

def crown_benchmark(j):
    """JBike6 bodies combined into the benchmark bodies, by hand (see the module doc)."""
    w, h, c = j["wheelbase"], j["head_angle"], j["trail"]
    lam = math.pi / 2 - h
    # The steer axis meets the ground at x = w + c; v runs up it (backward and up), u is
    # perpendicular to it, forward and up.
    v_hat = np.array([-math.cos(h), math.sin(h)])
    u_hat = np.array([math.sin(h), math.cos(h)])
    ground = np.array([w + c, 0.0])

    def planar(m, x, y, inertia, alpha):
        i11, i22, izz = inertia
        r = np.array([[math.cos(alpha), -math.sin(alpha)], [math.sin(alpha), math.cos(alpha)]])
        t = r @ np.diag([i11, i22]) @ r.T
        return m, np.array([x, y]), t, izz

    def combine(parts):
        m = sum(p[0] for p in parts)
        com = sum(p[0] * p[1] for p in parts) / m
        t = np.zeros((2, 2))
        tzz = 0.0
        for mi, ri, ti, izz in parts:
            d = ri - com
            # Parallel-axis theorem in the plane (tensor convention, products negative).
            t += ti + mi * (np.dot(d, d) * np.eye(2) - np.outer(d, d))
            tzz += izz + mi * np.dot(d, d)
        return m, com, t, tzz

    rear = [planar(j[k]["m"], j[k]["x"], j[k]["y"], j[k]["I"], j[k]["alpha"])
            for k in ("rider", "frame", "rack")]
    front = []
    for k in ("fork", "basket"):
        b = j[k]
        p = ground + b["u"] * u_hat + b["v"] * v_hat
        front.append(planar(b["m"], p[0], p[1], b["I"], b["alpha"]))
    mb, rb, tb, tzzb = combine(rear)
    mh, rh, th, tzzh = combine(front)
    rw, fw = j["rear_wheel"], j["front_wheel"]
    return {
        "w": w, "c": c, "lam": lam, "g": j["gravity"],
        "rR": rw["D"] / 2, "mR": rw["m"], "IRxx": rw["I"][0], "IRyy": rw["I"][2],
        "xB": rb[0], "zB": -rb[1], "mB": mb,
        "IBxx": tb[0, 0], "IByy": tzzb, "IBzz": tb[1, 1], "IBxz": -tb[0, 1],
        "xH": rh[0], "zH": -rh[1], "mH": mh,
        "IHxx": th[0, 0], "IHyy": tzzh, "IHzz": th[1, 1], "IHxz": -th[0, 1],
        "rF": fw["D"] / 2, "mF": fw["m"], "IFxx": fw["I"][0], "IFyy": fw["I"][2],
    }


def canonical(p):
    """M, C1, K0, K2 of Meijaard et al. 2007, Appendix A (eqs. A 1-A 23), by hand."""
    w, c, lam, g = p["w"], p["c"], p["lam"], p["g"]
    rR, rF = p["rR"], p["rF"]
    mT = p["mR"] + p["mB"] + p["mH"] + p["mF"]
    xT = (p["xB"] * p["mB"] + p["xH"] * p["mH"] + w * p["mF"]) / mT
    zT = (-rR * p["mR"] + p["zB"] * p["mB"] + p["zH"] * p["mH"] - rF * p["mF"]) / mT
    ITxx = (p["IRxx"] + p["IBxx"] + p["IHxx"] + p["IFxx"] + p["mR"] * rR ** 2
            + p["mB"] * p["zB"] ** 2 + p["mH"] * p["zH"] ** 2 + p["mF"] * rF ** 2)
    ITxz = (p["IBxz"] + p["IHxz"] - p["mB"] * p["xB"] * p["zB"]
            - p["mH"] * p["xH"] * p["zH"] + p["mF"] * w * rF)
    IRzz, IFzz = p["IRxx"], p["IFxx"]
    ITzz = (IRzz + p["IBzz"] + p["IHzz"] + IFzz + p["mB"] * p["xB"] ** 2
            + p["mH"] * p["xH"] ** 2 + p["mF"] * w ** 2)
    mA = p["mH"] + p["mF"]
    xA = (p["xH"] * p["mH"] + w * p["mF"]) / mA
    zA = (p["zH"] * p["mH"] - rF * p["mF"]) / mA
    IAxx = p["IHxx"] + p["IFxx"] + p["mH"] * (p["zH"] - zA) ** 2 + p["mF"] * (rF + zA) ** 2
    IAxz = (p["IHxz"] - p["mH"] * (p["xH"] - xA) * (p["zH"] - zA)
            + p["mF"] * (w - xA) * (rF + zA))
    IAzz = p["IHzz"] + IFzz + p["mH"] * (p["xH"] - xA) ** 2 + p["mF"] * (w - xA) ** 2
    uA = (xA - w - c) * math.cos(lam) - zA * math.sin(lam)
    sl, cl = math.sin(lam), math.cos(lam)
    IAll = mA * uA ** 2 + IAxx * sl ** 2 + 2 * IAxz * sl * cl + IAzz * cl ** 2
    IAlx = -mA * uA * zA + IAxx * sl + IAxz * cl
    IAlz = mA * uA * xA + IAxz * sl + IAzz * cl
    mu = c / w * cl
    SR, SF = p["IRyy"] / rR if rR > 0 else 0.0, p["IFyy"] / rF if rF > 0 else 0.0
    ST = SR + SF
    SA = mA * uA + mu * mT * xT
    M = np.array([[ITxx, IAlx + mu * ITxz], [IAlx + mu * ITxz, IAll + 2 * mu * IAlz + mu ** 2 * ITzz]])
    K0 = np.array([[mT * zT, -SA], [-SA, -SA * sl]])
    K2 = np.array([[0.0, (ST - mT * zT) / w * cl], [0.0, (SA + SF * sl) / w * cl]])
    C1 = np.array([[0.0, mu * ST + SF * cl + ITxz / w * cl - mu * mT * zT],
                   [-(mu * ST + SF * cl), IAlz / w * cl + mu * (SA + ITzz / w * cl)]])
    return M, C1, K0, K2


def weave_speed(p, lo, hi):
    """Where the largest real part of eig(A(v)) turns negative, by bisection to 1e-13 m/s."""
    M, C1, K0, K2 = canonical(p)
    Minv = np.linalg.inv(M)

    def max_re(v):
        a = np.block([[np.zeros((2, 2)), np.eye(2)],
                      [-Minv @ (p["g"] * K0 + v * v * K2), -v * Minv @ C1]])
        return max(np.linalg.eigvals(a).real)

    assert max_re(lo) > 0 > max_re(hi)
    while hi - lo > 1e-13:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if max_re(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def bicycleparameters_canonical(python, p):
    """The same matrices from BicycleParameters (its own Appendix A code), in another venv."""
    script = (
        "import json, sys\n"
        "from bicycleparameters.bicycle import benchmark_par_to_canonical\n"
        "p = json.loads(sys.stdin.read())\n"
        "M, C1, K0, K2 = benchmark_par_to_canonical(p)\n"
        "print(json.dumps([[[float(x) for x in row] for row in m] for m in (M, C1, K0, K2)]))\n")
    par = dict(p)
    # BicycleParameters divides the spin moments by the radii (0/0 for a skate). With massless,
    # spinless wheels the radii enter nothing else, so any positive radius gives the matrices.
    for r, m, spin in (("rR", "mR", "IRyy"), ("rF", "mF", "IFyy")):
        if par[r] == 0.0:
            assert par[m] == 0.0 and par[spin] == 0.0
            par[r] = 1.0
    out = subprocess.run([python, "-c", script], input=json.dumps(par), capture_output=True,
                         text=True, check=True)
    return [np.array(m) for m in json.loads(out.stdout)]


def scenarios():
    bench = pw.BENCH
    crown = crown_benchmark(CROWN)
    return [
        {
            "name": "benchmark, 4.6 m/s, lean-rate kick 0.5 rad/s (weave decays)",
            "bicycle": bench,
            "initial": {"speed": 4.6, "lean": 0.0, "steer": 0.0, "lean_rate": 0.5,
                        "steer_rate": 0.0},
            "torques": None,
            "times": [0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0],
        },
        {
            "name": "benchmark, 3 m/s, lean-rate kick 0.5 rad/s (the weave grows; it falls)",
            "bicycle": bench,
            "initial": {"speed": 3.0, "lean": 0.0, "steer": 0.0, "lean_rate": 0.5,
                        "steer_rate": 0.0},
            "torques": None,
            "times": [0.25, 0.5, 0.75, 1.0, 1.25, 1.5],
            "fall_angle": math.radians(30.0),
        },
        {
            "name": "Schwinn Crown (JBike6 form, converted here by hand), 6 m/s, leaning and "
                    "steering, with a lean torque 1.5 N m and a steer torque 0.4 sin(2t) N m",
            "bicycle": crown,
            "initial": {"speed": 6.0, "lean": math.radians(5.0), "steer": math.radians(-2.0),
                        "lean_rate": -0.2, "steer_rate": 0.3},
            "torques": {"lean": "1.5", "steer": "0.4*sin(2*t)"},
            "times": [0.25, 0.5, 1.0, 1.5, 2.0, 3.0],
        },
    ]


def torque_values(torques, t):
    if torques is None:
        return np.zeros(2)
    # The expressions above, evaluated here by hand (no eval).
    lean = 1.5
    steer = 0.4 * math.sin(2.0 * t)
    return np.array([lean, steer])


def run(rhs, helpers, lay, scenario):
    p = scenario["bicycle"]
    par = pw.parameter_values(p)
    ic = scenario["initial"]
    x0 = pw.consistent_state(helpers, lay, par, ic["lean"], ic["steer"], ic["lean_rate"],
                             ic["steer_rate"], ic["speed"])
    hol, vel = pw.constraint_residuals(helpers, lay, par, x0)
    assert hol < 1e-14 and vel < 1e-13, (hol, vel)
    torques = scenario["torques"]

    def f(t, x):
        # PyDy returns the same array on every call: copy it, or the stages alias.
        return rhs(x, t, torque_values(torques, t), par).copy()

    events = None
    if "fall_angle" in scenario:
        fall = scenario["fall_angle"]

        def fell(t, x):
            return abs(x[lay["q4"]]) - fall

        fell.terminal = False
        events = fell
    times = scenario["times"]
    sol = solve_ivp(f, (0.0, times[-1]), x0, method="DOP853", rtol=1e-13, atol=1e-13,
                    t_eval=times, events=events)
    assert sol.success, sol.message
    samples = []
    for k, t in enumerate(sol.t):
        x = sol.y[:, k]
        q, u = x[:lay.n_q], x[lay.n_q:]
        front = helpers["front_contact"](q, par)
        samples.append({
            "t": float(t),
            "lean": x[lay["q4"]], "steer": x[lay["q7"]],
            "lean_rate": x[lay["u4"]], "steer_rate": x[lay["u7"]],
            "yaw": x[lay["q3"]],
            # Moore's C axes are the rear frame turned by the steer axis tilt: whipple's pitch
            # is q5 - lam, nose down positive in both.
            "pitch": x[lay["q5"]] - p["lam"],
            "x": x[lay["q1"]], "y": x[lay["q2"]],
            "front_x": x[lay["q1"]] + front[0], "front_y": x[lay["q2"]] + front[1],
            "speed": helpers["speed"](q, u, par),
        })
        hol, vel = pw.constraint_residuals(helpers, lay, par, x)
        assert hol < 1e-10 and vel < 1e-10, (t, hol, vel)
    out = {k: v for k, v in scenario.items()}
    out["samples"] = [{k: float(v) for k, v in s.items()} for s in samples]
    if events is not None:
        out["fall_time"] = float(sol.t_events[0][0])
    return out


def main():
    out_path = "crates/whipple/tests/data/references.json"
    bp_python = None
    args = sys.argv[1:]
    while args:
        a = args.pop(0)
        if a == "--bicycleparameters":
            bp_python = args.pop(0)
        else:
            out_path = a

    kane, coordinates, speeds, qdot, constants, helpers, inputs = pw.derive(with_torques=True)
    rhs = generate_ode_function(
        kane.forcing, coordinates, speeds, constants, mass_matrix=kane.mass_matrix,
        coordinate_derivatives=qdot, specifieds=inputs, generator="cython",
        linear_sys_solver="sympy", constants_arg_type="array", specifieds_arg_type="array")
    lay = pw.Layout(coordinates, speeds)
    results = [run(rhs, helpers, lay, s) for s in scenarios()]
    for r in results:
        print(r["name"])
        for s in r["samples"]:
            print(f"  t = {s['t']:5.2f}  lean {s['lean']: .12f}  steer {s['steer']: .12f}  "
                  f"x {s['x']: .9f}  y {s['y']: .9f}")
        if "fall_time" in r:
            print(f"  |lean| reaches {math.degrees(r['fall_angle']):.0f} deg at "
                  f"t = {r['fall_time']:.12f} s")

    skate = {"bicycle": TWO_MASS_SKATE}
    M, C1, K0, K2 = canonical(TWO_MASS_SKATE)
    if bp_python:
        theirs = bicycleparameters_canonical(bp_python, TWO_MASS_SKATE)
        for mine, other, name in zip((M, C1, K0, K2), theirs, ("M", "C1", "K0", "K2")):
            d = np.max(np.abs(mine - other))
            print(f"two-mass-skate {name}: by hand vs BicycleParameters {d:.1e}")
            assert d < 1e-13, (name, mine, other)
        skate["checked_against"] = "BicycleParameters benchmark_par_to_canonical"
    # The benchmark bicycle's matrices by the same hand transcription, as a check of it
    # against the values printed in Meijaard et al. 2007, Section 5.
    Mb, C1b, K0b, K2b = canonical(pw.BENCH)
    assert abs(Mb[0, 1] - 2.31941332208709) < 1e-13 and abs(C1b[0, 1] - 33.86641391492494) < 1e-13
    assert abs(K0b[1, 1] + 0.80329488458618) < 1e-13 and abs(K2b[1, 1] - 2.65431523794604) < 1e-13
    skate.update({
        "M": M.tolist(), "C1": C1.tolist(), "K0": K0.tolist(), "K2": K2.tolist(),
        "weave_speed": weave_speed(TWO_MASS_SKATE, 1.0, 5.0),
    })
    print(f"two-mass-skate weave speed {skate['weave_speed']:.13f} m/s")

    doc = {
        "generated_by": "bench/trajectory_references.py (sympy/PyDy, scipy DOP853 at "
                        "rtol = atol = 1e-13; Meijaard 2007 Appendix A by hand; "
                        "BicycleParameters)",
        "crown_jbike6": CROWN,
        "trajectories": results,
        "two_mass_skate": skate,
    }
    with open(out_path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"written to {out_path}")


if __name__ == "__main__":
    main()
