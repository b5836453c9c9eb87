//! Hess's human controller from Python: the ridden bicycle's closed loop, each loop's
//! transfer functions and crossovers, gains by Hess 2012's rules, eigenvalues against speed
//! and HumanControl's gain tables — all computed by the core (`whipple::advanced::control`);
//! here only arguments are read and results shaped into numpy arrays and dicts.

use nalgebra::DMatrix;
use numpy::{Complex64 as NpComplex, PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::advanced::control::{
    CrossoverRules, GainSchedule, GainTable, HumanController, HumanGains, HumanLoop, Neuromuscular,
    Task, hess_gains, human_eigen_sweep,
};
use whipple::advanced::io::read_gains;
use whipple::advanced::linear::Input;
use whipple_front::system::parse_input;

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;

fn matrix<'py>(py: Python<'py>, m: &DMatrix<f64>) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([m.nrows(), m.ncols()])?
        .into_any())
}

fn gains_of(values: &[f64]) -> whipple::Result<HumanGains> {
    match values.len() {
        5 => Ok(HumanGains::from_array([
            values[0], values[1], values[2], values[3], values[4],
        ])),
        4 => Ok(HumanGains::from_array([
            values[0], values[1], values[2], values[3], 0.0,
        ])),
        n => Err(whipple::Error::InvalidArgument {
            what: "gains",
            rule: format!(
                "five gains (kDelta, kPhiDot, kPhi, kPsi, kY; four for the heading task), got {n}"
            ),
        }),
    }
}

fn controller(task: &str, gains: &[f64], neuro: (f64, f64)) -> whipple::Result<HumanController> {
    let task = Task::from_name(task)?;
    let g = gains_of(gains)?;
    if task == Task::Lateral && gains.len() == 4 {
        return Err(whipple::Error::InvalidArgument {
            what: "gains",
            rule: "the lateral task needs all five gains, kY included".into(),
        });
    }
    HumanController::new(
        task,
        g,
        Neuromuscular {
            frequency: neuro.0,
            damping: neuro.1,
        },
    )
}

/// Checks a controller's task, gains and neuromuscular filter (the core's errors).
#[pyfunction]
pub(crate) fn check_human_controller(
    py: Python<'_>,
    task: &str,
    gains: Vec<f64>,
    neuro: (f64, f64),
) -> PyResult<()> {
    controller(task, &gains, neuro).py_err(py).map(|_| ())
}

/// A gains file's text read by the core: (speeds, rows of kDelta, kPhiDot, kPhi, kPsi, kY).
#[pyfunction]
pub(crate) fn read_gains_text(py: Python<'_>, text: &str) -> PyResult<(Vec<f64>, Vec<[f64; 5]>)> {
    let table = read_gains(text).py_err(py)?;
    Ok((
        table.speeds().to_vec(),
        table.gains().iter().map(HumanGains::to_array).collect(),
    ))
}

fn table(speeds: Vec<f64>, rows: &[Vec<f64>]) -> whipple::Result<GainTable> {
    let gains = rows
        .iter()
        .map(|r| {
            if r.len() == 5 {
                Ok(HumanGains::from_array([r[0], r[1], r[2], r[3], r[4]]))
            } else {
                Err(whipple::Error::InvalidArgument {
                    what: "gains",
                    rule: format!("each row holds five gains, one holds {}", r.len()),
                })
            }
        })
        .collect::<whipple::Result<Vec<_>>>()?;
    GainTable::new(speeds, gains)
}

/// The table's gains at `speed` (interpolated as HumanControl's `lookup_gains.m`) and whether
/// they were extrapolated.
#[pyfunction]
pub(crate) fn gain_lookup(
    py: Python<'_>,
    speeds: Vec<f64>,
    rows: Vec<Vec<f64>>,
    speed: f64,
) -> PyResult<([f64; 5], bool)> {
    let at = table(speeds, &rows).and_then(|t| t.at(speed)).py_err(py)?;
    Ok((at.gains.to_array(), at.extrapolated))
}

fn complex_array<'py>(
    py: Python<'py>,
    values: &[whipple::advanced::eigen::Complex64],
) -> Bound<'py, PyAny> {
    let v: Vec<NpComplex> = values.iter().map(|z| NpComplex::new(z.re, z.im)).collect();
    PyArray1::from_vec(py, v).into_any()
}

#[pymethods]
impl NativeBicycle {
    /// The ridden bicycle's closed loop at `speed`: a dict of `a`, `b`, `states`, `inputs`
    /// (names) and `eigenvalues` (decreasing real part).
    fn human_closed_loop<'py>(
        &self,
        py: Python<'py>,
        task: &str,
        gains: Vec<f64>,
        neuro: (f64, f64),
        speed: f64,
        disturbances: Vec<String>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let rider = controller(task, &gains, neuro).py_err(py)?;
        let inputs = disturbances
            .iter()
            .map(|d| parse_input(d))
            .collect::<whipple::Result<Vec<Input>>>()
            .py_err(py)?;
        let ridden = HumanLoop::new(&self.checked.benchmark, speed, &rider, &inputs).py_err(py)?;
        let eigenvalues = ridden.eigenvalues().py_err(py)?;
        let d = PyDict::new(py);
        d.set_item("a", matrix(py, ridden.a())?)?;
        d.set_item("b", matrix(py, ridden.b())?)?;
        d.set_item(
            "states",
            ridden.states().iter().map(|s| s.name()).collect::<Vec<_>>(),
        )?;
        d.set_item(
            "inputs",
            ridden.inputs().iter().map(|s| s.name()).collect::<Vec<_>>(),
        )?;
        d.set_item("eigenvalues", complex_array(py, &eigenvalues))?;
        Ok(d)
    }

    /// Each loop of the task, inner first: a list of dicts with `loop`, `gain`, the open and
    /// closed loops' `*_numerator` / `*_denominator` (lowest power first) and `crossovers`
    /// (frequency, lo, hi, certified).
    fn human_loops<'py>(
        &self,
        py: Python<'py>,
        task: &str,
        gains: Vec<f64>,
        neuro: (f64, f64),
        speed: f64,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let rider = controller(task, &gains, neuro).py_err(py)?;
        let ridden = HumanLoop::new(&self.checked.benchmark, speed, &rider, &[]).py_err(py)?;
        let loops = ridden.loops().py_err(py)?;
        loops
            .iter()
            .map(|l| {
                let d = PyDict::new(py);
                d.set_item("loop", l.rider_loop.name())?;
                d.set_item("gain", l.rider_loop.gain_name())?;
                d.set_item("open_numerator", l.open.numerator.clone())?;
                d.set_item("open_denominator", l.open.denominator.clone())?;
                d.set_item("closed_numerator", l.closed.numerator.clone())?;
                d.set_item("closed_denominator", l.closed.denominator.clone())?;
                d.set_item(
                    "crossovers",
                    l.crossovers
                        .iter()
                        .map(|c| (c.frequency, c.lo, c.hi, c.certified))
                        .collect::<Vec<_>>(),
                )?;
                Ok(d)
            })
            .collect()
    }

    /// The five gains by Hess 2012's rules at `speed`.
    fn hess_gains(
        &self,
        py: Python<'_>,
        speed: f64,
        neuro: (f64, f64),
        rules: (f64, f64, [f64; 3]),
    ) -> PyResult<[f64; 5]> {
        let nm = Neuromuscular {
            frequency: neuro.0,
            damping: neuro.1,
        };
        let rules = CrossoverRules {
            steer_damping: rules.0,
            roll_rate_damping: rules.1,
            crossovers: rules.2,
        };
        let bike = &self.checked.benchmark;
        let k = py
            .detach(|| hess_gains(bike, speed, &nm, &rules))
            .py_err(py)?;
        Ok(k.to_array())
    }

    /// The closed loop's eigenvalues at each speed, the gains fixed (`gains`), from a table
    /// (`table`: speeds and rows) or by Hess's rules (`rules`): a dict of `speeds`, `gains`
    /// (n, 5), `extrapolated` (n,) and `eigenvalues` (n, states).
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (task, neuro, speeds, gains=None, table=None, rules=None))]
    fn human_eigen_sweep<'py>(
        &self,
        py: Python<'py>,
        task: &str,
        neuro: (f64, f64),
        speeds: Vec<f64>,
        gains: Option<Vec<f64>>,
        table: Option<(Vec<f64>, Vec<Vec<f64>>)>,
        rules: Option<(f64, f64, [f64; 3])>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let nm = Neuromuscular {
            frequency: neuro.0,
            damping: neuro.1,
        };
        let task_ = Task::from_name(task).py_err(py)?;
        let owned_table;
        let schedule = match (gains, table, rules) {
            (Some(g), None, None) => GainSchedule::Fixed(gains_of(&g).py_err(py)?),
            (None, Some((s, rows)), None) => {
                owned_table = self::table(s, &rows).py_err(py)?;
                GainSchedule::Table(&owned_table)
            }
            (None, None, Some(r)) => GainSchedule::Rules(CrossoverRules {
                steer_damping: r.0,
                roll_rate_damping: r.1,
                crossovers: r.2,
            }),
            _ => {
                return Err(whipple::Error::InvalidArgument {
                    what: "gains",
                    rule: "give exactly one of gains, a table or the rules".into(),
                })
                .py_err(py);
            }
        };
        let bike = &self.checked.benchmark;
        let rows = py
            .detach(|| human_eigen_sweep(bike, task_, &schedule, &nm, &speeds))
            .py_err(py)?;
        let n = rows.len();
        let m = rows.first().map_or(0, |r| r.eigenvalues.len());
        let mut values = Vec::with_capacity(n * m);
        for r in &rows {
            values.extend(r.eigenvalues.iter().map(|z| NpComplex::new(z.re, z.im)));
        }
        let d = PyDict::new(py);
        d.set_item("speeds", PyArray1::from_vec(py, speeds))?;
        let flat: Vec<f64> = rows.iter().flat_map(|r| r.gains.to_array()).collect();
        d.set_item("gains", PyArray1::from_vec(py, flat).reshape([n, 5])?)?;
        d.set_item(
            "extrapolated",
            rows.iter().map(|r| r.extrapolated).collect::<Vec<_>>(),
        )?;
        d.set_item(
            "eigenvalues",
            PyArray1::from_vec(py, values).reshape([n, m])?,
        )?;
        Ok(d)
    }
}
