//! Design studies from Python: the library's `analysis::design::Study` over one or two axes,
//! whole or one shard (the unit a Dask task computes), as columns of numpy arrays.

use std::sync::atomic::AtomicBool;

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::analysis::design::{Axis, DesignRow, DesignStatus, Shard, Study, StudyOptions};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;

fn axis_dict<'py>(py: Python<'py>, axis: &Axis) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", &axis.name)?;
    d.set_item("unit", axis.unit())?;
    d.set_item("degrees", axis.degrees)?;
    let values: Vec<f64> = (0..axis.count).map(|i| axis.value(i)).collect();
    d.set_item("values", PyArray1::from_vec(py, values))?;
    Ok(d)
}

#[pymethods]
impl NativeBicycle {
    /// The designs of a study (axes as the command line's `map --x`/`--y` take them, e.g.
    /// `trail=-0.05:0.25:100`, `head_angle_deg=60:85:100`), shard `shard_index` of
    /// `shard_count`, computed in parallel with the GIL released: a dict of columns in design
    /// order and the axes.
    #[pyo3(signature = (x, y=None, lo=0.0, hi=f64::INFINITY, speed=None, double_root=false,
                        shard_index=0, shard_count=1))]
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
    ) -> PyResult<Bound<'py, PyDict>> {
        let base = self.bicycle.clone();
        let x_axis = Axis::parse(x, &base).py_err(py)?;
        let y_axis = y.map(|y| Axis::parse(y, &base)).transpose().py_err(py)?;
        let shard = Shard::parse(&format!("{shard_index}/{shard_count}")).py_err(py)?;
        let options = StudyOptions {
            range: (lo, hi),
            speed,
            double_root,
        };
        let study = Study::new(base, x_axis.clone(), y_axis.clone(), options).py_err(py)?;
        let total = study.len();
        let base_point = study.base_point();
        let rows = py
            .detach(|| {
                let mut rows: Vec<DesignRow> = Vec::new();
                study
                    .run(shard, &AtomicBool::new(false), |chunk| {
                        rows.extend_from_slice(chunk);
                        Ok(())
                    })
                    .map(|_| rows)
            })
            .py_err(py)?;
        let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
        let column = |f: &dyn Fn(&DesignRow) -> f64| -> Vec<f64> { rows.iter().map(f).collect() };
        let d = PyDict::new(py);
        d.set_item("total", total)?;
        // The base design on the axes (user units; None for a speed axis).
        d.set_item("base", (base_point.0, base_point.1))?;
        d.set_item("x_axis", axis_dict(py, &x_axis)?)?;
        d.set_item(
            "y_axis",
            y_axis.as_ref().map(|a| axis_dict(py, a)).transpose()?,
        )?;
        let index: Vec<u64> = rows.iter().map(|r| r.index).collect();
        d.set_item("index", PyArray1::from_vec(py, index))?;
        let ix: Vec<u64> = rows.iter().map(|r| r.ix as u64).collect();
        let iy: Vec<u64> = rows.iter().map(|r| r.iy as u64).collect();
        d.set_item("ix", PyArray1::from_vec(py, ix))?;
        d.set_item("iy", PyArray1::from_vec(py, iy))?;
        d.set_item("x", PyArray1::from_vec(py, column(&|r| r.x)))?;
        d.set_item("y", PyArray1::from_vec(py, column(&|r| r.y)))?;
        let status: Vec<&str> = rows
            .iter()
            .map(|r| match r.status {
                DesignStatus::Ok => "ok",
                DesignStatus::Invalid => "invalid",
                DesignStatus::AccuracyLost => "accuracy_lost",
            })
            .collect();
        d.set_item("status", status)?;
        d.set_item(
            "reason",
            rows.iter().map(|r| r.reason.clone()).collect::<Vec<_>>(),
        )?;
        let q = |f: &dyn Fn(&whipple::analysis::design::DesignQuantities) -> f64| {
            PyArray1::from_vec(py, column(&|r| f(&r.quantities)))
        };
        d.set_item("v_d", q(&|q| nan(q.double_root_speed)))?;
        d.set_item("v_w", q(&|q| nan(q.weave_speed)))?;
        d.set_item("v_c", q(&|q| nan(q.capsize_speed)))?;
        d.set_item("weave_frequency", q(&|q| nan(q.weave_frequency)))?;
        d.set_item("stable_width", q(&|q| q.stable_width))?;
        d.set_item("stable_from", q(&|q| nan(q.stable_from)))?;
        d.set_item("stable_to", q(&|q| nan(q.stable_to)))?;
        d.set_item("max_real", q(&|q| nan(q.max_real)))?;
        let stable: Vec<bool> = rows.iter().map(|r| r.quantities.stable).collect();
        d.set_item("stable", PyArray1::from_vec(py, stable))?;
        let unresolved: Vec<bool> = rows.iter().map(|r| r.quantities.unresolved).collect();
        d.set_item("unresolved", PyArray1::from_vec(py, unresolved))?;
        Ok(d)
    }
}
