//! `whipple control lane-change`: the real binary against the library's lane changes, its
//! files, and its refusals naming the option or field.

use std::fs;
use std::path::PathBuf;

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::BenchmarkParameters;
use whipple::advanced::control::{
    HumanController, HumanGains, LaneChange, LaneKind, Neuromuscular, Task, lane_change_linear,
};

fn gains_file() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../whipple/tests/data/humancontrol/gains/BenchmarkSteerGains.txt")
        .to_string_lossy()
        .into_owned()
}

/// The CSV's columns by header name.
fn columns(text: &str) -> Vec<(String, Vec<f64>)> {
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .expect("a header")
        .split(',')
        .map(String::from)
        .collect();
    let mut values = vec![Vec::new(); header.len()];
    for line in lines {
        for (k, x) in line.split(',').enumerate() {
            values[k].push(x.parse::<f64>().expect("a number"));
        }
    }
    header.into_iter().zip(values).collect()
}

fn column<'a>(table: &'a [(String, Vec<f64>)], name: &str) -> &'a [f64] {
    &table
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("column {name}"))
        .1
}

#[test]
fn both_models_ride_the_double_lane_change_and_draw_it() {
    let dir = scratch("lane-change-both");
    let csv = dir.join("lane.csv");
    let png = dir.join("lane.png");
    let gains = gains_file();
    let out = whipple(&[
        "control",
        "lane-change",
        "--bike",
        "benchmark",
        "--gains",
        &gains,
        "--speed",
        "5",
        "--lane",
        "double",
        "--model",
        "both",
        "--out",
        csv.to_str().unwrap(),
        "--plot",
        png.to_str().unwrap(),
    ]);
    let text = stdout(&out);
    assert!(text.contains("double lane change at 5 m/s"), "{text}");
    assert!(
        text.contains("the models' front contacts differ by at most"),
        "{text}"
    );
    let table = columns(&fs::read_to_string(&csv).unwrap());
    let names: Vec<&str> = table.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "time_s",
            "path_m",
            "command_m",
            "linear_front_x_m",
            "linear_front_y_m",
            "linear_error_m",
            "linear_lean_rad",
            "linear_steer_rad",
            "linear_yaw_rad",
            "linear_steer_torque_N_m",
            "nonlinear_front_x_m",
            "nonlinear_front_y_m",
            "nonlinear_error_m",
            "nonlinear_lean_rad",
            "nonlinear_steer_rad",
            "nonlinear_yaw_rad",
            "nonlinear_steer_torque_N_m",
        ]
    );
    // The library's run, at the file's gains at 5 m/s (a tabulated speed).
    let rider = HumanController::new(
        Task::Lateral,
        HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]),
        Neuromuscular::default(),
    )
    .unwrap();
    let expected = lane_change_linear(
        &BenchmarkParameters::meijaard2007(),
        5.0,
        &rider,
        &LaneChange::humancontrol(LaneKind::Double),
    )
    .unwrap();
    assert_eq!(column(&table, "time_s").len(), 501);
    for (name, values) in [
        ("time_s", &expected.times),
        ("path_m", &expected.path),
        ("command_m", &expected.command),
        ("linear_front_y_m", &expected.front_y),
        ("linear_steer_torque_N_m", &expected.steer_torque),
    ] {
        for (a, b) in column(&table, name).iter().zip(values) {
            assert!(
                (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                "{name}: {a} vs {b}"
            );
        }
    }
    // Two metres over and back: the non-linear bicycle stays within centimetres of the
    // linear one.
    let difference = column(&table, "linear_front_y_m")
        .iter()
        .zip(column(&table, "nonlinear_front_y_m"))
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(difference > 1e-6 && difference < 0.02, "{difference}");
    let bytes = fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
}

#[test]
fn a_preset_by_name_the_single_lane_change_and_an_extrapolated_speed() {
    let dir = scratch("lane-change-single");
    let csv = dir.join("single.csv");
    let gains = gains_file();
    let out = whipple(&[
        "control",
        "lane-change",
        "--preset",
        "benchmark",
        "--gains",
        &gains,
        "--speed",
        "13",
        "--lane",
        "single",
        "--model",
        "linear",
        "--out",
        csv.to_str().unwrap(),
    ]);
    let text = stdout(&out);
    assert!(text.contains("single lane change at 13 m/s"), "{text}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("13 m/s is outside the gains file's speeds (2.5 to 12 m/s)"),
        "{stderr}"
    );
    let table = columns(&fs::read_to_string(&csv).unwrap());
    assert!(table.iter().all(|(n, _)| !n.starts_with("nonlinear")));
    let y = column(&table, "linear_front_y_m");
    assert!((y[y.len() - 1] - 2.0).abs() < 1e-3, "{}", y[y.len() - 1]);
}

#[test]
fn bad_requests_name_the_option_or_field() {
    let dir = scratch("lane-change-bad");
    let csv = dir.join("bad.csv");
    let missing = dir.join("MissingSteerGains.txt");
    fs::write(
        &missing,
        "speed,kDelta,kPhiDot,kPhi,kPsi\n5.0,46.5,-0.05,12.7,0.18\n",
    )
    .unwrap();
    let gains = gains_file();
    let run = |extra: &[&str], gains: &str| {
        let mut args = vec![
            "control",
            "lane-change",
            "--bike",
            "benchmark",
            "--gains",
            gains,
            "--out",
            csv.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        stderr_of_failure(&whipple(&args))
    };
    let err = run(&["--speed", "5"], missing.to_str().unwrap());
    assert!(err.contains("`kY`: missing column"), "{err}");
    assert!(err.contains("MissingSteerGains.txt:1"), "{err}");
    let err = run(&["--speed", "5", "--neuro-frequency", "-30"], &gains);
    assert!(
        err.contains("`neuromuscular frequency` = -30: must be positive"),
        "{err}"
    );
    let err = run(&["--speed", "0"], &gains);
    assert!(
        err.contains("--speed must be a positive finite number"),
        "{err}"
    );
    let err = run(&["--speed", "5", "--width", "0"], &gains);
    assert!(err.contains("--width must be a non-zero"), "{err}");
    assert!(!csv.exists());
}
