"""The non-linear benchmark bicycle's equations of motion at one general state against the
published accelerations: Basu-Mandal, Chatterjee & Papadopoulos 2007, "Hands-free circular
motions of a benchmark bicycle", Proc. R. Soc. A 463:1983–2003, Table 1 (digits as
transcribed in moorepants/DynamicistToolKit, dtk/bicycle.py), as the Rust test
crates/whipple/tests/nonlinear.rs checks them, to the same tolerance."""

import math

import numpy as np
import pytest

# Their state. Coordinates: x, y, z of the rear wheel centre (z up, x backward when θ = 0);
# θ yaw, ψ lean (π/2 upright), φ rear frame pitch (π upright), ψ_f steer, β_r, β_f wheel
# rotations; all with the opposite sense of this model's (yaw right, lean right, nose up,
# steer right, wheel rotation about the axle pointing right).
X, Y, Z = 0.0, 0.0, 0.2440472102925
THETA, PSI, PHI, PSIF, BETAR, BETAF = 0.0, 0.9501292851472, 3.1257073014894, 0.2311385135743, 0.0, 0.0
XD, YD, ZD = -2.8069345714545, -0.1480982396001, 0.1058778746261
THETAD, PSID, PHID, PSIFD = 0.7830033527065, 0.6068425835418, -0.0119185528069, 0.4859824687093
BETARD, BETAFD = 8.912989661489, 8.0133620584155
#: Table 1's output: xdd, ydd, zdd, thetadd, psidd, phidd, psifdd, betardd, betafdd.
OUTPUT = [-0.5041626315047, -0.3449706619454, -1.460452833298, 0.8353281706379,
          -7.8555281128244, 0.1205543897884, -4.6198904039403, 1.8472554144217,
          2.454807290455]


def test_table_1_accelerations(benchmark):
    r_r = benchmark.to_dict()["rR"]
    # Their rear contact from the wheel centre: r_R cos ψ to the left across the heading.
    contact = (-X - r_r * math.sin(THETA) * math.cos(PSI),
               Y - r_r * math.cos(THETA) * math.cos(PSI))
    out = benchmark.accelerations(
        yaw=-THETA, lean=math.pi / 2 - PSI, pitch=math.pi - PHI, steer=-PSIF,
        wheel_angles=(-BETAR, -BETAF), rear_contact=contact, hub_velocity=(-XD, YD, -ZD),
        yaw_rate=-THETAD, lean_rate=-PSID, pitch_rate=-PHID, steer_rate=-PSIFD,
        wheel_rates=(-BETARD, -BETAFD))
    # Their state is on the constraints, and the wheel centre where they put it.
    assert out["holonomic_residual"] < 1e-12
    assert out["velocity_residual"] < 1e-12
    assert np.max(np.abs(out["hub_position"] - np.array([-X, Y, -Z]))) < 1e-12
    a = out["hub_acceleration"]
    yaw, lean, pitch = out["angle_accelerations"]
    rear, front = out["wheel_accelerations"]
    ours = [-a[0], a[1], -a[2], -yaw, -lean, -pitch, -out["steer_acceleration"], -rear, -front]
    # The published values carry 13 significant digits; the Rust test's tolerance.
    for i, (x, published) in enumerate(zip(ours, OUTPUT)):
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
