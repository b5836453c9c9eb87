//! Eigenvalues and eigenvectors of the linearized bicycle at one speed.
//!
//! The four eigenvalues of A(v) are the roots of the characteristic quartic
//! det(M λ² + v C₁ λ + g K₀ + v² K₂). They are found in closed form (Ferrari's resolvent cubic)
//! and then polished by simultaneous Aberth–Ehrlich iterations on the quartic, a bounded number
//! of them, to the accuracy that double precision allows. This is several times faster than a
//! general Hessenberg QR and never iterates without bound. The tests cross-check it against
//! faer's general eigensolver on A(v).

use nalgebra::{Complex, Matrix2, Vector2, Vector4};

use crate::error::{Error, Result};
use crate::linear::{Canonical, CharacteristicPolynomial};

pub(crate) use super::roots::horner;
use super::roots::{Unpaired, aberth, pair_conjugates};

/// A complex number of f64.
pub type Complex64 = Complex<f64>;

/// The coefficients a₀ … a₄ in short, for messages.
fn coefficient_list(a: &[f64; 5]) -> String {
    a.iter()
        .map(|x| crate::error::short_number(*x))
        .collect::<Vec<_>>()
        .join(", ")
}

fn complex_text(z: Complex64) -> String {
    use crate::error::short_number;
    if z.im == 0.0 {
        short_number(z.re)
    } else {
        format!(
            "{} {} {}i",
            short_number(z.re),
            if z.im < 0.0 { "-" } else { "+" },
            short_number(z.im.abs())
        )
    }
}

/// Refuses a speed that is not a finite number, naming it.
pub(crate) fn check_speed(speed: f64) -> Result<()> {
    if speed.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument {
            what: "speed",
            rule: format!("a speed must be a finite number, got {speed}"),
        })
    }
}

/// How far a printed eigenvalue may be from the exact eigenvalue of the stored matrices,
/// relative to its size; a root near zero may also be off by 1e-12 of the bicycle's rate scale
/// at rest (max over k of |aₖ/a₄|^(1/(4−k)) at v = 0, a few 1/s for a real bicycle).
pub(crate) const EIGENVALUE_TOLERANCE: f64 = 1e-6;

/// The eigenvalues at `speed`, each certified: a bound on how far round-off (in forming the
/// quartic's coefficients at this speed and in evaluating it) can have moved it is computed,
/// and an eigenvalue whose bound exceeds [`EIGENVALUE_TOLERANCE`] of its size is refused with
/// [`Error::AccuracyLost`] instead of printed. The coefficients grow as powers of v up to v⁴
/// beside terms in g that do not, so at speeds far beyond any ridden one (about 1e16 m/s for the
/// benchmark bicycle, 1e4 m/s for the two-mass skate) the small roots are decided by
/// round-off; the critical speeds (`analysis::stability`) are certified at any speed and need
/// no eigenvalue.
///
/// The bound, first order in the perturbation: a root z of the computed quartic p moves by at
/// most (|p(z)| + Σₖ (eₖ + γ₈|aₖ|) |z|ᵏ) / |p′(z)|, eₖ bounding the error of aₖ
/// ([`CharacteristicPolynomial::error_bounds`]) and γ₈|aₖ| that of Horner's scheme. At a double
/// root (v_d) the computed pair is √ε apart and the bound stays near √ε, well inside the
/// tolerance.
pub(crate) fn certified_roots(
    poly: &CharacteristicPolynomial,
    speed: f64,
) -> Result<[Complex64; 4]> {
    check_speed(speed)?;
    let a = poly.at_speed(speed);
    let roots = quartic_roots(&a)?;
    let e = poly.error_bounds(speed);
    const U: f64 = f64::EPSILON / 2.0;
    let gamma8 = 8.0 * U / (1.0 - 8.0 * U);
    // The bicycle's own rate scale at rest (a Cauchy-type bound of the quartic at v = 0: the
    // rates of falling over, in 1/s), of which a millionth of a millionth is the absolute
    // accuracy asked of a root near zero (the capsize root at v_c).
    let floor = 1e-12 * poly.rest_rate();
    for z in &roots {
        let (p, dp) = horner(&a, *z);
        let size = crate::math::norm(z);
        let mut slack = 0.0;
        let mut power = 1.0;
        for k in 0..5 {
            slack += (e[k] + gamma8 * a[k].abs()) * power;
            power *= size;
        }
        let radius = (crate::math::norm(p) + slack) / crate::math::norm(dp);
        let allowed = EIGENVALUE_TOLERANCE * size + floor;
        // A NaN radius (an overflow) is refused too.
        if radius.is_nan() || radius > allowed {
            return Err(Error::AccuracyLost {
                quantity: format!(
                    "the eigenvalues at {} m/s",
                    crate::error::short_number(speed)
                ),
                reason: format!(
                    "round-off in the characteristic polynomial could move the eigenvalue {} by \
                     up to {} 1/s, more than {EIGENVALUE_TOLERANCE:e} of its size: the roots' \
                     scales are too far apart at this speed for double precision (the critical \
                     speeds, `speeds`, hold at any speed)",
                    complex_text(*z),
                    crate::error::short_number(radius)
                ),
            });
        }
    }
    Ok(roots)
}

/// The largest real root of t³ + b t² + c t + d.
fn largest_real_cubic_root(b: f64, c: f64, d: f64) -> f64 {
    let q = (b * b - 3.0 * c) / 9.0;
    let r = (2.0 * b * b * b - 9.0 * b * c + 27.0 * d) / 54.0;
    let mut t = if r * r < q * q * q {
        // Three real roots: trigonometric form, the largest one.
        let theta = crate::math::acos((r / (q * q * q).sqrt()).clamp(-1.0, 1.0));
        -2.0 * q.sqrt() * crate::math::cos(theta / 3.0) - b / 3.0
    } else {
        let a = -r.signum() * crate::math::cbrt(r.abs() + (r * r - q * q * q).sqrt());
        let bb = if a != 0.0 { q / a } else { 0.0 };
        (a + bb) - b / 3.0
    };
    // Two Newton steps against round-off in the closed form.
    for _ in 0..2 {
        let f = ((t + b) * t + c) * t + d;
        let df = (3.0 * t + 2.0 * b) * t + c;
        if df != 0.0 {
            let step = f / df;
            if step.is_finite() {
                t -= step;
            }
        }
    }
    t
}

/// The principal square root, without the slow `hypot` of the general library routine (the
/// arguments here are far from overflow).
fn csqrt(z: Complex64) -> Complex64 {
    let (a, b) = (z.re, z.im);
    if b == 0.0 {
        return if a >= 0.0 {
            Complex64::new(a.sqrt(), 0.0)
        } else {
            Complex64::new(0.0, (-a).sqrt())
        };
    }
    let t = (0.5 * (a.abs() + (a * a + b * b).sqrt())).sqrt();
    if a >= 0.0 {
        Complex64::new(t, 0.5 * b / t)
    } else {
        Complex64::new(0.5 * b.abs() / t, t.copysign(b))
    }
}

fn quadratic_roots(b: Complex64, c: Complex64) -> [Complex64; 2] {
    // z² + b z + c = 0, the cancellation-free way.
    let disc = csqrt(b * b - c * 4.0);
    let s = if (b.conj() * disc).re >= 0.0 {
        -(b + disc) * 0.5
    } else {
        -(b - disc) * 0.5
    };
    if s.norm_sqr() == 0.0 {
        [Complex64::new(0.0, 0.0); 2]
    } else {
        [s, c / s]
    }
}

/// Closed-form first guesses (Ferrari) for the roots of a monic quartic.
fn ferrari(b: f64, c: f64, d: f64, e: f64) -> [Complex64; 4] {
    let b2 = b * b;
    let p = c - 3.0 * b2 / 8.0;
    let q = d - b * c / 2.0 + b2 * b / 8.0;
    let r = e - b * d / 4.0 + b2 * c / 16.0 - 3.0 * b2 * b2 / 256.0;
    let shift = Complex64::new(-b / 4.0, 0.0);
    let m = largest_real_cubic_root(p, p * p / 4.0 - r, -q * q / 8.0);
    let ys = if m > 0.0 && m.is_finite() {
        let s = (2.0 * m).sqrt();
        let h = q / (2.0 * s);
        let first = quadratic_roots(
            Complex64::new(-s, 0.0),
            Complex64::new(p / 2.0 + m + h, 0.0),
        );
        let second = quadratic_roots(Complex64::new(s, 0.0), Complex64::new(p / 2.0 + m - h, 0.0));
        [first[0], first[1], second[0], second[1]]
    } else {
        // Biquadratic: y⁴ + p y² + r = 0.
        let w = quadratic_roots(Complex64::new(p, 0.0), Complex64::new(r, 0.0));
        let (a, bb) = (csqrt(w[0]), csqrt(w[1]));
        [a, -a, bb, -bb]
    };
    [ys[0] + shift, ys[1] + shift, ys[2] + shift, ys[3] + shift]
}

/// The four roots of a₄λ⁴ + a₃λ³ + a₂λ² + a₁λ + a₀ (coefficients lowest power first, a₄ ≠ 0),
/// sorted by decreasing real part, then decreasing imaginary part. Complex roots come in exact
/// conjugate pairs.
///
/// ```
/// use whipple::advanced::eigen::quartic_roots;
/// // (λ² − 1)(λ² + 4)
/// let roots = quartic_roots(&[-4.0, 0.0, 3.0, 0.0, 1.0])?;
/// assert!((roots[0].re - 1.0).abs() < 1e-15 && (roots[1].im - 2.0).abs() < 1e-15);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn quartic_roots(a: &[f64; 5]) -> Result<[Complex64; 4]> {
    if a.iter().any(|x| !x.is_finite()) || a[4] == 0.0 {
        return Err(Error::NonFinite {
            context: format!(
                "the characteristic polynomial's coefficients ({}): a parameter or the speed is \
                 too large for double precision",
                coefficient_list(a)
            ),
        });
    }
    let monic = [a[0] / a[4], a[1] / a[4], a[2] / a[4], a[3] / a[4], 1.0];
    let mut z = ferrari(monic[3], monic[2], monic[1], monic[0]);
    if z.iter().any(|r| !(r.re.is_finite() && r.im.is_finite())) {
        // Fall back to points on a circle of the Cauchy bound's radius.
        let radius = 1.0 + monic[..4].iter().fold(0.0f64, |m, c| m.max(c.abs()));
        for (k, r) in z.iter_mut().enumerate() {
            *r = crate::math::from_polar(radius, 0.4 + k as f64 * std::f64::consts::FRAC_PI_2);
        }
    }
    // Separate coincident first guesses so that Aberth's corrections stay finite.
    for i in 0..4 {
        for j in 0..i {
            let scale2 = z[i].norm_sqr().max(z[j].norm_sqr()).max(1e-300);
            if (z[i] - z[j]).norm_sqr() <= 1e-20 * scale2 {
                let scale = scale2.sqrt();
                z[i] += Complex64::new(1e-7 * scale, 1e-7 * scale);
            }
        }
    }
    aberth(&monic, &mut z);
    if z.iter().any(|r| !(r.re.is_finite() && r.im.is_finite())) {
        return Err(Error::NonFinite {
            context: format!(
                "the roots of the characteristic polynomial ({}): its coefficients' scales are \
                 too far apart for double precision",
                coefficient_list(a)
            ),
        });
    }
    // Real where the imaginary part is round-off of the largest root.
    let scale = z
        .iter()
        .fold(0.0f64, |m, r| m.max(r.norm_sqr()))
        .sqrt()
        .max(1e-300);
    pair_conjugates(
        &mut z,
        |r| r.im.abs() <= 8.0 * f64::EPSILON * scale,
        Unpaired::Kept,
    );
    refine_real(a, &mut z);
    Ok(z)
}

/// A few real Newton steps on the unscaled coefficients for each real root, each kept only
/// where it lowers |p|: a root far smaller than the others (the capsize root at a speed of
/// 1e16 m/s is 1e32 times smaller than the weave's) is left by the simultaneous iteration at
/// the accuracy of the largest root, and one Newton step on its own gives it to round-off.
fn refine_real(a: &[f64; 5], z: &mut [Complex64; 4]) {
    for root in z.iter_mut().filter(|r| r.im == 0.0) {
        let mut x = root.re;
        let (mut p, mut dp) = horner(a, Complex64::new(x, 0.0));
        for _ in 0..3 {
            if dp.re == 0.0 || p.re == 0.0 {
                break;
            }
            let next = x - p.re / dp.re;
            let (q, dq) = horner(a, Complex64::new(next, 0.0));
            if !(next.is_finite() && q.re.abs() < p.re.abs()) {
                break;
            }
            (x, p, dp) = (next, q, dq);
        }
        root.re = x;
    }
    z.sort_by(|x, y| y.re.total_cmp(&x.re).then(y.im.total_cmp(&x.im)));
}

/// The four eigenvalues of A(v), sorted by decreasing real part.
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical};
/// use whipple::advanced::eigen;
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let lambdas = eigen::eigenvalues(&canonical, 5.0)?;
/// assert!(lambdas.iter().all(|l| l.re < 0.0)); // 5 m/s is in the self-stable range
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn eigenvalues(canonical: &Canonical, speed: f64) -> Result<[Complex64; 4]> {
    // Refuses matrices whose characteristic polynomial double precision cannot form.
    crate::linear::SpeedPolynomials::new(canonical)?;
    certified_roots(&CharacteristicPolynomial::new(canonical), speed)
}

/// An eigenvalue of A(v) and its eigenvector x = [q; λ q] (unit length, largest component real
/// and positive), where (M λ² + v C₁ λ + g K₀ + v² K₂) q = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EigenPair {
    /// λ [1/s].
    pub value: Complex64,
    /// x = [φ, δ, φ̇, δ̇] of the mode.
    pub vector: Vector4<Complex64>,
}

/// Eigenvalues and eigenvectors of A(v), sorted by decreasing real part.
pub fn eigenpairs(canonical: &Canonical, speed: f64) -> Result<[EigenPair; 4]> {
    // Refuses matrices whose characteristic polynomial double precision cannot form.
    crate::linear::SpeedPolynomials::new(canonical)?;
    eigenpairs_with(canonical, &CharacteristicPolynomial::new(canonical), speed)
}

/// [`eigenpairs`] at many speeds: `poly` is `CharacteristicPolynomial::new(canonical)`, and the
/// caller has checked `SpeedPolynomials::new(canonical)` once (as [`eigenpairs`] does on every
/// call), so a batch pays for neither per speed. The same numbers, bit for bit.
///
/// ```
/// use whipple::advanced::eigen::{eigenpairs, eigenpairs_with};
/// use whipple::advanced::linear::{CharacteristicPolynomial, SpeedPolynomials};
/// use whipple::{BenchmarkParameters, Canonical};
/// let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// SpeedPolynomials::new(&c)?;
/// let poly = CharacteristicPolynomial::new(&c);
/// assert_eq!(eigenpairs_with(&c, &poly, 5.0)?, eigenpairs(&c, 5.0)?);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn eigenpairs_with(
    canonical: &Canonical,
    poly: &CharacteristicPolynomial,
    speed: f64,
) -> Result<[EigenPair; 4]> {
    let values = certified_roots(poly, speed)?;
    Ok(values.map(|value| EigenPair {
        value,
        vector: eigenvector(canonical, speed, value),
    }))
}

/// The eigenvalues of [`eigenpairs_with`] alone (its checks are the caller's; the same
/// numbers, in the same order, as [`eigenvalues`]), for a batch that computes the vectors
/// later ([`eigenvector`]).
pub fn eigenvalues_with(poly: &CharacteristicPolynomial, speed: f64) -> Result<[Complex64; 4]> {
    certified_roots(poly, speed)
}

/// The eigenvector of A(v) for its eigenvalue `value` at `speed`, as [`eigenpairs`] gives it
/// (x = [q; λ q], unit length, largest component real and positive), bit for bit.
///
/// ```
/// use whipple::advanced::eigen::{eigenpairs, eigenvector};
/// use whipple::{BenchmarkParameters, Canonical};
/// let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let pairs = eigenpairs(&c, 5.0)?;
/// assert_eq!(eigenvector(&c, 5.0, pairs[2].value), pairs[2].vector);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn eigenvector(canonical: &Canonical, speed: f64, value: Complex64) -> Vector4<Complex64> {
    let k = canonical.k0 * canonical.g + canonical.k2 * (speed * speed);
    let c = canonical.c1 * speed;
    second_order_eigenvector(&canonical.m, &c, &k, value)
}

/// The eigenvector x = [q; λ q] of the second-order system M q̈ + C q̇ + K q = 0 for its
/// eigenvalue `value`: q a null vector of M λ² + C λ + K, normalized as [`eigenvector`]
/// documents (the open loop's and the closed loop's vectors, one home).
pub(crate) fn second_order_eigenvector(
    m: &Matrix2<f64>,
    c: &Matrix2<f64>,
    k: &Matrix2<f64>,
    value: Complex64,
) -> Vector4<Complex64> {
    let at = |i: usize, j: usize| value * value * m[(i, j)] + value * c[(i, j)] + k[(i, j)];
    // A null vector of the 2×2 matrix P(λ): orthogonal to its larger row.
    let rows = [(at(0, 0), at(0, 1)), (at(1, 0), at(1, 1))];
    let (r0, r1) = if rows[0].0.norm_sqr() + rows[0].1.norm_sqr()
        >= rows[1].0.norm_sqr() + rows[1].1.norm_sqr()
    {
        rows[0]
    } else {
        rows[1]
    };
    let q = if crate::math::norm(r0) == 0.0 && crate::math::norm(r1) == 0.0 {
        Vector2::new(Complex64::new(1.0, 0.0), Complex64::new(0.0, 0.0))
    } else {
        Vector2::new(-r1, r0)
    };
    let mut x = Vector4::new(q[0], q[1], value * q[0], value * q[1]);
    // Squared moduli (no `hypot`: this runs for every speed of a sweep), rescaled first by
    // the largest |component| so that they can neither overflow nor underflow.
    let scale = x
        .iter()
        .map(|z| z.re.abs().max(z.im.abs()))
        .fold(0.0, f64::max);
    if scale > 0.0 && scale.is_finite() {
        x = x.map(|z| z.unscale(scale));
        let (imax, _) = x.iter().enumerate().fold((0, 0.0), |(bi, bn), (i, z)| {
            let n = z.norm_sqr();
            if n > bn { (i, n) } else { (bi, bn) }
        });
        let pivot = x[imax];
        let norm = x.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        let phase = pivot.conj() / (pivot.norm_sqr().sqrt() * norm);
        x *= phase;
    }
    x
}
