//! Bundles the page (`web/`) into `OUT_DIR/assets` so that the binary embeds it.
//!
//! Steps: copy `web/package.json` and `web/package-lock.json` to `OUT_DIR/npm`, run `npm ci`
//! there (skipped when the lockfile is unchanged since the last run), then run `web/build.mjs`
//! (esbuild, then gzip and brotli from Node's zlib) from there, reading `web/src` and
//! `web/index.html` and writing `OUT_DIR/assets`: the content-hashed files, their compressed
//! copies and `assets.rs`, the table `src/assets.rs` includes.
//! Cargo reruns this script only when a front-end source, the package files, `prebuilt/` or
//! this script change.
//!
//! Without Node.js (a user's `cargo install` or `pip install`: Node is a developer's tool), the
//! page is the one built before and kept in `prebuilt/` (the same files and `manifest.json`,
//! without `assets.rs`), and `assets.rs` is written here from its manifest. With Node, the page
//! is built from the sources, and the test `tests/prebuilt.rs` fails when `prebuilt/` is not
//! exactly what they build; `WHIPPLE_WEB_UPDATE_PREBUILT=1 cargo build -p whipple-web` writes
//! it again (the one time this script writes into the source tree).
//!
//! Environment: `NPM` and `NODE` name the programs to run (default `npm` and `node`).

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn main() {
    if let Err(message) = build() {
        // A build script reports failure by panicking; say what to do about it.
        panic!("\n\nwhipple-web: cannot build the web page.\n{message}\n\n");
    }
}

fn build() -> Result<(), String> {
    let manifest = PathBuf::from(env::var("CARGO_MANIFEST_DIR").map_err(|e| e.to_string())?);
    let out = PathBuf::from(env::var("OUT_DIR").map_err(|e| e.to_string())?);
    let web = manifest.join("web");
    for path in [
        "web/package.json",
        "web/package-lock.json",
        "web/build.mjs",
        "web/index.html",
        "web/src",
    ] {
        println!("cargo:rerun-if-changed={path}");
    }
    println!("cargo:rerun-if-changed=prebuilt");
    println!("cargo:rerun-if-env-changed=NPM");
    println!("cargo:rerun-if-env-changed=NODE");
    println!("cargo:rerun-if-env-changed=WHIPPLE_WEB_UPDATE_PREBUILT");

    // Without the server (the API alone, for the static site's WebAssembly module) there is
    // no page to embed.
    if env::var_os("CARGO_FEATURE_SERVER").is_none() {
        return Ok(());
    }

    let npm = env::var("NPM").unwrap_or_else(|_| default_program("npm"));
    let node = env::var("NODE").unwrap_or_else(|_| default_program("node"));
    let prebuilt = manifest.join("prebuilt");
    if let Err(missing) = check_tool(&npm, "npm").and_then(|()| check_tool(&node, "node")) {
        if !prebuilt.join("manifest.json").is_file() {
            return Err(missing);
        }
        println!(
            "cargo:warning=whipple-web: no Node.js here, so the page embedded is the prebuilt one \
             (crates/whipple-web/prebuilt), built from these sources with Node"
        );
        embed_prebuilt(&prebuilt, &out.join("assets"))?;
        // No browser tests without Node's packages; no built page to compare with prebuilt/.
        println!("cargo:rustc-env=WHIPPLE_WEB_NODE_MODULES=");
        println!("cargo:rustc-env=WHIPPLE_WEB_BUILT_ASSETS=");
        return Ok(());
    }

    let npm_dir = out.join("npm");
    fs::create_dir_all(&npm_dir).map_err(|e| format!("creating {}: {e}", npm_dir.display()))?;
    let lock = read(&web.join("package-lock.json"))?;
    let package = read(&web.join("package.json"))?;
    let stamp_path = npm_dir.join(".installed-lock");
    let installed = fs::read_to_string(&stamp_path).unwrap_or_default();
    let wanted = format!("{package}\n{lock}");
    if installed != wanted || !npm_dir.join("node_modules").is_dir() {
        write(&npm_dir.join("package.json"), &package)?;
        write(&npm_dir.join("package-lock.json"), &lock)?;
        // --ignore-scripts: esbuild finds its platform binary through its optional dependency;
        // no package needs an install script, and none is allowed to fetch anything else.
        run(
            Command::new(&npm)
                .args([
                    "ci",
                    "--ignore-scripts",
                    "--no-audit",
                    "--no-fund",
                    "--loglevel=error",
                ])
                .current_dir(&npm_dir),
            "npm ci (fetching the pinned front-end build tools from the npm registry)",
        )?;
        write(&stamp_path, &wanted)?;
    }

    // build.mjs imports esbuild, so it runs from the directory holding node_modules.
    let script = read(&web.join("build.mjs"))?;
    write(&npm_dir.join("build.mjs"), &script)?;
    let assets = out.join("assets");
    run(
        Command::new(&node)
            .arg(npm_dir.join("build.mjs"))
            .arg(&web)
            .arg(&assets)
            .current_dir(&npm_dir),
        "node build.mjs (bundling the page with esbuild)",
    )?;
    for name in ["index.html", "index.html.br", "manifest.json", "assets.rs"] {
        if !assets.join(name).is_file() {
            return Err(format!("the bundler did not write {name}"));
        }
    }
    // Tests find playwright-core (for the end-to-end test) here.
    println!(
        "cargo:rustc-env=WHIPPLE_WEB_NODE_MODULES={}",
        npm_dir.join("node_modules").display()
    );
    // tests/prebuilt.rs compares these with prebuilt/.
    println!(
        "cargo:rustc-env=WHIPPLE_WEB_BUILT_ASSETS={}",
        assets.display()
    );
    if env::var("WHIPPLE_WEB_UPDATE_PREBUILT").is_ok_and(|v| v == "1") {
        update_prebuilt(&assets, &prebuilt)?;
    }
    Ok(())
}

/// The files of a built page that `prebuilt/` keeps: all but `assets.rs`, whose paths are this
/// build's.
fn page_files(dir: &Path) -> Result<Vec<String>, String> {
    let mut names = Vec::new();
    for entry in fs::read_dir(dir).map_err(|e| format!("reading {}: {e}", dir.display()))? {
        let entry = entry.map_err(|e| format!("reading {}: {e}", dir.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name != "assets.rs" && entry.path().is_file() {
            names.push(name);
        }
    }
    names.sort();
    Ok(names)
}

/// Replaces `prebuilt/` with the page just built (`WHIPPLE_WEB_UPDATE_PREBUILT=1`).
fn update_prebuilt(assets: &Path, prebuilt: &Path) -> Result<(), String> {
    if prebuilt.is_dir() {
        fs::remove_dir_all(prebuilt)
            .map_err(|e| format!("removing {}: {e}", prebuilt.display()))?;
    }
    fs::create_dir_all(prebuilt).map_err(|e| format!("creating {}: {e}", prebuilt.display()))?;
    for name in page_files(assets)? {
        fs::copy(assets.join(&name), prebuilt.join(&name))
            .map_err(|e| format!("copying {name} into {}: {e}", prebuilt.display()))?;
    }
    Ok(())
}

/// Writes `assets/assets.rs` for the page in `prebuilt/`: one `Asset` per entry of its
/// `manifest.json` (`[{name, type, hash, immutable, …}]`, as `web/build.mjs` writes it), the
/// bodies included from `prebuilt/`.
fn embed_prebuilt(prebuilt: &Path, assets: &Path) -> Result<(), String> {
    let manifest: serde_json::Value = serde_json::from_str(&read(&prebuilt.join("manifest.json"))?)
        .map_err(|e| format!("prebuilt/manifest.json: {e}"))?;
    let entries = manifest
        .as_array()
        .ok_or("prebuilt/manifest.json: not a list")?;
    let mut rows = String::new();
    for entry in entries {
        let text = |key: &str| {
            entry[key]
                .as_str()
                .map(str::to_owned)
                .ok_or_else(|| format!("prebuilt/manifest.json: an entry without `{key}`"))
        };
        let (name, content_type, hash) = (text("name")?, text("type")?, text("hash")?);
        let immutable = entry["immutable"]
            .as_bool()
            .ok_or("prebuilt/manifest.json: an entry without `immutable`")?;
        let file = |suffix: &str| -> Result<String, String> {
            let path = prebuilt.join(format!("{name}{suffix}"));
            if !path.is_file() {
                return Err(format!("prebuilt/ lacks {name}{suffix}"));
            }
            Ok(format!("{:?}", path.display().to_string()))
        };
        rows.push_str(&format!(
            "    Asset {{\n        name: {name:?},\n        content_type: {content_type:?},\n        \
             hash: {hash:?},\n        immutable: {immutable},\n        identity: include_bytes!({}),\n        \
             gzip: include_bytes!({}),\n        brotli: include_bytes!({}),\n    }},\n",
            file("")?,
            file(".gz")?,
            file(".br")?
        ));
    }
    fs::create_dir_all(assets).map_err(|e| format!("creating {}: {e}", assets.display()))?;
    write(
        &assets.join("assets.rs"),
        &format!(
            "// Written by build.rs from prebuilt/manifest.json: the page's files, embedded.\n\
             pub(crate) static ASSETS: &[Asset] = &[\n{rows}];\n"
        ),
    )
}

fn default_program(name: &str) -> String {
    if cfg!(windows) {
        format!("{name}.cmd")
    } else {
        name.to_string()
    }
}

fn check_tool(program: &str, name: &str) -> Result<(), String> {
    match Command::new(program).arg("--version").output() {
        Ok(output) if output.status.success() => Ok(()),
        Ok(output) => Err(format!(
            "`{program} --version` failed ({}): {}",
            output.status,
            String::from_utf8_lossy(&output.stderr).trim()
        )),
        Err(e) => Err(format!(
            "`{name}` was not found ({e}).\n\
             Building whipple-web (the page of `whipple serve`) needs Node.js and npm at build \
             time only: install them (Debian: `apt-get install nodejs npm`), or point the \
             NODE and NPM environment variables at them. The built binary needs neither."
        )),
    }
}

fn run(command: &mut Command, what: &str) -> Result<(), String> {
    let output: Output = command
        .output()
        .map_err(|e| format!("{what}: could not start: {e}"))?;
    if output.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{what} failed ({}):\n{}\n{}",
            output.status,
            String::from_utf8_lossy(&output.stdout).trim(),
            String::from_utf8_lossy(&output.stderr).trim()
        ))
    }
}

fn read(path: &Path) -> Result<String, String> {
    fs::read_to_string(path).map_err(|e| format!("reading {}: {e}", path.display()))
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    fs::write(path, text).map_err(|e| format!("writing {}: {e}", path.display()))
}
