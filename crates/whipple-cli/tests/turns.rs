//! `whipple turn` and `whipple turns`, the real binary.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};

/// The issue's example: the held turn at 5 m/s and 11.5° of lean, its torque and stability.
#[test]
fn turn_prints_steer_radius_torque_and_stability() {
    let out = stdout(&whipple(&[
        "turn",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--lean",
        "11.5",
    ]));
    for word in [
        "steer ",
        "steer torque",
        "radius rear contact",
        "friction ratio",
        "stability             stable",
    ] {
        assert!(out.contains(word), "{word}: {out}");
    }
}

#[test]
fn turn_json_is_the_library_turn() {
    let out = stdout(&whipple(&[
        "turn",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--radius",
        "-12",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let turn = &doc["turns"][0];
    let r = turn["rear_radius"].as_f64().expect("radius");
    assert!((r + 12.0).abs() < 1e-9, "{r}");
    assert!(turn["lean_deg"].as_f64().expect("lean") < 0.0);
    assert!(
        turn["residuals"]["lean_acceleration"]
            .as_f64()
            .expect("r")
            .abs()
            < 1e-12
    );
    assert!(
        turn["stability"]["eigenvalues"]
            .as_array()
            .expect("eig")
            .len()
            == 4
    );
}

#[test]
fn hands_free_turns_at_a_speed_come_in_mirror_pairs() {
    let out = stdout(&whipple(&[
        "turn",
        "--bike",
        "benchmark",
        "--speed",
        "8",
        "--hands-free",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let turns = doc["turns"].as_array().expect("turns");
    assert!(!turns.is_empty() && turns.len() % 2 == 0, "{}", turns.len());
    for t in turns {
        assert_eq!(t["steer_torque"].as_f64(), Some(0.0));
        assert!((t["speed"].as_f64().expect("v") - 8.0).abs() < 1e-12);
    }
}

#[test]
fn impossible_and_bad_turns_are_errors() {
    let err = stderr_of_failure(&whipple(&[
        "turn",
        "--bike",
        "benchmark",
        "--speed",
        "8",
        "--radius",
        "0.05",
    ]));
    assert!(err.contains("no steady turn"), "{err}");
    let err = stderr_of_failure(&whipple(&[
        "turn",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--lean",
        "95",
    ]));
    assert!(err.contains("lean"), "{err}");
    let err = stderr_of_failure(&whipple(&["turn", "--bike", "benchmark", "--speed", "5"]));
    assert!(err.contains("--lean"), "{err}");
}

#[test]
fn turns_traces_families_and_draws_them() {
    let dir = scratch("turns-plot");
    let png = dir.join("turns.png");
    let out = stdout(&whipple(&[
        "turns",
        "--bike",
        "benchmark",
        "--plot",
        png.to_str().expect("path"),
    ]));
    assert!(out.contains("family 1:"), "{out}");
    assert!(out.contains("stable from v"), "{out}");
    let bytes = std::fs::read(&png).expect("the plot");
    assert_eq!(&bytes[1..4], b"PNG");
}

/// `simulate --from-turn` starts on the held turn and, with its torque, stays there.
#[test]
fn simulate_from_a_turn_stays_on_it() {
    let out = stdout(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--lean",
        "11.5",
        "--from-turn",
        "--duration",
        "2",
        "--integrator",
        "adaptive",
        "--rtol",
        "1e-10",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let samples = doc["samples"].as_array().expect("samples");
    let steer0 = doc["initial"]["steer"].as_f64().expect("steer");
    assert!(steer0 > 0.08, "the turn's steer is reported, got {steer0}");
    for s in samples {
        let lean = s["lean"].as_f64().expect("lean");
        assert!((lean - 11.5f64.to_radians()).abs() < 1e-7, "{lean}");
    }
}

/// `turn --radius 1e200` said "a computed result is not a finite number (NaN)";
/// `--radius 0.5` at 5 m/s printed a turn with the rear normal force at −1448 N. The first is
/// refused naming the radius and its bound, the second naming the wheel and the force.
#[test]
fn turns_past_the_radius_bound_or_lifting_a_wheel_are_errors() {
    let turn = |radius: &str| {
        stderr_of_failure(&whipple(&[
            "turn",
            "--bike",
            "benchmark",
            "--speed",
            "5",
            "--radius",
            radius,
        ]))
    };
    let err = turn("1e200");
    assert!(err.contains("radius") && err.contains("1e9 m"), "{err}");
    assert!(
        !err.contains("NaN") && !err.contains("not a finite"),
        "{err}"
    );
    let err = turn("0.5");
    assert!(
        err.contains("rear wheel's normal force would be -1448.") && err.contains("lifts off"),
        "{err}"
    );
}
