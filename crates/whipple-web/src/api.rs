//! The JSON API described in `openapi.json`, without a transport: [`routes`] names each
//! endpoint's handler, which reads the request and returns the work to do as a [`Job`]. The
//! server (`server.rs`) runs the jobs on its computing pool under its limits; [`answer`] runs
//! one at once, for a caller without a server (the static site's WebAssembly module), so that
//! both answer with the same bytes and the same messages.
//!
//! Bicycles travel as the JSON layout of the parameter files (`{"name", "source",
//! "benchmark": {...}}` or `{..., "jbike6": {...}}`) and are read and written by
//! `whipple::advanced::io`, so the API, the CLI and the files agree on every key and rule.

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use bytes::Bytes;
use http::StatusCode;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;
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

use crate::Limits;
use crate::error::{ApiError, quoted_field};
use crate::geometry::{SideView, side_view};
use crate::modes::{self as mode_api, ModesRequest, ResponseRequest};
use crate::simulation::{self, SimulateRequest};

/// The OpenAPI 3 description of every `/api` route (served at `/api/openapi.json`).
pub const OPENAPI: &str = include_str!("openapi.json");

/// Which computing slots a request's work takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Budget {
    /// Milliseconds of work the page asks for as one types: never queued behind heavy work.
    Interactive,
    /// Work that may take a second or more: its own slots and a bounded waiting line.
    Heavy,
}

/// The work a request asks for, once read and checked: run with a stop flag (set once nobody
/// waits for the answer any more), it returns the answer's JSON.
pub(crate) type Work = Box<dyn FnOnce(Arc<AtomicBool>) -> Result<Vec<u8>, ApiError> + Send>;

/// A request read and checked, its work still to do.
#[cfg_attr(not(feature = "server"), allow(dead_code))]
pub(crate) struct Job {
    /// The slots it takes on the server.
    pub(crate) budget: Budget,
    /// What a client whose request timed out should ask for instead.
    pub(crate) advice: &'static str,
    pub(crate) work: Work,
}

impl Job {
    /// Work whose answer is written as JSON when it ends (on the computing thread: a map's or
    /// a simulation's answer is megabytes, whose writing must not hold up anything else).
    pub(crate) fn json<T: Serialize + 'static>(
        budget: Budget,
        advice: &'static str,
        work: impl FnOnce(Arc<AtomicBool>) -> Result<T, ApiError> + Send + 'static,
    ) -> Job {
        Job {
            budget,
            advice,
            work: Box::new(move |stop| {
                let answer = work(stop)?;
                to_json(&answer)
            }),
        }
    }
}

fn to_json<T: Serialize + ?Sized>(answer: &T) -> Result<Vec<u8>, ApiError> {
    serde_json::to_vec(answer)
        .map_err(|e| ApiError::internal(format!("the answer could not be written: {e}")))
}

/// How an endpoint answers.
#[derive(Clone, Copy)]
pub(crate) enum Handler {
    /// A GET of fixed data, answered at once; the argument is the path's `{name}` (decoded),
    /// empty for a path without one.
    Get(fn(&str) -> Result<Vec<u8>, ApiError>),
    /// A POST of a JSON body: read and checked against the limits, its work returned.
    Post(fn(&Limits, Bytes) -> Result<Job, ApiError>),
}

/// One endpoint: its path (`{name}` for the one templated segment) and its handler.
pub(crate) struct Route {
    pub(crate) path: &'static str,
    pub(crate) handler: Handler,
}

const fn get(path: &'static str, answer: fn(&str) -> Result<Vec<u8>, ApiError>) -> Route {
    Route {
        path,
        handler: Handler::Get(answer),
    }
}

const fn post(path: &'static str, prepare: fn(&Limits, Bytes) -> Result<Job, ApiError>) -> Route {
    Route {
        path,
        handler: Handler::Post(prepare),
    }
}

/// The endpoints the page's first view asks for (the presets, the parameter table, a bicycle
/// checked and its eigenvalues with the critical speeds and σ): the first rows of the one table
/// of endpoints, [`routes`]. Without the crate feature `all-routes` they are the only ones
/// compiled, so that the static site's first module holds a third of the whole (its worker
/// loads the whole module for any other endpoint, `web/src/worker.js`).
pub(crate) const FIRST_VIEW: &[Route] = &[
    get("/api/health", health),
    get("/api/presets", list_presets),
    get("/api/presets/{name}", get_preset),
    get("/api/parameters", parameter_table),
    post("/api/bike/validate", validate),
    post("/api/eigen", eigen),
];

/// The other endpoints of `openapi.json`: the rest of [`routes`].
#[cfg(feature = "all-routes")]
const REST: &[Route] = &[
    get("/api/openapi.json", openapi),
    post("/api/bike/toml", to_toml),
    post("/api/bike/parse", parse_file),
    post("/api/sensitivity", sensitivity),
    post("/api/speeds", speeds),
    post("/api/simulate", simulate),
    post("/api/modes", modes),
    post("/api/linear/response", linear_response),
    post("/api/linear/frequency", crate::frequency::frequency),
    post("/api/linear/time", crate::time::time),
    post("/api/linear/closed_loop", crate::closed_loop::closed_loop),
    post("/api/measure", crate::measure::measure),
    get("/api/measure/samples", crate::measure::samples),
    post("/api/map", crate::design::map),
    post("/api/map/design", crate::design::design_at),
    post("/api/turn", crate::turns::turn),
    post("/api/study", crate::design::study),
    post("/api/ridden", crate::ridden::ridden),
];
#[cfg(not(feature = "all-routes"))]
const REST: &[Route] = &[];

/// Every endpoint of `openapi.json` compiled in, the one table the server routes and
/// [`answer`] reads: [`FIRST_VIEW`], then the rest (with the feature `all-routes`).
pub(crate) fn routes() -> impl Iterator<Item = &'static Route> {
    FIRST_VIEW.iter().chain(REST)
}

/// Whether this build answers `path` (`/api/eigen`; a query is ignored): every path of
/// `openapi.json` with the feature `all-routes`, the first view's alone without it.
pub fn answers(path: &str) -> bool {
    matching(path).is_some()
}

/// An answer without a server: its HTTP status and JSON body.
#[derive(Debug, Clone, PartialEq)]
pub struct Answer {
    /// The status the server would answer with.
    pub status: u16,
    /// The JSON body, byte for byte the server's (uncompressed).
    pub body: Vec<u8>,
}

/// Answers one API request at once, on this thread, as the server would: `method` (`GET`,
/// `POST`), `path` (`/api/eigen`, `/api/presets/benchmark`; percent-encoded as in a URL) and
/// the body. The same handlers, limits and messages as the server's; what only a server has
/// (computing slots, time limits, Host and Origin checks, compression) is left out: a caller
/// stops long work by setting `stop`, or by dropping the thread it runs on.
pub fn answer(
    method: &str,
    path: &str,
    body: &[u8],
    limits: &Limits,
    stop: Arc<AtomicBool>,
) -> Answer {
    let result = route(method, path, body, limits).and_then(|job| match job {
        Routed::Now(bytes) => Ok(bytes),
        Routed::Work(job) => (job.work)(stop),
    });
    match result {
        Ok(body) => Answer { status: 200, body },
        Err(error) => Answer {
            status: error.status.as_u16(),
            body: error.json(),
        },
    }
}

/// A hook told `(done, total)` as long work advances.
pub type ProgressHook = Rc<dyn Fn(u64, u64)>;

thread_local! {
    /// The progress hook of the answer running on this thread ([`answer_with_progress`]).
    static PROGRESS: RefCell<Option<ProgressHook>> = const { RefCell::new(None) };
}

/// [`answer`], with `progress(done, total)` called as long work advances (a map's or a
/// study's designs, after every chunk of them), on this thread: the static site's worker
/// passes it on to the page (the server's answers told line by line do the same, `server.rs`).
pub fn answer_with_progress(
    method: &str,
    path: &str,
    body: &[u8],
    limits: &Limits,
    stop: Arc<AtomicBool>,
    progress: ProgressHook,
) -> Answer {
    with_progress(progress, || answer(method, path, body, limits, stop))
}

/// Runs `work` with `progress` told how far it is on this thread, the hook taken away again
/// however the work ends.
pub(crate) fn with_progress<R>(progress: ProgressHook, work: impl FnOnce() -> R) -> R {
    /// Takes the hook away again however the work ends.
    struct Hooked;
    impl Drop for Hooked {
        fn drop(&mut self) {
            PROGRESS.with(|hook| hook.borrow_mut().take());
        }
    }
    PROGRESS.with(|hook| *hook.borrow_mut() = Some(progress));
    let _hooked = Hooked;
    work()
}

/// Tells the hook of [`answer_with_progress`], if this thread has one, how far the work is.
pub(crate) fn report_progress(done: u64, total: u64) {
    let hook = PROGRESS.with(|hook| hook.borrow().clone());
    if let Some(hook) = hook {
        hook(done, total);
    }
}

enum Routed {
    Now(Vec<u8>),
    Work(Job),
}

/// The route for `path` and its `{name}` segment (still percent-encoded), if any.
fn matching(path: &str) -> Option<(&'static Route, Option<&str>)> {
    let path = path.split(['?', '#']).next().unwrap_or(path);
    routes().find_map(|route| match route.path.find('{') {
        Some(brace) => match path.strip_prefix(&route.path[..brace]) {
            Some(rest) if !rest.is_empty() && !rest.contains('/') => Some((route, Some(rest))),
            _ => None,
        },
        None if route.path == path => Some((route, None)),
        None => None,
    })
}

fn route(method: &str, path: &str, body: &[u8], limits: &Limits) -> Result<Routed, ApiError> {
    let path = path.split(['?', '#']).next().unwrap_or(path);
    let Some((route, name)) = matching(path) else {
        return Err(not_found(path));
    };
    match (route.handler, method) {
        (Handler::Get(answer), "GET") => {
            let name = match name {
                Some(encoded) => percent_decoded(encoded)?,
                None => String::new(),
            };
            answer(&name).map(Routed::Now)
        }
        (Handler::Post(prepare), "POST") => {
            if body.len() > limits.max_body_bytes {
                return Err(too_large());
            }
            prepare(limits, Bytes::copy_from_slice(body)).map(Routed::Work)
        }
        _ => Err(method_not_allowed(method, path)),
    }
}

/// A path segment decoded as a URL's (`%2F` to `/`), refused when not UTF-8 once decoded.
fn percent_decoded(segment: &str) -> Result<String, ApiError> {
    let bytes = segment.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        match (
            bytes[i],
            bytes.get(i + 1).copied().and_then(hex),
            bytes.get(i + 2).copied().and_then(hex),
        ) {
            (b'%', Some(hi), Some(lo)) => {
                out.push((hi * 16 + lo) as u8);
                i += 3;
            }
            (b, _, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8(out).map_err(|_| {
        undecodable_name(&format!(
            "the path segment `{}` is not UTF-8 once decoded",
            whipple::advanced::shorten(segment, 40)
        ))
    })
}

/// 404 for a path no endpoint has.
pub(crate) fn not_found(path: &str) -> ApiError {
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not_found",
        format!("no such page or endpoint: {path} (the API is described at /api/openapi.json)"),
    )
}

/// 405 for a method an endpoint does not take.
pub(crate) fn method_not_allowed(method: &str, path: &str) -> ApiError {
    ApiError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        "method_not_allowed",
        format!("{method} is not allowed on {path} (see /api/openapi.json)"),
    )
}

/// 413 for a body past the limit.
pub(crate) fn too_large() -> ApiError {
    ApiError::new(
        StatusCode::PAYLOAD_TOO_LARGE,
        "too_large",
        "the request body is larger than the server's limit",
    )
}

/// 404 for a preset's name that cannot be decoded.
pub(crate) fn undecodable_name(why: &str) -> ApiError {
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not_found",
        format!("no such preset: {why}"),
    )
}

/// Reads a JSON body: 400 when it is not JSON, 422 when it is JSON of the wrong shape.
pub(crate) fn json_body<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    // A key named twice in one object is refused (serde_json would keep the last one), as in
    // every parameter file; then the body is read into its documented shape.
    whipple::advanced::io::json_slice_without_duplicates(bytes)
        .map(drop)
        .and_then(|()| serde_json::from_slice(bytes))
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

/// A bicycle in the files' JSON layout, every value in SI units: the page's fields and every
/// answer of the API are SI. The units a file was typed in (`c_mm`, `lam_deg`) travel apart
/// ([`typed_units`], `units` of `POST /api/bike/parse` and `POST /api/bike/toml`).
pub(crate) fn bicycle_json(bike: &Bicycle) -> Result<Value, ApiError> {
    let text = if bike.units.is_empty() {
        io::write(bike, Format::Json)?
    } else {
        let si = Bicycle {
            units: Default::default(),
            ..bike.clone()
        };
        io::write(&si, Format::Json)?
    };
    serde_json::from_str(&text).map_err(|e| ApiError::internal(e.to_string()))
}

/// The units a bicycle's parameters were typed in, by key, as their symbols (`c` → `mm`,
/// `lam` → `deg`): what `POST /api/bike/parse` answers besides the SI bicycle.
fn typed_units(bike: &Bicycle) -> std::collections::BTreeMap<String, &'static str> {
    bike.units
        .iter()
        .map(|(key, unit)| (key.clone(), unit.symbol()))
        .collect()
}

/// The units a client asks a bicycle to be written in (`{"c": "mm", "lam": "deg"}`, as
/// `POST /api/bike/parse` gave them), checked against the bicycle's form: each key must be one
/// of its parameters, and the unit one that quantity takes (`mm` a length, `deg` an angle).
fn with_typed_units(
    mut bike: Bicycle,
    units: &std::collections::BTreeMap<String, String>,
) -> Result<Bicycle, ApiError> {
    let form = match bike.description {
        Description::Benchmark(_) => Form::Benchmark,
        Description::Jbike6(_) => Form::Jbike6,
    };
    for (key, symbol) in units {
        let field = format!("units.{key}");
        let refuse = |message: String, expected: &str| {
            ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "invalid_request", message)
                .at(&field, expected)
        };
        let Some(unit) = table::TypedUnit::ALL
            .into_iter()
            .find(|u| u.symbol() == symbol)
        else {
            return Err(refuse(
                format!(
                    "`{}`: the units a parameter is written in are mm and deg",
                    whipple::advanced::shorten(symbol, 40)
                ),
                "mm or deg",
            ));
        };
        match table::find_typed(form, &format!("{key}{}", unit.suffix())) {
            Ok(Some((_, Some(_)))) => {
                bike.units.insert(key.clone(), unit);
            }
            Ok(_) => {
                return Err(refuse(
                    format!(
                        "`{}` is not a parameter of this bicycle's {} form",
                        whipple::advanced::shorten(key, 40),
                        form_name(&bike.description)
                    ),
                    "a parameter of the bicycle's form",
                ));
            }
            Err(rule) => return Err(refuse(rule, "a unit the quantity takes")),
        }
    }
    Ok(bike)
}

#[derive(Serialize)]
struct Health {
    status: &'static str,
    version: &'static str,
}

fn health(_: &str) -> Result<Vec<u8>, ApiError> {
    to_json(&Health {
        status: "ok",
        version: env!("CARGO_PKG_VERSION"),
    })
}

fn openapi(_: &str) -> Result<Vec<u8>, ApiError> {
    Ok(OPENAPI.as_bytes().to_vec())
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

fn list_presets(_: &str) -> Result<Vec<u8>, ApiError> {
    to_json(
        &PRESETS
            .iter()
            .map(|p| PresetSummary {
                name: p.name,
                title: p.title,
                summary: p.summary,
                source: p.source,
                form: form_name(&(p.description)()),
                measured: !p.measurements.is_empty(),
            })
            .collect::<Vec<_>>(),
    )
}

fn get_preset(name: &str) -> Result<Vec<u8>, ApiError> {
    let preset = presets::find(name)?;
    to_json(&bicycle_json(&preset.bicycle())?)
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

fn validate(_: &Limits, bytes: Bytes) -> Result<Job, ApiError> {
    Ok(Job::json(
        Budget::Interactive,
        "send a smaller bicycle",
        move |_| validate_bike(&bytes),
    ))
}

fn validate_bike(bytes: &[u8]) -> Result<Validated, ApiError> {
    let request: BikeRequest = json_body(bytes)?;
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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TomlRequest {
    bike: Value,
    /// The units to write keys in, as `POST /api/bike/parse` answered them (`{"c": "mm"}`).
    #[serde(default)]
    units: std::collections::BTreeMap<String, String>,
}

fn to_toml(_: &Limits, bytes: Bytes) -> Result<Job, ApiError> {
    Ok(Job::json(
        Budget::Interactive,
        "send a smaller bicycle",
        move |_| {
            let request: TomlRequest = json_body(&bytes)?;
            let bike = with_typed_units(bicycle(&request.bike)?, &request.units)?;
            Ok(TomlText {
                toml: io::write(&bike, Format::Toml)?,
            })
        },
    ))
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
    /// The units the file typed its parameters in where not SI, by key (`{"c": "mm"}`); the
    /// bicycle itself is SI. Give them back to `POST /api/bike/toml` to write the file in them.
    units: std::collections::BTreeMap<String, &'static str>,
    /// What reading found: keys of other models, redundant values that disagree.
    warnings: Vec<Notice>,
}

fn parse_file(_: &Limits, bytes: Bytes) -> Result<Job, ApiError> {
    // Parsing a file of up to the body limit is work: on the computing pool, not the
    // workers that answer `/api/health`.
    Ok(Job::json(
        Budget::Interactive,
        "send a smaller file",
        move |_| {
            let request: ParseRequest = json_body(&bytes)?;
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
                units: typed_units(&bike),
                warnings: bike.notices.clone(),
            })
        },
    ))
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
fn parameter_table(_: &str) -> Result<Vec<u8>, ApiError> {
    to_json(&ParameterTable {
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

fn sensitivity(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: SensitivityRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let (lo, hi) = SpeedRange::bounds(request.range);
    let speed = request.speed;
    Ok(Job::json(
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
    ))
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

fn eigen(limits: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: EigenRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let grid = request.speeds;
    let count = check_grid(grid, limits.max_speeds)?;
    let budget = if count <= INTERACTIVE_SPEEDS {
        Budget::Interactive
    } else {
        Budget::Heavy
    };
    Ok(Job::json(budget, "ask for fewer speeds", move |_| {
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
    }))
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

fn speeds(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: SpeedsRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let (lo, hi) = SpeedRange::bounds(request.range);
    Ok(Job::json(
        Budget::Interactive,
        "ask for a narrower range",
        move |_| {
            let canonical = Canonical::new(&bike.benchmark()?)?;
            Ok(critical_speeds(&canonical, lo, hi)?)
        },
    ))
}

fn simulate(limits: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: SimulateRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let plan = simulation::check(&request, limits)?;
    let max_steps = limits.max_sim_steps;
    Ok(Job::json(
        Budget::Heavy,
        "simulate a shorter time or use a larger dt",
        move |stop| {
            let benchmark = bike.benchmark()?;
            simulation::run(bike.name.clone(), &benchmark, plan, max_steps, stop)
        },
    ))
}

fn modes(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: ModesRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let speed = mode_api::check_modes(&request)?;
    Ok(Job::json(Budget::Interactive, "try again", move |_| {
        let canonical = Canonical::new(&bike.benchmark()?)?;
        mode_api::modes(bike.name.clone(), &canonical, speed)
    }))
}

fn linear_response(limits: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: ResponseRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let plan = mode_api::check_response(&request, limits)?;
    Ok(Job::json(
        Budget::Heavy,
        "ask for a shorter time or a larger dt",
        move |_| {
            let canonical = Canonical::new(&bike.benchmark()?)?;
            mode_api::response(bike.name.clone(), &canonical, plan)
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_view_is_answered_by_every_build_and_the_rest_with_all_routes() {
        for route in FIRST_VIEW {
            assert!(
                answers(&route.path.replace("{name}", "benchmark")),
                "{}",
                route.path
            );
        }
        assert!(answers("/api/presets/benchmark?x=1"));
        assert!(!answers("/api/presets/"));
        assert!(!answers("/api/nowhere"));
        assert_eq!(answers("/api/map"), cfg!(feature = "all-routes"));
        assert_eq!(answers("/api/openapi.json"), cfg!(feature = "all-routes"));
        assert_eq!(
            routes().count(),
            if cfg!(feature = "all-routes") {
                24
            } else {
                FIRST_VIEW.len()
            }
        );
    }

    #[test]
    #[cfg(feature = "all-routes")]
    fn a_maps_progress_is_reported_chunk_by_chunk_and_only_to_its_own_answer() {
        let seen = Rc::new(RefCell::new(Vec::new()));
        let into = Rc::clone(&seen);
        let bike = answer(
            "GET",
            "/api/presets/benchmark",
            b"",
            &Limits::default(),
            Arc::default(),
        );
        let bike: Value = serde_json::from_slice(&bike.body).unwrap();
        let body = serde_json::json!({"bike": bike, "x": "trail=0.02:0.2:300", "y": "head_angle_deg=60:80:150"});
        let body = serde_json::to_vec(&body).unwrap();
        let answered = answer_with_progress(
            "POST",
            "/api/map",
            &body,
            &Limits::default(),
            Arc::default(),
            Rc::new(move |done, total| into.borrow_mut().push((done, total))),
        );
        assert_eq!(
            answered.status,
            200,
            "{}",
            String::from_utf8_lossy(&answered.body)
        );
        let seen = seen.borrow().clone();
        // 45,000 designs: a chunk of 32,768, then the rest.
        assert_eq!(seen, vec![(32_768, 45_000), (45_000, 45_000)]);
        // The hook went with its answer: the next answer reports to nobody.
        assert!(PROGRESS.with(|hook| hook.borrow().is_none()));
    }
}
