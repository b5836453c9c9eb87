//! The non-linear model compared with the linear one (Dressel's JBike6 benchmark, redone): the
//! non-linear equations linearized about upright straight running at speed v, their
//! eigenvalues compared with the linear model's, speed by speed.
//!
//! Three ways to linearize ([`Linearization`]):
//!
//! - [`Linearization::FiniteDifferences`], the study's: central differences over the full state
//!   y = [q; u] (48 numbers), each perturbed state projected onto the constraints as the study
//!   did, the step of each column chosen by decimation
//!   ([`FdSettings`](crate::analysis::linearize::FdSettings)); the 48 eigenvalues of
//!   that Jacobian, and the four that belong to lean and steer picked out by matching them to
//!   the linear eigenvalues (an optimal assignment). The picking uses the linear result: the
//!   full state has no other way to say which four eigenvalues are lean and steer.
//! - [`Linearization::FullStateExact`]: the same full-state Jacobian by dual numbers (exact
//!   derivatives, no projection), the same picking. A diagnostic: it separates what the
//!   derivatives contribute from what the full state contributes.
//! - [`Linearization::Exact`]: exact derivatives (dual numbers) of the model reduced to the
//!   linear model's state x = [φ, δ, φ̇, δ̇] on the constraint manifold ([`lean_steer_matrix`]):
//!   a 4×4 A(v), comparable entry by entry with the linear model's, with no other eigenvalues
//!   to pick from.
//!
//! The full-state methods show a spike near the capsize speed and the reduced one does not;
//! why (a defective cluster of zero eigenvalues in the 48 × 48 Jacobian) is explained, with the
//! evidence, in `docs/validation.md` of the repository; [`capsize_spike`] and [`zero_cluster`]
//! compute that evidence.
//!
//! Files: `jacobians.rs` (the linearizations), `picking.rs` (eigenvalues and their
//! assignment), `conditioning.rs` (condition numbers, the zero cluster, the report's
//! diagnoses), this file (the comparison over a sweep).
//!
//! Words: *validate* always means checking input against rules
//! ([`crate::BenchmarkParameters::validate`]); comparing one model with another is *compare*.

use std::sync::atomic::{AtomicBool, Ordering};

mod conditioning;
mod jacobians;
mod picking;

use crate::analysis::eigen::Complex64;
use crate::analysis::modes::Mode;
use crate::analysis::stability::{CriticalSpeeds, critical_speeds};
use crate::analysis::sweep::eigen_sweep;
use crate::error::{Error, Result};
use crate::linear::{Canonical, StateSpace};
use crate::nonlinear::Model;
use crate::parameters::BenchmarkParameters;

pub(crate) use conditioning::{CAPSIZE_HALF_WIDTH, DOUBLE_ROOT_HALF_WIDTH};
pub use conditioning::{capsize_spike, double_root_conditioning, zero_cluster};
pub(crate) use jacobians::FullJacobian;
pub use jacobians::{
    ComparisonSettings, full_state_jacobian, full_state_jacobian_fd, lean_steer_matrix,
};
pub(crate) use picking::faer_failure;
pub use picking::{general_eigenvalues, lean_steer_eigenvalues, max_abs_diff, pick};

/// A way to linearize the non-linear model about upright straight running.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Linearization {
    /// The study's: central differences over the full state with step decimation and
    /// projection, lean and steer eigenvalues picked from the 48.
    FiniteDifferences,
    /// Exact derivatives (dual numbers) of the model reduced to [φ, δ, φ̇, δ̇]: a 4×4 A(v).
    Exact,
    /// Exact derivatives (dual numbers) over the full state, lean and steer eigenvalues picked
    /// from the 48 (a diagnostic of the capsize spike).
    FullStateExact,
}

impl Linearization {
    /// Short name used in file headers: `fd`, `ad`, `ad_full`.
    pub fn name(self) -> &'static str {
        match self {
            Linearization::FiniteDifferences => "fd",
            Linearization::Exact => "ad",
            Linearization::FullStateExact => "ad_full",
        }
    }

    /// A description for legends and reports.
    pub fn description(self) -> &'static str {
        match self {
            Linearization::FiniteDifferences => {
                "finite differences, full state (the study's method)"
            }
            Linearization::Exact => "exact derivatives, reduced to lean and steer",
            Linearization::FullStateExact => "exact derivatives, full state",
        }
    }
}

/// One method's linearization at one speed, compared with the linear model.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Comparison {
    /// The lean and steer eigenvalues [1/s], matched to the linear ones (same order).
    pub eigenvalues: [Complex64; 4],
    /// max |λ − λ_linear| over the four [1/s].
    pub max_abs_diff: f64,
    /// For [`Linearization::Exact`]: max |A − A_linear| / max |A_linear|.
    pub matrix_rel_diff: Option<f64>,
}

/// Linearizes `model` at `speed` by `method` and compares with the linear eigenvalues
/// `linear` (in the order to match) and, for the exact method, the linear `A`.
pub(crate) fn compare_at(
    model: &Model,
    canonical: &Canonical,
    speed: f64,
    linear: &[Complex64; 4],
    method: Linearization,
    study: &ComparisonSettings,
) -> Result<Comparison> {
    match method {
        Linearization::Exact => {
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
        Linearization::FiniteDifferences | Linearization::FullStateExact => {
            let a = if method == Linearization::FiniteDifferences {
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
pub struct LinearizationSweep {
    /// The method.
    pub method: Linearization,
    /// Per speed, the lean and steer eigenvalues matched to [`ComparisonSweep::linear`].
    pub eigenvalues: Vec<[Complex64; 4]>,
    /// Per speed, max |λ − λ_linear| [1/s].
    pub max_abs_diff: Vec<f64>,
    /// Per speed, max |A − A_linear| / max |A_linear| (exact method only).
    pub matrix_rel_diff: Option<Vec<f64>>,
}

/// The comparison of the non-linear model with the linear one over a sweep of speeds.
#[derive(Debug, Clone, PartialEq)]
pub struct ComparisonSweep {
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
    pub methods: Vec<LinearizationSweep>,
}

/// The most speeds one comparison takes, for every front end (the command line's `validate`,
/// Python's `compare`): each speed linearizes the non-linear model by every method asked for,
/// about 10 ms of one core, so the limit is about 20 minutes of one core.
pub const MAX_COMPARED_SPEEDS: usize = 100_000;

/// Compares the non-linear model of `bike` with the linear one at every speed of `speeds`
/// (sorted, as from [`crate::analysis::sweep::speed_grid`]) by each of `methods`: Dressel's
/// benchmark, redone.
///
/// ```
/// use whipple::advanced::comparison::{compare_with_linear, Linearization, ComparisonSettings};
/// use whipple::BenchmarkParameters;
/// let sweep = compare_with_linear(&BenchmarkParameters::meijaard2007(), &[1.0, 5.0],
///                                 &[Linearization::Exact], &ComparisonSettings::default())?;
/// assert!(sweep.methods[0].max_abs_diff.iter().all(|d| *d < 1e-11));
/// # Ok::<(), whipple::Error>(())
/// ```
///
/// At most [`MAX_COMPARED_SPEEDS`] speeds ([`Error::LimitExceeded`] `what: "speeds"`).
pub fn compare_with_linear(
    bike: &BenchmarkParameters,
    speeds: &[f64],
    methods: &[Linearization],
    study: &ComparisonSettings,
) -> Result<ComparisonSweep> {
    compare_with_linear_until(bike, speeds, methods, study, &AtomicBool::new(false))
}

/// [`compare_with_linear`] that stops early when `stop` is set (checked before every speed),
/// with [`Error::InvalidArgument`] `what: "stopped"`: for front ends that honour Ctrl-C.
pub fn compare_with_linear_until(
    bike: &BenchmarkParameters,
    speeds: &[f64],
    methods: &[Linearization],
    study: &ComparisonSettings,
    stop: &AtomicBool,
) -> Result<ComparisonSweep> {
    if speeds.len() > MAX_COMPARED_SPEEDS {
        return Err(Error::LimitExceeded {
            what: "speeds",
            rule: format!(
                "{} speeds is more than the limit of {MAX_COMPARED_SPEEDS} a comparison takes",
                speeds.len()
            ),
        });
    }
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
                if stop.load(Ordering::Relaxed) {
                    return Err(Error::InvalidArgument {
                        what: "stopped",
                        rule: "the comparison was stopped before it finished".into(),
                    });
                }
                methods
                    .iter()
                    .map(|&m| {
                        compare_at(&model, &canonical, speeds[i], &eig.eigenvalues[i], m, study)
                    })
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
            // A worker that panicked is a bug, not a numerical result: its panic goes on.
            let part = h
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))?;
            all.extend(part);
        }
        Ok::<_, Error>(all)
    })?;
    let out = methods
        .iter()
        .enumerate()
        .map(|(k, &method)| LinearizationSweep {
            method,
            eigenvalues: rows.iter().map(|r| r[k].eigenvalues).collect(),
            max_abs_diff: rows.iter().map(|r| r[k].max_abs_diff).collect(),
            matrix_rel_diff: (method == Linearization::Exact)
                .then(|| rows.iter().filter_map(|r| r[k].matrix_rel_diff).collect()),
        })
        .collect();
    Ok(ComparisonSweep {
        speeds: speeds.to_vec(),
        linear: eig.eigenvalues,
        modes: eig.modes,
        critical,
        methods: out,
    })
}

impl ComparisonSweep {
    /// The results of `method`, if it was asked for.
    pub fn method(&self, method: Linearization) -> Option<&LinearizationSweep> {
        self.methods.iter().find(|m| m.method == method)
    }
}

impl LinearizationSweep {
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

/// A named interval of speeds of a sweep, for tables of the largest difference: all speeds,
/// and where there are critical speeds, below, at and between v_d ± [`DOUBLE_ROOT_HALF_WIDTH`]
/// and v_c ± [`CAPSIZE_HALF_WIDTH`].
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedInterval {
    /// What it is, in words (`v_d ± 0.02 (double root)`).
    pub label: String,
    /// Lower end [m/s].
    pub lo: f64,
    /// Upper end [m/s].
    pub hi: f64,
}

impl ComparisonSweep {
    /// The intervals of speeds a report tabulates (see `SpeedInterval`).
    pub fn intervals(&self) -> Vec<SpeedInterval> {
        let lo = self.speeds.first().copied().unwrap_or(0.0);
        let hi = self.speeds.last().copied().unwrap_or(0.0);
        let interval = |label: String, lo: f64, hi: f64| SpeedInterval { label, lo, hi };
        let mut out = vec![interval(format!("all speeds {lo}–{hi} m/s"), lo, hi)];
        let d = DOUBLE_ROOT_HALF_WIDTH;
        let c = CAPSIZE_HALF_WIDTH;
        match (self.critical.double_root_speed, self.critical.capsize_speed) {
            (Some(vd), Some(vc)) if vd + d < vc - c => {
                out.push(interval(format!("below v_d − {d}"), lo, vd - d));
                out.push(interval(format!("v_d ± {d} (double root)"), vd - d, vd + d));
                out.push(interval(format!("v_d + {d} … v_c − {c}"), vd + d, vc - c));
                out.push(interval(format!("v_c ± {c} (capsize)"), vc - c, vc + c));
                out.push(interval(format!("above v_c + {c}"), vc + c, hi));
            }
            (Some(vd), _) => {
                out.push(interval(format!("below v_d − {d}"), lo, vd - d));
                out.push(interval(format!("v_d ± {d} (double root)"), vd - d, vd + d));
                out.push(interval(format!("above v_d + {d}"), vd + d, hi));
            }
            (None, Some(vc)) => {
                out.push(interval(format!("below v_c − {c}"), lo, vc - c));
                out.push(interval(format!("v_c ± {c} (capsize)"), vc - c, vc + c));
                out.push(interval(format!("above v_c + {c}"), vc + c, hi));
            }
            (None, None) => {}
        }
        out
    }
}

impl LinearizationSweep {
    /// The largest max |A − A_linear| / max |A_linear| over the sweep and the speed where it
    /// occurs (exact method only).
    pub fn max_matrix_diff(&self, speeds: &[f64]) -> Option<(f64, f64)> {
        self.matrix_rel_diff.as_ref().map(|a| {
            a.iter().zip(speeds).fold(
                (0.0f64, 0.0),
                |b, (d, v)| if *d > b.0 { (*d, *v) } else { b },
            )
        })
    }
}
