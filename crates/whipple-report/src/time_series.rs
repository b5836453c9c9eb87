//! stub
use crate::error::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
#[derive(Debug, Clone)]
pub(crate) struct TimeSeriesFigure;
impl TimeSeriesFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, _r: &DrawingArea<DB, Shift>) -> Result<()> {
        Ok(())
    }
}
/// stub
pub fn time_series_plot() {}
/// stub
pub struct SimulationSeries;
