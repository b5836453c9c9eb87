"""``whipple.Bicycle``: a checked bicycle and everything computed from it."""

from __future__ import annotations

import html
import math
import os
import warnings
from typing import (TYPE_CHECKING, Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple,
                    Union)

import numpy as np

from . import _whipple
from ._errors import (ArgumentError, LimitError, NoSteadyTurnError, ParameterError,
                      ParameterWarning, ParseError)
from ._results import Comparison, CriticalSpeeds, Eigen, Sensitivities, Simulation
from ._control import ClosedLoop, ManoeuvreComparison, UncontrollableSpeeds, compare_manoeuvre
from ._system import FrequencyResponse, LinearSystem, _names, _signals
from ._turns import SteadyTurn, Turns

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ._design import DesignMap

Torque = Union[None, float, str, Callable[[float, Dict[str, float]], float]]

#: The 26 benchmark keys (Meijaard 2007 Table 1 plus g), in the paper's order, with their
#: symbol, SI unit, meaning and whether the linear model depends on them.
BENCHMARK_KEYS: Tuple[str, ...] = tuple(row[0] for row in _whipple.parameter_table("benchmark"))


def _speeds(v: Any) -> Tuple[np.ndarray, bool]:
    """Speeds as a contiguous 1-D float array, and whether a scalar was given. A 2-D (or
    deeper) array is refused: flattened, its results would come back in a shape the caller
    did not give."""
    arr = np.asarray(v, dtype=np.float64)
    if arr.ndim > 1:
        from ._errors import ArgumentError

        raise ArgumentError(f"speeds must be a number or a 1-D array, got an array of shape {arr.shape}",
                            field="speeds", value=None,
                            rule="a number or a 1-D array (use .ravel() to flatten it yourself)")
    scalar = arr.ndim == 0
    return np.ascontiguousarray(arr.reshape(-1)), scalar


def _split(value: Any) -> Tuple[float, float]:
    """(value, sigma) of a float, an uncertainties ``ufloat``, a ``(value, sigma)`` pair or a
    ``{'value': …, 'sigma': …}`` mapping."""
    if hasattr(value, "nominal_value") and hasattr(value, "std_dev"):
        return float(value.nominal_value), float(value.std_dev)
    if isinstance(value, Mapping):
        return float(value["value"]), float(value.get("sigma", 0.0))
    if isinstance(value, (tuple, list)) and len(value) == 2:
        return float(value[0]), float(value[1])
    return float(value), 0.0


class Bicycle:
    """A bicycle of the Whipple model, checked: the 25 benchmark parameters of Meijaard et al.
    2007 (Proc. R. Soc. A 463:1955–1982, Table 1) plus gravity g, or JBike6's seven-body form
    converted to them. SI units and radians everywhere (``lam`` is the steer axis tilt λ in
    radians).

    Make one with :meth:`preset`, :meth:`from_file`, :meth:`from_dict` or
    :meth:`from_bicycleparameters`; change one with :meth:`replace`. A bicycle is immutable.
    Warnings about a measured bicycle's oddities (a tensor that breaks the triangle
    inequality, …) are issued as :class:`whipple.ParameterWarning` and kept in
    :attr:`notices`; ``strict=True`` refuses them.

    The linear model: :meth:`canonical` (M, C₁, K₀, K₂), :meth:`state_space` (A, B),
    :meth:`linear_system` (named inputs and outputs, transfer functions),
    :meth:`frequency_response` (many speeds at once), :meth:`eig`, :meth:`critical_speeds`, :meth:`sensitivities`. The non-linear model:
    :meth:`simulate`, :meth:`nonlinear_state_matrix`, :meth:`compare`, steady turns
    (:meth:`turn`, :meth:`turns`), :meth:`accelerations`. Figures: :meth:`plot_side_view`.
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_whipple.NativeBicycle") -> None:
        """Use the constructors (:meth:`preset`, :meth:`from_file`, :meth:`from_dict`)."""
        if not isinstance(native, _whipple.NativeBicycle):
            raise TypeError("use Bicycle.preset, Bicycle.from_file or Bicycle.from_dict")
        self._native = native

    @classmethod
    def _wrap(cls, native: "_whipple.NativeBicycle") -> "Bicycle":
        bike = cls(native)
        for notice in native.notices():
            if notice["severity"] == "warning":
                warnings.warn(f"{bike.label}: {notice['message']}", ParameterWarning, stacklevel=3)
        return bike

    # Constructors ----------------------------------------------------------------------------

    @classmethod
    def preset(cls, name: str) -> "Bicycle":
        """A named bicycle from the literature (``'benchmark'``: Meijaard 2007 Table 1;
        ``whipple.presets()`` lists them all with their sources)."""
        return cls._wrap(_whipple.NativeBicycle.preset(name))

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"], format: Optional[str] = None,
                  strict: bool = False) -> "Bicycle":
        """A bicycle from a parameter file, in every format the command line reads: TOML,
        JSON, JBike6's ``.m``, BicycleParameters' ``<Name>Benchmark.txt`` and YAML parameter
        sets, HumanControl's ``<Name>Par.txt``. The format follows from the extension and, for
        ``.txt``, the content, unless ``format`` names it (``'toml'``, ``'json'``, ``'m'``,
        ``'bp-txt'``, ``'hc-txt'``, ``'yaml'``)."""
        path = os.fspath(path)
        limit = _whipple.MAX_FILE_BYTES
        with open(path, "rb") as f:
            data = f.read(limit + 1)
        if len(data) > limit:
            # A file past the bound (or a device that never ends, /dev/zero) is not read whole.
            raise LimitError(f"{path}: longer than {limit >> 20} MiB, the most a parameter file "
                             "may hold (the field's files are a few kilobytes): is it the right "
                             "file?", field="path", value=path,
                             rule=f"a parameter file holds at most {limit} bytes")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as error:
            raise ParseError(f"{path}: the file is not UTF-8 text", field=None, value=None,
                             rule="a parameter file is UTF-8 text", format="unknown",
                             line=0, column=0) from error
        return cls._wrap(_whipple.NativeBicycle.parse(text, os.path.basename(path), format, strict))

    @classmethod
    def from_text(cls, text: str, format: str, strict: bool = False) -> "Bicycle":
        """A bicycle from the text of a parameter file in ``format`` (see :meth:`from_file`)."""
        return cls._wrap(_whipple.NativeBicycle.parse(text, "", format, strict))

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], name: Optional[str] = None,
                  source: Optional[str] = None, strict: bool = False) -> "Bicycle":
        """A benchmark-form bicycle from a mapping with BicycleParameters' keys (``'w'``,
        ``'c'``, ``'lam'``, ``'g'``, ``'rR'``, ``'mR'``, ``'IRxx'``, …; every one of the 26 is
        required, unknown keys are errors). A value is a float, an ``uncertainties`` ufloat, a
        ``(value, sigma)`` pair or ``{'value': …, 'sigma': …}``: the σ is propagated to the
        critical speeds. The same rules as a BicycleParameters ``.txt`` file apply (its optional
        ``yB``, ``IBxy``, ``IRzz``, … keys included). ``'IAlamlam'``, the front assembly's
        moment of inertia about the steer axis, may stand for ``'IHzz'``, which is then derived
        (see :meth:`front_assembly_steer_inertia`).

        Keys take their unit as a suffix, as TOML and JSON files do: ``_mm`` after a length
        (``'c_mm': 80``, ``'w_mm': 1020``, ``'rR_mm'``, ``'xB_mm'``, …) and ``_deg`` after an
        angle (``'lam_deg': 18``), the σ in the same unit; a suffix after a key of another
        quantity (``'IBxx_mm'``) or one key in two units (``'c'`` and ``'c_mm'``) raises
        :class:`ParameterError`. :meth:`to_dict` is SI."""
        items = []
        for key, value in d.items():
            try:
                v, s = _split(value)
            except (TypeError, ValueError, KeyError) as error:
                raise ParameterError(f"invalid parameter `{key}`: not a number ({value!r})",
                                     field=str(key), value=value, rule="must be a number") from error
            items.append((str(key), v, s))
        return cls._wrap(_whipple.NativeBicycle.from_items(items, name, source, strict))

    @classmethod
    def from_moore2012(cls, d: Mapping[str, Any], name: Optional[str] = None,
                       source: Optional[str] = None, strict: bool = False) -> "Bicycle":
        """A benchmark-form bicycle from Moore 2012's parameters (BicycleParameters'
        ``Moore2012`` keys: ``'rf'``, ``'rr'``, ``'d1'``, ``'d2'``, ``'d3'``, ``'l1'`` …
        ``'l4'``, ``'mc'``, ``'md'``, ``'me'``, ``'mf'``, ``'ic11'``, ``'ic22'``, ``'ic31'``,
        ``'ic33'``, ``'id11'``, ``'id22'``, ``'ie11'``, ``'ie22'``, ``'ie31'``, ``'ie33'``,
        ``'if11'``, ``'if22'``, ``'g'``; all required, ``'v'`` ignored, others refused), converted
        by the library: the inverse of :meth:`to_moore2012`. A Moore 2012 YAML set
        (``parameterization: Moore2012``) reads with :meth:`from_file` too."""
        items = [(str(k), float(v)) for k, v in d.items()]
        return cls._wrap(_whipple.NativeBicycle.from_moore2012(items, name, source, strict))

    @classmethod
    def from_bicycleparameters(cls, obj: Any, strict: bool = False) -> "Bicycle":
        """A bicycle from a BicycleParameters ``Bicycle`` (its ``parameters['Benchmark']``) or a
        ``ParameterSet`` of the benchmark parameterization (its ``parameters``), duck-typed:
        BicycleParameters is not imported. Uncertain values keep their σ."""
        name = None
        params = getattr(obj, "parameters", None)
        if isinstance(params, Mapping) and "Benchmark" in params:
            params = params["Benchmark"]
            name = getattr(obj, "bicycleName", None)
        elif isinstance(params, Mapping):
            parameterization = getattr(obj, "parameterization", "benchmark")
            # BicycleParameters calls the benchmark parameterization `Meijaard2007` in its
            # ParameterSet classes and `benchmark` in its YAML files.
            if str(parameterization).lower() not in ("benchmark", "meijaard2007"):
                raise ParameterError(
                    f"a {parameterization!r} parameter set: only the benchmark parameterization "
                    "is read (convert it with BicycleParameters first)",
                    field="parameterization", value=parameterization,
                    rule="must be 'benchmark' (Meijaard2007)")
            name = getattr(obj, "bicycleName", None) or getattr(obj, "name", None)
        elif isinstance(obj, Mapping):
            params = obj
        else:
            raise TypeError("expected a BicycleParameters Bicycle or ParameterSet (an object with "
                            "a `parameters` mapping)")
        return cls.from_dict(dict(params), name=name if isinstance(name, str) else None,
                             source="BicycleParameters", strict=strict)

    # The description ---------------------------------------------------------------------------

    @property
    def name(self) -> Optional[str]:
        """The bicycle's name (a preset's name, or the file's)."""
        return self._native.name

    @property
    def source(self) -> Optional[str]:
        """Where its numbers come from."""
        return self._native.source

    @property
    def label(self) -> str:
        return self.name or "bicycle"

    @property
    def form(self) -> str:
        """``'benchmark'`` or ``'jbike6'``: the form it was described in."""
        return self._native.form()

    @property
    def notices(self) -> List[Dict[str, Any]]:
        """Warnings and notes from reading and checking it (dicts: severity, field, message,
        violation_percent where one applies, affects: the server's and the command line's
        JSON keys)."""
        return self._native.notices()

    @property
    def extras(self) -> List[Dict[str, Any]]:
        """The file's keys that are not Whipple parameters (an operating speed ``v``, another
        model's ``xcl``, …): key, text, value, sigma, meaning."""
        return [dict(zip(("key", "text", "value", "sigma", "meaning"), e)) for e in self._native.extras()]

    @property
    def sigma(self) -> Dict[str, float]:
        """Standard deviations by key of the bicycle's own form (only those given)."""
        return self._native.sigma()

    def to_dict(self) -> Dict[str, float]:
        """The 26 benchmark parameters with BicycleParameters' keys, in the order of Meijaard 2007
        Table 1 (JBike6 bodies combined): ``Bicycle.from_dict(b.to_dict())`` gives the same
        numbers."""
        return dict(self._native.benchmark())

    def to_moore2012(self) -> Dict[str, float]:
        """Moore 2012's parameters (his dissertation, ch. 2; BicycleParameters' ``Moore2012``
        parameter set) with BicycleParameters' keys, computed by the library from the benchmark
        form: what ``Meijaard2007ParameterSet.to_parameterization('Moore2012')`` gives (less its
        redundant zero products and ``v``)."""
        return dict(self._native.moore2012())

    def front_assembly_steer_inertia(self) -> float:
        """The front assembly's (front frame and front wheel) moment of inertia about the steer
        axis, I_Aλλ [kg m²]: the number a torsional pendulum gives with the steer axis
        vertical. ``from_dict`` and the parameter files take it as ``IAlamlam`` instead of
        ``IHzz``, which is then derived (every other parameter kept)."""
        return self._native.front_assembly_steer_inertia()

    def jbike6_dict(self) -> Optional[Dict[str, float]]:
        """JBike6's own parameters (``.m`` names) where the bicycle was described that way."""
        return dict(self._native.own_form()) if self.form == "jbike6" else None

    def to_text(self, format: str = "toml") -> str:
        """The bicycle as parameter-file text (``'toml'``, ``'json'``, ``'m'``, ``'bp-txt'``,
        ``'hc-txt'``, ``'yaml'``); every number round-trips."""
        return self._native.write(format)

    def replace(self, **changes: float) -> "Bicycle":
        """A copy with parameters changed, by the names :meth:`design_map`'s axes take (the
        command line's ``--x``/``--y`` names): a key of the bicycle's form (``c``, ``mB``,
        ``lam``, ``rR``; JBike6 keys such as ``wheelbase`` or ``mrider`` and TOML paths such as
        ``rider.m`` for a JBike6-form bicycle), or an alias (``trail``, ``wheelbase``,
        ``head_angle``, ``steer_axis_tilt``, ``gravity``, ``wheel_radius``; ``wheel_diameter``),
        in SI units, or in degrees with ``_deg`` after an angle::

            bike.replace(trail=0.09, head_angle_deg=70.0, mB=90.0)

        The σ of the parameters changed are dropped, and the copy's name ends in
        ``(edited)``. A name the bicycle does not have raises :class:`ParameterError` listing
        the names it takes."""
        native = self._native.replace([(k, float(v)) for k, v in changes.items()])
        return type(self)._wrap(native)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Bicycle) and self._native == other._native

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        p = self.to_dict()
        return (f"Bicycle({self.label!r}, {self.form} form: w={p['w']:g} m, c={p['c']:g} m, "
                f"lam={p['lam']:g} rad, mB={p['mB']:g} kg)")

    def _repr_html_(self) -> str:
        sigma = self.sigma
        rows = []
        for key, symbol, unit, description, _linear in _whipple.parameter_table("benchmark"):
            value = self.to_dict()[key]
            s = sigma.get(key) if self.form == "benchmark" else None
            shown = f"{value:.6g}" + (f" ± {s:.3g}" if s else "")
            rows.append(f"<tr><td><code>{html.escape(key)}</code></td><td>{html.escape(symbol)}</td>"
                        f"<td style='text-align:right'>{shown}</td><td>{html.escape(unit)}</td>"
                        f"<td style='text-align:left'>{html.escape(description)}</td></tr>")
        caption = html.escape(self.label + (f" — {self.source}" if self.source else ""))
        return (f"<table><caption>{caption}</caption><tr><th>key</th><th>symbol</th><th>value</th>"
                f"<th>unit</th><th>meaning</th></tr>{''.join(rows)}</table>")

    # The linear model ---------------------------------------------------------------------------

    def canonical(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(M, C₁, K₀, K₂), each (2, 2), of M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f with q = [φ, δ]
        (Meijaard 2007, eq. 1 and Appendix A): M [kg m²], C₁ [kg m], K₀ [kg m], K₂ [kg]."""
        m, c1, k0, k2, _g = self._native.canonical()
        return m, c1, k0, k2

    def state_space(self, v: Any, parallel: bool = True) -> Tuple[np.ndarray, np.ndarray]:
        """A(v), B(v) of ẋ = A x + B u, x = [φ, δ, φ̇, δ̇], u = [T_φ, T_δ]. A scalar speed [m/s]
        gives A (4, 4) and B (4, 2); an array of n speeds gives (n, 4, 4) and (n, 4, 2), the
        shapes BicycleParameters uses. Computed in parallel with the GIL released."""
        speeds, scalar = _speeds(v)
        a, b = self._native.state_space(speeds, parallel)
        return (a[0], b[0]) if scalar else (a, b)

    def linear_system(self, speed: float,
                      inputs: Union[str, Sequence[str]] = ("lean_torque", "steer_torque"),
                      outputs: Union[str, Sequence[str]] = ("lean", "steer", "lean_rate",
                                                             "steer_rate"),
                      states: Union[str, Sequence[str]] = ()) -> LinearSystem:
        """The bicycle as a linear system ẋ = A x + B u, y = C x + D u at ``speed`` [m/s], with
        the signals named as the command line names them.

        ``inputs``: ``'lean_torque'`` [N m], ``'steer_torque'`` [N m], ``'lateral_force:X,Z'``
        [N] (a lateral force, right positive, at the point (X, Z) of the rear frame in metres,
        benchmark axes: z down, so negative above the ground). ``outputs``: any state
        (``'lean'``, ``'steer'``, ``'lean_rate'``, ``'steer_rate'``, ``'yaw'``,
        ``'rear_contact_x'``, ``'rear_contact_y'``, ``'rear_wheel_angle'``,
        ``'front_wheel_angle'``), ``'yaw_rate'``, ``'front_contact_y'``,
        ``'rear_contact_lateral_acceleration'``, ``'rear_frame_point_y:X,Z'`` and
        ``'front_frame_point_y:X,Z'`` (a point's lateral position). The ignorable coordinates an
        output needs (yaw and the rear contact's y for a lateral position) are added to the
        states; ``states`` asks for more. A bad name is a :class:`whipple.ArgumentError` naming
        ``inputs``, ``outputs`` or ``states``.

        >>> bike = Bicycle.preset("benchmark")
        >>> g = bike.linear_system(3.0, "steer_torque", "lean").transfer_function("lean", "steer_torque")
        >>> bool(g.rhp_zeros.size)  # counter-steering: the lean first goes the wrong way
        True
        """
        native = self._native.linear_system(float(speed), _names(inputs, "inputs"),
                                            _names(outputs, "outputs"), _names(states, "states"))
        return LinearSystem(native, self)

    def frequency_response(self, v: Any, omega: Any,
                           inputs: Union[str, Sequence[str]] = "steer_torque",
                           outputs: Union[str, Sequence[str]] = "lean",
                           parallel: bool = True) -> FrequencyResponse:
        """The frequency response G(iω) of each input–output pair (named as in
        :meth:`linear_system`) at the frequencies ``omega`` [rad/s] and the speeds ``v`` [m/s],
        many at once: the speeds are shared among the cores with the GIL released
        (``parallel``), the results' memory reserved first (:class:`MemoryError` when it cannot
        be) and Ctrl-C honoured. A scalar speed gives arrays of shape (outputs, inputs,
        frequencies), an array of n speeds (n, outputs, inputs, frequencies). Plot it with
        :meth:`FrequencyResponse.plot` (the speeds overlaid)."""
        speeds, scalar = _speeds(v)
        w = np.ascontiguousarray(np.asarray(omega, dtype=np.float64).reshape(-1))
        ins, outs = _names(inputs, "inputs"), _names(outputs, "outputs")
        g, reals = self._native.frequency_responses(speeds, w, ins, outs, parallel)
        system = self._native.linear_system(0.0, ins, outs, [])
        _, in_signals, out_signals = system.signals()
        if scalar:
            return FrequencyResponse(w, g[0], reals[0], _signals(in_signals),
                                     _signals(out_signals), label=self.label)
        return FrequencyResponse(w, g, reals, _signals(in_signals), _signals(out_signals),
                                 speeds=speeds, label=self.label)

    def closed_loop(self, gains: Any,
                    inputs: Union[str, Sequence[str]] = ("lean_torque", "steer_torque"),
                    states: Union[str, Sequence[str]] = ()) -> ClosedLoop:
        """The bicycle with feedback u = r − K x on ``inputs``: ``gains`` a matrix K (inputs ×
        states, the states φ, δ, φ̇, δ̇ then those of ``states``), or a schedule ``(speeds,
        [K₀, K₁, …])`` interpolated linearly in speed. A :class:`whipple.ClosedLoop` with
        ``eig(v)``, ``critical_speeds(lo, hi)`` and ``system(speed)``. A K of the wrong shape or
        with a value that is not finite, or schedule speeds not increasing, is an
        :class:`whipple.ArgumentError` naming ``gains`` or ``speeds``.

        >>> bike = Bicycle.preset("benchmark")
        >>> steer_into_fall = bike.closed_loop([[0, 0, 0, 0], [-20.0, 0, -2.0, 0]])
        >>> bool(steer_into_fall.eig(2.0).values.real.max() < 0)
        True
        """
        return ClosedLoop(self, gains, _names(inputs, "inputs"), _names(states, "states"))

    def lqr_schedule(self, speeds: Any, Q: Any, R: Any,
                     inputs: Union[str, Sequence[str]] = "steer_torque",
                     states: Union[str, Sequence[str]] = ()) -> ClosedLoop:
        """The LQR gain for weights ``Q`` and ``R`` at each of ``speeds`` [m/s] (strictly
        increasing, at least two), scheduled: a :class:`whipple.ClosedLoop` whose gains are
        interpolated linearly between those speeds (never extrapolated), so that
        ``critical_speeds(speeds[0], speeds[-1])`` certifies where the scheduled loop is stable
        between the design speeds too. Its ``residuals`` hold each speed's Riccati residual.
        Bad weights are :class:`whipple.ArgumentError` naming ``Q``, ``R`` or ``speeds``.

        >>> bike = Bicycle.preset("benchmark")
        >>> loop = bike.lqr_schedule([1.0, 2.0, 4.0, 8.0], np.eye(4), [[1.0]])
        >>> loop.critical_speeds(1.0, 8.0)["stable_speed_ranges"]
        [(1.0, 8.0)]
        """
        from ._control import _matrix

        names_in, names_states = _names(inputs, "inputs"), _names(states, "states")
        v = [float(x) for x in np.asarray(speeds, dtype=np.float64).reshape(-1)]
        gains, residuals = self._native.lqr_schedule(names_in, names_states, v,
                                                     _matrix(Q, "Q"), _matrix(R, "R"))
        loop = ClosedLoop(self, (v, gains), names_in, names_states)
        loop.residuals = np.asarray(residuals, dtype=np.float64)
        return loop

    def uncontrollable_speeds(self, input: str = "steer_torque") -> UncontrollableSpeeds:
        """The forward speeds [m/s] at which ``input`` loses a mode (the Kalman matrix drops
        rank), certified, with the eigenvalue lost at each: a
        :class:`whipple.UncontrollableSpeeds`."""
        speeds, values, everywhere = self._native.uncontrollable_speeds(input)
        return UncontrollableSpeeds(input, np.asarray(speeds, dtype=np.float64), values,
                                    bool(everywhere))

    def compare_manoeuvre(self, speed: float, t: Any, *, steer_torque: Any = None,
                          lean_torque: Any = None, lean0: float = 0.0, steer0: float = 0.0,
                          rtol: float = 1e-10) -> ManoeuvreComparison:
        """The linear model (exact) and the non-linear model (Dormand–Prince 5(4), relative
        tolerance ``rtol``, projected on the constraints) through the same manoeuvre from
        upright straight running at ``speed`` [m/s]: initial lean ``lean0`` and steer
        ``steer0`` [rad], torques [N m] given as ``(knots, values)`` (piecewise linear between
        the knots) or as one value per sample time ``t`` [s]. A
        :class:`whipple.ManoeuvreComparison` (both motions and their difference; its
        ``plot_paths()`` draws both paths in the ground plane). The difference grows as the
        cube of the amplitude: halving a torque divides it by about 8."""
        return compare_manoeuvre(self, speed, t, steer_torque, lean_torque, lean0, steer0, rtol)

    def origin_zero_speeds(self, input: str = "steer_torque", output: str = "lean") -> np.ndarray:
        """The speeds [m/s] at which a zero of ``input`` → ``output`` (lean or steer) passes
        through s = 0, certified; they come as ±v. For steer torque → lean the positive one is
        where the counter-steering (right-half-plane) zero leaves for the left half-plane."""
        return np.asarray(self._native.origin_zero_speeds(input, output), dtype=np.float64)

    def eig(self, v: Any, tracked: bool = True, parallel: bool = True) -> Eigen:
        """Eigenvalues [1/s] and eigenvectors of A(v) at speeds v [m/s]: ``values`` (n, 4)
        complex, ``vectors`` (n, 4, 4) complex with ``vectors[i, :, k]`` belonging to
        ``values[i, k]``. Tracked (the default): each column follows one mode over the speeds
        (sorted internally), labelled in ``modes`` (weave, weave, capsize, castering for the
        benchmark). ``parallel`` (from a few thousand speeds on): on every core with the GIL
        released, the tracking too (in chunks joined where they overlap); the same numbers, bit
        for bit, as ``parallel=False``. Unpacks as ``values, vectors = bike.eig(v)``."""
        speeds, scalar = _speeds(v)
        values, vectors, modes = self._native.eig(speeds, tracked, parallel)
        return Eigen(speeds, values, vectors, modes, scalar, self.label)

    def critical_speeds(self, lo: float = 0.0, hi: float = math.inf) -> CriticalSpeeds:
        """The double-root, weave and capsize speeds and every self-stable range in [lo, hi]
        m/s (by default all forward speeds), certified: found from the characteristic
        polynomial with root enclosures that cannot miss a root, polished to round-off. With
        σ where the bicycle's parameters carry uncertainties."""
        return CriticalSpeeds(self._native.critical_speeds(float(lo), float(hi)), self.label,
                              self._native.uncertain)

    def sensitivities(self, speed: Optional[float] = None, lo: float = 0.0,
                      hi: float = math.inf) -> Sensitivities:
        """Exact derivatives of v_w, v_c and the stable range's width with respect to every
        parameter of the bicycle's own form, with elasticities ∂ln v/∂ln p; at ``speed`` also
        those of the weave's and capsize's real parts."""
        return Sensitivities(self._native.sensitivities(speed, float(lo), float(hi)))

    def design_map(self, x: str, y: Optional[str] = None, *, lo: float = 0.0,
                   hi: float = math.inf, speed: Optional[float] = None,
                   double_root: bool = False,
                   band: Optional[Tuple[float, float]] = None) -> "DesignMap":
        """The critical speeds over a grid of designs around this bicycle (the command line's
        ``whipple map``): axes as ``'trail=-0.05:0.25:100'``, ``'head_angle_deg=60:85:100'``
        (any parameter of the bicycle's form or a derived one, ``speed``), critical speeds [m/s]
        read on [lo, hi] m/s, ``max_real`` [1/s] at ``speed`` [m/s]; ``double_root`` adds v_d.
        In parallel with the GIL released. ``band=(a, b)`` [m/s] asks, for every design, whether
        it is self-stable at every speed from a to b and by what margin (``stable_over``,
        ``band_margin_below``, ``band_margin_above``, ``band_margin``;
        ``plot(quantity='stable_over')``). Part of a map: :meth:`design_map_shard`."""
        from ._design import DesignMap, part

        # The whole map needs no coordinate columns (its designs are the grid in order).
        return DesignMap([part(self._native.design(
            x, y, lo=float(lo), hi=float(hi), speed=speed, double_root=double_root,
            shard_index=0, shard_count=1, coordinates=False,
            band=None if band is None else (float(band[0]), float(band[1]))))])

    def design_map_shard(self, x: str, y: Optional[str] = None, *, shard: Tuple[int, int],
                         lo: float = 0.0, hi: float = math.inf, speed: Optional[float] = None,
                         double_root: bool = False,
                         band: Optional[Tuple[float, float]] = None) -> Dict[str, Any]:
        """Part k of n of :meth:`design_map`'s map (``shard=(k, n)``, 0 ≤ k < n; the same other
        arguments and units): the columns of the designs ``start`` to ``start + count``
        (row-major) as a dict of arrays, with ``index``, ``ix``, ``iy``, ``x`` and ``y`` for
        each. ``whipple.DesignMap(parts)`` assembles the n parts into the map, bit for bit;
        :func:`whipple.design_map_dask` does it on a Dask cluster."""
        from ._design import part

        k, n = shard
        return part(self._native.design(
            x, y, lo=float(lo), hi=float(hi), speed=speed, double_root=double_root,
            shard_index=int(k), shard_count=int(n), coordinates=True,
            band=None if band is None else (float(band[0]), float(band[1]))))

    def __reduce__(self) -> Tuple[Callable[[str], "Bicycle"], Tuple[str]]:
        # Pickled as its TOML text (every number round-trips): for multiprocessing and Dask.
        return (_from_toml, (self.to_text("toml"),))

    # The non-linear model -----------------------------------------------------------------------

    def simulate(self, speed: float, duration: float = 10.0, *, lean: float = 0.0,
                 steer: float = 0.0, lean_rate: float = 0.0, steer_rate: float = 0.0,
                 integrator: str = "rk4", dt: Optional[float] = None,
                 rtol: Optional[float] = None, steer_torque: Torque = None,
                 lean_torque: Torque = None, fall_angle_deg: float = 60.0,
                 stop_on_lift_off: bool = True, max_steps: Optional[int] = None,
                 every: int = 1, poses: bool = False, from_turn: bool = False) -> Simulation:
        """Simulates the non-linear multibody bicycle (four rigid bodies, knife-edge wheels,
        projected onto the constraints after each step) from upright running at ``speed``
        [m/s] with initial ``lean``, ``steer`` [rad], ``lean_rate``, ``steer_rate`` [rad/s],
        for ``duration`` [s]. ``speed`` is the rear hub's forward speed (the rear wheel
        centre's velocity along the rear frame's heading: the model's own speed coordinate,
        the ``speed`` column of the result); in a turn it differs from the rear contact's speed
        that :meth:`turn` takes (``SteadyTurn.hub_speed`` gives one from the other).

        ``integrator``: ``'rk4'`` with step ``dt`` (default 1 ms) or ``'adaptive'``
        (Dormand–Prince 5(4)) with relative tolerance ``rtol`` (default 1e-8). Rider torques
        ``steer_torque`` T_δ and ``lean_torque`` T_φ [N m]: a number, an expression of ``t``,
        ``lean``, ``steer``, ``lean_rate``, ``steer_rate``, ``yaw``, ``speed`` (``'10*lean +
        20*lean_rate'``), or a callable ``f(t, state) -> float`` with ``state`` a dict of those
        names (called with the GIL held only around the call; an exception it raises ends the
        run and is raised here). The run stops when |lean| passes ``fall_angle_deg`` or a
        wheel's normal force turns negative (unless ``stop_on_lift_off=False``); those are
        outcomes, not errors. ``every=N`` keeps one sample in N steps (the first and the last
        always), for long runs: at most 1.5 million samples are kept. A step too coarse for the
        run raises :class:`whipple.ArgumentError` (``field`` ``'dt'`` or ``'rtol'``, the step to
        use in ``rule`` and ``suggested``), never an outcome: an RK4 ``dt`` with |λ|·dt beyond
        2.5 for the fastest mode λ of the upright linearized bicycle at ``speed``, or a run
        whose energy balance drifts by more than 1% (either integrator).

        ``from_turn=True`` starts on the held steady turn at ``speed`` (the rear contact's) and
        ``lean`` (:meth:`turn`), as ``whipple simulate --from-turn`` does: the turn's steer,
        pitch and every rate, the model's speed the turn's rear hub speed, and the steer torque
        held at the turn's unless ``steer_torque`` is given (``steer`` must stay 0);
        ``lean_rate`` and ``steer_rate`` perturb it. :class:`whipple.NoSteadyTurnError` when
        there is no such turn."""
        data = self._native.simulate(
            float(speed), float(duration), lean=float(lean), steer=float(steer),
            lean_rate=float(lean_rate), steer_rate=float(steer_rate), integrator=integrator,
            dt=dt, rtol=rtol, steer_torque=steer_torque, lean_torque=lean_torque,
            fall_angle_deg=float(fall_angle_deg), stop_on_lift_off=stop_on_lift_off,
            max_steps=max_steps, every=int(every), poses=poses, from_turn=bool(from_turn))
        return Simulation(data, self.label)

    def turn(self, speed: float, *, lean: Optional[float] = None, steer: Optional[float] = None,
             radius: Optional[float] = None) -> SteadyTurn:
        """The steady turn of the non-linear bicycle at ``speed`` (the rear contact's, m/s) with
        exactly one of ``lean`` or ``steer`` [rad, right positive] or ``radius`` [m, of the rear
        contact's circle, positive right, negative left] given, and the steer torque [N m] that
        holds it, with its stability (``whipple turn``). Found on the branch that grows out of
        straight running. The hands-free turns at a speed: :meth:`hands_free_turns`.

        :class:`whipple.NoSteadyTurnError` (``field`` the argument given) when there is no such
        turn, or when the ground would have to pull a wheel down (a negative normal force: the
        wheel lifts off, the message names it and the force); :class:`whipple.ArgumentError`
        for an unusable speed, lean, steer or radius (``radius`` at most 1e9 m in size)."""
        given = [name for name, x in (("lean", lean), ("steer", steer), ("radius", radius))
                 if x is not None]
        if len(given) != 1:
            raise ArgumentError("give exactly one of lean, steer, radius",
                                field="lean" if not given else given[1], value=None,
                                rule="exactly one of lean, steer, radius")
        try:
            data = self._native.held_turn(
                float(speed), lean=None if lean is None else float(lean),
                steer=None if steer is None else float(steer),
                radius=None if radius is None else float(radius))
        except NoSteadyTurnError as error:
            error.field = given[0]
            raise
        return SteadyTurn(data, self.label)

    def hands_free_turns(self, speed: float) -> List[SteadyTurn]:
        """Every hands-free steady turn (no steer torque) at ``speed`` (the rear contact's, m/s)
        on the families :meth:`turns` traces, leaning right and left, polished; an empty list
        where there is none. :class:`whipple.ArgumentError` for an unusable speed."""
        return [SteadyTurn(t, self.label) for t in self._native.hands_free_turns(float(speed))]

    def turns(self, max_speed: float = 20.0) -> Turns:
        """The families of hands-free steady turns up to ``max_speed`` [m/s] (``whipple
        turns``): the one that leaves straight running at the branch speed and those a grid
        scan of lean and steer finds (a family that crosses no grid line is missed), traced by
        pseudo-arclength continuation, each point with its stability. Leaning right; the left
        ones are their mirror images. In the library, with the GIL released (seconds)."""
        return Turns(self._native.turn_families(float(max_speed)), self, self.label)

    def accelerations(self, *, yaw: float = 0.0, lean: float, pitch: float, steer: float,
                      wheel_angles: Tuple[float, float] = (0.0, 0.0),
                      rear_contact: Tuple[float, float] = (0.0, 0.0),
                      hub_velocity: Tuple[float, float, float],
                      yaw_rate: float, lean_rate: float, pitch_rate: float, steer_rate: float,
                      wheel_rates: Tuple[float, float], lean_torque: float = 0.0,
                      steer_torque: float = 0.0) -> Dict[str, Any]:
        """The non-linear model's accelerations at one state, given by the rear frame's
        ``yaw``, ``lean`` and ``pitch``, the ``steer``, the wheels' ``wheel_angles`` relative to
        their frames [rad], the ``rear_contact`` point (x, y) [m], the rear hub's
        ``hub_velocity`` (world axes: x forward, y right, z down) [m/s], the rates of yaw, lean,
        pitch and steer and the wheels' ``wheel_rates`` relative to their frames [rad/s]; this
        model's signs (lean, steer, yaw right; pitch nose up). For checks against published
        equations of motion (Basu-Mandal et al. 2007, Table 1).

        A dict: ``hub_acceleration`` (3,) [m/s²], ``angle_accelerations`` (yaw, lean, pitch)
        (3,), ``steer_acceleration``, ``wheel_accelerations`` (2,) [rad/s²], ``hub_position``
        (3,) [m], and ``holonomic_residual``, ``velocity_residual``: how far the state is from
        the constraints (a pitch or velocity that does not fit them shows here, it is not
        corrected)."""
        return self._native.accelerations(
            [float(yaw), float(lean), float(pitch)], float(steer),
            [float(x) for x in wheel_angles], [float(x) for x in rear_contact],
            [float(x) for x in hub_velocity],
            [float(yaw_rate), float(lean_rate), float(pitch_rate)], float(steer_rate),
            [float(x) for x in wheel_rates], float(lean_torque), float(steer_torque))

    def side_view(self) -> Dict[str, Any]:
        """The side view's geometry (the library's ``side_view``; x forward from the rear
        contact, y up, metres): wheels, steer axis, trail, the stylized frame tubes
        (``frame_tubes``, a drawing aid), each body's centre of mass and inertia ellipse
        (``bodies``: ``part``, ``name``, ``mass``, ``centre``, ``ellipse`` as
        ``{'semi_axes': (a, b), 'angle': rad}`` or ``None``, ``is_wheel``, ``is_front``). The
        keys are the library's ``SideView``'s field names; points are ``(x, y)`` tuples."""
        return self._native.side_view()

    def plot_side_view(self, ax: Optional["Axes"] = None) -> "Axes":
        """The side view drawn to scale (the command line's side-view figure): ground, wheels,
        fork and steer axis with the trail, frame tubes, saddle and handlebar, every body's
        centre of mass with its inertia ellipse and the total centre of mass. Needs matplotlib;
        returns the axis."""
        from ._plot import plot_side_view

        return plot_side_view(self.side_view(), self.label, ax=ax)

    def nonlinear_state_matrix(self, v: Any, parallel: bool = True) -> np.ndarray:
        """The non-linear model's own A(v) about upright straight running, reduced to
        x = [φ, δ, φ̇, δ̇] and exact (dual numbers): (4, 4) for a scalar speed, (n, 4, 4) for n
        speeds. Equals :meth:`state_space`'s A to round-off: the benchmark check."""
        speeds, scalar = _speeds(v)
        a = self._native.nonlinear_state_matrix(speeds, parallel)
        return a[0] if scalar else a

    def compare(self, v: Any, methods: Tuple[str, ...] = ("ad", "fd")) -> Comparison:
        """``whipple validate``'s comparison of the non-linear model with the linear one at
        sorted speeds v [m/s], by the exact reduced linearization (``'ad'``), the study's
        central differences (``'fd'``) and/or exact full-state derivatives (``'ad_full'``)."""
        speeds, _ = _speeds(v)
        return Comparison(self._native.compare(speeds, list(methods)))


def presets() -> List[Dict[str, str]]:
    """The named bicycles: name, summary, source."""
    return [dict(zip(("name", "summary", "source"), p)) for p in _whipple.presets()]


def formats() -> List[Dict[str, str]]:
    """The parameter-file formats: name (as ``format=`` takes it) and description."""
    return [dict(zip(("name", "description"), f)) for f in _whipple.formats()]


def parameter_table(form: str = "benchmark") -> List[Dict[str, Any]]:
    """Every parameter of a form (``'benchmark'`` or ``'jbike6'``): key, symbol, unit,
    description, and whether the linear model depends on it."""
    return [dict(zip(("key", "symbol", "unit", "description", "linear"), p))
            for p in _whipple.parameter_table(form)]


def _from_toml(text: str) -> Bicycle:
    return Bicycle.from_text(text, "toml")
