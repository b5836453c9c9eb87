"""The non-linear simulation from Python: columns, torques as numbers, expressions and
callables, outcomes."""

import numpy as np
import pytest

import whipple
from conftest import optional


def test_columns_and_outcome(benchmark):
    run = benchmark.simulate(4.6, 1.0, lean_rate=0.5)
    assert run.outcome == "completed" and run.outcome_kind == "completed" and not run.failed
    assert run.csv_columns[:3] == ["t", "lean", "steer"] and len(run.csv_columns) == 20
    for name in run.csv_columns + ["pitch", "rear_wheel_angle", "front_wheel_angle"]:
        column = getattr(run, name)
        assert column.shape == (1001,) and column.dtype == np.float64 and np.all(np.isfinite(column))
    assert run.t[0] == 0.0 and abs(run.t[-1] - 1.0) < 1e-12
    assert run.lean_rate[0] == pytest.approx(0.5)
    # Hands free, the energy is conserved to the integrator's error.
    assert np.ptp(run.energy) < 1e-6 * abs(run.energy[0])
    assert run.position_residual.max() < 1e-10


def test_every_thins_the_samples(benchmark):
    full = benchmark.simulate(4.6, 2.0, lean_rate=0.5)
    thin = benchmark.simulate(4.6, 2.0, lean_rate=0.5, every=100)
    # Steps 0, 100, ..., 2000: the last step is one of them.
    assert thin.t.shape == (21,)
    assert np.array_equal(thin.lean, full.lean[::100])
    assert thin.t[-1] == pytest.approx(2.0)
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.6, 1.0, every=0)
    assert info.value.field == "every"


def test_falls_below_the_weave_speed(benchmark):
    run = benchmark.simulate(2.0, 10.0, lean_rate=0.5)
    assert run.outcome_kind in ("fell", "wheel_lifted") and not run.failed
    assert run.outcome_t is not None and run.outcome_t < 10.0
    assert str(run.outcome_t)[:3] in run.outcome or "at t =" in run.outcome


def test_callable_torque_equals_the_expression(benchmark):
    expression = benchmark.simulate(3.0, 2.0, lean_rate=0.5, steer_torque="10*lean + 20*lean_rate")
    called = benchmark.simulate(3.0, 2.0, lean_rate=0.5,
                                steer_torque=lambda t, s: 10 * s["lean"] + 20 * s["lean_rate"])
    assert expression.outcome == called.outcome == "completed"
    assert np.allclose(expression.lean, called.lean, rtol=0, atol=1e-14)
    constant = benchmark.simulate(4.6, 0.5, lean_torque=1.0)
    as_text = benchmark.simulate(4.6, 0.5, lean_torque="1")
    assert np.array_equal(constant.lean, as_text.lean)


def test_adaptive_integrator(benchmark):
    run = benchmark.simulate(4.6, 2.0, lean_rate=0.5, integrator="adaptive", rtol=1e-10)
    rk4 = benchmark.simulate(4.6, 2.0, lean_rate=0.5, dt=1e-3)
    assert run.outcome == "completed" and run.steps < rk4.steps
    assert abs(run.lean[-1] - rk4.lean[-1]) < 1e-8


def test_callable_exception_reaches_python(benchmark):
    class Boom(RuntimeError):
        pass

    def rider(t, state):
        if t > 0.1:
            raise Boom("rider gave up")
        return 0.0

    with pytest.raises(Boom, match="rider gave up"):
        benchmark.simulate(4.6, 1.0, steer_torque=rider)
    with pytest.raises(whipple.ArgumentError, match="finite"):
        benchmark.simulate(4.6, 1.0, steer_torque=lambda t, s: float("nan"))
    with pytest.raises(TypeError):
        benchmark.simulate(4.6, 1.0, steer_torque=lambda t, s: "left")


def test_poses(benchmark):
    run = benchmark.simulate(4.6, 0.1, poses=True)
    n = len(run)
    assert run.positions.shape == (n, 4, 3) and run.rotations.shape == (n, 4, 3, 3)
    r = run.rotations[-1, 1]
    assert np.allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert run.body_names == ["rear wheel", "rear frame", "front frame", "front wheel"]


def test_to_pandas(benchmark):
    optional("pandas")
    run = benchmark.simulate(4.6, 0.1)
    df = run.to_pandas()
    assert list(df.columns)[:20] == run.csv_columns and len(df) == len(run)
    e = benchmark.eig(np.linspace(0, 10, 11)).to_pandas()
    assert list(e.columns) == ["re1", "im1", "re2", "im2", "re3", "im3", "re4", "im4"]
    s = benchmark.sensitivities().to_pandas()
    assert "c" in s.index


def test_a_step_too_large_raises_instead_of_an_outcome(benchmark):
    # dt = 0.25 s at 4.6 m/s once gave "fell" while the energy grew 326-fold.
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.6, 10.0, lean_rate=0.5, dt=0.25)
    e = info.value
    assert e.field == "dt" and e.value == 0.25 and e.suggested == 0.05
    assert "use dt <= 0.05" in str(e) and "stability" in str(e)
    # A step inside the bound runs as before.
    assert benchmark.simulate(4.6, 2.0, lean_rate=0.5, dt=0.05).outcome_kind == "completed"
