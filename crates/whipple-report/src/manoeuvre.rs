//! One manoeuvre on the linear and the non-linear bicycle in one figure: lean and steer against
//! time for both models, the size of their difference on a logarithmic axis, and both paths of
//! the rear contact in the ground plane.

use plotters::coord::Shift;
use plotters::prelude::*;
use whipple::advanced::linear::ManoeuvreComparison;

use crate::clip::Rect;
use crate::draw::{
    BLUE, DARK, Dash, GREEN, GREY, VERMILLION, draw_clipped, house_mesh, text, tick,
};
use crate::error::{Error, Result};
use crate::figure::{Content, Figure, OrDraw};
use crate::xy::span;

const FIGURE: &str = "manoeuvre plot";

#[derive(Debug, Clone)]
pub(crate) struct ManoeuvreFigure {
    title: String,
    comparison: ManoeuvreComparison,
}

/// The manoeuvre of [`whipple::advanced::linear::compare_manoeuvre`] in one figure: on the left
/// lean and steer of both models (linear solid, non-linear dashed) and |non-linear − linear| of
/// lean, steer, yaw and the rear contact's y on a log axis; on the right the rear contact's
/// path in the ground plane for both models (x and y each on its own scale, so that a long,
/// narrow path still shows its lateral motion).
pub fn manoeuvre_plot(comparison: &ManoeuvreComparison, title: &str) -> Result<Figure> {
    let n = comparison.times.len();
    if n < 2 {
        return Err(Error::InvalidArgument {
            what: "manoeuvre",
            rule: format!("at least two sample times are needed, got {n}"),
        });
    }
    for (name, motion) in [
        ("linear", &comparison.linear),
        ("non-linear", &comparison.nonlinear),
        ("difference", &comparison.difference),
    ] {
        for (column, values) in motion.columns() {
            if values.len() != n {
                return Err(Error::InvalidArgument {
                    what: "manoeuvre",
                    rule: format!(
                        "the {name} {column} has {} values for {n} times",
                        values.len()
                    ),
                });
            }
        }
    }
    Figure {
        width: 1200,
        height: 760,
        content: Content::Manoeuvre(Box::new(ManoeuvreFigure {
            title: title.to_string(),
            comparison: comparison.clone(),
        })),
    }
    .with_size(1200, 760)
}

impl ManoeuvreFigure {
    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let c = &self.comparison;
        let root = root
            .titled(&self.title, text(20.0, &DARK))
            .or_draw(FIGURE)?;
        let (w, _) = root.dim_in_pixel();
        let (left, right) = root.split_horizontally((w as f64 * 0.55) as u32);
        let panels = left.split_evenly((3, 1));
        let t = &c.times;
        let (t0, t1) = span(t.iter().copied());
        let rows: [(&str, &[f64], &[f64], RGBColor); 2] = [
            ("lean φ [rad]", &c.linear.lean, &c.nonlinear.lean, BLUE),
            (
                "steer δ [rad]",
                &c.linear.steer,
                &c.nonlinear.steer,
                VERMILLION,
            ),
        ];
        for ((label, linear, nonlinear, colour), panel) in rows.iter().zip(&panels) {
            let (mut y0, mut y1) = span(linear.iter().chain(nonlinear.iter()).copied());
            let pad = 0.08 * (y1 - y0);
            y0 -= pad;
            y1 += pad;
            let mut chart = ChartBuilder::on(panel)
                .margin(8)
                .x_label_area_size(22)
                .y_label_area_size(70)
                .build_cartesian_2d(t0..t1, y0..y1)
                .or_draw(FIGURE)?;
            house_mesh(&mut chart, 13.0)
                .light_line_style(RGBColor(244, 244, 244))
                .y_desc(*label)
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
                .axis_desc_style(text(14.0, &DARK))
                .draw()
                .or_draw(FIGURE)?;
            let rect = Rect {
                x0: t0,
                x1: t1,
                y0,
                y1,
            };
            let area = chart.plotting_area();
            for (values, dash) in [(linear, Dash::Solid), (nonlinear, Dash::Dashed)] {
                let points: Vec<(f64, f64)> =
                    t.iter().copied().zip(values.iter().copied()).collect();
                draw_clipped(area, &points, &rect, colour.stroke_width(2), dash, FIGURE)?;
            }
        }
        self.draw_difference(&panels[2])?;
        self.draw_path(&right)
    }

    /// |non-linear − linear| of lean, steer, yaw and y on a log axis; exact zeros (at t = 0)
    /// break the lines.
    fn draw_difference<DB: DrawingBackend>(&self, panel: &DrawingArea<DB, Shift>) -> Result<()> {
        let c = &self.comparison;
        let t = &c.times;
        let (t0, t1) = span(t.iter().copied());
        let curves: [(&str, &[f64], RGBColor); 4] = [
            ("lean", &c.difference.lean, BLUE),
            ("steer", &c.difference.steer, VERMILLION),
            ("yaw", &c.difference.yaw, GREEN),
            ("rear y [m]", &c.difference.rear_y, DARK),
        ];
        let positive = curves
            .iter()
            .flat_map(|(_, v, _)| v.iter().map(|x| x.abs()))
            .filter(|x| *x > 0.0 && x.is_finite());
        let (lo, hi) = positive.fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        let (y0, y1) = if hi > 0.0 {
            (
                whipple::math::powf(10f64, whipple::math::log10(lo).floor()).max(hi * 1e-12),
                whipple::math::powf(10f64, whipple::math::log10(hi).ceil()),
            )
        } else {
            (1e-16, 1.0)
        };
        let mut chart = ChartBuilder::on(panel)
            .margin(8)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(t0..t1, (y0..y1).log_scale())
            .or_draw(FIGURE)?;
        house_mesh(&mut chart, 13.0)
            .light_line_style(RGBColor(244, 244, 244))
            .y_desc("|non-linear − linear|")
            .x_desc("time t [s]")
            .x_label_formatter(&tick)
            .y_label_formatter(&|v: &f64| format!("{v:.0e}"))
            .axis_desc_style(text(14.0, &DARK))
            .draw()
            .or_draw(FIGURE)?;
        let area = chart.plotting_area();
        for (_, values, colour) in &curves {
            let mut run: Vec<(f64, f64)> = Vec::new();
            for (time, x) in t.iter().zip(values.iter()) {
                let size = x.abs();
                if size > 0.0 && size.is_finite() {
                    run.push((*time, size.clamp(y0, y1)));
                } else if !run.is_empty() {
                    area.draw(&PathElement::new(
                        std::mem::take(&mut run),
                        colour.stroke_width(2),
                    ))
                    .or_draw(FIGURE)?;
                }
            }
            if run.len() > 1 {
                area.draw(&PathElement::new(run, colour.stroke_width(2)))
                    .or_draw(FIGURE)?;
            }
        }
        // The legend along the panel's top, inside the plotting area (pixels of the panel).
        let style = text(13.0, &DARK);
        let mut x = 90;
        for (name, _, colour) in &curves {
            panel
                .draw(&PathElement::new(
                    vec![(x, 18), (x + 22, 18)],
                    colour.stroke_width(2),
                ))
                .or_draw(FIGURE)?;
            panel
                .draw_text(name, &style, (x + 26, 11))
                .or_draw(FIGURE)?;
            x += 40 + 8 * name.chars().count() as i32;
        }
        Ok(())
    }

    /// The rear contact's path of both models: x along, y across (its own scale).
    fn draw_path<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()> {
        let c = &self.comparison;
        let h = area.dim_in_pixel().1;
        let (plot_area, note) = area.split_vertically(h.saturating_sub(70));
        let xs = c.linear.rear_x.iter().chain(&c.nonlinear.rear_x).copied();
        let ys = c.linear.rear_y.iter().chain(&c.nonlinear.rear_y).copied();
        let (mut x0, mut x1) = span(xs);
        let (mut y0, mut y1) = span(ys);
        let (px, py) = (0.04 * (x1 - x0), 0.08 * (y1 - y0));
        x0 -= px;
        x1 += px;
        y0 -= py;
        y1 += py;
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(12)
            .caption(
                "rear contact's path (x and y scaled apart)",
                text(16.0, &DARK),
            )
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .or_draw(FIGURE)?;
        house_mesh(&mut chart, 13.0)
            .light_line_style(RGBColor(244, 244, 244))
            .x_desc("x [m]")
            .y_desc("y [m], right positive")
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .axis_desc_style(text(14.0, &DARK))
            .draw()
            .or_draw(FIGURE)?;
        let rect = Rect { x0, x1, y0, y1 };
        let plot = chart.plotting_area();
        for (motion, colour, dash) in [
            (&c.linear, BLUE, Dash::Solid),
            (&c.nonlinear, VERMILLION, Dash::Dashed),
        ] {
            let points: Vec<(f64, f64)> = motion
                .rear_x
                .iter()
                .copied()
                .zip(motion.rear_y.iter().copied())
                .collect();
            draw_clipped(plot, &points, &rect, colour.stroke_width(2), dash, FIGURE)?;
        }
        let style = text(14.0, &DARK);
        let mut x = 16;
        for (colour, name) in [
            (BLUE, "linear (solid)"),
            (VERMILLION, "non-linear (dashed)"),
        ] {
            note.draw(&PathElement::new(
                vec![(x, 10), (x + 30, 10)],
                colour.stroke_width(2),
            ))
            .or_draw(FIGURE)?;
            note.draw_text(name, &style, (x + 36, 2)).or_draw(FIGURE)?;
            x += 210;
        }
        let [lean, _, _, _, y, _] = c.difference.max_abs();
        note.draw_text(
            &format!(
                "largest difference: lean {lean:.2e} rad, y {y:.2e} m; left panels: linear \
                 solid, non-linear dashed"
            ),
            &text(13.0, &GREY),
            (16, 30),
        )
        .or_draw(FIGURE)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Format;
    use whipple::BenchmarkParameters;
    use whipple::advanced::linear::{Input, InputSignal, Manoeuvre, compare_manoeuvre};

    #[test]
    fn a_steer_pulse_draws_both_models_and_their_difference() {
        let pulse = Manoeuvre {
            speed: 5.0,
            lean: 0.0,
            steer: 0.0,
            inputs: vec![(
                Input::SteerTorque,
                InputSignal::pulse(0.0, 0.5, 1.0).unwrap(),
            )],
        };
        let times: Vec<f64> = (0..=60).map(|k| 0.05 * k as f64).collect();
        let both =
            compare_manoeuvre(&BenchmarkParameters::meijaard2007(), &pulse, &times, 1e-10).unwrap();
        let figure = manoeuvre_plot(&both, "benchmark at 5 m/s: a 1 N m steer pulse").unwrap();
        let svg = figure.to_svg().unwrap();
        for word in [
            "lean φ",
            "steer δ",
            "non-linear − linear",
            "rear contact",
            "scaled apart",
        ] {
            assert!(svg.contains(word), "{word}");
        }
        let png = figure.render(Format::Png).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        if let Ok(dir) = std::env::var("WHIPPLE_FIGURE_DIR") {
            std::fs::write(std::path::Path::new(&dir).join("manoeuvre.png"), png).unwrap();
        }
        let mut short = both.clone();
        short.times.truncate(1);
        assert!(manoeuvre_plot(&short, "").is_err());
    }
}
