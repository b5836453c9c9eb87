//! `whipple simulate`: the non-linear model from a few initial numbers, with rider torques
//! given as expressions.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use serde_json::json;
use whipple::advanced::nonlinear::{Outcome, Sample, Simulation};
use whipple::{InitialConditions, Model, SimulationSettings, simulate};
use whipple_front::simulation::{IntegratorKind, SimulationRequest, TorqueInput};
use whipple_front::units::degrees;

use whipple::advanced::turns::{Held, SteadyTurn, TurnSettings, held_turn};

use crate::TableFormat;
use crate::bike::{LoadedBike, RunContext, load};
use crate::output::{self, Sink, number};

/// The integrators on offer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorChoice {
    /// Classical Runge–Kutta with a fixed step (the study's integrator).
    Rk4,
    /// Dormand–Prince 5(4) with error control.
    Adaptive,
}

/// Arguments of `whipple simulate`.
#[derive(Args, Debug, Clone)]
pub struct SimulateArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    pub bike: String,
    /// Forward speed v in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    pub speed: crate::TypedSpeed,
    /// Initial lean in degrees (right positive), below 90 in size.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub lean: f64,
    /// Initial steer in degrees (right positive).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub steer: f64,
    /// Initial lean rate in rad/s.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub lean_rate: f64,
    /// Initial steer rate in rad/s.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub steer_rate: f64,
    /// Steer torque in N m as an expression of t, lean, steer, lean_rate, steer_rate, yaw and
    /// speed (radians, seconds), e.g. "0.5*sin(2*t)" or "10*lean + 20*lean_rate" (steering into
    /// the lean, which holds the benchmark bicycle up at 3 m/s).
    #[arg(long, allow_hyphen_values = true)]
    pub steer_torque: Option<String>,
    /// Lean torque in N m, an expression like --steer-torque.
    #[arg(long, allow_hyphen_values = true)]
    pub lean_torque: Option<String>,
    /// Simulated time in seconds.
    #[arg(long, allow_hyphen_values = true)]
    pub duration: f64,
    /// The integrator.
    #[arg(long, value_enum, default_value = "rk4")]
    pub integrator: IntegratorChoice,
    /// Step of the RK4 integrator in seconds (default 0.001).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Relative tolerance of the adaptive integrator (default 1e-8).
    #[arg(long, allow_hyphen_values = true)]
    pub rtol: Option<f64>,
    /// The bicycle has fallen when |lean| passes this angle, in degrees.
    #[arg(long, default_value_t = 60.0, allow_hyphen_values = true)]
    pub fall_angle: f64,
    /// Go on when a wheel's normal force turns negative (by default the run stops there: the
    /// wheel would lift off, which the model's bilateral contacts cannot show).
    #[arg(long)]
    pub ignore_lift_off: bool,
    /// Keep one sample in N integration steps (the first and the last are always kept), for
    /// long runs: the samples kept are bounded (1.5 million), the steps only by the work
    /// (2·10⁷). The summary's extremes are taken over every step.
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub every: usize,
    /// Start on the held steady turn at --speed (the rear contact's) and --lean (see
    /// `whipple turn`): steer, pitch and every rate from the turn, the steer torque held at the
    /// turn's unless --steer-torque is given; --lean-rate and --steer-rate perturb it.
    #[arg(long, conflicts_with = "steer")]
    pub from_turn: bool,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: TableFormat,
    /// Write the samples to this file instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also plot lean, steer and speed against time and the ground track (.svg or .png).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// The library's request from the command line's options (degrees as typed).
fn request(args: &SimulateArgs) -> SimulationRequest {
    SimulationRequest {
        speed: args.speed.si,
        lean_deg: args.lean,
        steer_deg: args.steer,
        lean_rate: args.lean_rate,
        steer_rate: args.steer_rate,
        duration: args.duration,
        integrator: match args.integrator {
            IntegratorChoice::Rk4 => IntegratorKind::Rk4,
            IntegratorChoice::Adaptive => IntegratorKind::Adaptive,
        },
        dt: args.dt,
        rtol: args.rtol,
        steer_torque: torque(&args.steer_torque),
        lean_torque: torque(&args.lean_torque),
        fall_angle_deg: args.fall_angle,
        stop_on_lift_off: !args.ignore_lift_off,
        max_steps: None,
        host_max_steps: None,
        sample_every: args.every,
    }
}

fn torque(expression: &Option<String>) -> TorqueInput {
    expression
        .clone()
        .map_or_else(TorqueInput::default, TorqueInput::Expression)
}

/// The option that sets a field of the library's request.
fn option(field: &str) -> String {
    match field {
        "lean_deg" => "--lean".into(),
        "steer_deg" => "--steer".into(),
        "fall_angle_deg" => "--fall-angle".into(),
        "sample_every" => "--every".into(),
        other => format!("--{}", other.replace('_', "-")),
    }
}

/// The library's rules applied to the options; an error names the option.
fn settings(
    args: &SimulateArgs,
    turn: Option<&SteadyTurn>,
) -> Result<(InitialConditions, SimulationSettings)> {
    let mut request = request(args);
    if let Some(turn) = turn {
        request.speed = turn.hub_speed;
        request.lean_deg = degrees(turn.lean);
        request.steer_deg = degrees(turn.steer);
        if args.steer_torque.is_none() {
            request.steer_torque = TorqueInput::Constant(turn.steer_torque);
        }
    }
    request.validate().map_err(|error| match error {
        whipple::Error::InvalidArgument { what, rule }
        | whipple::Error::LimitExceeded { what, rule } => {
            // "--dt must be positive …", "--steer-torque: unknown name …".
            let joint = if rule.starts_with("must ") || rule.starts_with("applies ") {
                " "
            } else {
                ": "
            };
            anyhow::anyhow!("{}{joint}{rule}", option(what))
        }
        other => anyhow::Error::new(other),
    })
}

/// The CSV's columns: the library's sample columns up to [`Sample::CSV_COLUMNS`].
fn csv_columns() -> &'static [&'static str] {
    &Sample::COLUMNS[..Sample::CSV_COLUMNS]
}

/// A sample's numbers in the order of [`csv_columns`].
fn sample_values(s: &Sample) -> [f64; Sample::CSV_COLUMNS] {
    let all = s.values();
    std::array::from_fn(|i| all[i])
}

/// The samples that are finite (a run that went non-finite keeps what came before).
fn finite_samples(run: &Simulation) -> impl Iterator<Item = &Sample> {
    run.samples.iter().filter(|s| s.is_finite())
}

/// The samples as CSV, row by row into `out`.
fn write_csv(out: &mut Sink, run: &Simulation) -> Result<()> {
    out.text(&format!("{}\n", csv_columns().join(",")))?;
    let mut row = String::new();
    for s in finite_samples(run) {
        row.clear();
        for (i, x) in sample_values(s).iter().enumerate() {
            if i > 0 {
                row.push(',');
            }
            row.push_str(&number(*x)?);
        }
        row.push('\n');
        out.text(&row)?;
    }
    Ok(())
}

/// The run as JSON, the samples one object per line, written as they come (a run of a
/// million samples never stands as one document in memory).
fn write_json(
    out: &mut Sink,
    bike: &LoadedBike,
    args: &SimulateArgs,
    run: &Simulation,
    outcome: &str,
) -> Result<()> {
    let head = json!({
        "bike": bike.label,
        "initial": {
            "speed": args.speed.si,
            "lean": args.lean.to_radians(),
            "steer": args.steer.to_radians(),
            "lean_rate": args.lean_rate,
            "steer_rate": args.steer_rate,
        },
        "outcome": outcome,
        "steps": run.steps,
        "rejected_steps": run.rejected_steps,
        "sample_every": args.every,
        "pulled_down_from_start": run.pulled_down_from_start.iter().map(|w| w.name()).collect::<Vec<_>>(),
    });
    let head = serde_json::to_string_pretty(&head)?;
    // The head's closing brace gives way to the samples.
    let head = head.strip_suffix("\n}").unwrap_or(&head);
    out.text(head)?;
    out.text(",\n  \"samples\": [")?;
    let columns = csv_columns();
    for (k, s) in finite_samples(run).enumerate() {
        let mut obj = serde_json::Map::new();
        for (name, x) in columns.iter().zip(sample_values(s)) {
            obj.insert(name.to_string(), json!(x));
        }
        let line = serde_json::to_string(&obj)?;
        out.text(&format!("{}\n    {line}", if k == 0 { "" } else { "," }))?;
    }
    out.text("\n  ]\n}\n")
}

fn table(
    bike: &LoadedBike,
    args: &SimulateArgs,
    run: &Simulation,
    outcome: &str,
) -> Result<String> {
    let samples: Vec<&Sample> = finite_samples(run).collect();
    let mut t = format!("{}: non-linear simulation, {outcome}\n", bike.label);
    if let Some(last) = samples.last() {
        let x = &run.extremes;
        writeln!(
            t,
            "  {} steps to t = {} s; energy {} J, largest change {:.3e} J; largest constraint residuals {:.1e} m, {:.1e} m/s",
            run.steps,
            number(last.t)?,
            number(x.initial_energy)?,
            x.largest_energy_change,
            x.largest_position_residual,
            x.largest_velocity_residual
        )?;
        writeln!(
            t,
            "  smallest normal forces: rear {:.2} N, front {:.2} N",
            x.smallest_normal_force[0], x.smallest_normal_force[1]
        )?;
        if args.every > 1 {
            writeln!(
                t,
                "  {} samples kept, one in {} steps (and the last); the extremes are over every step",
                samples.len(),
                args.every
            )?;
        }
    }
    if args.steer_torque.is_some() || args.lean_torque.is_some() {
        writeln!(
            t,
            "  note: the rider's torques do work, so the energy changes"
        )?;
    }
    for w in &run.pulled_down_from_start {
        writeln!(
            t,
            "  note: the {w} contact pulls its wheel down from the start (the masses sit beyond the other contact); contacts are bilateral, as in the linearized model"
        )?;
    }
    writeln!(
        t,
        "\n{:>8} {:>10} {:>10} {:>12} {:>12} {:>10} {:>10} {:>9} {:>8} {:>10} {:>10}",
        "t [s]",
        "lean [deg]",
        "steer[deg]",
        "lean rate",
        "steer rate",
        "yaw [deg]",
        "x [m]",
        "y [m]",
        "v [m/s]",
        "rear N [N]",
        "front N [N]"
    )?;
    // About a hundred rows: every sample whose time crosses a multiple of the print interval.
    let span = samples.last().map_or(0.0, |s| s.t) - samples.first().map_or(0.0, |s| s.t);
    let interval = [
        0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0,
    ]
    .into_iter()
    .find(|i| span / i <= 100.0)
    .unwrap_or(span / 100.0);
    let t0 = samples.first().map_or(0.0, |s| s.t);
    let mut next = 0usize;
    for (k, s) in samples.iter().enumerate() {
        let slot = ((s.t - t0) / interval + 1e-6).floor();
        if slot >= next as f64 || k + 1 == samples.len() {
            writeln!(
                t,
                "{:>8.3} {:>10.4} {:>10.4} {:>12.5} {:>12.5} {:>10.3} {:>10.4} {:>9.4} {:>8.4} {:>10.2} {:>10.2}",
                // Adding 0.0 prints a negative zero as 0.
                s.t + 0.0,
                s.lean.to_degrees() + 0.0,
                s.steer.to_degrees() + 0.0,
                s.lean_rate + 0.0,
                s.steer_rate + 0.0,
                s.yaw.to_degrees() + 0.0,
                s.x + 0.0,
                s.y + 0.0,
                s.speed + 0.0,
                s.rear.normal + 0.0,
                s.front.normal + 0.0
            )?;
            next = slot as usize + 1;
        }
    }
    Ok(t)
}

/// The plot of `run`, rendered for `path` (not written).
fn plot(bike: &LoadedBike, args: &SimulateArgs, run: &Simulation, path: &Path) -> Result<Vec<u8>> {
    let samples: Vec<&Sample> = finite_samples(run).collect();
    let mut events = Vec::new();
    match run.outcome {
        Outcome::Fell { t, .. } => events.push((t, "fell".to_string())),
        Outcome::WheelLifted { t, wheel, .. } => events.push((t, format!("{wheel} wheel lifts"))),
        _ => {}
    }
    // The user's numbers as typed; a held turn's steer (solved, all digits) to 0.1 millidegree.
    let steer = if args.from_turn {
        format!("{:.4} deg (the held turn's)", args.steer)
    } else {
        format!("{} deg", args.steer)
    };
    let series = whipple_report::SimulationSeries {
        title: format!(
            "{}: v = {}, lean {} deg, steer {steer}, lean rate {} rad/s, steer rate {} rad/s",
            bike.label,
            output::speed_label(args.speed.si, args.speed.unit)?,
            args.lean,
            args.lean_rate,
            args.steer_rate
        ),
        t: samples.iter().map(|s| s.t).collect(),
        lean: samples.iter().map(|s| s.lean).collect(),
        steer: samples.iter().map(|s| s.steer).collect(),
        speed: samples.iter().map(|s| s.speed).collect(),
        rear_contact: samples.iter().map(|s| (s.x, s.y)).collect(),
        front_contact: samples.iter().map(|s| (s.front_x, s.front_y)).collect(),
        events,
        outcome: Some(run.caption()),
    };
    let figure = whipple_report::time_series_plot(&series)?;
    figure
        .render_for_path(path)
        .with_context(|| format!("drawing {}", path.display()))
}

pub fn run(cx: &RunContext, args: &SimulateArgs) -> Result<()> {
    // The options' own rules first (before any file is read).
    settings(args, None)?;
    // Every output is checked before the work, and none is put in place unless all are written.
    let (out_target, plot_target) =
        output::table_and_plot(args.out.as_deref(), args.plot.as_deref())?;
    let bike = load(cx, &args.bike)?;
    let model = Model::new(&bike.benchmark)
        .with_context(|| format!("building the non-linear model of {}", bike.label))?;
    let turn = if args.from_turn {
        let turn = held_turn(
            &model,
            args.speed.si,
            Held::Lean(args.lean.to_radians()),
            &TurnSettings::default(),
        )
        .with_context(|| format!("the steady turn to start from ({})", bike.label))?;
        eprintln!(
            "starting on the held turn: steer {:.4} deg, steer torque {:.6} N m, rear contact \
             radius {:.4} m, rear hub speed {:.6} m/s",
            turn.steer.to_degrees(),
            turn.steer_torque,
            turn.rear_radius.unwrap_or(0.0),
            turn.hub_speed
        );
        Some(turn)
    } else {
        None
    };
    let (initial, settings_without_progress) = settings(args, turn.as_ref())?;
    // What the outputs say the run started from: the turn's steer, not the option's 0.
    let shown = turn.as_ref().map(|t| SimulateArgs {
        steer: t.steer.to_degrees(),
        ..args.clone()
    });
    let args = shown.as_ref().unwrap_or(args);
    let start = model
        .initial_state(&initial)
        .context("placing the bicycle in its initial state")?;

    // A progress bar on a terminal, shown once the run has taken a second.
    let bar = indicatif::ProgressBar::hidden();
    bar.set_length(1000);
    bar.set_style(
        indicatif::ProgressStyle::with_template("simulating {bar:40} {percent:>3}% {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let on_terminal = std::io::stderr().is_terminal();
    let started = Instant::now();
    let hook_bar = bar.clone();
    let settings = SimulationSettings {
        progress: Some(Box::new(move |p| {
            if on_terminal && hook_bar.is_hidden() && started.elapsed() > Duration::from_secs(1) {
                hook_bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            }
            if p.t_end > 0.0 {
                hook_bar.set_position((1000.0 * p.t / p.t_end) as u64);
                hook_bar.set_message(format!("t = {:.2} s", p.t));
            }
        })),
        ..settings_without_progress
    };
    let run = simulate(&model, start, &settings).map_err(|error| match error {
        // "--dt 0.25 is too large for this run: …; use --dt <= 0.05" (no outcome, no samples).
        whipple::Error::StepTooLarge {
            what,
            value,
            reason,
            suggested,
        } => anyhow::anyhow!(
            "simulating: {} {} is too large for this run: {reason}; use {} <= {}",
            option(what),
            whipple::advanced::short_number(value),
            option(what),
            whipple::advanced::short_number(suggested)
        ),
        other => anyhow::Error::new(other).context("simulating"),
    })?;
    bar.finish_and_clear();

    let (outcome, failed) = (run.outcome.to_string(), run.outcome.is_failure());
    let mut finished = Vec::new();
    if let Some(target) = &plot_target {
        let bytes = plot(&bike, args, &run, target.path())?;
        let mut sink = target.open()?;
        sink.bytes(&bytes)?;
        finished.push(sink.finish()?);
    }
    // Beside a plot, a table reader that goes away ends only the table: the plot is still put
    // in place.
    let mut sink = match &out_target {
        Some(target) => target.open()?,
        None if plot_target.is_some() => Sink::stdout_beside_files(),
        None => Sink::stdout(),
    };
    match args.format {
        TableFormat::Csv => write_csv(&mut sink, &run)?,
        TableFormat::Json => write_json(&mut sink, &bike, args, &run, &outcome)?,
        TableFormat::Table => sink.text(&table(&bike, args, &run, &outcome)?)?,
    }
    finished.push(sink.finish()?);
    output::commit(finished)?;
    if args.format != TableFormat::Table || args.out.is_some() {
        eprintln!("{}: {outcome}", bike.label);
    }
    if failed {
        bail!("the simulation {outcome}; the samples computed before that were written");
    }
    Ok(())
}
