//! The linearized Whipple bicycle (Meijaard et al. 2007): canonical matrices, state space,
//! characteristic polynomial, and the bicycle as a linear system with named inputs and outputs
//! and its transfer functions.

mod canonical;
mod characteristic;
mod controllability;
mod state_space;
mod system;
mod transfer;

pub use canonical::Canonical;
pub use characteristic::{CharacteristicPolynomial, SpeedPolynomials};
pub use controllability::{
    Controllability, ModalControllability, UncontrollableSpeed, UncontrollableSpeeds,
    uncontrollable_speeds,
};
pub use state_space::StateSpace;
pub use system::{Input, LinearSystem, MAX_SIGNALS, Output, StateVariable, SystemRequest};
pub use transfer::{FrequencyResponse, TransferFunction, origin_zero_speeds};
