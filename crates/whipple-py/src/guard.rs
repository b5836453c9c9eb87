//! The guards of the long and the large calls.
//!
//! Memory: every buffer whose size the caller controls (speeds × what each speed gives,
//! designs × columns) is reserved fallibly before anything is computed; a reservation the
//! allocator refuses raises `MemoryError` naming the call, the count and the bytes, where an
//! infallible allocation would abort the interpreter. The buffers are handed to numpy without a
//! copy (`PyArray1::from_vec` keeps the `Vec`), so numpy allocates nothing large either.
//!
//! Ctrl-C: [`interruptible`] runs the work on a thread of its own with the GIL released while
//! the calling (main) thread checks for signals every [`POLL`]; on a signal it sets the flag the
//! work polls, waits for the work to stop and raises the signal's exception (`KeyboardInterrupt`).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;
use whipple::Error;

/// How often the calling thread checks for signals while the work runs.
pub const POLL: Duration = Duration::from_millis(10);

/// Speeds or designs few enough to compute on the calling thread without a watcher (at most
/// tens of microseconds each: a few milliseconds in all).
pub const SHORT: usize = 64;

/// The error a worker returns when it saw the stop flag (replaced by the signal's exception).
pub fn stopped() -> Error {
    Error::InvalidArgument {
        what: "stopped",
        rule: "interrupted".into(),
    }
}

/// Whether the work should stop (a `Relaxed` load: the flag only ever goes from false to true).
pub fn is_stopped(stop: &AtomicBool) -> bool {
    stop.load(Ordering::Relaxed)
}

/// `bytes` in words: `3840000000 bytes (3.6 GiB)`.
fn size(bytes: u128) -> String {
    format!(
        "{bytes} bytes ({:.1} GiB)",
        bytes as f64 / f64::from(1u32 << 30)
    )
}

/// The `MemoryError` of a call whose `count` items (`what`, e.g. `"speeds"`) need `bytes`.
pub fn memory_error(call: &str, count: u128, what: &str, bytes: u128) -> PyErr {
    PyMemoryError::new_err(format!(
        "{call}: {count} {what} need {} of results, more than this process can allocate; \
         use fewer {what} or compute them in parts",
        size(bytes)
    ))
}

/// The bytes `count` items of `per_item` bytes need (saturating: an absurd count is simply
/// more than can be allocated).
pub fn estimate(count: usize, per_item: usize) -> u128 {
    count as u128 * per_item as u128
}

/// A `Vec` with room for exactly `len` elements, or the `MemoryError` `on_failure`.
pub fn reserve<T>(len: usize, on_failure: impl FnOnce() -> PyErr) -> PyResult<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| on_failure())?;
    Ok(v)
}

/// Fills a reserved `v` up to `len` copies of `fill`, a million elements at a time, stopping
/// when `stop` is set (writing gigabytes of zeros takes a good part of a second).
pub fn grow<T: Clone>(v: &mut Vec<T>, len: usize, fill: T, stop: &AtomicBool) -> Result<(), Error> {
    const STEP: usize = 1 << 20;
    while v.len() < len {
        if is_stopped(stop) {
            return Err(stopped());
        }
        let next = len.min(v.len().saturating_add(STEP));
        v.resize(next, fill.clone());
    }
    Ok(())
}

/// Runs `work` on a thread of its own with the GIL released, checking for signals every
/// [`POLL`] on the calling thread. On a signal (Ctrl-C) the flag given to `work` is set, the
/// work's result (it should return soon after, with [`stopped`]) is dropped and the signal's
/// exception raised. Signals that arrived while the work ran are also raised when it finished
/// between two checks, before the caller touches Python or numpy again.
///
/// `short`: the work is known to take well under [`POLL`] (a few speeds or designs); it then
/// runs on the calling thread with no watcher, sparing the hand-over to another thread (tens
/// of microseconds on an idle machine, milliseconds on a loaded one).
pub fn interruptible<T: Send>(
    py: Python<'_>,
    short: bool,
    work: impl FnOnce(&AtomicBool) -> T + Send,
) -> PyResult<T> {
    let stop = AtomicBool::new(false);
    if short {
        let value = py.detach(|| work(&stop));
        py.check_signals()?;
        return Ok(value);
    }
    let outcome: PyResult<T> = py.detach(|| {
        std::thread::scope(|scope| {
            let (sender, receiver) = mpsc::channel();
            let flag = &stop;
            scope.spawn(move || {
                // The receiver is gone only when the caller stopped waiting: nothing to tell.
                let _ = sender.send(work(flag));
            });
            loop {
                match receiver.recv_timeout(POLL) {
                    Ok(result) => return Ok(result),
                    Err(mpsc::RecvTimeoutError::Timeout) => {
                        if let Err(signal) = Python::attach(|py| py.check_signals()) {
                            stop.store(true, Ordering::Relaxed);
                            // The scope joins the worker, which now stops at its next check.
                            return Err(signal);
                        }
                    }
                    Err(mpsc::RecvTimeoutError::Disconnected) => {
                        // The worker panicked: the scope re-raises its panic on exit.
                        return Err(pyo3::exceptions::PyRuntimeError::new_err(
                            "the computation's thread ended without a result",
                        ));
                    }
                }
            }
        })
    });
    let value = outcome?;
    py.check_signals()?;
    Ok(value)
}
