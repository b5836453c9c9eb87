//! Issue 10, messages that name the option as the user wrote it: negative numbers reach our
//! checks (not clap's "unexpected argument '-1'"), and numbers in messages are short.

mod common;

use common::{stderr_of_failure, whipple};

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
fn issue_10_negative_numbers_are_checked_and_named() {
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
fn issue_10_modes_names_speed_and_keeps_numbers_short() {
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
fn issue_10_tiny_steps_are_shown_in_scientific_notation() {
    let err = simulate_with("1e-300", &["--dt", "1e-3"]);
    assert!(err.contains("--dt") && err.contains("1e-300"), "{err}");
    assert!(err.len() < 400, "{err}");
}

/// `validate --speeds 0:1e5:0.01` was accepted and would have taken a day.
#[test]
fn issue_10_validate_refuses_sweeps_past_its_time_bound() {
    let err = stderr_of_failure(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "0:1e5:0.01",
    ]));
    assert!(err.contains("--speeds") && err.contains("minutes"), "{err}");
}
