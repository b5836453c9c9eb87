//! The model itself: the bodies, joints and contacts of a bicycle, built once from its
//! benchmark parameters along the topology of [`super::topology`], immutable afterwards and
//! shared by every state.

use nalgebra::Vector3;

use super::bodies::{Bodies, Geometry};
use super::contact::KnifeEdge;
use super::joints::Revolute;
use super::topology::{
    CONTACT_COUNT, CONTACTS, FRONT_WHEEL, JOINT_COUNT, JOINTS, JointKind, JointSpec, REAR_WHEEL,
};
use crate::error::Result;
use crate::parameters::BenchmarkParameters;

/// The multibody bicycle built from benchmark parameters: immutable, shared by every state.
///
/// ```
/// use whipple::{BenchmarkParameters, Model};
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// assert_eq!(model.parameters().w, 1.02);
/// assert_eq!(model.bodies().body[whipple::advanced::nonlinear::REAR_FRAME].mass, 85.0);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The parameters it was built from.
    pub(crate) parameters: BenchmarkParameters,
    /// Mass properties and attachment geometry.
    pub(crate) bodies: Bodies,
    /// Rear hub (B–R), steer (B–H), front hub (H–F), in [`JOINTS`] order.
    pub(crate) joints: [Revolute; JOINT_COUNT],
    /// Rear and front wheel contacts, in [`CONTACTS`] order.
    pub(crate) contacts: [KnifeEdge; CONTACT_COUNT],
    /// ρ of the augmented-Lagrangian solve (0: the reduced mass matrix is positive definite).
    pub(crate) augmentation: f64,
}

/// The revolute joint of one entry of the joint tree, from the attachment geometry.
fn revolute(spec: &JointSpec, g: &Geometry) -> Revolute {
    let (ex, ey, ez) = (Vector3::x(), Vector3::y(), Vector3::z());
    match spec.kind {
        // A wheel turns about its own y axis at its hub, its origin.
        JointKind::Hub => Revolute {
            parent: spec.parent,
            child: spec.child,
            point_in_parent: if spec.child == REAR_WHEEL {
                g.rear_hub_in_b
            } else {
                g.front_hub_in_h
            },
            point_in_child: Vector3::zeros(),
            axis_in_child: ey,
            perpendicular_in_parent: [ex, ez],
        },
        JointKind::Steer => Revolute {
            parent: spec.parent,
            child: spec.child,
            point_in_parent: g.steer_point_in_b,
            point_in_child: g.steer_point_in_h,
            axis_in_child: g.steer_axis,
            perpendicular_in_parent: [ey, g.steer_axis.cross(&ey)],
        },
    }
}

impl Model {
    /// The multibody model of a bicycle, after validating its parameters.
    pub fn new(p: &BenchmarkParameters) -> Result<Self> {
        p.validate()?;
        let bodies = Bodies::new(p);
        let joints = JOINTS.map(|spec| revolute(&spec, &bodies.geometry));
        let contacts = CONTACTS.map(|spec| KnifeEdge {
            wheel: spec.wheel,
            frame: spec.frame,
            radius: if spec.wheel == FRONT_WHEEL {
                p.r_f
            } else {
                p.r_r
            },
        });
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

    /// The (validated) parameters the model was built from.
    pub fn parameters(&self) -> &BenchmarkParameters {
        &self.parameters
    }

    /// The four bodies' mass properties and the points where the joints attach.
    pub fn bodies(&self) -> &Bodies {
        &self.bodies
    }

    /// ρ used when the plain factorization of the reduced mass matrix fails.
    pub(crate) fn fallback_augmentation(&self) -> f64 {
        let p = &self.parameters;
        p.m_r + p.m_b + p.m_h + p.m_f
    }
}
