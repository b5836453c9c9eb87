//! The real binary, run as a user runs it.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple_reference::meijaard2007 as published;

#[test]
fn presets_lists_every_preset_with_its_source() {
    let out = stdout(&whipple(&["presets"]));
    for name in [
        "benchmark",
        "schwinn-crown",
        "two-mass-skate",
        "browser-jason",
    ] {
        assert!(out.contains(name), "{out}");
    }
    assert!(out.contains("doi:10.1098/rspa.2007.1857"));
}

/// Meijaard et al. 2007, Table 2, at 5 m/s, through the CSV output.
#[test]
fn eig_csv_has_the_documented_header_and_published_values() {
    let out = stdout(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "0:10:0.5",
        "--format",
        "csv",
    ]));
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("v,re1,im1,re2,im2,re3,im3,re4,im4"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().expect("a number")).collect())
        .collect();
    assert_eq!(rows.len(), 21);
    let at5 = &rows[10];
    assert_eq!(at5[0], 5.0);
    // Meijaard et al. 2007, Table 2, at 5 m/s.
    let (v, weave_re, weave_im, capsize, castering) = published::EIGENVALUES[4];
    assert_eq!(v, 5.0);
    assert!((at5[1] - weave_re).abs() < 1e-12);
    assert!((at5[2] - weave_im).abs() < 1e-12);
    assert!((at5[5] - capsize).abs() < 1e-12);
    assert!((at5[7] - castering).abs() < 1e-12);
}

#[test]
fn eig_json_labels_the_modes() {
    let out = stdout(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "1:2:1",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    assert_eq!(
        doc["modes"],
        serde_json::json!(["weave", "weave", "capsize", "castering"])
    );
    assert_eq!(doc["rows"].as_array().map(Vec::len), Some(2));
}

/// Meijaard et al. 2007, Table 2: v_d, v_w, v_c through the JSON output, with exactly the
/// documented keys.
#[test]
fn speeds_json_has_the_documented_keys() {
    let out = stdout(&whipple(&[
        "speeds",
        "--bike",
        "benchmark",
        "--range",
        "0:10",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    let keys: Vec<&str> = doc
        .as_object()
        .expect("an object")
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        keys,
        [
            "bike",
            "capsize_speed",
            "crossings",
            "double_root_eigenvalue",
            "double_root_speed",
            "range",
            "stable_speed_ranges",
            "unresolved",
            "warnings",
            "weave_frequency",
            "weave_speed"
        ]
    );
    let get = |k: &str| doc[k].as_f64().expect("a number");
    assert!((get("double_root_speed") - published::DOUBLE_ROOT_SPEED).abs() < 1e-12);
    assert!((get("weave_speed") - published::WEAVE_SPEED).abs() < 1e-12);
    assert!((get("capsize_speed") - published::CAPSIZE_SPEED).abs() < 1e-12);
    assert_eq!(doc["stable_speed_ranges"].as_array().map(Vec::len), Some(1));
}

#[test]
fn speeds_says_none_where_a_speed_is_outside_the_range() {
    let out = stdout(&whipple(&[
        "speeds",
        "--bike",
        "benchmark",
        "--range",
        "0:5",
    ]));
    assert!(
        out.contains("capsize speed v_c      none in 0..5 m/s"),
        "{out}"
    );
    let json = stdout(&whipple(&[
        "speeds",
        "--bike",
        "benchmark",
        "--range",
        "0:4",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    assert!(doc["weave_speed"].is_null() && doc["capsize_speed"].is_null());
    assert_eq!(doc["stable_speed_ranges"], serde_json::json!([]));
}

#[test]
fn matrices_in_jbike6_convention_flip_the_steer_sign_and_carry_g() {
    let bench = stdout(&whipple(&[
        "matrices",
        "--bike",
        "benchmark",
        "--format",
        "json",
    ]));
    let jb = stdout(&whipple(&[
        "matrices",
        "--bike",
        "benchmark",
        "--jbike6",
        "--format",
        "json",
    ]));
    let b: serde_json::Value = serde_json::from_str(&bench).expect("JSON");
    let j: serde_json::Value = serde_json::from_str(&jb).expect("JSON");
    let m01 = b["M"][0][1].as_f64().expect("a number");
    assert!((m01 - 2.31941332208709).abs() < 1e-13, "{m01}");
    assert_eq!(j["M0"][0][1].as_f64(), b["M"][0][1].as_f64().map(|x| -x));
    let k0 = j["K0"][0][0].as_f64().expect("a number");
    assert!((k0 + 80.95 * 9.81).abs() < 1e-12, "{k0}");
}

#[test]
fn show_gives_both_forms_of_a_jbike6_bike() {
    let out = stdout(&whipple(&["show", "--bike", "schwinn-crown"]));
    assert!(out.contains("JBike6 form") && out.contains("Benchmark form"));
    assert!(out.contains("mrider") && out.contains("mB"));
}

/// A bike converted to TOML and JSON, and kept in JBike6 form as a .m file, reads back with
/// the same critical speeds.
#[test]
fn converted_files_read_back_with_the_same_results() {
    let dir = scratch("convert");
    let reference = stdout(&whipple(&[
        "speeds",
        "--bike",
        "schwinn-crown",
        "--format",
        "json",
    ]));
    for (to, name, keep) in [
        ("toml", "crown.toml", false),
        ("json", "crown.json", false),
        ("m", "crown.m", true),
        ("toml", "crown-jbike6.toml", true),
    ] {
        let path = dir.join(name);
        let path_text = path.to_string_lossy().into_owned();
        let mut args = vec![
            "convert",
            "--bike",
            "schwinn-crown",
            "--to",
            to,
            "--out",
            &path_text,
        ];
        if keep {
            args.push("--keep-form");
        }
        stdout(&whipple(&args));
        let again = stdout(&whipple(&[
            "speeds", "--bike", &path_text, "--format", "json",
        ]));
        if to == "m" {
            // The .m layout prints 8 decimals, as JBike6 does: equal to that precision.
            let a: serde_json::Value = serde_json::from_str(&again).expect("JSON");
            let r: serde_json::Value = serde_json::from_str(&reference).expect("JSON");
            let (x, y) = (a["capsize_speed"].as_f64(), r["capsize_speed"].as_f64());
            assert!((x.unwrap_or(0.0) - y.unwrap_or(1.0)).abs() < 1e-7);
        } else {
            assert_eq!(again, reference, "{name}");
        }
    }
}

#[test]
fn a_syntax_error_names_the_file_line_and_column() {
    let dir = scratch("syntax");
    let path = dir.join("bad.toml");
    std::fs::write(&path, "[benchmark]\nw = 1.02\nc = = 0.08\n").expect("write");
    let err = stderr_of_failure(&whipple(&["speeds", "--bike", &path.to_string_lossy()]));
    assert!(err.contains("bad.toml:3:5"), "{err}");
    assert!(err.contains("c = = 0.08"), "{err}");
}

#[test]
fn an_invalid_parameter_is_named_with_its_value_and_rule() {
    let dir = scratch("invalid");
    let path = dir.join("heavy.toml");
    let text = stdout(&whipple(&[
        "convert",
        "--bike",
        "benchmark",
        "--to",
        "toml",
    ]))
    .replace("mB = 85.0", "mB = -85.0");
    std::fs::write(&path, text).expect("write");
    let err = stderr_of_failure(&whipple(&["eig", "--bike", &path.to_string_lossy()]));
    assert!(
        err.contains("`mB` = -85") && err.contains("negative"),
        "{err}"
    );
}

#[test]
fn unknown_presets_and_bad_options_fail_with_a_message() {
    let err = stderr_of_failure(&whipple(&["eig", "--bike", "penny-farthing"]));
    assert!(
        err.contains("unknown preset") && err.contains("benchmark"),
        "{err}"
    );
    let err = stderr_of_failure(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "0:10:0",
    ]));
    assert!(err.contains("--speeds") && err.contains("STEP"), "{err}");
    let err = stderr_of_failure(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "0:x:1",
    ]));
    assert!(
        err.contains("--speeds") && err.contains("not a number"),
        "{err}"
    );
    let err = stderr_of_failure(&whipple(&[
        "speeds",
        "--bike",
        "benchmark",
        "--range",
        "5:1",
    ]));
    assert!(err.contains("--range"), "{err}");
    let err = stderr_of_failure(&whipple(&["speeds", "--bike", "missing-file.toml"]));
    assert!(err.contains("missing-file.toml"), "{err}");
}

#[test]
fn no_file_is_left_behind_when_writing_fails() {
    let dir = scratch("atomic");
    let target = dir.join("no-such-dir").join("eig.csv");
    let err = stderr_of_failure(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--format",
        "csv",
        "--out",
        &target.to_string_lossy(),
    ]));
    assert!(err.contains("does not exist"), "{err}");
    assert_eq!(std::fs::read_dir(&dir).map(|d| d.count()).unwrap_or(0), 0);
}

#[test]
fn modes_gives_labelled_eigenvalues_and_shapes() {
    let out = stdout(&whipple(&[
        "modes",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    let modes: Vec<&str> = doc["modes"]
        .as_array()
        .expect("a list")
        .iter()
        .map(|m| m["mode"].as_str().expect("a label"))
        .collect();
    assert_eq!(modes, ["capsize", "weave", "weave", "castering"]);
    let capsize = doc["modes"][0]["eigenvalue"][0].as_f64().expect("a number");
    assert!((capsize + 0.32286642900409).abs() < 1e-12);
    let table = stdout(&whipple(&["modes", "--bike", "benchmark", "--speed", "5"]));
    assert!(table.contains("period 1.4073 s"), "{table}");
    let err = stderr_of_failure(&whipple(&[
        "modes",
        "--bike",
        "benchmark",
        "--speed",
        "nan",
    ]));
    assert!(err.contains("--speed"), "{err}");
}

#[test]
fn plots_and_drawings_are_written_as_svg_or_png() {
    let dir = scratch("figures");
    let svg = dir.join("eig.svg");
    let png = dir.join("crown.png");
    stdout(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "0:10:0.05",
        "--plot",
        &svg.to_string_lossy(),
    ]));
    let text = std::fs::read_to_string(&svg).expect("the plot was written");
    assert!(text.starts_with("<svg") || text.contains("<svg"));
    for label in ["weave", "capsize", "castering", "4.292"] {
        assert!(text.contains(label), "the plot shows {label}");
    }
    stdout(&whipple(&[
        "draw",
        "--bike",
        "schwinn-crown",
        "--out",
        &png.to_string_lossy(),
    ]));
    let bytes = std::fs::read(&png).expect("the drawing was written");
    assert_eq!(&bytes[1..4], b"PNG");
    let bad = dir.join("eig.gif");
    let err = stderr_of_failure(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--plot",
        &bad.to_string_lossy(),
    ]));
    assert!(err.contains("eig.gif"), "{err}");
    assert!(!bad.exists());
}

/// The benchmark bicycle in the non-linear simulation: at 4.6 m/s (inside the self-stable range
/// 4.29–6.02 m/s) a lean-rate kick dies out as a decaying weave.
#[test]
fn simulate_shows_the_weave_decaying_inside_the_stable_range() {
    let dir = scratch("simulate");
    let csv_path = dir.join("run.csv");
    let plot = dir.join("run.svg");
    let out = whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "4.6",
        "--lean-rate",
        "0.5",
        "--duration",
        "10",
        "--format",
        "csv",
        "--out",
        &csv_path.to_string_lossy(),
        "--plot",
        &plot.to_string_lossy(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv_path).expect("the samples were written");
    let mut lines = text.lines();
    let header = lines.next().expect("a header");
    assert!(header.starts_with("t,lean,steer,lean_rate,steer_rate,yaw,x,y,speed,energy,"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().expect("a number")).collect())
        .collect();
    assert_eq!(rows.len(), 10_001);
    let first_second = rows[..1000].iter().map(|r| r[1].abs()).fold(0.0, f64::max);
    let last_second = rows[9000..].iter().map(|r| r[1].abs()).fold(0.0, f64::max);
    assert!(
        last_second < 0.1 * first_second,
        "{first_second} -> {last_second}"
    );
    let e0 = rows[0][9];
    assert!(
        rows.iter().all(|r| (r[9] - e0).abs() < 1e-6),
        "energy is conserved"
    );
    assert!(
        std::fs::read_to_string(&plot)
            .expect("plot")
            .contains("<svg")
    );
}

/// At 3 m/s, below the weave speed, the same kick grows until the bicycle falls.
#[test]
fn simulate_reports_a_fall_as_an_outcome() {
    let out = stdout(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "3",
        "--lean-rate",
        "0.5",
        "--duration",
        "10",
        "--ignore-lift-off",
    ]));
    assert!(out.contains("fell: |lean| passed the fall angle"), "{out}");
    let out = stdout(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "3",
        "--lean-rate",
        "0.5",
        "--duration",
        "10",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    assert!(
        doc["outcome"].as_str().unwrap_or("").contains("falling"),
        "{}",
        doc["outcome"]
    );
}

#[test]
fn simulate_takes_rider_torques_as_expressions() {
    let out = stdout(&whipple(&[
        "simulate",
        "--bike",
        "schwinn-crown",
        "--speed",
        "6",
        "--steer-torque",
        "0.5*sin(2*t)",
        "--duration",
        "2",
        "--integrator",
        "adaptive",
        "--rtol",
        "1e-9",
    ]));
    assert!(
        out.contains("completed") && out.contains("torques do work"),
        "{out}"
    );
}

#[test]
fn simulate_refuses_bad_options_by_name() {
    let cases: [(&[&str], &str); 9] = [
        (
            &["--speed", "5", "--duration", "1", "--lean", "90"],
            "--lean",
        ),
        (&["--speed", "5", "--duration", "1", "--dt", "0"], "--dt"),
        (&["--speed", "5", "--duration", "1", "--dt", "5"], "--dt"),
        (&["--speed", "5", "--duration", "-1"], "--duration"),
        (&["--speed", "nan", "--duration", "1"], "--speed"),
        (
            &["--speed", "5", "--duration", "1", "--steer-torque", "sin(t"],
            "--steer-torque",
        ),
        (
            &["--speed", "5", "--duration", "1", "--steer-torque", "2*foo"],
            "unknown name `foo`",
        ),
        (
            &[
                "--speed",
                "5",
                "--duration",
                "1",
                "--integrator",
                "adaptive",
                "--dt",
                "0.01",
            ],
            "--dt",
        ),
        (
            &["--speed", "5", "--duration", "1", "--rtol", "1e-6"],
            "--rtol",
        ),
    ];
    for (extra, expected) in cases {
        let mut args = vec!["simulate", "--bike", "benchmark"];
        args.extend_from_slice(extra);
        let err = stderr_of_failure(&whipple(&args));
        assert!(err.contains(expected), "{extra:?}: {err}");
    }
}

/// `whipple eig ... | head`: a reader that goes away early is not a failure, and never a panic.
#[test]
fn a_closed_output_pipe_ends_the_run_quietly() {
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_whipple"))
        .args([
            "eig",
            "--bike",
            "benchmark",
            "--speeds",
            "0:10:0.0001",
            "--format",
            "csv",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the whipple binary runs");
    drop(child.stdout.take()); // the reader goes away before reading anything
    let output = child.wait_with_output().expect("it ends");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(output.status.success(), "{stderr}");
}
