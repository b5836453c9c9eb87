//! Simulation of the multibody bicycle: integration step by step ([`crate::integrate`]'s
//! stepper), projection onto the constraints after every step, events (fall, wheel lift-off,
//! end time) and samples.
//!
//! ```
//! use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, SimulationSettings};
//! use whipple::advanced::nonlinear::*;
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

use super::Model;
use super::forward::{ContactForce, Inputs, StateRates};
use super::outcome::{Outcome, Progress, RunExtremes, Sample, Simulation, Wheel};
use super::poses::Poses;
use super::settings::{SimulationSettings, TorqueFn};
use super::state::{STATE_LEN, State};
use crate::analysis::eigen::{self, Complex64};
use crate::error::{Error, Result, short_number};
use crate::integrate::{
    DenseOutput, Integrator, OdeSystem, RK4_ACCURATE_RADIUS, RK4_STABLE_RADIUS, Step, StepFailure,
    Stepper, round_down_125,
};
use crate::linear::Canonical;

/// The largest drift of the energy balance a run may show, as a fraction of its energy scale
/// (the initial energy plus the work the rider's torques did, in size): E − E₀ − W, with W the
/// rider's work (trapezoidal over each step). Without rider torques the bicycle conserves its
/// energy (rolling without slip, no friction), and a run at the default step keeps it to about
/// 1e-12 of itself (the benchmark bicycle's kicked weave at 4.6 m/s; 1e-9 for one falling over
/// at 3 m/s); a drift of 1% is the integrator's, not the bicycle's.
pub(crate) const MAX_ENERGY_DRIFT: f64 = 1e-2;

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
    pub(crate) fn derivatives(&self, t: f64, state: &State<f64>) -> Result<StateRates<f64>> {
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

    /// The rider's power at (t, state) [W]: T_δ δ̇ + T_φ φ̇ (the steer torque acts between the
    /// frames about the steer axis, the lean torque on the rear frame about the lean axis); 0
    /// hands free, and 0 where a torque is not finite (the step reports that).
    pub(crate) fn power(&self, t: f64, state: &State<f64>) -> f64 {
        if self.steer_torque.is_none() && self.lean_torque.is_none() {
            return 0.0;
        }
        let view = self.model.observe(state);
        let steer = self.steer_torque.map_or(0.0, |f| f(t, &view));
        let lean = self.lean_torque.map_or(0.0, |f| f(t, &view));
        let power = steer * view.steer_rate + lean * view.lean_rate;
        if power.is_finite() { power } else { 0.0 }
    }
}

impl OdeSystem<STATE_LEN> for BicycleOde<'_> {
    fn rhs(&self, t: f64, y: &SVector<f64, STATE_LEN>) -> Result<SVector<f64, STATE_LEN>> {
        Ok(self.derivatives(t, &State::from_vector(y))?.to_vector())
    }
}

/// What a run steps: the four bodies ([`BicycleOde`]) or the four with more bodies and states
/// of their own (the leaning rider's `LeanOde`), as an ODE on a first-order vector of length
/// `N` whose first [`STATE_LEN`] entries are the four bodies' [q; u]. One loop steps them all:
/// projection of the four bodies onto the constraints after each step, the energy balance,
/// the fall, a lifted wheel and the mechanism's own events, samples, progress and stop.
pub(crate) trait Mechanism<const N: usize>: OdeSystem<N> {
    /// The whole state.
    type State: Copy;
    /// What a sample keeps of the state beyond the four bodies' [`Sample`].
    type Record: Copy;
    /// The four bodies' model.
    fn model(&self) -> &Model;
    /// The state of a first-order vector.
    fn from_vector(y: &SVector<f64, N>) -> Self::State;
    /// The first-order vector of a state.
    fn to_vector(state: &Self::State) -> SVector<f64, N>;
    /// The four bodies' part of a state.
    fn bicycle(state: &Self::State) -> &State<f64>;
    /// The same, to project it.
    fn bicycle_mut(state: &mut Self::State) -> &mut State<f64>;
    /// The rates and the ground forces on the rear and front wheel at (t, state).
    fn evaluate(
        &self,
        t: f64,
        state: &Self::State,
    ) -> Result<(SVector<f64, N>, [ContactForce<f64>; 2])>;
    /// The total mechanical energy \[J\].
    fn energy(&self, state: &Self::State) -> f64;
    /// The power of the inputs and of any damper at (t, state) \[W\].
    fn power(&self, t: f64, state: &Self::State) -> f64;
    /// What a sample keeps of the state besides the [`Sample`].
    fn record(&self, state: &Self::State) -> Self::Record;
    /// An event of the mechanism's own within the step from (t0, s0) to (t1, s1): its time and
    /// outcome.
    fn own_event(
        &self,
        _t0: f64,
        _s0: &Self::State,
        _t1: f64,
        _s1: &Self::State,
    ) -> Option<(f64, Outcome)> {
        None
    }
}

impl Mechanism<STATE_LEN> for BicycleOde<'_> {
    type State = State<f64>;
    type Record = ();

    fn model(&self) -> &Model {
        self.model
    }

    fn from_vector(y: &SVector<f64, STATE_LEN>) -> State<f64> {
        State::from_vector(y)
    }

    fn to_vector(state: &State<f64>) -> SVector<f64, STATE_LEN> {
        state.to_vector()
    }

    fn bicycle(state: &State<f64>) -> &State<f64> {
        state
    }

    fn bicycle_mut(state: &mut State<f64>) -> &mut State<f64> {
        state
    }

    fn evaluate(
        &self,
        t: f64,
        state: &State<f64>,
    ) -> Result<(SVector<f64, STATE_LEN>, [ContactForce<f64>; 2])> {
        let d = self.derivatives(t, state)?;
        Ok((d.to_vector(), d.contact))
    }

    fn energy(&self, state: &State<f64>) -> f64 {
        self.model.energy(state)
    }

    fn power(&self, t: f64, state: &State<f64>) -> f64 {
        BicycleOde::power(self, t, state)
    }

    fn record(&self, _: &State<f64>) {}
}

/// A finished run of a [`Mechanism`]: the four bodies' [`Simulation`], each sample's record,
/// and the last state reached.
pub(crate) struct MechanismRun<M: Mechanism<N>, const N: usize> {
    pub(crate) simulation: Simulation,
    pub(crate) records: Vec<M::Record>,
    pub(crate) final_state: M::State,
}

/// The upright linearized bicycle's fastest mode at `speed`: the eigenvalue of A(v) largest in
/// size (at low speed the castering mode, at very low speed the capsize and inverted-pendulum
/// pair). `None` when the linear model cannot be formed for these parameters.
pub fn fastest_mode(model: &Model, speed: f64) -> Option<Complex64> {
    let canonical = Canonical::new(model.parameters()).ok()?;
    eigen::eigenvalues(&canonical, speed)
        .ok()?
        .into_iter()
        .filter(|l| l.re.is_finite() && l.im.is_finite())
        .max_by(|a, b| crate::math::norm(a).total_cmp(&crate::math::norm(b)))
}

/// The a-priori check of RK4's fixed step `dt` for a run at `speed`: the upright linearized
/// bicycle's fastest mode λ ([`fastest_mode`]) must have |λ|·dt ≤ `RK4_STABLE_RADIUS`, or
/// [`Error::StepTooLarge`] suggests a step with |λ|·dt ≤ `RK4_ACCURATE_RADIUS` (rounded down
/// to 1, 2 or 5 × 10ᵏ). Cheap (one quartic), and a bound for the run's start only: a leaning
/// or turning bicycle has other modes, which the energy check during the run covers.
///
/// ```
/// use whipple::{BenchmarkParameters, Error};
/// use whipple::advanced::nonlinear::check_rk4_step;
/// use whipple::Model;
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// assert!(check_rk4_step(&model, 4.6, 1e-3).is_ok());
/// let Err(Error::StepTooLarge { what, suggested, .. }) = check_rk4_step(&model, 4.6, 0.25) else {
///     panic!("a quarter-second step resolves nothing at 4.6 m/s")
/// };
/// assert_eq!((what, suggested), ("dt", 0.05));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn check_rk4_step(model: &Model, speed: f64, dt: f64) -> Result<()> {
    check_rk4_mode(fastest_mode(model, speed), speed, dt)
}

/// [`check_rk4_step`] for a fastest mode `lambda` found elsewhere (the leaning rider's).
pub(crate) fn check_rk4_mode(lambda: Option<Complex64>, speed: f64, dt: f64) -> Result<()> {
    let Some(lambda) = lambda else {
        return Ok(());
    };
    let size = crate::math::norm(lambda);
    if size * dt <= RK4_STABLE_RADIUS {
        return Ok(());
    }
    let mode = if lambda.im == 0.0 {
        format!("{:.4}", lambda.re)
    } else {
        format!("{:.4} ± {:.4}i", lambda.re, lambda.im.abs())
    };
    Err(Error::StepTooLarge {
        what: "dt",
        value: dt,
        reason: format!(
            "the fastest mode of the linearized bicycle at {} m/s, λ = {mode} 1/s, has |λ|·dt = {:.3}, beyond RK4's stability bound |λ|·dt <= {RK4_STABLE_RADIUS} (the steps would amplify what the bicycle damps)",
            short_number(speed),
            size * dt
        ),
        suggested: round_down_125(RK4_ACCURATE_RADIUS / size),
    })
}

/// Simulates from `initial` (projected onto the constraints first) for `settings.duration`.
///
/// Returns `Err` for unusable settings, an initial state that cannot be evaluated, and a step
/// too coarse for the run ([`Error::StepTooLarge`]): an RK4 step beyond the stability bound of
/// the fastest mode at the run's speed ([`check_rk4_step`], before any step), or, for either
/// integrator, an energy balance drifting by more than `MAX_ENERGY_DRIFT` during the run.
/// Everything else that happens during the run (a fall, a lifted wheel, a failed projection, a
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
    if let Integrator::Rk4 { dt } = settings.integrator {
        check_rk4_step(model, model.speed(&initial), dt)?;
    }
    let ode = BicycleOde {
        model,
        steer_torque: settings.steer_torque.as_ref(),
        lean_torque: settings.lean_torque.as_ref(),
    };
    Ok(run_mechanism(&ode, initial, settings)?.simulation)
}

/// Runs a [`Mechanism`] from `initial` (its four bodies projected onto the constraints first)
/// for `settings.duration`: [`simulate`]'s loop for any mechanism (settings already checked).
pub(crate) fn run_mechanism<M: Mechanism<N>, const N: usize>(
    mechanism: &M,
    initial: M::State,
    settings: &SimulationSettings,
) -> Result<MechanismRun<M, N>> {
    let mut run = Run::start(mechanism, initial, settings)?;
    let outcome = run.until_done()?;
    // The last state reached is always a sample, thinned or not.
    if let Some((last, record)) = run.pending.take() {
        run.samples.push(last);
        run.records.push(record);
    }
    Ok(MechanismRun {
        simulation: Simulation {
            extremes: run.extremes,
            outcome,
            final_state: *M::bicycle(&run.state),
            steps: run.steps,
            rejected_steps: run.stepper.rejected(),
            pulled_down_from_start: Wheel::BOTH
                .into_iter()
                .zip(run.watched)
                .filter(|(_, watched)| !watched)
                .map(|(wheel, _)| wheel)
                .collect(),
            samples: run.samples,
        },
        records: run.records,
        final_state: run.state,
    })
}

/// A run under way: the last accepted (projected) state, its rates and ground forces, and the
/// samples.
struct Run<'a, M: Mechanism<N>, const N: usize> {
    ode: &'a M,
    settings: &'a SimulationSettings,
    stepper: Stepper,
    state: M::State,
    derivatives: SVector<f64, N>,
    contact: [ContactForce<f64>; 2],
    samples: Vec<Sample>,
    records: Vec<M::Record>,
    /// The last accepted step's sample when it was thinned out.
    pending: Option<(Sample, M::Record)>,
    extremes: RunExtremes,
    steps: usize,
    /// Lift-off is a normal force turning negative; a wheel pulled down from the start is not
    /// watched.
    watched: [bool; 2],
    /// The energy balance: the rider's power at the current state, the work done so far and
    /// the sum of its sizes (the scale of the balance besides the initial energy).
    power: f64,
    work: f64,
    work_size: f64,
}

/// What ends a run: an outcome, or an error (a step too coarse for the run).
enum End {
    Outcome(Outcome),
    Error(Error),
}

impl From<Outcome> for End {
    fn from(outcome: Outcome) -> Self {
        End::Outcome(outcome)
    }
}

impl<'a, M: Mechanism<N>, const N: usize> Run<'a, M, N> {
    /// Projects the initial state, evaluates it and records the first sample.
    fn start(ode: &'a M, initial: M::State, settings: &'a SimulationSettings) -> Result<Self> {
        let mut state = initial;
        let (report, poses) = ode
            .model()
            .project_posed(M::bicycle_mut(&mut state), &settings.projection)?;
        let (derivatives, contact) = ode.evaluate(0.0, &state)?;
        let stepper = Stepper::new(
            &settings.integrator,
            &M::to_vector(&state),
            &derivatives,
            settings.duration,
        )?;
        let first = sample(
            ode.model(),
            0.0,
            M::bicycle(&state),
            &poses,
            contact,
            ode.energy(&state),
            report.residual,
        );
        Ok(Run {
            ode,
            settings,
            stepper,
            state,
            derivatives,
            contact,
            samples: vec![first],
            records: vec![ode.record(&state)],
            pending: None,
            extremes: RunExtremes::start(&first),
            steps: 0,
            watched: contact.map(|c| c.normal >= 0.0),
            power: ode.power(0.0, &state),
            work: 0.0,
            work_size: 0.0,
        })
    }

    /// Steps until the end time, an event or a failure; `Err` for a step too coarse for the
    /// run.
    fn until_done(&mut self) -> Result<Outcome> {
        let lean = M::bicycle(&self.state).lean();
        if lean.abs() > self.settings.fall_angle {
            return Ok(Outcome::Fell { t: 0.0, lean });
        }
        loop {
            if self.stepper.done() {
                return Ok(Outcome::Completed);
            }
            let t = self.stepper.t();
            let stop = self.settings.stop.as_ref();
            if stop.is_some_and(|stop| stop.load(Ordering::Relaxed)) {
                return Ok(Outcome::Stopped { t });
            }
            match self.advance() {
                Ok(()) => {}
                Err(End::Outcome(outcome)) => return Ok(outcome),
                Err(End::Error(error)) => return Err(error),
            }
        }
    }

    /// The energy balance after the step from t0 to the sample `s` (its state `next`): the
    /// rider's work by the trapezoidal rule, and [`Error::StepTooLarge`] when E − E₀ − W has
    /// drifted beyond [`MAX_ENERGY_DRIFT`] of the balance's scale.
    fn check_energy(&mut self, t0: f64, next: &M::State, s: &Sample) -> Result<()> {
        let power = self.ode.power(s.t, next);
        let work = 0.5 * (self.power + power) * (s.t - t0);
        self.power = power;
        self.work += work;
        self.work_size += work.abs();
        let initial = self.extremes.initial_energy;
        let drift = s.energy - initial - self.work;
        let scale = initial.abs() + self.work_size;
        // A non-finite energy is the NonFiniteState outcome's, not this check's.
        if !(drift.is_finite() && scale.is_finite()) || drift.abs() <= MAX_ENERGY_DRIFT * scale {
            return Ok(());
        }
        let balance = if self.work_size > 0.0 {
            format!(" (beyond the rider's work of {} J)", digits4(self.work))
        } else {
            String::new()
        };
        let reason = format!(
            "the energy drifted by {} J{balance} from {} J by t = {:.4} s, {:.3e} of the run's energy where the bicycle conserves it (the limit is {MAX_ENERGY_DRIFT}): the motion computed is the integrator's, not the bicycle's",
            digits4(drift),
            digits4(initial),
            s.t,
            drift.abs() / scale
        );
        Err(match self.settings.integrator {
            Integrator::Rk4 { dt } => Error::StepTooLarge {
                what: "dt",
                value: dt,
                reason,
                suggested: round_down_125(dt / 10.0),
            },
            Integrator::Dopri5(p) => Error::StepTooLarge {
                what: "rtol",
                value: p.rtol,
                reason,
                suggested: round_down_125(p.rtol / 1000.0),
            },
        })
    }

    /// One accepted step: integrate, project, evaluate, record, look for events. The outcome
    /// that ends the run, if any, is the error, as is a step too coarse for the run.
    fn advance(&mut self) -> std::result::Result<(), End> {
        let (t, model) = (self.stepper.t(), self.ode.model());
        let y = M::to_vector(&self.state);
        let Step {
            t: t_new,
            y: y_new,
            dense,
        } = self.stepper.step(self.ode, &y, &self.derivatives).map_err(
            |failure| match failure {
                StepFailure::StepSizeTooSmall => Outcome::StepSizeTooSmall { t },
                StepFailure::Evaluation(error) => failed(t, error),
                StepFailure::NonFinite { t } => Outcome::NonFiniteState { t },
            },
        )?;
        let mut next = M::from_vector(&y_new);
        let (report, poses) = model
            .project_posed(M::bicycle_mut(&mut next), &self.settings.projection)
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
        let (d_new, contact) = self
            .ode
            .evaluate(t_new, &next)
            .map_err(|error| failed(t_new, error))?;
        self.steps += 1;
        let recorded = sample(
            model,
            t_new,
            M::bicycle(&next),
            &poses,
            contact,
            self.ode.energy(&next),
            report.residual,
        );
        self.check_energy(t, &next, &recorded).map_err(End::Error)?;
        self.extremes.observe(&recorded);
        if self.steps % self.settings.sample_every.max(1) == 0 {
            self.samples.push(recorded);
            self.records.push(self.ode.record(&next));
            self.pending = None;
        } else {
            self.pending = Some((recorded, self.ode.record(&next)));
        }
        if let Some(progress) = &self.settings.progress {
            progress(Progress {
                t: t_new,
                t_end: self.settings.duration,
                steps: self.steps,
            });
        }
        let event = self.first_event(t, &next, contact, t_new, dense.as_ref());
        self.state = next;
        self.derivatives = d_new;
        self.contact = contact;
        event.map_or(Ok(()), |outcome| Err(outcome.into()))
    }

    /// The first event within the step from (t0, the current state) to (t1, `next`): a fall
    /// (located on the dense output where there is one, linearly otherwise), a wheel's normal
    /// force turning negative (linearly) or the mechanism's own.
    fn first_event(
        &self,
        t0: f64,
        next: &M::State,
        contact: [ContactForce<f64>; 2],
        t1: f64,
        dense: Option<&DenseOutput<N>>,
    ) -> Option<Outcome> {
        let (lean0, lean1) = (M::bicycle(&self.state).lean(), M::bicycle(next).lean());
        let fall = self.settings.fall_angle;
        let mut events: Vec<(f64, Outcome)> = Vec::new();
        if lean1.abs() > fall {
            let (t_fall, lean) = match dense {
                Some(dense) => {
                    let lean = |t: f64| M::bicycle(&M::from_vector(&dense.at(t))).lean();
                    let t_fall = fall_time(lean, t0, t1, fall);
                    (t_fall, lean(t_fall))
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
                let (n0, n1) = (self.contact[i].normal, contact[i].normal);
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
        events.extend(self.ode.own_event(t0, &self.state, t1, next));
        events
            .into_iter()
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, outcome)| outcome)
    }
}

/// A number to four significant digits for a message (exponent form when very large or small).
fn digits4(x: f64) -> String {
    let size = x.abs();
    if (1e-3..1e6).contains(&size) {
        // 4 significant digits: 1 to 6 decimals in this range.
        let decimals = (3.0 - crate::math::log10(size).floor()).clamp(0.0, 6.0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.3e}")
    }
}

/// The sample of a projected state (its four bodies', with the mechanism's ground forces and
/// energy).
fn sample(
    model: &Model,
    t: f64,
    state: &State<f64>,
    poses: &Poses<f64>,
    contact: [ContactForce<f64>; 2],
    energy: f64,
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
        energy,
        position_residual,
        velocity_residual: model.velocity_residual_at(poses, state).amax(),
        rear: contact[0],
        front: contact[1],
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
pub(crate) fn crossing(t0: f64, g0: f64, t1: f64, g1: f64) -> f64 {
    if g1 == g0 {
        t1
    } else {
        (t0 + (t1 - t0) * g0 / (g0 - g1)).clamp(t0, t1)
    }
}

/// Bisection bound for locating the fall on the adaptive integrator's dense output.
const EVENT_ITERATIONS: usize = 60;

/// The time in [t0, t1] where |lean(t)| reaches `fall` (the lean on the dense output), by
/// bisection.
fn fall_time(lean: impl Fn(f64) -> f64, t0: f64, t1: f64, fall: f64) -> f64 {
    let g = |t: f64| lean(t).abs() - fall;
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
