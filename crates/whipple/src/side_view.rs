//! JBike6's stylized side view of a bicycle, as geometry: where the wheels, the steer axis, the
//! fork, the frame tubes, the bottom bracket, the saddle and the handlebar are, and each body's
//! centre of mass with the inertia ellipse of its mass distribution. The one home of these
//! rules: the report's drawing (`whipple-report`) and the web page's side view (`whipple-web`)
//! both draw from it.
//!
//! Coordinates: metres, x forward from the rear wheel's contact, y up (JBike6's side view; the
//! benchmark's z points down, so y = −z). Only the wheels, the steer axis, the trail and the
//! bodies come from the parameters; the frame tubes, saddle and handlebar are a drawing aid
//! placed from them by fixed rules of thumb.
//!
//! ```
//! use whipple::advanced::side_view::side_view;
//! use whipple::BenchmarkParameters;
//! let view = side_view(&BenchmarkParameters::meijaard2007(), None);
//! assert_eq!(view.front_hub, [1.02, 0.35]);
//! assert!((view.total_mass - 94.0).abs() < 1e-12);
//! ```

use serde::Serialize;

use crate::parameters::{BenchmarkParameters, Jbike6Parameters};

/// A point (x forward, y up) \[m\].
pub type Point = [f64; 2];

/// The uniform solid ellipsoid with a body's mass and inertia, cut by the side-view plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ellipse {
    /// Semi-axes \[m\], the first along `angle`.
    pub semi_axes: [f64; 2],
    /// Angle of the first semi-axis from x, counter-clockwise (toward up) \[rad\].
    pub angle: f64,
}

/// Which body a centre of mass belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Part {
    /// The rear wheel R.
    RearWheel,
    /// The front wheel F.
    FrontWheel,
    /// The benchmark's rear frame B (frame and rider).
    RearFrame,
    /// The benchmark's front frame H (fork and handlebar).
    FrontFrame,
    /// JBike6's rider (part of B).
    Rider,
    /// JBike6's frame (part of B).
    Frame,
    /// JBike6's rack (part of B).
    Rack,
    /// JBike6's fork (part of H).
    Fork,
    /// JBike6's basket (part of H).
    Basket,
}

impl Part {
    /// True for the wheels.
    pub fn is_wheel(self) -> bool {
        matches!(self, Part::RearWheel | Part::FrontWheel)
    }

    /// True for the parts of the front frame H (steered).
    pub fn is_front(self) -> bool {
        matches!(self, Part::FrontFrame | Part::Fork | Part::Basket)
    }
}

/// A body drawn at its centre of mass.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideBody {
    /// Which body.
    pub part: Part,
    /// Its name (`rear wheel`, `rear frame B`, `rider`, `fork`, …).
    pub name: &'static str,
    /// Mass \[kg\].
    pub mass: f64,
    /// Centre of mass \[m\].
    pub centre: Point,
    /// The inertia ellipse; `None` for the wheels (drawn as wheels) and bodies without mass or
    /// inertia.
    pub ellipse: Option<Ellipse>,
}

/// Everything a side view draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideView {
    /// Wheelbase w \[m\]: the front contact is at (w, 0).
    pub wheelbase: f64,
    /// Trail c \[m\]: the steer axis meets the ground at (w + c, 0).
    pub trail: f64,
    /// Steer axis tilt λ from the vertical \[rad\].
    pub steer_axis_tilt: f64,
    /// Rear wheel radius r_R \[m\] (0 for a skate).
    pub rear_wheel_radius: f64,
    /// Front wheel radius r_F \[m\].
    pub front_wheel_radius: f64,
    /// The rear hub, (0, r_R).
    pub rear_hub: Point,
    /// The front hub, (w, r_F).
    pub front_hub: Point,
    /// Where the steer axis meets the ground, (w + c, 0).
    pub ground_point: Point,
    /// The unit vector along the steer axis, pointing up.
    pub up: Point,
    /// The drawn steer axis, from just below the ground to above the handlebar.
    pub steer_axis: [Point; 2],
    /// The fork crown (bottom of the head tube), on the steer axis above the front hub.
    pub crown: Point,
    /// The top of the head tube, on the steer axis.
    pub head_top: Point,
    /// The top of the stem, where the handlebar starts, on the steer axis.
    pub bar: Point,
    /// The end of the handlebar, toward the rider.
    pub grip: Point,
    /// The bottom bracket.
    pub bottom_bracket: Point,
    /// The top of the seat tube, where the top tube and the seat stays meet.
    pub seat_cluster: Point,
    /// The saddle, above the seat cluster on the seat tube's line.
    pub saddle: Point,
    /// The bodies: the two wheels, then B and H (benchmark form) or JBike6's rider, frame, rack,
    /// fork and basket (those with mass).
    pub bodies: Vec<SideBody>,
    /// Total mass \[kg\].
    pub total_mass: f64,
    /// The whole bicycle's centre of mass \[m\].
    pub centre_of_mass: Point,
}

impl SideView {
    /// The stylized rear-frame tubes as segments (a drawing aid, not parameters): chain stay,
    /// seat tube, seat stay, top tube, down tube and seat post.
    pub fn frame_tubes(&self) -> [[Point; 2]; 6] {
        [
            [self.rear_hub, self.bottom_bracket],
            [self.bottom_bracket, self.seat_cluster],
            [self.seat_cluster, self.rear_hub],
            [self.seat_cluster, self.head_top],
            [self.bottom_bracket, self.crown],
            [self.seat_cluster, self.saddle],
        ]
    }
}

impl SideView {
    /// The box the bicycle occupies in the side view, `[min, max]` corners (x forward, y up)
    /// \[m\]: the wheels (x from −r_R to w + r_F, up to the taller wheel's top) and, for each
    /// other body, its inertia ellipse (the uniform solid ellipsoid with its mass and inertia)
    /// or, without one, its centre of mass. Only the parameters decide it: the drawing aids
    /// (tubes, saddle, handlebar) do not count. The ground, y = 0, is always its lower side.
    pub fn extent(&self) -> [Point; 2] {
        let mut lo = [0.0 - self.rear_wheel_radius, 0.0];
        let mut hi = [
            self.wheelbase + self.front_wheel_radius,
            2.0 * self.rear_wheel_radius.max(self.front_wheel_radius),
        ];
        for body in self
            .bodies
            .iter()
            .filter(|b| !b.part.is_wheel() && b.mass > 0.0)
        {
            let half = body.ellipse.map_or([0.0, 0.0], |e| {
                let [a, b] = e.semi_axes;
                let (s, c) = crate::math::sin_cos(e.angle);
                [
                    (a * a * c * c + b * b * s * s).sqrt(),
                    (a * a * s * s + b * b * c * c).sqrt(),
                ]
            });
            for k in 0..2 {
                lo[k] = lo[k].min(body.centre[k] - half[k]);
                hi[k] = hi[k].max(body.centre[k] + half[k]);
            }
        }
        lo[1] = 0.0;
        [lo, hi]
    }
}

/// Semi-axes of the uniform ellipsoid with in-plane principal moments `i1` (about the first
/// axis) and `i2`, and lateral moment `i3`: a_k² = 5 (I_j + I_3 − I_k) / (2m).
pub(crate) fn ellipse(mass: f64, i1: f64, i2: f64, i3: f64, angle: f64) -> Option<Ellipse> {
    if mass <= 0.0 {
        return None;
    }
    let k = 5.0 / (2.0 * mass);
    let a1 = (k * (i2 + i3 - i1)).max(0.0).sqrt();
    let a2 = (k * (i1 + i3 - i2)).max(0.0).sqrt();
    (a1 > 0.0 || a2 > 0.0).then_some(Ellipse {
        semi_axes: [a1, a2],
        angle,
    })
}

/// A benchmark body's ellipse from I_xx, I_yy (lateral), I_zz, I_xz (z down).
pub(crate) fn benchmark_ellipse(
    mass: f64,
    ixx: f64,
    iyy: f64,
    izz: f64,
    ixz: f64,
) -> Option<Ellipse> {
    let mean = 0.5 * (ixx + izz);
    let radius = (0.25 * (ixx - izz).powi(2) + ixz * ixz).sqrt();
    // The larger principal moment's axis lies at θ from x toward +z (down), so at −θ with y up.
    let theta = 0.5 * crate::math::atan2(2.0 * ixz, ixx - izz);
    ellipse(mass, mean + radius, mean - radius, iyy, -theta)
}

fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1]]
}

fn scale(a: Point, k: f64) -> Point {
    [a[0] * k, a[1] * k]
}

/// The side view of a bicycle whose benchmark parameters are `p` (validated), with JBike6's
/// separate bodies when it was described in that form.
pub fn side_view(p: &BenchmarkParameters, jbike6: Option<&Jbike6Parameters>) -> SideView {
    let ground_point = [p.w + p.c, 0.0];
    let up = [-crate::math::sin(p.lambda), crate::math::cos(p.lambda)];
    let rear_hub = [0.0, p.r_r];
    let front_hub = [p.w, p.r_f];
    let along = |s: f64| add(ground_point, scale(up, s));
    // Up the steer axis from its point nearest the front hub (at least 5 cm up the axis): the
    // crown 0.1 m further, a head tube of 0.2 m, a stem of 0.1 m, a handlebar 0.1 m back.
    let s_hub = (front_hub[0] - ground_point[0]) * up[0] + (front_hub[1] - ground_point[1]) * up[1];
    let crown = along(s_hub.max(0.05) + 0.1);
    let head_top = along(s_hub.max(0.05) + 0.3);
    let bar = along(s_hub.max(0.05) + 0.4);
    let grip = add(bar, [-0.1, 0.0]);
    // The bottom bracket at 40 % of the wheelbase, 0.8 of the larger wheel radius up (at least
    // 0.12 m); a seat tube 17° back from the vertical reaching 3 cm above the head tube (at
    // least 0.2 m long), the saddle 0.12 m further along it.
    let wheel = p.r_r.max(p.r_f).max(0.15);
    let bottom_bracket = [0.4 * p.w, 0.8 * wheel];
    let seat_angle = 17f64.to_radians();
    let tube = [-crate::math::sin(seat_angle), crate::math::cos(seat_angle)];
    let length = ((head_top[1] + 0.03 - bottom_bracket[1]) / tube[1]).max(0.2);
    let seat_cluster = add(bottom_bracket, scale(tube, length));
    let saddle = add(seat_cluster, scale(tube, 0.12));
    let steer_axis = [
        add(ground_point, scale(up, -0.06)),
        add(bar, scale(up, 0.12)),
    ];

    let mut bodies = vec![
        SideBody {
            part: Part::RearWheel,
            name: "rear wheel",
            mass: p.m_r,
            centre: rear_hub,
            ellipse: None,
        },
        SideBody {
            part: Part::FrontWheel,
            name: "front wheel",
            mass: p.m_f,
            centre: front_hub,
            ellipse: None,
        },
    ];
    match jbike6 {
        Some(j) => {
            for (part, name, b) in [
                (Part::Rider, "rider", &j.rider),
                (Part::Frame, "frame", &j.frame),
                (Part::Rack, "rack", &j.rack),
            ] {
                if b.m > 0.0 {
                    let [i1, i2, i3] = b.inertia;
                    bodies.push(SideBody {
                        part,
                        name,
                        mass: b.m,
                        centre: [b.xcm, b.ycm],
                        ellipse: ellipse(b.m, i1, i2, i3, b.alpha),
                    });
                }
            }
            for (part, name, b) in [
                (Part::Fork, "fork", &j.fork),
                (Part::Basket, "basket", &j.basket),
            ] {
                if b.m > 0.0 {
                    let [i1, i2, i3] = b.inertia;
                    bodies.push(SideBody {
                        part,
                        name,
                        mass: b.m,
                        centre: j.front_body_centre(b),
                        ellipse: ellipse(b.m, i1, i2, i3, b.alpha),
                    });
                }
            }
        }
        None => {
            bodies.push(SideBody {
                part: Part::RearFrame,
                name: "rear frame B",
                mass: p.m_b,
                centre: [p.x_b, -p.z_b],
                ellipse: benchmark_ellipse(p.m_b, p.i_bxx, p.i_byy, p.i_bzz, p.i_bxz),
            });
            bodies.push(SideBody {
                part: Part::FrontFrame,
                name: "front frame H",
                mass: p.m_h,
                centre: [p.x_h, -p.z_h],
                ellipse: benchmark_ellipse(p.m_h, p.i_hxx, p.i_hyy, p.i_hzz, p.i_hxz),
            });
        }
    }
    let total_mass: f64 = bodies.iter().map(|b| b.mass).sum();
    let centre_of_mass = if total_mass > 0.0 {
        [
            bodies.iter().map(|b| b.mass * b.centre[0]).sum::<f64>() / total_mass,
            bodies.iter().map(|b| b.mass * b.centre[1]).sum::<f64>() / total_mass,
        ]
    } else {
        [0.0, 0.0]
    };
    SideView {
        wheelbase: p.w,
        trail: p.c,
        steer_axis_tilt: p.lambda,
        rear_wheel_radius: p.r_r,
        front_wheel_radius: p.r_f,
        rear_hub,
        front_hub,
        ground_point,
        up,
        steer_axis,
        crown,
        head_top,
        bar,
        grip,
        bottom_bracket,
        seat_cluster,
        saddle,
        bodies,
        total_mass,
        centre_of_mass,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameters::presets;

    /// The centre of mass drawn is the one the benchmark parameters imply (masses R, B, H, F),
    /// whichever form the bicycle was described in.
    #[test]
    fn centre_of_mass_matches_benchmark_parameters() -> crate::Result<()> {
        for preset in presets::PRESETS {
            let bike = preset.bicycle();
            let p = bike.benchmark()?;
            let view = side_view(&p, bike.jbike6());
            let m = p.m_r + p.m_b + p.m_h + p.m_f;
            let x = (p.m_b * p.x_b + p.m_h * p.x_h + p.m_f * p.w) / m;
            let y = (p.m_r * p.r_r - p.m_b * p.z_b - p.m_h * p.z_h + p.m_f * p.r_f) / m;
            assert!((view.total_mass - m).abs() < 1e-9, "{}", preset.name);
            assert!((view.centre_of_mass[0] - x).abs() < 1e-9, "{}", preset.name);
            assert!((view.centre_of_mass[1] - y).abs() < 1e-9, "{}", preset.name);
        }
        Ok(())
    }

    /// A uniform ellipsoid's moments give back its semi-axes.
    #[test]
    fn ellipse_of_a_uniform_ellipsoid() {
        let (m, a, b, c) = (3.0, 0.5, 0.2, 0.1);
        let i1 = m * (b * b + c * c) / 5.0;
        let i2 = m * (a * a + c * c) / 5.0;
        let i3 = m * (a * a + b * b) / 5.0;
        let e = ellipse(m, i1, i2, i3, 0.3).expect("positive mass");
        assert!((e.semi_axes[0] - a).abs() < 1e-12 && (e.semi_axes[1] - b).abs() < 1e-12);
        // Rotated into the benchmark's axes (z down) by θ: the same ellipse comes back.
        let theta: f64 = 0.3;
        let (s, co) = crate::math::sin_cos(theta);
        // Tensor in (x, z) with the first principal axis at −θ from x toward +z.
        let ixx = i1 * co * co + i2 * s * s;
        let izz = i1 * s * s + i2 * co * co;
        let ixz = -(i1 - i2) * s * co;
        let e = benchmark_ellipse(m, ixx, i3, izz, ixz).expect("positive mass");
        let [p, q] = e.semi_axes;
        // The larger moment belongs to the shorter semi-axis along the first direction.
        assert!((p.max(q) - a).abs() < 1e-12 && (p.min(q) - b).abs() < 1e-12);
    }

    /// The drawn parts sit where the rules put them: the steer axis through the ground point
    /// and the head tube, the bottom bracket between the wheels, the saddle above it.
    #[test]
    fn parts_lie_on_their_lines() {
        let p = BenchmarkParameters::meijaard2007();
        let v = side_view(&p, None);
        let on_axis = |q: Point| {
            let d = [q[0] - v.ground_point[0], q[1] - v.ground_point[1]];
            (d[0] * v.up[1] - d[1] * v.up[0]).abs() < 1e-12
        };
        assert!(on_axis(v.crown) && on_axis(v.head_top) && on_axis(v.bar));
        assert!(on_axis(v.steer_axis[0]) && on_axis(v.steer_axis[1]));
        assert!(v.bottom_bracket[0] > 0.0 && v.bottom_bracket[0] < p.w);
        assert!(v.saddle[1] > v.seat_cluster[1] && v.seat_cluster[1] > v.bottom_bracket[1]);
    }
}
