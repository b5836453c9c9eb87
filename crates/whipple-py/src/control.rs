//! Time responses, the linear/non-linear manoeuvre comparison, feedback, LQR, pole placement
//! and controllability from Python: each computed by the core (`whipple::advanced::linear`,
//! `whipple::advanced::control`); here only the arguments are read and the results shaped
//! into numpy arrays and dicts.

use std::cell::RefCell;
use std::sync::atomic::AtomicBool;

use nalgebra::DMatrix;
use numpy::{Complex64 as NpComplex, PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Error;
use whipple::advanced::control::{ClosedLoop, Gains, lqr_schedule, uncontrollable_speeds};
use whipple::advanced::eigen::Complex64;
use whipple::advanced::integrate::Dopri5Settings;
use whipple::advanced::linear::{
    Input, InputSignal, LinearSystem, Manoeuvre, ManoeuvreMotion, TimeResponse, compare_manoeuvre,
};
use whipple_front::system::{parse_input, request_with_states};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::guard::{SHORT, estimate, interruptible, is_stopped, stopped};
use crate::serialized;
use crate::system::NativeLinearSystem;

fn complex(z: Complex64) -> NpComplex {
    NpComplex::new(z.re, z.im)
}

/// A matrix given as rows (the Python side passes `numpy.ndarray.tolist()`); ragged rows are an
/// error naming `what`.
fn dmatrix(rows: &[Vec<f64>], what: &'static str) -> whipple::Result<DMatrix<f64>> {
    let ncols = rows.first().map_or(0, Vec::len);
    if let Some((i, row)) = rows.iter().enumerate().find(|(_, r)| r.len() != ncols) {
        return Err(Error::InvalidArgument {
            what,
            rule: format!(
                "a matrix needs rows of equal length: row 0 has {ncols} entries, row {i} has {}",
                row.len()
            ),
        });
    }
    Ok(DMatrix::from_fn(rows.len(), ncols, |i, j| rows[i][j]))
}

fn array2<'py>(py: Python<'py>, m: &DMatrix<f64>) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([m.nrows(), m.ncols()])?
        .into_any())
}

fn array1<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyAny> {
    PyArray1::from_slice(py, v).into_any()
}

/// A time response as a dict: `times`, `states` and `outputs` (one row per time), and `path`
/// (rear_x, rear_y, yaw, front_y) when the states hold the ground path, else None.
fn response_dict<'py>(py: Python<'py>, r: &TimeResponse) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("times", array1(py, &r.times))?;
    d.set_item("states", array2(py, &r.states)?)?;
    d.set_item("outputs", array2(py, &r.outputs)?)?;
    match r.ground_path() {
        Some(path) => {
            let p = PyDict::new(py);
            p.set_item("rear_x", array1(py, &path.rear_x))?;
            p.set_item("rear_y", array1(py, &path.rear_y))?;
            p.set_item("yaw", array1(py, &path.yaw))?;
            match &path.front_y {
                Some(y) => p.set_item("front_y", array1(py, y))?,
                None => p.set_item("front_y", py.None())?,
            }
            d.set_item("path", p)?;
        }
        None => d.set_item("path", py.None())?,
    }
    Ok(d)
}

fn motion_dict<'py>(py: Python<'py>, m: &ManoeuvreMotion) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, column) in m.columns() {
        d.set_item(name, array1(py, column))?;
    }
    Ok(d)
}

/// Each input's signal, piecewise linear between `knots` with `values[i]` for input i.
fn signals(knots: &[f64], values: &[Vec<f64>]) -> whipple::Result<Vec<InputSignal>> {
    values
        .iter()
        .map(|v| InputSignal::piecewise_linear(knots.to_vec(), v.clone()))
        .collect()
}

fn gains(matrices: &[Vec<Vec<f64>>], speeds: Option<Vec<f64>>) -> whipple::Result<Gains> {
    let ks = matrices
        .iter()
        .map(|m| dmatrix(m, "gains"))
        .collect::<whipple::Result<Vec<_>>>()?;
    match speeds {
        None => match <[DMatrix<f64>; 1]>::try_from(ks) {
            Ok([k]) => Ok(Gains::Constant(k)),
            Err(ks) => Err(Error::InvalidArgument {
                what: "gains",
                rule: format!(
                    "one matrix K (inputs × states) without speeds, got {}",
                    ks.len()
                ),
            }),
        },
        Some(speeds) => Ok(Gains::Scheduled { speeds, gains: ks }),
    }
}

/// The lean–steer states, the closed loop's outputs unless others are asked for (its
/// eigenvalues and critical speeds do not depend on them).
const LEAN_STEER_OUTPUTS: [&str; 4] = ["lean", "steer", "lean_rate", "steer_rate"];

fn closed_loop(
    bike: &NativeBicycle,
    inputs: &[String],
    states: &[String],
    matrices: &[Vec<Vec<f64>>],
    speeds: Option<Vec<f64>>,
) -> whipple::Result<ClosedLoop> {
    closed_loop_with_outputs(bike, inputs, states, None, matrices, speeds)
}

fn closed_loop_with_outputs(
    bike: &NativeBicycle,
    inputs: &[String],
    states: &[String],
    outputs: Option<&[String]>,
    matrices: &[Vec<Vec<f64>>],
    speeds: Option<Vec<f64>>,
) -> whipple::Result<ClosedLoop> {
    let inputs: Vec<&str> = inputs.iter().map(String::as_str).collect();
    let states: Vec<&str> = states.iter().map(String::as_str).collect();
    let outputs: Vec<&str> = match outputs {
        Some(names) => names.iter().map(String::as_str).collect(),
        None => LEAN_STEER_OUTPUTS.to_vec(),
    };
    let request = request_with_states(&inputs, &outputs, &states)?;
    ClosedLoop::new(&bike.checked.benchmark, &request, gains(matrices, speeds)?)
}

#[pymethods]
impl NativeLinearSystem {
    /// The exact response from `initial` to inputs piecewise linear between `knots` (one list
    /// of values per input), sampled at `times`: a dict (times, states, outputs, path).
    fn response<'py>(
        &self,
        py: Python<'py>,
        initial: Vec<f64>,
        knots: Vec<f64>,
        values: Vec<Vec<f64>>,
        times: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let s = self.system();
        let r = py
            .detach(|| s.response(&initial, &signals(&knots, &values)?, &times))
            .py_err(py)?;
        response_dict(py, &r)
    }

    /// The response to `function(t)` → the inputs (a sequence of floats), integrated by
    /// Dormand–Prince 5(4) with relative tolerance `rtol` (absolute `atol`). An exception the
    /// function raises is raised again as it was.
    fn response_to_function<'py>(
        &self,
        py: Python<'py>,
        initial: Vec<f64>,
        function: Bound<'py, PyAny>,
        times: Vec<f64>,
        rtol: f64,
        atol: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let raised: RefCell<Option<PyErr>> = RefCell::new(None);
        let m = self.system().inputs().len();
        let call = |t: f64, u: &mut [f64]| -> whipple::Result<()> {
            let got = function.call1((t,)).and_then(|v| v.extract::<Vec<f64>>());
            match got {
                Ok(v) if v.len() == m => {
                    u.copy_from_slice(&v);
                    Ok(())
                }
                Ok(v) => Err(Error::InvalidArgument {
                    what: "u",
                    rule: format!(
                        "u(t) must give one value per input ({m}), got {} at t = {t}",
                        v.len()
                    ),
                }),
                Err(e) => {
                    *raised.borrow_mut() = Some(e);
                    Err(Error::InvalidArgument {
                        what: "u",
                        rule: format!("u(t) raised at t = {t}"),
                    })
                }
            }
        };
        let settings = Dopri5Settings {
            rtol,
            atol,
            ..Dopri5Settings::default()
        };
        let r = self
            .system()
            .response_to_function(&initial, call, &times, &settings);
        if let Some(e) = raised.into_inner() {
            return Err(e);
        }
        response_dict(py, &r.py_err(py)?)
    }

    /// From rest, a unit step of input `input` (index) at t = 0.
    fn step_response<'py>(
        &self,
        py: Python<'py>,
        input: usize,
        times: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let s = self.system();
        let r = py.detach(|| s.step_response(input, &times)).py_err(py)?;
        response_dict(py, &r)
    }

    /// A unit impulse of input `input` (index) at t = 0.
    fn impulse_response<'py>(
        &self,
        py: Python<'py>,
        input: usize,
        times: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let s = self.system();
        let r = py.detach(|| s.impulse_response(input, &times)).py_err(py)?;
        response_dict(py, &r)
    }

    /// The free response from `initial`.
    fn initial_response<'py>(
        &self,
        py: Python<'py>,
        initial: Vec<f64>,
        times: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let s = self.system();
        let r = py
            .detach(|| s.initial_response(&initial, &times))
            .py_err(py)?;
        response_dict(py, &r)
    }

    /// LQR for weights Q (states × states) and R (inputs × inputs): (K, X, closed-loop
    /// eigenvalues, residual, Newton steps).
    #[allow(clippy::type_complexity)]
    fn lqr<'py>(
        &self,
        py: Python<'py>,
        q: Vec<Vec<f64>>,
        r: Vec<Vec<f64>>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        f64,
        usize,
    )> {
        let q = dmatrix(&q, "Q").py_err(py)?;
        let r = dmatrix(&r, "R").py_err(py)?;
        let s = self.system();
        let lqr = py.detach(|| s.lqr(&q, &r)).py_err(py)?;
        let poles: Vec<NpComplex> = lqr
            .closed_loop_eigenvalues
            .iter()
            .map(|z| complex(*z))
            .collect();
        Ok((
            array2(py, &lqr.gains)?,
            array2(py, &lqr.solution)?,
            PyArray1::from_vec(py, poles).into_any(),
            lqr.residual,
            lqr.newton_steps,
        ))
    }

    /// K (1 × states) placing the eigenvalues of A − B K at `poles` ((re, im) pairs; one
    /// input).
    fn place_poles<'py>(
        &self,
        py: Python<'py>,
        poles: Vec<(f64, f64)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let poles: Vec<Complex64> = poles
            .iter()
            .map(|&(re, im)| Complex64::new(re, im))
            .collect();
        let k = self.system().place_poles(&poles).py_err(py)?;
        array2(py, &k)
    }

    /// The Kalman controllability matrix's singular values, rank, tolerance, condition and
    /// number of states, for input `input` (index) or all inputs (None).
    #[pyo3(signature = (input=None))]
    fn controllability<'py>(
        &self,
        py: Python<'py>,
        input: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let c = self.system().controllability(input).py_err(py)?;
        let d = PyDict::new(py);
        d.set_item("singular_values", array1(py, &c.singular_values))?;
        d.set_item("rank", c.rank)?;
        d.set_item("tolerance", c.tolerance)?;
        d.set_item("condition", c.condition)?;
        d.set_item("states", c.states)?;
        Ok(d)
    }

    /// Each mode's eigenvalue and modal controllability measure (two arrays) for input `input` (index).
    fn modal_controllability<'py>(
        &self,
        py: Python<'py>,
        input: usize,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let m = self.system().modal_controllability(input).py_err(py)?;
        let values: Vec<NpComplex> = m.iter().map(|x| complex(x.eigenvalue)).collect();
        let measures: Vec<f64> = m.iter().map(|x| x.measure).collect();
        Ok((
            PyArray1::from_vec(py, values).into_any(),
            array1(py, &measures),
        ))
    }
}

#[pymethods]
impl NativeBicycle {
    /// The closed loop's eigenvalues at `speeds`: (values (n, k), vectors (n, k, k), mode
    /// labels or None).
    /// With gains on φ, δ, φ̇, δ̇ only: tracked and labelled (the core's `eigen_sweep`);
    /// otherwise the general eigensolver's, by decreasing real part.
    #[pyo3(signature = (inputs, states, gains, gain_speeds, speeds))]
    #[allow(clippy::type_complexity)]
    fn closed_loop_eig<'py>(
        &self,
        py: Python<'py>,
        inputs: Vec<String>,
        states: Vec<String>,
        gains: Vec<Vec<Vec<f64>>>,
        gain_speeds: Option<Vec<f64>>,
        speeds: Vec<f64>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Option<Vec<&'static str>>,
    )> {
        let closed = closed_loop(self, &inputs, &states, &gains, gain_speeds).py_err(py)?;
        let n = speeds.len();
        // Each speed's eigenvectors, in its eigenvalues' order (row-major k × k: row = state,
        // column = eigenvalue, as `Bicycle.eig`'s), allocated only if memory allows.
        let vectors = |values: &[NpComplex],
                       k: usize,
                       stop: &AtomicBool|
         -> whipple::Result<Vec<NpComplex>> {
            let len = values.len().saturating_mul(k);
            let mut out = Vec::new();
            out.try_reserve_exact(len)
                .map_err(|_| Error::LimitExceeded {
                    what: "speeds",
                    rule: format!(
                        "{n} speeds' eigenvectors need {} bytes, more than this process can \
                         allocate; use fewer speeds",
                        estimate(len, 16)
                    ),
                })?;
            out.resize(len, NpComplex::new(0.0, 0.0));
            let mut at = Vec::with_capacity(k);
            for (i, v) in speeds.iter().enumerate() {
                if is_stopped(stop) {
                    return Err(stopped());
                }
                at.clear();
                at.extend(
                    values[i * k..(i + 1) * k]
                        .iter()
                        .map(|z| Complex64::new(z.re, z.im)),
                );
                for (col, x) in closed.eigenvectors(*v, &at)?.iter().enumerate() {
                    for row in 0..k {
                        out[i * k * k + row * k + col] = complex(x[row]);
                    }
                }
            }
            Ok(out)
        };
        let short = n <= SHORT;
        if closed.is_lean_steer() {
            let (by_speed, vecs, modes) = interruptible(py, short, |stop| {
                let sweep = closed.eigen_sweep_until(&speeds, stop)?;
                let values: Vec<NpComplex> = sweep
                    .eigenvalues
                    .iter()
                    .flat_map(|row| row.iter().map(|z| complex(*z)))
                    .collect();
                // The sweep sorts the speeds; put the rows back in the caller's order.
                let mut order: Vec<usize> = (0..n).collect();
                order.sort_by(|&i, &j| speeds[i].total_cmp(&speeds[j]));
                let mut by_speed = vec![NpComplex::new(0.0, 0.0); values.len()];
                if sweep.eigenvalues.len() == n {
                    for (k, &i) in order.iter().enumerate() {
                        by_speed[4 * i..4 * i + 4].copy_from_slice(&values[4 * k..4 * k + 4]);
                    }
                } else {
                    by_speed = values;
                }
                let vecs = vectors(&by_speed, 4, stop)?;
                Ok::<_, Error>((by_speed, vecs, sweep.modes))
            })?
            .py_err(py)?;
            let labels = modes.iter().map(|m| m.name()).collect();
            let arr = PyArray1::from_vec(py, by_speed).reshape([n, 4])?;
            let vecs = PyArray1::from_vec(py, vecs).reshape([n, 4, 4])?;
            Ok((arr.into_any(), vecs.into_any(), Some(labels)))
        } else {
            let (flat, vecs, width) = interruptible(py, short, |stop| {
                let rows = closed.general_sweep_until(&speeds, stop)?;
                let width = rows.first().map_or(0, Vec::len);
                let flat: Vec<NpComplex> = rows
                    .iter()
                    .flat_map(|row| row.iter().map(|z| complex(*z)))
                    .collect();
                let vecs = vectors(&flat, width, stop)?;
                Ok::<_, Error>((flat, vecs, width))
            })?
            .py_err(py)?;
            let arr = PyArray1::from_vec(py, flat).reshape([n, width])?;
            let vecs = PyArray1::from_vec(py, vecs).reshape([n, width, width])?;
            Ok((arr.into_any(), vecs.into_any(), None))
        }
    }

    /// The closed loop's certified critical speeds in [lo, hi] (the core's `CriticalSpeeds`
    /// as a dict).
    #[allow(clippy::too_many_arguments)]
    fn closed_loop_critical_speeds<'py>(
        &self,
        py: Python<'py>,
        inputs: Vec<String>,
        states: Vec<String>,
        gains: Vec<Vec<Vec<f64>>>,
        gain_speeds: Option<Vec<f64>>,
        lo: f64,
        hi: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let closed = closed_loop(self, &inputs, &states, &gains, gain_speeds).py_err(py)?;
        let speeds = py.detach(|| closed.critical_speeds(lo, hi)).py_err(py)?;
        serialized(py, &speeds)
    }

    /// LQR gains for the same Q and R at each of `speeds` (the core's `lqr_schedule`): the
    /// gains (speeds, inputs, states) and each speed's Riccati residual.
    fn lqr_schedule<'py>(
        &self,
        py: Python<'py>,
        inputs: Vec<String>,
        states: Vec<String>,
        speeds: Vec<f64>,
        q: Vec<Vec<f64>>,
        r: Vec<Vec<f64>>,
    ) -> PyResult<(Vec<Bound<'py, PyAny>>, Vec<f64>)> {
        let inputs: Vec<&str> = inputs.iter().map(String::as_str).collect();
        let states: Vec<&str> = states.iter().map(String::as_str).collect();
        let request = request_with_states(&inputs, &LEAN_STEER_OUTPUTS, &states).py_err(py)?;
        let q = dmatrix(&q, "Q").py_err(py)?;
        let r = dmatrix(&r, "R").py_err(py)?;
        let bike = self.checked.benchmark;
        let schedule = py
            .detach(|| lqr_schedule(&bike, &request, &speeds, &q, &r))
            .py_err(py)?;
        let gains = schedule
            .solutions
            .iter()
            .map(|s| array2(py, &s.gains))
            .collect::<PyResult<Vec<_>>>()?;
        Ok((
            gains,
            schedule.solutions.iter().map(|s| s.residual).collect(),
        ))
    }

    /// The closed loop at `speed` as a linear system (A − B K, B, C − D K, D), with
    /// `outputs` by name (default: the lean–steer states).
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (inputs, states, gains, gain_speeds, speed, outputs = None))]
    fn closed_loop_system(
        &self,
        py: Python<'_>,
        inputs: Vec<String>,
        states: Vec<String>,
        gains: Vec<Vec<Vec<f64>>>,
        gain_speeds: Option<Vec<f64>>,
        speed: f64,
        outputs: Option<Vec<String>>,
    ) -> PyResult<NativeLinearSystem> {
        let closed = closed_loop_with_outputs(
            self,
            &inputs,
            &states,
            outputs.as_deref(),
            &gains,
            gain_speeds,
        )
        .py_err(py)?;
        let system: LinearSystem = closed.system(speed).py_err(py)?;
        Ok(NativeLinearSystem::from_system(system))
    }

    /// The speeds where `input` loses a mode, certified: (speeds, eigenvalues there,
    /// everywhere).
    fn uncontrollable_speeds<'py>(
        &self,
        py: Python<'py>,
        input: String,
    ) -> PyResult<(Vec<f64>, Bound<'py, PyAny>, bool)> {
        let input = parse_input(&input).py_err(py)?;
        let bike = self.checked.benchmark;
        let lost = py
            .detach(|| uncontrollable_speeds(&bike, &input))
            .py_err(py)?;
        Ok((
            lost.speeds.iter().map(|s| s.speed.value()).collect(),
            PyArray1::from_vec(
                py,
                lost.speeds.iter().map(|s| complex(s.eigenvalue)).collect(),
            )
            .into_any(),
            lost.everywhere,
        ))
    }

    /// The linear and non-linear models through one manoeuvre from upright straight running:
    /// `torques` a list of (input name, knots, values), piecewise linear. A dict: times,
    /// linear, nonlinear, difference (each lean, steer, yaw, rear_x, rear_y, front_y),
    /// nonlinear_steps.
    #[allow(clippy::too_many_arguments)]
    fn compare_manoeuvre<'py>(
        &self,
        py: Python<'py>,
        speed: f64,
        lean: f64,
        steer: f64,
        torques: Vec<(String, Vec<f64>, Vec<f64>)>,
        times: Vec<f64>,
        rtol: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let inputs = torques
            .into_iter()
            .map(|(name, knots, values)| {
                let input: Input = parse_input(&name)?;
                Ok((input, InputSignal::piecewise_linear(knots, values)?))
            })
            .collect::<whipple::Result<Vec<_>>>()
            .py_err(py)?;
        let manoeuvre = Manoeuvre {
            speed,
            lean,
            steer,
            inputs,
        };
        let bike = self.checked.benchmark;
        let both = py
            .detach(|| compare_manoeuvre(&bike, &manoeuvre, &times, rtol))
            .py_err(py)?;
        let d = PyDict::new(py);
        d.set_item("times", array1(py, &both.times))?;
        d.set_item("linear", motion_dict(py, &both.linear)?)?;
        d.set_item("nonlinear", motion_dict(py, &both.nonlinear)?)?;
        d.set_item("difference", motion_dict(py, &both.difference)?)?;
        d.set_item("nonlinear_steps", both.nonlinear_steps)?;
        Ok(d)
    }
}
