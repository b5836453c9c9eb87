//! Stage 2 of the forward dynamics: the joints eliminated by the tree map. Every body's speeds
//! are written `u_i = J_i(q) w` in the nine tree speeds of [`super::topology`],
//! `w = [ν (rear hub velocity, rear frame axes), ω_B (rear frame), δ̇ (steer rate), σ_R, σ_F
//! (wheel spin rates relative to their frames)]`, and `u̇_i = J_i ẇ + c_i` (c_i: centripetal
//! and gyroscopic-coupling terms). Every `J_i w` satisfies the 15 joint velocity rows
//! identically, so `T = [J_i]` spans their null space.
//!
//! For a rolling rear wheel the three rear contact rows are then solved for ν
//! ([`Model::roll_on_rear_wheel`]), which gives the map in the six speeds `w' = [ω_B, δ̇, σ_R,
//! σ_F]` as a new [`RollingTree`] (the tree itself is left as it was).

use crate::math::Real;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::Model;
use super::poses::Poses;
use super::rotation;
use super::state::{COORDINATES, SPEEDS};
use super::topology::{
    BODIES, FRAME_RATE, FRONT_FRAME, FRONT_HUB, FRONT_SPIN, FRONT_WHEEL, HUB_VELOCITY,
    REAR_CONTACT, REAR_FRAME, REAR_HUB, REAR_SPIN, REAR_WHEEL, ROLLING_TREE, STEER_JOINT, TREE,
    TREE_STEER_RATE, rolling,
};

/// The tree map u_i = J_i w, u̇_i = J_i ẇ + c_i, and the tree-consistent speeds.
///
/// J_i is stored in two parts: the columns of ν, which are the rear frame's rotation R_B in
/// every body's translation rows (and zero in its rotation rows), and the columns of the six
/// other tree speeds `[ω_B, δ̇, σ_R, σ_F]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tree<T: Real> {
    /// R_B: the ν columns of every body's translation rows.
    pub hub: Matrix3<T>,
    /// The columns of `[ω_B, δ̇, σ_R, σ_F]`.
    pub rest: [SMatrix<T, 6, ROLLING_TREE>; BODIES],
    /// c_i: the accelerations of each body at ẇ = 0.
    pub bias: [SVector<T, 6>; BODIES],
    /// Velocities of the origins (world).
    pub velocity: [Vector3<T>; BODIES],
    /// Angular velocities (body axes).
    pub omega: [Vector3<T>; BODIES],
}

impl<T: Real> Tree<T> {
    /// Body k's whole J (6 × 9) over `w = [ν, ω_B, δ̇, σ_R, σ_F]`.
    pub(crate) fn jac(&self, k: usize) -> SMatrix<T, 6, TREE> {
        let mut j = SMatrix::<T, 6, TREE>::zeros();
        j.fixed_view_mut::<3, 3>(0, HUB_VELOCITY)
            .copy_from(&self.hub);
        j.fixed_columns_mut::<ROLLING_TREE>(FRAME_RATE)
            .copy_from(&self.rest[k]);
        j
    }

    /// Every body's whole J.
    pub(crate) fn jacobians(&self) -> [SMatrix<T, 6, TREE>; BODIES] {
        std::array::from_fn(|k| self.jac(k))
    }
}

/// The map in the six speeds w' = [ω_B, δ̇, σ_R, σ_F] once a rolling rear wheel's rows are
/// solved for ν: `u_i = J'_i w'`, `u̇_i = J'_i ẇ' + c'_i`, satisfying the joint rows and the
/// rear contact rows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RollingTree<T: Real> {
    /// J'_i.
    pub jac: [SMatrix<T, 6, ROLLING_TREE>; BODIES],
    /// c'_i.
    pub bias: [SVector<T, 6>; BODIES],
    /// The rear contact's longitudinal and lateral directions (world).
    pub rear_directions: [Vector3<T>; 2],
}

impl Model {
    /// Stage 2: the tree map at the poses, with tree speeds read from u.
    pub(crate) fn tree<T: Real>(
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
        let p_br: Vector3<T> = self.joints[REAR_HUB].point_in_parent.cast();
        let p_bs: Vector3<T> = self.joints[STEER_JOINT].point_in_parent.cast();
        let p_hs: Vector3<T> = self.joints[STEER_JOINT].point_in_child.cast();
        let p_hf: Vector3<T> = self.joints[FRONT_HUB].point_in_parent.cast();
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
        w.fixed_rows_mut::<3>(HUB_VELOCITY).copy_from(&nu);
        w.fixed_rows_mut::<3>(FRAME_RATE).copy_from(&w_b);
        w[TREE_STEER_RATE] = steer_rate;
        w[REAR_SPIN] = sigma_r;
        w[FRONT_SPIN] = sigma_f;

        // Columns [ω_B, δ̇, σ_R, σ_F] (the ν columns are R_B in every translation row).
        let (omega_b, delta) = (rolling(FRAME_RATE), rolling(TREE_STEER_RATE));
        let mut rest = [SMatrix::<T, 6, ROLLING_TREE>::zeros(); BODIES];
        // Rear wheel.
        let j = &mut rest[REAR_WHEEL];
        j.fixed_view_mut::<3, 3>(3, omega_b).copy_from(&a_rb);
        j.fixed_view_mut::<3, 1>(3, rolling(REAR_SPIN))
            .copy_from(&ey);
        // Rear frame.
        let rb_pbr = rb * rotation::skew(&p_br);
        let j = &mut rest[REAR_FRAME];
        j.fixed_view_mut::<3, 3>(0, omega_b).copy_from(&rb_pbr);
        j.fixed_view_mut::<3, 3>(3, omega_b)
            .copy_from(&Matrix3::identity());
        // Front frame.
        let rh_phs = rh * rotation::skew(&p_hs);
        let j = &mut rest[FRONT_FRAME];
        j.fixed_view_mut::<3, 3>(0, omega_b)
            .copy_from(&(rb_pbr - rb * rotation::skew(&p_bs) + rh_phs * a_hb));
        j.fixed_view_mut::<3, 1>(0, delta).copy_from(&(rh_phs * s));
        j.fixed_view_mut::<3, 3>(3, omega_b).copy_from(&a_hb);
        j.fixed_view_mut::<3, 1>(3, delta).copy_from(&s);
        // Front wheel.
        let jh = rest[FRONT_FRAME];
        let jh_w = jh.fixed_rows::<3>(3).into_owned();
        let jf_v = jh.fixed_rows::<3>(0) - rh * rotation::skew(&p_hf) * jh_w;
        let mut jf_w = a_fh * jh_w;
        jf_w[(1, rolling(FRONT_SPIN))] += T::one();
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
        let mut bias = [SVector::<T, 6>::zeros(); BODIES];
        bias[REAR_WHEEL] = six(cr_v, cr_w);
        bias[REAR_FRAME] = six(cb_v, Vector3::zeros());
        bias[FRONT_FRAME] = six(ch_v, ch_w);
        bias[FRONT_WHEEL] = six(cf_v, cf_w);
        let v_r = rb * nu;
        let v_b = rb * y_b;
        let v_h = v_b + rb * w_b.cross(&p_bs) - rh * w_h.cross(&p_hs);
        let v_f = v_h + rh * w_h.cross(&p_hf);
        let mut velocity = [Vector3::zeros(); BODIES];
        let mut omega = [Vector3::zeros(); BODIES];
        for (k, v, o) in [
            (REAR_WHEEL, v_r, w_r),
            (REAR_FRAME, v_b, w_b),
            (FRONT_FRAME, v_h, w_h),
            (FRONT_WHEEL, v_f, w_f),
        ] {
            velocity[k] = v;
            omega[k] = o;
        }
        (
            Tree {
                hub: rb,
                rest,
                bias,
                velocity,
                omega,
            },
            w,
        )
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
        let mut w = SVector::<f64, TREE>::zeros();
        w.fixed_rows_mut::<3>(HUB_VELOCITY)
            .copy_from(&(poses.rot[REAR_FRAME].transpose() * rear_hub_velocity));
        w.fixed_rows_mut::<3>(FRAME_RATE)
            .copy_from(rear_frame_angular_velocity);
        w[TREE_STEER_RATE] = steer_rate;
        w[REAR_SPIN] = wheel_rates[0];
        w[FRONT_SPIN] = wheel_rates[1];
        speeds_of(&tree.jacobians(), &w)
    }

    /// Solves the rear wheel's three rolling rows for ν (a rolling rear wheel, not a skate):
    /// the map of every body's `u_i = J'_i w'` and `u̇_i = J'_i ẇ' + c'_i` in the six tree
    /// speeds `w' = [ω_B, δ̇, σ_R, σ_F]`, satisfying the joint rows and the rear contact rows.
    /// With the rear contact's directions `E = [f n e_z]ᵀ` (orthonormal) the rows read
    /// `E R_B ν̇ + G' ẇ' = γ̃`, so `R_B ν̇ = Eᵀ(γ̃ − G' ẇ')`: every body's translation rows gain
    /// `−EᵀG' = [ρ]× R_W J'_R` (the hub velocity ρ × Ω of rolling about the contact) and its bias
    /// `Eᵀγ̃`.
    pub(crate) fn roll_on_rear_wheel<T: Real>(
        &self,
        poses: &Poses<T>,
        tree: &Tree<T>,
    ) -> RollingTree<T> {
        let rear = &self.contacts[REAR_CONTACT];
        let k = rear.kinematics(poses, &tree.velocity[rear.wheel], &tree.omega[rear.wheel]);
        let mut hub = SMatrix::<T, 3, ROLLING_TREE>::zeros();
        for j in 0..3 {
            hub.set_column(
                rolling(FRAME_RATE) + j,
                &k.rho.cross(&tree.hub.column(j).into_owned()),
            );
        }
        hub.set_column(rolling(REAR_SPIN), &k.rho.cross(&k.axle));
        let c_v = tree.bias[rear.wheel].fixed_rows::<3>(0).into_owned();
        let c_w = poses.rot[rear.wheel] * tree.bias[rear.wheel].fixed_rows::<3>(3);
        let hub_bias = -(k.f * k.f_dot.dot(&k.v_p) + k.n * k.n_dot.dot(&k.v_p))
            - k.omega.cross(&k.rho_dot)
            - c_v
            - c_w.cross(&k.rho);
        let mut jac = tree.rest;
        let mut bias = tree.bias;
        for b in 0..BODIES {
            let mut v = jac[b].fixed_rows_mut::<3>(0);
            v += hub;
            let mut c = bias[b].fixed_rows_mut::<3>(0);
            c += hub_bias;
        }
        RollingTree {
            jac,
            bias,
            rear_directions: [k.f, k.n],
        }
    }
}

/// u = [J_k w] of every body.
pub(crate) fn speeds_of<T: Real, const N: usize>(
    jac: &[SMatrix<T, 6, N>; BODIES],
    w: &SVector<T, N>,
) -> SVector<T, SPEEDS> {
    let mut u = SVector::<T, SPEEDS>::zeros();
    for (k, jac) in jac.iter().enumerate() {
        u.fixed_rows_mut::<6>(6 * k).copy_from(&(jac * w));
    }
    u
}
