"""Compares the PyDy Whipple trajectory with whipple's trajectory of the same motion.

Both are the benchmark bicycle from upright at 4.6 m/s (rear hub speed along the heading) with
a lean rate of 0.5 rad/s, 10 s of fixed-step RK4 at dt = 1 ms; angles in radians, benchmark
signs (lean right, steer right, yaw right positive). From the repository root:

    python3 -m venv /tmp/pydyvenv
    /tmp/pydyvenv/bin/pip install pydy sympy numpy scipy cython
    /tmp/pydyvenv/bin/python bench/pydy_whipple.py /tmp/pydy_traj.csv
    cargo build --release -p whipple-cli
    target/release/whipple simulate --bike benchmark --speed 4.6 --lean-rate 0.5 \
        --duration 10 --format csv --out /tmp/whipple_traj.csv
    /tmp/pydyvenv/bin/python bench/compare_trajectories.py /tmp/pydy_traj.csv /tmp/whipple_traj.csv

(any Python with numpy will do for this script). Columns are matched by name; the PyDy
trajectory is interpolated linearly onto whipple's times if the time grids differ. It prints
the largest difference of each common column over the run, where it occurs, the columns'
largest magnitudes, and both trajectories at a few times.
"""

import sys

import numpy as np

COLUMNS = ["lean", "steer", "lean_rate", "steer_rate", "speed", "yaw", "x", "y"]
TIMES = [0.5, 1.0, 2.0, 5.0, 10.0]


def load(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {name: data[name] for name in data.dtype.names}


def main():
    pydy_path = sys.argv[1] if len(sys.argv) > 1 else "/tmp/pydy_traj.csv"
    whipple_path = sys.argv[2] if len(sys.argv) > 2 else "/tmp/whipple_traj.csv"
    a, b = load(pydy_path), load(whipple_path)
    t = b["t"]
    same_grid = len(a["t"]) == len(t) and np.max(np.abs(a["t"] - t)) < 1e-9
    print(f"PyDy {pydy_path}: {len(a['t'])} samples to t = {a['t'][-1]:g} s; "
          f"whipple {whipple_path}: {len(t)} samples to t = {t[-1]:g} s"
          f"{'' if same_grid else ' (PyDy interpolated onto whipple times)'}")

    def pydy(name):
        return a[name] if same_grid else np.interp(t, a["t"], a[name])

    common = [c for c in COLUMNS if c in a and c in b]
    print(f"{'column':11} {'max |diff|':>11} {'at t [s]':>9} {'max |value|':>12} "
          f"{'relative':>9}")
    for c in common:
        d = np.abs(pydy(c) - b[c])
        k = int(np.argmax(d))
        scale = np.max(np.abs(b[c]))
        print(f"{c:11} {d[k]:11.2e} {t[k]:9.3f} {scale:12.4g} {d[k] / scale:9.1e}")

    for c in ("lean", "steer", "lean_rate", "steer_rate"):
        print(f"{c}:")
        for tt in TIMES:
            k = int(np.argmin(np.abs(t - tt)))
            pa, pb = pydy(c)[k], b[c][k]
            print(f"  t = {t[k]:5.2f} s  PyDy {pa: .12f}  whipple {pb: .12f}  "
                  f"diff {pa - pb: .2e}")


if __name__ == "__main__":
    main()
