//! Parameter files in the units people use (issue 33): `lam_deg`, `c_mm`, … in TOML and JSON,
//! read into the same SI bicycle and written back in the unit read, the typed digits kept.

use proptest::prelude::*;
use whipple::advanced::io::{Format, parse, write};
use whipple::advanced::parameters::Description;
use whipple::advanced::table::{Form, TypedUnit, parameters};
use whipple::{BenchmarkParameters, Bicycle};

/// The benchmark table as TOML, each key's value given by `value(key)`: `(name as written,
/// text)`.
fn benchmark_toml(value: impl Fn(&str, f64) -> (String, String)) -> String {
    let b = BenchmarkParameters::meijaard2007();
    let values = Bicycle::new(Description::Benchmark(b)).description.values();
    let mut text = String::from("[benchmark]\n");
    for (p, x) in parameters(Form::Benchmark).iter().zip(values) {
        let (name, v) = value(p.key, x);
        text.push_str(&format!("{name} = {v}\n"));
    }
    text
}

fn si(key: &str, x: f64) -> (String, String) {
    (key.to_string(), format!("{x:?}"))
}

fn designer(key: &str, x: f64) -> (String, String) {
    match key {
        "w" => ("w_mm".into(), "1020".into()),
        "c" => ("c_mm".into(), "{ value = 80, sigma = 1 }".into()),
        "lam" => ("lam_deg".into(), "18".into()),
        "rR" => ("rR_mm".into(), "300".into()),
        "xH" => ("xH_mm".into(), "0.5".into()),
        _ => si(key, x),
    }
}

fn benchmark(bike: &Bicycle) -> BenchmarkParameters {
    match bike.description {
        Description::Benchmark(b) => b,
        Description::Jbike6(_) => panic!("a benchmark file"),
    }
}

#[test]
fn suffixed_keys_read_as_si_and_remember_their_unit() {
    let bike = parse(&benchmark_toml(designer), Format::Toml).unwrap();
    let b = benchmark(&bike);
    assert_eq!(b.w, 1.02);
    assert_eq!(b.c, 0.08);
    assert_eq!(b.r_r, 0.3);
    assert_eq!(b.x_h, 0.0005);
    assert_eq!(b.lambda, 18f64.to_radians());
    assert_eq!(bike.sigma.get("c"), Some(&0.001));
    assert_eq!(bike.units.get("c"), Some(&TypedUnit::Millimetres));
    assert_eq!(bike.units.get("lam"), Some(&TypedUnit::Degrees));
    assert_eq!(bike.units.get("mB"), None);
}

/// mm → m → mm gives the typed digits back, in TOML and JSON, and the SI value bit for bit.
#[test]
fn written_back_in_the_unit_read_with_the_typed_digits() {
    let bike = parse(&benchmark_toml(designer), Format::Toml).unwrap();
    let toml = write(&bike, Format::Toml).unwrap();
    for line in [
        "w_mm = 1020.0 # wheelbase",
        "between the wheel contacts [mm]",
        "c_mm = { value = 80.0, sigma = 1.0 }",
        "lam_deg = 18.0",
        "rR_mm = 300.0",
        "xH_mm = 0.5",
        "mB = 85.0",
    ] {
        assert!(toml.contains(line), "{line} in\n{toml}");
    }
    assert_eq!(parse(&toml, Format::Toml).unwrap(), bike);
    let json = write(&bike, Format::Json).unwrap();
    for item in [
        "\"w_mm\": 1020.0",
        "\"c_mm\": { \"value\": 80.0, \"sigma\": 1.0 }",
        "\"lam_deg\": 18.0",
    ] {
        assert!(json.contains(item), "{item} in\n{json}");
    }
    assert_eq!(parse(&json, Format::Json).unwrap(), bike);
    // The other formats are SI, as their owners' programs read them.
    let txt = write(&bike, Format::BicycleParametersTxt).unwrap();
    assert!(txt.contains("c = 0.08") && !txt.contains("_mm"), "{txt}");
}

#[test]
fn a_key_in_two_units_is_refused_naming_both() {
    let text = benchmark_toml(designer).replace("[benchmark]\n", "[benchmark]\nc = 0.08\n");
    let err = parse(&text, Format::Toml).unwrap_err().to_string();
    assert!(err.contains("`c` and `c_mm`"), "{err}");
    let json = r#"{"benchmark": {"lam": 0.3, "lam_deg": 18}}"#;
    let err = parse(json, Format::Json).unwrap_err().to_string();
    assert!(err.contains("`lam` and `lam_deg`"), "{err}");
}

#[test]
fn a_suffix_that_does_not_fit_is_refused_naming_the_key_as_written() {
    for (from, to, rule) in [
        ("IBxx =", "IBxx_mm =", "`IBxx_mm`: `IBxx` is not a length"),
        ("lam =", "lam_mm =", "`lam_mm`: `lam` is not a length"),
        ("c =", "c_deg =", "`c_deg`: `c` is not an angle"),
        ("mB =", "mB_deg =", "`mB_deg`: `mB` is not an angle"),
    ] {
        let text = benchmark_toml(si).replace(from, to);
        let err = parse(&text, Format::Toml).unwrap_err().to_string();
        assert!(err.contains(rule), "{to}: {err}");
    }
    let text = benchmark_toml(si)
        .replace("c =", "c_mm =")
        .replace("c_mm = 0.08", "c_mm = nan");
    let err = parse(&text, Format::Toml).unwrap_err().to_string();
    assert!(err.contains("c_mm"), "{err}");
    let err = parse(
        &benchmark_toml(designer).replace("sigma = 1", "sigma = -1"),
        Format::Toml,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("`c_mm` cannot be negative"), "{err}");
}

#[test]
fn jbike6_tables_take_suffixes_too() {
    let bike = whipple::presets::find("schwinn-crown").unwrap().bicycle();
    assert!(matches!(bike.description, Description::Jbike6(_)));
    let toml = write(&bike, Format::Toml).unwrap();
    let typed = toml.replacen("trail = 0.", "trail_mm = 0.", 1).replacen(
        "head_angle = ",
        "head_angle_deg = ",
        1,
    );
    // The values are now read as mm and degrees: the same file, other numbers, its units kept.
    let read = parse(&typed, Format::Toml).unwrap();
    assert_eq!(read.units.get("trail"), Some(&TypedUnit::Millimetres));
    assert_eq!(read.units.get("head_angle"), Some(&TypedUnit::Degrees));
    let back = write(&read, Format::Toml).unwrap();
    assert!(
        back.contains("trail_mm = ") && back.contains("head_angle_deg = "),
        "{back}"
    );
    assert_eq!(parse(&back, Format::Toml).unwrap(), read);
    let err = parse(
        &toml.replacen("[jbike6.rider]\n", "[jbike6.rider]\nm_mm = 1\n", 1),
        Format::Toml,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("`rider.m` is not a length"), "{err}");
}

proptest! {
    /// For random finite values, every angle and length key of the table typed with its suffix
    /// gives the same bicycle as its SI value, bit for bit after the one conversion, and
    /// writes back to the same bicycle.
    #[test]
    fn suffixed_and_si_give_the_same_bicycle(
        typed in prop::collection::vec(-1e4f64..1e4, 26),
    ) {
        let units: Vec<Option<TypedUnit>> = parameters(Form::Benchmark)
            .iter()
            .map(|p| TypedUnit::ALL.into_iter().find(|u| u.fits(p.unit)))
            .collect();
        let keys: Vec<&str> = parameters(Form::Benchmark).iter().map(|p| p.key).collect();
        let suffixed = benchmark_toml(|key, x| {
            let i = keys.iter().position(|k| *k == key).unwrap();
            match units[i] {
                Some(u) => (format!("{key}{}", u.suffix()), format!("{:?}", typed[i])),
                None => si(key, x),
            }
        });
        let plain = benchmark_toml(|key, x| {
            let i = keys.iter().position(|k| *k == key).unwrap();
            match units[i] {
                Some(u) => si(key, u.to_si(typed[i])),
                None => si(key, x),
            }
        });
        let a = parse(&suffixed, Format::Toml).unwrap();
        let b = parse(&plain, Format::Toml).unwrap();
        let bits = |bike: &Bicycle| bike.description.values().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&a), bits(&b));
        prop_assert_eq!(a.units.len(), 9);
        for format in [Format::Toml, Format::Json] {
            let back = parse(&write(&a, format).unwrap(), format).unwrap();
            prop_assert_eq!(bits(&back), bits(&a));
        }
    }

    /// Values as designers type them (up to seven digits, up to four decimals) are written
    /// back in their unit, with their digits.
    #[test]
    fn typed_digits_come_back(
        typed in prop::collection::vec((-9_999_999i64..9_999_999, 0u32..5), 26),
    ) {
        let text = |i: usize| {
            let (m, k) = typed[i];
            let x = m as f64 / 10f64.powi(k as i32);
            format!("{x:?}")
        };
        let keys: Vec<&str> = parameters(Form::Benchmark).iter().map(|p| p.key).collect();
        let file = benchmark_toml(|key, x| {
            let i = keys.iter().position(|k| *k == key).unwrap();
            let p = &parameters(Form::Benchmark)[i];
            match TypedUnit::ALL.into_iter().find(|u| u.fits(p.unit)) {
                Some(u) => (format!("{key}{}", u.suffix()), text(i)),
                None => si(key, x),
            }
        });
        let a = parse(&file, Format::Toml).unwrap();
        let written = write(&a, Format::Toml).unwrap();
        for (i, p) in parameters(Form::Benchmark).iter().enumerate() {
            if let Some(u) = TypedUnit::ALL.into_iter().find(|u| u.fits(p.unit)) {
                let line = format!("{}{} = {} ", p.key, u.suffix(), text(i));
                prop_assert!(written.contains(&line), "{} in\n{}", line, written);
            }
        }
        prop_assert_eq!(parse(&written, Format::Toml).unwrap(), a);
    }

    /// The same for every length and angle of the JBike6 table, in its TOML tables.
    #[test]
    fn jbike6_suffixed_and_si_give_the_same_bicycle(
        typed in prop::collection::vec(-1e4f64..1e4, 64),
    ) {
        let crown = whipple::presets::find("schwinn-crown").unwrap().bicycle();
        let toml = write(&crown, Format::Toml).unwrap();
        let (mut suffixed, mut plain) = (String::new(), String::new());
        let mut table = String::new();
        let mut k = 0;
        for line in toml.lines() {
            if let Some(t) = line.strip_prefix("[jbike6.").and_then(|t| t.strip_suffix(']')) {
                table = format!("{t}.");
            }
            let field = line.split(" = ").next().unwrap_or("");
            let path = format!("{table}{field}");
            let p = parameters(Form::Jbike6).iter().find(|p| p.path == path);
            match p.and_then(|p| TypedUnit::ALL.into_iter().find(|u| u.fits(p.unit))) {
                Some(u) if line.contains(" = ") => {
                    let x = typed[k % typed.len()];
                    k += 1;
                    suffixed.push_str(&format!("{field}{} = {x:?}\n", u.suffix()));
                    plain.push_str(&format!("{field} = {:?}\n", u.to_si(x)));
                }
                _ => {
                    suffixed.push_str(line);
                    suffixed.push('\n');
                    plain.push_str(line);
                    plain.push('\n');
                }
            }
        }
        prop_assert!(k > 20, "{} lengths and angles in\n{}", k, toml);
        let a = parse(&suffixed, Format::Toml).unwrap();
        let b = parse(&plain, Format::Toml).unwrap();
        let bits = |bike: &Bicycle| bike.description.values().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&a), bits(&b));
        prop_assert_eq!(a.units.len(), k);
        let back = parse(&write(&a, Format::Toml).unwrap(), Format::Toml).unwrap();
        prop_assert_eq!(bits(&back), bits(&a));
    }
}
