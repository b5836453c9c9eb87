//! One function per subcommand.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result, bail};
use nalgebra::Matrix2;
use serde_json::json;
use whipple::advanced::io::{Format, moore2012_yaml, principal_yaml, write};
use whipple::advanced::parameters::Description;
use whipple::advanced::sensitivity;
use whipple::advanced::sweep;
use whipple::advanced::table::key_doc;
use whipple::presets::PRESETS;
use whipple::{Bicycle, Canonical};

use crate::bike::{LoadedBike, RunContext, load};
use crate::output::{self, Sink, Target, number, print_stdout};
use crate::{FileFormat, TableFormat, TextFormat};
use whipple_front::units::SpeedUnit;

/// Prints `text` to standard output or writes it whole to `out` (checked before the work).
pub fn emit(text: &str, out: Option<&Target>) -> Result<()> {
    match out {
        Some(target) => target.write_whole(text.as_bytes()),
        None => print_stdout(text),
    }
}

/// The most speeds `eig` sweeps: each is computed twice (the modes are labelled by a first
/// pass, the rows streamed by a second, so memory stays bounded whatever the count) and
/// written as a row of about 170 bytes of CSV or 400 of JSON.
pub const MAX_EIG_SPEEDS: u64 = 10_000_000;

/// The most speeds an eigenvalue plot draws: a longer sweep is thinned to every k-th speed
/// (a figure a few thousand pixels wide shows no more).
pub const MAX_PLOT_SPEEDS: u64 = 20_000;

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

pub fn show(cx: &RunContext, arg: &str) -> Result<()> {
    let bike = load(cx, arg)?;
    let mut text = String::new();
    writeln!(text, "{}", bike.label)?;
    if let Some(source) = &bike.bicycle.source {
        writeln!(text, "source: {source}")?;
    }
    if let Some(j) = bike.bicycle.jbike6() {
        writeln!(text, "\nJBike6 form (x forward, y up; SI units, radians):")?;
        for (name, value) in j.fields() {
            let sigma = match bike.bicycle.sigma.get(&name) {
                Some(s) => format!(" ± {}", number(*s)?),
                None => String::new(),
            };
            writeln!(
                text,
                "  {name:<18} {:>22}{sigma}  {}",
                number(value)?,
                key_doc(&name).unwrap_or_default()
            )?;
        }
    }
    writeln!(
        text,
        "\nBenchmark form (Meijaard et al. 2007; x forward, y right, z down):"
    )?;
    let own = bike.bicycle.jbike6().is_none();
    for (key, value) in bike.benchmark.fields() {
        let sigma = match bike.bicycle.sigma.get(key) {
            Some(s) if own => format!(" ± {}", number(*s)?),
            _ => String::new(),
        };
        writeln!(
            text,
            "  {key:<5} {:>22}{sigma}  {}",
            number(value)?,
            key_doc(key).unwrap_or_default()
        )?;
    }
    for e in &bike.bicycle.extras {
        writeln!(text, "  (not used) {} = {}: {}", e.key, e.text, e.meaning)?;
    }
    writeln!(
        text,
        "  (steer axis tilt {:.4} deg, head angle {:.4} deg)",
        bike.benchmark.lambda.to_degrees(),
        90.0 - bike.benchmark.lambda.to_degrees()
    )?;
    emit(&text, None)
}

pub fn convert(
    cx: &RunContext,
    arg: &str,
    to: FileFormat,
    keep_form: bool,
    out: Option<&Path>,
) -> Result<()> {
    let out = out.map(|p| Target::check("--out", p)).transpose()?;
    let bike = load(cx, arg)?;
    let bicycle = if keep_form {
        bike.bicycle.clone()
    } else {
        let (sigma, units) = if bike.bicycle.jbike6().is_none() {
            (bike.bicycle.sigma.clone(), bike.bicycle.units.clone())
        } else {
            // The sigmas and units typed of the JBike6 form do not carry over to the combined
            // bodies.
            Default::default()
        };
        Bicycle {
            description: Description::Benchmark(bike.benchmark),
            sigma,
            units,
            ..bike.bicycle.clone()
        }
    };
    let format = match to {
        FileFormat::Toml => Format::Toml,
        FileFormat::Json => Format::Json,
        FileFormat::M => Format::Jbike6M,
        FileFormat::BpTxt => Format::BicycleParametersTxt,
        FileFormat::HcTxt => Format::HumanControlTxt,
        FileFormat::Yaml => Format::Yaml,
        FileFormat::PrincipalYaml => {
            let text = principal_yaml(&bicycle)
                .with_context(|| format!("writing {} as a principal set", bike.label))?;
            return emit(&text, out.as_ref());
        }
        FileFormat::Moore2012Yaml => {
            let text = moore2012_yaml(&bicycle)
                .with_context(|| format!("writing {} as a Moore 2012 set", bike.label))?;
            return emit(&text, out.as_ref());
        }
    };
    let text = write(&bicycle, format).with_context(|| {
        if keep_form && bicycle.jbike6().is_some() {
            "--keep-form keeps the JBike6 bodies: leave it out to write the benchmark form"
                .to_string()
        } else {
            format!("writing {}", bike.label)
        }
    })?;
    emit(&text, out.as_ref())
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

pub fn matrices(cx: &RunContext, arg: &str, jbike6: bool, format: TextFormat) -> Result<()> {
    let bike = load(cx, arg)?;
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

/// The rows of an eigenvalue table against speed (`whipple eig`'s, and the closed loop's of
/// `whipple control feedback`): a head, one row per speed, a tail, in the chosen format.
pub(crate) struct EigenRows {
    format: TableFormat,
    modes: [whipple::advanced::modes::Mode; 4],
    rows: u64,
    /// The unit the speeds were typed in: km/h gives the table's speeds in km/h and adds a
    /// `v_kmh` column to the CSV and JSON (whose `v` stays in m/s).
    unit: SpeedUnit,
}

impl EigenRows {
    pub(crate) fn new(format: TableFormat, modes: [whipple::advanced::modes::Mode; 4]) -> Self {
        EigenRows {
            format,
            modes,
            rows: 0,
            unit: SpeedUnit::MetresPerSecond,
        }
    }

    /// The rows for speeds typed in `unit`.
    pub(crate) fn typed_in(mut self, unit: SpeedUnit) -> Self {
        self.unit = unit;
        self
    }

    fn kmh(&self) -> bool {
        self.unit == SpeedUnit::KilometresPerHour
    }

    /// The head: `what` names the eigenvalues in the table's title ("eigenvalues",
    /// "closed-loop eigenvalues"); `fields` go at the top of the JSON object, after `bike`.
    pub(crate) fn head(
        &self,
        label: &str,
        what: &str,
        fields: &serde_json::Map<String, serde_json::Value>,
    ) -> Result<String> {
        Ok(match self.format {
            TableFormat::Csv if self.kmh() => {
                format!("{},v_kmh\n", whipple_report::EIGEN_CSV_HEADER.trim_end())
            }
            TableFormat::Csv => whipple_report::EIGEN_CSV_HEADER.to_string(),
            TableFormat::Json => {
                let mut head = format!("{{\n  \"bike\": {},", serde_json::to_string(label)?);
                for (key, value) in fields {
                    write!(
                        head,
                        "\n  {}: {},",
                        serde_json::to_string(key)?,
                        serde_json::to_string(value)?
                    )?;
                }
                write!(
                    head,
                    "\n  \"modes\": {},\n  \"rows\": [",
                    serde_json::to_string(&self.modes.map(|m| m.name()))?
                )?;
                head
            }
            TableFormat::Table => format!(
                "{label}: {what} [1/s] against forward speed v [{}]\n{}",
                self.unit.symbol(),
                whipple_report::eigen_table_header(&self.modes)
            ),
        })
    }

    /// One speed's row.
    pub(crate) fn row(
        &mut self,
        v: f64,
        values: &[whipple::advanced::eigen::Complex64; 4],
    ) -> Result<String> {
        if let Some(l) = values
            .iter()
            .find(|l| !(l.re.is_finite() && l.im.is_finite()))
        {
            bail!("the eigenvalue {l} at v = {v} m/s is not a finite number");
        }
        let row = match self.format {
            TableFormat::Csv if self.kmh() => format!(
                "{},{}\n",
                whipple_report::eigen_csv_row(v, values).trim_end(),
                output::kmh_number(v)?
            ),
            TableFormat::Csv => whipple_report::eigen_csv_row(v, values),
            TableFormat::Table => whipple_report::eigen_table_row(self.unit.from_si(v), values),
            TableFormat::Json => {
                let eigs: Vec<_> = values
                    .iter()
                    .zip(self.modes)
                    .map(|(l, mode)| json!({"re": l.re, "im": l.im, "mode": mode.name()}))
                    .collect();
                let row = if self.kmh() {
                    let kmh = output::as_typed(v, self.unit);
                    json!({"v": v, "v_kmh": kmh, "eigenvalues": eigs})
                } else {
                    json!({"v": v, "eigenvalues": eigs})
                };
                format!(
                    "{}\n    {}",
                    if self.rows == 0 { "" } else { "," },
                    serde_json::to_string(&row)?
                )
            }
        };
        self.rows += 1;
        Ok(row)
    }

    /// The tail: `fields` go at the end of the JSON object, before `warnings`.
    pub(crate) fn tail(
        &self,
        warnings: &serde_json::Value,
        fields: &serde_json::Map<String, serde_json::Value>,
    ) -> Result<String> {
        if self.format != TableFormat::Json {
            return Ok(String::new());
        }
        let mut tail = "\n  ],".to_string();
        for (key, value) in fields {
            let pretty = serde_json::to_string_pretty(value)?.replace('\n', "\n  ");
            write!(tail, "\n  {}: {pretty},", serde_json::to_string(key)?)?;
        }
        write!(
            tail,
            "\n  \"warnings\": {}\n}}\n",
            serde_json::to_string(warnings)?
        )?;
        Ok(tail)
    }
}

pub fn eig(
    cx: &RunContext,
    arg: &str,
    speeds: &str,
    format: TableFormat,
    out: Option<&Path>,
    plot: Option<&Path>,
    sigma_bands: bool,
) -> Result<()> {
    let (out, plot) = output::table_and_plot(out, plot)?;
    let bike = load(cx, arg)?;
    let ((start, stop, step), unit) = output::parse_triple_in(speeds, "--speeds")?;
    let grid = sweep::SpeedGrid::new(start, stop, step).context("--speeds")?;
    if grid.len() > MAX_EIG_SPEEDS {
        bail!(
            "--speeds {speeds} holds {} speeds, more than the limit of {MAX_EIG_SPEEDS} \
             (each speed is solved twice and written as a row of about 170 bytes: the limit \
             is about 1.7 GB of CSV); use a larger step or a narrower range",
            grid.len()
        );
    }
    if sigma_bands && !bike.bicycle.has_uncertainty() {
        bail!(
            "--sigma-bands: {} gives no standard deviations (+/-sigma or {{ value, sigma }})",
            bike.label
        );
    }
    let c = canonical(&bike)?;
    // Every output is opened (its temporary file created) before the work.
    // Beside a plot, a table reader that goes away ends only the table.
    let mut sink = match &out {
        Some(target) => target.open()?,
        None if plot.is_some() => Sink::stdout_beside_files(),
        None => Sink::stdout(),
    };
    let plot_sink = plot.as_ref().map(Target::open).transpose()?;
    let plan = sweep::SweepPlan::new(&c, grid.iter())?;
    let modes = plan.modes();
    let every = grid.len().div_ceil(MAX_PLOT_SPEEDS).max(1);
    let last = grid.len() - 1;
    let mut shown = whipple::EigenSweep {
        speeds: Vec::new(),
        eigenvalues: Vec::new(),
        modes,
    };
    let mut rows = EigenRows::new(format, modes).typed_in(unit);
    sink.text(&rows.head(&bike.label, "eigenvalues", &serde_json::Map::new())?)?;
    let mut i = 0u64;
    plan.rows(|v, values| -> Result<()> {
        sink.text(&rows.row(v, values)?)?;
        if plot_sink.is_some() && (i % every == 0 || i == last) {
            shown.speeds.push(v);
            shown.eigenvalues.push(*values);
        }
        i += 1;
        Ok(())
    })?;
    sink.text(&rows.tail(&bike.warnings_json(), &serde_json::Map::new())?)?;
    let mut finished = vec![sink.finish()?];
    if let (Some(mut plot_sink), Some(target)) = (plot_sink, &plot) {
        if every > 1 {
            eprintln!(
                "note: {} draws every {every}th of the {} speeds ({} points)",
                target.describe(),
                grid.len(),
                shown.speeds.len()
            );
        }
        let critical = whipple::critical_speeds(&c, start.min(stop), stop.max(start + step))?;
        let bands = if sigma_bands {
            Some(eigen_sigma_bands(&bike, &shown)?)
        } else {
            None
        };
        let bytes = crate::figures::eigen_plot_bytes(
            &bike,
            "eigenvalues",
            &shown,
            &critical,
            bands.as_deref(),
            unit,
            target.path(),
        )?;
        plot_sink.bytes(&bytes)?;
        finished.push(plot_sink.finish()?);
    }
    output::commit(finished)
}

pub fn modes(
    cx: &RunContext,
    arg: &str,
    typed: crate::TypedSpeed,
    format: TextFormat,
) -> Result<()> {
    let speed = typed.si;
    let bike = load(cx, arg)?;
    if !speed.is_finite() {
        bail!("--speed must be a finite number, got {speed:?}");
    }
    let c = canonical(&bike)?;
    let pairs: Vec<_> = whipple::advanced::modes::mode_shapes(&c, speed)
        .with_context(|| format!("--speed {speed:?}"))?
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
                "{} at v = {}: eigenvalues and mode shapes\n\
                 (eigenvector x = [lean, steer, lean rate, steer rate], unit length; steer/lean is the\n\
                 steer amplitude per unit lean amplitude and its phase)\n",
                bike.label,
                output::speed_words(speed, typed.unit)?
            );
            for (pair, label) in &pairs {
                let l = pair.value;
                let x = pair.vector;
                let ratio = if whipple::math::norm(x[0]) > 0.0 {
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
                        whipple::math::norm(z),
                        whipple::math::arg(z).to_degrees()
                    )?;
                }
                if ratio.re.is_finite() && ratio.im.is_finite() {
                    writeln!(
                        t,
                        "    steer/lean  {:.6} at {:.3} deg",
                        whipple::math::norm(ratio),
                        whipple::math::arg(nalgebra::Complex::new(ratio.re + 0.0, ratio.im + 0.0))
                            .to_degrees()
                    )?;
                }
            }
            t
        }
    };
    emit(&text, None)
}

pub(crate) fn optional(x: Option<f64>) -> Result<serde_json::Value> {
    match x {
        Some(v) => {
            number(v)?;
            Ok(json!(v))
        }
        None => Ok(serde_json::Value::Null),
    }
}

/// `value ± sigma unit` when a sigma is known, else `value unit`.
pub(crate) fn with_sigma(v: f64, sigma: Option<f64>, unit: &str) -> Result<String> {
    Ok(match sigma {
        Some(s) if s > 0.0 => format!("{} ± {} {unit}", round_to_sigma(v, s), round_sigma(s)),
        _ => format!("{} {unit}", number(v)?),
    })
}

/// A standard deviation to three significant digits.
pub(crate) fn round_sigma(s: f64) -> String {
    let digits = (2 - whipple::math::log10(s.abs()).floor() as i32).max(0) as usize;
    format!("{s:.digits$}")
}

/// A value to the decimals of its three-digit standard deviation.
pub(crate) fn round_to_sigma(v: f64, s: f64) -> String {
    let digits = (2 - whipple::math::log10(s.abs()).floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

/// Each tracked eigenvalue's real part ± σ at every speed of the sweep.
fn eigen_sigma_bands(bike: &LoadedBike, s: &whipple::EigenSweep) -> Result<Vec<[(f64, f64); 4]>> {
    let d = sensitivity::ParameterDerivatives::new(&bike.bicycle)?;
    let mut bands = Vec::with_capacity(s.speeds.len());
    for (v, row) in s.speeds.iter().zip(&s.eigenvalues) {
        let sig = sensitivity::eigenvalue_sigmas(&d, *v)?;
        let mut out = [(f64::NAN, f64::NAN); 4];
        for (k, l) in row.iter().enumerate() {
            let nearest = sig.iter().min_by(|a, b| {
                let da = whipple::math::hypot(a.re - l.re, a.im - l.im);
                let db = whipple::math::hypot(b.re - l.re, b.im - l.im);
                da.total_cmp(&db)
            });
            if let Some(e) = nearest {
                if let Some(sr) = e.re_sigma {
                    out[k] = (l.re - sr, l.re + sr);
                }
            }
        }
        bands.push(out);
    }
    Ok(bands)
}

pub fn sensitivity(
    cx: &RunContext,
    arg: &str,
    typed: Option<crate::TypedSpeed>,
    range: &str,
    format: TableFormat,
    out: Option<&Path>,
    plot: Option<&Path>,
) -> Result<()> {
    let (out, plot) = output::table_and_plot(out, plot)?;
    let bike = load(cx, arg)?;
    let speed = typed.map(|t| t.si);
    let ((lo, hi), range_unit) = crate::speeds::parse_range_in(range, "--range")?;
    // Typed in km/h (the range, or else the speed), the base speeds are given in km/h too.
    let unit = match typed {
        Some(t) if range_unit == SpeedUnit::MetresPerSecond => t.unit,
        _ => range_unit,
    };
    if lo >= hi {
        bail!("--range: LO ({lo}) must be less than HI ({hi})");
    }
    if let Some(v) = speed {
        if !v.is_finite() || v < 0.0 {
            bail!("--speed must be a finite speed ≥ 0, got {v}");
        }
    }
    let s = sensitivity::sensitivities(&bike.bicycle, lo, hi, speed)
        .with_context(|| format!("the sensitivities of {}", bike.label))?;
    // The plot is drawn (and fails, if it must) before anything is written.
    let plot_bytes = plot
        .as_ref()
        .map(|target| crate::figures::tornado(&bike, &s, target.path()))
        .transpose()?;
    let opt = |x: Option<f64>| -> Result<String> {
        Ok(match x {
            Some(v) => number(v)?,
            None => String::new(),
        })
    };
    let text = match format {
        TableFormat::Json => {
            let mut doc = serde_json::to_value(&s)?;
            doc["bike"] = json!(bike.label);
            doc["warnings"] = bike.warnings_json();
            for p in &s.parameters {
                for x in [
                    p.weave_speed,
                    p.capsize_speed,
                    p.stable_width,
                    p.weave_real,
                    p.capsize_real,
                ]
                .into_iter()
                .flatten()
                {
                    number(x)?;
                }
            }
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TableFormat::Csv => {
            let mut t = String::from(
                "key,unit,value,d_weave_speed,d_capsize_speed,d_stable_width,e_weave_speed,e_capsize_speed,e_stable_width,d_weave_real,d_capsize_real\n",
            );
            for p in &s.parameters {
                writeln!(
                    t,
                    "{},{},{},{},{},{},{},{},{},{},{}",
                    p.key,
                    p.unit,
                    number(p.value)?,
                    opt(p.weave_speed)?,
                    opt(p.capsize_speed)?,
                    opt(p.stable_width)?,
                    opt(p.weave_speed_elasticity)?,
                    opt(p.capsize_speed_elasticity)?,
                    opt(p.stable_width_elasticity)?,
                    opt(p.weave_real)?,
                    opt(p.capsize_real)?
                )?;
            }
            t
        }
        TableFormat::Table => {
            let c = &s.critical;
            let mut t = format!(
                "{}: exact sensitivities (dual numbers) to each parameter of its {} form\n",
                bike.label,
                match s.form {
                    whipple::advanced::table::Form::Benchmark => "benchmark",
                    whipple::advanced::table::Form::Jbike6 => "JBike6",
                }
            );
            // Six decimals of m/s; typed in km/h, five of km/h beside.
            let show = |x: Option<f64>| {
                x.map_or("none".to_string(), |v| match unit {
                    SpeedUnit::MetresPerSecond => format!("{v:.6} m/s"),
                    SpeedUnit::KilometresPerHour => {
                        format!("{v:.6} m/s ({:.5} km/h)", unit.from_si(v))
                    }
                })
            };
            writeln!(
                t,
                "  base: v_w = {}, v_c = {}, stable width = {}",
                show(c.weave_speed),
                show(c.capsize_speed),
                show(s.stable_range.map(|(a, b)| b - a))
            )?;
            writeln!(
                t,
                "  d/dp: derivative per unit of p; e: elasticity d ln(.)/d ln p (dimensionless)"
            )?;
            let g = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.4e}"));
            let e = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:+.4}"));
            write!(
                t,
                "  {:<16} {:>8} {:>14} {:>12} {:>9} {:>12} {:>9} {:>12} {:>9}",
                "parameter",
                "unit",
                "value",
                "dv_w/dp",
                "e(v_w)",
                "dv_c/dp",
                "e(v_c)",
                "dwidth/dp",
                "e(width)"
            )?;
            // The speed as typed: `@5`, `@18km/h`; the columns as wide as their heads.
            let mut width = 12;
            if let Some(typed) = typed {
                let at = match typed.unit {
                    SpeedUnit::MetresPerSecond => number(typed.si)?,
                    SpeedUnit::KilometresPerHour => {
                        format!("{}km/h", output::speed_number(typed.si, typed.unit)?)
                    }
                };
                let (w, c) = (format!("dRe_w/dp@{at}"), format!("dRe_c/dp@{at}"));
                width = width.max(w.chars().count());
                write!(t, " {w:>width$} {c:>width$}")?;
            }
            writeln!(t)?;
            for p in &s.parameters {
                write!(
                    t,
                    "  {:<16} {:>8} {:>14} {:>12} {:>9} {:>12} {:>9} {:>12} {:>9}",
                    p.key,
                    p.unit,
                    number(p.value)?,
                    g(p.weave_speed),
                    e(p.weave_speed_elasticity),
                    g(p.capsize_speed),
                    e(p.capsize_speed_elasticity),
                    g(p.stable_width),
                    e(p.stable_width_elasticity)
                )?;
                if speed.is_some() {
                    write!(
                        t,
                        " {:>width$} {:>width$}",
                        g(p.weave_real),
                        g(p.capsize_real)
                    )?;
                }
                writeln!(t)?;
            }
            t
        }
    };
    let mut finished = Vec::new();
    if let (Some(target), Some(bytes)) = (&plot, &plot_bytes) {
        let mut sink = target.open()?;
        sink.bytes(bytes)?;
        finished.push(sink.finish()?);
    }
    let mut sink = match &out {
        Some(target) => target.open()?,
        None if plot.is_some() => Sink::stdout_beside_files(),
        None => Sink::stdout(),
    };
    sink.text(&text)?;
    finished.push(sink.finish()?);
    output::commit(finished)
}

pub fn draw(cx: &RunContext, arg: &str, out: &Path) -> Result<()> {
    whipple_report::Format::from_path(out).with_context(|| format!("--out {}", out.display()))?;
    let target = Target::check("--out", out)?;
    let bike = load(cx, arg)?;
    crate::figures::side_view(&bike, &target)
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
