//! Hess's loops one at a time: each loop's open- and closed-loop transfer function, its
//! crossover frequency, the gains found by the crossover rules of Hess, Moore & Hubbard 2012,
//! and the ridden bicycle's eigenvalues against speed.
//!
//! # The loops
//!
//! The loops are numbered from the inside out, as HumanControl's `generate_data.m` names them
//! (`Delta`, `PhiDot`, `Phi`, `Psi`, `Y`): i = 0 (steer angle δ), 1 (roll rate φ̇), 2 (roll
//! angle φ), 3 (heading ψ), 4 (lateral deviation of the front contact y_Q). In its Simulink
//! model `WhippleModel.mdl`, "perturbing" loop i feeds the model's input in as loop i's
//! command in place of the outer loop's output, and the output taken is loop i's measured
//! variable; `closed` sets each loop's feedback on or off. Its two tables give, for loop i:
//!
//! - the **open loop** L_i(s) = y_i / e_i: the loops inside i closed, loop i's own feedback
//!   off, from its error e_i (into its gain k_i, which L_i includes) to its output y_i;
//! - the **closed loop** T_i(s) = y_i / y_{i,c}: loops 0 … i closed, from loop i's command to
//!   its output. The loops outside i are cut off by the perturbation, so T_i = L_i / (1 + L_i).
//!
//! # How they are formed
//!
//! The bicycle's transfer functions from the steer torque to the measured outputs are exact
//! ([`LinearSystem::transfer_function`]): G_i = n_i / (s^{k_i} c(s)), c the characteristic
//! quartic. Over the common denominator s^K c(s) (K the most integrators, 2 with y_Q),
//! N_i = ω² s^{K − k_i} n_i; with the neuromuscular q(s) = s² + 2ζωs + ω² and loop i's forward
//! gain g_i = k_δ Π_{l=1..i} k_l,
//!
//! ```text
//! L_i = g_i N_i / (q s^K c + Σ_{m<i} g_m N_m),    T_i = g_i N_i / (q s^K c + Σ_{m≤i} g_m N_m),
//! ```
//!
//! a factor s common to numerator and denominator cancelled. The last denominator with i the
//! outermost loop is the characteristic polynomial of [`HumanLoop`]'s A.
//!
//! # Crossover frequencies
//!
//! Where |L_i(iω)| = 1: the positive real roots in x = ω² of |N(iω)|² − |D(iω)|², a polynomial
//! in x whose coefficients are formed with a bound on their round-off, solved by
//! [`crate::advanced::roots::real_roots`] (Smith's inclusion discs): every crossing is found,
//! none is sampled for. A loop may cross more than once; all are given.
//!
//! # Gains by Hess's rules
//!
//! As HumanControl's `exact_gains` (its `compute_inner_gains` and `find_open_gain`):
//!
//! - k_δ: the steer loop closed (δ/δ_c), an oscillatory pair of its poles has damping ratio
//!   ζ_δ = 0.1289 (HumanControl's "signature neuromuscular peak");
//! - k_φ̇: the roll-rate loop closed as well, a pair has damping ζ_φ̇ = 0.0855;
//! - k_φ, k_ψ, k_y: the open loop L_i crosses |L_i| = 1 at ω_c = 2, 1 and 0.5 rad/s:
//!   k_i = 1 / |L_i(iω_c)| computed with k_i = 1 (L_i is proportional to k_i).
//!
//! HumanControl solves the damping rules by `fsolve` from the benchmark bicycle's solution at
//! 5 m/s. Here every gain giving a closed-loop pole on the ray of damping ζ is found: with
//! s = ω u, u = −ζ + i√(1 − ζ²), the closed loop's polynomial P₀(s) + k P₁(s) vanishes for a
//! real k exactly where Im(P₀(ωu) conj P₁(ωu)) = 0, a real polynomial in ω whose positive
//! roots are certified as above; then k = −P₀(s)/P₁(s). Of these the rule takes the gain of
//! the loop's sign (k_δ > 0, k_φ̇ < 0, as HumanControl's gains all are) whose pair has the
//! highest frequency below the neuromuscular frequency ω (the pair the loop's gain brings
//! into the crossover region; at low speed the weave pair meets the same damping at a much
//! lower frequency, which is not the rule's). None: [`Error::GainRuleUnmet`] naming the gain.

use super::human::{GainTable, HumanController, HumanGains, HumanLoop, Neuromuscular, Task};
use super::poly::{Poly, eval, ratio};
use super::system::{LinearSystem, Output, StateVariable};
use crate::analysis::eigen::Complex64;
use crate::analysis::roots::{BoundedPolynomial, RealRoot, UNIT_ROUNDOFF, real_roots};
use crate::error::{Error, Result, short_number};
use crate::parameters::BenchmarkParameters;

/// One of Hess's nested loops, inner first (HumanControl's `loopNames`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RiderLoop {
    /// δ: the steer angle loop, gain k_δ.
    Steer,
    /// φ̇: the roll rate loop, gain k_φ̇.
    RollRate,
    /// φ: the roll angle loop, gain k_φ.
    Roll,
    /// ψ: the heading loop, gain k_ψ.
    Heading,
    /// y_Q: the front contact's lateral deviation loop, gain k_y.
    Lateral,
}

impl RiderLoop {
    /// Every loop, inner first.
    pub const ALL: [RiderLoop; 5] = [
        RiderLoop::Steer,
        RiderLoop::RollRate,
        RiderLoop::Roll,
        RiderLoop::Heading,
        RiderLoop::Lateral,
    ];

    /// The loops a task closes, inner first: four for heading, five for lateral.
    pub fn of_task(task: Task) -> &'static [RiderLoop] {
        match task {
            Task::Heading => &Self::ALL[..4],
            Task::Lateral => &Self::ALL,
        }
    }

    /// The loop's position from the inside, 0 (δ) to 4 (y).
    pub fn index(self) -> usize {
        self as usize
    }

    /// HumanControl's name: `delta`, `phi_dot`, `phi`, `psi`, `y` (its `Delta`, `PhiDot`, …
    /// in snake case).
    pub fn name(self) -> &'static str {
        match self {
            RiderLoop::Steer => "delta",
            RiderLoop::RollRate => "phi_dot",
            RiderLoop::Roll => "phi",
            RiderLoop::Heading => "psi",
            RiderLoop::Lateral => "y",
        }
    }

    /// The loop's gain as HumanControl's files name it (`kDelta`, …).
    pub fn gain_name(self) -> &'static str {
        HumanGains::NAMES[self.index()]
    }

    /// The loop's measured output.
    pub fn output(self) -> Output {
        match self {
            RiderLoop::Steer => Output::State(StateVariable::Steer),
            RiderLoop::RollRate => Output::State(StateVariable::LeanRate),
            RiderLoop::Roll => Output::State(StateVariable::Lean),
            RiderLoop::Heading => Output::State(StateVariable::Yaw),
            RiderLoop::Lateral => Output::FrontContactY,
        }
    }

    /// The loop of a name (`delta`, `phi_dot`, `phi`, `psi`, `y`).
    pub fn from_name(name: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|l| l.name() == name)
            .ok_or_else(|| Error::InvalidArgument {
                what: "loop",
                rule: format!("`{name}` is not a loop: use delta, phi_dot, phi, psi or y"),
            })
    }
}

impl std::fmt::Display for RiderLoop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A rational transfer function N(s)/D(s), coefficients lowest power first.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopTransferFunction {
    /// N(s), lowest power first.
    pub numerator: Vec<f64>,
    /// D(s), lowest power first.
    pub denominator: Vec<f64>,
}

impl LoopTransferFunction {
    /// The value at any complex s (Horner's scheme; in 1/s beyond |s| = 1).
    pub fn eval(&self, s: Complex64) -> Complex64 {
        ratio(&self.numerator, &self.denominator, s)
    }

    /// |G(iω)| at each ω \[rad/s\].
    pub fn magnitude(&self, frequencies: &[f64]) -> Vec<f64> {
        frequencies
            .iter()
            .map(|w| crate::math::norm(self.eval(Complex64::new(0.0, *w))))
            .collect()
    }
}

/// A frequency where an open loop's magnitude crosses 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossover {
    /// ω_c \[rad/s\].
    pub frequency: f64,
    /// The certified enclosure \[lo, hi\] of ω_c \[rad/s\].
    pub lo: f64,
    /// Its upper end \[rad/s\].
    pub hi: f64,
    /// False for a cluster of near-coincident crossings (a near-tangency of |L| to 1) that
    /// double precision cannot tell apart: `frequency` is then its middle.
    pub certified: bool,
}

/// One loop's transfer functions and crossover frequencies.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopResponse {
    /// The loop.
    pub rider_loop: RiderLoop,
    /// L(s): broken at the loop's error, the loops inside it closed.
    pub open: LoopTransferFunction,
    /// T(s): from the loop's command to its output, the loop and those inside it closed.
    pub closed: LoopTransferFunction,
    /// Every ω > 0 where |L(iω)| = 1, increasing.
    pub crossovers: Vec<Crossover>,
}

impl LoopResponse {
    /// The crossover frequency: the highest ω where |L(iω)| = 1 (None if it never crosses).
    pub fn crossover(&self) -> Option<f64> {
        self.crossovers.last().map(|c| c.frequency)
    }
}

/// The rules of Hess 2012 that set the gains ([`hess_gains`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossoverRules {
    /// ζ of the steer loop's closed-loop pair that sets k_δ (0.1289).
    pub steer_damping: f64,
    /// ζ of the roll-rate loop's closed-loop pair that sets k_φ̇ (0.0855).
    pub roll_rate_damping: f64,
    /// The crossover frequencies of the φ, ψ and y loops \[rad/s\] (2.0, 1.0, 0.5).
    pub crossovers: [f64; 3],
}

impl Default for CrossoverRules {
    /// HumanControl's steer-control values: ζ_δ = 0.1289, ζ_φ̇ = 0.0855, ω_c = 2, 1, 0.5 rad/s.
    fn default() -> Self {
        CrossoverRules {
            steer_damping: 0.1289,
            roll_rate_damping: 0.0855,
            crossovers: [2.0, 1.0, 0.5],
        }
    }
}

// ---------------------------------------------------------------------------------------
// Polynomials, lowest power first ([`Poly`]; their values here, the sizes unused).

fn trim(mut a: Vec<f64>) -> Vec<f64> {
    while a.last() == Some(&0.0) {
        a.pop();
    }
    a
}

/// Cancels the powers of s that numerator and denominator share (exact zeros at the low end).
fn cancel_s(n: &Poly, d: &Poly) -> (Vec<f64>, Vec<f64>) {
    let (mut n, mut d) = (n.values(), d.values());
    while n.len() > 1 && d.len() > 1 && n[0] == 0.0 && d[0] == 0.0 {
        n.remove(0);
        d.remove(0);
    }
    (trim(n), trim(d))
}

/// A polynomial of up to [`ROOT_COEFFICIENTS`] coefficients with round-off bounds (a relative
/// allowance of 8 (n + 2) u on the sum of the absolute values of each coefficient's terms).
const ROOT_COEFFICIENTS: usize = 11;

fn bounded(
    values: &[f64],
    sizes: &[f64],
    what: &str,
) -> Result<BoundedPolynomial<ROOT_COEFFICIENTS>> {
    let n = values.len();
    if n > ROOT_COEFFICIENTS {
        return Err(Error::InvalidArgument {
            what: "polynomial",
            rule: format!("{what}: degree {} is above the largest handled", n - 1),
        });
    }
    let mut q = BoundedPolynomial::exact([0.0; ROOT_COEFFICIENTS]);
    let gamma = 8.0 * (n as f64 + 2.0) * UNIT_ROUNDOFF;
    for k in 0..n {
        q.coefficients[k] = values[k];
        q.bounds[k] = gamma * sizes[k];
    }
    Ok(q)
}

/// |N(iω)|² − |D(iω)|² as a polynomial in x = ω², with each coefficient's size.
fn magnitude_difference(n: &[f64], d: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let square = |a: &[f64]| {
        let m = a.len().saturating_sub(1);
        let mut v = vec![0.0; m + 1];
        let mut s = vec![0.0; m + 1];
        for (k, x) in a.iter().enumerate() {
            for (l, y) in a.iter().enumerate() {
                if (k + l) % 2 == 0 {
                    let sign = if ((k as i64 - l as i64) / 2) % 2 == 0 {
                        1.0
                    } else {
                        -1.0
                    };
                    v[(k + l) / 2] += sign * x * y;
                    s[(k + l) / 2] += (x * y).abs();
                }
            }
        }
        (v, s)
    };
    let (vn, sn) = square(n);
    let (vd, sd) = square(d);
    let len = vn.len().max(vd.len());
    let at = |v: &[f64], k: usize| v.get(k).copied().unwrap_or(0.0);
    (
        (0..len).map(|k| at(&vn, k) - at(&vd, k)).collect(),
        (0..len).map(|k| at(&sn, k) + at(&sd, k)).collect(),
    )
}

/// Every ω > 0 where |N(iω)| = |D(iω)|, certified.
fn crossings(n: &[f64], d: &[f64]) -> Result<Vec<Crossover>> {
    let (mut v, mut s) = magnitude_difference(n, d);
    while v.len() > 1 && v.last() == Some(&0.0) {
        v.pop();
        s.pop();
    }
    let q = bounded(&v, &s, "|L(iω)|² − 1")?;
    let roots = real_roots(&q, "a loop's crossover polynomial |N(iω)|² − |D(iω)|²")?;
    let mut out = Vec::new();
    for r in roots.as_slice() {
        let (lo, hi) = r.enclosure();
        if hi <= 0.0 {
            continue;
        }
        out.push(Crossover {
            frequency: r.value().max(0.0).sqrt(),
            lo: lo.max(0.0).sqrt(),
            hi: hi.sqrt(),
            certified: matches!(r, RealRoot::Simple { .. }) && lo > 0.0,
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------
// The loops' polynomials.

/// The open-loop polynomials of the five loops over one denominator: q s^K c and
/// N_i = ω² s^{K − k_i} n_i (loops inner first).
struct LoopPolynomials {
    base: Poly,
    numerators: Vec<Poly>,
}

impl LoopPolynomials {
    /// From an open-loop system whose input 0 is the steer torque and whose outputs are
    /// [`HumanController::measured`]'s (ψ, φ, δ, φ̇, and y_Q if present).
    fn new(open: &LinearSystem, neuromuscular: &Neuromuscular) -> Result<Self> {
        let count = open.outputs().len();
        let mut tfs = Vec::with_capacity(count);
        for l in &RiderLoop::ALL[..count] {
            let row = open
                .outputs()
                .iter()
                .position(|o| *o == l.output())
                .ok_or_else(|| Error::InvalidArgument {
                    what: "outputs",
                    rule: format!("the open loop lacks loop {l}'s output"),
                })?;
            tfs.push(open.transfer_function(row, 0)?);
        }
        let k_max = tfs.iter().map(|t| t.integrators).max().unwrap_or(0);
        let (w, z) = (neuromuscular.frequency, neuromuscular.damping);
        let q = Poly::from_coefficients(&[w * w, 2.0 * z * w, 1.0]);
        let c = Poly::from_coefficients(&tfs[0].characteristic);
        let base = q.mul(&c.shift(k_max));
        let numerators = tfs
            .iter()
            .map(|t| {
                let n = Poly::from_coefficients(&t.numerator).scale(w).scale(w);
                if n.is_empty() {
                    // G ≡ 0 (k = 0): K zero coefficients all the same (`Poly::shift` leaves
                    // the zero polynomial empty).
                    return Poly::from_coefficients(&vec![0.0; k_max - t.integrators]);
                }
                n.shift(k_max - t.integrators)
            })
            .collect();
        Ok(LoopPolynomials { base, numerators })
    }

    /// Loop i's forward gains g_m = k_δ Π_{l=1..m} k_l for m ≤ i.
    fn forward_gains(gains: &HumanGains) -> [f64; 5] {
        let k = gains.to_array();
        let mut g = [0.0; 5];
        let mut p = 1.0;
        for i in 0..5 {
            p *= k[i];
            g[i] = p;
        }
        g
    }

    /// q s^K c + Σ_{m<i} g_m N_m.
    fn denominator_below(&self, i: usize, g: &[f64; 5]) -> Poly {
        let mut d = self.base.clone();
        for (n, gm) in self.numerators.iter().zip(g).take(i) {
            d = d.add_scaled(n, *gm);
        }
        d
    }

    fn response(&self, l: RiderLoop, gains: &HumanGains) -> Result<LoopResponse> {
        let i = l.index();
        let g = Self::forward_gains(gains);
        let below = self.denominator_below(i, &g);
        let numerator = self.numerators[i].scale(g[i]);
        let closed_den = below.add_scaled(&numerator, 1.0);
        let (on, od) = cancel_s(&numerator, &below);
        let (cn, cd) = cancel_s(&numerator, &closed_den);
        let crossovers = crossings(&on, &od)?;
        Ok(LoopResponse {
            rider_loop: l,
            open: LoopTransferFunction {
                numerator: on,
                denominator: od,
            },
            closed: LoopTransferFunction {
                numerator: cn,
                denominator: cd,
            },
            crossovers,
        })
    }
}

impl HumanLoop {
    /// Each of the task's loops, inner first: its open- and closed-loop transfer functions
    /// and crossover frequencies (the module documentation of `linear::human_loops` defines
    /// them).
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::control::{HumanController, HumanGains, HumanLoop, Neuromuscular, Task};
    /// let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
    /// let rider = HumanController::new(Task::Lateral, gains, Neuromuscular::default())?;
    /// let ridden = HumanLoop::new(&BenchmarkParameters::meijaard2007(), 5.0, &rider, &[])?;
    /// let loops = ridden.loops()?;
    /// // HumanControl tuned the roll loop to cross over at 2 rad/s.
    /// assert!((loops[2].crossover().unwrap() - 2.0).abs() < 0.05);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn loops(&self) -> Result<Vec<LoopResponse>> {
        let controller = self.controller();
        let polys = LoopPolynomials::new(self.open_loop(), controller.neuromuscular())?;
        RiderLoop::of_task(controller.task())
            .iter()
            .map(|l| polys.response(*l, controller.gains()))
            .collect()
    }
}

// ---------------------------------------------------------------------------------------
// Gains by Hess's rules.

/// The real gains k (with their pole frequency ω) that put a root of P₀ + k P₁ on the ray of
/// damping ζ (see the module documentation).
fn damping_ray_gains(p0: &[f64], p1: &[f64], zeta: f64) -> Result<Vec<(f64, f64)>> {
    let u = Complex64::new(-zeta, (1.0 - zeta * zeta).sqrt());
    let rotate = |p: &[f64]| -> Vec<Complex64> {
        let mut uk = Complex64::new(1.0, 0.0);
        p.iter()
            .map(|a| {
                let t = uk * *a;
                uk *= u;
                t
            })
            .collect()
    };
    let (a, b) = (rotate(p0), rotate(p1));
    let n = a.len() + b.len() - 1;
    let mut v = vec![0.0; n];
    let mut s = vec![0.0; n];
    for (k, x) in a.iter().enumerate() {
        for (l, y) in b.iter().enumerate() {
            v[k + l] += (x * y.conj()).im;
            s[k + l] += crate::math::norm(x) * crate::math::norm(y);
        }
    }
    // Im(P₀ conj P₁) vanishes at ω = 0 (both real there): divide by ω.
    v.remove(0);
    s.remove(0);
    while v.len() > 1 && v.last() == Some(&0.0) {
        v.pop();
        s.pop();
    }
    let q = bounded(&v, &s, "the damping ray's polynomial")?;
    let roots = real_roots(&q, "the damping ray's polynomial Im(P₀ conj P₁)")?;
    let mut out = Vec::new();
    for r in roots.as_slice() {
        let w = r.value();
        if w <= 0.0 {
            continue;
        }
        let s = u * w;
        let k = -(eval(p0, s) / eval(p1, s));
        if k.re.is_finite() {
            out.push((k.re, w));
        }
    }
    Ok(out)
}

/// The gain of `sign` whose pair has the highest frequency below ω (the rule's choice).
fn pick_gain(
    candidates: &[(f64, f64)],
    sign: f64,
    neuromuscular: &Neuromuscular,
    gain: &str,
    zeta: f64,
) -> Result<f64> {
    candidates
        .iter()
        .filter(|(k, w)| k * sign > 0.0 && *w < neuromuscular.frequency)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _)| *k)
        .ok_or_else(|| Error::GainRuleUnmet {
            gain: gain.into(),
            rule: format!(
                "no {} gain gives the closed loop a pair of damping ratio {} below the \
                 neuromuscular frequency {} rad/s",
                if sign > 0.0 { "positive" } else { "negative" },
                short_number(zeta),
                short_number(neuromuscular.frequency)
            ),
        })
}

/// The five gains by Hess 2012's rules (see the module documentation) for `bike` at `speed`:
/// k_δ and k_φ̇ by the closed loops' damping, k_φ, k_ψ, k_y by the open loops' crossover
/// frequencies. Every step is a closed computation (certified polynomial roots), no search.
/// Errors: [`Error::GainRuleUnmet`] naming the gain when no gain meets its rule; rules that
/// are not a damping ratio in (0, 1) or a positive frequency name the rule.
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::{CrossoverRules, Neuromuscular, hess_gains};
/// let k = hess_gains(&BenchmarkParameters::meijaard2007(), 5.0, &Neuromuscular::default(),
///     &CrossoverRules::default())?;
/// // HumanControl's BenchmarkSteerGains.txt at 5 m/s: 46.5457, -0.0522, 12.6611, 0.1849, 0.0959.
/// assert!((k.k_delta - 46.5457).abs() < 0.01 && (k.k_phi_dot + 0.0522).abs() < 1e-4);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn hess_gains(
    bike: &BenchmarkParameters,
    speed: f64,
    neuromuscular: &Neuromuscular,
    rules: &CrossoverRules,
) -> Result<HumanGains> {
    for (field, value) in [
        ("steer damping", rules.steer_damping),
        ("roll rate damping", rules.roll_rate_damping),
    ] {
        if !(value > 0.0 && value < 1.0) {
            return Err(Error::InvalidParameter {
                field: field.into(),
                value,
                rule: "a damping ratio of an oscillatory pair lies in (0, 1)".into(),
            });
        }
    }
    for (name, value) in ["phi crossover", "psi crossover", "y crossover"]
        .iter()
        .zip(rules.crossovers)
    {
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::InvalidParameter {
                field: (*name).into(),
                value,
                rule: "a crossover frequency must be positive and finite".into(),
            });
        }
    }
    // The controller only checks the neuromuscular filter here: its gains are placeholders.
    let probe = HumanController::new(
        Task::Lateral,
        HumanGains::from_array([1.0; 5]),
        *neuromuscular,
    )?;
    if !speed.is_finite() {
        return Err(Error::InvalidArgument {
            what: "speed",
            rule: format!("must be finite, got {}", short_number(speed)),
        });
    }
    let open = LinearSystem::new(bike, speed, &probe.open_loop_request(&[]))?;
    let polys = LoopPolynomials::new(&open, neuromuscular)?;
    // k_δ: P₀ = q s^K c, P₁ = N_δ.
    let (p0, p1) = cancel_s(&polys.base, &polys.numerators[0]);
    let candidates = damping_ray_gains(&p0, &p1, rules.steer_damping)?;
    let k_delta = pick_gain(
        &candidates,
        1.0,
        neuromuscular,
        "kDelta",
        rules.steer_damping,
    )?;
    // k_φ̇: P₀ = q s^K c + k_δ N_δ, P₁ = k_δ N_φ̇.
    let g0 = polys.base.add_scaled(&polys.numerators[0], k_delta);
    let n1 = polys.numerators[1].scale(k_delta);
    let (p0, p1) = cancel_s(&g0, &n1);
    let candidates = damping_ray_gains(&p0, &p1, rules.roll_rate_damping)?;
    let k_phi_dot = pick_gain(
        &candidates,
        -1.0,
        neuromuscular,
        "kPhiDot",
        rules.roll_rate_damping,
    )?;
    let mut k = [k_delta, k_phi_dot, 1.0, 1.0, 1.0];
    for (i, w) in (2..5).zip(rules.crossovers) {
        let g = LoopPolynomials::forward_gains(&HumanGains::from_array(k));
        let below = polys.denominator_below(i, &g);
        let at = ratio(
            &polys.numerators[i].values(),
            &below.values(),
            Complex64::new(0.0, w),
        ) * g[i];
        let m = crate::math::norm(at);
        if !(m.is_finite() && m > 0.0) {
            return Err(Error::GainRuleUnmet {
                gain: HumanGains::NAMES[i].into(),
                rule: format!(
                    "the open loop's magnitude at {} rad/s is {}: no gain makes it 1",
                    short_number(w),
                    short_number(m)
                ),
            });
        }
        k[i] = 1.0 / m;
    }
    Ok(HumanGains::from_array(k))
}

// ---------------------------------------------------------------------------------------
// Eigenvalues against speed.

/// The most speeds [`human_eigen_sweep`] takes.
pub const MAX_HUMAN_SWEEP_SPEEDS: usize = 100_000;

/// Where a sweep's gains come from at each speed.
#[derive(Debug, Clone, Copy)]
pub enum GainSchedule<'a> {
    /// The same gains at every speed.
    Fixed(HumanGains),
    /// A table, interpolated in speed ([`GainTable::at`]; outside it extrapolated and said).
    Table(&'a GainTable),
    /// Hess's rules at each speed ([`hess_gains`]).
    Rules(CrossoverRules),
}

/// One speed of a [`human_eigen_sweep`].
#[derive(Debug, Clone, PartialEq)]
pub struct HumanSweepRow {
    /// v \[m/s\].
    pub speed: f64,
    /// The gains used.
    pub gains: HumanGains,
    /// Whether they were extrapolated from a table.
    pub extrapolated: bool,
    /// The closed loop's eigenvalues ([`HumanLoop::eigenvalues`]: decreasing real part).
    pub eigenvalues: Vec<Complex64>,
}

/// The ridden bicycle's eigenvalues at each speed, the gains from `schedule`. At most
/// [`MAX_HUMAN_SWEEP_SPEEDS`] speeds; errors name `speeds`, or come from the gains or the
/// closed loop at the first speed that fails.
pub fn human_eigen_sweep(
    bike: &BenchmarkParameters,
    task: Task,
    schedule: &GainSchedule<'_>,
    neuromuscular: &Neuromuscular,
    speeds: &[f64],
) -> Result<Vec<HumanSweepRow>> {
    if speeds.len() > MAX_HUMAN_SWEEP_SPEEDS {
        return Err(Error::LimitExceeded {
            what: "speeds",
            rule: format!(
                "at most {MAX_HUMAN_SWEEP_SPEEDS} speeds, got {}",
                speeds.len()
            ),
        });
    }
    let mut rows = Vec::with_capacity(speeds.len());
    for &v in speeds {
        let (gains, extrapolated) = match schedule {
            GainSchedule::Fixed(g) => (*g, false),
            GainSchedule::Table(t) => {
                let at = t.at(v)?;
                (at.gains, at.extrapolated)
            }
            GainSchedule::Rules(r) => (hess_gains(bike, v, neuromuscular, r)?, false),
        };
        let rider = HumanController::new(task, gains, *neuromuscular)?;
        let ridden = HumanLoop::new(bike, v, &rider, &[])?;
        rows.push(HumanSweepRow {
            speed: v,
            gains,
            extrapolated,
            eigenvalues: ridden.eigenvalues()?,
        });
    }
    Ok(rows)
}

#[cfg(test)]
#[path = "human_loops_tests.rs"]
mod tests;
