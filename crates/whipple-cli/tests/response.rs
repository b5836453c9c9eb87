//! `whipple response bode`: the real binary against the library's transfer functions and
//! frequency responses, its files, and its refusals naming the option.

use std::fs;

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::BenchmarkParameters;
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};

fn lean_from_steer_torque(v: f64) -> whipple::advanced::linear::TransferFunction {
    let request = SystemRequest {
        states: vec![],
        inputs: vec![Input::SteerTorque],
        outputs: vec![Output::State(StateVariable::Lean)],
    };
    LinearSystem::new(&BenchmarkParameters::meijaard2007(), v, &request)
        .expect("system")
        .transfer_function(0, 0)
        .expect("transfer function")
}

#[test]
fn bode_prints_poles_zeros_and_gains_marking_right_half_plane_zeros() {
    let out = whipple(&[
        "response",
        "bode",
        "--bike",
        "benchmark",
        "--speeds",
        "0.3,3,7",
        "--input",
        "steer_torque",
        "--output",
        "lean",
        "--output",
        "front_contact_y",
    ]);
    let text = stdout(&out);
    // One block per speed and pair.
    assert_eq!(text.matches("\nv = ").count(), 6, "{text}");
    let block = |head: &str| {
        let start = text
            .find(head)
            .unwrap_or_else(|| panic!("{head} in {text}"));
        let rest = &text[start..];
        rest[..rest[1..].find("\nv = ").map_or(rest.len(), |e| e + 1)].to_string()
    };
    // Steer torque → lean: non-minimum-phase below √(−g K₀₁₂ / K₂₁₂) ≈ 0.577 m/s only.
    assert!(block("v = 0.3 m/s, steer_torque → lean").contains("(RHP)"));
    assert!(!block("v = 3 m/s, steer_torque → lean").contains("(RHP)"));
    assert!(!block("v = 7 m/s, steer_torque → lean").contains("(RHP)"));
    // The front contact first moves the wrong way at every speed.
    assert!(block("v = 7 m/s, steer_torque → front_contact_y").contains("(RHP)"));
    assert!(
        block("v = 7 m/s, steer_torque → front_contact_y").contains("static gain: none"),
        "an integrator"
    );
    // The gain and the static gain are the library's numbers as results print.
    let g = lean_from_steer_torque(3.0);
    let b = block("v = 3 m/s, steer_torque → lean");
    let number = |x: f64| whipple_front::format::number(x).expect("finite");
    assert!(
        b.contains(&format!("gain:        {} rad/(N m)", number(g.gain()))),
        "{b}"
    );
    assert!(
        b.contains(&format!(
            "static gain: {} rad/(N m)",
            number(g.static_gain().expect("finite"))
        )),
        "{b}"
    );
    for z in g.zeros().expect("zeros") {
        assert!(b.contains(&number(z.re)), "{b}");
    }
}

#[test]
fn bode_csv_holds_the_library_response_and_the_figure_is_drawn() {
    let dir = scratch("response-bode");
    let csv = dir.join("bode.csv");
    let png = dir.join("bode.png");
    let svg = dir.join("bode.svg");
    let args = |figure: &std::path::Path| {
        whipple(&[
            "response",
            "bode",
            "--bike",
            "benchmark",
            "--speeds",
            "3,5,7",
            "--input",
            "steer_torque",
            "--output",
            "lean",
            "--frequencies",
            "0.1:100:50",
            "--out",
            csv.to_str().expect("utf-8"),
            "--figure",
            figure.to_str().expect("utf-8"),
        ])
    };
    stdout(&args(&png));
    let bytes = fs::read(&png).expect("png");
    assert_eq!(&bytes[1..4], b"PNG");
    stdout(&args(&svg));
    let drawing = fs::read_to_string(&svg).expect("svg");
    for speed in [
        "3 m/s",
        "5 m/s",
        "7 m/s",
        "frequency ω [rad/s]",
        "phase [deg]",
    ] {
        assert!(drawing.contains(speed), "{speed}");
    }
    let text = fs::read_to_string(&csv).expect("csv");
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("speed_m_s,input,output,frequency_rad_s,magnitude,magnitude_db,phase_deg")
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    assert_eq!(rows.len(), 3 * 50);
    let grid = whipple_front::system::parse_log_grid("0.1:100:50").expect("grid");
    for (k, v) in [3.0, 5.0, 7.0].into_iter().enumerate() {
        let f = lean_from_steer_torque(v)
            .frequency_response(&grid)
            .expect("response");
        for j in 0..50 {
            let row = &rows[k * 50 + j];
            let x = |c: usize| row[c].parse::<f64>().expect("number");
            assert_eq!(
                (x(0), row[1].as_str(), row[2].as_str()),
                (v, "steer_torque", "lean")
            );
            assert_eq!(x(3), grid[j]);
            // Printed with the shortest digits that read back exactly.
            assert_eq!(x(4), f.magnitude[j]);
            assert_eq!(x(5), f.magnitude_db[j]);
            assert_eq!(x(6), f.phase[j].to_degrees());
        }
    }
}

#[test]
fn bode_in_hz_says_so_in_the_header_and_scales_the_grid() {
    let dir = scratch("response-bode-hz");
    let csv = dir.join("bode.csv");
    stdout(&whipple(&[
        "response",
        "bode",
        "--bike",
        "benchmark",
        "--speeds",
        "5",
        "--input",
        "steer_torque",
        "--output",
        "lean",
        "--frequencies",
        "1:1:1",
        "--hz",
        "--out",
        csv.to_str().expect("utf-8"),
    ]));
    let text = fs::read_to_string(&csv).expect("csv");
    let mut lines = text.lines();
    assert!(lines.next().expect("header").contains(",frequency_hz,"));
    let row: Vec<f64> = lines
        .next()
        .expect("row")
        .split(',')
        .filter_map(|x| x.parse().ok())
        .collect();
    let f = lean_from_steer_torque(5.0)
        .frequency_response(&[std::f64::consts::TAU])
        .expect("response");
    assert_eq!(row[1], 1.0);
    assert_eq!(row[2], f.magnitude[0]);
}

#[test]
fn bode_json_lists_each_pair() {
    let out = whipple(&[
        "response",
        "bode",
        "--bike",
        "benchmark",
        "--speeds",
        "0.3,7",
        "--input",
        "steer_torque",
        "--output",
        "lean",
        "--format",
        "json",
    ]);
    let doc: serde_json::Value = serde_json::from_str(&stdout(&out)).expect("json");
    let pairs = doc["pairs"].as_array().expect("pairs");
    assert_eq!(pairs.len(), 2);
    assert_eq!(pairs[0]["right_half_plane_zeros"], 1);
    assert_eq!(pairs[1]["right_half_plane_zeros"], 0);
    assert_eq!(pairs[0]["poles"].as_array().expect("poles").len(), 4);
}

#[test]
fn bad_input_is_refused_naming_the_option_and_nothing_is_written() {
    let dir = scratch("response-bode-bad");
    let csv = dir.join("bode.csv");
    let csv_arg = csv.to_str().expect("utf-8");
    let base = ["response", "bode", "--bike", "benchmark", "--out", csv_arg];
    let run = |extra: &[&str]| {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        stderr_of_failure(&whipple(&args))
    };
    let e = run(&["--input", "steer_torque", "--output", "heading"]);
    assert!(e.contains("--output") && e.contains("yaw_rate"), "{e}");
    let e = run(&["--input", "steer", "--output", "lean"]);
    assert!(e.contains("--input") && e.contains("steer_torque"), "{e}");
    for grid in ["0:10:5", "1:nan:5", "1:10", "10:1:5", "1:10:0"] {
        let e = run(&[
            "--input",
            "steer_torque",
            "--output",
            "lean",
            "--frequencies",
            grid,
        ]);
        assert!(e.contains("--frequencies"), "{grid}: {e}");
    }
    let e = run(&[
        "--input",
        "steer_torque",
        "--output",
        "lean",
        "--speeds",
        "3,inf",
    ]);
    assert!(e.contains("--speeds"), "{e}");
    // A point inside nothing: under the road, or two metres ahead of the front wheel.
    let e = run(&["--input", "lateral_force:0.3,0.5", "--output", "lean"]);
    assert!(
        e.contains("--input") && e.contains("below the ground"),
        "{e}"
    );
    let e = run(&[
        "--input",
        "steer_torque",
        "--output",
        "rear_frame_point_y:3.4,-1",
    ]);
    assert!(
        e.contains("--output") && e.contains("outside the bicycle") && e.contains("1.370 m"),
        "{e}"
    );
    assert!(!csv.exists(), "no file after a refusal");
}

/// `response step`: the CSV's samples equal the library's exact response bit for bit as printed,
/// the step settles at the static gain where the bicycle is stable (5 m/s), and the path
/// columns carry the run v t.
#[test]
fn step_writes_the_exact_response_and_settles_at_the_static_gain() {
    let dir = scratch("response-step");
    let csv = dir.join("step.csv");
    let figure = dir.join("step.png");
    let out = stdout(&whipple(&[
        "response",
        "step",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--input",
        "steer_torque",
        "--amplitude",
        "0.01",
        "--output",
        "lean",
        "--duration",
        "60",
        "--samples",
        "61",
        "--out",
        csv.to_str().unwrap(),
        "--figure",
        figure.to_str().unwrap(),
    ]));
    assert!(out.contains("a step of 0.01 N m in steer_torque"), "{out}");
    let text = fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t_s,lean,path_x_m,path_y_m,path_yaw_rad"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 61);
    let static_gain = lean_from_steer_torque(5.0).static_gain().unwrap();
    let last = &rows[60];
    assert_eq!((last[0], last[2]), (60.0, 300.0), "t and x = v t");
    assert!(
        (last[1] - 0.01 * static_gain).abs() < 1e-9 * static_gain.abs(),
        "{} vs {}",
        last[1],
        0.01 * static_gain
    );
    let png = fs::read(&figure).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    // The heading has turned far: the summary says where the linear path stops holding.
    assert!(out.contains("the linear path"), "{out}");
}

/// `response manoeuvre`: one call runs both models; halving the pulse divides the lean
/// difference by about 8 (the amplitude cubed).
#[test]
fn manoeuvre_runs_both_models_and_the_difference_scales_as_the_cube() {
    let dir = scratch("response-manoeuvre");
    let lean_difference = |amplitude: &str, name: &str| -> f64 {
        let csv = dir.join(name);
        stdout(&whipple(&[
            "response",
            "manoeuvre",
            "--bike",
            "benchmark",
            "--speed",
            "5",
            "--steer-torque",
            &format!("pulse:0:0.5:{amplitude}"),
            "--duration",
            "3",
            "--samples",
            "61",
            "--rtol",
            "1e-12",
            "--out",
            csv.to_str().unwrap(),
        ]));
        let text = fs::read_to_string(&csv).unwrap();
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        let column = header.iter().position(|h| *h == "difference_lean").unwrap();
        text.lines()
            .skip(1)
            .map(|l| {
                l.split(',')
                    .nth(column)
                    .unwrap()
                    .parse::<f64>()
                    .unwrap()
                    .abs()
            })
            .fold(0.0, f64::max)
    };
    let ratio = lean_difference("0.1", "a.csv") / lean_difference("0.05", "b.csv");
    assert!((ratio - 8.0).abs() < 0.1, "{ratio}");
    let figure = dir.join("pulse.svg");
    let out = stdout(&whipple(&[
        "response",
        "manoeuvre",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--steer-torque",
        "pulse:0:0.5:1",
        "--figure",
        figure.to_str().unwrap(),
    ]));
    assert!(
        out.contains("non-linear model") && out.contains("rear_y"),
        "{out}"
    );
    assert!(
        fs::read_to_string(&figure)
            .unwrap()
            .contains("non-linear − linear")
    );
}

#[test]
fn time_responses_refuse_bad_input_naming_the_option() {
    let dir = scratch("response-time-bad");
    let never = dir.join("never.csv");
    for (args, words) in [
        (
            vec!["step", "--speed", "5", "--input", "steer"],
            vec!["--input", "unknown input"],
        ),
        (
            vec![
                "step",
                "--speed",
                "5",
                "--input",
                "steer_torque",
                "--samples",
                "1",
            ],
            vec!["--samples"],
        ),
        (
            vec!["impulse", "--speed", "nan", "--input", "steer_torque"],
            vec!["--speed"],
        ),
        (
            vec!["initial", "--speed", "5", "--lean", "1", "--duration", "-1"],
            vec!["--duration"],
        ),
        (
            vec!["manoeuvre", "--speed", "5", "--steer-torque", "pulse:0:0:1"],
            vec!["--steer-torque", "duration"],
        ),
        (vec!["manoeuvre", "--speed", "5"], vec!["nothing happens"]),
        (
            vec!["manoeuvre", "--speed", "5", "--lean-torque", "wave:1"],
            vec!["--lean-torque", "pulse:T:D:A"],
        ),
    ] {
        let mut full = vec!["response"];
        full.extend(&args[..1]);
        full.extend(["--bike", "benchmark", "--out", never.to_str().unwrap()]);
        full.extend(&args[1..]);
        let e = stderr_of_failure(&whipple(&full));
        for w in &words {
            assert!(e.contains(w), "{args:?}: {w}: {e}");
        }
        assert!(!never.exists(), "{args:?} wrote a file");
    }
}

/// `--gains`: the closed loop's transfer functions. Their poles are the closed-loop eigenvalues
/// `control feedback` prints at the same speed, and the steer torque the loop applies has the
/// unit gain at high frequency (u = r − K x, D = 1) and the library's static gain.
#[test]
fn bode_with_gains_gives_the_closed_loop() {
    let json = |args: &[&str]| -> serde_json::Value {
        serde_json::from_str(&stdout(&whipple(args))).expect("JSON")
    };
    let bode = json(&[
        "response",
        "bode",
        "--bike",
        "benchmark",
        "--speeds",
        "5",
        "--input",
        "steer_torque",
        "--output",
        "lean",
        "--output",
        "steer_torque",
        "--gains",
        "-100,10,-20,0",
        "--format",
        "json",
    ]);
    assert_eq!(
        bode["gains"],
        serde_json::json!([[-100.0, 10.0, -20.0, 0.0]])
    );
    let feedback = json(&[
        "control",
        "feedback",
        "--bike",
        "benchmark",
        "--gains",
        "-100,10,-20,0",
        "--speeds",
        "5:5:1",
        "--format",
        "json",
    ]);
    let mut expected: Vec<(f64, f64)> = feedback["rows"][0]["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| (z["re"].as_f64().unwrap(), z["im"].as_f64().unwrap()))
        .collect();
    expected.sort_by(|a, b| a.partial_cmp(b).unwrap());
    for pair in bode["pairs"].as_array().unwrap() {
        let mut poles: Vec<(f64, f64)> = pair["poles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|z| (z[0].as_f64().unwrap(), z[1].as_f64().unwrap()))
            .collect();
        poles.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(poles.len(), 4, "{pair}");
        for (p, q) in poles.iter().zip(&expected) {
            assert!(
                (p.0 - q.0).abs() + (p.1 - q.1).abs() < 1e-12 * 20.0,
                "{p:?} vs {q:?}"
            );
        }
    }
    let applied = &bode["pairs"][1];
    assert_eq!(applied["output"], "steer_torque");
    assert_eq!(applied["gain"], 1.0);
    // The library's own closed loop, the same number.
    let request = SystemRequest {
        states: vec![],
        inputs: vec![Input::SteerTorque],
        outputs: vec![Output::Input(Input::SteerTorque)],
    };
    let k = nalgebra::DMatrix::from_row_slice(1, 4, &[-100.0, 10.0, -20.0, 0.0]);
    let closed = whipple::advanced::control::ClosedLoop::new(
        &BenchmarkParameters::meijaard2007(),
        &request,
        whipple::advanced::control::Gains::Constant(k),
    )
    .unwrap();
    let static_gain = closed
        .system(5.0)
        .unwrap()
        .transfer_function(0, 0)
        .unwrap()
        .static_gain()
        .unwrap();
    assert_eq!(applied["static_gain"].as_f64().unwrap(), static_gain);
    // K of the wrong shape is refused naming --gains.
    let refused = stderr_of_failure(&whipple(&[
        "response",
        "bode",
        "--bike",
        "benchmark",
        "--speeds",
        "5",
        "--input",
        "steer_torque",
        "--output",
        "lean",
        "--gains",
        "1,2,3",
    ]));
    assert!(
        refused.contains("--gains") && refused.contains("1 × 4"),
        "{refused}"
    );
}
