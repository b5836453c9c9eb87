"""Figures with matplotlib (the optional extra ``whipple[plot]``), in the look of the command
line's: eigenvalues against speed, a simulation's lean, steer, speed and ground track, the
steady-turn families, the side view, and design maps."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, List, Optional, Sequence, Tuple

import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ._bicycle import Bicycle

# The command line's colours per mode (whipple-report).
_MODE_COLOURS = {"weave": "#1f77b4", "capsize": "#d62728", "castering": "#2ca02c"}


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as error:  # pragma: no cover - depends on the environment
        raise ImportError("plots need matplotlib: pip install ./crates/whipple-py[plot]") from error
    return plt


#: Line styles per mode where several bicycles share one figure (colour then names the bicycle).
_MODE_STYLES = {"weave": "-", "capsize": "--", "castering": ":"}


def _mode_names(eigen: Any) -> List[str]:
    return list(eigen.modes) if eigen.modes else [f"eigenvalue {k + 1}" for k in range(4)]


def plot_eigen(eigen: Any, ax=None, imaginary: bool = True, label: Optional[str] = None,
               title: Optional[str] = None, color: Optional[str] = None):
    """Re λ and |Im λ| [1/s] against speed [m/s]. Alone: one colour per mode, Re solid, |Im|
    dashed. With ``label`` or ``color``: one bicycle among several on ``ax`` (its colour, a
    line style per mode, Re bold, |Im| thin) and a legend of bicycles and modes. The axis."""
    plt = _pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
    v = np.atleast_1d(eigen.speeds)
    values = np.atleast_2d(eigen.values)
    modes = _mode_names(eigen)
    overlay = label is not None or color is not None
    if overlay:
        _plot_eigen_overlaid(ax, v, values, modes, imaginary, label, color)
    else:
        shown = set()
        for k in range(values.shape[1]):
            colour = _MODE_COLOURS.get(modes[k], None)
            name = None if modes[k] in shown else f"{modes[k]} Re λ"
            shown.add(modes[k])
            ax.plot(v, values[:, k].real, color=colour, lw=1.6, label=name)
            if imaginary and np.any(values[:, k].imag > 0):
                ax.plot(v, np.abs(values[:, k].imag), color=colour, lw=1.0, ls="--",
                        label=f"{modes[k]} |Im λ|")
        ax.legend(loc="best", fontsize="small")
    if not any(line.get_gid() == "whipple-zero" for line in ax.lines):
        ax.axhline(0.0, color="0.3", lw=0.8, gid="whipple-zero")
    ax.set_xlabel("speed v [m/s]")
    ax.set_ylabel("eigenvalue λ [1/s]")
    ax.grid(True, color="0.9")
    if title is not None:
        ax.set_title(title)
    return ax


def _plot_eigen_overlaid(ax, v, values, modes, imaginary, label, color):
    """One bicycle's eigenvalues on an axis shared with others; the legend lists the bicycles
    (by colour) and then the modes (by line style), from gid-tagged entries without data."""
    bicycles = [line for line in ax.lines if line.get_gid() == "whipple-bicycle"]
    if color is None:
        used = {line.get_color() for line in bicycles}
        free = [c for c in _CYCLE if c not in used]
        color = free[0] if free else _CYCLE[len(bicycles) % len(_CYCLE)]
    drew_imaginary = False
    for k in range(values.shape[1]):
        style = _MODE_STYLES.get(modes[k], "-.")
        ax.plot(v, values[:, k].real, color=color, ls=style, lw=1.8)
        if imaginary and np.any(values[:, k].imag > 0):
            ax.plot(v, np.abs(values[:, k].imag), color=color, ls=style, lw=0.8, alpha=0.7)
            drew_imaginary = True
    ax.plot([], [], color=color, lw=1.8, label=label or f"bicycle {len(bicycles) + 1}",
            gid="whipple-bicycle")
    named = {line.get_label() for line in ax.lines if line.get_gid() == "whipple-mode"}
    for mode in dict.fromkeys(modes):
        if mode not in named:
            ax.plot([], [], color=_DARK, ls=_MODE_STYLES.get(mode, "-."), lw=1.8, label=mode,
                    gid="whipple-mode")
    if drew_imaginary and not any(line.get_gid() == "whipple-imaginary" for line in ax.lines):
        ax.plot([], [], color=_DARK, lw=0.8, alpha=0.7, label="thin: |Im λ|",
                gid="whipple-imaginary")
    order = {"whipple-bicycle": 0, "whipple-mode": 1, "whipple-imaginary": 2}
    entries = sorted((line for line in ax.lines if line.get_gid() in order),
                     key=lambda line: order[line.get_gid()])
    ax.legend(entries, [line.get_label() for line in entries], loc="best", fontsize="small")


def plot_eigenvalues(bicycles: Sequence["Bicycle"], speeds: Any, ax: Optional["Axes"] = None,
                     *, labels: Optional[Sequence[str]] = None, imaginary: bool = True,
                     title: Optional[str] = None) -> "Axes":
    """The eigenvalues [1/s] of several bicycles against speed [m/s] in one figure, to compare
    them (as BicycleParameters' ``compare_bicycles``): one colour per bicycle, one line style
    per mode (weave solid, capsize dashed, castering dotted), Re λ bold and |Im λ| thin, a
    legend naming the bicycles (``labels``, else their names) and the modes. Needs
    matplotlib; returns the axis."""
    plt = _pyplot()
    bicycles = list(bicycles)
    if labels is not None and len(labels) != len(bicycles):
        from ._errors import ArgumentError

        raise ArgumentError(f"{len(labels)} labels for {len(bicycles)} bicycles",
                            field="labels", value=None, rule="one label per bicycle")
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5.5), constrained_layout=True)
    for i, bike in enumerate(bicycles):
        name = labels[i] if labels is not None else bike.label
        bike.eig(speeds).plot(ax=ax, imaginary=imaginary, label=name)
    ax.set_title(title if title is not None else
                 "eigenvalues against speed: " + ", ".join(
                     labels if labels is not None else [b.label for b in bicycles]))
    return ax


def _shown_columns(eigen: Any) -> Tuple[List[str], np.ndarray]:
    """The modes (each once, in column order) and, per speed and mode, the column drawn: of
    columns sharing a label (the weave's pair) the one with the larger Im λ, or where both are
    real the larger Re λ. ``(modes, columns)`` with ``columns`` (n, len(modes)) int."""
    values = np.atleast_2d(eigen.values)
    names = _mode_names(eigen)
    modes = list(dict.fromkeys(names))
    picked = np.empty((values.shape[0], len(modes)), dtype=int)
    for j, mode in enumerate(modes):
        cols = np.array([k for k, name in enumerate(names) if name == mode])
        sub = values[:, cols]
        real = np.all(sub.imag == sub.imag[:, :1], axis=1)
        best = np.where(real, np.argmax(sub.real, axis=1), np.argmax(sub.imag, axis=1))
        picked[:, j] = cols[best]
    return modes, picked


def plot_mode_shapes(eigen: Any, axes=None, title: Optional[str] = None):
    """Magnitude of the normalized lean and steer components and the phase of steer relative
    to lean [deg] against speed [m/s], one column per mode; the (2, modes) axes."""
    plt = _pyplot()
    if eigen.modes is None:
        from ._errors import ArgumentError

        raise ArgumentError("mode shapes need the tracked modes: compute them with eig(v) "
                            "(tracked=True, the default)", field="tracked", value=False,
                            rule="tracked=True")
    v = np.atleast_1d(eigen.speeds)
    lean, steer = eigen.mode_shapes()
    lean, steer = np.atleast_2d(lean), np.atleast_2d(steer)
    modes, picked = _shown_columns(eigen)
    if axes is None:
        fig, axes = plt.subplots(2, len(modes), figsize=(4.2 * len(modes), 6.5), sharex=True,
                                 squeeze=False, constrained_layout=True)
        fig.suptitle(title if title is not None else
                     f"{eigen.label or 'bicycle'}: mode shapes against speed")
    rows = np.arange(len(v))
    for j, mode in enumerate(modes):
        top, bottom = axes[0][j], axes[1][j]
        phi = lean[rows, picked[:, j]]
        delta = steer[rows, picked[:, j]]
        colour = _MODE_COLOURS.get(mode, _DARK)
        top.plot(v, np.abs(phi), color=colour, lw=1.8, label="lean |φ|")
        top.plot(v, np.abs(delta), color=colour, lw=1.4, ls="--", label="steer |δ|")
        top.set_ylim(0.0, 1.05)
        top.set_title(mode)
        top.set_ylabel("magnitude (larger = 1)")
        top.grid(True, color="0.9")
        top.legend(loc="best", fontsize="small")
        bottom.plot(v, np.degrees(np.angle(delta)), color=colour, lw=1.4, ls="--",
                    label="steer δ relative to lean φ")
        bottom.set_ylim(-185.0, 185.0)
        bottom.set_yticks([-180, -90, 0, 90, 180])
        bottom.set_xlabel("speed v [m/s]")
        bottom.set_ylabel("phase of δ relative to φ [deg]")
        bottom.grid(True, color="0.9")
    return axes


def plot_phasors(eigen: Any, speed: Optional[float] = None, axes=None,
                 title: Optional[str] = None):
    """Each mode's normalized lean and steer components at one speed as arrows in the complex
    plane, one axis per mode; the axes."""
    plt = _pyplot()
    from ._errors import ArgumentError

    if eigen.modes is None:
        raise ArgumentError("phasors need the tracked modes: compute them with eig(v) "
                            "(tracked=True, the default)", field="tracked", value=False,
                            rule="tracked=True")
    v = np.atleast_1d(eigen.speeds)
    if speed is None:
        if len(v) != 1:
            raise ArgumentError(f"these eigenvalues are at {len(v)} speeds: name the one to "
                                "draw (plot_phasors(speed))", field="speed", value=None,
                                rule="a speed [m/s] when the results hold several")
        i = 0
    else:
        if not np.isfinite(speed):
            raise ArgumentError(f"speed must be finite, got {speed!r}", field="speed",
                                value=speed, rule="a finite speed [m/s]")
        i = int(np.argmin(np.abs(v - float(speed))))
    values = np.atleast_2d(eigen.values)
    lean, steer = eigen.mode_shapes()
    lean, steer = np.atleast_2d(lean), np.atleast_2d(steer)
    modes, picked = _shown_columns(eigen)
    if axes is None:
        fig, axes = plt.subplots(1, len(modes), figsize=(3.8 * len(modes), 4.2), squeeze=False,
                                 constrained_layout=True)
        axes = list(axes[0])
        fig.suptitle(title if title is not None else
                     f"{eigen.label or 'bicycle'}: eigenvectors at v = {v[i]:.4g} m/s")
    else:
        axes = list(axes)
    circle = np.exp(1j * np.linspace(0.0, 2.0 * np.pi, 181))
    for j, mode in enumerate(modes):
        ax = axes[j]
        k = picked[i, j]
        ax.plot(circle.real, circle.imag, color="0.8", lw=0.8)
        for z, name, colour in ((lean[i, k], "lean φ", _CYCLE[0]),
                                (steer[i, k], "steer δ", _CYCLE[1])):
            ax.annotate("", xy=(z.real, z.imag), xytext=(0.0, 0.0),
                        arrowprops=dict(arrowstyle="-|>", color=colour, lw=2.0,
                                        shrinkA=0, shrinkB=0))
            ax.plot([z.real], [z.imag], "o", color=colour, ms=4, label=name)
        lam = values[i, k]
        shown = (f"{lam.real:.3g}" if lam.imag == 0 else
                 f"{lam.real:.3g} {'+' if lam.imag > 0 else '−'} {abs(lam.imag):.3g}j")
        ax.set_title(f"{mode}: λ = {shown} 1/s", fontsize="medium")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.axvline(0.0, color="0.6", lw=0.6)
        ax.set_xlim(-1.15, 1.15)
        ax.set_ylim(-1.15, 1.15)
        ax.set_aspect("equal")
        ax.set_xlabel("real part")
        ax.set_ylabel("imaginary part")
        ax.legend(loc="lower left", fontsize="small")
    return axes


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


# The command line's colour cycle (whipple-report's Okabe–Ito palette).
_CYCLE = ["#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#282828"]
_DARK = "#282828"
_GREY = "#6e6e6e"


def _runs(mask):
    """(start, stop, value) of the runs of equal values of a boolean mask, each run extended
    by one point into the next so the pieces join."""
    out = []
    start = 0
    n = len(mask)
    for i in range(1, n + 1):
        if i == n or bool(mask[i]) != bool(mask[start]):
            out.append((start, min(i + 1, n), bool(mask[start])))
            start = i
    return out


def _bold_where(ax, x, y, stable, colour, label=None):
    """A curve drawn bold where ``stable``, thin elsewhere (``whipple turns --plot``); its
    legend entry a line of middle width."""
    for a, b, s in _runs(stable):
        ax.plot(x[a:b], y[a:b], color=colour, lw=3.2 if s else 1.0, solid_capstyle="butt")
    if label:
        ax.plot([], [], color=colour, lw=2.0, label=label)


def plot_turns(turns: Any, ax=None, held_speeds=(3.0, 5.0, 7.0), max_radius: float = 30.0):
    """Lean, steer and rear contact radius of the hands-free families against speed (stable
    bold), and the held steer torque against lateral acceleration at ``held_speeds``; the four
    axes."""
    plt = _pyplot()
    if ax is None:
        fig, ax = plt.subplots(2, 2, figsize=(13, 9), constrained_layout=True)
        fig.suptitle(f"{turns.label}: steady turns (bold: stable, thin: unstable)")
    axes = list(np.ravel(ax))
    panels = [("lean φ [deg]", lambda f: np.degrees(f.lean)),
              ("steer δ [deg]", lambda f: np.degrees(f.steer)),
              ("rear contact radius [m]", lambda f: np.abs(f.radius))]
    for k, (label, quantity) in enumerate(panels):
        a = axes[k]
        for i, f in enumerate(turns.families):
            _bold_where(a, f.speed, quantity(f), f.stable, _CYCLE[i % len(_CYCLE)],
                        label=f"hands-free family {i + 1}")
        if k == 2:
            a.set_ylim(0.0, max_radius)
        a.set_xlabel("speed of the rear contact v [m/s]")
        a.set_ylabel(label)
        a.grid(True, color="0.93")
    if turns.branch_speed is not None:
        for a in axes[:2]:
            a.axvline(turns.branch_speed, color=_GREY, lw=0.8, ls=":")
    axes[0].legend(loc="best", fontsize="small")
    held = axes[3]
    bike = turns._bicycle
    if bike is not None and len(held_speeds):
        leans = np.radians(np.arange(1, 61) * 0.5)
        for i, v in enumerate(held_speeds):
            points, stable = [], []
            for lean in leans:
                try:
                    t = bike.turn(float(v), lean=float(lean))
                except Exception:  # the curve ends where the turns do
                    break
                points.append((t.lateral_acceleration, t.steer_torque))
                stable.append(bool(t.stable))
            if points:
                xy = np.array(points)
                _bold_where(held, xy[:, 0], xy[:, 1], np.array(stable), _CYCLE[i % len(_CYCLE)],
                            label=f"held, {v:g} m/s")
        held.legend(loc="best", fontsize="small")
    held.set_xlabel("lateral acceleration [m/s²]")
    held.set_ylabel("held steer torque T_δ [N m]")
    held.grid(True, color="0.93")
    return ax


def plot_side_view(view: Any, label: str = "", ax=None):
    """The side view of the library's geometry (x forward, y up, metres, equal aspect): ground,
    wheels, fork, steer axis and trail, frame tubes, handlebar, each body's centre of mass with
    its inertia ellipse, and the whole bicycle's centre of mass; the axis."""
    plt = _pyplot()
    from matplotlib.patches import Circle, Ellipse

    if ax is None:
        _, ax = plt.subplots(figsize=(10, 6.5), constrained_layout=True)
    rear, front = view["rear_hub"], view["front_hub"]
    r_r, r_f = view["rear_wheel_radius"], view["front_wheel_radius"]
    w, c = view["wheelbase"], view["trail"]
    x0 = min(-r_r, view["grip"][0]) - 0.15
    x1 = max(w + r_f, view["ground_point"][0]) + 0.15
    ax.axhspan(-0.08, 0.0, color="#f4f1ea", zorder=0)
    ax.plot([x0, x1], [0.0, 0.0], color=_GREY, lw=2, zorder=1)
    for hub, r, name in ((rear, r_r, "rear wheel"), (front, r_f, "front wheel")):
        if r > 0:
            ax.add_patch(Circle(hub, r, fill=False, ec=_DARK, lw=2.5, zorder=2, label=None))
            ax.add_patch(Circle(hub, 0.93 * r, fill=False, ec=_GREY, lw=0.8, zorder=2))
        ax.plot(*hub, "o", color=_DARK, ms=4, zorder=5)
    (ax0, ay0), (ax1, ay1) = view["steer_axis"]
    ax.plot([ax0, ax1], [ay0, ay1], color=_GREY, lw=1, ls="--", zorder=2, label="steer axis")
    for a, b in view["frame_tubes"]:
        ax.plot([a[0], b[0]], [a[1], b[1]], color="#3c506e", lw=3.5, solid_capstyle="round",
                zorder=3)
    ax.plot([], [], color="#3c506e", lw=3.5, label="frame (drawing aid)")
    fork = [front, view["crown"], view["head_top"], view["bar"], view["grip"]]
    ax.plot([p[0] for p in fork], [p[1] for p in fork], color=_CYCLE[0], lw=3.5, zorder=3,
            solid_capstyle="round", label="fork and handlebar")
    saddle = view["saddle"]
    ax.plot([saddle[0] - 0.09, saddle[0] + 0.06], [saddle[1], saddle[1]], color=_DARK, lw=5,
            zorder=4)
    # Wheelbase and trail dimensions below the ground.
    yw = -0.05
    ax.annotate("", xy=(w, yw), xytext=(0.0, yw),
                arrowprops=dict(arrowstyle="<->", color=_DARK, lw=0.8))
    ax.text(0.5 * w, yw - 0.005, f"w = {w:.3g} m", ha="center", va="top", fontsize=9,
            color=_DARK)
    ax.plot([w, view["ground_point"][0]], [0.0, 0.0], color=_CYCLE[1], lw=3, zorder=4,
            label=f"trail c = {c:.3g} m")
    for body in view["bodies"]:
        colour = _GREY if body["is_wheel"] else (_CYCLE[0] if body["is_front"] else _CYCLE[1])
        cx, cy = body["centre"]
        ellipse = body["ellipse"]
        if ellipse is not None:
            (a, b), angle = ellipse["semi_axes"], ellipse["angle"]
            ax.add_patch(Ellipse((cx, cy), 2 * a, 2 * b, angle=np.degrees(angle), fill=True,
                                 fc=colour, alpha=0.18, ec=colour, lw=1.2, zorder=4))
        ax.plot(cx, cy, "o", color=colour, ms=6, mec="white", zorder=6)
        ax.annotate(f"{body['name']} {body['mass']:.3g} kg", (cx, cy), xytext=(6, 6),
                    textcoords="offset points", fontsize=8, color=colour, zorder=7)
    gx, gy = view["centre_of_mass"]
    ax.plot(gx, gy, marker="o", ms=11, mfc="white", mec=_DARK, mew=2, zorder=8,
            label=f"centre of mass ({view['total_mass']:.4g} kg)")
    ax.plot(gx, gy, marker="+", ms=11, color=_DARK, mew=1.5, zorder=9)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m] (forward from the rear contact)")
    ax.set_ylabel("y [m] (up)")
    ax.set_title(f"{label} — side view" if label else "side view")
    ax.grid(True, color="0.95")
    ax.legend(loc="upper right", fontsize="small")
    return ax


_QUANTITY_LABELS = {
    "stable_width": "width of the self-stable speed range [m/s]",
    "v_w": "weave speed v_w [m/s]",
    "v_c": "capsize speed v_c [m/s]",
    "v_d": "double-root speed v_d [m/s]",
    "weave_frequency": "weave frequency at v_w [rad/s]",
    "max_real": "largest real part of the eigenvalues [1/s]",
    "stable_over": "margin of self-stability over the band [m/s]",
}


def plot_design_map(design: Any, ax=None, quantity: str = "stable_width"):
    """A two-axis design map as a heat map (colour bar with unit, the boundary of the designs
    with a self-stable range, the base design marked), or a one-axis study as v_w and v_c
    against the parameter with the self-stable band shaded; the axis."""
    plt = _pyplot()
    if quantity not in _QUANTITY_LABELS:
        from ._errors import ArgumentError

        raise ArgumentError(f"unknown quantity {quantity!r} (known: {', '.join(_QUANTITY_LABELS)})",
                            field="quantity", value=quantity,
                            rule=f"one of {', '.join(_QUANTITY_LABELS)}")
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 6.5), constrained_layout=True)
    x_label = f"{design.x_name} [{design.x_unit}]"
    if design.y is None:
        x = design.x
        stable_from, stable_to = design.stable_from, design.stable_to
        top = np.nanmax(np.concatenate([design.v_w, design.v_c, stable_from,
                                        np.where(np.isfinite(stable_to), stable_to, np.nan)]))
        top = 1.15 * top if np.isfinite(top) and top > 0 else 10.0
        band_hi = np.where(np.isinf(stable_to), top, stable_to)
        ax.fill_between(x, stable_from, band_hi, where=np.isfinite(stable_from),
                        color=_CYCLE[2], alpha=0.22, lw=0, label="self-stable")
        ax.plot(x, design.v_w, color=_CYCLE[0], lw=2.2, label="weave speed v_w")
        ax.plot(x, design.v_c, color=_CYCLE[1], lw=2.2, label="capsize speed v_c")
        if design.base_x is not None:
            ax.axvline(design.base_x, color=_DARK, lw=1, ls="--", label="base design")
        ax.set_ylim(0.0, top)
        ax.set_xlabel(x_label)
        ax.set_ylabel("forward speed v [m/s]")
        ax.grid(True, color="0.93")
        ax.legend(loc="best", fontsize="small")
        return ax
    band = getattr(design, "band", None)
    if quantity == "stable_over" and band is None:
        from ._errors import ArgumentError

        raise ArgumentError("quantity 'stable_over' needs a map computed with band=(a, b)",
                            field="quantity", value=quantity, rule="compute the map with band=(a, b)")
    source = design.quantities["band_margin" if quantity == "stable_over" else quantity]
    if quantity == "stable_width":
        # A design with no self-stable speed has no width: none, never 0.
        source = np.where(design.stable, source, np.nan)
    values = np.where(design.status == "ok", source, np.nan).astype(float)
    finite = values[np.isfinite(values)]
    # As the command line: the colour scale spans the 1st to 99th percentile.
    vmin, vmax = (np.percentile(finite, [1, 99]) if finite.size else (0.0, 1.0))
    if vmin == vmax:
        vmin, vmax = vmin - 0.5, vmax + 0.5
    if quantity == "max_real" and vmin < 0.0 < vmax:
        # Diverging, white at zero, each side to its own extreme.
        from matplotlib.colors import TwoSlopeNorm

        mesh = ax.pcolormesh(design.x, design.y, values, shading="nearest", cmap="RdBu_r",
                             norm=TwoSlopeNorm(vcenter=0.0, vmin=vmin, vmax=vmax))
    else:
        mesh = ax.pcolormesh(design.x, design.y, values, shading="nearest", cmap="viridis",
                             vmin=vmin, vmax=vmax)
    bar = ax.figure.colorbar(mesh, ax=ax, extend="both")
    bar.set_label(_QUANTITY_LABELS[quantity])
    if quantity == "stable_over":
        inside = np.where(design.status == "ok", design.stable_over == 1.0, False).astype(float)
        label = f"self-stable at every speed {band[0]:g}–{band[1]:g} m/s"
    else:
        inside = design.stable.astype(float)
        label = "boundary of a self-stable range"
    if inside.min() < 0.5 < inside.max():
        ax.contour(design.x, design.y, inside, levels=[0.5], colors="white", linewidths=1.8)
        ax.plot([], [], color="white", lw=1.8, label=label)
    if design.base_x is not None and design.base_y is not None:
        ax.plot(design.base_x, design.base_y, marker="*", ms=16, color="white", mec=_DARK,
                ls="none", label="base design")
    ax.set_xlabel(x_label)
    ax.set_ylabel(f"{design.y_name} [{design.y_unit}]")
    ax.set_facecolor("0.85")
    handles = ax.get_legend_handles_labels()[0]
    if handles:
        ax.legend(loc="upper right", fontsize="small", facecolor="0.6", framealpha=0.8)
    return ax


def plot_bode(response: Any, output: Any = 0, input: Any = 0, axes=None, hz: bool = False,
              title: Optional[str] = None):
    """A Bode plot of one output–input pair of a :class:`whipple.FrequencyResponse`: the
    magnitude [dB] above, the unwrapped phase [deg] below, against the frequency on a
    logarithmic axis (rad/s, or Hz with ``hz``), one line per speed with a legend of speeds
    (several speeds when the response came from :meth:`whipple.Bicycle.frequency_response`
    with an array of speeds). ``axes``: two axes to draw on. The figure."""
    plt = _pyplot()
    o, i = response.pair(output, input)
    if axes is None:
        fig, axes = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True, constrained_layout=True)
    else:
        fig = axes[0].figure
    magnitude_axis, phase_axis = axes[0], axes[1]
    x = response.hz if hz else response.omega
    db = response.magnitude_db[..., o, i, :]
    phase = response.phase_deg[..., o, i, :]
    speeds = response.speeds
    if speeds is None:
        db, phase, names = db[np.newaxis], phase[np.newaxis], [None]
    else:
        names = [f"{v:g} m/s" for v in speeds]
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, max(len(names), 1)))
    for k, name in enumerate(names):
        colour = colours[k] if len(names) > 1 else "#1f77b4"
        magnitude_axis.semilogx(x, db[k], color=colour, lw=1.5, label=name)
        phase_axis.semilogx(x, phase[k], color=colour, lw=1.5, label=name)
    out, inp = response.outputs[o], response.inputs[i]
    magnitude_axis.set_ylabel(f"|{out.label} / {inp.label}| [dB re 1 {out.unit}/{inp.unit}]")
    phase_axis.set_ylabel("phase [deg]")
    phase_axis.set_xlabel("frequency [Hz]" if hz else "frequency [rad/s]")
    for ax in (magnitude_axis, phase_axis):
        ax.grid(True, which="both", alpha=0.3)
    if speeds is not None:
        magnitude_axis.legend(title="speed", fontsize="small")
    magnitude_axis.set_title(title if title is not None
                             else f"{response.label}: {inp.label} → {out.label}")
    return fig
