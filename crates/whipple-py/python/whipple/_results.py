"""Result objects: critical speeds, eigenvalues over speed, simulations, sensitivities and the
non-linear/linear comparison. Each holds numpy arrays and plain values, prints readably, shows a
table in a notebook (``_repr_html_``) and, where it is a table, converts with ``to_pandas()``."""

from __future__ import annotations

import html
import math
from typing import TYPE_CHECKING, Any, Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

if TYPE_CHECKING:
    import pandas
    from matplotlib.axes import Axes


def _num(x: Optional[float], digits: int = 6) -> str:
    if x is None:
        return "none"
    if math.isinf(x):
        return "∞" if x > 0 else "−∞"
    return f"{x:.{digits}g}"


def _pm(x: Optional[float], s: Optional[float], unit: str = "m/s") -> str:
    if x is None:
        return "none in the range"
    if s is not None and s > 0:
        return f"{x:.6g} ± {s:.3g} {unit}"
    return f"{x:.6g} {unit}"


def _range_text(lo: float, hi: float) -> str:
    if math.isinf(hi):
        return f"above {lo:.6g} m/s (no upper end)"
    if math.isinf(lo):
        return f"below {hi:.6g} m/s (no lower end)"
    return f"{lo:.6g} to {hi:.6g} m/s"


def _html_table(rows: Sequence[Tuple[str, str]], caption: str = "") -> str:
    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(k)}</th><td style='text-align:left'>{html.escape(v)}</td></tr>"
        for k, v in rows
    )
    cap = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{cap}{body}</table>"


def _pandas() -> Any:
    try:
        import pandas
    except ImportError as error:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from error
    return pandas


def _end(x: Optional[float], open_end: float) -> float:
    """An end of a range as the core serializes it (``None`` for an infinite end, as in the
    server's JSON) as a number: ``open_end`` (``math.inf`` or ``-math.inf``) for ``None``."""
    return open_end if x is None else x


def _range(r: Sequence[Optional[float]]) -> Tuple[float, float]:
    """A serialized range ``[lo, hi]`` (``None`` for no end) with ``±math.inf`` for the open ends."""
    return (_end(r[0], -math.inf), _end(r[1], math.inf))


class CriticalSpeeds:
    """The certified critical speeds of the linearized bicycle in a speed range.

    Attributes (m/s unless said; ``None`` where no such speed lies in the range):

    - ``v_d``: the double-root speed, where two real eigenvalues meet and leave as the weave pair;
    - ``v_w``: the weave speed, where the weave pair crosses into the left half plane;
    - ``v_c``: the capsize speed, where the capsize eigenvalue becomes positive;
    - ``weave_frequency``: |Im λ| of the weave at v_w [rad/s];
    - ``stable_ranges``: every self-stable interval ``(lo, hi)``; ``hi = math.inf`` for a
      range without an upper end (it is written as such, never cut at the search's end);
    - ``v_d_sigma``, ``v_w_sigma``, ``v_c_sigma``, ``stable_ranges_sigma``: first-order
      standard deviations from the parameters' σ (exact derivatives), ``None`` for a bicycle
      without uncertainties;
    - ``crossings``: every speed where an eigenvalue crosses the imaginary axis (dicts);
    - ``unresolved``: intervals round-off could not classify (normally empty);
    - ``range``: the range searched.

    ``to_dict()`` gives the library's own record, keyed as the server's ``/api/speeds`` JSON and
    ``whipple speeds --format json`` (``weave_speed``, ``stable_speed_ranges``, …, and the σ as
    ``weave_speed_sigma``, …), an open end of a range ``None``.
    """

    #: attribute ← the library's key (the one place the paper's symbols meet the record's names).
    _NAMES = {
        "v_d": "double_root_speed",
        "double_root_eigenvalue": "double_root_eigenvalue",
        "v_w": "weave_speed",
        "weave_frequency": "weave_frequency",
        "v_c": "capsize_speed",
        "v_d_sigma": "double_root_speed_sigma",
        "v_w_sigma": "weave_speed_sigma",
        "v_c_sigma": "capsize_speed_sigma",
    }

    def __init__(self, data: Dict[str, Any], label: str = "", uncertain: bool = False) -> None:
        self._data = data
        self.label = label
        self.uncertain: bool = uncertain
        for name, key in self._NAMES.items():
            setattr(self, name, data[key])
        self.v_d: Optional[float]
        self.double_root_eigenvalue: Optional[float]
        self.v_w: Optional[float]
        self.weave_frequency: Optional[float]
        self.v_c: Optional[float]
        self.v_d_sigma: Optional[float]
        self.v_w_sigma: Optional[float]
        self.v_c_sigma: Optional[float]
        self.range: Tuple[float, float] = _range(data["range"])
        self.stable_ranges: List[Tuple[float, float]] = [_range(r) for r in data["stable_speed_ranges"]]
        self.stable_ranges_sigma: List[Tuple[Optional[float], Optional[float]]] = [
            tuple(r) for r in data["stable_speed_ranges_sigma"]  # type: ignore[misc]
        ]
        self.crossings: List[Dict[str, Any]] = data["crossings"]
        self.unresolved: List[Tuple[float, float]] = [_range(r) for r in data["unresolved"]]
        self.double_root_unavailable: Optional[str] = data.get("double_root_unavailable")

    def is_stable(self, speed: float) -> bool:
        """True when ``speed`` lies in a self-stable range."""
        return any(lo < speed < hi for lo, hi in self.stable_ranges)

    def to_dict(self) -> Dict[str, Any]:
        """The library's record as a plain dict, keyed as the server's JSON (``weave_speed``,
        ``stable_speed_ranges``, ``weave_speed_sigma``, …; an open end of a range ``None``,
        ``double_root_unavailable`` only where v_d could not be given)."""
        return dict(self._data)

    def _rows(self) -> List[Tuple[str, str]]:
        # Where the certificate could not decide, "none" or "at no speed" would contradict it.
        undecided = ", ".join(_range_text(lo, hi) for lo, hi in self.unresolved)

        def named(v: Optional[float], sigma: Optional[float]) -> str:
            if v is None and undecided:
                return f"none certified (undecided in {undecided})"
            return _pm(v, sigma)

        rows = [
            ("v_d (double root)", self.double_root_unavailable or named(self.v_d, self.v_d_sigma)),
            ("v_w (weave)", named(self.v_w, self.v_w_sigma)),
            ("v_c (capsize)", named(self.v_c, self.v_c_sigma)),
        ]
        if not self.stable_ranges:
            rows.append(("self-stable", f"undecided in {undecided}; at no other speed in the range"
                         if undecided else "at no speed in the range"))
        for k, (lo, hi) in enumerate(self.stable_ranges):
            text = _range_text(lo, hi)
            if k < len(self.stable_ranges_sigma):
                s_lo, s_hi = self.stable_ranges_sigma[k]
                ends = [f"{name} ± {s:.3g} m/s" for name, s in (("lower end", s_lo), ("upper end", s_hi))
                        if s is not None and s > 0]
                if ends:
                    text += " (" + ", ".join(ends) + ")"
            rows.append(("self-stable" if k == 0 else "", text))
        for lo, hi in self.unresolved:
            rows.append(("unresolved by round-off", _range_text(lo, hi)))
        return rows

    def __repr__(self) -> str:
        head = f"CriticalSpeeds({self.label})" if self.label else "CriticalSpeeds"
        lo, hi = self.range
        head += f" on {_num(lo)} to {_num(hi)} m/s"
        return head + "\n" + "\n".join(f"  {k:<24}{v}" for k, v in self._rows())

    def _repr_html_(self) -> str:
        return _html_table(self._rows(), f"critical speeds {self.label}".strip())


class Eigen:
    """Eigenvalues and eigenvectors of A(v) over speeds.

    - ``speeds``: (n,) [m/s];
    - ``values``: (n, 4) complex [1/s];
    - ``vectors``: (n, 4, 4) complex, ``vectors[i, :, k]`` is the eigenvector of ``values[i, k]``
      in the state x = [φ, δ, φ̇, δ̇] (unit length, largest component real and positive);
    - ``modes``: the column labels (``'weave'``, ``'weave'``, ``'capsize'``, ``'castering'`` for
      the benchmark bicycle), or ``None`` when the columns are not tracked.

    Unpacks as BicycleParameters' ``calc_eigen`` result: ``values, vectors = bike.eig(v)``.
    """

    def __init__(self, speeds: np.ndarray, values: np.ndarray, vectors: np.ndarray,
                 modes: Optional[List[str]], scalar: bool, label: str = "") -> None:
        self.speeds = speeds
        self.values = values
        self.vectors = vectors
        self.modes = modes
        #: The bicycle's name (the legend's entry when several bicycles share a figure).
        self.label = label
        self._scalar = scalar
        if scalar:
            self.values = values[0]
            self.vectors = vectors[0]
            self.speeds = speeds[0]

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter((self.values, self.vectors))

    def __len__(self) -> int:
        return 2

    def to_pandas(self) -> "pandas.DataFrame":
        """A DataFrame indexed by speed with columns ``re1, im1, …, re4, im4`` (the command
        line's ``eig`` CSV) and the modes in ``df.attrs['modes']``."""
        pd = _pandas()
        values = np.atleast_2d(self.values)
        data = {}
        for k in range(4):
            data[f"re{k + 1}"] = values[:, k].real
            data[f"im{k + 1}"] = values[:, k].imag
        df = pd.DataFrame(data, index=pd.Index(np.atleast_1d(self.speeds), name="v"))
        df.attrs["modes"] = self.modes
        return df

    def mode_shapes(self) -> Tuple[np.ndarray, np.ndarray]:
        """The lean and steer components of every eigenvector, normalized for comparison: each
        eigenvector ``vectors[i, :, k]`` is scaled so that the larger of its |φ| and |δ| is 1
        and its lean φ is real and non-negative (phase 0). Returns ``(lean, steer)``, each
        complex of the shape of ``values`` ((n, 4), or (4,) at one speed), dimensionless (lean
        and steer in radians per radian of the larger): ``abs(steer)`` is the steer amplitude
        and ``np.angle(steer)`` [rad] the phase of steer relative to lean. The native
        eigenvectors are used as they are; only this scale is applied."""
        vectors = np.asarray(self.vectors)
        lean = vectors[..., 0, :]
        steer = vectors[..., 1, :]
        largest = np.maximum(np.abs(lean), np.abs(steer))
        # Lean's phase is the reference; a mode without lean (|φ| = 0) keeps steer's phase.
        has_lean = np.abs(lean) > 0
        reference = np.where(has_lean, lean, steer)
        rotation = np.exp(-1j * np.angle(reference))
        scale = np.where(largest > 0, 1.0 / np.where(largest > 0, largest, 1.0), 0.0)
        # Lean rotated onto the positive real axis exactly (its imaginary part 0, not round-off).
        shown_lean = np.where(has_lean, np.abs(lean), lean * rotation) * scale + 0j
        return shown_lean, steer * rotation * scale

    def plot(self, ax: Optional["Axes"] = None, imaginary: bool = True, *,
             label: Optional[str] = None, title: Optional[str] = None,
             color: Optional[str] = None) -> "Axes":
        """Real parts and |imaginary| parts [1/s] against speed [m/s], as the command line's
        ``eig --plot``: one colour per mode, Re λ solid, |Im λ| dashed.

        With ``label`` (a bicycle's name) or ``color``, the figure is one of several bicycles
        overlaid on one ``ax``: this bicycle in one colour (``color``, else the next of the
        palette not yet used on ``ax``), one line style per mode (weave solid, capsize dashed,
        castering dotted), Re λ bold and |Im λ| thin; the legend names every bicycle drawn on
        ``ax`` and every mode. ``title`` sets the axis' title. Needs matplotlib
        (``pip install whipple[plot]``); returns the axis. :func:`whipple.plot_eigenvalues`
        draws several bicycles at once."""
        from ._plot import plot_eigen

        return plot_eigen(self, ax=ax, imaginary=imaginary, label=label, title=title,
                          color=color)

    def plot_vectors(self, axes: Any = None, *, title: Optional[str] = None) -> np.ndarray:
        """Mode shapes against speed [m/s], one column of axes per mode (weave, capsize,
        castering): above, the magnitudes |φ| and |δ| of the lean and steer components of the
        eigenvector normalized as :meth:`mode_shapes` does (the larger is 1); below, the phase
        of steer relative to lean [deg]. Of the weave's conjugate pair the eigenvalue with
        Im λ ≥ 0 is drawn (the other's phase is its negative). Needs the tracked modes (the
        default of ``Bicycle.eig``) and matplotlib; returns the (2, number of modes) array of
        axes. ``axes``: such an array to draw into."""
        from ._plot import plot_mode_shapes

        return plot_mode_shapes(self, axes=axes, title=title)

    def plot_phasors(self, speed: Optional[float] = None, axes: Optional[Sequence["Axes"]] = None,
                     *, title: Optional[str] = None) -> List["Axes"]:
        """The lean and steer components of each mode's eigenvector at one speed as arrows in
        the complex plane (normalized as :meth:`mode_shapes` does: the larger has length 1,
        lean points along the positive real axis), one axis per mode, the eigenvalue [1/s] in
        its title. ``speed`` [m/s]: the speed of these results nearest to it (``None``: the one
        speed of a scalar ``eig``). Needs matplotlib; returns the axes (one per mode)."""
        from ._plot import plot_phasors

        return plot_phasors(self, speed=speed, axes=axes, title=title)

    def __repr__(self) -> str:
        shape = np.shape(self.values)
        return f"Eigen(values {shape} complex, vectors {np.shape(self.vectors)} complex, modes={self.modes})"


class Simulation:
    """A simulation of the non-linear bicycle.

    ``columns`` maps every column of the command line's ``simulate --format csv`` (``t``,
    ``lean``, ``steer``, …, ``front_y``, in that order, ``csv_columns``) and the dependent
    coordinates ``pitch``, ``rear_wheel_angle``, ``front_wheel_angle`` to numpy arrays; each is
    also an attribute (``run.lean``). Radians, metres, seconds, newtons, joules. ``speed`` is
    the rear hub's forward speed [m/s] (the rear wheel centre's velocity along the rear frame's
    heading, as :meth:`Bicycle.simulate` takes it), not the rear contact's of
    :meth:`Bicycle.turn`.

    ``outcome`` is how the run ended, in words; ``outcome_kind`` a machine name (``completed``,
    ``fell``, ``wheel_lifted``, ``projection_failed``, ``non_finite_state``, ``step_limit``,
    ``stopped``, ``failed``); ``failed`` is true when the computation (not the bicycle) failed.
    With ``poses=True``: ``positions`` (n, 4, 3) and ``rotations`` (n, 4, 3, 3) of the bodies
    named in ``body_names`` (world axes, x forward, y right, z down) for animation.
    """

    def __init__(self, data: Dict[str, Any], label: str = "") -> None:
        self.label = label
        self.columns: Dict[str, np.ndarray] = data["columns"]
        self.csv_columns: List[str] = data["csv_columns"]
        self.outcome: str = data["outcome"]
        self.outcome_kind: str = data["outcome_kind"]
        self.outcome_t: Optional[float] = data["outcome_t"]
        self.failed: bool = data["failed"]
        self.caption: str = data["caption"]
        self.steps: int = data["steps"]
        self.rejected_steps: int = data["rejected_steps"]
        self.pulled_down_from_start: List[str] = data["pulled_down_from_start"]
        self.body_names: List[str] = data["body_names"]
        self.positions: Optional[np.ndarray] = data.get("positions")
        self.rotations: Optional[np.ndarray] = data.get("rotations")

    def __getattr__(self, name: str) -> np.ndarray:
        columns = self.__dict__.get("columns", {})
        if name in columns:
            return columns[name]
        raise AttributeError(name)

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self.columns))

    def __len__(self) -> int:
        return len(self.columns["t"])

    def to_pandas(self) -> "pandas.DataFrame":
        """The samples as a DataFrame (one column per array, ``t`` included), the outcome in
        ``df.attrs['outcome']``."""
        pd = _pandas()
        df = pd.DataFrame(self.columns)
        df.attrs["outcome"] = self.outcome
        return df

    def plot(self, ax: Optional[Sequence["Axes"]] = None) -> Tuple["Axes", "Axes"]:
        """Lean, steer and speed against time and the ground track, as the command line's
        ``simulate --plot``. Needs matplotlib."""
        from ._plot import plot_simulation

        return plot_simulation(self, ax=ax)

    def _rows(self) -> List[Tuple[str, str]]:
        t = self.columns["t"]
        end = f"{t[-1]:.6g} s" if len(t) else "none"
        return [
            ("outcome", self.outcome),
            ("samples", f"{len(t)} to t = {end}"),
            ("steps", f"{self.steps} accepted, {self.rejected_steps} rejected"),
        ]

    def __repr__(self) -> str:
        head = f"Simulation({self.label})" if self.label else "Simulation"
        return head + "\n" + "\n".join(f"  {k:<10}{v}" for k, v in self._rows())

    def _repr_html_(self) -> str:
        return _html_table(self._rows(), f"simulation {self.label}".strip())


class Sensitivities:
    """Exact sensitivities (dual numbers) of the critical speeds to every parameter of the
    bicycle's own form: columns ``key``, ``symbol``, ``unit``, ``value``, ``d_v_w``, ``d_v_c``,
    ``d_width`` (∂/∂p in m/s per unit of p), ``elasticity_v_w``, ``elasticity_v_c``,
    ``elasticity_width`` (∂ln v/∂ln p) and, at ``speed``, ``d_weave_real``, ``d_capsize_real``
    (∂ Re λ/∂p). NaN where a quantity does not exist (no capsize speed in the range, say).

    ``to_dict()`` gives the library's own record, keyed as the server's ``/api/sensitivity``
    JSON: ``form``, ``critical`` (the critical speeds' record), ``stable_range``, ``speed``,
    ``weave_real``, ``capsize_real`` and ``parameters``, one record per parameter (``key``, …,
    ``weave_speed``, ``capsize_speed``, ``stable_width``, ``weave_speed_elasticity``, …)."""

    #: column ← the key of a parameter's record (the one place the paper's symbols meet the
    #: record's names).
    _FIELDS = {
        "key": "key",
        "symbol": "symbol",
        "unit": "unit",
        "description": "description",
        "value": "value",
        "d_v_w": "weave_speed",
        "d_v_c": "capsize_speed",
        "d_width": "stable_width",
        "elasticity_v_w": "weave_speed_elasticity",
        "elasticity_v_c": "capsize_speed_elasticity",
        "elasticity_width": "stable_width_elasticity",
        "d_weave_real": "weave_real",
        "d_capsize_real": "capsize_real",
    }
    _COLUMNS = list(_FIELDS)
    _TEXT = ("key", "symbol", "unit", "description")

    # The columns, one entry per parameter (set from _FIELDS in __init__).
    key: List[str]
    symbol: List[str]
    unit: List[str]
    description: List[str]
    value: np.ndarray
    d_v_w: np.ndarray
    d_v_c: np.ndarray
    d_width: np.ndarray
    elasticity_v_w: np.ndarray
    elasticity_v_c: np.ndarray
    elasticity_width: np.ndarray
    d_weave_real: np.ndarray
    d_capsize_real: np.ndarray

    def __init__(self, data: Dict[str, Any]) -> None:
        self._data = data
        rows = data["parameters"]
        self._columns: Dict[str, Any] = {}
        for name, field in self._FIELDS.items():
            values = [row[field] for row in rows]
            column = values if name in self._TEXT else np.array(
                [np.nan if x is None else x for x in values], dtype=float)
            self._columns[name] = column
            setattr(self, name, column)
        self.form: str = data["form"]
        self.v_w: Optional[float] = data["critical"]["weave_speed"]
        self.v_c: Optional[float] = data["critical"]["capsize_speed"]
        stable = data["stable_range"]
        self.stable_range: Optional[Tuple[float, float]] = _range(stable) if stable is not None else None
        self.speed: Optional[float] = data["speed"]
        self.weave_real: Optional[float] = data["weave_real"]
        self.capsize_real: Optional[float] = data["capsize_real"]

    def __getitem__(self, key: str) -> Dict[str, Any]:
        """The row of one parameter (``s['c']``), in the columns' names."""
        keys = list(self._columns["key"])
        if key not in keys:
            raise KeyError(key)
        i = keys.index(key)
        return {name: self._columns[name][i] for name in self._COLUMNS}

    def to_dict(self) -> Dict[str, Any]:
        """The library's record as a plain dict, keyed as the server's JSON (see the class)."""
        return dict(self._data)

    def to_pandas(self) -> "pandas.DataFrame":
        """The table as a DataFrame indexed by parameter key."""
        pd = _pandas()
        return pd.DataFrame({n: self._columns[n] for n in self._COLUMNS}).set_index("key")

    def __repr__(self) -> str:
        lines = [f"Sensitivities ({self.form} form; v_w = {_num(self.v_w)} m/s, v_c = {_num(self.v_c)} m/s)",
                 f"  {'key':<12}{'dv_w/dp':>14}{'dv_c/dp':>14}{'elast. v_w':>12}{'elast. v_c':>12}"]
        for i, key in enumerate(self._columns["key"]):
            lines.append(
                f"  {key:<12}{self.d_v_w[i] + 0.0:>14.5g}{self.d_v_c[i] + 0.0:>14.5g}"
                f"{self.elasticity_v_w[i] + 0.0:>12.4g}{self.elasticity_v_c[i] + 0.0:>12.4g}"
            )
        return "\n".join(lines)


class Comparison:
    """The non-linear model's linearizations against the linear model over speeds (what
    ``whipple validate`` reports): ``speeds`` (n,), ``linear`` (n, 4) complex eigenvalues in the
    columns ``modes``, and per method (``'ad'``: exact reduced A(v); ``'fd'``: the study's
    central differences; ``'ad_full'``) a dict with ``eigenvalues`` (n, 4), ``max_abs_diff``
    (n,) [1/s] and, for ``'ad'``, ``matrix_rel_diff`` (n,) = max|A − A_lin| / max|A_lin|."""

    def __init__(self, data: Dict[str, Any]) -> None:
        self.speeds: np.ndarray = data["speeds"]
        self.linear: np.ndarray = data["linear"]
        self.modes: List[str] = data["modes"]
        self.methods: Dict[str, Dict[str, Any]] = {
            k: v for k, v in data.items() if k not in ("speeds", "linear", "modes")
        }

    def __getitem__(self, method: str) -> Dict[str, Any]:
        return self.methods[method]

    def __repr__(self) -> str:
        parts = [f"Comparison over {len(self.speeds)} speeds"]
        for name, m in self.methods.items():
            worst = float(np.max(m["max_abs_diff"])) if len(m["max_abs_diff"]) else float("nan")
            parts.append(f"  {name}: largest |λ − λ_linear| = {worst:.3g} 1/s ({m['description']})")
        return "\n".join(parts)
