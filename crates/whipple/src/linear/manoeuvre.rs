//! One manoeuvre on the linear and the non-linear bicycle, sampled at the same times: lean,
//! steer, yaw, the rear contact's x and y and the front contact's y, and their differences.
//!
//! The linear response is exact ([`LinearSystem::response`], with ψ, x_P and y_P among the
//! states); the non-linear one is [`crate::nonlinear::simulate`] with Dormand–Prince 5(4) at a
//! tight tolerance, run from break point to break point (every sample time and every knot of
//! the inputs), so that each run's input is linear over it and every sample is a step's end,
//! never an interpolation.
//!
//! # How the difference scales with the amplitude
//!
//! Mirroring a manoeuvre left for right (every input and initial angle of the opposite sign)
//! mirrors the motion: lean, steer, yaw and the lateral positions are odd in the amplitude a
//! of the inputs and initial angles, and the forward position is even. The linear model is the
//! first-order term, so the non-linear model differs from it by O(a³) in lean, steer, yaw, y
//! and the front contact's y, but by O(a²) in x: the rear contact's x is v t + O(a²) (a leaning,
//! turning bicycle covers less ground along x, and its speed changes to second order), and the
//! linear x_P stays v t. Halving the amplitude divides the first differences by 8, x's by 4
//! (the tests check both) once the amplitude is small enough for the lowest order to dominate:
//! for a steer-torque pulse of 0.5 s on the benchmark bicycle at 5 m/s, over 3 s, below about
//! 0.1 N m. At 1 N m the bicycle turns through 0.6 rad and the linear lean is off by 17%.

use super::response::{InputSignal, TimeResponse};
use super::system::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use crate::error::{Error, Result, short_number};
use crate::integrate::Integrator;
use crate::nonlinear::{InitialConditions, Model, Outcome, Sample, SimulationSettings, simulate};
use crate::parameters::BenchmarkParameters;

/// The most break points (sample times and knots inside the run together) of one
/// [`compare_manoeuvre`]: each starts a run of the non-linear model.
pub const MAX_MANOEUVRE_BREAKS: usize = 100_000;

/// A manoeuvre from upright straight running at a forward speed: an initial lean and steer
/// (small) and torques applied as signals of time.
#[derive(Debug, Clone, PartialEq)]
pub struct Manoeuvre {
    /// v: forward speed [m/s].
    pub speed: f64,
    /// φ at t = 0 \[rad\].
    pub lean: f64,
    /// δ at t = 0 \[rad\].
    pub steer: f64,
    /// The inputs and their signals: [`Input::LeanTorque`] and [`Input::SteerTorque`] (the
    /// non-linear model takes no lateral force), each at most once.
    pub inputs: Vec<(Input, InputSignal)>,
}

/// What one model does at the sample times of a [`ManoeuvreComparison`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ManoeuvreMotion {
    /// φ: lean \[rad\].
    pub lean: Vec<f64>,
    /// δ: steer \[rad\].
    pub steer: Vec<f64>,
    /// ψ: yaw, right turn positive \[rad\].
    pub yaw: Vec<f64>,
    /// The rear contact's x (forward at t = 0), the run v t included \[m\].
    pub rear_x: Vec<f64>,
    /// The rear contact's y (right positive) \[m\].
    pub rear_y: Vec<f64>,
    /// The front contact's y \[m\].
    pub front_y: Vec<f64>,
}

impl ManoeuvreMotion {
    /// The quantities by name, in the order of the fields.
    pub fn columns(&self) -> [(&'static str, &[f64]); 6] {
        [
            ("lean", &self.lean),
            ("steer", &self.steer),
            ("yaw", &self.yaw),
            ("rear_x", &self.rear_x),
            ("rear_y", &self.rear_y),
            ("front_y", &self.front_y),
        ]
    }

    /// The largest size of each quantity over the samples, in the order of the fields.
    pub fn max_abs(&self) -> [f64; 6] {
        self.columns()
            .map(|(_, x)| x.iter().fold(0.0, |m: f64, v| m.max(v.abs())))
    }

    fn push(&mut self, [lean, steer, yaw, rear_x, rear_y, front_y]: [f64; 6]) {
        self.lean.push(lean);
        self.steer.push(steer);
        self.yaw.push(yaw);
        self.rear_x.push(rear_x);
        self.rear_y.push(rear_y);
        self.front_y.push(front_y);
    }
}

/// The same manoeuvre on both models at the same times.
#[derive(Debug, Clone, PartialEq)]
pub struct ManoeuvreComparison {
    /// The sample times \[s\].
    pub times: Vec<f64>,
    /// The linear model's exact response.
    pub linear: ManoeuvreMotion,
    /// The non-linear model's simulation.
    pub nonlinear: ManoeuvreMotion,
    /// Non-linear less linear.
    pub difference: ManoeuvreMotion,
    /// The non-linear run's accepted integration steps, all runs together.
    pub nonlinear_steps: usize,
}

/// Runs `manoeuvre` on the linear model (exactly) and on the non-linear model (Dormand–Prince
/// 5(4) with relative tolerance `rtol`, absolute `rtol`·1e-2, projected onto the constraints
/// after every step) and samples both at `times` (increasing, the first ≥ 0). Choose `rtol`
/// well below the differences sought: 1e-12 resolves differences of 1e-9 rad.
///
/// Errors: a lateral force among the inputs ([`Error::InvalidArgument`] naming `inputs`: the
/// non-linear model takes lean and steer torques only), what [`LinearSystem::new`],
/// [`LinearSystem::response`] and [`simulate`] refuse, more than [`MAX_MANOEUVRE_BREAKS`]
/// break points (`times`), and a non-linear run that does not complete (it fell, or a wheel
/// lifted: `manoeuvre`, with the outcome).
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::linear::{Input, InputSignal, Manoeuvre, compare_manoeuvre};
/// let pulse = Manoeuvre {
///     speed: 5.0,
///     lean: 0.0,
///     steer: 0.0,
///     inputs: vec![(Input::SteerTorque, InputSignal::pulse(0.0, 0.5, 0.1)?)],
/// };
/// let times: Vec<f64> = (0..=10).map(|k| 0.2 * k as f64).collect();
/// let both = compare_manoeuvre(&BenchmarkParameters::meijaard2007(), &pulse, &times, 1e-10)?;
/// // 0.1 N m for half a second: the models differ by 0.2% of the lean, 2.5 mm along x.
/// let [lean, .., x, _, _] = both.difference.max_abs();
/// assert!(lean < 1e-2 * both.linear.max_abs()[0] && x < 1e-2);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn compare_manoeuvre(
    bike: &BenchmarkParameters,
    manoeuvre: &Manoeuvre,
    times: &[f64],
    rtol: f64,
) -> Result<ManoeuvreComparison> {
    if let Some((input, _)) = manoeuvre
        .inputs
        .iter()
        .find(|(input, _)| matches!(input, Input::LateralForce { .. }))
    {
        return Err(Error::InvalidArgument {
            what: "inputs",
            rule: format!(
                "{input}: the non-linear model takes a lean torque and a steer torque, no lateral force"
            ),
        });
    }
    let request = SystemRequest {
        states: vec![
            StateVariable::Yaw,
            StateVariable::RearContactX,
            StateVariable::RearContactY,
        ],
        inputs: manoeuvre.inputs.iter().map(|(input, _)| *input).collect(),
        outputs: vec![Output::FrontContactY],
    };
    let system = LinearSystem::new(bike, manoeuvre.speed, &request)?;
    let signals: Vec<InputSignal> = manoeuvre.inputs.iter().map(|(_, s)| s.clone()).collect();
    let mut initial = vec![0.0; system.states().len()];
    initial[0] = manoeuvre.lean;
    initial[1] = manoeuvre.steer;
    let response = system.response(&initial, &signals, times)?;
    let linear = linear_motion(&response)?;

    // Break points: every sample time and every knot inside the run.
    let t_end = times[times.len() - 1];
    let mut breaks: Vec<f64> = signals
        .iter()
        .flat_map(|s| s.knots().iter().copied())
        .filter(|t| *t > 0.0 && *t < t_end)
        .chain(times.iter().copied().filter(|t| *t > 0.0))
        .collect();
    if breaks.len() > MAX_MANOEUVRE_BREAKS {
        return Err(Error::LimitExceeded {
            what: "times",
            rule: format!(
                "at most {MAX_MANOEUVRE_BREAKS} sample times and knots together (each starts a run of the non-linear model), got {}",
                breaks.len()
            ),
        });
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();

    let model = Model::new(bike)?;
    let start = InitialConditions {
        lean: manoeuvre.lean,
        steer: manoeuvre.steer,
        ..InitialConditions::upright(manoeuvre.speed)
    };
    let integrator = Integrator::adaptive(rtol);
    let torque = |input: Input, from: f64, to: f64| {
        let signal = manoeuvre
            .inputs
            .iter()
            .find(|(i, _)| *i == input)
            .map(|(_, s)| s)?;
        // Linear over the run, from its value after `from` to its value before `to`.
        let (u0, u1, h) = (signal.value(from), signal.value_before(to), to - from);
        let f: crate::nonlinear::TorqueFn = Box::new(move |t, _| {
            if h > 0.0 {
                u0 + (u1 - u0) * (t / h).clamp(0.0, 1.0)
            } else {
                u0
            }
        });
        Some(f)
    };
    let run = |state, from: f64, to: f64| {
        let settings = SimulationSettings {
            integrator,
            duration: to - from,
            steer_torque: torque(Input::SteerTorque, from, to),
            lean_torque: torque(Input::LeanTorque, from, to),
            ..SimulationSettings::default()
        };
        let simulation = simulate(&model, state, &settings)?;
        if simulation.outcome != Outcome::Completed {
            return Err(Error::InvalidArgument {
                what: "manoeuvre",
                rule: format!(
                    "the non-linear bicycle did not complete it: {} (in the run from t = {} s)",
                    simulation.outcome,
                    short_number(from)
                ),
            });
        }
        Ok(simulation)
    };
    // The initial state projected onto the constraints: a run of no time.
    let first = run(model.initial_state(&start)?, 0.0, 0.0)?;
    let mut nonlinear = ManoeuvreMotion::default();
    let mut state = first.final_state;
    let mut steps = 0;
    let mut next = 0;
    if times[0] == 0.0 {
        let at_start = first.samples.first().ok_or_else(|| Error::NonFinite {
            context: "the non-linear model's initial state (no sample)".into(),
        })?;
        nonlinear.push(sample_motion(at_start));
        next = 1;
    }
    let mut t = 0.0;
    for &b in &breaks {
        let simulation = run(state, t, b)?;
        steps += simulation.steps;
        state = simulation.final_state;
        t = b;
        if times.get(next) == Some(&b) {
            let last = simulation.samples.last().ok_or_else(|| Error::NonFinite {
                context: format!(
                    "the non-linear run to t = {} s (no sample)",
                    short_number(b)
                ),
            })?;
            nonlinear.push(sample_motion(last));
            next += 1;
        }
    }
    let mut difference = ManoeuvreMotion::default();
    for k in 0..times.len() {
        let [a, b] = [&nonlinear, &linear].map(|m| m.columns().map(|(_, x)| x[k]));
        difference.push(std::array::from_fn(|i| a[i] - b[i]));
    }
    Ok(ManoeuvreComparison {
        times: times.to_vec(),
        linear,
        nonlinear,
        difference,
        nonlinear_steps: steps,
    })
}

fn sample_motion(s: &Sample) -> [f64; 6] {
    [s.lean, s.steer, s.yaw, s.x, s.y, s.front_y]
}

fn linear_motion(response: &TimeResponse) -> Result<ManoeuvreMotion> {
    let missing = || Error::InvalidArgument {
        what: "states",
        rule: "the manoeuvre's linear system lacks yaw or the rear contact".into(),
    };
    let path = response.ground_path().ok_or_else(missing)?;
    let lean = response.state(StateVariable::Lean).ok_or_else(missing)?;
    let steer = response.state(StateVariable::Steer).ok_or_else(missing)?;
    Ok(ManoeuvreMotion {
        lean,
        steer,
        yaw: path.yaw,
        rear_x: path.rear_x,
        rear_y: path.rear_y,
        front_y: path.front_y.ok_or_else(missing)?,
    })
}
