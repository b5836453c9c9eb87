//! The steps from bench measurements to benchmark parameters, one function each, generic over
//! the scalar so that dual numbers carry exact first-order derivatives through them.
//!
//! Sources: Moore 2012 (PhD thesis, UC Davis), ch. 2 "Physical parameter measurement";
//! Moore, Hubbard, Kooijman & Schwab 2010, "A method for estimating physical properties of a
//! combined bicycle and rider" (ASME IDETC 2009, DETC2009-86947); Kooijman 2006, "Experimental
//! validation of a model for the motion of an uncontrolled bicycle" (TU Delft). The order of
//! the steps and their conventions are those of BicycleParameters' `calculate_from_measured`,
//! whose results the tests compare with.

use crate::math::Real;
use nalgebra::{Matrix3, Vector3};

use crate::error::{Error, Result};

fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

/// A wheel's radius from the distance it rolled on the ground in a whole number of turns:
/// r = d / (2π n).
pub fn wheel_radius<T: Real>(distance: T, rotations: T) -> T {
    distance / (T::two_pi() * rotations)
}

/// The steer axis tilt λ (from the vertical) from the head tube's angle γ with the ground, in
/// degrees as it is measured: λ = π/2 − γ.
pub fn steer_axis_tilt<T: Real>(head_angle_deg: T) -> T {
    (c::<T>(90.0) - head_angle_deg) * T::pi() / c(180.0)
}

/// The trail c from the front wheel's radius, the steer axis tilt and the fork offset f (the
/// perpendicular distance from the front hub to the steer axis):
/// c = (r_F sin λ − f) / cos λ.
pub fn trail<T: Real>(r_f: T, lambda: T, fork_offset: T) -> T {
    (r_f * crate::math::sin(lambda) - fork_offset) / crate::math::cos(lambda)
}

/// A line z = slope·x + intercept in the benchmark frame (x forward, z down, origin at the rear
/// contact) on which a hung frame's mass centre lies, with the angle β from the benchmark x
/// axis to the pendulum's x axis (a rotation about y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HangingLine<T = f64> {
    /// dz/dx of the line.
    pub slope: T,
    /// z where the line crosses x = 0 \[m\].
    pub intercept: T,
    /// β = λ − α: the pendulum frame's orientation relative to the benchmark frame \[rad\].
    pub beta: T,
}

/// Which frame hung: its reference point is a wheel's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HungFrame {
    /// The rear frame: the reference point is the rear hub, at (0, −r_R).
    Rear,
    /// The front frame (fork and handlebar): the reference point is the front hub, at
    /// (w, −r_F).
    Front,
}

/// The line through a frame's mass centre when it hangs still from a wire: the wire is
/// vertical and passes through the mass centre. The frame hangs with its steer axis at angle α
/// (degrees, measured in the vertical plane from the horizontal, right side view), and the
/// wire passes at distance `a` from the reference point (the wheel's centre), positive where
/// the point lies on the wire's left. In the benchmark frame the wire's direction makes the
/// angle β = λ − α with the z axis, so its slope is −tan β and its intercept follows from the
/// reference point: z₀ = −a / cos β + z_ref − x_ref·(−tan β)
/// (Moore 2012 §2.4; Kooijman 2006).
pub fn hanging_line<T: Real>(
    frame: HungFrame,
    alpha_deg: T,
    a: T,
    lambda: T,
    wheelbase: T,
    r_r: T,
    r_f: T,
) -> HangingLine<T> {
    let (x_ref, z_ref) = match frame {
        HungFrame::Rear => (T::zero(), -r_r),
        HungFrame::Front => (wheelbase, -r_f),
    };
    hanging_line_through(alpha_deg, a, lambda, x_ref, z_ref)
}

/// [`hanging_line`] for any reference point (x_ref, z_ref) of the benchmark frame: the wire
/// passes at distance `a` from it (positive with the point on the wire's left), so the line
/// is z = −tan β · x + z₀ with z₀ = −a / cos β + z_ref + x_ref tan β, β = λ − α. A handlebar
/// hung apart from its fork takes the handlebar's reference point
/// ([`handlebar_reference_offset`]).
pub fn hanging_line_through<T: Real>(
    alpha_deg: T,
    a: T,
    lambda: T,
    x_ref: T,
    z_ref: T,
) -> HangingLine<T> {
    let beta = lambda - alpha_deg * T::pi() / c(180.0);
    HangingLine {
        slope: -crate::math::tan(beta),
        intercept: -a / crate::math::cos(beta) + z_ref + x_ref * crate::math::tan(beta),
        beta,
    }
}

/// The geometry measured as perpendicular distances (Moore 2012 §2.3, the frame and fork on
/// a surface plate with a height gauge and dummy axles): the rear frame's offset a (the
/// perpendicular distance from the steer axis to the rear hub), the fork offset b (from the
/// steer axis to the front hub) and the distance c along the steer axis between the feet of
/// those two perpendiculars:
/// a = h1 + h2 − h3 + d1/2 − d2/2, b = h4 − d3/2 − h5 + d4/2,
/// c = √((d + (d2 + d3)/2)² − (a − b)²), where h1…h5 are the heights of the rear axle's
/// top, the gauge's base, the head tube's top, the front axle's top and the steer tube's
/// top, d1…d4 the diameters of the head tube, the dummy rear and front axles and the steer
/// tube, and d the inside distance between the axles with the fork reversed (the hubs
/// are d + (d2 + d3)/2 apart). c is NaN when the hubs are closer than |a − b|: the
/// measurements then describe no steer axis (the reader refuses them first).
#[allow(clippy::too_many_arguments)]
pub fn steer_axis_offsets<T: Real>(h: [T; 5], d1: T, d2: T, d3: T, d4: T, d: T) -> (T, T, T) {
    let half: T = c(0.5);
    let a = h[0] + h[1] - h[2] + half * d1 - half * d2;
    let b = h[3] - half * d3 - h[4] + half * d4;
    let hubs = d + half * (d2 + d3);
    let span = (hubs * hubs - (a - b) * (a - b)).sqrt();
    (a, b, span)
}

/// The most Newton steps [`steer_axis_tilt_from_offsets`] takes.
const MAX_TILT_STEPS: usize = 64;

/// The steer axis tilt λ from the offsets of [`steer_axis_offsets`] and the wheel radii: with
/// both wheels on the ground the hubs' heights differ by r_F − r_R, which the offsets and the
/// span along the axis give as (a + b) sin λ − c cos λ, so λ solves
/// F(λ) = sin λ − (r_F − r_R + c cos λ) / (a + b) = 0 (Moore 2012 §2.3). Newton's method from
/// atan(c / (a + b)) (the root for equal wheels), at most 64 steps, then two more so that a
/// dual number's derivative part, which follows the value one step behind, is converged
/// too: its derivative is the implicit one, −F_x / F_λ. Fails, naming `field`, when a + b is
/// not positive or the iteration does not settle in (−π/2, π/2).
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn steer_axis_tilt_from_offsets<T: Real>(
    r_f: T,
    r_r: T,
    a: T,
    b: T,
    span: T,
    field: &str,
) -> Result<T> {
    let bad = |value: f64, rule: &str| Error::InvalidParameter {
        field: field.into(),
        value,
        rule: rule.into(),
    };
    let ab = a + b;
    if !(ab > T::zero()) {
        return Err(bad(
            f64::NAN,
            "the rear frame's and the fork's offsets from the steer axis (a + b) must add              up to a positive distance",
        ));
    }
    let step = |lam: T| {
        let (s, co) = crate::math::sin_cos(lam);
        let value = s - (r_f - r_r + span * co) / ab;
        let slope = co + span * s / ab;
        value / slope
    };
    let mut lam = crate::math::atan(span / ab);
    let mut settled = 0;
    for _ in 0..MAX_TILT_STEPS {
        let delta = step(lam);
        lam -= delta;
        if !(lam.abs() < T::frac_pi_2()) {
            break;
        }
        if delta.abs() <= c::<T>(1e-15) * (T::one() + lam.abs()) {
            settled += 1;
            if settled > 2 {
                return Ok(lam);
            }
        }
    }
    Err(bad(
        f64::NAN,
        "the perpendicular distances give no steer axis tilt: Newton's method on          sin λ = (rF − rR + c cos λ)/(a + b) did not settle in (−90°, 90°)",
    ))
}

/// The wheelbase from the offsets and the steer axis tilt: the hubs' horizontal distance,
/// w = (a + b) cos λ + c sin λ (Moore 2012 §2.3).
pub fn wheelbase_from_offsets<T: Real>(a: T, b: T, span: T, lambda: T) -> T {
    (a + b) * crate::math::cos(lambda) + span * crate::math::sin(lambda)
}

/// Where a handlebar measured apart from its fork has its reference point (the centre of a
/// reference circle on the handlebar), relative to the front hub: (l1, l2), perpendicular to
/// the steer axis (forward positive) and along it (upwards positive), from the heights of
/// the front axle's top h6 and the reference circle's top h7, their diameters d5 and d6, and
/// the outer distance l between axle and circle (Moore 2012 §2.4): l1 = h7 − h6 + d5/2 − d6/2,
/// l0 = l − d5/2 − d6/2 (the centres' distance), l2 = √(l0² − l1²). l2 is NaN when |l1| > l0
/// (the reader refuses such measurements first).
pub fn handlebar_reference<T: Real>(h6: T, h7: T, d5: T, d6: T, l: T) -> (T, T) {
    let half: T = c(0.5);
    let l1 = h7 - h6 + half * d5 - half * d6;
    let l0 = l - half * d5 - half * d6;
    (l1, (l0 * l0 - l1 * l1).sqrt())
}

/// The handlebar's reference point relative to the front hub in the benchmark frame's
/// directions, (−u1, −u2) (x forward, z down), from its (l1, l2) across and along the steer
/// axis tilted by λ: u1 = l2 sin λ − l1 cos λ (backwards), u2 = l2 cos λ + l1 sin λ
/// (upwards). The point is at (w − u1, −r_F − u2).
pub fn handlebar_reference_offset<T: Real>(lambda: T, l1: T, l2: T) -> (T, T) {
    let (s, co) = crate::math::sin_cos(lambda);
    (l2 * s - l1 * co, l2 * co + l1 * s)
}

/// A flywheel's own quantity from a measurement of the front wheel with the flywheel inside
/// (BicycleParameters' part D, the gyro bicycle): the combined value less the wheel's,
/// for its mass and for its moments (compound pendulum about y, torsional about a diameter).
pub fn flywheel_part<T: Real>(wheel_with_flywheel: T, wheel: T) -> T {
    wheel_with_flywheel - wheel
}

/// The point where two lines meet, `None` for parallel lines (slopes equal to a relative 1e-9).
pub fn intersection<T: Real>(a: &HangingLine<T>, b: &HangingLine<T>) -> Option<(T, T)> {
    let ds = b.slope - a.slope;
    let scale = c::<T>(1.0) + a.slope.abs() + b.slope.abs();
    if ds.abs() <= scale * c(1e-9) {
        return None;
    }
    let x = (a.intercept - b.intercept) / ds;
    Some((x, a.intercept + a.slope * x))
}

/// A hung frame's mass centre (x, z): the mean of the lines' intersections, every pair once,
/// as BicycleParameters estimates it (`com.center_of_mass`; three lines give three points
/// whose spread shows the measurement error). Fails, naming `field`, when fewer than two lines
/// are given or two of them are parallel.
pub fn mass_centre<T: Real>(lines: &[HangingLine<T>], field: &str) -> Result<(T, T)> {
    if lines.len() < 2 {
        return Err(Error::InvalidParameter {
            field: field.into(),
            value: lines.len() as f64,
            rule: "a mass centre needs at least two hanging angles".into(),
        });
    }
    let (mut x, mut z, mut n) = (T::zero(), T::zero(), 0.0);
    for (i, a) in lines.iter().enumerate() {
        for (j, b) in lines.iter().enumerate().skip(i + 1) {
            let (xi, zi) = intersection(a, b).ok_or_else(|| Error::InvalidParameter {
                field: format!("{field}{} and {field}{}", i + 1, j + 1),
                value: f64::NAN,
                rule: "the two hanging lines are parallel: they do not determine the mass \
                       centre (hang the frame at another angle)"
                    .into(),
            })?;
            x += xi;
            z += zi;
            n += 1.0;
        }
    }
    Ok((x / c(n), z / c(n)))
}

/// The moment of inertia about its mass centre of a body swung as a compound pendulum about
/// an axis at distance l from the mass centre, from its period T:
/// I = m g l (T / 2π)² − m l² (Moore 2012 §2.5).
pub fn compound_pendulum_inertia<T: Real>(mass: T, g: T, length: T, period: T) -> T {
    let t = period / T::two_pi();
    t * t * mass * g * length - mass * length * length
}

/// The moment of inertia of a solid cylindrical rod about a transverse axis through its
/// centre: I = m (3 r² + l²) / 12 with r = d/2.
pub fn rod_transverse_inertia<T: Real>(mass: T, length: T, diameter: T) -> T {
    let r = diameter / c(2.0);
    mass / c(12.0) * (c::<T>(3.0) * r * r + length * length)
}

/// The torsion constant of a torsional pendulum from a body of known inertia I and its
/// period T: k = 4π² I / T².
pub fn torsion_constant<T: Real>(inertia: T, period: T) -> T {
    let w = T::two_pi() / period;
    inertia * w * w
}

/// The moment of inertia of a body on a torsional pendulum of constant k from its period T:
/// I = k T² / 4π² (the inverse of [`torsion_constant`]).
pub fn torsional_pendulum_inertia<T: Real>(k: T, period: T) -> T {
    let t = period / T::two_pi();
    k * t * t
}

/// The planar inertia components (I_xx, I_xz, I_zz) of a body from its moments J_i about axes
/// in the xz plane at angles β_i: J = I_xx cos²β − 2 I_xz sin β cos β + I_zz sin²β, solved by
/// least squares (exactly for three axes). Fails, naming `field`, when the axes do not
/// determine the three components.
pub fn planar_inertia<T: Real>(moments: &[T], betas: &[T], field: &str) -> Result<[T; 3]> {
    let bad = |rule: &str| Error::InvalidParameter {
        field: field.into(),
        value: moments.len() as f64,
        rule: rule.into(),
    };
    if moments.len() < 3 || moments.len() != betas.len() {
        return Err(bad(
            "the inertia in the plane needs at least three torsional periods at distinct angles",
        ));
    }
    let mut normal = Matrix3::<T>::zeros();
    let mut rhs = Vector3::<T>::zeros();
    for (j, beta) in moments.iter().zip(betas) {
        let (s, co) = crate::math::sin_cos(*beta);
        let row = Vector3::new(co * co, -c::<T>(2.0) * s * co, s * s);
        normal += row * row.transpose();
        rhs += row * *j;
    }
    let scale = normal.iter().fold(T::zero(), |m, x| m.max(x.abs()));
    let det = normal.determinant();
    if det.abs() <= scale * scale * scale * c(1e-12) {
        return Err(bad(
            "the hanging angles do not determine the inertia in the plane (two are parallel)",
        ));
    }
    let solution = normal
        .try_inverse()
        .ok_or_else(|| bad("the hanging angles do not determine the inertia in the plane"))?
        * rhs;
    Ok([solution[0], solution[1], solution[2]])
}

/// The distance from a point to a wheel's centre in the xz plane: the length of the compound
/// pendulum when a frame swings about that wheel's axle.
pub fn pendulum_length<T: Real>(x: T, z: T, axle_x: T, axle_z: T) -> T {
    let (dx, dz) = (x - axle_x, z - axle_z);
    (dx * dx + dz * dz).sqrt()
}

/// The principal moments of a body's inertia in the xz plane and the axes' orientation: from
/// (I_xx, I_xz, I_zz), the moments I₁ ≥ I₂ of the 2 × 2 tensor [[I_xx, I_xz], [I_xz, I_zz]] and
/// the angle θ from the x axis to I₁'s axis, a rotation about y, in (−π/2, π/2]
/// (Moore 2012 §2.7: the frames' principal axes). Inverse: I_xx = I₁ cos²θ + I₂ sin²θ,
/// I_zz = I₁ sin²θ + I₂ cos²θ, I_xz = (I₂ − I₁) sin θ cos θ (z down, so a rotation about y
/// takes x towards −z).
pub fn principal_planar<T: Real>(i_xx: T, i_xz: T, i_zz: T) -> (T, T, T) {
    let half: T = c(0.5);
    let mean = (i_xx + i_zz) * half;
    let d = (i_xx - i_zz) * half;
    let radius = (d * d + i_xz * i_xz).sqrt();
    let theta = crate::math::atan2(-i_xz, d) * half;
    (mean + radius, mean - radius, theta)
}

/// The root mean square distance of a point (x, z) from hanging lines: how well the lines of
/// a hung frame agree on its mass centre (zero for two lines, which always meet in one point;
/// the measurement error shows with three or more).
pub fn line_residual<T: Real>(lines: &[HangingLine<T>], x: T, z: T) -> T {
    if lines.is_empty() {
        return T::zero();
    }
    let mut sum = T::zero();
    for line in lines {
        let d = (z - line.slope * x - line.intercept) / (T::one() + line.slope * line.slope).sqrt();
        sum += d * d;
    }
    (sum / c(lines.len() as f64)).sqrt()
}
