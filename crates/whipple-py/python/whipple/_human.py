"""Hess's human controller (Hess, Moore & Hubbard 2012): ``whipple.HumanController`` (the rider's
nested loops and neuromuscular filter), the ridden bicycle's closed loop ``whipple.HumanLoop``,
each loop's transfer functions and crossover (``whipple.RiderLoop``), gains by Hess 2012's rules
(``whipple.hess_gains``), eigenvalues against speed (``whipple.human_eigenvalues``) and
HumanControl's gain tables (``whipple.read_gains``, ``whipple.GainTable``). Every number is
computed by the Rust library; SI units and radians."""

from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Any, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _whipple
from ._errors import ArgumentError, LimitError, ParseError

if TYPE_CHECKING:
    from ._bicycle import Bicycle

#: HumanControl's names of the five gains, in the order every gains array holds them.
GAIN_NAMES = ("kDelta", "kPhiDot", "kPhi", "kPsi", "kY")

#: Hess 2012's rules as HumanControl applies them for steer control: the steer and roll-rate
#: loops' closed-loop damping, and the φ, ψ, y loops' crossover frequencies [rad/s].
STEER_DAMPING = 0.1289
ROLL_RATE_DAMPING = 0.0855
CROSSOVERS = (2.0, 1.0, 0.5)


class ExtrapolationWarning(UserWarning):
    """Gains looked up outside a table's speeds: extrapolated linearly, as HumanControl's
    ``lookup_gains.m`` does (and warns)."""


def _gains(gains: Any) -> List[float]:
    arr = np.asarray(gains, dtype=np.float64).reshape(-1)
    return [float(x) for x in arr]


class GainLookup(NamedTuple):
    """The gains a :class:`GainTable` gives at one speed: ``gains`` (kDelta, kPhiDot, kPhi, kPsi,
    kY) and whether the speed lies outside the table (``extrapolated``)."""

    gains: np.ndarray
    extrapolated: bool


class GainTable:
    """Gains tabulated against speed (HumanControl's ``<Name>SteerGains.txt``): ``speeds`` (n,)
    [m/s] and ``gains`` (n, 5) in :data:`GAIN_NAMES`' order. :meth:`at` interpolates linearly in
    speed as ``lookup_gains.m`` does; outside the table it extrapolates and warns
    (:class:`ExtrapolationWarning`)."""

    def __init__(self, speeds: Any, gains: Any) -> None:
        self.speeds = np.asarray(speeds, dtype=np.float64).reshape(-1).copy()
        self.gains = np.asarray(gains, dtype=np.float64).reshape(len(self.speeds), -1).copy()
        # The core checks the table (speeds increasing, gains finite) on every lookup; check
        # once here so a bad table fails where it is made.
        if len(self.speeds):
            self.at(float(self.speeds[0]))

    def at(self, speed: float) -> GainLookup:
        """The gains at ``speed`` [m/s] and whether they are extrapolated (then warned)."""
        gains, extrapolated = _whipple.gain_lookup(
            [float(v) for v in self.speeds], self.gains.tolist(), float(speed))
        if extrapolated:
            warnings.warn(
                f"{speed:g} m/s is outside the gain table's speeds ({self.speeds[0]:g} to "
                f"{self.speeds[-1]:g} m/s): the gains are extrapolated", ExtrapolationWarning,
                stacklevel=2)
        return GainLookup(np.asarray(gains), bool(extrapolated))

    def __repr__(self) -> str:
        return f"<GainTable {len(self.speeds)} speeds, {self.speeds[0]:g} to {self.speeds[-1]:g} m/s>"


def read_gains(path: Union[str, "os.PathLike[str]"]) -> GainTable:
    """A HumanControl gains file (``gains/<Name>SteerGains.txt``: a header naming ``speed``,
    ``kDelta``, ``kPhiDot``, ``kPhi``, ``kPsi``, ``kY`` in any order, then one row per speed),
    read by the library: a missing column or a bad number is a :class:`whipple.ParseError`
    naming it and its line."""
    path = os.fspath(path)
    limit = _whipple.MAX_FILE_BYTES
    with open(path, "rb") as f:
        data = f.read(limit + 1)
    if len(data) > limit:
        raise LimitError(f"{path}: longer than {limit >> 20} MiB, the most a gains file may hold",
                         field="path", value=path, rule=f"at most {limit} bytes")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ParseError(f"{path}: the file is not UTF-8 text", field=None, value=None,
                         rule="a gains file is UTF-8 text", format="gains", line=0,
                         column=0) from error
    speeds, rows = _whipple.read_gains_text(text)
    return GainTable(speeds, rows)


class LoopTransferFunction(NamedTuple):
    """N(s)/D(s), ``numerator`` and ``denominator`` highest power first (as ``numpy.polyval``
    and ``scipy.signal`` take them)."""

    numerator: np.ndarray
    denominator: np.ndarray

    def __call__(self, s: Any) -> Any:
        """The value at complex ``s`` (an array of them)."""
        return np.polyval(self.numerator, s) / np.polyval(self.denominator, s)


class RiderLoop(NamedTuple):
    """One of Hess's loops at one speed: ``name`` (``'delta'``, ``'phi_dot'``, ``'phi'``,
    ``'psi'``, ``'y'``), its ``gain`` name, ``open`` L(s) (broken at the loop's error, the loops
    inside it closed), ``closed`` T(s) (from its command to its output, it and those inside
    closed) and ``crossovers``: every ω > 0 [rad/s] where |L(iω)| = 1, certified real roots of
    |N(iω)|² − |D(iω)|² in ω² (``crossover_bounds`` their enclosures). ``crossover``: the highest,
    or None."""

    name: str
    gain: str
    open: LoopTransferFunction
    closed: LoopTransferFunction
    crossovers: np.ndarray
    crossover_bounds: np.ndarray

    @property
    def crossover(self) -> Optional[float]:
        return float(self.crossovers[-1]) if len(self.crossovers) else None


class HumanLoop:
    """The bicycle ridden by a :class:`HumanController` at one speed, ẋ = A x + B u: ``a``,
    ``b``, ``states`` (the bicycle's, then ``steer_torque`` and ``steer_torque_rate``, the
    neuromuscular filter's), ``inputs`` (the command, then the disturbances), ``eigenvalues``
    (decreasing real part) and ``speed``. HumanControl's ``system_state_space.m``."""

    def __init__(self, data: dict, speed: float, controller: "HumanController") -> None:
        self.a: np.ndarray = data["a"]
        self.b: np.ndarray = data["b"]
        self.states: Tuple[str, ...] = tuple(data["states"])
        self.inputs: Tuple[str, ...] = tuple(data["inputs"])
        self.eigenvalues: np.ndarray = data["eigenvalues"]
        self.speed = float(speed)
        self.controller = controller

    @property
    def stable(self) -> bool:
        """Whether every eigenvalue has a negative real part."""
        return bool(np.all(self.eigenvalues.real < 0.0))

    def __repr__(self) -> str:
        return (f"<HumanLoop {self.controller.task} at {self.speed:g} m/s: "
                f"{len(self.states)} states, {'stable' if self.stable else 'unstable'}>")


class HumanController:
    """Hess's rider: ``task`` (``'heading'`` or ``'lateral'``), ``gains`` (kDelta, kPhiDot,
    kPhi, kPsi, kY; four suffice for heading) and the neuromuscular filter
    ω²/(s² + 2ζωs + ω²) (``neuro_frequency`` ω [rad/s], ``neuro_damping`` ζ). Checked by the
    library: a zero gain the task uses, a gain that is not finite, or ω, ζ not positive is a
    :class:`whipple.ParameterError` naming it.

    >>> import whipple
    >>> rider = whipple.HumanController("lateral", [46.5457, -0.0522, 12.6611, 0.1849, 0.0959])
    >>> rider.closed_loop(whipple.Bicycle.preset("benchmark"), 5.0).stable
    True
    """

    def __init__(self, task: str, gains: Any, neuro_frequency: float = 30.0,
                 neuro_damping: float = 0.707) -> None:
        self.task = str(task)
        self.gains = np.asarray(_gains(gains))
        self.neuro_frequency = float(neuro_frequency)
        self.neuro_damping = float(neuro_damping)
        _whipple.check_human_controller(self.task, list(self.gains), self._neuro)

    @property
    def _neuro(self) -> Tuple[float, float]:
        return (self.neuro_frequency, self.neuro_damping)

    def closed_loop(self, bicycle: "Bicycle", speed: float,
                    disturbances: Sequence[str] = ()) -> HumanLoop:
        """The closed loop at ``speed`` [m/s]; ``disturbances`` are further inputs named as
        :meth:`whipple.Bicycle.linear_system` names them (``'lean_torque'``,
        ``'lateral_force:X,Z'``), never ``'steer_torque'`` (the rider's)."""
        data = bicycle._native.human_closed_loop(self.task, list(self.gains), self._neuro,
                                                 float(speed), [str(d) for d in disturbances])
        return HumanLoop(data, speed, self)

    def loops(self, bicycle: "Bicycle", speed: float) -> List[RiderLoop]:
        """Each of the task's loops at ``speed``, inner first (see :class:`RiderLoop`)."""
        out = []
        for d in bicycle._native.human_loops(self.task, list(self.gains), self._neuro,
                                             float(speed)):
            c = d["crossovers"]
            out.append(RiderLoop(
                d["loop"], d["gain"],
                LoopTransferFunction(np.asarray(d["open_numerator"])[::-1].copy(),
                                     np.asarray(d["open_denominator"])[::-1].copy()),
                LoopTransferFunction(np.asarray(d["closed_numerator"])[::-1].copy(),
                                     np.asarray(d["closed_denominator"])[::-1].copy()),
                np.asarray([x[0] for x in c], dtype=np.float64),
                np.asarray([(x[1], x[2]) for x in c], dtype=np.float64).reshape(-1, 2)))
        return out

    def __repr__(self) -> str:
        gains = ", ".join(f"{n}={g:g}" for n, g in zip(GAIN_NAMES, self.gains))
        return (f"HumanController({self.task!r}, {gains}, ω={self.neuro_frequency:g} rad/s, "
                f"ζ={self.neuro_damping:g})")


def hess_gains(bicycle: "Bicycle", speed: float, *, neuro_frequency: float = 30.0,
               neuro_damping: float = 0.707, steer_damping: float = STEER_DAMPING,
               roll_rate_damping: float = ROLL_RATE_DAMPING,
               crossovers: Sequence[float] = CROSSOVERS) -> np.ndarray:
    """The five gains (kDelta, kPhiDot, kPhi, kPsi, kY) by Hess 2012's rules at ``speed``: k_δ
    and k_φ̇ put a closed-loop pair at damping ``steer_damping`` and ``roll_rate_damping``,
    k_φ, k_ψ, k_y put the open loops' crossovers at ``crossovers`` [rad/s]. A rule no gain
    meets is a :class:`whipple.WhippleError` naming the gain."""
    c = [float(x) for x in crossovers]
    if len(c) != 3:
        raise ArgumentError(f"crossovers: three frequencies (phi, psi, y loops), got {len(c)}",
                            field="crossovers", value=crossovers, rule="three values")
    return np.asarray(bicycle._native.hess_gains(
        float(speed), (float(neuro_frequency), float(neuro_damping)),
        (float(steer_damping), float(roll_rate_damping), (c[0], c[1], c[2]))))


class HumanEigen(NamedTuple):
    """The ridden bicycle's eigenvalues against speed: ``speeds`` (n,), ``gains`` (n, 5) used
    at each, ``extrapolated`` (n,) whether a table's gains were extrapolated there,
    ``eigenvalues`` (n, states) sorted by decreasing real part at each speed (not tracked)."""

    speeds: np.ndarray
    gains: np.ndarray
    extrapolated: np.ndarray
    eigenvalues: np.ndarray


def human_eigenvalues(bicycle: "Bicycle", task: str, speeds: Any, gains: Any = None, *,
                      table: Optional[GainTable] = None, rules: bool = False,
                      neuro_frequency: float = 30.0,
                      neuro_damping: float = 0.707) -> HumanEigen:
    """The closed loop's eigenvalues at each of ``speeds`` [m/s] with fixed ``gains``, the
    gains of ``table`` (interpolated; an :class:`ExtrapolationWarning` if any speed lies
    outside it) or, with ``rules=True``, Hess 2012's rules at each speed."""
    v = [float(x) for x in np.asarray(speeds, dtype=np.float64).reshape(-1)]
    given = sum(x is not None and x is not False for x in (gains, table, rules or None))
    if given != 1:
        raise ArgumentError("give exactly one of gains, table or rules=True", field="gains",
                            value=None, rule="one source of gains")
    kwargs: dict = {}
    if gains is not None:
        kwargs["gains"] = _gains(gains)
    elif table is not None:
        kwargs["table"] = ([float(x) for x in table.speeds], table.gains.tolist())
    else:
        kwargs["rules"] = (STEER_DAMPING, ROLL_RATE_DAMPING, CROSSOVERS)
    d = bicycle._native.human_eigen_sweep(str(task), (float(neuro_frequency),
                                                      float(neuro_damping)), v, **kwargs)
    extrapolated = np.asarray(d["extrapolated"], dtype=bool)
    if extrapolated.any():
        warnings.warn(f"{int(extrapolated.sum())} of {len(v)} speeds lie outside the gain "
                      "table: their gains are extrapolated", ExtrapolationWarning, stacklevel=2)
    return HumanEigen(d["speeds"], d["gains"], extrapolated, d["eigenvalues"])


__all__ = ["HumanController", "HumanLoop", "RiderLoop", "LoopTransferFunction", "GainTable",
           "GainLookup", "read_gains", "hess_gains", "human_eigenvalues", "HumanEigen",
           "ExtrapolationWarning", "GAIN_NAMES"]
