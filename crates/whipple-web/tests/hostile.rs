//! The server under hostile clients: slow and idle connections are closed, work runs
//! on the bounded computing pool, every error is JSON, and the OpenAPI document is valid 3.0.

use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::{Method, Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tower::ServiceExt;
use whipple_web::{Limits, ServeOptions, Server, app};

type TestResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// A real server on a loopback port with these limits; returns its address and a stopper.
async fn start(
    limits: Limits,
) -> Result<
    (std::net::SocketAddr, tokio::sync::oneshot::Sender<()>),
    Box<dyn std::error::Error + Send + Sync>,
> {
    let server = Server::bind(&ServeOptions {
        port: 0,
        limits,
        ..ServeOptions::default()
    })
    .await?;
    let address = server.local_addr();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    tokio::spawn(server.serve_until(async {
        let _ = stopped.await;
    }));
    Ok((address, stop))
}

/// Reads until the server closes the connection; the time that took, or `None` past `within`.
async fn closed_within(
    stream: &mut tokio::net::tcp::OwnedReadHalf,
    within: Duration,
) -> Option<Duration> {
    let started = Instant::now();
    let mut buffer = [0u8; 1024];
    tokio::time::timeout(within, async {
        loop {
            match stream.read(&mut buffer).await {
                Ok(0) | Err(_) => break,
                Ok(_) => continue,
            }
        }
    })
    .await
    .ok()
    .map(|()| started.elapsed())
}

/// One byte every 5 s held a connection for over 70 s: the headers must come within the limit.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_trickling_its_headers_is_disconnected() -> TestResult {
    let (address, _stop) = start(Limits {
        header_timeout: Duration::from_millis(300),
        ..Limits::default()
    })
    .await?;
    let (mut reader, mut writer) = TcpStream::connect(address).await?.into_split();
    let trickle = tokio::spawn(async move {
        writer.write_all(b"GET /api/health HTTP/1.1\r\n").await.ok();
        for _ in 0..100 {
            if writer.write_all(b"X").await.is_err() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    });
    let closed = closed_within(&mut reader, Duration::from_secs(4)).await;
    trickle.abort();
    assert!(
        closed.is_some(),
        "the trickling connection was still open after 4 s"
    );
    Ok(())
}

/// A connection that sends nothing at all is closed too.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_idle_connection_is_closed() -> TestResult {
    let (address, _stop) = start(Limits {
        idle_timeout: Duration::from_millis(300),
        ..Limits::default()
    })
    .await?;
    let (mut reader, _writer) = TcpStream::connect(address).await?.into_split();
    let closed = closed_within(&mut reader, Duration::from_secs(4)).await;
    assert!(
        closed.is_some(),
        "the idle connection was still open after 4 s"
    );
    Ok(())
}

/// A well-behaved client on the same server is answered, keep-alive included.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_prompt_client_is_answered_on_a_kept_alive_connection() -> TestResult {
    let (address, _stop) = start(Limits {
        header_timeout: Duration::from_secs(2),
        idle_timeout: Duration::from_secs(2),
        ..Limits::default()
    })
    .await?;
    let mut stream = TcpStream::connect(address).await?;
    for _ in 0..2 {
        stream
            .write_all(b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            .await?;
        let mut buffer = vec![0u8; 4096];
        let n = tokio::time::timeout(Duration::from_secs(4), stream.read(&mut buffer)).await??;
        let text = String::from_utf8_lossy(&buffer[..n]);
        assert!(text.starts_with("HTTP/1.1 200"), "{text}");
        assert!(text.contains("\"status\":\"ok\""), "{text}");
    }
    Ok(())
}

/// Past `max_connections`, a new connection waits until one closes, then is served.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn connections_past_the_limit_wait_for_a_free_slot() -> TestResult {
    let (address, _stop) = start(Limits {
        max_connections: 1,
        ..Limits::default()
    })
    .await?;
    let first = TcpStream::connect(address).await?;
    let mut second = TcpStream::connect(address).await?;
    second
        .write_all(b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
        .await?;
    let mut buffer = vec![0u8; 4096];
    let waiting = tokio::time::timeout(Duration::from_millis(300), second.read(&mut buffer)).await;
    assert!(
        waiting.is_err(),
        "the second connection was served past the limit"
    );
    drop(first);
    let n = tokio::time::timeout(Duration::from_secs(4), second.read(&mut buffer)).await??;
    assert!(String::from_utf8_lossy(&buffer[..n]).starts_with("HTTP/1.1 200"));
    Ok(())
}

async fn send(
    router: &axum::Router,
    method: Method,
    path: &str,
    body: String,
) -> Result<(StatusCode, Value), Box<dyn std::error::Error + Send + Sync>> {
    let request = Request::builder()
        .method(method)
        .uri(path)
        .header(header::CONTENT_TYPE, "application/json")
        .body(Body::from(body))?;
    let response = router.clone().oneshot(request).await?;
    let status = response.status();
    let bytes = response.into_body().collect().await?.to_bytes();
    Ok((status, serde_json::from_slice(&bytes)?))
}

#[tokio::test]
async fn an_oversized_body_is_413_in_json() -> TestResult {
    let router = app(Limits {
        max_body_bytes: 1000,
        ..Limits::default()
    });
    let text = "x".repeat(2000);
    for path in [
        "/api/bike/parse",
        "/api/bike/validate",
        "/api/bike/toml",
        "/api/eigen",
    ] {
        let body = json!({"text": text, "format": "toml"}).to_string();
        let (status, answer) = send(&router, Method::POST, path, body).await?;
        assert_eq!(status, StatusCode::PAYLOAD_TOO_LARGE, "{path}: {answer}");
        assert_eq!(answer["error"]["kind"], "too_large", "{path}");
    }
    Ok(())
}

/// `/api/presets/%ff` answered in plain text.
#[tokio::test]
async fn a_preset_name_that_is_not_utf8_is_answered_in_json() -> TestResult {
    let router = app(Limits::default());
    let (status, answer) = send(&router, Method::GET, "/api/presets/%ff", String::new()).await?;
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert_eq!(answer["error"]["kind"], "not_found");
    Ok(())
}

/// Parsing, validating and converting run on the bounded computing pool (so 40 large parses
/// cannot hold up `/api/health`): with a compute time limit of a microsecond they time out.
/// The file is near the body limit and the runtime has two workers, so that the parse takes
/// longer than the timer's 1 ms tick and a stalled test thread on a loaded machine (a
/// current-thread runtime answered 422 about one run in four under a load average of 9).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn parsing_runs_on_the_computing_pool() -> TestResult {
    let router = app(Limits {
        compute_timeout: Duration::from_micros(1),
        ..Limits::default()
    });
    let mut text = String::from("[benchmark]\n");
    for i in 0..45_000 {
        text.push_str(&format!("# comment line {i}\n"));
    }
    let body = json!({"text": text, "format": "toml"}).to_string();
    let (status, answer) = send(&router, Method::POST, "/api/bike/parse", body).await?;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "{answer}");
    assert_eq!(answer["error"]["kind"], "timeout");
    Ok(())
}

/// Every `$ref` in `doc` names something that exists.
fn check_refs(doc: &Value, node: &Value, at: &str, problems: &mut Vec<String>) {
    match node {
        Value::Object(map) => {
            for (key, value) in map {
                if key == "$ref" {
                    let target = value.as_str().unwrap_or("");
                    let pointer = target.trim_start_matches('#');
                    if !target.starts_with("#/") || doc.pointer(pointer).is_none() {
                        problems.push(format!("{at}: $ref {target} does not resolve"));
                    }
                }
                check_refs(doc, value, &format!("{at}/{key}"), problems);
            }
        }
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                check_refs(doc, item, &format!("{at}/{i}"), problems);
            }
        }
        _ => {}
    }
}

/// OpenAPI 3.0's schema objects: `exclusiveMinimum`/`exclusiveMaximum` are booleans (3.1's
/// numbers are invalid there) and need their `minimum`/`maximum`; `nullable` is a boolean; no
/// 3.1-only keywords.
fn check_schemas(node: &Value, at: &str, problems: &mut Vec<String>) {
    match node {
        Value::Object(map) => {
            for (exclusive, bound) in [
                ("exclusiveMinimum", "minimum"),
                ("exclusiveMaximum", "maximum"),
            ] {
                if let Some(value) = map.get(exclusive) {
                    if !value.is_boolean() {
                        problems.push(format!("{at}: {exclusive} must be a boolean in 3.0"));
                    }
                    if !map.contains_key(bound) {
                        problems.push(format!("{at}: {exclusive} without {bound}"));
                    }
                }
            }
            for only_31 in [
                "const",
                "prefixItems",
                "$defs",
                "examples",
                "unevaluatedProperties",
            ] {
                if map.contains_key(only_31) && at.contains("/schema") {
                    problems.push(format!("{at}: {only_31} is not OpenAPI 3.0"));
                }
            }
            if map.get("type").is_some_and(Value::is_array) {
                problems.push(format!("{at}: a list of types is not OpenAPI 3.0"));
            }
            for (key, value) in map {
                check_schemas(value, &format!("{at}/{key}"), problems);
            }
        }
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                check_schemas(item, &format!("{at}/{i}"), problems);
            }
        }
        _ => {}
    }
}

/// The document declared 3.0.3 but used 3.1's numeric `exclusiveMinimum` in five places, and
/// did not say that a bicycle is `benchmark` *or* `jbike6`.
#[tokio::test]
async fn the_openapi_document_is_valid_openapi_3_0() -> TestResult {
    let router = app(Limits::default());
    let (status, doc) = send(&router, Method::GET, "/api/openapi.json", String::new()).await?;
    assert_eq!(status, StatusCode::OK);
    assert!(
        doc["openapi"]
            .as_str()
            .is_some_and(|v| v.starts_with("3.0."))
    );
    for key in ["info", "paths", "components"] {
        assert!(doc.get(key).is_some(), "no {key}");
    }
    let mut problems = Vec::new();
    check_refs(&doc, &doc, "", &mut problems);
    check_schemas(&doc, "", &mut problems);
    assert!(problems.is_empty(), "{problems:#?}");
    let one_of = &doc["components"]["schemas"]["Bicycle"]["oneOf"];
    assert_eq!(
        one_of,
        &json!([{ "required": ["benchmark"] }, { "required": ["jbike6"] }])
    );
    Ok(())
}

/// One POST on a fresh connection: the status, the `Retry-After` header and the JSON body.
async fn post_raw(
    address: std::net::SocketAddr,
    path: &str,
    body: &str,
) -> Result<(u16, Option<String>, Value), Box<dyn std::error::Error + Send + Sync>> {
    let mut stream = TcpStream::connect(address).await?;
    let request = format!(
        "POST {path} HTTP/1.1\r\nHost: {address}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    );
    stream.write_all(request.as_bytes()).await?;
    let mut answer = Vec::new();
    tokio::time::timeout(Duration::from_secs(30), stream.read_to_end(&mut answer)).await??;
    let text = String::from_utf8_lossy(&answer);
    let (head, content) = text.split_once("\r\n\r\n").ok_or("no end of headers")?;
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .ok_or("no status")?;
    let retry_after = head.lines().find_map(|line| {
        let (name, value) = line.split_once(':')?;
        name.eq_ignore_ascii_case("retry-after")
            .then(|| value.trim().to_string())
    });
    Ok((status, retry_after, serde_json::from_str(content)?))
}

/// Heavy work past its budget (one slot, no waiting line) is told `busy`
/// at once, with Retry-After, while a small request beside it is answered: interactive work
/// has slots of its own.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn heavy_work_past_its_budget_is_busy_and_small_requests_are_not() -> TestResult {
    let (address, _stop) = start(Limits {
        max_concurrent_computations: 1,
        max_waiting_heavy: 0,
        max_interactive_computations: 1,
        ..Limits::default()
    })
    .await?;
    let bike: Value = serde_json::from_str(&whipple::advanced::io::write(
        &whipple::presets::find("benchmark")?.bicycle(),
        whipple::advanced::io::Format::Json,
    )?)?;
    let map = json!({"bike": bike, "x": "trail=-0.05:0.2:500", "y": "head_angle_deg=60:85:500"})
        .to_string();
    let small = json!({ "bike": bike }).to_string();
    // Two maps race for the one heavy slot: whichever arrives second, while the other is
    // under way, is refused at once. The small request goes out while the winner still
    // holds the slot. Bounded: a few attempts, in case one map ended before the other came.
    let mut refused = None;
    for _ in 0..5 {
        let mut one = tokio::spawn({
            let map = map.clone();
            async move { post_raw(address, "/api/map", &map).await }
        });
        let mut other = tokio::spawn({
            let map = map.clone();
            async move { post_raw(address, "/api/map", &map).await }
        });
        let (first_answer, running) = tokio::select! {
            answer = &mut one => (answer??, other),
            answer = &mut other => (answer??, one),
        };
        let (status, retry_after, body) = first_answer;
        if status == 503 {
            // The small request only counts while the winner still holds the slot.
            let small_answer = if running.is_finished() {
                None
            } else {
                Some(post_raw(address, "/api/bike/validate", &small).await?)
            };
            let still_running = !running.is_finished();
            let (winner_status, _, _) = running.await??;
            assert_eq!(winner_status, 200);
            if let (Some((small_status, _, small_body)), true) = (small_answer, still_running) {
                refused = Some((retry_after, body, small_status, small_body));
                break;
            }
        } else {
            // Both were answered: the first ended before the second arrived.
            assert_eq!(status, 200, "{body}");
            let (other_status, _, _) = running.await??;
            assert!(other_status == 200 || other_status == 503, "{other_status}");
        }
    }
    let (retry_after, body, small_status, small_body) =
        refused.ok_or("no second map was ever refused while the first ran")?;
    assert_eq!(body["error"]["kind"], "busy", "{body}");
    assert_eq!(retry_after.as_deref(), Some("2"), "{body}");
    assert_eq!(small_status, 200, "{small_body}");
    assert_eq!(small_body["form"], "benchmark");
    Ok(())
}
