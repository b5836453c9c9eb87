//! The fully non-linear multibody bicycle of Dressel's JBike6 study: four rigid bodies in 3-D
//! (rear wheel R, rear frame with rider B, front frame H, front wheel F), 24 coordinates and 24
//! speeds, three revolute joints and two knife-edge wheel contacts as constraint rows (17
//! holonomic + 4 non-holonomic), Newton–Euler dynamics with Lagrange multipliers.
//!
//! ```
//! use whipple::{BenchmarkParameters, InitialConditions, Model};
//! use whipple::advanced::nonlinear::Inputs;
//! let model = Model::new(&BenchmarkParameters::meijaard2007())?;
//! let state = model.initial_state(&InitialConditions {
//!     lean_rate: 0.5,
//!     ..InitialConditions::upright(4.6)
//! })?;
//! let view = model.observe(&state);
//! assert!((view.speed - 4.6).abs() < 1e-12 && (view.lean_rate - 0.5).abs() < 1e-12);
//! let derivatives = model.forward(&state, &Inputs::default())?;
//! assert!(derivatives.contact[0].normal > 0.0);
//! # Ok::<(), whipple::Error>(())
//! ```
//!
//! One concept per file (the design is in `docs/nonlinear.md`):
//!
//! | file | holds |
//! |---|---|
//! | `topology.rs` | body indices, the joint tree, the tree speeds and the row layout: the one description the others read |
//! | `bodies.rs` | mass, inertia and attachment points from the parameters |
//! | `model.rs` | [`Model`]: bodies, joints and contacts built along the topology |
//! | `rotation.rs`, `state.rs` | Euler angles; [`State`], [`StateView`], [`BodyPose`] |
//! | `joints.rs`, `contact.rs` | the rows of a revolute joint and of a knife-edge wheel |
//! | `configuration.rs`, `initial.rs` | configurations along the tree; [`Model::initial_state`] |
//! | `readout.rs` | lean, steer, rates, speed, contact points, energy, poses of a state |
//! | `constraints.rs` | residuals, the 21 velocity rows, the holonomic Jacobian |
//! | `poses.rs`, `tree.rs`, `forward.rs`, `assembly.rs`, `saddle.rs` | the forward dynamics' stages: poses → tree map (and the rolling rear wheel) → forces → contact rows → TᵀMT → saddle-point solve |
//! | `reference.rs` | the dense 45 × 45 reference solve that checks [`Model::forward`] |
//! | `projection.rs` | positions and velocities back onto the constraints |
//! | `lean.rs` | [`LeanModel`]: the rider's upper body as a fifth body hinged to the rear frame, its forward dynamics, energy and exact linearization |
//! | `reduced.rs` | the model on the linear model's state [φ, δ, φ̇, δ̇] and in spin-free speeds |
//! | `carried.rs` | a simulation carrying a controller's states beside the bicycle's (the rider's torque read from them) |
//! | `settings.rs`, `outcome.rs`, `simulate.rs` | a simulation's settings and bounds, its results, the run itself (rider torques as expressions are the crate's `expression.rs`, shared with the parameter files' values) |

mod assembly;
mod bodies;
pub(crate) mod carried;
mod configuration;
mod constraints;
mod contact;
mod forward;
mod initial;
mod joints;
mod lean;
mod model;
mod outcome;
mod poses;
mod projection;
mod readout;
pub(crate) mod reduced;
mod reference;
pub mod rotation;
mod saddle;
mod settings;
mod simulate;
mod state;
mod topology;
mod tree;

pub use crate::expression::{
    MAX_DEPTH as MAX_EXPRESSION_DEPTH, MAX_LENGTH as MAX_EXPRESSION_LENGTH, TorqueExpression,
};
pub(crate) use forward::StateRates;
pub use forward::{ContactForce, Inputs};
pub use initial::InitialConditions;
pub use lean::{HINGE_LIMIT, LeanForcing, LeanModel, LeanRates, LeanSimulation, LeanState};
pub use model::Model;
pub use outcome::{Outcome, Progress, Sample, Simulation, Wheel};
pub use projection::{ProjectionMethod, ProjectionSettings};
pub(crate) use reduced::{FullStateField, LeanSteerField};
pub use settings::{
    DEFAULT_FALL_ANGLE, MAX_SAMPLES, MAX_STEPS, SimulationSettings, TorqueFn, samples_kept,
};
pub use simulate::{check_rk4_step, fastest_mode, simulate};
pub(crate) use state::{BODY_PITCH, BODY_YAW};
pub use state::{BodyPose, STATE_LEN, State, StateView};
pub(crate) use topology::BODIES;
#[cfg(test)]
pub(crate) use topology::FRONT_FRAME;
pub use topology::{BODY_NAMES, FRONT_WHEEL, REAR_FRAME, REAR_WHEEL};
