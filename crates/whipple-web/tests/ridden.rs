//! `POST /api/ridden` through the router (no socket): the lane change and the handling
//! quality metric's peaks are the library's, and bad requests are refused naming the field.

use std::sync::atomic::AtomicBool;

use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whipple::advanced::control::{
    CrossoverRules, HumanController, LaneChange, LaneKind, Neuromuscular, OptimalHandlingSettings,
    Task, hess_gains, judge_handling, lane_change_linear,
};
use whipple::advanced::io::{Format, write};
use whipple::presets;
use whipple_web::{Limits, app};

type TestResult = Result<(), Box<dyn std::error::Error>>;

async fn post(body: &Value) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let request = Request::builder()
        .method("POST")
        .uri("/api/ridden")
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

#[tokio::test]
async fn the_lane_change_and_the_peaks_are_the_librarys() -> TestResult {
    let body = json!({
        "bike": benchmark()?, "speed": 5.0, "lane": "double",
        "speeds": {"start": 1.0, "stop": 6.0, "step": 1.0},
    });
    let (status, answer) = post(&body).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let bike = presets::find("benchmark")?.bicycle();
    let b = bike.benchmark()?;
    let nm = Neuromuscular::default();
    let gains = hess_gains(&b, 5.0, &nm, &CrossoverRules::default())?;
    assert_eq!(answer["gains"][0].as_f64(), Some(gains.k_delta));
    let rider = HumanController::new(Task::Lateral, gains, nm)?;
    let run = lane_change_linear(&b, 5.0, &rider, &LaneChange::humancontrol(LaneKind::Double))?;
    let y = answer["linear"]["front_y"].as_array().ok_or("front_y")?;
    assert_eq!(y.len(), run.front_y.len());
    assert_eq!(y[250].as_f64(), Some(run.front_y[250]));
    // The non-linear run follows the linear one within centimetres at 2 m.
    let ny = answer["nonlinear"]["front_y"]
        .as_array()
        .ok_or("non-linear")?;
    let worst = ny
        .iter()
        .zip(y)
        .map(|(a, b)| (a.as_f64().unwrap_or(f64::NAN) - b.as_f64().unwrap_or(f64::NAN)).abs())
        .fold(0.0_f64, f64::max);
    assert!(worst < 0.01, "{worst}");
    let rows = answer["hqm"].as_array().ok_or("hqm")?;
    assert_eq!(rows.len(), 6);
    for row in rows {
        let v = row["speed"].as_f64().ok_or("speed")?;
        let judged = judge_handling(&bike, &[], &[], &OptimalHandlingSettings::at(v));
        if judged.stable {
            assert_eq!(row["peak"].as_f64(), judged.peak.map(|p| p.magnitude));
        } else {
            assert!(row["peak"].is_null() && row["reason"].is_string(), "{row}");
        }
    }
    let _ = AtomicBool::new(false);
    Ok(())
}

#[tokio::test]
async fn bad_requests_are_refused_naming_the_field() -> TestResult {
    let bike = benchmark()?;
    for (body, field) in [
        (
            json!({"bike": bike, "speed": 0.5, "speeds": {"start": 1, "stop": 2, "step": 1}}),
            "speed",
        ),
        (
            json!({"bike": bike, "speed": 5, "lane": "triple", "speeds": {"start": 1, "stop": 2, "step": 1}}),
            "lane",
        ),
        (
            json!({"bike": bike, "speed": 5, "speeds": {"start": 0, "stop": 1000, "step": 0.01}}),
            "speeds",
        ),
    ] {
        let (status, answer) = post(&body).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
        assert!(answer.to_string().contains(field), "{field}: {answer}");
    }
    Ok(())
}
