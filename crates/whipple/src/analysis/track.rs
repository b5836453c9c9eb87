//! Mode tracking over eigenvalues computed beforehand, serially or in parallel chunks joined
//! where they overlap, with the same result as the serial sweep bit for bit.
//!
//! The serial sweep ([`super::sweep::SweepPlan`]) follows the modes from speed to speed, each
//! match depending on the two before it. In parallel the requested speeds are cut into chunks;
//! every chunk but the first is tracked by a tracker of its own that starts [`OVERLAP`]
//! speeds before the chunk, so that by the chunk's first speed it follows the same tracks as
//! the serial tracker, in a column order of its own. The chunks are then joined in order: the
//! chunk's tracked eigenvalues at the two speeds before its first are matched bit for bit
//! with the serial tracker's there (chunk k − 1's end, already joined); the permutation σ
//! found relabels the chunk's matches, its votes and its end. That is the serial tracker's
//! result when every match of the chunk was decisive (the chosen permutation cheaper than any
//! other by far more than round-off in summing the same four distances in another order:
//! the serial tracker, whose costs are those sums, then chooses the same match) and no speed's
//! votes depend on the column order. Otherwise (no σ, more than one, a close match, as at the
//! double root where the two real eigenvalues meet) the chunk is tracked again from the
//! serial tracker's state at its start, serially. The labels are decided as in the serial
//! sweep, from the votes of the whole sweep.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

use super::eigen::Complex64;
use super::modes::{Mode, Tracker, Votes};
use super::sweep::{between, checked_share, column_order, weave_swapped};
use crate::error::{Error, Result};
use crate::linear::{Canonical, CharacteristicPolynomial, SpeedPolynomials};

/// Requested speeds a chunk's own tracker runs through before the chunk (at least two: the
/// tracker extrapolates from the last two).
const OVERLAP: usize = 16;

/// The fewest requested speeds in a chunk tracked in parallel (chosen by measurement, see
/// BENCHMARKS.md: below it the chunks' overhead outweighs the second core).
const MIN_CHUNK: usize = 8192;

/// How the speeds are cut into chunks (`chunk` requested speeds each; one chunk is the serial
/// sweep).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Chunking {
    pub(crate) chunk: usize,
    pub(crate) overlap: usize,
}

impl Chunking {
    /// The chunks for `n` speeds: serial below two chunks of [`MIN_CHUNK`], else four chunks
    /// per thread of rayon's pool (the work per speed is even, the cores may not be).
    fn for_speeds(n: usize, parallel: bool) -> Chunking {
        let threads = rayon::current_num_threads().max(1);
        let chunk = if parallel && threads > 1 && n >= 2 * MIN_CHUNK {
            n.div_ceil(4 * threads).max(MIN_CHUNK)
        } else {
            n.max(1)
        };
        Chunking {
            chunk,
            overlap: OVERLAP,
        }
    }
}

/// How the chunks were joined (what the tests check).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Joins {
    /// Chunks joined by the permutation of their overlap.
    pub(crate) matched: usize,
    /// Chunks tracked again serially from the joined state.
    pub(crate) retracked: usize,
}

/// One chunk tracked: its tracker where the chunk starts and ends, its votes, and whether the
/// serial tracker, holding the same tracks in another column order, would have matched as it
/// did.
struct Chunk {
    start: Tracker,
    end: Tracker,
    votes: Votes,
    decisive: bool,
}

fn stopped() -> Error {
    Error::InvalidArgument {
        what: "stopped",
        rule: "the sweep was stopped before it finished".into(),
    }
}

/// The inputs of a tracking run.
struct Sweep<'a, R> {
    poly: &'a CharacteristicPolynomial,
    speeds: &'a [f64],
    roots: &'a R,
    share: f64,
    stop: &'a AtomicBool,
}

impl<R: Fn(usize) -> Result<[Complex64; 4]> + Sync> Sweep<'_, R> {
    /// Tracks the requested speeds `warm..start` (warming up `tracker`, nothing recorded),
    /// then `start..start + columns.len()`, writing each speed's match (tracked column k is
    /// `roots(i)[columns[i - start][k]]`).
    fn run(
        &self,
        mut tracker: Tracker,
        warm: usize,
        start: usize,
        columns: &mut [[u8; 4]],
    ) -> Result<Chunk> {
        for i in warm..start {
            if i > warm {
                let (p, v) = (self.speeds[i - 1], self.speeds[i]);
                between(self.poly, p, v, self.share, |r| {
                    tracker.step(r);
                    Ok::<(), Error>(())
                })?;
            }
            tracker.step((self.roots)(i)?);
        }
        let at_start = tracker;
        let mut votes = Votes::default();
        let mut decisive = true;
        for (i, out) in (start..).zip(columns.iter_mut()) {
            if self.stop.load(Ordering::Relaxed) {
                return Err(stopped());
            }
            if i > 0 && tracker.started() {
                let (p, v) = (self.speeds[i - 1], self.speeds[i]);
                between(self.poly, p, v, self.share, |r| {
                    let (perm, sure) = tracker.step(r);
                    let counted = votes.add_checked(&perm.map(|k| r[k]));
                    decisive &= sure && counted;
                    Ok::<(), Error>(())
                })?;
            }
            let r = (self.roots)(i)?;
            let (perm, sure) = tracker.step(r);
            let counted = votes.add_checked(&perm.map(|k| r[k]));
            decisive &= sure && counted;
            *out = perm.map(|k| k as u8);
        }
        Ok(Chunk {
            start: at_start,
            end: tracker,
            votes,
            decisive,
        })
    }
}

/// The permutation σ with `chunk`'s column σ\[k\] holding, bit for bit, what `serial`'s
/// column k holds, when there is exactly one.
fn join(serial: &Tracker, chunk: &Tracker) -> Option<[usize; 4]> {
    let (sp, sb) = serial.state()?;
    let (cp, cb) = chunk.state()?;
    let same = |a: Complex64, b: Complex64| {
        a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits()
    };
    let mut sigma = [0usize; 4];
    let mut taken = [false; 4];
    for k in 0..4 {
        let mut found = (0..4).filter(|&m| same(cp[m], sp[k]) && same(cb[m], sb[k]));
        let m = found.next()?;
        if found.next().is_some() || taken[m] {
            return None;
        }
        taken[m] = true;
        sigma[k] = m;
    }
    Some(sigma)
}

/// Tracks the modes over `speeds` (in the order given, as [`super::sweep::eigen_sweep`]
/// tracks them) from their eigenvalues `roots(i)` at `speeds[i]`, which must be the core's
/// (`eigenpairs` or `eigenvalues`, in their order): writes `columns[i]`, the index in
/// `roots(i)` of each reported column's eigenvalue, and returns the columns' modes, exactly as
/// [`super::sweep::SweepPlan`] reports them (its row at speed i is `roots(i)` taken in the
/// order `columns[i]`, bit for bit). Intermediate speeds where neighbouring speeds lie far
/// apart are computed here. `parallel`: in chunks on rayon's pool when the speeds are many
/// (the module documentation); the result is the same. Stops with
/// [`Error::InvalidArgument`] `what: "stopped"` soon after `stop` is set.
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// use whipple::advanced::eigen::eigenvalues;
/// use whipple::advanced::sweep::track_modes;
/// use whipple::{BenchmarkParameters, Canonical, eigen_sweep, speed_grid};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let speeds = speed_grid(0.0, 10.0, 0.01)?;
/// let mut columns = vec![[0u8; 4]; speeds.len()];
/// let roots = |i: usize| eigenvalues(&canonical, speeds[i]);
/// let modes = track_modes(&canonical, &speeds, roots, &mut columns, true, &AtomicBool::new(false))?;
/// let sweep = eigen_sweep(&canonical, &speeds)?;
/// assert_eq!(modes, sweep.modes);
/// assert_eq!(eigenvalues(&canonical, 5.0)?[columns[500][0] as usize], sweep.eigenvalues[500][0]);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn track_modes<R>(
    canonical: &Canonical,
    speeds: &[f64],
    roots: R,
    columns: &mut [[u8; 4]],
    parallel: bool,
    stop: &AtomicBool,
) -> Result<[Mode; 4]>
where
    R: Fn(usize) -> Result<[Complex64; 4]> + Sync,
{
    let chunking = Chunking::for_speeds(speeds.len(), parallel);
    track_modes_in(canonical, speeds, &roots, columns, chunking, stop).map(|(modes, _)| modes)
}

/// [`track_modes`] in the chunks given, saying how they were joined.
pub(crate) fn track_modes_in<R>(
    canonical: &Canonical,
    speeds: &[f64],
    roots: &R,
    columns: &mut [[u8; 4]],
    chunking: Chunking,
    stop: &AtomicBool,
) -> Result<([Mode; 4], Joins)>
where
    R: Fn(usize) -> Result<[Complex64; 4]> + Sync,
{
    if columns.len() != speeds.len() {
        return Err(Error::InvalidArgument {
            what: "columns",
            rule: format!(
                "one entry per speed is needed: {} for {} speeds",
                columns.len(),
                speeds.len()
            ),
        });
    }
    let share = checked_share(speeds.iter().copied())?;
    SpeedPolynomials::new(canonical)?;
    let poly = CharacteristicPolynomial::new(canonical);
    let sweep = Sweep {
        poly: &poly,
        speeds,
        roots,
        share,
        stop,
    };
    let size = chunking.chunk.max(chunking.overlap).max(2);
    // Each chunk tracked on its own (the first from the first speed, as the serial sweep).
    let chunks: Vec<Result<Chunk>> = columns
        .par_chunks_mut(size)
        .enumerate()
        .map(|(k, out)| {
            let start = k * size;
            let warm = start.saturating_sub(chunking.overlap.max(2));
            sweep.run(Tracker::default(), warm, start, out)
        })
        .collect();
    // Joined in order: `from[k]` maps each chunk's columns onto the serial ones.
    let mut votes = Votes::default();
    let mut serial = Tracker::default();
    let mut joins = Joins::default();
    let mut from = Vec::with_capacity(chunks.len());
    for (k, chunk) in chunks.into_iter().enumerate() {
        let chunk = chunk?;
        let sigma = if k == 0 {
            Some([0, 1, 2, 3])
        } else {
            join(&serial, &chunk.start).filter(|_| chunk.decisive)
        };
        match sigma {
            Some(sigma) => {
                joins.matched += usize::from(k > 0);
                votes.merge(&chunk.votes, sigma);
                serial = chunk.end.relabelled(sigma);
                from.push(sigma);
            }
            None => {
                joins.retracked += 1;
                let start = k * size;
                let end = (start + size).min(speeds.len());
                let again = sweep.run(serial, start, start, &mut columns[start..end])?;
                votes.merge(&again.votes, [0, 1, 2, 3]);
                serial = again.end;
                from.push([0, 1, 2, 3]);
            }
        }
    }
    let labels = votes.labels();
    let first = if speeds.is_empty() {
        None
    } else {
        Some(roots(0)?)
    };
    let order = column_order(labels, first);
    let modes = order.map(|k| labels[k]);
    let weave_pair = modes[0] == Mode::Weave && modes[1] == Mode::Weave;
    // Each match in the serial column order, then in the reported order.
    columns
        .par_chunks_mut(size)
        .zip(from.par_iter())
        .enumerate()
        .try_for_each(|(k, (out, sigma))| {
            for (i, column) in (k * size..).zip(out.iter_mut()) {
                if stop.load(Ordering::Relaxed) {
                    return Err(stopped());
                }
                let mut reported = order.map(|t| column[sigma[t]]);
                if weave_pair {
                    let r = roots(i)?;
                    if weave_swapped(r[reported[0] as usize], r[reported[1] as usize]) {
                        reported.swap(0, 1);
                    }
                }
                *column = reported;
            }
            Ok(())
        })?;
    Ok((modes, joins))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::eigen::eigenvalues;
    use crate::analysis::stability::critical_speeds;
    use crate::analysis::sweep::eigen_sweep;
    use crate::parameters::BenchmarkParameters;
    use crate::parameters::presets::PRESETS;

    fn bits(z: Complex64) -> (u64, u64) {
        (z.re.to_bits(), z.im.to_bits())
    }

    /// Tracks `speeds` in `chunking` and checks every match and the labels against the serial
    /// sweep (`eigen_sweep`), bit for bit.
    fn same_as_serial(canonical: &Canonical, speeds: &[f64], chunking: Chunking) -> Joins {
        let roots = |i: usize| eigenvalues(canonical, speeds[i]);
        let mut columns = vec![[9u8; 4]; speeds.len()];
        let stop = AtomicBool::new(false);
        let tracked = track_modes_in(canonical, speeds, &roots, &mut columns, chunking, &stop);
        let serial = eigen_sweep(canonical, speeds);
        let (modes, joins) = match (tracked, serial) {
            (Ok(t), Ok(s)) => {
                assert_eq!(t.0, s.modes);
                for (i, row) in s.eigenvalues.iter().enumerate() {
                    let r = roots(i).expect("computed in the sweep");
                    let ours = columns[i].map(|k| bits(r[k as usize]));
                    assert_eq!(ours, row.map(bits), "speed {} ({i})", speeds[i]);
                }
                (t.0, t.1)
            }
            (Err(t), Err(s)) => {
                assert_eq!(t.to_string(), s.to_string());
                return Joins::default();
            }
            (t, s) => panic!("tracked {t:?}, serial {s:?}"),
        };
        assert!(modes.iter().all(|m| *m != Mode::Unclassified) || speeds.len() < 3);
        joins
    }

    fn benchmark() -> Canonical {
        Canonical::new(&BenchmarkParameters::meijaard2007()).expect("the benchmark is valid")
    }

    /// `n` speeds `h` apart with `at` the speed of index `j` (a multiple of the chunk, so that a
    /// chunk starts right there).
    fn grid_through(at: f64, j: usize, n: usize, h: f64) -> Vec<f64> {
        (0..n).map(|i| at + (i as f64 - j as f64) * h).collect()
    }

    #[test]
    fn chunks_starting_at_the_critical_speeds_join_as_the_serial_sweep_tracks() {
        let c = benchmark();
        let s = critical_speeds(&c, 0.0, 10.0).expect("critical speeds");
        let chunk = Chunking {
            chunk: 250,
            overlap: OVERLAP,
        };
        let mut retracked = 0;
        for at in [s.double_root_speed, s.weave_speed, s.capsize_speed] {
            let at = at.expect("the benchmark has all three");
            for h in [1e-3, 1e-5, 1e-9] {
                let j = 1000;
                let joins = same_as_serial(&c, &grid_through(at, j, 2000, h), chunk);
                assert_eq!(joins.matched + joins.retracked, 7);
                retracked += joins.retracked;
            }
        }
        // Right at the double root the two real eigenvalues meet: the match there is a tie
        // that the column order decides, so that chunk is tracked again serially.
        assert!(retracked >= 1, "{retracked}");
    }

    #[test]
    fn a_sweep_over_every_preset_is_tracked_as_the_serial_sweep() {
        for preset in PRESETS {
            let bike = preset.bicycle().benchmark().expect("presets are valid");
            let c = Canonical::new(&bike).expect("presets are valid");
            let speeds: Vec<f64> = (0..6000).map(|i| i as f64 * 0.002).collect();
            for chunk in [97, 1000] {
                let joins = same_as_serial(&c, &speeds, Chunking { chunk, overlap: 4 });
                assert!(joins.matched > 0, "{}: {joins:?}", preset.name);
            }
            // A chunk starting right at each of its critical speeds.
            let s = critical_speeds(&c, 0.0, 10.0).expect("critical speeds");
            let chunking = Chunking {
                chunk: 250,
                overlap: OVERLAP,
            };
            for at in [s.double_root_speed, s.weave_speed, s.capsize_speed]
                .into_iter()
                .flatten()
            {
                same_as_serial(&c, &grid_through(at, 1000, 2000, 1e-4), chunking);
            }
        }
    }

    #[test]
    fn coarse_descending_and_tiny_sweeps_are_tracked_as_the_serial_sweep() {
        let c = benchmark();
        // Far apart: the intermediate speeds are tracked through, in the overlaps too.
        let coarse: Vec<f64> = (0..41).map(|i| i as f64 * 0.25).collect();
        same_as_serial(
            &c,
            &coarse,
            Chunking {
                chunk: 3,
                overlap: 2,
            },
        );
        let descending: Vec<f64> = (0..3000).rev().map(|i| i as f64 * 0.003).collect();
        same_as_serial(
            &c,
            &descending,
            Chunking {
                chunk: 128,
                overlap: 8,
            },
        );
        for n in 0..5 {
            let few: Vec<f64> = (0..n).map(|i| 4.0 + i as f64).collect();
            same_as_serial(
                &c,
                &few,
                Chunking {
                    chunk: 2,
                    overlap: 2,
                },
            );
        }
        // A speed where round-off forbids eigenvalues: the same error as the serial sweep.
        let far = [1.0, 2.0, 1e17];
        same_as_serial(
            &c,
            &far,
            Chunking {
                chunk: 2,
                overlap: 2,
            },
        );
    }

    #[test]
    fn joins_need_exactly_one_permutation() {
        let z = |re: f64, im: f64| Complex64::new(re, im);
        let mut serial = Tracker::default();
        serial.step([z(-1.0, 2.0), z(-1.0, -2.0), z(0.5, 0.0), z(-9.0, 0.0)]);
        serial.step([z(-1.1, 2.0), z(-1.1, -2.0), z(0.4, 0.0), z(-9.1, 0.0)]);
        let chunk = serial.relabelled([2, 0, 3, 1]);
        let sigma = join(&serial, &chunk).expect("a relabelling joins");
        assert_eq!(sigma, [1, 3, 0, 2]);
        assert_eq!(chunk.relabelled(sigma), serial);
        // A tracker that saw one speed only: nothing to join on.
        let mut once = Tracker::default();
        once.step([z(-1.1, 2.0), z(-1.1, -2.0), z(0.4, 0.0), z(-9.1, 0.0)]);
        assert_eq!(join(&serial, &once), None);
        assert_eq!(join(&serial, &Tracker::default()), None);
        // Two columns alike: more than one permutation, no join.
        let mut twins = Tracker::default();
        twins.step([z(1.0, 0.0), z(1.0, 0.0), z(0.5, 0.0), z(-9.0, 0.0)]);
        twins.step([z(1.0, 0.0), z(1.0, 0.0), z(0.4, 0.0), z(-9.1, 0.0)]);
        assert_eq!(join(&twins, &twins), None);
    }

    #[test]
    fn parallel_and_serial_give_the_same_columns_and_stop_when_asked() {
        let c = benchmark();
        let speeds: Vec<f64> = (0..4 * MIN_CHUNK).map(|i| i as f64 * 2e-4).collect();
        let roots = |i: usize| eigenvalues(&c, speeds[i]);
        let stop = AtomicBool::new(false);
        let mut serial = vec![[0u8; 4]; speeds.len()];
        let mut parallel = serial.clone();
        let a = track_modes(&c, &speeds, roots, &mut serial, false, &stop).expect("tracks");
        let b = track_modes(&c, &speeds, roots, &mut parallel, true, &stop).expect("tracks");
        assert_eq!((a, &serial), (b, &parallel));
        stop.store(true, Ordering::Relaxed);
        let e = track_modes(&c, &speeds, roots, &mut parallel, true, &stop);
        assert!(matches!(
            e,
            Err(Error::InvalidArgument {
                what: "stopped",
                ..
            })
        ));
        let short = track_modes(&c, &speeds, roots, &mut serial[..3], true, &stop);
        assert!(matches!(
            short,
            Err(Error::InvalidArgument {
                what: "columns",
                ..
            })
        ));
    }
}
