//! Bode plots: the magnitude in decibels above, the phase in degrees below, against the
//! frequency on a logarithmic axis, one line per curve (a speed) with a legend.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::draw::{CYCLE, DARK, Dash, Swatch, draw_legend, draw_run, house_mesh, text};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};
use crate::xy::span;

const FIGURE: &str = "Bode plot";

/// One frequency response: the frequencies (positive, any unit the axis names) and, at each,
/// the magnitude \[dB\] and the phase \[deg\]. Non-finite values break the line.
#[derive(Debug, Clone, PartialEq)]
pub struct BodeCurve {
    /// Legend text (for example `3 m/s`).
    pub name: String,
    /// The frequencies, increasing.
    pub frequencies: Vec<f64>,
    /// 20 log₁₀ |G| \[dB\] at each frequency.
    pub magnitude_db: Vec<f64>,
    /// The phase \[deg\] at each frequency (unwrapped).
    pub phase_deg: Vec<f64>,
}

/// What [`bode_plot`] draws.
#[derive(Debug, Clone, PartialEq)]
pub struct BodeData {
    /// Title above the magnitude panel.
    pub title: String,
    /// The frequency axis' label with its unit (`frequency ω [rad/s]`).
    pub frequency_label: String,
    /// The magnitude axis' label (`|lean / steer_torque| [dB re 1 rad/(N m)]`).
    pub magnitude_label: String,
    /// A heading above the legend (`speed`).
    pub legend_title: String,
    /// The curves, drawn in the palette's order.
    pub curves: Vec<BodeCurve>,
}

#[derive(Debug, Clone)]
pub(crate) struct BodeFigure {
    data: BodeData,
}

/// A Bode plot of several frequency responses overlaid (magnitude above, phase below, a
/// logarithmic frequency axis shared by both).
///
/// ```
/// use whipple_report::{bode_plot, BodeCurve, BodeData};
/// let curve = BodeCurve {
///     name: "5 m/s".into(),
///     frequencies: vec![0.1, 1.0, 10.0],
///     magnitude_db: vec![0.0, -3.0, -20.0],
///     phase_deg: vec![0.0, -45.0, -90.0],
/// };
/// let data = BodeData {
///     title: "G".into(),
///     frequency_label: "frequency ω [rad/s]".into(),
///     magnitude_label: "|G| [dB]".into(),
///     legend_title: "speed".into(),
///     curves: vec![curve],
/// };
/// assert!(bode_plot(&data)?.to_svg()?.contains("5 m/s"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn bode_plot(data: &BodeData) -> Result<Figure> {
    for c in &data.curves {
        let n = c.frequencies.len();
        if c.magnitude_db.len() != n || c.phase_deg.len() != n {
            return Err(Error::InvalidArgument {
                what: "Bode curve",
                rule: format!(
                    "{}: {n} frequencies, {} magnitudes and {} phases (give one of each per \
                     frequency)",
                    c.name,
                    c.magnitude_db.len(),
                    c.phase_deg.len()
                ),
            });
        }
        if c.frequencies.iter().any(|f| !(f.is_finite() && *f > 0.0)) {
            return Err(Error::InvalidArgument {
                what: "Bode curve",
                rule: format!(
                    "{}: the frequencies must be positive and finite (a logarithmic axis)",
                    c.name
                ),
            });
        }
    }
    Figure {
        width: 1000,
        height: 760,
        content: Content::Bode(Box::new(BodeFigure { data: data.clone() })),
    }
    .with_size(1000, 760)
}

/// The runs of finite points of one curve's (x, y).
fn runs(x: &[f64], y: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut run = Vec::new();
    for (&a, &b) in x.iter().zip(y) {
        if b.is_finite() {
            run.push((a, b));
        } else if !run.is_empty() {
            out.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        out.push(run);
    }
    out
}

impl BodeFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let d = &self.data;
        let (width, height) = root.dim_in_pixel();
        let (plots, legend_area) = root.split_horizontally(width.saturating_sub(170));
        let (top, bottom) = plots.split_vertically(height / 2);
        let (mut f0, mut f1) = span(
            d.curves
                .iter()
                .flat_map(|c| c.frequencies.iter().copied())
                .filter(|f| *f > 0.0),
        );
        if f0 <= 0.0 || f0 >= f1 {
            (f0, f1) = (f0.max(1e-3), f0.max(1e-3) * 10.0);
        }
        let range = |values: &dyn Fn(&BodeCurve) -> &[f64]| {
            let (lo, hi) = span(d.curves.iter().flat_map(|c| values(c).iter().copied()));
            let pad = 0.05 * (hi - lo);
            (lo - pad, hi + pad)
        };
        let panels = [
            (
                &top,
                range(&|c| &c.magnitude_db),
                d.magnitude_label.as_str(),
                false,
            ),
            (&bottom, range(&|c| &c.phase_deg), "phase [deg]", true),
        ];
        for (area, (y0, y1), y_label, is_phase) in panels {
            let mut builder = ChartBuilder::on(area);
            builder
                .margin(12)
                .x_label_area_size(48)
                .y_label_area_size(78);
            if !is_phase {
                builder.caption(&d.title, text(19.0, &DARK));
            }
            let mut chart = builder
                .build_cartesian_2d((f0..f1).log_scale(), y0..y1)
                .or_draw(FIGURE)?;
            house_mesh(&mut chart, 14.0)
                .x_desc(d.frequency_label.as_str())
                .y_desc(y_label)
                .x_label_formatter(&|v: &f64| format!("{v}"))
                .draw()
                .or_draw(FIGURE)?;
            let plotting = chart.plotting_area();
            for (i, c) in d.curves.iter().enumerate() {
                let y = if is_phase {
                    &c.phase_deg
                } else {
                    &c.magnitude_db
                };
                for run in runs(&c.frequencies, y) {
                    draw_run(
                        plotting,
                        run,
                        CYCLE[i % CYCLE.len()].stroke_width(2),
                        Dash::Solid,
                        FIGURE,
                    )?;
                }
            }
        }
        let mut entries = vec![(Swatch::Heading, d.legend_title.clone())];
        entries.extend(d.curves.iter().enumerate().map(|(i, c)| {
            (
                Swatch::Line {
                    colour: CYCLE[i % CYCLE.len()],
                    width: 2,
                    dash: Dash::Solid,
                },
                c.name.clone(),
            )
        }));
        draw_legend(&legend_area, &entries, FIGURE)
    }
}
