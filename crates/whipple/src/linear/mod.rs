//! The linearized Whipple bicycle (Meijaard et al. 2007): canonical matrices, state space,
//! characteristic polynomial, and the bicycle as a linear system with named inputs and outputs
//! and its transfer functions and time responses.

mod canonical;
mod characteristic;
mod controllability;
mod feedback;
mod handling;
mod human;
mod human_loops;
mod lane_change;
mod manoeuvre;
mod optimal_handling;
mod poly;
mod response;
mod riccati;
mod state_space;
mod system;
mod transfer;

pub use canonical::Canonical;
pub(crate) use canonical::Intermediates;
pub(crate) use characteristic::GeneralSpeedPolynomials;
pub use characteristic::{CharacteristicPolynomial, SpeedPolynomials};
pub use controllability::{
    Controllability, ModalControllability, UncontrollableSpeed, UncontrollableSpeeds,
    uncontrollable_speeds,
};
pub use feedback::{ClosedLoop, Gains, MAX_GENERAL_SWEEP_SPEEDS, MAX_SCHEDULE_SPEEDS};
pub use handling::{
    HandlingPeak, HandlingQuality, HandlingRow, MAX_HANDLING_POINTS, handling_against_parameter,
    handling_against_speed,
};
pub use human::{
    GainLookup, GainTable, HumanController, HumanGains, HumanLoop, LoopInput, LoopState,
    MAX_GAIN_SPEEDS, NEUROMUSCULAR_DAMPING, NEUROMUSCULAR_FREQUENCY, Neuromuscular, Task,
};
pub use human_loops::{
    Crossover, CrossoverRules, GainSchedule, HumanSweepRow, LoopResponse, LoopTransferFunction,
    MAX_HUMAN_SWEEP_SPEEDS, RiderLoop, hess_gains, human_eigen_sweep,
};
pub use lane_change::{
    LaneChange, LaneChangeRun, LaneKind, MAX_LANE_CHANGE_SAMPLES, lane_change_linear,
    lane_change_nonlinear,
};
pub use manoeuvre::{
    MAX_MANOEUVRE_BREAKS, Manoeuvre, ManoeuvreComparison, ManoeuvreMotion, compare_manoeuvre,
};
pub use optimal_handling::{
    HandlingBound, HandlingCandidate, HandlingStart, MAX_HANDLING_ITERATIONS,
    MAX_HANDLING_PARAMETERS, MAX_HANDLING_STARTS, OptimalHandling, OptimalHandlingSettings,
    judge_handling, optimal_handling,
};
pub use response::{
    GroundPath, InputSignal, MAX_KNOTS, MAX_RESPONSE_TIMES, MAX_RESPONSE_VALUES, TimeResponse,
};
pub use riccati::{Lqr, LqrSchedule, MAX_RICCATI_RESIDUAL, MAX_RICCATI_STATES, care, lqr_schedule};
pub use state_space::StateSpace;
pub use system::{Input, LinearSystem, MAX_SIGNALS, Output, StateVariable, SystemRequest};
pub use transfer::{FrequencyResponse, TransferFunction, origin_zero_speeds};
