//! Bounded loads on loopback. 2,000 requests, 64 at a time, across the endpoints the page
//! calls most (and a few simulations): every answer must be right. And
//! small requests while six clients loop design maps: none refused, none queued behind the
//! maps. Each prints its figures (run with `--nocapture`; `--release` for those quoted in
//! BENCHMARKS.md). The two run one after the other, not together.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use axum::body::Bytes;
use http_body_util::{BodyExt, Full};
use hyper::{Method, Request, StatusCode};
use hyper_util::client::legacy::Client;
use hyper_util::rt::TokioExecutor;
use serde_json::{Value, json};
use tokio::sync::Semaphore;
use whipple::advanced::io::{Format, write};
use whipple::presets;
use whipple_web::{ServeOptions, Server};

const REQUESTS: usize = 2_000;
const CONCURRENCY: usize = 64;

type TestResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// Held by each test for its whole run: the loads must not overlap.
static ONE_AT_A_TIME: tokio::sync::Mutex<()> = tokio::sync::Mutex::const_new(());

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_thousand_requests_sixty_four_at_a_time() -> TestResult {
    let _alone = ONE_AT_A_TIME.lock().await;
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

/// Clients looping design maps, each map 500 × 500 = 250,000 designs (the most one request may ask for).
const MAP_CLIENTS: usize = 6;
/// At most this many maps per client (the loops end as soon as the probes are done).
const MAPS_PER_CLIENT: usize = 200;
/// Clients sending small requests one after the other, and how many each sends.
const PROBE_CLIENTS: usize = 2;
const PROBES_PER_CLIENT: usize = 50;
/// The bound on the small requests' p99: generous, a correctness bound, not a benchmark
/// (when the maps and the small requests shared one queue, the small ones waited 8–9 s behind
/// the maps, or got 503).
const P99_BOUND: Duration = Duration::from_secs(3);

/// The `q` quantile (0–1) of sorted durations, nearest rank.
fn quantile(sorted: &[Duration], q: f64) -> Duration {
    let rank = ((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len().max(1));
    sorted.get(rank - 1).copied().unwrap_or_default()
}

/// While six clients loop design maps, `/api/speeds` and
/// `/api/bike/validate` (about a millisecond of work each) are all answered, right, with a
/// p99 latency below a few seconds; the maps may be told `busy` (503 with Retry-After) past
/// their budget, never the small requests.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn small_requests_stay_quick_while_maps_run() -> TestResult {
    let _alone = ONE_AT_A_TIME.lock().await;
    let server = Server::bind(&ServeOptions {
        port: 0,
        ..ServeOptions::default()
    })
    .await?;
    let base = format!("http://{}", server.local_addr());
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let serving = tokio::spawn(server.serve_until(async {
        let _ = stopped.await;
    }));
    let crown: Value = serde_json::from_str(&write(
        &presets::find("schwinn-crown")?.bicycle(),
        Format::Json,
    )?)?;
    let map = Bytes::from(
        json!({
            "bike": crown,
            "x": "trail=-0.05:0.2:500",
            "y": "head_angle_deg=60:85:500",
        })
        .to_string(),
    );
    let validate = Bytes::from(json!({ "bike": crown }).to_string());
    let speeds = Bytes::from(json!({ "bike": crown }).to_string());
    let client = Client::builder(TokioExecutor::new()).build_http::<Full<Bytes>>();
    let post = |path: &str, body: Bytes| {
        Request::builder()
            .method(Method::POST)
            .uri(format!("{base}{path}"))
            .header("content-type", "application/json")
            .body(Full::new(body))
    };

    // The map loops: each counts its answers; the first answer wakes the probes.
    let probes_done = Arc::new(AtomicBool::new(false));
    let maps_ok = Arc::new(AtomicUsize::new(0));
    let maps_busy = Arc::new(AtomicUsize::new(0));
    let first_map = Arc::new(tokio::sync::Notify::new());
    // Maps asked for and not yet answered (read by the probes: the maps must be under way).
    let maps_in_flight = Arc::new(AtomicUsize::new(0));
    let mut loops = tokio::task::JoinSet::new();
    for _ in 0..MAP_CLIENTS {
        let (client, done, ok, busy, first, in_flight) = (
            client.clone(),
            probes_done.clone(),
            maps_ok.clone(),
            maps_busy.clone(),
            first_map.clone(),
            maps_in_flight.clone(),
        );
        let (uri, map) = (format!("{base}/api/map"), map.clone());
        loops.spawn(async move {
            for _ in 0..MAPS_PER_CLIENT {
                if done.load(Ordering::Relaxed) {
                    break;
                }
                let request = Request::builder()
                    .method(Method::POST)
                    .uri(&uri)
                    .header("content-type", "application/json")
                    .body(Full::new(map.clone()))?;
                in_flight.fetch_add(1, Ordering::Relaxed);
                let response = client.request(request).await?;
                let status = response.status();
                let retry_after = response.headers().contains_key("retry-after");
                let bytes = response.into_body().collect().await?.to_bytes();
                in_flight.fetch_sub(1, Ordering::Relaxed);
                match status {
                    StatusCode::OK if bytes.starts_with(b"{\"x\":") => {
                        ok.fetch_add(1, Ordering::Relaxed);
                        first.notify_one();
                    }
                    StatusCode::SERVICE_UNAVAILABLE if retry_after => {
                        busy.fetch_add(1, Ordering::Relaxed);
                        first.notify_one();
                    }
                    other => {
                        return Err(format!(
                            "a map got {other}: {}",
                            String::from_utf8_lossy(&bytes[..bytes.len().min(300)])
                        )
                        .into());
                    }
                }
            }
            Ok::<(), Box<dyn std::error::Error + Send + Sync>>(())
        });
    }
    // Probe once the maps are under way: one answered (a condition, not a sleep).
    tokio::time::timeout(Duration::from_secs(120), first_map.notified()).await?;
    let maps_before = maps_ok.load(Ordering::Relaxed);
    let probing = Instant::now();
    let mut probes = tokio::task::JoinSet::new();
    for p in 0..PROBE_CLIENTS {
        let (client, in_flight) = (client.clone(), maps_in_flight.clone());
        let requests: Vec<_> = (0..PROBES_PER_CLIENT)
            .map(|i| {
                if (i + p) % 2 == 0 {
                    ("/api/speeds", post("/api/speeds", speeds.clone()))
                } else {
                    (
                        "/api/bike/validate",
                        post("/api/bike/validate", validate.clone()),
                    )
                }
            })
            .collect();
        probes.spawn(async move {
            let mut latencies = Vec::with_capacity(requests.len());
            let mut failures = Vec::new();
            let mut fewest_maps = usize::MAX;
            for (path, request) in requests {
                fewest_maps = fewest_maps.min(in_flight.load(Ordering::Relaxed));
                let started = Instant::now();
                let response = client.request(request?).await?;
                let status = response.status();
                let bytes = response.into_body().collect().await?.to_bytes();
                latencies.push(started.elapsed());
                let body: Value = serde_json::from_slice(&bytes).unwrap_or(Value::Null);
                let right = status == StatusCode::OK
                    && match path {
                        "/api/speeds" => body["capsize_speed"]
                            .as_f64()
                            .is_some_and(|v| (v - 7.9807).abs() < 5e-4),
                        _ => body["form"] == "jbike6",
                    };
                if !right {
                    failures.push(format!("{path}: {status} {body}"));
                }
            }
            Ok::<_, Box<dyn std::error::Error + Send + Sync>>((latencies, failures, fewest_maps))
        });
    }
    let mut latencies = Vec::new();
    let mut failures = Vec::new();
    let mut fewest_maps = usize::MAX;
    while let Some(result) = probes.join_next().await {
        let (l, f, m) = result??;
        latencies.extend(l);
        failures.extend(f);
        fewest_maps = fewest_maps.min(m);
    }
    let window = probing.elapsed();
    let maps_during = maps_ok.load(Ordering::Relaxed) - maps_before;
    probes_done.store(true, Ordering::Relaxed);
    while let Some(result) = loops.join_next().await {
        result??;
    }
    let _ = stop.send(());
    serving.await??;

    latencies.sort();
    let (p50, p99, max) = (
        quantile(&latencies, 0.5),
        quantile(&latencies, 0.99),
        latencies.last().copied().unwrap_or_default(),
    );
    println!(
        "load: {} small requests (/api/speeds, /api/bike/validate; {PROBE_CLIENTS} clients) while {MAP_CLIENTS} clients looped 500 × 500 maps: p50 {:.1} ms, p99 {:.1} ms, max {:.1} ms over {:.2} s; {maps_during} maps answered meanwhile, {} maps in all, {} maps told busy, at least {fewest_maps} maps under way at each small request; {} small requests failed",
        latencies.len(),
        p50.as_secs_f64() * 1e3,
        p99.as_secs_f64() * 1e3,
        max.as_secs_f64() * 1e3,
        window.as_secs_f64(),
        maps_ok.load(Ordering::Relaxed),
        maps_busy.load(Ordering::Relaxed),
        failures.len(),
    );
    assert!(failures.is_empty(), "small requests failed: {failures:?}");
    assert_eq!(latencies.len(), PROBE_CLIENTS * PROBES_PER_CLIENT);
    // The maps really ran alongside: not a measurement of an idle server.
    assert!(
        fewest_maps >= MAP_CLIENTS / 2,
        "only {fewest_maps} maps were under way at one of the small requests"
    );
    assert!(
        p99 < P99_BOUND,
        "p99 of the small requests {p99:?} while maps run, over the bound of {P99_BOUND:?}"
    );
    Ok(())
}
