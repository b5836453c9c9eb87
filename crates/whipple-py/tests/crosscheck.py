"""The cross-checks against BicycleParameters (and yeadon) that both the tests and the guide's
validation chapter run: BicycleParameters' side computed by BicycleParameters itself, whipple's
by the installed package, and their relative differences. One home for how each comparison is
set up (test_measure.py, test_add_rider.py, test_rider_lean.py and docs/hooks/validation.py
use it); no pytest here, so that the guide's build can import it by path.

BicycleParameters and yeadon come from PyPI in a throw-away environment (ci-test, the guide's
build), never as dependencies; the functions that need them take the imported module or
import it themselves."""

import copy
import importlib.util
import io
import math
import os
import shutil
import warnings
from contextlib import redirect_stdout
from pathlib import Path

import numpy as np

import whipple

ROOT = Path(__file__).resolve().parents[3]
DATA = ROOT / "crates" / "whipple" / "tests" / "data"
RAW = DATA / "measured"
RIDERS = DATA / "yeadon"

# --- bench measurements to benchmark parameters (calculate_from_measured) ---------------------

#: Every bicycle of BicycleParameters' data set with raw data (data/bicycles/*/RawData/ at the
#: commit the data's README names): all of them but Silver, whose file lacks dF (both refuse
#: it). Balanceassistv1, Gyro, Rigid and Rigidcl measure the geometry as perpendicular
#: distances; Rigid and Rigidcl the fork and handlebar apart; Gyro has a flywheel.
MEASURED = ["Balanceassistv1", "Browser", "Browserins", "Crescendo", "Fisher", "Gyro", "Pista",
            "Rigid", "Rigidcl", "Stratos", "Yellow", "Yellowrev"]
#: Keys BicycleParameters passes through unchanged from the raw file (the lateral force's
#: point): not computed, whipple keeps them with the file's other keys.
PASSED_THROUGH = {"xcl", "zcl"}

# --- a Yeadon rider seated on a measured bicycle (add_rider) ----------------------------------

#: Every rider configuration of the test data whose bicycle has raw data.
RIDDEN = [("Browser", "Jason"), ("Browserins", "Jason"), ("Rigid", "Jason"),
          ("Balanceassistv1", "Jason"), ("Rigidcl", "Charlie"), ("Rigidcl", "Luke"),
          ("Gyro", "Child")]
#: Jason cannot reach Stratos' handlebar: refused by whipple, not converged in BicycleParameters.
UNREACHABLE = ("Stratos", "Jason")
RIDER_KEYS = ["mB", "xB", "yB", "zB", "IBxx", "IByy", "IBzz", "IBxz"]

# --- Moore 2012's leaning rider (MooreRiderLean2012Model) -------------------------------------

RIDER_LEAN_SPEEDS = [0.5, 1.0, 2.5, 4.0, 5.5, 7.0, 10.0]
#: The hinge free, and stiff and damped (k9 N m/rad, c9 N m s/rad).
RIDER_LEAN_HINGES = [(0.0, 0.0), (128.0, 50.0)]
# Moore's states q1 q2 q3 q4 q6 q7 q8 q9 u4 u6 u7 u9: ours [φ, δ, φ_r, φ̇, δ̇, φ̇_r] are
# q4, q7, q9, u4, u7, u9; the others are ignorable (positions, yaw, wheel angles, u6).
OURS_IN_MOORE = [3, 5, 7, 8, 10, 11]
IGNORABLE = [0, 1, 2, 4, 6, 9]


def nominal(x):
    """A ufloat's value, or the plain number."""
    return float(getattr(x, "nominal_value", x))


def relative(ours, theirs):
    """|ours − theirs| / |theirs| (absolute where theirs is zero)."""
    return abs(ours - theirs) / abs(theirs) if theirs != 0.0 else abs(ours)


def bicycleparameters_layout(root, bicycles, riders=()):
    """BicycleParameters' folders under `root` around the test data's raw files:
    bicycles/<Name>/RawData/<Name>Measured.txt (no Parameters folder: it must compute from the
    raw data), and riders/<Rider>/RawData/ with the rider's measurements and, for each
    (bicycle, rider) of `riders`, its configuration."""
    root = Path(root)
    for name in bicycles:
        target = root / "bicycles" / name / "RawData"
        target.mkdir(parents=True, exist_ok=True)
        shutil.copy(RAW / f"{name}Measured.txt", target)
    for bike, rider in riders:
        folder = root / "riders" / rider / "RawData"
        folder.mkdir(parents=True, exist_ok=True)
        shutil.copy(RIDERS / f"{rider}YeadonMeas.txt", folder)
        shutil.copy(RIDERS / f"{rider}{bike}YeadonCFG.txt", folder)
    return root


def measured_ours(name):
    """whipple.measure on the raw file."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        return whipple.measure(RAW / f"{name}Measured.txt")


def exact_lambda_from_abc(original):
    """BicycleParameters' ``lambda_from_abc`` with λ's exact first-order uncertainty.

    BicycleParameters solves F(λ) = sin λ − (rF − rR + c cos λ)/(a + b) = 0 by Newton's method
    on the nominal values and returns λ with the σ of its starting guess atan(c/(a + b)), as a
    new independent variable (its source says so: "This is not true!"). whipple carries the
    implicit derivative ∂λ/∂x = −F_x/F_λ. Here the same root comes from BicycleParameters'
    own function, and λ is rebuilt as that linear function of rF, rR, a, b, c, so that every
    σ downstream is BicycleParameters' pipeline with only this one step made exact."""

    def exact(rF, rR, a, b, c):
        lam = original(rF, rR, a, b, c).nominal_value
        ab = a.nominal_value + b.nominal_value
        s, co = math.sin(lam), math.cos(lam)
        f_lam = co + c.nominal_value * s / ab
        f_ab = (rF.nominal_value - rR.nominal_value + c.nominal_value * co) / ab ** 2
        dev = lambda u: u - u.nominal_value  # noqa: E731 - the ufloat's linear part
        linear = (-dev(rF) / ab + dev(rR) / ab - co * dev(c) / ab
                  + f_ab * (dev(a) + dev(b)))
        return lam - linear / f_lam

    return exact


def measured_theirs(bp, data_dir, name, exact_tilt=True):
    """BicycleParameters' calculate_from_measured on the raw file (forced, as its users run
    it): the benchmark parameters as uncertainties' ufloats. With ``exact_tilt`` the tilt
    from perpendicular distances carries its exact derivative (:func:`exact_lambda_from_abc`;
    the values are BicycleParameters' own)."""
    cwd = os.getcwd()
    original = bp.geometry.lambda_from_abc
    try:
        os.chdir(data_dir)
        if exact_tilt:
            bp.geometry.lambda_from_abc = exact_lambda_from_abc(original)
        with warnings.catch_warnings(), redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            bike = bp.Bicycle(name, pathToData=str(data_dir), forceRawCalc=True)
        return bike.parameters["Benchmark"]
    finally:
        bp.geometry.lambda_from_abc = original
        os.chdir(cwd)


def measured_differences(expected, got):
    """{key: (relative difference of the value, of σ)} over every parameter BicycleParameters
    computes (the bicycle's extras included: fork S, handlebar G, flywheel D), and the two key
    sets (ours, theirs) for the caller to compare."""
    values, sigma = got.bicycle.to_dict(), got.bicycle.sigma
    for e in got.bicycle.extras:
        values[e["key"]] = e["value"]
        sigma[e["key"]] = e["sigma"] or 0.0
    keys = set(expected) - PASSED_THROUGH
    out = {}
    for key in sorted(keys & set(values)):
        # A value without σ in the file (Balanceassistv1's g) stays a plain float.
        v = nominal(expected[key])
        s = float(getattr(expected[key], "std_dev", 0.0))
        out[key] = (abs(values[key] - v) / max(abs(v), 1e-300),
                    relative(sigma.get(key, 0.0), s))
    return out, set(values), keys


def _yeadon_corrections():
    spec = importlib.util.spec_from_file_location("yeadon_expected", RIDERS / "expected.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def add_rider_ours(bike, rider):
    """whipple.measure with the rider's measurements and configuration."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        return whipple.measure(RAW / f"{bike}Measured.txt",
                               rider=RIDERS / f"{rider}YeadonMeas.txt",
                               configuration=RIDERS / f"{rider}{bike}YeadonCFG.txt")


def add_rider_theirs(bp, data_dir, bike, rider, corrected=True, xtol=1e-14, report=None):
    """BicycleParameters' add_rider after calculate_from_measured (forced, from the raw file):
    the benchmark parameters with the rider (ufloats), the rider alone, the configuration.

    yeadon runs with the three corrections of crates/whipple/tests/data/yeadon/expected.py
    (``corrected``), so that both compute the same body; BicycleParameters' joint-angle solve
    (scipy's fsolve, default xtol 1.49e-8) runs at ``xtol`` (None: its default). ``report``
    collects fsolve's (ier, largest residual)."""
    import scipy.optimize
    import yeadon
    import bicycleparameters.rider as bp_rider

    fix = _yeadon_corrections()
    original_fsolve = bp_rider.fsolve
    cwd = os.getcwd()
    try:
        fix.patch(fix.CORRECTED if corrected else fix.ORIGINAL)
        # yeadon scales its class-level densities in place by a file's totalmass: start afresh.
        yeadon.Human.segmental_densities = copy.deepcopy(fix.ORIGINAL_DENSITIES)

        def fsolve(f, x0):
            options = {} if xtol is None else {"xtol": xtol}
            solution, _, ier, _ = scipy.optimize.fsolve(f, x0, full_output=True, **options)
            if report is not None:
                report.append((ier, float(np.abs(f(solution)).max())))
            return solution

        bp_rider.fsolve = fsolve
        os.chdir(data_dir)
        with warnings.catch_warnings(), redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            bicycle = bp.Bicycle(bike, pathToData=str(data_dir), forceRawCalc=True)
            bicycle.add_rider(rider, reCalc=True)
        return (bicycle.parameters["Benchmark"], bicycle.riderPar["Benchmark"],
                dict(bicycle.human.CFG))
    finally:
        os.chdir(cwd)
        bp_rider.fsolve = original_fsolve
        fix.patch(fix.ORIGINAL)
        yeadon.Human.segmental_densities = copy.deepcopy(fix.ORIGINAL_DENSITIES)


def rider_values(got):
    """The rider alone in the benchmark's rear-frame keys."""
    r = got.rider
    c, i = r["center_of_mass"], r["inertia"]
    return {"mB": r["mass"], "xB": c[0], "yB": c[1], "zB": c[2], "IBxx": i[0][0],
            "IByy": i[1][1], "IBzz": i[2][2], "IBxz": i[0][2]}


def worst(values, expected, keys):
    """{key: relative difference of values[key] from expected[key]'s value}."""
    return {key: relative(values[key], nominal(expected[key])) for key in keys}


def rider_lean_pair(parameters):
    """Moore's model (BicycleParameters' MooreRiderLean2012Model) and whipple's RiderLean of
    the same parameters (Moore's keys)."""
    from bicycleparameters.models import MooreRiderLean2012Model
    from bicycleparameters.parameter_sets import MooreRiderLean2012ParameterSet

    theirs = MooreRiderLean2012Model(MooreRiderLean2012ParameterSet(parameters))
    return theirs, whipple.RiderLean.from_moore_rider_lean2012(parameters)


def rider_lean_differences(theirs, ours, v):
    """At speed v: the largest difference of A's and of B's entries (each against
    max(1, |Moore's entry|)), and the largest entry of Moore's A coupling an ignorable
    coordinate into the six states compared."""
    a_moore, b_moore = theirs.form_state_space_matrices(v=v)
    a, b = ours.linearize(v)
    rows = np.ix_(OURS_IN_MOORE, OURS_IN_MOORE)
    da = float(np.max(np.abs(a - a_moore[rows]) / np.maximum(1.0, np.abs(a_moore[rows]))))
    b_rows = b_moore[OURS_IN_MOORE]
    db = float(np.max(np.abs(b - b_rows) / np.maximum(1.0, np.abs(b_rows))))
    ignorable = float(np.max(np.abs(a_moore[np.ix_(OURS_IN_MOORE, IGNORABLE)])))
    return da, db, ignorable
