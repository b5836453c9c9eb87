//! The command's integration tests, one module per file of this folder (their helpers in
//! common/), built as one test binary. `cargo test -p whipple-cli --test suite -- guide::` runs
//! one file's tests.

mod cli;
mod common;
mod examples;
mod field;
mod formats;
mod guide;
mod hess;
mod hostile;
mod hqm;
mod in_process;
mod lane_change;
mod measure;
mod options;
mod outputs;
mod period;
mod response;
mod rider;
mod rider_lean;
mod serve;
mod set;
mod system;
mod turns;
mod units;
mod validate;
