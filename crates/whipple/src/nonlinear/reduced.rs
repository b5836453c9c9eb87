//! The non-linear model seen through the linear model's state x = [φ, δ, φ̇, δ̇]: every other
//! coordinate and speed solved from the constraints, at a forward speed v held fixed.
//!
//! [`Model::reduced_state`] maps x to a full consistent [`State`] (the dependent coordinates
//! from the holonomic constraints, the dependent speeds from the velocity constraints), generic
//! over the scalar, so that dual numbers carry exact derivatives through it.
//! [`Model::lean_steer_field`] is then ẋ = f(x) = [φ̇, δ̇, φ̈, δ̈] of the full non-linear
//! dynamics restricted to the constraint manifold; its Jacobian at x = 0 is the non-linear
//! model's own A(v) (see [`crate::analysis::comparison::lean_steer_matrix`]).
//!
//! The coordinates left out — yaw, rear contact position, wheel rotations — are ignorable: the
//! dynamics do not depend on them (the bicycle is the same wherever it is and however far its
//! wheels have turned), so fixing them at zero loses nothing. The forward speed is held: about
//! upright straight running a change of speed changes φ̈ and δ̈ only at second order (they
//! vanish for every v at x = 0), and the speed's own rate is even in x, so it decouples at first
//! order.

use crate::math::Real;
use nalgebra::{Matrix3, SVector, Vector3, Vector4};

use super::Model;
use super::forward::{Inputs, StateRates};
use super::poses::Poses;
use super::rotation;
use super::state::{BODY_PITCH, COORDINATES, STATE_LEN, State};
use super::topology::{FRONT_FRAME, FRONT_WHEEL, REAR_FRAME, REAR_WHEEL};
use crate::analysis::linearize::VectorField;
use crate::error::{Error, Result};

#[inline]
fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

impl Model {
    /// The full consistent state with lean, steer, lean rate and steer rate `x = [φ, δ, φ̇, δ̇]`
    /// and forward speed `speed`, heading along +x from the origin, wheel angles zero (with
    /// zero rates, a steady turn's state), for any lean and steer at which the front wheel can
    /// touch the ground.
    ///
    /// The rear frame's pitch is `Model::ground_pitch`'s from upright's (for dual numbers with
    /// the exact derivative ∂θ/∂x = −(∂h/∂θ)⁻¹ ∂h/∂x of the implicit function theorem); every
    /// other coordinate and speed is `Model::consistent_state`'s.
    pub fn reduced_state<T: Real>(&self, x: &Vector4<T>, speed: T) -> Result<State<T>> {
        let [lean, steer, lean_rate, steer_rate] = [x[0], x[1], x[2], x[3]];
        let upright = self.pitch_for(0.0, 0.0, 0.0)?;
        let pitch = self.ground_pitch(lean, steer, upright)?;
        self.consistent_state(
            [T::zero(), lean, steer],
            [T::zero(), T::zero()],
            pitch,
            [speed, lean_rate, steer_rate],
        )
        .ok_or_else(|| Error::SingularDynamics {
            context: "speed, lean rate and steer rate do not determine the motion of the \
                      reduced state (singular velocity constraints)"
                .into(),
        })
    }

    /// ẋ = f(x) = [φ̇, δ̇, φ̈, δ̈] of the non-linear dynamics at the reduced state of
    /// [`Model::reduced_state`], unforced.
    ///
    /// φ̇ = cos θ ω_x + sin θ ω_z (ω: rear frame angular velocity, body axes; θ: its pitch), so
    /// φ̈ = cos θ ω̇_x + sin θ ω̇_z + θ̇ (cos θ ω_z − sin θ ω_x). δ̇ = s·(ω_H − A ω_B) with
    /// A = R_Hᵀ R_B and s the steer axis, and Ȧ ω_B = −ω_H × (A ω_B), so
    /// δ̈ = s·(ω̇_H − A ω̇_B + ω_H × (A ω_B)).
    ///
    /// ```
    /// use nalgebra::Vector4;
    /// use whipple::{BenchmarkParameters, Model};
    /// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
    /// let f = model.lean_steer_field(&Vector4::new(0.01, 0.0, 0.0, 0.0), 4.6)?;
    /// assert!(f[2] > 0.0); // leaning right, it falls further right
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn lean_steer_field<T: Real>(&self, x: &Vector4<T>, speed: f64) -> Result<Vector4<T>> {
        let state = self.reduced_state(x, c(speed))?;
        let d = self.forward(&state, &Inputs::default())?;
        let [lean_acceleration, steer_acceleration] = self.lean_steer_accelerations(&state, &d);
        Ok(Vector4::new(
            state.lean_rate(),
            self.steer_rate(&state),
            lean_acceleration,
            steer_acceleration,
        ))
    }

    /// φ̈ and δ̈ of the rear frame's lean and of the steer angle, from the model's accelerations
    /// at `state` (see [`Model::lean_steer_field`] for the formulas).
    pub(crate) fn lean_steer_accelerations<T: Real>(
        &self,
        state: &State<T>,
        d: &StateRates<T>,
    ) -> [T; 2] {
        let b = 6 * REAR_FRAME;
        let pitch = state.q[b + BODY_PITCH];
        let pitch_rate = d.q_dot[b + BODY_PITCH];
        let (sp, cp) = crate::math::sin_cos(pitch);
        let w_b = state.angular_velocity(REAR_FRAME);
        let w_h = state.angular_velocity(FRONT_FRAME);
        let dw_b = d.u_dot.fixed_rows::<3>(b + 3).into_owned();
        let dw_h = d.u_dot.fixed_rows::<3>(6 * FRONT_FRAME + 3).into_owned();
        let lean_acceleration = cp * dw_b.x + sp * dw_b.z + pitch_rate * (cp * w_b.z - sp * w_b.x);
        let poses = Poses::new(&state.q);
        let a = poses.rot[FRONT_FRAME].transpose() * poses.rot[REAR_FRAME];
        let s: Vector3<T> = self.bodies.geometry.steer_axis.cast();
        let steer_acceleration = s.dot(&(dw_h - a * dw_b + w_h.cross(&(a * w_b))));
        [lean_acceleration, steer_acceleration]
    }
}

/// The non-linear model on the linear model's state x = [φ, δ, φ̇, δ̇] at a fixed forward speed
/// (see [`Model::lean_steer_field`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LeanSteerField<'a> {
    /// The model.
    pub model: &'a Model,
    /// v: forward speed [m/s].
    pub speed: f64,
}

impl VectorField<4> for LeanSteerField<'_> {
    fn eval<T: Real>(&self, x: &SVector<T, 4>) -> Result<SVector<T, 4>> {
        self.model.lean_steer_field(x, self.speed)
    }
}

/// The non-linear model's full first-order form, 48 states, ẏ = F(y) from [`Model::forward`],
/// unforced: y = [q; ũ], where ũ is the model's speeds u except that each wheel's angular
/// velocity is expressed in axes that follow the wheel's yaw and lean but not its spin,
/// ω̃ = R_y(θ) ω (θ: the wheel's third Euler angle; see `spin_free_vector`).
///
/// Why: the model's own speeds give a wheel's angular velocity in its body axes, which spin
/// with the wheel. In them the Jacobian of [q̇; u̇] at one instant of steady running is only
/// similar to the one a moment later, J(t) = T(t) J₀ T(t)⁻¹, and the motion obeys
/// ż = (J₀ − T⁻¹Ṫ) z: the eigenvalues of J(t) are not the exponents of the linearized motion
/// (they are off by terms of the order of the spin rate v/r). In spin-free axes the
/// reference motion is steady, F does not depend on the wheel angles, and the Jacobian's
/// eigenvalues are the exponents.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FullStateField<'a> {
    /// The model.
    pub model: &'a Model,
}

impl VectorField<STATE_LEN> for FullStateField<'_> {
    fn eval<T: Real>(&self, y: &SVector<T, STATE_LEN>) -> Result<SVector<T, STATE_LEN>> {
        let state = state_from_spin_free(y);
        let d = self.model.forward(&state, &Inputs::default())?;
        Ok(spin_free_derivative(&state, &d))
    }
}

/// The wheels' body indices.
const WHEELS: [usize; 2] = [REAR_WHEEL, FRONT_WHEEL];

/// R_y(θ) of wheel k: from its body axes to its spin-free axes.
fn unspin<T: Real>(q: &SVector<T, COORDINATES>, k: usize) -> Matrix3<T> {
    rotation::matrix(T::zero(), T::zero(), q[6 * k + BODY_PITCH])
}

/// y = [q; ũ] of a state: the wheels' angular velocities turned from body axes into
/// spin-free axes, ω̃ = R_y(θ) ω.
pub(crate) fn spin_free_vector<T: Real>(state: &State<T>) -> SVector<T, STATE_LEN> {
    let mut y = state.to_vector();
    for k in WHEELS {
        let w = unspin(&state.q, k) * state.angular_velocity(k);
        y.fixed_rows_mut::<3>(COORDINATES + 6 * k + 3).copy_from(&w);
    }
    y
}

/// The state of y = [q; ũ] (the inverse of [`spin_free_vector`]).
pub(crate) fn state_from_spin_free<T: Real>(y: &SVector<T, STATE_LEN>) -> State<T> {
    let mut state = State::from_vector(y);
    for k in WHEELS {
        let w = unspin(&state.q, k).transpose() * state.angular_velocity(k);
        state.u.fixed_rows_mut::<3>(6 * k + 3).copy_from(&w);
    }
    state
}

/// ẏ = [q̇; d/dt ũ] from the model's derivatives: for a wheel,
/// d/dt (R_y(θ) ω) = R_y(θ) ω̇ + θ̇ e_y × ω̃.
pub(crate) fn spin_free_derivative<T: Real>(
    state: &State<T>,
    d: &StateRates<T>,
) -> SVector<T, STATE_LEN> {
    let mut out = d.to_vector();
    for k in WHEELS {
        let r = unspin(&state.q, k);
        let w = r * state.angular_velocity(k);
        let dw = d.u_dot.fixed_rows::<3>(6 * k + 3).into_owned();
        let spin_rate = d.q_dot[6 * k + BODY_PITCH];
        let rate = r * dw + Vector3::y().cross(&w) * spin_rate;
        out.fixed_rows_mut::<3>(COORDINATES + 6 * k + 3)
            .copy_from(&rate);
    }
    out
}
