//! The solids of Yeadon's model (Yeadon 1990, J. Biomech. 23(1):67–74, Appendix B): the
//! stadium (a rectangle of half-length `t` with half-discs of radius `r` on its two ends), the
//! stadium solid between two stadia whose `r` and `t` vary linearly with height, and the
//! semi-ellipsoid of the head. Each solid's mass, mass centre and central inertia in closed form,
//! in the solid's own frame: `z` from its first stadium to its second, `x` along the stadium's
//! long (medio-lateral) direction.

use crate::math::Real;

use crate::error::Error;

pub(super) fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

/// A stadium: half-length `thickness` of its flat sides and `radius` of its round ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Stadium<T> {
    pub(super) radius: T,
    pub(super) thickness: T,
}

impl<T: Real> Stadium<T> {
    /// A circle of perimeter `p`.
    pub(super) fn circle(p: T) -> Self {
        Stadium {
            radius: p / T::two_pi(),
            thickness: T::zero(),
        }
    }

    /// From its perimeter `p = 4t + 2πr` and width `w = 2t + 2r`. A stadium exists only for
    /// `2w < p ≤ πw` (r > 0, t ≥ 0); `fields` names the measurements in the error.
    pub(super) fn from_perimeter_width(
        p: T,
        w: T,
        fields: &str,
    ) -> std::result::Result<Self, String> {
        let denominator = T::two_pi() - c(4.0);
        let thickness = (T::pi() * w - p) / denominator;
        let radius = (p - c::<T>(2.0) * w) / denominator;
        if radius.partial_cmp(&T::zero()) != Some(std::cmp::Ordering::Greater)
            || thickness < T::zero()
        {
            return Err(format!(
                "{fields}: not a stadium (a stadium's perimeter lies between 2 and π times its \
                 width, above 2 for a positive radius and at most π for a non-negative flat length)"
            ));
        }
        Ok(Stadium { radius, thickness })
    }

    /// From its depth `d = 2r` and width `w`: the perimeter is `2w + (π − 2)d`.
    pub(super) fn from_depth_width(d: T, w: T, fields: &str) -> std::result::Result<Self, String> {
        let p = c::<T>(2.0) * w + (T::pi() - c(2.0)) * d;
        Self::from_perimeter_width(p, w, fields)
    }
}

/// A solid's mass, mass centre on its `z` axis (from its first end) and central principal
/// moments about its `x`, `y`, `z` axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SolidInertia<T> {
    pub(super) mass: T,
    pub(super) z: T,
    pub(super) moments: [T; 3],
}

fn f1<T: Real>(a: T, b: T) -> T {
    T::one() + (a + b) / c(2.0) + a * b / c(3.0)
}
fn f2<T: Real>(a: T, b: T) -> T {
    c::<T>(0.5) + (a + b) / c(3.0) + a * b / c(4.0)
}
fn f3<T: Real>(a: T, b: T) -> T {
    c::<T>(1.0 / 3.0) + (a + b) / c(4.0) + a * b / c(5.0)
}
fn f4<T: Real>(a: T, b: T) -> T {
    T::one()
        + (a + c::<T>(3.0) * b) / c(2.0)
        + (a * b + b * b)
        + (c::<T>(3.0) * a * b * b + b * b * b) / c(4.0)
        + a * b * b * b / c(5.0)
}
fn f5<T: Real>(a: T, b: T) -> T {
    T::one()
        + (a + b)
        + (a * a + c::<T>(4.0) * a * b + b * b) / c(3.0)
        + a * b * (a + b) / c(2.0)
        + a * a * b * b / c(5.0)
}

/// The stadium solid of density `density` and height `h` from stadium `s0` (at z = 0) to `s1`
/// (at z = h), with `r` and `t` linear in z (Yeadon 1990, Appendix B: `r = r0(1 + a z/h)`,
/// `t = t0(1 + b z/h)`; the integrals F1…F5 of the paper). Where `t0 = 0` the ends are
/// exchanged (the closed form divides by `t0`) and the mass centre measured back from z = 0;
/// where both are circles, `b` is irrelevant. The moment about `x` integrates `y²` over the
/// stadium, `4 r³ t / 3 + π r⁴ / 4` per unit height (the package `yeadon` 2.0.1 has `r t³`
/// there, which breaks the perpendicular-axis theorem).
pub(super) fn stadium_solid<T: Real>(
    density: T,
    s0: Stadium<T>,
    s1: Stadium<T>,
    h: T,
) -> SolidInertia<T> {
    let exchanged = s0.thickness == T::zero();
    let (base, other) = if exchanged { (s1, s0) } else { (s0, s1) };
    let (r0, t0) = (base.radius, base.thickness);
    let a = (other.radius - r0) / r0;
    let b = if t0 == T::zero() {
        T::one()
    } else {
        (other.thickness - t0) / t0
    };
    let pi = T::pi();
    let (d, four, three) = (density, c::<T>(4.0), c::<T>(3.0));
    let mass = d * h * r0 * (four * t0 * f1(a, b) + pi * r0 * f1(a, a));
    let z_base = d * h * h * (four * r0 * t0 * f2(a, b) + pi * r0 * r0 * f2(a, a)) / mass;
    let z = if exchanged { h - z_base } else { z_base };
    let (r2, t2) = (r0 * r0, t0 * t0);
    let axial = d * h * h * h * (four * r0 * t0 * f3(a, b) + pi * r2 * f3(a, a));
    // Cross-section integrals of x² and y² (x along t), integrated over the height.
    let x2 = d
        * h
        * (four * r0 * t2 * t0 * f4(a, b) / three
            + pi * r2 * t2 * f5(a, b)
            + c::<T>(8.0) * r2 * r0 * t0 * f4(b, a) / three
            + pi * r2 * r2 * f4(a, a) / four);
    let y2 = d * h * (four * r2 * r0 * t0 * f4(b, a) / three + pi * r2 * r2 * f4(a, a) / four);
    let shift = mass * z_base * z_base;
    SolidInertia {
        mass,
        z,
        moments: [y2 + axial - shift, x2 + axial - shift, x2 + y2],
    }
}

/// The semi-ellipsoid of the head: circular base of perimeter `p` at z = 0, height `h`.
pub(super) fn semi_ellipsoid<T: Real>(density: T, p: T, h: T) -> SolidInertia<T> {
    let r = p / T::two_pi();
    let pi = T::pi();
    let r2 = r * r;
    let mass = density * c::<T>(2.0 / 3.0) * pi * r2 * h;
    let z = c::<T>(3.0 / 8.0) * h;
    // About the base: x² integrates to 2π r⁴ h / 15, z² to 2π r² h³ / 15; then to the centre.
    let lateral = density * pi * (c::<T>(2.0 / 15.0) * r2 * h * (r2 + h * h))
        - density * pi * c::<T>(3.0 / 32.0) * r2 * h * h * h;
    SolidInertia {
        mass,
        z,
        moments: [
            lateral,
            lateral,
            density * c::<T>(4.0 / 15.0) * pi * r2 * r2 * h,
        ],
    }
}

/// An error naming a measurement of the file (with its line when known).
pub(super) fn measurement_error(
    format: &'static str,
    field: &str,
    line: usize,
    value: f64,
    rule: String,
) -> Error {
    if line > 0 {
        Error::Parse {
            format,
            field: Some(field.to_string()),
            line,
            column: 1,
            message: rule,
        }
    } else {
        Error::InvalidParameter {
            field: field.to_string(),
            value,
            rule,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A truncated cone from radius 1 (z = 0) to 2 (z = 1): the mass centre at
    /// ∫z(1+z)²dz / ∫(1+z)²dz = 17/28, whichever end the closed form starts from.
    #[test]
    fn a_truncated_cone_has_its_mass_centre_towards_the_wide_end() {
        let (narrow, wide) = (Stadium::circle(2.0 * PI), Stadium::circle(4.0 * PI));
        let up = stadium_solid(1.0, narrow, wide, 1.0);
        let down = stadium_solid(1.0, wide, narrow, 1.0);
        assert!((up.z - 17.0 / 28.0).abs() < 1e-15);
        assert!((down.z - 11.0 / 28.0).abs() < 1e-15);
        assert!((up.mass - PI * 7.0 / 3.0).abs() < 1e-14);
        for (u, d) in up.moments.iter().zip(down.moments) {
            assert!((u - d).abs() < 1e-14 * u);
        }
    }

    /// A thin stadium prism (a = b = 0): the moments are the cross-section's second moments,
    /// ∫y² = 4tr³/3 + πr⁴/4 and ∫x² = 4rt³/3 + πr²t² + 8r³t/3 + πr⁴/4, and the
    /// perpendicular-axis theorem holds; the mass centre is half way; a stadium's perimeter and
    /// width give back its r and t.
    #[test]
    fn a_stadium_prism_has_the_cross_section_moments() {
        let (t, r, h) = (0.3, 0.1, 1e-4);
        let s = Stadium::from_perimeter_width(4.0 * t + 2.0 * PI * r, 2.0 * (t + r), "").unwrap();
        assert!((s.radius - r).abs() < 1e-15 && (s.thickness - t).abs() < 1e-15);
        let p = stadium_solid(1.0, s, s, h);
        let y2 = 4.0 * t * r.powi(3) / 3.0 + PI * r.powi(4) / 4.0;
        let x2 = 4.0 * r * t.powi(3) / 3.0
            + PI * r * r * t * t
            + 8.0 * r.powi(3) * t / 3.0
            + PI * r.powi(4) / 4.0;
        let area = 4.0 * r * t + PI * r * r;
        let axial = area * h.powi(3) / 12.0;
        assert!((p.mass - area * h).abs() < 1e-17);
        assert!((p.z - h / 2.0).abs() < 1e-18);
        assert!((p.moments[0] - (y2 * h + axial)).abs() < 1e-15 * p.moments[2]);
        assert!((p.moments[1] - (x2 * h + axial)).abs() < 1e-15 * p.moments[2]);
        assert!(
            (p.moments[2] - (p.moments[0] + p.moments[1] - 2.0 * axial)).abs()
                < 1e-15 * p.moments[2]
        );
    }

    /// Not stadia: a perimeter at most twice the width, or above π times it.
    #[test]
    fn perimeters_outside_two_to_pi_widths_are_refused() {
        assert!(Stadium::from_perimeter_width(2.0, 1.0, "p, w").is_err());
        assert!(Stadium::from_perimeter_width(3.2, 1.0, "p, w").is_err());
        assert!(Stadium::from_perimeter_width(PI, 1.0, "p, w").is_ok());
        assert!(Stadium::from_depth_width(1.2, 1.0, "d, w").is_err());
    }

    /// The half ellipsoid of revolution: mass 2πr²h/3, centre at 3h/8, moments about the base's
    /// centre 2πr²h(r² + h²)/15 (transverse) and 4πr⁴h/15 (axial), the transverse one moved to
    /// the mass centre.
    #[test]
    fn the_head_cap_is_half_an_ellipsoid() {
        let (r, h) = (0.1, 0.15);
        let s = semi_ellipsoid(1000.0, 2.0 * PI * r, h);
        let m = 1000.0 * 2.0 * PI * r * r * h / 3.0;
        assert!((s.mass - m).abs() < 1e-12 * m);
        assert!((s.z - 0.375 * h).abs() < 1e-15);
        let about_base = 1000.0 * 2.0 * PI * r * r * h * (r * r + h * h) / 15.0;
        assert!((s.moments[0] - (about_base - m * s.z * s.z)).abs() < 1e-12 * about_base);
        assert!((s.moments[2] - 1000.0 * 4.0 * PI * r.powi(4) * h / 15.0).abs() < 1e-15);
    }
}
