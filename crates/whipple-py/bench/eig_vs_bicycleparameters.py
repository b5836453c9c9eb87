"""Eigenvalues over many speeds from Python: whipple against BicycleParameters' ``Bicycle.eig``
(the call a user of the field would otherwise make), in the same run, on the benchmark bicycle
(BicycleParameters' own BenchmarkBenchmark.txt, shipped with whipple's tests), and a 10 s
simulation of the non-linear bicycle. Python-side overhead included: each timing is the call a
user makes, arrays in and out.

    python crates/whipple-py/bench/eig_vs_bicycleparameters.py [N_WHIPPLE] [N_BP]

Needs whipple installed (pip install ./crates/whipple-py) and bicycleparameters (PyPI)."""

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
    t_tracked = best(lambda: ours.eig(v_w))
    t_untracked = best(lambda: ours.eig(v_w, tracked=False))
    t_one = best(lambda: ours.eig(v_w, tracked=False, parallel=False))
    t_ss = best(lambda: ours.state_space(v_w))
    rate = lambda n, t: n / t
    r_bp = rate(n_bp, t_bp)
    print(f"machine: {os.cpu_count()} cores; numpy {np.__version__}; bicycleparameters {bp.__version__}; whipple {whipple.__version__}")
    print(f"BicycleParameters Bicycle.eig         {n_bp:>9} speeds  {t_bp:8.3f} s  {r_bp:12.0f} speeds/s  1.0x")
    for name, n, t in (("whipple eig (tracked, labelled)", n_whipple, t_tracked),
                       ("whipple eig (tracked=False)", n_whipple, t_untracked),
                       ("whipple eig (tracked=False, 1 core)", n_whipple, t_one),
                       ("whipple state_space (A, B)", n_whipple, t_ss)):
        print(f"{name:<37} {n:>9} speeds  {t:8.3f} s  {rate(n, t):12.0f} speeds/s  {rate(n, t) / r_bp:.0f}x")
    t_sim = best(lambda: ours.simulate(4.6, 10.0, lean_rate=0.5), repeat=3)
    t_sim_py = best(lambda: ours.simulate(4.6, 10.0, lean_rate=0.5,
                                          steer_torque=lambda t, s: 0.0), repeat=3)
    print(f"whipple simulate 10 s, RK4 dt = 1 ms (10,000 steps, non-linear)       {t_sim:8.3f} s")
    print(f"  the same with a Python callable steer torque (40,000 calls)          {t_sim_py:8.3f} s")


if __name__ == "__main__":
    main()
