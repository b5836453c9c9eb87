//! Helpers shared by the integration tests that run the real binary.
#![allow(dead_code)] // each test file uses its own subset

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Output, Stdio};

/// Runs `whipple` with these arguments.
pub fn whipple(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_whipple"))
        .args(args)
        .output()
        .expect("the whipple binary runs")
}

/// Standard output of a run that must succeed.
pub fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// Standard error of a run that must fail.
pub fn stderr_of_failure(output: &Output) -> String {
    assert!(!output.status.success(), "expected a failure");
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A fresh, empty scratch directory under the target directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// Runs `whipple ARGS | head -1`: reads the first line of standard output, closes the pipe and
/// waits for the end. The line is checked by `first`.
pub fn read_first_line_then_close(args: &[&str], first: impl Fn(&str) -> bool) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_whipple"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    {
        let out = child.stdout.take().expect("stdout");
        let mut line = String::new();
        BufReader::new(out).read_line(&mut line).expect("a line");
        assert!(first(&line), "first line: {line}");
    } // the pipe is closed here
    child.wait_with_output().expect("ends")
}

/// [`read_first_line_then_close`] with any non-empty first line.
pub fn read_one_line_then_close(args: &[&str]) -> Output {
    read_first_line_then_close(args, |line| !line.is_empty())
}

/// Starts `whipple ARGS` in the background, standard output discarded and standard error kept.
pub fn spawn_quiet(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_whipple"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs")
}
