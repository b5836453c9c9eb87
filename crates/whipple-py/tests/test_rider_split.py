"""Jason's upper body split off a bicycle's rider (``RiderLean.from_bicycle``): the locked
hinge gives the bicycle back, and where the upper body does not fit the error says why."""

import numpy as np
import pytest

import whipple


def test_split_and_locked_hinge_round_trip():
    bike = whipple.Bicycle.preset("schwinn-crown")
    rider = whipple.RiderLean.from_bicycle(bike, hinge_stiffness=800.0, hinge_damping=50.0)
    back = rider.rigid().to_dict()
    theirs = bike.to_dict()
    for key, value in theirs.items():
        assert back[key] == pytest.approx(value, rel=1e-12, abs=1e-12), key
    a, b = rider.linearize(5.0)
    assert a.shape == (6, 6) and b.shape == (6, 3)
    # The stiff hinge: the rider-lean rows carry the spring (−k / its inertia, negative).
    assert a[5, 2] < 0.0
    moore = rider.to_moore_rider_lean2012()
    assert moore["k9"] == 800.0 and moore["c9"] == 50.0 and moore["mg"] == pytest.approx(48.816)


def test_an_upper_body_that_does_not_fit_is_refused():
    with pytest.raises(whipple.ParameterError, match="does not fit"):
        whipple.RiderLean.from_bicycle(whipple.Bicycle.preset("benchmark"))
    with pytest.raises(whipple.ParameterError, match="lighter"):
        whipple.RiderLean.from_bicycle(whipple.Bicycle.preset("browser"))
    with pytest.raises(whipple.ParameterError, match="kLean"):
        whipple.RiderLean.from_bicycle(whipple.Bicycle.preset("schwinn-crown"), hinge_stiffness=-1.0)
    assert np.isfinite(whipple.RiderLean.from_bicycle(whipple.Bicycle.preset("browser-jason")).linearize(3.0)[0]).all()
