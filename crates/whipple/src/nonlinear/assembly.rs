//! The reduced mass matrix `TᵀMT` and forces `Tᵀ(f − Mc)` assembled body by body over the
//! tree speeds that can move each body ([`super::topology`]'s column lists), on the upper
//! triangle; shared by the forward dynamics (masses and inertias) and the velocity projection
//! (unit weights).

use crate::math::Real;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::topology::{
    FRONT_FRAME, FRONT_FRAME_COLUMNS, FRONT_FRAME_ROLLING, FRONT_WHEEL_COLUMNS,
    FRONT_WHEEL_ROLLING, REAR_FRAME, REAR_FRAME_COLUMNS, REAR_FRAME_ROLLING, REAR_WHEEL,
    REAR_WHEEL_COLUMNS, REAR_WHEEL_ROLLING, ROLLING_TREE, TREE,
};

/// One body's share of the reduced mass matrix TᵀMT and forces Tᵀ(f − Mc), over N tree
/// speeds (9, or 6 for the rolling tree).
pub(crate) struct Reduced<'a, T: Real, const N: usize> {
    /// TᵀMT being assembled (upper triangle).
    pub mass: &'a mut SMatrix<T, N, N>,
    /// Tᵀ(f − Mc) being assembled.
    pub force: &'a mut SVector<T, N>,
    /// The body's J (6 × N).
    pub jac: &'a SMatrix<T, 6, N>,
    /// The body's mass.
    pub m: T,
    /// Its inertia tensor, body axes.
    pub inertia: Matrix3<T>,
    /// f − M c of the body: world force, then body-axes torque.
    pub generalized: SVector<T, 6>,
}

impl<T: Real, const N: usize> Reduced<'_, T, N> {
    /// Adds body k's share over the tree speeds that can move it.
    #[inline]
    pub(crate) fn add_body(&mut self, k: usize) {
        if N == TREE {
            match k {
                REAR_WHEEL => self.add(REAR_WHEEL_COLUMNS),
                REAR_FRAME => self.add(REAR_FRAME_COLUMNS),
                FRONT_FRAME => self.add(FRONT_FRAME_COLUMNS),
                _ => self.add(FRONT_WHEEL_COLUMNS),
            }
        } else if N == ROLLING_TREE {
            match k {
                REAR_WHEEL => self.add(REAR_WHEEL_ROLLING),
                REAR_FRAME => self.add(REAR_FRAME_ROLLING),
                FRONT_FRAME => self.add(FRONT_FRAME_ROLLING),
                _ => self.add(FRONT_WHEEL_ROLLING),
            }
        } else {
            self.add(std::array::from_fn::<usize, N, _>(|i| i));
        }
    }

    /// Adds `Jᵀ diag(m I₃, I) J` (upper triangle) and `Jᵀ (f − Mc)` over the body's C
    /// non-zero columns of J (ascending), every entry one contiguous dot product of length 6.
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

/// Copies the upper triangle of a square matrix into its lower triangle.
#[inline]
pub(crate) fn symmetrize<T: Real, const N: usize>(a: &mut SMatrix<T, N, N>) {
    for j in 0..N {
        for i in 0..j {
            a[(j, i)] = a[(i, j)];
        }
    }
}
