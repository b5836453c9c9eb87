"""Figures with matplotlib (the optional extra ``whipple[plot]``), in the look of the command
line's: eigenvalues against speed, and a simulation's lean, steer, speed and ground track."""

from __future__ import annotations

from typing import Any

import numpy as np

# The command line's colours per mode (whipple-report).
_MODE_COLOURS = {"weave": "#1f77b4", "capsize": "#d62728", "castering": "#2ca02c"}


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as error:  # pragma: no cover - depends on the environment
        raise ImportError("plots need matplotlib: pip install ./crates/whipple-py[plot]") from error
    return plt


def plot_eigen(eigen: Any, ax=None, imaginary: bool = True):
    """Re λ (solid) and |Im λ| (dashed) against speed, one colour per mode; the axis."""
    plt = _pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
    v = np.atleast_1d(eigen.speeds)
    values = np.atleast_2d(eigen.values)
    modes = eigen.modes or [f"eigenvalue {k + 1}" for k in range(4)]
    shown = set()
    for k in range(values.shape[1]):
        colour = _MODE_COLOURS.get(modes[k], None)
        label = None if modes[k] in shown else f"{modes[k]} Re λ"
        shown.add(modes[k])
        ax.plot(v, values[:, k].real, color=colour, lw=1.6, label=label)
        if imaginary and np.any(values[:, k].imag > 0):
            ax.plot(v, np.abs(values[:, k].imag), color=colour, lw=1.0, ls="--",
                    label=f"{modes[k]} |Im λ|")
    ax.axhline(0.0, color="0.3", lw=0.8)
    ax.set_xlabel("speed v [m/s]")
    ax.set_ylabel("eigenvalue λ [1/s]")
    ax.grid(True, color="0.9")
    ax.legend(loc="best", fontsize="small")
    return ax


def plot_simulation(run: Any, ax=None):
    """Lean and steer [deg] and speed against time, and the ground track of both contacts.
    With ``ax`` a sequence of two axes, draws into them; returns the two axes."""
    plt = _pyplot()
    if ax is None:
        fig, ax = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
        fig.suptitle(f"{run.label}: {run.caption}")
    left, right = ax
    t = run.t
    left.plot(t, np.degrees(run.lean), label="lean φ [deg]", color="#1f77b4")
    left.plot(t, np.degrees(run.steer), label="steer δ [deg]", color="#d62728")
    left.set_xlabel("time t [s]")
    left.set_ylabel("angle [deg]")
    speed = left.twinx()
    speed.plot(t, run.speed, color="0.4", lw=1.0, ls="--", label="speed v [m/s]")
    speed.set_ylabel("speed v [m/s]")
    if run.outcome_t is not None and run.outcome_kind in ("fell", "wheel_lifted"):
        left.axvline(run.outcome_t, color="0.3", lw=0.8, ls=":")
    left.grid(True, color="0.9")
    left.legend(loc="upper left", fontsize="small")
    right.plot(run.x, run.y, label="rear contact", color="#1f77b4")
    right.plot(run.front_x, run.front_y, label="front contact", color="#d62728", lw=0.8)
    right.set_xlabel("x [m]")
    right.set_ylabel("y [m] (right)")
    right.invert_yaxis()
    right.set_aspect("equal", adjustable="datalim")
    right.grid(True, color="0.9")
    right.legend(loc="best", fontsize="small")
    return left, right
