//! Drawing helpers shared by the figures: palette, dashed and clipped lines, a legend panel,
//! labels placed so they do not overlap.

use plotters::chart::MeshStyle;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::{CoordTranslate, Shift};
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::clip::{Rect, clip_polyline};
use crate::error::Result;
use crate::figure::{FONT, OrDraw};

/// Okabe–Ito colours (distinguishable with the common colour-vision deficiencies).
pub(crate) const BLUE: RGBColor = RGBColor(0, 114, 178);
pub(crate) const VERMILLION: RGBColor = RGBColor(213, 94, 0);
pub(crate) const GREEN: RGBColor = RGBColor(0, 158, 115);
pub(crate) const PURPLE: RGBColor = RGBColor(204, 121, 167);
pub(crate) const ORANGE: RGBColor = RGBColor(230, 159, 0);
pub(crate) const SKY: RGBColor = RGBColor(86, 180, 233);
pub(crate) const GREY: RGBColor = RGBColor(110, 110, 110);
pub(crate) const LIGHT: RGBColor = RGBColor(225, 225, 225);
pub(crate) const DARK: RGBColor = RGBColor(40, 40, 40);

/// A cycle of distinct colours for named series.
pub(crate) const CYCLE: [RGBColor; 7] = [BLUE, VERMILLION, GREEN, PURPLE, ORANGE, SKY, DARK];

/// Line pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Dash {
    /// Unbroken.
    #[default]
    Solid,
    /// Dashes of 6 px with 4 px gaps.
    Dashed,
    /// Long dashes of 12 px with 5 px gaps.
    LongDashed,
    /// Dots: 2 px on, 4 px off.
    Dotted,
}

impl Dash {
    fn pattern(self) -> Option<(u32, u32)> {
        match self {
            Dash::Solid => None,
            Dash::Dashed => Some((6, 4)),
            Dash::LongDashed => Some((12, 5)),
            Dash::Dotted => Some((2, 4)),
        }
    }
}

/// A text style in the figures' font.
pub(crate) fn text(size: f64, colour: &'static RGBColor) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).color(colour)
}

/// The house style of a chart's grid and labels: a light grid, dark labels of `size` points
/// and axis names two points larger. The caller adds its axis names and formatters and draws.
pub(crate) fn house_mesh<'a, 'b, DB, XT, YT, X, Y>(
    chart: &'b mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    size: f64,
) -> MeshStyle<'a, 'b, X, Y, DB>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = XT> + ValueFormatter<XT>,
    Y: Ranged<ValueType = YT> + ValueFormatter<YT>,
{
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(242, 242, 242))
        .bold_line_style(LIGHT)
        .label_style(text(size, &DARK))
        .axis_desc_style(text(size + 2.0, &DARK));
    mesh
}

/// Draws one already-clipped run of points.
pub(crate) fn draw_run<DB: DrawingBackend, CT: CoordTranslate<From = (f64, f64)>>(
    area: &DrawingArea<DB, CT>,
    run: Vec<(f64, f64)>,
    style: ShapeStyle,
    dash: Dash,
    figure: &'static str,
) -> Result<()> {
    if run.len() < 2 {
        return Ok(());
    }
    match dash.pattern() {
        None => area.draw(&PathElement::new(run, style)).or_draw(figure),
        Some((on, off)) => area
            .draw(&DashedPathElement::new(run, on, off, style))
            .or_draw(figure),
    }
}

/// Clips a polyline to `rect` and draws the pieces.
pub(crate) fn draw_clipped<DB: DrawingBackend, CT: CoordTranslate<From = (f64, f64)>>(
    area: &DrawingArea<DB, CT>,
    points: &[(f64, f64)],
    rect: &Rect,
    style: ShapeStyle,
    dash: Dash,
    figure: &'static str,
) -> Result<()> {
    for run in clip_polyline(points, rect) {
        draw_run(area, run, style, dash, figure)?;
    }
    Ok(())
}

/// What a legend entry shows beside its text.
#[derive(Debug, Clone)]
pub(crate) enum Swatch {
    /// A short line.
    Line {
        colour: RGBColor,
        width: u32,
        dash: Dash,
    },
    /// A filled box.
    Fill { colour: RGBAColor },
    /// The text alone, as a heading.
    Heading,
    /// The text alone, indented, as a note.
    Note,
}

/// A legend: entries listed top to bottom in an area of its own (so it never hides data).
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Swatch, String)],
    figure: &'static str,
) -> Result<()> {
    let body = text(14.0, &DARK);
    let heading = TextStyle::from((FONT, 14.0, FontStyle::Bold).into_font()).color(&DARK);
    let note = text(12.5, &GREY);
    let mut y = 8i32;
    for (swatch, label) in entries {
        let x = 4i32;
        match swatch {
            Swatch::Line {
                colour,
                width,
                dash,
            } => {
                let style = colour.stroke_width(*width);
                let pts = vec![(x, y + 8), (x + 34, y + 8)];
                match dash.pattern() {
                    None => area.draw(&PathElement::new(pts, style)),
                    Some((on, off)) => area.draw(&DashedPathElement::new(pts, on, off, style)),
                }
                .or_draw(figure)?;
                area.draw_text(label, &body, (x + 42, y)).or_draw(figure)?;
                y += 22;
            }
            Swatch::Fill { colour } => {
                area.draw(&Rectangle::new(
                    [(x, y + 1), (x + 34, y + 15)],
                    colour.filled(),
                ))
                .or_draw(figure)?;
                area.draw(&Rectangle::new([(x, y + 1), (x + 34, y + 15)], GREY))
                    .or_draw(figure)?;
                area.draw_text(label, &body, (x + 42, y)).or_draw(figure)?;
                y += 22;
            }
            Swatch::Heading => {
                y += 4;
                area.draw_text(label, &heading, (x, y)).or_draw(figure)?;
                y += 22;
            }
            Swatch::Note => {
                area.draw_text(label, &note, (x + 4, y)).or_draw(figure)?;
                y += 18;
            }
        }
    }
    Ok(())
}

/// A label to place at a preferred pixel position.
pub(crate) struct Placed {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl Placed {
    fn overlaps(&self, other: &Placed) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }
}

/// Chooses the first candidate top-left corner whose box (of size `size`) overlaps none of
/// `taken`, records and returns it; falls back to the first candidate.
pub(crate) fn place(
    taken: &mut Vec<Placed>,
    candidates: &[(i32, i32)],
    size: (u32, u32),
) -> (i32, i32) {
    let boxed = |(x, y): (i32, i32)| Placed {
        x0: x - 2,
        y0: y - 2,
        x1: x + size.0 as i32 + 2,
        y1: y + size.1 as i32 + 2,
    };
    let chosen = candidates
        .iter()
        .copied()
        .find(|&c| {
            let b = boxed(c);
            taken.iter().all(|t| !t.overlaps(&b))
        })
        .or_else(|| candidates.first().copied())
        .unwrap_or((0, 0));
    taken.push(boxed(chosen));
    chosen
}

/// Text on a white box, top-left at `pos` (pixels of `area`).
pub(crate) fn boxed_text<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    style: &TextStyle,
    pos: (i32, i32),
    figure: &'static str,
) -> Result<()> {
    let (w, h) = area.estimate_text_size(label, style).or_draw(figure)?;
    area.draw(&Rectangle::new(
        [
            (pos.0 - 2, pos.1 - 1),
            (pos.0 + w as i32 + 2, pos.1 + h as i32 + 2),
        ],
        WHITE.mix(0.85).filled(),
    ))
    .or_draw(figure)?;
    area.draw_text(label, style, pos).or_draw(figure)
}

/// An axis tick label: the shortest text of the value rounded to nine decimals, so that a tick
/// at round-off from zero reads "0" (never "-0.0") and 0.30000000000000004 reads "0.3".
pub(crate) fn tick(value: &f64) -> String {
    let rounded = (value * 1e9).round() / 1e9 + 0.0;
    format!("{rounded}")
}

/// Labels' numbers with a fixed count of decimals, as the front ends print them.
pub(crate) use whipple_front::format::fixed;

/// Labels for vertical markers along the top of a plotting area (pixel range `px`, `py`), each
/// beside its line at pixel x, in rows chosen so that none overlap.
pub(crate) fn label_markers<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    (px, py): (std::ops::Range<i32>, std::ops::Range<i32>),
    markers: &[(i32, String)],
    figure: &'static str,
) -> Result<()> {
    let style = text(13.0, &DARK);
    let mut taken = Vec::new();
    let mut sorted: Vec<&(i32, String)> = markers.iter().collect();
    sorted.sort_by_key(|m| m.0);
    for (lx, label) in sorted {
        let (w, h) = root.estimate_text_size(label, &style).or_draw(figure)?;
        let right = lx + 4;
        let left = lx - 4 - w as i32;
        let mut candidates = Vec::new();
        for row in 0..8 {
            let y = py.start + 4 + row * (h as i32 + 6);
            if right + (w as i32) < px.end {
                candidates.push((right, y));
            }
            if left > px.start {
                candidates.push((left, y));
            }
        }
        let pos = place(&mut taken, &candidates, (w, h));
        boxed_text(root, label, &style, pos, figure)?;
    }
    Ok(())
}
