//! The linearized Whipple bicycle (Meijaard et al. 2007): canonical matrices, state space and
//! characteristic polynomial.

mod canonical;
mod characteristic;
mod state_space;

pub use canonical::{Canonical, Intermediates};
pub use characteristic::{
    discriminant, hurwitz_delta3, CharacteristicPolynomial, SpeedPolynomials,
};
pub use state_space::{StateSpace, LEAN, LEAN_RATE, STEER, STEER_RATE};
