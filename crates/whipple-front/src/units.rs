//! Units as people type and read them. Inside the library every quantity is SI and every angle
//! in radians; a front end takes an angle in degrees where its name says so (`_deg`) and prints
//! a unit as people write it (`kg m²`). What unit a parameter has, and whether it is an angle,
//! is the library's parameter table's ([`whipple::advanced::table`],
//! [`whipple::advanced::design::Parameter::is_angle`]); this module only converts and spells.

/// The suffix of a name whose value is given in degrees (`lean_deg`, `head_angle_deg`).
pub const DEGREES_SUFFIX: &str = "_deg";

/// Radians per degree: what one unit of an angle typed in degrees is in SI units.
pub const RADIANS_PER_DEGREE: f64 = std::f64::consts::PI / 180.0;

/// An angle typed in degrees, in radians (`x · π/180`, bit for bit `f64::to_radians`).
///
/// ```
/// assert_eq!(whipple_front::units::radians(180.0), std::f64::consts::PI);
/// ```
pub fn radians(degrees: f64) -> f64 {
    degrees * RADIANS_PER_DEGREE
}

/// An angle in radians, in degrees for people (bit for bit `f64::to_degrees`).
pub fn degrees(radians: f64) -> f64 {
    radians.to_degrees()
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

    #[test]
    fn units_print_with_superscripts() {
        assert_eq!(display("kg m^2"), "kg m²");
        assert_eq!(display("m/s^2"), "m/s²");
        assert_eq!(display("m"), "m");
        assert_eq!(display("rad"), "rad");
    }
}
