//! A simulation's time histories: lean, steer and speed against time in stacked panels, and the
//! ground track of both wheel contacts drawn to scale.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::clip::Rect;
use crate::draw::{
    BLUE, DARK, Dash, GREEN, GREY, VERMILLION, draw_clipped, house_mesh, label_markers, text, tick,
};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};
use crate::xy::span;

const FIGURE: &str = "time series plot";

/// A simulation's results as plain data, for [`time_series_plot`]. Vectors of one series have
/// one entry per time in `t`; angles in radians, SI units.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SimulationSeries {
    /// Title (bicycle, initial condition).
    pub title: String,
    /// Time t \[s\].
    pub t: Vec<f64>,
    /// Lean φ \[rad\].
    pub lean: Vec<f64>,
    /// Steer δ \[rad\].
    pub steer: Vec<f64>,
    /// Forward speed v [m/s].
    pub speed: Vec<f64>,
    /// Rear wheel ground contact (x, y) \[m\] over time.
    pub rear_contact: Vec<(f64, f64)>,
    /// Front wheel ground contact (x, y) \[m\] over time.
    pub front_contact: Vec<(f64, f64)>,
    /// Events at times \[s\] with a short label (for example "fell over").
    pub events: Vec<(f64, String)>,
    /// How the run ended, in words (shown under the ground track).
    pub outcome: Option<String>,
}

#[derive(Debug, Clone)]
pub(crate) struct TimeSeriesFigure {
    series: SimulationSeries,
}

/// Lean, steer and speed against time, and the ground track of both contacts.
///
/// ```
/// use whipple_report::{time_series_plot, SimulationSeries};
/// let t: Vec<f64> = (0..50).map(|i| i as f64 * 0.1).collect();
/// let s = SimulationSeries {
///     title: "test".into(),
///     lean: t.iter().map(|t| 0.1 * t.sin()).collect(),
///     steer: t.iter().map(|t| 0.1 * t.cos()).collect(),
///     speed: vec![5.0; 50],
///     rear_contact: t.iter().map(|t| (5.0 * t, 0.0)).collect(),
///     front_contact: t.iter().map(|t| (5.0 * t + 1.0, 0.0)).collect(),
///     t,
///     ..Default::default()
/// };
/// assert!(time_series_plot(&s)?.to_svg()?.contains("lean φ"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn time_series_plot(series: &SimulationSeries) -> Result<Figure> {
    let n = series.t.len();
    for (what, len) in [
        ("lean", series.lean.len()),
        ("steer", series.steer.len()),
        ("speed", series.speed.len()),
    ] {
        if len != n && len != 0 {
            return Err(Error::InvalidArgument {
                what: "simulation series",
                rule: format!("{what} has {len} values for {n} times (give one per time, or none)"),
            });
        }
    }
    Figure {
        width: 1200,
        height: 760,
        content: Content::TimeSeries(Box::new(TimeSeriesFigure {
            series: series.clone(),
        })),
    }
    .with_size(1200, 760)
}

impl TimeSeriesFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let s = &self.series;
        let root = root.titled(&s.title, text(20.0, &DARK)).or_draw(FIGURE)?;
        let (w, _) = root.dim_in_pixel();
        let (left, right) = root.split_horizontally((w as f64 * 0.58) as u32);
        let panels = left.split_evenly((3, 1));
        let (t0, t1) = span(s.t.iter().copied());
        let deg = 180.0 / std::f64::consts::PI;
        let rows: [(&str, &Vec<f64>, RGBColor, bool); 3] = [
            ("lean φ [rad]", &s.lean, BLUE, true),
            ("steer δ [rad]", &s.steer, VERMILLION, true),
            ("speed v [m/s]", &s.speed, GREEN, false),
        ];
        for (i, ((label, values, colour, angle), panel)) in rows.iter().zip(&panels).enumerate() {
            let (mut y0, mut y1) = span(values.iter().copied());
            let pad = 0.08 * (y1 - y0);
            y0 -= pad;
            y1 += pad;
            let last = i == rows.len() - 1;
            let mut chart = ChartBuilder::on(panel)
                .margin(8)
                .x_label_area_size(if last { 44 } else { 22 })
                .y_label_area_size(70)
                .right_y_label_area_size(60)
                .build_cartesian_2d(t0..t1, y0..y1)
                .or_draw(FIGURE)?
                .set_secondary_coord(t0..t1, (y0 * deg)..(y1 * deg));
            let mut mesh = house_mesh(&mut chart, 13.0);
            mesh.light_line_style(RGBColor(244, 244, 244))
                .y_desc(*label)
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
                .axis_desc_style(text(14.0, &DARK));
            if last {
                mesh.x_desc("time t [s]");
            }
            mesh.draw().or_draw(FIGURE)?;
            if *angle {
                chart
                    .configure_secondary_axes()
                    .y_desc("[deg]")
                    .y_label_formatter(&tick)
                    .label_style(text(13.0, &GREY))
                    .axis_desc_style(text(14.0, &GREY))
                    .draw()
                    .or_draw(FIGURE)?;
            }
            let area = chart.plotting_area();
            let rect = Rect {
                x0: t0,
                x1: t1,
                y0,
                y1,
            };
            if y0 < 0.0 && y1 > 0.0 {
                area.draw(&PathElement::new(
                    vec![(t0, 0.0), (t1, 0.0)],
                    GREY.stroke_width(1),
                ))
                .or_draw(FIGURE)?;
            }
            let mut markers = Vec::new();
            for (te, name) in &s.events {
                if *te >= t0 && *te <= t1 {
                    area.draw(&DashedPathElement::new(
                        vec![(*te, y0), (*te, y1)],
                        4,
                        3,
                        DARK.mix(0.75).stroke_width(1),
                    ))
                    .or_draw(FIGURE)?;
                    markers.push((chart.backend_coord(&(*te, y1)).0, name.clone()));
                }
            }
            let points: Vec<(f64, f64)> = s.t.iter().copied().zip(values.iter().copied()).collect();
            draw_clipped(
                area,
                &points,
                &rect,
                colour.stroke_width(2),
                Dash::Solid,
                FIGURE,
            )?;
            if i == 0 {
                label_markers(&root, area.get_pixel_range(), &markers, FIGURE)?;
            }
        }
        self.draw_track(&right)
    }

    fn draw_track<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let s = &self.series;
        let (w, h) = area.dim_in_pixel();
        let all = || s.rear_contact.iter().chain(&s.front_contact);
        let (mut x0, mut x1) = span(all().map(|p| p.0));
        let (mut y0, mut y1) = span(all().map(|p| p.1));
        // Equal aspect: widen the shorter side around its centre.
        let (mx, my, extra_h) = (12.0 + 60.0 + 12.0, 12.0 + 44.0 + 12.0, 60.0);
        let pw = (w as f64 - mx).max(10.0);
        let ph = (h as f64 - my - extra_h).max(10.0);
        let pad = 0.05 * (x1 - x0).max(y1 - y0);
        x0 -= pad;
        x1 += pad;
        y0 -= pad;
        y1 += pad;
        let k = (pw / (x1 - x0)).min(ph / (y1 - y0));
        let (dx, dy) = (pw / k - (x1 - x0), ph / k - (y1 - y0));
        x0 -= dx / 2.0;
        x1 += dx / 2.0;
        y0 -= dy / 2.0;
        y1 += dy / 2.0;
        let (track, note) = area.split_vertically(h.saturating_sub(extra_h as u32));
        let mut chart = ChartBuilder::on(&track)
            .margin(12)
            .caption("ground track (to scale)", text(16.0, &DARK))
            .x_label_area_size(44)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .or_draw(FIGURE)?;
        house_mesh(&mut chart, 13.0)
            .light_line_style(RGBColor(244, 244, 244))
            .x_desc("x [m]")
            .y_desc("y [m]")
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .axis_desc_style(text(14.0, &DARK))
            .draw()
            .or_draw(FIGURE)?;
        let rect = Rect { x0, x1, y0, y1 };
        let plot = chart.plotting_area();
        for (points, colour) in [(&s.rear_contact, BLUE), (&s.front_contact, VERMILLION)] {
            draw_clipped(
                plot,
                points,
                &rect,
                colour.stroke_width(2),
                Dash::Solid,
                FIGURE,
            )?;
            if let Some(&start) = points.first() {
                plot.draw(&Circle::new(start, 4, colour.filled()))
                    .or_draw(FIGURE)?;
            }
            if let Some(&end) = points.last() {
                plot.draw(&Cross::new(end, 6, colour.stroke_width(2)))
                    .or_draw(FIGURE)?;
            }
        }
        // Legend and outcome under the track.
        let style = text(14.0, &DARK);
        let mut x = 16;
        for (colour, name) in [(BLUE, "rear contact"), (VERMILLION, "front contact")] {
            note.draw(&PathElement::new(
                vec![(x, 10), (x + 30, 10)],
                colour.stroke_width(2),
            ))
            .or_draw(FIGURE)?;
            note.draw_text(name, &style, (x + 36, 2)).or_draw(FIGURE)?;
            x += 160;
        }
        note.draw_text("● start  ✕ end", &text(13.0, &GREY), (x, 2))
            .or_draw(FIGURE)?;
        if let Some(outcome) = &s.outcome {
            note.draw_text(outcome, &style, (16, 28)).or_draw(FIGURE)?;
        }
        Ok(())
    }
}
