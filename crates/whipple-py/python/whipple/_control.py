"""Time responses, feedback and controllability of the linear bicycle, and the linear model
beside the non-linear one through a manoeuvre: ``whipple.TimeResponse``, ``whipple.Lqr``,
``whipple.Controllability``, ``whipple.ClosedLoop``, ``whipple.ManoeuvreComparison``. Every
number is computed by the Rust library; this module reads the arguments and names the
results."""

from __future__ import annotations

from typing import (TYPE_CHECKING, Any, Callable, Dict, List, NamedTuple, Optional, Sequence,
                    Tuple, Union)

import numpy as np

from ._errors import ArgumentError
from ._results import Eigen
from ._system import LinearSystem, Signal, SignalKey, _index, _names

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ._bicycle import Bicycle

#: An input signal: an array of values at the sample times, or (knots, values), piecewise
#: linear between the knots.
Torque = Union[Sequence[float], np.ndarray, Tuple[Sequence[float], Sequence[float]]]


def _times(t: Any, field: str = "t") -> np.ndarray:
    try:
        arr = np.asarray(t, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"{field}: give the sample times as numbers [s]", field=field,
                            value=None, rule="a 1-D array of increasing times") from error
    if arr.ndim != 1:
        raise ArgumentError(f"{field}: the sample times must be 1-D, got shape {arr.shape}",
                            field=field, value=None, rule="a 1-D array of increasing times")
    return np.ascontiguousarray(arr)


def _vector(x: Any, n: int, field: str) -> List[float]:
    try:
        arr = np.asarray(x, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"{field}: give {n} numbers", field=field, value=None,
                            rule=f"{n} numbers") from error
    if arr.size != n:
        raise ArgumentError(f"{field}: one value per state ({n}), got {arr.size}", field=field,
                            value=None, rule=f"{n} numbers")
    return [float(v) for v in arr]


def _matrix(m: Any, field: str) -> List[List[float]]:
    try:
        arr = np.asarray(m, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"{field}: give a matrix of numbers", field=field, value=None,
                            rule="a 2-D array") from error
    if arr.ndim != 2:
        raise ArgumentError(f"{field}: a 2-D matrix is needed, got shape {arr.shape}",
                            field=field, value=None, rule="a 2-D array")
    rows: List[List[float]] = arr.tolist()
    return rows


class GroundPath(NamedTuple):
    """Where the bicycle goes in the ground plane [m, rad]: the rear contact's ``rear_x`` (the
    nominal run v t added back) and ``rear_y``, the heading ``yaw`` ψ, and the front contact's
    ``front_y`` (None when the response has no such column)."""

    rear_x: np.ndarray
    rear_y: np.ndarray
    yaw: np.ndarray
    front_y: Optional[np.ndarray]


class TimeResponse:
    """A time response of a :class:`whipple.LinearSystem`: ``t`` [s], ``x`` (times × states)
    and ``y`` (times × outputs) as arrays, ``states`` and ``outputs`` the same columns in dicts
    by label (``response.states['lean']``), ``path`` the :class:`GroundPath` when the system's
    states hold yaw and the rear contact (request ``states=('yaw', 'rear_contact_x',
    'rear_contact_y')``), else None."""

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    states: Dict[str, np.ndarray]
    outputs: Dict[str, np.ndarray]
    path: Optional[GroundPath]

    def __init__(self, data: Dict[str, Any], system: LinearSystem) -> None:
        self.t = data["times"]
        self.x = data["states"]
        self.y = data["outputs"]
        self.states = {s.label: self.x[:, k] for k, s in enumerate(system.states)}
        self.outputs = {s.label: self.y[:, k] for k, s in enumerate(system.outputs)}
        path = data["path"]
        self.path = None if path is None else GroundPath(path["rear_x"], path["rear_y"],
                                                         path["yaw"], path["front_y"])
        self._system = system

    def state(self, key: SignalKey) -> np.ndarray:
        """One state's column, by label, name or index."""
        return self.x[:, _index(self._system.states, key, "state")]  # type: ignore[no-any-return]

    def output(self, key: SignalKey) -> np.ndarray:
        """One output's column, by label, name or index."""
        return self.y[:, _index(self._system.outputs, key, "output")]  # type: ignore[no-any-return]

    def __repr__(self) -> str:
        return (f"<TimeResponse {len(self.t)} times, {self.x.shape[1]} states, "
                f"{self.y.shape[1]} outputs>")


def simulate(system: LinearSystem, t: Any, u: Any = None, x0: Any = None,
             rtol: float = 1e-10, atol: float = 1e-12) -> TimeResponse:
    """See :meth:`whipple.LinearSystem.simulate`."""
    times = _times(t)
    n, m = len(system.states), len(system.inputs)
    initial = [0.0] * n if x0 is None else _vector(x0, n, "x0")
    native = system._native
    if callable(u):
        fn: Callable[[float], Any] = u

        def inputs(tt: float) -> List[float]:
            values = np.asarray(fn(tt), dtype=np.float64).reshape(-1)
            return [float(v) for v in values]

        return TimeResponse(native.response_to_function(initial, inputs, times.tolist(),
                                                        float(rtol), float(atol)), system)
    if u is None:
        values = np.zeros((len(times), m))
    else:
        try:
            values = np.asarray(u, dtype=np.float64)
        except (TypeError, ValueError) as error:
            raise ArgumentError("u: give an array of inputs or a function u(t)", field="u",
                                value=None, rule="len(t) × inputs numbers, or callable") from error
        if values.ndim == 1 and m == 1:
            values = values.reshape(-1, 1)
        if values.shape != (len(times), m):
            raise ArgumentError(f"u: one row per time and one column per input "
                                f"({len(times)} × {m}), got shape {values.shape}", field="u",
                                value=None, rule=f"shape ({len(times)}, {m})")
    return TimeResponse(native.response(initial, times.tolist(),
                                        [values[:, j].tolist() for j in range(m)],
                                        times.tolist()), system)


class Lqr(NamedTuple):
    """The linear–quadratic regulator: ``K`` (inputs × states; u = −K x minimises
    ∫ xᵀQx + uᵀRu dt), ``X`` the stabilizing solution of the continuous algebraic Riccati
    equation, ``poles`` the eigenvalues of A − B K [1/s], ``residual`` the equation's relative
    residual, ``newton_steps`` the Newton–Kleinman refinements taken."""

    K: np.ndarray
    X: np.ndarray
    poles: np.ndarray
    residual: float
    newton_steps: int


class Controllability(NamedTuple):
    """The Kalman matrix [B, AB, …, Aⁿ⁻¹B]: its ``singular_values``, numerical ``rank`` (those
    above ``tolerance``), ``condition`` (largest over smallest singular value) and the number of
    ``states``; ``full`` when rank = states."""

    singular_values: np.ndarray
    rank: int
    tolerance: float
    condition: float
    states: int

    @property
    def full(self) -> bool:
        """Whether every state is reachable (rank = states)."""
        return self.rank == self.states


class ModalControllability(NamedTuple):
    """Each mode's ``eigenvalue`` [1/s] and ``measure``: how strongly the input reaches it
    (0 when the mode is uncontrollable)."""

    eigenvalues: np.ndarray
    measures: np.ndarray


class UncontrollableSpeeds(NamedTuple):
    """The speeds [m/s] where ``input`` loses a mode (certified), the ``eigenvalues`` lost there,
    and ``everywhere`` when the input reaches some mode at no speed."""

    input: str
    speeds: np.ndarray
    eigenvalues: np.ndarray
    everywhere: bool


class ClosedLoop:
    """The bicycle with feedback u = r − K x: ``K`` constant (a matrix, inputs × states) or
    scheduled with speed (``speeds`` and one matrix per speed, interpolated linearly between
    them; a speed outside the schedule is an error). See :meth:`whipple.Bicycle.closed_loop`."""

    def __init__(self, bicycle: "Bicycle", gains: Any, inputs: List[str], states: List[str]
                 ) -> None:
        self._bicycle = bicycle
        self.inputs = inputs
        self.states = states
        #: Each design speed's Riccati residual for a loop from
        #: :meth:`whipple.Bicycle.lqr_schedule`; None otherwise.
        self.residuals: Optional[np.ndarray] = None
        if isinstance(gains, tuple) and len(gains) == 2:
            speeds, matrices = gains
            self.speeds: Optional[List[float]] = [float(v) for v in
                                                  np.asarray(speeds, dtype=np.float64).reshape(-1)]
            self._gains = [_matrix(k, "gains") for k in matrices]
        else:
            self.speeds = None
            self._gains = [_matrix(gains, "gains")]
        # Checked now, so that a bad K is reported where it is given.
        at = 0.0 if self.speeds is None else self.speeds[0]
        self.system(at)

    def system(self, speed: float, outputs: Optional[Sequence[str]] = None) -> LinearSystem:
        """The closed loop at ``speed`` [m/s] as a :class:`whipple.LinearSystem`: A − B K, B,
        C − D K, D (the inputs are now the references r). ``outputs`` by name as in
        :meth:`whipple.Bicycle.linear_system` (default: lean, steer and their rates); an
        input's name, such as ``'steer_torque'``, is the torque the loop applies, r − K x. Its
        ``transfer_function`` gives the closed loop's, exactly (gains on lean, steer and their
        rates only).

        >>> loop = Bicycle.preset("benchmark").closed_loop([[-100.0, 10.0, -20.0, 0.0]],
        ...                                                 inputs="steer_torque")
        >>> g = loop.system(5.0, ["lean", "steer_torque"]).transfer_function(
        ...     "steer_torque", "steer_torque")
        >>> bool(np.all(g.poles.real < 0))  # this loop is stable at 5 m/s
        True
        """
        names = None if outputs is None else _names(outputs, "outputs")
        native = self._bicycle._native.closed_loop_system(self.inputs, self.states, self._gains,
                                                          self.speeds, float(speed), names)
        return LinearSystem(native, self._bicycle)

    def eig(self, v: Any) -> Eigen:
        """The eigenvalues of A − B K at speeds ``v`` [m/s] as a :class:`whipple.Eigen`. With
        gains on lean, steer and their rates only: tracked over the speeds and labelled (weave,
        capsize, …) as :meth:`whipple.Bicycle.eig`; with gains on other states: each speed's
        eigenvalues by decreasing real part, ``modes`` None. ``vectors[i, :, j]`` is the
        eigenvector of ``values[i, j]``, unit length with its largest component real: on
        (φ, δ, φ̇, δ̇) for gains on those states, on every state of the loop otherwise."""
        arr = np.asarray(v, dtype=np.float64)
        scalar = arr.ndim == 0
        speeds = np.ascontiguousarray(arr.reshape(-1))
        values, vectors, modes = self._bicycle._native.closed_loop_eig(
            self.inputs, self.states, self._gains, self.speeds, speeds.tolist())
        return Eigen(speeds, values, vectors, modes, scalar, self._bicycle.label)

    def critical_speeds(self, lo: float = 0.0, hi: float = 10.0) -> Dict[str, Any]:
        """The closed loop's weave and capsize speeds and stable ranges in [lo, hi] m/s,
        certified (the library's closed-loop ``CriticalSpeeds`` as a dict: ``weave_speed``,
        ``capsize_speed``, ``stable_speed_ranges``, ``unresolved``, …). Gains on states other
        than lean, steer and their rates are an :class:`whipple.ArgumentError` naming
        ``gains``."""
        result: Dict[str, Any] = self._bicycle._native.closed_loop_critical_speeds(
            self.inputs, self.states, self._gains, self.speeds, float(lo), float(hi))
        return result

    def __repr__(self) -> str:
        kind = "constant" if self.speeds is None else f"scheduled on {len(self.speeds)} speeds"
        return f"<ClosedLoop {self._bicycle.label}, inputs {self.inputs}, gains {kind}>"


def _torque(value: Any, times: np.ndarray, field: str) -> Tuple[List[float], List[float]]:
    if isinstance(value, tuple) and len(value) == 2 and np.ndim(value[0]) == 1:
        knots, values = value
        return ([float(x) for x in np.asarray(knots, dtype=np.float64)],
                [float(x) for x in np.asarray(values, dtype=np.float64)])
    arr = np.asarray(value, dtype=np.float64)
    if arr.shape != times.shape:
        raise ArgumentError(f"{field}: give (knots, values) or one value per sample time "
                            f"({len(times)}), got shape {arr.shape}", field=field, value=None,
                            rule="(knots, values) or an array on t")
    return times.tolist(), arr.tolist()


class ManoeuvreComparison:
    """The linear and the non-linear model through one manoeuvre: ``t`` [s], and ``linear``,
    ``nonlinear`` and ``difference`` (non-linear minus linear), each a dict of arrays
    ``lean``, ``steer``, ``yaw`` [rad], ``rear_x``, ``rear_y``, ``front_y`` [m];
    ``nonlinear_steps`` the integrator's steps."""

    def __init__(self, data: Dict[str, Any], label: str, wheelbase: float) -> None:
        self.t: np.ndarray = data["times"]
        self.linear: Dict[str, np.ndarray] = data["linear"]
        self.nonlinear: Dict[str, np.ndarray] = data["nonlinear"]
        self.difference: Dict[str, np.ndarray] = data["difference"]
        self.nonlinear_steps: int = data["nonlinear_steps"]
        self.label = label
        self._wheelbase = wheelbase

    def plot_paths(self, ax: Optional["Axes"] = None) -> "Axes":
        """Both models' rear- and front-contact paths in the ground plane (x forward, y to the
        right drawn downward as seen from above), equal scales; the front contact is drawn at
        x = rear x + w cos ψ (its lateral position ``front_y`` as computed, the wheelbase w
        ahead to first order). Needs matplotlib
        (``whipple[plot]``). The axes."""
        from ._plot import _pyplot

        if ax is None:
            _, ax = _pyplot().subplots()
        assert ax is not None
        for name, motion, style in (("linear", self.linear, "-"),
                                    ("non-linear", self.nonlinear, "--")):
            ax.plot(motion["rear_x"], motion["rear_y"], style, label=f"{name}: rear contact")
            front_x = motion["rear_x"] + self._wheelbase * np.cos(motion["yaw"])
            ax.plot(front_x, motion["front_y"], style, alpha=0.6,
                    label=f"{name}: front contact")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.invert_yaxis()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(f"{self.label}: linear and non-linear paths")
        ax.legend()
        return ax

    def __repr__(self) -> str:
        return f"<ManoeuvreComparison {self.label}, {len(self.t)} times>"


def compare_manoeuvre(bicycle: "Bicycle", speed: float, t: Any, steer_torque: Any = None,
                      lean_torque: Any = None, lean0: float = 0.0, steer0: float = 0.0,
                      rtol: float = 1e-10) -> ManoeuvreComparison:
    """See :meth:`whipple.Bicycle.compare_manoeuvre`."""
    times = _times(t)
    torques = []
    for name, value in (("lean_torque", lean_torque), ("steer_torque", steer_torque)):
        if value is not None:
            knots, values = _torque(value, times, name)
            torques.append((name, knots, values))
    data = bicycle._native.compare_manoeuvre(float(speed), float(lean0), float(steer0), torques,
                                             times.tolist(), float(rtol))
    return ManoeuvreComparison(data, bicycle.label, float(bicycle.to_dict()["w"]))


__all__ = ["TimeResponse", "GroundPath", "Lqr", "Controllability", "ModalControllability",
           "UncontrollableSpeeds", "ClosedLoop", "ManoeuvreComparison", "Torque", "Signal"]
