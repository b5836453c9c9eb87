//! Simulation of the multibody bicycle: integration step by step, projection onto the
//! constraints after every step, events (fall, wheel lift-off, end time) and samples.
//!
//! ```
//! use whipple::{BenchmarkParameters, nonlinear::*};
//! let model = Model::new(&BenchmarkParameters::meijaard2007())?;
//! let start = model.initial_state(&InitialConditions { lean_rate: 0.5, ..InitialConditions::upright(4.6) })?;
//! let settings = SimulationSettings { duration: 1.0, ..SimulationSettings::default() };
//! let run = simulate(&model, start, &settings)?;
//! assert_eq!(run.outcome, Outcome::Completed);
//! assert!(run.samples.iter().all(|s| s.position_residual < 1e-12));
//! # Ok::<(), whipple::Error>(())
//! ```

use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use nalgebra::SVector;

use super::forward::{ContactForce, Derivatives, Inputs, Poses};
use super::projection::ProjectionParams;
use super::state::{State, StateView, STATE_LEN};
use super::Model;
use crate::error::{Error, Result};
use crate::integrate::dopri5::{self, Controller, Dopri5Params};
use crate::integrate::{rk4, OdeSystem};

/// A rider input: torque [N m] as a function of time \[s\] and the state's named quantities.
pub type TorqueFn = Box<dyn Fn(f64, &StateView) -> f64 + Send + Sync>;

/// A progress hook, called after each accepted step.
pub type ProgressFn = Box<dyn Fn(Progress) + Send + Sync>;

/// How far a simulation is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Simulated time reached \[s\].
    pub t: f64,
    /// Time at which the run ends if nothing happens \[s\].
    pub t_end: f64,
    /// Steps accepted so far.
    pub steps: usize,
}

/// The integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Classical Runge–Kutta, fixed step `dt` \[s\] (the study's choice).
    Rk4 {
        /// Step \[s\].
        dt: f64,
    },
    /// Dormand–Prince 5(4) with error control.
    Dopri5(Dopri5Params),
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
    pub projection: ProjectionParams,
    /// Stop when a wheel's normal force becomes negative (it would lift off). Default true.
    pub stop_on_lift_off: bool,
    /// Called after each accepted step.
    pub progress: Option<ProgressFn>,
    /// Set it to true, from any thread, to end the run before its next step (outcome
    /// [`Outcome::Stopped`], the samples so far kept): a server stops a run whose client has
    /// gone or whose time is up.
    pub stop: Option<Arc<AtomicBool>>,
}

impl Default for SimulationSettings {
    fn default() -> Self {
        SimulationSettings {
            integrator: Integrator::Rk4 { dt: 1e-3 },
            duration: 10.0,
            fall_angle: std::f64::consts::FRAC_PI_3,
            steer_torque: None,
            lean_torque: None,
            projection: ProjectionParams::default(),
            stop_on_lift_off: true,
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
            .field("progress", &self.progress.is_some())
            .field("stop", &self.stop)
            .finish()
    }
}

/// Which wheel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wheel {
    /// The rear wheel.
    Rear,
    /// The front wheel.
    Front,
}

/// How a simulation ended. Only the first is the full duration; the others keep the samples
/// computed up to that point.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Reached the end time.
    Completed,
    /// |lean| passed the fall angle at time t (interpolated within the step).
    Fell {
        /// Time of the crossing \[s\].
        t: f64,
        /// Lean at that time \[rad\].
        lean: f64,
    },
    /// A wheel's normal force became negative at time t (interpolated within the step).
    WheelLifted {
        /// Time \[s\].
        t: f64,
        /// The wheel.
        wheel: Wheel,
    },
    /// Newton projection onto the holonomic constraints failed after the step ending at t.
    ProjectionFailed {
        /// Time \[s\].
        t: f64,
        /// Iterations made.
        iterations: usize,
        /// Residual reached.
        residual: f64,
    },
    /// The state became non-finite in the step ending at t.
    NonFiniteState {
        /// Time \[s\].
        t: f64,
    },
    /// The adaptive step size fell below its minimum, or its step limit was reached, at t.
    StepSizeTooSmall {
        /// Time \[s\].
        t: f64,
    },
    /// The run was stopped from outside ([`SimulationSettings::stop`]) at time t.
    Stopped {
        /// Time \[s\].
        t: f64,
    },
    /// The equations of motion could not be evaluated (for example singular) at time t.
    Failed {
        /// Time \[s\].
        t: f64,
        /// Why.
        error: Error,
    },
}

/// One recorded instant (after projection). Radians, metres, seconds, newtons, joules. The
/// configuration is complete: [`Model::sample_poses`] places the four bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// t \[s\].
    pub t: f64,
    /// φ \[rad\].
    pub lean: f64,
    /// δ \[rad\].
    pub steer: f64,
    /// φ̇ [rad/s].
    pub lean_rate: f64,
    /// δ̇ [rad/s].
    pub steer_rate: f64,
    /// ψ \[rad\].
    pub yaw: f64,
    /// θ_B: pitch of the rear frame (a dependent coordinate) \[rad\].
    pub pitch: f64,
    /// θ_R: rear wheel rotation relative to the rear frame (see [`Model::wheel_angles`]) \[rad\].
    pub rear_wheel_angle: f64,
    /// θ_F: front wheel rotation relative to the front frame \[rad\].
    pub front_wheel_angle: f64,
    /// Rear contact x \[m\].
    pub x: f64,
    /// Rear contact y \[m\].
    pub y: f64,
    /// Front contact x \[m\].
    pub front_x: f64,
    /// Front contact y \[m\].
    pub front_y: f64,
    /// v: forward speed of the rear hub [m/s].
    pub speed: f64,
    /// Total energy, kinetic + potential \[J\].
    pub energy: f64,
    /// Largest absolute holonomic residual \[m\].
    pub position_residual: f64,
    /// Largest absolute velocity-row residual (holonomic rows differentiated and rolling)
    /// [m/s].
    pub velocity_residual: f64,
    /// Ground force on the rear wheel \[N\].
    pub rear: ContactForce<f64>,
    /// Ground force on the front wheel \[N\].
    pub front: ContactForce<f64>,
}

/// The result of [`simulate`].
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Samples after every accepted step, the initial state first.
    pub samples: Vec<Sample>,
    /// How the run ended.
    pub outcome: Outcome,
    /// The last state reached (projected).
    pub final_state: State<f64>,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected step attempts (adaptive integrator only).
    pub rejected_steps: usize,
    /// Wheels whose contact already pulled the wheel down at the start (a negative normal
    /// force, as for the two-mass-skate, whose masses sit ahead of its front contact). The
    /// contacts are bilateral constraints, as in the linearized model, so such a run goes on;
    /// lift-off is watched only for the wheels that started pressed onto the ground.
    pub pulled_down_from_start: Vec<Wheel>,
}

/// The model with its rider inputs as an ODE ẏ = f(t, y) on y = [q; u].
pub struct BicycleOde<'a> {
    /// The model.
    pub model: &'a Model,
    /// Steer torque, if any.
    pub steer_torque: Option<&'a TorqueFn>,
    /// Lean torque, if any.
    pub lean_torque: Option<&'a TorqueFn>,
}

impl BicycleOde<'_> {
    /// Forward dynamics with the inputs evaluated at (t, state). A non-finite state or rider
    /// torque is [`Error::NonFiniteState`] at t (not a singular system, which is what the
    /// solve would otherwise report).
    pub fn derivatives(&self, t: f64, state: &State<f64>) -> Result<Derivatives<f64>> {
        let finite = |x: &f64| x.is_finite();
        if !(state.q.iter().all(finite) && state.u.iter().all(finite)) {
            return Err(Error::NonFiniteState { t });
        }
        let inputs = if self.steer_torque.is_some() || self.lean_torque.is_some() {
            let view = self.model.observe(state);
            Inputs {
                steer_torque: self.steer_torque.map_or(0.0, |f| f(t, &view)),
                lean_torque: self.lean_torque.map_or(0.0, |f| f(t, &view)),
            }
        } else {
            Inputs::default()
        };
        if !(inputs.steer_torque.is_finite() && inputs.lean_torque.is_finite()) {
            return Err(Error::NonFiniteState { t });
        }
        self.model.forward(state, &inputs)
    }
}

impl OdeSystem<STATE_LEN> for BicycleOde<'_> {
    fn rhs(&self, t: f64, y: &SVector<f64, STATE_LEN>) -> Result<SVector<f64, STATE_LEN>> {
        Ok(self.derivatives(t, &State::from_vector(y))?.to_vector())
    }
}

fn sample(
    model: &Model,
    t: f64,
    state: &State<f64>,
    poses: &Poses<f64>,
    d: &Derivatives<f64>,
    position_residual: f64,
) -> Sample {
    let view = model.observe_at(poses, state);
    let [rear_wheel_angle, front_wheel_angle] = model.wheel_angles(&state.q);
    Sample {
        t,
        lean: view.lean,
        steer: view.steer,
        lean_rate: view.lean_rate,
        steer_rate: view.steer_rate,
        yaw: view.yaw,
        pitch: view.pitch,
        rear_wheel_angle,
        front_wheel_angle,
        x: view.rear_contact_x,
        y: view.rear_contact_y,
        front_x: view.front_contact_x,
        front_y: view.front_contact_y,
        speed: view.speed,
        energy: model.energy(state),
        position_residual,
        velocity_residual: model.velocity_residual_at(poses, state).amax(),
        rear: d.contact[0],
        front: d.contact[1],
    }
}

/// Time at which a quantity going linearly from g0 (at t0) to g1 (at t1) crosses zero.
fn crossing(t0: f64, g0: f64, t1: f64, g1: f64) -> f64 {
    if g1 == g0 {
        t1
    } else {
        (t0 + (t1 - t0) * g0 / (g0 - g1)).clamp(t0, t1)
    }
}

/// Bisection bound for locating the fall on the adaptive integrator's dense output.
const EVENT_ITERATIONS: usize = 60;

/// Simulates from `initial` (projected onto the constraints first) for `settings.duration`.
///
/// Returns `Err` only for unusable settings or an initial state that cannot be evaluated;
/// everything that happens during the run (a fall, a lifted wheel, a failed projection, a
/// non-finite state) is an [`Outcome`], with the samples computed up to then.
pub fn simulate(
    model: &Model,
    initial: State<f64>,
    settings: &SimulationSettings,
) -> Result<Simulation> {
    validate(settings)?;
    if !initial
        .q
        .iter()
        .chain(initial.u.iter())
        .all(|x| x.is_finite())
    {
        return Err(Error::NonFiniteState { t: 0.0 });
    }
    let ode = BicycleOde {
        model,
        steer_torque: settings.steer_torque.as_ref(),
        lean_torque: settings.lean_torque.as_ref(),
    };
    let t_end = settings.duration;
    let mut state = initial;
    let (report, poses) = model.project_posed(&mut state, &settings.projection)?;
    let mut d = ode.derivatives(0.0, &state)?;
    let mut t = 0.0;
    let mut samples = vec![sample(model, t, &state, &poses, &d, report.residual)];
    let mut steps = 0;
    let mut rejected_steps = 0;
    // Lift-off is a normal force turning negative; a wheel pulled down from the start is not
    // watched.
    let watched = [d.contact[0].normal >= 0.0, d.contact[1].normal >= 0.0];
    let pulled_down_from_start: Vec<Wheel> = [Wheel::Rear, Wheel::Front]
        .into_iter()
        .zip(watched)
        .filter(|(_, w)| !w)
        .map(|(wheel, _)| wheel)
        .collect();
    let finish = |samples, outcome, state, steps, rejected_steps| Simulation {
        samples,
        outcome,
        final_state: state,
        steps,
        rejected_steps,
        pulled_down_from_start: pulled_down_from_start.clone(),
    };
    // Events already true at the start.
    if state.lean().abs() > settings.fall_angle {
        let outcome = Outcome::Fell {
            t,
            lean: state.lean(),
        };
        return Ok(finish(samples, outcome, state, steps, rejected_steps));
    }

    let mut stepper = match &settings.integrator {
        Integrator::Dopri5(p) => Stepper::Dopri5 {
            controller: Controller::new(p, &state.to_vector(), &d.to_vector(), t_end),
            params: *p,
        },
        Integrator::Rk4 { dt } => Stepper::Rk4 {
            dt: *dt,
            total: rk4::step_count(t_end, *dt),
        },
    };
    let mut attempts = 0usize;
    loop {
        let done = match stepper {
            Stepper::Rk4 { total, .. } => steps >= total,
            Stepper::Dopri5 { .. } => t >= t_end,
        };
        if done {
            return Ok(finish(
                samples,
                Outcome::Completed,
                state,
                steps,
                rejected_steps,
            ));
        }
        if settings
            .stop
            .as_ref()
            .is_some_and(|stop| stop.load(Ordering::Relaxed))
        {
            return Ok(finish(
                samples,
                Outcome::Stopped { t },
                state,
                steps,
                rejected_steps,
            ));
        }
        let y = state.to_vector();
        let k1 = d.to_vector();
        // One accepted step: new (unprojected) y, its end time, and a dense output if any.
        let (t_new, y_new, dense) = match &mut stepper {
            Stepper::Rk4 { dt, total } => {
                let (dt, rk4_steps) = (*dt, *total);
                let t_new = if steps + 1 == rk4_steps {
                    t_end
                } else {
                    (steps + 1) as f64 * dt
                };
                match rk4::step_with_slope(&ode, t, &y, &k1, t_new - t) {
                    Ok(y_new) => (t_new, y_new, None),
                    Err(error) => {
                        return Ok(finish(
                            samples,
                            failure(t, error),
                            state,
                            steps,
                            rejected_steps,
                        ))
                    }
                }
            }
            Stepper::Dopri5 { controller, params } => loop {
                attempts += 1;
                if attempts > params.max_steps {
                    return Ok(finish(
                        samples,
                        Outcome::StepSizeTooSmall { t },
                        state,
                        steps,
                        rejected_steps,
                    ));
                }
                let h = controller.step().min(t_end - t);
                let attempt = match dopri5::attempt(&ode, t, &y, &k1, h, params) {
                    Ok(a) => a,
                    // A failed evaluation inside the step (e.g. a trial state too far off):
                    // treat as a rejected step of infinite error.
                    Err(_) => dopri5::Attempt {
                        y,
                        k7: k1,
                        error: f64::INFINITY,
                        dense: dopri5_dummy(t, h, &y),
                    },
                };
                match controller.accept(attempt.error, h) {
                    Ok(true) => {
                        let t_new = if t_end - (t + h) <= 1e-12 * t_end.max(1.0) {
                            t_end
                        } else {
                            t + h
                        };
                        break (t_new, attempt.y, Some(attempt.dense));
                    }
                    Ok(false) => rejected_steps += 1,
                    Err(_) => {
                        return Ok(finish(
                            samples,
                            Outcome::StepSizeTooSmall { t },
                            state,
                            steps,
                            rejected_steps,
                        ))
                    }
                }
            },
        };
        let mut next = State::from_vector(&y_new);
        if !y_new.iter().all(|v| v.is_finite()) {
            return Ok(finish(
                samples,
                Outcome::NonFiniteState { t: t_new },
                state,
                steps,
                rejected_steps,
            ));
        }
        let (report, poses) = match model.project_posed(&mut next, &settings.projection) {
            Ok(r) => r,
            Err(Error::ProjectionDiverged {
                iterations,
                residual,
            }) => {
                let outcome = Outcome::ProjectionFailed {
                    t: t_new,
                    iterations,
                    residual,
                };
                return Ok(finish(samples, outcome, state, steps, rejected_steps));
            }
            Err(error) => {
                return Ok(finish(
                    samples,
                    failure(t_new, error),
                    state,
                    steps,
                    rejected_steps,
                ))
            }
        };
        let d_new = match ode.derivatives(t_new, &next) {
            Ok(d) => d,
            Err(error) => {
                return Ok(finish(
                    samples,
                    failure(t_new, error),
                    state,
                    steps,
                    rejected_steps,
                ))
            }
        };
        steps += 1;
        samples.push(sample(model, t_new, &next, &poses, &d_new, report.residual));
        if let Some(progress) = &settings.progress {
            progress(Progress {
                t: t_new,
                t_end,
                steps,
            });
        }
        // Events, in the order they happen within the step.
        let lean0 = state.lean();
        let lean1 = next.lean();
        let fall = settings.fall_angle;
        let mut events: Vec<(f64, Outcome)> = Vec::new();
        if lean1.abs() > fall {
            let t_fall = match &dense {
                Some(dense) => fall_time(dense, t, t_new, fall),
                None => crossing(t, lean0.abs() - fall, t_new, lean1.abs() - fall),
            };
            let lean = match &dense {
                Some(dense) => State::from_vector(&dense.at(t_fall)).lean(),
                None => lean0 + (lean1 - lean0) * (t_fall - t) / (t_new - t),
            };
            events.push((t_fall, Outcome::Fell { t: t_fall, lean }));
        }
        if settings.stop_on_lift_off {
            for (i, wheel) in [Wheel::Rear, Wheel::Front].into_iter().enumerate() {
                let (n0, n1) = (d.contact[i].normal, d_new.contact[i].normal);
                if watched[i] && n1 < 0.0 {
                    let t_lift = crossing(t, n0, t_new, n1);
                    events.push((t_lift, Outcome::WheelLifted { t: t_lift, wheel }));
                }
            }
        }
        state = next;
        d = d_new;
        t = t_new;
        if let Some((_, outcome)) = events.into_iter().min_by(|a, b| a.0.total_cmp(&b.0)) {
            return Ok(finish(samples, outcome, state, steps, rejected_steps));
        }
    }
}

/// The integrator's running state.
enum Stepper {
    Rk4 {
        dt: f64,
        total: usize,
    },
    Dopri5 {
        controller: Controller,
        params: Dopri5Params,
    },
}

fn failure(t: f64, error: Error) -> Outcome {
    match error {
        Error::NonFiniteState { t } => Outcome::NonFiniteState { t },
        error => Outcome::Failed { t, error },
    }
}

/// A constant "interpolant" for a failed attempt (it is rejected and never evaluated).
fn dopri5_dummy(t: f64, h: f64, y: &SVector<f64, STATE_LEN>) -> dopri5::DenseOutput<STATE_LEN> {
    dopri5::DenseOutput::constant(t, h, y)
}

/// The time in [t0, t1] where |lean| reaches `fall` on the dense output, by bisection.
fn fall_time(dense: &dopri5::DenseOutput<STATE_LEN>, t0: f64, t1: f64, fall: f64) -> f64 {
    let g = |t: f64| State::from_vector(&dense.at(t)).lean().abs() - fall;
    let (mut lo, mut hi) = (t0, t1);
    if g(lo) > 0.0 {
        return t0;
    }
    for _ in 0..EVENT_ITERATIONS {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo <= 1e-14 * hi.abs().max(1.0) {
            break;
        }
    }
    hi
}

fn validate(settings: &SimulationSettings) -> Result<()> {
    let d = settings.duration;
    if !(d.is_finite() && d >= 0.0) {
        return Err(Error::InvalidArgument {
            what: "duration",
            rule: format!("must be a finite number >= 0 s, got {d}"),
        });
    }
    let a = settings.fall_angle;
    if !(a > 0.0 && a < std::f64::consts::FRAC_PI_2) {
        return Err(Error::InvalidArgument {
            what: "fall_angle",
            rule: format!("must lie strictly between 0 and pi/2 rad (the orientation angles are singular at pi/2), got {a}"),
        });
    }
    let p = &settings.projection;
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
    match settings.integrator {
        Integrator::Rk4 { dt } => crate::integrate::Method::Rk4 { dt }.validate(),
        Integrator::Dopri5(p) => p.validate(),
    }
}
