//! Forward dynamics: ẋ = f(x, τ), in named stages.
//!
//! 1. **poses**: rotation matrices and positions of the four bodies from q;
//! 2. **tree**: the joint rows are eliminated exactly by writing every body's speeds as
//!    `u_i = J_i(q) w` in nine tree speeds `w = [ν (rear hub velocity, rear frame axes),
//!    ω_B (rear frame), δ̇ (steer rate), σ_R, σ_F (wheel spin rates relative to their frames)]`,
//!    and `u̇_i = J_i ẇ + c_i` (c_i: centripetal and gyroscopic-coupling terms). Every `J_i w`
//!    satisfies the 15 joint velocity rows identically, so `T = [J_i]` spans their null space;
//! 3. **forces**: gravity, gyroscopic torques `−ω × Iω`, rider torques (steer, lean);
//! 4. **constraint rows**: the six contact rows `D_c` (two normal, four rolling) and their γ.
//!    For a rolling rear wheel (radius > 0) its three rows are solved for ν exactly first
//!    (`Model::roll_on_rear_wheel`: ν̇ = (E R_B)ᵀ(γ̃ − G' ẇ') with the orthonormal contact
//!    directions E), leaving six tree speeds `w' = [ω_B, δ̇, σ_R, σ_F]` and the front
//!    contact's three rows; a rear skate keeps all nine speeds and six rows;
//! 5. **solve**: the saddle-point system `[M Dᵀ; D 0][u̇; μ] = [f; γ]` projected onto the
//!    remaining null space, `[TᵀMT  Gᵀ; G  0][ẇ; −μ_c] = [Tᵀ(f − M c); γ_c − D_c c]` with
//!    `G = D_c T`: 9 × 9 (or 15 × 15) instead of 45 × 45, solved at once for the accelerations
//!    and the contact multipliers by UᵀDU factors (Cholesky without square roots) of TᵀMT and
//!    of the Schur complement (`saddle.rs`). `TᵀMT` may be singular (massless wheels): it is then augmented by ρGᵀG,
//!    the saddle-point matrix stays regular whenever the bicycle has inertia in every direction
//!    the constraints leave free, and M⁻¹ is never formed. The eliminated rear multipliers are
//!    recovered from the balance of linear momentum of the four bodies (the joint forces are
//!    internal): the ground's force on the rear wheel is `Σ m_i a_i − Σ f_i` minus the front
//!    contact force.
//!
//! [`Model::forward_reference`] solves the full 45 × 45 system with every row (no tree), as a
//! check of the structured path.

use nalgebra::{DMatrix, DVector, Matrix3, RealField, SMatrix, SVector, Vector3};

use super::bodies::{BODIES, FRONT_FRAME, FRONT_WHEEL, REAR_FRAME, REAR_WHEEL};
use super::contact::ContactFrame;
use super::rotation::SinCos;
use super::state::{State, COORDINATES, SPEEDS, STATE_LEN};
use super::Model;
use super::{rotation, saddle};
use crate::error::{Error, Result};

/// Number of tree speeds w.
pub(crate) const TREE: usize = 9;
/// Number of tree speeds once the rear wheel's rolling rows are solved for ν.
pub(crate) const ROLLING_TREE: usize = 6;
/// Holonomic rows: 3 joints × 5 + 2 contact heights.
pub const HOLONOMIC_ROWS: usize = 17;
/// All velocity rows: the 17 holonomic ones differentiated, then 4 rolling (non-holonomic).
pub const VELOCITY_ROWS: usize = 21;

/// Poses of the four bodies.
#[derive(Debug, Clone, Copy)]
pub struct Poses<T: RealField + Copy> {
    /// Rotation matrices, body → world.
    pub rot: [Matrix3<T>; BODIES],
    /// Positions of the body origins, world axes \[m\].
    pub pos: [Vector3<T>; BODIES],
}

impl<T: RealField + Copy> Poses<T> {
    /// Stage 1: poses from the coordinates.
    pub fn new(q: &SVector<T, COORDINATES>) -> Self {
        Self::from_angles(q, &Angles::new(q))
    }

    /// Poses from q and the sines and cosines of its angles.
    #[inline]
    pub(crate) fn from_angles(q: &SVector<T, COORDINATES>, angles: &Angles<T>) -> Self {
        Poses {
            rot: std::array::from_fn(|k| {
                let [yaw, lean, pitch] = angles.0[k];
                rotation::matrix_from_sin_cos(yaw, lean, pitch)
            }),
            pos: std::array::from_fn(|k| Vector3::new(q[6 * k], q[6 * k + 1], q[6 * k + 2])),
        }
    }
}

/// Sines and cosines of the twelve Euler angles (yaw, lean, pitch per body), computed once per
/// evaluation and shared by the rotation matrices and the coordinate rates.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Angles<T>(pub [[SinCos<T>; 3]; BODIES]);

impl<T: RealField + Copy> Angles<T> {
    #[inline]
    pub fn new(q: &SVector<T, COORDINATES>) -> Self {
        Angles(std::array::from_fn(|k| {
            std::array::from_fn(|i| SinCos::new(q[6 * k + 3 + i]))
        }))
    }
}

/// Rider inputs: torques [N m], benchmark signs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs<T: RealField + Copy> {
    /// T_φ: lean torque, acting on the rear frame about the horizontal line of its heading
    /// (its generalized force is exactly the lean torque of the benchmark).
    pub lean_torque: T,
    /// T_δ: steer torque, acting on the front frame about the steer axis, and its reaction on
    /// the rear frame.
    pub steer_torque: T,
}

impl<T: RealField + Copy> Default for Inputs<T> {
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

/// The result of [`Model::forward`].
#[derive(Debug, Clone, Copy)]
pub struct Derivatives<T: RealField + Copy> {
    /// q̇: coordinate rates.
    pub q_dot: SVector<T, COORDINATES>,
    /// u̇: accelerations (world translational, body angular).
    pub u_dot: SVector<T, SPEEDS>,
    /// Ground forces on the rear and front wheels.
    pub contact: [ContactForce<T>; 2],
}

impl<T: RealField + Copy> Derivatives<T> {
    /// The first-order derivative `[q̇; u̇]`.
    pub fn to_vector(&self) -> SVector<T, STATE_LEN> {
        let mut y = SVector::<T, STATE_LEN>::zeros();
        y.fixed_rows_mut::<COORDINATES>(0).copy_from(&self.q_dot);
        y.fixed_rows_mut::<SPEEDS>(COORDINATES)
            .copy_from(&self.u_dot);
        y
    }
}

/// Stage 2: the tree map u_i = J_i w, u̇_i = J_i ẇ + c_i, and the tree-consistent speeds.
///
/// J_i is stored in two parts: the columns of ν, which are the rear frame's rotation R_B in
/// every body's translation rows (and zero in its rotation rows), and the columns of the six
/// other tree speeds `[ω_B, δ̇, σ_R, σ_F]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tree<T: RealField + Copy> {
    /// R_B: the ν columns of every body's translation rows.
    pub hub: Matrix3<T>,
    /// The columns of `[ω_B, δ̇, σ_R, σ_F]`.
    pub rest: [SMatrix<T, 6, ROLLING_TREE>; BODIES],
    pub bias: [SVector<T, 6>; BODIES],
    /// Velocities of the origins (world).
    pub velocity: [Vector3<T>; BODIES],
    /// Angular velocities (body axes).
    pub omega: [Vector3<T>; BODIES],
}

impl<T: RealField + Copy> Tree<T> {
    /// Body k's whole J (6 × 9) over `w = [ν, ω_B, δ̇, σ_R, σ_F]`.
    pub fn jac(&self, k: usize) -> SMatrix<T, 6, TREE> {
        let mut j = SMatrix::<T, 6, TREE>::zeros();
        j.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.hub);
        j.fixed_columns_mut::<ROLLING_TREE>(3)
            .copy_from(&self.rest[k]);
        j
    }
}

/// Tree speeds that can move each body (the other columns of its J are zero): rear wheel
/// ν, ω_B, σ_R; rear frame ν, ω_B; front frame ν, ω_B, δ̇; front wheel ν, ω_B, δ̇, σ_F.
const COLUMNS_REAR_WHEEL: [usize; 7] = [0, 1, 2, 3, 4, 5, 7];
const COLUMNS_REAR_FRAME: [usize; 6] = [0, 1, 2, 3, 4, 5];
const COLUMNS_FRONT_FRAME: [usize; 7] = [0, 1, 2, 3, 4, 5, 6];
const COLUMNS_FRONT_WHEEL: [usize; 8] = [0, 1, 2, 3, 4, 5, 6, 8];
/// The same for the rolling tree `[ω_B, δ̇, σ_R, σ_F]`, where ω_B and σ_R move every body
/// (rolling on the rear wheel).
const ROLLING_REAR: [usize; 4] = [0, 1, 2, 4];
const ROLLING_FRONT_FRAME: [usize; 5] = [0, 1, 2, 3, 4];
const ROLLING_FRONT_WHEEL: [usize; 6] = [0, 1, 2, 3, 4, 5];

/// One body's share of the reduced mass matrix TᵀMT and forces Tᵀ(f − Mc), over N tree
/// speeds (9, or 6 for the rolling tree).
pub(crate) struct Reduced<'a, T: RealField + Copy, const N: usize> {
    pub mass: &'a mut SMatrix<T, N, N>,
    pub force: &'a mut SVector<T, N>,
    /// The body's J (6 × N).
    pub jac: &'a SMatrix<T, 6, N>,
    pub m: T,
    pub inertia: Matrix3<T>,
    /// f − M c of the body: world force, then body-axes torque.
    pub generalized: SVector<T, 6>,
}

impl<T: RealField + Copy, const N: usize> Reduced<'_, T, N> {
    /// Adds body k's share over the tree speeds that can move it.
    #[inline]
    pub fn add_body(&mut self, k: usize) {
        if N == TREE {
            match k {
                REAR_WHEEL => self.add(COLUMNS_REAR_WHEEL),
                REAR_FRAME => self.add(COLUMNS_REAR_FRAME),
                FRONT_FRAME => self.add(COLUMNS_FRONT_FRAME),
                _ => self.add(COLUMNS_FRONT_WHEEL),
            }
        } else if N == ROLLING_TREE {
            match k {
                REAR_WHEEL | REAR_FRAME => self.add(ROLLING_REAR),
                FRONT_FRAME => self.add(ROLLING_FRONT_FRAME),
                _ => self.add(ROLLING_FRONT_WHEEL),
            }
        } else {
            self.add(std::array::from_fn::<usize, N, _>(|i| i));
        }
    }

    /// Adds `Jᵀ diag(m I₃, I) J` (upper triangle) and `Jᵀ (f − Mc)` over the body's C
    /// non-zero columns of J, every entry one contiguous dot product of length 6.
    #[inline]
    fn add<const C: usize>(&mut self, cols: [usize; C]) {
        let j = SMatrix::<T, 6, C>::from_fn(|r, k| self.jac[(r, cols[k])]);
        let mut mj = j;
        for k in 0..C {
            let w = Vector3::new(j[(3, k)], j[(4, k)], j[(5, k)]);
            let iw = self.inertia * w;
            mj.set_column(
                k,
                &SVector::<T, 6>::new(
                    j[(0, k)] * self.m,
                    j[(1, k)] * self.m,
                    j[(2, k)] * self.m,
                    iw.x,
                    iw.y,
                    iw.z,
                ),
            );
        }
        for (b, &jb) in cols.iter().enumerate() {
            let mjb = mj.column(b);
            for (a, &ia) in cols[..=b].iter().enumerate() {
                self.mass[(ia, jb)] += j.column(a).dot(&mjb);
            }
            self.force[jb] += j.column(b).dot(&self.generalized);
        }
    }
}

/// Applied forces per body: world force, body-axes torque.
type Applied<T> = [(Vector3<T>, Vector3<T>); BODIES];

/// Copies the upper triangle of a square matrix into its lower triangle.
#[inline]
pub(crate) fn symmetrize<T: RealField + Copy, const N: usize>(a: &mut SMatrix<T, N, N>) {
    for j in 0..N {
        for i in 0..j {
            a[(j, i)] = a[(i, j)];
        }
    }
}

#[inline]
fn c<T: RealField + Copy>(x: f64) -> T {
    nalgebra::convert(x)
}

impl Model {
    /// Stages 1–2: the tree map at q, with tree speeds read from u.
    pub(crate) fn tree<T: RealField + Copy>(
        &self,
        poses: &Poses<T>,
        u: &SVector<T, SPEEDS>,
    ) -> (Tree<T>, SVector<T, TREE>) {
        let g = &self.bodies.geometry;
        let rb = poses.rot[REAR_FRAME];
        let rh = poses.rot[FRONT_FRAME];
        let a_rb = poses.rot[REAR_WHEEL].transpose() * rb;
        let a_hb = rh.transpose() * rb;
        let a_fh = poses.rot[FRONT_WHEEL].transpose() * rh;
        let s: Vector3<T> = g.steer_axis.cast();
        let ey = Vector3::<T>::y();
        let p_br: Vector3<T> = g.rear_hub_in_b.cast();
        let p_bs: Vector3<T> = g.steer_point_in_b.cast();
        let p_hs: Vector3<T> = g.steer_point_in_h.cast();
        let p_hf: Vector3<T> = g.front_hub_in_h.cast();
        let omega_of = |k: usize| u.fixed_rows::<3>(6 * k + 3).into_owned();

        // Tree speeds from u.
        let nu = rb.transpose() * u.fixed_rows::<3>(6 * REAR_WHEEL).into_owned();
        let w_b = omega_of(REAR_FRAME);
        let x_h = a_hb * w_b;
        let steer_rate = s.dot(&(omega_of(FRONT_FRAME) - x_h));
        let x_r = a_rb * w_b;
        let sigma_r = omega_of(REAR_WHEEL).y - x_r.y;
        let w_h = x_h + s * steer_rate;
        let x_f = a_fh * w_h;
        let sigma_f = omega_of(FRONT_WHEEL).y - x_f.y;
        let mut w = SVector::<T, TREE>::zeros();
        w.fixed_rows_mut::<3>(0).copy_from(&nu);
        w.fixed_rows_mut::<3>(3).copy_from(&w_b);
        w[6] = steer_rate;
        w[7] = sigma_r;
        w[8] = sigma_f;

        // Columns [ω_B, δ̇, σ_R, σ_F] (the ν columns are R_B in every translation row).
        let mut rest = [SMatrix::<T, 6, ROLLING_TREE>::zeros(); BODIES];
        // Rear wheel.
        let j = &mut rest[REAR_WHEEL];
        j.fixed_view_mut::<3, 3>(3, 0).copy_from(&a_rb);
        j.fixed_view_mut::<3, 1>(3, 4).copy_from(&ey);
        // Rear frame.
        let rb_pbr = rb * rotation::skew(&p_br);
        let j = &mut rest[REAR_FRAME];
        j.fixed_view_mut::<3, 3>(0, 0).copy_from(&rb_pbr);
        j.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&Matrix3::identity());
        // Front frame.
        let rh_phs = rh * rotation::skew(&p_hs);
        let j = &mut rest[FRONT_FRAME];
        j.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&(rb_pbr - rb * rotation::skew(&p_bs) + rh_phs * a_hb));
        j.fixed_view_mut::<3, 1>(0, 3).copy_from(&(rh_phs * s));
        j.fixed_view_mut::<3, 3>(3, 0).copy_from(&a_hb);
        j.fixed_view_mut::<3, 1>(3, 3).copy_from(&s);
        // Front wheel.
        let jh = rest[FRONT_FRAME];
        let jh_w = jh.fixed_rows::<3>(3).into_owned();
        let jf_v = jh.fixed_rows::<3>(0) - rh * rotation::skew(&p_hf) * jh_w;
        let mut jf_w = a_fh * jh_w;
        jf_w[(1, 5)] += T::one();
        let j = &mut rest[FRONT_WHEEL];
        j.fixed_rows_mut::<3>(0).copy_from(&jf_v);
        j.fixed_rows_mut::<3>(3).copy_from(&jf_w);

        // Biases and tree-consistent speeds.
        let w_r = x_r + ey * sigma_r;
        let w_f = x_f + ey * sigma_f;
        let y_b = nu - w_b.cross(&p_br);
        let cr_v = rb * w_b.cross(&nu);
        let cr_w = x_r.cross(&ey) * sigma_r;
        let cb_v = rb * w_b.cross(&y_b);
        let ch_w = x_h.cross(&s) * steer_rate;
        let ch_v = cb_v + rb * w_b.cross(&w_b.cross(&p_bs))
            - rh * (w_h.cross(&w_h.cross(&p_hs)) + ch_w.cross(&p_hs));
        let cf_w = a_fh * ch_w + x_f.cross(&ey) * sigma_f;
        let cf_v = ch_v + rh * (ch_w.cross(&p_hf) + w_h.cross(&w_h.cross(&p_hf)));
        let six = |v: Vector3<T>, o: Vector3<T>| SVector::<T, 6>::new(v.x, v.y, v.z, o.x, o.y, o.z);
        let bias = [
            six(cr_v, cr_w),
            six(cb_v, Vector3::zeros()),
            six(ch_v, ch_w),
            six(cf_v, cf_w),
        ];
        let v_r = rb * nu;
        let v_b = rb * y_b;
        let v_h = v_b + rb * w_b.cross(&p_bs) - rh * w_h.cross(&p_hs);
        let v_f = v_h + rh * w_h.cross(&p_hf);
        (
            Tree {
                hub: rb,
                rest,
                bias,
                velocity: [v_r, v_b, v_h, v_f],
                omega: [w_r, w_b, w_h, w_f],
            },
            w,
        )
    }

    /// Stage 3: applied forces per body (world force, body-axes torque).
    fn applied<T: RealField + Copy>(
        &self,
        angles: &Angles<T>,
        poses: &Poses<T>,
        omega: &[Vector3<T>; BODIES],
        inputs: &Inputs<T>,
    ) -> Applied<T> {
        let g: T = c(self.bodies.geometry.g);
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

    /// ẋ = f(x, τ): accelerations, coordinate rates and contact forces of the constrained
    /// multibody bicycle, generic over the scalar (f64 or dual numbers for exact Jacobians).
    /// Allocation-free.
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, nonlinear::{Inputs, InitialConditions, Model}};
    /// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
    /// let state = model.initial_state(&InitialConditions::upright(5.0))?;
    /// let d = model.forward(&state, &Inputs::default())?;
    /// assert!(d.u_dot.amax() < 1e-12);                    // upright running is an equilibrium
    /// assert!((d.contact[0].normal + d.contact[1].normal - 94.0 * 9.81).abs() < 1e-9);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn forward<T: RealField + Copy>(
        &self,
        state: &State<T>,
        inputs: &Inputs<T>,
    ) -> Result<Derivatives<T>> {
        let angles = Angles::new(&state.q);
        let poses = Poses::from_angles(&state.q, &angles);
        let (mut tree, _) = self.tree(&poses, &state.u);
        let applied = self.applied(&angles, &poses, &tree.omega, inputs);
        let (u_dot, contact) = if self.contacts[0].is_skate() {
            self.solve_general(&poses, &tree, &applied)?
        } else {
            self.solve_rolling(&poses, &mut tree, &applied)?
        };
        Ok(Derivatives {
            q_dot: coordinate_rates(&angles, &state.u),
            u_dot,
            contact,
        })
    }

    /// Stages 4–5 with all six contact rows in the nine tree speeds (any bicycle, skates
    /// included).
    fn solve_general<T: RealField + Copy>(
        &self,
        poses: &Poses<T>,
        tree: &Tree<T>,
        applied: &Applied<T>,
    ) -> Result<(SVector<T, SPEEDS>, [ContactForce<T>; 2])> {
        let jac: [SMatrix<T, 6, TREE>; BODIES] = std::array::from_fn(|k| tree.jac(k));
        let mut g = SMatrix::<T, 6, TREE>::zeros();
        let mut gamma = SVector::<T, 6>::zeros();
        for i in 0..2 {
            let (gi, ci, _) = self.contact_rows_in(i, poses, tree, &jac, &tree.bias);
            g.fixed_rows_mut::<3>(3 * i).copy_from(&gi);
            gamma.fixed_rows_mut::<3>(3 * i).copy_from(&ci);
        }
        let (u_dot, nu) = self.solve_saddle(&jac, &tree.bias, applied, &g, &gamma)?;
        let contact =
            std::array::from_fn(|i| self.contact_force(i, &nu.fixed_rows::<3>(3 * i).into_owned()));
        Ok((u_dot, contact))
    }

    /// Stages 4–5 for a rolling rear wheel: its three rows are solved for ν exactly
    /// ([`Model::roll_on_rear_wheel`]), leaving the front contact's three rows in six tree
    /// speeds; the rear contact force follows from the balance of linear momentum of the whole
    /// bicycle (the joint forces are internal).
    fn solve_rolling<T: RealField + Copy>(
        &self,
        poses: &Poses<T>,
        tree: &mut Tree<T>,
        applied: &Applied<T>,
    ) -> Result<(SVector<T, SPEEDS>, [ContactForce<T>; 2])> {
        let [f, n] = self.roll_on_rear_wheel(poses, tree);
        let (g, gamma, frame) = self.contact_rows_in(1, poses, tree, &tree.rest, &tree.bias);
        let (u_dot, nu) = self.solve_saddle(&tree.rest, &tree.bias, applied, &g, &gamma)?;
        let front = self.contact_force(1, &nu);
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

    /// Solves the rear wheel's three rolling rows for ν (a rolling rear wheel, not a skate), in
    /// place: afterwards `tree.rest` and `tree.bias` give every body's `u_i = J'_i w'` and
    /// `u̇_i = J'_i ẇ' + c'_i` in the six tree speeds `w' = [ω_B, δ̇, σ_R, σ_F]`, satisfying the
    /// joint rows and the rear contact rows. With the rear contact's directions
    /// `E = [f n e_z]ᵀ` (orthonormal) the rows read `E R_B ν̇ + G' ẇ' = γ̃`, so
    /// `R_B ν̇ = Eᵀ(γ̃ − G' ẇ')`: every body's translation rows gain `−EᵀG' = [ρ]× R_W J'_R` (the
    /// hub velocity ρ × Ω of rolling about the contact) and its bias `Eᵀγ̃`. Returns the rear
    /// contact's longitudinal and lateral directions (world).
    pub(crate) fn roll_on_rear_wheel<T: RealField + Copy>(
        &self,
        poses: &Poses<T>,
        tree: &mut Tree<T>,
    ) -> [Vector3<T>; 2] {
        let rear = &self.contacts[0];
        let k = rear.kinematics(poses, &tree.velocity[REAR_WHEEL], &tree.omega[REAR_WHEEL]);
        let mut hub = SMatrix::<T, 3, ROLLING_TREE>::zeros();
        for j in 0..3 {
            hub.set_column(j, &k.rho.cross(&tree.hub.column(j).into_owned()));
        }
        hub.set_column(4, &k.rho.cross(&k.axle));
        let c_v = tree.bias[REAR_WHEEL].fixed_rows::<3>(0).into_owned();
        let c_w = poses.rot[REAR_WHEEL] * tree.bias[REAR_WHEEL].fixed_rows::<3>(3);
        let hub_bias = -(k.f * k.f_dot.dot(&k.v_p) + k.n * k.n_dot.dot(&k.v_p))
            - k.omega.cross(&k.rho_dot)
            - c_v
            - c_w.cross(&k.rho);
        for b in 0..BODIES {
            let mut v = tree.rest[b].fixed_rows_mut::<3>(0);
            v += hub;
            let mut c = tree.bias[b].fixed_rows_mut::<3>(0);
            c += hub_bias;
        }
        [k.f, k.n]
    }

    /// Contact i's three rows in the tree speeds of `jac`, their right-hand side `γ − D c`,
    /// and the contact's directions.
    pub(crate) fn contact_rows_in<T: RealField + Copy, const N: usize>(
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
    fn contact_force<T: RealField + Copy>(&self, i: usize, nu: &SVector<T, 3>) -> ContactForce<T> {
        ContactForce {
            normal: nu[2],
            longitudinal: if self.contacts[i].is_skate() {
                T::zero()
            } else {
                -nu[0]
            },
            lateral: -nu[1],
        }
    }

    /// Stage 5: the reduced mass matrix TᵀMT and forces Tᵀ(f − M c) over N tree speeds, the
    /// saddle-point solve `[TᵀMT Gᵀ; G 0][ẇ; ν] = [Tᵀ(f − Mc); γ̃]` with M contact rows, and
    /// `u̇ = J ẇ + c`.
    fn solve_saddle<T: RealField + Copy, const N: usize, const M: usize>(
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
        let mut u_dot = SVector::<T, SPEEDS>::zeros();
        for k in 0..BODIES {
            u_dot
                .fixed_rows_mut::<6>(6 * k)
                .copy_from(&(jac[k] * w_dot + bias[k]));
        }
        Ok((u_dot, nu))
    }

    /// All 21 velocity rows `D` (17 differentiated holonomic rows, then 4 rolling rows) and
    /// `γ = −Ḋu`, at the state's own speeds.
    ///
    /// Row order: rear hub joint (5), steer joint (5), front hub joint (5), rear normal, front
    /// normal, rear longitudinal (spin lock for a skate), rear lateral, front longitudinal,
    /// front lateral.
    pub fn velocity_rows<T: RealField + Copy>(
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
            r.fixed_rows_mut::<5>(5 * i).copy_from(
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
            r[15 + i] = du[2];
            r[17 + 2 * i] = du[0];
            r[18 + 2 * i] = du[1];
        }
        r
    }

    /// [`Model::velocity_rows`] with the poses of `state.q` already known.
    pub(crate) fn velocity_rows_at<T: RealField + Copy>(
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
            d.fixed_view_mut::<5, 6>(5 * i, 6 * joint.parent)
                .copy_from(&rows.parent);
            d.fixed_view_mut::<5, 6>(5 * i, 6 * joint.child)
                .copy_from(&rows.child);
            gamma.fixed_rows_mut::<5>(5 * i).copy_from(&rows.gamma);
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            let rows = contact.rows(
                poses,
                &state.velocity(contact.wheel),
                &state.angular_velocity(contact.wheel),
                &state.angular_velocity(contact.frame),
            );
            // (source row in the contact, destination row in D)
            for (src, dst) in [(2, 15 + i), (0, 17 + 2 * i), (1, 18 + 2 * i)] {
                let mut wheel_cols = d.fixed_view_mut::<1, 6>(dst, 6 * contact.wheel);
                wheel_cols += rows.wheel.fixed_rows::<1>(src);
                let mut frame_cols = d.fixed_view_mut::<1, 6>(dst, 6 * contact.frame);
                frame_cols += rows.frame.fixed_rows::<1>(src);
                gamma[dst] = rows.gamma[src];
            }
        }
        (d, gamma)
    }

    /// The unstructured reference: every constraint row, the full block-diagonal M, and the
    /// 45 × 45 saddle-point system `[M Dᵀ; D 0][u̇; −μ] = [f; γ]` solved by dense LU. Slow
    /// (allocates); used to check [`Model::forward`].
    pub fn forward_reference(
        &self,
        state: &State<f64>,
        inputs: &Inputs<f64>,
    ) -> Result<Derivatives<f64>> {
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
        let nu = |row: usize| x[SPEEDS + row];
        let contact = std::array::from_fn(|i| ContactForce {
            normal: nu(15 + i),
            longitudinal: if self.contacts[i].is_skate() {
                0.0
            } else {
                -nu(17 + 2 * i)
            },
            lateral: -nu(18 + 2 * i),
        });
        Ok(Derivatives {
            q_dot: coordinate_rates(&angles, &state.u),
            u_dot,
            contact,
        })
    }
}

/// q̇ from u, given the sines and cosines of q's angles: velocities as they are, angle rates
/// from body angular velocities.
#[inline]
fn coordinate_rates<T: RealField + Copy>(
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
