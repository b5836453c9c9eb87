//! The bicycle as a linear system from Python: the signals by name (parsed by
//! `whipple_front::system`, as the command line reads them), A, B, C, D, the transfer functions
//! (the core's, from the polynomial matrix) and frequency responses, one speed at a time or many
//! speeds at once (rayon, the GIL released, the buffers reserved first).

use numpy::{Complex64 as NpComplex, PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use whipple::Error;
use whipple::advanced::linear::{LinearSystem, SystemRequest, TransferFunction};
use whipple_front::system::request_with_states;

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::guard::{estimate, grow, interruptible, is_stopped, memory_error, reserve, stopped};

/// Points (speeds × pairs × frequencies) few enough to compute without a watcher thread.
const SHORT_POINTS: usize = 4096;

/// Points from which the speeds are shared among the cores (below, waking them costs more).
const PARALLEL_POINTS: usize = 16_384;

fn complex(z: whipple::advanced::eigen::Complex64) -> NpComplex {
    NpComplex::new(z.re, z.im)
}

fn request(
    inputs: &[String],
    outputs: &[String],
    states: &[String],
) -> whipple::Result<SystemRequest> {
    let inputs: Vec<&str> = inputs.iter().map(String::as_str).collect();
    let outputs: Vec<&str> = outputs.iter().map(String::as_str).collect();
    let states: Vec<&str> = states.iter().map(String::as_str).collect();
    request_with_states(&inputs, &outputs, &states)
}

/// A matrix as a 2-D numpy array.
pub(crate) fn matrix<'py>(
    py: Python<'py>,
    m: &nalgebra::DMatrix<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| (i, j)))
        .map(|(i, j)| m[(i, j)])
        .collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([m.nrows(), m.ncols()])?
        .into_any())
}

/// A linear system of one bicycle at one speed (`whipple.LinearSystem` wraps it).
#[pyclass(name = "NativeLinearSystem", module = "whipple._whipple", frozen)]
pub struct NativeLinearSystem {
    system: LinearSystem,
}

impl NativeLinearSystem {
    /// Wraps a system the core built.
    pub(crate) fn from_system(system: LinearSystem) -> Self {
        NativeLinearSystem { system }
    }

    /// The core's system.
    pub(crate) fn system(&self) -> &LinearSystem {
        &self.system
    }
}

/// A, B, C and D as numpy arrays.
type Matrices<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
);

/// One signal as (name, label, symbol, unit): the label tells points apart
/// (`lateral_force(x = 0.3 m, z = -1 m)`).
type Signal = (&'static str, String, &'static str, &'static str);

#[pymethods]
impl NativeBicycle {
    /// The linear system at `speed` with the inputs, outputs and extra states named as the
    /// command line names them.
    fn linear_system(
        &self,
        py: Python<'_>,
        speed: f64,
        inputs: Vec<String>,
        outputs: Vec<String>,
        states: Vec<String>,
    ) -> PyResult<NativeLinearSystem> {
        let request = request(&inputs, &outputs, &states).py_err(py)?;
        let system = LinearSystem::new(&self.checked.benchmark, speed, &request).py_err(py)?;
        Ok(NativeLinearSystem { system })
    }

    /// Frequency responses at many speeds: G(iω) (n, outputs, inputs, frequencies) complex,
    /// and (n, 3, outputs, inputs, frequencies) holding |G|, 20 log₁₀ |G| and the phase
    /// unwrapped along the frequencies [rad], each from the core.
    #[pyo3(signature = (speeds, frequencies, inputs, outputs, parallel=true))]
    fn frequency_responses<'py>(
        &self,
        py: Python<'py>,
        speeds: PyReadonlyArray1<'py, f64>,
        frequencies: PyReadonlyArray1<'py, f64>,
        inputs: Vec<String>,
        outputs: Vec<String>,
        parallel: bool,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let request = request(&inputs, &outputs, &[]).py_err(py)?;
        let bike = self.checked.benchmark;
        // The request and the bicycle checked once, before anything is reserved.
        LinearSystem::new(&bike, 0.0, &request).py_err(py)?;
        let (ny, nu) = (request.outputs.len(), request.inputs.len());
        let n = speeds.as_slice()?.len();
        let nf = frequencies.as_slice()?.len();
        let per_speed = ny * nu * nf;
        // G (16 bytes) and three reals (24) a point, and the core's per-pair response (its
        // own four arrays, one pair at a time).
        let points = n.saturating_mul(per_speed);
        let too_big = || {
            memory_error(
                "frequency_responses",
                points as u128,
                "points (speeds × pairs × frequencies)",
                estimate(points, 40),
            )
        };
        let mut speeds_copy = reserve::<f64>(n, too_big)?;
        speeds_copy.extend_from_slice(speeds.as_slice()?);
        let mut grid = reserve::<f64>(nf, too_big)?;
        grid.extend_from_slice(frequencies.as_slice()?);
        let mut response = reserve::<NpComplex>(points, too_big)?;
        let mut reals = reserve::<f64>(points.saturating_mul(3), too_big)?;
        let zero = NpComplex::new(0.0, 0.0);
        interruptible(py, points <= SHORT_POINTS, |stop| {
            grow(&mut response, points, zero, stop)?;
            grow(&mut reals, points * 3, 0.0, stop)?;
            let one = |k: usize, g: &mut [NpComplex], r: &mut [f64]| -> whipple::Result<()> {
                if is_stopped(stop) {
                    return Err(stopped());
                }
                let system = LinearSystem::new(&bike, speeds_copy[k], &request)?;
                for o in 0..ny {
                    for i in 0..nu {
                        let at = (o * nu + i) * nf;
                        let f = system.transfer_function(o, i)?.frequency_response(&grid)?;
                        for (j, value) in f.response.iter().enumerate() {
                            g[at + j] = complex(*value);
                            r[at + j] = f.magnitude[j];
                            r[per_speed + at + j] = f.magnitude_db[j];
                            r[2 * per_speed + at + j] = f.phase[j];
                        }
                    }
                }
                Ok(())
            };
            if per_speed == 0 {
                return Ok(());
            }
            let serial = |g: &mut [NpComplex], r: &mut [f64]| {
                g.chunks_mut(per_speed)
                    .zip(r.chunks_mut(3 * per_speed))
                    .enumerate()
                    .try_for_each(|(k, (g, r))| one(k, g, r))
            };
            if parallel && points >= PARALLEL_POINTS {
                let failed = response
                    .par_chunks_mut(per_speed)
                    .zip(reals.par_chunks_mut(3 * per_speed))
                    .enumerate()
                    .try_for_each(|(k, (g, r))| one(k, g, r))
                    .is_err();
                // The first error in speed order, as the serial path reports it.
                if failed {
                    serial(&mut response, &mut reals)?;
                }
                Ok(())
            } else {
                serial(&mut response, &mut reals)
            }
        })?
        .py_err(py)?;
        let g = PyArray1::from_vec(py, response).reshape([n, ny, nu, nf])?;
        let r = PyArray1::from_vec(py, reals).reshape([n, 3, ny, nu, nf])?;
        Ok((g.into_any(), r.into_any()))
    }

    /// The speeds [m/s] at which a zero of `input` → `output` (lean or steer) passes through
    /// s = 0, certified (the core's `origin_zero_speeds`).
    fn origin_zero_speeds(
        &self,
        py: Python<'_>,
        input: String,
        output: String,
    ) -> PyResult<Vec<f64>> {
        let input = whipple_front::system::parse_input(&input).py_err(py)?;
        let coordinate = match whipple_front::system::parse_output(&output).py_err(py)? {
            whipple::advanced::linear::Output::State(state) => state,
            other => {
                return Err(Error::InvalidArgument {
                    what: "output",
                    rule: format!(
                        "zeros through the origin are found for lean or steer, not {other}"
                    ),
                })
                .py_err(py);
            }
        };
        let roots = whipple::advanced::linear::origin_zero_speeds(
            &self.checked.benchmark,
            &input,
            coordinate,
        )
        .py_err(py)?;
        Ok(roots.iter().map(|r| r.value()).collect())
    }
}

fn transfer_dict<'py>(py: Python<'py>, tf: &TransferFunction) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("numerator", PyArray1::from_vec(py, tf.numerator.clone()))?;
    d.set_item("denominator", PyArray1::from_vec(py, tf.denominator()))?;
    let poles: Vec<NpComplex> = tf.poles().into_iter().map(complex).collect();
    d.set_item("poles", PyArray1::from_vec(py, poles))?;
    let zeros: Vec<NpComplex> = tf.zeros().py_err(py)?.into_iter().map(complex).collect();
    d.set_item("zeros", PyArray1::from_vec(py, zeros))?;
    d.set_item("gain", tf.gain())?;
    d.set_item("static_gain", tf.static_gain())?;
    d.set_item("integrators", tf.integrators)?;
    Ok(d)
}

#[pymethods]
impl NativeLinearSystem {
    /// The forward speed [m/s].
    #[getter]
    fn speed(&self) -> f64 {
        self.system.speed()
    }

    /// (A, B, C, D) as 2-D arrays.
    fn matrices<'py>(&self, py: Python<'py>) -> PyResult<Matrices<'py>> {
        let s = &self.system;
        Ok((
            matrix(py, s.a())?,
            matrix(py, s.b())?,
            matrix(py, s.c())?,
            matrix(py, s.d())?,
        ))
    }

    /// The states, inputs and outputs, each a list of (name, label, symbol, unit).
    fn signals(&self) -> (Vec<Signal>, Vec<Signal>, Vec<Signal>) {
        let s = &self.system;
        (
            s.states()
                .iter()
                .map(|x| (x.name(), x.to_string(), x.symbol(), x.unit()))
                .collect(),
            s.inputs()
                .iter()
                .map(|x| (x.name(), x.to_string(), x.symbol(), x.unit()))
                .collect(),
            s.outputs()
                .iter()
                .map(|x| (x.name(), x.to_string(), x.symbol(), x.unit()))
                .collect(),
        )
    }

    /// The nominal rates of the states (v/r for the wheel angles' drift, …) as the core gives them.
    fn nominal_rates<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.system.nominal_rates())
    }

    /// The transfer function of output `output` and input `input` (indices) as a dict:
    /// numerator and denominator lowest power first, poles, zeros, gain, static_gain,
    /// integrators.
    fn transfer_function<'py>(
        &self,
        py: Python<'py>,
        output: usize,
        input: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let tf = self.system.transfer_function(output, input).py_err(py)?;
        transfer_dict(py, &tf)
    }

    /// G(iω) for every pair: (outputs, inputs, frequencies) complex, and (3, outputs, inputs,
    /// frequencies) holding |G|, 20 log₁₀ |G| and the unwrapped phase [rad].
    fn frequency_response<'py>(
        &self,
        py: Python<'py>,
        frequencies: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let grid = frequencies.as_slice()?.to_vec();
        let s = &self.system;
        let (ny, nu, nf) = (s.outputs().len(), s.inputs().len(), grid.len());
        let points = ny * nu * nf;
        let too_big = || {
            memory_error(
                "frequency_response",
                points as u128,
                "points (pairs × frequencies)",
                estimate(points, 40),
            )
        };
        let mut g = reserve::<NpComplex>(points, too_big)?;
        let mut r = reserve::<f64>(3 * points, too_big)?;
        let all = py.detach(|| s.frequency_responses(&grid)).py_err(py)?;
        for row in &all {
            for f in row {
                g.extend(f.response.iter().map(|z| complex(*z)));
            }
        }
        for part in 0..3 {
            for row in &all {
                for f in row {
                    r.extend_from_slice(match part {
                        0 => &f.magnitude,
                        1 => &f.magnitude_db,
                        _ => &f.phase,
                    });
                }
            }
        }
        let g = PyArray1::from_vec(py, g).reshape([ny, nu, nf])?;
        let r = PyArray1::from_vec(py, r).reshape([3, ny, nu, nf])?;
        Ok((g.into_any(), r.into_any()))
    }
}
