"""Times BicycleParameters on the eigenvalue sweep that `cargo bench --bench sweep` times.

Run it in a throw-away virtual environment (BicycleParameters is never a dependency of whipple):

    python3 -m venv /tmp/bp && /tmp/bp/bin/pip install bicycleparameters
    /tmp/bp/bin/python bench/bicycleparameters_sweep.py

It prints speeds per second for (a) the loop of `Bicycle.eig` (canonical matrices once, then
A(v) and numpy.linalg.eig per speed) and (b) `Meijaard2007Model.calc_eigen` with all speeds at
once (numpy's batched eig), over 0 to 10 m/s in steps of 0.001 m/s (10,001 speeds), and the
largest difference from whipple's eigenvalues at the published Table 2 speeds.
"""

import math
import time

import numpy as np
from bicycleparameters import bicycle
from bicycleparameters.models import Meijaard2007Model
from bicycleparameters.parameter_sets import Meijaard2007ParameterSet

# Meijaard et al. 2007, Table 1.
PAR = {
    "w": 1.02, "c": 0.08, "lam": math.pi / 10, "g": 9.81,
    "rR": 0.3, "mR": 2.0, "IRxx": 0.0603, "IRyy": 0.12,
    "xB": 0.3, "zB": -0.9, "mB": 85.0,
    "IBxx": 9.2, "IByy": 11.0, "IBzz": 2.8, "IBxz": 2.4,
    "xH": 0.9, "zH": -0.7, "mH": 4.0,
    "IHxx": 0.05892, "IHyy": 0.06, "IHzz": 0.00708, "IHxz": -0.00756,
    "rF": 0.35, "mF": 3.0, "IFxx": 0.1405, "IFyy": 0.28,
}

SPEEDS = np.linspace(0.0, 10.0, 10001)


def bicycle_eig_loop(speeds):
    M, C1, K0, K2 = bicycle.benchmark_par_to_canonical(PAR)
    out = np.zeros((len(speeds), 4), dtype=complex)
    for i, v in enumerate(speeds):
        A, _ = bicycle.ab_matrix(M, C1, K0, K2, v, PAR["g"])
        out[i] = np.linalg.eig(A)[0]
    return out


def model_calc_eigen(speeds):
    pars = dict(PAR)
    pars["v"] = 0.0
    model = Meijaard2007Model(Meijaard2007ParameterSet(pars, True))
    return model.calc_eigen(v=speeds)[0]


def best_rate(fn, repeats=5):
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn(SPEEDS)
        best = min(best, time.perf_counter() - t0)
    return len(SPEEDS) / best


if __name__ == "__main__":
    print(f"Bicycle.eig loop:               {best_rate(bicycle_eig_loop):12.0f} speeds/s")
    try:
        print(f"Meijaard2007Model.calc_eigen:   {best_rate(model_calc_eigen):12.0f} speeds/s")
    except Exception as error:  # the model API has changed between releases
        print(f"Meijaard2007Model.calc_eigen: unavailable ({error})")
    # Accuracy against Meijaard 2007 Table 2 at v = 5 m/s.
    ev = np.sort_complex(bicycle_eig_loop(np.array([5.0]))[0])
    published = np.sort_complex(np.array([
        -0.77534188219585 + 4.46486771378823j, -0.77534188219585 - 4.46486771378823j,
        -0.32286642900409, -14.0783896927982]))
    print(f"max |difference| from Table 2 at 5 m/s: {np.max(np.abs(ev - published)):.2e}")
