//! The non-linear model's accelerations at a state given by its tree coordinates (the rear
//! frame's yaw, lean and pitch, the steer, the wheels' angles, the rear contact point) and tree
//! speeds (the rear hub's velocity, the Euler angle rates, the steer rate, the wheels' spin
//! rates): what a published table of the equations of motion at one state (Basu-Mandal et al.
//! 2007, Table 1) is checked against. Every number is the library's.

use nalgebra::Vector3;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use whipple::advanced::nonlinear::{Inputs, REAR_FRAME, REAR_WHEEL, State, rotation};
use whipple::{Error, Model};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;

fn finite(py: Python<'_>, what: &'static str, values: &[f64]) -> PyResult<()> {
    if let Some(x) = values.iter().find(|x| !x.is_finite()) {
        return Err(Error::InvalidArgument {
            what,
            rule: format!("must be finite, got {x}"),
        })
        .py_err(py);
    }
    Ok(())
}

#[pymethods]
impl NativeBicycle {
    /// The accelerations of the non-linear model at a state: `angles` (yaw, lean, pitch of the
    /// rear frame) and `steer` [rad], `wheel_angles` (rear, front, relative to their frames),
    /// `rear_contact` (x, y) [m]; `hub_velocity` (rear hub, world axes) [m/s], `angle_rates`
    /// (yaw, lean, pitch rates), `steer_rate`, `wheel_rates` (relative spin) [rad/s]. A dict:
    /// `hub_acceleration` (3,), `angle_accelerations` (3,), `steer_acceleration`,
    /// `wheel_accelerations` (2,), `hub_position` (3,), and the largest `holonomic_residual`
    /// and `velocity_residual` of the state (its constraints: zero for a consistent state).
    #[pyo3(signature = (angles, steer, wheel_angles, rear_contact, hub_velocity, angle_rates,
                        steer_rate, wheel_rates, lean_torque=0.0, steer_torque=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn accelerations<'py>(
        &self,
        py: Python<'py>,
        angles: [f64; 3],
        steer: f64,
        wheel_angles: [f64; 2],
        rear_contact: [f64; 2],
        hub_velocity: [f64; 3],
        angle_rates: [f64; 3],
        steer_rate: f64,
        wheel_rates: [f64; 2],
        lean_torque: f64,
        steer_torque: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        finite(py, "angles", &angles)?;
        finite(py, "steer", &[steer])?;
        finite(py, "wheel_angles", &wheel_angles)?;
        finite(py, "rear_contact", &rear_contact)?;
        finite(py, "hub_velocity", &hub_velocity)?;
        finite(py, "angle_rates", &angle_rates)?;
        finite(py, "steer_rate", &[steer_rate])?;
        finite(py, "wheel_rates", &wheel_rates)?;
        finite(py, "lean_torque", &[lean_torque])?;
        finite(py, "steer_torque", &[steer_torque])?;
        let model = self.model(py)?;
        let q = model.configuration(angles, steer, wheel_angles, rear_contact);
        let omega = rotation::rates_to_body(angles[1], angles[2]) * Vector3::from(angle_rates);
        let u = model.tree_speeds(
            &q,
            &Vector3::from(hub_velocity),
            &omega,
            steer_rate,
            wheel_rates,
        );
        let state = State { q, u };
        let residuals = model.residuals(&state);
        let d = model
            .forward(
                &state,
                &Inputs {
                    lean_torque,
                    steer_torque,
                },
            )
            .py_err(py)?;
        let a = d.u_dot.fixed_rows::<3>(6 * REAR_WHEEL).into_owned();
        let rate = |k: usize| Model::time_derivative(&state, &d, |s| s.angle_rates(REAR_FRAME)[k]);
        let steer_acc = Model::time_derivative(&state, &d, |s| model.steer_rate(s));
        let wheel = |k: usize| Model::time_derivative(&state, &d, |s| model.wheel_rates(s)[k]);
        let out = PyDict::new(py);
        out.set_item(
            "hub_acceleration",
            PyArray1::from_vec(py, vec![a.x, a.y, a.z]),
        )?;
        out.set_item(
            "angle_accelerations",
            PyArray1::from_vec(py, vec![rate(0), rate(1), rate(2)]),
        )?;
        out.set_item("steer_acceleration", steer_acc)?;
        out.set_item(
            "wheel_accelerations",
            PyArray1::from_vec(py, vec![wheel(0), wheel(1)]),
        )?;
        out.set_item(
            "hub_position",
            PyArray1::from_vec(py, vec![q[0], q[1], q[2]]),
        )?;
        out.set_item("holonomic_residual", residuals.max_holonomic())?;
        out.set_item("velocity_residual", residuals.max_velocity())?;
        Ok(out)
    }
}
