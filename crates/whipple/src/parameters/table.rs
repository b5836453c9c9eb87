//! The one table of every parameter: name, file key, symbol, unit, description and form. The
//! serde names and `fields()` of [`BenchmarkParameters`](super::BenchmarkParameters) and
//! [`Jbike6Parameters`](super::Jbike6Parameters), the comments of the TOML writer, the `.m`
//! variables, the CLI's `show` and the web API's `GET /api/parameters` are all read from here.

use serde::Serialize;

/// Which description of a bicycle a parameter belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Form {
    /// The 25 benchmark parameters of Meijaard et al. 2007 (Table 1) plus g.
    Benchmark,
    /// JBike6's seven-body description (wheels, rider, frame, rack, fork, basket).
    Jbike6,
}

/// One parameter of a bicycle description.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct ParameterInfo {
    /// The Rust field (`i_bxx`; for JBike6 the path of fields, `rider.inertia[0]`).
    pub name: &'static str,
    /// The key in files and messages: the benchmark keys of Meijaard 2007 and BicycleParameters
    /// (`IBxx`), JBike6's `.m` variables (`mrider`, `Irider(1)`).
    pub key: &'static str,
    /// The path inside the form's TOML/JSON table (`IBxx`; `rider.m`, `rider.I[1]`).
    pub path: &'static str,
    /// The paper's symbol (`I_Bxx`, `λ`).
    pub symbol: &'static str,
    /// SI unit (`kg m^2`, `rad`; empty for none).
    pub unit: &'static str,
    /// What it is, in a few words.
    pub description: &'static str,
    /// The description it belongs to.
    pub form: Form,
    /// Whether the linearized model (M, C₁, K₀, K₂) depends on it (I_Byy and I_Hyy it does
    /// not: they enter only the non-linear model).
    pub linear: bool,
}

/// The unit of every angle in the table (and of every angle inside the library).
pub(crate) const ANGLE_UNIT: &str = "rad";

/// The unit of every length in the table.
pub(crate) const LENGTH_UNIT: &str = "m";

/// A unit people type a parameter in, named by a suffix after its key (`lam_deg = 18`,
/// `c_mm = 80`): degrees after an angle, millimetres after a length. The library computes in SI
/// only; this is the one home of these two conversions, used by the TOML and JSON readers and
/// writers here and re-exported by whipple-front for every other name a person types
/// (design axes, `replace`, Python's `Bicycle.from_dict`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TypedUnit {
    /// Degrees, after an angle (`_deg`): x · π/180 radians, bit for bit `f64::to_radians`.
    Degrees,
    /// Millimetres, after a length (`_mm`): x / 1000 metres (one correctly rounded division,
    /// so `80` mm is the same f64 as `0.08` m typed).
    Millimetres,
}

/// Radians per degree: what one unit of an angle typed in degrees is in SI units.
pub const RADIANS_PER_DEGREE: f64 = std::f64::consts::PI / 180.0;

/// Millimetres per metre.
pub const MILLIMETRES_PER_METRE: f64 = 1000.0;

impl TypedUnit {
    /// Both units, in the order suffixes are tried.
    pub const ALL: [TypedUnit; 2] = [TypedUnit::Degrees, TypedUnit::Millimetres];

    /// The suffix naming it after a key: `_deg`, `_mm`.
    pub fn suffix(self) -> &'static str {
        match self {
            TypedUnit::Degrees => "_deg",
            TypedUnit::Millimetres => "_mm",
        }
    }

    /// Its symbol for labels: `deg`, `mm`.
    pub fn symbol(self) -> &'static str {
        match self {
            TypedUnit::Degrees => "deg",
            TypedUnit::Millimetres => "mm",
        }
    }

    /// The quantity it measures, for messages: `an angle`, `a length`.
    pub fn quantity(self) -> &'static str {
        match self {
            TypedUnit::Degrees => "an angle",
            TypedUnit::Millimetres => "a length",
        }
    }

    /// The SI unit of the table it converts to: `rad`, `m`.
    pub fn si_unit(self) -> &'static str {
        match self {
            TypedUnit::Degrees => ANGLE_UNIT,
            TypedUnit::Millimetres => LENGTH_UNIT,
        }
    }

    /// A value typed in this unit, in SI units.
    ///
    /// ```
    /// use whipple::advanced::table::TypedUnit;
    /// assert_eq!(TypedUnit::Millimetres.to_si(80.0), 0.08);
    /// assert_eq!(TypedUnit::Degrees.to_si(180.0), std::f64::consts::PI);
    /// ```
    pub fn to_si(self, x: f64) -> f64 {
        match self {
            TypedUnit::Degrees => x * RADIANS_PER_DEGREE,
            TypedUnit::Millimetres => x / MILLIMETRES_PER_METRE,
        }
    }

    /// An SI value in this unit (`f64::to_degrees`; metres · 1000).
    pub fn from_si(self, x: f64) -> f64 {
        match self {
            TypedUnit::Degrees => x.to_degrees(),
            TypedUnit::Millimetres => x * MILLIMETRES_PER_METRE,
        }
    }

    /// A name without its unit's suffix, and the unit it names (`c_mm` → `c`, millimetres;
    /// `lam_deg` → `lam`, degrees; `c` → `c`, none).
    ///
    /// ```
    /// use whipple::advanced::table::TypedUnit;
    /// assert_eq!(TypedUnit::strip("c_mm"), ("c", Some(TypedUnit::Millimetres)));
    /// assert_eq!(TypedUnit::strip("head_angle_deg"), ("head_angle", Some(TypedUnit::Degrees)));
    /// assert_eq!(TypedUnit::strip("IBxx"), ("IBxx", None));
    /// ```
    pub fn strip(name: &str) -> (&str, Option<TypedUnit>) {
        TypedUnit::ALL
            .iter()
            .find_map(|u| name.strip_suffix(u.suffix()).map(|stem| (stem, Some(*u))))
            .unwrap_or((name, None))
    }

    /// Whether a quantity of this SI unit (`rad`, `m`, `kg m^2`) may be typed in this unit.
    pub fn fits(self, si_unit: &str) -> bool {
        si_unit == self.si_unit()
    }

    /// The rule broken by this suffix after a name whose quantity does not fit, naming the
    /// name without it: "`IBxx` is not a length".
    pub fn misfit(self, stem: &str) -> String {
        let what = match self {
            TypedUnit::Degrees => "an angle",
            TypedUnit::Millimetres => "a length",
        };
        format!("`{stem}` is not {what}")
    }
}

impl ParameterInfo {
    /// Whether the parameter is an angle (its unit is `"rad"`): the one a front end may
    /// take in degrees.
    pub fn is_angle(&self) -> bool {
        self.unit == ANGLE_UNIT
    }

    /// Whether the parameter is a length (its unit is `"m"`): the one a front end may take in
    /// millimetres.
    pub fn is_length(&self) -> bool {
        self.unit == LENGTH_UNIT
    }

    /// `description [unit]`, as the TOML writer's comments and tables print it.
    pub fn doc(&self) -> String {
        if self.unit.is_empty() {
            self.description.to_string()
        } else {
            format!("{} [{}]", self.description, self.unit)
        }
    }
}

/// The parameter of a form's table a file key names, with the unit a suffix gives it:
/// `c_mm` → (`c`, millimetres), `lam_deg` → (`lam`, degrees), `c` → (`c`, none). `Ok(None)` for
/// a name that is no key of the form, with or without a suffix; an error, the rule broken, for a
/// suffix after a key whose quantity does not fit (`IBxx_mm`: "`IBxx` is not a length").
/// Keys are a form's file keys (`lam`, `mrider`) or, for JBike6, its TOML paths
/// (`head_angle`, `rider.m`).
pub fn find_typed(
    form: Form,
    name: &str,
) -> std::result::Result<Option<(usize, Option<TypedUnit>)>, String> {
    let matches = |p: &ParameterInfo, key: &str| p.key == key || p.path == key;
    if let Some(i) = parameters(form).iter().position(|p| matches(p, name)) {
        return Ok(Some((i, None)));
    }
    let (stem, Some(unit)) = TypedUnit::strip(name) else {
        return Ok(None);
    };
    match parameters(form).iter().position(|p| matches(p, stem)) {
        Some(i) if unit.fits(parameters(form)[i].unit) => Ok(Some((i, Some(unit)))),
        Some(_) => Err(unit.misfit(stem)),
        None => Ok(None),
    }
}

/// The parameters of a form, in file order (Meijaard 2007 Table 1 for the benchmark form; the
/// original study's listing for JBike6).
pub fn parameters(form: Form) -> &'static [ParameterInfo] {
    match form {
        Form::Benchmark => &super::benchmark::BENCHMARK_TABLE,
        Form::Jbike6 => &super::jbike6::JBIKE6_TABLE,
    }
}

/// The parameter with this file key in either form (`IBxx`, `mrider`, `Irider(1)`), or with this
/// TOML path in the JBike6 form (`rider.m`).
pub(crate) fn find(key: &str) -> Option<&'static ParameterInfo> {
    parameters(Form::Benchmark)
        .iter()
        .chain(parameters(Form::Jbike6))
        .find(|p| p.key == key || (p.form == Form::Jbike6 && p.path == key))
}

/// The position of a key in its form's table.
pub fn index_of(form: Form, key: &str) -> Option<usize> {
    parameters(form).iter().position(|p| p.key == key)
}

/// Meaning and unit of a benchmark or JBike6 key (`"wheelbase [m]"`), for comments and tables;
/// `None` for a key that is neither.
pub fn key_doc(key: &str) -> Option<String> {
    find(key).map(ParameterInfo::doc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lengths and angles are the table's: every entry in metres is a length, every one in
    /// radians an angle, and the suffixes go exactly there.
    #[test]
    fn lengths_and_angles_come_from_the_units_listed() {
        for form in [Form::Benchmark, Form::Jbike6] {
            for p in parameters(form) {
                assert_eq!(p.is_length(), p.unit == "m", "{}", p.key);
                assert_eq!(p.is_angle(), p.unit == "rad", "{}", p.key);
                for unit in TypedUnit::ALL {
                    let typed = format!("{}{}", p.key, unit.suffix());
                    let found = find_typed(form, &typed);
                    if unit.fits(p.unit) {
                        assert!(
                            matches!(found, Ok(Some((_, Some(u)))) if u == unit),
                            "{typed}"
                        );
                    } else {
                        assert_eq!(found, Err(unit.misfit(p.key)), "{typed}");
                    }
                }
            }
        }
        let lengths: Vec<&str> = parameters(Form::Benchmark)
            .iter()
            .filter(|p| p.is_length())
            .map(|p| p.key)
            .collect();
        assert_eq!(lengths, ["w", "c", "rR", "xB", "zB", "xH", "zH", "rF"]);
        assert_eq!(
            find_typed(Form::Benchmark, "IBxx_mm"),
            Err("`IBxx` is not a length".into())
        );
        assert_eq!(find_typed(Form::Benchmark, "nothing_mm"), Ok(None));
        assert_eq!(
            find_typed(Form::Jbike6, "rider.m_mm"),
            Err("`rider.m` is not a length".into())
        );
    }

    /// Typed values convert by one operation: mm by one division, degrees as the standard
    /// library does.
    #[test]
    fn typed_units_convert_by_one_operation() {
        for x in [0.0, 80.0, 1020.0, 0.5, -73.25, 1e-300, 1e300, 123.456] {
            assert_eq!(
                TypedUnit::Millimetres.to_si(x).to_bits(),
                (x / 1000.0).to_bits()
            );
            assert_eq!(
                TypedUnit::Degrees.to_si(x).to_bits(),
                x.to_radians().to_bits()
            );
            assert_eq!(
                TypedUnit::Degrees.from_si(x).to_bits(),
                x.to_degrees().to_bits()
            );
        }
        assert_eq!(TypedUnit::Millimetres.to_si(80.0), 0.08);
        assert_eq!(TypedUnit::Millimetres.to_si(1020.0), 1.02);
    }
}
