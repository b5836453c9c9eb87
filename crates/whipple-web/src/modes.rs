//! `POST /api/modes` and `POST /api/linear/response`: the linear model's eigenmodes at one
//! speed (what `whipple modes` prints), and its free response from an initial state (the
//! prediction the page draws beside a simulation of the non-linear bicycle). Both only call
//! the library ([`mode_shapes`], [`StateSpace::free_response`]) and shape its answer as JSON.

use http::StatusCode;
use nalgebra::Vector4;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::Canonical;
use whipple::advanced::linear::StateSpace;
use whipple::advanced::modes::mode_shapes;

use crate::Limits;
use crate::error::ApiError;

/// The body of `POST /api/modes`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ModesRequest {
    /// The bicycle, in the parameter files' JSON layout.
    pub bike: Value,
    /// v: forward speed [m/s].
    pub speed: f64,
}

/// One mode: its name, eigenvalue [1/s] as [re, im] and eigenvector x = [φ, δ, φ̇, δ̇] as
/// [re, im] pairs (unit length, largest component real and positive).
#[derive(Serialize, Debug)]
pub struct ModeJson {
    mode: &'static str,
    eigenvalue: [f64; 2],
    eigenvector: [[f64; 2]; 4],
}

/// The answer of `POST /api/modes`.
#[derive(Serialize, Debug)]
pub struct ModesResponse {
    name: Option<String>,
    speed: f64,
    /// The eigenvector's components, in order.
    state: [&'static str; 4],
    /// Sorted by decreasing real part of the eigenvalue.
    modes: Vec<ModeJson>,
}

fn invalid(field: &str, rule: String) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "invalid_argument",
        format!("invalid `{field}`: {rule}"),
    )
    .at(field, rule)
}

fn finite(field: &str, x: f64) -> Result<f64, ApiError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(invalid(field, format!("must be a finite number, got {x}")))
    }
}

/// Checks the speed before any work.
pub fn check_modes(request: &ModesRequest) -> Result<f64, ApiError> {
    finite("speed", request.speed)
}

/// The modes of `canonical` at `speed`.
pub fn modes(
    name: Option<String>,
    canonical: &Canonical,
    speed: f64,
) -> Result<ModesResponse, ApiError> {
    let shapes = mode_shapes(canonical, speed)?;
    let modes = shapes
        .iter()
        .map(|s| ModeJson {
            mode: s.mode.name(),
            eigenvalue: [s.pair.value.re, s.pair.value.im],
            // Adding 0.0 turns a negative zero into zero.
            eigenvector: s.pair.vector.map(|z| [z.re + 0.0, z.im + 0.0]).into(),
        })
        .collect::<Vec<_>>();
    if modes.iter().any(|m| {
        !m.eigenvalue
            .iter()
            .chain(m.eigenvector.iter().flatten())
            .all(|x| x.is_finite())
    }) {
        return Err(ApiError::from(whipple::Error::NonFinite {
            context: format!("the eigenmodes at {speed} m/s"),
        }));
    }
    Ok(ModesResponse {
        name,
        speed,
        state: ["lean", "steer", "lean_rate", "steer_rate"],
        modes,
    })
}

/// The body of `POST /api/linear/response`: the simulation's initial numbers, in its units
/// (degrees for the angles, radians per second for the rates).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ResponseRequest {
    /// The bicycle, in the parameter files' JSON layout.
    pub bike: Value,
    /// v: forward speed [m/s].
    pub speed: f64,
    /// φ₀ \[deg\] (default 0).
    #[serde(default)]
    pub lean_deg: f64,
    /// δ₀ \[deg\] (default 0).
    #[serde(default)]
    pub steer_deg: f64,
    /// φ̇₀ [rad/s] (default 0).
    #[serde(default)]
    pub lean_rate: f64,
    /// δ̇₀ [rad/s] (default 0).
    #[serde(default)]
    pub steer_rate: f64,
    /// Time span \[s\], positive and at most the server's simulation limit.
    pub duration: f64,
    /// Sample interval \[s\] (default 1/60 s, the simulation's frame interval).
    pub dt: Option<f64>,
}

/// A checked response request.
#[derive(Debug, Clone, Copy)]
pub struct ResponsePlan {
    speed: f64,
    x0: Vector4<f64>,
    dt: f64,
    steps: usize,
}

/// The answer of `POST /api/linear/response`: angles \[rad\] and rates [rad/s] at times `t` \[s\].
#[derive(Serialize, Debug)]
pub struct ResponseJson {
    name: Option<String>,
    speed: f64,
    t: Vec<f64>,
    lean: Vec<f64>,
    steer: Vec<f64>,
    lean_rate: Vec<f64>,
    steer_rate: Vec<f64>,
}

/// Checks a response request against the rules and the limits, before any work.
pub fn check_response(
    request: &ResponseRequest,
    limits: &Limits,
) -> Result<ResponsePlan, ApiError> {
    let speed = finite("speed", request.speed)?;
    let lean = finite("lean_deg", request.lean_deg)?;
    let steer = finite("steer_deg", request.steer_deg)?;
    let lean_rate = finite("lean_rate", request.lean_rate)?;
    let steer_rate = finite("steer_rate", request.steer_rate)?;
    let duration = finite("duration", request.duration)?;
    if duration <= 0.0 {
        return Err(invalid(
            "duration",
            format!("must be positive, got {duration} s"),
        ));
    }
    if duration > limits.max_sim_duration {
        let max = limits.max_sim_duration;
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "limit_exceeded",
            format!("a response of {duration} s is longer than this server's limit of {max} s per request"),
        )
        .at("duration", format!("at most {max} s per request")));
    }
    let dt = finite(
        "dt",
        request.dt.unwrap_or(1.0 / crate::simulation::FRAME_RATE),
    )?;
    if dt <= 0.0 {
        return Err(invalid("dt", format!("must be positive, got {dt} s")));
    }
    let count = (duration / dt).ceil();
    if count > limits.max_sim_steps as f64 {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "limit_exceeded",
            format!(
                "{duration} s at dt = {dt} s is {count} samples, more than this server's limit of {}; use a larger dt",
                limits.max_sim_steps
            ),
        )
        .at("dt", format!("at most {} samples", limits.max_sim_steps)));
    }
    // The last sample falls on `duration` exactly.
    let steps = (count as usize).max(1);
    Ok(ResponsePlan {
        speed,
        x0: Vector4::new(lean.to_radians(), steer.to_radians(), lean_rate, steer_rate),
        dt: duration / steps as f64,
        steps,
    })
}

/// The free response planned.
pub fn response(
    name: Option<String>,
    canonical: &Canonical,
    plan: ResponsePlan,
) -> Result<ResponseJson, ApiError> {
    let ss = StateSpace::new(canonical, plan.speed)?;
    let states = ss.free_response(&plan.x0, plan.dt, plan.steps)?;
    let column = |k: usize| states.iter().map(|x| x[k]).collect::<Vec<f64>>();
    Ok(ResponseJson {
        name,
        speed: plan.speed,
        t: (0..states.len()).map(|k| k as f64 * plan.dt).collect(),
        lean: column(0),
        steer: column(1),
        lean_rate: column(2),
        steer_rate: column(3),
    })
}

#[cfg(test)]
mod tests {
    use axum::body::Body;
    use axum::http::{Request, StatusCode};
    use http_body_util::BodyExt;
    use serde_json::{Value, json};
    use tower::ServiceExt;

    use crate::{Limits, app};

    async fn post(
        path: &str,
        body: Value,
    ) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
        let request = Request::builder()
            .method("POST")
            .uri(path)
            .header("content-type", "application/json")
            .body(Body::from(body.to_string()))?;
        let response = app(Limits::default()).oneshot(request).await?;
        let status = response.status();
        let bytes = response.into_body().collect().await?.to_bytes();
        Ok((status, serde_json::from_slice(&bytes)?))
    }

    async fn benchmark() -> Result<Value, Box<dyn std::error::Error>> {
        let request = Request::builder()
            .uri("/api/presets/benchmark")
            .body(Body::empty())?;
        let response = app(Limits::default()).oneshot(request).await?;
        let bytes = response.into_body().collect().await?.to_bytes();
        Ok(serde_json::from_slice(&bytes)?)
    }

    /// Meijaard et al. 2007, Table 2: at 5 m/s the weave is −0.775341882195 ± 4.46486771378823i
    /// and the capsize eigenvalue −0.322866429004; each eigenvector satisfies x = [q; λq].
    #[tokio::test]
    async fn modes_of_the_benchmark_at_5_m_s() -> Result<(), Box<dyn std::error::Error>> {
        let (status, body) = post(
            "/api/modes",
            json!({"bike": benchmark().await?, "speed": 5.0}),
        )
        .await?;
        assert_eq!(status, StatusCode::OK, "{body}");
        let modes = body["modes"].as_array().ok_or("no modes")?;
        assert_eq!(modes.len(), 4);
        let weave: Vec<&Value> = modes.iter().filter(|m| m["mode"] == "weave").collect();
        assert_eq!(weave.len(), 2);
        for m in &weave {
            let re = m["eigenvalue"][0].as_f64().ok_or("re")?;
            let im = m["eigenvalue"][1].as_f64().ok_or("im")?;
            assert!((re + 0.775341882195).abs() < 1e-10, "{re}");
            assert!((im.abs() - 4.46486771378823).abs() < 1e-10, "{im}");
        }
        let capsize = modes
            .iter()
            .find(|m| m["mode"] == "capsize")
            .ok_or("no capsize")?;
        let lambda = capsize["eigenvalue"][0].as_f64().ok_or("re")?;
        assert!((lambda + 0.322866429004).abs() < 1e-10, "{lambda}");
        for m in modes {
            let l = (
                m["eigenvalue"][0].as_f64().ok_or("re")?,
                m["eigenvalue"][1].as_f64().ok_or("im")?,
            );
            let x = |k: usize, p: usize| m["eigenvector"][k][p].as_f64().unwrap_or(f64::NAN);
            for (q, rate) in [(0, 2), (1, 3)] {
                let (qr, qi) = (x(q, 0), x(q, 1));
                let expected = (l.0 * qr - l.1 * qi, l.0 * qi + l.1 * qr);
                assert!(
                    (x(rate, 0) - expected.0).abs() < 1e-12
                        && (x(rate, 1) - expected.1).abs() < 1e-12
                );
            }
        }
        let (status, body) = post(
            "/api/modes",
            json!({"bike": benchmark().await?, "speed": "fast"}),
        )
        .await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
        Ok(())
    }

    /// The linear response from the simulation's initial numbers: starts where asked, ends at
    /// `duration`, decays at 4.6 m/s (self-stable); limits and bad numbers are 422 with the field.
    #[tokio::test]
    async fn linear_response_and_its_limits() -> Result<(), Box<dyn std::error::Error>> {
        let bike = benchmark().await?;
        let (status, body) = post(
            "/api/linear/response",
            json!({"bike": bike, "speed": 4.6, "lean_deg": 2.0, "lean_rate": 0.5, "duration": 10.0, "dt": 0.01}),
        )
        .await?;
        assert_eq!(status, StatusCode::OK, "{body}");
        let t = body["t"].as_array().ok_or("t")?;
        assert_eq!(t.len(), 1001);
        assert!((t[1000].as_f64().unwrap_or(0.0) - 10.0).abs() < 1e-12);
        assert!((body["lean"][0].as_f64().unwrap_or(0.0) - 2f64.to_radians()).abs() < 1e-15);
        assert_eq!(body["lean_rate"][0].as_f64(), Some(0.5));
        // The weave has died out; the slow capsize mode (−0.15/s at 4.6 m/s) is decaying.
        let end = body["lean"][1000].as_f64().unwrap_or(1.0).abs();
        assert!(end < 0.1 * 2f64.to_radians(), "{end}");
        for (request, field) in [
            (
                json!({"bike": bike, "speed": 4.6, "duration": 31.0}),
                "duration",
            ),
            (
                json!({"bike": bike, "speed": 4.6, "duration": 0.0}),
                "duration",
            ),
            (
                json!({"bike": bike, "speed": 4.6, "duration": 10.0, "dt": 1e-5}),
                "dt",
            ),
            (
                json!({"bike": bike, "speed": 4.6, "duration": 1.0, "dt": -1.0}),
                "dt",
            ),
        ] {
            let (status, body) = post("/api/linear/response", request).await?;
            assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
            assert_eq!(body["error"]["field"], field, "{body}");
        }
        Ok(())
    }
}
