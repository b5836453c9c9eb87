//! The non-linear bicycle simulated from Python. The request is the front ends'
//! `whipple_front::simulation::SimulationRequest` (one set of rules for every front end); a torque may also be a Python
//! callable `f(t, state) -> float`, called with the GIL taken only around the call.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::Error;
use whipple::advanced::nonlinear::{BODY_NAMES, Sample, StateView, TorqueFn};
use whipple::advanced::turns::{Held, TurnSettings, held_turn};
use whipple::{Model, simulate};
use whipple_front::simulation::{IntegratorKind, SimulationRequest, TorqueInput};
use whipple_front::units::degrees;

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;

/// A torque argument: None, a number, an expression, or a callable.
enum Torque {
    Input(TorqueInput),
    Callable(Py<PyAny>),
}

fn torque(
    py: Python<'_>,
    value: Option<&Bound<'_, PyAny>>,
    field: &'static str,
) -> PyResult<Torque> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(Torque::Input(TorqueInput::default()));
    };
    if let Ok(text) = value.extract::<String>() {
        return Ok(Torque::Input(TorqueInput::Expression(text)));
    }
    if value.is_callable() {
        return Ok(Torque::Callable(value.clone().unbind()));
    }
    match value.extract::<f64>() {
        Ok(x) => Ok(Torque::Input(TorqueInput::Constant(x))),
        Err(_) => Err(Error::InvalidArgument {
            what: field,
            rule: format!(
                "must be a number, an expression string or a callable f(t, state) -> float, got {}",
                value
                    .get_type()
                    .name()
                    .map_or_else(|_| "?".to_string(), |n| n.to_string())
            ),
        })
        .py_err(py),
    }
}

/// What a callable sees: the state's named quantities (radians, m/s, metres).
fn state_dict<'py>(py: Python<'py>, s: &StateView) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("lean", s.lean)?;
    d.set_item("steer", s.steer)?;
    d.set_item("yaw", s.yaw)?;
    d.set_item("pitch", s.pitch)?;
    d.set_item("lean_rate", s.lean_rate)?;
    d.set_item("steer_rate", s.steer_rate)?;
    d.set_item("yaw_rate", s.yaw_rate)?;
    d.set_item("speed", s.speed)?;
    d.set_item("x", s.rear_contact_x)?;
    d.set_item("y", s.rear_contact_y)?;
    d.set_item("front_x", s.front_contact_x)?;
    d.set_item("front_y", s.front_contact_y)?;
    Ok(d)
}

/// The first Python error raised inside a run, and the flag that stops the run at once.
#[derive(Clone)]
struct Failure {
    error: Arc<Mutex<Option<PyErr>>>,
    stop: Arc<AtomicBool>,
}

impl Failure {
    fn record(&self, error: PyErr) {
        if let Ok(mut slot) = self.error.lock() {
            if slot.is_none() {
                *slot = Some(error);
            }
        }
        self.stop.store(true, Ordering::SeqCst);
    }

    fn take(&self) -> Option<PyErr> {
        self.error.lock().ok().and_then(|mut slot| slot.take())
    }
}

fn callable_torque(f: Py<PyAny>, field: &'static str, failure: Failure) -> TorqueFn {
    Box::new(move |t: f64, s: &StateView| {
        if failure.stop.load(Ordering::Relaxed) {
            return 0.0;
        }
        Python::attach(|py| {
            let result = state_dict(py, s)
                .and_then(|state| f.call1(py, (t, state)))
                .and_then(|value| value.extract::<f64>(py));
            match result {
                Ok(x) if x.is_finite() => x,
                Ok(x) => {
                    failure.record(crate::errors::to_py(
                        py,
                        Error::InvalidArgument {
                            what: field,
                            rule: format!(
                                "the callable returned {x} at t = {t} s (a torque must be finite)"
                            ),
                        },
                    ));
                    0.0
                }
                Err(e) => {
                    failure.record(e);
                    0.0
                }
            }
        })
    })
}

#[pymethods]
impl NativeBicycle {
    /// Simulates the non-linear bicycle. Angles in radians (the fall angle in degrees, as its
    /// name says). Returns a dict: `columns` (name → array), `csv_columns`, `outcome` (words),
    /// `outcome_kind`, `outcome_t`, `failed`, `caption`, `steps`, `rejected_steps`,
    /// `pulled_down_from_start`, `body_names`, `positions` (n, 4, 3), `rotations` (n, 4, 3, 3).
    #[pyo3(signature = (speed, duration, lean=0.0, steer=0.0, lean_rate=0.0, steer_rate=0.0,
                        integrator="rk4", dt=None, rtol=None, steer_torque=None, lean_torque=None,
                        fall_angle_deg=60.0, stop_on_lift_off=true, max_steps=None, every=1,
                        poses=false, from_turn=false))]
    #[allow(clippy::too_many_arguments)]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        speed: f64,
        duration: f64,
        lean: f64,
        steer: f64,
        lean_rate: f64,
        steer_rate: f64,
        integrator: &str,
        dt: Option<f64>,
        rtol: Option<f64>,
        steer_torque: Option<&Bound<'py, PyAny>>,
        lean_torque: Option<&Bound<'py, PyAny>>,
        fall_angle_deg: f64,
        stop_on_lift_off: bool,
        max_steps: Option<usize>,
        every: usize,
        poses: bool,
        from_turn: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let integrator = match integrator {
            "rk4" => IntegratorKind::Rk4,
            "adaptive" => IntegratorKind::Adaptive,
            other => {
                return Err(Error::InvalidArgument {
                    what: "integrator",
                    rule: format!("must be 'rk4' or 'adaptive', got {other:?}"),
                })
                .py_err(py);
            }
        };
        let steer_torque_given = steer_torque.is_some_and(|v| !v.is_none());
        let steer_torque = torque(py, steer_torque, "steer_torque")?;
        let lean_torque = torque(py, lean_torque, "lean_torque")?;
        let input = |t: &Torque| match t {
            Torque::Input(i) => i.clone(),
            Torque::Callable(_) => TorqueInput::default(),
        };
        let model = Model::new(&self.checked.benchmark).py_err(py)?;
        // `from_turn`: start on the held steady turn at this speed (the rear contact's) and
        // lean, as `whipple simulate --from-turn` does: the turn's hub speed, steer and (unless
        // one is given) its steer torque.
        let turn = if from_turn {
            if steer != 0.0 {
                return Err(Error::InvalidArgument {
                    what: "steer",
                    rule: format!(
                        "comes from the steady turn with from_turn=True, got steer = {steer} rad"
                    ),
                })
                .py_err(py);
            }
            let settings = TurnSettings::default();
            Some(
                py.detach(|| held_turn(&model, speed, Held::Lean(lean), &settings))
                    .py_err(py)?,
            )
        } else {
            None
        };
        let mut request = SimulationRequest {
            speed,
            lean_deg: degrees(lean),
            steer_deg: degrees(steer),
            lean_rate,
            steer_rate,
            duration,
            integrator,
            dt,
            rtol,
            steer_torque: input(&steer_torque),
            lean_torque: input(&lean_torque),
            fall_angle_deg,
            stop_on_lift_off,
            max_steps,
            host_max_steps: None,
            sample_every: every,
        };
        if let Some(turn) = &turn {
            request.speed = turn.hub_speed;
            request.lean_deg = degrees(turn.lean);
            request.steer_deg = degrees(turn.steer);
            if !steer_torque_given {
                request.steer_torque = TorqueInput::Constant(turn.steer_torque);
            }
        }
        let (initial, mut settings) = request
            .validate()
            .map_err(|e| match e {
                // The request takes degrees; Python takes radians: name the Python argument.
                Error::InvalidArgument {
                    what: "sample_every",
                    rule,
                } => Error::InvalidArgument {
                    what: "every",
                    rule,
                },
                Error::LimitExceeded {
                    what: "sample_every",
                    rule,
                } => Error::LimitExceeded {
                    what: "every",
                    rule,
                },
                Error::InvalidArgument {
                    what: "lean_deg",
                    rule,
                } => Error::InvalidArgument {
                    what: "lean",
                    rule: format!("{rule} (lean = {lean} rad)"),
                },
                Error::InvalidArgument {
                    what: "steer_deg",
                    rule,
                } => Error::InvalidArgument {
                    what: "steer",
                    rule: format!("{rule} (steer = {steer} rad)"),
                },
                other => other,
            })
            .py_err(py)?;
        let failure = Failure {
            error: Arc::new(Mutex::new(None)),
            stop: Arc::new(AtomicBool::new(false)),
        };
        if let Torque::Callable(f) = steer_torque {
            settings.steer_torque = Some(callable_torque(f, "steer_torque", failure.clone()));
        }
        if let Torque::Callable(f) = lean_torque {
            settings.lean_torque = Some(callable_torque(f, "lean_torque", failure.clone()));
        }
        settings.stop = Some(failure.stop.clone());
        // Ctrl-C in a notebook or a terminal: checked every 256 steps.
        let steps = AtomicUsize::new(0);
        let signals = failure.clone();
        settings.progress = Some(Box::new(move |_| {
            if steps.fetch_add(1, Ordering::Relaxed) % 256 == 255 {
                Python::attach(|py| {
                    if let Err(e) = py.check_signals() {
                        signals.record(e);
                    }
                });
            }
        }));
        let start = model.initial_state(&initial).py_err(py)?;
        let run = py
            .detach(|| simulate(&model, start, &settings))
            .py_err(py)?;
        if let Some(error) = failure.take() {
            return Err(error);
        }

        let samples: Vec<&Sample> = run.samples.iter().filter(|s| s.is_finite()).collect();
        let n = samples.len();
        let d = PyDict::new(py);
        let columns = PyDict::new(py);
        for (k, name) in Sample::COLUMNS.iter().enumerate() {
            let column: Vec<f64> = samples.iter().map(|s| s.values()[k]).collect();
            columns.set_item(*name, PyArray1::from_vec(py, column))?;
        }
        d.set_item("columns", columns)?;
        d.set_item(
            "csv_columns",
            Sample::COLUMNS[..Sample::CSV_COLUMNS].to_vec(),
        )?;
        d.set_item("outcome", run.outcome.to_string())?;
        d.set_item("outcome_kind", run.outcome.kind())?;
        d.set_item("outcome_t", run.outcome.t())?;
        d.set_item("failed", run.outcome.is_failure())?;
        d.set_item("caption", run.caption())?;
        d.set_item("steps", run.steps)?;
        d.set_item("rejected_steps", run.rejected_steps)?;
        d.set_item(
            "pulled_down_from_start",
            run.pulled_down_from_start
                .iter()
                .map(|w| w.name())
                .collect::<Vec<_>>(),
        )?;
        d.set_item("body_names", BODY_NAMES.to_vec())?;
        if poses {
            let bodies = BODY_NAMES.len();
            let mut positions: Vec<f64> = Vec::with_capacity(n * bodies * 3);
            let mut rotations: Vec<f64> = Vec::with_capacity(n * bodies * 9);
            for s in &samples {
                for pose in model.sample_poses(s) {
                    positions.extend(pose.position.iter());
                    for i in 0..3 {
                        for j in 0..3 {
                            rotations.push(pose.rotation[(i, j)]);
                        }
                    }
                }
            }
            d.set_item(
                "positions",
                PyArray1::from_vec(py, positions).reshape([n, bodies, 3])?,
            )?;
            d.set_item(
                "rotations",
                PyArray1::from_vec(py, rotations).reshape([n, bodies, 3, 3])?,
            )?;
        }
        Ok(d)
    }
}
