//! Any text as a torque expression: never a panic, never an unbounded evaluation; an accepted
//! expression evaluates to a finite number at rest, as `parse` promises.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::nonlinear::{StateView, TorqueExpression};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match TorqueExpression::parse(text) {
        Ok(expression) => {
            assert!(expression.eval(0.0, &StateView::default()).is_finite());
            let s = StateView {
                lean: 0.1,
                steer: -0.2,
                lean_rate: 1e300,
                speed: 5.0,
                ..StateView::default()
            };
            // Any value, NaN included, but no panic.
            let _ = expression.eval(1.5, &s);
        }
        Err(error) => {
            let message = error.to_string();
            // Messages quote what was typed with control characters escaped: one line.
            assert!(!message.contains('\n'), "{message}");
        }
    }
});
