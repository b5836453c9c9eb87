//! Messages that name the right thing and parsers that never panic (property tests):
//! every reader's error names a field, a line or the format; the writers keep every digit and
//! cannot be broken by a name.

use proptest::prelude::*;
use whipple::Bicycle;
use whipple::advanced::io::{FORMATS, Format, parse, write};
use whipple::advanced::parameters::Description;
use whipple::{BenchmarkParameters, Error, presets};

fn message<T: std::fmt::Debug>(r: Result<T, Error>) -> String {
    match r {
        Ok(v) => panic!("expected an error, got {v:?}"),
        Err(e) => e.to_string(),
    }
}

fn crown_toml() -> String {
    write(
        &presets::find("schwinn-crown")
            .map(|p| p.bicycle())
            .unwrap_or_default(),
        Format::Toml,
    )
    .unwrap_or_default()
}

fn crown_m() -> String {
    write(
        &presets::find("schwinn-crown")
            .map(|p| p.bicycle())
            .unwrap_or_default(),
        Format::Jbike6M,
    )
    .unwrap_or_default()
}

/// JBike6-form inputs are reported under the names the user wrote.
#[test]
fn jbike6_errors_name_what_the_user_wrote() {
    for (from, to, name) in [
        ("wheelbase = ", "wheelbase = 0.0 #", "wheelbase"),
        ("gravity = ", "gravity = 0.0 #", "gravity"),
        ("head_angle = ", "head_angle = 0.0 #", "head_angle"),
    ] {
        let text: String = crown_toml()
            .lines()
            .map(|l| {
                if l.starts_with(from) {
                    to.to_string() + l
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        let bike = parse(&text, Format::Toml).unwrap_or_default();
        let m = message(bike.check());
        assert!(m.contains(&format!("`{name}`")), "{m}");
    }
    let text = crown_m().replace("Drearwheel = 0.6858;", "Drearwheel = 0.0;");
    let m = message(
        parse(&text, Format::Jbike6M)
            .map(|b| b.check())
            .and_then(|r| r),
    );
    assert!(m.contains("Drearwheel"), "{m}");
    assert!(!m.contains("IRyy"), "{m}");
}

/// A zero mass with non-zero inertia is refused, naming the body.
#[test]
fn zero_mass_with_inertia_is_refused_naming_the_body() {
    let mut bike = BenchmarkParameters::meijaard2007();
    bike.m_r = 0.0;
    let m = message(bike.validate());
    assert!(
        m.contains("rear wheel R") && m.contains("mR") && m.contains("IR"),
        "{m}"
    );
    let text = crown_m().replace("mrack = 2.0;", "mrack = 0.0;");
    let m = message(
        parse(&text, Format::Jbike6M)
            .map(|b| b.check())
            .and_then(|r| r),
    );
    assert!(m.contains("rear rack") && m.contains("mrack"), "{m}");
}

/// Overflow names the field; long numbers are cut in messages.
#[test]
fn overflow_names_the_field_and_numbers_are_short() {
    let mut bike = BenchmarkParameters::meijaard2007();
    bike.m_b = 1e300;
    let m = message(bike.validate());
    assert!(m.contains("mB") && m.len() < 300, "{m}");
    let long = "1".repeat(1425);
    let text = format!("w = {long}\n");
    let m = message(parse(&text, Format::BicycleParametersTxt));
    assert!(m.len() < 400, "{} characters", m.len());
}

/// Semantic errors are not "syntax error at line 0, column 0"; `[[benchmark]]` gets
/// a clear message; extra elements of an inertia array are refused.
#[test]
fn semantic_errors_are_labelled_as_such() {
    let m = message(parse("name = \"x\"\n", Format::Toml));
    assert!(!m.contains("line 0") && m.contains("benchmark"), "{m}");
    let m = message(parse("[[benchmark]]\nw = 1.0\n", Format::Toml));
    assert!(
        m.contains("[[benchmark]]") && m.contains("one table"),
        "{m}"
    );
    let text = crown_toml().replacen("\nI = [", "\nI = [1.0, ", 1);
    let m = message(parse(&text, Format::Toml));
    assert!(
        m.contains("exactly three") && m.contains("rear_wheel.I"),
        "{m}"
    );
}

/// `.m` column vectors read, matrices refused by name, `...` continuations joined.
#[test]
fn matlab_columns_matrices_and_continuations() -> Result<(), Error> {
    let text = crown_m();
    let line = text
        .lines()
        .find(|l| l.starts_with("Irider ="))
        .unwrap_or_default()
        .to_string();
    let inner = line
        .trim_start_matches("Irider = [")
        .trim_end_matches("];")
        .to_string();
    let numbers: Vec<&str> = inner.split(' ').collect();
    let column = text.replace(
        &line,
        &format!("Irider = [{}; {}; {}];", numbers[0], numbers[1], numbers[2]),
    );
    assert_eq!(
        parse(&column, Format::Jbike6M)?.description,
        parse(&text, Format::Jbike6M)?.description
    );
    let continued = text.replace(
        &line,
        &format!(
            "Irider = [{} ...\n  {} {}];",
            numbers[0], numbers[1], numbers[2]
        ),
    );
    assert_eq!(
        parse(&continued, Format::Jbike6M)?.description,
        parse(&text, Format::Jbike6M)?.description
    );
    let matrix = text.replace(&line, "Irider = [1 2; 3 4];");
    let m = message(parse(&matrix, Format::Jbike6M));
    assert!(m.contains("matrix") && m.contains("Irider"), "{m}");
    Ok(())
}

/// A UTF-8 byte-order mark, CRLF line endings and no final newline are read in
/// every format.
#[test]
fn files_as_their_owners_wrote_them() -> Result<(), Error> {
    let bike = presets::find("benchmark")?.bicycle();
    let crown = presets::find("schwinn-crown")?.bicycle();
    for (format, _, _) in FORMATS {
        let source = if format == Format::Jbike6M {
            &crown
        } else {
            &bike
        };
        let text = write(source, format)?;
        let owner = format!("\u{feff}{}", text.replace('\n', "\r\n").trim_end());
        let back = parse(&owner, format).map_err(|e| {
            eprintln!("{format:?}: {e}");
            e
        })?;
        assert_eq!(back.description, source.description, "{format:?}");
    }
    Ok(())
}

/// Writers keep every digit and a name cannot inject lines or break TOML.
#[test]
fn writers_keep_every_digit_and_escape_names() -> Result<(), Error> {
    let mut crown = presets::find("schwinn-crown")?.bicycle();
    if let Description::Jbike6(p) = &mut crown.description {
        p.trail = 0.0909681234567;
        p.rack.inertia = [1e-12, 1e-12, 1e-12];
    }
    crown.name = Some("evil\nwheelbase = 5;\u{7f}\"".into());
    for format in [Format::Toml, Format::Json, Format::Jbike6M] {
        let text = write(&crown, format)?;
        let back = parse(&text, format)?;
        assert_eq!(back.description, crown.description, "{format:?}");
        if format != Format::Jbike6M {
            assert_eq!(back.name, crown.name, "{format:?}");
        }
    }
    Ok(())
}

/// A NaN or an infinity is refused by every reader (the web API's parse no longer
/// answers it as `null`).
#[test]
fn non_finite_numbers_are_refused_by_every_reader() {
    let bike = presets::find("benchmark")
        .map(|p| p.bicycle())
        .unwrap_or_default();
    for format in [
        Format::Toml,
        Format::BicycleParametersTxt,
        Format::HumanControlTxt,
        Format::Yaml,
    ] {
        let text = write(&bike, format).unwrap_or_default();
        let bad = text.replacen("0.08", "nan", 1);
        let m = message(parse(&bad, format));
        assert!(m.contains("`c`") || m.contains("finite"), "{format:?}: {m}");
    }
}

/// Every missing key of a BicycleParameters file is named in one message, the front frame's
/// among them (with the handlebar-and-fork alternative), not one group per attempt; a front
/// frame given as handlebar G and fork S is not missing.
#[test]
fn missing_keys_are_all_named_at_once() -> Result<(), Error> {
    let base = write(
        &presets::find("benchmark")?.bicycle(),
        Format::BicycleParametersTxt,
    )?;
    let without = |keys: &[&str]| -> String {
        base.lines()
            .filter(|l| {
                !keys
                    .iter()
                    .any(|k| l.split('=').next().map(str::trim) == Some(*k))
            })
            .map(|l| format!("{l}\n"))
            .collect()
    };
    let m = message(parse(
        &without(&["w", "mH", "IHxz"]),
        Format::BicycleParametersTxt,
    ));
    assert!(m.contains("missing keys: w, mH, IHxz"), "{m}");
    assert!(m.contains("handlebar G and fork S"), "{m}");
    let m = message(parse(&without(&["c"]), Format::BicycleParametersTxt));
    assert!(
        m.contains("missing key: `c`") && !m.contains("handlebar"),
        "{m}"
    );
    // The benchmark's front frame split into a handlebar G (all of H) and a massless fork S.
    let h = ["mH", "xH", "zH", "IHxx", "IHyy", "IHzz", "IHxz"];
    let mut split = without(&h);
    for (k, g) in h
        .iter()
        .zip(["mG", "xG", "zG", "IGxx", "IGyy", "IGzz", "IGxz"])
    {
        let line = base
            .lines()
            .find(|l| l.split('=').next().map(str::trim) == Some(*k))
            .unwrap_or_default();
        split.push_str(&line.replacen(k, g, 1));
        split.push('\n');
    }
    split.push_str("mS = 0\nxS = 0.9\nzS = -0.7\nISxx = 0\nISyy = 0\nISzz = 0\nISxz = 0\n");
    let bike = parse(&split, Format::BicycleParametersTxt)?;
    assert_eq!(
        bike.description,
        presets::find("benchmark")?.bicycle().description
    );
    assert!(bike.notices.iter().any(|n| n.field.contains("mH")));
    Ok(())
}

/// The benchmark's file with its front frame H replaced by a handlebar G and a fork S.
fn split_front_frame(g: [f64; 7], s: [f64; 7]) -> Result<String, Error> {
    let base = write(
        &presets::find("benchmark")?.bicycle(),
        Format::BicycleParametersTxt,
    )?;
    let h = ["mH", "xH", "zH", "IHxx", "IHyy", "IHzz", "IHxz"];
    let mut text: String = base
        .lines()
        .filter(|l| {
            !h.iter()
                .any(|k| l.split('=').next().map(str::trim) == Some(*k))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    for (body, values) in [("G", g), ("S", s)] {
        for (key, value) in ["m", "x", "z", "Ixx", "Iyy", "Izz", "Ixz"]
            .iter()
            .zip(values)
        {
            let key = match key.strip_prefix('I') {
                Some(axes) => format!("I{body}{axes}"),
                None => format!("{key}{body}"),
            };
            text.push_str(&format!("{key} = {value:e}\n"));
        }
    }
    Ok(text)
}

/// The tensor of a body of the plane of symmetry (the only product is xz), 3 × 3.
fn tensor(ixx: f64, iyy: f64, izz: f64, ixz: f64) -> nalgebra::Matrix3<f64> {
    nalgebra::Matrix3::new(ixx, 0.0, ixz, 0.0, iyy, 0.0, ixz, 0.0, izz)
}

/// A front frame read as a handlebar G and a fork S with masses and centres apart (so that
/// every parallel-axis term counts) equals an independent combination: each body's full 3 × 3
/// tensor moved to the origin, I + m (|r|² E − r rᵀ), summed, and moved back to the combined
/// centre of mass, rather than the reader's direct shift of each body to that centre.
#[test]
fn handlebar_and_fork_combine_by_the_parallel_axis_theorem() -> Result<(), Error> {
    use nalgebra::{Matrix3, Vector3};
    let g = [2.3, 0.91, -0.98, 0.072, 0.081, 0.022, 0.011];
    let s = [1.9, 0.96, -0.55, 0.05, 0.06, 0.013, -0.008];
    let h = parse(&split_front_frame(g, s)?, Format::BicycleParametersTxt)?.benchmark()?;
    let shift =
        |m: f64, r: Vector3<f64>| m * (r.norm_squared() * Matrix3::identity() - r * r.transpose());
    let mut about_origin = Matrix3::zeros();
    let mut moment = Vector3::zeros();
    for b in [g, s] {
        let r = Vector3::new(b[1], 0.0, b[2]);
        about_origin += tensor(b[3], b[4], b[5], b[6]) + shift(b[0], r);
        moment += b[0] * r;
    }
    let m = g[0] + s[0];
    let centre = moment / m;
    let expected = about_origin - shift(m, centre);
    let got = tensor(h.i_hxx, h.i_hyy, h.i_hzz, h.i_hxz);
    assert!((h.m_h - m).abs() <= 1e-15 * m);
    assert!((Vector3::new(h.x_h, 0.0, h.z_h) - centre).norm() <= 1e-14);
    assert!((got - expected).norm() <= 1e-13, "{got} vs {expected}");
    // The Steiner terms are not small here: the sum of the two tensors is far from the answer.
    let plain = tensor(g[3] + s[3], g[4] + s[4], g[5] + s[5], g[6] + s[6]);
    assert!((plain - expected).norm() > 0.05, "{plain} vs {expected}");

    // Textbook case: two point masses m₁, m₂ a distance d apart have, about their centre of
    // mass, the moment μ d² (μ = m₁ m₂ / (m₁ + m₂)) about any axis perpendicular to the line
    // joining them, and none along it.
    let (m1, m2) = (3.0, 1.0);
    let (p1, p2) = ([0.8, -1.0], [1.1, -0.6]);
    let h = parse(
        &split_front_frame(
            [m1, p1[0], p1[1], 0.0, 0.0, 0.0, 0.0],
            [m2, p2[0], p2[1], 0.0, 0.0, 0.0, 0.0],
        )?,
        Format::BicycleParametersTxt,
    )?
    .benchmark()?;
    let mu = m1 * m2 / (m1 + m2);
    let (dx, dz): (f64, f64) = (p2[0] - p1[0], p2[1] - p1[1]);
    assert!((h.i_hyy - mu * (dx * dx + dz * dz)).abs() <= 1e-14);
    assert!((h.i_hxx - mu * dz * dz).abs() <= 1e-14);
    assert!((h.i_hzz - mu * dx * dx).abs() <= 1e-14);
    assert!((h.i_hxz + mu * dx * dz).abs() <= 1e-14);
    Ok(())
}

/// Keys of other models are never dropped silently; left-right asymmetry refused.
#[test]
fn other_keys_are_reported_or_refused() -> Result<(), Error> {
    let base = write(
        &presets::find("benchmark")?.bicycle(),
        Format::HumanControlTxt,
    )?;
    let bike = parse(
        &format!("{base}xcl = 1.2\nzcl = -0.4\nv = 5\n"),
        Format::HumanControlTxt,
    )?;
    for key in ["xcl", "zcl", "v"] {
        assert!(bike.notices.iter().any(|n| n.field == key), "{key}");
        assert!(bike.extras.iter().any(|e| e.key == key), "{key}");
    }
    let m = message(parse(
        &format!("{base}yB = 0.01\n"),
        Format::HumanControlTxt,
    ));
    assert!(
        m.contains("left-right symmetric") && m.contains("yB"),
        "{m}"
    );
    let m = message(parse(
        &format!("{base}IRzz = 0.07\n"),
        Format::HumanControlTxt,
    ));
    assert!(m.contains("axisymmetric"), "{m}");
    let m = message(parse(&format!("{base}foo = 1\n"), Format::HumanControlTxt));
    assert!(m.contains("unknown key `foo`"), "{m}");
    let m = message(parse("TcB1 = 1.2\n", Format::BicycleParametersTxt));
    assert!(m.contains("Measured.txt"), "{m}");
    let bike = parse(
        &base.replace("lam = 0.3141592653589793", "lam = pi/10"),
        Format::HumanControlTxt,
    )?;
    assert_eq!(
        bike.description,
        parse(&base, Format::HumanControlTxt)?.description
    );
    Ok(())
}

/// Arithmetic in a `.txt` value follows the usual precedence, as torque expressions do: a
/// leading minus binds looser than `^` (`-3^2/10` is −0.9, the benchmark's z_B, not +0.9),
/// `-` and `/` associate to the left, `^` to the right; a value that cannot be evaluated is
/// refused naming its key as the file wrote it.
#[test]
fn txt_values_evaluate_with_the_usual_precedence() -> Result<(), Error> {
    let base = write(
        &presets::find("benchmark")?.bicycle(),
        Format::HumanControlTxt,
    )?;
    let with = |key: &str, value: &str| -> String {
        base.lines()
            .map(|l| {
                if l.split('=').next().map(str::trim) == Some(key) {
                    format!("{key} = {value}")
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let expected = parse(&base, Format::HumanControlTxt)?.description;
    // zB = -0.9, xB = 0.3, w = 1.02, c = 0.08 in the benchmark.
    for (key, value) in [
        ("zB", "-3^2/10"),
        ("xB", "1.2 - 0.6 - 0.3"),
        ("w", "4.08/2/2"),
        ("c", "2^3^2/6400"),
        ("zB", "-0.9*2^-1*2"),
    ] {
        let bike = parse(&with(key, value), Format::HumanControlTxt)?;
        assert_eq!(bike.description, expected, "{key} = {value}");
    }
    for (value, says) in [
        ("2*t", "unknown name `t` at column 3"),
        ("sqrt 2", "needs its argument in parentheses"),
        ("(1", "to close the `(` at column 1"),
        ("1/0", "not a finite number"),
    ] {
        let m = message(parse(&with("zB", value), Format::HumanControlTxt));
        assert!(m.contains("zB") && m.contains(says), "{value}: {m}");
    }
    Ok(())
}

/// An ambiguous `.txt` gets a message listing the formats and how to choose one (the front
/// ends name their option: whipple-front's `message`).
#[test]
fn ambiguous_text_files_list_the_formats() {
    let m = message(Format::detect("bike.txt", "# only a comment\n"));
    for name in [
        "bp-txt",
        "hc-txt",
        "yaml",
        "Name one or give the file its extension",
    ] {
        assert!(m.contains(name), "{m}");
    }
    assert!(
        !m.contains("--bike-format"),
        "the library names no option: {m}"
    );
}

/// Errors name a field, a line or the format: the condition every random file must meet.
fn names_something(e: &Error) -> bool {
    match e {
        Error::Parse { line, field, .. } => *line > 0 || field.is_some(),
        Error::InvalidParameter { field, .. } => !field.is_empty(),
        Error::InvalidBicycle { fields, .. } => !fields.is_empty(),
        Error::InvalidArgument { .. } => true,
        _ => false,
    }
}

fn formats() -> impl Strategy<Value = Format> {
    prop_oneof![
        Just(Format::Toml),
        Just(Format::Json),
        Just(Format::Jbike6M),
        Just(Format::BicycleParametersTxt),
        Just(Format::HumanControlTxt),
        Just(Format::Yaml),
    ]
}

fn valid_text(format: Format) -> String {
    let name = if format == Format::Jbike6M {
        "schwinn-crown"
    } else {
        "benchmark"
    };
    let bike: Bicycle = presets::find(name).map(|p| p.bicycle()).unwrap_or_default();
    write(&bike, format).unwrap_or_default()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Random text never panics any reader, and every error names a field, a line or the format.
    #[test]
    fn random_text_never_panics(format in formats(), text in "\\PC{0,200}") {
        if let Err(e) = parse(&text, format) {
            prop_assert!(names_something(&e) || matches!(e, Error::Parse { .. }), "{e}");
        }
    }

    /// A valid file with one byte changed, a line cut or a value replaced never panics, and the
    /// error (or the check of what it read) names a field or a line.
    #[test]
    fn mutated_files_never_panic(format in formats(), at in 0usize..2000, replacement in "[-0-9a-zA-Z\\[\\]{}=:;,.+/# \n]{0,6}") {
        let text = valid_text(format);
        let mut at = at % text.len().max(1);
        while !text.is_char_boundary(at) { at -= 1; }
        let end = (at + 3).min(text.len());
        let end = (end..=text.len()).find(|e| text.is_char_boundary(*e)).unwrap_or(text.len());
        let mutated = format!("{}{}{}", &text[..at], replacement, &text[end..]);
        match parse(&mutated, format) {
            Err(e) => prop_assert!(names_something(&e), "{e}"),
            Ok(bike) => {
                if let Err(e) = bike.check() {
                    prop_assert!(names_something(&e), "{e}");
                }
            }
        }
    }

    /// Random benchmark bicycles round-trip through every benchmark-form writer bit for bit.
    #[test]
    fn random_bicycles_round_trip(values in proptest::collection::vec(-1e6f64..1e6, 26), sigma in 0.0f64..1.0) {
        let mut array = [0.0; 26];
        array.copy_from_slice(&values);
        let mut bike = Bicycle::new(Description::Benchmark(BenchmarkParameters::from_array(array)));
        bike.sigma.insert("IBxx".into(), sigma);
        if sigma == 0.0 { bike.sigma.clear(); }
        bike.name = Some("a \"name\"\twith\u{7f}".into());
        for format in [Format::Toml, Format::Json, Format::BicycleParametersTxt, Format::HumanControlTxt, Format::Yaml] {
            let text = write(&bike, format).map_err(|e| TestCaseError::fail(e.to_string()))?;
            let back = parse(&text, format).map_err(|e| TestCaseError::fail(format!("{format:?}: {e}\n{text}")))?;
            prop_assert_eq!(&back.description, &bike.description);
            prop_assert_eq!(&back.sigma, &bike.sigma);
        }
    }
}

/// A value written with a decimal comma (`w = 1,02`) was read as two measurements and averaged
/// to 1.5 without a word; it is refused, naming the line, the column and both readings. A list
/// of measurements (a comma and a space, or a point in each value) is still averaged.
#[test]
fn a_decimal_comma_is_refused_not_averaged() {
    let base = "w = 1.02\nc = 0.08\n";
    for (format, text, line, column, shown) in [
        (
            Format::BicycleParametersTxt,
            format!("{base}rR = 0,3\n"),
            3,
            6,
            "0,3",
        ),
        (
            Format::BicycleParametersTxt,
            "c = 0.08\nw = 1,02 +/- 0.01\n".to_string(),
            2,
            5,
            "1,02",
        ),
        (
            Format::BicycleParametersTxt,
            "w = 1.02 +/- 0,01\n".to_string(),
            1,
            14,
            "0,01",
        ),
        (
            Format::HumanControlTxt,
            "w = 1,02\n".to_string(),
            1,
            5,
            "1,02",
        ),
        (
            Format::HumanControlTxt,
            "c,0.08\nw,1,02\n".to_string(),
            2,
            3,
            "1,02",
        ),
        (
            Format::BicycleParametersTxt,
            "w = -1,5\n".to_string(),
            1,
            5,
            "-1,5",
        ),
    ] {
        let m = message(parse(&text, format));
        assert!(
            m.contains(&format!("line {line}")) && m.contains(&format!("column {column}")),
            "{format:?} {text:?}: {m}"
        );
        assert!(m.contains(&format!("`{shown}`")), "{text:?}: {m}");
        assert!(m.contains("decimal comma"), "{m}");
        assert!(m.contains(&shown.replacen(',', ".", 1)), "{m}");
    }
    // Lists of measurements, as BicycleParameters writes them, are still averaged.
    let rigid = include_str!("data/bicycleparameters/RigidBenchmark.txt");
    for list in [
        "1.0, 2.0",
        "1.0,2.0",
        "1, 2",
        "1.0 ,2",
        "1.0 +/- 0.1, 2 +/- 0.1",
    ] {
        let text: String = rigid
            .lines()
            .map(|l| {
                if l.starts_with("w = ") {
                    format!("w = {list}\n")
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        let w = parse(&text, Format::BicycleParametersTxt)
            .and_then(|b| b.benchmark())
            .map(|p| p.w);
        assert_eq!(w.ok(), Some(1.5), "{list}");
    }
}

/// A JSON bicycle naming a key twice was read with the last value winning; every other format
/// refuses the repetition, and so does JSON now, naming the key, the line and the column.
#[test]
fn a_duplicate_json_key_is_refused() {
    let json = write(
        &Bicycle::new(Description::Benchmark(BenchmarkParameters::meijaard2007())),
        Format::Json,
    )
    .unwrap_or_default();
    assert!(parse(&json, Format::Json).is_ok());
    // Repeat the first key of the benchmark table inside its object.
    let at = json.find("\"w\"").expect("a `w` key");
    let doubled = format!("{}\"w\": 2.0,\n    {}", &json[..at], &json[at..]);
    let m = message(parse(&doubled, Format::Json));
    assert!(m.contains("duplicate key `w`"), "{m}");
    assert!(m.contains("line "), "{m}");
    // The same key in two different objects is fine.
    assert!(
        whipple::advanced::io::json_without_duplicates(r#"{"a": {"w": 1}, "b": {"w": 2}}"#).is_ok()
    );
}
