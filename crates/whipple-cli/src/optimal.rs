//! `whipple control optimal-handling`: the design search of BMD 2016 (HumanControl's
//! `optimal_bicycle.m`): the peak HQM at a design speed minimized over chosen parameters
//! within bounds, the rider's gains set for each candidate by Hess 2012's rules. The library
//! runs the search ([`whipple::advanced::control::optimal_handling`]); this prints the base and
//! the best bicycle, every start, and says that a search from several starts is local.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::json;
use whipple::advanced::control::{
    HandlingCandidate, HumanGains, Neuromuscular, OptimalHandlingSettings, optimal_handling,
};
use whipple_front::design::BoundSpec;

use crate::TextFormat;
use crate::bike::{RunContext, load};
use crate::commands::emit;
use crate::output::Target;
use crate::time_response::short;

/// The arguments of `whipple control optimal-handling`.
#[derive(Args)]
pub struct OptimalArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    bike: String,
    /// The design speed in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    speed: crate::TypedSpeed,
    /// A varied parameter and its bounds, NAME=LOW:HIGH, named as `whipple design` names its
    /// axes (`trail=0:0.2`, `head_angle_deg=60:85`, `w=0.8:1.4`, `rF=0.2:0.5`); repeat for
    /// more.
    #[arg(long = "vary", required = true, allow_hyphen_values = true)]
    vary: Vec<String>,
    /// How many starts: the bicycle's own values, then points of a Halton sequence in the box.
    #[arg(long, default_value_t = 6)]
    starts: usize,
    /// The most Nelder–Mead iterations of each start (each evaluates one to n + 2 bicycles).
    #[arg(long, default_value_t = 2000)]
    iterations: usize,
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
}

fn peak_words(c: &HandlingCandidate) -> Result<String> {
    Ok(match (&c.peak, &c.refused) {
        (_, Some(why)) => format!("refused: {why}"),
        (Some(p), None) if c.stable => format!(
            "{} at {} rad/s{}",
            short(p.magnitude)?,
            short(p.frequency)?,
            if p.certified { "" } else { " (not certified)" }
        ),
        (Some(p), None) => format!(
            "UNSTABLE loop (the peak {} is not a handling quality)",
            short(p.magnitude)?
        ),
        (None, None) => "none".into(),
    })
}

fn candidate_json(c: &HandlingCandidate, specs: &[BoundSpec]) -> serde_json::Value {
    json!({
        "values": specs.iter().zip(&c.values).map(|(s, &x)| s.from_si(x)).collect::<Vec<f64>>(),
        "cost": c.cost,
        "stable": c.stable,
        "peak": c.peak.map(|p| json!({
            "magnitude": p.magnitude, "frequency": p.frequency, "certified": p.certified,
        })),
        "gains": c.gains.map(|g| g.to_array()),
        "refused": c.refused,
    })
}

/// Runs `whipple control optimal-handling`.
pub fn run(cx: &RunContext, args: &OptimalArgs) -> Result<()> {
    let out = args
        .out
        .as_deref()
        .map(|p| Target::check("--out", p))
        .transpose()?;
    let bike = load(cx, &args.bike)?;
    let specs = args
        .vary
        .iter()
        .map(|v| BoundSpec::parse(v, &bike.bicycle).context("--vary"))
        .collect::<Result<Vec<BoundSpec>>>()?;
    let bounds: Vec<_> = specs.iter().map(|s| s.bound.clone()).collect();
    let settings = OptimalHandlingSettings {
        neuromuscular: Neuromuscular {
            frequency: args.neuro_frequency,
            damping: args.neuro_damping,
        },
        starts: args.starts,
        max_iterations: args.iterations,
        ..OptimalHandlingSettings::at(args.speed.si)
    };
    let started = Instant::now();
    let result = optimal_handling(&bike.bicycle, &bounds, &settings, crate::interrupt::flag())
        .context("the optimal-handling search")?;
    let seconds = started.elapsed().as_secs_f64();
    if !result.best.stable {
        bail!(
            "no start found a bicycle whose roll and lateral loops are stable at {} within \
             these bounds: there is no handling quality to optimize (the bicycle itself: {})",
            at_speed(args.speed)?,
            peak_words(&result.base)?
        );
    }
    let names: Vec<String> = specs
        .iter()
        .map(|s| format!("{} [{}]", s.name, s.unit()))
        .collect();
    let text = match args.format {
        TextFormat::Json => {
            let doc = json!({
                "bike": bike.label,
                "speed": args.speed.si,
                "parameters": specs.iter().map(|s| json!({
                    "name": s.name, "unit": s.unit(),
                    "low": s.from_si(s.bound.low), "high": s.from_si(s.bound.high),
                })).collect::<Vec<_>>(),
                "gain_names": HumanGains::NAMES,
                "base": candidate_json(&result.base, &specs),
                "best": candidate_json(&result.best, &specs),
                "starts": result.starts.iter().map(|s| json!({
                    "start": specs.iter().zip(&s.start).map(|(p, &x)| p.from_si(x)).collect::<Vec<f64>>(),
                    "best": candidate_json(&s.best, &specs),
                    "evaluations": s.evaluations,
                    "converged": s.converged,
                })).collect::<Vec<_>>(),
                "evaluations": result.evaluations(),
                "seconds": seconds,
                "local_search": true,
                "warnings": bike.warnings_json(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            writeln!(
                t,
                "{}: optimal handling at {} (peak HQM, the gains by Hess 2012's rules for \
                 each candidate)",
                bike.label,
                at_speed(args.speed)?
            )?;
            writeln!(
                t,
                "Nelder–Mead from {} starts: a local search, the best start's result, not a \
                 certified global minimum",
                result.starts.len()
            )?;
            let width = names.iter().map(|n| n.chars().count()).max().unwrap_or(0) + 2;
            writeln!(
                t,
                "  {:<width$}{:<12}{:<12}bounds",
                "parameter", "base", "optimal"
            )?;
            for (i, s) in specs.iter().enumerate() {
                writeln!(
                    t,
                    "  {:<width$}{:<12}{:<12}{} to {}",
                    names[i],
                    short(s.from_si(result.base.values[i]))?,
                    short(s.from_si(result.best.values[i]))?,
                    short(s.from_si(s.bound.low))?,
                    short(s.from_si(s.bound.high))?
                )?;
            }
            writeln!(t, "peak HQM, base:    {}", peak_words(&result.base)?)?;
            writeln!(t, "peak HQM, optimal: {}", peak_words(&result.best)?)?;
            if let Some(g) = result.best.gains {
                let gains: Vec<String> = HumanGains::NAMES
                    .iter()
                    .zip(g.to_array())
                    .map(|(n, k)| Ok(format!("{n} {}", short(k)?)))
                    .collect::<Result<_>>()?;
                writeln!(t, "optimal gains: {}", gains.join(", "))?;
            }
            writeln!(t, "starts:")?;
            for (k, s) in result.starts.iter().enumerate() {
                let values: Vec<String> = specs
                    .iter()
                    .zip(&s.best.values)
                    .map(|(p, &x)| short(p.from_si(x)))
                    .collect::<Result<_>>()?;
                writeln!(
                    t,
                    "  {}: [{}]  {}  ({} evaluations{})",
                    k + 1,
                    values.join(", "),
                    peak_words(&s.best)?,
                    s.evaluations,
                    if s.converged {
                        ""
                    } else {
                        ", the iterations ran out before the simplex converged"
                    }
                )?;
            }
            writeln!(
                t,
                "{} evaluations in {} s",
                result.evaluations(),
                short(seconds)?
            )?;
            t
        }
    };
    emit(&text, out.as_ref())
}

/// The design speed as the outputs print it: `5 m/s`, `5 m/s (18 km/h)` where typed in km/h.
fn at_speed(speed: crate::TypedSpeed) -> Result<String> {
    crate::output::speed_words(speed.si, speed.unit)
}
