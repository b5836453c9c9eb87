//! `whipple`: bicycle dynamics from the command line. A thin layer: arguments → library →
//! report; every error gets its context here.
//!
//! The command is this library's [`main_with_args`]: the `whipple` binary calls it with the
//! process's arguments, and the Python package calls it for its own `whipple` script, so both
//! are the same CLI.

mod bike;
mod commands;
mod control;
mod design;
mod examples;
mod feedback;
mod figures;
mod hess;
mod hqm;
mod interrupt;
mod lane_change;
mod lean;
mod measure;
mod optimal;
mod output;
mod period;
mod response;
mod rider;
mod simulate;
mod speeds;
mod time_response;
mod turns;
mod validate;

use std::ffi::OsString;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand, ValueEnum};

/// The units rule, under every command's help.
const UNITS_HELP: &str = "Units: a speed is in m/s, or in km/h with km/h after the value \
(--speed 18km/h, --range 15:25km/h, --speeds 10:30:0.5km/h, --speeds 3,5,7km/h, \
--x speed=10:30:21km/h). Results print in m/s; speeds typed in km/h are answered in km/h too: \
a speed or range echoed in a heading or title, each critical speed and stable range after its \
m/s, the speed column of a table against speed (eig, control's tables, hess, hqm) and eig's plot \
axis in km/h. Quantities computed along the way (a simulation's speed, a map's or study's \
critical speeds) and CSV and JSON files stay in m/s (eig's CSV and JSON add a v_kmh column); a \
design axis prints its values as typed. A parameter's name takes _mm after a length and \
_deg after an angle, in design axes (--x trail_mm=40:120:81) and in TOML and JSON files \
(c_mm = 80, lam_deg = 18).";

/// `command` and every subcommand of it, at any depth, with the units rule under its help.
fn with_units_help(command: clap::Command) -> clap::Command {
    command
        .after_help(UNITS_HELP)
        .mut_subcommands(with_units_help)
}

/// Dynamics of the Whipple bicycle: benchmark parameters, linearized stability, eigenvalues,
/// critical speeds and drawings (the successor of JBike6).
#[derive(Parser)]
#[command(name = "whipple", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    #[arg(
        long = "bike-format",
        global = true,
        value_parser = parse_format,
        help = format!(
            "Format of the --bike file: {}; by default from the extension and content",
            whipple_front::formats::names()
        ),
        long_help = format!(
            "Format of the --bike file; by default from the extension and content.\n{}",
            whipple_front::formats::described()
        ),
    )]
    format_in: Option<whipple::advanced::io::Format>,
    /// Treat the bicycle's warnings (a triangle inequality broken by a measured tensor, ...) as
    /// errors.
    #[arg(long, global = true)]
    strict: bool,
    /// Change a parameter of the --bike before anything is computed: NAME=VALUE, repeatable
    /// (`--set head_angle_deg=72 --set trail=0.05`); NAME as a design axis takes it (a key, an
    /// alias such as trail, a JBike6 key or TOML path; `_deg` after an angle for degrees).
    #[arg(long = "set", global = true, value_name = "NAME=VALUE")]
    set: Vec<String>,
}

/// A speed as typed: in m/s, and the unit it was typed in (a command that echoes it answers in
/// that unit too).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TypedSpeed {
    /// The speed [m/s].
    pub si: f64,
    /// The unit it was typed in.
    pub unit: whipple_front::units::SpeedUnit,
}

/// A speed option as typed (`4.6`, `18km/h`), in m/s with its unit: whipple-front's one
/// reading of speeds.
fn typed_speed_arg(text: &str) -> Result<TypedSpeed, String> {
    let (si, unit) = whipple_front::units::typed_speed(text).map_err(|e| match e {
        whipple::Error::InvalidArgument { rule, .. } => rule,
        other => other.to_string(),
    })?;
    Ok(TypedSpeed { si, unit })
}

fn parse_format(name: &str) -> Result<whipple::advanced::io::Format, String> {
    whipple::advanced::io::Format::from_name(name).ok_or_else(|| {
        format!(
            "unknown format `{name}` (formats: {})",
            whipple_front::formats::names()
        )
    })
}

/// Output formats for tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TableFormat {
    /// Aligned text for reading.
    Table,
    /// Comma-separated values.
    Csv,
    /// JSON.
    Json,
}

/// Output formats without CSV.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TextFormat {
    /// Aligned text for reading.
    Table,
    /// JSON.
    Json,
}

/// File formats a bicycle can be written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FileFormat {
    /// TOML (the hand-edited format).
    Toml,
    /// JSON.
    Json,
    /// JBike6's MATLAB assignments (JBike6-form bicycles only).
    M,
    /// BicycleParameters' `<Name>Benchmark.txt` (`key = value+/-sigma`).
    #[value(help = "BicycleParameters' <Name>Benchmark.txt (`key = value+/-sigma`)")]
    BpTxt,
    /// HumanControl's `<Name>Par.txt` (`key = value`).
    #[value(help = "HumanControl's <Name>Par.txt (`key = value`)")]
    HcTxt,
    /// BicycleParameters' YAML parameter set.
    Yaml,
    /// BicycleParameters' YAML parameter set in the principal parameterization (Moore 2019);
    /// the bicycle must carry its rider P (as a principal set read by whipple does).
    #[value(
        help = "BicycleParameters' YAML set in the principal parameterization (Moore 2019); needs the rider P a principal set carries"
    )]
    PrincipalYaml,
    /// BicycleParameters' YAML parameter set in Moore 2012's parameterization (rf, rr, d1, d2,
    /// d3, l1..l4, mc, md, me, mf, ic11.., id11.., ie11.., if11.., g).
    #[value(
        name = "moore2012-yaml",
        help = "BicycleParameters' YAML set in Moore 2012's parameterization (d1, d2, d3, l1..l4, ic11, ...)"
    )]
    Moore2012Yaml,
}

#[derive(Subcommand)]
enum Command {
    /// List the named bicycles with their sources.
    Presets,
    /// Write the field's example files the user guide's commands read (BicycleParameters' and
    /// HumanControl's parameter files, raw bench measurements, pendulum records, Yeadon riders)
    /// into a folder, with their sources and licences.
    Examples {
        /// The folder to write them into (created when missing).
        #[arg(long)]
        out: std::path::PathBuf,
    },
    /// Show a bicycle's parameters (JBike6 form where known, and the benchmark form).
    Show {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
    },
    /// Write a bicycle as a parameter file in the benchmark form (JBike6 bodies combined).
    Convert {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Output format.
        #[arg(long, value_enum)]
        to: FileFormat,
        /// Keep JBike6's form instead of converting to the benchmark form.
        #[arg(long)]
        keep_form: bool,
        /// Write to this file instead of standard output.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
    },
    /// The linearized model's matrices M, C1, K0, K2.
    Matrices {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// JBike6's convention: steer left positive, g inside K0.
        #[arg(long)]
        jbike6: bool,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// Eigenvalues against forward speed, modes tracked and labelled.
    Eig {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Speeds START:STOP:STEP in m/s (or km/h after them), both ends included.
        #[arg(long, default_value = "0:10:0.1", allow_hyphen_values = true)]
        speeds: String,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TableFormat,
        /// Write the table to this file instead of standard output.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Also draw the eigenvalues against speed to this .svg or .png file.
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
        /// In the plot, shade each eigenvalue's real part ± its standard deviation (from the
        /// parameters' sigmas).
        #[arg(long)]
        sigma_bands: bool,
    },
    /// The bicycle as a linear system: responses of named inputs to outputs (`bode`: frequency
    /// responses at several speeds).
    Response {
        #[command(subcommand)]
        kind: response::ResponseCommand,
    },
    /// Eigenvalues and mode shapes (eigenvectors) at one speed.
    Modes {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Forward speed in m/s (or km/h after it: 18km/h).
        #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
        speed: TypedSpeed,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// Critical speeds (double root, weave, capsize) and the self-stable speed ranges.
    Speeds {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Speed range LO:HI in m/s (or km/h after them); HI may be `inf` (default: every speed v >= 0).
        #[arg(long, allow_hyphen_values = true)]
        range: Option<String>,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// A map of one quantity over two parameters of a bicycle (a design study).
    Map {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// The x axis: NAME=START:STOP:COUNT (for example trail=0:0.2:401; `_deg` for degrees, `_mm` for millimetres).
        #[arg(long, allow_hyphen_values = true)]
        x: String,
        /// The y axis: NAME=START:STOP:COUNT (for example head_angle_deg=60:80:401, or speed=0:10:101).
        #[arg(long, allow_hyphen_values = true)]
        y: String,
        /// The quantity the plot shows (every quantity is in the CSV/JSON).
        #[arg(long, value_enum, default_value = "stable-width")]
        quantity: design::Quantity,
        #[command(flatten)]
        options: design::StudyArgs,
        /// Also draw the heat map to this .svg or .png file.
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
    },
    /// The classic one-parameter study: critical speeds against one parameter.
    Study {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// The parameter: NAME=START:STOP:COUNT (for example trail=-0.1:0.3:401).
        #[arg(long, allow_hyphen_values = true)]
        vary: String,
        #[command(flatten)]
        options: design::StudyArgs,
        /// Also draw v_w and v_c against the parameter, the self-stable band shaded (.svg, .png).
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
    },
    /// Join the CSV shards of a map or study (`--shard I/N`) into the one-machine file.
    Merge {
        /// The shards' CSV files, in any order.
        files: Vec<std::path::PathBuf>,
        /// Write the merged CSV here instead of standard output.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Also draw the merged map to this .svg or .png file.
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
        /// The quantity the plot shows.
        #[arg(long, value_enum, default_value = "stable-width")]
        quantity: design::Quantity,
    },
    /// Exact sensitivities of the weave and capsize speeds and the stable range's width to every
    /// parameter of the bicycle's own form (and, at --speed, of the weave's and capsize's real
    /// parts): derivatives and elasticities.
    Sensitivity {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Also the derivatives of the weave's and capsize's real parts at this speed [m/s, or km/h after it: 18km/h].
        #[arg(value_parser = crate::typed_speed_arg, long)]
        speed: Option<TypedSpeed>,
        /// Speed range LO:HI searched for the critical speeds, in m/s (or km/h after them).
        #[arg(long, default_value = "0:20", allow_hyphen_values = true)]
        range: String,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TableFormat,
        /// Write the table to this file instead of standard output.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Also draw a tornado plot of the elasticities of v_w to this .svg or .png file.
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
    },
    /// Simulate the fully non-linear bicycle from a few initial numbers.
    Simulate(simulate::SimulateArgs),
    /// One steady turn of the non-linear bicycle (held at a lean, steer or radius, or every
    /// hands-free one at a speed): steer, radii, torque, contact forces and stability.
    Turn(turns::TurnArgs),
    /// The bicycle under control: which modes each input can reach (controllability).
    Control(control::ControlArgs),
    /// A rider's body from the Yeadon model (95 measurements, 21 joint angles): the body's and
    /// each segment's mass, mass centre and inertia.
    RiderInertia(rider::RiderInertiaArgs),
    /// The leaning rider (Moore 2012's rider-lean model: the upper body hinged to the rear
    /// frame): its modes at a speed or against speed beside the rigid rider's, or the
    /// non-linear motion under a rider lean torque.
    Rider(lean::RiderArgs),
    /// The families of hands-free steady turns (pseudo-arclength continuation), with a figure of
    /// lean, steer and radius against speed (stable parts bold).
    Turns(turns::TurnsArgs),
    /// Serve JBike6's window in the browser: a local page and JSON API (Ctrl-C to stop).
    Serve {
        /// Port to listen on (0 picks a free one).
        #[arg(long, default_value_t = 8080)]
        port: u16,
        /// Address to listen on; the default serves this machine only.
        #[arg(long, default_value = "127.0.0.1")]
        address: std::net::IpAddr,
        /// Open the page in the system's browser.
        #[arg(long)]
        open: bool,
    },
    /// Linearize the non-linear model about upright straight running and compare its
    /// eigenvalues with the linear model's, speed by speed (the JBike6 benchmark).
    Validate {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Speeds START:STOP:STEP in m/s (or km/h after them), both ends included.
        #[arg(long, default_value = "0:10:0.01", allow_hyphen_values = true)]
        speeds: String,
        /// Linearization: the study's finite differences, exact derivatives, or both.
        #[arg(long, value_enum, default_value = "both")]
        method: validate::MethodChoice,
        /// Output format of the table on standard output.
        #[arg(long, value_enum, default_value = "csv")]
        format: validate::ValidateFormat,
        /// Also write a report to this directory: the CSV, the figures, a summary.
        #[arg(long)]
        report: Option<std::path::PathBuf>,
    },
    /// A pendulum's period (± σ) and damping fitted to an oscillation record (CSV or MATLAB
    /// .mat, as BicycleParameters' rate-gyro files), with a figure of the fit.
    Period(period::PeriodArgs),
    /// JBike6's stylized side view of the bicycle.
    Draw {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// The drawing, .svg or .png.
        #[arg(long)]
        out: std::path::PathBuf,
    },
    /// A bicycle from BicycleParameters' raw bench measurements (`<Name>Measured.txt`): its
    /// benchmark parameters with σ, and a report of every step.
    Measure(measure::MeasureArgs),
}

/// Whether the command reads a `--bike` (what `--set` changes).
fn reads_a_bike(command: &Command) -> bool {
    !matches!(
        command,
        Command::Presets
            | Command::Examples { .. }
            | Command::Merge { .. }
            | Command::Serve { .. }
            | Command::RiderInertia(_)
            | Command::Period(_)
            | Command::Measure(_)
    )
}

/// Runs the `whipple` command with `args` (the program name first, as in `std::env::args_os`)
/// and returns its exit status: 0 on success, 1 when the command failed (its message is on
/// standard error), 2 for a usage error (clap's message); `--help` and `--version` print and
/// return 0.
pub fn main_with_args<I, T>(args: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let parsed = with_units_help(Cli::command())
        .try_get_matches_from(args)
        .and_then(|matches| Cli::from_arg_matches(&matches));
    let cli = match parsed {
        Ok(cli) => cli,
        Err(error) => {
            // Help and version go to standard output, usage errors to standard error.
            let _ = error.print();
            return error.exit_code();
        }
    };
    output::begin_run();
    if !matches!(cli.command, Command::Serve { .. }) {
        // Every catchable signal ends the run cleanly: no temporary file or half a report
        // directory is left, and the message says what was not written.
        interrupt::install();
    }
    let changes = cli
        .set
        .iter()
        .map(|text| whipple_front::design::parse_change(text))
        .collect::<whipple::Result<Vec<_>>>()
        .map_err(|e| anyhow::anyhow!(whipple_front::message::message(&e)));
    let changes = match changes {
        Ok(changes) => changes,
        Err(error) => {
            eprintln!("error: --set: {error:#}");
            return 1;
        }
    };
    if !changes.is_empty() && !reads_a_bike(&cli.command) {
        eprintln!("error: --set changes the --bike, and this command reads no --bike");
        return 1;
    }
    let cx = &bike::RunContext {
        format: cli.format_in,
        strict: cli.strict,
        changes,
    };
    let result = match cli.command {
        Command::Presets => commands::presets(),
        Command::Examples { out } => examples::examples(&out),
        Command::Show { bike } => commands::show(cx, &bike),
        Command::Convert {
            bike,
            to,
            keep_form,
            out,
        } => commands::convert(cx, &bike, to, keep_form, out.as_deref()),
        Command::Matrices {
            bike,
            jbike6,
            format,
        } => commands::matrices(cx, &bike, jbike6, format),
        Command::Eig {
            bike,
            speeds,
            format,
            out,
            plot,
            sigma_bands,
        } => commands::eig(
            cx,
            &bike,
            &speeds,
            format,
            out.as_deref(),
            plot.as_deref(),
            sigma_bands,
        ),
        Command::Sensitivity {
            bike,
            speed,
            range,
            format,
            out,
            plot,
        } => commands::sensitivity(
            cx,
            &bike,
            speed,
            &range,
            format,
            out.as_deref(),
            plot.as_deref(),
        ),
        Command::Modes {
            bike,
            speed,
            format,
        } => commands::modes(cx, &bike, speed, format),
        Command::Response { kind } => response::run(cx, kind),
        Command::Speeds {
            bike,
            range,
            format,
        } => speeds::speeds(cx, &bike, range.as_deref(), format),
        Command::Draw { bike, out } => commands::draw(cx, &bike, &out),
        Command::Period(args) => period::run(args),
        Command::Map {
            bike,
            x,
            y,
            quantity,
            options,
            plot,
        } => design::run(
            cx,
            &options.args(&bike, &x, Some(&y), quantity, plot.as_deref()),
        ),
        Command::Study {
            bike,
            vary,
            options,
            plot,
        } => design::run(
            cx,
            &options.args(
                &bike,
                &vary,
                None,
                design::Quantity::StableWidth,
                plot.as_deref(),
            ),
        ),
        Command::Merge {
            files,
            out,
            plot,
            quantity,
        } => design::merge(&files, out.as_deref(), plot.as_deref(), quantity),
        Command::Simulate(args) => simulate::run(cx, &args),
        Command::Measure(args) => measure::run(cx, &args),
        Command::Turn(args) => turns::turn(cx, &args),
        Command::Control(args) => control::run(cx, &args),
        Command::RiderInertia(args) => rider::run(&args),
        Command::Rider(args) => lean::run(cx, &args),
        Command::Turns(args) => turns::turns(cx, &args),
        Command::Serve {
            port,
            address,
            open,
        } => commands::serve(address, port, open),
        Command::Validate {
            bike,
            speeds,
            method,
            format,
            report,
        } => validate::validate(cx, &bike, &speeds, method, format, report.as_deref()),
    };
    match result {
        Ok(()) => 0,
        // A reader that went away (`whipple eig ... | head`) got what it wanted.
        Err(error) if output::is_closed_stdout(&error) => 0,
        Err(error) => {
            eprintln!("error: {error:#}");
            1
        }
    }
}
