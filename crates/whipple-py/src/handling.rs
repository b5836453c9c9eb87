//! Hess's handling quality metric from Python: the metric, its certified peak and its peaks
//! against speed computed by the core (`whipple::advanced::control::HandlingQuality`,
//! `handling_against_speed`); here only the arguments are read and the results shaped into a
//! dict of numbers and numpy arrays.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::advanced::control::{
    GainTable, HandlingQuality, HumanGains, MAX_HANDLING_POINTS, Neuromuscular,
    handling_against_speed,
};
use whipple::advanced::io::read_gains;
use whipple::{BenchmarkParameters, Error};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;

/// The neuromuscular filter of the arguments `neuro_frequency` and `neuro_damping`.
fn neuromuscular(frequency: f64, damping: f64) -> Neuromuscular {
    Neuromuscular { frequency, damping }
}

/// The arguments HQM and its sweep against speed share: the bicycle's benchmark form, the
/// gains as given (read by [`Setup::table`] inside the computation) and the neuromuscular
/// filter.
struct Setup {
    bike: BenchmarkParameters,
    gains_text: Option<String>,
    gains_row: Option<Vec<f64>>,
    neuromuscular: Neuromuscular,
}

impl Setup {
    fn new(
        bicycle: &NativeBicycle,
        gains_text: Option<String>,
        gains_row: Option<Vec<f64>>,
        neuro_frequency: f64,
        neuro_damping: f64,
    ) -> Self {
        Setup {
            bike: bicycle.checked.benchmark,
            gains_text,
            gains_row,
            neuromuscular: neuromuscular(neuro_frequency, neuro_damping),
        }
    }

    /// Whether the gains were given as one row: the table gives it at every speed, and
    /// `extrapolated` is then not said.
    fn single_row(&self) -> bool {
        self.gains_row.is_some()
    }

    /// The gains: a SteerGains file's text, or one row of five gains (kDelta … kY) used at
    /// every speed.
    fn table(&self) -> whipple::Result<GainTable> {
        match (&self.gains_text, &self.gains_row) {
            (Some(text), None) => read_gains(text),
            (None, Some(row)) => {
                let Ok(k) = <[f64; 5]>::try_from(row.as_slice()) else {
                    return Err(Error::InvalidArgument {
                        what: "gains",
                        rule: format!(
                            "five gains (kDelta, kPhiDot, kPhi, kPsi, kY), got {}",
                            row.len()
                        ),
                    });
                };
                GainTable::new(vec![0.0], vec![HumanGains::from_array(k)])
            }
            _ => Err(Error::InvalidArgument {
                what: "gains",
                rule: "give a SteerGains file or five gains".into(),
            }),
        }
    }
}

/// HQM of `bicycle` at `speed`: a dict of `frequencies`, `magnitudes` (|HQM(jω)|),
/// `peak`, `peak_frequency`, `certified`, `stable`, `gains` (the five), `extrapolated`,
/// `numerator` and `denominator` (lowest power of s first).
#[pyfunction]
#[pyo3(signature = (bicycle, speed, frequencies, gains_text=None, gains_row=None, neuro_frequency=30.0, neuro_damping=0.707))]
#[allow(clippy::too_many_arguments)]
pub fn handling_quality_native<'py>(
    py: Python<'py>,
    bicycle: &NativeBicycle,
    speed: f64,
    frequencies: Vec<f64>,
    gains_text: Option<String>,
    gains_row: Option<Vec<f64>>,
    neuro_frequency: f64,
    neuro_damping: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let setup = Setup::new(
        bicycle,
        gains_text,
        gains_row,
        neuro_frequency,
        neuro_damping,
    );
    let (hqm, extrapolated, peak, magnitudes) = py
        .detach(|| -> whipple::Result<_> {
            let lookup = setup.table()?.at(speed)?;
            let hqm =
                HandlingQuality::new(&setup.bike, speed, &lookup.gains, &setup.neuromuscular)?;
            let peak = hqm.peak()?;
            let magnitudes = hqm.magnitude(&frequencies)?;
            let extrapolated = lookup.extrapolated && !setup.single_row();
            Ok((hqm, extrapolated, peak, magnitudes))
        })
        .py_err(py)?;
    let d = PyDict::new(py);
    d.set_item("speed", speed)?;
    d.set_item("frequencies", PyArray1::from_slice(py, &frequencies))?;
    d.set_item("magnitudes", PyArray1::from_vec(py, magnitudes))?;
    d.set_item("peak", peak.magnitude)?;
    d.set_item("peak_frequency", peak.frequency)?;
    d.set_item("certified", peak.certified)?;
    d.set_item("stable", hqm.is_stable())?;
    d.set_item("gains", hqm.gains().to_array().to_vec())?;
    d.set_item("extrapolated", extrapolated)?;
    d.set_item("numerator", PyArray1::from_slice(py, hqm.numerator()))?;
    d.set_item("denominator", PyArray1::from_slice(py, hqm.denominator()))?;
    Ok(d)
}

/// HQM's peak at each of `speeds`: a dict of numpy arrays `speeds`, `peaks`,
/// `peak_frequencies`, and of booleans `certified`, `stable`, `extrapolated`.
#[pyfunction]
#[pyo3(signature = (bicycle, speeds, gains_text=None, gains_row=None, neuro_frequency=30.0, neuro_damping=0.707))]
pub fn handling_against_speed_native<'py>(
    py: Python<'py>,
    bicycle: &NativeBicycle,
    speeds: Vec<f64>,
    gains_text: Option<String>,
    gains_row: Option<Vec<f64>>,
    neuro_frequency: f64,
    neuro_damping: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let setup = Setup::new(
        bicycle,
        gains_text,
        gains_row,
        neuro_frequency,
        neuro_damping,
    );
    if speeds.len() > MAX_HANDLING_POINTS {
        return Err(whipple::Error::LimitExceeded {
            what: "speeds",
            rule: format!("at most {MAX_HANDLING_POINTS}, got {}", speeds.len()),
        })
        .py_err(py);
    }
    let rows = py
        .detach(|| -> whipple::Result<_> {
            let table = setup.table()?;
            handling_against_speed(&setup.bike, &table, &setup.neuromuscular, &speeds)
        })
        .py_err(py)?;
    let d = PyDict::new(py);
    d.set_item("speeds", PyArray1::from_slice(py, &speeds))?;
    d.set_item(
        "peaks",
        PyArray1::from_vec(py, rows.iter().map(|r| r.peak.magnitude).collect()),
    )?;
    d.set_item(
        "peak_frequencies",
        PyArray1::from_vec(py, rows.iter().map(|r| r.peak.frequency).collect()),
    )?;
    d.set_item(
        "certified",
        rows.iter().map(|r| r.peak.certified).collect::<Vec<bool>>(),
    )?;
    d.set_item(
        "stable",
        rows.iter().map(|r| r.stable).collect::<Vec<bool>>(),
    )?;
    d.set_item(
        "extrapolated",
        rows.iter()
            .map(|r| r.extrapolated && !setup.single_row())
            .collect::<Vec<bool>>(),
    )?;
    Ok(d)
}

/// A candidate judged, as a dict: `values` (in the user's units, degrees for a `_deg` name),
/// `cost`, `stable`, `peak`, `peak_frequency`, `certified` (None when refused), `gains`
/// (None when refused), `refused` (the library's reason, or None).
fn candidate<'py>(
    py: Python<'py>,
    c: &whipple::advanced::control::HandlingCandidate,
    specs: &[whipple_front::design::BoundSpec],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let values: Vec<f64> = specs
        .iter()
        .zip(&c.values)
        .map(|(s, &x)| s.from_si(x))
        .collect();
    d.set_item("values", PyArray1::from_vec(py, values))?;
    d.set_item("cost", c.cost)?;
    d.set_item("stable", c.stable)?;
    d.set_item("peak", c.peak.map(|p| p.magnitude))?;
    d.set_item("peak_frequency", c.peak.map(|p| p.frequency))?;
    d.set_item("certified", c.peak.map(|p| p.certified))?;
    d.set_item("gains", c.gains.map(|g| g.to_array().to_vec()))?;
    d.set_item("refused", c.refused.clone())?;
    Ok(d)
}

/// BMD 2016's optimal-handling search (`whipple::advanced::control::optimal_handling`) over
/// `bounds` given as (name, low, high) in the user's units (`head_angle_deg` in degrees), with
/// the GIL released and Ctrl-C honoured: a dict of `names`, `units`, `base` and `best`
/// (candidates), `starts` (a list of dicts: `start`, `best`, `evaluations`, `converged`),
/// `evaluations` and the best `bicycle` (a NativeBicycle).
#[pyfunction]
#[pyo3(signature = (bicycle, speed, bounds, starts=6, iterations=2000, neuro_frequency=30.0, neuro_damping=0.707))]
#[allow(clippy::too_many_arguments)]
pub fn optimal_handling_native<'py>(
    py: Python<'py>,
    bicycle: &NativeBicycle,
    speed: f64,
    bounds: Vec<(String, f64, f64)>,
    starts: usize,
    iterations: usize,
    neuro_frequency: f64,
    neuro_damping: f64,
) -> PyResult<Bound<'py, PyDict>> {
    use whipple::advanced::control::{OptimalHandlingSettings, optimal_handling};
    use whipple_front::design::BoundSpec;
    let base = bicycle.bicycle.clone();
    let specs = bounds
        .iter()
        .map(|(name, low, high)| BoundSpec::parse(&format!("{name}={low}:{high}"), &base))
        .collect::<whipple::Result<Vec<BoundSpec>>>()
        .py_err(py)?;
    let settings = OptimalHandlingSettings {
        neuromuscular: neuromuscular(neuro_frequency, neuro_damping),
        starts,
        max_iterations: iterations,
        ..OptimalHandlingSettings::at(speed)
    };
    let limits: Vec<_> = specs.iter().map(|s| s.bound.clone()).collect();
    let result = crate::guard::interruptible(py, false, |stop| {
        optimal_handling(&base, &limits, &settings, stop)
    })?
    .py_err(py)?;
    let d = PyDict::new(py);
    d.set_item(
        "names",
        specs.iter().map(|s| s.name.clone()).collect::<Vec<_>>(),
    )?;
    d.set_item("units", specs.iter().map(|s| s.unit()).collect::<Vec<_>>())?;
    d.set_item("speed", speed)?;
    d.set_item("base", candidate(py, &result.base, &specs)?)?;
    d.set_item("best", candidate(py, &result.best, &specs)?)?;
    let mut runs = Vec::new();
    for s in &result.starts {
        let r = PyDict::new(py);
        let start: Vec<f64> = specs
            .iter()
            .zip(&s.start)
            .map(|(p, &x)| p.from_si(x))
            .collect();
        r.set_item("start", PyArray1::from_vec(py, start))?;
        r.set_item("best", candidate(py, &s.best, &specs)?)?;
        r.set_item("evaluations", s.evaluations)?;
        r.set_item("converged", s.converged)?;
        runs.push(r);
    }
    d.set_item("starts", runs)?;
    d.set_item("evaluations", result.evaluations())?;
    d.set_item(
        "bicycle",
        Bound::new(py, NativeBicycle::new(py, result.bicycle, false)?)?,
    )?;
    Ok(d)
}
