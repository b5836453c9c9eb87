//! `--set NAME=VALUE`: a design changed on the command line is the design written in a file
//! with that value, for every command that reads a `--bike`; a bad change is refused naming it.

use crate::common;

use crate::common::{stderr_of_failure, stdout, whipple};

fn speeds_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["speeds", "--format", "json"];
    all.extend_from_slice(args);
    serde_json::from_str(&stdout(&whipple(&all))).expect("JSON")
}

/// The changed bicycle is the one a file with the changed value describes, bit for bit: the
/// head angle in degrees is the steer axis tilt π/2 − angle in radians.
#[test]
fn a_change_is_the_file_with_that_value() {
    let dir = common::scratch("set-file");
    let file = dir.join("steep.toml");
    let converted = whipple(&[
        "convert",
        "--bike",
        "benchmark",
        "--set",
        "head_angle_deg=74",
        "--set",
        "trail=0.06",
        "--to",
        "toml",
        "--out",
        file.to_str().expect("a UTF-8 path"),
    ]);
    stdout(&converted);
    let written = std::fs::read_to_string(&file).expect("the file");
    assert!(written.contains("(edited)"), "{written}");
    let from_file = speeds_json(&["--bike", file.to_str().expect("a UTF-8 path")]);
    let by_set = speeds_json(&[
        "--bike",
        "benchmark",
        "--set",
        "head_angle_deg=74",
        "--set",
        "trail=0.06",
    ]);
    for key in ["weave_speed", "capsize_speed", "double_root_speed"] {
        assert_eq!(from_file[key], by_set[key], "{key}");
    }
    // The head angle is π/2 − λ: the same design as λ = 16° in radians (to the rounding of
    // the two ways of computing it).
    let lam = (90.0_f64 - 74.0).to_radians();
    let by_lam = speeds_json(&[
        "--bike",
        "benchmark",
        "--set",
        &format!("lam={lam:?}"),
        "--set",
        "c=0.06",
    ]);
    for key in ["weave_speed", "capsize_speed"] {
        let (a, b) = (
            by_set[key].as_f64().expect("a speed"),
            by_lam[key].as_f64().expect("a speed"),
        );
        assert!((a - b).abs() < 1e-12 * a, "{key}: {a} {b}");
    }
    let plain = speeds_json(&["--bike", "benchmark"]);
    assert_ne!(plain["weave_speed"], by_set["weave_speed"]);
    // Setting a value to what it is changes nothing but the name.
    let same = speeds_json(&["--bike", "benchmark", "--set", "c=0.08"]);
    assert_eq!(same["weave_speed"], plain["weave_speed"]);
    assert_eq!(same["bike"], "benchmark (edited)");
}

#[test]
fn a_bad_change_is_refused_naming_it() {
    for (args, expected) in [
        (
            &["speeds", "--bike", "benchmark", "--set", "trail"][..],
            "expects NAME=VALUE",
        ),
        (
            &["speeds", "--bike", "benchmark", "--set", "trail=abc"][..],
            "`abc` is not a finite number",
        ),
        (
            &["speeds", "--bike", "benchmark", "--set", "trail=NaN"][..],
            "not a finite number",
        ),
        (
            &["speeds", "--bike", "benchmark", "--set", "trail_deg=3"][..],
            "`trail` is not an angle",
        ),
        (
            &["speeds", "--bike", "benchmark", "--set", "wheelbase_x=3"][..],
            "wheelbase_x",
        ),
        (
            &["speeds", "--bike", "benchmark", "--set", "IBxx=-3"][..],
            "IBxx",
        ),
        (&["presets", "--set", "trail=0.1"][..], "reads no --bike"),
    ] {
        let message = stderr_of_failure(&whipple(args));
        assert!(message.contains(expected), "{args:?}: {message}");
        assert!(
            !message.contains("NaN ") && !message.contains("panicked"),
            "{message}"
        );
    }
}
