//! The linearized Whipple bicycle (Meijaard et al. 2007): canonical matrices, state space and
//! characteristic polynomial.

mod canonical;
mod characteristic;
mod state_space;

pub use canonical::Canonical;
pub use characteristic::{CharacteristicPolynomial, SpeedPolynomials};
pub use state_space::StateSpace;
