//! Bundles the field's example files that the user guide's commands read, for `whipple
//! examples --out DIR`: BicycleParameters' and HumanControl's parameter files, BicycleParameters'
//! raw bench measurements and pendulum records, and Yeadon riders — the copies kept with the
//! library's tests (`crates/whipple/tests/data`), each folder's README (their sources and
//! licences) and THIRD-PARTY.md beside them. They are found beside this crate, in the
//! repository and in the Python package's sdist (which holds the core crate's package, its
//! test data and THIRD-PARTY.md included); this crate built from its own package alone bundles
//! none, and the command says so.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::{env, fs};

/// The folders of `crates/whipple/tests/data` and the endings of the files taken from each:
/// the files the guide's examples name (crates/whipple-cli/tests/guide.rs runs them on exactly
/// these, written by `whipple examples`).
const INPUTS: [(&str, &[&str]); 8] = [
    ("bicycleparameters", &[".txt", ".yml"]),
    ("humancontrol", &[".txt", ".yml"]),
    ("humancontrol/gains", &["SteerGains.txt"]),
    ("humancontrol/optimal", &["Par.txt"]),
    ("bicycleparameters-yaml", &[".txt", ".yml"]),
    ("measured", &["Measured.txt"]),
    ("measured/periods", &[".mat"]),
    ("yeadon", &["YeadonMeas.txt", "YeadonCFG.txt"]),
];

fn main() {
    let manifest = PathBuf::from(env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let data = manifest.join("../whipple/tests/data");
    // The licences: the repository's THIRD-PARTY.md, else the core crate's (a link to it in the
    // repository, which the crate's package, and so the Python sdist, carries as a file; a
    // checkout without links, as on Windows, has the root's).
    let candidates = [
        manifest.join("../../THIRD-PARTY.md"),
        manifest.join("../whipple/THIRD-PARTY.md"),
    ];
    println!("cargo:rerun-if-changed={}", data.display());
    for c in &candidates {
        println!("cargo:rerun-if-changed={}", c.display());
    }
    let third_party = candidates
        .iter()
        .find(|c| c.is_file())
        .cloned()
        .unwrap_or_else(|| candidates[0].clone());
    let mut files: Vec<(String, PathBuf)> = Vec::new();
    if data.is_dir() && third_party.is_file() {
        for (sub, endings) in INPUTS {
            let folder = data.join(sub);
            let mut names: Vec<String> = fs::read_dir(&folder)
                .map(|entries| {
                    entries
                        .filter_map(|e| e.ok())
                        .map(|e| e.file_name().to_string_lossy().into_owned())
                        .collect()
                })
                .unwrap_or_default();
            names.sort();
            for name in names {
                if endings.iter().any(|e| name.ends_with(e)) {
                    files.push((name.clone(), folder.join(&name)));
                }
            }
            let readme = folder.join("README.md");
            if readme.is_file() {
                files.push((format!("README-{}.md", sub.replace('/', "-")), readme));
            }
        }
        files.push(("THIRD-PARTY.md".into(), third_party));
    }
    let mut names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), files.len(), "two example files of one name");
    let mut code = String::from(
        "/// The bundled example files: (name, contents).\npub(crate) const FILES: &[(&str, &[u8])] = &[\n",
    );
    for (name, path) in &files {
        let absolute = fs::canonicalize(path).unwrap_or_else(|_| path.clone());
        let _ = writeln!(
            code,
            "    ({name:?}, include_bytes!({:?})),",
            absolute.display().to_string()
        );
    }
    code.push_str("];\n");
    let out = Path::new(&env::var("OUT_DIR").expect("cargo sets it")).join("examples.rs");
    fs::write(out, code).expect("write the list of example files");
}
