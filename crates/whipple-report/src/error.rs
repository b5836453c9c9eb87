//! The report crate's error type.

use thiserror::Error;

/// Everything that can go wrong while drawing a figure or writing a table.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum Error {
    /// The embedded font could not be registered with the plotting library.
    #[error("the embedded font {name} could not be loaded")]
    Font {
        /// The font's name.
        name: &'static str,
    },
    /// The plotting library failed while drawing.
    #[error("drawing the {figure} failed: {message}")]
    Draw {
        /// Which figure was being drawn.
        figure: &'static str,
        /// The plotting library's message.
        message: String,
    },
    /// Encoding the PNG image failed.
    #[error("encoding PNG failed: {message}")]
    Encode {
        /// The encoder's message.
        message: String,
    },
    /// The output format could not be told from a file name.
    #[error("cannot tell the figure format from `{name}`: use a .svg or .png file name")]
    UnknownFormat {
        /// The file name (or extension) given.
        name: String,
    },
    /// An option or input breaks a rule (for example an empty or reversed axis range).
    #[error("invalid {what}: {rule}")]
    InvalidArgument {
        /// What was invalid.
        what: &'static str,
        /// The rule it breaks, with the value.
        rule: String,
    },
}

/// `Result` with the report crate's [`enum@Error`].
pub type Result<T> = std::result::Result<T, Error>;
