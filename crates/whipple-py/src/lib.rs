//! Python bindings of whipple: the native module `whipple._whipple`. A thin front end: it
//! converts Python values to the library's types and the library's results to numpy arrays and
//! plain Python values; every number is computed by the `whipple` crate. The Python package
//! (`python/whipple/`) wraps these functions in the documented classes.

mod accelerations;
mod bicycle;
mod cli;
mod control;
mod design;
mod errors;
mod guard;
mod handling;
mod human;
mod lane_change;
mod linear;
mod measure;
mod period;
mod rider_lean;
mod side_view;
mod simulate;
mod system;
mod turns;

use pyo3::prelude::*;

/// A core result as Python objects by its own serde derive, so its names are the core's (those
/// of the server's JSON): structs as dicts, sequences as lists, tuples and arrays as tuples,
/// `None` as None. Large numeric arrays are not built this way but as numpy arrays.
pub(crate) fn serialized<'py, T: serde::Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(pythonize::pythonize(py, value)?)
}

/// The native module.
#[pymodule]
fn _whipple(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // numpy's C API is looked up once, on first use, by importing numpy; were that first use
    // after a Ctrl-C (a result built after an interrupted computation), the import would
    // raise the pending KeyboardInterrupt and rust-numpy panic ("Failed to access NumPy array
    // API capsule"). Looked up here, at import, it never is.
    let py = m.py();
    py.check_signals()?;
    py.import("numpy")?;
    numpy::PyArray1::<f64>::zeros(py, 0, false);
    m.add_class::<bicycle::NativeBicycle>()?;
    m.add_class::<system::NativeLinearSystem>()?;
    m.add_class::<rider_lean::NativeRiderLean>()?;
    m.add_function(wrap_pyfunction!(bicycle::presets, m)?)?;
    m.add_function(wrap_pyfunction!(bicycle::formats, m)?)?;
    m.add_function(wrap_pyfunction!(bicycle::parameter_table, m)?)?;
    m.add_function(wrap_pyfunction!(cli::cli_main, m)?)?;
    m.add_function(wrap_pyfunction!(period::fit_period_native, m)?)?;
    m.add_function(wrap_pyfunction!(period::read_period_native, m)?)?;
    m.add_function(wrap_pyfunction!(measure::measure, m)?)?;
    m.add_function(wrap_pyfunction!(human::check_human_controller, m)?)?;
    m.add_function(wrap_pyfunction!(human::read_gains_text, m)?)?;
    m.add_function(wrap_pyfunction!(human::gain_lookup, m)?)?;
    m.add_function(wrap_pyfunction!(handling::handling_quality_native, m)?)?;
    m.add_function(wrap_pyfunction!(
        handling::handling_against_speed_native,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(handling::optimal_handling_native, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_FILE_BYTES", whipple::advanced::io::MAX_FILE_BYTES)?;
    Ok(())
}
