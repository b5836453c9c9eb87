"""Published values from Python: Meijaard, Papadopoulos, Ruina & Schwab 2007, "Linearized
dynamics equations for the balance and steer of a bicycle: a benchmark and review", Proc. R.
Soc. A 463:1955–1982 (doi:10.1098/rspa.2007.1857): the canonical matrices of §5 and the
eigenvalues and critical speeds of Table 2, to the tolerances the core's own tests use."""

import numpy as np
import pytest

import whipple
from reference import (AT_REST, C1, CAPSIZE_SPEED, DOUBLE_ROOT_EIGENVALUE, DOUBLE_ROOT_SPEED, K0,
                       K2, M, TABLE_2, WEAVE_FREQUENCY, WEAVE_SPEED)


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
    assert abs(s.v_d - DOUBLE_ROOT_SPEED) < 1e-12
    assert abs(s.double_root_eigenvalue - DOUBLE_ROOT_EIGENVALUE) < 1e-9
    assert abs(s.v_w - WEAVE_SPEED) < 1e-12
    assert abs(s.weave_frequency - WEAVE_FREQUENCY) < 1e-12
    assert abs(s.v_c - CAPSIZE_SPEED) < 1e-12
    assert len(s.stable_ranges) == 1
    lo, hi = s.stable_ranges[0]
    assert abs(lo - WEAVE_SPEED) < 1e-12 and abs(hi - CAPSIZE_SPEED) < 1e-12
    # No parameter carries a sigma: none is reported.
    assert s.v_w_sigma is None and not s.uncertain


def test_canonical_matrices_section_5(benchmark):
    m, c1, k0, k2 = benchmark.canonical()
    assert np.allclose(m, M, rtol=0, atol=1e-13)
    assert np.allclose(c1, C1, rtol=0, atol=1e-13)
    assert np.allclose(k0, K0, rtol=0, atol=1e-13)
    assert np.allclose(k2, K2, rtol=0, atol=1e-13)


def test_nonlinear_model_linearizes_to_the_benchmark(benchmark):
    """Exact derivatives of the non-linear model reduced to lean and steer give the linear A(v)."""
    v = np.linspace(0.5, 10.0, 20)
    a_nonlinear = benchmark.nonlinear_state_matrix(v)
    a_linear, _ = benchmark.state_space(v)
    scale = np.abs(a_linear).max(axis=(1, 2))
    assert np.all(np.abs(a_nonlinear - a_linear).max(axis=(1, 2)) <= 1e-12 * scale)
    cmp = benchmark.compare(v[::4], methods=("ad",))
    assert np.all(cmp["ad"]["max_abs_diff"] < 1e-11)
