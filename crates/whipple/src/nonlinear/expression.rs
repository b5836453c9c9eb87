//! Rider torques written as expressions of time and the state, such as `0.5*sin(2*t)` or
//! `10*lean + 20*lean_rate`: parsed once (by exmex), checked for unknown names, and turned into
//! a [`TorqueFn`] for [`super::SimulationSettings`]. The command line and the web API read the
//! same language.
//!
//! ```
//! use whipple::nonlinear::TorqueExpression;
//! let torque = TorqueExpression::parse("10*lean + 20*lean_rate")?;
//! assert_eq!(torque.text(), "10*lean + 20*lean_rate");
//! assert!(TorqueExpression::parse("2*foo").is_err());
//! # Ok::<(), whipple::Error>(())
//! ```

use exmex::prelude::*;

use super::settings::TorqueFn;
use super::state::StateView;
use crate::error::{Error, Result};

/// The names an expression may use: time t \[s\], the lean, steer and yaw angles \[rad\], their
/// rates [rad/s] and the forward speed [m/s].
pub const VARIABLES: [&str; 7] = [
    "lean",
    "lean_rate",
    "speed",
    "steer",
    "steer_rate",
    "t",
    "yaw",
];

/// Longest expression accepted, in bytes.
pub const MAX_LENGTH: usize = 1000;

/// A parsed torque expression [N m].
#[derive(Debug, Clone)]
pub struct TorqueExpression {
    text: String,
    expr: FlatEx<f64>,
    /// For each of the expression's variables (in the order exmex wants their values), its
    /// index in [`VARIABLES`].
    slots: Vec<usize>,
}

fn value(slot: usize, t: f64, s: &StateView) -> f64 {
    match slot {
        0 => s.lean,
        1 => s.lean_rate,
        2 => s.speed,
        3 => s.steer,
        4 => s.steer_rate,
        5 => t,
        _ => s.yaw,
    }
}

impl TorqueExpression {
    /// Parses `text`; its names must be among [`VARIABLES`] and it must evaluate to a finite
    /// number at rest (every variable zero).
    pub fn parse(text: &str) -> Result<Self> {
        let invalid = |rule: String| Error::InvalidArgument {
            what: "torque expression",
            rule,
        };
        if text.len() > MAX_LENGTH {
            return Err(invalid(format!(
                "is {} bytes long, more than the limit of {MAX_LENGTH}",
                text.len()
            )));
        }
        let expr =
            exmex::parse::<f64>(text).map_err(|e| invalid(format!("cannot read `{text}`: {e}")))?;
        let mut slots = Vec::with_capacity(VARIABLES.len());
        for name in expr.var_names() {
            let slot = VARIABLES.iter().position(|v| v == name).ok_or_else(|| {
                invalid(format!(
                    "unknown name `{name}` in `{text}` (use {})",
                    VARIABLES.join(", ")
                ))
            })?;
            slots.push(slot);
        }
        let at_rest = expr
            .eval(&vec![0.0; slots.len()])
            .map_err(|e| invalid(format!("cannot evaluate `{text}`: {e}")))?;
        if !at_rest.is_finite() {
            return Err(invalid(format!(
                "`{text}` is not a finite number at rest (t = 0, every angle and rate 0): {at_rest}"
            )));
        }
        Ok(TorqueExpression {
            text: text.to_string(),
            expr,
            slots,
        })
    }

    /// The text it was parsed from.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The torque at time t \[s\] in state s [N m]; NaN when the expression cannot be evaluated
    /// there (a simulation then stops with a non-finite state).
    pub fn eval(&self, t: f64, s: &StateView) -> f64 {
        let mut values = [0.0; VARIABLES.len()];
        for (value_of, &slot) in values.iter_mut().zip(&self.slots) {
            *value_of = value(slot, t, s);
        }
        self.expr
            .eval(&values[..self.slots.len()])
            .unwrap_or(f64::NAN)
    }

    /// The expression as a rider input of a simulation.
    pub fn into_torque(self) -> TorqueFn {
        Box::new(move |t: f64, s: &StateView| self.eval(t, s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn evaluates_with_the_state() -> Result<()> {
        let torque = TorqueExpression::parse("-10*lean - 2*lean_rate + t*speed + 0*yaw")?;
        let s = StateView {
            lean: 0.1,
            lean_rate: -0.5,
            speed: 4.0,
            ..StateView::default()
        };
        assert!((torque.eval(2.0, &s) - (-1.0 + 1.0 + 8.0)).abs() < 1e-15);
        Ok(())
    }

    #[test]
    fn refuses_bad_expressions_by_rule() {
        for (text, rule) in [
            ("sin(t", "cannot read"),
            ("2*foo", "unknown name `foo`"),
            ("1/t", "not a finite number at rest"),
        ] {
            match TorqueExpression::parse(text) {
                Err(Error::InvalidArgument { what, rule: got }) => {
                    assert_eq!(what, "torque expression");
                    assert!(got.contains(rule), "{text}: {got}");
                }
                other => panic!("{text}: {other:?}"),
            }
        }
        assert!(TorqueExpression::parse(&"1+".repeat(600)).is_err());
    }
}
