//! The hostile catalogue: every seed input kept under `fuzz/seeds/TARGET/` (the fuzz targets'
//! starting corpus and this project's regression inputs) is replayed here on stable Rust,
//! through the same parser the target feeds. A seed named `err-*` must be refused with a
//! message; one named `ok-*` must be read and survive a round trip. A new hostile input found by
//! hand or by the fuzzer goes in the same folders.

use std::fs;
use std::path::PathBuf;

use whipple::advanced::io::{Format, parse, write};

fn seeds(target: &str) -> Vec<(String, Vec<u8>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/seeds")
        .join(target);
    let mut out: Vec<(String, Vec<u8>)> = fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                fs::read(e.path()).expect("a seed reads"),
            )
        })
        .collect();
    out.sort();
    assert!(!out.is_empty(), "no seeds in {}", dir.display());
    out
}

fn replay(name: &str, text: &str, format: Format) {
    match parse(text, format) {
        Ok(bike) => {
            assert!(
                name.starts_with("ok-"),
                "{name}: read, but it is a hostile input"
            );
            let written = write(&bike, Format::Toml).expect("writes");
            let again = parse(&written, Format::Toml).expect("reads back");
            assert_eq!(
                write(&again, Format::Toml).expect("writes"),
                written,
                "{name}"
            );
        }
        Err(e) => {
            assert!(name.starts_with("err-"), "{name}: refused: {e}");
            assert!(!e.to_string().is_empty(), "{name}");
        }
    }
}

#[test]
fn field_file_seeds() {
    const FORMATS: [Format; 3] = [
        Format::BicycleParametersTxt,
        Format::HumanControlTxt,
        Format::Yaml,
    ];
    for (name, data) in seeds("parse_field_files") {
        // The target's first byte picks the format.
        let (&which, rest) = data.split_first().expect("a format byte");
        let text = std::str::from_utf8(rest).expect("UTF-8");
        replay(&name, text, FORMATS[usize::from(which) % FORMATS.len()]);
    }
}

#[test]
fn json_seeds() {
    for (name, data) in seeds("parse_json") {
        replay(
            &name,
            std::str::from_utf8(&data).expect("UTF-8"),
            Format::Json,
        );
    }
}

#[test]
fn toml_seeds() {
    for (name, data) in seeds("parse_toml") {
        replay(
            &name,
            std::str::from_utf8(&data).expect("UTF-8"),
            Format::Toml,
        );
    }
}

/// BicycleParameters' raw measurements: an `ok-*` seed reads and computes with every σ finite;
/// an `err-*` seed is refused, by the reader or by the pipeline, naming the key at fault.
#[test]
fn measured_file_seeds() {
    use whipple::advanced::measured::{MeasuredParameters, read_measurements};
    for (name, data) in seeds("measured_files") {
        let text = std::str::from_utf8(&data).expect("UTF-8");
        let result =
            read_measurements(text).and_then(|file| MeasuredParameters::new(&file.measurements));
        match result {
            Ok(parameters) => {
                assert!(name.starts_with("ok-"), "{name}: accepted");
                assert!(parameters.sigma.values().all(|s| s.is_finite()), "{name}");
            }
            Err(e) => {
                assert!(name.starts_with("err-"), "{name}: refused: {e}");
                let message = e.to_string();
                let key = if name.contains("dF") { "dF" } else { "TcB1" };
                assert!(message.contains(key), "{name}: {message}");
            }
        }
    }
}

/// `yeadon`'s files: an `ok-*` seed reads (a `-meas` one also builds a body with finite mass,
/// mass centre and inertia); an `err-*` seed is refused by the reader or the model.
#[test]
fn yeadon_file_seeds() {
    use whipple::advanced::rider::{
        YeadonConfiguration, read_yeadon_configuration, read_yeadon_measurements, yeadon_body,
    };
    for (name, data) in seeds("yeadon_files") {
        let text = std::str::from_utf8(&data).expect("UTF-8");
        let result = if name.ends_with("-cfg.txt") {
            read_yeadon_configuration(text).map(|_| ())
        } else {
            read_yeadon_measurements(text)
                .and_then(|m| yeadon_body(&m, &YeadonConfiguration::zero()))
                .map(|body| {
                    assert!(body.mass.is_finite() && body.inertia.iter().all(|x| x.is_finite()));
                })
        };
        match result {
            Ok(()) => assert!(name.starts_with("ok-"), "{name}: accepted"),
            Err(e) => assert!(name.starts_with("err-"), "{name}: refused: {e}"),
        }
    }
}
