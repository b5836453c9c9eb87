//! Critical speeds and self-stable speed ranges, found on the characteristic polynomial's
//! coefficients (smooth polynomials in v) rather than on tracked eigenvalues, so that each is
//! located to round-off.
//!
//! With p(λ) = a₄λ⁴ + a₃λ³ + a₂λ² + a₁λ + a₀ and a₄ = det M > 0, all four eigenvalues have
//! negative real parts exactly when a₀, a₁, a₃ and the Hurwitz determinant
//! Δ₃ = a₃a₂a₁ − a₄a₁² − a₀a₃² are positive (Routh–Hurwitz). A real eigenvalue crosses zero where
//! a₀ = 0 (capsize), a complex pair crosses the imaginary axis where Δ₃ = 0 (weave), and two real
//! eigenvalues meet where the discriminant vanishes (the double root where the weave is born).

use serde::Serialize;

use super::eigen::{quartic_roots, Complex64};
use super::roots::all_roots;
use crate::error::{Error, Result};
use crate::linear::{discriminant, hurwitz_delta3, Canonical, CharacteristicPolynomial};

/// The critical speeds of a bicycle within a speed range. `None` where no such speed lies in the
/// range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalSpeeds {
    /// The range searched [m/s].
    pub range: (f64, f64),
    /// v_d: the lowest speed where two real eigenvalues meet and leave as a complex (weave) pair
    /// [m/s].
    pub double_root_speed: Option<f64>,
    /// The double eigenvalue at v_d [1/s].
    pub double_root_eigenvalue: Option<f64>,
    /// v_w: the lowest speed where a complex (weave) pair crosses into the left half plane as
    /// speed rises [m/s].
    pub weave_speed: Option<f64>,
    /// The weave's angular frequency at v_w, |Im λ| [rad/s].
    pub weave_frequency: Option<f64>,
    /// v_c: the lowest speed where a real (capsize) eigenvalue crosses from negative to
    /// positive as speed rises [m/s].
    pub capsize_speed: Option<f64>,
    /// Every interval of speeds in the range where all eigenvalues have negative real parts,
    /// [lo, hi] in increasing order; empty when there is none.
    pub stable_speed_ranges: Vec<(f64, f64)>,
}

/// How finely the range is scanned for sign changes before Brent refines each one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchParams {
    /// Number of grid intervals over the range (default 4000).
    pub intervals: usize,
}

impl Default for SearchParams {
    fn default() -> Self {
        SearchParams { intervals: 4000 }
    }
}

fn check_range(lo: f64, hi: f64) -> Result<()> {
    if !(lo.is_finite() && hi.is_finite()) || lo >= hi {
        return Err(Error::InvalidArgument {
            what: "range",
            rule: format!("needs finite LO < HI, got {lo}:{hi}"),
        });
    }
    Ok(())
}

/// Number of eigenvalues with positive real part, on either side of v.
fn unstable_count(poly: &CharacteristicPolynomial, v: f64) -> Result<usize> {
    Ok(quartic_roots(&poly.at_speed(v))?
        .iter()
        .filter(|l| l.re > 0.0)
        .count())
}

fn real_count(roots: &[Complex64; 4]) -> usize {
    roots.iter().filter(|l| l.im == 0.0).count()
}

/// A small step in speed for looking either side of a crossing.
fn side_step(v: f64) -> f64 {
    1e-6 * v.abs().max(1.0)
}

/// The critical speeds of a bicycle in [lo, hi] (m/s), with default search settings.
///
/// ```
/// use whipple::{BenchmarkParameters, linear::Canonical, analysis::stability};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let speeds = stability::critical_speeds(&canonical, 0.0, 10.0)?;
/// assert!((speeds.weave_speed.unwrap() - 4.29238253634111).abs() < 1e-12);
/// assert!((speeds.capsize_speed.unwrap() - 6.02426201538837).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn critical_speeds(canonical: &Canonical, lo: f64, hi: f64) -> Result<CriticalSpeeds> {
    critical_speeds_with(canonical, lo, hi, SearchParams::default())
}

/// [`critical_speeds`] with explicit search settings.
pub fn critical_speeds_with(
    canonical: &Canonical,
    lo: f64,
    hi: f64,
    params: SearchParams,
) -> Result<CriticalSpeeds> {
    check_range(lo, hi)?;
    let poly = CharacteristicPolynomial::new(canonical);
    let n = params.intervals.max(16);
    let a0 = |v: f64| poly.at_speed(v)[0];
    let a1 = |v: f64| poly.at_speed(v)[1];
    let a3 = |v: f64| poly.at_speed(v)[3];
    let d3 = |v: f64| poly.hurwitz_delta3(v);
    let disc = |v: f64| discriminant(&poly.at_speed(v));

    let a0_roots = all_roots(a0, lo, hi, n)?;
    let d3_roots = all_roots(d3, lo, hi, n)?;

    // Stable ranges: between consecutive boundary candidates, test the midpoint.
    let mut cuts = vec![lo, hi];
    cuts.extend(&a0_roots);
    cuts.extend(&d3_roots);
    cuts.extend(all_roots(a1, lo, hi, n)?);
    cuts.extend(all_roots(a3, lo, hi, n)?);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let stable_at = |v: f64| {
        let a = poly.at_speed(v);
        a[0] > 0.0 && a[1] > 0.0 && a[3] > 0.0 && hurwitz_delta3(&a) > 0.0
    };
    let mut stable_speed_ranges: Vec<(f64, f64)> = Vec::new();
    for w in cuts.windows(2) {
        let (u0, u1) = (w[0], w[1]);
        if u1 > u0 && stable_at(0.5 * (u0 + u1)) {
            match stable_speed_ranges.last_mut() {
                Some(last) if last.1 == u0 => last.1 = u1,
                _ => stable_speed_ranges.push((u0, u1)),
            }
        }
    }

    // Weave speed: a root of Δ₃ where a complex pair sits on the imaginary axis and the number
    // of unstable eigenvalues drops as speed rises.
    let mut weave_speed = None;
    let mut weave_frequency = None;
    for &v in &d3_roots {
        let roots = quartic_roots(&poly.at_speed(v))?;
        let scale = roots.iter().fold(1.0f64, |m, l| m.max(l.norm()));
        let Some(pair) = roots
            .iter()
            .filter(|l| l.im > 0.0 && l.re.abs() <= 1e-6 * scale)
            .min_by(|x, y| x.re.abs().total_cmp(&y.re.abs()))
        else {
            continue;
        };
        let h = side_step(v);
        if unstable_count(&poly, v - h)? > unstable_count(&poly, v + h)? {
            weave_speed = Some(v);
            weave_frequency = Some(pair.im);
            break;
        }
    }

    // Capsize speed: a root of a₀ (an eigenvalue at zero) where the count of unstable
    // eigenvalues rises with speed.
    let mut capsize_speed = None;
    for &v in &a0_roots {
        let h = side_step(v);
        if unstable_count(&poly, v + h)? > unstable_count(&poly, v - h)? {
            capsize_speed = Some(v);
            break;
        }
    }

    // Double root: the discriminant changes sign while two real roots become a complex pair.
    let mut double_root_speed = None;
    let mut double_root_eigenvalue = None;
    for v in all_roots(disc, lo, hi, n)? {
        let h = side_step(v);
        let before = real_count(&quartic_roots(&poly.at_speed(v - h))?);
        let after = real_count(&quartic_roots(&poly.at_speed(v + h))?);
        if before >= after + 2 {
            let reals: Vec<f64> = quartic_roots(&poly.at_speed(v - h))?
                .iter()
                .filter(|l| l.im == 0.0)
                .map(|l| l.re)
                .collect();
            // The two real roots closest together are the ones meeting.
            let mut guess = reals.first().copied().unwrap_or(0.0);
            let mut gap = f64::INFINITY;
            for i in 0..reals.len() {
                for j in 0..i {
                    if (reals[i] - reals[j]).abs() < gap {
                        gap = (reals[i] - reals[j]).abs();
                        guess = 0.5 * (reals[i] + reals[j]);
                    }
                }
            }
            let (vd, ld) = refine_double_root(&poly, v, guess);
            double_root_speed = Some(vd);
            double_root_eigenvalue = Some(ld);
            break;
        }
    }

    Ok(CriticalSpeeds {
        range: (lo, hi),
        double_root_speed,
        double_root_eigenvalue,
        weave_speed,
        weave_frequency,
        capsize_speed,
        stable_speed_ranges,
    })
}

/// Newton's method on p(λ, v) = 0, ∂p/∂λ(λ, v) = 0 from a bracketed first guess; falls back to
/// the guess when the iteration does not improve it (bounded at 50 steps).
fn refine_double_root(poly: &CharacteristicPolynomial, v0: f64, lambda0: f64) -> (f64, f64) {
    let residual = |v: f64, l: f64| {
        let a = poly.at_speed(v);
        let da = poly.d_dv(v);
        let p = (((a[4] * l + a[3]) * l + a[2]) * l + a[1]) * l + a[0];
        let pl = ((4.0 * a[4] * l + 3.0 * a[3]) * l + 2.0 * a[2]) * l + a[1];
        let pll = (12.0 * a[4] * l + 6.0 * a[3]) * l + 2.0 * a[2];
        let pv = (((da[4] * l + da[3]) * l + da[2]) * l + da[1]) * l + da[0];
        let plv = ((4.0 * da[4] * l + 3.0 * da[3]) * l + 2.0 * da[2]) * l + da[1];
        (p, pl, pll, pv, plv)
    };
    let (mut v, mut l) = (v0, lambda0);
    for _ in 0..50 {
        let (p, pl, pll, pv, plv) = residual(v, l);
        // J [dl, dv] = -[p, pl] with J = [[pl, pv], [pll, plv]].
        let det = pl * plv - pv * pll;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let dl = -(p * plv - pv * pl) / det;
        let dv = -(pl * pl - p * pll) / det;
        if !(dl.is_finite() && dv.is_finite()) || dv.abs() > 0.1 * v0.abs().max(1.0) {
            return (v0, lambda0);
        }
        l += dl;
        v += dv;
        if dv.abs() <= 2.0 * f64::EPSILON * v.abs() && dl.abs() <= 2.0 * f64::EPSILON * l.abs() {
            break;
        }
    }
    (v, l)
}
