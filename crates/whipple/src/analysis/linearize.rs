//! Jacobians of a vector field ẋ = f(x) at a point: by central differences with the step
//! chosen per column by decimation (the method of Dressel's JBike6 study), and exactly by
//! forward-mode automatic differentiation (dual numbers through the same model code, no
//! derivative written by hand).
//!
//! A model offers itself to both through [`VectorField`]: one generic evaluation `f::<T>(x)`
//! for `T = f64` (differences) and `T = Dual64` (exact derivatives).
//!
//! ```
//! use nalgebra::{SVector, Vector2};
//! use whipple::advanced::linearize::{central_differences, jacobian, FdSettings, VectorField};
//! use whipple::math::{self, Real};
//!
//! /// The pendulum θ̈ = −sin θ in first-order form.
//! struct Pendulum;
//! impl VectorField<2> for Pendulum {
//!     fn eval<T: Real>(&self, x: &SVector<T, 2>) -> whipple::Result<SVector<T, 2>> {
//!         Ok(Vector2::new(x[1], -math::sin(x[0])))
//!     }
//! }
//! let x0 = Vector2::new(0.5, 0.0);
//! let exact = jacobian(&Pendulum, &x0)?;
//! assert_eq!(exact[(1, 0)], -math::cos(0.5f64));
//! let fd = central_differences(|x| Pendulum.eval(x), &x0, &FdSettings::default())?;
//! assert!((fd.jacobian - exact).amax() < 1e-9);
//! # Ok::<(), whipple::Error>(())
//! ```

use crate::math::Real;
use nalgebra::{SMatrix, SVector};
use num_dual::Dual64;

use crate::error::{Error, Result};

/// A vector field ẋ = f(x) on N states, evaluable on any scalar type (f64, dual numbers).
pub trait VectorField<const N: usize> {
    /// f(x).
    fn eval<T: Real>(&self, x: &SVector<T, N>) -> Result<SVector<T, N>>;
}

/// The exact Jacobian ∂f/∂x at `x0` by forward-mode automatic differentiation: one pass of
/// `f::<Dual64>` per column, seeded with the unit vector of that column. Exact up to the
/// round-off of evaluating f itself; no step to choose.
pub fn jacobian<const N: usize>(
    f: &impl VectorField<N>,
    x0: &SVector<f64, N>,
) -> Result<SMatrix<f64, N, N>> {
    let mut a = SMatrix::<f64, N, N>::zeros();
    for j in 0..N {
        let x = SVector::<Dual64, N>::from_fn(|i, _| {
            Dual64::new(x0[i], if i == j { 1.0 } else { 0.0 })
        });
        let fx = f.eval(&x)?;
        for i in 0..N {
            let d = fx[i].eps;
            if !d.is_finite() {
                return Err(Error::NonFinite {
                    context: format!("∂f{i}/∂x{j} by dual numbers"),
                });
            }
            a[(i, j)] = d;
        }
    }
    Ok(a)
}

/// Settings of [`central_differences`]: the study's step decimation.
///
/// For each column the step starts at `initial_step` and is divided by `decimation` until two
/// successive candidate columns agree to `tolerance` (relative to the column's largest entry,
/// at least 1), or until the change between successive candidates stops shrinking (round-off
/// has taken over from truncation), at most `max_decimations` times. The candidate that
/// changed least from its predecessor is kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FdSettings {
    /// First step, absolute (state variables in SI units). Default 1e-2.
    pub initial_step: f64,
    /// Factor by which the step shrinks at each decimation. Default 10 (the study's).
    pub decimation: f64,
    /// Upper bound on decimations per column. Default 12 (steps down to 1e-14).
    pub max_decimations: usize,
    /// Relative change between successive candidates accepted as converged. Default 1e-12.
    pub tolerance: f64,
}

impl Default for FdSettings {
    fn default() -> Self {
        FdSettings {
            initial_step: 1e-2,
            decimation: 10.0,
            max_decimations: 12,
            tolerance: 1e-12,
        }
    }
}

/// A Jacobian by central differences and the step kept for each column.
#[derive(Debug, Clone, PartialEq)]
pub struct FdJacobian<const N: usize> {
    /// ∂f/∂x, approximated.
    pub jacobian: SMatrix<f64, N, N>,
    /// The step h of each column.
    pub steps: [f64; N],
    /// The largest change between the kept candidate column and its predecessor, relative to
    /// the column's largest entry (at least 1): an estimate of the column's error.
    pub changes: [f64; N],
    /// Evaluations of f made.
    pub evaluations: usize,
}

/// The Jacobian at `x0` by central differences `(f(x0 + h eⱼ) − f(x0 − h eⱼ)) / 2h`, with h
/// chosen per column by decimation (see [`FdSettings`]). `f` may do more than evaluate the vector
/// field (the study projected each perturbed state onto the constraints first).
pub fn central_differences<const N: usize>(
    mut f: impl FnMut(&SVector<f64, N>) -> Result<SVector<f64, N>>,
    x0: &SVector<f64, N>,
    params: &FdSettings,
) -> Result<FdJacobian<N>> {
    if !(params.initial_step > 0.0
        && params.initial_step.is_finite()
        && params.decimation > 1.0
        && params.decimation.is_finite()
        && params.tolerance >= 0.0)
    {
        return Err(Error::InvalidArgument {
            what: "finite-difference settings",
            rule: format!("need initial_step > 0, decimation > 1, tolerance >= 0; got {params:?}"),
        });
    }
    let mut out = FdJacobian {
        jacobian: SMatrix::zeros(),
        steps: [0.0; N],
        changes: [0.0; N],
        evaluations: 0,
    };
    for j in 0..N {
        let mut column = |h: f64| -> Result<SVector<f64, N>> {
            let mut plus = *x0;
            let mut minus = *x0;
            plus[j] += h;
            minus[j] -= h;
            let c = (f(&plus)? - f(&minus)?) / (2.0 * h);
            if c.iter().all(|x| x.is_finite()) {
                Ok(c)
            } else {
                Err(Error::NonFinite {
                    context: format!("central difference of column {j} with step {h:e}"),
                })
            }
        };
        let mut h = params.initial_step;
        let mut previous = column(h)?;
        out.evaluations += 2;
        let mut best = (previous, h, f64::INFINITY);
        let mut last_change = f64::INFINITY;
        for _ in 0..params.max_decimations {
            h /= params.decimation;
            let candidate = column(h)?;
            out.evaluations += 2;
            let scale = candidate.amax().max(1.0);
            let change = (candidate - previous).amax() / scale;
            if change < best.2 {
                best = (candidate, h, change);
            }
            if change <= params.tolerance || change > last_change {
                break;
            }
            last_change = change;
            previous = candidate;
        }
        out.jacobian.set_column(j, &best.0);
        out.steps[j] = best.1;
        out.changes[j] = best.2;
    }
    Ok(out)
}
