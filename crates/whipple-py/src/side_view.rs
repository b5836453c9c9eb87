//! The library's side view (`whipple::advanced::side_view`: wheels, steer axis, trail, stylized frame
//! tubes, each body's centre of mass and inertia ellipse) as a dict for the Python figure.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use whipple::advanced::side_view::{Part, side_view};

use crate::bicycle::NativeBicycle;

fn part_name(part: Part) -> &'static str {
    match part {
        Part::RearWheel => "rear_wheel",
        Part::FrontWheel => "front_wheel",
        Part::RearFrame => "rear_frame",
        Part::FrontFrame => "front_frame",
        Part::Rider => "rider",
        Part::Frame => "frame",
        Part::Rack => "rack",
        Part::Fork => "fork",
        Part::Basket => "basket",
    }
}

#[pymethods]
impl NativeBicycle {
    /// The side view's geometry (x forward from the rear contact, y up, metres): every point of
    /// `whipple::advanced::side_view::SideView`, `frame_tubes` (six segments) and `bodies` (dicts: part,
    /// name, mass, centre, ellipse (semi_axes, angle) or None, is_wheel, is_front).
    fn side_view<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let v = side_view(&self.checked.benchmark, self.bicycle.jbike6());
        let d = PyDict::new(py);
        let pt = |p: [f64; 2]| (p[0], p[1]);
        d.set_item("wheelbase", v.wheelbase)?;
        d.set_item("trail", v.trail)?;
        d.set_item("steer_axis_tilt", v.steer_axis_tilt)?;
        d.set_item("rear_wheel_radius", v.rear_wheel_radius)?;
        d.set_item("front_wheel_radius", v.front_wheel_radius)?;
        for (name, p) in [
            ("rear_hub", v.rear_hub),
            ("front_hub", v.front_hub),
            ("ground_point", v.ground_point),
            ("up", v.up),
            ("crown", v.crown),
            ("head_top", v.head_top),
            ("bar", v.bar),
            ("grip", v.grip),
            ("bottom_bracket", v.bottom_bracket),
            ("seat_cluster", v.seat_cluster),
            ("saddle", v.saddle),
            ("centre_of_mass", v.centre_of_mass),
        ] {
            d.set_item(name, pt(p))?;
        }
        d.set_item("steer_axis", (pt(v.steer_axis[0]), pt(v.steer_axis[1])))?;
        d.set_item("total_mass", v.total_mass)?;
        let tubes: Vec<((f64, f64), (f64, f64))> = v
            .frame_tubes()
            .iter()
            .map(|[a, b]| (pt(*a), pt(*b)))
            .collect();
        d.set_item("frame_tubes", tubes)?;
        let bodies = PyList::empty(py);
        for b in &v.bodies {
            let bd = PyDict::new(py);
            bd.set_item("part", part_name(b.part))?;
            bd.set_item("name", b.name)?;
            bd.set_item("mass", b.mass)?;
            bd.set_item("centre", pt(b.centre))?;
            bd.set_item(
                "ellipse",
                b.ellipse
                    .map(|e| ((e.semi_axes[0], e.semi_axes[1]), e.angle)),
            )?;
            bd.set_item("is_wheel", b.part.is_wheel())?;
            bd.set_item("is_front", b.part.is_front())?;
            bodies.append(bd)?;
        }
        d.set_item("bodies", bodies)?;
        Ok(d)
    }
}
