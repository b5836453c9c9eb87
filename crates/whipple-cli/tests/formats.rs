//! What a user reads, as README.md documents it: the default `eig` and `matrices` tables,
//! `show`, `draw` to SVG, the simulate CSV's exact columns; the simulation's failures (message,
//! non-zero exit status, samples kept); and files written whole through a temporary file and a
//! rename.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};
use whipple::{Canonical, presets};

/// The default `eig` table: a header naming the modes in the documented column order, one row
/// per speed, Meijaard et al. 2007's Table 2 to the ten decimals printed.
#[test]
fn eig_table_shows_table_2() {
    let out = stdout(&whipple(&[
        "eig",
        "--bike",
        "benchmark",
        "--speeds",
        "4:6:1",
    ]));
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].starts_with("benchmark: eigenvalues"), "{out}");
    let header: Vec<&str> = lines[1].split_whitespace().collect();
    assert_eq!(
        header,
        [
            "v",
            "weave",
            "(1)",
            "weave",
            "(2)",
            "capsize",
            "(3)",
            "castering",
            "(4)"
        ]
    );
    assert_eq!(lines.len(), 5, "{out}");
    // v, weave re + im i, weave re - im i, capsize, castering (Table 2, 5 m/s).
    let row: Vec<&str> = lines[3].split_whitespace().collect();
    assert_eq!(
        row,
        [
            "5.0000",
            "-0.7753418822",
            "+",
            "4.4648677138i",
            "-0.7753418822",
            "-",
            "4.4648677138i",
            "-0.3228664290",
            "-14.0783896928"
        ]
    );
}

/// The default `matrices` table prints M, C1, K0, K2 in shortest round-trip form: every entry
/// reads back as the library's value, bit for bit.
#[test]
fn matrices_table_reads_back_as_the_matrices() -> whipple::Result<()> {
    let out = stdout(&whipple(&["matrices", "--bike", "benchmark"]));
    let c = Canonical::new(&presets::find("benchmark")?.bicycle().benchmark()?)?;
    assert!(out.contains("g = 9.81"), "{out}");
    let mut lines = out.lines().skip(1);
    for (name, m) in [("M", c.m), ("C1", c.c1), ("K0", c.k0), ("K2", c.k2)] {
        assert_eq!(lines.next(), Some(format!("{name} =").as_str()));
        for i in 0..2 {
            let row: Vec<f64> = lines
                .next()
                .expect("a row")
                .trim_matches(|ch: char| ch == '[' || ch == ']' || ch.is_whitespace())
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            assert_eq!(row, [m[(i, 0)], m[(i, 1)]], "{name} row {i}");
        }
    }
    Ok(())
}

/// `show` lists both forms of a JBike6 bicycle; every value it prints reads back as the
/// preset's (JBike6 form) or the conversion's (benchmark form).
#[test]
fn show_lists_every_parameter_of_both_forms() -> whipple::Result<()> {
    let out = stdout(&whipple(&["show", "--bike", "schwinn-crown"]));
    let value = |key: &str| -> f64 {
        out.lines()
            .find_map(|l| {
                let mut words = l.split_whitespace();
                (words.next() == Some(key)).then(|| words.next())?
            })
            .unwrap_or_else(|| panic!("`{key}` is not listed:\n{out}"))
            .parse()
            .expect("a number")
    };
    let j = presets::schwinn_crown_jbike6();
    for (key, expected) in [
        ("wheelbase", j.wheelbase),
        ("head_angle", j.head_angle),
        ("trail", j.trail),
        ("gravity", j.gravity),
        ("Drearwheel", j.rear_wheel.diameter),
        ("Irider(1)", j.rider.inertia[0]),
        ("alphaIrider", j.rider.alpha),
        ("ucmbasket", j.basket.ucm),
        ("vcmfork", j.fork.vcm),
        ("Ibasket(3)", j.basket.inertia[2]),
        ("ycmrack", j.rack.ycm),
    ] {
        assert_eq!(value(key), expected, "{key}");
    }
    for (key, expected) in j.to_benchmark()?.fields() {
        assert_eq!(value(key), expected, "{key}");
    }
    Ok(())
}

/// `draw --out FILE.svg`: an SVG with both wheels and each body's centre of mass labelled with
/// its mass, as JBike6 draws it, and the geometry written on it.
#[test]
fn draw_writes_the_side_view_as_svg() {
    let dir = scratch("draw-svg");
    let path = dir.join("crown.svg");
    stdout(&whipple(&[
        "draw",
        "--bike",
        "schwinn-crown",
        "--out",
        &path.to_string_lossy(),
    ]));
    let svg = std::fs::read_to_string(&path).expect("the drawing was written");
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<circle").count(), 2, "two wheels");
    for label in [
        "schwinn-crown",
        "w = 1.016 m",
        "c = 0.091 m",
        "head angle 71.0°",
        "rear wheel 1.82 kg",
        "front wheel 1.82 kg",
        "rider 80 kg",
        "frame 2.5 kg",
        "rack 2 kg",
        "fork 1.5 kg",
        "basket 1.5 kg",
    ] {
        assert!(svg.contains(label), "the drawing shows `{label}`");
    }
}

const CSV_HEADER: &str = "t,lean,steer,lean_rate,steer_rate,yaw,x,y,speed,energy,position_residual,velocity_residual,rear_normal,rear_longitudinal,rear_lateral,front_normal,front_longitudinal,front_lateral,front_x,front_y";

fn csv_rows(text: &str) -> Vec<Vec<f64>> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(CSV_HEADER), "the documented header");
    lines
        .map(|l| {
            let row: Vec<f64> = l.split(',').map(|x| x.parse().expect("a number")).collect();
            assert_eq!(row.len(), 20, "{l}");
            row
        })
        .collect()
}

/// The simulate CSV has exactly the 20 documented columns, with the documented meaning: at
/// upright running the normal forces carry the weight (rear (w − x_T)/w of it), friction is
/// zero, the front contact is a wheelbase ahead; the rear contact moves at the speed.
#[test]
fn simulate_csv_has_the_documented_columns() {
    let out = stdout(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "5",
        "--duration",
        "0.01",
        "--format",
        "csv",
    ]));
    let rows = csv_rows(&out);
    assert_eq!(rows.len(), 11);
    let first = &rows[0];
    let b = whipple::BenchmarkParameters::meijaard2007();
    let m_t = b.m_r + b.m_b + b.m_h + b.m_f;
    let x_t = (b.m_b * b.x_b + b.m_h * b.x_h + b.m_f * b.w) / m_t;
    let weight = m_t * b.g;
    let close = |x: f64, y: f64| (x - y).abs() < 1e-9 * y.abs().max(1.0);
    assert!(
        close(first[12], weight * (b.w - x_t) / b.w),
        "rear normal {}",
        first[12]
    );
    assert!(
        close(first[15], weight * x_t / b.w),
        "front normal {}",
        first[15]
    );
    for k in [13, 14, 16, 17] {
        assert!(first[k].abs() < 1e-9, "friction {k}: {}", first[k]);
    }
    assert!(
        close(first[18], b.w) && first[19].abs() < 1e-12,
        "front contact"
    );
    let last = &rows[10];
    assert!(close(last[0], 0.01) && close(last[6], 0.05) && close(last[8], 5.0));
    assert!(close(last[18], b.w + 0.05));
    assert!(
        rows.iter().all(|r| r[10] < 1e-12 && r[11] < 1e-12),
        "residuals"
    );
}

/// The README's promise for a run that fails: a message naming what happened and when, a
/// non-zero exit status, and the samples computed before it written.
#[test]
fn a_failed_simulation_says_why_exits_non_zero_and_keeps_its_samples() {
    let dir = scratch("simulate-failures");
    let cases: [(&[&str], &str, usize); 3] = [
        (
            &["--steer-torque", "5000", "--dt", "0.05"],
            "the projection onto the constraints diverged at t = 0.0500 s",
            1,
        ),
        (
            &["--steer-torque", "1/(t-0.5)", "--dt", "0.01"],
            "the state became non-finite at t = 0.5000 s",
            50,
        ),
        (
            &[
                "--steer-torque",
                "1/(t-0.5)",
                "--integrator",
                "adaptive",
                "--ignore-lift-off",
            ],
            "the adaptive step size became too small at t = 0.5000 s",
            0,
        ),
    ];
    for (k, (extra, words, samples)) in cases.into_iter().enumerate() {
        let path = dir.join(format!("run{k}.csv"));
        let path_text = path.to_string_lossy().into_owned();
        let mut args = vec![
            "simulate",
            "--bike",
            "benchmark",
            "--speed",
            "5",
            "--duration",
            "1",
            "--format",
            "csv",
            "--out",
            &path_text,
        ];
        args.extend_from_slice(extra);
        let err = stderr_of_failure(&whipple(&args));
        assert!(err.contains(words), "{extra:?}: {err}");
        assert!(
            err.contains("the samples computed before that were written"),
            "{err}"
        );
        let rows = csv_rows(&std::fs::read_to_string(&path).expect("the samples were written"));
        if samples > 0 {
            assert_eq!(rows.len(), samples, "{extra:?}");
        } else {
            assert!(rows.len() > 10, "{extra:?}: {}", rows.len());
        }
        assert_eq!(rows[0][0], 0.0);
        assert!(rows.last().is_some_and(|r| r[0] < 0.5));
    }
}

/// `--fall-angle`: the run ends as a fall when |lean| passes it (30° at 3 m/s, before the rear
/// wheel would lift off at about 41°), at the time the independent reference gives
/// (tests/data/references.json: 1.482762 s), as the outcome rather than a failure.
#[test]
fn the_fall_angle_option_ends_the_run_there() {
    let out = whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "3",
        "--lean-rate",
        "0.5",
        "--duration",
        "5",
        "--fall-angle",
        "30",
    ]);
    let text = stdout(&out);
    assert!(
        text.contains("fell: |lean| passed the fall angle at t = 1.4828 s (lean -30.00 deg)"),
        "{text}"
    );
    let text = stdout(&whipple(&[
        "simulate",
        "--bike",
        "benchmark",
        "--speed",
        "3",
        "--lean-rate",
        "0.5",
        "--duration",
        "5",
    ]));
    assert!(
        text.contains("the rear wheel's normal force turned negative at t = 1.6036 s"),
        "{text}"
    );
}

/// A file is written through a temporary file beside it and a rename: an existing file is
/// replaced whole, and a target that is not a regular file (a directory) is refused, left as
/// it was, with no temporary file left behind.
#[test]
fn output_files_are_written_whole_through_a_rename() {
    let dir = scratch("atomic-rename");
    let target = dir.join("eig.csv");
    std::fs::write(
        &target,
        "old contents that are longer than nothing\n".repeat(100),
    )
    .expect("write");
    let args = |out: &str| {
        vec![
            "eig".to_string(),
            "--bike".into(),
            "benchmark".into(),
            "--speeds".into(),
            "0:1:0.5".into(),
            "--format".into(),
            "csv".into(),
            "--out".into(),
            out.to_string(),
        ]
    };
    let run = |out: &str| {
        let a = args(out);
        whipple(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    stdout(&run(&target.to_string_lossy()));
    let on_stdout = {
        let mut a = args("-");
        a.truncate(7);
        stdout(&whipple(&a.iter().map(String::as_str).collect::<Vec<_>>()))
    };
    assert_eq!(
        std::fs::read_to_string(&target).expect("read"),
        on_stdout,
        "the file holds exactly the new table"
    );
    let blocked = dir.join("blocked");
    std::fs::create_dir(&blocked).expect("mkdir");
    std::fs::write(blocked.join("keep"), "x").expect("write");
    let err = stderr_of_failure(&run(&blocked.to_string_lossy()));
    assert!(err.contains("blocked"), "{err}");
    assert!(blocked.is_dir() && blocked.join("keep").exists());
    let names: Vec<String> = std::fs::read_dir(&dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        names.iter().all(|n| !n.ends_with(".tmp")),
        "no temporary file left: {names:?}"
    );
}
