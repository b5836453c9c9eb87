//! A bounded load on loopback: 2,000 requests, 64 at a time, across the endpoints the page
//! calls most (and a few simulations); every answer must be right. Prints the throughput (run with `--nocapture`;
//! `--release` for the figure quoted in BENCHMARKS.md).

use std::sync::Arc;
use std::time::Instant;

use axum::body::Bytes;
use http_body_util::{BodyExt, Full};
use hyper::{Method, Request, StatusCode};
use hyper_util::client::legacy::Client;
use hyper_util::rt::TokioExecutor;
use serde_json::{json, Value};
use tokio::sync::Semaphore;
use whipple::parameters::io::{write, Format};
use whipple::parameters::presets;
use whipple_web::{ServeOptions, Server};

const REQUESTS: usize = 2_000;
const CONCURRENCY: usize = 64;

type TestResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_thousand_requests_sixty_four_at_a_time() -> TestResult {
    let server = Server::bind(&ServeOptions {
        port: 0,
        ..ServeOptions::default()
    })
    .await?;
    assert!(server.local_addr().ip().is_loopback());
    let base = format!("http://{}", server.local_addr());
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let serving = tokio::spawn(server.serve_until(async {
        let _ = stopped.await;
    }));

    let crown: Value = serde_json::from_str(&write(
        &presets::find("schwinn-crown")?.bicycle(),
        Format::Json,
    )?)?;
    let validate = Bytes::from(json!({ "bike": crown }).to_string());
    let eigen = Bytes::from(
        json!({"bike": crown, "speeds": {"start": 0, "stop": 10, "step": 0.1}}).to_string(),
    );
    let simulate = Bytes::from(
        json!({"bike": crown, "speed": 6.0, "lean_rate": 0.5, "duration": 1.0}).to_string(),
    );
    let client = Client::builder(TokioExecutor::new()).build_http::<Full<Bytes>>();
    let gate = Arc::new(Semaphore::new(CONCURRENCY));
    let started = Instant::now();
    let mut tasks = tokio::task::JoinSet::new();
    for i in 0..REQUESTS {
        let permit = gate.clone().acquire_owned().await?;
        let client = client.clone();
        let (method, path, body) = match i % 4 {
            // One request in 40: a 1 s simulation (1,000 RK4 steps, 61 frames).
            _ if i % 40 == 3 => (Method::POST, "/api/simulate", simulate.clone()),
            0 => (Method::GET, "/api/presets", Bytes::new()),
            1 => (Method::POST, "/api/bike/validate", validate.clone()),
            _ => (Method::POST, "/api/eigen", eigen.clone()),
        };
        let uri = format!("{base}{path}");
        tasks.spawn(async move {
            let _permit = permit;
            let request = Request::builder()
                .method(method)
                .uri(uri)
                .header("content-type", "application/json")
                .body(Full::new(body))?;
            let response = client.request(request).await?;
            let status = response.status();
            let bytes = response.into_body().collect().await?.to_bytes();
            let body: Value = serde_json::from_slice(&bytes)?;
            let ok = status == StatusCode::OK
                && match path {
                    "/api/eigen" => body["critical"]["capsize_speed"]
                        .as_f64()
                        .is_some_and(|v| (v - 7.9807).abs() < 5e-5),
                    "/api/bike/validate" => body["form"] == "jbike6",
                    "/api/simulate" => {
                        body["outcome"]["kind"] == "completed"
                            && body["frames"].as_array().is_some_and(|f| f.len() == 61)
                    }
                    _ => body.as_array().is_some_and(|a| !a.is_empty()),
                };
            Ok::<bool, Box<dyn std::error::Error + Send + Sync>>(ok)
        });
    }
    let mut good = 0;
    let mut bad = 0;
    while let Some(result) = tasks.join_next().await {
        match result? {
            Ok(true) => good += 1,
            Ok(false) | Err(_) => bad += 1,
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "load: {REQUESTS} requests ({CONCURRENCY} concurrent; 1/4 presets, 1/4 validate, 1/2 eigen with 101 speeds, 1/40 of them 1 s simulations instead) in {seconds:.2} s: {:.0} requests/s, {bad} errors",
        REQUESTS as f64 / seconds
    );
    assert_eq!((good, bad), (REQUESTS, 0));
    let _ = stop.send(());
    serving.await??;
    Ok(())
}
