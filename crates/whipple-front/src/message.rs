//! The library's errors worded for the people who asked: what the library says in terms of
//! its own (a strict reading refused warnings), a front end says in the words the user used to
//! ask (`--strict`, the command line's option, and the same words from the server and Python).

use whipple::Error;
use whipple::advanced::io::UNDETERMINED_FORMAT;

/// The option that asks for a strict reading, as every front end names it in messages.
pub const STRICT_OPTION: &str = "--strict";

/// How each front end names a parameter file's format, for a file whose format the library
/// could not tell.
pub const FORMAT_OPTIONS: &str =
    "--bike-format on the command line, `format` in the web API and in Python";

/// An error's message for the user: the library's own words, except where the library's
/// error stands for an option the user gave ([`Error::WarningsRefused`]: `N warning(s) with
/// --strict: …`) or could give (a file whose format could not be told: [`FORMAT_OPTIONS`]).
///
/// ```
/// let error = whipple::Error::WarningsRefused {
///     field: "IBxx".into(),
///     count: 1,
///     message: "warning: IBxx ...".into(),
/// };
/// assert_eq!(whipple_front::message::message(&error), "1 warning(s) with --strict: warning: IBxx ...");
/// ```
pub fn message(error: &Error) -> String {
    match error {
        Error::WarningsRefused { count, message, .. } => {
            format!("{count} warning(s) with {STRICT_OPTION}: {message}")
        }
        Error::Parse { format, .. } if *format == UNDETERMINED_FORMAT => {
            format!("{error} ({FORMAT_OPTIONS})")
        }
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refused_warnings_name_the_option() {
        let error = Error::WarningsRefused {
            field: "IBxx".into(),
            count: 2,
            message: "first; second".into(),
        };
        assert_eq!(message(&error), "2 warning(s) with --strict: first; second");
        assert!(!error.to_string().contains("--strict"), "{error}");
        let other = Error::NonFinite {
            context: "x".into(),
        };
        assert_eq!(message(&other), other.to_string());
    }

    #[test]
    fn a_file_of_no_known_format_is_told_how_to_name_one() {
        let Err(error) = whipple::advanced::io::Format::detect("bike", "x\ny\n") else {
            panic!("a two-word file has no format");
        };
        let text = message(&error);
        assert!(text.contains("cannot tell the format of bike"), "{text}");
        assert!(text.ends_with(&format!("({FORMAT_OPTIONS})")), "{text}");
        assert!(!error.to_string().contains("--bike-format"), "{error}");
    }
}
