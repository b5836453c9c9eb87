"""whipple.measure against BicycleParameters' own calculate_from_measured (issue 30, "How it is
checked"): every raw bicycle of the core's test data (crates/whipple/tests/data/measured/,
copied from BicycleParameters' data set) computed by both, every parameter to 1e-12 relative
and every σ to 1e-9 relative. BicycleParameters 1.5.2 comes from PyPI in the test environment
only (ci-test), never as a dependency; without it these cross-checks skip with the reason."""

import io
import os
import shutil
import warnings
from contextlib import redirect_stdout

import numpy as np
import pytest

import whipple
from conftest import DATA, optional

RAW = DATA / "measured"
# Every raw file BicycleParameters can compute (Silver's lacks dF: both refuse it, below).
NAMES = ["Browser", "Browserins", "Crescendo", "Fisher", "Pista", "Stratos", "Yellow",
         "Yellowrev"]


def ours(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        return whipple.measure(RAW / f"{name}Measured.txt")


def test_measure_reads_a_path_or_text():
    by_path = ours("Browser")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        by_text = whipple.measure((RAW / "BrowserMeasured.txt").read_text())
    assert by_path.bicycle.name == "Browser"
    assert by_path.bicycle.to_dict() == by_text.bicycle.to_dict()
    assert by_path.covariance.shape == (26, 26)
    assert by_path.jacobian.shape == (26, len(by_path.inputs))
    # σ² on the covariance's diagonal; the correlation matrix symmetric with ones on it.
    sigma = by_path.bicycle.sigma
    for i, key in enumerate(by_path.keys):
        assert by_path.covariance[i, i] == pytest.approx(sigma.get(key, 0.0) ** 2, rel=1e-12)
    rho = by_path.correlation()
    assert np.allclose(rho, rho.T, equal_nan=True)
    w = by_path.keys.index("w")
    assert rho[w, w] == pytest.approx(1.0)
    top = by_path.largest_correlations(3)
    assert len(top) == 3 and abs(top[0][2]) >= abs(top[2][2])
    k = by_path.step("k")
    assert k["function"] == "torsion_constant" and k["inputs"] == ["mP", "lP", "dP", "TtP1"]
    assert by_path.step("residualB")["sigma"] is None
    # The steps that are parameters carry the bicycle's numbers.
    values = by_path.bicycle.to_dict()
    for s in by_path.steps:
        if s["benchmark"]:
            assert s["value"] == values[s["key"]]


def test_measure_names_what_is_missing():
    with pytest.raises(whipple.ParseError) as error:
        whipple.measure(RAW / "SilverMeasured.txt")
    assert "dF is missing: the front wheel's radius needs it" in str(error.value)
    text = (RAW / "BrowserMeasured.txt").read_text()
    line = next(l for l in text.splitlines() if l.startswith("TcR1"))
    with pytest.raises(whipple.ParameterError) as error:
        whipple.measure(text.replace(line, "TcR1 = -1.4+/-0.001"))
    assert error.value.field == "TcR1" and "a period must be positive" in str(error.value)


@pytest.fixture(scope="module")
def bp():
    return optional("bicycleparameters")


@pytest.fixture(scope="module")
def data_dir(tmp_path_factory):
    """BicycleParameters' layout, bicycles/<Name>/RawData/<Name>Measured.txt, around the raw
    files of the core's tests (no Parameters folder: it must compute from the raw data)."""
    root = tmp_path_factory.mktemp("bp-raw")
    for name in NAMES + ["Silver"]:
        target = root / "bicycles" / name / "RawData"
        target.mkdir(parents=True)
        shutil.copy(RAW / f"{name}Measured.txt", target)
    return root


def theirs(bp, data_dir, name):
    """BicycleParameters' calculate_from_measured on the raw file (forced, as its users run
    it): the benchmark parameters as uncertainties' ufloats."""
    cwd = os.getcwd()
    try:
        os.chdir(data_dir)
        with warnings.catch_warnings(), redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            bike = bp.Bicycle(name, pathToData=str(data_dir), forceRawCalc=True)
        return bike.parameters["Benchmark"]
    finally:
        os.chdir(cwd)


@pytest.mark.parametrize("name", NAMES)
def test_measure_matches_bicycleparameters(bp, data_dir, name):
    expected = theirs(bp, data_dir, name)
    got = ours(name)
    values, sigma = got.bicycle.to_dict(), got.bicycle.sigma
    worst_value, worst_sigma = 0.0, 0.0
    for key in whipple.BENCHMARK_KEYS:
        assert key in expected, f"{name}: BicycleParameters gave no {key}"
        v, s = float(expected[key].nominal_value), float(expected[key].std_dev)
        dv = abs(values[key] - v) / max(abs(v), 1e-300)
        assert dv <= 1e-12, f"{name} {key}: {values[key]!r} vs BicycleParameters' {v!r}"
        ours_s = sigma.get(key, 0.0)
        ds = abs(ours_s - s) / max(abs(s), 1e-300) if s != 0.0 else abs(ours_s)
        assert ds <= 1e-9, f"{name} {key}: σ {ours_s!r} vs BicycleParameters' {s!r}"
        worst_value, worst_sigma = max(worst_value, dv), max(worst_sigma, ds)
    print(f"{name}: largest relative difference {worst_value:.2e} (values), "
          f"{worst_sigma:.2e} (σ)")


def test_silver_fails_in_both(bp, data_dir):
    with pytest.raises(Exception):
        theirs(bp, data_dir, "Silver")
    with pytest.raises(whipple.ParseError, match="dF"):
        whipple.measure(RAW / "SilverMeasured.txt")
