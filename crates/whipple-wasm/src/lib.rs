//! # whipple-wasm
//!
//! whipple's JSON API compiled to WebAssembly, for the static site: the page's requests are
//! answered in the browser by the same handlers `whipple serve` runs ([`whipple_web::answer`]),
//! so both back ends give the same bytes and the same messages.
//!
//! The interface is one call, [`call`], exported by wasm-bindgen: the page's worker
//! (`web/src/worker.js`) hands it the method, the path and the body of a request, and a function
//! told of the progress of long work, and gets the HTTP status and the JSON answer back. Long work is stopped by ending the worker that runs it.
//!
//! The site holds two builds of this crate: the first module, the endpoints of the page's
//! first view alone (whipple-web's `FIRST_VIEW`: presets, the parameter table, validate,
//! eigen), which a first visit loads, and the whole module (the feature `all-routes`), which
//! the worker loads for any other endpoint. [`answers`] tells which a build holds.

use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use wasm_bindgen::JsValue;
use wasm_bindgen::prelude::wasm_bindgen;
use whipple_web::{Answer, Limits, answer_with_progress};

/// Whether this build answers `path` (`/api/map`): any endpoint with the feature
/// `all-routes`, the first view's alone without it.
#[wasm_bindgen]
pub fn answers(path: &str) -> bool {
    whipple_web::answers(path)
}

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
/// `progress(done, total)` is called as long work advances (a map's designs, chunk by chunk).
#[wasm_bindgen]
pub fn call(method: &str, path: &str, body: &[u8], progress: &js_sys::Function) -> Reply {
    let progress = progress.clone();
    reply(
        method,
        path,
        body,
        Rc::new(move |done, total| {
            // Only a report: a hook that throws does not stop the work.
            let _ = progress.call2(
                &JsValue::NULL,
                &JsValue::from_f64(done as f64),
                &JsValue::from_f64(total as f64),
            );
        }),
    )
}

/// [`call`]'s answer, with its progress told to `progress`.
fn reply(method: &str, path: &str, body: &[u8], progress: Rc<dyn Fn(u64, u64)>) -> Reply {
    let Answer { status, body } = answer_with_progress(
        method,
        path,
        body,
        &Limits::default(),
        Arc::new(AtomicBool::new(false)),
        progress,
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
        let call =
            |method: &str, path: &str, body: &[u8]| reply(method, path, body, Rc::new(|_, _| ()));
        let answer = call("GET", "/api/presets/benchmark", b"");
        assert_eq!(answer.status(), 200);
        let text = String::from_utf8_lossy(&answer.body).into_owned();
        assert!(text.contains("\"benchmark\""), "{text}");
        assert_eq!(call("GET", "/api/nowhere", b"").status(), 404);
        assert_eq!(call("DELETE", "/api/eigen", b"").status(), 405);
        assert_eq!(call("POST", "/api/eigen", b"{").status(), 400);
    }
}
