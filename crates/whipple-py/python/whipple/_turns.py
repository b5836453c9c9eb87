"""Steady turns of the non-linear bicycle: one turn (held by a steer torque, or hands-free) with
its stability, and the families of hands-free turns over speed. Solved by the Rust library
(``whipple::analysis::turns``); radians, SI units, benchmark signs (lean, steer and yaw right
positive; radii positive for right turns)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

if TYPE_CHECKING:
    import pandas

from ._results import _html_table, _num


class WheelContact:
    """The ground's force on one wheel [N]: ``normal`` (up positive), ``longitudinal`` (along
    the wheel's rolling direction, forward positive), ``lateral`` (right positive), and
    ``friction_ratio`` = √(longitudinal² + lateral²) / normal, the friction coefficient the
    contact needs (``math.inf`` when the wheel would lift off)."""

    __slots__ = ("normal", "longitudinal", "lateral", "friction_ratio")

    def __init__(self, d: Dict[str, float]) -> None:
        self.normal: float = d["normal"]
        self.longitudinal: float = d["longitudinal"]
        self.lateral: float = d["lateral"]
        self.friction_ratio: float = d["friction_ratio"]

    def to_dict(self) -> Dict[str, float]:
        return {k: getattr(self, k) for k in self.__slots__}

    def __repr__(self) -> str:
        return (f"WheelContact(normal={self.normal:.6g} N, lateral={self.lateral:.6g} N, "
                f"longitudinal={self.longitudinal:.6g} N, friction_ratio={self.friction_ratio:.4g})")


class SteadyTurn:
    """One steady turn of the non-linear bicycle: constant lean, steer and pitch, no lean or
    steer rate, the steer torque ``steer_torque`` that holds it (zero for a hands-free turn).

    Attributes (radians, SI; ``None`` where a quantity does not exist):

    - ``speed``: v, the rear contact's speed [m/s]; ``hub_speed`` the rear hub's (the model's
      own speed coordinate);
    - ``lean`` φ, ``steer`` δ, ``pitch`` θ (rear frame) [rad];
    - ``steer_torque`` T_δ [N m];
    - ``yaw_rate`` ψ̇ [rad/s]; ``wheel_rates`` (rear, front) spin relative to their frames
      (negative rolling forward) [rad/s];
    - ``rear_radius``, ``front_radius``, ``mass_centre_radius`` [m] (positive right, ``None``
      running straight); ``centre`` (x, y) of the circles [m];
    - ``lateral_acceleration`` of the mass centre (right positive) [m/s²];
    - ``contact``: (rear, front) :class:`WheelContact`;
    - ``residuals``: the lean and steer accelerations and the forward speed's rate at the
      solution (``lean_acceleration``, ``steer_acceleration`` [rad/s²], ``speed_rate`` [m/s²]),
      all at round-off; ``iterations`` of Newton's last solve;
    - stability, from the exact Jacobian of the reduced equations: ``eigenvalues`` (the four
      that decide, largest real part first, complex [1/s]), ``family_eigenvalue`` (the fifth,
      zero up to round-off: along the curve of turns), ``max_real``, ``stable``; these are
      ``None`` and ``stability_error`` says why when stability could not be decided.
    """

    def __init__(self, data: Dict[str, Any], label: str = "") -> None:
        # The library's record, keyed as the server's /api/turn: `turn` (the turn's fields,
        # read by their own names), `stability` (None when not decided) and `stability_error`.
        self._data = data
        self.label = label
        turn = data["turn"]
        self.speed: float = turn["speed"]
        self.hub_speed: float = turn["hub_speed"]
        self.lean: float = turn["lean"]
        self.steer: float = turn["steer"]
        self.pitch: float = turn["pitch"]
        self.steer_torque: float = turn["steer_torque"]
        self.yaw_rate: float = turn["yaw_rate"]
        self.wheel_rates: Tuple[float, float] = tuple(turn["wheel_rates"])  # type: ignore[assignment]
        self.rear_radius: Optional[float] = turn["rear_radius"]
        self.front_radius: Optional[float] = turn["front_radius"]
        self.mass_centre_radius: Optional[float] = turn["mass_centre_radius"]
        self.centre: Optional[Tuple[float, float]] = (tuple(turn["centre"])  # type: ignore[assignment]
                                                      if turn["centre"] is not None else None)
        self.lateral_acceleration: float = turn["lateral_acceleration"]
        self.contact: Tuple[WheelContact, WheelContact] = tuple(  # type: ignore[assignment]
            WheelContact(c) for c in turn["contact"])
        self.residuals: Dict[str, float] = dict(turn["residuals"])
        self.iterations: int = turn["iterations"]
        stability = data["stability"]
        self.eigenvalues: Optional[np.ndarray] = None
        self.family_eigenvalue: Optional[float] = None
        self.max_real: Optional[float] = None
        self.stable: Optional[bool] = None
        if stability is not None:
            self.eigenvalues = np.array([complex(z["re"], z["im"]) for z in stability["eigenvalues"]],
                                        dtype=complex)
            self.family_eigenvalue = stability["family_eigenvalue"]
            self.max_real = stability["max_real"]
            self.stable = stability["stable"]
        self.stability_error: Optional[str] = data["stability_error"]

    @property
    def hands_free(self) -> bool:
        """True when no steer torque holds the turn."""
        return self.steer_torque == 0.0

    def to_dict(self) -> Dict[str, Any]:
        """The library's record as a plain dict, keyed as the server's ``/api/turn`` JSON:
        ``turn`` (``speed``, ``lean``, …, ``contact`` as two dicts, ``residuals``),
        ``stability`` (``eigenvalues`` as ``{'re', 'im'}`` dicts, ``family_eigenvalue``,
        ``max_real``, ``stable``; ``None`` when not decided) and ``stability_error``."""
        return dict(self._data)

    def _rows(self) -> List[Tuple[str, str]]:
        def deg(x: float) -> str:
            return f"{x:.6g} rad ({math.degrees(x):.4f}°)"

        def radius(r: Optional[float]) -> str:
            return "straight" if r is None else f"{r:.6g} m"

        rows = [
            ("speed (rear contact)", f"{self.speed:.6g} m/s (rear hub {self.hub_speed:.6g} m/s)"),
            ("lean φ", deg(self.lean)),
            ("steer δ", deg(self.steer)),
            ("steer torque T_δ", f"{self.steer_torque:.6g} N m" + (" (hands-free)" if self.hands_free else "")),
            ("pitch θ (rear frame)", deg(self.pitch)),
            ("radius rear contact", radius(self.rear_radius)),
            ("radius front contact", radius(self.front_radius)),
            ("radius mass centre", radius(self.mass_centre_radius)),
            ("yaw rate", f"{self.yaw_rate:.6g} rad/s"),
            ("lateral acceleration", f"{self.lateral_acceleration:.6g} m/s² (mass centre)"),
            ("wheel rates", f"rear {self.wheel_rates[0]:.6g} rad/s, front {self.wheel_rates[1]:.6g} rad/s"),
        ]
        for name, c in zip(("rear", "front"), self.contact):
            ratio = "lifts off" if math.isinf(c.friction_ratio) else f"{c.friction_ratio:.4g}"
            rows.append((f"{name} contact", f"normal {c.normal:.6g} N, lateral {c.lateral:.6g} N, "
                                            f"longitudinal {c.longitudinal:.6g} N, friction ratio {ratio}"))
        r = self.residuals
        rows.append(("residuals", f"lean {r['lean_acceleration']:.1e} rad/s², steer "
                                  f"{r['steer_acceleration']:.1e} rad/s², forward speed "
                                  f"{r['speed_rate']:.1e} m/s²"))
        if self.eigenvalues is not None:
            values = ", ".join(f"{z.real:.4f}" if z.imag == 0 else f"{z.real:.4f}{z.imag:+.4f}i"
                               for z in self.eigenvalues)
            rows.append(("stability", f"{'stable' if self.stable else 'unstable'} (eigenvalues "
                                      f"{values} 1/s)"))
        else:
            rows.append(("stability", f"not decided: {self.stability_error}"))
        return rows

    def __repr__(self) -> str:
        kind = "hands-free" if self.hands_free else "held"
        head = f"SteadyTurn({self.label}, {kind})" if self.label else f"SteadyTurn({kind})"
        return head + "\n" + "\n".join(f"  {k:<22}{v}" for k, v in self._rows())

    def _repr_html_(self) -> str:
        kind = "hands-free" if self.hands_free else "held"
        return _html_table(self._rows(), f"{kind} steady turn {self.label}".strip())


class TurnFamily:
    """One traced family of hands-free turns leaning right (its mirror image, (φ, δ) → (−φ, −δ),
    leans left), as arrays in order along the curve: ``speed`` (rear contact) and ``hub_speed``
    [m/s], ``lean``, ``steer``, ``pitch`` [rad], ``radius`` (rear contact, NaN running straight)
    and ``front_radius`` [m], ``yaw_rate`` [rad/s], ``lateral_acceleration`` [m/s²],
    ``stable`` (bool mask), ``decided`` (whether the stability was decided), ``max_real``
    [1/s]; ``end``: why the tracing stopped (``'fell'``, ``'max_speed'``, ``'standstill'``,
    ``'steer_half_turn'``, ``'closed'``, ``'max_points'``, ``'step_too_small'``,
    ``'straight'``)."""

    _ARRAYS = ("speed", "hub_speed", "lean", "steer", "pitch", "yaw_rate", "radius",
               "front_radius", "lateral_acceleration", "stable", "decided", "max_real")

    def __init__(self, data: Dict[str, Any]) -> None:
        for name in self._ARRAYS:
            setattr(self, name, data[name])
        self.end: str = data["end"]

    speed: np.ndarray
    hub_speed: np.ndarray
    lean: np.ndarray
    steer: np.ndarray
    pitch: np.ndarray
    yaw_rate: np.ndarray
    radius: np.ndarray
    front_radius: np.ndarray
    lateral_acceleration: np.ndarray
    stable: np.ndarray
    decided: np.ndarray
    max_real: np.ndarray

    def __len__(self) -> int:
        return len(self.speed)

    def stable_speeds(self) -> List[Tuple[float, float]]:
        """The stretches of the family where its turns are stable, as (lowest, highest) speed
        of consecutive stable traced points."""
        out: List[Tuple[float, float]] = []
        run: Optional[List[float]] = None
        for v, s in zip(self.speed, self.stable):
            if s:
                run = [min(run[0], v), max(run[1], v)] if run else [v, v]
            elif run:
                out.append((run[0], run[1]))
                run = None
        if run:
            out.append((run[0], run[1]))
        return out

    def to_pandas(self) -> "pandas.DataFrame":
        """The points as a DataFrame."""
        from ._results import _pandas

        df = _pandas().DataFrame({n: getattr(self, n) for n in self._ARRAYS})
        df.attrs["end"] = self.end
        return df

    def __repr__(self) -> str:
        if not len(self):
            return "TurnFamily(empty)"
        return (f"TurnFamily({len(self)} points, v {np.min(self.speed):.4g} to "
                f"{np.max(self.speed):.4g} m/s, ends: {self.end})")


class Turns:
    """The hands-free steady turns of a bicycle (what ``whipple turns`` traces): ``families``
    (a list of :class:`TurnFamily`, leaning right; the first leaves straight running), and
    where they branch from upright straight running: ``branch_speed`` [m/s] (the capsize speed
    of the linear model, reached from the non-linear one) and ``branch_steer_per_lean`` (δ/φ as
    φ → 0), ``None`` when no family branches off. ``max_speed``: the tracing's limit."""

    def __init__(self, data: Dict[str, Any], bicycle: Any = None, label: str = "") -> None:
        self.label = label
        self._bicycle = bicycle
        self.families: List[TurnFamily] = [TurnFamily(f) for f in data["families"]]
        branch = data["branch"]
        self.branch_speed: Optional[float] = branch["speed"] if branch else None
        self.branch_steer_per_lean: Optional[float] = branch["steer_per_lean"] if branch else None
        self.max_speed: float = data["max_speed"]

    def __len__(self) -> int:
        return len(self.families)

    def __iter__(self) -> Iterator[TurnFamily]:
        return iter(self.families)

    def __getitem__(self, k: int) -> TurnFamily:
        return self.families[k]

    def plot(self, ax: Any = None, held_speeds: Sequence[float] = (3.0, 5.0, 7.0),
             max_radius: float = 30.0) -> np.ndarray:
        """The figure of ``whipple turns --plot``: lean, steer and rear contact radius of every
        family against speed, stable parts bold, and the steer torque that holds a turn against
        its lateral acceleration at ``held_speeds`` (leans 0.5°…30°; none drawn when empty).
        ``ax``: four axes to draw into; returns them."""
        from ._plot import plot_turns

        return plot_turns(self, ax=ax, held_speeds=held_speeds, max_radius=max_radius)

    def _rows(self) -> List[Tuple[str, str]]:
        rows = [("branch from straight",
                 "none" if self.branch_speed is None else
                 f"v = {self.branch_speed:.10g} m/s, δ/φ = {self.branch_steer_per_lean:.6g}")]
        for i, f in enumerate(self.families):
            if not len(f):
                continue
            stretches = ", ".join(f"{a:.4g}–{b:.4g} m/s" for a, b in f.stable_speeds()) or "nowhere"
            rows.append((f"family {i + 1}", f"{len(f)} points, v {_num(float(np.min(f.speed)), 4)}"
                                            f"–{_num(float(np.max(f.speed)), 4)} m/s, ends {f.end}; "
                                            f"stable {stretches}"))
        return rows

    def __repr__(self) -> str:
        head = f"Turns({self.label})" if self.label else "Turns"
        return head + f": {len(self.families)} hands-free family(ies) leaning right\n" + \
            "\n".join(f"  {k:<22}{v}" for k, v in self._rows())

    def _repr_html_(self) -> str:
        return _html_table(self._rows(), f"hands-free turns {self.label}".strip())
