//! Stage 5 of the forward dynamics: the saddle-point system
//! `[A Gᵀ; G 0][x; y] = [f; γ]` with A (N × N, N = 6 or 9) symmetric and positive definite on
//! the null space of G (M × N, full row rank), by UᵀDU factors (Cholesky without square roots)
//! of A and of the Schur complement `G A⁻¹ Gᵀ`:
//! no pivoting, no branch on values other than the positivity checks of the factorizations,
//! so dual numbers pass through it exactly.
//!
//! When A itself may be singular (a wheel without spin inertia), it is first replaced by
//! `A + ρ GᵀG` and f by `f + ρ Gᵀγ` (augmented Lagrangian): on `G x = γ` both systems have the
//! same solution, and the augmented matrix is positive definite whenever the saddle-point
//! matrix is regular.

use crate::math::Real;
use nalgebra::{SMatrix, SVector};

/// In-place factorization `A = UᵀDU` (U unit upper triangular in the strict upper triangle,
/// D diagonal), without square roots: the pivots are a chain of dependent operations, and a
/// square root would lengthen every link. Returns the reciprocals of D (the solves multiply by
/// them instead of dividing); None when A is not (numerically) positive definite. Every loop
/// bound is a constant of N, so the compiler unrolls the small factorizations completely.
#[inline(always)]
fn factor<T: Real, const N: usize>(a: &mut SMatrix<T, N, N>) -> Option<[T; N]> {
    let mut inverse = [T::zero(); N];
    for j in 0..N {
        // w_i = d_i u_ij, then u_ij = w_i / d_i.
        let mut w = [T::zero(); N];
        for i in 0..j {
            let mut s = a[(i, j)];
            for k in 0..i {
                s -= a[(k, i)] * w[k];
            }
            w[i] = s;
        }
        let mut d = a[(j, j)];
        for i in 0..j {
            let u = w[i] * inverse[i];
            a[(i, j)] = u;
            d -= u * w[i];
        }
        if d <= T::zero() || !d.is_finite() {
            return None;
        }
        a[(j, j)] = d;
        inverse[j] = T::one() / d;
    }
    Some(inverse)
}

/// Solves Uᵀ y = b in place (U unit upper triangular from [`factor`]).
#[inline(always)]
fn forward_substitute<T: Real, const N: usize>(u: &SMatrix<T, N, N>, b: &mut [T; N]) {
    for i in 0..N {
        let mut s = b[i];
        for k in 0..i {
            s -= u[(k, i)] * b[k];
        }
        b[i] = s;
    }
}

/// Solves U x = b in place.
#[inline(always)]
fn back_substitute<T: Real, const N: usize>(u: &SMatrix<T, N, N>, b: &mut [T; N]) {
    for i in (0..N).rev() {
        let mut s = b[i];
        for k in i + 1..N {
            s -= u[(i, k)] * b[k];
        }
        b[i] = s;
    }
}

/// Multiplies b entry by entry by the reciprocals of D (the diagonal solve).
#[inline(always)]
fn scale<T: Real, const N: usize>(b: &mut [T; N], d_inverse: &[T; N]) {
    for (entry, &inverse) in b.iter_mut().zip(d_inverse) {
        *entry *= inverse;
    }
}

/// Solves `[A Gᵀ; G 0][x; y] = [f; γ]`; `rho` > 0 augments A by ρ GᵀG first (see the module
/// documentation). None when a factorization fails (the system is singular).
pub(crate) fn solve<T: Real, const N: usize, const M: usize>(
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
    let d_inverse = factor(&mut l)?;
    // Y = U⁻ᵀ Gᵀ, column by column; z = U⁻ᵀ f.
    let mut y = [[T::zero(); N]; M];
    for (j, column) in y.iter_mut().enumerate() {
        for (i, entry) in column.iter_mut().enumerate() {
            *entry = g[(j, i)];
        }
        forward_substitute(&l, column);
    }
    let mut z: [T; N] = f.into();
    forward_substitute(&l, &mut z);
    // Schur complement S = G A⁻¹ Gᵀ = Yᵀ D⁻¹ Y; S λ = G A⁻¹ f − γ = Yᵀ D⁻¹ z − γ.
    let mut dz = z;
    scale(&mut dz, &d_inverse);
    let mut s = SMatrix::<T, M, M>::zeros();
    let mut lambda = [T::zero(); M];
    for a in 0..M {
        for b in a..M {
            let mut sum = T::zero();
            for k in 0..N {
                sum += y[a][k] * d_inverse[k] * y[b][k];
            }
            s[(a, b)] = sum;
        }
        let mut sum = -gamma[a];
        for k in 0..N {
            sum += y[a][k] * dz[k];
        }
        lambda[a] = sum;
    }
    let s_inverse = factor(&mut s)?;
    forward_substitute(&s, &mut lambda);
    scale(&mut lambda, &s_inverse);
    back_substitute(&s, &mut lambda);
    // x = A⁻¹ (f − Gᵀ λ) = U⁻¹ D⁻¹ (z − Y λ).
    for (k, column) in y.iter().enumerate() {
        for i in 0..N {
            z[i] -= column[i] * lambda[k];
        }
    }
    scale(&mut z, &d_inverse);
    back_substitute(&l, &mut z);
    Some((SVector::from(z), SVector::from(lambda)))
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
