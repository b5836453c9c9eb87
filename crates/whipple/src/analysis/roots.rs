//! Bracketing and Brent's root finder, bounded.

use crate::error::{Error, Result};

/// Upper bound on Brent iterations (it needs about 60 in the worst case for f64).
const MAX_ITERATIONS: usize = 200;

/// A root of `f` in [a, b] where f(a) and f(b) differ in sign (or one is zero), to an absolute
/// tolerance of `4 ε |x| + tolerance` (Brent 1973, zeroin).
pub fn brent(f: impl Fn(f64) -> f64, a: f64, b: f64, tolerance: f64) -> Result<f64> {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if !(fa.is_finite() && fb.is_finite()) || fa.signum() == fb.signum() {
        return Err(Error::InvalidArgument {
            what: "bracket",
            rule: format!("f({a}) = {fa} and f({b}) = {fb} do not bracket a root"),
        });
    }
    let (mut c, mut fc) = (a, fa);
    let (mut d, mut e) = (b - a, b - a);
    for _ in 0..MAX_ITERATIONS {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * tolerance;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = f(b);
        if !fb.is_finite() {
            return Err(Error::NonFinite {
                context: format!("root finding at {b}"),
            });
        }
    }
    Err(Error::NoConvergence {
        method: "Brent's root finder",
        iterations: MAX_ITERATIONS,
        residual: fb.abs(),
    })
}

/// Every root of `f` on [lo, hi] that changes sign between neighbouring points of a uniform
/// grid of `intervals` intervals, refined by Brent; grid points where f is exactly zero count
/// too. Sorted, without repeats.
pub fn all_roots(f: impl Fn(f64) -> f64, lo: f64, hi: f64, intervals: usize) -> Result<Vec<f64>> {
    let intervals = intervals.max(1);
    let h = (hi - lo) / intervals as f64;
    let mut roots = Vec::new();
    let mut x0 = lo;
    let mut f0 = f(x0);
    if f0 == 0.0 {
        roots.push(x0);
    }
    for i in 1..=intervals {
        let x1 = if i == intervals {
            hi
        } else {
            lo + h * i as f64
        };
        let f1 = f(x1);
        if f1 == 0.0 {
            roots.push(x1);
        } else if f0 != 0.0 && f0.signum() != f1.signum() && f0.is_finite() && f1.is_finite() {
            roots.push(brent(&f, x0, x1, 0.0)?);
        }
        x0 = x1;
        f0 = f1;
    }
    roots.sort_by(f64::total_cmp);
    roots.dedup();
    Ok(roots)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_sqrt_two_to_round_off() -> Result<()> {
        let r = brent(|x| x * x - 2.0, 0.0, 2.0, 0.0)?;
        assert!((r - 2f64.sqrt()).abs() <= 4.0 * f64::EPSILON);
        Ok(())
    }

    #[test]
    fn rejects_a_non_bracket() {
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 0.0).is_err());
    }

    #[test]
    fn lists_every_root_of_a_sine() -> Result<()> {
        let roots = all_roots(f64::sin, 0.5, 10.0, 1000)?;
        assert_eq!(roots.len(), 3);
        for (k, r) in roots.iter().enumerate() {
            assert!((r - (k + 1) as f64 * std::f64::consts::PI).abs() < 1e-14);
        }
        Ok(())
    }
}
