//! The page in real headless Chromium (Debian's `chromium`), driven by Playwright
//! (`e2e/test.mjs` and `e2e/page.mjs`, issue 14's checks; playwright-core and axe-core from the
//! crate's pinned npm packages), each against its own server on an ephemeral loopback port.
//!
//! Skipped, loudly, when Chromium is absent, unless `WHIPPLE_E2E_REQUIRED=1` or `CI` is set, in
//! which case its absence fails the test. `CHROMIUM` overrides the browser's path.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use whipple_web::{ServeOptions, Server};

/// The whole browser run must end within this.
const LIMIT: Duration = Duration::from_secs(300);

type TestResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn page_in_headless_chromium() -> TestResult {
    run_script("e2e/test.mjs").await
}

/// Issue 14: every numbered bug, exploring the plots, links, modes, weight, accessibility and
/// layouts (prints the navigation-to-plot time and the page's weight).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn page_issue_14_in_headless_chromium() -> TestResult {
    run_script("e2e/page.mjs").await
}

/// One browser at a time: two SwiftShader-drawn pages on CI's two cores would slow each other
/// past their timeouts.
static ONE_BROWSER: tokio::sync::Mutex<()> = tokio::sync::Mutex::const_new(());

async fn run_script(name: &'static str) -> TestResult {
    let _turn = ONE_BROWSER.lock().await;
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !Path::new(&chromium).exists() {
        // Required in CI (which sets CI=true and installs Chromium) or when asked for.
        let required = std::env::var("WHIPPLE_E2E_REQUIRED").is_ok_and(|v| v == "1")
            || std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false");
        let message = format!(
            "\n\n*** whipple-web e2e test SKIPPED: no Chromium at {chromium}. ***\n\
             *** Install it with `apt-get install -y chromium` (or set CHROMIUM). ***\n"
        );
        if required {
            return Err(format!(
                "the e2e test is required here (CI or WHIPPLE_E2E_REQUIRED=1) but there is no Chromium at {chromium}: \
                 `apt-get install -y chromium` (or set CHROMIUM)"
            )
            .into());
        }
        eprintln!("{message}");
        return Ok(());
    }
    let server = Server::bind(&ServeOptions {
        port: 0,
        ..ServeOptions::default()
    })
    .await?;
    let url = server.url();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let serving = tokio::spawn(server.serve_until(async {
        let _ = stopped.await;
    }));

    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(name);
    let outcome = tokio::task::spawn_blocking(move || run_node(&script, &url, &chromium)).await?;
    let _ = stop.send(());
    serving.await??;
    outcome
}

/// Runs `node test.mjs URL`, killing it past [`LIMIT`].
fn run_node(script: &Path, url: &str, chromium: &str) -> TestResult {
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
        if let Some(status) = child.try_wait()? {
            println!("e2e: {:.1} s", started.elapsed().as_secs_f64());
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
