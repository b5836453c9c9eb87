//! `whipple control feedback | lqr | place`: the bicycle under full-state feedback
//! u = r − K x on (φ, δ, φ̇, δ̇). The core closes the loop, sweeps it, certifies its critical
//! speeds and designs K; this file reads the options and prints the results with `eig`'s rows
//! ([`EigenRows`]) and `speeds`' words ([`crate::speeds::worded_table`]).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use nalgebra::DMatrix;
use serde_json::json;
use whipple::CriticalSpeeds;
use whipple::advanced::control::{ClosedLoop, Gains, MAX_SCHEDULE_SPEEDS, lqr_schedule};
use whipple::advanced::eigen::Complex64;
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};

use crate::bike::{RunContext, load};
use crate::commands::{EigenRows, MAX_EIG_SPEEDS, MAX_PLOT_SPEEDS, emit};
use crate::control::complex;
use crate::output::{self, Sink, Target, number, parse_triple_in};
use crate::speeds::{parse_range_in, worded_table};
use crate::{TableFormat, TextFormat};
use whipple_front::units::SpeedUnit;

/// The states K reads, in the order of its columns.
const STATES: &str = "φ, δ, φ̇, δ̇";

/// The options of `whipple control feedback`.
pub(crate) struct FeedbackArgs<'a> {
    pub bike: &'a str,
    pub gains: Option<&'a str>,
    pub schedule: Option<&'a Path>,
    pub inputs: &'a [String],
    pub speeds: Option<&'a str>,
    pub format: TableFormat,
    pub out: Option<&'a Path>,
    pub plot: Option<&'a Path>,
    pub range: Option<&'a str>,
}

/// A core error whose field the user typed as an option: `options` maps the core's field
/// names (`Q`, `gains`, …) to the options (`--q`, `--gains`, …); other errors pass unchanged.
fn named(error: whipple::Error, options: &[(&str, &str)]) -> anyhow::Error {
    let option = match &error {
        whipple::Error::InvalidArgument { what, .. } => options
            .iter()
            .find(|(field, _)| field == what)
            .map(|(_, option)| *option),
        _ => None,
    };
    match option {
        Some(option) => anyhow::Error::new(error).context(option.to_string()),
        None => anyhow::Error::new(error),
    }
}

/// The inputs as typed (default: steer torque).
fn inputs(typed: &[String]) -> Result<Vec<Input>> {
    if typed.is_empty() {
        return Ok(vec![Input::SteerTorque]);
    }
    typed
        .iter()
        .map(|name| whipple_front::system::parse_input(name))
        .collect::<whipple::Result<_>>()
        .context("--input")
}

/// The lean–steer system with `inputs` (K reads φ, δ, φ̇, δ̇).
fn request(inputs: Vec<Input>) -> SystemRequest {
    SystemRequest {
        states: Vec::new(),
        inputs,
        outputs: StateVariable::LEAN_STEER.map(Output::State).to_vec(),
    }
}

/// A matrix as typed: rows separated by `;`, entries by `,`, or `diag:a,b,…`.
fn parse_matrix(text: &str, option: &str) -> Result<DMatrix<f64>> {
    let entry = |t: &str| -> Result<f64> {
        let t = t.trim();
        match t.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => bail!("{option}: `{t}` is not a finite number"),
        }
    };
    if let Some(diagonal) = text.trim().strip_prefix("diag:") {
        let d = diagonal.split(',').map(entry).collect::<Result<Vec<_>>>()?;
        return Ok(DMatrix::from_diagonal(&nalgebra::DVector::from_vec(d)));
    }
    let rows = text
        .split(';')
        .map(|row| row.split(',').map(entry).collect::<Result<Vec<_>>>())
        .collect::<Result<Vec<_>>>()?;
    let columns = rows.first().map_or(0, Vec::len);
    if let Some((i, row)) = rows
        .iter()
        .enumerate()
        .find(|(_, row)| row.len() != columns)
    {
        bail!(
            "{option}: every row needs the same number of entries: row 1 has {columns}, row {} \
             has {} (rows are separated by `;`, entries by `,`)",
            i + 1,
            row.len()
        );
    }
    Ok(DMatrix::from_row_iterator(
        rows.len(),
        columns,
        rows.into_iter().flatten(),
    ))
}

/// K as typed in `--gains`: inputs × 4.
pub(crate) fn parse_gains(text: &str, inputs: usize) -> Result<DMatrix<f64>> {
    let k = parse_matrix(text, "--gains")?;
    if k.shape() != (inputs, 4) {
        bail!(
            "--gains: K must be {inputs} × 4 (one row per input, rows separated by `;`; the \
             columns are {STATES}), got {} × {}",
            k.nrows(),
            k.ncols()
        );
    }
    Ok(k)
}

/// A gain schedule from a CSV file of rows `speed,k1,k2,…` (K's rows one after the other).
fn read_schedule(path: &Path, inputs: usize) -> Result<Gains> {
    let shown = path.display();
    let text = std::fs::read_to_string(path).with_context(|| format!("--schedule {shown}"))?;
    // An input: no output may be written onto it.
    output::register_input(path);
    let width = 1 + 4 * inputs;
    let mut speeds = Vec::new();
    let mut gains = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let values: Option<Vec<f64>> = fields
            .iter()
            .map(|f| f.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        let Some(values) = values else {
            if i == 0 && fields.iter().any(|f| f.parse::<f64>().is_err()) {
                // A first line of names.
                continue;
            }
            bail!(
                "{shown}:{}: every field must be a finite number, got `{line}`",
                i + 1
            );
        };
        if values.len() != width {
            bail!(
                "{shown}:{}: a row is `speed,k1,…,k{}` ({width} fields: the speed in m/s and K's \
                 {inputs} row(s) of 4 gains, columns {STATES}), got {} fields",
                i + 1,
                width - 1,
                values.len()
            );
        }
        if let Some(&last) = speeds.last()
            && values[0] <= last
        {
            bail!(
                "{shown}:{}: the speeds must increase, got {} after {}",
                i + 1,
                number(values[0])?,
                number(last)?
            );
        }
        if speeds.len() == MAX_SCHEDULE_SPEEDS {
            bail!("{shown}: at most {MAX_SCHEDULE_SPEEDS} rows");
        }
        speeds.push(values[0]);
        gains.push(DMatrix::from_row_slice(inputs, 4, &values[1..]));
    }
    if speeds.len() < 2 {
        bail!(
            "{shown}: a schedule needs at least two rows `speed,k1,…`, got {}",
            speeds.len()
        );
    }
    Ok(Gains::Scheduled { speeds, gains })
}

/// One complex number as typed: `-2`, `-4+1i`, `-4-1.5j`, `3i`.
fn parse_complex(text: &str, option: &str) -> Result<Complex64> {
    let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    let bad = || anyhow!("{option}: `{text}` is not a number like -2 or -4+1i");
    let finite = |s: &str| -> Result<f64> {
        s.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(bad)
    };
    let Some(body) = t.strip_suffix('i').or_else(|| t.strip_suffix('j')) else {
        return Ok(Complex64::new(finite(&t)?, 0.0));
    };
    // The imaginary part starts at the last sign that is not the first character and not
    // an exponent's.
    let bytes = body.as_bytes();
    let split = (1..bytes.len())
        .rev()
        .find(|&k| matches!(bytes[k], b'+' | b'-') && !matches!(bytes[k - 1], b'e' | b'E'));
    let imaginary = |s: &str| -> Result<f64> {
        match s {
            "" | "+" => Ok(1.0),
            "-" => Ok(-1.0),
            _ => finite(s),
        }
    };
    Ok(match split {
        Some(k) => Complex64::new(finite(&body[..k])?, imaginary(&body[k..])?),
        None => Complex64::new(0.0, imaginary(body)?),
    })
}

/// A matrix as JSON rows.
fn matrix_json(m: &DMatrix<f64>) -> Result<serde_json::Value> {
    let mut rows = Vec::new();
    for i in 0..m.nrows() {
        let mut row = Vec::new();
        for j in 0..m.ncols() {
            number(m[(i, j)])?;
            row.push(m[(i, j)]);
        }
        rows.push(json!(row));
    }
    Ok(json!(rows))
}

/// A matrix as aligned text rows, each indented by `indent`.
fn matrix_text(m: &DMatrix<f64>, indent: &str) -> Result<String> {
    let mut t = String::new();
    for i in 0..m.nrows() {
        let row = (0..m.ncols())
            .map(|j| Ok(format!("{:>22}", number(m[(i, j)])?)))
            .collect::<Result<Vec<_>>>()?;
        writeln!(t, "{indent}{}", row.join(""))?;
    }
    Ok(t)
}

fn eigenvalues_json(values: &[Complex64]) -> Result<serde_json::Value> {
    let mut out = Vec::new();
    for l in values {
        number(l.re)?;
        number(l.im)?;
        out.push(json!([l.re, l.im]));
    }
    Ok(json!(out))
}

fn eigenvalues_text(values: &[Complex64]) -> Result<String> {
    Ok(values
        .iter()
        .map(|l| complex(*l))
        .collect::<Result<Vec<_>>>()?
        .join(", "))
}

fn input_names(inputs: &[Input]) -> Vec<String> {
    inputs.iter().map(ToString::to_string).collect()
}

/// `whipple control feedback`.
pub(crate) fn feedback(cx: &RunContext, args: &FeedbackArgs) -> Result<()> {
    let (out, plot) = output::table_and_plot(args.out, args.plot)?;
    let bike = load(cx, args.bike)?;
    let inputs = inputs(args.inputs)?;
    let count = inputs.len();
    let (gains, gains_option) = match (args.gains, args.schedule) {
        (Some(text), None) => (Gains::Constant(parse_gains(text, count)?), "--gains"),
        (None, Some(path)) => (read_schedule(path, count)?, "--schedule"),
        _ => bail!("give the gains: --gains K or --schedule FILE.csv"),
    };
    let request = request(inputs.clone());
    let closed = ClosedLoop::new(&bike.benchmark, &request, gains).map_err(|e| {
        named(
            e,
            &[
                ("gains", gains_option),
                ("speeds", gains_option),
                ("inputs", "--input"),
            ],
        )
    })?;
    let (first, last) = closed.gains().speed_range();
    let scheduled = first.is_finite();
    // The unit the speeds were typed in (--speeds, else --range): km/h gives them in km/h too.
    let mut unit = SpeedUnit::MetresPerSecond;
    let grid = match args.speeds {
        Some(text) => {
            let ((start, stop, step), typed) = parse_triple_in(text, "--speeds")?;
            unit = typed;
            let grid =
                whipple::advanced::sweep::SpeedGrid::new(start, stop, step).context("--speeds")?;
            if grid.len() > MAX_EIG_SPEEDS {
                bail!(
                    "--speeds {text} holds {} speeds, more than the limit of {MAX_EIG_SPEEDS}",
                    grid.len()
                );
            }
            grid.iter().collect::<Vec<f64>>()
        }
        None if scheduled => (0..=100)
            .map(|i| first + (last - first) * f64::from(i) / 100.0)
            .collect(),
        None => (0..=100).map(|i| f64::from(i) / 10.0).collect(),
    };
    let (lo, hi) = match args.range {
        Some(text) => {
            let (range, typed) = parse_range_in(text, "--range")?;
            if args.speeds.is_none() {
                unit = typed;
            }
            range
        }
        None if scheduled => (first, last),
        None => (0.0, f64::INFINITY),
    };
    let sweep = closed
        .eigen_sweep(&grid)
        .map_err(|e| named(e, &[("speed", "--speeds")]))?;
    let critical = closed
        .critical_speeds(lo, hi)
        .map_err(|e| named(e, &[("speed", "--range"), ("range", "--range")]))?;

    // Every output is opened (its temporary file created) before it is written.
    let mut sink = match (&out, &plot) {
        (Some(target), _) => target.open()?,
        (None, Some(_)) => Sink::stdout_beside_files(),
        (None, None) => Sink::stdout(),
    };
    let plot_sink = plot.as_ref().map(Target::open).transpose()?;
    let mut rows = EigenRows::new(args.format, sweep.modes).typed_in(unit);
    let mut fields = serde_json::Map::new();
    fields.insert("inputs".into(), json!(input_names(&inputs)));
    fields.insert(
        "states".into(),
        json!(["lean", "steer", "lean_rate", "steer_rate"]),
    );
    fields.insert("gains".into(), gains_json(closed.gains())?);
    let label = format!("{} under feedback", bike.label);
    let mut head = rows.head(&bike.label, "closed-loop eigenvalues", &fields)?;
    if args.format == TableFormat::Table {
        head = format!(
            "{}{head}",
            gains_text(closed.gains(), &input_names(&inputs))?
        );
    }
    sink.text(&head)?;
    for (v, values) in sweep.speeds.iter().zip(&sweep.eigenvalues) {
        sink.text(&rows.row(*v, values)?)?;
    }
    let mut tail_fields = serde_json::Map::new();
    tail_fields.insert("critical_speeds".into(), serde_json::to_value(&critical)?);
    let mut tail = rows.tail(&bike.warnings_json(), &tail_fields)?;
    if args.format == TableFormat::Table {
        tail = format!(
            "\n{}",
            worded_table(&label, &critical, None, "stable", unit)?
        );
    }
    sink.text(&tail)?;
    let mut finished = vec![sink.finish()?];
    if let (Some(mut plot_sink), Some(target)) = (plot_sink, &plot) {
        let every = sweep.speeds.len().div_ceil(MAX_PLOT_SPEEDS as usize).max(1);
        let shown = whipple::EigenSweep {
            speeds: sweep.speeds.iter().step_by(every).copied().collect(),
            eigenvalues: sweep.eigenvalues.iter().step_by(every).copied().collect(),
            modes: sweep.modes,
        };
        let bytes = crate::figures::eigen_plot_bytes(
            &bike,
            "closed-loop eigenvalues",
            &shown,
            &critical,
            None,
            unit,
            target.path(),
        )?;
        plot_sink.bytes(&bytes)?;
        finished.push(plot_sink.finish()?);
    }
    output::commit(finished)
}

fn gains_json(gains: &Gains) -> Result<serde_json::Value> {
    Ok(match gains {
        Gains::Constant(k) => json!({"constant": matrix_json(k)?}),
        Gains::Scheduled { speeds, gains } => {
            let mut rows = Vec::new();
            for (v, k) in speeds.iter().zip(gains) {
                rows.push(json!({"speed": v, "gains": matrix_json(k)?}));
            }
            json!({"scheduled": rows})
        }
    })
}

fn gains_text(gains: &Gains, inputs: &[String]) -> Result<String> {
    let mut t = format!(
        "feedback u = r − K x on inputs {}, K's columns {STATES}\n",
        inputs.join(", ")
    );
    match gains {
        Gains::Constant(k) => {
            t.push_str("  K =\n");
            t.push_str(&matrix_text(k, "  ")?);
        }
        Gains::Scheduled { speeds, .. } => {
            writeln!(
                t,
                "  K scheduled at {} speeds from {} to {} m/s, linear between them",
                speeds.len(),
                number(speeds[0])?,
                number(speeds[speeds.len() - 1])?
            )?;
        }
    }
    Ok(t)
}

/// The fields of the core that `--q`, `--r`, `--input` and `--speed` feed.
const LQR_OPTIONS: [(&str, &str); 5] = [
    ("Q", "--q"),
    ("R", "--r"),
    ("inputs", "--input"),
    ("speed", "--speed"),
    ("speeds", "--speeds"),
];

/// `whipple control lqr`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn lqr(
    cx: &RunContext,
    arg: &str,
    typed: Option<crate::TypedSpeed>,
    speeds: Option<&str>,
    q: &str,
    r: &str,
    typed_inputs: &[String],
    format: TextFormat,
) -> Result<()> {
    let bike = load(cx, arg)?;
    let inputs = inputs(typed_inputs)?;
    let names = input_names(&inputs);
    let request = request(inputs);
    let q = parse_matrix(q, "--q")?;
    let r = parse_matrix(r, "--r")?;
    let speed = typed.map(|t| t.si);
    let text = match (speed, speeds) {
        (Some(v), None) => {
            if !v.is_finite() {
                bail!("--speed: {v} is not a finite speed");
            }
            let system = LinearSystem::new(&bike.benchmark, v, &request)
                .map_err(|e| named(e, &LQR_OPTIONS))?;
            let lqr = system.lqr(&q, &r).map_err(|e| named(e, &LQR_OPTIONS))?;
            match format {
                TextFormat::Json => {
                    let doc = json!({
                        "bike": bike.label,
                        "speed": v,
                        "inputs": names,
                        "states": ["lean", "steer", "lean_rate", "steer_rate"],
                        "gains": matrix_json(&lqr.gains)?,
                        "solution": matrix_json(&lqr.solution)?,
                        "closed_loop_eigenvalues": eigenvalues_json(&lqr.closed_loop_eigenvalues)?,
                        "residual": lqr.residual,
                        "warnings": bike.warnings_json(),
                    });
                    format!("{}\n", serde_json::to_string_pretty(&doc)?)
                }
                TextFormat::Table => {
                    let mut t = format!(
                        "{}: LQR at v = {}, inputs {}, states {STATES}\n",
                        bike.label,
                        output::speed_words(
                            v,
                            typed.map_or(SpeedUnit::MetresPerSecond, |t| t.unit)
                        )?,
                        names.join(", ")
                    );
                    writeln!(t, "  K (u = r − K x) =")?;
                    t.push_str(&matrix_text(&lqr.gains, "  ")?);
                    writeln!(t, "  X (the Riccati equation's stabilizing solution) =")?;
                    t.push_str(&matrix_text(&lqr.solution, "  ")?);
                    writeln!(
                        t,
                        "  closed-loop poles [1/s]: {}",
                        eigenvalues_text(&lqr.closed_loop_eigenvalues)?
                    )?;
                    writeln!(
                        t,
                        "  relative residual of AᵀX + XA − XBR⁻¹BᵀX + Q = 0: {:.3e}",
                        lqr.residual
                    )?;
                    t
                }
            }
        }
        (None, Some(text)) => {
            let ((start, stop, step), unit) = parse_triple_in(text, "--speeds")?;
            let grid = whipple::speed_grid(start, stop, step).context("--speeds")?;
            let schedule = lqr_schedule(&bike.benchmark, &request, &grid, &q, &r)
                .map_err(|e| named(e, &LQR_OPTIONS))?;
            let closed = ClosedLoop::new(&bike.benchmark, &request, schedule.gains.clone())
                .map_err(|e| named(e, &LQR_OPTIONS))?;
            let (first, last) = closed.gains().speed_range();
            let critical = closed.critical_speeds(first, last)?;
            lqr_schedule_text(&bike, &names, &grid, &schedule, &critical, format, unit)?
        }
        _ => bail!("give --speed V (one speed) or --speeds START:STOP:STEP (a schedule)"),
    };
    emit(&text, None)
}

fn lqr_schedule_text(
    bike: &crate::bike::LoadedBike,
    names: &[String],
    grid: &[f64],
    schedule: &whipple::advanced::control::LqrSchedule,
    critical: &CriticalSpeeds,
    format: TextFormat,
    unit: SpeedUnit,
) -> Result<String> {
    Ok(match format {
        TextFormat::Json => {
            let mut rows = Vec::new();
            for (v, s) in grid.iter().zip(&schedule.solutions) {
                rows.push(json!({
                    "speed": v,
                    "gains": matrix_json(&s.gains)?,
                    "residual": s.residual,
                    "closed_loop_eigenvalues": eigenvalues_json(&s.closed_loop_eigenvalues)?,
                }));
            }
            let doc = json!({
                "bike": bike.label,
                "inputs": names,
                "states": ["lean", "steer", "lean_rate", "steer_rate"],
                "schedule": rows,
                "critical_speeds": serde_json::to_value(critical)?,
                "warnings": bike.warnings_json(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = format!(
                "{}: LQR gain schedule, inputs {}, K's columns {STATES} (u = r − K x)\n  \
                 v [{}]   K (row by row)   residual   slowest closed-loop pole [1/s]\n",
                bike.label,
                names.join(", "),
                unit.symbol()
            );
            for (v, s) in grid.iter().zip(&schedule.solutions) {
                let k = s
                    .gains
                    .transpose()
                    .iter()
                    .map(|x| number(*x))
                    .collect::<Result<Vec<_>>>()?
                    .join(", ");
                let slowest = s
                    .closed_loop_eigenvalues
                    .iter()
                    .copied()
                    .max_by(|a, b| a.re.total_cmp(&b.re))
                    .map(complex)
                    .transpose()?
                    .unwrap_or_default();
                let v = crate::output::speed_number(*v, unit)?;
                writeln!(t, "  {v:<9} [{k}]   {:.1e}   {slowest}", s.residual)?;
            }
            t.push('\n');
            t.push_str(&worded_table(
                &format!("{} under the scheduled LQR gains", bike.label),
                critical,
                None,
                "stable",
                unit,
            )?);
            t
        }
    })
}

/// `whipple control place`.
pub(crate) fn place(
    cx: &RunContext,
    arg: &str,
    typed: crate::TypedSpeed,
    input: &str,
    poles: &str,
    format: TextFormat,
) -> Result<()> {
    let speed = typed.si;
    let bike = load(cx, arg)?;
    if !speed.is_finite() {
        bail!("--speed: {speed} is not a finite speed");
    }
    let inputs = inputs(std::slice::from_ref(&input.to_string()))?;
    let names = input_names(&inputs);
    let request = request(inputs);
    let poles = poles
        .split(',')
        .map(|p| parse_complex(p, "--poles"))
        .collect::<Result<Vec<_>>>()?;
    let options = [
        ("poles", "--poles"),
        ("inputs", "--input"),
        ("speed", "--speed"),
    ];
    let system =
        LinearSystem::new(&bike.benchmark, speed, &request).map_err(|e| named(e, &options))?;
    let k = system.place_poles(&poles).map_err(|e| named(e, &options))?;
    let check = ClosedLoop::new(&bike.benchmark, &request, Gains::Constant(k.clone()))?
        .eigenvalues(speed)?;
    let text = match format {
        TextFormat::Json => {
            let doc = json!({
                "bike": bike.label,
                "speed": speed,
                "inputs": names,
                "states": ["lean", "steer", "lean_rate", "steer_rate"],
                "poles": eigenvalues_json(&poles)?,
                "gains": matrix_json(&k)?,
                "closed_loop_eigenvalues": eigenvalues_json(&check)?,
                "warnings": bike.warnings_json(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = format!(
                "{}: pole placement at v = {}, input {}, states {STATES}\n",
                bike.label,
                output::speed_words(speed, typed.unit)?,
                names.join(", ")
            );
            writeln!(t, "  poles asked for [1/s]: {}", eigenvalues_text(&poles)?)?;
            writeln!(t, "  K (u = r − K x) =")?;
            t.push_str(&matrix_text(&k, "  ")?);
            writeln!(
                t,
                "  check, the eigenvalues of A − B K [1/s]: {}",
                eigenvalues_text(&check)?
            )?;
            t
        }
    };
    emit(&text, None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complex_numbers_parse_as_typed() {
        let c = |t| parse_complex(t, "--poles").unwrap();
        assert_eq!(c("-2"), Complex64::new(-2.0, 0.0));
        assert_eq!(c("-4+1i"), Complex64::new(-4.0, 1.0));
        assert_eq!(c(" -4 - 1.5j"), Complex64::new(-4.0, -1.5));
        assert_eq!(c("3i"), Complex64::new(0.0, 3.0));
        assert_eq!(c("-1e-1-i"), Complex64::new(-0.1, -1.0));
        assert!(parse_complex("two", "--poles").is_err());
        assert!(parse_complex("1+xi", "--poles").is_err());
    }

    #[test]
    fn matrices_parse_by_rows_or_diagonal() {
        let m = parse_matrix("diag:1,2", "--q").unwrap();
        assert_eq!(m, DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]));
        let m = parse_matrix("1,2;3,4", "--q").unwrap();
        assert_eq!(m, DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]));
        assert!(parse_matrix("1,2;3", "--q").is_err());
    }
}
