//! Hess's handling quality metric (HQM; Hess, Moore & Hubbard 2012, IEEE TSMC-A 42(3)), as
//! HumanControl computes it (`generate_data.m`'s `handlingQuality` block on `WhippleModel.mdl`).
//!
//! # Which transfer function
//!
//! HumanControl linearizes its Simulink model with `isHandling` set, the steer-angle and
//! roll-rate loops' `closed` flags cleared, the roll-angle loop perturbed and its output
//! chosen (loop 3). Read from the model's wiring, that configuration is:
//!
//! - the input passes through the handling filter F(s) = 400/(s² + 40 s + 400) and becomes the
//!   roll angle command φ_c (the heading and lateral loops are cut off);
//! - the steer-angle and roll-rate feedback are rerouted, not removed: the roll-rate loop's
//!   feedback is φ̇ + δ/k_φ̇, so the command into the neuromuscular filter is still
//!   k_δ (k_φ̇ (k_φ (φ_c − φ) − φ̇) − δ), the inner loops of [`super::HumanController`] closed;
//! - the output is −(φ̇ + δ/k_φ̇)/k_φ, the roll-rate loop's feedback signal over the roll-angle
//!   gain.
//!
//! With G_φ = N_φ/D and G_δ = N_δ/D the bicycle's steer torque → roll and steer angle transfer
//! functions ([`super::LinearSystem::transfer_function`], D the characteristic quartic) and the
//! neuromuscular filter ω²/Q(s), Q = s² + 2ζωs + ω², closing the two inner loops and the roll
//! loop gives
//!
//! ```text
//! Δ(s)   = Q D + ω² k_δ (k_φ̇ (k_φ + s) N_φ + N_δ)         (the roll loop's characteristic)
//! HQM(s) = −400 ω² k_δ (k_φ̇ s N_φ + N_δ) / ((s² + 40 s + 400) Δ(s))
//! ```
//!
//! (k_φ cancels from the numerator). HumanControl plots and maximizes |HQM(jω)|; Hess reads
//! peaks below 5 as good handling, above 8 as poor.
//!
//! # Its peak, certified
//!
//! |HQM(jω)|² = A(x)/B(x) with x = ω², A and B polynomials (degrees 3 and 8). Its derivative
//! with respect to x vanishes where P(x) = A′(x) B(x) − A(x) B′(x) = 0 (degree ≤ 10), so the
//! maximum over a frequency range is at an end of the range or at a real root of P inside it.
//! The roots are certified by [`crate::advanced::roots::real_roots`] (Gerschgorin discs around
//! Aberth–Ehrlich approximations, bounds on every coefficient from the round-off of forming
//! them): nothing is sampled. The bounds cover forming A, B and P from HQM's coefficients,
//! which are taken as exact (they carry the round-off of the bicycle's transfer functions).

use nalgebra::Complex;

use super::human::{GainTable, HumanGains, Neuromuscular};
use super::poly::{Poly, ratio};
use super::system::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use crate::analysis::design::Parameter;
use crate::analysis::roots::{BoundedPolynomial, RealRoot, UNIT_ROUNDOFF, approximate, real_roots};
use crate::error::{Error, Result, short_number};
use crate::parameters::{BenchmarkParameters, Bicycle};

type Complex64 = Complex<f64>;

/// The handling filter's numerator 400 and denominator s² + 40 s + 400 (HumanControl's
/// `handlingFilterNum`, `handlingFilterDen`): a critically damped second-order filter at
/// 20 rad/s.
pub(crate) const HANDLING_FILTER: [f64; 3] = [400.0, 40.0, 400.0];

/// The most frequencies, speeds or parameter values one handling-quality call evaluates.
pub const MAX_HANDLING_POINTS: usize = 1_000_000;

/// The highest degree the certified peak's polynomial P reaches (A of degree 3 and B of 8 give
/// 10).
const PEAK_DEGREE: usize = 10;

/// The handling quality metric of one bicycle at one speed with one set of gains: the exact
/// transfer function HQM(s) of the module documentation, its magnitude and its certified peak.
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::{HandlingQuality, HumanGains, Neuromuscular};
/// // HumanControl's benchmark gains at 5 m/s (BenchmarkSteerGains.txt).
/// let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
/// let hqm = HandlingQuality::new(&BenchmarkParameters::meijaard2007(), 5.0, &gains,
///     &Neuromuscular::default())?;
/// let peak = hqm.peak()?;
/// assert!(peak.certified && peak.magnitude > 0.0);
/// assert!(hqm.magnitude(&[peak.frequency * 1.01])?[0] <= peak.magnitude);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HandlingQuality {
    speed: f64,
    gains: HumanGains,
    neuromuscular: Neuromuscular,
    numerator: Vec<f64>,
    denominator: Vec<f64>,
    roll_loop: Vec<f64>,
}

/// The peak of |HQM(jω)| over a frequency range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandlingPeak {
    /// ω at the peak \[rad/s\] (an end of the range when the maximum is there).
    pub frequency: f64,
    /// |HQM(jω)| at the peak.
    pub magnitude: f64,
    /// Every critical point of |HQM|² in the range was certified as a simple root (no
    /// unresolved cluster, no lost leading coefficient): the peak is the maximum. When false,
    /// the candidates were still compared, but one of them is only the middle of a cluster.
    pub certified: bool,
}

/// The peak at one point of a sweep (speed or parameter value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandlingRow {
    /// The swept value (speed \[m/s\], or the parameter's value in SI).
    pub value: f64,
    /// The speed \[m/s\].
    pub speed: f64,
    /// The gains used.
    pub gains: HumanGains,
    /// The gains were extrapolated from their table (the speed lies outside it).
    pub extrapolated: bool,
    /// The roll loop (steer, roll-rate and roll-angle loops closed) is stable: HQM means
    /// something only then (HumanControl warns otherwise).
    pub stable: bool,
    /// The peak over all frequencies.
    pub peak: HandlingPeak,
}

/// Refuses gains HQM cannot use: k_δ, k_φ̇, k_φ finite and non-zero (k_φ̇ and k_φ divide the
/// output); the neuromuscular filter positive and finite. Errors name the gain or field.
fn check(gains: &HumanGains, neuromuscular: &Neuromuscular) -> Result<()> {
    for (name, value) in HumanGains::NAMES.iter().zip(gains.to_array()).take(3) {
        if !(value.is_finite() && value != 0.0) {
            return Err(Error::InvalidParameter {
                field: (*name).into(),
                value,
                rule: "the handling quality metric needs kDelta, kPhiDot and kPhi finite and \
                       non-zero (its output is divided by kPhiDot and kPhi)"
                    .into(),
            });
        }
    }
    for (field, value) in [
        ("neuromuscular frequency", neuromuscular.frequency),
        ("neuromuscular damping", neuromuscular.damping),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::InvalidParameter {
                field: field.into(),
                value,
                rule: "must be positive and finite".into(),
            });
        }
    }
    Ok(())
}

impl HandlingQuality {
    /// HQM of `bike` at `speed` with `gains` (k_δ, k_φ̇ and k_φ used; k_ψ and k_y are cut off
    /// with the outer loops) and the `neuromuscular` filter. Errors name the gain, the
    /// neuromuscular field or `speed`.
    pub fn new(
        bike: &BenchmarkParameters,
        speed: f64,
        gains: &HumanGains,
        neuromuscular: &Neuromuscular,
    ) -> Result<Self> {
        check(gains, neuromuscular)?;
        if !speed.is_finite() {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!("must be finite, got {}", short_number(speed)),
            });
        }
        let request = SystemRequest {
            states: Vec::new(),
            inputs: vec![Input::SteerTorque],
            outputs: vec![
                Output::State(StateVariable::Lean),
                Output::State(StateVariable::Steer),
            ],
        };
        let system = LinearSystem::new(bike, speed, &request)?;
        let lean = system.transfer_function(0, 0)?;
        let steer = system.transfer_function(1, 0)?;
        let (w, z) = (neuromuscular.frequency, neuromuscular.damping);
        let (k_delta, k_phi_dot, k_phi) = (gains.k_delta, gains.k_phi_dot, gains.k_phi);
        let n_phi = Poly::from_coefficients(&lean.numerator);
        let n_delta = Poly::from_coefficients(&steer.numerator);
        let d = Poly::from_coefficients(&lean.characteristic);
        let q = Poly::from_coefficients(&[w * w, 2.0 * z * w, 1.0]);
        // Δ = Q D + ω² k_δ (k_φ̇ (k_φ + s) N_φ + N_δ)
        let loop_gain = n_phi
            .scale(k_phi)
            .add(&n_phi.shift(1))
            .scale(k_phi_dot)
            .add(&n_delta);
        let roll_loop = q.mul(&d).add(&loop_gain.scale(w * w * k_delta));
        // HQM = −400 ω² k_δ (k_φ̇ s N_φ + N_δ) / ((s² + 40 s + 400) Δ)
        let numerator = n_phi
            .shift(1)
            .scale(k_phi_dot)
            .add(&n_delta)
            .scale(-HANDLING_FILTER[0] * w * w * k_delta);
        let filter = Poly::from_coefficients(&[HANDLING_FILTER[2], HANDLING_FILTER[1], 1.0]);
        let denominator = filter.mul(&roll_loop);
        let (numerator, denominator, roll_loop) =
            (numerator.values(), denominator.values(), roll_loop.values());
        if numerator.iter().chain(&denominator).any(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                context: "the handling quality metric (gains or speed too large)".into(),
            });
        }
        Ok(HandlingQuality {
            speed,
            gains: *gains,
            neuromuscular: *neuromuscular,
            numerator,
            denominator,
            roll_loop,
        })
    }

    /// The speed \[m/s\].
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// The gains.
    pub fn gains(&self) -> &HumanGains {
        &self.gains
    }

    /// The neuromuscular filter.
    pub fn neuromuscular(&self) -> &Neuromuscular {
        &self.neuromuscular
    }

    /// HQM's numerator, lowest power of s first.
    pub fn numerator(&self) -> &[f64] {
        &self.numerator
    }

    /// HQM's denominator (s² + 40 s + 400) Δ(s), lowest power of s first.
    pub fn denominator(&self) -> &[f64] {
        &self.denominator
    }

    /// Δ(s), the characteristic polynomial of the roll loop (steer angle, roll rate and roll
    /// angle loops closed, the neuromuscular filter included), lowest power first.
    pub fn roll_loop(&self) -> &[f64] {
        &self.roll_loop
    }

    /// The roll loop's poles, the roots of Δ (Aberth–Ehrlich iterations; not certified).
    pub fn roll_loop_poles(&self) -> Vec<Complex64> {
        let mut c = self.roll_loop.clone();
        while c.len() > 1 && c.last() == Some(&0.0) {
            c.pop();
        }
        let mut z = vec![Complex64::new(0.0, 0.0); c.len() - 1];
        approximate(&c, &mut z);
        z.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        z
    }

    /// Whether every pole of the roll loop has a negative real part (HQM is meaningful only
    /// then).
    pub fn is_stable(&self) -> bool {
        self.roll_loop_poles().iter().all(|p| p.re < 0.0)
    }

    /// HQM(s) at any complex s (Horner's scheme, in 1/s beyond |s| = 1).
    pub fn eval(&self, s: Complex64) -> Complex64 {
        ratio(&self.numerator, &self.denominator, s)
    }

    /// |HQM(jω)| at each ω of `frequencies` \[rad/s\]. Errors name `frequencies`: a value
    /// that is not finite, or more than [`MAX_HANDLING_POINTS`].
    pub fn magnitude(&self, frequencies: &[f64]) -> Result<Vec<f64>> {
        if frequencies.len() > MAX_HANDLING_POINTS {
            return Err(Error::LimitExceeded {
                what: "frequencies",
                rule: format!("at most {MAX_HANDLING_POINTS}, got {}", frequencies.len()),
            });
        }
        frequencies
            .iter()
            .enumerate()
            .map(|(k, &omega)| {
                if !omega.is_finite() {
                    return Err(Error::InvalidArgument {
                        what: "frequencies",
                        rule: format!("frequency {} must be a finite number, got {omega}", k + 1),
                    });
                }
                Ok(crate::math::norm(self.eval(Complex64::new(0.0, omega))))
            })
            .collect()
    }

    /// The peak of |HQM(jω)| over all frequencies ω ≥ 0 (see [`Self::peak_between`]).
    pub fn peak(&self) -> Result<HandlingPeak> {
        self.peak_between(0.0, f64::INFINITY)
    }

    /// The peak of |HQM(jω)| over `low` ≤ ω ≤ `high` \[rad/s\] (`high` may be +∞; HQM is
    /// strictly proper, so it vanishes there): the largest of its values at the ends and at
    /// the certified real roots of P(x) = A′B − AB′ inside (module documentation). Errors name
    /// `range`; a pole on the imaginary axis inside the range is an error naming
    /// `frequencies`.
    pub fn peak_between(&self, low: f64, high: f64) -> Result<HandlingPeak> {
        if !(low.is_finite() && low >= 0.0 && high >= low && !high.is_nan()) {
            return Err(Error::InvalidArgument {
                what: "range",
                rule: format!(
                    "needs 0 <= low <= high, low finite, got {} to {}",
                    short_number(low),
                    short_number(high)
                ),
            });
        }
        let a = Poly::from_coefficients(&self.numerator).magnitude_squared();
        let b = Poly::from_coefficients(&self.denominator).magnitude_squared();
        let p = a
            .derivative()
            .mul(&b)
            .add(&a.mul(&b.derivative()).scale(-1.0));
        if p.len() > PEAK_DEGREE + 1 {
            return Err(Error::InvalidArgument {
                what: "polynomial",
                rule: format!(
                    "degree {} is above the largest handled, {PEAK_DEGREE}",
                    p.len() - 1
                ),
            });
        }
        // Scale x = σ t so that the coefficients are balanced (σ a power of two: exact).
        let sigma = balance(&p);
        let mut coefficients = [0.0; PEAK_DEGREE + 1];
        let mut bounds = [0.0; PEAK_DEGREE + 1];
        let mut power = 1.0;
        for (k, (c, size)) in p.terms().iter().enumerate() {
            coefficients[k] = c * power;
            // Forming |N|², |D|², their derivatives, products and difference: a few dozen
            // roundings of at most one unit each per term, bounded generously.
            bounds[k] = 256.0 * UNIT_ROUNDOFF * size * power;
            power *= sigma;
        }
        let roots = real_roots(
            &BoundedPolynomial {
                coefficients,
                bounds,
            },
            "the handling quality metric's peak",
        )?;
        let (x_low, x_high) = (low * low / sigma, high * high / sigma);
        let mut certified = roots.horizon >= x_high || roots.horizon.is_infinite();
        let mut candidates = vec![low];
        if high.is_finite() {
            candidates.push(high);
        }
        for root in roots.as_slice() {
            let (lo, hi) = root.enclosure();
            if hi < x_low || lo > x_high {
                continue;
            }
            match root {
                RealRoot::Simple { value, .. } => {
                    if *value > x_low && *value < x_high {
                        candidates.push((value * sigma).sqrt());
                    }
                }
                RealRoot::Cluster { .. } => {
                    certified = false;
                    for x in [lo, root.value(), hi] {
                        if x > x_low && x < x_high {
                            candidates.push((x * sigma).sqrt());
                        }
                    }
                }
            }
        }
        let mut best = HandlingPeak {
            frequency: low,
            magnitude: 0.0,
            certified,
        };
        for omega in candidates {
            let m = crate::math::norm(self.eval(Complex64::new(0.0, omega)));
            if !m.is_finite() {
                return Err(Error::InvalidArgument {
                    what: "frequencies",
                    rule: format!(
                        "ω = {} rad/s is a pole of the handling quality metric (the roll loop \
                         is marginally stable)",
                        short_number(omega)
                    ),
                });
            }
            if m > best.magnitude {
                best.magnitude = m;
                best.frequency = omega;
            }
        }
        Ok(best)
    }
}

/// A power of two σ that balances the coefficients of p(σ t): the geometric mean of the ratios
/// |c₀/cₙ|^{1/n}, rounded to a power of two.
fn balance(p: &Poly) -> f64 {
    let p = p.terms();
    let first = p.iter().position(|(c, _)| *c != 0.0);
    let last = p.iter().rposition(|(c, _)| *c != 0.0);
    match (first, last) {
        (Some(i), Some(j)) if j > i => {
            let ratio = crate::math::ln((p[i].0 / p[j].0).abs()) / (j - i) as f64;
            let exponent = (ratio / std::f64::consts::LN_2)
                .round()
                .clamp(-500.0, 500.0);
            2f64.powi(exponent as i32)
        }
        _ => 1.0,
    }
}

/// HQM's peak at each of `speeds` \[m/s\], the gains from `table` at each speed (extrapolated
/// outside it, and said so in each row). Errors name `speeds` or come from
/// [`HandlingQuality::new`].
pub fn handling_against_speed(
    bike: &BenchmarkParameters,
    table: &GainTable,
    neuromuscular: &Neuromuscular,
    speeds: &[f64],
) -> Result<Vec<HandlingRow>> {
    if speeds.len() > MAX_HANDLING_POINTS {
        return Err(Error::LimitExceeded {
            what: "speeds",
            rule: format!("at most {MAX_HANDLING_POINTS}, got {}", speeds.len()),
        });
    }
    speeds
        .iter()
        .map(|&v| {
            let lookup = table.at(v)?;
            let hqm = HandlingQuality::new(bike, v, &lookup.gains, neuromuscular)?;
            Ok(HandlingRow {
                value: v,
                speed: v,
                gains: lookup.gains,
                extrapolated: lookup.extrapolated,
                stable: hqm.is_stable(),
                peak: hqm.peak()?,
            })
        })
        .collect()
}

/// HQM's peak at `speed` with `gains` for `base` changed in one `parameter` to each of
/// `values` (SI; the design studies' [`Parameter::set`]). Errors name `parameter` (the speed,
/// or one this bicycle's form lacks) or come from the changed bicycle's check or
/// [`HandlingQuality::new`].
pub fn handling_against_parameter(
    base: &Bicycle,
    parameter: &Parameter,
    values: &[f64],
    speed: f64,
    gains: &HumanGains,
    neuromuscular: &Neuromuscular,
) -> Result<Vec<HandlingRow>> {
    if values.len() > MAX_HANDLING_POINTS {
        return Err(Error::LimitExceeded {
            what: "values",
            rule: format!("at most {MAX_HANDLING_POINTS}, got {}", values.len()),
        });
    }
    if matches!(parameter, Parameter::Speed) {
        return Err(Error::InvalidArgument {
            what: "parameter",
            rule: "the speed changes the gains too: sweep it with the gain table \
                   (handling_against_speed)"
                .into(),
        });
    }
    values
        .iter()
        .map(|&x| {
            let mut bike = base.clone();
            if !parameter.set(&mut bike.description, x) {
                return Err(Error::InvalidArgument {
                    what: "parameter",
                    rule: format!("`{}` is not a parameter of this bicycle", parameter.name()),
                });
            }
            let hqm = HandlingQuality::new(&bike.benchmark()?, speed, gains, neuromuscular)?;
            Ok(HandlingRow {
                value: x,
                speed,
                gains: *gains,
                extrapolated: false,
                stable: hqm.is_stable(),
                peak: hqm.peak()?,
            })
        })
        .collect()
}

#[cfg(test)]
#[path = "handling_tests.rs"]
mod tests;
