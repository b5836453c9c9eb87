//! The library's errors worded for the people who asked: what the library says in terms of
//! its own (a strict reading refused warnings), a front end says in the words the user used to
//! ask (`--strict`, the command line's option, and the same words from the server and Python).

use whipple::Error;

/// The option that asks for a strict reading, as every front end names it in messages.
pub const STRICT_OPTION: &str = "--strict";

/// An error's message for the user: the library's own words, except where the library's
/// error stands for an option the user gave ([`Error::WarningsRefused`]: `N warning(s) with
/// --strict: …`).
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
}
