//! Pendulum periods fitted to synthetic records of known period, damping and noise.

use std::f64::consts::TAU;

use whipple::Error;
use whipple::advanced::measured::period::{
    MIN_SAMPLES, decay_window, fit_period, fit_period_sampled, index, uniform_time,
};

/// A reproducible normal deviate stream (xorshift64* and Box–Muller), so the tests need no
/// random crate and never change.
struct Noise(u64);

impl Noise {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        (-2.0 * whipple::math::ln(self.uniform())).sqrt() * whipple::math::cos(TAU * self.uniform())
    }
}

/// A decaying oscillation of period `period` and damping ratio `zeta` sampled at `rate`,
/// with Gaussian noise of standard deviation `noise`.
fn record(
    samples: usize,
    rate: f64,
    period: f64,
    zeta: f64,
    noise: f64,
    seed: u64,
) -> (Vec<f64>, Vec<f64>) {
    let omega_d = TAU / period;
    let omega_n = omega_d / (1.0 - zeta * zeta).sqrt();
    let mut stream = Noise(seed);
    let time = uniform_time(samples, rate).expect("a positive rate");
    let signal = time
        .iter()
        .map(|t| {
            1.2 + whipple::math::exp(-zeta * omega_n * t)
                * (0.8 * whipple::math::sin(omega_d * t + 0.7))
                + noise * stream.normal()
        })
        .collect();
    (time, signal)
}

#[test]
fn noiseless_record_gives_its_period_and_damping_exactly() -> Result<(), Error> {
    let (time, signal) = record(3000, 1000.0, 1.59, 0.009, 0.0, 1);
    let fit = fit_period(&time, &signal)?;
    assert!((fit.period - 1.59).abs() < 1e-12 * 1.59, "{}", fit.period);
    assert!(
        (fit.damping_ratio - 0.009).abs() < 1e-11,
        "{}",
        fit.damping_ratio
    );
    assert!((fit.parameters[index::OFFSET] - 1.2).abs() < 1e-12);
    assert!((fit.amplitude - 0.8).abs() < 1e-11);
    assert!(fit.residual_rms < 1e-12);
    assert!((fit.evaluate(0.5) - signal[500]).abs() < 1e-12);
    Ok(())
}

#[test]
fn strongly_damped_and_fast_records_are_found() -> Result<(), Error> {
    // ζ = 0.15: the swing falls to a fortieth in four periods; a period of 12 samples.
    for (period, zeta, rate) in [(0.8, 0.15, 200.0), (0.06, 0.002, 200.0), (3.0, 0.0, 50.0)] {
        let (time, signal) = record(600, rate, period, zeta, 0.0, 2);
        let fit = fit_period(&time, &signal)?;
        assert!(
            (fit.period - period).abs() < 1e-10 * period,
            "{period}: {}",
            fit.period
        );
        assert!(
            (fit.damping_ratio - zeta).abs() < 1e-9,
            "{zeta}: {}",
            fit.damping_ratio
        );
    }
    Ok(())
}

/// The period recovered within its σ (|error| < 3σ for every one of 20 noisy records, and
/// the errors' spread matching the σ reported), and σ falling as 1/√N.
#[test]
fn noisy_records_give_their_period_within_sigma_and_sigma_falls_as_one_over_root_n()
-> Result<(), Error> {
    let true_period = 1.59;
    let mut sigmas = Vec::new();
    for samples in [2000, 8000] {
        let mut squared_z = 0.0;
        let mut sigma_mean = 0.0;
        let trials = 20;
        for seed in 0..trials {
            let (time, signal) = record(
                samples,
                500.0 * samples as f64 / 2000.0,
                true_period,
                0.01,
                0.05,
                10 + seed,
            );
            let fit = fit_period(&time, &signal)?;
            let z = (fit.period - true_period) / fit.period_sigma;
            assert!(z.abs() < 4.0, "N = {samples}, seed {seed}: error {z} σ");
            assert!((fit.residual_sigma - 0.05).abs() < 0.005);
            squared_z += z * z;
            sigma_mean += fit.period_sigma / trials as f64;
        }
        // χ² with 20 degrees of freedom: 99.9 % of it lies in [5.9, 45.3].
        assert!(
            (5.9..45.3).contains(&squared_z),
            "N = {samples}: Σz² = {squared_z}"
        );
        sigmas.push(sigma_mean);
    }
    // Four times the samples over the same 4 s: σ halves (to 5 %).
    let ratio = sigmas[0] / sigmas[1];
    assert!((ratio - 2.0).abs() < 0.1, "σ ratio {ratio}");
    Ok(())
}

#[test]
fn sampled_record_equals_the_record_with_its_times() -> Result<(), Error> {
    let (time, signal) = record(1500, 250.0, 0.9, 0.02, 0.01, 3);
    let a = fit_period(&time, &signal)?;
    let b = fit_period_sampled(&signal, 250.0)?;
    assert!((a.period - b.period).abs() < 1e-12);
    // A clock started elsewhere changes the phase, not the period.
    let shifted: Vec<f64> = time.iter().map(|t| t + 100.0).collect();
    let c = fit_period(&shifted, &signal)?;
    assert!((a.period - c.period).abs() < 1e-10);
    assert!((a.evaluate(1.0) - c.evaluate(101.0)).abs() < 1e-9);
    Ok(())
}

#[test]
fn decay_window_keeps_the_largest_swing_to_a_tenth_of_it() -> Result<(), Error> {
    let (_, signal) = record(4000, 100.0, 1.0, 0.05, 0.0, 4);
    let window = decay_window(&signal, 0.1)?;
    let mean = signal.iter().sum::<f64>() / signal.len() as f64;
    let largest = signal.iter().map(|y| (y - mean).abs()).fold(0.0, f64::max);
    assert!(((signal[window.start] - mean).abs() - largest).abs() < 1e-15);
    assert!(signal[window.end] - mean > 0.1 * largest);
    assert!(
        signal[window.end + 1..]
            .iter()
            .all(|y| y - mean <= 0.1 * largest)
    );
    Ok(())
}

fn rule_of(error: Error) -> (String, String) {
    match error {
        Error::InvalidArgument { what, rule } => (what.to_string(), rule),
        Error::InvalidParameter { field, rule, .. } => (field, rule),
        other => (String::new(), other.to_string()),
    }
}

#[test]
fn bad_records_are_refused_naming_the_field() {
    let (time, signal) = record(500, 100.0, 1.0, 0.01, 0.0, 5);
    let few = fit_period(&time[..MIN_SAMPLES - 1], &signal[..MIN_SAMPLES - 1]).unwrap_err();
    assert_eq!(rule_of(few).0, "signal");

    let mut nan = signal.clone();
    nan[7] = f64::NAN;
    let (what, rule) = rule_of(fit_period(&time, &nan).unwrap_err());
    assert_eq!(what, "signal");
    assert!(rule.contains("sample 8"), "{rule}");

    let mut backwards = time.clone();
    backwards[9] = backwards[8];
    let (what, rule) = rule_of(fit_period(&backwards, &signal).unwrap_err());
    assert_eq!(what, "time");
    assert!(rule.contains("sample 10"), "{rule}");

    let (what, _) = rule_of(fit_period(&time[..400], &signal).unwrap_err());
    assert_eq!(what, "time");

    let flat = vec![2.0; 500];
    let (_, rule) = rule_of(fit_period(&time, &flat).unwrap_err());
    assert!(rule.contains("no oscillation found"), "{rule}");

    // Less than one swing: a ramp.
    let ramp: Vec<f64> = time.iter().map(|t| t * t).collect();
    let (_, rule) = rule_of(fit_period(&time, &ramp).unwrap_err());
    assert!(rule.contains("no oscillation found"), "{rule}");

    let (what, _) = rule_of(uniform_time(100, 0.0).unwrap_err());
    assert_eq!(what, "sample rate");
    let (what, _) = rule_of(decay_window(&signal, 1.5).unwrap_err());
    assert_eq!(what, "trim");
}
