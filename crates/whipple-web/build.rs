//! Bundles the page (`web/`) into `OUT_DIR/assets` so that the binary embeds it.
//!
//! Steps: copy `web/package.json` and `web/package-lock.json` to `OUT_DIR/npm`, run `npm ci`
//! there (skipped when the lockfile is unchanged since the last run), then run `web/build.mjs`
//! (esbuild, then gzip and brotli from Node's zlib) from there, reading `web/src` and
//! `web/index.html` and writing `OUT_DIR/assets`: the content-hashed files, their compressed
//! copies and `assets.rs`, the table `src/assets.rs` includes.
//! Nothing is written into the source tree. Cargo reruns this script only when a front-end
//! source, the package files or this script change.
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
    println!("cargo:rerun-if-env-changed=NPM");
    println!("cargo:rerun-if-env-changed=NODE");

    let npm = env::var("NPM").unwrap_or_else(|_| default_program("npm"));
    let node = env::var("NODE").unwrap_or_else(|_| default_program("node"));
    check_tool(&npm, "npm")?;
    check_tool(&node, "node")?;

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
    Ok(())
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
