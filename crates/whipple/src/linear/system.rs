//! The linearized bicycle as a linear system with named states, inputs and outputs:
//! ẋ = A x + B u, y = C x + D u, about upright straight running at a forward speed v.
//!
//! # States
//!
//! Always lean φ, steer δ, lean rate φ̇ and steer rate δ̇ (Meijaard 2007's x, in that order),
//! then, on request, the ignorable coordinates: yaw ψ, the rear contact's x and y, and the
//! wheels' rotation angles θ_R, θ_F. Nothing in the dynamics depends on them (the bicycle is
//! the same wherever it is, whichever way it heads and however far its wheels have turned), so
//! they add rows to A but no columns to the lean–steer block.
//!
//! # Their kinematics, to first order about upright straight running
//!
//! Benchmark axes: x forward, y right, z down; lean right and steer right positive; ψ about z,
//! so a turn to the right is positive.
//!
//! - **Front contact.** Steer δ turns the front frame about the steer axis, whose downward unit
//!   vector is ŝ = (sin λ, 0, cos λ) and which meets the ground at (w + c, 0, 0), the trail c
//!   ahead of the front contact. A point p of the front frame moves by δ ŝ × (p − (w + c, 0, 0)),
//!   whose y part is δ [(x − w − c) cos λ − z sin λ]; for the front contact (x = w, z = 0) that
//!   is −c δ cos λ. Lean rotates the whole bicycle about the ground line (the x axis), moving a
//!   point at height −z right by −z φ; the front contact, the lowest point of the wheel, stays
//!   on the ground line (its hub moves right by r_F φ, the contact back by r_F φ within the
//!   leaned wheel's plane). Yaw turns the bicycle about the rear contact. So the front contact
//!   is at y_F = y + w ψ − c δ cos λ.
//! - **Yaw.** Neither wheel slides sideways: the rear contact moves along the heading ψ, so
//!   ẏ = v ψ; the front contact along the front wheel's heading, which steer turns by δ cos λ
//!   (to first order), so ẏ_F = v (ψ + δ cos λ). Differentiating y_F and subtracting:
//!   w ψ̇ − c δ̇ cos λ = v δ cos λ, that is **ψ̇ = (v δ + c δ̇) cos λ / w**.
//! - **Rear contact.** **ẏ = v ψ**; ẋ = v cos ψ = v + O(ψ²). Its lateral acceleration is
//!   ÿ = v ψ̇ = v (v δ + c δ̇) cos λ / w.
//! - **Wheels.** Rolling without slip, θ̇_R = −v / r_R and θ̇_F = −v / r_F + O(x²) (a wheel
//!   rolling forward turns negatively about the y axis, as in Meijaard 2007).
//!
//! The states x_P, θ_R and θ_F are therefore *deviations from the nominal run*
//! (x_P − v t, θ_R + v t / r_R, θ_F + v t / r_F): their rows of A are zero, and
//! [`LinearSystem::nominal_rates`] gives the constant rates to add back. Every row above, and
//! the nominal rates, are checked in the tests against the exact linearization (hyper-dual
//! numbers) of the non-linear multibody model, to 1e-12; the lateral acceleration as the
//! derivative of ẏ along ẋ = A x + B u.
//!
//! # Inputs
//!
//! Lean torque T_φ and steer torque T_δ (the generalized forces of Meijaard 2007), and a
//! lateral force F (along +y) at a point of the rear frame that is at (x, z) when upright (the
//! push of Schwab's and Moore's perturbation experiments). Its generalized forces are its
//! virtual work per virtual displacement of φ and δ, the virtual displacements obeying the
//! constraints. The point is at y + x ψ − z φ; the rolling constraints in virtual form are
//! δy = 0 (at ψ = 0) and δψ = (c cos λ / w) δδ (the rear frame yaws about the rear contact so
//! that the front contact does not slide when the bicycle is steered, the term in the rolling
//! displacement being multiplied by δ = 0). So F does the virtual work
//! F (−z δφ + x (c cos λ / w) δδ), and
//!
//! f = F [−z, x c cos λ / w]ᵀ, so the column of B is [0; M⁻¹ f] per newton.
//!
//! # Outputs
//!
//! Any state, the yaw rate, the front contact's lateral position, the lateral position of a
//! point of the rear frame (y + x ψ − z φ) or of the front frame
//! (y + x ψ − z φ + [(x − w − c) cos λ − z sin λ] δ), and the rear contact's lateral
//! acceleration. A lateral position needs the states ψ and y; D is zero for all of them (none
//! depends on the inputs directly) and is kept for outputs that will (a rider model's torque).

use nalgebra::{DMatrix, Matrix2};

use super::state_space::{STEER, STEER_RATE};
use super::{Canonical, StateSpace};
use crate::error::{Error, Result, short_number};
use crate::parameters::BenchmarkParameters;

/// A state of a [`LinearSystem`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum StateVariable {
    /// φ: lean \[rad\].
    Lean,
    /// δ: steer \[rad\].
    Steer,
    /// φ̇: lean rate [rad/s].
    LeanRate,
    /// δ̇: steer rate [rad/s].
    SteerRate,
    /// ψ: yaw (heading), right positive \[rad\].
    Yaw,
    /// x_P − v t: the rear contact's forward position, less the nominal run's \[m\].
    RearContactX,
    /// y: the rear contact's lateral position, right positive \[m\].
    RearContactY,
    /// θ_R + v t / r_R: the rear wheel's rotation angle, less the nominal run's \[rad\].
    RearWheelAngle,
    /// θ_F + v t / r_F: the front wheel's rotation angle, less the nominal run's \[rad\].
    FrontWheelAngle,
}

impl StateVariable {
    /// The four states every system has, in this order.
    pub const LEAN_STEER: [StateVariable; 4] = [
        StateVariable::Lean,
        StateVariable::Steer,
        StateVariable::LeanRate,
        StateVariable::SteerRate,
    ];

    /// The ignorable coordinates a request may add.
    pub const IGNORABLE: [StateVariable; 5] = [
        StateVariable::Yaw,
        StateVariable::RearContactX,
        StateVariable::RearContactY,
        StateVariable::RearWheelAngle,
        StateVariable::FrontWheelAngle,
    ];

    /// The name in snake case (`lean`, `rear_contact_y`, …), as files and the front ends spell it.
    pub fn name(self) -> &'static str {
        match self {
            StateVariable::Lean => "lean",
            StateVariable::Steer => "steer",
            StateVariable::LeanRate => "lean_rate",
            StateVariable::SteerRate => "steer_rate",
            StateVariable::Yaw => "yaw",
            StateVariable::RearContactX => "rear_contact_x",
            StateVariable::RearContactY => "rear_contact_y",
            StateVariable::RearWheelAngle => "rear_wheel_angle",
            StateVariable::FrontWheelAngle => "front_wheel_angle",
        }
    }

    /// The symbol (Meijaard 2007's where it has one).
    pub fn symbol(self) -> &'static str {
        match self {
            StateVariable::Lean => "φ",
            StateVariable::Steer => "δ",
            StateVariable::LeanRate => "φ̇",
            StateVariable::SteerRate => "δ̇",
            StateVariable::Yaw => "ψ",
            StateVariable::RearContactX => "x_P",
            StateVariable::RearContactY => "y_P",
            StateVariable::RearWheelAngle => "θ_R",
            StateVariable::FrontWheelAngle => "θ_F",
        }
    }

    /// The SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            StateVariable::LeanRate | StateVariable::SteerRate => "rad/s",
            StateVariable::RearContactX | StateVariable::RearContactY => "m",
            _ => "rad",
        }
    }
}

impl std::fmt::Display for StateVariable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// An input of a [`LinearSystem`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Input {
    /// T_φ: lean torque [N m].
    LeanTorque,
    /// T_δ: steer torque [N m].
    SteerTorque,
    /// F: a lateral force, right positive, at the point of the rear frame that is at (x, z)
    /// when upright (benchmark axes from the rear contact, z down) \[N\].
    LateralForce {
        /// x of the point \[m\].
        x: f64,
        /// z of the point, negative above the ground \[m\].
        z: f64,
    },
}

impl Input {
    /// The name in snake case (`steer_torque`, `lateral_force`).
    pub fn name(&self) -> &'static str {
        match self {
            Input::LeanTorque => "lean_torque",
            Input::SteerTorque => "steer_torque",
            Input::LateralForce { .. } => "lateral_force",
        }
    }

    /// The symbol.
    pub fn symbol(&self) -> &'static str {
        match self {
            Input::LeanTorque => "T_φ",
            Input::SteerTorque => "T_δ",
            Input::LateralForce { .. } => "F",
        }
    }

    /// The SI unit.
    pub fn unit(&self) -> &'static str {
        match self {
            Input::LateralForce { .. } => "N",
            _ => "N m",
        }
    }
}

impl std::fmt::Display for Input {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Input::LateralForce { x, z } => write!(
                f,
                "lateral_force(x = {} m, z = {} m)",
                short_number(*x),
                short_number(*z)
            ),
            other => f.write_str(other.name()),
        }
    }
}

/// An output of a [`LinearSystem`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Output {
    /// One of the states (which the request must include).
    State(StateVariable),
    /// ψ̇: yaw rate [rad/s].
    YawRate,
    /// y_F: the front contact's lateral position \[m\] (needs ψ and y).
    FrontContactY,
    /// The lateral position of the point of the rear frame that is at (x, z) when upright \[m\]
    /// (needs ψ and y).
    RearFramePointY {
        /// x of the point \[m\].
        x: f64,
        /// z of the point, negative above the ground \[m\].
        z: f64,
    },
    /// The lateral position of the point of the front frame (fork and handlebar) that is at
    /// (x, z) when upright \[m\] (needs ψ and y).
    FrontFramePointY {
        /// x of the point \[m\].
        x: f64,
        /// z of the point, negative above the ground \[m\].
        z: f64,
    },
    /// ÿ: the rear contact's lateral acceleration [m/s²].
    RearContactLateralAcceleration,
    /// One of the system's inputs as applied: u itself in the open loop (D's row), and in a
    /// closed loop u = r − K x, the torque or force the controller applies ("steer torque in
    /// the loop"). The request must list the input among its inputs.
    Input(Input),
}

impl Output {
    /// The name in snake case (`lean`, `yaw_rate`, `front_contact_y`, …).
    pub fn name(&self) -> &'static str {
        match self {
            Output::State(s) => s.name(),
            Output::YawRate => "yaw_rate",
            Output::FrontContactY => "front_contact_y",
            Output::RearFramePointY { .. } => "rear_frame_point_y",
            Output::FrontFramePointY { .. } => "front_frame_point_y",
            Output::RearContactLateralAcceleration => "rear_contact_lateral_acceleration",
            Output::Input(input) => input.name(),
        }
    }

    /// The symbol.
    pub fn symbol(&self) -> &'static str {
        match self {
            Output::State(s) => s.symbol(),
            Output::YawRate => "ψ̇",
            Output::FrontContactY => "y_F",
            Output::RearFramePointY { .. } | Output::FrontFramePointY { .. } => "y",
            Output::RearContactLateralAcceleration => "ÿ_P",
            Output::Input(input) => input.symbol(),
        }
    }

    /// The SI unit.
    pub fn unit(&self) -> &'static str {
        match self {
            Output::State(s) => s.unit(),
            Output::YawRate => "rad/s",
            Output::RearContactLateralAcceleration => "m/s²",
            Output::Input(input) => input.unit(),
            _ => "m",
        }
    }
}

impl std::fmt::Display for Output {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Output::RearFramePointY { x, z } | Output::FrontFramePointY { x, z } => write!(
                f,
                "{}(x = {} m, z = {} m)",
                self.name(),
                short_number(*x),
                short_number(*z)
            ),
            Output::Input(input) => input.fmt(f),
            other => f.write_str(other.name()),
        }
    }
}

/// The most inputs, and the most outputs, one [`LinearSystem`] holds (each is compared with
/// every other for duplicates, and every pair may have a transfer function).
pub const MAX_SIGNALS: usize = 256;

/// What a [`LinearSystem`] is asked to hold: which ignorable coordinates join the four
/// lean–steer states (in the order given), which inputs and which outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct SystemRequest {
    /// Ignorable coordinates to add after φ, δ, φ̇, δ̇ (see [`StateVariable::IGNORABLE`]).
    pub states: Vec<StateVariable>,
    /// The inputs, the columns of B and D (may be empty).
    pub inputs: Vec<Input>,
    /// The outputs, the rows of C and D (at least one).
    pub outputs: Vec<Output>,
}

impl SystemRequest {
    /// Meijaard 2007's system: the four states, T_φ and T_δ in, the four states out.
    pub fn lean_steer() -> Self {
        SystemRequest {
            states: Vec::new(),
            inputs: vec![Input::LeanTorque, Input::SteerTorque],
            outputs: StateVariable::LEAN_STEER.map(Output::State).to_vec(),
        }
    }

    /// Refuses a duplicated or misplaced state, a duplicated input or output, a point that is
    /// not finite, an empty output list, and an output whose states are not requested.
    fn check(&self) -> Result<()> {
        let bad = |what: &'static str, rule: String| Err(Error::InvalidArgument { what, rule });
        for (what, count) in [
            ("inputs", self.inputs.len()),
            ("outputs", self.outputs.len()),
        ] {
            if count > MAX_SIGNALS {
                return Err(Error::LimitExceeded {
                    what,
                    rule: format!("at most {MAX_SIGNALS} can be asked for, got {count}"),
                });
            }
        }
        for (k, s) in self.states.iter().enumerate() {
            if StateVariable::LEAN_STEER.contains(s) {
                return bad(
                    "states",
                    format!(
                        "{s} is always a state: list only ignorable coordinates (yaw, \
                         rear_contact_x, rear_contact_y, rear_wheel_angle, front_wheel_angle)"
                    ),
                );
            }
            if self.states[..k].contains(s) {
                return bad("states", format!("{s} is listed twice"));
            }
        }
        let has =
            |s: StateVariable| StateVariable::LEAN_STEER.contains(&s) || self.states.contains(&s);
        if has(StateVariable::RearContactY) && !has(StateVariable::Yaw) {
            return bad(
                "states",
                "rear_contact_y needs yaw among the states (ẏ = v ψ)".into(),
            );
        }
        for (k, input) in self.inputs.iter().enumerate() {
            if let Input::LateralForce { x, z } = input
                && !(x.is_finite() && z.is_finite())
            {
                return bad(
                    "inputs",
                    format!(
                        "the point of input {} ({input}) must have finite coordinates",
                        k + 1
                    ),
                );
            }
            if self.inputs[..k].contains(input) {
                return bad("inputs", format!("{input} is listed twice"));
            }
        }
        if self.outputs.is_empty() {
            return bad("outputs", "at least one output is needed".into());
        }
        for (k, output) in self.outputs.iter().enumerate() {
            if let Output::RearFramePointY { x, z } | Output::FrontFramePointY { x, z } = output
                && !(x.is_finite() && z.is_finite())
            {
                return bad(
                    "outputs",
                    format!(
                        "the point of output {} ({output}) must have finite coordinates",
                        k + 1
                    ),
                );
            }
            if self.outputs[..k].contains(output) {
                return bad("outputs", format!("{output} is listed twice"));
            }
            if let Output::Input(input) = output
                && !self.inputs.contains(input)
            {
                return bad(
                    "outputs",
                    format!(
                        "{output} as an output is the input applied: list it among the inputs \
                         too"
                    ),
                );
            }
            let needs: &[StateVariable] = match output {
                Output::State(s) => std::slice::from_ref(s),
                Output::FrontContactY
                | Output::RearFramePointY { .. }
                | Output::FrontFramePointY { .. } => {
                    &[StateVariable::Yaw, StateVariable::RearContactY]
                }
                _ => &[],
            };
            if let Some(missing) = needs.iter().find(|s| !has(**s)) {
                return bad(
                    "outputs",
                    format!("{output} needs {missing} among the states"),
                );
            }
        }
        Ok(())
    }
}

impl SystemRequest {
    /// Refuses a point (a lateral force's, or an output's on the rear or front frame) that lies
    /// below the ground (z > 0) or outside the box the bicycle occupies in its side view
    /// ([`SideView::extent`](crate::side_view::SideView::extent): the wheels and each frame's
    /// uniform ellipsoid of the same mass and inertia), naming `inputs` or `outputs`.
    pub(crate) fn check_points(&self, bike: &BenchmarkParameters) -> Result<()> {
        let [lo, hi] = crate::side_view::side_view(bike, None).extent();
        let points = self
            .inputs
            .iter()
            .enumerate()
            .filter_map(|(k, input)| match *input {
                Input::LateralForce { x, z } => {
                    Some(("inputs", "input", k, input.to_string(), x, z))
                }
                _ => None,
            })
            .chain(
                self.outputs
                    .iter()
                    .enumerate()
                    .filter_map(|(k, output)| match *output {
                        Output::RearFramePointY { x, z } | Output::FrontFramePointY { x, z } => {
                            Some(("outputs", "output", k, output.to_string(), x, z))
                        }
                        _ => None,
                    }),
            );
        for (what, one, k, name, x, z) in points {
            let rule = if z > 0.0 {
                format!(
                    "the point of {one} {} ({name}) is below the ground: z points down, so a \
                     point on the bicycle has z ≤ 0",
                    k + 1
                )
            } else if x < lo[0] || x > hi[0] || -z > hi[1] {
                format!(
                    "the point of {one} {} ({name}) lies outside the bicycle, which spans x from \
                     {:.3} to {:.3} m and z from {:.3} to 0 m (its wheels, and each frame's \
                     uniform ellipsoid of the same mass and inertia)",
                    k + 1,
                    lo[0],
                    hi[0],
                    0.0 - hi[1],
                )
            } else {
                continue;
            };
            return Err(Error::InvalidArgument { what, rule });
        }
        Ok(())
    }
}

/// The geometry the ignorable coordinates' kinematics need (benchmark symbols, SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Geometry {
    /// w: wheelbase \[m\].
    pub(crate) w: f64,
    /// c: trail \[m\].
    pub(crate) c: f64,
    /// λ: steer axis tilt \[rad\].
    pub(crate) lambda: f64,
    /// r_R, r_F: wheel radii \[m\].
    pub(crate) r_r: f64,
    pub(crate) r_f: f64,
}

impl Geometry {
    /// The geometry of a bicycle.
    pub(crate) fn of(bike: &BenchmarkParameters) -> Self {
        Geometry {
            w: bike.w,
            c: bike.c,
            lambda: bike.lambda,
            r_r: bike.r_r,
            r_f: bike.r_f,
        }
    }

    /// ψ̇ = (v δ + c δ̇) cos λ / w on [φ, δ, φ̇, δ̇].
    fn yaw_rate_row(&self, speed: f64) -> [f64; 4] {
        let k = crate::math::cos(self.lambda) / self.w;
        let mut row = [0.0; 4];
        row[STEER] = speed * k;
        row[STEER_RATE] = self.c * k;
        row
    }

    /// The generalized forces [f_φ, f_δ] of one unit of an input (see the module's derivation).
    pub(crate) fn generalized_forces(&self, input: &Input) -> [f64; 2] {
        match *input {
            Input::LeanTorque => [1.0, 0.0],
            Input::SteerTorque => [0.0, 1.0],
            Input::LateralForce { x, z } => {
                [-z, x * self.c * crate::math::cos(self.lambda) / self.w]
            }
        }
    }
}

/// The linearized bicycle at one forward speed as ẋ = A x + B u, y = C x + D u, with named
/// states, inputs and outputs (see the module documentation for their kinematics).
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
/// let request = SystemRequest {
///     states: vec![StateVariable::Yaw, StateVariable::RearContactY],
///     inputs: vec![Input::SteerTorque],
///     outputs: vec![Output::State(StateVariable::Lean), Output::FrontContactY],
/// };
/// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 5.0, &request)?;
/// assert_eq!((system.a().shape(), system.b().shape(), system.c().shape()), ((6, 6), (6, 1), (2, 6)));
/// // Steer torque → lean: the counter-steering zero has left the right half-plane at 5 m/s.
/// let lean = system.transfer_function(0, 0)?;
/// assert!(lean.zeros()?.iter().all(|z| z.re < 0.0));
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LinearSystem {
    pub(crate) speed: f64,
    pub(crate) canonical: Canonical,
    pub(crate) geometry: Geometry,
    states: Vec<StateVariable>,
    inputs: Vec<Input>,
    outputs: Vec<Output>,
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    c: DMatrix<f64>,
    d: DMatrix<f64>,
    /// The generalized forces of each input (2 × inputs): B's lower block is M⁻¹ times this.
    pub(crate) forces: DMatrix<f64>,
    /// K (inputs × states) when this is a closed loop u = r − K x (`control::ClosedLoop`).
    gains: Option<DMatrix<f64>>,
}

impl LinearSystem {
    /// The system of a bicycle (validated first) at forward speed `speed` (any finite value),
    /// holding what `request` asks for. Errors: invalid parameters, a speed that is not finite,
    /// and a bad request ([`Error::InvalidArgument`] naming `states`, `inputs` or `outputs`).
    pub fn new(bike: &BenchmarkParameters, speed: f64, request: &SystemRequest) -> Result<Self> {
        let canonical = Canonical::new(bike)?;
        let lean_steer = StateSpace::new(&canonical, speed)?;
        request.check()?;
        request.check_points(bike)?;
        let geometry = Geometry::of(bike);
        let states: Vec<StateVariable> = StateVariable::LEAN_STEER
            .iter()
            .chain(&request.states)
            .copied()
            .collect();
        let n = states.len();
        let index = |s: StateVariable| states.iter().position(|x| *x == s);
        let mut a = DMatrix::zeros(n, n);
        a.view_mut((0, 0), (4, 4)).copy_from(&lean_steer.a);
        for (i, s) in states.iter().enumerate().skip(4) {
            match s {
                StateVariable::Yaw => {
                    for (j, x) in geometry.yaw_rate_row(speed).iter().enumerate() {
                        a[(i, j)] = *x;
                    }
                }
                StateVariable::RearContactY => {
                    // `check` refuses y without ψ; the error stays should that change.
                    let Some(yaw) = index(StateVariable::Yaw) else {
                        return Err(Error::InvalidArgument {
                            what: "states",
                            rule: "the rear contact's y needs the yaw ψ among the states".into(),
                        });
                    };
                    a[(i, yaw)] = speed;
                }
                // Deviations from the nominal run: zero rows (see the module documentation).
                _ => {}
            }
        }
        let m = request.inputs.len();
        let forces = DMatrix::from_fn(2, m, |i, j| {
            geometry.generalized_forces(&request.inputs[j])[i]
        });
        let mut b = DMatrix::zeros(n, m);
        let m_inv: Matrix2<f64> = lean_steer.b.fixed_view::<2, 2>(2, 0).into_owned();
        b.view_mut((2, 0), (2, m)).copy_from(&(m_inv * &forces));
        let p = request.outputs.len();
        let mut c = DMatrix::zeros(p, n);
        for (i, output) in request.outputs.iter().enumerate() {
            let mut set = |s: StateVariable, x: f64| {
                if let Some(j) = index(s) {
                    c[(i, j)] += x;
                }
            };
            let (cos_l, sin_l) = (
                crate::math::cos(geometry.lambda),
                crate::math::sin(geometry.lambda),
            );
            let point = |set: &mut dyn FnMut(StateVariable, f64), x: f64, z: f64| {
                set(StateVariable::RearContactY, 1.0);
                set(StateVariable::Yaw, x);
                set(StateVariable::Lean, -z);
            };
            match *output {
                Output::State(s) => set(s, 1.0),
                Output::YawRate => {
                    for (j, x) in geometry.yaw_rate_row(speed).iter().enumerate() {
                        set(StateVariable::LEAN_STEER[j], *x);
                    }
                }
                Output::RearContactLateralAcceleration => {
                    for (j, x) in geometry.yaw_rate_row(speed).iter().enumerate() {
                        set(StateVariable::LEAN_STEER[j], speed * x);
                    }
                }
                Output::FrontContactY => {
                    point(&mut set, geometry.w, 0.0);
                    set(StateVariable::Steer, -geometry.c * cos_l);
                }
                // D's row (below): u itself, no state.
                Output::Input(_) => {}
                Output::RearFramePointY { x, z } => point(&mut set, x, z),
                Output::FrontFramePointY { x, z } => {
                    point(&mut set, x, z);
                    set(
                        StateVariable::Steer,
                        (x - geometry.w - geometry.c) * cos_l - z * sin_l,
                    );
                }
            }
        }
        let mut d = DMatrix::zeros(p, m);
        for (i, output) in request.outputs.iter().enumerate() {
            if let Output::Input(input) = output
                && let Some(j) = request.inputs.iter().position(|u| u == input)
            {
                d[(i, j)] = 1.0;
            }
        }
        Ok(LinearSystem {
            speed,
            canonical,
            geometry,
            states,
            inputs: request.inputs.clone(),
            outputs: request.outputs.clone(),
            a,
            b,
            c,
            d,
            forces,
            gains: None,
        })
    }

    /// The closed loop u = r − K x of this open loop: A − B K, B, C − D K, D, the inputs
    /// becoming reference inputs r. `k` must be inputs × states (checked by the caller).
    pub(crate) fn closed(&self, k: &DMatrix<f64>) -> LinearSystem {
        LinearSystem {
            a: &self.a - &self.b * k,
            c: &self.c - &self.d * k,
            gains: Some(k.clone()),
            ..self.clone()
        }
    }

    /// K (inputs × states) when the system is a closed loop u = r − K x, `None` for the
    /// open loop.
    pub fn gains(&self) -> Option<&DMatrix<f64>> {
        self.gains.as_ref()
    }

    /// The forward speed v [m/s].
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// The states, in the order of A's rows: φ, δ, φ̇, δ̇, then the requested ones.
    pub fn states(&self) -> &[StateVariable] {
        &self.states
    }

    /// The inputs, in the order of B's columns.
    pub fn inputs(&self) -> &[Input] {
        &self.inputs
    }

    /// The outputs, in the order of C's rows.
    pub fn outputs(&self) -> &[Output] {
        &self.outputs
    }

    /// A: the state matrix (states × states).
    pub fn a(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// B: the input matrix (states × inputs).
    pub fn b(&self) -> &DMatrix<f64> {
        &self.b
    }

    /// C: the output matrix (outputs × states).
    pub fn c(&self) -> &DMatrix<f64> {
        &self.c
    }

    /// D: the feedthrough matrix (outputs × inputs); zero for every output offered so far.
    pub fn d(&self) -> &DMatrix<f64> {
        &self.d
    }

    /// The canonical matrices the system was built from.
    pub(crate) fn canonical(&self) -> &Canonical {
        &self.canonical
    }

    /// The rates of the nominal straight run that the states x_P, θ_R, θ_F are measured from:
    /// v, −v / r_R, −v / r_F for those states, zero for the others. The position of the rear
    /// contact is x_P + v t, the rear wheel's angle θ_R − v t / r_R.
    pub fn nominal_rates(&self) -> Vec<f64> {
        let v = self.speed;
        self.states
            .iter()
            .map(|s| match s {
                StateVariable::RearContactX => v,
                StateVariable::RearWheelAngle if self.geometry.r_r > 0.0 => -v / self.geometry.r_r,
                StateVariable::FrontWheelAngle if self.geometry.r_f > 0.0 => -v / self.geometry.r_f,
                _ => 0.0,
            })
            .collect()
    }

    /// The index of a state, if the system has it.
    pub fn state_index(&self, state: StateVariable) -> Option<usize> {
        self.states.iter().position(|s| *s == state)
    }
}

#[cfg(test)]
#[path = "system_tests.rs"]
mod tests;
