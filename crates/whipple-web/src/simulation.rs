//! `POST /api/simulate`: the non-linear bicycle from a few initial numbers, thinned to frames
//! for the page's animation (the four bodies' poses at each frame) and its time plots.
//!
//! The request is checked against [`Limits`] before any work: the simulated time
//! (`max_sim_duration`) and the number of integration steps (`max_sim_steps`, which bounds
//! both the time and the memory of a run, since the library keeps one sample per step).

use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::integrate::dopri5::Dopri5Params;
use whipple::integrate::rk4;
use whipple::nonlinear::{
    simulate, ContactForce, InitialConditions, Integrator, Model, Outcome, Sample, Simulation,
    SimulationSettings, StateView, TorqueExpression, TorqueFn, Wheel,
};
use whipple::BenchmarkParameters;

use crate::error::ApiError;
use crate::Limits;

/// Frames per simulated second sent back (the page plays them at 1x, 0.5x or 2x).
pub const FRAME_RATE: f64 = 60.0;

/// The RK4 step when the request names none \[s\] (the library's and the CLI's default).
const DEFAULT_DT: f64 = 1e-3;
/// The adaptive integrator's relative tolerance when the request names none.
const DEFAULT_RTOL: f64 = 1e-8;

/// The integrator asked for.
#[derive(Deserialize, Clone, Copy, Debug, Default, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorChoice {
    /// Classical Runge–Kutta, fixed step `dt`.
    #[default]
    Rk4,
    /// Dormand–Prince 5(4) with error control, tolerance `rtol`.
    Adaptive,
}

/// The body of `POST /api/simulate`. Degrees for the initial angles (as in the CLI), radians
/// per second for the rates, SI elsewhere.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct SimulateRequest {
    /// The bicycle, in the parameter files' JSON layout.
    pub bike: Value,
    /// v: forward speed [m/s].
    pub speed: f64,
    /// φ₀: initial lean [deg], below 90 in size (default 0).
    #[serde(default)]
    pub lean_deg: f64,
    /// δ₀: initial steer [deg] (default 0).
    #[serde(default)]
    pub steer_deg: f64,
    /// φ̇₀: initial lean rate [rad/s] (default 0).
    #[serde(default)]
    pub lean_rate: f64,
    /// δ̇₀: initial steer rate [rad/s] (default 0).
    #[serde(default)]
    pub steer_rate: f64,
    /// Simulated time [s], positive and at most `Limits::max_sim_duration`.
    pub duration: f64,
    /// The integrator (default RK4).
    #[serde(default)]
    pub integrator: IntegratorChoice,
    /// RK4 step [s] (default 0.001); only with RK4.
    pub dt: Option<f64>,
    /// Relative tolerance of the adaptive integrator (default 1e-8); only with it.
    pub rtol: Option<f64>,
    /// T_δ: steer torque [N m], a number or an expression of t, lean, steer, lean_rate,
    /// steer_rate, yaw and speed (default 0, hands free).
    #[serde(default)]
    pub steer_torque: TorqueInput,
    /// T_φ: lean torque [N m], as `steer_torque` (default 0).
    #[serde(default)]
    pub lean_torque: TorqueInput,
}

/// A rider torque as the request gives it: a constant, or an expression (the CLI's language,
/// [`TorqueExpression`]).
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(untagged)]
pub enum TorqueInput {
    /// A constant torque [N m].
    Constant(f64),
    /// An expression of time and the state [N m].
    Expression(String),
}

impl Default for TorqueInput {
    fn default() -> Self {
        TorqueInput::Constant(0.0)
    }
}

/// A checked rider torque.
#[derive(Debug, Clone)]
enum Torque {
    None,
    Constant(f64),
    Expression(Box<TorqueExpression>),
}

impl Torque {
    fn check(field: &str, input: &TorqueInput) -> Result<Self, ApiError> {
        match input {
            TorqueInput::Constant(x) if !x.is_finite() => Err(invalid(
                field,
                format!("must be a finite number or an expression, got {x}"),
            )),
            TorqueInput::Constant(x) if *x == 0.0 => Ok(Torque::None),
            TorqueInput::Constant(x) => Ok(Torque::Constant(*x)),
            TorqueInput::Expression(text) => match TorqueExpression::parse(text) {
                Ok(expression) => Ok(Torque::Expression(Box::new(expression))),
                Err(whipple::Error::InvalidArgument { rule, .. }) => Err(invalid(field, rule)),
                Err(other) => Err(invalid(field, other.to_string())),
            },
        }
    }

    fn into_fn(self) -> Option<TorqueFn> {
        match self {
            Torque::None => None,
            Torque::Constant(x) => Some(Box::new(move |_: f64, _: &StateView| x)),
            Torque::Expression(expression) => Some((*expression).into_torque()),
        }
    }
}

/// A checked request: everything [`run`] needs.
#[derive(Debug, Clone)]
pub struct Plan {
    initial: InitialConditions,
    integrator: Integrator,
    duration: f64,
    steer_torque: Torque,
    lean_torque: Torque,
}

fn unprocessable(kind: &'static str, field: &str, rule: String, message: String) -> ApiError {
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, kind, message).at(field, rule)
}

fn invalid(field: &str, rule: String) -> ApiError {
    let message = format!("invalid `{field}`: {rule}");
    unprocessable("invalid_argument", field, rule, message)
}

/// Checks a request against the rules and the server's limits, before any computation.
pub fn check(request: &SimulateRequest, limits: &Limits) -> Result<Plan, ApiError> {
    for (field, x) in [
        ("speed", request.speed),
        ("lean_deg", request.lean_deg),
        ("steer_deg", request.steer_deg),
        ("lean_rate", request.lean_rate),
        ("steer_rate", request.steer_rate),
        ("duration", request.duration),
    ] {
        if !x.is_finite() {
            return Err(invalid(field, format!("must be a finite number, got {x}")));
        }
    }
    if request.lean_deg.abs() >= 90.0 {
        return Err(invalid(
            "lean_deg",
            format!(
                "must be below 90 degrees in size (the bicycle would lie on the ground), got {}",
                request.lean_deg
            ),
        ));
    }
    let duration = request.duration;
    if duration <= 0.0 {
        return Err(invalid(
            "duration",
            format!("must be positive, got {duration} s"),
        ));
    }
    let max_duration = limits.max_sim_duration;
    if duration > max_duration {
        return Err(unprocessable(
            "limit_exceeded",
            "duration",
            format!("at most {max_duration} s per request"),
            format!(
                "a simulation of {duration} s is longer than this server's limit of {max_duration} s per request; simulate a shorter time"
            ),
        ));
    }
    let max_steps = limits.max_sim_steps;
    let integrator = match request.integrator {
        IntegratorChoice::Rk4 => {
            if request.rtol.is_some() {
                return Err(invalid(
                    "rtol",
                    "applies to the adaptive integrator; RK4 takes `dt`".into(),
                ));
            }
            let dt = request.dt.unwrap_or(DEFAULT_DT);
            if !(dt.is_finite() && dt > 0.0 && dt <= duration) {
                return Err(invalid(
                    "dt",
                    format!("must be positive and at most the duration ({duration} s), got {dt}"),
                ));
            }
            // Counted as the integrator counts (a last step within 1e-9 of a whole one is not
            // another step).
            let steps = rk4::step_count(duration, dt);
            if steps > max_steps {
                return Err(unprocessable(
                    "limit_exceeded",
                    "dt",
                    format!("at most {max_steps} integration steps per request"),
                    format!(
                        "{duration} s in steps of {dt} s takes {steps} integration steps, more than this server's limit of {max_steps}; use a larger dt or a shorter duration"
                    ),
                ));
            }
            Integrator::Rk4 { dt }
        }
        IntegratorChoice::Adaptive => {
            if request.dt.is_some() {
                return Err(invalid(
                    "dt",
                    "applies to RK4; the adaptive integrator takes `rtol`".into(),
                ));
            }
            let rtol = request.rtol.unwrap_or(DEFAULT_RTOL);
            if !(rtol.is_finite() && rtol > 0.0 && rtol < 1.0) {
                return Err(invalid(
                    "rtol",
                    format!("must lie strictly between 0 and 1, got {rtol}"),
                ));
            }
            // Step attempts are bounded by the same limit; reaching it ends the run early,
            // reported as the outcome.
            Integrator::Dopri5(Dopri5Params {
                rtol,
                atol: rtol * 1e-2,
                max_steps,
                ..Dopri5Params::default()
            })
        }
    };
    Ok(Plan {
        initial: InitialConditions {
            speed: request.speed,
            lean: request.lean_deg.to_radians(),
            steer: request.steer_deg.to_radians(),
            lean_rate: request.lean_rate,
            steer_rate: request.steer_rate,
            ..InitialConditions::upright(request.speed)
        },
        integrator,
        duration,
        steer_torque: Torque::check("steer_torque", &request.steer_torque)?,
        lean_torque: Torque::check("lean_torque", &request.lean_torque)?,
    })
}

/// How a run ended: a machine-readable kind, the time, and a sentence for people.
#[derive(Serialize, Debug)]
pub struct OutcomeJson {
    /// `completed`, `fell`, `wheel_lifted`, `projection_failed`, `non_finite_state`,
    /// `step_limit`, `stopped` or `failed`.
    pub kind: &'static str,
    /// When it happened [s] (the end time for `completed`).
    pub t: f64,
    /// Which wheel, for `wheel_lifted`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wheel: Option<&'static str>,
    /// The outcome in words.
    pub message: String,
}

/// Ground force on one wheel [N].
#[derive(Serialize, Debug, Clone, Copy)]
pub struct Force {
    /// Normal force, upward positive (negative: the wheel would lift off).
    pub normal: f64,
    /// Friction along the rolling direction, forward positive.
    pub longitudinal: f64,
    /// Friction across the wheel, to the right positive.
    pub lateral: f64,
}

impl From<ContactForce<f64>> for Force {
    fn from(f: ContactForce<f64>) -> Self {
        Force {
            normal: f.normal,
            longitudinal: f.longitudinal,
            lateral: f.lateral,
        }
    }
}

/// One body's pose, world axes (x forward, y right, z down), in single precision: plenty for
/// drawing, and half the JSON.
#[derive(Serialize, Debug, Clone, Copy)]
pub struct Pose {
    /// The body's origin, its centre of mass [m].
    pub position: [f32; 3],
    /// Rotation matrix body → world, row by row.
    pub rotation: [f32; 9],
}

/// One animation frame (a recorded sample).
#[derive(Serialize, Debug)]
pub struct Frame {
    /// t [s].
    pub t: f64,
    /// φ [rad].
    pub lean: f64,
    /// δ [rad].
    pub steer: f64,
    /// φ̇ [rad/s].
    pub lean_rate: f64,
    /// δ̇ [rad/s].
    pub steer_rate: f64,
    /// ψ [rad].
    pub yaw: f64,
    /// v [m/s].
    pub speed: f64,
    /// Kinetic + potential energy [J].
    pub energy: f64,
    /// Rear contact point (x, y) [m].
    pub rear_contact: [f64; 2],
    /// Front contact point (x, y) [m].
    pub front_contact: [f64; 2],
    /// Ground force on the rear wheel [N].
    pub rear_force: Force,
    /// Ground force on the front wheel [N].
    pub front_force: Force,
    /// Rear wheel, rear frame (with the rider), front frame, front wheel.
    pub bodies: [Pose; 4],
}

/// Where the drawing's points sit in the bodies' own axes (x forward, y right, z down, parallel
/// to the world's when upright) relative to each body's origin [m].
#[derive(Serialize, Debug)]
pub struct DrawingGeometry {
    /// r_R [m].
    pub rear_wheel_radius: f64,
    /// r_F [m].
    pub front_wheel_radius: f64,
    /// Rear hub, in the rear frame's axes from its centre of mass.
    pub rear_hub_in_rear_frame: [f64; 3],
    /// The steer axis point nearest the front hub, in the rear frame's axes.
    pub steer_point_in_rear_frame: [f64; 3],
    /// The same point, in the front frame's axes from its centre of mass.
    pub steer_point_in_front_frame: [f64; 3],
    /// Front hub, in the front frame's axes.
    pub front_hub_in_front_frame: [f64; 3],
    /// Unit steer axis, pointing down, in either frame's axes.
    pub steer_axis: [f64; 3],
    /// Masses of the rear wheel, rear frame with rider, front frame, front wheel [kg].
    pub masses: [f64; 4],
}

/// The answer of `POST /api/simulate`.
#[derive(Serialize, Debug)]
pub struct SimulateResponse {
    /// The bicycle's name, if it has one.
    pub name: Option<String>,
    /// How the run ended.
    pub outcome: OutcomeJson,
    /// Simulated time asked for [s].
    pub duration: f64,
    /// Accepted integration steps.
    pub steps: usize,
    /// Frames per simulated second.
    pub frame_rate: f64,
    /// Wheels pulled down by their contact from the start (see the library's `Simulation`).
    pub pulled_down_from_start: Vec<&'static str>,
    /// The drawing's fixed geometry.
    pub geometry: DrawingGeometry,
    /// The frames, the first at t = 0 and the last at the end of the run.
    pub frames: Vec<Frame>,
}

fn wheel_name(wheel: Wheel) -> &'static str {
    match wheel {
        Wheel::Rear => "rear",
        Wheel::Front => "front",
    }
}

fn describe(run: &Simulation, duration: f64, max_steps: usize) -> OutcomeJson {
    let plain = |kind, t, message| OutcomeJson {
        kind,
        t,
        wheel: None,
        message,
    };
    match &run.outcome {
        Outcome::Completed => plain(
            "completed",
            duration,
            format!("completed: {duration} s without falling"),
        ),
        Outcome::Fell { t, lean } => plain(
            "fell",
            *t,
            format!(
                "fell: |lean| passed 60° at t = {t:.2} s (lean {:.1}°)",
                lean.to_degrees()
            ),
        ),
        Outcome::WheelLifted { t, wheel } => {
            let lean = run.samples.last().map_or(0.0, |s| s.lean).to_degrees();
            OutcomeJson {
                kind: "wheel_lifted",
                t: *t,
                wheel: Some(wheel_name(*wheel)),
                message: format!(
                    "the {} wheel lifts off at t = {t:.2} s (normal force below zero; lean {lean:.1}°{})",
                    wheel_name(*wheel),
                    if lean.abs() > 20.0 { ", falling" } else { "" }
                ),
            }
        }
        Outcome::ProjectionFailed {
            t,
            iterations,
            residual,
        } => plain(
            "projection_failed",
            *t,
            format!("stopped at t = {t:.2} s: the projection onto the constraints diverged ({iterations} iterations, residual {residual:e})"),
        ),
        Outcome::NonFiniteState { t } => plain(
            "non_finite_state",
            *t,
            format!("stopped at t = {t:.2} s: the state became non-finite"),
        ),
        Outcome::StepSizeTooSmall { t } => plain(
            "step_limit",
            *t,
            format!("stopped at t = {t:.2} s: the adaptive integrator's step became too small or it reached this server's limit of {max_steps} steps; loosen rtol or simulate a shorter time"),
        ),
        Outcome::Stopped { t } => plain(
            "stopped",
            *t,
            format!("stopped at t = {t:.2} s: nobody waits for the result any more (time up or client gone)"),
        ),
        Outcome::Failed { t, error } => plain(
            "failed",
            *t,
            format!("stopped at t = {t:.2} s: {error}"),
        ),
    }
}

fn finite(s: &Sample) -> bool {
    [
        s.t,
        s.lean,
        s.steer,
        s.lean_rate,
        s.steer_rate,
        s.yaw,
        s.pitch,
        s.x,
        s.y,
        s.front_x,
        s.front_y,
        s.speed,
        s.energy,
    ]
    .iter()
    .all(|x| x.is_finite())
}

fn frame(model: &Model, s: &Sample) -> Frame {
    let bodies = model.sample_poses(s).map(|p| {
        let (x, r) = (p.position, p.rotation);
        // Narrowed to f32 on purpose (see `Pose`).
        let f = |v: f64| v as f32;
        Pose {
            position: [f(x.x), f(x.y), f(x.z)],
            rotation: [
                f(r[(0, 0)]),
                f(r[(0, 1)]),
                f(r[(0, 2)]),
                f(r[(1, 0)]),
                f(r[(1, 1)]),
                f(r[(1, 2)]),
                f(r[(2, 0)]),
                f(r[(2, 1)]),
                f(r[(2, 2)]),
            ],
        }
    });
    Frame {
        t: s.t,
        lean: s.lean,
        steer: s.steer,
        lean_rate: s.lean_rate,
        steer_rate: s.steer_rate,
        yaw: s.yaw,
        speed: s.speed,
        energy: s.energy,
        rear_contact: [s.x, s.y],
        front_contact: [s.front_x, s.front_y],
        rear_force: s.rear.into(),
        front_force: s.front.into(),
        bodies,
    }
}

/// The samples at about [`FRAME_RATE`] per simulated second: the first sample at or after each
/// frame time, and always the first and the last.
fn thin(samples: &[Sample]) -> Vec<&Sample> {
    let mut frames: Vec<&Sample> = Vec::new();
    let mut next = 0.0;
    let good: Vec<&Sample> = samples.iter().filter(|s| finite(s)).collect();
    for (i, s) in good.iter().enumerate() {
        if s.t >= next - 1e-9 || i + 1 == good.len() {
            frames.push(s);
            // The next frame's time; the tolerance keeps a sample at k/60 from counting twice.
            next = ((s.t * FRAME_RATE + 1e-6).floor() + 1.0) / FRAME_RATE;
        }
    }
    frames
}

/// Runs a checked request (on the blocking pool).
pub fn run(
    name: Option<String>,
    parameters: &BenchmarkParameters,
    plan: Plan,
    max_steps: usize,
    stop: Arc<AtomicBool>,
) -> Result<SimulateResponse, ApiError> {
    let model = Model::new(parameters)?;
    let start = model.initial_state(&plan.initial)?;
    let settings = SimulationSettings {
        integrator: plan.integrator,
        duration: plan.duration,
        steer_torque: plan.steer_torque.into_fn(),
        lean_torque: plan.lean_torque.into_fn(),
        stop: Some(stop),
        ..SimulationSettings::default()
    };
    let simulation = simulate(&model, start, &settings)?;
    let g = &model.bodies().geometry;
    let geometry = DrawingGeometry {
        rear_wheel_radius: model.parameters().r_r,
        front_wheel_radius: model.parameters().r_f,
        rear_hub_in_rear_frame: g.rear_hub_in_b.into(),
        steer_point_in_rear_frame: g.steer_point_in_b.into(),
        steer_point_in_front_frame: g.steer_point_in_h.into(),
        front_hub_in_front_frame: g.front_hub_in_h.into(),
        steer_axis: g.steer_axis.into(),
        masses: model.bodies().body.map(|b| b.mass),
    };
    let frames = thin(&simulation.samples)
        .into_iter()
        .map(|s| frame(&model, s))
        .collect();
    Ok(SimulateResponse {
        name,
        outcome: describe(&simulation, plan.duration, max_steps),
        duration: plan.duration,
        steps: simulation.steps,
        frame_rate: FRAME_RATE,
        pulled_down_from_start: simulation
            .pulled_down_from_start
            .iter()
            .map(|w| wheel_name(*w))
            .collect(),
        geometry,
        frames,
    })
}
