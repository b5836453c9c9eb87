//! A pendulum's period from its oscillation record: the decaying oscillation
//!
//! y(t) = c + e^{−σt} (a sin ω_d t + b cos ω_d t)
//!
//! fitted to the samples (tᵢ, yᵢ) by non-linear least squares (Levenberg–Marquardt, the
//! Jacobian exact by dual numbers), as BicycleParameters' `period.py` fits its rate-gyro records
//! (Moore 2012 §2.4). Its five parameters are written here with the decay rate σ = ζω_n and the
//! damped angular frequency ω_d instead of BicycleParameters' ζ and ω_n: the same curves and the
//! same minimum, with the period T = 2π/ω_d read off one parameter. Time is counted from the
//! first sample.
//!
//! Uncertainty, as BicycleParameters computes it: the parameters' covariance is
//! s² (JᵀJ)⁻¹ at the minimum, with s² = Σrᵢ²/(N − 5) the residuals' variance. Two
//! differences, both documented in the tests that compare with it: BicycleParameters takes Σrᵢ²
//! as SST − SSR (equal at a least-squares minimum up to the fit's tolerance), and it propagates
//! σ_ζ and σ_{ω_n} to T as if they were uncorrelated; here σ_T = 2π σ_{ω_d}/ω_d² from the
//! full covariance (the two agree to 2e-3 relative on BicycleParameters' sample record).
//!
//! The starting guess cannot miss the period: ω_d from the zero crossings of the record less
//! its mean (with a hysteresis band of a tenth of the largest swing, so noise does not add
//! crossings), then the decay rate from a short scan in which the three linear parameters are
//! solved exactly for each trial rate.

use std::ops::Range;

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use num_dual::{DualNum, DualSVec64, gradient};

use crate::error::{Error, Result};

/// The fewest samples a record may have (the fit has five parameters).
pub const MIN_SAMPLES: usize = 16;
/// The most samples a record may have (ten million: over two hours at 1 kHz).
pub const MAX_SAMPLES: usize = 10_000_000;
/// The most Levenberg–Marquardt iterations before the fit is declared not converged.
pub const MAX_ITERATIONS: usize = 200;

/// Index of each parameter in [`PeriodFit::parameters`] and [`PeriodFit::covariance`].
pub mod index {
    /// c: the offset \[the signal's unit\].
    pub const OFFSET: usize = 0;
    /// a: the sine's amplitude at t = 0 \[the signal's unit\].
    pub const SINE: usize = 1;
    /// b: the cosine's amplitude at t = 0 \[the signal's unit\].
    pub const COSINE: usize = 2;
    /// σ = ζω_n: the decay rate \[1/s\].
    pub const DECAY_RATE: usize = 3;
    /// ω_d: the damped angular frequency \[rad/s\].
    pub const DAMPED_FREQUENCY: usize = 4;
}

/// A decaying oscillation fitted to a record: the period with its σ, the damping, the fit.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodFit {
    /// T = 2π/ω_d: the period \[s\].
    pub period: f64,
    /// σ_T, from the fit's covariance \[s\].
    pub period_sigma: f64,
    /// ζ = σ/√(σ² + ω_d²): the damping ratio (negative for a growing oscillation).
    pub damping_ratio: f64,
    /// σ_ζ, from the fit's covariance.
    pub damping_ratio_sigma: f64,
    /// ω_n = √(σ² + ω_d²): the undamped natural angular frequency \[rad/s\].
    pub natural_frequency: f64,
    /// √(a² + b²): the oscillation's amplitude at the first sample \[the signal's unit\].
    pub amplitude: f64,
    /// The fitted parameters [c, a, b, σ, ω_d], in the order of [`index`].
    pub parameters: [f64; 5],
    /// Their covariance s² (JᵀJ)⁻¹.
    pub covariance: [[f64; 5]; 5],
    /// The time of the first sample, from which the curve's t is counted \[s\].
    pub start: f64,
    /// √(Σrᵢ²/N): the residuals' root mean square \[the signal's unit\].
    pub residual_rms: f64,
    /// s = √(Σrᵢ²/(N − 5)): the residuals' standard deviation \[the signal's unit\].
    pub residual_sigma: f64,
    /// 1 − Σrᵢ²/Σ(yᵢ − ȳ)²: the share of the signal's variance the curve explains.
    pub r_squared: f64,
    /// The samples fitted.
    pub samples: usize,
    /// Levenberg–Marquardt iterations made.
    pub iterations: usize,
}

impl PeriodFit {
    /// The fitted curve at time `t` \[s\] (the record's own clock).
    pub fn evaluate(&self, t: f64) -> f64 {
        model(&self.parameters, t - self.start)
    }
}

/// y(t) = c + e^{−σt} (a sin ω_d t + b cos ω_d t), on any scalar (dual numbers give the
/// Jacobian).
fn model<T: DualNum<Primitive = f64> + Copy>(p: &[T; 5], t: f64) -> T {
    let phase = p[index::DAMPED_FREQUENCY] * t;
    p[index::OFFSET]
        + (-p[index::DECAY_RATE] * t).exp()
            * (p[index::SINE] * phase.sin() + p[index::COSINE] * phase.cos())
}

/// The samples of a record sampled at `rate` \[Hz\] from t = 0: tᵢ = i / rate.
pub fn uniform_time(samples: usize, rate: f64) -> Result<Vec<f64>> {
    if !(rate.is_finite() && rate > 0.0) {
        return Err(Error::InvalidParameter {
            field: "sample rate".into(),
            value: rate,
            rule: "must be finite and positive [Hz]".into(),
        });
    }
    check_count(samples)?;
    Ok((0..samples).map(|i| i as f64 / rate).collect())
}

/// BicycleParameters' `select_good_data`: the samples from the largest swing (from the mean)
/// to the last sample above `fraction` of it (that sample excluded), which leaves out the
/// release and the tail where the swing is lost in the sensor's resolution. BicycleParameters
/// applies it with `fraction` = 0.1 to records given with a sample rate.
pub fn decay_window(signal: &[f64], fraction: f64) -> Result<Range<usize>> {
    if !(fraction.is_finite() && (0.0..1.0).contains(&fraction)) {
        return Err(Error::InvalidParameter {
            field: "trim".into(),
            value: fraction,
            rule: "must be a fraction of the largest swing in [0, 1)".into(),
        });
    }
    check_signal(signal)?;
    let mean = signal.iter().sum::<f64>() / signal.len() as f64;
    let (start, largest) = signal
        .iter()
        .enumerate()
        .map(|(i, y)| (i, (y - mean).abs()))
        .fold(
            (0, -1.0),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    let end = signal
        .iter()
        .rposition(|y| y - mean > fraction * largest)
        .unwrap_or(0);
    if end < start + MIN_SAMPLES {
        return Err(Error::InvalidArgument {
            what: "signal",
            rule: format!(
                "trimmed to the samples from the largest swing ({start}) to the last above {fraction} of it ({end}), fewer than {MIN_SAMPLES} remain"
            ),
        });
    }
    Ok(start..end)
}

fn check_count(samples: usize) -> Result<()> {
    if samples < MIN_SAMPLES {
        return Err(Error::InvalidArgument {
            what: "signal",
            rule: format!("{samples} samples; a period fit needs at least {MIN_SAMPLES}"),
        });
    }
    if samples > MAX_SAMPLES {
        return Err(Error::LimitExceeded {
            what: "signal",
            rule: format!("{samples} samples; at most {MAX_SAMPLES} are fitted"),
        });
    }
    Ok(())
}

fn check_signal(signal: &[f64]) -> Result<()> {
    check_count(signal.len())?;
    if let Some(i) = signal.iter().position(|y| !y.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "signal",
            rule: format!(
                "sample {} is {}; every sample must be finite",
                i + 1,
                signal[i]
            ),
        });
    }
    Ok(())
}

fn check_record(time: &[f64], signal: &[f64]) -> Result<()> {
    if time.len() != signal.len() {
        return Err(Error::InvalidArgument {
            what: "time",
            rule: format!(
                "{} times for {} samples of the signal; they must be as many",
                time.len(),
                signal.len()
            ),
        });
    }
    check_signal(signal)?;
    if let Some(i) = time.iter().position(|t| !t.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "time",
            rule: format!("sample {} is {}; every time must be finite", i + 1, time[i]),
        });
    }
    if let Some(i) = time.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::InvalidArgument {
            what: "time",
            rule: format!(
                "sample {} ({} s) does not come after sample {} ({} s); times must increase",
                i + 2,
                time[i + 1],
                i + 1,
                time[i]
            ),
        });
    }
    Ok(())
}

/// ω_d's first guess from the zero crossings of the record less its mean: a crossing counts
/// only once the signal has gone past a tenth of its largest swing on the other side, and the
/// half periods are the times between counted crossings (each at the linearly interpolated
/// zero just before the band was left).
fn frequency_from_crossings(time: &[f64], signal: &[f64], mean: f64) -> Result<f64> {
    let band = 0.1 * signal.iter().map(|y| (y - mean).abs()).fold(0.0, f64::max);
    if band <= 0.0 {
        return Err(Error::InvalidArgument {
            what: "signal",
            rule: "no oscillation found: the signal is constant".into(),
        });
    }
    let mut side = 0i8;
    let mut last_zero = time[0];
    let (mut first, mut last, mut count) = (0.0, 0.0, 0usize);
    for i in 0..signal.len() {
        let d = signal[i] - mean;
        if i > 0 {
            let previous = signal[i - 1] - mean;
            if (previous < 0.0) != (d < 0.0) {
                let s = previous / (previous - d);
                last_zero = time[i - 1] + s * (time[i] - time[i - 1]);
            }
        }
        let now = if d > band {
            1
        } else if d < -band {
            -1
        } else {
            side
        };
        if side != 0 && now != side {
            if count == 0 {
                first = last_zero;
            }
            last = last_zero;
            count += 1;
        }
        side = now;
    }
    if count < 3 || last <= first {
        return Err(Error::InvalidArgument {
            what: "signal",
            rule: format!(
                "no oscillation found: {count} crossing(s) of the mean past a tenth of the largest swing; a period needs at least 3"
            ),
        });
    }
    let half_period = (last - first) / (count - 1) as f64;
    Ok(std::f64::consts::PI / half_period)
}

/// The three linear parameters (c, a, b) solved exactly for a decay rate and a frequency,
/// with the sum of squared residuals.
fn linear_parameters(
    time: &[f64],
    signal: &[f64],
    decay_rate: f64,
    frequency: f64,
) -> Option<([f64; 5], f64)> {
    let t0 = time[0];
    let mut normal = Matrix3::zeros();
    let mut right = Vector3::zeros();
    for (t, y) in time.iter().zip(signal) {
        let t = t - t0;
        let e = crate::math::exp(-decay_rate * t);
        let row = Vector3::new(
            1.0,
            e * crate::math::sin(frequency * t),
            e * crate::math::cos(frequency * t),
        );
        normal += row * row.transpose();
        right += row * *y;
    }
    let x = normal.cholesky()?.solve(&right);
    let p = [x[0], x[1], x[2], decay_rate, frequency];
    let cost = cost(time, signal, &p);
    cost.is_finite().then_some((p, cost))
}

fn cost(time: &[f64], signal: &[f64], p: &[f64; 5]) -> f64 {
    let t0 = time[0];
    time.iter()
        .zip(signal)
        .map(|(t, y)| (y - model(p, t - t0)).powi(2))
        .sum()
}

/// JᵀJ and Jᵀr of the residuals r = y − f(t; p), the Jacobian exact by dual numbers.
fn normal_equations(
    time: &[f64],
    signal: &[f64],
    p: &[f64; 5],
) -> (SMatrix<f64, 5, 5>, SVector<f64, 5>) {
    let t0 = time[0];
    let point = SVector::from(*p);
    let mut jtj = SMatrix::<f64, 5, 5>::zeros();
    let mut jtr = SVector::<f64, 5>::zeros();
    for (t, y) in time.iter().zip(signal) {
        let t = t - t0;
        let (value, row) = gradient(
            |q: SVector<DualSVec64<5>, 5>| model(&[q[0], q[1], q[2], q[3], q[4]], t),
            &point,
        );
        jtj += row * row.transpose();
        jtr += row * (y - value);
    }
    (jtj, jtr)
}

/// Fits y(t) = c + e^{−σt} (a sin ω_d t + b cos ω_d t) to a record: `time` \[s\], increasing,
/// and `signal` (any unit), as many samples, at least [`MIN_SAMPLES`] and at most
/// [`MAX_SAMPLES`], all finite.
///
/// ```
/// use whipple::advanced::measured::period::{fit_period, uniform_time};
/// let time = uniform_time(2000, 200.0)?;
/// let signal: Vec<f64> = time
///     .iter()
///     .map(|t| 0.5 + (-0.05 * t).exp() * (4.0 * t).sin())
///     .collect();
/// let fit = fit_period(&time, &signal)?;
/// assert!((fit.period - std::f64::consts::TAU / 4.0).abs() < 1e-9);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn fit_period(time: &[f64], signal: &[f64]) -> Result<PeriodFit> {
    check_record(time, signal)?;
    let n = signal.len();
    let mean = signal.iter().sum::<f64>() / n as f64;
    let frequency = frequency_from_crossings(time, signal, mean)?;
    // The decay rate: the best of a scan from none to heavy damping (ζ ≈ 0.3).
    let mut best: Option<([f64; 5], f64)> = None;
    for zeta in [0.0, 0.001, 0.003, 0.01, 0.03, 0.1, 0.3] {
        if let Some(candidate) = linear_parameters(time, signal, zeta * frequency, frequency)
            && best.is_none_or(|b| candidate.1 < b.1)
        {
            best = Some(candidate);
        }
    }
    let Some((mut p, mut current)) = best else {
        return Err(Error::InvalidArgument {
            what: "signal",
            rule: "no oscillation found: no sine and cosine fit the record at the frequency of its zero crossings".into(),
        });
    };
    // A sum of squares well above what round-off alone leaves (a residual of 1e-8 of the
    // signal): the smallest scale of the convergence tests.
    let largest = signal.iter().fold(0.0, |m: f64, y| m.max(y.abs()));
    let floor = n as f64 * (1e-8 * largest).powi(2);
    // Each component of the gradient against the scale of its own column and of the residual
    // (the cosine of their angle): zero at a minimum.
    let stationary = |jtj: &SMatrix<f64, 5, 5>, jtr: &SVector<f64, 5>, cost: f64, tol: f64| {
        (0..5).all(|i| jtr[i].abs() <= tol * (jtj[(i, i)] * cost.max(floor)).sqrt())
    };
    let mut damping = 1e-3;
    let mut iterations = 0;
    let mut converged = false;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let (jtj, jtr) = normal_equations(time, signal, &p);
        if stationary(&jtj, &jtr, current, 1e-8) {
            converged = true;
            break;
        }
        let mut accepted = false;
        while damping < 1e16 {
            let mut system = jtj;
            for i in 0..5 {
                system[(i, i)] += damping * jtj[(i, i)].max(f64::MIN_POSITIVE);
            }
            let Some(step) = system.cholesky().map(|c| c.solve(&jtr)) else {
                damping *= 10.0;
                continue;
            };
            let trial: [f64; 5] = std::array::from_fn(|i| p[i] + step[i]);
            let trial_cost = cost(time, signal, &trial);
            if trial[index::DAMPED_FREQUENCY] > 0.0 && trial_cost <= current {
                // A step far below every parameter's standard error: nothing left to gain.
                let small = (0..5).all(|i| {
                    step[i].abs() * jtj[(i, i)].sqrt() <= 1e-9 * current.max(floor).sqrt()
                });
                // Or a step that lowers the sum no more (round-off's floor).
                converged = small || trial_cost == current;
                p = trial;
                current = trial_cost;
                damping = (damping / 10.0).max(1e-12);
                accepted = true;
                break;
            }
            damping *= 10.0;
        }
        if !accepted || converged {
            // No step lowers the sum any more: a minimum to round-off (checked below).
            converged = true;
            break;
        }
    }
    let (jtj, jtr) = normal_equations(time, signal, &p);
    if !converged || !stationary(&jtj, &jtr, current, 1e-6) || !current.is_finite() {
        return Err(Error::NoConvergence {
            method: "the period fit (Levenberg–Marquardt)",
            iterations,
            residual: (current / n as f64).sqrt(),
        });
    }
    let inverse = jtj.try_inverse().ok_or_else(|| Error::InvalidArgument {
        what: "signal",
        rule: "the fit's parameters are not determined by the record (singular normal equations)"
            .into(),
    })?;
    let variance = current / (n - 5) as f64;
    let covariance = inverse * variance;
    let (sigma, omega) = (p[index::DECAY_RATE], p[index::DAMPED_FREQUENCY]);
    let natural = crate::math::hypot(sigma, omega);
    let tau = std::f64::consts::TAU;
    let period = tau / omega;
    let period_sigma = tau / (omega * omega) * covariance[(4, 4)].max(0.0).sqrt();
    // ζ = σ/√(σ² + ω²): ∂ζ/∂σ = ω²/ω_n³, ∂ζ/∂ω = −σω/ω_n³.
    let g = [omega * omega, -sigma * omega].map(|x| x / natural.powi(3));
    let zeta_variance = g[0] * g[0] * covariance[(3, 3)]
        + 2.0 * g[0] * g[1] * covariance[(3, 4)]
        + g[1] * g[1] * covariance[(4, 4)];
    let total: f64 = signal.iter().map(|y| (y - mean).powi(2)).sum();
    let fit = PeriodFit {
        period,
        period_sigma,
        damping_ratio: sigma / natural,
        damping_ratio_sigma: zeta_variance.max(0.0).sqrt(),
        natural_frequency: natural,
        amplitude: crate::math::hypot(p[index::SINE], p[index::COSINE]),
        parameters: p,
        covariance: std::array::from_fn(|i| std::array::from_fn(|j| covariance[(i, j)])),
        start: time[0],
        residual_rms: (current / n as f64).sqrt(),
        residual_sigma: variance.sqrt(),
        r_squared: 1.0 - current / total,
        samples: n,
        iterations,
    };
    if !(fit.period.is_finite() && fit.period_sigma.is_finite()) {
        return Err(Error::NonFinite {
            context: "the period fit".into(),
        });
    }
    Ok(fit)
}

/// [`fit_period`] on a record sampled at `rate` \[Hz\] from t = 0.
pub fn fit_period_sampled(signal: &[f64], rate: f64) -> Result<PeriodFit> {
    let time = uniform_time(signal.len(), rate)?;
    fit_period(&time, signal)
}
