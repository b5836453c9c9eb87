//! HumanControl's lane change ridden by Hess's controller from Python: computed by the core
//! (`whipple::advanced::control::lane_change_linear`, `lane_change_nonlinear`); here only the
//! arguments are read and the runs shaped into numpy arrays.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Error;
use whipple::advanced::control::{
    HumanController, HumanGains, LaneChange, LaneChangeRun, LaneKind, Neuromuscular, Task,
    lane_change_linear, lane_change_nonlinear,
};
use whipple::advanced::io::read_gains;

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;

fn run_dict<'py>(py: Python<'py>, run: &LaneChangeRun) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, values) in run.columns() {
        d.set_item(name, PyArray1::from_slice(py, values))?;
    }
    Ok(d)
}

#[pymethods]
impl NativeBicycle {
    /// HumanControl's lane change at `speed`: the lateral task's gains either `gains` (kDelta,
    /// kPhiDot, kPhi, kPsi, kY) or interpolated from `gains_text` (a SteerGains file's text);
    /// `lane` single or double, `width` the lateral offset (None: 2 m), `model` linear,
    /// nonlinear or both. A dict: gains, extrapolated, and `linear` / `nonlinear` (each a dict
    /// of arrays: time, path, command, front_x, front_y, error, lean, steer, yaw,
    /// steer_torque) for the models run.
    #[pyo3(signature = (speed, gains, gains_text, lane, width, model, neuro_frequency, neuro_damping, rtol))]
    #[allow(clippy::too_many_arguments)]
    fn lane_change<'py>(
        &self,
        py: Python<'py>,
        speed: f64,
        gains: Option<Vec<f64>>,
        gains_text: Option<String>,
        lane: &str,
        width: Option<f64>,
        model: &str,
        neuro_frequency: f64,
        neuro_damping: f64,
        rtol: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let bad = |what: &'static str, rule: String| Error::InvalidArgument { what, rule };
        let (gains, extrapolated) = match (gains, gains_text) {
            (Some(k), None) => {
                let k: [f64; 5] = k
                    .as_slice()
                    .try_into()
                    .map_err(|_| {
                        bad(
                            "gains",
                            format!(
                                "five gains (kDelta, kPhiDot, kPhi, kPsi, kY), got {}",
                                k.len()
                            ),
                        )
                    })
                    .py_err(py)?;
                (HumanGains::from_array(k), false)
            }
            (None, Some(text)) => {
                let lookup = read_gains(&text)
                    .and_then(|table| table.at(speed))
                    .py_err(py)?;
                (lookup.gains, lookup.extrapolated)
            }
            _ => {
                return Err(bad(
                    "gains",
                    "give the gains or a gains file, not both".into(),
                ))
                .py_err(py);
            }
        };
        let (run_linear, run_nonlinear) = match model {
            "linear" => (true, false),
            "nonlinear" => (false, true),
            "both" => (true, true),
            other => {
                return Err(bad(
                    "model",
                    format!("`{other}` is not a model: use linear, nonlinear or both"),
                ))
                .py_err(py);
            }
        };
        let controller = HumanController::new(
            Task::Lateral,
            gains,
            Neuromuscular {
                frequency: neuro_frequency,
                damping: neuro_damping,
            },
        )
        .py_err(py)?;
        let mut path = LaneChange::humancontrol(LaneKind::from_name(lane).py_err(py)?);
        if let Some(width) = width {
            if !(width.is_finite() && width != 0.0) {
                return Err(Error::InvalidParameter {
                    field: "width".into(),
                    value: width,
                    rule: "must be non-zero and finite".into(),
                })
                .py_err(py);
            }
            path = path.scaled(width / path.width);
        }
        let bike = self.checked.benchmark;
        let (linear, nonlinear) = py
            .detach(|| -> whipple::Result<_> {
                let linear = run_linear
                    .then(|| lane_change_linear(&bike, speed, &controller, &path))
                    .transpose()?;
                let nonlinear = run_nonlinear
                    .then(|| lane_change_nonlinear(&bike, speed, &controller, &path, rtol))
                    .transpose()?;
                Ok((linear, nonlinear))
            })
            .py_err(py)?;
        let d = PyDict::new(py);
        d.set_item("gains", PyArray1::from_slice(py, &gains.to_array()))?;
        d.set_item("extrapolated", extrapolated)?;
        for (name, run) in [("linear", &linear), ("nonlinear", &nonlinear)] {
            match run {
                Some(run) => d.set_item(name, run_dict(py, run)?)?,
                None => d.set_item(name, py.None())?,
            }
        }
        Ok(d)
    }
}
