//! Any text read as a parameter file (format Toml): never a panic; an error names a field, a
//! line or what is missing; a bicycle read back writes and reads back to the same bicycle.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::io::Format;

fuzz_target!(|data: &[u8]| whipple_fuzz::check_parse(data, Format::Toml));
