//! `whipple validate`, the real binary: the CSV header and values, JSON, the report directory.

use crate::common::{scratch, stdout, whipple};

const LIN: &str = "v,lin_re1,lin_im1,lin_re2,lin_im2,lin_re3,lin_im3,lin_re4,lin_im4";

fn method_columns(m: &str) -> String {
    let mut s = String::new();
    for k in 1..=4 {
        s.push_str(&format!(",{m}_re{k},{m}_im{k}"));
    }
    s.push_str(&format!(",max_abs_diff_{m}"));
    s
}

#[test]
fn validate_csv_has_the_documented_header_and_round_off_differences() {
    let out = stdout(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "1:5:1",
        "--method",
        "ad",
    ]));
    let mut lines = out.lines();
    assert_eq!(
        lines.next(),
        Some(format!("{LIN}{}", method_columns("ad")).as_str())
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().expect("a number")).collect())
        .collect();
    assert_eq!(rows.len(), 5);
    for row in &rows {
        assert_eq!(row.len(), 9 + 9);
        assert!(row[17] < 1e-11, "{row:?}");
    }
    // Meijaard et al. 2007, Table 2 at 5 m/s: the capsize eigenvalue.
    assert!(
        rows[4][1..9]
            .chunks(2)
            .any(|z| (z[0] + 0.32286642900409).abs() < 1e-12 && z[1] == 0.0)
    );
}

#[test]
fn validate_both_methods_and_json() {
    let out = stdout(&whipple(&[
        "validate",
        "--bike",
        "schwinn-crown",
        "--speeds",
        "4:4.5:0.5",
    ]));
    let header = out.lines().next().unwrap_or_default();
    assert_eq!(
        header,
        format!("{LIN}{}{}", method_columns("fd"), method_columns("ad"))
    );
    let json = stdout(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "2:2:1",
        "--method",
        "fd",
        "--format",
        "json",
    ]));
    let doc: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    let d = doc["rows"][0]["methods"]["fd"]["max_abs_diff"]
        .as_f64()
        .expect("a difference");
    assert!(d < 1e-9, "{d}");
}

#[test]
fn validate_report_holds_the_csv_figures_and_summary() {
    let dir = scratch("validate-report");
    let dir_arg = dir.to_string_lossy().into_owned();
    let out = stdout(&whipple(&[
        "validate",
        "--bike",
        "benchmark",
        "--speeds",
        "5.5:6.5:0.25",
        "--report",
        &dir_arg,
    ]));
    for file in [
        "validation.csv",
        "eigenvalues_real.png",
        "eigenvalues_imag.png",
        "difference_fd.png",
        "difference_ad.png",
        "difference_ad_full.png",
        "difference_all.png",
        "difference_capsize.png",
        "summary.md",
    ] {
        let bytes = std::fs::read(dir.join(file)).unwrap_or_default();
        assert!(bytes.len() > 100, "{file} missing or empty");
        if file.ends_with(".png") {
            assert_eq!(&bytes[1..4], b"PNG", "{file}");
        }
    }
    let csv = std::fs::read_to_string(dir.join("validation.csv")).unwrap_or_default();
    assert_eq!(csv, out);
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap_or_default();
    assert!(summary.contains("v_c ± 0.25 (capsize)") && summary.contains("Jordan"));
}

#[test]
fn validate_rejects_a_bad_speed_range() {
    let out = whipple(&["validate", "--bike", "benchmark", "--speeds", "5:1:0.1"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--speeds"));
}
