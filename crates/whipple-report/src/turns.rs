//! The families of steady turns: lean, steer and radius against speed (stable parts bold, as
//! Basu-Mandal et al. 2007 draw them) and the steer torque of held turns against lateral
//! acceleration.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::clip::Rect;
use crate::draw::{CYCLE, DARK, Dash, LIGHT, Swatch, draw_clipped, draw_legend, text};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};
use crate::xy::span;

const FIGURE: &str = "turn families";

/// A curve's points and whether each is stable.
type Curve = (Vec<(f64, f64)>, Vec<bool>);
/// A panel's y label and the quantity it draws.
type Quantity = (&'static str, fn(&TurnPoint) -> f64);

/// One point of a family of steady turns, in the figure's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnPoint {
    /// Speed of the rear contact [m/s].
    pub speed: f64,
    /// Lean \[deg\].
    pub lean_deg: f64,
    /// Steer \[deg\].
    pub steer_deg: f64,
    /// Rear contact radius, absolute \[m\] (non-finite when straight: the line breaks).
    pub radius: f64,
    /// Whether the turn is stable (drawn bold).
    pub stable: bool,
}

/// A curve of held turns at one speed: steer torque against lateral acceleration.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldCurve {
    /// Legend text (for example "5 m/s").
    pub name: String,
    /// (lateral acceleration [m/s²], steer torque [N m]) points.
    pub points: Vec<(f64, f64)>,
    /// Whether each point's turn is stable (drawn bold).
    pub stable: Vec<bool>,
}

/// What [`turns_plot`] draws.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TurnsData {
    /// A title (the bicycle's name).
    pub title: String,
    /// The hands-free families, each a list of points along the curve.
    pub families: Vec<Vec<TurnPoint>>,
    /// Held turns at a few speeds.
    pub held: Vec<HeldCurve>,
    /// Largest radius drawn \[m\] (the radius grows without bound near straight running).
    pub max_radius: f64,
}

#[derive(Debug, Clone)]
pub(crate) struct TurnsFigure {
    data: TurnsData,
}

/// The four-panel figure of steady turns (lean, steer and radius of the hands-free families
/// against speed, stable parts bold; held torque against lateral acceleration).
///
/// ```
/// use whipple_report::{turns_plot, TurnPoint, TurnsData};
/// let p = |v: f64, s: bool| TurnPoint { speed: v, lean_deg: v, steer_deg: 1.0, radius: 10.0, stable: s };
/// let data = TurnsData { title: "test".into(), families: vec![vec![p(1.0, false), p(2.0, true)]], held: vec![], max_radius: 50.0 };
/// let svg = turns_plot(&data, (1200, 900))?.to_svg()?;
/// assert!(svg.contains("lean"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn turns_plot(data: &TurnsData, size: (u32, u32)) -> Result<Figure> {
    if !(data.max_radius > 0.0 && data.max_radius.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "largest radius",
            rule: format!("must be a positive number, got {}", data.max_radius),
        });
    }
    Figure {
        width: 100,
        height: 100,
        content: Content::Turns(Box::new(TurnsFigure { data: data.clone() })),
    }
    .with_size(size.0, size.1)
}

/// Runs of consecutive points with the same stability, overlapping by one point so the line
/// is continuous.
fn runs(stable: &[bool]) -> Vec<(usize, usize, bool)> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=stable.len() {
        if i == stable.len() || stable[i] != stable[start] {
            out.push((start, (i + 1).min(stable.len()), stable[start]));
            start = i;
        }
    }
    out
}

impl TurnsFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (width, _) = root.dim_in_pixel();
        let (plots, legend) = root.split_horizontally(width.saturating_sub(230));
        let panels = plots.split_evenly((2, 2));
        let d = &self.data;
        let speeds = span(d.families.iter().flatten().map(|p| p.speed));
        let pick: [Quantity; 3] = [
            ("lean φ [deg]", |p| p.lean_deg),
            ("steer δ [deg]", |p| p.steer_deg),
            ("rear contact radius [m]", |p| p.radius),
        ];
        for (k, (label, f)) in pick.iter().enumerate() {
            let (y0, y1) = if k == 2 {
                (0.0, d.max_radius)
            } else {
                let (a, b) = span(d.families.iter().flatten().map(f));
                let pad = 0.05 * (b - a);
                (a - pad, b + pad)
            };
            let curves: Vec<Curve> = d
                .families
                .iter()
                .map(|fam| {
                    (
                        fam.iter().map(|p| (p.speed, f(p))).collect(),
                        fam.iter().map(|p| p.stable).collect(),
                    )
                })
                .collect();
            panel(
                &panels[k],
                "speed of the rear contact v [m/s]",
                label,
                speeds,
                (y0, y1),
                &curves,
                0,
            )?;
        }
        let held: Vec<Curve> = d
            .held
            .iter()
            .map(|h| (h.points.clone(), h.stable.clone()))
            .collect();
        let xs = span(d.held.iter().flat_map(|h| h.points.iter().map(|p| p.0)));
        let (a, b) = span(d.held.iter().flat_map(|h| h.points.iter().map(|p| p.1)));
        let pad = 0.05 * (b - a);
        panel(
            &panels[3],
            "lateral acceleration [m/s²]",
            "held steer torque T_δ [N m]",
            xs,
            (a - pad, b + pad),
            &held,
            d.families.len(),
        )?;
        let mut entries: Vec<(Swatch, String)> = vec![(Swatch::Heading, d.title.clone())];
        for (i, _) in d.families.iter().enumerate() {
            entries.push((
                Swatch::Line {
                    colour: CYCLE[i % CYCLE.len()],
                    width: 2,
                    dash: Dash::Solid,
                },
                format!("hands-free family {}", i + 1),
            ));
        }
        for (i, h) in d.held.iter().enumerate() {
            entries.push((
                Swatch::Line {
                    // After the families' colours: a held curve is not a family.
                    colour: CYCLE[(d.families.len() + i) % CYCLE.len()],
                    width: 2,
                    dash: Dash::Solid,
                },
                format!("held, {}", h.name),
            ));
        }
        entries.push((Swatch::Note, "bold: stable".into()));
        entries.push((Swatch::Note, "thin: unstable".into()));
        draw_legend(&legend, &entries, FIGURE)
    }
}

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    x_label: &str,
    y_label: &str,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    curves: &[Curve],
    first_colour: usize,
) -> Result<()> {
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .or_draw(FIGURE)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(242, 242, 242))
        .bold_line_style(LIGHT)
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(text(13.0, &DARK))
        .axis_desc_style(text(15.0, &DARK))
        .draw()
        .or_draw(FIGURE)?;
    let plot = chart.plotting_area();
    let rect = Rect { x0, x1, y0, y1 };
    for (i, (points, stable)) in curves.iter().enumerate() {
        let colour = CYCLE[(first_colour + i) % CYCLE.len()];
        for (a, b, s) in runs(stable) {
            let style = if s {
                colour.stroke_width(5)
            } else {
                colour.stroke_width(1)
            };
            draw_clipped(plot, &points[a..b], &rect, style, Dash::Solid, FIGURE)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::runs;

    #[test]
    fn runs_overlap_by_one_point() {
        assert_eq!(
            runs(&[true, true, false, false, true]),
            vec![(0, 3, true), (2, 5, false), (4, 5, true)]
        );
        assert_eq!(runs(&[]), vec![]);
    }
}
