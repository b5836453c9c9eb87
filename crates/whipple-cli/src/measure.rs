//! `whipple measure`: a bicycle from BicycleParameters' raw bench measurements
//! (`<Name>Measured.txt`), written as a parameter file with σ, and a report of every step the
//! core's pipeline took (`whipple::advanced::measured`): which measurements gave which number,
//! with its σ, and on request the largest correlations between the parameters.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use serde_json::json;
use whipple::Bicycle;
use whipple::advanced::io::{Format, name_from_file_name, write};
use whipple::advanced::measured::{
    FittedPeriod, MeasuredParameters, read_measurements, read_measurements_with_records,
};
use whipple::advanced::rider::{
    YeadonConfiguration, YeadonMeasurements, read_yeadon_configuration, read_yeadon_measurements,
};

use crate::bike::{RunContext, located, read_capped};
use crate::commands::{round_sigma, round_to_sigma};
use crate::output::{Target, number, print_stdout, register_input};
use crate::{FileFormat, TextFormat};

/// The most correlations `--correlations` prints (every pair of the 26 parameters is 325).
const MAX_CORRELATIONS: usize = 325;

#[derive(Args)]
pub struct MeasureArgs {
    /// BicycleParameters' raw measurements, `<Name>Measured.txt` (values with `+/-` and σ).
    #[arg(long)]
    raw: PathBuf,
    /// Write the bicycle (benchmark form, with σ) to this file; its format follows from the
    /// extension (.toml, .json, .yaml; .txt is BicycleParameters' Benchmark.txt) or --to.
    #[arg(long)]
    out: Option<PathBuf>,
    /// The format of --out, overriding its extension.
    #[arg(long, value_enum)]
    to: Option<FileFormat>,
    /// Output format of the report on standard output.
    #[arg(long, value_enum, default_value = "table")]
    format: TextFormat,
    /// Also print the N largest correlations between the parameters (from their covariance).
    #[arg(long, value_name = "N")]
    correlations: Option<usize>,
    /// A directory of rate-gyro records (`<Name>FrameCompoundFirst1.mat`, named as
    /// BicycleParameters names them): every period the raw file lacks is fitted from its
    /// records (the trials' mean), as BicycleParameters' calculate_from_measured does.
    #[arg(long, value_name = "DIR")]
    periods: Option<PathBuf>,
    /// A rider's Yeadon measurements (`<Rider>YeadonMeas.txt`): the rider is seated on the
    /// bicycle (feet on the bottom bracket, hands on the grips) and added to its rear frame,
    /// as BicycleParameters' `add_rider`. Needs --configuration.
    #[arg(long, requires = "configuration")]
    rider: Option<PathBuf>,
    /// The rider's configuration on this bicycle (`<Rider><Bike>YeadonCFG.txt`): the angles
    /// the seating does not solve (somersault, the trunk's). Needs --rider.
    #[arg(long, requires = "rider")]
    configuration: Option<PathBuf>,
}

/// The file format `--out` is written in: `--to`, else its extension.
fn out_format(path: &Path, to: Option<FileFormat>) -> Result<Format> {
    let format = match to {
        Some(FileFormat::Toml) => Format::Toml,
        Some(FileFormat::Json) => Format::Json,
        Some(FileFormat::BpTxt) => Format::BicycleParametersTxt,
        Some(FileFormat::HcTxt) => Format::HumanControlTxt,
        Some(FileFormat::Yaml) => Format::Yaml,
        Some(FileFormat::M) => Format::Jbike6M,
        Some(FileFormat::PrincipalYaml) => bail!(
            "--to principal-yaml: a measured bicycle has no rider P kept apart from its rear \
             frame, which the principal parameterization needs; write it as --to yaml"
        ),
        Some(FileFormat::Moore2012Yaml) => bail!(
            "--to moore2012-yaml: Moore 2012's form does not carry standard deviations yet, and \
             a measured bicycle's are its point; write it as --to yaml"
        ),
        None => {
            let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if extension.eq_ignore_ascii_case("txt") {
                Format::BicycleParametersTxt
            } else {
                Format::from_extension(extension).ok_or_else(|| {
                    anyhow!(
                        "--out {}: the extension does not name a parameter format (.toml, \
                         .json, .yaml, .txt): give one or --to",
                        path.display()
                    )
                })?
            }
        }
    };
    if format == Format::Jbike6M {
        bail!(
            "--out {}: JBike6's .m files hold no standard deviations, and a measured bicycle's \
             are its point: write .toml, .json, .yaml or .txt",
            path.display()
        );
    }
    Ok(format)
}

pub fn run(_cx: &RunContext, args: &MeasureArgs) -> Result<()> {
    if let Some(n) = args.correlations {
        if n == 0 || n > MAX_CORRELATIONS {
            bail!(
                "--correlations {n}: give a count from 1 to {MAX_CORRELATIONS} (the pairs of \
                 the 26 parameters)"
            );
        }
    }
    let format = args
        .out
        .as_deref()
        .map(|p| out_format(p, args.to))
        .transpose()?;
    if args.to.is_some() && args.out.is_none() {
        bail!("--to names the format of --out: give --out too");
    }
    let path = args.raw.as_path();
    let bytes = read_capped(path).with_context(|| format!("--raw {}", path.display()))?;
    // The measurements are an input: no output of this run may be written onto them.
    register_input(path);
    let out = args
        .out
        .as_deref()
        .map(|p| Target::check("--out", p))
        .transpose()?;
    let text = String::from_utf8(bytes)
        .map_err(|_| anyhow!("{}: the file is not UTF-8 text", path.display()))?;
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let named = name_from_file_name(&file_name, Format::BicycleParametersTxt);
    let file = match &args.periods {
        None => read_measurements(&text),
        Some(dir) => {
            let Some(bike) = named.as_deref() else {
                bail!(
                    "--periods {}: the records are found by the bicycle's name, which comes \
                     from --raw's file name <Name>Measured.txt ({file_name} names none)",
                    dir.display()
                );
            };
            if !dir.is_dir() {
                bail!("--periods {}: not a directory", dir.display());
            }
            read_measurements_with_records(&text, &mut |key| {
                whipple_front::record::period_from_records(dir, bike, key).map(Some)
            })
        }
    }
    .map_err(|e| located(e, path, &text))?;
    let rider = match (&args.rider, &args.configuration) {
        (Some(rider), Some(configuration)) => Some(read_rider(rider, configuration)?),
        _ => None,
    };
    let result = match &rider {
        Some(r) => MeasuredParameters::with_rider(&file, &r.measurements, &r.configuration)
            .map_err(|e| match &e {
                // A measurement of the rider's file, at its line there.
                whipple::Error::Parse { format, .. } if format.starts_with("Yeadon") => {
                    located(e, &r.path, &r.text)
                }
                _ => located(e, path, &text),
            })
            .with_context(|| {
                format!(
                    "seating the rider of {} on the bicycle of {}",
                    r.name,
                    path.display()
                )
            })?,
        None => MeasuredParameters::new(&file.measurements)
            .map_err(|e| anyhow!(whipple_front::message::message(&e)))
            .with_context(|| format!("computing the parameters from {}", path.display()))?,
    };
    let bike_name = named.unwrap_or_else(|| "measured".into());
    let (name, source) = match &rider {
        Some(r) => (
            format!("{bike_name} with {}", r.name),
            format!(
                "computed by whipple measure from the bench measurements in {file_name} (Moore \
                 2012 ch. 2) with the rider of {} seated as {} (Yeadon 1990; BicycleParameters' \
                 add_rider)",
                r.file_name, r.configuration_file_name
            ),
        ),
        None => (
            bike_name,
            format!(
                "computed by whipple measure from the bench measurements in {file_name} (Moore \
                 2012 ch. 2)"
            ),
        ),
    };
    let bicycle = Bicycle {
        name: Some(name.clone()),
        source: Some(source),
        ..result.bicycle()
    };
    let checked = bicycle
        .check()
        .with_context(|| format!("checking the parameters computed for {name}"))?;
    for notice in &checked.notices {
        eprintln!("{notice}");
    }
    if let (Some(target), Some(format)) = (&out, format) {
        let written = write(&bicycle, format).with_context(|| format!("writing {name}"))?;
        target.write_whole(written.as_bytes())?;
    }
    let report = match args.format {
        TextFormat::Table => table(&name, &file_name, &result, &file.fitted, args.correlations)?,
        TextFormat::Json => {
            json_report(&name, &file_name, &result, &file.fitted, args.correlations)?
        }
    };
    print_stdout(&report)
}

fn rider_iterations(result: &MeasuredParameters) -> usize {
    result.rider.as_ref().map_or(0, |r| r.solve.iterations)
}

fn rider_residual(result: &MeasuredParameters) -> f64 {
    result.rider.as_ref().map_or(0.0, |r| r.solve.residual)
}

/// The rider's two files, read.
struct RiderFiles {
    name: String,
    path: PathBuf,
    text: String,
    file_name: String,
    configuration_file_name: String,
    measurements: YeadonMeasurements<f64>,
    configuration: YeadonConfiguration<f64>,
}

fn read_rider(rider: &Path, configuration: &Path) -> Result<RiderFiles> {
    let text_of = |option: &str, path: &Path| -> Result<String> {
        let bytes = read_capped(path).with_context(|| format!("{option} {}", path.display()))?;
        register_input(path);
        String::from_utf8(bytes)
            .map_err(|_| anyhow!("{}: the file is not UTF-8 text", path.display()))
    };
    let text = text_of("--rider", rider)?;
    let measurements = read_yeadon_measurements(&text).map_err(|e| located(e, rider, &text))?;
    let cfg_text = text_of("--configuration", configuration)?;
    let read =
        read_yeadon_configuration(&cfg_text).map_err(|e| located(e, configuration, &cfg_text))?;
    let base = |p: &Path| {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let file_name = base(rider);
    let name = file_name
        .strip_suffix("YeadonMeas.txt")
        .filter(|n| !n.is_empty())
        .unwrap_or("the rider")
        .to_string();
    Ok(RiderFiles {
        name,
        path: rider.to_path_buf(),
        text,
        file_name,
        configuration_file_name: base(configuration),
        measurements,
        configuration: read,
    })
}

/// `value ± σ` to the σ's three digits, or the value alone to about six significant digits (the
/// JSON report keeps every digit).
fn shown(value: f64, sigma: Option<f64>) -> Result<(String, String)> {
    Ok(match sigma {
        Some(s) if s > 0.0 => (round_to_sigma(value, s), round_sigma(s)),
        Some(_) => (number(value)?, "0".into()),
        None if value != 0.0 && value.is_finite() => {
            (round_to_sigma(value, value.abs() * 1e-3), "-".into())
        }
        None => (number(value)?, "-".into()),
    })
}

fn table(
    name: &str,
    file_name: &str,
    result: &MeasuredParameters,
    fitted: &[FittedPeriod],
    correlations: Option<usize>,
) -> Result<String> {
    let mut rows = vec![[
        "key".to_string(),
        "value".into(),
        "σ".into(),
        "unit".into(),
        "step".into(),
        "from".into(),
    ]];
    for step in &result.steps {
        let (value, sigma) = shown(step.value, step.sigma)?;
        let key = if step.benchmark {
            format!("{} *", step.key)
        } else {
            step.key.clone()
        };
        rows.push([
            key,
            value,
            sigma,
            step.unit.to_string(),
            if step.function.is_empty() {
                "as measured".into()
            } else {
                step.function.to_string()
            },
            step.inputs.join(" "),
        ]);
    }
    let widths: Vec<usize> = (0..5)
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut text = format!(
        "{name}: benchmark parameters from the bench measurements in {file_name}\n\
         (* a benchmark parameter, written to --out; σ to first order, exact, the measurements \
         independent; `from`: the measurements each number depends on)\n\n"
    );
    if let Some(rider) = &result.rider {
        text.push_str(&format!(
            "The rider is seated by solving its joint angles ({} Newton iterations, residual \
             {:.1e} m) and taken as exact (no σ of its own); mB, xB, zB and IB.. are the rear \
             frame with the rider ({} kg), the frame alone is under mB_frame, xB_frame, ….\n\n",
            rider_iterations(result),
            rider_residual(result),
            round_to_sigma(rider.rider.mass, 1e-3),
        ));
    }
    for row in &rows {
        let mut line = String::new();
        for (c, cell) in row.iter().enumerate() {
            if c < 5 {
                let pad = widths[c].saturating_sub(cell.chars().count());
                if c == 1 || c == 2 {
                    line.push_str(&" ".repeat(pad));
                    line.push_str(cell);
                } else {
                    line.push_str(cell);
                    line.push_str(&" ".repeat(pad));
                }
                line.push_str("  ");
            } else {
                line.push_str(cell);
            }
        }
        text.push_str(line.trim_end());
        text.push('\n');
    }
    if !fitted.is_empty() {
        text.push_str("\nPeriods the raw file lacked, fitted from records (--periods):\n");
        for f in fitted {
            let (value, sigma) = shown(f.period.value, Some(f.period.sigma))?;
            text.push_str(&format!(
                "  {} = {value} ± {sigma} s, {}\n",
                f.key, f.source
            ));
        }
    }
    if let Some(n) = correlations {
        text.push_str(
            "\nLargest correlations between the parameters (ρ = cov/(σσ); \
             BicycleParameters keeps only the σ):\n",
        );
        for c in result.largest_correlations(n) {
            text.push_str(&format!("  {:>5} {:>5}  {:+.4}\n", c.a, c.b, c.rho));
        }
    }
    Ok(text)
}

fn json_report(
    name: &str,
    file_name: &str,
    result: &MeasuredParameters,
    fitted: &[FittedPeriod],
    correlations: Option<usize>,
) -> Result<String> {
    for step in &result.steps {
        number(step.value)?;
    }
    let mut doc = json!({
        "bike": name,
        "raw": file_name,
        "steps": result.steps,
        "parameters": result
            .benchmark
            .to_array()
            .iter()
            .zip(whipple::advanced::table::parameters(whipple::advanced::table::Form::Benchmark))
            .map(|(v, p)| (p.key.to_string(), json!({ "value": v, "sigma": result.sigma.get(p.key).copied().unwrap_or(0.0) })))
            .collect::<serde_json::Map<String, serde_json::Value>>(),
    });
    if let (false, Some(map)) = (fitted.is_empty(), doc.as_object_mut()) {
        let rows: Vec<serde_json::Value> = fitted
            .iter()
            .map(|f| {
                json!({ "key": f.key, "value": f.period.value, "sigma": f.period.sigma,
                        "source": f.source })
            })
            .collect();
        map.insert("fitted".into(), json!(rows));
    }
    if let (Some(rider), Some(map)) = (&result.rider, doc.as_object_mut()) {
        let r = &rider.rider;
        map.insert(
            "rider".into(),
            json!({
                "mass_kg": r.mass,
                "center_of_mass_m": [r.center_of_mass.x, r.center_of_mass.y, r.center_of_mass.z],
                "inertia_kg_m2": (0..3).map(|i| (0..3).map(|j| r.inertia[(i, j)]).collect::<Vec<f64>>()).collect::<Vec<_>>(),
                "configuration": whipple::advanced::rider::CONFIGURATION_ANGLES
                    .iter()
                    .zip(rider.configuration.angles)
                    .map(|((n, _, _), a)| (n.to_string(), json!(a)))
                    .collect::<serde_json::Map<String, serde_json::Value>>(),
                "iterations": rider_iterations(result),
                "residual_m": rider_residual(result),
            }),
        );
    }
    if let (Some(n), Some(map)) = (correlations, doc.as_object_mut()) {
        map.insert("correlations".into(), json!(result.largest_correlations(n)));
    }
    Ok(format!("{}\n", serde_json::to_string_pretty(&doc)?))
}
