//! `POST /api/linear/closed_loop` through the router (no socket): the bicycle under full-state
//! feedback, its gains, eigenvalues and certified critical speeds checked against the library
//! called directly (`ClosedLoop`, `LinearSystem::lqr`) and against the speed from which steer
//! into the fall stabilizes the benchmark; and its errors, each naming the field.

use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use nalgebra::DMatrix;
use serde_json::{Value, json};
use tower::ServiceExt;
use whipple::advanced::control::{ClosedLoop, Gains};
use whipple::advanced::io::{Format, write};
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use whipple::{BenchmarkParameters, presets};
use whipple_web::{Limits, app};

type TestResult = Result<(), Box<dyn std::error::Error>>;

async fn post(body: &Value) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let request = Request::builder()
        .method("POST")
        .uri("/api/linear/closed_loop")
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

fn steer_torque() -> SystemRequest {
    SystemRequest {
        states: vec![],
        inputs: vec![Input::SteerTorque],
        outputs: StateVariable::LEAN_STEER.map(Output::State).to_vec(),
    }
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

/// T_δ = 100 φ − 10 δ + 20 φ̇ (steer into the fall against a steer spring): the library's own
/// example says it stabilizes the benchmark from 0.8067 m/s; the route gives the same certified
/// speed, and the same tracked eigenvalues as the library's closed-loop sweep.
#[tokio::test]
async fn steer_into_the_fall_stabilizes_the_benchmark_from_0_8067() -> TestResult {
    let body = json!({
        "bike": benchmark()?,
        "gains": [[-100, 10, -20, 0]],
        "speeds": {"start": 0, "stop": 10, "step": 0.01},
    });
    let (status, answer) = post(&body).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["gains"]["kind"], "constant");
    assert_eq!(answer["inputs"], json!(["steer_torque"]));
    let ranges = answer["critical"]["stable_speed_ranges"]
        .as_array()
        .ok_or("no ranges")?;
    assert_eq!(ranges.len(), 1, "{ranges:?}");
    let range = numbers(&ranges[0]);
    assert!(
        (range[0] - 0.806_665_615_880_373_6).abs() < 1e-12,
        "{range:?}"
    );
    assert_eq!(range[1], 10.0);
    // The library called directly.
    let k = DMatrix::from_row_slice(1, 4, &[-100.0, 10.0, -20.0, 0.0]);
    let closed = ClosedLoop::new(
        &BenchmarkParameters::meijaard2007(),
        &steer_torque(),
        Gains::Constant(k),
    )?;
    let core = closed.critical_speeds(0.0, 10.0)?;
    assert_eq!(range[0], core.stable_speed_ranges[0].0);
    let speeds = numbers(&answer["speeds"]);
    assert_eq!(speeds.len(), 1001);
    let sweep = closed.eigen_sweep(&speeds)?;
    let columns = answer["eigenvalues"].as_array().ok_or("no eigenvalues")?;
    assert_eq!(columns.len(), 4);
    for (k, column) in columns.iter().enumerate() {
        assert_eq!(column["mode"], sweep.modes[k].name());
        let (re, im) = (numbers(&column["re"]), numbers(&column["im"]));
        for (i, row) in sweep.eigenvalues.iter().enumerate() {
            assert_eq!(
                (re[i], im[i]),
                (row[k].re, row[k].im),
                "column {k}, speed {i}"
            );
        }
    }
    // Above 0.8067 m/s every real part is negative, below it one is not.
    let largest = |i: usize| {
        columns
            .iter()
            .map(|c| numbers(&c["re"])[i])
            .fold(f64::NEG_INFINITY, f64::max)
    };
    assert!(largest(80) > 0.0 && largest(81) < 0.0);
    assert!(answer["critical_unavailable"].is_null());
    Ok(())
}

/// LQR at one design speed: K and the residual are the library's `LinearSystem::lqr` at that
/// speed, Q given as its diagonal or whole, R as a number or a 1 × 1 matrix.
#[tokio::test]
async fn an_lqr_gain_is_the_library_s_at_the_design_speed() -> TestResult {
    let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 5.0, &steer_torque())?;
    let core = system.lqr(&DMatrix::identity(4, 4), &DMatrix::identity(1, 1))?;
    for (q, r) in [
        (json!([1, 1, 1, 1]), json!(1)),
        (
            json!([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
            json!([[1]]),
        ),
    ] {
        let body = json!({
            "bike": benchmark()?,
            "lqr": {"q": q, "r": r, "speed": 5},
            "speeds": {"start": 0, "stop": 10, "step": 0.05},
        });
        let (status, answer) = post(&body).await?;
        assert_eq!(status, StatusCode::OK, "{answer}");
        assert_eq!(answer["gains"]["kind"], "lqr");
        assert_eq!(answer["gains"]["speed"], 5.0);
        let k = numbers(&answer["gains"]["k"][0]);
        let expected: Vec<f64> = core.gains.iter().copied().collect();
        assert_eq!(k, expected);
        assert_eq!(answer["gains"]["residual"].as_f64(), Some(core.residual));
        assert!(core.residual < 1e-12);
        // At the design speed the closed loop's eigenvalues are the LQR's.
        let speeds = numbers(&answer["speeds"]);
        let i = speeds
            .iter()
            .position(|v| (v - 5.0).abs() < 1e-12)
            .ok_or("5 m/s")?;
        let mut re: Vec<f64> = answer["eigenvalues"]
            .as_array()
            .ok_or("eigenvalues")?
            .iter()
            .map(|c| numbers(&c["re"])[i])
            .collect();
        let mut expected: Vec<f64> = core.closed_loop_eigenvalues.iter().map(|l| l.re).collect();
        re.sort_by(f64::total_cmp);
        expected.sort_by(f64::total_cmp);
        for (a, b) in re.iter().zip(&expected) {
            assert!(
                (a - b).abs() < 1e-9 * b.abs().max(1.0),
                "{re:?} vs {expected:?}"
            );
        }
        // The design at 5 m/s stabilizes the benchmark above its certified weave speed.
        let from = numbers(&answer["critical"]["stable_speed_ranges"][0])[0];
        assert!((from - 3.527_815_140_053_881).abs() < 1e-9, "{from}");
    }
    Ok(())
}

/// LQR scheduled at every speed of the sweep, Q = I, R = 1: the library's gain at each speed,
/// and a loop stable over the whole sweep from 0.1 m/s (certified). From 0 m/s round-off cannot
/// certify the first segment: the sweep is answered, the speeds are not, and it says why.
#[tokio::test]
async fn a_scheduled_lqr_is_stable_over_the_whole_sweep() -> TestResult {
    let body = json!({
        "bike": benchmark()?,
        "lqr": {"q": [1, 1, 1, 1], "r": 1, "scheduled": true},
        "speeds": {"start": 0.1, "stop": 10, "step": 0.1},
    });
    let (status, answer) = post(&body).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["gains"]["kind"], "scheduled");
    let schedule = answer["gains"]["schedule"].as_array().ok_or("schedule")?;
    assert_eq!(schedule.len(), 100);
    let at = &schedule[29];
    let v = at["speed"].as_f64().ok_or("speed")?;
    let core = LinearSystem::new(&BenchmarkParameters::meijaard2007(), v, &steer_torque())?
        .lqr(&DMatrix::identity(4, 4), &DMatrix::identity(1, 1))?;
    assert_eq!(
        numbers(&at["k"][0]),
        core.gains.iter().copied().collect::<Vec<_>>()
    );
    assert!(answer["gains"]["largest_residual"].as_f64() < Some(1e-10));
    let ranges = &answer["critical"]["stable_speed_ranges"];
    assert_eq!(ranges.as_array().map(Vec::len), Some(1), "{ranges}");
    let range = numbers(&ranges[0]);
    assert!((range[0] - 0.1).abs() < 1e-12 && (range[1] - 10.0).abs() < 1e-12);
    for c in answer["eigenvalues"].as_array().ok_or("eigenvalues")? {
        assert!(numbers(&c["re"]).iter().all(|re| *re < 0.0));
    }

    let from_zero = json!({
        "bike": benchmark()?,
        "lqr": {"q": [1, 1, 1, 1], "r": 1, "scheduled": true},
        "speeds": {"start": 0, "stop": 10, "step": 0.1},
    });
    let (status, answer) = post(&from_zero).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    if answer["critical"].is_null() {
        let why = answer["critical_unavailable"].as_str().ok_or("why")?;
        assert!(why.contains("certified"), "{why}");
    }
    for c in answer["eigenvalues"].as_array().ok_or("eigenvalues")? {
        assert!(numbers(&c["re"]).iter().all(|re| *re < 0.0));
    }
    Ok(())
}

/// Every bad request is 422 naming the field at fault.
#[tokio::test]
async fn bad_requests_name_the_field() -> TestResult {
    let bike = benchmark()?;
    let speeds = json!({"start": 0, "stop": 10, "step": 0.1});
    let cases = [
        (json!({"gains": [[-100, 10, -20]]}), "gains"),
        (
            json!({"gains": [[-100, 10, -20, 0], [1, 2, 3, 4]]}),
            "gains",
        ),
        (json!({"gains": [[-100, null, -20, 0]]}), "gains"),
        (json!({"gains": [[-100, "NaN", -20, 0]]}), "gains"),
        (json!({"gains": [[-100, 10], [-20, 0]]}), "gains"),
        (json!({}), "gains"),
        (
            json!({"gains": [-100, 10, -20, 0], "lqr": {"q": [1, 1, 1, 1], "r": 1, "speed": 5}}),
            "gains",
        ),
        (
            json!({"lqr": {"q": [[1, 2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], "r": 1, "speed": 5}}),
            "lqr.q",
        ),
        (
            json!({"lqr": {"q": [1, -1, 1, 1], "r": 1, "speed": 5}}),
            "lqr.q",
        ),
        (
            json!({"lqr": {"q": [1, 1, 1], "r": 1, "speed": 5}}),
            "lqr.q",
        ),
        (
            json!({"lqr": {"q": [1, 1, 1, 1], "r": 0, "speed": 5}}),
            "lqr.r",
        ),
        (
            json!({"lqr": {"q": [1, 1, 1, 1], "r": [[1, 0], [0, 0]], "speed": 5}, "inputs": ["steer_torque", "lean_torque"]}),
            "lqr.r",
        ),
        (json!({"lqr": {"q": [1, 1, 1, 1], "r": 1}}), "lqr"),
        (
            json!({"lqr": {"q": [1, 1, 1, 1], "r": 1, "speed": 5, "scheduled": true}}),
            "lqr",
        ),
        (
            json!({"gains": [-100, 10, -20, 0], "inputs": ["handlebar_twist"]}),
            "inputs",
        ),
        (json!({"gains": [-100, 10, -20, 0], "inputs": []}), "inputs"),
    ];
    for (fields, field) in cases {
        let mut body = json!({"bike": bike, "speeds": speeds});
        for (k, v) in fields.as_object().ok_or("object")? {
            body[k] = v.clone();
        }
        let (status, answer) = post(&body).await?;
        assert_eq!(
            status,
            StatusCode::UNPROCESSABLE_ENTITY,
            "{fields}: {answer}"
        );
        assert_eq!(answer["error"]["field"], field, "{fields}: {answer}");
        let message = answer["error"]["message"].as_str().unwrap_or("");
        assert!(!message.is_empty(), "{fields}: {answer}");
    }
    // The sweep's bounds: as /api/eigen's, and a schedule designed at each speed at most 10,000.
    let too_many = json!({
        "bike": bike,
        "gains": [-100, 10, -20, 0],
        "speeds": {"start": 0, "stop": 10, "step": 1e-6},
    });
    let (status, answer) = post(&too_many).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(answer["error"]["field"], "speeds");
    let schedule = json!({
        "bike": bike,
        "lqr": {"q": [1, 1, 1, 1], "r": 1, "scheduled": true},
        "speeds": {"start": 0, "stop": 10, "step": 1e-4},
    });
    let (status, answer) = post(&schedule).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(answer["error"]["field"], "speeds");
    assert_eq!(answer["error"]["kind"], "limit_exceeded");
    Ok(())
}
