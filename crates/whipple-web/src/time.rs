//! `POST /api/linear/time`: the linear bicycle's response in time to a step, an impulse or a
//! pulse of one input, or from an initial lean and steer — lean, steer, yaw and the path in the
//! ground plane (the rear contact's x and y, the front contact's y) — and, when asked, the same
//! manoeuvre on the non-linear model beside it with the difference: what the page's Response
//! tab draws as time plots and paths. The numbers are the library's (`LinearSystem::response`,
//! `TimeResponse::ground_path`, `compare_manoeuvre`); this module only shapes them.

use bytes::Bytes;
use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::advanced::linear::{
    Input, InputSignal, LinearSystem, Manoeuvre, ManoeuvreMotion, StateVariable, compare_manoeuvre,
};

use crate::Limits;
use crate::api::{Budget, Job, bicycle, json_body};
use crate::error::ApiError;

/// The longest simulated time one request asks for [s].
pub(crate) const MAX_DURATION: f64 = 10.0;

/// The most sample times one request asks for.
pub(crate) const MAX_SAMPLES: usize = 2_000;

/// The non-linear model's relative tolerance: differences of 1e-8 rad are resolved.
const NONLINEAR_RTOL: f64 = 1e-10;

/// What drives the response.
#[derive(Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(rename_all = "snake_case")]
enum Kind {
    /// The input jumps to `amplitude` at t = 0 and stays.
    Step,
    /// An impulse of `amplitude` [N m s or N s] at t = 0.
    Impulse,
    /// No input: the motion from `lean_deg`, `steer_deg`.
    Initial,
    /// The input at `amplitude` from t = 0 to `pulse_duration`, then zero.
    Pulse,
}

fn default_input() -> String {
    "steer_torque".into()
}

fn one() -> f64 {
    1.0
}

fn half() -> f64 {
    0.5
}

/// The body of `POST /api/linear/time`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct TimeRequest {
    /// The bicycle, in the parameter files' JSON layout.
    bike: Value,
    /// v [m/s].
    speed: f64,
    kind: Kind,
    /// `lean_torque`, `steer_torque` or `lateral_force:X,Z` (whipple-front's spellings).
    #[serde(default = "default_input")]
    input: String,
    /// The input's size [N m or N; N m s or N s for an impulse].
    #[serde(default = "one")]
    amplitude: f64,
    /// A pulse's length [s].
    #[serde(default = "half")]
    pulse_duration: f64,
    /// φ at t = 0 [deg] (kind `initial` only).
    #[serde(default)]
    lean_deg: f64,
    /// δ at t = 0 [deg] (kind `initial` only).
    #[serde(default)]
    steer_deg: f64,
    /// The time span [s], at most [`MAX_DURATION`].
    duration: f64,
    /// Sample times from 0 to `duration` evenly, both included: 2 to [`MAX_SAMPLES`].
    samples: usize,
    /// Also the non-linear model's motion and the difference.
    #[serde(default)]
    nonlinear: bool,
}

/// A signal as the library names it.
#[derive(Serialize, Debug)]
struct Signal {
    name: String,
    symbol: &'static str,
    unit: &'static str,
}

/// One model's motion at the sample times.
#[derive(Serialize, Debug)]
struct Motion {
    /// φ [deg].
    lean_deg: Vec<f64>,
    /// δ [deg].
    steer_deg: Vec<f64>,
    /// ψ, right turn positive [deg].
    yaw_deg: Vec<f64>,
    /// The rear contact's x, the run v t included [m].
    rear_x: Vec<f64>,
    /// The rear contact's y, right positive [m].
    rear_y: Vec<f64>,
    /// The front contact's y [m].
    front_y: Vec<f64>,
}

/// The largest size of each quantity of a [`Motion`].
#[derive(Serialize, Debug)]
struct Largest {
    lean_deg: f64,
    steer_deg: f64,
    yaw_deg: f64,
    rear_x: f64,
    rear_y: f64,
    front_y: f64,
}

#[derive(Serialize, Debug)]
struct Nonlinear {
    motion: Motion,
    /// Non-linear less linear.
    difference: Motion,
    /// The largest size of each difference over the samples.
    largest_difference: Largest,
    /// Accepted integration steps, all runs together.
    steps: usize,
}

/// The answer of `POST /api/linear/time`.
#[derive(Serialize, Debug)]
pub(crate) struct TimeResponseJson {
    name: Option<String>,
    speed: f64,
    kind: &'static str,
    input: Signal,
    amplitude: f64,
    /// [s].
    times: Vec<f64>,
    linear: Motion,
    /// With `nonlinear: true`; null otherwise.
    nonlinear: Option<Nonlinear>,
}

fn invalid(field: &str, rule: String) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "invalid_argument",
        format!("invalid `{field}`: {rule}"),
    )
    .at(field, rule)
}

fn limit(field: &str, message: String, rule: String) -> ApiError {
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "limit_exceeded", message).at(field, rule)
}

fn finite(field: &str, x: f64) -> Result<(), ApiError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(invalid(field, format!("must be a finite number, got {x}")))
    }
}

/// The request checked, before any work.
struct Plan {
    speed: f64,
    kind: Kind,
    input: Input,
    input_text: String,
    amplitude: f64,
    pulse_duration: f64,
    lean: f64,
    steer: f64,
    times: Vec<f64>,
    nonlinear: bool,
}

fn check(request: &TimeRequest) -> Result<Plan, ApiError> {
    finite("speed", request.speed)?;
    finite("amplitude", request.amplitude)?;
    finite("lean_deg", request.lean_deg)?;
    finite("steer_deg", request.steer_deg)?;
    let input = whipple_front::system::parse_input(&request.input)
        .map_err(|e| ApiError::from(e).in_field("input"))?;
    let duration = request.duration;
    if !(duration.is_finite() && duration > 0.0) {
        return Err(invalid(
            "duration",
            format!("must be a positive number of seconds, got {duration}"),
        ));
    }
    if duration > MAX_DURATION {
        return Err(limit(
            "duration",
            format!("{duration} s is more than this server's limit of {MAX_DURATION} s"),
            format!("at most {MAX_DURATION} s"),
        ));
    }
    let samples = request.samples;
    if samples < 2 {
        return Err(invalid(
            "samples",
            format!("at least 2 samples (t = 0 and the duration), got {samples}"),
        ));
    }
    if samples > MAX_SAMPLES {
        return Err(limit(
            "samples",
            format!("{samples} samples are more than this server's limit of {MAX_SAMPLES}"),
            format!("at most {MAX_SAMPLES} samples"),
        ));
    }
    let pulse_duration = request.pulse_duration;
    if request.kind == Kind::Pulse && !(pulse_duration.is_finite() && pulse_duration > 0.0) {
        return Err(invalid(
            "pulse_duration",
            format!("must be a positive number of seconds, got {pulse_duration}"),
        ));
    }
    if request.nonlinear {
        // An initial condition has no input: the lateral force named is not applied.
        if matches!(input, Input::LateralForce { .. }) && request.kind != Kind::Initial {
            return Err(invalid(
                "input",
                format!(
                    "{input}: the non-linear model takes a lean torque or a steer torque, no lateral force"
                ),
            ));
        }
        if request.kind == Kind::Impulse {
            return Err(invalid(
                "kind",
                "the non-linear comparison takes a step, a pulse or an initial lean and steer, not an impulse".into(),
            ));
        }
    }
    let last = samples - 1;
    let times = (0..samples)
        .map(|k| {
            if k == last {
                duration
            } else {
                duration * k as f64 / last as f64
            }
        })
        .collect();
    Ok(Plan {
        speed: request.speed,
        kind: request.kind,
        input,
        input_text: request.input.trim().to_string(),
        amplitude: request.amplitude,
        pulse_duration,
        lean: request.lean_deg.to_radians(),
        steer: request.steer_deg.to_radians(),
        times,
        nonlinear: request.nonlinear,
    })
}

fn degrees(x: &[f64]) -> Vec<f64> {
    x.iter().map(|v| v.to_degrees()).collect()
}

fn motion(m: &ManoeuvreMotion) -> Motion {
    Motion {
        lean_deg: degrees(&m.lean),
        steer_deg: degrees(&m.steer),
        yaw_deg: degrees(&m.yaw),
        rear_x: m.rear_x.clone(),
        rear_y: m.rear_y.clone(),
        front_y: m.front_y.clone(),
    }
}

/// The input's signal over time: zero for an impulse (its effect is the initial state) and
/// for an initial condition.
fn signal(plan: &Plan) -> Result<InputSignal, ApiError> {
    let field = |e: whipple::Error| ApiError::from(e).in_field("amplitude");
    Ok(match plan.kind {
        Kind::Step => InputSignal::constant(plan.amplitude).map_err(field)?,
        Kind::Pulse => InputSignal::pulse(0.0, plan.pulse_duration, plan.amplitude)
            .map_err(|e| ApiError::from(e).in_field("pulse_duration"))?,
        Kind::Impulse | Kind::Initial => InputSignal::zero(),
    })
}

fn linear(bike: &whipple::BenchmarkParameters, plan: &Plan) -> Result<Motion, ApiError> {
    let request = whipple_front::system::request_with_states(
        &[&plan.input_text],
        &["front_contact_y"],
        &["yaw", "rear_contact_x", "rear_contact_y"],
    )
    .map_err(|e| ApiError::from(e).in_field("input"))?;
    let system = LinearSystem::new(bike, plan.speed, &request)?;
    let states = system.states();
    let mut initial = vec![0.0; states.len()];
    match plan.kind {
        Kind::Initial => {
            for (j, s) in states.iter().enumerate() {
                match s {
                    StateVariable::Lean => initial[j] = plan.lean,
                    StateVariable::Steer => initial[j] = plan.steer,
                    _ => {}
                }
            }
        }
        Kind::Impulse => {
            for (j, b) in system.b().column(0).iter().enumerate() {
                initial[j] = plan.amplitude * b;
            }
        }
        Kind::Step | Kind::Pulse => {}
    }
    let response = system.response(&initial, &[signal(plan)?], &plan.times)?;
    let path = response
        .ground_path()
        .ok_or_else(|| ApiError::internal("the path in the plane is missing"))?;
    let column = |s: StateVariable| {
        response
            .state(s)
            .ok_or_else(|| ApiError::internal(format!("the state {s:?} is missing")))
    };
    let lean = column(StateVariable::Lean)?;
    let steer = column(StateVariable::Steer)?;
    let front_y = path
        .front_y
        .ok_or_else(|| ApiError::internal("the front contact's path is missing"))?;
    Ok(Motion {
        lean_deg: degrees(&lean),
        steer_deg: degrees(&steer),
        yaw_deg: degrees(&path.yaw),
        rear_x: path.rear_x,
        rear_y: path.rear_y,
        front_y,
    })
}

fn nonlinear(bike: &whipple::BenchmarkParameters, plan: &Plan) -> Result<Nonlinear, ApiError> {
    let (lean, steer) = match plan.kind {
        Kind::Initial => (plan.lean, plan.steer),
        _ => (0.0, 0.0),
    };
    let inputs = match plan.kind {
        Kind::Initial => Vec::new(),
        _ => vec![(plan.input, signal(plan)?)],
    };
    let manoeuvre = Manoeuvre {
        speed: plan.speed,
        lean,
        steer,
        inputs,
    };
    let both = compare_manoeuvre(bike, &manoeuvre, &plan.times, NONLINEAR_RTOL)?;
    let [lean, steer, yaw, rear_x, rear_y, front_y] = both.difference.max_abs();
    Ok(Nonlinear {
        motion: motion(&both.nonlinear),
        difference: motion(&both.difference),
        largest_difference: Largest {
            lean_deg: lean.to_degrees(),
            steer_deg: steer.to_degrees(),
            yaw_deg: yaw.to_degrees(),
            rear_x,
            rear_y,
            front_y,
        },
        steps: both.nonlinear_steps,
    })
}

fn answer(
    name: Option<String>,
    bike: &whipple::BenchmarkParameters,
    plan: &Plan,
) -> Result<TimeResponseJson, ApiError> {
    let linear = linear(bike, plan)?;
    let nonlinear = if plan.nonlinear {
        Some(nonlinear(bike, plan)?)
    } else {
        None
    };
    Ok(TimeResponseJson {
        name,
        speed: plan.speed,
        kind: match plan.kind {
            Kind::Step => "step",
            Kind::Impulse => "impulse",
            Kind::Initial => "initial",
            Kind::Pulse => "pulse",
        },
        input: Signal {
            name: plan.input_text.clone(),
            symbol: plan.input.symbol(),
            unit: plan.input.unit(),
        },
        amplitude: plan.amplitude,
        times: plan.times.clone(),
        linear,
        nonlinear,
    })
}

pub(crate) fn time(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: TimeRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let plan = check(&request)?;
    // The linear response is milliseconds (exact, one matrix exponential per interval length);
    // the non-linear model is integrated run by run between the samples: heavy work.
    let budget = if plan.nonlinear {
        Budget::Heavy
    } else {
        Budget::Interactive
    };
    Ok(Job::json(
        budget,
        "ask for fewer samples or a shorter duration",
        move |_| {
            let benchmark = bike.benchmark()?;
            answer(bike.name.clone(), &benchmark, &plan)
        },
    ))
}
