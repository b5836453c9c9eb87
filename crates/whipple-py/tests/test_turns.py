"""Steady turns from Python: the command line's numbers reproduced exactly (the same library
behind both), the mirror symmetry of the benchmark bicycle, the branch of hands-free turns
from straight running at the capsize speed, and the typed error for a turn that does not
exist."""

import json
import math
import subprocess

import numpy as np
import pytest

import whipple

#: The benchmark bicycle's capsize speed v_c [m/s], where the hands-free turns branch from
#: straight running (Meijaard et al. 2007, Proc. R. Soc. A 463:1955–1982, section 5:
#: v_c = 6.0243 m/s; these digits from the certified critical speeds, to round-off).
CAPSIZE_SPEED = 6.024262015388371


def cli_turn(cli, *args):
    done = subprocess.run([cli, "turn", "--bike", "benchmark", *args, "--format", "json"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def optional_number(x):
    # The CLI's JSON writes a non-finite number (a lifting wheel's friction ratio) as null.
    return math.inf if x is None else x


def test_turn_matches_cli_exactly(cli, benchmark):
    doc = cli_turn(cli, "--speed", "5", "--lean", "11.5")
    (theirs,) = doc["turns"]
    t = benchmark.turn(5.0, lean=math.radians(11.5))
    for name in ("speed", "lean", "steer", "steer_torque", "pitch", "hub_speed", "yaw_rate",
                 "rear_radius", "front_radius", "mass_centre_radius", "lateral_acceleration",
                 "iterations"):
        assert getattr(t, name) == theirs[name], name
    assert list(t.wheel_rates) == theirs["wheel_rates"]
    assert list(t.centre) == theirs["centre"]
    for ours, c in zip(t.contact, theirs["contact"]):
        for name in ("normal", "longitudinal", "lateral"):
            assert getattr(ours, name) == c[name], name
        assert ours.friction_ratio == optional_number(c["friction_ratio"])
    assert t.residuals == theirs["residuals"]
    stab = theirs["stability"]
    assert t.stable is stab["stable"]
    assert t.max_real == stab["max_real"]
    assert t.family_eigenvalue == stab["family_eigenvalue"]
    assert [complex(z["re"], z["im"]) for z in stab["eigenvalues"]] == list(t.eigenvalues)
    # And the degrees the command line adds beside the radians.
    assert math.degrees(t.lean) == theirs["lean_deg"]
    assert math.degrees(t.steer) == theirs["steer_deg"]
    assert not t.hands_free and t.steer_torque != 0.0
    assert max(abs(x) for x in t.residuals.values()) < 1e-9
    assert "steer δ" in repr(t) and "<table>" in t._repr_html_()
    # to_dict() is the library's record, keyed as the server's /api/turn.
    d = t.to_dict()
    assert set(d) == {"turn", "stability", "stability_error"} and d["stability_error"] is None
    assert d["turn"]["steer_torque"] == t.steer_torque and d["stability"]["stable"] is t.stable


def test_turn_by_steer_and_radius_agree_with_lean(benchmark):
    by_lean = benchmark.turn(5.0, lean=math.radians(11.5))
    by_steer = benchmark.turn(5.0, steer=by_lean.steer)
    by_radius = benchmark.turn(5.0, radius=by_lean.rear_radius)
    assert by_steer.lean == pytest.approx(by_lean.lean, abs=1e-11)
    assert by_radius.lean == pytest.approx(by_lean.lean, abs=1e-11)
    assert by_radius.rear_radius == pytest.approx(by_lean.rear_radius, rel=1e-12)


@pytest.mark.parametrize("lean_deg", [2.0, 11.5, 30.0])
def test_mirror_symmetry(benchmark, lean_deg):
    right = benchmark.turn(5.0, lean=math.radians(lean_deg))
    left = benchmark.turn(5.0, lean=-math.radians(lean_deg))
    assert left.lean == -right.lean
    assert left.steer == pytest.approx(-right.steer, rel=1e-12, abs=1e-15)
    assert left.steer_torque == pytest.approx(-right.steer_torque, rel=1e-10, abs=1e-13)
    assert left.rear_radius == pytest.approx(-right.rear_radius, rel=1e-12)
    assert left.yaw_rate == pytest.approx(-right.yaw_rate, rel=1e-12)
    assert left.pitch == pytest.approx(right.pitch, abs=1e-14)
    assert left.lateral_acceleration == pytest.approx(-right.lateral_acceleration, rel=1e-12)
    for a, b in zip(left.contact, right.contact):
        assert a.normal == pytest.approx(b.normal, rel=1e-12)
        assert a.lateral == pytest.approx(-b.lateral, rel=1e-10, abs=1e-10)
    assert left.stable is right.stable
    np.testing.assert_allclose(left.eigenvalues, right.eigenvalues, rtol=1e-9, atol=1e-9)


@pytest.fixture(scope="module")
def turns(benchmark):
    return benchmark.turns(max_speed=12.0)


def test_families_branch_at_the_capsize_speed(benchmark, turns):
    assert turns.branch_speed == pytest.approx(CAPSIZE_SPEED, abs=1e-9)
    # The linear model's capsize speed, found independently (certified critical speeds).
    assert benchmark.critical_speeds().v_c == pytest.approx(turns.branch_speed, abs=1e-9)
    first = turns.families[0]
    # Traced from a lean of 0.5°: it starts next to the branch, at small lean and steer.
    assert abs(first.speed[0] - CAPSIZE_SPEED) < 0.01
    assert 0 < first.lean[0] < math.radians(1.0)
    assert first.steer[0] / first.lean[0] == pytest.approx(turns.branch_steer_per_lean, rel=0.05)
    for f in turns.families:
        n = len(f)
        assert n > 1
        for name in ("speed", "lean", "steer", "radius", "stable", "max_real"):
            assert getattr(f, name).shape == (n,)
        assert f.stable.dtype == bool
        assert np.all(f.speed <= 12.0 + 1e-9)
        # The mask agrees with the eigenvalues it was decided from.
        decided = f.decided
        assert np.array_equal(f.stable[decided], f.max_real[decided] < 0)
    assert "family 1" in repr(turns)


def test_hands_free_turns_at_a_speed(benchmark, turns):
    found = benchmark.hands_free_turns(8.0)
    assert found, "the benchmark bicycle has hands-free turns at 8 m/s"
    for t in found:
        assert t.hands_free and t.speed == pytest.approx(8.0, abs=1e-12)
        assert max(abs(x) for x in t.residuals.values()) < 1e-9
    # Both leans: each right-leaning turn has its mirror image.
    rights = [t for t in found if t.lean > 0]
    lefts = [t for t in found if t.lean < 0]
    assert len(rights) == len(lefts)
    for r in rights:
        assert any(abs(l.lean + r.lean) < 1e-9 and abs(l.steer + r.steer) < 1e-9 for l in lefts)
    # Every crossing of 8 m/s by a family traced as `hands_free_turns` traces them (to
    # 20 m/s), interpolated between its points, is near one of the turns found (they are those
    # crossings, polished), and each turn found is near a crossing.
    crossings = 0
    near = set()
    for f in benchmark.turns(max_speed=20.0).families:
        for a in range(len(f) - 1):
            va, vb = f.speed[a], f.speed[a + 1]
            if (va - 8.0) * (vb - 8.0) <= 0 and va != vb:
                s = (8.0 - va) / (vb - va)
                lean = f.lean[a] + s * (f.lean[a + 1] - f.lean[a])
                crossings += 1
                distances = [abs(t.lean - lean) for t in rights]
                assert min(distances) < math.radians(1.0)
                near.add(int(np.argmin(distances)))
    assert crossings >= len(rights) and near == set(range(len(rights)))


def test_impossible_turn_raises_typed_error(benchmark):
    # A circle of 5 cm at 8 m/s: smaller than the wheelbase allows.
    with pytest.raises(whipple.NoSteadyTurnError) as info:
        benchmark.turn(8.0, radius=0.05)
    e = info.value
    assert isinstance(e, whipple.WhippleError) and isinstance(e, ValueError)
    assert e.field == "radius"
    assert e.rule and e.given and "radius" in str(e)


def test_turn_with_a_wheel_pulled_down_is_refused(benchmark):
    # A 0.5 m circle at 5 m/s solves with the rear normal force at -1448 N; the
    # knife-edge model cannot hold it, and it was returned as a turn.
    with pytest.raises(whipple.NoSteadyTurnError) as info:
        benchmark.turn(5.0, radius=0.5)
    e = info.value
    assert e.field == "radius"
    assert "rear wheel's normal force would be -14" in str(e) and "lift" in str(e)


def test_huge_radius_is_refused_naming_the_bound(benchmark):
    # radius=1e200 once said "a computed result is not a finite number".
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.turn(5.0, radius=1e200)
    assert info.value.field == "radius" and "1e9" in str(info.value)
    # The bound itself is a turn, straight running to round-off.
    turn = benchmark.turn(5.0, radius=1e9)
    assert math.isfinite(turn.lean) and abs(turn.lean) < 1e-8


@pytest.mark.parametrize("kwargs, field", [
    (dict(), "lean"),
    (dict(lean=0.1, steer=0.1), "steer"),
    (dict(lean=float("nan")), "lean"),
    (dict(lean=math.radians(95)), "lean"),
    (dict(radius=0.0), "radius"),
    (dict(steer=4.0), "steer"),
])
def test_bad_turn_arguments(benchmark, kwargs, field):
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.turn(5.0, **kwargs)
    assert info.value.field == field


def test_bad_speed(benchmark):
    with pytest.raises(whipple.ArgumentError):
        benchmark.turn(float("nan"), lean=0.1)
    with pytest.raises(whipple.ArgumentError):
        benchmark.turns(max_speed=-1.0)


def test_simulate_from_turn_stays_on_it(benchmark):
    turn = benchmark.turn(5.0, lean=math.radians(11.5))
    run = benchmark.simulate(5.0, 1.0, lean=math.radians(11.5), from_turn=True)
    assert run.outcome_kind == "completed"
    assert run.lean[0] == pytest.approx(turn.lean, abs=1e-12)
    assert run.steer[0] == pytest.approx(turn.steer, abs=1e-9)
    # A steady turn: lean and steer stay (held turns at 5 m/s and 11.5° are near-steady over a
    # second even if unstable: the start is exact to round-off).
    assert np.max(np.abs(run.lean - turn.lean)) < 1e-6
    assert np.max(np.abs(run.steer - turn.steer)) < 1e-6
    assert run.yaw[-1] == pytest.approx(turn.yaw_rate * run.t[-1], rel=1e-5)
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(5.0, 1.0, lean=0.2, steer=0.1, from_turn=True)
    assert info.value.field == "steer"
    with pytest.raises(whipple.NoSteadyTurnError):
        benchmark.simulate(5.0, 1.0, lean=math.radians(88.9), from_turn=True)


def test_simulate_from_turn_matches_cli(cli, benchmark):
    done = subprocess.run([cli, "simulate", "--bike", "benchmark", "--speed", "5", "--lean",
                           "11.5", "--from-turn", "--duration", "0.5", "--format", "csv"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.strip().splitlines()
    header = lines[0].split(",")
    rows = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    run = benchmark.simulate(5.0, 0.5, lean=math.radians(11.5), from_turn=True)
    ours = np.column_stack([run.columns[name] for name in header])
    assert ours.shape == rows.shape
    assert np.array_equal(ours, rows)


def test_each_speed_says_whose_it_is(benchmark):
    """Issue 28, item 13: ``simulate``'s speed is the rear hub's, ``turn``'s the rear
    contact's; the docstrings say so and the numbers agree: a run started on a turn at the rear
    contact's speed v runs at the turn's hub speed."""
    assert "rear hub" in whipple.Bicycle.simulate.__doc__
    assert "rear contact" in whipple.Bicycle.turn.__doc__
    assert "rear hub" in whipple.Simulation.__doc__
    turn = benchmark.turn(5.0, lean=0.2)
    assert turn.speed == 5.0 and abs(turn.hub_speed - turn.speed) > 1e-3
    run = benchmark.simulate(5.0, 0.01, lean=0.2, from_turn=True)
    assert abs(run.speed[0] - turn.hub_speed) < 1e-9
    assert benchmark.simulate(5.0, 0.01).speed[0] == 5.0
