//! `whipple`: bicycle dynamics from the command line. A thin layer: arguments → library →
//! report; every error gets its context here.

mod bike;
mod commands;
mod figures;
mod output;
mod simulate;
mod speeds;
mod validate;

use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

/// Dynamics of the Whipple bicycle: benchmark parameters, linearized stability, eigenvalues,
/// critical speeds and drawings (the successor of JBike6).
#[derive(Parser)]
#[command(name = "whipple", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
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
}

#[derive(Subcommand)]
enum Command {
    /// List the named bicycles with their sources.
    Presets,
    /// Show a bicycle's parameters (JBike6 form where known, and the benchmark form).
    Show {
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
        bike: String,
    },
    /// Write a bicycle as a parameter file in the benchmark form (JBike6 bodies combined).
    Convert {
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
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
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
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
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
        bike: String,
        /// Speeds START:STOP:STEP in m/s, both ends included.
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
    },
    /// Eigenvalues and mode shapes (eigenvectors) at one speed.
    Modes {
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
        bike: String,
        /// Forward speed in m/s.
        #[arg(long, allow_hyphen_values = true)]
        speed: f64,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// Critical speeds (double root, weave, capsize) and the self-stable speed ranges.
    Speeds {
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
        bike: String,
        /// Speed range LO:HI in m/s; HI may be `inf` (default: every speed v >= 0).
        #[arg(long, allow_hyphen_values = true)]
        range: Option<String>,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// Simulate the fully non-linear bicycle from a few initial numbers.
    Simulate(simulate::SimulateArgs),
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
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
        bike: String,
        /// Speeds START:STOP:STEP in m/s, both ends included.
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
    /// JBike6's stylized side view of the bicycle.
    Draw {
        /// A preset name or a parameter file (.toml, .json, .m).
        #[arg(long)]
        bike: String,
        /// The drawing, .svg or .png.
        #[arg(long)]
        out: std::path::PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Presets => commands::presets(),
        Command::Show { bike } => commands::show(&bike),
        Command::Convert {
            bike,
            to,
            keep_form,
            out,
        } => commands::convert(&bike, to, keep_form, out.as_deref()),
        Command::Matrices {
            bike,
            jbike6,
            format,
        } => commands::matrices(&bike, jbike6, format),
        Command::Eig {
            bike,
            speeds,
            format,
            out,
            plot,
        } => commands::eig(&bike, &speeds, format, out.as_deref(), plot.as_deref()),
        Command::Modes {
            bike,
            speed,
            format,
        } => commands::modes(&bike, speed, format),
        Command::Speeds {
            bike,
            range,
            format,
        } => speeds::speeds(&bike, range.as_deref(), format),
        Command::Draw { bike, out } => commands::draw(&bike, &out),
        Command::Simulate(args) => simulate::run(&args),
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
        } => validate::validate(&bike, &speeds, method, format, report.as_deref()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
