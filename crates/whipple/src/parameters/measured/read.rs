//! BicycleParameters' `*Measured.txt`: one `key = value` a line, a value optionally followed by
//! `+/-` and its standard deviation, repeated measurements as a comma-separated list (their
//! mean is used), `#` starting a comment. Every key is checked: the measurements the pipeline
//! needs, the rider's seat and handlebar geometry kept for later, anything else an error.

use std::collections::BTreeMap;

use super::{
    Flywheel, FrontFrame, Geometry, HandlebarReference, Hanging, HungPart, Measured, Measurements,
    Offsets,
};
use crate::error::{Error, Result};
use crate::parameters::io::MAX_FILE_BYTES;

const FORMAT: &str = "BicycleParameters Measured .txt";

/// The most hangings of one frame a file may give (`alphaB1` … `alphaB16`).
pub const MAX_HANGINGS: usize = 16;

/// The most values in one key's list of repeated measurements.
const MAX_REPEATS: usize = 64;

/// The scalar measurements every file needs, with what each one feeds (for a missing key's
/// message).
const COMMON: [(&str, &str); 19] = [
    ("g", "every compound pendulum's inertia"),
    ("dR", "the rear wheel's radius"),
    ("nR", "the rear wheel's radius"),
    ("dF", "the front wheel's radius"),
    ("nF", "the front wheel's radius"),
    ("mR", "the rear wheel's mass and IRyy"),
    ("mF", "the front wheel's mass and IFyy"),
    ("mB", "the rear frame's mass and IByy"),
    ("lR", "the rear wheel's IRyy (compound pendulum length)"),
    ("lF", "the front wheel's IFyy (compound pendulum length)"),
    ("TcR1", "the rear wheel's IRyy"),
    ("TcF1", "the front wheel's IFyy"),
    ("TcB1", "the rear frame's IByy"),
    ("TtR1", "the rear wheel's IRxx"),
    ("TtF1", "the front wheel's IFxx"),
    ("mP", "the torsion constant (calibration rod)"),
    ("lP", "the torsion constant (calibration rod)"),
    ("dP", "the torsion constant (calibration rod)"),
    ("TtP1", "the torsion constant (calibration rod)"),
];

/// The geometry measured directly.
const DIRECT: [(&str, &str); 3] = [
    ("w", "the wheelbase"),
    ("gamma", "the steer axis tilt"),
    ("f", "the trail"),
];

/// What the perpendicular distances feed.
const OFFSETS_FEED: &str =
    "the steer axis tilt, the wheelbase and the trail (geometry as perpendicular distances)";

/// The geometry measured as perpendicular distances.
const OFFSETS: [&str; 10] = ["h1", "h2", "h3", "h4", "h5", "d1", "d2", "d3", "d4", "d"];

/// The front frame measured as one.
const WHOLE: [(&str, &str); 2] = [
    ("mH", "the front frame's mass and IHyy"),
    ("TcH1", "the front frame's IHyy"),
];

/// The fork and the handlebar measured apart.
const SPLIT: [(&str, &str); 9] = [
    ("mS", "the fork's mass, ISyy and the front frame's mass"),
    (
        "mG",
        "the handlebar's mass, IGyy and the front frame's mass",
    ),
    ("TcS1", "the fork's ISyy"),
    ("TcG1", "the handlebar's IGyy"),
    (
        "h6",
        "the handlebar's reference point (front axle's height)",
    ),
    (
        "h7",
        "the handlebar's reference point (reference circle's height)",
    ),
    (
        "d5",
        "the handlebar's reference point (front axle's diameter)",
    ),
    (
        "d6",
        "the handlebar's reference point (reference circle's diameter)",
    ),
    ("l", "the handlebar's reference point (axle to circle)"),
];

/// A flywheel inside the front wheel.
const FLYWHEEL: [(&str, &str); 3] = [
    ("mD", "the flywheel's mass (front wheel with flywheel)"),
    (
        "TcD1",
        "the flywheel's IDyy (front wheel with flywheel, compound pendulum)",
    ),
    (
        "TtD1",
        "the flywheel's IDxx (front wheel with flywheel, torsional pendulum)",
    ),
];

/// Whether `key` is one of the scalar measurements.
fn is_scalar(key: &str) -> bool {
    COMMON.iter().any(|(k, _)| *k == key)
        || DIRECT.iter().any(|(k, _)| *k == key)
        || OFFSETS.contains(&key)
        || WHOLE.iter().any(|(k, _)| *k == key)
        || SPLIT.iter().any(|(k, _)| *k == key)
        || FLYWHEEL.iter().any(|(k, _)| *k == key)
}

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
    /// The periods the file lacked, fitted from records ([`read_measurements_with_records`]),
    /// in the order asked.
    pub fitted: Vec<FittedPeriod>,
}

/// A period the file lacked, taken from its records.
#[derive(Debug, Clone, PartialEq)]
pub struct FittedPeriod {
    /// Its key (`TcB1`, `TtH2`).
    pub key: String,
    /// The period with its σ (the mean of the trials' fits, σ = √(Σσᵢ²)/n).
    pub period: Measured,
    /// Where it came from, as the caller words it (the record files).
    pub source: String,
}

/// The name BicycleParameters gives a period's records without the bicycle's name and the
/// trial's number: `TcH1` → `ForkCompoundFirst` (its files are
/// `<Name>ForkCompoundFirst1.mat`, `…2.mat`, …). The part's word: `Frame` (B), `Fork` (H, or
/// S when the handlebar was measured apart), `Handlebar` (G), `Fwheel` (F), `Rwheel` (R),
/// `Flywheel` (D), `Rod` (P); the pendulum: `Compound` (Tc) or `Torsional` (Tt); the hanging's
/// ordinal `First` … `Sixth`. `None` for a key that is not a period or has no such name.
pub fn record_name(key: &str) -> Option<String> {
    let (pendulum, rest) = if let Some(rest) = key.strip_prefix("Tc") {
        ("Compound", rest)
    } else {
        ("Torsional", key.strip_prefix("Tt")?)
    };
    let mut chars = rest.chars();
    let part = match chars.next()? {
        'B' => "Frame",
        'H' | 'S' => "Fork",
        'G' => "Handlebar",
        'F' => "Fwheel",
        'R' => "Rwheel",
        'D' => "Flywheel",
        'P' => "Rod",
        _ => return None,
    };
    let ordinal = match chars.as_str() {
        "1" => "First",
        "2" => "Second",
        "3" => "Third",
        "4" => "Fourth",
        "5" => "Fifth",
        "6" => "Sixth",
        _ => return None,
    };
    Some(format!("{part}{pendulum}{ordinal}"))
}

/// What a caller gives for a period the file lacks: `Ok(Some((period, source)))` from its
/// records, `Ok(None)` to leave it missing, or an error naming the key and what was looked
/// for.
pub type PeriodSource<'a> = dyn FnMut(&str) -> Result<Option<(Measured, String)>> + 'a;

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

/// A hanging key (`alphaB2`, `aH1`, `TtB3`): which frame, which of the three, its number.
fn hanging_key(key: &str) -> Option<(char, usize, usize)> {
    for (which, prefix) in [(0, "alpha"), (2, "Tt"), (1, "a")] {
        if let Some(rest) = key.strip_prefix(prefix) {
            let mut chars = rest.chars();
            let part = chars.next()?;
            let number: usize = chars.as_str().parse().ok()?;
            if matches!(part, 'B' | 'H' | 'S' | 'G') && number >= 1 {
                return Some((part, which, number));
            }
        }
    }
    None
}

/// Reads a `*Measured.txt` (BicycleParameters' raw data, Moore 2012 ch. 2). Errors name the key
/// and its line; a missing measurement is named with what it feeds. A hanging's distance
/// (`aB4`) given without its angle and period is no hanging, as BicycleParameters reads it:
/// it is kept in [`MeasuredFile::other`].
///
/// ```
/// use whipple::advanced::measured::read_measurements;
/// let file = read_measurements("g = 9.81 +/- 0.01\nnF = 13, 14\n");
/// let message = file.unwrap_err().to_string();
/// assert!(message.contains("dR is missing: the rear wheel's radius needs it"), "{message}");
/// ```
pub fn read_measurements(text: &str) -> Result<MeasuredFile> {
    read_measurements_with_records(text, &mut |_| Ok(None))
}

/// [`read_measurements`], asking `records` for every period the file lacks (as
/// BicycleParameters' `calculate_from_measured` fits them from its rate-gyro records when the
/// file has too few): the compound and torsional periods of the parts measured, and the
/// torsional period of every hanging whose angle and distance are given. The periods given
/// are listed in [`MeasuredFile::fitted`].
pub fn read_measurements_with_records(
    text: &str,
    records: &mut PeriodSource<'_>,
) -> Result<MeasuredFile> {
    if text.len() > MAX_FILE_BYTES {
        return Err(error(
            0,
            None,
            format!("the file is larger than {} MiB", MAX_FILE_BYTES >> 20),
        ));
    }
    let mut scalars: BTreeMap<String, Measured> = BTreeMap::new();
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
        let measured = values(rest, line, key)?;
        if is_scalar(key) {
            scalars.insert(key.to_string(), measured);
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
    // A hanging's distance given without its angle and period describes no hanging (Gyro's
    // aB4): BicycleParameters reads a frame's hangings by their angles and passes it by;
    // it is kept with the other keys.
    let orphans: Vec<(char, usize)> = hangings
        .iter()
        .filter(|(_, h)| h[0].is_none() && h[2].is_none())
        .map(|(k, _)| *k)
        .collect();
    for (part, number) in orphans {
        if let Some([_, Some(a), _]) = hangings.remove(&(part, number)) {
            other.push((format!("a{part}{number}"), a));
        }
    }
    let has = |k: &str| scalars.contains_key(k);
    let line_of = |k: &str| scalars.get(k).map_or(0, |m| m.line);
    // Which forms the file measured, from the keys it gives.
    let offsets = OFFSETS.iter().find(|k| has(k));
    let direct = DIRECT.iter().find(|(k, _)| has(k));
    if let (Some(o), Some((d, _))) = (offsets, direct) {
        return Err(error(
            line_of(o),
            Some(o),
            format!(
                "the geometry is given twice: as perpendicular distances (h1…h5, d1…d4, d) \
                 and as {d} (w, gamma, f, line {}); give one",
                line_of(d)
            ),
        ));
    }
    let split_key = SPLIT
        .iter()
        .map(|(k, _)| k.to_string())
        .chain(
            hangings
                .keys()
                .filter(|(p, _)| matches!(p, 'S' | 'G'))
                .map(|(p, n)| format!("alpha{p}{n}")),
        )
        .find(|k| has(k) || k.starts_with("alpha"));
    let whole_key = WHOLE
        .iter()
        .map(|(k, _)| k.to_string())
        .chain(
            hangings
                .keys()
                .filter(|(p, _)| *p == 'H')
                .map(|(p, n)| format!("alpha{p}{n}")),
        )
        .find(|k| has(k) || k.starts_with("alpha"));
    if let (Some(s), Some(h)) = (&split_key, &whole_key) {
        return Err(error(
            line_of(s),
            Some(s),
            format!(
                "the front frame is given twice: as fork and handlebar apart (parts S and G) \
                 and as one ({h}, part H); give one"
            ),
        ));
    }
    let split = split_key.is_some();
    let flywheel = FLYWHEEL.iter().any(|(k, _)| has(k));
    // The periods the file lacks, from the caller's records.
    let mut periods: Vec<String> = ["TcR1", "TcF1", "TcB1", "TtR1", "TtF1", "TtP1"]
        .iter()
        .map(|k| k.to_string())
        .collect();
    periods.extend(
        if split {
            &["TcS1", "TcG1"][..]
        } else {
            &["TcH1"][..]
        }
        .iter()
        .map(|k| k.to_string()),
    );
    if flywheel {
        periods.extend(["TcD1", "TtD1"].map(String::from));
    }
    for ((part, number), given) in &hangings {
        if given[0].is_some() && given[1].is_some() && given[2].is_none() {
            periods.push(format!("Tt{part}{number}"));
        }
    }
    let mut fitted = Vec::new();
    for key in periods {
        if scalars.contains_key(&key)
            || hanging_key(&key)
                .is_some_and(|(p, _, n)| hangings.get(&(p, n)).is_some_and(|h| h[2].is_some()))
        {
            continue;
        }
        if let Some((period, source)) = records(&key)? {
            if let Some((part, which, number)) = hanging_key(&key) {
                hangings.entry((part, number)).or_default()[which] = Some(period);
            } else {
                scalars.insert(key.clone(), period);
            }
            fitted.push(FittedPeriod {
                key,
                period,
                source,
            });
        }
    }
    let has = |k: &str| scalars.contains_key(k);
    let mut missing: Vec<String> = Vec::new();
    let mut need = |list: &[(&str, &str)]| {
        for (k, feeds) in list {
            if !has(k) {
                missing.push(format!("{k} is missing: {feeds} needs it"));
            }
        }
    };
    need(&COMMON);
    if offsets.is_some() {
        let list: Vec<(&str, &str)> = OFFSETS.iter().map(|k| (*k, OFFSETS_FEED)).collect();
        need(&list);
    } else {
        need(&DIRECT);
    }
    if split {
        need(&SPLIT);
    } else {
        need(&WHOLE);
    }
    if flywheel {
        need(&FLYWHEEL);
    }
    let parts: &[(char, &str)] = if split {
        &[('B', "rear frame"), ('S', "fork"), ('G', "handlebar")]
    } else {
        &[('B', "rear frame"), ('H', "front frame")]
    };
    let mut frames: Vec<Vec<Hanging>> = Vec::new();
    for (part, name) in parts {
        let part = *part;
        let count = hangings
            .keys()
            .filter(|(p, _)| *p == part)
            .map(|(_, n)| *n)
            .max()
            .unwrap_or(0);
        if count == 0 {
            missing.push(format!(
                "alpha{part}1 is missing: the {name}'s mass centre and inertia need its hangings (alpha{part}i, a{part}i, Tt{part}i)"
            ));
        }
        let mut set = Vec::new();
        for number in 1..=count {
            let given = hangings.get(&(part, number)).copied().unwrap_or_default();
            match given {
                [Some(alpha), Some(a), Some(period)] => set.push(Hanging { alpha, a, period }),
                _ => {
                    for (which, prefix) in ["alpha", "a", "Tt"].iter().enumerate() {
                        if given[which].is_none() {
                            missing.push(format!(
                                "{prefix}{part}{number} is missing: the {name}'s hanging {number} needs it"
                            ));
                        }
                    }
                }
            }
        }
        frames.push(set);
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
    let geometry = if offsets.is_some() {
        Geometry::Offsets(Offsets {
            h: [get("h1"), get("h2"), get("h3"), get("h4"), get("h5")],
            d1: get("d1"),
            d2: get("d2"),
            d3: get("d3"),
            d4: get("d4"),
            d: get("d"),
        })
    } else {
        Geometry::Direct {
            w: get("w"),
            gamma: get("gamma"),
            f: get("f"),
        }
    };
    let mut frames = frames.into_iter();
    let rear_frame = frames.next().unwrap_or_default();
    let mut part = |p: &str| HungPart {
        mass: get(&format!("m{p}")),
        compound_period: get(&format!("Tc{p}1")),
        hangings: frames.next().unwrap_or_default(),
    };
    let front_frame = if split {
        let fork = part("S");
        let handlebar = part("G");
        FrontFrame::Split {
            fork,
            handlebar,
            reference: HandlebarReference {
                h6: get("h6"),
                h7: get("h7"),
                d5: get("d5"),
                d6: get("d6"),
                l: get("l"),
            },
        }
    } else {
        FrontFrame::Whole(part("H"))
    };
    let flywheel = flywheel.then(|| Flywheel {
        mass: get("mD"),
        compound_period: get("TcD1"),
        torsional_period: get("TtD1"),
    });
    Ok(MeasuredFile {
        measurements: Measurements {
            g: get("g"),
            d_r: get("dR"),
            n_r: get("nR"),
            d_f: get("dF"),
            n_f: get("nF"),
            geometry,
            m_r: get("mR"),
            m_f: get("mF"),
            m_b: get("mB"),
            l_r: get("lR"),
            l_f: get("lF"),
            t_c_r: get("TcR1"),
            t_c_f: get("TcF1"),
            t_c_b: get("TcB1"),
            t_t_r: get("TtR1"),
            t_t_f: get("TtF1"),
            m_p: get("mP"),
            l_p: get("lP"),
            d_p: get("dP"),
            t_t_p: get("TtP1"),
            rear_frame,
            front_frame,
            flywheel,
        },
        other,
        fitted,
    })
}
