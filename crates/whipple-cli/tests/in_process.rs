//! The command run in-process from several threads at once (as the Python package's threads
//! run it): each run reads with its own global options (`--strict`, `--bike-format`), never
//! with another run's.

use std::sync::{Arc, Barrier};
use std::thread;

use crate::common::scratch;

fn data(path: &str) -> String {
    format!(
        "{}/../whipple/tests/data/{path}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// `whipple convert --bike benchmark --to toml --out PATH`, run in-process: its exit status.
fn convert_benchmark_to_toml(path: &std::path::Path) -> i32 {
    let out = path.to_string_lossy();
    let args = [
        "whipple",
        "convert",
        "--bike",
        "benchmark",
        "--to",
        "toml",
        "--out",
        &out,
    ];
    whipple_cli::main_with_args(args)
}

/// The benchmark bicycle written as TOML at `path`, by the command run in-process.
fn write_benchmark_toml(path: &std::path::Path) {
    assert_eq!(convert_benchmark_to_toml(path), 0);
}

/// Four kinds of run, started together many times: `--strict` on a bicycle with a warning
/// (refused: 1), the same without it (0), a TOML file named `.json` read with `--bike-format
/// toml` (0), the same without the option (a JSON syntax error: 1). A run that saw another's
/// options would exit with the other's status.
#[test]
fn concurrent_runs_keep_their_own_options() {
    let dir = scratch("in_process_options");
    let warned = data("bicycleparameters/BrowserBenchmark.txt");
    let toml_as_json = dir.join("bike.json");
    let benchmark_toml = dir.join("benchmark.toml");
    write_benchmark_toml(&benchmark_toml);
    std::fs::copy(&benchmark_toml, &toml_as_json).expect("scratch file");
    let toml_as_json = toml_as_json.to_string_lossy().into_owned();

    let kinds: [(Vec<&str>, i32); 4] = [
        (vec!["--bike", &warned, "--strict"], 1),
        (vec!["--bike", &warned], 0),
        (vec!["--bike", &toml_as_json, "--bike-format", "toml"], 0),
        (vec!["--bike", &toml_as_json], 1),
    ];
    const ROUNDS: usize = 200;
    let barrier = Arc::new(Barrier::new(kinds.len()));
    thread::scope(|scope| {
        let mut handles = Vec::new();
        for (k, (options, expected)) in kinds.iter().enumerate() {
            let barrier = Arc::clone(&barrier);
            let dir = &dir;
            handles.push(scope.spawn(move || {
                let mut wrong = Vec::new();
                for round in 0..ROUNDS {
                    let out = dir.join(format!("out-{k}-{round}.toml"));
                    let out = out.to_string_lossy().into_owned();
                    let mut args = vec!["whipple", "convert", "--to", "toml", "--out", &out];
                    args.extend(options.iter().copied());
                    barrier.wait();
                    let status = whipple_cli::main_with_args(args);
                    if status != *expected {
                        wrong.push((round, status));
                    }
                }
                wrong
            }));
        }
        for (handle, (options, expected)) in handles.into_iter().zip(&kinds) {
            let wrong = handle.join().expect("a run never panics");
            assert!(
                wrong.is_empty(),
                "{options:?} should exit {expected}; (round, status) that did not: {wrong:?}"
            );
        }
    });
}

/// A run that would write its output onto the file it reads is refused, however many runs start
/// beside it in the same process (a run's start forgets only its own thread's inputs).
#[test]
fn concurrent_runs_keep_their_own_inputs() {
    let dir = scratch("in_process_inputs");
    let input = dir.join("bike.toml");
    write_benchmark_toml(&input);
    let input = input.to_string_lossy().into_owned();
    const ROUNDS: usize = 200;
    let barrier = Barrier::new(2);
    thread::scope(|scope| {
        let onto_input = scope.spawn(|| {
            let mut wrong = Vec::new();
            for round in 0..ROUNDS {
                let args = [
                    "whipple", "convert", "--bike", &input, "--to", "toml", "--out", &input,
                ];
                barrier.wait();
                let status = whipple_cli::main_with_args(args);
                if status != 1 {
                    wrong.push(round);
                }
            }
            wrong
        });
        let beside = scope.spawn(|| {
            let mut wrong = Vec::new();
            for round in 0..ROUNDS {
                let out = dir.join(format!("beside-{round}.toml"));
                barrier.wait();
                if convert_benchmark_to_toml(&out) != 0 {
                    wrong.push(round);
                }
            }
            wrong
        });
        let onto_input = onto_input.join().expect("a run never panics");
        assert!(
            onto_input.is_empty(),
            "rounds that wrote onto their input: {onto_input:?}"
        );
        assert_eq!(
            beside.join().expect("a run never panics"),
            Vec::<usize>::new()
        );
    });
}
