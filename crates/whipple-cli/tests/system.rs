//! The bicycle as a system from the command line, the real binary: `whipple control`.

mod common;

use common::{stderr_of_failure, stdout, whipple};

/// The "list the uncontrollable speeds": the benchmark's two speeds where steer torque
/// loses a mode, as the library certifies them, in the table and in JSON with the enclosures.
#[test]
fn control_controllability_lists_the_certified_speeds() {
    let table = stdout(&whipple(&[
        "control",
        "controllability",
        "--bike",
        "benchmark",
        "--input",
        "steer_torque",
        "--speeds",
        "1:2:0.5",
    ]));
    for word in [
        "controllability by steer_torque",
        "v = 0.0250778535121",
        "the unstable motion λ = 3.13466385808",
        "v = 1.41102435675",
        "the stable motion λ = -3.13466385808",
        "capsize",
        "castering",
    ] {
        assert!(table.contains(word), "{word}: {table}");
    }
    // Three speeds, each at full rank.
    assert_eq!(table.matches(" 4/4 ").count(), 3, "{table}");

    let json = stdout(&whipple(&[
        "control",
        "controllability",
        "--bike",
        "benchmark",
        "--speeds",
        "1.4110243567568979:1.4110243567568979:1",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
    let inputs = doc["inputs"].as_array().unwrap();
    assert_eq!(inputs.len(), 2, "steer and lean torque by default");
    let steer = &inputs[0];
    assert_eq!(steer["input"], "steer_torque");
    let speeds = steer["uncontrollable_speeds"].as_array().unwrap();
    assert_eq!(speeds.len(), 2);
    let second = &speeds[1];
    let (lo, hi) = (
        second["enclosure"][0].as_f64().unwrap(),
        second["enclosure"][1].as_f64().unwrap(),
    );
    assert!(
        lo <= 1.4110243567569 && 1.4110243567569 <= hi + 1e-13,
        "{second}"
    );
    assert_eq!(second["resolved"], true);
    // At the lost speed itself the Kalman matrix is rank-deficient: its condition is null, and
    // the lost mode's modal controllability is zero.
    let row = &steer["table"][0];
    assert_eq!(row["rank"], 3, "{row}");
    assert!(row["condition"].is_null());
    let smallest = row["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["modal_controllability"].as_f64().unwrap())
        .fold(f64::INFINITY, f64::min);
    assert!(smallest < 1e-12, "{row}");
    let lean = &inputs[1];
    assert_eq!(lean["input"], "lean_torque");
    assert_eq!(lean["uncontrollable_speeds"].as_array().unwrap().len(), 2);
}

#[test]
fn control_controllability_refuses_bad_input_naming_the_option() {
    for (args, words) in [
        (
            vec!["--input", "steer"],
            vec!["--input", "unknown input", "steer_torque"],
        ),
        (vec!["--input", "lateral_force:1"], vec!["--input", "X,Z"]),
        (vec!["--speeds", "0:10"], vec!["--speeds"]),
        (vec!["--speeds", "0:1e9:1e-9"], vec!["--speeds"]),
    ] {
        let mut full = vec!["control", "controllability", "--bike", "benchmark"];
        full.extend(args.iter());
        let e = stderr_of_failure(&whipple(&full));
        for w in &words {
            assert!(e.contains(w), "{args:?}: {w}: {e}");
        }
    }
    // A push at the rear contact does no work: said, not a table of zeros alone.
    let out = stdout(&whipple(&[
        "control",
        "controllability",
        "--bike",
        "benchmark",
        "--input",
        "lateral_force:0,0",
        "--speeds",
        "1:1:1",
    ]));
    assert!(out.contains("does no work on lean or steer"), "{out}");
    assert!(out.contains(" 0/4 "), "{out}");
}
