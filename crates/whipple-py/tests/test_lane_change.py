"""``whipple.lane_change`` against an independent computation: the closed loop of
HumanControl's ``system_state_space.m`` (lateral task) written here from the MATLAB source's
nested loops on whipple's open-loop A, B, C, with ``generate_data.m``'s path filter appended and
``lane_change.m``'s path, simulated by scipy.signal.lsim (its own matrix exponential)."""

import os

import numpy as np
import pytest

import whipple
from conftest import optional

# HumanControl's BenchmarkSteerGains.txt at 5 m/s: kDelta, kPhiDot, kPhi, kPsi, kY.
GAINS_5 = [46.5457, -0.0522, 12.6611, 0.1849, 0.0959]
GAINS_FILE = os.path.join(os.path.dirname(__file__), "..", "..", "whipple", "tests", "data",
                          "humancontrol", "gains", "BenchmarkSteerGains.txt")


def matlab_lane_change(kind, speed):
    """lane_change(35, 2, 0.2, 250, speed, 500, kind, 60) transcribed: x, y, t."""
    start, width, slope, path_length, num, lane_length = 35.0, 2.0, 0.2, 250.0, 500, 60.0
    x = np.arange(num + 1) * (path_length / num)
    t = x / speed
    y = np.zeros_like(x)
    end_of_slope = width / slope + start
    slope_ind = (x > start) & (x <= end_of_slope)
    y[slope_ind] = slope * (x[slope_ind] - start)
    if kind == "single":
        y[np.nonzero(slope_ind)[0][-1] + 1:] = width
    else:
        start_of_slope = start + lane_length - width / slope
        lane = (x > end_of_slope) & (x <= start_of_slope)
        y[lane] = width
        down = (x > start_of_slope) & (x <= start + lane_length)
        y[down] = slope * (start + lane_length - x[down])
    return x, y, t


def closed_loop_with_filter(bike, speed, k, omega=30.0, zeta=0.707, path_frequency=2.4):
    """The lateral closed loop with the path filter: states [bicycle (6), T, Tdot, yc, ycdot]."""
    s = bike.linear_system(speed, "steer_torque",
                           ["yaw", "lean", "steer", "lean_rate", "front_contact_y"])
    a, b, c = s.A, s.B[:, 0], s.C
    n = a.shape[0]
    k_delta, k_phi_dot, k_phi, k_psi, k_y = k
    psi, phi, delta, phi_dot, y_q = c
    # system_state_space.m's loops, innermost last: y_c − y_Q → ψ_c → φ_c → φ̇_c → δ_c → T_c.
    # Each row is the command's dependence on the bicycle's states; the last column on y_c.
    psi_c = np.append(-k_y * y_q, k_y)
    phi_c = k_psi * (psi_c - np.append(psi, 0.0))
    phi_dot_c = k_phi * (phi_c - np.append(phi, 0.0))
    delta_c = k_phi_dot * (phi_dot_c - np.append(phi_dot, 0.0))
    torque_c = k_delta * (delta_c - np.append(delta, 0.0))
    big = np.zeros((n + 4, n + 4))
    big[:n, :n] = a
    big[:n, n] = b
    big[n, n + 1] = 1.0
    big[n + 1, :n] = omega ** 2 * torque_c[:n]
    big[n + 1, n + 2] = omega ** 2 * torque_c[n]
    big[n + 1, n] -= omega ** 2
    big[n + 1, n + 1] -= 2 * zeta * omega
    big[n + 2, n + 3] = 1.0
    big[n + 3, n + 2] = -path_frequency ** 2
    big[n + 3, n + 3] = -2 * path_frequency
    bb = np.zeros((n + 4, 1))
    bb[n + 3, 0] = path_frequency ** 2
    outputs = np.zeros((3, n + 4))
    outputs[0, :n] = y_q
    outputs[1, n] = 1.0
    outputs[2, n + 2] = 1.0
    return big, bb, outputs


@pytest.mark.parametrize("kind", ["single", "double"])
def test_the_linear_lane_change_matches_an_independent_closed_loop(kind):
    optional("scipy")
    import scipy.signal

    bike = whipple.Bicycle.preset("benchmark")
    ours = whipple.lane_change(bike, GAINS_5, 5.0, lane=kind, model="linear")["linear"]
    a, b, c, d = *closed_loop_with_filter(bike, 5.0, GAINS_5), np.zeros((3, 1))
    x, y, t = matlab_lane_change(kind, 5.0)
    _, out, _ = scipy.signal.lsim((a, b, c, d), y, t, interp=True)
    assert np.allclose(ours["time"], t, rtol=0, atol=1e-12)
    for name, column in (("front_y", 0), ("steer_torque", 1), ("command", 2)):
        scale = np.max(np.abs(out[:, column]))
        assert np.max(np.abs(ours[name] - out[:, column])) < 1e-9 * scale, name
    # The road: the path 2.75 s later (550 samples of 0.1 s... 27.5 samples: compare on x).
    assert np.allclose(ours["path"], np.interp(ours["time"] - 2.75, t, y, left=0.0))
    assert np.array_equal(ours["error"], ours["command"] - ours["front_y"])


def test_the_nonlinear_bicycle_follows_from_a_gains_file():
    bike = whipple.Bicycle.preset("benchmark")
    both = whipple.lane_change(bike, GAINS_FILE, 5.0)
    assert np.allclose(both["gains"], GAINS_5)
    assert not both["extrapolated"]
    linear, nonlinear = both["linear"], both["nonlinear"]
    assert np.array_equal(linear["time"], nonlinear["time"])
    difference = np.max(np.abs(linear["front_y"] - nonlinear["front_y"]))
    assert 1e-6 < difference < 0.01
    # The same run on a narrower lane: the difference falls as the width cubed.
    narrow = whipple.lane_change(bike, GAINS_FILE, 5.0, width=0.5)
    smaller = np.max(np.abs(narrow["linear"]["front_y"] - narrow["nonlinear"]["front_y"]))
    assert abs(np.log(difference / smaller) / np.log(4.0) - 3.0) < 0.05


def test_bad_requests_name_the_argument():
    bike = whipple.Bicycle.preset("benchmark")
    with pytest.raises(whipple.ArgumentError, match="five gains"):
        whipple.lane_change(bike, GAINS_5[:4], 5.0)
    with pytest.raises(whipple.ParameterError, match="neuromuscular frequency"):
        whipple.lane_change(bike, GAINS_5, 5.0, neuro_frequency=-30.0, model="linear")
    with pytest.raises(whipple.ArgumentError, match="not a lane change"):
        whipple.lane_change(bike, GAINS_5, 5.0, lane="triple")
    with pytest.raises(whipple.ArgumentError, match="not a model"):
        whipple.lane_change(bike, GAINS_5, 5.0, model="both_ways")
    with pytest.warns(whipple.ParameterWarning, match="extrapolated"):
        whipple.lane_change(bike, GAINS_FILE, 13.0, model="linear")


def test_the_run_plots_the_road_and_both_paths():
    optional("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    bike = whipple.Bicycle.preset("benchmark")
    run = whipple.lane_change(bike, GAINS_5, 5.0)
    ax = run.plot()
    assert [line.get_label() for line in ax.get_lines()] == [
        "road (the path, preview delayed)", "front contact y_Q, linear",
        "front contact y_Q, nonlinear"]
    assert np.array_equal(ax.get_lines()[2].get_ydata(), run["nonlinear"]["front_y"])
