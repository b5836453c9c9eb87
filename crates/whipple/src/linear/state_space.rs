//! First-order form of the linearized model at one forward speed.

use nalgebra::{Matrix2, Matrix4, Matrix4x2, Vector4};

use super::Canonical;
use crate::error::{Error, Result};

/// Index of lean φ in the state x = [φ, δ, φ̇, δ̇].
pub(crate) const LEAN: usize = 0;
/// Index of steer δ in the state.
pub(crate) const STEER: usize = 1;
/// Index of lean rate φ̇ in the state.
pub(crate) const LEAN_RATE: usize = 2;
/// Index of steer rate δ̇ in the state.
pub(crate) const STEER_RATE: usize = 3;

/// ẋ = A x + B f for x = [φ, δ, φ̇, δ̇] and f = [T_φ, T_δ]:
/// `A = [[0, I], [−M⁻¹(g K₀ + v² K₂), −v M⁻¹ C₁]]`, `B = [[0], [M⁻¹]]`.
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
    /// use whipple::{BenchmarkParameters, Canonical};
    /// use whipple::advanced::linear::StateSpace;
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

    /// The free response of ẋ = A x (hands free, no torques) from `x0`: the states
    /// x(k Δt) = e^{A k Δt} x₀ for k = 0, 1, …, `steps`. One step's matrix exponential
    /// (nalgebra's Padé approximant with scaling and squaring) is applied repeatedly, so the
    /// answer is exact to round-off at every speed, the double root (where A is defective)
    /// included. This is the linear model's prediction to compare with a simulation of the
    /// non-linear bicycle started from the same state.
    ///
    /// ```
    /// use nalgebra::Vector4;
    /// use whipple::{BenchmarkParameters, Canonical};
    /// use whipple::advanced::linear::StateSpace;
    /// let ss = StateSpace::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 5.0)?;
    /// let x = ss.free_response(&Vector4::new(0.0, 0.0, 0.5, 0.0), 0.01, 1000)?;
    /// assert_eq!(x.len(), 1001);
    /// assert!(x[1000].norm() < 0.05 * x[0].norm()); // 5 m/s is self-stable: it decays
    /// # Ok::<(), whipple::Error>(())
    /// ```
    ///
    /// Errors: `dt` not positive and finite, `x0` not finite, or a state that overflows (an
    /// unstable mode grown past f64) as [`Error::NonFinite`], naming its time.
    pub fn free_response(
        &self,
        x0: &Vector4<f64>,
        dt: f64,
        steps: usize,
    ) -> Result<Vec<Vector4<f64>>> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::InvalidArgument {
                what: "dt",
                rule: format!("must be a positive finite time step, got {dt}"),
            });
        }
        if !x0.iter().all(|x| x.is_finite()) {
            return Err(Error::InvalidArgument {
                what: "initial state",
                rule: format!("must be finite, got {:?}", x0.as_slice()),
            });
        }
        let step = (self.a * dt).exp();
        let mut states = Vec::with_capacity(steps.saturating_add(1));
        let mut x = *x0;
        states.push(x);
        for k in 1..=steps {
            x = step * x;
            if !x.iter().all(|v| v.is_finite()) {
                return Err(Error::NonFinite {
                    context: format!("the linear free response at t = {} s", k as f64 * dt),
                });
            }
            states.push(x);
        }
        Ok(states)
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

#[cfg(test)]
mod free_response_tests {
    use super::*;
    use crate::BenchmarkParameters;
    use crate::analysis::eigen::eigenpairs;

    /// Started on a real mode's eigenvector, the free response is that vector times e^{λt}
    /// (A·v = λ·v), and the real part of a complex mode rotates as Re(v e^{λt}).
    #[test]
    fn free_response_follows_each_eigenvector() -> Result<()> {
        let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
        for speed in [0.5, 3.0, 4.2923825363411, 5.0, 8.0] {
            let ss = StateSpace::new(&canonical, speed)?;
            for pair in eigenpairs(&canonical, speed)? {
                let x0 = pair.vector.map(|z| z.re);
                let (dt, steps) = (0.01, 200);
                let states = ss.free_response(&x0, dt, steps)?;
                for (k, x) in states.iter().enumerate() {
                    let t = k as f64 * dt;
                    let expected = pair
                        .vector
                        .map(|z| (z * crate::math::complex_exp(pair.value * t)).re);
                    // Against the unit initial state: the eigenvector's round-off along a
                    // growing mode (+3/s at 0.5 m/s) grows with it while this mode decays.
                    assert!(
                        (x - expected).norm() <= 1e-9,
                        "v = {speed}, λ = {}, t = {t}: {x:?} vs {expected:?}",
                        pair.value
                    );
                }
            }
        }
        Ok(())
    }

    #[test]
    fn free_response_refuses_bad_steps_and_overflow() -> Result<()> {
        let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
        let ss = StateSpace::new(&canonical, 1.0)?;
        let x0 = Vector4::new(0.01, 0.0, 0.0, 0.0);
        assert!(ss.free_response(&x0, 0.0, 10).is_err());
        assert!(ss.free_response(&x0, f64::NAN, 10).is_err());
        assert!(
            ss.free_response(&Vector4::new(f64::NAN, 0.0, 0.0, 0.0), 0.01, 10)
                .is_err()
        );
        // At 1 m/s the capsize-like mode grows by e^{~3 t}: past f64 long before 1e5 s.
        assert!(matches!(
            ss.free_response(&x0, 100.0, 1000),
            Err(Error::NonFinite { .. })
        ));
        Ok(())
    }
}
