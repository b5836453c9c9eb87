//! `POST /api/measure`: a bicycle from bench measurements, what the page's Measure tab shows as
//! the form is filled. The measurements come as the text of BicycleParameters'
//! `<Name>Measured.txt` or as JSON key → value and σ under the file's keys; both are read by the
//! core's reader (`read_measurements`, the JSON written as that file's lines), so the same keys
//! and rules hold, and the numbers are the core's pipeline's (`MeasuredParameters`): the
//! benchmark parameters with σ, every step of the report, the largest correlations, and the
//! bicycle's warnings. `GET /api/measure/samples` gives the tab's sample files.

use bytes::Bytes;
use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use whipple::Bicycle;
use whipple::advanced::io::{Format, name_from_file_name};
use whipple::advanced::measured::{
    Correlation, Measured, MeasuredFile, MeasuredParameters, Step, read_measurements,
};
use whipple::advanced::parameters::Notice;
use whipple::advanced::rider::{
    CONFIGURATION_ANGLES, read_yeadon_configuration, read_yeadon_measurements,
};
use whipple::advanced::table::{Form, parameters};

use crate::Limits;
use crate::api::{Budget, Job, bicycle_json, json_body};
use crate::error::ApiError;

/// The most keys a JSON request may give (the 24 measurements, 16 hangings of three keys for
/// each frame, the 12 kept keys, with room to spare).
const MAX_KEYS: usize = 256;

/// The longest key a JSON request may give.
const MAX_KEY_CHARS: usize = 32;

/// How many of the largest correlations the answer lists.
const CORRELATIONS: usize = 5;

/// One measurement in the JSON form: its value and σ (0 when absent).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct MeasurementIn {
    value: f64,
    #[serde(default)]
    sigma: Option<f64>,
}

/// The body of `POST /api/measure`: `text` (a `*Measured.txt`) or `measurements` (JSON), one
/// of them; `file_name` or `name` names the bicycle.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct MeasureRequest {
    #[serde(default)]
    text: Option<String>,
    #[serde(default)]
    measurements: Option<Map<String, Value>>,
    #[serde(default)]
    file_name: Option<String>,
    #[serde(default)]
    name: Option<String>,
    /// The rider's `<Rider>YeadonMeas.txt` (Yeadon's 95 measurements), with `configuration`.
    #[serde(default)]
    rider: Option<String>,
    /// The rider's `<Rider><Bike>YeadonCFG.txt` on this bicycle, with `rider`.
    #[serde(default)]
    configuration: Option<String>,
    /// The rider's name, for the bicycle's (`Browser with Jason`).
    #[serde(default)]
    rider_name: Option<String>,
}

/// The rider seated (`MeasuredParameters::with_rider`): the rider alone in the benchmark's
/// axes, the joint angles solved and the solve's iterations and residual.
#[derive(Serialize)]
struct RiderOut {
    mass: f64,
    center_of_mass: [f64; 3],
    inertia: [[f64; 3]; 3],
    configuration: Map<String, Value>,
    iterations: usize,
    residual: f64,
}

/// A benchmark parameter computed, with its σ and unit.
#[derive(Serialize)]
struct ParameterOut {
    key: &'static str,
    value: f64,
    sigma: f64,
    unit: &'static str,
}

/// A measurement as the core read it (a list's mean, its σ).
#[derive(Serialize)]
struct MeasurementOut {
    key: String,
    value: f64,
    sigma: f64,
}

/// The answer.
#[derive(Serialize)]
pub(crate) struct MeasureAnswer {
    name: Option<String>,
    /// The bicycle in the files' JSON layout (benchmark form, values with σ).
    bike: Value,
    /// The 25 benchmark parameters and g, in the table's order.
    parameters: Vec<ParameterOut>,
    /// Every number the pipeline derived, in the order computed (the report of `whipple
    /// measure`).
    steps: Vec<Step>,
    /// The measurements used, as read (repeated measurements averaged).
    measurements: Vec<MeasurementOut>,
    /// The keys read and kept but not used (the rider's seat and handlebar geometry).
    other: Vec<MeasurementOut>,
    /// The largest correlations between the parameters.
    correlations: Vec<Correlation>,
    /// The bicycle's warnings and notes.
    warnings: Vec<Notice>,
    /// The rider seated and added to the rear frame, when one was sent.
    rider: Option<RiderOut>,
}

fn invalid(field: &str, rule: String) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "invalid_argument",
        format!("invalid `{field}`: {rule}"),
    )
    .at(field, rule)
}

/// The JSON form written as the lines of a `*Measured.txt`, for the core's reader.
fn as_text(measurements: &Map<String, Value>) -> Result<String, ApiError> {
    if measurements.len() > MAX_KEYS {
        return Err(invalid(
            "measurements",
            format!(
                "at most {MAX_KEYS} measurements, got {}",
                measurements.len()
            ),
        ));
    }
    let mut text = String::new();
    for (key, value) in measurements {
        let shown = whipple::advanced::shorten(key, MAX_KEY_CHARS);
        if key.is_empty()
            || key.chars().count() > MAX_KEY_CHARS
            || !key.chars().all(|c| c.is_ascii_alphanumeric())
        {
            return Err(invalid(
                &shown,
                format!(
                    "a measurement's key is a file key of BicycleParameters' raw data (letters \
                     and digits, at most {MAX_KEY_CHARS}), got `{shown}`"
                ),
            ));
        }
        let m: MeasurementIn = serde_json::from_value(value.clone()).map_err(|e| {
            invalid(
                key,
                format!("give {{\"value\": number, \"sigma\": number}}: {e}"),
            )
        })?;
        // A negative σ is refused by the reader, naming the key.
        let sigma = m.sigma.unwrap_or(0.0);
        // Rust's shortest round-trip form: the reader gets the very numbers sent.
        text.push_str(&format!("{key} = {}+/-{sigma}\n", m.value));
    }
    Ok(text)
}

/// The core's error, its position dropped where the text was written here from JSON.
fn core_error(error: whipple::Error, from_json: bool) -> ApiError {
    let mut e = ApiError::from(error);
    if from_json {
        e.body.line = None;
        e.body.column = None;
    }
    e
}

fn measure_request(request: MeasureRequest) -> Result<MeasureAnswer, ApiError> {
    let (text, from_json) = match (&request.text, &request.measurements) {
        (Some(text), None) => (text.clone(), false),
        (None, Some(map)) => (as_text(map)?, true),
        _ => {
            return Err(invalid(
                "text",
                "give the measurements as `text` (a *Measured.txt) or as `measurements` \
                 (key → {value, sigma}), one of them"
                    .into(),
            ));
        }
    };
    let file = read_measurements(&text).map_err(|e| core_error(e, from_json))?;
    // Lines of a text written here mean nothing to the client.
    let measurements = if from_json {
        file.measurements.map(|m| Measured::new(m.value, m.sigma))
    } else {
        file.measurements
    };
    let rider_texts = match (&request.rider, &request.configuration) {
        (Some(r), Some(c)) => Some((r, c)),
        (None, None) => None,
        (Some(_), None) => {
            return Err(invalid(
                "configuration",
                "a rider is seated in a configuration: send `configuration` (the \
                 <Rider><Bike>YeadonCFG.txt) with `rider`"
                    .into(),
            ));
        }
        (None, Some(_)) => {
            return Err(invalid(
                "rider",
                "send `rider` (the <Rider>YeadonMeas.txt) with `configuration`".into(),
            ));
        }
    };
    let result = match rider_texts {
        None => MeasuredParameters::new(&measurements),
        Some((rider, configuration)) => MeasuredParameters::with_rider(
            &MeasuredFile {
                measurements: measurements.clone(),
                other: file.other.clone(),
                fitted: Vec::new(),
            },
            &read_yeadon_measurements(rider)?,
            &read_yeadon_configuration(configuration)?,
        ),
    }
    .map_err(|e| core_error(e, from_json))?;
    let name = request
        .name
        .clone()
        .filter(|n| !n.trim().is_empty())
        .or_else(|| {
            request
                .file_name
                .as_deref()
                .and_then(|f| name_from_file_name(f, Format::BicycleParametersTxt))
        });
    let source = match &request.file_name {
        Some(f) => format!(
            "computed from the bench measurements in {} (Moore 2012 ch. 2)",
            whipple::advanced::shorten(f, 80)
        ),
        None => "computed from bench measurements (Moore 2012 ch. 2)".to_string(),
    };
    let rider_name = request
        .rider_name
        .as_deref()
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map(|n| whipple::advanced::shorten(n, 40));
    let (name, source) = match (&result.rider, rider_name) {
        (None, _) => (name, source),
        (Some(_), who) => {
            let who = who.unwrap_or_else(|| "a rider".into());
            (
                name.map(|n| format!("{n} with {who}")),
                format!("{source}, with {who} seated (Yeadon 1990; BicycleParameters' add_rider)"),
            )
        }
    };
    let rider = result.rider.as_ref().map(|seated| {
        let r = &seated.rider;
        RiderOut {
            mass: r.mass,
            center_of_mass: [r.center_of_mass.x, r.center_of_mass.y, r.center_of_mass.z],
            inertia: std::array::from_fn(|i| std::array::from_fn(|j| r.inertia[(i, j)])),
            configuration: CONFIGURATION_ANGLES
                .iter()
                .zip(seated.configuration.angles)
                .map(|((n, _, _), a)| (n.to_string(), Value::from(a)))
                .collect(),
            iterations: seated.solve.iterations,
            residual: seated.solve.residual,
        }
    });
    let bicycle = Bicycle {
        name: name.clone(),
        source: Some(source),
        ..result.bicycle()
    };
    let checked = bicycle.check()?;
    let parameters = result
        .benchmark
        .to_array()
        .iter()
        .zip(parameters(Form::Benchmark))
        .map(|(value, p)| ParameterOut {
            key: p.key,
            value: *value,
            sigma: result.sigma.get(p.key).copied().unwrap_or(0.0),
            unit: p.unit,
        })
        .collect();
    let out = |(key, m): (String, Measured)| MeasurementOut {
        key,
        value: m.value,
        sigma: m.sigma,
    };
    Ok(MeasureAnswer {
        name,
        bike: bicycle_json(&bicycle)?,
        parameters,
        correlations: result.largest_correlations(CORRELATIONS),
        steps: result.steps,
        measurements: measurements.entries().into_iter().map(out).collect(),
        other: file.other.into_iter().map(out).collect(),
        warnings: checked.notices,
        rider,
    })
}

pub(crate) fn measure(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: MeasureRequest = json_body(&body)?;
    Ok(Job::json(
        Budget::Interactive,
        "send fewer measurements",
        move |_| measure_request(request),
    ))
}

/// A sample of raw measurements the page offers to start from.
#[derive(Serialize)]
pub(crate) struct Sample {
    name: &'static str,
    title: &'static str,
    file_name: &'static str,
    source: &'static str,
    text: &'static str,
    /// The rider's name and files, for a sample with a rider.
    rider_name: Option<&'static str>,
    rider_file_name: Option<&'static str>,
    rider: Option<&'static str>,
    configuration_file_name: Option<&'static str>,
    configuration: Option<&'static str>,
}

/// The samples (see `data/README.md` for their source and licence).
const SAMPLES: [Sample; 2] = [
    Sample {
        name: "browser",
        title: "Browser (BicycleParameters)",
        file_name: "BrowserMeasured.txt",
        source: "Batavus Browser, measured by Moore (2012, ch. 2); BicycleParameters' data set \
                 (BSD 2-Clause)",
        text: include_str!("../data/BrowserMeasured.txt"),
        rider_name: None,
        rider_file_name: None,
        rider: None,
        configuration_file_name: None,
        configuration: None,
    },
    Sample {
        name: "browser-jason",
        title: "Browser with Jason (BicycleParameters)",
        file_name: "BrowserMeasured.txt",
        source: "Batavus Browser and its rider Jason, measured by Moore (2012, ch. 2; Yeadon's \
                 95 lengths); BicycleParameters' data set (BSD 2-Clause)",
        text: include_str!("../data/BrowserMeasured.txt"),
        rider_name: Some("Jason"),
        rider_file_name: Some("JasonYeadonMeas.txt"),
        rider: Some(include_str!("../data/JasonYeadonMeas.txt")),
        configuration_file_name: Some("JasonBrowserYeadonCFG.txt"),
        configuration: Some(include_str!("../data/JasonBrowserYeadonCFG.txt")),
    },
];

pub(crate) fn samples(_: &str) -> Result<Vec<u8>, ApiError> {
    serde_json::to_vec(&SAMPLES[..])
        .map_err(|e| ApiError::internal(format!("the answer could not be written: {e}")))
}
