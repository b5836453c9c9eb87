"""Pendulum periods from oscillation records: ``whipple.fit_period(t, y)`` and
``whipple.read_period(path)``. The decaying oscillation
y(t) = c + e^(−σt) (a sin ω_d t + b cos ω_d t) is fitted by the Rust library (Levenberg–Marquardt,
exact Jacobian), as BicycleParameters' ``period.py`` fits its rate-gyro records; this module reads
the arguments and names the results."""

from __future__ import annotations

import os
from typing import Any, Dict, Optional, Tuple, Union

import numpy as np

from . import _whipple
from ._errors import ArgumentError


class PeriodFit:
    """A decaying oscillation fitted to a record.

    Attributes: ``period`` T = 2π/ω_d [s] and ``period_sigma`` (from the fit's covariance
    s²(JᵀJ)⁻¹), ``damping_ratio`` ζ and ``damping_ratio_sigma``, ``natural_frequency`` ω_n
    [rad/s], ``amplitude``, ``parameters`` [c, a, b, σ, ω_d] with their ``covariance`` (5 × 5),
    ``residual_rms``, ``residual_sigma`` s, ``r_squared``, ``iterations``; the record as fitted:
    ``time``, ``signal`` (numpy arrays, the whole record), ``window`` (start, end) of the samples
    fitted and ``fitted`` (the curve at those samples' times); for a file also ``signal_name``
    and ``time_source``.
    """

    period: float
    period_sigma: float
    damping_ratio: float
    damping_ratio_sigma: float
    natural_frequency: float
    amplitude: float
    parameters: np.ndarray
    covariance: np.ndarray
    residual_rms: float
    residual_sigma: float
    r_squared: float
    iterations: int
    window: Tuple[int, int]
    time: np.ndarray
    signal: np.ndarray
    fitted: np.ndarray
    signal_name: Optional[str]
    time_source: Optional[str]

    def __init__(self, values: Dict[str, Any]) -> None:
        self.signal_name = None
        self.time_source = None
        for key, value in values.items():
            setattr(self, key, value)
        self.covariance = np.asarray(self.covariance, dtype=np.float64)
        self.window = tuple(self.window)  # type: ignore[assignment]

    def __repr__(self) -> str:
        return (f"PeriodFit(period={self.period!r}, period_sigma={self.period_sigma!r}, "
                f"damping_ratio={self.damping_ratio!r})")

    def plot(self, ax: Any = None) -> Any:
        """The record and the fitted curve on matplotlib axes (new ones when ``ax`` is None)."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        start, end = self.window
        ax.plot(self.time, self.signal, ".", markersize=2, label="record")
        ax.plot(self.time[start:end], self.fitted, "-", label="fitted decaying oscillation")
        ax.set_xlabel("time t [s]")
        ax.set_title(f"T = {self.period:.6f} ± {self.period_sigma:.2e} s, "
                     f"ζ = {self.damping_ratio:.4e}")
        ax.legend()
        return ax


def _samples(values: Any, field: str) -> list:
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"{field}: give the samples as numbers", field=field, value=None,
                            rule="a 1-D array of numbers") from error
    if arr.ndim != 1:
        raise ArgumentError(f"{field}: the samples must be 1-D, got shape {arr.shape}",
                            field=field, value=None, rule="a 1-D array of numbers")
    return arr.tolist()


def fit_period(t: Any, y: Any, trim: Optional[float] = None) -> PeriodFit:
    """The period (with σ) and damping of a decaying oscillation sampled at times ``t`` [s]
    (increasing) with values ``y``. ``trim`` keeps only the samples from the largest swing to
    the last above that fraction of it (BicycleParameters uses 0.1).

    >>> import numpy as np, whipple
    >>> t = np.arange(2000) / 200.0
    >>> fit = whipple.fit_period(t, 0.5 + np.exp(-0.05 * t) * np.sin(4.0 * t))
    >>> round(fit.period, 9) == round(2 * np.pi / 4.0, 9)
    True
    """
    return PeriodFit(_whipple.fit_period_native(_samples(t, "time"), _samples(y, "signal"),
                                                trim))


def read_period(path: Union[str, "os.PathLike[str]"], column: Optional[str] = None,
                time: Optional[str] = None, rate: Optional[float] = None,
                trim: Optional[float] = None) -> PeriodFit:
    """Reads an oscillation record — CSV (a time column and a signal column, or one column
    with ``rate`` [Hz]) or MATLAB v5 ``.mat`` as BicycleParameters' rate-gyro files (``data``
    with ``ActualRate``, ``sampleRate`` or ``time``) — and fits its period as
    :func:`fit_period`. ``column`` and ``time`` name the columns (header name or 1-based
    number) or ``.mat`` variables."""
    return PeriodFit(_whipple.read_period_native(os.fspath(path), column, time, rate, trim))


__all__ = ["PeriodFit", "fit_period", "read_period"]
