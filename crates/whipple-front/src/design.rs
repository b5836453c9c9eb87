//! Design axes as people type them, `NAME=START:STOP:COUNT` (`trail=0:0.2:401`,
//! `head_angle_deg=60:80:401`), into the library's typed [`Axis`] (a [`Parameter`] over a
//! linear grid whose SI values the study computes with), and a [`DesignStudy`]: the library's
//! [`Study`] with its axes as they were typed, for headers, labels and answers. Which names
//! exist and what unit each has is read from the library ([`Parameter::named`],
//! [`Parameter::unit`], which read the parameter table); only the syntax and the degrees are
//! this module's.

use serde::ser::SerializeStruct;
use serde::{Serialize, Serializer};
use whipple::Study;
use whipple::advanced::control::HandlingBound;
use whipple::advanced::design::{Axis, MAX_AXIS_POINTS, Parameter, StudySettings, aliases};
use whipple::advanced::table::{Form, parameters};
use whipple::{Bicycle, Error, Result};

use crate::units::{self, TypedUnit, UserUnit};

/// An axis as the user typed it: the name as written (`head_angle_deg`), the unit of its values
/// (degrees after `_deg`, millimetres after `_mm`, km/h after a speed's values), and the library's axis (whose `start`, `stop` and values are in the user's units,
/// `scale` taking them to SI).
#[derive(Debug, Clone, PartialEq)]
pub struct AxisSpec {
    /// The name as the user wrote it (`trail`, `head_angle_deg`, `mrider`, `speed`).
    pub name: String,
    /// The unit of the user's values.
    pub typed: UserUnit,
    /// The parameter and its grid.
    pub axis: Axis,
}

/// The answers' layout of an axis: `name`, `parameter`, `start`, `stop`, `count`, `degrees`,
/// `unit` (of `start` and `stop` as typed: `deg`, `mm`, `km/h`, or the table's).
impl Serialize for AxisSpec {
    fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        let mut s = serializer.serialize_struct("Axis", 7)?;
        s.serialize_field("name", &self.name)?;
        s.serialize_field("parameter", &self.axis.parameter)?;
        s.serialize_field("start", &self.axis.start)?;
        s.serialize_field("stop", &self.axis.stop)?;
        s.serialize_field("count", &self.axis.count)?;
        s.serialize_field(
            "degrees",
            &(self.typed == UserUnit::Typed(TypedUnit::Degrees)),
        )?;
        s.serialize_field("unit", self.unit())?;
        s.end()
    }
}

/// The names a base bicycle's parameters may take, for the message naming an unknown one: its
/// form's table keys and the library's aliases ([`aliases`]), `speed` where it is accepted.
fn known_names(base: &Bicycle, speed: bool) -> String {
    let form = base.description.form();
    let keys: Vec<&str> = parameters(form).iter().map(|p| p.key).collect();
    let speed = if speed { "; speed" } else { "" };
    match form {
        Form::Benchmark => format!(
            "the benchmark keys {}; {}{speed}; _deg after an angle, _mm after a length",
            keys.join(", "),
            aliases(form).join(", ")
        ),
        Form::Jbike6 => format!(
            "{}, {} (or their TOML paths: rider.m, rider.xcm, rider.I[1], ...){speed}; _deg \
             after an angle, _mm after a length",
            keys.join(", "),
            aliases(form).join(", ")
        ),
    }
}

/// A parameter's name as people type it (`trail`, `head_angle_deg`, `trail_mm`, `c`,
/// `rider.m`, `speed`): the library's [`Parameter`] of `base`'s form ([`Parameter::named`]) and
/// the unit its suffix names (`_deg` only after an angle, `_mm` only after a length: the
/// table's units). The error is the rule broken, naming the name as typed; `speed` says whether
/// the speed is a name here.
fn resolve(
    name: &str,
    base: &Bicycle,
    speed: bool,
) -> std::result::Result<(Parameter, Option<TypedUnit>), String> {
    let named = |n: &str| match Parameter::named(n, base) {
        Some(Parameter::Speed) if !speed => None,
        other => other,
    };
    if let Some(parameter) = named(name) {
        return Ok((parameter, None));
    }
    let (stem, typed) = units::strip_unit(name);
    let (Some(parameter), Some(unit)) = (named(stem), typed) else {
        return Err(format!(
            "`{name}` is not a parameter of this bicycle (known: {})",
            known_names(base, speed)
        ));
    };
    if parameter == Parameter::Speed {
        return Err(format!(
            "speed has no `{}` form (give km/h after its values: speed=10:30:21km/h)",
            unit.suffix()
        ));
    }
    if !unit.fits(parameter.unit()) {
        return Err(format!("`{name}`: {}", unit.misfit(stem)));
    }
    Ok((parameter, Some(unit)))
}

/// The unit of the values typed after `name=` (`10:30:21km/h` for the speed) and the values'
/// text without it; km/h after anything but the speed is refused.
fn values_unit<'a>(
    name: &str,
    values: &'a str,
    parameter: Parameter,
    typed: Option<TypedUnit>,
) -> std::result::Result<(&'a str, UserUnit), String> {
    if parameter != Parameter::Speed {
        let tail = values.trim_end();
        let kmh = tail.len() >= units::KMH_SUFFIX.len()
            && tail.is_char_boundary(tail.len() - units::KMH_SUFFIX.len())
            && tail[tail.len() - units::KMH_SUFFIX.len()..].eq_ignore_ascii_case(units::KMH_SUFFIX);
        if kmh {
            return Err(format!(
                "`{name}` is not a speed: only the speed takes a unit after its values (`km/h`)"
            ));
        }
        return Ok((values, typed.map_or(UserUnit::Si, UserUnit::Typed)));
    }
    let (numbers, speed_unit) = units::split_speed(values).map_err(|e| match e {
        Error::InvalidArgument { rule, .. } => rule,
        other => other.to_string(),
    })?;
    Ok((numbers, UserUnit::Speed(speed_unit)))
}

/// The bicycle with parameters changed by the names a design axis takes (a table key such as
/// `c` or `mB`, an alias such as `trail` or `head_angle`, `wheel_radius`, a JBike6 `.m` key or
/// TOML path, `_deg` after an angle for a value in degrees), in the order given: the values set
/// in SI units ([`Parameter::set`]), the σ of the keys they set dropped, and the name marked
/// ` (edited)` (as the page names an edited design) unless it already is. A name the base's
/// form does not have, the speed, or `_deg` after what is not an angle is
/// [`Error::InvalidParameter`] naming it as typed, with the names accepted.
///
/// ```
/// use whipple::presets;
/// use whipple_front::design::replace;
/// let crown = presets::find("schwinn-crown")?.bicycle();
/// let steeper = replace(&crown, &[("head_angle_deg".into(), 72.0), ("trail".into(), 0.05)])?;
/// assert_eq!(steeper.name.as_deref(), Some("schwinn-crown (edited)"));
/// let benchmark = replace(&presets::find("benchmark")?.bicycle(), &[("trail".into(), 0.09)])?;
/// assert_eq!(benchmark.description.values()[1], 0.09);
/// assert!(replace(&benchmark, &[("speed".into(), 5.0)]).is_err());
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn replace(base: &Bicycle, changes: &[(String, f64)]) -> Result<Bicycle> {
    let mut bicycle = base.clone();
    for (name, value) in changes {
        let refuse = |rule: String| Error::InvalidParameter {
            field: name.clone(),
            value: *value,
            rule,
        };
        let (parameter, typed) = resolve(name.trim(), base, false).map_err(refuse)?;
        if !value.is_finite() {
            return Err(refuse("must be a finite number".into()));
        }
        let si = typed.map_or(*value, |u| u.to_si(*value));
        if !parameter.set(&mut bicycle.description, si) {
            return Err(refuse(format!(
                "not a parameter of this bicycle (known: {})",
                known_names(base, false)
            )));
        }
        for key in parameter.keys() {
            bicycle.sigma.remove(*key);
        }
    }
    bicycle.name = bicycle.name.map(|name| {
        if name.ends_with(EDITED) {
            name
        } else {
            format!("{name}{EDITED}")
        }
    });
    Ok(bicycle)
}

/// One change typed as `NAME=VALUE` (`head_angle_deg=72`, `trail=0.05`: the command line's
/// `--set`), for [`replace`], which resolves the name: the name as written and the value, a
/// finite number. An error names the text as typed.
///
/// ```
/// use whipple_front::design::parse_change;
/// assert_eq!(parse_change("head_angle_deg=72")?, ("head_angle_deg".to_string(), 72.0));
/// assert!(parse_change("trail").is_err() && parse_change("trail=inf").is_err());
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn parse_change(text: &str) -> Result<(String, f64)> {
    let bad = |rule: String| Error::InvalidArgument {
        what: "change",
        rule,
    };
    let Some((name, value)) = text.split_once('=') else {
        return Err(bad(format!(
            "expects NAME=VALUE (for example head_angle_deg=72), got `{text}`"
        )));
    };
    let name = name.trim();
    if name.is_empty() {
        return Err(bad(format!("`{text}`: no NAME before `=`")));
    }
    match value.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok((name.to_string(), x)),
        _ => Err(bad(format!(
            "`{text}`: `{}` is not a finite number",
            value.trim()
        ))),
    }
}

/// What an edited bicycle's name ends with (the page's compare names an edited design so).
pub const EDITED: &str = " (edited)";

impl AxisSpec {
    /// Parses `NAME=START:STOP:COUNT` for a base bicycle: the name must exist in its form
    /// (a key, an alias such as `trail`, a JBike6 TOML path, or `speed`), `_deg` only after an
    /// angle (a parameter whose unit in the table is the radian), START and STOP finite
    /// numbers, COUNT a whole number in 1..=[`MAX_AXIS_POINTS`]. An error names the spec as
    /// typed (`Error::InvalidArgument { what: "axis", .. }`).
    ///
    /// ```
    /// use whipple_front::design::AxisSpec;
    /// use whipple::presets;
    /// let crown = presets::find("schwinn-crown")?.bicycle();
    /// let axis = AxisSpec::parse("head_angle_deg=60:80:401", &crown)?;
    /// assert!(axis.unit() == "deg" && axis.axis.count == 401 && (axis.value(200) - 70.0).abs() < 1e-12);
    /// assert_eq!(axis.unit(), "deg");
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn parse(spec: &str, base: &Bicycle) -> Result<AxisSpec> {
        let bad = |rule: String| Error::InvalidArgument { what: "axis", rule };
        let Some((name, grid)) = spec.split_once('=') else {
            return Err(bad(format!(
                "expects NAME=START:STOP:COUNT (for example trail=0:0.2:401), got `{spec}`"
            )));
        };
        let name = name.trim();
        let (parameter, typed) = resolve(name, base, true).map_err(bad)?;
        let (grid, unit) = values_unit(name, grid, parameter, typed).map_err(bad)?;
        let parts: Vec<&str> = grid.split(':').collect();
        let [start, stop, count] = parts[..] else {
            return Err(bad(format!(
                "`{spec}`: expects START:STOP:COUNT after `{name}=`"
            )));
        };
        let number = |t: &str| -> Result<f64> {
            let x: f64 = t
                .trim()
                .parse()
                .map_err(|_| bad(format!("`{spec}`: `{t}` is not a number")))?;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(bad(format!("`{spec}`: `{t}` is not a finite number")))
            }
        };
        let (start, stop) = (number(start)?, number(stop)?);
        let count: usize = count.trim().parse().map_err(|_| {
            bad(format!(
                "`{spec}`: COUNT `{count}` must be a whole number ≥ 1"
            ))
        })?;
        if count == 0 || count > MAX_AXIS_POINTS {
            return Err(bad(format!(
                "`{spec}`: COUNT must lie in 1..={MAX_AXIS_POINTS}, got {count}"
            )));
        }
        let scale = unit.to_si(1.0);
        Ok(AxisSpec {
            name: name.to_string(),
            typed: unit,
            axis: Axis::scaled(parameter, start, stop, count, scale)?,
        })
    }

    /// The i-th value in the user's units.
    #[inline]
    pub fn value(&self, i: usize) -> f64 {
        self.axis.value(i)
    }

    /// The unit of the user's values, for labels: `deg` for an angle typed in degrees, `mm` for
    /// a length in millimetres, `km/h` for speeds typed so, otherwise the parameter table's unit as printed (`m`, `kg`, `kg m²`, `rad`, `m/s²`,
    /// `m/s` for the speed).
    pub fn unit(&self) -> &'static str {
        self.typed.label(self.axis.parameter.unit())
    }

    /// An SI value of the axis's parameter in the user's units (degrees for a `_deg` axis).
    pub fn from_si(&self, si: f64) -> f64 {
        self.typed.from_si(si)
    }
}

/// A bounded parameter as the user typed it for the optimal-handling search: `NAME=LOW:HIGH`
/// (`trail=0:0.2`, `head_angle_deg=60:85`), named as [`AxisSpec`] names its parameter (the
/// speed is the design speed, not a bound).
#[derive(Debug, Clone)]
pub struct BoundSpec {
    /// The name as the user wrote it.
    pub name: String,
    /// The unit of the user's values (`_deg`, `_mm` or SI).
    pub typed: UserUnit,
    /// The library's bound, in SI.
    pub bound: HandlingBound,
}

impl BoundSpec {
    /// Parses `NAME=LOW:HIGH` against `base`'s parameters.
    ///
    /// ```
    /// use whipple_front::design::BoundSpec;
    /// let bike = whipple::presets::find("benchmark")?.bicycle();
    /// let b = BoundSpec::parse("head_angle_deg=60:85", &bike)?;
    /// assert!(b.unit() == "deg" && (b.bound.high - 85f64.to_radians()).abs() < 1e-15);
    /// assert!(BoundSpec::parse("speed=1:2", &bike).is_err());
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn parse(spec: &str, base: &Bicycle) -> Result<BoundSpec> {
        let bad = |rule: String| Error::InvalidArgument {
            what: "bound",
            rule,
        };
        let Some((name, range)) = spec.split_once('=') else {
            return Err(bad(format!(
                "expects NAME=LOW:HIGH (for example trail=0:0.2), got `{spec}`"
            )));
        };
        let name = name.trim();
        let [low, high] = range.split(':').collect::<Vec<&str>>()[..] else {
            return Err(bad(format!("`{spec}`: expects LOW:HIGH after `{name}=`")));
        };
        let number = |t: &str| -> Result<f64> {
            match t.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(bad(format!("`{spec}`: `{t}` is not a finite number"))),
            }
        };
        let (low, high) = (number(low)?, number(high)?);
        if low > high {
            return Err(bad(format!("`{spec}`: LOW must not exceed HIGH")));
        }
        let (parameter, typed) = resolve(name, base, false).map_err(bad)?;
        let unit = typed.map_or(UserUnit::Si, UserUnit::Typed);
        Ok(BoundSpec {
            name: name.to_string(),
            typed: unit,
            bound: HandlingBound {
                parameter,
                low: unit.to_si(low),
                high: unit.to_si(high),
            },
        })
    }

    /// The unit of the user's values, for labels (`deg` for a `_deg` name).
    pub fn unit(&self) -> &'static str {
        self.typed.label(self.bound.parameter.unit())
    }

    /// An SI value in the user's units.
    pub fn from_si(&self, si: f64) -> f64 {
        self.typed.from_si(si)
    }
}

/// A study with its axes as typed: the library's [`Study`] (which computes the rows) and the
/// names and units the answers show.
#[derive(Debug, Clone)]
pub struct DesignStudy {
    /// The study the library runs.
    pub study: Study,
    /// The first axis as typed.
    pub x: AxisSpec,
    /// The second axis as typed, for a map.
    pub y: Option<AxisSpec>,
}

impl DesignStudy {
    /// A study of `base` over the typed axes: the library's rules for the options and sizes
    /// ([`Study::new`]), and two axes of different names.
    pub fn new(
        base: Bicycle,
        x: AxisSpec,
        y: Option<AxisSpec>,
        options: StudySettings,
    ) -> Result<DesignStudy> {
        // The options' rules come first, then the names, then the size (in that order the
        // library checked them when it held the names).
        Study::new(base.clone(), x.axis.clone(), None, options)?;
        if let Some(y) = &y {
            if y.name == x.name {
                return Err(Error::InvalidArgument {
                    what: "axis",
                    rule: format!("x and y both vary `{}`", x.name),
                });
            }
        }
        let study = Study::new(
            base,
            x.axis.clone(),
            y.as_ref().map(|y| y.axis.clone()),
            options,
        )?;
        Ok(DesignStudy { study, x, y })
    }

    /// The base design's coordinates on the axes in the user's units, where the axis varies a
    /// parameter of the bicycle ([`Study::base_point`]).
    ///
    /// ```
    /// use whipple::advanced::design::StudySettings;
    /// use whipple::presets;
    /// use whipple_front::design::{AxisSpec, DesignStudy};
    /// let bike = presets::find("benchmark")?.bicycle(); // λ = π/10: a head angle of 72°
    /// let x = AxisSpec::parse("trail=0:0.2:5", &bike)?;
    /// let y = AxisSpec::parse("head_angle_deg=60:80:5", &bike)?;
    /// let study = DesignStudy::new(bike, x, Some(y), StudySettings::default())?;
    /// let (c, head) = study.base_point();
    /// assert_eq!(c, Some(0.08));
    /// assert!((head.unwrap_or(0.0) - 72.0).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn base_point(&self) -> (Option<f64>, Option<f64>) {
        let (x, y) = self.study.base_point();
        (
            x.map(|x| self.x.from_si(x)),
            y.zip(self.y.as_ref()).map(|(y, axis)| axis.from_si(y)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use whipple::presets;

    fn bike(name: &str) -> Bicycle {
        match presets::find(name) {
            Ok(preset) => preset.bicycle(),
            Err(e) => panic!("{e}"),
        }
    }

    fn rule(spec: &str, base: &Bicycle) -> String {
        match AxisSpec::parse(spec, base) {
            Err(Error::InvalidArgument { what: "axis", rule }) => rule,
            other => panic!("{spec}: {other:?}"),
        }
    }

    #[test]
    fn a_spec_gives_the_parameter_and_its_grid() -> Result<()> {
        let benchmark = bike("benchmark");
        let trail = AxisSpec::parse(" trail = 0 : 0.2 : 5", &benchmark)?;
        assert_eq!(trail.name, "trail");
        assert_eq!(trail.axis.parameter, Parameter::find("c", &benchmark)?);
        assert_eq!(
            (trail.axis.start, trail.axis.stop, trail.axis.count),
            (0.0, 0.2, 5)
        );
        assert_eq!(trail.value(4), 0.2);
        assert_eq!(trail.axis.si_value(2), 0.1);
        let speed = AxisSpec::parse("v=1:10:10", &benchmark)?;
        assert_eq!(
            (speed.axis.parameter, speed.unit()),
            (Parameter::Speed, "m/s")
        );
        let one = AxisSpec::parse("mB=85:90:1", &benchmark)?;
        assert_eq!((one.value(0), one.value(7)), (85.0, 85.0));
        Ok(())
    }

    /// Units come from the parameter table: an angle in degrees (its SI values in radians), an
    /// inertia in kg m², a length in m, a mass in kg, gravity in m/s².
    #[test]
    fn units_are_read_from_the_parameter_table() -> Result<()> {
        let benchmark = bike("benchmark");
        let head = AxisSpec::parse("head_angle_deg=60:80:3", &benchmark)?;
        assert_eq!(head.typed, UserUnit::Typed(TypedUnit::Degrees));
        assert_eq!(head.unit(), "deg");
        assert_eq!(head.value(1), 70.0);
        assert_eq!(
            head.axis.si_value(1).to_bits(),
            70f64.to_radians().to_bits()
        );
        let lam = AxisSpec::parse("lam=0.1:0.3:3", &benchmark)?;
        assert_eq!((lam.unit(), lam.typed), ("rad", UserUnit::Si));
        for (spec, unit) in [
            ("IBxx=5:15:3", "kg m²"),
            ("w=0.9:1.1:3", "m"),
            ("wheel_radius=0.3:0.4:3", "m"),
            ("mB=80:90:3", "kg"),
            ("gravity=9:10:3", "m/s²"),
        ] {
            let axis = AxisSpec::parse(spec, &benchmark)?;
            assert_eq!(axis.unit(), unit, "{spec}");
            assert_eq!(axis.axis.si_value(1), axis.value(1), "{spec}: SI as typed");
        }
        let crown = bike("schwinn-crown");
        for (spec, unit) in [
            ("Irider(1)=5:15:3", "kg m²"),
            ("rider.I[1]=5:15:3", "kg m²"),
            ("mrider=60:90:3", "kg"),
            ("Drearwheel=0.6:0.7:3", "m"),
            ("wheel_diameter=0.6:0.7:3", "m"),
            ("alphaIrider=-0.3:0.3:3", "rad"),
            ("rider.alpha_deg=-20:20:5", "deg"),
        ] {
            assert_eq!(AxisSpec::parse(spec, &crown)?.unit(), unit, "{spec}");
        }
        Ok(())
    }

    /// Every parameter of both tables: `_deg` is taken exactly where the table's unit is the
    /// radian.
    #[test]
    fn degrees_only_after_an_angle_of_the_table() {
        use whipple::advanced::table::{Form, parameters};
        for (form, preset) in [
            (Form::Benchmark, "benchmark"),
            (Form::Jbike6, "schwinn-crown"),
        ] {
            let base = bike(preset);
            for p in parameters(form) {
                let parsed = AxisSpec::parse(&format!("{}_deg=1:2:2", p.key), &base);
                assert_eq!(parsed.is_ok(), p.is_angle(), "{}", p.key);
            }
        }
    }

    /// `_mm` after a length, km/h after the speed's values: the same rule as the files'.
    #[test]
    fn lengths_take_millimetres_and_speeds_km_per_h() -> Result<()> {
        let benchmark = bike("benchmark");
        let trail = AxisSpec::parse("trail_mm=50:100:3", &benchmark)?;
        assert_eq!(trail.unit(), "mm");
        assert_eq!(trail.value(1), 75.0);
        assert_eq!(trail.from_si(0.075), 75.0);
        let speed = AxisSpec::parse("speed=18:36:3km/h", &benchmark)?;
        assert_eq!(speed.unit(), "km/h");
        assert_eq!(speed.axis.scale, 1.0 / 3.6);
        let edited = replace(
            &benchmark,
            &[
                ("c_mm".into(), 80.0),
                ("w_mm".into(), 1020.0),
                ("lam_deg".into(), 18.0),
            ],
        )?;
        let values = edited.description.values();
        assert_eq!(
            (values[0], values[1], values[2]),
            (1.02, 0.08, 18f64.to_radians())
        );
        let bound = BoundSpec::parse("trail_mm=0:200", &benchmark)?;
        assert_eq!((bound.unit(), bound.bound.high), ("mm", 0.2));
        for (spec, words) in [
            ("IBxx_mm=0:1:3", "`IBxx_mm`: `IBxx` is not a length"),
            (
                "head_angle_mm=0:1:3",
                "`head_angle_mm`: `head_angle` is not a length",
            ),
            ("speed_mm=0:1:3", "speed has no `_mm` form"),
            ("trail=0:1:3km/h", "`trail` is not a speed"),
            ("speed=0:1:3mph", "`mph` is not a unit of speed"),
        ] {
            let err = AxisSpec::parse(spec, &benchmark).unwrap_err().to_string();
            assert!(err.contains(words), "{spec}: {err}");
        }
        let err = replace(&benchmark, &[("mB_mm".into(), 1.0)])
            .unwrap_err()
            .to_string();
        assert!(err.contains("`mB_mm`: `mB` is not a length"), "{err}");
        let err = replace(&benchmark, &[("c_mm".into(), f64::NAN)])
            .unwrap_err()
            .to_string();
        assert!(err.contains("c_mm") && err.contains("finite"), "{err}");
        Ok(())
    }

    #[test]
    fn bad_specs_are_refused_naming_the_spec() {
        let benchmark = bike("benchmark");
        for (spec, words) in [
            (
                "trail",
                "expects NAME=START:STOP:COUNT (for example trail=0:0.2:401), got `trail`",
            ),
            (
                "trail=0:1",
                "`trail=0:1`: expects START:STOP:COUNT after `trail=`",
            ),
            ("trail=0:x:3", "`trail=0:x:3`: `x` is not a number"),
            (
                "trail=0:inf:3",
                "`trail=0:inf:3`: `inf` is not a finite number",
            ),
            (
                "trail=0:1:-3",
                "`trail=0:1:-3`: COUNT `-3` must be a whole number ≥ 1",
            ),
            (
                "trail=0:1:0",
                "`trail=0:1:0`: COUNT must lie in 1..=10000000, got 0",
            ),
            ("trail_deg=0:1:3", "`trail_deg`: `trail` is not an angle"),
            ("IBxx_deg=0:1:3", "`IBxx_deg`: `IBxx` is not an angle"),
            (
                "speed_deg=0:1:3",
                "speed has no `_deg` form (give km/h after its values: speed=10:30:21km/h)",
            ),
            (
                "trail=0:1:x",
                "`trail=0:1:x`: COUNT `x` must be a whole number ≥ 1",
            ),
        ] {
            assert_eq!(rule(spec, &benchmark), words, "{spec}");
        }
        let unknown = rule("mrider=60:90:3", &benchmark);
        assert!(
            unknown.starts_with(
                "`mrider` is not a parameter of this bicycle (known: the benchmark keys w, c,"
            ),
            "{unknown}"
        );
        let crown = bike("schwinn-crown");
        let unknown = rule("rider.height=1:2:3", &crown);
        assert!(
            unknown.contains("`rider.height`") && unknown.contains("TOML paths"),
            "{unknown}"
        );
    }

    /// The same parameter by its TOML path and by its `.m` key, in degrees too.
    #[test]
    fn jbike6_axes_take_toml_paths() -> Result<()> {
        let crown = bike("schwinn-crown");
        for (path, key) in [
            ("rider.ycm=0.8:1.4:7", "ycmrider=0.8:1.4:7"),
            ("rider.I[1]=5:15:3", "Irider(1)=5:15:3"),
            ("rider.alpha_deg=-20:20:5", "alphaIrider_deg=-20:20:5"),
        ] {
            let (by_path, by_key) = (
                AxisSpec::parse(path, &crown)?,
                AxisSpec::parse(key, &crown)?,
            );
            assert_eq!(by_path.axis, by_key.axis, "{path}");
            assert_eq!(by_path.typed, by_key.typed, "{path}");
        }
        Ok(())
    }

    #[test]
    fn a_study_refuses_one_name_twice_and_gives_the_base_as_typed() -> Result<()> {
        let benchmark = bike("benchmark");
        let x = AxisSpec::parse("trail=0:0.2:3", &benchmark)?;
        match DesignStudy::new(
            benchmark.clone(),
            x.clone(),
            Some(x.clone()),
            StudySettings::default(),
        ) {
            Err(Error::InvalidArgument { what: "axis", rule }) => {
                assert_eq!(rule, "x and y both vary `trail`")
            }
            other => panic!("{other:?}"),
        }
        let v = AxisSpec::parse("speed=1:10:3", &benchmark)?;
        let study = DesignStudy::new(benchmark, x, Some(v), StudySettings::default())?;
        assert_eq!(study.base_point(), (Some(0.08), None));
        Ok(())
    }

    /// The answers' layout of an axis is the one the command line and the server have always
    /// written.
    #[test]
    fn an_axis_serializes_as_typed() -> Result<()> {
        let axis = AxisSpec::parse("head_angle_deg=60:80:3", &bike("benchmark"))?;
        let json = serde_json_text(&axis);
        assert_eq!(
            json,
            r#"{"name":"head_angle_deg","parameter":{"kind":"benchmark","name":"head_angle"},"start":60.0,"stop":80.0,"count":3,"degrees":true,"unit":"deg"}"#
        );
        Ok(())
    }

    fn serde_json_text(axis: &AxisSpec) -> String {
        match serde_json::to_string(axis) {
            Ok(text) => text,
            Err(e) => panic!("{e}"),
        }
    }
}
