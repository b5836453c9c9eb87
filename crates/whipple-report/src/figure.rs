//! A figure: what to draw, held as plain data, rendered on demand to SVG text or PNG bytes.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

use crate::error::{Error, Result};

/// The font family every figure uses; registered from the `dejavu` crate's embedded DejaVu Sans
/// so that PNG text works on machines without system fonts.
pub(crate) const FONT: &str = "sans-serif";

/// resvg's options with DejaVu Sans as the sans-serif family (no system fonts needed).
fn png_options() -> &'static resvg::usvg::Options<'static> {
    static OPTIONS: OnceLock<resvg::usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut options = resvg::usvg::Options::default();
        let fonts = options.fontdb_mut();
        for bytes in [
            dejavu::sans::regular(),
            dejavu::sans::bold(),
            dejavu::sans::oblique(),
        ] {
            fonts.load_font_data(bytes.to_vec());
        }
        fonts.set_sans_serif_family("DejaVu Sans");
        options.font_family = "DejaVu Sans".to_string();
        options
    })
}

/// Registers DejaVu Sans (regular, bold, oblique) once per process.
pub(crate) fn ensure_fonts() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Oblique, dejavu::sans::oblique()),
            (FontStyle::Italic, dejavu::sans::oblique()),
        ]
        .into_iter()
        .all(|(style, bytes)| plotters::style::register_font(FONT, style, bytes).is_ok())
    });
    if ok {
        Ok(())
    } else {
        Err(Error::Font {
            name: "DejaVu Sans",
        })
    }
}

/// An output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Scalable vector graphics (UTF-8 text).
    Svg,
    /// Portable network graphics (8-bit RGB).
    Png,
}

impl Format {
    /// The format named by a file extension, `svg` or `png` in any case.
    ///
    /// ```
    /// use whipple_report::Format;
    /// assert_eq!(Format::from_extension("PNG")?, Format::Png);
    /// # Ok::<(), whipple_report::Error>(())
    /// ```
    pub fn from_extension(extension: &str) -> Result<Format> {
        match extension.to_ascii_lowercase().as_str() {
            "svg" => Ok(Format::Svg),
            "png" => Ok(Format::Png),
            _ => Err(Error::UnknownFormat {
                name: extension.to_string(),
            }),
        }
    }

    /// The format named by a path's extension (`eigen.svg` → SVG).
    pub fn from_path(path: &Path) -> Result<Format> {
        path.extension()
            .and_then(|e| e.to_str())
            .ok_or_else(|| Error::UnknownFormat {
                name: path.display().to_string(),
            })
            .and_then(Format::from_extension)
    }

    /// The usual file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Png => "png",
        }
    }
}

/// What a figure shows; each variant owns the data it needs.
#[derive(Debug, Clone)]
pub(crate) enum Content {
    Eigen(Box<crate::eigen::EigenFigure>),
    SideView(Box<crate::side_view::SideViewFigure>),
    TimeSeries(Box<crate::time_series::TimeSeriesFigure>),
    Turns(Box<crate::turns::TurnsFigure>),
    Xy(Box<crate::xy::XyFigure>),
    Stacked(Box<crate::xy::XyStack>),
    Map(Box<crate::design::MapFigure>),
    Study(Box<crate::design::StudyFigure>),
    Tornado(Box<crate::tornado::TornadoFigure>),
    Manoeuvre(Box<crate::manoeuvre::ManoeuvreFigure>),
    Bode(Box<crate::bode::BodeFigure>),
}

/// A figure ready to render: its size in pixels and what it shows. Built by
/// [`eigen_plot`](crate::eigen_plot), [`side_view`](crate::side_view()),
/// [`time_series_plot`](crate::time_series_plot), [`xy_log_plot`](crate::xy_log_plot) and
/// [`line_plot`](crate::line_plot); it does no file I/O.
#[derive(Debug, Clone)]
pub struct Figure {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) content: Content,
}

/// Maps any plotters error to [`Error::Draw`] for the named figure.
pub(crate) trait OrDraw<T> {
    fn or_draw(self, figure: &'static str) -> Result<T>;
}

impl<T, E: std::fmt::Display> OrDraw<T> for std::result::Result<T, E> {
    fn or_draw(self, figure: &'static str) -> Result<T> {
        self.map_err(|e| Error::Draw {
            figure,
            message: e.to_string(),
        })
    }
}

/// Smallest and largest figure side accepted [px].
const MIN_SIDE: u32 = 100;
const MAX_SIDE: u32 = 10_000;

impl Figure {
    /// Width and height \[px\].
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The same figure at another size \[px\], each side within 100..=10000. Figures drawn to
    /// scale (the side view, the ground track) keep their aspect ratio inside the new size.
    pub fn with_size(mut self, width: u32, height: u32) -> Result<Figure> {
        for (what, side) in [("width", width), ("height", height)] {
            if !(MIN_SIDE..=MAX_SIDE).contains(&side) {
                return Err(Error::InvalidArgument {
                    what: "figure size",
                    rule: format!("{what} must lie in {MIN_SIDE}..={MAX_SIDE} px, got {side}"),
                });
            }
        }
        self.width = width;
        self.height = height;
        Ok(self)
    }

    /// Renders to bytes in `format`: UTF-8 SVG text or a PNG image.
    ///
    /// ```
    /// use whipple::advanced::{stability, sweep};
    /// use whipple::{Canonical, BenchmarkParameters};
    /// use whipple_report::{eigen_plot, EigenPlotOptions, Format};
    /// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007()).unwrap();
    /// let s = whipple::eigen_sweep(&canonical, &whipple::speed_grid(0.0, 10.0, 0.1).unwrap()).unwrap();
    /// let c = whipple::critical_speeds(&canonical, 0.0, 10.0).unwrap();
    /// let svg = eigen_plot(&s, &c, &EigenPlotOptions::default())?.render(Format::Svg)?;
    /// assert!(String::from_utf8_lossy(&svg).contains("<svg"));
    /// # Ok::<(), whipple_report::Error>(())
    /// ```
    pub fn render(&self, format: Format) -> Result<Vec<u8>> {
        match format {
            Format::Svg => self.to_svg().map(String::into_bytes),
            Format::Png => self.to_png(),
        }
    }

    /// Renders in the format named by the path's extension (the path is not touched).
    pub fn render_for_path(&self, path: &Path) -> Result<Vec<u8>> {
        self.render(Format::from_path(path)?)
    }

    /// Renders to SVG text.
    pub fn to_svg(&self) -> Result<String> {
        let text = self.plotters_svg()?;
        if let Content::Map(map) = &self.content {
            // The cells as an embedded PNG under the axes (one pixel per cell, not smoothed).
            let png = map.raster()?.encode_png().map_err(|e| Error::Encode {
                message: e.to_string(),
            })?;
            let (x0, y0, x1, y1) = map.area.get();
            let image = format!(
                "<image x=\"{x0}\" y=\"{y0}\" width=\"{}\" height=\"{}\" \
                 preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\" \
                 href=\"data:image/png;base64,{}\"/>",
                x1 - x0,
                y1 - y0,
                crate::design::base64(&png)
            );
            let at = background_end(&text);
            return Ok(format!("{}{image}{}", &text[..at], &text[at..]));
        }
        Ok(text)
    }

    /// The SVG as plotters draws it.
    fn plotters_svg(&self) -> Result<String> {
        ensure_fonts()?;
        let mut text = String::new();
        {
            let root =
                SVGBackend::with_string(&mut text, (self.width, self.height)).into_drawing_area();
            self.draw(&root)?;
            root.present().or_draw(self.name())?;
        }
        Ok(text)
    }

    /// Renders to a PNG image (8-bit RGB).
    pub fn to_png(&self) -> Result<Vec<u8>> {
        // Rendered from the SVG by resvg: the same picture as the SVG, with properly spaced,
        // anti-aliased text (plotters' own bitmap text drops the glyphs' side bearings).
        let svg = match &self.content {
            // The cells are painted first; the axes go over them without the background.
            Content::Map(_) => {
                let svg = self.plotters_svg()?;
                let at = background_end(&svg);
                let start = svg[..at].rfind("<rect").unwrap_or(at);
                format!("{}{}", &svg[..start], &svg[at..])
            }
            _ => self.to_svg()?,
        };
        let tree = resvg::usvg::Tree::from_str(&svg, png_options()).map_err(|e| Error::Encode {
            message: format!("reading the {} back as SVG: {e}", self.name()),
        })?;
        let mut pixmap =
            resvg::tiny_skia::Pixmap::new(self.width, self.height).ok_or(Error::Encode {
                message: format!(
                    "a {} x {} image cannot be allocated",
                    self.width, self.height
                ),
            })?;
        pixmap.fill(resvg::tiny_skia::Color::WHITE);
        if let Content::Map(map) = &self.content {
            let cells = map.raster()?;
            let (x0, y0, x1, y1) = map.area.get();
            let sx = f64::from(x1 - x0) / f64::from(cells.width());
            let sy = f64::from(y1 - y0) / f64::from(cells.height());
            pixmap.draw_pixmap(
                0,
                0,
                cells.as_ref(),
                &resvg::tiny_skia::PixmapPaint {
                    quality: resvg::tiny_skia::FilterQuality::Nearest,
                    ..Default::default()
                },
                resvg::tiny_skia::Transform::from_row(
                    sx as f32, 0.0, 0.0, sy as f32, x0 as f32, y0 as f32,
                ),
                None,
            );
        }
        resvg::render(
            &tree,
            resvg::tiny_skia::Transform::identity(),
            &mut pixmap.as_mut(),
        );
        pixmap.encode_png().map_err(|e| Error::Encode {
            message: e.to_string(),
        })
    }

    fn name(&self) -> &'static str {
        match self.content {
            Content::Eigen(_) => "eigenvalue plot",
            Content::SideView(_) => "side view",
            Content::TimeSeries(_) => "time series plot",
            Content::Xy(_) => "line plot",
            Content::Stacked(_) => "stacked line plots",
            Content::Map(_) => "design map",
            Content::Study(_) => "design study",
            Content::Tornado(_) => "tornado plot",
            Content::Bode(_) => "Bode plot",
            Content::Turns(_) => "turn families",
            Content::Manoeuvre(_) => "manoeuvre plot",
        }
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        root.fill(&WHITE).or_draw(self.name())?;
        match &self.content {
            Content::Eigen(f) => f.draw(root),
            Content::SideView(f) => f.draw(root),
            Content::TimeSeries(f) => f.draw(root),
            Content::Xy(f) => f.draw(root),
            Content::Stacked(f) => f.draw(root),
            Content::Map(f) => f.draw(root),
            Content::Study(f) => f.draw(root),
            Content::Tornado(f) => f.draw(root),
            Content::Bode(f) => f.draw(root),
            Content::Turns(f) => f.draw(root),
            Content::Manoeuvre(f) => f.draw(root),
        }
    }
}

/// The byte offset just after the figure's background rectangle (the first `<rect .../>`).
fn background_end(svg: &str) -> usize {
    svg.find("<rect")
        .and_then(|start| svg[start..].find("/>").map(|end| start + end + 2))
        .unwrap_or_else(|| svg.find('>').map_or(0, |k| k + 1))
}
