//! A knife-edge wheel on flat level ground: one holonomic row (the lowest point of the rim is
//! on the ground) and two non-holonomic rows (no slip, longitudinal and lateral).
//!
//! With the wheel's unit axle `a` (world), its hub `x_W` and radius r, the ground directions at
//! the contact are `f = (a × e_z)/|a × e_z|` (longitudinal, forward), `n = e_z × f` (lateral,
//! right) and `e_z` (down); the lowest rim point is `P = x_W + r d` with `d = f × a`.
//!
//! - holonomic: `z_W + r |a × e_z| = 0`;
//! - velocity rows: the contact point's material velocity `v_P = v_W + ω_W × r d` has no
//!   component along `f`, `n` (rolling) and `e_z` (the time derivative of the holonomic row).
//!
//! A wheel of zero radius (a skate, as in the two-mass-skate bicycle) has its contact at the hub
//! and glides freely along `f`: its longitudinal row is replaced by "the wheel does not spin
//! relative to its frame", `(ω_W − ω_frame) · a = 0`, which fixes the (meaningless, inertia-free)
//! spin of a wheel that has none; the longitudinal contact force of a skate is zero.

use crate::math::Real;
use nalgebra::{SMatrix, SVector, Vector3};

use super::poses::Poses;

/// Row of the longitudinal rolling row (a skate's spin lock) among a contact's three rows.
pub(crate) const LONGITUDINAL: usize = 0;
/// Row of the lateral rolling row.
pub(crate) const LATERAL: usize = 1;
/// Row of the normal row (the time derivative of the contact height).
pub(crate) const NORMAL: usize = 2;

/// The knife-edge contact of one wheel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct KnifeEdge {
    /// The wheel's body index.
    pub wheel: usize,
    /// The index of the frame that carries the wheel's axle.
    pub frame: usize,
    /// Wheel radius \[m\]; 0 for a skate.
    pub radius: f64,
}

/// Ground directions at a contact and the offset from hub to contact point, world axes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactFrame<T: Real> {
    /// f: longitudinal (rolling) direction, horizontal.
    pub longitudinal: Vector3<T>,
    /// n: lateral direction, horizontal, to the right of f.
    pub lateral: Vector3<T>,
    /// Hub → contact point, r d \[m\].
    pub offset: Vector3<T>,
}

/// Velocity rows `[longitudinal (or spin lock), lateral, normal]` of one contact.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactRows<T: Real> {
    /// Coefficients of the wheel's speeds (v world, ω body).
    pub wheel: SMatrix<T, 3, 6>,
    /// Coefficients of the frame's speeds (non-zero only in a skate's spin-lock row).
    pub frame: SMatrix<T, 3, 6>,
    /// γ = −Ḋu.
    pub gamma: SVector<T, 3>,
    /// The directions along which the multipliers act.
    pub contact_frame: ContactFrame<T>,
}

/// Directions, offset and rates at one contact, world axes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactKinematics<T: Real> {
    /// a: the wheel's axle, and ȧ.
    pub axle: Vector3<T>,
    pub axle_dot: Vector3<T>,
    /// The wheel's angular velocity.
    pub omega: Vector3<T>,
    /// f (longitudinal) and ḟ.
    pub f: Vector3<T>,
    pub f_dot: Vector3<T>,
    /// n (lateral) and ṅ.
    pub n: Vector3<T>,
    pub n_dot: Vector3<T>,
    /// Hub → contact point, and its rate.
    pub rho: Vector3<T>,
    pub rho_dot: Vector3<T>,
    /// Material velocity of the wheel at the contact point (zero when rolling).
    pub v_p: Vector3<T>,
}

impl KnifeEdge {
    /// True for a wheel of zero radius.
    pub(crate) fn is_skate(&self) -> bool {
        self.radius == 0.0
    }

    /// Ground directions and hub → contact offset for the wheel's current axle.
    pub(crate) fn contact_frame<T: Real>(&self, poses: &Poses<T>) -> ContactFrame<T> {
        let a = poses.rot[self.wheel].column(1).into_owned();
        let (f, _) = longitudinal(&a);
        let lateral = Vector3::new(-f.y, f.x, T::zero());
        let offset = f.cross(&a) * nalgebra::convert::<f64, T>(self.radius);
        ContactFrame {
            longitudinal: f,
            lateral,
            offset,
        }
    }

    /// The contact point (lowest point of the rim), world axes \[m\].
    pub(crate) fn point<T: Real>(&self, poses: &Poses<T>) -> Vector3<T> {
        poses.pos[self.wheel] + self.contact_frame(poses).offset
    }

    /// Holonomic residual: height of the lowest rim point above the ground, as z (down) \[m\].
    pub(crate) fn height<T: Real>(&self, poses: &Poses<T>) -> T {
        let a = poses.rot[self.wheel].column(1).into_owned();
        poses.pos[self.wheel].z + (a.x * a.x + a.y * a.y).sqrt() * nalgebra::convert(self.radius)
    }

    /// The contact's directions, offset and their rates from the wheel's velocity (world) and
    /// angular velocity (body axes).
    pub(crate) fn kinematics<T: Real>(
        &self,
        poses: &Poses<T>,
        v_wheel: &Vector3<T>,
        omega_wheel: &Vector3<T>,
    ) -> ContactKinematics<T> {
        let rw = &poses.rot[self.wheel];
        let a = rw.column(1).into_owned();
        let w = rw * omega_wheel;
        let a_dot = w.cross(&a);
        let (f, inverse) = longitudinal(&a);
        let ez = Vector3::z();
        // ṡ and ḟ of s = |a × e_z|, f = (a × e_z)/s.
        let s_dot = -a.z * a_dot.z * inverse;
        let f_dot = (a_dot.cross(&ez) - f * s_dot) * inverse;
        let n = Vector3::new(-f.y, f.x, T::zero());
        let n_dot = Vector3::new(-f_dot.y, f_dot.x, T::zero());
        let r: T = nalgebra::convert(self.radius);
        let rho = f.cross(&a) * r;
        let rho_dot = (f_dot.cross(&a) + f.cross(&a_dot)) * r;
        ContactKinematics {
            axle: a,
            axle_dot: a_dot,
            omega: w,
            f,
            f_dot,
            n,
            n_dot,
            rho,
            rho_dot,
            v_p: v_wheel + w.cross(&rho),
        }
    }

    /// Velocity rows and γ from the wheel's velocity (world) and angular velocity (body axes)
    /// and its frame's angular velocity (body axes).
    pub(crate) fn rows<T: Real>(
        &self,
        poses: &Poses<T>,
        v_wheel: &Vector3<T>,
        omega_wheel: &Vector3<T>,
        omega_frame: &Vector3<T>,
    ) -> ContactRows<T> {
        let rw = &poses.rot[self.wheel];
        let k = self.kinematics(poses, v_wheel, omega_wheel);
        let ez = Vector3::z();

        let mut wheel = SMatrix::<T, 3, 6>::zeros();
        let mut frame = SMatrix::<T, 3, 6>::zeros();
        let mut gamma = SVector::<T, 3>::zeros();
        let mut directions = [ez; 3];
        let mut rates = [Vector3::zeros(); 3];
        (directions[LONGITUDINAL], rates[LONGITUDINAL]) = (k.f, k.f_dot);
        (directions[LATERAL], rates[LATERAL]) = (k.n, k.n_dot);
        let spin_of_offset = k.omega.cross(&k.rho_dot);
        for row in 0..3 {
            let e = directions[row];
            wheel
                .fixed_view_mut::<1, 3>(row, 0)
                .copy_from(&e.transpose());
            let rot_row = (rw.transpose() * k.rho.cross(&e)).transpose();
            wheel.fixed_view_mut::<1, 3>(row, 3).copy_from(&rot_row);
            gamma[row] = -(rates[row].dot(&k.v_p) + e.dot(&spin_of_offset));
        }
        if self.is_skate() {
            let rf = &poses.rot[self.frame];
            let w_frame = rf * omega_frame;
            wheel
                .fixed_view_mut::<1, 3>(LONGITUDINAL, 0)
                .fill(T::zero());
            wheel
                .fixed_view_mut::<1, 3>(LONGITUDINAL, 3)
                .copy_from(&(rw.transpose() * k.axle).transpose());
            frame
                .fixed_view_mut::<1, 3>(LONGITUDINAL, 3)
                .copy_from(&(-(rf.transpose() * k.axle).transpose()));
            gamma[LONGITUDINAL] = -(k.omega - w_frame).dot(&k.axle_dot);
        }
        ContactRows {
            wheel,
            frame,
            gamma,
            contact_frame: ContactFrame {
                longitudinal: k.f,
                lateral: k.n,
                offset: k.rho,
            },
        }
    }
}

/// f = (a × e_z)/|a × e_z| and 1/|a × e_z| for a unit axle a that is not vertical (one
/// division).
#[inline]
fn longitudinal<T: Real>(a: &Vector3<T>) -> (Vector3<T>, T) {
    let inverse = T::one() / (a.x * a.x + a.y * a.y).sqrt();
    (
        Vector3::new(a.y * inverse, -a.x * inverse, T::zero()),
        inverse,
    )
}
