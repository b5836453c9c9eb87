"""Hess's handling quality metric from Python: whipple.handling_quality against an independent
realization of HumanControl's Simulink wiring (WhippleModel.mdl with isHandling set) built here
in numpy from the bicycle's A and B, the certified peak against dense sampling, HumanControl's
gains file, the optimal bicycle of BMD 2016 at 5 m/s, and bad input."""

import numpy as np
import pytest

import whipple
from conftest import DATA

HC = DATA / "humancontrol"
GAINS_5 = [46.5457, -0.0522, 12.6611, 0.1849, 0.0959]  # BenchmarkSteerGains.txt at 5 m/s


def simulink_handling(bike, speed, gains, omega_nm=30.0, zeta_nm=0.707):
    """HumanControl's handling configuration, block by block: the bicycle (steer torque in),
    the neuromuscular filter, the handling filter 400/(s² + 40 s + 400) feeding φ_c; the roll
    rate loop's feedback φ̇ + δ/k_φ̇; the output −(φ̇ + δ/k_φ̇)/k_φ."""
    k_delta, k_phi_dot, k_phi = gains[:3]
    system = bike.linear_system(speed, "steer_torque", "lean")
    a = np.zeros((8, 8))
    a[:4, :4] = system.A
    a[:4, 4] = system.B[:, 0]
    a[4, 5] = 1.0
    a[5, 4] = -omega_nm**2
    a[5, 5] = -2 * zeta_nm * omega_nm
    sum6 = np.zeros(8)
    sum6[6] = k_phi_dot * k_phi      # φ_c
    sum6[0] = -k_phi_dot * k_phi     # φ
    sum6[2] = -k_phi_dot             # φ̇
    sum6[1] = -1.0                   # δ
    a[5] += omega_nm**2 * k_delta * sum6
    a[6, 7] = 1.0
    a[7, 6] = -400.0
    a[7, 7] = -40.0
    b = np.zeros(8)
    b[7] = 400.0
    c = np.zeros(8)
    c[2] = -1.0 / k_phi
    c[1] = -1.0 / (k_phi_dot * k_phi)
    return a, b, c


def magnitudes(a, b, c, omegas):
    return np.array([abs(c @ np.linalg.solve(1j * w * np.eye(8) - a, b)) for w in omegas])


def test_handling_quality_matches_the_simulink_wiring_and_its_peak_bounds_every_sample(benchmark):
    omegas = np.linspace(0.0, 60.0, 6001)
    hqm = whipple.handling_quality(benchmark, GAINS_5, speed=5.0, frequencies=omegas)
    expected = magnitudes(*simulink_handling(benchmark, 5.0, GAINS_5), omegas)
    assert np.allclose(hqm.magnitudes, expected, rtol=1e-9, atol=0)
    assert hqm.certified and hqm.stable
    assert expected.max() <= hqm.peak * (1 + 1e-12)
    assert expected.max() == pytest.approx(hqm.peak, rel=1e-4)
    near = hqm.peak_frequency * (1 + np.linspace(-1e-4, 1e-4, 201))
    assert magnitudes(*simulink_handling(benchmark, 5.0, GAINS_5), near).max() <= \
        hqm.peak * (1 + 1e-10)
    assert hqm.gains == GAINS_5 and not hqm.extrapolated


def test_gains_file_interpolated_and_peaks_against_speed():
    bike = whipple.Bicycle.from_file(HC / "BenchmarkPar.txt")
    gains = HC / "gains" / "BenchmarkSteerGains.txt"
    one = whipple.handling_quality(bike, gains, speed=5.0)
    sweep = whipple.handling_quality(bike, gains, speeds=[3.0, 5.0, 13.0])
    assert sweep.peaks[1] == one.peak and sweep.peak_frequencies[1] == one.peak_frequency
    assert sweep.extrapolated == [False, False, True]
    # BMD 2016: the bicycle optimised for 5 m/s handles better there than the benchmark.
    optimal = whipple.handling_quality(whipple.Bicycle.from_file(HC / "optimal" / "Optimal05Par.txt"),
                                       HC / "gains" / "Optimal05SteerGains.txt", speed=5.0)
    assert optimal.stable and optimal.peak < one.peak


def test_bad_input_is_refused_naming_the_field(benchmark):
    with pytest.raises(whipple.ArgumentError, match="five gains"):
        whipple.handling_quality(benchmark, [1.0, 2.0], speed=5.0)
    with pytest.raises(whipple.ParameterError, match="neuromuscular frequency"):
        whipple.handling_quality(benchmark, GAINS_5, speed=5.0, neuro_frequency=-30.0)
    with pytest.raises(whipple.ParameterError, match="kPhi"):
        whipple.handling_quality(benchmark, [46.5, -0.05, 0.0, 0.18, 0.1], speed=5.0)
    with pytest.raises(whipple.ArgumentError, match="speed"):
        whipple.handling_quality(benchmark, GAINS_5)


def test_optimal_handling_lowers_the_benchmarks_peak_and_reports_every_start():
    bike = whipple.Bicycle.preset("benchmark")
    result = whipple.optimal_handling(
        bike, 5.0, {"trail": (-0.1, 0.2), "head_angle_deg": (60.0, 85.0)}, starts=3)
    assert result.names == ["trail", "head_angle_deg"]
    assert result.units == ["m", "deg"]
    assert result.best["stable"] and result.best["certified"]
    assert result.peak < 0.9 * result.base["peak"]
    assert -0.1 <= result.values["trail"] <= 0.2
    assert 60.0 <= result.values["head_angle_deg"] <= 85.0
    assert len(result.starts) == 3
    assert result.evaluations == sum(s["evaluations"] for s in result.starts)
    # The best bicycle carries the values, and its own HQM with the best gains is the peak.
    again = whipple.handling_quality(result.bicycle, result.best["gains"], speed=5.0)
    assert again.peak == pytest.approx(result.peak, rel=1e-12)


def test_optimal_handling_refuses_bad_bounds_naming_them():
    bike = whipple.Bicycle.preset("benchmark")
    with pytest.raises(whipple.ArgumentError, match="speed"):
        whipple.optimal_handling(bike, 5.0, {"speed": (1.0, 2.0)})
    with pytest.raises(whipple.ArgumentError, match="LOW"):
        whipple.optimal_handling(bike, 5.0, {"trail": (0.2, 0.1)})
    with pytest.raises(whipple.ArgumentError, match="vary"):
        whipple.optimal_handling(bike, 5.0, {"trail": "wide"})
    with pytest.raises(whipple.WhippleError, match="starts"):
        whipple.optimal_handling(bike, 5.0, {"trail": (0.0, 0.2)}, starts=0)
