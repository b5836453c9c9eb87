//! Design studies: one or two parameters of a base bicycle varied over grids, and for every
//! design the quantities a designer reads (critical speeds, whether and how widely it is
//! self-stable, the weave frequency, the largest real part at a given speed).
//!
//! A study is plain data ([`Study`]); its designs are numbered row-major (`index = iy · nx +
//! ix`) and computed in order, in parallel chunks, and handed to the caller as [`DesignRow`]s
//! chunk by chunk ([`Study::run`]), so memory stays bounded however large the grid. A
//! [`Shard`] selects a contiguous block of indices: `n` machines running shards `0/n … n−1/n`
//! produce exactly the rows, bit for bit, of one machine running the whole study.
//!
//! Every design is computed by the certified critical speeds of [`super::stability`]: a design
//! whose parameters break a rule is marked [`DesignStatus::Invalid`] with the rule, one whose
//! answer round-off cannot give is marked [`DesignStatus::AccuracyLost`]; neither stops the
//! study.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::Serialize;

use super::eigen::certified_roots;
use super::modes::Mode;
use super::stability::{self, summary};
use crate::error::{Error, Result};
use crate::linear::{Canonical, CharacteristicPolynomial, SpeedPolynomials};
use crate::parameters::table::{ANGLE_UNIT, Form, ParameterInfo, parameters};
use crate::parameters::{Bicycle, Description};

/// The most designs one study may hold (a 100,000 × 100,000 map).
pub(crate) const MAX_DESIGNS: u64 = 10_000_000_000;

/// The most points on one axis.
pub const MAX_AXIS_POINTS: usize = 10_000_000;

/// What an axis varies: a parameter of the table of the base's form, one of the aliases that
/// stand for a derived parameter or two at once, or the speed. Typed: built from a name by
/// [`Parameter::named`], which knows the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parameter {
    /// A parameter of the table ([`crate::advanced::table::parameters`]) of either form:
    /// a benchmark key (`w`, `c`, `lam`, `g`, `rR`, `mB`, `IBxx`, …) or a JBike6 `.m` key
    /// (`wheelbase`, `head_angle`, `trail`, `gravity`, `mrider`, `Irider(1)`, `Drearwheel`, …).
    Table(&'static ParameterInfo),
    /// The benchmark form's head angle π/2 − λ (`head_angle`; the JBike6 form's own
    /// `head_angle` is a table entry).
    HeadAngle,
    /// The benchmark form's two wheel radii rR and rF together (`wheel_radius`).
    WheelRadius,
    /// The JBike6 form's two wheel diameters together (`wheel_diameter`).
    WheelDiameter,
    /// The forward speed v [m/s] at which the speed-dependent quantities are read.
    Speed,
}

/// The answers' layout of a parameter: `{"kind": "benchmark" | "jbike6", "name": key}`, or
/// `{"kind": "speed"}`.
impl Serialize for Parameter {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let (kind, name) = match self.form() {
            Some(Form::Benchmark) => ("benchmark", Some(self.name())),
            Some(Form::Jbike6) => ("jbike6", Some(self.name())),
            None => ("speed", None),
        };
        let mut s = serializer.serialize_struct("Parameter", 1 + usize::from(name.is_some()))?;
        s.serialize_field("kind", kind)?;
        if let Some(name) = name {
            s.serialize_field("name", name)?;
        }
        s.end()
    }
}

/// One axis of a study: a parameter over `count` evenly spaced values from `start` to `stop`
/// (both included). The grid is linear in the unit the values are given in, `scale` SI units
/// (1 when they are SI; a front end taking an angle in degrees gives π/180): the design at
/// point `i` has the parameter at `scale · value(i)` in SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Axis {
    /// What it varies.
    pub parameter: Parameter,
    /// First value, in units of `scale`.
    pub start: f64,
    /// Last value, in units of `scale`.
    pub stop: f64,
    /// Number of values (≥ 1; with 1 the axis holds `start` only).
    pub count: usize,
    /// SI units per unit of `start` and `stop` (1 for SI values).
    pub scale: f64,
}

/// A form's name in messages.
fn form_name(form: Form) -> &'static str {
    match form {
        Form::Benchmark => "benchmark",
        Form::Jbike6 => "JBike6",
    }
}

/// Benchmark-form names that stand for a key (aliases of the paper's symbols): (alias, key).
const BENCHMARK_ALIASES: [(&str, &str); 4] = [
    ("wheelbase", "w"),
    ("trail", "c"),
    ("steer_axis_tilt", "lam"),
    ("gravity", "g"),
];

/// The key an alias of the benchmark form stands for, or the name itself.
fn benchmark_alias(name: &str) -> &str {
    BENCHMARK_ALIASES
        .iter()
        .find(|(alias, _)| *alias == name)
        .map_or(name, |(_, key)| key)
}

/// The names a form accepts beside its table's keys (and, in the JBike6 form, their TOML
/// paths), in the order messages list them: the benchmark form's aliases (`wheelbase`,
/// `trail`, `steer_axis_tilt`, `gravity`), `head_angle` and `wheel_radius`; the JBike6 form's
/// `wheel_diameter`. The speed is not among them (it is no parameter of the bicycle).
pub fn aliases(form: Form) -> Vec<&'static str> {
    match form {
        Form::Benchmark => {
            let mut names: Vec<&'static str> = BENCHMARK_ALIASES.iter().map(|(a, _)| *a).collect();
            names.extend(["head_angle", "wheel_radius"]);
            names
        }
        Form::Jbike6 => vec!["wheel_diameter"],
    }
}

impl Parameter {
    /// The parameter of `base` named `name`: a benchmark key or its alias (`trail` for `c`),
    /// `head_angle`, `wheel_radius`; a JBike6 `.m` key or TOML path (`rider.ycm` for
    /// `ycmrider`), `wheel_diameter`; `speed` or `v`. `None` when the base's form has no such
    /// parameter.
    ///
    /// ```
    /// use whipple::advanced::design::Parameter;
    /// use whipple::presets;
    /// let bike = presets::find("benchmark")?.bicycle();
    /// let Some(Parameter::Table(trail)) = Parameter::named("trail", &bike) else { panic!() };
    /// assert_eq!((trail.key, trail.unit), ("c", "m"));
    /// assert_eq!(Parameter::named("mrider", &bike), None);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn named(name: &str, base: &Bicycle) -> Option<Parameter> {
        if name == "speed" || name == "v" {
            return Some(Parameter::Speed);
        }
        let (form, key) = match &base.description {
            Description::Benchmark(_) => match benchmark_alias(name) {
                "head_angle" => return Some(Parameter::HeadAngle),
                "wheel_radius" => return Some(Parameter::WheelRadius),
                key => (Form::Benchmark, key),
            },
            // A TOML path (`rider.ycm`, `rider.I[1]`) names the same parameter as its `.m` key
            // (`ycmrider`, `Irider(1)`).
            Description::Jbike6(_) if name == "wheel_diameter" => {
                return Some(Parameter::WheelDiameter);
            }
            Description::Jbike6(_) => (Form::Jbike6, name),
        };
        parameters(form)
            .iter()
            .find(|p| p.key == key || (form == Form::Jbike6 && p.path == key))
            .map(Parameter::Table)
    }

    /// [`Parameter::named`], or an error that names `name` and the base's form.
    pub fn find(name: &str, base: &Bicycle) -> Result<Parameter> {
        Parameter::named(name, base).ok_or_else(|| Error::InvalidArgument {
            what: "axis",
            rule: format!(
                "the {} form has no parameter `{name}`",
                form_name(base.description.form())
            ),
        })
    }

    /// The form whose descriptions it varies; `None` for the speed.
    pub fn form(&self) -> Option<Form> {
        match self {
            Parameter::Table(info) => Some(info.form),
            Parameter::HeadAngle | Parameter::WheelRadius => Some(Form::Benchmark),
            Parameter::WheelDiameter => Some(Form::Jbike6),
            Parameter::Speed => None,
        }
    }

    /// Its name: the table's key (`c`, `mrider`), the alias (`head_angle`, `wheel_radius`,
    /// `wheel_diameter`), or `speed`.
    pub fn name(&self) -> &'static str {
        match self {
            Parameter::Table(info) => info.key,
            Parameter::HeadAngle => "head_angle",
            Parameter::WheelRadius => "wheel_radius",
            Parameter::WheelDiameter => "wheel_diameter",
            Parameter::Speed => "speed",
        }
    }

    /// The SI unit of the parameter, from the parameter table (`rad`, `kg m^2`, `m`); `m/s` for
    /// the speed, `rad` for the benchmark form's derived head angle, `m` for the wheel
    /// aliases.
    pub fn unit(&self) -> &'static str {
        match self {
            Parameter::Table(info) => info.unit,
            Parameter::HeadAngle => ANGLE_UNIT,
            Parameter::WheelRadius | Parameter::WheelDiameter => "m",
            Parameter::Speed => "m/s",
        }
    }

    /// Whether the parameter is an angle (its unit is the radian).
    pub fn is_angle(&self) -> bool {
        self.unit() == ANGLE_UNIT
    }

    /// The table keys whose values it sets (`c` for `trail`, `lam` for the benchmark form's
    /// `head_angle`, `rR` and `rF` for `wheel_radius`); none for the speed. A bicycle's σ of
    /// these keys no longer applies once the parameter is set.
    pub fn keys(&self) -> &'static [&'static str] {
        match self {
            Parameter::Table(info) => std::slice::from_ref(&info.key),
            Parameter::HeadAngle => &["lam"],
            Parameter::WheelRadius => &["rR", "rF"],
            Parameter::WheelDiameter => &["Drearwheel", "Dfrontwheel"],
            Parameter::Speed => &[],
        }
    }

    /// Sets the parameter to `x` (SI units) in a description of its own form: by the table's
    /// key, or the parameters an alias stands for (both wheel radii for `wheel_radius`,
    /// λ = π/2 − x for the benchmark form's `head_angle`). `false`, the description unchanged,
    /// for the speed or a description of the other form.
    ///
    /// ```
    /// use whipple::advanced::design::Parameter;
    /// let mut bike = whipple::presets::find("benchmark")?.bicycle();
    /// let head = Parameter::find("head_angle", &bike)?;
    /// assert!(head.set(&mut bike.description, 70f64.to_radians()));
    /// assert!((bike.description.values()[2] - 20f64.to_radians()).abs() < 1e-15);
    /// assert!(!Parameter::Speed.set(&mut bike.description, 5.0));
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn set(&self, description: &mut Description, x: f64) -> bool {
        match (self, description) {
            (Parameter::Table(info), Description::Benchmark(b)) if info.form == Form::Benchmark => {
                b.set(info.key, x)
            }
            (Parameter::Table(info), Description::Jbike6(j)) if info.form == Form::Jbike6 => {
                j.set(info.key, x)
            }
            (Parameter::HeadAngle, Description::Benchmark(b)) => {
                b.lambda = std::f64::consts::FRAC_PI_2 - x;
                true
            }
            (Parameter::WheelRadius, Description::Benchmark(b)) => {
                b.r_r = x;
                b.r_f = x;
                true
            }
            (Parameter::WheelDiameter, Description::Jbike6(j)) => {
                j.rear_wheel.diameter = x;
                j.front_wheel.diameter = x;
                true
            }
            _ => false,
        }
    }

    /// Its value in a description of its own form (SI), the inverse of [`Parameter::set`];
    /// `None` for the speed, a description of the other form, or a wheel alias whose two
    /// wheels differ (it has no single value).
    ///
    /// ```
    /// use whipple::advanced::design::Parameter;
    /// let bike = whipple::presets::find("benchmark")?.bicycle();
    /// let head = Parameter::find("head_angle", &bike)?;
    /// assert!((head.get(&bike.description).unwrap() - 72f64.to_radians()).abs() < 1e-15);
    /// assert_eq!(Parameter::find("trail", &bike)?.get(&bike.description), Some(0.08));
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn get(&self, description: &Description) -> Option<f64> {
        match (self, description) {
            (Parameter::Table(info), Description::Benchmark(b)) if info.form == Form::Benchmark => {
                b.get(info.key)
            }
            (Parameter::Table(info), Description::Jbike6(j)) if info.form == Form::Jbike6 => {
                j.get(info.key)
            }
            (Parameter::HeadAngle, Description::Benchmark(b)) => {
                Some(std::f64::consts::FRAC_PI_2 - b.lambda)
            }
            (Parameter::WheelRadius, Description::Benchmark(b)) if b.r_r == b.r_f => Some(b.r_r),
            (Parameter::WheelDiameter, Description::Jbike6(j))
                if j.rear_wheel.diameter == j.front_wheel.diameter =>
            {
                Some(j.rear_wheel.diameter)
            }
            _ => None,
        }
    }
}

impl Axis {
    /// An axis of SI values: `count` points from `start` to `stop`; both finite, `count` in
    /// 1..=[`MAX_AXIS_POINTS`].
    ///
    /// ```
    /// use whipple::advanced::design::{Axis, Parameter};
    /// let bike = whipple::presets::find("benchmark")?.bicycle();
    /// let trail = Axis::new(Parameter::find("c", &bike)?, 0.0, 0.2, 5)?;
    /// assert_eq!(trail.si_value(2), 0.1);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn new(parameter: Parameter, start: f64, stop: f64, count: usize) -> Result<Axis> {
        Axis::scaled(parameter, start, stop, count, 1.0)
    }

    /// An axis whose values are given in a unit of `scale` SI units (π/180 for degrees); the
    /// same rules as [`Axis::new`], and a positive finite scale.
    pub fn scaled(
        parameter: Parameter,
        start: f64,
        stop: f64,
        count: usize,
        scale: f64,
    ) -> Result<Axis> {
        let bad = |rule: String| Error::InvalidArgument { what: "axis", rule };
        for x in [start, stop] {
            if !x.is_finite() {
                return Err(bad(format!("{x} is not a finite number")));
            }
        }
        if count == 0 || count > MAX_AXIS_POINTS {
            return Err(bad(format!(
                "COUNT must lie in 1..={MAX_AXIS_POINTS}, got {count}"
            )));
        }
        if !(scale.is_finite() && scale > 0.0) {
            return Err(bad(format!("the scale must be positive, got {scale}")));
        }
        Ok(Axis {
            parameter,
            start,
            stop,
            count,
            scale,
        })
    }

    /// The i-th value, in units of `scale`.
    #[inline]
    pub fn value(&self, i: usize) -> f64 {
        if self.count <= 1 {
            return self.start;
        }
        if i + 1 == self.count {
            return self.stop;
        }
        self.start + (self.stop - self.start) * (i as f64 / (self.count - 1) as f64)
    }

    /// The i-th value in SI units (radians for an angle).
    #[inline]
    pub fn si_value(&self, i: usize) -> f64 {
        self.value(i) * self.scale
    }
}

/// A contiguous part `index` of `count` equal parts of a study (0-based: `0/4 … 3/4`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Shard {
    /// Which part, 0 ≤ index < count.
    pub index: u64,
    /// How many parts.
    pub count: u64,
}

impl Shard {
    /// The whole study.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Parses `I/N`.
    pub fn parse(text: &str) -> Result<Shard> {
        let bad = || Error::InvalidArgument {
            what: "shard",
            rule: format!("expects I/N with 0 <= I < N (for example 3/16), got `{text}`"),
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let index: u64 = i.trim().parse().map_err(|_| bad())?;
        let count: u64 = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The design indices [first, end) of this shard of `total` designs.
    pub fn indices(&self, total: u64) -> (u64, u64) {
        let part = |k: u64| ((k as u128 * total as u128) / self.count as u128) as u64;
        (part(self.index), part(self.index + 1))
    }
}

/// Why a design has no numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DesignStatus {
    /// Computed.
    Ok,
    /// Its parameters break a rule of the model (see the row's `reason`).
    Invalid,
    /// Double precision cannot give its answer (see the row's `reason`).
    AccuracyLost,
}

/// The quantities of one design. Speeds in m/s, frequencies in rad/s, real parts in 1/s;
/// `None` where the quantity does not exist (no weave speed in the range) or was not asked for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DesignQuantities {
    /// v_d (only when [`StudySettings::double_root`] is set).
    pub double_root_speed: Option<f64>,
    /// v_w.
    pub weave_speed: Option<f64>,
    /// v_c.
    pub capsize_speed: Option<f64>,
    /// |Im λ| of the weave at v_w.
    pub weave_frequency: Option<f64>,
    /// Whether a self-stable speed exists in the range.
    pub stable: bool,
    /// Total width of the self-stable ranges in the range (+∞ when unbounded; 0 when none).
    pub stable_width: f64,
    /// Lowest self-stable speed.
    pub stable_from: Option<f64>,
    /// Upper end of the first self-stable range (+∞ when unbounded).
    pub stable_to: Option<f64>,
    /// At the study's speed: the largest real part of the eigenvalues.
    pub max_real: Option<f64>,
    /// The mode that largest real part belongs to (weave: a complex pair; capsize or castering:
    /// the larger or smaller real eigenvalue where the spectrum has one complex pair and two real
    /// eigenvalues; unclassified otherwise).
    pub max_real_mode: Option<Mode>,
    /// Whether some speeds in the range could not be classified (near-tangency).
    pub unresolved: bool,
    /// Self-stable at every speed of [`StudySettings::band`]: yes, no, or `None` (no band
    /// asked for, or undecided: round-off left speeds of the band unclassified, `unresolved`).
    pub stable_over: Option<bool>,
    /// How far the self-stable range reaches below the band's lower end [m/s] (when
    /// `stable_over`).
    pub band_margin_below: Option<f64>,
    /// How far it reaches above the band's upper end [m/s] (+∞ when it has none; when
    /// `stable_over`).
    pub band_margin_above: Option<f64>,
}

impl DesignQuantities {
    const NONE: DesignQuantities = DesignQuantities {
        double_root_speed: None,
        weave_speed: None,
        capsize_speed: None,
        weave_frequency: None,
        stable: false,
        stable_width: 0.0,
        stable_from: None,
        stable_to: None,
        max_real: None,
        max_real_mode: None,
        unresolved: false,
        stable_over: None,
        band_margin_below: None,
        band_margin_above: None,
    };
}

/// One design of a study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignRow {
    /// Row-major index, iy · nx + ix.
    pub index: u64,
    /// Index along x.
    pub ix: usize,
    /// Index along y (0 for a one-parameter study).
    pub iy: usize,
    /// x in the axis's units (those of its `start` and `stop`).
    pub x: f64,
    /// y in the axis's units (NaN-free: 0 for a one-parameter study).
    pub y: f64,
    /// Computed, invalid, or accuracy lost.
    pub status: DesignStatus,
    /// The rule broken or the accuracy lost, in words (`None` when computed).
    pub reason: Option<String>,
    /// The quantities (all `None`/false when not computed).
    pub quantities: DesignQuantities,
}

/// What to compute for every design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StudySettings {
    /// The speed range the critical speeds and stable ranges are read on [m/s] (default
    /// [0, +∞)).
    pub range: (f64, f64),
    /// The speed at which `max_real` is read [m/s] (an axis named `speed` overrides it).
    pub speed: Option<f64>,
    /// Also compute v_d (costs about as much again as the rest).
    pub double_root: bool,
    /// A band of speeds [a, b] inside `range` over which to ask "self-stable at every speed?"
    /// ([`DesignQuantities::stable_over`] and the margins) [m/s].
    pub band: Option<(f64, f64)>,
}

impl Default for StudySettings {
    fn default() -> Self {
        StudySettings {
            range: (0.0, f64::INFINITY),
            speed: None,
            double_root: false,
            band: None,
        }
    }
}

/// A parameter study over a base bicycle: one axis (`y` = None) or two.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Study {
    /// The base design.
    #[serde(skip)]
    pub base: Bicycle,
    /// The first axis.
    pub x: Axis,
    /// The second axis, for a map.
    pub y: Option<Axis>,
    /// What to compute.
    pub options: StudySettings,
}

/// Designs computed per parallel chunk (bounds memory: a few MB of rows).
pub(crate) const CHUNK: u64 = 1 << 15;

impl Study {
    /// A study; checks the sizes and the options.
    ///
    /// ```
    /// use whipple::advanced::design::{Axis, Parameter, StudySettings, Shard};
    /// use whipple::{Study, presets};
    /// let bike = presets::find("benchmark")?.bicycle();
    /// let x = Axis::new(Parameter::find("c", &bike)?, 0.0, 0.2, 5)?;
    /// let study = Study::new(bike, x, None, StudySettings::default())?;
    /// let mut rows = Vec::new();
    /// study.run(Shard::WHOLE, &Default::default(), |chunk| { rows.extend_from_slice(chunk); Ok(()) })?;
    /// assert_eq!(rows.len(), 5);
    /// assert!((rows[2].quantities.weave_speed.unwrap() - 4.6).abs() < 1.0); // c = 0.1 m
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn new(base: Bicycle, x: Axis, y: Option<Axis>, options: StudySettings) -> Result<Study> {
        stability::check_range(options.range.0, options.range.1)?;
        if let Some(band) = options.band {
            stability::check_band(band, options.range)?;
        }
        if let Some(v) = options.speed {
            if !v.is_finite() {
                return Err(Error::InvalidArgument {
                    what: "speed",
                    rule: format!("must be a finite number, got {v}"),
                });
            }
        }
        let total = x.count as u128 * y.as_ref().map_or(1, |a| a.count) as u128;
        if total > MAX_DESIGNS as u128 {
            return Err(Error::InvalidArgument {
                what: "axis",
                rule: format!("{total} designs is more than the limit of {MAX_DESIGNS}"),
            });
        }
        // Each axis varies a parameter of the base's own form.
        for axis in std::iter::once(&x).chain(y.as_ref()) {
            if let Some(form) = axis.parameter.form() {
                if form != base.description.form() {
                    return Err(Error::InvalidArgument {
                        what: "axis",
                        rule: format!(
                            "`{}` is a parameter of the {} form, and the base is in the {} form",
                            axis.parameter.name(),
                            form_name(form),
                            form_name(base.description.form())
                        ),
                    });
                }
            }
        }
        // The base itself must be a valid bicycle.
        base.benchmark()?;
        Ok(Study {
            base,
            x,
            y,
            options,
        })
    }

    /// Number of designs.
    pub fn len(&self) -> u64 {
        self.x.count as u64 * self.y.as_ref().map_or(1, |a| a.count) as u64
    }

    /// Whether the study holds no design (never: every axis has at least one point).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The base design's coordinates on the axes in SI units, where the axis varies a
    /// parameter of the bicycle (speed axes give `None`, and so does an alias of two parameters
    /// that the base gives two values: `wheel_radius` of a bicycle with wheels of two sizes).
    ///
    /// ```
    /// use whipple::advanced::design::{Axis, Parameter, StudySettings};
    /// use whipple::{Study, presets};
    /// let bike = presets::find("benchmark")?.bicycle(); // rR = 0.3 m, rF = 0.35 m
    /// let trail = Axis::new(Parameter::find("c", &bike)?, 0.0, 0.2, 5)?;
    /// let radius = Axis::new(Parameter::WheelRadius, 0.2, 0.5, 4)?;
    /// let study = Study::new(bike, trail, Some(radius), StudySettings::default())?;
    /// assert_eq!(study.base_point(), (Some(0.08), None));
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn base_point(&self) -> (Option<f64>, Option<f64>) {
        let at = |a: &Axis| -> Option<f64> {
            let si = match (&a.parameter, &self.base.description) {
                (Parameter::Speed, _) => return None,
                (Parameter::Table(info), Description::Benchmark(b)) => b.get(info.key)?,
                (Parameter::Table(info), Description::Jbike6(j)) => j.get(info.key)?,
                (Parameter::HeadAngle, Description::Benchmark(b)) => {
                    std::f64::consts::FRAC_PI_2 - b.lambda
                }
                // The alias sets both radii: a base with two sizes is on no point of it.
                (Parameter::WheelRadius, Description::Benchmark(b)) if b.r_r == b.r_f => b.r_r,
                (Parameter::WheelDiameter, Description::Jbike6(j))
                    if j.rear_wheel.diameter == j.front_wheel.diameter =>
                {
                    j.rear_wheel.diameter
                }
                _ => return None,
            };
            Some(si)
        };
        (at(&self.x), self.y.as_ref().and_then(at))
    }

    /// The grid indices (ix, iy) of design `index` (row-major).
    fn cell(&self, index: u64) -> (usize, usize) {
        let nx = self.x.count as u64;
        ((index % nx) as usize, (index / nx) as usize)
    }

    /// The description and the speed (where an axis is the speed) of design `index`.
    fn variant(&self, index: u64) -> (Description, Option<f64>) {
        let (ix, iy) = self.cell(index);
        let mut speed = self.options.speed;
        let mut description = self.base.description;
        let mut apply = |axis: &Axis, i: usize| {
            let v = axis.si_value(i);
            match &axis.parameter {
                Parameter::Speed => speed = Some(v),
                // Study::new checked that the axes belong to the base's form.
                parameter => {
                    parameter.set(&mut description, v);
                }
            }
        };
        apply(&self.x, ix);
        if let Some(y) = &self.y {
            apply(y, iy);
        }
        (description, speed)
    }

    /// The bicycle of design `index` (row-major, `iy · nx + ix`): the base bicycle with the
    /// axes' parameters set (a speed axis changes no parameter), named after the base, its
    /// uncertainties kept. An index outside the study is [`Error::InvalidArgument`].
    pub fn bicycle_at(&self, index: u64) -> Result<Bicycle> {
        if index >= self.len() {
            return Err(Error::InvalidArgument {
                what: "index",
                rule: format!(
                    "must be below the study's {} designs, got {index}",
                    self.len()
                ),
            });
        }
        let (description, _) = self.variant(index);
        Ok(Bicycle {
            description,
            ..self.base.clone()
        })
    }

    /// Computes one design.
    pub fn design(&self, index: u64) -> DesignRow {
        let (ix, iy) = self.cell(index);
        let (description, speed) = self.variant(index);
        let (status, reason, quantities) = match analyse(&description, speed, &self.options) {
            Ok(q) => (DesignStatus::Ok, None, q),
            Err(e @ Error::AccuracyLost { .. }) => (
                DesignStatus::AccuracyLost,
                Some(e.to_string()),
                DesignQuantities::NONE,
            ),
            Err(e) => (
                DesignStatus::Invalid,
                Some(e.to_string()),
                DesignQuantities::NONE,
            ),
        };
        DesignRow {
            index,
            ix,
            iy,
            x: self.x.value(ix),
            y: self.y.as_ref().map_or(0.0, |a| a.value(iy)),
            status,
            reason,
            quantities,
        }
    }

    /// Computes the shard's designs in order, in parallel chunks of `CHUNK` on rayon's pool,
    /// handing each chunk to `sink` in index order; stops early (with
    /// [`Error::InvalidArgument`] `what: "stopped"`) when `stop` is set, and with the sink's
    /// error when it fails. Memory: one chunk of rows at a time.
    pub fn run(
        &self,
        shard: Shard,
        stop: &AtomicBool,
        mut sink: impl FnMut(&[DesignRow]) -> Result<()>,
    ) -> Result<()> {
        let (first, end) = shard.indices(self.len());
        let mut start = first;
        while start < end {
            if stop.load(Ordering::Relaxed) {
                return Err(stopped());
            }
            let stop_at = (start + CHUNK).min(end);
            // The flag is checked before every design too, so that a chunk (a second or more
            // of work) stops within one design's time.
            let rows = (0..(stop_at - start) as usize)
                .into_par_iter()
                .map(|k| {
                    if stop.load(Ordering::Relaxed) {
                        Err(stopped())
                    } else {
                        Ok(self.design(start + k as u64))
                    }
                })
                .collect::<Result<Vec<DesignRow>>>()?;
            sink(&rows)?;
            start = stop_at;
        }
        Ok(())
    }
}

fn stopped() -> Error {
    Error::InvalidArgument {
        what: "stopped",
        rule: "the study was stopped before it finished".into(),
    }
}

/// The canonical matrices of a described bicycle, validated (formed once: validation needs
/// them too).
fn canonical_of(d: &Description) -> Result<Canonical> {
    match d {
        Description::Benchmark(b) => b.check_with_canonical().map(|(_, c)| c),
        Description::Jbike6(j) => Ok(Canonical::from_unchecked(&j.to_benchmark()?)),
    }
}

/// The quantities of one described bicycle.
pub(crate) fn analyse(
    description: &Description,
    speed: Option<f64>,
    options: &StudySettings,
) -> Result<DesignQuantities> {
    let canonical = canonical_of(description)?;
    let sp = SpeedPolynomials::new(&canonical)?;
    let (lo, hi) = options.range;
    let s = summary(&sp, lo, hi, options.band)?;
    let mut q = DesignQuantities {
        double_root_speed: None,
        weave_speed: s.weave_speed,
        capsize_speed: s.capsize_speed,
        weave_frequency: s.weave_frequency,
        stable: s.stable_ranges > 0,
        stable_width: s.stable_width,
        stable_from: s.stable_from,
        stable_to: s.stable_to,
        max_real: None,
        max_real_mode: None,
        unresolved: s.unresolved,
        stable_over: s.band.and_then(|b| b.stable),
        band_margin_below: s.band.and_then(|b| b.margin_below),
        band_margin_above: s.band.and_then(|b| b.margin_above),
    };
    if options.double_root {
        let c = stability::critical_speeds(&canonical, lo, hi)?;
        if let Some(why) = c.double_root_unavailable {
            return Err(Error::AccuracyLost {
                quantity: "the double-root speed".into(),
                reason: why,
            });
        }
        q.double_root_speed = c.double_root_speed;
    }
    if let Some(v) = speed {
        let roots = certified_roots(&CharacteristicPolynomial::new(&canonical), v)?;
        let labels = super::modes::pattern_labels(&roots);
        // Sorted by decreasing real part: the first is the largest.
        q.max_real = Some(roots[0].re);
        q.max_real_mode = Some(labels.map_or(Mode::Unclassified, |l| l[0]));
    }
    Ok(q)
}
