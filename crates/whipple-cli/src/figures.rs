//! Figures: library results handed to whipple-report, written whole or not at all.

use std::path::Path;

use anyhow::{Context, Result};
use whipple::analysis::{stability::CriticalSpeeds, sweep::EigenSweep};
use whipple_report::{EigenPlotOptions, Figure};

use crate::bike::LoadedBike;
use crate::output::Target;

/// The figure's bytes in the format `path`'s extension names.
fn render(figure: &Figure, path: &Path) -> Result<Vec<u8>> {
    figure
        .render_for_path(path)
        .with_context(|| format!("drawing {}", path.display()))
}

/// The eigenvalue plot of `sweep`, rendered for `path` (not written).
pub fn eigen_plot_bytes(
    bike: &LoadedBike,
    sweep: &EigenSweep,
    critical: &CriticalSpeeds,
    path: &Path,
) -> Result<Vec<u8>> {
    let options = EigenPlotOptions {
        title: Some(format!("{}: eigenvalues against forward speed", bike.label)),
        ..EigenPlotOptions::default()
    };
    let figure = whipple_report::eigen_plot(sweep, critical, &options)?;
    render(&figure, path)
}

/// JBike6's side view, written to `target`.
pub fn side_view(bike: &LoadedBike, target: &Target) -> Result<()> {
    let figure = whipple_report::side_view(&bike.benchmark, bike.bicycle.jbike6(), &bike.label);
    target.write_whole(&render(&figure, target.path())?)
}
