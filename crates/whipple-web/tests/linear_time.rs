//! `POST /api/linear/time` through the router (no socket): the linear time responses checked
//! against the frequency route's static gain (the step settles at G(0)), against the identity
//! impulse = derivative of the step, against the initial state asked for, and the non-linear
//! comparison against the amplitude scaling of its difference (odd quantities: O(a³)); and its
//! errors and limits.

use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whipple::advanced::io::{Format, write};
use whipple::presets;
use whipple_web::{Limits, app};

type TestResult = Result<(), Box<dyn std::error::Error>>;

async fn post(uri: &str, body: &Value) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let request = Request::builder()
        .method("POST")
        .uri(uri)
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

#[tokio::test]
async fn step_response_settles_at_the_frequency_routes_static_gain() -> TestResult {
    let bike = benchmark()?;
    for output in ["lean", "steer"] {
        let (status, g) = post(
            "/api/linear/frequency",
            &json!({"bike": bike, "speeds": [5.0], "input": "steer_torque", "output": output,
                    "frequencies": {"start": 1.0, "stop": 1.0, "count": 1}}),
        )
        .await?;
        assert_eq!(status, StatusCode::OK, "{g}");
        let g0 = g["responses"][0]["static_gain"]
            .as_f64()
            .ok_or("no static gain")?
            .to_degrees();
        let (status, r) = post(
            "/api/linear/time",
            &json!({"bike": bike, "speed": 5.0, "kind": "step", "input": "steer_torque",
                    "amplitude": 1.0, "duration": 10.0, "samples": 201}),
        )
        .await?;
        assert_eq!(status, StatusCode::OK, "{r}");
        let y = numbers(&r["linear"][format!("{output}_deg")]);
        assert_eq!(y.len(), 201);
        assert_eq!(y[0], 0.0);
        // The slowest mode at 5 m/s is the capsize, λ = −0.322 1/s (Meijaard 2007, Table 2):
        // after 10 s the step is within e^(−3.2) of its final value, and the distance to G(0)
        // shrinks by e^(−0.322·5) ≈ 0.2 from 5 s to 10 s.
        let (half, end) = (y[100] - g0, y[200] - g0);
        assert!(
            end.abs() < 0.06 * g0.abs(),
            "{output}: {} vs G(0) {g0}",
            y[200]
        );
        let ratio = end / half;
        assert!((0.15..0.25).contains(&ratio), "{output}: ratio {ratio}");
    }
    Ok(())
}

#[tokio::test]
async fn impulse_is_the_derivative_of_the_step() -> TestResult {
    let bike = benchmark()?;
    let ask = |kind: &str| {
        json!({"bike": bike, "speed": 4.0, "kind": kind, "input": "lean_torque",
               "amplitude": 2.0, "duration": 1.999, "samples": 2000})
    };
    let (status, step) = post("/api/linear/time", &ask("step")).await?;
    assert_eq!(status, StatusCode::OK, "{step}");
    let (status, impulse) = post("/api/linear/time", &ask("impulse")).await?;
    assert_eq!(status, StatusCode::OK, "{impulse}");
    let t = numbers(&step["times"]);
    let s = numbers(&step["linear"]["lean_deg"]);
    let i = numbers(&impulse["linear"]["lean_deg"]);
    let largest = i.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(largest > 0.1, "{largest}");
    for k in (100..1999).step_by(100) {
        let slope = (s[k + 1] - s[k - 1]) / (t[k + 1] - t[k - 1]);
        assert!(
            (slope - i[k]).abs() < 1e-3 * largest,
            "t = {}: {slope} vs {}",
            t[k],
            i[k]
        );
    }
    Ok(())
}

#[tokio::test]
async fn initial_condition_starts_there_and_the_path_runs_at_the_speed() -> TestResult {
    let bike = benchmark()?;
    let (status, r) = post(
        "/api/linear/time",
        &json!({"bike": bike, "speed": 5.0, "kind": "initial", "lean_deg": 2.0, "steer_deg": -1.0,
                "duration": 4.0, "samples": 41}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{r}");
    let lean = numbers(&r["linear"]["lean_deg"]);
    let steer = numbers(&r["linear"]["steer_deg"]);
    assert!((lean[0] - 2.0).abs() < 1e-12 && (steer[0] + 1.0).abs() < 1e-12);
    // Self-stable at 5 m/s: it dies away (slowly: the capsize's λ = −0.322 1/s).
    assert!(lean[40].abs() < 0.6 * lean[0], "{}", lean[40]);
    let x = numbers(&r["linear"]["rear_x"]);
    assert!((x[40] - 20.0).abs() < 1e-9, "{}", x[40]);
    assert_eq!(numbers(&r["linear"]["front_y"]).len(), 41);
    assert!(r["nonlinear"].is_null());
    Ok(())
}

async fn pulse_difference(amplitude: f64) -> Result<(Value, f64), Box<dyn std::error::Error>> {
    let (status, r) = post(
        "/api/linear/time",
        &json!({"bike": benchmark()?, "speed": 5.0, "kind": "pulse", "input": "steer_torque",
                "amplitude": amplitude, "pulse_duration": 0.5, "duration": 3.0, "samples": 31,
                "nonlinear": true}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{r}");
    let d = r["nonlinear"]["largest_difference"]["lean_deg"]
        .as_f64()
        .ok_or("no difference")?;
    Ok((r, d))
}

#[tokio::test]
async fn pulse_manoeuvres_difference_shrinks_by_eight_when_the_amplitude_halves() -> TestResult {
    let (r, full) = pulse_difference(0.1).await?;
    let (_, half) = pulse_difference(0.05).await?;
    let ratio = full / half;
    assert!((7.5..8.5).contains(&ratio), "ratio {ratio}");
    // The difference is the non-linear motion less the linear one, sample by sample.
    let lin = numbers(&r["linear"]["lean_deg"]);
    let non = numbers(&r["nonlinear"]["motion"]["lean_deg"]);
    let diff = numbers(&r["nonlinear"]["difference"]["lean_deg"]);
    for k in 0..lin.len() {
        assert!((non[k] - lin[k] - diff[k]).abs() < 1e-9, "sample {k}");
    }
    assert_eq!(numbers(&r["nonlinear"]["motion"]["rear_y"]).len(), 31);
    Ok(())
}

#[tokio::test]
async fn initial_condition_compares_with_the_nonlinear_model() -> TestResult {
    let (status, r) = post(
        "/api/linear/time",
        &json!({"bike": benchmark()?, "speed": 5.0, "kind": "initial", "lean_deg": 3.0,
                "duration": 3.0, "samples": 31, "nonlinear": true}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{r}");
    let non = numbers(&r["nonlinear"]["motion"]["lean_deg"]);
    assert!((non[0] - 3.0).abs() < 1e-9, "{}", non[0]);
    let d = r["nonlinear"]["largest_difference"]["lean_deg"]
        .as_f64()
        .ok_or("no difference")?;
    // 3° is small: the models agree to well under a tenth of it.
    assert!(d > 0.0 && d < 0.3, "{d}");
    Ok(())
}

#[tokio::test]
async fn errors_name_the_field() -> TestResult {
    let bike = benchmark()?;
    let base = json!({"bike": bike, "speed": 5.0, "kind": "pulse", "input": "steer_torque",
                      "amplitude": 1.0, "duration": 3.0, "samples": 31});
    let cases: [(&str, Value, &str, &str); 6] = [
        ("duration", json!(10.5), "duration", "limit_exceeded"),
        ("duration", json!(0.0), "duration", "invalid_argument"),
        ("samples", json!(2001), "samples", "limit_exceeded"),
        ("samples", json!(1), "samples", "invalid_argument"),
        (
            "pulse_duration",
            json!(0.0),
            "pulse_duration",
            "invalid_argument",
        ),
        ("input", json!("wind"), "input", "invalid_argument"),
    ];
    for (key, value, field, kind) in cases {
        let mut body = base.clone();
        body[key] = value;
        let (status, answer) = post("/api/linear/time", &body).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{key}: {answer}");
        assert_eq!(answer["error"]["field"], field, "{answer}");
        assert_eq!(answer["error"]["kind"], kind, "{answer}");
    }
    let mut body = base.clone();
    body["input"] = json!("lateral_force:0.5,-1");
    body["nonlinear"] = json!(true);
    let (status, answer) = post("/api/linear/time", &body).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(answer["error"]["field"], "input", "{answer}");
    // Without the comparison a lateral force is fine.
    body["nonlinear"] = json!(false);
    let (status, answer) = post("/api/linear/time", &body).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    // An initial condition applies no input: the lateral force named does not matter.
    body["kind"] = json!("initial");
    body["lean_deg"] = json!(2.0);
    body["nonlinear"] = json!(true);
    let (status, answer) = post("/api/linear/time", &body).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let mut body = base;
    body["kind"] = json!("impulse");
    body["nonlinear"] = json!(true);
    let (status, answer) = post("/api/linear/time", &body).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(answer["error"]["field"], "kind", "{answer}");
    Ok(())
}
