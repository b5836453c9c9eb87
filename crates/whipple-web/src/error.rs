//! The API's one error shape: `{"error": {"kind", "message", "field", "rule", ...}}` with the
//! HTTP status that fits, built from the library's typed errors where they are the cause.

use http::StatusCode;
use serde::Serialize;
use whipple::Error;

/// An error answered to a client: status code plus the JSON body's fields (boxed, so that
/// `Result<_, ApiError>` stays small).
#[derive(Debug, Clone, PartialEq)]
pub struct ApiError {
    /// HTTP status.
    pub status: StatusCode,
    /// What the body says.
    pub body: Box<ErrorBody>,
    /// Seconds to wait before trying again, sent as `Retry-After` (with 503 `busy`).
    pub retry_after: Option<u64>,
}

/// The `error` object of an error response.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorBody {
    /// Machine-readable kind (`invalid_parameter`, `invalid_bicycle`, `parse`, `bad_json`,
    /// `invalid_request`, `limit_exceeded`, `step_too_large`, `too_large`, `unknown_preset`,
    /// `not_found`, `method_not_allowed`, `misdirected_request`, `forbidden_origin`,
    /// `unsupported_media_type`, `timeout`, `busy`, `numerical`, `internal`).
    pub kind: &'static str,
    /// The whole message, for people.
    pub message: String,
    /// The parameter or argument at fault, as written in files (`mB`, `mrider`,
    /// `Irider(1)`, `speeds`); several comma separated for a rule on a combination; null when
    /// none.
    pub field: Option<String>,
    /// The rule broken, in words; null when none.
    pub rule: Option<String>,
    /// The offending value, when one number is at fault.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// Line of a parse error in a parameter file (1-based).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// Column of a parse error in a parameter file (1-based).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub column: Option<usize>,
}

impl ApiError {
    /// An error with a kind and message only.
    pub fn new(status: StatusCode, kind: &'static str, message: impl Into<String>) -> Self {
        ApiError {
            status,
            body: Box::new(ErrorBody {
                kind,
                message: message.into(),
                field: None,
                rule: None,
                value: None,
                line: None,
                column: None,
            }),
            retry_after: None,
        }
    }

    /// The same error asking the client to try again in `seconds` (`Retry-After`).
    pub fn retry_after(mut self, seconds: u64) -> Self {
        self.retry_after = Some(seconds);
        self
    }

    /// The same error naming the field at fault and the rule broken.
    pub fn at(mut self, field: impl Into<String>, rule: impl Into<String>) -> Self {
        self.body.field = Some(field.into());
        self.body.rule = Some(rule.into());
        self
    }

    /// The same error, naming the request's field it came from (the rule kept).
    pub(crate) fn in_field(mut self, field: impl Into<String>) -> Self {
        self.body.field = Some(field.into());
        self
    }

    pub(crate) fn internal(message: impl Into<String>) -> Self {
        ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "internal", message)
    }
}

impl From<Error> for ApiError {
    fn from(error: Error) -> Self {
        let message = whipple_front::message::message(&error);
        let unprocessable = StatusCode::UNPROCESSABLE_ENTITY;
        match error {
            Error::InvalidParameter { field, value, rule } => {
                let mut e =
                    ApiError::new(unprocessable, "invalid_parameter", message).at(field, rule);
                e.body.value = value.is_finite().then_some(value);
                e
            }
            Error::InvalidBicycle { fields, rule } => {
                ApiError::new(unprocessable, "invalid_bicycle", message).at(fields, rule)
            }
            Error::Parse {
                line,
                column,
                message: what,
                field,
                ..
            } => {
                let mut e = ApiError::new(unprocessable, "parse", message);
                e.body.field = field.or_else(|| quoted_field(&what));
                e.body.rule = Some(what);
                e.body.line = (line > 0).then_some(line);
                e.body.column = (column > 0).then_some(column);
                e
            }
            Error::UnknownPreset { name, .. } => {
                ApiError::new(StatusCode::NOT_FOUND, "unknown_preset", message)
                    .at("name", format!("no preset is called `{name}`"))
            }
            Error::InvalidArgument { what, rule } => {
                ApiError::new(unprocessable, "invalid_argument", message).at(what, rule)
            }
            Error::AccuracyLost { .. } => ApiError::new(unprocessable, "accuracy_lost", message),
            Error::LimitExceeded { what, rule } => {
                ApiError::new(unprocessable, "limit_exceeded", message).at(what, rule)
            }
            // The integrator's step or tolerance cannot resolve the run: no outcome, the step
            // to use in the rule.
            Error::StepTooLarge {
                what,
                value,
                reason,
                suggested,
            } => {
                let rule = format!(
                    "{reason}; use {what} <= {}",
                    whipple::advanced::short_number(suggested)
                );
                let mut e = ApiError::new(unprocessable, "step_too_large", message).at(what, rule);
                e.body.value = value.is_finite().then_some(value);
                e
            }
            Error::WarningsRefused { field, .. } => ApiError::new(unprocessable, "strict", message)
                .at(field, "a warning, with strict set"),
            // A user's numbers can drive any numerical failure: 422 naming it, never a 500.
            Error::NoConvergence { .. }
            | Error::NonFinite { .. }
            | Error::ProjectionDiverged { .. }
            | Error::NonFiniteState { .. }
            | Error::SingularDynamics { .. } => ApiError::new(unprocessable, "numerical", message),
            // The turn asked for does not exist (or is not reached from straight running).
            Error::NoSteadyTurn { .. } => ApiError::new(unprocessable, "no_steady_turn", message),
            Error::GainRuleUnmet { gain, rule } => {
                ApiError::new(unprocessable, "gain_rule_unmet", message).at(gain, rule)
            }
            _ => ApiError::internal(message),
        }
    }
}

/// The field named in serde's "missing field `x`" / "unknown field `x`" messages.
pub(crate) fn quoted_field(message: &str) -> Option<String> {
    for prefix in [
        "missing field `",
        "unknown field `",
        "duplicate field `",
        "duplicate key `",
    ] {
        if let Some(rest) = message.strip_prefix(prefix) {
            return rest.split('`').next().map(str::to_string);
        }
    }
    None
}

#[derive(Serialize)]
struct Envelope<'a> {
    error: &'a ErrorBody,
}

impl ApiError {
    /// The JSON body answered: `{"error": {...}}`.
    pub fn json(&self) -> Vec<u8> {
        // Strings, numbers and options only: writing it cannot fail; were it to, the kind
        // and message still go out.
        serde_json::to_vec(&Envelope { error: &self.body }).unwrap_or_else(|_| {
            format!(
                "{{\"error\":{{\"kind\":\"{}\",\"message\":\"the error could not be written\"}}}}",
                self.body.kind
            )
            .into_bytes()
        })
    }
}

/// The last line of an answer told line by line (`server.rs`): the status the answer would
/// have had, the error, and the seconds to wait before asking again where the server is busy.
#[cfg(feature = "server")]
#[derive(Serialize)]
struct Line<'a> {
    status: u16,
    error: &'a ErrorBody,
    #[serde(skip_serializing_if = "Option::is_none")]
    retry_after: Option<u64>,
}

#[cfg(feature = "server")]
impl ApiError {
    /// The error as the last line of an answer told line by line: `{"status": 422, "error":
    /// {...}}` and a newline.
    pub(crate) fn line(&self) -> Vec<u8> {
        let line = Line {
            status: self.status.as_u16(),
            error: &self.body,
            retry_after: self.retry_after,
        };
        let mut bytes = serde_json::to_vec(&line).unwrap_or_else(|_| {
            format!(
                "{{\"status\":{},\"error\":{{\"kind\":\"{}\",\"message\":\"the error could not be written\"}}}}",
                self.status.as_u16(),
                self.body.kind
            )
            .into_bytes()
        });
        bytes.push(b'\n');
        bytes
    }
}

#[cfg(feature = "server")]
impl axum::response::IntoResponse for ApiError {
    fn into_response(self) -> axum::response::Response {
        use axum::http::{HeaderValue, header};
        let mut response = (
            self.status,
            [(
                header::CONTENT_TYPE,
                HeaderValue::from_static("application/json"),
            )],
            self.json(),
        )
            .into_response();
        if let Some(seconds) = self.retry_after {
            response
                .headers_mut()
                .insert(axum::http::header::RETRY_AFTER, seconds.into());
        }
        response
    }
}
