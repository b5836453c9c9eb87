//! JBike6's stylized side view, as geometry for the page to draw: the library's
//! [`whipple::advanced::side_view`] (wheels, steer axis, fork, frame tubes, each body's centre of mass
//! with its inertia ellipse) in the shape the page reads.
//!
//! Coordinates: metres, x forward from the rear wheel's contact, y up (JBike6's side view;
//! the benchmark's z points down, so y = −z).

use serde::Serialize;
pub use whipple::advanced::side_view::{Ellipse, Point};
use whipple::{BenchmarkParameters, Bicycle};

/// A wheel: a circle standing on the ground.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Wheel {
    /// `rear` or `front`.
    pub name: &'static str,
    /// The hub \[m\].
    pub centre: Point,
    /// The radius \[m\] (0 for a skate).
    pub radius: f64,
}

/// A massive body: where its mass is and how it is spread.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Body {
    /// Short name (`rider`, `frame`, `rear frame B`, `front frame H`, `rear wheel`, ...).
    pub name: String,
    /// Mass \[kg\].
    pub mass: f64,
    /// Centre of mass \[m\].
    pub centre: Point,
    /// The inertia ellipse; null for wheels (drawn as wheels) and bodies without inertia.
    pub ellipse: Option<Ellipse>,
}

/// Everything the side view draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideView {
    /// Wheelbase w \[m\]: the front contact is at (w, 0).
    pub wheelbase: f64,
    /// Trail c \[m\]: the steer axis meets the ground at (w + c, 0).
    pub trail: f64,
    /// Steer axis tilt λ from the vertical \[rad\].
    pub steer_axis_tilt: f64,
    /// The two wheels.
    pub wheels: Vec<Wheel>,
    /// The steer axis, from the ground to above the handlebar.
    pub steer_axis: [Point; 2],
    /// The fork, from the front hub to the crown.
    pub fork: [Point; 2],
    /// The head tube and stem on the steer axis, from the crown to the handlebar.
    pub head_tube: [Point; 2],
    /// Stylized rear-frame tubes as segments (a drawing aid, not parameters): chain stay, seat
    /// tube, seat stay, top tube, down tube, seat post.
    pub frame: Vec<[Point; 2]>,
    /// The handlebar, from the top of the stem back toward the rider.
    pub handlebar: [Point; 2],
    /// The bodies with mass, wheels included.
    pub bodies: Vec<Body>,
    /// Total mass \[kg\].
    pub total_mass: f64,
    /// The whole bicycle's centre of mass \[m\].
    pub centre_of_mass: Point,
}

/// The side view of a bicycle whose benchmark parameters are `p` (already validated), with
/// JBike6's separate bodies when it was described in that form.
pub fn side_view(bike: &Bicycle, p: &BenchmarkParameters) -> SideView {
    let v = whipple::advanced::side_view::side_view(p, bike.jbike6());
    SideView {
        wheelbase: v.wheelbase,
        trail: v.trail,
        steer_axis_tilt: v.steer_axis_tilt,
        wheels: vec![
            Wheel {
                name: "rear",
                centre: v.rear_hub,
                radius: v.rear_wheel_radius,
            },
            Wheel {
                name: "front",
                centre: v.front_hub,
                radius: v.front_wheel_radius,
            },
        ],
        steer_axis: v.steer_axis,
        fork: [v.front_hub, v.crown],
        head_tube: [v.crown, v.bar],
        frame: v.frame_tubes().to_vec(),
        handlebar: [v.bar, v.grip],
        bodies: v
            .bodies
            .iter()
            .filter(|b| b.mass > 0.0)
            .map(|b| Body {
                name: b.name.to_string(),
                mass: b.mass,
                centre: b.centre,
                ellipse: b.ellipse,
            })
            .collect(),
        total_mass: v.total_mass,
        centre_of_mass: v.centre_of_mass,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use whipple::presets;

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

    /// The page and the report draw the same bicycle: every point the page gets is one of the
    /// library's.
    #[test]
    fn the_page_draws_the_library_geometry() -> Result<(), whipple::Error> {
        let bike = presets::find("schwinn-crown")?.bicycle();
        let p = bike.benchmark()?;
        let v = whipple::advanced::side_view::side_view(&p, bike.jbike6());
        let page = side_view(&bike, &p);
        assert_eq!(page.fork, [v.front_hub, v.crown]);
        assert_eq!(page.steer_axis, v.steer_axis);
        assert!(page.frame.iter().any(|s| s.contains(&v.bottom_bracket)));
        assert_eq!(page.bodies.len(), v.bodies.len());
        Ok(())
    }
}
