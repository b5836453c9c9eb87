//! `POST /api/linear/frequency` through the router (no socket): the transfer function of one
//! input–output pair at a few speeds, checked against an independent state-space evaluation
//! of the published matrices, against Table 2's eigenvalues and against the counter-steering
//! zero's crossing speed; and its errors and limits.

use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use nalgebra::{Complex, Matrix2, Matrix4, Vector4};
use serde_json::{Value, json};
use tower::ServiceExt;
use whipple::advanced::io::{Format, write};
use whipple::presets;
use whipple_reference::meijaard2007 as published;
use whipple_web::{Limits, app};

type TestResult = Result<(), Box<dyn std::error::Error>>;

async fn post(body: &Value) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let request = Request::builder()
        .method("POST")
        .uri("/api/linear/frequency")
        .header(header::CONTENT_TYPE, "application/json")
        .body(Body::from(body.to_string()))?;
    let response = app(Limits::default()).oneshot(request).await?;
    let status = response.status();
    let bytes = response.into_body().collect().await?.to_bytes();
    Ok((status, serde_json::from_slice(&bytes)?))
}

fn benchmark() -> Result<Value, Box<dyn std::error::Error>> {
    let text = write(&presets::find("benchmark")?.bicycle(), Format::Json)?;
    Ok(serde_json::from_str(&text)?)
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

/// g [m/s²] of the benchmark bicycle (Table 1), by which K₀ is multiplied.
const G: f64 = 9.81;

fn matrix(rows: [[f64; 2]; 2]) -> Matrix2<f64> {
    Matrix2::new(rows[0][0], rows[0][1], rows[1][0], rows[1][1])
}

/// G(iω) of steer torque → lean from the published M, C₁, K₀, K₂ (§5; K = g K₀ + v² K₂) by another route than
/// the library's: the state-space form ẋ = A x + B T_δ and (iω I − A)⁻¹ B solved by LU.
fn steer_torque_to_lean(v: f64, omega: f64) -> Option<Complex<f64>> {
    let m_inv = matrix(published::M).try_inverse()?;
    let k = G * matrix(published::K0) + v * v * matrix(published::K2);
    let c = v * matrix(published::C1);
    let mut a = Matrix4::<f64>::zeros();
    a.fixed_view_mut::<2, 2>(0, 2).fill_with_identity();
    a.fixed_view_mut::<2, 2>(2, 0).copy_from(&(-m_inv * k));
    a.fixed_view_mut::<2, 2>(2, 2).copy_from(&(-m_inv * c));
    let b = Vector4::new(0.0, 0.0, m_inv[(0, 1)], m_inv[(1, 1)]);
    let system = Matrix4::<Complex<f64>>::identity() * Complex::new(0.0, omega)
        - a.map(|x| Complex::new(x, 0.0));
    let x = system.lu().solve(&b.map(|x| Complex::new(x, 0.0)))?;
    Some(x[0])
}

/// The Bode data of steer torque → lean at 3, 5 and 7 m/s equal the state-space evaluation of
/// the published matrices (magnitude to 1e-9 relative, phase to 1e-7 rad modulo 2π); dB is
/// 20 log₁₀ of the magnitude; the phase is unwrapped (no step of 180° or more); the poles at
/// 5 m/s are Table 2's eigenvalues; the static gain equals the state-space −C A⁻¹ B.
#[tokio::test]
async fn steer_torque_to_lean_matches_the_published_matrices() -> TestResult {
    let (status, body) = post(&json!({
        "bike": benchmark()?, "speeds": [3.0, 5.0, 7.0], "input": "steer_torque",
        "output": "lean", "frequencies": {"start": 0.1, "stop": 100.0, "count": 61}
    }))
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["input"]["symbol"], "T_δ", "{}", body["input"]);
    assert_eq!(body["output"]["name"], "lean");
    let omegas = numbers(&body["frequencies"]);
    assert_eq!(omegas.len(), 61);
    assert_eq!((omegas[0], omegas[60]), (0.1, 100.0));
    let responses = body["responses"].as_array().ok_or("responses")?;
    assert_eq!(responses.len(), 3);
    for r in responses {
        let v = r["speed"].as_f64().ok_or("speed")?;
        let magnitude = numbers(&r["magnitude"]);
        let db = numbers(&r["magnitude_db"]);
        let phase = numbers(&r["phase_deg"]);
        for (k, &omega) in omegas.iter().enumerate() {
            let g = steer_torque_to_lean(v, omega).ok_or("singular")?;
            let relative = (magnitude[k] - whipple::math::norm(g)).abs() / whipple::math::norm(g);
            assert!(
                relative < 1e-9,
                "v {v} ω {omega}: {} vs {}",
                magnitude[k],
                whipple::math::norm(g)
            );
            assert!((db[k] - 20.0 * whipple::math::log10(magnitude[k])).abs() < 1e-12);
            let turns = (phase[k].to_radians() - whipple::math::arg(g)) / std::f64::consts::TAU;
            assert!(
                (turns - turns.round()).abs() * std::f64::consts::TAU < 1e-7,
                "v {v} ω {omega}: phase {} vs {}",
                phase[k],
                whipple::math::arg(g).to_degrees()
            );
            if k > 0 {
                assert!((phase[k] - phase[k - 1]).abs() < 180.0, "unwrapped");
            }
        }
        let static_gain = r["static_gain"].as_f64().ok_or("static gain")?;
        let g0 = steer_torque_to_lean(v, 0.0).ok_or("singular at 0")?;
        assert!(
            (static_gain - g0.re).abs() < 1e-9 * g0.re.abs(),
            "{static_gain} {g0}"
        );
        assert_eq!(r["poles"].as_array().map(Vec::len), Some(4));
        assert_eq!(r["zeros"].as_array().map(Vec::len), Some(2));
    }
    // Meijaard et al. 2007, Table 2 at 5 m/s: weave −0.775341882195 ± 4.46486771378823i,
    // capsize −0.322866429004, castering −14.0783896927982.
    let row = published::EIGENVALUES
        .iter()
        .find(|r| r.0 == 5.0)
        .ok_or("row")?;
    let poles: Vec<(f64, f64)> = responses[1]["poles"]
        .as_array()
        .ok_or("poles")?
        .iter()
        .map(|p| {
            (
                p[0].as_f64().unwrap_or(f64::NAN),
                p[1].as_f64().unwrap_or(f64::NAN),
            )
        })
        .collect();
    for expected in [(row.1, row.2), (row.1, -row.2), (row.3, 0.0), (row.4, 0.0)] {
        assert!(
            poles
                .iter()
                .any(|p| (p.0 - expected.0).abs() < 1e-9 && (p.1 - expected.1).abs() < 1e-9),
            "{expected:?} not among {poles:?}"
        );
    }
    Ok(())
}

/// The counter-steering zero: steer torque → lean has a zero in the right half-plane below
/// v = √(−g K₀₁₂ / K₂₁₂) (0.577 m/s for the benchmark, from the published K₀ and K₂) and
/// none above; the answer gives that speed, and the zeros flagged agree with it.
#[tokio::test]
async fn the_right_half_plane_zero_is_flagged_below_its_crossing_speed() -> TestResult {
    let (status, body) = post(&json!({
        "bike": benchmark()?, "speeds": [0.3, 0.5, 0.65, 3.0, 5.0], "input": "steer_torque",
        "output": "lean", "frequencies": {"start": 1.0, "stop": 10.0, "count": 3}
    }))
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    let crossing = (-G * published::K0[0][1] / published::K2[0][1]).sqrt();
    let speeds = body["origin_zero_speeds"].as_array().ok_or("crossings")?;
    assert_eq!(speeds.len(), 1, "{speeds:?}");
    let value = speeds[0]["value"].as_f64().ok_or("value")?;
    assert!((value - crossing).abs() < 1e-9, "{value} vs {crossing}");
    assert!(speeds[0]["lo"].as_f64() <= Some(value) && speeds[0]["hi"].as_f64() >= Some(value));
    for r in body["responses"].as_array().ok_or("responses")? {
        let v = r["speed"].as_f64().ok_or("speed")?;
        let zeros = r["zeros"].as_array().ok_or("zeros")?;
        let flagged = zeros
            .iter()
            .filter(|z| z["right_half_plane"] == true)
            .count();
        let positive = zeros
            .iter()
            .filter(|z| z["re"].as_f64().is_some_and(|re| re > 0.0))
            .count();
        assert_eq!(flagged, positive, "v {v}: {zeros:?}");
        assert_eq!(flagged, usize::from(v < crossing), "v {v}: {zeros:?}");
    }
    // Another output has no such speed; yaw rate's static gain is finite, the front contact's
    // lateral position has two integrators (poles at 0) and no static gain.
    let (status, body) = post(&json!({
        "bike": benchmark()?, "speeds": [5.0], "input": "steer_torque",
        "output": "front_contact_y", "frequencies": {"start": 0.1, "stop": 10.0, "count": 5}
    }))
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert!(body["origin_zero_speeds"].is_null());
    let r = &body["responses"][0];
    assert_eq!(r["poles"].as_array().map(Vec::len), Some(6));
    assert!(r["static_gain"].is_null());
    let db = numbers(&r["magnitude_db"]);
    assert!(db[0] > db[4], "an integrator's roll-off: {db:?}");
    Ok(())
}

/// Bad signals, speeds and grids are 422 naming the field; the limits are 16 speeds and 2,000
/// frequencies; a bicycle the library refuses names its parameter; an output the input does
/// not reach answers G ≡ 0 with no dB values.
#[tokio::test]
async fn bad_requests_name_their_field() -> TestResult {
    let bike = benchmark()?;
    let base = json!({
        "bike": bike, "speeds": [5.0], "input": "steer_torque", "output": "lean",
        "frequencies": {"start": 0.1, "stop": 100.0, "count": 10}
    });
    let with = |key: &str, value: Value| {
        let mut b = base.clone();
        b[key] = value;
        b
    };
    for (body, field, kind) in [
        (with("input", json!("steer")), "input", "invalid_argument"),
        (
            with("input", json!("lateral_force")),
            "input",
            "invalid_argument",
        ),
        (
            with("output", json!("heading")),
            "output",
            "invalid_argument",
        ),
        (with("speeds", json!([])), "speeds", "invalid_argument"),
        (
            with("speeds", json!(vec![5.0; 17])),
            "speeds",
            "limit_exceeded",
        ),
        (
            with(
                "frequencies",
                json!({"start": 0.0, "stop": 10.0, "count": 5}),
            ),
            "frequencies",
            "invalid_argument",
        ),
        (
            with(
                "frequencies",
                json!({"start": 10.0, "stop": 1.0, "count": 5}),
            ),
            "frequencies",
            "invalid_argument",
        ),
        (
            with(
                "frequencies",
                json!({"start": 0.1, "stop": 10.0, "count": 2001}),
            ),
            "frequencies",
            "limit_exceeded",
        ),
        (
            with(
                "frequencies",
                json!({"start": 0.1, "stop": 10.0, "count": 0}),
            ),
            "frequencies",
            "limit_exceeded",
        ),
    ] {
        let (status, answer) = post(&body).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
        assert_eq!(answer["error"]["field"], field, "{answer}");
        assert_eq!(answer["error"]["kind"], kind, "{answer}");
    }
    let mut bad_bike = base.clone();
    bad_bike["bike"]["benchmark"]["mB"] = json!(-1.0);
    let (status, answer) = post(&bad_bike).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(answer["error"]["field"], "mB", "{answer}");
    let (status, answer) = post(&with("speeds", json!(["fast"]))).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    // x_P does not respond to a torque to first order.
    let (status, answer) = post(&with("output", json!("rear_contact_x"))).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let r = &answer["responses"][0];
    assert_eq!(r["zero_response"], true);
    assert!(
        r["magnitude_db"]
            .as_array()
            .is_some_and(|a| a.iter().all(Value::is_null))
    );
    Ok(())
}
