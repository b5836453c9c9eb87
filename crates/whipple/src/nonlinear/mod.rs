//! The fully non-linear multibody bicycle of Dressel's JBike6 study: four rigid bodies in 3-D
//! (rear wheel R, rear frame with rider B, front frame H, front wheel F), 24 coordinates and 24
//! speeds, three revolute joints and two knife-edge wheel contacts as constraint rows (17
//! holonomic + 4 non-holonomic), Newton–Euler dynamics with Lagrange multipliers.
//!
//! ```
//! use whipple::{BenchmarkParameters, nonlinear::{InitialConditions, Inputs, Model}};
//! let model = Model::new(&BenchmarkParameters::meijaard2007())?;
//! let state = model.initial_state(&InitialConditions {
//!     lean_rate: 0.5,
//!     ..InitialConditions::upright(4.6)
//! })?;
//! let view = model.observe(&state);
//! assert!((view.speed - 4.6).abs() < 1e-12 && (view.lean_rate - 0.5).abs() < 1e-12);
//! let derivatives = model.forward(&state, &Inputs::default())?;
//! assert!(derivatives.contact[0].normal > 0.0);
//! # Ok::<(), whipple::Error>(())
//! ```

pub mod bodies;
pub mod contact;
pub mod expression;
pub mod forward;
pub mod joints;
pub mod projection;
pub mod reduced;
pub mod rotation;
mod saddle;
pub mod simulate;
pub mod state;

use nalgebra::{RealField, SMatrix, SVector, Vector3};
use num_dual::Dual64;

pub use bodies::{Bodies, BODIES, FRONT_FRAME, FRONT_WHEEL, REAR_FRAME, REAR_WHEEL};
pub use expression::TorqueExpression;
pub use forward::{ContactForce, Derivatives, Inputs, Poses, HOLONOMIC_ROWS, VELOCITY_ROWS};
pub use projection::{ProjectionMethod, ProjectionParams, ProjectionReport};
pub use reduced::{FullStateField, LeanSteerField};
pub use simulate::{
    simulate, Integrator, Outcome, Progress, ProgressFn, Sample, Simulation, SimulationSettings,
    TorqueFn, Wheel,
};
pub use state::{BodyPose, State, StateView, COORDINATES, SPEEDS, STATE_LEN};

use crate::error::{Error, Result};
use crate::parameters::BenchmarkParameters;
use contact::KnifeEdge;
use forward::TREE;
use joints::Revolute;

/// The multibody bicycle built from benchmark parameters: immutable, shared by every state.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The parameters it was built from.
    pub parameters: BenchmarkParameters,
    /// Mass properties and attachment geometry.
    pub bodies: Bodies,
    /// Rear hub (B–R), steer (B–H), front hub (H–F).
    pub(crate) joints: [Revolute; 3],
    /// Rear and front wheel contacts.
    pub(crate) contacts: [KnifeEdge; 2],
    /// ρ of the augmented-Lagrangian solve (0: the reduced mass matrix is positive definite).
    pub(crate) augmentation: f64,
}

/// A few numbers from which [`Model::initial_state`] builds a consistent state. Angles in
/// radians, benchmark signs (lean right, steer right positive).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitialConditions {
    /// v: forward speed of the rear hub along the rear frame's heading [m/s].
    pub speed: f64,
    /// φ: lean \[rad\], |φ| < π/2.
    pub lean: f64,
    /// δ: steer \[rad\].
    pub steer: f64,
    /// φ̇: lean rate [rad/s].
    pub lean_rate: f64,
    /// δ̇: steer rate [rad/s].
    pub steer_rate: f64,
    /// ψ: yaw (heading) \[rad\].
    pub yaw: f64,
    /// Rear contact x \[m\].
    pub rear_contact_x: f64,
    /// Rear contact y \[m\].
    pub rear_contact_y: f64,
}

impl InitialConditions {
    /// Upright, straight running at `speed`, heading along +x from the origin.
    pub fn upright(speed: f64) -> Self {
        InitialConditions {
            speed,
            lean: 0.0,
            steer: 0.0,
            lean_rate: 0.0,
            steer_rate: 0.0,
            yaw: 0.0,
            rear_contact_x: 0.0,
            rear_contact_y: 0.0,
        }
    }
}

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
        self.velocity.rows(HOLONOMIC_ROWS, 4).amax()
    }
    /// Largest absolute velocity-row residual.
    pub fn max_velocity(&self) -> f64 {
        self.velocity.amax()
    }
}

/// Poses of the two frames and the two hubs (world axes).
struct FramePoses<T: RealField + Copy> {
    x_b: Vector3<T>,
    rh: nalgebra::Matrix3<T>,
    x_h: Vector3<T>,
    hub_r: Vector3<T>,
    hub_f: Vector3<T>,
}

/// Newton iterations allowed when solving the pitch of a new state.
const PITCH_ITERATIONS: usize = 50;

impl Model {
    /// The multibody model of a bicycle, after validating its parameters.
    pub fn new(p: &BenchmarkParameters) -> Result<Self> {
        p.validate()?;
        let bodies = Bodies::new(p);
        let g = &bodies.geometry;
        let (ex, ey, ez) = (Vector3::x(), Vector3::y(), Vector3::z());
        let s = g.steer_axis;
        let hub = |parent, child, point| Revolute {
            parent,
            child,
            point_in_parent: point,
            point_in_child: Vector3::zeros(),
            axis_in_child: ey,
            perpendicular_in_parent: [ex, ez],
        };
        let joints = [
            hub(REAR_FRAME, REAR_WHEEL, g.rear_hub_in_b),
            Revolute {
                parent: REAR_FRAME,
                child: FRONT_FRAME,
                point_in_parent: g.steer_point_in_b,
                point_in_child: g.steer_point_in_h,
                axis_in_child: s,
                perpendicular_in_parent: [ey, s.cross(&ey)],
            },
            hub(FRONT_FRAME, FRONT_WHEEL, g.front_hub_in_h),
        ];
        let contacts = [
            KnifeEdge {
                wheel: REAR_WHEEL,
                frame: REAR_FRAME,
                radius: p.r_r,
            },
            KnifeEdge {
                wheel: FRONT_WHEEL,
                frame: FRONT_FRAME,
                radius: p.r_f,
            },
        ];
        // Without spin inertia in a wheel, the reduced mass matrix is singular along that
        // wheel's spin: the solve then augments it by ρ GᵀG, ρ of the order of the masses.
        let augmentation = if p.i_ryy > 0.0 && p.i_fyy > 0.0 {
            0.0
        } else {
            p.m_r + p.m_b + p.m_h + p.m_f
        };
        Ok(Model {
            parameters: *p,
            bodies,
            joints,
            contacts,
            augmentation,
        })
    }

    /// ρ used when the plain Cholesky factorization of the reduced mass matrix fails.
    pub(crate) fn fallback_augmentation(&self) -> f64 {
        let p = &self.parameters;
        p.m_r + p.m_b + p.m_h + p.m_f
    }

    /// The 17 holonomic residuals: rear hub, steer and front hub joints (5 each: gap x, y, z,
    /// two axis misalignments), then rear and front contact heights.
    pub fn holonomic_residual<T: RealField + Copy>(
        &self,
        q: &SVector<T, COORDINATES>,
    ) -> SVector<T, HOLONOMIC_ROWS> {
        self.holonomic_residual_at(&Poses::new(q))
    }

    /// [`Model::holonomic_residual`] from the poses.
    pub(crate) fn holonomic_residual_at<T: RealField + Copy>(
        &self,
        poses: &Poses<T>,
    ) -> SVector<T, HOLONOMIC_ROWS> {
        let mut r = SVector::<T, HOLONOMIC_ROWS>::zeros();
        for (i, joint) in self.joints.iter().enumerate() {
            r.fixed_rows_mut::<5>(5 * i)
                .copy_from(&joint.residual(poses));
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            r[15 + i] = contact.height(poses);
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

    /// Total mechanical energy, kinetic plus gravitational potential (zero at ground level) \[J\].
    pub fn energy<T: RealField + Copy>(&self, state: &State<T>) -> T {
        let g: T = nalgebra::convert(self.bodies.geometry.g);
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
    pub fn steer<T: RealField + Copy>(&self, q: &SVector<T, COORDINATES>) -> T {
        self.steer_at(&Poses::new(q))
    }

    /// [`Model::steer`] from the poses.
    pub(crate) fn steer_at<T: RealField + Copy>(&self, poses: &Poses<T>) -> T {
        let relative = poses.rot[REAR_FRAME].transpose() * poses.rot[FRONT_FRAME];
        let s: Vector3<T> = self.bodies.geometry.steer_axis.cast();
        let ey = Vector3::<T>::y();
        let e = relative * ey;
        e.dot(&s.cross(&ey)).atan2(e.dot(&ey))
    }

    /// δ̇: steer rate [rad/s].
    pub fn steer_rate<T: RealField + Copy>(&self, state: &State<T>) -> T {
        self.steer_rate_at(&Poses::new(&state.q), state)
    }

    /// [`Model::steer_rate`] from the poses of `state.q`.
    fn steer_rate_at<T: RealField + Copy>(&self, poses: &Poses<T>, state: &State<T>) -> T {
        let a_hb = poses.rot[FRONT_FRAME].transpose() * poses.rot[REAR_FRAME];
        let s: Vector3<T> = self.bodies.geometry.steer_axis.cast();
        s.dot(&(state.angular_velocity(FRONT_FRAME) - a_hb * state.angular_velocity(REAR_FRAME)))
    }

    /// Spin rates of the rear and front wheels relative to their frames, about the axle
    /// (negative when rolling forward) [rad/s].
    pub fn wheel_rates<T: RealField + Copy>(&self, state: &State<T>) -> [T; 2] {
        let poses = Poses::new(&state.q);
        self.contacts.map(|c| {
            let a = poses.rot[c.wheel].transpose() * poses.rot[c.frame];
            state.angular_velocity(c.wheel).y - (a * state.angular_velocity(c.frame)).y
        })
    }

    /// v: forward speed, the rear hub's velocity along the rear frame's heading [m/s].
    pub fn speed<T: RealField + Copy>(&self, state: &State<T>) -> T {
        let (s, c) = state.yaw().sin_cos();
        let v = state.velocity(REAR_WHEEL);
        v.x * c + v.y * s
    }

    /// Rear and front contact points (lowest rim points), world axes \[m\].
    pub fn contact_points<T: RealField + Copy>(
        &self,
        q: &SVector<T, COORDINATES>,
    ) -> [Vector3<T>; 2] {
        let poses = Poses::new(q);
        self.contacts.map(|c| c.point(&poses))
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
    pub fn wheel_angles<T: RealField + Copy>(&self, q: &SVector<T, COORDINATES>) -> [T; 2] {
        self.contacts
            .map(|c| q[6 * c.wheel + state::PITCH] - q[6 * c.frame + state::PITCH])
    }

    /// The pose of each body ([`REAR_WHEEL`], [`REAR_FRAME`], [`FRONT_FRAME`], [`FRONT_WHEEL`]
    /// order) in a state: origin (centre of mass) and rotation matrix, world axes.
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, nonlinear::{InitialConditions, Model, REAR_FRAME}};
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

    /// The pose of each body at a recorded [`Sample`] (see [`Model::body_poses`]), so that a
    /// simulation can be animated from its samples alone.
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, nonlinear::*};
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

    /// Rotation matrices and origins of the rear and front frames, and the rear and front hub
    /// positions, for a configuration given by the rear frame's yaw, lean and pitch, the steer
    /// angle and the rear contact point; joints and rear contact hold exactly.
    fn frames<T: RealField + Copy>(
        &self,
        angles: [T; 3],
        steer: T,
        rear_contact: [T; 2],
    ) -> FramePoses<T> {
        let g = &self.bodies.geometry;
        let [yaw, lean, pitch] = angles;
        let rb = rotation::matrix(yaw, lean, pitch);
        let a = rb.column(1).into_owned();
        let s_len = (a.x * a.x + a.y * a.y).sqrt();
        let f = Vector3::new(a.y / s_len, -a.x / s_len, T::zero());
        let down = f.cross(&a);
        let r_r: T = nalgebra::convert(g.r_r);
        let hub_r = Vector3::new(rear_contact[0], rear_contact[1], T::zero()) - down * r_r;
        let x_b = hub_r - rb * g.rear_hub_in_b.cast::<T>();
        let s: Vector3<T> = g.steer_axis.cast();
        let rh = rb * rotation::axis_angle(&s, steer);
        let x_h = x_b + rb * g.steer_point_in_b.cast::<T>() - rh * g.steer_point_in_h.cast::<T>();
        let x_f = x_h + rh * g.front_hub_in_h.cast::<T>();
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
    pub fn front_height<T: RealField + Copy>(
        &self,
        angles: [T; 3],
        steer: T,
        rear_contact: [T; 2],
    ) -> T {
        let p = self.frames(angles, steer, rear_contact);
        let a = p.rh.column(1);
        let r_f: T = nalgebra::convert(self.bodies.geometry.r_f);
        p.hub_f.z + (a.x * a.x + a.y * a.y).sqrt() * r_f
    }

    /// The 24 coordinates of a configuration that satisfies the 15 joint constraints and the
    /// rear contact exactly, from the rear frame's yaw, lean and pitch, the steer angle, the
    /// wheels' rotations relative to their frames and the rear contact point. (The front
    /// contact height is satisfied only at the right pitch: see [`Model::initial_state`].)
    pub fn configuration<T: RealField + Copy>(
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

    /// The tree Jacobians J_k (6 × 9 each) and the six contact rows expressed in the nine tree
    /// speeds (they depend on the configuration only).
    pub(crate) fn contact_tree_rows(
        &self,
        poses: &Poses<f64>,
    ) -> ([SMatrix<f64, 6, TREE>; BODIES], SMatrix<f64, 6, TREE>) {
        let (tree, _) = self.tree(poses, &SVector::zeros());
        let jac: [SMatrix<f64, 6, TREE>; BODIES] = std::array::from_fn(|k| tree.jac(k));
        let mut g = SMatrix::<f64, 6, TREE>::zeros();
        for i in 0..2 {
            let (gi, _, _) = self.contact_rows_in(i, poses, &tree, &jac, &tree.bias);
            g.fixed_rows_mut::<3>(3 * i).copy_from(&gi);
        }
        (jac, g)
    }

    /// The speeds of all four bodies from the nine tree speeds: the rear hub's velocity (world
    /// axes), the rear frame's angular velocity (body axes), the steer rate and the wheels'
    /// spin rates relative to their frames. The result satisfies the 15 joint velocity rows
    /// exactly (not necessarily the contact rows).
    pub fn tree_speeds(
        &self,
        q: &SVector<f64, COORDINATES>,
        rear_hub_velocity: &Vector3<f64>,
        rear_frame_angular_velocity: &Vector3<f64>,
        steer_rate: f64,
        wheel_rates: [f64; 2],
    ) -> SVector<f64, SPEEDS> {
        let poses = Poses::new(q);
        let (tree, _) = self.tree(&poses, &SVector::zeros());
        let nu = poses.rot[REAR_FRAME].transpose() * rear_hub_velocity;
        let w = SVector::<f64, TREE>::from_column_slice(&[
            nu.x,
            nu.y,
            nu.z,
            rear_frame_angular_velocity.x,
            rear_frame_angular_velocity.y,
            rear_frame_angular_velocity.z,
            steer_rate,
            wheel_rates[0],
            wheel_rates[1],
        ]);
        let mut u = SVector::<f64, SPEEDS>::zeros();
        for k in 0..BODIES {
            u.fixed_rows_mut::<6>(6 * k).copy_from(&(tree.jac(k) * w));
        }
        u
    }

    /// A state that satisfies all constraints, built from a few numbers: the pitch of the rear
    /// frame by Newton iteration on the front contact height, every other coordinate from the
    /// joints, and the dependent speeds from the velocity constraints given speed, lean rate
    /// and steer rate. Wheel rotation angles start at zero.
    pub fn initial_state(&self, ic: &InitialConditions) -> Result<State<f64>> {
        for (what, value) in [
            ("speed", ic.speed),
            ("lean", ic.lean),
            ("steer", ic.steer),
            ("lean_rate", ic.lean_rate),
            ("steer_rate", ic.steer_rate),
            ("yaw", ic.yaw),
            ("rear_contact_x", ic.rear_contact_x),
            ("rear_contact_y", ic.rear_contact_y),
        ] {
            if !value.is_finite() {
                return Err(Error::InvalidArgument {
                    what: "initial conditions",
                    rule: format!("{what} must be a finite number, got {value}"),
                });
            }
        }
        if ic.lean.abs() >= std::f64::consts::FRAC_PI_2 {
            return Err(Error::InvalidArgument {
                what: "initial conditions",
                rule: format!(
                    "the lean must lie strictly between -pi/2 and pi/2, got {}",
                    ic.lean
                ),
            });
        }
        let pitch = self.pitch_for(ic.lean, ic.steer, 0.0)?;
        let q = self.configuration(
            [ic.yaw, ic.lean, pitch],
            ic.steer,
            [0.0, 0.0],
            [ic.rear_contact_x, ic.rear_contact_y],
        );
        let poses = Poses::new(&q);
        let (jac, g) = self.contact_tree_rows(&poses);
        // Nine equations in the nine tree speeds: six contact rows and the three given speeds.
        let mut a = SMatrix::<f64, TREE, TREE>::zeros();
        let mut b = SVector::<f64, TREE>::zeros();
        a.fixed_rows_mut::<6>(0).copy_from(&g);
        let rb = poses.rot[REAR_FRAME];
        let heading = rb.transpose() * Vector3::new(ic.yaw.cos(), ic.yaw.sin(), 0.0);
        a.fixed_view_mut::<1, 3>(6, 0)
            .copy_from(&heading.transpose());
        b[6] = ic.speed;
        let (sp, cp) = pitch.sin_cos();
        a[(7, 3)] = cp;
        a[(7, 5)] = sp;
        b[7] = ic.lean_rate;
        a[(8, 6)] = 1.0;
        b[8] = ic.steer_rate;
        let w = a
            .lu()
            .solve(&b)
            .filter(|w| w.iter().all(|x| x.is_finite()))
            .ok_or_else(|| Error::InvalidArgument {
                what: "initial conditions",
                rule: "speed, lean rate and steer rate do not determine the motion in this \
                       configuration (singular velocity constraints)"
                    .into(),
            })?;
        let mut u = SVector::<f64, SPEEDS>::zeros();
        for (k, jac) in jac.iter().enumerate() {
            u.fixed_rows_mut::<6>(6 * k).copy_from(&(jac * w));
        }
        Ok(State { q, u })
    }

    /// The time derivative of any smooth function of the state, `d/dt h(q, u)`, along the
    /// motion `(q̇, u̇)`, by one forward-mode dual number. Used to turn accelerations in this
    /// model's speeds into second derivatives of other coordinates (steer, Euler angles).
    pub fn time_derivative(
        state: &State<f64>,
        derivatives: &Derivatives<f64>,
        h: impl Fn(&State<Dual64>) -> Dual64,
    ) -> f64 {
        let dual = State {
            q: state.q.zip_map(&derivatives.q_dot, Dual64::new),
            u: state.u.zip_map(&derivatives.u_dot, Dual64::new),
        };
        h(&dual).eps
    }
}
