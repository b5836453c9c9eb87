//! JBike6's stylized side view of a bicycle, drawn to scale (metres, equal aspect): ground,
//! wheels, steer axis, fork, frame, rider silhouette and every body's centre of mass with its
//! mass, plus wheelbase, trail and head angle.
//!
//! Only the wheels, the steer axis and the centres of mass are the bicycle's own numbers; the
//! frame tubes, saddle and rider figure are drawn from them by fixed rules of thumb.

use plotters::coord::Shift;
use plotters::prelude::*;
use whipple::BenchmarkParameters;
use whipple::advanced::parameters::Jbike6Parameters;
use whipple::advanced::side_view::{Part, SideView};

use crate::draw::{BLUE, DARK, GREY, Placed, VERMILLION, place, text};
use crate::error::Result;
use crate::figure::{Content, Figure, OrDraw};

const FIGURE: &str = "side view";

/// A rider is drawn when the rear body (or JBike6's rider) weighs more than this [kg].
const RIDER_MASS: f64 = 30.0;

type P = (f64, f64);

#[derive(Debug, Clone)]
struct CentreOfMass {
    at: P,
    label: String,
    colour: &'static RGBColor,
}

/// Everything the side view draws, in metres, x forward, y up.
#[derive(Debug, Clone)]
pub(crate) struct SideViewFigure {
    name: String,
    view: SideView,
    centres: Vec<CentreOfMass>,
    rider: bool,
}

/// Mass as short text: "85 kg", "2.5 kg", "1.82 kg".
fn mass(m: f64) -> String {
    let s = format!("{m:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    format!("{s} kg")
}

/// The side view of a bicycle (JBike6 style), drawn from the library's geometry
/// ([`whipple::advanced::side_view`]); with its JBike6 form, the individual bodies (rider, frame, rack,
/// fork, basket) are shown instead of the combined B and H.
///
/// ```
/// use whipple::BenchmarkParameters;
/// let svg = whipple_report::side_view(&BenchmarkParameters::meijaard2007(), None, "benchmark")
///     .to_svg()?;
/// assert!(svg.contains("85 kg") && svg.contains("w = 1.020 m"));
/// # Ok::<(), whipple_report::Error>(())
/// ```
pub fn side_view(
    bike: &BenchmarkParameters,
    jbike6: Option<&Jbike6Parameters>,
    name: &str,
) -> Figure {
    let view = whipple::advanced::side_view::side_view(bike, jbike6);
    let rider = jbike6.map_or(bike.m_b, |j| j.rider.m) > RIDER_MASS;
    let centres = view
        .bodies
        .iter()
        .map(|body| {
            let label = match body.part {
                Part::RearFrame if rider => "B frame + rider",
                Part::RearFrame => "B frame",
                Part::FrontFrame => "H fork",
                _ => body.name,
            };
            CentreOfMass {
                at: (body.centre[0], body.centre[1]),
                label: format!("{label} {}", mass(body.mass)),
                colour: if body.part.is_wheel() {
                    &DARK
                } else if body.part.is_front() {
                    &BLUE
                } else {
                    &VERMILLION
                },
            }
        })
        .collect();
    let figure = SideViewFigure {
        name: name.to_string(),
        view,
        centres,
        rider,
    };
    let (x0, x1, y0, y1) = figure.extent();
    let width = 1000u32;
    let pw = width as f64 - MARGIN_W;
    let height = (pw * (y1 - y0) / (x1 - x0) + MARGIN_H).clamp(200.0, 2000.0) as u32;
    Figure {
        width,
        height,
        content: Content::SideView(Box::new(figure)),
    }
}

/// Pixels taken by margins and axis labels, across and down.
const MARGIN_W: f64 = 2.0 * 12.0 + 52.0;
const MARGIN_H: f64 = 2.0 * 12.0 + 40.0 + 34.0;

/// The library's geometry as the drawing's points.
struct Geometry {
    rear_hub: P,
    front_hub: P,
    ground_point: P,
    crown: P,
    head_top: P,
    bar: P,
    grip: P,
    bottom_bracket: P,
    saddle: P,
    axis_ends: [P; 2],
}

fn add(a: P, b: P) -> P {
    (a.0 + b.0, a.1 + b.1)
}

fn scale(a: P, k: f64) -> P {
    (a.0 * k, a.1 * k)
}

impl SideViewFigure {
    fn geometry(&self) -> Geometry {
        let v = &self.view;
        let p = |a: [f64; 2]| (a[0], a[1]);
        Geometry {
            rear_hub: p(v.rear_hub),
            front_hub: p(v.front_hub),
            ground_point: p(v.ground_point),
            crown: p(v.crown),
            head_top: p(v.head_top),
            bar: p(v.bar),
            grip: p(v.grip),
            bottom_bracket: p(v.bottom_bracket),
            saddle: p(v.saddle),
            axis_ends: v.steer_axis.map(p),
        }
    }

    /// Shoulder and head centre of the rider figure.
    fn rider_points(&self, g: &Geometry) -> (P, P, P) {
        let hip = add(g.saddle, (0.0, 0.06));
        let lean = 50f64.to_radians();
        let shoulder = add(
            hip,
            (
                0.55 * whipple::math::cos(lean),
                0.55 * whipple::math::sin(lean),
            ),
        );
        let head = add(shoulder, (0.1, 0.17));
        (hip, shoulder, head)
    }

    /// (x0, x1, y0, y1) in metres.
    fn extent(&self) -> (f64, f64, f64, f64) {
        let g = self.geometry();
        let v = &self.view;
        let (r_r, r_f) = (v.rear_wheel_radius, v.front_wheel_radius);
        let mut x0 = (-r_r).min(-0.1);
        let mut x1 = (v.wheelbase + r_f).max(g.ground_point.0) + 0.1;
        let mut y1 = g.bar.1.max(r_r * 2.0).max(r_f * 2.0);
        for c in &self.centres {
            x0 = x0.min(c.at.0);
            x1 = x1.max(c.at.0);
            y1 = y1.max(c.at.1);
        }
        if self.rider {
            let (_, _, head) = self.rider_points(&g);
            y1 = y1.max(head.1 + 0.12);
        }
        (x0 - 0.25, x1 + 0.45, -0.2, y1 + 0.15)
    }

    pub(crate) fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (w, h) = root.dim_in_pixel();
        // Fit the extent into the plotting area at equal scale, centring the slack.
        let (mut x0, mut x1, mut y0, mut y1) = self.extent();
        let pw = (w as f64 - MARGIN_W).max(10.0);
        let ph = (h as f64 - MARGIN_H).max(10.0);
        let k = (pw / (x1 - x0)).min(ph / (y1 - y0));
        let (dx, dy) = (pw / k - (x1 - x0), ph / k - (y1 - y0));
        x0 -= dx / 2.0;
        x1 += dx / 2.0;
        y1 += dy;
        y0 -= 0.0;

        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption(format!("{} — side view", self.name), text(20.0, &DARK))
            .x_label_area_size(40)
            .y_label_area_size(52)
            .build_cartesian_2d(x0..x1, y0..y1)
            .or_draw(FIGURE)?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(245, 245, 245))
            .bold_line_style(RGBColor(232, 232, 232))
            .x_desc("x [m]")
            .y_desc("height [m]")
            .label_style(text(13.0, &GREY))
            .axis_desc_style(text(14.0, &GREY))
            .draw()
            .or_draw(FIGURE)?;
        let area = chart.plotting_area();
        let px = |p: P| chart.backend_coord(&p);
        let v = &self.view;
        let (w, c, lambda) = (v.wheelbase, v.trail, v.steer_axis_tilt);
        let g = self.geometry();
        let line = |pts: Vec<P>, style: ShapeStyle| area.draw(&PathElement::new(pts, style));

        // Ground.
        area.draw(&Rectangle::new(
            [(x0, y0), (x1, 0.0)],
            RGBColor(244, 241, 234).filled(),
        ))
        .or_draw(FIGURE)?;
        line(vec![(x0, 0.0), (x1, 0.0)], GREY.stroke_width(2)).or_draw(FIGURE)?;

        // Rider silhouette, behind the bicycle.
        if self.rider {
            let (hip, shoulder, head) = self.rider_points(&g);
            let body = RGBColor(190, 200, 215).stroke_width((0.07 * k).max(3.0) as u32);
            let limb = RGBColor(190, 200, 215).stroke_width((0.05 * k).max(2.0) as u32);
            let pedal = add(g.bottom_bracket, (0.08, -0.1));
            let mid = scale(add(hip, pedal), 0.5);
            let knee = add(mid, (0.17, 0.05));
            line(vec![hip, knee, pedal], limb).or_draw(FIGURE)?;
            line(vec![hip, shoulder], body).or_draw(FIGURE)?;
            let elbow = add(scale(add(shoulder, g.grip), 0.5), (0.0, -0.06));
            line(vec![shoulder, elbow, g.grip], limb).or_draw(FIGURE)?;
            area.draw(&Polygon::new(
                circle(head, 0.11),
                RGBColor(190, 200, 215).filled(),
            ))
            .or_draw(FIGURE)?;
        }

        // Wheels (a skate where the radius is zero).
        for (hub, r) in [
            (g.rear_hub, v.rear_wheel_radius),
            (g.front_hub, v.front_wheel_radius),
        ] {
            if r > 0.0 {
                line(circle(hub, r), DARK.stroke_width(3)).or_draw(FIGURE)?;
                line(circle(hub, 0.93 * r), GREY.stroke_width(1)).or_draw(FIGURE)?;
            } else {
                let blade = vec![
                    (hub.0 - 0.1, 0.0),
                    (hub.0 + 0.08, 0.0),
                    (hub.0 + 0.11, 0.03),
                ];
                line(blade, DARK.stroke_width(4)).or_draw(FIGURE)?;
                line(
                    vec![(hub.0 - 0.05, 0.0), (hub.0 - 0.05, 0.05)],
                    DARK.stroke_width(2),
                )
                .or_draw(FIGURE)?;
            }
        }

        // Steer axis, from below the ground to above the bars.
        let [axis_start, axis_end] = g.axis_ends;
        area.draw(&plotters::element::DashedPathElement::new(
            vec![axis_start, axis_end],
            8,
            4,
            GREY.stroke_width(1),
        ))
        .or_draw(FIGURE)?;

        // Frame tubes and fork.
        let frame = RGBColor(60, 80, 110).stroke_width(4);
        for [a, b] in self.view.frame_tubes() {
            line(vec![(a[0], a[1]), (b[0], b[1])], frame).or_draw(FIGURE)?;
        }
        line(
            vec![g.crown, g.head_top],
            RGBColor(60, 80, 110).stroke_width(7),
        )
        .or_draw(FIGURE)?;
        let fork = BLUE.stroke_width(4);
        line(vec![g.front_hub, g.crown, g.head_top, g.bar, g.grip], fork).or_draw(FIGURE)?;
        line(
            vec![add(g.saddle, (-0.11, 0.0)), add(g.saddle, (0.09, 0.0))],
            DARK.stroke_width(6),
        )
        .or_draw(FIGURE)?;
        for hub in [g.rear_hub, g.front_hub] {
            area.draw(&Circle::new(hub, 3, DARK.filled()))
                .or_draw(FIGURE)?;
        }

        // Dimensions: wheelbase and trail below the ground, head angle at the steer axis.
        let dim = DARK.stroke_width(1);
        let yw = -0.1;
        line(vec![(0.0, yw), (w, yw)], dim).or_draw(FIGURE)?;
        for x in [0.0, w] {
            line(vec![(x, yw - 0.03), (x, 0.0)], dim).or_draw(FIGURE)?;
        }
        let label = text(14.0, &DARK);
        let mut taken: Vec<Placed> = Vec::new();
        let centred = |s: &str, at: P| -> Result<(i32, i32)> {
            let (tw, th) = root.estimate_text_size(s, &label).or_draw(FIGURE)?;
            let (cx, cy) = px(at);
            Ok((cx - tw as i32 / 2, cy - th as i32 / 2))
        };
        let wl = format!("w = {w:.3} m");
        let pos = centred(&wl, (0.5 * w, yw - 0.045))?;
        root.draw_text(&wl, &label, pos).or_draw(FIGURE)?;
        let yc = -0.045;
        line(vec![(w, yc), (w + c, yc)], dim).or_draw(FIGURE)?;
        line(vec![(w + c, yc - 0.02), (w + c, 0.0)], dim).or_draw(FIGURE)?;
        let cl = format!("c = {c:.3} m");
        let (cx, cy) = px((w.max(w + c) + 0.03, yc));
        root.draw_text(&cl, &label, (cx, cy - 8)).or_draw(FIGURE)?;
        let head = format!(
            "head angle {:.1}°  (λ = {:.1}°)",
            90.0 - lambda.to_degrees(),
            lambda.to_degrees()
        );
        let (hx, hy) = px(add(axis_end, (0.03, 0.0)));
        root.draw_text(&head, &label, (hx, hy - 8))
            .or_draw(FIGURE)?;
        taken.push(Placed {
            x0: hx,
            y0: hy - 8,
            x1: hx + 260,
            y1: hy + 10,
        });

        // Centres of mass with their masses.
        let radius = 9.0 / k;
        for c in &self.centres {
            cm_symbol(area, c.at, radius, *c.colour)?;
        }
        for c in &self.centres {
            let (tw, th) = root.estimate_text_size(&c.label, &label).or_draw(FIGURE)?;
            let (cx, cy) = px(c.at);
            let (tw, th) = (tw as i32, th as i32);
            let candidates = [
                (cx + 13, cy - th / 2),
                (cx - 13 - tw, cy - th / 2),
                (cx + 13, cy - th - 8),
                (cx + 13, cy + 8),
                (cx - tw / 2, cy - th - 14),
                (cx - tw / 2, cy + 14),
                (cx - 13 - tw, cy - th - 8),
                (cx - 13 - tw, cy + 8),
            ];
            let pos = place(&mut taken, &candidates, (tw as u32, th as u32));
            crate::draw::boxed_text(root, &c.label, &text(14.0, c.colour), pos, FIGURE)?;
        }
        Ok(())
    }
}

/// Points on a circle (closed).
fn circle(centre: P, r: f64) -> Vec<P> {
    (0..=240)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 240.0;
            (
                centre.0 + r * whipple::math::cos(a),
                centre.1 + r * whipple::math::sin(a),
            )
        })
        .collect()
}

/// The quartered-circle centre-of-mass symbol: two opposite quarters filled.
fn cm_symbol<DB: DrawingBackend, CT: plotters::coord::CoordTranslate<From = P>>(
    area: &DrawingArea<DB, CT>,
    at: P,
    r: f64,
    colour: RGBColor,
) -> Result<()> {
    area.draw(&Polygon::new(circle(at, r), WHITE.filled()))
        .or_draw(FIGURE)?;
    for start in [0.0, std::f64::consts::PI] {
        let mut quarter = vec![at];
        quarter.extend((0..=12).map(|i| {
            let a = start + i as f64 * std::f64::consts::FRAC_PI_2 / 12.0;
            (
                at.0 + r * whipple::math::cos(a),
                at.1 + r * whipple::math::sin(a),
            )
        }));
        area.draw(&Polygon::new(quarter, colour.filled()))
            .or_draw(FIGURE)?;
    }
    area.draw(&PathElement::new(circle(at, r), colour.stroke_width(2)))
        .or_draw(FIGURE)?;
    Ok(())
}
