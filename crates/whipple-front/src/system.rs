//! The linear system's signals as people type them: inputs and outputs by name
//! (`steer_torque`, `lean`, `front_contact_y`), a point of a frame after a colon in metres
//! (`lateral_force:0.3,-1.0`, `rear_frame_point_y:0.5,-1.2`), and logarithmic frequency grids
//! `START:STOP:COUNT`. The names are the library's ([`StateVariable::name`], [`Input::name`],
//! [`Output::name`]); this module only reads them, and asks for the ignorable coordinates an
//! output needs so that nobody has to list them.
//!
//! ```
//! use whipple_front::system::request;
//! let request = request(&["steer_torque"], &["lean", "front_contact_y"])?;
//! // The front contact's lateral position needs yaw and the rear contact's y.
//! assert_eq!(request.states.len(), 2);
//! # Ok::<(), whipple::Error>(())
//! ```

use whipple::advanced::linear::{
    Input, InputSignal, MAX_KNOTS, MAX_SIGNALS, Output, StateVariable, SystemRequest,
};
use whipple::{Error, Result};

/// The most frequencies one grid holds.
pub const MAX_FREQUENCIES: usize = 1_000_000;

/// Every state by name, in the library's order.
const ALL_STATES: [StateVariable; 9] = [
    StateVariable::Lean,
    StateVariable::Steer,
    StateVariable::LeanRate,
    StateVariable::SteerRate,
    StateVariable::Yaw,
    StateVariable::RearContactX,
    StateVariable::RearContactY,
    StateVariable::RearWheelAngle,
    StateVariable::FrontWheelAngle,
];

/// The outputs that are not states and take no point.
const PLAIN_OUTPUTS: [Output; 3] = [
    Output::YawRate,
    Output::FrontContactY,
    Output::RearContactLateralAcceleration,
];

fn invalid(what: &'static str, rule: String) -> Error {
    Error::InvalidArgument { what, rule }
}

/// The names a state may be given, for messages.
pub fn state_names() -> Vec<&'static str> {
    ALL_STATES.iter().map(|s| s.name()).collect()
}

/// The spellings an input may be given, for messages and help texts.
pub fn input_names() -> Vec<&'static str> {
    vec!["lean_torque", "steer_torque", "lateral_force:X,Z"]
}

/// The spellings an output may be given, for messages and help texts.
pub fn output_names() -> Vec<&'static str> {
    let mut names = state_names();
    names.extend(PLAIN_OUTPUTS.iter().map(|o| o.name()));
    names.extend(["rear_frame_point_y:X,Z", "front_frame_point_y:X,Z"]);
    // An input as an output: the torque or force applied (in a closed loop, r − K x).
    names.extend(input_names());
    names
}

/// A state by its name (`lean`, `yaw`, `rear_contact_y`).
pub fn parse_state(name: &str) -> Result<StateVariable> {
    let name = name.trim();
    ALL_STATES
        .iter()
        .copied()
        .find(|s| s.name() == name)
        .ok_or_else(|| {
            invalid(
                "states",
                format!(
                    "unknown state {name:?}; known: {}",
                    state_names().join(", ")
                ),
            )
        })
}

/// A name and, after a colon, the point `X,Z` in metres (benchmark axes, z down, so a point
/// above the ground has a negative z).
fn split_point(spec: &str, what: &'static str) -> Result<(String, Option<(f64, f64)>)> {
    let Some((name, point)) = spec.split_once(':') else {
        return Ok((spec.trim().to_string(), None));
    };
    let name = name.trim();
    let coordinates: Vec<&str> = point.split(',').map(str::trim).collect();
    let [x, z] = coordinates[..] else {
        return Err(invalid(
            what,
            format!(
                "{spec:?}: give the point as {name}:X,Z in metres (z down, negative above the \
                 ground), e.g. {name}:0.3,-1.0"
            ),
        ));
    };
    let number = |text: &str, axis: &str| -> Result<f64> {
        match text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value),
            _ => Err(invalid(
                what,
                format!("{spec:?}: {axis} = {text:?} is not a finite number of metres"),
            )),
        }
    };
    Ok((name.to_string(), Some((number(x, "X")?, number(z, "Z")?))))
}

/// An input as typed: `lean_torque`, `steer_torque` or `lateral_force:X,Z` (the point of the
/// rear frame, in metres, where the force pushes to the right).
pub fn parse_input(spec: &str) -> Result<Input> {
    let (name, point) = split_point(spec, "inputs")?;
    let unknown = || {
        invalid(
            "inputs",
            format!(
                "unknown input {spec:?}; known: {}",
                input_names().join(", ")
            ),
        )
    };
    match (name.as_str(), point) {
        ("lean_torque", None) => Ok(Input::LeanTorque),
        ("steer_torque", None) => Ok(Input::SteerTorque),
        ("lateral_force", Some((x, z))) => Ok(Input::LateralForce { x, z }),
        ("lateral_force", None) => Err(invalid(
            "inputs",
            "lateral_force needs the point it pushes at: lateral_force:X,Z in metres (z down), \
             e.g. lateral_force:0.3,-1.0"
                .into(),
        )),
        ("lean_torque" | "steer_torque", Some(_)) => Err(invalid(
            "inputs",
            format!("{spec:?}: a torque takes no point"),
        )),
        _ => Err(unknown()),
    }
}

/// An output as typed: a state's name, `yaw_rate`, `front_contact_y`,
/// `rear_contact_lateral_acceleration`, or the lateral position of a point of a frame,
/// `rear_frame_point_y:X,Z` or `front_frame_point_y:X,Z` (metres, z down), or an input's
/// name (`steer_torque`, …): the torque or force applied, which in a closed loop u = r − K x
/// is the controller's (the input must be among the inputs too).
pub fn parse_output(spec: &str) -> Result<Output> {
    let (name, point) = split_point(spec, "outputs")?;
    if matches!(
        name.as_str(),
        "lean_torque" | "steer_torque" | "lateral_force"
    ) {
        return parse_input(spec).map(Output::Input).map_err(|e| match e {
            Error::InvalidArgument { rule, .. } => invalid("outputs", rule),
            other => other,
        });
    }
    if let Some((x, z)) = point {
        return match name.as_str() {
            "rear_frame_point_y" => Ok(Output::RearFramePointY { x, z }),
            "front_frame_point_y" => Ok(Output::FrontFramePointY { x, z }),
            _ => Err(invalid(
                "outputs",
                format!(
                    "{spec:?}: only rear_frame_point_y and front_frame_point_y take a point; \
                     known outputs: {}",
                    output_names().join(", ")
                ),
            )),
        };
    }
    if let Some(state) = ALL_STATES.iter().find(|s| s.name() == name) {
        return Ok(Output::State(*state));
    }
    if let Some(output) = PLAIN_OUTPUTS.iter().find(|o| o.name() == name) {
        return Ok(*output);
    }
    if name == "rear_frame_point_y" || name == "front_frame_point_y" {
        return Err(invalid(
            "outputs",
            format!("{name} needs its point: {name}:X,Z in metres (z down), e.g. {name}:0.5,-1.2"),
        ));
    }
    Err(invalid(
        "outputs",
        format!(
            "unknown output {spec:?}; known: {}",
            output_names().join(", ")
        ),
    ))
}

/// The ignorable coordinates an output needs among the states.
fn needed_states(output: &Output) -> &'static [StateVariable] {
    match output {
        Output::State(StateVariable::RearContactY) => {
            &[StateVariable::Yaw, StateVariable::RearContactY]
        }
        Output::State(StateVariable::Yaw) => &[StateVariable::Yaw],
        Output::State(StateVariable::RearContactX) => &[StateVariable::RearContactX],
        Output::State(StateVariable::RearWheelAngle) => &[StateVariable::RearWheelAngle],
        Output::State(StateVariable::FrontWheelAngle) => &[StateVariable::FrontWheelAngle],
        Output::FrontContactY
        | Output::RearFramePointY { .. }
        | Output::FrontFramePointY { .. } => &[StateVariable::Yaw, StateVariable::RearContactY],
        _ => &[],
    }
}

/// A request from typed inputs and outputs, with the ignorable coordinates the outputs need
/// added as states in the library's order (ψ, x, y, θ_R, θ_F).
pub fn request(inputs: &[&str], outputs: &[&str]) -> Result<SystemRequest> {
    request_with_states(inputs, outputs, &[])
}

/// As [`request`], with more ignorable coordinates asked for by name (`yaw`, `rear_contact_x`,
/// …; the plane's path is `yaw`, `rear_contact_x`, `rear_contact_y`).
pub fn request_with_states(
    inputs: &[&str],
    outputs: &[&str],
    states: &[&str],
) -> Result<SystemRequest> {
    for (what, count) in [("inputs", inputs.len()), ("outputs", outputs.len())] {
        if count > MAX_SIGNALS {
            return Err(Error::LimitExceeded {
                what,
                rule: format!("at most {MAX_SIGNALS} can be asked for, got {count}"),
            });
        }
    }
    if states.len() > ALL_STATES.len() {
        return Err(Error::LimitExceeded {
            what: "states",
            rule: format!(
                "at most {} states exist, got {}",
                ALL_STATES.len(),
                states.len()
            ),
        });
    }
    let inputs = inputs
        .iter()
        .map(|s| parse_input(s))
        .collect::<Result<Vec<_>>>()?;
    let outputs = outputs
        .iter()
        .map(|s| parse_output(s))
        .collect::<Result<Vec<_>>>()?;
    let mut wanted = Vec::new();
    for name in states {
        let state = parse_state(name)?;
        if !StateVariable::LEAN_STEER.contains(&state) {
            wanted.push(state);
        }
        if state == StateVariable::RearContactY {
            wanted.push(StateVariable::Yaw);
        }
    }
    for output in &outputs {
        wanted.extend_from_slice(needed_states(output));
    }
    let states = StateVariable::IGNORABLE
        .iter()
        .copied()
        .filter(|s| wanted.contains(s))
        .collect();
    Ok(SystemRequest {
        states,
        inputs,
        outputs,
    })
}

/// `count` frequencies spaced evenly in logarithm from `start` to `stop` (both included),
/// checked: positive and finite ends, `start < stop` (or equal with one point), and
/// 1 ≤ `count` ≤ [`MAX_FREQUENCIES`]. The unit is the caller's (rad/s in the library).
pub fn log_grid(start: f64, stop: f64, count: usize) -> Result<Vec<f64>> {
    let what = "frequencies";
    if !(start.is_finite() && stop.is_finite() && start > 0.0 && stop > 0.0) {
        return Err(invalid(
            what,
            format!(
                "the ends must be positive finite frequencies (a logarithmic grid), got {start} \
                 and {stop}"
            ),
        ));
    }
    if count == 0 || count > MAX_FREQUENCIES {
        return Err(Error::LimitExceeded {
            what,
            rule: format!("the count must be 1 to {MAX_FREQUENCIES}, got {count}"),
        });
    }
    if count == 1 {
        return if start == stop {
            Ok(vec![start])
        } else {
            Err(invalid(
                what,
                format!("one frequency needs START = STOP, got {start} and {stop}"),
            ))
        };
    }
    if start >= stop {
        return Err(invalid(
            what,
            format!("START must be below STOP, got {start} and {stop}"),
        ));
    }
    let (a, b) = (whipple::math::ln(start), whipple::math::ln(stop));
    let last = (count - 1) as f64;
    Ok((0..count)
        .map(|k| match k {
            0 => start,
            _ if k == count - 1 => stop,
            _ => whipple::math::exp(a + (b - a) * k as f64 / last),
        })
        .collect())
}

/// A frequency grid as typed, `START:STOP:COUNT` (logarithmic; the unit is the caller's).
pub fn parse_log_grid(spec: &str) -> Result<Vec<f64>> {
    let parts: Vec<&str> = spec.split(':').map(str::trim).collect();
    let [start, stop, count] = parts[..] else {
        return Err(invalid(
            "frequencies",
            format!("{spec:?}: give START:STOP:COUNT, e.g. 0.1:100:500"),
        ));
    };
    let number = |text: &str| text.parse::<f64>().ok().filter(|x| x.is_finite());
    let (Some(start), Some(stop)) = (number(start), number(stop)) else {
        return Err(invalid(
            "frequencies",
            format!("{spec:?}: START and STOP must be finite numbers"),
        ));
    };
    let Ok(count) = count.parse::<usize>() else {
        return Err(invalid(
            "frequencies",
            format!("{spec:?}: COUNT must be a whole number, got {count:?}"),
        ));
    };
    log_grid(start, stop, count)
}

/// An input signal of time as typed (seconds and the input's SI unit):
///
/// - `step:T:A`: zero before T, A from T on;
/// - `pulse:T:D:A`: A from T for D seconds, zero before and after;
/// - `linear:T1=U1,T2=U2,…`: piecewise linear through the points (a time given twice is a jump),
///   constant before the first and after the last;
/// - `constant:T1=U1,T2=U2,…`: U1 from T1 on, U2 from T2 on, … (piecewise constant).
///
/// `what` names the option or field in messages.
pub fn parse_signal(spec: &str, what: &'static str) -> Result<InputSignal> {
    let spec = spec.trim();
    let usage = || {
        invalid(
            what,
            format!(
                "{spec:?}: give step:T:A, pulse:T:D:A, linear:T1=U1,T2=U2,… or \
                 constant:T1=U1,T2=U2,… (seconds; the input's unit)"
            ),
        )
    };
    let (kind, rest) = spec.split_once(':').ok_or_else(usage)?;
    let number = |text: &str| -> Result<f64> {
        text.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| invalid(what, format!("{spec:?}: {text:?} is not a finite number")))
    };
    // The library's errors name its own fields (`knots`, `duration`): say which option it was.
    let named =
        |result: Result<InputSignal>| result.map_err(|e| invalid(what, format!("{spec:?}: {e}")));
    match kind.trim() {
        "step" => {
            let parts: Vec<&str> = rest.split(':').collect();
            let [t, a] = parts[..] else {
                return Err(usage());
            };
            named(InputSignal::step(number(t)?, number(a)?))
        }
        "pulse" => {
            let parts: Vec<&str> = rest.split(':').collect();
            let [t, d, a] = parts[..] else {
                return Err(usage());
            };
            named(InputSignal::pulse(number(t)?, number(d)?, number(a)?))
        }
        "linear" | "constant" => {
            let points: Vec<&str> = rest.split(',').collect();
            if points.len() > MAX_KNOTS {
                return Err(Error::LimitExceeded {
                    what,
                    rule: format!("at most {MAX_KNOTS} points, got {}", points.len()),
                });
            }
            let mut knots = Vec::with_capacity(points.len());
            let mut values = Vec::with_capacity(points.len());
            for point in points {
                let (t, u) = point.split_once('=').ok_or_else(usage)?;
                knots.push(number(t)?);
                values.push(number(u)?);
            }
            named(if kind.trim() == "linear" {
                InputSignal::piecewise_linear(knots, values)
            } else {
                InputSignal::piecewise_constant(knots, values)
            })
        }
        _ => Err(usage()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_the_library_gives_reads_back() {
        for state in ALL_STATES {
            assert_eq!(parse_state(state.name()).unwrap(), state);
            assert_eq!(parse_output(state.name()).unwrap(), Output::State(state));
        }
        for output in PLAIN_OUTPUTS {
            assert_eq!(parse_output(output.name()).unwrap(), output);
        }
        assert_eq!(parse_input("steer_torque").unwrap(), Input::SteerTorque);
        assert_eq!(parse_input(" lean_torque ").unwrap(), Input::LeanTorque);
        assert_eq!(
            parse_input("lateral_force:0.3, -1.0").unwrap(),
            Input::LateralForce { x: 0.3, z: -1.0 }
        );
        assert_eq!(
            parse_output("front_frame_point_y:1.1,-0.9").unwrap(),
            Output::FrontFramePointY { x: 1.1, z: -0.9 }
        );
        // An input as an output, the torque or force applied.
        assert_eq!(
            parse_output("steer_torque").unwrap(),
            Output::Input(Input::SteerTorque)
        );
        assert_eq!(
            parse_output("lateral_force:0.3,-1").unwrap(),
            Output::Input(Input::LateralForce { x: 0.3, z: -1.0 })
        );
        let e = parse_output("lateral_force").unwrap_err();
        assert!(
            matches!(&e, Error::InvalidArgument { what: "outputs", rule } if rule.contains("X,Z")),
            "{e:?}"
        );
        assert!(output_names().contains(&"steer_torque"));
    }

    #[test]
    fn the_states_outputs_need_are_added_in_order() {
        let r = request(&["steer_torque"], &["front_contact_y", "lean"]).unwrap();
        assert_eq!(
            r.states,
            [StateVariable::Yaw, StateVariable::RearContactY],
            "yaw before y"
        );
        let r = request_with_states(
            &["lean_torque"],
            &["lean"],
            &["rear_contact_y", "rear_contact_x", "lean"],
        )
        .unwrap();
        assert_eq!(
            r.states,
            [
                StateVariable::Yaw,
                StateVariable::RearContactX,
                StateVariable::RearContactY
            ]
        );
        let r = request(&[], &["rear_wheel_angle"]).unwrap();
        assert_eq!(r.states, [StateVariable::RearWheelAngle]);
        // What the library checks, the library checks: duplicates stay its error.
        let r = request(&["steer_torque", "steer_torque"], &["lean"]).unwrap();
        let system = whipple::advanced::linear::LinearSystem::new(
            &whipple::BenchmarkParameters::meijaard2007(),
            5.0,
            &r,
        );
        assert!(system.unwrap_err().to_string().contains("listed twice"));
    }

    #[test]
    fn bad_names_and_points_name_the_field_and_the_spelling() {
        let message = |e: Error| e.to_string();
        let e = message(parse_input("steer").unwrap_err());
        assert!(e.contains("inputs") && e.contains("steer_torque"), "{e}");
        let e = message(parse_input("lateral_force").unwrap_err());
        assert!(e.contains("lateral_force:X,Z"), "{e}");
        let e = message(parse_input("lateral_force:0.3").unwrap_err());
        assert!(e.contains("X,Z"), "{e}");
        let e = message(parse_input("lateral_force:0.3,nan").unwrap_err());
        assert!(e.contains("Z") && e.contains("finite"), "{e}");
        let e = message(parse_input("steer_torque:1,2").unwrap_err());
        assert!(e.contains("no point"), "{e}");
        let e = message(parse_output("lean:1,2").unwrap_err());
        assert!(e.contains("only rear_frame_point_y"), "{e}");
        let e = message(parse_output("rear_frame_point_y").unwrap_err());
        assert!(e.contains("needs its point"), "{e}");
        let e = message(parse_output("heading").unwrap_err());
        assert!(e.contains("outputs") && e.contains("yaw_rate"), "{e}");
        let e = message(parse_state("phi").unwrap_err());
        assert!(e.contains("states") && e.contains("lean"), "{e}");
        let many = vec!["lean"; MAX_SIGNALS + 1];
        assert!(matches!(
            request(&[], &many),
            Err(Error::LimitExceeded {
                what: "outputs",
                ..
            })
        ));
    }

    #[test]
    fn signals_read_as_the_library_builds_them() {
        assert_eq!(
            parse_signal("pulse:0:0.5:1", "x").unwrap(),
            InputSignal::pulse(0.0, 0.5, 1.0).unwrap()
        );
        assert_eq!(
            parse_signal(" step:1:-2 ", "x").unwrap(),
            InputSignal::step(1.0, -2.0).unwrap()
        );
        let ramp = parse_signal("linear:0=0,1=2,3=2", "x").unwrap();
        assert_eq!(
            (ramp.value(0.5), ramp.value(2.0), ramp.value(9.0)),
            (1.0, 2.0, 2.0)
        );
        let stairs = parse_signal("constant:0=1,2=3", "x").unwrap();
        assert_eq!((stairs.value(1.9), stairs.value(2.0)), (1.0, 3.0));
        for bad in [
            "pulse:0:0:1",
            "pulse:0:1",
            "step:1",
            "linear:1=0,0=1",
            "linear:0=x",
            "ramp:0:1",
            "pulse:0:inf:1",
            "",
        ] {
            let e = parse_signal(bad, "--steer-torque").unwrap_err().to_string();
            assert!(e.contains("--steer-torque"), "{bad}: {e}");
        }
    }

    #[test]
    fn logarithmic_grids_hold_their_ends_and_refuse_bad_ones() {
        let grid = parse_log_grid("0.1:100:4").unwrap();
        assert_eq!(grid.len(), 4);
        assert_eq!((grid[0], grid[3]), (0.1, 100.0));
        assert!((grid[1] - 1.0).abs() < 1e-14 && (grid[2] - 10.0).abs() < 1e-13);
        assert_eq!(parse_log_grid("2:2:1").unwrap(), [2.0]);
        for bad in [
            "0:10:5",
            "-1:10:5",
            "10:1:5",
            "1:10:0",
            "1:10",
            "1:inf:3",
            "1:10:x",
            "1:2:1",
            "1:10:2000000",
        ] {
            let e = parse_log_grid(bad).unwrap_err().to_string();
            assert!(e.contains("frequencies"), "{bad}: {e}");
        }
    }
}
