//! The units people use (issue 33): `_mm` and `_deg` keys in TOML and JSON files, written back
//! in the unit read; km/h after any speed argument; errors naming what was typed.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};

/// The benchmark bicycle with a designer's keys: mm, degrees, σ in mm.
const DESIGNER: &str = r#"name = "designer"
[benchmark]
w_mm = 1020
c_mm = { value = 80, sigma = 1 }
lam_deg = 18
g = 9.81
rR_mm = 300
mR = 2.0
IRxx = 0.0603
IRyy = 0.12
xB_mm = 300
zB_mm = -900
mB = 85.0
IBxx = 9.2
IByy = 11.0
IBzz = 2.8
IBxz = 2.4
xH_mm = 900
zH_mm = -700
mH = 4.0
IHxx = 0.05892
IHyy = 0.06
IHzz = 0.00708
IHxz = -0.00756
rF_mm = 350
mF = 3.0
IFxx = 0.1405
IFyy = 0.28
"#;

fn designer_file(dir: &str, text: &str) -> String {
    let path = scratch(dir).join("designer.toml");
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// The shortest text of a speed typed in km/h, in m/s: what the same run takes in m/s.
fn ms(kmh: f64) -> String {
    format!("{:?}", kmh / 3.6)
}

#[test]
fn convert_writes_keys_back_in_the_unit_read() {
    let file = designer_file("units-convert", DESIGNER);
    let toml = stdout(&whipple(&["convert", "--bike", &file, "--to", "toml"]));
    for line in [
        "w_mm = 1020.0 ",
        "c_mm = { value = 80.0, sigma = 1.0 } ",
        "lam_deg = 18.0 ",
        "xB_mm = 300.0 ",
        "zB_mm = -900.0 ",
        "mB = 85.0 ",
    ] {
        assert!(toml.contains(line), "{line} in\n{toml}");
    }
    let json = stdout(&whipple(&["convert", "--bike", &file, "--to", "json"]));
    assert!(
        json.contains("\"c_mm\": { \"value\": 80.0, \"sigma\": 1.0 }"),
        "{json}"
    );
    // The field's formats are SI.
    let txt = stdout(&whipple(&["convert", "--bike", &file, "--to", "bp-txt"]));
    assert!(txt.contains("c = 0.08+/-0.001"), "{txt}");
    // What convert wrote reads back to the same bicycle: the same critical speeds.
    let again = designer_file("units-convert-again", &toml);
    let speeds = |f: &str| stdout(&whipple(&["speeds", "--bike", f]));
    assert_eq!(speeds(&again), speeds(&file));
}

/// The same bicycle typed in SI and in the designer's units gives the same results.
#[test]
fn millimetres_and_degrees_are_the_same_bicycle() {
    let file = designer_file("units-same", DESIGNER);
    let si = DESIGNER
        .replace("w_mm = 1020", "w = 1.02")
        .replace(
            "c_mm = { value = 80, sigma = 1 }",
            "c = { value = 0.08, sigma = 0.001 }",
        )
        .replace("lam_deg = 18", &format!("lam = {:?}", 18f64.to_radians()))
        .replace("rR_mm = 300", "rR = 0.3")
        .replace("xB_mm = 300", "xB = 0.3")
        .replace("zB_mm = -900", "zB = -0.9")
        .replace("xH_mm = 900", "xH = 0.9")
        .replace("zH_mm = -700", "zH = -0.7")
        .replace("rF_mm = 350", "rF = 0.35");
    let si_file = designer_file("units-same-si", &si);
    for args in [["speeds"].as_slice(), &["eig", "--speeds", "4:6:1"]] {
        let run = |f: &str| {
            let mut a = args.to_vec();
            a.extend(["--bike", f]);
            stdout(&whipple(&a))
        };
        assert_eq!(run(&file), run(&si_file), "{args:?}");
    }
}

#[test]
fn file_keys_in_a_unit_that_does_not_fit_or_twice_are_refused() {
    for (from, to, words) in [
        (
            "IBxx = 9.2",
            "IBxx_mm = 9.2",
            "`IBxx_mm`: `IBxx` is not a length",
        ),
        (
            "lam_deg = 18",
            "lam_mm = 18",
            "`lam_mm`: `lam` is not a length",
        ),
        (
            "mB = 85.0",
            "mB_deg = 85.0",
            "`mB_deg`: `mB` is not an angle",
        ),
        (
            "g = 9.81",
            "g = 9.81\nc = 0.08",
            "give the same parameter twice",
        ),
        ("w_mm = 1020", "w_mm = nan", "w_mm"),
    ] {
        let file = designer_file("units-refused", &DESIGNER.replacen(from, to, 1));
        let err = stderr_of_failure(&whipple(&["show", "--bike", &file]));
        assert!(err.contains(words), "{to}: {err}");
    }
    // A negative radius in mm is refused by the same checks as in m.
    let file = designer_file(
        "units-negative",
        &DESIGNER.replace("rR_mm = 300", "rR_mm = -300"),
    );
    let err = stderr_of_failure(&whipple(&["show", "--bike", &file]));
    assert!(err.contains("rR"), "{err}");
}

/// km/h after any speed argument: the same run as its value in m/s (the JSON and CSV, which
/// stay in m/s; `eig`'s CSV adds its `v_kmh` column last).
#[test]
fn speeds_take_km_per_h_after_the_value() {
    let same = |kmh: &[&str], si: &[&str]| {
        assert_eq!(stdout(&whipple(kmh)), stdout(&whipple(si)), "{kmh:?}");
    };
    let (a, b) = (ms(15.0), ms(25.0));
    same(
        &[
            "speeds",
            "--bike",
            "benchmark",
            "--range",
            "15:25km/h",
            "--format",
            "json",
        ],
        &[
            "speeds",
            "--bike",
            "benchmark",
            "--range",
            &format!("{a}:{b}"),
            "--format",
            "json",
        ],
    );
    same(
        &[
            "speeds",
            "--bike",
            "benchmark",
            "--range",
            "15:km/h",
            "--format",
            "json",
        ],
        &[
            "speeds",
            "--bike",
            "benchmark",
            "--range",
            &format!("{a}:"),
            "--format",
            "json",
        ],
    );
    let (start, stop, step) = (ms(10.0), ms(30.0), ms(5.0));
    let kmh_csv = stdout(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "10:30:5km/h",
        "--format",
        "csv",
    ]));
    let si_csv = stdout(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        &format!("{start}:{stop}:{step}"),
        "--format",
        "csv",
    ]));
    let without_last = |text: &str| -> Vec<String> {
        text.lines()
            .map(|l| l.rsplit_once(',').map_or(l, |(head, _)| head).to_string())
            .collect()
    };
    assert_eq!(without_last(&kmh_csv), si_csv.lines().collect::<Vec<_>>());
    same(
        &[
            "modes",
            "--bike",
            "benchmark",
            "--speed",
            "18km/h",
            "--format",
            "json",
        ],
        &[
            "modes",
            "--bike",
            "benchmark",
            "--speed",
            &ms(18.0),
            "--format",
            "json",
        ],
    );
    same(
        &["modes", "--bike", "benchmark", "--speed", "4.6m/s"],
        &["modes", "--bike", "benchmark", "--speed", "4.6"],
    );
    same(
        &[
            "study",
            "--bike",
            "benchmark",
            "--vary",
            "trail_mm=60:100:3",
            "--range",
            "0:36km/h",
        ],
        &[
            "study",
            "--bike",
            "benchmark",
            "--vary",
            "trail_mm=60:100:3",
            "--range",
            &format!("0:{}", ms(36.0)),
        ],
    );
}

/// Speeds typed in km/h are answered in km/h too: after each m/s of `speeds` (± σ in both),
/// `sensitivity`'s base and the headings of `modes` and `response`; `eig`'s table, CSV, JSON
/// and plot against km/h; a map's band named in km/h; typed in m/s, m/s alone.
#[test]
fn speeds_typed_in_km_per_h_are_answered_in_km_per_h_too() {
    let out = |args: &[&str]| stdout(&whipple(args));
    let speeds = out(&["speeds", "--bike", "benchmark", "--range", "10:30km/h"]);
    for expected in [
        "critical speeds for 2.7777777777777777..8.333333333333334 m/s (10..30 km/h)",
        "weave speed v_w        4.292382536341103 m/s (15.4525771308 km/h)",
        "capsize speed v_c      6.024262015388365 m/s (21.6873432554 km/h)",
        "4.292382536341103 .. 6.024262015388365 m/s (15.4525771308 .. 21.6873432554 km/h)",
    ] {
        assert!(speeds.contains(expected), "{expected} in\n{speeds}");
    }
    let plain = out(&["speeds", "--bike", "benchmark", "--range", "0:10"]);
    assert!(!plain.contains("km/h"), "{plain}");
    // With σ (c ± 1 mm): the km/h rounded to its own σ, which is 3.6 times the m/s one.
    let file = designer_file("units-kmh-sigma", DESIGNER);
    let sigma = out(&["speeds", "--bike", &file, "--range", "0:40km/h"]);
    let line = sigma
        .lines()
        .find(|l| l.contains("weave speed"))
        .unwrap_or_default();
    let numbers: Vec<f64> = line
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter_map(|t| t.parse().ok())
        .collect();
    // v_w ± σ m/s (v_w ± σ km/h): the second pair 3.6 times the first, to their roundings.
    assert!(line.contains(" m/s (") && line.contains(" km/h)"), "{line}");
    assert!(
        (numbers[2] - 3.6 * numbers[0]).abs() < 0.01
            && (numbers[3] - 3.6 * numbers[1]).abs() < 0.01,
        "{line}: {numbers:?}"
    );
    let eig = out(&["eig", "--bike", "benchmark", "--speeds", "10:30:10km/h"]);
    assert!(
        eig.starts_with("benchmark: eigenvalues [1/s] against forward speed v [km/h]"),
        "{eig}"
    );
    let first: Vec<&str> = eig
        .lines()
        .nth(2)
        .unwrap_or_default()
        .split_whitespace()
        .collect();
    assert_eq!(first.first(), Some(&"10.0000"), "{eig}");
    let csv = out(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "10:30:10km/h",
        "--format",
        "csv",
    ]);
    let lines: Vec<&str> = csv.lines().collect();
    assert!(lines[0].ends_with(",im4,v_kmh"), "{csv}");
    assert!(
        lines[1].starts_with("2.7777777777777777,") && lines[1].ends_with(",10"),
        "{csv}"
    );
    assert!(lines[3].ends_with(",30"), "{csv}");
    let json: serde_json::Value = serde_json::from_str(&out(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "10:30:10km/h",
        "--format",
        "json",
    ]))
    .unwrap();
    assert_eq!(json["rows"][1]["v_kmh"], 20.0);
    assert_eq!(json["rows"][1]["v"], 20.0 / 3.6);
    let dir = scratch("units-kmh-plots");
    let plot = dir.join("eig.svg");
    whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "0:40:0.5km/h",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&plot).unwrap();
    for expected in [
        "forward speed v [km/h]",
        "v_w = 15.453 km/h",
        "15.453 – 21.687 km/h",
    ] {
        assert!(svg.contains(expected), "{expected} in the eigenvalue plot");
    }
    let modes = out(&["modes", "--bike", "benchmark", "--speed", "20km/h"]);
    assert!(
        modes.starts_with("benchmark at v = 5.555555555555555 m/s (20 km/h):"),
        "{modes}"
    );
    let base = out(&[
        "sensitivity",
        "--bike",
        "benchmark",
        "--speed",
        "18km/h",
        "--range",
        "0:72km/h",
    ]);
    assert!(
        base.contains("v_w = 4.292383 m/s (15.45258 km/h)"),
        "{base}"
    );
    assert!(base.contains("dRe_w/dp@18km/h"), "{base}");
    let bode = out(&[
        "response",
        "bode",
        "--bike",
        "benchmark",
        "--speeds",
        "10,20km/h",
        "--input",
        "steer_torque",
        "--output",
        "lean",
    ]);
    assert!(
        bode.contains("v = 2.7777777777777777 m/s (10 km/h), steer_torque → lean"),
        "{bode}"
    );
    // The other commands: the speed echoed in their headings, tables against speed in km/h.
    let lqr = out(&[
        "control",
        "lqr",
        "--bike",
        "benchmark",
        "--speed",
        "18km/h",
        "--q",
        "diag:1,1,1,1",
        "--r",
        "1",
    ]);
    assert!(
        lqr.starts_with("benchmark: LQR at v = 5 m/s (18 km/h),"),
        "{lqr}"
    );
    let hess = out(&[
        "control",
        "hess",
        "--bike",
        "benchmark",
        "--rules",
        "--speed",
        "18km/h",
    ]);
    assert!(
        hess.starts_with("benchmark at 5 m/s (18 km/h) ridden by Hess's controller"),
        "{hess}"
    );
    let table = out(&[
        "control",
        "hess",
        "--bike",
        "benchmark",
        "--rules",
        "--speeds",
        "10:20:10km/h",
    ]);
    let rows: Vec<&str> = table.lines().skip(1).take(3).collect();
    assert!(
        rows[0].starts_with("v [km/h]  stable")
            && rows[1].starts_with("10 ")
            && rows[2].starts_with("20 "),
        "{table}"
    );
    let reach = out(&[
        "control",
        "controllability",
        "--bike",
        "benchmark",
        "--speeds",
        "10:20:10km/h",
    ]);
    assert!(
        reach.contains("  v [km/h]   rank") && reach.contains("\n  20        4/4"),
        "{reach}"
    );
    let step = out(&[
        "response",
        "step",
        "--bike",
        "benchmark",
        "--speed",
        "18km/h",
        "--input",
        "steer_torque",
    ]);
    assert!(
        step.starts_with("benchmark at 5 m/s (18 km/h), linear model:"),
        "{step}"
    );
    let same = out(&[
        "control",
        "hess",
        "--bike",
        "benchmark",
        "--rules",
        "--speeds",
        "3:4:1",
    ]);
    assert!(
        same.lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("v [m/s]   stable")),
        "{same}"
    );
    let map = dir.join("map.svg");
    whipple(&[
        "map",
        "--bike",
        "benchmark",
        "--x",
        "trail=0.06:0.12:3",
        "--y",
        "head_angle_deg=70:76:3",
        "--band",
        "16:23km/h",
        "--quantity",
        "stable-over",
        "--plot",
        map.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&map).unwrap();
    assert!(
        svg.contains("16–23 km/h (inside)"),
        "the band in km/h in the map's legend"
    );
}

#[test]
fn design_axes_take_millimetres() {
    let out = stdout(&whipple(&[
        "study",
        "--bike",
        "benchmark",
        "--vary",
        "trail_mm=60:100:3",
        "--format",
        "csv",
    ]));
    assert!(
        out.contains("trail_mm") && out.contains(r#""unit":"mm""#),
        "{out}"
    );
    assert!(out.lines().any(|l| l.starts_with("1,1,80,")), "{out}");
}

#[test]
fn units_that_do_not_fit_are_refused_naming_what_was_typed() {
    for (args, words) in [
        (
            vec!["modes", "--bike", "benchmark", "--speed", "18kph"],
            "`18kph`: `kph` is not a unit of speed",
        ),
        (
            vec!["modes", "--bike", "benchmark", "--speed", "nan"],
            "`nan`: `nan` is not a finite number",
        ),
        (
            vec!["speeds", "--bike", "benchmark", "--range", "15:25mph"],
            "--range: `15:25mph`: `mph` is not a unit of speed",
        ),
        (
            vec!["eig", "--bike", "benchmark", "--speeds", "0:10:1_mm"],
            "--speeds: `0:10:1_mm`: `_mm` is not a unit of speed",
        ),
        (
            vec!["study", "--bike", "benchmark", "--vary", "trail=0:1:3km/h"],
            "`trail` is not a speed",
        ),
        (
            vec!["study", "--bike", "benchmark", "--vary", "IBxx_mm=0:1:3"],
            "`IBxx_mm`: `IBxx` is not a length",
        ),
        (
            vec!["study", "--bike", "benchmark", "--vary", "lam_mm=0:1:3"],
            "`lam_mm`: `lam` is not a length",
        ),
        (
            vec![
                "simulate",
                "--bike",
                "benchmark",
                "--speed",
                "5",
                "--duration",
                "5km/h",
            ],
            "5km/h",
        ),
    ] {
        let err = stderr_of_failure(&whipple(&args));
        assert!(err.contains(words), "{args:?}: {err}");
    }
}
