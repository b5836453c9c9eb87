"""Times a design map the way a BicycleParameters user computes one today: for each design of
a trail x head-angle grid, BicycleParameters' canonical matrices (`benchmark_par_to_canonical`)
and an eigenvalue scan over speed, A(v) for all speeds at once and numpy's batched `eigvals`
(about twice the speeds per second of BicycleParameters' own `calc_eigen`, so the comparison
favours it), the self-stable range read off where every real part is negative. Compare with
`cargo bench -p whipple-bench --bench design` (whipple's certified structure on every speed
v >= 0) run on the same machine in the same session (bench/run_all.sh does both).

    python3 -m venv /tmp/bp && /tmp/bp/bin/pip install bicycleparameters
    /tmp/bp/bin/python bench/bicycleparameters_design_map.py [N_PER_AXIS] [N_SPEEDS]

Defaults: an 8 x 8 grid of the benchmark bicycle (trail 0..0.2 m, head angle 60..80 deg) and
1001 speeds from 0 to 10 m/s per design (a resolution of 0.01 m/s; whipple's speeds are exact
to round-off on the whole half-line). Prints designs per second and, for one design, the
stable range both ways.
"""

import math
import sys
import time

import numpy as np
from bicycleparameters import bicycle

# Meijaard et al. 2007, Table 1 (the sweep script beside this one holds it).
from bicycleparameters_sweep import PAR  # noqa: E402


def stable_range(par, speeds):
    """(first, last) sampled speed where all four eigenvalues have negative real parts."""
    M, C1, K0, K2 = bicycle.benchmark_par_to_canonical(par)
    g = par["g"]
    Minv = np.linalg.inv(M)
    n = len(speeds)
    A = np.zeros((n, 4, 4))
    A[:, 0, 2] = 1.0
    A[:, 1, 3] = 1.0
    v = speeds[:, None, None]
    A[:, 2:, :2] = -(Minv @ (g * K0 + v**2 * K2))
    A[:, 2:, 2:] = -(Minv @ (v * C1))
    stable = np.all(np.linalg.eigvals(A).real < 0.0, axis=1)
    idx = np.flatnonzero(stable)
    return (float(speeds[idx[0]]), float(speeds[idx[-1]])) if idx.size else None


def main():
    n_axis = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    n_speeds = int(sys.argv[2]) if len(sys.argv) > 2 else 1001
    speeds = np.linspace(0.0, 10.0, n_speeds)
    trails = np.linspace(0.0, 0.2, n_axis)
    heads = np.radians(np.linspace(60.0, 80.0, n_axis))
    t0 = time.perf_counter()
    found = 0
    for head in heads:
        for trail in trails:
            par = dict(PAR, c=trail, lam=math.pi / 2 - head)
            found += stable_range(par, speeds) is not None
    t = time.perf_counter() - t0
    n = n_axis * n_axis
    print(f"BicycleParameters eigenvalue scans: {n} designs x {n_speeds} speeds in {t:.3f} s: "
          f"{n / t:.1f} designs/s ({found} with a sampled self-stable range)")
    print(f"benchmark bicycle, sampled stable range: {stable_range(PAR, speeds)} m/s "
          f"(whipple, certified: 4.292383 to 6.024262 m/s)")


if __name__ == "__main__":
    main()
