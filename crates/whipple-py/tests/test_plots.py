"""The figures draw (Agg backend) and hold what they show: the steady-turn families, the side
view, a design map and a one-parameter study, the eigenvalues of several bicycles overlaid, the
mode shapes against speed and the phasors at one speed. The figures go to a scratch directory,
or to $WHIPPLE_PLOTS_OUT to look at them."""

import math
import os

import numpy as np
import pytest

from conftest import optional

import whipple


@pytest.fixture(scope="module")
def plt():
    matplotlib = optional("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    yield plt
    plt.close("all")


def test_turns_plot(plt, benchmark, tmp_path):
    turns = benchmark.turns(max_speed=10.0)
    axes = turns.plot(held_speeds=(5.0,))
    flat = list(np.ravel(axes))
    assert len(flat) == 4
    # Every family is drawn in each of the three speed panels, stable parts bold.
    for ax in flat[:3]:
        widths = {line.get_linewidth() for line in ax.lines}
        assert max(widths) > 3 and min(widths) <= 1.0
        xs = np.concatenate([line.get_xdata() for line in ax.lines if len(line.get_xdata()) > 1])
        assert np.min(xs) >= 0 and np.max(xs) <= 10.0 + 1e-9
    lean_lines = [ln for ln in flat[0].lines if len(ln.get_xdata()) > 1]
    assert sum(len(ln.get_xdata()) for ln in lean_lines) >= sum(len(f) for f in turns.families)
    assert flat[0].get_ylabel() == "lean φ [deg]"
    assert flat[2].get_ylim() == (0.0, 30.0)
    # The held curve at 5 m/s: its first point is the held turn at a lean of 0.5°.
    held = [ln for ln in flat[3].lines if len(ln.get_xdata()) > 1]
    assert held
    first = benchmark.turn(5.0, lean=math.radians(0.5))
    assert held[0].get_xdata()[0] == first.lateral_acceleration
    assert held[0].get_ydata()[0] == first.steer_torque
    flat[0].figure.savefig(tmp_path / "turns.png")


def test_side_view_plot(plt, benchmark, tmp_path):
    from matplotlib.patches import Circle, Ellipse

    view = benchmark.side_view()
    assert view["front_hub"] == (1.02, 0.35)
    assert view["total_mass"] == pytest.approx(94.0, abs=1e-12)
    assert len(view["frame_tubes"]) == 6
    # The library's SideView's own field names; an ellipse as its record (semi_axes, angle).
    ellipse = next(b["ellipse"] for b in view["bodies"] if b["ellipse"] is not None)
    assert set(ellipse) == {"semi_axes", "angle"} and len(ellipse["semi_axes"]) == 2
    assert [b["is_wheel"] for b in view["bodies"]][:2] == [True, True]
    ax = benchmark.plot_side_view()
    circles = [p for p in ax.patches if isinstance(p, Circle)]
    ellipses = [p for p in ax.patches if isinstance(p, Ellipse) and not isinstance(p, Circle)]
    radii = sorted({round(c.radius, 12) for c in circles})
    assert {0.3, 0.35} <= set(radii)
    # B and H have inertia ellipses (the wheels are drawn as wheels).
    assert len(ellipses) == 2
    # The six frame tubes are drawn as given by the library.
    drawn = {((ln.get_xdata()[0], ln.get_ydata()[0]), (ln.get_xdata()[1], ln.get_ydata()[1]))
             for ln in ax.lines if len(ln.get_xdata()) == 2}
    for a, b in view["frame_tubes"]:
        assert (tuple(a), tuple(b)) in drawn
    labels = ax.get_legend_handles_labels()[1]
    assert any(lb.startswith("trail c = 0.08") for lb in labels)
    assert any(lb.startswith("centre of mass (94 kg)") for lb in labels)
    texts = [t.get_text() for t in ax.texts]
    assert any("rear frame" in t for t in texts)
    ax.figure.savefig(tmp_path / "side.png")


def test_side_view_of_a_jbike6_bicycle(plt):
    import whipple

    jbike6 = [p["name"] for p in whipple.presets()]
    bikes = [whipple.Bicycle.preset(n) for n in jbike6]
    bike = next((b for b in bikes if b.form == "jbike6"), None)
    if bike is None:
        pytest.skip("no JBike6-form preset")
    view = bike.side_view()
    parts = {b["part"] for b in view["bodies"]}
    assert "rear_frame" not in parts and parts & {"rider", "frame", "fork"}
    assert bike.plot_side_view().patches


def test_design_map_plot(plt, benchmark, tmp_path):
    m = benchmark.design_map("c=0.0:0.2:9", "w=0.8:1.3:7")
    ax = m.plot(quantity="v_w")
    meshes = [c for c in ax.collections if c.__class__.__name__ == "QuadMesh"]
    assert len(meshes) == 1
    assert meshes[0].get_array().size == 7 * 9
    # The colour bar with the unit.
    bar = meshes[0].colorbar
    assert bar is not None and "[m/s]" in bar.ax.get_ylabel()
    # A boundary of the stable set exists on this grid (some designs stable, some not).
    assert m.stable.any() and not m.stable.all()
    labels = ax.get_legend_handles_labels()[1]
    assert "boundary of a self-stable range" in labels
    # The base design (c = 0.08, w = 1.02) is marked.
    assert (m.base_x, m.base_y) == (0.08, 1.02)
    stars = [ln for ln in ax.lines if ln.get_marker() == "*"]
    assert stars and (stars[0].get_xdata()[0], stars[0].get_ydata()[0]) == (0.08, 1.02)
    assert ax.get_xlabel() == "c [m]" and ax.get_ylabel() == "w [m]"
    ax.figure.savefig(tmp_path / "map.png")


def test_band_map_plot(plt, benchmark, tmp_path):
    """stable_over: the smaller margin, the qualifying designs outlined and named by the band;
    max_real on a diverging scale centred on zero; without a band stable_over is refused."""
    m = benchmark.design_map("c=-0.05:0.2:26", "head_angle_deg=60:85:26", band=(4.5, 5.5), speed=5)
    ax = m.plot(quantity="stable_over")
    labels = ax.get_legend_handles_labels()[1]
    assert "self-stable at every speed 4.5–5.5 m/s" in labels
    mesh = [c for c in ax.collections if c.__class__.__name__ == "QuadMesh"][0]
    assert "over the band" in mesh.colorbar.ax.get_ylabel()
    ax.figure.savefig(tmp_path / "band.png")
    ax = m.plot(quantity="max_real")
    mesh = [c for c in ax.collections if c.__class__.__name__ == "QuadMesh"][-1]
    assert mesh.norm.__class__.__name__ == "TwoSlopeNorm" and mesh.norm.vcenter == 0.0
    with pytest.raises(whipple.ArgumentError, match="band"):
        benchmark.design_map("c=0.0:0.2:3", "w=0.9:1.1:3").plot(quantity="stable_over")


def test_study_plot(plt, benchmark, tmp_path):
    s = benchmark.design_map("c=-0.02:0.2:23")
    ax = s.plot()
    labels = ax.get_legend_handles_labels()[1]
    assert {"weave speed v_w", "capsize speed v_c", "self-stable", "base design"} <= set(labels)
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert np.array_equal(lines["weave speed v_w"].get_ydata(), s.v_w, equal_nan=True)
    assert np.array_equal(lines["capsize speed v_c"].get_ydata(), s.v_c, equal_nan=True)
    assert ax.get_ylabel() == "forward speed v [m/s]"
    ax.figure.savefig(tmp_path / "study.png")


def test_unknown_quantity(plt, benchmark):
    import whipple

    with pytest.raises(whipple.ArgumentError):
        benchmark.design_map("c=0.0:0.2:3", "w=0.9:1.1:3").plot(quantity="nope")


def _out(tmp_path):
    out = os.environ.get("WHIPPLE_PLOTS_OUT")
    if out:
        os.makedirs(out, exist_ok=True)
        return out
    return str(tmp_path)


def _drawn(ax):
    """The lines that hold data (not the legend's entries nor the zero line)."""
    return [ln for ln in ax.lines if len(ln.get_xdata()) > 1 and ln.get_gid() != "whipple-zero"]


SPEEDS = np.linspace(0.0, 10.0, 201)


def test_eigenvalues_of_several_bicycles_overlaid(plt, benchmark, tmp_path):
    longer = benchmark.replace(c=0.12)
    ax = whipple.plot_eigenvalues([benchmark, longer], SPEEDS, labels=["benchmark", "trail 12 cm"])
    lines = _drawn(ax)
    e = benchmark.eig(SPEEDS)
    oscillating = sum(bool(np.any(e.values[:, k].imag > 0)) for k in range(4))
    per_bicycle = 4 + oscillating
    assert oscillating >= 1 and len(lines) == 2 * per_bicycle
    # One colour per bicycle, one line style per mode.
    colours = [ln.get_color() for ln in lines]
    assert len(set(colours[:per_bicycle])) == 1 and len(set(colours[per_bicycle:])) == 1
    assert colours[0] != colours[-1]
    styles = {ln.get_linestyle() for ln in lines[:per_bicycle]}
    assert styles == {"-", "--", ":"}
    # The real parts drawn are the eigenvalues, column by column.
    assert np.array_equal(lines[0].get_ydata(), e.values[:, 0].real)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts == ["benchmark", "trail 12 cm", "weave", "capsize", "castering", "thin: |Im λ|"]
    assert ax.get_xlabel() == "speed v [m/s]" and ax.get_ylabel() == "eigenvalue λ [1/s]"
    assert "benchmark" in ax.get_title() and "trail 12 cm" in ax.get_title()
    ax.set_ylim(-10, 10)
    ax.figure.savefig(os.path.join(_out(tmp_path), "eigenvalues-overlaid.png"), dpi=110)
    with pytest.raises(whipple.ArgumentError):
        whipple.plot_eigenvalues([benchmark, longer], SPEEDS, labels=["one"])


def test_eigen_plot_label_title_ax(plt, benchmark):
    fig, ax = plt.subplots()
    e = benchmark.eig(SPEEDS)
    assert e.label == "benchmark"
    assert e.plot(ax=ax, label="A", title="two bicycles") is ax
    benchmark.replace(mB=100.0).eig(SPEEDS).plot(ax=ax, label="B", imaginary=False)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts[:2] == ["A", "B"] and texts.count("weave") == 1
    assert ax.get_title() == "two bicycles"
    # Without a label, one figure as before: a colour per mode, Re solid and |Im| dashed.
    alone = e.plot()
    labels = alone.get_legend_handles_labels()[1]
    assert "weave Re λ" in labels and "capsize Re λ" in labels


def test_mode_shapes_are_normalized(benchmark):
    e = benchmark.eig(SPEEDS)
    lean, steer = e.mode_shapes()
    assert lean.shape == steer.shape == (len(SPEEDS), 4)
    largest = np.maximum(np.abs(lean), np.abs(steer))
    assert np.allclose(largest, 1.0, rtol=0, atol=1e-12)
    assert np.all(np.abs(lean.imag) <= 1e-12) and np.all(lean.real >= 0)
    # Where lean dominates the eigenvector, its normalized magnitude is 1.
    raw = np.abs(e.vectors[:, 0, :]) >= np.abs(e.vectors[:, 1, :])
    assert raw.any() and (~raw).any()
    assert np.allclose(np.abs(lean[raw]), 1.0, rtol=0, atol=1e-12)
    assert np.allclose(np.abs(steer[~raw]), 1.0, rtol=0, atol=1e-12)
    # The ratio steer / lean is the eigenvector's own.
    ratio = e.vectors[:, 1, :] / e.vectors[:, 0, :]
    assert np.allclose(steer / lean, ratio, rtol=1e-12, atol=0)
    one = benchmark.eig(5.0)
    assert one.mode_shapes()[0].shape == (4,)


def test_mode_shapes_plot(plt, benchmark, tmp_path):
    e = benchmark.eig(SPEEDS)
    axes = e.plot_vectors()
    assert np.shape(axes) == (2, 3)
    assert [a.get_title() for a in axes[0]] == ["weave", "capsize", "castering"]
    for top, bottom in zip(axes[0], axes[1]):
        assert [ln.get_label() for ln in top.lines] == ["lean |φ|", "steer |δ|"]
        assert len(bottom.lines) == 1
        assert bottom.get_ylabel() == "phase of δ relative to φ [deg]"
        assert bottom.get_xlabel() == "speed v [m/s]"
        assert top.get_ylabel() == "magnitude (larger = 1)"
        mags = np.array([ln.get_ydata() for ln in top.lines])
        assert np.allclose(mags.max(axis=0), 1.0, atol=1e-12)
    axes[0][0].figure.savefig(os.path.join(_out(tmp_path), "mode-shapes.png"), dpi=110)
    with pytest.raises(whipple.ArgumentError, match="tracked"):
        benchmark.eig(SPEEDS, tracked=False).plot_vectors()


def test_weave_shape_against_numpy(plt, benchmark):
    """The weave's steer/lean ratio drawn at 5 m/s is numpy.linalg.eig's of A(5) to 1e-9."""
    v = 5.0
    w, vectors = np.linalg.eig(benchmark.state_space(v)[0])
    k = int(np.argmax(w.imag))  # the weave with Im λ > 0 (the other modes are real here)
    expected = vectors[1, k] / vectors[0, k]
    e = benchmark.eig(SPEEDS)
    i = int(np.argmin(np.abs(SPEEDS - v)))
    assert SPEEDS[i] == v
    axes = e.plot_vectors()
    top, bottom = axes[0][0], axes[1][0]
    lean_mag, steer_mag = (ln.get_ydata()[i] for ln in top.lines)
    phase = np.radians(bottom.lines[0].get_ydata()[i])
    assert abs(steer_mag / lean_mag - abs(expected)) <= 1e-9 * abs(expected)
    assert abs(phase - np.angle(expected)) <= 1e-9
    # The phasors at that speed: the arrows end at the normalized components.
    phasors = e.plot_phasors(v)
    assert len(phasors) == 3
    arrows = [t for t in phasors[0].texts if getattr(t, "arrow_patch", None) is not None]
    (lx, ly), (sx, sy) = (a.xy for a in arrows)
    assert ly == 0.0 and lx > 0
    assert abs(complex(sx, sy) / complex(lx, ly) - expected) <= 1e-9 * abs(expected)
    assert max(abs(complex(lx, ly)), abs(complex(sx, sy))) == pytest.approx(1.0, abs=1e-12)
    assert phasors[0].get_title().startswith("weave: λ = ")
    assert phasors[0].get_legend_handles_labels()[1] == ["lean φ", "steer δ"]


def test_phasors_plot(plt, benchmark, tmp_path):
    axes = benchmark.eig(SPEEDS).plot_phasors(4.0)
    assert [a.get_title().split(":")[0] for a in axes] == ["weave", "capsize", "castering"]
    for a in axes:
        assert a.get_xlabel() == "real part" and a.get_ylabel() == "imaginary part"
        assert len([t for t in a.texts if getattr(t, "arrow_patch", None) is not None]) == 2
    axes[0].figure.savefig(os.path.join(_out(tmp_path), "phasors.png"), dpi=110)
    # One speed needs no argument; several do.
    assert len(benchmark.eig(6.0).plot_phasors()) == 3
    with pytest.raises(whipple.ArgumentError, match="speed"):
        benchmark.eig(SPEEDS).plot_phasors()
