//! A bicycle from bench measurements: BicycleParameters' `*Measured.txt` read into typed
//! [`Measurements`], and the pipeline (Moore 2012 ch. 2; Moore, Hubbard, Kooijman & Schwab
//! 2010) that turns them into [`BenchmarkParameters`] with the standard deviation of every
//! output and their full covariance, by exact first-order propagation (one dual-number pass
//! per measurement through the same steps as the values, [`steps`]).
//!
//! The pipeline, in order:
//! 1. wheel radii from the distance rolled in whole turns ([`steps::wheel_radius`]);
//! 2. the geometry: steer axis tilt from the head tube angle, wheelbase as measured, trail
//!    from the fork offset ([`steps::steer_axis_tilt`], [`steps::trail`]); or, measured as
//!    perpendicular distances ([`Geometry::Offsets`]), the offsets of the hubs from the steer
//!    axis ([`steps::steer_axis_offsets`]), the tilt that puts both wheels on the ground
//!    ([`steps::steer_axis_tilt_from_offsets`], Newton's method with its implicit
//!    derivative), the wheelbase ([`steps::wheelbase_from_offsets`]) and the trail;
//! 3. each hung frame's mass centre from the lines of its hangings
//!    ([`steps::hanging_line_through`], [`steps::mass_centre`]): the rear frame and the front
//!    frame, or the fork and the handlebar measured apart, the handlebar referred to its
//!    reference circle ([`steps::handlebar_reference`],
//!    [`steps::handlebar_reference_offset`]);
//! 4. the wheels' and frames' moments about y from compound pendulum periods
//!    ([`steps::compound_pendulum_inertia`], [`steps::pendulum_length`]);
//! 5. the torsion constant from the calibration rod ([`steps::rod_transverse_inertia`],
//!    [`steps::torsion_constant`]);
//! 6. the wheels' moments about a diameter and the frames' in-plane tensors from torsional
//!    pendulum periods ([`steps::torsional_pendulum_inertia`], [`steps::planar_inertia`]);
//!    a fork and handlebar measured apart combined into the front frame by parallel axes;
//!    a flywheel inside the front wheel as the wheel-with-flywheel's values less the wheel's
//!    ([`steps::flywheel_part`]), kept as extras (the model has no flywheel);
//! 7. masses and g as measured.
//!
//! Measurements are independent inputs; a key given as a list (repeated measurements) is
//! their mean, with σ = √(Σσᵢ²)/n as BicycleParameters computes it.

pub mod period;
mod read;
pub(crate) mod report;
pub mod steps;
#[cfg(test)]
mod tests;

use crate::math::Real;
use std::collections::BTreeMap;

use nalgebra::DMatrix;
use num_dual::Dual64;

use super::benchmark::{BENCHMARK_TABLE, BenchmarkParameters};
use super::jbike6::PlaneBody;
use super::{Bicycle, Description, Extra};
use crate::error::{Error, Result};
use crate::rider::{
    RIDER_GEOMETRY_KEYS, RiderGeometry, SEATED_ANGLES, SeatedRider, SeatedSolve,
    YeadonConfiguration, YeadonMeasurements, combine_with_rear_frame, seated_rider, solve_seated,
};

pub use read::{
    FittedPeriod, MAX_HANGINGS, MeasuredFile, PeriodSource, read_measurements,
    read_measurements_with_records, record_name,
};

/// A measured value with its standard deviation and where it was read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// The value (the mean of a list) in the file's unit.
    pub value: f64,
    /// Its standard deviation σ (0 where the file gave none).
    pub sigma: f64,
    /// The 1-based line of the file it was read from (0 when not read from a file).
    pub line: usize,
}

impl Measured {
    /// A value with its σ, not from a file.
    pub fn new(value: f64, sigma: f64) -> Self {
        Measured {
            value,
            sigma,
            line: 0,
        }
    }
}

/// One hanging of a frame: how it hung from the torsional pendulum's wire, and its period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hanging<T = Measured> {
    /// `alphaB1`…: the steer axis' angle α with the horizontal, right side view \[deg\].
    pub alpha: T,
    /// `aB1`…: the wire's distance from the wheel's centre, positive with the centre on the
    /// wire's left \[m\].
    pub a: T,
    /// `TtB1`…: the torsional pendulum's period in this hanging \[s\].
    pub period: T,
}

/// How the steer axis and the wheelbase were measured.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry<T = Measured> {
    /// `w`, `gamma`, `f`: the wheelbase, the head tube's angle and the fork offset.
    Direct {
        /// `w`: wheelbase \[m\].
        w: T,
        /// `gamma`: the head tube's angle with the ground \[deg\].
        gamma: T,
        /// `f`: fork offset, the front hub's perpendicular distance to the steer axis \[m\].
        f: T,
    },
    /// `h1`…`h5`, `d1`…`d4`, `d`: perpendicular distances measured on a surface plate
    /// ([`steps::steer_axis_offsets`]).
    Offsets(Offsets<T>),
}

/// The geometry as perpendicular distances (BicycleParameters' `h1`…`h5`, `d1`…`d4`, `d`;
/// Moore 2012 §2.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Offsets<T = Measured> {
    /// `h1`…`h5`: heights of the rear axle's top (from the gauge's base), the gauge's base,
    /// the head tube's top, the front axle's top and the steer tube's top \[m\].
    pub h: [T; 5],
    /// `d1`: the head tube's outer diameter \[m\].
    pub d1: T,
    /// `d2`: the dummy rear axle's diameter \[m\].
    pub d2: T,
    /// `d3`: the dummy front axle's diameter \[m\].
    pub d3: T,
    /// `d4`: the steer tube's outer diameter \[m\].
    pub d4: T,
    /// `d`: the inside distance between the axles with the fork reversed \[m\].
    pub d: T,
}

/// One frame hung on the bench: its mass, its compound pendulum period about its reference
/// point and its torsional hangings.
#[derive(Debug, Clone, PartialEq)]
pub struct HungPart<T = Measured> {
    /// `mH`, `mS`, `mG`: the mass \[kg\].
    pub mass: T,
    /// `TcH1`, `TcS1`, `TcG1`: the compound pendulum period \[s\].
    pub compound_period: T,
    /// `alphaH1`, `aH1`, `TtH1`, …: the hangings, in number order.
    pub hangings: Vec<Hanging<T>>,
}

/// The front frame as measured: fork and handlebar as one frame (part H), or apart (the fork
/// S, the handlebar G) and then combined.
#[derive(Debug, Clone, PartialEq)]
pub enum FrontFrame<T = Measured> {
    /// Part H: fork and handlebar together, referred to the front hub.
    Whole(HungPart<T>),
    /// Parts S (the fork, referred to the front hub) and G (the handlebar, referred to its
    /// reference circle, located by [`HandlebarReference`]).
    Split {
        /// The fork, S.
        fork: HungPart<T>,
        /// The handlebar, G.
        handlebar: HungPart<T>,
        /// Where the handlebar's reference point is.
        reference: HandlebarReference<T>,
    },
}

/// The handlebar's reference circle relative to the front axle (`h6`, `h7`, `d5`, `d6`, `l`;
/// [`steps::handlebar_reference`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandlebarReference<T = Measured> {
    /// `h6`: height of the front axle's top \[m\].
    pub h6: T,
    /// `h7`: height of the reference circle's top \[m\].
    pub h7: T,
    /// `d5`: the front axle's diameter \[m\].
    pub d5: T,
    /// `d6`: the reference circle's diameter \[m\].
    pub d6: T,
    /// `l`: the outer distance from the axle to the circle \[m\].
    pub l: T,
}

/// A flywheel inside the front wheel (part D), measured together with the wheel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flywheel<T = Measured> {
    /// `mD`: the front wheel's mass with the flywheel \[kg\].
    pub mass: T,
    /// `TcD1`: their compound pendulum period, swung at the front wheel's length `lF` \[s\].
    pub compound_period: T,
    /// `TtD1`: their torsional pendulum period about a diameter \[s\].
    pub torsional_period: T,
}

/// The measurements of a bicycle on the bench, under BicycleParameters' file keys (Moore 2012
/// ch. 2): the geometry measured directly or as perpendicular distances, the front frame as
/// one or as fork and handlebar apart, with or without a flywheel in the front wheel. Generic
/// over the scalar so that the pipeline runs on dual numbers; the file's form is
/// `Measurements<Measured>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurements<T = Measured> {
    /// `g`: gravity where the pendulums swung \[m/s²\].
    pub g: T,
    /// `dR`: the distance the rear wheel rolled \[m\].
    pub d_r: T,
    /// `nR`: in that many whole turns.
    pub n_r: T,
    /// `dF`: the distance the front wheel rolled \[m\].
    pub d_f: T,
    /// `nF`: in that many whole turns.
    pub n_f: T,
    /// The steer axis and wheelbase.
    pub geometry: Geometry<T>,
    /// `mR`: rear wheel mass \[kg\].
    pub m_r: T,
    /// `mF`: front wheel mass \[kg\].
    pub m_f: T,
    /// `mB`: rear frame mass \[kg\].
    pub m_b: T,
    /// `lR`: the rear wheel's compound pendulum length, axle to pivot \[m\].
    pub l_r: T,
    /// `lF`: the front wheel's compound pendulum length \[m\].
    pub l_f: T,
    /// `TcR1`: the rear wheel's compound pendulum period \[s\].
    pub t_c_r: T,
    /// `TcF1`: the front wheel's compound pendulum period \[s\].
    pub t_c_f: T,
    /// `TcB1`: the rear frame's compound pendulum period, swung about the rear axle \[s\].
    pub t_c_b: T,
    /// `TtR1`: the rear wheel's torsional pendulum period, about a diameter \[s\].
    pub t_t_r: T,
    /// `TtF1`: the front wheel's torsional pendulum period, about a diameter \[s\].
    pub t_t_f: T,
    /// `mP`: the calibration rod's mass \[kg\].
    pub m_p: T,
    /// `lP`: its length \[m\].
    pub l_p: T,
    /// `dP`: its diameter \[m\].
    pub d_p: T,
    /// `TtP1`: its torsional pendulum period \[s\].
    pub t_t_p: T,
    /// The rear frame's hangings (`alphaB1`, `aB1`, `TtB1`, …), in number order.
    pub rear_frame: Vec<Hanging<T>>,
    /// The front frame (H, or S and G).
    pub front_frame: FrontFrame<T>,
    /// A flywheel in the front wheel (D), if any.
    pub flywheel: Option<Flywheel<T>>,
}

/// A frame's hangings visited in number order (`alpha{part}n`, `a{part}n`, `Tt{part}n`).
fn walk_hangings<T, U>(
    f: &mut dyn FnMut(&str, &T) -> U,
    part: &str,
    set: &[Hanging<T>],
) -> Vec<Hanging<U>> {
    set.iter()
        .enumerate()
        .map(|(i, h)| {
            let n = i + 1;
            let alpha = f(&format!("alpha{part}{n}"), &h.alpha);
            let a = f(&format!("a{part}{n}"), &h.a);
            let period = f(&format!("Tt{part}{n}"), &h.period);
            Hanging { alpha, a, period }
        })
        .collect()
}

impl<T> Measurements<T> {
    /// Every value visited in the one fixed order of [`Measurements::entries`] (scalars, the
    /// geometry, the flywheel, the rear frame's hangings, then the front frame: H, or S and G
    /// and the handlebar's reference), each with its file key, into a copy holding `f`'s
    /// results.
    fn walk<U>(&self, f: &mut dyn FnMut(&str, &T) -> U) -> Measurements<U> {
        let g = f("g", &self.g);
        let d_r = f("dR", &self.d_r);
        let n_r = f("nR", &self.n_r);
        let d_f = f("dF", &self.d_f);
        let n_f = f("nF", &self.n_f);
        let geometry = match &self.geometry {
            Geometry::Direct { w, gamma, f: fo } => {
                let w = f("w", w);
                let gamma = f("gamma", gamma);
                let fo = f("f", fo);
                Geometry::Direct { w, gamma, f: fo }
            }
            Geometry::Offsets(o) => {
                let h0 = f("h1", &o.h[0]);
                let h1 = f("h2", &o.h[1]);
                let h2 = f("h3", &o.h[2]);
                let h3 = f("h4", &o.h[3]);
                let h4 = f("h5", &o.h[4]);
                let d1 = f("d1", &o.d1);
                let d2 = f("d2", &o.d2);
                let d3 = f("d3", &o.d3);
                let d4 = f("d4", &o.d4);
                let d = f("d", &o.d);
                Geometry::Offsets(Offsets {
                    h: [h0, h1, h2, h3, h4],
                    d1,
                    d2,
                    d3,
                    d4,
                    d,
                })
            }
        };
        let m_r = f("mR", &self.m_r);
        let m_f = f("mF", &self.m_f);
        let m_b = f("mB", &self.m_b);
        let l_r = f("lR", &self.l_r);
        let l_f = f("lF", &self.l_f);
        let t_c_r = f("TcR1", &self.t_c_r);
        let t_c_f = f("TcF1", &self.t_c_f);
        let t_c_b = f("TcB1", &self.t_c_b);
        let t_t_r = f("TtR1", &self.t_t_r);
        let t_t_f = f("TtF1", &self.t_t_f);
        let m_p = f("mP", &self.m_p);
        let l_p = f("lP", &self.l_p);
        let d_p = f("dP", &self.d_p);
        let t_t_p = f("TtP1", &self.t_t_p);
        let flywheel = self.flywheel.as_ref().map(|d| Flywheel {
            mass: f("mD", &d.mass),
            compound_period: f("TcD1", &d.compound_period),
            torsional_period: f("TtD1", &d.torsional_period),
        });
        let rear_frame = walk_hangings(f, "B", &self.rear_frame);
        let part = |f: &mut dyn FnMut(&str, &T) -> U, p: &str, part: &HungPart<T>| {
            let mass = f(&format!("m{p}"), &part.mass);
            let compound_period = f(&format!("Tc{p}1"), &part.compound_period);
            HungPart {
                mass,
                compound_period,
                hangings: walk_hangings(f, p, &part.hangings),
            }
        };
        let front_frame = match &self.front_frame {
            FrontFrame::Whole(h) => FrontFrame::Whole(part(f, "H", h)),
            FrontFrame::Split {
                fork,
                handlebar,
                reference,
            } => {
                let fork = part(f, "S", fork);
                let handlebar = part(f, "G", handlebar);
                let reference = HandlebarReference {
                    h6: f("h6", &reference.h6),
                    h7: f("h7", &reference.h7),
                    d5: f("d5", &reference.d5),
                    d6: f("d6", &reference.d6),
                    l: f("l", &reference.l),
                };
                FrontFrame::Split {
                    fork,
                    handlebar,
                    reference,
                }
            }
        };
        Measurements {
            g,
            d_r,
            n_r,
            d_f,
            n_f,
            geometry,
            m_r,
            m_f,
            m_b,
            l_r,
            l_f,
            t_c_r,
            t_c_f,
            t_c_b,
            t_t_r,
            t_t_f,
            m_p,
            l_p,
            d_p,
            t_t_p,
            rear_frame,
            front_frame,
            flywheel,
        }
    }

    /// The same measurements with every value mapped, in the order of [`Measurements::entries`].
    pub fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> Measurements<U> {
        self.walk(&mut |_, v| f(v))
    }
}

impl<T: Copy> Measurements<T> {
    /// Every value with its file key, in a fixed order (scalars, the geometry, the flywheel
    /// where measured, the rear frame's hangings, then the front frame: mass, compound period
    /// and hangings of H, or of S and G followed by the handlebar's reference).
    pub fn entries(&self) -> Vec<(String, T)> {
        let mut out = Vec::new();
        self.walk(&mut |k, v| out.push((k.to_string(), *v)));
        out
    }
}

impl Measurements<Measured> {
    /// The values alone.
    pub fn values(&self) -> Measurements<f64> {
        self.map(|m| m.value)
    }

    /// Checks what the pipeline divides by or takes roots of: every value finite, every σ
    /// finite and non-negative, periods, masses, lengths, turns and g positive; perpendicular
    /// distances that describe a steer axis and a handlebar reference the axle can reach. The
    /// error names the key and its line.
    pub fn check(&self) -> Result<()> {
        let at = |m: &Measured| {
            if m.line > 0 {
                format!(" (line {})", m.line)
            } else {
                String::new()
            }
        };
        for (key, m) in self.entries() {
            let bad = |rule: String| Error::InvalidParameter {
                field: key.clone(),
                value: m.value,
                rule,
            };
            if !m.value.is_finite() {
                return Err(bad(format!("must be finite{}", at(&m))));
            }
            if !(m.sigma.is_finite() && m.sigma >= 0.0) {
                return Err(bad(format!(
                    "its standard deviation {} must be finite and not negative{}",
                    m.sigma,
                    at(&m)
                )));
            }
            let positive = key.starts_with('T')
                || key.starts_with('m')
                || key.starts_with('n')
                || matches!(
                    key.as_str(),
                    "g" | "dR" | "dF" | "w" | "lR" | "lF" | "lP" | "dP" | "d" | "l"
                );
            if positive && m.value <= 0.0 {
                let what = match key.as_bytes().first() {
                    Some(b'T') => "a period",
                    Some(b'm') => "a mass",
                    Some(b'n') => "a number of turns",
                    _ if key == "lP" => "the calibration rod's length",
                    _ if key == "dP" => "the calibration rod's diameter",
                    _ => "a length",
                };
                return Err(bad(format!("{what} must be positive{}", at(&m))));
            }
        }
        if let Geometry::Offsets(o) = &self.geometry {
            let v = o.h.map(|m| m.value);
            let (a, b, span) = steps::steer_axis_offsets(
                v, o.d1.value, o.d2.value, o.d3.value, o.d4.value, o.d.value,
            );
            if (a + b).is_nan() || a + b <= 0.0 {
                return Err(Error::InvalidParameter {
                    field: "h1".into(),
                    value: o.h[0].value,
                    rule: format!(
                        "h1…h5 and d1…d4 give the rear frame's offset a = {a} m and the fork's \
                         b = {b} m from the steer axis, whose sum must be positive{}",
                        at(&o.h[0])
                    ),
                });
            }
            if span.is_nan() || span <= 0.0 {
                return Err(Error::InvalidParameter {
                    field: "d".into(),
                    value: o.d.value,
                    rule: format!(
                        "the hubs, d + (d2 + d3)/2 = {} m apart, must be farther apart than \
                         the offsets' difference |a − b| = {} m for a steer axis to join \
                         them{}",
                        o.d.value + 0.5 * (o.d2.value + o.d3.value),
                        (a - b).abs(),
                        at(&o.d)
                    ),
                });
            }
        }
        if let FrontFrame::Split { reference: r, .. } = &self.front_frame {
            let (l1, l2) = steps::handlebar_reference(
                r.h6.value, r.h7.value, r.d5.value, r.d6.value, r.l.value,
            );
            if l2.is_nan() || l2 <= 0.0 {
                return Err(Error::InvalidParameter {
                    field: "l".into(),
                    value: r.l.value,
                    rule: format!(
                        "the handlebar's reference circle, {l1} m above the front axle \
                         across the steer axis (h6, h7, d5, d6), must be nearer than the \
                         centres' distance l − d5/2 − d6/2 = {} m{}",
                        r.l.value - 0.5 * (r.d5.value + r.d6.value),
                        at(&r.l)
                    ),
                });
            }
        }
        Ok(())
    }
}

/// The benchmark parameters computed from [`Measurements`] (the pipeline of the module's
/// documentation), on any scalar. Fails, naming the measurement, where the hangings do not
/// determine a mass centre or an inertia.
pub fn benchmark_from_measurements<T: Real>(m: &Measurements<T>) -> Result<BenchmarkParameters<T>> {
    pipeline(m).map(|(benchmark, _)| benchmark)
}

/// One frame hung on the bench as the pipeline sees it: its letter (B, H, S, G), its name in
/// the report, and the point its hangings and its compound pendulum are referred to.
struct PartSpec<'a, T> {
    letter: &'static str,
    name: &'static str,
    mass: T,
    compound_period: T,
    hangings: &'a [Hanging<T>],
    reference: (T, T),
    reference_name: &'static str,
}

/// What the pipeline found for one hung frame: its mass centre, its inertia about y and in the
/// plane.
struct PartResult<T> {
    mass: T,
    x: T,
    z: T,
    i_yy: T,
    planar: [T; 3],
}

/// The keys of the parts BicycleParameters computes besides the benchmark's four bodies (a
/// fork S and handlebar G measured apart, a flywheel D in the front wheel): kept with the
/// bicycle as extras, their meanings from the one table of other models' keys
/// ([`crate::parameters::io::extra_meaning`]).
const PART_KEYS: [&str; 17] = [
    "mS", "xS", "zS", "ISxx", "ISyy", "ISzz", "ISxz", "mG", "xG", "zG", "IGxx", "IGyy", "IGzz",
    "IGxz", "mD", "IDxx", "IDyy",
];

/// The pipeline itself: the benchmark parameters and every number derived on the way, in the
/// order computed ([`report::Record`]), so the report and the parameters are one computation.
fn pipeline<T: Real>(
    m: &Measurements<T>,
) -> Result<(BenchmarkParameters<T>, Vec<report::Record<T>>)> {
    use report::Record;
    let mut out: Vec<Record<T>> = Vec::new();
    // 1. wheels
    let r_r = steps::wheel_radius(m.d_r, m.n_r);
    let r_f = steps::wheel_radius(m.d_f, m.n_f);
    out.push(Record::new(
        "rR",
        "rear wheel radius, from the distance rolled",
        "wheel_radius",
        "m",
        r_r,
    ));
    out.push(Record::new(
        "rF",
        "front wheel radius, from the distance rolled",
        "wheel_radius",
        "m",
        r_f,
    ));
    // 2. geometry
    let (lambda, w, fork_offset) = match &m.geometry {
        Geometry::Direct { w, gamma, f } => {
            let lambda = steps::steer_axis_tilt(*gamma);
            out.push(Record::new(
                "lam",
                "steer axis tilt, from the head tube angle",
                "steer_axis_tilt",
                "rad",
                lambda,
            ));
            out.push(Record::new("w", "wheelbase, as measured", "", "m", *w));
            (lambda, *w, *f)
        }
        Geometry::Offsets(o) => {
            let (a, b, span) = steps::steer_axis_offsets(o.h, o.d1, o.d2, o.d3, o.d4, o.d);
            out.push(Record::new(
                "a",
                "rear frame's offset: the rear hub's perpendicular distance to the steer axis \
                 (h1, h2, h3, d1, d2)",
                "steer_axis_offsets",
                "m",
                a,
            ));
            out.push(Record::new(
                "b",
                "fork offset: the front hub's perpendicular distance to the steer axis \
                 (h4, h5, d3, d4)",
                "steer_axis_offsets",
                "m",
                b,
            ));
            out.push(Record::new(
                "cAxis",
                "distance along the steer axis between the two offsets' feet (d, d2, d3, a, b)",
                "steer_axis_offsets",
                "m",
                span,
            ));
            let lambda = steps::steer_axis_tilt_from_offsets(r_f, r_r, a, b, span, "h1")?;
            out.push(Record::new(
                "lam",
                "steer axis tilt: both wheels on the ground, from the offsets and the radii",
                "steer_axis_tilt_from_offsets",
                "rad",
                lambda,
            ));
            let w = steps::wheelbase_from_offsets(a, b, span, lambda);
            out.push(Record::new(
                "w",
                "wheelbase, from the offsets and the steer axis tilt",
                "wheelbase_from_offsets",
                "m",
                w,
            ));
            (lambda, w, b)
        }
    };
    let c = steps::trail(r_f, lambda, fork_offset);
    out.push(Record::new(
        "c",
        "trail, from the fork offset, rF and lam",
        "trail",
        "m",
        c,
    ));
    // The hung frames and the points they are referred to.
    let mut parts = vec![PartSpec {
        letter: "B",
        name: "rear frame",
        mass: m.m_b,
        compound_period: m.t_c_b,
        hangings: &m.rear_frame,
        reference: (T::zero(), -r_r),
        reference_name: "the rear axle",
    }];
    match &m.front_frame {
        FrontFrame::Whole(h) => parts.push(PartSpec {
            letter: "H",
            name: "front frame",
            mass: h.mass,
            compound_period: h.compound_period,
            hangings: &h.hangings,
            reference: (w, -r_f),
            reference_name: "the front axle",
        }),
        FrontFrame::Split {
            fork,
            handlebar,
            reference: r,
        } => {
            let (l1, l2) = steps::handlebar_reference(r.h6, r.h7, r.d5, r.d6, r.l);
            let (u1, u2) = steps::handlebar_reference_offset(lambda, l1, l2);
            for (key, description, function, value) in [
                (
                    "l1",
                    "handlebar's reference point from the front hub, across the steer axis \
                     (h6, h7, d5, d6)",
                    "handlebar_reference",
                    l1,
                ),
                (
                    "l2",
                    "handlebar's reference point from the front hub, along the steer axis \
                     (l, d5, d6, l1)",
                    "handlebar_reference",
                    l2,
                ),
                (
                    "u1",
                    "handlebar's reference point behind the front hub, benchmark x",
                    "handlebar_reference_offset",
                    u1,
                ),
                (
                    "u2",
                    "handlebar's reference point above the front hub, benchmark −z",
                    "handlebar_reference_offset",
                    u2,
                ),
            ] {
                out.push(Record::new(key, description, function, "m", value));
            }
            parts.push(PartSpec {
                letter: "S",
                name: "fork",
                mass: fork.mass,
                compound_period: fork.compound_period,
                hangings: &fork.hangings,
                reference: (w, -r_f),
                reference_name: "the front axle",
            });
            parts.push(PartSpec {
                letter: "G",
                name: "handlebar",
                mass: handlebar.mass,
                compound_period: handlebar.compound_period,
                hangings: &handlebar.hangings,
                reference: (w - u1, -r_f - u2),
                reference_name: "the handlebar's reference point",
            });
        }
    }
    // 3. mass centres
    let mut lines_of = Vec::with_capacity(parts.len());
    let mut centres = Vec::with_capacity(parts.len());
    for p in &parts {
        let (part, name) = (p.letter, p.name);
        let set: Vec<steps::HangingLine<T>> = p
            .hangings
            .iter()
            .map(|h| {
                steps::hanging_line_through(h.alpha, h.a, lambda, p.reference.0, p.reference.1)
            })
            .collect();
        let (x, z) = steps::mass_centre(&set, &format!("alpha{part}"))?;
        for (i, line) in set.iter().enumerate() {
            let n = i + 1;
            out.push(Record::owned(
                format!("beta{part}{n}"),
                format!("{name}, hanging {n}: angle from the x axis to the pendulum's axis"),
                "hanging_line",
                "rad",
                line.beta,
            ));
            out.push(Record::owned(
                format!("slope{part}{n}"),
                format!("{name}, hanging {n}: slope dz/dx of the line through the mass centre"),
                "hanging_line",
                "",
                line.slope,
            ));
            out.push(Record::owned(
                format!("intercept{part}{n}"),
                format!("{name}, hanging {n}: that line's z at x = 0"),
                "hanging_line",
                "m",
                line.intercept,
            ));
        }
        for (i, a) in set.iter().enumerate() {
            for (j, b) in set.iter().enumerate().skip(i + 1) {
                if let Some((xi, zi)) = steps::intersection(a, b) {
                    let (p, q) = (i + 1, j + 1);
                    for (axis, value) in [("x", xi), ("z", zi)] {
                        out.push(Record::owned(
                            format!("{axis}{part}{p}{q}"),
                            format!("{name}: {axis} where the lines of hangings {p} and {q} meet"),
                            "intersection",
                            "m",
                            value,
                        ));
                    }
                }
            }
        }
        for (axis, value) in [("x", x), ("z", z)] {
            out.push(Record::owned(
                format!("{axis}{part}"),
                format!("{name}'s mass centre: the mean of the intersections"),
                "mass_centre",
                "m",
                value,
            ));
        }
        let mut residual = Record::owned(
            format!("residual{part}"),
            format!("{name}: root mean square distance of the mass centre from the hanging lines"),
            "line_residual",
            "m",
            steps::line_residual(&set, x, z),
        );
        residual.propagated = false;
        out.push(residual);
        lines_of.push(set);
        centres.push((x, z));
    }
    // 4. compound pendulums
    let i_ryy = steps::compound_pendulum_inertia(m.m_r, m.g, m.l_r, m.t_c_r);
    let i_fyy = steps::compound_pendulum_inertia(m.m_f, m.g, m.l_f, m.t_c_f);
    out.push(Record::new(
        "IRyy",
        "rear wheel's spin inertia, compound pendulum (TcR1, lR, mR, g)",
        "compound_pendulum_inertia",
        "kg m^2",
        i_ryy,
    ));
    out.push(Record::new(
        "IFyy",
        "front wheel's spin inertia, compound pendulum (TcF1, lF, mF, g)",
        "compound_pendulum_inertia",
        "kg m^2",
        i_fyy,
    ));
    if let Some(d) = &m.flywheel {
        let both = steps::compound_pendulum_inertia(d.mass, m.g, m.l_f, d.compound_period);
        out.push(Record::new(
            "IFDyy",
            "front wheel with its flywheel, spin inertia, compound pendulum (TcD1, lF, mD, g)",
            "compound_pendulum_inertia",
            "kg m^2",
            both,
        ));
        let own = steps::flywheel_part(both, i_fyy);
        out.push(Record::new(
            "IDyy",
            "flywheel's spin inertia: the wheel with it less the wheel (IFDyy − IFyy)",
            "flywheel_part",
            "kg m^2",
            own,
        ));
    }
    let mut i_yy = Vec::with_capacity(parts.len());
    for (p, &(x, z)) in parts.iter().zip(&centres) {
        let (part, name) = (p.letter, p.name);
        let length = steps::pendulum_length(x, z, p.reference.0, p.reference.1);
        out.push(Record::owned(
            format!("l{part}"),
            format!(
                "{name}'s pendulum length: mass centre to {}",
                p.reference_name
            ),
            "pendulum_length",
            "m",
            length,
        ));
        let inertia = steps::compound_pendulum_inertia(p.mass, m.g, length, p.compound_period);
        out.push(Record::owned(
            format!("I{part}yy"),
            format!("{name}'s inertia about y, compound pendulum (Tc{part}1, l{part}, m{part}, g)"),
            "compound_pendulum_inertia",
            "kg m^2",
            inertia,
        ));
        i_yy.push(inertia);
    }
    // 5. torsion constant
    let rod = steps::rod_transverse_inertia(m.m_p, m.l_p, m.d_p);
    let k = steps::torsion_constant(rod, m.t_t_p);
    out.push(Record::new(
        "IP",
        "calibration rod's inertia about a transverse axis (mP, lP, dP)",
        "rod_transverse_inertia",
        "kg m^2",
        rod,
    ));
    out.push(Record::new(
        "k",
        "torsion constant of the pendulum's wire, from the rod's period TtP1",
        "torsion_constant",
        "N m/rad",
        k,
    ));
    // 6. torsional pendulums
    let i_rxx = steps::torsional_pendulum_inertia(k, m.t_t_r);
    let i_fxx = steps::torsional_pendulum_inertia(k, m.t_t_f);
    out.push(Record::new(
        "IRxx",
        "rear wheel's inertia about a diameter, torsional pendulum (TtR1, k)",
        "torsional_pendulum_inertia",
        "kg m^2",
        i_rxx,
    ));
    out.push(Record::new(
        "IFxx",
        "front wheel's inertia about a diameter, torsional pendulum (TtF1, k)",
        "torsional_pendulum_inertia",
        "kg m^2",
        i_fxx,
    ));
    if let Some(d) = &m.flywheel {
        let both = steps::torsional_pendulum_inertia(k, d.torsional_period);
        out.push(Record::new(
            "IFDxx",
            "front wheel with its flywheel, inertia about a diameter, torsional pendulum \
             (TtD1, k)",
            "torsional_pendulum_inertia",
            "kg m^2",
            both,
        ));
        let own = steps::flywheel_part(both, i_fxx);
        out.push(Record::new(
            "IDxx",
            "flywheel's inertia about a diameter: the wheel with it less the wheel \
             (IFDxx − IFxx)",
            "flywheel_part",
            "kg m^2",
            own,
        ));
    }
    let mut results = Vec::with_capacity(parts.len());
    for ((p, lines), (&(x, z), &i_yy)) in parts.iter().zip(&lines_of).zip(centres.iter().zip(&i_yy))
    {
        let (part, name) = (p.letter, p.name);
        let moments: Vec<T> = p
            .hangings
            .iter()
            .map(|h| steps::torsional_pendulum_inertia(k, h.period))
            .collect();
        for (i, j) in moments.iter().enumerate() {
            let n = i + 1;
            out.push(Record::owned(
                format!("J{part}{n}"),
                format!(
                    "{name}, hanging {n}: inertia about the wire, torsional pendulum \
                     (Tt{part}{n}, k)"
                ),
                "torsional_pendulum_inertia",
                "kg m^2",
                *j,
            ));
        }
        let betas: Vec<T> = lines.iter().map(|l| l.beta).collect();
        let tensor = steps::planar_inertia(&moments, &betas, &format!("Tt{part}"))?;
        for (key, value) in ["xx", "xz", "zz"].iter().zip(tensor) {
            out.push(Record::owned(
                format!("I{part}{key}"),
                format!("{name}'s inertia in the plane, least squares over the hangings' moments"),
                "planar_inertia",
                "kg m^2",
                value,
            ));
        }
        let (first, second, theta) = steps::principal_planar(tensor[0], tensor[1], tensor[2]);
        out.push(Record::owned(
            format!("I{part}1"),
            format!("{name}'s larger principal moment in the plane"),
            "principal_planar",
            "kg m^2",
            first,
        ));
        out.push(Record::owned(
            format!("I{part}2"),
            format!("{name}'s smaller principal moment in the plane"),
            "principal_planar",
            "kg m^2",
            second,
        ));
        out.push(Record::owned(
            format!("theta{part}"),
            format!("{name}: angle from the x axis to the larger moment's axis"),
            "principal_planar",
            "rad",
            theta,
        ));
        results.push(PartResult {
            mass: p.mass,
            x,
            z,
            i_yy,
            planar: tensor,
        });
    }
    // The front frame: as measured, or the fork and handlebar combined (parallel axes).
    let (rear, front) = match results.as_slice() {
        [rear, front] => (rear, body(front)),
        [rear, fork, handlebar] => {
            let h = PlaneBody::combine(&[body(handlebar), body(fork)]);
            for (key, description, value) in [
                (
                    "mH",
                    "front frame's mass: the fork's and the handlebar's",
                    h.m,
                ),
                (
                    "xH",
                    "front frame's mass centre, fork and handlebar combined",
                    h.x,
                ),
                (
                    "zH",
                    "front frame's mass centre, fork and handlebar combined",
                    h.z,
                ),
                (
                    "IHxx",
                    "front frame's inertia, fork and handlebar by parallel axes",
                    h.i_xx,
                ),
                (
                    "IHyy",
                    "front frame's inertia, fork and handlebar by parallel axes",
                    h.i_yy,
                ),
                (
                    "IHzz",
                    "front frame's inertia, fork and handlebar by parallel axes",
                    h.i_zz,
                ),
                (
                    "IHxz",
                    "front frame's inertia, fork and handlebar by parallel axes",
                    h.i_xz,
                ),
            ] {
                let unit = if key.starts_with('I') {
                    "kg m^2"
                } else if key.starts_with('m') {
                    "kg"
                } else {
                    "m"
                };
                out.push(Record::new(key, description, "combine", unit, value));
            }
            (rear, h)
        }
        _ => {
            return Err(Error::InvalidParameter {
                field: "alphaH".into(),
                value: f64::NAN,
                rule: "the front frame must be hung as one (H) or as fork and handlebar (S, G)"
                    .into(),
            });
        }
    };
    // 7. masses and gravity
    let mut masses = vec![
        ("mR", "rear wheel's mass, as measured", "kg", m.m_r),
        ("mF", "front wheel's mass, as measured", "kg", m.m_f),
        ("mB", "rear frame's mass, as measured", "kg", m.m_b),
    ];
    match &m.front_frame {
        FrontFrame::Whole(h) => {
            masses.push(("mH", "front frame's mass, as measured", "kg", h.mass));
        }
        FrontFrame::Split {
            fork, handlebar, ..
        } => {
            masses.push(("mS", "fork's mass, as measured", "kg", fork.mass));
            masses.push(("mG", "handlebar's mass, as measured", "kg", handlebar.mass));
        }
    }
    masses.push(("g", "gravity, as measured", "m/s^2", m.g));
    for (key, description, unit, value) in masses {
        out.push(Record::new(key, description, "", unit, value));
    }
    if let Some(d) = &m.flywheel {
        out.push(Record::new(
            "mD",
            "flywheel's mass: the front wheel with it (mD as measured) less the wheel (mF)",
            "flywheel_part",
            "kg",
            steps::flywheel_part(d.mass, m.m_f),
        ));
    }
    let [i_bxx, i_bxz, i_bzz] = rear.planar;
    let benchmark = BenchmarkParameters {
        w,
        c,
        lambda,
        g: m.g,
        r_r,
        m_r: m.m_r,
        i_rxx,
        i_ryy,
        x_b: rear.x,
        z_b: rear.z,
        m_b: m.m_b,
        i_bxx,
        i_byy: rear.i_yy,
        i_bzz,
        i_bxz,
        x_h: front.x,
        z_h: front.z,
        m_h: front.m,
        i_hxx: front.i_xx,
        i_hyy: front.i_yy,
        i_hzz: front.i_zz,
        i_hxz: front.i_xz,
        r_f,
        m_f: m.m_f,
        i_fxx,
        i_fyy,
    };
    Ok((benchmark, out))
}

/// A hung frame's result as a body in the plane, for [`PlaneBody::combine`].
fn body<T: Real>(p: &PartResult<T>) -> PlaneBody<T> {
    let [i_xx, i_xz, i_zz] = p.planar;
    PlaneBody {
        m: p.mass,
        x: p.x,
        z: p.z,
        i_xx,
        i_yy: p.i_yy,
        i_zz,
        i_xz,
    }
}

/// Benchmark parameters computed from measurements, with the exact first-order uncertainty of
/// each and their covariance (measurements independent).
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredParameters {
    /// The parameters.
    pub benchmark: BenchmarkParameters,
    /// σ of each parameter by file key (`IBxx`), those with σ > 0: the shape of
    /// [`Bicycle::sigma`].
    pub sigma: BTreeMap<String, f64>,
    /// The measurements' keys, in the order of the Jacobian's columns
    /// ([`Measurements::entries`]).
    pub inputs: Vec<String>,
    /// ∂pᵢ/∂mⱼ: one row per benchmark parameter in table order
    /// ([`crate::advanced::table::parameters`]), one column per measurement.
    pub jacobian: DMatrix<f64>,
    /// The covariance of the benchmark parameters, table order: J diag(σ²) Jᵀ.
    pub covariance: DMatrix<f64>,
    /// Every number the pipeline derived, in the order computed, with its σ and the
    /// measurements it depends on: the report of `whipple measure`.
    pub steps: Vec<report::Step>,
    /// The rider seated on the bicycle ([`MeasuredParameters::with_rider`]): its place, joint
    /// angles and body, the rider alone in the benchmark's axes (`None` for the bicycle alone).
    pub rider: Option<SeatedRider<f64>>,
}

/// What one pass computes: the parameters, every record, the seated rider if any.
type PassOutput<T> = (
    BenchmarkParameters<T>,
    Vec<report::Record<T>>,
    Option<SeatedRider<T>>,
);

/// The measurements of `template`'s shape from the flat inputs `x` (its entries first).
fn rebuild<T: Copy>(template: &Measurements<f64>, x: &[T]) -> Measurements<T> {
    let mut k = 0;
    template.map(|_| {
        let v = x[k];
        k += 1;
        v
    })
}

/// The rear frame's keys, reported apart (`mB_frame`) when a rider joins the frame.
const REAR_FRAME_KEYS: [&str; 7] = ["mB", "xB", "zB", "IBxx", "IByy", "IBzz", "IBxz"];

/// The rider's steps after the bicycle's: seated by the f64 `solve`, lifted to `T`, added to
/// the rear frame; the records of the frame alone renamed, the rider's appended.
fn seated<T: Real>(
    solve: &SeatedSolve,
    rider: &YeadonMeasurements<f64>,
    configuration: &YeadonConfiguration<f64>,
    geometry: &RiderGeometry<T>,
    bicycle: BenchmarkParameters<T>,
    mut records: Vec<report::Record<T>>,
) -> Result<PassOutput<T>> {
    use report::Record;
    let s = seated_rider(
        solve,
        rider,
        configuration,
        geometry,
        bicycle.w,
        bicycle.r_r,
        bicycle.r_f,
    )?;
    for r in &mut records {
        if REAR_FRAME_KEYS.contains(&r.key.as_str()) {
            r.key = format!("{}_frame", r.key);
            r.description = format!("{} (without the rider)", r.description);
        }
    }
    let mut push = |key: &str, description: &str, function: &'static str, unit, value| {
        records.push(Record::new(key, description, function, unit, value));
    };
    push(
        "xbb",
        "bottom bracket, x (lcs, hbb, rR)",
        "bottom_bracket",
        "m",
        s.bottom_bracket[0],
    );
    push(
        "zbb",
        "bottom bracket, z (hbb)",
        "bottom_bracket",
        "m",
        s.bottom_bracket[1],
    );
    push(
        "xseat",
        "the rider's seat, x (lst + lsp up the seat tube at lamst)",
        "seat",
        "m",
        s.seat[0],
    );
    push("zseat", "the rider's seat, z", "seat", "m", s.seat[1]);
    push(
        "xgrip",
        "the grips' centre, x (LhbF, LhbR, whb, w, rR, rF)",
        "handlebar_grips",
        "m",
        s.grips[0],
    );
    push(
        "zgrip",
        "the grips' centre, z",
        "handlebar_grips",
        "m",
        s.grips[1],
    );
    for name in SEATED_ANGLES {
        if let Some(angle) = s.configuration.get(name) {
            push(
                name,
                "joint angle solved so that the feet reach the bottom bracket and the hands the grips",
                "seated_configuration",
                "rad",
                angle,
            );
        }
    }
    let (m, c, i) = (s.rider.mass, s.rider.center_of_mass, s.rider.inertia);
    push(
        "mRider",
        "the rider's mass (Yeadon body)",
        "rider_in_benchmark_frame",
        "kg",
        m,
    );
    for (key, value) in [("xRider", c.x), ("yRider", c.y), ("zRider", c.z)] {
        push(
            key,
            "the rider's mass centre, benchmark axes",
            "rider_in_benchmark_frame",
            "m",
            value,
        );
    }
    for (key, value) in [
        ("IRiderxx", i[(0, 0)]),
        ("IRideryy", i[(1, 1)]),
        ("IRiderzz", i[(2, 2)]),
        ("IRiderxz", i[(0, 2)]),
        ("IRiderxy", i[(0, 1)]),
        ("IRideryz", i[(1, 2)]),
    ] {
        push(
            key,
            "the rider's inertia about its mass centre, benchmark axes",
            "rider_in_benchmark_frame",
            "kg m^2",
            value,
        );
    }
    let combined = combine_with_rear_frame(&bicycle, &s.rider);
    for (key, value) in [
        ("mB", combined.m_b),
        ("xB", combined.x_b),
        ("zB", combined.z_b),
        ("IBxx", combined.i_bxx),
        ("IByy", combined.i_byy),
        ("IBzz", combined.i_bzz),
        ("IBxz", combined.i_bxz),
    ] {
        push(
            key,
            "the rear frame with the rider",
            "combine_with_rear_frame",
            if key.starts_with('I') {
                "kg m^2"
            } else if key == "mB" {
                "kg"
            } else {
                "m"
            },
            value,
        );
    }
    Ok((combined, records, Some(s)))
}

impl MeasuredParameters {
    /// The parameters from measurements: one pass on `f64` and one dual-number pass per
    /// measurement (its exact derivative), then σ and the covariance.
    ///
    /// ```
    /// use whipple::advanced::measured::{read_measurements, MeasuredParameters};
    /// # let text = include_str!("../../../tests/data/measured/BrowserMeasured.txt");
    /// let file = read_measurements(text)?;
    /// let result = MeasuredParameters::new(&file.measurements)?;
    /// assert!((result.benchmark.w - 1.121).abs() < 1e-12);
    /// assert!((result.sigma["w"] - 0.002).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn new(measurements: &Measurements<Measured>) -> Result<Self> {
        measurements.check()?;
        let entries = measurements.entries();
        let template = measurements.values();
        Self::propagate(
            entries,
            |x: &[f64]| pipeline(&rebuild(&template, x)).map(|(b, r)| (b, r, None)),
            |x: &[Dual64]| pipeline(&rebuild(&template, x)).map(|(b, r)| (b, r, None)),
        )
    }

    /// The bicycle of a `*Measured.txt` with a rider seated on it and added to its rear frame
    /// (BicycleParameters' `add_rider`; [`crate::advanced::rider`]'s steps): the rider from
    /// Yeadon's 95 `measurements` in the configuration `configuration`, whose hips', knees',
    /// shoulders' and elbows' angles are solved so that the feet reach the bottom bracket and
    /// the hands the grips. The seat and handlebar come from the file's `lcs`, `hbb`, `lsp`,
    /// `lst`, `lamst`, `whb`, `LhbF` and `LhbR` ([`crate::advanced::rider::RIDER_GEOMETRY_KEYS`]).
    ///
    /// σ: the bicycle's measurements' (including those eight keys' where the file gives one)
    /// through every step, the rider's place and joint angles included (they follow rR, rF and
    /// w); the rider's body is taken as exact, as BicycleParameters takes it. The steps report
    /// the rear frame alone under `mB_frame`, `xB_frame`, … and the rider alone under `mRider`,
    /// `xRider`, …; `mB`, `xB`, … are the rear frame with the rider.
    ///
    /// ```
    /// use whipple::advanced::measured::{read_measurements, MeasuredParameters};
    /// use whipple::advanced::rider::{read_yeadon_configuration, read_yeadon_measurements};
    /// # let text = include_str!("../../../tests/data/measured/BrowserMeasured.txt");
    /// # let meas = include_str!("../../../tests/data/yeadon/JasonYeadonMeas.txt");
    /// # let cfg = include_str!("../../../tests/data/yeadon/JasonBrowserYeadonCFG.txt");
    /// let result = MeasuredParameters::with_rider(
    ///     &read_measurements(text)?,
    ///     &read_yeadon_measurements(meas)?,
    ///     &read_yeadon_configuration(cfg)?,
    /// )?;
    /// let rider = result.rider.as_ref().map(|r| r.rider.mass).unwrap_or(0.0);
    /// assert!((result.benchmark.m_b - (9.86 + rider)).abs() < 1e-9);
    /// assert!(result.sigma["xB"] > 0.0);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn with_rider(
        file: &MeasuredFile,
        rider: &YeadonMeasurements<f64>,
        configuration: &YeadonConfiguration<f64>,
    ) -> Result<Self> {
        let measurements = &file.measurements;
        measurements.check()?;
        let mut geometry = Vec::with_capacity(RIDER_GEOMETRY_KEYS.len());
        for (key, what) in RIDER_GEOMETRY_KEYS {
            let Some((_, m)) = file.other.iter().find(|(k, _)| k == key) else {
                return Err(Error::Parse {
                    format: "BicycleParameters Measured .txt",
                    field: Some(key.to_string()),
                    line: 0,
                    column: 0,
                    message: format!(
                        "{key} is missing: seating a rider needs the {}",
                        what.split(" [").next().unwrap_or(what)
                    ),
                });
            };
            let at = if m.line > 0 {
                format!(" (line {})", m.line)
            } else {
                String::new()
            };
            if !(m.value.is_finite() && m.value > 0.0) {
                return Err(Error::InvalidParameter {
                    field: key.to_string(),
                    value: m.value,
                    rule: format!("the rider's seat and handlebar need it positive{at}"),
                });
            }
            if !(m.sigma.is_finite() && m.sigma >= 0.0) {
                return Err(Error::InvalidParameter {
                    field: key.to_string(),
                    value: m.value,
                    rule: format!(
                        "its standard deviation {} must be finite and not negative{at}",
                        m.sigma
                    ),
                });
            }
            geometry.push((key.to_string(), *m));
        }
        let template = measurements.values();
        let n = measurements.entries().len();
        let geometry_values = |x: &[f64]| -> [f64; 8] { std::array::from_fn(|i| x[n + i]) };
        let mut entries = measurements.entries();
        entries.extend(geometry.iter().cloned());
        let values: Vec<f64> = entries.iter().map(|(_, m)| m.value).collect();
        // The joint angles on f64 once; each dual pass lifts them (implicit function theorem).
        let (bicycle, _) = pipeline(&template)?;
        let g = RiderGeometry::from_array(geometry_values(&values));
        let solve = solve_seated(
            rider,
            configuration,
            &g,
            bicycle.w,
            bicycle.r_r,
            bicycle.r_f,
        )?;
        let f64_pass = |x: &[f64]| {
            let (b, r) = pipeline(&rebuild(&template, x))?;
            let g = RiderGeometry::from_array(std::array::from_fn(|i| x[n + i]));
            seated(&solve, rider, configuration, &g, b, r)
        };
        let dual_pass = |x: &[Dual64]| {
            let (b, r) = pipeline(&rebuild(&template, x))?;
            let g = RiderGeometry::from_array(std::array::from_fn(|i| x[n + i]));
            seated(&solve, rider, configuration, &g, b, r)
        };
        Self::propagate(entries, f64_pass, dual_pass)
    }

    /// One pass on f64 and one dual-number pass per input (its exact derivative), then σ, the
    /// covariance and the report.
    fn propagate(
        entries: Vec<(String, Measured)>,
        f64_pass: impl Fn(&[f64]) -> Result<PassOutput<f64>>,
        dual_pass: impl Fn(&[Dual64]) -> Result<PassOutput<Dual64>>,
    ) -> Result<Self> {
        let values: Vec<f64> = entries.iter().map(|(_, m)| m.value).collect();
        let (benchmark, records, rider) = f64_pass(&values)?;
        let n = entries.len();
        let rows = BENCHMARK_TABLE.len();
        let mut jacobian = DMatrix::zeros(rows, n);
        let mut step_jacobian = DMatrix::zeros(records.len(), n);
        for j in 0..n {
            let seeded: Vec<Dual64> = values
                .iter()
                .enumerate()
                .map(|(k, v)| Dual64::new(*v, if k == j { 1.0 } else { 0.0 }))
                .collect();
            let (derivative, derived, _) = dual_pass(&seeded)?;
            for (i, d) in derivative.to_array().iter().enumerate() {
                jacobian[(i, j)] = d.eps;
            }
            // The same records in the same order: the pipeline's steps do not branch on values
            // except where a pair of lines is parallel, which the f64 pass refused already.
            for (i, d) in derived.iter().enumerate().take(records.len()) {
                step_jacobian[(i, j)] = d.value.eps;
            }
        }
        let variances = DMatrix::from_diagonal(&nalgebra::DVector::from_iterator(
            n,
            entries.iter().map(|(_, m)| m.sigma * m.sigma),
        ));
        let covariance = &jacobian * variances * jacobian.transpose();
        let sigma = BENCHMARK_TABLE
            .iter()
            .enumerate()
            .map(|(i, info)| (info.key.to_string(), covariance[(i, i)].max(0.0).sqrt()))
            .filter(|(_, s)| *s > 0.0)
            .collect();
        for (info, v) in BENCHMARK_TABLE.iter().zip(benchmark.to_array()) {
            if !v.is_finite() {
                return Err(Error::InvalidParameter {
                    field: info.key.into(),
                    value: v,
                    rule: "the measurements give no finite value".into(),
                });
            }
        }
        let inputs: Vec<String> = entries.iter().map(|(k, _)| k.clone()).collect();
        let sigmas: Vec<f64> = entries.iter().map(|(_, m)| m.sigma).collect();
        let steps = report::steps(records, &step_jacobian, &inputs, &values, &sigmas);
        Ok(MeasuredParameters {
            benchmark,
            sigma,
            inputs,
            jacobian,
            covariance,
            steps,
            rider,
        })
    }

    /// The correlation coefficient of two parameters by file key (`xB`, `IBxx`), `None` for an
    /// unknown key or a parameter with σ = 0.
    pub fn correlation(&self, a: &str, b: &str) -> Option<f64> {
        let i = BENCHMARK_TABLE.iter().position(|p| p.key == a)?;
        let j = BENCHMARK_TABLE.iter().position(|p| p.key == b)?;
        let (si, sj) = (
            self.covariance[(i, i)].sqrt(),
            self.covariance[(j, j)].sqrt(),
        );
        (si > 0.0 && sj > 0.0).then(|| self.covariance[(i, j)] / (si * sj))
    }

    /// A [`Bicycle`] in the benchmark form carrying these values and σ.
    ///
    /// The parts BicycleParameters computes besides the benchmark's four bodies (a fork S and
    /// a handlebar G measured apart, a flywheel D in the front wheel) are kept as the
    /// bicycle's extras, with their σ: reported and written back, never used by the model.
    pub fn bicycle(&self) -> Bicycle {
        Bicycle {
            description: Description::Benchmark(self.benchmark),
            sigma: self.sigma.clone(),
            extras: self.part_extras(),
            ..Bicycle::default()
        }
    }

    /// The steps that are quantities of the fork S, the handlebar G or the flywheel D, as
    /// extras.
    fn part_extras(&self) -> Vec<Extra> {
        PART_KEYS
            .iter()
            .filter_map(|key| {
                let step = self.steps.iter().rev().find(|s| s.key == *key)?;
                let meaning = crate::parameters::io::extra_meaning(key).unwrap_or_default();
                Some(Extra {
                    key: key.to_string(),
                    text: format!("{}", step.value),
                    value: Some(step.value),
                    sigma: step.sigma.filter(|s| *s > 0.0),
                    meaning: meaning.to_string(),
                })
            })
            .collect()
    }
}
