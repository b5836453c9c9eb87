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

/// One browser run must end within this.
const LIMIT: Duration = Duration::from_secs(300);

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
    let trials = SCRIPTS
        .iter()
        .map(|&(name, script)| {
            let browser = browser.clone();
            Trial::test(name, move || run_script(script, &browser))
                .with_ignored_flag(!present && !required())
        })
        .collect();
    libtest_mimic::run(&args, trials).exit();
}

/// Serves the page on an ephemeral loopback port and runs one script against it.
fn run_script(script: &str, browser: &str) -> Result<(), Failed> {
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
        let outcome = tokio::task::spawn_blocking(move || run_node(&path, &url, &browser))
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

/// Runs `node SCRIPT URL`, killing it past [`LIMIT`].
fn run_node(script: &Path, url: &str, chromium: &str) -> Result<(), Failed> {
    let mut child = Command::new("node")
        .arg(script)
        .arg(url)
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
