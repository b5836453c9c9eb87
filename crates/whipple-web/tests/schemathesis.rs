//! Schemathesis (a schema-driven API fuzzer, from PyPI in a throw-away environment,
//! never a dependency) against the real server, a bounded number of cases per operation: no
//! 5xx, every status, content type and body as the OpenAPI document says, and no operation
//! whose every generated request the server refused.
//!
//! The `schemathesis` (or `st`) executable is taken from `WHIPPLE_SCHEMATHESIS`. Skipped,
//! loudly, when that is unset, unless `CI` is set (`.ci/run` installs it into a venv under
//! /tmp and sets the variable): then its absence fails the test.

use std::process::Command;

use whipple_web::{ServeOptions, Server};

/// Examples per operation: about 800 requests in all, about 45 s on two busy cores.
const EXAMPLES: &str = "50";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn schemathesis_finds_no_server_error_and_no_schema_mismatch() {
    let Some(executable) = std::env::var_os("WHIPPLE_SCHEMATHESIS") else {
        let required = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false");
        assert!(
            !required,
            "CI is set but WHIPPLE_SCHEMATHESIS is not: install schemathesis into a venv \
             (python3 -m venv /tmp/st && /tmp/st/bin/pip install schemathesis) and set \
             WHIPPLE_SCHEMATHESIS=/tmp/st/bin/schemathesis"
        );
        eprintln!(
            "SKIPPED: schemathesis run (set WHIPPLE_SCHEMATHESIS to its executable to run it)"
        );
        return;
    };
    let server = Server::bind(&ServeOptions {
        port: 0,
        ..ServeOptions::default()
    })
    .await
    .expect("binds");
    let url = format!("http://{}/api/openapi.json", server.local_addr());
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let serving = tokio::spawn(server.serve_until(async {
        let _ = stopped.await;
    }));
    // The requests and answers, to count the accepted ones per operation (HAR, JSON).
    let reports = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("schemathesis-har");
    let _ = std::fs::remove_dir_all(&reports);
    let report_dir = reports.clone();
    let output = tokio::task::spawn_blocking(move || {
        Command::new(executable)
            // Its cache (`.schemathesis/`) goes to the target directory, not the source tree.
            .current_dir(env!("CARGO_TARGET_TMPDIR"))
            .args([
                "run",
                &url,
                "--max-examples",
                EXAMPLES,
                "--checks",
                // Not `positive_data_acceptance`: the schema states each field's type and
                // simple bounds, not the physics (a positive-definite mass matrix, a wheel
                // that touches the ground), which the server checks and answers with a 422.
                "not_a_server_error,status_code_conformance,content_type_conformance,response_schema_conformance",
                "--seed",
                "10",
                "--no-color",
                "--report",
                "har",
                "--report-dir",
            ])
            .arg(&report_dir)
            .output()
            .expect("schemathesis runs")
    })
    .await
    .expect("joins");
    let _ = stop.send(());
    let _ = serving.await;
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "schemathesis found problems:\n{text}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    // The document says what the server enforces, so that what it
    // accepts is accepted: an operation where every request schemathesis made from the
    // document was refused (400/422) is a document that promises more than the server keeps.
    // Counted from the HAR report. (Schemathesis's own "mostly rejected generated data"
    // warning varies from run to run with the same seed, as the physics refuses random
    // bicycles the schema cannot rule out: it is printed, not asserted.)
    let accepted = accepted_per_operation(&reports);
    let doc: serde_json::Value =
        serde_json::from_str(include_str!("../src/openapi.json")).expect("the document");
    let mut never = Vec::new();
    for (path, item) in doc["paths"].as_object().expect("paths") {
        if item.get("post").is_some() && accepted.get(path.as_str()).copied().unwrap_or(0) == 0 {
            never.push(path.clone());
        }
    }
    assert!(
        never.is_empty(),
        "the server refused every request the document allowed for {never:?}:\n{text}"
    );
    if text.contains("mostly rejected generated data") {
        eprintln!(
            "note: schemathesis: {}",
            text.lines()
                .filter(|l| l.contains("POST"))
                .collect::<Vec<_>>()
                .join("; ")
        );
    }
    // Every operation of the document was tested (schemathesis skips the ones whose schema is
    // not valid OpenAPI 3.0): "Selected: 13/13" then "Tested: 13".
    let total = text
        .split_once("Selected: ")
        .and_then(|(_, rest)| rest.split_whitespace().next())
        .and_then(|n| n.split('/').nth(1))
        .unwrap_or("?");
    assert!(
        text.contains(&format!("Tested: {total}")),
        "not every operation was tested:\n{text}"
    );
}

/// The number of 2xx answers to POST requests per path in the HAR reports under `dir`.
fn accepted_per_operation(dir: &std::path::Path) -> std::collections::HashMap<String, usize> {
    let mut counts = std::collections::HashMap::new();
    let files = std::fs::read_dir(dir).expect("the HAR report directory");
    for file in files.filter_map(|f| f.ok()) {
        let text = std::fs::read_to_string(file.path()).expect("a HAR report");
        let har: serde_json::Value = serde_json::from_str(&text).expect("HAR is JSON");
        for entry in har["log"]["entries"].as_array().into_iter().flatten() {
            let status = entry["response"]["status"].as_u64().unwrap_or(0);
            if entry["request"]["method"] != "POST" {
                continue;
            }
            let url = entry["request"]["url"].as_str().unwrap_or("");
            let path = url
                .split_once("://")
                .and_then(|(_, rest)| rest.split_once('/'))
                .map(|(_, p)| format!("/{}", p.split(['?', '#']).next().unwrap_or("")))
                .unwrap_or_default();
            let n = counts.entry(path).or_insert(0);
            if (200..300).contains(&status) {
                *n += 1;
            }
        }
    }
    counts
}
