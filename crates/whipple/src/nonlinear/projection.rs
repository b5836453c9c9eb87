//! Projection of a state back onto the constraints after an integration step, as in Dressel's
//! study: positions by Newton iteration on the 17 holonomic rows (always at least one
//! iteration), velocities by a least-norm correction onto the 21 velocity rows.
//!
//! Positions: `Δq = −Jᵀ (J Jᵀ)⁻¹ r(q)` with `J = ∂r/∂q` (17 × 24, the velocity rows times the
//! map from angle rates to body angular velocities), the least-norm Newton step; `J Jᵀ` is
//! factored by Cholesky.
//!
//! Velocities: `u ← u − Dᵀ (D Dᵀ)⁻¹ D u`, the orthogonal projection of u onto the null space of
//! all 21 velocity rows. It is computed in the nine tree speeds of [`super::tree`]: with
//! `u = T w` the joint rows hold identically, so the projection is
//! `min |T w − u|²` subject to `G w = 0`, a 15 × 15 saddle-point system; for a rolling rear wheel
//! its rows are solved for the hub velocity first (as in [`Model::forward`]), which leaves six
//! tree speeds and the three front rows, a 9 × 9 system with the same solution.

use nalgebra::{Matrix3, SMatrix, SVector};
use num_dual::Dual64;

use super::Model;
use super::assembly::{Reduced, symmetrize};
use super::poses::Poses;
use super::saddle;
use super::state::{BODY_LEAN, BODY_PITCH, BODY_YAW, COORDINATES, SPEEDS, State};
use super::topology::{
    BODIES, FRONT_CONTACT, FRONT_FRAME, FRONT_WHEEL, HOLONOMIC_ROWS, REAR_CONTACT, REAR_FRAME,
    REAR_WHEEL, row_bodies,
};
use super::tree::speeds_of;
use crate::error::{Error, Result};

/// How positions are brought back onto the holonomic constraints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProjectionMethod {
    /// The study's coordinate projection: least-norm Newton steps on all 24 coordinates,
    /// `Δq = −Jᵀ(JJᵀ)⁻¹ r` (17 × 17 Cholesky per iteration).
    LeastNorm,
    /// Coordinate partitioning: keep the independent coordinates as integrated (rear frame yaw
    /// and lean, steer, wheel rotations, rear contact x and y), solve the rear frame's pitch by
    /// scalar Newton iteration on the front contact height, and rebuild every other coordinate
    /// from the joints. About three times cheaper; the default.
    Coordinates,
}

/// Settings of the position projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectionSettings {
    /// The method. Default [`ProjectionMethod::Coordinates`].
    pub method: ProjectionMethod,
    /// Largest holonomic residual accepted near the origin \[m\]. Default 1e-13. The rows are
    /// differences of positions, so their round-off grows with the distance from the origin:
    /// the residual accepted is `tolerance · max(1, L / 1 m)`, with L the largest body position
    /// coordinate, a tolerance relative to the coordinates' scale (see `accepted_residual`).
    pub tolerance: f64,
    /// Newton iterations always made, even when the residual is already below tolerance
    /// (the study found one necessary to keep the drift from building up). Default 1.
    pub min_iterations: usize,
    /// Upper bound on Newton iterations; more means divergence. Default 10.
    pub max_iterations: usize,
}

impl Default for ProjectionSettings {
    fn default() -> Self {
        ProjectionSettings {
            method: ProjectionMethod::Coordinates,
            tolerance: 1e-13,
            min_iterations: 1,
            max_iterations: 10,
        }
    }
}

/// The largest holonomic residual accepted at q: `tolerance · max(1, L / 1 m)` with L the
/// largest absolute body position coordinate. A residual row is a difference of positions, so
/// its round-off is a few units in the last place of the positions' size: an absolute
/// tolerance would fail any run that goes far enough (at 1 km, one ulp is 1.1e-13 m).
pub(crate) fn accepted_residual(q: &SVector<f64, COORDINATES>, tolerance: f64) -> f64 {
    let scale = (0..BODIES)
        .flat_map(|k| (0..3).map(move |i| 6 * k + i))
        .map(|i| q[i].abs())
        .fold(1.0_f64, f64::max);
    tolerance * scale
}

/// What a position projection did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectionReport {
    /// Newton iterations made.
    pub iterations: usize,
    /// Largest absolute holonomic residual after projection.
    pub residual: f64,
}

/// J Jᵀ using the block sparsity of J: rows share columns only through a common body.
fn gram(
    j: &SMatrix<f64, HOLONOMIC_ROWS, COORDINATES>,
) -> SMatrix<f64, HOLONOMIC_ROWS, HOLONOMIC_ROWS> {
    let mut out = SMatrix::<f64, HOLONOMIC_ROWS, HOLONOMIC_ROWS>::zeros();
    let bodies: [[usize; 2]; HOLONOMIC_ROWS] = std::array::from_fn(row_bodies);
    for a in 0..HOLONOMIC_ROWS {
        for b in a..HOLONOMIC_ROWS {
            let mut sum = 0.0;
            for (n, &k) in bodies[a].iter().enumerate() {
                if n == 1 && k == bodies[a][0] {
                    continue;
                }
                if bodies[b].contains(&k) {
                    for col in 6 * k..6 * k + 6 {
                        sum += j[(a, col)] * j[(b, col)];
                    }
                }
            }
            out[(a, b)] = sum;
            out[(b, a)] = sum;
        }
    }
    out
}

impl Model {
    /// Moves q onto the holonomic constraints by Newton iteration (see [`ProjectionMethod`]).
    pub fn project_positions(
        &self,
        q: &mut SVector<f64, COORDINATES>,
        params: &ProjectionSettings,
    ) -> Result<ProjectionReport> {
        self.project_positions_posed(q, params)
            .map(|(report, _)| report)
    }

    /// [`Model::project_positions`], also returning the poses of the projected q.
    fn project_positions_posed(
        &self,
        q: &mut SVector<f64, COORDINATES>,
        params: &ProjectionSettings,
    ) -> Result<(ProjectionReport, Poses<f64>)> {
        match params.method {
            ProjectionMethod::LeastNorm => {
                let report = self.project_least_norm(q, params)?;
                Ok((report, Poses::new(q)))
            }
            ProjectionMethod::Coordinates => self.project_coordinates(q, params),
        }
    }

    /// Coordinate partitioning: see [`ProjectionMethod::Coordinates`].
    fn project_coordinates(
        &self,
        q: &mut SVector<f64, COORDINATES>,
        params: &ProjectionSettings,
    ) -> Result<(ProjectionReport, Poses<f64>)> {
        let b = 6 * REAR_FRAME;
        let (yaw, lean, mut pitch) = (q[b + BODY_YAW], q[b + BODY_LEAN], q[b + BODY_PITCH]);
        let poses = Poses::new(q);
        let steer = self.steer_at(&poses);
        let wheel_angles = [
            q[6 * REAR_WHEEL + BODY_PITCH] - pitch,
            q[6 * FRONT_WHEEL + BODY_PITCH] - q[6 * FRONT_FRAME + BODY_PITCH],
        ];
        let contact = self.contacts[REAR_CONTACT].point(&poses);
        let c = Dual64::from_re;
        let mut iterations = 0;
        loop {
            // The front contact's height does not depend on where the bicycle is on the
            // ground: compute it with the rear contact at the origin, free of the round-off of
            // far-away positions.
            let h = self.front_height(
                [c(yaw), c(lean), Dual64::new(pitch, 1.0)],
                c(steer),
                [c(0.0), c(0.0)],
            );
            let residual = h.re.abs();
            if !(residual.is_finite() && h.eps.is_finite() && h.eps != 0.0) {
                return Err(Error::ProjectionDiverged {
                    iterations,
                    residual,
                });
            }
            if iterations >= params.min_iterations && residual <= params.tolerance {
                break;
            }
            if iterations >= params.max_iterations {
                return Err(Error::ProjectionDiverged {
                    iterations,
                    residual,
                });
            }
            pitch -= h.re / h.eps;
            iterations += 1;
        }
        *q = self.configuration(
            [yaw, lean, pitch],
            steer,
            wheel_angles,
            [contact.x, contact.y],
        );
        let poses = Poses::new(q);
        let residual = self.holonomic_residual_at(&poses).amax();
        if residual.is_nan() || residual > accepted_residual(q, params.tolerance) {
            return Err(Error::ProjectionDiverged {
                iterations,
                residual,
            });
        }
        Ok((
            ProjectionReport {
                iterations,
                residual,
            },
            poses,
        ))
    }

    /// The study's least-norm Newton projection: see [`ProjectionMethod::LeastNorm`].
    fn project_least_norm(
        &self,
        q: &mut SVector<f64, COORDINATES>,
        params: &ProjectionSettings,
    ) -> Result<ProjectionReport> {
        let mut r = self.holonomic_residual(q);
        let mut iterations = 0;
        loop {
            let residual = r.amax();
            if !residual.is_finite() {
                return Err(Error::ProjectionDiverged {
                    iterations,
                    residual,
                });
            }
            if iterations >= params.min_iterations
                && residual <= accepted_residual(q, params.tolerance)
            {
                return Ok(ProjectionReport {
                    iterations,
                    residual,
                });
            }
            if iterations >= params.max_iterations {
                return Err(Error::ProjectionDiverged {
                    iterations,
                    residual,
                });
            }
            let j = self.holonomic_jacobian(q);
            let y = gram(&j)
                .cholesky()
                .map(|c| c.solve(&r))
                .ok_or(Error::ProjectionDiverged {
                    iterations,
                    residual,
                })?;
            *q -= j.transpose() * y;
            iterations += 1;
            r = self.holonomic_residual(q);
        }
    }

    /// Replaces u by its least-norm correction onto the velocity constraints at q.
    pub fn project_velocities(&self, state: &mut State<f64>) -> Result<()> {
        self.project_velocities_at(&Poses::new(&state.q), state)
    }

    /// [`Model::project_velocities`] with the poses of `state.q` already known. For a rolling
    /// rear wheel the rear contact rows are solved for the hub velocity first
    /// ([`Model::roll_on_rear_wheel`]), which leaves six tree speeds and the three front rows.
    fn project_velocities_at(&self, poses: &Poses<f64>, state: &mut State<f64>) -> Result<()> {
        let (tree, _) = self.tree(poses, &SVector::zeros());
        state.u = if self.contacts[REAR_CONTACT].is_skate() {
            let jac = tree.jacobians();
            let (g, _) = self.contact_rows(poses, &tree, &jac, &tree.bias);
            least_norm_speeds(&jac, &g, &state.u)?
        } else {
            let rolling = self.roll_on_rear_wheel(poses, &tree);
            let (g, _, _) =
                self.contact_rows_in(FRONT_CONTACT, poses, &tree, &rolling.jac, &rolling.bias);
            least_norm_speeds(&rolling.jac, &g, &state.u)?
        };
        Ok(())
    }

    /// Positions, then velocities at the new positions.
    pub fn project(
        &self,
        state: &mut State<f64>,
        params: &ProjectionSettings,
    ) -> Result<ProjectionReport> {
        self.project_posed(state, params).map(|(report, _)| report)
    }

    /// [`Model::project`], also returning the poses of the projected coordinates (the
    /// simulation's sample reuses them).
    pub(crate) fn project_posed(
        &self,
        state: &mut State<f64>,
        params: &ProjectionSettings,
    ) -> Result<(ProjectionReport, Poses<f64>)> {
        let (report, poses) = self.project_positions_posed(&mut state.q, params)?;
        self.project_velocities_at(&poses, state)?;
        Ok((report, poses))
    }
}

/// The speeds `T w` nearest to u (least squares over all 24 speeds, unweighted) among those
/// with `G w = 0`: `min |T w − u|²` subject to `G w = 0`, whose normal equations `TᵀT w = Tᵀu`
/// are assembled body by body (m = 1, I = identity).
fn least_norm_speeds<const N: usize, const M: usize>(
    jac: &[SMatrix<f64, 6, N>; BODIES],
    g: &SMatrix<f64, M, N>,
    u: &SVector<f64, SPEEDS>,
) -> Result<SVector<f64, SPEEDS>> {
    let mut gram = SMatrix::<f64, N, N>::zeros();
    let mut rhs = SVector::<f64, N>::zeros();
    for (k, jac) in jac.iter().enumerate() {
        let mut share = Reduced {
            mass: &mut gram,
            force: &mut rhs,
            jac,
            m: 1.0,
            inertia: Matrix3::identity(),
            generalized: u.fixed_rows::<6>(6 * k).into_owned(),
        };
        share.add_body(k);
    }
    symmetrize(&mut gram);
    let (w, _) = saddle::solve(&gram, g, &rhs, &SVector::zeros(), 0.0).ok_or_else(|| {
        Error::SingularDynamics {
            context: "velocity projection: singular constraint rows".into(),
        }
    })?;
    Ok(speeds_of(jac, &w))
}
