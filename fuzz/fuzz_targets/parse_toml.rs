//! Any text read as a parameter file (format Toml): never a panic; an error names a field, a
//! line or what is missing; a bicycle read back writes and reads back to the same bicycle.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::parameters::io::{parse, write, Format};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match parse(text, Format::Toml) {
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
});
