//! The router: the page, its assets and the JSON API described in `openapi.json`.
//!
//! Bicycles travel as the JSON layout of the parameter files (`{"name", "source",
//! "benchmark": {...}}` or `{..., "jbike6": {...}}`) and are read and written by
//! `whipple::advanced::io`, so the API, the CLI and the files agree on every key and rule.

use std::net::{IpAddr, Ipv4Addr};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, PathRejection};
use axum::extract::{DefaultBodyLimit, Path, Request, State};
use axum::http::{HeaderValue, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use tokio::sync::{OwnedSemaphorePermit, Semaphore, TryAcquireError};
use whipple::advanced::io;
use whipple::advanced::io::Format;
use whipple::advanced::parameters::Description;
use whipple::advanced::parameters::Notice;
use whipple::advanced::sensitivity;
use whipple::advanced::table;
use whipple::advanced::table::{Form, ParameterInfo};
use whipple::presets;
use whipple::presets::PRESETS;
use whipple::{Bicycle, Canonical};
use whipple::{CriticalSpeeds, critical_speeds, eigen_sweep, speed_grid};

use crate::closed_loop::closed_loop;
use crate::error::{ApiError, quoted_field};
use crate::geometry::{SideView, side_view};
use crate::modes::{self as mode_api, ModesRequest, ModesResponse, ResponseRequest};
use crate::simulation::{self, SimulateRequest};
use crate::{Limits, assets};

/// The OpenAPI 3 description of every `/api` route (served at `/api/openapi.json`).
pub const OPENAPI: &str = include_str!("openapi.json");

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

/// Which computing slots a request's work takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Budget {
    /// Milliseconds of work the page asks for as one types: never queued behind heavy work.
    Interactive,
    /// Work that may take a second or more: its own slots and a bounded waiting line.
    Heavy,
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
    Router::new()
        .route("/", get(assets::index))
        .route("/assets/{name}", get(assets::file))
        .route("/api/health", get(health))
        .route("/api/openapi.json", get(openapi))
        .route("/api/presets", get(list_presets))
        .route("/api/presets/{name}", get(get_preset))
        .route("/api/bike/validate", post(validate))
        .route("/api/bike/toml", post(to_toml))
        .route("/api/bike/parse", post(parse_file))
        .route("/api/parameters", get(parameter_table))
        .route("/api/sensitivity", post(sensitivity))
        .route("/api/eigen", post(eigen))
        .route("/api/speeds", post(speeds))
        .route("/api/simulate", post(simulate))
        .route("/api/modes", post(modes))
        .route("/api/linear/response", post(linear_response))
        .route("/api/linear/frequency", post(crate::frequency::frequency))
        .route("/api/linear/time", post(crate::time::time))
        .route("/api/linear/closed_loop", post(closed_loop))
        .route("/api/measure", post(crate::measure::measure))
        .route("/api/measure/samples", get(crate::measure::samples))
        .route("/api/map", post(crate::design::map))
        .route("/api/map/design", post(crate::design::design_at))
        .route("/api/turn", post(crate::turns::turn))
        .route("/api/study", post(crate::design::study))
        .route("/api/ridden", post(crate::ridden::ridden))
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .layer(DefaultBodyLimit::max(limits.max_body_bytes))
        .layer(middleware::from_fn(compress_json))
        .layer(middleware::from_fn_with_state(state.clone(), guard))
        .with_state(state)
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
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not_found",
        format!(
            "no such page or endpoint: {} (the API is described at /api/openapi.json)",
            request.uri().path()
        ),
    )
}

async fn method_not_allowed(request: Request) -> ApiError {
    ApiError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        "method_not_allowed",
        format!(
            "{} is not allowed on {} (see /api/openapi.json)",
            request.method(),
            request.uri().path()
        ),
    )
}

/// The request body: 413 past the size limit, 400 when it cannot be read.
fn body_bytes(body: Result<Bytes, BytesRejection>) -> Result<Bytes, ApiError> {
    body.map_err(|rejection| {
        if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::new(
                StatusCode::PAYLOAD_TOO_LARGE,
                "too_large",
                "the request body is larger than the server's limit",
            )
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
pub(crate) fn json_body<T: DeserializeOwned>(
    body: Result<Bytes, BytesRejection>,
) -> Result<T, ApiError> {
    let bytes = body_bytes(body)?;
    // A key named twice in one object is refused (serde_json would keep the last one), as in
    // every parameter file; then the body is read into its documented shape.
    whipple::advanced::io::json_slice_without_duplicates(&bytes)
        .map(drop)
        .and_then(|()| serde_json::from_slice(&bytes))
        .map_err(|e| {
            use serde_json::error::Category;
            match e.classify() {
                Category::Data => {
                    let what = strip_position(&e.to_string());
                    let mut error = ApiError::new(
                        StatusCode::UNPROCESSABLE_ENTITY,
                        "invalid_request",
                        format!("the request does not have the documented shape: {what}"),
                    );
                    error.body.field = quoted_field(&what);
                    error.body.rule = Some(what);
                    error
                }
                Category::Syntax | Category::Eof | Category::Io => ApiError::new(
                    StatusCode::BAD_REQUEST,
                    "bad_json",
                    format!("the request body is not valid JSON: {e}"),
                ),
            }
        })
}

fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(p) => message[..p].to_string(),
        None => message.to_string(),
    }
}

/// Reads a bicycle in the files' JSON layout through the library's reader.
pub(crate) fn bicycle(value: &Value) -> Result<Bicycle, ApiError> {
    let text = serde_json::to_string(value).map_err(|e| ApiError::internal(e.to_string()))?;
    io::parse(&text, Format::Json).map_err(|e| {
        let mut error = ApiError::from(e);
        // Positions refer to the re-serialized text, not to anything the client sent.
        error.body.line = None;
        error.body.column = None;
        error
    })
}

/// A bicycle in the files' JSON layout.
pub(crate) fn bicycle_json(bike: &Bicycle) -> Result<Value, ApiError> {
    let text = io::write(bike, Format::Json)?;
    serde_json::from_str(&text).map_err(|e| ApiError::internal(e.to_string()))
}

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

/// [`compute`], the answer written as JSON on the computing thread too: a map's or a
/// simulation's answer is megabytes, whose writing must not hold up the threads that answer
/// everything else.
pub(crate) async fn compute_json<T: Serialize + 'static>(
    state: &AppState,
    budget: Budget,
    advice: &str,
    work: impl FnOnce(Arc<AtomicBool>) -> Result<T, ApiError> + Send + 'static,
) -> Result<Response, ApiError> {
    let bytes = compute(state, budget, advice, move |stop| {
        let answer = work(stop)?;
        serde_json::to_vec(&answer)
            .map_err(|e| ApiError::internal(format!("the answer could not be written: {e}")))
    })
    .await?;
    Ok((
        [(
            header::CONTENT_TYPE,
            HeaderValue::from_static("application/json"),
        )],
        bytes,
    )
        .into_response())
}

#[derive(Serialize)]
struct Health {
    status: &'static str,
    version: &'static str,
}

async fn health() -> Json<Health> {
    Json(Health {
        status: "ok",
        version: env!("CARGO_PKG_VERSION"),
    })
}

async fn openapi() -> Response {
    (
        [(header::CONTENT_TYPE, "application/json")],
        OPENAPI.to_string(),
    )
        .into_response()
}

#[derive(Serialize)]
struct PresetSummary {
    name: &'static str,
    title: &'static str,
    summary: &'static str,
    source: &'static str,
    form: &'static str,
    /// A measured bicycle, its parameters with σ (the page lists them apart).
    measured: bool,
}

fn form_name(description: &Description) -> &'static str {
    match description {
        Description::Benchmark(_) => "benchmark",
        Description::Jbike6(_) => "jbike6",
    }
}

async fn list_presets() -> Json<Vec<PresetSummary>> {
    Json(
        PRESETS
            .iter()
            .map(|p| PresetSummary {
                name: p.name,
                title: p.title,
                summary: p.summary,
                source: p.source,
                form: form_name(&(p.description)()),
                measured: !p.measurements.is_empty(),
            })
            .collect(),
    )
}

async fn get_preset(name: Result<Path<String>, PathRejection>) -> Result<Json<Value>, ApiError> {
    // A name that is not UTF-8 once decoded (`/api/presets/%ff`) is answered in JSON too.
    let Path(name) = name.map_err(|rejection| {
        ApiError::new(
            StatusCode::NOT_FOUND,
            "not_found",
            format!("no such preset: {}", rejection.body_text()),
        )
    })?;
    let preset = presets::find(&name)?;
    Ok(Json(bicycle_json(&preset.bicycle())?))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BikeRequest {
    bike: Value,
}

#[derive(Serialize)]
struct Derived {
    /// Steer axis tilt λ [deg].
    steer_axis_tilt_deg: f64,
    /// Head angle from the horizontal, 90° − λ [deg].
    head_angle_deg: f64,
    /// Total mass [kg].
    total_mass: f64,
}

#[derive(Serialize)]
struct Validated {
    name: Option<String>,
    form: &'static str,
    benchmark: whipple::BenchmarkParameters,
    derived: Derived,
    side_view: SideView,
    /// The bicycle's warnings and notes (see `GET /api/parameters` for the fields).
    warnings: Vec<Notice>,
}

async fn validate(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Json<Validated>, ApiError> {
    let bytes = body_bytes(body)?;
    compute(
        &state,
        Budget::Interactive,
        "send a smaller bicycle",
        move |_| validate_bike(bytes),
    )
    .await
    .map(Json)
}

fn validate_bike(bytes: Bytes) -> Result<Validated, ApiError> {
    let request: BikeRequest = json_body(Ok(bytes))?;
    let bike = bicycle(&request.bike)?;
    let checked = bike.check()?;
    let benchmark = checked.benchmark;
    let view = side_view(&bike, &benchmark);
    Ok(Validated {
        name: bike.name.clone(),
        form: form_name(&bike.description),
        derived: Derived {
            steer_axis_tilt_deg: benchmark.lambda.to_degrees(),
            head_angle_deg: 90.0 - benchmark.lambda.to_degrees(),
            total_mass: view.total_mass,
        },
        benchmark,
        side_view: view,
        warnings: checked.notices,
    })
}

#[derive(Serialize)]
struct TomlText {
    toml: String,
}

async fn to_toml(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Json<TomlText>, ApiError> {
    let bytes = body_bytes(body)?;
    compute(
        &state,
        Budget::Interactive,
        "send a smaller bicycle",
        move |_| {
            let request: BikeRequest = json_body(Ok(bytes))?;
            let bike = bicycle(&request.bike)?;
            Ok(TomlText {
                toml: io::write(&bike, Format::Toml)?,
            })
        },
    )
    .await
    .map(Json)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ParseRequest {
    text: String,
    /// `toml`, `json`, `m`, `bp-txt`, `hc-txt`, `yaml`, or `auto` (from `file_name` and the text).
    format: String,
    /// The file's name, for `auto`.
    #[serde(default)]
    file_name: Option<String>,
}

#[derive(Serialize)]
struct Parsed {
    bike: Value,
    /// The format read (useful with `auto`).
    format: &'static str,
    /// What reading found: keys of other models, redundant values that disagree.
    warnings: Vec<Notice>,
}

async fn parse_file(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Json<Parsed>, ApiError> {
    let bytes = body_bytes(body)?;
    // Parsing a file of up to the body limit is work: on the computing pool, not the
    // workers that answer `/api/health`.
    compute(
        &state,
        Budget::Interactive,
        "send a smaller file",
        move |_| {
            let request: ParseRequest = json_body(Ok(bytes))?;
            let format = if request.format == "auto" {
                Format::detect(request.file_name.as_deref().unwrap_or(""), &request.text)?
            } else {
                Format::from_name(&request.format).ok_or_else(|| {
                    ApiError::new(
                        StatusCode::UNPROCESSABLE_ENTITY,
                        "invalid_request",
                        format!(
                            "unknown format `{}` (formats: {}, auto)",
                            whipple::advanced::shorten(&request.format, 40),
                            whipple_front::formats::names()
                        ),
                    )
                    .at(
                        "format",
                        format!("one of {}, auto", whipple_front::formats::names()),
                    )
                })?
            };
            let mut bike = io::parse(&request.text, format)?;
            // A file without a name of its own is named after the file, as the CLI names it.
            if bike.name.is_none() {
                bike.name = request
                    .file_name
                    .as_deref()
                    .and_then(|f| io::name_from_file_name(f, format));
            }
            Ok(Parsed {
                bike: bicycle_json(&bike)?,
                format: format.name(),
                warnings: bike.notices.clone(),
            })
        },
    )
    .await
    .map(Json)
}

#[derive(Serialize)]
struct ParameterTable {
    benchmark: &'static [ParameterInfo],
    jbike6: &'static [ParameterInfo],
    /// Benchmark key → the JBike6 entries to flag for it (the library's
    /// `jbike6::BENCHMARK_FROM_JBIKE6`).
    jbike6_sources: std::collections::BTreeMap<&'static str, &'static [&'static str]>,
}

/// The one parameter table of the library: every parameter of both forms with its key, path,
/// symbol, unit, description and whether the linear model sees it, and which JBike6 entries
/// each benchmark key comes from.
async fn parameter_table() -> Json<ParameterTable> {
    Json(ParameterTable {
        benchmark: table::parameters(Form::Benchmark),
        jbike6: table::parameters(Form::Jbike6),
        jbike6_sources: whipple::advanced::parameters::BENCHMARK_FROM_JBIKE6
            .into_iter()
            .collect(),
    })
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SensitivityRequest {
    bike: Value,
    #[serde(default)]
    range: Option<SpeedRange>,
    #[serde(default)]
    speed: Option<f64>,
}

#[derive(Serialize)]
struct SensitivityResponse {
    name: Option<String>,
    #[serde(flatten)]
    sensitivities: sensitivity::Sensitivities,
    /// σ of the critical speeds from the parameters' sigmas.
    double_root_speed_sigma: Option<f64>,
    weave_speed_sigma: Option<f64>,
    capsize_speed_sigma: Option<f64>,
    warnings: Vec<Notice>,
}

async fn sensitivity(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let request: SensitivityRequest = json_body(body)?;
    let bike = bicycle(&request.bike)?;
    let (lo, hi) = SpeedRange::bounds(request.range);
    let speed = request.speed;
    compute_json(
        &state,
        Budget::Heavy,
        "ask for a narrower range",
        move |_| {
            let checked = bike.check()?;
            let s = sensitivity::sensitivities(&bike, lo, hi, speed)?;
            let u = sensitivity::critical_speeds_sigma(&bike, lo, hi)?;
            Ok(SensitivityResponse {
                name: bike.name.clone(),
                sensitivities: s,
                double_root_speed_sigma: u.double_root_speed_sigma,
                weave_speed_sigma: u.weave_speed_sigma,
                capsize_speed_sigma: u.capsize_speed_sigma,
                warnings: checked.notices,
            })
        },
    )
    .await
}

#[derive(Deserialize, Clone, Copy, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct SpeedGrid {
    pub(crate) start: f64,
    pub(crate) stop: f64,
    pub(crate) step: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EigenRequest {
    bike: Value,
    speeds: SpeedGrid,
}

#[derive(Serialize)]
pub(crate) struct EigenColumn {
    mode: &'static str,
    re: Vec<f64>,
    im: Vec<f64>,
}

impl EigenColumn {
    /// The sweep's columns, one per tracked eigenvalue, as `/api/eigen` answers them.
    pub(crate) fn of(sweep: &whipple::EigenSweep) -> Vec<EigenColumn> {
        (0..4)
            .map(|k| EigenColumn {
                mode: sweep.modes[k].name(),
                re: sweep.eigenvalues.iter().map(|row| row[k].re).collect(),
                im: sweep.eigenvalues.iter().map(|row| row[k].im).collect(),
            })
            .collect()
    }
}

#[derive(Serialize)]
struct EigenResponse {
    name: Option<String>,
    speeds: Vec<f64>,
    eigenvalues: Vec<EigenColumn>,
    critical: Option<Critical>,
}

/// The critical speeds, with their σ (`*_sigma`, `stable_speed_ranges_sigma`) in line for a
/// bicycle whose parameters carry standard deviations.
#[derive(Serialize)]
#[serde(untagged)]
enum Critical {
    Plain(CriticalSpeeds),
    WithSigma(sensitivity::CriticalSpeedsSigma),
}

/// Sweeps of at most this many speeds (the page's plot asks for a few hundred as one types)
/// take the interactive budget; longer ones are heavy work.
pub(crate) const INTERACTIVE_SPEEDS: f64 = 2_000.0;

/// The number of speeds on the grid, as the library counts them (`sweep::SpeedGrid::count`; 0 when it
/// is not a valid grid: the library says why when the sweep is built),
/// checked against the limit before the grid is built, so that no huge vector is ever
/// allocated.
pub(crate) fn check_grid(grid: SpeedGrid, max_speeds: usize) -> Result<f64, ApiError> {
    let SpeedGrid { start, stop, step } = grid;
    let Ok(count) = whipple::advanced::sweep::SpeedGrid::count(start, stop, step) else {
        return Ok(0.0);
    };
    if count > max_speeds as f64 {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "limit_exceeded",
            format!(
                "{start}:{stop}:{step} holds {count} speeds, more than this server's limit of {max_speeds} per request; use a larger step"
            ),
        )
        .at(
            "speeds",
            format!("at most {max_speeds} speeds per request"),
        ));
    }
    Ok(count)
}

async fn eigen(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let request: EigenRequest = json_body(body)?;
    let bike = bicycle(&request.bike)?;
    let grid = request.speeds;
    let count = check_grid(grid, state.limits.max_speeds)?;
    let budget = if count <= INTERACTIVE_SPEEDS {
        Budget::Interactive
    } else {
        Budget::Heavy
    };
    compute_json(&state, budget, "ask for fewer speeds", move |_| {
        let benchmark = bike.benchmark()?;
        let canonical = Canonical::new(&benchmark)?;
        let speeds = speed_grid(grid.start, grid.stop, grid.step)?;
        let sweep = eigen_sweep(&canonical, &speeds)?;
        let (lo, hi) = (
            speeds.first().copied().unwrap_or(grid.start),
            speeds.last().copied().unwrap_or(grid.stop),
        );
        let critical = if hi <= lo {
            None
        } else if bike.has_uncertainty() {
            Some(Critical::WithSigma(sensitivity::critical_speeds_sigma(
                &bike, lo, hi,
            )?))
        } else {
            Some(Critical::Plain(critical_speeds(&canonical, lo, hi)?))
        };
        let eigenvalues = EigenColumn::of(&sweep);
        Ok(EigenResponse {
            name: bike.name.clone(),
            speeds: sweep.speeds,
            eigenvalues,
            critical,
        })
    })
    .await
}

/// A speed range; `hi` null or left out for no upper end.
#[derive(Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub(crate) struct SpeedRange {
    pub(crate) lo: f64,
    #[serde(default)]
    pub(crate) hi: Option<f64>,
}

impl SpeedRange {
    pub(crate) fn bounds(range: Option<SpeedRange>) -> (f64, f64) {
        range.map_or((0.0, f64::INFINITY), |r| {
            (r.lo, r.hi.unwrap_or(f64::INFINITY))
        })
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpeedsRequest {
    bike: Value,
    #[serde(default)]
    range: Option<SpeedRange>,
}

async fn speeds(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Json<CriticalSpeeds>, ApiError> {
    let request: SpeedsRequest = json_body(body)?;
    let bike = bicycle(&request.bike)?;
    let (lo, hi) = SpeedRange::bounds(request.range);
    let result = compute(
        &state,
        Budget::Interactive,
        "ask for a narrower range",
        move |_| {
            let canonical = Canonical::new(&bike.benchmark()?)?;
            Ok(critical_speeds(&canonical, lo, hi)?)
        },
    )
    .await?;
    Ok(Json(result))
}

async fn simulate(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let request: SimulateRequest = json_body(body)?;
    let bike = bicycle(&request.bike)?;
    let plan = simulation::check(&request, &state.limits)?;
    let max_steps = state.limits.max_sim_steps;
    compute_json(
        &state,
        Budget::Heavy,
        "simulate a shorter time or use a larger dt",
        move |stop| {
            let benchmark = bike.benchmark()?;
            simulation::run(bike.name.clone(), &benchmark, plan, max_steps, stop)
        },
    )
    .await
}

async fn modes(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Json<ModesResponse>, ApiError> {
    let request: ModesRequest = json_body(body)?;
    let bike = bicycle(&request.bike)?;
    let speed = mode_api::check_modes(&request)?;
    let response = compute(&state, Budget::Interactive, "try again", move |_| {
        let canonical = Canonical::new(&bike.benchmark()?)?;
        mode_api::modes(bike.name.clone(), &canonical, speed)
    })
    .await?;
    Ok(Json(response))
}

async fn linear_response(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let request: ResponseRequest = json_body(body)?;
    let bike = bicycle(&request.bike)?;
    let plan = mode_api::check_response(&request, &state.limits)?;
    compute_json(
        &state,
        Budget::Heavy,
        "ask for a shorter time or a larger dt",
        move |_| {
            let canonical = Canonical::new(&bike.benchmark()?)?;
            mode_api::response(bike.name.clone(), &canonical, plan)
        },
    )
    .await
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Work that ends past the limit is over it, even when it ends before the timer's next
    /// tick (about a millisecond): 200 µs of work against a 1 µs limit is a timeout every time.
    #[tokio::test]
    async fn work_past_the_limit_is_a_timeout_whatever_the_timer_tick() {
        let state = AppState {
            limits: Limits {
                compute_timeout: std::time::Duration::from_micros(1),
                ..Limits::default()
            },
            bound: IpAddr::V4(Ipv4Addr::LOCALHOST),
            heavy: Arc::new(Semaphore::new(1)),
            heavy_waiting: Arc::new(AtomicUsize::new(0)),
            interactive: Arc::new(Semaphore::new(1)),
        };
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
        let state = AppState {
            limits,
            bound: IpAddr::V4(Ipv4Addr::LOCALHOST),
            heavy: Arc::new(Semaphore::new(1)),
            heavy_waiting: Arc::new(AtomicUsize::new(0)),
            interactive: Arc::new(Semaphore::new(1)),
        };
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
        let permit = tokio::time::timeout(
            std::time::Duration::from_secs(10),
            state.heavy.clone().acquire_owned(),
        )
        .await;
        assert!(matches!(permit, Ok(Ok(_))), "the slot did not come back");
        assert!(saw_stop.load(Ordering::Relaxed));
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
