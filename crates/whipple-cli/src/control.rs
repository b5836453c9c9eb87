//! `whipple control`: the bicycle under control. `controllability` lists, per input, the speeds
//! where it cannot reach a lean–steer mode (certified by the library) and, over a speed grid,
//! the Kalman matrix's rank and condition and each mode's modal controllability. `feedback`
//! closes the loop u = r − K x with given gains (constant, or scheduled from a CSV file) and
//! prints its eigenvalues against speed and its certified critical speeds as `eig` and
//! `speeds` print the open loop's; `lqr` and `place` design K at one speed (`lqr` also over
//! speeds, a schedule, with the speeds it stabilizes).

use std::fmt::Write as _;

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use serde_json::json;
use whipple::advanced::control::uncontrollable_speeds;
use whipple::advanced::eigen::Complex64;
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use whipple::advanced::modes::mode_shapes;
use whipple::advanced::roots::RealRoot;

use crate::bike::{RunContext, load};
use crate::commands::emit;
use crate::output::number;
use crate::{TableFormat, TextFormat};

/// The most speeds the controllability table holds.
pub const MAX_CONTROL_SPEEDS: usize = 100_000;

/// The arguments of `whipple control`.
#[derive(Args)]
pub struct ControlArgs {
    #[command(subcommand)]
    command: ControlCommand,
}

#[derive(Subcommand)]
enum ControlCommand {
    /// Which modes each input can reach: the speeds where an input loses a lean–steer mode
    /// (certified: the real roots of a polynomial in the speed, none missed), and over a speed
    /// grid the Kalman matrix's rank and condition and each mode's modal controllability.
    Controllability {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// An input: lean_torque, steer_torque or lateral_force:X,Z (the point of the rear
        /// frame in metres, z down); repeat for several (default: steer_torque and lean_torque).
        #[arg(long = "input", allow_hyphen_values = true)]
        inputs: Vec<String>,
        /// Speeds START:STOP:STEP in m/s (or km/h after them) for the table, both ends included.
        #[arg(long, default_value = "0:10:0.5", allow_hyphen_values = true)]
        speeds: String,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
        /// Write to this file instead of standard output.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
    },
    /// The closed loop u = r − K x: its eigenvalues against speed, tracked and labelled as
    /// `whipple eig` prints them, and its critical speeds, certified as `whipple speeds` gives
    /// them. K's columns are (lean φ, steer δ, lean rate φ̇, steer rate δ̇), one row per input
    /// (N m per rad and per rad/s). Sign: the input is u = −K x, so steering into the fall,
    /// T_δ = 100 φ − 10 δ + 20 φ̇, is `--gains "-100,10,-20,0"`.
    Feedback {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// K: one row per input, rows separated by `;`, four gains each (φ, δ, φ̇, δ̇), for
        /// example "-100,10,-20,0". Give this or --schedule.
        #[arg(long, allow_hyphen_values = true, conflicts_with = "schedule")]
        gains: Option<String>,
        /// Gains scheduled with speed: a CSV file of rows `speed,k1,k2,…` (speed in m/s,
        /// increasing; K's rows one after the other, four gains each); linear between the
        /// speeds, never extrapolated. A first line of names and lines starting with # are
        /// skipped.
        #[arg(long)]
        schedule: Option<std::path::PathBuf>,
        /// An input fed back: lean_torque, steer_torque or lateral_force:X,Z; repeat for
        /// several, in the order of K's rows (default: steer_torque).
        #[arg(long = "input", allow_hyphen_values = true)]
        inputs: Vec<String>,
        /// Speeds START:STOP:STEP in m/s (or km/h after them), both ends included (default: 0:10:0.1, or the
        /// schedule's first to last speed in 100 steps).
        #[arg(long, allow_hyphen_values = true)]
        speeds: Option<String>,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TableFormat,
        /// Write the table to this file instead of standard output.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Also draw the closed-loop eigenvalues against speed to this .svg or .png file.
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
        /// The speeds LO:HI in m/s (or km/h after them) for the critical speeds; HI may be `inf` (default: every
        /// speed v >= 0, or the schedule's speeds).
        #[arg(long, allow_hyphen_values = true)]
        range: Option<String>,
    },
    /// LQR: the gain K minimizing ∫ xᵀQx + uᵀRu dt at one speed (K, the Riccati solution X,
    /// the closed-loop poles, the residual), or over speeds a gain schedule and the speeds
    /// from which the scheduled loop is stable (certified). The states are (φ, δ, φ̇, δ̇).
    Lqr {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Forward speed in m/s, or km/h after it: 18km/h (or --speeds for a schedule).
        #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true, conflicts_with = "speeds")]
        speed: Option<crate::TypedSpeed>,
        /// Speeds START:STOP:STEP in m/s (or km/h after them) for a gain schedule, both ends included.
        #[arg(long, allow_hyphen_values = true)]
        speeds: Option<String>,
        /// The state weight Q (4 × 4, symmetric positive semi-definite): "diag:1,1,1,1" or
        /// rows separated by `;` ("1,0,0,0;0,1,0,0;0,0,1,0;0,0,0,1").
        #[arg(long, allow_hyphen_values = true)]
        q: String,
        /// The input weight R (inputs × inputs, symmetric positive definite): "1", "diag:1,2"
        /// or rows separated by `;`.
        #[arg(long, allow_hyphen_values = true)]
        r: String,
        /// An input: lean_torque, steer_torque or lateral_force:X,Z; repeat for several
        /// (default: steer_torque).
        #[arg(long = "input", allow_hyphen_values = true)]
        inputs: Vec<String>,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// Hess's handling quality metric (HQM) as HumanControl computes it, with the gains of a
    /// HumanControl SteerGains file: the peak of |HQM(jω)| over frequency (certified) at one
    /// speed, or against speed; Hess reads peaks below 5 as good handling, above 8 as poor.
    Hqm(crate::hqm::HqmArgs),
    /// The design search of BMD 2016: the peak HQM at a design speed minimized over chosen
    /// parameters within bounds (`--vary trail=0:0.2 --vary head_angle_deg=60:85`), the gains
    /// set for each candidate by Hess 2012's rules; Nelder–Mead from several starts (local).
    OptimalHandling(crate::optimal::OptimalArgs),
    /// The bicycle ridden by Hess's human controller (Hess, Moore & Hubbard 2012; HumanControl's
    /// closed loop): the gains used (a HumanControl gains file, or Hess 2012's rules), the
    /// closed-loop eigenvalues and each loop's crossover frequency at one speed, or the
    /// eigenvalues against speed.
    Hess(crate::hess::HessArgs),
    /// Pole placement for one input: the K (1 × 4) that gives A − B K the poles asked for, and
    /// the check (the closed loop's eigenvalues).
    Place {
        #[arg(long, help = whipple_front::formats::bike_help())]
        bike: String,
        /// Forward speed in m/s (or km/h after it: 18km/h).
        #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
        speed: crate::TypedSpeed,
        /// The input: lean_torque, steer_torque or lateral_force:X,Z.
        #[arg(long, default_value = "steer_torque", allow_hyphen_values = true)]
        input: String,
        /// Four poles in 1/s, complex ones in conjugate pairs: "-2,-3,-4+1i,-4-1i".
        #[arg(long, allow_hyphen_values = true)]
        poles: String,
        /// Output format.
        #[arg(long, value_enum, default_value = "table")]
        format: TextFormat,
    },
    /// HumanControl's single or double lane change ridden by Hess's controller (the lateral
    /// task, gains from a SteerGains file) on the linear bicycle (exactly), the non-linear one,
    /// or both: a CSV of the runs and a figure of the path and the lateral error.
    LaneChange(crate::lane_change::LaneChangeArgs),
}

/// Runs `whipple control`.
pub fn run(cx: &RunContext, args: &ControlArgs) -> Result<()> {
    match &args.command {
        ControlCommand::Controllability {
            bike,
            inputs,
            speeds,
            format,
            out,
        } => controllability(cx, bike, inputs, speeds, *format, out.as_deref()),
        ControlCommand::Feedback {
            bike,
            gains,
            schedule,
            inputs,
            speeds,
            format,
            out,
            plot,
            range,
        } => crate::feedback::feedback(
            cx,
            &crate::feedback::FeedbackArgs {
                bike,
                gains: gains.as_deref(),
                schedule: schedule.as_deref(),
                inputs,
                speeds: speeds.as_deref(),
                format: *format,
                out: out.as_deref(),
                plot: plot.as_deref(),
                range: range.as_deref(),
            },
        ),
        ControlCommand::Lqr {
            bike,
            speed,
            speeds,
            q,
            r,
            inputs,
            format,
        } => crate::feedback::lqr(cx, bike, *speed, speeds.as_deref(), q, r, inputs, *format),
        ControlCommand::Hqm(hqm) => crate::hqm::run(cx, hqm),
        ControlCommand::Place {
            bike,
            speed,
            input,
            poles,
            format,
        } => crate::feedback::place(cx, bike, *speed, input, poles, *format),
        ControlCommand::Hess(args) => crate::hess::hess(cx, args),
        ControlCommand::OptimalHandling(args) => crate::optimal::run(cx, args),
        ControlCommand::LaneChange(args) => crate::lane_change::run(cx, args),
    }
}

/// A complex number as `a ± bi`.
pub(crate) fn complex(z: Complex64) -> Result<String> {
    Ok(if z.im == 0.0 {
        number(z.re)?
    } else {
        format!(
            "{} {} {}i",
            number(z.re)?,
            if z.im < 0.0 { '-' } else { '+' },
            number(z.im.abs())?
        )
    })
}

/// One row of the table: a speed's rank, condition and modal measures (mode, λ, measure).
struct Row {
    speed: f64,
    rank: usize,
    states: usize,
    condition: f64,
    modes: Vec<(&'static str, Complex64, f64)>,
}

fn controllability(
    cx: &RunContext,
    arg: &str,
    inputs: &[String],
    speeds: &str,
    format: TextFormat,
    out: Option<&std::path::Path>,
) -> Result<()> {
    let target = out
        .map(|p| crate::output::Target::check("--out", p))
        .transpose()?;
    let bike = load(cx, arg)?;
    let names: Vec<&str> = if inputs.is_empty() {
        vec!["steer_torque", "lean_torque"]
    } else {
        inputs.iter().map(String::as_str).collect()
    };
    let inputs: Vec<Input> = names
        .iter()
        .map(|name| whipple_front::system::parse_input(name))
        .collect::<whipple::Result<_>>()
        .context("--input")?;
    let ((start, stop, step), unit) = crate::output::parse_triple_in(speeds, "--speeds")?;
    let grid = whipple::speed_grid(start, stop, step).context("--speeds")?;
    if grid.len() > MAX_CONTROL_SPEEDS {
        anyhow::bail!(
            "--speeds: at most {MAX_CONTROL_SPEEDS} speeds, got {}",
            grid.len()
        );
    }
    let c = crate::commands::canonical(&bike)?;
    let mut sections = Vec::new();
    for input in &inputs {
        let lost = uncontrollable_speeds(&bike.benchmark, input)
            .with_context(|| format!("the speeds where {input} loses a mode"))?;
        let request = SystemRequest {
            states: Vec::new(),
            inputs: vec![*input],
            outputs: vec![Output::State(StateVariable::Lean)],
        };
        let mut rows = Vec::with_capacity(grid.len());
        for &v in &grid {
            let system = LinearSystem::new(&bike.benchmark, v, &request)
                .with_context(|| format!("the linear system at {v} m/s"))?;
            let kalman = system.controllability(Some(0))?;
            let shapes = mode_shapes(&c, v).with_context(|| format!("the modes at {v} m/s"))?;
            let modes = system
                .modal_controllability(0)?
                .into_iter()
                .map(|m| {
                    let label = shapes
                        .iter()
                        .min_by(|a, b| {
                            whipple::math::norm(a.pair.value - m.eigenvalue)
                                .total_cmp(&whipple::math::norm(b.pair.value - m.eigenvalue))
                        })
                        .map_or("mode", |s| s.mode.name());
                    (label, m.eigenvalue, m.measure)
                })
                .collect();
            rows.push(Row {
                speed: v,
                rank: kalman.rank,
                states: kalman.states,
                condition: kalman.condition,
                modes,
            });
        }
        sections.push((input, lost, rows));
    }
    let text = match format {
        TextFormat::Json => {
            let mut doc_inputs = Vec::new();
            for (input, lost, rows) in &sections {
                let mut speeds = Vec::new();
                for s in &lost.speeds {
                    let (lo, hi) = s.speed.enclosure();
                    number(s.speed.value())?;
                    speeds.push(json!({
                        "speed": s.speed.value(),
                        "enclosure": [lo, hi],
                        "resolved": matches!(s.speed, RealRoot::Simple { .. }),
                        "eigenvalue": [s.eigenvalue.re, s.eigenvalue.im],
                    }));
                }
                let mut table = Vec::new();
                for r in rows {
                    let mut modes = Vec::new();
                    for (label, value, measure) in &r.modes {
                        number(*measure)?;
                        modes.push(json!({
                            "mode": label,
                            "eigenvalue": [value.re, value.im],
                            "modal_controllability": measure,
                        }));
                    }
                    table.push(json!({
                        "speed": r.speed,
                        "rank": r.rank,
                        "states": r.states,
                        // JSON has no infinity: a rank-deficient matrix's condition is null.
                        "condition": if r.condition.is_finite() { json!(r.condition) } else { json!(null) },
                        "modes": modes,
                    }));
                }
                doc_inputs.push(json!({
                    "input": input.to_string(),
                    "uncontrollable_speeds": speeds,
                    "uncontrollable_everywhere": lost.everywhere,
                    "table": table,
                }));
            }
            let doc = json!({
                "bike": bike.label,
                "inputs": doc_inputs,
                "warnings": bike.warnings_json(),
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            for (input, lost, rows) in &sections {
                writeln!(t, "{}: controllability by {input}", bike.label)?;
                if lost.everywhere {
                    writeln!(
                        t,
                        "  {input} does no work on lean or steer: it controls no mode at any speed"
                    )?;
                } else if lost.speeds.is_empty() {
                    writeln!(
                        t,
                        "  {input} reaches every lean–steer mode at every speed (certified: the \
                         polynomial whose roots are the speeds where a mode is lost has no real root)"
                    )?;
                } else {
                    writeln!(
                        t,
                        "  speeds where {input} cannot reach a lean–steer mode (certified: the real \
                         roots of a polynomial in v, none missed; the same at -v):"
                    )?;
                    for s in &lost.speeds {
                        let (lo, hi) = s.speed.enclosure();
                        let stable = if s.eigenvalue.re < 0.0 {
                            "stable"
                        } else {
                            "unstable"
                        };
                        match s.speed {
                            RealRoot::Simple { value, .. } => writeln!(
                                t,
                                "    v = {} m/s: the {stable} motion λ = {} 1/s is lost",
                                number(value)?,
                                complex(s.eigenvalue)?
                            )?,
                            RealRoot::Cluster { .. } => writeln!(
                                t,
                                "    v in [{}, {}] m/s (not resolved: a near-double root): a mode \
                                 near λ = {} 1/s is lost",
                                number(lo)?,
                                number(hi)?,
                                complex(s.eigenvalue)?
                            )?,
                        }
                    }
                }
                writeln!(
                    t,
                    "  at each speed (numerical): the Kalman matrix's rank and condition, and each \
                     mode's λ [1/s] and modal\n  controllability |ℓᵀb|/(‖ℓ‖‖b‖) (0: not reached, 1: \
                     best)\n  v [{}]   rank   condition   modes",
                    unit.symbol()
                )?;
                for r in rows {
                    let condition = if r.condition.is_finite() {
                        format!("{:.3e}", r.condition)
                    } else {
                        "inf".to_string()
                    };
                    let mut modes = Vec::new();
                    for (label, value, measure) in &r.modes {
                        // A conjugate pair has one measure: listed once, as `a ± bi`.
                        if value.im < 0.0 {
                            continue;
                        }
                        number(value.re)?;
                        number(*measure)?;
                        let value = if value.im > 0.0 {
                            format!("{:.4}±{:.4}i", value.re, value.im)
                        } else {
                            format!("{:.4}", value.re)
                        };
                        let measure = if *measure >= 1e-3 || *measure == 0.0 {
                            format!("{measure:.3}")
                        } else {
                            format!("{measure:.1e}")
                        };
                        modes.push(format!("{label} {value}: {measure}"));
                    }
                    writeln!(
                        t,
                        "  {:<9} {}/{}    {:<11} {}",
                        crate::output::speed_number(r.speed, unit)?,
                        r.rank,
                        r.states,
                        condition,
                        modes.join("; ")
                    )?;
                }
                t.push('\n');
            }
            t
        }
    };
    emit(&text, target.as_ref())
}
