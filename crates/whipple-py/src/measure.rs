//! Bicycles from bench measurements: BicycleParameters' `<Name>Measured.txt` text through the
//! core's pipeline (`whipple::advanced::measured`), returned as the bicycle with σ, every
//! step of the report, and the covariance and Jacobian as numpy arrays.

use nalgebra::DMatrix;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Bicycle;
use whipple::advanced::io::{Format, name_from_file_name};
use whipple::advanced::measured::{
    MeasuredParameters, read_measurements, read_measurements_with_records,
};
use whipple::advanced::rider::{
    CONFIGURATION_ANGLES, read_yeadon_configuration, read_yeadon_measurements,
};

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
/// `correlations` (every pair of parameters with σ > 0, largest |ρ| first); with `rider`, the
/// tuple (the texts of `<Rider>YeadonMeas.txt` and `<Rider><Bike>YeadonCFG.txt`, the rider's
/// name), the rider seated and added to the rear frame, and `rider` (mass, centre, inertia in
/// the benchmark's axes, the configuration on the bicycle, the solve's iterations), else None.
///
/// With `periods` (a directory), every period the text lacks is fitted from the rate-gyro
/// records there, named as BicycleParameters names them after the bicycle (whose name comes
/// from `file_name`), by whipple-front's `period_from_records`; `fitted` lists them (key,
/// value, sigma, source).
#[pyfunction]
#[pyo3(signature = (text, file_name, strict=false, periods=None, rider=None))]
pub fn measure<'py>(
    py: Python<'py>,
    text: &str,
    file_name: &str,
    strict: bool,
    periods: Option<std::path::PathBuf>,
    rider: Option<(String, String, String)>,
) -> PyResult<Bound<'py, PyDict>> {
    let name = name_from_file_name(file_name, Format::BicycleParametersTxt);
    let (file, result) = py
        .detach(|| {
            let file = match (&periods, &name) {
                (None, _) => read_measurements(text)?,
                (Some(dir), Some(bike)) => read_measurements_with_records(text, &mut |key| {
                    whipple_front::record::period_from_records(dir, bike, key).map(Some)
                })?,
                (Some(dir), None) => {
                    return Err(whipple::Error::InvalidParameter {
                        field: "periods".into(),
                        value: f64::NAN,
                        rule: format!(
                            "the records in {} are found by the bicycle's name, which comes \
                             from the raw file's name <Name>Measured.txt: give the file's path",
                            dir.display()
                        ),
                    });
                }
            };
            let result = match &rider {
                Some((rider, configuration, _)) => MeasuredParameters::with_rider(
                    &file,
                    &read_yeadon_measurements(rider)?,
                    &read_yeadon_configuration(configuration)?,
                )?,
                None => MeasuredParameters::new(&file.measurements)?,
            };
            Ok((file, result))
        })
        .py_err(py)?;
    let mut name = name;
    let mut source = if file_name.is_empty() {
        "computed from bench measurements (Moore 2012 ch. 2)".to_string()
    } else {
        format!("computed from the bench measurements in {file_name} (Moore 2012 ch. 2)")
    };
    if result.rider.is_some() {
        let who = match &rider {
            Some((_, _, name)) if !name.is_empty() => name.as_str(),
            _ => "a rider",
        };
        name = name.map(|n| format!("{n} with {who}"));
        source.push_str(&format!(
            ", with {who} seated (Yeadon 1990; BicycleParameters' add_rider)"
        ));
    }
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
    let fitted: Vec<(String, f64, f64, String)> = file
        .fitted
        .iter()
        .map(|f| {
            (
                f.key.clone(),
                f.period.value,
                f.period.sigma,
                f.source.clone(),
            )
        })
        .collect();
    out.set_item("fitted", fitted)?;
    if let Some(seated) = &result.rider {
        let r = &seated.rider;
        let rider = PyDict::new(py);
        rider.set_item("mass", r.mass)?;
        rider.set_item(
            "center_of_mass",
            vec![r.center_of_mass.x, r.center_of_mass.y, r.center_of_mass.z],
        )?;
        let inertia: Vec<Vec<f64>> = (0..3)
            .map(|i| (0..3).map(|j| r.inertia[(i, j)]).collect())
            .collect();
        rider.set_item("inertia", inertia)?;
        let angles = PyDict::new(py);
        for ((n, _, _), a) in CONFIGURATION_ANGLES.iter().zip(seated.configuration.angles) {
            angles.set_item(*n, a)?;
        }
        rider.set_item("configuration", angles)?;
        rider.set_item("iterations", seated.solve.iterations)?;
        rider.set_item("residual", seated.solve.residual)?;
        out.set_item("rider", rider)?;
    } else {
        out.set_item("rider", py.None())?;
    }
    out.set_item(
        "correlations",
        serialized(py, &result.largest_correlations(usize::MAX))?,
    )?;
    Ok(out)
}
