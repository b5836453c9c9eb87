//! Model-agnostic integration of ẏ = f(t, y) for fixed-size states: the classical fixed-step
//! Runge–Kutta method (the study's integrator) and the adaptive Dormand–Prince 5(4) pair with
//! error control and dense output. Projection onto constraints and event handling belong to
//! the caller (see [`crate::nonlinear::simulate`]), which drives the steppers one step at a time.
//!
//! ```
//! use nalgebra::Vector2;
//! use whipple::integrate::{solve, Method};
//! // Harmonic oscillator: y = [x, ẋ], ẍ = −x.
//! let f = |_t: f64, y: &Vector2<f64>| Ok(Vector2::new(y[1], -y[0]));
//! let trajectory = solve(&f, 0.0, Vector2::new(1.0, 0.0), 1.0, &Method::Rk4 { dt: 1e-3 })?;
//! let end = trajectory.y.last().copied().unwrap_or_default();
//! assert!((end[0] - 1f64.cos()).abs() < 1e-12);
//! # Ok::<(), whipple::Error>(())
//! ```

pub mod dopri5;
pub mod rk4;

use nalgebra::SVector;

use crate::error::{Error, Result};
pub use dopri5::{DenseOutput, Dopri5Params};

/// A first-order system ẏ = f(t, y) of fixed size N.
pub trait OdeSystem<const N: usize> {
    /// f(t, y). May fail (for example a singular constrained system).
    fn rhs(&self, t: f64, y: &SVector<f64, N>) -> Result<SVector<f64, N>>;
}

impl<F, const N: usize> OdeSystem<N> for F
where
    F: Fn(f64, &SVector<f64, N>) -> Result<SVector<f64, N>>,
{
    fn rhs(&self, t: f64, y: &SVector<f64, N>) -> Result<SVector<f64, N>> {
        self(t, y)
    }
}

/// Times and states of an integration, in step order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trajectory<const N: usize> {
    /// Times \[s\].
    pub t: Vec<f64>,
    /// States at those times.
    pub y: Vec<SVector<f64, N>>,
}

/// Integration method and its step settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Classical fourth-order Runge–Kutta with fixed step `dt` \[s\].
    Rk4 {
        /// Step \[s\].
        dt: f64,
    },
    /// Dormand–Prince 5(4), adaptive.
    Dopri5(Dopri5Params),
}

impl Method {
    /// Checks the step settings.
    pub fn validate(&self) -> Result<()> {
        match self {
            Method::Rk4 { dt } => {
                if !(dt.is_finite() && *dt > 0.0) {
                    return Err(Error::InvalidArgument {
                        what: "dt",
                        rule: format!("the RK4 step must be a positive finite number, got {dt}"),
                    });
                }
                Ok(())
            }
            Method::Dopri5(p) => p.validate(),
        }
    }
}

/// Integrates from (t0, y0) to t_end, recording every step. A non-finite state ends the
/// integration with [`Error::NonFiniteState`].
pub fn solve<S: OdeSystem<N>, const N: usize>(
    system: &S,
    t0: f64,
    y0: SVector<f64, N>,
    t_end: f64,
    method: &Method,
) -> Result<Trajectory<N>> {
    method.validate()?;
    if !(t0.is_finite() && t_end.is_finite() && t_end >= t0) {
        return Err(Error::InvalidArgument {
            what: "time span",
            rule: format!("need finite t0 <= t_end, got {t0} and {t_end}"),
        });
    }
    let mut out = Trajectory {
        t: vec![t0],
        y: vec![y0],
    };
    let (mut t, mut y) = (t0, y0);
    match method {
        Method::Rk4 { dt } => {
            let steps = rk4::step_count(t_end - t0, *dt);
            for i in 0..steps {
                let t_next = if i + 1 == steps {
                    t_end
                } else {
                    t0 + (i + 1) as f64 * dt
                };
                y = rk4::step(system, t, &y, t_next - t)?;
                t = t_next;
                check_finite(&y, t)?;
                out.t.push(t);
                out.y.push(y);
            }
        }
        Method::Dopri5(params) => {
            let mut k1 = system.rhs(t, &y)?;
            let mut controller = dopri5::Controller::new(params, &y, &k1, t_end - t0);
            let mut steps = 0;
            while t < t_end {
                if steps >= params.max_steps {
                    return Err(Error::NoConvergence {
                        method: "Dormand-Prince 5(4): step limit reached",
                        iterations: steps,
                        residual: t_end - t,
                    });
                }
                steps += 1;
                let h = controller.step().min(t_end - t);
                let attempt = dopri5::attempt(system, t, &y, &k1, h, params)?;
                if controller.accept(attempt.error, h)? {
                    t = if t_end - (t + h) <= 1e-12 * t_end.abs().max(1.0) {
                        t_end
                    } else {
                        t + h
                    };
                    y = attempt.y;
                    k1 = attempt.k7;
                    check_finite(&y, t)?;
                    out.t.push(t);
                    out.y.push(y);
                }
            }
        }
    }
    Ok(out)
}

fn check_finite<const N: usize>(y: &SVector<f64, N>, t: f64) -> Result<()> {
    if y.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFiniteState { t })
    }
}
