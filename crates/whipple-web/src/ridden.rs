//! `POST /api/ridden`: the bicycle ridden by Hess's human controller, what the page's Ridden
//! tab draws: HumanControl's lane change at one speed on the linear and the non-linear bicycle
//! (the front contact's path in the plane beside the road), and the handling quality metric's
//! peak against speed; the rider's gains set at every speed by Hess 2012's rules. The numbers
//! are the library's (`hess_gains`, `lane_change_linear`, `lane_change_nonlinear`,
//! `judge_handling`); this module only checks the request and shapes the answer.

use std::sync::atomic::Ordering;

use bytes::Bytes;
use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::advanced::control::{
    CrossoverRules, HumanController, HumanGains, LaneChange, LaneChangeRun, LaneKind,
    Neuromuscular, OptimalHandlingSettings, Task, hess_gains, judge_handling, lane_change_linear,
    lane_change_nonlinear,
};
use whipple::speed_grid;

use crate::Limits;
use crate::api::{Budget, Job, SpeedGrid, bicycle, check_grid, json_body};
use crate::error::ApiError;

/// The slowest lane change asked for [m/s]: its 250 m take 250 s of the non-linear model.
pub(crate) const MIN_LANE_SPEED: f64 = 1.0;

/// The fastest [m/s].
pub(crate) const MAX_LANE_SPEED: f64 = 20.0;

/// The most speeds of the metric's sweep.
pub(crate) const MAX_HQM_SPEEDS: usize = 500;

/// The non-linear lane change's relative tolerance.
const NONLINEAR_RTOL: f64 = 1e-8;

fn default_lane() -> String {
    "double".into()
}

/// The body of `POST /api/ridden`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct RiddenRequest {
    /// The bicycle, in the parameter files' JSON layout.
    bike: Value,
    /// The lane change's speed [m/s].
    speed: f64,
    /// `single` or `double` (HumanControl's `lane_change.m`).
    #[serde(default = "default_lane")]
    lane: String,
    /// The speeds of the handling quality metric's sweep [m/s].
    speeds: SpeedGrid,
}

/// One model's run of the lane change.
#[derive(Serialize, Debug)]
struct Run {
    /// The front contact's distance along x [m].
    front_x: Vec<f64>,
    /// The front contact's y, right positive [m].
    front_y: Vec<f64>,
    /// The road: the path delayed by the rider's preview [m].
    road: Vec<f64>,
}

impl Run {
    fn of(run: &LaneChangeRun) -> Run {
        Run {
            front_x: run.front_x.clone(),
            front_y: run.front_y.clone(),
            road: run.path.clone(),
        }
    }
}

/// The metric's peak at one speed of the sweep, or why there is none.
#[derive(Serialize, Debug)]
struct HqmRow {
    speed: f64,
    /// The certified peak of |HQM(jω)|; null where the rules or the loops fail.
    peak: Option<f64>,
    /// ω at the peak [rad/s].
    frequency: Option<f64>,
    /// The roll and lateral loops are stable (the metric means something only then).
    stable: bool,
    /// Why the speed has no peak.
    reason: Option<String>,
}

/// The answer of `POST /api/ridden`.
#[derive(Serialize, Debug)]
pub(crate) struct RiddenResponse {
    name: Option<String>,
    speed: f64,
    lane: &'static str,
    /// The gains by Hess 2012's rules at `speed`: kDelta, kPhiDot, kPhi, kPsi, kY.
    gains: [f64; 5],
    gain_names: [&'static str; 5],
    linear: Run,
    /// Null when the non-linear bicycle did not complete the manoeuvre (`nonlinear_error`).
    nonlinear: Option<Run>,
    nonlinear_error: Option<String>,
    hqm: Vec<HqmRow>,
}

fn invalid(field: &str, rule: String) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "invalid_argument",
        format!("invalid `{field}`: {rule}"),
    )
    .at(field, rule)
}

/// `POST /api/ridden`.
pub(crate) fn ridden(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: RiddenRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let speed = request.speed;
    if !(speed.is_finite() && (MIN_LANE_SPEED..=MAX_LANE_SPEED).contains(&speed)) {
        return Err(invalid(
            "speed",
            format!(
                "the lane change's speed must lie from {MIN_LANE_SPEED} to {MAX_LANE_SPEED} m/s, got {speed}"
            ),
        ));
    }
    let lane = match request.lane.as_str() {
        "single" => LaneKind::Single,
        "double" => LaneKind::Double,
        other => {
            return Err(invalid(
                "lane",
                format!("`single` or `double`, got `{other}`"),
            ));
        }
    };
    let grid = request.speeds;
    check_grid(grid, MAX_HQM_SPEEDS)?;
    Ok(Job::json(
        Budget::Heavy,
        "ask for fewer speeds",
        move |stop| {
            let benchmark = bike.benchmark()?;
            let speeds = speed_grid(grid.start, grid.stop, grid.step)
                .map_err(|e| ApiError::from(e).in_field("speeds"))?;
            let nm = Neuromuscular::default();
            let gains = hess_gains(&benchmark, speed, &nm, &CrossoverRules::default())
                .map_err(|e| ApiError::from(e).in_field("speed"))?;
            let controller = HumanController::new(Task::Lateral, gains, nm)?;
            let path = LaneChange::humancontrol(lane);
            let linear = lane_change_linear(&benchmark, speed, &controller, &path)?;
            let (nonlinear, nonlinear_error) = match lane_change_nonlinear(
                &benchmark,
                speed,
                &controller,
                &path,
                NONLINEAR_RTOL,
            ) {
                Ok(run) => (Some(Run::of(&run)), None),
                Err(e) => (None, Some(e.to_string())),
            };
            let mut hqm = Vec::with_capacity(speeds.len());
            for &v in &speeds {
                if stop.load(Ordering::Relaxed) {
                    return Err(ApiError::internal("stopped"));
                }
                let judged = judge_handling(&bike, &[], &[], &OptimalHandlingSettings::at(v));
                // A peak is shown only where both loops are stable: elsewhere it means nothing.
                let peak = judged.peak.filter(|_| judged.stable);
                let reason = match (&judged.refused, judged.stable) {
                    (Some(why), _) => Some(why.clone()),
                    (None, false) => Some("the roll or the lateral loop is unstable".to_string()),
                    (None, true) => None,
                };
                hqm.push(HqmRow {
                    speed: v,
                    peak: peak.map(|p| p.magnitude),
                    frequency: peak.map(|p| p.frequency),
                    stable: judged.stable,
                    reason,
                });
            }
            Ok(RiddenResponse {
                name: bike.name.clone(),
                speed,
                lane: lane.name(),
                gains: gains.to_array(),
                gain_names: HumanGains::NAMES,
                linear: Run::of(&linear),
                nonlinear,
                nonlinear_error,
                hqm,
            })
        },
    ))
}
