//! BicycleParameters' principal parameterization (Moore 2019): its Browser + Jason set read and
//! compared with BicycleParameters' own conversion, the conversion inverted, the principal
//! YAML written and read back, and the refusals.

use std::path::{Path, PathBuf};

use whipple::advanced::io::{Format, parse, principal_yaml, write};
use whipple::advanced::parameters::{PRINCIPAL_KEYS, PrincipalBody, PrincipalParameters};
use whipple::{BenchmarkParameters, Error, presets};

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bicycleparameters-yaml/principal-browserjason.yml")
}

fn text() -> String {
    std::fs::read_to_string(file()).unwrap_or_default()
}

/// The file's `values:` read by a plain split, independently of the crate's reader.
fn principal_from_file() -> Result<PrincipalParameters, Box<dyn std::error::Error>> {
    let text = text();
    let value = |key: &str| -> Result<f64, Box<dyn std::error::Error>> {
        let prefix = format!("  {key}:");
        let line = text
            .lines()
            .find(|l| l.starts_with(&prefix))
            .ok_or(format!("no {key}"))?;
        Ok(line[prefix.len()..].trim().parse()?)
    };
    let mut v = [0.0; 35];
    for (slot, key) in v.iter_mut().zip(PRINCIPAL_KEYS) {
        *slot = value(key)?;
    }
    Ok(PrincipalParameters::from_array(v))
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1e-300)
}

fn assert_benchmark_close(a: &BenchmarkParameters, b: &BenchmarkParameters, rel: f64) {
    for (i, (x, y)) in a.to_array().iter().zip(b.to_array()).enumerate() {
        assert!(close(*x, y, rel), "parameter {i}: {x} against {y}");
    }
}

/// BicycleParameters 1.5.2's conversion of `principal-browserjason.yml`, computed with
///
/// ```text
/// python -c 'import yaml; from bicycleparameters.parameter_sets import Moore2019ParameterSet as S
/// d = yaml.safe_load(open("principal-browserjason.yml"))
/// b = S({k: float(v) for k, v in d["values"].items()}).to_parameterization("Meijaard2007").parameters
/// print({k: repr(float(v)) for k, v in b.items()})'
/// ```
fn bicycleparameters_conversion() -> BenchmarkParameters {
    BenchmarkParameters {
        w: 1.121,
        c: 0.068581,
        lambda: 0.39968,
        g: 9.81,
        r_r: 0.34096,
        m_r: 3.11,
        i_rxx: 0.09040847750000001,
        i_ryy: 0.152390776256,
        x_b: 0.31156450299914307,
        z_b: -1.039734387317909,
        m_b: 93.36,
        i_bxx: 14.29206481301247,
        i_byy: 15.364343852477893,
        i_bzz: 3.039936346019427,
        i_bxz: -1.6214426214717788,
        x_h: 0.86695,
        z_h: -0.74824,
        m_h: 3.22,
        i_hxx: 0.25335447184108945,
        i_hyy: 0.24582024179999998,
        i_hzz: 0.09556607572891058,
        i_hxz: -0.07202300071642019,
        r_f: 0.34353,
        m_f: 2.02,
        i_fxx: 0.088379219578,
        i_fyy: 0.149217004282,
    }
}

#[test]
fn principal_browser_jason_equals_bicycleparameters_conversion() -> TestResult {
    let bike = parse(&text(), Format::Yaml)?;
    let checked = bike.check()?;
    assert_benchmark_close(&checked.benchmark, &bicycleparameters_conversion(), 1e-12);
    assert!(
        checked
            .notices
            .iter()
            .any(|n| n.field == "parameterization" && n.message.contains("principal")),
        "{:?}",
        checked.notices
    );
    // The rider is kept, and the operating speed.
    for key in ["mP", "alphaP", "lP", "wP", "v"] {
        assert!(bike.extras.iter().any(|e| e.key == key), "{key}");
    }
    // The typed conversion gives the same numbers as the reader.
    assert_benchmark_close(
        &principal_from_file()?.to_benchmark(),
        &checked.benchmark,
        0.0,
    );
    Ok(())
}

/// BicycleParameters' own set follows the choice `from_benchmark` makes (aa the larger
/// in-plane moment, α in (−π/2, π/2]), so its set comes back to round-off.
#[test]
fn principal_set_round_trips_through_the_benchmark_form() -> TestResult {
    let p = principal_from_file()?;
    let back = PrincipalParameters::from_benchmark(&p.to_benchmark(), &p.p, p.l_p, p.w_p)?;
    for (i, (x, y)) in p.to_array().iter().zip(back.to_array()).enumerate() {
        assert!(
            close(*x, y, 1e-12),
            "{}: {x} against {y}",
            PRINCIPAL_KEYS[i]
        );
    }
    Ok(())
}

#[test]
fn benchmark_round_trips_through_the_principal_form() -> TestResult {
    for name in ["benchmark", "browser-jason", "browser", "pista"] {
        let b = presets::find(name)?.bicycle().benchmark()?;
        // A rider of a third of the rear frame's mass, near its centre, its axes turned.
        let radius = |i: f64| (i / b.m_b).sqrt();
        let rider = PrincipalBody {
            m: b.m_b / 3.0,
            x: b.x_b + 0.05,
            z: b.z_b - 0.05,
            k_aa: 0.4 * radius(b.i_bxx),
            k_bb: 0.3 * radius(b.i_bzz),
            k_yy: 0.4 * radius(b.i_byy),
            alpha: -0.4,
        };
        let p = PrincipalParameters::from_benchmark(&b, &rider, 1.7, 0.5)?;
        assert!(p.d.k_aa >= p.d.k_bb && p.h.k_aa >= p.h.k_bb, "{name}");
        assert!(p.d.alpha.abs() <= std::f64::consts::FRAC_PI_2, "{name}");
        assert_benchmark_close(&p.to_benchmark(), &b, 1e-12);
    }
    Ok(())
}

/// Written as a principal set and read back: the same benchmark parameters; through TOML
/// (the rider kept among the extras) as well.
#[test]
fn principal_yaml_written_reads_back() -> TestResult {
    let bike = parse(&text(), Format::Yaml)?;
    let b = bike.benchmark()?;
    let written = principal_yaml(&bike)?;
    assert!(
        written.starts_with("parameterization: principal\n"),
        "{written}"
    );
    let again = parse(&written, Format::Yaml)?;
    assert_benchmark_close(&again.benchmark()?, &b, 1e-12);
    let toml = parse(&write(&bike, Format::Toml)?, Format::Toml)?;
    let through = parse(&principal_yaml(&toml)?, Format::Yaml)?;
    assert_benchmark_close(&through.benchmark()?, &b, 1e-12);
    // The frame D recovered equals the file's to round-off.
    let d = principal_from_file()?.d;
    let line = |key: &str| format!("  {key}: ");
    for (key, expected) in [("mD", d.m), ("kDaa", d.k_aa), ("alphaD", d.alpha)] {
        let text = written
            .lines()
            .find_map(|l| l.strip_prefix(&line(key)))
            .ok_or(key)?;
        assert!(close(text.parse()?, expected, 1e-12), "{key}: {text}");
    }
    Ok(())
}

#[test]
fn principal_refusals_name_the_field() -> TestResult {
    // No rider to split the rear frame with.
    let bike = presets::find("benchmark")?.bicycle();
    let message = principal_yaml(&bike)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        message.contains("mP") && message.contains("rider"),
        "{message}"
    );
    // A rider heavier than the rear frame with the rider.
    let p = principal_from_file()?;
    let heavy = PrincipalBody { m: 200.0, ..p.p };
    match PrincipalParameters::from_benchmark(&p.to_benchmark(), &heavy, p.l_p, p.w_p) {
        Err(Error::InvalidParameter { field, .. }) => assert_eq!(field, "mP"),
        other => panic!("{other:?}"),
    }
    // A rider that leaves the frame D without a positive moment.
    let wide = PrincipalBody { k_yy: 2.0, ..p.p };
    match PrincipalParameters::from_benchmark(&p.to_benchmark(), &wide, p.l_p, p.w_p) {
        Err(Error::InvalidBicycle { fields, .. }) => assert!(fields.starts_with("kD"), "{fields}"),
        other => panic!("{other:?}"),
    }
    // A redundant key that disagrees, and a missing key, each named with its line.
    for (from, to, field) in [
        ("  xF: 1.1210", "  xF: 1.2", "xF"),
        ("  yP: 0.0", "  yP: 0.1", "yP"),
        ("  kDaa: 0.28587\n", "", "kDaa"),
        ("  v: 3.0", "  vv: 3.0", "vv"),
    ] {
        let changed = text().replace(from, to);
        assert_ne!(changed, text(), "{from}");
        match parse(&changed, Format::Yaml) {
            Err(Error::Parse { field: Some(f), .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    Ok(())
}
