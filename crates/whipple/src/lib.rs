//! # whipple
//!
//! Dynamics of the Whipple bicycle: the benchmark parameters of Meijaard et al. 2007 and
//! JBike6's seven-body description, the linearized model (M, C₁, K₀, K₂), eigenvalues, modes,
//! critical speeds and the self-stable speed range; the fully non-linear multibody bicycle
//! ([`nonlinear`]) and its simulation ([`nonlinear::simulate`], [`integrate`]).
//!
//! Data flows one way: parameters → model → analysis.
//!
//! ```
//! use whipple::{analysis::{stability, sweep}, linear::Canonical, parameters::presets};
//!
//! let bike = presets::find("benchmark")?.bicycle().benchmark()?;   // parameters
//! let canonical = Canonical::new(&bike)?;                           // linearized model
//! let speeds = sweep::speed_grid(0.0, 10.0, 0.01)?;
//! let eig = sweep::eigen_sweep(&canonical, &speeds)?;               // eigenvalues, modes
//! let critical = stability::critical_speeds(&canonical, 0.0, 10.0)?; // v_d, v_w, v_c
//! let (lo, hi) = critical.stable_speed_ranges[0];
//! assert!((lo - 4.29238253634111).abs() < 1e-12 && (hi - 6.02426201538837).abs() < 1e-12);
//! assert_eq!(eig.speeds.len(), 1001);
//! # Ok::<(), whipple::Error>(())
//! ```
#![warn(missing_docs)]

pub mod analysis;
pub mod error;
pub mod integrate;
pub mod linear;
pub mod nonlinear;
pub mod parameters;
pub mod side_view;

pub use error::{Error, Result};
pub use parameters::{BenchmarkParameters, Bicycle, Description, Jbike6Parameters};
