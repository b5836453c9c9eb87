//! The library's error type: one variant per kind of failure, each carrying the context a
//! user needs to mend the input (the field, the value, the rule).

use thiserror::Error;

/// Everything that can go wrong in `whipple`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter breaks a rule of the model (non-finite, out of range, inconsistent).
    #[error("invalid parameter `{field}` = {value}: {rule}")]
    InvalidParameter {
        /// The parameter's name as it is written in files (for example `mB`, `rider.m`).
        field: String,
        /// The offending value (may be NaN or infinite).
        value: f64,
        /// The rule that the value breaks, in words.
        rule: String,
    },
    /// A combination of parameters breaks a rule (for example a mass matrix that is not
    /// positive definite); `fields` names those involved.
    #[error("invalid bicycle ({fields}): {rule}")]
    InvalidBicycle {
        /// The parameters involved, comma separated.
        fields: String,
        /// The rule, in words, with the numbers that break it.
        rule: String,
    },
    /// A parameter file could not be read: syntax, unknown or missing keys, wrong types.
    #[error("{format} syntax error at line {line}, column {column}: {message}")]
    Parse {
        /// `TOML`, `JSON` or `JBike6 .m`.
        format: &'static str,
        /// 1-based line of the error (0 when unknown).
        line: usize,
        /// 1-based column of the error (0 when unknown).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// No preset of that name.
    #[error("unknown preset `{name}` (known presets: {known})")]
    UnknownPreset {
        /// The name asked for.
        name: String,
        /// The names that exist, comma separated.
        known: String,
    },
    /// A speed, range or step given to an analysis is unusable.
    #[error("invalid {what}: {rule}")]
    InvalidArgument {
        /// The argument's name (for example `speeds`, `range`).
        what: &'static str,
        /// What is wrong with it.
        rule: String,
    },
    /// A numerical method did not reach its tolerance within its iteration bound.
    #[error("{method} did not converge after {iterations} iterations (residual {residual:e})")]
    NoConvergence {
        /// The method that failed.
        method: &'static str,
        /// How many iterations were made.
        iterations: usize,
        /// The residual reached.
        residual: f64,
    },
    /// A computation produced a NaN or an infinity.
    #[error("non-finite result in {context}")]
    NonFinite {
        /// Where it appeared.
        context: String,
    },
    /// Newton iteration of the non-linear model's positions onto its holonomic constraints did
    /// not reach its tolerance within its iteration bound (or its linear system was singular).
    #[error(
        "constraint projection diverged after {iterations} iterations (residual {residual:e})"
    )]
    ProjectionDiverged {
        /// Newton iterations made.
        iterations: usize,
        /// Largest absolute holonomic residual reached [m or dimensionless].
        residual: f64,
    },
    /// The non-linear model's state holds a NaN or an infinity at time `t`.
    #[error("non-finite state at t = {t} s")]
    NonFiniteState {
        /// Simulation time \[s\].
        t: f64,
    },
    /// The constrained equations of motion could not be solved: the saddle-point matrix
    /// [M Dᵀ; D 0] is singular at this state (for example a lean of ±90°, where the
    /// orientation angles are singular, or a bicycle without inertia in some direction).
    #[error("singular equations of motion: {context}")]
    SingularDynamics {
        /// Where and why.
        context: String,
    },
    /// Double precision cannot give this answer to the accuracy that is printed: an overflow, an
    /// underflow or a cancellation (for example a mass matrix whose determinant is lost to
    /// round-off, or a leading coefficient whose sign round-off cannot decide). Nothing is computed
    /// into a number that cannot be stood behind.
    #[error("accuracy lost in {quantity}: {reason}")]
    AccuracyLost {
        /// What was being computed (for example `critical speeds`, `eigenvalues at 5 m/s`).
        quantity: String,
        /// Why, with the numbers that show it.
        reason: String,
    },
}

/// Shorthand used throughout the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
