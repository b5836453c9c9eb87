//! A simulation that carries a few states of its own beside the bicycle's: a controller's (a
//! rider's neuromuscular filter, a command filter), integrated together with the bicycle in one
//! system so that the adaptive integrator controls the error of both.
//!
//! The carried states x_c have rates f_c(t, view, x_c) given the bicycle's named quantities
//! ([`StateView`]), and the rider's torques are read from them: [`Inputs`](super::Inputs)
//! from (t, view, x_c). After every step the bicycle's part is projected onto the constraints
//! as [`super::simulate`] does (each segment is a run of its one stepping loop); the carried
//! part is left as integrated. The run goes from break point to break point (each a fresh
//! Dormand–Prince 5(4) run to it), so that an input with a kink at a break point is smooth
//! within every run, and every sample is a step's end, never an interpolation.

use nalgebra::SVector;

use super::Model;
use super::forward::{ContactForce, Inputs};
use super::outcome::Outcome;
use super::settings::SimulationSettings;
use super::simulate::{Mechanism, run_mechanism};
use super::state::{STATE_LEN, State, StateView};
use crate::error::{Error, Result};
use crate::integrate::{Integrator, OdeSystem};

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
/// (`ends`, increasing, positive), recording the state at t = 0 and at every end: each a run of
/// [`super::simulate`]'s one stepping loop (its projection, energy balance and events; a lean
/// beyond `fall_angle` ends the run, outcome [`Outcome::Fell`]; a lifted wheel does not).
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
    let mut state = (initial, carried);
    let mut run = CarriedRun {
        views: Vec::with_capacity(ends.len() + 1),
        carried: Vec::with_capacity(ends.len() + 1),
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
        let settings = SimulationSettings {
            integrator,
            duration: span,
            fall_angle,
            stop_on_lift_off: false,
            // The first and the last step's ends are kept: the break points.
            sample_every: usize::MAX,
            ..SimulationSettings::default()
        };
        let ode = CarriedOde {
            model,
            rhs: &rhs,
            t0,
        };
        let segment = run_mechanism(&ode, state, &settings)?;
        if run.views.is_empty() {
            let (view, carried) = segment.records[0];
            run.views.push(view);
            run.carried.push(carried);
        }
        run.steps += segment.simulation.steps;
        if segment.simulation.outcome != Outcome::Completed {
            run.outcome = segment.simulation.outcome.delayed(t0);
            return Ok(run);
        }
        let last = segment.records.len() - 1;
        let (view, carried) = segment.records[last];
        run.views.push(view);
        run.carried.push(carried);
        state = segment.final_state;
        t0 = end;
    }
    Ok(run)
}

/// The bicycle with the carried states, its inputs read from them, as a [`Mechanism`] on
/// [q; u; x_c], its time counted from `t0`.
struct CarriedOde<'a, F> {
    model: &'a Model,
    rhs: &'a F,
    t0: f64,
}

impl<F> CarriedOde<'_, F>
where
    F: Fn(f64, &StateView, &[f64; CARRIED]) -> ([f64; CARRIED], Inputs<f64>),
{
    /// The carried states' rates and the inputs at local time t; a non-finite one is
    /// [`Error::NonFiniteState`] at t.
    fn carried_rates(
        &self,
        t: f64,
        (bicycle, carried): &(State<f64>, [f64; CARRIED]),
    ) -> Result<([f64; CARRIED], Inputs<f64>, StateView)> {
        if !(bicycle.is_finite() && carried.iter().all(|x| x.is_finite())) {
            return Err(Error::NonFiniteState { t });
        }
        let view = self.model.observe(bicycle);
        let (rates, inputs) = (self.rhs)(self.t0 + t, &view, carried);
        if !(inputs.steer_torque.is_finite()
            && inputs.lean_torque.is_finite()
            && rates.iter().all(|x| x.is_finite()))
        {
            return Err(Error::NonFiniteState { t });
        }
        Ok((rates, inputs, view))
    }
}

impl<F> OdeSystem<CARRYING_LEN> for CarriedOde<'_, F>
where
    F: Fn(f64, &StateView, &[f64; CARRIED]) -> ([f64; CARRIED], Inputs<f64>),
{
    fn rhs(&self, t: f64, y: &SVector<f64, CARRYING_LEN>) -> Result<SVector<f64, CARRYING_LEN>> {
        Ok(self.evaluate(t, &Self::from_vector(y))?.0)
    }
}

impl<F> Mechanism<CARRYING_LEN> for CarriedOde<'_, F>
where
    F: Fn(f64, &StateView, &[f64; CARRIED]) -> ([f64; CARRIED], Inputs<f64>),
{
    type State = (State<f64>, [f64; CARRIED]);
    type Record = (StateView, [f64; CARRIED]);

    fn model(&self) -> &Model {
        self.model
    }

    fn from_vector(y: &SVector<f64, CARRYING_LEN>) -> Self::State {
        let bicycle = State::from_vector(&y.fixed_rows::<STATE_LEN>(0).into_owned());
        (bicycle, std::array::from_fn(|i| y[STATE_LEN + i]))
    }

    fn to_vector((bicycle, carried): &Self::State) -> SVector<f64, CARRYING_LEN> {
        let mut y = SVector::<f64, CARRYING_LEN>::zeros();
        y.fixed_rows_mut::<STATE_LEN>(0)
            .copy_from(&bicycle.to_vector());
        for (i, c) in carried.iter().enumerate() {
            y[STATE_LEN + i] = *c;
        }
        y
    }

    fn bicycle(state: &Self::State) -> &State<f64> {
        &state.0
    }

    fn bicycle_mut(state: &mut Self::State) -> &mut State<f64> {
        &mut state.0
    }

    fn evaluate(
        &self,
        t: f64,
        state: &Self::State,
    ) -> Result<(SVector<f64, CARRYING_LEN>, [ContactForce<f64>; 2])> {
        let (rates, inputs, _) = self.carried_rates(t, state)?;
        let d = self.model.forward(&state.0, &inputs)?;
        let mut y = SVector::<f64, CARRYING_LEN>::zeros();
        y.fixed_rows_mut::<STATE_LEN>(0).copy_from(&d.to_vector());
        for (i, r) in rates.iter().enumerate() {
            y[STATE_LEN + i] = *r;
        }
        Ok((y, d.contact))
    }

    fn energy(&self, state: &Self::State) -> f64 {
        self.model.energy(&state.0)
    }

    /// T_δ δ̇ + T_φ φ̇ of the inputs read from the carried states.
    fn power(&self, t: f64, state: &Self::State) -> f64 {
        match self.carried_rates(t, state) {
            Ok((_, inputs, view)) => {
                let power =
                    inputs.steer_torque * view.steer_rate + inputs.lean_torque * view.lean_rate;
                if power.is_finite() { power } else { 0.0 }
            }
            Err(_) => 0.0,
        }
    }

    fn record(&self, (bicycle, carried): &Self::State) -> Self::Record {
        (self.model.observe(bicycle), *carried)
    }
}
