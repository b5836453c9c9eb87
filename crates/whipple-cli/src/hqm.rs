//! `whipple control hqm`: Hess's handling quality metric as HumanControl computes it, with the
//! gains of a HumanControl SteerGains file. At one speed: the gains, whether the roll loop is
//! stable, and the peak of |HQM(jω)| over frequency (certified by the library); over speeds, a
//! table of the peaks; with `--vary NAME=START:STOP:COUNT`, the peaks against one parameter of
//! the bicycle at one speed. `--plot` draws |HQM(jω)| against ω (one speed) or the peaks.

use std::fmt::Write as _;
use std::path::PathBuf;
use whipple_front::units::SpeedUnit;

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::json;
use whipple::advanced::control::{
    GainTable, HandlingQuality, HandlingRow, Neuromuscular, handling_against_parameter,
    handling_against_speed,
};
use whipple_report::{Dash, Marker, Series, XyPlotOptions, line_plot};

use crate::TextFormat;
use crate::bike::{RunContext, load};
use crate::commands::emit;
use crate::output::number;

/// The most speeds `hqm --speeds` evaluates.
pub const MAX_HQM_SPEEDS: usize = 100_000;

/// The most points of a drawn |HQM(jω)| curve.
const PLOT_POINTS: usize = 2000;

/// The arguments of `whipple control hqm`.
#[derive(Args)]
pub struct HqmArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    bike: String,
    /// The rider's gains: a HumanControl `<Name>SteerGains.txt` file (speed, kDelta, kPhiDot,
    /// kPhi, kPsi, kY), interpolated linearly in speed; outside its speeds extrapolated, and
    /// said so.
    #[arg(long)]
    gains: PathBuf,
    /// Forward speed in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true, conflicts_with = "speeds")]
    speed: Option<crate::TypedSpeed>,
    /// Speeds START:STOP:STEP in m/s (or km/h after them), both ends included: the peak against speed.
    #[arg(long, allow_hyphen_values = true)]
    speeds: Option<String>,
    /// One parameter of the bicycle varied at --speed, the gains held at that speed's:
    /// NAME=START:STOP:COUNT as `whipple design` takes its axes (`trail=0:0.2:21`,
    /// `head_angle_deg=60:80:21`); prints the peak against the parameter.
    #[arg(long, allow_hyphen_values = true, requires = "speed")]
    vary: Option<String>,
    /// The neuromuscular filter's natural frequency in rad/s.
    #[arg(long, default_value_t = whipple::advanced::control::NEUROMUSCULAR_FREQUENCY, allow_hyphen_values = true)]
    neuro_frequency: f64,
    /// The neuromuscular filter's damping ratio.
    #[arg(long, default_value_t = whipple::advanced::control::NEUROMUSCULAR_DAMPING, allow_hyphen_values = true)]
    neuro_damping: f64,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    format: TextFormat,
    /// Write to this file instead of standard output.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also draw |HQM(jω)| against ω (with --speed) or the peak against speed (with --speeds)
    /// to this .svg or .png file.
    #[arg(long)]
    plot: Option<PathBuf>,
}

fn lookup_word(table: &GainTable, v: f64, extrapolated: bool) -> &'static str {
    if extrapolated {
        "extrapolated"
    } else if table.speeds().contains(&v) {
        "tabulated"
    } else {
        "interpolated"
    }
}

/// Runs `whipple control hqm`.
pub fn run(cx: &RunContext, args: &HqmArgs) -> Result<()> {
    let (out, plot) = crate::output::table_and_plot(args.out.as_deref(), args.plot.as_deref())?;
    let neuromuscular = Neuromuscular {
        frequency: args.neuro_frequency,
        damping: args.neuro_damping,
    };
    let bike = load(cx, &args.bike)?;
    let table = crate::bike::read_gains_file(&args.gains)?;
    let gains_name = args
        .gains
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let unit = args
        .speed
        .map_or(SpeedUnit::MetresPerSecond, |typed| typed.unit);
    let (text, figure) = match (args.speed.map(|typed| typed.si), args.speeds.as_deref()) {
        (Some(v), None) if args.vary.is_some() => {
            let spec = args.vary.as_deref().unwrap_or_default();
            let axis =
                whipple_front::design::AxisSpec::parse(spec, &bike.bicycle).context("--vary")?;
            let lookup = table.at(v).context("--speed")?;
            if lookup.extrapolated {
                eprintln!(
                    "warning: {} m/s is outside {gains_name}'s speeds: the gains are extrapolated",
                    number(v)?
                );
            }
            let values: Vec<f64> = (0..axis.axis.count)
                .map(|i| axis.axis.si_value(i))
                .collect();
            let rows = handling_against_parameter(
                &bike.bicycle,
                &axis.axis.parameter,
                &values,
                v,
                &lookup.gains,
                &neuromuscular,
            )
            .with_context(|| format!("the handling quality metric against {}", axis.name))?;
            let xs: Vec<f64> = (0..rows.len()).map(|i| axis.value(i)).collect();
            let words = vec![lookup_word(&table, v, lookup.extrapolated); rows.len()];
            let x_name = format!("{} [{}]", axis.name, axis.unit());
            let title = format!(
                "{}: peak HQM against {} at {} ({gains_name})",
                bike.label,
                axis.name,
                crate::output::speed_words(v, unit)?
            );
            sweep(
                &bike.label,
                &gains_name,
                &x_name,
                &title,
                &xs,
                &rows,
                &words,
                args,
            )?
        }
        (Some(v), None) => one_speed(&bike, &table, &gains_name, (v, unit), &neuromuscular, args)?,
        (None, Some(speeds)) => {
            let ((start, stop, step), unit) = crate::output::parse_triple_in(speeds, "--speeds")?;
            let grid = whipple::speed_grid(start, stop, step).context("--speeds")?;
            if grid.len() > MAX_HQM_SPEEDS {
                bail!(
                    "--speeds: at most {MAX_HQM_SPEEDS} speeds, got {}",
                    grid.len()
                );
            }
            let rows = handling_against_speed(&bike.benchmark, &table, &neuromuscular, &grid)
                .context("the handling quality metric against speed")?;
            let extrapolated = rows.iter().filter(|r| r.extrapolated).count();
            if extrapolated > 0 {
                eprintln!(
                    "warning: {extrapolated} of the speeds are outside {gains_name}'s speeds: \
                     their gains are extrapolated"
                );
            }
            // The speeds as typed: in km/h where they were (the JSON's `speed` stays m/s).
            let xs: Vec<f64> = rows
                .iter()
                .map(|r| crate::output::as_typed(r.speed, unit))
                .collect();
            let words: Vec<&str> = rows
                .iter()
                .map(|r| lookup_word(&table, r.speed, r.extrapolated))
                .collect();
            let title = format!("{}: peak HQM against speed ({gains_name})", bike.label);
            sweep(
                &bike.label,
                &gains_name,
                &format!("speed [{}]", unit.symbol()),
                &title,
                &xs,
                &rows,
                &words,
                args,
            )?
        }
        _ => bail!("give --speed V or --speeds START:STOP:STEP"),
    };
    if let (Some(target), Some(figure)) = (plot, figure) {
        let bytes = figure
            .render_for_path(target.path())
            .with_context(|| format!("drawing {}", target.path().display()))?;
        target.write_whole(&bytes)?;
    }
    emit(&text, out.as_ref())
}

type Output = (String, Option<whipple_report::Figure>);

fn one_speed(
    bike: &crate::bike::LoadedBike,
    table: &GainTable,
    gains_name: &str,
    (v, unit): (f64, SpeedUnit),
    neuromuscular: &Neuromuscular,
    args: &HqmArgs,
) -> Result<Output> {
    let lookup = table.at(v).context("--speed")?;
    let hqm = HandlingQuality::new(&bike.benchmark, v, &lookup.gains, neuromuscular)
        .with_context(|| format!("the handling quality metric at {v} m/s"))?;
    let peak = hqm
        .peak()
        .context("the peak of the handling quality metric")?;
    let stable = hqm.is_stable();
    let how = lookup_word(table, v, lookup.extrapolated);
    if lookup.extrapolated {
        eprintln!(
            "warning: {} m/s is outside {gains_name}'s speeds ({} to {} m/s): the gains are \
             extrapolated",
            number(v)?,
            number(table.speeds()[0])?,
            number(table.speeds()[table.speeds().len() - 1])?
        );
    }
    if !stable {
        eprintln!(
            "warning: the roll loop is unstable with these gains: the handling quality metric \
             is not meaningful"
        );
    }
    let g = lookup.gains;
    number(peak.magnitude)?;
    let text = match args.format {
        TextFormat::Json => {
            let doc = json!({
                "bicycle": bike.label,
                "speed": v,
                "gains_file": gains_name,
                "gains": {"kDelta": g.k_delta, "kPhiDot": g.k_phi_dot, "kPhi": g.k_phi,
                          "kPsi": g.k_psi, "kY": g.k_y},
                "gains_lookup": how,
                "neuromuscular": {"frequency": neuromuscular.frequency,
                                  "damping": neuromuscular.damping},
                "roll_loop_stable": stable,
                "peak": {"magnitude": peak.magnitude,
                         "frequency": peak.frequency, "certified": peak.certified},
                "numerator": hqm.numerator(),
                "denominator": hqm.denominator(),
                "warnings": bike.warnings_json(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            writeln!(t, "bicycle: {}", bike.label)?;
            writeln!(t, "speed: {}", crate::output::speed_words(v, unit)?)?;
            writeln!(
                t,
                "gains ({gains_name}, {how}): kDelta = {}, kPhiDot = {}, kPhi = {}",
                number(g.k_delta)?,
                number(g.k_phi_dot)?,
                number(g.k_phi)?
            )?;
            writeln!(
                t,
                "neuromuscular filter: ω = {} rad/s, ζ = {}",
                number(neuromuscular.frequency)?,
                number(neuromuscular.damping)?
            )?;
            writeln!(
                t,
                "roll loop: {}",
                if stable { "stable" } else { "UNSTABLE" }
            )?;
            writeln!(
                t,
                "peak HQM = {:.6} at ω = {:.6} rad/s ({})",
                peak.magnitude,
                peak.frequency,
                if peak.certified {
                    "certified"
                } else {
                    "a critical point unresolved: not certified"
                }
            )?;
            t
        }
    };
    let figure = match args.plot {
        Some(_) => {
            let top = 40f64.max(2.0 * peak.frequency);
            let grid: Vec<f64> = (0..PLOT_POINTS)
                .map(|k| top * k as f64 / (PLOT_POINTS - 1) as f64)
                .collect();
            let magnitude = hqm.magnitude(&grid)?;
            let curve: Vec<(f64, f64)> = grid.into_iter().zip(magnitude).collect();
            let options = XyPlotOptions {
                title: Some(format!(
                    "{} at {}: peak HQM {:.3} at {:.3} rad/s",
                    bike.label,
                    crate::output::speed_label(v, unit)?,
                    peak.magnitude,
                    peak.frequency
                )),
                x_label: "frequency ω [rad/s]".into(),
                y_label: "|HQM(jω)|".into(),
                ..XyPlotOptions::default()
            };
            let mut series = vec![Series::new("|HQM(jω)|", curve).coloured(0)];
            series.extend(hess_levels(0.0, top));
            Some(line_plot(&series, &[], &options)?)
        }
        None => None,
    };
    Ok((text, figure))
}

/// Hess's levels: peaks below 5 read as good handling, above 8 as poor.
fn hess_levels(lo: f64, hi: f64) -> [Series; 2] {
    [
        Series::new("5 (Hess: good below)", vec![(lo, 5.0), (hi, 5.0)])
            .coloured(6)
            .dashed(Dash::Dashed),
        Series::new("8 (Hess: poor above)", vec![(lo, 8.0), (hi, 8.0)])
            .coloured(6)
            .dashed(Dash::Dotted),
    ]
}

/// A sweep's table (or JSON) and figure: one row per value `xs[i]` of the swept quantity.
#[allow(clippy::too_many_arguments)]
fn sweep(
    label: &str,
    gains_name: &str,
    x_name: &str,
    title: &str,
    xs: &[f64],
    rows: &[HandlingRow],
    words: &[&str],
    args: &HqmArgs,
) -> Result<Output> {
    let text = match args.format {
        TextFormat::Json => {
            let mut list = Vec::with_capacity(rows.len());
            for ((x, r), word) in xs.iter().zip(rows).zip(words) {
                number(r.peak.magnitude)?;
                list.push(json!({
                    "value": x,
                    "speed": r.speed,
                    "peak": r.peak.magnitude,
                    "frequency": r.peak.frequency,
                    "certified": r.peak.certified,
                    "roll_loop_stable": r.stable,
                    "gains_lookup": word,
                    "gains": r.gains.to_array(),
                }));
            }
            let doc = json!({"bicycle": label, "gains_file": gains_name, "swept": x_name,
                             "rows": list});
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            writeln!(t, "bicycle: {label}; gains: {gains_name}")?;
            writeln!(
                t,
                "{:>16} {:>12} {:>14} {:>10} {:>13}",
                x_name, "peak HQM", "ω [rad/s]", "roll loop", "gains"
            )?;
            for ((x, r), word) in xs.iter().zip(rows).zip(words) {
                writeln!(
                    t,
                    "{:>16} {:>12.6} {:>14.6} {:>10} {:>13}{}",
                    number(*x)?,
                    r.peak.magnitude,
                    r.peak.frequency,
                    if r.stable { "stable" } else { "UNSTABLE" },
                    word,
                    if r.peak.certified {
                        ""
                    } else {
                        " (not certified)"
                    }
                )?;
            }
            t
        }
    };
    let figure = match args.plot {
        Some(_) => {
            let points: Vec<(f64, f64)> = xs
                .iter()
                .zip(rows)
                .map(|(x, r)| (*x, r.peak.magnitude))
                .collect();
            let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            // Where the roll loop is unstable the metric means nothing: marked (the first five
            // such values; the table names them all).
            let markers: Vec<Marker> = xs
                .iter()
                .zip(rows)
                .filter(|(_, r)| !r.stable)
                .take(5)
                .map(|(&x, _)| Marker {
                    x,
                    label: "roll loop unstable".into(),
                })
                .collect();
            let options = XyPlotOptions {
                title: Some(title.to_string()),
                x_label: x_name.to_string(),
                y_label: "max |HQM(jω)|".into(),
                ..XyPlotOptions::default()
            };
            let mut series = vec![Series::new("peak HQM", points).coloured(0)];
            series.extend(hess_levels(lo, hi));
            Some(line_plot(&series, &markers, &options)?)
        }
        None => None,
    };
    Ok((text, figure))
}
