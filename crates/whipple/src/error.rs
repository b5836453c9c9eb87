//! The library's error type: one variant per kind of failure, each carrying the context a
//! user needs to mend the input (the field, the value, the rule).

use thiserror::Error;

/// Everything that can go wrong in `whipple`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter breaks a rule of the model (non-finite, out of range, inconsistent).
    #[error("invalid parameter `{field}` = {}: {rule}", short_number(*.value))]
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
    #[error("{}", parse_message(format, *.line, *.column, .field.as_deref(), message))]
    Parse {
        /// `TOML`, `JSON`, `JBike6 .m`, `BicycleParameters .txt`, `HumanControl .txt`, `YAML`.
        format: &'static str,
        /// The key at fault as written in the file (`IBxx`, `rider.m`, `mrider`), when one is.
        field: Option<String>,
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
    /// A rule that sets a gain (Hess 2012's damping and crossover rules for the rider's loops)
    /// cannot be met: `gain` names it as HumanControl's files do (`kDelta`, …).
    #[error("no `{gain}` meets its rule: {rule}")]
    GainRuleUnmet {
        /// The gain (`kDelta`, `kPhiDot`, `kPhi`, `kPsi`, `kY`).
        gain: String,
        /// Why not, in words, with the numbers.
        rule: String,
    },
    /// A speed, range or step given to an analysis is unusable.
    #[error("invalid {what}: {rule}")]
    InvalidArgument {
        /// The argument's name (for example `speeds`, `range`).
        what: &'static str,
        /// What is wrong with it.
        rule: String,
    },
    /// A request asks for more work than a bound allows (for example more integration steps
    /// than a simulation may take).
    #[error("{what}: {rule}")]
    LimitExceeded {
        /// The argument's name (for example `dt`).
        what: &'static str,
        /// The bound and how far the request is past it.
        rule: String,
    },
    /// An integration step (RK4's `dt`) or tolerance (the adaptive integrator's `rtol`) too
    /// coarse for the run: the step cannot resolve the bicycle's fastest mode, or the energy
    /// (conserved but for the rider's work) drifted far beyond what the integrator's accuracy
    /// allows. Never answered with an outcome (fell, completed): the motion computed would be
    /// the integrator's, not the bicycle's.
    #[error("{what} = {} is too large for this run: {reason}; use {what} <= {}", short_number(*.value), short_number(*.suggested))]
    StepTooLarge {
        /// `dt` or `rtol`.
        what: &'static str,
        /// The step \[s\] or tolerance given.
        value: f64,
        /// Why, with the numbers that show it.
        reason: String,
        /// The step or tolerance to use instead (at most this).
        suggested: f64,
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
    #[error("constraint projection diverged after {iterations} iterations (residual {residual:e})")]
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
    /// Warnings were to be refused ([`Checked::strict`](crate::advanced::parameters::Checked::strict)) and the bicycle has
    /// some. A front end words it with the option that asked for it.
    #[error("{count} warning(s) refused: {message}")]
    WarningsRefused {
        /// The first field warned about.
        field: String,
        /// How many warnings.
        count: usize,
        /// Every warning, in words.
        message: String,
    },
    /// The constrained equations of motion could not be solved: the saddle-point matrix
    /// [M Dᵀ; D 0] is singular at this state (for example a lean of ±90°, where the
    /// orientation angles are singular, or a bicycle without inertia in some direction).
    #[error("singular equations of motion: {context}")]
    SingularDynamics {
        /// Where and why.
        context: String,
    },
    /// No steady turn satisfies what was asked (or none could be reached from straight running):
    /// never answered with a point that is not one.
    #[error("no steady turn for {given}: {reason}")]
    NoSteadyTurn {
        /// What was given (speed, lean, steer or radius, in the user's units).
        given: String,
        /// Why not.
        reason: String,
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

/// A number for a message: shortest round-trip text, in exponent form when very large or small,
/// so that a 1e300 never prints as 301 digits.
pub fn short_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A piece of a user's input for a message, cut to at most `max` characters (`…` marks the cut).
pub fn shorten(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        text.to_string()
    } else {
        let head: String = text.chars().take(max.saturating_sub(1)).collect();
        format!("{head}…")
    }
}

fn parse_message(
    format: &str,
    line: usize,
    column: usize,
    field: Option<&str>,
    message: &str,
) -> String {
    let at = match (line, field) {
        (0, Some(field)) => format!("{format} file, `{field}`"),
        (0, None) => format!("{format} file"),
        (_, Some(field)) => format!("{format} file, line {line}, column {column}, `{field}`"),
        (_, None) => format!("{format} syntax error at line {line}, column {column}"),
    };
    format!("{at}: {message}")
}

/// Shorthand used throughout the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
