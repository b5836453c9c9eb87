//! `whipple control lane-change`: HumanControl's single or double lane change ridden by Hess's
//! controller (gains from a HumanControl SteerGains file, interpolated at the speed) on the
//! linear bicycle, the non-linear one, or both; a CSV of the runs and a figure of the path and
//! the front contact in the plane above the lateral loop's error against time.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, ValueEnum};
use whipple::advanced::control::{
    HumanController, LaneChange, LaneChangeRun, LaneKind, Neuromuscular, Task, lane_change_linear,
    lane_change_nonlinear,
};
use whipple_report::{Dash, Series, XyPlotOptions, stacked_line_plots};

use crate::bike::{RunContext, load};
use crate::output::{self, number};
use crate::time_response::short;

/// Which bicycle model rides the lane change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LaneModel {
    /// The linear bicycle, exactly.
    Linear,
    /// The non-linear bicycle, integrated.
    Nonlinear,
    /// Both, at the same times.
    Both,
}

/// The options of `whipple control lane-change`.
#[derive(Debug, Args)]
pub struct LaneChangeArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    bike: Option<String>,
    /// A preset bicycle by name (the same as --bike NAME).
    #[arg(long, conflicts_with = "bike")]
    preset: Option<String>,
    /// HumanControl's gains file `<Name>SteerGains.txt` (speed, kDelta, kPhiDot, kPhi, kPsi,
    /// kY), interpolated linearly at the speed.
    #[arg(long)]
    gains: PathBuf,
    /// Forward speed in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    speed: crate::TypedSpeed,
    /// Single or double lane change (HumanControl's: 2 m over at 35 m, slope 0.2, back within
    /// 60 m; 250 m in 500 intervals; preview 2.75 s; path filter 2.4 rad/s).
    #[arg(long, value_enum, default_value = "double")]
    lane: LaneArg,
    /// The lane's lateral offset in metres (right positive; default HumanControl's 2 m).
    #[arg(long, allow_hyphen_values = true)]
    width: Option<f64>,
    /// The bicycle model.
    #[arg(long, value_enum, default_value = "both")]
    model: LaneModel,
    /// The neuromuscular filter's natural frequency in rad/s.
    #[arg(long, default_value_t = whipple::advanced::control::NEUROMUSCULAR_FREQUENCY, allow_hyphen_values = true)]
    neuro_frequency: f64,
    /// The neuromuscular filter's damping ratio.
    #[arg(long, default_value_t = whipple::advanced::control::NEUROMUSCULAR_DAMPING, allow_hyphen_values = true)]
    neuro_damping: f64,
    /// The non-linear model's relative tolerance (Dormand–Prince 5(4)).
    #[arg(long, default_value_t = 1e-9)]
    rtol: f64,
    /// Write the runs as CSV to this file.
    #[arg(long)]
    out: PathBuf,
    /// Also draw the path and the front contact in the plane, and the lateral error against
    /// time, to this .svg or .png file.
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// `single` or `double`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LaneArg {
    /// Over and stay.
    Single,
    /// Over and back.
    Double,
}

/// Runs `whipple control lane-change`.
pub fn run(cx: &RunContext, args: &LaneChangeArgs) -> Result<()> {
    let (out, plot) = output::table_and_plot(Some(&args.out), args.plot.as_deref())?;
    let Some(out) = out else {
        bail!("--out is required");
    };
    let typed = args.speed;
    let speed = typed.si;
    if !(speed.is_finite() && speed > 0.0) {
        bail!("--speed must be a positive finite number of m/s, got {speed}");
    }
    if !(args.rtol.is_finite() && args.rtol > 0.0 && args.rtol < 1e-2) {
        bail!("--rtol must be between 0 and 0.01, got {}", args.rtol);
    }
    let bike_arg = match (&args.bike, &args.preset) {
        (Some(bike), None) => bike.as_str(),
        (None, Some(preset)) => preset.as_str(),
        _ => bail!("give the bicycle: --bike FILE|NAME or --preset NAME"),
    };
    let bike = load(cx, bike_arg)?;
    let table = crate::bike::read_gains_file(&args.gains)?;
    let lookup = table.at(speed).map_err(core)?;
    if lookup.extrapolated {
        eprintln!(
            "warning: {} m/s is outside the gains file's speeds ({} to {} m/s): the gains are \
             extrapolated, as HumanControl warns",
            number(speed)?,
            number(table.speeds()[0])?,
            number(table.speeds()[table.speeds().len() - 1])?
        );
    }
    let controller = HumanController::new(
        Task::Lateral,
        lookup.gains,
        Neuromuscular {
            frequency: args.neuro_frequency,
            damping: args.neuro_damping,
        },
    )
    .map_err(core)?;
    let kind = match args.lane {
        LaneArg::Single => LaneKind::Single,
        LaneArg::Double => LaneKind::Double,
    };
    let mut lane = LaneChange::humancontrol(kind);
    if let Some(width) = args.width {
        if !(width.is_finite() && width != 0.0) {
            bail!("--width must be a non-zero finite number of metres, got {width}");
        }
        lane = lane.scaled(width / lane.width);
    }
    let linear = match args.model {
        LaneModel::Nonlinear => None,
        _ => Some(
            lane_change_linear(&bike.benchmark, speed, &controller, &lane)
                .map_err(core)
                .context("the linear lane change")?,
        ),
    };
    let nonlinear = match args.model {
        LaneModel::Linear => None,
        _ => Some(
            lane_change_nonlinear(&bike.benchmark, speed, &controller, &lane, args.rtol)
                .map_err(core)
                .context("the non-linear lane change")?,
        ),
    };
    let runs: Vec<(&str, &LaneChangeRun)> = [("linear", &linear), ("nonlinear", &nonlinear)]
        .into_iter()
        .filter_map(|(name, run)| run.as_ref().map(|r| (name, r)))
        .collect();
    let title = format!(
        "{}: {} lane change at {}",
        bike.label,
        kind.name(),
        output::speed_label(speed, typed.unit)?
    );
    let mut finished = Vec::new();
    let mut sink = out.open()?;
    sink.text(&csv(&runs)?)?;
    finished.push(sink.finish()?);
    if let Some(target) = plot {
        let path = target.path().to_path_buf();
        let bytes = figure(&runs, speed, &title)?
            .render_for_path(&path)
            .with_context(|| format!("drawing {}", path.display()))?;
        let mut sink = target.open()?;
        sink.bytes(&bytes)?;
        finished.push(sink.finish()?);
    }
    output::commit(finished)?;
    output::print_stdout(&summary(&title, &runs)?)
}

/// A core error in the front end's words.
fn core(error: whipple::Error) -> anyhow::Error {
    anyhow!(whipple_front::message::message(&error))
}

fn summary(title: &str, runs: &[(&str, &LaneChangeRun)]) -> Result<String> {
    let largest = |x: &mut dyn Iterator<Item = f64>| x.fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut text = format!(
        "{title}\n  model      largest |y_c − y_Q|  largest |road − y_Q|  largest |lean|  largest |T_δ|\n"
    );
    for (name, run) in runs {
        let road = largest(&mut run.path.iter().zip(&run.front_y).map(|(p, y)| p - y));
        writeln!(
            text,
            "  {:<10} {:<20} {:<21} {:<15} {} N m",
            name,
            format!("{} m", short(largest(&mut run.error.iter().copied()))?),
            format!("{} m", short(road)?),
            format!("{} rad", short(largest(&mut run.lean.iter().copied()))?),
            short(largest(&mut run.steer_torque.iter().copied()))?
        )?;
    }
    if let [(_, a), (_, b)] = runs {
        let difference = largest(&mut a.front_y.iter().zip(&b.front_y).map(|(x, y)| x - y));
        writeln!(
            text,
            "  the models' front contacts differ by at most {} m (the difference shrinks as the \
             path's amplitude cubed)",
            short(difference)?
        )?;
    }
    text.push_str(
        "  (y_c is the path through the path filter, what the rider tracks; the road is the path \
         delayed by the 2.75 s preview)\n",
    );
    Ok(text)
}

fn csv(runs: &[(&str, &LaneChangeRun)]) -> Result<String> {
    let Some((_, first)) = runs.first() else {
        bail!("no model ran");
    };
    let units = ["s", "m", "m", "m", "m", "m", "rad", "rad", "rad", "N_m"];
    let mut text = String::from("time_s,path_m,command_m");
    for (model, run) in runs {
        for ((name, _), unit) in run.columns().iter().zip(units).skip(3) {
            write!(text, ",{model}_{name}_{unit}")?;
        }
    }
    text.push('\n');
    for k in 0..first.times.len() {
        write!(
            text,
            "{},{},{}",
            number(first.times[k])?,
            number(first.path[k])?,
            number(first.command[k])?
        )?;
        for (_, run) in runs {
            for (_, values) in run.columns().iter().skip(3) {
                write!(text, ",{}", number(values[k])?)?;
            }
        }
        text.push('\n');
    }
    Ok(text)
}

fn figure(
    runs: &[(&str, &LaneChangeRun)],
    speed: f64,
    title: &str,
) -> Result<whipple_report::Figure> {
    let Some((_, first)) = runs.first() else {
        bail!("no model ran");
    };
    // The road under the front contact against the distance travelled at the nominal speed.
    let road: Vec<(f64, f64)> = first
        .times
        .iter()
        .zip(&first.path)
        .map(|(t, y)| (speed * t, *y))
        .collect();
    let mut plane = vec![
        Series::new("road (the path, preview delayed)", road)
            .coloured(6)
            .dashed(Dash::Dashed),
    ];
    let mut error = Vec::new();
    for (k, (name, run)) in runs.iter().enumerate() {
        plane.push(
            Series::new(
                format!("front contact y_Q, {name}"),
                run.front_x
                    .iter()
                    .copied()
                    .zip(run.front_y.iter().copied())
                    .collect(),
            )
            .coloured(k),
        );
        error.push(
            Series::new(
                format!("y_c − y_Q, {name}"),
                run.times
                    .iter()
                    .copied()
                    .zip(run.error.iter().copied())
                    .collect(),
            )
            .coloured(k),
        );
    }
    let top = XyPlotOptions {
        title: Some(title.to_string()),
        x_label: "distance along x [m]".into(),
        y_label: "lateral position y [m]".into(),
        ..XyPlotOptions::default()
    };
    let bottom = XyPlotOptions {
        title: Some(
            "the lateral loop's error (command y_c less y_Q) and the deviation from the road"
                .into(),
        ),
        x_label: "time t [s]".into(),
        y_label: "lateral error [m]".into(),
        ..XyPlotOptions::default()
    };
    Ok(stacked_line_plots(
        &[(plane, top), (error, bottom)],
        (1100, 900),
    )?)
}
