//! Speed sweeps: eigenvalues at many speeds, modes tracked and labelled.

use std::sync::atomic::{AtomicBool, Ordering};

use super::eigen::{Complex64, certified_roots, quartic_roots};
use super::modes::{Mode, Tracker, Votes};
use crate::error::{Error, Result};
use crate::linear::{Canonical, CharacteristicPolynomial};

/// The largest number of speeds one sweep may hold.
pub(crate) const MAX_SPEEDS: usize = 10_000_000;

/// An evenly spaced grid of speeds START:STOP:STEP, both ends included (STOP is included when
/// it lies on the grid to within round-off), held as its three numbers: a grid of any size
/// costs no memory until it is collected ([`speed_grid`]) or swept ([`SweepPlan`]).
///
/// ```
/// use whipple::advanced::sweep::SpeedGrid;
/// let grid = SpeedGrid::new(0.0, 1.0, 0.25)?;
/// assert_eq!(grid.len(), 5);
/// assert_eq!(grid.iter().collect::<Vec<_>>(), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedGrid {
    start: f64,
    stop: f64,
    step: f64,
    intervals: u64,
}

/// The most speeds a [`SpeedGrid`] may describe (callers bound what they sweep far lower).
pub(crate) const MAX_GRID_SPEEDS: f64 = 1e15;

impl SpeedGrid {
    /// The grid START:STOP:STEP: finite numbers, STEP > 0, STOP ≥ START.
    pub fn new(start: f64, stop: f64, step: f64) -> Result<Self> {
        let count = Self::count(start, stop, step)?;
        // An infinite count (a span past f64's range over the step) is refused too.
        if count.is_nan() || count > MAX_GRID_SPEEDS {
            return Err(Error::InvalidArgument {
                what: "speeds",
                rule: format!(
                    "{start}:{stop}:{step} holds {count:e} speeds, more than any sweep can take"
                ),
            });
        }
        let intervals = count - 1.0;
        Ok(SpeedGrid {
            start,
            stop,
            step,
            intervals: intervals as u64,
        })
    }

    /// How many speeds START:STOP:STEP holds, as a float, without building the grid (so a
    /// server can refuse a grid over its limit before any work): the count [`SpeedGrid::len`]
    /// gives, however large. The same checks as [`SpeedGrid::new`] but no upper bound.
    ///
    /// ```
    /// use whipple::advanced::sweep::SpeedGrid;
    /// assert_eq!(SpeedGrid::count(0.0, 10.0, 0.01)?, 1001.0);
    /// assert!(SpeedGrid::count(0.0, 1e300, 1e-10)?.is_infinite());
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn count(start: f64, stop: f64, step: f64) -> Result<f64> {
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
        // STOP counts when it lies on the grid to within round-off.
        Ok(((stop - start) / step * (1.0 + 1e-12) + 1e-9).floor() + 1.0)
    }

    /// How many speeds the grid holds.
    pub fn len(&self) -> u64 {
        self.intervals + 1
    }

    /// Never empty (START is always on it); for clippy's sake.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The i-th speed (0-based), as [`speed_grid`] lists it.
    pub fn speed(&self, i: u64) -> f64 {
        let n = self.intervals;
        let v = self.start + self.step * i as f64;
        if i == n && (v - self.stop).abs() <= 1e-9 * self.step {
            self.stop
        } else {
            v
        }
    }

    /// The speeds in order.
    pub fn iter(&self) -> impl Iterator<Item = f64> + Clone + '_ {
        (0..=self.intervals).map(|i| self.speed(i))
    }
}

/// Evenly spaced speeds START:STOP:STEP, both ends included (STOP is included when it lies on
/// the grid to within round-off), at most `MAX_SPEEDS` of them; [`SpeedGrid`] describes a
/// larger grid without holding it.
///
/// ```
/// let v = whipple::speed_grid(0.0, 1.0, 0.25)?;
/// assert_eq!(v, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn speed_grid(start: f64, stop: f64, step: f64) -> Result<Vec<f64>> {
    let grid = SpeedGrid::new(start, stop, step)?;
    if grid.len() > MAX_SPEEDS as u64 {
        return Err(Error::InvalidArgument {
            what: "speeds",
            rule: format!(
                "{start}:{stop}:{step} holds {} speeds, more than the limit of {MAX_SPEEDS} held at once (64 bytes each)",
                grid.len()
            ),
        });
    }
    Ok(grid.iter().collect())
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
/// one would be. The whole sweep is held in memory; [`SweepPlan`] streams it row by row.
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical, eigen_sweep, speed_grid};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let s = eigen_sweep(&canonical, &speed_grid(0.0, 10.0, 0.1)?)?;
/// assert_eq!(s.modes[2], whipple::advanced::modes::Mode::Capsize);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn eigen_sweep(canonical: &Canonical, speeds: &[f64]) -> Result<EigenSweep> {
    let plan = SweepPlan::new(canonical, speeds.iter().copied())?;
    let mut eigenvalues = Vec::with_capacity(speeds.len());
    plan.rows(|_, values| {
        eigenvalues.push(*values);
        Ok::<(), Error>(())
    })?;
    Ok(EigenSweep {
        speeds: speeds.to_vec(),
        eigenvalues,
        modes: plan.modes,
    })
}

/// A sweep of any length in bounded memory: [`SweepPlan::new`] runs it once to track and label
/// the modes (what the columns are is known before the first row), [`SweepPlan::rows`] runs it
/// again and hands each speed's eigenvalues, in the column order of [`SweepPlan::modes`], to a
/// callback. [`eigen_sweep`] is this plan with its rows collected into a vector: the same two
/// passes and the same rows, bit for bit, but here no row is kept, so a sweep of any length
/// takes bounded memory.
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical};
/// use whipple::advanced::sweep::{SpeedGrid, SweepPlan};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let grid = SpeedGrid::new(0.0, 10.0, 0.01)?;
/// let plan = SweepPlan::new(&canonical, grid.iter())?;
/// let mut rows = 0;
/// plan.rows(|v, eigenvalues| { rows += 1; Ok::<(), whipple::Error>(()) })?;
/// assert_eq!(rows, 1001);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct SweepPlan<I> {
    poly: CharacteristicPolynomial,
    speeds: I,
    /// The fraction of the wanted intermediate speeds taken (≤ 1).
    share: f64,
    /// Reported column k is tracked column `order[k]`.
    order: [usize; 4],
    /// The mode of each reported column.
    modes: [Mode; 4],
}

/// Speeds to visit between two requested ones, before the share is applied.
fn wanted(a: f64, b: f64) -> f64 {
    ((b - a).abs() / TRACKING_STEP)
        .ceil()
        .min(MAX_SUBSTEPS as f64)
}

/// The eigenvalues at the intermediate speeds tracked through between the requested speeds
/// `p` and `v` (none when they are close), in order.
pub(crate) fn between<P: Quartics + ?Sized, E: From<Error>>(
    poly: &P,
    p: f64,
    v: f64,
    share: f64,
    mut each: impl FnMut([Complex64; 4]) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    let substeps = (wanted(p, v) * share).floor() as usize;
    for k in 1..substeps {
        let u = p + (v - p) * k as f64 / substeps as f64;
        each(quartic_roots(&poly.coefficients_at(u))?)?;
    }
    Ok(())
}

/// Checks that every speed is finite and gives the fraction of the wanted intermediate speeds
/// a sweep over them takes (≤ 1, at most `MAX_EXTRA_SPEEDS` in all).
pub(crate) fn checked_share(speeds: impl Iterator<Item = f64>) -> Result<f64> {
    let mut total = 0.0;
    let mut previous: Option<f64> = None;
    for v in speeds {
        if !v.is_finite() {
            return Err(Error::InvalidArgument {
                what: "speeds",
                rule: format!("every speed must be finite, got {v}"),
            });
        }
        if let Some(p) = previous {
            total += wanted(p, v);
        }
        previous = Some(v);
    }
    Ok(if total > MAX_EXTRA_SPEEDS {
        MAX_EXTRA_SPEEDS / total
    } else {
        1.0
    })
}

/// The reported columns from the tracked ones' labels: weave, weave, capsize, castering, then
/// unclassified, ties by decreasing real part at the first speed (`first`); reported column k
/// is tracked column `order[k]`.
pub(crate) fn column_order(labels: [Mode; 4], first: Option<[Complex64; 4]>) -> [usize; 4] {
    let mut order = [0usize, 1, 2, 3];
    order.sort_by(|&i, &j| {
        mode_rank(labels[i])
            .cmp(&mode_rank(labels[j]))
            .then_with(|| match first {
                Some(f) => f[j].re.total_cmp(&f[i].re),
                None => std::cmp::Ordering::Equal,
            })
    });
    order
}

/// Whether the reported weave pair `a`, `b` is to be swapped (the eigenvalue of positive
/// imaginary part, or the larger real one, first).
pub(crate) fn weave_swapped(a: Complex64, b: Complex64) -> bool {
    b.im > a.im || (b.im == a.im && b.re > a.re)
}

/// Runs the tracking over `speeds` and calls `each(reported, tracked eigenvalues)` at every
/// speed visited, intermediate ones included (`reported` false).
fn visit<P, I, E>(
    poly: &P,
    speeds: I,
    share: f64,
    mut each: impl FnMut(Option<f64>, &[Complex64; 4]) -> std::result::Result<(), E>,
) -> std::result::Result<(), E>
where
    P: Quartics + ?Sized,
    I: Iterator<Item = f64>,
    E: From<Error>,
{
    let mut tracker = Tracker::default();
    let mut previous: Option<f64> = None;
    for v in speeds {
        if let Some(p) = previous {
            between(poly, p, v, share, |roots| each(None, &tracker.next(roots)))?;
        }
        let values = tracker.next(poly.certified_at(v)?);
        each(Some(v), &values)?;
        previous = Some(v);
    }
    Ok(())
}

impl<I: Iterator<Item = f64> + Clone> SweepPlan<I> {
    /// Checks the speeds (every one finite), then sweeps them once to track and label the
    /// modes.
    pub fn new(canonical: &Canonical, speeds: I) -> Result<Self> {
        let share = checked_share(speeds.clone())?;
        // Refuses matrices whose characteristic polynomial double precision cannot form
        // (overflow, a determinant of M lost to cancellation) instead of sweeping garbage.
        crate::linear::SpeedPolynomials::new(canonical)?;
        let poly = CharacteristicPolynomial::new(canonical);
        let (order, modes) = columns(&poly, speeds.clone(), share)?;
        Ok(SweepPlan {
            poly,
            speeds,
            share,
            modes,
            order,
        })
    }

    /// The mode of each column: weave, weave, capsize, castering (then unclassified); within
    /// the weave pair the eigenvalue of positive imaginary part (or the larger real one, below
    /// the double-root speed) comes first.
    pub fn modes(&self) -> [Mode; 4] {
        self.modes
    }

    /// Sweeps again, calling `row(v, eigenvalues)` for each requested speed in order, the
    /// eigenvalues [1/s] in the column order of [`SweepPlan::modes`]. Stops at the first
    /// error `row` returns.
    pub fn rows<E: From<Error>>(
        &self,
        mut row: impl FnMut(f64, &[Complex64; 4]) -> std::result::Result<(), E>,
    ) -> std::result::Result<(), E> {
        rows_of(
            &self.poly,
            self.speeds.clone(),
            self.share,
            (self.order, self.modes),
            &mut row,
        )
    }
}

/// What a sweep needs of the quartics in λ at each speed: their coefficients (lowest power
/// first) and their certified roots. A [`CharacteristicPolynomial`] is one; a closed loop with
/// a gain schedule is another (one polynomial per segment).
pub(crate) trait Quartics {
    /// p(λ) at speed v, lowest power first.
    fn coefficients_at(&self, v: f64) -> [f64; 5];
    /// Its roots, certified ([`certified_roots`]).
    fn certified_at(&self, v: f64) -> Result<[Complex64; 4]>;
}

impl Quartics for CharacteristicPolynomial {
    #[inline]
    fn coefficients_at(&self, v: f64) -> [f64; 5] {
        self.at_speed(v)
    }
    fn certified_at(&self, v: f64) -> Result<[Complex64; 4]> {
        certified_roots(self, v)
    }
}

/// The first pass of a sweep: tracks and labels the modes, giving the reported columns'
/// order and modes.
fn columns<P: Quartics + ?Sized>(
    poly: &P,
    speeds: impl Iterator<Item = f64>,
    share: f64,
) -> Result<([usize; 4], [Mode; 4])> {
    let mut votes = Votes::default();
    let mut first: Option<[Complex64; 4]> = None;
    visit(poly, speeds, share, |reported, values| {
        votes.add(values);
        if reported.is_some() && first.is_none() {
            first = Some(*values);
        }
        Ok::<(), Error>(())
    })?;
    let labels = votes.labels();
    let order = column_order(labels, first);
    Ok((order, order.map(|k| labels[k])))
}

/// The second pass: each requested speed's eigenvalues in the reported columns' order.
fn rows_of<P: Quartics + ?Sized, E: From<Error>>(
    poly: &P,
    speeds: impl Iterator<Item = f64>,
    share: f64,
    (order, modes): ([usize; 4], [Mode; 4]),
    row: &mut impl FnMut(f64, &[Complex64; 4]) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    let weave_pair = modes[0] == Mode::Weave && modes[1] == Mode::Weave;
    visit(poly, speeds, share, |reported, values| {
        let Some(v) = reported else {
            return Ok(());
        };
        let mut reordered: [Complex64; 4] = order.map(|k| values[k]);
        if weave_pair {
            let (a, b) = (reordered[0], reordered[1]);
            if weave_swapped(a, b) {
                reordered[0] = b;
                reordered[1] = a;
            }
        }
        row(v, &reordered)
    })
}

/// [`eigen_sweep`] of any family of quartics (a closed loop's): the same two passes, stopped
/// with [`Error::InvalidArgument`] `what: "stopped"` when `stop` is set (checked before every
/// speed of each pass).
pub(crate) fn eigen_sweep_of<P: Quartics + ?Sized>(
    poly: &P,
    speeds: &[f64],
    stop: &AtomicBool,
) -> Result<EigenSweep> {
    let stopped = || {
        Err(Error::InvalidArgument {
            what: "stopped",
            rule: "the sweep was stopped before it finished".into(),
        })
    };
    // The passes see the speeds up to the first one after `stop` is set.
    let until = || {
        speeds
            .iter()
            .copied()
            .take_while(|_| !stop.load(Ordering::Relaxed))
    };
    let share = checked_share(until())?;
    let columns = columns(poly, until(), share)?;
    if stop.load(Ordering::Relaxed) {
        return stopped();
    }
    let mut eigenvalues = Vec::with_capacity(speeds.len());
    rows_of(poly, until(), share, columns, &mut |_, values| {
        eigenvalues.push(*values);
        Ok::<(), Error>(())
    })?;
    if stop.load(Ordering::Relaxed) {
        return stopped();
    }
    Ok(EigenSweep {
        speeds: speeds.to_vec(),
        eigenvalues,
        modes: columns.1,
    })
}
