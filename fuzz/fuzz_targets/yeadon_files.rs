//! Any bytes as `yeadon`'s measurement or configuration file: never a panic. Measurements that
//! read are put through the Yeadon model in the zero configuration: the body's mass, mass centre
//! and inertia are finite, or a typed error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple::advanced::rider::{
    YeadonConfiguration, read_yeadon_configuration, read_yeadon_measurements, yeadon_body,
};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = read_yeadon_configuration(text);
    let Ok(measurements) = read_yeadon_measurements(text) else {
        return;
    };
    if let Ok(body) = yeadon_body(&measurements, &YeadonConfiguration::zero()) {
        assert!(body.mass.is_finite() && body.mass > 0.0);
        assert!(body.center_of_mass.iter().chain(body.inertia.iter()).all(|x| x.is_finite()));
    }
});
