//! What a simulation gives back: the samples, how the run ended (in words through `Display`,
//! in a machine-readable kind), and the counts. The one place where an outcome is worded, for
//! the command line and the web server alike.

use std::fmt;

use super::forward::ContactForce;
use super::state::State;
use crate::error::Error;

/// How far a simulation is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Simulated time reached \[s\].
    pub t: f64,
    /// Time at which the run ends if nothing happens \[s\].
    pub t_end: f64,
    /// Steps accepted so far.
    pub steps: usize,
}

/// Which wheel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wheel {
    /// The rear wheel.
    Rear,
    /// The front wheel.
    Front,
}

impl Wheel {
    /// Both wheels, rear first (the contacts' order).
    pub const BOTH: [Wheel; 2] = [Wheel::Rear, Wheel::Front];

    /// `rear` or `front`.
    pub fn name(self) -> &'static str {
        match self {
            Wheel::Rear => "rear",
            Wheel::Front => "front",
        }
    }
}

impl fmt::Display for Wheel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How a simulation ended. Only the first is the full duration; the others keep the samples
/// computed up to that point. `Display` words it for people (the command line prints it, the
/// web API sends it as the outcome's message).
///
/// ```
/// use whipple::advanced::nonlinear::{Outcome, Wheel};
/// assert_eq!(Outcome::Completed.to_string(), "completed");
/// let fell = Outcome::Fell { t: 2.5, lean: -1.05 };
/// assert_eq!(fell.to_string(), "fell: |lean| passed the fall angle at t = 2.5000 s (lean -60.16 deg)");
/// assert_eq!((fell.kind(), fell.is_failure()), ("fell", false));
/// let lifted = Outcome::WheelLifted { t: 2.5858, wheel: Wheel::Rear, lean: 0.468 };
/// assert!(lifted.to_string().starts_with("the rear wheel's normal force turned negative at t = 2.5858 s"));
/// assert!(format!("{lifted:.2}").contains("at t = 2.59 s"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Reached the end time.
    Completed,
    /// |lean| passed the fall angle at time t (interpolated within the step).
    Fell {
        /// Time of the crossing \[s\].
        t: f64,
        /// Lean at that time \[rad\].
        lean: f64,
    },
    /// The leaning rider's upper body passed its hinge limit at time t (interpolated within the
    /// step): it lies across the bicycle (`super::LeanModel`).
    UpperBodyFell {
        /// Time of the crossing \[s\].
        t: f64,
        /// The upper body's lean on the hinge at that time \[rad\].
        lean: f64,
    },
    /// A wheel's normal force became negative at time t (interpolated within the step).
    WheelLifted {
        /// Time \[s\].
        t: f64,
        /// The wheel.
        wheel: Wheel,
        /// Lean at the end of the step in which it happened (the last sample) \[rad\].
        lean: f64,
    },
    /// Newton projection onto the holonomic constraints failed after the step ending at t.
    ProjectionFailed {
        /// Time \[s\].
        t: f64,
        /// Iterations made.
        iterations: usize,
        /// Residual reached.
        residual: f64,
    },
    /// The state became non-finite in the step ending at t.
    NonFiniteState {
        /// Time \[s\].
        t: f64,
    },
    /// The adaptive step size fell below its minimum, or its step limit was reached, at t.
    StepSizeTooSmall {
        /// Time \[s\].
        t: f64,
    },
    /// The run was stopped from outside ([`super::SimulationSettings::stop`]) at time t.
    Stopped {
        /// Time \[s\].
        t: f64,
    },
    /// The equations of motion could not be evaluated (for example singular) at time t.
    Failed {
        /// Time \[s\].
        t: f64,
        /// Why.
        error: Error,
    },
}

/// A lifted wheel is reported as falling past this lean \[deg\].
const FALLING_DEG: f64 = 20.0;

impl Outcome {
    /// A machine-readable name: `completed`, `fell`, `upper_body_fell`, `wheel_lifted`,
    /// `projection_failed`, `non_finite_state`, `step_limit`, `stopped` or `failed`.
    pub fn kind(&self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::Fell { .. } => "fell",
            Outcome::UpperBodyFell { .. } => "upper_body_fell",
            Outcome::WheelLifted { .. } => "wheel_lifted",
            Outcome::ProjectionFailed { .. } => "projection_failed",
            Outcome::NonFiniteState { .. } => "non_finite_state",
            Outcome::StepSizeTooSmall { .. } => "step_limit",
            Outcome::Stopped { .. } => "stopped",
            Outcome::Failed { .. } => "failed",
        }
    }

    /// When it happened \[s\]; `None` for [`Outcome::Completed`] (the end time).
    pub fn t(&self) -> Option<f64> {
        match self {
            Outcome::Completed => None,
            Outcome::Fell { t, .. }
            | Outcome::UpperBodyFell { t, .. }
            | Outcome::WheelLifted { t, .. }
            | Outcome::ProjectionFailed { t, .. }
            | Outcome::NonFiniteState { t }
            | Outcome::StepSizeTooSmall { t }
            | Outcome::Stopped { t }
            | Outcome::Failed { t, .. } => Some(*t),
        }
    }

    /// The same outcome `dt` seconds later (a run started at t = dt reports local times).
    pub(crate) fn delayed(self, dt: f64) -> Outcome {
        match self {
            Outcome::Completed => Outcome::Completed,
            Outcome::Fell { t, lean } => Outcome::Fell { t: t + dt, lean },
            Outcome::UpperBodyFell { t, lean } => Outcome::UpperBodyFell { t: t + dt, lean },
            Outcome::WheelLifted { t, wheel, lean } => Outcome::WheelLifted {
                t: t + dt,
                wheel,
                lean,
            },
            Outcome::ProjectionFailed {
                t,
                iterations,
                residual,
            } => Outcome::ProjectionFailed {
                t: t + dt,
                iterations,
                residual,
            },
            Outcome::NonFiniteState { t } => Outcome::NonFiniteState { t: t + dt },
            Outcome::StepSizeTooSmall { t } => Outcome::StepSizeTooSmall { t: t + dt },
            Outcome::Stopped { t } => Outcome::Stopped { t: t + dt },
            Outcome::Failed { t, error } => Outcome::Failed { t: t + dt, error },
        }
    }

    /// True when the computation failed (rather than the bicycle doing something): every
    /// outcome but completing, falling and lifting a wheel.
    pub fn is_failure(&self) -> bool {
        !matches!(
            self,
            Outcome::Completed
                | Outcome::Fell { .. }
                | Outcome::UpperBodyFell { .. }
                | Outcome::WheelLifted { .. }
        )
    }
}

impl fmt::Display for Outcome {
    /// Times with four decimals, or as many as the precision asks (`{:.2}`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let digits = f.precision().unwrap_or(4);
        let at = |t: f64| format!("t = {t:.digits$} s");
        match self {
            Outcome::Completed => f.write_str("completed"),
            Outcome::Fell { t, lean } => write!(
                f,
                "fell: |lean| passed the fall angle at {} (lean {:.2} deg)",
                at(*t),
                lean.to_degrees()
            ),
            Outcome::UpperBodyFell { t, lean } => write!(
                f,
                "the rider's upper body fell across the bicycle at {} (its lean on the hinge \
                 {:.1} deg)",
                at(*t),
                lean.to_degrees()
            ),
            Outcome::WheelLifted { t, wheel, lean } => write!(
                f,
                "the {wheel} wheel's normal force turned negative at {}: it would lift off \
                 (lean {:.1} deg{})",
                at(*t),
                lean.to_degrees(),
                if lean.abs() > FALLING_DEG.to_radians() {
                    ", falling"
                } else {
                    ""
                }
            ),
            Outcome::ProjectionFailed {
                t,
                iterations,
                residual,
            } => write!(
                f,
                "stopped: the projection onto the constraints diverged at {} ({iterations} \
                 iterations, residual {residual:e})",
                at(*t)
            ),
            Outcome::NonFiniteState { t } => write!(
                f,
                "stopped: the state became non-finite at {} (check the torque expressions)",
                at(*t)
            ),
            Outcome::StepSizeTooSmall { t } => write!(
                f,
                "stopped: the adaptive step size became too small at {}",
                at(*t)
            ),
            Outcome::Stopped { t } => write!(f, "stopped on request at {}", at(*t)),
            Outcome::Failed { t, error } => write!(f, "stopped at {}: {error}", at(*t)),
        }
    }
}

/// One recorded instant (after projection). Radians, metres, seconds, newtons, joules. The
/// configuration is complete: [`super::Model::sample_poses`] places the four bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// t \[s\].
    pub t: f64,
    /// φ \[rad\].
    pub lean: f64,
    /// δ \[rad\].
    pub steer: f64,
    /// φ̇ [rad/s].
    pub lean_rate: f64,
    /// δ̇ [rad/s].
    pub steer_rate: f64,
    /// ψ \[rad\].
    pub yaw: f64,
    /// θ_B: pitch of the rear frame (a dependent coordinate) \[rad\].
    pub pitch: f64,
    /// θ_R: rear wheel rotation relative to the rear frame (see [`super::Model::wheel_angles`]) \[rad\].
    pub rear_wheel_angle: f64,
    /// θ_F: front wheel rotation relative to the front frame \[rad\].
    pub front_wheel_angle: f64,
    /// Rear contact x \[m\].
    pub x: f64,
    /// Rear contact y \[m\].
    pub y: f64,
    /// Front contact x \[m\].
    pub front_x: f64,
    /// Front contact y \[m\].
    pub front_y: f64,
    /// v: forward speed of the rear hub [m/s].
    pub speed: f64,
    /// Total energy, kinetic + potential \[J\].
    pub energy: f64,
    /// Largest absolute holonomic residual \[m\].
    pub position_residual: f64,
    /// Largest absolute velocity-row residual (holonomic rows differentiated and rolling)
    /// [m/s].
    pub velocity_residual: f64,
    /// Ground force on the rear wheel \[N\].
    pub rear: ContactForce<f64>,
    /// Ground force on the front wheel \[N\].
    pub front: ContactForce<f64>,
}

impl Sample {
    /// The names of [`Sample::values`]: the columns front ends write (`whipple simulate`'s CSV
    /// has the first [`Sample::CSV_COLUMNS`]; the dependent coordinates follow).
    pub const COLUMNS: [&'static str; 23] = [
        "t",
        "lean",
        "steer",
        "lean_rate",
        "steer_rate",
        "yaw",
        "x",
        "y",
        "speed",
        "energy",
        "position_residual",
        "velocity_residual",
        "rear_normal",
        "rear_longitudinal",
        "rear_lateral",
        "front_normal",
        "front_longitudinal",
        "front_lateral",
        "front_x",
        "front_y",
        "pitch",
        "rear_wheel_angle",
        "front_wheel_angle",
    ];

    /// How many of [`Sample::COLUMNS`] the command line's CSV writes.
    pub const CSV_COLUMNS: usize = 20;

    /// The sample's numbers in the order of [`Sample::COLUMNS`].
    pub fn values(&self) -> [f64; 23] {
        [
            self.t,
            self.lean,
            self.steer,
            self.lean_rate,
            self.steer_rate,
            self.yaw,
            self.x,
            self.y,
            self.speed,
            self.energy,
            self.position_residual,
            self.velocity_residual,
            self.rear.normal,
            self.rear.longitudinal,
            self.rear.lateral,
            self.front.normal,
            self.front.longitudinal,
            self.front.lateral,
            self.front_x,
            self.front_y,
            self.pitch,
            self.rear_wheel_angle,
            self.front_wheel_angle,
        ]
    }

    /// True when every number of the sample is finite.
    pub fn is_finite(&self) -> bool {
        let forces = [self.rear, self.front]
            .into_iter()
            .flat_map(|c| [c.normal, c.longitudinal, c.lateral]);
        [
            self.t,
            self.lean,
            self.steer,
            self.lean_rate,
            self.steer_rate,
            self.yaw,
            self.pitch,
            self.rear_wheel_angle,
            self.front_wheel_angle,
            self.x,
            self.y,
            self.front_x,
            self.front_y,
            self.speed,
            self.energy,
            self.position_residual,
            self.velocity_residual,
        ]
        .into_iter()
        .chain(forces)
        .all(f64::is_finite)
    }
}

/// The result of [`super::simulate`].
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Samples: the initial state, then one in [`super::SimulationSettings::sample_every`]
    /// accepted steps (every step by default), and always the last state reached.
    pub samples: Vec<Sample>,
    /// The extremes over every accepted step, thinned out of `samples` or not.
    pub extremes: RunExtremes,
    /// How the run ended.
    pub outcome: Outcome,
    /// The last state reached (projected).
    pub final_state: State<f64>,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected step attempts (adaptive integrator only).
    pub rejected_steps: usize,
    /// Wheels whose contact already pulled the wheel down at the start (a negative normal
    /// force, as for the two-mass-skate, whose masses sit ahead of its front contact). The
    /// contacts are bilateral constraints, as in the linearized model, so such a run goes on;
    /// lift-off is watched only for the wheels that started pressed onto the ground.
    pub pulled_down_from_start: Vec<Wheel>,
}

/// Extremes over every accepted step of a run (finite samples only), whether kept in
/// [`Simulation::samples`] or thinned out: what a summary of the run says.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunExtremes {
    /// Total energy at the start \[J\].
    pub initial_energy: f64,
    /// Largest |energy − initial energy| \[J\].
    pub largest_energy_change: f64,
    /// Largest holonomic residual \[m\].
    pub largest_position_residual: f64,
    /// Largest velocity-row residual [m/s].
    pub largest_velocity_residual: f64,
    /// Smallest normal force on the rear and on the front wheel \[N\].
    pub smallest_normal_force: [f64; 2],
}

impl RunExtremes {
    /// The extremes of a run that has only its first sample.
    pub fn start(first: &Sample) -> Self {
        RunExtremes {
            initial_energy: first.energy,
            largest_energy_change: 0.0,
            largest_position_residual: first.position_residual,
            largest_velocity_residual: first.velocity_residual,
            smallest_normal_force: [first.rear.normal, first.front.normal],
        }
    }

    /// Takes in one more sample (a non-finite one is left out).
    pub fn observe(&mut self, s: &Sample) {
        if !s.is_finite() {
            return;
        }
        let change = (s.energy - self.initial_energy).abs();
        self.largest_energy_change = self.largest_energy_change.max(change);
        self.largest_position_residual = self.largest_position_residual.max(s.position_residual);
        self.largest_velocity_residual = self.largest_velocity_residual.max(s.velocity_residual);
        for (smallest, n) in self
            .smallest_normal_force
            .iter_mut()
            .zip([s.rear.normal, s.front.normal])
        {
            *smallest = smallest.min(n);
        }
    }
}

impl Simulation {
    /// A short line on how the run ended, for a figure's caption: `completed`, `fell at t = …`,
    /// `rear wheel lifts off at t = … (lean …°)`, or `stopped at t = …` (the last sample's
    /// time).
    pub fn caption(&self) -> String {
        match &self.outcome {
            Outcome::Completed => "completed".into(),
            Outcome::Fell { t, .. } => format!("fell at t = {t:.3} s"),
            Outcome::WheelLifted { t, wheel, lean } => format!(
                "{wheel} wheel lifts off at t = {t:.3} s (lean {:.1}°)",
                lean.to_degrees()
            ),
            _ => format!(
                "stopped at t = {:.3} s",
                self.samples.last().map_or(0.0, |s| s.t)
            ),
        }
    }
}
