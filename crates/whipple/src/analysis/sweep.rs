//! Speed sweeps: eigenvalues at many speeds, modes tracked and labelled.

use super::eigen::{quartic_roots, Complex64};
use super::modes::{classify, track, Mode};
use crate::error::{Error, Result};
use crate::linear::{Canonical, CharacteristicPolynomial};

/// The largest number of speeds one sweep may hold.
pub const MAX_SPEEDS: usize = 10_000_000;

/// Evenly spaced speeds START:STOP:STEP, both ends included (STOP is included when it lies on
/// the grid to within round-off).
///
/// ```
/// let v = whipple::analysis::sweep::speed_grid(0.0, 1.0, 0.25)?;
/// assert_eq!(v, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn speed_grid(start: f64, stop: f64, step: f64) -> Result<Vec<f64>> {
    if !(start.is_finite() && stop.is_finite() && step.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "speeds",
            rule: format!("START:STOP:STEP must be finite numbers, got {start}:{stop}:{step}"),
        });
    }
    if step <= 0.0 {
        return Err(Error::InvalidArgument {
            what: "speeds",
            rule: format!("STEP must be greater than zero, got {step}"),
        });
    }
    if stop < start {
        return Err(Error::InvalidArgument {
            what: "speeds",
            rule: format!("STOP ({stop}) must not be less than START ({start})"),
        });
    }
    let intervals = ((stop - start) / step * (1.0 + 1e-12) + 1e-9).floor();
    if intervals + 1.0 > MAX_SPEEDS as f64 {
        return Err(Error::InvalidArgument {
            what: "speeds",
            rule: format!(
                "{start}:{stop}:{step} holds {} speeds, more than the limit of {MAX_SPEEDS}",
                intervals + 1.0
            ),
        });
    }
    let n = intervals as usize;
    Ok((0..=n)
        .map(|i| {
            if i == n && ((start + step * i as f64) - stop).abs() <= 1e-9 * step {
                stop
            } else {
                start + step * i as f64
            }
        })
        .collect())
}

/// Eigenvalues over a sweep of speeds, each column one tracked mode.
#[derive(Debug, Clone, PartialEq)]
pub struct EigenSweep {
    /// The forward speeds v [m/s].
    pub speeds: Vec<f64>,
    /// For each speed, the four eigenvalues [1/s] in the column order of `modes`.
    pub eigenvalues: Vec<[Complex64; 4]>,
    /// The mode of each column. Columns are ordered weave, weave, capsize, castering (then
    /// unclassified); within the weave pair the eigenvalue of positive imaginary part (or the
    /// larger real one, below the double-root speed) comes first.
    pub modes: [Mode; 4],
}

fn mode_rank(mode: Mode) -> usize {
    match mode {
        Mode::Weave => 0,
        Mode::Capsize => 1,
        Mode::Castering => 2,
        Mode::Unclassified => 3,
    }
}

/// The largest speed step [m/s] over which modes are tracked directly; coarser sweeps are
/// tracked through intermediate speeds that are computed but not reported.
const TRACKING_STEP: f64 = 0.02;

/// At most this many intermediate speeds between two requested ones.
const MAX_SUBSTEPS: usize = 1000;

/// At most this many intermediate speeds in one sweep (fewer per interval when exceeded).
const MAX_EXTRA_SPEEDS: f64 = 2_000_000.0;

/// Sweeps the eigenvalues over `speeds` (any order is tracked as given; sorted input gives
/// continuous tracks). Where neighbouring speeds lie more than 0.02 m/s apart, the modes are
/// tracked through intermediate speeds (not reported), so a coarse sweep is labelled as a fine
/// one would be.
///
/// ```
/// use whipple::{BenchmarkParameters, linear::Canonical, analysis::sweep};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let s = sweep::eigen_sweep(&canonical, &sweep::speed_grid(0.0, 10.0, 0.1)?)?;
/// assert_eq!(s.modes[2], whipple::analysis::modes::Mode::Capsize);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn eigen_sweep(canonical: &Canonical, speeds: &[f64]) -> Result<EigenSweep> {
    if let Some(v) = speeds.iter().find(|v| !v.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "speeds",
            rule: format!("every speed must be finite, got {v}"),
        });
    }
    // Refuses matrices whose characteristic polynomial double precision cannot form
    // (overflow, a determinant of M lost to cancellation) instead of sweeping garbage.
    crate::linear::SpeedPolynomials::new(canonical)?;
    let poly = CharacteristicPolynomial::new(canonical);
    // Every speed the tracking visits, and where the requested ones sit among them.
    let wanted = |a: f64, b: f64| {
        ((b - a).abs() / TRACKING_STEP)
            .ceil()
            .min(MAX_SUBSTEPS as f64)
    };
    let total: f64 = speeds.windows(2).map(|w| wanted(w[0], w[1])).sum();
    let share = if total > MAX_EXTRA_SPEEDS {
        MAX_EXTRA_SPEEDS / total
    } else {
        1.0
    };
    let mut visited = Vec::with_capacity(speeds.len());
    let mut reported = Vec::with_capacity(speeds.len());
    for (i, &v) in speeds.iter().enumerate() {
        if i > 0 {
            let previous = speeds[i - 1];
            let substeps = (wanted(previous, v) * share).floor() as usize;
            for k in 1..substeps {
                visited.push(previous + (v - previous) * k as f64 / substeps as f64);
            }
        }
        reported.push(visited.len());
        visited.push(v);
    }
    let mut all = visited
        .iter()
        .map(|&v| quartic_roots(&poly.at_speed(v)))
        .collect::<Result<Vec<_>>>()?;
    track(&mut all);
    let labels = classify(&all);
    let mut eigenvalues: Vec<[Complex64; 4]> = reported.iter().map(|&k| all[k]).collect();
    let mut order = [0usize, 1, 2, 3];
    let first = eigenvalues.first().copied();
    order.sort_by(|&i, &j| {
        mode_rank(labels[i])
            .cmp(&mode_rank(labels[j]))
            .then_with(|| match first {
                Some(f) => f[j].re.total_cmp(&f[i].re),
                None => std::cmp::Ordering::Equal,
            })
    });
    let modes = order.map(|k| labels[k]);
    for values in eigenvalues.iter_mut() {
        let mut reordered: [Complex64; 4] = order.map(|k| values[k]);
        if modes[0] == Mode::Weave && modes[1] == Mode::Weave {
            let (a, b) = (reordered[0], reordered[1]);
            if b.im > a.im || (b.im == a.im && b.re > a.re) {
                reordered[0] = b;
                reordered[1] = a;
            }
        }
        *values = reordered;
    }
    Ok(EigenSweep {
        speeds: speeds.to_vec(),
        eigenvalues,
        modes,
    })
}
