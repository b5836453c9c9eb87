//! The eigenmodes of the bicycle (weave, capsize, castering), tracked continuously across a
//! speed sweep.
//!
//! Tracking: from one speed to the next, the four new eigenvalues are matched to the four
//! tracks by the permutation that minimises the squared distance to each track's linear
//! extrapolation. Classification: at every speed where the spectrum has the benchmark's pattern
//! (one complex pair and two real eigenvalues), the pair votes for *weave*, the larger real
//! eigenvalue for *capsize* and the smaller for *castering*; each track takes the label most of
//! its speeds voted for. Tracks that never see that pattern stay *unclassified*, so a bicycle
//! whose modes do not follow the benchmark's pattern is reported as it is.

use serde::Serialize;

use super::eigen::{Complex64, EigenPair, eigenpairs};
use super::sweep::{EigenSweep, eigen_sweep, speed_grid};
use crate::error::{Error, Result};
use crate::linear::Canonical;

/// The name of an eigenmode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// The oscillatory lean-and-steer mode (a complex pair above the double-root speed).
    Weave,
    /// The slow, mostly-lean real mode that becomes mildly unstable at high speed.
    Capsize,
    /// The fast, heavily damped, mostly-steer real mode.
    Castering,
    /// A mode that never showed the benchmark's pattern in this sweep.
    Unclassified,
}

impl Mode {
    /// Lowercase name.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Weave => "weave",
            Mode::Capsize => "capsize",
            Mode::Castering => "castering",
            Mode::Unclassified => "unclassified",
        }
    }
}

const PERMUTATIONS: [[usize; 4]; 24] = [
    [0, 1, 2, 3],
    [0, 1, 3, 2],
    [0, 2, 1, 3],
    [0, 2, 3, 1],
    [0, 3, 1, 2],
    [0, 3, 2, 1],
    [1, 0, 2, 3],
    [1, 0, 3, 2],
    [1, 2, 0, 3],
    [1, 2, 3, 0],
    [1, 3, 0, 2],
    [1, 3, 2, 0],
    [2, 0, 1, 3],
    [2, 0, 3, 1],
    [2, 1, 0, 3],
    [2, 1, 3, 0],
    [2, 3, 0, 1],
    [2, 3, 1, 0],
    [3, 0, 1, 2],
    [3, 0, 2, 1],
    [3, 1, 0, 2],
    [3, 1, 2, 0],
    [3, 2, 0, 1],
    [3, 2, 1, 0],
];

/// Tracking one speed at a time: column k of each result continues column k of the results
/// before it (see the module documentation). [`track`] over a slice is the same, speed by speed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Tracker {
    previous: Option<[Complex64; 4]>,
    before: Option<[Complex64; 4]>,
}

impl Tracker {
    /// The eigenvalues `current` reordered to continue the tracks.
    pub(crate) fn next(&mut self, current: [Complex64; 4]) -> [Complex64; 4] {
        let (perm, _) = self.step(current);
        perm.map(|k| current[k])
    }

    /// As [`Tracker::next`], giving the match instead (tracked column k continues with
    /// `current[perm[k]]`) and whether it was decisive: every other permutation cost more than
    /// the chosen one by far more than round-off in summing the four distances in another
    /// order, so a tracker holding the same tracks in another column order makes the same
    /// match (what joining chunks tracked in parallel relies on, `analysis::track`). The first
    /// two speeds (no extrapolation yet) count as not decisive.
    pub(crate) fn step(&mut self, current: [Complex64; 4]) -> ([usize; 4], bool) {
        let Some(previous) = self.previous else {
            self.previous = Some(current);
            return ([0, 1, 2, 3], false);
        };
        let (predicted, extrapolated): ([Complex64; 4], bool) = match self.before {
            Some(before) => (std::array::from_fn(|k| previous[k] * 2.0 - before[k]), true),
            None => (previous, false),
        };
        let mut best = PERMUTATIONS[0];
        let mut best_cost = f64::INFINITY;
        let mut second_cost = f64::INFINITY;
        // The sixteen squared distances once; each permutation sums four of them, in the
        // order of the columns.
        let distance: [[f64; 4]; 4] = std::array::from_fn(|k| {
            std::array::from_fn(|j| (current[j] - predicted[k]).norm_sqr())
        });
        for perm in PERMUTATIONS.iter() {
            let cost: f64 = (0..4).map(|k| distance[k][perm[k]]).sum();
            if cost < best_cost {
                second_cost = best_cost;
                best_cost = cost;
                best = *perm;
            } else if cost < second_cost {
                second_cost = cost;
            }
        }
        // A sum of four non-negative terms is exact to 3 units of round-off in any order; a
        // margin of 1e-12 of the cost is thousands of times that.
        let decisive = extrapolated
            && best_cost.is_finite()
            && second_cost.is_finite()
            && second_cost - best_cost > 1e-12 * second_cost;
        let tracked = std::array::from_fn(|k| current[best[k]]);
        self.before = Some(previous);
        self.previous = Some(tracked);
        (best, decisive)
    }

    /// Whether a speed was tracked (the next one is matched to it).
    pub(crate) fn started(&self) -> bool {
        self.previous.is_some()
    }

    /// The tracked eigenvalues at the last two speeds (the last first), once two were seen.
    pub(crate) fn state(&self) -> Option<([Complex64; 4], [Complex64; 4])> {
        Some((self.previous?, self.before?))
    }

    /// The same tracks with column k taken from column `from[k]` of this tracker.
    pub(crate) fn relabelled(&self, from: [usize; 4]) -> Tracker {
        Tracker {
            previous: self.previous.map(|p| from.map(|k| p[k])),
            before: self.before.map(|b| from.map(|k| b[k])),
        }
    }
}

/// The structural labels at one speed, when it shows the benchmark's pattern.
fn vote(values: &[Complex64; 4]) -> Option<[Mode; 4]> {
    // The columns of complex and of real eigenvalues, each in column order (no allocation:
    // this runs at every speed of a sweep).
    let mut complex = [0usize; 4];
    let mut real = [0usize; 4];
    let (mut nc, mut nr) = (0, 0);
    for (k, value) in values.iter().enumerate() {
        if value.im != 0.0 {
            complex[nc] = k;
            nc += 1;
        } else {
            real[nr] = k;
            nr += 1;
        }
    }
    if nc != 2 {
        return None;
    }
    let mut labels = [Mode::Unclassified; 4];
    labels[complex[0]] = Mode::Weave;
    labels[complex[1]] = Mode::Weave;
    let (hi, lo) = if values[real[0]].re >= values[real[1]].re {
        (real[0], real[1])
    } else {
        (real[1], real[0])
    };
    labels[hi] = Mode::Capsize;
    labels[lo] = Mode::Castering;
    Some(labels)
}

/// The labels at one speed where the spectrum shows the benchmark's pattern (one complex pair:
/// weave; two real eigenvalues: the larger capsize, the smaller castering), else `None`.
pub(crate) fn pattern_labels(values: &[Complex64; 4]) -> Option<[Mode; 4]> {
    vote(values)
}

/// The labels' votes, gathered one tracked speed at a time ([`classify`] over a slice is the
/// same).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Votes {
    /// `votes[column][m]`: speeds at which the column showed weave, capsize, castering.
    votes: [[usize; 3]; 4],
}

const LABELS: [Mode; 3] = [Mode::Weave, Mode::Capsize, Mode::Castering];

impl Votes {
    /// Counts the votes of one speed's tracked eigenvalues.
    pub(crate) fn add(&mut self, values: &[Complex64; 4]) {
        self.add_checked(values);
    }

    /// As [`Votes::add`]; false when the votes depend on the column order (two real
    /// eigenvalues of equal real part beside the pair: which is capsize is then decided by
    /// position).
    pub(crate) fn add_checked(&mut self, values: &[Complex64; 4]) -> bool {
        let Some(labels) = vote(values) else {
            return true;
        };
        for (column, label) in self.votes.iter_mut().zip(labels) {
            if let Some(m) = LABELS.iter().position(|&m| m == label) {
                column[m] += 1;
            }
        }
        let mut real = values.iter().filter(|z| z.im == 0.0);
        !matches!((real.next(), real.next()), (Some(a), Some(b)) if a.re == b.re)
    }

    /// Adds `other`'s votes, its column `from[k]` counted for column k.
    pub(crate) fn merge(&mut self, other: &Votes, from: [usize; 4]) {
        for (column, k) in self.votes.iter_mut().zip(from) {
            for (mine, theirs) in column.iter_mut().zip(other.votes[k]) {
                *mine += theirs;
            }
        }
    }

    /// Labels for the four tracked columns (see the module documentation).
    pub(crate) fn labels(&self) -> [Mode; 4] {
        let votes = &self.votes;
        let mut labels = [Mode::Unclassified; 4];
        // Assign the weave to the two columns with most weave votes, then capsize and castering.
        let mut taken = [false; 4];
        for (m, mode) in LABELS.iter().enumerate() {
            let slots = if *mode == Mode::Weave { 2 } else { 1 };
            for _ in 0..slots {
                let best = (0..4)
                    .filter(|&k| !taken[k] && votes[k][m] > 0)
                    .max_by_key(|&k| votes[k][m]);
                if let Some(k) = best {
                    taken[k] = true;
                    labels[k] = *mode;
                }
            }
        }
        labels
    }
}

/// One eigenmode at one speed: its name, eigenvalue and shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeShape {
    /// The mode's name, from a sweep through this speed ([`Mode::Unclassified`] at negative
    /// speeds, where the sweep's labels do not apply).
    pub mode: Mode,
    /// The eigenvalue and eigenvector x = [φ, δ, φ̇, δ̇] (unit length, largest component real).
    pub pair: EigenPair,
}

/// The four eigenmodes at `speed`, named: the eigenpairs of A(v) (sorted by decreasing real
/// part) labelled by a sweep from rest to 1.5 × max(|v|, 10 m/s), 3000 steps, tracked through
/// `speed` (what `whipple modes` prints and the page animates).
///
/// ```
/// use whipple::advanced::modes::{mode_shapes, Mode};
/// use whipple::{BenchmarkParameters, Canonical};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let shapes = mode_shapes(&canonical, 5.0)?;
/// assert_eq!(shapes.iter().filter(|s| s.mode == Mode::Weave).count(), 2);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn mode_shapes(canonical: &Canonical, speed: f64) -> Result<[ModeShape; 4]> {
    let pairs = eigenpairs(canonical, speed)?;
    let labelling = |top: f64| -> Result<(Vec<f64>, EigenSweep)> {
        let mut grid = speed_grid(0.0, top, top / 3000.0)?;
        grid.push(speed.abs());
        grid.sort_by(f64::total_cmp);
        let sweep = eigen_sweep(canonical, &grid)?;
        Ok((grid, sweep))
    };
    // Past |v| the sweep only adds evidence; where round-off forbids eigenvalues there (a
    // speed far beyond any ridden one), the sweep stops at |v|.
    let (grid, sweep) = match labelling(speed.abs().max(10.0) * 1.5) {
        Err(Error::AccuracyLost { .. }) if speed.abs() > 10.0 => labelling(speed.abs())?,
        other => other?,
    };
    let at = grid
        .iter()
        .position(|v| *v == speed.abs())
        .unwrap_or_default();
    let values = sweep.eigenvalues[at];
    Ok(pairs.map(|pair| {
        // Eigenvalues at -v are those at v (the sweep runs at |v|) only when v >= 0.
        let mode = if speed >= 0.0 {
            values
                .iter()
                .position(|l| {
                    crate::math::norm(l - pair.value) <= 1e-9 * (1.0 + crate::math::norm(l))
                })
                .map_or(Mode::Unclassified, |k| sweep.modes[k])
        } else {
            Mode::Unclassified
        };
        ModeShape { mode, pair }
    }))
}
