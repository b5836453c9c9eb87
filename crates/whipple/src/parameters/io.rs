//! Parameter files, read from and written to strings (the library never touches the file
//! system): TOML (the hand-edited format), JSON, and JBike6's MATLAB assignments (`.m`).
//!
//! TOML and JSON share one layout: optional `name` and `source` strings and exactly one of a
//! `benchmark` table (keys `w`, `c`, `lam`, `g`, `rR`, `mR`, `IRxx`, … as in Meijaard 2007) or a
//! `jbike6` table (`wheelbase`, `head_angle`, `trail`, optional `gravity`, and the tables
//! `rear_wheel`, `front_wheel`, `rider`, `frame`, `rack`, `fork`, `basket`). Unknown and
//! missing keys are errors.

use serde::{Deserialize, Serialize};

use super::{
    BenchmarkParameters, Bicycle, Description, Jbike6FrontBody, Jbike6Parameters, Jbike6RearBody,
    Jbike6Wheel, JBIKE6_GRAVITY,
};
use crate::error::{Error, Result};

/// A file format for bicycle descriptions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// TOML, the primary hand-edited format.
    Toml,
    /// JSON, the same layout as TOML.
    Json,
    /// JBike6's MATLAB assignments (`wheelbase = 1.016;`), JBike6 form only.
    Jbike6M,
}

impl Format {
    /// The format that a file name's extension names (`.toml`, `.json`, `.m`), if any.
    pub fn from_extension(extension: &str) -> Option<Format> {
        match extension.to_ascii_lowercase().as_str() {
            "toml" => Some(Format::Toml),
            "json" => Some(Format::Json),
            "m" => Some(Format::Jbike6M),
            _ => None,
        }
    }
}

/// The layout shared by TOML and JSON files.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileLayout {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    source: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    benchmark: Option<BenchmarkParameters>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    jbike6: Option<Jbike6Parameters>,
}

impl FileLayout {
    fn into_bicycle(self, format: &'static str) -> Result<Bicycle> {
        let description = match (self.benchmark, self.jbike6) {
            (Some(b), None) => Description::Benchmark(b),
            (None, Some(j)) => Description::Jbike6(j),
            (Some(_), Some(_)) => {
                return Err(Error::Parse {
                    format,
                    line: 0,
                    column: 0,
                    message: "give either a `benchmark` table or a `jbike6` table, not both".into(),
                })
            }
            (None, None) => {
                return Err(Error::Parse {
                    format,
                    line: 0,
                    column: 0,
                    message: "missing the bicycle: a `benchmark` table or a `jbike6` table".into(),
                })
            }
        };
        Ok(Bicycle {
            name: self.name,
            source: self.source,
            description,
        })
    }

    fn from_bicycle(bike: &Bicycle) -> Self {
        let (benchmark, jbike6) = match bike.description {
            Description::Benchmark(b) => (Some(b), None),
            Description::Jbike6(j) => (None, Some(j)),
        };
        FileLayout {
            name: bike.name.clone(),
            source: bike.source.clone(),
            benchmark,
            jbike6,
        }
    }
}

/// 1-based line and column of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text.as_bytes()[..offset];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    (line, column)
}

/// Reads a bicycle from a parameter file's text in the given format. The numbers are not
/// validated here: call [`Bicycle::benchmark`].
///
/// ```
/// use whipple::parameters::io::{parse, Format};
/// let text = "wheelbase = 1.016; % metres\n";
/// let err = parse(text, Format::Jbike6M).unwrap_err();
/// assert!(err.to_string().contains("missing"));
/// ```
pub fn parse(text: &str, format: Format) -> Result<Bicycle> {
    match format {
        Format::Toml => {
            let layout: FileLayout = toml::from_str(text).map_err(|e| {
                let (line, column) = e
                    .span()
                    .map_or((0, 0), |span| line_column(text, span.start));
                Error::Parse {
                    format: "TOML",
                    line,
                    column,
                    message: e.message().trim().to_string(),
                }
            })?;
            layout.into_bicycle("TOML")
        }
        Format::Json => {
            let layout: FileLayout = serde_json::from_str(text).map_err(|e| Error::Parse {
                format: "JSON",
                line: e.line(),
                column: e.column(),
                message: strip_json_position(&e.to_string()),
            })?;
            layout.into_bicycle("JSON")
        }
        Format::Jbike6M => parse_jbike6_m(text).map(|p| Bicycle::new(Description::Jbike6(p))),
    }
}

fn strip_json_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(p) => message[..p].to_string(),
        None => message.to_string(),
    }
}

/// Writes a bicycle in the given format. JBike6's `.m` form exists only for bicycles described
/// in JBike6's form.
pub fn write(bike: &Bicycle, format: Format) -> Result<String> {
    match format {
        Format::Toml => Ok(to_toml(bike)),
        Format::Json => {
            let mut text =
                serde_json::to_string_pretty(&FileLayout::from_bicycle(bike)).map_err(|e| {
                    Error::InvalidArgument {
                        what: "bicycle",
                        rule: format!("cannot be written as JSON: {e}"),
                    }
                })?;
            text.push('\n');
            Ok(text)
        }
        Format::Jbike6M => match &bike.description {
            Description::Jbike6(p) => Ok(to_jbike6_m(bike.name.as_deref(), p)),
            Description::Benchmark(_) => Err(Error::InvalidArgument {
                what: "format",
                rule: "only a bicycle described in JBike6's form can be written as a .m file"
                    .into(),
            }),
        },
    }
}

/// Shortest round-trip text of a number that TOML reads back as a float.
fn toml_number(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

/// TOML written by hand (rather than by serde) so that every key carries its unit and meaning.
fn to_toml(bike: &Bicycle) -> String {
    let mut out = String::new();
    if let Some(name) = &bike.name {
        out.push_str(&format!("name = {}\n", toml_string(name)));
    }
    if let Some(source) = &bike.source {
        out.push_str(&format!("source = {}\n", toml_string(source)));
    }
    if !out.is_empty() {
        out.push('\n');
    }
    match &bike.description {
        Description::Benchmark(p) => {
            out.push_str(
                "# Benchmark parameters (Meijaard et al. 2007, Table 1). SI units, radians.\n\
                 # Axes: x forward, y right, z down, origin at the rear contact (z < 0 is above ground).\n\
                 [benchmark]\n",
            );
            for (key, value) in p.fields() {
                out.push_str(&format!(
                    "{key} = {} # {}\n",
                    toml_number(value),
                    benchmark_key_doc(key)
                ));
            }
        }
        Description::Jbike6(p) => {
            out.push_str(
                "# JBike6 form. SI units, radians. Axes: x forward from the rear contact, y up.\n\
                 # I = [I11, I22, Izz]: principal moments about the centre of mass, axis 1 at alpha\n\
                 # from x (counter-clockwise); Izz about the lateral axis (a wheel's spin axis).\n\
                 [jbike6]\n",
            );
            out.push_str(&format!(
                "wheelbase = {} # horizontal distance between the wheel contacts [m]\n",
                toml_number(p.wheelbase)
            ));
            out.push_str(&format!(
                "head_angle = {} # steer axis angle from the horizontal [rad]\n",
                toml_number(p.head_angle)
            ));
            out.push_str(&format!(
                "trail = {} # front contact behind the steer axis' ground point [m]\n",
                toml_number(p.trail)
            ));
            out.push_str(&format!("gravity = {} # [m/s^2]\n", toml_number(p.gravity)));
            for (key, w) in [
                ("rear_wheel", &p.rear_wheel),
                ("front_wheel", &p.front_wheel),
            ] {
                out.push_str(&format!(
                    "\n[jbike6.{key}]\nD = {} # diameter [m]\nm = {} # [kg]\nI = {} # [kg m^2]\nalpha = {} # [rad]\n",
                    toml_number(w.diameter),
                    toml_number(w.m),
                    toml_array(&w.inertia),
                    toml_number(w.alpha)
                ));
            }
            for (key, b) in [("rider", &p.rider), ("frame", &p.frame), ("rack", &p.rack)] {
                out.push_str(&format!(
                    "\n[jbike6.{key}]\nm = {} # [kg]\nxcm = {} # forward of the rear contact [m]\nycm = {} # above the ground [m]\nI = {} # [kg m^2]\nalpha = {} # [rad]\n",
                    toml_number(b.m),
                    toml_number(b.xcm),
                    toml_number(b.ycm),
                    toml_array(&b.inertia),
                    toml_number(b.alpha)
                ));
            }
            for (key, b) in [("fork", &p.fork), ("basket", &p.basket)] {
                out.push_str(&format!(
                    "\n[jbike6.{key}]\nm = {} # [kg]\nucm = {} # perpendicular to the steer axis, forward [m]\nvcm = {} # up the steer axis from the ground [m]\nI = {} # [kg m^2]\nalpha = {} # [rad]\n",
                    toml_number(b.m),
                    toml_number(b.ucm),
                    toml_number(b.vcm),
                    toml_array(&b.inertia),
                    toml_number(b.alpha)
                ));
            }
        }
    }
    out
}

fn toml_string(s: &str) -> String {
    // TOML's own escaping: JSON's leaves characters raw (DEL, U+0080..U+009F) that a TOML
    // basic string may not hold.
    toml::Value::String(s.to_string()).to_string()
}

fn toml_array(values: &[f64; 3]) -> String {
    format!(
        "[{}, {}, {}]",
        toml_number(values[0]),
        toml_number(values[1]),
        toml_number(values[2])
    )
}

/// Meaning and unit of each benchmark file key, for comments and tables.
pub fn benchmark_key_doc(key: &str) -> &'static str {
    match key {
        "w" => "wheelbase [m]",
        "c" => "trail [m]",
        "lam" => "steer axis tilt from vertical [rad]",
        "g" => "gravity [m/s^2]",
        "rR" => "rear wheel radius [m]",
        "mR" => "rear wheel mass [kg]",
        "IRxx" => "rear wheel diametral moment of inertia [kg m^2]",
        "IRyy" => "rear wheel spin moment of inertia [kg m^2]",
        "xB" => "rear body centre of mass, forward [m]",
        "zB" => "rear body centre of mass, down (negative: up) [m]",
        "mB" => "rear body (frame and rider) mass [kg]",
        "IBxx" => "rear body inertia xx [kg m^2]",
        "IByy" => "rear body inertia yy [kg m^2]",
        "IBzz" => "rear body inertia zz [kg m^2]",
        "IBxz" => "rear body inertia xz [kg m^2]",
        "xH" => "front frame centre of mass, forward [m]",
        "zH" => "front frame centre of mass, down (negative: up) [m]",
        "mH" => "front frame (fork and handlebar) mass [kg]",
        "IHxx" => "front frame inertia xx [kg m^2]",
        "IHyy" => "front frame inertia yy [kg m^2]",
        "IHzz" => "front frame inertia zz [kg m^2]",
        "IHxz" => "front frame inertia xz [kg m^2]",
        "rF" => "front wheel radius [m]",
        "mF" => "front wheel mass [kg]",
        "IFxx" => "front wheel diametral moment of inertia [kg m^2]",
        "IFyy" => "front wheel spin moment of inertia [kg m^2]",
        _ => "",
    }
}

/// JBike6's MATLAB assignments, in the layout printed in the original study.
fn to_jbike6_m(name: Option<&str>, p: &Jbike6Parameters) -> String {
    let mut out = String::new();
    if let Some(name) = name {
        // One comment line: a line break in the name would start a statement.
        out.push_str(&format!("% {}\n", name.replace(['\n', '\r'], " ")));
    }
    let num = |x: f64| format!("{x:.8}");
    let arr = |v: &[f64; 3]| format!("[{} {} {}]", num(v[0]), num(v[1]), num(v[2]));
    out.push_str(&format!(
        "wheelbase = {};\nhead_angle = {};\ntrail = {};\ngravity = {};\n",
        num(p.wheelbase),
        num(p.head_angle),
        num(p.trail),
        num(p.gravity)
    ));
    for (title, key, w) in [
        ("rear wheel", "rearwheel", &p.rear_wheel),
        ("front wheel", "frontwheel", &p.front_wheel),
    ] {
        out.push_str(&format!(
            "\n% {title}\nD{key} = {};\nm{key} = {};\nI{key} = {};\nalphaI{key} = {};\n",
            num(w.diameter),
            num(w.m),
            arr(&w.inertia),
            num(w.alpha)
        ));
    }
    for (title, key, b) in [
        ("rider", "rider", &p.rider),
        ("frame", "frame", &p.frame),
        ("rear rack", "rack", &p.rack),
    ] {
        out.push_str(&format!(
            "\n% {title}\nm{key} = {};\nxcm{key} = {};\nycm{key} = {};\nI{key} = {};\nalphaI{key} = {};\n",
            num(b.m),
            num(b.xcm),
            num(b.ycm),
            arr(&b.inertia),
            num(b.alpha)
        ));
    }
    for (title, key, b) in [
        ("front fork", "fork", &p.fork),
        ("front basket", "basket", &p.basket),
    ] {
        out.push_str(&format!(
            "\n% {title}\nm{key} = {};\nucm{key} = {};\nvcm{key} = {};\nI{key} = {};\nalphaI{key} = {};\n",
            num(b.m),
            num(b.ucm),
            num(b.vcm),
            arr(&b.inertia),
            num(b.alpha)
        ));
    }
    out
}

/// One value on the right of a `.m` assignment.
#[derive(Debug, Clone)]
enum MValue {
    Scalar(f64),
    Vector(Vec<f64>),
}

fn m_error(line: usize, column: usize, message: impl Into<String>) -> Error {
    Error::Parse {
        format: "JBike6 .m",
        line,
        column,
        message: message.into(),
    }
}

/// The variable names of a JBike6 `.m` file, in the order of the original study.
const M_SCALARS: &[&str] = &[
    "wheelbase",
    "head_angle",
    "trail",
    "gravity",
    "Drearwheel",
    "mrearwheel",
    "alphaIrearwheel",
    "Dfrontwheel",
    "mfrontwheel",
    "alphaIfrontwheel",
    "mrider",
    "xcmrider",
    "ycmrider",
    "alphaIrider",
    "mframe",
    "xcmframe",
    "ycmframe",
    "alphaIframe",
    "mrack",
    "xcmrack",
    "ycmrack",
    "alphaIrack",
    "mfork",
    "ucmfork",
    "vcmfork",
    "alphaIfork",
    "mbasket",
    "ucmbasket",
    "vcmbasket",
    "alphaIbasket",
];
const M_VECTORS: &[&str] = &[
    "Irearwheel",
    "Ifrontwheel",
    "Irider",
    "Iframe",
    "Irack",
    "Ifork",
    "Ibasket",
];

fn parse_number(token: &str, line: usize, column: usize) -> Result<f64> {
    let lower = token.to_ascii_lowercase();
    if lower.contains("inf") || lower.contains("nan") {
        return Err(m_error(
            line,
            column,
            format!("`{token}` is not a finite number"),
        ));
    }
    token
        .parse::<f64>()
        .map_err(|_| m_error(line, column, format!("`{token}` is not a number")))
}

/// Reads JBike6's MATLAB assignments: `name = number;` or `name = [a b c];` one per line,
/// `%` starting a comment, blank lines ignored. Every variable of the original study's listing
/// is required except `gravity` (JBike6's default 9.80665); unknown names and repeated
/// assignments are errors.
pub fn parse_jbike6_m(text: &str) -> Result<Jbike6Parameters> {
    let mut values: std::collections::HashMap<&'static str, (MValue, usize)> =
        std::collections::HashMap::new();
    for (index, raw_line) in text.lines().enumerate() {
        let line_no = index + 1;
        let code = match raw_line.find('%') {
            Some(p) => &raw_line[..p],
            None => raw_line,
        };
        if code.trim().is_empty() {
            continue;
        }
        // Several statements may share a line: split on ';' (a trailing ';' is optional).
        let mut offset = 0;
        for statement in code.split(';') {
            let start = offset;
            offset += statement.len() + 1;
            if statement.trim().is_empty() {
                continue;
            }
            let column = start + statement.len() - statement.trim_start().len() + 1;
            let Some(eq) = statement.find('=') else {
                return Err(m_error(
                    line_no,
                    column,
                    format!("expected `name = value;`, found `{}`", statement.trim()),
                ));
            };
            let name = statement[..eq].trim();
            let rhs = &statement[eq + 1..];
            let rhs_column = start + eq + 2 + (rhs.len() - rhs.trim_start().len());
            let rhs = rhs.trim();
            let key: &'static str = match M_SCALARS
                .iter()
                .chain(M_VECTORS.iter())
                .find(|k| **k == name)
            {
                Some(k) => k,
                None => {
                    return Err(m_error(
                        line_no,
                        column,
                        format!("unknown variable `{name}` (JBike6 names such as `wheelbase`, `Drearwheel`, `Irider`, `ucmfork` are expected)"),
                    ))
                }
            };
            let value = if let Some(inner) = rhs.strip_prefix('[') {
                let Some(inner) = inner.strip_suffix(']') else {
                    return Err(m_error(line_no, rhs_column, "missing `]`"));
                };
                let numbers = inner
                    .split(|c: char| c.is_whitespace() || c == ',')
                    .filter(|t| !t.is_empty())
                    .map(|t| parse_number(t, line_no, rhs_column))
                    .collect::<Result<Vec<f64>>>()?;
                MValue::Vector(numbers)
            } else {
                MValue::Scalar(parse_number(rhs, line_no, rhs_column)?)
            };
            let is_vector = M_VECTORS.contains(&key);
            match (&value, is_vector) {
                (MValue::Vector(v), true) if v.len() != 3 => {
                    return Err(m_error(
                        line_no,
                        rhs_column,
                        format!(
                            "`{key}` needs three numbers [I11 I22 Izz], found {}",
                            v.len()
                        ),
                    ))
                }
                (MValue::Scalar(_), true) => {
                    return Err(m_error(
                        line_no,
                        rhs_column,
                        format!("`{key}` needs three numbers in brackets: [I11 I22 Izz]"),
                    ))
                }
                (MValue::Vector(_), false) => {
                    return Err(m_error(
                        line_no,
                        rhs_column,
                        format!("`{key}` is a single number, not a list"),
                    ))
                }
                _ => {}
            }
            if let Some((_, first)) = values.get(key) {
                return Err(m_error(
                    line_no,
                    column,
                    format!("`{key}` is assigned twice (first on line {first})"),
                ));
            }
            values.insert(key, (value, line_no));
        }
    }
    let missing: Vec<&str> = M_SCALARS
        .iter()
        .chain(M_VECTORS.iter())
        .filter(|k| **k != "gravity" && !values.contains_key(*k))
        .copied()
        .collect();
    if !missing.is_empty() {
        return Err(m_error(
            0,
            0,
            format!("missing variables: {}", missing.join(", ")),
        ));
    }
    let scalar = |k: &str| match values.get(k) {
        Some((MValue::Scalar(x), _)) => *x,
        _ => JBIKE6_GRAVITY, // only `gravity` may be absent, checked above
    };
    let vector = |k: &str| match values.get(k) {
        Some((MValue::Vector(v), _)) if v.len() == 3 => [v[0], v[1], v[2]],
        _ => [0.0; 3], // unreachable: presence and length checked above
    };
    let wheel = |n: &str| Jbike6Wheel {
        diameter: scalar(&format!("D{n}")),
        m: scalar(&format!("m{n}")),
        inertia: vector(&format!("I{n}")),
        alpha: scalar(&format!("alphaI{n}")),
    };
    let rear = |n: &str| Jbike6RearBody {
        m: scalar(&format!("m{n}")),
        xcm: scalar(&format!("xcm{n}")),
        ycm: scalar(&format!("ycm{n}")),
        inertia: vector(&format!("I{n}")),
        alpha: scalar(&format!("alphaI{n}")),
    };
    let front = |n: &str| Jbike6FrontBody {
        m: scalar(&format!("m{n}")),
        ucm: scalar(&format!("ucm{n}")),
        vcm: scalar(&format!("vcm{n}")),
        inertia: vector(&format!("I{n}")),
        alpha: scalar(&format!("alphaI{n}")),
    };
    Ok(Jbike6Parameters {
        wheelbase: scalar("wheelbase"),
        head_angle: scalar("head_angle"),
        trail: scalar("trail"),
        gravity: scalar("gravity"),
        rear_wheel: wheel("rearwheel"),
        front_wheel: wheel("frontwheel"),
        rider: rear("rider"),
        frame: rear("frame"),
        rack: rear("rack"),
        fork: front("fork"),
        basket: front("basket"),
    })
}
