//! `whipple rider-inertia` through the real binary: the Yeadon model of BicycleParameters'
//! riders (the core's values are checked against `yeadon` in `crates/whipple/tests/yeadon.rs`;
//! here, that the command prints them, in both formats, and words bad input with its line).

use crate::common::{scratch, stderr_of_failure, stdout, whipple};

fn data(name: &str) -> String {
    format!(
        "{}/../whipple/tests/data/yeadon/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn rider_inertia_prints_the_body_and_its_segments_as_json() {
    let meas = data("JasonYeadonMeas.txt");
    let cfg = data("JasonBrowserYeadonCFG.txt");
    let out = whipple(&[
        "rider-inertia",
        "--measurements",
        &meas,
        "--configuration",
        &cfg,
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    // The file's total mass (83.5 kg) scales the densities.
    assert!((v["body"]["mass_kg"].as_f64().unwrap() - 83.5).abs() < 1e-12);
    let segments = v["segments"].as_array().unwrap();
    let names: Vec<&str> = segments
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "P", "T", "C", "A1", "A2", "B1", "B2", "J1", "J2", "K1", "K2"
        ]
    );
    let sum: f64 = segments
        .iter()
        .map(|s| s["mass_kg"].as_f64().unwrap())
        .sum();
    assert!((sum - 83.5).abs() < 1e-12);
    // A symmetric configuration: the mass centre on the mid-plane; the forward lean
    // (somersault 0.175 rad) moves it to −y.
    let com: Vec<f64> = v["body"]["center_of_mass_m"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(
        com[0].abs() < 1e-15 && com[1] < 0.0 && com[2] > 0.0,
        "{com:?}"
    );
    // yeadon 2.0.1 (corrected, data/yeadon/expected.json): the body's Iyz.
    let iyz = v["body"]["inertia_kg_m2"][1][2].as_f64().unwrap();
    assert!((iyz - 2.368784176467583).abs() < 1e-11, "{iyz}");
}

#[test]
fn rider_inertia_table_names_every_segment() {
    let meas = data("CharlieYeadonMeas.txt");
    let text = stdout(&whipple(&["rider-inertia", "--measurements", &meas]));
    assert!(text.contains("configuration zero"), "{text}");
    for name in [
        "body",
        "P (pelvis)",
        "C (chest-head)",
        "K2 (right shank-foot)",
    ] {
        assert!(text.lines().any(|l| l == name), "{name} missing:\n{text}");
    }
    assert!(text.contains("78.745"), "{text}");
}

#[test]
fn rider_inertia_names_the_bad_measurement_and_its_line() {
    let original = std::fs::read_to_string(data("JasonYeadonMeas.txt")).unwrap();
    let bad = original.replace("Ls1p: 86.5", "Ls1p: 50");
    let line = bad.lines().position(|l| l.starts_with("Ls1p:")).unwrap() + 1;
    let dir = scratch("rider-inertia-bad");
    let path = dir.join("stadium.txt");
    std::fs::write(&path, bad).unwrap();
    let err = stderr_of_failure(&whipple(&[
        "rider-inertia",
        "--measurements",
        path.to_str().unwrap(),
    ]));
    assert!(err.contains(&format!(":{line}:")), "{err}");
    assert!(
        err.contains("Ls1p") && err.contains("not a stadium"),
        "{err}"
    );

    let cfg = std::fs::read_to_string(data("JasonBrowserYeadonCFG.txt"))
        .unwrap()
        .replace("K1K2flexion: 0.0", "K1K2flexion: 4");
    let cfg_path = dir.join("angle.txt");
    std::fs::write(&cfg_path, cfg).unwrap();
    let err = stderr_of_failure(&whipple(&[
        "rider-inertia",
        "--measurements",
        &data("JasonYeadonMeas.txt"),
        "--configuration",
        cfg_path.to_str().unwrap(),
    ]));
    assert!(
        err.contains("K1K2flexion") && err.contains("outside its range"),
        "{err}"
    );
}
