//! The 25 benchmark parameters of Meijaard et al. 2007 (Table 1) plus gravity, and the rules
//! a bicycle must satisfy before any computation.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// Benchmark parameters of the Whipple bicycle (Meijaard, Papadopoulos, Ruina & Schwab 2007,
/// Proc. R. Soc. A 463:1955–1982, Table 1). SI units, radians.
///
/// Axes: x forward, y to the right, z down, origin at the rear wheel's ground contact in the
/// upright reference configuration; so `z_b < 0` puts the rear body's centre of mass above the
/// ground. Four bodies: rear wheel R, rear frame with rider B, front frame (fork and handlebar)
/// H, front wheel F. The file keys (serde names) are those of the paper and of
/// BicycleParameters: `w`, `c`, `lam`, `g`, `rR`, `mR`, `IRxx`, …
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BenchmarkParameters {
    /// w: wheelbase, the distance between the wheel contacts [m].
    pub w: f64,
    /// c: trail, the horizontal distance from the front contact to the point where the steer
    /// axis meets the ground, positive when the contact is behind that point [m].
    pub c: f64,
    /// λ: steer axis tilt from the vertical (π/2 − head angle) [rad].
    #[serde(rename = "lam")]
    pub lambda: f64,
    /// g: gravitational acceleration [m/s²].
    pub g: f64,
    /// r_R: rear wheel radius [m] (0 for a skate).
    #[serde(rename = "rR")]
    pub r_r: f64,
    /// m_R: rear wheel mass [kg].
    #[serde(rename = "mR")]
    pub m_r: f64,
    /// I_Rxx: rear wheel moment of inertia about a diameter (= I_Rzz) [kg m²].
    #[serde(rename = "IRxx")]
    pub i_rxx: f64,
    /// I_Ryy: rear wheel moment of inertia about its axle (polar, spin) [kg m²].
    #[serde(rename = "IRyy")]
    pub i_ryy: f64,
    /// x_B: rear body centre of mass, forward of the rear contact [m].
    #[serde(rename = "xB")]
    pub x_b: f64,
    /// z_B: rear body centre of mass, below the ground (negative: above) [m].
    #[serde(rename = "zB")]
    pub z_b: f64,
    /// m_B: rear body (frame and rider) mass [kg].
    #[serde(rename = "mB")]
    pub m_b: f64,
    /// I_Bxx: rear body moment of inertia about x through its centre of mass [kg m²].
    #[serde(rename = "IBxx")]
    pub i_bxx: f64,
    /// I_Byy: rear body moment of inertia about y (pitch) [kg m²]. Not seen by the linear model.
    #[serde(rename = "IByy")]
    pub i_byy: f64,
    /// I_Bzz: rear body moment of inertia about z (yaw) [kg m²].
    #[serde(rename = "IBzz")]
    pub i_bzz: f64,
    /// I_Bxz: rear body product of inertia, the x-z entry of its inertia tensor
    /// (I_Bxz = −∫ x z dm) [kg m²].
    #[serde(rename = "IBxz")]
    pub i_bxz: f64,
    /// x_H: front frame centre of mass, forward of the rear contact [m].
    #[serde(rename = "xH")]
    pub x_h: f64,
    /// z_H: front frame centre of mass, below the ground (negative: above) [m].
    #[serde(rename = "zH")]
    pub z_h: f64,
    /// m_H: front frame (fork and handlebar) mass [kg].
    #[serde(rename = "mH")]
    pub m_h: f64,
    /// I_Hxx: front frame moment of inertia about x [kg m²].
    #[serde(rename = "IHxx")]
    pub i_hxx: f64,
    /// I_Hyy: front frame moment of inertia about y [kg m²]. Not seen by the linear model.
    #[serde(rename = "IHyy")]
    pub i_hyy: f64,
    /// I_Hzz: front frame moment of inertia about z [kg m²].
    #[serde(rename = "IHzz")]
    pub i_hzz: f64,
    /// I_Hxz: front frame product of inertia [kg m²].
    #[serde(rename = "IHxz")]
    pub i_hxz: f64,
    /// r_F: front wheel radius [m] (0 for a skate).
    #[serde(rename = "rF")]
    pub r_f: f64,
    /// m_F: front wheel mass [kg].
    #[serde(rename = "mF")]
    pub m_f: f64,
    /// I_Fxx: front wheel moment of inertia about a diameter (= I_Fzz) [kg m²].
    #[serde(rename = "IFxx")]
    pub i_fxx: f64,
    /// I_Fyy: front wheel moment of inertia about its axle (polar, spin) [kg m²].
    #[serde(rename = "IFyy")]
    pub i_fyy: f64,
}

/// Relative allowance for round-off when checking the triangle inequality of principal moments
/// (a thin disk, I_yy = 2 I_xx, sits exactly on it).
const TRIANGLE_ROUND_OFF: f64 = 1e-9;

impl BenchmarkParameters {
    /// The parameters as (file key, value) pairs in the order of Meijaard 2007 Table 1.
    pub fn fields(&self) -> [(&'static str, f64); 26] {
        [
            ("w", self.w),
            ("c", self.c),
            ("lam", self.lambda),
            ("g", self.g),
            ("rR", self.r_r),
            ("mR", self.m_r),
            ("IRxx", self.i_rxx),
            ("IRyy", self.i_ryy),
            ("xB", self.x_b),
            ("zB", self.z_b),
            ("mB", self.m_b),
            ("IBxx", self.i_bxx),
            ("IByy", self.i_byy),
            ("IBzz", self.i_bzz),
            ("IBxz", self.i_bxz),
            ("xH", self.x_h),
            ("zH", self.z_h),
            ("mH", self.m_h),
            ("IHxx", self.i_hxx),
            ("IHyy", self.i_hyy),
            ("IHzz", self.i_hzz),
            ("IHxz", self.i_hxz),
            ("rF", self.r_f),
            ("mF", self.m_f),
            ("IFxx", self.i_fxx),
            ("IFyy", self.i_fyy),
        ]
    }

    /// Checks every rule a bicycle must satisfy before any computation:
    /// all numbers finite; g > 0; w > 0; wheel radii ≥ 0; λ strictly inside (−π/2, π/2);
    /// masses ≥ 0 with the rear (R + B) and front (H + F) assemblies of positive mass; every
    /// inertia tensor positive semi-definite with principal moments obeying the triangle
    /// inequality; a wheel of zero radius has no spin inertia; the mass matrix M of the
    /// linearized model positive definite.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// let mut bike = BenchmarkParameters::meijaard2007();
    /// assert!(bike.validate().is_ok());
    /// bike.m_b = -1.0;
    /// let message = bike.validate().unwrap_err().to_string();
    /// assert!(message.contains("mB"));
    /// ```
    pub fn validate(&self) -> Result<()> {
        for (field, value) in self.fields() {
            if !value.is_finite() {
                return Err(invalid(field, value, "must be a finite number"));
            }
        }
        positive("g", self.g)?;
        positive("w", self.w)?;
        non_negative("rR", self.r_r)?;
        non_negative("rF", self.r_f)?;
        if self.lambda.abs() >= std::f64::consts::FRAC_PI_2 {
            return Err(invalid(
                "lam",
                self.lambda,
                "the steer axis tilt must lie strictly between -pi/2 and pi/2 rad",
            ));
        }
        for (field, value) in [
            ("mR", self.m_r),
            ("mB", self.m_b),
            ("mH", self.m_h),
            ("mF", self.m_f),
        ] {
            non_negative(field, value)?;
        }
        if self.m_r + self.m_b <= 0.0 {
            return Err(Error::InvalidBicycle {
                fields: "mR, mB".into(),
                rule: "the rear assembly (rear wheel and rear body) must have a positive mass"
                    .into(),
            });
        }
        if self.m_h + self.m_f <= 0.0 {
            return Err(Error::InvalidBicycle {
                fields: "mH, mF".into(),
                rule: "the front assembly (front frame and front wheel) must have a positive mass"
                    .into(),
            });
        }
        wheel_inertia("R", self.r_r, self.i_rxx, self.i_ryy)?;
        wheel_inertia("F", self.r_f, self.i_fxx, self.i_fyy)?;
        frame_inertia("B", self.i_bxx, self.i_byy, self.i_bzz, self.i_bxz)?;
        frame_inertia("H", self.i_hxx, self.i_hyy, self.i_hzz, self.i_hxz)?;

        let m = crate::linear::Canonical::from_unchecked(self).m;
        let det = m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)];
        if !(m[(0, 0)] > 0.0 && det > 0.0) {
            return Err(Error::InvalidBicycle {
                fields: "all masses, inertias and geometry".into(),
                rule: format!(
                    "the mass matrix M of the linearized model must be positive definite, \
                     but M = [[{}, {}], [{}, {}]] (det {det:e})",
                    m[(0, 0)],
                    m[(0, 1)],
                    m[(1, 0)],
                    m[(1, 1)]
                ),
            });
        }
        Ok(())
    }
}

fn invalid(field: &str, value: f64, rule: &str) -> Error {
    Error::InvalidParameter {
        field: field.to_string(),
        value,
        rule: rule.to_string(),
    }
}

fn positive(field: &str, value: f64) -> Result<()> {
    if value > 0.0 {
        Ok(())
    } else {
        Err(invalid(field, value, "must be greater than zero"))
    }
}

fn non_negative(field: &str, value: f64) -> Result<()> {
    if value >= 0.0 {
        Ok(())
    } else {
        Err(invalid(field, value, "must not be negative"))
    }
}

/// Checks principal moments (a, b, c) of one body: each ≥ 0 and each ≤ the sum of the others.
pub(crate) fn principal_moments(fields: [&str; 3], moments: [f64; 3]) -> Result<()> {
    let scale = moments.iter().map(|m| m.abs()).sum::<f64>();
    for (i, (&field, &value)) in fields.iter().zip(moments.iter()).enumerate() {
        if value < -TRIANGLE_ROUND_OFF * scale {
            return Err(invalid(
                field,
                value,
                "principal moments of inertia must not be negative (the tensor must be positive semi-definite)",
            ));
        }
        let others = moments[(i + 1) % 3] + moments[(i + 2) % 3];
        if value > others + TRIANGLE_ROUND_OFF * scale {
            return Err(Error::InvalidBicycle {
                fields: fields.join(", "),
                rule: format!(
                    "principal moments of inertia ({}, {}, {}) break the triangle inequality: \
                     {field} = {value} exceeds the sum of the other two, {others}",
                    moments[0], moments[1], moments[2]
                ),
            });
        }
    }
    Ok(())
}

fn wheel_inertia(wheel: &str, radius: f64, i_xx: f64, i_yy: f64) -> Result<()> {
    let xx = format!("I{wheel}xx");
    let yy = format!("I{wheel}yy");
    non_negative(&xx, i_xx)?;
    non_negative(&yy, i_yy)?;
    principal_moments([&xx, &yy, &xx], [i_xx, i_yy, i_xx])?;
    if radius == 0.0 && i_yy != 0.0 {
        return Err(invalid(
            &yy,
            i_yy,
            "a wheel of zero radius (a skate) cannot have a spin moment of inertia: its spin rate would be infinite",
        ));
    }
    Ok(())
}

fn frame_inertia(body: &str, i_xx: f64, i_yy: f64, i_zz: f64, i_xz: f64) -> Result<()> {
    let xx = format!("I{body}xx");
    let yy = format!("I{body}yy");
    let zz = format!("I{body}zz");
    non_negative(&xx, i_xx)?;
    non_negative(&yy, i_yy)?;
    non_negative(&zz, i_zz)?;
    // Principal moments of the x-z block.
    let mean = 0.5 * (i_xx + i_zz);
    let radius = (0.25 * (i_xx - i_zz).powi(2) + i_xz * i_xz).sqrt();
    let (i1, i3) = (mean + radius, mean - radius);
    let scale = i_xx + i_yy + i_zz;
    if i3 < -TRIANGLE_ROUND_OFF * scale {
        return Err(Error::InvalidBicycle {
            fields: format!("{xx}, {zz}, I{body}xz"),
            rule: format!(
                "the inertia tensor is not positive semi-definite: I{body}xz² = {} exceeds {xx}·{zz} = {}",
                i_xz * i_xz,
                i_xx * i_zz
            ),
        });
    }
    principal_moments(
        [
            &format!("I{body} (first principal moment in the x-z plane)"),
            &yy,
            &format!("I{body} (second principal moment in the x-z plane)"),
        ],
        [i1, i_yy, i3],
    )
}
