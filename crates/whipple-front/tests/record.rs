//! Oscillation records read from CSV and MATLAB `.mat`, and BicycleParameters' sample record
//! fitted as BicycleParameters fits it.

use proptest::prelude::*;
use whipple::Error;
use whipple::advanced::measured::period::{decay_window, fit_period};
use whipple_front::record::{RecordRequest, mat_variables, read_record};

const SAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../whipple/tests/data/measured/periods/BrowserForkCompoundFirst1.mat"
);

fn sample() -> Vec<u8> {
    std::fs::read(SAMPLE).expect("BicycleParameters' sample record is in the repository")
}

/// BicycleParameters' `tests/test_io.py::test_load_pendulum_mat_file`: the same variables,
/// rate and first samples.
#[test]
fn sample_mat_reads_as_bicycleparameters_reads_it() -> Result<(), Error> {
    let variables = mat_variables(&sample())?;
    let names: Vec<&str> = variables.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["duration", "ActualRate", "data"]);
    let record = read_record(
        &sample(),
        "BrowserForkCompoundFirst1.mat",
        &RecordRequest::default(),
    )?;
    assert_eq!(record.signal.len(), 30000);
    assert_eq!(record.signal_name, "data");
    assert_eq!(record.time[1], 1e-3);
    let first = [0.33034183, 0.32525861, 0.31509219, 0.31509219, 0.33034183];
    for (a, b) in record.signal.iter().zip(first) {
        assert!((a - b).abs() < 1e-8, "{a} {b}");
    }
    Ok(())
}

/// BicycleParameters 1.5.2 on its own sample record (the numbers and how they were computed:
/// `crates/whipple/tests/data/measured/periods/README.md`).
#[test]
fn sample_record_period_equals_bicycleparameters() -> Result<(), Error> {
    let record = read_record(
        &sample(),
        "BrowserForkCompoundFirst1.mat",
        &RecordRequest::default(),
    )?;
    let window = decay_window(&record.signal, 0.1)?;
    assert_eq!((window.start, window.end), (2, 29696));
    // BicycleParameters counts time from the window's first sample.
    let fit = fit_period(&record.time[..window.len()], &record.signal[window])?;
    // Its fit with the analytic Jacobian to scipy's tightest tolerances, to 1e-4 of σ_T
    // (BicycleParameters' own result, 1.5903143897002077, stopped at scipy's default
    // tolerance, 3e-9 away).
    assert!(
        (fit.period - 1.5903143948411882).abs() < 1e-9,
        "{}",
        fit.period
    );
    assert!((fit.period - 1.5903143897002077).abs() < 1e-8);
    // σ from the full covariance (1.2223837191221983e-05), and BicycleParameters' σ, which
    // treats σ_ζ and σ_ωn as uncorrelated.
    assert!(
        (fit.period_sigma / 1.2223837191221983e-05 - 1.0).abs() < 1e-6,
        "{}",
        fit.period_sigma
    );
    assert!((fit.period_sigma / 1.2221435140156404e-05 - 1.0).abs() < 1e-3);
    assert!((fit.damping_ratio - 0.00890250531186835).abs() < 1e-9);
    assert!((fit.damping_ratio_sigma / 7.652237021801475e-06 - 1.0).abs() < 1e-5);
    assert!((fit.residual_rms - 0.019752831437066617).abs() < 1e-12);
    Ok(())
}

#[test]
fn csv_records_by_header_number_and_rate() -> Result<(), Error> {
    let rows: String = (0..400)
        .map(|i| {
            let t = i as f64 * 0.01;
            format!(
                "{t},{},{}\n",
                7.0,
                whipple::math::exp(-0.02 * t) * whipple::math::cos(3.0 * t)
            )
        })
        .collect();
    let text = format!("# a comment\ntime,temperature,gyro\n{rows}");
    let by_name = RecordRequest {
        signal: Some("gyro".into()),
        ..RecordRequest::default()
    };
    let record = read_record(text.as_bytes(), "r.csv", &by_name)?;
    assert_eq!(
        (record.signal_name.as_str(), record.time_source.as_str()),
        ("gyro", "time")
    );
    let fit = fit_period(&record.time, &record.signal)?;
    assert!((fit.period - std::f64::consts::TAU / 3.0).abs() < 1e-10);

    let by_number = RecordRequest {
        signal: Some("3".into()),
        ..RecordRequest::default()
    };
    assert_eq!(
        read_record(text.as_bytes(), "r.csv", &by_number)?.signal,
        record.signal
    );

    // One column of numbers with a rate, spaces as separators.
    let column: String = record.signal.iter().map(|y| format!("{y}\n")).collect();
    let rated = RecordRequest {
        rate: Some(100.0),
        ..RecordRequest::default()
    };
    let sampled = read_record(column.as_bytes(), "r.txt", &rated)?;
    assert_eq!(sampled.signal, record.signal);
    assert!((sampled.time[399] - 3.99).abs() < 1e-12);
    Ok(())
}

fn message(error: Error) -> String {
    error.to_string()
}

#[test]
fn bad_records_are_refused_naming_what_is_wrong() {
    let default = RecordRequest::default();
    let missing = RecordRequest {
        signal: Some("x".into()),
        ..default.clone()
    };
    let m = message(read_record(&sample(), "a.mat", &missing).unwrap_err());
    assert!(
        m.contains("the .mat has no numeric variable 'x'") && m.contains("data"),
        "{m}"
    );

    let m = message(read_record(b"t,y,z\n1,2,3\n", "a.csv", &default).unwrap_err());
    assert!(m.contains("3 column(s) (t, y, z)"), "{m}");
    let m = message(read_record(b"t,y\n1,2\n2,oops\n", "a.csv", &default).unwrap_err());
    assert!(m.contains("line 3") && m.contains("`oops`"), "{m}");
    let m = message(read_record(b"t,y\n1,2\n2\n", "a.csv", &default).unwrap_err());
    assert!(m.contains("line 3"), "{m}");
    let m = message(read_record(b"t,y\n1,2\n", "a.csv", &missing).unwrap_err());
    assert!(m.contains("no column `x`"), "{m}");
    let m = message(read_record(b"", "a.csv", &default).unwrap_err());
    assert!(m.contains("no rows"), "{m}");

    let mut truncated = sample();
    truncated.truncate(4000);
    let m = message(read_record(&truncated, "a.mat", &default).unwrap_err());
    assert!(m.contains("MATLAB .mat"), "{m}");
    let mut v73 = sample();
    v73[..19].copy_from_slice(b"MATLAB 7.3 MAT-file");
    let m = message(read_record(&v73, "a.mat", &default).unwrap_err());
    assert!(m.contains("-v7.3"), "{m}");
    let bad_rate = RecordRequest {
        rate: Some(-1.0),
        ..default
    };
    let m = message(read_record(b"1\n2\n", "a.csv", &bad_rate).unwrap_err());
    assert!(m.contains("sample rate"), "{m}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// Any bytes, as CSV or after a valid `.mat` header: an answer or an error, never a panic.
    #[test]
    fn readers_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        let _ = read_record(&bytes, "r.csv", &RecordRequest::default());
        let mut mat = sample()[..128].to_vec();
        mat.extend_from_slice(&bytes);
        let _ = read_record(&mat, "r.mat", &RecordRequest::default());
    }

    /// The sample file with one byte changed: an answer or an error, never a panic.
    #[test]
    fn corrupted_sample_never_panics(at in 128usize..73187, value in any::<u8>()) {
        let mut bytes = sample();
        bytes[at] = value;
        let _ = read_record(&bytes, "r.mat", &RecordRequest::default());
    }
}

/// The fuzz target's seeds (`fuzz/seeds/period_records/`), replayed on stable: `ok-` seeds read
/// and fit, `err-` seeds give an error with a message.
#[test]
fn fuzz_seeds_replay() {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/seeds/period_records");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).expect("the seeds are in the repository") {
        let path = entry.expect("a directory entry").path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default()
            .to_string();
        let bytes = std::fs::read(&path).expect("a seed reads");
        let result = read_record(&bytes, &name, &RecordRequest::default())
            .and_then(|record| fit_period(&record.time, &record.signal));
        match result {
            Ok(fit) => assert!(name.starts_with("ok-") && fit.period.is_finite(), "{name}"),
            Err(e) => assert!(
                name.starts_with("err-") && !e.to_string().is_empty(),
                "{name}: {e}"
            ),
        }
        count += 1;
    }
    assert!(count >= 5);
}
