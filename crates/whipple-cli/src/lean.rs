//! `whipple rider`: the leaning rider (Moore 2012's rider-lean model, the library's five-body
//! `LeanModel`): the modes of the linearized model at a speed or against speed beside the rigid
//! rider's (the hinge locked), and the non-linear motion under a rider lean torque at the hinge.
//! The parameters are BicycleParameters' `MooreRiderLean2012` set, Moore's Browser with Jason
//! unless `--moore FILE` gives another (a JSON object of its 36 keys), or `--bike`: any bicycle
//! with its rider, Jason's upper body split off its rear frame (the library's
//! `RiderLeanParameters::split`).

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use serde_json::json;
use whipple::advanced::eigen::{Complex64, eigenvalues};
use whipple::advanced::integrate::Integrator;
use whipple::advanced::io::read_moore_rider_lean2012;
use whipple::advanced::nonlinear::{HINGE_LIMIT, LeanForcing, LeanModel, Outcome, TorqueFn};
use whipple::advanced::parameters::RiderLeanParameters;
use whipple::{Canonical, InitialConditions, SimulationSettings};
use whipple_report::{Series, XyPlotOptions, line_plot};

use crate::TextFormat;
use crate::bike::RunContext;
use crate::bike::read_capped;
use crate::output::{self, number};
use crate::time_response::short;

/// The most speeds `whipple rider --speeds` takes.
pub const MAX_RIDER_SPEEDS: usize = 100_000;

/// The arguments of `whipple rider`.
#[derive(Args)]
pub struct RiderArgs {
    /// BicycleParameters' `MooreRiderLean2012` parameter set as a JSON object of its 36 keys
    /// (`json.dump(parameter_set.parameters, f)`); default Moore's Browser with Jason
    /// (`mooreriderlean2012_browser_jason`).
    #[arg(long, conflicts_with = "bike")]
    moore: Option<PathBuf>,
    /// A bicycle with its rider (a preset or a parameter file, as every command's --bike):
    /// Jason's upper body (from the Browser with Jason set) split off its rear frame and hinged
    /// at Jason's hinge; refused where it does not fit inside the bicycle's rider.
    #[arg(long)]
    bike: Option<String>,
    /// The hinge's passive stiffness in N m/rad (Moore's k9), replacing the file's.
    #[arg(long, allow_hyphen_values = true)]
    hinge_stiffness: Option<f64>,
    /// The hinge's passive damping in N m s/rad (Moore's c9), replacing the file's.
    #[arg(long, allow_hyphen_values = true)]
    hinge_damping: Option<f64>,
    /// Forward speed in m/s (or km/h after it: 18km/h): the modes at this speed (and the speed of --simulate).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true, conflicts_with = "speeds")]
    speed: Option<crate::TypedSpeed>,
    /// Speeds START:STOP:STEP in m/s (or km/h after them): the modes against speed.
    #[arg(long, allow_hyphen_values = true)]
    speeds: Option<String>,
    /// Simulate the non-linear bicycle for this many seconds from upright running at --speed.
    #[arg(long, requires = "speed", allow_hyphen_values = true)]
    simulate: Option<f64>,
    /// The rider's lean torque at the hinge in N m (on the upper body, its reaction on the rear
    /// frame; right positive), held for --torque-duration.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    lean_torque: f64,
    /// How long the lean torque acts, in seconds from the start (default: the whole run).
    #[arg(long, allow_hyphen_values = true)]
    torque_duration: Option<f64>,
    /// The initial hinge angle (the upper body's lean relative to the rear frame) in degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    rider_lean_deg: f64,
    /// The non-linear run's relative tolerance (Dormand–Prince 5(4)).
    #[arg(long, default_value_t = 1e-9, allow_hyphen_values = true)]
    rtol: f64,
    /// Output format of the modes.
    #[arg(long, value_enum, default_value = "table")]
    format: TextFormat,
    /// Write the simulation as CSV to this file (t, lean, steer, rider lean, their rates in
    /// rad and rad/s, energy in J).
    #[arg(long, requires = "simulate")]
    out: Option<PathBuf>,
    /// Draw the simulation (lean, steer, rider lean against time) to this .svg or .png file.
    #[arg(long, requires = "simulate")]
    plot: Option<PathBuf>,
}

fn parameters(path: Option<&std::path::Path>) -> Result<(RiderLeanParameters, String)> {
    match path {
        None => Ok((
            RiderLeanParameters::browser_jason(),
            "Browser with Jason (MooreRiderLean2012)".into(),
        )),
        Some(path) => {
            let bytes = read_capped(path)?;
            output::register_input(path);
            let text = String::from_utf8(bytes)
                .map_err(|_| anyhow!("--moore {}: the file is not UTF-8 text", path.display()))?;
            let p = read_moore_rider_lean2012(&text)
                .map_err(|e| crate::bike::located(e, path, &text))?;
            Ok((p, path.display().to_string()))
        }
    }
}

fn complex(z: Complex64) -> Result<String> {
    Ok(if z.im == 0.0 {
        short(z.re)?
    } else {
        format!(
            "{}{}{}i",
            short(z.re)?,
            if z.im < 0.0 { "−" } else { "+" },
            short(z.im.abs())?
        )
    })
}

fn core(error: whipple::Error) -> anyhow::Error {
    anyhow!(whipple_front::message::message(&error))
}

/// Runs `whipple rider`.
pub fn run(cx: &RunContext, args: &RiderArgs) -> Result<()> {
    let (mut p, label) = match &args.bike {
        None => parameters(args.moore.as_deref())?,
        Some(arg) => {
            let loaded = crate::bike::load(cx, arg)?;
            let jason = RiderLeanParameters::browser_jason().upper_body;
            let p = RiderLeanParameters::split(&loaded.benchmark, jason)
                .map_err(core)
                .with_context(|| {
                    format!(
                        "Jason's upper body ({} kg, Moore 2012) cannot lean on {}",
                        jason.m, loaded.label
                    )
                })?;
            (
                p,
                format!("{} with Jason's upper body leaning", loaded.label),
            )
        }
    };
    if let Some(k) = args.hinge_stiffness {
        p.upper_body.stiffness = k;
    }
    if let Some(c) = args.hinge_damping {
        p.upper_body.damping = c;
    }
    p.check()
        .map_err(core)
        .context("the leaning rider's parameters")?;
    let model = LeanModel::new(&p)
        .map_err(core)
        .context("the leaning rider")?;
    let rigid = Canonical::new(&p.rigid())
        .map_err(core)
        .context("the rigid rider (the hinge locked)")?;
    // With the unit the speeds were typed in: each speed's heading gives km/h too where it was.
    let (speeds, unit) = match (args.speed, args.speeds.as_deref()) {
        (Some(typed), None) if typed.si.is_finite() => (vec![typed.si], typed.unit),
        (Some(_), None) => bail!("--speed must be a finite number of m/s"),
        (None, Some(text)) => {
            let ((a, b, step), unit) = output::parse_triple_in(text, "--speeds")?;
            let grid = whipple::speed_grid(a, b, step).context("--speeds")?;
            if grid.len() > MAX_RIDER_SPEEDS {
                bail!(
                    "--speeds: at most {MAX_RIDER_SPEEDS} speeds, got {}",
                    grid.len()
                );
            }
            (grid, unit)
        }
        _ => bail!("give --speed V or --speeds START:STOP:STEP"),
    };
    if let Some(duration) = args.simulate {
        return simulate(&model, &label, args, speeds[0], duration);
    }
    let mut rows = Vec::with_capacity(speeds.len());
    for &v in &speeds {
        let lean = model
            .eigenvalues(v)
            .map_err(core)
            .with_context(|| format!("the leaning rider's modes at {v} m/s"))?;
        let locked = eigenvalues(&rigid, v)
            .map_err(core)
            .context("the rigid rider's modes")?;
        rows.push((v, lean, locked));
    }
    let text = match args.format {
        TextFormat::Json => {
            let pairs = |zs: &[Complex64]| zs.iter().map(|z| [z.re, z.im]).collect::<Vec<_>>();
            let doc = json!({
                "rider": label,
                "states": ["lean", "steer", "rider_lean", "lean_rate", "steer_rate", "rider_lean_rate"],
                "rows": rows.iter().map(|(v, lean, locked)| json!({
                    "speed": v,
                    "eigenvalues": pairs(lean),
                    "stable": lean.iter().all(|z| z.re < 0.0),
                    "rigid_rider_eigenvalues": pairs(locked),
                    "rigid_rider_stable": locked.iter().all(|z| z.re < 0.0),
                })).collect::<Vec<_>>(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            writeln!(
                t,
                "{label}: the leaning rider's modes (Moore 2012; six states: lean, steer, rider \
                 lean and their rates) beside the rigid rider's (the hinge locked)"
            )?;
            writeln!(
                t,
                "eigenvalues [1/s], by decreasing real part (faer's eigensolver of the exact \
                 linearization; not certified)"
            )?;
            for (v, lean, locked) in &rows {
                let show = |zs: &[Complex64]| -> Result<String> {
                    Ok(zs
                        .iter()
                        .map(|z| complex(*z))
                        .collect::<Result<Vec<_>>>()?
                        .join(", "))
                };
                writeln!(
                    t,
                    "v = {}\n  leaning rider ({}): {}\n  rigid rider   ({}): {}",
                    output::speed_words(*v, unit)?,
                    if lean.iter().all(|z| z.re < 0.0) {
                        "stable"
                    } else {
                        "unstable"
                    },
                    show(lean)?,
                    if locked.iter().all(|z| z.re < 0.0) {
                        "stable"
                    } else {
                        "unstable"
                    },
                    show(locked)?
                )?;
            }
            t
        }
    };
    output::print_stdout(&text)
}

fn simulate(
    model: &LeanModel,
    label: &str,
    args: &RiderArgs,
    speed: f64,
    duration: f64,
) -> Result<()> {
    if !(duration.is_finite() && duration > 0.0 && duration <= 600.0) {
        bail!("--simulate must be a positive number of seconds up to 600, got {duration}");
    }
    if !(args.rtol.is_finite() && args.rtol > 0.0 && args.rtol < 1e-2) {
        bail!("--rtol must be between 0 and 0.01, got {}", args.rtol);
    }
    if !args.lean_torque.is_finite() {
        bail!("--lean-torque must be a finite number of N m");
    }
    if !args.rider_lean_deg.is_finite() || args.rider_lean_deg.abs() >= 90.0 {
        bail!("--rider-lean-deg must lie strictly between -90 and 90 degrees");
    }
    let until = match args.torque_duration {
        Some(d) if d.is_finite() && d >= 0.0 => d,
        Some(d) => bail!("--torque-duration must be a non-negative number of seconds, got {d}"),
        None => f64::INFINITY,
    };
    let (out, plot) = crate::output::table_and_plot(args.out.as_deref(), args.plot.as_deref())?;
    let start = model
        .initial_state(
            &InitialConditions::upright(speed),
            args.rider_lean_deg.to_radians(),
            0.0,
        )
        .map_err(core)?;
    let torque = args.lean_torque;
    let hinge_torque: TorqueFn = Box::new(move |t, _| if t <= until { torque } else { 0.0 });
    let settings = SimulationSettings {
        integrator: Integrator::adaptive(args.rtol),
        duration,
        ..SimulationSettings::default()
    };
    let run = model
        .simulate(
            &start,
            &settings,
            &LeanForcing {
                hinge_torque: Some(&hinge_torque),
                hinge_limit: HINGE_LIMIT,
            },
        )
        .map_err(core)
        .context("the leaning rider's simulation")?;
    let rows: Vec<[f64; 8]> = run
        .simulation
        .samples
        .iter()
        .zip(&run.rider)
        .map(|(s, [rider_lean, rider_lean_rate])| {
            [
                s.t,
                s.lean,
                s.steer,
                *rider_lean,
                s.lean_rate,
                s.steer_rate,
                *rider_lean_rate,
                s.energy,
            ]
        })
        .collect();
    let outcome = &run.simulation.outcome;
    let last = rows.last().copied().unwrap_or([0.0; 8]);
    let mut finished = Vec::new();
    if let Some(target) = &out {
        let mut text =
            String::from("t,lean,steer,rider_lean,lean_rate,steer_rate,rider_lean_rate,energy\n");
        for r in &rows {
            let cells = r.iter().map(|x| number(*x)).collect::<Result<Vec<_>>>()?;
            text.push_str(&cells.join(","));
            text.push('\n');
        }
        let mut sink = target.open()?;
        sink.text(&text)?;
        finished.push(sink.finish()?);
    }
    if let Some(target) = plot {
        let series = |name: &str, k: usize, colour: usize| {
            Series::new(
                name,
                rows.iter().map(|r| (r[0], r[k].to_degrees())).collect(),
            )
            .coloured(colour)
        };
        let options = XyPlotOptions {
            title: Some(format!(
                "{label}: {} N m rider lean torque at {} m/s",
                short(torque)?,
                short(speed)?
            )),
            x_label: "time t [s]".into(),
            y_label: "angle [deg]".into(),
            ..XyPlotOptions::default()
        };
        let figure = line_plot(
            &[
                series("lean φ (rear frame)", 1, 0),
                series("steer δ", 2, 1),
                series("rider lean φ_r", 3, 2),
            ],
            &[],
            &options,
        )?;
        let bytes = figure
            .render_for_path(target.path())
            .with_context(|| format!("drawing {}", target.path().display()))?;
        let mut sink = target.open()?;
        sink.bytes(&bytes)?;
        finished.push(sink.finish()?);
    }
    output::commit(finished)?;
    let energy_drift = rows
        .iter()
        .map(|r| (r[7] - rows[0][7]).abs())
        .fold(0.0_f64, f64::max);
    let mut t = String::new();
    writeln!(
        t,
        "{label}: {} s at {} m/s, rider lean torque {} N m{}",
        short(duration)?,
        short(speed)?,
        short(torque)?,
        match args.torque_duration {
            Some(d) => format!(" for the first {} s", short(d)?),
            None => String::new(),
        }
    )?;
    if *outcome != Outcome::Completed {
        writeln!(t, "the run ended: {outcome:.3}")?;
    }
    writeln!(
        t,
        "at t = {} s: lean {}°, steer {}°, rider lean {}°",
        short(last[0])?,
        short(last[1].to_degrees())?,
        short(last[2].to_degrees())?,
        short(last[3].to_degrees())?
    )?;
    writeln!(
        t,
        "{} steps; total energy changed by at most {} J{}",
        rows.len() - 1,
        short(energy_drift)?,
        if torque == 0.0 {
            " (no torque: only the hinge's damper, if any, takes energy)"
        } else {
            " (the torque works on the bicycle)"
        }
    )?;
    output::print_stdout(&t)
}
