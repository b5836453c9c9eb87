//! `POST /api/measure` and `GET /api/measure/samples` through the router (no socket): the
//! Browser sample's parameters, σ and steps equal the library's pipeline called directly, the
//! JSON form equals the text form, and bad measurements are refused naming the key as written.

use axum::body::Body;
use axum::http::{Method, Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Map, Value, json};
use tower::ServiceExt;
use whipple::advanced::measured::{MeasuredParameters, read_measurements};
use whipple::advanced::table::{Form, parameters};
use whipple_web::{Limits, app};

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// The core's copy of the same file (its tests read it); the server serves its own copy.
const BROWSER: &str = include_str!("../../whipple/tests/data/measured/BrowserMeasured.txt");

async fn send(
    method: Method,
    uri: &str,
    body: Option<&Value>,
) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let mut request = Request::builder().method(method).uri(uri);
    if body.is_some() {
        request = request.header(header::CONTENT_TYPE, "application/json");
    }
    let request = request.body(match body {
        Some(b) => Body::from(b.to_string()),
        None => Body::empty(),
    })?;
    let response = app(Limits::default()).oneshot(request).await?;
    let status = response.status();
    let bytes = response.into_body().collect().await?.to_bytes();
    Ok((status, serde_json::from_slice(&bytes)?))
}

async fn post(body: &Value) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    send(Method::POST, "/api/measure", Some(body)).await
}

/// Browser's text with one key's line replaced (or added).
fn browser_with(key: &str, value: &str) -> String {
    let mut found = false;
    let mut lines: Vec<String> = BROWSER
        .lines()
        .map(|l| {
            if l.split('=').next().map(str::trim) == Some(key) {
                found = true;
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect();
    if !found {
        lines.push(format!("{key} = {value}"));
    }
    lines.join("\n")
}

fn error_of(answer: &Value) -> (String, String) {
    (
        answer["error"]["field"].as_str().unwrap_or("").to_string(),
        answer["error"]["message"]
            .as_str()
            .unwrap_or("")
            .to_string(),
    )
}

/// The sample served is BicycleParameters' Browser file, byte for byte the core's copy.
#[tokio::test]
async fn the_browser_sample_is_served() -> TestResult {
    let (status, samples) = send(Method::GET, "/api/measure/samples", None).await?;
    assert_eq!(status, StatusCode::OK, "{samples}");
    let first = &samples[0];
    assert_eq!(first["name"], "browser");
    assert_eq!(first["title"], "Browser (BicycleParameters)");
    assert_eq!(first["file_name"], "BrowserMeasured.txt");
    assert_eq!(first["text"].as_str(), Some(BROWSER));
    Ok(())
}

/// Every parameter, σ and step of the answer is the library's `MeasuredParameters` on the same
/// text, bit for bit; the bicycle carries the σ; the name comes from the file's name.
#[tokio::test]
async fn browser_equals_the_library_pipeline() -> TestResult {
    let (status, answer) =
        post(&json!({"text": BROWSER, "file_name": "BrowserMeasured.txt"})).await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let core = MeasuredParameters::new(&read_measurements(BROWSER)?.measurements)?;
    assert_eq!(answer["name"], "Browser");
    let table = parameters(Form::Benchmark);
    let got = answer["parameters"].as_array().ok_or("parameters")?;
    assert_eq!(got.len(), table.len());
    for ((p, value), info) in got.iter().zip(core.benchmark.to_array()).zip(table) {
        assert_eq!(p["key"], info.key);
        assert_eq!(p["value"].as_f64(), Some(value), "{}", info.key);
        let sigma = core.sigma.get(info.key).copied().unwrap_or(0.0);
        assert_eq!(p["sigma"].as_f64(), Some(sigma), "{}", info.key);
        assert_eq!(p["unit"], info.unit);
        // The bicycle in the files' layout holds the same value and σ.
        let in_bike = &answer["bike"]["benchmark"][info.key];
        if sigma > 0.0 {
            assert_eq!(in_bike["value"].as_f64(), Some(value), "{}", info.key);
            assert_eq!(in_bike["sigma"].as_f64(), Some(sigma), "{}", info.key);
        } else {
            assert_eq!(in_bike.as_f64(), Some(value), "{}", info.key);
        }
    }
    let steps = answer["steps"].as_array().ok_or("steps")?;
    assert_eq!(steps.len(), core.steps.len());
    for (s, c) in steps.iter().zip(&core.steps) {
        assert_eq!(s["key"], c.key.as_str());
        assert_eq!(s["value"].as_f64(), Some(c.value), "{}", c.key);
        assert_eq!(s["sigma"].as_f64(), c.sigma, "{}", c.key);
        let inputs: Vec<&str> = s["inputs"]
            .as_array()
            .ok_or("inputs")?
            .iter()
            .filter_map(Value::as_str)
            .collect();
        assert_eq!(inputs, c.inputs, "{}", c.key);
    }
    // rR from 27.85 m in 13 turns: d / (2π n).
    let r_r = steps.iter().find(|s| s["key"] == "rR").ok_or("rR")?;
    let expected = 27.85 / (2.0 * std::f64::consts::PI * 13.0);
    assert!((r_r["value"].as_f64().ok_or("rR")? - expected).abs() < 1e-15);
    // The measurements as read, and the rider's geometry kept apart.
    let measured = answer["measurements"].as_array().ok_or("measurements")?;
    let t_t_p = measured.iter().find(|m| m["key"] == "TtP1").ok_or("TtP1")?;
    assert_eq!(t_t_p["value"].as_f64(), Some(1.89399317145));
    assert_eq!(t_t_p["sigma"].as_f64(), Some(5.93377589066e-06));
    assert_eq!(measured.len(), 24 + 2 * 3 * 3);
    let other: Vec<&str> = answer["other"]
        .as_array()
        .ok_or("other")?
        .iter()
        .filter_map(|m| m["key"].as_str())
        .collect();
    assert_eq!(
        other,
        ["lcs", "hbb", "lsp", "lst", "lamst", "whb", "LhbF", "LhbR"]
    );
    let top = core.largest_correlations(5);
    let correlations = answer["correlations"].as_array().ok_or("correlations")?;
    assert_eq!(correlations.len(), 5);
    assert_eq!(correlations[0]["a"], top[0].a);
    assert_eq!(correlations[0]["rho"].as_f64(), Some(top[0].rho));
    Ok(())
}

/// The same measurements as JSON key → {value, sigma} give the same answer as the text, and a
/// name given names the bicycle.
#[tokio::test]
async fn json_measurements_equal_the_text() -> TestResult {
    let (_, from_text) = post(&json!({"text": BROWSER})).await?;
    let mut map = Map::new();
    for group in ["measurements", "other"] {
        for m in from_text[group].as_array().ok_or("measurements")? {
            map.insert(
                m["key"].as_str().ok_or("key")?.to_string(),
                json!({"value": m["value"], "sigma": m["sigma"]}),
            );
        }
    }
    let (status, from_json) = post(&json!({"measurements": map, "name": "Mine"})).await?;
    assert_eq!(status, StatusCode::OK, "{from_json}");
    assert_eq!(from_json["parameters"], from_text["parameters"]);
    assert_eq!(from_json["steps"], from_text["steps"]);
    assert_eq!(from_json["name"], "Mine");
    assert_eq!(from_json["bike"]["name"], "Mine");
    Ok(())
}

/// Bad measurements: 422 naming the key as the user wrote it, in both forms.
#[tokio::test]
async fn bad_measurements_name_the_key() -> TestResult {
    // An unknown key, with its line.
    let (status, answer) = post(&json!({"text": browser_with("TtX1", "1.0+/-0.1")})).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    let (field, message) = error_of(&answer);
    assert_eq!(field, "TtX1");
    assert!(message.contains("unknown key"), "{message}");
    assert_eq!(answer["error"]["line"].as_u64(), Some(51));
    // A negative period.
    let (status, answer) = post(&json!({"text": browser_with("TtB2", "-2.3+/-0.001")})).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    let (field, message) = error_of(&answer);
    assert_eq!(field, "TtB2");
    assert!(message.contains("a period must be positive"), "{message}");
    // Parallel hanging lines: 3.4° and 183.4° hang the frame along the same line.
    let (status, answer) = post(&json!({"text": browser_with("alphaB2", "183.4+/-0.2")})).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    let (field, message) = error_of(&answer);
    assert_eq!(field, "alphaB1 and alphaB2");
    assert!(message.contains("parallel"), "{message}");
    // A missing measurement, named with what it feeds.
    let without: String = BROWSER
        .lines()
        .filter(|l| !l.starts_with("dF "))
        .collect::<Vec<_>>()
        .join("\n");
    let (status, answer) = post(&json!({"text": without})).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    let (field, message) = error_of(&answer);
    assert_eq!(field, "dF");
    assert!(
        message.contains("the front wheel's radius needs it"),
        "{message}"
    );
    Ok(())
}

#[tokio::test]
async fn bad_json_measurements_name_the_key_without_a_line() -> TestResult {
    let (_, from_text) = post(&json!({"text": BROWSER})).await?;
    let mut map = Map::new();
    for m in from_text["measurements"].as_array().ok_or("measurements")? {
        map.insert(
            m["key"].as_str().ok_or("key")?.to_string(),
            json!({"value": m["value"], "sigma": m["sigma"]}),
        );
    }
    let with = |key: &str, value: Value| {
        let mut m = map.clone();
        m.insert(key.to_string(), value);
        json!({ "measurements": m })
    };
    let (status, answer) = post(&with("TcR1", json!({"value": -1.36, "sigma": 0.001}))).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(error_of(&answer).0, "TcR1");
    assert!(
        !error_of(&answer).1.contains("line"),
        "no line of a text the client never wrote: {}",
        error_of(&answer).1
    );
    let (status, answer) = post(&with("lB1", json!({"value": 0.84, "sigma": 0.001}))).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(error_of(&answer).0, "lB1");
    assert!(answer["error"].get("line").is_none(), "{answer}");
    let (status, answer) = post(&with("aH2", json!({"value": 0.383, "sigma": -0.003}))).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(error_of(&answer).0, "aH2");
    assert!(
        error_of(&answer).1.contains("standard deviation"),
        "{answer}"
    );
    // A key that is not a file key cannot smuggle a line into the text.
    let (status, answer) = post(&with("g = 1\nmR", json!({"value": 3.11}))).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert!(
        error_of(&answer).1.contains("letters and digits"),
        "{answer}"
    );
    let (status, answer) = post(&with("mR", json!({"value": "heavy"}))).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(error_of(&answer).0, "mR");
    // Text and measurements together, or neither.
    let (status, answer) = post(&json!({"text": BROWSER, "measurements": map})).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
    assert_eq!(error_of(&answer).0, "text");
    let (status, _) = post(&json!({})).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    Ok(())
}

const JASON: &str = include_str!("../../whipple/tests/data/yeadon/JasonYeadonMeas.txt");
const JASON_ON_BROWSER: &str =
    include_str!("../../whipple/tests/data/yeadon/JasonBrowserYeadonCFG.txt");

/// The sample "Browser with Jason": the rider seated and added to the rear frame, every
/// parameter and σ the core's `with_rider`, the rider alone given; a rider without his
/// configuration (or the reverse) and a rider who cannot reach are refused by name.
#[tokio::test]
async fn a_rider_is_seated_as_the_core_seats_him() -> TestResult {
    use whipple::advanced::rider::{read_yeadon_configuration, read_yeadon_measurements};
    let (_, samples) = send(Method::GET, "/api/measure/samples", None).await?;
    let sample = &samples[1];
    assert_eq!(sample["name"], "browser-jason");
    assert_eq!(sample["rider"].as_str(), Some(JASON));
    assert_eq!(sample["configuration"].as_str(), Some(JASON_ON_BROWSER));
    assert_eq!(sample["text"].as_str(), Some(BROWSER));
    let (status, answer) = post(&json!({
        "text": BROWSER, "file_name": "BrowserMeasured.txt",
        "rider": JASON, "configuration": JASON_ON_BROWSER, "rider_name": "Jason",
    }))
    .await?;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let expected = MeasuredParameters::with_rider(
        &read_measurements(BROWSER)?,
        &read_yeadon_measurements(JASON)?,
        &read_yeadon_configuration(JASON_ON_BROWSER)?,
    )?;
    assert_eq!(answer["name"], "Browser with Jason");
    for (p, value) in parameters(Form::Benchmark)
        .iter()
        .zip(expected.benchmark.to_array())
    {
        let row = answer["parameters"]
            .as_array()
            .and_then(|rows| rows.iter().find(|r| r["key"] == p.key))
            .ok_or("parameter missing")?;
        assert_eq!(row["value"].as_f64(), Some(value), "{}", p.key);
        assert_eq!(
            row["sigma"].as_f64(),
            Some(expected.sigma.get(p.key).copied().unwrap_or(0.0)),
            "{}",
            p.key
        );
    }
    let rider = expected.rider.as_ref().ok_or("no rider")?;
    assert_eq!(answer["rider"]["mass"].as_f64(), Some(rider.rider.mass));
    assert_eq!(
        answer["rider"]["iterations"].as_u64(),
        Some(rider.solve.iterations as u64)
    );
    assert_eq!(
        answer["steps"].as_array().map(Vec::len),
        Some(expected.steps.len())
    );
    // The same from the JSON form (the seat and handlebar keys among the measurements).
    let without = json!({ "text": BROWSER });
    let (_, plain) = post(&without).await?;
    assert!(plain["rider"].is_null(), "{plain}");
    let mut measurements = Map::new();
    for m in plain["measurements"]
        .as_array()
        .into_iter()
        .flatten()
        .chain(plain["other"].as_array().into_iter().flatten())
    {
        measurements.insert(
            m["key"].as_str().unwrap_or("").to_string(),
            json!({ "value": m["value"], "sigma": m["sigma"] }),
        );
    }
    let (status, from_json) = post(&json!({
        "measurements": measurements, "rider": JASON, "configuration": JASON_ON_BROWSER,
    }))
    .await?;
    assert_eq!(status, StatusCode::OK, "{from_json}");
    assert_eq!(from_json["parameters"], answer["parameters"]);

    let (status, e) = post(&json!({ "text": BROWSER, "rider": JASON })).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(error_of(&e).0, "configuration", "{e}");
    let (status, e) = post(&json!({ "text": BROWSER, "configuration": JASON_ON_BROWSER })).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(error_of(&e).0, "rider", "{e}");
    let far = browser_with("LhbF", "1.8930");
    let (status, e) = post(&json!({
        "text": browser_with_text(&far, "LhbR", "1.9213"),
        "rider": JASON, "configuration": JASON_ON_BROWSER,
    }))
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{e}");
    assert!(
        error_of(&e)
            .1
            .contains("the rider cannot reach the handlebar"),
        "{e}"
    );
    Ok(())
}

/// `text` with one key's line replaced.
fn browser_with_text(text: &str, key: &str, value: &str) -> String {
    text.lines()
        .map(|l| {
            if l.split('=').next().map(str::trim) == Some(key) {
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}
