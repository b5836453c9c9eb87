//! `whipple turn` (one steady turn and its stability) and `whipple turns` (the families of
//! hands-free turns, and a figure).

use std::fmt::Write as _;

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::json;
use whipple::Model;
use whipple::advanced::turns::{
    Family, FamilySettings, Held, Stability, SteadyTurn, TurnSettings, hands_free_families,
    hands_free_turns_at_speed, held_turn, stability,
};

use crate::TextFormat;
use crate::bike::{LoadedBike, RunContext, load};
use crate::commands::emit;
use crate::output::{number, table_and_plot};
use whipple_front::units::SpeedUnit;

/// Arguments of `whipple turn`.
#[derive(Args, Debug)]
pub struct TurnArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    pub bike: String,
    /// Speed of the rear contact in m/s (or km/h after it: 18km/h).
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    pub speed: crate::TypedSpeed,
    /// Lean in degrees (right positive): the held turn at this lean.
    #[arg(long, allow_hyphen_values = true, group = "given")]
    pub lean: Option<f64>,
    /// Steer in degrees (right positive): the held turn at this steer.
    #[arg(long, allow_hyphen_values = true, group = "given")]
    pub steer: Option<f64>,
    /// Radius of the rear contact's circle in m (positive right, negative left).
    #[arg(long, allow_hyphen_values = true, group = "given")]
    pub radius: Option<f64>,
    /// Every hands-free turn (no steer torque) at this speed, from the traced families.
    #[arg(long, group = "given")]
    pub hands_free: bool,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    pub format: TextFormat,
}

/// Arguments of `whipple turns`.
#[derive(Args, Debug)]
pub struct TurnsArgs {
    #[arg(long, help = whipple_front::formats::bike_help())]
    pub bike: String,
    /// Speeds traced, LO:HI in m/s (or km/h after them) (default 0:20).
    #[arg(long, allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Output format of the summary.
    #[arg(long, value_enum, default_value = "table")]
    pub format: TextFormat,
    /// Write the summary (or with --format json every point) to this file instead of stdout.
    #[arg(long)]
    pub out: Option<std::path::PathBuf>,
    /// Figure of the families (.svg or .png): lean, steer and radius against speed, stable
    /// parts bold, and the held steer torque against lateral acceleration.
    #[arg(long)]
    pub plot: Option<std::path::PathBuf>,
}

fn model_of(bike: &LoadedBike) -> Result<Model> {
    Model::new(&bike.benchmark).with_context(|| format!("the non-linear model of {}", bike.label))
}

fn deg(x: f64) -> Result<String> {
    fixed(x.to_degrees(), 4)
}

/// A finite result with `digits` decimals ([`whipple_front::format::fixed`]).
fn fixed(x: f64, digits: usize) -> Result<String> {
    number(x)?;
    Ok(whipple_front::format::fixed(x, digits))
}

fn radius_text(r: Option<f64>) -> Result<String> {
    match r {
        Some(r) => Ok(format!("{} m", fixed(r, 4)?)),
        None => Ok("straight".into()),
    }
}

/// The text of one turn and its stability.
pub fn turn_text(turn: &SteadyTurn, stab: &Result<Stability, String>) -> Result<String> {
    let mut t = String::new();
    writeln!(
        t,
        "  speed (rear contact)  {} m/s (rear hub {} m/s)",
        fixed(turn.speed, 6)?,
        fixed(turn.hub_speed, 6)?
    )?;
    writeln!(t, "  lean                  {} deg", deg(turn.lean)?)?;
    writeln!(t, "  steer                 {} deg", deg(turn.steer)?)?;
    writeln!(
        t,
        "  steer torque          {} N m",
        fixed(turn.steer_torque, 6)?
    )?;
    writeln!(t, "  pitch (rear frame)    {} deg", deg(turn.pitch)?)?;
    writeln!(
        t,
        "  radius rear contact   {}",
        radius_text(turn.rear_radius)?
    )?;
    writeln!(
        t,
        "  radius front contact  {}",
        radius_text(turn.front_radius)?
    )?;
    writeln!(
        t,
        "  radius mass centre    {}",
        radius_text(turn.mass_centre_radius)?
    )?;
    writeln!(
        t,
        "  yaw rate              {} rad/s",
        fixed(turn.yaw_rate, 6)?
    )?;
    writeln!(
        t,
        "  lateral acceleration  {} m/s^2 (mass centre)",
        fixed(turn.lateral_acceleration, 4)?
    )?;
    writeln!(
        t,
        "  wheel rates           rear {} rad/s, front {} rad/s",
        fixed(turn.wheel_rates[0], 4)?,
        fixed(turn.wheel_rates[1], 4)?
    )?;
    for (name, c) in ["rear", "front"].iter().zip(&turn.contact) {
        let ratio = if c.friction_ratio.is_finite() {
            fixed(c.friction_ratio, 4)?
        } else {
            "lifts off".into()
        };
        writeln!(
            t,
            "  {name:<5} contact         normal {} N, lateral {} N, longitudinal {} N, friction ratio {ratio}",
            fixed(c.normal, 3)?,
            fixed(c.lateral, 3)?,
            fixed(c.longitudinal, 3)?
        )?;
        if c.normal < 0.0 {
            // A held turn like this is refused by the library; a hands-free one from the
            // families is shown, flagged.
            writeln!(
                t,
                "  WARNING: the ground would pull the {name} wheel down ({} N): it lifts off, and the knife-edge model cannot hold this turn",
                fixed(c.normal, 1)?
            )?;
        }
    }
    writeln!(
        t,
        "  residuals             lean {:.1e} rad/s^2, steer {:.1e} rad/s^2, forward speed {:.1e} m/s^2 (not solved for: it vanishes by itself)",
        turn.residuals.lean_acceleration,
        turn.residuals.steer_acceleration,
        turn.residuals.speed_rate
    )?;
    match stab {
        Ok(s) => {
            let values: Vec<String> = s
                .eigenvalues
                .iter()
                .map(|z| {
                    if z.im == 0.0 {
                        format!("{:.4}", z.re)
                    } else {
                        format!("{:.4}{:+.4}i", z.re, z.im)
                    }
                })
                .collect();
            writeln!(
                t,
                "  stability             {} (eigenvalues {} 1/s; the fifth, {:.1e}, is the family's: a neighbouring turn at another speed)",
                if s.stable { "stable" } else { "unstable" },
                values.join(", "),
                s.family_eigenvalue
            )?;
        }
        Err(e) => writeln!(t, "  stability             not decided: {e}")?,
    }
    Ok(t)
}

fn turn_json(turn: &SteadyTurn, stab: &Result<Stability, String>) -> Result<serde_json::Value> {
    let mut v = serde_json::to_value(turn)?;
    if let Some(m) = v.as_object_mut() {
        m.insert("lean_deg".into(), json!(turn.lean.to_degrees()));
        m.insert("steer_deg".into(), json!(turn.steer.to_degrees()));
        match stab {
            Ok(s) => m.insert("stability".into(), serde_json::to_value(s)?),
            Err(e) => m.insert("stability_error".into(), json!(e)),
        };
    }
    Ok(v)
}

pub fn turn(cx: &RunContext, args: &TurnArgs) -> Result<()> {
    let bike = load(cx, &args.bike)?;
    let model = model_of(&bike)?;
    let settings = TurnSettings::default();
    let given = match (args.lean, args.steer, args.radius, args.hands_free) {
        (Some(l), None, None, false) => Some(Held::Lean(l.to_radians())),
        (None, Some(s), None, false) => Some(Held::Steer(s.to_radians())),
        (None, None, Some(r), false) => Some(Held::Radius(r)),
        (None, None, None, true) => None,
        _ => bail!("give one of --lean, --steer, --radius or --hands-free"),
    };
    let turns: Vec<SteadyTurn> = match given {
        Some(g) => vec![
            held_turn(&model, args.speed.si, g, &settings)
                .with_context(|| format!("steady turn of {}", bike.label))?,
        ],
        None => {
            let families = hands_free_families(&model, &FamilySettings::default())
                .with_context(|| format!("hands-free turns of {}", bike.label))?;
            let mut found = hands_free_turns_at_speed(&model, args.speed.si, &families, &settings)?;
            // Both leans: the families are traced to the right, their mirror images lean left.
            let mirrored: Vec<SteadyTurn> = found
                .iter()
                .filter(|t| t.lean != 0.0)
                .map(|t| held_turn_mirror(&model, t, &settings))
                .collect::<Result<_>>()?;
            found.extend(mirrored);
            found
        }
    };
    let with_stab: Vec<(SteadyTurn, Result<Stability, String>)> = turns
        .into_iter()
        .map(|t| {
            let s = stability(&model, &t).map_err(|e| e.to_string());
            (t, s)
        })
        .collect();
    let text = match args.format {
        TextFormat::Json => {
            let list = with_stab
                .iter()
                .map(|(t, s)| turn_json(t, s))
                .collect::<Result<Vec<_>>>()?;
            let doc = json!({
                "bike": bike.label,
                "warnings": bike.warnings_json(),
                "hands_free": args.hands_free,
                "turns": list,
            });
            format!("{}\n", serde_json::to_string_pretty(&doc)?)
        }
        TextFormat::Table => {
            let mut t = String::new();
            if args.hands_free {
                writeln!(
                    t,
                    "{}: {} hands-free steady turn(s) at {} (on the families traced by `whipple turns`; a family the grid scan misses is missed here too)",
                    bike.label,
                    with_stab.len(),
                    crate::output::speed_words(args.speed.si, args.speed.unit)?
                )?;
            } else {
                writeln!(t, "{}: held steady turn", bike.label)?;
            }
            for (i, (turn, s)) in with_stab.iter().enumerate() {
                if args.hands_free {
                    writeln!(t, "turn {}:", i + 1)?;
                }
                t.push_str(&turn_text(turn, s)?);
            }
            t
        }
    };
    emit(&text, None)
}

/// The mirror image of a hands-free turn, (φ, δ) → (−φ, −δ), solved again (not copied).
fn held_turn_mirror(model: &Model, t: &SteadyTurn, settings: &TurnSettings) -> Result<SteadyTurn> {
    Ok(whipple::advanced::turns::hands_free_turn_near(
        model,
        [-t.lean, -t.steer, t.speed],
        2,
        settings,
    )?)
}

/// Leans of the held-torque curves [deg] and their speeds [m/s].
const HELD_LEANS_DEG: [f64; 4] = [0.0, 10.0, 20.0, 30.0];
const HELD_SPEEDS: [f64; 3] = [3.0, 5.0, 7.0];

pub fn turns(cx: &RunContext, args: &TurnsArgs) -> Result<()> {
    let (out, plot) = table_and_plot(args.out.as_deref(), args.plot.as_deref())?;
    let bike = load(cx, &args.bike)?;
    let model = model_of(&bike)?;
    let ((lo, hi), unit) = match &args.range {
        Some(text) => crate::speeds::parse_range_in(text, "--range")?,
        None => ((0.0, 20.0), SpeedUnit::MetresPerSecond),
    };
    if !(lo >= 0.0 && hi.is_finite()) {
        bail!("--range: the speeds must lie in 0..HI with a finite HI, got {lo}:{hi}");
    }
    let settings = FamilySettings {
        max_speed: hi,
        ..FamilySettings::default()
    };
    let families = hands_free_families(&model, &settings)
        .with_context(|| format!("hands-free turns of {}", bike.label))?;
    let in_range =
        |p: &whipple::advanced::turns::FamilyPoint| p.turn.speed >= lo && p.turn.speed <= hi;
    let text = match args.format {
        TextFormat::Json => {
            let fams: Vec<serde_json::Value> = families
                .iter()
                .map(|f| {
                    json!({
                        "end": f.end,
                        "points": f.points.iter().filter(|p| in_range(p)).collect::<Vec<_>>(),
                    })
                })
                .collect();
            format!(
                "{}\n",
                serde_json::to_string_pretty(&json!({
                    "bike": bike.label,
                    "warnings": bike.warnings_json(),
                    "range": [lo, hi],
                    "families": fams,
                }))?
            )
        }
        TextFormat::Table => summary(&bike.label, &families, (lo, hi), unit)?,
    };
    if let Some(target) = &plot {
        let data = figure_data(&model, &bike.label, &families, lo, hi)?;
        let figure = whipple_report::turns_plot(&data, (1400, 1000))?;
        let bytes = figure
            .render_for_path(target.path())
            .with_context(|| format!("drawing {}", target.describe()))?;
        target.write_whole(&bytes)?;
    }
    emit(&text, out.as_ref())
}

fn summary(
    label: &str,
    families: &[Family],
    (lo, hi): (f64, f64),
    unit: SpeedUnit,
) -> Result<String> {
    let mut t = String::new();
    writeln!(
        t,
        "{label}: hands-free steady turns, {} family(ies) leaning right (left leans are their mirror images), speeds {}",
        families.len(),
        crate::speeds::range_words(lo, hi, unit)?
    )?;
    writeln!(
        t,
        "  (the first leaves straight running; the others were found by a grid scan of lean and steer, which can miss a family that crosses no grid line)"
    )?;
    for (i, f) in families.iter().enumerate() {
        let pts: Vec<_> = f
            .points
            .iter()
            .filter(|p| p.turn.speed >= lo && p.turn.speed <= hi)
            .collect();
        let Some(first) = pts.first() else { continue };
        let last = pts[pts.len() - 1];
        writeln!(
            t,
            "family {}: {} points, from v {} m/s lean {} deg steer {} deg to v {} m/s lean {} deg steer {} deg (ends: {:?})",
            i + 1,
            pts.len(),
            fixed(first.turn.speed, 3)?,
            fixed(first.turn.lean.to_degrees(), 2)?,
            fixed(first.turn.steer.to_degrees(), 2)?,
            fixed(last.turn.speed, 3)?,
            fixed(last.turn.lean.to_degrees(), 2)?,
            fixed(last.turn.steer.to_degrees(), 2)?,
            f.end
        )?;
        // Stable stretches.
        let mut run: Option<(f64, f64)> = None;
        let mut stretches = Vec::new();
        for p in &pts {
            let s = p.stability.as_ref().is_some_and(|s| s.stable);
            match (s, run) {
                (true, None) => run = Some((p.turn.speed, p.turn.speed)),
                (true, Some((a, _))) => run = Some((a, p.turn.speed)),
                (false, Some(r)) => {
                    stretches.push(r);
                    run = None;
                }
                _ => {}
            }
        }
        stretches.extend(run);
        if stretches.is_empty() {
            writeln!(t, "  stable nowhere on it")?;
        }
        for (a, b) in stretches {
            writeln!(
                t,
                "  stable from v {} to {} m/s (between traced points)",
                fixed(a, 3)?,
                fixed(b, 3)?
            )?;
        }
        let lifting: Vec<f64> = pts
            .iter()
            .filter(|p| p.turn.contact.iter().any(|c| c.normal < 0.0))
            .map(|p| p.turn.speed)
            .collect();
        if let (Some(a), Some(b)) = (lifting.first(), lifting.last()) {
            writeln!(
                t,
                "  a wheel's normal force is negative at {} point(s), v {} to {} m/s: the ground would pull the wheel down, so those are not turns the knife-edge model can hold",
                lifting.len(),
                fixed(*a, 3)?,
                fixed(*b, 3)?
            )?;
        }
        let undecided = pts.iter().filter(|p| p.stability.is_none()).count();
        if undecided > 0 {
            writeln!(t, "  stability not decided at {undecided} point(s)")?;
        }
    }
    Ok(t)
}

fn figure_data(
    model: &Model,
    label: &str,
    families: &[Family],
    lo: f64,
    hi: f64,
) -> Result<whipple_report::TurnsData> {
    let fams = families
        .iter()
        .map(|f| {
            f.points
                .iter()
                .filter(|p| p.turn.speed >= lo && p.turn.speed <= hi)
                .map(|p| whipple_report::TurnPoint {
                    speed: p.turn.speed,
                    lean_deg: p.turn.lean.to_degrees(),
                    steer_deg: p.turn.steer.to_degrees(),
                    radius: p.turn.rear_radius.map_or(f64::NAN, f64::abs),
                    stable: p.stability.as_ref().is_some_and(|s| s.stable),
                })
                .collect()
        })
        .collect();
    let settings = TurnSettings::default();
    let mut held = Vec::new();
    for v in HELD_SPEEDS {
        let mut points = Vec::new();
        let mut stable = Vec::new();
        let leans = (0..=60).map(|k| k as f64 * 0.5 * HELD_LEANS_DEG[3] / 30.0 + 0.0);
        for lean_deg in leans.filter(|l| *l > 0.0) {
            let Ok(turn) = held_turn(model, v, Held::Lean(lean_deg.to_radians()), &settings) else {
                break;
            };
            points.push((turn.lateral_acceleration, turn.steer_torque));
            stable.push(stability(model, &turn).is_ok_and(|s| s.stable));
        }
        held.push(whipple_report::HeldCurve {
            name: format!("{} m/s", number(v)?),
            points,
            stable,
        });
    }
    Ok(whipple_report::TurnsData {
        title: label.to_string(),
        families: fams,
        held,
        max_radius: 30.0,
    })
}
