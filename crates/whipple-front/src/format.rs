//! Numbers as the front ends write them in results (tables, text, CSV): one home for each way
//! of writing one. Numbers in messages are the library's ([`whipple::advanced::short_number`]); numbers
//! in parameter files are its writers'.

/// A result as tables and text outputs print it: the shortest text that reads back as the same
/// f64, in exponent form when very large or small (the rule of [`whipple::advanced::short_number`]), and
/// negative zero as `0` (it carries no meaning in a table of results). `None` for NaN and the
/// infinities, which no result is printed as.
///
/// ```
/// use whipple_front::format::number;
/// assert_eq!(number(4.25).as_deref(), Some("4.25"));
/// assert_eq!(number(-0.0).as_deref(), Some("0"));
/// assert_eq!(number(1e300).as_deref(), Some("1e300"));
/// assert_eq!(number(f64::NAN), None);
/// ```
pub fn number(x: f64) -> Option<String> {
    // -0 + 0 is +0; every other number is unchanged by adding zero.
    x.is_finite()
        .then(|| whipple::advanced::short_number(x + 0.0))
}

/// A number with a fixed count of decimals, trailing zeros kept for alignment (`4.2900`).
///
/// ```
/// assert_eq!(whipple_front::format::fixed(4.29, 4), "4.2900");
/// ```
pub fn fixed(x: f64, digits: usize) -> String {
    format!("{x:.digits$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thresholds of the exponent form, on both sides, and the signs.
    #[test]
    fn results_print_shortest_with_an_exponent_at_the_extremes() {
        for (x, text) in [
            (0.0, "0"),
            (-0.0, "0"),
            (1.0, "1"),
            (-2.5, "-2.5"),
            (0.1 + 0.2, "0.30000000000000004"),
            (1e-5, "0.00001"),
            (9.99e-6, "9.99e-6"),
            (-3e-7, "-3e-7"),
            (9999999999999998.0, "9999999999999998"),
            (1e16, "1e16"),
            (-2.5e20, "-2.5e20"),
        ] {
            assert_eq!(number(x).as_deref(), Some(text), "{x:e}");
        }
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(number(x), None);
        }
    }

    #[test]
    fn fixed_keeps_its_decimals() {
        assert_eq!(fixed(1.0, 3), "1.000");
        assert_eq!(fixed(-0.00049, 3), "-0.000");
        assert_eq!(fixed(2.5, 0), "2");
    }
}
