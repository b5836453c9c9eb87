//! The non-linear simulation against trajectories computed independently: a sympy/PyDy model of
//! the Whipple bicycle (Moore's formulation, Kane's method) integrated by scipy's DOP853 at
//! rtol = atol = 1e-13, by `bench/trajectory_references.py`, stored in `data/references.json`
//! with how it was made. Lean, steer, their rates, yaw, pitch, both contact points and the speed
//! at several times, for the benchmark bicycle (a decaying weave, and a fall) and for the
//! Schwinn Crown in JBike6's form (converted by the crate; the reference converted it by hand)
//! with rider torques, through RK4 and the adaptive integrator, each to the accuracy it
//! reaches; and the time the lean reaches a fall angle.

use serde_json::Value;
use whipple::advanced::integrate::{Dopri5Settings, Integrator};
use whipple::advanced::io::{Format, parse};
use whipple::advanced::nonlinear::{Outcome, Sample, TorqueExpression};
use whipple::{
    BenchmarkParameters, InitialConditions, Model, Result, SimulationSettings, presets, simulate,
};

const REFERENCES: &str = include_str!("data/references.json");

fn references() -> Value {
    serde_json::from_str(REFERENCES).expect("data/references.json is valid JSON")
}

fn number(v: &Value) -> f64 {
    v.as_f64().expect("a number in data/references.json")
}

/// The scenario's bicycle: the reference's own parameters read by the files' reader, except
/// for the Crown, which is the crate's own conversion of the preset (checked against the
/// reference's hand conversion first).
fn bicycle(scenario: &Value) -> Result<BenchmarkParameters> {
    let text = serde_json::json!({ "benchmark": scenario["bicycle"] }).to_string();
    let listed = parse(&text, Format::Json)?.benchmark()?;
    if scenario["name"]
        .as_str()
        .is_some_and(|n| n.contains("Schwinn Crown"))
    {
        let converted = presets::find("schwinn-crown")?.bicycle().benchmark()?;
        for ((name, ours), (_, theirs)) in converted.fields().iter().zip(listed.fields().iter()) {
            assert!(
                (ours - theirs).abs() <= 1e-12 * theirs.abs().max(1.0),
                "{name}: {ours} vs the hand conversion's {theirs}"
            );
        }
        return Ok(converted);
    }
    Ok(listed)
}

fn settings(scenario: &Value, integrator: Integrator, duration: f64) -> Result<SimulationSettings> {
    let torque = |key: &str| -> Result<_> {
        match scenario["torques"][key].as_str() {
            Some(text) => Ok(Some(TorqueExpression::parse(text)?.into_torque())),
            None => Ok(None),
        }
    };
    Ok(SimulationSettings {
        integrator,
        duration,
        lean_torque: torque("lean")?,
        steer_torque: torque("steer")?,
        // The references run through the fall: only the fall-angle test stops early.
        stop_on_lift_off: false,
        fall_angle: 80f64.to_radians(),
        ..SimulationSettings::default()
    })
}

fn start(model: &Model, scenario: &Value) -> Result<whipple::advanced::nonlinear::State<f64>> {
    let ic = &scenario["initial"];
    model.initial_state(&InitialConditions {
        lean: number(&ic["lean"]),
        steer: number(&ic["steer"]),
        lean_rate: number(&ic["lean_rate"]),
        steer_rate: number(&ic["steer_rate"]),
        ..InitialConditions::upright(number(&ic["speed"]))
    })
}

const QUANTITIES: [&str; 11] = [
    "lean",
    "steer",
    "lean_rate",
    "steer_rate",
    "yaw",
    "pitch",
    "x",
    "y",
    "front_x",
    "front_y",
    "speed",
];

fn quantity(s: &Sample, name: &str) -> f64 {
    match name {
        "lean" => s.lean,
        "steer" => s.steer,
        "lean_rate" => s.lean_rate,
        "steer_rate" => s.steer_rate,
        "yaw" => s.yaw,
        "pitch" => s.pitch,
        "x" => s.x,
        "y" => s.y,
        "front_x" => s.front_x,
        "front_y" => s.front_y,
        _ => s.speed,
    }
}

/// The largest difference from the reference over every sample time and quantity, and where.
fn largest_difference(
    scenario: &Value,
    at: &mut dyn FnMut(f64) -> Result<Sample>,
) -> Result<(f64, String)> {
    let mut worst = (0.0, String::new());
    for reference in scenario["samples"].as_array().expect("samples") {
        let t = number(&reference["t"]);
        let sample = at(t)?;
        assert!(
            (sample.t - t).abs() < 1e-12,
            "sampled at {} for {t}",
            sample.t
        );
        for name in QUANTITIES {
            let d = (quantity(&sample, name) - number(&reference[name])).abs();
            if d > worst.0 {
                worst = (d, format!("{name} at t = {t}"));
            }
        }
    }
    Ok(worst)
}

/// RK4 at dt: every sample of one run, looked up at the reference's times.
fn rk4_difference(scenario: &Value, dt: f64) -> Result<(f64, String)> {
    let model = Model::new(&bicycle(scenario)?)?;
    let times = scenario["times"].as_array().expect("times");
    let end = number(times.last().expect("a time"));
    let run = simulate(
        &model,
        start(&model, scenario)?,
        &settings(scenario, Integrator::Rk4 { dt }, end)?,
    )?;
    assert_eq!(run.outcome, Outcome::Completed, "{}", scenario["name"]);
    largest_difference(scenario, &mut |t| {
        Ok(*run
            .samples
            .iter()
            .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
            .expect("samples"))
    })
}

/// The adaptive integrator: one run per sample time, ending exactly there.
fn adaptive_difference(scenario: &Value, rtol: f64) -> Result<(f64, String)> {
    let model = Model::new(&bicycle(scenario)?)?;
    let initial = start(&model, scenario)?;
    let integrator = Integrator::Dopri5(Dopri5Settings {
        rtol,
        atol: rtol * 1e-2,
        ..Dopri5Settings::default()
    });
    largest_difference(scenario, &mut |t| {
        let run = simulate(&model, initial, &settings(scenario, integrator, t)?)?;
        assert_eq!(run.outcome, Outcome::Completed);
        Ok(*run.samples.last().expect("samples"))
    })
}

fn scenarios() -> Vec<Value> {
    references()["trajectories"]
        .as_array()
        .expect("trajectories")
        .clone()
}

/// RK4 at the study's dt = 1 ms follows each reference to 3e-9 (rad, m, m/s; measured 1.1e-9,
/// the front contact after 5 s; 2e-10 to 7e-10 in the angles and rates), and doubling dt
/// multiplies the difference by 16: fourth order on the bicycle (measured 4.00-4.01), the
/// reference being that much more accurate.
#[test]
fn rk4_follows_the_independent_trajectories() -> Result<()> {
    for scenario in scenarios() {
        let (coarse, where_coarse) = rk4_difference(&scenario, 2e-3)?;
        let (fine, where_fine) = rk4_difference(&scenario, 1e-3)?;
        let order = whipple::math::log2(coarse / fine);
        println!(
            "{}: RK4 dt = 2 ms {coarse:.2e} ({where_coarse}), 1 ms {fine:.2e} ({where_fine}), order {order:.2}",
            scenario["name"]
        );
        assert!(
            fine < 3e-9,
            "{}: {fine:e} at {where_fine}",
            scenario["name"]
        );
        assert!(
            (3.6..4.4).contains(&order),
            "{}: order {order}",
            scenario["name"]
        );
    }
    Ok(())
}

/// The adaptive integrator at rtol = 1e-10 follows each reference to 3e-10 (measured up to
/// 9e-11), and at 1e-12 to 1e-11 (measured up to 3.2e-12): the error follows the tolerance.
#[test]
fn the_adaptive_integrator_follows_the_independent_trajectories() -> Result<()> {
    for scenario in scenarios() {
        let (loose, where_loose) = adaptive_difference(&scenario, 1e-10)?;
        let (tight, where_tight) = adaptive_difference(&scenario, 1e-12)?;
        println!(
            "{}: adaptive rtol 1e-10 {loose:.2e} ({where_loose}), 1e-12 {tight:.2e} ({where_tight})",
            scenario["name"]
        );
        assert!(
            loose < 3e-10,
            "{}: {loose:e} at {where_loose}",
            scenario["name"]
        );
        assert!(
            tight < 1e-11,
            "{}: {tight:e} at {where_tight}",
            scenario["name"]
        );
        assert!(tight < loose, "{}", scenario["name"]);
    }
    Ok(())
}

/// The rider's torques act with the right sign and size: without them the Crown's motion
/// departs from the reference by far more than the integrator's error, and with the lean
/// torque's sign flipped too.
#[test]
fn the_rider_torques_are_applied_as_the_reference_applies_them() -> Result<()> {
    let scenario = scenarios()
        .into_iter()
        .find(|s| s["torques"].is_object())
        .expect("a scenario with torques");
    let (with, _) = rk4_difference(&scenario, 1e-3)?;
    let mut flipped = scenario.clone();
    flipped["torques"]["lean"] = Value::from("-1.5");
    let (lean_flipped, _) = rk4_difference(&flipped, 1e-3)?;
    let mut no_steer = scenario.clone();
    no_steer["torques"]["steer"] = Value::from("0");
    let (steer_dropped, _) = rk4_difference(&no_steer, 1e-3)?;
    println!(
        "with torques {with:.1e}; lean torque flipped {lean_flipped:.1e}; steer torque dropped {steer_dropped:.1e}"
    );
    assert!(with < 5e-10);
    assert!(lean_flipped > 1e-3 && steer_dropped > 1e-3);
    Ok(())
}

/// The time at which |lean| reaches the fall angle (30° here, before the rear wheel would lift
/// off) against the reference's event location: RK4 interpolates linearly within its 1 ms
/// step (measured 4.7e-8 s off) and ends in the step that crosses it; the adaptive integrator
/// bisects on its dense output (measured 1e-12 s off).
#[test]
fn the_fall_is_located_where_the_reference_locates_it() -> Result<()> {
    let scenario = scenarios()
        .into_iter()
        .find(|s| s["fall_time"].is_number())
        .expect("a scenario with a fall");
    let fall_angle = number(&scenario["fall_angle"]);
    let reference = number(&scenario["fall_time"]);
    let model = Model::new(&bicycle(&scenario)?)?;
    let initial = start(&model, &scenario)?;
    for (integrator, tolerance) in [
        (Integrator::Rk4 { dt: 1e-3 }, 2e-7),
        (
            Integrator::Dopri5(Dopri5Settings {
                rtol: 1e-11,
                atol: 1e-13,
                ..Dopri5Settings::default()
            }),
            1e-10,
        ),
    ] {
        let run = simulate(
            &model,
            initial,
            &SimulationSettings {
                fall_angle,
                ..settings(&scenario, integrator, 5.0)?
            },
        )?;
        let Outcome::Fell { t, lean } = run.outcome else {
            panic!("{integrator:?}: expected a fall, got {:?}", run.outcome);
        };
        println!("{integrator:?}: fell at {t:.12} (reference {reference:.12}), lean {lean}");
        assert!(
            (t - reference).abs() < tolerance,
            "{integrator:?}: {t} vs {reference}"
        );
        assert!((lean.abs() - fall_angle).abs() < 1e-12, "{lean}");
        // The run ends with the step that crosses the fall angle.
        let n = run.samples.len();
        assert!(run.samples[n - 2].t < t && t <= run.samples[n - 1].t);
        assert!(run.samples[n - 2].lean.abs() < fall_angle);
        assert!(run.samples[n - 1].lean.abs() >= fall_angle);
        if let Integrator::Rk4 { dt } = integrator {
            assert_eq!(run.steps, (reference / dt).ceil() as usize);
        }
    }
    Ok(())
}
