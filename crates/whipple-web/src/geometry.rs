//! JBike6's stylized side view, as geometry for the page to draw: wheels, steer axis, fork,
//! a stylized frame, and each body's centre of mass with its inertia ellipse.
//!
//! Coordinates: metres, x forward from the rear wheel's contact, y up (JBike6's side view;
//! the benchmark's z points down, so y = −z). Only the wheels, the steer axis, the trail and
//! the bodies come from the parameters; the frame tubes are a drawing aid placed from them.

use serde::Serialize;
use whipple::{BenchmarkParameters, Bicycle, Description, Jbike6Parameters};

/// A point (x forward, y up) [m].
pub type Point = [f64; 2];

/// A wheel: a circle standing on the ground.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Wheel {
    /// `rear` or `front`.
    pub name: &'static str,
    /// The hub [m].
    pub centre: Point,
    /// The radius [m] (0 for a skate).
    pub radius: f64,
}

/// The uniform solid ellipsoid with a body's mass and inertia, cut by the side-view plane.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ellipse {
    /// Semi-axes [m], the first along `angle`.
    pub semi_axes: [f64; 2],
    /// Angle of the first semi-axis from x, counter-clockwise (toward up) [rad].
    pub angle: f64,
}

/// A massive body: where its mass is and how it is spread.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Body {
    /// Short name (`rider`, `frame`, `B`, `H`, `rear wheel`, ...).
    pub name: String,
    /// Mass [kg].
    pub mass: f64,
    /// Centre of mass [m].
    pub centre: Point,
    /// The inertia ellipse; null for wheels (drawn as wheels) and bodies without inertia.
    pub ellipse: Option<Ellipse>,
}

/// Everything the side view draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideView {
    /// Wheelbase w [m]: the front contact is at (w, 0).
    pub wheelbase: f64,
    /// Trail c [m]: the steer axis meets the ground at (w + c, 0).
    pub trail: f64,
    /// Steer axis tilt λ from the vertical [rad].
    pub steer_axis_tilt: f64,
    /// The two wheels.
    pub wheels: Vec<Wheel>,
    /// The steer axis, from the ground to above the head tube.
    pub steer_axis: [Point; 2],
    /// The fork, from the front hub to the bottom of the head tube.
    pub fork: [Point; 2],
    /// The head tube on the steer axis.
    pub head_tube: [Point; 2],
    /// Stylized rear-frame tubes as segments (a drawing aid, not parameters).
    pub frame: Vec<[Point; 2]>,
    /// The handlebar, from the top of the head tube back toward the rider.
    pub handlebar: [Point; 2],
    /// The bodies with mass, wheels included.
    pub bodies: Vec<Body>,
    /// Total mass [kg].
    pub total_mass: f64,
    /// The whole bicycle's centre of mass [m].
    pub centre_of_mass: Point,
}

/// Semi-axes of the uniform ellipsoid with in-plane principal moments `i1` (about the first
/// axis) and `i2`, and lateral moment `i3`: a_k² = 5 (I_j + I_3 − I_k) / (2m).
fn ellipse(mass: f64, i1: f64, i2: f64, i3: f64, angle: f64) -> Option<Ellipse> {
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
fn benchmark_ellipse(mass: f64, ixx: f64, iyy: f64, izz: f64, ixz: f64) -> Option<Ellipse> {
    let mean = 0.5 * (ixx + izz);
    let radius = (0.25 * (ixx - izz).powi(2) + ixz * ixz).sqrt();
    // The larger principal moment's axis lies at θ from x toward +z (down), so at −θ with y up.
    let theta = 0.5 * (2.0 * ixz).atan2(ixx - izz);
    ellipse(mass, mean + radius, mean - radius, iyy, -theta)
}

/// The side view of a bicycle whose benchmark parameters are `p` (already validated), with
/// JBike6's separate bodies when it was described in that form.
pub fn side_view(bike: &Bicycle, p: &BenchmarkParameters) -> SideView {
    let (w, c, lambda) = (p.w, p.c, p.lambda);
    let (s, co) = lambda.sin_cos();
    let up = [-s, co];
    let ground = [w + c, 0.0];
    let on_axis = |t: f64| [ground[0] + t * up[0], ground[1] + t * up[1]];
    let rear_hub = [0.0, p.r_r];
    let front_hub = [w, p.r_f];
    // A length scale for the drawing aids, sensible for skates (zero radii) too.
    let scale = w.max(0.2);
    let height_at = |h: f64| if co > 1e-3 { h / co } else { h };
    let head_bottom_t = height_at((2.0 * p.r_f).max(0.55 * scale) + 0.06 * scale);
    let head_top_t = head_bottom_t + 0.17 * scale;
    let head_bottom = on_axis(head_bottom_t);
    let head_top = on_axis(head_top_t);
    let bracket = [0.4 * w, (0.85 * p.r_r).max(0.05 * scale) + 0.02 * scale];
    let seat_angle = 73f64.to_radians();
    let seat_length = ((head_top[1] - bracket[1]) / seat_angle.sin()).max(0.1 * scale);
    let seat = [
        bracket[0] - seat_length * seat_angle.cos(),
        bracket[1] + seat_length * seat_angle.sin(),
    ];
    let frame = vec![
        [rear_hub, bracket],
        [rear_hub, seat],
        [bracket, seat],
        [bracket, head_bottom],
        [seat, head_top],
    ];
    let handlebar = [
        head_top,
        [head_top[0] - 0.12 * scale, head_top[1] + 0.03 * scale],
    ];

    let mut bodies = Vec::new();
    let mut wheel_body = |name: &str, m: f64, centre: Point| {
        if m > 0.0 {
            bodies.push(Body {
                name: name.to_string(),
                mass: m,
                centre,
                ellipse: None,
            });
        }
    };
    wheel_body("rear wheel", p.m_r, rear_hub);
    wheel_body("front wheel", p.m_f, front_hub);
    match &bike.description {
        Description::Jbike6(j) => jbike6_bodies(j, &mut bodies),
        Description::Benchmark(_) => {
            for (name, m, x, z, ixx, iyy, izz, ixz) in [
                (
                    "rear frame B",
                    p.m_b,
                    p.x_b,
                    p.z_b,
                    p.i_bxx,
                    p.i_byy,
                    p.i_bzz,
                    p.i_bxz,
                ),
                (
                    "front frame H",
                    p.m_h,
                    p.x_h,
                    p.z_h,
                    p.i_hxx,
                    p.i_hyy,
                    p.i_hzz,
                    p.i_hxz,
                ),
            ] {
                if m > 0.0 {
                    bodies.push(Body {
                        name: name.to_string(),
                        mass: m,
                        centre: [x, -z],
                        ellipse: benchmark_ellipse(m, ixx, iyy, izz, ixz),
                    });
                }
            }
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
        wheelbase: w,
        trail: c,
        steer_axis_tilt: lambda,
        wheels: vec![
            Wheel {
                name: "rear",
                centre: rear_hub,
                radius: p.r_r,
            },
            Wheel {
                name: "front",
                centre: front_hub,
                radius: p.r_f,
            },
        ],
        steer_axis: [ground, on_axis(head_top_t + 0.12 * scale)],
        fork: [front_hub, head_bottom],
        head_tube: [head_bottom, head_top],
        frame,
        handlebar,
        bodies,
        total_mass,
        centre_of_mass,
    }
}

/// JBike6's five bodies, placed as [`Jbike6Parameters::to_benchmark`] places them.
fn jbike6_bodies(j: &Jbike6Parameters, bodies: &mut Vec<Body>) {
    for (name, b) in [("rider", &j.rider), ("frame", &j.frame), ("rack", &j.rack)] {
        if b.m > 0.0 {
            let [i1, i2, i3] = b.inertia;
            bodies.push(Body {
                name: name.to_string(),
                mass: b.m,
                centre: [b.xcm, b.ycm],
                ellipse: ellipse(b.m, i1, i2, i3, b.alpha),
            });
        }
    }
    let (s, c) = j.steer_axis_tilt().sin_cos();
    let front_point = j.wheelbase + j.trail;
    for (name, b) in [("fork", &j.fork), ("basket", &j.basket)] {
        if b.m > 0.0 {
            let [i1, i2, i3] = b.inertia;
            bodies.push(Body {
                name: name.to_string(),
                mass: b.m,
                centre: [front_point + b.ucm * c - b.vcm * s, b.ucm * s + b.vcm * c],
                ellipse: ellipse(b.m, i1, i2, i3, b.alpha),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use whipple::parameters::presets;

    /// The centre of mass drawn is the one the benchmark parameters imply (masses R, B, H, F).
    #[test]
    fn centre_of_mass_matches_benchmark_parameters() -> Result<(), whipple::Error> {
        for preset in presets::PRESETS {
            let bike = preset.bicycle();
            let p = bike.benchmark()?;
            let view = side_view(&bike, &p);
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
        let (s, co) = theta.sin_cos();
        // Tensor in (x, z) with the first principal axis at −θ from x toward +z.
        let ixx = i1 * co * co + i2 * s * s;
        let izz = i1 * s * s + i2 * co * co;
        let ixz = -(i1 - i2) * s * co;
        let e = benchmark_ellipse(m, ixx, i3, izz, ixz).expect("positive mass");
        let [p, q] = e.semi_axes;
        // The larger moment belongs to the shorter semi-axis along the first direction.
        assert!((p.max(q) - a).abs() < 1e-12 && (p.min(q) - b).abs() < 1e-12);
    }
}
