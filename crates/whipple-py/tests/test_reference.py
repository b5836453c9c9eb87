"""Published values from Python: Meijaard, Papadopoulos, Ruina & Schwab 2007, "Linearized
dynamics equations for the balance and steer of a bicycle: a benchmark and review", Proc. R.
Soc. A 463:1955–1982 (doi:10.1098/rspa.2007.1857): the canonical matrices of §5 and the
eigenvalues and critical speeds of Table 2, to the tolerances the core's own tests use."""

import numpy as np
import pytest

import whipple

# Meijaard 2007, Table 2: (v, weave re, weave im, capsize, castering); the table carries
# round-off of up to about 6e-13.
TABLE_2 = [
    (1.0, 3.5269617099007, 0.8077402751993, -3.13423125066578, -7.11008014637442),
    (2.0, 2.68234517512745, 1.68066296590675, -3.07158645641514, -8.67387984831735),
    (3.0, 1.70675605663975, 2.31582447384325, -2.63366137253667, -10.3510146724592),
    (4.0, 0.41325331521125, 3.07910818603206, -1.42944427361326, -12.1586142657645),
    (5.0, -0.77534188219585, 4.46486771378823, -0.32286642900409, -14.0783896927982),
    (6.0, -1.52644486584142, 5.87673060598709, -0.0040669007697, -16.0853712309803),
    (7.0, -2.13875644258362, 7.19525913329805, 0.10268170574766, -18.15788466125262),
    (8.0, -2.69348683581097, 8.46037971396931, 0.14327879765713, -20.27940894394569),
    (9.0, -3.21675402252485, 9.69377351531791, 0.15790184030917, -22.43788559040858),
    (10.0, -3.72016840437287, 10.90681139476287, 0.16105338653172, -24.62459635017404),
]
# Meijaard 2007, Table 2: the eigenvalues at rest.
AT_REST = [5.53094371765393, 3.13164324790656, -3.13164324790656, -5.53094371765393]


def test_table_2_eigenvalues_to_1e_12(benchmark):
    v = np.array([row[0] for row in TABLE_2])
    e = benchmark.eig(v)
    assert e.modes == ["weave", "weave", "capsize", "castering"]
    for i, (_, re, im, capsize, castering) in enumerate(TABLE_2):
        lam = e.values[i]
        assert abs(lam[0] - complex(re, im)) < 1e-12
        assert abs(lam[1] - complex(re, -im)) < 1e-12
        assert abs(lam[2] - capsize) < 1e-12 and lam[2].imag == 0.0
        assert abs(lam[3] - castering) < 1e-12 and lam[3].imag == 0.0


def test_eigenvalues_at_rest(benchmark):
    values, _ = benchmark.eig(0.0, tracked=False)
    assert np.allclose(sorted(values.real, reverse=True), AT_REST, rtol=0, atol=1e-12)
    assert np.all(values.imag == 0.0)


def test_critical_speeds_table_2(benchmark):
    s = benchmark.critical_speeds()
    assert abs(s.v_d - 0.68428307889246) < 1e-12
    assert abs(s.double_root_eigenvalue - 3.7829040512932) < 1e-9
    assert abs(s.v_w - 4.29238253634111) < 1e-12
    assert abs(s.weave_frequency - 3.43503384866144) < 1e-12
    assert abs(s.v_c - 6.02426201538837) < 1e-12
    assert len(s.stable_ranges) == 1
    lo, hi = s.stable_ranges[0]
    assert abs(lo - 4.29238253634111) < 1e-12 and abs(hi - 6.02426201538837) < 1e-12
    # No parameter carries a sigma: none is reported.
    assert s.v_w_sigma is None and not s.uncertain


def test_canonical_matrices_section_5(benchmark):
    m, c1, k0, k2 = benchmark.canonical()
    assert np.allclose(m, [[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]],
                       rtol=0, atol=1e-13)
    assert np.allclose(c1, [[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]],
                       rtol=0, atol=1e-13)
    assert np.allclose(k0, [[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]],
                       rtol=0, atol=1e-13)
    assert np.allclose(k2, [[0.0, 76.59734589573222], [0.0, 2.65431523794604]], rtol=0, atol=1e-13)


def test_nonlinear_model_linearizes_to_the_benchmark(benchmark):
    """Exact derivatives of the non-linear model reduced to lean and steer give the linear A(v)."""
    v = np.linspace(0.5, 10.0, 20)
    a_nonlinear = benchmark.nonlinear_state_matrix(v)
    a_linear, _ = benchmark.state_space(v)
    scale = np.abs(a_linear).max(axis=(1, 2))
    assert np.all(np.abs(a_nonlinear - a_linear).max(axis=(1, 2)) <= 1e-12 * scale)
    cmp = benchmark.compare(v[::4], methods=("ad",))
    assert np.all(cmp["ad"]["max_abs_diff"] < 1e-11)
