//! JBike6's seven-body description of a bicycle (Schwab & Papadopoulos 2003; Dressel
//! 2005–2015) and its conversion to the benchmark parameters.
//!
//! JBike6 works in a side view: x forward from the rear wheel's ground contact, y up, z lateral
//! (z = x × y). Every body is symmetric about the x-y plane. Its in-plane inertia is given by
//! principal moments `I = [I11, I22, Izz]` about the body's centre of mass, axis 1 at angle
//! `alpha` from x (counter-clockwise, from forward toward up), and Izz about the lateral axis.

use serde::{Deserialize, Serialize};

use super::benchmark::{principal_moments, BenchmarkParameters};
use crate::error::{Error, Result};

/// JBike6's default gravitational acceleration [m/s²] (standard gravity).
pub const JBIKE6_GRAVITY: f64 = 9.80665;

/// A wheel in JBike6's description: a disk whose centre sits at height `D / 2` above its
/// contact point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6Wheel {
    /// D: diameter [m] (0 for a skate).
    #[serde(rename = "D")]
    pub diameter: f64,
    /// m: mass [kg].
    pub m: f64,
    /// I = [I11, I22, Izz]: I11 = I22 the diametral moments, Izz the polar (spin) moment [kg m²].
    #[serde(rename = "I")]
    pub inertia: [f64; 3],
    /// alpha: angle of principal axis 1 from x [rad] (irrelevant for an axisymmetric wheel).
    pub alpha: f64,
}

/// A body rigidly joined to the rear frame (rider, frame, rack), placed by its centre of mass
/// (x, y) from the rear contact, y up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6RearBody {
    /// m: mass [kg].
    pub m: f64,
    /// xcm: centre of mass forward of the rear contact [m].
    pub xcm: f64,
    /// ycm: centre of mass above the ground [m].
    pub ycm: f64,
    /// I = [I11, I22, Izz]: principal moments about the centre of mass [kg m²].
    #[serde(rename = "I")]
    pub inertia: [f64; 3],
    /// alpha: angle of principal axis 1 from x, counter-clockwise [rad].
    pub alpha: f64,
}

/// A body rigidly joined to the front frame (fork, basket), placed by its centre of mass in a
/// frame at the steer axis' ground point: v up the steer axis, u perpendicular to it (forward and
/// up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6FrontBody {
    /// m: mass [kg].
    pub m: f64,
    /// ucm: centre of mass perpendicular to the steer axis, forward and up [m].
    pub ucm: f64,
    /// vcm: centre of mass along the steer axis, up from the ground [m].
    pub vcm: f64,
    /// I = [I11, I22, Izz]: principal moments about the centre of mass [kg m²].
    #[serde(rename = "I")]
    pub inertia: [f64; 3],
    /// alpha: angle of principal axis 1 from x (not from u), counter-clockwise [rad].
    pub alpha: f64,
}

fn default_gravity() -> f64 {
    JBIKE6_GRAVITY
}

/// A bicycle in JBike6's form: geometry and seven bodies. A body of zero mass and zero inertia
/// is absent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6Parameters {
    /// Horizontal distance between the wheel contacts [m] (benchmark w).
    pub wheelbase: f64,
    /// Angle of the steer axis from the horizontal [rad]; the steer axis tilt is
    /// λ = π/2 − head_angle.
    pub head_angle: f64,
    /// Horizontal distance from the front contact to the steer axis' ground point, positive when
    /// the contact is behind it [m] (benchmark c).
    pub trail: f64,
    /// Gravitational acceleration [m/s²]; JBike6's default, 9.80665, when left out.
    #[serde(default = "default_gravity")]
    pub gravity: f64,
    /// The rear wheel.
    pub rear_wheel: Jbike6Wheel,
    /// The front wheel.
    pub front_wheel: Jbike6Wheel,
    /// The rider, rigidly joined to the rear frame.
    pub rider: Jbike6RearBody,
    /// The rear frame.
    pub frame: Jbike6RearBody,
    /// A rear rack (with its load), rigidly joined to the rear frame.
    pub rack: Jbike6RearBody,
    /// The front fork (with the handlebar).
    pub fork: Jbike6FrontBody,
    /// A front basket (with its load), rigidly joined to the fork.
    pub basket: Jbike6FrontBody,
}

/// One planar body ready to be combined: mass, centre of mass (x, y up) and in-plane tensor
/// (xx, yy, xy) plus the lateral moment zz, in JBike6's axes.
#[derive(Debug, Clone, Copy)]
struct PlanarBody {
    m: f64,
    x: f64,
    y: f64,
    t_xx: f64,
    t_yy: f64,
    t_xy: f64,
    t_zz: f64,
}

impl PlanarBody {
    fn new(m: f64, x: f64, y: f64, inertia: [f64; 3], alpha: f64) -> Self {
        let [i11, i22, izz] = inertia;
        let (s, c) = alpha.sin_cos();
        // R(alpha) diag(I11, I22) R(alpha)^T with R = [[c, -s], [s, c]].
        PlanarBody {
            m,
            x,
            y,
            t_xx: i11 * c * c + i22 * s * s,
            t_yy: i11 * s * s + i22 * c * c,
            t_xy: (i11 - i22) * s * c,
            t_zz: izz,
        }
    }

    /// Combines bodies: masses added, centre of mass the mass-weighted mean, tensors moved to
    /// the combined centre of mass by the parallel-axis theorem.
    fn combine(bodies: &[PlanarBody]) -> PlanarBody {
        let m: f64 = bodies.iter().map(|b| b.m).sum();
        let (x, y) = if m > 0.0 {
            (
                bodies.iter().map(|b| b.m * b.x).sum::<f64>() / m,
                bodies.iter().map(|b| b.m * b.y).sum::<f64>() / m,
            )
        } else {
            (0.0, 0.0)
        };
        let mut total = PlanarBody {
            m,
            x,
            y,
            t_xx: 0.0,
            t_yy: 0.0,
            t_xy: 0.0,
            t_zz: 0.0,
        };
        for b in bodies {
            let (dx, dy) = (b.x - x, b.y - y);
            total.t_xx += b.t_xx + b.m * dy * dy;
            total.t_yy += b.t_yy + b.m * dx * dx;
            total.t_xy += b.t_xy - b.m * dx * dy;
            total.t_zz += b.t_zz + b.m * (dx * dx + dy * dy);
        }
        total
    }
}

impl Jbike6Parameters {
    /// Every number with its name as written in JBike6's `.m` files, for validation and display.
    pub fn fields(&self) -> Vec<(String, f64)> {
        let mut out = vec![
            ("wheelbase".to_string(), self.wheelbase),
            ("head_angle".to_string(), self.head_angle),
            ("trail".to_string(), self.trail),
            ("gravity".to_string(), self.gravity),
        ];
        for (name, w) in [
            ("rearwheel", &self.rear_wheel),
            ("frontwheel", &self.front_wheel),
        ] {
            out.push((format!("D{name}"), w.diameter));
            out.push((format!("m{name}"), w.m));
            for (k, v) in w.inertia.iter().enumerate() {
                out.push((format!("I{name}({})", k + 1), *v));
            }
            out.push((format!("alphaI{name}"), w.alpha));
        }
        for (name, b) in [
            ("rider", &self.rider),
            ("frame", &self.frame),
            ("rack", &self.rack),
        ] {
            out.push((format!("m{name}"), b.m));
            out.push((format!("xcm{name}"), b.xcm));
            out.push((format!("ycm{name}"), b.ycm));
            for (k, v) in b.inertia.iter().enumerate() {
                out.push((format!("I{name}({})", k + 1), *v));
            }
            out.push((format!("alphaI{name}"), b.alpha));
        }
        for (name, b) in [("fork", &self.fork), ("basket", &self.basket)] {
            out.push((format!("m{name}"), b.m));
            out.push((format!("ucm{name}"), b.ucm));
            out.push((format!("vcm{name}"), b.vcm));
            for (k, v) in b.inertia.iter().enumerate() {
                out.push((format!("I{name}({})", k + 1), *v));
            }
            out.push((format!("alphaI{name}"), b.alpha));
        }
        out
    }

    /// Steer axis tilt λ = π/2 − head_angle [rad].
    pub fn steer_axis_tilt(&self) -> f64 {
        std::f64::consts::FRAC_PI_2 - self.head_angle
    }

    /// Checks the rules that belong to this form (finite numbers, non-negative masses and
    /// diameters, head angle strictly inside (0, π), positive semi-definite inertia with the
    /// triangle inequality, axisymmetric wheels). The benchmark form's rules are checked again
    /// after conversion by [`Jbike6Parameters::to_benchmark`].
    pub fn validate(&self) -> Result<()> {
        for (field, value) in self.fields() {
            if !value.is_finite() {
                return Err(Error::InvalidParameter {
                    field,
                    value,
                    rule: "must be a finite number".into(),
                });
            }
        }
        if !(self.head_angle > 0.0 && self.head_angle < std::f64::consts::PI) {
            return Err(Error::InvalidParameter {
                field: "head_angle".into(),
                value: self.head_angle,
                rule: "the head angle (from the horizontal) must lie strictly between 0 and pi rad"
                    .into(),
            });
        }
        let check_mass = |field: String, m: f64| -> Result<()> {
            if m >= 0.0 {
                Ok(())
            } else {
                Err(Error::InvalidParameter {
                    field,
                    value: m,
                    rule: "must not be negative".into(),
                })
            }
        };
        for (name, w) in [
            ("rearwheel", &self.rear_wheel),
            ("frontwheel", &self.front_wheel),
        ] {
            check_mass(format!("m{name}"), w.m)?;
            if w.diameter < 0.0 {
                return Err(Error::InvalidParameter {
                    field: format!("D{name}"),
                    value: w.diameter,
                    rule: "must not be negative".into(),
                });
            }
            let [i11, i22, _] = w.inertia;
            let scale = w.inertia.iter().map(|v| v.abs()).sum::<f64>();
            if (i11 - i22).abs() > 1e-9 * scale {
                return Err(Error::InvalidBicycle {
                    fields: format!("I{name}"),
                    rule: format!(
                        "a wheel must be axisymmetric: its in-plane moments I11 = {i11} and I22 = {i22} must be equal"
                    ),
                });
            }
            principal_moments(
                [
                    &format!("I{name}(1)"),
                    &format!("I{name}(2)"),
                    &format!("I{name}(3)"),
                ],
                w.inertia,
            )?;
        }
        for (name, m, inertia) in [
            ("rider", self.rider.m, self.rider.inertia),
            ("frame", self.frame.m, self.frame.inertia),
            ("rack", self.rack.m, self.rack.inertia),
            ("fork", self.fork.m, self.fork.inertia),
            ("basket", self.basket.m, self.basket.inertia),
        ] {
            check_mass(format!("m{name}"), m)?;
            principal_moments(
                [
                    &format!("I{name}(1)"),
                    &format!("I{name}(2)"),
                    &format!("I{name}(3)"),
                ],
                inertia,
            )?;
        }
        Ok(())
    }

    /// Where a front body's centre of mass is, (x forward from the rear contact, y up) [m]:
    /// `ucm` perpendicular to the steer axis (forward and up) and `vcm` along it (up) from the
    /// point where the axis meets the ground, w + c ahead of the rear contact.
    pub fn front_body_centre(&self, b: &Jbike6FrontBody) -> [f64; 2] {
        let (s, c) = self.steer_axis_tilt().sin_cos();
        let front_point = self.wheelbase + self.trail;
        [front_point + b.ucm * c - b.vcm * s, b.ucm * s + b.vcm * c]
    }

    /// Converts to the 25 benchmark parameters (plus g): B = rider + frame + rack, H = fork +
    /// basket, combined with the parallel-axis theorem; with T a combined tensor in JBike6's
    /// axes, x_B = x, z_B = −y, I_Bxx = T_xx, I_Bzz = T_yy, I_Byy = T_zz, I_Bxz = −T_xy.
    /// Validates both this form and the result.
    ///
    /// ```
    /// use whipple::parameters::presets;
    /// let crown = presets::schwinn_crown_jbike6();
    /// let bike = crown.to_benchmark()?;
    /// assert_eq!(bike.w, 1.016);
    /// assert!((bike.m_b - 84.5).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn to_benchmark(&self) -> Result<BenchmarkParameters> {
        self.validate()?;
        let lambda = self.steer_axis_tilt();
        let rear = PlanarBody::combine(&[
            rear_body(&self.rider),
            rear_body(&self.frame),
            rear_body(&self.rack),
        ]);
        let place = |b: &Jbike6FrontBody| {
            let [x, y] = self.front_body_centre(b);
            PlanarBody::new(b.m, x, y, b.inertia, b.alpha)
        };
        let front = PlanarBody::combine(&[place(&self.fork), place(&self.basket)]);
        let bike = BenchmarkParameters {
            w: self.wheelbase,
            c: self.trail,
            lambda,
            g: self.gravity,
            r_r: 0.5 * self.rear_wheel.diameter,
            m_r: self.rear_wheel.m,
            i_rxx: self.rear_wheel.inertia[0],
            i_ryy: self.rear_wheel.inertia[2],
            x_b: rear.x,
            z_b: -rear.y,
            m_b: rear.m,
            i_bxx: rear.t_xx,
            i_byy: rear.t_zz,
            i_bzz: rear.t_yy,
            i_bxz: -rear.t_xy,
            x_h: front.x,
            z_h: -front.y,
            m_h: front.m,
            i_hxx: front.t_xx,
            i_hyy: front.t_zz,
            i_hzz: front.t_yy,
            i_hxz: -front.t_xy,
            r_f: 0.5 * self.front_wheel.diameter,
            m_f: self.front_wheel.m,
            i_fxx: self.front_wheel.inertia[0],
            i_fyy: self.front_wheel.inertia[2],
        };
        bike.validate()?;
        Ok(bike)
    }
}

fn rear_body(b: &Jbike6RearBody) -> PlanarBody {
    PlanarBody::new(b.m, b.xcm, b.ycm, b.inertia, b.alpha)
}
