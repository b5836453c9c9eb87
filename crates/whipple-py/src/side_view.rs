//! The library's side view (`whipple::advanced::side_view`: wheels, steer axis, trail, stylized frame
//! tubes, each body's centre of mass and inertia ellipse) as a dict for the Python figure.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyDictMethods, PyList};
use whipple::advanced::side_view::side_view;

use crate::bicycle::NativeBicycle;
use crate::serialized;

#[pymethods]
impl NativeBicycle {
    /// The side view's geometry (x forward from the rear contact, y up, metres): the core's
    /// `whipple::advanced::side_view::SideView` as a dict (points as (x, y) tuples, each body's
    /// `ellipse` a dict of `semi_axes` and `angle` or None), with what its methods derive beside:
    /// `frame_tubes` (six segments) and each body's `is_wheel` and `is_front`.
    fn side_view<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = side_view(&self.checked.benchmark, self.bicycle.jbike6());
        let d = serialized(py, &v)?;
        let dict = d.cast::<PyDict>()?;
        dict.set_item("frame_tubes", serialized(py, &v.frame_tubes())?)?;
        let bodies = dict
            .get_item("bodies")?
            .ok_or_else(|| pyo3::exceptions::PyKeyError::new_err("bodies"))?;
        for (body, b) in bodies.cast::<PyList>()?.iter().zip(&v.bodies) {
            let body = body.cast::<PyDict>()?;
            body.set_item("is_wheel", b.part.is_wheel())?;
            body.set_item("is_front", b.part.is_front())?;
        }
        Ok(d)
    }
}
