//! The non-linear model linearized about upright straight running at speed v: its own 4 × 4
//! A(v) on the lean–steer state (exact, by dual numbers), and the 48 × 48 full-state Jacobian,
//! exact or by the study's decimated central differences with projection.

use nalgebra::{Matrix4, SMatrix, SVector, Vector4};

use crate::analysis::linearize::{FdJacobian, FdSettings, central_differences, jacobian};
use crate::error::Result;
use crate::nonlinear::reduced::{spin_free_derivative, spin_free_vector, state_from_spin_free};
use crate::nonlinear::{
    FullStateField, InitialConditions, Inputs, LeanSteerField, Model, ProjectionMethod,
    ProjectionSettings, STATE_LEN, State,
};

/// The full-state Jacobian (48 × 48).
pub(crate) type FullJacobian = SMatrix<f64, STATE_LEN, STATE_LEN>;

/// Settings of the study's finite-difference method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComparisonSettings {
    /// Step decimation (default [`FdSettings::default`]).
    pub fd: FdSettings,
    /// Projection of every perturbed state onto the constraints before its derivative is
    /// evaluated, as the study did; `None` evaluates the perturbed state as it is. Default: the
    /// study's least-norm projection ([`ProjectionMethod::LeastNorm`]), tolerance 1e-13, at
    /// least one Newton iteration.
    pub projection: Option<ProjectionSettings>,
}

impl Default for ComparisonSettings {
    fn default() -> Self {
        ComparisonSettings {
            fd: FdSettings::default(),
            projection: Some(ProjectionSettings {
                method: ProjectionMethod::LeastNorm,
                ..ProjectionSettings::default()
            }),
        }
    }
}

/// The consistent full state of upright straight running at `speed`.
pub(crate) fn upright_state(model: &Model, speed: f64) -> Result<State<f64>> {
    model.initial_state(&InitialConditions::upright(speed))
}

/// The non-linear model's A(v) for x = [φ, δ, φ̇, δ̇] about upright straight running at
/// `speed`, by exact forward-mode derivatives of [`Model::lean_steer_field`]; comparable entry
/// by entry with the linear model's `StateSpace::a` (`crate::StateSpace`).
///
/// ```
/// use whipple::advanced::comparison::lean_steer_matrix;
/// use whipple::{BenchmarkParameters, Canonical, Model};
/// use whipple::advanced::linear::StateSpace;
/// let bike = BenchmarkParameters::meijaard2007();
/// let a = lean_steer_matrix(&Model::new(&bike)?, 5.0)?;
/// let linear = StateSpace::new(&Canonical::new(&bike)?, 5.0)?.a;
/// assert!((a - linear).amax() < 1e-12 * linear.amax());
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn lean_steer_matrix(model: &Model, speed: f64) -> Result<Matrix4<f64>> {
    crate::analysis::eigen::check_speed(speed)?;
    jacobian(&LeanSteerField { model, speed }, &Vector4::zeros())
}

/// The full-state Jacobian ∂[q̇; u̇]/∂[q; u] about upright straight running at `speed`, exact
/// (dual numbers, 48 passes of the model).
pub fn full_state_jacobian(model: &Model, speed: f64) -> Result<FullJacobian> {
    crate::analysis::eigen::check_speed(speed)?;
    let y0 = spin_free_vector(&upright_state(model, speed)?);
    jacobian(&FullStateField { model }, &y0)
}

/// The full-state Jacobian by the study's method: central differences with step decimation,
/// each perturbed state projected onto the constraints (see [`ComparisonSettings`]).
pub fn full_state_jacobian_fd(
    model: &Model,
    speed: f64,
    params: &ComparisonSettings,
) -> Result<FdJacobian<STATE_LEN>> {
    crate::analysis::eigen::check_speed(speed)?;
    let y0 = spin_free_vector(&upright_state(model, speed)?);
    let field = |y: &SVector<f64, STATE_LEN>| -> Result<SVector<f64, STATE_LEN>> {
        let mut state = state_from_spin_free(y);
        if let Some(p) = &params.projection {
            model.project(&mut state, p)?;
        }
        let d = model.forward(&state, &Inputs::default())?;
        Ok(spin_free_derivative(&state, &d))
    };
    central_differences(field, &y0, &params.fd)
}
