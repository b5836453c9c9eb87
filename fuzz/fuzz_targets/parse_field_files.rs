//! Any text read as one of the field's files (BicycleParameters' `.txt` and YAML, HumanControl's
//! `.txt`; the first byte picks which): never a panic; a bicycle read writes to TOML and reads
//! back to the same text.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::io::{Format, parse, write};

const FIELD_FORMATS: [Format; 3] = [
    Format::BicycleParametersTxt,
    Format::HumanControlTxt,
    Format::Yaml,
];

fuzz_target!(|data: &[u8]| {
    let Some((&which, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let format = FIELD_FORMATS[usize::from(which) % FIELD_FORMATS.len()];
    match parse(text, format) {
        Ok(bike) => {
            let written = write(&bike, Format::Toml).expect("a valid bicycle writes");
            let again = parse(&written, Format::Toml).expect("what was written reads back");
            assert_eq!(write(&again, Format::Toml).expect("writes again"), written);
        }
        Err(error) => assert!(!error.to_string().is_empty()),
    }
});
