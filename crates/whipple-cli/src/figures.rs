//! Figures: library results handed to whipple-report, written whole or not at all.

use std::path::Path;

use anyhow::{Context, Result};
use whipple::analysis::{stability::CriticalSpeeds, sweep::EigenSweep};
use whipple_report::{EigenPlotOptions, Figure};

use crate::bike::LoadedBike;
use crate::output::write_atomically;

fn write_figure(figure: &Figure, path: &Path) -> Result<()> {
    let bytes = figure
        .render_for_path(path)
        .with_context(|| format!("drawing {}", path.display()))?;
    write_atomically(path, &bytes)
}

pub fn eigen_plot(
    bike: &LoadedBike,
    sweep: &EigenSweep,
    critical: &CriticalSpeeds,
    path: &Path,
) -> Result<()> {
    // Fail on an unknown extension before any work is done.
    whipple_report::Format::from_path(path)
        .with_context(|| format!("--plot {}", path.display()))?;
    let options = EigenPlotOptions {
        title: Some(format!("{}: eigenvalues against forward speed", bike.label)),
        ..EigenPlotOptions::default()
    };
    let figure = whipple_report::eigen_plot(sweep, critical, &options)?;
    write_figure(&figure, path)
}

pub fn side_view(bike: &LoadedBike, path: &Path) -> Result<()> {
    whipple_report::Format::from_path(path).with_context(|| format!("--out {}", path.display()))?;
    let figure = whipple_report::side_view(&bike.benchmark, bike.bicycle.jbike6(), &bike.label);
    write_figure(&figure, path)
}
