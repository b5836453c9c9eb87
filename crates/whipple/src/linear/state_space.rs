//! First-order form of the linearized model at one forward speed.

use nalgebra::{Matrix2, Matrix4, Matrix4x2};

use super::Canonical;
use crate::error::{Error, Result};

/// Index of lean φ in the state x = [φ, δ, φ̇, δ̇].
pub const LEAN: usize = 0;
/// Index of steer δ in the state.
pub const STEER: usize = 1;
/// Index of lean rate φ̇ in the state.
pub const LEAN_RATE: usize = 2;
/// Index of steer rate δ̇ in the state.
pub const STEER_RATE: usize = 3;

/// ẋ = A x + B f for x = [φ, δ, φ̇, δ̇] and f = [T_φ, T_δ]:
/// A = [[0, I], [−M⁻¹(g K₀ + v² K₂), −v M⁻¹ C₁]], B = [[0], [M⁻¹]].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateSpace {
    /// The forward speed v [m/s] this was built for.
    pub speed: f64,
    /// A: the state matrix.
    pub a: Matrix4<f64>,
    /// B: the input matrix for [lean torque, steer torque].
    pub b: Matrix4x2<f64>,
}

impl StateSpace {
    /// A and B at forward speed `speed` (any finite value; negative is riding backwards).
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, linear::{Canonical, StateSpace}};
    /// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    /// let ss = StateSpace::new(&canonical, 5.0)?;
    /// assert_eq!(ss.a[(0, 2)], 1.0);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn new(canonical: &Canonical, speed: f64) -> Result<Self> {
        if !speed.is_finite() {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!("must be a finite number, got {speed}"),
            });
        }
        let m_inv = inverse(&canonical.m)?;
        let k = canonical.k0 * canonical.g + canonical.k2 * (speed * speed);
        let stiffness = -(m_inv * k);
        let damping = -(m_inv * canonical.c1) * speed;
        let mut a = Matrix4::zeros();
        a[(LEAN, LEAN_RATE)] = 1.0;
        a[(STEER, STEER_RATE)] = 1.0;
        a.fixed_view_mut::<2, 2>(2, 0).copy_from(&stiffness);
        a.fixed_view_mut::<2, 2>(2, 2).copy_from(&damping);
        let mut b = Matrix4x2::zeros();
        b.fixed_view_mut::<2, 2>(2, 0).copy_from(&m_inv);
        Ok(StateSpace { speed, a, b })
    }
}

/// The inverse of a symmetric positive definite 2×2 mass matrix.
fn inverse(m: &Matrix2<f64>) -> Result<Matrix2<f64>> {
    let det = m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)];
    if !(det.is_finite() && det > 0.0) {
        return Err(Error::InvalidBicycle {
            fields: "mass matrix".into(),
            rule: format!("M must be positive definite, det M = {det:e}"),
        });
    }
    Ok(Matrix2::new(m[(1, 1)], -m[(0, 1)], -m[(1, 0)], m[(0, 0)]) / det)
}
