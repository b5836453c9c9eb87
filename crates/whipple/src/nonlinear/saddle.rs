//! Stage 5 of the forward dynamics: the saddle-point system
//! `[A Gᵀ; G 0][x; y] = [f; γ]` with A (9 × 9) symmetric and positive definite on the null space
//! of G (6 × 9, full row rank), by Cholesky factors and the Schur complement `G A⁻¹ Gᵀ`:
//! no pivoting, no branch on values other than the positivity checks of the factorizations,
//! so dual numbers pass through it exactly.
//!
//! When A itself may be singular (a wheel without spin inertia), it is first replaced by
//! `A + ρ GᵀG` and f by `f + ρ Gᵀγ` (augmented Lagrangian): on `G x = γ` both systems have the
//! same solution, and the augmented matrix is positive definite whenever the saddle-point
//! matrix is regular.

use nalgebra::{RealField, SMatrix, SVector};

/// In-place Cholesky factorization `A = L Lᵀ` (L in the lower triangle). False when A is not
/// (numerically) positive definite.
fn cholesky<T: RealField + Copy, const N: usize>(a: &mut SMatrix<T, N, N>) -> bool {
    for j in 0..N {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        if d <= T::zero() || !d.is_finite() {
            return false;
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..N {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = s / d;
        }
    }
    true
}

/// Solves L y = b (L lower triangular from [`cholesky`]).
fn forward_substitute<T: RealField + Copy, const N: usize>(
    l: &SMatrix<T, N, N>,
    b: &mut SVector<T, N>,
) {
    for i in 0..N {
        let mut s = b[i];
        for k in 0..i {
            s -= l[(i, k)] * b[k];
        }
        b[i] = s / l[(i, i)];
    }
}

/// Solves Lᵀ x = b.
fn back_substitute<T: RealField + Copy, const N: usize>(
    l: &SMatrix<T, N, N>,
    b: &mut SVector<T, N>,
) {
    for i in (0..N).rev() {
        let mut s = b[i];
        for k in i + 1..N {
            s -= l[(k, i)] * b[k];
        }
        b[i] = s / l[(i, i)];
    }
}

/// Solves `[A Gᵀ; G 0][x; y] = [f; γ]`; `rho` > 0 augments A by ρ GᵀG first (see the module
/// documentation). None when a factorization fails (the system is singular).
pub(crate) fn solve<T: RealField + Copy, const N: usize, const M: usize>(
    a: &SMatrix<T, N, N>,
    g: &SMatrix<T, M, N>,
    f: &SVector<T, N>,
    gamma: &SVector<T, M>,
    rho: f64,
) -> Option<(SVector<T, N>, SVector<T, M>)> {
    let mut l = *a;
    let mut f = *f;
    if rho > 0.0 {
        let rho: T = nalgebra::convert(rho);
        l += g.transpose() * g * rho;
        f += g.transpose() * gamma * rho;
    }
    if !cholesky(&mut l) {
        return None;
    }
    // Y = L⁻¹ Gᵀ, column by column; z = L⁻¹ f.
    let mut y = g.transpose();
    for j in 0..M {
        let mut col = y.column(j).into_owned();
        forward_substitute(&l, &mut col);
        y.set_column(j, &col);
    }
    let mut z = f;
    forward_substitute(&l, &mut z);
    // Schur complement S = G A⁻¹ Gᵀ = Yᵀ Y; S λ = G A⁻¹ f − γ = Yᵀ z − γ.
    let mut s = y.transpose() * y;
    let mut lambda = y.transpose() * z - gamma;
    if !cholesky(&mut s) {
        return None;
    }
    forward_substitute(&s, &mut lambda);
    back_substitute(&s, &mut lambda);
    // x = A⁻¹ (f − Gᵀ λ) = L⁻ᵀ (z − Y λ).
    let mut x = z - y * lambda;
    back_substitute(&l, &mut x);
    Some((x, lambda))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector2, Vector3};

    #[test]
    fn solves_a_saddle_point_system_with_singular_a() {
        // A singular in the constrained direction; [A Gᵀ; G 0] regular.
        let a = Matrix3::new(2.0, 0.5, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0);
        let g = SMatrix::<f64, 2, 3>::new(0.0, 0.0, 1.0, 1.0, 1.0, 0.0);
        let f = Vector3::new(1.0, -2.0, 0.5);
        let gamma = Vector2::new(0.3, -0.1);
        assert!(solve(&a, &g, &f, &gamma, 0.0).is_none());
        let (x, y) = solve(&a, &g, &f, &gamma, 1.0).expect("regular system");
        assert!((a * x + g.transpose() * y - f).amax() < 1e-14);
        assert!((g * x - gamma).amax() < 1e-14);
    }
}
