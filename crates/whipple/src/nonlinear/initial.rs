//! A consistent state from a few numbers: the configuration along the joint tree
//! ([`super::configuration`]), the pitch that puts the front wheel on the ground, and the
//! dependent speeds from the velocity constraints given the forward speed, lean rate and
//! steer rate.

use crate::math::Real;
use nalgebra::{SMatrix, SVector, Vector3};

use super::Model;
use super::poses::Poses;
use super::state::State;
use super::topology::{FRAME_RATE, REAR_FRAME, TREE, TREE_STEER_RATE};
use super::tree::speeds_of;
use crate::error::{Error, Result};

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

    /// Checks the numbers: every one finite, and the lean strictly between −π/2 and π/2 (the
    /// bicycle would lie on the ground, where the orientation angles are singular).
    pub fn validate(&self) -> Result<()> {
        for (what, value) in [
            ("speed", self.speed),
            ("lean", self.lean),
            ("steer", self.steer),
            ("lean_rate", self.lean_rate),
            ("steer_rate", self.steer_rate),
            ("yaw", self.yaw),
            ("rear_contact_x", self.rear_contact_x),
            ("rear_contact_y", self.rear_contact_y),
        ] {
            if !value.is_finite() {
                return Err(Error::InvalidArgument {
                    what: "initial conditions",
                    rule: format!("{what} must be a finite number, got {value}"),
                });
            }
        }
        if self.lean.abs() >= std::f64::consts::FRAC_PI_2 {
            return Err(Error::InvalidArgument {
                what: "initial conditions",
                rule: format!(
                    "the lean must lie strictly between -pi/2 and pi/2, got {}",
                    self.lean
                ),
            });
        }
        Ok(())
    }
}

/// The nine tree speeds that satisfy the six contact rows `g` (in the tree speeds) and give
/// the forward speed (the rear hub velocity ν along `heading`, in rear frame axes), the lean
/// rate of the yaw–lean–pitch angles (cos θ ω_x + sin θ ω_z, θ the rear frame's pitch) and the
/// steer rate: nine equations solved by LU in the scalar type. None when they are singular.
pub(crate) fn solve_tree_speeds<T: Real>(
    g: &SMatrix<T, 6, TREE>,
    heading: &Vector3<T>,
    pitch: T,
    [speed, lean_rate, steer_rate]: [T; 3],
) -> Option<SVector<T, TREE>> {
    let mut a = SMatrix::<T, TREE, TREE>::zeros();
    let mut b = SVector::<T, TREE>::zeros();
    a.fixed_rows_mut::<6>(0).copy_from(g);
    a.fixed_view_mut::<1, 3>(6, 0)
        .copy_from(&heading.transpose());
    b[6] = speed;
    let (sp, cp) = crate::math::sin_cos(pitch);
    a[(7, FRAME_RATE)] = cp;
    a[(7, FRAME_RATE + 2)] = sp;
    b[7] = lean_rate;
    a[(8, TREE_STEER_RATE)] = T::one();
    b[8] = steer_rate;
    a.lu().solve(&b).filter(|w| w.iter().all(|x| x.is_finite()))
}

impl Model {
    /// A state that satisfies all constraints, built from a few numbers: the pitch of the rear
    /// frame by Newton iteration on the front contact height ([`Model::pitch_for`]), and the
    /// rest by `Model::consistent_state`. Wheel rotation angles start at zero.
    pub fn initial_state(&self, ic: &InitialConditions) -> Result<State<f64>> {
        ic.validate()?;
        let pitch = self.pitch_for(ic.lean, ic.steer, 0.0)?;
        let at = |speed_and_rates: [f64; 3]| {
            self.consistent_state(
                [ic.yaw, ic.lean, ic.steer],
                [ic.rear_contact_x, ic.rear_contact_y],
                pitch,
                speed_and_rates,
            )
        };
        at([ic.speed, ic.lean_rate, ic.steer_rate]).ok_or_else(|| {
            // Solvable at a unit speed: it is the size of the numbers that failed (1e308 m/s
            // overflows the solve), not the constraints.
            if at([1.0, 0.0, 0.0]).is_some() {
                Error::InvalidArgument {
                    what: "initial conditions",
                    rule: format!(
                        "the speed and rates (speed {} m/s, lean rate {} rad/s, steer rate {} \
                         rad/s) are too large for double precision: the velocity constraints \
                         overflow",
                        crate::error::short_number(ic.speed),
                        crate::error::short_number(ic.lean_rate),
                        crate::error::short_number(ic.steer_rate)
                    ),
                }
            } else {
                Error::InvalidArgument {
                    what: "initial conditions",
                    rule: "speed, lean rate and steer rate do not determine the motion in this \
                           configuration (singular velocity constraints)"
                        .into(),
                }
            }
        })
    }

    /// The one builder of a consistent state, in any scalar: at yaw ψ, lean φ and steer δ
    /// (`angles`), the rear contact at `rear_contact` (x, y) and a pitch that puts the front
    /// wheel down, every other coordinate from the joints (wheel angles zero), and the nine
    /// tree speeds from the six contact rows with the forward speed (the rear hub's velocity
    /// along the heading), lean rate and steer rate. None when the velocity constraints are
    /// singular there.
    pub(crate) fn consistent_state<T: Real>(
        &self,
        [yaw, lean, steer]: [T; 3],
        rear_contact: [T; 2],
        pitch: T,
        speed_and_rates: [T; 3],
    ) -> Option<State<T>> {
        let q = self.configuration(
            [yaw, lean, pitch],
            steer,
            [T::zero(), T::zero()],
            rear_contact,
        );
        let poses = Poses::new(&q);
        let (tree, _) = self.tree(&poses, &SVector::zeros());
        let jac = tree.jacobians();
        let (g, _) = self.contact_rows(&poses, &tree, &jac, &tree.bias);
        let heading = poses.rot[REAR_FRAME].transpose()
            * Vector3::new(crate::math::cos(yaw), crate::math::sin(yaw), T::zero());
        let w = solve_tree_speeds(&g, &heading, pitch, speed_and_rates)?;
        Some(State {
            q,
            u: speeds_of(&jac, &w),
        })
    }
}
