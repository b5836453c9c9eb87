//! Which eigenvalues are the lean and steer ones: the quartic of a lean–steer matrix, faer's
//! general eigensolver for the full state, and an optimal assignment of candidates to the
//! linear model's eigenvalues (the full state has no other way to say which four of its 48
//! are lean and steer).

use nalgebra::{Complex, Matrix4, SMatrix};

use crate::analysis::eigen::{Complex64, quartic_roots};
use crate::error::{Error, Result};

/// The four eigenvalues of a lean–steer state matrix A = [[0, I], [X, Y]] as the roots of
/// det(λ²I − λY − X), by the same quartic solver as the linear model's; sorted by decreasing
/// real part. Only the lower two rows of `a` enter (the upper two are [0 I] by construction).
pub fn lean_steer_eigenvalues(a: &Matrix4<f64>) -> Result<[Complex64; 4]> {
    let x = |i: usize, j: usize| a[(2 + i, j)];
    let y = |i: usize, j: usize| a[(2 + i, 2 + j)];
    let a0 = x(0, 0) * x(1, 1) - x(0, 1) * x(1, 0);
    let a1 = y(0, 0) * x(1, 1) + y(1, 1) * x(0, 0) - y(0, 1) * x(1, 0) - x(0, 1) * y(1, 0);
    let a2 = y(0, 0) * y(1, 1) - x(0, 0) - x(1, 1) - y(0, 1) * y(1, 0);
    let a3 = -(y(0, 0) + y(1, 1));
    quartic_roots(&[a0, a1, a2, a3, 1.0])
}

/// The eigenvalues of a square matrix (faer's general eigensolver, bounded).
pub fn general_eigenvalues<const N: usize>(a: &SMatrix<f64, N, N>) -> Result<Vec<Complex64>> {
    let m = faer::Mat::<f64>::from_fn(N, N, |i, j| a[(i, j)]);
    let values = m.eigenvalues().map_err(faer_failure)?;
    Ok(values.iter().map(|z| Complex::new(z.re, z.im)).collect())
}

/// faer's reason for failing, kept in the error.
pub(crate) fn faer_failure(error: faer::linalg::evd::EvdError) -> Error {
    match error {
        faer::linalg::evd::EvdError::NoConvergence => Error::NoConvergence {
            method: "faer's general eigensolver (QR iteration): no convergence within its \
                     iteration bound",
            iterations: 0,
            residual: f64::NAN,
        },
    }
}

/// Assigns to each of the four `targets` a distinct member of `candidates`, minimising the sum
/// of the distances (an optimal assignment). Returns the candidates' indices.
///
/// Only the four nearest candidates of each target can take part in an optimal assignment
/// (were one assigned further away, one of its four nearest would be free, and closer), so the
/// search is over at most 4⁴ combinations.
pub(crate) fn assign(targets: &[Complex64; 4], candidates: &[Complex64]) -> Result<[usize; 4]> {
    if candidates.len() < 4 {
        return Err(Error::InvalidArgument {
            what: "candidates",
            rule: format!("need at least four eigenvalues, got {}", candidates.len()),
        });
    }
    let nearest: [Vec<usize>; 4] = std::array::from_fn(|t| {
        let mut idx: Vec<usize> = (0..candidates.len()).collect();
        idx.sort_by(|&a, &b| {
            crate::math::norm(candidates[a] - targets[t])
                .total_cmp(&crate::math::norm(candidates[b] - targets[t]))
        });
        idx.truncate(4);
        idx
    });
    let mut best = ([0usize; 4], f64::INFINITY);
    for a in &nearest[0] {
        for b in &nearest[1] {
            for c in &nearest[2] {
                for d in &nearest[3] {
                    let pick = [*a, *b, *c, *d];
                    if (0..4).any(|i| (0..i).any(|j| pick[i] == pick[j])) {
                        continue;
                    }
                    let cost: f64 = (0..4)
                        .map(|i| crate::math::norm(candidates[pick[i]] - targets[i]))
                        .sum();
                    if cost < best.1 {
                        best = (pick, cost);
                    }
                }
            }
        }
    }
    if best.1.is_finite() {
        Ok(best.0)
    } else {
        Err(Error::NonFinite {
            context: "assignment of eigenvalues".into(),
        })
    }
}

/// The members of `candidates` assigned to `targets` (see `assign`), in the targets' order.
pub fn pick(targets: &[Complex64; 4], candidates: &[Complex64]) -> Result<[Complex64; 4]> {
    Ok(assign(targets, candidates)?.map(|i| candidates[i]))
}

/// The largest |λ_method − λ_linear| over four matched pairs.
pub fn max_abs_diff(a: &[Complex64; 4], b: &[Complex64; 4]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| crate::math::norm(x - y))
        .fold(0.0, f64::max)
}
