//! Transfer functions of a [`LinearSystem`], exactly, from the polynomial matrix
//! P(s) = M s² + v C₁ s + g K₀ + v² K₂ rather than from a state-space realization.
//!
//! P(s) q(s) = f(s) gives q(s) = adj P(s) f(s) / det P(s), and for a 2 × 2 matrix the adjugate
//! is exact: adj P = [[p₂₂, −p₁₂], [−p₂₁, p₁₁]]. The denominator det P(s) is the characteristic
//! quartic ([`super::CharacteristicPolynomial`]), whose roots are the certified eigenvalues
//! ([`crate::advanced::eigen`]). Every state is a polynomial combination of φ(s) and δ(s)
//! divided by a power of s: φ̇ = s φ, and an ignorable coordinate integrates its row of A
//! (ψ = (v + c s) cos λ / (w s) · δ, y = v ψ / s); an output is C's combination of those. So
//! the transfer function from input j to output i is
//!
//! G(s) = [o_φ(s) (adj P f_j)_φ + o_δ(s) (adj P f_j)_δ] / (s^k det P(s)),
//!
//! f_j the input's generalized forces, o the output's polynomials and k its integrators. Each
//! coefficient is formed with the sum of the absolute values of its terms beside it; a
//! coefficient within round-off of that sum is an exact cancellation and is dropped (the s²
//! terms of the front contact's position cancel so), and a factor s common to the numerator
//! and the integrators is cancelled.
//!
//! States are resolved as polynomials on φ and δ from A's rows, which holds for the bicycle's
//! states (the ignorable coordinates are pure integrators). A state with dynamics of its own
//! (a rider model's, to come) will bring its own polynomial rows; until then such a row is
//! refused with an error naming `states`, never answered wrongly.

use nalgebra::DMatrix;

use super::CharacteristicPolynomial;
use super::characteristic::{GeneralSpeedPolynomials, Pencil};
use super::poly::{Poly, eval};
use super::system::{Input, LinearSystem, StateVariable};
use crate::analysis::eigen::{Complex64, eigenvalues, eigenvalues_with};
use crate::analysis::roots::{
    BoundedPolynomial, RealRoot, Unpaired, approximate, pair_conjugates, real_roots,
};
use crate::error::{Error, Result, short_number};
use crate::parameters::BenchmarkParameters;

/// A signal as polynomials on φ(s) and δ(s) over s^integrators.
#[derive(Debug, Clone, PartialEq)]
struct LeanSteer {
    lean: Poly,
    steer: Poly,
    integrators: usize,
}

impl LeanSteer {
    fn zero() -> Self {
        LeanSteer {
            lean: Poly::zero(),
            steer: Poly::zero(),
            integrators: 0,
        }
    }

    fn scale(&self, x: f64) -> Self {
        LeanSteer {
            lean: self.lean.scale(x),
            steer: self.steer.scale(x),
            integrators: self.integrators,
        }
    }

    fn add(&self, other: &LeanSteer) -> Self {
        let k = self.integrators.max(other.integrators);
        let (a, b) = (k - self.integrators, k - other.integrators);
        LeanSteer {
            lean: self.lean.shift(a).add(&other.lean.shift(b)),
            steer: self.steer.shift(a).add(&other.steer.shift(b)),
            integrators: k,
        }
    }
}

/// Each state of the system as polynomials on φ(s), δ(s): the four lean–steer states by
/// definition, each ignorable coordinate as 1/s times its row of A (A is the one home of their
/// kinematics). A row of A refers only to states earlier in [`StateVariable`]'s order (ψ to
/// δ, δ̇; y to ψ), so they are resolved in that order.
fn states_in_lean_steer(system: &LinearSystem) -> Result<Vec<LeanSteer>> {
    let states = system.states();
    let mut rows: Vec<Option<LeanSteer>> = vec![None; states.len()];
    for (i, s) in states.iter().enumerate() {
        let one = Poly::constant(1.0);
        let rate = Poly::from_terms(vec![(0.0, 0.0), (1.0, 1.0)]);
        let (lean, steer) = match s {
            StateVariable::Lean => (one, Poly::zero()),
            StateVariable::Steer => (Poly::zero(), one),
            StateVariable::LeanRate => (rate, Poly::zero()),
            StateVariable::SteerRate => (Poly::zero(), rate),
            _ => continue,
        };
        rows[i] = Some(LeanSteer {
            lean,
            steer,
            integrators: 0,
        });
    }
    let mut order: Vec<usize> = (0..states.len()).filter(|&i| rows[i].is_none()).collect();
    order.sort_by_key(|&i| states[i]);
    for i in order {
        let mut sum = LeanSteer::zero();
        for j in 0..states.len() {
            let x = system.a()[(i, j)];
            if x == 0.0 {
                continue;
            }
            let Some(row) = &rows[j] else {
                return Err(Error::InvalidArgument {
                    what: "states",
                    rule: format!(
                        "{} depends on {}, which is not resolved before it",
                        states[i], states[j]
                    ),
                });
            };
            sum = sum.add(&row.scale(x));
        }
        sum.integrators += 1;
        rows[i] = Some(sum);
    }
    Ok(rows
        .into_iter()
        .map(|r| r.unwrap_or_else(LeanSteer::zero))
        .collect())
}

/// The transfer function G(s) = N(s) / (s^k det P(s)) of one input–output pair of a
/// [`LinearSystem`] (see the module documentation for how it is formed).
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction {
    /// N(s): the numerator's coefficients, lowest power first; empty when G ≡ 0 (an output
    /// the input does not reach to first order, such as x_P).
    pub numerator: Vec<f64>,
    /// det P(s) = a₀ + a₁ s + … + a₄ s⁴: the characteristic quartic at the system's speed.
    pub characteristic: [f64; 5],
    /// k: the integrators, poles at s = 0 beyond the quartic's (1 for yaw, 2 for the lateral
    /// positions), after cancelling any factor s of the numerator.
    pub integrators: usize,
    /// The quartic's roots, the eigenvalues of the lean–steer dynamics (certified).
    eigenvalues: [Complex64; 4],
}

impl TransferFunction {
    /// The denominator s^k det P(s), lowest power first.
    pub fn denominator(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.integrators];
        d.extend_from_slice(&self.characteristic);
        d
    }

    /// The poles: the eigenvalues of the lean–steer dynamics (certified, sorted by decreasing
    /// real part, [`crate::advanced::eigen`]), then k poles at zero.
    pub fn poles(&self) -> Vec<Complex64> {
        let mut p = self.eigenvalues.to_vec();
        p.extend(std::iter::repeat_n(
            Complex64::new(0.0, 0.0),
            self.integrators,
        ));
        p
    }

    /// The zeros: the roots of N(s) (Aberth–Ehrlich iterations, conjugates paired), sorted by
    /// decreasing real part. None for a constant or zero numerator.
    pub fn zeros(&self) -> Result<Vec<Complex64>> {
        let n = self.numerator.len();
        if n < 2 {
            return Ok(Vec::new());
        }
        let mut z = vec![Complex64::new(0.0, 0.0); n - 1];
        approximate(&self.numerator, &mut z);
        let scale = z
            .iter()
            .fold(0.0f64, |m, r| m.max(crate::math::norm(r)))
            .max(1e-300);
        pair_conjugates(
            &mut z,
            |r| r.im.abs() <= 8.0 * f64::EPSILON * scale,
            Unpaired::MadeReal,
        );
        if z.iter().any(|r| !(r.re.is_finite() && r.im.is_finite())) {
            return Err(Error::NonFinite {
                context: "the zeros of a transfer function".into(),
            });
        }
        z.sort_by(|x, y| y.re.total_cmp(&x.re).then(y.im.total_cmp(&x.im)));
        Ok(z)
    }

    /// The gain K of G(s) = K Π(s − zᵢ) / Π(s − pᵢ): the numerator's leading coefficient over
    /// the denominator's (det M); 0 when G ≡ 0.
    pub fn gain(&self) -> f64 {
        self.numerator
            .last()
            .map_or(0.0, |n| n / self.characteristic[4])
    }

    /// G(0), the static gain, when finite: None with an integrator or where det(g K₀ + v² K₂)
    /// vanishes.
    pub fn static_gain(&self) -> Option<f64> {
        if self.integrators > 0 || self.characteristic[0] == 0.0 {
            return None;
        }
        Some(
            self.numerator
                .first()
                .map_or(0.0, |n| n / self.characteristic[0]),
        )
    }

    /// G(s) at any complex s, by Horner's scheme on the polynomials (in 1/s beyond |s| = 1, so
    /// that high frequencies neither overflow nor lose the leading terms). Infinite or NaN at a
    /// pole.
    pub fn eval(&self, s: Complex64) -> Complex64 {
        if self.numerator.is_empty() {
            return Complex64::new(0.0, 0.0);
        }
        if crate::math::norm(s) <= 1.0 {
            let (n, d) = (eval(&self.numerator, s), eval(&self.characteristic, s));
            return n / (d * s.powi(self.integrators as i32));
        }
        let w = s.inv();
        let reversed = |c: &[f64]| c.iter().rev().copied().collect::<Vec<f64>>();
        let n = eval(&reversed(&self.numerator), w);
        let d = eval(&reversed(&self.characteristic), w);
        let excess = self.numerator.len() as i32 - 1 - 4 - self.integrators as i32;
        s.powi(excess) * n / d
    }

    /// The frequency response G(iω) at each ω of `frequencies` [rad/s] (any grid, any order;
    /// the phase is unwrapped along it). Errors name `frequencies`: a value that is not finite,
    /// or one at which G has a pole (ω = 0 with an integrator).
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::linear::{LinearSystem, SystemRequest};
    /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 5.0, &SystemRequest::lean_steer())?;
    /// let steer_torque_to_lean = system.transfer_function(0, 1)?;
    /// let bode = steer_torque_to_lean.frequency_response(&[0.1, 1.0, 10.0, 100.0])?;
    /// assert!(bode.magnitude_db[3] < bode.magnitude_db[2]); // rolls off at high frequency
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn frequency_response(&self, frequencies: &[f64]) -> Result<FrequencyResponse> {
        let mut response = Vec::with_capacity(frequencies.len());
        for (k, &omega) in frequencies.iter().enumerate() {
            if !omega.is_finite() {
                return Err(Error::InvalidArgument {
                    what: "frequencies",
                    rule: format!("frequency {} must be a finite number, got {omega}", k + 1),
                });
            }
            let g = self.eval(Complex64::new(0.0, omega));
            if !(g.re.is_finite() && g.im.is_finite()) {
                return Err(Error::InvalidArgument {
                    what: "frequencies",
                    rule: format!(
                        "frequency {} (ω = {} rad/s) is a pole of the transfer function",
                        k + 1,
                        short_number(omega)
                    ),
                });
            }
            response.push(g);
        }
        Ok(FrequencyResponse::new(frequencies.to_vec(), response))
    }
}

/// G(iω) on a grid of frequencies, with its magnitude and unwrapped phase.
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyResponse {
    /// ω [rad/s], as given.
    pub frequencies: Vec<f64>,
    /// G(iω) [output unit per input unit].
    pub response: Vec<Complex64>,
    /// |G(iω)|.
    pub magnitude: Vec<f64>,
    /// 20 log₁₀ |G(iω)| \[dB\].
    pub magnitude_db: Vec<f64>,
    /// arg G(iω) \[rad\], unwrapped along the grid: each value within π of the one before, the
    /// first the principal value in (−π, π].
    pub phase: Vec<f64>,
}

impl FrequencyResponse {
    fn new(frequencies: Vec<f64>, response: Vec<Complex64>) -> Self {
        let magnitude: Vec<f64> = response.iter().map(crate::math::norm).collect();
        let magnitude_db = magnitude
            .iter()
            .map(|m| 20.0 * crate::math::log10(*m))
            .collect();
        let mut phase: Vec<f64> = Vec::with_capacity(response.len());
        for g in &response {
            let mut p = crate::math::arg(g);
            if let Some(&last) = phase.last() {
                p -= std::f64::consts::TAU * ((p - last) / std::f64::consts::TAU).round();
            }
            phase.push(p);
        }
        FrequencyResponse {
            frequencies,
            response,
            magnitude,
            magnitude_db,
            phase,
        }
    }
}

impl LinearSystem {
    /// The transfer function from input `input` to output `output` (indices into
    /// [`LinearSystem::inputs`] and [`LinearSystem::outputs`]), exactly from P(s) and its
    /// adjugate (see the module documentation of `linear::transfer`).
    ///
    /// For steer torque → lean, G(s) = −(M₁₂ s² + v C₁₁₂ s + g K₀₁₂ + v² K₂₁₂) / det P(s):
    /// the adjugate's entry −p₁₂ times f = [0, 1].
    pub fn transfer_function(&self, output: usize, input: usize) -> Result<TransferFunction> {
        if output >= self.outputs().len() {
            return Err(Error::InvalidArgument {
                what: "output",
                rule: format!(
                    "there are {} outputs, so {} is not one",
                    self.outputs().len(),
                    output
                ),
            });
        }
        if input >= self.inputs().len() {
            return Err(Error::InvalidArgument {
                what: "input",
                rule: format!(
                    "there are {} inputs, so {} is not one",
                    self.inputs().len(),
                    input
                ),
            });
        }
        let canonical = self.canonical();
        let v = self.speed();
        // The open loop's polynomial matrix, or the closed loop's: u = r − K x moves F K's
        // rate columns into C and its angle columns into K (`Pencil::closed`).
        let (pencil, eigenvalues) = match self.gains() {
            None => (Pencil::open_loop(canonical), eigenvalues(canonical, v)?),
            Some(k) => {
                if (4..k.ncols()).any(|j| k.column(j).iter().any(|x| *x != 0.0)) {
                    return Err(Error::InvalidArgument {
                        what: "gains",
                        rule: "a closed loop's transfer functions are formed from its 2 × 2 \
                               polynomial matrix, which holds for gains on lean, steer and \
                               their rates only; with gains on ignorable states use its A, B, \
                               C, D"
                            .into(),
                    });
                }
                let zero = DMatrix::zeros(k.nrows(), k.ncols());
                let pencil = Pencil::closed(canonical, &self.forces, k, &zero);
                GeneralSpeedPolynomials::new(&pencil)?;
                let poly = CharacteristicPolynomial::from_pencil(&pencil);
                let values = eigenvalues_with(&poly, v)?;
                (pencil, values)
            }
        };
        let characteristic = CharacteristicPolynomial::from_pencil(&pencil).at_speed(v);
        let (m, c, k) = pencil.at_speed(v);
        // P(s)'s entries, each coefficient with the sum of its terms' magnitudes.
        let p = |i: usize, j: usize| {
            let k0 = pencil.k0[(i, j)];
            let k1 = v * pencil.k1[(i, j)];
            let k2 = v * v * pencil.k2[(i, j)];
            let c0 = pencil.c0[(i, j)];
            let c1 = v * pencil.c1[(i, j)];
            Poly::from_terms(vec![
                (k[(i, j)], k0.abs() + k1.abs() + k2.abs()),
                (c[(i, j)], c0.abs() + c1.abs()),
                (m[(i, j)], m[(i, j)].abs()),
            ])
        };
        let f = [self.forces[(0, input)], self.forces[(1, input)]];
        let adj_lean = p(1, 1).scale(f[0]).add(&p(0, 1).scale(-f[1]));
        let adj_steer = p(1, 0).scale(-f[0]).add(&p(0, 0).scale(f[1]));
        let states = states_in_lean_steer(self)?;
        let mut o = LeanSteer::zero();
        for (j, row) in states.iter().enumerate() {
            let x = self.c()[(output, j)];
            if x != 0.0 {
                o = o.add(&row.scale(x));
            }
        }
        let mut numerator = o.lean.mul(&adj_lean).add(&o.steer.mul(&adj_steer));
        let feedthrough = self.d()[(output, input)];
        if feedthrough != 0.0 {
            let den = Poly::from_coefficients(&characteristic);
            numerator = numerator.add(&den.shift(o.integrators).scale(feedthrough));
        }
        let mut coefficients = numerator.into_terms();
        while coefficients.last().is_some_and(|c| Poly::negligible(*c)) {
            coefficients.pop();
        }
        let mut integrators = o.integrators;
        while integrators > 0 && coefficients.first().is_some_and(|c| Poly::negligible(*c)) {
            coefficients.remove(0);
            integrators -= 1;
        }
        if coefficients.is_empty() {
            integrators = 0;
        }
        Ok(TransferFunction {
            numerator: coefficients.iter().map(|(c, _)| *c).collect(),
            characteristic,
            integrators,
            eigenvalues,
        })
    }

    /// Every input–output pair's frequency response (`[output][input]`), each as
    /// [`TransferFunction::frequency_response`].
    pub fn frequency_responses(&self, frequencies: &[f64]) -> Result<Vec<Vec<FrequencyResponse>>> {
        (0..self.outputs().len())
            .map(|i| {
                (0..self.inputs().len())
                    .map(|j| {
                        self.transfer_function(i, j)?
                            .frequency_response(frequencies)
                    })
                    .collect()
            })
            .collect()
    }
}

/// The speeds v at which a zero of the transfer function from `input` to lean or steer
/// (`coordinate`) passes through s = 0, certified: the real roots of the numerator's constant
/// term N(0; v) = [adj(g K₀ + v² K₂) f]_coordinate, a polynomial in v (even, degree 2), so
/// they come as ±v.
///
/// For steer torque → lean, N(0; v) = −(g K₀₁₂ + v² K₂₁₂): the right-half-plane zero of
/// counter-steering (the lean first goes the wrong way) reaches the origin at
/// v = √(−g K₀₁₂ / K₂₁₂) and is in the left half-plane beyond. The numerator is a quadratic
/// a s² + b s + c(v) with b = v (C₁₂₂ f_φ − C₁₁₂ f_δ) for lean, so for v ≠ 0 (and b ≠ 0) its
/// zeros cross the imaginary axis only through the origin: these are all the speeds where the
/// pair changes from non-minimum-phase to minimum-phase.
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::linear::{origin_zero_speeds, Input, StateVariable};
/// let speeds = origin_zero_speeds(&BenchmarkParameters::meijaard2007(), &Input::SteerTorque, StateVariable::Lean)?;
/// let v = speeds.last().expect("a crossing").value();
/// assert!((v - 0.577).abs() < 1e-3); // √(−g K₀₁₂ / K₂₁₂)
/// # Ok::<(), whipple::Error>(())
/// ```
///
/// Errors: invalid parameters, a point that is not finite (`inputs`), and a `coordinate`
/// other than lean or steer (`output`).
pub fn origin_zero_speeds(
    bike: &BenchmarkParameters,
    input: &Input,
    coordinate: StateVariable,
) -> Result<Vec<RealRoot>> {
    let request = super::system::SystemRequest {
        states: Vec::new(),
        inputs: vec![*input],
        outputs: vec![super::system::Output::State(coordinate)],
    };
    // Checks the bicycle and the input; the speed does not matter here.
    let system = LinearSystem::new(bike, 0.0, &request)?;
    let f = [system.forces[(0, 0)], system.forces[(1, 0)]];
    let c = system.canonical();
    let k0 = c.k0 * c.g;
    let adjugate = |m: &nalgebra::Matrix2<f64>| {
        DMatrix::from_row_slice(2, 2, &[m[(1, 1)], -m[(0, 1)], -m[(1, 0)], m[(0, 0)]])
    };
    let row = match coordinate {
        StateVariable::Lean => 0,
        StateVariable::Steer => 1,
        other => {
            return Err(Error::InvalidArgument {
                what: "output",
                rule: format!("zeros through the origin are found for lean or steer, not {other}"),
            });
        }
    };
    let term = |a: &DMatrix<f64>| {
        let (x, y) = (a[(row, 0)] * f[0], a[(row, 1)] * f[1]);
        (x + y, 4.0 * f64::EPSILON * (x.abs() + y.abs()))
    };
    let (c0, e0) = term(&adjugate(&k0));
    let (c2, e2) = term(&adjugate(&c.k2));
    let polynomial = BoundedPolynomial {
        coefficients: [c0, 0.0, c2],
        bounds: [e0, 0.0, e2],
    };
    let roots = real_roots(&polynomial, "the numerator's constant term in v")?;
    Ok(roots.as_slice().to_vec())
}
