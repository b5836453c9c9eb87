//! Which requests the local server accepts, through real HTTP on loopback.
//! A web page on another site must not be able to drive it: a body that is not
//! `application/json` gets 415 (a browser sends `text/plain` cross-origin without asking
//! first), a Host that does not name this server gets 421 (a DNS-rebinding page's requests
//! carry its own host name), and a state-changing request from another Origin gets 403.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::time::Duration;

use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use whipple::advanced::io::{Format, write};
use whipple::presets;
use whipple_web::{ServeOptions, Server};

type TestResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// A real server bound to `ip` on a free port; returns its address and a stopper.
async fn start(
    ip: IpAddr,
) -> Result<(SocketAddr, tokio::sync::oneshot::Sender<()>), Box<dyn std::error::Error + Send + Sync>>
{
    let server = Server::bind(&ServeOptions {
        address: ip,
        port: 0,
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

/// One request written byte for byte (so that Host, Origin and Content-Type are exactly what
/// the test says, or absent); returns the status and the JSON body (null when not JSON).
async fn raw(
    address: SocketAddr,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &str,
) -> Result<(u16, Value), Box<dyn std::error::Error + Send + Sync>> {
    let mut request = format!("{method} {path} HTTP/1.1\r\nConnection: close\r\n");
    for (name, value) in headers {
        request.push_str(&format!("{name}: {value}\r\n"));
    }
    if method != "GET" {
        request.push_str(&format!("Content-Length: {}\r\n", body.len()));
    }
    request.push_str("\r\n");
    request.push_str(body);
    let mut stream = TcpStream::connect(address).await?;
    stream.write_all(request.as_bytes()).await?;
    let mut answer = Vec::new();
    tokio::time::timeout(Duration::from_secs(20), stream.read_to_end(&mut answer)).await??;
    let text = String::from_utf8_lossy(&answer);
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("no status line in {text:?}"))?;
    let (_, content) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
    Ok((status, serde_json::from_str(content).unwrap_or(Value::Null)))
}

fn validate_body() -> Result<String, Box<dyn std::error::Error + Send + Sync>> {
    let bike: Value = serde_json::from_str(&write(
        &presets::find("benchmark")?.bicycle(),
        Format::Json,
    )?)?;
    Ok(json!({ "bike": bike }).to_string())
}

/// The error's kind and field, for the messages of failed assertions.
fn kind_and_field(body: &Value) -> (String, String) {
    (
        body["error"]["kind"].as_str().unwrap_or("").to_string(),
        body["error"]["field"].as_str().unwrap_or("").to_string(),
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn only_json_bodies_are_accepted() -> TestResult {
    let (address, _stop) = start(IpAddr::V4(Ipv4Addr::LOCALHOST)).await?;
    let host = address.to_string();
    let body = validate_body()?;
    // What a cross-origin form or a "simple" fetch can send without a preflight.
    for content_type in [
        Some("text/plain"),
        Some("text/plain;charset=UTF-8"),
        Some("application/x-www-form-urlencoded"),
        Some("multipart/form-data; boundary=x"),
        Some("application/jsonx"),
        Some("application/json; charset=latin1"),
        None,
    ] {
        let mut headers = vec![("Host", host.as_str())];
        if let Some(value) = content_type {
            headers.push(("Content-Type", value));
        }
        let (status, answer) = raw(address, "POST", "/api/bike/validate", &headers, &body).await?;
        assert_eq!(status, 415, "Content-Type {content_type:?}: {answer}");
        assert_eq!(
            kind_and_field(&answer),
            ("unsupported_media_type".into(), "Content-Type".into()),
            "{answer}"
        );
    }
    for content_type in [
        "application/json",
        "application/json; charset=utf-8",
        "Application/JSON;Charset=\"UTF-8\"",
    ] {
        let headers = [("Host", host.as_str()), ("Content-Type", content_type)];
        let (status, answer) = raw(address, "POST", "/api/bike/validate", &headers, &body).await?;
        assert_eq!(status, 200, "Content-Type {content_type}: {answer}");
        assert_eq!(answer["form"], "benchmark");
    }
    // A GET has no body to check.
    let (status, _) = raw(address, "GET", "/api/presets", &[("Host", &host)], "").await?;
    assert_eq!(status, 200);
    Ok(())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn only_hosts_naming_this_server_are_answered() -> TestResult {
    let (address, _stop) = start(IpAddr::V4(Ipv4Addr::LOCALHOST)).await?;
    let port = address.port();
    let json = ("Content-Type", "application/json");
    let body = validate_body()?;
    for host in [
        format!("127.0.0.1:{port}"),
        "127.0.0.1".to_string(),
        format!("localhost:{port}"),
        "LocalHost".to_string(),
        format!("[::1]:{port}"),
        "[::1]".to_string(),
    ] {
        let (status, answer) = raw(address, "GET", "/api/presets", &[("Host", &host)], "").await?;
        assert_eq!(status, 200, "Host {host}: {answer}");
        let (status, answer) = raw(
            address,
            "POST",
            "/api/bike/validate",
            &[("Host", &host), json],
            &body,
        )
        .await?;
        assert_eq!(status, 200, "Host {host}: {answer}");
    }
    // A DNS-rebinding page reaches 127.0.0.1 under its own name, which the Host header carries.
    for host in [
        format!("attacker.example:{port}"),
        "attacker.example".to_string(),
        format!("localhost.attacker.example:{port}"),
        format!("127.0.0.1.nip.io:{port}"),
        format!("127.0.0.2:{port}"),
        format!("[::2]:{port}"),
        format!("127.0.0.1:{port}:{port}"),
        format!("127.0.0.1@attacker.example:{port}"),
        String::new(),
    ] {
        for (method, path, headers, body) in [
            ("GET", "/", vec![("Host", host.as_str())], ""),
            ("GET", "/api/presets", vec![("Host", host.as_str())], ""),
            (
                "POST",
                "/api/bike/validate",
                vec![("Host", host.as_str()), json],
                body.as_str(),
            ),
        ] {
            let (status, answer) = raw(address, method, path, &headers, body).await?;
            assert_eq!(status, 421, "Host {host:?}, {method} {path}: {answer}");
            assert_eq!(
                kind_and_field(&answer),
                ("misdirected_request".into(), "Host".into()),
                "{answer}"
            );
        }
    }
    Ok(())
}

/// The host `serve` was told to bind is accepted as well as the loopback names (here
/// 127.0.0.2, a loopback address that is not one of them).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_bound_host_is_answered() -> TestResult {
    let (address, _stop) = start(IpAddr::V4(Ipv4Addr::new(127, 0, 0, 2))).await?;
    let port = address.port();
    for (host, expected) in [
        (format!("127.0.0.2:{port}"), 200),
        (format!("localhost:{port}"), 200),
        (format!("127.0.0.3:{port}"), 421),
    ] {
        let (status, answer) = raw(address, "GET", "/api/presets", &[("Host", &host)], "").await?;
        assert_eq!(status, expected, "Host {host}: {answer}");
    }
    Ok(())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn state_changing_requests_from_other_origins_are_refused() -> TestResult {
    let (address, _stop) = start(IpAddr::V4(Ipv4Addr::LOCALHOST)).await?;
    let port = address.port();
    let host = format!("127.0.0.1:{port}");
    let json = ("Content-Type", "application/json");
    let body = validate_body()?;
    let own = format!("http://{host}");
    for origin in [
        "http://attacker.example".to_string(),
        format!("http://attacker.example:{port}"),
        format!("http://localhost:{}", port.wrapping_add(1)),
        format!("https://{host}"),
        format!("http://{host}.attacker.example"),
        "null".to_string(),
        String::new(),
    ] {
        for method in ["POST", "PUT", "DELETE"] {
            let headers = [("Host", host.as_str()), ("Origin", origin.as_str()), json];
            let (status, answer) =
                raw(address, method, "/api/bike/validate", &headers, &body).await?;
            assert_eq!(status, 403, "Origin {origin:?}, {method}: {answer}");
            assert_eq!(
                kind_and_field(&answer),
                ("forbidden_origin".into(), "Origin".into()),
                "{answer}"
            );
        }
    }
    // The page's own origin, and no Origin at all (curl, Python): answered.
    for headers in [
        vec![("Host", host.as_str()), ("Origin", own.as_str()), json],
        vec![("Host", host.as_str()), json],
    ] {
        let (status, answer) = raw(address, "POST", "/api/bike/validate", &headers, &body).await?;
        assert_eq!(status, 200, "{headers:?}: {answer}");
    }
    // The page loaded as http://localhost:PORT sends that origin with Host localhost:PORT.
    let local = format!("localhost:{port}");
    let local_origin = format!("http://localhost:{port}");
    let headers = [
        ("Host", local.as_str()),
        ("Origin", local_origin.as_str()),
        json,
    ];
    let (status, answer) = raw(address, "POST", "/api/bike/validate", &headers, &body).await?;
    assert_eq!(status, 200, "{answer}");
    // A GET reads nothing it could change: its Origin is not checked (the Host check is what
    // keeps other sites' pages from reading answers).
    let headers = [
        ("Host", host.as_str()),
        ("Origin", "http://attacker.example"),
    ];
    let (status, _) = raw(address, "GET", "/api/presets", &headers, "").await?;
    assert_eq!(status, 200);
    Ok(())
}
