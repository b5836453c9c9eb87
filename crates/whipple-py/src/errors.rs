//! The library's errors as Python exceptions. The classes live in `whipple/_errors.py` (so they
//! can inherit from `ValueError`, `LookupError`, `ArithmeticError` as Python users expect);
//! here each `whipple::Error` variant is mapped to one of them with its fields as attributes.

use pyo3::IntoPyObjectExt;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Error;

/// The exception class of that name from `whipple._errors`.
fn class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("whipple._errors")?.getattr(name)
}

/// A `whipple.<class>` exception with `message` and the attributes in `attributes`.
fn raise(py: Python<'_>, name: &str, message: String, attributes: &[(&str, Py<PyAny>)]) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let kwargs = PyDict::new(py);
        for (key, value) in attributes {
            kwargs.set_item(key, value)?;
        }
        let instance = class(py, name)?.call((message.clone(),), Some(&kwargs))?;
        Ok(PyErr::from_value(instance))
    };
    build().unwrap_or_else(|e| e)
}

fn obj<'py, T: IntoPyObject<'py>>(py: Python<'py>, value: T) -> Py<PyAny> {
    value.into_py_any(py).unwrap_or_else(|_| py.None())
}

/// The Python exception for a library error.
pub fn to_py(py: Python<'_>, error: Error) -> PyErr {
    let message = whipple_front::message::message(&error);
    match error {
        Error::InvalidParameter { field, value, rule } => raise(
            py,
            "ParameterError",
            message,
            &[
                ("field", obj(py, field)),
                ("value", obj(py, value)),
                ("rule", obj(py, rule)),
            ],
        ),
        Error::InvalidBicycle { fields, rule } => raise(
            py,
            "ParameterError",
            message,
            &[
                ("field", obj(py, fields)),
                ("value", py.None()),
                ("rule", obj(py, rule)),
            ],
        ),
        Error::WarningsRefused {
            field,
            count,
            message: rule,
        } => raise(
            py,
            "StrictError",
            message,
            &[
                ("field", obj(py, field)),
                ("value", obj(py, count)),
                ("rule", obj(py, rule)),
            ],
        ),
        Error::Parse {
            format,
            field,
            line,
            column,
            message: rule,
        } => raise(
            py,
            "ParseError",
            message,
            &[
                ("format", obj(py, format)),
                ("field", obj(py, field)),
                ("value", py.None()),
                ("rule", obj(py, rule)),
                ("line", obj(py, line)),
                ("column", obj(py, column)),
            ],
        ),
        Error::UnknownPreset { name, known } => raise(
            py,
            "UnknownPresetError",
            message,
            &[
                ("field", obj(py, "name")),
                ("value", obj(py, name)),
                ("rule", obj(py, format!("known presets: {known}"))),
            ],
        ),
        Error::InvalidArgument { what, rule } => raise(
            py,
            "ArgumentError",
            message,
            &[
                ("field", obj(py, what)),
                ("value", py.None()),
                ("rule", obj(py, rule)),
            ],
        ),
        Error::LimitExceeded { what, rule } => raise(
            py,
            "LimitError",
            message,
            &[
                ("field", obj(py, what)),
                ("value", py.None()),
                ("rule", obj(py, rule)),
            ],
        ),
        // A step or tolerance too coarse for the run: the argument (`dt`, `rtol`) at fault,
        // the step to use in the rule.
        Error::StepTooLarge {
            what,
            value,
            reason,
            suggested,
        } => raise(
            py,
            "ArgumentError",
            message,
            &[
                ("field", obj(py, what)),
                ("value", obj(py, value)),
                (
                    "rule",
                    obj(
                        py,
                        format!(
                            "{reason}; use {what} <= {}",
                            whipple::advanced::short_number(suggested)
                        ),
                    ),
                ),
                ("suggested", obj(py, suggested)),
            ],
        ),
        Error::AccuracyLost { quantity, reason } => raise(
            py,
            "AccuracyLostError",
            message,
            &[
                ("field", obj(py, quantity)),
                ("value", py.None()),
                ("rule", obj(py, reason)),
            ],
        ),
        Error::NoSteadyTurn { given, reason } => raise(
            py,
            "NoSteadyTurnError",
            message,
            &[
                ("field", py.None()),
                ("value", obj(py, given.clone())),
                ("rule", obj(py, reason)),
                ("given", obj(py, given)),
            ],
        ),
        Error::NoConvergence { method, .. } => raise(
            py,
            "NumericalError",
            message.clone(),
            &[
                ("field", obj(py, method)),
                ("value", py.None()),
                ("rule", obj(py, message)),
            ],
        ),
        Error::NonFinite { .. }
        | Error::ProjectionDiverged { .. }
        | Error::NonFiniteState { .. }
        | Error::SingularDynamics { .. } => raise(
            py,
            "NumericalError",
            message.clone(),
            &[
                ("field", py.None()),
                ("value", py.None()),
                ("rule", obj(py, message)),
            ],
        ),
        // `whipple::Error` is non-exhaustive: a variant added later still reaches Python as
        // the base class, never as a panic.
        _ => match class(py, "WhippleError").and_then(|c| c.call1((message.clone(),))) {
            Ok(instance) => PyErr::from_value(instance),
            Err(_) => PyRuntimeError::new_err(message),
        },
    }
}

/// `Result<T, whipple::Error>` into `PyResult<T>`.
pub trait IntoPy<T> {
    /// The value, or the error as its Python exception.
    fn py_err(self, py: Python<'_>) -> PyResult<T>;
}

impl<T> IntoPy<T> for Result<T, Error> {
    fn py_err(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| to_py(py, e))
    }
}
