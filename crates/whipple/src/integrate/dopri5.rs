//! The Dormand–Prince 5(4) embedded Runge–Kutta pair (Dormand & Prince 1980, J. Comput. Appl.
//! Math. 6:19–26), propagating the fifth-order solution (local extrapolation), with the
//! fourth-order continuous extension of Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I* (2nd ed., 1993), §II.6 (coefficients of their code DOPRI5),
//! and a PI step-size controller (ibid. §IV.2, β = 0.04).

use nalgebra::SVector;

use super::OdeSystem;
use crate::error::{Error, Result};

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error coefficients: fifth minus fourth order weights.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output (Hairer's DOPRI5, CONTD5).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// Settings of the adaptive method, with their defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dopri5Settings {
    /// Relative tolerance per component. Default 1e-8.
    pub rtol: f64,
    /// Absolute tolerance per component. Default 1e-10.
    pub atol: f64,
    /// First step \[s\]; `None` chooses one from the initial slope. Default `None`.
    pub initial_step: Option<f64>,
    /// Largest step \[s\]. Default infinity.
    pub max_step: f64,
    /// Smallest step \[s\] before giving up. Default 1e-12.
    pub min_step: f64,
    /// Upper bound on step attempts. Default 10 000 000.
    pub max_steps: usize,
}

impl Default for Dopri5Settings {
    /// [`Dopri5Settings::with_rtol`] of [`super::DEFAULT_RTOL`]: rtol 1e-8, atol 1e-10.
    fn default() -> Self {
        Dopri5Settings::with_rtol(super::DEFAULT_RTOL)
    }
}

impl Dopri5Settings {
    /// Relative tolerance `rtol`, absolute tolerance `rtol`·1e-2, the first step chosen from
    /// the initial slope, no largest step, smallest step 1e-12 s, at most 10 000 000 step
    /// attempts.
    pub fn with_rtol(rtol: f64) -> Self {
        Dopri5Settings {
            rtol,
            atol: rtol * 1e-2,
            initial_step: None,
            max_step: f64::INFINITY,
            min_step: 1e-12,
            max_steps: 10_000_000,
        }
    }

    /// Checks the settings.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: &'static str, rule: String| Err(Error::InvalidArgument { what, rule });
        if !(self.rtol.is_finite() && self.rtol > 0.0) {
            return bad(
                "rtol",
                format!("must be positive and finite, got {}", self.rtol),
            );
        }
        if !(self.atol.is_finite() && self.atol > 0.0) {
            return bad(
                "atol",
                format!("must be positive and finite, got {}", self.atol),
            );
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return bad(
                "max_step",
                format!("must be positive, got {}", self.max_step),
            );
        }
        if !(self.min_step.is_finite() && self.min_step > 0.0 && self.min_step <= self.max_step) {
            return bad(
                "min_step",
                format!(
                    "must be positive, finite and at most max_step, got {}",
                    self.min_step
                ),
            );
        }
        if let Some(h) = self.initial_step {
            if !(h.is_finite() && h > 0.0) {
                return bad(
                    "initial_step",
                    format!("must be positive and finite, got {h}"),
                );
            }
        }
        Ok(())
    }
}

/// The continuous extension over one accepted step, fourth order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseOutput<const N: usize> {
    /// Start of the step \[s\].
    pub t0: f64,
    /// Step size \[s\].
    pub h: f64,
    r: [SVector<f64, N>; 5],
}

impl<const N: usize> DenseOutput<N> {
    /// The constant interpolant y over [t0, t0 + h].
    pub(crate) fn constant(t0: f64, h: f64, y: &SVector<f64, N>) -> Self {
        DenseOutput {
            t0,
            h,
            r: [
                *y,
                SVector::zeros(),
                SVector::zeros(),
                SVector::zeros(),
                SVector::zeros(),
            ],
        }
    }

    /// The interpolated state at t in [t0, t0 + h].
    pub fn at(&self, t: f64) -> SVector<f64, N> {
        let s = (t - self.t0) / self.h;
        let s1 = 1.0 - s;
        let r = &self.r;
        r[0] + (r[1] + (r[2] + (r[3] + r[4] * s1) * s) * s1) * s
    }
}

/// One attempted step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Attempt<const N: usize> {
    /// Fifth-order solution at t + h.
    pub y: SVector<f64, N>,
    /// f(t + h, y) (first slope of the next step unless y is changed).
    pub k7: SVector<f64, N>,
    /// Scaled RMS error estimate; the step is acceptable when ≤ 1.
    pub error: f64,
    /// Interpolant over the step.
    pub dense: DenseOutput<N>,
}

impl<const N: usize> Attempt<N> {
    /// An attempt whose evaluation failed (a trial state too far off): infinite error, so that
    /// it is rejected and its constant interpolant never evaluated.
    pub(crate) fn failed(t: f64, h: f64, y: &SVector<f64, N>, k1: &SVector<f64, N>) -> Self {
        Attempt {
            y: *y,
            k7: *k1,
            error: f64::INFINITY,
            dense: DenseOutput::constant(t, h, y),
        }
    }
}

/// One step attempt of size h from (t, y) with slope k1 = f(t, y).
pub(crate) fn attempt<S: OdeSystem<N>, const N: usize>(
    system: &S,
    t: f64,
    y: &SVector<f64, N>,
    k1: &SVector<f64, N>,
    h: f64,
    params: &Dopri5Settings,
) -> Result<Attempt<N>> {
    let k2 = system.rhs(t + C2 * h, &(y + k1 * (h * A21)))?;
    let k3 = system.rhs(t + C3 * h, &(y + (k1 * A31 + k2 * A32) * h))?;
    let k4 = system.rhs(t + C4 * h, &(y + (k1 * A41 + k2 * A42 + k3 * A43) * h))?;
    let k5 = system.rhs(
        t + C5 * h,
        &(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h),
    )?;
    let k6 = system.rhs(
        t + h,
        &(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h),
    )?;
    let y1 = y + (k1 * A71 + k3 * A73 + k4 * A74 + k5 * A75 + k6 * A76) * h;
    let k7 = system.rhs(t + h, &y1)?;
    let err = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    let mut sum = 0.0;
    for i in 0..N {
        let scale = params.atol + params.rtol * y[i].abs().max(y1[i].abs());
        sum += (err[i] / scale).powi(2);
    }
    let error = (sum / N.max(1) as f64).sqrt();
    let diff = y1 - y;
    let bspl = k1 * h - diff;
    let dense = DenseOutput {
        t0: t,
        h,
        r: [
            *y,
            diff,
            bspl,
            diff - k7 * h - bspl,
            (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6 + k7 * D7) * h,
        ],
    };
    Ok(Attempt {
        y: y1,
        k7,
        error,
        dense,
    })
}

/// PI step-size control (Hairer & Wanner §IV.2): proposes steps and judges attempts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Controller {
    h: f64,
    previous_error: f64,
    rejected: bool,
    min_step: f64,
    max_step: f64,
}

const SAFETY: f64 = 0.9;
const BETA: f64 = 0.04;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;

impl Controller {
    /// A controller whose first step comes from the settings or from the initial slope.
    pub fn new<const N: usize>(
        params: &Dopri5Settings,
        y: &SVector<f64, N>,
        f: &SVector<f64, N>,
        span: f64,
    ) -> Self {
        let h = params.initial_step.unwrap_or_else(|| {
            // Hairer's first guess: 0.01 ‖y‖/‖f‖ in the error norm.
            let (mut dy, mut df) = (0.0, 0.0);
            for i in 0..N {
                let scale = params.atol + params.rtol * y[i].abs();
                dy += (y[i] / scale).powi(2);
                df += (f[i] / scale).powi(2);
            }
            let guess = if dy < 1e-10 || df < 1e-10 {
                1e-6
            } else {
                0.01 * (dy / df).sqrt()
            };
            guess.min(0.01 * span.abs().max(1e-12))
        });
        Controller {
            h: h.clamp(params.min_step, params.max_step),
            previous_error: 1e-4,
            rejected: false,
            min_step: params.min_step,
            max_step: params.max_step,
        }
    }

    /// The step to attempt next \[s\].
    pub fn step(&self) -> f64 {
        self.h
    }

    /// Judges an attempt of size h with scaled error `error`: true to accept. Sets the next
    /// step either way; fails when the step would fall below the minimum.
    pub fn accept(&mut self, error: f64, h: f64) -> Result<bool> {
        if !error.is_finite() {
            self.h = h * MIN_FACTOR;
            self.rejected = true;
        } else if error <= 1.0 {
            let factor = if error == 0.0 {
                MAX_FACTOR
            } else {
                (SAFETY * error.powf(-0.2 + 0.75 * BETA) * self.previous_error.powf(BETA))
                    .clamp(MIN_FACTOR, MAX_FACTOR)
            };
            let factor = if self.rejected {
                factor.min(1.0)
            } else {
                factor
            };
            self.h = (h * factor).min(self.max_step);
            self.previous_error = error.max(1e-4);
            self.rejected = false;
            return Ok(true);
        } else {
            let factor = (SAFETY * error.powf(-0.2)).max(MIN_FACTOR);
            self.h = h * factor;
            self.rejected = true;
        }
        if self.h < self.min_step {
            return Err(Error::NoConvergence {
                method: "Dormand-Prince 5(4): step size fell below min_step",
                iterations: 0,
                residual: self.h,
            });
        }
        Ok(false)
    }
}
