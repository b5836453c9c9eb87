//! JBike6's seven-body description of a bicycle (Schwab & Papadopoulos 2003; Dressel
//! 2005–2015) and its conversion to the benchmark parameters.
//!
//! JBike6 works in a side view: x forward from the rear wheel's ground contact, y up, z lateral
//! (z = x × y). Every body is symmetric about the x-y plane. Its in-plane inertia is given by
//! principal moments `I = [I11, I22, Izz]` about the body's centre of mass, axis 1 at angle
//! `alpha` from x (counter-clockwise, from forward toward up), and Izz about the lateral axis.
//!
//! The types are generic over the scalar (default `f64`), so that the conversion runs on dual
//! numbers too: exact derivatives of anything computed from a JBike6-form bicycle with respect
//! to its own parameters.

use crate::math::Real;
use serde::{Deserialize, Serialize};

use super::benchmark::{BenchmarkParameters, principal_moments, zero_mass_inertia};
use super::check::Notice;
use super::table::{Form, ParameterInfo};
use crate::error::{Error, Result, short_number};

/// JBike6's default gravitational acceleration [m/s²] (standard gravity).
pub(crate) const JBIKE6_GRAVITY: f64 = 9.80665;

/// A wheel in JBike6's description: a disk whose centre sits at height `D / 2` above its
/// contact point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6Wheel<T = f64> {
    /// D: diameter \[m\] (0 for a skate).
    #[serde(rename = "D")]
    pub diameter: T,
    /// m: mass \[kg\].
    pub m: T,
    /// I = [I11, I22, Izz]: I11 = I22 the diametral moments, Izz the polar (spin) moment [kg m²].
    #[serde(rename = "I")]
    pub inertia: [T; 3],
    /// alpha: angle of principal axis 1 from x \[rad\] (irrelevant for an axisymmetric wheel).
    pub alpha: T,
}

/// A body rigidly joined to the rear frame (rider, frame, rack), placed by its centre of mass
/// (x, y) from the rear contact, y up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6RearBody<T = f64> {
    /// m: mass \[kg\].
    pub m: T,
    /// xcm: centre of mass forward of the rear contact \[m\].
    pub xcm: T,
    /// ycm: centre of mass above the ground \[m\].
    pub ycm: T,
    /// I = [I11, I22, Izz]: principal moments about the centre of mass [kg m²].
    #[serde(rename = "I")]
    pub inertia: [T; 3],
    /// alpha: angle of principal axis 1 from x, counter-clockwise \[rad\].
    pub alpha: T,
}

/// A body rigidly joined to the front frame (fork, basket), placed by its centre of mass in a
/// frame at the steer axis' ground point: v up the steer axis, u perpendicular to it (forward and
/// up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jbike6FrontBody<T = f64> {
    /// m: mass \[kg\].
    pub m: T,
    /// ucm: centre of mass perpendicular to the steer axis, forward and up \[m\].
    pub ucm: T,
    /// vcm: centre of mass along the steer axis, up from the ground \[m\].
    pub vcm: T,
    /// I = [I11, I22, Izz]: principal moments about the centre of mass [kg m²].
    #[serde(rename = "I")]
    pub inertia: [T; 3],
    /// alpha: angle of principal axis 1 from x (not from u), counter-clockwise \[rad\].
    pub alpha: T,
}

fn default_gravity<T: From<f64>>() -> T {
    T::from(JBIKE6_GRAVITY)
}

/// A bicycle in JBike6's form: geometry and seven bodies. A body of zero mass and zero inertia
/// is absent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound(deserialize = "T: Deserialize<'de> + From<f64>"))]
pub struct Jbike6Parameters<T = f64> {
    /// Horizontal distance between the wheel contacts \[m\] (benchmark w).
    pub wheelbase: T,
    /// Angle of the steer axis from the horizontal \[rad\]; the steer axis tilt is
    /// λ = π/2 − head_angle.
    pub head_angle: T,
    /// Horizontal distance from the front contact to the steer axis' ground point, positive when
    /// the contact is behind it \[m\] (benchmark c).
    pub trail: T,
    /// Gravitational acceleration [m/s²]; JBike6's default, 9.80665, when left out.
    #[serde(default = "default_gravity")]
    pub gravity: T,
    /// The rear wheel.
    pub rear_wheel: Jbike6Wheel<T>,
    /// The front wheel.
    pub front_wheel: Jbike6Wheel<T>,
    /// The rider, rigidly joined to the rear frame.
    pub rider: Jbike6RearBody<T>,
    /// The rear frame.
    pub frame: Jbike6RearBody<T>,
    /// A rear rack (with its load), rigidly joined to the rear frame.
    pub rack: Jbike6RearBody<T>,
    /// The front fork (with the handlebar).
    pub fork: Jbike6FrontBody<T>,
    /// A front basket (with its load), rigidly joined to the fork.
    pub basket: Jbike6FrontBody<T>,
}

/// Every JBike6 parameter in the order of the original study's listing.
pub(crate) const JBIKE6_TABLE: [ParameterInfo; 51] = [
    ParameterInfo {
        name: "wheelbase",
        key: "wheelbase",
        path: "wheelbase",
        symbol: "w",
        unit: "m",
        description: "horizontal distance between the wheel contacts (benchmark w)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "head_angle",
        key: "head_angle",
        path: "head_angle",
        symbol: "π/2 − λ",
        unit: "rad",
        description: "steer axis angle from the horizontal; the steer axis tilt is λ = π/2 − head_angle",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "trail",
        key: "trail",
        path: "trail",
        symbol: "c",
        unit: "m",
        description: "front contact behind the steer axis' ground point (benchmark c)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "gravity",
        key: "gravity",
        path: "gravity",
        symbol: "g",
        unit: "m/s^2",
        description: "gravitational acceleration (JBike6's default 9.80665 when left out)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rear_wheel.diameter",
        key: "Drearwheel",
        path: "rear_wheel.D",
        symbol: "D",
        unit: "m",
        description: "rear wheel diameter (0 for a skate)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rear_wheel.m",
        key: "mrearwheel",
        path: "rear_wheel.m",
        symbol: "m",
        unit: "kg",
        description: "rear wheel mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rear_wheel.inertia[0]",
        key: "Irearwheel(1)",
        path: "rear_wheel.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "rear wheel diametral moment of inertia I11",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rear_wheel.inertia[1]",
        key: "Irearwheel(2)",
        path: "rear_wheel.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "rear wheel diametral moment of inertia I22 (= I11)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rear_wheel.inertia[2]",
        key: "Irearwheel(3)",
        path: "rear_wheel.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "rear wheel spin (polar) moment of inertia Izz",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rear_wheel.alpha",
        key: "alphaIrearwheel",
        path: "rear_wheel.alpha",
        symbol: "α",
        unit: "rad",
        description: "rear wheel principal axis angle (irrelevant for an axisymmetric wheel)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "front_wheel.diameter",
        key: "Dfrontwheel",
        path: "front_wheel.D",
        symbol: "D",
        unit: "m",
        description: "front wheel diameter (0 for a skate)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "front_wheel.m",
        key: "mfrontwheel",
        path: "front_wheel.m",
        symbol: "m",
        unit: "kg",
        description: "front wheel mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "front_wheel.inertia[0]",
        key: "Ifrontwheel(1)",
        path: "front_wheel.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "front wheel diametral moment of inertia I11",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "front_wheel.inertia[1]",
        key: "Ifrontwheel(2)",
        path: "front_wheel.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "front wheel diametral moment of inertia I22 (= I11)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "front_wheel.inertia[2]",
        key: "Ifrontwheel(3)",
        path: "front_wheel.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "front wheel spin (polar) moment of inertia Izz",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "front_wheel.alpha",
        key: "alphaIfrontwheel",
        path: "front_wheel.alpha",
        symbol: "α",
        unit: "rad",
        description: "front wheel principal axis angle (irrelevant for an axisymmetric wheel)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.m",
        key: "mrider",
        path: "rider.m",
        symbol: "m",
        unit: "kg",
        description: "rider mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.xcm",
        key: "xcmrider",
        path: "rider.xcm",
        symbol: "x",
        unit: "m",
        description: "rider centre of mass, forward of the rear contact",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.ycm",
        key: "ycmrider",
        path: "rider.ycm",
        symbol: "y",
        unit: "m",
        description: "rider centre of mass, above the ground",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.inertia[0]",
        key: "Irider(1)",
        path: "rider.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "rider first in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.inertia[1]",
        key: "Irider(2)",
        path: "rider.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "rider second in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.inertia[2]",
        key: "Irider(3)",
        path: "rider.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "rider lateral moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rider.alpha",
        key: "alphaIrider",
        path: "rider.alpha",
        symbol: "α",
        unit: "rad",
        description: "rider angle of principal axis 1 from x, counter-clockwise",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.m",
        key: "mframe",
        path: "frame.m",
        symbol: "m",
        unit: "kg",
        description: "rear frame mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.xcm",
        key: "xcmframe",
        path: "frame.xcm",
        symbol: "x",
        unit: "m",
        description: "rear frame centre of mass, forward of the rear contact",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.ycm",
        key: "ycmframe",
        path: "frame.ycm",
        symbol: "y",
        unit: "m",
        description: "rear frame centre of mass, above the ground",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.inertia[0]",
        key: "Iframe(1)",
        path: "frame.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "rear frame first in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.inertia[1]",
        key: "Iframe(2)",
        path: "frame.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "rear frame second in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.inertia[2]",
        key: "Iframe(3)",
        path: "frame.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "rear frame lateral moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "frame.alpha",
        key: "alphaIframe",
        path: "frame.alpha",
        symbol: "α",
        unit: "rad",
        description: "rear frame angle of principal axis 1 from x, counter-clockwise",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.m",
        key: "mrack",
        path: "rack.m",
        symbol: "m",
        unit: "kg",
        description: "rear rack with its load mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.xcm",
        key: "xcmrack",
        path: "rack.xcm",
        symbol: "x",
        unit: "m",
        description: "rear rack with its load centre of mass, forward of the rear contact",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.ycm",
        key: "ycmrack",
        path: "rack.ycm",
        symbol: "y",
        unit: "m",
        description: "rear rack with its load centre of mass, above the ground",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.inertia[0]",
        key: "Irack(1)",
        path: "rack.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "rear rack with its load first in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.inertia[1]",
        key: "Irack(2)",
        path: "rack.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "rear rack with its load second in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.inertia[2]",
        key: "Irack(3)",
        path: "rack.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "rear rack with its load lateral moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "rack.alpha",
        key: "alphaIrack",
        path: "rack.alpha",
        symbol: "α",
        unit: "rad",
        description: "rear rack with its load angle of principal axis 1 from x, counter-clockwise",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.m",
        key: "mfork",
        path: "fork.m",
        symbol: "m",
        unit: "kg",
        description: "front fork with the handlebar mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.ucm",
        key: "ucmfork",
        path: "fork.ucm",
        symbol: "u",
        unit: "m",
        description: "front fork with the handlebar centre of mass, perpendicular to the steer axis (forward and up)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.vcm",
        key: "vcmfork",
        path: "fork.vcm",
        symbol: "v",
        unit: "m",
        description: "front fork with the handlebar centre of mass, along the steer axis up from the ground",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.inertia[0]",
        key: "Ifork(1)",
        path: "fork.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "front fork with the handlebar first in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.inertia[1]",
        key: "Ifork(2)",
        path: "fork.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "front fork with the handlebar second in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.inertia[2]",
        key: "Ifork(3)",
        path: "fork.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "front fork with the handlebar lateral moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "fork.alpha",
        key: "alphaIfork",
        path: "fork.alpha",
        symbol: "α",
        unit: "rad",
        description: "front fork with the handlebar angle of principal axis 1 from x (not from u), counter-clockwise",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.m",
        key: "mbasket",
        path: "basket.m",
        symbol: "m",
        unit: "kg",
        description: "front basket with its load mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.ucm",
        key: "ucmbasket",
        path: "basket.ucm",
        symbol: "u",
        unit: "m",
        description: "front basket with its load centre of mass, perpendicular to the steer axis (forward and up)",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.vcm",
        key: "vcmbasket",
        path: "basket.vcm",
        symbol: "v",
        unit: "m",
        description: "front basket with its load centre of mass, along the steer axis up from the ground",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.inertia[0]",
        key: "Ibasket(1)",
        path: "basket.I[1]",
        symbol: "I11",
        unit: "kg m^2",
        description: "front basket with its load first in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.inertia[1]",
        key: "Ibasket(2)",
        path: "basket.I[2]",
        symbol: "I22",
        unit: "kg m^2",
        description: "front basket with its load second in-plane principal moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.inertia[2]",
        key: "Ibasket(3)",
        path: "basket.I[3]",
        symbol: "Izz",
        unit: "kg m^2",
        description: "front basket with its load lateral moment of inertia about its centre of mass",
        form: Form::Jbike6,
        linear: true,
    },
    ParameterInfo {
        name: "basket.alpha",
        key: "alphaIbasket",
        path: "basket.alpha",
        symbol: "α",
        unit: "rad",
        description: "front basket with its load angle of principal axis 1 from x (not from u), counter-clockwise",
        form: Form::Jbike6,
        linear: true,
    },
];

/// Number of JBike6 parameters.
pub(crate) const JBIKE6_COUNT: usize = 51;

impl<T: Copy> Jbike6Parameters<T> {
    /// The values in the order of `JBIKE6_TABLE`.
    pub fn to_array(&self) -> [T; JBIKE6_COUNT] {
        let mut out = Vec::with_capacity(JBIKE6_COUNT);
        out.extend([self.wheelbase, self.head_angle, self.trail, self.gravity]);
        for w in [&self.rear_wheel, &self.front_wheel] {
            out.extend([
                w.diameter,
                w.m,
                w.inertia[0],
                w.inertia[1],
                w.inertia[2],
                w.alpha,
            ]);
        }
        for b in [&self.rider, &self.frame, &self.rack] {
            out.extend([
                b.m,
                b.xcm,
                b.ycm,
                b.inertia[0],
                b.inertia[1],
                b.inertia[2],
                b.alpha,
            ]);
        }
        for b in [&self.fork, &self.basket] {
            out.extend([
                b.m,
                b.ucm,
                b.vcm,
                b.inertia[0],
                b.inertia[1],
                b.inertia[2],
                b.alpha,
            ]);
        }
        let mut array = [self.wheelbase; JBIKE6_COUNT];
        array.copy_from_slice(&out);
        array
    }

    /// The parameters from values in the order of `JBIKE6_TABLE`.
    pub fn from_array(v: [T; JBIKE6_COUNT]) -> Self {
        let wheel = |o: usize| Jbike6Wheel {
            diameter: v[o],
            m: v[o + 1],
            inertia: [v[o + 2], v[o + 3], v[o + 4]],
            alpha: v[o + 5],
        };
        let rear = |o: usize| Jbike6RearBody {
            m: v[o],
            xcm: v[o + 1],
            ycm: v[o + 2],
            inertia: [v[o + 3], v[o + 4], v[o + 5]],
            alpha: v[o + 6],
        };
        let front = |o: usize| Jbike6FrontBody {
            m: v[o],
            ucm: v[o + 1],
            vcm: v[o + 2],
            inertia: [v[o + 3], v[o + 4], v[o + 5]],
            alpha: v[o + 6],
        };
        Jbike6Parameters {
            wheelbase: v[0],
            head_angle: v[1],
            trail: v[2],
            gravity: v[3],
            rear_wheel: wheel(4),
            front_wheel: wheel(10),
            rider: rear(16),
            frame: rear(23),
            rack: rear(30),
            fork: front(37),
            basket: front(44),
        }
    }
}

/// A body of the bicycle's plane of symmetry in the benchmark's axes (x forward, y to the
/// right, z down): mass \[kg\], centre of mass (x, z) \[m\] and the inertia tensor about it
/// \[kg m²\], whose only product is I_xz, the tensor's xz entry as in Table 1. The one home of
/// combining bodies: JBike6's seven bodies and a BicycleParameters file's handlebar and fork.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PlaneBody<T> {
    pub(crate) m: T,
    pub(crate) x: T,
    pub(crate) z: T,
    pub(crate) i_xx: T,
    pub(crate) i_yy: T,
    pub(crate) i_zz: T,
    pub(crate) i_xz: T,
}

impl<T: Real> PlaneBody<T> {
    /// A JBike6 body: centre (x forward, y up) and principal moments [I11, I22, Izz], the first
    /// two in the plane with the principal axis of I11 turned by `alpha` from x towards y.
    fn jbike6(m: T, x: T, y: T, inertia: [T; 3], alpha: T) -> Self {
        Self::principal(m, x, -y, inertia, alpha)
    }

    /// A body from its principal moments [I11, I22, Iyy] about the centre (x, z), the first
    /// two in the plane with the axis of I11 turned by `alpha` from x upwards (towards −z):
    /// JBike6's bodies and Moore 2019's principal parameterization alike.
    pub(crate) fn principal(m: T, x: T, z: T, inertia: [T; 3], alpha: T) -> Self {
        let [i11, i22, izz] = inertia;
        let (s, c) = crate::math::sin_cos(alpha);
        // R(alpha) diag(I11, I22) R(alpha)^T with R = [[c, -s], [s, c]], in axes x forward,
        // y up; the benchmark's z is −y, so its xz product is minus that xy product.
        PlaneBody {
            m,
            x,
            z,
            i_xx: i11 * c * c + i22 * s * s,
            i_yy: izz,
            i_zz: i11 * s * s + i22 * c * c,
            i_xz: -((i11 - i22) * s * c),
        }
    }

    /// The inverse of [`PlaneBody::principal`]: the principal moments [I11, I22, Iyy] about the
    /// centre, I11 ≥ I22 the in-plane ones, and the angle α in (−π/2, π/2] of I11's axis from
    /// x upwards (α = 0 where the two in-plane moments are equal).
    pub(crate) fn principal_axes(&self) -> ([T; 3], T) {
        let half: T = nalgebra::convert(0.5);
        let two: T = nalgebra::convert(2.0);
        let mean = (self.i_xx + self.i_zz) * half;
        let diff = (self.i_xx - self.i_zz) * half;
        let radius = (diff * diff + self.i_xz * self.i_xz).sqrt();
        // atan2 gives (−π, π]; halved, (−π/2, π/2].
        let alpha = if radius > T::zero() {
            crate::math::atan2(-(two * self.i_xz), two * diff) * half
        } else {
            T::zero()
        };
        ([mean + radius, mean - radius, self.i_yy], alpha)
    }

    /// One body from several: masses added, centre of mass the mass-weighted mean (the origin
    /// when the total mass is zero), each tensor moved to that centre by the parallel-axis
    /// theorem, I + m (|d|² E − d dᵀ) with d from the combined centre to the body's.
    pub(crate) fn combine(bodies: &[PlaneBody<T>]) -> PlaneBody<T> {
        let zero = T::zero();
        let m = bodies.iter().fold(zero, |a, b| a + b.m);
        let (x, z) = if m > zero {
            (
                bodies.iter().fold(zero, |a, b| a + b.m * b.x) / m,
                bodies.iter().fold(zero, |a, b| a + b.m * b.z) / m,
            )
        } else {
            (zero, zero)
        };
        let mut total = PlaneBody {
            m,
            x,
            z,
            i_xx: zero,
            i_yy: zero,
            i_zz: zero,
            i_xz: zero,
        };
        for b in bodies {
            let (dx, dz) = (b.x - x, b.z - z);
            total.i_xx += b.i_xx + b.m * dz * dz;
            total.i_yy += b.i_yy + b.m * (dx * dx + dz * dz);
            total.i_zz += b.i_zz + b.m * dx * dx;
            total.i_xz += b.i_xz - b.m * dx * dz;
        }
        total
    }
}

impl<T: Real> Jbike6Parameters<T> {
    /// Where a front body's centre of mass is, (x forward from the rear contact, y up) \[m\]:
    /// `ucm` perpendicular to the steer axis (forward and up) and `vcm` along it (up) from the
    /// point where the axis meets the ground, w + c ahead of the rear contact.
    pub fn front_body_centre(&self, b: &Jbike6FrontBody<T>) -> [T; 2] {
        let (s, c) = crate::math::sin_cos(T::frac_pi_2() - self.head_angle);
        let front_point = self.wheelbase + self.trail;
        [front_point + b.ucm * c - b.vcm * s, b.ucm * s + b.vcm * c]
    }

    /// JBike6's form of benchmark parameters, exactly and without a check: the rear wheel,
    /// the frame (the benchmark's rear body B, rider included), the fork (the front frame H)
    /// and the front wheel; the rider, rack and basket absent (zero mass and inertia, as
    /// JBike6 takes an absent body). Each body's in-plane tensor becomes its principal moments
    /// I11 ≥ I22 with α in (−π/2, π/2] (α = 0 where they are equal); the wheels' I11 = I22
    /// are the benchmark's diametral moments, Izz the spin moments; the fork's centre goes to
    /// (ucm, vcm) about the steer axis' ground point. [`Jbike6Parameters::to_benchmark`] gives
    /// the 25 numbers and g back to round-off.
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, advanced::parameters::Jbike6Parameters};
    /// let b = BenchmarkParameters::meijaard2007();
    /// let back = Jbike6Parameters::from_benchmark(&b).to_benchmark()?;
    /// assert!((back.i_hxz - b.i_hxz).abs() < 1e-15 && (back.x_h - b.x_h).abs() < 1e-15);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn from_benchmark(b: &BenchmarkParameters<T>) -> Self {
        let zero = T::zero();
        let two: T = nalgebra::convert(2.0);
        let wheel = |r: T, m: T, i_diametral: T, i_spin: T| Jbike6Wheel {
            diameter: two * r,
            m,
            inertia: [i_diametral, i_diametral, i_spin],
            alpha: zero,
        };
        let absent_rear = Jbike6RearBody {
            m: zero,
            xcm: zero,
            ycm: zero,
            inertia: [zero; 3],
            alpha: zero,
        };
        let absent_front = Jbike6FrontBody {
            m: zero,
            ucm: zero,
            vcm: zero,
            inertia: [zero; 3],
            alpha: zero,
        };
        let rear = PlaneBody {
            m: b.m_b,
            x: b.x_b,
            z: b.z_b,
            i_xx: b.i_bxx,
            i_yy: b.i_byy,
            i_zz: b.i_bzz,
            i_xz: b.i_bxz,
        };
        let front = PlaneBody {
            m: b.m_h,
            x: b.x_h,
            z: b.z_h,
            i_xx: b.i_hxx,
            i_yy: b.i_hyy,
            i_zz: b.i_hzz,
            i_xz: b.i_hxz,
        };
        let (rear_moments, rear_alpha) = rear.principal_axes();
        let (front_moments, front_alpha) = front.principal_axes();
        // The inverse of `front_body_centre`: the centre relative to the steer axis' ground
        // point, turned by λ.
        let (s, c) = crate::math::sin_cos(b.lambda);
        let (x, y) = (b.x_h - b.w - b.c, -b.z_h);
        Jbike6Parameters {
            wheelbase: b.w,
            head_angle: T::frac_pi_2() - b.lambda,
            trail: b.c,
            gravity: b.g,
            rear_wheel: wheel(b.r_r, b.m_r, b.i_rxx, b.i_ryy),
            front_wheel: wheel(b.r_f, b.m_f, b.i_fxx, b.i_fyy),
            rider: absent_rear,
            frame: Jbike6RearBody {
                m: b.m_b,
                xcm: b.x_b,
                ycm: -b.z_b,
                inertia: rear_moments,
                alpha: rear_alpha,
            },
            rack: absent_rear,
            fork: Jbike6FrontBody {
                m: b.m_h,
                ucm: x * c + y * s,
                vcm: -x * s + y * c,
                inertia: front_moments,
                alpha: front_alpha,
            },
            basket: absent_front,
        }
    }

    /// The benchmark parameters without any check, on any scalar (for dual numbers); see
    /// [`Jbike6Parameters::to_benchmark`].
    pub fn to_benchmark_unchecked(&self) -> BenchmarkParameters<T> {
        let half: T = nalgebra::convert(0.5);
        let lambda = T::frac_pi_2() - self.head_angle;
        let rear = PlaneBody::combine(&[
            rear_body(&self.rider),
            rear_body(&self.frame),
            rear_body(&self.rack),
        ]);
        let place = |b: &Jbike6FrontBody<T>| {
            let [x, y] = self.front_body_centre(b);
            PlaneBody::jbike6(b.m, x, y, b.inertia, b.alpha)
        };
        let front = PlaneBody::combine(&[place(&self.fork), place(&self.basket)]);
        BenchmarkParameters {
            w: self.wheelbase,
            c: self.trail,
            lambda,
            g: self.gravity,
            r_r: half * self.rear_wheel.diameter,
            m_r: self.rear_wheel.m,
            i_rxx: self.rear_wheel.inertia[0],
            i_ryy: self.rear_wheel.inertia[2],
            x_b: rear.x,
            z_b: rear.z,
            m_b: rear.m,
            i_bxx: rear.i_xx,
            i_byy: rear.i_yy,
            i_bzz: rear.i_zz,
            i_bxz: rear.i_xz,
            x_h: front.x,
            z_h: front.z,
            m_h: front.m,
            i_hxx: front.i_xx,
            i_hyy: front.i_yy,
            i_hzz: front.i_zz,
            i_hxz: front.i_xz,
            r_f: half * self.front_wheel.diameter,
            m_f: self.front_wheel.m,
            i_fxx: self.front_wheel.inertia[0],
            i_fyy: self.front_wheel.inertia[2],
        }
    }
}

fn rear_body<T: Real>(b: &Jbike6RearBody<T>) -> PlaneBody<T> {
    PlaneBody::jbike6(b.m, b.xcm, b.ycm, b.inertia, b.alpha)
}

const REAR_BODY_MASSES: &[&str] = &["mrider", "mframe", "mrack"];
const FRONT_FRAME_MASSES: &[&str] = &["mfork", "mbasket"];

/// For each benchmark key (in the order of Meijaard 2007 Table 1, then g), the JBike6 entries a
/// form flags when a rule on that key fails for a bicycle given in JBike6's form: the entry it
/// is converted from (`w` from `wheelbase`, `rR` from `Drearwheel`); for a wheel's moments of
/// inertia, the entries a rule on them involves (`IRxx`: `Irearwheel(1)` and `Irearwheel(2)`,
/// the two diameters; `IRyy`: `Irearwheel(3)` and the diameter); for the combined rear body
/// `B` and front frame `H`, each combined body's mass, standing for all its entries. The web
/// page reads this from `GET /api/parameters`.
///
/// ```
/// use whipple::advanced::parameters::BENCHMARK_FROM_JBIKE6;
/// let (_, sources) = BENCHMARK_FROM_JBIKE6.iter().find(|(key, _)| *key == "mH").unwrap();
/// assert_eq!(*sources, ["mfork", "mbasket"]);
/// ```
pub const BENCHMARK_FROM_JBIKE6: [(&str, &[&str]); 26] = [
    ("w", &["wheelbase"]),
    ("c", &["trail"]),
    ("lam", &["head_angle"]),
    ("g", &["gravity"]),
    ("rR", &["Drearwheel"]),
    ("mR", &["mrearwheel"]),
    ("IRxx", &["Irearwheel(1)", "Irearwheel(2)"]),
    ("IRyy", &["Irearwheel(3)", "Drearwheel"]),
    ("xB", REAR_BODY_MASSES),
    ("zB", REAR_BODY_MASSES),
    ("mB", REAR_BODY_MASSES),
    ("IBxx", REAR_BODY_MASSES),
    ("IByy", REAR_BODY_MASSES),
    ("IBzz", REAR_BODY_MASSES),
    ("IBxz", REAR_BODY_MASSES),
    ("xH", FRONT_FRAME_MASSES),
    ("zH", FRONT_FRAME_MASSES),
    ("mH", FRONT_FRAME_MASSES),
    ("IHxx", FRONT_FRAME_MASSES),
    ("IHyy", FRONT_FRAME_MASSES),
    ("IHzz", FRONT_FRAME_MASSES),
    ("IHxz", FRONT_FRAME_MASSES),
    ("rF", &["Dfrontwheel"]),
    ("mF", &["mfrontwheel"]),
    ("IFxx", &["Ifrontwheel(1)", "Ifrontwheel(2)"]),
    ("IFyy", &["Ifrontwheel(3)", "Dfrontwheel"]),
];

/// The JBike6 names behind a benchmark key, for messages about a converted bicycle.
fn jbike6_names(benchmark_key: &str) -> &'static str {
    match benchmark_key {
        "w" => "wheelbase",
        "c" => "trail",
        "lam" => "head_angle",
        "g" => "gravity",
        "rR" => "Drearwheel",
        "mR" => "mrearwheel",
        "IRxx" => "Irearwheel(1)",
        "IRyy" => "Irearwheel(3)",
        "rF" => "Dfrontwheel",
        "mF" => "mfrontwheel",
        "IFxx" => "Ifrontwheel(1)",
        "IFyy" => "Ifrontwheel(3)",
        "mB" => "mrider, mframe, mrack",
        "xB" => "xcmrider, xcmframe, xcmrack",
        "zB" => "ycmrider, ycmframe, ycmrack",
        "IBxx" | "IByy" | "IBzz" | "IBxz" => "Irider, Iframe, Irack (combined rear body)",
        "mH" => "mfork, mbasket",
        "xH" | "zH" => "ucmfork, vcmfork, ucmbasket, vcmbasket",
        "IHxx" | "IHyy" | "IHzz" | "IHxz" => "Ifork, Ibasket (combined front frame)",
        _ => "",
    }
}

/// Renames a comma-separated list of benchmark keys to the JBike6 names they come from.
fn rename_fields(fields: &str) -> String {
    let mut out: Vec<&str> = Vec::new();
    for key in fields.split(',').map(str::trim) {
        let name = jbike6_names(key);
        let name = if name.is_empty() { key } else { name };
        if !out.contains(&name) {
            out.push(name);
        }
    }
    out.join(", ")
}

/// A benchmark-form error of a converted JBike6 bicycle, reported under the JBike6 names the
/// user wrote.
fn rename_error(error: Error) -> Error {
    match error {
        Error::InvalidParameter { field, value, rule } => {
            let name = jbike6_names(&field);
            if name.is_empty()
                || name.contains(',')
                || name.contains('(') && name.contains("combined")
            {
                Error::InvalidBicycle {
                    fields: rename_fields(&field),
                    rule: format!(
                        "after combining the JBike6 bodies, the benchmark {field} = {} {rule}",
                        short_number(value)
                    ),
                }
            } else {
                Error::InvalidParameter {
                    field: name.to_string(),
                    value,
                    rule,
                }
            }
        }
        Error::InvalidBicycle { fields, rule } => Error::InvalidBicycle {
            fields: rename_fields(&fields),
            rule,
        },
        other => other,
    }
}

impl Jbike6Parameters {
    /// Every number with its name as written in JBike6's `.m` files, for validation and display.
    pub fn fields(&self) -> Vec<(String, f64)> {
        JBIKE6_TABLE
            .iter()
            .zip(self.to_array())
            .map(|(p, v)| (p.key.to_string(), v))
            .collect()
    }

    /// The value of the parameter with this `.m` key (`mrider`, `Irider(1)`) or TOML path
    /// (`rider.m`).
    pub fn get(&self, key: &str) -> Option<f64> {
        JBIKE6_TABLE
            .iter()
            .position(|p| p.key == key || p.path == key)
            .map(|i| self.to_array()[i])
    }

    /// Sets the parameter with this `.m` key or TOML path; `false` for an unknown key.
    ///
    /// ```
    /// let mut crown = whipple::presets::schwinn_crown_jbike6();
    /// assert!(crown.set("mrider", 70.0) && crown.set("fork.ucm", 0.01));
    /// assert_eq!((crown.rider.m, crown.fork.ucm), (70.0, 0.01));
    /// assert!(!crown.set("mB", 1.0));
    /// ```
    pub fn set(&mut self, key: &str, value: f64) -> bool {
        match JBIKE6_TABLE
            .iter()
            .position(|p| p.key == key || p.path == key)
        {
            Some(i) => {
                let mut values = self.to_array();
                values[i] = value;
                *self = Self::from_array(values);
                true
            }
            None => false,
        }
    }

    /// Steer axis tilt λ = π/2 − head_angle \[rad\].
    pub fn steer_axis_tilt(&self) -> f64 {
        std::f64::consts::FRAC_PI_2 - self.head_angle
    }

    /// Checks the rules that belong to this form (see [`Jbike6Parameters::check`]).
    pub fn validate(&self) -> Result<()> {
        self.check().map(|_| ())
    }

    /// Checks this form's rules under JBike6's names and returns its warnings: finite numbers;
    /// wheelbase and gravity positive; head angle strictly inside (0, π); non-negative masses
    /// and diameters; a body of zero mass has no inertia; a skate (zero diameter) does not
    /// spin; axisymmetric wheels; principal moments non-negative (a warning where they break
    /// the triangle inequality). The benchmark form's rules are checked again after conversion
    /// by [`Jbike6Parameters::to_benchmark`], and reported under the JBike6 names.
    pub fn check(&self) -> Result<Vec<Notice>> {
        let mut notices = Vec::new();
        // The keys are formed only for an error: a design map checks a million bicycles.
        for (p, value) in JBIKE6_TABLE.iter().zip(self.to_array()) {
            if !value.is_finite() {
                return Err(Error::InvalidParameter {
                    field: p.key.to_string(),
                    value,
                    rule: "must be a finite number".into(),
                });
            }
        }
        for (field, value) in [("wheelbase", self.wheelbase), ("gravity", self.gravity)] {
            if value.is_nan() || value <= 0.0 {
                return Err(Error::InvalidParameter {
                    field: field.into(),
                    value,
                    rule: "must be greater than zero".into(),
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
        let check_mass = |field: &str, m: f64| -> Result<()> {
            if m >= 0.0 {
                Ok(())
            } else {
                Err(Error::InvalidParameter {
                    field: field.to_string(),
                    value: m,
                    rule: "must not be negative".into(),
                })
            }
        };
        for (keys, title, w) in [
            (&REAR_WHEEL_KEYS, "the rear wheel", &self.rear_wheel),
            (&FRONT_WHEEL_KEYS, "the front wheel", &self.front_wheel),
        ] {
            let name = keys.name;
            check_mass(keys.m, w.m)?;
            if w.diameter < 0.0 {
                return Err(Error::InvalidParameter {
                    field: keys.d.to_string(),
                    value: w.diameter,
                    rule: "must not be negative".into(),
                });
            }
            inertia_of_massless(title, keys, w.m, w.inertia)?;
            if w.diameter == 0.0 && w.inertia[2] != 0.0 {
                return Err(Error::InvalidParameter {
                    field: keys.d.to_string(),
                    value: w.diameter,
                    rule: format!(
                        "a wheel of zero diameter (a skate) cannot have a spin moment of inertia \
                         (I{name}(3) = {}): its spin rate would be infinite",
                        short_number(w.inertia[2])
                    ),
                });
            }
            let [i11, i22, _] = w.inertia;
            let scale = w.inertia.iter().map(|v| v.abs()).sum::<f64>();
            if (i11 - i22).abs() > 1e-9 * scale {
                return Err(Error::InvalidBicycle {
                    fields: format!("I{name}"),
                    rule: format!(
                        "a wheel must be axisymmetric: its in-plane moments I11 = {} and I22 = {} must be equal",
                        short_number(i11),
                        short_number(i22)
                    ),
                });
            }
            principal_moments(
                keys.inertia,
                w.inertia,
                "the linear and the non-linear model, which both stay well defined",
                &mut notices,
            )?;
        }
        for (keys, title, m, inertia) in [
            (&RIDER_KEYS, "the rider", self.rider.m, self.rider.inertia),
            (
                &FRAME_KEYS,
                "the rear frame",
                self.frame.m,
                self.frame.inertia,
            ),
            (&RACK_KEYS, "the rear rack", self.rack.m, self.rack.inertia),
            (&FORK_KEYS, "the fork", self.fork.m, self.fork.inertia),
            (
                &BASKET_KEYS,
                "the basket",
                self.basket.m,
                self.basket.inertia,
            ),
        ] {
            check_mass(keys.m, m)?;
            inertia_of_massless(title, keys, m, inertia)?;
            principal_moments(
                keys.inertia,
                inertia,
                "the linear and the non-linear model (through the combined bodies), which both stay well defined",
                &mut notices,
            )?;
        }
        Ok(notices)
    }

    /// Converts to the 25 benchmark parameters (plus g): B = rider + frame + rack, H = fork +
    /// basket, combined with the parallel-axis theorem; with T a combined tensor in JBike6's
    /// axes, x_B = x, z_B = −y, I_Bxx = T_xx, I_Bzz = T_yy, I_Byy = T_zz, I_Bxz = −T_xy.
    /// Validates both this form and the result, naming JBike6's variables in errors.
    ///
    /// ```
    /// use whipple::presets;
    /// let crown = presets::schwinn_crown_jbike6();
    /// let bike = crown.to_benchmark()?;
    /// assert_eq!(bike.w, 1.016);
    /// assert!((bike.m_b - 84.5).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn to_benchmark(&self) -> Result<BenchmarkParameters> {
        self.to_benchmark_checked().map(|(bike, _)| bike)
    }

    /// [`Jbike6Parameters::to_benchmark`] with the warnings of both forms.
    pub fn to_benchmark_checked(&self) -> Result<(BenchmarkParameters, Vec<Notice>)> {
        let mut notices = self.check()?;
        let bike = self.to_benchmark_unchecked();
        let more = bike.check().map_err(rename_error)?;
        for mut n in more {
            if !n.field.starts_with('I') {
                n.field = rename_fields(&n.field);
                notices.push(n);
            }
        }
        Ok((bike, notices))
    }
}

/// The `.m` keys of one JBike6 body (static, so that checking a valid bicycle allocates
/// nothing).
struct BodyKeys {
    name: &'static str,
    m: &'static str,
    d: &'static str,
    inertia: [&'static str; 3],
}

macro_rules! body_keys {
    ($name:literal) => {
        BodyKeys {
            name: $name,
            m: concat!("m", $name),
            d: concat!("D", $name),
            inertia: [
                concat!("I", $name, "(1)"),
                concat!("I", $name, "(2)"),
                concat!("I", $name, "(3)"),
            ],
        }
    };
}

const REAR_WHEEL_KEYS: BodyKeys = body_keys!("rearwheel");
const FRONT_WHEEL_KEYS: BodyKeys = body_keys!("frontwheel");
const RIDER_KEYS: BodyKeys = body_keys!("rider");
const FRAME_KEYS: BodyKeys = body_keys!("frame");
const RACK_KEYS: BodyKeys = body_keys!("rack");
const FORK_KEYS: BodyKeys = body_keys!("fork");
const BASKET_KEYS: BodyKeys = body_keys!("basket");

fn inertia_of_massless(title: &str, keys: &BodyKeys, m: f64, inertia: [f64; 3]) -> Result<()> {
    let [a, b, c] = keys.inertia;
    zero_mass_inertia(
        title,
        keys.m,
        m,
        &[(a, inertia[0]), (b, inertia[1]), (c, inertia[2])],
    )
}
