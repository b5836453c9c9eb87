//! Configurations that satisfy the constraints, built along the joint tree: from the rear
//! frame's yaw, lean and pitch, the steer angle, the wheel rotations and the rear contact point,
//! the position chain rear contact → rear hub → rear frame → steer axis → front frame → front
//! hub places every body with the joints and the rear contact holding exactly; the rear frame's
//! pitch that also puts the front wheel on the ground comes from Newton iteration.

use crate::math::Real;
use nalgebra::{Matrix3, SVector, Vector3};
use num_dual::Dual64;

use super::Model;
use super::outcome::Sample;
use super::rotation;
use super::state::COORDINATES;
use super::topology::{
    FRONT_CONTACT, FRONT_FRAME, FRONT_HUB, FRONT_WHEEL, REAR_CONTACT, REAR_FRAME, REAR_HUB,
    REAR_WHEEL, STEER_JOINT,
};
use crate::error::{Error, Result};

/// Poses of the two frames and the two hubs (world axes).
struct FramePoses<T: Real> {
    x_b: Vector3<T>,
    rh: Matrix3<T>,
    x_h: Vector3<T>,
    hub_r: Vector3<T>,
    hub_f: Vector3<T>,
}

/// Newton iterations allowed when solving the pitch of a new state.
const PITCH_ITERATIONS: usize = 50;

impl Model {
    /// The 24 coordinates of a recorded [`Sample`]: its lean, steer, yaw, pitch, wheel angles
    /// and rear contact point determine the configuration (the constraints holding exactly), as
    /// they did the state it was recorded from (to the projection's tolerance).
    pub fn sample_coordinates(&self, sample: &Sample) -> SVector<f64, COORDINATES> {
        self.configuration(
            [sample.yaw, sample.lean, sample.pitch],
            sample.steer,
            [sample.rear_wheel_angle, sample.front_wheel_angle],
            [sample.x, sample.y],
        )
    }

    /// Rotation matrices and origins of the rear and front frames, and the rear and front hub
    /// positions, for a configuration given by the rear frame's yaw, lean and pitch, the steer
    /// angle and the rear contact point; joints and rear contact hold exactly.
    fn frames<T: Real>(&self, angles: [T; 3], steer: T, rear_contact: [T; 2]) -> FramePoses<T> {
        let [rear_hub, steer_joint, front_hub] = [
            &self.joints[REAR_HUB],
            &self.joints[STEER_JOINT],
            &self.joints[FRONT_HUB],
        ];
        let [yaw, lean, pitch] = angles;
        let rb = rotation::matrix(yaw, lean, pitch);
        let a = rb.column(1).into_owned();
        let s_len = (a.x * a.x + a.y * a.y).sqrt();
        let f = Vector3::new(a.y / s_len, -a.x / s_len, T::zero());
        let down = f.cross(&a);
        let r_r: T = nalgebra::convert(self.contacts[REAR_CONTACT].radius);
        let hub_r = Vector3::new(rear_contact[0], rear_contact[1], T::zero()) - down * r_r;
        let x_b = hub_r - rb * rear_hub.point_in_parent.cast::<T>();
        let s: Vector3<T> = steer_joint.axis_in_child.cast();
        let rh = rb * rotation::axis_angle(&s, steer);
        let x_h = x_b + rb * steer_joint.point_in_parent.cast::<T>()
            - rh * steer_joint.point_in_child.cast::<T>();
        let x_f = x_h + rh * front_hub.point_in_parent.cast::<T>();
        FramePoses {
            x_b,
            rh,
            x_h,
            hub_r,
            hub_f: x_f,
        }
    }

    /// Height (z, down) of the front wheel's lowest rim point in the configuration of
    /// [`Model::configuration`]; zero when the front wheel touches the ground.
    pub(crate) fn front_height<T: Real>(
        &self,
        angles: [T; 3],
        steer: T,
        rear_contact: [T; 2],
    ) -> T {
        let p = self.frames(angles, steer, rear_contact);
        let a = p.rh.column(1);
        let r_f: T = nalgebra::convert(self.contacts[FRONT_CONTACT].radius);
        p.hub_f.z + (a.x * a.x + a.y * a.y).sqrt() * r_f
    }

    /// The 24 coordinates of a configuration that satisfies the 15 joint constraints and the
    /// rear contact exactly, from the rear frame's yaw, lean and pitch, the steer angle, the
    /// wheels' rotations relative to their frames and the rear contact point. (The front
    /// contact height is satisfied only at the right pitch: see [`Model::initial_state`].)
    pub fn configuration<T: Real>(
        &self,
        angles: [T; 3],
        steer: T,
        wheel_angles: [T; 2],
        rear_contact: [T; 2],
    ) -> SVector<T, COORDINATES> {
        let [yaw, lean, pitch] = angles;
        let FramePoses {
            rh,
            x_b,
            x_h,
            hub_r,
            hub_f: x_f,
            ..
        } = self.frames(angles, steer, rear_contact);
        // H's angles relative to the rear frame's heading, so that its yaw stays continuous.
        let relative = rotation::matrix(-yaw, T::zero(), T::zero()) * rh;
        let ah = rotation::angles(&relative);
        let h_angles = Vector3::new(yaw + ah.x, ah.y, ah.z);
        let mut q = SVector::<T, COORDINATES>::zeros();
        let mut put = |k: usize, x: Vector3<T>, ang: Vector3<T>| {
            q.fixed_rows_mut::<3>(6 * k).copy_from(&x);
            q.fixed_rows_mut::<3>(6 * k + 3).copy_from(&ang);
        };
        put(
            REAR_WHEEL,
            hub_r,
            Vector3::new(yaw, lean, pitch + wheel_angles[0]),
        );
        put(REAR_FRAME, x_b, Vector3::new(yaw, lean, pitch));
        put(FRONT_FRAME, x_h, h_angles);
        put(
            FRONT_WHEEL,
            x_f,
            Vector3::new(h_angles.x, h_angles.y, h_angles.z + wheel_angles[1]),
        );
        q
    }

    /// The rear frame pitch θ that puts the front wheel on the ground at lean φ and steer δ, in
    /// any scalar: [`Model::pitch_for`]'s bounded Newton iteration in f64 from `guess` gives
    /// θ₀, then one more Newton step θ₀ − h(θ₀)/h'(θ₀) is taken in the scalar type, which gives
    /// dual numbers the exact derivative ∂θ/∂(φ, δ) = −(∂h/∂θ)⁻¹ ∂h/∂(φ, δ) (implicit function
    /// theorem) and moves the value by at most the last step's round-off.
    pub(crate) fn ground_pitch<T: Real>(&self, lean: T, steer: T, guess: f64) -> Result<T> {
        let re = |x: T| nalgebra::try_convert::<T, f64>(x).unwrap_or(f64::NAN);
        let (lean0, steer0) = (re(lean), re(steer));
        let pitch0 = self.pitch_for(lean0, steer0, guess)?;
        let zero = Dual64::from_re(0.0);
        let slope = self
            .front_height(
                [zero, Dual64::from_re(lean0), Dual64::new(pitch0, 1.0)],
                Dual64::from_re(steer0),
                [zero, zero],
            )
            .eps;
        if !(slope.is_finite() && slope != 0.0) {
            return Err(Error::SingularDynamics {
                context: format!("the front contact height does not depend on pitch ({slope})"),
            });
        }
        let convert = |x: f64| -> T { nalgebra::convert(x) };
        let h = self.front_height(
            [T::zero(), lean, convert(pitch0)],
            steer,
            [T::zero(), T::zero()],
        );
        Ok(convert(pitch0) - h / convert(slope))
    }

    /// The rear frame pitch that puts the front wheel on the ground, by Newton iteration
    /// (derivative by a dual number) from `guess`.
    pub fn pitch_for(&self, lean: f64, steer: f64, guess: f64) -> Result<f64> {
        let mut pitch = guess;
        let mut residual = f64::INFINITY;
        for _ in 0..PITCH_ITERATIONS {
            let p = Dual64::new(pitch, 1.0);
            let c = Dual64::from_re;
            let h = self.front_height([c(0.0), c(lean), p], c(steer), [c(0.0), c(0.0)]);
            residual = h.re;
            if residual.abs() < 1e-15 {
                return Ok(pitch);
            }
            let step = h.re / h.eps;
            if !step.is_finite() {
                break;
            }
            pitch -= step;
            if step.abs() < 1e-16 * (1.0 + pitch.abs()) {
                return Ok(pitch);
            }
        }
        Err(Error::NoConvergence {
            method: "Newton iteration for the rear frame pitch",
            iterations: PITCH_ITERATIONS,
            residual,
        })
    }
}
