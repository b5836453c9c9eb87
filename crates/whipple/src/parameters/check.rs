//! What a check of a bicycle says besides refusing it: warnings (a measured tensor that breaks
//! the triangle inequality, a centre of mass below the ground, redundant geometry that disagrees)
//! and notes (a key of another model that the Whipple model does not use). A warning never
//! stops a computation whose equations stay well defined; a strict reading
//! ([`strict`]) makes it an error.

use serde::Serialize;

use crate::error::{Error, Result};

/// How much a notice matters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// For information (a key not used by the Whipple model, a redundant value that agrees).
    Note,
    /// Something a measured bicycle may well have but that deserves a look; a strict reading refuses it.
    Warning,
}

/// One warning or note about a bicycle, naming the quantity as the user wrote it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Notice {
    /// Warning or note.
    pub severity: Severity,
    /// The fields involved, as written in the file (`IByy`, `IBxx, IBzz, IBxz`, `d3`, `xcl`).
    pub field: String,
    /// The whole sentence.
    pub message: String,
    /// The size of the violation in percent, where one applies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub violation_percent: Option<f64>,
    /// Which analyses it affects, in words.
    pub affects: String,
}

impl Notice {
    pub(crate) fn warning(
        field: impl Into<String>,
        message: impl Into<String>,
        violation_percent: Option<f64>,
        affects: impl Into<String>,
    ) -> Self {
        Notice {
            severity: Severity::Warning,
            field: field.into(),
            message: message.into(),
            // A violation against a zero or overflowing reference has no finite percentage
            // (the message says it in words); JSON would print it as null.
            violation_percent: violation_percent.filter(|p| p.is_finite()),
            affects: affects.into(),
        }
    }

    pub(crate) fn note(field: impl Into<String>, message: impl Into<String>) -> Self {
        Notice {
            severity: Severity::Note,
            field: field.into(),
            message: message.into(),
            violation_percent: None,
            affects: "none: not used by the Whipple model".into(),
        }
    }

    /// `true` for a warning.
    pub fn is_warning(&self) -> bool {
        self.severity == Severity::Warning
    }
}

impl std::fmt::Display for Notice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let label = match self.severity {
            Severity::Note => "note",
            Severity::Warning => "warning",
        };
        write!(f, "{label}: `{}`: {}", self.field, self.message)?;
        if self.severity == Severity::Warning {
            write!(f, " (affects: {})", self.affects)?;
        }
        Ok(())
    }
}

/// Turns the warnings among `notices` into an error (notes pass): what a strict reading asks
/// for.
pub(crate) fn strict(notices: &[Notice]) -> Result<()> {
    let warnings: Vec<&Notice> = notices.iter().filter(|n| n.is_warning()).collect();
    match warnings.first() {
        None => Ok(()),
        Some(first) => Err(Error::WarningsRefused {
            field: first.field.clone(),
            count: warnings.len(),
            message: warnings
                .iter()
                .map(|w| w.to_string())
                .collect::<Vec<_>>()
                .join("; "),
        }),
    }
}

/// Relative size of a violation `excess / reference`, in percent.
pub(crate) fn percent(excess: f64, reference: f64) -> f64 {
    if reference.abs() > 0.0 {
        100.0 * excess / reference.abs()
    } else {
        f64::INFINITY
    }
}
