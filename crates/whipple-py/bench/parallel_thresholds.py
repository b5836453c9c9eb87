"""Where parallel pays: `state_space`, untracked and tracked `eig` on one core
(`parallel=False`) against the default (`parallel=True`), at 10 to 10⁶ speeds of the benchmark
bicycle, best of many calls (60 up to 10⁴ speeds, 9 at 10⁵, 3 at 10⁶), in milliseconds.

    python crates/whipple-py/bench/parallel_thresholds.py [SPEEDS ...]

Needs whipple installed (pip install ./crates/whipple-py). Say how many cores the machine has
and how loaded it was when quoting the figures (BENCHMARKS.md)."""

import os
import sys
import time

import numpy as np

import whipple


def best(f, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    bike = whipple.Bicycle.preset("benchmark")
    sizes = [int(x) for x in sys.argv[1:]] or [10, 100, 1000, 10**4, 10**5, 10**6]
    print(f"machine: {os.cpu_count()} cores; load average {os.getloadavg()[0]:.1f}; "
          "ms, one core / parallel")
    calls = (
        ("state_space", lambda v, p: bike.state_space(v, parallel=p)),
        ("eig untracked", lambda v, p: bike.eig(v, tracked=False, parallel=p)),
        ("eig tracked", lambda v, p: bike.eig(v, parallel=p)),
    )
    for n in sizes:
        v = np.linspace(0.0, 10.0, n)
        repeat = 60 if n <= 10**4 else (9 if n < 10**6 else 3)
        row = [f"{n:>8}"]
        for name, call in calls:
            one = best(lambda: call(v, False), repeat)
            both = best(lambda: call(v, True), repeat)
            row.append(f"{name} {one * 1e3:9.3f} / {both * 1e3:9.3f}")
        print("  |  ".join(row), flush=True)


if __name__ == "__main__":
    main()
