//! `whipple measure` through the real binary: BicycleParameters' raw bench measurements to a
//! parameter file with σ and a report of every step (issue 30, items 1 and 5).

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::advanced::io::{Format, parse};
use whipple::advanced::measured::{MeasuredParameters, read_measurements};

fn raw(name: &str) -> String {
    format!(
        "{}/../whipple/tests/data/measured/{name}Measured.txt",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn core(name: &str) -> MeasuredParameters {
    let text = std::fs::read_to_string(raw(name)).expect("raw file");
    let file = read_measurements(&text).expect("reads");
    MeasuredParameters::new(&file.measurements).expect("computes")
}

/// Browser's raw file gives, in the file written, exactly the core's parameters and σ; the
/// JSON report holds every step, the benchmark ones equal to the file's.
#[test]
fn browser_file_holds_the_core_parameters() {
    let dir = scratch("measure-browser");
    let out = dir.join("browser.toml");
    let report = stdout(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--out",
        out.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let expected = core("Browser");
    let written = parse(&std::fs::read_to_string(&out).unwrap(), Format::Toml).unwrap();
    assert_eq!(written.name.as_deref(), Some("Browser"));
    assert_eq!(written.benchmark().unwrap(), expected.benchmark);
    assert_eq!(written.sigma, expected.sigma);
    let json: serde_json::Value = serde_json::from_str(&report).expect("JSON");
    let steps = json["steps"].as_array().expect("steps");
    assert_eq!(steps.len(), expected.steps.len());
    let step = |key: &str| steps.iter().find(|s| s["key"] == key).expect(key);
    assert_eq!(step("k")["function"], "torsion_constant");
    assert_eq!(step("rR")["inputs"], serde_json::json!(["dR", "nR"]));
    assert_eq!(
        step("IBxx")["value"].as_f64(),
        Some(expected.benchmark.i_bxx)
    );
    assert!(step("residualB")["sigma"].is_null());
    assert_eq!(
        json["parameters"]["xB"]["sigma"].as_f64(),
        Some(expected.sigma["xB"])
    );
    // Every format --out knows by its extension reads back the same numbers.
    for (file, format) in [
        ("b.json", Format::Json),
        ("bBenchmark.txt", Format::BicycleParametersTxt),
    ] {
        let path = dir.join(file);
        stdout(&whipple(&[
            "measure",
            "--raw",
            &raw("Browser"),
            "--out",
            path.to_str().unwrap(),
        ]));
        let back = parse(&std::fs::read_to_string(&path).unwrap(), format).unwrap();
        assert_eq!(back.benchmark().unwrap(), expected.benchmark, "{file}");
    }
}

/// The critical speeds of the file written, with σ, are those of the parameters
/// BicycleParameters computed from the same measurements (its stored `BrowserBenchmark.txt`).
#[test]
fn critical_speeds_with_sigma_from_the_written_file() {
    let dir = scratch("measure-speeds");
    let out = dir.join("browser.toml");
    stdout(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--out",
        out.to_str().unwrap(),
    ]));
    let speeds = |bike: &str| -> serde_json::Value {
        serde_json::from_str(&stdout(&whipple(&[
            "speeds", "--bike", bike, "--format", "json",
        ])))
        .expect("JSON")
    };
    let ours = speeds(out.to_str().unwrap());
    let stored = speeds(&format!(
        "{}/../whipple/tests/data/measured/BrowserBenchmark.txt",
        env!("CARGO_MANIFEST_DIR")
    ));
    for key in [
        "weave_speed",
        "capsize_speed",
        "weave_speed_sigma",
        "capsize_speed_sigma",
    ] {
        let (a, b) = (
            ours[key].as_f64().expect(key),
            stored[key].as_f64().expect(key),
        );
        assert!(
            (a - b).abs() <= 1e-9 * b.abs(),
            "{key}: {a} vs BicycleParameters' {b}"
        );
        assert!(a > 0.0, "{key}");
    }
    let table = stdout(&whipple(&["speeds", "--bike", out.to_str().unwrap()]));
    assert!(table.contains(" ± "), "{table}");
}

/// The table names each step's function and inputs; --correlations adds the largest |ρ|.
#[test]
fn table_report_and_correlations() {
    let text = stdout(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--correlations",
        "4",
    ]));
    assert!(text.starts_with("Browser: benchmark parameters"), "{text}");
    let line = text.lines().find(|l| l.starts_with("k ")).expect("k row");
    assert!(
        line.contains("torsion_constant") && line.ends_with("mP lP dP TtP1"),
        "{line}"
    );
    let after = text
        .split("Largest correlations")
        .nth(1)
        .expect("correlations");
    assert_eq!(
        after.lines().filter(|l| l.starts_with("  ")).count(),
        4,
        "{after}"
    );
    let json: serde_json::Value = serde_json::from_str(&stdout(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--correlations",
        "3",
        "--format",
        "json",
    ])))
    .unwrap();
    let top = json["correlations"].as_array().unwrap();
    let expected = core("Browser").largest_correlations(3);
    assert_eq!(top.len(), 3);
    for (got, want) in top.iter().zip(&expected) {
        assert_eq!(got["a"], want.a);
        assert_eq!(got["rho"].as_f64(), Some(want.rho));
    }
}

/// Silver's raw file has no rolled distance of the front wheel: the message names dF and what
/// it feeds, and nothing is written.
#[test]
fn silver_names_the_missing_measurement() {
    let dir = scratch("measure-silver");
    let out = dir.join("silver.toml");
    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        &raw("Silver"),
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(
        err.contains("dF is missing: the front wheel's radius needs it"),
        "{err}"
    );
    assert!(err.contains("SilverMeasured.txt"), "{err}");
    assert!(!out.exists());
}

/// A negative period is refused naming the key and its line; a missing file and the options
/// not supported yet are refused clearly; the output never replaces the measurements.
#[test]
fn bad_input_is_refused() {
    let dir = scratch("measure-bad");
    let text = std::fs::read_to_string(raw("Browser")).unwrap();
    let (index, line) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with("TcR1"))
        .expect("TcR1");
    let bad = text.replace(line, "TcR1 = -1.4+/-0.001");
    let path = dir.join("BadMeasured.txt");
    std::fs::write(&path, &bad).unwrap();
    let err = stderr_of_failure(&whipple(&["measure", "--raw", path.to_str().unwrap()]));
    assert!(
        err.contains("TcR1") && err.contains("a period must be positive"),
        "{err}"
    );
    assert!(err.contains(&format!("line {}", index + 1)), "{err}");

    let missing = dir.join("NoneMeasured.txt");
    let err = stderr_of_failure(&whipple(&["measure", "--raw", missing.to_str().unwrap()]));
    assert!(
        err.contains("--raw") && err.contains("NoneMeasured.txt"),
        "{err}"
    );

    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--rider",
        "JasonYeadonMeas.txt",
    ]));
    assert!(
        err.contains("--rider") && err.contains("--configuration"),
        "{err}"
    );

    let copy = dir.join("BrowserMeasured.txt");
    std::fs::write(&copy, &text).unwrap();
    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        copy.to_str().unwrap(),
        "--out",
        copy.to_str().unwrap(),
        "--to",
        "toml",
    ]));
    assert!(err.contains("would destroy it"), "{err}");
    assert_eq!(std::fs::read_to_string(&copy).unwrap(), text);

    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--out",
        dir.join("b.m").to_str().unwrap(),
    ]));
    assert!(
        err.contains(".m files hold no standard deviations"),
        "{err}"
    );
    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--out",
        dir.to_str().unwrap(),
        "--to",
        "toml",
    ]));
    assert!(err.contains("--out"), "{err}");
}

/// `--periods DIR`: Browser's file without TcH1 takes it from BicycleParameters' record of
/// Browser's fork (`BrowserForkCompoundFirst1.mat`), fitted by the core as `whipple period
/// --trim 0.1` fits it; the report names the period, its σ and the file. A period with no
/// record is refused naming the key and the file looked for.
#[test]
fn periods_from_records() {
    use whipple::advanced::measured::period::{decay_window, fit_period};
    use whipple_front::record::{RecordRequest, read_record};
    let dir = scratch("measure-periods");
    let records = format!(
        "{}/../whipple/tests/data/measured/periods",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(raw("Browser")).unwrap();
    let without = |key: &str| -> String {
        text.lines()
            .filter(|l| l.split('=').next().map(str::trim) != Some(key))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    let path = dir.join("BrowserMeasured.txt");
    std::fs::write(&path, without("TcH1")).unwrap();
    let report = stdout(&whipple(&[
        "measure",
        "--raw",
        path.to_str().unwrap(),
        "--periods",
        &records,
        "--format",
        "json",
    ]));
    let json: serde_json::Value = serde_json::from_str(&report).expect("JSON");
    let bytes = std::fs::read(format!("{records}/BrowserForkCompoundFirst1.mat")).unwrap();
    let record = read_record(
        &bytes,
        "BrowserForkCompoundFirst1.mat",
        &RecordRequest::default(),
    )
    .unwrap();
    let window = decay_window(&record.signal, 0.1).unwrap();
    let fit = fit_period(&record.time[window.clone()], &record.signal[window]).unwrap();
    let fitted = json["fitted"].as_array().expect("fitted");
    assert_eq!(fitted.len(), 1);
    assert_eq!(fitted[0]["key"], "TcH1");
    assert_eq!(fitted[0]["value"].as_f64(), Some(fit.period));
    assert_eq!(fitted[0]["sigma"].as_f64(), Some(fit.period_sigma));
    assert_eq!(
        fitted[0]["source"],
        "fitted from BrowserForkCompoundFirst1.mat"
    );
    // The table names them too.
    let table = stdout(&whipple(&[
        "measure",
        "--raw",
        path.to_str().unwrap(),
        "--periods",
        &records,
    ]));
    assert!(
        table.contains("fitted from records") && table.contains("TcH1 = 1.5903"),
        "{table}"
    );
    // No record of the rear frame's compound pendulum.
    std::fs::write(&path, without("TcB1")).unwrap();
    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        path.to_str().unwrap(),
        "--periods",
        &records,
    ]));
    assert!(
        err.contains("TcB1")
            && err.contains("looked for")
            && err.contains("BrowserFrameCompoundFirst1.mat"),
        "{err}"
    );
}

/// The bicycles measured with perpendicular distances, a split fork or a flywheel compute
/// through the binary; the flywheel's and the fork's parts are written as extras.
#[test]
fn rigid_and_gyro_compute() {
    let dir = scratch("measure-rigid");
    for (name, key) in [("Rigid", "ISxx"), ("Gyro", "IDyy")] {
        let out = dir.join(format!("{name}.txt"));
        stdout(&whipple(&[
            "measure",
            "--raw",
            &raw(name),
            "--out",
            out.to_str().unwrap(),
        ]));
        let written = std::fs::read_to_string(&out).unwrap();
        assert!(written.contains(key), "{name}: {written}");
        let expected = core(name);
        let parsed = parse(&written, Format::BicycleParametersTxt).unwrap();
        let back = parsed.benchmark().unwrap();
        for (a, b) in back.to_array().iter().zip(expected.benchmark.to_array()) {
            assert!(
                (a - b).abs() <= 1e-10 * b.abs().max(1e-12),
                "{name}: {a} vs {b}"
            );
        }
    }
}

fn rider_file(name: &str) -> String {
    format!(
        "{}/../whipple/tests/data/yeadon/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// `--rider` and `--configuration`: Browser with Jason seated, the file written holds the
/// core's `with_rider` parameters and σ, the report the rider's steps; a handlebar out of
/// reach is refused naming what.
#[test]
fn browser_with_jason() {
    use whipple::advanced::rider::{read_yeadon_configuration, read_yeadon_measurements};
    let dir = scratch("measure-browser-jason");
    let out = dir.join("browser-jason.toml");
    let args = |raw: &str, out: &str| {
        vec![
            "measure".to_string(),
            "--raw".into(),
            raw.into(),
            "--rider".into(),
            rider_file("JasonYeadonMeas.txt"),
            "--configuration".into(),
            rider_file("JasonBrowserYeadonCFG.txt"),
            "--out".into(),
            out.into(),
        ]
    };
    let mut json_args = args(&raw("Browser"), out.to_str().unwrap());
    json_args.extend(["--format".to_string(), "json".into()]);
    let refs: Vec<&str> = json_args.iter().map(String::as_str).collect();
    let report = stdout(&whipple(&refs));
    let text = std::fs::read_to_string(raw("Browser")).unwrap();
    let expected = MeasuredParameters::with_rider(
        &read_measurements(&text).unwrap(),
        &read_yeadon_measurements(
            &std::fs::read_to_string(rider_file("JasonYeadonMeas.txt")).unwrap(),
        )
        .unwrap(),
        &read_yeadon_configuration(
            &std::fs::read_to_string(rider_file("JasonBrowserYeadonCFG.txt")).unwrap(),
        )
        .unwrap(),
    )
    .unwrap();
    let written = parse(&std::fs::read_to_string(&out).unwrap(), Format::Toml).unwrap();
    assert_eq!(written.name.as_deref(), Some("Browser with Jason"));
    assert_eq!(
        written.benchmark().unwrap().to_array(),
        expected.benchmark.to_array()
    );
    assert_eq!(written.sigma, expected.sigma);
    let doc: serde_json::Value = serde_json::from_str(&report).unwrap();
    let rider = &doc["rider"];
    let mass = expected.rider.as_ref().unwrap().rider.mass;
    assert_eq!(rider["mass_kg"].as_f64(), Some(mass));
    assert!(rider["iterations"].as_u64().unwrap() >= 1);
    let steps = doc["steps"].as_array().unwrap();
    let keys: Vec<&str> = steps.iter().map(|s| s["key"].as_str().unwrap()).collect();
    for key in ["mB_frame", "xseat", "xgrip", "PJ1extension", "mRider", "mB"] {
        assert!(keys.contains(&key), "{key} not in {keys:?}");
    }

    // The table names the rider's steps too.
    let table_args = args(&raw("Browser"), dir.join("b.toml").to_str().unwrap());
    let refs: Vec<&str> = table_args.iter().map(String::as_str).collect();
    let table = stdout(&whipple(&refs));
    assert!(
        table.starts_with("Browser with Jason: benchmark parameters"),
        "{table}"
    );
    assert!(table.contains("seated_configuration") && table.contains("combine_with_rear_frame"));

    // A handlebar a metre further than Jason's arms.
    let far = dir.join("FarMeasured.txt");
    std::fs::write(
        &far,
        text.replace("LhbF = 0.8930", "LhbF = 1.8930")
            .replace("LhbR = 0.9213", "LhbR = 1.9213"),
    )
    .unwrap();
    let bad_args = args(
        far.to_str().unwrap(),
        dir.join("far.toml").to_str().unwrap(),
    );
    let refs: Vec<&str> = bad_args.iter().map(String::as_str).collect();
    let err = stderr_of_failure(&whipple(&refs));
    assert!(
        err.contains("the rider cannot reach the handlebar")
            && err.contains("La2L, La4L, La5L, LhbF, LhbR, whb, somersault"),
        "{err}"
    );
    assert!(!dir.join("far.toml").exists());

    // A configuration without its somersault: the angle named.
    let cfg = dir.join("JasonBrowserYeadonCFG.txt");
    let cfg_text = std::fs::read_to_string(rider_file("JasonBrowserYeadonCFG.txt")).unwrap();
    std::fs::write(&cfg, cfg_text.replace("somersault: 0.175\n", "")).unwrap();
    let err = stderr_of_failure(&whipple(&[
        "measure",
        "--raw",
        &raw("Browser"),
        "--rider",
        &rider_file("JasonYeadonMeas.txt"),
        "--configuration",
        cfg.to_str().unwrap(),
    ]));
    assert!(
        err.contains("1 of the 21 angles missing: somersault"),
        "{err}"
    );
}
