//! The bicycle as a system from the command line, the real binary: `whipple control`.

use crate::common;

use crate::common::{stderr_of_failure, stdout, whipple};

/// The issue's "list the uncontrollable speeds": the benchmark's two speeds where steer torque
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

/// The issue's "this controller stabilizes from 0.8 m/s": steering into the fall,
/// T_δ = 100 φ − 10 δ + 20 φ̇ (`--gains "-100,10,-20,0"`), stable from the speed the library
/// certifies (0.806665615880 m/s, `crates/whipple/tests/feedback.rs`), the closed loop's v_d
/// said not computed, and its eigenvalues in `eig`'s columns.
#[test]
fn control_feedback_prints_the_closed_loop_and_its_certified_speeds() {
    let table = stdout(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--gains",
        "-100,10,-20,0",
        "--speeds",
        "0:2:0.5",
    ]));
    for word in [
        "closed-loop eigenvalues [1/s] against forward speed",
        "weave (1)",
        "castering (4)",
        "double root speed v_d  not given: not computed for a closed loop",
        "weave speed v_w        none at any speed",
        "stable                 above 0.80666561588",
    ] {
        assert!(table.contains(word), "{word}: {table}");
    }
    // At 0.5 m/s the capsize root is still unstable, at 1 m/s no longer (0.8067 lies between).
    let row = |v: &str| {
        table
            .lines()
            .find(|l| l.trim_start().starts_with(v))
            .unwrap_or_else(|| panic!("{v}: {table}"))
            .to_string()
    };
    assert!(row("0.5000").contains(" 1.2945655870"), "{table}");
    assert!(row("1.0000").contains("-0.8205647832"), "{table}");

    let json: serde_json::Value = serde_json::from_str(&stdout(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--gains",
        "-100,10,-20,0",
        "--speeds",
        "1:2:0.5",
        "--format",
        "json",
    ])))
    .unwrap();
    assert_eq!(json["inputs"], serde_json::json!(["steer_torque"]));
    assert_eq!(
        json["gains"]["constant"],
        serde_json::json!([[-100.0, 10.0, -20.0, 0.0]])
    );
    assert_eq!(json["rows"].as_array().unwrap().len(), 3);
    assert_eq!(json["rows"][0]["eigenvalues"].as_array().unwrap().len(), 4);
    let from = json["critical_speeds"]["stable_speed_ranges"][0][0]
        .as_f64()
        .unwrap();
    assert!((from - 0.806665615880).abs() < 1e-11, "{json}");
    assert!(json["critical_speeds"]["double_root_unavailable"].is_string());

    let csv = stdout(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--gains",
        "-100,10,-20,0",
        "--speeds",
        "1:2:0.5",
        "--format",
        "csv",
    ]));
    assert_eq!(csv.lines().count(), 4, "{csv}");
}

/// A schedule from a file (the same law at 1 and 5 m/s: the same closed loop), read between
/// its speeds, and the plot written.
#[test]
fn control_feedback_reads_a_schedule_and_draws_the_plot() {
    let dir = common::scratch("control-feedback-schedule");
    let schedule = dir.join("gains.csv");
    std::fs::write(
        &schedule,
        "speed,k_lean,k_steer,k_lean_rate,k_steer_rate\n1,-100,10,-20,0\n5,-100,10,-20,0\n",
    )
    .unwrap();
    let plot = dir.join("closed.png");
    let table = stdout(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--schedule",
        schedule.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
    ]));
    assert!(
        table.contains("K scheduled at 2 speeds from 1 to 5 m/s"),
        "{table}"
    );
    assert!(table.contains("critical speeds for 1..5 m/s"), "{table}");
    assert!(
        table.contains("stable                 1 .. 5 m/s"),
        "{table}"
    );
    let bytes = std::fs::read(&plot).unwrap();
    assert!(bytes.starts_with(b"\x89PNG"), "not a PNG");

    // --out: the table goes to the file, whole, and nothing to standard output; the same
    // table as standard output's. Never onto an input.
    let out = dir.join("closed.csv");
    let quiet = stdout(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--schedule",
        schedule.to_str().unwrap(),
        "--format",
        "csv",
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(quiet.is_empty(), "{quiet}");
    let written = std::fs::read_to_string(&out).unwrap();
    let printed = stdout(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--schedule",
        schedule.to_str().unwrap(),
        "--format",
        "csv",
    ]));
    assert_eq!(written, printed);
    assert_eq!(written.lines().filter(|l| !l.starts_with('#')).count(), 102);
    let refused = stderr_of_failure(&whipple(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--schedule",
        schedule.to_str().unwrap(),
        "--out",
        schedule.to_str().unwrap(),
    ]));
    assert!(refused.contains("--out"), "{refused}");
    assert!(
        std::fs::read_to_string(&schedule)
            .unwrap()
            .starts_with("speed,k_lean")
    );
}

/// LQR at 5 m/s for Q = I, R = 1: the gain the library computes (checked against scipy's
/// `solve_continuous_are` in `crates/whipple/tests/feedback.rs`), X, poles and residual; and
/// over speeds, the schedule and its certified stable range.
#[test]
fn control_lqr_gives_the_gain_and_the_scheduled_stable_speeds() {
    let json: serde_json::Value = serde_json::from_str(&stdout(&whipple(&[
        "control",
        "lqr",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--q",
        "diag:1,1,1,1",
        "--r",
        "1",
        "--format",
        "json",
    ])))
    .unwrap();
    let expected = [
        -2.54040070234819,
        4.85198630211049,
        -0.334518332164070,
        0.450072814568567,
    ];
    for (j, k) in expected.iter().enumerate() {
        let got = json["gains"][0][j].as_f64().unwrap();
        assert!((got - k).abs() < 1e-9 * k.abs().max(1.0), "{j}: {got}");
    }
    assert_eq!(json["solution"].as_array().unwrap().len(), 4);
    assert!(json["residual"].as_f64().unwrap() < 1e-12);
    let poles = json["closed_loop_eigenvalues"].as_array().unwrap();
    assert_eq!(poles.len(), 4);
    assert!(poles.iter().all(|p| p[0].as_f64().unwrap() < 0.0));
    // The same Q written out row by row.
    let table = stdout(&whipple(&[
        "control",
        "lqr",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--q",
        "1,0,0,0;0,1,0,0;0,0,1,0;0,0,0,1",
        "--r",
        "1",
    ]));
    for word in ["-2.540400702348", "closed-loop poles", "relative residual"] {
        assert!(table.contains(word), "{word}: {table}");
    }

    let table = stdout(&whipple(&[
        "control",
        "lqr",
        "--bike",
        "benchmark",
        "--speeds",
        "1:6:1",
        "--q",
        "diag:1,1,1,1",
        "--r",
        "1",
    ]));
    for word in [
        "LQR gain schedule",
        "[-2.540400702348",
        "under the scheduled LQR gains: critical speeds for 1..6 m/s (certified)",
        "stable                 1 .. 6 m/s",
    ] {
        assert!(table.contains(word), "{word}: {table}");
    }
}

/// Pole placement: K, and the check by the closed loop's eigenvalues, which are the poles.
#[test]
fn control_place_puts_the_poles_where_asked() {
    let json: serde_json::Value = serde_json::from_str(&stdout(&whipple(&[
        "control",
        "place",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--input",
        "steer_torque",
        "--poles",
        "-2,-3,-4+1i,-4-1i",
        "--format",
        "json",
    ])))
    .unwrap();
    assert_eq!(json["gains"][0].as_array().unwrap().len(), 4);
    let mut got: Vec<(f64, f64)> = json["closed_loop_eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    got.sort_by(|a, b| b.0.total_cmp(&a.0).then(b.1.total_cmp(&a.1)));
    let want = [(-2.0, 0.0), (-3.0, 0.0), (-4.0, 1.0), (-4.0, -1.0)];
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g.0 - w.0).abs() < 1e-9 && (g.1 - w.1).abs() < 1e-9,
            "{got:?}"
        );
    }
}

/// Each bad input names its option (or the schedule file and line), and LQR without a
/// stabilizing solution (a push at the rear contact cannot steady the weave at 2 m/s) gives
/// the library's reason.
#[test]
fn control_feedback_lqr_place_refuse_bad_input_naming_the_option() {
    let dir = common::scratch("control-feedback-bad");
    let short = dir.join("short.csv");
    std::fs::write(&short, "1,-100,10,-20,0\n5,-100,10\n").unwrap();
    let word = dir.join("word.csv");
    std::fs::write(&word, "speed,a,b,c,d\n1,-100,10,-20,0\n5,-100,x,-20,0\n").unwrap();
    let down = dir.join("down.csv");
    std::fs::write(&down, "5,-100,10,-20,0\n1,-100,10,-20,0\n").unwrap();
    let (short, word, down) = (
        short.to_str().unwrap().to_string(),
        word.to_str().unwrap().to_string(),
        down.to_str().unwrap().to_string(),
    );
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec!["feedback", "--gains", "-100,10,-20"],
            vec!["--gains", "1 × 4", "got 1 × 3"],
        ),
        (
            vec!["feedback", "--gains", "-100,10,-20,0;1,2,3,4"],
            vec!["--gains", "1 × 4", "got 2 × 4"],
        ),
        (
            vec!["feedback", "--gains", "a,b,c,d"],
            vec!["--gains", "`a`"],
        ),
        (vec!["feedback"], vec!["--gains", "--schedule"]),
        (
            vec!["feedback", "--schedule", &short],
            vec!["short.csv:2", "5 fields", "got 3"],
        ),
        (vec!["feedback", "--schedule", &word], vec!["word.csv:3"]),
        (
            vec!["feedback", "--schedule", &down],
            vec!["down.csv:2", "increase"],
        ),
        (
            vec!["feedback", "--gains", "-100,10,-20,0", "--input", "steer"],
            vec!["--input", "unknown input"],
        ),
        (
            vec![
                "lqr",
                "--speed",
                "5",
                "--q",
                "1,2,0,0;0,1,0,0;0,0,1,0;0,0,0,1",
                "--r",
                "1",
            ],
            vec!["--q", "symmetric"],
        ),
        (
            vec!["lqr", "--speed", "5", "--q", "diag:1,-1,1,1", "--r", "1"],
            vec!["--q"],
        ),
        (
            vec!["lqr", "--speed", "5", "--q", "diag:1,1,1,1", "--r", "0"],
            vec!["--r"],
        ),
        (
            vec!["lqr", "--speed", "5", "--q", "diag:1,1,1", "--r", "1"],
            vec!["--q"],
        ),
        (
            vec!["lqr", "--q", "diag:1,1,1,1", "--r", "1"],
            vec!["--speed", "--speeds"],
        ),
        (
            vec![
                "lqr",
                "--speed",
                "2",
                "--q",
                "diag:1,1,1,1",
                "--r",
                "1",
                "--input",
                "lateral_force:0,0",
            ],
            vec!["Riccati", "not of negative real part"],
        ),
        (
            vec!["place", "--speed", "5", "--poles", "-2,-3,-4+1i"],
            vec!["--poles", "one pole per state"],
        ),
        (
            vec!["place", "--speed", "5", "--poles", "-2,-3,-4+1i,-4+2i"],
            vec!["--poles", "conjugat"],
        ),
        (
            vec!["place", "--speed", "5", "--poles", "-2,-3,-4+1k,-4-1i"],
            vec!["--poles", "`-4+1k`"],
        ),
    ];
    for (args, words) in cases {
        let mut full = vec!["control", args[0], "--bike", "benchmark"];
        full.extend(&args[1..]);
        let e = stderr_of_failure(&whipple(&full));
        for w in &words {
            assert!(e.contains(w), "{args:?}: {w}: {e}");
        }
    }
}
