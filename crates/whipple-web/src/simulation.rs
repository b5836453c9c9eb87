//! `POST /api/simulate`: the non-linear bicycle from a few initial numbers, thinned to frames
//! for the page's animation (the four bodies' poses at each frame) and its time plots.
//!
//! The request is checked against [`Limits`] before any work: the simulated time
//! (`max_sim_duration`) and the number of integration steps (`max_sim_steps`, which bounds
//! both the time and the memory of a run, since the library keeps one sample per step).

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::BenchmarkParameters;
use whipple::advanced::nonlinear::{
    BodyPose, ContactForce, HINGE_LIMIT, LeanForcing, LeanModel, Outcome, Sample, TorqueFn,
};
use whipple::advanced::parameters::{RiderLeanParameters, UpperBody};
use whipple::advanced::turns::{Held, SteadyTurn, TurnSettings, held_turn};
use whipple::{InitialConditions, Model, SimulationSettings, simulate};
use whipple_front::simulation::{IntegratorKind, SimulationRequest, TorqueInput};
use whipple_front::units::radians;

use crate::Limits;
use crate::error::ApiError;

/// Frames per simulated second sent back (the page plays them at 1x, 0.5x or 2x).
pub const FRAME_RATE: f64 = 60.0;

/// The request's fields that make the initial state (with the bicycle): named by an error in
/// placing the bicycle there or in its first evaluation.
const INITIAL_FIELDS: &str = "speed, lean_deg, steer_deg, lean_rate, steer_rate";

/// The body of `POST /api/simulate`. Degrees for the initial angles (as in the CLI), radians
/// per second for the rates, SI elsewhere.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct SimulateRequest {
    /// The bicycle, in the parameter files' JSON layout.
    pub bike: Value,
    /// v: forward speed [m/s].
    pub speed: f64,
    /// φ₀: initial lean \[deg\], below 90 in size (default 0).
    #[serde(default)]
    pub lean_deg: f64,
    /// δ₀: initial steer \[deg\] (default 0).
    #[serde(default)]
    pub steer_deg: f64,
    /// φ̇₀: initial lean rate [rad/s] (default 0).
    #[serde(default)]
    pub lean_rate: f64,
    /// δ̇₀: initial steer rate [rad/s] (default 0).
    #[serde(default)]
    pub steer_rate: f64,
    /// Simulated time \[s\], positive and at most `Limits::max_sim_duration`.
    pub duration: f64,
    /// The integrator (default RK4).
    #[serde(default)]
    pub integrator: IntegratorKind,
    /// RK4 step \[s\] (default 0.001); only with RK4.
    pub dt: Option<f64>,
    /// Relative tolerance of the adaptive integrator (default 1e-8); only with it.
    pub rtol: Option<f64>,
    /// T_δ: steer torque [N m], a number or an expression of t, lean, steer, lean_rate,
    /// steer_rate, yaw and speed (default 0, hands free; with `from_turn`, the turn's).
    #[serde(default, deserialize_with = "given")]
    pub steer_torque: Option<TorqueInput>,
    /// T_φ: lean torque [N m], as `steer_torque` (default 0).
    #[serde(default)]
    pub lean_torque: TorqueInput,
    /// Start on the held steady turn at `speed` (the rear contact's) and `lean_deg`, as
    /// `whipple simulate --from-turn`: steer, pitch and rates from the library's
    /// `SteadyTurn::initial_conditions`, the steer torque held at the turn's unless
    /// `steer_torque` is given; `lean_rate` and `steer_rate` perturb it; no `steer_deg`.
    #[serde(default)]
    pub from_turn: bool,
    /// The rider's upper body free to lean on a hinge (Moore 2012's rider-lean model, the
    /// library's `LeanModel`); absent, the rider is rigid.
    #[serde(default)]
    pub rider: Option<RiderLeanRequest>,
}

/// The leaning rider of `POST /api/simulate`: Jason's upper body (BicycleParameters'
/// `mooreriderlean2012_browser_jason`, as `whipple rider`) split off the bicycle's rear frame
/// (the library's `RiderLeanParameters::split`), hinged to it at Jason's hinge, with the
/// hinge's stiffness and damping and the rider's torque about the hinge, beside the request's
/// steer and lean torques; `from_turn` (the rigid rider's turn) is not taken with it.
#[derive(Deserialize, Debug, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RiderLeanRequest {
    /// k: the hinge's passive stiffness [N m/rad] (default 0).
    #[serde(default)]
    pub hinge_stiffness: f64,
    /// c: the hinge's passive damping [N m s/rad] (default 0).
    #[serde(default)]
    pub hinge_damping: f64,
    /// The rider's torque about the hinge [N m] (on the upper body, its reaction on the rear
    /// frame; right positive), held for `torque_duration` (default 0).
    #[serde(default)]
    pub torque: f64,
    /// How long the torque acts \[s\] from the start (default: the whole run).
    pub torque_duration: Option<f64>,
    /// φ_r₀: the upper body's initial lean relative to the rear frame \[deg\] (default 0).
    #[serde(default)]
    pub lean_deg: f64,
}

/// A torque that was given (`null` is not one).
fn given<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<TorqueInput>, D::Error> {
    TorqueInput::deserialize(d).map(Some)
}

/// A checked request: everything [`run`] needs.
#[derive(Debug)]
pub struct Plan {
    /// With `rider`: the leaning rider's request, checked.
    rider: Option<RiderLeanRequest>,
    initial: InitialConditions,
    settings: SimulationSettings,
    /// With `from_turn`: the library's request, to be made again from the turn in [`run`].
    from_turn: Option<FromTurn>,
}

/// What [`run`] needs to start on a held turn.
#[derive(Debug)]
struct FromTurn {
    request: SimulationRequest,
    /// The rear contact's speed [m/s] and the held lean [rad].
    speed: f64,
    lean: f64,
    /// Whether the request gave its own steer torque (else the turn's is held).
    steer_torque_given: bool,
}

fn library_error(error: whipple::Error) -> ApiError {
    match error {
        whipple::Error::InvalidArgument { what, rule } => invalid(what, rule),
        whipple::Error::LimitExceeded { what, rule } => {
            unprocessable("limit_exceeded", what, rule.clone(), rule)
        }
        other => ApiError::from(other),
    }
}

fn unprocessable(kind: &'static str, field: &str, rule: String, message: String) -> ApiError {
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, kind, message).at(field, rule)
}

fn invalid(field: &str, rule: String) -> ApiError {
    let message = format!("invalid `{field}`: {rule}");
    unprocessable("invalid_argument", field, rule, message)
}

/// Checks a request against the server's limit on simulated time, then against the library's
/// rules (with the server's limit on steps), before any computation.
pub fn check(request: &SimulateRequest, limits: &Limits) -> Result<Plan, ApiError> {
    let (duration, max_duration) = (request.duration, limits.max_sim_duration);
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
    let library = SimulationRequest {
        speed: request.speed,
        lean_deg: request.lean_deg,
        steer_deg: request.steer_deg,
        lean_rate: request.lean_rate,
        steer_rate: request.steer_rate,
        duration,
        integrator: request.integrator,
        dt: request.dt,
        rtol: request.rtol,
        steer_torque: request.steer_torque.clone().unwrap_or_default(),
        lean_torque: request.lean_torque.clone(),
        host_max_steps: Some(limits.max_sim_steps),
        ..SimulationRequest::new(request.speed, duration)
    };
    if request.from_turn && request.steer_deg != 0.0 {
        return Err(invalid(
            "steer_deg",
            "must not be given with `from_turn` (the turn sets the steer)".into(),
        ));
    }
    if let Some(rider) = &request.rider {
        check_rider(request, rider)?;
    }
    let (initial, settings) = library.validate().map_err(library_error)?;
    let from_turn = request.from_turn.then(|| FromTurn {
        speed: request.speed,
        lean: radians(request.lean_deg),
        steer_torque_given: request.steer_torque.is_some(),
        request: library,
    });
    Ok(Plan {
        rider: request.rider,
        initial,
        settings,
        from_turn,
    })
}

/// The leaning rider's own rules; the upper body and the hinge are checked by the library.
fn check_rider(request: &SimulateRequest, rider: &RiderLeanRequest) -> Result<(), ApiError> {
    if request.from_turn {
        return Err(invalid(
            "from_turn",
            "the held turn is the rigid rider's: not taken with `rider`".into(),
        ));
    }
    let finite = |field: &str, value: f64| {
        if value.is_finite() {
            Ok(())
        } else {
            Err(invalid(
                field,
                format!("must be a finite number, got {value}"),
            ))
        }
    };
    finite("rider.hinge_stiffness", rider.hinge_stiffness)?;
    finite("rider.hinge_damping", rider.hinge_damping)?;
    finite("rider.torque", rider.torque)?;
    if rider.lean_deg.abs() >= 90.0 || !rider.lean_deg.is_finite() {
        return Err(invalid(
            "rider.lean_deg",
            format!(
                "the upper body's lean must be below 90° in size (across the bicycle), got {}",
                rider.lean_deg
            ),
        ));
    }
    if let Some(d) = rider.torque_duration {
        if !(d.is_finite() && d >= 0.0) {
            return Err(invalid(
                "rider.torque_duration",
                format!("must be a finite number of seconds, not negative, got {d}"),
            ));
        }
    }
    Ok(())
}

/// How a run ended: a machine-readable kind, the time, and a sentence for people.
#[derive(Serialize, Debug)]
pub struct OutcomeJson {
    /// `completed`, `fell`, `wheel_lifted`, `projection_failed`, `non_finite_state`,
    /// `step_limit`, `stopped` or `failed`.
    pub kind: &'static str,
    /// When it happened \[s\] (the end time for `completed`).
    pub t: f64,
    /// Which wheel, for `wheel_lifted`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wheel: Option<&'static str>,
    /// The outcome in words.
    pub message: String,
}

/// Ground force on one wheel \[N\].
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
    /// The body's origin, its centre of mass \[m\].
    pub position: [f32; 3],
    /// Rotation matrix body → world, row by row.
    pub rotation: [f32; 9],
}

/// One animation frame (a recorded sample).
#[derive(Serialize, Debug)]
pub struct Frame {
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
    /// v [m/s].
    pub speed: f64,
    /// Kinetic + potential energy \[J\].
    pub energy: f64,
    /// Rear contact point (x, y) \[m\].
    pub rear_contact: [f64; 2],
    /// Front contact point (x, y) \[m\].
    pub front_contact: [f64; 2],
    /// Ground force on the rear wheel \[N\].
    pub rear_force: Force,
    /// Ground force on the front wheel \[N\].
    pub front_force: Force,
    /// Rear wheel, rear frame (with the rider, or with the rider's lower body when the upper
    /// body leans), front frame, front wheel; then the upper body when it leans.
    pub bodies: Vec<Pose>,
    /// φ_r: the upper body's lean relative to the rear frame \[rad\], when it leans.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rider_lean: Option<f64>,
}

/// Where the drawing's points sit in the bodies' own axes (x forward, y right, z down, parallel
/// to the world's when upright) relative to each body's origin \[m\].
#[derive(Serialize, Debug)]
pub struct DrawingGeometry {
    /// r_R \[m\].
    pub rear_wheel_radius: f64,
    /// r_F \[m\].
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
    /// Masses of the rear wheel, rear frame with rider (or with the lower body), front frame,
    /// front wheel \[kg\].
    pub masses: [f64; 4],
    /// The leaning upper body, when it leans.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub upper_body: Option<UpperBodyDrawing>,
}

/// The leaning upper body G in the drawing.
#[derive(Serialize, Debug)]
pub struct UpperBodyDrawing {
    /// m_G \[kg\].
    pub mass: f64,
    /// The hinge line's point nearest G's centre of mass, in G's axes from that centre \[m\].
    pub hinge_in_upper_body: [f64; 3],
    /// The hinge's stiffness [N m/rad].
    pub hinge_stiffness: f64,
    /// The hinge's damping [N m s/rad].
    pub hinge_damping: f64,
}

/// The answer of `POST /api/simulate`.
#[derive(Serialize, Debug)]
pub struct SimulateResponse {
    /// The bicycle's name, if it has one.
    pub name: Option<String>,
    /// How the run ended.
    pub outcome: OutcomeJson,
    /// Simulated time asked for \[s\].
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
    /// With `from_turn`: the held turn the run started on.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn: Option<SteadyTurn>,
}

/// The library's outcome, with what this server adds (its step limit, why it stopped a run).
fn describe(outcome: &Outcome, duration: f64, max_steps: usize) -> OutcomeJson {
    // Times to the hundredth of a second, as the page shows them.
    let message = match outcome {
        Outcome::Completed => format!("{outcome}: {duration} s without falling"),
        Outcome::StepSizeTooSmall { .. } => format!(
            "{outcome:.2} (or it reached this server's limit of {max_steps} steps); loosen rtol or simulate a shorter time"
        ),
        Outcome::Stopped { .. } => {
            format!("{outcome:.2}: nobody waits for the result any more (time up or client gone)")
        }
        _ => format!("{outcome:.2}"),
    };
    OutcomeJson {
        kind: outcome.kind(),
        t: outcome.t().unwrap_or(duration),
        wheel: match outcome {
            Outcome::WheelLifted { wheel, .. } => Some(wheel.name()),
            _ => None,
        },
        message,
    }
}

fn pose(p: &BodyPose) -> Pose {
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
}

fn frame(model: &Model, s: &Sample) -> Frame {
    let bodies = model.sample_poses(s).iter().map(pose).collect();
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
        rider_lean: None,
    }
}

/// The samples at about [`FRAME_RATE`] per simulated second: the first sample at or after each
/// frame time, and always the first and the last (their indices).
fn thin_indices(samples: &[Sample]) -> Vec<usize> {
    let mut frames = Vec::new();
    let mut next = 0.0;
    let good: Vec<usize> = (0..samples.len())
        .filter(|&i| samples[i].is_finite())
        .collect();
    for (k, &i) in good.iter().enumerate() {
        let s = &samples[i];
        if s.t >= next - 1e-9 || k + 1 == good.len() {
            frames.push(i);
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
    if let Some(rider) = plan.rider {
        return run_rider(name, parameters, plan, rider, max_steps, stop);
    }
    let model = Model::new(parameters)?;
    let at_start = |error: whipple::Error| {
        // The initial state comes from the request's numbers and the bicycle.
        let rule = error.to_string();
        ApiError::from(error).at(INITIAL_FIELDS, rule)
    };
    let (initial, settings, turn) = match plan.from_turn {
        None => (plan.initial, plan.settings, None),
        Some(from) => {
            let turn = held_turn(
                &model,
                from.speed,
                Held::Lean(from.lean),
                &TurnSettings::default(),
            )
            .map_err(|error| match error {
                whipple::Error::InvalidArgument { what, rule } => {
                    invalid(if what == "lean" { "lean_deg" } else { what }, rule)
                }
                other => ApiError::from(other).in_field("speed, lean_deg".to_string()),
            })?;
            // The turn's own state, perturbed by the request's rates, and its torque held.
            let mut request = from.request;
            if !from.steer_torque_given {
                request.steer_torque = TorqueInput::Constant(turn.steer_torque);
            }
            let (_, settings) = request.validate().map_err(library_error)?;
            let initial = InitialConditions {
                lean_rate: plan.initial.lean_rate,
                steer_rate: plan.initial.steer_rate,
                ..turn.initial_conditions()
            };
            (initial, settings, Some(turn))
        }
    };
    let start = model.initial_state(&initial).map_err(at_start)?;
    let settings = SimulationSettings {
        stop: Some(stop),
        ..settings
    };
    let duration = settings.duration;
    let simulation = simulate(&model, start, &settings).map_err(|error| match error {
        // A step too coarse for the run names `dt` or `rtol`, not the initial state.
        error @ whipple::Error::StepTooLarge { .. } => ApiError::from(error),
        other => at_start(other),
    })?;
    let geometry = drawing(&model, None);
    let frames = thin_indices(&simulation.samples)
        .into_iter()
        .map(|i| frame(&model, &simulation.samples[i]))
        .collect();
    Ok(SimulateResponse {
        name,
        outcome: describe(&simulation.outcome, duration, max_steps),
        duration,
        steps: simulation.steps,
        frame_rate: FRAME_RATE,
        pulled_down_from_start: simulation
            .pulled_down_from_start
            .iter()
            .map(|w| w.name())
            .collect(),
        geometry,
        frames,
        turn,
    })
}

/// The drawing's fixed geometry of a bicycle (and its leaning upper body).
fn drawing(model: &Model, upper_body: Option<UpperBodyDrawing>) -> DrawingGeometry {
    let g = &model.bodies().geometry;
    DrawingGeometry {
        rear_wheel_radius: model.parameters().r_r,
        front_wheel_radius: model.parameters().r_f,
        rear_hub_in_rear_frame: g.rear_hub_in_b.into(),
        steer_point_in_rear_frame: g.steer_point_in_b.into(),
        steer_point_in_front_frame: g.steer_point_in_h.into(),
        front_hub_in_front_frame: g.front_hub_in_h.into(),
        steer_axis: g.steer_axis.into(),
        masses: model.bodies().body.map(|b| b.mass),
        upper_body,
    }
}

/// Runs a checked request with the leaning rider: the library's `LeanModel` of the bicycle
/// with Jason's upper body split off its rear frame, under the rider's hinge torque.
fn run_rider(
    name: Option<String>,
    parameters: &BenchmarkParameters,
    plan: Plan,
    rider: RiderLeanRequest,
    max_steps: usize,
    stop: Arc<AtomicBool>,
) -> Result<SimulateResponse, ApiError> {
    let jason = RiderLeanParameters::browser_jason().upper_body;
    let upper_body = UpperBody {
        stiffness: rider.hinge_stiffness,
        damping: rider.hinge_damping,
        ..jason
    };
    let field = |error: whipple::Error| -> ApiError {
        match error {
            whipple::Error::InvalidParameter { field, rule, .. } => match field.as_str() {
                "kLean" => invalid("rider.hinge_stiffness", rule),
                "cLean" => invalid("rider.hinge_damping", rule),
                // Jason's upper body against the bicycle's rear frame: the bicycle's fault.
                _ => unprocessable(
                    "invalid_parameter",
                    "bike",
                    rule.clone(),
                    format!(
                        "Jason's upper body ({} kg, Moore 2012) cannot lean on this bicycle: \
                         {rule}",
                        jason.m
                    ),
                ),
            },
            other => ApiError::from(other),
        }
    };
    let p = RiderLeanParameters::split(parameters, upper_body).map_err(field)?;
    let model = LeanModel::new(&p).map_err(field)?;
    let lean = radians(rider.lean_deg);
    let start = model
        .initial_state(&plan.initial, lean, 0.0)
        .map_err(|error| {
            let rule = error.to_string();
            ApiError::from(error).at(INITIAL_FIELDS, rule)
        })?;
    let settings = SimulationSettings {
        stop: Some(stop),
        ..plan.settings
    };
    let duration = settings.duration;
    let until = rider.torque_duration.unwrap_or(f64::INFINITY);
    let torque = rider.torque;
    let hinge_torque: TorqueFn = Box::new(move |t, _| if t <= until { torque } else { 0.0 });
    let run = model
        .simulate(
            &start,
            &settings,
            &LeanForcing {
                hinge_torque: Some(&hinge_torque),
                hinge_limit: HINGE_LIMIT,
            },
        )
        .map_err(|error| match error {
            // A step too coarse for the run names `dt` or `rtol`, not the initial state.
            error @ whipple::Error::StepTooLarge { .. } => ApiError::from(error),
            error @ whipple::Error::InvalidArgument { .. } => library_error(error),
            other => ApiError::from(other),
        })?;
    let bicycle = model.bicycle();
    let simulation = &run.simulation;
    let kept: Vec<usize> = thin_indices(&simulation.samples);
    let frames = kept
        .into_iter()
        .map(|i| {
            let (s, [rider_lean, _]) = (&simulation.samples[i], run.rider[i]);
            Frame {
                bodies: model.sample_poses(s, rider_lean).iter().map(pose).collect(),
                rider_lean: Some(rider_lean),
                ..frame(bicycle, s)
            }
        })
        .collect();
    let hinge = model.hinge_in_upper_body();
    let geometry = drawing(
        bicycle,
        Some(UpperBodyDrawing {
            mass: upper_body.m,
            hinge_in_upper_body: hinge.into(),
            hinge_stiffness: upper_body.stiffness,
            hinge_damping: upper_body.damping,
        }),
    );
    Ok(SimulateResponse {
        name,
        outcome: describe(&simulation.outcome, duration, max_steps),
        duration,
        steps: simulation.steps,
        frame_rate: FRAME_RATE,
        pulled_down_from_start: simulation
            .pulled_down_from_start
            .iter()
            .map(|w| w.name())
            .collect(),
        geometry,
        frames,
        turn: None,
    })
}
