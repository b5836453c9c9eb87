"""whipple.measure against BicycleParameters' own calculate_from_measured (issue 30, "How it is
checked"): every raw bicycle of the core's test data (crates/whipple/tests/data/measured/,
copied from BicycleParameters' data set) computed by both, every parameter to 1e-12 relative
and every σ to 1e-9 relative. BicycleParameters 1.5.2 comes from PyPI in the test environment
only (ci-test), never as a dependency; without it these cross-checks skip with the reason."""

import warnings

import numpy as np
import pytest

import whipple
from conftest import DATA, optional
from crosscheck import (MEASURED as NAMES, bicycleparameters_layout, measured_differences,
                        measured_ours as ours, measured_theirs as theirs)

RAW = DATA / "measured"


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
    """BicycleParameters' layout around the raw files of the core's tests."""
    return bicycleparameters_layout(tmp_path_factory.mktemp("bp-raw"), NAMES + ["Silver"])


@pytest.mark.parametrize("name", NAMES)
def test_measure_matches_bicycleparameters(bp, data_dir, name):
    expected = theirs(bp, data_dir, name)
    differences, ours_keys, their_keys = measured_differences(expected, ours(name))
    assert their_keys >= set(whipple.BENCHMARK_KEYS)
    assert ours_keys == their_keys, f"{name}: ours {sorted(ours_keys)} vs theirs {sorted(their_keys)}"
    for key, (dv, ds) in differences.items():
        assert dv <= 1e-12, f"{name} {key}: value {dv:.2e} from BicycleParameters'"
        assert ds <= 1e-9, f"{name} {key}: σ {ds:.2e} from BicycleParameters'"
    print(f"{name}: largest relative difference {max(d for d, _ in differences.values()):.2e} "
          f"(values), {max(s for _, s in differences.values()):.2e} (σ)")


@pytest.mark.parametrize("name", ["Balanceassistv1", "Gyro", "Rigid"])
def test_bicycleparameters_tilt_sigma_is_its_guess(bp, data_dir, name):
    """Without the exact derivative, BicycleParameters' σ of λ is its guess's: different from
    ours (and from the exact one above), while the values are the same."""
    plain = theirs(bp, data_dir, name, exact_tilt=False)["lam"]
    exact = theirs(bp, data_dir, name)["lam"]
    got = ours(name)
    assert plain.nominal_value == exact.nominal_value
    assert got.bicycle.sigma["lam"] == pytest.approx(exact.std_dev, rel=1e-9)
    assert abs(plain.std_dev - exact.std_dev) > 1e-5 * exact.std_dev  # 3.6e-4 to 5.5e-4 here
    print(f"{name}: σ(λ) BicycleParameters {plain.std_dev:.3e}, exact {exact.std_dev:.3e}")


def test_silver_fails_in_both(bp, data_dir):
    with pytest.raises(Exception) as theirs_error:
        theirs(bp, data_dir, "Silver")
    assert "dF" in str(theirs_error.value)
    with pytest.raises(whipple.ParseError, match="dF is missing: the front wheel's radius"):
        whipple.measure(RAW / "SilverMeasured.txt")


def without(text, *keys):
    return "\n".join(l for l in text.splitlines() if l.split("=")[0].strip() not in keys)


def period_of(text, key):
    line = next(l for l in text.splitlines() if l.split("=")[0].strip() == key)
    return float(line.split("=")[1].split("+/-")[0])


def test_periods_from_synthetic_records(tmp_path):
    """Browser's file with TcB1 and TtB2 removed, and rate-gyro records (.mat, as
    BicycleParameters names them) of a decaying oscillation at exactly those periods: the
    fitted periods are the file's, and so are the parameters."""
    sio = optional("scipy.io").io
    text = (RAW / "BrowserMeasured.txt").read_text()
    raw = tmp_path / "BrowserMeasured.txt"
    raw.write_text(without(text, "TcB1", "TtB2"))
    records = tmp_path / "records"
    records.mkdir()
    rate = 1000
    t = np.arange(20 * rate) / rate
    for key, stem, trials in [("TcB1", "FrameCompoundFirst", 2), ("TtB2", "FrameTorsionalSecond", 1)]:
        period = period_of(text, key)
        for trial in range(1, trials + 1):
            phase = 0.3 * trial  # trials differ, their period does not
            data = 1.2 + np.exp(-0.04 * t) * np.sin(2 * np.pi / period * t + phase)
            sio.savemat(records / f"Browser{stem}{trial}.mat",
                        {"data": data, "sampleRate": np.array([[rate]], dtype=float)})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        got = whipple.measure(raw, periods=records)
    fitted = {f["key"]: f for f in got.fitted}
    assert sorted(fitted) == ["TcB1", "TtB2"]
    for key in fitted:
        assert fitted[key]["value"] == pytest.approx(period_of(text, key), rel=1e-9)
    assert fitted["TcB1"]["source"] == ("fitted from BrowserFrameCompoundFirst1.mat, "
                                        "BrowserFrameCompoundFirst2.mat")
    assert fitted["TtB2"]["source"] == "fitted from BrowserFrameTorsionalSecond1.mat"
    want = ours("Browser").bicycle.to_dict()
    for key, value in got.bicycle.to_dict().items():
        assert value == pytest.approx(want[key], rel=1e-8, abs=1e-12), key


def test_periods_from_bicycleparameters_record(tmp_path):
    """Browser's fork record from BicycleParameters' test data fills a missing TcH1 with the
    core's fit of it, trimmed as BicycleParameters trims it (whipple.read_period, trim 0.1);
    a period without a record names the key and the file looked for."""
    text = (RAW / "BrowserMeasured.txt").read_text()
    raw = tmp_path / "BrowserMeasured.txt"
    raw.write_text(without(text, "TcH1"))
    records = RAW / "periods"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        got = whipple.measure(raw, periods=records)
    fit = whipple.read_period(records / "BrowserForkCompoundFirst1.mat", trim=0.1)
    (tc,) = got.fitted
    assert tc["key"] == "TcH1" and tc["value"] == fit.period and tc["sigma"] == fit.period_sigma
    assert tc["source"] == "fitted from BrowserForkCompoundFirst1.mat"
    assert got.step("IHyy")["inputs"].count("TcH1") == 1
    raw.write_text(without(text, "TcB1"))
    with pytest.raises(whipple.ParameterError) as error:
        whipple.measure(raw, periods=records)
    assert error.value.field == "TcB1"
    assert "looked for" in str(error.value) and "BrowserFrameCompoundFirst1.mat" in str(error.value)
    # Without periods= the missing period is named with what it feeds.
    with pytest.raises(whipple.ParseError, match="TcB1 is missing: the rear frame's IByy"):
        whipple.measure(raw)
