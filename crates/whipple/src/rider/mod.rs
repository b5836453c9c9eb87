//! The Yeadon human body model (Yeadon 1990, "The simulation of aerial movement II: a
//! mathematical inertia model of the human body", J. Biomech. 23(1):67–74).
//!
//! The body is 11 segments — pelvis `P`, thorax `T`, chest-head `C`, upper arms `A1` (left) and
//! `B1` (right), forearm-hands `A2` and `B2`, thighs `J1` and `K1`, shank-feet `J2` and `K2` —
//! built of 39 stadium solids and the semi-ellipsoid of the head cap from the 95
//! anthropometric measurements (lengths `…L`, perimeters `…p`, widths `…w`, depths `…d`, named
//! as Yeadon's levels: `Ls` the torso, `La`/`Lb` the left/right arm, `Lj`/`Lk` the left/right
//! leg). Densities are Dempster's as the package `yeadon` tabulates them, scaled uniformly to
//! the measured total mass when the file gives one. Left and right limbs are averaged, as
//! `yeadon` does by default. The configuration's 21 angles (`somersault`, `tilt`, `twist`, …)
//! orient each segment relative to its parent by body-fixed x-y-z rotations.
//!
//! Frames: the origin is the centre of the hip level `Ls0`; in the zero configuration `z` runs
//! up the trunk and `x` to the body's left (the stadia's long direction). A segment's
//! orientation `R` maps its own components to global ones (`v_global = R v_local`), so its
//! inertia is `R I_local Rᵀ`.
//!
//! Against the package `yeadon` 2.0.1, whose formulas and file formats this follows, three
//! things differ, each checked by an identity in the tests: a truncated cone's mass centre
//! (yeadon measures it from the wrong end), the moment about a stadium solid's `x` axis
//! (`r³t`, not yeadon's `rt³`) and the rotation of a segment's inertia into the global frame
//! (yeadon applies the inverse rotation).

mod on_bicycle;
mod read;
mod solids;

use crate::math::Real;
use nalgebra::{Matrix3, Vector3};

pub use on_bicycle::{
    MAX_ITERATIONS, RIDER_GEOMETRY_KEYS, RiderBody, RiderGeometry, SEATED_ANGLES, SeatedRider,
    SeatedSolve, bottom_bracket, combine_with_rear_frame, handlebar_grips,
    rider_in_benchmark_frame, rider_on_bicycle, seat, seated_configuration, seated_rider,
    solve_seated,
};
pub use read::{read_yeadon_configuration, read_yeadon_measurements};

use crate::error::{Error, Result};
use solids::{SolidInertia, Stadium, c, measurement_error, semi_ellipsoid, stadium_solid};

/// The format name of a `*YeadonMeas.txt` in messages.
pub(crate) const MEASUREMENTS_FORMAT: &str = "Yeadon measurements .txt";
/// The format name of a `*YeadonCFG.txt` in messages.
pub(crate) const CONFIGURATION_FORMAT: &str = "Yeadon configuration .txt";

/// The 95 measurements' names in `yeadon`'s order: torso (21), left arm (18), right arm (18),
/// left leg (19), right leg (19).
pub const MEASUREMENT_NAMES: [&str; 95] = [
    "Ls1L", "Ls2L", "Ls3L", "Ls4L", "Ls5L", "Ls6L", "Ls7L", "Ls8L", "Ls0p", "Ls1p", "Ls2p", "Ls3p",
    "Ls5p", "Ls6p", "Ls7p", "Ls0w", "Ls1w", "Ls2w", "Ls3w", "Ls4w", "Ls4d", "La2L", "La3L", "La4L",
    "La5L", "La6L", "La7L", "La0p", "La1p", "La2p", "La3p", "La4p", "La5p", "La6p", "La7p", "La4w",
    "La5w", "La6w", "La7w", "Lb2L", "Lb3L", "Lb4L", "Lb5L", "Lb6L", "Lb7L", "Lb0p", "Lb1p", "Lb2p",
    "Lb3p", "Lb4p", "Lb5p", "Lb6p", "Lb7p", "Lb4w", "Lb5w", "Lb6w", "Lb7w", "Lj1L", "Lj3L", "Lj4L",
    "Lj5L", "Lj6L", "Lj8L", "Lj9L", "Lj1p", "Lj2p", "Lj3p", "Lj4p", "Lj5p", "Lj6p", "Lj7p", "Lj8p",
    "Lj9p", "Lj8w", "Lj9w", "Lj6d", "Lk1L", "Lk3L", "Lk4L", "Lk5L", "Lk6L", "Lk8L", "Lk9L", "Lk1p",
    "Lk2p", "Lk3p", "Lk4p", "Lk5p", "Lk6p", "Lk7p", "Lk8p", "Lk9p", "Lk8w", "Lk9w", "Lk6d",
];

/// The configuration's 21 joint angles with the range (rad) `yeadon` allows each.
pub const CONFIGURATION_ANGLES: [(&str, f64, f64); 21] = {
    use std::f64::consts::{FRAC_PI_2 as H, PI as P};
    [
        ("somersault", -P, P),
        ("tilt", -P, P),
        ("twist", -P, P),
        ("PTsagittalFlexion", -H, P),
        ("PTbending", -H, H),
        ("TCspinalTorsion", -H, H),
        ("TCsagittalSpinalFlexion", -H, H),
        ("CA1extension", -P, H),
        ("CA1adduction", -3.0 * H, H),
        ("CA1rotation", -P, P),
        ("CB1extension", -P, H),
        ("CB1abduction", -H, 3.0 * H),
        ("CB1rotation", -P, P),
        ("A1A2extension", -P, 0.0),
        ("B1B2extension", -P, 0.0),
        ("PJ1extension", -P, H),
        ("PJ1adduction", -H, H),
        ("PK1extension", -P, H),
        ("PK1abduction", -H, H),
        ("J1J2flexion", 0.0, P),
        ("K1K2flexion", 0.0, P),
    ]
};

/// The segments' names in order, with what each is.
pub const SEGMENT_NAMES: [(&str, &str); 11] = [
    ("P", "pelvis"),
    ("T", "thorax"),
    ("C", "chest-head"),
    ("A1", "left upper arm"),
    ("A2", "left forearm-hand"),
    ("B1", "right upper arm"),
    ("B2", "right forearm-hand"),
    ("J1", "left thigh"),
    ("J2", "left shank-foot"),
    ("K1", "right thigh"),
    ("K2", "right shank-foot"),
];

/// Dempster's segment densities (kg/m³) as `yeadon` tabulates them.
const HEAD_NECK: f64 = 1110.0;
const SHOULDERS: f64 = 1040.0;
const THORAX: f64 = 920.0;
const ABDOMEN_PELVIS: f64 = 1010.0;
const UPPER_ARM: f64 = 1070.0;
const FOREARM: f64 = 1130.0;
const HAND: f64 = 1160.0;
const THIGH: f64 = 1050.0;
const LOWER_LEG: f64 = 1090.0;
const FOOT: f64 = 1100.0;

/// The 95 measurements in SI units (m), in [`MEASUREMENT_NAMES`]' order.
#[derive(Debug, Clone, PartialEq)]
pub struct YeadonMeasurements<T> {
    /// The values (m), in [`MEASUREMENT_NAMES`]' order.
    pub values: [T; 95],
    /// The measured total mass (kg), to which the densities are scaled; `None` keeps
    /// Dempster's densities.
    pub total_mass: Option<T>,
    /// Each value's line in the file it was read from (0 where not from a file), for messages.
    pub lines: [usize; 95],
}

impl<T: Copy> YeadonMeasurements<T> {
    /// The value of a measurement by its name (`Ls1L`, `La4w`, …).
    pub fn get(&self, name: &str) -> Option<T> {
        MEASUREMENT_NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| self.values[i])
    }
}

/// The 21 joint angles (rad), in [`CONFIGURATION_ANGLES`]' order.
#[derive(Debug, Clone, PartialEq)]
pub struct YeadonConfiguration<T> {
    /// The angles (rad).
    pub angles: [T; 21],
    /// Each angle's line in the file it was read from (0 where not from a file).
    pub lines: [usize; 21],
}

impl<T: Real> YeadonConfiguration<T> {
    /// Every angle zero: standing, arms down.
    pub fn zero() -> Self {
        YeadonConfiguration {
            angles: [T::zero(); 21],
            lines: [0; 21],
        }
    }

    /// The value of an angle by its name (`somersault`, `CA1extension`, …).
    pub fn get(&self, name: &str) -> Option<T> {
        CONFIGURATION_ANGLES
            .iter()
            .position(|(n, _, _)| *n == name)
            .map(|i| self.angles[i])
    }

    /// Each angle within the range `yeadon` gives it ([`CONFIGURATION_ANGLES`]).
    pub fn check(&self) -> Result<()> {
        for (i, (name, low, high)) in CONFIGURATION_ANGLES.iter().enumerate() {
            let value = to_f64(self.angles[i]);
            if !(value >= *low && value <= *high) {
                return Err(measurement_error(
                    CONFIGURATION_FORMAT,
                    name,
                    self.lines[i],
                    value,
                    format!("{name} = {value} rad is outside its range [{low:.6}, {high:.6}] rad"),
                ));
            }
        }
        Ok(())
    }
}

fn to_f64<T: Real>(x: T) -> f64 {
    x.to_subset().unwrap_or(f64::NAN)
}

/// One segment of the body, placed by the configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct YeadonSegment<T> {
    /// Yeadon's name (`P`, `T`, `C`, `A1`, …; see [`SEGMENT_NAMES`]).
    pub name: &'static str,
    /// Its mass (kg).
    pub mass: T,
    /// Its proximal joint centre (for `P`, the origin) in the global frame (m).
    pub origin: Vector3<T>,
    /// Its mass centre in the global frame (m).
    pub center_of_mass: Vector3<T>,
    /// `R`: its own components to global ones.
    pub orientation: Matrix3<T>,
    /// Its inertia about its mass centre in its own frame (kg m²).
    pub local_inertia: Matrix3<T>,
    /// Its inertia about its mass centre in the global frame, `R I_local Rᵀ` (kg m²).
    pub inertia: Matrix3<T>,
}

/// The whole body: its segments and their sum.
#[derive(Debug, Clone, PartialEq)]
pub struct YeadonBody<T> {
    /// The 11 segments in [`SEGMENT_NAMES`]' order.
    pub segments: Vec<YeadonSegment<T>>,
    /// The body's mass (kg).
    pub mass: T,
    /// The body's mass centre in the global frame (m).
    pub center_of_mass: Vector3<T>,
    /// The body's inertia about its mass centre in the global frame (kg m²).
    pub inertia: Matrix3<T>,
}

/// The inertia of a point mass `m` at `d` from the point it is taken about (parallel axes).
pub(crate) fn parallel_axis<T: Real>(m: T, d: &Vector3<T>) -> Matrix3<T> {
    (Matrix3::identity() * d.dot(d) - d * d.transpose()) * m
}

/// Body-fixed x, then y, then z rotation: `Rx(a) Ry(b) Rz(c)`.
fn euler_123<T: Real>(a: T, b: T, c: T) -> Matrix3<T> {
    let (sa, ca) = crate::math::sin_cos(a);
    let (sb, cb) = crate::math::sin_cos(b);
    let (sc, cc) = crate::math::sin_cos(c);
    let (o, l) = (T::zero(), T::one());
    let rx = Matrix3::new(l, o, o, o, ca, -sa, o, sa, ca);
    let ry = Matrix3::new(cb, o, sb, o, l, o, -sb, o, cb);
    let rz = Matrix3::new(cc, -sc, o, sc, cc, o, o, o, l);
    rx * ry * rz
}

/// The measurements of one body, averaged left/right, with the file's lines for messages.
struct Reader<'a, T> {
    m: &'a YeadonMeasurements<T>,
    values: [T; 95],
}

impl<T: Real> Reader<'_, T> {
    fn index(name: &str) -> usize {
        MEASUREMENT_NAMES
            .iter()
            .position(|n| *n == name)
            .unwrap_or(0)
    }
    fn v(&self, name: &str) -> T {
        self.values[Self::index(name)]
    }
    fn error(&self, name: &str, rule: String) -> Error {
        let i = Self::index(name);
        measurement_error(
            MEASUREMENTS_FORMAT,
            name,
            self.m.lines[i],
            to_f64(self.m.values[i]),
            rule,
        )
    }
    fn circle(&self, p: &str) -> Stadium<T> {
        Stadium::circle(self.v(p))
    }
    fn perimeter_width(&self, p: &str, w: &str) -> Result<Stadium<T>> {
        let (pv, wv) = (self.v(p), self.v(w));
        Stadium::from_perimeter_width(
            pv,
            wv,
            &format!("{p} = {} m, {w} = {} m", to_f64(pv), to_f64(wv)),
        )
        .map_err(|rule| self.error(p, rule))
    }
    /// `upper − lower`, refused unless positive (a solid of negative or no volume).
    fn height(&self, upper: T, lower: T, upper_name: &str, what: &str) -> Result<T> {
        let h = upper - lower;
        if h > T::zero() {
            Ok(h)
        } else {
            Err(self.error(
                upper_name,
                format!(
                    "the solid {what} would have a height of {} m (negative or no volume): \
                     the lengths must increase away from the joint",
                    to_f64(h)
                ),
            ))
        }
    }
}

/// A solid in a segment: its inertia, height and whether its stadia lie antero-posteriorly.
struct Placed<T> {
    solid: SolidInertia<T>,
    height: T,
    antero_posterior: bool,
}

/// A limb's two segments: the solids of its upper and lower segment.
type Limb<T> = (Vec<Placed<T>>, Vec<Placed<T>>);

/// A segment's mass, mass centre on its z axis, inertia about it (own frame) and length, its
/// solids stacked from its joint along +z (`up`) or −z.
fn stack<T: Real>(solids: &[Placed<T>], up: bool) -> (T, T, Matrix3<T>, T) {
    let mut mass = T::zero();
    let mut moment = T::zero();
    let mut start = T::zero();
    let mut centres = Vec::with_capacity(solids.len());
    for s in solids {
        // A solid's first stadium is at its lower end when stacked up, its far end when down.
        let z = if up {
            start + s.solid.z
        } else {
            -(start + s.height) + s.solid.z
        };
        start += s.height;
        mass += s.solid.mass;
        moment += s.solid.mass * z;
        centres.push(z);
    }
    let zc = moment / mass;
    let mut inertia = Matrix3::zeros();
    for (s, z) in solids.iter().zip(centres) {
        let [mut ix, mut iy, iz] = s.solid.moments;
        if s.antero_posterior {
            std::mem::swap(&mut ix, &mut iy);
        }
        let d = z - zc;
        inertia += Matrix3::from_diagonal(&Vector3::new(ix, iy, iz))
            + parallel_axis(s.solid.mass, &Vector3::new(T::zero(), T::zero(), d));
    }
    let length = if up { start } else { -start };
    (mass, zc, inertia, length)
}

/// The body of these measurements in this configuration: every segment's and the whole body's
/// mass, mass centre and inertia. Fails naming the measurement (and its file line) where a
/// level is not a stadium, a solid would have negative volume or a value is not positive, and
/// naming the angle where it is out of range.
pub fn yeadon_body<T: Real>(
    measurements: &YeadonMeasurements<T>,
    configuration: &YeadonConfiguration<T>,
) -> Result<YeadonBody<T>> {
    configuration.check()?;
    for (i, name) in MEASUREMENT_NAMES.iter().enumerate() {
        let v = to_f64(measurements.values[i]);
        if !(v.is_finite() && v > 0.0) {
            return Err(measurement_error(
                MEASUREMENTS_FORMAT,
                name,
                measurements.lines[i],
                v,
                format!("{name} = {v} m: every measurement must be positive and finite"),
            ));
        }
    }
    if let Some(total) = measurements.total_mass {
        let v = to_f64(total);
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::InvalidParameter {
                field: "totalmass".to_string(),
                value: v,
                rule: "the total mass must be positive and finite".to_string(),
            });
        }
    }
    let reader = Reader {
        m: measurements,
        values: averaged(measurements),
    };
    let body = build(&reader, configuration, T::one())?;
    let body = match measurements.total_mass {
        Some(total) => build(&reader, configuration, total / body.mass)?,
        None => body,
    };
    let finite = std::iter::once(body.mass)
        .chain(body.center_of_mass.iter().copied())
        .chain(body.inertia.iter().copied())
        .all(|x| to_f64(x).is_finite());
    if !finite {
        return Err(Error::NonFinite {
            context: "the Yeadon body (measurements too large for the arithmetic)".to_string(),
        });
    }
    Ok(body)
}

/// The measurements with left and right limbs averaged (as `yeadon` does by default): left arm
/// 21..39 with right arm 39..57, left leg 57..76 with right leg 76..95.
pub(crate) fn averaged<T: Real>(measurements: &YeadonMeasurements<T>) -> [T; 95] {
    let mut values = measurements.values;
    for (left, right) in (21..39).zip(39..57).chain((57..76).zip(76..95)) {
        let mean = (values[left] + values[right]) * c(0.5);
        values[left] = mean;
        values[right] = mean;
    }
    values
}

/// The segments placed by a configuration without checking the angles' ranges (Dempster's
/// densities unscaled: the places, not the masses, are what this is for): the iterates of
/// the seated rider's joint-angle solve ([`on_bicycle`]). The measurements must have passed
/// [`yeadon_body`] once.
pub(crate) fn placed<T: Real>(
    measurements: &YeadonMeasurements<T>,
    configuration: &YeadonConfiguration<T>,
) -> Result<YeadonBody<T>> {
    let reader = Reader {
        m: measurements,
        values: averaged(measurements),
    };
    build(&reader, configuration, T::one())
}

fn build<T: Real>(
    r: &Reader<'_, T>,
    cfg: &YeadonConfiguration<T>,
    scale: T,
) -> Result<YeadonBody<T>> {
    let density = |d: f64| c::<T>(d) * scale;
    let placed = |d: f64, s0: Stadium<T>, s1: Stadium<T>, h: T, ap: bool| Placed {
        solid: stadium_solid(density(d), s0, s1, h),
        height: h,
        antero_posterior: ap,
    };
    let zero = T::zero();
    // Torso levels.
    let ls0 = r.perimeter_width("Ls0p", "Ls0w")?;
    let ls1 = r.perimeter_width("Ls1p", "Ls1w")?;
    let ls2 = r.perimeter_width("Ls2p", "Ls2w")?;
    let ls3 = r.perimeter_width("Ls3p", "Ls3w")?;
    let ls4 = Stadium::from_depth_width(r.v("Ls4d"), r.v("Ls4w"), "Ls4d, Ls4w")
        .map_err(|rule| r.error("Ls4d", rule))?;
    // The acromion level cannot be measured: Yeadon's ISEG code takes 0.57 of the shoulder
    // level's radius and keeps its width (as `yeadon` does).
    let shoulder_width = r.v("Ls4w");
    let ls5_radius = c::<T>(0.57) * ls4.radius;
    let ls5 = Stadium {
        radius: ls5_radius,
        thickness: shoulder_width / c(2.0) - ls5_radius,
    };
    let (ls5_neck, ls6, ls7) = (r.circle("Ls5p"), r.circle("Ls6p"), r.circle("Ls7p"));
    let h = |upper: &str, lower: Option<&str>, what: &str| -> Result<T> {
        r.height(r.v(upper), lower.map_or(zero, |l| r.v(l)), upper, what)
    };
    let s0 = placed(ABDOMEN_PELVIS, ls0, ls1, h("Ls1L", None, "s0")?, false);
    let s1 = placed(
        ABDOMEN_PELVIS,
        ls1,
        ls2,
        h("Ls2L", Some("Ls1L"), "s1")?,
        false,
    );
    let s2 = placed(THORAX, ls2, ls3, h("Ls3L", Some("Ls2L"), "s2")?, false);
    let s3 = placed(THORAX, ls3, ls4, h("Ls4L", Some("Ls3L"), "s3")?, false);
    let s4 = placed(SHOULDERS, ls4, ls5, h("Ls5L", Some("Ls4L"), "s4")?, false);
    let s5 = placed(HEAD_NECK, ls5_neck, ls6, h("Ls6L", None, "s5")?, false);
    let s6 = placed(HEAD_NECK, ls6, ls7, h("Ls7L", Some("Ls6L"), "s6")?, false);
    let h7 = h("Ls8L", Some("Ls7L"), "s7 (head cap)")?;
    let s7 = Placed {
        solid: semi_ellipsoid(density(HEAD_NECK), r.v("Ls7p"), h7),
        height: h7,
        antero_posterior: false,
    };
    let s3_height = s3.height;

    // Arms: levels 0..7 from the shoulder, solids built from the distal level up.
    let arm = |side: char| -> Result<Limb<T>> {
        let n = |suffix: &str| format!("L{side}{suffix}");
        let mut levels = Vec::with_capacity(8);
        for i in 0..4 {
            levels.push(r.circle(&n(&format!("{i}p"))));
        }
        for i in 4..8 {
            levels.push(r.perimeter_width(&n(&format!("{i}p")), &n(&format!("{i}w")))?);
        }
        let half = r.v(&n("2L")) * c(0.5);
        let heights = [
            r.height(half, zero, &n("2L"), &format!("{side}0"))?,
            r.height(r.v(&n("2L")), half, &n("2L"), &format!("{side}1"))?,
            r.height(r.v(&n("3L")), r.v(&n("2L")), &n("3L"), &format!("{side}2"))?,
            r.height(r.v(&n("4L")), r.v(&n("3L")), &n("4L"), &format!("{side}3"))?,
            r.height(r.v(&n("5L")), zero, &n("5L"), &format!("{side}4"))?,
            r.height(r.v(&n("6L")), r.v(&n("5L")), &n("6L"), &format!("{side}5"))?,
            r.height(r.v(&n("7L")), r.v(&n("6L")), &n("7L"), &format!("{side}6"))?,
        ];
        let densities = [UPPER_ARM, UPPER_ARM, FOREARM, FOREARM, HAND, HAND, HAND];
        let mut solids: Vec<Placed<T>> = (0..7)
            .map(|i| placed(densities[i], levels[i + 1], levels[i], heights[i], false))
            .collect();
        let lower = solids.split_off(2);
        Ok((solids, lower))
    };
    let leg = |side: char| -> Result<Limb<T>> {
        let n = |suffix: &str| format!("L{side}{suffix}");
        // The hip level: a circle of the mean of Ls0's radius and width.
        let hip = Stadium::circle(T::pi() * (ls0.radius * r.v("Ls0w")).abs().sqrt());
        let mut levels = vec![hip];
        for i in 1..6 {
            levels.push(r.circle(&n(&format!("{i}p"))));
        }
        levels.push(r.perimeter_width(&n("6p"), &n("6d"))?);
        levels.push(r.circle(&n("7p")));
        levels.push(r.perimeter_width(&n("8p"), &n("8w"))?);
        levels.push(r.perimeter_width(&n("9p"), &n("9w"))?);
        let mid_thigh = (r.v(&n("3L")) + r.v(&n("1L"))) * c(0.5);
        let arch = (r.v(&n("8L")) + r.v(&n("6L"))) * c(0.5);
        let heights = [
            r.height(r.v(&n("1L")), zero, &n("1L"), &format!("{side}0"))?,
            r.height(mid_thigh, r.v(&n("1L")), &n("3L"), &format!("{side}1"))?,
            r.height(r.v(&n("3L")), mid_thigh, &n("3L"), &format!("{side}2"))?,
            r.height(r.v(&n("4L")), r.v(&n("3L")), &n("4L"), &format!("{side}3"))?,
            r.height(r.v(&n("5L")), r.v(&n("4L")), &n("5L"), &format!("{side}4"))?,
            r.height(r.v(&n("6L")), zero, &n("6L"), &format!("{side}5"))?,
            r.height(arch, r.v(&n("6L")), &n("8L"), &format!("{side}6"))?,
            r.height(r.v(&n("8L")), arch, &n("8L"), &format!("{side}7"))?,
            r.height(r.v(&n("9L")), r.v(&n("8L")), &n("9L"), &format!("{side}8"))?,
        ];
        let densities = [
            THIGH, THIGH, THIGH, LOWER_LEG, LOWER_LEG, FOOT, FOOT, FOOT, FOOT,
        ];
        // The heel level (6) lies antero-posteriorly: so do the two solids that touch it.
        let mut solids: Vec<Placed<T>> = (0..9)
            .map(|i| {
                placed(
                    densities[i],
                    levels[i + 1],
                    levels[i],
                    heights[i],
                    i == 5 || i == 6,
                )
            })
            .collect();
        let lower = solids.split_off(3);
        Ok((solids, lower))
    };
    let (a1, a2) = arm('a')?;
    let (b1, b2) = arm('b')?;
    let (j1, j2) = leg('j')?;
    let (k1, k2) = leg('k')?;

    let q = |name: &str| cfg.get(name).unwrap_or(zero);
    let mut segments = Vec::with_capacity(11);
    let mut place = |name: &'static str,
                     origin: Vector3<T>,
                     rot: Matrix3<T>,
                     solids: &[Placed<T>],
                     up: bool| {
        let (mass, zc, local, length) = stack(solids, up);
        let axis = rot * Vector3::z();
        segments.push(YeadonSegment {
            name,
            mass,
            origin,
            center_of_mass: origin + axis * zc,
            orientation: rot,
            local_inertia: local,
            inertia: rot * local * rot.transpose(),
        });
        origin + axis * length
    };
    let r_p = euler_123(q("somersault"), q("tilt"), q("twist"));
    let origin = Vector3::zeros();
    let p_end = place("P", origin, r_p, &[s0, s1], true);
    let r_t = r_p * euler_123(q("PTsagittalFlexion"), q("PTbending"), zero);
    let t_end = place("T", p_end, r_t, &[s2], true);
    let r_c = r_t * euler_123(q("TCsagittalSpinalFlexion"), zero, q("TCspinalTorsion"));
    place("C", t_end, r_c, &[s3, s4, s5, s6, s7], true);
    let shoulder =
        |sign: T| t_end + r_c * Vector3::new(sign * shoulder_width / c(2.0), zero, s3_height);
    let r_a1 = r_c * euler_123(q("CA1extension"), q("CA1adduction"), q("CA1rotation"));
    let elbow = place("A1", shoulder(T::one()), r_a1, &a1, false);
    place(
        "A2",
        elbow,
        r_a1 * euler_123(q("A1A2extension"), zero, zero),
        &a2,
        false,
    );
    let r_b1 = r_c * euler_123(q("CB1extension"), q("CB1abduction"), q("CB1rotation"));
    let elbow = place("B1", shoulder(-T::one()), r_b1, &b1, false);
    place(
        "B2",
        elbow,
        r_b1 * euler_123(q("B1B2extension"), zero, zero),
        &b2,
        false,
    );
    let hip_half_width = (ls0.thickness + ls0.radius) / c(2.0);
    let hip = |sign: T| origin + r_p * Vector3::new(sign * hip_half_width, zero, zero);
    let r_j1 = r_p * euler_123(q("PJ1extension"), q("PJ1adduction"), zero);
    let knee = place("J1", hip(T::one()), r_j1, &j1, false);
    place(
        "J2",
        knee,
        r_j1 * euler_123(q("J1J2flexion"), zero, zero),
        &j2,
        false,
    );
    let r_k1 = r_p * euler_123(q("PK1extension"), q("PK1abduction"), zero);
    let knee = place("K1", hip(-T::one()), r_k1, &k1, false);
    place(
        "K2",
        knee,
        r_k1 * euler_123(q("K1K2flexion"), zero, zero),
        &k2,
        false,
    );

    let mass = segments.iter().fold(zero, |m, s| m + s.mass);
    let center_of_mass = segments
        .iter()
        .fold(Vector3::zeros(), |acc, s| acc + s.center_of_mass * s.mass)
        / mass;
    let inertia = segments.iter().fold(Matrix3::zeros(), |acc, s| {
        acc + s.inertia + parallel_axis(s.mass, &(s.center_of_mass - center_of_mass))
    });
    Ok(YeadonBody {
        segments,
        mass,
        center_of_mass,
        inertia,
    })
}
