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
    /// [`Dopri5Settings::with_rtol`] of `super::DEFAULT_RTOL`: rtol 1e-8, atol 1e-10.
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
    pub(crate) fn new<const N: usize>(
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
    pub(crate) fn step(&self) -> f64 {
        self.h
    }

    /// Judges an attempt of size h with scaled error `error`: true to accept. Sets the next
    /// step either way; fails when the step would fall below the minimum.
    pub(crate) fn accept(&mut self, error: f64, h: f64) -> Result<bool> {
        if !error.is_finite() {
            self.h = h * MIN_FACTOR;
            self.rejected = true;
        } else if error <= 1.0 {
            let factor = if error == 0.0 {
                MAX_FACTOR
            } else {
                (SAFETY
                    * crate::math::powf(error, -0.2 + 0.75 * BETA)
                    * crate::math::powf(self.previous_error, BETA))
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
            let factor = (SAFETY * crate::math::powf(error, -0.2)).max(MIN_FACTOR);
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

#[cfg(test)]
mod tests {
    //! The error control checked on problems with known solutions: the order of the method and
    //! of its error estimate, global error against the tolerance, rejected steps, the dense
    //! output, and both ways the controller gives up.

    use nalgebra::SVector;

    use super::*;
    use crate::integrate::{Integrator as Method, OdeSystem, Stepper};

    /// The times and states of a run.
    #[derive(Debug)]
    struct Run<const N: usize> {
        t: Vec<f64>,
        y: Vec<SVector<f64, N>>,
    }

    /// Integrates from t = 0 to `t_end` through the [`Stepper`] the simulation uses; on failure
    /// the error and the time reached.
    fn run<S: OdeSystem<N>, const N: usize>(
        system: &S,
        y0: SVector<f64, N>,
        t_end: f64,
        method: &Method,
    ) -> std::result::Result<Run<N>, (Error, f64)> {
        let f0 = system.rhs(0.0, &y0).map_err(|e| (e, 0.0))?;
        let mut stepper = Stepper::new(method, &y0, &f0, t_end).map_err(|e| (e, 0.0))?;
        let (mut y, mut k1) = (y0, f0);
        let mut out = Run {
            t: vec![0.0],
            y: vec![y0],
        };
        // Bounded: no test run takes more than a million steps.
        for _ in 0..1_000_000 {
            if stepper.done() {
                return Ok(out);
            }
            let step = stepper
                .step(system, &y, &k1)
                .map_err(|f| (Error::from(f), stepper.t()))?;
            y = step.y;
            k1 = system.rhs(step.t, &y).map_err(|e| (e, step.t))?;
            out.t.push(step.t);
            out.y.push(y);
        }
        Err((
            Error::InvalidArgument {
                what: "test",
                rule: "more than a million steps".into(),
            },
            stepper.t(),
        ))
    }

    /// [`run`] for `?`.
    fn solve<S: OdeSystem<N>, const N: usize>(
        system: &S,
        y0: SVector<f64, N>,
        t_end: f64,
        method: &Method,
    ) -> Result<Run<N>> {
        run(system, y0, t_end, method).map_err(|(e, _)| e)
    }

    type V3 = SVector<f64, 3>;

    /// y = [x, ẋ, z]: ẍ = −x (x = cos t) and ż = z cos t (z = exp(sin t)), so that the stages'
    /// times (c_i) matter as well as their states.
    fn oscillator(t: f64, y: &V3) -> Result<V3> {
        Ok(V3::new(y[1], -y[0], y[2] * crate::math::cos(t)))
    }

    fn exact(t: f64) -> V3 {
        V3::new(
            crate::math::cos(t),
            -crate::math::sin(t),
            crate::math::exp(crate::math::sin(t)),
        )
    }

    /// Fixed steps of h over [0, span] with the method's fifth-order solution; the global
    /// error at the end.
    fn fixed_step_error(steps: usize, span: f64) -> f64 {
        let params = Dopri5Settings::default();
        let h = span / steps as f64;
        let (mut t, mut y) = (0.0, exact(0.0));
        let mut k1 = oscillator(t, &y).expect("finite");
        for _ in 0..steps {
            let a = attempt(&oscillator, t, &y, &k1, h, &params).expect("finite");
            t += h;
            y = a.y;
            k1 = a.k7;
        }
        (y - exact(span)).amax()
    }

    /// The propagated solution is fifth order: halving the step divides the global error by
    /// 2⁵ = 32 (measured order 4.9–5.1 over h = 0.2 … 0.025).
    #[test]
    fn global_error_is_fifth_order() {
        let errors: Vec<f64> = [10, 20, 40, 80]
            .iter()
            .map(|&n| fixed_step_error(n, 2.0))
            .collect();
        for pair in errors.windows(2) {
            let order = crate::math::log2(pair[0] / pair[1]);
            assert!(
                (4.8..5.3).contains(&order),
                "measured order {order} from errors {errors:?}"
            );
        }
    }

    /// The embedded estimate is the difference of the fifth- and fourth-order solutions: its
    /// size over one step scales as h⁵ (the fourth-order solution's local error), and it is a
    /// fair estimate of that solution's error against the exact one.
    #[test]
    fn error_estimate_scales_as_h_to_the_fifth() {
        let params = Dopri5Settings {
            rtol: 1.0,
            atol: 1.0,
            ..Dopri5Settings::default()
        };
        let t = 0.3;
        let y = exact(t);
        let k1 = oscillator(t, &y).expect("finite");
        let estimate = |h: f64| {
            // With rtol = atol = 1 the scaled norm is close to the absolute RMS error.
            attempt(&oscillator, t, &y, &k1, h, &params)
                .expect("finite")
                .error
        };
        let hs = [0.2, 0.1, 0.05, 0.025];
        let e: Vec<f64> = hs.iter().map(|&h| estimate(h)).collect();
        for pair in e.windows(2) {
            let order = crate::math::log2(pair[0] / pair[1]);
            assert!((4.7..5.3).contains(&order), "estimate order {order}: {e:?}");
        }
        // The fifth-order solution's own local error is far below the estimate (order 6).
        let a = attempt(&oscillator, t, &y, &k1, 0.1, &params).expect("finite");
        let local = (a.y - exact(t + 0.1)).amax();
        assert!(
            local < 0.2 * e[1],
            "local error {local} vs estimate {}",
            e[1]
        );
    }

    fn adaptive(rtol: f64) -> Method {
        Method::Dopri5(Dopri5Settings {
            rtol,
            atol: rtol,
            ..Dopri5Settings::default()
        })
    }

    /// Under error control the global error follows the tolerance: over 10 s it stays within
    /// a small factor of rtol, and tightening rtol by 10⁻² reduces it by 10⁻¹·⁵ or more, while
    /// the step count grows as rtol^(−1/5).
    #[test]
    fn global_error_follows_the_tolerance() -> Result<()> {
        let mut previous: Option<(f64, usize)> = None;
        for rtol in [1e-4, 1e-6, 1e-8, 1e-10] {
            let run = solve(&oscillator, exact(0.0), 10.0, &adaptive(rtol))?;
            let error = run
                .t
                .iter()
                .zip(&run.y)
                .map(|(&t, y)| (y - exact(t)).amax())
                .fold(0.0, f64::max);
            let steps = run.t.len() - 1;
            assert!(error < 50.0 * rtol, "rtol {rtol}: error {error}");
            assert!(
                error > 0.01 * rtol,
                "rtol {rtol}: error {error} suspiciously small"
            );
            if let Some((e0, s0)) = previous {
                assert!(e0 / error > 30.0, "rtol {rtol}: {e0} -> {error}");
                let growth = steps as f64 / s0 as f64;
                // 100^(1/5) = 2.5.
                assert!((1.8..3.5).contains(&growth), "steps {s0} -> {steps}");
            }
            previous = Some((error, steps));
            assert_eq!(run.t.last().copied(), Some(10.0));
        }
        Ok(())
    }

    /// An attempt whose error is too large is rejected and retried with a smaller step; after
    /// a rejection the step does not grow at once; every accepted step meets the tolerance.
    #[test]
    fn too_large_steps_are_rejected_and_retried_smaller() -> Result<()> {
        let params = Dopri5Settings {
            rtol: 1e-10,
            atol: 1e-10,
            initial_step: Some(1.0),
            ..Dopri5Settings::default()
        };
        let (mut t, mut y) = (0.0, exact(0.0));
        let mut k1 = oscillator(t, &y)?;
        let mut controller = Controller::new(&params, &y, &k1, 5.0);
        let (mut accepted, mut rejected) = (0, 0);
        let mut after_rejection = false;
        while t < 5.0 {
            assert!(
                accepted + rejected < 100_000,
                "the controller does not advance"
            );
            let h = controller.step().min(5.0 - t);
            let a = attempt(&oscillator, t, &y, &k1, h, &params)?;
            if controller.accept(a.error, h)? {
                assert!(a.error <= 1.0);
                if after_rejection {
                    assert!(controller.step() <= h * (1.0 + 1e-15));
                }
                after_rejection = false;
                accepted += 1;
                t += h;
                y = a.y;
                k1 = a.k7;
            } else {
                assert!(a.error > 1.0);
                assert!(controller.step() < h, "a rejected step is retried smaller");
                after_rejection = true;
                rejected += 1;
            }
        }
        assert!(
            rejected >= 2,
            "a first step of 1 s at 1e-10 is rejected: {rejected}"
        );
        assert!(accepted > 50, "{accepted}");
        assert!((y - exact(t)).amax() < 1e-8);
        // A non-finite error (a failed evaluation) is a rejection at the smallest factor.
        let mut c = Controller::new(&params, &y, &k1, 5.0);
        assert!(!c.accept(f64::NAN, 0.5)?);
        assert_eq!(c.step(), 0.5 * MIN_FACTOR);
        Ok(())
    }

    /// The continuous extension passes through both ends of the step and is fourth order in
    /// between: at mid-step its error against the exact solution scales as h⁵ per step.
    #[test]
    fn dense_output_matches_the_exact_solution() {
        let params = Dopri5Settings::default();
        let t0 = 0.7;
        let y0 = exact(t0);
        let k1 = oscillator(t0, &y0).expect("finite");
        let mut mid_errors = Vec::new();
        for h in [0.4, 0.2, 0.1, 0.05] {
            let a = attempt(&oscillator, t0, &y0, &k1, h, &params).expect("finite");
            let d = a.dense;
            assert_eq!((d.t0, d.h), (t0, h));
            assert!((d.at(t0) - y0).amax() < 1e-15);
            assert!((d.at(t0 + h) - a.y).amax() < 1e-15);
            let worst = (1..10)
                .map(|i| {
                    let t = t0 + h * i as f64 / 10.0;
                    (d.at(t) - exact(t)).amax()
                })
                .fold(0.0, f64::max);
            mid_errors.push(worst);
        }
        for pair in mid_errors.windows(2) {
            let order = crate::math::log2(pair[0] / pair[1]);
            assert!(
                (4.6..5.6).contains(&order),
                "dense order {order}: {mid_errors:?}"
            );
        }
        // Along an adaptive run the interpolant is as accurate as the steps.
        let params = Dopri5Settings {
            rtol: 1e-9,
            atol: 1e-9,
            ..Dopri5Settings::default()
        };
        let (mut t, mut y) = (0.0, exact(0.0));
        let mut k1 = oscillator(t, &y).expect("finite");
        let mut controller = Controller::new(&params, &y, &k1, 3.0);
        let mut worst = 0.0f64;
        let mut attempts = 0;
        while t < 3.0 {
            attempts += 1;
            assert!(attempts < 100_000, "the controller does not advance");
            let h = controller.step().min(3.0 - t);
            let a = attempt(&oscillator, t, &y, &k1, h, &params).expect("finite");
            if controller.accept(a.error, h).expect("step") {
                for i in 1..8 {
                    let s = t + h * i as f64 / 8.0;
                    worst = worst.max((a.dense.at(s) - exact(s)).amax());
                }
                t += h;
                y = a.y;
                k1 = a.k7;
            }
        }
        assert!(worst < 1e-7, "dense output error {worst}");
    }

    /// The constant interpolant of a failed attempt is the state itself everywhere.
    #[test]
    fn constant_dense_output_is_constant() {
        let y = V3::new(1.0, -2.0, 3.0);
        let d = DenseOutput::constant(1.0, 0.5, &y);
        for t in [1.0, 1.2, 1.5] {
            assert_eq!(d.at(t), y);
        }
    }

    /// The step limit ends the integration with `NoConvergence` naming it; so does a step
    /// that would fall below `min_step`.
    #[test]
    fn the_controller_gives_up_with_a_typed_error() {
        let limited = Method::Dopri5(Dopri5Settings {
            max_steps: 5,
            ..Dopri5Settings::default()
        });
        match run(&oscillator, exact(0.0), 10.0, &limited) {
            Err((Error::NoConvergence { method, .. }, t)) => {
                assert!(method.contains("step limit"), "{method}");
                // Five attempts of the initial step size cannot reach 10 s.
                assert!(t < 5.0, "gave up at {t}");
            }
            Err((other, _)) => panic!("expected the step limit, got {other:?}"),
            Ok(_) => panic!("expected the step limit, the run completed"),
        }
        // A solution that blows up at t = 1 (ẏ = y², y = 1/(1 − t)): the steps shrink until
        // they pass min_step, just before the singularity.
        let blow_up = |_t: f64, y: &SVector<f64, 1>| Ok(y.map(|v| v * v));
        let method = Method::Dopri5(Dopri5Settings {
            min_step: 1e-6,
            ..Dopri5Settings::default()
        });
        match run(&blow_up, SVector::<f64, 1>::new(1.0), 2.0, &method) {
            Err((Error::NoConvergence { method, .. }, t)) => {
                assert!(method.contains("min_step"), "{method}");
                assert!((t - 1.0).abs() < 1e-3, "gave up at {t}");
            }
            Err((Error::NonFiniteState { t }, _)) => panic!("reached a non-finite state at {t}"),
            Err((other, _)) => {
                panic!("expected the step size to fall below min_step, got {other:?}")
            }
            Ok(_) => panic!("expected the step size to fall below min_step, the run completed"),
        }
    }

    /// RK4 through the same driver: fourth order (halving dt divides the error by 16).
    #[test]
    fn rk4_is_fourth_order() -> Result<()> {
        let error = |dt: f64| -> Result<f64> {
            let run = solve(&oscillator, exact(0.0), 2.0, &Method::Rk4 { dt })?;
            Ok((run.y.last().copied().unwrap_or_default() - exact(2.0)).amax())
        };
        let e: Vec<f64> = [0.1, 0.05, 0.025]
            .iter()
            .map(|&dt| error(dt))
            .collect::<Result<_>>()?;
        for pair in e.windows(2) {
            let order = crate::math::log2(pair[0] / pair[1]);
            assert!((3.8..4.2).contains(&order), "RK4 order {order}: {e:?}");
        }
        Ok(())
    }

    /// A state that turns non-finite ends the integration with `NonFiniteState` at that time.
    #[test]
    fn a_non_finite_state_is_an_error_with_its_time() {
        let f = |t: f64, _y: &SVector<f64, 1>| {
            Ok(SVector::<f64, 1>::new(if t >= 0.5 {
                f64::INFINITY
            } else {
                1.0
            }))
        };
        match solve(
            &f,
            SVector::<f64, 1>::zeros(),
            1.0,
            &Method::Rk4 { dt: 0.1 },
        ) {
            Err(Error::NonFiniteState { t }) => assert!((t - 0.5).abs() < 1e-12, "{t}"),
            other => panic!("expected a non-finite state, got {other:?}"),
        }
    }
}
