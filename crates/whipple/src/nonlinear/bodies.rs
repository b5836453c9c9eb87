//! The four rigid bodies of the multibody bicycle, built from the benchmark parameters: mass,
//! inertia tensor about the body's origin, and the points and axes where the joints and the
//! contacts attach.
//!
//! Every body frame is parallel to the benchmark axes (x forward, y right, z down) in the upright
//! reference configuration. Origins: each wheel at its hub (its centre of mass), the rear frame B
//! and the front frame H at their centres of mass (x_B, 0, z_B) and (x_H, 0, z_H).

use nalgebra::{Matrix3, Vector3};

use super::topology::{BODIES, FRONT_FRAME, FRONT_WHEEL, REAR_FRAME, REAR_WHEEL};
use crate::parameters::BenchmarkParameters;

/// One rigid body: mass and inertia tensor about its origin (its centre of mass), in body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Mass \[kg\] (may be zero).
    pub mass: f64,
    /// Inertia tensor about the origin in body axes [kg m²] (may be zero).
    pub inertia: Matrix3<f64>,
    /// Position of the origin in the upright reference configuration, benchmark axes \[m\].
    pub reference_position: Vector3<f64>,
}

/// Where the joints attach, in body axes relative to the body origins (the wheel radii and
/// gravity are the parameters' own, [`super::Model::parameters`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Rear hub seen from the rear frame B's origin \[m\].
    pub rear_hub_in_b: Vector3<f64>,
    /// A point of the steer axis seen from B's origin \[m\] (the point nearest the front hub).
    pub steer_point_in_b: Vector3<f64>,
    /// The same point of the steer axis seen from the front frame H's origin \[m\].
    pub steer_point_in_h: Vector3<f64>,
    /// Front hub seen from H's origin \[m\].
    pub front_hub_in_h: Vector3<f64>,
    /// Unit steer axis, pointing down (positive steer rotation turns the front right); the same
    /// vector in B and H axes, since both are parallel in the reference configuration.
    pub steer_axis: Vector3<f64>,
}

/// The four bodies in index order ([`REAR_WHEEL`], [`REAR_FRAME`], [`FRONT_FRAME`],
/// [`FRONT_WHEEL`]) and the geometry joining them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bodies {
    /// Mass properties, in index order.
    pub body: [RigidBody; BODIES],
    /// Joint and contact points.
    pub geometry: Geometry,
}

impl Bodies {
    /// The bodies of a bicycle (parameters assumed validated).
    ///
    /// Wheels: mass m at the hub, inertia diag(I_xx, I_yy, I_xx) (I_yy the spin moment). Frames:
    /// inertia [[I_xx, 0, I_xz], [0, I_yy, 0], [I_xz, 0, I_zz]] about their centres of mass, as in
    /// Meijaard 2007 Table 1 (where I_xz = −∫xz dm enters the tensor directly).
    pub fn new(p: &BenchmarkParameters) -> Self {
        let wheel = |m: f64, i_xx: f64, i_yy: f64, x: f64, r: f64| RigidBody {
            mass: m,
            inertia: Matrix3::from_diagonal(&Vector3::new(i_xx, i_yy, i_xx)),
            reference_position: Vector3::new(x, 0.0, -r),
        };
        let frame = |m: f64, xx: f64, yy: f64, zz: f64, xz: f64, x: f64, z: f64| RigidBody {
            mass: m,
            inertia: Matrix3::new(xx, 0.0, xz, 0.0, yy, 0.0, xz, 0.0, zz),
            reference_position: Vector3::new(x, 0.0, z),
        };
        let body = [
            wheel(p.m_r, p.i_rxx, p.i_ryy, 0.0, p.r_r),
            frame(p.m_b, p.i_bxx, p.i_byy, p.i_bzz, p.i_bxz, p.x_b, p.z_b),
            frame(p.m_h, p.i_hxx, p.i_hyy, p.i_hzz, p.i_hxz, p.x_h, p.z_h),
            wheel(p.m_f, p.i_fxx, p.i_fyy, p.w, p.r_f),
        ];
        let (sin_l, cos_l) = crate::math::sin_cos(p.lambda);
        let steer_axis = Vector3::new(sin_l, 0.0, cos_l);
        // The steer axis meets the ground at (w + c, 0, 0); take its point nearest the front hub.
        let ground_point = Vector3::new(p.w + p.c, 0.0, 0.0);
        let front_hub = body[FRONT_WHEEL].reference_position;
        let steer_point = ground_point + steer_axis * steer_axis.dot(&(front_hub - ground_point));
        let b = body[REAR_FRAME].reference_position;
        let h = body[FRONT_FRAME].reference_position;
        let geometry = Geometry {
            rear_hub_in_b: body[REAR_WHEEL].reference_position - b,
            steer_point_in_b: steer_point - b,
            steer_point_in_h: steer_point - h,
            front_hub_in_h: front_hub - h,
            steer_axis,
        };
        Bodies { body, geometry }
    }
}
