//! `whipple control hess` through the real binary: HumanControl's benchmark bicycle and gains at
//! one speed and against speed, the gains by Hess 2012's rules, and bad input.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::advanced::control::{
    CrossoverRules, HumanController, HumanLoop, Neuromuscular, Task, hess_gains,
};
use whipple::advanced::io::{Format, parse, read_gains};

const DATA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../whipple/tests/data/humancontrol"
);

fn path(name: &str) -> String {
    format!("{DATA}/{name}")
}

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&stdout(&whipple(args))).expect("JSON")
}

fn benchmark() -> whipple::BenchmarkParameters {
    let text = std::fs::read_to_string(path("BenchmarkPar.txt")).expect("the bicycle");
    parse(&text, Format::HumanControlTxt)
        .expect("parsed")
        .benchmark()
        .expect("checked")
}

#[test]
fn the_closed_loop_at_5_ms_is_the_librarys() {
    let (bike, gains) = (
        path("BenchmarkPar.txt"),
        path("gains/BenchmarkSteerGains.txt"),
    );
    let doc = json(&[
        "control", "hess", "--bike", &bike, "--gains", &gains, "--speed", "5", "--format", "json",
    ]);
    let table = read_gains(&std::fs::read_to_string(&gains).unwrap()).unwrap();
    let k = table.at(5.0).unwrap().gains;
    assert_eq!(doc["gains"]["kDelta"].as_f64(), Some(k.k_delta));
    let rider = HumanController::new(Task::Lateral, k, Neuromuscular::default()).unwrap();
    let expected = HumanLoop::new(&benchmark(), 5.0, &rider, &[])
        .unwrap()
        .eigenvalues()
        .unwrap();
    let got = doc["eigenvalues"].as_array().expect("eigenvalues");
    assert_eq!(got.len(), expected.len());
    for (z, e) in got.iter().zip(&expected) {
        assert_eq!((z[0].as_f64(), z[1].as_f64()), (Some(e.re), Some(e.im)));
    }
    assert_eq!(doc["stable"], true);
    assert_eq!(doc["extrapolated"], false);
    // The roll, heading and lateral loops cross over near Hess's 2, 1 and 0.5 rad/s.
    let loops = doc["loops"].as_array().expect("loops");
    let crossover = |name: &str| {
        loops.iter().find(|l| l["loop"] == name).expect(name)["crossover"]
            .as_f64()
            .expect("a crossover")
    };
    assert!((crossover("phi") - 2.0).abs() < 0.01);
    assert!((crossover("psi") - 1.0).abs() < 0.01);
    assert!((crossover("y") - 0.5).abs() < 0.01);
}

#[test]
fn the_rules_give_the_librarys_gains_and_a_sweep_has_every_speed() {
    let bike = path("BenchmarkPar.txt");
    let doc = json(&[
        "control", "hess", "--bike", &bike, "--rules", "--speed", "5", "--format", "json",
    ]);
    let k = hess_gains(
        &benchmark(),
        5.0,
        &Neuromuscular::default(),
        &CrossoverRules::default(),
    )
    .unwrap();
    assert_eq!(doc["gains"]["kDelta"].as_f64(), Some(k.k_delta));
    assert_eq!(doc["gains"]["kY"].as_f64(), Some(k.k_y));
    let sweep = json(&[
        "control",
        "hess",
        "--bike",
        &bike,
        "--gains",
        &path("gains/BenchmarkSteerGains.txt"),
        "--speeds",
        "3:6:0.5",
        "--format",
        "json",
    ]);
    let rows = sweep["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 7);
    assert_eq!(rows[6]["speed"].as_f64(), Some(6.0));
    // HumanControl's tabulated gains keep the lateral loop stable at these speeds.
    assert!(rows.iter().all(|r| r["stable"] == true));
}

#[test]
fn bad_input_is_refused_or_said() {
    let bike = path("BenchmarkPar.txt");
    let gains = path("gains/BenchmarkSteerGains.txt");
    let error = stderr_of_failure(&whipple(&[
        "control", "hess", "--bike", &bike, "--speed", "5",
    ]));
    assert!(
        error.contains("--gains") || error.contains("--rules"),
        "{error}"
    );
    let dir = scratch("hess-bad");
    let missing = dir.join("MissingSteerGains.txt");
    std::fs::write(
        &missing,
        "speed,kDelta,kPhiDot,kPhi,kPsi\n5,46,-0.05,12,0.18\n",
    )
    .unwrap();
    let error = stderr_of_failure(&whipple(&[
        "control",
        "hess",
        "--bike",
        &bike,
        "--gains",
        missing.to_str().unwrap(),
        "--speed",
        "5",
    ]));
    assert!(error.contains("--gains") && error.contains("kY"), "{error}");
    let error = stderr_of_failure(&whipple(&[
        "control",
        "hess",
        "--bike",
        &bike,
        "--rules",
        "--speed",
        "5",
        "--neuro-frequency",
        "-30",
    ]));
    assert!(error.contains("neuromuscular"), "{error}");
    let error = stderr_of_failure(&whipple(&[
        "control", "hess", "--bike", &bike, "--gains", &gains, "--speeds", "3:6:0",
    ]));
    assert!(error.contains("--speeds"), "{error}");
    // Outside the table's speeds: computed, and the extrapolation said.
    let output = whipple(&[
        "control", "hess", "--bike", &bike, "--gains", &gains, "--speed", "13",
    ]);
    assert!(output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("extrapolated"));
}
