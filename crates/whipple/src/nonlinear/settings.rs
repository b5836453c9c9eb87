//! The rules of a simulation, in one place: [`SimulationSettings`] (what [`super::simulate`]
//! runs with, checked by [`SimulationSettings::validate`]) and [`SimulationRequest`], a
//! simulation as a person asks for it on the command line or through the web API (initial
//! angles in degrees, an integrator by name with an optional step or tolerance, torques as
//! numbers or expressions), whose [`SimulationRequest::validate`] applies every rule once and
//! names the field at fault. Both front ends call it; neither re-checks anything.

use std::fmt;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use serde::Deserialize;

use super::expression::TorqueExpression;
use super::initial::InitialConditions;
use super::projection::ProjectionSettings;
use super::state::StateView;
use crate::error::{Error, Result};
use crate::integrate::{Integrator, DEFAULT_DT, DEFAULT_RTOL};

/// A rider input: torque [N m] as a function of time \[s\] and the state's named quantities.
pub type TorqueFn = Box<dyn Fn(f64, &StateView) -> f64 + Send + Sync>;

/// A progress hook, called after each accepted step.
pub(crate) type ProgressFn = Box<dyn Fn(super::Progress) + Send + Sync>;

/// The fall angle when none is given \[deg\].
pub(crate) const DEFAULT_FALL_ANGLE_DEG: f64 = 60.0;

/// The most integration steps a request may ask for when it sets no bound of its own (RK4's
/// steps are known in advance and refused beyond it; the adaptive integrator stops there). It
/// bounds the work: a step takes about 20 µs, so 2·10⁷ steps are about seven minutes of
/// computing.
pub(crate) const MAX_STEPS: usize = 20_000_000;

/// The most samples a run keeps (see [`SimulationSettings::sample_every`]). It bounds the
/// memory: a [`super::Sample`] is about 190 bytes and a front end writes it as a row of about
/// 400 bytes of text, so 1.5 million samples stay within about 0.8 GiB (a run keeping all of
/// 10⁸ steps had grown towards 25 GB).
pub(crate) const MAX_SAMPLES: usize = 1_500_000;

/// What keeping 1 sample in `every` steps of `steps` amounts to: the first, every `every`-th
/// and the last.
pub(crate) fn samples_kept(steps: usize, every: usize) -> usize {
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
            fall_angle: DEFAULT_FALL_ANGLE_DEG.to_radians(),
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
                rule: format!("must lie strictly between 0 and pi/2 rad (the orientation angles are singular at pi/2), got {a}"),
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

/// The integrators a person can name.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorKind {
    /// Classical Runge–Kutta with a fixed step `dt` (the study's integrator).
    #[default]
    Rk4,
    /// Dormand–Prince 5(4) with error control, tolerance `rtol`.
    Adaptive,
}

/// A rider torque as a person gives it: a constant, or an expression of time and the state
/// ([`TorqueExpression`]).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum TorqueInput {
    /// A constant torque [N m]; zero is hands free.
    Constant(f64),
    /// An expression of time and the state [N m].
    Expression(String),
}

impl Default for TorqueInput {
    /// Hands free.
    fn default() -> Self {
        TorqueInput::Constant(0.0)
    }
}

impl TorqueInput {
    /// The torque as a rider input (`None` for zero), or the rule it breaks, naming `field`.
    fn torque(&self, field: &'static str) -> Result<Option<TorqueFn>> {
        let invalid = |rule: String| Error::InvalidArgument { what: field, rule };
        match self {
            TorqueInput::Constant(x) if !x.is_finite() => Err(invalid(format!(
                "must be a finite number or an expression, got {x}"
            ))),
            TorqueInput::Constant(x) if *x == 0.0 => Ok(None),
            &TorqueInput::Constant(x) => Ok(Some(Box::new(move |_: f64, _: &StateView| x))),
            TorqueInput::Expression(text) => match TorqueExpression::parse(text) {
                Ok(expression) => Ok(Some(expression.into_torque())),
                Err(Error::InvalidArgument { rule, .. }) => Err(invalid(rule)),
                Err(other) => Err(other),
            },
        }
    }
}

/// A simulation as a person asks for it, in the units the command line and the web API take:
/// the initial lean and steer and the fall angle in degrees as typed (radians everywhere
/// else), an integrator by name with an optional step or tolerance, rider torques as numbers or
/// expressions. Field names are those of the web API (the command line's options are the same
/// words: `--lean` for `lean_deg`, `--fall-angle` for `fall_angle_deg`).
///
/// ```
/// use whipple::advanced::nonlinear::{IntegratorKind, SimulationRequest};
/// let request = SimulationRequest {
///     lean_rate: 0.5,
///     integrator: IntegratorKind::Adaptive,
///     ..SimulationRequest::new(4.6, 5.0)
/// };
/// let (initial, settings) = request.validate()?;
/// assert_eq!((initial.lean_rate, settings.duration), (0.5, 5.0));
/// let bad = SimulationRequest { lean_deg: 95.0, ..SimulationRequest::new(4.6, 5.0) };
/// assert!(matches!(bad.validate(), Err(whipple::Error::InvalidArgument { what: "lean_deg", .. })));
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationRequest {
    /// v: forward speed [m/s].
    pub speed: f64,
    /// φ₀: initial lean \[deg\], below 90 in size.
    pub lean_deg: f64,
    /// δ₀: initial steer \[deg\].
    pub steer_deg: f64,
    /// φ̇₀: initial lean rate [rad/s].
    pub lean_rate: f64,
    /// δ̇₀: initial steer rate [rad/s].
    pub steer_rate: f64,
    /// Simulated time \[s\], positive.
    pub duration: f64,
    /// The integrator.
    pub integrator: IntegratorKind,
    /// RK4 step \[s\] (default `DEFAULT_DT`); only with RK4.
    pub dt: Option<f64>,
    /// Relative tolerance of the adaptive integrator (default `DEFAULT_RTOL`; the absolute
    /// tolerance is rtol·1e-2); only with it.
    pub rtol: Option<f64>,
    /// T_δ: steer torque (default hands free).
    pub steer_torque: TorqueInput,
    /// T_φ: lean torque (default none).
    pub lean_torque: TorqueInput,
    /// The bicycle has fallen when |lean| passes this angle \[deg\], in (0, 90).
    pub fall_angle_deg: f64,
    /// Stop when a wheel's normal force turns negative (default true).
    pub stop_on_lift_off: bool,
    /// The most integration steps the run may take: an RK4 request needing more is refused
    /// ([`Error::LimitExceeded`]), the adaptive integrator stops there (outcome
    /// [`super::Outcome::StepSizeTooSmall`]). `None`: `MAX_STEPS`.
    pub max_steps: Option<usize>,
    /// Keep one sample in this many steps (default 1: every step); the samples kept are
    /// bounded by `MAX_SAMPLES`.
    pub sample_every: usize,
}

impl SimulationRequest {
    /// Upright running at `speed` for `duration`, hands free, RK4 at its default step, fall at
    /// 60°, stopping at lift-off.
    pub fn new(speed: f64, duration: f64) -> Self {
        SimulationRequest {
            speed,
            lean_deg: 0.0,
            steer_deg: 0.0,
            lean_rate: 0.0,
            steer_rate: 0.0,
            duration,
            integrator: IntegratorKind::Rk4,
            dt: None,
            rtol: None,
            steer_torque: TorqueInput::default(),
            lean_torque: TorqueInput::default(),
            fall_angle_deg: DEFAULT_FALL_ANGLE_DEG,
            stop_on_lift_off: true,
            max_steps: None,
            sample_every: 1,
        }
    }

    /// Applies every rule of a simulation request and gives the initial conditions and the
    /// settings; an error names the field at fault (`Error::InvalidArgument { what, .. }`, or
    /// [`Error::LimitExceeded`] for too many steps). Every number finite; |lean| < 90°; the
    /// fall angle in (0°, 90°); a positive duration; RK4 takes `dt` (0 < dt ≤ duration,
    /// default 1 ms), the adaptive integrator `rtol` (0 < rtol < 1, default 1e-8, atol =
    /// rtol·1e-2), never both; torques finite numbers or valid expressions.
    pub fn validate(&self) -> Result<(InitialConditions, SimulationSettings)> {
        let invalid = |what: &'static str, rule: String| Err(Error::InvalidArgument { what, rule });
        for (what, x) in [
            ("speed", self.speed),
            ("lean_deg", self.lean_deg),
            ("steer_deg", self.steer_deg),
            ("lean_rate", self.lean_rate),
            ("steer_rate", self.steer_rate),
            ("duration", self.duration),
            ("fall_angle_deg", self.fall_angle_deg),
        ] {
            if !x.is_finite() {
                return invalid(what, format!("must be a finite number, got {x}"));
            }
        }
        if self.lean_deg.abs() >= 90.0 {
            return invalid(
                "lean_deg",
                format!(
                    "must be below 90 degrees in size (the bicycle would lie on the ground), got {}",
                    self.lean_deg
                ),
            );
        }
        let fall = self.fall_angle_deg;
        if !(fall > 0.0 && fall < 90.0) {
            return invalid(
                "fall_angle_deg",
                format!("must lie between 0 and 90 degrees, got {fall}"),
            );
        }
        let duration = self.duration;
        if duration <= 0.0 {
            return invalid("duration", format!("must be positive, got {duration} s"));
        }
        let every = self.sample_every;
        if every == 0 {
            return invalid(
                "sample_every",
                "must be at least 1 (keep every step: 1)".into(),
            );
        }
        let integrator = match self.integrator {
            IntegratorKind::Rk4 => {
                if self.rtol.is_some() {
                    return invalid(
                        "rtol",
                        "applies to the adaptive integrator; RK4 takes `dt`".into(),
                    );
                }
                let dt = self.dt.unwrap_or(DEFAULT_DT);
                if !(dt.is_finite() && dt > 0.0 && dt <= duration) {
                    return invalid(
                        "dt",
                        format!(
                            "must be positive and at most the duration ({duration:?} s), got {dt:?}"
                        ),
                    );
                }
                let integrator = Integrator::Rk4 { dt };
                let limit = self.max_steps.unwrap_or(MAX_STEPS);
                if let Some(steps) = integrator.fixed_steps(duration) {
                    if steps > limit {
                        return Err(Error::LimitExceeded {
                            what: "dt",
                            rule: format!(
                                "{duration:?} s in steps of {dt:?} s takes {steps} integration steps, more than the limit of {limit} (the work it bounds is about {:.0} minutes at 20 µs a step); use a larger dt or a shorter duration",
                                limit as f64 * 20e-6 / 60.0
                            ),
                        });
                    }
                    let kept = samples_kept(steps, every);
                    if kept > MAX_SAMPLES {
                        let needed = steps.div_ceil(MAX_SAMPLES - 2).max(2);
                        return Err(Error::LimitExceeded {
                            what: "sample_every",
                            rule: format!(
                                "{steps} steps would keep {kept} samples, more than the limit of {MAX_SAMPLES} (a sample is {} bytes and about 400 as text: the limit keeps a run within about {:.1} GiB); keep one sample in {needed} steps or more, or use a larger dt or a shorter duration",
                                std::mem::size_of::<super::Sample>(),
                                MAX_SAMPLES as f64 * (std::mem::size_of::<super::Sample>() + 400) as f64 / (1u64 << 30) as f64
                            ),
                        });
                    }
                }
                integrator
            }
            IntegratorKind::Adaptive => {
                if self.dt.is_some() {
                    return invalid(
                        "dt",
                        "applies to RK4; the adaptive integrator takes `rtol`".into(),
                    );
                }
                let rtol = self.rtol.unwrap_or(DEFAULT_RTOL);
                if !(rtol.is_finite() && rtol > 0.0 && rtol < 1.0) {
                    return invalid(
                        "rtol",
                        format!("must lie strictly between 0 and 1, got {rtol}"),
                    );
                }
                // The same bounds as RK4's, on the work and on the samples kept: a run that
                // needs more steps stops there.
                match Integrator::adaptive(rtol) {
                    Integrator::Dopri5(mut settings) => {
                        settings.max_steps = self
                            .max_steps
                            .unwrap_or(MAX_STEPS)
                            .min((MAX_SAMPLES - 2).saturating_mul(every));
                        Integrator::Dopri5(settings)
                    }
                    integrator => integrator,
                }
            }
        };
        let settings = SimulationSettings {
            integrator,
            duration,
            fall_angle: fall.to_radians(),
            steer_torque: self.steer_torque.torque("steer_torque")?,
            lean_torque: self.lean_torque.torque("lean_torque")?,
            stop_on_lift_off: self.stop_on_lift_off,
            sample_every: every,
            ..SimulationSettings::default()
        };
        let initial = InitialConditions {
            speed: self.speed,
            lean: self.lean_deg.to_radians(),
            steer: self.steer_deg.to_radians(),
            lean_rate: self.lean_rate,
            steer_rate: self.steer_rate,
            ..InitialConditions::upright(self.speed)
        };
        initial.validate()?;
        settings.validate()?;
        Ok((initial, settings))
    }
}
