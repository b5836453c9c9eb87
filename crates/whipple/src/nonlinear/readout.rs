//! What a state says, read off in the quantities a rider, a plot or a drawing uses: lean,
//! steer, rates, forward speed, contact points, wheel angles, energy, and each body's pose.

use crate::math::Real;
use nalgebra::{SVector, Vector3};
use num_dual::Dual64;

use super::Model;
use super::forward::StateRates;
use super::outcome::Sample;
use super::poses::Poses;
use super::state::{BODY_PITCH, BodyPose, COORDINATES, State, StateView};
use super::topology::{BODIES, FRONT_FRAME, REAR_FRAME, REAR_WHEEL};

impl Model {
    /// Total mechanical energy, kinetic plus gravitational potential (zero at ground level) \[J\].
    pub fn energy<T: Real>(&self, state: &State<T>) -> T {
        let g: T = nalgebra::convert(self.parameters.g);
        let half: T = nalgebra::convert(0.5);
        let mut e = T::zero();
        for k in 0..BODIES {
            let body = &self.bodies.body[k];
            let m: T = nalgebra::convert(body.mass);
            let v = state.velocity(k);
            let w = state.angular_velocity(k);
            let inertia: nalgebra::Matrix3<T> = body.inertia.cast();
            e += half * (m * v.norm_squared() + w.dot(&(inertia * w))) - m * g * state.q[6 * k + 2];
        }
        e
    }

    /// δ: steer angle, the front frame's rotation relative to the rear frame about the steer
    /// axis, right positive \[rad\].
    pub fn steer<T: Real>(&self, q: &SVector<T, COORDINATES>) -> T {
        self.steer_at(&Poses::new(q))
    }

    /// [`Model::steer`] from the poses.
    pub(crate) fn steer_at<T: Real>(&self, poses: &Poses<T>) -> T {
        let relative = poses.rot[REAR_FRAME].transpose() * poses.rot[FRONT_FRAME];
        let s: Vector3<T> = self.bodies.geometry.steer_axis.cast();
        let ey = Vector3::<T>::y();
        let e = relative * ey;
        crate::math::atan2(e.dot(&s.cross(&ey)), e.dot(&ey))
    }

    /// δ̇: steer rate [rad/s].
    pub fn steer_rate<T: Real>(&self, state: &State<T>) -> T {
        self.steer_rate_at(&Poses::new(&state.q), state)
    }

    /// [`Model::steer_rate`] from the poses of `state.q`.
    fn steer_rate_at<T: Real>(&self, poses: &Poses<T>, state: &State<T>) -> T {
        let a_hb = poses.rot[FRONT_FRAME].transpose() * poses.rot[REAR_FRAME];
        let s: Vector3<T> = self.bodies.geometry.steer_axis.cast();
        s.dot(&(state.angular_velocity(FRONT_FRAME) - a_hb * state.angular_velocity(REAR_FRAME)))
    }

    /// Spin rates of the rear and front wheels relative to their frames, about the axle
    /// (negative when rolling forward) [rad/s].
    pub fn wheel_rates<T: Real>(&self, state: &State<T>) -> [T; 2] {
        let poses = Poses::new(&state.q);
        self.contacts.map(|c| {
            let a = poses.rot[c.wheel].transpose() * poses.rot[c.frame];
            state.angular_velocity(c.wheel).y - (a * state.angular_velocity(c.frame)).y
        })
    }

    /// v: forward speed, the rear hub's velocity along the rear frame's heading [m/s].
    pub fn speed<T: Real>(&self, state: &State<T>) -> T {
        let (s, c) = crate::math::sin_cos(state.yaw());
        let v = state.velocity(REAR_WHEEL);
        v.x * c + v.y * s
    }

    /// Rear and front contact points (lowest rim points), world axes \[m\].
    pub fn contact_points<T: Real>(&self, q: &SVector<T, COORDINATES>) -> [Vector3<T>; 2] {
        let poses = Poses::new(q);
        self.contacts.map(|c| c.point(&poses))
    }

    /// Where a point fixed in body `body` is in the configuration `q` (world axes): `local` is
    /// the point in the body's own axes relative to its centre of mass (for a point at p in a
    /// reference pose of the body, Rᵀ (p − centre)). Any scalar, so dual numbers carry its
    /// exact derivatives.
    #[cfg(test)]
    pub(crate) fn body_point<T: Real>(
        q: &SVector<T, COORDINATES>,
        body: usize,
        local: &Vector3<f64>,
    ) -> Vector3<T> {
        let poses = Poses::new(q);
        let local: Vector3<T> = local.cast();
        poses.pos[body] + poses.rot[body] * local
    }

    /// All named quantities of a state.
    pub fn observe(&self, state: &State<f64>) -> StateView {
        self.observe_at(&Poses::new(&state.q), state)
    }

    /// [`Model::observe`] from the poses of `state.q`.
    pub(crate) fn observe_at(&self, poses: &Poses<f64>, state: &State<f64>) -> StateView {
        let rates = state.angle_rates(REAR_FRAME);
        let [rear, front] = self.contacts.map(|c| c.point(poses));
        StateView {
            lean: state.lean(),
            steer: self.steer_at(poses),
            yaw: state.yaw(),
            pitch: state.pitch(),
            lean_rate: rates.y,
            steer_rate: self.steer_rate_at(poses, state),
            yaw_rate: rates.x,
            speed: self.speed(state),
            rear_contact_x: rear.x,
            rear_contact_y: rear.y,
            front_contact_x: front.x,
            front_contact_y: front.y,
        }
    }

    /// θ_R, θ_F: rotation of the rear and front wheels relative to their frames, about the
    /// axle (negative when rolling forward, never wrapped) \[rad\]. With the hub joints holding,
    /// a wheel and its frame share yaw and lean, so this is the difference of their third
    /// angles.
    pub fn wheel_angles<T: Real>(&self, q: &SVector<T, COORDINATES>) -> [T; 2] {
        self.contacts
            .map(|c| q[6 * c.wheel + BODY_PITCH] - q[6 * c.frame + BODY_PITCH])
    }

    /// The pose of each body ([`super::REAR_WHEEL`], [`super::REAR_FRAME`], `super::FRONT_FRAME`, [`super::FRONT_WHEEL`]
    /// order) in a state: origin (centre of mass) and rotation matrix, world axes.
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, InitialConditions, Model};
    /// use whipple::advanced::nonlinear::REAR_FRAME;
    /// let bike = BenchmarkParameters::meijaard2007();
    /// let model = Model::new(&bike)?;
    /// let state = model.initial_state(&InitialConditions::upright(5.0))?;
    /// let poses = model.body_poses(&state);
    /// // Upright: the rear frame's centre of mass is at (x_B, 0, z_B), its axes the world's.
    /// assert!((poses[REAR_FRAME].position.x - bike.x_b).abs() < 1e-12);
    /// assert!((poses[REAR_FRAME].position.z - bike.z_b).abs() < 1e-12);
    /// assert!((poses[REAR_FRAME].rotation.determinant() - 1.0).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn body_poses(&self, state: &State<f64>) -> [BodyPose; BODIES] {
        Self::poses_of(&state.q)
    }

    /// The pose of each body at a recorded [`Sample`] (see [`Model::body_poses`]), so that a
    /// simulation can be animated from its samples alone.
    ///
    /// ```
    /// use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, SimulationSettings};
    /// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
    /// let start = model.initial_state(&InitialConditions { lean_rate: 0.5, ..InitialConditions::upright(4.6) })?;
    /// let run = simulate(&model, start, &SimulationSettings { duration: 0.5, ..SimulationSettings::default() })?;
    /// let (last, exact) = (run.samples.last().expect("a sample"), model.body_poses(&run.final_state));
    /// for (from_sample, from_state) in model.sample_poses(last).iter().zip(&exact) {
    ///     assert!((from_sample.position - from_state.position).amax() < 1e-9);
    ///     assert!((from_sample.rotation - from_state.rotation).amax() < 1e-9);
    /// }
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn sample_poses(&self, sample: &Sample) -> [BodyPose; BODIES] {
        Self::poses_of(&self.sample_coordinates(sample))
    }

    fn poses_of(q: &SVector<f64, COORDINATES>) -> [BodyPose; BODIES] {
        let poses = Poses::new(q);
        std::array::from_fn(|k| BodyPose {
            position: poses.pos[k],
            rotation: poses.rot[k],
        })
    }

    /// The time derivative of any smooth function of the state, `d/dt h(q, u)`, along the
    /// motion `(q̇, u̇)`, by one forward-mode dual number. Used to turn accelerations in this
    /// model's speeds into second derivatives of other coordinates (steer, Euler angles).
    pub fn time_derivative(
        state: &State<f64>,
        derivatives: &StateRates<f64>,
        h: impl Fn(&State<Dual64>) -> Dual64,
    ) -> f64 {
        let dual = State {
            q: state.q.zip_map(&derivatives.q_dot, Dual64::new),
            u: state.u.zip_map(&derivatives.u_dot, Dual64::new),
        };
        h(&dual).eps
    }
}
