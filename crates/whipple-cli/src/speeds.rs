//! `whipple speeds`: the certified critical speeds and self-stable ranges, on the whole
//! half-line of forward speeds unless `--range` narrows it.

use std::fmt::Write as _;

use anyhow::{Context, Result, anyhow, bail};
use serde_json::json;
use whipple::CriticalSpeeds;
use whipple::advanced::sensitivity;
use whipple::advanced::sensitivity::CriticalSpeedsSigma;

use crate::TextFormat;
use crate::bike::{RunContext, load};
use crate::commands::{emit, optional, round_sigma, round_to_sigma, with_sigma};
use crate::output::{kmh_beside, kmh_number, number};
use whipple_front::units::SpeedUnit;

/// The rule of a whipple-front error about an argument, without its `speed: ` prefix.
pub fn rule_of(e: whipple::Error) -> String {
    match e {
        whipple::Error::InvalidArgument { rule, .. } => rule,
        other => other.to_string(),
    }
}

/// Parses speeds `LO:HI` where either end may be `inf` (or left empty: `4:` is every speed from
/// 4 m/s up, `:10` every speed up to 10 m/s); `km/h` after them (`15:25km/h`) gives them in km/h.
pub fn parse_range(text: &str, option: &str) -> Result<(f64, f64)> {
    Ok(parse_range_in(text, option)?.0)
}

/// [`parse_range`], with the unit the speeds were typed in.
pub fn parse_range_in(text: &str, option: &str) -> Result<((f64, f64), SpeedUnit)> {
    let (numbers, unit) =
        whipple_front::units::split_speed(text).map_err(|e| anyhow!("{option}: {}", rule_of(e)))?;
    let (lo, hi) = parse_range_numbers(numbers, text, option)?;
    Ok(((unit.to_si(lo), unit.to_si(hi)), unit))
}

fn parse_range_numbers(numbers: &str, text: &str, option: &str) -> Result<(f64, f64)> {
    let parts: Vec<&str> = numbers.split(':').collect();
    if parts.len() != 2 {
        bail!("{option} expects LO:HI (HI may be `inf`), got `{text}`");
    }
    let end = |t: &str, missing: f64| -> Result<f64> {
        let t = t.trim();
        if t.is_empty() {
            return Ok(missing);
        }
        match t.to_ascii_lowercase().as_str() {
            "inf" | "+inf" | "infinity" => return Ok(f64::INFINITY),
            "-inf" | "-infinity" => return Ok(f64::NEG_INFINITY),
            _ => {}
        }
        let x: f64 = t
            .parse()
            .with_context(|| format!("{option}: `{t}` is not a number"))?;
        if !x.is_finite() {
            bail!("{option}: `{t}` is not a finite number (write `inf` for no bound)");
        }
        Ok(x)
    };
    let lo = end(parts[0], f64::NEG_INFINITY)?;
    let hi = end(parts[1], f64::INFINITY)?;
    if lo >= hi {
        bail!("{option}: LO ({lo}) must be less than HI ({hi})");
    }
    Ok((lo, hi))
}

/// `lo..hi` in words: "every speed v ≥ 0 m/s", "0..20 m/s"; typed in km/h, with km/h beside:
/// "2.7777777777777777..8.333333333333334 m/s (10..30 km/h)".
pub fn range_words(lo: f64, hi: f64, unit: SpeedUnit) -> Result<String> {
    let kmh = unit == SpeedUnit::KilometresPerHour;
    let beside = |a: Option<f64>, b: Option<f64>| -> Result<String> {
        if !kmh {
            return Ok(String::new());
        }
        Ok(match (a, b) {
            (Some(a), Some(b)) => format!(" ({}..{} km/h)", kmh_number(a)?, kmh_number(b)?),
            (Some(x), None) | (None, Some(x)) => format!(" ({} km/h)", kmh_number(x)?),
            (None, None) => String::new(),
        })
    };
    Ok(match (lo.is_finite(), hi.is_finite()) {
        (true, true) => format!(
            "{}..{} m/s{}",
            number(lo)?,
            number(hi)?,
            beside(Some(lo), Some(hi))?
        ),
        (true, false) => format!(
            "every speed v >= {} m/s{}",
            number(lo)?,
            beside(Some(lo), None)?
        ),
        (false, true) => format!(
            "every speed v <= {} m/s{}",
            number(hi)?,
            beside(None, Some(hi))?
        ),
        (false, false) => "every speed".to_string(),
    })
}

/// An end of a stable range, `value ± σ` where it has a σ (as the speeds above print), in
/// m/s, or in km/h (`unit`).
fn range_end(x: f64, sd: Option<f64>, unit: SpeedUnit) -> Result<String> {
    Ok(match sd {
        Some(s) if s > 0.0 => {
            let (x, s) = (unit.from_si(x), unit.from_si(s));
            format!("{} ± {}", round_to_sigma(x, s), round_sigma(s))
        }
        _ if unit == SpeedUnit::KilometresPerHour => kmh_number(x)?,
        _ => number(x)?,
    })
}

/// A stable range in words; `sd` holds its ends' σ where the bicycle has σ; typed in km/h,
/// its ends in km/h beside.
fn stable_words(
    s: &CriticalSpeeds,
    a: f64,
    b: f64,
    sd: (Option<f64>, Option<f64>),
    unit: SpeedUnit,
) -> Result<String> {
    let kmh = |x: f64, sd: Option<f64>| -> Result<String> {
        Ok(match unit {
            SpeedUnit::MetresPerSecond => String::new(),
            SpeedUnit::KilometresPerHour => {
                format!(
                    " ({} km/h)",
                    range_end(x, sd, SpeedUnit::KilometresPerHour)?
                )
            }
        })
    };
    let m_s = SpeedUnit::MetresPerSecond;
    let (lo, hi) = s.range;
    Ok(if b == f64::INFINITY {
        format!(
            "above {} m/s{} (at every higher speed)",
            range_end(a, sd.0, m_s)?,
            kmh(a, sd.0)?
        )
    } else if let Some(open) = s
        .unresolved
        .iter()
        .find(|u| u.0 <= b && u.1 == f64::INFINITY)
    {
        format!(
            "above {} m/s{} (certified up to {} m/s; above that, round-off in the matrices \
             leaves it open)",
            range_end(a, sd.0, m_s)?,
            kmh(a, sd.0)?,
            number(open.0)?
        )
    } else if a == f64::NEG_INFINITY {
        format!("below {} m/s{}", range_end(b, sd.1, m_s)?, kmh(b, sd.1)?)
    } else {
        let open_end = if b == hi && hi.is_finite() {
            " (up to the end of the range)"
        } else if a == lo && lo.is_finite() && lo != 0.0 {
            " (from the start of the range)"
        } else {
            ""
        };
        let beside = match unit {
            SpeedUnit::MetresPerSecond => String::new(),
            SpeedUnit::KilometresPerHour => format!(
                " ({} .. {} km/h)",
                range_end(a, sd.0, unit)?,
                range_end(b, sd.1, unit)?
            ),
        };
        format!(
            "{} .. {} m/s{beside}{open_end}",
            range_end(a, sd.0, m_s)?,
            range_end(b, sd.1, m_s)?
        )
    })
}

/// The table of `whipple speeds`; with `sigma`, each speed as `value ± σ` (one standard
/// deviation, first order, parameters independent).
/// Typed in km/h (`unit`), every speed and range is given in km/h too, after the m/s.
pub fn table(
    label: &str,
    s: &CriticalSpeeds,
    sigma: Option<&CriticalSpeedsSigma>,
    unit: SpeedUnit,
) -> Result<String> {
    worded_table(label, s, sigma, "self-stable", unit)
}

/// The table of critical speeds, a stable range called `stable` ("self-stable" for the
/// bicycle alone, "stable" for a closed loop); typed in km/h (`unit`), every speed and range
/// in km/h too, after the m/s.
pub fn worded_table(
    label: &str,
    s: &CriticalSpeeds,
    sigma: Option<&CriticalSpeedsSigma>,
    stable: &str,
    unit: SpeedUnit,
) -> Result<String> {
    let (lo, hi) = s.range;
    let where_ = range_words(lo, hi, unit)?;
    let none = if lo == 0.0 && hi == f64::INFINITY {
        "none at any speed".to_string()
    } else {
        format!("none in {where_}")
    };
    // Where the certificate could not decide, "none" or "nowhere" would contradict it.
    let undecided = s
        .unresolved
        .iter()
        .map(|&(a, b)| {
            Ok(if b == f64::INFINITY {
                format!("above {} m/s", number(a)?)
            } else {
                format!("{} .. {} m/s", number(a)?, number(b)?)
            })
        })
        .collect::<Result<Vec<_>>>()?
        .join(", ");
    let none = if undecided.is_empty() {
        none
    } else {
        format!("none certified (undecided in {undecided})")
    };
    let show = |x: Option<f64>, sd: Option<f64>| -> Result<String> {
        Ok(match x {
            Some(v) if sigma.is_some() => {
                let mut t = with_sigma(v, sd, "m/s")?;
                if unit == SpeedUnit::KilometresPerHour {
                    match sd {
                        Some(sd) if sd > 0.0 => write!(
                            t,
                            " ({})",
                            with_sigma(unit.from_si(v), Some(unit.from_si(sd)), "km/h")?
                        )?,
                        _ => t.push_str(&kmh_beside(v, unit)?),
                    }
                }
                t
            }
            Some(v) => format!("{} m/s{}", number(v)?, kmh_beside(v, unit)?),
            None => none.clone(),
        })
    };
    let mut t = format!("{label}: critical speeds for {where_} (certified)");
    if sigma.is_some() {
        t.push_str(" (± one standard deviation, first order, parameters independent)");
    }
    t.push('\n');
    match &s.double_root_unavailable {
        Some(why) => write!(t, "  double root speed v_d  not given: {why}")?,
        None => write!(
            t,
            "  double root speed v_d  {}",
            show(
                s.double_root_speed,
                sigma.and_then(|u| u.double_root_speed_sigma)
            )?
        )?,
    }
    if let Some(l) = s.double_root_eigenvalue {
        write!(t, "  (double eigenvalue {} 1/s)", number(l)?)?;
    }
    write!(
        t,
        "\n  weave speed v_w        {}",
        show(s.weave_speed, sigma.and_then(|u| u.weave_speed_sigma))?
    )?;
    if let Some(w) = s.weave_frequency {
        write!(t, "  (weave frequency {} rad/s)", number(w)?)?;
    }
    writeln!(
        t,
        "\n  capsize speed v_c      {}",
        show(s.capsize_speed, sigma.and_then(|u| u.capsize_speed_sigma))?
    )?;
    if s.stable_speed_ranges.is_empty() {
        if undecided.is_empty() {
            writeln!(t, "  {stable:<22} nowhere in {where_}")?;
        } else {
            writeln!(
                t,
                "  {stable:<22} undecided in {undecided}; nowhere else in {where_}"
            )?;
        }
    }
    for (k, &(a, b)) in s.stable_speed_ranges.iter().enumerate() {
        let sd = sigma
            .and_then(|u| u.stable_speed_ranges_sigma.get(k).copied())
            .unwrap_or((None, None));
        writeln!(t, "  {stable:<22} {}", stable_words(s, a, b, sd, unit)?)?;
    }
    for &(a, b) in &s.unresolved {
        if b == f64::INFINITY {
            writeln!(
                t,
                "  not decided            above {} m/s: a coefficient's sign is lost to round-off \
                 in the stored matrices there",
                number(a)?
            )?;
        } else {
            writeln!(
                t,
                "  not decided            {} .. {} m/s: round-off cannot place where the \
                 stability changes inside this interval (roots closer than round-off, or a \
                 crossing known only to this width); the stability there cannot be told in \
                 double precision",
                number(a)?,
                number(b)?
            )?;
        }
    }
    Ok(t)
}

pub fn speeds(cx: &RunContext, arg: &str, range: Option<&str>, format: TextFormat) -> Result<()> {
    let bike = load(cx, arg)?;
    let ((lo, hi), unit) = match range {
        Some(text) => parse_range_in(text, "--range")?,
        None => ((0.0, f64::INFINITY), SpeedUnit::MetresPerSecond),
    };
    // The certified speeds, with their first-order standard deviations where the file gives
    // the parameters' (the speeds are the same as whipple::critical_speeds gives).
    let su = sensitivity::critical_speeds_sigma(&bike.bicycle, lo, hi)
        .with_context(|| format!("critical speeds of {}", bike.label))?;
    let s = &su.speeds;
    let uncertain = bike.bicycle.has_uncertainty();
    let text = match format {
        TextFormat::Json => {
            let mut doc = serde_json::to_value(s)?;
            if let Some(map) = doc.as_object_mut() {
                map.insert("bike".into(), json!(bike.label));
                map.insert("warnings".into(), bike.warnings_json());
                if uncertain {
                    let ranges = su
                        .stable_speed_ranges_sigma
                        .iter()
                        .map(|(a, b)| Ok(json!([optional(*a)?, optional(*b)?])))
                        .collect::<Result<Vec<_>>>()?;
                    map.insert(
                        "double_root_speed_sigma".into(),
                        optional(su.double_root_speed_sigma)?,
                    );
                    map.insert("weave_speed_sigma".into(), optional(su.weave_speed_sigma)?);
                    map.insert(
                        "capsize_speed_sigma".into(),
                        optional(su.capsize_speed_sigma)?,
                    );
                    map.insert("stable_speed_ranges_sigma".into(), json!(ranges));
                }
            }
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => table(&bike.label, s, uncertain.then_some(&su), unit)?,
    };
    emit(&text, None)
}
