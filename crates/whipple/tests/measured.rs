//! Bicycles from BicycleParameters' raw bench data (`tests/data/measured/*Measured.txt`)
//! against the parameters BicycleParameters computed from the same files and stored in its
//! data set (`*Benchmark.txt`, with σ): values and σ to the digits those files carry
//! (see `tests/data/measured/README.md` for the source).

use std::collections::BTreeMap;

use whipple::advanced::measured::{MeasuredParameters, read_measurements};

/// `key = value+/-sigma` lines of a stored `*Benchmark.txt`.
fn stored(text: &str) -> BTreeMap<String, (f64, f64)> {
    text.lines()
        .filter_map(|l| {
            let (key, rest) = l.split_once('=')?;
            let (v, s) = rest.split_once("+/-").unwrap_or((rest, "0"));
            Some((
                key.trim().to_string(),
                (v.trim().parse().ok()?, s.trim().parse().ok()?),
            ))
        })
        .collect()
}

/// Computes `name` from its raw file and returns the largest relative differences of the
/// values and of the σ from the stored results.
fn compare(name: &str, raw: &str, expected: &str) -> (f64, f64) {
    let file = read_measurements(raw).unwrap_or_else(|e| panic!("{name}: {e}"));
    let result =
        MeasuredParameters::new(&file.measurements).unwrap_or_else(|e| panic!("{name}: {e}"));
    let bicycle = result.bicycle();
    let values = whipple::advanced::table::parameters(whipple::advanced::table::Form::Benchmark);
    let ours: BTreeMap<&str, f64> = values
        .iter()
        .zip(result.benchmark.to_array())
        .map(|(p, v)| (p.key, v))
        .collect();
    let mut worst = (0.0f64, 0.0f64);
    for (key, (value, sigma)) in stored(expected) {
        let Some(v) = ours.get(key.as_str()) else {
            panic!("{name}: stored key {key} is not a benchmark parameter")
        };
        let dv = (v - value).abs() / value.abs().max(1e-300);
        let s = bicycle.sigma_of(&key);
        let ds = (s - sigma).abs() / sigma.abs().max(1e-300);
        assert!(dv < 1e-10, "{name} {key}: {v} vs stored {value} ({dv:e})");
        assert!(ds < 1e-10, "{name} {key}: σ {s} vs stored {sigma} ({ds:e})");
        worst = (worst.0.max(dv), worst.1.max(ds));
    }
    worst
}

macro_rules! bicycle {
    ($test:ident, $name:literal) => {
        #[test]
        fn $test() {
            let worst = compare(
                $name,
                include_str!(concat!("data/measured/", $name, "Measured.txt")),
                include_str!(concat!("data/measured/", $name, "Benchmark.txt")),
            );
            println!(
                "{}: worst relative difference {:e} (values), {:e} (σ)",
                $name, worst.0, worst.1
            );
        }
    };
}

bicycle!(browser_matches_bicycleparameters, "Browser");
bicycle!(browserins_matches_bicycleparameters, "Browserins");
bicycle!(crescendo_matches_bicycleparameters, "Crescendo");
bicycle!(fisher_matches_bicycleparameters, "Fisher");
bicycle!(pista_matches_bicycleparameters, "Pista");
bicycle!(yellow_matches_bicycleparameters, "Yellow");
bicycle!(yellowrev_matches_bicycleparameters, "Yellowrev");

/// Stratos has raw data but no stored result: it must compute, with every σ finite.
#[test]
fn stratos_computes() {
    let file = read_measurements(include_str!("data/measured/StratosMeasured.txt")).unwrap();
    let result = MeasuredParameters::new(&file.measurements).unwrap();
    assert_eq!(result.sigma.len(), 26);
    assert!(result.sigma.values().all(|s| s.is_finite() && *s > 0.0));
}

/// Silver's raw file has only the rider's geometry: the error names the first missing
/// measurement and what it feeds (BicycleParameters itself fails with `KeyError: 'dF'`).
#[test]
fn silver_names_what_is_missing() {
    let e = read_measurements(include_str!("data/measured/SilverMeasured.txt")).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("g is missing")
            && message.contains("dF is missing: the front wheel's radius needs it"),
        "{message}"
    );
}

/// A stored value's text and the half unit of its last printed digit (BicycleParameters
/// rounds some stored files to the σ's digits: `c = 0.042+/-0.010`).
fn printed(text: &str) -> BTreeMap<String, (f64, f64)> {
    text.lines()
        .filter_map(|l| {
            let (key, rest) = l.split_once('=')?;
            let v = rest.split_once("+/-").map_or(rest, |(v, _)| v).trim();
            let decimals = v.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
            Some((
                key.trim().to_string(),
                (v.parse().ok()?, 0.5 * 10f64.powi(-decimals)),
            ))
        })
        .collect()
}

/// Every value of a stored file, the benchmark's and the other parts' (`IGxx`, `mS`: the
/// bicycle's extras), equal to the digits it prints (and to `relative`). The σ of these
/// bicycles are not compared here: BicycleParameters gives the steer axis tilt found from
/// perpendicular distances the σ of its starting guess, atan(c / (a + b)), as a new
/// independent variable, where ours is the implicit derivative; the live Python test
/// (`crates/whipple-py/tests/test_measure.py`) compares the σ with BicycleParameters' own
/// pipeline given the exact derivative of that one step.
fn compare_printed(name: &str, raw: &str, expected: &str, relative: f64) -> f64 {
    let file = read_measurements(raw).unwrap_or_else(|e| panic!("{name}: {e}"));
    let result =
        MeasuredParameters::new(&file.measurements).unwrap_or_else(|e| panic!("{name}: {e}"));
    let bicycle = result.bicycle();
    let table = whipple::advanced::table::parameters(whipple::advanced::table::Form::Benchmark);
    let mut ours: BTreeMap<String, f64> = table
        .iter()
        .zip(result.benchmark.to_array())
        .map(|(p, v)| (p.key.to_string(), v))
        .collect();
    for e in &bicycle.extras {
        if let Some(v) = e.value {
            ours.insert(e.key.clone(), v);
        }
    }
    let mut worst = 0.0f64;
    for (key, (value, half_digit)) in printed(expected) {
        let Some(v) = ours.get(&key) else {
            panic!("{name}: stored key {key} is not computed")
        };
        let tolerance = half_digit.max(relative * value.abs()) * (1.0 + 1e-9);
        assert!(
            (v - value).abs() <= tolerance,
            "{name} {key}: {v} vs stored {value} (±{tolerance:e})"
        );
        worst = worst.max((v - value).abs() / value.abs().max(1e-300));
    }
    worst
}

/// Rigid: geometry as perpendicular distances, fork and handlebar measured apart (stored to
/// twelve digits).
#[test]
fn rigid_matches_bicycleparameters_values() {
    let worst = compare_printed(
        "Rigid",
        include_str!("data/measured/RigidMeasured.txt"),
        include_str!("data/measured/RigidBenchmark.txt"),
        1e-10,
    );
    println!("Rigid: worst relative difference {worst:e} (values)");
}

/// Balanceassistv1: geometry as perpendicular distances (stored rounded to its σ's digits).
#[test]
fn balanceassist_matches_bicycleparameters_values() {
    compare_printed(
        "Balanceassistv1",
        include_str!("data/measured/Balanceassistv1Measured.txt"),
        include_str!("data/measured/Balanceassistv1Benchmark.txt"),
        1e-10,
    );
}

/// Gyro (a flywheel in the front wheel) and Rigidcl (Rigid re-measured) have no stored
/// result: they compute, every σ finite and positive, the flywheel's and the split fork's
/// quantities kept as extras.
#[test]
fn gyro_and_rigidcl_compute() {
    for (name, raw, extras) in [
        (
            "Gyro",
            include_str!("data/measured/GyroMeasured.txt"),
            &["mD", "IDxx", "IDyy"][..],
        ),
        (
            "Rigidcl",
            include_str!("data/measured/RigidclMeasured.txt"),
            &["mS", "xS", "ISyy", "mG", "zG", "IGxz"][..],
        ),
    ] {
        let file = read_measurements(raw).unwrap_or_else(|e| panic!("{name}: {e}"));
        let result =
            MeasuredParameters::new(&file.measurements).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            result.sigma.values().all(|s| s.is_finite() && *s > 0.0),
            "{name}: {:?}",
            result.sigma
        );
        let bicycle = result.bicycle();
        for key in extras {
            let e = bicycle.extras.iter().find(|e| e.key == *key);
            assert!(
                e.is_some_and(
                    |e| e.value.is_some_and(f64::is_finite) && e.sigma.is_some_and(|s| s > 0.0)
                ),
                "{name}: {key} {e:?}"
            );
        }
    }
}
