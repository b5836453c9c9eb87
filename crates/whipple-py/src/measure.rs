//! Bicycles from bench measurements: BicycleParameters' `<Name>Measured.txt` text through the
//! core's pipeline (`whipple::advanced::measured`), returned as the bicycle with σ, every
//! step of the report, and the covariance and Jacobian as numpy arrays.

use nalgebra::DMatrix;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Bicycle;
use whipple::advanced::io::{Format, name_from_file_name};
use whipple::advanced::measured::{MeasuredParameters, read_measurements};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::serialized;

fn array<'py>(py: Python<'py>, m: &DMatrix<f64>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows: Vec<Vec<f64>> = m.row_iter().map(|r| r.iter().copied().collect()).collect();
    PyArray2::from_vec2(py, &rows)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}

/// The pipeline on a `*Measured.txt`'s text: a dict with `bicycle` (a NativeBicycle, benchmark
/// form with σ), `steps` (list of dicts), `inputs` (the measurements' keys, the Jacobian's
/// columns), `jacobian` (26 × n), `covariance` (26 × 26, the parameter table's order) and
/// `correlations` (every pair of parameters with σ > 0, largest |ρ| first).
#[pyfunction]
#[pyo3(signature = (text, file_name, strict=false))]
pub fn measure<'py>(
    py: Python<'py>,
    text: &str,
    file_name: &str,
    strict: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let result = py
        .detach(|| {
            let file = read_measurements(text)?;
            MeasuredParameters::new(&file.measurements)
        })
        .py_err(py)?;
    let name = name_from_file_name(file_name, Format::BicycleParametersTxt);
    let source = if file_name.is_empty() {
        "computed from bench measurements (Moore 2012 ch. 2)".to_string()
    } else {
        format!("computed from the bench measurements in {file_name} (Moore 2012 ch. 2)")
    };
    let bicycle = Bicycle {
        name,
        source: Some(source),
        ..result.bicycle()
    };
    let out = PyDict::new(py);
    out.set_item("bicycle", NativeBicycle::new(py, bicycle, strict)?)?;
    out.set_item("steps", serialized(py, &result.steps)?)?;
    out.set_item("inputs", result.inputs.clone())?;
    out.set_item("jacobian", array(py, &result.jacobian)?)?;
    out.set_item("covariance", array(py, &result.covariance)?)?;
    out.set_item(
        "correlations",
        serialized(py, &result.largest_correlations(usize::MAX))?,
    )?;
    Ok(out)
}
