//! The classical fourth-order Runge–Kutta method (Kutta 1901), fixed step:
//! k₁ = f(t, y), k₂ = f(t + h/2, y + h k₁/2), k₃ = f(t + h/2, y + h k₂/2), k₄ = f(t + h, y + h k₃),
//! y₁ = y + h (k₁ + 2k₂ + 2k₃ + k₄)/6.

use nalgebra::SVector;

use super::OdeSystem;
use crate::error::Result;

/// One step when k₁ = f(t, y) is already known (it is, after the caller evaluated the state).
pub(crate) fn step_with_slope<S: OdeSystem<N>, const N: usize>(
    system: &S,
    t: f64,
    y: &SVector<f64, N>,
    k1: &SVector<f64, N>,
    h: f64,
) -> Result<SVector<f64, N>> {
    let half = 0.5 * h;
    let k2 = system.rhs(t + half, &(y + k1 * half))?;
    let k3 = system.rhs(t + half, &(y + k2 * half))?;
    let k4 = system.rhs(t + h, &(y + k3 * h))?;
    Ok(y + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0))
}

/// Number of steps of at most `dt` covering `span` (the last may be shorter; a remainder
/// below 1e-9 dt is absorbed).
pub(crate) fn step_count(span: f64, dt: f64) -> usize {
    if span <= 0.0 {
        return 0;
    }
    let n = span / dt;
    let whole = n.floor();
    // Steps are counted in f64 and converted once; span/dt is finite and non-negative here.
    (if n - whole > 1e-9 {
        whole + 1.0
    } else {
        whole.max(1.0)
    }) as usize
}
