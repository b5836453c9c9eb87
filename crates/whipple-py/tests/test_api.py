"""Shapes, dtypes, identities and the bicycle constructors."""

import math
import warnings

import numpy as np
import pytest

import whipple
from conftest import DATA
from reference import CAPSIZE_SPEED, WEAVE_SPEED


def test_state_space_shapes_and_dtypes(benchmark):
    a, b = benchmark.state_space(5.0)
    assert a.shape == (4, 4) and b.shape == (4, 2) and a.dtype == np.float64
    v = np.linspace(0, 10, 7)
    a, b = benchmark.state_space(v)
    assert a.shape == (7, 4, 4) and b.shape == (7, 4, 2)
    # The kinematic rows of A and the sequential path give the same numbers.
    assert np.all(a[:, 0, 2] == 1.0) and np.all(a[:, 1, 3] == 1.0)
    a_seq, b_seq = benchmark.state_space(v, parallel=False)
    assert np.array_equal(a, a_seq) and np.array_equal(b, b_seq)
    # Lists, ints and 0-d arrays are speeds too.
    assert benchmark.state_space([1, 2])[0].shape == (2, 4, 4)
    assert benchmark.state_space(np.float64(3.0))[0].shape == (4, 4)


def test_state_space_from_canonical(benchmark):
    """A = [[0, I], [−M⁻¹(g K0 + v² K2), −M⁻¹ v C1]] from the canonical matrices."""
    m, c1, k0, k2 = benchmark.canonical()
    g = benchmark.to_dict()["g"]
    v = 4.0
    a, b = benchmark.state_space(v)
    minv = np.linalg.inv(m)
    assert np.allclose(a[2:, :2], -minv @ (g * k0 + v * v * k2), rtol=1e-13, atol=1e-13)
    assert np.allclose(a[2:, 2:], -minv @ (v * c1), rtol=1e-13, atol=1e-13)
    assert np.allclose(b[2:, :], minv, rtol=1e-13, atol=1e-13)


def test_eig_shapes_and_identity(benchmark):
    v = np.linspace(0, 10, 51)
    e = benchmark.eig(v)
    values, vectors = e
    assert values.shape == (51, 4) and values.dtype == np.complex128
    assert vectors.shape == (51, 4, 4) and vectors.dtype == np.complex128
    a, _ = benchmark.state_space(v)
    for i in range(len(v)):
        for k in range(4):
            x = vectors[i, :, k]
            assert abs(np.linalg.norm(x) - 1.0) < 1e-12
            residual = a[i] @ x - values[i, k] * x
            assert np.linalg.norm(residual) < 1e-11 * max(1.0, abs(values[i, k]))
    # Against numpy's general eigensolver.
    for i in range(len(v)):
        ref = np.sort_complex(np.linalg.eigvals(a[i]))
        assert np.allclose(np.sort_complex(values[i]), ref, rtol=1e-9, atol=1e-9)


def test_eig_unsorted_speeds_follow_their_speed(benchmark):
    v = np.array([5.0, 1.0, 3.0, 1.0])
    e = benchmark.eig(v)
    ordered = benchmark.eig(np.sort(v))
    for i, speed in enumerate(v):
        j = int(np.searchsorted(np.sort(v), speed))
        assert np.array_equal(e.values[i], ordered.values[j])
    untracked = benchmark.eig(v, tracked=False)
    assert untracked.modes is None
    assert np.all(np.diff(untracked.values.real, axis=1) <= 0)


@pytest.mark.parametrize("name", ["benchmark", "browser", "fisher", "rigid", "yellowrev"])
def test_tracked_eig_in_parallel_equals_serial(name):
    """Tracked in parallel (the core tracks chunks of the speeds on their own and joins them
    where they overlap) gives the serial tracking's columns, labels and numbers bit for bit, on
    grids through the double-root, weave and capsize speeds (each on the grid), ascending,
    descending and shuffled, fine and coarse; each row holds the untracked row's eigenvalues."""
    bike = whipple.Bicycle.preset(name)
    s = bike.critical_speeds(0.0, 10.0)
    critical = [s.v_d, s.v_w, s.v_c]
    critical = [v for v in critical if v is not None]

    def certified(v):
        try:
            bike.eig(np.array([v]), tracked=False)
            return True
        except whipple.AccuracyLostError:
            return False

    # Exactly at a double root the eigenvalues may not be certifiable (the rigid bicycle's v_d):
    # there both modes refuse alike, and the grids pass beside that one speed.
    for v in critical:
        if not certified(v):
            for parallel in (True, False):
                with pytest.raises(whipple.AccuracyLostError):
                    bike.eig(np.array([v - 1e-3, v, v + 1e-3]), parallel=parallel)
    on_grid = [v for v in critical if certified(v)]
    fine = np.sort(np.concatenate([np.linspace(0.0, 10.0, 60_000), on_grid]))
    windows = [np.linspace(v - 1e-3, v + 1e-3, 20_001) for v in critical]
    near = np.concatenate([w if v in on_grid else w[w != v] for v, w in zip(critical, windows)])
    shuffled = np.random.default_rng(28).permutation(fine)
    for v in (fine, fine[::-1], near, shuffled, np.linspace(0.0, 10.0, 41)):
        together = bike.eig(v)
        alone = bike.eig(v, parallel=False)
        assert together.modes == alone.modes == ["weave", "weave", "capsize", "castering"]
        assert np.array_equal(together.values, alone.values)
        assert np.array_equal(together.vectors, alone.vectors)
        untracked = bike.eig(v, tracked=False)
        assert np.array_equal(np.sort_complex(together.values), np.sort_complex(untracked.values))


def test_eig_scalar(benchmark):
    e = benchmark.eig(5.0)
    assert e.values.shape == (4,) and e.vectors.shape == (4, 4)
    assert e.speeds == 5.0


def test_a_2d_speeds_array_is_refused(benchmark):
    """A (2, 3) array was flattened silently and came back as six rows."""
    speeds = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    for call in (benchmark.eig, benchmark.state_space):
        with pytest.raises(whipple.ArgumentError, match=r"shape \(2, 3\)") as error:
            call(speeds)
        assert error.value.field == "speeds"
    assert benchmark.eig(speeds.ravel()).values.shape == (6, 4)


def test_to_dict_round_trip(benchmark):
    d = benchmark.to_dict()
    assert tuple(d) == whipple.BENCHMARK_KEYS and len(d) == 26
    again = whipple.Bicycle.from_dict(d, name="copy")
    assert again.to_dict() == d
    assert again.critical_speeds().v_w == benchmark.critical_speeds().v_w


class UFloat:
    """What the uncertainties package's ufloat offers (duck-typed)."""

    def __init__(self, n, s):
        self.nominal_value, self.std_dev = n, s


def test_from_dict_with_uncertainty(benchmark):
    d = dict(benchmark.to_dict())
    d["c"] = UFloat(0.08, 0.001)
    d["mB"] = (85.0, 0.5)
    d["xB"] = {"value": 0.3, "sigma": 0.01}
    bike = whipple.Bicycle.from_dict(d)
    assert bike.sigma == {"c": 0.001, "mB": 0.5, "xB": 0.01}
    s = bike.critical_speeds()
    assert s.uncertain and s.v_w_sigma > 0 and s.v_c_sigma > 0
    assert s.v_w == pytest.approx(benchmark.critical_speeds().v_w, abs=1e-13)
    assert "±" in repr(s)


def test_from_bicycleparameters_duck_typed(benchmark):
    class FakeBicycle:
        bicycleName = "Fake"
        parameters = {"Benchmark": benchmark.to_dict()}

    class FakeParameterSet:
        parameterization = "benchmark"
        parameters = benchmark.to_dict()

    class Principal:
        parameterization = "principal"
        parameters = {"a": 1.0}

    assert whipple.Bicycle.from_bicycleparameters(FakeBicycle()).name == "Fake"
    assert whipple.Bicycle.from_bicycleparameters(FakeParameterSet()).to_dict() == benchmark.to_dict()
    with pytest.raises(whipple.ParameterError, match="principal"):
        whipple.Bicycle.from_bicycleparameters(Principal())
    with pytest.raises(TypeError):
        whipple.Bicycle.from_bicycleparameters(42)


def test_replace(benchmark):
    longer = benchmark.replace(c=0.09, w=1.1)
    d = longer.to_dict()
    assert d["c"] == 0.09 and d["w"] == 1.1 and d["mB"] == benchmark.to_dict()["mB"]
    assert longer.critical_speeds().v_w != benchmark.critical_speeds().v_w
    assert benchmark.to_dict()["c"] == 0.08  # unchanged
    crown = whipple.Bicycle.preset("schwinn-crown")
    assert crown.form == "jbike6" and crown.jbike6_dict() is not None
    heavier = crown.replace(mrider=90.0)
    assert heavier.jbike6_dict()["mrider"] == 90.0


def test_every_file_format_reads(benchmark):
    files = sorted((DATA / "bicycleparameters").glob("*.txt"))
    files += sorted((DATA / "humancontrol").glob("*.txt"))
    files += sorted((DATA / "bicycleparameters-yaml").glob("*.yml"))
    assert len(files) > 20
    read = 0
    for path in files:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", whipple.ParameterWarning)
            try:
                bike = whipple.Bicycle.from_file(path)
            except whipple.WhippleError as error:
                # Refused with a reason naming the field (a non-benchmark parameterization, …).
                assert error.rule
                continue
        assert len(bike.to_dict()) == 26
        read += 1
    assert read > 20
    # TOML, JSON and JBike6 .m written by the library and read back.
    crown = whipple.Bicycle.preset("schwinn-crown")
    for fmt in ("toml", "json", "m"):
        again = whipple.Bicycle.from_text(crown.to_text(fmt), fmt)
        assert again.to_dict() == crown.to_dict()
    assert whipple.Bicycle.from_text(benchmark.to_text("bp-txt"), "bp-txt").to_dict() == benchmark.to_dict()


def test_from_file_detects_the_format(tmp_path, benchmark):
    p = tmp_path / "mine.toml"
    p.write_text(benchmark.to_text("toml"))
    bike = whipple.Bicycle.from_file(p)
    assert bike.to_dict() == benchmark.to_dict()
    bp = tmp_path / "FisherBenchmark.txt"
    bp.write_bytes((DATA / "bicycleparameters" / "FisherBenchmark.txt").read_bytes())
    fisher = whipple.Bicycle.from_file(bp)
    assert fisher.name == "Fisher" and fisher.sigma["IBxx"] > 0


def test_measured_bicycle_warns_and_strict_refuses():
    path = DATA / "bicycleparameters" / "BrowserBenchmark.txt"
    with pytest.warns(whipple.ParameterWarning, match="triangle"):
        bike = whipple.Bicycle.from_file(path)
    assert any(n["severity"] == "warning" for n in bike.notices)
    with pytest.raises(whipple.StrictError) as info:
        whipple.Bicycle.from_file(path, strict=True)
    assert info.value.field


def test_repr_and_html(benchmark):
    assert "benchmark" in repr(benchmark) and "lam=0.314159" in repr(benchmark)
    page = benchmark._repr_html_()
    assert "<table>" in page and "IBxx" in page and "I_Bxx" in page
    assert "<table>" in benchmark.critical_speeds()._repr_html_()
    text = str(benchmark.critical_speeds())
    assert f"{WEAVE_SPEED:.5f}" in text and f"{CAPSIZE_SPEED:.5f}" in text


def test_unresolved_and_range_ends_are_reported():
    """The two-mass skate is self-stable from its weave speed on; at millions of m/s round-off
    can no longer tell (reported as unresolved, never as a number)."""
    skate = whipple.Bicycle.preset("two-mass-skate")
    s = skate.critical_speeds()
    assert s.unresolved and math.isinf(s.unresolved[-1][1])
    assert "unresolved by round-off" in str(s) and "no upper end" in str(s)
    bounded = skate.critical_speeds(0.0, 100.0)
    assert bounded.stable_ranges[-1][1] == 100.0 and not bounded.unresolved


def test_presets_formats_table():
    names = [p["name"] for p in whipple.presets()]
    assert "benchmark" in names and all(p["source"] for p in whipple.presets())
    assert {f["name"] for f in whipple.formats()} == {"toml", "json", "m", "bp-txt", "hc-txt", "yaml"}
    table = whipple.parameter_table()
    assert [r["key"] for r in table] == list(whipple.BENCHMARK_KEYS)
    assert {r["key"] for r in table if not r["linear"]} == {"IByy", "IHyy"}


def test_sensitivities_against_central_difference(benchmark):
    s = benchmark.sensitivities(speed=5.0)
    row = s["c"]
    h = 1e-6
    up = benchmark.replace(c=0.08 + h).critical_speeds().v_w
    down = benchmark.replace(c=0.08 - h).critical_speeds().v_w
    assert row["d_v_w"] == pytest.approx((up - down) / (2 * h), rel=1e-7)
    assert s.d_v_w.shape == (26,) and s.d_v_w.dtype == np.float64
    # The columns are read from the library's records (the server's /api/sensitivity keys).
    d = s.to_dict()
    record = next(p for p in d["parameters"] if p["key"] == "c")
    assert record["weave_speed"] == row["d_v_w"] and record["capsize_speed"] == row["d_v_c"]
    assert record["weave_speed_elasticity"] == row["elasticity_v_w"]
    assert d["critical"]["weave_speed"] == s.v_w == benchmark.critical_speeds().v_w
    assert d["form"] == "benchmark" and d["speed"] == 5.0
    assert s.stable_range == tuple(d["stable_range"])


def test_gil_is_released_for_batches(benchmark):
    """Two threads computing sweeps at once both finish with the same numbers."""
    import threading

    v = np.linspace(0, 10, 200_000)
    out = {}

    def work(k):
        out[k] = benchmark.state_space(v)[0]

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(out[0], out[1])


def test_from_file_reads_at_most_the_file_limit(tmp_path):
    """A device that never ends (/dev/zero) or a huge file is refused at the bound, not read into
    memory; the same bound as the command's --bike."""
    limit = whipple._whipple.MAX_FILE_BYTES
    assert limit == 4 << 20
    with pytest.raises(whipple.LimitError, match="MiB"):
        whipple.Bicycle.from_file("/dev/zero")
    big = tmp_path / "big.toml"
    big.write_bytes(b"# padding\n" * (limit // 10 + 1))
    with pytest.raises(whipple.LimitError, match="is it the right file"):
        whipple.Bicycle.from_file(big)
    with pytest.raises(whipple.LimitError):
        whipple.Bicycle.from_text("#" * (limit + 1), "toml")


def test_a_decimal_comma_is_an_error_not_an_average():
    """`w = 1,02` in a BicycleParameters file was averaged to 1.5; now it is refused with the
    line, the column and the fix."""
    with pytest.raises(whipple.ParseError, match=r"decimal comma.*`1\.02`") as info:
        whipple.Bicycle.from_text("w = 1,02\n", "bp-txt")
    assert info.value.line == 1 and info.value.column == 5
