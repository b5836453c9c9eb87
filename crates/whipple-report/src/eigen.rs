//! Eigenvalues against forward speed, as in JBike6 and Meijaard et al. 2007, Fig. 3: real parts
//! solid, imaginary parts dashed, one colour per mode, the self-stable speed range shaded and the
//! critical speeds marked.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use whipple::advanced::modes::Mode;
use whipple::{CriticalSpeeds, EigenSweep};
use whipple_front::units::SpeedUnit;

use crate::clip::Rect;
use crate::draw::{
    BLUE, DARK, Dash, GREEN, GREY, Swatch, VERMILLION, draw_clipped, draw_legend, fixed,
    house_mesh, label_markers, text, tick,
};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};

const FIGURE: &str = "eigenvalue plot";

/// Settings of [`eigen_plot`] and [`eigen_comparison_plot`].
#[derive(Debug, Clone, PartialEq)]
pub struct EigenPlotOptions {
    /// Range of the eigenvalue axis [1/s]; curves are clipped at it. Default (−10, 10), the range
    /// of Meijaard 2007 Fig. 3 (the castering eigenvalue falls below −10 above about 4 m/s).
    pub y_range: (f64, f64),
    /// Range of the speed axis [m/s]; `None` (default) spans the sweep's speeds.
    pub x_range: Option<(f64, f64)>,
    /// Draw |Im λ| as dashed lines (default true).
    pub show_imaginary: bool,
    /// A title above the plot (default none).
    pub title: Option<String>,
    /// Figure size \[px\] (default 1000 × 620).
    pub size: (u32, u32),
    /// Bands to shade around the first bicycle's real parts: for each speed of its sweep and
    /// each column, (Re λ − σ, Re λ + σ) (NaN where unknown); default none.
    pub sigma_bands: Option<Vec<[(f64, f64); 4]>>,
    /// What the shaded speed ranges are called in the legend (default "self-stable"; a closed
    /// loop's are "stable").
    pub stable_label: String,
    /// The unit of the speed axis, its critical-speed labels and its legend's ranges (default
    /// m/s; km/h for speeds typed in km/h). `x_range` stays in m/s.
    pub speed_unit: SpeedUnit,
}

impl Default for EigenPlotOptions {
    fn default() -> Self {
        EigenPlotOptions {
            y_range: (-10.0, 10.0),
            x_range: None,
            show_imaginary: true,
            title: None,
            size: (1000, 620),
            sigma_bands: None,
            stable_label: "self-stable".to_string(),
            speed_unit: SpeedUnit::MetresPerSecond,
        }
    }
}

/// One bicycle's results for [`eigen_comparison_plot`].
#[derive(Debug, Clone, Copy)]
pub struct BikeEigen<'a> {
    /// The name shown in the legend.
    pub name: &'a str,
    /// The eigenvalue sweep.
    pub sweep: &'a EigenSweep,
    /// The critical speeds and stable ranges.
    pub critical: &'a CriticalSpeeds,
}

#[derive(Debug, Clone)]
struct BikeData {
    name: Option<String>,
    sweep: EigenSweep,
    critical: CriticalSpeeds,
}

/// The data of an eigenvalue figure.
#[derive(Debug, Clone)]
pub(crate) struct EigenFigure {
    bikes: Vec<BikeData>,
    options: EigenPlotOptions,
}

/// Line patterns (real, imaginary) for the first, second and third bicycle.
const PATTERNS: [(Dash, Dash); 3] = [
    (Dash::Solid, Dash::Dashed),
    (Dash::LongDashed, Dash::Dotted),
    (Dash::Dotted, Dash::Dashed),
];

/// Shading of the self-stable ranges for the first, second and third bicycle.
const SHADES: [RGBColor; 3] = [
    RGBColor(150, 150, 150),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
];

/// The colour of a mode's curves.
pub fn mode_colour(mode: Mode) -> (u8, u8, u8) {
    let c = match mode {
        Mode::Weave => BLUE,
        Mode::Capsize => VERMILLION,
        Mode::Castering => GREEN,
        _ => GREY,
    };
    (c.0, c.1, c.2)
}

fn colour(mode: Mode) -> RGBColor {
    let (r, g, b) = mode_colour(mode);
    RGBColor(r, g, b)
}

fn check_range(what: &'static str, (lo, hi): (f64, f64)) -> Result<()> {
    if lo.is_finite() && hi.is_finite() && lo < hi {
        Ok(())
    } else {
        Err(Error::InvalidArgument {
            what,
            rule: format!("needs finite LO < HI, got ({lo}, {hi})"),
        })
    }
}

/// Eigenvalues of one bicycle against speed (Meijaard 2007 Fig. 3 style).
///
/// ```
/// use whipple::advanced::{stability, sweep};
/// use whipple::{Canonical, BenchmarkParameters};
/// use whipple_report::{eigen_plot, EigenPlotOptions};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007()).unwrap();
/// let s = whipple::eigen_sweep(&canonical, &whipple::speed_grid(0.0, 10.0, 0.05).unwrap()).unwrap();
/// let c = whipple::critical_speeds(&canonical, 0.0, 10.0).unwrap();
/// let svg = eigen_plot(&s, &c, &EigenPlotOptions::default())?.to_svg()?;
/// assert!(svg.contains("v_w = 4.292 m/s") && svg.contains("castering"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn eigen_plot(
    sweep: &EigenSweep,
    critical: &CriticalSpeeds,
    options: &EigenPlotOptions,
) -> Result<Figure> {
    build(
        vec![BikeData {
            name: None,
            sweep: sweep.clone(),
            critical: critical.clone(),
        }],
        options,
    )
}

/// Eigenvalues of up to three bicycles overlaid: mode colours as in [`eigen_plot`], one line
/// pattern per bicycle, one legend entry per bicycle name.
pub fn eigen_comparison_plot(
    bikes: &[BikeEigen<'_>],
    options: &EigenPlotOptions,
) -> Result<Figure> {
    if bikes.is_empty() || bikes.len() > PATTERNS.len() {
        return Err(Error::InvalidArgument {
            what: "bicycles",
            rule: format!(
                "compare 1 to {} bicycles, got {}",
                PATTERNS.len(),
                bikes.len()
            ),
        });
    }
    build(
        bikes
            .iter()
            .map(|b| BikeData {
                name: Some(b.name.to_string()),
                sweep: b.sweep.clone(),
                critical: b.critical.clone(),
            })
            .collect(),
        options,
    )
}

fn build(mut bikes: Vec<BikeData>, options: &EigenPlotOptions) -> Result<Figure> {
    check_range("eigenvalue axis range", options.y_range)?;
    if let Some(r) = options.x_range {
        check_range("speed axis range", r)?;
    }
    // Drawn in the speed unit asked for: every speed converted once, here.
    let unit = options.speed_unit;
    let size = options.size;
    let mut options = options.clone();
    options.x_range = options
        .x_range
        .map(|(a, b)| (unit.from_si(a), unit.from_si(b)));
    for b in &mut bikes {
        for v in &mut b.sweep.speeds {
            *v = unit.from_si(*v);
        }
        let c = &mut b.critical;
        c.range = (unit.from_si(c.range.0), unit.from_si(c.range.1));
        for speed in [
            &mut c.double_root_speed,
            &mut c.weave_speed,
            &mut c.capsize_speed,
        ] {
            *speed = speed.map(|v| unit.from_si(v));
        }
        for (lo, hi) in &mut c.stable_speed_ranges {
            (*lo, *hi) = (unit.from_si(*lo), unit.from_si(*hi));
        }
    }
    Figure {
        width: 100,
        height: 100,
        content: Content::Eigen(Box::new(EigenFigure { bikes, options })),
    }
    .with_size(size.0, size.1)
}

impl EigenFigure {
    /// The speed axis range: the option, else the sweeps' span, else the searched range.
    fn x_range(&self) -> (f64, f64) {
        if let Some(r) = self.options.x_range {
            return r;
        }
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for b in &self.bikes {
            for &v in &b.sweep.speeds {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if lo < hi {
            return (lo, hi);
        }
        let (clo, chi) = self
            .bikes
            .first()
            .map(|b| b.critical.range)
            .unwrap_or((0.0, 1.0));
        if clo.is_finite() && chi.is_finite() && clo < chi {
            (clo, chi)
        } else if lo.is_finite() {
            (lo - 0.5, lo + 0.5)
        } else {
            (0.0, 1.0)
        }
    }

    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (width, _) = root.dim_in_pixel();
        let (plot_area, legend_area) = root.split_horizontally(width.saturating_sub(250));
        let (x0, x1) = self.x_range();
        let (y0, y1) = self.options.y_range;
        let rect = Rect { x0, x1, y0, y1 };
        let mut builder = ChartBuilder::on(&plot_area);
        builder
            .margin(12)
            .x_label_area_size(52)
            .y_label_area_size(64);
        if let Some(title) = &self.options.title {
            builder.caption(title, text(20.0, &DARK));
        }
        let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).or_draw(FIGURE)?;
        house_mesh(&mut chart, 14.0)
            .x_desc(format!(
                "forward speed v [{}]",
                self.options.speed_unit.symbol()
            ))
            .y_desc("eigenvalue λ [1/s]")
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .draw()
            .or_draw(FIGURE)?;
        let area = chart.plotting_area();

        // Self-stable ranges, behind everything.
        let alpha = if self.bikes.len() == 1 { 0.28 } else { 0.22 };
        for (i, b) in self.bikes.iter().enumerate() {
            for &(lo, hi) in &b.critical.stable_speed_ranges {
                let (lo, hi) = (lo.max(x0), hi.min(x1));
                if lo < hi {
                    area.draw(&Rectangle::new(
                        [(lo, y0), (hi, y1)],
                        SHADES[i].mix(alpha).filled(),
                    ))
                    .or_draw(FIGURE)?;
                }
            }
        }
        // Zero line.
        if y0 < 0.0 && y1 > 0.0 {
            area.draw(&PathElement::new(
                vec![(x0, 0.0), (x1, 0.0)],
                BLACK.stroke_width(1),
            ))
            .or_draw(FIGURE)?;
        }

        // Critical speeds: vertical lines; labels placed after the curves.
        let mut markers: Vec<(f64, String)> = Vec::new();
        for b in &self.bikes {
            let c = &b.critical;
            for (symbol, speed) in [
                ("v_d", c.double_root_speed),
                ("v_w", c.weave_speed),
                ("v_c", c.capsize_speed),
            ] {
                let Some(v) = speed else { continue };
                if !(v >= x0 && v <= x1) {
                    continue;
                }
                area.draw(&DashedPathElement::new(
                    vec![(v, y0), (v, y1)],
                    4,
                    3,
                    DARK.mix(0.75).stroke_width(1),
                ))
                .or_draw(FIGURE)?;
                let mut label = format!(
                    "{symbol} = {} {}",
                    fixed(v, 3),
                    self.options.speed_unit.symbol()
                );
                if let (Some(name), true) = (&b.name, self.bikes.len() > 1) {
                    label.push_str(&format!(" ({name})"));
                }
                markers.push((v, label));
            }
        }

        // ±σ bands of the first bicycle's real parts, under the curves.
        if let (Some(bands), Some(b)) = (&self.options.sigma_bands, self.bikes.first()) {
            let s = &b.sweep;
            let n = s.speeds.len().min(bands.len());
            // k indexes both the modes and each speed's bands.
            #[allow(clippy::needless_range_loop)]
            for k in 0..4 {
                let col = colour(s.modes[k]);
                let mut j = 0;
                while j < n {
                    // One polygon per run of speeds with a known band.
                    let known = |j: usize| bands[j][k].0.is_finite() && bands[j][k].1.is_finite();
                    if !known(j) {
                        j += 1;
                        continue;
                    }
                    let start = j;
                    while j < n && known(j) {
                        j += 1;
                    }
                    let clamp = |y: f64| y.clamp(y0, y1);
                    let mut points: Vec<(f64, f64)> = (start..j)
                        .map(|i| (s.speeds[i].clamp(x0, x1), clamp(bands[i][k].1)))
                        .collect();
                    points.extend(
                        (start..j)
                            .rev()
                            .map(|i| (s.speeds[i].clamp(x0, x1), clamp(bands[i][k].0))),
                    );
                    if points.len() >= 4 {
                        area.draw(&Polygon::new(points, col.mix(0.25).filled()))
                            .or_draw(FIGURE)?;
                    }
                }
            }
        }

        // Curves.
        for (i, b) in self.bikes.iter().enumerate() {
            let (re_dash, im_dash) = PATTERNS[i.min(PATTERNS.len() - 1)];
            let s = &b.sweep;
            let n = s.speeds.len().min(s.eigenvalues.len());
            for k in 0..4 {
                let col = colour(s.modes[k]);
                let re: Vec<(f64, f64)> = (0..n)
                    .map(|j| (s.speeds[j], s.eigenvalues[j][k].re))
                    .collect();
                draw_clipped(area, &re, &rect, col.stroke_width(2), re_dash, FIGURE)?;
                if !self.options.show_imaginary {
                    continue;
                }
                let visible = |j: usize| shows_imaginary(&s.eigenvalues[j], k);
                let im: Vec<(f64, f64)> = (0..n)
                    .map(|j| {
                        let shown = visible(j)
                            || (j > 0 && visible(j - 1))
                            || (j + 1 < n && visible(j + 1));
                        let y = if shown {
                            s.eigenvalues[j][k].im.abs()
                        } else {
                            f64::NAN
                        };
                        (s.speeds[j], y)
                    })
                    .collect();
                draw_clipped(area, &im, &rect, col.stroke_width(2), im_dash, FIGURE)?;
            }
        }

        // Critical speed labels along the top, rows chosen so that none overlap.
        let pixels: Vec<(i32, String)> = markers
            .into_iter()
            .map(|(v, label)| (chart.backend_coord(&(v, y1)).0, label))
            .collect();
        label_markers(root, area.get_pixel_range(), &pixels, FIGURE)?;

        draw_legend(&legend_area, &self.legend(), FIGURE)
    }

    fn legend(&self) -> Vec<(Swatch, String)> {
        let mut entries = vec![(Swatch::Heading, "modes".to_string())];
        let mut seen: Vec<Mode> = Vec::new();
        for b in &self.bikes {
            for m in b.sweep.modes {
                if !seen.contains(&m) {
                    seen.push(m);
                }
            }
        }
        for m in [
            Mode::Weave,
            Mode::Capsize,
            Mode::Castering,
            Mode::Unclassified,
        ] {
            if seen.contains(&m) || (m != Mode::Unclassified && seen.is_empty()) {
                entries.push((
                    Swatch::Line {
                        colour: colour(m),
                        width: 3,
                        dash: Dash::Solid,
                    },
                    m.name().to_string(),
                ));
            }
        }
        for (i, b) in self.bikes.iter().enumerate() {
            let (re_dash, im_dash) = PATTERNS[i.min(PATTERNS.len() - 1)];
            entries.push((
                Swatch::Heading,
                b.name.clone().unwrap_or_else(|| "parts".to_string()),
            ));
            entries.push((
                Swatch::Line {
                    colour: DARK,
                    width: 2,
                    dash: re_dash,
                },
                "real part Re λ".to_string(),
            ));
            if self.options.show_imaginary {
                entries.push((
                    Swatch::Line {
                        colour: DARK,
                        width: 2,
                        dash: im_dash,
                    },
                    "imaginary part |Im λ|".to_string(),
                ));
            }
            let alpha = if self.bikes.len() == 1 { 0.28 } else { 0.22 };
            entries.push((
                Swatch::Fill {
                    colour: SHADES[i.min(SHADES.len() - 1)].mix(alpha),
                },
                self.options.stable_label.clone(),
            ));
            let ranges = &b.critical.stable_speed_ranges;
            if ranges.is_empty() {
                entries.push((
                    Swatch::Note,
                    format!("no {} speed in range", self.options.stable_label),
                ));
            }
            for &(lo, hi) in ranges {
                let unit = self.options.speed_unit.symbol();
                let words = if hi.is_finite() {
                    format!("{} – {} {unit}", fixed(lo, 3), fixed(hi, 3))
                } else {
                    format!("above {} {unit}", fixed(lo, 3))
                };
                entries.push((Swatch::Note, words));
            }
        }
        entries.push((Swatch::Heading, "critical speeds".to_string()));
        for note in [
            "v_d  weave pair born (double root)",
            "v_w  weave speed",
            "v_c  capsize speed",
        ] {
            entries.push((Swatch::Note, note.to_string()));
        }
        let (y0, y1) = self.options.y_range;
        entries.push((
            Swatch::Note,
            format!("curves cut at the axis, {y0} … {y1} 1/s"),
        ));
        entries
    }
}

/// Whether column k's |Im λ| is drawn at this speed: it is complex, and it is not the
/// negative-imaginary member of a conjugate pair whose other member is also a column.
fn shows_imaginary(values: &[whipple::advanced::eigen::Complex64; 4], k: usize) -> bool {
    let l = values[k];
    if l.im > 0.0 {
        return true;
    }
    l.im < 0.0
        && !values.iter().enumerate().any(|(j, m)| {
            let scale = 1e-9 * (1.0 + whipple::math::norm(l));
            j != k && (m.im + l.im).abs() <= scale && (m.re - l.re).abs() <= scale
        })
}
