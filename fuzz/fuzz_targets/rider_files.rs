//! Any bytes as a HumanControl gains file (`<Name>SteerGains.txt`) or as BicycleParameters'
//! `MooreRiderLean2012` set (a JSON object): never a panic. A table that reads gives finite
//! gains at any finite speed (extrapolated or not); a rider-lean set that reads builds the
//! five-body model or gives a typed error, and its linearization at 5 m/s is finite or an error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::io::{read_gains, read_moore_rider_lean2012};
use whipple::advanced::nonlinear::LeanModel;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(table) = read_gains(text) {
        for speed in [-1.0, 0.0, 2.5, 5.0, 1e3] {
            if let Ok(at) = table.at(speed) {
                assert!(at.gains.to_array().iter().all(|k| k.is_finite()));
            }
        }
    }
    if let Ok(parameters) = read_moore_rider_lean2012(text) {
        if let Ok(model) = LeanModel::new(&parameters) {
            if let Ok((a, b)) = model.linearize(5.0) {
                assert!(a.iter().chain(b.iter()).all(|x| x.is_finite()));
            }
        }
    }
});
