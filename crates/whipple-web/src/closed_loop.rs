//! `POST /api/linear/closed_loop`: the bicycle under full-state feedback u = r − K x on
//! (φ, δ, φ̇, δ̇), what the page's Control tab draws. K is given, or designed by LQR (Q, R) at
//! one speed or at every speed of the sweep (a schedule); the answer is the gain used, the
//! closed loop's eigenvalues against speed in `/api/eigen`'s shape (tracked and labelled by the
//! library's sweep, so the page's eigenvalue plot draws them unchanged) and its certified
//! critical speeds. The inputs are read by `whipple_front::system` (the names the CLI and
//! Python take); the numbers are the library's (`ClosedLoop`, `LinearSystem::lqr`,
//! `lqr_schedule`); this module only checks the request and shapes the answer.

use bytes::Bytes;
use http::StatusCode;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::advanced::control::{ClosedLoop, Gains, MAX_SCHEDULE_SPEEDS, lqr_schedule};
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use whipple::{CriticalSpeeds, speed_grid};

use crate::Limits;
use crate::api::{
    Budget, EigenColumn, INTERACTIVE_SPEEDS, Job, SpeedGrid, bicycle, check_grid, json_body,
};
use crate::error::ApiError;

/// The most inputs fed back at once (there are two torques and a lateral force).
pub(crate) const MAX_INPUTS: usize = 4;

/// The states K reads, in the order of its columns.
const STATES: [&str; 4] = ["lean", "steer", "lean_rate", "steer_rate"];

/// The LQR design asked for: Q (4 × 4, or its diagonal), R (inputs × inputs, its diagonal, or
/// one number for one input), at one `speed` or `scheduled` at every speed of the sweep.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct LqrRequest {
    q: Value,
    r: Value,
    #[serde(default)]
    speed: Option<f64>,
    #[serde(default)]
    scheduled: bool,
}

/// The body of `POST /api/linear/closed_loop`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct ClosedLoopRequest {
    /// The bicycle, in the parameter files' JSON layout.
    bike: Value,
    /// The inputs fed back, by name (default: `["steer_torque"]`).
    #[serde(default)]
    inputs: Option<Vec<String>>,
    /// K: one row of 4 gains per input (a flat list of 4 for one input).
    #[serde(default)]
    gains: Option<Value>,
    /// Or K designed by LQR.
    #[serde(default)]
    lqr: Option<LqrRequest>,
    /// The sweep's speeds [m/s].
    speeds: SpeedGrid,
}

/// How K was found, and K.
#[derive(Serialize, Debug)]
#[serde(tag = "kind", rename_all = "snake_case")]
enum GainsUsed {
    /// K as given.
    Constant { k: Vec<Vec<f64>> },
    /// K of the LQR at one speed, with the Riccati equation's relative residual.
    Lqr {
        speed: f64,
        k: Vec<Vec<f64>>,
        residual: f64,
    },
    /// K of the LQR at every speed of the sweep, interpolated linearly between them.
    Scheduled {
        schedule: Vec<ScheduledGain>,
        largest_residual: f64,
    },
}

#[derive(Serialize, Debug)]
struct ScheduledGain {
    speed: f64,
    k: Vec<Vec<f64>>,
    residual: f64,
}

/// The answer: `/api/eigen`'s fields for the closed loop, and the gains.
#[derive(Serialize)]
pub(crate) struct ClosedLoopAnswer {
    name: Option<String>,
    inputs: Vec<String>,
    /// K's columns.
    states: [&'static str; 4],
    gains: GainsUsed,
    speeds: Vec<f64>,
    eigenvalues: Vec<EigenColumn>,
    /// Certified over the sweep's speeds; null for a single speed, or where round-off could
    /// not certify them (`critical_unavailable` says why).
    critical: Option<CriticalSpeeds>,
    critical_unavailable: Option<String>,
}

fn invalid(field: &str, rule: String) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "invalid_argument",
        format!("invalid `{field}`: {rule}"),
    )
    .at(field, rule)
}

/// A number, a list of numbers (one row) or a list of rows, at most `max` × `max`, every
/// entry finite; errors name `field`.
fn matrix(value: &Value, field: &str, max: usize) -> Result<DMatrix<f64>, ApiError> {
    let entry = |x: &Value, at: String| -> Result<f64, ApiError> {
        x.as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| invalid(field, format!("{at} must be a finite number, got {x}")))
    };
    let rows: Vec<Vec<f64>> = match value {
        Value::Number(_) => vec![vec![entry(value, "the entry".into())?]],
        Value::Array(items) if items.iter().all(|x| !x.is_array()) => {
            if items.len() > max {
                return Err(invalid(
                    field,
                    format!("at most {max} entries, got {}", items.len()),
                ));
            }
            vec![
                items
                    .iter()
                    .enumerate()
                    .map(|(j, x)| entry(x, format!("entry {}", j + 1)))
                    .collect::<Result<_, _>>()?,
            ]
        }
        Value::Array(items) => {
            if items.len() > max {
                return Err(invalid(
                    field,
                    format!("at most {max} rows, got {}", items.len()),
                ));
            }
            let mut rows = Vec::with_capacity(items.len());
            for (i, row) in items.iter().enumerate() {
                let Some(row) = row.as_array() else {
                    return Err(invalid(
                        field,
                        format!("row {} must be a list of numbers, got {row}", i + 1),
                    ));
                };
                if row.len() > max {
                    return Err(invalid(
                        field,
                        format!("at most {max} entries a row, got {}", row.len()),
                    ));
                }
                rows.push(
                    row.iter()
                        .enumerate()
                        .map(|(j, x)| entry(x, format!("row {} entry {}", i + 1, j + 1)))
                        .collect::<Result<Vec<_>, _>>()?,
                );
            }
            rows
        }
        other => {
            return Err(invalid(
                field,
                format!("must be a number, a list of numbers or a list of rows, got {other}"),
            ));
        }
    };
    let columns = rows.first().map_or(0, Vec::len);
    if columns == 0 {
        return Err(invalid(field, "give at least one entry".into()));
    }
    if let Some((i, row)) = rows.iter().enumerate().find(|(_, r)| r.len() != columns) {
        return Err(invalid(
            field,
            format!(
                "every row needs the same number of entries: row 1 has {columns}, row {} has {}",
                i + 1,
                row.len()
            ),
        ));
    }
    Ok(DMatrix::from_row_iterator(
        rows.len(),
        columns,
        rows.into_iter().flatten(),
    ))
}

/// A square weight: n × n as given, or its diagonal given as one row of n (one number for
/// n = 1).
fn weight(value: &Value, field: &str, n: usize, what: &str) -> Result<DMatrix<f64>, ApiError> {
    let m = matrix(value, field, n.max(1))?;
    match m.shape() {
        (1, c) if c == n => Ok(DMatrix::from_diagonal(&DVector::from_iterator(
            n,
            m.iter().copied(),
        ))),
        (r, c) if r == n && c == n => Ok(m),
        (r, c) => Err(invalid(
            field,
            format!("{what} must be {n} × {n}, or its diagonal of {n}, got {r} × {c}"),
        )),
    }
}

/// How the gains are to be found.
enum Design {
    Given(DMatrix<f64>),
    Lqr {
        q: DMatrix<f64>,
        r: DMatrix<f64>,
        speed: f64,
    },
    Scheduled {
        q: DMatrix<f64>,
        r: DMatrix<f64>,
    },
}

/// The request checked, before any work.
struct Plan {
    inputs: Vec<String>,
    request: SystemRequest,
    design: Design,
    grid: SpeedGrid,
}

fn check(request: &ClosedLoopRequest, max_speeds: usize) -> Result<(Plan, f64), ApiError> {
    let names = match &request.inputs {
        None => vec!["steer_torque".to_string()],
        Some(names) if names.is_empty() => {
            return Err(invalid("inputs", "give at least one input".into()));
        }
        Some(names) if names.len() > MAX_INPUTS => {
            return Err(invalid(
                "inputs",
                format!("at most {MAX_INPUTS} inputs, got {}", names.len()),
            ));
        }
        Some(names) => names.iter().map(|n| n.trim().to_string()).collect(),
    };
    let inputs = names
        .iter()
        .map(|n| whipple_front::system::parse_input(n))
        .collect::<whipple::Result<Vec<Input>>>()
        .map_err(|e| ApiError::from(e).in_field("inputs"))?;
    let m = inputs.len();
    let design = match (&request.gains, &request.lqr) {
        (Some(k), None) => {
            let k = matrix(k, "gains", MAX_INPUTS.max(4))?;
            if k.shape() != (m, 4) {
                return Err(invalid(
                    "gains",
                    format!(
                        "K must be inputs × states = {m} × 4 (one row per input; the columns are \
                         φ, δ, φ̇, δ̇), got {} × {}",
                        k.nrows(),
                        k.ncols()
                    ),
                ));
            }
            Design::Given(k)
        }
        (None, Some(lqr)) => {
            let q = weight(&lqr.q, "lqr.q", 4, "Q")?;
            let r = weight(&lqr.r, "lqr.r", m, "R")?;
            match (lqr.speed, lqr.scheduled) {
                (Some(speed), false) if speed.is_finite() => Design::Lqr { q, r, speed },
                (Some(speed), false) => {
                    return Err(invalid(
                        "lqr.speed",
                        format!("the design speed must be a finite number, got {speed}"),
                    ));
                }
                (None, true) => Design::Scheduled { q, r },
                _ => {
                    return Err(invalid(
                        "lqr",
                        "give the design speed (`speed`) or `scheduled: true` (the gains at \
                         every speed of the sweep), one of them"
                            .into(),
                    ));
                }
            }
        }
        _ => {
            return Err(invalid(
                "gains",
                "give the gains K (`gains`) or LQR weights (`lqr`), one of them".into(),
            ));
        }
    };
    let count = check_grid(request.speeds, max_speeds)?;
    if matches!(design, Design::Scheduled { .. }) && count > MAX_SCHEDULE_SPEEDS as f64 {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "limit_exceeded",
            format!(
                "a schedule is designed at each speed of the sweep: {count} speeds are more \
                 than the limit of {MAX_SCHEDULE_SPEEDS}; use a larger step"
            ),
        )
        .at(
            "speeds",
            format!("at most {MAX_SCHEDULE_SPEEDS} speeds for a scheduled LQR"),
        ));
    }
    let request_system = SystemRequest {
        states: Vec::new(),
        inputs,
        outputs: StateVariable::LEAN_STEER.map(Output::State).to_vec(),
    };
    Ok((
        Plan {
            inputs: names,
            request: request_system,
            design,
            grid: request.speeds,
        },
        count,
    ))
}

/// A core error about a field of the request, named as the request names it.
fn named(error: whipple::Error, fields: &[(&str, &str)]) -> ApiError {
    let field = match &error {
        whipple::Error::InvalidArgument { what, .. } => fields
            .iter()
            .find(|(core, _)| core == what)
            .map(|(_, field)| *field),
        _ => None,
    };
    let e = ApiError::from(error);
    match field {
        Some(field) => e.in_field(field),
        None => e,
    }
}

const LQR_FIELDS: [(&str, &str); 4] = [
    ("Q", "lqr.q"),
    ("R", "lqr.r"),
    ("inputs", "inputs"),
    ("speed", "lqr.speed"),
];

fn rows(k: &DMatrix<f64>) -> Vec<Vec<f64>> {
    k.row_iter().map(|r| r.iter().copied().collect()).collect()
}

fn answer(
    name: Option<String>,
    bike: &whipple::BenchmarkParameters,
    plan: Plan,
) -> Result<ClosedLoopAnswer, ApiError> {
    let SpeedGrid { start, stop, step } = plan.grid;
    let speeds = speed_grid(start, stop, step).map_err(|e| ApiError::from(e).in_field("speeds"))?;
    let (gains, used) = match plan.design {
        Design::Given(k) => (
            Gains::Constant(k.clone()),
            GainsUsed::Constant { k: rows(&k) },
        ),
        Design::Lqr { q, r, speed } => {
            let lqr = LinearSystem::new(bike, speed, &plan.request)
                .and_then(|s| s.lqr(&q, &r))
                .map_err(|e| named(e, &LQR_FIELDS))?;
            (
                Gains::Constant(lqr.gains.clone()),
                GainsUsed::Lqr {
                    speed,
                    k: rows(&lqr.gains),
                    residual: lqr.residual,
                },
            )
        }
        Design::Scheduled { q, r } => {
            if speeds.len() < 2 {
                return Err(invalid(
                    "speeds",
                    "a schedule needs a sweep of at least two speeds".into(),
                ));
            }
            let schedule = lqr_schedule(bike, &plan.request, &speeds, &q, &r)
                .map_err(|e| named(e, &LQR_FIELDS))?;
            let largest_residual = schedule
                .solutions
                .iter()
                .fold(0.0f64, |m, s| m.max(s.residual));
            let used = GainsUsed::Scheduled {
                schedule: speeds
                    .iter()
                    .zip(&schedule.solutions)
                    .map(|(v, s)| ScheduledGain {
                        speed: *v,
                        k: rows(&s.gains),
                        residual: s.residual,
                    })
                    .collect(),
                largest_residual,
            };
            (schedule.gains, used)
        }
    };
    let closed = ClosedLoop::new(bike, &plan.request, gains)
        .map_err(|e| named(e, &[("gains", "gains"), ("inputs", "inputs")]))?;
    let sweep = closed
        .eigen_sweep(&speeds)
        .map_err(|e| named(e, &[("speed", "speeds"), ("speeds", "speeds")]))?;
    let (lo, hi) = (
        speeds.first().copied().unwrap_or(start),
        speeds.last().copied().unwrap_or(stop),
    );
    let (critical, critical_unavailable) = if hi <= lo {
        (None, None)
    } else {
        match closed.critical_speeds(lo, hi) {
            Ok(c) => (Some(c), None),
            // Round-off could not certify a speed: the sweep stands, the speeds are not given.
            Err(e @ whipple::Error::AccuracyLost { .. }) => {
                (None, Some(whipple_front::message::message(&e)))
            }
            Err(e) => return Err(named(e, &[("range", "speeds"), ("speed", "speeds")])),
        }
    };
    Ok(ClosedLoopAnswer {
        name,
        inputs: plan.inputs,
        states: STATES,
        gains: used,
        eigenvalues: EigenColumn::of(&sweep),
        speeds: sweep.speeds,
        critical,
        critical_unavailable,
    })
}

pub(crate) fn closed_loop(limits: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: ClosedLoopRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let (plan, count) = check(&request, limits.max_speeds)?;
    let budget = if count <= INTERACTIVE_SPEEDS {
        Budget::Interactive
    } else {
        Budget::Heavy
    };
    Ok(Job::json(budget, "ask for fewer speeds", move |_| {
        let benchmark = bike.benchmark()?;
        answer(bike.name.clone(), &benchmark, plan)
    }))
}
