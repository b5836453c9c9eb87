"""Closed-loop eigenvalues over many speeds from Python: whipple's ``ClosedLoop.eig(speeds)``
(certified eigenvalues of the closed loop's quartic, tracked and labelled, with eigenvectors)
against BicycleParameters' ``Meijaard2007WithFeedbackModel.calc_eigen(v=speeds, gains…)`` (its
broadcast state space, then numpy's ``eig``) and against numpy's batched ``eig`` of the stack of
A − B K alone (the matrices formed beforehand, untimed: the least a numpy user pays), in the
same run, on the benchmark bicycle with steer into the fall, T_δ = 100 φ − 10 δ + 20 φ̇.

    python crates/whipple-py/bench/closed_loop_vs_bicycleparameters.py [N_SPEEDS] [N_BP]

Needs whipple (pip install ./crates/whipple-py), numpy and bicycleparameters (PyPI)."""

import sys
import time
import warnings

import numpy as np

import whipple

GAINS = np.array([[-100.0, 10.0, -20.0, 0.0]])


def timed(f, repeat=3):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    n_bp = int(sys.argv[2]) if len(sys.argv) > 2 else n
    from bicycleparameters.models import Meijaard2007WithFeedbackModel
    from bicycleparameters.parameter_sets import Meijaard2007ParameterSet

    bike = whipple.Bicycle.preset("benchmark")
    loop = bike.closed_loop(GAINS, inputs="steer_torque")
    speeds = np.linspace(0.0, 10.0, n)
    bp_speeds = np.linspace(0.0, 10.0, n_bp)
    ps = Meijaard2007ParameterSet({**bike.to_dict(), "v": 1.0}, True)
    model = Meijaard2007WithFeedbackModel(ps)
    gains = {"kTdel_phi": GAINS[0, 0], "kTdel_del": GAINS[0, 1], "kTdel_phid": GAINS[0, 2],
             "kTdel_deld": GAINS[0, 3]}

    t_ours, ours = timed(lambda: loop.eig(speeds))
    t_ours1, _ = timed(lambda: loop.eig(speeds[:1000]))

    def with_bp():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return model.calc_eigen(v=bp_speeds, **gains)

    t_bp, theirs = timed(with_bp, repeat=1)
    a, _ = model.form_state_space_matrices(v=bp_speeds, **gains)
    t_np, _ = timed(lambda: np.linalg.eig(a), repeat=1)
    t_npv, _ = timed(lambda: np.linalg.eigvals(a), repeat=1)

    # The same numbers: every speed of BicycleParameters' sweep against ours (sets compared).
    if n_bp == n:
        mine = np.sort_complex(ours.values)
        their = np.sort_complex(theirs[0])
        scale = np.maximum(1.0, np.abs(their))
        print(f"largest difference from BicycleParameters' eigenvalues: "
              f"{np.max(np.abs(mine - their) / scale):.1e} (relative to max(1, |λ|))")
    per = lambda t, k: t / k * 1e6  # noqa: E731
    print(f"\n{n:,} speeds for whipple; {n_bp:,} for BicycleParameters and numpy\n")
    print("| call | speeds | time | µs per speed | vs BicycleParameters |")
    print("|---|---|---|---|---|")
    bp_us = per(t_bp, n_bp)
    for name, t, k in (
        ("BicycleParameters `calc_eigen(v=speeds, gains…)` (values and vectors)", t_bp, n_bp),
        ("numpy `eig` of the A − B K stack alone (vectors)", t_np, n_bp),
        ("numpy `eigvals` of the A − B K stack alone", t_npv, n_bp),
        ("whipple `ClosedLoop.eig(speeds)` (certified, tracked, vectors)", t_ours, n),
    ):
        print(f"| {name} | {k:,} | {t:.3f} s | {per(t, k):.2f} | {bp_us / per(t, k):.1f}× |")
    print(f"\n(whipple on 1,000 speeds: {t_ours1 * 1e3:.2f} ms)")


if __name__ == "__main__":
    main()
