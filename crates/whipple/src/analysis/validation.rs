//! Validation of the non-linear model against the linear one (Dressel's JBike6 study, redone):
//! the non-linear equations linearized about upright straight running at speed v, their
//! eigenvalues compared with the linear model's.
//!
//! Three ways to linearize ([`Method`]):
//!
//! - [`Method::FiniteDifferences`], the study's: central differences over the full state
//!   y = [q; u] (48 numbers), each perturbed state projected onto the constraints as the study
//!   did, the step of each column chosen by decimation ([`FdParams`]); the 48 eigenvalues of
//!   that Jacobian, and the four that belong to lean and steer picked out by matching them to
//!   the linear eigenvalues (an optimal assignment). The picking uses the linear result: the
//!   full state has no other way to say which four eigenvalues are lean and steer.
//! - [`Method::FullStateExact`]: the same full-state Jacobian by dual numbers (exact
//!   derivatives, no projection), the same picking. A diagnostic: it separates what the
//!   derivatives contribute from what the full state contributes.
//! - [`Method::Exact`]: exact derivatives (dual numbers) of the model reduced to the linear
//!   model's state x = [φ, δ, φ̇, δ̇] on the constraint manifold ([`lean_steer_matrix`]): a 4×4
//!   A(v), comparable entry by entry with the linear model's, with no other eigenvalues to pick
//!   from.
//!
//! **Why the full state fails near the capsize speed.** Besides the four lean and steer
//! eigenvalues, the 48 × 48 Jacobian has 44 eigenvalues at zero: the ignorable coordinates
//! (yaw, rear contact position, wheel rotations) and the forward speed, and the 38 directions
//! off the constraint manifold (a velocity-constraint violation persists, a position
//! violation grows linearly). Many of these form Jordan chains (a yaw error makes the lateral
//! position grow, a speed error the wheel angles, a velocity violation the position
//! violation): zero is a defective eigenvalue. A perturbation of size ε of a matrix with a
//! Jordan block of size k moves its eigenvalues by about ε^(1/k), so the derivative errors of
//! differencing (and even round-off) spread the zero cluster over a disc of radius about √ε.
//! The capsize eigenvalue crosses zero at v_c: there it enters that disc, becomes
//! ill-conditioned itself (its left and right eigenvectors turn nearly orthogonal) and can be
//! confused with a cluster member. [`full_state_spectrum`] measures this (eigenvalue condition
//! numbers from left and right eigenvectors). The reduced 4×4 A(v) has no zero cluster, so no
//! spike.

use nalgebra::{Complex, DMatrix, Matrix4, SMatrix, SVector, Vector4};

use super::eigen::{quartic_roots, Complex64};
use super::linearize::{central_differences, jacobian, FdJacobian, FdParams};
use super::modes::Mode;
use super::stability::{critical_speeds, CriticalSpeeds};
use super::sweep::eigen_sweep;
use crate::error::{Error, Result};
use crate::linear::{Canonical, StateSpace};
use crate::nonlinear::reduced::{spin_free_derivative, spin_free_vector, state_from_spin_free};
use crate::nonlinear::{
    FullStateField, InitialConditions, LeanSteerField, Model, ProjectionMethod, ProjectionSettings,
    State, STATE_LEN,
};
use crate::parameters::BenchmarkParameters;

/// The full-state Jacobian (48 × 48).
pub type FullJacobian = SMatrix<f64, STATE_LEN, STATE_LEN>;

/// A linearization method of the non-linear model about upright straight running.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// The study's: central differences over the full state with step decimation and
    /// projection, lean and steer eigenvalues picked from the 48.
    FiniteDifferences,
    /// Exact derivatives (dual numbers) of the model reduced to [φ, δ, φ̇, δ̇]: a 4×4 A(v).
    Exact,
    /// Exact derivatives (dual numbers) over the full state, lean and steer eigenvalues picked
    /// from the 48 (a diagnostic of the capsize spike).
    FullStateExact,
}

impl Method {
    /// Short name used in file headers: `fd`, `ad`, `ad_full`.
    pub fn name(self) -> &'static str {
        match self {
            Method::FiniteDifferences => "fd",
            Method::Exact => "ad",
            Method::FullStateExact => "ad_full",
        }
    }

    /// A description for legends and reports.
    pub fn description(self) -> &'static str {
        match self {
            Method::FiniteDifferences => "finite differences, full state (the study's method)",
            Method::Exact => "exact derivatives, reduced to lean and steer",
            Method::FullStateExact => "exact derivatives, full state",
        }
    }
}

/// Settings of the study's finite-difference method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudyParams {
    /// Step decimation (default [`FdParams::default`]).
    pub fd: FdParams,
    /// Projection of every perturbed state onto the constraints before its derivative is
    /// evaluated, as the study did; `None` evaluates the perturbed state as it is. Default: the
    /// study's least-norm projection ([`ProjectionMethod::LeastNorm`]), tolerance 1e-13, at
    /// least one Newton iteration.
    pub projection: Option<ProjectionSettings>,
}

impl Default for StudyParams {
    fn default() -> Self {
        StudyParams {
            fd: FdParams::default(),
            projection: Some(ProjectionSettings {
                method: ProjectionMethod::LeastNorm,
                ..ProjectionSettings::default()
            }),
        }
    }
}

/// The consistent full state of upright straight running at `speed`.
pub fn upright_state(model: &Model, speed: f64) -> Result<State<f64>> {
    model.initial_state(&InitialConditions::upright(speed))
}

/// The non-linear model's A(v) for x = [φ, δ, φ̇, δ̇] about upright straight running at
/// `speed`, by exact forward-mode derivatives of [`Model::lean_steer_field`]; comparable entry
/// by entry with the linear model's [`StateSpace::a`].
///
/// ```
/// use whipple::{BenchmarkParameters, linear::{Canonical, StateSpace}, nonlinear::Model};
/// use whipple::analysis::validation::lean_steer_matrix;
/// let bike = BenchmarkParameters::meijaard2007();
/// let a = lean_steer_matrix(&Model::new(&bike)?, 5.0)?;
/// let linear = StateSpace::new(&Canonical::new(&bike)?, 5.0)?.a;
/// assert!((a - linear).amax() < 1e-12 * linear.amax());
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn lean_steer_matrix(model: &Model, speed: f64) -> Result<Matrix4<f64>> {
    check_speed(speed)?;
    jacobian(&LeanSteerField { model, speed }, &Vector4::zeros())
}

/// The full-state Jacobian ∂[q̇; u̇]/∂[q; u] about upright straight running at `speed`, exact
/// (dual numbers, 48 passes of the model).
pub fn full_state_jacobian(model: &Model, speed: f64) -> Result<FullJacobian> {
    check_speed(speed)?;
    let y0 = spin_free_vector(&upright_state(model, speed)?);
    jacobian(&FullStateField { model }, &y0)
}

/// The full-state Jacobian by the study's method: central differences with step decimation,
/// each perturbed state projected onto the constraints (see [`StudyParams`]).
pub fn full_state_jacobian_fd(
    model: &Model,
    speed: f64,
    params: &StudyParams,
) -> Result<FdJacobian<STATE_LEN>> {
    check_speed(speed)?;
    let y0 = spin_free_vector(&upright_state(model, speed)?);
    let field = |y: &SVector<f64, STATE_LEN>| -> Result<SVector<f64, STATE_LEN>> {
        let mut state = state_from_spin_free(y);
        if let Some(p) = &params.projection {
            model.project(&mut state, p)?;
        }
        let d = model.forward(&state, &crate::nonlinear::Inputs::default())?;
        Ok(spin_free_derivative(&state, &d))
    };
    central_differences(field, &y0, &params.fd)
}

fn check_speed(speed: f64) -> Result<()> {
    if speed.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument {
            what: "speed",
            rule: format!("must be a finite number, got {speed}"),
        })
    }
}

/// The four eigenvalues of a lean–steer state matrix A = [[0, I], [X, Y]] as the roots of
/// det(λ²I − λY − X), by the same quartic solver as the linear model's; sorted by decreasing
/// real part. Only the lower two rows of `a` enter (the upper two are [0 I] by construction).
pub fn lean_steer_eigenvalues(a: &Matrix4<f64>) -> Result<[Complex64; 4]> {
    let x = |i: usize, j: usize| a[(2 + i, j)];
    let y = |i: usize, j: usize| a[(2 + i, 2 + j)];
    let a0 = x(0, 0) * x(1, 1) - x(0, 1) * x(1, 0);
    let a1 = y(0, 0) * x(1, 1) + y(1, 1) * x(0, 0) - y(0, 1) * x(1, 0) - x(0, 1) * y(1, 0);
    let a2 = y(0, 0) * y(1, 1) - x(0, 0) - x(1, 1) - y(0, 1) * y(1, 0);
    let a3 = -(y(0, 0) + y(1, 1));
    quartic_roots(&[a0, a1, a2, a3, 1.0])
}

/// The eigenvalues of a square matrix (faer's general eigensolver, bounded).
pub fn general_eigenvalues<const N: usize>(a: &SMatrix<f64, N, N>) -> Result<Vec<Complex64>> {
    let m = faer::Mat::<f64>::from_fn(N, N, |i, j| a[(i, j)]);
    let values = m.eigenvalues().map_err(|e| Error::NoConvergence {
        method: faer_failure(&e),
        iterations: 0,
        residual: f64::NAN,
    })?;
    Ok(values.iter().map(|z| Complex::new(z.re, z.im)).collect())
}

fn faer_failure(_: &faer::linalg::evd::EvdError) -> &'static str {
    "faer's general eigensolver (QR iteration)"
}

/// Assigns to each of the four `targets` a distinct member of `candidates`, minimising the sum
/// of the distances (an optimal assignment). Returns the candidates' indices.
///
/// Only the four nearest candidates of each target can take part in an optimal assignment
/// (were one assigned further away, one of its four nearest would be free, and closer), so the
/// search is over at most 4⁴ combinations.
pub fn assign(targets: &[Complex64; 4], candidates: &[Complex64]) -> Result<[usize; 4]> {
    if candidates.len() < 4 {
        return Err(Error::InvalidArgument {
            what: "candidates",
            rule: format!("need at least four eigenvalues, got {}", candidates.len()),
        });
    }
    let nearest: [Vec<usize>; 4] = std::array::from_fn(|t| {
        let mut idx: Vec<usize> = (0..candidates.len()).collect();
        idx.sort_by(|&a, &b| {
            (candidates[a] - targets[t])
                .norm()
                .total_cmp(&(candidates[b] - targets[t]).norm())
        });
        idx.truncate(4);
        idx
    });
    let mut best = ([0usize; 4], f64::INFINITY);
    for a in &nearest[0] {
        for b in &nearest[1] {
            for c in &nearest[2] {
                for d in &nearest[3] {
                    let pick = [*a, *b, *c, *d];
                    if (0..4).any(|i| (0..i).any(|j| pick[i] == pick[j])) {
                        continue;
                    }
                    let cost: f64 = (0..4)
                        .map(|i| (candidates[pick[i]] - targets[i]).norm())
                        .sum();
                    if cost < best.1 {
                        best = (pick, cost);
                    }
                }
            }
        }
    }
    if best.1.is_finite() {
        Ok(best.0)
    } else {
        Err(Error::NonFinite {
            context: "assignment of eigenvalues".into(),
        })
    }
}

/// The members of `candidates` assigned to `targets` (see [`assign`]), in the targets' order.
pub fn pick(targets: &[Complex64; 4], candidates: &[Complex64]) -> Result<[Complex64; 4]> {
    Ok(assign(targets, candidates)?.map(|i| candidates[i]))
}

/// The largest |λ_method − λ_linear| over four matched pairs.
pub fn max_abs_diff(a: &[Complex64; 4], b: &[Complex64; 4]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max)
}

/// One method's linearization at one speed, compared with the linear model.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The lean and steer eigenvalues [1/s], matched to the linear ones (same order).
    pub eigenvalues: [Complex64; 4],
    /// max |λ − λ_linear| over the four [1/s].
    pub max_abs_diff: f64,
    /// For [`Method::Exact`]: max |A − A_linear| / max |A_linear|.
    pub matrix_rel_diff: Option<f64>,
}

/// Linearizes `model` at `speed` by `method` and compares with the linear eigenvalues
/// `linear` (in the order to match) and, for the exact method, the linear `A`.
pub fn compare(
    model: &Model,
    canonical: &Canonical,
    speed: f64,
    linear: &[Complex64; 4],
    method: Method,
    study: &StudyParams,
) -> Result<Comparison> {
    match method {
        Method::Exact => {
            let a = lean_steer_matrix(model, speed)?;
            let a_linear = StateSpace::new(canonical, speed)?.a;
            let values = lean_steer_eigenvalues(&a)?;
            let eigenvalues = pick(linear, &values)?;
            Ok(Comparison {
                max_abs_diff: max_abs_diff(&eigenvalues, linear),
                eigenvalues,
                matrix_rel_diff: Some((a - a_linear).amax() / a_linear.amax()),
            })
        }
        Method::FiniteDifferences | Method::FullStateExact => {
            let a = if method == Method::FiniteDifferences {
                full_state_jacobian_fd(model, speed, study)?.jacobian
            } else {
                full_state_jacobian(model, speed)?
            };
            let values = general_eigenvalues(&a)?;
            let eigenvalues = pick(linear, &values)?;
            Ok(Comparison {
                max_abs_diff: max_abs_diff(&eigenvalues, linear),
                eigenvalues,
                matrix_rel_diff: None,
            })
        }
    }
}

/// One method over a sweep of speeds.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodSweep {
    /// The method.
    pub method: Method,
    /// Per speed, the lean and steer eigenvalues matched to [`ValidationSweep::linear`].
    pub eigenvalues: Vec<[Complex64; 4]>,
    /// Per speed, max |λ − λ_linear| [1/s].
    pub max_abs_diff: Vec<f64>,
    /// Per speed, max |A − A_linear| / max |A_linear| (exact method only).
    pub matrix_rel_diff: Option<Vec<f64>>,
}

/// The validation of the non-linear model over a sweep of speeds.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidationSweep {
    /// Forward speeds v [m/s].
    pub speeds: Vec<f64>,
    /// The linear model's eigenvalues per speed, in mode columns (see
    /// [`crate::analysis::sweep::EigenSweep`]).
    pub linear: Vec<[Complex64; 4]>,
    /// The mode of each column.
    pub modes: [Mode; 4],
    /// Critical speeds of the linear model over the swept range.
    pub critical: CriticalSpeeds,
    /// One entry per method asked for, in the order asked.
    pub methods: Vec<MethodSweep>,
}

/// Validates the non-linear model of `bike` against the linear one at every speed of
/// `speeds` (sorted, as from [`crate::analysis::sweep::speed_grid`]) by each of `methods`.
///
/// ```
/// use whipple::{BenchmarkParameters, analysis::validation::{validate, Method, StudyParams}};
/// let sweep = validate(&BenchmarkParameters::meijaard2007(), &[1.0, 5.0], &[Method::Exact],
///                      &StudyParams::default())?;
/// assert!(sweep.methods[0].max_abs_diff.iter().all(|d| *d < 1e-11));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn validate(
    bike: &BenchmarkParameters,
    speeds: &[f64],
    methods: &[Method],
    study: &StudyParams,
) -> Result<ValidationSweep> {
    let canonical = Canonical::new(bike)?;
    let model = Model::new(bike)?;
    let eig = eigen_sweep(&canonical, speeds)?;
    let (lo, hi) = speeds
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let (lo, hi) = if lo < hi { (lo, hi) } else { (lo, lo + 1.0) };
    let critical = critical_speeds(&canonical, lo, hi)?;
    // Speeds are independent: share them among the machine's cores, in contiguous chunks.
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, speeds.len().max(1));
    let chunk = speeds.len().div_ceil(threads).max(1);
    let work = |range: std::ops::Range<usize>| -> Result<Vec<Vec<Comparison>>> {
        range
            .map(|i| {
                methods
                    .iter()
                    .map(|&m| compare(&model, &canonical, speeds[i], &eig.eigenvalues[i], m, study))
                    .collect::<Result<Vec<_>>>()
            })
            .collect()
    };
    let rows: Vec<Vec<Comparison>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..speeds.len())
            .step_by(chunk)
            .map(|start| {
                let range = start..(start + chunk).min(speeds.len());
                scope.spawn(move || work(range))
            })
            .collect();
        let mut all = Vec::with_capacity(speeds.len());
        for h in handles {
            let part = h.join().map_err(|_| Error::NonFinite {
                context: "a validation worker thread panicked".into(),
            })??;
            all.extend(part);
        }
        Ok::<_, Error>(all)
    })?;
    let out = methods
        .iter()
        .enumerate()
        .map(|(k, &method)| MethodSweep {
            method,
            eigenvalues: rows.iter().map(|r| r[k].eigenvalues).collect(),
            max_abs_diff: rows.iter().map(|r| r[k].max_abs_diff).collect(),
            matrix_rel_diff: (method == Method::Exact)
                .then(|| rows.iter().filter_map(|r| r[k].matrix_rel_diff).collect()),
        })
        .collect();
    Ok(ValidationSweep {
        speeds: speeds.to_vec(),
        linear: eig.eigenvalues,
        modes: eig.modes,
        critical,
        methods: out,
    })
}

impl ValidationSweep {
    /// The results of `method`, if it was asked for.
    pub fn method(&self, method: Method) -> Option<&MethodSweep> {
        self.methods.iter().find(|m| m.method == method)
    }
}

impl MethodSweep {
    /// The largest eigenvalue difference over the speeds in [lo, hi] and the speed where it
    /// occurs; `None` when no speed of the sweep lies there.
    pub fn max_diff_between(&self, speeds: &[f64], lo: f64, hi: f64) -> Option<(f64, f64)> {
        speeds
            .iter()
            .zip(&self.max_abs_diff)
            .filter(|(v, _)| **v >= lo && **v <= hi)
            .map(|(v, d)| (*d, *v))
            .fold(None, |best: Option<(f64, f64)>, x| match best {
                Some(b) if b.0 >= x.0 => Some(b),
                _ => Some(x),
            })
    }
}

/// Right eigenvectors of a real square matrix, with their eigenvalues (faer).
fn eigenvectors<const N: usize>(
    a: &SMatrix<f64, N, N>,
) -> Result<(Vec<Complex64>, DMatrix<Complex64>)> {
    let m = faer::Mat::<f64>::from_fn(N, N, |i, j| a[(i, j)]);
    let evd = m.eigen().map_err(|e| Error::NoConvergence {
        method: faer_failure(&e),
        iterations: 0,
        residual: f64::NAN,
    })?;
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
pub fn eigenvalue_condition<const N: usize>(
    a: &SMatrix<f64, N, N>,
    near: Complex64,
) -> Result<(Complex64, f64)> {
    let nearest = |values: &[Complex64]| {
        (0..values.len())
            .min_by(|&i, &j| {
                (values[i] - near)
                    .norm()
                    .total_cmp(&(values[j] - near).norm())
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
    Ok((values[k], x.norm() * y_bar.norm() / overlap.norm()))
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

/// The zero cluster of `a` (see [`ZeroCluster`]); `lean_steer` are the eigenvalues of `a`
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
    values.sort_by(|p, q| p.norm().total_cmp(&q.norm()));
    let radius = values
        .iter()
        .take(kernel_dims[4])
        .filter(|z| !lean_steer.contains(z))
        .map(|z| z.norm())
        .fold(0.0, f64::max);
    Ok(ZeroCluster {
        kernel_dims,
        radius,
    })
}
