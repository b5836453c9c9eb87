//! The elementary functions (sin, cos, exp, ln, …) of every answer whipple computes: one
//! implementation on every target, the [`libm`] crate (a pure-Rust port of musl's libm).
//!
//! The standard library's `f64::sin` and its kin call the platform's C library natively (glibc
//! on Linux) and Rust's port of musl's libm in WebAssembly; the two round some arguments
//! differently, so a native server and the static site's module would part in the last
//! places. Everything here rounds the same everywhere, and `clippy.toml` refuses the standard
//! library's (and nalgebra's generic `ComplexField`'s) versions outside this module. Square
//! roots, `abs`, `mul_add` and `powi` stay the standard library's: IEEE operations (or exact
//! products) that every target rounds alike.
//!
//! The free functions take `f64`; [`Real`] gives the generic dynamics (over `f64` and
//! num-dual's dual numbers) the same functions, derivatives included.
#![allow(clippy::disallowed_methods)]

use std::borrow::Borrow;

use nalgebra::{Complex, RealField};
use num_dual::{Dual64, HyperDual64};

/// sin x.
#[inline]
pub fn sin<T: Real>(x: T) -> T {
    T::sin_of(x)
}

/// cos x.
#[inline]
pub fn cos<T: Real>(x: T) -> T {
    T::cos_of(x)
}

/// (sin x, cos x).
#[inline]
pub fn sin_cos<T: Real>(x: T) -> (T, T) {
    T::sin_cos_of(x)
}

/// tan x.
#[inline]
pub fn tan<T: Real>(x: T) -> T {
    T::tan_of(x)
}

/// arcsin x.
#[inline]
pub fn asin<T: Real>(x: T) -> T {
    T::asin_of(x)
}

/// arccos x.
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// arctan x.
#[inline]
pub fn atan<T: Real>(x: T) -> T {
    T::atan_of(x)
}

/// The angle of (x, y): atan2(y, x), as `y.atan2(x)`.
#[inline]
pub fn atan2<T: Real>(y: T, x: T) -> T {
    T::atan2_of(y, x)
}

/// eˣ.
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// ln x.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// log₁₀ x.
#[inline]
pub fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// xʸ.
#[inline]
pub fn powf(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// √(x² + y²) without overflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// ∛x.
#[inline]
pub fn cbrt(x: f64) -> f64 {
    libm::cbrt(x)
}

/// log₂ x.
#[inline]
pub fn log2(x: f64) -> f64 {
    libm::log2(x)
}

/// arsinh x.
#[inline]
pub fn asinh(x: f64) -> f64 {
    libm::asinh(x)
}

/// arcosh x.
#[inline]
pub fn acosh(x: f64) -> f64 {
    libm::acosh(x)
}

/// artanh x.
#[inline]
pub fn atanh(x: f64) -> f64 {
    libm::atanh(x)
}

/// sinh x.
#[inline]
pub fn sinh(x: f64) -> f64 {
    libm::sinh(x)
}

/// cosh x.
#[inline]
pub fn cosh(x: f64) -> f64 {
    libm::cosh(x)
}

/// tanh x.
#[inline]
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}

/// The modulus |z| of a complex number (`Complex::norm`'s hypot).
#[inline]
pub fn norm(z: impl Borrow<Complex<f64>>) -> f64 {
    let z = z.borrow();
    hypot(z.re, z.im)
}

/// The argument of a complex number (`Complex::arg`'s atan2).
#[inline]
pub fn arg(z: impl Borrow<Complex<f64>>) -> f64 {
    let z = z.borrow();
    atan2(z.im, z.re)
}

/// r·e^(iθ).
#[inline]
pub fn from_polar(r: f64, theta: f64) -> Complex<f64> {
    let (s, c) = sin_cos(theta);
    Complex::new(r * c, r * s)
}

/// eᶻ of a complex z.
#[inline]
pub fn complex_exp(z: Complex<f64>) -> Complex<f64> {
    from_polar(exp(z.re), z.im)
}

/// The principal square root of a complex z (its real part ≥ 0), without cancellation.
pub fn complex_sqrt(z: Complex<f64>) -> Complex<f64> {
    if z.im == 0.0 {
        return if z.re >= 0.0 {
            Complex::new(z.re.sqrt(), z.im)
        } else {
            Complex::new(0.0, (-z.re).sqrt().copysign(z.im))
        };
    }
    let t = ((z.re.abs() + norm(z)) / 2.0).sqrt();
    if z.re >= 0.0 {
        Complex::new(t, z.im / (2.0 * t))
    } else {
        Complex::new(z.im.abs() / (2.0 * t), t.copysign(z.im))
    }
}

/// The scalars the dynamics is generic over (`f64`, num-dual's `Dual64` and `HyperDual64`):
/// nalgebra's [`RealField`] with this module's elementary functions, derivatives by the chain
/// rule. Call them as [`Real::sin_cos_of`] and so on (not `x.sin_cos()`, which is nalgebra's:
/// the platform's C library).
pub trait Real: RealField + Copy {
    /// (sin x, cos x).
    fn sin_cos_of(x: Self) -> (Self, Self);
    /// arcsin x.
    fn asin_of(x: Self) -> Self;
    /// arctan x.
    fn atan_of(x: Self) -> Self;
    /// atan2(y, x).
    fn atan2_of(y: Self, x: Self) -> Self;

    /// sin x.
    #[inline]
    fn sin_of(x: Self) -> Self {
        Self::sin_cos_of(x).0
    }
    /// cos x.
    #[inline]
    fn cos_of(x: Self) -> Self {
        Self::sin_cos_of(x).1
    }
    /// tan x.
    #[inline]
    fn tan_of(x: Self) -> Self {
        let (s, c) = Self::sin_cos_of(x);
        s / c
    }
}

impl Real for f64 {
    #[inline]
    fn sin_cos_of(x: f64) -> (f64, f64) {
        libm::sincos(x)
    }
    #[inline]
    fn sin_of(x: f64) -> f64 {
        libm::sin(x)
    }
    #[inline]
    fn cos_of(x: f64) -> f64 {
        libm::cos(x)
    }
    #[inline]
    fn tan_of(x: f64) -> f64 {
        libm::tan(x)
    }
    #[inline]
    fn asin_of(x: f64) -> f64 {
        libm::asin(x)
    }
    #[inline]
    fn atan_of(x: f64) -> f64 {
        libm::atan(x)
    }
    #[inline]
    fn atan2_of(y: f64, x: f64) -> f64 {
        libm::atan2(y, x)
    }
}

impl Real for Dual64 {
    #[inline]
    fn sin_cos_of(x: Self) -> (Self, Self) {
        let (s, c) = sin_cos(x.re);
        (Dual64::new(s, x.eps * c), Dual64::new(c, x.eps * -s))
    }
    #[inline]
    fn asin_of(x: Self) -> Self {
        let rec = (1.0 - x.re * x.re).recip();
        Dual64::new(asin(x.re), x.eps * rec.sqrt())
    }
    #[inline]
    fn atan_of(x: Self) -> Self {
        let rec = (1.0 + x.re * x.re).recip();
        Dual64::new(atan(x.re), x.eps * rec)
    }
    #[inline]
    fn atan2_of(y: Self, x: Self) -> Self {
        let mut angle = Self::atan_of(y / x);
        angle.re = atan2(y.re, x.re);
        angle
    }
}

impl Real for HyperDual64 {
    #[inline]
    fn sin_cos_of(x: Self) -> (Self, Self) {
        let (s, c) = sin_cos(x.re);
        (hyper(x, s, c, -s), hyper(x, c, -s, -c))
    }
    #[inline]
    fn asin_of(x: Self) -> Self {
        let rec = (1.0 - x.re * x.re).recip();
        let f1 = rec.sqrt();
        hyper(x, asin(x.re), f1, x.re * f1 * rec)
    }
    #[inline]
    fn atan_of(x: Self) -> Self {
        let rec = (1.0 + x.re * x.re).recip();
        hyper(x, atan(x.re), rec, -x.re * rec * rec * 2.0)
    }
    #[inline]
    fn atan2_of(y: Self, x: Self) -> Self {
        let mut angle = Self::atan_of(y / x);
        angle.re = atan2(y.re, x.re);
        angle
    }
}

/// f(x) for a hyper-dual x from f(x.re), f′(x.re) and f″(x.re).
#[inline]
fn hyper(x: HyperDual64, f0: f64, f1: f64, f2: f64) -> HyperDual64 {
    HyperDual64::new(
        f0,
        x.eps1 * f1,
        x.eps2 * f1,
        x.eps1eps2 * f1 + x.eps1 * x.eps2 * f2,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_numbers_carry_the_derivatives() {
        let x = 0.7;
        let (s, c) = Dual64::sin_cos_of(Dual64::new(x, 1.0));
        assert_eq!(
            (s.re, s.eps, c.re, c.eps),
            (sin(x), cos(x), cos(x), -sin(x))
        );
        let a = Dual64::asin_of(Dual64::new(0.3, 1.0));
        assert!((a.eps - 1.0 / (1.0 - 0.09f64).sqrt()).abs() < 1e-15);
        let t = Dual64::atan2_of(Dual64::new(0.3, 1.0), Dual64::new(-0.8, 0.0));
        assert_eq!(t.re, atan2(0.3, -0.8));
        assert!((t.eps - -0.8 / 0.73).abs() < 1e-14);
        let h = HyperDual64::sin_cos_of(HyperDual64::new(x, 1.0, 1.0, 0.0)).0;
        assert_eq!((h.eps1, h.eps1eps2), (cos(x), -sin(x)));
        let h = HyperDual64::atan_of(HyperDual64::new(0.5, 1.0, 1.0, 0.0));
        assert!((h.eps1eps2 - -2.0 * 0.5 / (1.25f64 * 1.25)).abs() < 1e-15);
    }

    #[test]
    fn the_functions_are_libm_s() {
        assert_eq!(sin(1e22).to_bits(), libm::sin(1e22).to_bits());
        assert_eq!(powf(2.0, 0.5), libm::sqrt(2.0));
        assert_eq!(hypot(3.0, 4.0), 5.0);
        for z in [
            (4.0, 0.0),
            (-4.0, 0.0),
            (-4.0, -0.0),
            (3.0, 4.0),
            (-3.0, 4.0),
            (-3.0, -4.0),
        ] {
            let z = Complex::new(z.0, z.1);
            let r = complex_sqrt(z);
            assert!((r * r - z).norm_sqr() < 1e-28 && r.re >= 0.0, "{z} {r}");
        }
    }
}
