//! The page in real headless Chromium (Debian's `chromium`), driven by Playwright
//! (`e2e/*.mjs`, playwright-core and axe-core from the crate's pinned npm packages), against a server on an
//! ephemeral loopback port.
//!
//! A harness of its own (libtest-mimic, `harness = false`) so that a run without Chromium is
//! visible: each script is reported **ignored**, with the reason printed, and counted in the
//! summary, rather than passing silently. With `WHIPPLE_E2E_REQUIRED=1` (which `.ci/run`
//! exports) a missing Chromium fails instead. `CHROMIUM` overrides the browser's path.
//!
//! Each browser script is one trial in [`SCRIPTS`]: add a new `e2e/NAME.mjs` there.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use libtest_mimic::{Arguments, Failed, Trial};
use whipple_web::{ServeOptions, Server};

/// The browser scripts, each a test: (test name, script under `e2e/`).
/// `page.mjs`: the page's checks (plots, links, modes, weight, accessibility, layouts; prints
/// the navigation-to-plot time and the page's weight).
const SCRIPTS: &[(&str, &str)] = &[
    ("page_in_headless_chromium", "test.mjs"),
    (
        "page_plots_links_modes_layouts_in_headless_chromium",
        "page.mjs",
    ),
];

/// The same scripts against the static site (`crates/whipple-wasm/build-site`), whose folder
/// `WHIPPLE_SITE` names, served by Python's plain static file server; `page.mjs` also compares
/// the site's answers with a `whipple serve`'s, bit for bit.
const SITE_SCRIPTS: &[(&str, &str)] = &[
    ("static_site_in_headless_chromium", "test.mjs"),
    (
        "static_site_plots_links_modes_layouts_offline_in_headless_chromium",
        "page.mjs",
    ),
];

/// The user guide's screenshots (the names of docs/screenshots/*.png), taken of the page this
/// build serves by `e2e/shots.mjs` with `SHOTS_GUIDE=1`, into `guide-screenshots` under the
/// target folder; the guide's build (docs/hooks/screenshots.py) shows them in place of the
/// copies kept in docs/screenshots, so the guide pictures the page of the same build.
const GUIDE_SHOTS: (&str, &str) = ("guide_screenshots_in_headless_chromium", "shots.mjs");

/// Where the guide's screenshots go: `guide-screenshots` in `CARGO_TARGET_DIR`, else in the
/// workspace's `target`.
fn guide_screenshots() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"))
        .join("guide-screenshots")
}

/// One browser run must end within this: `page.mjs` takes about 110–150 s on CI's two cores with
/// another build beside it; a run that hangs is stopped here.
const LIMIT: Duration = Duration::from_secs(480);

/// One browser at a time: two SwiftShader-drawn pages on CI's two cores would slow each other
/// past their timeouts (the harness runs trials in parallel).
static ONE_BROWSER: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn chromium() -> String {
    std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into())
}

fn required() -> bool {
    std::env::var("WHIPPLE_E2E_REQUIRED").is_ok_and(|v| v == "1")
}

fn main() {
    let args = Arguments::from_args();
    let browser = chromium();
    let present = Path::new(&browser).exists();
    if !present {
        let reason = if required() {
            "it is required here (WHIPPLE_E2E_REQUIRED=1): the tests fail"
        } else {
            "the tests are IGNORED (set WHIPPLE_E2E_REQUIRED=1 to make that an error)"
        };
        eprintln!(
            "\n*** whipple-web e2e: no Chromium at {browser}; {reason}. ***\n\
             *** Install it with `apt-get install -y chromium` (or set CHROMIUM). ***\n"
        );
    }
    let site = std::env::var_os("WHIPPLE_SITE").map(PathBuf::from);
    if site.is_none() {
        let reason = if required() {
            "it is required here (WHIPPLE_E2E_REQUIRED=1): the tests fail"
        } else {
            "its tests are IGNORED"
        };
        eprintln!(
            "\n*** whipple-web e2e: no static site (WHIPPLE_SITE names the folder \
             crates/whipple-wasm/build-site writes); {reason}. ***\n"
        );
    }
    let mut trials: Vec<Trial> = SCRIPTS
        .iter()
        .map(|&(name, script)| {
            let browser = browser.clone();
            Trial::test(name, move || {
                run_script(script, &browser, None, &Run::default())
            })
            .with_ignored_flag(!present && !required())
        })
        .collect();
    trials.push({
        let browser = browser.clone();
        Trial::test(GUIDE_SHOTS.0, move || take_guide_screenshots(&browser))
            .with_ignored_flag(!present && !required())
    });
    trials.extend(SITE_SCRIPTS.iter().map(|&(name, script)| {
        let browser = browser.clone();
        let folder = site.clone();
        Trial::test(name, move || match &folder {
            Some(folder) => run_script(script, &browser, Some(folder), &Run::default()),
            None => Err(
                "the static site is required here (WHIPPLE_E2E_REQUIRED=1): build it \
                 with crates/whipple-wasm/build-site DIR and set WHIPPLE_SITE=DIR"
                    .into(),
            ),
        })
        .with_ignored_flag((!present || site.is_none()) && !required())
    }));
    libtest_mimic::run(&args, trials).exit();
}

/// What a script is given besides the page's address: more arguments and environment.
#[derive(Default)]
struct Run {
    args: Vec<String>,
    env: Vec<(&'static str, String)>,
}

/// The guide's screenshots into a fresh folder, which replaces the last one only when every
/// screenshot was taken (whole or not at all).
fn take_guide_screenshots(browser: &str) -> Result<(), Failed> {
    let done = guide_screenshots();
    let partial = done.with_extension("partial");
    let _ = std::fs::remove_dir_all(&partial);
    std::fs::create_dir_all(&partial).map_err(|e| format!("{}: {e}", partial.display()))?;
    let run = Run {
        args: vec![partial.display().to_string(), "390,1280".into()],
        env: vec![("SHOTS_GUIDE", "1".into())],
    };
    run_script(GUIDE_SHOTS.1, browser, None, &run)?;
    let kept = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/screenshots");
    for entry in std::fs::read_dir(&kept).map_err(|e| format!("{}: {e}", kept.display()))? {
        let name = entry.map_err(|e| e.to_string())?.file_name();
        if !partial.join(&name).is_file() {
            return Err(format!(
                "shots.mjs took no {} (docs/screenshots has it): add its state to GUIDE there",
                name.to_string_lossy()
            )
            .into());
        }
    }
    let _ = std::fs::remove_dir_all(&done);
    std::fs::rename(&partial, &done).map_err(|e| format!("{}: {e}", done.display()))?;
    println!("e2e: the guide's screenshots are in {}", done.display());
    Ok(())
}

/// Serves the page on an ephemeral loopback port and runs one script against it; with `site`,
/// against that static site served by a plain static file server, the server beside it for
/// comparison.
fn run_script(script: &str, browser: &str, site: Option<&Path>, run: &Run) -> Result<(), Failed> {
    if !Path::new(browser).exists() {
        return Err(format!(
            "the e2e tests are required here (WHIPPLE_E2E_REQUIRED=1) but there is no Chromium at \
             {browser}: `apt-get install -y chromium` (or set CHROMIUM)"
        )
        .into());
    }
    let _turn = ONE_BROWSER
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| format!("tokio runtime: {e}"))?;
    runtime.block_on(async {
        let server = Server::bind(&ServeOptions {
            port: 0,
            ..ServeOptions::default()
        })
        .await
        .map_err(|e| format!("cannot start the server: {e}"))?;
        let url = server.url();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let serving = tokio::spawn(server.serve_until(async {
            let _ = stopped.await;
        }));
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("e2e")
            .join(script);
        let browser = browser.to_string();
        let site = site.map(Path::to_path_buf);
        let (args, extra) = (run.args.clone(), run.env.clone());
        let outcome = tokio::task::spawn_blocking(move || match site {
            None => run_node(&path, &url, &args, &browser, &extra),
            Some(folder) => {
                let files = StaticServer::start(&folder)?;
                let mut env = vec![("E2E_BACKEND", "site".to_string()), ("E2E_SERVER", url)];
                env.extend(extra);
                run_node(&path, &files.url, &args, &browser, &env)
            }
        })
        .await
        .map_err(|e| format!("the browser run panicked: {e}"))?;
        let _ = stop.send(());
        serving
            .await
            .map_err(|e| format!("the server task: {e}"))?
            .map_err(|e| format!("the server: {e}"))?;
        outcome
    })
}

/// Python's `http.server` serving a folder on an ephemeral loopback port: a plain static file
/// server, as a user's `python3 -m http.server` (no compression, no API). Ended when dropped.
struct StaticServer {
    child: std::process::Child,
    url: String,
}

impl StaticServer {
    fn start(folder: &Path) -> Result<StaticServer, Failed> {
        use std::io::BufRead;
        let mut child = Command::new("python3")
            .args([
                "-u",
                "-m",
                "http.server",
                "--bind",
                "127.0.0.1",
                "--directory",
            ])
            .arg(folder)
            .arg("0")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| format!("cannot start python3 -m http.server: {e}"))?;
        // "Serving HTTP on 127.0.0.1 port 41234 (http://127.0.0.1:41234/) ..."
        let first = child.stdout.take().and_then(|out| {
            std::io::BufReader::new(out)
                .lines()
                .next()
                .and_then(Result::ok)
        });
        let url = first.as_deref().and_then(|line| {
            let from = line.find("(http://")? + 1;
            let to = from + line[from..].find(')')?;
            Some(line[from..to].to_string())
        });
        match url {
            Some(url) => Ok(StaticServer { child, url }),
            None => {
                let _ = child.kill();
                let _ = child.wait();
                Err(format!("python3 -m http.server did not say where it serves: {first:?}").into())
            }
        }
    }
}

impl Drop for StaticServer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Runs `node SCRIPT URL ARGS...` with `env`, killing it past [`LIMIT`].
fn run_node(
    script: &Path,
    url: &str,
    args: &[String],
    chromium: &str,
    env: &[(&str, String)],
) -> Result<(), Failed> {
    let mut child = Command::new("node")
        .arg(script)
        .arg(url)
        .args(args)
        .envs(env.iter().map(|(k, v)| (k, v)))
        .env("WHIPPLE_WEB_NODE_MODULES", env!("WHIPPLE_WEB_NODE_MODULES"))
        .env("CHROMIUM", chromium)
        .env("E2E_TIMEOUT_MS", (LIMIT.as_millis() - 10_000).to_string())
        .stdin(Stdio::null())
        .spawn()
        .map_err(|e| format!("cannot start node: {e}"))?;
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            println!(
                "e2e {}: {:.1} s",
                script.display(),
                started.elapsed().as_secs_f64()
            );
            return if status.success() {
                Ok(())
            } else {
                Err(format!(
                    "{} failed ({status}); see its output above",
                    script.display()
                )
                .into())
            };
        }
        if started.elapsed() > LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "{} took longer than {} s",
                script.display(),
                LIMIT.as_secs()
            )
            .into());
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}
