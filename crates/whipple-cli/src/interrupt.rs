//! SIGINT, SIGTERM and SIGHUP (Ctrl-C, `kill`, a Slurm time limit, a closed terminal): the
//! command stops at once, removes every temporary file and every report directory it created,
//! says on standard error what was not written, and exits with 128 + the signal's number, as a
//! shell reports a process killed by it. An output already renamed into place stays (outputs
//! are renamed together, under the same lock, in [`crate::output::commit`]).
//!
//! The handler runs on a thread of its own (signal-hook's iterator), never inside the signal
//! handler, so it may take locks and touch files. `whipple serve` keeps tokio's handling of
//! Ctrl-C (it writes no files) and does not install this one.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// Set when a signal arrived: long loops that check it (a design map) stop early.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Installs the handler, once a process (the Python package runs the command in-process, once
/// or many times). A failure to install leaves the default action (the process ends; temporary
/// files may stay), which is said on standard error.
pub fn install() {
    static INSTALLED: OnceLock<()> = OnceLock::new();
    INSTALLED.get_or_init(|| match Signals::new([SIGINT, SIGTERM, SIGHUP]) {
        Ok(mut signals) => {
            let spawned = std::thread::Builder::new()
                .name("whipple-signals".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        INTERRUPTED.store(true, Ordering::SeqCst);
                        crate::output::abandon_and_exit(signal, name(signal));
                    }
                });
            if let Err(e) = spawned {
                eprintln!(
                    "warning: no signal handler ({e}): an interrupted run may leave temporary files"
                );
            }
        }
        Err(e) => {
            eprintln!(
                "warning: no signal handler ({e}): an interrupted run may leave temporary files"
            );
        }
    });
    INTERRUPTED.store(false, Ordering::SeqCst);
}

/// Set when a signal has arrived during this run.
pub fn flag() -> &'static AtomicBool {
    &INTERRUPTED
}

fn name(signal: i32) -> &'static str {
    match signal {
        SIGINT => "SIGINT (Ctrl-C)",
        SIGTERM => "SIGTERM",
        SIGHUP => "SIGHUP",
        _ => "a signal",
    }
}
