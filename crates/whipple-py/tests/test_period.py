"""Pendulum periods from Python: whipple.fit_period on synthetic records, whipple.read_period
on BicycleParameters' sample record against the numbers its own fit gave (quoted, with their
provenance in crates/whipple/tests/data/measured/periods/README.md) and, where
bicycleparameters is installed, against its fit run now."""

import math

import numpy as np
import pytest

import whipple
from conftest import DATA, optional

SAMPLE = DATA / "measured" / "periods" / "BrowserForkCompoundFirst1.mat"

# BicycleParameters 1.5.2 (numpy 2.4.6, scipy 1.17.1), its fit with the analytic Jacobian to
# scipy's tightest tolerances, on samples 2..29696 (select_good_data(data, 0.1)).
BP_PERIOD = 1.5903143948411882
BP_PERIOD_SIGMA_FULL = 1.2223837191221983e-05
BP_DAMPING_RATIO = 0.00890250531186835


def test_fit_period_recovers_a_synthetic_record():
    t = np.arange(3000) / 500.0
    y = 1.5 + np.exp(-0.03 * t) * (0.7 * np.sin(3.3 * t) + 0.2 * np.cos(3.3 * t))
    fit = whipple.fit_period(t, y)
    assert fit.period == pytest.approx(2 * math.pi / 3.3, rel=1e-11)
    zeta = 0.03 / math.hypot(0.03, 3.3)
    assert fit.damping_ratio == pytest.approx(zeta, rel=1e-8)
    assert fit.window == (0, 3000)
    assert isinstance(fit.fitted, np.ndarray) and fit.fitted.shape == (3000,)
    assert np.allclose(fit.fitted, y, atol=1e-10)
    assert fit.covariance.shape == (5, 5)


def test_fit_period_sigma_covers_the_error_of_noisy_records():
    rng = np.random.default_rng(7)
    t = np.arange(4000) / 1000.0
    errors = []
    for _ in range(10):
        y = np.exp(-0.05 * t) * np.sin(2 * math.pi / 0.8 * t) + rng.normal(0, 0.05, t.size)
        fit = whipple.fit_period(t, y)
        errors.append((fit.period - 0.8) / fit.period_sigma)
    assert max(abs(e) for e in errors) < 4.0


def test_read_period_on_bicycleparameters_sample():
    fit = whipple.read_period(SAMPLE, trim=0.1)
    assert fit.signal_name == "data"
    assert fit.window == (2, 29696)
    assert fit.signal.shape == (30000,)
    assert fit.period == pytest.approx(BP_PERIOD, abs=1e-9)
    assert fit.period_sigma == pytest.approx(BP_PERIOD_SIGMA_FULL, rel=1e-6)
    assert fit.damping_ratio == pytest.approx(BP_DAMPING_RATIO, abs=1e-9)


def test_read_period_errors_name_what_is_wrong(tmp_path):
    with pytest.raises(whipple.ArgumentError, match="no numeric variable 'x'"):
        whipple.read_period(SAMPLE, column="x")
    flat = tmp_path / "flat.csv"
    flat.write_text("".join(f"{i},1\n" for i in range(100)))
    with pytest.raises(whipple.ArgumentError, match="no oscillation found"):
        whipple.read_period(flat)
    with pytest.raises(whipple.ArgumentError):
        whipple.fit_period([0.0, 1.0], [1.0])
    with pytest.raises(OSError):
        whipple.read_period(tmp_path / "missing.csv")


def test_against_bicycleparameters_fit_now(tmp_path):
    """BicycleParameters' own get_period_from_truncated on its sample file, run now."""
    optional("bicycleparameters")
    from bicycleparameters import io, period

    data = io.load_pendulum_mat_file(str(SAMPLE))
    theirs = period.get_period_from_truncated(data["data"], period.get_sample_rate(data),
                                              str(tmp_path / "fit.png"))
    fit = whipple.read_period(SAMPLE, trim=0.1)
    # BicycleParameters stops scipy's leastsq at its default tolerance (3e-9 relative from the
    # minimum here) and treats σ_ζ and σ_ωn as uncorrelated (2e-4 relative).
    assert fit.period == pytest.approx(theirs.nominal_value, rel=1e-8)
    assert fit.period_sigma == pytest.approx(theirs.std_dev, rel=1e-3)
