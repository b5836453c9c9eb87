//! The human controller of Hess, Moore & Hubbard 2012 ("Modeling the manually controlled
//! bicycle", IEEE TSMC-A 42(3)): the rider steers with nested loops closed one inside the
//! other, each a pure gain, and the steer torque comes through a neuromuscular filter.
//!
//! From the outside in, each loop turns its error into the next loop's command:
//!
//! ```text
//! y_c ─► k_y (y_c − y_Q) = ψ_c ─► k_ψ (ψ_c − ψ) = φ_c ─► k_φ (φ_c − φ) = φ̇_c
//!     ─► k_φ̇ (φ̇_c − φ̇) = δ_c ─► k_δ (δ_c − δ) ─► ω²/(s² + 2ζωs + ω²) ─► T_δ
//! ```
//!
//! The "heading" task starts at ψ_c (no lateral loop), the "lateral" task at the front
//! contact's commanded lateral position y_c. Written out, the command into the neuromuscular
//! filter is k_δ (Π r − Σᵢ wᵢ yᵢ): the reference r weighted by the product Π of the gains
//! outside k_δ, and each measured output yᵢ (ψ, φ, δ, φ̇, y_Q) by the product of the gains
//! outside its own loop (ψ: k_φ̇ k_φ k_ψ; φ: k_φ̇ k_φ; δ: 1; φ̇: k_φ̇; y_Q: k_φ̇ k_φ k_ψ k_y).
//! The filter adds two states, T_δ and Ṫ_δ: T̈_δ = −ω² T_δ − 2ζω Ṫ_δ + ω² k_δ (Π r − Σᵢ wᵢ yᵢ).
//! This is the closed loop of HumanControl's `system_state_space.m`, whose two task names it
//! keeps; its gains files (`<Name>SteerGains.txt`: speed, kDelta, kPhiDot, kPhi, kPsi, kY) are
//! read by [`crate::advanced::io::read_gains`] into a [`GainTable`], interpolated in speed as
//! its `lookup_gains.m` does.

use nalgebra::DMatrix;

use super::system::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use crate::analysis::eigen::Complex64;
use crate::error::{Error, Result, short_number};
use crate::parameters::BenchmarkParameters;

/// The neuromuscular filter's default natural frequency ω \[rad/s\] (Hess 2012).
pub const NEUROMUSCULAR_FREQUENCY: f64 = 30.0;
/// The neuromuscular filter's default damping ratio ζ (Hess 2012).
pub const NEUROMUSCULAR_DAMPING: f64 = 0.707;

/// The five loop gains, named as HumanControl's files name them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HumanGains {
    /// k_δ: steer angle loop \[N m/rad\].
    pub k_delta: f64,
    /// k_φ̇: roll rate loop \[s\] (rad of steer per rad/s of roll rate).
    pub k_phi_dot: f64,
    /// k_φ: roll angle loop \[1/s\].
    pub k_phi: f64,
    /// k_ψ: heading loop \[1\].
    pub k_psi: f64,
    /// k_y: lateral deviation loop \[rad/m\] (unused by the heading task).
    pub k_y: f64,
}

impl HumanGains {
    /// The gains as HumanControl orders them: kDelta, kPhiDot, kPhi, kPsi, kY.
    pub fn to_array(&self) -> [f64; 5] {
        [
            self.k_delta,
            self.k_phi_dot,
            self.k_phi,
            self.k_psi,
            self.k_y,
        ]
    }

    /// The gains from HumanControl's order: kDelta, kPhiDot, kPhi, kPsi, kY.
    pub fn from_array(k: [f64; 5]) -> Self {
        HumanGains {
            k_delta: k[0],
            k_phi_dot: k[1],
            k_phi: k[2],
            k_psi: k[3],
            k_y: k[4],
        }
    }

    /// HumanControl's names for the gains, in [`Self::to_array`]'s order.
    pub const NAMES: [&'static str; 5] = ["kDelta", "kPhiDot", "kPhi", "kPsi", "kY"];
}

/// The neuromuscular filter ω²/(s² + 2ζωs + ω²) between the rider's command and the steer
/// torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neuromuscular {
    /// ω: natural frequency \[rad/s\], positive.
    pub frequency: f64,
    /// ζ: damping ratio, positive.
    pub damping: f64,
}

impl Default for Neuromuscular {
    /// Hess 2012's ω = 30 rad/s, ζ = 0.707.
    fn default() -> Self {
        Neuromuscular {
            frequency: NEUROMUSCULAR_FREQUENCY,
            damping: NEUROMUSCULAR_DAMPING,
        }
    }
}

/// Which loop is outermost: HumanControl's two closed systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Task {
    /// Heading tracking: the command is ψ_c.
    Heading,
    /// Lateral deviation tracking: the command is the front contact's lateral position y_c.
    Lateral,
}

impl Task {
    /// `heading` or `lateral`, as HumanControl names the systems.
    pub fn name(self) -> &'static str {
        match self {
            Task::Heading => "heading",
            Task::Lateral => "lateral",
        }
    }

    /// The task of a name (`heading`, `lateral`).
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "heading" => Ok(Task::Heading),
            "lateral" => Ok(Task::Lateral),
            other => Err(Error::InvalidArgument {
                what: "task",
                rule: format!("`{other}` is not a task: use heading or lateral"),
            }),
        }
    }
}

impl std::fmt::Display for Task {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The rider as Hess's controller: a task, its gains and the neuromuscular filter, checked.
///
/// ```
/// use whipple::advanced::control::{HumanController, HumanGains, Neuromuscular, Task};
/// // HumanControl's benchmark gains at 5 m/s (BenchmarkSteerGains.txt).
/// let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
/// let rider = HumanController::new(Task::Lateral, gains, Neuromuscular::default())?;
/// assert_eq!(rider.measured().len(), 5);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HumanController {
    task: Task,
    gains: HumanGains,
    neuromuscular: Neuromuscular,
}

impl HumanController {
    /// Checks the gains (finite, and non-zero where a loop would open: every gain the task
    /// uses) and the neuromuscular filter (ω and ζ positive and finite); errors name the gain
    /// (`kDelta`, …) or `neuromuscular frequency` / `neuromuscular damping`.
    pub fn new(task: Task, gains: HumanGains, neuromuscular: Neuromuscular) -> Result<Self> {
        let used = match task {
            Task::Heading => 4,
            Task::Lateral => 5,
        };
        for (k, (name, value)) in HumanGains::NAMES.iter().zip(gains.to_array()).enumerate() {
            if !value.is_finite() {
                return Err(Error::InvalidParameter {
                    field: (*name).into(),
                    value,
                    rule: "a gain must be finite".into(),
                });
            }
            if k < used && value == 0.0 {
                return Err(Error::InvalidParameter {
                    field: (*name).into(),
                    value,
                    rule: format!(
                        "a zero gain opens its loop and every loop outside it: the {task} task \
                         needs all of {} non-zero",
                        HumanGains::NAMES[..used].join(", ")
                    ),
                });
            }
        }
        for (field, value) in [
            ("neuromuscular frequency", neuromuscular.frequency),
            ("neuromuscular damping", neuromuscular.damping),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::InvalidParameter {
                    field: field.into(),
                    value,
                    rule: "must be positive and finite".into(),
                });
            }
        }
        Ok(HumanController {
            task,
            gains,
            neuromuscular,
        })
    }

    /// The task.
    pub fn task(&self) -> Task {
        self.task
    }

    /// The gains.
    pub fn gains(&self) -> &HumanGains {
        &self.gains
    }

    /// The neuromuscular filter.
    pub fn neuromuscular(&self) -> &Neuromuscular {
        &self.neuromuscular
    }

    /// The outputs the rider measures, outermost last: ψ, φ, δ, φ̇, and y_Q for the lateral
    /// task.
    pub fn measured(&self) -> Vec<Output> {
        let mut outputs = vec![
            Output::State(StateVariable::Yaw),
            Output::State(StateVariable::Lean),
            Output::State(StateVariable::Steer),
            Output::State(StateVariable::LeanRate),
        ];
        if self.task == Task::Lateral {
            outputs.push(Output::FrontContactY);
        }
        outputs
    }

    /// The weight wᵢ of each measured output ([`Self::measured`]'s order) in the command
    /// k_δ (Π r − Σᵢ wᵢ yᵢ): the product of the gains outside its loop, k_δ excluded.
    pub fn weights(&self) -> Vec<f64> {
        let g = &self.gains;
        let mut w = vec![
            g.k_phi_dot * g.k_phi * g.k_psi,
            g.k_phi_dot * g.k_phi,
            1.0,
            g.k_phi_dot,
        ];
        if self.task == Task::Lateral {
            w.push(g.k_phi_dot * g.k_phi * g.k_psi * g.k_y);
        }
        w
    }

    /// Π: the reference's weight in the command, the product of the gains outside k_δ that
    /// the task uses.
    pub fn reference_weight(&self) -> f64 {
        let g = &self.gains;
        let heading = g.k_phi_dot * g.k_phi * g.k_psi;
        match self.task {
            Task::Heading => heading,
            Task::Lateral => heading * g.k_y,
        }
    }

    /// The open-loop system the rider closes: the states the task needs (yaw, and the rear
    /// contact's lateral position for the lateral task), steer torque first among the inputs
    /// followed by `disturbances`, and the measured outputs.
    pub fn open_loop_request(&self, disturbances: &[Input]) -> SystemRequest {
        let states = match self.task {
            Task::Heading => vec![StateVariable::Yaw],
            Task::Lateral => vec![StateVariable::Yaw, StateVariable::RearContactY],
        };
        let mut inputs = vec![Input::SteerTorque];
        inputs.extend_from_slice(disturbances);
        SystemRequest {
            states,
            inputs,
            outputs: self.measured(),
        }
    }
}

/// A state of a [`HumanLoop`]: the bicycle's, or one of the neuromuscular filter's two.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LoopState {
    /// A state of the bicycle.
    Bicycle(StateVariable),
    /// T_δ: the steer torque the filter puts out \[N m\].
    SteerTorque,
    /// Ṫ_δ: its rate \[N m/s\].
    SteerTorqueRate,
}

impl LoopState {
    /// The state's name (`lean`, …, `steer_torque`, `steer_torque_rate`).
    pub fn name(self) -> &'static str {
        match self {
            LoopState::Bicycle(s) => s.name(),
            LoopState::SteerTorque => "steer_torque",
            LoopState::SteerTorqueRate => "steer_torque_rate",
        }
    }
}

/// An input of a [`HumanLoop`]: the task's command, or a disturbance on the bicycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoopInput {
    /// The command: ψ_c \[rad\] for the heading task, y_c \[m\] for the lateral task.
    Command(Task),
    /// A disturbance applied to the bicycle (lean torque, a lateral force).
    Disturbance(Input),
}

impl LoopInput {
    /// `heading_command`, `lateral_command`, or the disturbance's name.
    pub fn name(&self) -> &'static str {
        match self {
            LoopInput::Command(Task::Heading) => "heading_command",
            LoopInput::Command(Task::Lateral) => "lateral_command",
            LoopInput::Disturbance(input) => input.name(),
        }
    }
}

/// The bicycle with Hess's rider closing the loops, at one speed: ẋ = A x + B u with the
/// bicycle's states, then T_δ and Ṫ_δ; the inputs are the task's command and the
/// disturbances asked for (HumanControl's `system_state_space.m`, in our state order).
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::{HumanController, HumanGains, HumanLoop, Neuromuscular, Task};
/// let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
/// let rider = HumanController::new(Task::Lateral, gains, Neuromuscular::default())?;
/// let ridden = HumanLoop::new(&BenchmarkParameters::meijaard2007(), 5.0, &rider, &[])?;
/// assert_eq!(ridden.a().shape(), (8, 8));
/// assert!(ridden.eigenvalues()?.iter().all(|z| z.re < 0.0));
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HumanLoop {
    controller: HumanController,
    open: LinearSystem,
    states: Vec<LoopState>,
    inputs: Vec<LoopInput>,
    a: DMatrix<f64>,
    b: DMatrix<f64>,
}

impl HumanLoop {
    /// The closed loop of `bike` at `speed` ridden by `controller`, with `disturbances` as
    /// further inputs (not the steer torque, which the rider applies). Errors name `speed` or
    /// `disturbances`, or come from [`LinearSystem::new`].
    pub fn new(
        bike: &BenchmarkParameters,
        speed: f64,
        controller: &HumanController,
        disturbances: &[Input],
    ) -> Result<Self> {
        if !speed.is_finite() {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!("must be finite, got {}", short_number(speed)),
            });
        }
        if disturbances.contains(&Input::SteerTorque) {
            return Err(Error::InvalidArgument {
                what: "disturbances",
                rule: "the rider applies the steer torque: it cannot also be a disturbance".into(),
            });
        }
        let open = LinearSystem::new(bike, speed, &controller.open_loop_request(disturbances))?;
        let n = open.states().len();
        let (omega, zeta) = (
            controller.neuromuscular.frequency,
            controller.neuromuscular.damping,
        );
        let k_delta = controller.gains.k_delta;
        let mut a = DMatrix::zeros(n + 2, n + 2);
        a.view_mut((0, 0), (n, n)).copy_from(open.a());
        // The steer torque is the filter's first state: B's steer column moves into A.
        a.view_mut((0, n), (n, 1)).copy_from(&open.b().column(0));
        a[(n, n + 1)] = 1.0;
        a[(n + 1, n)] = -omega * omega;
        a[(n + 1, n + 1)] = -2.0 * zeta * omega;
        for (w, row) in controller.weights().iter().zip(open.c().row_iter()) {
            for j in 0..n {
                a[(n + 1, j)] -= k_delta * omega * omega * w * row[j];
            }
        }
        let m = 1 + disturbances.len();
        let mut b = DMatrix::zeros(n + 2, m);
        b[(n + 1, 0)] = omega * omega * k_delta * controller.reference_weight();
        for k in 1..m {
            b.view_mut((0, k), (n, 1)).copy_from(&open.b().column(k));
        }
        if a.iter().chain(b.iter()).any(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                context: "the ridden bicycle's closed loop (gains or speed too large)".into(),
            });
        }
        let mut states: Vec<LoopState> = open
            .states()
            .iter()
            .map(|s| LoopState::Bicycle(*s))
            .collect();
        states.extend([LoopState::SteerTorque, LoopState::SteerTorqueRate]);
        let mut inputs = vec![LoopInput::Command(controller.task)];
        inputs.extend(disturbances.iter().map(|d| LoopInput::Disturbance(*d)));
        Ok(HumanLoop {
            controller: *controller,
            open,
            states,
            inputs,
            a,
            b,
        })
    }

    /// The controller.
    pub fn controller(&self) -> &HumanController {
        &self.controller
    }

    /// The open-loop bicycle the rider closes ([`HumanController::open_loop_request`]).
    pub fn open_loop(&self) -> &LinearSystem {
        &self.open
    }

    /// The forward speed v \[m/s\].
    pub fn speed(&self) -> f64 {
        self.open.speed()
    }

    /// The states, in the order of A's rows.
    pub fn states(&self) -> &[LoopState] {
        &self.states
    }

    /// The inputs, in the order of B's columns (the command first).
    pub fn inputs(&self) -> &[LoopInput] {
        &self.inputs
    }

    /// A: the closed loop's state matrix.
    pub fn a(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// B: the inputs' matrix.
    pub fn b(&self) -> &DMatrix<f64> {
        &self.b
    }

    /// The eigenvalues of A from the general eigensolver (faer), sorted by decreasing real
    /// part (not certified).
    pub fn eigenvalues(&self) -> Result<Vec<Complex64>> {
        let mut values = super::feedback::matrix_eigenvalues(&self.a)?;
        values.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        Ok(values)
    }
}

/// The most speeds a [`GainTable`] holds.
pub const MAX_GAIN_SPEEDS: usize = 10_000;

/// Gains tabulated against speed (HumanControl's `<Name>SteerGains.txt`), interpolated
/// linearly in speed as its `lookup_gains.m` does; outside the table, extrapolated linearly and
/// said so ([`GainLookup::extrapolated`]).
#[derive(Debug, Clone, PartialEq)]
pub struct GainTable {
    speeds: Vec<f64>,
    gains: Vec<HumanGains>,
}

/// The gains a [`GainTable`] gives at one speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GainLookup {
    /// The gains.
    pub gains: HumanGains,
    /// Whether the speed lies outside the table's speeds (the gains are extrapolated, or the
    /// table's one row is used at another speed): the closed loop may then be far from what
    /// the gains were tuned for.
    pub extrapolated: bool,
}

impl GainTable {
    /// A table from its rows: speeds finite, non-negative and strictly increasing, at least
    /// one row, at most [`MAX_GAIN_SPEEDS`]; every gain finite. Errors name `speeds` or the
    /// gain (`kPhi`).
    pub fn new(speeds: Vec<f64>, gains: Vec<HumanGains>) -> Result<Self> {
        let bad = |rule: String| {
            Err(Error::InvalidArgument {
                what: "speeds",
                rule,
            })
        };
        if speeds.len() != gains.len() {
            return bad(format!(
                "{} speeds for {} rows of gains",
                speeds.len(),
                gains.len()
            ));
        }
        if speeds.is_empty() {
            return bad("a gain table needs at least one row".into());
        }
        if speeds.len() > MAX_GAIN_SPEEDS {
            return Err(Error::LimitExceeded {
                what: "speeds",
                rule: format!("at most {MAX_GAIN_SPEEDS} rows, got {}", speeds.len()),
            });
        }
        for (k, v) in speeds.iter().enumerate() {
            if !(v.is_finite() && *v >= 0.0) {
                return bad(format!(
                    "speed {} must be finite and non-negative, got {}",
                    k + 1,
                    short_number(*v)
                ));
            }
            if k > 0 && *v <= speeds[k - 1] {
                return bad(format!(
                    "must increase: speed {} ({} m/s) is not above speed {k} ({} m/s)",
                    k + 1,
                    short_number(*v),
                    short_number(speeds[k - 1])
                ));
            }
        }
        for row in &gains {
            for (name, value) in HumanGains::NAMES.iter().zip(row.to_array()) {
                if !value.is_finite() {
                    return Err(Error::InvalidParameter {
                        field: (*name).into(),
                        value,
                        rule: "a gain must be finite".into(),
                    });
                }
            }
        }
        Ok(GainTable { speeds, gains })
    }

    /// The tabulated speeds \[m/s\].
    pub fn speeds(&self) -> &[f64] {
        &self.speeds
    }

    /// The tabulated gains, one row per speed.
    pub fn gains(&self) -> &[HumanGains] {
        &self.gains
    }

    /// The gains at `speed`: interpolated linearly between the two nearest tabulated speeds,
    /// extrapolated from the two nearest the end outside the table (`extrapolated` set); a
    /// one-row table gives its row at every speed (`extrapolated` set at any other speed).
    pub fn at(&self, speed: f64) -> Result<GainLookup> {
        if !speed.is_finite() {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!("must be finite, got {}", short_number(speed)),
            });
        }
        let n = self.speeds.len();
        let (first, last) = (self.speeds[0], self.speeds[n - 1]);
        let extrapolated = speed < first || speed > last;
        if n == 1 {
            return Ok(GainLookup {
                gains: self.gains[0],
                extrapolated,
            });
        }
        // The segment [j − 1, j] holding the speed, or the end segment nearest it.
        let j = self.speeds.partition_point(|v| *v < speed).clamp(1, n - 1);
        let (v0, v1) = (self.speeds[j - 1], self.speeds[j]);
        let t = (speed - v0) / (v1 - v0);
        let (g0, g1) = (self.gains[j - 1].to_array(), self.gains[j].to_array());
        let mut k = [0.0; 5];
        for i in 0..5 {
            k[i] = g0[i] + t * (g1[i] - g0[i]);
        }
        // Finite rows can still extrapolate past double precision (two speeds a hair apart,
        // a speed far outside them): say so rather than hand on an infinite gain.
        if let Some(i) = k.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                context: format!(
                    "`{}` interpolated at {} m/s from the table's speeds {} and {}",
                    HumanGains::NAMES[i],
                    short_number(speed),
                    short_number(v0),
                    short_number(v1)
                ),
            });
        }
        Ok(GainLookup {
            gains: HumanGains::from_array(k),
            extrapolated,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// HumanControl's `gains/BenchmarkSteerGains.txt` (MIT licence, J. K. Moore), copied here:
    /// speed, kDelta, kPhiDot, kPhi, kPsi, kY.
    const BENCHMARK_GAINS: [[f64; 6]; 8] = [
        [2.5, 22.0, -0.09, 23.3, 0.058, 0.195],
        [3.2, 29.283, -0.049, 25.64, 0.087, 0.15],
        [3.6, 33.1311, -0.0535, 19.8266, 0.1056, 0.1338],
        [4.8, 44.6406, -0.0529, 13.2253, 0.172, 0.1001],
        [5.0, 46.5457, -0.0522, 12.6611, 0.1849, 0.0959],
        [8.0, 74.988, -0.04, 9.351, 0.434, 0.06],
        [8.34, 78.2238, -0.0388, 9.2493, 0.4676, 0.0571],
        [12.0, 115.379, -0.029, 9.28, 0.855, 0.04],
    ];

    fn table() -> GainTable {
        GainTable::new(
            BENCHMARK_GAINS.iter().map(|r| r[0]).collect(),
            BENCHMARK_GAINS
                .iter()
                .map(|r| HumanGains::from_array([r[1], r[2], r[3], r[4], r[5]]))
                .collect(),
        )
        .unwrap()
    }

    #[test]
    fn tabulated_benchmark_gains_stabilize_both_tasks_at_every_tabulated_speed() {
        let bike = BenchmarkParameters::meijaard2007();
        let table = table();
        for (v, gains) in table.speeds().iter().zip(table.gains()) {
            for task in [Task::Heading, Task::Lateral] {
                let rider = HumanController::new(task, *gains, Neuromuscular::default()).unwrap();
                let ridden = HumanLoop::new(&bike, *v, &rider, &[]).unwrap();
                let values = ridden.eigenvalues().unwrap();
                assert_eq!(values.len(), ridden.states().len());
                assert!(
                    values[0].re < 0.0,
                    "{task} at {v} m/s: rightmost eigenvalue {}",
                    values[0]
                );
            }
        }
    }

    #[test]
    fn a_steady_command_is_followed_exactly() {
        // The integrators (ψ, y) make the steady state follow the command: at DC, solving
        // A x = −B r for r = 1 gives ψ = 1 (heading) or y_Q = 1 (lateral).
        let bike = BenchmarkParameters::meijaard2007();
        let gains = table().at(5.0).unwrap().gains;
        for task in [Task::Heading, Task::Lateral] {
            let rider = HumanController::new(task, gains, Neuromuscular::default()).unwrap();
            let ridden = HumanLoop::new(&bike, 5.0, &rider, &[]).unwrap();
            let rhs = -ridden.b().column(0);
            let x = ridden.a().clone().lu().solve(&rhs).unwrap();
            let c = ridden.open_loop().c();
            // The outermost loop's output: ψ (the first measured) or y_Q (the last).
            let row = match task {
                Task::Heading => 0,
                Task::Lateral => c.nrows() - 1,
            };
            let followed: f64 = (0..c.ncols()).map(|j| c[(row, j)] * x[j]).sum();
            assert!((followed - 1.0).abs() < 1e-9, "{task}: {followed}");
        }
    }

    #[test]
    fn lookup_interpolates_and_says_when_it_extrapolates() {
        let table = table();
        let at = table.at(4.9).unwrap();
        assert!(!at.extrapolated);
        assert!((at.gains.k_delta - 0.5 * (44.6406 + 46.5457)).abs() < 1e-12);
        let exact = table.at(8.0).unwrap();
        assert_eq!(exact.gains.k_phi, 9.351);
        let beyond = table.at(13.0).unwrap();
        assert!(beyond.extrapolated);
        let slope = (115.379 - 78.2238) / (12.0 - 8.34);
        assert!((beyond.gains.k_delta - (115.379 + slope)).abs() < 1e-9);
        assert!(table.at(1.0).unwrap().extrapolated);
        // Extrapolated past double precision: refused, naming the gain.
        let steep = GainTable::new(
            vec![1.0, 1.0 + 1e-15],
            vec![
                HumanGains::from_array([1.0; 5]),
                HumanGains::from_array([1e300; 5]),
            ],
        )
        .unwrap();
        let err = steep.at(1e3).unwrap_err();
        assert!(err.to_string().contains("`kDelta`"), "{err}");
    }

    #[test]
    fn bad_controllers_and_tables_are_refused_naming_the_field() {
        let gains = table().at(5.0).unwrap().gains;
        let err = HumanController::new(
            Task::Heading,
            gains,
            Neuromuscular {
                frequency: -30.0,
                damping: 0.707,
            },
        )
        .unwrap_err();
        assert!(
            err.to_string()
                .contains("`neuromuscular frequency` = -30: must be positive"),
            "{err}"
        );
        let err = HumanController::new(
            Task::Lateral,
            HumanGains { k_y: 0.0, ..gains },
            Neuromuscular::default(),
        )
        .unwrap_err();
        assert!(err.to_string().contains("`kY` = 0"), "{err}");
        // The heading task does not use kY.
        assert!(
            HumanController::new(
                Task::Heading,
                HumanGains { k_y: 0.0, ..gains },
                Neuromuscular::default()
            )
            .is_ok()
        );
        let err = GainTable::new(vec![5.0, 4.0], vec![gains, gains]).unwrap_err();
        assert!(err.to_string().contains("must increase: speed 2"), "{err}");
        let rider = HumanController::new(Task::Heading, gains, Neuromuscular::default()).unwrap();
        let err = HumanLoop::new(
            &BenchmarkParameters::meijaard2007(),
            5.0,
            &rider,
            &[Input::SteerTorque],
        )
        .unwrap_err();
        assert!(err.to_string().contains("disturbances"), "{err}");
    }
}
