//! One test per class of bad input: each is refused with an error naming the field, the value
//! and the rule, and nothing panics.

use whipple::advanced::io::{Format, parse};
use whipple::{BenchmarkParameters, Error, presets, speed_grid};

fn benchmark() -> BenchmarkParameters {
    BenchmarkParameters::meijaard2007()
}

fn message(result: whipple::Result<()>) -> String {
    match result {
        Ok(()) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn non_finite_numbers_are_refused() {
    let mut b = benchmark();
    b.i_bxx = f64::NAN;
    let m = message(b.validate());
    assert!(m.contains("IBxx") && m.contains("finite"), "{m}");
    b = benchmark();
    b.w = f64::INFINITY;
    assert!(message(b.validate()).contains("`w`"));
}

#[test]
fn gravity_and_wheelbase_must_be_positive() {
    let mut b = benchmark();
    b.g = 0.0;
    assert!(message(b.validate()).contains("`g` = 0"));
    b = benchmark();
    b.w = -1.0;
    assert!(message(b.validate()).contains("`w` = -1"));
}

#[test]
fn negative_wheel_radius_is_refused() {
    let mut b = benchmark();
    b.r_f = -0.35;
    let m = message(b.validate());
    assert!(m.contains("rF") && m.contains("negative"), "{m}");
}

#[test]
fn steer_axis_tilt_must_lie_inside_plus_minus_half_pi() {
    let mut b = benchmark();
    b.lambda = std::f64::consts::FRAC_PI_2;
    let m = message(b.validate());
    assert!(m.contains("lam") && m.contains("pi/2"), "{m}");
}

#[test]
fn negative_masses_and_massless_assemblies_are_refused() {
    let mut b = benchmark();
    b.m_h = -4.0;
    assert!(message(b.validate()).contains("mH"));
    b = benchmark();
    b.m_h = 0.0;
    b.m_f = 0.0;
    let m = message(b.validate());
    assert!(m.contains("mH, mF") && m.contains("front assembly"), "{m}");
}

#[test]
fn inertia_tensors_must_be_positive_semi_definite() {
    let mut b = benchmark();
    b.i_bxz = 6.0; // 36 > 9.2 * 2.8
    let m = message(b.validate());
    assert!(
        m.contains("IBxz") && m.contains("positive semi-definite"),
        "{m}"
    );
}

#[test]
fn principal_moments_must_obey_the_triangle_inequality() {
    // A warning (measured tensors break it within their error), not an error.
    let mut b = benchmark();
    b.i_ryy = 0.2; // > 2 * 0.0603
    let warnings = b.check().unwrap_or_default();
    let m = warnings.iter().map(|w| w.to_string()).collect::<String>();
    assert!(
        m.contains("IRyy") && m.contains("triangle") && m.contains("65.8"),
        "{m}"
    );
    // A thin disk sits exactly on the inequality and is accepted.
    b.i_ryy = 2.0 * b.i_rxx;
    assert!(b.validate().is_ok());
}

#[test]
fn a_skate_cannot_spin() {
    let mut b = presets::two_mass_skate();
    b.m_r = 1.0;
    b.i_rxx = 0.01;
    b.i_ryy = 0.01;
    let m = message(b.validate());
    assert!(m.contains("IRyy") && m.contains("zero radius"), "{m}");
}

#[test]
fn a_singular_mass_matrix_is_refused() {
    // Point masses on the ground: nothing resists lean acceleration, M_φφ = 0.
    let mut b = presets::two_mass_skate();
    b.z_b = 0.0;
    b.z_h = 0.0;
    let m = message(b.validate());
    assert!(m.contains("positive definite"), "{m}");
}

#[test]
fn jbike6_rules_are_checked_before_conversion() {
    let mut j = presets::schwinn_crown_jbike6();
    j.head_angle = 0.0;
    assert!(
        j.to_benchmark()
            .unwrap_err()
            .to_string()
            .contains("head_angle")
    );
    j = presets::schwinn_crown_jbike6();
    j.front_wheel.inertia = [0.08, 0.09, 0.17];
    let m = j.to_benchmark().unwrap_err().to_string();
    assert!(
        m.contains("Ifrontwheel") && m.contains("axisymmetric"),
        "{m}"
    );
    j = presets::schwinn_crown_jbike6();
    j.basket.m = -1.5;
    assert!(
        j.to_benchmark()
            .unwrap_err()
            .to_string()
            .contains("mbasket")
    );
    j = presets::schwinn_crown_jbike6();
    j.rider.inertia = [10.0, 1.0, 12.0];
    // A warning under JBike6's name, not an error.
    let (_, warnings) = j.to_benchmark_checked().unwrap_or_else(|e| panic!("{e}"));
    let m = warnings.iter().map(|w| w.to_string()).collect::<String>();
    assert!(m.contains("Irider") && m.contains("triangle"), "{m}");
}

#[test]
fn unknown_preset_lists_the_known_ones() {
    let e = presets::find("penny-farthing").unwrap_err();
    assert!(matches!(e, Error::UnknownPreset { .. }));
    assert!(e.to_string().contains("benchmark, schwinn-crown"));
}

fn parse_error(text: &str, format: Format) -> (usize, usize, String) {
    match parse(text, format) {
        Err(Error::Parse {
            line,
            column,
            message,
            ..
        }) => (line, column, message),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn toml_syntax_errors_name_line_and_column() {
    let (line, column, message) = parse_error("[benchmark]\nw = 1.02\nc = = 0.08\n", Format::Toml);
    assert_eq!((line, column), (3, 5), "{message}");
}

#[test]
fn toml_unknown_and_missing_keys_are_refused() {
    let good = whipple::advanced::io::write(
        &presets::find("benchmark").expect("preset").bicycle(),
        Format::Toml,
    )
    .expect("writes");
    let unknown = good.replace("mB = ", "mass_B = ");
    let (line, _, message) = parse_error(&unknown, Format::Toml);
    assert!(message.contains("mass_B"), "{message}");
    assert!(line > 0);
    let missing: String = good
        .lines()
        .filter(|l| !l.starts_with("IHxz"))
        .map(|l| format!("{l}\n"))
        .collect();
    let (_, _, message) = parse_error(&missing, Format::Toml);
    assert!(message.contains("IHxz"), "{message}");
    let (_, _, message) = parse_error("name = \"x\"\n", Format::Toml);
    assert!(message.contains("benchmark") && message.contains("jbike6"));
    let (_, _, message) = parse_error("w = \"wide\"\n", Format::Toml);
    assert!(message.contains("unknown key `w`"), "{message}");
    // A number of the wrong type names its key and what was expected.
    let wrong_type = good.replace("w = 1.02", "w = \"wide\"");
    assert_ne!(wrong_type, good);
    let (line, _, message) = parse_error(&wrong_type, Format::Toml);
    assert!(
        message.contains("`w`") && message.contains("must be a number"),
        "{message}"
    );
    assert!(
        wrong_type
            .lines()
            .nth(line - 1)
            .is_some_and(|l| l.starts_with("w = ")),
        "line {line}"
    );
}

#[test]
fn json_errors_name_line_and_column() {
    let (line, column, _) = parse_error("{\n  \"benchmark\": {\n    \"w\": 1.02,,\n", Format::Json);
    assert_eq!((line, column), (3, 15)); // the second comma
}

const CROWN_M: &str = "wheelbase = 1.01600000;\nhead_angle = 1.23879599;\ntrail = 0.09096800;\n\
Drearwheel = 0.68580000;\nmrearwheel = 1.81818200;\nIrearwheel = [0.08551300 0.08551300 0.17102600];\n\
alphaIrearwheel = 0.00000000;\nDfrontwheel = 0.68580000;\nmfrontwheel = 1.81818200;\n\
Ifrontwheel = [0.08551300 0.08551300 0.17102600];\nalphaIfrontwheel = 0.00000000;\n\
% rider\nmrider = 80.00000000;\nxcmrider = 0.30000000;\nycmrider = 1.20000000;\n\
Irider = [10.53112900 2.46887100 12.00000000];\nalphaIrider = -0.25957299;\n\
mframe = 2.50000000;\nxcmframe = 0.30000000;\nycmframe = 0.50000000;\n\
Iframe = [0.05857900 0.34142100 0.40000000];\nalphaIframe = 0.39269899;\n\
mfork = 1.50000000;\nucmfork = 0.00000000;\nvcmfork = 0.68580000;\n\
Ifork = [0.05879000 0.00058800 0.05879000];\nalphaIfork = 0.33200000;\n\
mbasket = 1.50000000;\nucmbasket = 0.15000000;\nvcmbasket = 0.80000000;\n\
Ibasket = [0.01000000 0.01000000 0.01000000];\nalphaIbasket = 0.00000000;\n\
mrack = 2.00000000;\nxcmrack = -0.10000000;\nycmrack = 0.80000000;\n\
Irack = [0.02000000 0.02000000 0.02000000];\nalphaIrack = 0.00000000;\n";

/// The listing printed in Dressel's study reads back as the Schwinn Crown preset, with JBike6's
/// default gravity when `gravity` is left out.
#[test]
fn jbike6_m_listing_of_the_study_reads_back() {
    let bike = parse(CROWN_M, Format::Jbike6M).expect("the study's listing parses");
    assert_eq!(bike.jbike6(), Some(&presets::schwinn_crown_jbike6()));
}

#[test]
fn jbike6_m_errors_name_line_and_column() {
    let (line, column, message) = parse_error(
        &CROWN_M.replace("mframe = 2.5", "mfram = 2.5"),
        Format::Jbike6M,
    );
    assert_eq!((line, column), (18, 1));
    assert!(message.contains("unknown variable `mfram`"), "{message}");
    let (line, _, message) = parse_error(
        &CROWN_M.replace("trail = 0.09096800", "trail = 0.09o"),
        Format::Jbike6M,
    );
    assert_eq!(line, 3);
    assert!(message.contains("not a number"), "{message}");
    let (_, _, message) = parse_error(
        &CROWN_M.replace(
            "Ibasket = [0.01000000 0.01000000 0.01000000]",
            "Ibasket = [0.01 0.01]",
        ),
        Format::Jbike6M,
    );
    assert!(message.contains("three numbers"), "{message}");
    let (_, _, message) = parse_error(
        &CROWN_M.replace("mrack = 2.00000000;\n", ""),
        Format::Jbike6M,
    );
    assert!(message.contains("missing variables: mrack"), "{message}");
    let (line, _, message) = parse_error(&format!("{CROWN_M}trail = 0.1;\n"), Format::Jbike6M);
    assert_eq!(line, 38);
    assert!(message.contains("assigned twice"), "{message}");
    let (_, _, message) = parse_error(
        &CROWN_M.replace("trail = 0.09096800", "trail = NaN"),
        Format::Jbike6M,
    );
    assert!(message.contains("finite"), "{message}");
}

#[test]
fn speed_grids_must_be_finite_increasing_and_bounded() {
    assert!(speed_grid(0.0, 10.0, 0.0).is_err());
    assert!(speed_grid(0.0, 10.0, -0.1).is_err());
    assert!(speed_grid(10.0, 0.0, 0.1).is_err());
    assert!(speed_grid(0.0, f64::NAN, 0.1).is_err());
    assert!(speed_grid(0.0, 1e9, 1e-3).is_err());
    assert_eq!(speed_grid(0.0, 10.0, 0.01).expect("valid").len(), 1001);
    assert_eq!(speed_grid(2.0, 2.0, 1.0).expect("valid"), vec![2.0]);
}

/// Random parameter sets, valid or not, never make the library panic: each either computes or
/// returns an error (a cheap fuzz over all 26 numbers).
#[test]
fn no_panic_on_arbitrary_parameters() {
    let mut state = 0x2545F4914F6CDD1Du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..300 {
        let mut b = benchmark();
        let fields: Vec<&str> = b.fields().iter().map(|f| f.0).collect();
        let pick = (next() * fields.len() as f64) as usize % fields.len();
        let value = match (next() * 6.0) as usize {
            0 => -next() * 10.0,
            1 => 0.0,
            2 => next() * 1e6,
            3 => f64::NAN,
            _ => next() * 2.0,
        };
        let mut text = whipple::advanced::io::write(
            &whipple::Bicycle::new(whipple::advanced::parameters::Description::Benchmark(b)),
            Format::Json,
        )
        .expect("writes");
        let key = format!("\"{}\": ", fields[pick]);
        if let Some(start) = text.find(&key) {
            let end = text[start..]
                .find([',', '\n'])
                .map_or(text.len(), |e| start + e);
            let literal = if value.is_nan() {
                "1e999".to_string()
            } else {
                format!("{value}")
            };
            text.replace_range(start..end, &format!("{key}{literal}"));
        }
        if let Ok(bike) = parse(&text, Format::Json) {
            if let Ok(p) = bike.benchmark() {
                b = p;
                let c = whipple::Canonical::new(&b).expect("validated");
                let _ = whipple::critical_speeds(&c, 0.0, 10.0);
                let _ = whipple::eigen_sweep(&c, &[0.0, 1.0, 5.0]);
            }
        }
    }
}

/// Wheels that overlap (a rear wheel of radius 2 m on a 1.02 m wheelbase) got certified
/// numbers without a word; they are warned about, as a centre of mass below the ground is (the
/// equations stay well defined, so it is not an error; `--strict` refuses it).
#[test]
fn overlapping_wheels_are_warned_about() {
    let mut b = benchmark();
    assert!(b.check().is_ok_and(|n| n.is_empty()));
    b.r_r = 2.0;
    let notices = b.check().unwrap_or_default();
    let overlap: Vec<_> = notices
        .iter()
        .filter(|n| n.message.contains("wheels overlap"))
        .collect();
    assert_eq!(overlap.len(), 1, "{notices:?}");
    assert_eq!(overlap[0].field, "w");
    assert!(
        overlap[0].message.contains("1.67"),
        "{}",
        overlap[0].message
    );
    // Exactly touching wheels (w = 2·√(rR·rF)) are not warned about; a hair closer is.
    let mut touching = benchmark();
    touching.r_r = 0.5;
    touching.r_f = 0.5;
    touching.w = 1.0;
    assert!(touching.check().is_ok_and(|n| n.is_empty()));
    touching.w = 0.999;
    assert!(
        touching
            .check()
            .is_ok_and(|n| n.iter().any(|n| n.message.contains("wheels overlap")))
    );
}

/// The comparison of the models takes at most the library's one limit of
/// speeds (the command line's `validate` and Python's `compare` both use it), refused before
/// any work; a stop flag ends it early.
#[test]
fn the_comparison_takes_at_most_its_limit_of_speeds_and_stops_when_asked() {
    use std::sync::atomic::AtomicBool;
    use whipple::advanced::comparison::{ComparisonSettings, Linearization, compare_with_linear};
    use whipple::advanced::comparison::{MAX_COMPARED_SPEEDS, compare_with_linear_until};

    let speeds = vec![1.0; MAX_COMPARED_SPEEDS + 1];
    let methods = [Linearization::Exact];
    let settings = ComparisonSettings::default();
    match compare_with_linear(&benchmark(), &speeds, &methods, &settings) {
        Err(Error::LimitExceeded { what, rule }) => {
            assert_eq!(what, "speeds");
            assert!(rule.contains("100001") && rule.contains("100000"), "{rule}");
        }
        other => panic!("expected LimitExceeded, got {other:?}"),
    }
    let stop = AtomicBool::new(true);
    let stopped = compare_with_linear_until(&benchmark(), &[1.0, 2.0], &methods, &settings, &stop);
    assert!(
        matches!(
            stopped,
            Err(Error::InvalidArgument {
                what: "stopped",
                ..
            })
        ),
        "{stopped:?}"
    );
}

/// A warning whose violation has no finite percentage (a wheel with IRxx = 0 and IRyy > 0:
/// the reference is zero) carried an infinite `violation_percent`, which JSON prints as null
/// (the server's answer then broke its own schema, found by schemathesis).
#[test]
fn a_notice_never_carries_a_non_finite_percentage() {
    let mut b = benchmark();
    b.i_rxx = 0.0;
    let notices = b.check().unwrap_or_default();
    assert!(!notices.is_empty());
    for n in &notices {
        assert!(n.violation_percent.is_none_or(f64::is_finite), "{n:?}");
        let json = serde_json::to_string(n).unwrap_or_default();
        assert!(!json.contains("null"), "{json}");
    }
}
