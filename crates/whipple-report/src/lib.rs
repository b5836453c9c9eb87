//! # whipple-report
//!
//! Figures and tables from `whipple`'s analysis results: eigenvalues against speed (Meijaard
//! 2007 Fig. 3 style), JBike6's side view of a bicycle, simulation time series, and line and
//! log plots for validation reports; CSV and fixed-width tables.
//!
//! Figures are plain data ([`Figure`]) rendered on demand to SVG text or PNG bytes; this crate
//! writes no files. Text is set in DejaVu Sans, embedded from the `dejavu` crate.
//!
//! ```
//! use whipple::advanced::{stability, sweep};
//! use whipple::{Canonical, BenchmarkParameters};
//! use whipple_report::{eigen_csv, eigen_plot, EigenPlotOptions, Format};
//!
//! let canonical = Canonical::new(&BenchmarkParameters::meijaard2007()).unwrap();
//! let speeds = whipple::speed_grid(0.0, 10.0, 0.1).unwrap();
//! let eig = whipple::eigen_sweep(&canonical, &speeds).unwrap();
//! let critical = whipple::critical_speeds(&canonical, 0.0, 10.0).unwrap();
//! let png = eigen_plot(&eig, &critical, &EigenPlotOptions::default())?.render(Format::Png)?;
//! assert_eq!(&png[1..4], b"PNG");
//! assert!(eigen_csv(&eig).starts_with("v,re1,im1,re2,im2,re3,im3,re4,im4\n"));
//! # Ok::<(), whipple_report::Error>(())
//! ```
#![warn(missing_docs)]

mod bode;
mod clip;
mod design;
mod draw;
mod eigen;
mod error;
mod figure;
mod manoeuvre;
mod side_view;
mod table;
mod time_series;
mod tornado;
mod turns;
mod xy;

pub use bode::{BodeCurve, BodeData, bode_plot};
pub use design::{MapData, StudyData, design_map, design_study};
pub use draw::Dash;
pub use eigen::{BikeEigen, EigenPlotOptions, eigen_comparison_plot, eigen_plot, mode_colour};
pub use error::{Error, Result};
pub use figure::{Figure, Format};
pub use manoeuvre::manoeuvre_plot;
pub use side_view::side_view;
pub use table::{
    EIGEN_CSV_HEADER, eigen_csv, eigen_csv_row, eigen_table, eigen_table_header, eigen_table_row,
};
pub use time_series::{SimulationSeries, time_series_plot};
pub use tornado::{Bar, tornado_plot};
pub use turns::{HeldCurve, TurnPoint, TurnsData, turns_plot};
pub use xy::{Marker, Series, XyPlotOptions, line_plot, stacked_line_plots, xy_log_plot};
