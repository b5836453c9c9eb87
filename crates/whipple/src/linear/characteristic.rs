//! The characteristic polynomial of the linearized model as a polynomial in both the eigenvalue
//! λ and the forward speed v: p(λ, v) = det(M λ² + v C₁ λ + g K₀ + v² K₂).
//!
//! Its roots in λ are the four eigenvalues of A(v) (det M > 0, so there are exactly four), and
//! its coefficients in λ are polynomials in v of degree ≤ 4. Stability questions become questions
//! about smooth polynomials in v (Routh–Hurwitz), which is how the critical speeds are found to
//! round-off.

use nalgebra::{DMatrix, Matrix2};

use super::Canonical;
use crate::analysis::roots::{BoundedPolynomial, horner_real};
use crate::error::{Error, Result};

/// Degree in λ and in v.
const DEGREE: usize = 4;

/// p(λ, v) = Σ_k Σ_j `coefficients[k][j]` λᵏ vʲ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacteristicPolynomial {
    /// `coefficients[k][j]` multiplies λᵏ vʲ.
    pub coefficients: [[f64; DEGREE + 1]; DEGREE + 1],
    /// The same expansion of the matrices' absolute values with every subtraction an addition:
    /// what bounds the round-off in `coefficients` and in [`Self::at_speed`]
    /// ([`Self::error_bounds`]).
    magnitudes: [[f64; DEGREE + 1]; DEGREE + 1],
    /// The bicycle's own rate scale at rest [1/s] ([`Self::rest_rate`]), formed once.
    rest_rate: f64,
    /// The depth of the circuit forming each coefficient from the stored matrices, in rounded
    /// operations ([`Self::error_bounds`]): 12 for the open loop, more for a closed loop's
    /// matrices, which are formed from the gains.
    depth: u32,
}

/// The depth of the open loop's coefficients' circuit ([`CharacteristicPolynomial::error_bounds`]).
const OPEN_LOOP_DEPTH: u32 = 12;

/// A quadratic matrix pencil in λ whose coefficients are polynomials in the speed v:
/// M λ² + (C₀ + v C₁) λ + K₀ + v K₁ + v² K₂ (2 × 2, SI). The open loop has C₀ = K₁ = 0 and
/// K₀ = g K₀ (Meijaard's); full-state feedback u = −(P + v Q) x on φ, δ, φ̇, δ̇ through inputs
/// of generalized forces F adds C₀ = F P_rate, C₁ += F Q_rate, K₀ += F P_angle, K₁ = F Q_angle
/// (constant gains: Q = 0), so the closed loop keeps the open loop's degrees in λ and v.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pencil {
    pub(crate) m: Matrix2<f64>,
    pub(crate) c0: Matrix2<f64>,
    pub(crate) c1: Matrix2<f64>,
    pub(crate) k0: Matrix2<f64>,
    pub(crate) k1: Matrix2<f64>,
    pub(crate) k2: Matrix2<f64>,
    /// g [m/s²]: the scale of the speed polynomials ([`GeneralSpeedPolynomials`]).
    pub(crate) g: f64,
    /// Rounded operations in forming an entry beyond the canonical matrices' (the gains'
    /// products and sums), added to the coefficients' circuit depth.
    pub(crate) formation_depth: u32,
}

impl Pencil {
    /// The open loop: M λ² + v C₁ λ + g K₀ + v² K₂.
    pub(crate) fn open_loop(canonical: &Canonical) -> Self {
        Pencil {
            m: canonical.m,
            c0: Matrix2::zeros(),
            c1: canonical.c1,
            k0: canonical.k0.map(|x| canonical.g * x),
            k1: Matrix2::zeros(),
            k2: canonical.k2,
            g: canonical.g,
            formation_depth: 0,
        }
    }

    /// The closed loop u = r − K(v) x with K(v) = P + v Q (inputs × states, the first four
    /// columns on φ, δ, φ̇, δ̇; the caller checks that no gain reads another state) and the
    /// inputs' generalized forces F (2 × inputs): M λ² + (v C₁ + F K_rate) λ + g K₀ + v² K₂ +
    /// F K_angle.
    pub(crate) fn closed(
        canonical: &Canonical,
        forces: &DMatrix<f64>,
        p: &DMatrix<f64>,
        q: &DMatrix<f64>,
    ) -> Self {
        let block = |k: &DMatrix<f64>, col: usize| -> Matrix2<f64> {
            let fk = forces * k.columns(col, 2);
            Matrix2::new(fk[(0, 0)], fk[(0, 1)], fk[(1, 0)], fk[(1, 1)])
        };
        let inputs = forces.ncols() as u32;
        Pencil {
            m: canonical.m,
            c0: block(p, 2),
            c1: canonical.c1 + block(q, 2),
            k0: canonical.k0.map(|x| canonical.g * x) + block(p, 0),
            k1: block(q, 0),
            k2: canonical.k2,
            g: canonical.g,
            // F K: a sum of `inputs` products; one addition to the open loop's entry; for a
            // schedule, P and Q from the gains (a difference, a division, a product and a
            // difference).
            formation_depth: inputs + 6,
        }
    }

    /// The matrices of P(λ) = M λ² + C λ + K at speed `v`: (M, C, K).
    pub(crate) fn at_speed(&self, v: f64) -> (Matrix2<f64>, Matrix2<f64>, Matrix2<f64>) {
        (
            self.m,
            self.c0 + self.c1 * v,
            self.k0 + self.k1 * v + self.k2 * (v * v),
        )
    }
}

type Bivariate = [[f64; DEGREE + 1]; DEGREE + 1];

fn multiply(a: &Bivariate, b: &Bivariate) -> Bivariate {
    let mut out = [[0.0; DEGREE + 1]; DEGREE + 1];
    for (ka, row_a) in a.iter().enumerate() {
        for (ja, &x) in row_a.iter().enumerate() {
            if x == 0.0 {
                continue;
            }
            for (kb, row_b) in b.iter().enumerate() {
                for (jb, &y) in row_b.iter().enumerate() {
                    if y != 0.0 && ka + kb <= DEGREE && ja + jb <= DEGREE {
                        out[ka + kb][ja + jb] += x * y;
                    }
                }
            }
        }
    }
    out
}

impl CharacteristicPolynomial {
    /// Expands det(M λ² + v C₁ λ + g K₀ + v² K₂).
    pub fn new(canonical: &Canonical) -> Self {
        Self::from_pencil(&Pencil::open_loop(canonical))
    }

    /// Expands det(M λ² + (C₀ + v C₁) λ + K₀ + v K₁ + v² K₂) of any [`Pencil`].
    pub(crate) fn from_pencil(pencil: &Pencil) -> Self {
        let entry = |i: usize, j: usize, f: fn(f64) -> f64| {
            let mut e = [[0.0; DEGREE + 1]; DEGREE + 1];
            e[2][0] = f(pencil.m[(i, j)]);
            e[1][0] = f(pencil.c0[(i, j)]);
            e[1][1] = f(pencil.c1[(i, j)]);
            e[0][0] = f(pencil.k0[(i, j)]);
            e[0][1] = f(pencil.k1[(i, j)]);
            e[0][2] = f(pencil.k2[(i, j)]);
            e
        };
        let same = |x: f64| x;
        let d = multiply(&entry(0, 0, same), &entry(1, 1, same));
        let o = multiply(&entry(0, 1, same), &entry(1, 0, same));
        let d_abs = multiply(&entry(0, 0, f64::abs), &entry(1, 1, f64::abs));
        let o_abs = multiply(&entry(0, 1, f64::abs), &entry(1, 0, f64::abs));
        let mut coefficients = [[0.0; DEGREE + 1]; DEGREE + 1];
        let mut magnitudes = [[0.0; DEGREE + 1]; DEGREE + 1];
        for k in 0..=DEGREE {
            for j in 0..=DEGREE {
                coefficients[k][j] = d[k][j] - o[k][j];
                magnitudes[k][j] = d_abs[k][j] + o_abs[k][j];
            }
        }
        let mut poly = CharacteristicPolynomial {
            coefficients,
            magnitudes,
            rest_rate: 0.0,
            depth: OPEN_LOOP_DEPTH + pencil.formation_depth,
        };
        let rest = poly.at_speed(0.0);
        poly.rest_rate = (0..DEGREE)
            .map(|k| crate::math::powf((rest[k] / rest[DEGREE]).abs(), 1.0 / (DEGREE - k) as f64))
            .fold(0.0f64, f64::max);
        poly
    }

    /// The bicycle's own rate scale at rest [1/s]: a Cauchy-type bound of the quartic at v = 0
    /// (the rates of falling over), max over k of |aₖ / a₄|^(1/(4−k)); formed with the
    /// polynomial, not at every speed of a sweep.
    pub(crate) fn rest_rate(&self) -> f64 {
        self.rest_rate
    }

    /// Bounds on the round-off in each coefficient of [`Self::at_speed`] (lowest power of λ
    /// first): the expansion (products of two entries, each of which may hold a product with
    /// g or a sum of at most three terms) and Horner's scheme in v are circuits of depth at
    /// most 12 on the matrices as stored, so each computed aₖ lies within γ₁₂ Σⱼ |cₖⱼ| |v|ʲ of
    /// the exact coefficient of those matrices (Higham 2002, §3.1; the |cₖⱼ| are the expansion
    /// of the entries' absolute values). A closed loop's entries are formed from the gains
    /// with more operations, which deepen the circuit ([`Pencil::formation_depth`]).
    pub(crate) fn error_bounds(&self, v: f64) -> [f64; DEGREE + 1] {
        const U: f64 = f64::EPSILON / 2.0;
        let depth = f64::from(self.depth);
        let gamma = depth * U / (1.0 - depth * U);
        let mut e = [0.0; DEGREE + 1];
        let av = v.abs();
        for (k, row) in self.magnitudes.iter().enumerate() {
            e[k] = gamma * horner_real(row, av);
        }
        e
    }

    /// The coefficients in λ at speed v, lowest power first: p(λ) = Σ aₖ λᵏ.
    #[inline]
    pub fn at_speed(&self, v: f64) -> [f64; DEGREE + 1] {
        let mut a = [0.0; DEGREE + 1];
        for (k, row) in self.coefficients.iter().enumerate() {
            a[k] = horner_real(row, v);
        }
        a
    }
}

/// A value with what an a-priori round-off bound needs: the computed value, the same circuit
/// evaluated on absolute values (subtractions become additions) and the circuit's depth in
/// rounded operations. For a circuit of +, −, × of depth d on exact inputs, the computed value
/// lies within γ_d · |circuit| of the exact one (γ_d = d u / (1 − d u), u = 2⁻⁵³; Higham 2002,
/// §3.1), provided nothing underflows — see [`SpeedPolynomials::new`] for why nothing does.
#[derive(Debug, Clone, Copy)]
struct Tracked {
    v: f64,
    a: f64,
    d: u32,
}

impl Tracked {
    const ZERO: Tracked = Tracked {
        v: 0.0,
        a: 0.0,
        d: 0,
    };
    fn exact(x: f64) -> Self {
        Tracked {
            v: x,
            a: x.abs(),
            d: 0,
        }
    }
    /// A stored matrix entry, with the allowance for its formation from the parameters.
    fn entry(x: f64) -> Self {
        Tracked {
            v: x,
            a: x.abs(),
            d: FORMATION_ALLOWANCE,
        }
    }
    fn bound(self) -> f64 {
        if self.a == 0.0 {
            return 0.0;
        }
        let du = f64::from(self.d) * f64::EPSILON / 2.0;
        self.a * du / (1.0 - 2.0 * du) * (1.0 + 4.0 * f64::EPSILON) + 1e-300
    }
}

impl std::ops::Add for Tracked {
    type Output = Tracked;
    #[inline]
    fn add(self, o: Tracked) -> Tracked {
        Tracked {
            v: self.v + o.v,
            a: self.a + o.a,
            d: self.d.max(o.d) + 1,
        }
    }
}
impl std::ops::Sub for Tracked {
    type Output = Tracked;
    #[inline]
    fn sub(self, o: Tracked) -> Tracked {
        Tracked {
            v: self.v - o.v,
            a: self.a + o.a,
            d: self.d.max(o.d) + 1,
        }
    }
}
impl std::ops::Mul for Tracked {
    type Output = Tracked;
    #[inline]
    fn mul(self, o: Tracked) -> Tracked {
        Tracked {
            v: self.v * o.v,
            a: self.a * o.a,
            d: self.d.max(o.d) + 1,
        }
    }
}
impl std::ops::Mul<f64> for Tracked {
    type Output = Tracked;
    /// Multiplication by a small exact integer constant.
    #[inline]
    fn mul(self, k: f64) -> Tracked {
        Tracked {
            v: self.v * k,
            a: self.a * k.abs(),
            d: self.d + 1,
        }
    }
}

/// A polynomial in u of degree ≤ 6 with tracked coefficients.
#[derive(Debug, Clone, Copy)]
struct UPoly {
    c: [Tracked; 7],
    deg: usize,
}

impl UPoly {
    fn new(c: &[Tracked]) -> Self {
        let mut p = UPoly {
            c: [Tracked::ZERO; 7],
            deg: 0,
        };
        p.c[..c.len()].copy_from_slice(c);
        p.deg = c.len().saturating_sub(1);
        p
    }
    fn constant(x: Tracked) -> Self {
        Self::new(&[x])
    }
    fn mul(&self, o: &UPoly) -> UPoly {
        let mut out = UPoly {
            c: [Tracked::ZERO; 7],
            deg: (self.deg + o.deg).min(6),
        };
        let mut first = [true; 7];
        for i in 0..=self.deg {
            for j in 0..=o.deg {
                if i + j <= 6 {
                    let t = self.c[i] * o.c[j];
                    if first[i + j] {
                        out.c[i + j] = t;
                        first[i + j] = false;
                    } else {
                        out.c[i + j] = out.c[i + j] + t;
                    }
                }
            }
        }
        out
    }
    fn scale(&self, k: f64) -> UPoly {
        let mut out = *self;
        for c in out.c.iter_mut().take(self.deg + 1) {
            *c = *c * k;
        }
        out
    }
    /// Multiplies by uᵏ.
    fn shift(&self, k: usize) -> UPoly {
        let mut out = UPoly {
            c: [Tracked::ZERO; 7],
            deg: (self.deg + k).min(6),
        };
        for i in 0..=self.deg {
            if i + k <= 6 {
                out.c[i + k] = self.c[i];
            }
        }
        out
    }
    fn add(&self, o: &UPoly) -> UPoly {
        let mut out = UPoly {
            c: [Tracked::ZERO; 7],
            deg: self.deg.max(o.deg),
        };
        for i in 0..=out.deg {
            out.c[i] = match (i <= self.deg, i <= o.deg) {
                (true, true) => self.c[i] + o.c[i],
                (true, false) => self.c[i],
                (false, true) => o.c[i],
                (false, false) => Tracked::ZERO,
            };
        }
        out
    }
    fn bounded<const N: usize>(&self) -> BoundedPolynomial<N> {
        let mut p = BoundedPolynomial {
            coefficients: [0.0; N],
            bounds: [0.0; N],
        };
        for i in 0..N.min(7) {
            p.coefficients[i] = self.c[i].v;
            p.bounds[i] = self.c[i].bound();
        }
        p
    }
}

/// Units of round-off allowed in each stored matrix entry for its formation from the parameters
/// (Appendix A: a few dozen operations per entry); structural zeros stay exact.
const FORMATION_ALLOWANCE: u32 = 64;

/// The smallest non-zero matrix entry, relative to the largest, that keeps every product in
/// the discriminant (degree 12 in the entries) far above the underflow threshold.
const SMALLEST_RELATIVE_ENTRY: f64 = 1.3e-23; // 2⁻⁷⁶

/// The characteristic polynomial's coefficients as polynomials in the speed, built exactly from
/// M, C₁, K₀, K₂ with rigorous bounds on their round-off.
///
/// With λ = √g μ and v = √g ν, det(M λ² + v C₁ λ + g K₀ + v² K₂) = g² det(M μ² + ν C₁ μ + K₀ +
/// ν² K₂), so g drops out: everything here is in the scaled speed ν = v / √g and the scaled
/// eigenvalue μ = λ / √g, and u = ν² = v² / g \[m\]. The matrices are also scaled by a common power
/// of two (exact), so that no coefficient overflows for any physical magnitude.
///
/// Parity: p(λ, −v) = p(−λ, v), so the coefficients of λ⁴, λ², λ⁰ are even in ν and those of λ³,
/// λ¹ odd:
///
/// - a₄ = det M (constant), a₃ = ν α, a₂ = a₂₀ + a₂₂ u, a₁ = ν (β₀ + β₁ u),
///   a₀ = a₀₀ + a₀₂ u + a₀₄ u² (= det(K₀ + u K₂));
/// - the second Hurwitz determinant Δ₂ = a₃a₂ − a₄a₁ = ν E(u), E = α a₂ − a₄ β (degree 1);
/// - the third, Δ₃ = a₃a₂a₁ − a₄a₁² − a₀a₃² = u D(u), D = α a₂ β − a₄ β² − α² a₀ (degree 2);
/// - the discriminant in λ is even in ν: a polynomial of degree 6 in u ([`Self::discriminant`]);
/// - the quartic's P = 8a₄a₂ − 3a₃² (degree 1) and
///   D₄ = 64a₄³a₀ − 16a₄²a₂² + 16a₄a₃²a₂ − 16a₄²a₃a₁ − 3a₃⁴ (degree 2), which with the
///   discriminant tell how many eigenvalues are real.
///
/// Bounds: each coefficient is a circuit of +, −, × on the (exact) f64 matrix entries, evaluated
/// alongside its absolute-value circuit; the bound γ_d · |circuit| (Higham 2002, §3.1) holds for
/// the true coefficient of the polynomial of any matrices whose entries lie within 64 units of
/// round-off (relative) of the stored ones: that allowance covers the round-off in forming
/// M, C₁, K₀, K₂ from the 25 parameters (a few dozen operations per entry), unless one of the
/// Appendix A formulas itself cancels catastrophically. Entries that are exactly zero by
/// structure (K₂'s first column, C₁₁₁) stay exact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedPolynomials {
    /// √g, the scale between ν and v [√(m/s²)].
    pub sqrt_g: f64,
    /// a₄ = det M (scaled).
    pub a4: BoundedPolynomial<1>,
    /// α = a₃ / ν.
    pub alpha: BoundedPolynomial<1>,
    /// a₂(u).
    pub a2: BoundedPolynomial<2>,
    /// β(u) = a₁ / ν.
    pub beta: BoundedPolynomial<2>,
    /// a₀(u).
    pub a0: BoundedPolynomial<3>,
    /// E(u) = Δ₂ / ν.
    pub e: BoundedPolynomial<2>,
    /// D(u) = Δ₃ / u.
    pub d: BoundedPolynomial<3>,
}

fn accuracy_lost(reason: String) -> Error {
    Error::AccuracyLost {
        quantity: "the characteristic polynomial".into(),
        reason,
    }
}

/// The scaled, tracked entries: m, c, k (K₀), s (K₂).
type Entries = [[Tracked; 4]; 4];

fn entries(canonical: &Canonical) -> Result<(Entries, f64, i32)> {
    let g = canonical.g;
    if !(g.is_finite() && g > 0.0) {
        return Err(Error::InvalidParameter {
            field: "g".into(),
            value: g,
            rule: "must be a finite number greater than zero".into(),
        });
    }
    let mats = [canonical.m, canonical.c1, canonical.k0, canonical.k2];
    let mut largest = 0.0f64;
    for m in &mats {
        for x in m.iter() {
            if !x.is_finite() {
                return Err(accuracy_lost(format!(
                    "a matrix entry is not finite ({x}): the parameters overflow double precision"
                )));
            }
            largest = largest.max(x.abs());
        }
    }
    if largest == 0.0 {
        return Err(accuracy_lost("every matrix entry is zero".into()));
    }
    // Common power-of-two scale (exact): the largest entry in [0.5, 1).
    let exponent = crate::math::log2(largest).floor() as i32 + 1;
    let scale = 2f64.powi(-exponent);
    let mut out = [[Tracked::ZERO; 4]; 4];
    for (mi, m) in mats.iter().enumerate() {
        for (k, x) in m.iter().enumerate() {
            let y = x * scale;
            if y != 0.0 && y.abs() < SMALLEST_RELATIVE_ENTRY {
                return Err(accuracy_lost(format!(
                    "the entries of M, C1, K0, K2 span more than 22 orders of magnitude \
                     (largest {largest:e}, smallest non-zero {:e})",
                    x.abs()
                )));
            }
            // nalgebra stores column-major: index k = row + 2 col.
            out[mi][k] = Tracked::entry(y);
        }
    }
    Ok((out, g.sqrt(), exponent))
}

/// Entry (i, j) of the tracked matrix `m` (column-major storage).
#[inline]
fn at(m: &[Tracked; 4], i: usize, j: usize) -> Tracked {
    m[i + 2 * j]
}

/// The tracked coefficients a₄, α, a₂, β, a₀ (scaled).
struct Coefficients {
    a4: Tracked,
    alpha: Tracked,
    a2: [Tracked; 2],
    beta: [Tracked; 2],
    a0: [Tracked; 3],
}

/// Coefficient of det(X + Y)'s cross terms: x₀₀y₁₁ + y₀₀x₁₁ − x₀₁y₁₀ − y₀₁x₁₀.
#[inline]
fn mixed(x: &[Tracked; 4], y: &[Tracked; 4]) -> Tracked {
    (at(x, 0, 0) * at(y, 1, 1) + at(y, 0, 0) * at(x, 1, 1))
        - (at(x, 0, 1) * at(y, 1, 0) + at(y, 0, 1) * at(x, 1, 0))
}

#[inline]
fn det(x: &[Tracked; 4]) -> Tracked {
    at(x, 0, 0) * at(x, 1, 1) - at(x, 0, 1) * at(x, 1, 0)
}

fn coefficients(e: &Entries) -> Coefficients {
    let [m, c, k, s] = e;
    Coefficients {
        a4: det(m),
        alpha: mixed(m, c),
        a2: [mixed(m, k), mixed(m, s) + det(c)],
        beta: [mixed(c, k), mixed(c, s)],
        a0: [det(k), mixed(k, s), det(s)],
    }
}

impl SpeedPolynomials {
    /// The polynomials of a bicycle's linearized model.
    ///
    /// Errors with [`Error::AccuracyLost`] when an entry of the matrices is not finite, when the
    /// entries span so many orders of magnitude that products could underflow, or when det M is
    /// not certainly positive (lost to cancellation).
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, Canonical};
    /// use whipple::advanced::linear::SpeedPolynomials;
    /// let p = SpeedPolynomials::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?)?;
    /// // The capsize speed is the positive root of a₀(u), u = v²/g.
    /// let vc = p.sqrt_g * (-p.a0.coefficients[0] / p.a0.coefficients[1]).sqrt();
    /// assert!((vc - 6.02426201538837).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn new(canonical: &Canonical) -> Result<Self> {
        let (e, sqrt_g, exponent) = entries(canonical)?;
        let co = coefficients(&e);
        if co.a4.v.partial_cmp(&co.a4.bound()) != Some(std::cmp::Ordering::Greater) {
            // Unscaled for the message: det M scales with the square of the entries.
            let unscale = 2f64.powi(2 * exponent);
            return Err(accuracy_lost(format!(
                "det M = {:e} is not certainly positive: its round-off bound is {:e} (the mass \
                 matrix's determinant is lost to cancellation, as happens when one body's mass \
                 dwarfs the others)",
                co.a4.v * unscale,
                co.a4.bound() * unscale
            )));
        }
        let a4 = UPoly::constant(co.a4);
        let alpha = UPoly::constant(co.alpha);
        let a2 = UPoly::new(&co.a2);
        let beta = UPoly::new(&co.beta);
        let a0 = UPoly::new(&co.a0);
        // E = α a₂ − a₄ β.
        let ep = alpha.mul(&a2).add(&a4.mul(&beta).scale(-1.0));
        // D = α a₂ β − a₄ β² − α² a₀.
        let dp = alpha
            .mul(&a2)
            .mul(&beta)
            .add(&a4.mul(&beta).mul(&beta).scale(-1.0))
            .add(&alpha.mul(&alpha).mul(&a0).scale(-1.0));
        let out = SpeedPolynomials {
            sqrt_g,
            a4: a4.bounded(),
            alpha: alpha.bounded(),
            a2: a2.bounded(),
            beta: beta.bounded(),
            a0: a0.bounded(),
            e: ep.bounded(),
            d: dp.bounded(),
        };
        for x in [
            out.a2.coefficients[1],
            out.a0.coefficients[2],
            out.d.coefficients[2],
            out.d.bounds[2],
        ] {
            if !x.is_finite() {
                return Err(accuracy_lost("a coefficient overflowed".into()));
            }
        }
        Ok(out)
    }

    /// The discriminant of the quartic in μ as a polynomial of degree 6 in u, with bounds; and
    /// the quartic's P(u) and D₄(u) (see the type's documentation).
    pub fn discriminant(
        canonical: &Canonical,
    ) -> Result<(
        BoundedPolynomial<7>,
        BoundedPolynomial<2>,
        BoundedPolynomial<3>,
    )> {
        let (e, _, _) = entries(canonical)?;
        let co = coefficients(&e);
        let a = UPoly::constant(co.a4);
        let b = UPoly::constant(co.alpha); // a₃ = ν b
        let c = UPoly::new(&co.a2);
        let d = UPoly::new(&co.beta); // a₁ = ν d
        let ee = UPoly::new(&co.a0);
        // Each term has an even total power of a₃ and a₁ (the quartic discriminant is
        // isobaric of weight 12): bⁱdʲ carries u^((i+j)/2).
        let m = |parts: &[&UPoly], k: f64, shift: usize| -> UPoly {
            let mut p = UPoly::constant(Tracked::exact(1.0));
            for q in parts {
                p = p.mul(q);
            }
            p.scale(k).shift(shift)
        };
        let terms = [
            m(&[&a, &a, &a, &ee, &ee, &ee], 256.0, 0),
            m(&[&a, &a, &b, &d, &ee, &ee], -192.0, 1),
            m(&[&a, &a, &c, &c, &ee, &ee], -128.0, 0),
            m(&[&a, &a, &c, &d, &d, &ee], 144.0, 1),
            m(&[&a, &a, &d, &d, &d, &d], -27.0, 2),
            m(&[&a, &b, &b, &c, &ee, &ee], 144.0, 1),
            m(&[&a, &b, &b, &d, &d, &ee], -6.0, 2),
            m(&[&a, &b, &c, &c, &d, &ee], -80.0, 1),
            m(&[&a, &b, &c, &d, &d, &d], 18.0, 2),
            m(&[&a, &c, &c, &c, &c, &ee], 16.0, 0),
            m(&[&a, &c, &c, &c, &d, &d], -4.0, 1),
            m(&[&b, &b, &b, &b, &ee, &ee], -27.0, 2),
            m(&[&b, &b, &b, &c, &d, &ee], 18.0, 2),
            m(&[&b, &b, &b, &d, &d, &d], -4.0, 3),
            m(&[&b, &b, &c, &c, &c, &ee], -4.0, 1),
            m(&[&b, &b, &c, &c, &d, &d], 1.0, 2),
        ];
        let mut disc = terms[0];
        for t in &terms[1..] {
            disc = disc.add(t);
        }
        // P = 8 a₄ a₂ − 3 α² u.
        let p = a.mul(&c).scale(8.0).add(&b.mul(&b).scale(-3.0).shift(1));
        // D₄ = 64a₄³a₀ − 16a₄²a₂² + 16a₄α²u a₂ − 16a₄²αβ u − 3α⁴u².
        let d4 = m(&[&a, &a, &a, &ee], 64.0, 0)
            .add(&m(&[&a, &a, &c, &c], -16.0, 0))
            .add(&m(&[&a, &b, &b, &c], 16.0, 1))
            .add(&m(&[&a, &a, &b, &d], -16.0, 1))
            .add(&m(&[&b, &b, &b, &b], -3.0, 2));
        Ok((disc.bounded(), p.bounded(), d4.bounded()))
    }
}

/// The characteristic polynomial of any [`Pencil`] with its coefficients, and the Hurwitz
/// determinants, as polynomials in the scaled speed ν = v/√g with a-priori round-off bounds:
/// what the certified stability line needs when p(λ, −v) = p(−λ, v) no longer holds (a closed
/// loop: the gains add damping and stiffness that do not change sign with the speed), so the
/// even–odd structure of [`SpeedPolynomials`] is lost. With μ = λ/√g:
///
/// - a₄ = det M (constant), a₃(ν) (degree 1), a₂(ν) (2), a₁(ν) (3), a₀(ν) (4);
/// - Δ₂ = a₃a₂ − a₄a₁ (degree 3) and Δ₃ = a₃a₂a₁ − a₄a₁² − a₀a₃² (degree 6).
///
/// Bounds as in [`SpeedPolynomials`]: the stored entries (scaled by 1/√g and 1/g where the
/// speed's and the eigenvalue's scaling ask, then by a common power of two) are taken within
/// 64 units of round-off of the pencil's, and every coefficient is a tracked circuit on them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GeneralSpeedPolynomials {
    /// √g, the scale between ν and v [√(m/s²)].
    pub(crate) sqrt_g: f64,
    /// a₄ = det M (scaled).
    pub(crate) a4: BoundedPolynomial<1>,
    pub(crate) a3: BoundedPolynomial<2>,
    pub(crate) a1: BoundedPolynomial<4>,
    pub(crate) a0: BoundedPolynomial<5>,
    /// Δ₂ = a₃a₂ − a₄a₁.
    pub(crate) delta2: BoundedPolynomial<4>,
    /// Δ₃ = a₃a₂a₁ − a₄a₁² − a₀a₃².
    pub(crate) delta3: BoundedPolynomial<7>,
}

impl GeneralSpeedPolynomials {
    /// The polynomials of a pencil. Errors as [`SpeedPolynomials::new`]: [`Error::AccuracyLost`]
    /// when an entry is not finite, the entries span too many orders of magnitude, or det M is
    /// not certainly positive; [`Error::InvalidParameter`] naming `g` when g is not positive.
    pub(crate) fn new(pencil: &Pencil) -> Result<Self> {
        let g = pencil.g;
        if !(g.is_finite() && g > 0.0) {
            return Err(Error::InvalidParameter {
                field: "g".into(),
                value: g,
                rule: "must be a finite number greater than zero".into(),
            });
        }
        let sqrt_g = g.sqrt();
        let mats = [
            pencil.m,
            pencil.c0 / sqrt_g,
            pencil.c1,
            pencil.k0 / g,
            pencil.k1 / sqrt_g,
            pencil.k2,
        ];
        let mut largest = 0.0f64;
        for m in &mats {
            for x in m.iter() {
                if !x.is_finite() {
                    return Err(accuracy_lost(format!(
                        "a matrix entry of the closed loop is not finite ({x})"
                    )));
                }
                largest = largest.max(x.abs());
            }
        }
        if largest == 0.0 {
            return Err(accuracy_lost("every matrix entry is zero".into()));
        }
        let exponent = crate::math::log2(largest).floor() as i32 + 1;
        let scale = 2f64.powi(-exponent);
        let mut e = [[Tracked::ZERO; 4]; 6];
        for (mi, m) in mats.iter().enumerate() {
            for (k, x) in m.iter().enumerate() {
                let y = x * scale;
                if y != 0.0 && y.abs() < SMALLEST_RELATIVE_ENTRY {
                    return Err(accuracy_lost(format!(
                        "the entries of the closed loop's matrices span more than 22 orders of \
                         magnitude (largest {largest:e}, smallest non-zero {:e})",
                        x.abs()
                    )));
                }
                e[mi][k] = Tracked::entry(y);
            }
        }
        // Entry (i, j) as a polynomial in μ whose coefficients are polynomials in ν.
        let entry = |i: usize, j: usize| -> [UPoly; 3] {
            let [m, c0, c1, k0, k1, k2] = &e;
            [
                UPoly::new(&[at(k0, i, j), at(k1, i, j), at(k2, i, j)]),
                UPoly::new(&[at(c0, i, j), at(c1, i, j)]),
                UPoly::constant(at(m, i, j)),
            ]
        };
        let product = |x: [UPoly; 3], y: [UPoly; 3]| -> [Option<UPoly>; 5] {
            let mut out: [Option<UPoly>; 5] = [None; 5];
            for (a, xa) in x.iter().enumerate() {
                for (b, yb) in y.iter().enumerate() {
                    let t = xa.mul(yb);
                    out[a + b] = Some(match out[a + b] {
                        Some(s) => s.add(&t),
                        None => t,
                    });
                }
            }
            out
        };
        let diagonal = product(entry(0, 0), entry(1, 1));
        let off = product(entry(0, 1), entry(1, 0));
        let mut a = [UPoly::constant(Tracked::ZERO); 5];
        for k in 0..5 {
            if let (Some(d), Some(o)) = (diagonal[k], off[k]) {
                a[k] = d.add(&o.scale(-1.0));
            }
        }
        let [a0, a1, a2, a3, a4] = a;
        if a4.c[0].v.partial_cmp(&a4.c[0].bound()) != Some(std::cmp::Ordering::Greater) {
            return Err(accuracy_lost(
                "det M is not certainly positive: the mass matrix's determinant is lost to \
                 cancellation"
                    .into(),
            ));
        }
        let delta2 = a3.mul(&a2).add(&a4.mul(&a1).scale(-1.0));
        let delta3 = a3
            .mul(&a2)
            .mul(&a1)
            .add(&a4.mul(&a1).mul(&a1).scale(-1.0))
            .add(&a0.mul(&a3).mul(&a3).scale(-1.0));
        let out = GeneralSpeedPolynomials {
            sqrt_g,
            a4: a4.bounded(),
            a3: a3.bounded(),
            a1: a1.bounded(),
            a0: a0.bounded(),
            delta2: delta2.bounded(),
            delta3: delta3.bounded(),
        };
        if out
            .delta3
            .coefficients
            .iter()
            .chain(out.delta3.bounds.iter())
            .any(|x| !x.is_finite())
        {
            return Err(accuracy_lost("a coefficient overflowed".into()));
        }
        Ok(out)
    }
}
