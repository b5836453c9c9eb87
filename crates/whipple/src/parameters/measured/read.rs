//! BicycleParameters' `*Measured.txt`: one `key = value` a line, a value optionally followed by
//! `+/-` and its standard deviation, repeated measurements as a comma-separated list (their
//! mean is used), `#` starting a comment. Every key is checked: the measurements the pipeline
//! needs, the rider's seat and handlebar geometry kept for later, anything else an error.

use std::collections::BTreeMap;

use super::{Hanging, Measured, Measurements};
use crate::error::{Error, Result};
use crate::parameters::io::MAX_FILE_BYTES;

const FORMAT: &str = "BicycleParameters Measured .txt";

/// The most hangings of one frame a file may give (`alphaB1` … `alphaB16`).
pub const MAX_HANGINGS: usize = 16;

/// The most values in one key's list of repeated measurements.
const MAX_REPEATS: usize = 64;

/// The scalar measurements, with what each one feeds (for a missing key's message).
const SCALARS: [(&str, &str); 24] = [
    ("g", "every compound pendulum's inertia"),
    ("dR", "the rear wheel's radius"),
    ("nR", "the rear wheel's radius"),
    ("dF", "the front wheel's radius"),
    ("nF", "the front wheel's radius"),
    ("w", "the wheelbase"),
    ("gamma", "the steer axis tilt"),
    ("f", "the trail"),
    ("mR", "the rear wheel's mass and IRyy"),
    ("mF", "the front wheel's mass and IFyy"),
    ("mB", "the rear frame's mass and IByy"),
    ("mH", "the front frame's mass and IHyy"),
    ("lR", "the rear wheel's IRyy (compound pendulum length)"),
    ("lF", "the front wheel's IFyy (compound pendulum length)"),
    ("TcR1", "the rear wheel's IRyy"),
    ("TcF1", "the front wheel's IFyy"),
    ("TcB1", "the rear frame's IByy"),
    ("TcH1", "the front frame's IHyy"),
    ("TtR1", "the rear wheel's IRxx"),
    ("TtF1", "the front wheel's IFxx"),
    ("mP", "the torsion constant (calibration rod)"),
    ("lP", "the torsion constant (calibration rod)"),
    ("dP", "the torsion constant (calibration rod)"),
    ("TtP1", "the torsion constant (calibration rod)"),
];

/// Keys of the rider's seat and handlebar geometry (BicycleParameters' `add_rider`) and of
/// the lateral force point: read and kept, not used by the bicycle's parameters.
const KEPT: [&str; 12] = [
    "lcs", "hbb", "lsp", "lst", "lamst", "whb", "LhbF", "LhbR", "xcl", "zcl", "ds1", "ds3",
];

/// A `*Measured.txt` read: the measurements and the other keys kept as written.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredFile {
    /// The measurements the pipeline uses.
    pub measurements: Measurements<Measured>,
    /// The rider's geometry and other known keys the bicycle's parameters do not use
    /// (`lcs`, `hbb`, `LhbF`, …), in file order.
    pub other: Vec<(String, Measured)>,
}

fn error(line: usize, field: Option<&str>, message: String) -> Error {
    Error::Parse {
        format: FORMAT,
        field: field.map(str::to_string),
        line,
        column: if line > 0 { 1 } else { 0 },
        message,
    }
}

/// One value: `0.293+/-0.001` or `13`.
fn value(text: &str, line: usize, key: &str) -> Result<(f64, f64, bool)> {
    let number = |t: &str| -> Result<f64> {
        t.trim()
            .parse::<f64>()
            .map_err(|_| error(line, Some(key), format!("`{}` is not a number", t.trim())))
    };
    match text.split_once("+/-") {
        Some((v, s)) => {
            let sigma = number(s)?;
            if sigma.is_nan() || sigma < 0.0 {
                return Err(error(
                    line,
                    Some(key),
                    format!(
                        "the standard deviation `{}` must be zero or positive",
                        s.trim()
                    ),
                ));
            }
            Ok((number(v)?, sigma, true))
        }
        None => Ok((number(text)?, 0.0, false)),
    }
}

/// One line's values: the mean of the list, σ = √(Σσᵢ²)/n.
fn values(text: &str, line: usize, key: &str) -> Result<Measured> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() > MAX_REPEATS {
        return Err(error(
            line,
            Some(key),
            format!(
                "{} values: at most {MAX_REPEATS} repeated measurements a key",
                parts.len()
            ),
        ));
    }
    let read: Vec<(f64, f64, bool)> = parts
        .iter()
        .map(|p| value(p, line, key))
        .collect::<Result<_>>()?;
    if read.iter().any(|r| r.2) && !read.iter().all(|r| r.2) {
        return Err(error(
            line,
            Some(key),
            "some values of the list have a +/- and some do not: give every value its \
             standard deviation, or none"
                .into(),
        ));
    }
    let n = read.len() as f64;
    let mean = read.iter().map(|r| r.0).sum::<f64>() / n;
    let sigma = read.iter().map(|r| r.1 * r.1).sum::<f64>().sqrt() / n;
    Ok(Measured {
        value: mean,
        sigma,
        line,
    })
}

/// What a key that this reader does not compute from says about the file.
fn unsupported(key: &str) -> Option<&'static str> {
    let geometry = ["h1", "h2", "h3", "h4", "h5", "d1", "d2", "d3", "d4", "d"];
    let split = ["h6", "h7", "d5", "d6", "l", "mS", "mG", "TcS1", "TcG1"];
    let flywheel = ["mD", "TcD1", "TtD1"];
    let part = |p: char| {
        key.strip_prefix("alpha")
            .or_else(|| key.strip_prefix("Tt"))
            .or_else(|| key.strip_prefix('a'))
            .is_some_and(|rest| rest.starts_with(p))
    };
    if geometry.contains(&key) {
        Some(
            "the geometry measured as perpendicular distances (h1…h5, d1…d4, d) is not \
             supported yet: give w, gamma and f",
        )
    } else if split.contains(&key) || part('S') || part('G') {
        Some("a fork measured apart from its handlebar (parts S and G) is not supported yet")
    } else if flywheel.contains(&key) {
        Some("a flywheel in the front wheel (part D) is not supported yet")
    } else {
        None
    }
}

/// A hanging key (`alphaB2`, `aH1`, `TtB3`): which frame, which of the three, its number.
fn hanging_key(key: &str) -> Option<(char, usize, usize)> {
    for (which, prefix) in [(0, "alpha"), (2, "Tt"), (1, "a")] {
        if let Some(rest) = key.strip_prefix(prefix) {
            let mut chars = rest.chars();
            let part = chars.next()?;
            let number: usize = chars.as_str().parse().ok()?;
            if matches!(part, 'B' | 'H') && number >= 1 {
                return Some((part, which, number));
            }
        }
    }
    None
}

/// Reads a `*Measured.txt` (BicycleParameters' raw data, Moore 2012 ch. 2). Errors name the key
/// and its line; a missing measurement is named with what it feeds.
///
/// ```
/// use whipple::advanced::measured::read_measurements;
/// let file = read_measurements("g = 9.81 +/- 0.01\nnF = 13, 14\n");
/// let message = file.unwrap_err().to_string();
/// assert!(message.contains("dR is missing: the rear wheel's radius needs it"), "{message}");
/// ```
pub fn read_measurements(text: &str) -> Result<MeasuredFile> {
    if text.len() > MAX_FILE_BYTES {
        return Err(error(
            0,
            None,
            format!("the file is larger than {} MiB", MAX_FILE_BYTES >> 20),
        ));
    }
    let mut scalars: BTreeMap<&str, Measured> = BTreeMap::new();
    let mut hangings: BTreeMap<(char, usize), [Option<Measured>; 3]> = BTreeMap::new();
    let mut other = Vec::new();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let Some((key, rest)) = content.split_once('=') else {
            return Err(error(
                line,
                None,
                format!("expected `key = value`, found `{content}`"),
            ));
        };
        let key = key.trim();
        if let Some(first) = seen.insert(key.to_string(), line) {
            return Err(error(
                line,
                Some(key),
                format!("given twice (first on line {first})"),
            ));
        }
        if let Some(why) = unsupported(key) {
            return Err(error(line, Some(key), why.into()));
        }
        let measured = values(rest, line, key)?;
        if let Some((name, _)) = SCALARS.iter().find(|(k, _)| *k == key) {
            scalars.insert(name, measured);
        } else if let Some((part, which, number)) = hanging_key(key) {
            if number > MAX_HANGINGS {
                return Err(error(
                    line,
                    Some(key),
                    format!("at most {MAX_HANGINGS} hangings of a frame"),
                ));
            }
            hangings.entry((part, number)).or_default()[which] = Some(measured);
        } else if KEPT.contains(&key) {
            other.push((key.to_string(), measured));
        } else {
            return Err(error(
                line,
                Some(key),
                "unknown key: not a measurement of BicycleParameters' raw data".into(),
            ));
        }
    }
    let mut missing: Vec<String> = SCALARS
        .iter()
        .filter(|(k, _)| !scalars.contains_key(k))
        .map(|(k, feeds)| format!("{k} is missing: {feeds} needs it"))
        .collect();
    let mut frames: [Vec<Hanging>; 2] = [Vec::new(), Vec::new()];
    for (slot, part, name) in [(0, 'B', "rear"), (1, 'H', "front")] {
        let count = hangings
            .keys()
            .filter(|(p, _)| *p == part)
            .map(|(_, n)| *n)
            .max()
            .unwrap_or(0);
        if count == 0 {
            missing.push(format!(
                "alpha{part}1 is missing: the {name} frame's mass centre and inertia need its hangings (alpha{part}i, a{part}i, Tt{part}i)"
            ));
        }
        for number in 1..=count {
            let set = hangings.get(&(part, number)).copied().unwrap_or_default();
            match set {
                [Some(alpha), Some(a), Some(period)] => {
                    frames[slot].push(Hanging { alpha, a, period })
                }
                _ => {
                    for (which, prefix) in ["alpha", "a", "Tt"].iter().enumerate() {
                        if set[which].is_none() {
                            missing.push(format!(
                                "{prefix}{part}{number} is missing: the {name} frame's hanging {number} needs it"
                            ));
                        }
                    }
                }
            }
        }
    }
    if let Some(first) = missing.first() {
        let field = first.split(' ').next().unwrap_or("").to_string();
        let more = if missing.len() > 1 {
            format!(
                " (and {} more: {})",
                missing.len() - 1,
                missing[1..].join("; ")
            )
        } else {
            String::new()
        };
        return Err(error(0, Some(&field), format!("{first}{more}")));
    }
    let get = |k: &str| {
        scalars
            .get(k)
            .copied()
            .unwrap_or(Measured::new(f64::NAN, 0.0))
    };
    let [rear_frame, front_frame] = frames;
    Ok(MeasuredFile {
        measurements: Measurements {
            g: get("g"),
            d_r: get("dR"),
            n_r: get("nR"),
            d_f: get("dF"),
            n_f: get("nF"),
            w: get("w"),
            gamma: get("gamma"),
            f: get("f"),
            m_r: get("mR"),
            m_f: get("mF"),
            m_b: get("mB"),
            m_h: get("mH"),
            l_r: get("lR"),
            l_f: get("lF"),
            t_c_r: get("TcR1"),
            t_c_f: get("TcF1"),
            t_c_b: get("TcB1"),
            t_c_h: get("TcH1"),
            t_t_r: get("TtR1"),
            t_t_f: get("TtF1"),
            m_p: get("mP"),
            l_p: get("lP"),
            d_p: get("dP"),
            t_t_p: get("TtP1"),
            rear_frame,
            front_frame,
        },
        other,
    })
}
