//! Any bytes as a BicycleParameters `*Measured.txt`: never a panic. A file that reads and
//! passes its check goes through the whole pipeline (values, σ from dual numbers, covariance):
//! an answer is finite, or a typed error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::measured::{MeasuredParameters, read_measurements};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(file) = read_measurements(text) else {
        return;
    };
    if let Ok(result) = MeasuredParameters::new(&file.measurements) {
        assert!(result.sigma.values().all(|s| s.is_finite() && *s >= 0.0));
    }
});
