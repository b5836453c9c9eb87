//! The state of the multibody bicycle: 24 coordinates `q` and 24 speeds `u`, six of each per
//! body, as in Dressel's JBike6 study.
//!
//! For body k (see [`super::bodies`] for the order R, B, H, F):
//! - `q[6k..6k+3]`: position of the body's origin in world axes \[m\];
//! - `q[6k+3]`, `q[6k+4]`, `q[6k+5]`: yaw, lean, pitch (z–x–y Euler angles, see
//!   [`super::rotation`]) \[rad\]; for a wheel the third angle is its rotation;
//! - `u[6k..6k+3]`: velocity of the origin in world axes [m/s];
//! - `u[6k+3..6k+6]`: angular velocity in body axes [rad/s].
//!
//! With these speeds the mass matrix is constant and block-diagonal, diag(m I₃, I_body) per body.

use crate::math::Real;
use nalgebra::{Matrix3, SVector, Vector3};

/// Number of coordinates (3 position + 3 angles per body).
pub(crate) const COORDINATES: usize = 24;
/// Number of speeds (3 translational + 3 angular per body).
pub(crate) const SPEEDS: usize = 24;
/// Length of the first-order state `[q; u]`.
pub const STATE_LEN: usize = COORDINATES + SPEEDS;

/// Offset of the yaw angle within a body's six coordinates.
pub(crate) const BODY_YAW: usize = 3;
/// Offset of the lean angle within a body's six coordinates.
pub(crate) const BODY_LEAN: usize = 4;
/// Offset of the pitch angle (wheel rotation for a wheel) within a body's six coordinates.
pub(crate) const BODY_PITCH: usize = 5;

/// Coordinates and speeds of the four bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State<T: Real> {
    /// q: positions and yaw–lean–pitch angles, six per body.
    pub q: SVector<T, COORDINATES>,
    /// u: world-axes velocities and body-axes angular velocities, six per body.
    pub u: SVector<T, SPEEDS>,
}

impl<T: Real> State<T> {
    /// The state from the first-order vector `[q; u]`.
    pub fn from_vector(y: &SVector<T, STATE_LEN>) -> Self {
        State {
            q: y.fixed_rows::<COORDINATES>(0).into_owned(),
            u: y.fixed_rows::<SPEEDS>(COORDINATES).into_owned(),
        }
    }

    /// The first-order vector `[q; u]`.
    pub fn to_vector(&self) -> SVector<T, STATE_LEN> {
        let mut y = SVector::<T, STATE_LEN>::zeros();
        y.fixed_rows_mut::<COORDINATES>(0).copy_from(&self.q);
        y.fixed_rows_mut::<SPEEDS>(COORDINATES).copy_from(&self.u);
        y
    }

    /// Position of body `k`'s origin, world axes \[m\].
    #[inline]
    pub fn position(&self, k: usize) -> Vector3<T> {
        self.q.fixed_rows::<3>(6 * k).into_owned()
    }

    /// (yaw, lean, pitch) of body `k` \[rad\].
    #[inline]
    pub fn angles(&self, k: usize) -> Vector3<T> {
        self.q.fixed_rows::<3>(6 * k + 3).into_owned()
    }

    /// Velocity of body `k`'s origin, world axes [m/s].
    #[inline]
    pub fn velocity(&self, k: usize) -> Vector3<T> {
        self.u.fixed_rows::<3>(6 * k).into_owned()
    }

    /// Angular velocity of body `k`, body axes [rad/s].
    #[inline]
    pub fn angular_velocity(&self, k: usize) -> Vector3<T> {
        self.u.fixed_rows::<3>(6 * k + 3).into_owned()
    }

    /// φ: lean of the rear frame, right positive \[rad\].
    pub fn lean(&self) -> T {
        self.q[6 * super::REAR_FRAME + BODY_LEAN]
    }

    /// ψ: yaw (heading) of the rear frame, right turn positive \[rad\].
    pub fn yaw(&self) -> T {
        self.q[6 * super::REAR_FRAME + BODY_YAW]
    }

    /// θ_B: pitch of the rear frame, nose up positive (a dependent coordinate) \[rad\].
    pub fn pitch(&self) -> T {
        self.q[6 * super::REAR_FRAME + BODY_PITCH]
    }

    /// (yaw rate, lean rate, pitch rate) of body `k` [rad/s].
    pub fn angle_rates(&self, k: usize) -> Vector3<T> {
        let a = self.angles(k);
        super::rotation::body_to_rates(a.y, a.z, &self.angular_velocity(k))
    }

    /// φ̇: lean rate of the rear frame [rad/s].
    pub fn lean_rate(&self) -> T {
        self.angle_rates(super::REAR_FRAME).y
    }

    /// ψ̇: yaw rate of the rear frame [rad/s].
    pub fn yaw_rate(&self) -> T {
        self.angle_rates(super::REAR_FRAME).x
    }

    /// True when every number is finite.
    pub fn is_finite(&self) -> bool
    where
        T: Into<f64>,
    {
        self.q
            .iter()
            .chain(self.u.iter())
            .all(|&x| x.into().is_finite())
    }
}

/// Named quantities of a state, as a rider or a controller sees them (benchmark sign
/// convention: lean right and steer right positive). Radians, metres, seconds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StateView {
    /// φ: lean of the rear frame \[rad\].
    pub lean: f64,
    /// δ: steer angle of the front frame relative to the rear frame about the steer axis \[rad\].
    pub steer: f64,
    /// ψ: yaw (heading) of the rear frame \[rad\].
    pub yaw: f64,
    /// θ_B: pitch of the rear frame \[rad\].
    pub pitch: f64,
    /// φ̇: lean rate [rad/s].
    pub lean_rate: f64,
    /// δ̇: steer rate [rad/s].
    pub steer_rate: f64,
    /// ψ̇: yaw rate [rad/s].
    pub yaw_rate: f64,
    /// v: forward speed, the rear hub's velocity along the rear frame's heading [m/s].
    pub speed: f64,
    /// x_P: rear contact point, x (forward at yaw 0) \[m\].
    pub rear_contact_x: f64,
    /// y_P: rear contact point, y \[m\].
    pub rear_contact_y: f64,
    /// Front contact point, x \[m\].
    pub front_contact_x: f64,
    /// Front contact point, y \[m\].
    pub front_contact_y: f64,
}

/// Where one rigid body is and how it is turned, world axes (x forward, y right, z down, the
/// benchmark's): what a drawing needs to place the body.
///
/// A point `p_body` given in the body's axes relative to its origin lies at
/// `position + rotation * p_body` in the world. Every origin is the body's centre of mass (the
/// hubs for the wheels), and the attachment points in body axes are in [`super::Model::bodies`]'s geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyPose {
    /// Position of the body's origin (its centre of mass), world axes \[m\].
    pub position: Vector3<f64>,
    /// Rotation matrix, body axes → world axes (orthonormal, determinant 1).
    pub rotation: Matrix3<f64>,
}
