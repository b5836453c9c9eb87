//! Model-agnostic integration of ẏ = f(t, y) for fixed-size states: the classical fixed-step
//! Runge–Kutta method (the study's integrator) and the adaptive Dormand–Prince 5(4) pair with
//! error control and dense output, both driven one accepted step at a time by one [`Stepper`].
//! Projection onto constraints and event handling belong to the caller (see
//! [`crate::nonlinear`]'s `simulate`), which may change the state between steps.
//!
//! ```
//! use nalgebra::Vector2;
//! use whipple::advanced::integrate::{Integrator, OdeSystem, Stepper};
//! // Harmonic oscillator: y = [x, ẋ], ẍ = −x.
//! let f = |_t: f64, y: &Vector2<f64>| Ok(Vector2::new(y[1], -y[0]));
//! let mut y = Vector2::new(1.0, 0.0);
//! let mut stepper = Stepper::new(&Integrator::Rk4 { dt: 1e-3 }, &y, &f.rhs(0.0, &y)?, 1.0)?;
//! while !stepper.done() {
//!     let slope = f.rhs(stepper.t(), &y)?;
//!     y = stepper.step(&f, &y, &slope)?.y;
//! }
//! assert_eq!((stepper.t(), stepper.accepted()), (1.0, 1000));
//! assert!((y[0] - 1f64.cos()).abs() < 1e-12);
//! # Ok::<(), whipple::Error>(())
//! ```

pub(crate) mod dopri5;
pub(crate) mod rk4;

use nalgebra::SVector;

use crate::error::{Error, Result};
pub(crate) use dopri5::DenseOutput;
pub use dopri5::Dopri5Settings;

/// The RK4 step when none is given \[s\] (the study's).
pub const DEFAULT_DT: f64 = 1e-3;
/// The adaptive integrator's relative tolerance when none is given.
pub const DEFAULT_RTOL: f64 = 1e-8;

/// The largest |λ·dt| RK4 is given for a mode λ of the system it integrates. RK4's stability
/// region (|1 + z + z²/2 + z³/6 + z⁴/24| ≤ 1, z = λ·dt) reaches 2.785 along the negative real
/// axis and 2.828 along the imaginary one; the half-disc |z| ≤ 2.5, Re z ≤ 0 lies inside it
/// with a margin (|R(z)| ≤ 0.873 on it). Beyond this bound a decaying mode can grow from step
/// to step: the motion computed is the integrator's, not the system's.
pub(crate) const RK4_STABLE_RADIUS: f64 = 2.5;

/// The |λ·dt| of the step a too-coarse RK4 run is told to use: within it a mode's growth
/// factor per step is off by at most 2% (for example R(−1) = 0.375 against e⁻¹ = 0.368, and
/// R(i) = 0.994 e^(0.994i) against e^i).
pub(crate) const RK4_ACCURATE_RADIUS: f64 = 1.0;

/// The largest number of the form 1, 2 or 5 × 10ᵏ that is at most `x` (positive, finite): a
/// step or tolerance to suggest in a message. `x` itself when it is not positive and finite.
pub(crate) fn round_down_125(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let decade = crate::math::powf(10f64, crate::math::log10(x).floor());
    let mantissa = x / decade;
    let m = if mantissa >= 5.0 - 1e-9 {
        5.0
    } else if mantissa >= 2.0 - 1e-9 {
        2.0
    } else {
        1.0
    };
    let rounded = m * decade;
    // Round-off in log10 may land a hair above x: one step down then.
    if rounded > x * (1.0 + 1e-12) {
        match m as u8 {
            5 => 2.0 * decade,
            2 => decade,
            _ => 0.5 * decade,
        }
    } else {
        rounded
    }
}

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

/// The integration method and its step settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Classical fourth-order Runge–Kutta, fixed step `dt` \[s\] (the study's choice).
    Rk4 {
        /// Step \[s\].
        dt: f64,
    },
    /// Dormand–Prince 5(4) with error control and dense output.
    Dopri5(Dopri5Settings),
}

impl Default for Integrator {
    /// RK4 with the step `DEFAULT_DT`.
    fn default() -> Self {
        Integrator::Rk4 { dt: DEFAULT_DT }
    }
}

impl Integrator {
    /// Dormand–Prince 5(4) with relative tolerance `rtol`, absolute tolerance `rtol`·1e-2 and
    /// the other settings at their defaults (the rule every front end uses).
    pub fn adaptive(rtol: f64) -> Self {
        Integrator::Dopri5(Dopri5Settings::with_rtol(rtol))
    }

    /// Checks the step settings.
    pub fn validate(&self) -> Result<()> {
        match self {
            Integrator::Rk4 { dt } => {
                if !(dt.is_finite() && *dt > 0.0) {
                    return Err(Error::InvalidArgument {
                        what: "dt",
                        rule: format!("the RK4 step must be a positive finite number, got {dt}"),
                    });
                }
                Ok(())
            }
            Integrator::Dopri5(p) => p.validate(),
        }
    }

    /// The number of RK4 steps of at most `dt` that cover `span` (the last may be shorter; a
    /// remainder below 1e-9 dt is absorbed); `None` for the adaptive method, whose steps are
    /// known only as it goes.
    pub fn fixed_steps(&self, span: f64) -> Option<usize> {
        match self {
            Integrator::Rk4 { dt } => Some(rk4::step_count(span, *dt)),
            Integrator::Dopri5(_) => None,
        }
    }
}

/// One accepted step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step<const N: usize> {
    /// The step's end time \[s\].
    pub t: f64,
    /// The state there.
    pub y: SVector<f64, N>,
    /// The interpolant over the step (adaptive method only).
    pub dense: Option<DenseOutput<N>>,
}

/// Why no step could be taken.
#[derive(Debug, Clone, PartialEq)]
pub enum StepFailure {
    /// The adaptive step size fell below its minimum, or its bound on step attempts was reached.
    StepSizeTooSmall,
    /// f could not be evaluated within a fixed step.
    Evaluation(Error),
    /// The step ended in a non-finite state at time t.
    NonFinite {
        /// The step's end time \[s\].
        t: f64,
    },
}

impl From<StepFailure> for Error {
    fn from(failure: StepFailure) -> Self {
        match failure {
            StepFailure::StepSizeTooSmall => Error::NoConvergence {
                method: "Dormand-Prince 5(4): the step size fell below min_step or the step \
                         limit was reached",
                iterations: 0,
                residual: f64::NAN,
            },
            StepFailure::Evaluation(error) => error,
            StepFailure::NonFinite { t } => Error::NonFiniteState { t },
        }
    }
}

/// The running state of one method.
#[derive(Debug, Clone, Copy)]
enum Running {
    Rk4 {
        dt: f64,
        total: usize,
    },
    Dopri5 {
        controller: dopri5::Controller,
        settings: Dopri5Settings,
    },
}

/// Integrates from t = 0 to `t_end` one accepted step at a time. Between steps the caller may
/// replace the state (a projection onto constraints) and must give the slope f(t, y) at the
/// state it passes: that evaluation is the caller's (it also yields what the caller records).
#[derive(Debug, Clone, Copy)]
pub struct Stepper {
    running: Running,
    t: f64,
    t_end: f64,
    accepted: usize,
    attempts: usize,
    rejected: usize,
}

impl Stepper {
    /// A stepper at t = 0 with state `y0` and slope `f0` = f(0, y0), to end at `t_end` ≥ 0.
    pub fn new<const N: usize>(
        integrator: &Integrator,
        y0: &SVector<f64, N>,
        f0: &SVector<f64, N>,
        t_end: f64,
    ) -> Result<Self> {
        integrator.validate()?;
        if !(t_end.is_finite() && t_end >= 0.0) {
            return Err(Error::InvalidArgument {
                what: "duration",
                rule: format!("must be a finite number >= 0 s, got {t_end}"),
            });
        }
        let running = match integrator {
            Integrator::Rk4 { dt } => Running::Rk4 {
                dt: *dt,
                total: rk4::step_count(t_end, *dt),
            },
            Integrator::Dopri5(settings) => Running::Dopri5 {
                controller: dopri5::Controller::new(settings, y0, f0, t_end),
                settings: *settings,
            },
        };
        Ok(Stepper {
            running,
            t: 0.0,
            t_end,
            accepted: 0,
            attempts: 0,
            rejected: 0,
        })
    }

    /// The time reached \[s\].
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Steps accepted so far.
    pub fn accepted(&self) -> usize {
        self.accepted
    }

    /// Step attempts rejected so far (adaptive method only).
    pub fn rejected(&self) -> usize {
        self.rejected
    }

    /// True once the end time is reached.
    pub fn done(&self) -> bool {
        match self.running {
            Running::Rk4 { total, .. } => self.accepted >= total,
            Running::Dopri5 { .. } => self.t >= self.t_end,
        }
    }

    /// One accepted step from the current time, state `y` and slope `k1` = f(t, y). An
    /// adaptive attempt whose evaluation fails counts as rejected (infinite error) and is
    /// retried with a smaller step.
    pub fn step<S: OdeSystem<N>, const N: usize>(
        &mut self,
        system: &S,
        y: &SVector<f64, N>,
        k1: &SVector<f64, N>,
    ) -> std::result::Result<Step<N>, StepFailure> {
        let t = self.t;
        let step = match &mut self.running {
            Running::Rk4 { dt, total } => {
                let t_new = if self.accepted + 1 == *total {
                    self.t_end
                } else {
                    (self.accepted + 1) as f64 * *dt
                };
                let y_new = rk4::step_with_slope(system, t, y, k1, t_new - t)
                    .map_err(StepFailure::Evaluation)?;
                Step {
                    t: t_new,
                    y: y_new,
                    dense: None,
                }
            }
            Running::Dopri5 {
                controller,
                settings,
            } => loop {
                self.attempts += 1;
                if self.attempts > settings.max_steps {
                    return Err(StepFailure::StepSizeTooSmall);
                }
                let h = controller.step().min(self.t_end - t);
                let attempt = dopri5::attempt(system, t, y, k1, h, settings)
                    .unwrap_or_else(|_| dopri5::Attempt::failed(t, h, y, k1));
                match controller.accept(attempt.error, h) {
                    Ok(true) => {
                        let t_new = if self.t_end - (t + h) <= 1e-12 * self.t_end.max(1.0) {
                            self.t_end
                        } else {
                            t + h
                        };
                        break Step {
                            t: t_new,
                            y: attempt.y,
                            dense: Some(attempt.dense),
                        };
                    }
                    Ok(false) => self.rejected += 1,
                    Err(_) => return Err(StepFailure::StepSizeTooSmall),
                }
            },
        };
        if !step.y.iter().all(|v| v.is_finite()) {
            return Err(StepFailure::NonFinite { t: step.t });
        }
        self.t = step.t;
        self.accepted += 1;
        Ok(step)
    }
}
