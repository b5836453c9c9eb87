//! `prebuilt/` (the page embedded when a user builds without Node.js: `cargo install`, `pip
//! install`) must be exactly what the sources build: every file of the page just built by
//! `build.rs` with Node (`OUT_DIR/assets`) byte for byte, and no other. When it is not, the
//! message says how to write it again.
//!
//! A build without Node has no page of its own to compare: the test says so and passes, unless
//! `WHIPPLE_E2E_REQUIRED=1` (CI, which has Node) makes that an error.

use std::fs;
use std::path::Path;

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .filter_map(Result::ok)
        .filter(|e| e.path().is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| name != "assets.rs")
        .collect();
    names.sort();
    names
}

#[test]
fn the_prebuilt_page_is_what_the_sources_build() {
    let built = env!("WHIPPLE_WEB_BUILT_ASSETS");
    if built.is_empty() {
        let required = std::env::var("WHIPPLE_E2E_REQUIRED").is_ok_and(|v| v == "1");
        assert!(
            !required,
            "built without Node: the page could not be compared with prebuilt/"
        );
        eprintln!("built without Node: the embedded page is prebuilt/ itself; nothing to compare");
        return;
    }
    let built = Path::new(built);
    let prebuilt = Path::new(env!("CARGO_MANIFEST_DIR")).join("prebuilt");
    let again = "write it again with `WHIPPLE_WEB_UPDATE_PREBUILT=1 cargo build -p whipple-web` \
                 and commit crates/whipple-web/prebuilt";
    let (ours, theirs) = (files(built), files(&prebuilt));
    assert_eq!(
        ours, theirs,
        "prebuilt/ does not hold the files the sources build: {again}"
    );
    for name in &ours {
        let (a, b) = (
            fs::read(built.join(name)).expect("a built file"),
            fs::read(prebuilt.join(name)).expect("a prebuilt file"),
        );
        assert!(
            a == b,
            "prebuilt/{name} is not what the sources build ({} bytes built, {} kept): {again}",
            a.len(),
            b.len()
        );
    }
}
