//! Questions asked of the models: eigenvalues and eigenvectors, modes, critical speeds, sweeps,
//! linearization of the non-linear model and its validation against the linear one.

pub mod comparison;
pub mod design;
pub mod eigen;
pub mod linearize;
pub mod modes;
pub mod roots;
pub mod sensitivity;
pub mod stability;
pub mod sweep;
pub mod turns;
