//! What whipple's front ends (the `whipple` command, `whipple serve`, the Python package)
//! share between the user and the library: the library speaks SI units and typed parameters;
//! people type degrees, names and `NAME=START:STOP:COUNT`, and read messages naming the options
//! they gave. This crate is that one thin layer, so that no front end keeps a copy of it and the
//! library keeps none of it.
//!
//! - [`simulation`]: a simulation as asked for (degrees, an integrator by name, torques as
//!   typed), checked into the library's `InitialConditions` and `SimulationSettings`;
//! - [`design`]: design axes `NAME=START:STOP:COUNT` into the library's typed `Axis`, and a study
//!   with its axes as typed;
//! - [`system`]: the linear system's inputs and outputs by name, frequency grids;
//! - [`record`]: oscillation records (CSV, MATLAB `.mat`) for the period fit;
//! - [`units`]: degrees to radians and back, units spelled for people (the units themselves are
//!   the library's parameter table's);
//! - [`message`]: the library's errors in the words of the options the user gave;
//! - [`formats`]: the parameter file formats as help texts list them, from the library's list;
//! - [`format`](mod@format): numbers as results print them (numbers in messages are the library's).
//!
//! ```
//! use whipple_front::simulation::SimulationRequest;
//! let request = SimulationRequest { lean_deg: 5.0, ..SimulationRequest::new(4.6, 5.0) };
//! let (initial, settings) = request.validate()?;
//! assert_eq!(initial.lean, 5f64.to_radians());
//! assert_eq!(settings.duration, 5.0);
//! # Ok::<(), whipple::Error>(())
//! ```
#![deny(missing_docs)]

pub mod design;
pub mod format;
pub mod formats;
pub mod message;
pub mod record;
pub mod simulation;
pub mod system;
pub mod units;
