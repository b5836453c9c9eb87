"""The figures draw (Agg backend) and hold what they show: the steady-turn families, the side
view, a design map and a one-parameter study."""

import math

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
