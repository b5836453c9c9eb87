//! Which requests the local server answers at all. A page on any web site
//! can make the browser send requests to `127.0.0.1:PORT`; these checks keep it from driving
//! the server or reading its answers:
//!
//! - **Host** must name this server: `127.0.0.1`, `localhost`, `[::1]` (any port) or the
//!   address `serve` was told to bind; otherwise 421 `misdirected_request`. A DNS-rebinding
//!   page reaches the loopback address under its own host name, which its requests carry. A
//!   request without Host (HTTP/1.0, or the router called directly) passes: browsers always
//!   send one.
//! - **Origin**, on a state-changing request (any method but GET, HEAD and OPTIONS), must be
//!   absent (curl, Python) or the server's own origin, `http://` and the request's Host;
//!   otherwise 403 `forbidden_origin`.
//! - **Content-Type** must be `application/json` (a `charset`, if given, `utf-8`) on every
//!   POST, PUT and PATCH and on any request with a body; otherwise 415
//!   `unsupported_media_type`. A browser sends such a body cross-origin only after a CORS
//!   preflight, which this server never grants.

use std::net::{IpAddr, Ipv4Addr, Ipv6Addr};

use axum::http::{HeaderMap, HeaderValue, Method, StatusCode, header};

use crate::error::ApiError;

/// The host of a Host header or an Origin's authority, lower-cased, and its port.
#[derive(Debug, PartialEq)]
struct Authority {
    host: String,
    port: Option<u16>,
}

/// `HOST`, `HOST:PORT`, `[IPV6]` or `[IPV6]:PORT`; `None` when it is none of these.
fn authority(text: &str) -> Option<Authority> {
    let (host, port) = if let Some(rest) = text.strip_prefix('[') {
        let (inside, after) = rest.split_once(']')?;
        let port = match after {
            "" => None,
            _ => Some(after.strip_prefix(':')?),
        };
        // Kept in brackets' absence: a bare IPv6 literal, checked below.
        inside.parse::<Ipv6Addr>().ok()?;
        (inside, port)
    } else {
        match text.split_once(':') {
            Some((host, port)) => (host, Some(port)),
            None => (text, None),
        }
    };
    let port = match port {
        None => None,
        Some(digits) => {
            if digits.is_empty() || digits.len() > 5 || !digits.bytes().all(|b| b.is_ascii_digit())
            {
                return None;
            }
            Some(digits.parse::<u16>().ok()?)
        }
    };
    let allowed = |b: u8| b.is_ascii_alphanumeric() || b"-._:".contains(&b);
    if host.is_empty() || !host.bytes().all(allowed) {
        return None;
    }
    Some(Authority {
        host: host.to_ascii_lowercase(),
        port,
    })
}

/// Whether `host` names this server: a loopback name or the bound address.
fn names_this_server(host: &str, bound: IpAddr) -> bool {
    if host == "localhost" {
        return true;
    }
    match host.parse::<IpAddr>() {
        Ok(ip) => {
            ip == IpAddr::V4(Ipv4Addr::LOCALHOST)
                || ip == IpAddr::V6(Ipv6Addr::LOCALHOST)
                || ip == bound
        }
        Err(_) => false,
    }
}

/// A header's value as text for a message: printable, at most 60 characters.
fn shown(value: &HeaderValue) -> String {
    match value.to_str() {
        Ok(text) => format!("`{}`", whipple::advanced::shorten(text, 60)),
        Err(_) => "a value that is not visible ASCII".to_string(),
    }
}

fn misdirected(message: String) -> ApiError {
    ApiError::new(StatusCode::MISDIRECTED_REQUEST, "misdirected_request", message).at(
        "Host",
        "127.0.0.1, localhost or [::1] (with any port), or the address `whipple serve` was told to bind",
    )
}

/// The request's Host, checked; `None` when it has none.
fn checked_host(headers: &HeaderMap, bound: IpAddr) -> Result<Option<Authority>, ApiError> {
    let mut values = headers.get_all(header::HOST).iter();
    let Some(value) = values.next() else {
        return Ok(None);
    };
    if values.next().is_some() {
        return Err(misdirected(
            "the request has more than one Host header".to_string(),
        ));
    }
    let parsed = value.to_str().ok().and_then(authority);
    match parsed {
        Some(a) if names_this_server(&a.host, bound) => Ok(Some(a)),
        _ => Err(misdirected(format!(
            "Host {} does not name this server: it answers only requests addressed to \
             127.0.0.1, localhost, [::1] or {bound} (a web page reaching it under another \
             name is refused)",
            shown(value)
        ))),
    }
}

fn forbidden(message: String) -> ApiError {
    ApiError::new(StatusCode::FORBIDDEN, "forbidden_origin", message).at(
        "Origin",
        "absent, or the server's own origin (http:// and the request's Host)",
    )
}

/// A state-changing request's Origin: absent, or `http://` and the request's own Host.
fn check_origin(headers: &HeaderMap, host: Option<&Authority>) -> Result<(), ApiError> {
    let mut values = headers.get_all(header::ORIGIN).iter();
    let Some(value) = values.next() else {
        return Ok(());
    };
    let refuse = || {
        forbidden(format!(
            "Origin {} is not this server's own: a request that computes or changes anything \
             is accepted only from the page this server serves, or without an Origin",
            shown(value)
        ))
    };
    if values.next().is_some() {
        return Err(refuse());
    }
    let origin = value
        .to_str()
        .ok()
        .and_then(|text| text.strip_prefix("http://"))
        .and_then(authority)
        .ok_or_else(refuse)?;
    // The browser omits the default port from both; anything else must match exactly.
    let same = host.is_some_and(|h| {
        h.host == origin.host && h.port.unwrap_or(80) == origin.port.unwrap_or(80)
    });
    if same { Ok(()) } else { Err(refuse()) }
}

/// Whether a Content-Type value is `application/json`, with a `charset`, if any, of `utf-8`.
fn is_json(value: &HeaderValue) -> bool {
    let Ok(text) = value.to_str() else {
        return false;
    };
    let mut parts = text.split(';');
    let media = parts.next().unwrap_or("").trim();
    if !media.eq_ignore_ascii_case("application/json") {
        return false;
    }
    parts.all(|parameter| match parameter.split_once('=') {
        Some((name, value)) if name.trim().eq_ignore_ascii_case("charset") => {
            value.trim().trim_matches('"').eq_ignore_ascii_case("utf-8")
        }
        Some(_) => true,
        None => parameter.trim().is_empty(),
    })
}

fn has_body(headers: &HeaderMap) -> bool {
    headers.contains_key(header::TRANSFER_ENCODING)
        || headers
            .get(header::CONTENT_LENGTH)
            .is_some_and(|length| length.as_bytes() != b"0")
}

fn check_content_type(method: &Method, headers: &HeaderMap) -> Result<(), ApiError> {
    let needs = *method == Method::POST
        || *method == Method::PUT
        || *method == Method::PATCH
        || has_body(headers);
    if !needs {
        return Ok(());
    }
    let mut values = headers.get_all(header::CONTENT_TYPE).iter();
    let (first, second) = (values.next(), values.next());
    let rule = "application/json (a charset, if given, utf-8)";
    match (first, second) {
        (Some(value), None) if is_json(value) => Ok(()),
        (Some(value), None) => Err(ApiError::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "unsupported_media_type",
            format!(
                "Content-Type {} is not accepted: send the body as application/json",
                shown(value)
            ),
        )
        .at("Content-Type", rule)),
        (None, _) => Err(ApiError::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "unsupported_media_type",
            format!("{method} needs a Content-Type header: send the body as application/json"),
        )
        .at("Content-Type", rule)),
        (Some(_), Some(_)) => Err(ApiError::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "unsupported_media_type",
            "the request has more than one Content-Type header: send one, application/json",
        )
        .at("Content-Type", rule)),
    }
}

/// All three checks, in the order Host (421), Origin (403), Content-Type (415).
pub(crate) fn check(method: &Method, headers: &HeaderMap, bound: IpAddr) -> Result<(), ApiError> {
    let host = checked_host(headers, bound)?;
    let safe = *method == Method::GET || *method == Method::HEAD || *method == Method::OPTIONS;
    if !safe {
        check_origin(headers, host.as_ref())?;
    }
    check_content_type(method, headers)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn authorities() {
        let a = |host: &str, port: Option<u16>| {
            Some(Authority {
                host: host.into(),
                port,
            })
        };
        assert_eq!(authority("LocalHost:8080"), a("localhost", Some(8080)));
        assert_eq!(authority("127.0.0.1"), a("127.0.0.1", None));
        assert_eq!(authority("[::1]:80"), a("::1", Some(80)));
        assert_eq!(authority("[::1]"), a("::1", None));
        for bad in [
            "", ":80", "a:", "a:b", "a:1:2", "a:99999", "[::1", "[x]:1", "[::1]x", "a b", "a@b:1",
            "a/b", "::1",
        ] {
            assert_eq!(authority(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn json_content_types() {
        for good in [
            "application/json",
            "application/json;charset=utf-8",
            "APPLICATION/JSON; Charset=\"UTF-8\"",
            "application/json; foo=bar",
        ] {
            assert!(is_json(&HeaderValue::from_static(good)), "{good}");
        }
        for bad in [
            "text/plain",
            "application/json; charset=latin1",
            "application/json-seq",
            "application/jsonx",
            "application/json;;x",
        ] {
            assert!(!is_json(&HeaderValue::from_static(bad)), "{bad}");
        }
    }
}
