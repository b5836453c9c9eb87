"""Every error class, with its field, value and rule; never a panic."""

import math

import numpy as np
import pytest

import whipple
from reference import CAPSIZE_SPEED, DOUBLE_ROOT_SPEED, WEAVE_SPEED


def test_parameter_error(benchmark):
    with pytest.raises(whipple.ParameterError) as info:
        benchmark.replace(mB=-1.0)
    e = info.value
    assert isinstance(e, ValueError) and isinstance(e, whipple.WhippleError)
    assert e.field == "mB" and e.value == -1.0 and e.rule
    with pytest.raises(whipple.ParameterError) as info:
        benchmark.replace(IBxx=math.nan)
    assert info.value.field == "IBxx" and math.isnan(info.value.value)


def test_unknown_and_missing_keys(benchmark):
    d = benchmark.to_dict()
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict({**d, "IBxxx": 1.0})
    assert info.value.field == "IBxxx"
    del d["IBxx"]
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict(d)
    assert "IBxx" in str(info.value)
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict({**benchmark.to_dict(), "w": "wide"})
    assert info.value.field == "w"
    # `wheelbase` is a design axis's name for `w` (issue 28), a misspelling is not.
    assert benchmark.replace(wheelbase=1.0).to_dict()["w"] == 1.0
    with pytest.raises(whipple.ParameterError) as info:
        benchmark.replace(wheelbas=1.0)
    assert info.value.field == "wheelbas" and "not a parameter" in info.value.rule


def test_invalid_bicycle_names_the_fields(benchmark):
    # A front frame whose inertia makes the mass matrix indefinite.
    with pytest.raises(whipple.ParameterError) as info:
        benchmark.replace(IHxz=10.0)
    assert info.value.field and info.value.rule


def test_parse_error_has_line_and_column():
    with pytest.raises(whipple.ParseError) as info:
        whipple.Bicycle.from_text("[benchmark]\nw = = 1\n", "toml")
    e = info.value
    assert isinstance(e, ValueError) and e.format == "TOML" and e.line == 2 and e.column > 0
    with pytest.raises(whipple.ParseError):
        whipple.Bicycle.from_text("w = 1.02\n", "bp-txt")


def test_not_utf8(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_bytes(b"\xff\xfe[benchmark]")
    with pytest.raises(whipple.ParseError, match="UTF-8"):
        whipple.Bicycle.from_file(p)
    with pytest.raises(FileNotFoundError):
        whipple.Bicycle.from_file(tmp_path / "missing.toml")


def test_unknown_preset():
    with pytest.raises(whipple.UnknownPresetError) as info:
        whipple.Bicycle.preset("penny-farthing")
    assert isinstance(info.value, LookupError)
    assert info.value.value == "penny-farthing" and "benchmark" in info.value.rule


def test_argument_errors(benchmark):
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.critical_speeds(5.0, 1.0)
    assert info.value.field == "range"
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.0, 1.0, lean=2.0)
    assert info.value.field == "lean"
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.0, 1.0, dt=-1.0)
    assert info.value.field == "dt"
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.0, 1.0, steer_torque="sin(")
    assert info.value.field == "steer_torque"
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.0, 1.0, integrator="euler")
    assert info.value.field == "integrator"
    with pytest.raises(whipple.ArgumentError) as info:
        benchmark.simulate(4.0, 1.0, steer_torque=[1, 2, 3])
    assert info.value.field == "steer_torque"
    with pytest.raises(whipple.ArgumentError):
        benchmark.to_text("xml")
    with pytest.raises(whipple.ArgumentError):
        benchmark.compare([1.0], methods=("magic",))


def test_limit_error(benchmark):
    with pytest.raises(whipple.LimitError) as info:
        benchmark.simulate(4.0, 1000.0, dt=1e-5)
    assert isinstance(info.value, whipple.ArgumentError) and info.value.field == "dt"


def test_numerical_errors_are_arithmetic_errors():
    assert issubclass(whipple.NumericalError, ArithmeticError)
    assert issubclass(whipple.AccuracyLostError, whipple.NumericalError)


def test_non_finite_speed_is_refused(benchmark):
    with pytest.raises(whipple.WhippleError):
        benchmark.state_space([1.0, math.inf])
    with pytest.raises(whipple.WhippleError):
        benchmark.eig([math.nan])


def test_eigenvalues_at_absurd_speeds_are_right_or_refused():
    """The capsize root at 1e16 m/s was returned as 0 (it is +2.3722196e-16 1/s, from a
    60-digit reference on the same matrices); where round-off decides the roots (the two-mass
    skate at 1e6 m/s) the call raises instead of returning numbers."""
    bike = whipple.Bicycle.preset("benchmark")
    for tracked in (True, False):
        values = bike.eig([1e16], tracked=tracked).values[0]
        small = values[np.argmin(np.abs(values))]
        assert small.imag == 0 and abs(small.real - 2.3722196e-16) < 1e-22, values
    skate = whipple.Bicycle.preset("two-mass-skate")
    for tracked in (True, False):
        with pytest.raises(whipple.AccuracyLostError, match="eigenvalues at 1000000 m/s"):
            skate.eig([1e6], tracked=tracked)


def test_critical_speeds_are_those_of_forward_riding():
    """On a range reaching below zero, v_w and v_c were their mirror images (−4.29, −6.02)."""
    c = whipple.Bicycle.preset("benchmark").critical_speeds(-math.inf, 10.0)
    assert abs(c.v_w - WEAVE_SPEED) < 1e-9 and abs(c.v_c - CAPSIZE_SPEED) < 1e-9
    assert abs(c.v_d - DOUBLE_ROOT_SPEED) < 1e-9
