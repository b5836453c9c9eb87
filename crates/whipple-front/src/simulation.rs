//! A simulation as a person asks for it on the command line, through the web API or from
//! Python: the initial lean and steer and the fall angle in degrees as typed, an integrator by
//! name with an optional step or tolerance, rider torques as numbers or expressions.
//! [`SimulationRequest::validate`] applies every rule of a run once, names the field at fault
//! as the user wrote it, and gives the library's SI [`InitialConditions`] and
//! [`SimulationSettings`]. Every front end calls it; none re-checks anything.

use serde::Deserialize;
use whipple::advanced::integrate::{DEFAULT_DT, DEFAULT_RTOL, Integrator};
use whipple::advanced::nonlinear::{
    MAX_SAMPLES, MAX_STEPS, Sample, StateView, TorqueExpression, TorqueFn, samples_kept,
};
use whipple::{Error, InitialConditions, Result, SimulationSettings};

use crate::units::radians;

/// The fall angle when none is given \[deg\] (the library's
/// [`whipple::advanced::nonlinear::DEFAULT_FALL_ANGLE`]).
pub const DEFAULT_FALL_ANGLE_DEG: f64 = 60.0;

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
/// use whipple_front::simulation::{IntegratorKind, SimulationRequest};
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
    /// RK4 step \[s\] (default [`DEFAULT_DT`]); only with RK4.
    pub dt: Option<f64>,
    /// Relative tolerance of the adaptive integrator (default [`DEFAULT_RTOL`]; the absolute
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
    /// [`whipple::advanced::nonlinear::Outcome::StepSizeTooSmall`]). `None`: [`MAX_STEPS`].
    pub max_steps: Option<usize>,
    /// A limit on the steps the host running the request sets (a server's own budget), which
    /// the person asking cannot change: a request past it is refused naming `dt`, not
    /// `max_steps`. `None`: no limit beyond [`Self::max_steps`].
    pub host_max_steps: Option<usize>,
    /// Keep one sample in this many steps (default 1: every step); the samples kept are
    /// bounded by [`MAX_SAMPLES`].
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
            host_max_steps: None,
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
                let limit = self.step_limit();
                if let Some(steps) = integrator.fixed_steps(duration) {
                    if steps > limit {
                        // The limit the user set is the field at fault; the default one and
                        // the host's are met by choosing dt.
                        let user_limit = self.max_steps.is_some_and(|m| m <= limit);
                        let (what, advice) = if user_limit {
                            (
                                "max_steps",
                                "raise max_steps, use a larger dt or a shorter duration",
                            )
                        } else {
                            ("dt", "use a larger dt or a shorter duration")
                        };
                        return Err(Error::LimitExceeded {
                            what,
                            rule: format!(
                                "{duration:?} s in steps of {dt:?} s takes {steps} integration steps, more than the limit of {limit} (the work it bounds is {} at 20 µs a step); {advice}",
                                work_time(limit)
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
                                std::mem::size_of::<Sample>(),
                                MAX_SAMPLES as f64 * (std::mem::size_of::<Sample>() + 400) as f64
                                    / (1u64 << 30) as f64
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
                            .step_limit()
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
            fall_angle: radians(fall),
            steer_torque: self.steer_torque.torque("steer_torque")?,
            lean_torque: self.lean_torque.torque("lean_torque")?,
            stop_on_lift_off: self.stop_on_lift_off,
            sample_every: every,
            ..SimulationSettings::default()
        };
        let initial = InitialConditions {
            speed: self.speed,
            lean: radians(self.lean_deg),
            steer: radians(self.steer_deg),
            lean_rate: self.lean_rate,
            steer_rate: self.steer_rate,
            ..InitialConditions::upright(self.speed)
        };
        initial.validate()?;
        settings.validate()?;
        Ok((initial, settings))
    }

    /// The most steps the run may take: the user's `max_steps` (or [`MAX_STEPS`]), within the
    /// host's limit.
    fn step_limit(&self) -> usize {
        self.max_steps
            .unwrap_or(MAX_STEPS)
            .min(self.host_max_steps.unwrap_or(usize::MAX))
    }
}

/// The work of `steps` integration steps at about 20 µs each, in words ("about 2.0 ms",
/// "about 40 s", "about 7 minutes").
fn work_time(steps: usize) -> String {
    let seconds = steps as f64 * 20e-6;
    if seconds < 1.0 {
        format!("about {:.1} ms", seconds * 1e3)
    } else if seconds < 120.0 {
        format!("about {:.0} s", seconds)
    } else {
        format!("about {:.0} minutes", seconds / 60.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The work of a step limit in words: milliseconds, seconds or minutes, never "0 minutes".
    #[test]
    fn work_time_reads_in_a_sensible_unit() {
        assert_eq!(work_time(100), "about 2.0 ms");
        assert_eq!(work_time(1_000_000), "about 20 s");
        assert_eq!(work_time(20_000_000), "about 7 minutes");
    }

    /// A step limit the user set is named `max_steps`; a host's limit (a server's budget, which
    /// the user cannot change) is met by choosing `dt`, and names it.
    #[test]
    fn a_step_limit_names_the_field_the_user_can_change() {
        let long = |max_steps, host_max_steps| SimulationRequest {
            dt: Some(1e-3),
            max_steps,
            host_max_steps,
            ..SimulationRequest::new(4.6, 10.0)
        };
        let (what, rule) = rule_of(long(Some(1000), None));
        assert_eq!(what, "max_steps", "{rule}");
        assert!(
            rule.contains("raise max_steps") && rule.contains("about 20.0 ms"),
            "{rule}"
        );
        let (what, rule) = rule_of(long(None, Some(1000)));
        assert_eq!(what, "dt", "{rule}");
        assert!(!rule.contains("max_steps"), "{rule}");
        let (what, _) = rule_of(long(Some(500), Some(1000)));
        assert_eq!(what, "max_steps");
        let (what, _) = rule_of(long(Some(5000), Some(1000)));
        assert_eq!(what, "dt");
        assert!(long(Some(20_000), Some(20_000)).validate().is_ok());
    }

    fn rule_of(request: SimulationRequest) -> (&'static str, String) {
        match request.validate() {
            Err(Error::InvalidArgument { what, rule } | Error::LimitExceeded { what, rule }) => {
                (what, rule)
            }
            other => panic!("{:?}", other.map(|_| ())),
        }
    }

    /// Degrees as typed become the library's radians, bit for bit as `f64::to_radians`; the
    /// default fall angle is the library's default.
    #[test]
    fn angles_in_degrees_become_radians() -> Result<()> {
        let request = SimulationRequest {
            lean_deg: 5.0,
            steer_deg: -2.5,
            fall_angle_deg: 45.0,
            ..SimulationRequest::new(4.6, 1.0)
        };
        let (initial, settings) = request.validate()?;
        assert_eq!(initial.lean, 5f64.to_radians());
        assert_eq!(initial.steer, (-2.5f64).to_radians());
        assert_eq!(settings.fall_angle, std::f64::consts::FRAC_PI_4);
        let (_, default) = SimulationRequest::new(4.6, 1.0).validate()?;
        assert_eq!(default.fall_angle, SimulationSettings::default().fall_angle);
        Ok(())
    }

    /// An error names the field as the user wrote it, in the user's units.
    #[test]
    fn errors_name_the_field_as_typed() {
        let base = SimulationRequest::new(4.6, 1.0);
        let (what, rule) = rule_of(SimulationRequest {
            lean_deg: 95.0,
            ..base.clone()
        });
        assert_eq!(what, "lean_deg");
        assert!(
            rule.contains("below 90 degrees") && rule.ends_with("got 95"),
            "{rule}"
        );
        let (what, rule) = rule_of(SimulationRequest {
            fall_angle_deg: 0.0,
            ..base.clone()
        });
        assert_eq!(
            (what, rule.as_str()),
            ("fall_angle_deg", "must lie between 0 and 90 degrees, got 0")
        );
        let (what, _) = rule_of(SimulationRequest {
            steer_deg: f64::NAN,
            ..base.clone()
        });
        assert_eq!(what, "steer_deg");
        let (what, rule) = rule_of(SimulationRequest {
            rtol: Some(1e-6),
            ..base.clone()
        });
        assert_eq!(
            (what, rule.as_str()),
            ("rtol", "applies to the adaptive integrator; RK4 takes `dt`")
        );
        let (what, _) = rule_of(SimulationRequest {
            dt: Some(1e-9),
            duration: 100.0,
            ..base.clone()
        });
        assert_eq!(what, "dt");
        let (what, _) = rule_of(SimulationRequest {
            steer_torque: TorqueInput::Expression("2 *".into()),
            ..base
        });
        assert_eq!(what, "steer_torque");
    }
}
