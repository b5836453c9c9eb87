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
        let Some(previous) = self.previous else {
            self.previous = Some(current);
            return current;
        };
        let predicted: [Complex64; 4] = match self.before {
            Some(before) => std::array::from_fn(|k| previous[k] * 2.0 - before[k]),
            None => previous,
        };
        let mut best = PERMUTATIONS[0];
        let mut best_cost = f64::INFINITY;
        for perm in PERMUTATIONS.iter() {
            let cost: f64 = (0..4)
                .map(|k| (current[perm[k]] - predicted[k]).norm_sqr())
                .sum();
            if cost < best_cost {
                best_cost = cost;
                best = *perm;
            }
        }
        let tracked = std::array::from_fn(|k| current[best[k]]);
        self.before = Some(previous);
        self.previous = Some(tracked);
        tracked
    }
}

/// The structural labels at one speed, when it shows the benchmark's pattern.
fn vote(values: &[Complex64; 4]) -> Option<[Mode; 4]> {
    let complex: Vec<usize> = (0..4).filter(|&k| values[k].im != 0.0).collect();
    if complex.len() != 2 {
        return None;
    }
    let real: Vec<usize> = (0..4).filter(|&k| values[k].im == 0.0).collect();
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
        if let Some(labels) = vote(values) {
            for (column, label) in self.votes.iter_mut().zip(labels) {
                if let Some(m) = LABELS.iter().position(|&m| m == label) {
                    column[m] += 1;
                }
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
                .position(|l| (l - pair.value).norm() <= 1e-9 * (1.0 + l.norm()))
                .map_or(Mode::Unclassified, |k| sweep.modes[k])
        } else {
            Mode::Unclassified
        };
        ModeShape { mode, pair }
    }))
}
