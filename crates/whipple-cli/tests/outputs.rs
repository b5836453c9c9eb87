//! Outputs: every output is checked before the work, written whole or not at all,
//! written through symbolic links and directly into devices, never replacing something that is
//! not a regular file. The real binary, run as a user runs it.

use std::fs;

use crate::common::{read_one_line_then_close, scratch, stderr_of_failure, stdout, whipple};

const EIG: [&str; 5] = ["eig", "--bike", "benchmark", "--speeds", "0:10:0.5"];

fn eig_with(extra: &[&str]) -> std::process::Output {
    let mut args = EIG.to_vec();
    args.extend_from_slice(extra);
    whipple(&args)
}

#[test]
fn dev_full_is_an_error_naming_the_option() {
    if fs::metadata("/dev/full").is_err() {
        return; // not a Linux machine
    }
    let err = stderr_of_failure(&eig_with(&["--out", "/dev/full"]));
    assert!(err.contains("--out /dev/full"), "{err}");
    // /dev/full is still the device.
    use std::os::unix::fs::FileTypeExt;
    assert!(
        fs::metadata("/dev/full")
            .expect("/dev/full")
            .file_type()
            .is_char_device()
    );
}

#[test]
fn dev_null_is_written_in_place_and_stays_a_device() {
    use std::os::unix::fs::FileTypeExt;
    if fs::metadata("/dev/null").is_err() {
        return;
    }
    stdout(&eig_with(&["--out", "/dev/null"]));
    assert!(
        fs::metadata("/dev/null")
            .expect("/dev/null")
            .file_type()
            .is_char_device()
    );
}

#[test]
fn a_directory_as_out_is_refused_naming_out() {
    let dir = scratch("out-is-a-directory");
    let err = stderr_of_failure(&eig_with(&["--out", dir.to_str().expect("utf-8")]));
    assert!(
        err.contains("--out") && err.contains("is a directory"),
        "{err}"
    );
}

#[test]
fn a_missing_directory_is_refused_before_the_work() {
    let dir = scratch("missing-directory");
    let out = dir.join("old.csv");
    fs::write(&out, "old contents\n").expect("write");
    let plot = dir.join("no-such-dir").join("plot.svg");
    let err = stderr_of_failure(&eig_with(&[
        "--out",
        out.to_str().expect("utf-8"),
        "--plot",
        plot.to_str().expect("utf-8"),
    ]));
    assert!(
        err.contains("--plot") && err.contains("does not exist"),
        "{err}"
    );
    assert_eq!(fs::read_to_string(&out).expect("read"), "old contents\n");
}

#[test]
fn a_failing_run_leaves_the_old_file_intact() {
    let dir = scratch("failing-run");
    let out = dir.join("old.csv");
    fs::write(&out, "old contents\n").expect("write");
    // A bicycle that cannot be read fails after the outputs were checked.
    let err = stderr_of_failure(&whipple(&[
        "eig",
        "--bike",
        "no-such-bicycle.toml",
        "--speeds",
        "0:1:1",
        "--out",
        out.to_str().expect("utf-8"),
    ]));
    assert!(err.contains("no-such-bicycle"), "{err}");
    assert_eq!(fs::read_to_string(&out).expect("read"), "old contents\n");
    // No temporary file is left beside it.
    let names: Vec<_> = fs::read_dir(&dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("old.csv")]);
}

#[test]
fn a_symlink_stays_a_link_and_its_target_is_written() {
    let dir = scratch("symlink-out");
    let real = dir.join("real.csv");
    fs::write(&real, "old\n").expect("write");
    let link = dir.join("link.csv");
    std::os::unix::fs::symlink("real.csv", &link).expect("symlink");
    stdout(&eig_with(&[
        "--format",
        "csv",
        "--out",
        link.to_str().expect("utf-8"),
    ]));
    assert!(
        fs::symlink_metadata(&link)
            .expect("link")
            .file_type()
            .is_symlink()
    );
    let text = fs::read_to_string(&real).expect("read");
    assert!(text.starts_with("v,re1,im1"), "{text}");
}

#[test]
fn a_replaced_file_keeps_its_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("permissions");
    let out = dir.join("eig.csv");
    fs::write(&out, "old\n").expect("write");
    fs::set_permissions(&out, fs::Permissions::from_mode(0o640)).expect("chmod");
    stdout(&eig_with(&["--out", out.to_str().expect("utf-8")]));
    let mode = fs::metadata(&out).expect("meta").permissions().mode() & 0o777;
    assert_eq!(mode, 0o640);
}

#[test]
fn out_and_plot_naming_one_file_are_refused() {
    let dir = scratch("same-file");
    let path = dir.join("x.svg");
    let p = path.to_str().expect("utf-8");
    let err = stderr_of_failure(&eig_with(&["--out", p, "--plot", p]));
    assert!(err.contains("name the same file"), "{err}");
    assert!(!path.exists());
}

/// `validate --report` left a CSV and six PNGs behind when `summary.md` could not be written.
#[test]
fn validate_report_is_whole_or_not_at_all() {
    let dir = scratch("partial-report");
    let report = dir.join("report");
    fs::create_dir_all(report.join("summary.md")).expect("a directory in the way");
    let err = stderr_of_failure(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "4:5:0.5",
        "--report",
        report.to_str().expect("utf-8"),
    ]));
    assert!(
        err.contains("--report") && err.contains("summary.md"),
        "{err}"
    );
    let names: Vec<_> = fs::read_dir(&report)
        .expect("list")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("summary.md")]);
}

/// A report directory the command created is removed again when the command fails.
#[test]
fn validate_report_into_a_missing_parent_is_refused_before_the_work() {
    let dir = scratch("report-missing-parent");
    let report = dir.join("a").join("b");
    let err = stderr_of_failure(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "4:5:0.5",
        "--report",
        report.to_str().expect("utf-8"),
    ]));
    assert!(
        err.contains("--report") && err.contains("does not exist"),
        "{err}"
    );
    assert!(!dir.join("a").exists());
}

/// `simulate --duration 1e-4 --dt 1e-12` was accepted (1e8 steps) and grew towards ~25 GB: now
/// refused by the bound on the work, which the message states in minutes.
#[test]
fn simulate_refuses_runs_past_the_work_bound() {
    let err = stderr_of_failure(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--duration",
        "1e-4",
        "--dt",
        "1e-12",
    ]));
    assert!(err.contains("--dt") && err.contains("minutes"), "{err}");
}

/// 2000 s at 1 ms keeps 2·10⁶ samples, past the memory bound: refused naming `--every` and
/// the thinning that fits; with `--every 2` the same run is within it (checked, not run).
#[test]
fn simulate_keeps_at_most_the_memory_bound_of_samples() {
    let err = stderr_of_failure(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--duration",
        "2000",
    ]));
    assert!(
        err.contains("--every") && err.contains("GiB") && err.contains("one sample in 2 steps"),
        "{err}"
    );
    let err = stderr_of_failure(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--duration",
        "1",
        "--every",
        "0",
    ]));
    assert!(err.contains("--every must be at least 1"), "{err}");
}

/// `--every N` keeps the first sample, one in N steps and the last, in every format; the
/// summary's extremes are over every step (the same as an unthinned run's).
#[test]
fn simulate_every_thins_the_samples() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "simulate",
            "--bike",
            "benchmark",
            "--speed",
            "5",
            "--lean-rate",
            "0.5",
            "--duration",
            "2.0005",
            "--dt",
            "0.001",
        ];
        args.extend_from_slice(extra);
        stdout(&whipple(&args))
    };
    let all = run(&["--format", "csv"]);
    let thin = run(&["--format", "csv", "--every", "100"]);
    let rows = |text: &str| -> Vec<String> { text.lines().skip(1).map(str::to_string).collect() };
    let (all, thin) = (rows(&all), rows(&thin));
    assert_eq!(all.len(), 2002, "2001 steps and the start");
    // Steps 0, 100, …, 2000 and the last (2001).
    assert_eq!(thin.len(), 22);
    for (k, row) in thin.iter().take(21).enumerate() {
        assert_eq!(row, &all[100 * k], "sample {k}");
    }
    assert_eq!(thin.last(), all.last());
    let json = run(&["--format", "json", "--every", "100"]);
    let doc: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    assert_eq!(doc["sample_every"], 100);
    assert_eq!(doc["steps"], 2001);
    assert_eq!(doc["samples"].as_array().map(Vec::len), Some(22));
    let summary = |text: &str| text.lines().nth(1).unwrap_or_default().to_string();
    let table_all = run(&[]);
    let table_thin = run(&["--every", "100"]);
    assert_eq!(summary(&table_all), summary(&table_thin));
    assert!(
        table_thin.contains("22 samples kept, one in 100 steps"),
        "{table_thin}"
    );
}

/// `whipple eig ... --plot eig.png | head -1` and the same for `simulate`: the table's reader
/// going away ends only the table; the plot is still drawn and put in place.
#[test]
fn a_closed_stdout_still_writes_the_plot() {
    let dir = scratch("closed-stdout-plot");
    for (name, args) in [
        (
            "eig.png",
            vec!["eig", "--bike", "benchmark", "--speeds", "0:100:0.0005"],
        ),
        (
            "simulate.png",
            vec![
                "simulate",
                "--bike",
                "benchmark",
                "--speed",
                "5",
                "--duration",
                "20",
                "--format",
                "csv",
            ],
        ),
    ] {
        let plot = dir.join(name);
        let mut args: Vec<&str> = args;
        args.extend(["--plot", plot.to_str().expect("utf-8")]);
        let output = read_one_line_then_close(&args);
        let err = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{name}: {err}");
        let bytes = fs::read(&plot).unwrap_or_default();
        assert!(
            bytes.starts_with(b"\x89PNG"),
            "{name}: no plot written ({err})"
        );
    }
}

/// `simulate --out` and `--plot` are checked before the run and land together.
#[test]
fn simulate_checks_its_outputs_before_the_run() {
    let dir = scratch("simulate-outputs");
    let out = dir.join("run.csv");
    let err = stderr_of_failure(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--duration",
        "0.1",
        "--out",
        out.to_str().expect("utf-8"),
        "--plot",
        dir.to_str().expect("utf-8"),
    ]));
    assert!(err.contains("--plot"), "{err}");
    assert!(!out.exists());
}

/// `whipple eig ... | head -1`: the reader going away ends the run quietly, with success.
#[test]
fn a_closed_stdout_ends_quietly() {
    let output =
        read_one_line_then_close(&["eig", "--bike", "benchmark", "--speeds", "0:1000:0.001"]);
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{err}");
    assert!(err.is_empty(), "{err}");
}

/// The designer's question "self-stable from A to B?" (`--band`): the benchmark bicycle (its
/// self-stable range 4.292… to 6.024… m/s, Meijaard et al. 2007) is self-stable over 4.5 to
/// 5.5 m/s with those margins and not over 4 to 8; a sharded map with a band merges to the
/// whole map bit for bit and draws the qualifying designs.
#[test]
fn a_band_answers_whether_each_design_is_self_stable_over_it() {
    let (v_w, v_c) = (4.29238253634111, 6.02426201538837);
    let row_of = |band: &str| -> Vec<String> {
        let csv = stdout(&whipple(&[
            "study",
            "--bike",
            "benchmark",
            "--vary",
            "trail=0.08:0.08:1",
            "--band",
            band,
        ]));
        let mut lines = csv.lines().skip(1);
        let header: Vec<&str> = lines.next().expect("header").split(',').collect();
        let row: Vec<&str> = lines.next().expect("a row").split(',').collect();
        ["stable_over", "band_margin_below", "band_margin_above"]
            .iter()
            .map(|name| {
                let k = header.iter().position(|h| h == name).expect("the column");
                row[k].to_string()
            })
            .collect()
    };
    let inside = row_of("4.5:5.5");
    assert_eq!(inside[0], "1");
    let below: f64 = inside[1].parse().expect("a margin below");
    let above: f64 = inside[2].parse().expect("a margin above");
    assert!((below - (4.5 - v_w)).abs() < 1e-12, "{below}");
    assert!((above - (v_c - 5.5)).abs() < 1e-12, "{above}");
    assert_eq!(row_of("4:8"), ["0", "", ""]);

    // Without a band the columns are as they were.
    let plain = stdout(&whipple(&[
        "study",
        "--bike",
        "benchmark",
        "--vary",
        "trail=0:0.1:2",
    ]));
    assert!(
        !plain.contains("stable_over") && !plain.contains("band"),
        "{plain}"
    );

    let dir = scratch("band-shards");
    let map = |extra: &[&str]| {
        let mut args = vec![
            "map",
            "--bike",
            "benchmark",
            "--x",
            "trail=0:0.2:21",
            "--y",
            "w=0.9:1.2:13",
            "--band",
            "4.5:5.5",
        ];
        args.extend_from_slice(extra);
        stdout(&whipple(&args))
    };
    let whole = map(&[]);
    let mut shards = Vec::new();
    for k in 0..3 {
        let path = dir.join(format!("shard-{k}.csv"));
        let shard = format!("{k}/3");
        map(&["--shard", &shard, "--out", path.to_str().expect("utf-8")]);
        shards.push(path.to_str().expect("utf-8").to_string());
    }
    let png = dir.join("band.png");
    let mut args = vec!["merge"];
    args.extend(shards.iter().map(String::as_str));
    args.extend([
        "--quantity",
        "stable-over",
        "--plot",
        png.to_str().expect("utf-8"),
    ]);
    assert_eq!(stdout(&whipple(&args)), whole);
    assert!(fs::metadata(&png).expect("the plot").len() > 10_000);
    assert!(
        whole.lines().skip(2).any(|l| l.contains(",1,")),
        "no design qualifies"
    );

    // stable-over without a band is refused before any work.
    let err = stderr_of_failure(&whipple(&[
        "map",
        "--bike",
        "benchmark",
        "--x",
        "trail=0:0.2:3",
        "--y",
        "w=1:1.1:2",
        "--quantity",
        "stable-over",
    ]));
    assert!(err.contains("--band"), "{err}");
}
