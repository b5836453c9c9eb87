//! The leaning rider (Moore 2012's rider-lean model): BicycleParameters' `MooreRiderLean2012`
//! keys in, the library's five-body model and its exact linearization out.

use pyo3::prelude::*;
use whipple::Bicycle;
use whipple::advanced::nonlinear::LeanModel;
use whipple::advanced::parameters::{
    Description, MOORE_RIDER_LEAN2012_KEYS, MooreRiderLean2012Parameters, RiderLeanParameters,
    UpperBody,
};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::system::matrix;

/// A bicycle with a leaning rider (the native half of `whipple.RiderLean`).
#[pyclass(name = "NativeRiderLean", module = "whipple._whipple", frozen)]
pub struct NativeRiderLean {
    model: LeanModel,
}

#[pymethods]
impl NativeRiderLean {
    /// From (key, value) pairs of BicycleParameters' `MooreRiderLean2012` set: every one of
    /// the 36 keys once, `v` accepted and ignored, other keys refused; checked by the library.
    #[staticmethod]
    fn from_moore_rider_lean2012(py: Python<'_>, items: Vec<(String, f64)>) -> PyResult<Self> {
        let parameters = MooreRiderLean2012Parameters::from_pairs(&items, "MooreRiderLean2012")
            .py_err(py)?
            .to_rider_lean()
            .py_err(py)?;
        let model = LeanModel::new(&parameters).py_err(py)?;
        Ok(NativeRiderLean { model })
    }

    /// A bicycle with its rider, Jason's upper body (of the Browser with Jason set) split off
    /// its rear frame, hinged at Jason's hinge with this stiffness and damping; refused where
    /// it does not fit inside the bicycle's rider (the library's `RiderLeanParameters::split`).
    #[staticmethod]
    fn from_bicycle(
        py: Python<'_>,
        bike: &NativeBicycle,
        hinge_stiffness: f64,
        hinge_damping: f64,
    ) -> PyResult<Self> {
        let jason = RiderLeanParameters::browser_jason().upper_body;
        let upper_body = UpperBody {
            stiffness: hinge_stiffness,
            damping: hinge_damping,
            ..jason
        };
        let parameters =
            RiderLeanParameters::split(&bike.checked.benchmark, upper_body).py_err(py)?;
        let model = LeanModel::new(&parameters).py_err(py)?;
        Ok(NativeRiderLean { model })
    }

    /// BicycleParameters' `MooreRiderLean2012` keys and values, in the order of
    /// `MOORE_RIDER_LEAN2012_KEYS`.
    fn moore_rider_lean2012(&self) -> Vec<(&'static str, f64)> {
        MOORE_RIDER_LEAN2012_KEYS
            .iter()
            .copied()
            .zip(MooreRiderLean2012Parameters::from_rider_lean(self.model.parameters()).to_array())
            .collect()
    }

    /// The rigid rider: the hinge locked, the upper body combined into the rear frame.
    fn rigid(&self, py: Python<'_>) -> PyResult<NativeBicycle> {
        let bicycle = Bicycle::new(Description::Benchmark(self.model.parameters().rigid()));
        NativeBicycle::new(py, bicycle, false)
    }

    /// A (6 × 6) and B (6 × 3) of the exact linearization at `speed`.
    fn linearize<'py>(
        &self,
        py: Python<'py>,
        speed: f64,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let (a, b) = self.model.linearize(speed).py_err(py)?;
        let a = nalgebra::DMatrix::from_fn(6, 6, |i, j| a[(i, j)]);
        let b = nalgebra::DMatrix::from_fn(6, 3, |i, j| b[(i, j)]);
        Ok((matrix(py, &a)?, matrix(py, &b)?))
    }
}
