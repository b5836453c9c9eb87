//! The server: the router (the page, its assets and the API of [`crate::api::routes`]), its
//! guards (Host, Origin, Content-Type, time, compression) and the computing slots that run each
//! endpoint's [`Job`] on the blocking pool.

use std::net::{IpAddr, Ipv4Addr};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use axum::Router;
use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, PathRejection};
use axum::extract::{DefaultBodyLimit, Path, Request, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use tokio::sync::{OwnedSemaphorePermit, Semaphore, TryAcquireError};

use crate::api::{Budget, Handler, Job, routes};
use crate::error::ApiError;
use crate::{Limits, assets};

#[derive(Clone)]
pub(crate) struct AppState {
    pub(crate) limits: Limits,
    /// The address the server is bound to: a Host naming it is accepted (see `access`).
    bound: IpAddr,
    /// Slots of the heavy work (maps, studies, simulations, sweeps, sensitivities, responses).
    heavy: Arc<Semaphore>,
    /// Heavy requests waiting for a slot now.
    heavy_waiting: Arc<AtomicUsize>,
    /// Slots of the interactive work (validate, convert, parse, critical speeds, modes,
    /// turns): its own, so that it never waits behind heavy work.
    interactive: Arc<Semaphore>,
}

/// The whole application for a server on a loopback address: page, assets and API, with the
/// body-size limit, the request timeout, the Host, Origin and Content-Type checks and JSON
/// errors for unknown paths and methods.
pub fn app(limits: Limits) -> Router {
    app_bound_to(limits, IpAddr::V4(Ipv4Addr::LOCALHOST))
}

/// [`app`] for a server bound to `bound`: a Host header naming that address is accepted as
/// well as the loopback names.
pub fn app_bound_to(limits: Limits, bound: IpAddr) -> Router {
    let state = AppState {
        limits,
        bound,
        heavy: Arc::new(Semaphore::new(limits.max_concurrent_computations.max(1))),
        heavy_waiting: Arc::new(AtomicUsize::new(0)),
        interactive: Arc::new(Semaphore::new(limits.max_interactive_computations.max(1))),
    };
    let mut router = Router::new()
        .route("/", get(assets::index))
        .route("/assets/{name}", get(assets::file));
    // The API: every route of the one table the static site's module answers from too.
    for route in routes() {
        router = match route.handler {
            Handler::Get(answer) if route.path.contains('{') => router.route(
                route.path,
                get(
                    move |name: Result<Path<String>, PathRejection>| async move {
                        // A name that is not UTF-8 once decoded (`/api/presets/%ff`) is answered
                        // in JSON too.
                        match name {
                            Ok(Path(name)) => json_response(answer(&name)),
                            Err(rejection) => {
                                crate::api::undecodable_name(&rejection.body_text()).into_response()
                            }
                        }
                    },
                ),
            ),
            Handler::Get(answer) => router.route(
                route.path,
                get(move || async move { json_response(answer("")) }),
            ),
            Handler::Post(prepare) => router.route(
                route.path,
                post(
                    move |State(state): State<AppState>,
                          headers: HeaderMap,
                          body: Result<Bytes, BytesRejection>| async move {
                        match body_bytes(body).and_then(|bytes| prepare(&state.limits, bytes)) {
                            Ok(job) if wants_lines(&headers) => {
                                run_in_lines(state, job, gzip_accepted(&headers))
                            }
                            Ok(job) => run(&state, job).await,
                            Err(error) => error.into_response(),
                        }
                    },
                ),
            ),
        };
    }
    router
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .layer(DefaultBodyLimit::max(limits.max_body_bytes))
        .layer(middleware::from_fn(compress_json))
        .layer(middleware::from_fn_with_state(state.clone(), guard))
        .with_state(state)
}

/// JSON bytes answered with 200, or the error.
fn json_response(answer: Result<Vec<u8>, ApiError>) -> Response {
    match answer {
        Ok(bytes) => (
            [(
                header::CONTENT_TYPE,
                HeaderValue::from_static("application/json"),
            )],
            bytes,
        )
            .into_response(),
        Err(error) => error.into_response(),
    }
}

/// Runs an endpoint's job in a computing slot of its budget, within the limits.
async fn run(state: &AppState, job: Job) -> Response {
    let Job {
        budget,
        advice,
        work,
    } = job;
    json_response(compute(state, budget, advice, work).await)
}

/// The media type of an answer told line by line, asked for with `Accept`.
const NDJSON: &str = "application/x-ndjson";

/// Time between two progress lines at most (the designs done are told in chunks, often).
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_millis(200);

/// Whether the request asks for its answer line by line (`Accept: application/x-ndjson`).
fn wants_lines(headers: &HeaderMap) -> bool {
    headers.get_all(header::ACCEPT).iter().any(|value| {
        value.to_str().is_ok_and(|text| {
            text.split(',').any(|range| {
                range
                    .split(';')
                    .next()
                    .is_some_and(|media| media.trim().eq_ignore_ascii_case(NDJSON))
            })
        })
    })
}

fn gzip_accepted(headers: &HeaderMap) -> bool {
    crate::assets::accepts_gzip(
        headers
            .get(header::ACCEPT_ENCODING)
            .and_then(|v| v.to_str().ok()),
    )
}

/// A job's answer told line by line (NDJSON, status 200 once the request is read and checked):
/// `{"progress": [done, total]}` as long work advances (a map's or a study's designs, at most
/// every [`PROGRESS_EVERY`]), then one last line, `{"status": 200, "answer": ...}` with the
/// bytes [`run`] would have answered, or `{"status": ..., "error": {...}}`. The work runs in a
/// computing slot under the same limits; a client that goes away stops it (the lines' stream
/// is dropped, and with it the work's stop flag is set). gzip-compressed, flushed line by line,
/// where the client accepts gzip.
fn run_in_lines(state: AppState, job: Job, gzip: bool) -> Response {
    let Job {
        budget,
        advice,
        work,
    } = job;
    let (tell, told) = tokio::sync::watch::channel(None::<(u64, u64)>);
    let work = move |stop: Arc<AtomicBool>| {
        let hook: crate::api::ProgressHook = std::rc::Rc::new(move |done, total| {
            tell.send_replace(Some((done, total)));
        });
        crate::api::with_progress(hook, || work(stop))
    };
    let answer = Box::pin(async move { compute(&state, budget, advice, work).await });
    let encoder =
        gzip.then(|| flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast()));
    let next = tokio::time::Instant::now();
    let lines = futures_util::stream::unfold(
        Some((answer, told, next, encoder)),
        |under_way| async move {
            let (mut answer, mut told, mut next, mut encoder) = under_way?;
            loop {
                // A change of the progress (the first told at once, the next ones at most
                // every PROGRESS_EVERY), or the answer, whichever comes first; once the work
                // has ended (its hook dropped), the answer.
                let result = tokio::select! {
                    result = &mut answer => Some(Some(result)),
                    changed = told.changed() => changed.err().map(|_| None),
                };
                let result = match result {
                    Some(Some(result)) => Some(result),
                    Some(None) => Some((&mut answer).await),
                    None => tokio::select! {
                        result = &mut answer => Some(result),
                        () = tokio::time::sleep_until(next) => None,
                    },
                };
                if let Some(result) = result {
                    let line = match result {
                        Ok(bytes) => answer_line(&bytes),
                        Err(error) => error.line(),
                    };
                    return Some((last_chunk(line, encoder).await, None));
                }
                let Some((done, total)) = *told.borrow_and_update() else {
                    continue;
                };
                next = tokio::time::Instant::now() + PROGRESS_EVERY;
                let line = format!("{{\"progress\":[{done},{total}]}}\n");
                let chunk = match encoder.as_mut() {
                    Some(encoder) => flushed(encoder, line.as_bytes()),
                    None => Ok(Bytes::from(line)),
                };
                let failed = chunk.is_err();
                return Some((chunk, (!failed).then_some((answer, told, next, encoder))));
            }
        },
    );
    let mut response = Response::new(axum::body::Body::from_stream(lines));
    let headers = response.headers_mut();
    headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(NDJSON));
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    headers.insert(
        header::VARY,
        HeaderValue::from_static("accept, accept-encoding"),
    );
    if gzip {
        headers.insert(header::CONTENT_ENCODING, HeaderValue::from_static("gzip"));
    }
    response
}

/// `{"status":200,"answer":` the answer's JSON `}` and a newline.
fn answer_line(answer: &[u8]) -> Vec<u8> {
    let mut line = Vec::with_capacity(answer.len() + 28);
    line.extend_from_slice(b"{\"status\":200,\"answer\":");
    line.extend_from_slice(answer);
    line.extend_from_slice(b"}\n");
    line
}

/// `line` through the encoder, flushed: the bytes that tell it whole so far.
fn flushed(encoder: &mut flate2::write::GzEncoder<Vec<u8>>, line: &[u8]) -> std::io::Result<Bytes> {
    use std::io::Write;
    encoder.write_all(line)?;
    encoder.flush()?;
    Ok(Bytes::from(std::mem::take(encoder.get_mut())))
}

/// The last line, through the encoder and its end (a long answer compressed on the blocking
/// pool, as [`compress_json`] does).
async fn last_chunk(
    line: Vec<u8>,
    encoder: Option<flate2::write::GzEncoder<Vec<u8>>>,
) -> std::io::Result<Bytes> {
    let Some(mut encoder) = encoder else {
        return Ok(Bytes::from(line));
    };
    let length = line.len();
    let end = move || -> std::io::Result<Vec<u8>> {
        use std::io::Write;
        encoder.write_all(&line)?;
        encoder.finish()
    };
    let bytes = if length < COMPRESS_ASIDE_FROM_BYTES {
        end()?
    } else {
        tokio::task::spawn_blocking(end)
            .await
            .map_err(|e| std::io::Error::other(e.to_string()))??
    };
    Ok(Bytes::from(bytes))
}

/// JSON answers past this many bytes are sent gzip-compressed to a client that accepts it.
const COMPRESS_FROM_BYTES: usize = 1024;

/// JSON answers past this many bytes are compressed on the blocking pool, not on the runtime.
const COMPRESS_ASIDE_FROM_BYTES: usize = 256 * 1024;

/// Sends a JSON answer gzip-compressed (fast level: a design map's columns shrink about three
/// times) where the request accepts gzip and the answer is long enough to gain from it; the
/// page's first load asked for 279 KB of JSON uncompressed.
async fn compress_json(request: Request, next: Next) -> Response {
    let gzip = crate::assets::accepts_gzip(
        request
            .headers()
            .get(header::ACCEPT_ENCODING)
            .and_then(|v| v.to_str().ok()),
    );
    let response = next.run(request).await;
    let is_json = response
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|t| t.starts_with("application/json"));
    if !gzip || !is_json || response.headers().contains_key(header::CONTENT_ENCODING) {
        return response;
    }
    let (mut parts, body) = response.into_parts();
    // The answers are built whole in memory (compute_json); nothing is streamed here.
    let Ok(bytes) = axum::body::to_bytes(body, usize::MAX).await else {
        return ApiError::internal("the answer could not be read back for compression")
            .into_response();
    };
    parts
        .headers
        .insert(header::VARY, HeaderValue::from_static("accept-encoding"));
    if bytes.len() < COMPRESS_FROM_BYTES {
        return Response::from_parts(parts, axum::body::Body::from(bytes));
    }
    let length = bytes.len();
    let compress = move || -> std::io::Result<Vec<u8>> {
        use std::io::Write;
        let mut encoder = flate2::write::GzEncoder::new(
            Vec::with_capacity(bytes.len() / 4),
            flate2::Compression::fast(),
        );
        encoder.write_all(&bytes)?;
        encoder.finish()
    };
    let compressed = if length < COMPRESS_ASIDE_FROM_BYTES {
        compress()
    } else {
        match tokio::task::spawn_blocking(compress).await {
            Ok(result) => result,
            Err(e) => Err(std::io::Error::other(e.to_string())),
        }
    };
    match compressed {
        Ok(body) => {
            parts.headers.remove(header::CONTENT_LENGTH);
            parts
                .headers
                .insert(header::CONTENT_ENCODING, HeaderValue::from_static("gzip"));
            Response::from_parts(parts, axum::body::Body::from(body))
        }
        Err(e) => {
            ApiError::internal(format!("the answer could not be compressed: {e}")).into_response()
        }
    }
}

/// Refuses requests from elsewhere (Host 421, Origin 403, Content-Type 415: see `access`),
/// bounds each request's total time (408) and marks every answer `nosniff`.
async fn guard(State(state): State<AppState>, request: Request, next: Next) -> Response {
    let limit = state.limits.request_timeout;
    let checked = crate::access::check(request.method(), request.headers(), state.bound);
    let answer = async move {
        match checked {
            Ok(()) => next.run(request).await,
            Err(refused) => refused.into_response(),
        }
    };
    let mut response = match tokio::time::timeout(limit, answer).await {
        Ok(response) => response,
        Err(_) => ApiError::new(
            StatusCode::REQUEST_TIMEOUT,
            "timeout",
            format!(
                "the request took longer than the server's limit of {} s",
                limit.as_secs_f64()
            ),
        )
        .into_response(),
    };
    response.headers_mut().insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    response
}
async fn not_found(request: Request) -> ApiError {
    crate::api::not_found(request.uri().path())
}

async fn method_not_allowed(request: Request) -> ApiError {
    crate::api::method_not_allowed(request.method().as_str(), request.uri().path())
}

/// The request body: 413 past the size limit, 400 when it cannot be read.
fn body_bytes(body: Result<Bytes, BytesRejection>) -> Result<Bytes, ApiError> {
    body.map_err(|rejection| {
        if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE {
            crate::api::too_large()
        } else {
            ApiError::new(
                StatusCode::BAD_REQUEST,
                "bad_request",
                rejection.body_text(),
            )
        }
    })
}

/// Reads a JSON body: 413 past the size limit, 400 when it is not JSON, 422 when it is JSON of
/// the wrong shape.
/// Sets its flag when dropped: when the request's future ends, whether the work finished, its
/// time ran out or the client went away.
struct StopOnDrop(Arc<AtomicBool>);

impl Drop for StopOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Leaves the heavy waiting line when dropped (served, refused or gone).
struct InLine(Arc<AtomicUsize>);

impl Drop for InLine {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::Relaxed);
    }
}

/// Seconds a client told "busy" is asked to wait before trying again (`Retry-After`).
const RETRY_AFTER_SECONDS: u64 = 2;

fn busy(message: String) -> ApiError {
    ApiError::new(StatusCode::SERVICE_UNAVAILABLE, "busy", message).retry_after(RETRY_AFTER_SECONDS)
}

/// A computing slot of `budget`: at once when one is free; else, for heavy work, a place in a
/// waiting line of at most `max_waiting_heavy` (503 `busy` at once past it); then at most
/// `queue_timeout` of waiting (503 `busy`).
async fn slot(state: &AppState, budget: Budget) -> Result<OwnedSemaphorePermit, ApiError> {
    let limits = state.limits;
    let (slots, what) = match budget {
        Budget::Interactive => (&state.interactive, "interactive"),
        Budget::Heavy => (&state.heavy, "heavy"),
    };
    match slots.clone().try_acquire_owned() {
        Ok(permit) => return Ok(permit),
        Err(TryAcquireError::Closed) => {
            return Err(ApiError::internal("the computing pool is closed"));
        }
        Err(TryAcquireError::NoPermits) => {}
    }
    let _in_line = match budget {
        Budget::Interactive => None,
        Budget::Heavy => {
            let ahead = state.heavy_waiting.fetch_add(1, Ordering::Relaxed);
            let place = InLine(state.heavy_waiting.clone());
            if ahead >= limits.max_waiting_heavy {
                return Err(busy(format!(
                    "the server is busy: all {} slots for heavy work (maps, studies, \
                     simulations, sweeps) are taken and {ahead} requests wait for one, the \
                     server's limit; try again in {RETRY_AFTER_SECONDS} s",
                    limits.max_concurrent_computations.max(1)
                )));
            }
            Some(place)
        }
    };
    tokio::time::timeout(limits.queue_timeout, slots.clone().acquire_owned())
        .await
        .map_err(|_| {
            busy(format!(
                "the server is busy: no {what} computing slot came free within {} s; try again",
                limits.queue_timeout.as_secs_f64()
            ))
        })?
        .map_err(|_| ApiError::internal("the computing pool is closed"))
}

/// Runs CPU-heavy work on the blocking pool, a bounded number at a time per `budget`, within
/// the limits; `advice` ends the timeout's message (what to ask for instead). The work gets a
/// stop flag, set once nobody waits for its result any more (time up, client gone): work that
/// can stop early (a simulation, a map) should, to give its computing slot back.
pub(crate) async fn compute<T: Send + 'static>(
    state: &AppState,
    budget: Budget,
    advice: &str,
    work: impl FnOnce(Arc<AtomicBool>) -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    let limits = state.limits;
    let permit = slot(state, budget).await?;
    let stop = StopOnDrop(Arc::new(AtomicBool::new(false)));
    let flag = stop.0.clone();
    // Taken before the work starts: a busy machine may run all of it before this thread
    // goes on.
    let started = std::time::Instant::now();
    let task = tokio::task::spawn_blocking(move || {
        // The slot stays taken until the work ends, even if the client has gone.
        let _permit = permit;
        work(flag)
    });
    match tokio::time::timeout(limits.compute_timeout, task).await {
        // The timer fires on its own coarse ticks: work that ends past the limit before the
        // tick is over the limit all the same, so the answer does not depend on the race.
        Ok(Ok(result)) if started.elapsed() <= limits.compute_timeout => result,
        Ok(Err(join)) => Err(ApiError::internal(format!(
            "the computation failed: {join}"
        ))),
        Ok(Ok(_)) | Err(_) => Err(ApiError::new(
            StatusCode::SERVICE_UNAVAILABLE,
            "timeout",
            format!(
                "the computation took longer than the server's limit of {} s; {advice}",
                limits.compute_timeout.as_secs_f64()
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::OPENAPI;
    use serde_json::Value;

    /// Work that ends past the limit is over it, even when it ends before the timer's next
    /// tick (about a millisecond): 200 µs of work against a 1 µs limit is a timeout every time.
    #[tokio::test]
    async fn work_past_the_limit_is_a_timeout_whatever_the_timer_tick() {
        let state = one_slot(Limits {
            compute_timeout: std::time::Duration::from_micros(1),
            ..Limits::default()
        });
        for _ in 0..20 {
            let result = compute(&state, Budget::Interactive, "wait less", |_| {
                let until = std::time::Instant::now() + std::time::Duration::from_micros(200);
                while std::time::Instant::now() < until {
                    std::hint::spin_loop();
                }
                Ok(())
            })
            .await;
            assert!(matches!(result, Err(ref e) if e.status == StatusCode::SERVICE_UNAVAILABLE));
        }
    }

    /// Work whose result nobody waits for any more is told to stop: after a timeout the flag
    /// is set while the work still runs, so a simulation gives its computing slot back instead
    /// of running to its step limit.
    #[tokio::test]
    async fn timed_out_work_is_told_to_stop() {
        let limits = Limits {
            compute_timeout: std::time::Duration::from_millis(20),
            ..Limits::default()
        };
        let state = one_slot(limits);
        let saw_stop = Arc::new(AtomicBool::new(false));
        let seen = saw_stop.clone();
        let result = compute(&state, Budget::Heavy, "wait less", move |stop| {
            // Bounded: 30 s at most, unless told to stop.
            let until = std::time::Instant::now() + std::time::Duration::from_secs(30);
            while std::time::Instant::now() < until {
                if stop.load(Ordering::Relaxed) {
                    seen.store(true, Ordering::Relaxed);
                    return Ok(());
                }
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            Ok(())
        })
        .await;
        assert!(matches!(result, Err(ref e) if e.status == StatusCode::SERVICE_UNAVAILABLE));
        // The slot comes back as soon as the work has stopped, long before its 30 s.
        slot_comes_back(&state, &saw_stop).await;
    }

    /// The heavy slot comes back within 10 s (long before the work's own 30 s), the work
    /// having seen its stop flag.
    async fn slot_comes_back(state: &AppState, saw_stop: &AtomicBool) {
        let permit = tokio::time::timeout(
            std::time::Duration::from_secs(10),
            state.heavy.clone().acquire_owned(),
        )
        .await;
        assert!(matches!(permit, Ok(Ok(_))), "the slot did not come back");
        assert!(saw_stop.load(Ordering::Relaxed));
    }

    /// A server's state with one computing slot of each budget.
    fn one_slot(limits: Limits) -> AppState {
        AppState {
            limits,
            bound: IpAddr::V4(Ipv4Addr::LOCALHOST),
            heavy: Arc::new(Semaphore::new(1)),
            heavy_waiting: Arc::new(AtomicUsize::new(0)),
            interactive: Arc::new(Semaphore::new(1)),
        }
    }

    /// An answer told line by line whose client goes away after the first progress line:
    /// the work is told to stop and its slot comes back, long before the work's 30 s.
    #[tokio::test]
    async fn work_told_line_by_line_stops_when_the_client_goes() -> Result<(), String> {
        use http_body_util::BodyExt;
        let state = one_slot(Limits::default());
        let saw_stop = Arc::new(AtomicBool::new(false));
        let seen = saw_stop.clone();
        let job = Job {
            budget: Budget::Heavy,
            advice: "wait less",
            work: Box::new(move |stop| {
                let until = std::time::Instant::now() + std::time::Duration::from_secs(30);
                let mut done = 0;
                while std::time::Instant::now() < until {
                    if stop.load(Ordering::Relaxed) {
                        seen.store(true, Ordering::Relaxed);
                        return Ok(Vec::new());
                    }
                    done += 1;
                    crate::api::report_progress(done, 1_000_000);
                    std::thread::sleep(std::time::Duration::from_millis(1));
                }
                Ok(b"{}".to_vec())
            }),
        };
        let mut body = run_in_lines(state.clone(), job, false).into_body();
        let first = tokio::time::timeout(std::time::Duration::from_secs(10), body.frame())
            .await
            .map_err(|_| "no first line within 10 s")?
            .ok_or("no first line")?
            .map_err(|e| e.to_string())?
            .into_data()
            .map_err(|_| "not data")?;
        assert!(first.starts_with(b"{\"progress\":["), "{first:?}");
        drop(body);
        slot_comes_back(&state, &saw_stop).await;
        Ok(())
    }

    /// `Accept` asks for the lines as a media range among others, in any case.
    #[test]
    fn lines_are_asked_for_with_accept() {
        let asked = |value: &'static str| {
            let mut headers = HeaderMap::new();
            headers.insert(header::ACCEPT, HeaderValue::from_static(value));
            wants_lines(&headers)
        };
        assert!(asked("application/x-ndjson"));
        assert!(asked("application/json;q=0.5, Application/X-NDJSON; q=1"));
        assert!(!asked("application/json"));
        assert!(!asked("*/*"));
        assert!(!wants_lines(&HeaderMap::new()));
    }

    /// The page calls only endpoints the OpenAPI document describes.
    #[test]
    fn page_uses_only_documented_endpoints() -> Result<(), serde_json::Error> {
        let doc: Value = serde_json::from_str(OPENAPI)?;
        let paths: Vec<String> = doc["paths"]
            .as_object()
            .map(|p| p.keys().cloned().collect())
            .unwrap_or_default();
        let text = assets::script_text();
        let script = text.as_str();
        let mut used = Vec::new();
        let mut rest = script;
        while let Some(at) = rest.find("/api/") {
            let tail = &rest[at..];
            let end = tail
                .find(|c: char| !(c.is_ascii_alphanumeric() || "/._-".contains(c)))
                .unwrap_or(tail.len());
            used.push(tail[..end].to_string());
            rest = &tail[end..];
        }
        assert!(used.len() >= 6, "found {used:?}");
        for path in used {
            let documented = paths.iter().any(|p| match p.find('{') {
                // A templated path: the script builds it from its fixed prefix.
                Some(brace) => path == p[..brace],
                None => path == *p,
            });
            assert!(
                documented,
                "the page calls {path}, which openapi.json does not describe"
            );
        }
        Ok(())
    }
}
