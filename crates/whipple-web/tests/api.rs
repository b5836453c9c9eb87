//! Every endpoint of the API through the router (no socket): answers, errors and limits.

use std::time::Duration;

use axum::Router;
use axum::body::Body;
use axum::http::{Method, Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whipple::advanced::io::{Format, write};
use whipple::presets;
use whipple_reference::meijaard2007 as published;
use whipple_web::{Limits, app};

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// Sends one request; returns the status, the content type and the body as text.
async fn send(
    app: &Router,
    method: Method,
    path: &str,
    body: Option<String>,
) -> Result<(StatusCode, String, String), Box<dyn std::error::Error>> {
    let request = Request::builder()
        .method(method)
        .uri(path)
        .header(header::CONTENT_TYPE, "application/json")
        .body(body.map_or_else(Body::empty, Body::from))?;
    let response = app.clone().oneshot(request).await?;
    let status = response.status();
    let content_type = response
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .unwrap_or("")
        .to_string();
    let bytes = response.into_body().collect().await?.to_bytes();
    Ok((status, content_type, String::from_utf8(bytes.to_vec())?))
}

async fn get(app: &Router, path: &str) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let (status, _, text) = send(app, Method::GET, path, None).await?;
    Ok((status, serde_json::from_str(&text)?))
}

async fn post(
    app: &Router,
    path: &str,
    body: &Value,
) -> Result<(StatusCode, Value), Box<dyn std::error::Error>> {
    let (status, _, text) = send(app, Method::POST, path, Some(body.to_string())).await?;
    Ok((status, serde_json::from_str(&text)?))
}

fn preset_json(name: &str) -> Result<Value, Box<dyn std::error::Error>> {
    let text = write(&presets::find(name)?.bicycle(), Format::Json)?;
    Ok(serde_json::from_str(&text)?)
}

fn approx(value: &Value, expected: f64, tolerance: f64) -> bool {
    value
        .as_f64()
        .is_some_and(|v| (v - expected).abs() <= tolerance)
}

#[tokio::test]
async fn health_and_openapi() -> TestResult {
    let app = app(Limits::default());
    let (status, body) = get(&app, "/api/health").await?;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(body["status"], "ok");
    let (status, doc) = get(&app, "/api/openapi.json").await?;
    assert_eq!(status, StatusCode::OK);
    assert!(doc["openapi"].as_str().is_some_and(|v| v.starts_with("3.")));
    assert!(doc["paths"]["/api/eigen"]["post"].is_object());
    Ok(())
}

#[tokio::test]
async fn page_and_assets_are_served() -> TestResult {
    let app = app(Limits::default());
    let (status, content_type, html) = send(&app, Method::GET, "/", None).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(content_type.starts_with("text/html"));
    // Content-hashed names (app-HASH.js, app-HASH.css), as the page names them.
    let named = |ext: &str| {
        html.split('"')
            .find(|s| s.starts_with("/assets/app-") && s.ends_with(ext))
            .map(str::to_string)
            .ok_or(format!("the page names no /assets/app-*{ext}"))
    };
    let (status, content_type, js) = send(&app, Method::GET, &named(".js")?, None).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(content_type.starts_with("text/javascript"));
    assert!(js.contains("/api/eigen"));
    let (status, content_type, _) = send(&app, Method::GET, &named(".css")?, None).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(content_type.starts_with("text/css"));
    Ok(())
}

#[tokio::test]
async fn presets_listed_and_fetched() -> TestResult {
    let app = app(Limits::default());
    let (status, list) = get(&app, "/api/presets").await?;
    assert_eq!(status, StatusCode::OK);
    let names: Vec<&str> = list
        .as_array()
        .map(|a| a.iter().filter_map(|p| p["name"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(names.len(), presets::PRESETS.len());
    assert!(list.as_array().is_some_and(|a| {
        a.iter()
            .any(|p| p["name"] == "schwinn-crown" && p["form"] == "jbike6")
    }));
    // Each preset's display title is the library's (the page's picker shows it).
    for (served, preset) in list.as_array().ok_or("list")?.iter().zip(presets::PRESETS) {
        assert_eq!(served["name"], preset.name);
        assert_eq!(served["title"], preset.title);
        assert!(!preset.title.is_empty(), "{} has no title", preset.name);
    }
    let (status, crown) = get(&app, "/api/presets/schwinn-crown").await?;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(crown, preset_json("schwinn-crown")?);
    let (status, error) = get(&app, "/api/presets/penny-farthing").await?;
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert_eq!(error["error"]["kind"], "unknown_preset");
    assert!(
        error["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("schwinn-crown"))
    );
    Ok(())
}

#[tokio::test]
async fn validate_converts_and_draws() -> TestResult {
    let app = app(Limits::default());
    let (status, body) = post(
        &app,
        "/api/bike/validate",
        &json!({"bike": preset_json("schwinn-crown")?}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(body["form"], "jbike6");
    assert!(approx(&body["benchmark"]["w"], 1.016, 0.0));
    assert!(approx(&body["benchmark"]["mB"], 84.5, 1e-12));
    let view = &body["side_view"];
    assert_eq!(view["wheels"].as_array().map(Vec::len), Some(2));
    // Rider, frame, rack, fork, basket and the two wheels.
    assert_eq!(view["bodies"].as_array().map(Vec::len), Some(7));
    assert!(approx(
        &view["total_mass"],
        80.0 + 2.5 + 2.0 + 1.5 + 1.5 + 2.0 * 1.818182,
        1e-9
    ));
    Ok(())
}

#[tokio::test]
async fn invalid_values_name_the_field_and_rule() -> TestResult {
    let app = app(Limits::default());
    let mut crown = preset_json("schwinn-crown")?;
    crown["jbike6"]["rider"]["m"] = json!(-5.0);
    let (status, body) = post(&app, "/api/bike/validate", &json!({ "bike": crown })).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let error = &body["error"];
    assert_eq!(error["kind"], "invalid_parameter");
    assert_eq!(error["field"], "mrider");
    assert_eq!(error["rule"], "must not be negative");
    assert_eq!(error["value"], -5.0);
    assert_eq!(
        error["message"],
        "invalid parameter `mrider` = -5: must not be negative"
    );

    let mut bench = preset_json("benchmark")?;
    bench["benchmark"]["IBxz"] = json!(100.0);
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": bench, "speeds": {"start": 0, "stop": 1, "step": 0.5}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "invalid_bicycle");
    assert_eq!(body["error"]["field"], "IBxx, IBzz, IBxz");

    // Missing, unknown and doubled tables: the files' reader's messages.
    let mut missing = preset_json("benchmark")?;
    if let Some(table) = missing["benchmark"].as_object_mut() {
        table.remove("mB");
    }
    let (status, body) = post(&app, "/api/bike/validate", &json!({ "bike": missing })).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "parse");
    assert_eq!(body["error"]["field"], "mB");
    let mut unknown = preset_json("benchmark")?;
    unknown["benchmark"]["mass"] = json!(1.0);
    let (status, body) = post(&app, "/api/bike/validate", &json!({ "bike": unknown })).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["field"], "mass");
    let mut both = preset_json("benchmark")?;
    both["jbike6"] = preset_json("schwinn-crown")?["jbike6"].clone();
    let (status, body) = post(&app, "/api/bike/validate", &json!({ "bike": both })).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("not both"))
    );
    Ok(())
}

#[tokio::test]
async fn toml_round_trip() -> TestResult {
    let app = app(Limits::default());
    for name in ["schwinn-crown", "benchmark"] {
        let bike = preset_json(name)?;
        let (status, body) = post(&app, "/api/bike/toml", &json!({ "bike": bike })).await?;
        assert_eq!(status, StatusCode::OK);
        let text = body["toml"].as_str().unwrap_or_default().to_string();
        assert!(text.contains(if name == "benchmark" {
            "[benchmark]"
        } else {
            "[jbike6]"
        }));
        let (status, parsed) = post(
            &app,
            "/api/bike/parse",
            &json!({"text": text, "format": "toml"}),
        )
        .await?;
        assert_eq!(status, StatusCode::OK);
        assert_eq!(parsed["bike"], bike, "{name} survives TOML and back");
    }
    // JBike6's own .m files are read too.
    let m = write(&presets::find("schwinn-crown")?.bicycle(), Format::Jbike6M)?;
    let (status, parsed) =
        post(&app, "/api/bike/parse", &json!({"text": m, "format": "m"})).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(approx(&parsed["bike"]["jbike6"]["wheelbase"], 1.016, 1e-8));
    // A syntax error comes back with its place.
    let (status, body) = post(
        &app,
        "/api/bike/parse",
        &json!({"text": "name = \"x\"\n[benchmark]\nw = = 1\n", "format": "toml"}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "parse");
    assert_eq!(body["error"]["line"], 3);
    Ok(())
}

/// A file typed in millimetres and degrees: the bicycle comes back in SI (what the page's
/// fields read) with the units apart, and the TOML written with those units back has the keys
/// and digits typed; units that do not fit are refused naming them.
#[tokio::test]
async fn units_typed_in_a_file_travel_apart_and_come_back() -> TestResult {
    let app = app(Limits::default());
    let (_, plain) = post(
        &app,
        "/api/bike/toml",
        &json!({ "bike": preset_json("benchmark")? }),
    )
    .await?;
    let text = plain["toml"]
        .as_str()
        .unwrap_or_default()
        .replace("\nc = 0.08 #", "\nc_mm = 80 #")
        .replace("\nlam = 0.3141592653589793 #", "\nlam_deg = 18 #");
    assert!(
        text.contains("c_mm = 80") && text.contains("lam_deg = 18"),
        "{text}"
    );
    let (status, parsed) = post(
        &app,
        "/api/bike/parse",
        &json!({"text": text, "format": "toml"}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(parsed["bike"]["benchmark"]["c"], 0.08);
    assert!(parsed["bike"]["benchmark"].get("c_mm").is_none());
    assert_eq!(parsed["units"], json!({"c": "mm", "lam": "deg"}));
    // Read from a preset or an SI file: no units.
    let (_, si) = post(
        &app,
        "/api/bike/parse",
        &json!({"text": plain["toml"], "format": "toml"}),
    )
    .await?;
    assert_eq!(si["units"], json!({}));
    let (status, written) = post(
        &app,
        "/api/bike/toml",
        &json!({ "bike": parsed["bike"], "units": parsed["units"] }),
    )
    .await?;
    assert_eq!(status, StatusCode::OK);
    let toml = written["toml"].as_str().unwrap_or_default();
    assert!(
        toml.contains("c_mm = 80") && toml.contains("lam_deg = 18"),
        "{toml}"
    );
    assert!(
        !toml.contains("\nc = ") && !toml.contains("\nlam = "),
        "{toml}"
    );
    for (units, field, words) in [
        (json!({"IBxx": "mm"}), "units.IBxx", "is not a length"),
        (json!({"c": "deg"}), "units.c", "is not an angle"),
        (json!({"c": "inch"}), "units.c", "mm and deg"),
        (json!({"nope": "mm"}), "units.nope", "not a parameter"),
    ] {
        let (status, body) = post(
            &app,
            "/api/bike/toml",
            &json!({ "bike": parsed["bike"], "units": units }),
        )
        .await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{units}");
        assert_eq!(body["error"]["field"], field, "{body}");
        let message = body["error"]["message"].as_str().unwrap_or_default();
        assert!(message.contains(words), "{units}: {message}");
    }
    Ok(())
}

/// Meijaard et al. 2007, Table 2 (doi:10.1098/rspa.2007.1857); JBike6's Schwinn Crown 7.9807.
#[tokio::test]
async fn eigen_sweep_and_critical_speeds() -> TestResult {
    let app = app(Limits::default());
    let request =
        json!({"bike": preset_json("benchmark")?, "speeds": {"start": 0, "stop": 10, "step": 0.1}});
    let (status, body) = post(&app, "/api/eigen", &request).await?;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(body["speeds"].as_array().map(Vec::len), Some(101));
    let modes: Vec<&str> = body["eigenvalues"]
        .as_array()
        .map(|c| c.iter().filter_map(|c| c["mode"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(modes, ["weave", "weave", "capsize", "castering"]);
    for column in body["eigenvalues"].as_array().into_iter().flatten() {
        assert_eq!(column["re"].as_array().map(Vec::len), Some(101));
        assert_eq!(column["im"].as_array().map(Vec::len), Some(101));
    }
    let critical = &body["critical"];
    assert!(approx(
        &critical["weave_speed"],
        published::WEAVE_SPEED,
        1e-10
    ));
    assert!(approx(
        &critical["capsize_speed"],
        published::CAPSIZE_SPEED,
        1e-10
    ));
    assert!(approx(
        &critical["stable_speed_ranges"][0][0],
        published::WEAVE_SPEED,
        1e-10
    ));

    let request = json!({"bike": preset_json("schwinn-crown")?, "speeds": {"start": 0, "stop": 10, "step": 0.01}});
    let (status, body) = post(&app, "/api/eigen", &request).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(approx(&body["critical"]["capsize_speed"], 7.9807, 5e-5));

    // One speed: eigenvalues, no range to search.
    let request =
        json!({"bike": preset_json("benchmark")?, "speeds": {"start": 5, "stop": 5, "step": 1}});
    let (status, body) = post(&app, "/api/eigen", &request).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(body["critical"].is_null());
    Ok(())
}

#[tokio::test]
async fn speeds_endpoint() -> TestResult {
    let app = app(Limits::default());
    let bike = preset_json("benchmark")?;
    let (status, body) = post(
        &app,
        "/api/speeds",
        &json!({"bike": bike, "range": {"lo": 0, "hi": 10}}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK);
    assert!(approx(
        &body["capsize_speed"],
        published::CAPSIZE_SPEED,
        1e-10
    ));
    assert!(approx(&body["double_root_speed"], 0.684, 1e-3));
    let (status, body) = post(
        &app,
        "/api/speeds",
        &json!({"bike": bike, "range": {"lo": 10, "hi": 0}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "invalid_argument");
    assert_eq!(body["error"]["field"], "range");
    Ok(())
}

#[tokio::test]
async fn out_of_range_speeds() -> TestResult {
    let app = app(Limits::default());
    let bike = preset_json("benchmark")?;
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 10, "step": 0}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "invalid_argument");
    assert_eq!(body["error"]["field"], "speeds");
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 100, "step": 1e-6}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "limit_exceeded");
    assert_eq!(body["error"]["field"], "speeds");
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("100000"))
    );
    // One over the default limit (0:10:1e-4 holds 100,001 speeds) is refused before any work.
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 10, "step": 1e-4}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "limit_exceeded");
    // Exactly at a limit is served (a small limit, to keep the debug-build test quick).
    let small = whipple_web::app(Limits {
        max_speeds: 1000,
        ..Limits::default()
    });
    let (status, body) = post(
        &small,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 9.99, "step": 0.01}}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(body["speeds"].as_array().map(Vec::len), Some(1000));
    let (status, body) = post(
        &small,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 10, "step": 0.01}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "limit_exceeded");
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 1e300, "step": 1e299}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    // A grid past any count f64 holds (0:1e300:1e-10) is over the server's limit, counted by
    // the library without building it.
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": bike, "speeds": {"start": 0, "stop": 1e300, "step": 1e-10}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["kind"], "limit_exceeded");
    assert_eq!(body["error"]["field"], "speeds");
    Ok(())
}

#[tokio::test]
async fn malformed_requests() -> TestResult {
    let app = app(Limits::default());
    let (status, _, text) =
        send(&app, Method::POST, "/api/eigen", Some("{\"bike\": ".into())).await?;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let body: Value = serde_json::from_str(&text)?;
    assert_eq!(body["error"]["kind"], "bad_json");
    let (status, _, text) = send(
        &app,
        Method::POST,
        "/api/bike/validate",
        Some("not json".into()),
    )
    .await?;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(text.contains("bad_json"));
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": preset_json("benchmark")?}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "invalid_request");
    assert_eq!(body["error"]["field"], "speeds");
    let (status, body) = post(
        &app,
        "/api/eigen",
        &json!({"bike": preset_json("benchmark")?, "speeds": {"start": "0", "stop": 1, "step": 1}}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "invalid_request");
    let (status, body) = post(
        &app,
        "/api/bike/parse",
        &json!({"text": "", "format": "pdf"}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["kind"], "invalid_request");
    // Unknown paths and methods answer JSON too.
    let (status, body) = get(&app, "/api/nothing").await?;
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert_eq!(body["error"]["kind"], "not_found");
    let (status, body) = get(&app, "/api/eigen").await?;
    assert_eq!(status, StatusCode::METHOD_NOT_ALLOWED);
    assert_eq!(body["error"]["kind"], "method_not_allowed");
    let (status, _, _) = send(&app, Method::DELETE, "/api/presets", None).await?;
    assert_eq!(status, StatusCode::METHOD_NOT_ALLOWED);
    Ok(())
}

#[tokio::test]
async fn oversized_requests_are_refused() -> TestResult {
    let app = app(Limits {
        max_body_bytes: 64 * 1024,
        ..Limits::default()
    });
    let huge = json!({"text": "#".repeat(100 * 1024), "format": "toml"}).to_string();
    let (status, _, text) = send(&app, Method::POST, "/api/bike/parse", Some(huge)).await?;
    assert_eq!(status, StatusCode::PAYLOAD_TOO_LARGE);
    let body: Value = serde_json::from_str(&text)?;
    assert_eq!(body["error"]["kind"], "too_large");
    // The default limit, 1 MiB.
    let app = whipple_web::app(Limits::default());
    let huge = json!({"text": "#".repeat(2 << 20), "format": "toml"}).to_string();
    let (status, _, _) = send(&app, Method::POST, "/api/bike/parse", Some(huge)).await?;
    assert_eq!(status, StatusCode::PAYLOAD_TOO_LARGE);
    Ok(())
}

fn heavy() -> Result<Value, Box<dyn std::error::Error>> {
    Ok(
        json!({"bike": preset_json("benchmark")?, "speeds": {"start": 0, "stop": 19.999, "step": 0.001}}),
    )
}

#[tokio::test]
async fn slow_computations_time_out() -> TestResult {
    let app = app(Limits {
        compute_timeout: Duration::from_micros(1),
        ..Limits::default()
    });
    let (status, body) = post(&app, "/api/eigen", &heavy()?).await?;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    assert_eq!(body["error"]["kind"], "timeout");
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("fewer speeds"))
    );
    Ok(())
}

#[tokio::test]
async fn slow_requests_time_out() -> TestResult {
    let app = app(Limits {
        request_timeout: Duration::from_micros(1),
        ..Limits::default()
    });
    let (status, body) = post(&app, "/api/eigen", &heavy()?).await?;
    assert_eq!(status, StatusCode::REQUEST_TIMEOUT);
    assert_eq!(body["error"]["kind"], "timeout");
    Ok(())
}

#[tokio::test]
async fn a_full_server_says_busy() -> TestResult {
    let app = app(Limits {
        max_concurrent_computations: 1,
        queue_timeout: Duration::from_millis(1),
        ..Limits::default()
    });
    let request = heavy()?;
    let (first, second) = tokio::join!(
        post(&app, "/api/eigen", &request),
        post(&app, "/api/eigen", &request)
    );
    let mut statuses = [first?.0, second?.0];
    statuses.sort();
    assert_eq!(statuses, [StatusCode::OK, StatusCode::SERVICE_UNAVAILABLE]);
    Ok(())
}

fn simulation(fields: Value) -> Result<Value, Box<dyn std::error::Error>> {
    let mut request =
        json!({"bike": preset_json("benchmark")?, "speed": 4.6, "lean_rate": 0.5, "duration": 2.0});
    if let (Some(request), Some(fields)) = (request.as_object_mut(), fields.as_object()) {
        for (k, v) in fields {
            request.insert(k.clone(), v.clone());
        }
    }
    Ok(request)
}

/// The benchmark bicycle at 4.6 m/s (inside its self-stable range 4.29–6.02 m/s): the weave
/// started by a lean rate of 0.5 rad/s decays; frames at 60 per second carry the poses.
#[tokio::test]
async fn simulation_runs_and_sends_frames() -> TestResult {
    let app = app(Limits::default());
    let (status, body) = post(
        &app,
        "/api/simulate",
        &simulation(json!({"duration": 3.0}))?,
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "completed");
    assert!(approx(&body["outcome"]["t"], 3.0, 1e-12));
    assert_eq!(body["steps"], 3000);
    let frames = body["frames"].as_array().ok_or("frames")?;
    assert_eq!(frames.len(), 181, "60 frames per second, both ends");
    assert!(approx(&frames[0]["t"], 0.0, 0.0));
    assert!(approx(&frames[180]["t"], 3.0, 1e-9));
    assert!(approx(&frames[0]["lean_rate"], 0.5, 1e-9));
    assert!(approx(&frames[0]["speed"], 4.6, 1e-9));
    // Upright at the start: the rear frame's centre of mass is at (x_B, 0, z_B) = (0.3, 0, -0.9).
    let rider = &frames[0]["bodies"][1];
    assert!(approx(&rider["position"][0], 0.3, 1e-6));
    assert!(approx(&rider["position"][2], -0.9, 1e-6));
    assert!(approx(&rider["rotation"][0], 1.0, 1e-6));
    // The weave decays: the lean late in the run is smaller than early on.
    let peak = |from: usize, to: usize| {
        frames[from..to]
            .iter()
            .filter_map(|f| f["lean"].as_f64())
            .fold(0.0_f64, |m, x| m.max(x.abs()))
    };
    assert!(
        peak(150, 181) < 0.5 * peak(0, 60),
        "{} vs {}",
        peak(150, 181),
        peak(0, 60)
    );
    assert!(
        frames[180]["rear_contact"][0]
            .as_f64()
            .is_some_and(|x| x > 13.0)
    );
    assert!(
        frames[90]["rear_force"]["normal"]
            .as_f64()
            .is_some_and(|n| n > 0.0)
    );
    assert!(approx(&body["geometry"]["rear_wheel_radius"], 0.3, 1e-12));
    assert!(approx(&body["geometry"]["masses"][1], 85.0, 1e-12));
    // The adaptive integrator gives the same motion.
    let (status, adaptive) = post(
        &app,
        "/api/simulate",
        &simulation(json!({"duration": 3.0, "integrator": "adaptive", "rtol": 1e-8}))?,
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{adaptive}");
    assert_eq!(adaptive["outcome"]["kind"], "completed");
    let last = adaptive["frames"]
        .as_array()
        .and_then(|f| f.last())
        .ok_or("frames")?;
    assert!(approx(
        &last["lean"],
        frames[180]["lean"].as_f64().ok_or("lean")?,
        1e-6
    ));
    Ok(())
}

/// A map's cell as a bicycle: the base with both axes' parameters set (what the page loads
/// when a cell is clicked); an index past the map is refused naming `index`.
#[tokio::test]
async fn a_map_cell_is_a_bicycle() -> TestResult {
    let app = app(Limits::default());
    let request = |index: u64| -> Result<Value, Box<dyn std::error::Error>> {
        Ok(json!({
            "bike": preset_json("benchmark")?,
            "x": "trail=-0.05:0.2:51",
            "y": "head_angle_deg=60:85:51",
            "index": index,
        }))
    };
    // ix = 30 (trail 0.1 m), iy = 20 (head angle 70°).
    let (status, body) = post(&app, "/api/map/design", &request(20 * 51 + 30)?).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    let b = &body["bike"]["benchmark"];
    assert!(approx(&b["c"], 0.1, 1e-12), "{b}");
    assert!(approx(&b["lam"], 20f64.to_radians(), 1e-12), "{b}");
    assert!(approx(&b["w"], 1.02, 0.0), "the other parameters stay: {b}");
    let (status, body) = post(&app, "/api/map/design", &request(51 * 51)?).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["field"], "index", "{body}");
    Ok(())
}

/// JSON answers go gzip-compressed to a client that accepts gzip (the page's first load sent
/// 279 KB uncompressed): the same JSON once inflated, over twice smaller; a short answer,
/// and any answer to a client that does not ask, goes as it is.
#[tokio::test]
async fn json_answers_are_gzipped_for_clients_that_accept_it() -> TestResult {
    use std::io::Read;
    let app = app(Limits::default());
    let body =
        json!({"bike": preset_json("benchmark")?, "x": "trail=0:0.2:41", "y": "w=0.9:1.2:31"})
            .to_string();
    let ask = |encoding: Option<&str>| -> Result<Request<Body>, axum::http::Error> {
        let mut request = Request::builder()
            .method(Method::POST)
            .uri("/api/map")
            .header(header::CONTENT_TYPE, "application/json");
        if let Some(encoding) = encoding {
            request = request.header(header::ACCEPT_ENCODING, encoding);
        }
        request.body(Body::from(body.clone()))
    };
    let plain = app.clone().oneshot(ask(None)?).await?;
    assert!(plain.headers().get(header::CONTENT_ENCODING).is_none());
    let plain = plain.into_body().collect().await?.to_bytes();
    let zipped = app.clone().oneshot(ask(Some("gzip, deflate, br"))?).await?;
    assert_eq!(zipped.headers()[header::CONTENT_ENCODING], "gzip");
    assert_eq!(zipped.headers()[header::VARY], "accept-encoding");
    let zipped = zipped.into_body().collect().await?.to_bytes();
    let mut inflated = Vec::new();
    flate2::read::GzDecoder::new(&zipped[..]).read_to_end(&mut inflated)?;
    assert_eq!(inflated, plain.to_vec());
    assert!(
        zipped.len() * 2 < plain.len(),
        "{} of {} bytes",
        zipped.len(),
        plain.len()
    );
    let refused = app.clone().oneshot(ask(Some("gzip;q=0"))?).await?;
    assert!(refused.headers().get(header::CONTENT_ENCODING).is_none());
    let health = Request::builder()
        .uri("/api/health")
        .header(header::ACCEPT_ENCODING, "gzip")
        .body(Body::empty())?;
    let health = app.clone().oneshot(health).await?;
    assert!(
        health.headers().get(header::CONTENT_ENCODING).is_none(),
        "a short answer as it is"
    );
    Ok(())
}

/// A bicycle whose parameters carry σ gets the critical speeds with their σ beside (what the
/// page's table shows as v ± σ), the same numbers as `critical_speeds_sigma`; one without σ
/// gets no σ fields.
#[tokio::test]
async fn the_eigenvalues_answer_carries_the_critical_speeds_sigma() -> TestResult {
    let app = app(Limits::default());
    let mut bike = preset_json("benchmark")?;
    bike["benchmark"]["c"] = json!({"value": 0.08, "sigma": 0.002});
    let speeds = json!({"start": 0, "stop": 10, "step": 0.5});
    let (status, body) = post(&app, "/api/eigen", &json!({"bike": bike, "speeds": speeds})).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    let mut library = presets::find("benchmark")?.bicycle();
    library.sigma.insert("c".into(), 0.002);
    let expected = whipple::advanced::sensitivity::critical_speeds_sigma(&library, 0.0, 10.0)?;
    let critical = &body["critical"];
    assert!(
        approx(&critical["weave_speed"], 4.29238253634111, 1e-12),
        "{critical}"
    );
    let sigma = expected.weave_speed_sigma.ok_or("σ of v_w")?;
    assert!(
        sigma > 0.0 && approx(&critical["weave_speed_sigma"], sigma, 1e-15),
        "{critical}"
    );
    assert_eq!(
        critical["stable_speed_ranges_sigma"]
            .as_array()
            .map(Vec::len),
        Some(1)
    );
    let (_, plain) = post(
        &app,
        "/api/eigen",
        &json!({"bike": preset_json("benchmark")?, "speeds": speeds}),
    )
    .await?;
    assert!(
        plain["critical"].get("weave_speed_sigma").is_none(),
        "{plain}"
    );
    Ok(())
}

/// A map with a band answers "self-stable over [a, b]?" per design: at the benchmark's own
/// design (trail 0.08 m, its range 4.292… to 6.024… m/s) yes over 4.5–5.5 with those margins;
/// a band outside the range names `band`; without a band the answer has no band arrays.
#[tokio::test]
async fn a_map_with_a_band_answers_stable_over_it() -> TestResult {
    let app = app(Limits::default());
    let map = |band: Value, range: Value| -> Result<Value, Box<dyn std::error::Error>> {
        let mut request = json!({
            "bike": preset_json("benchmark")?,
            "x": "trail=0.04:0.12:3",
            "y": "w=1.02:1.02:1",
        });
        if let Some(object) = request.as_object_mut() {
            if !band.is_null() {
                object.insert("band".into(), band);
            }
            if !range.is_null() {
                object.insert("range".into(), range);
            }
        }
        Ok(request)
    };
    let (status, body) = post(&app, "/api/map", &map(json!([4.5, 5.5]), Value::Null)?).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["band"], json!([4.5, 5.5]));
    assert_eq!(body["stable_over"][1], true, "{body}");
    assert!(approx(
        &body["band_margin_below"][1],
        4.5 - 4.29238253634111,
        1e-12
    ));
    assert!(approx(
        &body["band_margin_above"][1],
        6.02426201538837 - 5.5,
        1e-12
    ));
    assert!(approx(
        &body["band_margin"][1],
        4.5 - 4.29238253634111,
        1e-12
    ));
    assert_eq!(body["stable_over"][0], false, "trail 0.04 m: {body}");
    assert!(body["band_margin"][0].is_null());
    let (status, body) = post(
        &app,
        "/api/map",
        &map(json!([4.0, 8.0]), json!({"lo": 0.0, "hi": 6.0}))?,
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["field"], "band", "{body}");
    let (status, body) = post(&app, "/api/map", &map(Value::Null, Value::Null)?).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert!(
        body.get("stable_over").is_none() && body.get("band").is_none(),
        "{body}"
    );
    Ok(())
}

/// The benchmark bicycle's held turn at 5 m/s and 11.5° of lean, as `whipple turn` prints it:
/// steer 4.864°, a small counter-steering torque, rear radius 12.35 m, stable; the rear wheel
/// turns at exactly v / r_R. A lean past 89° names `lean_deg`; two givens are refused.
#[tokio::test]
async fn a_held_steady_turn_and_its_stability() -> TestResult {
    let app = app(Limits::default());
    let turn = |fields: Value| -> Result<Value, Box<dyn std::error::Error>> {
        let mut request = json!({"bike": preset_json("benchmark")?, "speed": 5.0});
        if let (Some(request), Some(fields)) = (request.as_object_mut(), fields.as_object()) {
            for (k, v) in fields {
                request.insert(k.clone(), v.clone());
            }
        }
        Ok(request)
    };
    let (status, body) = post(&app, "/api/turn", &turn(json!({"lean_deg": 11.5}))?).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert!(approx(&body["steer_deg"], 4.8639, 1e-4), "{body}");
    assert!(
        approx(&body["turn"]["steer_torque"], -0.141903, 1e-6),
        "{body}"
    );
    assert!(
        approx(&body["turn"]["rear_radius"], 12.3510, 1e-4),
        "{body}"
    );
    assert!(
        approx(&body["turn"]["wheel_rates"][0], -5.0 / 0.3, 1e-9),
        "{body}"
    );
    assert_eq!(body["stability"]["stable"], true, "{body}");
    let residual = body["turn"]["residuals"]["lean_acceleration"]
        .as_f64()
        .ok_or("residual")?;
    assert!(residual.abs() < 1e-12, "{residual}");
    let (status, body) = post(&app, "/api/turn", &turn(json!({"lean_deg": 89.5}))?).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["field"], "lean_deg", "{body}");
    let both = turn(json!({"lean_deg": 10.0, "radius": 20.0}))?;
    let (status, body) = post(&app, "/api/turn", &both).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    // A turn that is not reached names what was given (the page marks that field).
    for (given, field) in [
        (json!({"lean_deg": 89.0, "speed": 3.0}), "lean_deg"),
        (json!({"radius": 0.05, "speed": 8.0}), "radius"),
    ] {
        let (status, body) = post(&app, "/api/turn", &turn(given)?).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
        assert_eq!(body["error"]["kind"], "no_steady_turn", "{body}");
        assert_eq!(body["error"]["field"], field, "{body}");
    }
    Ok(())
}

/// The largest departure of the frames' lean from `lean` [rad].
fn lean_departure(body: &Value, lean: f64) -> Result<f64, Box<dyn std::error::Error>> {
    let frames = body["frames"].as_array().ok_or("frames")?;
    let mut worst: f64 = 0.0;
    for frame in frames {
        worst = worst.max((frame["lean"].as_f64().ok_or("lean")? - lean).abs());
    }
    Ok(worst)
}

/// A simulation started on the held turn (`from_turn`) of the benchmark bicycle at 5 m/s and
/// 11.5° of lean, a stable turn: with the turn's steer torque held, the run stays on it for
/// 2 s (the lean within 1e-4 rad, the steer the turn's 4.864°); hands free (`steer_torque` 0
/// given) it leaves. At 3 m/s the turn is unstable: a lean rate of 0.01 rad/s grows away from
/// it. A steer beside `from_turn`, or a lean with no turn, is refused naming the field.
#[tokio::test]
async fn a_simulation_starts_on_a_held_turn() -> TestResult {
    let app = app(Limits::default());
    let lean = 11.5_f64.to_radians();
    let on_turn = |fields: Value| {
        simulation(json!({"from_turn": true, "speed": 5.0, "lean_deg": 11.5, "lean_rate": 0.0}))
            .map(|mut request| {
                if let (Some(request), Some(fields)) = (request.as_object_mut(), fields.as_object())
                {
                    for (k, v) in fields {
                        request.insert(k.clone(), v.clone());
                    }
                }
                request
            })
    };
    let (status, body) = post(&app, "/api/simulate", &on_turn(json!({}))?).await?;
    assert_eq!(status, StatusCode::OK, "{}", body["error"]);
    assert_eq!(body["outcome"]["kind"], "completed", "{}", body["outcome"]);
    assert!(
        approx(&body["turn"]["steer_torque"], -0.141903, 1e-6),
        "{}",
        body["turn"]
    );
    let first = &body["frames"][0];
    assert!(approx(&first["lean"], lean, 1e-12), "{first}");
    assert!(
        approx(&first["steer"], 4.8639_f64.to_radians(), 2e-6),
        "{first}"
    );
    let last = body["frames"]
        .as_array()
        .and_then(|f| f.last())
        .ok_or("frames")?;
    assert!(approx(&last["t"], 2.0, 1e-9), "{last}");
    let held = lean_departure(&body, lean)?;
    assert!(held < 1e-4, "the held turn's lean moved {held} rad");
    // The rear contact goes round the turn's circle: 2 s at 5 m/s on 12.351 m is 0.81 rad.
    assert!(approx(&last["yaw"], 10.0 / 12.3510, 1e-3), "{last}");

    let (status, body) = post(
        &app,
        "/api/simulate",
        &on_turn(json!({"steer_torque": 0.0}))?,
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{}", body["error"]);
    let free = lean_departure(&body, lean)?;
    assert!(
        free > 100.0 * held.max(1e-6),
        "hands free the lean moved only {free} rad"
    );

    let unstable = on_turn(json!({"speed": 3.0, "lean_rate": 0.01, "duration": 3.0}))?;
    let (status, body) = post(&app, "/api/simulate", &unstable).await?;
    assert_eq!(status, StatusCode::OK, "{}", body["error"]);
    let departed = lean_departure(&body, lean)?;
    assert!(
        departed > 0.05,
        "the unstable turn's lean moved only {departed} rad"
    );

    for (fields, field) in [
        (json!({"steer_deg": 3.0}), "steer_deg"),
        (json!({"lean_deg": 89.5}), "lean_deg"),
    ] {
        let (status, body) = post(&app, "/api/simulate", &on_turn(fields.clone())?).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{fields}: {body}");
        assert_eq!(body["error"]["field"], field, "{fields}: {body}");
    }
    Ok(())
}

/// 30 s at 40 m/s ends 1.2 km from the start: the run completes (with an absolute position
/// tolerance it failed there, where round-off of the coordinates exceeds 1e-13 m).
#[tokio::test]
async fn a_long_fast_simulation_completes() -> TestResult {
    let app = app(Limits::default());
    let request = simulation(json!({"speed": 40.0, "lean_rate": 0.0, "duration": 30.0}))?;
    let (status, body) = post(&app, "/api/simulate", &request).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "completed", "{}", body["outcome"]);
    let last = body["frames"]
        .as_array()
        .and_then(|f| f.last())
        .ok_or("frames")?;
    assert!(approx(&last["rear_contact"][0], 1200.0, 1e-6), "{last}");
    Ok(())
}

/// At 3 m/s, below the weave speed, the benchmark bicycle falls over: the rear wheel would lift
/// off first (at t = 1.6036 s, 41° of lean), in step 1604 of RK4 at 1 ms, and the last frame is
/// that step.
#[tokio::test]
async fn simulation_reports_a_fall() -> TestResult {
    let app = app(Limits::default());
    let (status, body) = post(
        &app,
        "/api/simulate",
        &simulation(json!({"speed": 3.0, "duration": 10.0}))?,
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(
        body["outcome"]["kind"], "wheel_lifted",
        "{}",
        body["outcome"]
    );
    assert_eq!(body["outcome"]["wheel"], "rear");
    let t = body["outcome"]["t"].as_f64().ok_or("t")?;
    assert!((t - 1.60357).abs() < 1e-4, "{t}");
    assert_eq!(body["steps"], 1604);
    let message = body["outcome"]["message"].as_str().ok_or("message")?;
    assert!(
        message.contains("rear wheel") && message.contains("at t = 1.60 s"),
        "{message}"
    );
    assert!(
        message.contains("lean -41.1") && message.contains("falling"),
        "{message}"
    );
    let frames = body["frames"].as_array().ok_or("frames")?;
    let last = frames.last().ok_or("no frames")?;
    assert!(
        approx(&last["t"], 1.604, 1e-9),
        "the last frame is the event's step"
    );
    assert!(
        last["rear_force"]["normal"]
            .as_f64()
            .is_some_and(|n| n < 0.0)
    );
    Ok(())
}

/// Every way a run can fail comes back as its outcome with the frames so far (200): a
/// diverging projection, a non-finite state, the step limit; and a start that cannot be
/// computed is a 422 `numerical` error, never a 500.
#[tokio::test]
async fn simulation_failures_are_reported() -> TestResult {
    let app = app(Limits::default());
    let cases = [
        (
            json!({"speed": 5.0, "lean_rate": 0.0, "steer_torque": 5000.0, "dt": 0.05}),
            "projection_failed",
            0.05,
            "the projection onto the constraints diverged",
        ),
        (
            json!({"speed": 5.0, "lean_rate": 0.0, "steer_torque": "1/(t-0.5)", "dt": 0.01}),
            "non_finite_state",
            0.5,
            "the state became non-finite",
        ),
    ];
    for (fields, kind, t, words) in cases {
        let (status, body) = post(&app, "/api/simulate", &simulation(fields.clone())?).await?;
        assert_eq!(status, StatusCode::OK, "{fields}: {body}");
        assert_eq!(
            body["outcome"]["kind"], kind,
            "{fields}: {}",
            body["outcome"]
        );
        assert!(
            approx(&body["outcome"]["t"], t, 1e-12),
            "{}",
            body["outcome"]
        );
        let message = body["outcome"]["message"].as_str().unwrap_or("");
        assert!(message.contains(words), "{message}");
        assert!(body["frames"].as_array().is_some_and(|f| !f.is_empty()));
    }
    let limited = whipple_web::app(Limits {
        max_sim_steps: 30,
        ..Limits::default()
    });
    let request = simulation(json!({"integrator": "adaptive", "rtol": 1e-12, "duration": 2.0}))?;
    let (status, body) = post(&limited, "/api/simulate", &request).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "step_limit", "{}", body["outcome"]);
    let t = body["outcome"]["t"].as_f64().ok_or("t")?;
    assert!(t > 0.0 && t < 2.0, "{t}");
    assert!(
        body["outcome"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("limit of 30 steps"))
    );
    // A lean a hair's breadth from 90 degrees: the start cannot be projected onto the
    // constraints.
    let (status, body) = post(
        &app,
        "/api/simulate",
        &simulation(json!({"lean_deg": 89.999999}))?,
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["kind"], "numerical");
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("projection diverged"))
    );
    Ok(())
}

/// Rider torques as numbers or as expressions of time and the state: at 3 m/s, where the
/// hands-free benchmark bicycle falls, a steer torque that steers into the lean (the CLI's
/// language; gains chosen by the linear model's closed-loop eigenvalues) keeps it up; a constant and the same constant written as an expression give the
/// same motion.
#[tokio::test]
async fn simulation_takes_rider_torques_as_expressions() -> TestResult {
    let app = app(Limits::default());
    let (status, body) = post(
        &app,
        "/api/simulate",
        &simulation(json!({
            "speed": 3.0,
            "duration": 5.0,
            "steer_torque": "10*lean + 20*lean_rate",
        }))?,
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "completed", "{}", body["outcome"]);
    let frames = body["frames"].as_array().ok_or("frames")?;
    let late = frames[240..]
        .iter()
        .filter_map(|f| f["lean"].as_f64())
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(late < 0.01, "the controlled lean dies out: {late}");
    let mut last = Vec::new();
    for torque in [json!(0.3), json!("0.3 + 0*t"), json!(0.0), json!(-0.3)] {
        let (status, body) = post(
            &app,
            "/api/simulate",
            &simulation(json!({"lean_torque": torque}))?,
        )
        .await?;
        assert_eq!(status, StatusCode::OK, "{body}");
        let frames = body["frames"].as_array().ok_or("frames")?;
        last.push(
            frames.last().ok_or("no frames")?["lean"]
                .as_f64()
                .ok_or("lean")?,
        );
    }
    assert!((last[0] - last[1]).abs() < 1e-12, "{last:?}");
    // And the torque acts: a lean torque to the right leans the bicycle further right than none,
    // one to the left less (its sign is the benchmark's, lean right positive).
    assert!(
        last[0] > last[2] + 1e-3 && last[3] < last[2] - 1e-3,
        "{last:?}"
    );
    Ok(())
}

#[tokio::test]
async fn simulation_refuses_bad_inputs_and_limits() -> TestResult {
    let app = app(Limits::default());
    let cases = [
        (
            json!({"lean_deg": 90.0}),
            "invalid_argument",
            "lean_deg",
            "below 90 degrees",
        ),
        (
            json!({"lean_deg": -95.0}),
            "invalid_argument",
            "lean_deg",
            "below 90 degrees",
        ),
        (
            json!({"dt": 0.0}),
            "invalid_argument",
            "dt",
            "must be positive",
        ),
        (
            json!({"dt": -1e-3}),
            "invalid_argument",
            "dt",
            "must be positive",
        ),
        (
            json!({"dt": 3.0}),
            "invalid_argument",
            "dt",
            "at most the duration",
        ),
        (
            json!({"duration": 0.0}),
            "invalid_argument",
            "duration",
            "must be positive",
        ),
        (
            json!({"duration": 31.0}),
            "limit_exceeded",
            "duration",
            "limit of 30 s",
        ),
        (
            json!({"duration": 20.0, "dt": 1e-4}),
            "limit_exceeded",
            "dt",
            "limit of 100000",
        ),
        (
            json!({"duration": 30.0, "dt": 2.9e-4}),
            "limit_exceeded",
            "dt",
            "takes 103449 integration steps",
        ),
        (
            json!({"rtol": 1e-6}),
            "invalid_argument",
            "rtol",
            "RK4 takes `dt`",
        ),
        (
            json!({"integrator": "adaptive", "dt": 1e-3}),
            "invalid_argument",
            "dt",
            "takes `rtol`",
        ),
        (
            json!({"integrator": "adaptive", "rtol": 2.0}),
            "invalid_argument",
            "rtol",
            "between 0 and 1",
        ),
        (
            json!({"steer_torque": "sin(t"}),
            "invalid_argument",
            "steer_torque",
            "cannot read `sin(t`",
        ),
        (
            json!({"lean_torque": "2*foo"}),
            "invalid_argument",
            "lean_torque",
            "unknown name `foo`",
        ),
        (
            json!({"steer_torque": "1/t"}),
            "invalid_argument",
            "steer_torque",
            "not a finite number at rest",
        ),
    ];
    for (fields, kind, field, words) in cases {
        let (status, body) = post(&app, "/api/simulate", &simulation(fields.clone())?).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{fields}: {body}");
        assert_eq!(body["error"]["kind"], kind, "{fields}: {body}");
        assert_eq!(body["error"]["field"], field, "{fields}: {body}");
        let message = body["error"]["message"].as_str().unwrap_or("");
        assert!(message.contains(words), "{fields}: {message}");
    }
    // Non-finite numbers: JSON has none, and one out of range is not a number.
    let text = simulation(json!({}))?
        .to_string()
        .replace("\"speed\":4.6", "\"speed\":1e999");
    let (status, _, body) = send(&app, Method::POST, "/api/simulate", Some(text)).await?;
    assert!(
        status == StatusCode::BAD_REQUEST || status == StatusCode::UNPROCESSABLE_ENTITY,
        "{status} {body}"
    );
    // Wrong shapes and unknown keys.
    for fields in [
        json!({"speed": "fast"}),
        json!({"integrator": "euler"}),
        json!({"fall_angle": 30}),
    ] {
        let (status, body) = post(&app, "/api/simulate", &simulation(fields.clone())?).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{fields}: {body}");
        assert_eq!(body["error"]["kind"], "invalid_request");
    }
    // An invalid bicycle names its parameter.
    let mut bike = preset_json("benchmark")?;
    bike["benchmark"]["mB"] = json!(-1.0);
    let (status, body) = post(&app, "/api/simulate", &simulation(json!({"bike": bike}))?).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(body["error"]["field"], "mB");
    // Exactly at the step limit is allowed (0.3 / 0.0003 is 1,000 steps to round-off).
    let at_limit = whipple_web::app(Limits {
        max_sim_steps: 1000,
        ..Limits::default()
    });
    let request = simulation(json!({"duration": 0.3, "dt": 3e-4}))?;
    let (status, body) = post(&at_limit, "/api/simulate", &request).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["steps"], 1000);
    // A smaller limit is honoured, and the compute timeout names what to change.
    let small = whipple_web::app(Limits {
        max_sim_duration: 1.0,
        ..Limits::default()
    });
    let (status, body) = post(&small, "/api/simulate", &simulation(json!({}))?).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("limit of 1 s"))
    );
    let slow = whipple_web::app(Limits {
        compute_timeout: Duration::from_micros(1),
        ..Limits::default()
    });
    let (status, body) = post(&slow, "/api/simulate", &simulation(json!({}))?).await?;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("shorter time"))
    );
    Ok(())
}

/// The parameter table is served whole, and the OpenAPI document's benchmark keys are
/// the table's.
#[tokio::test]
async fn the_parameter_table_is_served_and_matches_openapi()
-> Result<(), Box<dyn std::error::Error>> {
    let app = app(Limits::default());
    let (status, body) = get(&app, "/api/parameters").await?;
    assert_eq!(status, StatusCode::OK);
    let benchmark = body["benchmark"].as_array().ok_or("benchmark")?;
    assert_eq!(benchmark.len(), 26);
    assert_eq!(body["jbike6"].as_array().map(Vec::len), Some(51));
    assert_eq!(benchmark[2]["key"], "lam");
    assert_eq!(benchmark[12]["linear"], false); // IByy
    let (_, doc) = get(&app, "/api/openapi.json").await?;
    let required = doc["components"]["schemas"]["BenchmarkParameters"]["required"]
        .as_array()
        .ok_or("required")?;
    let keys: Vec<&Value> = benchmark.iter().map(|p| &p["key"]).collect();
    assert_eq!(required.iter().collect::<Vec<_>>(), keys);
    // Which JBike6 entries feed each benchmark key: every benchmark key has some, and each is
    // a key of the JBike6 table (a misspelt one would flag nothing in the page's form).
    let sources = body["jbike6_sources"].as_object().ok_or("jbike6_sources")?;
    let jbike6_keys: Vec<&Value> = body["jbike6"]
        .as_array()
        .ok_or("jbike6")?
        .iter()
        .map(|p| &p["key"])
        .collect();
    assert_eq!(sources.len(), keys.len());
    for key in &keys {
        let key = key.as_str().ok_or("key")?;
        let names = sources[key]
            .as_array()
            .ok_or(format!("no sources for {key}"))?;
        assert!(!names.is_empty(), "{key}");
        for name in names {
            assert!(
                jbike6_keys.contains(&name),
                "{key} <- {name}: not a JBike6 key"
            );
        }
    }
    assert_eq!(sources["mB"], json!(["mrider", "mframe", "mrack"]));
    assert_eq!(sources["IRyy"], json!(["Irearwheel(3)", "Drearwheel"]));
    Ok(())
}

/// Sensitivities and sigmas over the API; warnings in validate; NaN refused by parse.
#[tokio::test]
async fn sensitivity_warnings_and_nan() -> Result<(), Box<dyn std::error::Error>> {
    let app = app(Limits::default());
    let mut bike = preset_json("benchmark")?;
    bike["benchmark"]["c"] = json!({"value": 0.08, "sigma": 0.001});
    let (status, body) = post(
        &app,
        "/api/sensitivity",
        &json!({"bike": bike, "range": {"lo": 0, "hi": 10}, "speed": 5}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    let trail = body["parameters"]
        .as_array()
        .ok_or("parameters")?
        .iter()
        .find(|p| p["key"] == "c")
        .ok_or("c")?;
    assert!(approx(&trail["weave_speed"], 11.48, 0.01), "{trail}");
    assert!(body["weave_speed_sigma"].as_f64().unwrap_or(0.0) > 0.011);
    let mut odd = preset_json("benchmark")?;
    odd["benchmark"]["IByy"] = json!(13.0);
    let (status, body) = post(&app, "/api/bike/validate", &json!({"bike": odd})).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["warnings"][0]["field"], "IByy");
    assert_eq!(body["warnings"][0]["severity"], "warning");
    let text =
        write(&presets::find("benchmark")?.bicycle(), Format::Toml)?.replacen("0.08", "nan", 1);
    let (status, body) = post(
        &app,
        "/api/bike/parse",
        &json!({"text": text, "format": "toml"}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["field"], "c");
    let (status, body) = post(
        &app,
        "/api/bike/parse",
        &json!({"text": "w=1.02\nlam=pi/10\n", "format": "auto", "file_name": "BenchmarkPar.txt"}),
    )
    .await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["kind"], "parse");
    Ok(())
}

/// The OpenAPI document against the router itself: the routes declared in `app()` (read from
/// its source) are exactly the documented paths and methods, every documented operation is
/// answered by a handler (not the JSON 404 or 405 fallbacks), and every other method on a
/// documented path is refused with 405.
#[tokio::test]
async fn openapi_describes_exactly_the_routes_the_router_serves() -> TestResult {
    let app = app(Limits::default());
    let (_, doc) = get(&app, "/api/openapi.json").await?;
    let mut documented: Vec<(String, String)> = Vec::new();
    for (path, item) in doc["paths"].as_object().ok_or("paths")? {
        for method in item.as_object().ok_or("an operation")?.keys() {
            documented.push((path.clone(), method.to_uppercase()));
        }
    }
    documented.sort();
    // The rows `get("/api/...", handler),` and `post(...)` of api.rs's ROUTES, the one table
    // the router is built from.
    let source = include_str!("../src/api.rs");
    let mut routed: Vec<(String, String)> = Vec::new();
    for line in source.lines() {
        let line = line.trim();
        let (method, rest) = if let Some(rest) = line.strip_prefix("get(\"") {
            ("GET", rest)
        } else if let Some(rest) = line.strip_prefix("post(\"") {
            ("POST", rest)
        } else {
            continue;
        };
        if let Some((path, _)) = rest.split_once('"')
            && path.starts_with("/api/")
        {
            routed.push((path.to_string(), method.to_string()));
        }
    }
    routed.sort();
    assert_eq!(routed, documented, "router vs openapi.json");
    for (path, method) in &documented {
        let concrete = path.replace("{name}", "benchmark");
        let method = Method::from_bytes(method.as_bytes())?;
        let body = (method == Method::POST).then(|| "{}".to_string());
        let (status, _, text) = send(&app, method.clone(), &concrete, body).await?;
        assert_ne!(
            status,
            StatusCode::METHOD_NOT_ALLOWED,
            "{method} {path}: {text}"
        );
        let kind = serde_json::from_str::<Value>(&text)
            .ok()
            .and_then(|v| v["error"]["kind"].as_str().map(str::to_string));
        assert_ne!(
            kind.as_deref(),
            Some("not_found"),
            "{method} {path}: {text}"
        );
        for other in [Method::GET, Method::POST, Method::PUT, Method::DELETE] {
            let listed = documented
                .iter()
                .any(|(p, m)| p == path && *m == other.as_str());
            if !listed {
                let (status, _, _) = send(&app, other.clone(), &concrete, None).await?;
                assert_eq!(status, StatusCode::METHOD_NOT_ALLOWED, "{other} {path}");
            }
        }
    }
    Ok(())
}

/// The security headers `whipple serve` sends: `nosniff` on every answer, API and page alike;
/// the page and its assets with a content security policy that allows scripts only from the
/// server itself and forbids framing.
#[tokio::test]
async fn security_headers_are_sent() -> TestResult {
    let app = app(Limits::default());
    // The assets under the content-hashed names the page gives them.
    let (_, _, html) = send(&app, Method::GET, "/", None).await?;
    let named = |ext: &str| {
        html.split('"')
            .find(|s| s.starts_with("/assets/app-") && s.ends_with(ext))
            .map(str::to_string)
            .ok_or(format!("the page names no /assets/app-*{ext}"))
    };
    let (script, style) = (named(".js")?, named(".css")?);
    for path in ["/", &script, &style, "/api/health", "/api/nothing"] {
        let request = Request::builder().uri(path).body(Body::empty())?;
        let response = app.clone().oneshot(request).await?;
        let headers = response.headers();
        assert_eq!(
            headers
                .get(header::X_CONTENT_TYPE_OPTIONS)
                .and_then(|v| v.to_str().ok()),
            Some("nosniff"),
            "{path}"
        );
        if !path.starts_with("/api/") {
            let csp = headers
                .get(header::CONTENT_SECURITY_POLICY)
                .and_then(|v| v.to_str().ok())
                .unwrap_or_default();
            for rule in [
                "default-src 'self'",
                "script-src 'self'",
                "object-src 'none'",
                "frame-ancestors 'none'",
                "base-uri 'none'",
            ] {
                assert!(csp.contains(rule), "{path}: {csp}");
            }
            assert!(!csp.contains("unsafe-eval"), "{path}: {csp}");
        }
    }
    Ok(())
}

/// A request body naming a key twice was read with the last value winning (serde_json's rule);
/// it is refused with 422 naming the key, as a parameter file is.
#[tokio::test]
async fn a_duplicate_json_key_in_a_body_is_refused() -> TestResult {
    let app = app(Limits::default());
    let bike = preset_json("benchmark")?.to_string();
    for text in [
        format!(r#"{{"bike": {bike}, "range": [0, 10], "range": [0, 20]}}"#),
        bike.replacen(r#""w":"#, r#""w": 2.0, "w":"#, 1),
    ] {
        let body = if text.starts_with(r#"{"bike""#) {
            text
        } else {
            format!(r#"{{"bike": {text}}}"#)
        };
        let (status, _, answer) = send(&app, Method::POST, "/api/speeds", Some(body)).await?;
        let answer: Value = serde_json::from_str(&answer)?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{answer}");
        assert_eq!(answer["error"]["kind"], "invalid_request", "{answer}");
        let field = answer["error"]["field"].as_str().unwrap_or_default();
        assert!(field == "range" || field == "w", "{answer}");
    }
    // The same body without the repetition is answered.
    let (status, _) = post(
        &app,
        "/api/speeds",
        &json!({"bike": preset_json("benchmark")?}),
    )
    .await?;
    assert_eq!(status, StatusCode::OK);
    Ok(())
}

/// A step beyond RK4's stability bound for the fastest mode at the run's speed is a
/// 422 naming `dt` and the step to use (it was a 200 with the outcome `fell`); a step inside
/// it runs as before.
#[tokio::test]
async fn a_step_too_large_is_422_naming_the_step_to_use() -> TestResult {
    let app = app(Limits::default());
    let coarse = simulation(json!({"duration": 10.0, "dt": 0.25}))?;
    let (status, body) = post(&app, "/api/simulate", &coarse).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    let error = &body["error"];
    assert_eq!(error["kind"], "step_too_large", "{body}");
    assert_eq!(error["field"], "dt", "{body}");
    assert_eq!(error["value"], 0.25, "{body}");
    for text in [&error["message"], &error["rule"]] {
        assert!(
            text.as_str().is_some_and(|t| t.contains("use dt <= 0.05")),
            "{body}"
        );
    }
    let fine = simulation(json!({"dt": 0.05}))?;
    let (status, body) = post(&app, "/api/simulate", &fine).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "completed", "{body}");
    Ok(())
}

/// A turn whose rear normal force is negative (0.5 m at 5 m/s: −1448 N) was
/// answered as a turn; a radius of 1e200 as a non-finite result. Both are 422 naming `radius`.
#[tokio::test]
async fn turns_lifting_a_wheel_or_past_the_radius_bound_are_422() -> TestResult {
    let app = app(Limits::default());
    let bike = preset_json("benchmark")?;
    let turn = |radius: f64| json!({"bike": bike.clone(), "speed": 5.0, "radius": radius});
    let (status, body) = post(&app, "/api/turn", &turn(0.5)).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["kind"], "no_steady_turn", "{body}");
    assert_eq!(body["error"]["field"], "radius", "{body}");
    assert!(
        body["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("rear wheel's normal force would be -1448.")),
        "{body}"
    );
    let (status, body) = post(&app, "/api/turn", &turn(1e200)).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
    assert_eq!(body["error"]["kind"], "invalid_argument", "{body}");
    assert_eq!(body["error"]["field"], "radius", "{body}");
    Ok(())
}

/// Issue 28, item 13: a file without a `name` is named after the file without the parameter
/// set's suffix, as BicycleParameters names it and as the CLI and Python do (one function in
/// the library): `FisherBenchmark.txt` is `Fisher`; a file with a `name` keeps it.
#[tokio::test]
async fn a_parsed_file_is_named_without_the_parameter_sets_suffix() -> TestResult {
    let app = app(Limits::default());
    let mut fisher = presets::find("fisher")?.bicycle();
    fisher.name = None;
    let text = write(&fisher, Format::BicycleParametersTxt)?;
    for (file_name, expected) in [
        ("FisherBenchmark.txt", json!("Fisher")),
        (
            "bicycles/Fisher/RawData/FisherMeasured.txt",
            json!("Fisher"),
        ),
        ("Benchmark.txt", json!("Benchmark")),
    ] {
        let (status, body) = post(
            &app,
            "/api/bike/parse",
            &json!({"text": text, "format": "auto", "file_name": file_name}),
        )
        .await?;
        assert_eq!(status, StatusCode::OK, "{body}");
        assert_eq!(body["bike"]["name"], expected, "{file_name}");
    }
    Ok(())
}

/// The leaning rider (`rider`): Jason's upper body split off the Schwinn Crown's rider, a
/// 20 N m pulse for 0.5 s about a stiff, damped hinge at 5 m/s. Five poses per frame, the
/// upper body at Jason's place at the start, leaning right under the torque while the bicycle
/// leans left (the reaction on the rear frame); the run completes.
#[tokio::test]
async fn simulate_with_the_leaning_rider() -> TestResult {
    let app = app(Limits::default());
    let rider = json!({"hinge_stiffness": 800.0, "hinge_damping": 50.0, "torque": 20.0, "torque_duration": 0.5});
    let request = simulation(
        json!({"bike": preset_json("schwinn-crown")?, "speed": 5.0, "lean_rate": 0.0, "rider": rider}),
    )?;
    let (status, body) = post(&app, "/api/simulate", &request).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "completed", "{}", body["outcome"]);
    let upper = &body["geometry"]["upper_body"];
    assert!(approx(&upper["mass"], 48.816, 1e-12), "{upper}");
    assert!(approx(&upper["hinge_stiffness"], 800.0, 0.0));
    let frames = body["frames"].as_array().ok_or("frames")?;
    let first = &frames[0];
    assert_eq!(first["bodies"].as_array().map(Vec::len), Some(5));
    let g = &first["bodies"][4]["position"];
    // Jason's upper body: xG 0.2312, zG −1.2830 m (single precision in the frames).
    assert!(
        approx(&g[0], 0.231_223_5, 1e-6)
            && approx(&g[1], 0.0, 1e-6)
            && approx(&g[2], -1.283_035, 1e-6),
        "{g}"
    );
    let at = |t: f64| {
        frames
            .iter()
            .find(|f| f["t"].as_f64().is_some_and(|ft| ft >= t))
    };
    let half = at(0.5).ok_or("a frame at 0.5 s")?;
    let (rider_lean, lean) = (
        half["rider_lean"].as_f64().ok_or("rider_lean")?,
        half["lean"].as_f64().ok_or("lean")?,
    );
    assert!(
        rider_lean > 0.0 && lean < 0.0,
        "rider {rider_lean}, bicycle {lean}"
    );
    // The lean model's reaction forces carry the rider's weight: both normal forces together.
    let weight = first["rear_force"]["normal"].as_f64().ok_or("n")?
        + first["front_force"]["normal"].as_f64().ok_or("n")?;
    let bike = whipple::presets::find("schwinn-crown")?
        .bicycle()
        .benchmark()?;
    let total = bike.m_r + bike.m_b + bike.m_h + bike.m_f;
    assert!(
        (weight - total * bike.g).abs() < 1e-6 * weight,
        "{weight} vs {}",
        total * bike.g
    );
    Ok(())
}

/// With the hinge free the upper body falls over it: the run ends and says so. With a
/// stiff undamped hinge and no torque the energy is conserved.
#[tokio::test]
async fn the_leaning_rider_falls_or_keeps_its_energy() -> TestResult {
    let app = app(Limits::default());
    let bike = preset_json("schwinn-crown")?;
    let free = simulation(
        json!({"bike": bike, "speed": 5.0, "lean_rate": 0.0, "duration": 5.0, "rider": {"lean_deg": 2.0}}),
    )?;
    let (status, body) = post(&app, "/api/simulate", &free).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(
        body["outcome"]["kind"], "upper_body_fell",
        "{}",
        body["outcome"]
    );
    let message = body["outcome"]["message"].as_str().unwrap_or("");
    assert!(
        message.contains("upper body fell across the bicycle"),
        "{message}"
    );
    let stiff = simulation(
        json!({"bike": bike, "speed": 5.0, "lean_rate": 0.0, "duration": 2.0, "integrator": "adaptive", "rtol": 1e-10, "rider": {"lean_deg": 3.0, "hinge_stiffness": 1500.0}}),
    )?;
    let (status, body) = post(&app, "/api/simulate", &stiff).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    let frames = body["frames"].as_array().ok_or("frames")?;
    let energy: Vec<f64> = frames.iter().filter_map(|f| f["energy"].as_f64()).collect();
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(
        drift < 1e-6 * energy[0].abs(),
        "drift {drift} of {}",
        energy[0]
    );
    assert!(
        frames
            .iter()
            .any(|f| f["rider_lean"].as_f64().is_some_and(|r| r < 0.0)),
        "the upper body swings back"
    );
    Ok(())
}

/// What the leaning rider refuses, each naming its field.
#[tokio::test]
async fn the_leaning_rider_refuses_naming_the_field() -> TestResult {
    let app = app(Limits::default());
    let schwinn = preset_json("schwinn-crown")?;
    let cases = [
        (
            json!({"bike": preset_json("benchmark")?, "rider": {}}),
            "bike",
            "does not fit",
        ),
        (
            json!({"bike": preset_json("browser")?, "rider": {}}),
            "bike",
            "lighter",
        ),
        (
            json!({"bike": schwinn, "rider": {}, "steer_torque": "2*foo"}),
            "steer_torque",
            "foo",
        ),
        (
            json!({"bike": schwinn, "rider": {}, "from_turn": true}),
            "from_turn",
            "rigid rider",
        ),
        (
            json!({"bike": schwinn, "rider": {"lean_deg": 95.0}}),
            "rider.lean_deg",
            "below 90",
        ),
        (
            json!({"bike": schwinn, "rider": {"hinge_stiffness": -1.0}}),
            "rider.hinge_stiffness",
            "passive",
        ),
        (
            json!({"bike": schwinn, "rider": {"torque_duration": -1.0}}),
            "rider.torque_duration",
            "not negative",
        ),
    ];
    for (fields, field, words) in cases {
        let (status, body) = post(&app, "/api/simulate", &simulation(fields.clone())?).await?;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{fields}: {body}");
        assert_eq!(body["error"]["field"], field, "{body}");
        let message = body["error"]["message"].as_str().unwrap_or("");
        assert!(message.contains(words), "{message}");
    }
    let (status, body) = post(
        &app,
        "/api/simulate",
        &simulation(json!({"bike": schwinn, "rider": {"hinge": 1}}))?,
    )
    .await?;
    assert!(status.is_client_error(), "{body}");
    Ok(())
}

/// The rider's steer torque acts on the leaning rider's bicycle as on the rigid one (the same
/// loop): steering into the lean holds up the Schwinn Crown at 3 m/s, below its weave speed,
/// where hands free it falls; the server's step limit ends a run as without the rider.
#[tokio::test]
async fn the_leaning_riders_bicycle_takes_the_steer_torque() -> TestResult {
    let app = app(Limits::default());
    let bike = preset_json("schwinn-crown")?;
    let rider = json!({"hinge_stiffness": 800.0, "hinge_damping": 50.0});
    let run = |torque: Value| {
        simulation(
            json!({"bike": bike, "speed": 3.0, "lean_rate": 0.3, "duration": 8.0, "rider": rider, "steer_torque": torque}),
        )
    };
    let (status, body) = post(&app, "/api/simulate", &run(json!(0.0))?).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    // Hands free it falls (its front wheel lifting on the way down, which ends the run first).
    let kind = body["outcome"]["kind"].as_str().unwrap_or("");
    assert!(
        kind == "fell" || kind == "wheel_lifted",
        "{}",
        body["outcome"]
    );
    assert!(
        body["outcome"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("fall") || m.contains("fell")),
        "{}",
        body["outcome"]
    );
    let (status, body) = post(
        &app,
        "/api/simulate",
        &run(json!("10*lean + 20*lean_rate"))?,
    )
    .await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "completed", "{}", body["outcome"]);
    let limited = whipple_web::app(Limits {
        max_sim_steps: 30,
        ..Limits::default()
    });
    let request = simulation(
        json!({"bike": bike, "rider": rider, "integrator": "adaptive", "rtol": 1e-12, "duration": 2.0}),
    )?;
    let (status, body) = post(&limited, "/api/simulate", &request).await?;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["outcome"]["kind"], "step_limit", "{}", body["outcome"]);
    Ok(())
}

/// `answer` (the API without a server, which the static site's WebAssembly module runs) gives
/// the router's status and bytes for every kind of request: fixed data, work, each error.
#[tokio::test]
async fn answered_without_a_server_as_through_the_router() -> TestResult {
    let limits = Limits::default();
    let app = app(limits);
    let bike = preset_json("benchmark")?;
    let measured = preset_json("browser")?;
    let requests: Vec<(Method, &str, Option<String>)> = vec![
        (Method::GET, "/api/health", None),
        (Method::GET, "/api/presets", None),
        (Method::GET, "/api/presets/benchmark", None),
        (Method::GET, "/api/presets/schwinn%2Dcrown", None),
        (Method::GET, "/api/presets/nothing", None),
        (Method::GET, "/api/presets/%ff", None),
        (Method::GET, "/api/parameters", None),
        (Method::GET, "/api/measure/samples", None),
        (Method::GET, "/api/openapi.json", None),
        (Method::GET, "/api/nowhere", None),
        (Method::GET, "/api/eigen", None),
        (Method::POST, "/api/presets", Some("{}".into())),
        (Method::POST, "/api/eigen", Some("{".into())),
        (
            Method::POST,
            "/api/eigen",
            Some(json!({"bike": bike}).to_string()),
        ),
        (
            Method::POST,
            "/api/eigen",
            Some(
                json!({"bike": bike, "speeds": {"start": 0, "stop": 10, "step": 0.01}}).to_string(),
            ),
        ),
        (
            Method::POST,
            "/api/eigen",
            Some(
                json!({"bike": bike, "speeds": {"start": 0, "stop": 1e9, "step": 1e-6}})
                    .to_string(),
            ),
        ),
        (
            Method::POST,
            "/api/speeds",
            Some(json!({"bike": measured}).to_string()),
        ),
        (
            Method::POST,
            "/api/bike/validate",
            Some(json!({"bike": bike}).to_string()),
        ),
        (
            Method::POST,
            "/api/map",
            Some(json!({"bike": bike, "x": "trail=0:0.2:21", "y": "lambda=0:0.6:11"}).to_string()),
        ),
        (
            Method::POST,
            "/api/simulate",
            Some(json!({"bike": bike, "speed": 4.6, "lean_deg": 5, "duration": 1}).to_string()),
        ),
        (
            Method::POST,
            "/api/sensitivity",
            Some(json!({"bike": measured}).to_string()),
        ),
    ];
    for (method, path, body) in requests {
        let (status, content_type, text) = send(&app, method.clone(), path, body.clone()).await?;
        let answered = whipple_web::answer(
            method.as_str(),
            path,
            body.as_deref().unwrap_or("").as_bytes(),
            &limits,
            std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)),
        );
        assert_eq!(content_type, "application/json", "{method} {path}");
        assert_eq!(answered.status, status.as_u16(), "{method} {path}: {text}");
        let without = String::from_utf8(answered.body)?;
        if path == "/api/presets/%ff" {
            // axum's own words for the undecodable segment; the kind and status agree.
            let (a, b): (Value, Value) = (
                serde_json::from_str(&text)?,
                serde_json::from_str(&without)?,
            );
            assert_eq!(a["error"]["kind"], b["error"]["kind"]);
            continue;
        }
        assert!(
            text == without,
            "{method} {path}: the bodies differ:\n{text}\n{without}"
        );
    }
    Ok(())
}

/// A request's answer told line by line: the lines of an `Accept: application/x-ndjson`
/// request to `path`, inflated where `gzip`, with the response's status and content type.
async fn lines(
    app: &Router,
    path: &str,
    body: &str,
    gzip: bool,
) -> Result<(StatusCode, String, Vec<Value>), Box<dyn std::error::Error>> {
    use std::io::Read;
    let mut request = Request::builder()
        .method(Method::POST)
        .uri(path)
        .header(header::CONTENT_TYPE, "application/json")
        .header(
            header::ACCEPT,
            "application/x-ndjson, application/json;q=0.5",
        );
    if gzip {
        request = request.header(header::ACCEPT_ENCODING, "gzip");
    }
    let response = app
        .clone()
        .oneshot(request.body(Body::from(body.to_string()))?)
        .await?;
    let status = response.status();
    let content_type = response.headers()[header::CONTENT_TYPE]
        .to_str()?
        .to_string();
    let zipped = response.headers().get(header::CONTENT_ENCODING).is_some();
    assert_eq!(zipped, gzip && status == StatusCode::OK);
    let bytes = response.into_body().collect().await?.to_bytes();
    let mut text = String::new();
    if zipped {
        flate2::read::GzDecoder::new(&bytes[..]).read_to_string(&mut text)?;
    } else {
        text = String::from_utf8(bytes.to_vec())?;
    }
    if !content_type.starts_with("application/x-ndjson") {
        return Ok((status, content_type, vec![serde_json::from_str(&text)?]));
    }
    assert!(text.ends_with('\n'), "every line ends with a newline");
    let values = text
        .lines()
        .map(serde_json::from_str)
        .collect::<Result<Vec<Value>, _>>()?;
    Ok((status, content_type, values))
}

/// Asked line by line, a map of three chunks of designs tells how far it is (the designs done,
/// growing, of the whole), then answers exactly what it answers in one piece; with gzip too.
#[tokio::test]
async fn a_map_told_line_by_line_tells_its_progress_then_the_same_answer() -> TestResult {
    let app = app(Limits::default());
    let request =
        json!({"bike": preset_json("benchmark")?, "x": "trail=0:0.2:257", "y": "w=0.9:1.2:256"});
    let (status, plain) = post(&app, "/api/map", &request).await?;
    assert_eq!(status, StatusCode::OK);
    let total = 257 * 256;
    for gzip in [false, true] {
        let (status, content_type, told) =
            lines(&app, "/api/map", &request.to_string(), gzip).await?;
        assert_eq!(
            (status, content_type.as_str()),
            (StatusCode::OK, "application/x-ndjson")
        );
        let (last, progress) = told.split_last().ok_or("no line")?;
        assert_eq!(last["status"], 200);
        assert_eq!(last["answer"], plain, "the same answer as in one piece");
        assert!(
            !progress.is_empty(),
            "the first chunk's designs are told before the answer"
        );
        let mut before = 0;
        for line in progress {
            let done = line["progress"][0].as_u64().ok_or("done")?;
            assert_eq!(line["progress"][1], total);
            assert!(done > before && done <= total, "{line} after {before}");
            assert!(
                done == total || done % (1 << 15) == 0,
                "chunks of 32768 designs: {line}"
            );
            before = done;
        }
    }
    Ok(())
}

/// Asked line by line, a request refused before any work is a plain JSON error; work that ends
/// in an error says so in the last line, with the status it would have had.
#[tokio::test]
async fn an_error_told_line_by_line() -> TestResult {
    let app = app(Limits::default());
    let bad = json!({"bike": preset_json("benchmark")?, "x": "trail=0:0.2:0", "y": "w=0.9:1.2:3"});
    let (status, content_type, told) = lines(&app, "/api/map", &bad.to_string(), false).await?;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(content_type, "application/json");
    assert_eq!(told[0]["error"]["field"], "x");
    let slow = app_with_timeout();
    let (status, _, told) = lines(&slow, "/api/eigen", &heavy()?.to_string(), true).await?;
    assert_eq!(status, StatusCode::OK);
    let last = told.last().ok_or("no line")?;
    assert_eq!(last["status"], 503);
    assert_eq!(last["error"]["kind"], "timeout");
    assert!(
        last["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("fewer speeds"))
    );
    Ok(())
}

fn app_with_timeout() -> Router {
    app(Limits {
        compute_timeout: Duration::from_micros(1),
        ..Limits::default()
    })
}
