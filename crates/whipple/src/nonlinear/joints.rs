//! Revolute joints (steer axis, two hubs) as constraint rows: coincident points (3 rows) and
//! parallel axes (2 rows), with their velocity rows `D` and convective terms `γ`.
//!
//! For parent A and child C with joint point p_A (A axes) = p_C (C axes), child axis a_C and two
//! parent vectors b₁, b₂ perpendicular to the parent's copy of the axis:
//!
//! - position: `x_A + R_A p_A − x_C − R_C p_C = 0`;
//! - axis: `(R_A b_i) · (R_C a_C) = 0`, i = 1, 2.
//!
//! Velocity rows, with speeds (v world, ω body) of each body:
//! `v_A − R_A [p_A]× ω_A − v_C + R_C [p_C]× ω_C = 0` and `(ω_A − ω_C)_world · (b_i × a_C) = 0`.
//! Acceleration rows `D u̇ = γ` with `γ = −Ḋ u`.

use crate::math::Real;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::poses::Poses;
use super::rotation::skew;

/// A revolute joint between two bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Revolute {
    /// Parent body index.
    pub parent: usize,
    /// Child body index.
    pub child: usize,
    /// Joint point in parent axes, from the parent's origin \[m\].
    pub point_in_parent: Vector3<f64>,
    /// Joint point in child axes, from the child's origin \[m\].
    pub point_in_child: Vector3<f64>,
    /// Unit joint axis in child axes (positive rotation of the child about it is positive).
    pub axis_in_child: Vector3<f64>,
    /// Two unit vectors in parent axes perpendicular to the parent's copy of the axis.
    pub perpendicular_in_parent: [Vector3<f64>; 2],
}

/// Rows of one joint: coefficients of the parent's and the child's six speeds, and γ.
#[derive(Debug, Clone, Copy)]
pub(crate) struct JointRows<T: Real> {
    /// Coefficients of the parent's speeds (v world, ω body).
    pub parent: SMatrix<T, 5, 6>,
    /// Coefficients of the child's speeds.
    pub child: SMatrix<T, 5, 6>,
    /// γ = −Ḋu.
    pub gamma: SVector<T, 5>,
}

impl Revolute {
    /// The five holonomic residuals: point coincidence (3) \[m\], axis alignment (2) [-].
    pub(crate) fn residual<T: Real>(&self, poses: &Poses<T>) -> SVector<T, 5> {
        let (ra, rc) = (&poses.rot[self.parent], &poses.rot[self.child]);
        let pa: Vector3<T> = self.point_in_parent.cast();
        let pc: Vector3<T> = self.point_in_child.cast();
        let gap = poses.pos[self.parent] + ra * pa - poses.pos[self.child] - rc * pc;
        let axis = rc * self.axis_in_child.cast::<T>();
        let b1 = ra * self.perpendicular_in_parent[0].cast::<T>();
        let b2 = ra * self.perpendicular_in_parent[1].cast::<T>();
        SVector::<T, 5>::new(gap.x, gap.y, gap.z, b1.dot(&axis), b2.dot(&axis))
    }

    /// Velocity rows and γ, given the angular velocities (body axes) of parent and child.
    pub(crate) fn rows<T: Real>(
        &self,
        poses: &Poses<T>,
        omega_parent: &Vector3<T>,
        omega_child: &Vector3<T>,
    ) -> JointRows<T> {
        let (ra, rc) = (&poses.rot[self.parent], &poses.rot[self.child]);
        let pa: Vector3<T> = self.point_in_parent.cast();
        let pc: Vector3<T> = self.point_in_child.cast();
        let mut parent = SMatrix::<T, 5, 6>::zeros();
        let mut child = SMatrix::<T, 5, 6>::zeros();
        let identity = Matrix3::<T>::identity();
        parent.fixed_view_mut::<3, 3>(0, 0).copy_from(&identity);
        parent
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-(ra * skew(&pa))));
        child.fixed_view_mut::<3, 3>(0, 0).copy_from(&(-identity));
        child
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(rc * skew(&pc)));

        let wa = ra * omega_parent;
        let wc = rc * omega_child;
        let axis = rc * self.axis_in_child.cast::<T>();
        let mut gamma = SVector::<T, 5>::zeros();
        let centripetal = ra * omega_parent.cross(&omega_parent.cross(&pa))
            - rc * omega_child.cross(&omega_child.cross(&pc));
        gamma.fixed_rows_mut::<3>(0).copy_from(&(-centripetal));
        for i in 0..2 {
            let b = ra * self.perpendicular_in_parent[i].cast::<T>();
            let c = b.cross(&axis);
            let row_a = (ra.transpose() * c).transpose();
            let row_c = -(rc.transpose() * c).transpose();
            parent.fixed_view_mut::<1, 3>(3 + i, 3).copy_from(&row_a);
            child.fixed_view_mut::<1, 3>(3 + i, 3).copy_from(&row_c);
            let c_dot = wa.cross(&b).cross(&axis) + b.cross(&wc.cross(&axis));
            gamma[3 + i] = -(wa - wc).dot(&c_dot);
        }
        JointRows {
            parent,
            child,
            gamma,
        }
    }
}
