//! `whipple response`: the bicycle as a linear system, one subcommand per kind of response.
//! `bode` (frequency responses at several speeds) is here; the time responses (`step`,
//! `impulse`, `initial`) and the linear and non-linear `manoeuvre` are in `time_response.rs`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use whipple_front::units::SpeedUnit;

use anyhow::{Context, Result, anyhow, bail};
use clap::Subcommand;
use nalgebra::DMatrix;
use serde_json::json;
use whipple::advanced::control::{ClosedLoop, Gains};
use whipple::advanced::eigen::Complex64;
use whipple::advanced::linear::{FrequencyResponse, LinearSystem, TransferFunction};
use whipple_front::system::{parse_log_grid, request};

use crate::TextFormat;
use crate::bike::{RunContext, load};
use crate::output::{self, Target, number};

/// The kinds of response.
#[derive(Subcommand)]
pub enum ResponseCommand {
    /// Frequency responses (Bode plots) of inputs to outputs at several speeds: prints each
    /// pair's poles, zeros (right-half-plane ones marked), gain and static gain; writes the
    /// magnitude and unwrapped phase as CSV (--out) and a Bode figure with the speeds
    /// overlaid (--figure).
    Bode {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Forward speeds in m/s (or km/h after them), separated by commas.
        #[arg(long, default_value = "3,5,7", allow_hyphen_values = true)]
        speeds: String,
        /// An input, repeatable: lean_torque, steer_torque, lateral_force:X,Z (the point of
        /// the rear frame in metres, z down).
        #[arg(long = "input", required = true, allow_hyphen_values = true)]
        inputs: Vec<String>,
        /// An output, repeatable: a state (lean, steer, lean_rate, steer_rate, yaw,
        /// rear_contact_x, rear_contact_y, rear_wheel_angle, front_wheel_angle), yaw_rate,
        /// front_contact_y, rear_contact_lateral_acceleration, rear_frame_point_y:X,Z,
        /// front_frame_point_y:X,Z.
        #[arg(long = "output", required = true, allow_hyphen_values = true)]
        outputs: Vec<String>,
        /// Frequencies START:STOP:COUNT, spaced logarithmically, in rad/s (in Hz with --hz).
        #[arg(long, default_value = "0.1:100:500")]
        frequencies: String,
        /// Frequencies in Hz (--frequencies, the CSV's column and the figure's axis).
        #[arg(long)]
        hz: bool,
        /// The summary's format on standard output.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
        /// Write the frequency responses to this CSV file.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Draw the Bode plot (first input and output, the speeds overlaid) to this .svg or
        /// .png file.
        #[arg(long)]
        figure: Option<PathBuf>,
        /// Close the loop u = r − K x first, K as `control feedback --gains` takes it (one row
        /// per --input, four gains each on φ, δ, φ̇, δ̇): the closed loop's transfer functions
        /// from the references r, exact from its own polynomial matrix. An input's name among
        /// the outputs is then the torque the loop applies.
        #[arg(long, allow_hyphen_values = true)]
        gains: Option<String>,
    },
    /// The response to a step of one input at t = 0, exact (no time step), with the path in
    /// the ground plane.
    Step {
        #[command(flatten)]
        time: crate::time_response::TimeArgs,
        /// The input: lean_torque, steer_torque or lateral_force:X,Z.
        #[arg(long, allow_hyphen_values = true)]
        input: String,
        /// The step's size in the input's unit (N m, or N for a force).
        #[arg(long, default_value = "1", allow_hyphen_values = true)]
        amplitude: f64,
    },
    /// The response to an impulse of one input at t = 0, exact, with the path in the plane.
    Impulse {
        #[command(flatten)]
        time: crate::time_response::TimeArgs,
        /// The input: lean_torque, steer_torque or lateral_force:X,Z.
        #[arg(long, allow_hyphen_values = true)]
        input: String,
        /// The impulse's size (N m s, or N s for a force).
        #[arg(long, default_value = "1", allow_hyphen_values = true)]
        amplitude: f64,
    },
    /// The free motion from an initial lean, steer and rates, exact, with the path in the plane.
    Initial {
        #[command(flatten)]
        time: crate::time_response::TimeArgs,
        /// Initial lean [deg].
        #[arg(long, default_value = "0", allow_hyphen_values = true)]
        lean: f64,
        /// Initial steer [deg].
        #[arg(long, default_value = "0", allow_hyphen_values = true)]
        steer: f64,
        /// Initial lean rate [deg/s].
        #[arg(long, default_value = "0", allow_hyphen_values = true)]
        lean_rate: f64,
        /// Initial steer rate [deg/s].
        #[arg(long, default_value = "0", allow_hyphen_values = true)]
        steer_rate: f64,
    },
    /// One manoeuvre (torques against time, an initial lean or steer) on the linear model and
    /// the non-linear model together: both motions, their difference, both paths in one figure.
    Manoeuvre(crate::time_response::ManoeuvreArgs),
}

/// The most speeds one run takes.
const MAX_SPEEDS: usize = 1000;

/// The most rows (speeds × pairs × frequencies) of one CSV: about 120 bytes each, 1.2 GB.
const MAX_ROWS: usize = 10_000_000;

/// Runs one `whipple response` subcommand.
pub fn run(cx: &RunContext, command: ResponseCommand) -> Result<()> {
    match command {
        ResponseCommand::Bode {
            bike,
            speeds,
            inputs,
            outputs,
            frequencies,
            hz,
            format,
            out,
            figure,
            gains,
        } => bode(
            cx,
            &Bode {
                gains: gains.as_deref(),
                bike: &bike,
                speeds: &speeds,
                inputs: &inputs,
                outputs: &outputs,
                frequencies: &frequencies,
                hz,
                format,
                out: out.as_deref(),
                figure: figure.as_deref(),
            },
        ),
        ResponseCommand::Step {
            time,
            input,
            amplitude,
        } => crate::time_response::linear(
            cx,
            &time,
            &crate::time_response::Kind::Step { input, amplitude },
        ),
        ResponseCommand::Impulse {
            time,
            input,
            amplitude,
        } => crate::time_response::linear(
            cx,
            &time,
            &crate::time_response::Kind::Impulse { input, amplitude },
        ),
        ResponseCommand::Initial {
            time,
            lean,
            steer,
            lean_rate,
            steer_rate,
        } => crate::time_response::linear(
            cx,
            &time,
            &crate::time_response::Kind::Initial {
                state_deg: [lean, steer, lean_rate, steer_rate],
            },
        ),
        ResponseCommand::Manoeuvre(args) => crate::time_response::manoeuvre(cx, &args),
    }
}

/// One speed's system and, per output and input, its transfer function and response.
type AtSpeed = (
    f64,
    LinearSystem,
    Vec<Vec<(TransferFunction, FrequencyResponse)>>,
);

struct Bode<'a> {
    bike: &'a str,
    speeds: &'a str,
    inputs: &'a [String],
    outputs: &'a [String],
    frequencies: &'a str,
    hz: bool,
    format: TextFormat,
    out: Option<&'a Path>,
    figure: Option<&'a Path>,
    gains: Option<&'a str>,
}

/// Speeds as typed, `3,5,7` (m/s) or `10,18,25km/h`, each finite; in m/s, with the unit
/// they were typed in.
fn parse_speeds(text: &str) -> Result<(Vec<f64>, SpeedUnit)> {
    let (numbers, unit) = whipple_front::units::split_speed(text)
        .map_err(|e| anyhow!("--speeds: {}", crate::speeds::rule_of(e)))?;
    let speeds = numbers
        .split(',')
        .map(|s| {
            let s = s.trim();
            s.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .map(|v| unit.to_si(v))
                .ok_or_else(|| {
                    anyhow!(
                        "--speeds: `{s}` is not a finite number of {}",
                        unit.symbol()
                    )
                })
        })
        .collect::<Result<Vec<f64>>>()?;
    if speeds.len() > MAX_SPEEDS {
        bail!(
            "--speeds: {} speeds is more than the limit of {MAX_SPEEDS}",
            speeds.len()
        );
    }
    Ok((speeds, unit))
}

/// `x + yi` with the numbers as results print.
fn complex(z: Complex64) -> Result<String> {
    if z.im == 0.0 {
        return number(z.re);
    }
    Ok(format!(
        "{} {} {}i",
        number(z.re)?,
        if z.im < 0.0 { '-' } else { '+' },
        number(z.im.abs())?
    ))
}

/// The words an option's error gets: the library names `inputs`, `outputs`, `frequencies`.
fn option_of(error: &whipple::Error) -> &'static str {
    match error {
        whipple::Error::InvalidArgument { what, .. }
        | whipple::Error::LimitExceeded { what, .. } => match *what {
            "inputs" | "input" => "--input",
            "outputs" | "output" | "states" => "--output",
            "frequencies" => "--frequencies",
            _ => "--speeds",
        },
        _ => "--speeds",
    }
}

fn bode(cx: &RunContext, args: &Bode<'_>) -> Result<()> {
    let figure = args
        .figure
        .map(|p| {
            whipple_report::Format::from_path(p)
                .with_context(|| format!("--figure {}", p.display()))?;
            Target::check("--figure", p)
        })
        .transpose()?;
    let out = args.out.map(|p| Target::check("--out", p)).transpose()?;
    if let (Some(a), Some(b)) = (&out, &figure) {
        output::distinct(a, b)?;
    }
    let bike = load(cx, args.bike)?;
    let (speeds, speed_unit) = parse_speeds(args.speeds)?;
    let inputs: Vec<&str> = args.inputs.iter().map(String::as_str).collect();
    let outputs: Vec<&str> = args.outputs.iter().map(String::as_str).collect();
    let req = request(&inputs, &outputs).map_err(|e| {
        let option = option_of(&e);
        anyhow!(whipple_front::message::message(&e)).context(option)
    })?;
    let grid = parse_log_grid(args.frequencies)
        .map_err(|e| anyhow!(whipple_front::message::message(&e)))
        .with_context(|| format!("--frequencies {}", args.frequencies))?;
    let omega: Vec<f64> = if args.hz {
        grid.iter().map(|f| std::f64::consts::TAU * f).collect()
    } else {
        grid.clone()
    };
    let pairs = req.inputs.len() * req.outputs.len();
    let rows = speeds
        .len()
        .saturating_mul(pairs)
        .saturating_mul(omega.len());
    if out.is_some() && rows > MAX_ROWS {
        bail!(
            "--out: {} speeds × {pairs} pairs × {} frequencies is {rows} rows, more than the \
             limit of {MAX_ROWS}; use fewer",
            speeds.len(),
            omega.len()
        );
    }
    // The closed loop, when asked: K on φ, δ, φ̇, δ̇, zeros on the states the outputs add.
    let closed = match args.gains {
        None => None,
        Some(text) => {
            let k = crate::feedback::parse_gains(text, req.inputs.len())?;
            let states = 4 + req.states.len();
            let padded = DMatrix::from_fn(
                k.nrows(),
                states,
                |i, j| {
                    if j < 4 { k[(i, j)] } else { 0.0 }
                },
            );
            let closed = ClosedLoop::new(&bike.benchmark, &req, Gains::Constant(padded))
                .map_err(|e| anyhow!(whipple_front::message::message(&e)).context("--gains"))?;
            Some(closed)
        }
    };
    // Everything is computed before anything is written.
    let mut results: Vec<AtSpeed> = Vec::with_capacity(speeds.len());
    for &v in &speeds {
        let system = match &closed {
            Some(closed) => closed.system(v),
            None => LinearSystem::new(&bike.benchmark, v, &req),
        }
        .map_err(|e| {
            let option = option_of(&e);
            anyhow!(whipple_front::message::message(&e)).context(option)
        })?;
        let mut rows = Vec::with_capacity(req.outputs.len());
        for o in 0..req.outputs.len() {
            let mut row = Vec::with_capacity(req.inputs.len());
            for i in 0..req.inputs.len() {
                let tf = system
                    .transfer_function(o, i)
                    .with_context(|| format!("at v = {v} m/s"))?;
                let response = tf.frequency_response(&omega).map_err(|e| {
                    anyhow!(whipple_front::message::message(&e))
                        .context(format!("--frequencies {} at v = {v} m/s", args.frequencies))
                })?;
                row.push((tf, response));
            }
            rows.push(row);
        }
        results.push((v, system, rows));
    }
    let mut summary = match args.format {
        TextFormat::Table => format!(
            "{}{}: transfer functions and frequency responses (poles and zeros in 1/s; a zero \
             marked RHP is in the right half-plane: non-minimum-phase)\n",
            bike.label,
            match args.gains {
                Some(k) => format!(" under feedback u = r − K x, K = {k} (on φ, δ, φ̇, δ̇)"),
                None => String::new(),
            }
        ),
        TextFormat::Json => String::new(),
    };
    let mut json_rows = Vec::new();
    for (v, system, rows) in &results {
        for (o, row) in rows.iter().enumerate() {
            for (i, (tf, _)) in row.iter().enumerate() {
                let input = system.inputs()[i];
                let output = system.outputs()[o];
                let zeros = tf.zeros().with_context(|| format!("at v = {v} m/s"))?;
                let poles = tf.poles();
                let unit = format!("{}/({})", output.unit(), input.unit());
                match args.format {
                    TextFormat::Table => {
                        write!(
                            summary,
                            "\nv = {}, {input} → {output}\n",
                            output::speed_words(*v, speed_unit)?
                        )?;
                        let list = |values: &[Complex64], mark: bool| -> Result<String> {
                            if values.is_empty() {
                                return Ok("none".into());
                            }
                            let mut parts = Vec::new();
                            for z in values {
                                let mut s = complex(*z)?;
                                if mark && z.re > 0.0 {
                                    s.push_str(" (RHP)");
                                }
                                parts.push(s);
                            }
                            Ok(parts.join(", "))
                        };
                        writeln!(summary, "  poles:       {}", list(&poles, false)?)?;
                        writeln!(summary, "  zeros:       {}", list(&zeros, true)?)?;
                        writeln!(summary, "  gain:        {} {unit}", number(tf.gain())?)?;
                        match tf.static_gain() {
                            Some(g) => writeln!(summary, "  static gain: {} {unit}", number(g)?)?,
                            None => writeln!(
                                summary,
                                "  static gain: none (an integrator: a pole at s = 0)"
                            )?,
                        }
                    }
                    TextFormat::Json => {
                        let pair = |z: &Complex64| json!([z.re, z.im]);
                        for z in poles.iter().chain(&zeros) {
                            complex(*z)?;
                        }
                        json_rows.push(json!({
                            "speed": v,
                            "input": input.to_string(),
                            "output": output.to_string(),
                            "unit": unit,
                            "poles": poles.iter().map(pair).collect::<Vec<_>>(),
                            "zeros": zeros.iter().map(pair).collect::<Vec<_>>(),
                            "right_half_plane_zeros": zeros.iter().filter(|z| z.re > 0.0).count(),
                            "gain": tf.gain(),
                            "static_gain": tf.static_gain(),
                        }));
                    }
                }
            }
        }
    }
    if args.format == TextFormat::Json {
        let doc = json!({
            "bike": bike.label,
            "gains": closed.as_ref().and_then(|c| match c.gains() {
                Gains::Constant(k) => Some(
                    k.row_iter()
                        .map(|r| r.iter().take(4).copied().collect::<Vec<f64>>())
                        .collect::<Vec<_>>(),
                ),
                Gains::Scheduled { .. } => None,
            }),
            "pairs": json_rows,
            "warnings": bike.warnings_json(),
        });
        summary = format!("{}\n", serde_json::to_string_pretty(&doc)?);
    }
    let frequency_column = if args.hz {
        "frequency_hz"
    } else {
        "frequency_rad_s"
    };
    let mut finished = Vec::new();
    if let Some(target) = &out {
        let mut sink = target.open()?;
        sink.text(&format!(
            "speed_m_s,input,output,{frequency_column},magnitude,magnitude_db,phase_deg\n"
        ))?;
        for (v, system, rows) in &results {
            for (o, row) in rows.iter().enumerate() {
                for (i, (_, f)) in row.iter().enumerate() {
                    let (input, output) = (system.inputs()[i], system.outputs()[o]);
                    let mut text = String::new();
                    for (k, at) in grid.iter().enumerate() {
                        writeln!(
                            text,
                            "{},{input},{output},{},{},{},{}",
                            number(*v)?,
                            number(*at)?,
                            number(f.magnitude[k])?,
                            number(f.magnitude_db[k])?,
                            number(f.phase[k].to_degrees())?
                        )?;
                    }
                    sink.text(&text)?;
                }
            }
        }
        finished.push(sink.finish()?);
    }
    if let (Some(target), Some(path)) = (&figure, args.figure) {
        if pairs > 1 {
            eprintln!(
                "note: {} draws the first input and output ({} → {})",
                target.describe(),
                req.inputs[0],
                req.outputs[0]
            );
        }
        let (input, output) = (req.inputs[0], req.outputs[0]);
        let curves = results
            .iter()
            .map(|(v, _, rows)| {
                let f = &rows[0][0].1;
                Ok(whipple_report::BodeCurve {
                    name: output::speed_label(*v, speed_unit)?,
                    frequencies: grid.clone(),
                    magnitude_db: f.magnitude_db.clone(),
                    phase_deg: f.phase.iter().map(|p| p.to_degrees()).collect(),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let data = whipple_report::BodeData {
            title: format!("{}: {input} → {output}", bike.label),
            frequency_label: if args.hz {
                "frequency f [Hz]".into()
            } else {
                "frequency ω [rad/s]".into()
            },
            magnitude_label: format!(
                "|{} / {}| [dB re 1 {}/({})]",
                output.symbol(),
                input.symbol(),
                output.unit(),
                input.unit()
            ),
            legend_title: "speed".into(),
            curves,
        };
        let bytes = whipple_report::bode_plot(&data)?
            .render_for_path(path)
            .with_context(|| format!("drawing {}", path.display()))?;
        let mut sink = target.open()?;
        sink.bytes(&bytes)?;
        finished.push(sink.finish()?);
    }
    output::commit(finished)?;
    output::print_stdout(&summary)?;
    Ok(())
}
