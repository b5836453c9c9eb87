//! The Yeadon human body model: every rider file of BicycleParameters' data set against the
//! Python package `yeadon` (2.0.1, with its three corrections described in
//! `data/yeadon/expected.py`, which made `data/yeadon/expected.json`:
//! `/tmp/yeadon-venv/bin/python expected.py > expected.json` in that folder), then identities
//! that do not depend on `yeadon` (the corrections' own checks), then bad input.

use nalgebra::{Matrix3, Vector3};
use num_dual::Dual64;
use serde_json::Value;
use whipple::Error;
use whipple::advanced::rider::{
    SEGMENT_NAMES, YeadonBody, YeadonConfiguration, YeadonMeasurements, read_yeadon_configuration,
    read_yeadon_measurements, yeadon_body,
};

fn file(name: &str) -> String {
    let path = format!("{}/tests/data/yeadon/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn body(measurements: &str, configuration: Option<&str>) -> YeadonBody<f64> {
    let m = read_yeadon_measurements(&file(measurements)).unwrap();
    let c = match configuration {
        Some(name) => read_yeadon_configuration(&file(name)).unwrap(),
        None => YeadonConfiguration::zero(),
    };
    yeadon_body(&m, &c).unwrap()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The largest difference relative to the expected quantity's size (its largest component).
fn relative(got: &[f64], expected: &[f64]) -> f64 {
    assert_eq!(got.len(), expected.len());
    let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    got.iter()
        .zip(expected)
        .fold(0.0f64, |m, (g, e)| m.max((g - e).abs() / scale))
}

fn row_major(m: &Matrix3<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// Every segment's mass, mass centre, orientation and inertia (own frame and global) and the
/// whole body's, for each rider and configuration file, to 1e-12 of each quantity's size.
#[test]
fn every_rider_agrees_with_yeadon() {
    let expected: Value = serde_json::from_str(&file("expected.json")).unwrap();
    let cases = expected["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 16);
    let mut worst = 0.0f64;
    for case in cases {
        let meas = case["measurements"].as_str().unwrap();
        let cfg = case["configuration"].as_str();
        let b = body(meas, cfg);
        let what = format!("{meas} {cfg:?}");
        let mut check = |name: &str, got: &[f64], want: &[f64]| {
            let r = relative(got, want);
            assert!(r < 1e-12, "{what} {name}: {got:?} vs {want:?} ({r:e})");
            worst = worst.max(r);
        };
        check("mass", &[b.mass], &[case["mass"].as_f64().unwrap()]);
        check(
            "mass centre",
            b.center_of_mass.as_slice(),
            &numbers(&case["center_of_mass"]),
        );
        check(
            "inertia",
            &row_major(&b.inertia),
            &numbers(&case["inertia"]),
        );
        let segments = case["segments"].as_array().unwrap();
        assert_eq!(segments.len(), 11);
        for (s, e) in b.segments.iter().zip(segments) {
            assert_eq!(s.name, e["name"].as_str().unwrap());
            let n = s.name;
            check(
                &format!("{n} mass"),
                &[s.mass],
                &[e["mass"].as_f64().unwrap()],
            );
            check(
                &format!("{n} mass centre"),
                s.center_of_mass.as_slice(),
                &numbers(&e["center_of_mass"]),
            );
            check(
                &format!("{n} orientation"),
                &row_major(&s.orientation),
                &numbers(&e["orientation"]),
            );
            check(
                &format!("{n} local inertia"),
                &row_major(&s.local_inertia),
                &numbers(&e["local_inertia"]),
            );
            check(
                &format!("{n} inertia"),
                &row_major(&s.inertia),
                &numbers(&e["inertia"]),
            );
        }
    }
    println!("largest relative difference from yeadon: {worst:e}");
}

/// A configuration symmetric about the mid-plane (only somersault and the limbs' sagittal
/// angles, equal left and right) puts the mass centre on it and zeroes the products with x.
#[test]
fn symmetric_configurations_keep_the_mass_centre_on_the_mid_plane() {
    for (meas, cfg) in [
        ("JasonYeadonMeas.txt", "JasonBrowserYeadonCFG.txt"),
        ("CharlieYeadonMeas.txt", "CharlieRigidclYeadonCFG.txt"),
        ("LukeYeadonMeas.txt", "LukeRigidclYeadonCFG.txt"),
    ] {
        let m = read_yeadon_measurements(&file(meas)).unwrap();
        let mut c = read_yeadon_configuration(&file(cfg)).unwrap();
        for (left, right, value) in [
            ("CA1extension", "CB1extension", -0.7),
            ("A1A2extension", "B1B2extension", -1.2),
            ("PJ1extension", "PK1extension", -1.0),
            ("J1J2flexion", "K1K2flexion", 1.4),
        ] {
            for name in [left, right] {
                let i = whipple::advanced::rider::CONFIGURATION_ANGLES
                    .iter()
                    .position(|(n, _, _)| *n == name)
                    .unwrap();
                c.angles[i] = value;
            }
        }
        let b = yeadon_body(&m, &c).unwrap();
        let size = b.center_of_mass.norm();
        assert!(
            b.center_of_mass.x.abs() < 1e-14 * size.max(1.0),
            "{meas}: {}",
            b.center_of_mass
        );
        let scale = b.inertia.amax();
        assert!(b.inertia[(0, 1)].abs() < 1e-14 * scale && b.inertia[(0, 2)].abs() < 1e-14 * scale);
    }
}

/// The parallel-axis theorem: the body's inertia about the origin summed segment by segment
/// equals its central inertia moved there; and each segment's inertia is its own-frame inertia
/// rotated (its long axis keeps its own-frame moment).
#[test]
fn parallel_axes_and_rotations_agree() {
    let b = body("JasonYeadonMeas.txt", Some("ArbitraryYeadonCFG.txt"));
    let shift = |m: f64, d: &Vector3<f64>| (Matrix3::identity() * d.dot(d) - d * d.transpose()) * m;
    let about_origin = b.segments.iter().fold(Matrix3::zeros(), |acc, s| {
        acc + s.inertia + shift(s.mass, &s.center_of_mass)
    });
    let moved = b.inertia + shift(b.mass, &b.center_of_mass);
    assert!((about_origin - moved).amax() < 1e-13 * moved.amax());
    for s in &b.segments {
        let axis = s.orientation * Vector3::z();
        let along = axis.dot(&(s.inertia * axis));
        assert!(
            (along - s.local_inertia[(2, 2)]).abs() < 1e-13 * s.local_inertia.amax(),
            "{}",
            s.name
        );
        assert!((s.orientation.transpose() * s.orientation - Matrix3::identity()).amax() < 1e-15);
    }
    assert_eq!(b.segments.len(), SEGMENT_NAMES.len());
}

/// Dual numbers through the model: the total mass scales the body, so d(mass)/d(totalmass) = 1
/// and the mass centre does not move with it.
#[test]
fn derivatives_through_the_model() {
    let m = read_yeadon_measurements(&file("JasonYeadonMeas.txt")).unwrap();
    let dual = YeadonMeasurements {
        values: m.values.map(Dual64::from),
        total_mass: m.total_mass.map(|t| Dual64::new(t, 1.0)),
        lines: m.lines,
    };
    let c = YeadonConfiguration::<Dual64>::zero();
    let b = yeadon_body(&dual, &c).unwrap();
    assert!((b.mass.eps - 1.0).abs() < 1e-12);
    assert!(b.center_of_mass.iter().all(|x| x.eps.abs() < 1e-15));
    let plain = yeadon_body(&m, &YeadonConfiguration::zero()).unwrap();
    assert!((b.inertia[(0, 0)].eps * m.total_mass.unwrap() - plain.inertia[(0, 0)]).abs() < 1e-12);
}

fn replaced(name: &str, key: &str, value: &str) -> String {
    file(name)
        .lines()
        .map(|l| {
            if l.starts_with(&format!("{key}:")) {
                format!("{key}: {value}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn line_of(text: &str, key: &str) -> usize {
    text.lines()
        .position(|l| l.starts_with(&format!("{key}:")))
        .unwrap()
        + 1
}

fn parse_error(e: Error) -> (Option<String>, usize, String) {
    match e {
        Error::Parse {
            field,
            line,
            message,
            ..
        } => (field, line, message),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn a_solid_of_negative_volume_names_the_measurement_and_its_line() {
    // Ls2L below Ls1L: the solid s1 between the umbilicus and the lowest rib turns inside out.
    let text = replaced("JasonYeadonMeas.txt", "Ls2L", "15.0");
    let m = read_yeadon_measurements(&text).unwrap();
    let e = yeadon_body(&m, &YeadonConfiguration::zero()).unwrap_err();
    let (field, line, message) = parse_error(e.clone());
    assert_eq!(field.as_deref(), Some("Ls2L"));
    assert_eq!(line, line_of(&text, "Ls2L"));
    assert!(message.contains("negative"), "{e}");
}

#[test]
fn a_level_that_is_not_a_stadium_names_the_measurement_and_its_line() {
    // A perimeter below twice the width: no stadium has it.
    let text = replaced("JasonYeadonMeas.txt", "Ls1p", "60");
    let m = read_yeadon_measurements(&text).unwrap();
    let e = yeadon_body(&m, &YeadonConfiguration::zero()).unwrap_err();
    let (field, line, message) = parse_error(e.clone());
    assert_eq!(field.as_deref(), Some("Ls1p"));
    assert_eq!(line, line_of(&text, "Ls1p"));
    assert!(
        message.contains("not a stadium") && message.contains("Ls1w"),
        "{e}"
    );
    // Above π times the width is not one either (a negative flat length).
    let text = replaced("JasonYeadonMeas.txt", "Ls1p", "120");
    let m = read_yeadon_measurements(&text).unwrap();
    let e = yeadon_body(&m, &YeadonConfiguration::zero()).unwrap_err();
    assert_eq!(parse_error(e).0.as_deref(), Some("Ls1p"));
}

#[test]
fn missing_unknown_and_bad_measurements_are_named() {
    let text = file("JasonYeadonMeas.txt")
        .lines()
        .filter(|l| !l.starts_with("La4w:"))
        .collect::<Vec<_>>()
        .join("\n");
    let (field, _, message) = parse_error(read_yeadon_measurements(&text).unwrap_err());
    assert_eq!(field.as_deref(), Some("La4w"));
    assert!(
        message.contains("1 of the 95 measurements missing: La4w"),
        "{message}"
    );

    let text = format!("{}\nLs9L: 3\n", file("JasonYeadonMeas.txt"));
    let (field, line, _) = parse_error(read_yeadon_measurements(&text).unwrap_err());
    assert_eq!(
        (field.as_deref(), line),
        (Some("Ls9L"), text.lines().count())
    );

    let text = replaced("JasonYeadonMeas.txt", "Lj3p", "-4");
    let (field, line, _) = parse_error(read_yeadon_measurements(&text).unwrap_err());
    assert_eq!(
        (field.as_deref(), line),
        (Some("Lj3p"), line_of(&text, "Lj3p"))
    );

    let text = file("JasonYeadonMeas.txt").replace("measurementconversionfactor", "# factor");
    let (field, _, _) = parse_error(read_yeadon_measurements(&text).unwrap_err());
    assert_eq!(field.as_deref(), Some("measurementconversionfactor"));
}

#[test]
fn configuration_files_are_checked() {
    let text = replaced("JasonBrowserYeadonCFG.txt", "J1J2flexion", "-0.5");
    let (field, line, message) = parse_error(read_yeadon_configuration(&text).unwrap_err());
    assert_eq!(
        (field.as_deref(), line),
        (Some("J1J2flexion"), line_of(&text, "J1J2flexion"))
    );
    assert!(message.contains("outside its range"), "{message}");

    let text = file("JasonBrowserYeadonCFG.txt").replace("somersault:", "somersalt:");
    let (field, _, message) = parse_error(read_yeadon_configuration(&text).unwrap_err());
    assert_eq!(field.as_deref(), Some("somersalt"));
    assert!(message.contains("`somersault`"), "{message}");

    let text = file("JasonBrowserYeadonCFG.txt").replace("tilt: 0.0", "");
    let (field, _, _) = parse_error(read_yeadon_configuration(&text).unwrap_err());
    assert_eq!(field.as_deref(), Some("tilt"));

    // A configuration built in code is checked as well, naming the angle.
    let m = read_yeadon_measurements(&file("JasonYeadonMeas.txt")).unwrap();
    let mut c = YeadonConfiguration::zero();
    c.angles[0] = 4.0;
    match yeadon_body(&m, &c).unwrap_err() {
        Error::InvalidParameter { field, .. } => assert_eq!(field, "somersault"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_key_given_twice_names_both_lines() {
    let text = format!("{}\nLs1L: 17.6\n", file("JasonYeadonMeas.txt"));
    let (field, line, message) = parse_error(read_yeadon_measurements(&text).unwrap_err());
    assert_eq!(
        (field.as_deref(), line),
        (Some("Ls1L"), text.lines().count())
    );
    assert!(
        message.contains(&format!("first on line {}", line_of(&text, "Ls1L"))),
        "{message}"
    );
}
