//! Figures: library results handed to whipple-report, written whole or not at all.

use std::path::Path;

use anyhow::{Context, Result};
use whipple::{CriticalSpeeds, EigenSweep};
use whipple_report::{EigenPlotOptions, Figure};

use crate::bike::LoadedBike;
use crate::output::Target;

/// The figure's bytes in the format `path`'s extension names.
fn render(figure: &Figure, path: &Path) -> Result<Vec<u8>> {
    figure
        .render_for_path(path)
        .with_context(|| format!("drawing {}", path.display()))
}

/// The eigenvalue plot of `sweep` (`what`: "eigenvalues", "closed-loop eigenvalues"), rendered for `path` (not written).
pub fn eigen_plot_bytes(
    bike: &LoadedBike,
    what: &str,
    sweep: &EigenSweep,
    critical: &CriticalSpeeds,
    sigma_bands: Option<&[[(f64, f64); 4]]>,
    speed_unit: whipple_front::units::SpeedUnit,
    path: &Path,
) -> Result<Vec<u8>> {
    let options = EigenPlotOptions {
        title: Some(if sigma_bands.is_some() {
            format!(
                "{}: {what} against forward speed (real parts ± 1σ shaded)",
                bike.label
            )
        } else {
            format!("{}: {what} against forward speed", bike.label)
        }),
        sigma_bands: sigma_bands.map(<[_]>::to_vec),
        // An open loop that is stable is self-stable; a closed loop is stable by its control.
        stable_label: if what == "eigenvalues" {
            "self-stable"
        } else {
            "stable"
        }
        .to_string(),
        speed_unit,
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

/// A tornado plot of the elasticities of the weave speed (∂ln v_w/∂ln p), the base design
/// named, rendered for `path` (not written).
pub fn tornado(
    bike: &LoadedBike,
    s: &whipple::advanced::sensitivity::Sensitivities,
    path: &Path,
) -> Result<Vec<u8>> {
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
    render(&figure, path)
}
