//! The page, bundled by `build.rs` (esbuild, then gzip and brotli) into `OUT_DIR/assets` and
//! embedded here.
//!
//! Every file is served in the best encoding the browser accepts (brotli, then gzip, then as
//! is) with `Vary: Accept-Encoding` and a strong ETag per encoding; `If-None-Match` answers 304.
//! Files with a content hash in their name (`app-HASH.js`, …) never change, so they are cached
//! for a year (`immutable`); the page itself (`/`) is revalidated on every load (`no-cache`),
//! which costs a 304 when nothing changed.

use axum::extract::Path;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};

/// One embedded file, in its three encodings.
pub(crate) struct Asset {
    /// The file name under `/assets/` (`index.html` is served at `/`).
    pub(crate) name: &'static str,
    pub(crate) content_type: &'static str,
    /// A hash of the uncompressed content (base64url), the root of the ETags.
    pub(crate) hash: &'static str,
    /// True for content-hashed names, which may be cached for good.
    pub(crate) immutable: bool,
    pub(crate) identity: &'static [u8],
    pub(crate) gzip: &'static [u8],
    pub(crate) brotli: &'static [u8],
}

include!(concat!(env!("OUT_DIR"), "/assets/assets.rs"));

/// Scripts only from this server; inline styles and data/blob images for the drawings and
/// their PNG export.
const CONTENT_SECURITY_POLICY: &str = "default-src 'self'; script-src 'self'; \
     style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:; connect-src 'self'; \
     object-src 'none'; base-uri 'none'; frame-ancestors 'none'";

/// A content coding of a response body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Coding {
    Brotli,
    Gzip,
    Identity,
}

impl Coding {
    fn token(self) -> Option<&'static str> {
        match self {
            Coding::Brotli => Some("br"),
            Coding::Gzip => Some("gzip"),
            Coding::Identity => None,
        }
    }
}

/// Whether an `Accept-Encoding` header accepts gzip (named, or through `*`, and not refused
/// with `q=0`): the coding of the API's JSON answers.
pub(crate) fn accepts_gzip(accept: Option<&str>) -> bool {
    negotiate_among(accept, false) == Coding::Gzip
}

/// The coding to answer with for an `Accept-Encoding` header (RFC 9110 §12.5.3): brotli, then
/// gzip, each unless refused with `q=0`; `*` stands for any coding not named.
fn negotiate(accept: Option<&str>) -> Coding {
    negotiate_among(accept, true)
}

/// [`negotiate`], brotli offered or not.
fn negotiate_among(accept: Option<&str>, offer_brotli: bool) -> Coding {
    let Some(accept) = accept else {
        return Coding::Identity;
    };
    let mut brotli = None;
    let mut gzip = None;
    let mut any = None;
    for item in accept.split(',') {
        let mut parts = item.split(';');
        let name = parts.next().unwrap_or("").trim().to_ascii_lowercase();
        let mut q = 1.0_f64;
        for param in parts {
            if let Some((key, value)) = param.split_once('=') {
                if key.trim().eq_ignore_ascii_case("q") {
                    q = value.trim().parse().unwrap_or(0.0);
                }
            }
        }
        let accepted = q > 0.0;
        match name.as_str() {
            "br" => brotli = Some(accepted),
            "gzip" | "x-gzip" => gzip = Some(accepted),
            "*" => any = Some(accepted),
            _ => {}
        }
    }
    if offer_brotli && brotli.or(any) == Some(true) {
        Coding::Brotli
    } else if gzip.or(any) == Some(true) {
        Coding::Gzip
    } else {
        Coding::Identity
    }
}

/// The strong ETag of one encoding of an asset.
fn etag(asset: &Asset, coding: Coding) -> String {
    match coding.token() {
        Some(token) => format!("\"{}.{token}\"", asset.hash),
        None => format!("\"{}\"", asset.hash),
    }
}

/// True when `If-None-Match` lists `tag` (or `*`); weak comparison, as RFC 9110 §13.1.2 asks.
fn matches(if_none_match: &str, tag: &str) -> bool {
    let tag = tag.trim_start_matches("W/");
    if_none_match
        .split(',')
        .map(|t| t.trim())
        .any(|t| t == "*" || t.trim_start_matches("W/") == tag)
}

fn serve(asset: &Asset, headers: &HeaderMap) -> Response {
    let coding = negotiate(
        headers
            .get(header::ACCEPT_ENCODING)
            .and_then(|v| v.to_str().ok()),
    );
    let tag = etag(asset, coding);
    let cache = if asset.immutable {
        "public, max-age=31536000, immutable"
    } else {
        "no-cache"
    };
    let mut response = if headers
        .get(header::IF_NONE_MATCH)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|list| matches(list, &tag))
    {
        StatusCode::NOT_MODIFIED.into_response()
    } else {
        let body = match coding {
            Coding::Brotli => asset.brotli,
            Coding::Gzip => asset.gzip,
            Coding::Identity => asset.identity,
        };
        let mut response = body.into_response();
        response.headers_mut().insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static(asset.content_type),
        );
        if let Some(token) = coding.token() {
            response
                .headers_mut()
                .insert(header::CONTENT_ENCODING, HeaderValue::from_static(token));
        }
        response
    };
    let h = response.headers_mut();
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static(cache));
    h.insert(header::VARY, HeaderValue::from_static("Accept-Encoding"));
    if let Ok(value) = HeaderValue::from_str(&tag) {
        h.insert(header::ETAG, value);
    }
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(CONTENT_SECURITY_POLICY),
    );
    response
}

fn find(name: &str) -> Option<&'static Asset> {
    ASSETS.iter().find(|a| a.name == name)
}

/// The scripts' text, concatenated (the API's tests read which endpoints the page calls).
#[cfg(test)]
pub(crate) fn script_text() -> String {
    ASSETS
        .iter()
        .filter(|a| a.name.ends_with(".js"))
        .map(|a| String::from_utf8_lossy(a.identity).into_owned())
        .collect()
}

/// `GET /`: the page.
pub async fn index(headers: HeaderMap) -> Response {
    match find("index.html") {
        Some(asset) => serve(asset, &headers),
        None => (StatusCode::INTERNAL_SERVER_ERROR, "the page was not built").into_response(),
    }
}

/// `GET /assets/{name}`: a script, a style sheet; 404 (JSON, like every unknown path) otherwise.
pub async fn file(Path(name): Path<String>, headers: HeaderMap) -> Response {
    match find(&name).filter(|a| a.name != "index.html") {
        Some(asset) => serve(asset, &headers),
        None => crate::error::ApiError::new(
            StatusCode::NOT_FOUND,
            "not_found",
            format!("no such asset: /assets/{name}"),
        )
        .into_response(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodings_are_negotiated() {
        assert_eq!(negotiate(None), Coding::Identity);
        assert_eq!(negotiate(Some("gzip, deflate, br, zstd")), Coding::Brotli);
        assert_eq!(negotiate(Some("gzip")), Coding::Gzip);
        assert_eq!(negotiate(Some("br;q=0, gzip;q=0.5")), Coding::Gzip);
        assert_eq!(negotiate(Some("identity")), Coding::Identity);
        assert_eq!(negotiate(Some("*")), Coding::Brotli);
        assert_eq!(negotiate(Some("*;q=0")), Coding::Identity);
        assert_eq!(negotiate(Some("br;q=0, *")), Coding::Gzip);
        assert_eq!(negotiate(Some("BR; Q=1")), Coding::Brotli);
        assert_eq!(negotiate(Some("gzip;q=nonsense")), Coding::Identity);
    }

    #[test]
    fn if_none_match_lists_are_read() {
        assert!(matches("\"abc.br\"", "\"abc.br\""));
        assert!(matches("\"x\", W/\"abc\"", "\"abc\""));
        assert!(matches("*", "\"abc\""));
        assert!(!matches("\"abc\"", "\"abc.br\""));
    }

    /// The page, its script and style sheet, and the lazily loaded 3-D code are all embedded,
    /// each compressed; the page names the hashed files, and the initial page (HTML, CSS and
    /// the first script, compressed as a browser receives them) stays under 100 KB.
    #[test]
    fn the_page_is_embedded_small_and_compressed() {
        let page = find("index.html").map(|a| String::from_utf8_lossy(a.identity).into_owned());
        let page = page.unwrap_or_default();
        let named: Vec<&Asset> = ASSETS
            .iter()
            .filter(|a| a.name != "index.html" && page.contains(&format!("/assets/{}", a.name)))
            .collect();
        assert!(named.iter().any(|a| a.name.ends_with(".js")), "{page}");
        assert!(named.iter().any(|a| a.name.ends_with(".css")), "{page}");
        let initial: usize = find("index.html").map_or(0, |a| a.brotli.len())
            + named.iter().map(|a| a.brotli.len()).sum::<usize>();
        assert!(initial < 100_000, "initial page {initial} bytes compressed");
        // three.js is not part of it but is there for the 3-D views.
        assert!(
            ASSETS
                .iter()
                .any(|a| a.name.starts_with("view3d-") && a.identity.len() > 300_000)
        );
        for a in ASSETS {
            assert!(
                a.gzip.len() < a.identity.len() && a.brotli.len() < a.identity.len(),
                "{}",
                a.name
            );
            assert_eq!(a.immutable, a.name != "index.html");
        }
    }

    async fn get(
        uri: &str,
        headers: &[(&str, &str)],
    ) -> Result<axum::http::Response<axum::body::Body>, Box<dyn std::error::Error>> {
        use tower::ServiceExt;
        let mut request = axum::http::Request::builder().uri(uri);
        for (k, v) in headers {
            request = request.header(*k, *v);
        }
        let app = crate::app(crate::Limits::default());
        Ok(app
            .oneshot(request.body(axum::body::Body::empty())?)
            .await?)
    }

    /// Through the router: brotli when accepted, gzip for older clients, the bytes as they are
    /// otherwise; a year's caching for hashed names, revalidation for the page; 304 on a match.
    #[tokio::test]
    async fn assets_are_served_compressed_cached_and_revalidated()
    -> Result<(), Box<dyn std::error::Error>> {
        use http_body_util::BodyExt;
        let script = ASSETS
            .iter()
            .find(|a| a.name.starts_with("app-") && a.name.ends_with(".js"))
            .ok_or("no script")?;
        let uri = format!("/assets/{}", script.name);
        let br = get(&uri, &[("accept-encoding", "gzip, deflate, br")]).await?;
        assert_eq!(br.status(), StatusCode::OK);
        let h = br.headers();
        assert_eq!(h[header::CONTENT_ENCODING], "br");
        assert_eq!(h[header::VARY], "Accept-Encoding");
        assert_eq!(
            h[header::CACHE_CONTROL],
            "public, max-age=31536000, immutable"
        );
        assert!(
            h[header::CONTENT_TYPE]
                .to_str()?
                .starts_with("text/javascript")
        );
        let tag = h[header::ETAG].to_str()?.to_string();
        let body = br.into_body().collect().await?.to_bytes();
        assert_eq!(&body[..], script.brotli);

        let gz = get(&uri, &[("accept-encoding", "gzip")]).await?;
        assert_eq!(gz.headers()[header::CONTENT_ENCODING], "gzip");
        assert_ne!(gz.headers()[header::ETAG].to_str()?, tag);
        let plain = get(&uri, &[]).await?;
        assert!(plain.headers().get(header::CONTENT_ENCODING).is_none());
        let body = plain.into_body().collect().await?.to_bytes();
        assert_eq!(&body[..], script.identity);

        let again = get(&uri, &[("accept-encoding", "br"), ("if-none-match", &tag)]).await?;
        assert_eq!(again.status(), StatusCode::NOT_MODIFIED);
        assert_eq!(again.headers()[header::ETAG].to_str()?, tag);
        assert!(again.into_body().collect().await?.to_bytes().is_empty());

        let page = get("/", &[("accept-encoding", "br")]).await?;
        assert_eq!(page.headers()[header::CACHE_CONTROL], "no-cache");
        assert!(
            page.headers()[header::CONTENT_SECURITY_POLICY]
                .to_str()?
                .contains("script-src 'self'")
        );
        let tag = page.headers()[header::ETAG].to_str()?.to_string();
        let again = get("/", &[("accept-encoding", "br"), ("if-none-match", &tag)]).await?;
        assert_eq!(again.status(), StatusCode::NOT_MODIFIED);

        let missing = get("/assets/app.js", &[]).await?;
        assert_eq!(missing.status(), StatusCode::NOT_FOUND);
        let missing = get("/assets/index.html", &[]).await?;
        assert_eq!(missing.status(), StatusCode::NOT_FOUND);
        Ok(())
    }
}
