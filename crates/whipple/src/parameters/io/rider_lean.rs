//! BicycleParameters' `MooreRiderLean2012` parameter set as the user has it: a JSON object of
//! its 36 keys (`json.dump(parameter_set.parameters, f)`), `v` accepted and ignored.

use super::json_without_duplicates;
use crate::error::{Error, Result};
use crate::parameters::{MooreRiderLean2012Parameters, RiderLeanParameters};

const FORMAT: &str = "JSON";

/// Reads a JSON object of BicycleParameters' `MooreRiderLean2012` keys (every one of the 36 once,
/// numbers; `v` ignored) and converts it to the library's leaning-rider parameters, checked.
/// Errors name the key (unknown, missing, twice, not a number) or the line and column of a
/// syntax error.
///
/// ```
/// use whipple::advanced::io::read_moore_rider_lean2012;
/// use whipple::advanced::parameters::{MOORE_RIDER_LEAN2012_KEYS, MooreRiderLean2012Parameters};
/// let values = MooreRiderLean2012Parameters::browser_jason().to_array();
/// let pairs: Vec<String> = MOORE_RIDER_LEAN2012_KEYS.iter().zip(values)
///     .map(|(k, v)| format!("\"{k}\": {v:?}")).collect();
/// let p = read_moore_rider_lean2012(&format!("{{{}}}", pairs.join(", ")))?;
/// assert_eq!(p, whipple::advanced::parameters::RiderLeanParameters::browser_jason());
/// assert!(read_moore_rider_lean2012("{\"d1\": 1}").unwrap_err().to_string().contains("missing"));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn read_moore_rider_lean2012(text: &str) -> Result<RiderLeanParameters> {
    let value =
        json_without_duplicates(text.trim_start_matches('\u{feff}')).map_err(|e| Error::Parse {
            format: FORMAT,
            field: None,
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
    let Some(object) = value.as_object() else {
        return Err(Error::Parse {
            format: FORMAT,
            field: None,
            line: 0,
            column: 0,
            message: "expects an object of MooreRiderLean2012 keys and numbers".into(),
        });
    };
    let mut pairs = Vec::with_capacity(object.len());
    for (key, value) in object {
        let Some(x) = value.as_f64() else {
            return Err(Error::Parse {
                format: FORMAT,
                field: Some(key.clone()),
                line: 0,
                column: 0,
                message: format!("`{key}` must be a number, got {value}"),
            });
        };
        pairs.push((key.clone(), x));
    }
    MooreRiderLean2012Parameters::from_pairs(&pairs, FORMAT)?.to_rider_lean()
}
