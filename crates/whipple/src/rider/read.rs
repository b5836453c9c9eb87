//! `yeadon`'s input files, as BicycleParameters keeps them (`<Rider>YeadonMeas.txt`,
//! `<Rider><Bike>YeadonCFG.txt`): one `name: value` a line (a YAML mapping of numbers), `#`
//! starting a comment. The measurements' file gives the 95 measurements in any unit with
//! `measurementconversionfactor` (to metres) and optionally `totalmass` (kg; zero or less, as
//! `yeadon` writes `-1`, for not measured); the
//! configuration's file the 21 angles in radians. Every key is checked: unknown, repeated and
//! missing keys are errors naming the key and its line.

use super::{
    CONFIGURATION_ANGLES, CONFIGURATION_FORMAT, MEASUREMENT_NAMES, MEASUREMENTS_FORMAT,
    YeadonConfiguration, YeadonMeasurements,
};
use crate::error::{Error, Result};
use crate::parameters::io::MAX_FILE_BYTES;

/// `yeadon`'s earlier names of the configuration's angles, with their current names.
const OLD_ANGLE_NAMES: [(&str, &str); 11] = [
    ("somersalt", "somersault"),
    ("CA1elevation", "CA1extension"),
    ("CB1elevation", "CB1extension"),
    ("CA1abduction", "CA1adduction"),
    ("A1A2flexion", "A1A2extension"),
    ("B1B2flexion", "B1B2extension"),
    ("TClateralSpinalFlexion", "TCsagittalSpinalFlexion"),
    ("PJ1flexion", "PJ1extension"),
    ("PK1flexion", "PK1extension"),
    ("PJ1abduction", "PJ1adduction"),
    ("PTfrontalFlexion", "PTbending"),
];

fn error(format: &'static str, line: usize, field: Option<&str>, message: String) -> Error {
    Error::Parse {
        format,
        field: field.map(str::to_string),
        line,
        column: if line > 0 { 1 } else { 0 },
        message,
    }
}

/// The file's `(line, key, value)` entries, comments and blank lines skipped.
fn entries(text: &str, format: &'static str) -> Result<Vec<(usize, String, f64)>> {
    if text.len() > MAX_FILE_BYTES {
        return Err(error(
            format,
            0,
            None,
            format!("the file is larger than {MAX_FILE_BYTES} bytes"),
        ));
    }
    let mut out = Vec::new();
    let mut seen = std::collections::HashMap::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let Some((key, value)) = content.split_once(':') else {
            return Err(error(
                format,
                line,
                None,
                format!("expected `name: value`, found `{content}`"),
            ));
        };
        let key = key.trim();
        let value = value.trim();
        let number = value.parse::<f64>().ok().filter(|v| v.is_finite());
        let Some(number) = number else {
            return Err(error(
                format,
                line,
                Some(key),
                format!("`{value}` is not a finite number"),
            ));
        };
        if let Some(first) = seen.insert(key.to_string(), line) {
            return Err(error(
                format,
                line,
                Some(key),
                format!("`{key}` is given twice (first on line {first})"),
            ));
        }
        out.push((line, key.to_string(), number));
    }
    Ok(out)
}

/// Reads a `*YeadonMeas.txt`: the 95 measurements converted to metres, the total mass if
/// given. Fails naming the key and its line for an unknown or repeated key, a value that is not
/// a positive number, a missing `measurementconversionfactor`, and naming the missing
/// measurements.
pub fn read_yeadon_measurements(text: &str) -> Result<YeadonMeasurements<f64>> {
    let f = MEASUREMENTS_FORMAT;
    let mut values = [f64::NAN; 95];
    let mut lines = [0usize; 95];
    let mut factor = None;
    let mut total_mass = None;
    for (line, key, value) in entries(text, f)? {
        match key.as_str() {
            "measurementconversionfactor" => {
                if value.is_nan() || value <= 0.0 {
                    return Err(error(
                        f,
                        line,
                        Some(&key),
                        format!(
                            "{value}: the factor converting the measurements to metres must be positive"
                        ),
                    ));
                }
                factor = Some(value);
            }
            // yeadon's convention: a total mass of zero or less (it writes -1) was not
            // measured, and the densities stay Dempster's.
            "totalmass" => total_mass = (value > 0.0).then_some(value),
            name => {
                let Some(i) = MEASUREMENT_NAMES.iter().position(|n| *n == name) else {
                    return Err(error(
                        f,
                        line,
                        Some(name),
                        format!("`{name}` is not one of Yeadon's 95 measurements"),
                    ));
                };
                if value.is_nan() || value <= 0.0 {
                    return Err(error(
                        f,
                        line,
                        Some(name),
                        format!("{value}: a measurement must be positive"),
                    ));
                }
                values[i] = value;
                lines[i] = line;
            }
        }
    }
    let missing: Vec<&str> = MEASUREMENT_NAMES
        .iter()
        .zip(lines)
        .filter(|(_, l)| *l == 0)
        .map(|(n, _)| *n)
        .collect();
    if !missing.is_empty() {
        return Err(error(
            f,
            0,
            missing.first().copied(),
            format!(
                "{} of the 95 measurements missing: {}",
                missing.len(),
                missing.join(", ")
            ),
        ));
    }
    let Some(factor) = factor else {
        return Err(error(
            f,
            0,
            Some("measurementconversionfactor"),
            "missing: the factor converting the measurements to metres (1 for metres, 0.01 for \
             centimetres)"
                .to_string(),
        ));
    };
    for v in &mut values {
        *v *= factor;
    }
    Ok(YeadonMeasurements {
        values,
        total_mass,
        lines,
    })
}

/// Reads a `*YeadonCFG.txt`: the 21 joint angles (rad), each within `yeadon`'s range. Fails
/// naming the key and its line for an unknown, old-named or repeated key and an angle out of
/// range, and naming the missing angles.
pub fn read_yeadon_configuration(text: &str) -> Result<YeadonConfiguration<f64>> {
    let f = CONFIGURATION_FORMAT;
    let mut angles = [0.0; 21];
    let mut lines = [0usize; 21];
    for (line, key, value) in entries(text, f)? {
        let Some(i) = CONFIGURATION_ANGLES.iter().position(|(n, _, _)| *n == key) else {
            let hint = OLD_ANGLE_NAMES
                .iter()
                .find(|(old, _)| *old == key)
                .map(|(_, new)| format!(" (an earlier name of `{new}`: rename it)"))
                .unwrap_or_default();
            return Err(error(
                f,
                line,
                Some(&key),
                format!("`{key}` is not one of the configuration's 21 angles{hint}"),
            ));
        };
        angles[i] = value;
        lines[i] = line;
    }
    let missing: Vec<&str> = CONFIGURATION_ANGLES
        .iter()
        .zip(lines)
        .filter(|(_, l)| *l == 0)
        .map(|((n, _, _), _)| *n)
        .collect();
    if !missing.is_empty() {
        return Err(error(
            f,
            0,
            missing.first().copied(),
            format!(
                "{} of the 21 angles missing: {}",
                missing.len(),
                missing.join(", ")
            ),
        ));
    }
    let configuration = YeadonConfiguration { angles, lines };
    configuration.check()?;
    Ok(configuration)
}
