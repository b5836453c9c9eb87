//! `/api/map` and `/api/study`: design studies computed by `whipple::advanced::design` within
//! the server's limits, answered as columns (one array per quantity, row-major).

use bytes::Bytes;
use http::StatusCode;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use whipple::advanced::design::{DesignStatus, Shard, StudySettings};
use whipple::advanced::modes::Mode;
use whipple_front::design::{AxisSpec, DesignStudy};

use crate::Limits;
use crate::api::{Budget, Job, SpeedRange, bicycle, bicycle_json, json_body};
use crate::error::ApiError;

/// A map or study request: axes as `NAME=START:STOP:COUNT`, as in the CLI.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct DesignRequest {
    bike: Value,
    x: String,
    #[serde(default)]
    y: Option<String>,
    #[serde(default)]
    speed: Option<f64>,
    #[serde(default)]
    range: Option<SpeedRange>,
    #[serde(default)]
    double_root: bool,
    /// A band of speeds [a, b] (m/s) inside the range: is each design self-stable at every
    /// speed of it, and by what margin.
    #[serde(default)]
    band: Option<(f64, f64)>,
}

/// The answer: the axes and one array per quantity (null where absent or not computed).
#[derive(Serialize)]
pub(crate) struct DesignResponse {
    x: AxisSpec,
    y: Option<AxisSpec>,
    /// The base design's coordinates (user units), where the axes vary bicycle parameters.
    base: (Option<f64>, Option<f64>),
    nx: usize,
    ny: usize,
    status: Vec<DesignStatus>,
    /// The reason of every design that was not computed, by row-major index.
    reasons: Vec<(u64, String)>,
    v_d: Vec<Option<f64>>,
    v_w: Vec<Option<f64>>,
    v_c: Vec<Option<f64>>,
    weave_frequency: Vec<Option<f64>>,
    stable: Vec<bool>,
    /// Null where the range is unbounded (see `stable_unbounded`) or not computed.
    stable_width: Vec<Option<f64>>,
    stable_unbounded: Vec<bool>,
    stable_from: Vec<Option<f64>>,
    /// Null where unbounded.
    stable_to: Vec<Option<f64>>,
    max_real: Vec<Option<f64>>,
    max_real_mode: Vec<Option<Mode>>,
    /// With a band only: self-stable at every speed of it (null where undecided or not
    /// computed), the margins below and above it (null where not self-stable over it; the
    /// margin above is null where unbounded too, see `band_margin_above_unbounded`), and the
    /// smaller of the two.
    #[serde(skip_serializing_if = "Option::is_none")]
    band: Option<(f64, f64)>,
    #[serde(skip_serializing_if = "Option::is_none")]
    stable_over: Option<Vec<Option<bool>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    band_margin_below: Option<Vec<Option<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    band_margin_above: Option<Vec<Option<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    band_margin_above_unbounded: Option<Vec<bool>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    band_margin: Option<Vec<Option<f64>>>,
}

/// An axis of the request, an error in it naming its field (`x` or `y`).
fn axis(spec: &str, bike: &whipple::Bicycle, field: &str) -> Result<AxisSpec, ApiError> {
    AxisSpec::parse(spec, bike).map_err(|e| ApiError::from(e).in_field(field))
}

/// The body of `POST /api/map/design`: a map's or study's axes and one design's row-major
/// index (`iy · nx + ix`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct DesignAtRequest {
    bike: Value,
    x: String,
    #[serde(default)]
    y: Option<String>,
    index: u64,
}

/// One design of a map or study as a bicycle, in the parameter files' JSON layout (what the
/// page loads into its editor when a cell is clicked).
pub(crate) fn design_at(_: &Limits, body: Bytes) -> Result<Job, ApiError> {
    let request: DesignAtRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    let x = axis(&request.x, &bike, "x")?;
    let y = match &request.y {
        Some(spec) => Some(axis(spec, &bike, "y")?),
        None => None,
    };
    let study = DesignStudy::new(bike, x, y, StudySettings::default())?;
    Ok(Job::json(Budget::Interactive, "try again", move |_| {
        let design = study.study.bicycle_at(request.index)?;
        Ok(serde_json::json!({ "bike": bicycle_json(&design)? }))
    }))
}

fn run(limits: &Limits, body: Bytes, two: bool) -> Result<Job, ApiError> {
    let request: DesignRequest = json_body(&body)?;
    let bike = bicycle(&request.bike)?;
    if two != request.y.is_some() {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "invalid_argument",
            if two {
                "a map needs two axes, `x` and `y`"
            } else {
                "a study varies one parameter: `x` only (use /api/map for two)"
            },
        )
        .at("y", "NAME=START:STOP:COUNT"));
    }
    let x = axis(&request.x, &bike, "x")?;
    let y = match &request.y {
        Some(spec) => Some(axis(spec, &bike, "y")?),
        None => None,
    };
    let (lo, hi) = SpeedRange::bounds(request.range);
    let options = StudySettings {
        range: (lo, hi),
        speed: request.speed,
        double_root: request.double_root,
        band: request.band,
    };
    let study = DesignStudy::new(bike, x, y, options)?;
    let limit = limits.max_designs as u64;
    if study.study.len() > limit {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "limit_exceeded",
            format!(
                "{} designs is more than this server's limit of {limit} per request; use fewer points",
                study.study.len()
            ),
        )
        .at("x", format!("at most {limit} designs per request")));
    }
    Ok(Job::json(
        Budget::Heavy,
        "ask for fewer designs",
        move |stop| {
            let n = study.study.len() as usize;
            let mut r = DesignResponse {
                x: study.x.clone(),
                y: study.y.clone(),
                base: study.base_point(),
                nx: study.x.axis.count,
                ny: study.y.as_ref().map_or(1, |a| a.axis.count),
                status: Vec::with_capacity(n),
                reasons: Vec::new(),
                v_d: Vec::with_capacity(n),
                v_w: Vec::with_capacity(n),
                v_c: Vec::with_capacity(n),
                weave_frequency: Vec::with_capacity(n),
                stable: Vec::with_capacity(n),
                stable_width: Vec::with_capacity(n),
                stable_unbounded: Vec::with_capacity(n),
                stable_from: Vec::with_capacity(n),
                stable_to: Vec::with_capacity(n),
                max_real: Vec::with_capacity(n),
                max_real_mode: Vec::with_capacity(n),
                band: options.band,
                stable_over: options.band.map(|_| Vec::with_capacity(n)),
                band_margin_below: options.band.map(|_| Vec::with_capacity(n)),
                band_margin_above: options.band.map(|_| Vec::with_capacity(n)),
                band_margin_above_unbounded: options.band.map(|_| Vec::with_capacity(n)),
                band_margin: options.band.map(|_| Vec::with_capacity(n)),
            };
            let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
            let mut done = 0u64;
            study.study.run(Shard::WHOLE, &stop, |rows| {
                done += rows.len() as u64;
                crate::api::report_progress(done, n as u64);
                for row in rows {
                    let q = &row.quantities;
                    let ok = row.status == DesignStatus::Ok;
                    r.status.push(row.status);
                    if let Some(reason) = &row.reason {
                        r.reasons.push((row.index, reason.clone()));
                    }
                    r.v_d.push(finite(q.double_root_speed));
                    r.v_w.push(finite(q.weave_speed));
                    r.v_c.push(finite(q.capsize_speed));
                    r.weave_frequency.push(finite(q.weave_frequency));
                    r.stable.push(q.stable);
                    r.stable_width.push(if ok {
                        finite(Some(q.stable_width))
                    } else {
                        None
                    });
                    r.stable_unbounded.push(q.stable_width == f64::INFINITY);
                    r.stable_from.push(finite(q.stable_from));
                    r.stable_to.push(finite(q.stable_to));
                    r.max_real.push(finite(q.max_real));
                    r.max_real_mode.push(q.max_real_mode);
                    if let (Some(over), Some(below), Some(above), Some(unbounded), Some(margin)) = (
                        r.stable_over.as_mut(),
                        r.band_margin_below.as_mut(),
                        r.band_margin_above.as_mut(),
                        r.band_margin_above_unbounded.as_mut(),
                        r.band_margin.as_mut(),
                    ) {
                        over.push(q.stable_over);
                        below.push(finite(q.band_margin_below));
                        above.push(finite(q.band_margin_above));
                        unbounded.push(q.band_margin_above == Some(f64::INFINITY));
                        margin.push(finite(
                            q.band_margin_below
                                .zip(q.band_margin_above)
                                .map(|(a, b)| a.min(b)),
                        ));
                    }
                }
                Ok(())
            })?;
            Ok(r)
        },
    ))
}

pub(crate) fn map(limits: &Limits, body: Bytes) -> Result<Job, ApiError> {
    run(limits, body, true)
}

pub(crate) fn study(limits: &Limits, body: Bytes) -> Result<Job, ApiError> {
    run(limits, body, false)
}
