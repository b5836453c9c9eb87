//! Any bytes as the body of each POST endpoint of the web API, through the real router: never
//! a panic and never a 5xx other than the documented 503 (busy, timeout); every answer is JSON.
#![no_main]

use std::sync::OnceLock;

use axum::body::Body;
use axum::http::{Method, Request, header};
use http_body_util::BodyExt;
use libfuzzer_sys::fuzz_target;
use tower::ServiceExt;
use whipple_web::{Limits, app};

const ROUTES: [&str; 11] = [
    "/api/bike/validate",
    "/api/sensitivity",
    "/api/bike/toml",
    "/api/bike/parse",
    "/api/eigen",
    "/api/speeds",
    "/api/simulate",
    "/api/modes",
    "/api/linear/response",
    "/api/linear/frequency",
    "/api/linear/time",
];

fn runtime() -> &'static tokio::runtime::Runtime {
    static RUNTIME: OnceLock<tokio::runtime::Runtime> = OnceLock::new();
    RUNTIME.get_or_init(|| {
        tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .expect("a runtime")
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&which, body)) = data.split_first() else {
        return;
    };
    let route = ROUTES[usize::from(which) % ROUTES.len()];
    let router = app(Limits::default());
    let request = Request::builder()
        .method(Method::POST)
        .uri(route)
        .header(header::CONTENT_TYPE, "application/json")
        .body(Body::from(body.to_vec()))
        .expect("a request");
    runtime().block_on(async {
        let response = router.oneshot(request).await.expect("an answer");
        let status = response.status().as_u16();
        let bytes = response
            .into_body()
            .collect()
            .await
            .expect("a body")
            .to_bytes();
        assert!(
            status < 500 || status == 503,
            "{route}: {status} {}",
            String::from_utf8_lossy(&bytes)
        );
        serde_json_check(&bytes, route, status);
    });
});

/// Every answer, error or not, is JSON.
fn serde_json_check(bytes: &[u8], route: &str, status: u16) {
    assert!(
        bytes.first() == Some(&b'{') || bytes.first() == Some(&b'['),
        "{route}: {status} is not JSON: {}",
        String::from_utf8_lossy(bytes)
    );
}
