//! The characteristic polynomial of the linearized model as a polynomial in both the eigenvalue
//! λ and the forward speed v: p(λ, v) = det(M λ² + v C₁ λ + g K₀ + v² K₂).
//!
//! Its roots in λ are the four eigenvalues of A(v) (det M > 0, so there are exactly four), and
//! its coefficients in λ are polynomials in v of degree ≤ 4. Stability questions become questions
//! about smooth polynomials in v (Routh–Hurwitz), which is how the critical speeds are found to
//! round-off.

use super::Canonical;

/// Degree in λ and in v.
const DEGREE: usize = 4;

/// p(λ, v) = Σ_k Σ_j `coefficients[k][j]` λᵏ vʲ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacteristicPolynomial {
    /// `coefficients[k][j]` multiplies λᵏ vʲ.
    pub coefficients: [[f64; DEGREE + 1]; DEGREE + 1],
}

type Bivariate = [[f64; DEGREE + 1]; DEGREE + 1];

fn multiply(a: &Bivariate, b: &Bivariate) -> Bivariate {
    let mut out = [[0.0; DEGREE + 1]; DEGREE + 1];
    for (ka, row_a) in a.iter().enumerate() {
        for (ja, &x) in row_a.iter().enumerate() {
            if x == 0.0 {
                continue;
            }
            for (kb, row_b) in b.iter().enumerate() {
                for (jb, &y) in row_b.iter().enumerate() {
                    if y != 0.0 && ka + kb <= DEGREE && ja + jb <= DEGREE {
                        out[ka + kb][ja + jb] += x * y;
                    }
                }
            }
        }
    }
    out
}

impl CharacteristicPolynomial {
    /// Expands det(M λ² + v C₁ λ + g K₀ + v² K₂).
    pub fn new(canonical: &Canonical) -> Self {
        let entry = |i: usize, j: usize| {
            let mut e = [[0.0; DEGREE + 1]; DEGREE + 1];
            e[2][0] = canonical.m[(i, j)];
            e[1][1] = canonical.c1[(i, j)];
            e[0][0] = canonical.g * canonical.k0[(i, j)];
            e[0][2] = canonical.k2[(i, j)];
            e
        };
        let d = multiply(&entry(0, 0), &entry(1, 1));
        let o = multiply(&entry(0, 1), &entry(1, 0));
        let mut coefficients = [[0.0; DEGREE + 1]; DEGREE + 1];
        for k in 0..=DEGREE {
            for j in 0..=DEGREE {
                coefficients[k][j] = d[k][j] - o[k][j];
            }
        }
        CharacteristicPolynomial { coefficients }
    }

    /// The coefficients in λ at speed v, lowest power first: p(λ) = Σ aₖ λᵏ.
    #[inline]
    pub fn at_speed(&self, v: f64) -> [f64; DEGREE + 1] {
        let mut a = [0.0; DEGREE + 1];
        for (k, row) in self.coefficients.iter().enumerate() {
            a[k] = row.iter().rev().fold(0.0, |acc, &c| acc * v + c);
        }
        a
    }

    /// The derivative of each coefficient with respect to v, lowest power of λ first.
    pub fn d_dv(&self, v: f64) -> [f64; DEGREE + 1] {
        let mut a = [0.0; DEGREE + 1];
        for (k, row) in self.coefficients.iter().enumerate() {
            a[k] = row
                .iter()
                .enumerate()
                .skip(1)
                .rev()
                .fold(0.0, |acc, (j, &c)| acc * v + j as f64 * c);
        }
        a
    }

    /// The third Hurwitz determinant Δ₃ = a₃a₂a₁ − a₄a₁² − a₀a₃² at speed v. With a₄ > 0, all
    /// four eigenvalues have negative real parts exactly when a₀, a₁, a₃ and Δ₃ are positive;
    /// Δ₃ vanishes where a complex pair crosses the imaginary axis.
    pub fn hurwitz_delta3(&self, v: f64) -> f64 {
        let a = self.at_speed(v);
        hurwitz_delta3(&a)
    }
}

/// Δ₃ of a quartic with coefficients `a` (lowest power first).
pub fn hurwitz_delta3(a: &[f64; 5]) -> f64 {
    a[3] * a[2] * a[1] - a[4] * a[1] * a[1] - a[0] * a[3] * a[3]
}

/// The discriminant of a quartic with coefficients `a` (lowest power first): positive when the
/// roots are all real or all complex, negative with two real roots and a complex pair, zero at a
/// multiple root.
pub fn discriminant(a: &[f64; 5]) -> f64 {
    let (e, d, c, b, a) = (a[0], a[1], a[2], a[3], a[4]);
    256.0 * a.powi(3) * e.powi(3) - 192.0 * a * a * b * d * e * e - 128.0 * a * a * c * c * e * e
        + 144.0 * a * a * c * d * d * e
        - 27.0 * a * a * d.powi(4)
        + 144.0 * a * b * b * c * e * e
        - 6.0 * a * b * b * d * d * e
        - 80.0 * a * b * c * c * d * e
        + 18.0 * a * b * c * d.powi(3)
        + 16.0 * a * c.powi(4) * e
        - 4.0 * a * c.powi(3) * d * d
        - 27.0 * b.powi(4) * e * e
        + 18.0 * b.powi(3) * c * d * e
        - 4.0 * b.powi(3) * d.powi(3)
        - 4.0 * b * b * c.powi(3) * e
        + b * b * c * c * d * d
}
