//! Simulation of the multibody bicycle: integration step by step ([`crate::integrate`]'s
//! stepper), projection onto the constraints after every step, events (fall, wheel lift-off,
//! end time) and samples.
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

use std::sync::atomic::Ordering;

use nalgebra::SVector;

use super::forward::{Derivatives, Inputs};
use super::outcome::{Outcome, Progress, RunExtremes, Sample, Simulation, Wheel};
use super::poses::Poses;
use super::settings::{SimulationSettings, TorqueFn};
use super::state::{State, STATE_LEN};
use super::Model;
use crate::error::{Error, Result};
use crate::integrate::{DenseOutput, OdeSystem, Step, StepFailure, Stepper};

/// The model with its rider inputs as an ODE ẏ = f(t, y) on y = [q; u].
pub(crate) struct BicycleOde<'a> {
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
    settings.validate()?;
    if !initial.is_finite() {
        return Err(Error::NonFiniteState { t: 0.0 });
    }
    let ode = BicycleOde {
        model,
        steer_torque: settings.steer_torque.as_ref(),
        lean_torque: settings.lean_torque.as_ref(),
    };
    let mut run = Run::start(&ode, initial, settings)?;
    let outcome = run.until_done();
    // The last state reached is always a sample, thinned or not.
    if let Some(last) = run.pending.take() {
        run.samples.push(last);
    }
    Ok(Simulation {
        extremes: run.extremes,
        outcome,
        final_state: run.state,
        steps: run.steps,
        rejected_steps: run.stepper.rejected(),
        pulled_down_from_start: Wheel::BOTH
            .into_iter()
            .zip(run.watched)
            .filter(|(_, watched)| !watched)
            .map(|(wheel, _)| wheel)
            .collect(),
        samples: run.samples,
    })
}

/// A run under way: the last accepted (projected) state, its derivatives and the samples.
struct Run<'a> {
    ode: &'a BicycleOde<'a>,
    settings: &'a SimulationSettings,
    stepper: Stepper,
    state: State<f64>,
    derivatives: Derivatives<f64>,
    samples: Vec<Sample>,
    /// The last accepted step's sample when it was thinned out.
    pending: Option<Sample>,
    extremes: RunExtremes,
    steps: usize,
    /// Lift-off is a normal force turning negative; a wheel pulled down from the start is not
    /// watched.
    watched: [bool; 2],
}

impl<'a> Run<'a> {
    /// Projects the initial state, evaluates it and records the first sample.
    fn start(
        ode: &'a BicycleOde<'a>,
        initial: State<f64>,
        settings: &'a SimulationSettings,
    ) -> Result<Self> {
        let mut state = initial;
        let (report, poses) = ode.model.project_posed(&mut state, &settings.projection)?;
        let derivatives = ode.derivatives(0.0, &state)?;
        let stepper = Stepper::new(
            &settings.integrator,
            &state.to_vector(),
            &derivatives.to_vector(),
            settings.duration,
        )?;
        let first = sample(
            ode.model,
            0.0,
            &state,
            &poses,
            &derivatives,
            report.residual,
        );
        Ok(Run {
            ode,
            settings,
            stepper,
            state,
            derivatives,
            samples: vec![first],
            pending: None,
            extremes: RunExtremes::start(&first),
            steps: 0,
            watched: derivatives.contact.map(|c| c.normal >= 0.0),
        })
    }

    /// Steps until the end time, an event or a failure.
    fn until_done(&mut self) -> Outcome {
        let lean = self.state.lean();
        if lean.abs() > self.settings.fall_angle {
            return Outcome::Fell { t: 0.0, lean };
        }
        loop {
            if self.stepper.done() {
                return Outcome::Completed;
            }
            let t = self.stepper.t();
            let stop = self.settings.stop.as_ref();
            if stop.is_some_and(|stop| stop.load(Ordering::Relaxed)) {
                return Outcome::Stopped { t };
            }
            if let Err(outcome) = self.advance() {
                return outcome;
            }
        }
    }

    /// One accepted step: integrate, project, evaluate, record, look for events. The outcome
    /// that ends the run, if any, is the error.
    fn advance(&mut self) -> std::result::Result<(), Outcome> {
        let (t, model) = (self.stepper.t(), self.ode.model);
        let y = self.state.to_vector();
        let Step {
            t: t_new,
            y: y_new,
            dense,
        } = self
            .stepper
            .step(self.ode, &y, &self.derivatives.to_vector())
            .map_err(|failure| match failure {
                StepFailure::StepSizeTooSmall => Outcome::StepSizeTooSmall { t },
                StepFailure::Evaluation(error) => failed(t, error),
                StepFailure::NonFinite { t } => Outcome::NonFiniteState { t },
            })?;
        let mut next = State::from_vector(&y_new);
        let (report, poses) = model
            .project_posed(&mut next, &self.settings.projection)
            .map_err(|error| match error {
                Error::ProjectionDiverged {
                    iterations,
                    residual,
                } => Outcome::ProjectionFailed {
                    t: t_new,
                    iterations,
                    residual,
                },
                error => failed(t_new, error),
            })?;
        let d_new = self
            .ode
            .derivatives(t_new, &next)
            .map_err(|error| failed(t_new, error))?;
        self.steps += 1;
        let recorded = sample(model, t_new, &next, &poses, &d_new, report.residual);
        self.extremes.observe(&recorded);
        if self.steps % self.settings.sample_every.max(1) == 0 {
            self.samples.push(recorded);
            self.pending = None;
        } else {
            self.pending = Some(recorded);
        }
        if let Some(progress) = &self.settings.progress {
            progress(Progress {
                t: t_new,
                t_end: self.settings.duration,
                steps: self.steps,
            });
        }
        let event = self.first_event(t, &next, &d_new, t_new, dense.as_ref());
        self.state = next;
        self.derivatives = d_new;
        event.map_or(Ok(()), Err)
    }

    /// The first event within the step from (t0, the current state) to (t1, `next`): a fall
    /// (located on the dense output where there is one, linearly otherwise) or a wheel's normal
    /// force turning negative (linearly).
    fn first_event(
        &self,
        t0: f64,
        next: &State<f64>,
        d_new: &Derivatives<f64>,
        t1: f64,
        dense: Option<&DenseOutput<STATE_LEN>>,
    ) -> Option<Outcome> {
        let (lean0, lean1) = (self.state.lean(), next.lean());
        let fall = self.settings.fall_angle;
        let mut events: Vec<(f64, Outcome)> = Vec::new();
        if lean1.abs() > fall {
            let (t_fall, lean) = match dense {
                Some(dense) => {
                    let t_fall = fall_time(dense, t0, t1, fall);
                    (t_fall, State::from_vector(&dense.at(t_fall)).lean())
                }
                None => {
                    let t_fall = crossing(t0, lean0.abs() - fall, t1, lean1.abs() - fall);
                    (t_fall, lean0 + (lean1 - lean0) * (t_fall - t0) / (t1 - t0))
                }
            };
            events.push((t_fall, Outcome::Fell { t: t_fall, lean }));
        }
        if self.settings.stop_on_lift_off {
            for (i, wheel) in Wheel::BOTH.into_iter().enumerate() {
                let (n0, n1) = (self.derivatives.contact[i].normal, d_new.contact[i].normal);
                if self.watched[i] && n1 < 0.0 {
                    let t = crossing(t0, n0, t1, n1);
                    events.push((
                        t,
                        Outcome::WheelLifted {
                            t,
                            wheel,
                            lean: lean1,
                        },
                    ));
                }
            }
        }
        events
            .into_iter()
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, outcome)| outcome)
    }
}

/// The sample of a projected state.
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

/// The outcome of an evaluation that failed at t.
fn failed(t: f64, error: Error) -> Outcome {
    match error {
        Error::NonFiniteState { t } => Outcome::NonFiniteState { t },
        error => Outcome::Failed { t, error },
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

/// The time in [t0, t1] where |lean| reaches `fall` on the dense output, by bisection.
fn fall_time(dense: &DenseOutput<STATE_LEN>, t0: f64, t1: f64, fall: f64) -> f64 {
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
