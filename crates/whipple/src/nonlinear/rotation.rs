//! Orientation of each body: yaw–lean–pitch Euler angles (body-fixed z–x–y sequence), rotation
//! matrices, and the map between angular velocity and angle rates.
//!
//! World axes are the benchmark's: x forward, y right, z down. A body's orientation is
//! `R = R_z(yaw) · R_x(lean) · R_y(pitch)` (body → world). The sequence is singular only when
//! the body's y axis (the wheel axles, the frames' lateral axes) is vertical, that is when the
//! bicycle lies flat on the ground (lean ±90°). Yaw and the third angle (pitch of a frame,
//! rotation of a wheel) are unrestricted: any heading, any number of wheel turns.
//!
//! With z down, positive yaw turns right, positive lean leans right (benchmark convention),
//! positive pitch lifts the nose, and a wheel rolling forward turns with a negative rate.

use crate::math::Real;
use nalgebra::{Matrix3, Vector3};

/// `R = R_z(yaw) R_x(lean) R_y(pitch)`: body → world.
#[inline]
pub fn matrix<T: Real>(yaw: T, lean: T, pitch: T) -> Matrix3<T> {
    matrix_from_sin_cos(SinCos::new(yaw), SinCos::new(lean), SinCos::new(pitch))
}

/// Sine and cosine of one angle, computed once and shared by every formula that needs them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SinCos<T> {
    pub sin: T,
    pub cos: T,
}

impl<T: Real> SinCos<T> {
    #[inline]
    pub(crate) fn new(angle: T) -> Self {
        let (sin, cos) = crate::math::sin_cos(angle);
        SinCos { sin, cos }
    }
}

/// [`matrix`] from the sines and cosines of yaw, lean and pitch.
#[inline]
pub(crate) fn matrix_from_sin_cos<T: Real>(
    yaw: SinCos<T>,
    lean: SinCos<T>,
    pitch: SinCos<T>,
) -> Matrix3<T> {
    let (sy, cy) = (yaw.sin, yaw.cos);
    let (sl, cl) = (lean.sin, lean.cos);
    let (sp, cp) = (pitch.sin, pitch.cos);
    Matrix3::new(
        cy * cp - sy * sl * sp,
        -sy * cl,
        cy * sp + sy * sl * cp,
        sy * cp + cy * sl * sp,
        cy * cl,
        sy * sp - cy * sl * cp,
        -cl * sp,
        sl,
        cl * cp,
    )
}

/// The matrix W with ω (body axes) = W · [yaw rate, lean rate, pitch rate].
#[inline]
pub fn rates_to_body<T: Real>(lean: T, pitch: T) -> Matrix3<T> {
    let (sl, cl) = crate::math::sin_cos(lean);
    let (sp, cp) = crate::math::sin_cos(pitch);
    let zero = T::zero();
    let one = T::one();
    Matrix3::new(-sp * cl, cp, zero, sl, zero, one, cp * cl, sp, zero)
}

/// [yaw rate, lean rate, pitch rate] from the body-axes angular velocity ω: the inverse of
/// [`rates_to_body`], singular at lean = ±90°.
#[inline]
pub fn body_to_rates<T: Real>(lean: T, pitch: T, omega: &Vector3<T>) -> Vector3<T> {
    body_to_rates_from_sin_cos(SinCos::new(lean), SinCos::new(pitch), omega)
}

/// [`body_to_rates`] from the sines and cosines of lean and pitch.
#[inline]
pub(crate) fn body_to_rates_from_sin_cos<T: Real>(
    lean: SinCos<T>,
    pitch: SinCos<T>,
    omega: &Vector3<T>,
) -> Vector3<T> {
    let (sl, cl) = (lean.sin, lean.cos);
    let (sp, cp) = (pitch.sin, pitch.cos);
    let yaw_rate = (-sp * omega.x + cp * omega.z) / cl;
    let lean_rate = cp * omega.x + sp * omega.z;
    let pitch_rate = omega.y - sl * yaw_rate;
    Vector3::new(yaw_rate, lean_rate, pitch_rate)
}

/// (yaw, lean, pitch) of a rotation matrix, the inverse of [`matrix`] for |lean| < 90°.
pub fn angles<T: Real>(r: &Matrix3<T>) -> Vector3<T> {
    let one = T::one();
    let lean = crate::math::asin(r[(2, 1)].clamp(-one, one));
    let yaw = crate::math::atan2(-r[(0, 1)], r[(1, 1)]);
    let pitch = crate::math::atan2(-r[(2, 0)], r[(2, 2)]);
    Vector3::new(yaw, lean, pitch)
}

/// Rotation by `angle` about the unit vector `axis` (Rodrigues).
pub fn axis_angle<T: Real>(axis: &Vector3<T>, angle: T) -> Matrix3<T> {
    let (s, c) = crate::math::sin_cos(angle);
    let k = skew(axis);
    Matrix3::identity() + k * s + k * k * (T::one() - c)
}

/// The cross-product matrix: `skew(a) b = a × b`.
#[inline]
pub fn skew<T: Real>(a: &Vector3<T>) -> Matrix3<T> {
    let zero = T::zero();
    Matrix3::new(zero, -a.z, a.y, a.z, zero, -a.x, -a.y, a.x, zero)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn angles_invert_matrix() {
        let (yaw, lean, pitch) = (2.5, -1.2, 3.0);
        let a = angles(&matrix(yaw, lean, pitch));
        assert_relative_eq!(a, Vector3::new(yaw, lean, pitch), epsilon = 1e-14);
    }

    #[test]
    fn rates_round_trip_and_match_rotation_derivative() {
        let (lean, pitch) = (0.4, -0.3);
        let rates = Vector3::new(0.7, -1.1, 2.3);
        let omega = rates_to_body(lean, pitch) * rates;
        assert_relative_eq!(body_to_rates(lean, pitch, &omega), rates, epsilon = 1e-14);
        // Ṙ = R [ω]× checked by central differences.
        let (yaw, h) = (0.9, 1e-6);
        let r = |t: f64| matrix(yaw + rates.x * t, lean + rates.y * t, pitch + rates.z * t);
        let r_dot = (r(h) - r(-h)) / (2.0 * h);
        assert_relative_eq!(r_dot, r(0.0) * skew(&omega), epsilon = 1e-8);
    }
}
