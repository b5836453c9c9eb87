//! The core's integration tests, one module per file of this folder, built as one test binary
//! (each file its own binary compiled the generic dynamics again for every one and linked it on
//! its own). `cargo test -p whipple --test suite -- turns::` runs one file's tests.

mod certified_speeds;
mod controllability;
mod cross_checks;
mod failures;
mod feedback;
mod field_files;
mod file_messages;
mod handling;
mod hostile_seeds;
mod invalid_input;
mod linear_response;
mod linear_system;
mod linearize;
mod measured;
mod nonlinear;
mod period;
mod principal;
mod properties;
mod reference;
mod rider_lean;
mod rider_on_bicycle;
mod round_trip;
mod trajectories;
mod turns;
mod typed_units;
mod yeadon;
