//! One function per subcommand.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{bail, Context, Result};
use nalgebra::Matrix2;
use serde_json::json;
use whipple::analysis::{stability, sweep};
use whipple::linear::Canonical;
use whipple::parameters::io::{benchmark_key_doc, write, Format};
use whipple::parameters::presets::PRESETS;
use whipple::{Bicycle, Description};

use crate::bike::{load, LoadedBike};
use crate::output::{number, parse_triple, print_stdout, write_atomically};
use crate::{FileFormat, TableFormat, TextFormat};

/// Prints `text` to standard output or writes it to `out`.
pub fn emit(text: &str, out: Option<&Path>) -> Result<()> {
    match out {
        Some(path) => write_atomically(path, text.as_bytes()),
        None => print_stdout(text),
    }
}

pub fn presets() -> Result<()> {
    let mut text = String::new();
    for p in PRESETS {
        let form = match (p.description)() {
            Description::Benchmark(_) => "benchmark form",
            Description::Jbike6(_) => "JBike6 form",
        };
        writeln!(text, "{:<16} {} ({form})", p.name, p.summary)?;
        writeln!(text, "{:<16} source: {}", "", p.source)?;
    }
    emit(&text, None)
}

pub fn show(arg: &str) -> Result<()> {
    let bike = load(arg)?;
    let mut text = String::new();
    writeln!(text, "{}", bike.label)?;
    if let Some(source) = &bike.bicycle.source {
        writeln!(text, "source: {source}")?;
    }
    if let Some(j) = bike.bicycle.jbike6() {
        writeln!(text, "\nJBike6 form (x forward, y up; SI units, radians):")?;
        for (name, value) in j.fields() {
            writeln!(text, "  {name:<18} {:>22}", number(value)?)?;
        }
    }
    writeln!(
        text,
        "\nBenchmark form (Meijaard et al. 2007; x forward, y right, z down):"
    )?;
    for (key, value) in bike.benchmark.fields() {
        writeln!(
            text,
            "  {key:<5} {:>22}  {}",
            number(value)?,
            benchmark_key_doc(key)
        )?;
    }
    writeln!(
        text,
        "  (steer axis tilt {:.4} deg, head angle {:.4} deg)",
        bike.benchmark.lambda.to_degrees(),
        90.0 - bike.benchmark.lambda.to_degrees()
    )?;
    emit(&text, None)
}

pub fn convert(arg: &str, to: FileFormat, keep_form: bool, out: Option<&Path>) -> Result<()> {
    let bike = load(arg)?;
    let bicycle = if keep_form {
        bike.bicycle.clone()
    } else {
        Bicycle {
            name: bike.bicycle.name.clone(),
            source: bike.bicycle.source.clone(),
            description: Description::Benchmark(bike.benchmark),
        }
    };
    let format = match to {
        FileFormat::Toml => Format::Toml,
        FileFormat::Json => Format::Json,
        FileFormat::M => Format::Jbike6M,
    };
    let text = write(&bicycle, format).with_context(|| {
        if format == Format::Jbike6M && !keep_form {
            "--to m needs --keep-form (the benchmark form has no .m layout)".to_string()
        } else {
            format!("writing {}", bike.label)
        }
    })?;
    emit(&text, out)
}

pub fn canonical(bike: &LoadedBike) -> Result<Canonical> {
    Canonical::new(&bike.benchmark).with_context(|| format!("building the model of {}", bike.label))
}

fn matrix_json(m: &Matrix2<f64>) -> Result<serde_json::Value> {
    for x in m.iter() {
        number(*x)?;
    }
    Ok(json!([[m[(0, 0)], m[(0, 1)]], [m[(1, 0)], m[(1, 1)]]]))
}

pub fn matrices(arg: &str, jbike6: bool, format: TextFormat) -> Result<()> {
    let bike = load(arg)?;
    let c = canonical(&bike)?;
    let (names, mats, note) = if jbike6 {
        let [m, c1, k0, k2] = c.jbike6_convention();
        (
            ["M0", "C1", "K0", "K2"],
            [m, c1, k0, k2],
            "JBike6 convention: q = [lean right +, steer left +], M0 q'' + v C1 q' + (K0 + v^2 K2) q = 0, g inside K0",
        )
    } else {
        (
            ["M", "C1", "K0", "K2"],
            [c.m, c.c1, c.k0, c.k2],
            "benchmark convention: q = [lean right +, steer right +], M q'' + v C1 q' + (g K0 + v^2 K2) q = f",
        )
    };
    let text = match format {
        TextFormat::Json => {
            let mut obj = serde_json::Map::new();
            obj.insert("bike".into(), json!(bike.label));
            obj.insert(
                "convention".into(),
                json!(if jbike6 { "jbike6" } else { "benchmark" }),
            );
            obj.insert("g".into(), json!(c.g));
            for (name, m) in names.iter().zip(mats.iter()) {
                obj.insert(name.to_string(), matrix_json(m)?);
            }
            format!("{}\n", serde_json::to_string_pretty(&obj)?)
        }
        TextFormat::Table => {
            let mut t = format!("{} ({note}; g = {})\n", bike.label, number(c.g)?);
            for (name, m) in names.iter().zip(mats.iter()) {
                writeln!(t, "{name} =")?;
                for i in 0..2 {
                    writeln!(
                        t,
                        "  [{:>22} {:>22}]",
                        number(m[(i, 0)])?,
                        number(m[(i, 1)])?
                    )?;
                }
            }
            t
        }
    };
    emit(&text, None)
}

pub fn eig(
    arg: &str,
    speeds: &str,
    format: TableFormat,
    out: Option<&Path>,
    plot: Option<&Path>,
) -> Result<()> {
    let bike = load(arg)?;
    let (start, stop, step) = parse_triple(speeds, "--speeds")?;
    let grid = sweep::speed_grid(start, stop, step).context("--speeds")?;
    let c = canonical(&bike)?;
    let s = sweep::eigen_sweep(&c, &grid)?;
    if let Some(path) = plot {
        let critical = stability::critical_speeds(&c, start.min(stop), stop.max(start + step))?;
        crate::figures::eigen_plot(&bike, &s, &critical, path)?;
    }
    let text = match format {
        TableFormat::Csv => whipple_report::eigen_csv(&s),
        TableFormat::Json => {
            let mut rows = Vec::with_capacity(s.speeds.len());
            for (v, values) in s.speeds.iter().zip(&s.eigenvalues) {
                number(*v)?;
                let mut eigs = Vec::new();
                for (l, mode) in values.iter().zip(s.modes) {
                    number(l.re)?;
                    number(l.im)?;
                    eigs.push(json!({"re": l.re, "im": l.im, "mode": mode.name()}));
                }
                rows.push(json!({"v": v, "eigenvalues": eigs}));
            }
            let doc = json!({
                "bike": bike.label,
                "modes": s.modes.map(|m| m.name()),
                "rows": rows,
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TableFormat::Table => format!(
            "{}: eigenvalues [1/s] against forward speed v [m/s]\n{}",
            bike.label,
            whipple_report::eigen_table(&s)
        ),
    };
    emit(&text, out)
}

pub fn modes(arg: &str, speed: f64, format: TextFormat) -> Result<()> {
    let bike = load(arg)?;
    if !speed.is_finite() {
        bail!("--speed must be a finite number, got {speed}");
    }
    let c = canonical(&bike)?;
    let pairs: Vec<_> = whipple::analysis::modes::mode_shapes(&c, speed)?
        .into_iter()
        .map(|shape| (shape.pair, shape.mode.name()))
        .collect();
    let text = match format {
        TextFormat::Json => {
            let mut rows = Vec::new();
            for (pair, label) in &pairs {
                let mut vector = Vec::new();
                for z in pair.vector.iter() {
                    number(z.re)?;
                    number(z.im)?;
                    vector.push(json!([z.re, z.im]));
                }
                rows.push(json!({
                    "mode": label,
                    "eigenvalue": [pair.value.re, pair.value.im],
                    "eigenvector": vector,
                }));
            }
            let doc = json!({
                "bike": bike.label,
                "speed": speed,
                "state": ["lean", "steer", "lean_rate", "steer_rate"],
                "modes": rows,
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = format!(
                "{} at v = {} m/s: eigenvalues and mode shapes\n\
                 (eigenvector x = [lean, steer, lean rate, steer rate], unit length; steer/lean is the\n\
                 steer amplitude per unit lean amplitude and its phase)\n",
                bike.label,
                number(speed)?
            );
            for (pair, label) in &pairs {
                let l = pair.value;
                let x = pair.vector;
                let ratio = if x[0].norm() > 0.0 {
                    x[1] / x[0]
                } else {
                    x[1] * f64::INFINITY
                };
                write!(
                    t,
                    "\n{label:<13} λ = {} {} {}i 1/s",
                    number(l.re)?,
                    if l.im < 0.0 { '-' } else { '+' },
                    number(l.im.abs())?
                )?;
                if l.im != 0.0 {
                    write!(
                        t,
                        "  (period {:.4} s)",
                        2.0 * std::f64::consts::PI / l.im.abs()
                    )?;
                }
                if l.re != 0.0 {
                    write!(
                        t,
                        "  ({} {:.4} s)",
                        if l.re < 0.0 {
                            "time to half"
                        } else {
                            "time to double"
                        },
                        std::f64::consts::LN_2 / l.re.abs()
                    )?;
                }
                writeln!(t)?;
                for (name, z) in ["lean", "steer", "lean rate", "steer rate"]
                    .iter()
                    .zip(x.iter())
                {
                    // Adding 0.0 turns a negative zero into zero (no "-0.000" or "-180 deg").
                    let z = nalgebra::Complex::new(z.re + 0.0, z.im + 0.0);
                    writeln!(
                        t,
                        "    {name:<11} {:>12.6} {} {:.6}i   (magnitude {:.6}, phase {:>8.3} deg)",
                        z.re,
                        if z.im < 0.0 { '-' } else { '+' },
                        z.im.abs(),
                        z.norm(),
                        z.arg().to_degrees()
                    )?;
                }
                if ratio.re.is_finite() && ratio.im.is_finite() {
                    writeln!(
                        t,
                        "    steer/lean  {:.6} at {:.3} deg",
                        ratio.norm(),
                        nalgebra::Complex::new(ratio.re + 0.0, ratio.im + 0.0)
                            .arg()
                            .to_degrees()
                    )?;
                }
            }
            t
        }
    };
    emit(&text, None)
}

pub fn draw(arg: &str, out: &Path) -> Result<()> {
    let bike = load(arg)?;
    crate::figures::side_view(&bike, out)
}

pub fn serve(address: std::net::IpAddr, port: u16, open: bool) -> Result<()> {
    whipple_web::run(whipple_web::ServeOptions {
        address,
        port,
        open,
        ..whipple_web::ServeOptions::default()
    })
    .context("whipple serve")
}
