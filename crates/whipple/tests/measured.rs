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
