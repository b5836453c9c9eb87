//! The settings of a simulation: [`SimulationSettings`] (what [`super::simulate`] runs with,
//! checked by [`SimulationSettings::validate`]), in SI units, and the bounds on a run's work
//! and memory ([`MAX_STEPS`], [`MAX_SAMPLES`]). A simulation as a person asks for it (angles in
//! degrees, an integrator by name, torques as typed) is the front ends' `whipple_front`
//! crate's, which checks it into these settings.

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use super::projection::ProjectionSettings;
use super::state::StateView;
use crate::error::{Error, Result};
use crate::integrate::Integrator;

/// A rider input: torque [N m] as a function of time \[s\] and the state's named quantities.
pub type TorqueFn = Box<dyn Fn(f64, &StateView) -> f64 + Send + Sync>;

/// A progress hook, called after each accepted step.
pub(crate) type ProgressFn = Box<dyn Fn(super::Progress) + Send + Sync>;

/// The fall angle when none is given \[rad\]: 60°, as `60f64.to_radians()` gives it.
pub const DEFAULT_FALL_ANGLE: f64 = 60.0 * (std::f64::consts::PI / 180.0);

/// The most integration steps a request may ask for when it sets no bound of its own (RK4's
/// steps are known in advance and refused beyond it; the adaptive integrator stops there). It
/// bounds the work: a step takes about 20 µs, so 2·10⁷ steps are about seven minutes of
/// computing.
pub const MAX_STEPS: usize = 20_000_000;

/// The most samples a run keeps (see [`SimulationSettings::sample_every`]). It bounds the
/// memory: a [`super::Sample`] is about 190 bytes and a front end writes it as a row of about
/// 400 bytes of text, so 1.5 million samples stay within about 0.8 GiB (a run keeping all of
/// 10⁸ steps had grown towards 25 GB).
pub const MAX_SAMPLES: usize = 1_500_000;

/// What keeping 1 sample in `every` steps of `steps` amounts to: the first, every `every`-th
/// and the last.
pub fn samples_kept(steps: usize, every: usize) -> usize {
    steps / every.max(1) + 2
}

/// Everything a simulation needs besides the model and the initial state. Defaults: RK4 with
/// dt = 1 ms, 10 s, fall at 60°, no rider torques, default projection, no progress hook.
pub struct SimulationSettings {
    /// Integrator and its step settings.
    pub integrator: Integrator,
    /// Simulated time \[s\].
    pub duration: f64,
    /// The bicycle has fallen when |lean| exceeds this \[rad\], in (0, π/2). Default π/3.
    pub fall_angle: f64,
    /// Steer torque T_δ(t, state) [N m]; `None` for hands-free.
    pub steer_torque: Option<TorqueFn>,
    /// Lean torque T_φ(t, state) [N m]; `None` for none.
    pub lean_torque: Option<TorqueFn>,
    /// Projection settings.
    pub projection: ProjectionSettings,
    /// Stop when a wheel's normal force becomes negative (it would lift off). Default true.
    pub stop_on_lift_off: bool,
    /// Keep one sample in this many accepted steps (the first and the last are always kept);
    /// at least 1, the default. The run's extremes (`super::RunExtremes`: energy change,
    /// residuals, normal forces) are taken over every step all the same.
    pub sample_every: usize,
    /// Called after each accepted step.
    pub progress: Option<ProgressFn>,
    /// Set it to true, from any thread, to end the run before its next step (outcome
    /// [`super::Outcome::Stopped`], the samples so far kept): a server stops a run whose client
    /// has gone or whose time is up.
    pub stop: Option<Arc<AtomicBool>>,
}

impl Default for SimulationSettings {
    fn default() -> Self {
        SimulationSettings {
            integrator: Integrator::default(),
            duration: 10.0,
            fall_angle: DEFAULT_FALL_ANGLE,
            steer_torque: None,
            lean_torque: None,
            projection: ProjectionSettings::default(),
            stop_on_lift_off: true,
            sample_every: 1,
            progress: None,
            stop: None,
        }
    }
}

impl fmt::Debug for SimulationSettings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SimulationSettings")
            .field("integrator", &self.integrator)
            .field("duration", &self.duration)
            .field("fall_angle", &self.fall_angle)
            .field("steer_torque", &self.steer_torque.is_some())
            .field("lean_torque", &self.lean_torque.is_some())
            .field("projection", &self.projection)
            .field("stop_on_lift_off", &self.stop_on_lift_off)
            .field("sample_every", &self.sample_every)
            .field("progress", &self.progress.is_some())
            .field("stop", &self.stop)
            .finish()
    }
}

impl SimulationSettings {
    /// Checks the settings: a finite duration ≥ 0, a fall angle in (0, π/2), `sample_every` at
    /// least 1, a usable projection and integrator.
    pub fn validate(&self) -> Result<()> {
        if self.sample_every == 0 {
            return Err(Error::InvalidArgument {
                what: "sample_every",
                rule: "must be at least 1 (keep every step: 1)".into(),
            });
        }
        let d = self.duration;
        if !(d.is_finite() && d >= 0.0) {
            return Err(Error::InvalidArgument {
                what: "duration",
                rule: format!("must be a finite number >= 0 s, got {d}"),
            });
        }
        let a = self.fall_angle;
        if !(a > 0.0 && a < std::f64::consts::FRAC_PI_2) {
            return Err(Error::InvalidArgument {
                what: "fall_angle",
                rule: format!(
                    "must lie strictly between 0 and pi/2 rad (the orientation angles are singular at pi/2), got {a}"
                ),
            });
        }
        let p = &self.projection;
        if !(p.tolerance.is_finite() && p.tolerance > 0.0)
            || p.min_iterations == 0
            || p.min_iterations > p.max_iterations
        {
            return Err(Error::InvalidArgument {
                what: "projection",
                rule: format!(
                    "need a positive finite tolerance and 1 <= min_iterations <= max_iterations, got {p:?}"
                ),
            });
        }
        self.integrator.validate()
    }
}
