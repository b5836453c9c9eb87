//! Generic line plots of named series against one variable, on linear or logarithmic y axes,
//! with labelled vertical markers (for validation reports).

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::clip::{Rect, clip_polyline};
use crate::draw::{
    CYCLE, DARK, Dash, Swatch, draw_clipped, draw_legend, draw_run, house_mesh, label_markers, text,
};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};

const FIGURE: &str = "line plot";

/// A named series of (x, y) points. Non-finite points break the line; on a log axis so do
/// y ≤ 0 (an exact zero difference has no place on a log scale).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line pattern.
    pub dash: Dash,
    /// Index into the figure palette (blue, vermillion, green, purple, orange, sky, dark);
    /// `None` takes the series' position.
    pub colour: Option<usize>,
}

impl Series {
    /// A solid series in the colour of its position.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            dash: Dash::Solid,
            colour: None,
        }
    }

    /// The same series with another line pattern.
    pub fn dashed(mut self, dash: Dash) -> Self {
        self.dash = dash;
        self
    }

    /// The same series in palette colour `index`.
    pub fn coloured(mut self, index: usize) -> Self {
        self.colour = Some(index);
        self
    }
}

/// A vertical line at `x` with a label (for example `v_c = 6.024 m/s`).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Position on the x axis.
    pub x: f64,
    /// Text beside the line.
    pub label: String,
}

/// Settings of [`line_plot`] and [`xy_log_plot`].
#[derive(Debug, Clone, PartialEq)]
pub struct XyPlotOptions {
    /// A title above the plot (default none).
    pub title: Option<String>,
    /// x axis label with unit (default "forward speed v [m/s]").
    pub x_label: String,
    /// y axis label with unit (default "value").
    pub y_label: String,
    /// x axis range; `None` (default) spans the data.
    pub x_range: Option<(f64, f64)>,
    /// y axis range; `None` (default) spans the data (on a log axis: whole decades around the
    /// positive values). Lines are clipped at it.
    pub y_range: Option<(f64, f64)>,
    /// Figure size \[px\] (default 1000 × 600).
    pub size: (u32, u32),
}

impl Default for XyPlotOptions {
    fn default() -> Self {
        XyPlotOptions {
            title: None,
            x_label: "forward speed v [m/s]".to_string(),
            y_label: "value".to_string(),
            x_range: None,
            y_range: None,
            size: (1000, 600),
        }
    }
}

#[derive(Debug, Clone)]
pub(crate) struct XyFigure {
    series: Vec<Series>,
    markers: Vec<Marker>,
    options: XyPlotOptions,
    log: bool,
}

/// Several named series against x on a linear y axis (for example real and imaginary parts
/// from two models against speed).
///
/// ```
/// use whipple_report::{line_plot, Marker, Series, XyPlotOptions};
/// let s = Series::new("Re λ", vec![(0.0, 1.0), (1.0, -1.0)]);
/// let m = Marker { x: 0.5, label: "v_w".into() };
/// let svg = line_plot(&[s], &[m], &XyPlotOptions::default())?.to_svg()?;
/// assert!(svg.contains("Re λ"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn line_plot(series: &[Series], markers: &[Marker], options: &XyPlotOptions) -> Result<Figure> {
    build(series, markers, options, false)
}

/// Several named series against x on a logarithmic y axis (for example absolute differences
/// between two models against speed), with vertical markers.
pub fn xy_log_plot(
    series: &[Series],
    markers: &[Marker],
    options: &XyPlotOptions,
) -> Result<Figure> {
    if let Some((lo, _)) = options.y_range {
        if lo <= 0.0 {
            return Err(Error::InvalidArgument {
                what: "log axis range",
                rule: format!("the lower end must be positive, got {lo}"),
            });
        }
    }
    build(series, markers, options, true)
}

/// Several line plots stacked top to bottom in one figure of `size` pixels, each with its own
/// axes, title and legend (for example a path in the plane above an error against time).
///
/// ```
/// use whipple_report::{stacked_line_plots, Series, XyPlotOptions};
/// let top = (vec![Series::new("path", vec![(0.0, 0.0), (1.0, 1.0)])], XyPlotOptions::default());
/// let bottom = (vec![Series::new("error", vec![(0.0, 0.1), (1.0, 0.0)])], XyPlotOptions::default());
/// let svg = stacked_line_plots(&[top, bottom], (1000, 900))?.to_svg()?;
/// assert!(svg.contains("path") && svg.contains("error"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn stacked_line_plots(
    panels: &[(Vec<Series>, XyPlotOptions)],
    size: (u32, u32),
) -> Result<Figure> {
    if panels.is_empty() {
        return Err(Error::InvalidArgument {
            what: "panels",
            rule: "at least one panel is needed".into(),
        });
    }
    let mut figures = Vec::with_capacity(panels.len());
    for (series, options) in panels {
        figures.push(checked(series, &[], options, false)?);
    }
    Figure {
        width: 100,
        height: 100,
        content: Content::Stacked(Box::new(XyStack { panels: figures })),
    }
    .with_size(size.0, size.1)
}

/// Line plots one above the other.
#[derive(Debug, Clone)]
pub(crate) struct XyStack {
    panels: Vec<XyFigure>,
}

impl XyStack {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let areas = root.split_evenly((self.panels.len(), 1));
        for (panel, area) in self.panels.iter().zip(&areas) {
            panel.draw(area)?;
        }
        Ok(())
    }
}

fn build(
    series: &[Series],
    markers: &[Marker],
    options: &XyPlotOptions,
    log: bool,
) -> Result<Figure> {
    Figure {
        width: 100,
        height: 100,
        content: Content::Xy(Box::new(checked(series, markers, options, log)?)),
    }
    .with_size(options.size.0, options.size.1)
}

/// A line plot's content, its ranges checked.
fn checked(
    series: &[Series],
    markers: &[Marker],
    options: &XyPlotOptions,
    log: bool,
) -> Result<XyFigure> {
    for (what, r) in [
        ("x axis range", options.x_range),
        ("y axis range", options.y_range),
    ] {
        if let Some((lo, hi)) = r {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(Error::InvalidArgument {
                    what,
                    rule: format!("needs finite LO < HI, got ({lo}, {hi})"),
                });
            }
        }
    }
    Ok(XyFigure {
        series: series.to_vec(),
        markers: markers.to_vec(),
        options: options.clone(),
        log,
    })
}

/// The span of finite values, widened when empty or degenerate.
pub(crate) fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        (0.0, 1.0)
    } else if lo == hi {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - d, hi + d)
    } else {
        (lo, hi)
    }
}

impl XyFigure {
    fn y_range(&self) -> (f64, f64) {
        if let Some(r) = self.options.y_range {
            return r;
        }
        let ys = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1));
        if self.log {
            let (lo, hi) = span(ys.filter(|&y| y > 0.0).map(whipple::math::log10));
            (
                whipple::math::powf(10f64, lo.floor()),
                whipple::math::powf(10f64, hi.ceil().max(lo.floor() + 1.0)),
            )
        } else {
            let (lo, hi) = span(ys);
            let pad = 0.05 * (hi - lo);
            (lo - pad, hi + pad)
        }
    }

    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (width, _) = root.dim_in_pixel();
        let (plot_area, legend_area) = root.split_horizontally(width.saturating_sub(250));
        let (x0, x1) = self.options.x_range.unwrap_or_else(|| {
            span(
                self.series
                    .iter()
                    .flat_map(|s| s.points.iter().map(|p| p.0)),
            )
        });
        let (y0, y1) = self.y_range();
        let mut builder = ChartBuilder::on(&plot_area);
        builder
            .margin(12)
            .x_label_area_size(52)
            .y_label_area_size(78);
        if let Some(title) = &self.options.title {
            builder.caption(title, text(20.0, &DARK));
        }
        let colour = |i: usize, s: &Series| CYCLE[s.colour.unwrap_or(i) % CYCLE.len()];
        let marker_style = DARK.mix(0.75).stroke_width(1);
        let pixel_markers: Vec<(i32, String)>;
        let pixel_range;
        if self.log {
            let mut chart = builder
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .or_draw(FIGURE)?;
            house_mesh(&mut chart, 14.0)
                .x_desc(self.options.x_label.as_str())
                .y_desc(self.options.y_label.as_str())
                .y_label_formatter(&|v: &f64| format!("{v:.0e}"))
                .draw()
                .or_draw(FIGURE)?;
            let area = chart.plotting_area();
            let rect = Rect {
                x0,
                x1,
                y0: whipple::math::log10(y0),
                y1: whipple::math::log10(y1),
            };
            for (i, s) in self.series.iter().enumerate() {
                let logged: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .map(|&(x, y)| {
                        (
                            x,
                            if y > 0.0 {
                                whipple::math::log10(y)
                            } else {
                                f64::NAN
                            },
                        )
                    })
                    .collect();
                for run in clip_polyline(&logged, &rect) {
                    let back = run
                        .into_iter()
                        .map(|(x, ly)| (x, whipple::math::powf(10f64, ly).clamp(y0, y1)))
                        .collect();
                    draw_run(area, back, colour(i, s).stroke_width(2), s.dash, FIGURE)?;
                }
            }
            pixel_markers = self.draw_markers(area, (x0, x1), (y0, y1), marker_style, |p| {
                chart.backend_coord(p).0
            })?;
            pixel_range = area.get_pixel_range();
        } else {
            let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).or_draw(FIGURE)?;
            house_mesh(&mut chart, 14.0)
                .x_desc(self.options.x_label.as_str())
                .y_desc(self.options.y_label.as_str())
                .draw()
                .or_draw(FIGURE)?;
            let area = chart.plotting_area();
            let rect = Rect { x0, x1, y0, y1 };
            if y0 < 0.0 && y1 > 0.0 {
                area.draw(&PathElement::new(
                    vec![(x0, 0.0), (x1, 0.0)],
                    BLACK.stroke_width(1),
                ))
                .or_draw(FIGURE)?;
            }
            for (i, s) in self.series.iter().enumerate() {
                draw_clipped(
                    area,
                    &s.points,
                    &rect,
                    colour(i, s).stroke_width(2),
                    s.dash,
                    FIGURE,
                )?;
            }
            pixel_markers = self.draw_markers(area, (x0, x1), (y0, y1), marker_style, |p| {
                chart.backend_coord(p).0
            })?;
            pixel_range = area.get_pixel_range();
        }
        label_markers(root, pixel_range, &pixel_markers, FIGURE)?;
        let entries: Vec<(Swatch, String)> = self
            .series
            .iter()
            .enumerate()
            .map(|(i, s)| {
                (
                    Swatch::Line {
                        colour: colour(i, s),
                        width: 2,
                        dash: s.dash,
                    },
                    s.name.clone(),
                )
            })
            .collect();
        draw_legend(&legend_area, &entries, FIGURE)
    }

    /// Draws the vertical marker lines inside the x range; returns their pixel x and labels.
    fn draw_markers<DB: DrawingBackend, CT: plotters::coord::CoordTranslate<From = (f64, f64)>>(
        &self,
        area: &DrawingArea<DB, CT>,
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
        style: ShapeStyle,
        to_pixel: impl Fn(&(f64, f64)) -> i32,
    ) -> Result<Vec<(i32, String)>> {
        let mut out = Vec::new();
        for m in &self.markers {
            if m.x >= x0 && m.x <= x1 {
                area.draw(&DashedPathElement::new(
                    vec![(m.x, y0), (m.x, y1)],
                    4,
                    3,
                    style,
                ))
                .or_draw(FIGURE)?;
                out.push((to_pixel(&(m.x, y1)), m.label.clone()));
            }
        }
        Ok(out)
    }
}
