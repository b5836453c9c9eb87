//! Units as people type and read them. Inside the library every quantity is SI and every angle
//! in radians; people type degrees, millimetres and km/h. One rule for every command and every
//! format:
//!
//! - **a name carries its unit as a suffix**: `_deg` after an angle (`lam_deg`,
//!   `head_angle_deg`), `_mm` after a length (`c_mm`, `trail_mm`, `wheelbase_mm`); a suffix
//!   after a name whose quantity does not fit is refused naming the name as written (`IBxx_mm`:
//!   "`IBxx` is not a length"). The suffixes and their conversions are the library's
//!   ([`TypedUnit`], the parameter table's one home of them, because the core's TOML and JSON
//!   readers take them too); which parameters are angles or lengths is the parameter table's
//!   ([`whipple::advanced::table`], `ParameterInfo::is_angle`, `is_length`);
//! - **a speed carries its unit after the value**: `18km/h`, `15:25km/h`, `10:30:0.5km/h`,
//!   `3,5,7km/h` (the suffix once, after the whole value, for every number of it); without it
//!   m/s ([`split_speed`], [`speed`]). Results print in m/s; a front end answers speeds typed
//!   in km/h in km/h too ([`SpeedUnit::from_si`]).
//!
//! This module converts and spells; the units themselves are the table's.

pub use whipple::advanced::table::{MILLIMETRES_PER_METRE, RADIANS_PER_DEGREE, TypedUnit};

/// The suffix of a name whose value is given in degrees (`lean_deg`, `head_angle_deg`).
pub const DEGREES_SUFFIX: &str = "_deg";

/// The suffix after a speed typed in kilometres per hour (`18km/h`).
pub const KMH_SUFFIX: &str = "km/h";

/// Kilometres per hour in one metre per second.
pub const KMH_PER_METRE_PER_SECOND: f64 = 3.6;

/// The unit a speed was typed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpeedUnit {
    /// Metres per second, SI: a speed without a suffix.
    MetresPerSecond,
    /// Kilometres per hour: `km/h` after the value (x / 3.6 m/s).
    KilometresPerHour,
}

impl SpeedUnit {
    /// The symbol: `m/s`, `km/h`.
    pub fn symbol(self) -> &'static str {
        match self {
            SpeedUnit::MetresPerSecond => "m/s",
            SpeedUnit::KilometresPerHour => KMH_SUFFIX,
        }
    }

    /// A speed typed in this unit, in m/s (one division for km/h).
    pub fn to_si(self, x: f64) -> f64 {
        match self {
            SpeedUnit::MetresPerSecond => x,
            SpeedUnit::KilometresPerHour => x / KMH_PER_METRE_PER_SECOND,
        }
    }

    /// A speed in m/s, in this unit.
    pub fn from_si(self, x: f64) -> f64 {
        match self {
            SpeedUnit::MetresPerSecond => x,
            SpeedUnit::KilometresPerHour => x * KMH_PER_METRE_PER_SECOND,
        }
    }
}

/// The unit a person typed a value in: the table's SI unit, a suffix's (`_deg`, `_mm`), or a
/// speed's (`km/h`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UserUnit {
    /// The parameter table's SI unit.
    Si,
    /// A name's suffix: degrees or millimetres.
    Typed(TypedUnit),
    /// A speed, in m/s or km/h.
    Speed(SpeedUnit),
}

impl UserUnit {
    /// A value typed in this unit, in SI units.
    pub fn to_si(self, x: f64) -> f64 {
        match self {
            UserUnit::Si => x,
            UserUnit::Typed(u) => u.to_si(x),
            UserUnit::Speed(u) => u.to_si(x),
        }
    }

    /// An SI value in this unit.
    pub fn from_si(self, x: f64) -> f64 {
        match self {
            UserUnit::Si => x,
            UserUnit::Typed(u) => u.from_si(x),
            UserUnit::Speed(u) => u.from_si(x),
        }
    }

    /// The unit for labels, given the parameter's SI unit in the table (`kg m^2` printed
    /// `kg m²`).
    pub fn label(self, si_unit: &'static str) -> &'static str {
        match self {
            UserUnit::Si => display(si_unit),
            UserUnit::Typed(u) => u.symbol(),
            UserUnit::Speed(u) => u.symbol(),
        }
    }
}

/// Parameters as a front end's mapping gives them (Python's `Bicycle.from_dict`): (key as
/// typed, value, σ) with the keys of `form`'s table, a suffixed key in SI under its table key
/// (`c_mm`, 80, 1 → `c`, 0.08, 0.001), and the units typed, for the writers
/// ([`whipple::Bicycle::units`]). Keys that are not the table's (BicycleParameters' optional
/// `yB`, `IBxy`, …, or unknown ones) pass unchanged, for the reader to judge. A suffix after a
/// key whose quantity does not fit, a value that is not finite in a suffixed key, and one key
/// given in two units are refused naming the keys as typed.
///
/// ```
/// use whipple::advanced::table::Form;
/// use whipple_front::units::{si_items, TypedUnit};
/// let (items, units) = si_items(&[("c_mm".into(), 80.0, 1.0), ("mB".into(), 85.0, 0.0)], Form::Benchmark)?;
/// assert_eq!(items, [("c".to_string(), 0.08, 0.001), ("mB".to_string(), 85.0, 0.0)]);
/// assert_eq!(units, [("c".to_string(), TypedUnit::Millimetres)]);
/// assert!(si_items(&[("IBxx_mm".into(), 1.0, 0.0)], Form::Benchmark).is_err());
/// # Ok::<(), whipple::Error>(())
/// ```
#[allow(clippy::type_complexity)]
pub fn si_items(
    items: &[(String, f64, f64)],
    form: whipple::advanced::table::Form,
) -> whipple::Result<(Vec<(String, f64, f64)>, Vec<(String, TypedUnit)>)> {
    let table = whipple::advanced::table::parameters(form);
    let mut out = Vec::with_capacity(items.len());
    let mut units = Vec::new();
    let mut seen: Vec<(usize, &str)> = Vec::new();
    for (name, value, sigma) in items {
        let refuse = |rule: String| whipple::Error::InvalidParameter {
            field: name.clone(),
            value: *value,
            rule,
        };
        let found = whipple::advanced::table::find_typed(form, name)
            .map_err(|rule| refuse(format!("`{name}`: {rule}")))?;
        let Some((i, typed)) = found else {
            out.push((name.clone(), *value, *sigma));
            continue;
        };
        if let Some((_, first)) = seen.iter().find(|(j, _)| *j == i) {
            return Err(refuse(format!(
                "`{first}` and `{name}` give the same parameter twice: keep one"
            )));
        }
        seen.push((i, name));
        let key = table[i].key.to_string();
        match typed {
            None => out.push((key, *value, *sigma)),
            Some(unit) => {
                if !value.is_finite() || !sigma.is_finite() {
                    return Err(refuse("must be a finite number".into()));
                }
                out.push((key.clone(), unit.to_si(*value), unit.to_si(*sigma)));
                units.push((key, unit));
            }
        }
    }
    Ok((out, units))
}

/// A speed argument as typed, split into the text of its numbers and its unit: `18km/h` →
/// (`18`, km/h), `10:30:0.5 km/h` → (`10:30:0.5`, km/h), `4.6` → (`4.6`, m/s). A `m/s` after the
/// value is taken too. Any other letters after the last number (`18kph`, `5mph`, `3_mm`) are
/// refused, naming the text as written: km/h is the one unit a speed takes besides m/s.
///
/// ```
/// use whipple_front::units::{split_speed, SpeedUnit};
/// assert_eq!(split_speed("15:25km/h")?, ("15:25", SpeedUnit::KilometresPerHour));
/// assert_eq!(split_speed("3,5,7")?, ("3,5,7", SpeedUnit::MetresPerSecond));
/// assert!(split_speed("18mph").is_err());
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn split_speed(text: &str) -> whipple::Result<(&str, SpeedUnit)> {
    let trimmed = text.trim_end();
    let (numbers, unit) = if let Some(n) = strip_suffix_ignore_case(trimmed, KMH_SUFFIX) {
        (n.trim_end(), SpeedUnit::KilometresPerHour)
    } else if let Some(n) = strip_suffix_ignore_case(trimmed, "m/s") {
        (n.trim_end(), SpeedUnit::MetresPerSecond)
    } else {
        (trimmed, SpeedUnit::MetresPerSecond)
    };
    let tail = numbers
        .rfind(|c: char| c.is_ascii_digit() || c == '.' || c == ':' || c == ',')
        .map_or(numbers, |p| &numbers[p + 1..]);
    let word = tail.trim().to_ascii_lowercase();
    let spelled = matches!(word.as_str(), "" | "inf" | "infinity" | "nan");
    if !spelled
        && tail
            .chars()
            .any(|c| c.is_alphabetic() || c == '/' || c == '_')
    {
        return Err(whipple::Error::InvalidArgument {
            what: "speed",
            rule: format!(
                "`{}`: `{}` is not a unit of speed (write m/s without a unit, or km/h after the \
                 value: 18km/h)",
                shorten(text),
                tail.trim()
            ),
        });
    }
    Ok((numbers, unit))
}

/// One speed as typed (`18km/h`, `4.6`), in m/s; a finite number, negative speeds allowed
/// (riding backwards), NaN and infinities refused naming the text.
///
/// ```
/// assert_eq!(whipple_front::units::speed("18km/h")?, 5.0);
/// assert_eq!(whipple_front::units::speed("4.6")?, 4.6);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn speed(text: &str) -> whipple::Result<f64> {
    Ok(typed_speed(text)?.0)
}

/// [`speed`], with the unit it was typed in (a front end answers in that unit too).
///
/// ```
/// use whipple_front::units::{typed_speed, SpeedUnit};
/// assert_eq!(typed_speed("18km/h")?, (5.0, SpeedUnit::KilometresPerHour));
/// assert_eq!(typed_speed("4.6")?, (4.6, SpeedUnit::MetresPerSecond));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn typed_speed(text: &str) -> whipple::Result<(f64, SpeedUnit)> {
    let (number, unit) = split_speed(text)?;
    let x = finite(number, text)?;
    Ok((unit.to_si(x), unit))
}

/// A number of a speed argument, finite: the error names the whole argument as written.
pub fn finite(number: &str, written: &str) -> whipple::Result<f64> {
    let refuse = |why: &str| whipple::Error::InvalidArgument {
        what: "speed",
        rule: format!("`{}`: `{}` {why}", shorten(written), shorten(number.trim())),
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(refuse("is not a finite number")),
        Err(_) => Err(refuse("is not a number")),
    }
}

fn strip_suffix_ignore_case<'a>(text: &'a str, suffix: &str) -> Option<&'a str> {
    let split = text.len().checked_sub(suffix.len())?;
    (text.is_char_boundary(split) && text[split..].eq_ignore_ascii_case(suffix))
        .then(|| &text[..split])
}

fn shorten(text: &str) -> String {
    if text.chars().count() <= 40 {
        text.to_string()
    } else {
        format!("{}…", text.chars().take(40).collect::<String>())
    }
}

/// An angle typed in degrees, in radians (`x · π/180`, bit for bit `f64::to_radians`).
///
/// ```
/// assert_eq!(whipple_front::units::radians(180.0), std::f64::consts::PI);
/// ```
pub fn radians(degrees: f64) -> f64 {
    TypedUnit::Degrees.to_si(degrees)
}

/// An angle in radians, in degrees for people (bit for bit `f64::to_degrees`).
pub fn degrees(radians: f64) -> f64 {
    TypedUnit::Degrees.from_si(radians)
}

/// A length typed in millimetres, in metres (one division: `80` mm is the f64 `0.08`).
pub fn metres(millimetres: f64) -> f64 {
    TypedUnit::Millimetres.to_si(millimetres)
}

/// A length in metres, in millimetres for people.
pub fn millimetres(metres: f64) -> f64 {
    TypedUnit::Millimetres.from_si(metres)
}

/// A name without its unit's suffix (`_deg`, `_mm`), and the unit it names.
///
/// ```
/// use whipple_front::units::{strip_unit, TypedUnit};
/// assert_eq!(strip_unit("trail_mm"), ("trail", Some(TypedUnit::Millimetres)));
/// assert_eq!(strip_unit("mB"), ("mB", None));
/// ```
pub fn strip_unit(name: &str) -> (&str, Option<TypedUnit>) {
    TypedUnit::strip(name)
}

/// A name without its `_deg` suffix, and whether it had one.
///
/// ```
/// use whipple_front::units::strip_degrees;
/// assert_eq!(strip_degrees("head_angle_deg"), ("head_angle", true));
/// assert_eq!(strip_degrees("trail"), ("trail", false));
/// ```
pub fn strip_degrees(name: &str) -> (&str, bool) {
    match name.strip_suffix(DEGREES_SUFFIX) {
        Some(stem) => (stem, true),
        None => (name, false),
    }
}

/// A unit of the parameter table as printed in labels and answers: powers as superscripts
/// (`kg m^2` → `kg m²`, `m/s^2` → `m/s²`); every other unit as it is.
pub fn display(unit: &'static str) -> &'static str {
    match unit {
        "kg m^2" => "kg m²",
        "m/s^2" => "m/s²",
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The conversion is the standard library's, bit for bit, both ways.
    #[test]
    fn degrees_convert_as_the_standard_library_does() {
        for x in [
            0.0, -0.0, 1.0, 45.0, 60.0, 90.0, -73.25, 1e-300, 1e300, 123.456,
        ] {
            assert_eq!(radians(x).to_bits(), x.to_radians().to_bits(), "{x}");
            assert_eq!(degrees(x).to_bits(), x.to_degrees().to_bits(), "{x}");
        }
        assert_eq!(radians(90.0), std::f64::consts::FRAC_PI_2);
        assert_eq!(
            radians(60.0),
            whipple::advanced::nonlinear::DEFAULT_FALL_ANGLE
        );
        assert!(radians(f64::NAN).is_nan());
    }

    /// mm by one division, km/h by one division, both exact for the values people type.
    #[test]
    fn millimetres_and_kilometres_per_hour_convert_by_one_division() {
        for x in [0.0, 80.0, 1020.0, 0.5, -73.25, 1e-300, 1e300, 123.456] {
            assert_eq!(metres(x).to_bits(), (x / 1000.0).to_bits(), "{x}");
            assert_eq!(
                SpeedUnit::KilometresPerHour.to_si(x).to_bits(),
                (x / 3.6).to_bits()
            );
        }
        assert_eq!(
            (metres(80.0), metres(1020.0), metres(0.5)),
            (0.08, 1.02, 0.0005)
        );
        assert_eq!((millimetres(0.08), millimetres(1.02)), (80.0, 1020.0));
        assert_eq!(speed("18km/h").unwrap(), 5.0);
        assert_eq!(speed("18 KM/H").unwrap(), 5.0);
        assert_eq!(speed(" 4.6 ").unwrap(), 4.6);
        assert_eq!(speed("4.6m/s").unwrap(), 4.6);
        assert_eq!(speed("-18km/h").unwrap(), -5.0);
    }

    /// For random finite values, every angle and length key of the benchmark table typed with
    /// its suffix gives the SI value bit for bit after the one conversion.
    #[test]
    fn suffixed_items_are_si_after_one_conversion() {
        use proptest::prelude::*;
        use whipple::advanced::table::{Form, parameters};
        proptest!(|(x in proptest::num::f64::NORMAL | proptest::num::f64::ZERO, s in 0.0f64..1e6)| {
            for p in parameters(Form::Benchmark) {
                for unit in TypedUnit::ALL.into_iter().filter(|u| u.fits(p.unit)) {
                    let typed = format!("{}{}", p.key, unit.suffix());
                    let (items, units) = si_items(&[(typed, x, s)], Form::Benchmark).unwrap();
                    prop_assert_eq!(&items[0].0, p.key);
                    prop_assert_eq!(items[0].1.to_bits(), unit.to_si(x).to_bits());
                    prop_assert_eq!(items[0].2.to_bits(), unit.to_si(s).to_bits());
                    prop_assert_eq!(&units, &vec![(p.key.to_string(), unit)]);
                }
            }
        });
    }

    #[test]
    fn bad_items_are_refused_naming_the_keys_as_typed() {
        use whipple::advanced::table::Form;
        for (items, words) in [
            (vec![("IBxx_mm", 1.0)], "`IBxx_mm`: `IBxx` is not a length"),
            (vec![("lam_mm", 1.0)], "`lam_mm`: `lam` is not a length"),
            (vec![("c_deg", 1.0)], "`c_deg`: `c` is not an angle"),
            (
                vec![("c", 0.08), ("c_mm", 80.0)],
                "`c` and `c_mm` give the same parameter",
            ),
            (vec![("c_mm", f64::NAN)], "must be a finite number"),
            (vec![("lam_deg", f64::INFINITY)], "must be a finite number"),
        ] {
            let items: Vec<(String, f64, f64)> = items
                .iter()
                .map(|(k, v)| (k.to_string(), *v, 0.0))
                .collect();
            let err = si_items(&items, Form::Benchmark).unwrap_err().to_string();
            assert!(err.contains(words), "{items:?}: {err}");
        }
    }

    #[test]
    fn speeds_split_once_for_every_number() {
        use SpeedUnit::*;
        for (text, numbers, unit) in [
            ("10:30:0.5km/h", "10:30:0.5", KilometresPerHour),
            ("15:25 km/h", "15:25", KilometresPerHour),
            ("3,5,7km/h", "3,5,7", KilometresPerHour),
            ("4:inf", "4:inf", MetresPerSecond),
            ("4:km/h", "4:", KilometresPerHour),
            ("0:10", "0:10", MetresPerSecond),
        ] {
            assert_eq!(split_speed(text).unwrap(), (numbers, unit), "{text}");
        }
    }

    /// A unit that is not a speed's, or a number that is not finite, is refused naming the
    /// argument as written.
    #[test]
    fn bad_speeds_are_refused_naming_the_text() {
        for (text, words) in [
            ("18kph", "`18kph`: `kph` is not a unit of speed"),
            ("5mph", "`5mph`: `mph` is not a unit of speed"),
            ("80_mm", "`80_mm`: `_mm` is not a unit of speed"),
            ("10:30:1mm", "`10:30:1mm`: `mm` is not a unit of speed"),
            ("nan", "`nan`: `nan` is not a finite number"),
            ("NaNkm/h", "`NaNkm/h`: `NaN` is not a finite number"),
            ("infkm/h", "`infkm/h`: `inf` is not a finite number"),
            ("km/h", "`km/h`: `` is not a number"),
            ("fast", "`fast`: `fast` is not a unit of speed"),
            ("18 km/h/h", "is not a unit of speed"),
        ] {
            let err = speed(text).unwrap_err().to_string();
            assert!(err.contains(words), "{text}: {err}");
        }
    }

    #[test]
    fn units_print_with_superscripts() {
        assert_eq!(display("kg m^2"), "kg m²");
        assert_eq!(display("m/s^2"), "m/s²");
        assert_eq!(display("m"), "m");
        assert_eq!(display("rad"), "rad");
    }
}
