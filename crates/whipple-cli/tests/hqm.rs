//! `whipple control hqm` through the real binary: HumanControl's benchmark bicycle and gains,
//! one speed and a speed sweep, the figures, and bad input.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::advanced::control::{HandlingQuality, Neuromuscular};
use whipple::advanced::io::{Format, parse, read_gains};

const DATA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../whipple/tests/data/humancontrol"
);

fn path(name: &str) -> String {
    format!("{DATA}/{name}")
}

fn number_after(text: &str, prefix: &str) -> f64 {
    let rest = &text[text.find(prefix).expect(prefix) + prefix.len()..];
    rest.split_whitespace()
        .next()
        .expect("a number")
        .parse()
        .expect("a number")
}

/// The library's peak for HumanControl's benchmark at `v` with its tabulated gains.
fn library_peak(v: f64) -> (f64, f64) {
    let text = std::fs::read_to_string(path("BenchmarkPar.txt")).expect("the bicycle");
    let bike = parse(&text, Format::HumanControlTxt)
        .expect("parsed")
        .benchmark()
        .expect("checked");
    let table = read_gains(
        &std::fs::read_to_string(path("gains/BenchmarkSteerGains.txt")).expect("the gains"),
    )
    .expect("read");
    let gains = table.at(v).expect("looked up").gains;
    let peak = HandlingQuality::new(&bike, v, &gains, &Neuromuscular::default())
        .expect("formed")
        .peak()
        .expect("certified");
    (peak.magnitude, peak.frequency)
}

#[test]
fn peak_hqm_of_humancontrols_benchmark_at_one_speed_with_its_figure() {
    let dir = scratch("hqm-one");
    let plot = dir.join("hqm.svg");
    let out = stdout(&whipple(&[
        "control",
        "hqm",
        "--bike",
        &path("BenchmarkPar.txt"),
        "--gains",
        &path("gains/BenchmarkSteerGains.txt"),
        "--speed",
        "5",
        "--plot",
        plot.to_str().expect("a UTF-8 path"),
    ]));
    let (peak, omega) = library_peak(5.0);
    assert!(
        (number_after(&out, "peak HQM = ") - peak).abs() < 1e-6,
        "{out}"
    );
    assert!(
        (number_after(&out, "at ω = ") - omega).abs() < 1e-6,
        "{out}"
    );
    assert!(out.contains("(certified)"), "{out}");
    assert!(out.contains("BenchmarkSteerGains.txt, tabulated"), "{out}");
    assert!(out.contains("roll loop: stable"), "{out}");
    let svg = std::fs::read_to_string(&plot).expect("the figure was written");
    assert!(svg.contains("|HQM(jω)|") && svg.contains("frequency ω [rad/s]"));
}

#[test]
fn peak_hqm_against_speed_as_json_with_its_figure() {
    let dir = scratch("hqm-speeds");
    let plot = dir.join("peaks.png");
    let out = stdout(&whipple(&[
        "control",
        "hqm",
        "--bike",
        &path("BenchmarkPar.txt"),
        "--gains",
        &path("gains/BenchmarkSteerGains.txt"),
        "--speeds",
        "3:8:1",
        "--format",
        "json",
        "--plot",
        plot.to_str().expect("a UTF-8 path"),
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let rows = doc["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 6);
    let five = &rows[2];
    assert_eq!(five["speed"], 5.0);
    assert_eq!(five["gains_lookup"], "tabulated");
    assert_eq!(rows[0]["gains_lookup"], "interpolated");
    let (peak, _) = library_peak(5.0);
    assert!((five["peak"].as_f64().expect("a number") - peak).abs() < 1e-12);
    let png = std::fs::read(&plot).expect("the figure was written");
    assert!(png.starts_with(b"\x89PNG"));
}

#[test]
fn peak_hqm_against_trail_at_one_speed() {
    let out = stdout(&whipple(&[
        "control",
        "hqm",
        "--bike",
        &path("BenchmarkPar.txt"),
        "--gains",
        &path("gains/BenchmarkSteerGains.txt"),
        "--speed",
        "5",
        "--vary",
        "c=0.04:0.12:5",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let rows = doc["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 5);
    // The file's own trail (c = 0.08) gives the one-speed peak.
    // (The axis's grid value, 0.08 to the last bit or one below it.)
    assert!((rows[2]["value"].as_f64().expect("a number") - 0.08).abs() <= 2e-17);
    let (peak, _) = library_peak(5.0);
    assert!((rows[2]["peak"].as_f64().expect("a number") - peak).abs() < 1e-12);
    assert!(rows[0]["peak"] != rows[4]["peak"]);
    let err = stderr_of_failure(&whipple(&[
        "control",
        "hqm",
        "--bike",
        &path("BenchmarkPar.txt"),
        "--gains",
        &path("gains/BenchmarkSteerGains.txt"),
        "--speed",
        "5",
        "--vary",
        "nonsense=0:1:3",
    ]));
    assert!(err.contains("--vary") && err.contains("nonsense"), "{err}");
}

#[test]
fn bad_input_is_refused_naming_the_option_or_field() {
    let dir = scratch("hqm-bad");
    let bike = path("BenchmarkPar.txt");
    let gains = path("gains/BenchmarkSteerGains.txt");
    let err = stderr_of_failure(&whipple(&[
        "control",
        "hqm",
        "--bike",
        &bike,
        "--gains",
        &gains,
        "--speed",
        "5",
        "--neuro-frequency",
        "-30",
    ]));
    assert!(err.contains("`neuromuscular frequency` = -30"), "{err}");
    let err = stderr_of_failure(&whipple(&[
        "control", "hqm", "--bike", &bike, "--gains", &gains,
    ]));
    assert!(err.contains("give --speed V or --speeds"), "{err}");
    let missing = dir.join("MissingSteerGains.txt");
    std::fs::write(
        &missing,
        "speed,kDelta,kPhiDot,kPhi,kPsi\n5.0,46.5,-0.05,12.7,0.18\n",
    )
    .expect("written");
    let err = stderr_of_failure(&whipple(&[
        "control",
        "hqm",
        "--bike",
        &bike,
        "--gains",
        missing.to_str().expect("a UTF-8 path"),
        "--speed",
        "5",
    ]));
    assert!(err.contains("--gains") && err.contains("kY"), "{err}");
    // Outside the table: computed, and the extrapolation said.
    let output = whipple(&[
        "control", "hqm", "--bike", &bike, "--gains", &gains, "--speed", "13",
    ]);
    assert!(output.status.success());
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(err.contains("extrapolated"), "{err}");
}
