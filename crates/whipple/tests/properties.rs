//! Property tests of the torque expressions: any text is parsed or refused on one
//! line, never a panic; generated expressions evaluate as Rust's arithmetic does. (The parsers
//! and writers of bicycle files have theirs in `file_messages.rs` and `round_trip.rs`.) The
//! same inputs the fuzz targets in `fuzz/` explore for hours, a few hundred cases here.

use proptest::prelude::*;
use whipple::advanced::io::{Format, parse};
use whipple::advanced::nonlinear::{
    MAX_EXPRESSION_DEPTH, MAX_EXPRESSION_LENGTH, StateView, TorqueExpression,
};

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]
    /// Any text as a torque expression: parsed or refused on one line, never a panic; an
    /// accepted one is finite at rest.
    #[test]
    fn any_text_as_a_torque_expression(text in "[0-9a-z_+\\-*/^(), .eE\\n\\u{7f}π]{0,80}") {
        match TorqueExpression::parse(&text) {
            Ok(expression) => {
                prop_assert!(expression.eval(0.0, &StateView::default()).is_finite());
            }
            Err(e) => {
                let message = e.to_string();
                prop_assert!(!message.contains('\n'), "{}", message);
            }
        }
    }

    /// Expressions built from the grammar are accepted and evaluate as the same arithmetic in
    /// Rust does.
    #[test]
    fn generated_expressions_evaluate_as_rust_does(
        a in -1e3f64..1e3, b in 0.1f64..1e3, c in -10f64..10.0, t in 0f64..10.0,
    ) {
        let text = format!("{a:e}*t + {b:e}/(1 + t^2) - sin({c:e}*t)");
        let expression = TorqueExpression::parse(&text)
            .map_err(|e| TestCaseError::fail(format!("{text}: {e}")))?;
        let expected = a * t + b / (1.0 + t * t) - whipple::math::sin(c * t);
        let got = expression.eval(t, &StateView::default());
        prop_assert!((got - expected).abs() <= 1e-12 * (1.0 + expected.abs()), "{} at t = {}: {} vs {}", text, t, got, expected);
    }
}

/// A syntax error in a long one-line file echoed the whole line: the message stays short. Every
/// format listed must refuse the line (a format that accepted it would leave nothing checked).
#[test]
fn a_syntax_error_in_a_long_line_gives_a_short_message() {
    let long = format!("name = \"{}\" x", "a".repeat(1_000_000));
    for format in [Format::Toml, Format::Json, Format::Jbike6M] {
        match parse(&long, format) {
            Ok(_) => panic!("{format:?}: a line with a stray `x` was accepted"),
            Err(e) => {
                let message = e.to_string();
                assert!(message.len() < 2_000, "{format:?}: {} bytes", message.len());
                assert!(
                    !message.contains(&"a".repeat(100)),
                    "{format:?}: {message:.300}"
                );
            }
        }
    }
}

/// Hostile lengths and nesting are refused with the limit named, without deep recursion.
#[test]
fn torque_expressions_are_bounded() {
    let long = "1+".repeat(MAX_EXPRESSION_LENGTH) + "1";
    let err = TorqueExpression::parse(&long)
        .expect_err("too long")
        .to_string();
    assert!(err.contains(&MAX_EXPRESSION_LENGTH.to_string()), "{err}");
    let deep = format!(
        "{}1{}",
        "(".repeat(MAX_EXPRESSION_DEPTH + 1),
        ")".repeat(MAX_EXPRESSION_DEPTH + 1)
    );
    let err = TorqueExpression::parse(&deep)
        .expect_err("too deep")
        .to_string();
    assert!(
        err.contains("nest") || err.contains(&MAX_EXPRESSION_DEPTH.to_string()),
        "{err}"
    );
    // A long run of signs is nesting too.
    let signs = format!("{}1", "-".repeat(500));
    assert!(TorqueExpression::parse(&signs).is_err());
}
