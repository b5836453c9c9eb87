//! `POST /api/linear/frequency`: one input–output pair of the bicycle as a linear system at a
//! few speeds — poles, zeros (the right-half-plane ones flagged), gain, static gain and the
//! frequency response on a logarithmic grid (magnitude absolute and in dB, phase unwrapped in
//! degrees) — what the page's Response tab draws as Bode plots. The signals are read by
//! `whipple_front::system` (the names the CLI and Python take), the numbers are the library's
//! (`LinearSystem::transfer_function`, `origin_zero_speeds`); this module only shapes them.

use bytes::Bytes;
use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::advanced::linear::{
    Input, LinearSystem, Output, StateVariable, SystemRequest, TransferFunction, origin_zero_speeds,
};

use crate::Limits;
use crate::api::{Budget, Job, bicycle, json_body};
use crate::error::ApiError;

/// The most speeds one request compares.
pub(crate) const MAX_SPEEDS: usize = 16;

/// The most frequencies one request's grid holds (the page asks for a few hundred).
pub(crate) const MAX_FREQUENCIES: usize = 2_000;

/// A logarithmic grid of angular frequencies ω [rad/s], both ends included.
#[derive(Deserialize, Clone, Copy, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct FrequencyGrid {
    start: f64,
    stop: f64,
    count: usize,
}

/// The body of `POST /api/linear/frequency`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct FrequencyRequest {
    /// The bicycle, in the parameter files' JSON layout.
    bike: Value,
    /// v [m/s]: one to [`MAX_SPEEDS`] forward speeds.
    speeds: Vec<f64>,
    /// `lean_torque`, `steer_torque` or `lateral_force:X,Z` (whipple-front's spellings).
    input: String,
    /// A state's name, `yaw_rate`, `front_contact_y`, … (whipple-front's spellings).
    output: String,
    /// ω [rad/s].
    frequencies: FrequencyGrid,
}

/// A signal as the library names it.
#[derive(Serialize, Debug)]
struct Signal {
    name: String,
    symbol: &'static str,
    unit: &'static str,
}

/// A zero of the transfer function [1/s]; `right_half_plane`: its real part is positive (a
/// non-minimum-phase zero).
#[derive(Serialize, Debug)]
struct Zero {
    re: f64,
    im: f64,
    right_half_plane: bool,
}

/// One speed's transfer function and frequency response.
#[derive(Serialize, Debug)]
struct AtSpeed {
    speed: f64,
    /// [re, im] [1/s]: the lean–steer eigenvalues, then the integrators' poles at 0.
    poles: Vec<[f64; 2]>,
    zeros: Vec<Zero>,
    /// K of G(s) = K Π(s − zᵢ) / Π(s − pᵢ).
    gain: f64,
    /// G(0); null with an integrator or where G(0) is not finite.
    static_gain: Option<f64>,
    /// True when the input does not reach the output to first order (G ≡ 0).
    zero_response: bool,
    /// |G(iω)| [output unit per input unit].
    magnitude: Vec<f64>,
    /// 20 log₁₀ |G(iω)| [dB]; null where G ≡ 0.
    magnitude_db: Vec<Option<f64>>,
    /// arg G(iω) [deg], unwrapped along the grid.
    phase_deg: Vec<f64>,
}

/// A speed [m/s] at which a zero crosses s = 0, certified within [lo, hi].
#[derive(Serialize, Debug)]
struct Crossing {
    value: f64,
    lo: f64,
    hi: f64,
}

/// The answer of `POST /api/linear/frequency`.
#[derive(Serialize, Debug)]
pub(crate) struct FrequencyResponseJson {
    name: Option<String>,
    input: Signal,
    output: Signal,
    /// ω [rad/s].
    frequencies: Vec<f64>,
    /// One per speed asked for, in order.
    responses: Vec<AtSpeed>,
    /// For a lean or steer output: the positive speeds where a zero passes through s = 0,
    /// where the pair changes between non-minimum-phase and minimum-phase; null otherwise.
    origin_zero_speeds: Option<Vec<Crossing>>,
}

/// The request checked: signals read, speeds and grid within the limits.
struct Plan {
    speeds: Vec<f64>,
    /// One input, one output, and the ignorable coordinates the output needs.
    request: SystemRequest,
    input: Input,
    output: Output,
    input_text: String,
    output_text: String,
    frequencies: Vec<f64>,
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

/// Checks everything but the bicycle, before any work.
fn check(request: &FrequencyRequest) -> Result<Plan, ApiError> {
    let n = request.speeds.len();
    if n == 0 {
        return Err(invalid("speeds", "give at least one speed".into()));
    }
    if n > MAX_SPEEDS {
        return Err(limit(
            "speeds",
            format!("{n} speeds are more than this server's limit of {MAX_SPEEDS} per request"),
            format!("at most {MAX_SPEEDS} speeds per request"),
        ));
    }
    for (k, v) in request.speeds.iter().enumerate() {
        if !v.is_finite() {
            return Err(invalid(
                "speeds",
                format!("speed {} must be a finite number, got {v}", k + 1),
            ));
        }
    }
    let input = whipple_front::system::parse_input(&request.input)
        .map_err(|e| ApiError::from(e).in_field("input"))?;
    let output = whipple_front::system::parse_output(&request.output)
        .map_err(|e| ApiError::from(e).in_field("output"))?;
    let system = whipple_front::system::request(&[&request.input], &[&request.output])
        .map_err(|e| ApiError::from(e).in_field("output"))?;
    let FrequencyGrid { start, stop, count } = request.frequencies;
    if count > MAX_FREQUENCIES {
        return Err(limit(
            "frequencies",
            format!(
                "{count} frequencies are more than this server's limit of {MAX_FREQUENCIES} per request"
            ),
            format!("at most {MAX_FREQUENCIES} frequencies per request"),
        ));
    }
    let frequencies = whipple_front::system::log_grid(start, stop, count)
        .map_err(|e| ApiError::from(e).in_field("frequencies"))?;
    Ok(Plan {
        speeds: request.speeds.clone(),
        request: system,
        input,
        output,
        input_text: request.input.trim().to_string(),
        output_text: request.output.trim().to_string(),
        frequencies,
    })
}

/// A zero in the right half-plane: its real part positive beyond round-off (a rate output's
/// zero at the origin comes out of the iteration within a few ulps of it).
fn right_half_plane(re: f64, largest: f64) -> bool {
    re > 1e-9 * largest.max(1.0)
}

fn at_speed(
    bike: &whipple::BenchmarkParameters,
    plan: &Plan,
    speed: f64,
) -> Result<AtSpeed, ApiError> {
    let system = LinearSystem::new(bike, speed, &plan.request)?;
    let g: TransferFunction = system.transfer_function(0, 0)?;
    let zero_response = g.numerator.is_empty();
    let zeros = g.zeros()?;
    let largest = zeros
        .iter()
        .fold(0.0f64, |m, z| m.max(whipple::math::norm(z)));
    let zeros = zeros
        .into_iter()
        .map(|z| Zero {
            // Adding 0.0 turns a negative zero into zero.
            re: z.re + 0.0,
            im: z.im + 0.0,
            right_half_plane: right_half_plane(z.re, largest),
        })
        .collect();
    let poles = g
        .poles()
        .into_iter()
        .map(|p| [p.re + 0.0, p.im + 0.0])
        .collect();
    let response = if zero_response {
        None
    } else {
        Some(g.frequency_response(&plan.frequencies)?)
    };
    let n = plan.frequencies.len();
    let (magnitude, magnitude_db, phase_deg) = match response {
        Some(r) => (
            r.magnitude,
            r.magnitude_db
                .into_iter()
                .map(|x| x.is_finite().then_some(x))
                .collect(),
            r.phase.into_iter().map(f64::to_degrees).collect(),
        ),
        None => (vec![0.0; n], vec![None; n], vec![0.0; n]),
    };
    Ok(AtSpeed {
        speed,
        poles,
        zeros,
        gain: g.gain(),
        static_gain: g.static_gain().filter(|x| x.is_finite()),
        zero_response,
        magnitude,
        magnitude_db,
        phase_deg,
    })
}

fn answer(
    name: Option<String>,
    bike: &whipple::BenchmarkParameters,
    plan: &Plan,
) -> Result<FrequencyResponseJson, ApiError> {
    let responses = plan
        .speeds
        .iter()
        .map(|&v| at_speed(bike, plan, v))
        .collect::<Result<Vec<_>, _>>()?;
    let coordinate = match plan.output {
        Output::State(s @ (StateVariable::Lean | StateVariable::Steer)) => Some(s),
        _ => None,
    };
    let origin_zero_speeds = match coordinate {
        Some(c) => Some(
            origin_zero_speeds(bike, &plan.input, c)?
                .into_iter()
                .filter(|r| r.value() > 0.0)
                .map(|r| {
                    let (lo, hi) = r.enclosure();
                    Crossing {
                        value: r.value(),
                        lo,
                        hi,
                    }
                })
                .collect(),
        ),
        None => None,
    };
    Ok(FrequencyResponseJson {
        name,
        input: Signal {
            name: plan.input_text.clone(),
            symbol: plan.input.symbol(),
            unit: plan.input.unit(),
        },
        output: Signal {
            name: plan.output_text.clone(),
            symbol: plan.output.symbol(),
            unit: plan.output.unit(),
        },
        frequencies: plan.frequencies.clone(),
        responses,
        origin_zero_speeds,
    })
}

pub(crate) fn frequency(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: FrequencyRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let plan = check(&request)?;
    // At most 16 speeds × 2,000 frequencies: milliseconds, asked for as the slider moves.
    Ok(Job::json(
        Budget::Interactive,
        "ask for fewer speeds or frequencies",
        move |_| {
            let benchmark = bike.benchmark()?;
            answer(bike.name.clone(), &benchmark, &plan)
        },
    ))
}
