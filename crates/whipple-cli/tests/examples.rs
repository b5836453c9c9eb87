//! `whipple examples --out DIR`: the field's files the guide's examples read, written whole
//! into a folder, each byte for byte the copy kept with the library's tests, with the sources
//! and licences beside them.

use crate::common;

use std::fs;
use std::path::Path;

use crate::common::{stderr_of_failure, whipple};

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

#[test]
fn the_field_files_are_written_as_kept() {
    let dir = common::scratch("examples-written").join("new folder");
    let done = whipple(&["examples", "--out", dir.to_str().expect("a UTF-8 path")]);
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let names: Vec<String> = fs::read_dir(&dir)
        .expect("the folder")
        .map(|e| {
            e.expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    assert!(names.len() >= 90, "{} files", names.len());
    let data = root().join("crates/whipple/tests/data");
    for (name, kept) in [
        (
            "FisherBenchmark.txt",
            data.join("bicycleparameters/FisherBenchmark.txt"),
        ),
        ("BrowserPar.txt", data.join("humancontrol/BrowserPar.txt")),
        (
            "Optimal05SteerGains.txt",
            data.join("humancontrol/gains/Optimal05SteerGains.txt"),
        ),
        (
            "Optimal05Par.txt",
            data.join("humancontrol/optimal/Optimal05Par.txt"),
        ),
        (
            "BrowserMeasured.txt",
            data.join("measured/BrowserMeasured.txt"),
        ),
        (
            "JasonYeadonMeas.txt",
            data.join("yeadon/JasonYeadonMeas.txt"),
        ),
        (
            "README-bicycleparameters.md",
            data.join("bicycleparameters/README.md"),
        ),
        (
            "README-humancontrol.md",
            data.join("humancontrol/README.md"),
        ),
        ("THIRD-PARTY.md", root().join("THIRD-PARTY.md")),
    ] {
        assert_eq!(
            fs::read(dir.join(name)).expect(name),
            fs::read(&kept).expect("the kept copy"),
            "{name}"
        );
    }
    let mat = names
        .iter()
        .find(|n| n.ends_with(".mat"))
        .expect("a .mat record");
    assert!(!fs::read(dir.join(mat)).expect("the record").is_empty());
    // Written again over the same folder: the same files.
    let again = whipple(&["examples", "--out", dir.to_str().expect("a UTF-8 path")]);
    assert!(again.status.success());
}

#[test]
fn a_folder_that_cannot_be_one_is_refused() {
    let dir = common::scratch("examples-refused");
    let file = dir.join("a-file");
    fs::write(&file, "x").expect("a file");
    let message = stderr_of_failure(&whipple(&[
        "examples",
        "--out",
        file.to_str().expect("a UTF-8 path"),
    ]));
    assert!(message.contains("not a directory"), "{message}");
    assert_eq!(fs::read_to_string(&file).expect("the file"), "x");
    let message = stderr_of_failure(&whipple(&["examples", "--out", "/dev/null"]));
    assert!(message.contains("--out"), "{message}");
}
