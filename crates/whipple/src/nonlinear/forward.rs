//! Forward dynamics ẋ = f(x, τ) in named stages, each reading only what earlier stages
//! produced:
//!
//! 1. **poses** ([`super::poses`]): rotation matrices and positions of the four bodies from q;
//! 2. **tree** ([`super::tree`]): the joint rows eliminated exactly by the tree map
//!    `u_i = J_i(q) w`, `u̇_i = J_i ẇ + c_i` in the nine tree speeds of [`super::topology`];
//! 3. **forces**: gravity, gyroscopic torques `−ω × Iω`, rider torques (steer, lean);
//! 4. **constraint rows**: the contact rows `D_c` (normal, two rolling per contact) and their γ
//!    in the tree speeds. For a rolling rear wheel (radius > 0) its three rows are first solved
//!    for ν exactly (`Model::roll_on_rear_wheel`: ν̇ = (E R_B)ᵀ(γ̃ − G' ẇ') with the orthonormal
//!    contact directions E), a new map in the six tree speeds `w' = [ω_B, δ̇, σ_R, σ_F]`,
//!    leaving the front contact's three rows; a rear skate keeps all nine speeds and six rows;
//! 5. **solve**: the saddle-point system `[M Dᵀ; D 0][u̇; μ] = [f; γ]` projected onto the
//!    remaining null space, `[TᵀMT  Gᵀ; G  0][ẇ; −μ_c] = [Tᵀ(f − M c); γ_c − D_c c]` with
//!    `G = D_c T`: 9 × 9 (or 15 × 15) instead of 45 × 45, solved at once for the accelerations
//!    and the contact multipliers by UᵀDU factors (Cholesky without square roots) of TᵀMT and
//!    of the Schur complement ([`super::saddle`]; TᵀMT assembled in [`super::assembly`]).
//!    `TᵀMT` may be singular (massless wheels): it is then augmented by ρGᵀG, the
//!    saddle-point matrix stays regular whenever the bicycle has inertia in every direction
//!    the constraints leave free, and M⁻¹ is never formed. The eliminated rear multipliers are
//!    recovered from the balance of linear momentum of the four bodies (the joint forces are
//!    internal): the ground's force on the rear wheel is `Σ m_i a_i − Σ f_i` minus the front
//!    contact force.
//!
//! [`Model::forward_reference`] (in [`super::reference`]) solves the full 45 × 45 system with
//! every row (no tree), as a check of the structured path.

use crate::math::Real;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::Model;
use super::assembly::{Reduced, symmetrize};
use super::contact::{ContactFrame, LATERAL, LONGITUDINAL, NORMAL};
use super::poses::{Angles, Poses};
use super::rotation;
use super::saddle;
use super::state::{COORDINATES, SPEEDS, STATE_LEN, State};
use super::topology::{
    BODIES, CONTACT_COUNT, FRONT_CONTACT, FRONT_FRAME, REAR_CONTACT, REAR_FRAME,
};
use super::tree::{Tree, speeds_of};
use crate::error::{Error, Result};

/// Applied forces per body: world force, body-axes torque.
pub(crate) type Applied<T> = [(Vector3<T>, Vector3<T>); BODIES];

#[inline]
fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

/// Rider inputs: torques [N m], benchmark signs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs<T: Real> {
    /// T_φ: lean torque, acting on the rear frame about the horizontal line of its heading
    /// (its generalized force is exactly the lean torque of the benchmark).
    pub lean_torque: T,
    /// T_δ: steer torque, acting on the front frame about the steer axis, and its reaction on
    /// the rear frame.
    pub steer_torque: T,
}

impl<T: Real> Default for Inputs<T> {
    fn default() -> Self {
        Inputs {
            lean_torque: T::zero(),
            steer_torque: T::zero(),
        }
    }
}

/// The force of the ground on one wheel at its contact point, in the contact's directions \[N\].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactForce<T> {
    /// Normal force, upward positive. Negative means the ground would have to pull: the wheel
    /// would lift off.
    pub normal: T,
    /// Friction along the wheel's rolling direction (forward positive); zero for a skate.
    pub longitudinal: T,
    /// Friction across the wheel (to the right of the rolling direction positive).
    pub lateral: T,
}

/// The result of [`Model::forward`]: the rates of the state ẋ = [q̇; u̇] and the ground forces
/// that come with them.
#[derive(Debug, Clone, Copy)]
pub struct StateRates<T: Real> {
    /// q̇: coordinate rates.
    pub q_dot: SVector<T, COORDINATES>,
    /// u̇: accelerations (world translational, body angular).
    pub u_dot: SVector<T, SPEEDS>,
    /// Ground forces on the rear and front wheels.
    pub contact: [ContactForce<T>; 2],
}

impl<T: Real> StateRates<T> {
    /// The first-order derivative `[q̇; u̇]`.
    pub fn to_vector(self) -> SVector<T, STATE_LEN> {
        let mut y = SVector::<T, STATE_LEN>::zeros();
        y.fixed_rows_mut::<COORDINATES>(0).copy_from(&self.q_dot);
        y.fixed_rows_mut::<SPEEDS>(COORDINATES)
            .copy_from(&self.u_dot);
        y
    }
}

impl Model {
    /// ẋ = f(x, τ): accelerations, coordinate rates and contact forces of the constrained
    /// multibody bicycle, generic over the scalar (f64 or dual numbers for exact Jacobians).
    /// Allocation-free.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::nonlinear::Inputs;
    /// use whipple::{InitialConditions, Model};
    /// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
    /// let state = model.initial_state(&InitialConditions::upright(5.0))?;
    /// let d = model.forward(&state, &Inputs::default())?;
    /// assert!(d.u_dot.amax() < 1e-12);                    // upright running is an equilibrium
    /// assert!((d.contact[0].normal + d.contact[1].normal - 94.0 * 9.81).abs() < 1e-9);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn forward<T: Real>(&self, state: &State<T>, inputs: &Inputs<T>) -> Result<StateRates<T>> {
        let angles = Angles::new(&state.q);
        let poses = Poses::from_angles(&state.q, &angles);
        let (tree, _) = self.tree(&poses, &state.u);
        let applied = self.applied(&angles, &poses, &tree.omega, inputs);
        let (u_dot, contact) = if self.contacts[REAR_CONTACT].is_skate() {
            self.solve_general(&poses, &tree, &applied)?
        } else {
            self.solve_rolling(&poses, &tree, &applied)?
        };
        Ok(StateRates {
            q_dot: coordinate_rates(&angles, &state.u),
            u_dot,
            contact,
        })
    }

    /// Stage 3: applied forces per body (world force, body-axes torque).
    pub(crate) fn applied<T: Real>(
        &self,
        angles: &Angles<T>,
        poses: &Poses<T>,
        omega: &[Vector3<T>; BODIES],
        inputs: &Inputs<T>,
    ) -> Applied<T> {
        let g: T = c(self.parameters.g);
        let mut out = [(Vector3::zeros(), Vector3::zeros()); BODIES];
        for k in 0..BODIES {
            let body = &self.bodies.body[k];
            let inertia: Matrix3<T> = body.inertia.cast();
            let force = Vector3::new(T::zero(), T::zero(), g * c(body.mass));
            out[k] = (force, -omega[k].cross(&(inertia * omega[k])));
        }
        let s: Vector3<T> = self.bodies.geometry.steer_axis.cast();
        let s_in_b = poses.rot[REAR_FRAME].transpose() * (poses.rot[FRONT_FRAME] * s);
        out[FRONT_FRAME].1 += s * inputs.steer_torque;
        out[REAR_FRAME].1 -= s_in_b * inputs.steer_torque;
        let pitch = angles.0[REAR_FRAME][2];
        let (sp, cp) = (pitch.sin, pitch.cos);
        out[REAR_FRAME].1 += Vector3::new(cp, T::zero(), sp) * inputs.lean_torque;
        out
    }

    /// Stages 4–5 with all six contact rows in the nine tree speeds (any bicycle, skates
    /// included).
    fn solve_general<T: Real>(
        &self,
        poses: &Poses<T>,
        tree: &Tree<T>,
        applied: &Applied<T>,
    ) -> Result<(SVector<T, SPEEDS>, [ContactForce<T>; 2])> {
        let jac = tree.jacobians();
        let (g, gamma) = self.contact_rows(poses, tree, &jac, &tree.bias);
        let (u_dot, nu) = self.solve_saddle(&jac, &tree.bias, applied, &g, &gamma)?;
        let contact =
            std::array::from_fn(|i| self.contact_force(i, &nu.fixed_rows::<3>(3 * i).into_owned()));
        Ok((u_dot, contact))
    }

    /// Stages 4–5 for a rolling rear wheel: its three rows are solved for ν exactly
    /// ([`Model::roll_on_rear_wheel`]), leaving the front contact's three rows in six tree
    /// speeds; the rear contact force follows from the balance of linear momentum of the whole
    /// bicycle (the joint forces are internal).
    fn solve_rolling<T: Real>(
        &self,
        poses: &Poses<T>,
        tree: &Tree<T>,
        applied: &Applied<T>,
    ) -> Result<(SVector<T, SPEEDS>, [ContactForce<T>; 2])> {
        let rolling = self.roll_on_rear_wheel(poses, tree);
        let [f, n] = rolling.rear_directions;
        let (g, gamma, frame) =
            self.contact_rows_in(FRONT_CONTACT, poses, tree, &rolling.jac, &rolling.bias);
        let (u_dot, nu) = self.solve_saddle(&rolling.jac, &rolling.bias, applied, &g, &gamma)?;
        let front = self.contact_force(FRONT_CONTACT, &nu);
        let on_front = frame.longitudinal * front.longitudinal + frame.lateral * front.lateral
            - Vector3::z() * front.normal;
        let mut on_rear = -on_front;
        for (k, body) in self.bodies.body.iter().enumerate() {
            let m: T = c(body.mass);
            on_rear += u_dot.fixed_rows::<3>(6 * k) * m - applied[k].0;
        }
        let rear = ContactForce {
            normal: -on_rear.z,
            longitudinal: on_rear.dot(&f),
            lateral: on_rear.dot(&n),
        };
        Ok((u_dot, [rear, front]))
    }

    /// Every contact's three rows in the tree speeds of `jac` (contact i in rows 3i..3i+3) and
    /// their right-hand side `γ − D c`.
    pub(crate) fn contact_rows<T: Real, const N: usize>(
        &self,
        poses: &Poses<T>,
        tree: &Tree<T>,
        jac: &[SMatrix<T, 6, N>; BODIES],
        bias: &[SVector<T, 6>; BODIES],
    ) -> (SMatrix<T, 6, N>, SVector<T, 6>) {
        let mut g = SMatrix::<T, 6, N>::zeros();
        let mut gamma = SVector::<T, 6>::zeros();
        for i in 0..CONTACT_COUNT {
            let (gi, ci, _) = self.contact_rows_in(i, poses, tree, jac, bias);
            g.fixed_rows_mut::<3>(3 * i).copy_from(&gi);
            gamma.fixed_rows_mut::<3>(3 * i).copy_from(&ci);
        }
        (g, gamma)
    }

    /// Contact i's three rows in the tree speeds of `jac`, their right-hand side `γ − D c`,
    /// and the contact's directions.
    pub(crate) fn contact_rows_in<T: Real, const N: usize>(
        &self,
        i: usize,
        poses: &Poses<T>,
        tree: &Tree<T>,
        jac: &[SMatrix<T, 6, N>; BODIES],
        bias: &[SVector<T, 6>; BODIES],
    ) -> (SMatrix<T, 3, N>, SVector<T, 3>, ContactFrame<T>) {
        let contact = &self.contacts[i];
        let (wheel, frame) = (contact.wheel, contact.frame);
        let rows = contact.rows(
            poses,
            &tree.velocity[wheel],
            &tree.omega[wheel],
            &tree.omega[frame],
        );
        let mut g = rows.wheel * jac[wheel];
        let mut gamma = rows.gamma - rows.wheel * bias[wheel];
        if contact.is_skate() {
            g += rows.frame * jac[frame];
            gamma -= rows.frame * bias[frame];
        }
        (g, gamma, rows.contact_frame)
    }

    /// Contact i's force from its three multipliers `ν = −μ` (the multipliers act along
    /// `[f, n, e_z]`, e_z down; a skate's first row is its spin lock, not a force).
    pub(crate) fn contact_force<T: Real>(&self, i: usize, nu: &SVector<T, 3>) -> ContactForce<T> {
        ContactForce {
            normal: nu[NORMAL],
            longitudinal: if self.contacts[i].is_skate() {
                T::zero()
            } else {
                -nu[LONGITUDINAL]
            },
            lateral: -nu[LATERAL],
        }
    }

    /// Stage 5: the reduced mass matrix TᵀMT and forces Tᵀ(f − M c) over N tree speeds, the
    /// saddle-point solve `[TᵀMT Gᵀ; G 0][ẇ; ν] = [Tᵀ(f − Mc); γ̃]` with M contact rows, and
    /// `u̇ = J ẇ + c`.
    fn solve_saddle<T: Real, const N: usize, const M: usize>(
        &self,
        jac: &[SMatrix<T, 6, N>; BODIES],
        bias: &[SVector<T, 6>; BODIES],
        applied: &Applied<T>,
        g: &SMatrix<T, M, N>,
        gamma: &SVector<T, M>,
    ) -> Result<(SVector<T, SPEEDS>, SVector<T, M>)> {
        let mut mass = SMatrix::<T, N, N>::zeros();
        let mut force = SVector::<T, N>::zeros();
        for (k, (body, &(f, torque))) in self.bodies.body.iter().zip(applied).enumerate() {
            let m: T = c(body.mass);
            let inertia: Matrix3<T> = body.inertia.cast();
            let cv = bias[k].fixed_rows::<3>(0).into_owned();
            let cw = bias[k].fixed_rows::<3>(3).into_owned();
            let fv = f - cv * m;
            let fw = torque - inertia * cw;
            let mut share = Reduced {
                mass: &mut mass,
                force: &mut force,
                jac: &jac[k],
                m,
                inertia,
                generalized: SVector::<T, 6>::new(fv.x, fv.y, fv.z, fw.x, fw.y, fw.z),
            };
            share.add_body(k);
        }
        symmetrize(&mut mass);
        let solved = saddle::solve(&mass, g, &force, gamma, self.augmentation)
            .or_else(|| saddle::solve(&mass, g, &force, gamma, self.fallback_augmentation()));
        let Some((w_dot, nu)) = solved else {
            return Err(Error::SingularDynamics {
                context: "the saddle-point matrix [TᵀMT Gᵀ; G 0] is singular".into(),
            });
        };
        // A regular system whose solution overflows (speeds or torques far out of range) is
        // not singular: say what happened.
        if !w_dot.iter().chain(nu.iter()).all(|v| v.is_finite()) {
            return Err(Error::NonFinite {
                context: "the equations of motion: the accelerations overflow (speeds or \
                          torques out of range)"
                    .into(),
            });
        }
        let mut u_dot = speeds_of(jac, &w_dot);
        for (k, c) in bias.iter().enumerate() {
            let mut rows = u_dot.fixed_rows_mut::<6>(6 * k);
            rows += c;
        }
        Ok((u_dot, nu))
    }
}

/// q̇ from u, given the sines and cosines of q's angles: velocities as they are, angle rates
/// from body angular velocities.
#[inline]
pub(crate) fn coordinate_rates<T: Real>(
    angles: &Angles<T>,
    u: &SVector<T, SPEEDS>,
) -> SVector<T, COORDINATES> {
    let mut q_dot = SVector::<T, COORDINATES>::zeros();
    for k in 0..BODIES {
        q_dot
            .fixed_rows_mut::<3>(6 * k)
            .copy_from(&u.fixed_rows::<3>(6 * k));
        let omega = u.fixed_rows::<3>(6 * k + 3).into_owned();
        let [_, lean, pitch] = angles.0[k];
        let rates = rotation::body_to_rates_from_sin_cos(lean, pitch, &omega);
        q_dot.fixed_rows_mut::<3>(6 * k + 3).copy_from(&rates);
    }
    q_dot
}
