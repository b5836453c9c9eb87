//! `whipple rider-inertia`: a rider's body from the Yeadon model (the core's
//! `advanced::rider`): the measurements' file (`*YeadonMeas.txt`) and optionally a
//! configuration (`*YeadonCFG.txt`, else every angle zero), printed as the body's and each
//! segment's mass, mass centre and inertia.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use nalgebra::{Matrix3, Vector3};
use serde_json::json;
use whipple::advanced::rider::{
    SEGMENT_NAMES, YeadonConfiguration, read_yeadon_configuration, read_yeadon_measurements,
    yeadon_body,
};

use crate::TextFormat;
use crate::bike::{located, read_capped};
use crate::output::{number, print_stdout};

/// The arguments of `whipple rider-inertia`.
#[derive(Args)]
pub struct RiderInertiaArgs {
    /// The 95 anthropometric measurements: yeadon's / BicycleParameters' `<Rider>YeadonMeas.txt`.
    #[arg(long)]
    measurements: PathBuf,
    /// The 21 joint angles (rad): a `<Rider><Bike>YeadonCFG.txt`; by default every angle zero
    /// (standing, arms down).
    #[arg(long)]
    configuration: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    format: TextFormat,
}

const FRAME: &str = "origin at the centre of the hip level Ls0; in the zero configuration x to \
                     the body's left, y backward, z up the trunk";

fn text_of(path: &Path) -> Result<String> {
    let bytes = read_capped(path)?;
    crate::output::register_input(path);
    String::from_utf8(bytes).map_err(|_| anyhow!("{}: the file is not UTF-8 text", path.display()))
}

fn vector(v: &Vector3<f64>) -> Result<Vec<f64>> {
    v.iter().map(|x| number(*x).map(|_| *x)).collect()
}

fn rows(m: &Matrix3<f64>) -> Result<Vec<Vec<f64>>> {
    (0..3)
        .map(|i| {
            (0..3)
                .map(|j| number(m[(i, j)]).map(|_| m[(i, j)]))
                .collect()
        })
        .collect()
}

/// The numbers of one quantity to ten significant digits of its largest (round-off below that
/// shows as zero; JSON keeps every digit).
fn shown(values: &[f64]) -> Result<Vec<String>> {
    if let Some(x) = values.iter().find(|x| !x.is_finite()) {
        bail!("a computed result is not a finite number ({x})");
    }
    let largest = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let decimals = if largest > 0.0 {
        (9 - whipple::math::log10(largest).floor() as i32).clamp(0, 20) as usize
    } else {
        0
    };
    Ok(values
        .iter()
        .map(|x| {
            let text = format!("{x:.decimals$}");
            // No "-0.000…" for a round-off of either sign.
            if text
                .trim_start_matches('-')
                .chars()
                .all(|c| c == '0' || c == '.')
            {
                text.trim_start_matches('-').to_string()
            } else {
                text
            }
        })
        .collect())
}

fn write_body(t: &mut String, mass: f64, com: &Vector3<f64>, inertia: &Matrix3<f64>) -> Result<()> {
    writeln!(t, "  mass (kg)              {}", shown(&[mass])?[0])?;
    let c = shown(com.as_slice())?;
    writeln!(t, "  mass centre (m)        [{}, {}, {}]", c[0], c[1], c[2])?;
    let entries: Vec<f64> = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| inertia[(i, j)])
        .collect();
    let m = shown(&entries)?;
    let width = m.iter().map(String::len).max().unwrap_or(0);
    for i in 0..3 {
        writeln!(
            t,
            "  {} [{:>width$} {:>width$} {:>width$}]",
            if i == 0 {
                "inertia (kg m^2)    "
            } else {
                "                    "
            },
            m[3 * i],
            m[3 * i + 1],
            m[3 * i + 2]
        )?;
    }
    Ok(())
}

/// Runs `whipple rider-inertia`.
pub fn run(args: &RiderInertiaArgs) -> Result<()> {
    let path = &args.measurements;
    let text = text_of(path)?;
    let measurements = read_yeadon_measurements(&text).map_err(|e| located(e, path, &text))?;
    let configuration = match &args.configuration {
        Some(cfg_path) => {
            let cfg_text = text_of(cfg_path)?;
            read_yeadon_configuration(&cfg_text).map_err(|e| located(e, cfg_path, &cfg_text))?
        }
        None => YeadonConfiguration::zero(),
    };
    // The configuration's angles were checked as it was read: what fails now is a measurement.
    let body = yeadon_body(&measurements, &configuration).map_err(|e| located(e, path, &text));
    let body = body.with_context(|| format!("the Yeadon model of {}", path.display()))?;
    let configuration_name = args
        .configuration
        .as_ref()
        .map_or("zero (every angle 0)".to_string(), |p| {
            p.display().to_string()
        });
    let what = |name: &str| {
        SEGMENT_NAMES
            .iter()
            .find(|(n, _)| *n == name)
            .map_or("", |(_, w)| *w)
    };
    let out = match args.format {
        TextFormat::Json => {
            let mut segments = Vec::with_capacity(body.segments.len());
            for s in &body.segments {
                segments.push(json!({
                    "name": s.name,
                    "segment": what(s.name),
                    "mass_kg": s.mass,
                    "origin_m": vector(&s.origin)?,
                    "center_of_mass_m": vector(&s.center_of_mass)?,
                    "inertia_kg_m2": rows(&s.inertia)?,
                    "orientation": rows(&s.orientation)?,
                    "local_inertia_kg_m2": rows(&s.local_inertia)?,
                }));
            }
            let value = json!({
                "measurements": path.display().to_string(),
                "configuration": configuration_name,
                "frame": FRAME,
                "total_mass_measured_kg": measurements.total_mass,
                "body": {
                    "mass_kg": body.mass,
                    "center_of_mass_m": vector(&body.center_of_mass)?,
                    "inertia_kg_m2": rows(&body.inertia)?,
                },
                "segments": segments,
            });
            format!("{}\n", serde_json::to_string_pretty(&value)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            writeln!(
                t,
                "Yeadon model of {} in configuration {configuration_name}",
                path.display()
            )?;
            writeln!(
                t,
                "({FRAME}; inertia about each mass centre, in that frame; {})",
                match measurements.total_mass {
                    Some(m) => format!("densities scaled to the measured {} kg", number(m)?),
                    None => "Dempster's densities".to_string(),
                }
            )?;
            writeln!(t, "body")?;
            write_body(&mut t, body.mass, &body.center_of_mass, &body.inertia)?;
            for s in &body.segments {
                writeln!(t, "{} ({})", s.name, what(s.name))?;
                write_body(&mut t, s.mass, &s.center_of_mass, &s.inertia)?;
            }
            t
        }
    };
    print_stdout(&out)
}
