//! Design-study figures: a heat map of one quantity over two parameters (colour bar with units,
//! the boundary of "a self-stable range exists", the base design marked), and the classic
//! one-parameter study (v_w and v_c against the parameter, the self-stable band shaded).
//!
//! A map's cells are one pixel each of a raster image scaled to the plot area without
//! smoothing: embedded as a PNG in the SVG, painted under the axes in the PNG. A 1000 × 1000 map
//! stays a small file that way.

use std::cell::Cell;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::draw::{BLUE, DARK, GREEN, LIGHT, VERMILLION, house_mesh, text, tick};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};

/// A map to draw: `values` row-major (`iy · nx + ix`), NaN where a design has no value
/// (invalid, or the quantity does not exist), +∞ where it is unbounded.
#[derive(Debug, Clone, PartialEq)]
pub struct MapData {
    /// Figure title.
    pub title: String,
    /// x axis label with its unit.
    pub x_label: String,
    /// y axis label with its unit.
    pub y_label: String,
    /// x grid: start, stop, count (user units).
    pub x: (f64, f64, usize),
    /// y grid: start, stop, count.
    pub y: (f64, f64, usize),
    /// The quantity at every design.
    pub values: Vec<f64>,
    /// Whether each design is inside the outline (has a self-stable range, say): its boundary
    /// is drawn.
    pub stable: Vec<bool>,
    /// The legend's two lines for the outline (`["self-stable range", "exists (inside)"]`).
    pub outline: [String; 2],
    /// A diverging scale, white at zero (blue below, red above, each side to its own extreme;
    /// for a signed quantity such as the largest real part), instead of the sequential one.
    pub diverging: bool,
    /// The colour bar's label with its unit.
    pub quantity: String,
    /// The base design (x, y), marked.
    pub base: Option<(f64, f64)>,
}

/// A one-parameter study to draw: for each x, the weave and capsize speeds and the first
/// self-stable range (None where absent; `stable_to` +∞ when unbounded).
#[derive(Debug, Clone, PartialEq)]
pub struct StudyData {
    /// Figure title.
    pub title: String,
    /// x axis label with its unit.
    pub x_label: String,
    /// The parameter's values.
    pub x: Vec<f64>,
    /// v_w [m/s].
    pub weave: Vec<Option<f64>>,
    /// v_c [m/s].
    pub capsize: Vec<Option<f64>>,
    /// Lower end of the self-stable range [m/s].
    pub stable_from: Vec<Option<f64>>,
    /// Upper end of the self-stable range [m/s].
    pub stable_to: Vec<Option<f64>>,
    /// The base design's x, marked.
    pub base: Option<f64>,
}

#[derive(Debug, Clone)]
pub(crate) struct MapFigure {
    data: MapData,
    range: (f64, f64),
    /// The plot area in pixels, found while drawing (x0, y0, x1, y1).
    pub(crate) area: Cell<(i32, i32, i32, i32)>,
}

#[derive(Debug, Clone)]
pub(crate) struct StudyFigure {
    data: StudyData,
}

/// The most cells of one map figure.
const MAX_CELLS: usize = 25_000_000;

/// A heat map figure.
///
/// ```
/// use whipple_report::{design_map, MapData, Format};
/// let values: Vec<f64> = (0..100).map(|k| k as f64).collect();
/// let stable: Vec<bool> = (0..100).map(|k| k % 10 > 4).collect();
/// let map = MapData { title: "t".into(), x_label: "x [m]".into(), y_label: "y [m]".into(),
///     x: (0.0, 1.0, 10), y: (0.0, 1.0, 10), values, stable,
///     outline: ["self-stable range".into(), "exists (inside)".into()], diverging: false,
///     quantity: "q [m/s]".into(),
///     base: Some((0.5, 0.5)) };
/// let png = design_map(&map)?.render(Format::Png)?;
/// assert_eq!(&png[1..4], b"PNG");
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn design_map(data: &MapData) -> Result<Figure> {
    let n = data.x.2 * data.y.2;
    if data.x.2 == 0 || data.y.2 == 0 || n > MAX_CELLS {
        return Err(Error::InvalidArgument {
            what: "map",
            rule: format!(
                "needs 1..={MAX_CELLS} cells, got {} x {}",
                data.x.2, data.y.2
            ),
        });
    }
    if data.values.len() != n || data.stable.len() != n {
        return Err(Error::InvalidArgument {
            what: "map",
            rule: format!(
                "{} values and {} stability flags for {n} cells",
                data.values.len(),
                data.stable.len()
            ),
        });
    }
    // The colour scale spans the 1st to 99th percentile of the finite values, so that a few
    // extreme designs do not wash out the rest; values beyond are drawn in the end colours
    // (the colour bar says so).
    let mut finite: Vec<f64> = data
        .values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    if !finite.is_empty() {
        let n = finite.len();
        let at = |q: f64| ((n - 1) as f64 * q).round() as usize;
        let (a, b) = (at(0.01), at(0.99));
        lo = *finite.select_nth_unstable_by(a, f64::total_cmp).1;
        hi = *finite.select_nth_unstable_by(b, f64::total_cmp).1;
    }
    if lo.is_nan() || hi.is_nan() || lo > hi {
        (lo, hi) = (0.0, 1.0);
    } else if lo == hi {
        (lo, hi) = (lo - 0.5, hi + 0.5);
    }
    Ok(Figure {
        width: 1000,
        height: 800,
        content: Content::Map(Box::new(MapFigure {
            data: data.clone(),
            range: (lo, hi),
            area: Cell::new((0, 0, 0, 0)),
        })),
    })
}

/// The one-parameter study figure.
pub fn design_study(data: &StudyData) -> Result<Figure> {
    let n = data.x.len();
    if n == 0
        || data.weave.len() != n
        || data.capsize.len() != n
        || data.stable_from.len() != n
        || data.stable_to.len() != n
    {
        return Err(Error::InvalidArgument {
            what: "study",
            rule: "needs one weave speed, capsize speed and stable range per parameter value"
                .into(),
        });
    }
    Ok(Figure {
        width: 1000,
        height: 650,
        content: Content::Study(Box::new(StudyFigure { data: data.clone() })),
    })
}

/// Viridis-like colour map (five stops, linear between them).
fn colour(t: f64) -> (u8, u8, u8) {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let k = (t.floor() as usize).min(3);
    let f = t - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Where `v` sits on a diverging scale over [lo, hi]: 0.5 at zero, 0 at `lo` (when negative),
/// 1 at `hi` (when positive).
fn diverging_place(v: f64, (lo, hi): (f64, f64)) -> f64 {
    if v < 0.0 {
        if lo < 0.0 {
            0.5 - 0.5 * (v / lo).min(1.0)
        } else {
            0.5
        }
    } else if hi > 0.0 {
        0.5 + 0.5 * (v / hi).min(1.0)
    } else {
        0.5
    }
}

/// Blue (0) through white (0.5) to red (1).
fn diverging_colour(t: f64) -> (u8, u8, u8) {
    let t = t.clamp(0.0, 1.0);
    let (from, to, f) = if t < 0.5 {
        ((37.0, 99.0, 235.0), (255.0, 255.0, 255.0), t / 0.5)
    } else {
        ((255.0, 255.0, 255.0), (220.0, 38.0, 38.0), (t - 0.5) / 0.5)
    };
    let mix = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    (mix(from.0, to.0), mix(from.1, to.1), mix(from.2, to.2))
}

/// No value (invalid design, quantity absent).
const NO_VALUE: (u8, u8, u8) = (215, 215, 215);
/// Unbounded (+∞).
const UNBOUNDED: (u8, u8, u8) = (190, 30, 45);

impl MapFigure {
    fn cell_colour(&self, v: f64) -> (u8, u8, u8) {
        if v == f64::INFINITY {
            UNBOUNDED
        } else if v.is_finite() {
            let (lo, hi) = self.range;
            if self.data.diverging {
                diverging_colour(diverging_place(v, self.range))
            } else {
                colour((v - lo) / (hi - lo))
            }
        } else {
            NO_VALUE
        }
    }

    /// The cells as an image, one pixel per cell, top row = largest y.
    pub(crate) fn raster(&self) -> Result<resvg::tiny_skia::Pixmap> {
        let (nx, ny) = (self.data.x.2, self.data.y.2);
        let mut pixmap =
            resvg::tiny_skia::Pixmap::new(nx as u32, ny as u32).ok_or(Error::Encode {
                message: format!("a {nx} x {ny} image cannot be allocated"),
            })?;
        let pixels = pixmap.pixels_mut();
        for iy in 0..ny {
            for ix in 0..nx {
                let (r, g, b) = self.cell_colour(self.data.values[iy * nx + ix]);
                let row = ny - 1 - iy;
                pixels[row * nx + ix] =
                    resvg::tiny_skia::PremultipliedColorU8::from_rgba(r, g, b, 255)
                        .unwrap_or(resvg::tiny_skia::PremultipliedColorU8::TRANSPARENT);
            }
        }
        Ok(pixmap)
    }

    /// Segments of the boundary of the stable set (marching squares at 0.5 between cell
    /// centres), in data coordinates.
    fn boundary(&self) -> Vec<[(f64, f64); 2]> {
        let (x0, x1, nx) = self.data.x;
        let (y0, y1, ny) = self.data.y;
        let at = |i: usize, j: usize| self.data.stable[j * nx + i];
        let px = |i: f64| {
            if nx > 1 {
                x0 + (x1 - x0) * i / (nx - 1) as f64
            } else {
                x0
            }
        };
        let py = |j: f64| {
            if ny > 1 {
                y0 + (y1 - y0) * j / (ny - 1) as f64
            } else {
                y0
            }
        };
        let mut out = Vec::new();
        for j in 0..ny.saturating_sub(1) {
            for i in 0..nx.saturating_sub(1) {
                let c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                let case = c
                    .iter()
                    .enumerate()
                    .fold(0u8, |m, (k, &b)| m | (u8::from(b) << k));
                if case == 0 || case == 15 {
                    continue;
                }
                let (fi, fj) = (i as f64, j as f64);
                // Edge midpoints: bottom, right, top, left.
                let e = [
                    (px(fi + 0.5), py(fj)),
                    (px(fi + 1.0), py(fj + 0.5)),
                    (px(fi + 0.5), py(fj + 1.0)),
                    (px(fi), py(fj + 0.5)),
                ];
                let pairs: &[(usize, usize)] = match case {
                    1 | 14 => &[(3, 0)],
                    2 | 13 => &[(0, 1)],
                    3 | 12 => &[(3, 1)],
                    4 | 11 => &[(1, 2)],
                    6 | 9 => &[(0, 2)],
                    7 | 8 => &[(3, 2)],
                    5 => &[(3, 0), (1, 2)],
                    10 => &[(0, 1), (2, 3)],
                    _ => &[],
                };
                for &(a, b) in pairs {
                    out.push([e[a], e[b]]);
                }
            }
        }
        out
    }

    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        const FIGURE: &str = "design map";
        let (width, _) = root.dim_in_pixel();
        let (plot, bar) = root.split_horizontally(width.saturating_sub(170));
        let (x0, x1, nx) = self.data.x;
        let (y0, y1, ny) = self.data.y;
        // Cells are centred on the grid values: the image spans half a cell beyond them.
        let half = |a: f64, b: f64, n: usize| {
            if n > 1 {
                0.5 * (b - a) / (n - 1) as f64
            } else {
                0.5
            }
        };
        let (hx, hy) = (half(x0, x1, nx), half(y0, y1, ny));
        let (ax0, ax1) = (x0.min(x1) - hx.abs(), x0.max(x1) + hx.abs());
        let (ay0, ay1) = (y0.min(y1) - hy.abs(), y0.max(y1) + hy.abs());
        let mut chart = ChartBuilder::on(&plot)
            .margin(14)
            .caption(&self.data.title, text(20.0, &DARK))
            .x_label_area_size(56)
            .y_label_area_size(80)
            .build_cartesian_2d(ax0..ax1, ay0..ay1)
            .or_draw(FIGURE)?;
        house_mesh(&mut chart, 14.0)
            .disable_mesh()
            .x_desc(&self.data.x_label)
            .y_desc(&self.data.y_label)
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .draw()
            .or_draw(FIGURE)?;
        let (px, py) = chart.plotting_area().get_pixel_range();
        self.area.set((px.start, py.start, px.end, py.end));
        let area = chart.plotting_area();
        for seg in self.boundary() {
            area.draw(&PathElement::new(seg.to_vec(), BLACK.stroke_width(2)))
                .or_draw(FIGURE)?;
        }
        if let Some((bx, by)) = self.data.base {
            if bx >= ax0 && bx <= ax1 && by >= ay0 && by <= ay1 {
                area.draw(&Cross::new((bx, by), 9, WHITE.stroke_width(5)))
                    .or_draw(FIGURE)?;
                area.draw(&Cross::new((bx, by), 9, BLACK.stroke_width(2)))
                    .or_draw(FIGURE)?;
                area.draw(&Text::new(
                    "base design",
                    (bx + 0.015 * (ax1 - ax0), by + 0.01 * (ay1 - ay0)),
                    text(14.0, &DARK).pos(plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Left,
                        plotters::style::text_anchor::VPos::Bottom,
                    )),
                ))
                .or_draw(FIGURE)?;
            }
        }
        // Colour bar.
        let (lo, hi) = self.range;
        let mut cb = ChartBuilder::on(&bar)
            .margin_top(80)
            .margin_bottom(160)
            .margin_right(70)
            .y_label_area_size(0)
            .right_y_label_area_size(60)
            .build_cartesian_2d(0.0..1.0, lo..hi)
            .or_draw(FIGURE)?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_label_formatter(&tick)
            .label_style(text(13.0, &DARK))
            .draw()
            .or_draw(FIGURE)?;
        let steps = 200;
        for k in 0..steps {
            let a = lo + (hi - lo) * k as f64 / steps as f64;
            let b = lo + (hi - lo) * (k + 1) as f64 / steps as f64;
            let (r, g, bb) = if self.data.diverging {
                diverging_colour(diverging_place(0.5 * (a + b), (lo, hi)))
            } else {
                colour((k as f64 + 0.5) / steps as f64)
            };
            cb.draw_series(std::iter::once(Rectangle::new(
                [(0.0, a), (1.0, b)],
                RGBColor(r, g, bb).filled(),
            )))
            .or_draw(FIGURE)?;
        }
        let (bw, bh) = bar.dim_in_pixel();
        // The label in two lines: the name, then the unit.
        let (name, unit) = match self.data.quantity.rfind(" [") {
            Some(k) => (&self.data.quantity[..k], &self.data.quantity[k + 1..]),
            None => (self.data.quantity.as_str(), ""),
        };
        let mut line_y = 6;
        for line in wrap(name, 22)
            .iter()
            .map(String::as_str)
            .chain(std::iter::once(unit))
        {
            bar.draw(&Text::new(line.to_string(), (6, line_y), text(13.0, &DARK)))
                .or_draw(FIGURE)?;
            line_y += 16;
        }
        let swatch = |y: i32, c: (u8, u8, u8), label: &str| -> Result<()> {
            bar.draw(&Rectangle::new(
                [(10, y), (28, y + 14)],
                RGBColor(c.0, c.1, c.2).filled(),
            ))
            .or_draw(FIGURE)?;
            bar.draw(&Text::new(label.to_string(), (34, y), text(13.0, &DARK)))
                .or_draw(FIGURE)?;
            Ok(())
        };
        let y = bh as i32 - 140;
        swatch(y, UNBOUNDED, "unbounded")?;
        swatch(y + 22, NO_VALUE, "none / invalid")?;
        bar.draw(&PathElement::new(
            vec![(10, y + 51), (28, y + 51)],
            BLACK.stroke_width(2),
        ))
        .or_draw(FIGURE)?;
        bar.draw(&Text::new(
            self.data.outline[0].as_str(),
            (34, y + 44),
            text(13.0, &DARK),
        ))
        .or_draw(FIGURE)?;
        bar.draw(&Text::new(
            self.data.outline[1].as_str(),
            (34, y + 60),
            text(13.0, &DARK),
        ))
        .or_draw(FIGURE)?;
        let _ = bw;
        Ok(())
    }
}

impl StudyFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        const FIGURE: &str = "design study";
        let d = &self.data;
        let mut top = 0.0f64;
        for v in d
            .weave
            .iter()
            .chain(&d.capsize)
            .chain(&d.stable_from)
            .chain(&d.stable_to)
        {
            if let Some(v) = v.filter(|v| v.is_finite()) {
                top = top.max(v);
            }
        }
        let top = if top > 0.0 { top * 1.1 } else { 10.0 };
        let (xa, xb) =
            d.x.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
        let (xa, xb) = if xa < xb {
            (xa, xb)
        } else {
            (xa - 0.5, xa + 0.5)
        };
        let mut chart = ChartBuilder::on(root)
            .margin(16)
            .caption(&d.title, text(20.0, &DARK))
            .x_label_area_size(56)
            .y_label_area_size(70)
            .build_cartesian_2d(xa..xb, 0.0..top)
            .or_draw(FIGURE)?;
        house_mesh(&mut chart, 14.0)
            .x_desc(&d.x_label)
            .y_desc("forward speed v [m/s]")
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .draw()
            .or_draw(FIGURE)?;
        // The self-stable band: one polygon per run of consecutive stable designs.
        let mut run: Vec<(f64, f64, f64)> = Vec::new();
        let mut flush = |run: &mut Vec<(f64, f64, f64)>| -> Result<()> {
            if run.len() >= 2 {
                let mut pts: Vec<(f64, f64)> = run.iter().map(|&(x, a, _)| (x, a)).collect();
                pts.extend(run.iter().rev().map(|&(x, _, b)| (x, b)));
                chart
                    .draw_series(std::iter::once(Polygon::new(pts, GREEN.mix(0.3).filled())))
                    .or_draw(FIGURE)?;
            }
            run.clear();
            Ok(())
        };
        for k in 0..d.x.len() {
            match (d.stable_from[k], d.stable_to[k]) {
                (Some(a), Some(b)) => run.push((d.x[k], a.min(top), b.min(top))),
                _ => flush(&mut run)?,
            }
        }
        flush(&mut run)?;
        for (values, colour, name) in [
            (&d.weave, BLUE, "weave speed v_w"),
            (&d.capsize, VERMILLION, "capsize speed v_c"),
        ] {
            let mut first = true;
            let mut seg: Vec<(f64, f64)> = Vec::new();
            let mut segments = Vec::new();
            for (k, v) in values.iter().enumerate() {
                match v.filter(|v| v.is_finite() && *v <= top) {
                    Some(v) => seg.push((d.x[k], v)),
                    None => {
                        if !seg.is_empty() {
                            segments.push(std::mem::take(&mut seg));
                        }
                    }
                }
            }
            if !seg.is_empty() {
                segments.push(seg);
            }
            for s in segments {
                let series = chart
                    .draw_series(LineSeries::new(s, colour.stroke_width(3)))
                    .or_draw(FIGURE)?;
                if first {
                    series.label(name).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3))
                    });
                    first = false;
                }
            }
        }
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(xa, 0.0), (xa, 0.0)],
                GREEN.mix(0.3).filled(),
            )))
            .or_draw(FIGURE)?
            .label("self-stable")
            .legend(|(x, y)| {
                Rectangle::new([(x, y - 6), (x + 20, y + 6)], GREEN.mix(0.3).filled())
            });
        if let Some(b) = d.base {
            if b >= xa && b <= xb {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(b, 0.0), (b, top)],
                        DARK.stroke_width(1),
                    )))
                    .or_draw(FIGURE)?
                    .label("base design")
                    .legend(|(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], DARK.stroke_width(1))
                    });
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(LIGHT)
            .label_font(text(14.0, &DARK))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .or_draw(FIGURE)?;
        Ok(())
    }
}

/// Words of `text` in lines of at most `width` characters.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(l) if l.chars().count() + 1 + word.chars().count() <= width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Standard base64 (RFC 4648) of `bytes`.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(A[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }
}
