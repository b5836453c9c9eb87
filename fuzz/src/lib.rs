//! What the parse targets share: any text read as a parameter file in one format.

use whipple::advanced::io::{Format, parse, write};

/// Reads `data` (when it is UTF-8) as a parameter file in `format`: never a panic; an error
/// has a message; a bicycle read writes to TOML and JSON and each reads back to the same text.
pub fn check_parse(data: &[u8], format: Format) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match parse(text, format) {
        Ok(bike) => {
            // Every writer's output reads back (in the writer's own format).
            for format in [Format::Toml, Format::Json] {
                let written = write(&bike, format).expect("a valid bicycle writes");
                let again = parse(&written, format).expect("what was written reads back");
                assert_eq!(
                    write(&again, format).expect("writes again"),
                    written,
                    "a round trip changed the bicycle"
                );
            }
        }
        Err(error) => {
            assert!(!error.to_string().is_empty());
        }
    }
}
