//! # whipple-wasm
//!
//! whipple's JSON API compiled to WebAssembly, for the static site: the page's requests are
//! answered in the browser by the same handlers `whipple serve` runs ([`whipple_web::answer`]),
//! so both back ends give the same bytes and the same messages.
//!
//! The interface is one call, [`call`], exported by wasm-bindgen: the page's worker
//! (`web/src/worker.js`) hands it the method, the path and the body of a request, and gets the
//! HTTP status and the JSON answer back. Long work is stopped by ending the worker that runs it.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use wasm_bindgen::prelude::wasm_bindgen;
use whipple_web::{Answer, Limits, answer};

/// An answer: the HTTP status the server would send and the JSON body.
#[wasm_bindgen]
pub struct Reply {
    status: u16,
    body: Vec<u8>,
}

#[wasm_bindgen]
impl Reply {
    /// The HTTP status.
    #[wasm_bindgen(getter)]
    pub fn status(&self) -> u16 {
        self.status
    }

    /// The JSON body (UTF-8), byte for byte the server's.
    #[wasm_bindgen(getter)]
    pub fn body(&self) -> Vec<u8> {
        self.body.clone()
    }
}

/// Answers one API request as `whipple serve` would: `method` (`GET`, `POST`), `path`
/// (`/api/eigen`) and the JSON body (empty for a GET), with the server's default limits.
#[wasm_bindgen]
pub fn call(method: &str, path: &str, body: &[u8]) -> Reply {
    let Answer { status, body } = answer(
        method,
        path,
        body,
        &Limits::default(),
        Arc::new(AtomicBool::new(false)),
    );
    Reply { status, body }
}

/// The crate's version, which the page shows in its About box.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

#[cfg(target_arch = "wasm32")]
#[unsafe(no_mangle)]
unsafe extern "Rust" fn __getrandom_v03_custom(
    _dest: *mut u8,
    _len: usize,
) -> Result<(), getrandom::Error> {
    Err(getrandom::Error::UNSUPPORTED)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_is_answered_as_the_server_would() {
        let answer = call("GET", "/api/presets/benchmark", b"");
        assert_eq!(answer.status(), 200);
        let text = String::from_utf8_lossy(&answer.body).into_owned();
        assert!(text.contains("\"benchmark\""), "{text}");
        assert_eq!(call("GET", "/api/nowhere", b"").status(), 404);
        assert_eq!(call("DELETE", "/api/eigen", b"").status(), 405);
        assert_eq!(call("POST", "/api/eigen", b"{").status(), 400);
    }
}
