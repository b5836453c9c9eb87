//! Questions asked of the models: eigenvalues and eigenvectors, modes, critical speeds, sweeps.

pub mod eigen;
pub mod modes;
pub mod roots;
pub mod stability;
pub mod sweep;
