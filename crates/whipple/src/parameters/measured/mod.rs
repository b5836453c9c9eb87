//! A bicycle from bench measurements: BicycleParameters' `*Measured.txt` read into typed
//! [`Measurements`], and the pipeline (Moore 2012 ch. 2; Moore, Hubbard, Kooijman & Schwab
//! 2010) that turns them into [`BenchmarkParameters`] with the standard deviation of every
//! output and their full covariance, by exact first-order propagation (one dual-number pass
//! per measurement through the same steps as the values, [`steps`]).
//!
//! The pipeline, in order:
//! 1. wheel radii from the distance rolled in whole turns ([`steps::wheel_radius`]);
//! 2. steer axis tilt from the head tube angle, wheelbase as measured, trail from the fork
//!    offset ([`steps::steer_axis_tilt`], [`steps::trail`]);
//! 3. each frame's mass centre from the lines of its hangings ([`steps::hanging_line`],
//!    [`steps::mass_centre`]);
//! 4. the wheels' and frames' moments about y from compound pendulum periods
//!    ([`steps::compound_pendulum_inertia`], [`steps::pendulum_length`]);
//! 5. the torsion constant from the calibration rod ([`steps::rod_transverse_inertia`],
//!    [`steps::torsion_constant`]);
//! 6. the wheels' moments about a diameter and the frames' in-plane tensors from torsional
//!    pendulum periods ([`steps::torsional_pendulum_inertia`], [`steps::planar_inertia`]);
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

use std::collections::BTreeMap;

use nalgebra::{DMatrix, RealField};
use num_dual::Dual64;

use super::benchmark::{BENCHMARK_TABLE, BenchmarkParameters};
use super::{Bicycle, Description};
use crate::error::{Error, Result};
use crate::rider::{
    RIDER_GEOMETRY_KEYS, RiderGeometry, SEATED_ANGLES, SeatedRider, SeatedSolve,
    YeadonConfiguration, YeadonMeasurements, combine_with_rear_frame, seated_rider, solve_seated,
};
use steps::HungFrame;

pub use read::{MAX_HANGINGS, MeasuredFile, read_measurements};

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

/// The measurements of a bicycle on the bench, under BicycleParameters' file keys (Moore 2012
/// ch. 2), for a bicycle whose fork and handlebar were measured as one frame and whose geometry
/// was measured as wheelbase, head angle and fork offset. Generic over the scalar so that the
/// pipeline runs on dual numbers; the file's form is `Measurements<Measured>`.
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
    /// `w`: wheelbase \[m\].
    pub w: T,
    /// `gamma`: the head tube's angle with the ground \[deg\].
    pub gamma: T,
    /// `f`: fork offset, the front hub's perpendicular distance to the steer axis \[m\].
    pub f: T,
    /// `mR`: rear wheel mass \[kg\].
    pub m_r: T,
    /// `mF`: front wheel mass \[kg\].
    pub m_f: T,
    /// `mB`: rear frame mass \[kg\].
    pub m_b: T,
    /// `mH`: front frame (fork and handlebar) mass \[kg\].
    pub m_h: T,
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
    /// `TcH1`: the front frame's compound pendulum period, swung about the front axle \[s\].
    pub t_c_h: T,
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
    /// The front frame's hangings (`alphaH1`, `aH1`, `TtH1`, …), in number order.
    pub front_frame: Vec<Hanging<T>>,
}

impl<T: Copy> Measurements<T> {
    /// Every value with its file key, in a fixed order (scalars in field order, then the rear
    /// frame's and the front frame's hangings).
    pub fn entries(&self) -> Vec<(String, T)> {
        let mut out: Vec<(String, T)> = [
            ("g", self.g),
            ("dR", self.d_r),
            ("nR", self.n_r),
            ("dF", self.d_f),
            ("nF", self.n_f),
            ("w", self.w),
            ("gamma", self.gamma),
            ("f", self.f),
            ("mR", self.m_r),
            ("mF", self.m_f),
            ("mB", self.m_b),
            ("mH", self.m_h),
            ("lR", self.l_r),
            ("lF", self.l_f),
            ("TcR1", self.t_c_r),
            ("TcF1", self.t_c_f),
            ("TcB1", self.t_c_b),
            ("TcH1", self.t_c_h),
            ("TtR1", self.t_t_r),
            ("TtF1", self.t_t_f),
            ("mP", self.m_p),
            ("lP", self.l_p),
            ("dP", self.d_p),
            ("TtP1", self.t_t_p),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        for (part, set) in [("B", &self.rear_frame), ("H", &self.front_frame)] {
            for (i, h) in set.iter().enumerate() {
                out.push((format!("alpha{part}{}", i + 1), h.alpha));
                out.push((format!("a{part}{}", i + 1), h.a));
                out.push((format!("Tt{part}{}", i + 1), h.period));
            }
        }
        out
    }

    /// The same measurements with every value mapped, in the order of [`Measurements::entries`].
    pub fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> Measurements<U> {
        let g = f(&self.g);
        let d_r = f(&self.d_r);
        let n_r = f(&self.n_r);
        let d_f = f(&self.d_f);
        let n_f = f(&self.n_f);
        let w = f(&self.w);
        let gamma = f(&self.gamma);
        let ff = f(&self.f);
        let m_r = f(&self.m_r);
        let m_f = f(&self.m_f);
        let m_b = f(&self.m_b);
        let m_h = f(&self.m_h);
        let l_r = f(&self.l_r);
        let l_f = f(&self.l_f);
        let t_c_r = f(&self.t_c_r);
        let t_c_f = f(&self.t_c_f);
        let t_c_b = f(&self.t_c_b);
        let t_c_h = f(&self.t_c_h);
        let t_t_r = f(&self.t_t_r);
        let t_t_f = f(&self.t_t_f);
        let m_p = f(&self.m_p);
        let l_p = f(&self.l_p);
        let d_p = f(&self.d_p);
        let t_t_p = f(&self.t_t_p);
        let mut hangings = |set: &[Hanging<T>]| -> Vec<Hanging<U>> {
            set.iter()
                .map(|h| {
                    let alpha = f(&h.alpha);
                    let a = f(&h.a);
                    let period = f(&h.period);
                    Hanging { alpha, a, period }
                })
                .collect()
        };
        let rear_frame = hangings(&self.rear_frame);
        let front_frame = hangings(&self.front_frame);
        Measurements {
            g,
            d_r,
            n_r,
            d_f,
            n_f,
            w,
            gamma,
            f: ff,
            m_r,
            m_f,
            m_b,
            m_h,
            l_r,
            l_f,
            t_c_r,
            t_c_f,
            t_c_b,
            t_c_h,
            t_t_r,
            t_t_f,
            m_p,
            l_p,
            d_p,
            t_t_p,
            rear_frame,
            front_frame,
        }
    }
}

impl Measurements<Measured> {
    /// The values alone.
    pub fn values(&self) -> Measurements<f64> {
        self.map(|m| m.value)
    }

    /// Checks what the pipeline divides by or takes roots of: every value finite, every σ
    /// finite and non-negative, periods, masses, lengths, turns and g positive. The error
    /// names the key and its line.
    pub fn check(&self) -> Result<()> {
        for (key, m) in self.entries() {
            let at = if m.line > 0 {
                format!(" (line {})", m.line)
            } else {
                String::new()
            };
            let bad = |rule: String| Error::InvalidParameter {
                field: key.clone(),
                value: m.value,
                rule,
            };
            if !m.value.is_finite() {
                return Err(bad(format!("must be finite{at}")));
            }
            if !(m.sigma.is_finite() && m.sigma >= 0.0) {
                return Err(bad(format!(
                    "its standard deviation {} must be finite and not negative{at}",
                    m.sigma
                )));
            }
            let positive = key.starts_with('T')
                || key.starts_with('m')
                || key.starts_with('n')
                || matches!(
                    key.as_str(),
                    "g" | "dR" | "dF" | "w" | "lR" | "lF" | "lP" | "dP"
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
                return Err(bad(format!("{what} must be positive{at}")));
            }
        }
        Ok(())
    }
}

/// The benchmark parameters computed from [`Measurements`] (the pipeline of the module's
/// documentation), on any scalar. Fails, naming the measurement, where the hangings do not
/// determine a mass centre or an inertia.
pub fn benchmark_from_measurements<T: RealField + Copy>(
    m: &Measurements<T>,
) -> Result<BenchmarkParameters<T>> {
    pipeline(m).map(|(benchmark, _)| benchmark)
}

/// The pipeline itself: the benchmark parameters and every number derived on the way, in the
/// order computed ([`report::Record`]), so the report and the parameters are one computation.
fn pipeline<T: RealField + Copy>(
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
    let lambda = steps::steer_axis_tilt(m.gamma);
    let w = m.w;
    let c = steps::trail(r_f, lambda, m.f);
    out.push(Record::new(
        "lam",
        "steer axis tilt, from the head tube angle",
        "steer_axis_tilt",
        "rad",
        lambda,
    ));
    out.push(Record::new("w", "wheelbase, as measured", "", "m", w));
    out.push(Record::new(
        "c",
        "trail, from the fork offset, rF and lam",
        "trail",
        "m",
        c,
    ));
    // 3. mass centres
    let lines = |frame, set: &[Hanging<T>]| -> Vec<steps::HangingLine<T>> {
        set.iter()
            .map(|h| steps::hanging_line(frame, h.alpha, h.a, lambda, w, r_r, r_f))
            .collect()
    };
    let rear_lines = lines(HungFrame::Rear, &m.rear_frame);
    let front_lines = lines(HungFrame::Front, &m.front_frame);
    let (x_b, z_b) = steps::mass_centre(&rear_lines, "alphaB")?;
    let (x_h, z_h) = steps::mass_centre(&front_lines, "alphaH")?;
    for (part, name, set, (x, z)) in [
        ("B", "rear", &rear_lines, (x_b, z_b)),
        ("H", "front", &front_lines, (x_h, z_h)),
    ] {
        for (i, line) in set.iter().enumerate() {
            let n = i + 1;
            out.push(Record::owned(
                format!("beta{part}{n}"),
                format!("{name} frame, hanging {n}: angle from the x axis to the pendulum's axis"),
                "hanging_line",
                "rad",
                line.beta,
            ));
            out.push(Record::owned(
                format!("slope{part}{n}"),
                format!(
                    "{name} frame, hanging {n}: slope dz/dx of the line through the mass centre"
                ),
                "hanging_line",
                "",
                line.slope,
            ));
            out.push(Record::owned(
                format!("intercept{part}{n}"),
                format!("{name} frame, hanging {n}: that line's z at x = 0"),
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
                            format!(
                                "{name} frame: {axis} where the lines of hangings {p} and {q} meet"
                            ),
                            "intersection",
                            "m",
                            value,
                        ));
                    }
                }
            }
        }
        out.push(Record::owned(
            format!("x{part}"),
            format!("{name} frame's mass centre: the mean of the intersections"),
            "mass_centre",
            "m",
            x,
        ));
        out.push(Record::owned(
            format!("z{part}"),
            format!("{name} frame's mass centre: the mean of the intersections"),
            "mass_centre",
            "m",
            z,
        ));
        let mut residual = Record::owned(
            format!("residual{part}"),
            format!(
                "{name} frame: root mean square distance of the mass centre from the hanging lines"
            ),
            "line_residual",
            "m",
            steps::line_residual(set, x, z),
        );
        residual.propagated = false;
        out.push(residual);
    }
    // 4. compound pendulums
    let i_ryy = steps::compound_pendulum_inertia(m.m_r, m.g, m.l_r, m.t_c_r);
    let i_fyy = steps::compound_pendulum_inertia(m.m_f, m.g, m.l_f, m.t_c_f);
    let l_b = steps::pendulum_length(x_b, z_b, T::zero(), -r_r);
    let i_byy = steps::compound_pendulum_inertia(m.m_b, m.g, l_b, m.t_c_b);
    let l_h = steps::pendulum_length(x_h, z_h, w, -r_f);
    let i_hyy = steps::compound_pendulum_inertia(m.m_h, m.g, l_h, m.t_c_h);
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
    out.push(Record::new(
        "lB",
        "rear frame's pendulum length: mass centre to the rear axle",
        "pendulum_length",
        "m",
        l_b,
    ));
    out.push(Record::new(
        "IByy",
        "rear frame's inertia about y, compound pendulum (TcB1, lB, mB, g)",
        "compound_pendulum_inertia",
        "kg m^2",
        i_byy,
    ));
    out.push(Record::new(
        "lH",
        "front frame's pendulum length: mass centre to the front axle",
        "pendulum_length",
        "m",
        l_h,
    ));
    out.push(Record::new(
        "IHyy",
        "front frame's inertia about y, compound pendulum (TcH1, lH, mH, g)",
        "compound_pendulum_inertia",
        "kg m^2",
        i_hyy,
    ));
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
    let mut planar = |part: &str,
                      name: &str,
                      set: &[Hanging<T>],
                      lines: &[steps::HangingLine<T>]|
     -> Result<[T; 3]> {
        let moments: Vec<T> = set
            .iter()
            .map(|h| steps::torsional_pendulum_inertia(k, h.period))
            .collect();
        for (i, j) in moments.iter().enumerate() {
            let n = i + 1;
            out.push(Record::owned(
                format!("J{part}{n}"),
                format!("{name} frame, hanging {n}: inertia about the wire, torsional pendulum (Tt{part}{n}, k)"),
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
                format!(
                    "{name} frame's inertia in the plane, least squares over the hangings' moments"
                ),
                "planar_inertia",
                "kg m^2",
                value,
            ));
        }
        let (first, second, theta) = steps::principal_planar(tensor[0], tensor[1], tensor[2]);
        out.push(Record::owned(
            format!("I{part}1"),
            format!("{name} frame's larger principal moment in the plane"),
            "principal_planar",
            "kg m^2",
            first,
        ));
        out.push(Record::owned(
            format!("I{part}2"),
            format!("{name} frame's smaller principal moment in the plane"),
            "principal_planar",
            "kg m^2",
            second,
        ));
        out.push(Record::owned(
            format!("theta{part}"),
            format!("{name} frame: angle from the x axis to the larger moment's axis"),
            "principal_planar",
            "rad",
            theta,
        ));
        Ok(tensor)
    };
    let [i_bxx, i_bxz, i_bzz] = planar("B", "rear", &m.rear_frame, &rear_lines)?;
    let [i_hxx, i_hxz, i_hzz] = planar("H", "front", &m.front_frame, &front_lines)?;
    // 7. masses and gravity
    for (key, description, unit, value) in [
        ("mR", "rear wheel's mass, as measured", "kg", m.m_r),
        ("mF", "front wheel's mass, as measured", "kg", m.m_f),
        ("mB", "rear frame's mass, as measured", "kg", m.m_b),
        ("mH", "front frame's mass, as measured", "kg", m.m_h),
        ("g", "gravity, as measured", "m/s^2", m.g),
    ] {
        out.push(Record::new(key, description, "", unit, value));
    }
    let benchmark = BenchmarkParameters {
        w,
        c,
        lambda,
        g: m.g,
        r_r,
        m_r: m.m_r,
        i_rxx,
        i_ryy,
        x_b,
        z_b,
        m_b: m.m_b,
        i_bxx,
        i_byy,
        i_bzz,
        i_bxz,
        x_h,
        z_h,
        m_h: m.m_h,
        i_hxx,
        i_hyy,
        i_hzz,
        i_hxz,
        r_f,
        m_f: m.m_f,
        i_fxx,
        i_fyy,
    };
    Ok((benchmark, out))
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
fn seated<T: RealField + Copy>(
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
    pub fn bicycle(&self) -> Bicycle {
        Bicycle {
            description: Description::Benchmark(self.benchmark),
            sigma: self.sigma.clone(),
            ..Bicycle::default()
        }
    }
}
