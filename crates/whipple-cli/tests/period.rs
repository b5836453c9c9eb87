//! `whipple period` through the real binary: BicycleParameters' sample record, a CSV record,
//! the figure, and bad input.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};

const SAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../whipple/tests/data/measured/periods/BrowserForkCompoundFirst1.mat"
);

fn number_after<'a>(text: &'a str, prefix: &str) -> f64 {
    let rest = &text[text.find(prefix).expect(prefix) + prefix.len()..];
    let word: &'a str = rest.split_whitespace().next().expect("a number");
    word.parse().expect("a number")
}

/// BicycleParameters 1.5.2's fit of its sample record, trimmed as it trims (the numbers:
/// `crates/whipple/tests/data/measured/periods/README.md`).
#[test]
fn period_of_bicycleparameters_sample_record() {
    let dir = scratch("period-sample");
    let plot = dir.join("fit.svg");
    let out = stdout(&whipple(&[
        "period",
        SAMPLE,
        "--trim",
        "0.1",
        "--plot",
        plot.to_str().expect("a UTF-8 path"),
    ]));
    let period = number_after(&out, "period T = ");
    assert!((period - 1.5903143948411882).abs() < 2e-9, "{out}");
    assert!(out.contains("± 1.222e-5 s"), "{out}");
    assert!(out.contains("samples 3 to 29696 of 30000"), "{out}");
    let zeta = number_after(&out, "damping ratio ζ = ");
    assert!((zeta - 0.00890250531186835).abs() < 1e-8, "{out}");
    let svg = std::fs::read_to_string(&plot).expect("the figure was written");
    assert!(svg.contains("fitted decaying oscillation") && svg.contains("time t [s]"));
}

#[test]
fn period_of_a_csv_record_by_column_name() {
    let dir = scratch("period-csv");
    let path = dir.join("swing.csv");
    let rows: String = (0..1000)
        .map(|i| {
            let t = i as f64 * 0.005;
            format!(
                "{t},{}\n",
                2.0 + whipple::math::exp(-0.1 * t) * whipple::math::sin(5.0 * t)
            )
        })
        .collect();
    std::fs::write(&path, format!("t,rate gyro\n{rows}")).expect("written");
    let out = stdout(&whipple(&[
        "period",
        path.to_str().expect("a UTF-8 path"),
        "--column",
        "rate gyro",
    ]));
    let period = number_after(&out, "period T = ");
    assert!((period - std::f64::consts::TAU / 5.0).abs() < 1e-9, "{out}");
    assert!(
        out.contains("signal rate gyro, time from t; 1000 samples"),
        "{out}"
    );
}

#[test]
fn bad_records_fail_with_a_message() {
    let e = stderr_of_failure(&whipple(&["period", SAMPLE, "--column", "x"]));
    assert!(e.contains("the .mat has no numeric variable 'x'"), "{e}");
    let e = stderr_of_failure(&whipple(&["period", SAMPLE, "--trim", "2"]));
    assert!(e.contains("--trim") && e.contains("trim"), "{e}");
    let e = stderr_of_failure(&whipple(&["period", SAMPLE, "--plot", "fit.txt"]));
    assert!(e.contains("--plot"), "{e}");
    let e = stderr_of_failure(&whipple(&["period", "no-such-record.csv"]));
    assert!(e.contains("no-such-record.csv"), "{e}");
    let dir = scratch("period-flat");
    let flat = dir.join("flat.csv");
    let rows: String = (0..100).map(|i| format!("{i},1\n")).collect();
    std::fs::write(&flat, rows).expect("written");
    let e = stderr_of_failure(&whipple(&["period", flat.to_str().expect("UTF-8")]));
    assert!(e.contains("no oscillation found"), "{e}");
}
