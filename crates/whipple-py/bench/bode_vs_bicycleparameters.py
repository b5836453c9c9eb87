"""Frequency responses over many speeds from Python: whipple's batch call
``Bicycle.frequency_response(speeds, omega)`` against scipy.signal (``freqresp`` of the state
space, one speed at a time) and BicycleParameters' Bode path (``Bicycle.plot_bode(speed, u, y)``:
1,000 frequencies a call, logspace(0, 2), each by inverting iωI − A, with its figure), in the
same run, on the benchmark bicycle (BicycleParameters' own BenchmarkBenchmark.txt, shipped with
whipple's tests), steer torque → lean. Each timing is the call a user makes, arrays in and out.

    python crates/whipple-py/bench/bode_vs_bicycleparameters.py [N_SPEEDS] [N_FREQUENCIES] [N_SCIPY] [N_BP]

Needs whipple (pip install ./crates/whipple-py), scipy, matplotlib and bicycleparameters (PyPI)."""

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
    n_speeds = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    n_freq = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    n_scipy = int(sys.argv[3]) if len(sys.argv) > 3 else n_speeds
    n_bp = int(sys.argv[4]) if len(sys.argv) > 4 else 20
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import scipy.signal as signal
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
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        ours = whipple.Bicycle.from_file(FILE)

    speeds = np.linspace(0.5, 10.0, n_speeds)
    omega = np.logspace(0, 2, n_freq)
    points = n_speeds * n_freq
    rows = []

    t = best(lambda: ours.frequency_response(speeds, omega, "steer_torque", "lean"))
    rows.append(("whipple `bike.frequency_response(speeds, omega)` (2 cores)", n_speeds, t))
    t = best(lambda: ours.frequency_response(speeds, omega, "steer_torque", "lean", parallel=False))
    rows.append(("whipple, `parallel=False` (1 core)", n_speeds, t))

    def with_scipy(vs):
        out = np.empty((len(vs), n_freq), dtype=complex)
        for k, v in enumerate(vs):
            a, b = ours.state_space(v)
            sys_ = signal.StateSpace(a, b[:, [1]], np.array([[1.0, 0, 0, 0]]), np.zeros((1, 1)))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                out[k] = signal.freqresp(sys_, omega)[1]
        return out

    vs_scipy = speeds[:: max(1, n_speeds // n_scipy)][:n_scipy]
    t = best(lambda: with_scipy(vs_scipy), repeat=1)
    rows.append(("scipy.signal `freqresp(StateSpace(A, B, C, D), omega)` per speed", len(vs_scipy), t))

    # BicycleParameters' Bode path: its frequencies are fixed (logspace(0, 2, 1000)).
    bp_omega = np.logspace(0, 2, 1000)
    vs_bp = np.linspace(0.5, 10.0, n_bp)

    def with_bp():
        for v in vs_bp:
            _, _, fig = theirs.plot_bode(v, 1, 0)
            plt.close(fig)

    _, _, fig = theirs.plot_bode(vs_bp[0], 1, 0)  # matplotlib's first figure, not timed
    plt.close(fig)
    t_bp = best(with_bp, repeat=1)
    bp_points = n_bp * len(bp_omega)

    # The same numbers (at one speed of each).
    mag, phase, fig = theirs.plot_bode(vs_bp[0], 1, 0)
    plt.close(fig)
    mine = ours.frequency_response(vs_bp[0], bp_omega, "steer_torque", "lean")
    rel = np.max(np.abs(10 ** ((mine.magnitude_db[0, 0] - mag) / 20) - 1))
    print(f"agreement with BicycleParameters at {vs_bp[0]} m/s: |G| {rel:.1e} relative, phase "
          f"{np.max(np.abs(mine.phase_deg[0, 0] - phase)):.1e} deg")

    per_point_bp = t_bp / bp_points
    print(f"\n{n_speeds} speeds × {n_freq} frequencies = {points:,} points; "
          f"BicycleParameters on {n_bp} speeds × 1,000 frequencies\n")
    per_point_scipy = rows[2][2] / (rows[2][1] * n_freq)
    print("| call | speeds | time | points per second | vs BicycleParameters `plot_bode` (per point) | vs scipy |")
    print("|---|---|---|---|---|---|")
    print(f"| BicycleParameters `Bicycle.plot_bode(v, 1, 0)` (figure included) | {n_bp} | "
          f"{t_bp:.3f} s | {bp_points / t_bp:,.0f} | 1× | {per_point_scipy / per_point_bp:.2f}× |")
    for name, n, t in rows:
        pts = n * n_freq
        print(f"| {name} | {n:,} | {t:.3f} s | {pts / t:,.0f} | {per_point_bp / (t / pts):,.0f}× "
              f"| {per_point_scipy / (t / pts):,.1f}× |")


if __name__ == "__main__":
    main()
