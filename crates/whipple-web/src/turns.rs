//! `POST /api/turn`: one held steady turn of the non-linear bicycle, the steer torque that holds
//! it and its stability (`whipple::advanced::turns`, what `whipple turn` prints).

use bytes::Bytes;
use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::Model;
use whipple::advanced::turns::{Held, Stability, SteadyTurn, TurnSettings, held_turn, stability};

use crate::Limits;
use crate::api::{Budget, Job, bicycle, json_body};
use crate::error::ApiError;

/// The body of `POST /api/turn`: the speed of the rear contact and exactly one of the lean, the
/// steer (degrees, as typed; right positive) or the rear contact's radius (m, positive right).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TurnRequest {
    bike: Value,
    speed: f64,
    #[serde(default)]
    lean_deg: Option<f64>,
    #[serde(default)]
    steer_deg: Option<f64>,
    #[serde(default)]
    radius: Option<f64>,
}

/// The answer: the turn (radians, SI) with its angles in degrees beside, and its stability (or
/// why it could not be decided).
#[derive(Serialize)]
pub(crate) struct TurnResponse {
    name: Option<String>,
    turn: SteadyTurn,
    lean_deg: f64,
    steer_deg: f64,
    stability: Option<Stability>,
    stability_error: Option<String>,
}

/// The request's field for a library argument's name.
fn field(what: &str) -> &str {
    match what {
        "lean" => "lean_deg",
        "steer" => "steer_deg",
        other => other,
    }
}

pub(crate) fn turn(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: TurnRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let (given, given_field) = match (request.lean_deg, request.steer_deg, request.radius) {
        (Some(lean), None, None) => (Held::Lean(lean.to_radians()), "lean_deg"),
        (None, Some(steer), None) => (Held::Steer(steer.to_radians()), "steer_deg"),
        (None, None, Some(radius)) => (Held::Radius(radius), "radius"),
        _ => {
            return Err(ApiError::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                "invalid_argument",
                "give exactly one of `lean_deg`, `steer_deg` or `radius`",
            )
            .at("lean_deg", "exactly one of lean_deg, steer_deg, radius"));
        }
    };
    let speed = request.speed;
    Ok(Job::json(
        Budget::Interactive,
        "ask for a smaller lean or steer",
        move |_| {
            let model = Model::new(&bike.benchmark()?)?;
            let turn = held_turn(&model, speed, given, &TurnSettings::default()).map_err(|e| {
                let name = match &e {
                    whipple::Error::InvalidArgument { what, .. } => Some(field(what).to_string()),
                    // No turn at this speed with what was given: the given is the field to change.
                    whipple::Error::NoSteadyTurn { .. } => Some(given_field.to_string()),
                    _ => None,
                };
                let error = ApiError::from(e);
                match name {
                    Some(name) => error.in_field(name),
                    None => error,
                }
            })?;
            let (stability, stability_error) = match stability(&model, &turn) {
                Ok(s) => (Some(s), None),
                Err(e) => (None, Some(e.to_string())),
            };
            Ok(TurnResponse {
                name: bike.name.clone(),
                lean_deg: turn.lean.to_degrees(),
                steer_deg: turn.steer.to_degrees(),
                turn,
                stability,
                stability_error,
            })
        },
    ))
}
