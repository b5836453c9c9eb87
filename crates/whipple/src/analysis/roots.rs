//! Certified real roots of low-degree real polynomials whose coefficients are known only to
//! within stated bounds, and the one Aberth–Ehrlich iteration and conjugate pairing that every
//! polynomial of the crate (this module's and the eigenvalues' quartic) is solved with.
//!
//! # The method
//!
//! A polynomial q(x) = Σ cₖ xᵏ of degree n ≤ [`MAX_DEGREE`] is given by computed coefficients ĉₖ
//! and bounds eₖ with |cₖ − ĉₖ| ≤ eₖ for the true coefficients cₖ (see
//! [`crate::linear::SpeedPolynomials`] for where the bounds come from). Approximations z₁ … zₙ of
//! all n complex roots come from a closed form (n ≤ 2) or from bounded Aberth–Ehrlich
//! iterations (n > 2); *nothing below depends on how good they are*. They are then certified by
//! the inclusion theorem that goes back to Gerschgorin: with the Weierstrass corrections
//! wᵢ = q(zᵢ) / (cₙ Πⱼ≠ᵢ (zᵢ − zⱼ)), the zeros of q are the eigenvalues of diag(zᵢ) − 𝟙wᵀ
//! (Lagrange interpolation at the zᵢ), so by Gerschgorin's theorem applied to its columns
//! every zero lies in the union of the discs |x − zᵢ| ≤ n |wᵢ| (Smith 1970, J. ACM 17:661), and a
//! connected component of m discs holds exactly m zeros. Each |wᵢ| is bounded from above for
//! *every* polynomial within the coefficient bounds (|q(zᵢ)| by the computed value plus a
//! rigorous Horner error bound plus Σ eₖ|zᵢ|ᵏ; the leading coefficient by |ĉₙ| − eₙ), so:
//!
//! - a component of one disc centred on the real axis holds exactly one zero, and it is real
//!   (its conjugate lies in the same disc): a certified simple real root with an enclosure;
//! - a component that misses the real axis holds no real zero;
//! - a component of m ≥ 2 discs that meets the real axis (a near-multiple root, a
//!   near-tangency) is reported as an unresolved [`RealRoot::Cluster`] with its real extent
//!   and m: the number of real zeros in it cannot be told apart in double precision.
//!
//! Nothing is sampled, so no root can be missed however close roots lie or however large
//! they are. What is certified is the statement for the true coefficients within the bounds.

use crate::error::{Error, Result};

/// A complex number of f64.
type Complex64 = nalgebra::Complex<f64>;

/// The largest degree [`real_roots`] handles.
pub(crate) const MAX_DEGREE: usize = 10;

/// Unit round-off of f64, 2⁻⁵³.
pub(crate) const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// A real polynomial Σ `coefficients[k]` xᵏ (lowest power first) whose true coefficients lie
/// within `bounds[k]` of the stored ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundedPolynomial<const N: usize> {
    /// The computed coefficients, lowest power first.
    pub coefficients: [f64; N],
    /// Bounds on their errors (≥ 0; 0 where a coefficient is exact).
    pub bounds: [f64; N],
}

impl<const N: usize> BoundedPolynomial<N> {
    /// A polynomial with exact coefficients.
    pub fn exact(coefficients: [f64; N]) -> Self {
        BoundedPolynomial {
            coefficients,
            bounds: [0.0; N],
        }
    }

    /// The value at x (Horner, real arithmetic).
    #[inline]
    pub fn eval(&self, x: f64) -> f64 {
        horner_real(&self.coefficients, x)
    }

    /// The value at x and a rigorous bound on its distance from the value of any polynomial
    /// within the coefficient bounds (round-off of Horner's rule included).
    #[inline]
    pub fn eval_with_bound(&self, x: f64) -> (f64, f64) {
        let ax = x.abs();
        let mut p = 0.0;
        let mut size = 0.0;
        let mut slack = 0.0;
        for k in (0..N).rev() {
            p = p * x + self.coefficients[k];
            size = size * ax + self.coefficients[k].abs();
            slack = slack * ax + self.bounds[k];
        }
        let n = N as f64;
        (
            p,
            slack * (1.0 + 4.0 * n * UNIT_ROUNDOFF) + 4.0 * n * UNIT_ROUNDOFF * size + TINY,
        )
    }

    /// The sign of the value at x when round-off and the coefficient bounds cannot change it.
    pub fn certain_sign(&self, x: f64) -> Option<f64> {
        let (p, bound) = self.eval_with_bound(x);
        if p.abs() > bound {
            Some(p.signum())
        } else {
            None
        }
    }
}

/// An absolute allowance for gradual underflow in one evaluation (far below any value that
/// matters; see the module documentation).
const TINY: f64 = 1e-300;

/// A real root, certified.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RealRoot {
    /// Exactly one real zero, simple, in [lo, hi]; `value` is the polished approximation.
    Simple {
        /// The polished root.
        value: f64,
        /// Lower end of the enclosure.
        lo: f64,
        /// Upper end of the enclosure.
        hi: f64,
    },
    /// `count` zeros (with multiplicity) in a cluster whose real extent is [lo, hi]; how many
    /// of them are real is not decided (count mod 2 of them at least).
    Cluster {
        /// Lower end of the cluster's real extent.
        lo: f64,
        /// Upper end of the cluster's real extent.
        hi: f64,
        /// Zeros in the cluster, with multiplicity.
        count: usize,
    },
}

impl RealRoot {
    /// The enclosure [lo, hi].
    pub fn enclosure(&self) -> (f64, f64) {
        match *self {
            RealRoot::Simple { lo, hi, .. } | RealRoot::Cluster { lo, hi, .. } => (lo, hi),
        }
    }

    /// The polished value, or the middle of a cluster.
    pub fn value(&self) -> f64 {
        match *self {
            RealRoot::Simple { value, .. } => value,
            RealRoot::Cluster { lo, hi, .. } => 0.5 * (lo + hi),
        }
    }
}

/// The certified real roots of a polynomial, sorted by their enclosures' lower ends; fixed
/// size, no allocation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RealRoots {
    roots: [RealRoot; MAX_DEGREE],
    len: usize,
    /// The polynomial's degree (the highest power whose coefficient may be non-zero), or `None`
    /// for the zero polynomial.
    pub degree: Option<usize>,
    /// The sign of the leading coefficient (certain).
    pub leading_sign: f64,
    /// Multiplicity of an exact root at 0 (coefficients that are exactly zero with zero bound).
    pub zero_multiplicity: usize,
    /// The roots are certified for |x| < `horizon` only (+∞ unless the leading coefficient's
    /// sign is lost to round-off: then a root may lie anywhere beyond it, or nowhere).
    pub horizon: f64,
    /// With a finite horizon: the sign just right of zero (that of the lowest non-zero
    /// coefficient).
    pub near_zero_sign: f64,
}

impl RealRoots {
    fn empty() -> Self {
        RealRoots {
            roots: [RealRoot::Cluster {
                lo: 0.0,
                hi: 0.0,
                count: 0,
            }; MAX_DEGREE],
            len: 0,
            degree: None,
            leading_sign: 0.0,
            zero_multiplicity: 0,
            horizon: f64::INFINITY,
            near_zero_sign: 0.0,
        }
    }

    fn push(&mut self, root: RealRoot) {
        if self.len < MAX_DEGREE {
            self.roots[self.len] = root;
            self.len += 1;
        }
    }

    /// The roots, sorted.
    pub fn as_slice(&self) -> &[RealRoot] {
        &self.roots[..self.len]
    }

    fn sign_below_horizon(&self, x: f64) -> Option<f64> {
        if x.abs() >= self.horizon || (x == 0.0 && self.zero_multiplicity > 0) {
            return None;
        }
        let mut sign = self.near_zero_sign;
        if x < 0.0 && self.zero_multiplicity % 2 == 1 {
            sign = -sign;
        }
        for root in self.as_slice() {
            let (lo, hi) = root.enclosure();
            if x >= lo && x <= hi {
                return None;
            }
            let between = if x > 0.0 {
                hi < x && lo > 0.0
            } else {
                lo > x && hi < 0.0
            };
            let count = match root {
                RealRoot::Simple { .. } => 1,
                RealRoot::Cluster { count, .. } => *count,
            };
            if between && count % 2 == 1 {
                sign = -sign;
            }
        }
        Some(sign)
    }

    /// True for the zero polynomial.
    pub fn is_zero_polynomial(&self) -> bool {
        self.degree.is_none()
    }

    /// The sign of the polynomial at x, from the root structure alone: certain for any x outside
    /// every enclosure (and not an exact root at 0), `None` inside one or for the zero
    /// polynomial.
    pub fn sign_at(&self, x: f64) -> Option<f64> {
        self.degree?;
        if self.horizon.is_finite() {
            return self.sign_below_horizon(x);
        }
        let mut sign = self.leading_sign;
        if self.zero_multiplicity > 0 {
            if x == 0.0 {
                return None;
            }
            if x < 0.0 && self.zero_multiplicity % 2 == 1 {
                sign = -sign;
            }
        }
        for root in self.as_slice() {
            let (lo, hi) = root.enclosure();
            if x >= lo && x <= hi {
                return None;
            }
            if x < lo {
                let count = match root {
                    RealRoot::Simple { .. } => 1,
                    RealRoot::Cluster { count, .. } => *count,
                };
                if count % 2 == 1 {
                    sign = -sign;
                }
            }
        }
        Some(sign)
    }
}

/// Bound on the Aberth–Ehrlich iterations (each converges cubically near a simple root; near
/// a double root linearly, where the accuracy is limited by the problem itself, and the
/// iteration stops when its corrections stop shrinking).
const MAX_ABERTH_ITERATIONS: usize = 80;

/// Σ `c[k]` xᵏ at a real x (lowest power first; 0 for no coefficients) by Horner's scheme.
#[inline]
pub(crate) fn horner_real(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * x + ck)
}

/// p(z) and p'(z) of Σ `c[k]` zᵏ (lowest power first, at least one coefficient) by Horner's
/// scheme.
pub(crate) fn horner(c: &[f64], z: Complex64) -> (Complex64, Complex64) {
    let n = c.len();
    let mut p = Complex64::new(c[n - 1], 0.0);
    let mut dp = Complex64::new(0.0, 0.0);
    for k in (0..n - 1).rev() {
        dp = dp * z + p;
        p = p * z + c[k];
    }
    (p, dp)
}

/// Aberth–Ehrlich iterations on all the roots `z` of Σ `c[k]` xᵏ (lowest power first,
/// `z.len()` = the degree) from the approximations in `z`, until the corrections reach
/// round-off, a bounded number of times.
///
/// Near a simple root the iteration converges cubically: after a relative correction δ the
/// remaining error is about δ³ / g², g being the root's relative distance to its nearest
/// neighbour. So the iteration stops as soon as that estimate falls below the round-off ε for
/// every root; near a (nearly) double root, where convergence is only linear, it goes on until
/// the corrections stop shrinking.
pub(crate) fn aberth(c: &[f64], z: &mut [Complex64]) {
    let mut previous = f64::INFINITY;
    for _ in 0..MAX_ABERTH_ITERATIONS {
        let mut largest = 0.0f64;
        let mut converged = true;
        for i in 0..z.len() {
            let (p, dp) = horner(c, z[i]);
            if p.norm_sqr() == 0.0 {
                continue;
            }
            let newton = p / dp;
            let mut repulsion = Complex64::new(0.0, 0.0);
            let mut gap2 = f64::INFINITY;
            for (j, zj) in z.iter().enumerate() {
                if j != i {
                    let d = z[i] - zj;
                    repulsion += d.inv();
                    gap2 = gap2.min(d.norm_sqr());
                }
            }
            let step = newton / (Complex64::new(1.0, 0.0) - newton * repulsion);
            if !(step.re.is_finite() && step.im.is_finite()) {
                continue;
            }
            z[i] -= step;
            // Squared relative sizes, to stay clear of the slow `hypot`.
            let size2 = z[i].norm_sqr().max(f64::MIN_POSITIVE);
            let delta2 = step.norm_sqr() / size2;
            let gap2 = gap2 / size2;
            largest = largest.max(delta2.sqrt());
            // δ > 4ε and δ³ > ε g², compared squared.
            if delta2 > 16.0 * f64::EPSILON * f64::EPSILON
                && delta2 * delta2 * delta2 > f64::EPSILON * f64::EPSILON * gap2 * gap2
            {
                converged = false;
            }
        }
        if converged || (largest >= previous && largest < 1e-9) {
            break;
        }
        previous = largest;
    }
}

/// What [`pair_conjugates`] does with an approximation left without a conjugate partner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Unpaired {
    /// Made real: the certification's discs must be symmetric about the real axis.
    MadeReal,
    /// Kept as it is: near a double root an approximation a little off the axis beside a real
    /// one keeps |p′| away from zero, which the eigenvalues' own error bound divides by.
    Kept,
}

/// The roots of a real polynomial are real or come in conjugate pairs, and its computed
/// approximations are made so: those `is_real` calls real lose their imaginary part; each of
/// positive imaginary part is paired with the nearest unpaired one of negative imaginary part
/// (the pair becomes their conjugate mean); any left unpaired is treated as `unpaired` says.
pub(crate) fn pair_conjugates(
    z: &mut [Complex64],
    is_real: impl Fn(Complex64) -> bool,
    unpaired: Unpaired,
) {
    for zi in z.iter_mut() {
        if is_real(*zi) {
            zi.im = 0.0;
        }
    }
    let n = z.len();
    let mut paired = [false; MAX_DEGREE];
    for i in 0..n {
        if paired[i] || z[i].im <= 0.0 {
            continue;
        }
        let partner = (0..n)
            .filter(|&j| j != i && !paired[j] && z[j].im < 0.0)
            .min_by(|&j, &k| {
                let dj = (z[j] - z[i].conj()).norm_sqr();
                let dk = (z[k] - z[i].conj()).norm_sqr();
                dj.total_cmp(&dk)
            });
        if let Some(j) = partner {
            let re = 0.5 * (z[i].re + z[j].re);
            let im = 0.5 * (z[i].im - z[j].im);
            z[i] = Complex64::new(re, im);
            z[j] = Complex64::new(re, -im);
            paired[i] = true;
            paired[j] = true;
        }
    }
    for (zi, &done) in z.iter_mut().zip(&paired) {
        if !done && unpaired == Unpaired::MadeReal {
            zi.im = 0.0;
        }
    }
}

/// Approximations of all roots of the polynomial with coefficients `c` (lowest first,
/// c[n] ≠ 0): in closed form up to degree 2, by [`aberth`] from a circle beyond.
pub(crate) fn approximate(c: &[f64], z: &mut [Complex64]) {
    let n = c.len() - 1;
    match n {
        0 => {}
        1 => z[0] = Complex64::new(-c[0] / c[1], 0.0),
        2 => {
            let (a, b, cc) = (c[2], c[1], c[0]);
            let disc = b * b - 4.0 * a * cc;
            if disc >= 0.0 {
                let s = -0.5 * (b + disc.sqrt().copysign(b));
                if s == 0.0 {
                    z[0] = Complex64::new(0.0, 0.0);
                    z[1] = Complex64::new(0.0, 0.0);
                } else {
                    z[0] = Complex64::new(s / a, 0.0);
                    z[1] = Complex64::new(cc / s, 0.0);
                }
            } else {
                let re = -b / (2.0 * a);
                let im = (-disc).sqrt() / (2.0 * a).abs();
                z[0] = Complex64::new(re, im);
                z[1] = Complex64::new(re, -im);
            }
        }
        _ => {
            // Initial points on a circle of the Fujiwara bound's radius (halved, as its roots'
            // sizes average well below it), off the axes.
            let lead = c[n];
            let mut radius = 0.0f64;
            for (k, &ck) in c.iter().enumerate().take(n) {
                let r = crate::math::powf((ck / lead).abs(), 1.0 / (n - k) as f64);
                radius = radius.max(r);
            }
            if !(radius > 0.0 && radius.is_finite()) {
                radius = 1.0;
            }
            for (k, zk) in z.iter_mut().enumerate().take(n) {
                let angle = 0.4 + std::f64::consts::TAU * k as f64 / n as f64;
                *zk = Complex64::new(
                    radius * crate::math::cos(angle),
                    radius * crate::math::sin(angle),
                );
            }
            aberth(c, &mut z[..n]);
        }
    }
}

/// Makes near-real approximations real and pairs the others as exact conjugates
/// ([`pair_conjugates`]), so that the discs are symmetric about the real axis, and separates
/// coincident approximations (their discs' radii would be infinite).
fn tidy(z: &mut [Complex64]) {
    pair_conjugates(z, |x| x.im.abs() <= 1e-9 * x.re.abs(), Unpaired::MadeReal);
    for i in 0..z.len() {
        for j in 0..i {
            if z[i] == z[j] {
                let s = z[i].re.abs().max(z[i].im.abs()).max(f64::MIN_POSITIVE);
                z[i].re += 1e-12 * s;
            }
        }
    }
}

/// Newton steps on a real simple root inside its enclosure (stops when the step reaches
/// round-off, bounded).
fn polish_real(c: &[f64], mut x: f64, lo: f64, hi: f64) -> f64 {
    for _ in 0..8 {
        let n = c.len();
        let mut p = c[n - 1];
        let mut dp = 0.0;
        for k in (0..n - 1).rev() {
            dp = dp * x + p;
            p = p * x + c[k];
        }
        if dp == 0.0 || p == 0.0 {
            break;
        }
        let step = p / dp;
        let next = x - step;
        if !next.is_finite() || next < lo || next > hi {
            break;
        }
        let done = step.abs() <= 2.0 * f64::EPSILON * next.abs();
        x = next;
        if done {
            break;
        }
    }
    x.clamp(lo, hi)
}

/// Certified real roots of Σ c[k] xᵏ (degree d = c.len() − 1 ≥ 1, |c[d]| > e[d], c[0] not
/// exactly zero), sorted; returns how many were written.
fn certify(c: &[f64], e: &[f64], roots: &mut [RealRoot; MAX_DEGREE]) -> usize {
    let d = c.len() - 1;
    let mut z = [Complex64::new(0.0, 0.0); MAX_DEGREE];
    approximate(c, &mut z[..d]);
    tidy(&mut z[..d]);
    // Upper bounds on the disc radii n |wᵢ|.
    let lead_lower = (c[d].abs() - e[d]) * (1.0 - 2.0 * UNIT_ROUNDOFF);
    let mut radius = [0.0f64; MAX_DEGREE];
    for i in 0..d {
        let (p, _) = horner(c, z[i]);
        let az = crate::math::norm(z[i]);
        // Σ|cₖ||z|ᵏ, for the bound on Horner's round-off.
        let size = c.iter().rev().fold(0.0, |acc, &ck| acc * az + ck.abs());
        let slack = e.iter().rev().fold(0.0, |acc, &ek| acc * az + ek);
        let eval_error = 8.0 * (d + 1) as f64 * UNIT_ROUNDOFF * size;
        let numerator = (crate::math::norm(p) + eval_error + slack) * (1.0 + 8.0 * UNIT_ROUNDOFF)
            + TINY * (1.0 + az);
        let mut denominator = lead_lower;
        for j in 0..d {
            if j != i {
                denominator *= crate::math::norm(z[i] - z[j]);
            }
        }
        denominator *= 1.0 - 4.0 * (d + 1) as f64 * UNIT_ROUNDOFF;
        let r = d as f64 * numerator / denominator * (1.0 + 4.0 * UNIT_ROUNDOFF);
        radius[i] = if r.is_finite() && denominator > 0.0 {
            r
        } else {
            f64::INFINITY
        };
    }
    // Connected components (union of overlapping discs).
    let mut component = [0usize; MAX_DEGREE];
    for (i, ci) in component.iter_mut().enumerate().take(d) {
        *ci = i;
    }
    loop {
        let mut changed = false;
        for i in 0..d {
            for j in 0..i {
                let gap = crate::math::norm(z[i] - z[j]);
                if gap <= radius[i] + radius[j] && component[i] != component[j] {
                    let (a, b) = (
                        component[i].min(component[j]),
                        component[i].max(component[j]),
                    );
                    for ck in component.iter_mut().take(d) {
                        if *ck == b {
                            *ck = a;
                        }
                    }
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let mut count = 0;
    for root in 0..d {
        let members = (0..d).filter(|&i| component[i] == root);
        let size = members.clone().count();
        if size == 0 {
            continue;
        }
        // The component's extent on the real axis.
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for i in members.clone() {
            let (x, y, r) = (z[i].re, z[i].im.abs(), radius[i]);
            if y <= r {
                let half = if r.is_finite() {
                    ((r - y) * (r + y)).sqrt()
                } else {
                    f64::INFINITY
                };
                lo = lo.min(x - half);
                hi = hi.max(x + half);
            }
        }
        if lo > hi {
            continue; // misses the real axis: no real zero
        }
        if size == 1 {
            let i = members.clone().next().unwrap_or(0);
            if z[i].im == 0.0 {
                let value = polish_real(c, z[i].re, lo, hi);
                roots[count] = RealRoot::Simple { value, lo, hi };
                count += 1;
                continue;
            }
        }
        roots[count] = RealRoot::Cluster {
            lo,
            hi,
            count: size,
        };
        count += 1;
    }
    roots[..count].sort_by(|a, b| a.enclosure().0.total_cmp(&b.enclosure().0));
    count
}

/// Every real root of the polynomial, certified (see the module documentation).
///
/// Errors with [`Error::AccuracyLost`] when the leading coefficient's sign is not certain (the
/// degree itself is then unknown) or a value overflows; `what` names the polynomial in the
/// message.
///
/// ```
/// use whipple::advanced::roots::{real_roots, BoundedPolynomial, RealRoot};
/// // (x - 1)(x - 2)(x² + 1) = x⁴ - 3x³ + 3x² - 3x + 2
/// let q = BoundedPolynomial::exact([2.0, -3.0, 3.0, -3.0, 1.0]);
/// let roots = real_roots(&q, "example")?;
/// assert_eq!(roots.as_slice().len(), 2);
/// let RealRoot::Simple { value, lo, hi } = roots.as_slice()[1] else { panic!() };
/// assert!(lo <= 2.0 && 2.0 <= hi && (value - 2.0).abs() < 1e-15);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn real_roots<const N: usize>(q: &BoundedPolynomial<N>, what: &str) -> Result<RealRoots> {
    let mut out = RealRoots::empty();
    if q.coefficients
        .iter()
        .chain(q.bounds.iter())
        .any(|x| !x.is_finite())
    {
        return Err(Error::AccuracyLost {
            quantity: what.to_string(),
            reason: "a coefficient overflowed".into(),
        });
    }
    let Some(n) = (0..N)
        .rev()
        .find(|&k| q.coefficients[k] != 0.0 || q.bounds[k] != 0.0)
    else {
        return Ok(out); // the zero polynomial
    };
    if n > MAX_DEGREE {
        return Err(Error::InvalidArgument {
            what: "polynomial",
            rule: format!("degree {n} is above the largest handled, {MAX_DEGREE}"),
        });
    }
    let lead = q.coefficients[n];
    // Exact roots at zero.
    let m = (0..=n)
        .find(|&k| q.coefficients[k] != 0.0 || q.bounds[k] != 0.0)
        .unwrap_or(0);
    out.degree = Some(n);
    out.zero_multiplicity = m;
    let d = n - m;
    let c = &q.coefficients[m..=n];
    let e = &q.bounds[m..=n];
    let mut roots = [RealRoot::Cluster {
        lo: 0.0,
        hi: 0.0,
        count: 0,
    }; MAX_DEGREE];
    if lead.abs() > q.bounds[n] {
        out.leading_sign = lead.signum();
        let count = if d == 0 { 0 } else { certify(c, e, &mut roots) };
        for r in &roots[..count] {
            out.push(*r);
        }
        return Ok(out);
    }
    // The leading coefficient's sign is lost to round-off, so a root may lie anywhere beyond
    // some size (or nowhere): certify the reversed polynomial yᵈ q(1/y), whose roots near
    // y = 0 are those large ones, and keep the answer below that horizon.
    if c[0].abs() <= e[0] {
        return Err(Error::AccuracyLost {
            quantity: what.to_string(),
            reason: format!(
                "both its leading coefficient ({lead:e}, round-off bound {:e}) and its lowest \
                 ({:e}, bound {:e}) are lost to round-off",
                q.bounds[n], c[0], e[0]
            ),
        });
    }
    let mut rc = [0.0; MAX_DEGREE + 1];
    let mut re = [0.0; MAX_DEGREE + 1];
    for k in 0..=d {
        rc[k] = c[d - k];
        re[k] = e[d - k];
    }
    let count = certify(&rc[..=d], &re[..=d], &mut roots);
    out.leading_sign = 0.0;
    out.near_zero_sign = c[0].signum();
    let mut horizon = f64::INFINITY;
    let mut mapped = [RealRoot::Cluster {
        lo: 0.0,
        hi: 0.0,
        count: 0,
    }; MAX_DEGREE];
    let mut kept = 0;
    for r in &roots[..count] {
        let (lo, hi) = r.enclosure();
        if lo <= 0.0 && hi >= 0.0 {
            horizon = horizon.min(1.0 / lo.abs().max(hi.abs()));
            continue;
        }
        let (a, b) = (
            (1.0 / hi) * (1.0 - 2.0 * UNIT_ROUNDOFF),
            (1.0 / lo) * (1.0 + 2.0 * UNIT_ROUNDOFF),
        );
        let (a, b) = (a.min(b), a.max(b));
        mapped[kept] = match *r {
            RealRoot::Simple { value, .. } => RealRoot::Simple {
                value: (1.0 / value).clamp(a, b),
                lo: a,
                hi: b,
            },
            RealRoot::Cluster { count, .. } => RealRoot::Cluster {
                lo: a,
                hi: b,
                count,
            },
        };
        kept += 1;
    }
    out.horizon = horizon * (1.0 - 4.0 * UNIT_ROUNDOFF);
    let mapped = &mut mapped[..kept];
    mapped.sort_by(|a, b| a.enclosure().0.total_cmp(&b.enclosure().0));
    for r in mapped.iter() {
        if r.enclosure().1 < out.horizon && r.enclosure().0 > -out.horizon {
            out.push(*r);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn simple(roots: &RealRoots) -> Vec<f64> {
        roots
            .as_slice()
            .iter()
            .map(|r| match r {
                RealRoot::Simple { value, .. } => *value,
                RealRoot::Cluster { .. } => f64::NAN,
            })
            .collect()
    }

    /// Roots 1e-6 apart and four orders of magnitude apart are all found, each in its own
    /// enclosure (a grid scan of a few thousand cells over [0, 1e4] misses the close pair).
    #[test]
    fn close_and_distant_roots_are_all_certified() -> Result<()> {
        // (x - 1)(x - 1 - 1e-6)(x - 1e4)(x + 3)
        let r = [1.0, 1.0 + 1e-6, 1e4, -3.0];
        let mut c = [0.0f64; 5];
        c[0] = 1.0;
        for (deg, &root) in r.iter().enumerate() {
            for k in (0..=deg).rev() {
                c[k + 1] += c[k];
                c[k] *= -root;
            }
        }
        let roots = real_roots(&BoundedPolynomial::exact(c), "test")?;
        let found = simple(&roots);
        assert_eq!(found.len(), 4, "{roots:?}");
        let mut want = r.to_vec();
        want.sort_by(f64::total_cmp);
        for (f, w) in found.iter().zip(&want) {
            assert!((f - w).abs() <= 1e-9 * w.abs().max(1.0), "{found:?}");
        }
        Ok(())
    }

    /// A double root is a cluster, never two roots or none; complex roots are no real roots.
    #[test]
    fn a_double_root_is_an_unresolved_cluster() -> Result<()> {
        // (x - 2)² (x² + 1)
        let q = BoundedPolynomial::exact([4.0, -4.0, 5.0, -4.0, 1.0]);
        let roots = real_roots(&q, "test")?;
        assert_eq!(roots.as_slice().len(), 1);
        assert!(matches!(
            roots.as_slice()[0],
            RealRoot::Cluster { count: 2, lo, hi } if lo <= 2.0 && 2.0 <= hi
        ));
        let none = real_roots(&BoundedPolynomial::exact([1.0, 0.0, 1.0]), "test")?;
        assert!(none.as_slice().is_empty());
        assert_eq!(none.sign_at(0.3), Some(1.0));
        Ok(())
    }

    /// Coefficient bounds widen the enclosures; a leading coefficient within its bound is
    /// refused rather than guessed.
    #[test]
    fn coefficient_bounds_are_respected() -> Result<()> {
        let q = BoundedPolynomial {
            coefficients: [-2.0, 0.0, 1.0],
            bounds: [1e-6, 0.0, 0.0],
        };
        let roots = real_roots(&q, "test")?;
        let RealRoot::Simple { lo, hi, .. } = roots.as_slice()[1] else {
            panic!("{roots:?}")
        };
        // x² = 2 ± 1e-6 moves the root by ±3.5e-7.
        assert!(lo <= (2.0f64 - 1e-6).sqrt() && hi >= (2.0f64 + 1e-6).sqrt());
        // A leading coefficient within its bound: the root at 2 is certified, and beyond the
        // horizon (about 1e19, where the uncertain term could matter) nothing is claimed.
        let uncertain = BoundedPolynomial {
            coefficients: [-2.0, 1.0, 1e-20],
            bounds: [0.0, 0.0, 1e-19],
        };
        let roots = real_roots(&uncertain, "test")?;
        assert_eq!(roots.as_slice().len(), 1);
        assert!((roots.as_slice()[0].value() - 2.0).abs() < 1e-15);
        assert!(roots.horizon > 1e18 && roots.horizon < 1e20, "{roots:?}");
        assert_eq!(roots.sign_at(1.0), Some(-1.0));
        assert_eq!(roots.sign_at(3.0), Some(1.0));
        assert_eq!(roots.sign_at(1e21), None);
        let lost = BoundedPolynomial {
            coefficients: [1e-20, 1.0, 1e-20],
            bounds: [1e-19, 0.0, 1e-19],
        };
        assert!(matches!(
            real_roots(&lost, "test"),
            Err(Error::AccuracyLost { .. })
        ));
        Ok(())
    }

    #[test]
    fn signs_follow_from_the_roots() -> Result<()> {
        // x (x - 1)(x + 2) = x³ + x² - 2x
        let roots = real_roots(&BoundedPolynomial::exact([0.0, -2.0, 1.0, 1.0]), "test")?;
        assert_eq!(roots.zero_multiplicity, 1);
        assert_eq!(roots.sign_at(0.5), Some(-1.0));
        assert_eq!(roots.sign_at(2.0), Some(1.0));
        assert_eq!(roots.sign_at(-1.0), Some(1.0));
        assert_eq!(roots.sign_at(-3.0), Some(-1.0));
        Ok(())
    }
}
