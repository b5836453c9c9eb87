//! `whipple control hess`: the bicycle ridden by Hess's human controller (Hess, Moore &
//! Hubbard 2012; HumanControl's closed loop). At one speed: the gains used (from a HumanControl
//! gains file, interpolated in speed and said when extrapolated, or by Hess 2012's rules), the
//! closed loop's eigenvalues and each loop's crossover frequency; over `--speeds START:STOP:STEP` the
//! eigenvalues against speed. Every number is the library's.

use std::fmt::Write as _;
use std::path::PathBuf;
use whipple_front::units::SpeedUnit;

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::json;
use whipple::advanced::control::{
    CrossoverRules, GainSchedule, GainTable, HumanController, HumanLoop, Neuromuscular, Task,
    hess_gains, human_eigen_sweep,
};

use crate::TextFormat;
use crate::bike::{RunContext, load};
use crate::commands::emit;
use crate::control::complex;
use crate::output::number;

/// The most speeds `--speeds` takes.
pub const MAX_HESS_SPEEDS: usize = 100_000;

/// The arguments of `whipple control hess`.
#[derive(Args)]
pub struct HessArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    bike: String,
    /// A HumanControl gains file (`<Name>SteerGains.txt`: speed, kDelta, kPhiDot, kPhi, kPsi,
    /// kY), interpolated linearly in speed; outside its speeds extrapolated, and said so.
    #[arg(long, conflicts_with = "rules", required_unless_present = "rules")]
    gains: Option<PathBuf>,
    /// Find the gains by Hess 2012's rules instead (HumanControl's exact_gains: the steer and
    /// roll-rate loops' closed-loop damping 0.1289 and 0.0855, the phi, psi, y loops' crossover
    /// at 2, 1, 0.5 rad/s).
    #[arg(long)]
    rules: bool,
    /// Forward speed in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg,
        long,
        allow_hyphen_values = true,
        conflicts_with = "speeds",
        required_unless_present = "speeds"
    )]
    speed: Option<crate::TypedSpeed>,
    /// Speeds START:STOP:STEP in m/s (or km/h after them), both ends included; prints the eigenvalues against
    /// speed.
    #[arg(long, allow_hyphen_values = true)]
    speeds: Option<String>,
    /// The task: heading (ψ command, four loops) or lateral (front contact's lateral
    /// deviation, five loops).
    #[arg(long, default_value = "lateral")]
    task: String,
    /// The neuromuscular filter's natural frequency ω in rad/s.
    #[arg(long, default_value_t = 30.0, allow_hyphen_values = true)]
    neuro_frequency: f64,
    /// The neuromuscular filter's damping ratio ζ.
    #[arg(long, default_value_t = 0.707, allow_hyphen_values = true)]
    neuro_damping: f64,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    format: TextFormat,
}

/// `START:STOP:STEP` in m/s, both ends included, as every `--speeds` of the CLI; with the unit
/// they were typed in.
fn parse_speeds(text: &str) -> Result<(Vec<f64>, SpeedUnit)> {
    let ((start, stop, step), unit) = crate::output::parse_triple_in(text, "--speeds")?;
    let grid = whipple::speed_grid(start, stop, step).context("--speeds")?;
    if grid.len() > MAX_HESS_SPEEDS {
        bail!(
            "--speeds: at most {MAX_HESS_SPEEDS} speeds, got {}",
            grid.len()
        );
    }
    Ok((grid, unit))
}

fn gains_words(source: &str, extrapolated: bool, speed: f64, table: Option<&GainTable>) -> String {
    match table {
        Some(t) if extrapolated => format!(
            "{source}, EXTRAPOLATED: {speed} m/s lies outside the table's speeds ({} to {} m/s)",
            t.speeds()[0],
            t.speeds()[t.speeds().len() - 1]
        ),
        Some(_) => format!("{source}, interpolated in speed"),
        None => source.to_string(),
    }
}

/// Runs `whipple control hess`.
pub fn hess(cx: &RunContext, args: &HessArgs) -> Result<()> {
    let bike = load(cx, &args.bike)?;
    let task = Task::from_name(&args.task).context("--task")?;
    let nm = Neuromuscular {
        frequency: args.neuro_frequency,
        damping: args.neuro_damping,
    };
    let table = args
        .gains
        .as_deref()
        .map(crate::bike::read_gains_file)
        .transpose()?;
    let source = match &args.gains {
        Some(p) => format!("from {}", p.display()),
        None => "by Hess 2012's rules".to_string(),
    };
    let rules = CrossoverRules::default();
    let schedule = match &table {
        Some(t) => GainSchedule::Table(t),
        None => GainSchedule::Rules(rules),
    };
    if let Some(text) = &args.speeds {
        let (speeds, unit) = parse_speeds(text)?;
        let rows = human_eigen_sweep(&bike.benchmark, task, &schedule, &nm, &speeds)
            .context("the ridden bicycle's eigenvalues against speed")?;
        let outside = rows.iter().filter(|r| r.extrapolated).count();
        if outside > 0 {
            eprintln!(
                "warning: at {outside} of {} speeds the gains are extrapolated outside the \
                 table's speeds",
                rows.len()
            );
        }
        let text = match args.format {
            TextFormat::Json => {
                let mut out = Vec::new();
                for r in &rows {
                    out.push(json!({
                        "speed": r.speed,
                        "gains": r.gains.to_array(),
                        "extrapolated": r.extrapolated,
                        "stable": r.eigenvalues.iter().all(|z| z.re < 0.0),
                        "eigenvalues": r.eigenvalues.iter().map(|z| [z.re, z.im]).collect::<Vec<_>>(),
                    }));
                }
                let doc = json!({
                    "bike": bike.label,
                    "task": task.name(),
                    "gains_source": source,
                    "gain_names": whipple::advanced::control::HumanGains::NAMES,
                    "rows": out,
                    "warnings": bike.warnings_json(),
                });
                format!("{}\n", serde_json::to_string_pretty(&doc)?)
            }
            TextFormat::Table => {
                let mut t = String::new();
                writeln!(
                    t,
                    "{}: ridden by Hess's controller, {task} task, gains {source}",
                    bike.label
                )?;
                writeln!(
                    t,
                    "v [{}]{}stable  kDelta      kPhiDot     kPhi        kPsi        kY          eigenvalues [1/s]",
                    unit.symbol(),
                    " ".repeat(6 - unit.symbol().len())
                )?;
                for r in &rows {
                    let k = r.gains.to_array();
                    let mut line = format!(
                        "{:<9} {:<7}",
                        crate::output::speed_number(r.speed, unit)?,
                        if r.eigenvalues.iter().all(|z| z.re < 0.0) {
                            "yes"
                        } else {
                            "no"
                        }
                    );
                    for x in k {
                        write!(line, " {:<11.6}", x)?;
                    }
                    let values = r
                        .eigenvalues
                        .iter()
                        .filter(|z| z.im >= 0.0)
                        .map(|z| {
                            Ok(if z.im > 0.0 {
                                format!("{:.4}±{:.4}i", z.re, z.im)
                            } else {
                                format!("{:.4}", z.re)
                            })
                        })
                        .collect::<Result<Vec<_>>>()?;
                    write!(line, " {}", values.join(", "))?;
                    if r.extrapolated {
                        line.push_str("  (gains extrapolated)");
                    }
                    writeln!(t, "{}", line.trim_end())?;
                }
                t
            }
        };
        return emit(&text, None);
    }
    let Some(typed) = args.speed else {
        bail!("give --speed V or --speeds START:STOP:STEP");
    };
    let speed = typed.si;
    let (gains, extrapolated) = match &table {
        Some(t) => {
            let at = t.at(speed).context("--speed")?;
            (at.gains, at.extrapolated)
        }
        None => (
            hess_gains(&bike.benchmark, speed, &nm, &rules)
                .with_context(|| format!("the gains by Hess 2012's rules at {speed} m/s"))?,
            false,
        ),
    };
    if extrapolated {
        eprintln!(
            "warning: {speed} m/s lies outside the gains file's speeds: the gains are extrapolated"
        );
    }
    let rider = HumanController::new(task, gains, nm).context("the controller")?;
    let ridden = HumanLoop::new(&bike.benchmark, speed, &rider, &[])
        .with_context(|| format!("the ridden bicycle at {speed} m/s"))?;
    let eigenvalues = ridden.eigenvalues()?;
    let loops = ridden.loops().context("the loops' transfer functions")?;
    let stable = eigenvalues.iter().all(|z| z.re < 0.0);
    let used = match task {
        Task::Heading => 4,
        Task::Lateral => 5,
    };
    let words = gains_words(&source, extrapolated, speed, table.as_ref());
    let text = match args.format {
        TextFormat::Json => {
            let names = whipple::advanced::control::HumanGains::NAMES;
            let k = gains.to_array();
            let mut g = serde_json::Map::new();
            for i in 0..used {
                g.insert(names[i].to_string(), json!(k[i]));
            }
            let loops_json: Vec<_> = loops
                .iter()
                .map(|l| {
                    json!({
                        "loop": l.rider_loop.name(),
                        "gain": l.rider_loop.gain_name(),
                        "crossover": l.crossover(),
                        "crossovers": l.crossovers.iter().map(|c| json!({
                            "frequency": c.frequency, "enclosure": [c.lo, c.hi],
                            "certified": c.certified,
                        })).collect::<Vec<_>>(),
                    })
                })
                .collect();
            let doc = json!({
                "bike": bike.label,
                "speed": speed,
                "task": task.name(),
                "gains": g,
                "gains_source": source,
                "extrapolated": extrapolated,
                "neuromuscular": {"frequency": nm.frequency, "damping": nm.damping},
                "stable": stable,
                "eigenvalues": eigenvalues.iter().map(|z| [z.re, z.im]).collect::<Vec<_>>(),
                "loops": loops_json,
                "warnings": bike.warnings_json(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            writeln!(
                t,
                "{} at {} ridden by Hess's controller, {task} task (neuromuscular ω = {} rad/s, ζ = {})",
                bike.label,
                crate::output::speed_words(speed, typed.unit)?,
                number(nm.frequency)?,
                number(nm.damping)?
            )?;
            writeln!(t, "gains {words}:")?;
            let k = gains.to_array();
            for (name, value) in whipple::advanced::control::HumanGains::NAMES
                .iter()
                .zip(k)
                .take(used)
            {
                writeln!(t, "  {name:<8} {}", number(value)?)?;
            }
            writeln!(
                t,
                "closed-loop eigenvalues [1/s] ({}):",
                if stable { "stable" } else { "UNSTABLE" }
            )?;
            for z in &eigenvalues {
                writeln!(t, "  {}", complex(*z)?)?;
            }
            writeln!(
                t,
                "crossover frequencies [rad/s] (|L(iω)| = 1, L broken at the loop's error with the \
                 inner loops closed;\ncertified real roots of |N(iω)|² − |D(iω)|² in ω², none missed):"
            )?;
            for l in &loops {
                let list = if l.crossovers.is_empty() {
                    "none (|L| never crosses 1)".to_string()
                } else {
                    l.crossovers
                        .iter()
                        .map(|c| {
                            let mut s = number(c.frequency)?;
                            if !c.certified {
                                s.push_str(" (unresolved cluster)");
                            }
                            Ok(s)
                        })
                        .collect::<Result<Vec<_>>>()?
                        .join(", ")
                };
                writeln!(
                    t,
                    "  {:<8} {:<8} {list}",
                    l.rider_loop.name(),
                    l.rider_loop.gain_name()
                )?;
            }
            t
        }
    };
    emit(&text, None)
}
