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
    sigma_bands: Option<&[[(f64, f64); 4]]>,
    path: &Path,
) -> Result<()> {
    // Fail on an unknown extension before any work is done.
    whipple_report::Format::from_path(path)
        .with_context(|| format!("--plot {}", path.display()))?;
    let options = EigenPlotOptions {
        title: Some(if sigma_bands.is_some() {
            format!(
                "{}: eigenvalues against forward speed (real parts ± 1σ shaded)",
                bike.label
            )
        } else {
            format!("{}: eigenvalues against forward speed", bike.label)
        }),
        sigma_bands: sigma_bands.map(<[_]>::to_vec),
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

/// A tornado plot of the elasticities of the weave speed (∂ln v_w/∂ln p), the base design named.
pub fn tornado(
    bike: &LoadedBike,
    s: &whipple::analysis::sensitivity::Sensitivities,
    path: &Path,
) -> Result<()> {
    let bars: Vec<whipple_report::Bar> = s
        .parameters
        .iter()
        .filter_map(|p| {
            p.weave_speed_elasticity.map(|e| whipple_report::Bar {
                label: p.key.to_string(),
                value: e,
            })
        })
        .collect();
    let title = match s.critical.weave_speed {
        Some(v) => format!(
            "{}: what moves the weave speed (v_w = {v:.4} m/s)",
            bike.label
        ),
        None => format!("{}: what moves the weave speed", bike.label),
    };
    let figure = whipple_report::tornado_plot(
        &bars,
        20,
        &title,
        "elasticity of v_w, ∂ln v_w / ∂ln p (1 % more p moves v_w by this many %)",
    )
    .with_context(|| {
        format!(
            "the tornado plot of {} (no weave speed in the range?)",
            bike.label
        )
    })?;
    write_figure(&figure, path)
}
