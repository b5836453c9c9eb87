//! The field's files through the real binary: uncertainty printed, warnings on stderr and in
//! JSON, --strict, sensitivities, conversions.

use crate::common::{scratch, stderr_of_failure, stdout, whipple};

fn data(path: &str) -> String {
    format!(
        "{}/../whipple/tests/data/{path}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn speeds_print_the_uncertainty_of_a_measured_bicycle() {
    let out = stdout(&whipple(&[
        "speeds",
        "--bike",
        &data("bicycleparameters/FisherBenchmark.txt"),
    ]));
    assert!(
        out.contains("weave speed v_w        3.7981 ± 0.0764 m/s"),
        "{out}"
    );
    // Named as BicycleParameters names it, without the parameter set's suffix (issue 28).
    assert!(out.starts_with("Fisher: critical speeds"), "{out}");
    // The self-stable range's ends carry their σ as the speeds do (issue 28, item 2).
    assert!(
        out.contains("self-stable            3.7981 ± 0.0764 .. 6.119 ± 0.241 m/s"),
        "{out}"
    );
    let json: serde_json::Value = serde_json::from_str(&stdout(&whipple(&[
        "speeds",
        "--bike",
        &data("bicycleparameters/FisherBenchmark.txt"),
        "--format",
        "json",
    ])))
    .expect("JSON");
    assert!((json["weave_speed_sigma"].as_f64().unwrap_or(0.0) - 0.0764).abs() < 1e-3);
}

#[test]
fn warnings_go_to_stderr_and_json_and_strict_refuses() {
    let bike = data("bicycleparameters/BrowserBenchmark.txt");
    let output = whipple(&["speeds", "--bike", &bike, "--format", "json"]);
    assert!(output.status.success());
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(
        err.contains("warning: `IByy`") && err.contains("2.332 %"),
        "{err}"
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    assert_eq!(json["warnings"][0]["field"], "IByy");
    let err = stderr_of_failure(&whipple(&["speeds", "--bike", &bike, "--strict"]));
    assert!(err.contains("--strict"), "{err}");
}

#[test]
fn sensitivity_table_csv_json_and_tornado() {
    let csv = stdout(&whipple(&[
        "sensitivity",
        "--bike",
        "benchmark",
        "--format",
        "csv",
    ]));
    assert!(csv.starts_with("key,unit,value,d_weave_speed"), "{csv}");
    assert_eq!(csv.lines().count(), 27);
    let dir = scratch("tornado");
    let png = dir.join("tornado.png");
    stdout(&whipple(&[
        "sensitivity",
        "--bike",
        "schwinn-crown",
        "--speed",
        "5",
        "--plot",
        &png.to_string_lossy(),
    ]));
    assert!(
        std::fs::metadata(&png)
            .map(|m| m.len() > 1000)
            .unwrap_or(false)
    );
}

#[test]
fn field_formats_convert_and_read_back() {
    let dir = scratch("field-convert");
    for (to, name) in [
        ("bp-txt", "BrowserBenchmark.txt"),
        ("yaml", "browser.yml"),
        ("hc-txt", "BrowserPar.txt"),
    ] {
        let path = dir.join(name);
        stdout(&whipple(&[
            "convert",
            "--bike",
            &data("humancontrol/BrowserPar.txt"),
            "--to",
            to,
            "--out",
            &path.to_string_lossy(),
        ]));
        let a = stdout(&whipple(&[
            "speeds",
            "--bike",
            &path.to_string_lossy(),
            "--format",
            "json",
        ]));
        let b = stdout(&whipple(&[
            "speeds",
            "--bike",
            &data("humancontrol/BrowserPar.txt"),
            "--format",
            "json",
        ]));
        let (a, b): (serde_json::Value, serde_json::Value) = (
            serde_json::from_str(&a).expect("JSON"),
            serde_json::from_str(&b).expect("JSON"),
        );
        assert_eq!(a["weave_speed"], b["weave_speed"], "{to}");
    }
    let ambiguous = dir.join("bike.txt");
    std::fs::write(&ambiguous, "# nothing\n").expect("write");
    let err = stderr_of_failure(&whipple(&[
        "speeds",
        "--bike",
        &ambiguous.to_string_lossy(),
    ]));
    assert!(
        err.contains("--bike-format") && err.contains("hc-txt"),
        "{err}"
    );
}

/// Issue 28, item 14: a σ of 1e300 (a slip of the pen in a measured file) printed "± inf" in
/// `whipple speeds`, and the JSON output refused it. The propagated σ is now a scaled norm (no
/// overflow where the true value is finite), and a σ of a speed larger than the speed itself,
/// or past the largest double, is refused in both outputs with the parameter named as the file
/// writes it (`mB`) and its σ.
#[test]
fn issue_28_an_absurd_sigma_is_refused_naming_the_field_never_printed_as_inf() {
    let fisher = std::fs::read_to_string(data("bicycleparameters/FisherBenchmark.txt"))
        .expect("the Fisher file");
    let dir = scratch("absurd-sigma");
    for (line, sigma, field) in [
        ("mB = 4.5+/-0.02", "mB = 4.5+/-1e300", "`mB` = 1e300"),
        // ∂v/∂IBxx · σ is itself past f64::MAX.
        (
            "IBxx = 0.2825+/-0.00127383578938",
            "IBxx = 0.2825+/-1.7e308",
            "`IBxx` = 1.7e308",
        ),
    ] {
        assert!(fisher.contains(line), "{line}");
        let path = dir.join("AbsurdBenchmark.txt");
        std::fs::write(&path, fisher.replace(line, sigma)).expect("write");
        let bike = path.to_string_lossy().into_owned();
        for format in ["table", "json"] {
            let err = stderr_of_failure(&whipple(&["speeds", "--bike", &bike, "--format", format]));
            assert!(
                err.contains(field)
                    && err.contains("standard deviation")
                    && err.contains("σ of v_"),
                "{format}: {err}"
            );
            assert!(
                !err.contains("inf") && !err.contains("NaN"),
                "{format}: {err}"
            );
        }
    }
    // A large but sane σ (a tenth of the mass) still prints.
    let path = dir.join("WideBenchmark.txt");
    std::fs::write(&path, fisher.replace("mB = 4.5+/-0.02", "mB = 4.5+/-0.45")).expect("write");
    let out = stdout(&whipple(&["speeds", "--bike", &path.to_string_lossy()]));
    assert!(
        out.contains("weave speed v_w") && out.contains(" ± "),
        "{out}"
    );
    assert!(!out.contains("inf"), "{out}");
}

/// A principal set (Moore 2019) is read (converted, with a note), written back with
/// `--to principal-yaml` and read again to the same weave speed; a bicycle without the rider P
/// is refused, naming what it lacks.
#[test]
fn principal_sets_convert_and_read_back() {
    let dir = scratch("field-principal");
    let original = data("bicycleparameters-yaml/principal-browserjason.yml");
    let path = dir.join("principal.yml");
    let out = whipple(&[
        "convert",
        "--bike",
        &original,
        "--to",
        "principal-yaml",
        "--out",
        &path.to_string_lossy(),
    ]);
    stdout(&out);
    let notes = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        notes.contains("principal parameterization (Moore 2019)"),
        "{notes}"
    );
    let speeds = |bike: &str| -> serde_json::Value {
        serde_json::from_str(&stdout(&whipple(&[
            "speeds", "--bike", bike, "--format", "json",
        ])))
        .expect("JSON")
    };
    let (a, b) = (speeds(&path.to_string_lossy()), speeds(&original));
    let (wa, wb) = (
        a["weave_speed"].as_f64().expect("v_w"),
        b["weave_speed"].as_f64().expect("v_w"),
    );
    assert!((wa - wb).abs() < 1e-9 * wb, "{wa} against {wb}");
    let err = stderr_of_failure(&whipple(&[
        "convert",
        "--bike",
        "browser-jason",
        "--to",
        "principal-yaml",
    ]));
    assert!(err.contains("rider") && err.contains("mP"), "{err}");
}

/// `--to moore2012-yaml` writes Moore 2012's parameterization, which `--bike` reads back
/// (converted, with a note) to the same benchmark numbers; `--to m` writes a benchmark bicycle
/// as JBike6's bodies, read back to the same numbers; a bicycle with standard deviations is
/// refused for Moore's form, naming why.
#[test]
fn moore2012_and_m_files_of_a_benchmark_bicycle_read_back() {
    let dir = scratch("field-moore2012");
    let show = |bike: &str| -> serde_json::Value {
        let text = stdout(&whipple(&["convert", "--bike", bike, "--to", "json"]));
        let v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        v["benchmark"].clone()
    };
    let reference = show("benchmark");
    for (to, file) in [("moore2012-yaml", "moore.yml"), ("m", "bodies.m")] {
        let path = dir.join(file);
        let out = whipple(&[
            "convert",
            "--bike",
            "benchmark",
            "--to",
            to,
            "--out",
            &path.to_string_lossy(),
        ]);
        stdout(&out);
        let text = std::fs::read_to_string(&path).expect("written");
        if to == "m" {
            assert!(
                text.contains("mframe = 85.0;") && text.contains("mrider = 0.0;"),
                "{text}"
            );
        } else {
            assert!(text.starts_with("parameterization: Moore2012\n"), "{text}");
            // dtk's docstring prints d1 = 0.9534570696121849 for the benchmark bicycle.
            assert!(text.contains("  d1: 0.95345706961218"), "{text}");
        }
        let back = show(&path.to_string_lossy());
        for (key, value) in reference.as_object().expect("a table") {
            let (x, y) = (value.as_f64().unwrap(), back[key].as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(1.0),
                "{to} {key}: {x} vs {y}"
            );
        }
    }
    let out = whipple(&["speeds", "--bike", &dir.join("moore.yml").to_string_lossy()]);
    let notes = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(notes.contains("Moore 2012's parameterization"), "{notes}");
    let err = stderr_of_failure(&whipple(&[
        "convert",
        "--bike",
        "fisher",
        "--to",
        "moore2012-yaml",
    ]));
    assert!(err.contains("standard deviations"), "{err}");
}

/// A TOML file giving the front assembly's moment about the steer axis (`IAlamlam`) instead
/// of IHzz reads as the bicycle it was computed from; an impossible one is an error naming it.
#[test]
fn the_steer_axis_moment_stands_for_ihzz() {
    let dir = scratch("field-steer");
    let text = stdout(&whipple(&[
        "convert",
        "--bike",
        "benchmark",
        "--to",
        "toml",
    ]));
    // The benchmark bicycle's I_Aλλ by Meijaard 2007's A28 (through A's combined centre),
    // evaluated apart from whipple.
    let i_a = 0.15389731601426776_f64;
    let line = text
        .lines()
        .find(|l| l.starts_with("IHzz = "))
        .expect("IHzz line")
        .to_string();
    let steer = text.replace(&line, &format!("IAlamlam = {i_a:?}"));
    let path = dir.join("steer.toml");
    std::fs::write(&path, &steer).expect("write");
    let back = stdout(&whipple(&[
        "convert",
        "--bike",
        &path.to_string_lossy(),
        "--to",
        "json",
    ]));
    let v: serde_json::Value = serde_json::from_str(&back).expect("JSON");
    let ihzz = v["benchmark"]["IHzz"].as_f64().expect("IHzz");
    assert!((ihzz - 0.00708).abs() < 1e-14, "{ihzz}");
    std::fs::write(&path, text.replace(&line, "IAlamlam = 0.14")).expect("write");
    let err = stderr_of_failure(&whipple(&["speeds", "--bike", &path.to_string_lossy()]));
    assert!(
        err.contains("IAlamlam") && err.contains("the least the front assembly"),
        "{err}"
    );
    std::fs::write(
        &path,
        text.replace(&line, &format!("{line}\nIAlamlam = 0.3")),
    )
    .expect("write");
    let err = stderr_of_failure(&whipple(&["speeds", "--bike", &path.to_string_lossy()]));
    assert!(err.contains("give either IHzz"), "{err}");
}
