//! Stage 1 of the forward dynamics: where every body is. The sines and cosines of the twelve
//! Euler angles, once per evaluation, and from them each body's rotation matrix and origin.

use crate::math::Real;
use nalgebra::{Matrix3, SVector, Vector3};

use super::rotation::{self, SinCos};
use super::state::COORDINATES;
use super::topology::BODIES;

/// Poses of the four bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Poses<T: Real> {
    /// Rotation matrices, body → world.
    pub rot: [Matrix3<T>; BODIES],
    /// Positions of the body origins, world axes \[m\].
    pub pos: [Vector3<T>; BODIES],
}

impl<T: Real> Poses<T> {
    /// Stage 1: poses from the coordinates.
    pub(crate) fn new(q: &SVector<T, COORDINATES>) -> Self {
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

impl<T: Real> Angles<T> {
    /// The sines and cosines of q's angles.
    #[inline]
    pub(crate) fn new(q: &SVector<T, COORDINATES>) -> Self {
        Angles(std::array::from_fn(|k| {
            std::array::from_fn(|i| SinCos::new(q[6 * k + 3 + i]))
        }))
    }
}
