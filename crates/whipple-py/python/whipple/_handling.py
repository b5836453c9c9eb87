"""Hess's handling quality metric (HQM) as HumanControl computes it:
``whipple.handling_quality(bicycle, gains=..., speed=...)``. The metric, its magnitude and its
peak over frequency (certified: the critical points are the real roots of a polynomial, none
sampled) are computed by the Rust library; this module reads the arguments and names the
results."""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _whipple
from ._errors import ArgumentError, NumericalError

GainsLike = Union[str, "os.PathLike[str]", Sequence[float]]


class HandlingQuality:
    """HQM of a bicycle at one speed, or its peaks against speed.

    At one speed: ``speed`` [m/s], ``frequencies`` ω [rad/s] and ``magnitudes`` |HQM(jω)|
    (numpy arrays), ``peak`` and ``peak_frequency`` (the maximum over all ω ≥ 0), ``certified``
    (every critical point resolved), ``stable`` (the roll loop; HQM is meaningful only then),
    ``gains`` (kDelta, kPhiDot, kPhi, kPsi, kY as used), ``extrapolated`` (the speed is outside
    the gains file's), ``numerator`` and ``denominator`` of HQM(s), lowest power first.

    Against speed: ``speeds``, ``peaks`` and ``peak_frequencies`` (numpy arrays) and the lists
    ``certified``, ``stable``, ``extrapolated``.
    """

    def __init__(self, values: dict) -> None:
        for key, value in values.items():
            setattr(self, key, value)

    def __repr__(self) -> str:
        if hasattr(self, "peaks"):
            return f"HandlingQuality(speeds={len(self.speeds)} values)"
        return (f"HandlingQuality(speed={self.speed!r}, peak={self.peak!r}, "
                f"peak_frequency={self.peak_frequency!r})")

    def plot(self, ax: Any = None) -> Any:
        """|HQM(jω)| against ω (one speed) or the peak against speed, with Hess's levels 5 and
        8, on matplotlib axes (new ones when ``ax`` is None)."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        if hasattr(self, "peaks"):
            ax.plot(self.speeds, self.peaks, label="peak HQM")
            ax.set_xlabel("forward speed v [m/s]")
            ax.set_ylabel("max |HQM(jω)|")
        else:
            ax.plot(self.frequencies, self.magnitudes, label="|HQM(jω)|")
            ax.plot([self.peak_frequency], [self.peak], "o", label="peak")
            ax.set_xlabel("frequency ω [rad/s]")
            ax.set_ylabel("|HQM(jω)|")
        for level, style in ((5.0, "--"), (8.0, ":")):
            ax.axhline(level, color="k", linestyle=style, linewidth=0.8)
        ax.legend()
        return ax


def _gains(gains: GainsLike) -> dict:
    if isinstance(gains, (str, os.PathLike)):
        path = os.fspath(gains)
        size = os.path.getsize(path)
        if size > _whipple.MAX_FILE_BYTES:
            raise ArgumentError(f"invalid gains: {path} holds {size} bytes, more than a gains "
                                f"file may")
        with open(path, encoding="utf-8") as f:
            return {"gains_text": f.read()}
    try:
        row = [float(k) for k in np.asarray(gains, dtype=np.float64).ravel()]
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"invalid gains: a SteerGains file's path or five numbers "
                            f"(kDelta, kPhiDot, kPhi, kPsi, kY): {error}") from None
    return {"gains_row": row}


def handling_quality(bicycle: Any, gains: GainsLike, speed: Optional[float] = None,
                     speeds: Optional[Sequence[float]] = None,
                     frequencies: Optional[Sequence[float]] = None,
                     neuro_frequency: float = 30.0,
                     neuro_damping: float = 0.707) -> HandlingQuality:
    """Hess's handling quality metric of ``bicycle`` ridden by Hess's controller with
    ``gains``: a HumanControl ``<Name>SteerGains.txt`` path (interpolated in speed,
    extrapolated outside it and said so in ``extrapolated``) or five gains (kDelta, kPhiDot,
    kPhi, kPsi, kY; only the first three enter). With ``speed`` [m/s]: |HQM(jω)| at
    ``frequencies`` [rad/s] (default 0 to 40 rad/s, 801 points, as HumanControl plots it) and
    the peak over all ω; with ``speeds``: the peak at each. The neuromuscular filter is
    ω²/(s² + 2ζωs + ω²) with ω = ``neuro_frequency``, ζ = ``neuro_damping``.

    >>> import whipple
    >>> bike = whipple.Bicycle.preset("benchmark")
    >>> hqm = whipple.handling_quality(bike, [46.5457, -0.0522, 12.6611, 0.1849, 0.0959], speed=5.0)
    >>> hqm.stable and hqm.certified and hqm.magnitudes.max() <= hqm.peak
    True
    """
    native = bicycle._native
    rider = dict(_gains(gains), neuro_frequency=float(neuro_frequency),
                 neuro_damping=float(neuro_damping))
    if (speed is None) == (speeds is None):
        raise ArgumentError("invalid speed: give speed (one, in m/s) or speeds (several)")
    if speeds is not None:
        values = [float(v) for v in np.asarray(speeds, dtype=np.float64).ravel()]
        return HandlingQuality(_whipple.handling_against_speed_native(native, values, **rider))
    if frequencies is None:
        grid = np.linspace(0.0, 40.0, 801)
    else:
        grid = np.asarray(frequencies, dtype=np.float64).ravel()
    return HandlingQuality(_whipple.handling_quality_native(native, float(speed),
                                                           [float(w) for w in grid], **rider))


class OptimalHandling:
    """The result of :func:`optimal_handling`: ``names`` and ``units`` of the varied
    parameters; ``base`` and ``best`` (dicts: ``values`` in the user's units, ``cost``,
    ``stable``, ``peak``, ``peak_frequency``, ``certified``, ``gains``, ``refused``);
    ``starts`` (a list of dicts: ``start``, ``best``, ``evaluations``, ``converged``);
    ``evaluations``; ``bicycle``, the best design as a :class:`whipple.Bicycle`.

    A local search from several starts: the best start's result, not a certified global
    minimum."""

    def __init__(self, values: dict) -> None:
        from ._bicycle import Bicycle

        for key, value in values.items():
            setattr(self, key, value)
        self.bicycle = Bicycle._wrap(values["bicycle"])

    @property
    def values(self) -> Dict[str, float]:
        """The best design's varied parameters by name (the user's units)."""
        return {n: float(x) for n, x in zip(self.names, self.best["values"])}

    @property
    def peak(self) -> float:
        """The best design's certified peak HQM."""
        return float(self.best["peak"])

    def __repr__(self) -> str:
        return (f"OptimalHandling(values={self.values!r}, peak={self.peak!r}, "
                f"base_peak={self.base['peak']!r}, starts={len(self.starts)})")


def optimal_handling(bicycle: Any, speed: float,
                     vary: Mapping[str, Tuple[float, float]],
                     starts: int = 6, iterations: int = 2000,
                     neuro_frequency: float = 30.0,
                     neuro_damping: float = 0.707) -> OptimalHandling:
    """BMD 2016's optimal-handling search: the peak HQM of ``bicycle`` at the design ``speed``
    [m/s] minimized over the parameters of ``vary`` ({name: (low, high)}, named as design
    studies name their axes: ``trail``, ``head_angle_deg`` in degrees, ``w``, ``rF``), the
    rider's gains set for each candidate by Hess 2012's rules. Nelder–Mead from ``starts``
    starts (the bicycle's own values, then Halton points in the box), each at most
    ``iterations`` iterations; Ctrl-C honoured. Raises when no start finds a design whose
    roll and lateral loops are stable.

    >>> import whipple
    >>> bike = whipple.Bicycle.preset("benchmark")
    >>> best = whipple.optimal_handling(bike, 5.0, {"trail": (0.0, 0.2)}, starts=2)
    >>> best.peak < best.base["peak"]
    True
    """
    bounds = []
    for name, pair in vary.items():
        try:
            low, high = (float(x) for x in pair)
        except (TypeError, ValueError) as error:
            raise ArgumentError(f"invalid vary[{name!r}]: expects (low, high): {error}") from None
        bounds.append((str(name), low, high))
    result = OptimalHandling(_whipple.optimal_handling_native(
        bicycle._native, float(speed), bounds, starts=int(starts), iterations=int(iterations),
        neuro_frequency=float(neuro_frequency), neuro_damping=float(neuro_damping)))
    if not result.best["stable"]:
        raise NumericalError(
            f"no start found a design whose roll and lateral loops are stable at {speed} m/s "
            f"within these bounds (the bicycle itself: "
            f"{result.base['refused'] or 'unstable'})")
    return result


__all__ = ["HandlingQuality", "handling_quality", "OptimalHandling", "optimal_handling"]
