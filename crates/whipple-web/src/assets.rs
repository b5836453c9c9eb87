//! The page, bundled by `build.rs` into `OUT_DIR/assets` and embedded here.

use axum::http::header;
use axum::response::{IntoResponse, Response};

/// The one page.
pub const INDEX_HTML: &str = include_str!(concat!(env!("OUT_DIR"), "/assets/index.html"));
/// The page's script (esbuild bundle of `web/src`).
pub const APP_JS: &str = include_str!(concat!(env!("OUT_DIR"), "/assets/app.js"));
/// The page's style sheet.
pub const APP_CSS: &str = include_str!(concat!(env!("OUT_DIR"), "/assets/app.css"));

/// Scripts only from this server; inline styles and data/blob images for the drawings and
/// their PNG export.
const CONTENT_SECURITY_POLICY: &str = "default-src 'self'; script-src 'self'; \
     style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:; connect-src 'self'; \
     object-src 'none'; base-uri 'none'; frame-ancestors 'none'";

fn asset(content_type: &'static str, body: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type),
            (header::CACHE_CONTROL, "no-cache"),
            (header::CONTENT_SECURITY_POLICY, CONTENT_SECURITY_POLICY),
        ],
        body,
    )
        .into_response()
}

pub async fn index() -> Response {
    asset("text/html; charset=utf-8", INDEX_HTML)
}

pub async fn app_js() -> Response {
    asset("text/javascript; charset=utf-8", APP_JS)
}

pub async fn app_css() -> Response {
    asset("text/css; charset=utf-8", APP_CSS)
}
