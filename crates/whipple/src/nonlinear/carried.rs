//! A simulation that carries a few states of its own beside the bicycle's: a controller's (a
//! rider's neuromuscular filter, a command filter), integrated together with the bicycle in one
//! system so that the adaptive integrator controls the error of both.
//!
//! The carried states x_c have rates f_c(t, view, x_c) given the bicycle's named quantities
//! ([`StateView`]), and the rider's torques are read from them: [`Inputs`](super::Inputs)
//! from (t, view, x_c). After every step the bicycle's part is projected onto the constraints
//! as [`super::simulate`] does; the carried part is left as integrated. The run goes from
//! break point to break point (each a fresh Dormand–Prince 5(4) run to it), so that an input
//! with a kink at a break point is smooth within every run, and every sample is a step's end,
//! never an interpolation.

use nalgebra::SVector;

use super::Model;
use super::forward::Inputs;
use super::outcome::Outcome;
use super::projection::ProjectionSettings;
use super::state::{STATE_LEN, State, StateView};
use crate::error::{Error, Result};
use crate::integrate::{Integrator, StepFailure, Stepper};

/// How many states a carrying simulation holds beside the bicycle's.
pub(crate) const CARRIED: usize = 4;

/// The bicycle's states and the carried ones in one vector.
const CARRYING_LEN: usize = STATE_LEN + CARRIED;

/// What a carrying simulation computed at its break points.
pub(crate) struct CarriedRun {
    /// The bicycle's named quantities at each break point reached (the first at t = 0).
    pub(crate) views: Vec<StateView>,
    /// The carried states there.
    pub(crate) carried: Vec<[f64; CARRIED]>,
    /// The accepted steps, all runs together.
    pub(crate) steps: usize,
    /// Completed, or why the run ended early (the samples so far kept).
    pub(crate) outcome: Outcome,
}

/// Simulates from `initial` (projected first) with the carried states starting at `carried`,
/// their rates and the rider's torques given by `rhs(t, view, carried)`, Dormand–Prince 5(4)
/// at relative tolerance `rtol` (absolute `rtol`·1e-2), from break point to break point
/// (`ends`, increasing, positive), recording the state at t = 0 and at every end. A lean beyond
/// `fall_angle` ends the run (outcome [`Outcome::Fell`], at the step's end).
pub(crate) fn simulate_carrying<F>(
    model: &Model,
    initial: State<f64>,
    carried: [f64; CARRIED],
    rhs: F,
    ends: &[f64],
    rtol: f64,
    fall_angle: f64,
) -> Result<CarriedRun>
where
    F: Fn(f64, &StateView, &[f64; CARRIED]) -> ([f64; CARRIED], Inputs<f64>),
{
    let integrator = Integrator::adaptive(rtol);
    integrator.validate()?;
    let projection = ProjectionSettings::default();
    let mut state = initial;
    model.project(&mut state, &projection)?;
    let split = |y: &SVector<f64, CARRYING_LEN>| -> (State<f64>, [f64; CARRIED]) {
        let bicycle = State::from_vector(&y.fixed_rows::<STATE_LEN>(0).into_owned());
        (bicycle, std::array::from_fn(|i| y[STATE_LEN + i]))
    };
    let join = |bicycle: &SVector<f64, STATE_LEN>, carried: &[f64; CARRIED]| {
        let mut y = SVector::<f64, CARRYING_LEN>::zeros();
        y.fixed_rows_mut::<STATE_LEN>(0).copy_from(bicycle);
        for (i, c) in carried.iter().enumerate() {
            y[STATE_LEN + i] = *c;
        }
        y
    };
    let rates = |t: f64, y: &SVector<f64, CARRYING_LEN>| -> Result<SVector<f64, CARRYING_LEN>> {
        let (bicycle, carried) = split(y);
        if !(bicycle.is_finite() && carried.iter().all(|x| x.is_finite())) {
            return Err(Error::NonFiniteState { t });
        }
        let view = model.observe(&bicycle);
        let (carried_rates, inputs) = rhs(t, &view, &carried);
        if !(inputs.steer_torque.is_finite()
            && inputs.lean_torque.is_finite()
            && carried_rates.iter().all(|x| x.is_finite()))
        {
            return Err(Error::NonFiniteState { t });
        }
        let bicycle_rates = model.forward(&bicycle, &inputs)?.to_vector();
        Ok(join(&bicycle_rates, &carried_rates))
    };
    let mut y = join(&state.to_vector(), &carried);
    let mut run = CarriedRun {
        views: vec![model.observe(&state)],
        carried: vec![carried],
        steps: 0,
        outcome: Outcome::Completed,
    };
    let mut t0 = 0.0;
    for &end in ends {
        let span = end - t0;
        if !(span.is_finite() && span > 0.0) {
            return Err(Error::InvalidArgument {
                what: "times",
                rule: format!("break points must increase from 0 s: {end} s after {t0} s"),
            });
        }
        let shifted = |t: f64, y: &SVector<f64, CARRYING_LEN>| rates(t0 + t, y);
        let mut stepper = Stepper::new(&integrator, &y, &shifted(0.0, &y)?, span)?;
        while !stepper.done() {
            let t = t0 + stepper.t();
            let slope = match shifted(stepper.t(), &y) {
                Ok(slope) => slope,
                Err(error) => {
                    run.outcome = failed(t, error);
                    return Ok(run);
                }
            };
            let step = match stepper.step(&shifted, &y, &slope) {
                Ok(step) => step,
                Err(failure) => {
                    run.outcome = match failure {
                        StepFailure::StepSizeTooSmall => Outcome::StepSizeTooSmall { t },
                        StepFailure::Evaluation(error) => failed(t, error),
                        StepFailure::NonFinite { t } => Outcome::NonFiniteState { t: t0 + t },
                    };
                    return Ok(run);
                }
            };
            run.steps += 1;
            let (mut bicycle, carried) = split(&step.y);
            if let Err(error) = model.project(&mut bicycle, &projection) {
                run.outcome = failed(t0 + step.t, error);
                return Ok(run);
            }
            y = join(&bicycle.to_vector(), &carried);
            let lean = bicycle.lean();
            if lean.abs() > fall_angle {
                run.outcome = Outcome::Fell {
                    t: t0 + step.t,
                    lean,
                };
                return Ok(run);
            }
        }
        let (bicycle, carried) = split(&y);
        run.views.push(model.observe(&bicycle));
        run.carried.push(carried);
        t0 = end;
    }
    Ok(run)
}

/// The outcome of an evaluation or projection that failed at t.
fn failed(t: f64, error: Error) -> Outcome {
    match error {
        Error::NonFiniteState { t } => Outcome::NonFiniteState { t },
        Error::ProjectionDiverged {
            iterations,
            residual,
        } => Outcome::ProjectionFailed {
            t,
            iterations,
            residual,
        },
        error => Outcome::Failed { t, error },
    }
}
