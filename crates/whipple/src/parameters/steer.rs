//! The front assembly's moment of inertia about the steer axis, I_Aλλ (Meijaard 2007,
//! Appendix A): a single number a torsional pendulum measures with the steer axis vertical and
//! the rear frame held, which a user may give instead of the front frame's I_Hzz
//! (BicycleParameters issue #65).
//!
//! The front assembly A is the front frame H and the front wheel F. About the steer axis,
//!
//! I_Aλλ = I_Hxx sin²λ + 2 I_Hxz sinλ cosλ + I_Hzz cos²λ + m_H d_H² + I_Fxx + m_F d_F²,
//!
//! with d_H and d_F the perpendicular distances of H's mass centre and of the front wheel's
//! centre from the steer axis (the wheel is axisymmetric, so its moment about any in-plane axis
//! through its centre is I_Fxx); Appendix A writes the same through A's combined mass centre,
//! and `linear::canonical` computes it there, the one home of the formula. One number fixes one
//! unknown: given I_Aλλ, every other benchmark parameter is kept as written (the geometry, both
//! wheels, H's mass and mass centre, and H's I_Hxx, I_Hyy, I_Hxz), and I_Hzz, on which I_Aλλ
//! depends linearly with the factor cos²λ, is derived. I_Hzz is the entry the steer-axis moment
//! weighs most (cos²λ, about 0.9 for a road bicycle's tilt), so the one such a measurement
//! determines best.

use crate::math::Real;

use super::BenchmarkParameters;
use crate::error::{Error, Result, short_number};
use crate::linear::Intermediates;

/// The key of the front assembly's steer-axis moment in parameter files, an alternative to
/// `IHzz`: `IAlamlam`, Meijaard 2007's I_Aλλ.
pub(crate) const STEER_INERTIA_KEY: &str = "IAlamlam";

impl<T: Real> BenchmarkParameters<T> {
    /// The front assembly's (front frame H and front wheel F) moment of inertia about the
    /// steer axis, I_Aλλ \[kg m²\] (Meijaard 2007, Appendix A): with d_H and d_F the distances
    /// of H's mass centre and of the front wheel's centre from the steer axis, I_Aλλ = I_Hxx
    /// sin²λ + 2 I_Hxz sinλ cosλ + I_Hzz cos²λ + m_H d_H² + I_Fxx + m_F d_F². What a torsional
    /// pendulum about the steer axis measures with the rear frame held (the linearized model's
    /// M_δδ adds the rear frame's yaw through the trail). Not finite for a massless front
    /// assembly, which [`BenchmarkParameters::check`] refuses.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// let b = BenchmarkParameters::meijaard2007();
    /// assert!((b.front_assembly_steer_inertia() - 0.15389731601426776).abs() < 1e-15);
    /// ```
    pub fn front_assembly_steer_inertia(&self) -> T {
        Intermediates::new(self).i_all
    }
}

impl BenchmarkParameters {
    /// The bicycle with I_Hzz derived from the front assembly's moment about the steer axis
    /// `i_a` (I_Aλλ \[kg m²\], key `IAlamlam`; see
    /// [`BenchmarkParameters::front_assembly_steer_inertia`]), every other parameter kept (the
    /// geometry, both wheels, H's mass, mass centre, I_Hxx, I_Hyy and I_Hxz); the value of
    /// `i_hzz` on entry is ignored. I_Hzz is the entry the steer-axis moment weighs most (by
    /// cos²λ), so the one a measurement of it determines best.
    ///
    /// Errors, naming `IAlamlam`: a number that is not finite or is negative; a moment smaller
    /// than the least the assembly can have with the other parameters as given, which is what
    /// the front wheel and H's mass at its centre contribute plus the least H's own moment can
    /// be (with I_Hzz = I_Hxz² / I_Hxx, below which H's in-plane tensor is not positive
    /// semi-definite; 0 where I_Hxx = 0). A steer axis tilt outside (−π/2, π/2) is an error
    /// naming `lam`, a massless front assembly one naming `mH, mF`.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// let b = BenchmarkParameters::meijaard2007();
    /// let i_a = b.front_assembly_steer_inertia();
    /// let back = BenchmarkParameters { i_hzz: 0.0, ..b }.with_front_assembly_steer_inertia(i_a)?;
    /// assert!((back.i_hzz - b.i_hzz).abs() < 1e-15);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn with_front_assembly_steer_inertia(self, i_a: f64) -> Result<Self> {
        let invalid = |rule: String| Error::InvalidParameter {
            field: STEER_INERTIA_KEY.into(),
            value: i_a,
            rule,
        };
        if !i_a.is_finite() {
            return Err(invalid("must be a finite number".into()));
        }
        if i_a < 0.0 {
            return Err(invalid("must not be negative".into()));
        }
        let c = crate::math::cos(self.lambda);
        if !(c > 0.0 && self.lambda.is_finite()) {
            return Err(Error::InvalidParameter {
                field: "lam".into(),
                value: self.lambda,
                rule: format!(
                    "must lie strictly between -pi/2 and pi/2 rad for {STEER_INERTIA_KEY} to \
                     give IHzz"
                ),
            });
        }
        let massive = self.m_h + self.m_f > 0.0; // false for NaN
        if !massive {
            return Err(Error::InvalidBicycle {
                fields: "mH, mF".into(),
                rule: format!(
                    "a front assembly without mass has no moment about the steer axis to give \
                     as {STEER_INERTIA_KEY}"
                ),
            });
        }
        // I_Aλλ is linear in I_Hzz with the factor cos²λ.
        let without = BenchmarkParameters { i_hzz: 0.0, ..self }.front_assembly_steer_inertia();
        let least_hzz = if self.i_hxx > 0.0 {
            self.i_hxz * self.i_hxz / self.i_hxx
        } else {
            0.0
        };
        let least = without + least_hzz * c * c;
        if i_a < least {
            return Err(invalid(format!(
                "is less than {} kg m^2, the least the front assembly can have about the steer \
                 axis with its other parameters as given: the front wheel and the front frame's \
                 mass at its centre contribute {}, and the front frame's own IHzz cannot be \
                 below IHxz^2/IHxx = {} (else its inertia tensor is not positive \
                 semi-definite)",
                short_number(least),
                short_number(
                    without
                        - self.i_hxx * crate::math::sin(self.lambda).powi(2)
                        - 2.0 * self.i_hxz * crate::math::sin(self.lambda) * c
                ),
                short_number(least_hzz)
            )));
        }
        let i_hzz = (i_a - without) / (c * c);
        Ok(BenchmarkParameters { i_hzz, ..self })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets::PRESETS;

    /// An independent I_Aλλ: the sum over H and F about the steer axis, each body's own moment
    /// about the parallel axis through its centre plus its mass times the squared distance.
    fn by_parts(b: &BenchmarkParameters) -> f64 {
        let (s, c) = crate::math::sin_cos(b.lambda);
        let distance = |x: f64, z: f64| (x - b.w - b.c) * c - z * s;
        let (d_f, d_h) = (distance(b.w, -b.r_f), distance(b.x_h, b.z_h));
        b.i_fxx
            + b.m_f * d_f * d_f
            + b.m_h * d_h * d_h
            + b.i_hxx * s * s
            + 2.0 * b.i_hxz * s * c
            + b.i_hzz * c * c
    }

    /// For every benchmark-form preset: I_Aλλ (Appendix A, through A's combined centre) equals
    /// the sum by parts, and entering it as the steer-axis moment gives I_Hzz back.
    #[test]
    fn identity_for_every_preset() {
        for preset in PRESETS {
            let Ok(b) = preset.bicycle().benchmark() else {
                continue;
            };
            let i_a = b.front_assembly_steer_inertia();
            let parts = by_parts(&b);
            assert!(
                (i_a - parts).abs() <= 1e-12 * i_a.abs(),
                "{}: {i_a} vs {parts}",
                preset.name
            );
            let back = BenchmarkParameters { i_hzz: -7.0, ..b }
                .with_front_assembly_steer_inertia(i_a)
                .expect("the bicycle's own moment is possible");
            let scale = b.i_hxx.abs().max(b.i_hzz.abs()).max(i_a);
            assert!(
                (back.i_hzz - b.i_hzz).abs() <= 1e-12 * scale,
                "{}: {} vs {}",
                preset.name,
                back.i_hzz,
                b.i_hzz
            );
            assert_eq!(
                BenchmarkParameters {
                    i_hzz: b.i_hzz,
                    ..back
                },
                b
            );
        }
    }

    #[test]
    fn impossible_moments_are_refused() {
        let b = BenchmarkParameters::meijaard2007();
        let e = b.with_front_assembly_steer_inertia(-1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            Error::InvalidParameter {
                field: "IAlamlam".into(),
                value: -1.0,
                rule: "must not be negative".into()
            }
            .to_string()
        );
        // The wheel alone: IFxx + mF dF^2 with dF = rF sin λ − c cos λ; less than the least.
        let (s, c) = crate::math::sin_cos(b.lambda);
        let d_f = b.r_f * s - b.c * c;
        let wheel = b.i_fxx + b.m_f * d_f * d_f;
        let message = b
            .with_front_assembly_steer_inertia(wheel)
            .unwrap_err()
            .to_string();
        assert!(message.contains("IAlamlam"), "{message}");
        assert!(
            message.contains("the least the front assembly can have"),
            "{message}"
        );
        let least_hzz = b.i_hxz * b.i_hxz / b.i_hxx;
        assert!(message.contains(&short_number(least_hzz)), "{message}");
        // The least itself: possible, and H's in-plane tensor singular.
        let least = by_parts(&BenchmarkParameters {
            i_hzz: least_hzz,
            ..b
        });
        let edge = b
            .with_front_assembly_steer_inertia(least * (1.0 + 1e-13))
            .unwrap();
        let det = edge.i_hxx * edge.i_hzz - edge.i_hxz * edge.i_hxz;
        assert!(det.abs() < 1e-9 * edge.i_hxx * edge.i_hxx, "{det}");
        assert!(
            b.with_front_assembly_steer_inertia(least * (1.0 - 1e-9))
                .is_err()
        );
        assert!(b.with_front_assembly_steer_inertia(f64::NAN).is_err());
    }
}
