//! Figures: library results handed to whipple-report, written whole or not at all.

use std::path::Path;

use anyhow::{bail, Result};
use whipple::analysis::{stability::CriticalSpeeds, sweep::EigenSweep};

use crate::bike::LoadedBike;

pub fn eigen_plot(
    _bike: &LoadedBike,
    _sweep: &EigenSweep,
    _critical: &CriticalSpeeds,
    _path: &Path,
) -> Result<()> {
    bail!("TEMPORARY")
}

pub fn side_view(_bike: &LoadedBike, _path: &Path) -> Result<()> {
    bail!("TEMPORARY")
}
