"""The units people use (issue 33): ``from_dict`` takes ``_mm`` after a length and ``_deg``
after an angle, through the same front-layer code as the files and the CLI; ``to_dict`` is SI."""

import math

import pytest

import whipple

DESIGNER = {"w_mm": 1020.0, "c_mm": (80.0, 1.0), "lam_deg": 18.0, "rR_mm": 300.0,
            "xB_mm": 300.0, "zB_mm": -900.0, "xH_mm": 900.0, "zH_mm": -700.0, "rF_mm": 350.0}
SI = {"w": 1.02, "c": (0.08, 0.001), "lam": math.radians(18.0), "rR": 0.3, "xB": 0.3,
      "zB": -0.9, "xH": 0.9, "zH": -0.7, "rF": 0.35}


def _with(benchmark, changes):
    d = benchmark.to_dict()
    for key in list(changes):
        stem = key[:-3] if key.endswith("_mm") else key[:-4] if key.endswith("_deg") else key
        d.pop(stem, None)
    d.update(changes)
    return d


def test_suffixed_keys_give_the_si_bicycle(benchmark):
    typed = whipple.Bicycle.from_dict(_with(benchmark, DESIGNER))
    si = whipple.Bicycle.from_dict(_with(benchmark, SI))
    assert typed.to_dict() == si.to_dict()
    d = typed.to_dict()
    assert d["c"] == 0.08 and d["w"] == 1.02 and d["lam"] == math.radians(18.0)
    assert "c_mm" not in d and "lam_deg" not in d  # to_dict stays SI
    assert typed.sigma["c"] == 0.001
    assert typed.critical_speeds().v_w == si.critical_speeds().v_w


def test_written_back_in_the_unit_given(benchmark):
    typed = whipple.Bicycle.from_dict(_with(benchmark, DESIGNER))
    text = typed.to_text("toml")
    assert "c_mm = { value = 80.0, sigma = 1.0 }" in text
    assert "w_mm = 1020.0" in text and "lam_deg = 18.0" in text
    assert whipple.Bicycle.from_text(text, "toml").to_dict() == typed.to_dict()


@pytest.mark.parametrize("key, words", [
    ("IBxx_mm", "`IBxx` is not a length"),
    ("lam_mm", "`lam` is not a length"),
    ("c_deg", "`c` is not an angle"),
])
def test_a_suffix_that_does_not_fit_is_refused(benchmark, key, words):
    d = benchmark.to_dict()
    d[key] = d.pop(key.rsplit("_", 1)[0])
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict(d)
    assert info.value.field == key and words in str(info.value)


def test_one_key_in_two_units_is_refused(benchmark):
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict({**benchmark.to_dict(), "c_mm": 80.0})
    assert "`c` and `c_mm`" in str(info.value)


@pytest.mark.parametrize("value", [math.nan, math.inf])
def test_a_suffixed_value_must_be_finite(benchmark, value):
    d = benchmark.to_dict()
    del d["c"]
    d["c_mm"] = value
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict(d)
    assert info.value.field == "c_mm"


def test_a_negative_radius_in_mm_is_refused(benchmark):
    d = benchmark.to_dict()
    del d["rR"]
    d["rR_mm"] = -300.0
    with pytest.raises(whipple.ParameterError) as info:
        whipple.Bicycle.from_dict(d)
    assert "rR" in str(info.value)
