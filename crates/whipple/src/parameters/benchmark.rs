//! The 25 benchmark parameters of Meijaard et al. 2007 (Table 1) plus gravity, and the rules
//! a bicycle must satisfy before any computation.

use serde::{Deserialize, Serialize};

use super::check::{Notice, percent};
use super::table::{Form, ParameterInfo};
use crate::error::{Error, Result, short_number};

/// The benchmark form's parameters, one row each: field, file key, symbol, unit, whether the
/// linear model sees it, description. The struct, its serde names, its field list and
/// [`BENCHMARK_TABLE`] are all generated from these rows.
macro_rules! benchmark_parameters {
    ($( $field:ident, $key:literal, $symbol:literal, $unit:literal, $linear:literal, $doc:literal; )*) => {
        /// Benchmark parameters of the Whipple bicycle (Meijaard, Papadopoulos, Ruina & Schwab
        /// 2007, Proc. R. Soc. A 463:1955–1982, Table 1). SI units, radians.
        ///
        /// Axes: x forward, y to the right, z down, origin at the rear wheel's ground contact in
        /// the upright reference configuration; so `z_b < 0` puts the rear body's centre of mass
        /// above the ground. Four bodies: rear wheel R, rear frame with rider B, front frame
        /// (fork and handlebar) H, front wheel F. The file keys (serde names) are those of the
        /// paper and of BicycleParameters: `w`, `c`, `lam`, `g`, `rR`, `mR`, `IRxx`, … (see
        /// `BENCHMARK_TABLE`).
        ///
        /// Generic over the scalar so that dual numbers run through the same conversion and
        /// linear model as `f64` (exact derivatives); `BenchmarkParameters` alone is the `f64` one.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct BenchmarkParameters<T = f64> {
            $(
                #[doc = concat!($symbol, ": ", $doc, " \\[", $unit, "\\].")]
                #[serde(rename = $key)]
                pub $field: T,
            )*
        }

        /// Every benchmark parameter in the order of Meijaard 2007 Table 1.
        pub(crate) const BENCHMARK_TABLE: [ParameterInfo; 26] = [
            $(
                ParameterInfo {
                    name: stringify!($field),
                    key: $key,
                    path: $key,
                    symbol: $symbol,
                    unit: $unit,
                    description: $doc,
                    form: Form::Benchmark,
                    linear: $linear,
                },
            )*
        ];

        impl<T: Copy> BenchmarkParameters<T> {
            /// The values in the order of `BENCHMARK_TABLE`.
            pub fn to_array(&self) -> [T; 26] {
                [$(self.$field,)*]
            }

            /// The parameters from values in the order of `BENCHMARK_TABLE`.
            pub fn from_array(values: [T; 26]) -> Self {
                let [$($field,)*] = values;
                BenchmarkParameters { $($field,)* }
            }
        }
    };
}

benchmark_parameters! {
    w, "w", "w", "m", true, "wheelbase, the distance between the wheel contacts";
    c, "c", "c", "m", true, "trail, from the front contact back to where the steer axis meets the ground (positive: contact behind it)";
    lambda, "lam", "λ", "rad", true, "steer axis tilt from the vertical (π/2 − head angle)";
    g, "g", "g", "m/s^2", true, "gravitational acceleration";
    r_r, "rR", "r_R", "m", true, "rear wheel radius (0 for a skate)";
    m_r, "mR", "m_R", "kg", true, "rear wheel mass";
    i_rxx, "IRxx", "I_Rxx", "kg m^2", true, "rear wheel moment of inertia about a diameter (= I_Rzz)";
    i_ryy, "IRyy", "I_Ryy", "kg m^2", true, "rear wheel moment of inertia about its axle (spin)";
    x_b, "xB", "x_B", "m", true, "rear body centre of mass, forward of the rear contact";
    z_b, "zB", "z_B", "m", true, "rear body centre of mass, below the ground (negative: above)";
    m_b, "mB", "m_B", "kg", true, "rear body (frame and rider) mass";
    i_bxx, "IBxx", "I_Bxx", "kg m^2", true, "rear body moment of inertia about x through its centre of mass";
    i_byy, "IByy", "I_Byy", "kg m^2", false, "rear body moment of inertia about y (pitch; not seen by the linear model)";
    i_bzz, "IBzz", "I_Bzz", "kg m^2", true, "rear body moment of inertia about z (yaw)";
    i_bxz, "IBxz", "I_Bxz", "kg m^2", true, "rear body product of inertia, the x-z entry of its tensor (−∫ x z dm)";
    x_h, "xH", "x_H", "m", true, "front frame centre of mass, forward of the rear contact";
    z_h, "zH", "z_H", "m", true, "front frame centre of mass, below the ground (negative: above)";
    m_h, "mH", "m_H", "kg", true, "front frame (fork and handlebar) mass";
    i_hxx, "IHxx", "I_Hxx", "kg m^2", true, "front frame moment of inertia about x";
    i_hyy, "IHyy", "I_Hyy", "kg m^2", false, "front frame moment of inertia about y (not seen by the linear model)";
    i_hzz, "IHzz", "I_Hzz", "kg m^2", true, "front frame moment of inertia about z";
    i_hxz, "IHxz", "I_Hxz", "kg m^2", true, "front frame product of inertia, the x-z entry of its tensor";
    r_f, "rF", "r_F", "m", true, "front wheel radius (0 for a skate)";
    m_f, "mF", "m_F", "kg", true, "front wheel mass";
    i_fxx, "IFxx", "I_Fxx", "kg m^2", true, "front wheel moment of inertia about a diameter (= I_Fzz)";
    i_fyy, "IFyy", "I_Fyy", "kg m^2", true, "front wheel moment of inertia about its axle (spin)";
}

/// Relative allowance for round-off when checking the triangle inequality of principal moments
/// (a thin disk, I_yy = 2 I_xx, sits exactly on it).
const TRIANGLE_ROUND_OFF: f64 = 1e-9;

impl BenchmarkParameters {
    /// The parameters as (file key, value) pairs in the order of Meijaard 2007 Table 1.
    pub fn fields(&self) -> [(&'static str, f64); 26] {
        let values = self.to_array();
        std::array::from_fn(|i| (BENCHMARK_TABLE[i].key, values[i]))
    }

    /// The value of the parameter with this file key (`IBxx`).
    pub fn get(&self, key: &str) -> Option<f64> {
        super::table::index_of(Form::Benchmark, key).map(|i| self.to_array()[i])
    }

    /// Sets the parameter with this file key; `false` for an unknown key.
    pub fn set(&mut self, key: &str, value: f64) -> bool {
        match super::table::index_of(Form::Benchmark, key) {
            Some(i) => {
                let mut values = self.to_array();
                values[i] = value;
                *self = Self::from_array(values);
                true
            }
            None => false,
        }
    }

    /// Checks every rule a bicycle must satisfy before any computation (see
    /// [`BenchmarkParameters::check`]); warnings do not fail it.
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
        self.check().map(|_| ())
    }

    /// Checks the bicycle and returns its warnings. Refused (errors): a number that is not
    /// finite; g ≤ 0; w ≤ 0; a negative wheel radius; λ outside (−π/2, π/2); a negative mass; a
    /// massless rear (R + B) or front (H + F) assembly; a body of zero mass with inertia; an
    /// inertia tensor that is not positive semi-definite; a spinning skate (zero radius with
    /// spin inertia); a mass matrix M of the linearized model that is not positive definite or
    /// overflows. Warned about (the equations stay well defined): principal moments that break
    /// the triangle inequality (as measured bicycles' do within their measurement error), a
    /// centre of mass below the ground, wheels that overlap (w < 2·√(rR·rF)).
    pub fn check(&self) -> Result<Vec<Notice>> {
        self.check_with_canonical().map(|(notices, _)| notices)
    }

    /// [`BenchmarkParameters::check`] that also hands back the canonical matrices it formed to
    /// test M (so that a design map forms them once per design).
    pub(crate) fn check_with_canonical(&self) -> Result<(Vec<Notice>, crate::linear::Canonical)> {
        let mut notices = Vec::new();
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
        // Slices, not vectors: a valid bicycle is checked without touching the heap (design
        // maps check a million of them).
        let bodies: [BodyInertia<'_>; 4] = [
            (
                "the rear wheel R",
                "mR",
                self.m_r,
                &[("IRxx", self.i_rxx), ("IRyy", self.i_ryy)],
            ),
            (
                "the rear body B",
                "mB",
                self.m_b,
                &[
                    ("IBxx", self.i_bxx),
                    ("IByy", self.i_byy),
                    ("IBzz", self.i_bzz),
                    ("IBxz", self.i_bxz),
                ],
            ),
            (
                "the front frame H",
                "mH",
                self.m_h,
                &[
                    ("IHxx", self.i_hxx),
                    ("IHyy", self.i_hyy),
                    ("IHzz", self.i_hzz),
                    ("IHxz", self.i_hxz),
                ],
            ),
            (
                "the front wheel F",
                "mF",
                self.m_f,
                &[("IFxx", self.i_fxx), ("IFyy", self.i_fyy)],
            ),
        ];
        for (body, mass_key, mass, inertia) in bodies {
            zero_mass_inertia(body, mass_key, mass, inertia)?;
        }
        wheel_inertia(&REAR_WHEEL, self.r_r, self.i_rxx, self.i_ryy, &mut notices)?;
        wheel_inertia(&FRONT_WHEEL, self.r_f, self.i_fxx, self.i_fyy, &mut notices)?;
        frame_inertia(
            &REAR_BODY,
            self.i_bxx,
            self.i_byy,
            self.i_bzz,
            self.i_bxz,
            &mut notices,
        )?;
        frame_inertia(
            &FRONT_FRAME,
            self.i_hxx,
            self.i_hyy,
            self.i_hzz,
            self.i_hxz,
            &mut notices,
        )?;
        for (key, z, body) in [
            ("zB", self.z_b, "rear body B"),
            ("zH", self.z_h, "front frame H"),
        ] {
            if z > 0.0 {
                notices.push(Notice::warning(
                    key,
                    format!(
                        "the centre of mass of the {body} lies {} m below the ground (z points down)",
                        short_number(z)
                    ),
                    None,
                    "every analysis (the equations stay well defined)",
                ));
            }
        }
        // Wheel discs in the plane of the frame, centres at heights rR and rF a wheelbase
        // apart: they overlap where (rR + rF)² > w² + (rR − rF)², that is w² < 4 rR rF.
        if self.w * self.w < 4.0 * self.r_r * self.r_f {
            notices.push(Notice::warning(
                "w",
                format!(
                    "the wheels overlap: a wheelbase of {} m is shorter than {} m, the least \
                     that keeps wheels of radii {} m and {} m apart (2·√(rR·rF)); no real \
                     bicycle is built so",
                    short_number(self.w),
                    short_number(2.0 * (self.r_r * self.r_f).sqrt()),
                    short_number(self.r_r),
                    short_number(self.r_f)
                ),
                None,
                "every analysis (the equations stay well defined)",
            ));
        }

        let canonical = crate::linear::Canonical::from_unchecked(self);
        let m = canonical.m;
        let det = m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)];
        if m.iter().any(|x| !x.is_finite()) || !det.is_finite() {
            // Overflow: name the largest number, the likely culprit.
            let (field, value) = self
                .fields()
                .into_iter()
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .unwrap_or(("w", self.w));
            return Err(invalid(
                field,
                value,
                "is too large: the mass matrix M of the linearized model overflows double precision",
            ));
        }
        if !(m[(0, 0)] > 0.0 && det > 0.0) {
            return Err(Error::InvalidBicycle {
                fields: "all masses, inertias and geometry".into(),
                rule: format!(
                    "the mass matrix M of the linearized model must be positive definite, \
                     but M = [[{}, {}], [{}, {}]] (det {det:e})",
                    short_number(m[(0, 0)]),
                    short_number(m[(0, 1)]),
                    short_number(m[(1, 0)]),
                    short_number(m[(1, 1)])
                ),
            });
        }
        Ok((notices, canonical))
    }
}

/// A body's words, mass key, mass and moments of inertia (key, value), for the zero-mass check.
type BodyInertia<'a> = (&'a str, &'a str, f64, &'a [(&'a str, f64)]);

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

/// A body of zero mass cannot have inertia: it names the body and the first non-zero moment.
pub(crate) fn zero_mass_inertia(
    body: &str,
    mass_key: &str,
    mass: f64,
    inertia: &[(&str, f64)],
) -> Result<()> {
    if mass == 0.0 {
        if let Some((key, value)) = inertia.iter().find(|(_, v)| *v != 0.0) {
            return Err(Error::InvalidBicycle {
                fields: format!("{mass_key}, {key}"),
                rule: format!(
                    "{body} has zero mass ({mass_key} = 0) but a moment of inertia \
                     ({key} = {}): a body without mass has no inertia; give its mass or set its \
                     inertia to zero",
                    short_number(*value)
                ),
            });
        }
    }
    Ok(())
}

/// Checks principal moments (a, b, c) of one body: each ≥ 0 (an error otherwise) and each ≤ the
/// sum of the others (a warning otherwise, with the size of the violation in percent).
pub(crate) fn principal_moments(
    fields: [&str; 3],
    moments: [f64; 3],
    affects: &str,
    notices: &mut Vec<Notice>,
) -> Result<()> {
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
            let pct = percent(value - others, others);
            notices.push(Notice::warning(
                field,
                format!(
                    "the principal moments of inertia ({}, {}, {}) break the triangle inequality: \
                     {field} = {} exceeds the sum of the other two, {}, by {:.3} % (no rigid body \
                     has such a tensor; measured ones may, within their error)",
                    short_number(moments[0]),
                    short_number(moments[1]),
                    short_number(moments[2]),
                    short_number(value),
                    short_number(others),
                    pct
                ),
                Some(pct),
                affects,
            ));
            break;
        }
    }
    Ok(())
}

/// The file keys of a wheel's moments of inertia (static, so that checking allocates nothing).
struct WheelKeys {
    xx: &'static str,
    yy: &'static str,
}

const REAR_WHEEL: WheelKeys = WheelKeys {
    xx: "IRxx",
    yy: "IRyy",
};
const FRONT_WHEEL: WheelKeys = WheelKeys {
    xx: "IFxx",
    yy: "IFyy",
};

/// The file keys of a frame's inertia tensor and the words its warnings use.
struct FrameKeys {
    xx: &'static str,
    yy: &'static str,
    zz: &'static str,
    xz: &'static str,
    first: &'static str,
    second: &'static str,
    affects: &'static str,
}

macro_rules! frame_keys {
    ($b:literal) => {
        FrameKeys {
            xx: concat!("I", $b, "xx"),
            yy: concat!("I", $b, "yy"),
            zz: concat!("I", $b, "zz"),
            xz: concat!("I", $b, "xz"),
            first: concat!(
                "I",
                $b,
                "xx, I",
                $b,
                "zz, I",
                $b,
                "xz (first principal moment in the x-z plane)"
            ),
            second: concat!(
                "I",
                $b,
                "xx, I",
                $b,
                "zz, I",
                $b,
                "xz (second principal moment in the x-z plane)"
            ),
            affects: concat!(
                "only the non-linear model (simulate, validate), which still runs; the linear \
                 model (matrices, eig, modes, speeds, sensitivity) never sees I",
                $b,
                "yy"
            ),
        }
    };
}

const REAR_BODY: FrameKeys = frame_keys!("B");
const FRONT_FRAME: FrameKeys = frame_keys!("H");
/// The rider's upper body G of the rider-lean model: the non-linear model and its linearization
/// see every entry of its tensor.
const UPPER_BODY: FrameKeys = FrameKeys {
    affects: "the rider-lean model (non-linear and linearized), which still runs",
    ..frame_keys!("G")
};

/// The checks of a frame's tensor ([`BenchmarkParameters::check`]'s for B and H) applied to the
/// rider's upper body G, under the keys `IGxx`, `IGyy`, `IGzz`, `IGxz`.
pub(crate) fn upper_body_inertia(
    i_xx: f64,
    i_yy: f64,
    i_zz: f64,
    i_xz: f64,
    notices: &mut Vec<Notice>,
) -> Result<()> {
    frame_inertia(&UPPER_BODY, i_xx, i_yy, i_zz, i_xz, notices)
}

fn wheel_inertia(
    keys: &WheelKeys,
    radius: f64,
    i_xx: f64,
    i_yy: f64,
    notices: &mut Vec<Notice>,
) -> Result<()> {
    let (xx, yy) = (keys.xx, keys.yy);
    non_negative(xx, i_xx)?;
    non_negative(yy, i_yy)?;
    principal_moments(
        [xx, yy, xx],
        [i_xx, i_yy, i_xx],
        "the linear model (through the wheel's gyroscopic term) and the non-linear model; both stay well defined",
        notices,
    )?;
    if radius == 0.0 && i_yy != 0.0 {
        return Err(invalid(
            yy,
            i_yy,
            "a wheel of zero radius (a skate) cannot have a spin moment of inertia: its spin rate would be infinite",
        ));
    }
    Ok(())
}

fn frame_inertia(
    keys: &FrameKeys,
    i_xx: f64,
    i_yy: f64,
    i_zz: f64,
    i_xz: f64,
    notices: &mut Vec<Notice>,
) -> Result<()> {
    let (xx, yy, zz, xz) = (keys.xx, keys.yy, keys.zz, keys.xz);
    non_negative(xx, i_xx)?;
    non_negative(yy, i_yy)?;
    non_negative(zz, i_zz)?;
    // Principal moments of the x-z block.
    let mean = 0.5 * (i_xx + i_zz);
    let radius = (0.25 * (i_xx - i_zz).powi(2) + i_xz * i_xz).sqrt();
    let (i1, i3) = (mean + radius, mean - radius);
    let scale = i_xx + i_yy + i_zz;
    if i3 < -TRIANGLE_ROUND_OFF * scale {
        return Err(Error::InvalidBicycle {
            fields: format!("{xx}, {zz}, {xz}"),
            rule: format!(
                "the inertia tensor is not positive semi-definite: {xz}² = {} exceeds {xx}·{zz} = {}",
                short_number(i_xz * i_xz),
                short_number(i_xx * i_zz)
            ),
        });
    }
    principal_moments(
        [keys.first, yy, keys.second],
        [i1, i_yy, i3],
        keys.affects,
        notices,
    )
}
