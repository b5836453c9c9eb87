"""Design maps from Python: every cell as the single-bicycle critical speeds, shards that
assemble to the whole, and the map spread over a local Dask cluster of processes."""

import pickle

import numpy as np
import pytest

import whipple
from conftest import optional


def test_map_cells_are_the_single_bicycle_speeds(benchmark):
    m = benchmark.design_map("c=0.0:0.2:5", "w=0.9:1.2:4")
    assert m.v_w.shape == (4, 5) and m.v_w.dtype == np.float64
    assert np.allclose(m.x, np.linspace(0.0, 0.2, 5)) and np.allclose(m.y, np.linspace(0.9, 1.2, 4))
    for iy, w in enumerate(m.y):
        for ix, c in enumerate(m.x):
            s = benchmark.replace(c=float(c), w=float(w)).critical_speeds()
            for name, value in (("v_w", s.v_w), ("v_c", s.v_c)):
                cell = getattr(m, name)[iy, ix]
                if value is None:
                    assert np.isnan(cell)
                else:
                    assert abs(cell - value) < 1e-10, (name, c, w)
    assert set(m.status.ravel()) <= {"ok", "invalid", "accuracy_lost"}


def test_replace_takes_the_names_design_map_takes(benchmark):
    """Issue 28, item 13: ``replace`` takes the axis names (``trail``, ``head_angle_deg``,
    ``wheel_radius``, the keys), read by the same code as the map's axes, so a map's cell is the
    replaced bicycle's speeds; a wrong name lists the names accepted."""
    m = benchmark.design_map("trail=0.05:0.11:3", "head_angle_deg=68:74:3")
    for iy, head in enumerate(m.y):
        for ix, trail in enumerate(m.x):
            s = benchmark.replace(trail=float(trail), head_angle_deg=float(head)).critical_speeds()
            assert s.v_w is not None and abs(m.v_w[iy, ix] - s.v_w) < 1e-10, (trail, head)
    by_alias = benchmark.replace(trail=0.09, head_angle_deg=70.0, wheel_radius=0.33)
    d = by_alias.to_dict()
    assert d["c"] == 0.09 and d["rR"] == d["rF"] == 0.33
    assert abs(d["lam"] - np.radians(20.0)) < 1e-15
    assert by_alias.to_dict() == benchmark.replace(
        c=0.09, lam=np.pi / 2 - np.radians(70.0), rR=0.33, rF=0.33).to_dict()
    assert benchmark.replace(lam_deg=18.0).to_dict()["lam"] == pytest.approx(np.pi / 10, abs=1e-15)
    crown = whipple.Bicycle.preset("schwinn-crown")
    assert crown.replace(**{"rider.m": 80.0}).jbike6_dict()["mrider"] == 80.0
    assert crown.replace(wheel_diameter=0.7).jbike6_dict()["Dfrontwheel"] == 0.7
    for bad, words in (("trial", "known:"), ("speed", "known:"), ("c_deg", "not an angle"),
                       ("mrider", "known:")):
        with pytest.raises(whipple.ParameterError) as raised:
            benchmark.replace(**{bad: 1.0})
        assert raised.value.field == bad and words in raised.value.rule, raised.value.rule
    with pytest.raises(whipple.ParameterError) as raised:
        benchmark.replace(trial=0.09)
    assert "trail" in raised.value.rule and "head_angle" in raised.value.rule


def test_replace_names_the_copy_edited_and_drops_the_sigma_it_replaced():
    fisher = whipple.Bicycle.preset("fisher")
    assert fisher.sigma["c"] > 0 and fisher.sigma["lam"] > 0
    edited = fisher.replace(trail=0.07, head_angle_deg=71.0)
    assert edited.name == f"{fisher.name} (edited)"
    assert "c" not in edited.sigma and "lam" not in edited.sigma
    assert edited.sigma["mB"] == fisher.sigma["mB"]
    assert edited.replace(mB=5.0).name == edited.name  # once, however many edits


def test_refused_designs_say_why(benchmark):
    m = benchmark.design_map("mB=-10:10:3")
    assert m.status[0] == "invalid" and "mB" in m.reason[0] and np.isnan(m.v_w[0])
    assert m.status[2] == "ok"


def test_shards_assemble_to_the_whole(benchmark):
    whole = benchmark.design_map("c=0.0:0.2:7", "w=0.9:1.2:5")
    parts = [benchmark.design_map_shard("c=0.0:0.2:7", "w=0.9:1.2:5", shard=(k, 3))
             for k in range(3)]
    again = whipple.DesignMap(parts)
    for name in ("v_w", "v_c", "stable_width"):
        assert np.array_equal(getattr(whole, name), getattr(again, name), equal_nan=True)
    with pytest.raises(ValueError, match="missing"):
        whipple.DesignMap(parts[:2])
    with pytest.raises(whipple.ArgumentError):
        benchmark.design_map_shard("c=0.0:0.2:7", shard=(3, 3))


def test_jbike6_axes_by_toml_path():
    crown = whipple.Bicycle.preset("schwinn-crown")
    by_path = crown.design_map("rider.ycm=0.8:1.4:4")
    by_key = crown.design_map("ycmrider=0.8:1.4:4")
    assert np.array_equal(by_path.v_w, by_key.v_w, equal_nan=True)
    assert not np.isnan(by_path.v_w).all()
    with pytest.raises(whipple.ArgumentError, match="rider.height"):
        crown.design_map("rider.height=1:2:3")


def test_pickle(benchmark):
    assert pickle.loads(pickle.dumps(benchmark)).to_dict() == benchmark.to_dict()
    crown = whipple.Bicycle.preset("schwinn-crown")
    assert pickle.loads(pickle.dumps(crown)).jbike6_dict() == crown.jbike6_dict()


def test_to_xarray(benchmark):
    optional("xarray")
    ds = benchmark.design_map("c=0.0:0.2:5", "w=0.9:1.2:4").to_xarray()
    assert ds["v_w"].dims == ("w", "c") and ds["v_w"].shape == (4, 5)


def test_dask_local_cluster(benchmark):
    optional("distributed")
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None, host="127.0.0.1") as cluster, Client(cluster) as client:
        spread = whipple.design_map_dask(benchmark, "c=0.0:0.2:11", "w=0.9:1.2:9", client=client)
    whole = benchmark.design_map("c=0.0:0.2:11", "w=0.9:1.2:9")
    for name in ("v_w", "v_c", "stable_width", "max_real"):
        assert np.array_equal(getattr(whole, name), getattr(spread, name), equal_nan=True)


def test_a_band_asks_self_stable_over_it(benchmark):
    """The designer's question over a band: the benchmark's own design (its self-stable range
    4.292… to 6.024… m/s, Meijaard et al. 2007) is self-stable over 4.5–5.5 m/s with those
    margins, and no design of this map over 4–8; shards with a band assemble to the whole."""
    from reference import CAPSIZE_SPEED, WEAVE_SPEED

    m = benchmark.design_map("c=0.04:0.12:3", "w=1.02:1.02:1", band=(4.5, 5.5))
    assert m.band == (4.5, 5.5)
    assert m.stable_over[0, 1] == 1.0 and m.stable_over[0, 0] == 0.0
    assert abs(m.band_margin_below[0, 1] - (4.5 - WEAVE_SPEED)) < 1e-12
    assert abs(m.band_margin_above[0, 1] - (CAPSIZE_SPEED - 5.5)) < 1e-12
    assert m.band_margin[0, 1] == min(m.band_margin_below[0, 1], m.band_margin_above[0, 1])
    assert np.isnan(m.band_margin[0, 0])
    wide = benchmark.design_map("c=-0.05:0.2:11", "head_angle_deg=60:85:11", band=(4, 8))
    assert not (wide.stable_over == 1.0).any()
    parts = [benchmark.design_map_shard("c=0.0:0.2:7", "w=0.9:1.2:5", band=(4.5, 5.5),
                                       shard=(k, 3))
             for k in range(3)]
    whole = benchmark.design_map("c=0.0:0.2:7", "w=0.9:1.2:5", band=(4.5, 5.5))
    again = whipple.DesignMap(parts)
    assert np.array_equal(whole.band_margin, again.band_margin, equal_nan=True)
    plain = benchmark.design_map("c=0.0:0.2:3")
    assert plain.band is None and "stable_over" not in plain.quantities
    with pytest.raises(whipple.ArgumentError, match="band"):
        benchmark.design_map("c=0.0:0.2:3", band=(8, 4))
