//! How well-conditioned the compared eigenvalues are: eigenvalue condition numbers, the zero
//! cluster of the full-state Jacobian (its Jordan structure and spread), and the two
//! diagnoses the comparison report shows — the conditioning near the double-root speed and the
//! capsize spike of the full-state methods (the cause is explained in `docs/validation.md`).

use nalgebra::{Complex, DMatrix, SMatrix};

use super::jacobians::{full_state_jacobian, full_state_jacobian_fd, lean_steer_matrix};
use super::picking::{faer_failure, general_eigenvalues, max_abs_diff, pick};
use super::{ComparisonSettings, ComparisonSweep, FullJacobian, Linearization};
use crate::analysis::eigen::{Complex64, eigenvalues};
use crate::error::{Error, Result};
use crate::linear::{Canonical, StateSpace};
use crate::nonlinear::{Model, STATE_LEN};
use crate::parameters::BenchmarkParameters;

/// Half-width of the interval about v_d where the eigenvalues are ill-conditioned by nature
/// (two real eigenvalues meet there) [m/s].
pub(crate) const DOUBLE_ROOT_HALF_WIDTH: f64 = 0.02;
/// Half-width of the interval about v_c called "near the capsize speed" [m/s].
pub(crate) const CAPSIZE_HALF_WIDTH: f64 = 0.25;

/// Right eigenvectors of a real square matrix, with their eigenvalues (faer).
fn eigenvectors<const N: usize>(
    a: &SMatrix<f64, N, N>,
) -> Result<(Vec<Complex64>, DMatrix<Complex64>)> {
    let m = faer::Mat::<f64>::from_fn(N, N, |i, j| a[(i, j)]);
    let evd = m.eigen().map_err(faer_failure)?;
    let u = evd.U();
    let s = evd.S().column_vector();
    let values = (0..N).map(|k| Complex::new(s[k].re, s[k].im)).collect();
    let vectors = DMatrix::<Complex64>::from_fn(N, N, |i, j| {
        let z = u[(i, j)];
        Complex::new(z.re, z.im)
    });
    Ok((values, vectors))
}

/// The eigenvalue of `a` nearest `near` and its condition number
/// κ = ‖x‖ ‖y‖ / |yᴴ x| (x, y: its right and left eigenvectors, the left ones from Aᵀ): a
/// perturbation of size ε of the matrix moves a simple eigenvalue by up to about κ ε; κ grows
/// without bound as the eigenvalue approaches a defective one.
pub(crate) fn eigenvalue_condition<const N: usize>(
    a: &SMatrix<f64, N, N>,
    near: Complex64,
) -> Result<(Complex64, f64)> {
    let nearest = |values: &[Complex64]| {
        (0..values.len())
            .min_by(|&i, &j| {
                crate::math::norm(values[i] - near).total_cmp(&crate::math::norm(values[j] - near))
            })
            .unwrap_or(0)
    };
    let (values, right) = eigenvectors(a)?;
    let (left_values, left) = eigenvectors(&a.transpose())?;
    let (k, l) = (nearest(&values), nearest(&left_values));
    let x = right.column(k);
    // A left eigenvector y of A for λ is the conjugate of a right eigenvector of Aᵀ for λ.
    let y_bar = left.column(l);
    let overlap: Complex64 = y_bar.iter().zip(x.iter()).map(|(p, q)| p * q).sum();
    Ok((
        values[k],
        x.norm() * y_bar.norm() / crate::math::norm(overlap),
    ))
}

/// The cluster of zero eigenvalues of a full-state Jacobian: its Jordan structure and how far
/// round-off or derivative errors have spread it.
#[derive(Debug, Clone, PartialEq)]
pub struct ZeroCluster {
    /// dim ker Aᵏ for k = 1…5 (singular values below 1e-9 of the largest): the number of
    /// Jordan blocks at zero, then how many reach sizes 2, 3, … (differences of successive
    /// entries). A non-defective zero would give equal entries.
    pub kernel_dims: [usize; 5],
    /// The largest |λ| among the eigenvalues of the cluster (the `kernel_dims[4]` smallest in
    /// modulus, less any picked as lean and steer): zero in exact arithmetic.
    pub radius: f64,
}

/// The zero cluster of `a` (see `ZeroCluster`); `lean_steer` are the eigenvalues of `a`
/// picked as lean and steer, left out of the radius.
pub fn zero_cluster(a: &FullJacobian, lean_steer: &[Complex64; 4]) -> Result<ZeroCluster> {
    let n = STATE_LEN;
    let m = DMatrix::from_fn(n, n, |i, j| a[(i, j)]);
    let mut power = DMatrix::<f64>::identity(n, n);
    let mut kernel_dims = [0usize; 5];
    for dim in kernel_dims.iter_mut() {
        power = &power * &m;
        let svd = power
            .clone()
            .try_svd(false, false, f64::EPSILON, 1000)
            .ok_or(Error::NoConvergence {
                method: "singular value decomposition",
                iterations: 1000,
                residual: f64::NAN,
            })?;
        let top = svd.singular_values.max();
        *dim = svd
            .singular_values
            .iter()
            .filter(|s| **s <= 1e-9 * top)
            .count();
    }
    // The cluster: the dim ker A⁵ eigenvalues smallest in modulus (the algebraic multiplicity
    // of zero), less any picked as lean and steer (the capsize eigenvalue near v_c).
    let mut values = general_eigenvalues(a)?;
    values.sort_by(|p, q| crate::math::norm(p).total_cmp(&crate::math::norm(q)));
    let radius = values
        .iter()
        .take(kernel_dims[4])
        .filter(|z| !lean_steer.contains(z))
        .map(crate::math::norm)
        .fold(0.0, f64::max);
    Ok(ZeroCluster {
        kernel_dims,
        radius,
    })
}

/// The exact method's agreement near the double-root speed v_d, where the eigenvalues are
/// ill-conditioned by nature, measured against first-order perturbation theory
/// (|Δλ| ≲ κ‖ΔA‖, with ‖ΔA‖₂ ≤ 4 max |ΔA_ij| for a 4 × 4 matrix).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoubleRootConditioning {
    /// v_d [m/s].
    pub double_root_speed: f64,
    /// The half-width of the interval about v_d looked at [m/s]
    /// ([`DOUBLE_ROOT_HALF_WIDTH`]).
    pub half_width: f64,
    /// The largest eigenvalue difference within v_d ± half-width [1/s].
    pub max_diff: f64,
    /// The largest max |A − A_linear| there (absolute) [1/s²].
    pub max_matrix_diff: f64,
    /// The largest eigenvalue condition number κ of the linear A there.
    pub max_condition: f64,
    /// The largest |Δλ| / (κ · 4 max |ΔA_ij|) there (above 1: the eigen-solvers' own round-off
    /// at a nearly double root, of order √ε).
    pub max_ratio: f64,
    /// The largest eigenvalue difference outside v_d ± half-width [1/s].
    pub max_diff_away: f64,
}

/// The conditioning of the exact method near v_d (see `DoubleRootConditioning`); `None`
/// when the sweep has no double-root speed or no exact method.
pub fn double_root_conditioning(
    bike: &BenchmarkParameters,
    sweep: &ComparisonSweep,
) -> Result<Option<DoubleRootConditioning>> {
    let (Some(vd), Some(exact)) = (
        sweep.critical.double_root_speed,
        sweep.method(Linearization::Exact),
    ) else {
        return Ok(None);
    };
    let d = DOUBLE_ROOT_HALF_WIDTH;
    let model = Model::new(bike)?;
    let canonical = Canonical::new(bike)?;
    let mut worst_diff = 0.0f64;
    let mut worst_delta_a = 0.0f64;
    let mut worst_kappa = 0.0f64;
    let mut worst_ratio = 0.0f64;
    for (i, v) in sweep.speeds.iter().enumerate() {
        if (v - vd).abs() > d {
            continue;
        }
        let a = lean_steer_matrix(&model, *v)?;
        let linear = StateSpace::new(&canonical, *v)?.a;
        let delta_a = (a - linear).amax();
        let mut kappa = 0.0f64;
        for l in &sweep.linear[i] {
            kappa = kappa.max(eigenvalue_condition(&linear, *l)?.1);
        }
        worst_diff = worst_diff.max(exact.max_abs_diff[i]);
        worst_delta_a = worst_delta_a.max(delta_a);
        worst_kappa = worst_kappa.max(kappa);
        if delta_a > 0.0 {
            worst_ratio = worst_ratio.max(exact.max_abs_diff[i] / (kappa * 4.0 * delta_a));
        }
    }
    let away = sweep
        .speeds
        .iter()
        .zip(&exact.max_abs_diff)
        .filter(|(v, _)| (*v - vd).abs() > d)
        .map(|(_, x)| *x)
        .fold(0.0f64, f64::max);
    Ok(Some(DoubleRootConditioning {
        double_root_speed: vd,
        half_width: d,
        max_diff: worst_diff,
        max_matrix_diff: worst_delta_a,
        max_condition: worst_kappa,
        max_ratio: worst_ratio,
        max_diff_away: away,
    }))
}

/// One full-state Jacobian near the capsize speed: the evidence for the spike.
#[derive(Debug, Clone, PartialEq)]
pub struct SpikeRow {
    /// v [m/s].
    pub speed: f64,
    /// The linear model's capsize eigenvalue there (its real eigenvalue nearest zero) [1/s].
    pub capsize: Complex64,
    /// Which full-state Jacobian: [`Linearization::FullStateExact`] or
    /// [`Linearization::FiniteDifferences`] (the study's, projected).
    pub jacobian: Linearization,
    /// Its zero cluster.
    pub cluster: ZeroCluster,
    /// The condition number of its eigenvalue nearest the capsize one.
    pub condition: f64,
    /// max |λ − λ_linear| of the four picked eigenvalues [1/s].
    pub max_abs_diff: f64,
}

/// The speeds about v_c at which [`capsize_spike`] looks [m/s].
pub(crate) const SPIKE_OFFSETS: [f64; 6] = [-0.5, -0.05, -0.01, 0.01, 0.05, 0.5];

/// The capsize spike's evidence at v_c + `SPIKE_OFFSETS`: for the exact full-state Jacobian
/// and the study's, the zero cluster, the capsize eigenvalue's condition number and the
/// eigenvalue difference.
pub fn capsize_spike(bike: &BenchmarkParameters, capsize_speed: f64) -> Result<Vec<SpikeRow>> {
    let model = Model::new(bike)?;
    let canonical = Canonical::new(bike)?;
    let mut rows = Vec::with_capacity(2 * SPIKE_OFFSETS.len());
    for offset in SPIKE_OFFSETS {
        let v = capsize_speed + offset;
        let linear = eigenvalues(&canonical, v)?;
        let capsize = linear
            .iter()
            .filter(|l| l.im == 0.0)
            .min_by(|a, b| crate::math::norm(*a).total_cmp(&crate::math::norm(*b)))
            .copied()
            .unwrap_or_default();
        let exact = full_state_jacobian(&model, v)?;
        let fd = full_state_jacobian_fd(&model, v, &ComparisonSettings::default())?.jacobian;
        for (jacobian, j) in [
            (Linearization::FullStateExact, exact),
            (Linearization::FiniteDifferences, fd),
        ] {
            let picked = pick(&linear, &general_eigenvalues(&j)?)?;
            let cluster = zero_cluster(&j, &picked)?;
            let (_, condition) = eigenvalue_condition(&j, capsize)?;
            rows.push(SpikeRow {
                speed: v,
                capsize,
                jacobian,
                cluster,
                condition,
                max_abs_diff: max_abs_diff(&picked, &linear),
            });
        }
    }
    Ok(rows)
}
