//! Steady turns of the non-linear bicycle from Python: the library's
//! `analysis::turns` (held turns, their stability, the hands-free families and the branch from
//! straight running): a turn and its stability as the core's own structs serialized (the
//! server's keys), the families' points as numpy arrays. Nothing is solved here.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use whipple::advanced::turns::{
    Family, FamilyPoint, FamilySettings, Held, Stability, SteadyTurn, TurnSettings,
    branch_from_straight, hands_free_families, hands_free_turn_near, hands_free_turns_at_speed,
    held_turn, stability,
};
use whipple::{Error, Model};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::serialized;

/// One turn and its stability (or why it could not be decided): the core's `FamilyPoint` as a
/// dict, `turn`, `stability` (or None) and `stability_error` (or None), the keys of the
/// server's `/api/turn`.
fn turn_dict<'py>(
    py: Python<'py>,
    turn: &SteadyTurn,
    stab: &Result<Stability, String>,
) -> PyResult<Bound<'py, PyAny>> {
    let point = FamilyPoint {
        turn: *turn,
        stability: stab.as_ref().ok().cloned(),
        stability_error: stab.as_ref().err().cloned(),
    };
    serialized(py, &point)
}

/// A family's points up to `max_speed` (the tracing stops one step beyond it; the command line
/// shows the points in its range, so does this) as a dict of arrays.
fn family_dict<'py>(
    py: Python<'py>,
    family: &Family,
    max_speed: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let points: Vec<&FamilyPoint> = family
        .points
        .iter()
        .filter(|p| p.turn.speed >= 0.0 && p.turn.speed <= max_speed)
        .collect();
    let column = |f: &dyn Fn(&SteadyTurn) -> f64| -> Vec<f64> {
        points.iter().map(|p| f(&p.turn)).collect()
    };
    let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
    d.set_item("speed", PyArray1::from_vec(py, column(&|t| t.speed)))?;
    d.set_item(
        "hub_speed",
        PyArray1::from_vec(py, column(&|t| t.hub_speed)),
    )?;
    d.set_item("lean", PyArray1::from_vec(py, column(&|t| t.lean)))?;
    d.set_item("steer", PyArray1::from_vec(py, column(&|t| t.steer)))?;
    d.set_item("pitch", PyArray1::from_vec(py, column(&|t| t.pitch)))?;
    d.set_item("yaw_rate", PyArray1::from_vec(py, column(&|t| t.yaw_rate)))?;
    d.set_item(
        "radius",
        PyArray1::from_vec(py, column(&|t| nan(t.rear_radius))),
    )?;
    d.set_item(
        "front_radius",
        PyArray1::from_vec(py, column(&|t| nan(t.front_radius))),
    )?;
    d.set_item(
        "lateral_acceleration",
        PyArray1::from_vec(py, column(&|t| t.lateral_acceleration)),
    )?;
    let stable: Vec<bool> = points
        .iter()
        .map(|p| p.stability.as_ref().is_some_and(|s| s.stable))
        .collect();
    let decided: Vec<bool> = points.iter().map(|p| p.stability.is_some()).collect();
    let max_real: Vec<f64> = points
        .iter()
        .map(|p| p.stability.as_ref().map_or(f64::NAN, |s| s.max_real))
        .collect();
    d.set_item("stable", PyArray1::from_vec(py, stable))?;
    d.set_item("decided", PyArray1::from_vec(py, decided))?;
    d.set_item("max_real", PyArray1::from_vec(py, max_real))?;
    d.set_item("end", serialized(py, &family.end)?)?;
    Ok(d)
}

impl NativeBicycle {
    pub(crate) fn model(&self, py: Python<'_>) -> PyResult<Model> {
        Model::new(&self.checked.benchmark).py_err(py)
    }
}

#[pymethods]
impl NativeBicycle {
    /// The held steady turn at `speed` (the rear contact's, m/s) with exactly one of `lean`,
    /// `steer` [rad] or `radius` [m, right positive] given, and its stability: a dict.
    #[pyo3(signature = (speed, lean=None, steer=None, radius=None))]
    fn held_turn<'py>(
        &self,
        py: Python<'py>,
        speed: f64,
        lean: Option<f64>,
        steer: Option<f64>,
        radius: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let given = match (lean, steer, radius) {
            (Some(l), None, None) => Held::Lean(l),
            (None, Some(s), None) => Held::Steer(s),
            (None, None, Some(r)) => Held::Radius(r),
            _ => {
                return Err(Error::InvalidArgument {
                    what: "lean",
                    rule: "give exactly one of lean, steer, radius (or hands_free=True)".into(),
                })
                .py_err(py);
            }
        };
        let model = self.model(py)?;
        let (turn, stab) = py
            .detach(|| {
                let turn = held_turn(&model, speed, given, &TurnSettings::default())?;
                let stab = stability(&model, &turn).map_err(|e| e.to_string());
                Ok::<_, Error>((turn, stab))
            })
            .py_err(py)?;
        turn_dict(py, &turn, &stab)
    }

    /// Every hands-free turn at `speed` on the traced families (right leans, then their mirror
    /// images solved again), each with its stability: a list of dicts.
    fn hands_free_turns<'py>(&self, py: Python<'py>, speed: f64) -> PyResult<Bound<'py, PyList>> {
        let model = self.model(py)?;
        let settings = TurnSettings::default();
        let found = py
            .detach(|| {
                let families = hands_free_families(&model, &FamilySettings::default())?;
                let mut found = hands_free_turns_at_speed(&model, speed, &families, &settings)?;
                let mirrored = found
                    .iter()
                    .filter(|t| t.lean != 0.0)
                    .map(|t| {
                        hands_free_turn_near(&model, [-t.lean, -t.steer, t.speed], 2, &settings)
                    })
                    .collect::<Result<Vec<_>, Error>>()?;
                found.extend(mirrored);
                Ok::<_, Error>(
                    found
                        .into_iter()
                        .map(|t| {
                            let s = stability(&model, &t).map_err(|e| e.to_string());
                            (t, s)
                        })
                        .collect::<Vec<_>>(),
                )
            })
            .py_err(py)?;
        let list = PyList::empty(py);
        for (t, s) in &found {
            list.append(turn_dict(py, t, s)?)?;
        }
        Ok(list)
    }

    /// The families of hands-free turns leaning right, traced up to `max_speed` (m/s), and where
    /// they branch from straight running: a dict with `families` (list of dicts of arrays) and
    /// `branch` (speed, steer_per_lean, iterations, or None).
    #[pyo3(signature = (max_speed=20.0))]
    fn turn_families<'py>(&self, py: Python<'py>, max_speed: f64) -> PyResult<Bound<'py, PyDict>> {
        if !(max_speed.is_finite() && max_speed > 0.0) {
            return Err(Error::InvalidArgument {
                what: "max_speed",
                rule: format!("must be a positive finite speed in m/s, got {max_speed}"),
            })
            .py_err(py);
        }
        let model = self.model(py)?;
        let settings = FamilySettings {
            max_speed,
            ..FamilySettings::default()
        };
        let (families, branch) = py
            .detach(|| {
                let families = hands_free_families(&model, &settings)?;
                let branch = branch_from_straight(&model, &settings.turn)?;
                Ok::<_, Error>((families, branch))
            })
            .py_err(py)?;
        let d = PyDict::new(py);
        let list = PyList::empty(py);
        for f in &families {
            list.append(family_dict(py, f, max_speed)?)?;
        }
        d.set_item("families", list)?;
        d.set_item("branch", serialized(py, &branch)?)?;
        d.set_item("max_speed", max_speed)?;
        Ok(d)
    }
}
