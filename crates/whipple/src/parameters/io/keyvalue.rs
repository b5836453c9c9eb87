//! BicycleParameters' `<Name>Benchmark.txt` and HumanControl's `<Name>Par.txt`: one
//! `key = value` a line (HumanControl's older files also `key,value`), `+/-sigma` optional, `#`
//! comments whole-line or trailing; HumanControl's values may be simple expressions (`pi/10`).
//! Several comma-separated measurements on one line are averaged, as BicycleParameters does.
//!
//! The keys besides the benchmark ones, with their meaning from the owning projects'
//! documentation (BicycleParameters `docs/data.rst`, HumanControl `parameters/README.rst`,
//! Moore 2012):
//! - `yB`, `yH`, `IBxy`, `IByz`, `IHxy`, `IHyz`: lateral offsets and products of inertia; the
//!   model is left-right symmetric, so they must be zero.
//! - `IRzz`, `IFzz`: the wheels' second diametral moments; wheels are axisymmetric, so they
//!   must equal `IRxx`, `IFxx`.
//! - `v`: the forward speed the owner evaluated the model at (an operating point, not a
//!   parameter).
//! - `d1`, `d3`: Moore's rear and front offsets of the wheel centres from the steer axis,
//!   redundant with the benchmark geometry: d1 = cos λ (c + w − r_R tan λ),
//!   d3 = −cos λ (c − r_F tan λ); checked against it.
//! - `xcl`, `zcl`: where the lateral force of Moore's lateral-force input acts; `ds1`, `ds3`:
//!   where an accelerometer sits. Not used by the Whipple model.
//! - `mG`, `xG`, `zG`, `IGxx`, `IGyy`, `IGzz`, `IGxz` and the same for `S`: the handlebar (G) and
//!   fork (S) measured apart; together they are the front frame H, which is built from them
//!   when absent and checked against them when given.

use super::{Format, error_at, parse_number, rounding_allowance};
use crate::error::{Result, shorten};
use crate::parameters::check::{Notice, percent};
use crate::parameters::jbike6::PlaneBody;
use crate::parameters::table::{Form, index_of};
use crate::parameters::{
    BENCHMARK_TABLE, BenchmarkParameters, Bicycle, Description, Extra, STEER_INERTIA_KEY,
};

/// One value read from a file.
#[derive(Debug, Clone)]
pub(crate) struct Entry {
    pub key: String,
    pub value: f64,
    pub sigma: Option<f64>,
    pub text: String,
    pub line: usize,
    pub column: usize,
    pub allowance: f64,
}

pub(crate) fn parse(text: &str, format: Format) -> Result<Bicycle> {
    let mut entries = Vec::new();
    let mut name = None;
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let trimmed = raw.trim();
        if trimmed.is_empty() {
            continue;
        }
        if let Some(comment) = trimmed.strip_prefix('#') {
            if name.is_none() && index == 0 {
                if let Some(n) = comment.trim().strip_prefix("name:") {
                    name = Some(n.trim().to_string());
                }
            }
            continue;
        }
        let code = match raw.find('#') {
            Some(p) => &raw[..p],
            None => raw,
        };
        if code.trim().is_empty() {
            continue;
        }
        let (key, rhs, rhs_offset) = match code.find('=') {
            Some(eq) => (&code[..eq], &code[eq + 1..], eq + 1),
            None => match code.find(',') {
                Some(comma) if format == Format::HumanControlTxt => {
                    (&code[..comma], &code[comma + 1..], comma + 1)
                }
                _ => {
                    return Err(error_at(
                        format,
                        line_no,
                        code.len() - code.trim_start().len() + 1,
                        None,
                        format!(
                            "expected `key = value`, found `{}`",
                            shorten(code.trim(), 60)
                        ),
                    ));
                }
            },
        };
        let key = key.trim();
        let key_column = code.len() - code.trim_start().len() + 1;
        if key.is_empty() || !key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(error_at(
                format,
                line_no,
                key_column,
                None,
                format!("`{}` is not a parameter name", shorten(key, 40)),
            ));
        }
        let column = rhs_offset + rhs.len() - rhs.trim_start().len() + 1;
        let measurements: Vec<&str> = if format == Format::HumanControlTxt && !code.contains('=') {
            vec![rhs]
        } else {
            rhs.split(',').collect()
        };
        if let Some(at) = decimal_comma(rhs) {
            let number: String = rhs[at..]
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == ',' || *c == '-' || *c == '+')
                .collect();
            return Err(error_at(
                format,
                line_no,
                rhs_offset + at + 1,
                Some(key),
                format!(
                    "`{number}` looks like a number with a decimal comma; write it with a point \
                     (`{}`), or put a space after each comma of a list of measurements \
                     (`{}`), which are averaged",
                    number.replacen(',', ".", 1),
                    number.replace(',', ", "),
                ),
            ));
        }
        let mut values = Vec::new();
        for m in &measurements {
            let (value_text, sigma_text) = match m.split_once("+/-").or_else(|| m.split_once('±'))
            {
                Some((v, s)) => (v.trim(), Some(s.trim())),
                None => (m.trim(), None),
            };
            let at = |message: String| error_at(format, line_no, column, Some(key), message);
            let value = match parse_number(value_text) {
                Ok(v) => v,
                Err(plain) => {
                    if value_text.parse::<f64>().is_err()
                        && !value_text.to_ascii_lowercase().contains("inf")
                        && !value_text.to_ascii_lowercase().contains("nan")
                    {
                        crate::expression::evaluate_constant(value_text).map_err(|e| {
                            at(format!(
                                "`{}` is neither a number nor an expression whipple can evaluate ({e})",
                                shorten(value_text, 40)
                            ))
                        })?
                    } else {
                        return Err(at(plain));
                    }
                }
            };
            let sigma = match sigma_text {
                Some(s) => {
                    let sigma =
                        parse_number(s).map_err(|e| at(format!("standard deviation: {e}")))?;
                    if sigma < 0.0 {
                        return Err(at(format!(
                            "a standard deviation cannot be negative (`+/-{}`)",
                            shorten(s, 40)
                        )));
                    }
                    Some(sigma)
                }
                None => None,
            };
            values.push((value, sigma, value_text));
        }
        let n = values.len() as f64;
        let value = values.iter().map(|v| v.0).sum::<f64>() / n;
        let sigma = if values.len() == 1 {
            values[0].1
        } else if values.iter().any(|v| v.1.is_some()) {
            Some(
                values
                    .iter()
                    .map(|v| v.1.unwrap_or(0.0).powi(2))
                    .sum::<f64>()
                    .sqrt()
                    / n,
            )
        } else {
            None
        };
        let allowance = values
            .iter()
            .map(|v| rounding_allowance(v.2))
            .fold(0.0, f64::max);
        if !value.is_finite() {
            return Err(error_at(
                format,
                line_no,
                column,
                Some(key),
                "the value is not a finite number",
            ));
        }
        entries.push(Entry {
            key: key.to_string(),
            value,
            sigma,
            text: rhs.trim().to_string(),
            line: line_no,
            column,
            allowance,
        });
    }
    let mut bike = assemble(entries, format)?;
    if bike.name.is_none() {
        bike.name = name;
    }
    Ok(bike)
}

/// Where a value written with a decimal comma starts in `rhs` (`1,02`: digits, a comma, digits,
/// no space between), if one does. A list of measurements separates its values with a comma
/// and a space, or has a point in each (`0.72,0.73`); an integer list without spaces (`1,2`)
/// is ambiguous and refused too, with both readings in the message.
fn decimal_comma(rhs: &str) -> Option<usize> {
    let bytes = rhs.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        if b != b',' || i == 0 || i + 1 >= bytes.len() {
            continue;
        }
        if !(bytes[i - 1].is_ascii_digit() && bytes[i + 1].is_ascii_digit()) {
            continue;
        }
        // The integer part: digits back to a space, a sign, `=` or a separating comma.
        let start = rhs[..i]
            .rfind(|c: char| !c.is_ascii_digit())
            .map_or(0, |p| p + 1);
        let before = rhs[..start].trim_end();
        let integer = before.is_empty()
            || before.ends_with(['+', '-', ','])
            || before.ends_with("+/-")
            || before.ends_with('±');
        if integer {
            let sign = rhs[..start].ends_with(['+', '-']) && !before.ends_with("+/-");
            return Some(if sign { start - 1 } else { start });
        }
    }
    None
}

/// Keys that must be zero in a left-right symmetric model.
const SYMMETRIC_ZERO: [&str; 6] = ["yB", "yH", "IBxy", "IByz", "IHxy", "IHyz"];

/// The front frame H's keys, in the order of [`combine_fork`]'s result.
const FRONT_FRAME: [&str; 7] = ["mH", "xH", "zH", "IHxx", "IHyy", "IHzz", "IHxz"];

/// The handlebar (G) and fork (S) keys, measured apart.
const SPLIT_FORK: [&str; 14] = [
    "mG", "xG", "zG", "IGxx", "IGyy", "IGzz", "IGxz", "mS", "xS", "zS", "ISxx", "ISyy", "ISzz",
    "ISxz",
];

/// Keys of BicycleParameters' raw measurements (`<Name>Measured.txt`).
fn is_raw_measurement(key: &str) -> bool {
    let body = |rest: &str| {
        rest.starts_with(['B', 'H', 'F', 'R', 'P', 'S', 'G'])
            && rest[1..].chars().all(|c| c.is_ascii_digit())
    };
    key.strip_prefix("Tc").is_some_and(body)
        || key.strip_prefix("Tt").is_some_and(body)
        || key.strip_prefix("alpha").is_some_and(body)
        || (key.starts_with('a') && key.len() <= 3 && key[1..].starts_with(['B', 'H', 'S', 'G']))
        || matches!(
            key,
            "f" | "gamma"
                | "lF"
                | "lP"
                | "lR"
                | "dF"
                | "dR"
                | "dP"
                | "nF"
                | "nR"
                | "mP"
                | "h1"
                | "h2"
                | "h3"
                | "h4"
                | "h5"
                | "d"
                | "d2"
                | "d4"
        )
}

/// The meaning of a key that is not a benchmark parameter, for notes and for writing it back.
pub(crate) fn extra_meaning(key: &str) -> Option<&'static str> {
    Some(match key {
        "v" => {
            "forward speed the file's owner evaluated the model at [m/s]; whipple takes the speeds as arguments of each analysis"
        }
        "d1" => {
            "Moore 2012's rear offset: rear wheel centre to the steer axis [m], redundant with w, c, lam, rR"
        }
        "d3" => {
            "Moore 2012's fork offset: front wheel centre to the steer axis [m], redundant with c, lam, rF"
        }
        "xcl" | "zcl" => {
            "location of the point where Moore 2012's lateral-force input acts, in benchmark axes [m]; not used by the Whipple model"
        }
        "ds1" | "ds3" => {
            "location of an accelerometer from the steer axis [m] (BicycleParameters); not used by the Whipple model"
        }
        "yB" | "yH" => {
            "lateral offset of a centre of mass [m]; zero in the left-right symmetric model"
        }
        "IBxy" | "IByz" | "IHxy" | "IHyz" => {
            "product of inertia with the lateral axis [kg m^2]; zero in the left-right symmetric model"
        }
        "IRzz" => {
            "rear wheel's second diametral moment [kg m^2]; equals IRxx for an axisymmetric wheel"
        }
        "IFzz" => {
            "front wheel's second diametral moment [kg m^2]; equals IFxx for an axisymmetric wheel"
        }
        k if SPLIT_FORK.contains(&k) && k.contains('G') => {
            "handlebar G measured apart from the fork (BicycleParameters); with the fork S it makes the front frame H"
        }
        k if SPLIT_FORK.contains(&k) => {
            "fork S measured apart from the handlebar (BicycleParameters); with the handlebar G it makes the front frame H"
        }
        "mD" | "IDxx" | "IDyy" => {
            "flywheel D inside the front wheel, measured with it (BicycleParameters' Gyro): its own mass [kg] or inertia [kg m^2]; not in the Whipple model, which BicycleParameters' analyses ignore it in too"
        }
        "parameterization" | "parameters" | "rider" | "description" => {
            "YAML metadata of a BicycleParameters parameter set"
        }
        "mP" | "xP" | "zP" | "kPaa" | "kPbb" | "kPyy" | "alphaP" => {
            "the rigid rider P of Moore 2019's principal parameterization (BicycleParameters), inside the rear frame B; kept to write the principal form back"
        }
        "lP" | "wP" => {
            "length and width of the rider diamond BicycleParameters draws for Moore 2019's principal parameterization [m]; not used by the Whipple model"
        }
        _ => return None,
    })
}

/// Builds a benchmark-form bicycle from the entries of a BicycleParameters, HumanControl or
/// YAML file: every key is a benchmark parameter, a documented key of another model (kept and
/// noted), or an error.
pub(crate) fn assemble(entries: Vec<Entry>, format: Format) -> Result<Bicycle> {
    let mut values: [Option<&Entry>; 26] = [None; 26];
    let mut extras: Vec<&Entry> = Vec::new();
    let mut steer: Option<&Entry> = None;
    let mut notices = Vec::new();
    for (i, e) in entries.iter().enumerate() {
        if let Some(first) = entries[..i].iter().find(|f| f.key == e.key) {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(&e.key),
                format!("`{}` is given twice (first on line {})", e.key, first.line),
            ));
        }
        if let Some(k) = index_of(Form::Benchmark, &e.key) {
            values[k] = Some(e);
        } else if e.key == STEER_INERTIA_KEY {
            steer = Some(e);
        } else if extra_meaning(&e.key).is_some() {
            extras.push(e);
        } else if is_raw_measurement(&e.key) {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(&e.key),
                format!(
                    "`{}` is a raw measurement: this looks like BicycleParameters' \
                     <Name>Measured.txt (pendulum periods and distances). whipple reads the \
                     benchmark parameters BicycleParameters computes from it \
                     (Bicycle(name).save_parameters() writes <Name>Benchmark.txt)",
                    e.key
                ),
            ));
        } else {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(&e.key),
                format!(
                    "unknown key `{}`: neither a benchmark parameter (w, c, lam, g, rR, mR, IRxx, \
                     ...) nor a key of BicycleParameters or HumanControl that whipple knows",
                    shorten(&e.key, 40)
                ),
            ));
        }
    }
    let get = |key: &str| extras.iter().find(|e| e.key == key).copied();
    // The front frame H: given, or built from the handlebar G and fork S.
    let split: Vec<Option<&Entry>> = SPLIT_FORK.iter().map(|k| get(k)).collect();
    let split_values: Option<Vec<f64>> = split.iter().map(|e| e.map(|e| e.value)).collect();
    // The front assembly's moment about the steer axis stands for IHzz: one of them.
    let ihzz = index_of(Form::Benchmark, "IHzz").unwrap_or(20);
    if let Some(e) = steer {
        if values[ihzz].is_some() || split_values.is_some() {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(STEER_INERTIA_KEY),
                format!(
                    "give either IHzz (or the handlebar G and fork S) or {STEER_INERTIA_KEY} \
                     (the front assembly's moment about the steer axis, from which IHzz is \
                     derived), not both"
                ),
            ));
        }
        if e.sigma.is_some_and(|s| s > 0.0) {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(STEER_INERTIA_KEY),
                format!(
                    "a standard deviation of `{STEER_INERTIA_KEY}` is not carried to IHzz yet: \
                     give its value alone, or IHzz with its own"
                ),
            ));
        }
    }
    // Missing keys, all named in one message: IByy BicycleParameters takes as zero; the front
    // frame's keys are not missing when its handlebar G and fork S are given; IHzz is not
    // missing when IAlamlam is given; the rest are required.
    let missing: Vec<&str> = BENCHMARK_TABLE
        .iter()
        .enumerate()
        .filter(|(i, p)| {
            values[*i].is_none()
                && p.key != "IByy"
                && !(split_values.is_some() && FRONT_FRAME.contains(&p.key))
                && !(steer.is_some() && *i == ihzz)
        })
        .map(|(_, p)| p.key)
        .collect();
    let present_b = entries
        .iter()
        .all(|e| e.key.ends_with('B') || e.key.starts_with("IB"));
    if !missing.is_empty() && present_b && !entries.is_empty() {
        return Err(error_at(
            format,
            0,
            0,
            Some(missing[0]),
            "this holds only a rear body B (mB, xB, zB, IB..): it looks like a rider's file \
             (BicycleParameters' riders/<Rider>/Parameters/<Rider><Bicycle>Benchmark.txt), not a \
             bicycle. BicycleParameters adds the rider to a bicycle (Bicycle.add_rider) and \
             saves the combination, which whipple reads",
        ));
    }
    if !missing.is_empty() {
        let front = if missing.iter().any(|k| FRONT_FRAME.contains(k)) {
            format!(
                " (the front frame H may instead be given as its handlebar G and fork S \
                 measured apart: {})",
                SPLIT_FORK.join(", ")
            )
        } else {
            String::new()
        };
        let (noun, list) = match missing.as_slice() {
            [one] => ("key", format!("`{one}`")),
            many => ("keys", many.join(", ")),
        };
        return Err(error_at(
            format,
            0,
            0,
            Some(missing[0]),
            format!("missing {noun}: {list}{front}"),
        ));
    }
    let combined = split_values.as_ref().map(|v| combine_fork(v));
    let mut filled: [f64; 26] = [0.0; 26];
    let mut sigma = std::collections::BTreeMap::new();
    for (i, p) in BENCHMARK_TABLE.iter().enumerate() {
        match values[i] {
            Some(e) => {
                filled[i] = e.value;
                if let Some(s) = e.sigma {
                    if s > 0.0 {
                        sigma.insert(p.key.to_string(), s);
                    }
                }
            }
            None if steer.is_some() && i == ihzz => {}
            None => {
                if let (Some(pos), Some(c)) = (
                    FRONT_FRAME.iter().position(|k| *k == p.key),
                    combined.as_ref(),
                ) {
                    filled[i] = c[pos];
                    if pos == 0 {
                        notices.push(Notice::note(
                            FRONT_FRAME.join(", "),
                            "the front frame H is not given: built from the handlebar G and the \
                             fork S (masses added, parallel-axis theorem); their standard \
                             deviations are not carried over",
                        ));
                    }
                } else {
                    // IByy, which BicycleParameters takes as zero when absent.
                    notices.push(Notice::warning(
                        p.key,
                        format!(
                            "`{}` is not given: taken as 0, as BicycleParameters does; the linear \
                             model never uses it, the non-linear model does",
                            p.key
                        ),
                        None,
                        "only the non-linear model (simulate, validate)",
                    ));
                }
            }
        }
    }
    let mut bike = BenchmarkParameters::from_array(filled);
    if let Some(e) = steer {
        bike = bike.with_front_assembly_steer_inertia(e.value)?;
        notices.push(super::tree::steer_note(e.value, bike.i_hzz));
    }
    for e in &extras {
        check_extra(
            e,
            &bike,
            combined.as_ref().map(|c| &c[..]),
            values[index_of(Form::Benchmark, "mH").unwrap_or(17)].is_some(),
            format,
            &mut notices,
        )?;
    }
    Ok(Bicycle {
        description: Description::Benchmark(bike),
        sigma,
        extras: extras
            .iter()
            .map(|e| Extra {
                key: e.key.clone(),
                text: e.text.clone(),
                value: Some(e.value),
                sigma: e.sigma,
                meaning: extra_meaning(&e.key).unwrap_or("").to_string(),
            })
            .collect(),
        notices,
        ..Bicycle::default()
    })
}

/// Checks one extra key against the benchmark parameters and says what it is.
fn check_extra(
    e: &Entry,
    bike: &BenchmarkParameters,
    combined: Option<&[f64]>,
    h_given: bool,
    format: Format,
    notices: &mut Vec<Notice>,
) -> Result<()> {
    let key = e.key.as_str();
    let meaning = extra_meaning(key).unwrap_or("");
    let agree = |given: f64, implied: f64, allowance: f64| {
        (given - implied).abs() <= allowance + 1e-9 * implied.abs().max(given.abs())
    };
    if SYMMETRIC_ZERO.contains(&key) {
        if e.value != 0.0 {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(key),
                format!(
                    "`{key}` = {}: the Whipple model is left-right symmetric (as the benchmark \
                     is), so {meaning}; a bicycle with a non-zero {key} cannot be described here",
                    shorten(&e.text, 40)
                ),
            ));
        }
        notices.push(Notice::note(key, format!("`{key}` = 0: {meaning}")));
        return Ok(());
    }
    if key == "IRzz" || key == "IFzz" {
        let (xx_key, xx) = if key == "IRzz" {
            ("IRxx", bike.i_rxx)
        } else {
            ("IFxx", bike.i_fxx)
        };
        if !agree(e.value, xx, e.allowance) {
            return Err(error_at(
                format,
                e.line,
                e.column,
                Some(key),
                format!(
                    "`{key}` = {} differs from `{xx_key}` = {}: the wheels are axisymmetric, \
                     so a wheel's two diametral moments must be equal",
                    shorten(&e.text, 40),
                    xx
                ),
            ));
        }
        notices.push(Notice::note(
            key,
            format!("`{key}` equals `{xx_key}`: {meaning}"),
        ));
        return Ok(());
    }
    if key == "d1" || key == "d3" {
        let (s, c) = crate::math::sin_cos(bike.lambda);
        let implied = if key == "d1" {
            c * (bike.c + bike.w - bike.r_r * s / c)
        } else {
            -c * (bike.c - bike.r_f * s / c)
        };
        if agree(e.value, implied, e.allowance) {
            notices.push(Notice::note(
                key,
                format!(
                    "`{key}` = {} agrees with the benchmark geometry ({meaning})",
                    e.text
                ),
            ));
        } else {
            let pct = percent((e.value - implied).abs(), implied);
            notices.push(Notice::warning(
                key,
                format!(
                    "`{key}` = {} disagrees with the {} m that the benchmark geometry (w, c, lam, \
                     rR, rF) implies, by {pct:.2} %, more than the digits written allow; whipple \
                     uses the benchmark geometry ({meaning})",
                    e.text,
                    crate::error::short_number(implied)
                ),
                Some(pct),
                "none directly: the benchmark geometry is used; one of the two descriptions of the geometry is off",
            ));
        }
        return Ok(());
    }
    if SPLIT_FORK.contains(&key) {
        if key == "mG" {
            if let (Some(c), true) = (combined, h_given) {
                let h = [
                    bike.m_h, bike.x_h, bike.z_h, bike.i_hxx, bike.i_hyy, bike.i_hzz, bike.i_hxz,
                ];
                let mut worst: Option<(usize, f64)> = None;
                for k in 0..7 {
                    let scale = h[k]
                        .abs()
                        .max(c[k].abs())
                        .max(if k < 3 { 1e-3 } else { 1e-6 });
                    let rel = (h[k] - c[k]).abs() / scale;
                    if rel > 1e-3 && worst.is_none_or(|(_, w)| rel > w) {
                        worst = Some((k, rel));
                    }
                }
                match worst {
                    None => notices.push(Notice::note(
                        "mG, mS, ...",
                        "the handlebar G and fork S measured apart combine to the front frame H \
                         as given (to 0.1 %); whipple uses H",
                    )),
                    Some((k, rel)) => notices.push(Notice::warning(
                        FRONT_FRAME[k],
                        format!(
                            "the handlebar G and fork S measured apart combine to {} = {}, but \
                             the file gives {} = {}: they differ by {:.2} %; whipple uses H as given",
                            FRONT_FRAME[k],
                            crate::error::short_number(c[k]),
                            FRONT_FRAME[k],
                            crate::error::short_number(h[k]),
                            100.0 * rel
                        ),
                        Some(100.0 * rel),
                        "none directly (H is used); the file's two descriptions of the front frame disagree",
                    )),
                }
            }
        }
        if combined.is_none() && key == "mG" {
            notices.push(Notice::note(
                key,
                "the handlebar G and fork S are only partly given; whipple uses the front frame H",
            ));
        }
        return Ok(());
    }
    if matches!(
        key,
        "parameterization" | "parameters" | "rider" | "description"
    ) {
        return Ok(());
    }
    notices.push(Notice::note(
        key,
        format!("`{key}` = {}: {meaning}", shorten(&e.text, 40)),
    ));
    Ok(())
}

/// The front frame H from the handlebar G and fork S ([mG, xG, zG, IGxx, IGyy, IGzz, IGxz, mS,
/// ...]), combined as every body is ([`PlaneBody::combine`]: masses added, mass-weighted
/// centre, tensors moved by the parallel-axis theorem).
fn combine_fork(v: &[f64]) -> [f64; 7] {
    let body = |k: usize| PlaneBody {
        m: v[k],
        x: v[k + 1],
        z: v[k + 2],
        i_xx: v[k + 3],
        i_yy: v[k + 4],
        i_zz: v[k + 5],
        i_xz: v[k + 6],
    };
    let h = PlaneBody::combine(&[body(0), body(7)]);
    [h.m, h.x, h.z, h.i_xx, h.i_yy, h.i_zz, h.i_xz]
}
