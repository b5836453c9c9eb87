//! `whipple rider` (the leaning rider) and `whipple control optimal-handling` through the real
//! binary: the numbers against the library's, the files written, and bad input.

use std::sync::atomic::AtomicBool;

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::advanced::control::{HandlingBound, OptimalHandlingSettings, optimal_handling};
use whipple::advanced::design::Parameter;
use whipple::advanced::nonlinear::LeanModel;
use whipple::advanced::parameters::{
    MOORE_RIDER_LEAN2012_KEYS, MooreRiderLean2012Parameters, RiderLeanParameters,
};

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&stdout(&whipple(args))).expect("JSON")
}

#[test]
fn the_leaning_riders_modes_are_the_librarys_beside_the_rigid_riders() {
    let doc = json(&["rider", "--speeds", "2:6:2", "--format", "json"]);
    let rows = doc["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 3);
    let model = LeanModel::new(&RiderLeanParameters::browser_jason()).expect("model");
    for row in rows {
        let v = row["speed"].as_f64().expect("speed");
        let expected = model.eigenvalues(v).expect("eigenvalues");
        let got = row["eigenvalues"].as_array().expect("eigenvalues");
        assert_eq!(got.len(), 6);
        for (z, e) in got.iter().zip(&expected) {
            assert_eq!(z[0].as_f64(), Some(e.re));
            assert_eq!(z[1].as_f64(), Some(e.im));
        }
        assert_eq!(
            row["rigid_rider_eigenvalues"].as_array().map(Vec::len),
            Some(4)
        );
    }
    // A free hinge with no stiffness: the upper body falls over it, an unstable mode.
    assert_eq!(rows[2]["stable"], false);
}

/// `--bike`: Jason's upper body split off any bicycle's rider (the library's split), the
/// modes the library's for that split; refused, saying why, where it does not fit.
#[test]
fn a_bicycle_with_its_rider_leans_with_jasons_upper_body() {
    let doc = json(&[
        "rider",
        "--bike",
        "schwinn-crown",
        "--speed",
        "5",
        "--hinge-stiffness",
        "800",
        "--format",
        "json",
    ]);
    let schwinn = whipple::presets::find("schwinn-crown")
        .expect("preset")
        .bicycle()
        .benchmark()
        .expect("benchmark");
    let jason = RiderLeanParameters::browser_jason().upper_body;
    let upper_body = whipple::advanced::parameters::UpperBody {
        stiffness: 800.0,
        ..jason
    };
    let p = RiderLeanParameters::split(&schwinn, upper_body).expect("split");
    let expected = LeanModel::new(&p)
        .expect("model")
        .eigenvalues(5.0)
        .expect("eigenvalues");
    let got = doc["rows"][0]["eigenvalues"]
        .as_array()
        .expect("eigenvalues");
    for (z, e) in got.iter().zip(&expected) {
        assert_eq!(z[0].as_f64(), Some(e.re));
        assert_eq!(z[1].as_f64(), Some(e.im));
    }
    let message = stderr_of_failure(&whipple(&["rider", "--bike", "benchmark", "--speed", "5"]));
    assert!(
        message.contains("cannot lean on benchmark") && message.contains("does not fit"),
        "{message}"
    );
    let message = stderr_of_failure(&whipple(&[
        "rider", "--bike", "browser", "--moore", "x.json", "--speed", "5",
    ]));
    assert!(message.contains("cannot be used with"), "{message}");
}

#[test]
fn a_moore_file_is_read_and_bad_ones_are_refused_naming_the_key() {
    let dir = scratch("rider-lean-moore");
    let values = MooreRiderLean2012Parameters::browser_jason().to_array();
    let mut object = serde_json::Map::new();
    for (k, v) in MOORE_RIDER_LEAN2012_KEYS.iter().zip(values) {
        object.insert((*k).into(), v.into());
    }
    let good = dir.join("jason.json");
    std::fs::write(&good, serde_json::Value::Object(object.clone()).to_string()).unwrap();
    let from_file = json(&[
        "rider",
        "--moore",
        good.to_str().unwrap(),
        "--speed",
        "5",
        "--format",
        "json",
    ]);
    let preset = json(&["rider", "--speed", "5", "--format", "json"]);
    assert_eq!(from_file["rows"], preset["rows"]);

    object.remove("d4");
    let missing = dir.join("missing.json");
    std::fs::write(
        &missing,
        serde_json::Value::Object(object.clone()).to_string(),
    )
    .unwrap();
    let error = stderr_of_failure(&whipple(&[
        "rider",
        "--moore",
        missing.to_str().unwrap(),
        "--speed",
        "5",
    ]));
    assert!(error.contains("d4") && error.contains("missing"), "{error}");

    object.insert("d4".into(), "tall".into());
    let text = dir.join("text.json");
    std::fs::write(&text, serde_json::Value::Object(object).to_string()).unwrap();
    let error = stderr_of_failure(&whipple(&[
        "rider",
        "--moore",
        text.to_str().unwrap(),
        "--speed",
        "5",
    ]));
    assert!(error.contains("d4") && error.contains("number"), "{error}");

    let error = stderr_of_failure(&whipple(&[
        "rider",
        "--speed",
        "5",
        "--hinge-stiffness",
        "-1",
    ]));
    assert!(error.contains("kLean"), "{error}");
}

#[test]
fn a_lean_torque_pulse_leans_the_rider_and_the_run_is_written_whole() {
    let dir = scratch("rider-lean-simulate");
    let csv = dir.join("lean.csv");
    let svg = dir.join("lean.svg");
    let out = stdout(&whipple(&[
        "rider",
        "--speed",
        "5",
        "--simulate",
        "2",
        "--lean-torque",
        "20",
        "--torque-duration",
        "0.5",
        "--hinge-stiffness",
        "800",
        "--hinge-damping",
        "50",
        "--out",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]));
    assert!(out.contains("at t = 2 s"), "{out}");
    let text = std::fs::read_to_string(&csv).expect("the CSV");
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,lean,steer,rider_lean,lean_rate,steer_rate,rider_lean_rate,energy")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().expect("a number")).collect())
        .collect();
    assert!(rows.len() > 10);
    // Pushed right about the hinge, the upper body leans right and the bicycle left.
    let early = rows.iter().find(|r| r[0] >= 0.2).expect("t = 0.2 s");
    assert!(early[3] > 0.0 && early[1] < 0.0, "{early:?}");
    assert!(
        std::fs::read_to_string(&svg)
            .expect("the figure")
            .contains("<svg")
    );

    // The free hinge: the upper body falls across the bicycle, and the run says so.
    let out = stdout(&whipple(&[
        "rider",
        "--speed",
        "5",
        "--simulate",
        "5",
        "--lean-torque",
        "5",
    ]));
    assert!(
        out.contains("the run ended: the rider's upper body fell across the bicycle at t = "),
        "{out}"
    );
    let error = stderr_of_failure(&whipple(&["rider", "--speed", "5", "--simulate", "-1"]));
    assert!(error.contains("--simulate"), "{error}");
}

#[test]
fn the_optimal_handling_search_prints_the_librarys_result() {
    let doc = json(&[
        "control",
        "optimal-handling",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--vary",
        "trail=0:0.2",
        "--vary",
        "head_angle_deg=60:85",
        "--starts",
        "3",
        "--format",
        "json",
    ]);
    let bike = whipple::presets::find("benchmark").unwrap().bicycle();
    let bounds = [
        HandlingBound {
            parameter: Parameter::find("trail", &bike).unwrap(),
            low: 0.0,
            high: 0.2,
        },
        HandlingBound {
            parameter: Parameter::find("head_angle", &bike).unwrap(),
            low: 60f64.to_radians(),
            high: 85f64.to_radians(),
        },
    ];
    let settings = OptimalHandlingSettings {
        starts: 3,
        ..OptimalHandlingSettings::at(5.0)
    };
    let library = optimal_handling(&bike, &bounds, &settings, &AtomicBool::new(false)).unwrap();
    assert_eq!(doc["best"]["cost"].as_f64(), Some(library.best.cost));
    let values = doc["best"]["values"].as_array().expect("values");
    assert_eq!(values[0].as_f64(), Some(library.best.values[0]));
    // The angle is shown in degrees, as it was typed.
    let head = values[1].as_f64().unwrap();
    assert!((head - library.best.values[1].to_degrees()).abs() < 1e-12);
    assert_eq!(doc["local_search"], true);
    assert_eq!(doc["starts"].as_array().map(Vec::len), Some(3));

    for (bad, word) in [
        ("speed=1:2", "speed"),
        ("trail=0.2:0", "LOW"),
        ("trail=0,1:0,2", "number"),
        ("mystery=0:1", "mystery"),
    ] {
        let error = stderr_of_failure(&whipple(&[
            "control",
            "optimal-handling",
            "--bike",
            "benchmark",
            "--speed",
            "5",
            "--vary",
            bad,
        ]));
        assert!(error.contains(word), "{bad}: {error}");
    }
}
