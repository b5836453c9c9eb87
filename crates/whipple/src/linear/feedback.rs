//! Full-state feedback u = r − K x on the linear system (BicycleParameters'
//! `Meijaard2007WithFeedbackModel`): the closed loop at any speed, its eigenvalues against
//! speed tracked and labelled as the open loop's, and its certified critical speeds.
//!
//! # Why the closed loop keeps the open loop's polynomial structure
//!
//! With gains on the four lean–steer states only, K = [K_angle, K_rate] (inputs × 2 each), and
//! inputs whose generalized forces are the columns of F (2 × inputs), the loop closes on the
//! second-order form:
//!
//! M q̈ + (v C₁ + F K_rate) q̇ + (g K₀ + v² K₂ + F K_angle) q = F r,
//!
//! so det(M λ² + (v C₁ + F K_rate) λ + g K₀ + v² K₂ + F K_angle) is still of degree 4 in λ and
//! at most 4 in v. With gains scheduled with speed and interpolated linearly, K(v) = P + v Q on
//! each segment of the schedule, which moves F Q_rate into C₁ and adds a term v F Q_angle to the
//! stiffness: the same degrees again, one polynomial per segment. The characteristic polynomial
//! ([`CharacteristicPolynomial`]) then gives certified eigenvalues at every speed and the
//! tracked, labelled sweep; the Routh–Hurwitz structure, written as polynomials in v (the
//! closed loop has no parity in v), gives certified critical speeds (`analysis::stability`).
//!
//! Gains on the ignorable states (yaw, lateral position: heading or path control) raise the
//! order: the closed loop is then only the matrix A − B K, its eigenvalues come from the
//! general eigensolver ([`ClosedLoop::eigenvalues`]) and nothing about it is certified.

use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::{DMatrix, DVector};

use super::characteristic::{GeneralSpeedPolynomials, Pencil};
use super::system::{LinearSystem, SystemRequest};
use super::{Canonical, CharacteristicPolynomial};
use crate::analysis::eigen::{Complex64, second_order_eigenvector};
use crate::analysis::stability::{CriticalSpeeds, closed_loop_critical_speeds};
use crate::analysis::sweep::{EigenSweep, Quartics, eigen_sweep_of};
use crate::error::{Error, Result, short_number};
use crate::parameters::BenchmarkParameters;

/// The most speeds in a gain schedule.
pub const MAX_SCHEDULE_SPEEDS: usize = 10_000;

/// The most speeds in one [`ClosedLoop::general_sweep`] (each a dense eigenproblem).
pub const MAX_GENERAL_SWEEP_SPEEDS: usize = 1_000_000;

/// Feedback gains K (inputs × states, in the order of the system's inputs and states): constant,
/// or scheduled with speed.
#[derive(Debug, Clone, PartialEq)]
pub enum Gains {
    /// The same K at every speed.
    Constant(DMatrix<f64>),
    /// K given at increasing speeds [m/s] and interpolated linearly between them; a speed
    /// outside [first, last] is an error, never an extrapolation.
    Scheduled {
        /// The speeds, strictly increasing, at least two [m/s].
        speeds: Vec<f64>,
        /// K at each speed.
        gains: Vec<DMatrix<f64>>,
    },
}

fn bad_gains(rule: String) -> Error {
    Error::InvalidArgument {
        what: "gains",
        rule,
    }
}

/// Checks one gain matrix: its shape and that every entry is finite.
fn check_matrix(k: &DMatrix<f64>, inputs: usize, states: usize, at: &str) -> Result<()> {
    if k.shape() != (inputs, states) {
        return Err(bad_gains(format!(
            "K{at} must be inputs × states = {inputs} × {states}, got {} × {}",
            k.nrows(),
            k.ncols()
        )));
    }
    for i in 0..inputs {
        for j in 0..states {
            let x = k[(i, j)];
            if !x.is_finite() {
                return Err(bad_gains(format!(
                    "K{at} entry ({i}, {j}) is {x}: every gain must be finite"
                )));
            }
        }
    }
    Ok(())
}

impl Gains {
    fn check(&self, inputs: usize, states: usize) -> Result<()> {
        match self {
            Gains::Constant(k) => check_matrix(k, inputs, states, ""),
            Gains::Scheduled { speeds, gains } => {
                if speeds.len() < 2 || speeds.len() > MAX_SCHEDULE_SPEEDS {
                    return Err(Error::InvalidArgument {
                        what: "speeds",
                        rule: format!(
                            "a gain schedule needs 2 to {MAX_SCHEDULE_SPEEDS} speeds, got {}",
                            speeds.len()
                        ),
                    });
                }
                if gains.len() != speeds.len() {
                    return Err(bad_gains(format!(
                        "one K per speed of the schedule: {} for {} speeds",
                        gains.len(),
                        speeds.len()
                    )));
                }
                for w in speeds.windows(2) {
                    if !(w[0].is_finite() && w[1].is_finite() && w[0] < w[1]) {
                        return Err(Error::InvalidArgument {
                            what: "speeds",
                            rule: format!(
                                "a gain schedule's speeds must be finite and strictly \
                                 increasing, got {} then {}",
                                w[0], w[1]
                            ),
                        });
                    }
                }
                for (k, v) in gains.iter().zip(speeds) {
                    check_matrix(k, inputs, states, &format!(" at {} m/s", short_number(*v)))?;
                }
                Ok(())
            }
        }
    }

    /// The speeds the gains are defined on: the whole line, or the schedule's first to last
    /// (NaN for an empty schedule).
    pub fn speed_range(&self) -> (f64, f64) {
        match self {
            Gains::Constant(_) => (f64::NEG_INFINITY, f64::INFINITY),
            Gains::Scheduled { speeds, .. } => (
                speeds.first().copied().unwrap_or(f64::NAN),
                speeds.last().copied().unwrap_or(f64::NAN),
            ),
        }
    }

    /// The segment of the schedule holding `speed` (the last one holds its upper end).
    fn segment(speeds: &[f64], speed: f64) -> usize {
        speeds
            .partition_point(|s| *s <= speed)
            .saturating_sub(1)
            .min(speeds.len() - 2)
    }

    /// K at `speed`: constant, or interpolated linearly in the schedule. Errors
    /// ([`Error::InvalidArgument`]) naming `speed` for a speed outside the schedule, and
    /// `gains` or `speeds` for a schedule [`ClosedLoop::new`] would refuse.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use whipple::advanced::control::Gains;
    /// let gains = Gains::Scheduled {
    ///     speeds: vec![1.0, 3.0],
    ///     gains: vec![DMatrix::from_element(1, 4, -10.0), DMatrix::from_element(1, 4, -20.0)],
    /// };
    /// assert_eq!(gains.at(1.5)?[(0, 0)], -12.5);
    /// assert!(gains.at(3.5).is_err()); // never extrapolated
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn at(&self, speed: f64) -> Result<DMatrix<f64>> {
        let shape = self.matrices().first().map_or((0, 0), |k| k.shape());
        self.check(shape.0, shape.1)?;
        self.at_checked(speed)
    }

    /// [`Self::at`] for gains already checked.
    fn at_checked(&self, speed: f64) -> Result<DMatrix<f64>> {
        match self {
            Gains::Constant(k) => Ok(k.clone()),
            Gains::Scheduled { speeds, gains } => {
                let (lo, hi) = self.speed_range();
                if !(speed >= lo && speed <= hi) {
                    return Err(Error::InvalidArgument {
                        what: "speed",
                        rule: format!(
                            "{} m/s lies outside the gain schedule's speeds {}..{} m/s (gains \
                             are interpolated, never extrapolated)",
                            short_number(speed),
                            short_number(lo),
                            short_number(hi)
                        ),
                    });
                }
                let i = Self::segment(speeds, speed);
                let t = (speed - speeds[i]) / (speeds[i + 1] - speeds[i]);
                Ok(&gains[i] + (&gains[i + 1] - &gains[i]) * t)
            }
        }
    }

    /// The segments as (start, end, P, Q) with K(v) = P + v Q on [start, end].
    fn segments(&self) -> Vec<(f64, f64, DMatrix<f64>, DMatrix<f64>)> {
        match self {
            Gains::Constant(k) => vec![(
                f64::NEG_INFINITY,
                f64::INFINITY,
                k.clone(),
                DMatrix::zeros(k.nrows(), k.ncols()),
            )],
            Gains::Scheduled { speeds, gains } => (0..speeds.len() - 1)
                .map(|i| {
                    let q = (&gains[i + 1] - &gains[i]) / (speeds[i + 1] - speeds[i]);
                    let p = &gains[i] - &q * speeds[i];
                    (speeds[i], speeds[i + 1], p, q)
                })
                .collect(),
        }
    }

    fn matrices(&self) -> &[DMatrix<f64>] {
        match self {
            Gains::Constant(k) => std::slice::from_ref(k),
            Gains::Scheduled { gains, .. } => gains,
        }
    }
}

/// A bicycle under full-state feedback u = r − K x: the system asked for by a
/// [`SystemRequest`] (its inputs are the ones fed back; its states are the ones K reads),
/// closed at any speed.
///
/// ```
/// use nalgebra::DMatrix;
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::{ClosedLoop, Gains};
/// use whipple::advanced::linear::{Input, Output, StateVariable, SystemRequest};
/// let request = SystemRequest {
///     states: vec![],
///     inputs: vec![Input::SteerTorque],
///     outputs: StateVariable::LEAN_STEER.map(Output::State).to_vec(),
/// };
/// // Steer into the fall against a steer spring: T_δ = 100 φ − 10 δ + 20 φ̇ (N m per rad,
/// // per rad/s), so K = −[100, −10, 20, 0].
/// let k = DMatrix::from_row_slice(1, 4, &[-100.0, 10.0, -20.0, 0.0]);
/// let closed = ClosedLoop::new(&BenchmarkParameters::meijaard2007(), &request, Gains::Constant(k))?;
/// let speeds = closed.critical_speeds(0.0, 10.0)?;
/// let (from, to) = speeds.stable_speed_ranges[0];
/// // This controller stabilizes from 0.81 m/s (certified), past the capsize speed.
/// assert!((from - 0.8067).abs() < 1e-4 && to == 10.0);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedLoop {
    bike: BenchmarkParameters,
    request: SystemRequest,
    gains: Gains,
    canonical: Canonical,
    /// The inputs' generalized forces F (2 × inputs).
    forces: DMatrix<f64>,
    /// Whether every gain on an ignorable state is zero (the quartic holds).
    lean_steer: bool,
}

impl ClosedLoop {
    /// Checks the bicycle, the request and the gains (each K inputs × states, finite; a
    /// schedule's speeds strictly increasing). Errors name `gains`, `speeds`, or the
    /// request's field.
    pub fn new(bike: &BenchmarkParameters, request: &SystemRequest, gains: Gains) -> Result<Self> {
        let open = LinearSystem::new(bike, 0.0, request)?;
        let (inputs, states) = (open.inputs().len(), open.states().len());
        gains.check(inputs, states)?;
        let lean_steer = gains
            .matrices()
            .iter()
            .all(|k| (4..states).all(|j| (0..inputs).all(|i| k[(i, j)] == 0.0)));
        Ok(ClosedLoop {
            bike: *bike,
            request: request.clone(),
            gains,
            canonical: *open.canonical(),
            forces: open.forces.clone(),
            lean_steer,
        })
    }

    /// The gains.
    pub fn gains(&self) -> &Gains {
        &self.gains
    }

    /// Whether the gains read only φ, δ, φ̇, δ̇ (every gain on an ignorable state is zero):
    /// then the characteristic polynomial, the tracked sweep and the certified critical speeds
    /// are available.
    pub fn is_lean_steer(&self) -> bool {
        self.lean_steer
    }

    /// The closed loop at `speed` as a [`LinearSystem`]: A − B K(v), B, C − D K(v), D (the
    /// inputs are now reference inputs r; [`LinearSystem::gains`] holds K(v)).
    pub fn system(&self, speed: f64) -> Result<LinearSystem> {
        let k = self.gains.at_checked(speed)?;
        Ok(LinearSystem::new(&self.bike, speed, &self.request)?.closed(&k))
    }

    /// The eigenvalues of A − B K(v) at `speed` from the general eigensolver (faer), for any
    /// gains, those on ignorable states included (not certified; sorted by decreasing real
    /// part).
    pub fn eigenvalues(&self, speed: f64) -> Result<Vec<Complex64>> {
        let system = self.system(speed)?;
        let mut values = matrix_eigenvalues(system.a())?;
        values.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        Ok(values)
    }

    /// The eigenvector of the closed loop at `speed` for its eigenvalue `value`, unit length
    /// with its largest component real and positive (as the open loop's,
    /// [`crate::advanced::eigen::eigenvector`]). With gains on φ, δ, φ̇, δ̇ only: the four
    /// components (φ, δ, φ̇, δ̇) from a null vector of the closed loop's 2 × 2 second-order
    /// matrix, as the open loop's; otherwise one component per state of the system, the
    /// right singular vector of A − B K − λ I for its smallest singular value.
    pub fn eigenvector(&self, speed: f64, value: Complex64) -> Result<DVector<Complex64>> {
        let mut vectors = self.eigenvectors(speed, &[value])?;
        vectors.pop().ok_or_else(|| Error::InvalidArgument {
            what: "eigenvalue",
            rule: "no eigenvector was formed".into(),
        })
    }

    /// [`Self::eigenvector`] of each of `values` at one `speed` (the loop's matrices formed
    /// once).
    pub fn eigenvectors(
        &self,
        speed: f64,
        values: &[Complex64],
    ) -> Result<Vec<DVector<Complex64>>> {
        let k = self.gains.at_checked(speed)?;
        if let Some(value) = values
            .iter()
            .find(|z| !z.re.is_finite() || !z.im.is_finite())
        {
            return Err(Error::InvalidArgument {
                what: "eigenvalue",
                rule: format!("must be finite, got {value}"),
            });
        }
        if self.lean_steer {
            let zero = DMatrix::zeros(k.nrows(), k.ncols());
            let (m, damping, stiffness) =
                Pencil::closed(&self.canonical, &self.forces, &k, &zero).at_speed(speed);
            return Ok(values
                .iter()
                .map(|value| {
                    let x = second_order_eigenvector(&m, &damping, &stiffness, *value);
                    DVector::from_iterator(4, x.iter().copied())
                })
                .collect());
        }
        values
            .iter()
            .map(|value| self.general_eigenvector(speed, *value))
            .collect()
    }

    fn general_eigenvector(&self, speed: f64, value: Complex64) -> Result<DVector<Complex64>> {
        let system = self.system(speed)?;
        let a = system.a();
        let n = a.nrows();
        let shifted = DMatrix::<Complex64>::from_fn(n, n, |i, j| {
            let diagonal = if i == j {
                value
            } else {
                Complex64::new(0.0, 0.0)
            };
            Complex64::new(a[(i, j)], 0.0) - diagonal
        });
        // Bounded: nalgebra's iteration stops after 1000 sweeps (None then).
        let svd = shifted.try_svd(false, true, f64::EPSILON, 1000);
        let (Some(v_t), Some(smallest)) = (
            svd.as_ref().and_then(|s| s.v_t.clone()),
            svd.iter()
                .flat_map(|s| s.singular_values.iter())
                .enumerate()
                .min_by(|a, b| a.1.total_cmp(b.1))
                .map(|(i, _)| i),
        ) else {
            return Err(Error::InvalidArgument {
                what: "eigenvalue",
                rule: "the singular value decomposition of A − B K − λ I failed".into(),
            });
        };
        let mut x: DVector<Complex64> = v_t.row(smallest).adjoint();
        let pivot = x.iter().copied().fold(Complex64::new(0.0, 0.0), |best, z| {
            if z.norm_sqr() > best.norm_sqr() {
                z
            } else {
                best
            }
        });
        let norm = x.norm();
        if crate::math::norm(pivot) > 0.0 && norm > 0.0 {
            x *= pivot.conj() / (crate::math::norm(pivot) * norm);
        }
        Ok(x)
    }

    fn refuse_ignorable(&self, what: &str) -> Result<()> {
        if self.lean_steer {
            return Ok(());
        }
        Err(bad_gains(format!(
            "{what} needs gains on lean, steer and their rates only: gains on the ignorable \
             states raise the closed loop's order above four, so its eigenvalues come from \
             the general eigensolver (ClosedLoop::eigenvalues, ClosedLoop::general_sweep) and \
             its critical speeds are not certified"
        )))
    }

    /// The pencil of one segment K(v) = P + v Q.
    fn pencil(&self, p: &DMatrix<f64>, q: &DMatrix<f64>) -> Pencil {
        Pencil::closed(&self.canonical, &self.forces, p, q)
    }

    /// The pencils of the segments, with their speed intervals.
    fn pencils(&self) -> Vec<(f64, f64, Pencil)> {
        self.gains
            .segments()
            .iter()
            .map(|(a, b, p, q)| (*a, *b, self.pencil(p, q)))
            .collect()
    }

    /// The closed loop's characteristic polynomial p(λ, v) = det(M λ² + (v C₁ + F K_rate) λ +
    /// g K₀ + v² K₂ + F K_angle) for constant gains on φ, δ, φ̇, δ̇ (errors naming `gains`
    /// otherwise; a schedule has one polynomial per segment, used inside the sweep and the
    /// critical speeds).
    pub fn characteristic_polynomial(&self) -> Result<CharacteristicPolynomial> {
        self.refuse_ignorable("the characteristic polynomial")?;
        let Gains::Constant(k) = &self.gains else {
            return Err(bad_gains(
                "a gain schedule has one characteristic polynomial per segment, not one".into(),
            ));
        };
        let zero = DMatrix::zeros(k.nrows(), k.ncols());
        Ok(CharacteristicPolynomial::from_pencil(
            &self.pencil(k, &zero),
        ))
    }

    /// The closed-loop eigenvalues over `speeds`, certified at each speed and tracked and
    /// labelled as [`crate::eigen_sweep`] does for the open loop (the same code), for gains
    /// on φ, δ, φ̇, δ̇; every speed must lie in the schedule's range.
    pub fn eigen_sweep(&self, speeds: &[f64]) -> Result<EigenSweep> {
        self.eigen_sweep_until(speeds, &AtomicBool::new(false))
    }

    /// [`Self::eigen_sweep`] that stops early when `stop` is set (checked before every
    /// speed), with [`Error::InvalidArgument`] `what: "stopped"`: for front ends that honour
    /// Ctrl-C.
    pub fn eigen_sweep_until(&self, speeds: &[f64], stop: &AtomicBool) -> Result<EigenSweep> {
        self.refuse_ignorable("the tracked sweep")?;
        let (lo, hi) = self.gains.speed_range();
        if let Some(v) = speeds.iter().find(|v| !(**v >= lo && **v <= hi)) {
            // The schedule's own message.
            self.gains.at_checked(*v)?;
        }
        let mut breaks = Vec::new();
        let mut pieces = Vec::new();
        for (a, _, pencil) in self.pencils() {
            GeneralSpeedPolynomials::new(&pencil)?;
            breaks.push(a);
            pieces.push(CharacteristicPolynomial::from_pencil(&pencil));
        }
        eigen_sweep_of(&Piecewise { breaks, pieces }, speeds, stop)
    }

    /// The eigenvalues of A − B K(v) over `speeds` from the general eigensolver, for any
    /// gains (those on ignorable states included: a loop of any order), each row in tracked
    /// column order: each speed's eigenvalues are matched to the previous speed's by the
    /// smallest total distance (an optimal assignment for up to eight states, greedy by
    /// distance beyond). Not certified, and not labelled: what [`Self::eigen_sweep`] gives
    /// for gains on φ, δ, φ̇, δ̇ only, with certified eigenvalues and named modes. At most
    /// [`MAX_GENERAL_SWEEP_SPEEDS`] speeds.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::control::{ClosedLoop, Gains};
    /// use whipple::advanced::linear::{Input, Output, StateVariable, SystemRequest};
    /// let request = SystemRequest {
    ///     states: vec![StateVariable::Yaw],
    ///     inputs: vec![Input::SteerTorque],
    ///     outputs: vec![Output::State(StateVariable::Yaw)],
    /// };
    /// // Heading control on top of steer into the fall: a gain on yaw, order 5.
    /// let k = DMatrix::from_row_slice(1, 5, &[-100.0, 10.0, -20.0, 0.0, 5.0]);
    /// let closed = ClosedLoop::new(&BenchmarkParameters::meijaard2007(), &request, Gains::Constant(k))?;
    /// let rows = closed.general_sweep(&[3.0, 3.1, 3.2])?;
    /// assert_eq!((rows.len(), rows[0].len()), (3, 5));
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn general_sweep(&self, speeds: &[f64]) -> Result<Vec<Vec<Complex64>>> {
        self.general_sweep_until(speeds, &AtomicBool::new(false))
    }

    /// [`Self::general_sweep`] that stops early when `stop` is set (checked before every
    /// speed), with [`Error::InvalidArgument`] `what: "stopped"`.
    pub fn general_sweep_until(
        &self,
        speeds: &[f64],
        stop: &AtomicBool,
    ) -> Result<Vec<Vec<Complex64>>> {
        if speeds.len() > MAX_GENERAL_SWEEP_SPEEDS {
            return Err(Error::InvalidArgument {
                what: "speeds",
                rule: format!(
                    "at most {MAX_GENERAL_SWEEP_SPEEDS} speeds in a general sweep, got {}",
                    speeds.len()
                ),
            });
        }
        let mut rows: Vec<Vec<Complex64>> = Vec::with_capacity(speeds.len());
        for v in speeds {
            if stop.load(Ordering::Relaxed) {
                return Err(Error::InvalidArgument {
                    what: "stopped",
                    rule: "the sweep was stopped before it finished".into(),
                });
            }
            let values = self.eigenvalues(*v)?;
            let row = match rows.last() {
                Some(previous) => matched(previous, values),
                None => values,
            };
            rows.push(row);
        }
        Ok(rows)
    }

    /// The closed loop's critical speeds on [lo, hi] (m/s; constant gains allow ±∞),
    /// certified as the open loop's are (`analysis::stability`): every speed where an
    /// eigenvalue crosses the imaginary axis, with its enclosure, and the ranges of speed
    /// where the loop is stable, exact between the enclosures. A schedule is read segment by
    /// segment (each one's polynomial is exact there) and [lo, hi] must lie inside it.
    /// `weave_speed` and `capsize_speed` keep the open loop's rules (the lowest forward speed
    /// where a pair crossing stabilizes, where a real one destabilizes); the double-root
    /// speed is not computed (`double_root_unavailable` says why). Where round-off cannot
    /// decide (a near-tangency, a crossing whose enclosure is wider than 1e-8 of its speed,
    /// or a coefficient of these polynomials that cancels to zero
    /// within its bound, as the two-mass skate's does with zero gains) the speeds are listed
    /// in `unresolved`, never guessed. Gains on ignorable states are refused (naming
    /// `gains`): nothing about that loop is certified ([`Self::general_sweep`] samples it).
    pub fn critical_speeds(&self, lo: f64, hi: f64) -> Result<CriticalSpeeds> {
        self.refuse_ignorable("certified critical speeds")?;
        let (a, b) = self.gains.speed_range();
        if lo < a || hi > b {
            return Err(Error::InvalidArgument {
                what: "range",
                rule: format!(
                    "{lo}:{hi} reaches outside the gain schedule's speeds {a}:{b} (gains are \
                     never extrapolated)"
                ),
            });
        }
        let mut pieces = Vec::new();
        for (start, end, pencil) in self.pencils() {
            pieces.push((start, end, GeneralSpeedPolynomials::new(&pencil)?));
        }
        closed_loop_critical_speeds(&pieces, lo, hi)
    }
}

/// One characteristic polynomial per segment of a gain schedule (segment i from `breaks[i]`).
struct Piecewise {
    breaks: Vec<f64>,
    pieces: Vec<CharacteristicPolynomial>,
}

impl Piecewise {
    fn piece(&self, v: f64) -> &CharacteristicPolynomial {
        let i = self
            .breaks
            .partition_point(|s| *s <= v)
            .saturating_sub(1)
            .min(self.pieces.len() - 1);
        &self.pieces[i]
    }
}

impl Quartics for Piecewise {
    fn coefficients_at(&self, v: f64) -> [f64; 5] {
        self.piece(v).at_speed(v)
    }
    fn certified_at(&self, v: f64) -> Result<[Complex64; 4]> {
        self.piece(v).certified_at(v)
    }
}

/// `values` reordered to follow `previous`: the assignment of least total distance, by
/// exhaustive search over permutations for up to eight values, greedy (closest pair first)
/// beyond.
fn matched(previous: &[Complex64], values: Vec<Complex64>) -> Vec<Complex64> {
    let n = values.len();
    let cost = |i: usize, j: usize| crate::math::norm(previous[i] - values[j]);
    let mut assignment: Vec<usize> = (0..n).collect();
    if n <= 8 {
        // Heap's algorithm over the permutations (8! = 40 320 at most).
        let mut best = assignment.clone();
        let total = |a: &[usize]| (0..n).map(|i| cost(i, a[i])).sum::<f64>();
        let mut best_cost = total(&best);
        let mut c = vec![0usize; n];
        let mut i = 1;
        while i < n {
            if c[i] < i {
                let k = if i % 2 == 0 { 0 } else { c[i] };
                assignment.swap(k, i);
                let t = total(&assignment);
                if t < best_cost {
                    best_cost = t;
                    best.clone_from(&assignment);
                }
                c[i] += 1;
                i = 1;
            } else {
                c[i] = 0;
                i += 1;
            }
        }
        assignment = best;
    } else {
        let mut pairs: Vec<(usize, usize)> =
            (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
        pairs.sort_by(|a, b| cost(a.0, a.1).total_cmp(&cost(b.0, b.1)));
        let (mut row_done, mut col_done) = (vec![false; n], vec![false; n]);
        for (i, j) in pairs {
            if !row_done[i] && !col_done[j] {
                assignment[i] = j;
                row_done[i] = true;
                col_done[j] = true;
            }
        }
    }
    assignment.iter().map(|&j| values[j]).collect()
}

/// The eigenvalues of a square matrix (faer's general eigensolver).
pub(crate) fn matrix_eigenvalues(a: &DMatrix<f64>) -> Result<Vec<Complex64>> {
    let n = a.nrows();
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)]);
    let values = m
        .eigenvalues()
        .map_err(crate::analysis::comparison::faer_failure)?;
    Ok(values.iter().map(|z| Complex64::new(z.re, z.im)).collect())
}
