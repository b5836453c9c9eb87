//! The unstructured reference solve: every constraint row, the full block-diagonal M, and the
//! 45 × 45 saddle-point system by dense LU. Slow (allocates); it exists to check
//! [`Model::forward`], whose tree elimination and structured solve must give the same
//! accelerations and contact forces.

use nalgebra::{DMatrix, DVector, SVector, Vector3};

use super::Model;
use super::constraints::contact_destinations;
use super::forward::{Inputs, StateRates, coordinate_rates};
use super::poses::{Angles, Poses};
use super::state::{SPEEDS, State};
use super::topology::{BODIES, VELOCITY_ROWS};
use crate::error::{Error, Result};

impl Model {
    /// The unstructured reference: every constraint row, the full block-diagonal M, and the
    /// 45 × 45 saddle-point system `[M Dᵀ; D 0][u̇; −μ] = [f; γ]` solved by dense LU. Slow
    /// (allocates); used to check [`Model::forward`].
    pub fn forward_reference(
        &self,
        state: &State<f64>,
        inputs: &Inputs<f64>,
    ) -> Result<StateRates<f64>> {
        let angles = Angles::new(&state.q);
        let poses = Poses::from_angles(&state.q, &angles);
        let omega: [Vector3<f64>; BODIES] = std::array::from_fn(|k| state.angular_velocity(k));
        let applied = self.applied(&angles, &poses, &omega, inputs);
        let (d, gamma) = self.velocity_rows(state);
        let n = SPEEDS + VELOCITY_ROWS;
        let mut kkt = DMatrix::<f64>::zeros(n, n);
        let mut rhs = DVector::<f64>::zeros(n);
        for k in 0..BODIES {
            let body = &self.bodies.body[k];
            for i in 0..3 {
                kkt[(6 * k + i, 6 * k + i)] = body.mass;
            }
            kkt.view_mut((6 * k + 3, 6 * k + 3), (3, 3))
                .copy_from(&body.inertia);
            rhs.rows_mut(6 * k, 3).copy_from(&applied[k].0);
            rhs.rows_mut(6 * k + 3, 3).copy_from(&applied[k].1);
        }
        kkt.view_mut((SPEEDS, 0), (VELOCITY_ROWS, SPEEDS))
            .copy_from(&d);
        kkt.view_mut((0, SPEEDS), (SPEEDS, VELOCITY_ROWS))
            .copy_from(&d.transpose());
        rhs.rows_mut(SPEEDS, VELOCITY_ROWS).copy_from(&gamma);
        let x = kkt
            .lu()
            .solve(&rhs)
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .ok_or_else(|| Error::SingularDynamics {
                context: "the saddle-point matrix [M Dᵀ; D 0] is singular".into(),
            })?;
        let u_dot = SVector::<f64, SPEEDS>::from_iterator(x.rows(0, SPEEDS).iter().copied());
        let contact = std::array::from_fn(|i| {
            // The contact's three multipliers, in the contact's own row order.
            let mut nu = Vector3::zeros();
            for (src, dst) in contact_destinations(i) {
                nu[src] = x[SPEEDS + dst];
            }
            self.contact_force(i, &nu)
        });
        Ok(StateRates {
            q_dot: coordinate_rates(&angles, &state.u),
            u_dot,
            contact,
        })
    }
}
