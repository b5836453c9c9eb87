"""The non-linear benchmark bicycle's equations of motion at one general state against the
published accelerations: Basu-Mandal, Chatterjee & Papadopoulos 2007, "Hands-free circular
motions of a benchmark bicycle", Proc. R. Soc. A 463:1983–2003, Table 1 (digits as
transcribed in moorepants/DynamicistToolKit, dtk/bicycle.py), as the Rust test
crates/whipple/tests/nonlinear.rs checks them, to the same tolerance."""

import numpy as np
import pytest

from reference import BASU_MANDAL_OUTPUT, BASU_MANDAL_STATE, basu_mandal_accelerations


def test_table_1_accelerations(benchmark):
    ours, out = basu_mandal_accelerations(benchmark)
    s = BASU_MANDAL_STATE
    # Their state is on the constraints, and the wheel centre where they put it.
    assert out["holonomic_residual"] < 1e-12
    assert out["velocity_residual"] < 1e-12
    assert np.max(np.abs(out["hub_position"] - np.array([-s["x"], s["y"], -s["z"]]))) < 1e-12
    # The published values carry 13 significant digits; the Rust test's tolerance.
    for i, (x, published) in enumerate(zip(ours, BASU_MANDAL_OUTPUT)):
        assert abs(x - published) < 2e-12, (i, x, published)


def test_upright_straight_running_has_no_acceleration(benchmark):
    # An invariant: upright straight running at constant speed is steady.
    r_r = benchmark.to_dict()["rR"]
    v = 4.0
    out = benchmark.accelerations(lean=0.0, pitch=0.0, steer=0.0, hub_velocity=(v, 0.0, 0.0),
                                  yaw_rate=0.0, lean_rate=0.0, pitch_rate=0.0, steer_rate=0.0,
                                  wheel_rates=(-v / r_r, -v / benchmark.to_dict()["rF"]))
    assert out["velocity_residual"] < 1e-12
    values = np.concatenate([out["hub_acceleration"], out["angle_accelerations"],
                             [out["steer_acceleration"]], out["wheel_accelerations"]])
    assert np.max(np.abs(values)) < 1e-12


def test_state_off_the_constraints_is_reported(benchmark):
    # A pitch that does not fit the front contact: reported, not corrected.
    out = benchmark.accelerations(lean=0.0, pitch=0.05, steer=0.0, hub_velocity=(0.0, 0.0, 0.0),
                                  yaw_rate=0.0, lean_rate=0.0, pitch_rate=0.0, steer_rate=0.0,
                                  wheel_rates=(0.0, 0.0))
    assert out["holonomic_residual"] > 1e-3


def test_non_finite_state_is_an_argument_error(benchmark):
    import whipple

    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.accelerations(lean=float("nan"), pitch=0.0, steer=0.0,
                                hub_velocity=(0.0, 0.0, 0.0), yaw_rate=0.0, lean_rate=0.0,
                                pitch_rate=0.0, steer_rate=0.0, wheel_rates=(0.0, 0.0))
    assert info.value.field == "angles"
