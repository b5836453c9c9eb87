//! Polynomials in s (or in x = ω²), lowest power first: the one home of the polynomial
//! arithmetic of the transfer functions ([`super::transfer`]), Hess's loops
//! ([`super::human_loops`]) and the handling quality metric ([`super::handling`]).
//!
//! Each coefficient is kept with the sum of the absolute values of the terms it was formed
//! from, its size: a coefficient within round-off of its size is an exact cancellation
//! ([`Poly::negligible`]), and the sizes bound the round-off of coefficients handed to the
//! certified root finder ([`crate::analysis::roots::real_roots`]). Where only the values matter
//! the sizes come along unused. Values are evaluated by the root finder's Horner scheme
//! ([`crate::analysis::roots::horner`]).

use crate::analysis::eigen::Complex64;
use crate::analysis::roots::horner;

/// A polynomial, lowest power first, each coefficient as (value, size): the size is the sum of
/// the absolute values of the terms the value was formed from. Empty is the zero polynomial.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Poly(Vec<(f64, f64)>);

impl Poly {
    /// The constant x.
    pub(crate) fn constant(x: f64) -> Self {
        Poly(vec![(x, x.abs())])
    }

    /// The zero polynomial (no coefficients).
    pub(crate) fn zero() -> Self {
        Poly(Vec::new())
    }

    /// Exact coefficients, lowest power first: each its own size.
    pub(crate) fn from_coefficients(c: &[f64]) -> Self {
        Poly(c.iter().map(|x| (*x, x.abs())).collect())
    }

    /// Coefficients with their sizes, lowest power first.
    pub(crate) fn from_terms(terms: Vec<(f64, f64)>) -> Self {
        Poly(terms)
    }

    /// The coefficients with their sizes, lowest power first.
    pub(crate) fn terms(&self) -> &[(f64, f64)] {
        &self.0
    }

    /// The coefficients with their sizes, lowest power first.
    pub(crate) fn into_terms(self) -> Vec<(f64, f64)> {
        self.0
    }

    /// The coefficients' values, lowest power first.
    pub(crate) fn values(&self) -> Vec<f64> {
        self.0.iter().map(|(x, _)| *x).collect()
    }

    /// The number of coefficients (the degree plus one; 0 for the zero polynomial).
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether this is the zero polynomial (no coefficients).
    pub(crate) fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Coefficient by coefficient, `f` of the two (a missing coefficient is (0, 0)).
    fn zip_with(&self, other: &Poly, f: impl Fn((f64, f64), (f64, f64)) -> (f64, f64)) -> Poly {
        let n = self.0.len().max(other.0.len());
        Poly(
            (0..n)
                .map(|k| {
                    let a = self.0.get(k).copied().unwrap_or((0.0, 0.0));
                    let b = other.0.get(k).copied().unwrap_or((0.0, 0.0));
                    f(a, b)
                })
                .collect(),
        )
    }

    /// self + other.
    pub(crate) fn add(&self, other: &Poly) -> Poly {
        self.zip_with(other, |(a, ma), (b, mb)| (a + b, ma + mb))
    }

    /// self + k other, each coefficient formed as a + k b.
    pub(crate) fn add_scaled(&self, other: &Poly, k: f64) -> Poly {
        self.zip_with(other, |(a, ma), (b, mb)| (a + k * b, ma + k.abs() * mb))
    }

    /// self × other.
    pub(crate) fn mul(&self, other: &Poly) -> Poly {
        if self.0.is_empty() || other.0.is_empty() {
            return Poly::zero();
        }
        let mut out = vec![(0.0, 0.0); self.0.len() + other.0.len() - 1];
        for (i, (a, ma)) in self.0.iter().enumerate() {
            for (j, (b, mb)) in other.0.iter().enumerate() {
                out[i + j].0 += a * b;
                out[i + j].1 += ma * mb;
            }
        }
        Poly(out)
    }

    /// x self.
    pub(crate) fn scale(&self, x: f64) -> Poly {
        Poly(self.0.iter().map(|(a, m)| (a * x, m * x.abs())).collect())
    }

    /// Times s^k (the zero polynomial stays empty).
    pub(crate) fn shift(&self, k: usize) -> Poly {
        if self.0.is_empty() {
            return Poly::zero();
        }
        let mut out = vec![(0.0, 0.0); k];
        out.extend_from_slice(&self.0);
        Poly(out)
    }

    /// |p(jω)|² as a polynomial in x = ω²: the coefficient of xᵐ is Σ_{i+j=2m} (−1)^{m+j} pᵢ pⱼ.
    pub(crate) fn magnitude_squared(&self) -> Poly {
        let p = &self.0;
        if p.is_empty() {
            return Poly::zero();
        }
        let n = p.len() - 1;
        Poly(
            (0..=n)
                .map(|m| {
                    let mut value = 0.0;
                    let mut size = 0.0;
                    for i in 0..=(2 * m).min(n) {
                        let j = 2 * m - i;
                        if j > n {
                            continue;
                        }
                        let sign = if (m + j) % 2 == 0 { 1.0 } else { -1.0 };
                        value += sign * p[i].0 * p[j].0;
                        size += p[i].1 * p[j].1;
                    }
                    (value, size)
                })
                .collect(),
        )
    }

    /// The derivative.
    pub(crate) fn derivative(&self) -> Poly {
        Poly(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, (x, m))| (k as f64 * x, k as f64 * m))
                .collect(),
        )
    }

    /// A coefficient is an exact cancellation when it is within round-off of its terms' size.
    pub(crate) fn negligible((value, size): (f64, f64)) -> bool {
        value.abs() <= 64.0 * f64::EPSILON * size
    }
}

/// Σ `c[k]` zᵏ (lowest power first) by Horner's scheme; 0 for no coefficients.
pub(crate) fn eval(c: &[f64], z: Complex64) -> Complex64 {
    if c.is_empty() {
        return Complex64::new(0.0, 0.0);
    }
    horner(c, z).0
}

/// N(s)/D(s) (lowest powers first), in 1/s beyond |s| = 1 so that neither overflows; 0 when N
/// has no coefficients.
pub(crate) fn ratio(n: &[f64], d: &[f64], s: Complex64) -> Complex64 {
    if n.is_empty() {
        return Complex64::new(0.0, 0.0);
    }
    if crate::math::norm(s) <= 1.0 || d.is_empty() {
        return eval(n, s) / eval(d, s);
    }
    let w = s.inv();
    let reversed = |c: &[f64]| c.iter().rev().copied().collect::<Vec<f64>>();
    let excess = n.len() as i32 - d.len() as i32;
    s.powi(excess) * eval(&reversed(n), w) / eval(&reversed(d), w)
}
