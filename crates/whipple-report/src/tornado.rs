//! A tornado plot: one horizontal bar per parameter, sorted by size, for sensitivities and
//! elasticities (which of many changes helps most).

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::draw::{BLUE, DARK, VERMILLION, house_mesh, text, tick};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};

const FIGURE: &str = "tornado plot";

/// One bar.
#[derive(Debug, Clone, PartialEq)]
pub struct Bar {
    /// The label (a parameter's key).
    pub label: String,
    /// The bar's length (signed).
    pub value: f64,
}

/// The data of a tornado figure.
#[derive(Debug, Clone)]
pub(crate) struct TornadoFigure {
    bars: Vec<Bar>,
    title: String,
    x_label: String,
}

/// A tornado plot of `bars` (sorted by |value|, largest on top; at most `max_bars` shown;
/// zero and non-finite values left out), titled (name the base design there) and with the
/// quantity on the x axis. Positive bars blue, negative vermillion.
pub fn tornado_plot(bars: &[Bar], max_bars: usize, title: &str, x_label: &str) -> Result<Figure> {
    let mut bars: Vec<Bar> = bars
        .iter()
        .filter(|b| b.value.is_finite() && b.value != 0.0)
        .cloned()
        .collect();
    if bars.is_empty() {
        return Err(Error::InvalidArgument {
            what: "bars",
            rule: "no finite, non-zero value to draw".into(),
        });
    }
    bars.sort_by(|a, b| b.value.abs().total_cmp(&a.value.abs()));
    bars.truncate(max_bars.max(1));
    let height = (120 + 26 * bars.len() as u32).clamp(300, 2000);
    Figure {
        width: 100,
        height: 100,
        content: Content::Tornado(Box::new(TornadoFigure {
            bars,
            title: title.to_string(),
            x_label: x_label.to_string(),
        })),
    }
    .with_size(900, height)
}

impl TornadoFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let n = self.bars.len();
        let m = self.bars.iter().fold(0.0f64, |m, b| m.max(b.value.abs())) * 1.1;
        let labels: Vec<String> = self.bars.iter().map(|b| b.label.clone()).collect();
        let mut chart = ChartBuilder::on(root)
            .margin(14)
            .caption(&self.title, text(20.0, &DARK))
            .x_label_area_size(48)
            .y_label_area_size(120)
            .build_cartesian_2d(-m..m, -0.5..(n as f64 - 0.5))
            .or_draw(FIGURE)?;
        let label_of = |y: &f64| {
            let k = y.round();
            if (y - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < n {
                labels[n - 1 - k as usize].clone()
            } else {
                String::new()
            }
        };
        house_mesh(&mut chart, 14.0)
            .disable_y_mesh()
            .y_labels(n)
            .y_label_formatter(&label_of)
            .x_label_formatter(&tick)
            .x_desc(&self.x_label)
            .draw()
            .or_draw(FIGURE)?;
        let area = chart.plotting_area();
        for (i, b) in self.bars.iter().enumerate() {
            let y = (n - 1 - i) as f64;
            let colour = if b.value > 0.0 { BLUE } else { VERMILLION };
            area.draw(&Rectangle::new(
                [(0.0, y - 0.35), (b.value, y + 0.35)],
                colour.filled(),
            ))
            .or_draw(FIGURE)?;
        }
        area.draw(&PathElement::new(
            vec![(0.0, -0.5), (0.0, n as f64 - 0.5)],
            DARK.stroke_width(1),
        ))
        .or_draw(FIGURE)?;
        Ok(())
    }
}
