//! The leaning rider: the rider's upper body G as a fifth rigid body, hinged to the rear frame
//! B about B's x axis (the roll axis of the upright reference configuration), Moore 2012's
//! rider-lean model ([`RiderLeanParameters`]).
//!
//! The four bodies are [`Model`]'s, built from the bicycle whose rear frame holds the rider's
//! lower body, with its state, tree map and contact rows unchanged; G adds one tree speed, the
//! hinge rate φ̇_r, below B in the joint tree, and one coordinate, the hinge angle φ_r (G's
//! rotation relative to B, right positive as the lean). G's speeds are
//! `u_G = J_G [w'; φ̇_r]` with
//!
//! - ω_G = A ω_B + e_x φ̇_r (G axes, A = R_x(φ_r)ᵀ), ω̇_G = A ω̇_B + e_x φ̈_r + (A ω_B) × e_x φ̇_r;
//! - v_G = v_B + R_B (ω_B × h) + R_G (ω_G × c), h the hinge point from B's origin (B axes), c
//!   G's centre from the hinge point (G axes), so the translation rows are
//!   J_B,v − R_B [h]× J_B,ω − R_G [c]× J_G,ω and the bias adds the centripetal terms of both
//!   arms.
//!
//! The reduced mass matrix and forces gain G's share over the seven speeds [ω_B, δ̇, σ_R, σ_F,
//! φ̇_r] (a rolling rear wheel's three rows solved for ν as in [`Model::forward`]), the front
//! contact's three rows are unchanged (G touches no contact), and the same saddle-point solve
//! gives the accelerations. The hinge torque T_r − k φ_r − c φ̇_r acts on G about e_x and its
//! reaction on B; the rear contact force comes from the momentum balance of all five bodies.

use crate::math::Real;
use nalgebra::{Complex, Matrix3, SMatrix, SVector, Vector3, Vector4};
use num_dual::Dual64;

use super::Model;
use super::assembly::{Reduced, symmetrize};
use super::forward::{ContactForce, Inputs, StateRates, coordinate_rates};
use super::initial::InitialConditions;
use super::outcome::{Outcome, Sample, Simulation};
use super::poses::{Angles, Poses};
use super::rotation;
use super::saddle;
use super::settings::{SimulationSettings, TorqueFn};
use super::simulate::{Mechanism, check_rk4_mode, crossing, run_mechanism};
use super::state::{BodyPose, COORDINATES, SPEEDS, STATE_LEN, State};
use super::topology::{BODIES, FRONT_CONTACT, REAR_FRAME, ROLLING_TREE};
use crate::analysis::linearize::{VectorField, jacobian};
use crate::error::{Error, Result};
use crate::integrate::{Integrator, OdeSystem};
use crate::parameters::RiderLeanParameters;

/// Tree speeds with the hinge: w' = [ω_B, δ̇, σ_R, σ_F] and φ̇_r.
const LEAN_TREE: usize = ROLLING_TREE + 1;
/// The hinge rate's index among them.
const HINGE_RATE: usize = ROLLING_TREE;

#[inline]
fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

/// The bicycle with a leaning rider: [`Model`]'s four bodies (the rear frame holding the
/// rider's lower body) and the upper body G hinged to the rear frame.
///
/// ```
/// use whipple::advanced::nonlinear::LeanModel;
/// use whipple::advanced::parameters::RiderLeanParameters;
/// let model = LeanModel::new(&RiderLeanParameters::browser_jason())?;
/// let (a, b) = model.linearize(5.0)?;
/// // Lean rates: [φ, δ, φ_r, φ̇, δ̇, φ̇_r]; a lean torque leans the upper body right.
/// assert_eq!(a[(2, 5)], 1.0);
/// assert!(b[(5, 2)] > 0.0);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LeanModel {
    /// The four bodies.
    model: Model,
    /// The parameters it was built from.
    parameters: RiderLeanParameters,
    /// G's mass \[kg\].
    mass: f64,
    /// G's tensor about its centre, G axes \[kg m²\].
    inertia: Matrix3<f64>,
    /// A point of the hinge line from B's origin, B axes \[m\] (the one straight above or below
    /// G's centre in the reference configuration).
    hinge_in_b: Vector3<f64>,
    /// G's centre from that point, G axes \[m\].
    centre_in_g: Vector3<f64>,
}

/// A state of the leaning rider: the four bodies' [`State`] and the hinge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeanState<T: Real> {
    /// The four bodies.
    pub bicycle: State<T>,
    /// φ_r: the upper body's lean relative to the rear frame, right positive \[rad\].
    pub lean: T,
    /// φ̇_r: its rate [rad/s].
    pub lean_rate: T,
}

/// The result of [`LeanModel::forward`].
#[derive(Debug, Clone, Copy)]
pub struct LeanRates<T: Real> {
    /// The four bodies' rates and the ground forces (the whole bicycle's, rider included).
    pub bicycle: StateRates<T>,
    /// φ̈_r: the hinge's angular acceleration [rad/s²].
    pub lean_acceleration: T,
}

/// The rider's input at the hinge to [`LeanModel::simulate`], and where the upper body's fall
/// ends a run.
#[derive(Clone, Copy)]
pub struct LeanForcing<'a> {
    /// The rider's torque about the hinge T_r(t, the four bodies' state) \[N m\] (on the upper
    /// body, its reaction on the rear frame; right positive); `None` for none.
    pub hinge_torque: Option<&'a TorqueFn>,
    /// The run ends (outcome [`Outcome::UpperBodyFell`]) when |φ_r| passes this \[rad\]:
    /// [`HINGE_LIMIT`], the upper body across the bicycle, by default; infinite, never (the
    /// mechanics run on, the upper body through the bicycle).
    pub hinge_limit: f64,
}

impl Default for LeanForcing<'_> {
    /// No hinge torque; the run ends at [`HINGE_LIMIT`].
    fn default() -> Self {
        LeanForcing {
            hinge_torque: None,
            hinge_limit: HINGE_LIMIT,
        }
    }
}

/// The hinge angle past which [`LeanModel::simulate`] ends a run by default: the upper body
/// lies across the bicycle (90°).
pub const HINGE_LIMIT: f64 = std::f64::consts::FRAC_PI_2;

/// Length of the leaning rider's first-order state [q; u; φ_r; φ̇_r].
pub(crate) const LEAN_STATE_LEN: usize = STATE_LEN + 2;

/// A run of [`LeanModel::simulate`]: the four bodies' [`Simulation`] (the same samples,
/// events and extremes as [`crate::simulate`]'s; each sample's energy the five bodies' with the
/// hinge spring's, its ground forces the whole bicycle's) and the hinge at each sample.
#[derive(Debug, Clone)]
pub struct LeanSimulation {
    /// The four bodies' run.
    pub simulation: Simulation,
    /// φ_r and φ̇_r at each sample \[rad, rad/s\].
    pub rider: Vec<[f64; 2]>,
    /// The last state reached.
    pub final_state: LeanState<f64>,
}

impl<T: Real> LeanState<T> {
    /// The first-order vector [q; u; φ_r; φ̇_r].
    pub fn to_vector(&self) -> SVector<T, LEAN_STATE_LEN> {
        let mut y = SVector::<T, LEAN_STATE_LEN>::zeros();
        y.fixed_rows_mut::<STATE_LEN>(0)
            .copy_from(&self.bicycle.to_vector());
        y[STATE_LEN] = self.lean;
        y[STATE_LEN + 1] = self.lean_rate;
        y
    }

    /// The state of a first-order vector [q; u; φ_r; φ̇_r].
    pub fn from_vector(y: &SVector<T, LEAN_STATE_LEN>) -> Self {
        LeanState {
            bicycle: State::from_vector(&y.fixed_rows::<STATE_LEN>(0).into_owned()),
            lean: y[STATE_LEN],
            lean_rate: y[STATE_LEN + 1],
        }
    }
}

/// The leaning rider's reduced state [φ, δ, φ_r, φ̇, δ̇, φ̇_r] at a fixed speed: the vector field
/// whose Jacobian at zero is the linear model's A(v).
#[derive(Debug, Clone, Copy)]
struct LeanField<'a> {
    model: &'a LeanModel,
    speed: f64,
}

impl VectorField<6> for LeanField<'_> {
    fn eval<T: Real>(&self, x: &SVector<T, 6>) -> Result<SVector<T, 6>> {
        self.model
            .lean_field(x, self.speed, &Inputs::default(), T::zero())
    }
}

/// The leaning rider with its inputs as a [`Mechanism`] on [q; u; φ_r; φ̇_r].
struct LeanOde<'a> {
    model: &'a LeanModel,
    steer_torque: Option<&'a TorqueFn>,
    lean_torque: Option<&'a TorqueFn>,
    hinge_torque: Option<&'a TorqueFn>,
    hinge_limit: f64,
}

impl LeanOde<'_> {
    /// The rider's lean and steer torques and the hinge torque at (t, state), each evaluated on
    /// the four bodies' named quantities; a non-finite one is [`Error::NonFiniteState`] at t.
    fn torques(&self, t: f64, state: &LeanState<f64>) -> Result<(Inputs<f64>, f64)> {
        if self.steer_torque.is_none() && self.lean_torque.is_none() && self.hinge_torque.is_none()
        {
            return Ok((Inputs::default(), 0.0));
        }
        let view = self.model.model.observe(&state.bicycle);
        let at = |f: Option<&TorqueFn>| f.map_or(0.0, |f| f(t, &view));
        let (inputs, hinge) = (
            Inputs {
                steer_torque: at(self.steer_torque),
                lean_torque: at(self.lean_torque),
            },
            at(self.hinge_torque),
        );
        if [inputs.steer_torque, inputs.lean_torque, hinge]
            .iter()
            .all(|x| x.is_finite())
        {
            Ok((inputs, hinge))
        } else {
            Err(Error::NonFiniteState { t })
        }
    }
}

impl OdeSystem<LEAN_STATE_LEN> for LeanOde<'_> {
    fn rhs(
        &self,
        t: f64,
        y: &SVector<f64, LEAN_STATE_LEN>,
    ) -> Result<SVector<f64, LEAN_STATE_LEN>> {
        Ok(self.evaluate(t, &LeanState::from_vector(y))?.0)
    }
}

impl Mechanism<LEAN_STATE_LEN> for LeanOde<'_> {
    type State = LeanState<f64>;
    type Record = [f64; 2];

    fn model(&self) -> &Model {
        &self.model.model
    }

    fn from_vector(y: &SVector<f64, LEAN_STATE_LEN>) -> LeanState<f64> {
        LeanState::from_vector(y)
    }

    fn to_vector(state: &LeanState<f64>) -> SVector<f64, LEAN_STATE_LEN> {
        state.to_vector()
    }

    fn bicycle(state: &LeanState<f64>) -> &State<f64> {
        &state.bicycle
    }

    fn bicycle_mut(state: &mut LeanState<f64>) -> &mut State<f64> {
        &mut state.bicycle
    }

    fn evaluate(
        &self,
        t: f64,
        state: &LeanState<f64>,
    ) -> Result<(SVector<f64, LEAN_STATE_LEN>, [ContactForce<f64>; 2])> {
        if !(state.bicycle.is_finite() && state.lean.is_finite() && state.lean_rate.is_finite()) {
            return Err(Error::NonFiniteState { t });
        }
        let (inputs, hinge) = self.torques(t, state)?;
        let d = self.model.forward(state, &inputs, hinge)?;
        let mut out = SVector::<f64, LEAN_STATE_LEN>::zeros();
        out.fixed_rows_mut::<COORDINATES>(0)
            .copy_from(&d.bicycle.q_dot);
        out.fixed_rows_mut::<SPEEDS>(COORDINATES)
            .copy_from(&d.bicycle.u_dot);
        out[STATE_LEN] = state.lean_rate;
        out[STATE_LEN + 1] = d.lean_acceleration;
        Ok((out, d.bicycle.contact))
    }

    fn energy(&self, state: &LeanState<f64>) -> f64 {
        self.model.energy(state)
    }

    /// T_δ δ̇ + T_φ φ̇ + (T_r − c φ̇_r) φ̇_r: the rider's torques and the hinge's damper (its
    /// spring is in the energy); 0 where a torque is not finite (the step reports that).
    fn power(&self, t: f64, state: &LeanState<f64>) -> f64 {
        let Ok((inputs, hinge)) = self.torques(t, state) else {
            return 0.0;
        };
        let view = self.model.model.observe(&state.bicycle);
        let damper = self.model.parameters.upper_body.damping * state.lean_rate;
        let power = inputs.steer_torque * view.steer_rate
            + inputs.lean_torque * view.lean_rate
            + (hinge - damper) * state.lean_rate;
        if power.is_finite() { power } else { 0.0 }
    }

    fn record(&self, state: &LeanState<f64>) -> [f64; 2] {
        [state.lean, state.lean_rate]
    }

    fn own_event(
        &self,
        t0: f64,
        s0: &LeanState<f64>,
        t1: f64,
        s1: &LeanState<f64>,
    ) -> Option<(f64, Outcome)> {
        let limit = self.hinge_limit;
        if s1.lean.abs() <= limit {
            return None;
        }
        let t = crossing(t0, s0.lean.abs() - limit, t1, s1.lean.abs() - limit);
        let lean = s0.lean + (s1.lean - s0.lean) * (t - t0) / (t1 - t0);
        Some((t, Outcome::UpperBodyFell { t, lean }))
    }
}

impl LeanModel {
    /// The model of a bicycle with a leaning rider, after checking its parameters
    /// ([`RiderLeanParameters::check`]); the rear wheel must roll (a skate is refused, `rR`).
    pub fn new(p: &RiderLeanParameters) -> Result<Self> {
        p.check()?;
        if p.bicycle.r_r <= 0.0 {
            return Err(Error::InvalidParameter {
                field: "rR".into(),
                value: p.bicycle.r_r,
                rule: "the leaning rider's model needs a rolling rear wheel (rR > 0)".into(),
            });
        }
        let model = Model::new(&p.bicycle)?;
        let g = &p.upper_body;
        let b = &p.bicycle;
        Ok(LeanModel {
            model,
            parameters: *p,
            mass: g.m,
            inertia: Matrix3::new(g.i_xx, 0.0, g.i_xz, 0.0, g.i_yy, 0.0, g.i_xz, 0.0, g.i_zz),
            hinge_in_b: Vector3::new(g.x - b.x_b, 0.0, g.z_hinge - b.z_b),
            centre_in_g: Vector3::new(0.0, 0.0, g.z - g.z_hinge),
        })
    }

    /// The four bodies' model (the bicycle with the rider's lower body).
    pub fn bicycle(&self) -> &Model {
        &self.model
    }

    /// The parameters it was built from.
    pub fn parameters(&self) -> &RiderLeanParameters {
        &self.parameters
    }

    /// G's rotation (G axes → world), centre (world), angular velocity (G axes) and centre's
    /// velocity (world) in a state.
    fn upper_body<T: Real>(
        &self,
        state: &LeanState<T>,
    ) -> (Matrix3<T>, Vector3<T>, Vector3<T>, Vector3<T>) {
        let s = &state.bicycle;
        let rb = rotation::matrix(
            s.q[6 * REAR_FRAME + 3],
            s.q[6 * REAR_FRAME + 4],
            s.q[6 * REAR_FRAME + 5],
        );
        let rg = rb * rotation::axis_angle(&Vector3::x(), state.lean);
        let h: Vector3<T> = self.hinge_in_b.cast();
        let cg: Vector3<T> = self.centre_in_g.cast();
        let w_b = s.angular_velocity(REAR_FRAME);
        let w_g = rg.transpose() * (rb * w_b) + Vector3::x() * state.lean_rate;
        let x = s.position(REAR_FRAME) + rb * h + rg * cg;
        let v = s.velocity(REAR_FRAME) + rb * w_b.cross(&h) + rg * w_g.cross(&cg);
        (rg, x, w_g, v)
    }

    /// The five bodies' poses in a state: the four of [`Model::body_poses`] and the upper
    /// body G's last (its origin its centre of mass, its axes turned from the rear frame's by
    /// the hinge angle about their x axis).
    pub fn body_poses(&self, state: &LeanState<f64>) -> [BodyPose; BODIES + 1] {
        let four = self.model.body_poses(&state.bicycle);
        let (rotation, position, _, _) = self.upper_body(state);
        std::array::from_fn(|k| {
            if k < BODIES {
                four[k]
            } else {
                BodyPose { position, rotation }
            }
        })
    }

    /// The hinge line's point nearest G's centre of mass (straight above or below it in the
    /// reference configuration), in G's axes from that centre \[m\].
    pub fn hinge_in_upper_body(&self) -> Vector3<f64> {
        -self.centre_in_g
    }

    /// Total mechanical energy: the four bodies', G's kinetic and potential energy and the
    /// hinge spring's ½ k φ_r² \[J\].
    pub fn energy<T: Real>(&self, state: &LeanState<T>) -> T {
        let (_, x, w, v) = self.upper_body(state);
        let half: T = c(0.5);
        let m: T = c(self.mass);
        let inertia: Matrix3<T> = self.inertia.cast();
        let k: T = c(self.parameters.upper_body.stiffness);
        self.model.energy(&state.bicycle) + half * (m * v.norm_squared() + w.dot(&(inertia * w)))
            - m * c::<T>(self.parameters.bicycle.g) * x.z
            + half * k * state.lean * state.lean
    }

    /// ẋ = f(x, τ) of the five bodies: the four bodies' rates, the hinge's acceleration and the
    /// ground forces, with the rider's lean and steer torques `inputs` and the torque
    /// `hinge_torque` of the rider's upper body about the hinge (on G, its reaction on B),
    /// generic over the scalar. Allocation-free.
    pub fn forward<T: Real>(
        &self,
        state: &LeanState<T>,
        inputs: &Inputs<T>,
        hinge_torque: T,
    ) -> Result<LeanRates<T>> {
        let m = &self.model;
        let s = &state.bicycle;
        let angles = Angles::new(&s.q);
        let poses = Poses::from_angles(&s.q, &angles);
        let (tree, _) = m.tree(&poses, &s.u);
        let applied4 = m.applied(&angles, &poses, &tree.omega, inputs);
        let rolling = m.roll_on_rear_wheel(&poses, &tree);

        // G's tree map and bias over [w'; φ̇_r].
        let ex = Vector3::<T>::x();
        let turn = rotation::axis_angle(&ex, state.lean);
        let a = turn.transpose();
        let rb = poses.rot[REAR_FRAME];
        let rg = rb * turn;
        let h: Vector3<T> = self.hinge_in_b.cast();
        let cg: Vector3<T> = self.centre_in_g.cast();
        let w_b = tree.omega[REAR_FRAME];
        let x_g = a * w_b;
        let w_g = x_g + ex * state.lean_rate;
        let jb = rolling.jac[REAR_FRAME];
        let jb_v = jb.fixed_rows::<3>(0).into_owned();
        let jb_w = jb.fixed_rows::<3>(3).into_owned();
        let jg_w = a * jb_w;
        let rb_h = rb * rotation::skew(&h);
        let rg_c = rg * rotation::skew(&cg);
        let mut jg = SMatrix::<T, 6, LEAN_TREE>::zeros();
        jg.fixed_view_mut::<3, ROLLING_TREE>(0, 0)
            .copy_from(&(jb_v - rb_h * jb_w - rg_c * jg_w));
        jg.fixed_view_mut::<3, ROLLING_TREE>(3, 0).copy_from(&jg_w);
        jg.fixed_view_mut::<3, 1>(0, HINGE_RATE)
            .copy_from(&(-(rg_c * ex)));
        jg.fixed_view_mut::<3, 1>(3, HINGE_RATE).copy_from(&ex);
        let cb = rolling.bias[REAR_FRAME];
        let cb_v = cb.fixed_rows::<3>(0).into_owned();
        let cb_w = cb.fixed_rows::<3>(3).into_owned();
        let cg_w = a * cb_w + x_g.cross(&ex) * state.lean_rate;
        let cg_v = cb_v - rb_h * cb_w
            + rb * w_b.cross(&w_b.cross(&h))
            + rg * (cg_w.cross(&cg) + w_g.cross(&w_g.cross(&cg)));

        // Every body's map over the seven speeds, and its forces.
        let hinge = hinge_torque
            - c::<T>(self.parameters.upper_body.stiffness) * state.lean
            - c::<T>(self.parameters.upper_body.damping) * state.lean_rate;
        let inertia_g: Matrix3<T> = self.inertia.cast();
        let mass_g: T = c(self.mass);
        let mut applied = [(Vector3::zeros(), Vector3::zeros()); BODIES + 1];
        applied[..BODIES].copy_from_slice(&applied4);
        applied[REAR_FRAME].1 -= ex * hinge;
        applied[BODIES] = (
            Vector3::new(
                T::zero(),
                T::zero(),
                mass_g * c::<T>(self.parameters.bicycle.g),
            ),
            -w_g.cross(&(inertia_g * w_g)) + ex * hinge,
        );
        let mut jac = [SMatrix::<T, 6, LEAN_TREE>::zeros(); BODIES + 1];
        let mut bias = [SVector::<T, 6>::zeros(); BODIES + 1];
        for k in 0..BODIES {
            jac[k]
                .fixed_columns_mut::<ROLLING_TREE>(0)
                .copy_from(&rolling.jac[k]);
            bias[k] = rolling.bias[k];
        }
        jac[BODIES] = jg;
        bias[BODIES] = SVector::<T, 6>::new(cg_v.x, cg_v.y, cg_v.z, cg_w.x, cg_w.y, cg_w.z);
        let masses: [(T, Matrix3<T>); BODIES + 1] = std::array::from_fn(|k| {
            if k < BODIES {
                let body = &m.bodies.body[k];
                (c(body.mass), body.inertia.cast())
            } else {
                (mass_g, inertia_g)
            }
        });

        let mut mass = SMatrix::<T, LEAN_TREE, LEAN_TREE>::zeros();
        let mut force = SVector::<T, LEAN_TREE>::zeros();
        for k in 0..=BODIES {
            let (mk, ik) = masses[k];
            let (f, torque) = applied[k];
            let fv = f - bias[k].fixed_rows::<3>(0) * mk;
            let fw = torque - ik * bias[k].fixed_rows::<3>(3);
            Reduced {
                mass: &mut mass,
                force: &mut force,
                jac: &jac[k],
                m: mk,
                inertia: ik,
                generalized: SVector::<T, 6>::new(fv.x, fv.y, fv.z, fw.x, fw.y, fw.z),
            }
            .add_body(k);
        }
        symmetrize(&mut mass);
        let (g6, gamma, frame) =
            m.contact_rows_in(FRONT_CONTACT, &poses, &tree, &rolling.jac, &rolling.bias);
        let mut g = SMatrix::<T, 3, LEAN_TREE>::zeros();
        g.fixed_columns_mut::<ROLLING_TREE>(0).copy_from(&g6);
        let solved = saddle::solve(&mass, &g, &force, &gamma, m.augmentation)
            .or_else(|| saddle::solve(&mass, &g, &force, &gamma, m.fallback_augmentation()));
        let Some((w_dot, nu)) = solved else {
            return Err(Error::SingularDynamics {
                context: "the leaning rider's saddle-point matrix [TᵀMT Gᵀ; G 0] is singular"
                    .into(),
            });
        };
        if !w_dot.iter().chain(nu.iter()).all(|v| v.is_finite()) {
            return Err(Error::NonFinite {
                context: "the leaning rider's equations of motion: the accelerations overflow"
                    .into(),
            });
        }

        let mut u_dot = SVector::<T, SPEEDS>::zeros();
        let mut on_rear = Vector3::zeros();
        for k in 0..=BODIES {
            let acceleration = jac[k] * w_dot + bias[k];
            if k < BODIES {
                u_dot.fixed_rows_mut::<6>(6 * k).copy_from(&acceleration);
            }
            on_rear += acceleration.fixed_rows::<3>(0) * masses[k].0 - applied[k].0;
        }
        let front = m.contact_force(FRONT_CONTACT, &nu);
        on_rear -= frame.longitudinal * front.longitudinal + frame.lateral * front.lateral
            - Vector3::z() * front.normal;
        let [f, n] = rolling.rear_directions;
        let rear = ContactForce {
            normal: -on_rear.z,
            longitudinal: on_rear.dot(&f),
            lateral: on_rear.dot(&n),
        };
        Ok(LeanRates {
            bicycle: StateRates {
                q_dot: coordinate_rates(&angles, &s.u),
                u_dot,
                contact: [rear, front],
            },
            lean_acceleration: w_dot[HINGE_RATE],
        })
    }

    /// A consistent state: the four bodies' [`Model::initial_state`] and the hinge's angle
    /// φ_r \[rad\] and rate φ̇_r [rad/s] relative to the rear frame.
    pub fn initial_state(
        &self,
        ic: &InitialConditions,
        lean: f64,
        lean_rate: f64,
    ) -> Result<LeanState<f64>> {
        for (what, value) in [("rider lean", lean), ("rider lean rate", lean_rate)] {
            if !value.is_finite() {
                return Err(Error::InvalidArgument {
                    what: "initial conditions",
                    rule: format!("{what} must be a finite number, got {value}"),
                });
            }
        }
        Ok(LeanState {
            bicycle: self.model.initial_state(ic)?,
            lean,
            lean_rate,
        })
    }

    /// The motion from `start` under `settings` (integrator, duration, fall angle, the rider's
    /// steer and lean torques, projection, lift-off, sampling, progress and stop, exactly as
    /// [`crate::simulate`]) with the rider's torque about the hinge: the one stepping loop of the
    /// four bodies, with the hinge's angle and rate carried and [`Outcome::UpperBodyFell`] as
    /// one more event; the energy balance counts the hinge torque's and damper's power.
    /// Refused before any step as [`crate::simulate`] refuses (an RK4 step beyond the stability
    /// bound of the leaning rider's fastest mode among them), and a hinge limit that is not
    /// positive.
    pub fn simulate(
        &self,
        start: &LeanState<f64>,
        settings: &SimulationSettings,
        forcing: &LeanForcing<'_>,
    ) -> Result<LeanSimulation> {
        settings.validate()?;
        if forcing.hinge_limit.is_nan() || forcing.hinge_limit <= 0.0 {
            return Err(Error::InvalidArgument {
                what: "hinge_limit",
                rule: format!("must be positive, got {}", forcing.hinge_limit),
            });
        }
        if !(start.bicycle.is_finite() && start.lean.is_finite() && start.lean_rate.is_finite()) {
            return Err(Error::NonFiniteState { t: 0.0 });
        }
        if let Integrator::Rk4 { dt } = settings.integrator {
            let speed = self.model.speed(&start.bicycle);
            let fastest = self.eigenvalues(speed).ok().and_then(|l| {
                l.into_iter()
                    .filter(|z| z.re.is_finite() && z.im.is_finite())
                    .max_by(|a, b| crate::math::norm(a).total_cmp(&crate::math::norm(b)))
            });
            check_rk4_mode(fastest, speed, dt)?;
        }
        let ode = LeanOde {
            model: self,
            steer_torque: settings.steer_torque.as_ref(),
            lean_torque: settings.lean_torque.as_ref(),
            hinge_torque: forcing.hinge_torque,
            hinge_limit: forcing.hinge_limit,
        };
        let run = run_mechanism(&ode, *start, settings)?;
        Ok(LeanSimulation {
            simulation: run.simulation,
            rider: run.records,
            final_state: run.final_state,
        })
    }

    /// The five bodies' poses at a recorded [`Sample`] of [`LeanModel::simulate`] and the hinge
    /// angle `rider_lean` \[rad\] recorded with it ([`LeanSimulation::rider`]), so that a run can
    /// be animated from its samples alone (as [`Model::sample_poses`]).
    pub fn sample_poses(&self, sample: &Sample, rider_lean: f64) -> [BodyPose; BODIES + 1] {
        let state = LeanState {
            bicycle: State {
                q: self.model.sample_coordinates(sample),
                u: SVector::zeros(),
            },
            lean: rider_lean,
            lean_rate: 0.0,
        };
        self.body_poses(&state)
    }

    /// The consistent state with x = [φ, δ, φ_r, φ̇, δ̇, φ̇_r] at forward speed `speed`: the
    /// four bodies' [`Model::reduced_state`] of [φ, δ, φ̇, δ̇] (the hinge touches no
    /// constraint) and the hinge's angle and rate.
    pub fn reduced_state<T: Real>(&self, x: &SVector<T, 6>, speed: T) -> Result<LeanState<T>> {
        let bicycle = self
            .model
            .reduced_state(&Vector4::new(x[0], x[1], x[3], x[4]), speed)?;
        Ok(LeanState {
            bicycle,
            lean: x[2],
            lean_rate: x[5],
        })
    }

    /// ẋ of x = [φ, δ, φ_r, φ̇, δ̇, φ̇_r] at the reduced state of [`LeanModel::reduced_state`],
    /// forced by `inputs` and the hinge torque.
    pub fn lean_field<T: Real>(
        &self,
        x: &SVector<T, 6>,
        speed: f64,
        inputs: &Inputs<T>,
        hinge_torque: T,
    ) -> Result<SVector<T, 6>> {
        let state = self.reduced_state(x, c(speed))?;
        let d = self.forward(&state, inputs, hinge_torque)?;
        let [lean, steer] = self
            .model
            .lean_steer_accelerations(&state.bicycle, &d.bicycle);
        Ok(SVector::<T, 6>::from_column_slice(&[
            state.bicycle.lean_rate(),
            self.model.steer_rate(&state.bicycle),
            state.lean_rate,
            lean,
            steer,
            d.lean_acceleration,
        ]))
    }

    /// The eigenvalues of [`LeanModel::linearize`]'s A at `speed` (faer's general eigensolver,
    /// not certified), sorted by decreasing real part: the leaning rider's modes.
    pub fn eigenvalues(&self, speed: f64) -> Result<Vec<Complex<f64>>> {
        let (a, _) = self.linearize(speed)?;
        let mut values = crate::analysis::comparison::general_eigenvalues(&a)?;
        values.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        Ok(values)
    }

    /// The exact linearization about upright straight running at `speed`: A (6 × 6) on
    /// [φ, δ, φ_r, φ̇, δ̇, φ̇_r] and B (6 × 3) on the inputs [T_φ, T_δ, T_r] (lean torque on the
    /// rear frame, steer torque, the upper body's hinge torque), by dual numbers through
    /// [`LeanModel::forward`] (no derivative written by hand).
    pub fn linearize(&self, speed: f64) -> Result<(SMatrix<f64, 6, 6>, SMatrix<f64, 6, 3>)> {
        if !speed.is_finite() {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!("must be a finite number of m/s, got {speed}"),
            });
        }
        let a = jacobian(&LeanField { model: self, speed }, &SVector::zeros())?;
        let mut b = SMatrix::<f64, 6, 3>::zeros();
        let x = SVector::<Dual64, 6>::zeros();
        for j in 0..3 {
            let seed = |i: usize| Dual64::new(0.0, if i == j { 1.0 } else { 0.0 });
            let inputs = Inputs {
                lean_torque: seed(0),
                steer_torque: seed(1),
            };
            let f = self.lean_field(&x, speed, &inputs, seed(2))?;
            for i in 0..6 {
                b[(i, j)] = f[i].eps;
            }
        }
        Ok((a, b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> LeanModel {
        LeanModel::new(&RiderLeanParameters::browser_jason()).unwrap()
    }

    /// Upright running is an equilibrium of the five bodies, and the ground carries them all.
    #[test]
    fn upright_running_is_an_equilibrium() {
        let lean = model();
        let x = SVector::<f64, 6>::zeros();
        let state = lean.reduced_state(&x, 5.0).unwrap();
        let d = lean.forward(&state, &Inputs::default(), 0.0).unwrap();
        assert!(d.bicycle.u_dot.amax() < 1e-10, "{}", d.bicycle.u_dot.amax());
        assert!(d.lean_acceleration.abs() < 1e-10);
        let p = lean.parameters();
        let weight =
            (p.bicycle.m_r + p.bicycle.m_b + p.bicycle.m_h + p.bicycle.m_f + p.upper_body.m)
                * p.bicycle.g;
        let [rear, front] = d.bicycle.contact;
        assert!((rear.normal + front.normal - weight).abs() < 1e-9 * weight);
    }

    fn settings(duration: f64) -> SimulationSettings {
        SimulationSettings {
            integrator: Integrator::adaptive(1e-11),
            duration,
            stop_on_lift_off: false,
            ..SimulationSettings::default()
        }
    }

    /// Energy is conserved with the hinge free and undamped: the upper body, an inverted
    /// pendulum on the running bicycle, falls right round its hinge (φ_r past 5 rad in 1.2 s,
    /// the bicycle leaning 0.55 rad; a few hundred joules of G's height become motion), and
    /// the total energy stays within 1e-12 of itself (measured: 6e-14), through the one
    /// stepping loop of the four bodies.
    #[test]
    fn energy_is_conserved_with_a_free_hinge() {
        let lean = model();
        let start = lean
            .initial_state(&InitialConditions::upright(5.0), 0.0, 0.2)
            .unwrap();
        let forcing = LeanForcing {
            hinge_limit: f64::INFINITY,
            ..LeanForcing::default()
        };
        let run = lean.simulate(&start, &settings(1.2), &forcing).unwrap();
        assert_eq!(run.simulation.outcome, Outcome::Completed);
        let samples = &run.simulation.samples;
        assert_eq!(samples.len(), run.rider.len());
        let e0 = samples[0].energy;
        let drift = samples
            .iter()
            .map(|s| (s.energy - e0).abs())
            .fold(0.0, f64::max);
        let last = samples.last().unwrap();
        assert!((last.t - 1.2).abs() < 1e-12);
        assert!(run.final_state.lean.abs() > 5.0, "{}", run.final_state.lean);
        assert_eq!(run.rider.last().unwrap()[0], run.final_state.lean);
        assert!(drift < 1e-12 * e0.abs(), "drift {drift:e} of {e0}");
        let residuals = lean.bicycle().residuals(&run.final_state.bicycle);
        assert!(residuals.max_holonomic() < 1e-12 && residuals.max_velocity() < 1e-12);
    }

    /// With the hinge limit the same run ends where the upper body lies across the bicycle,
    /// the crossing located within its step.
    #[test]
    fn the_upper_body_falling_ends_the_run() {
        let lean = model();
        let start = lean
            .initial_state(&InitialConditions::upright(5.0), 0.0, 0.2)
            .unwrap();
        let run = lean
            .simulate(&start, &settings(1.2), &LeanForcing::default())
            .unwrap();
        let Outcome::UpperBodyFell { t, lean: at } = run.simulation.outcome else {
            panic!("{:?}", run.simulation.outcome)
        };
        assert!(t < 1.2 && (at.abs() - HINGE_LIMIT).abs() < 1e-2, "{t} {at}");
    }

    /// With the damper the energy only falls, by the damper's work: the run's energy balance
    /// (the one loop's check, which counts the damper's power) holds.
    #[test]
    fn a_damped_hinge_takes_energy() {
        let mut p = RiderLeanParameters::browser_jason();
        (p.upper_body.stiffness, p.upper_body.damping) = (800.0, 50.0);
        let lean = LeanModel::new(&p).unwrap();
        let start = lean
            .initial_state(&InitialConditions::upright(5.0), 0.0, 0.2)
            .unwrap();
        let run = lean
            .simulate(&start, &settings(0.5), &LeanForcing::default())
            .unwrap();
        let samples = &run.simulation.samples;
        let first = samples[0].energy;
        let last = samples.last().unwrap().energy;
        assert!(last < first - 1e-3, "{first} → {last}");
        // The damper's work, ∫ c φ̇_r² dt by the trapezoidal rule, is the energy lost.
        let mut work = 0.0;
        for k in 1..samples.len() {
            let (a, b) = (run.rider[k - 1][1], run.rider[k][1]);
            work += 0.5 * 50.0 * (a * a + b * b) * (samples[k].t - samples[k - 1].t);
        }
        assert!(
            ((first - last) - work).abs() < 1e-3 * work,
            "{} vs {work}",
            first - last
        );
    }

    /// The poses from a sample and the hinge angle are those of the state.
    #[test]
    fn sample_poses_are_the_states() {
        let lean = model();
        let start = lean
            .initial_state(&InitialConditions::upright(5.0), 0.1, 0.3)
            .unwrap();
        let run = lean
            .simulate(&start, &settings(0.3), &LeanForcing::default())
            .unwrap();
        let from_sample = lean.sample_poses(
            run.simulation.samples.last().unwrap(),
            run.rider.last().unwrap()[0],
        );
        let exact = lean.body_poses(&run.final_state);
        for (a, b) in from_sample.iter().zip(&exact) {
            assert!((a.position - b.position).amax() < 1e-9);
            assert!((a.rotation - b.rotation).amax() < 1e-9);
        }
    }

    /// A lean torque on the upper body alone: equal and opposite on B, so the whole bicycle's
    /// angular momentum about the ground line changes only through the ground's forces; G leans
    /// right and the rear frame left at first.
    #[test]
    fn hinge_torque_leans_the_rider_right_and_the_bicycle_left() {
        let lean = model();
        let state = lean.reduced_state(&SVector::zeros(), 5.0).unwrap();
        let d = lean.forward(&state, &Inputs::default(), 10.0).unwrap();
        assert!(d.lean_acceleration > 0.0);
        let [lean_acceleration, _] = lean
            .model
            .lean_steer_accelerations(&state.bicycle, &d.bicycle);
        assert!(lean_acceleration < 0.0);
    }
}
