//! The constraint rows themselves, row by row in the layout of [`super::topology`]: the 17
//! holonomic residuals, the 21 velocity rows `D` (the holonomic ones differentiated, then the
//! rolling rows) with `γ = −Ḋu`, their residuals `D u`, and the holonomic Jacobian `∂r/∂q`.
//!
//! The forward dynamics never assembles these: it eliminates the joint rows by the tree map.
//! They serve the checks (residuals of a state, the dense reference solve) and the study's
//! least-norm position projection.

use crate::math::Real;
use nalgebra::{SMatrix, SVector};

use super::Model;
use super::contact::{LATERAL, LONGITUDINAL, NORMAL};
use super::poses::Poses;
use super::rotation;
use super::state::{COORDINATES, SPEEDS, State};
use super::topology::{
    BODIES, HOLONOMIC_ROWS, JOINT_ROWS, VELOCITY_ROWS, height_row, joint_row, lateral_row,
    longitudinal_row,
};

/// Constraint residuals of a state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residuals {
    /// The 17 holonomic residuals (joint gaps \[m\], axis misalignments [-], contact heights \[m\]).
    pub holonomic: SVector<f64, HOLONOMIC_ROWS>,
    /// The 21 velocity rows D u: 17 differentiated holonomic rows then 4 rolling rows [m/s].
    pub velocity: SVector<f64, VELOCITY_ROWS>,
}

impl Residuals {
    /// Largest absolute holonomic residual.
    pub fn max_holonomic(&self) -> f64 {
        self.holonomic.amax()
    }
    /// Largest absolute non-holonomic (rolling) residual.
    pub fn max_nonholonomic(&self) -> f64 {
        self.velocity
            .rows(HOLONOMIC_ROWS, VELOCITY_ROWS - HOLONOMIC_ROWS)
            .amax()
    }
    /// Largest absolute velocity-row residual.
    pub fn max_velocity(&self) -> f64 {
        self.velocity.amax()
    }
}

/// A contact's three rows (see [`super::contact::ContactRows`]) and where each lands among
/// the velocity rows.
pub(crate) fn contact_destinations(contact: usize) -> [(usize, usize); 3] {
    [
        (NORMAL, height_row(contact)),
        (LONGITUDINAL, longitudinal_row(contact)),
        (LATERAL, lateral_row(contact)),
    ]
}

impl Model {
    /// The 17 holonomic residuals: rear hub, steer and front hub joints (5 each: gap x, y, z,
    /// two axis misalignments), then rear and front contact heights.
    pub fn holonomic_residual<T: Real>(
        &self,
        q: &SVector<T, COORDINATES>,
    ) -> SVector<T, HOLONOMIC_ROWS> {
        self.holonomic_residual_at(&Poses::new(q))
    }

    /// [`Model::holonomic_residual`] from the poses.
    pub(crate) fn holonomic_residual_at<T: Real>(
        &self,
        poses: &Poses<T>,
    ) -> SVector<T, HOLONOMIC_ROWS> {
        let mut r = SVector::<T, HOLONOMIC_ROWS>::zeros();
        for (i, joint) in self.joints.iter().enumerate() {
            r.fixed_rows_mut::<JOINT_ROWS>(joint_row(i))
                .copy_from(&joint.residual(poses));
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            r[height_row(i)] = contact.height(poses);
        }
        r
    }

    /// Holonomic residuals and velocity-row residuals D u of a state.
    pub fn residuals(&self, state: &State<f64>) -> Residuals {
        let poses = Poses::new(&state.q);
        Residuals {
            holonomic: self.holonomic_residual_at(&poses),
            velocity: self.velocity_residual_at(&poses, state),
        }
    }

    /// All 21 velocity rows `D` (17 differentiated holonomic rows, then 4 rolling rows) and
    /// `γ = −Ḋu`, at the state's own speeds.
    ///
    /// Row order: rear hub joint (5), steer joint (5), front hub joint (5), rear normal, front
    /// normal, rear longitudinal (spin lock for a skate), rear lateral, front longitudinal,
    /// front lateral.
    pub fn velocity_rows<T: Real>(
        &self,
        state: &State<T>,
    ) -> (SMatrix<T, VELOCITY_ROWS, SPEEDS>, SVector<T, VELOCITY_ROWS>) {
        self.velocity_rows_at(&Poses::new(&state.q), state)
    }

    /// The velocity residuals `D u` row by row from the rows' non-zero blocks, with the poses
    /// of `state.q` already known (no 21 × 24 matrix).
    pub(crate) fn velocity_residual_at(
        &self,
        poses: &Poses<f64>,
        state: &State<f64>,
    ) -> SVector<f64, VELOCITY_ROWS> {
        let mut r = SVector::<f64, VELOCITY_ROWS>::zeros();
        let speeds = |k: usize| state.u.fixed_rows::<6>(6 * k);
        for (i, joint) in self.joints.iter().enumerate() {
            let rows = joint.rows(
                poses,
                &state.angular_velocity(joint.parent),
                &state.angular_velocity(joint.child),
            );
            r.fixed_rows_mut::<JOINT_ROWS>(joint_row(i)).copy_from(
                &(rows.parent * speeds(joint.parent) + rows.child * speeds(joint.child)),
            );
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            let rows = contact.rows(
                poses,
                &state.velocity(contact.wheel),
                &state.angular_velocity(contact.wheel),
                &state.angular_velocity(contact.frame),
            );
            let du = rows.wheel * speeds(contact.wheel) + rows.frame * speeds(contact.frame);
            for (src, dst) in contact_destinations(i) {
                r[dst] = du[src];
            }
        }
        r
    }

    /// [`Model::velocity_rows`] with the poses of `state.q` already known.
    pub(crate) fn velocity_rows_at<T: Real>(
        &self,
        poses: &Poses<T>,
        state: &State<T>,
    ) -> (SMatrix<T, VELOCITY_ROWS, SPEEDS>, SVector<T, VELOCITY_ROWS>) {
        let mut d = SMatrix::<T, VELOCITY_ROWS, SPEEDS>::zeros();
        let mut gamma = SVector::<T, VELOCITY_ROWS>::zeros();
        for (i, joint) in self.joints.iter().enumerate() {
            let rows = joint.rows(
                poses,
                &state.angular_velocity(joint.parent),
                &state.angular_velocity(joint.child),
            );
            d.fixed_view_mut::<JOINT_ROWS, 6>(joint_row(i), 6 * joint.parent)
                .copy_from(&rows.parent);
            d.fixed_view_mut::<JOINT_ROWS, 6>(joint_row(i), 6 * joint.child)
                .copy_from(&rows.child);
            gamma
                .fixed_rows_mut::<JOINT_ROWS>(joint_row(i))
                .copy_from(&rows.gamma);
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            let rows = contact.rows(
                poses,
                &state.velocity(contact.wheel),
                &state.angular_velocity(contact.wheel),
                &state.angular_velocity(contact.frame),
            );
            for (src, dst) in contact_destinations(i) {
                let mut wheel_cols = d.fixed_view_mut::<1, 6>(dst, 6 * contact.wheel);
                wheel_cols += rows.wheel.fixed_rows::<1>(src);
                let mut frame_cols = d.fixed_view_mut::<1, 6>(dst, 6 * contact.frame);
                frame_cols += rows.frame.fixed_rows::<1>(src);
                gamma[dst] = rows.gamma[src];
            }
        }
        (d, gamma)
    }

    /// ∂r/∂q of the 17 holonomic residuals: the holonomic velocity rows times the map from
    /// angle rates to body angular velocities.
    pub(crate) fn holonomic_jacobian(
        &self,
        q: &SVector<f64, COORDINATES>,
    ) -> SMatrix<f64, HOLONOMIC_ROWS, COORDINATES> {
        let state = State {
            q: *q,
            u: SVector::zeros(),
        };
        let (d, _) = self.velocity_rows(&state);
        let mut j = d.fixed_rows::<HOLONOMIC_ROWS>(0).into_owned();
        for k in 0..BODIES {
            let w = rotation::rates_to_body(q[6 * k + 4], q[6 * k + 5]);
            let cols = j.fixed_columns::<3>(6 * k + 3) * w;
            j.fixed_columns_mut::<3>(6 * k + 3).copy_from(&cols);
        }
        j
    }
}
