//! Any bytes as an oscillation record, CSV or MATLAB `.mat`: never a panic. A record that reads
//! goes through the period fit: an answer is finite with σ ≥ 0, or a typed error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::measured::period::fit_period;
use whipple_front::record::{RecordRequest, read_record};

fuzz_target!(|data: &[u8]| {
    for name in ["record.csv", "record.mat"] {
        if let Ok(record) = read_record(data, name, &RecordRequest::default())
            && let Ok(fit) = fit_period(&record.time, &record.signal)
        {
            assert!(fit.period.is_finite() && fit.period_sigma >= 0.0);
        }
    }
});
