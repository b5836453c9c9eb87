"""The bicycle as a linear system: ``whipple.LinearSystem`` (A, B, C, D with named signals),
``whipple.TransferFunction`` (poles, zeros, gain, exactly from the polynomial matrix) and
``whipple.FrequencyResponse`` (G(iω) with magnitude and unwrapped phase, at one speed or many)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _whipple
from ._errors import ArgumentError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ._control import Controllability, Lqr, ModalControllability, TimeResponse

    from ._bicycle import Bicycle

#: A signal chosen by its label or name (``"lean"``), or by its index.
SignalKey = Union[str, int]


class Signal(NamedTuple):
    """A state, input or output of a :class:`LinearSystem`: ``name`` as typed (``'lean'``,
    ``'lateral_force'``), ``label`` telling points apart (``'lateral_force(x = 0.3 m, z = -1
    m)'``; the name otherwise), ``symbol`` (Meijaard 2007's where it has one) and SI ``unit``."""

    name: str
    label: str
    symbol: str
    unit: str

    def __str__(self) -> str:
        return self.label


def _signals(rows: Sequence[Tuple[str, str, str, str]]) -> Tuple[Signal, ...]:
    return tuple(Signal(*row) for row in rows)


def _index(signals: Sequence[Signal], key: SignalKey, field: str) -> int:
    """The index of the signal ``key`` names (its label, or its name when only one signal has
    it) or is; an :class:`whipple.ArgumentError` naming ``field`` otherwise."""
    if isinstance(key, (int, np.integer)) and not isinstance(key, bool):
        k = int(key)
        if not -len(signals) <= k < len(signals):
            raise ArgumentError(f"{field}: index {k} is out of range: the system has "
                                f"{len(signals)} {field}s", field=field, value=k,
                                rule=f"0 to {len(signals) - 1}")
        return k % len(signals)
    if isinstance(key, str):
        for k, s in enumerate(signals):
            if s.label == key:
                return k
        named = [k for k, s in enumerate(signals) if s.name == key]
        if len(named) == 1:
            return named[0]
        known = ", ".join(s.label for s in signals)
        rule = (f"{key!r} names several; use a label: {known}" if named
                else f"not one of this system's {field}s: {known}")
        raise ArgumentError(f"{field}: {rule}", field=field, value=key, rule=rule)
    raise ArgumentError(f"{field}: give a name or an index, got {type(key).__name__}",
                        field=field, value=key, rule="a name (str) or an index (int)")


def _frequencies(omega: Any) -> np.ndarray:
    arr = np.ascontiguousarray(np.asarray(omega, dtype=np.float64).reshape(-1))
    return arr


class FrequencyResponse:
    """G(iω) of every output–input pair on a grid of frequencies ``omega`` [rad/s], at one speed
    (``response`` of shape (outputs, inputs, frequencies)) or at several (``speeds`` given: a
    leading axis of speeds, (speeds, outputs, inputs, frequencies)).

    ``magnitude`` |G| and ``magnitude_db`` 20 log₁₀ |G| [dB], ``phase`` [rad] and ``phase_deg``
    [deg], unwrapped along the frequencies (each value within half a turn of the one before,
    the first the principal value), all computed by the library. The units are the output's per
    the input's (``outputs``, ``inputs``)."""

    omega: np.ndarray
    response: np.ndarray
    magnitude: np.ndarray
    magnitude_db: np.ndarray
    phase: np.ndarray
    inputs: Tuple[Signal, ...]
    outputs: Tuple[Signal, ...]
    speeds: Optional[np.ndarray]

    def __init__(self, omega: np.ndarray, response: np.ndarray, reals: np.ndarray,
                 inputs: Tuple[Signal, ...], outputs: Tuple[Signal, ...],
                 speeds: Optional[np.ndarray] = None, label: str = "") -> None:
        self.omega = omega
        self.response = response
        # reals: |G|, dB and phase along the axis before the pairs.
        self.magnitude = reals[..., 0, :, :, :]
        self.magnitude_db = reals[..., 1, :, :, :]
        self.phase = reals[..., 2, :, :, :]
        self.inputs = inputs
        self.outputs = outputs
        self.speeds = speeds
        self.label = label

    @property
    def phase_deg(self) -> np.ndarray:
        """The unwrapped phase in degrees."""
        return np.degrees(self.phase)

    @property
    def hz(self) -> np.ndarray:
        """The frequencies in Hz (ω / 2π)."""
        return self.omega / (2 * np.pi)

    def pair(self, output: SignalKey = 0, input: SignalKey = 0) -> Tuple[int, int]:
        """The indices of an output and an input given by name or index."""
        return _index(self.outputs, output, "output"), _index(self.inputs, input, "input")

    def plot(self, output: SignalKey = 0, input: SignalKey = 0, *, axes: Any = None,
             hz: bool = False, title: Optional[str] = None) -> "Figure":
        """A Bode plot of one pair (magnitude [dB] above, phase [deg] below, a logarithmic
        frequency axis), one line per speed with a legend of speeds. Needs matplotlib
        (``whipple[plot]``). The figure."""
        from ._plot import plot_bode

        return plot_bode(self, output, input, axes=axes, hz=hz, title=title)

    def __repr__(self) -> str:
        at = (f"{len(self.speeds)} speeds" if self.speeds is not None else "one speed")
        return (f"<FrequencyResponse {self.label} {at}, {len(self.outputs)} outputs × "
                f"{len(self.inputs)} inputs × {len(self.omega)} frequencies>")


class TransferFunction:
    """G(s) = numerator(s) / denominator(s) of one input–output pair, formed exactly from the
    polynomial matrix M s² + v C₁ s + g K₀ + v² K₂ and its adjugate (not from a numerical
    state-space realization); for a closed loop (:meth:`whipple.ClosedLoop.system`), from the
    closed loop's, M s² + (v C₁ + F K_rate) s + g K₀ + v² K₂ + F K_angle. ``numerator`` and ``denominator`` hold the coefficients highest
    power first (as ``numpy.polyval`` and ``scipy.signal`` take them); the denominator is
    s^k det P(s) with ``integrators`` k (yaw 1, lateral positions 2).

    ``poles``: the certified eigenvalues of the lean–steer dynamics (decreasing real part), then
    k poles at 0; ``zeros``: the numerator's roots (decreasing real part; a zero with positive
    real part makes the pair non-minimum-phase, as steer torque → lean below the
    counter-steering speed); ``gain`` K in G = K Π(s − zᵢ) / Π(s − pᵢ); ``static_gain`` G(0),
    None with an integrator."""

    numerator: np.ndarray
    denominator: np.ndarray
    poles: np.ndarray
    zeros: np.ndarray
    gain: float
    static_gain: Optional[float]
    integrators: int

    def __init__(self, data: dict, system: "LinearSystem", output: int, input: int) -> None:
        self.numerator = np.asarray(data["numerator"])[::-1].copy()
        self.denominator = np.asarray(data["denominator"])[::-1].copy()
        self.poles = data["poles"]
        self.zeros = data["zeros"]
        self.gain = float(data["gain"])
        self.static_gain = data["static_gain"]
        self.integrators = int(data["integrators"])
        self.output = system.outputs[output]
        self.input = system.inputs[input]
        self.speed = system.speed
        self._system = system
        self._pair = (output, input)

    @property
    def rhp_zeros(self) -> np.ndarray:
        """The zeros in the right half-plane (real part > 0)."""
        return self.zeros[self.zeros.real > 0]

    def frequency_response(self, omega: Any) -> FrequencyResponse:
        """G(iω) of this pair at the frequencies ``omega`` [rad/s] (shape (1, 1, n))."""
        full = self._system._native.frequency_response(_frequencies(omega))
        o, i = self._pair
        g, reals = full
        return FrequencyResponse(_frequencies(omega), g[o:o + 1, i:i + 1],
                                 reals[:, o:o + 1, i:i + 1], (self.input,), (self.output,),
                                 label=self._system.label)

    def to_scipy(self) -> Any:
        """``scipy.signal.TransferFunction`` of the same polynomials (``whipple[scipy]``)."""
        signal = _import("scipy.signal", "scipy", "scipy")
        return signal.TransferFunction(self.numerator, self.denominator)

    def __repr__(self) -> str:
        return (f"<TransferFunction {self.input.label} → {self.output.label} at "
                f"{self.speed:g} m/s: {len(self.zeros)} zeros, {len(self.poles)} poles, "
                f"gain {self.gain:.6g}>")


def _import(module: str, package: str, extra: str) -> Any:
    """``module``, imported on first use; missing, an ImportError naming the package and the
    extra that installs it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as error:
        raise ImportError(f"this needs {package}, an optional dependency of whipple: "
                          f"pip install 'whipple[{extra}]' (or pip install {package})") from error


class LinearSystem:
    """The bicycle as a linear system ẋ = A x + B u, y = C x + D u at one forward ``speed``
    [m/s] about upright straight running (:meth:`whipple.Bicycle.linear_system`). States: lean
    φ, steer δ, their rates, then the ignorable coordinates asked for or needed by an output
    (yaw ψ, the rear contact's x and y, the wheels' angles); ``states``, ``inputs`` and
    ``outputs`` are :class:`Signal` s with their SI units. A, B, C, D are numpy arrays.

    Carry on in your own tools with :meth:`to_scipy` or :meth:`to_control`."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    states: Tuple[Signal, ...]
    inputs: Tuple[Signal, ...]
    outputs: Tuple[Signal, ...]

    def __init__(self, native: Any, bicycle: "Bicycle") -> None:
        self._native = native
        self._bicycle = bicycle
        self.A, self.B, self.C, self.D = native.matrices()
        for m in (self.A, self.B, self.C, self.D):
            m.flags.writeable = False
        states, inputs, outputs = native.signals()
        self.states = _signals(states)
        self.inputs = _signals(inputs)
        self.outputs = _signals(outputs)

    @property
    def speed(self) -> float:
        """The forward speed [m/s]."""
        return float(self._native.speed)

    @property
    def label(self) -> str:
        """The bicycle's label."""
        return self._bicycle.label

    def poles(self) -> np.ndarray:
        """The eigenvalues of A [1/s]: the four of the lean–steer dynamics (certified, by
        decreasing real part) and one zero for each ignorable coordinate among the states."""
        values = self._bicycle.eig(self.speed, tracked=False).values
        return np.concatenate([np.asarray(values).reshape(-1),
                               np.zeros(len(self.states) - 4, dtype=complex)])

    def transfer_function(self, output: SignalKey = 0, input: SignalKey = 0) -> TransferFunction:
        """The transfer function from ``input`` to ``output``, each by label, name or index."""
        o = _index(self.outputs, output, "output")
        i = _index(self.inputs, input, "input")
        return TransferFunction(self._native.transfer_function(o, i), self, o, i)

    def frequency_response(self, omega: Any) -> FrequencyResponse:
        """G(iω) of every pair at the frequencies ``omega`` [rad/s] (any finite values; the
        phase is unwrapped along them): ``response`` (outputs, inputs, frequencies) complex,
        with ``magnitude``, ``magnitude_db`` and ``phase`` (``phase_deg``). A frequency that is
        not finite, or a pole (ω = 0 with an integrator), is an :class:`whipple.ArgumentError`
        naming ``frequencies``."""
        w = _frequencies(omega)
        g, reals = self._native.frequency_response(w)
        return FrequencyResponse(w, g, reals, self.inputs, self.outputs, label=self.label)

    def simulate(self, t: Any, u: Any = None, x0: Any = None, *, rtol: float = 1e-10,
                 atol: float = 1e-12) -> "TimeResponse":
        """The response sampled at times ``t`` [s] (increasing, from t[0] ≥ 0; the state is
        ``x0`` at t = 0, zero by default) to the inputs ``u``:

        - None: every input zero;
        - an array of shape (len(t), inputs) (or (len(t),) with one input): the inputs at the
          sample times, taken as piecewise linear between them, and the response computed
          exactly (matrix exponentials, no time step; as ``scipy.signal.lsim`` with
          ``interp=True``);
        - a callable ``u(t)`` returning the inputs at t: integrated by Dormand–Prince 5(4) with
          ``rtol``/``atol`` (an exception it raises propagates).

        A :class:`whipple.TimeResponse`. Bad shapes, times that are not increasing, values that
        are not finite are :class:`whipple.ArgumentError` s naming ``t``, ``u``, ``x0``
        (``initial state``) or ``times``.

        >>> import whipple
        >>> system = whipple.Bicycle.preset("benchmark").linear_system(5.0)
        >>> r = system.simulate([0.0, 1.0, 2.0], x0=[0.0, 0.0, 0.5, 0.0])
        >>> bool(abs(r.states["lean"][-1]) < 0.1)
        True
        """
        from ._control import simulate

        return simulate(self, t, u, x0, rtol, atol)

    def step(self, input: SignalKey, t: Any) -> "TimeResponse":
        """From rest, a unit step of ``input`` (label, name or index) at t = 0, sampled at
        ``t`` [s]; where the system is stable the outputs settle at G(0)."""
        from ._control import TimeResponse, _times

        i = _index(self.inputs, input, "input")
        return TimeResponse(self._native.step_response(i, _times(t).tolist()), self)

    def impulse(self, input: SignalKey, t: Any) -> "TimeResponse":
        """A unit impulse of ``input`` at t = 0 (the free response from x(0⁺) = B eᵢ), sampled
        at ``t`` [s]: the derivative of :meth:`step`."""
        from ._control import TimeResponse, _times

        i = _index(self.inputs, input, "input")
        return TimeResponse(self._native.impulse_response(i, _times(t).tolist()), self)

    def initial(self, x0: Any, t: Any) -> "TimeResponse":
        """The free response (inputs zero) from the state ``x0`` at t = 0, sampled at ``t``."""
        from ._control import TimeResponse, _times, _vector

        x = _vector(x0, len(self.states), "x0")
        return TimeResponse(self._native.initial_response(x, _times(t).tolist()), self)

    def lqr(self, Q: Any, R: Any) -> "Lqr":
        """The linear–quadratic regulator for ∫ xᵀQx + uᵀRu dt: Q (states × states) symmetric
        positive semi-definite, R (inputs × inputs) symmetric positive definite. Solves the
        continuous algebraic Riccati equation (stable invariant subspace of the Hamiltonian,
        refined by Newton–Kleinman) and gives a :class:`whipple.Lqr` (K, X, poles, residual).
        Bad weights, or a pair (A, B) that cannot be stabilized, are errors naming ``Q``,
        ``R`` or the system."""
        from ._control import Lqr, _matrix

        k, x, poles, residual, steps = self._native.lqr(_matrix(Q, "Q"), _matrix(R, "R"))
        return Lqr(k, x, poles, float(residual), int(steps))

    def place_poles(self, poles: Any) -> np.ndarray:
        """K (1 × states) with the eigenvalues of A − B K at ``poles`` [1/s] (one per state,
        complex ones in conjugate pairs), for a system with one input (Ackermann's formula with
        its checks). An :class:`whipple.ArgumentError` otherwise."""
        p = np.asarray(poles, dtype=complex).reshape(-1)
        k: np.ndarray = self._native.place_poles([(float(z.real), float(z.imag)) for z in p])
        return k

    def controllability(self, input: Optional[SignalKey] = None) -> "Controllability":
        """The Kalman controllability matrix's singular values and numerical rank, for one
        input (label, name or index) or all of them (None): a
        :class:`whipple.Controllability`."""
        from ._control import Controllability

        i = None if input is None else _index(self.inputs, input, "input")
        d = self._native.controllability(i)
        return Controllability(d["singular_values"], int(d["rank"]), float(d["tolerance"]),
                               float(d["condition"]), int(d["states"]))

    def modal_controllability(self, input: SignalKey = 0) -> "ModalControllability":
        """How strongly ``input`` reaches each mode: the eigenvalues of A and, for each, a
        measure that is zero when that mode is uncontrollable from this input."""
        from ._control import ModalControllability

        values, measures = self._native.modal_controllability(
            _index(self.inputs, input, "input"))
        return ModalControllability(values, measures)

    def to_scipy(self) -> Any:
        """``scipy.signal.StateSpace(A, B, C, D)`` (needs scipy: ``whipple[scipy]``)."""
        signal = _import("scipy.signal", "scipy", "scipy")
        return signal.StateSpace(self.A, self.B, self.C, self.D)

    def to_control(self) -> Any:
        """python-control's ``ss(A, B, C, D)`` with the states', inputs' and outputs' labels as
        its signal names (needs python-control: ``whipple[control]``)."""
        control = _import("control", "control", "control")
        return control.ss(self.A, self.B, self.C, self.D,
                          states=[s.label for s in self.states],
                          inputs=[s.label for s in self.inputs],
                          outputs=[s.label for s in self.outputs],
                          name=f"{self.label} at {self.speed:g} m/s")

    def __repr__(self) -> str:
        names = lambda signals: ", ".join(s.label for s in signals)  # noqa: E731
        return (f"<LinearSystem {self.label} at {self.speed:g} m/s: states [{names(self.states)}], "
                f"inputs [{names(self.inputs)}], outputs [{names(self.outputs)}]>")


def _names(signals: Union[str, Sequence[str]], field: str) -> List[str]:
    if isinstance(signals, str):
        return [signals]
    names = list(signals)
    if not all(isinstance(s, str) for s in names):
        raise ArgumentError(f"{field}: give names (str), e.g. 'steer_torque'", field=field,
                            value=None, rule="a name or a sequence of names")
    return names


__all__ = ["LinearSystem", "TransferFunction", "FrequencyResponse", "Signal"]
