"""Eigenvalues over many speeds from Python: whipple against BicycleParameters' ``Bicycle.eig``
(the call a user of the field would otherwise make), in the same run, on the benchmark bicycle
(BicycleParameters' own BenchmarkBenchmark.txt, shipped with whipple's tests), and a 10 s
simulation of the non-linear bicycle. Python-side overhead included: each timing is the call a
user makes, arrays in and out.

    python crates/whipple-py/bench/eig_vs_bicycleparameters.py [N_WHIPPLE] [N_BP]

Needs whipple installed (pip install ./crates/whipple-py) and bicycleparameters (PyPI). Where
PyDy, sympy, scipy and Cython are installed too, the 10 s simulation is also run with the PyDy
model of bench/pydy_whipple.py (Kane's equations in sympy, compiled by PyDy's Cython generator,
integrated by the same fixed-step RK4 in a Python loop, as a PyDy user would): that script's
derivation and compilation take a minute or two and are not timed."""

import importlib.util
import os
import shutil
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

import whipple

ROOT = Path(__file__).resolve().parents[3]
FILE = ROOT / "crates" / "whipple" / "tests" / "data" / "bicycleparameters" / "BenchmarkBenchmark.txt"


def best(f, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    n_whipple = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    n_bp = int(sys.argv[2]) if len(sys.argv) > 2 else 20_000
    import bicycleparameters as bp

    data = Path(tempfile.mkdtemp())
    target = data / "bicycles" / "Benchmark" / "Parameters"
    target.mkdir(parents=True)
    shutil.copy(FILE, target)
    cwd = os.getcwd()
    os.chdir(data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        theirs = bp.Bicycle("Benchmark", pathToData=str(data))
    os.chdir(cwd)
    ours = whipple.Bicycle.from_file(FILE)

    v_bp = np.linspace(0.0, 10.0, n_bp)
    v_w = np.linspace(0.0, 10.0, n_whipple)
    t_bp = best(lambda: theirs.eig(v_bp), repeat=1)
    # BicycleParameters' batched path (numpy's eig over all speeds at once), when this release
    # has it: bench/bicycleparameters_sweep.py's call.
    spec = importlib.util.spec_from_file_location(
        "bicycleparameters_sweep", ROOT / "bench" / "bicycleparameters_sweep.py")
    sweep = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(sweep)
        t_calc = best(lambda: sweep.model_calc_eigen(v_bp), repeat=1)
    except Exception as error:  # the model API has changed between releases
        print(f"Meijaard2007Model.calc_eigen unavailable ({error})")
        t_calc = None
    runs = (
        ("whipple eig (tracked, labelled)", lambda: ours.eig(v_w)),
        ("whipple eig (tracked, 1 core)", lambda: ours.eig(v_w, parallel=False)),
        ("whipple eig (tracked=False)", lambda: ours.eig(v_w, tracked=False)),
        ("whipple eig (tracked=False, 1 core)", lambda: ours.eig(v_w, tracked=False, parallel=False)),
        ("whipple state_space (A, B)", lambda: ours.state_space(v_w)),
        ("whipple state_space (A, B), 1 core", lambda: ours.state_space(v_w, parallel=False)),
    )
    times = [(name, best(f)) for name, f in runs]
    rate = lambda n, t: n / t
    r_bp = rate(n_bp, t_bp)
    print(f"machine: {os.cpu_count()} cores; numpy {np.__version__}; bicycleparameters {bp.__version__}; whipple {whipple.__version__}")
    print(f"BicycleParameters Bicycle.eig         {n_bp:>9} speeds  {t_bp:8.3f} s  {r_bp:12.0f} speeds/s  1.0x")
    r_calc = None
    if t_calc is not None:
        r_calc = rate(n_bp, t_calc)
        print(f"BicycleParameters calc_eigen          {n_bp:>9} speeds  {t_calc:8.3f} s  {r_calc:12.0f} speeds/s  {r_calc / r_bp:.1f}x")
    for name, t in times:
        against = f"  {rate(n_whipple, t) / r_calc:.0f}x calc_eigen" if r_calc else ""
        print(f"{name:<37} {n_whipple:>9} speeds  {t:8.3f} s  {rate(n_whipple, t):12.0f} speeds/s  {rate(n_whipple, t) / r_bp:.0f}x{against}")
    t_sim = best(lambda: ours.simulate(4.6, 10.0, lean_rate=0.5), repeat=3)
    t_sim_py = best(lambda: ours.simulate(4.6, 10.0, lean_rate=0.5,
                                          steer_torque=lambda t, s: 0.0), repeat=3)
    print(f"whipple simulate 10 s, RK4 dt = 1 ms (10,000 steps, non-linear)       {t_sim:8.3f} s")
    print(f"  the same with a Python callable steer torque (40,000 calls)          {t_sim_py:8.3f} s")
    pydy_simulation(t_sim)


def pydy_simulation(t_whipple):
    """The same 10 s motion with PyDy's generated model, when PyDy is installed."""

    try:
        import pydy  # noqa: F401
    except ImportError:
        print("PyDy is not installed: its 10 s simulation is skipped")
        return
    spec = importlib.util.spec_from_file_location("pydy_whipple", ROOT / "bench" / "pydy_whipple.py")
    model = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(model)
    from pydy.codegen.ode_function_generators import generate_ode_function

    kane, coordinates, speeds, qdot, constants, helpers = model.derive()
    rhs = generate_ode_function(
        kane.forcing, coordinates, speeds, constants, mass_matrix=kane.mass_matrix,
        coordinate_derivatives=qdot, generator="cython", linear_sys_solver="sympy",
        constants_arg_type="array")
    lay = model.Layout(coordinates, speeds)
    par = model.parameter_values(model.BENCH)
    x0 = model.consistent_state(helpers, lay, par, lean=0.0, steer=0.0, lean_rate=0.5,
                                steer_rate=0.0, speed=4.6)
    t_pydy = best(lambda: model.rk4(rhs, x0, par, 1e-3, 10_000), repeat=3)
    print(f"PyDy (Cython RHS, RK4 in a Python loop, no projection) 10 s           {t_pydy:8.3f} s"
          f"  whipple {t_pydy / t_whipple:.1f}x faster")


if __name__ == "__main__":
    main()
