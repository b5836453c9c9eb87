"""HumanControl's lane change ridden by Hess's controller: ``whipple.lane_change``. The path
(``lane_change.m`` as ``generate_data.m`` sets it up: its path filter and preview time), the
closed loop on the linear bicycle (exact) and the same controller steering the non-linear
bicycle are the Rust library's; this module reads the arguments and names the results."""

from __future__ import annotations

import os
import warnings
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np

from ._errors import ArgumentError, ParameterWarning

# The largest gains file read (HumanControl's are a few hundred bytes).
_MAX_GAINS_BYTES = 16 << 20


class LaneChangeRun(Dict[str, Any]):
    """The dict :func:`lane_change` returns, with :meth:`plot`."""

    def plot(self, ax: Any = None) -> Any:
        """The road (the path, preview delayed) and the front contact's path in the plane for
        each model run, on matplotlib axes (new ones when ``ax`` is None)."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        runs = [(name, self[name]) for name in ("linear", "nonlinear") if self.get(name)]
        if runs:
            first = runs[0][1]
            ax.plot(first["front_x"], first["path"], "k--", label="road (the path, preview delayed)")
        for name, run in runs:
            ax.plot(run["front_x"], run["front_y"], label=f"front contact y_Q, {name}")
        ax.set_xlabel("distance along x [m]")
        ax.set_ylabel("lateral position y [m]")
        ax.legend()
        return ax


def lane_change(bicycle: Any, gains: Union[str, "os.PathLike[str]", Sequence[float]],
                speed: float, lane: str = "double", model: str = "both",
                width: Optional[float] = None, neuro_frequency: float = 30.0,
                neuro_damping: float = 0.707, rtol: float = 1e-9) -> LaneChangeRun:
    """HumanControl's single or double lane change at ``speed`` [m/s], ridden by Hess's
    controller (the lateral task) on the linear bicycle (exactly), the non-linear one, or both.

    ``gains``: a HumanControl ``<Name>SteerGains.txt`` file (interpolated linearly at the speed;
    outside its speeds extrapolated, with a :class:`whipple.ParameterWarning`), or the five
    gains kDelta, kPhiDot, kPhi, kPsi, kY. ``lane``: ``"single"`` or ``"double"`` (2 m over at
    35 m, slope 0.2, back within 60 m; 250 m in 500 intervals; preview 2.75 s; path filter
    2.4 rad/s). ``width``: the lateral offset [m], right positive (default 2). ``model``:
    ``"linear"``, ``"nonlinear"`` or ``"both"``. ``neuro_frequency`` [rad/s] and
    ``neuro_damping``: the neuromuscular filter. ``rtol``: the non-linear run's tolerance.

    Returns a dict (:class:`LaneChangeRun`, whose ``plot()`` draws the paths): ``gains`` (the five used), ``extrapolated``, and ``linear`` and
    ``nonlinear`` (None for a model not run), each a dict of numpy arrays at the path's 501
    sample times: ``time`` [s], ``path`` (the road: the path delayed by the preview) [m],
    ``command`` y_c (the path through the path filter) [m], ``front_x`` (distance travelled)
    [m], ``front_y`` y_Q [m], ``error`` y_c − y_Q [m], ``lean``, ``steer``, ``yaw`` [rad],
    ``steer_torque`` [N m].

    >>> import whipple
    >>> bike = whipple.Bicycle.preset("benchmark")
    >>> run = whipple.lane_change(bike, [46.5457, -0.0522, 12.6611, 0.1849, 0.0959], 5.0,
    ...                           model="linear")
    >>> run["linear"]["front_y"].shape
    (501,)
    """
    if isinstance(gains, (str, os.PathLike)):
        with open(gains, "rb") as f:
            data = f.read(_MAX_GAINS_BYTES + 1)
        if len(data) > _MAX_GAINS_BYTES:
            raise ArgumentError(f"gains: {os.fspath(gains)} is longer than 16 MiB")
        try:
            text: Optional[str] = data.decode("utf-8")
        except UnicodeDecodeError as e:
            raise ArgumentError(f"gains: {os.fspath(gains)} is not UTF-8 text") from e
        values = None
    else:
        values = [float(k) for k in np.asarray(gains, dtype=float).reshape(-1)]
        text = None
    result = bicycle._native.lane_change(
        float(speed), values, text, str(lane), None if width is None else float(width),
        str(model), float(neuro_frequency), float(neuro_damping), float(rtol))
    if result["extrapolated"]:
        warnings.warn(f"{speed} m/s is outside the gains file's speeds: the gains are "
                      "extrapolated, as HumanControl warns", ParameterWarning, stacklevel=2)
    return LaneChangeRun(result)


__all__ = ["lane_change", "LaneChangeRun"]
