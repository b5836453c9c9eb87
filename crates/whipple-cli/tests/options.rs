//! Messages that name the option as the user wrote it: negative numbers reach our
//! checks (not clap's "unexpected argument '-1'"), and numbers in messages are short.

use crate::common;

use crate::common::{stderr_of_failure, stdout, whipple};

const SIMULATE: [&str; 6] = [
    "simulate",
    "--bike",
    "benchmark",
    "--speed",
    "5",
    "--duration",
];

fn simulate_with(duration: &str, extra: &[&str]) -> String {
    let mut args = SIMULATE.to_vec();
    args.push(duration);
    args.extend_from_slice(extra);
    stderr_of_failure(&whipple(&args))
}

#[test]
fn negative_numbers_are_checked_and_named() {
    for (extra, option) in [
        (&["--dt", "-1"][..], "--dt"),
        (&["--integrator", "adaptive", "--rtol", "-1"][..], "--rtol"),
        (&["--fall-angle", "-3"][..], "--fall-angle"),
    ] {
        let err = simulate_with("1", extra);
        assert!(err.contains(option), "{extra:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{extra:?}: {err}");
    }
    let err = simulate_with("-3", &[]);
    assert!(err.contains("--duration must be positive, got -3"), "{err}");
}

#[test]
fn modes_names_speed_and_keeps_numbers_short() {
    let err = stderr_of_failure(&whipple(&[
        "modes",
        "--bike",
        "benchmark",
        "--speed",
        "1e154",
    ]));
    assert!(err.contains("--speed 1e154"), "{err}");
    // The 155-digit spelling of 1e154 is not in the message.
    assert!(!err.contains("10000000000"), "{err}");
}

#[test]
fn tiny_steps_are_shown_in_scientific_notation() {
    let err = simulate_with("1e-300", &["--dt", "1e-3"]);
    assert!(err.contains("--dt") && err.contains("1e-300"), "{err}");
    assert!(err.len() < 400, "{err}");
}

/// `validate --speeds 0:1e5:0.01` was accepted and would have taken a day.
#[test]
fn validate_refuses_sweeps_past_its_time_bound() {
    let err = stderr_of_failure(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "0:1e5:0.01",
    ]));
    assert!(err.contains("--speeds") && err.contains("minutes"), "{err}");
}

/// A file named `benchmark` in the working directory does not silently replace the preset:
/// the preset is taken with a note saying so and how to name the file (`./benchmark`), which
/// then reads the file.
#[test]
fn a_file_named_like_a_preset_does_not_hide_it() {
    let dir = common::scratch("preset-and-file");
    // The benchmark bicycle with a 0.5 m trail instead of 0.08 m: a different bicycle.
    let preset = whipple(&["convert", "--bike", "benchmark", "--to", "toml"]);
    assert!(preset.status.success());
    let text = String::from_utf8_lossy(&preset.stdout).replace("c = 0.08", "c = 0.5");
    assert!(text.contains("c = 0.5"), "{text}");
    std::fs::write(dir.join("benchmark"), text).expect("written");
    let show = |bike: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_whipple"))
            .args(["show", "--bike", bike])
            .current_dir(&dir)
            .output()
            .expect("runs")
    };
    let by_name = show("benchmark");
    let (out, err) = (
        String::from_utf8_lossy(&by_name.stdout),
        String::from_utf8_lossy(&by_name.stderr),
    );
    assert!(by_name.status.success(), "{err}");
    assert!(
        err.contains("names both a preset and a file") && err.contains("./benchmark"),
        "{err}"
    );
    let trail = |out: &str| {
        out.lines()
            .find_map(|l| l.trim_start().strip_prefix("c "))
            .and_then(|rest| rest.split_whitespace().next())
            .map(str::to_string)
    };
    assert_eq!(trail(&out).as_deref(), Some("0.08"), "{out}");
    let by_path = show("./benchmark");
    let (out, err) = (
        String::from_utf8_lossy(&by_path.stdout),
        String::from_utf8_lossy(&by_path.stderr),
    );
    assert!(by_path.status.success(), "{err}");
    assert!(!err.contains("names both"), "{err}");
    assert_eq!(trail(&out).as_deref(), Some("0.5"), "{out}");
}

/// This exact command reported `fell` with exit status 0 for a bicycle inside its
/// self-stable range, the energy grown 326-fold. A step beyond RK4's stability bound for the
/// fastest mode at the run's speed is an error naming the step to use, never an outcome.
#[test]
fn a_step_too_large_is_an_error_naming_the_step_to_use() {
    let command = [
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "4.6",
        "--lean-rate",
        "0.5",
        "--duration",
        "10",
        "--dt",
    ];
    let mut args = command.to_vec();
    args.push("0.25");
    let output = whipple(&args);
    let err = stderr_of_failure(&output);
    assert!(err.contains("--dt 0.25 is too large"), "{err}");
    assert!(err.contains("use --dt <= 0.05"), "{err}");
    assert!(!err.contains("fell"), "{err}");
    assert!(output.stdout.is_empty(), "no table for a refused run");
    // The step it suggests runs, and the outcome is the default step's.
    for dt in ["0.05", "0.001"] {
        let mut args = command.to_vec();
        args.push(dt);
        let out = stdout(&whipple(&args));
        assert!(
            out.lines()
                .next()
                .is_some_and(|l| l.ends_with("non-linear simulation, completed")),
            "--dt {dt}: {out}"
        );
    }
}
