//! `whipple response step | impulse | initial | manoeuvre`: time responses of the linear
//! system (exact, no time step) with the path in the ground plane, and one manoeuvre on the
//! linear and the non-linear bicycle together.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use whipple::advanced::linear::{
    Input, InputSignal, LinearSystem, MAX_RESPONSE_TIMES, Manoeuvre, ManoeuvreComparison,
    TimeResponse, compare_manoeuvre,
};
use whipple_front::system::{parse_signal, request_with_states};

use crate::bike::{LoadedBike, RunContext, load};
use crate::output::{self, Target, number};

/// What every time response takes.
#[derive(Args)]
pub struct TimeArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    bike: String,
    /// Forward speed in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    speed: crate::TypedSpeed,
    /// An output, repeatable (default: lean, steer, yaw and rear_contact_y); the names of
    /// `whipple response bode --help`.
    #[arg(long = "output", allow_hyphen_values = true)]
    outputs: Vec<String>,
    /// How long, in seconds, from t = 0.
    #[arg(long, default_value = "5", allow_hyphen_values = true)]
    duration: f64,
    /// How many samples, evenly spaced from 0 to the duration (both included).
    #[arg(long, default_value = "501")]
    samples: usize,
    /// Write the samples to this CSV file: t, the outputs, the rear contact's path (x with the
    /// run v t, y, yaw).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Draw lean, steer and the contacts' paths to this .svg or .png file.
    #[arg(long)]
    figure: Option<PathBuf>,
}

/// The kind of a linear time response.
pub enum Kind {
    /// A step of `amplitude` in `input` at t = 0.
    Step {
        /// The input's name.
        input: String,
        /// The step's size in the input's unit.
        amplitude: f64,
    },
    /// A unit impulse in `input` at t = 0, times `amplitude`.
    Impulse {
        /// The input's name.
        input: String,
        /// The impulse's size (N m s or N s).
        amplitude: f64,
    },
    /// Free motion from an initial lean, steer and rates (degrees and degrees per second).
    Initial {
        /// [lean, steer, lean rate, steer rate] in degrees and degrees per second.
        state_deg: [f64; 4],
    },
}

/// The sample times 0, …, duration.
fn sample_times(duration: f64, samples: usize) -> Result<Vec<f64>> {
    if !(duration.is_finite() && duration > 0.0) {
        bail!("--duration must be a positive number of seconds, got {duration}");
    }
    if !(2..=MAX_RESPONSE_TIMES).contains(&samples) {
        bail!("--samples must be 2 to {MAX_RESPONSE_TIMES}, got {samples}");
    }
    let last = (samples - 1) as f64;
    Ok((0..samples)
        .map(|k| {
            if k == samples - 1 {
                duration
            } else {
                duration * k as f64 / last
            }
        })
        .collect())
}

/// The library's error as a message naming the option it stands for.
fn named(error: whipple::Error) -> anyhow::Error {
    let option = match &error {
        whipple::Error::InvalidArgument { what, .. }
        | whipple::Error::LimitExceeded { what, .. } => match *what {
            "inputs" | "input" => "--input",
            "outputs" | "output" | "states" => "--output",
            "times" => "--samples/--duration",
            _ => "--speed",
        },
        _ => "--speed",
    };
    anyhow!(whipple_front::message::message(&error)).context(option)
}

/// The output (`--out`) and figure (`--figure`) files, checked before any work.
fn targets(
    out: Option<&std::path::Path>,
    figure: Option<&std::path::Path>,
) -> Result<(Option<Target>, Option<Target>)> {
    let figure = figure
        .map(|p| {
            whipple_report::Format::from_path(p)
                .with_context(|| format!("--figure {}", p.display()))?;
            Target::check("--figure", p)
        })
        .transpose()?;
    let out = out.map(|p| Target::check("--out", p)).transpose()?;
    if let (Some(a), Some(b)) = (&out, &figure) {
        output::distinct(a, b)?;
    }
    Ok((out, figure))
}

/// Runs `step`, `impulse` or `initial`.
pub fn linear(cx: &RunContext, args: &TimeArgs, kind: &Kind) -> Result<()> {
    let (out, figure) = targets(args.out.as_deref(), args.figure.as_deref())?;
    if !args.speed.si.is_finite() {
        bail!(
            "--speed must be a finite number of m/s, got {}",
            args.speed.si
        );
    }
    let times = sample_times(args.duration, args.samples)?;
    let bike = load(cx, &args.bike)?;
    let outputs: Vec<&str> = if args.outputs.is_empty() {
        vec!["lean", "steer", "yaw", "rear_contact_y"]
    } else {
        args.outputs.iter().map(String::as_str).collect()
    };
    let input_name = match kind {
        Kind::Step { input, .. } | Kind::Impulse { input, .. } => Some(input.as_str()),
        Kind::Initial { .. } => None,
    };
    let inputs: Vec<&str> = input_name.into_iter().collect();
    let plane = ["yaw", "rear_contact_x", "rear_contact_y"];
    let req = request_with_states(&inputs, &outputs, &plane).map_err(named)?;
    let system = LinearSystem::new(&bike.benchmark, args.speed.si, &req).map_err(named)?;
    let n = system.states().len();
    let (response, what) = match kind {
        Kind::Step { amplitude, .. } => {
            let step = InputSignal::step(0.0, *amplitude).map_err(named)?;
            let r = system
                .response(&vec![0.0; n], &[step], &times)
                .map_err(named)?;
            let unit = req.inputs[0].unit();
            (
                r,
                format!(
                    "a step of {} {unit} in {} at t = 0",
                    number(*amplitude)?,
                    req.inputs[0]
                ),
            )
        }
        Kind::Impulse { amplitude, .. } => {
            let mut r = system.impulse_response(0, &times).map_err(named)?;
            r.states.scale_mut(*amplitude);
            r.outputs.scale_mut(*amplitude);
            let unit = req.inputs[0].unit();
            (
                r,
                format!(
                    "an impulse of {} {unit} s in {} at t = 0",
                    number(*amplitude)?,
                    req.inputs[0]
                ),
            )
        }
        Kind::Initial { state_deg } => {
            let mut x0 = vec![0.0; n];
            for (k, value) in state_deg.iter().enumerate() {
                x0[k] = whipple_front::units::radians(*value);
            }
            let r = system.initial_response(&x0, &times).map_err(named)?;
            (
                r,
                format!(
                    "free motion from lean {}°, steer {}°, rates {}°/s and {}°/s",
                    number(state_deg[0])?,
                    number(state_deg[1])?,
                    number(state_deg[2])?,
                    number(state_deg[3])?
                ),
            )
        }
    };
    let title = format!(
        "{} at {}, linear model: {what}",
        bike.label,
        crate::output::speed_words(args.speed.si, args.speed.unit)?
    );
    let summary = summary(&title, &response)?;
    let mut finished = Vec::new();
    if let Some(target) = out {
        let mut sink = target.open()?;
        sink.text(&csv(&response)?)?;
        finished.push(sink.finish()?);
    }
    if let Some(target) = figure {
        let series = series(&bike, &title, &response)?;
        let path = target.path().to_path_buf();
        let bytes = whipple_report::time_series_plot(&series)?
            .render_for_path(&path)
            .with_context(|| format!("drawing {}", path.display()))?;
        let mut sink = target.open()?;
        sink.bytes(&bytes)?;
        finished.push(sink.finish()?);
    }
    output::commit(finished)?;
    output::print_stdout(&summary)
}

/// A result with six significant digits, for the summaries (the CSV has every digit).
pub(crate) fn short(x: f64) -> Result<String> {
    number(x)?;
    let size = x.abs();
    Ok(if x == 0.0 {
        "0".to_string()
    } else if (1e-3..1e6).contains(&size) {
        let decimals = (5 - whipple::math::log10(size).floor() as i32).clamp(0, 8) as usize;
        let text = format!("{x:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        format!("{x:.5e}")
    })
}

/// Beyond this size of lean or steer [rad] (about 11°) a linear response is no longer a small
/// motion: the summary says so.
const SMALL_ANGLE: f64 = 0.2;

/// Each output's value at the end, and its largest size and when.
fn summary(title: &str, r: &TimeResponse) -> Result<String> {
    let mut t = format!(
        "{title}\n  output                          at the end          largest |value| (at t)\n"
    );
    for (j, output) in r.output_names.iter().enumerate() {
        let column = r.outputs.column(j);
        let last = column[column.len() - 1];
        let (k, peak) = column
            .iter()
            .enumerate()
            .fold(
                (0, 0.0f64),
                |(k, m), (i, x)| if x.abs() > m { (i, x.abs()) } else { (k, m) },
            );
        writeln!(
            t,
            "  {:<31} {:<19} {} {} (t = {} s)",
            output.to_string(),
            format!("{} {}", short(last)?, output.unit()),
            short(peak)?,
            output.unit(),
            short(r.times[k])?
        )?;
    }
    if let Some(path) = r.ground_path() {
        let k = r.times.len() - 1;
        writeln!(
            t,
            "  the rear contact ends at x = {} m, y = {} m, heading {} rad",
            short(path.rear_x[k])?,
            short(path.rear_y[k])?,
            short(path.yaw[k])?
        )?;
    }
    use whipple::advanced::linear::StateVariable;
    let largest = |s: StateVariable| {
        r.state(s)
            .map_or(0.0, |x| x.iter().fold(0.0f64, |m, v| m.max(v.abs())))
    };
    let angle = largest(StateVariable::Lean).max(largest(StateVariable::Steer));
    if angle > SMALL_ANGLE {
        writeln!(
            t,
            "  note: lean or steer reaches {} rad ({}°), beyond small motions: these are the \
             linear model's numbers, not the bicycle's (`whipple response manoeuvre` runs the \
             non-linear model beside it)",
            short(angle)?,
            short(angle.to_degrees())?
        )?;
    }
    let heading = largest(StateVariable::Yaw);
    if heading > SMALL_ANGLE {
        writeln!(
            t,
            "  note: the heading turns by {} rad ({}°): the linear path (ẏ = v ψ) holds for small \
             headings only",
            short(heading)?,
            short(heading.to_degrees())?
        )?;
    }
    Ok(t)
}

fn csv(r: &TimeResponse) -> Result<String> {
    let path = r.ground_path();
    let mut text = String::from("t_s");
    for output in &r.output_names {
        let name = output.to_string().replace([' ', '(', ')', '=', ','], "");
        write!(text, ",{name}")?;
    }
    if path.is_some() {
        text.push_str(",path_x_m,path_y_m,path_yaw_rad");
    }
    text.push('\n');
    for (k, t) in r.times.iter().enumerate() {
        text.push_str(&number(*t)?);
        for j in 0..r.output_names.len() {
            write!(text, ",{}", number(r.outputs[(k, j)])?)?;
        }
        if let Some(p) = &path {
            write!(
                text,
                ",{},{},{}",
                number(p.rear_x[k])?,
                number(p.rear_y[k])?,
                number(p.yaw[k])?
            )?;
        }
        text.push('\n');
    }
    Ok(text)
}

/// The response as the simulation's figure draws it: lean, steer, speed and both contacts.
fn series(
    bike: &LoadedBike,
    title: &str,
    r: &TimeResponse,
) -> Result<whipple_report::SimulationSeries> {
    use whipple::advanced::linear::StateVariable;
    let state = |s: StateVariable| {
        r.state(s)
            .ok_or_else(|| anyhow!("the response has no {s} (an internal error)"))
    };
    let path = r
        .ground_path()
        .ok_or_else(|| anyhow!("the response has no path (an internal error)"))?;
    let (w, c, lambda) = (bike.benchmark.w, bike.benchmark.c, bike.benchmark.lambda);
    let steer = state(StateVariable::Steer)?;
    // The front contact to first order: w ahead along the heading, −c δ cos λ aside.
    let front = (0..r.times.len())
        .map(|k| {
            (
                path.rear_x[k] + w,
                path.rear_y[k] + w * path.yaw[k] - c * steer[k] * whipple::math::cos(lambda),
            )
        })
        .collect();
    Ok(whipple_report::SimulationSeries {
        title: title.to_string(),
        t: r.times.clone(),
        lean: state(StateVariable::Lean)?,
        steer,
        speed: vec![r.speed; r.times.len()],
        rear_contact: path
            .rear_x
            .iter()
            .copied()
            .zip(path.rear_y.iter().copied())
            .collect(),
        front_contact: front,
        events: Vec::new(),
        outcome: Some("linear model: small motions about upright straight running".into()),
    })
}

/// The arguments of `whipple response manoeuvre`.
#[derive(Args)]
pub struct ManoeuvreArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    bike: String,
    /// Forward speed in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    speed: crate::TypedSpeed,
    /// Steer torque [N m] against time: step:T:A, pulse:T:D:A, linear:T1=U1,T2=U2,… or
    /// constant:T1=U1,… (for example pulse:0:0.5:1, 1 N m for half a second).
    #[arg(long, allow_hyphen_values = true)]
    steer_torque: Option<String>,
    /// Lean torque [N m] against time, as --steer-torque.
    #[arg(long, allow_hyphen_values = true)]
    lean_torque: Option<String>,
    /// Initial lean [deg].
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    lean: f64,
    /// Initial steer [deg].
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    steer: f64,
    /// How long, in seconds, from t = 0.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    duration: f64,
    /// How many samples, evenly spaced from 0 to the duration (both included).
    #[arg(long, default_value = "301")]
    samples: usize,
    /// The non-linear integration's relative tolerance (Dormand–Prince 5(4)).
    #[arg(long, default_value = "1e-10")]
    rtol: f64,
    /// Write both models' samples and their differences to this CSV file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Draw both models and their difference to this .svg or .png file.
    #[arg(long)]
    figure: Option<PathBuf>,
}

/// The largest the non-linear side of a manoeuvre may take: its break points are the samples.
const MAX_MANOEUVRE_SAMPLES: usize = 20_000;

/// Runs `whipple response manoeuvre`.
pub fn manoeuvre(cx: &RunContext, args: &ManoeuvreArgs) -> Result<()> {
    let (out, figure) = targets(args.out.as_deref(), args.figure.as_deref())?;
    if !args.speed.si.is_finite() {
        bail!(
            "--speed must be a finite number of m/s, got {}",
            args.speed.si
        );
    }
    for (option, value) in [("--lean", args.lean), ("--steer", args.steer)] {
        if !value.is_finite() {
            bail!("{option} must be a finite number of degrees, got {value}");
        }
    }
    if !(args.rtol.is_finite() && args.rtol > 0.0 && args.rtol < 1e-2) {
        bail!("--rtol must be between 0 and 0.01, got {}", args.rtol);
    }
    if args.samples > MAX_MANOEUVRE_SAMPLES {
        bail!(
            "--samples: at most {MAX_MANOEUVRE_SAMPLES} (each starts a run of the non-linear \
             model), got {}",
            args.samples
        );
    }
    let times = sample_times(args.duration, args.samples)?;
    let mut inputs = Vec::new();
    for (option, spec, input) in [
        ("--steer-torque", &args.steer_torque, Input::SteerTorque),
        ("--lean-torque", &args.lean_torque, Input::LeanTorque),
    ] {
        if let Some(spec) = spec {
            let signal = parse_signal(spec, option)
                .map_err(|e| anyhow!(whipple_front::message::message(&e)))?;
            inputs.push((input, signal));
        }
    }
    if inputs.is_empty() && args.lean == 0.0 && args.steer == 0.0 {
        bail!(
            "nothing happens: give --steer-torque, --lean-torque or an initial --lean or --steer \
             (for example --steer-torque pulse:0:0.5:1)"
        );
    }
    let bike = load(cx, &args.bike)?;
    let manoeuvre = Manoeuvre {
        speed: args.speed.si,
        lean: whipple_front::units::radians(args.lean),
        steer: whipple_front::units::radians(args.steer),
        inputs,
    };
    let both = compare_manoeuvre(&bike.benchmark, &manoeuvre, &times, args.rtol)
        .map_err(|e| anyhow!(whipple_front::message::message(&e)))
        .context("the manoeuvre")?;
    let mut what = Vec::new();
    if let Some(s) = &args.steer_torque {
        what.push(format!("steer torque {s}"));
    }
    if let Some(s) = &args.lean_torque {
        what.push(format!("lean torque {s}"));
    }
    if args.lean != 0.0 || args.steer != 0.0 {
        what.push(format!(
            "from lean {}°, steer {}°",
            number(args.lean)?,
            number(args.steer)?
        ));
    }
    let title = format!(
        "{} at {}: {}",
        bike.label,
        crate::output::speed_words(args.speed.si, args.speed.unit)?,
        what.join(", ")
    );
    let text = manoeuvre_summary(&title, &both)?;
    let mut finished = Vec::new();
    if let Some(target) = out {
        let mut sink = target.open()?;
        sink.text(&manoeuvre_csv(&both)?)?;
        finished.push(sink.finish()?);
    }
    if let Some(target) = figure {
        let path = target.path().to_path_buf();
        let bytes = whipple_report::manoeuvre_plot(&both, &title)?
            .render_for_path(&path)
            .with_context(|| format!("drawing {}", path.display()))?;
        let mut sink = target.open()?;
        sink.bytes(&bytes)?;
        finished.push(sink.finish()?);
    }
    output::commit(finished)?;
    output::print_stdout(&text)
}

fn manoeuvre_summary(title: &str, both: &ManoeuvreComparison) -> Result<String> {
    let mut t = format!(
        "{title}\n  the linear model (exact) and the non-linear model (Dormand–Prince 5(4), {} \
         steps), on the same {} samples\n  quantity   largest linear     largest non-linear   \
         largest difference\n",
        both.nonlinear_steps,
        both.times.len()
    );
    let units = ["rad", "rad", "rad", "m", "m", "m"];
    let linear = both.linear.max_abs();
    let nonlinear = both.nonlinear.max_abs();
    let difference = both.difference.max_abs();
    for (k, (name, _)) in both.linear.columns().iter().enumerate() {
        writeln!(
            t,
            "  {:<10} {:<18} {:<20} {} {}",
            name,
            format!("{} {}", short(linear[k])?, units[k]),
            format!("{} {}", short(nonlinear[k])?, units[k]),
            short(difference[k])?,
            units[k]
        )?;
    }
    t.push_str(
        "  (the difference shrinks as the amplitude cubed, x's as its square: the linear model \
         is the first-order term)\n",
    );
    Ok(t)
}

fn manoeuvre_csv(both: &ManoeuvreComparison) -> Result<String> {
    let mut text = String::from("t_s");
    for (model, motion) in [
        ("linear", &both.linear),
        ("nonlinear", &both.nonlinear),
        ("difference", &both.difference),
    ] {
        for (name, _) in motion.columns() {
            write!(text, ",{model}_{name}")?;
        }
    }
    text.push('\n');
    for (k, t) in both.times.iter().enumerate() {
        text.push_str(&number(*t)?);
        for motion in [&both.linear, &both.nonlinear, &both.difference] {
            for (_, values) in motion.columns() {
                write!(text, ",{}", number(values[k])?)?;
            }
        }
        text.push('\n');
    }
    Ok(text)
}
