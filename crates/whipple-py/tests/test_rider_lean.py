"""The leaning rider against BicycleParameters' MooreRiderLean2012Model (Moore 2012's
rider-lean model, its linear equations generated from his dissertation's Autolev source), live:
every entry of A and B for ``mooreriderlean2012_browser_jason`` at speeds from 0.5 to 10 m/s,
with the hinge free and stiff and damped; and the hinge locked against the rigid rider's
benchmark model."""

import numpy as np
import pytest

import whipple
from conftest import optional

bp = optional("bicycleparameters", module_level=True)

from bicycleparameters.parameter_dicts import mooreriderlean2012_browser_jason  # noqa: E402
from crosscheck import (RIDER_LEAN_HINGES, RIDER_LEAN_SPEEDS as SPEEDS,  # noqa: E402
                        rider_lean_differences, rider_lean_pair)


@pytest.mark.parametrize("k9, c9", RIDER_LEAN_HINGES)
def test_linearization_is_moores(k9, c9):
    theirs, ours = rider_lean_pair(dict(mooreriderlean2012_browser_jason, k9=k9, c9=c9))
    for v in SPEEDS:
        da, db, ignorable = rider_lean_differences(theirs, ours, v)
        assert da < 1e-10 and db < 1e-10, v
        # The ignorable coordinates do not enter Moore's dynamics either.
        assert ignorable < 1e-12, v


def test_moore_keys_round_trip():
    ours = whipple.RiderLean.from_moore_rider_lean2012(mooreriderlean2012_browser_jason)
    back = ours.to_moore_rider_lean2012()
    for key, value in mooreriderlean2012_browser_jason.items():
        if key != "v":
            assert back[key] == pytest.approx(value, rel=1e-12, abs=1e-12), key


def test_locked_hinge_is_the_rigid_rider():
    """M = B⁻¹ on the three torques, −M A the rest: their (lean, steer) blocks are the
    benchmark model of the rigid rider (the upper body combined into the rear frame)."""
    ours = whipple.RiderLean.from_moore_rider_lean2012(mooreriderlean2012_browser_jason)
    rigid = ours.rigid()
    assert rigid.to_dict()["mB"] == pytest.approx(81.86, rel=1e-15)
    m_r, c1, k0, k2 = rigid.canonical()
    g = mooreriderlean2012_browser_jason["g"]
    for v in SPEEDS:
        a, b = ours.linearize(v)
        m = np.linalg.inv(b[3:, :])
        stiffness = -m @ a[3:, :3]
        damping = -m @ a[3:, 3:]
        assert np.max(np.abs(m[:2, :2] - m_r)) < 1e-12 * np.max(np.abs(m_r))
        k = g * k0 + v**2 * k2
        assert np.max(np.abs(stiffness[:2, :2] - k)) < 1e-12 * np.max(np.abs(k))
        assert np.max(np.abs(damping[:2, :2] - v * c1)) < 1e-12 * np.max(np.abs(v * c1))


def test_a_hinge_above_the_top_is_refused():
    # The hinge 2 m above the rear hub with the upper body's mass centre where it was (l6, G's
    # centre below the hinge, grows by as much as d4 shrinks): above everything else.
    base = mooreriderlean2012_browser_jason
    par = dict(base, d4=-2.0, l6=base["l6"] + base["d4"] + 2.0)
    with pytest.raises(whipple.ParameterError, match="zHinge"):
        whipple.RiderLean.from_moore_rider_lean2012(par)
    # Moving the hinge and the body together is a (tall) rider, not an error.
    whipple.RiderLean.from_moore_rider_lean2012(dict(base, d4=-2.0))
    with pytest.raises(whipple.ParseError, match="d9"):
        whipple.RiderLean.from_moore_rider_lean2012(dict(base, d9=1.0))
    with pytest.raises(whipple.ParseError, match="missing"):
        whipple.RiderLean.from_moore_rider_lean2012({"d1": 1.0})
