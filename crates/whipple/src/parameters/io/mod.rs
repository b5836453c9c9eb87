//! Parameter files, read from and written to strings (the library never touches the file
//! system): TOML (the hand-edited format), JSON, JBike6's MATLAB assignments (`.m`), and the
//! field's own formats: BicycleParameters' `<Name>Benchmark.txt` (`key = value+/-sigma`) and
//! YAML parameter sets, and HumanControl's `<Name>Par.txt` (`key=value` with simple
//! expressions such as `lam=pi/10`).
//!
//! TOML and JSON share one layout: optional `name` and `source` strings, exactly one of a
//! `benchmark` table (keys `w`, `c`, `lam`, `g`, `rR`, `mR`, `IRxx`, … as in Meijaard 2007) or a
//! `jbike6` table (`wheelbase`, `head_angle`, `trail`, optional `gravity`, and the tables
//! `rear_wheel`, `front_wheel`, `rider`, `frame`, `rack`, `fork`, `basket`), and an optional
//! `extra` table of keys other models use. A value is a number or `{ value = 9.2, sigma = 0.1 }`
//! (a standard deviation). A key may carry its unit as a suffix, `_mm` after a length and `_deg`
//! after an angle (`c_mm = 80`, `lam_deg = 18`, σ in the same unit; [`TypedUnit`](crate::advanced::table::TypedUnit)):
//! the value is read in SI, the unit kept in `Bicycle::units` and written back by the TOML and
//! JSON writers. Unknown and missing keys are errors; every error names the key, and
//! the line and column where known. Files come as their owners wrote them: a UTF-8 byte-order
//! mark, CRLF line endings and a missing final newline are all accepted.

mod gains;
pub use gains::read_gains;
mod json;
mod keyvalue;
pub(crate) use keyvalue::extra_meaning;
mod matlab;
mod rider_lean;
pub use rider_lean::read_moore_rider_lean2012;
mod tree;
mod write;
pub use write::{moore2012_yaml, principal_yaml};
mod yaml;

pub use json::{json_slice_without_duplicates, json_without_duplicates};

use super::Bicycle;
use crate::error::{Error, Result, shorten};

/// A file format for bicycle descriptions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// TOML, the primary hand-edited format.
    Toml,
    /// JSON, the same layout as TOML.
    Json,
    /// JBike6's MATLAB assignments (`wheelbase = 1.016;`), JBike6 form only.
    Jbike6M,
    /// BicycleParameters' `<Name>Benchmark.txt`: `key = value+/-sigma` lines.
    BicycleParametersTxt,
    /// HumanControl's `<Name>Par.txt`: `key=value` lines with simple expressions.
    HumanControlTxt,
    /// BicycleParameters' YAML parameter sets (`parameterization: benchmark`, `values:`).
    Yaml,
}

/// Every format with its `--format` name and a line on what it is.
pub const FORMATS: [(Format, &str, &str); 6] = [
    (
        Format::Toml,
        "toml",
        "TOML, whipple's hand-edited layout (.toml)",
    ),
    (Format::Json, "json", "JSON, the same layout (.json)"),
    (Format::Jbike6M, "m", "JBike6's MATLAB assignments (.m)"),
    (
        Format::BicycleParametersTxt,
        "bp-txt",
        "BicycleParameters' <Name>Benchmark.txt, `key = value+/-sigma` (.txt)",
    ),
    (
        Format::HumanControlTxt,
        "hc-txt",
        "HumanControl's <Name>Par.txt, `key=value` with expressions such as pi/10 (.txt)",
    ),
    (
        Format::Yaml,
        "yaml",
        "BicycleParameters' YAML parameter sets (.yml, .yaml)",
    ),
];

impl Format {
    /// The file name extensions of the format, without the dot (`toml`; `yml` and `yaml`; `txt`
    /// for both text formats of the field, which the content tells apart).
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Format::Toml => &["toml"],
            Format::Json => &["json"],
            Format::Jbike6M => &["m"],
            Format::BicycleParametersTxt | Format::HumanControlTxt => &["txt"],
            Format::Yaml => &["yml", "yaml"],
        }
    }

    /// The format that a file name's extension names (`.toml`, `.json`, `.m`, `.yml`, `.yaml`),
    /// if any: an extension of one format only ([`Format::extensions`]); `.txt` needs the
    /// content too (see [`Format::detect`]).
    pub fn from_extension(extension: &str) -> Option<Format> {
        let mut named = FORMATS.iter().map(|(f, _, _)| *f).filter(|f| {
            f.extensions()
                .iter()
                .any(|e| e.eq_ignore_ascii_case(extension))
        });
        match (named.next(), named.next()) {
            (Some(format), None) => Some(format),
            _ => None,
        }
    }

    /// The format of a `--format` name (`toml`, `json`, `m`, `bp-txt`, `hc-txt`, `yaml`).
    pub fn from_name(name: &str) -> Option<Format> {
        FORMATS
            .iter()
            .find(|(_, n, _)| n.eq_ignore_ascii_case(name))
            .map(|(f, _, _)| *f)
    }

    /// The `--format` name.
    pub fn name(self) -> &'static str {
        FORMATS
            .iter()
            .find(|(f, _, _)| *f == self)
            .map_or("toml", |(_, n, _)| n)
    }

    /// How messages name the format.
    pub fn label(self) -> &'static str {
        match self {
            Format::Toml => "TOML",
            Format::Json => "JSON",
            Format::Jbike6M => "JBike6 .m",
            Format::BicycleParametersTxt => "BicycleParameters .txt",
            Format::HumanControlTxt => "HumanControl .txt",
            Format::Yaml => "YAML",
        }
    }

    /// The format of a file from its name and, where the extension does not settle it (`.txt`,
    /// no extension), its content. A file that fits no format, or several that read it
    /// differently, gets an error listing the formats and how to choose one (`--format`).
    ///
    /// ```
    /// use whipple::advanced::io::Format;
    /// assert_eq!(Format::detect("BrowserPar.txt", "w=1.121\n")?, Format::HumanControlTxt);
    /// assert_eq!(Format::detect("FisherBenchmark.txt", "w = 1.07+/-0.002\n")?,
    ///            Format::BicycleParametersTxt);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn detect(file_name: &str, text: &str) -> Result<Format> {
        let extension = file_name.rsplit_once('.').map(|(_, e)| e).unwrap_or("");
        if let Some(format) = Format::from_extension(extension) {
            return Ok(format);
        }
        let lower = file_name.to_ascii_lowercase();
        let text = strip_bom(text);
        let lines: Vec<&str> = text
            .lines()
            .map(|l| l.trim())
            .filter(|l| !l.is_empty() && !l.starts_with('#') && !l.starts_with('%'))
            .collect();
        let ambiguous = |why: &str| {
            let list = FORMATS
                .iter()
                .map(|(_, n, d)| format!("`{n}`: {d}"))
                .collect::<Vec<_>>()
                .join("; ");
            Err(Error::Parse {
                format: UNDETERMINED_FORMAT,
                field: None,
                line: 0,
                column: 0,
                message: format!(
                    "cannot tell the format of {}: {why}. The formats are {list}. Name one or \
                     give the file its extension",
                    shorten(file_name, 80)
                ),
            })
        };
        let Some(first) = lines.first() else {
            return ambiguous("it holds no parameters");
        };
        if first.starts_with('{') {
            return Ok(Format::Json);
        }
        if lines.iter().any(|l| l.starts_with('[')) && !lines.iter().any(|l| l.ends_with(';')) {
            return Ok(Format::Toml);
        }
        let colon = lines
            .iter()
            .filter(|l| {
                matches!((l.find(':'), l.find('=')), (Some(c), None) | (Some(c), Some(_)) if l.find('=').is_none_or(|e| c < e))
            })
            .count();
        let assignment = lines
            .iter()
            .filter(|l| l.contains('=') || l.contains(','))
            .count();
        if colon > 0 && assignment == 0 {
            return Ok(Format::Yaml);
        }
        if colon > 0 {
            return ambiguous("it mixes `key: value` (YAML) and `key = value` lines");
        }
        if lines.iter().any(|l| l.ends_with(';')) {
            return Ok(Format::Jbike6M);
        }
        if lower.ends_with("par.txt") {
            return Ok(Format::HumanControlTxt);
        }
        if lower.ends_with("benchmark.txt") || lower.ends_with("measured.txt") {
            return Ok(Format::BicycleParametersTxt);
        }
        if assignment == 0 {
            return ambiguous("its lines are neither `key = value` nor `key: value`");
        }
        let hc = lines.iter().any(|l| {
            let (key, value) = l
                .split_once('=')
                .or_else(|| l.split_once(','))
                .unwrap_or((l, ""));
            matches!(key.trim(), "d1" | "d3")
                || (!value.contains("+/-")
                    && !value.contains('±')
                    && value.trim().parse::<f64>().is_err()
                    && !value.contains(','))
                || !l.contains('=')
        });
        if hc {
            return Ok(Format::HumanControlTxt);
        }
        Ok(Format::BicycleParametersTxt)
    }
}

/// The suffixes that name a parameter set in a file's name rather than the bicycle, by format:
/// BicycleParameters' `<Name>Benchmark.txt` (its `Parameters/` directory) and
/// `<Name>Measured.txt` (its `RawData/`), HumanControl's `<Name>Par.txt`.
fn name_suffixes(format: Format) -> &'static [&'static str] {
    match format {
        Format::BicycleParametersTxt => &["Benchmark", "Measured"],
        Format::HumanControlTxt => &["Par"],
        Format::Toml | Format::Json | Format::Jbike6M | Format::Yaml => &[],
    }
}

/// The name a bicycle read from a file without a `name` of its own takes from the file's name:
/// the last path component without its extension, and without the parameter set's suffix that
/// the format's files carry (`BrowserBenchmark.txt` is `Browser`, as BicycleParameters calls
/// it; `BrowserPar.txt` is `Browser`; `Benchmark.txt` stays `Benchmark`). `None` for an empty
/// name. The one place a file's name becomes a bicycle's (the CLI, the server and Python).
///
/// ```
/// use whipple::advanced::io::{Format, name_from_file_name};
/// let bp = Format::BicycleParametersTxt;
/// assert_eq!(name_from_file_name("data/BrowserBenchmark.txt", bp).as_deref(), Some("Browser"));
/// assert_eq!(name_from_file_name("BenchmarkBenchmark.txt", bp).as_deref(), Some("Benchmark"));
/// assert_eq!(name_from_file_name("my-Benchmark.toml", Format::Toml).as_deref(), Some("my-Benchmark"));
/// assert_eq!(name_from_file_name("", Format::Toml), None);
/// ```
pub fn name_from_file_name(file_name: &str, format: Format) -> Option<String> {
    let last = file_name.rsplit(['/', '\\']).next().unwrap_or(file_name);
    let stem = match last.rsplit_once('.') {
        Some((stem, _)) if !stem.is_empty() => stem,
        _ => last,
    };
    let name = name_suffixes(format)
        .iter()
        .find_map(|suffix| stem.strip_suffix(suffix).filter(|s| !s.is_empty()))
        .unwrap_or(stem);
    (!name.is_empty()).then(|| name.to_string())
}

/// The [`Error::Parse`] `format` of a file whose format could not be told (from its extension
/// or its text): the front ends name their own way to give it.
pub const UNDETERMINED_FORMAT: &str = "parameter";

/// The largest parameter file read, in bytes (4 MiB): the field's files are a few kilobytes, and
/// a reader of a file past this stops there (`--bike /dev/zero` would otherwise read until
/// memory runs out). [`parse`] refuses longer text.
pub const MAX_FILE_BYTES: usize = 4 << 20;

/// The text without a leading UTF-8 byte-order mark.
pub(crate) fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Reads a bicycle from a parameter file's text in the given format. Keys of other models and
/// redundant values are reported in [`Bicycle::notices`] and kept in [`Bicycle::extras`]; the
/// numbers are checked by [`Bicycle::check`], not here.
///
/// ```
/// use whipple::advanced::io::{parse, Format};
/// let text = "wheelbase = 1.016; % metres\n";
/// let err = parse(text, Format::Jbike6M).unwrap_err();
/// assert!(err.to_string().contains("missing"));
/// ```
pub fn parse(text: &str, format: Format) -> Result<Bicycle> {
    if text.len() > MAX_FILE_BYTES {
        return Err(crate::Error::LimitExceeded {
            what: "parameter file",
            rule: format!(
                "{} bytes, more than the {} MiB a parameter file may hold (the field's files \
                 are a few kilobytes): is it the right file?",
                text.len(),
                MAX_FILE_BYTES >> 20
            ),
        });
    }
    let text = strip_bom(text);
    match format {
        Format::Toml => tree::parse_toml(text),
        Format::Json => tree::parse_json(text),
        Format::Jbike6M => {
            matlab::parse_jbike6_m(text).map(|p| Bicycle::new(super::Description::Jbike6(p)))
        }
        Format::BicycleParametersTxt => keyvalue::parse(text, Format::BicycleParametersTxt),
        Format::HumanControlTxt => keyvalue::parse(text, Format::HumanControlTxt),
        Format::Yaml => yaml::parse(text),
    }
}

/// Writes a bicycle in the given format, every number in its shortest round-trip form and
/// every standard deviation kept, so that reading the text back gives the same bicycle.
/// JBike6's `.m` files hold no standard deviations; a benchmark-form bicycle is written in them
/// as JBike6's bodies (`Jbike6Parameters::from_benchmark`:
/// the frame is the rear body B, the fork the front frame H, rider, rack and basket absent),
/// which JBike6 and whipple read back as the same 25 numbers and g. BicycleParameters' formats
/// and HumanControl's exist only for the benchmark form.
pub fn write(bike: &Bicycle, format: Format) -> Result<String> {
    write::write(bike, format)
}

/// 1-based line and column of a byte offset.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text.as_bytes()[..offset];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let column = text[line_start..offset].chars().count() + 1;
    (line, column)
}

/// A parse error of a format, at a place, about a field.
pub(crate) fn error_at(
    format: Format,
    line: usize,
    column: usize,
    field: Option<&str>,
    message: impl Into<String>,
) -> Error {
    Error::Parse {
        format: format.label(),
        field: field.map(str::to_string),
        line,
        column,
        message: message.into(),
    }
}

/// Parses a plain number as written in a file; refuses NaN and infinities, naming the text
/// (cut to 40 characters).
pub(crate) fn parse_number(token: &str) -> std::result::Result<f64, String> {
    let t = token.trim();
    let lower = t.to_ascii_lowercase();
    if lower.contains("inf") || lower.contains("nan") {
        return Err(format!("`{}` is not a finite number", shorten(t, 40)));
    }
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!(
            "`{}` is too large for double precision",
            shorten(t, 40)
        )),
        Err(_) => Err(format!("`{}` is not a number", shorten(t, 40))),
    }
}

/// Half a unit in the last digit written (`0.0705` → 5e-5; `1.2e-3` → 5e-5): how far a value
/// may be from the truth by rounding alone.
pub(crate) fn rounding_allowance(token: &str) -> f64 {
    let t = token.trim().trim_start_matches(['+', '-']);
    let (mantissa, exponent) = match t.find(['e', 'E']) {
        Some(p) => (&t[..p], t[p + 1..].parse::<i32>().unwrap_or(0)),
        None => (t, 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, frac)| {
        frac.chars().filter(|c| c.is_ascii_digit()).count()
    });
    0.5 * 10f64.powi(exponent - decimals as i32)
}
