//! Design studies from Python: the library's `analysis::design::Study` over one or two axes
//! (typed as on the command line: `whipple_front::design`),
//! whole or one shard (the unit a Dask task computes), as typed columns of numpy arrays built
//! here (no Python object per design): 67 bytes a design, 107 with the coordinate columns.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::advanced::design::{DesignRow, DesignStatus, Shard, StudySettings};
use whipple_front::design::{AxisSpec, DesignStudy};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::guard::{SHORT, interruptible, memory_error, reserve, stopped};
use crate::serialized;

/// An axis: the core's serialization of it (`name`, `parameter`, `start`, `stop`, `count`,
/// `degrees`: the server's keys) with its `unit` and its `values` (numpy) beside.
fn axis_dict<'py>(py: Python<'py>, axis: &AxisSpec) -> PyResult<Bound<'py, PyAny>> {
    let d = serialized(py, axis)?;
    let dict = d.cast::<PyDict>()?;
    dict.set_item("unit", axis.unit())?;
    let count = axis.axis.count;
    let mut values = reserve(count, || {
        memory_error(
            "design_map",
            count as u128,
            "axis values",
            count as u128 * 8,
        )
    })?;
    values.extend((0..count).map(|i| axis.value(i)));
    dict.set_item("values", PyArray1::from_vec(py, values))?;
    Ok(d)
}

/// The quantity columns, in the order of `QUANTITY_NAMES`.
const QUANTITY_NAMES: [&str; 8] = [
    "v_d",
    "v_w",
    "v_c",
    "weave_frequency",
    "stable_width",
    "stable_from",
    "stable_to",
    "max_real",
];

/// Bytes a design takes in the columns: eight quantities, two flags and the status code; the
/// coordinates (index, ix, iy, x, y) 40 more.
const BYTES_PER_DESIGN: usize = 8 * 8 + 2 + 1;
const BYTES_PER_COORDINATES: usize = 5 * 8;

/// The band's columns (with a band only), in this order.
const BAND_NAMES: [&str; 4] = [
    "stable_over",
    "band_margin_below",
    "band_margin_above",
    "band_margin",
];

/// Bytes a design takes in the band's columns.
const BYTES_PER_BAND: usize = 4 * 8;

/// A shard's columns, reserved whole before the first design is computed.
struct Columns {
    index: Vec<u64>,
    ix: Vec<u64>,
    iy: Vec<u64>,
    x: Vec<f64>,
    y: Vec<f64>,
    status: Vec<u8>,
    /// Position in the shard and words of each design refused with a reason.
    reason_at: Vec<u64>,
    reason_text: Vec<String>,
    quantities: [Vec<f64>; 8],
    stable: Vec<bool>,
    unresolved: Vec<bool>,
    /// With a band: stable over it (1, 0, NaN where undecided or not computed), the margins
    /// below and above it and the smaller of the two (NaN where not stable over it).
    band: Option<[Vec<f64>; 4]>,
}

impl Columns {
    fn new(count: usize, coordinates: bool, band: bool) -> PyResult<Columns> {
        let per = BYTES_PER_DESIGN
            + if coordinates {
                BYTES_PER_COORDINATES
            } else {
                0
            }
            + if band { BYTES_PER_BAND } else { 0 };
        let too_big = || {
            memory_error(
                "design_map",
                count as u128,
                "designs",
                count as u128 * per as u128,
            )
        };
        let c = if coordinates { count } else { 0 };
        Ok(Columns {
            index: reserve(c, too_big)?,
            ix: reserve(c, too_big)?,
            iy: reserve(c, too_big)?,
            x: reserve(c, too_big)?,
            y: reserve(c, too_big)?,
            status: reserve(count, too_big)?,
            reason_at: Vec::new(),
            reason_text: Vec::new(),
            quantities: [
                reserve(count, too_big)?,
                reserve(count, too_big)?,
                reserve(count, too_big)?,
                reserve(count, too_big)?,
                reserve(count, too_big)?,
                reserve(count, too_big)?,
                reserve(count, too_big)?,
                reserve(count, too_big)?,
            ],
            stable: reserve(count, too_big)?,
            unresolved: reserve(count, too_big)?,
            band: if band {
                Some([
                    reserve(count, too_big)?,
                    reserve(count, too_big)?,
                    reserve(count, too_big)?,
                    reserve(count, too_big)?,
                ])
            } else {
                None
            },
        })
    }

    /// Appends a design; false when the reasons (the one column not reserved ahead: only
    /// refused designs have one) cannot grow.
    fn push(&mut self, r: &DesignRow, coordinates: bool) -> bool {
        if coordinates {
            self.index.push(r.index);
            self.ix.push(r.ix as u64);
            self.iy.push(r.iy as u64);
            self.x.push(r.x);
            self.y.push(r.y);
        }
        if let Some(reason) = &r.reason {
            if self.reason_at.try_reserve(1).is_err() || self.reason_text.try_reserve(1).is_err() {
                return false;
            }
            self.reason_at.push(self.status.len() as u64);
            self.reason_text.push(reason.clone());
        }
        self.status.push(match r.status {
            DesignStatus::Ok => 0,
            DesignStatus::Invalid => 1,
            DesignStatus::AccuracyLost => 2,
        });
        let q = &r.quantities;
        let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
        let values = [
            nan(q.double_root_speed),
            nan(q.weave_speed),
            nan(q.capsize_speed),
            nan(q.weave_frequency),
            q.stable_width,
            nan(q.stable_from),
            nan(q.stable_to),
            nan(q.max_real),
        ];
        for (column, value) in self.quantities.iter_mut().zip(values) {
            column.push(value);
        }
        self.stable.push(q.stable);
        self.unresolved.push(q.unresolved);
        if let Some(band) = &mut self.band {
            let over = q
                .stable_over
                .map_or(f64::NAN, |b| if b { 1.0 } else { 0.0 });
            let margin = q
                .band_margin_below
                .zip(q.band_margin_above)
                .map(|(a, b)| a.min(b));
            let values = [
                over,
                nan(q.band_margin_below),
                nan(q.band_margin_above),
                nan(margin),
            ];
            for (column, value) in band.iter_mut().zip(values) {
                column.push(value);
            }
        }
        true
    }
}

#[pymethods]
impl NativeBicycle {
    /// The designs of a study (axes as the command line's `map --x`/`--y` take them, e.g.
    /// `trail=-0.05:0.25:100`, `head_angle_deg=60:85:100`), shard `shard_index` of
    /// `shard_count`, computed in parallel with the GIL released (Ctrl-C honoured): a dict of
    /// columns in design order (the designs `start..start + count`) and the axes;
    /// `coordinates` adds each design's index, ix, iy, x and y; `band` (a, b) the columns of
    /// "self-stable at every speed of it?" and the margins.
    #[pyo3(signature = (x, y=None, lo=0.0, hi=f64::INFINITY, speed=None, double_root=false,
                        shard_index=0, shard_count=1, coordinates=true, band=None))]
    #[allow(clippy::too_many_arguments)]
    fn design<'py>(
        &self,
        py: Python<'py>,
        x: &str,
        y: Option<&str>,
        lo: f64,
        hi: f64,
        speed: Option<f64>,
        double_root: bool,
        shard_index: u64,
        shard_count: u64,
        coordinates: bool,
        band: Option<(f64, f64)>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let base = self.bicycle.clone();
        let x_axis = AxisSpec::parse(x, &base).py_err(py)?;
        let y_axis = y
            .map(|y| AxisSpec::parse(y, &base))
            .transpose()
            .py_err(py)?;
        let shard = Shard::parse(&format!("{shard_index}/{shard_count}")).py_err(py)?;
        let options = StudySettings {
            range: (lo, hi),
            speed,
            double_root,
            band,
        };
        let study = DesignStudy::new(base, x_axis.clone(), y_axis.clone(), options).py_err(py)?;
        let total = study.study.len();
        let base_point = study.base_point();
        let (first, end) = shard.indices(total);
        let count = usize::try_from(end - first).unwrap_or(usize::MAX);
        let mut columns = Columns::new(count, coordinates, band.is_some())?;
        let mut full = false;
        let outcome = interruptible(py, count <= SHORT, |stop| {
            study.study.run(shard, stop, |chunk| {
                for r in chunk {
                    if !columns.push(r, coordinates) {
                        full = true;
                        return Err(stopped());
                    }
                }
                Ok(())
            })
        })?;
        if full {
            let reasons = columns.reason_at.len() as u128;
            return Err(memory_error(
                "design_map",
                reasons,
                "refused designs' reasons",
                reasons * 100,
            ));
        }
        outcome.py_err(py)?;
        let c = columns;
        let d = PyDict::new(py);
        d.set_item("total", total)?;
        // This part's designs are those of index start..start + count, in order.
        d.set_item("start", first)?;
        d.set_item("count", end - first)?;
        // The base design on the axes (user units; None for a speed axis).
        d.set_item("base", (base_point.0, base_point.1))?;
        d.set_item("x_axis", axis_dict(py, &x_axis)?)?;
        d.set_item(
            "y_axis",
            y_axis.as_ref().map(|a| axis_dict(py, a)).transpose()?,
        )?;
        if coordinates {
            d.set_item("index", PyArray1::from_vec(py, c.index))?;
            d.set_item("ix", PyArray1::from_vec(py, c.ix))?;
            d.set_item("iy", PyArray1::from_vec(py, c.iy))?;
            d.set_item("x", PyArray1::from_vec(py, c.x))?;
            d.set_item("y", PyArray1::from_vec(py, c.y))?;
        }
        // 0 ok, 1 invalid, 2 accuracy_lost (the Python side maps the codes to the words).
        d.set_item("status_code", PyArray1::from_vec(py, c.status))?;
        d.set_item("reason_at", PyArray1::from_vec(py, c.reason_at))?;
        d.set_item("reason_text", c.reason_text)?;
        for (name, column) in QUANTITY_NAMES.iter().zip(c.quantities) {
            d.set_item(name, PyArray1::from_vec(py, column))?;
        }
        d.set_item("stable", PyArray1::from_vec(py, c.stable))?;
        d.set_item("unresolved", PyArray1::from_vec(py, c.unresolved))?;
        d.set_item("band", band)?;
        if let Some(columns) = c.band {
            for (name, column) in BAND_NAMES.iter().zip(columns) {
                d.set_item(name, PyArray1::from_vec(py, column))?;
            }
        }
        Ok(d)
    }
}
