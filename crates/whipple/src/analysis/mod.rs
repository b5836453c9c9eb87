//! Questions asked of the models: eigenvalues and eigenvectors, modes, critical speeds, sweeps,
//! linearization of the non-linear model and its validation against the linear one.

pub(crate) mod comparison;
pub(crate) mod design;
pub(crate) mod eigen;
pub(crate) mod linearize;
pub(crate) mod modes;
pub(crate) mod roots;
pub(crate) mod sensitivity;
pub(crate) mod stability;
pub(crate) mod sweep;
pub(crate) mod track;
pub(crate) mod turns;
