//! Pendulum periods from Python: the record read by whipple-front's `record` (CSV, MATLAB
//! `.mat`), the fit by the core (`whipple::advanced::measured::period`); here only the
//! arguments are read and the results shaped into a dict of numbers and numpy arrays.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Error;
use whipple::advanced::measured::period::{PeriodFit, decay_window, fit_period};
use whipple_front::record::{MAX_RECORD_BYTES, RecordRequest, read_record};

use crate::errors::IntoPy;

fn fit_dict<'py>(
    py: Python<'py>,
    fit: &PeriodFit,
    time: &[f64],
    signal: &[f64],
    window: std::ops::Range<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("period", fit.period)?;
    d.set_item("period_sigma", fit.period_sigma)?;
    d.set_item("damping_ratio", fit.damping_ratio)?;
    d.set_item("damping_ratio_sigma", fit.damping_ratio_sigma)?;
    d.set_item("natural_frequency", fit.natural_frequency)?;
    d.set_item("amplitude", fit.amplitude)?;
    d.set_item("parameters", PyArray1::from_slice(py, &fit.parameters))?;
    let covariance: Vec<Vec<f64>> = fit.covariance.iter().map(|r| r.to_vec()).collect();
    d.set_item("covariance", covariance)?;
    d.set_item("residual_rms", fit.residual_rms)?;
    d.set_item("residual_sigma", fit.residual_sigma)?;
    d.set_item("r_squared", fit.r_squared)?;
    d.set_item("iterations", fit.iterations)?;
    d.set_item("window", (window.start, window.end))?;
    let fitted: Vec<f64> = time[window].iter().map(|t| fit.evaluate(*t)).collect();
    d.set_item("time", PyArray1::from_slice(py, time))?;
    d.set_item("signal", PyArray1::from_slice(py, signal))?;
    d.set_item("fitted", PyArray1::from_vec(py, fitted))?;
    Ok(d)
}

fn fit_window(
    time: &[f64],
    signal: &[f64],
    trim: Option<f64>,
) -> whipple::Result<(PeriodFit, std::ops::Range<usize>)> {
    let window = match trim {
        Some(fraction) => decay_window(signal, fraction)?,
        None => 0..signal.len(),
    };
    if time.len() != signal.len() {
        return Err(Error::InvalidArgument {
            what: "time",
            rule: format!(
                "{} times for {} samples of the signal; they must be as many",
                time.len(),
                signal.len()
            ),
        });
    }
    let fit = fit_period(&time[window.clone()], &signal[window.clone()])?;
    Ok((fit, window))
}

/// The decaying oscillation fitted to (time, signal), optionally trimmed as BicycleParameters
/// trims (`trim` = 0.1): a dict of the fit's numbers and arrays.
#[pyfunction]
#[pyo3(signature = (time, signal, trim=None))]
pub fn fit_period_native<'py>(
    py: Python<'py>,
    time: Vec<f64>,
    signal: Vec<f64>,
    trim: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (fit, window) = py.detach(|| fit_window(&time, &signal, trim)).py_err(py)?;
    fit_dict(py, &fit, &time, &signal, window)
}

/// A record read from a file (CSV or `.mat`) and fitted: the same dict, with `signal_name`
/// and `time_source`.
#[pyfunction]
#[pyo3(signature = (path, column=None, time=None, rate=None, trim=None))]
pub fn read_period_native<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    column: Option<String>,
    time: Option<String>,
    rate: Option<f64>,
    trim: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(&path)
        .and_then(|f| f.take(MAX_RECORD_BYTES as u64 + 1).read_to_end(&mut bytes))
        .map_err(|e| pyo3::exceptions::PyOSError::new_err(format!("{}: {e}", path.display())))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let request = RecordRequest {
        signal: column,
        time,
        rate,
    };
    let (record, fit, window) = py
        .detach(|| {
            let record = read_record(&bytes, &name, &request)?;
            let (fit, window) = fit_window(&record.time, &record.signal, trim)?;
            Ok::<_, Error>((record, fit, window))
        })
        .py_err(py)?;
    let d = fit_dict(py, &fit, &record.time, &record.signal, window)?;
    d.set_item("signal_name", &record.signal_name)?;
    d.set_item("time_source", &record.time_source)?;
    Ok(d)
}
