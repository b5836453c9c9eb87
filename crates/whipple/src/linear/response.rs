//! Time responses of a [`LinearSystem`]: exact for inputs piecewise linear in time, and through
//! the adaptive integrator for any input function.
//!
//! # Exact, without a time step
//!
//! Between two consecutive break points (a knot of an input, or a sample time) every input is
//! linear in time, u(a + s) = u_a + s r, and ẋ = A x + B u has the exact solution
//!
//! x(a + h) = Φ x(a) + Ψ₁ B u_a + Ψ₂ B r, with Φ = e^{Ah}, Ψ₁ = ∫₀ʰ e^{Aτ} dτ and
//! Ψ₂ = ∫₀ʰ e^{A(h−s)} s ds.
//!
//! All three come from one matrix exponential (Van Loan 1978): the state z = [x; p; q] of
//! ż = [A x + p; q; 0] starts at p = B u_a, q = B r, so that p(s) = B u(a + s), and
//!
//! exp([[A, I, 0], [0, 0, I], [0, 0, 0]] h) = [[Φ, Ψ₁, Ψ₂], [0, I, h I], [0, 0, I]].
//!
//! (This is Van Loan's block [[A, B, 0], [0, 0, I], [0, 0, 0]] with B = I: a 3n × 3n exponential
//! whatever the number of inputs, the B u products taken per interval.) The exponential is
//! nalgebra's scaling and squaring with a Padé approximant, accurate to round-off. Intervals of
//! the same length share one exponential, so a uniform grid costs one: a length within the
//! round-off of the times themselves (4 ε of the later time) of one already computed reuses it,
//! and the remaining δ = h − h' (a few units in the last place) is added as one Euler step
//! x += δ (A x + B u), exact to O(δ²).
//!
//! # Through the integrator
//!
//! [`LinearSystem::response_to_function`] takes any u(t) (an expression, a Python callable)
//! and integrates with Dormand–Prince 5(4) ([`crate::integrate`]), sampling its dense output;
//! its accuracy is the integrator's tolerance, which the tests check against the exact
//! response.

use std::cell::RefCell;

use nalgebra::{DMatrix, DVector, SVector};

use super::system::{LinearSystem, Output, StateVariable};
use crate::error::{Error, Result, short_number};
use crate::integrate::{Dopri5Settings, Integrator, Stepper};

/// The most sample times one response may have.
pub const MAX_RESPONSE_TIMES: usize = 1_000_000;

/// The most knots an input signal may have, and all the inputs of one response together.
pub const MAX_KNOTS: usize = 1_000_000;

/// The most numbers one response may hold: (states + outputs) × sample times. At 8 bytes
/// each, about 400 MB.
pub const MAX_RESPONSE_VALUES: usize = 50_000_000;

/// The most distinct interval lengths whose exponentials one response keeps (each 3 n² numbers,
/// at most 2 KB): beyond it an exponential is computed for each interval and dropped.
const MAX_CACHED_EXPONENTIALS: usize = 4096;

/// The largest ‖A h‖ (bounded by n max |a_ij| h) an interval's exponential is computed for.
const MAX_EXPONENT_SIZE: f64 = 1e15;

/// An input signal u(t), piecewise linear in time: linear between consecutive knots, a jump
/// where a knot is given twice (the first value just before it, the second from it on), and
/// constant before the first knot and after the last, at their values.
///
/// ```
/// use whipple::advanced::linear::InputSignal;
/// let ramp = InputSignal::piecewise_linear(vec![0.0, 1.0], vec![0.0, 2.0])?;
/// assert_eq!((ramp.value(-1.0), ramp.value(0.25), ramp.value(5.0)), (0.0, 0.5, 2.0));
/// let pulse = InputSignal::pulse(0.1, 0.5, 1.0)?; // 1 N m from 0.1 s to 0.6 s
/// assert_eq!((pulse.value(0.0999), pulse.value(0.1), pulse.value(0.6)), (0.0, 1.0, 0.0));
/// let held = InputSignal::piecewise_constant(vec![0.0, 1.0, 2.0], vec![3.0, -1.0, 0.0])?;
/// assert_eq!((held.value(0.5), held.value(1.5), held.value(9.0)), (3.0, -1.0, 0.0));
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct InputSignal {
    knots: Vec<f64>,
    values: Vec<f64>,
}

impl InputSignal {
    /// Linear between the knots `knots` (non-decreasing, finite; a knot given twice is a jump,
    /// three times is refused) through `values` (one per knot, finite). Errors name `knots` or
    /// `values`.
    pub fn piecewise_linear(knots: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        let bad = |what: &'static str, rule: String| Err(Error::InvalidArgument { what, rule });
        if knots.is_empty() {
            return bad("knots", "at least one knot is needed".into());
        }
        if knots.len() > MAX_KNOTS {
            return Err(Error::LimitExceeded {
                what: "knots",
                rule: format!("at most {MAX_KNOTS} knots, got {}", knots.len()),
            });
        }
        if values.len() != knots.len() {
            return bad(
                "values",
                format!(
                    "one value per knot: {} knots, {} values",
                    knots.len(),
                    values.len()
                ),
            );
        }
        for (k, t) in knots.iter().enumerate() {
            if !t.is_finite() {
                return bad("knots", format!("knot {} is not finite ({t})", k + 1));
            }
            if k > 0 && *t < knots[k - 1] {
                return bad(
                    "knots",
                    format!(
                        "must not decrease: knot {} ({} s) is before knot {k} ({} s)",
                        k + 1,
                        short_number(*t),
                        short_number(knots[k - 1])
                    ),
                );
            }
            if k > 1 && *t == knots[k - 2] {
                return bad(
                    "knots",
                    format!(
                        "a knot may be given twice (a jump), not three times: {} s at knots {k} to {}",
                        short_number(*t),
                        k + 1
                    ),
                );
            }
        }
        if let Some(k) = values.iter().position(|x| !x.is_finite()) {
            return bad(
                "values",
                format!("value {} is not finite ({})", k + 1, values[k]),
            );
        }
        Ok(InputSignal { knots, values })
    }

    /// `values[k]` from `knots[k]` until the next knot (strictly increasing, finite), the last
    /// value from the last knot on, and the first value before the first knot. Errors name
    /// `knots` or `values`.
    pub fn piecewise_constant(knots: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        if let Some(k) = knots.iter().position(|t| !t.is_finite()) {
            return Err(Error::InvalidArgument {
                what: "knots",
                rule: format!("knot {} is not finite ({})", k + 1, knots[k]),
            });
        }
        if let Some(k) = (1..knots.len()).find(|&k| knots[k] <= knots[k - 1]) {
            return Err(Error::InvalidArgument {
                what: "knots",
                rule: format!(
                    "must increase: knot {} ({} s) is not after knot {k} ({} s)",
                    k + 1,
                    short_number(knots[k]),
                    short_number(knots[k - 1])
                ),
            });
        }
        if knots.len() > MAX_KNOTS / 2 {
            return Err(Error::LimitExceeded {
                what: "knots",
                rule: format!(
                    "at most {} knots for a piecewise-constant signal (each is a jump, two knots), got {}",
                    MAX_KNOTS / 2,
                    knots.len()
                ),
            });
        }
        if values.len() != knots.len() {
            return Err(Error::InvalidArgument {
                what: "values",
                rule: format!(
                    "one value per knot: {} knots, {} values",
                    knots.len(),
                    values.len()
                ),
            });
        }
        // Each knot after the first is a jump from the previous value to its own.
        let mut doubled_knots = Vec::with_capacity(2 * knots.len());
        let mut doubled_values = Vec::with_capacity(2 * knots.len());
        for (k, (t, x)) in knots.iter().zip(&values).enumerate() {
            if k > 0 {
                doubled_knots.push(*t);
                doubled_values.push(values[k - 1]);
            }
            doubled_knots.push(*t);
            doubled_values.push(*x);
        }
        Self::piecewise_linear(doubled_knots, doubled_values)
    }

    /// Zero for ever.
    pub fn zero() -> Self {
        InputSignal {
            knots: vec![0.0],
            values: vec![0.0],
        }
    }

    /// `amplitude` for ever (from t = 0 on, a step at t = 0 from a zero initial state).
    pub fn constant(amplitude: f64) -> Result<Self> {
        Self::piecewise_linear(vec![0.0], vec![amplitude])
    }

    /// Zero before `time`, `amplitude` from it on.
    pub fn step(time: f64, amplitude: f64) -> Result<Self> {
        Self::piecewise_linear(vec![time, time], vec![0.0, amplitude])
    }

    /// `amplitude` from `start` for `duration` (> 0), zero before and after.
    pub fn pulse(start: f64, duration: f64, amplitude: f64) -> Result<Self> {
        if !(duration.is_finite() && duration > 0.0) {
            return Err(Error::InvalidArgument {
                what: "duration",
                rule: format!(
                    "a pulse lasts a positive finite time, got {}",
                    short_number(duration)
                ),
            });
        }
        let end = start + duration;
        Self::piecewise_linear(
            vec![start, start, end, end],
            vec![0.0, amplitude, amplitude, 0.0],
        )
    }

    /// The knots \[s\].
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The values at the knots.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// u(t), continuous from the right: at a jump, the value after it.
    pub fn value(&self, t: f64) -> f64 {
        let j = self.knots.partition_point(|k| *k <= t);
        self.between(j, t)
    }

    /// The limit of u from the left at t: at a jump, the value before it.
    pub fn value_before(&self, t: f64) -> f64 {
        let j = self.knots.partition_point(|k| *k < t);
        self.between(j, t)
    }

    /// u at t, which lies in [knots[j − 1], knots[j]] (constant outside the knots).
    fn between(&self, j: usize, t: f64) -> f64 {
        let last = self.knots.len() - 1;
        if j == 0 {
            return self.values[0];
        }
        if j > last {
            return self.values[last];
        }
        let (t0, t1) = (self.knots[j - 1], self.knots[j]);
        let (u0, u1) = (self.values[j - 1], self.values[j]);
        if t1 <= t0 {
            return u1;
        }
        u0 + (u1 - u0) * ((t - t0) / (t1 - t0))
    }
}

/// A time response: the states and outputs of a [`LinearSystem`] at the sample times.
///
/// The states x_P, θ_R, θ_F are deviations from the nominal run (see [`LinearSystem`]);
/// [`TimeResponse::ground_path`] adds the nominal run back.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeResponse {
    /// The sample times \[s\].
    pub times: Vec<f64>,
    /// The states at each time: one row per time, one column per state (in the order of
    /// [`TimeResponse::state_names`]).
    pub states: DMatrix<f64>,
    /// The outputs y = C x + D u at each time: one row per time, one column per output. u is
    /// taken after a jump at a jump's instant.
    pub outputs: DMatrix<f64>,
    /// The states, in the order of the columns of `states`.
    pub state_names: Vec<StateVariable>,
    /// The outputs, in the order of the columns of `outputs`.
    pub output_names: Vec<Output>,
    /// The forward speed v [m/s].
    pub speed: f64,
    /// The rates of the nominal run the states are measured from
    /// ([`LinearSystem::nominal_rates`]).
    pub nominal_rates: Vec<f64>,
}

/// The path in the ground plane (benchmark axes: x forward, y right, ψ right turn positive).
#[derive(Debug, Clone, PartialEq)]
pub struct GroundPath {
    /// The rear contact's x, the nominal run v t included \[m\].
    pub rear_x: Vec<f64>,
    /// The rear contact's y \[m\].
    pub rear_y: Vec<f64>,
    /// ψ: the yaw \[rad\].
    pub yaw: Vec<f64>,
    /// The front contact's y \[m\], when [`Output::FrontContactY`] is among the outputs. (Its
    /// x is the rear contact's plus the wheelbase, to first order.)
    pub front_y: Option<Vec<f64>>,
}

impl TimeResponse {
    /// One state at every time, if the system has it.
    pub fn state(&self, state: StateVariable) -> Option<Vec<f64>> {
        let j = self.state_names.iter().position(|s| *s == state)?;
        Some(self.states.column(j).iter().copied().collect())
    }

    /// One output at every time, if the system has it.
    pub fn output(&self, output: &Output) -> Option<Vec<f64>> {
        let j = self.output_names.iter().position(|o| o == output)?;
        Some(self.outputs.column(j).iter().copied().collect())
    }

    /// The rear contact's path (x with the nominal run v t added back, or v t alone when x_P is
    /// not a state), the yaw, and the front contact's lateral position when it is an output;
    /// `None` unless ψ and y are among the states.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::linear::{Input, InputSignal, LinearSystem, Output, StateVariable, SystemRequest};
    /// let request = SystemRequest {
    ///     states: vec![StateVariable::Yaw, StateVariable::RearContactX, StateVariable::RearContactY],
    ///     inputs: vec![Input::SteerTorque],
    ///     outputs: vec![Output::FrontContactY],
    /// };
    /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 5.0, &request)?;
    /// let times: Vec<f64> = (0..=30).map(|k| 0.1 * k as f64).collect();
    /// let pulse = InputSignal::pulse(0.0, 0.5, 1.0)?; // steer right for half a second
    /// let path = system.response(&[0.0; 7], &[pulse], &times)?.ground_path().expect("ψ and y are states");
    /// assert_eq!(path.rear_x[30], 15.0); // 5 m/s for 3 s
    /// // Counter-steering: a steer torque to the right ends in a turn to the left.
    /// assert!(path.yaw[30] < 0.0 && path.rear_y[30] < 0.0);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn ground_path(&self) -> Option<GroundPath> {
        let yaw = self.state(StateVariable::Yaw)?;
        let rear_y = self.state(StateVariable::RearContactY)?;
        let rate = self
            .state_names
            .iter()
            .position(|s| *s == StateVariable::RearContactX)
            .map_or(self.speed, |j| self.nominal_rates[j]);
        let deviation = self.state(StateVariable::RearContactX);
        let rear_x = self
            .times
            .iter()
            .enumerate()
            .map(|(k, t)| deviation.as_ref().map_or(0.0, |x| x[k]) + rate * t)
            .collect();
        Some(GroundPath {
            rear_x,
            rear_y,
            yaw,
            front_y: self.output(&Output::FrontContactY),
        })
    }
}

/// Φ, Ψ₁, Ψ₂ over one interval length (see the module documentation).
struct Exponential {
    h: f64,
    phi: DMatrix<f64>,
    psi1: DMatrix<f64>,
    psi2: DMatrix<f64>,
}

impl Exponential {
    fn new(a: &DMatrix<f64>, h: f64) -> Result<Self> {
        let n = a.nrows();
        // Scaling and squaring takes about log2 ‖A h‖ squarings: an interval whose ‖A h‖ is
        // not finite, or beyond 1e15 (50 squarings; the response's modes have long since
        // decayed or overflowed), is refused rather than handed to it.
        let size = a.amax() * h * n as f64;
        if !size.is_finite() || size > MAX_EXPONENT_SIZE {
            return Err(Error::LimitExceeded {
                what: "times",
                rule: format!(
                    "an interval of {} s without a knot or sample is too long for the matrix exponential (‖A‖ h ≈ {size:.3e}, at most {MAX_EXPONENT_SIZE:e}): sample more often",
                    short_number(h)
                ),
            });
        }
        let mut m = DMatrix::zeros(3 * n, 3 * n);
        m.view_mut((0, 0), (n, n)).copy_from(&(a * h));
        for i in 0..n {
            m[(i, n + i)] = h;
            m[(n + i, 2 * n + i)] = h;
        }
        let e = m.exp();
        if !e.iter().all(|x| x.is_finite()) {
            return Err(Error::NonFinite {
                context: format!(
                    "the matrix exponential over an interval of {} s (the response grows beyond double precision)",
                    short_number(h)
                ),
            });
        }
        Ok(Exponential {
            h,
            phi: e.view((0, 0), (n, n)).into_owned(),
            psi1: e.view((0, n), (n, n)).into_owned(),
            psi2: e.view((0, 2 * n), (n, n)).into_owned(),
        })
    }
}

/// The exponentials computed so far, sorted by interval length.
struct Exponentials<'a> {
    a: &'a DMatrix<f64>,
    cached: Vec<Exponential>,
}

impl Exponentials<'_> {
    /// The exponential for an interval of length h ending at `end`: one whose length is within
    /// 4 ε · end of h, or a new one.
    fn with<R>(&mut self, h: f64, end: f64, use_it: impl FnOnce(&Exponential) -> R) -> Result<R> {
        let close = 4.0 * f64::EPSILON * end.abs().max(h);
        let k = self.cached.partition_point(|e| e.h < h);
        let nearest = [k.checked_sub(1), Some(k)]
            .into_iter()
            .flatten()
            .filter(|&i| i < self.cached.len())
            .min_by(|&i, &j| {
                (self.cached[i].h - h)
                    .abs()
                    .total_cmp(&(self.cached[j].h - h).abs())
            });
        if let Some(i) = nearest
            && (self.cached[i].h - h).abs() <= close
        {
            return Ok(use_it(&self.cached[i]));
        }
        let e = Exponential::new(self.a, h)?;
        let result = use_it(&e);
        if self.cached.len() < MAX_CACHED_EXPONENTIALS {
            self.cached.insert(k, e);
        }
        Ok(result)
    }
}

impl LinearSystem {
    /// Checks an initial state, sample times and the size of the result.
    fn check_response(&self, initial: &[f64], times: &[f64]) -> Result<()> {
        let n = self.states().len();
        let bad = |what: &'static str, rule: String| Err(Error::InvalidArgument { what, rule });
        if initial.len() != n {
            return bad(
                "initial state",
                format!(
                    "one value per state ({}): {n} values, got {}",
                    self.states()
                        .iter()
                        .map(|s| s.name())
                        .collect::<Vec<_>>()
                        .join(", "),
                    initial.len()
                ),
            );
        }
        if let Some(k) = initial.iter().position(|x| !x.is_finite()) {
            return bad(
                "initial state",
                format!("{} is not finite ({})", self.states()[k], initial[k]),
            );
        }
        check_times(times, n + self.outputs().len())
    }

    /// The exact response from the state `initial` at t = 0 (one value per state, in the
    /// order of [`LinearSystem::states`]) to the inputs `inputs` (one signal per input, in the
    /// order of [`LinearSystem::inputs`]), sampled at `times` (increasing, the first ≥ 0; they
    /// need not meet the knots): no time step, the matrix exponential over each interval
    /// between break points (see the module documentation).
    ///
    /// Errors name `initial state`, `inputs`, `times` (not finite, not increasing, too many)
    /// or `knots` (too many in all).
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::linear::{InputSignal, LinearSystem, StateVariable, SystemRequest};
    /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 5.0, &SystemRequest::lean_steer())?;
    /// let times: Vec<f64> = (0..=100).map(|k| 0.1 * k as f64).collect();
    /// // Hands free after a lean rate of 0.5 rad/s, at a self-stable speed: it dies away.
    /// let kicked = system.response(&[0.0, 0.0, 0.5, 0.0], &[InputSignal::zero(), InputSignal::zero()], &times)?;
    /// let lean = kicked.state(StateVariable::Lean).expect("lean is a state");
    /// assert!(lean[..20].iter().any(|x| x.abs() > 0.02) && lean[100].abs() < 1e-3);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn response(
        &self,
        initial: &[f64],
        inputs: &[InputSignal],
        times: &[f64],
    ) -> Result<TimeResponse> {
        self.check_response(initial, times)?;
        let (states, outputs) = exact_response(
            (self.a(), self.b(), self.c(), self.d()),
            initial,
            inputs,
            times,
        )?;
        let mut result = self.empty_response(times);
        result.states = states;
        result.outputs = outputs;
        Ok(result)
    }

    /// The response with every input zero from `initial` (see [`LinearSystem::response`]).
    pub fn initial_response(&self, initial: &[f64], times: &[f64]) -> Result<TimeResponse> {
        let zeros = vec![InputSignal::zero(); self.inputs().len()];
        self.response(initial, &zeros, times)
    }

    /// The response from rest to a unit step of input `input` (index into
    /// [`LinearSystem::inputs`]) at t = 0, the other inputs zero. Where the system is stable
    /// its outputs settle at the static gains G(0).
    pub fn step_response(&self, input: usize, times: &[f64]) -> Result<TimeResponse> {
        self.check_input_index(input)?;
        let signals: Vec<InputSignal> = (0..self.inputs().len())
            .map(|j| {
                if j == input {
                    InputSignal::constant(1.0)
                } else {
                    Ok(InputSignal::zero())
                }
            })
            .collect::<Result<_>>()?;
        self.response(&vec![0.0; self.states().len()], &signals, times)
    }

    /// The response to a unit impulse of input `input` (index into [`LinearSystem::inputs`])
    /// at t = 0: the free response from x(0⁺) = B eᵢ (one newton-metre-second of steer torque
    /// gives the steer rate its jump). The outputs are C x(t) for t ≥ 0⁺; a non-zero column
    /// of D would add D eᵢ δ(t), an impulse at t = 0 that no sample can hold, and is left out
    /// (D is zero for every output offered so far). The derivative of the step response.
    pub fn impulse_response(&self, input: usize, times: &[f64]) -> Result<TimeResponse> {
        self.check_input_index(input)?;
        let initial: Vec<f64> = self.b().column(input).iter().copied().collect();
        self.initial_response(&initial, times)
    }

    fn check_input_index(&self, input: usize) -> Result<()> {
        let m = self.inputs().len();
        if input >= m {
            return Err(Error::InvalidArgument {
                what: "input",
                rule: format!(
                    "the system has {m} input(s) (indices 0 to {}), got index {input}",
                    m.saturating_sub(1)
                ),
            });
        }
        Ok(())
    }

    /// The response from `initial` at t = 0 to any input function u(t), sampled at `times`,
    /// integrated by Dormand–Prince 5(4) with `settings` (its tolerances are the accuracy) and
    /// its dense output between steps. `input(t, u)` writes the inputs at t into `u` (one per
    /// input); an error it returns ends the integration with that error, a value that is not
    /// finite is [`Error::NonFinite`]. Bounded by the settings' `max_steps`.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::integrate::Dopri5Settings;
    /// use whipple::advanced::linear::{Input, InputSignal, LinearSystem, Output, StateVariable, SystemRequest};
    /// let request = SystemRequest { states: vec![], inputs: vec![Input::SteerTorque], outputs: vec![Output::State(StateVariable::Lean)] };
    /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 5.0, &request)?;
    /// let times = [0.0, 0.5, 1.0];
    /// let wiggle = |t: f64, u: &mut [f64]| { u[0] = (2.0 * t).sin(); Ok(()) };
    /// let integrated = system.response_to_function(&[0.0; 4], wiggle, &times, &Dopri5Settings::with_rtol(1e-10))?;
    /// assert!(integrated.outputs[(2, 0)].abs() > 1e-3);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn response_to_function<F>(
        &self,
        initial: &[f64],
        input: F,
        times: &[f64],
        settings: &Dopri5Settings,
    ) -> Result<TimeResponse>
    where
        F: Fn(f64, &mut [f64]) -> Result<()>,
    {
        self.check_response(initial, times)?;
        settings.validate()?;
        let input = |t: f64| -> Result<DVector<f64>> {
            let mut u = DVector::zeros(self.inputs().len());
            input(t, u.as_mut_slice())?;
            if let Some(j) = u.iter().position(|x| !x.is_finite()) {
                return Err(Error::NonFinite {
                    context: format!(
                        "the input function: {} at t = {} s is {}",
                        self.inputs()[j],
                        short_number(t),
                        u[j]
                    ),
                });
            }
            Ok(u)
        };
        match self.states().len() {
            4 => self.integrate::<4>(initial, &input, times, settings),
            5 => self.integrate::<5>(initial, &input, times, settings),
            6 => self.integrate::<6>(initial, &input, times, settings),
            7 => self.integrate::<7>(initial, &input, times, settings),
            8 => self.integrate::<8>(initial, &input, times, settings),
            9 => self.integrate::<9>(initial, &input, times, settings),
            n => Err(Error::InvalidArgument {
                what: "states",
                rule: format!("a system has 4 to 9 states, this one {n}"),
            }),
        }
    }

    fn integrate<const N: usize>(
        &self,
        initial: &[f64],
        input: &dyn Fn(f64) -> Result<DVector<f64>>,
        times: &[f64],
        settings: &Dopri5Settings,
    ) -> Result<TimeResponse> {
        let a = nalgebra::SMatrix::<f64, N, N>::from_fn(|i, j| self.a()[(i, j)]);
        let b = self.b();
        // The integrator retries an attempt whose evaluation failed with a smaller step: the
        // input function's own error is kept, to be returned should the step fail.
        let failure: RefCell<Option<Error>> = RefCell::new(None);
        let rhs = |t: f64, x: &SVector<f64, N>| -> Result<SVector<f64, N>> {
            let u = input(t).inspect_err(|error| {
                failure.borrow_mut().get_or_insert_with(|| error.clone());
            })?;
            let bu = b * u;
            Ok(a * x + SVector::<f64, N>::from_fn(|i, _| bu[i]))
        };
        let mut result = self.empty_response(times);
        let mut x = SVector::<f64, N>::from_column_slice(initial);
        let t_end = times[times.len() - 1];
        let mut stepper = Stepper::new(&Integrator::Dopri5(*settings), &x, &rhs(0.0, &x)?, t_end)?;
        let mut k = 0;
        while k < times.len() && times[k] <= 0.0 {
            self.record(
                &mut result,
                k,
                &DVector::from_column_slice(x.as_slice()),
                &input(times[k])?,
            );
            k += 1;
        }
        while k < times.len() {
            let slope = rhs(stepper.t(), &x)?;
            let step = match stepper.step(&rhs, &x, &slope) {
                Ok(step) => step,
                Err(failure_of_step) => {
                    return Err(failure.take().unwrap_or_else(|| failure_of_step.into()));
                }
            };
            while k < times.len() && (times[k] <= step.t || stepper.done()) {
                let at = match (&step.dense, times[k] < step.t) {
                    (Some(dense), true) => dense.at(times[k]),
                    _ => step.y,
                };
                self.record(
                    &mut result,
                    k,
                    &DVector::from_column_slice(at.as_slice()),
                    &input(times[k])?,
                );
                k += 1;
            }
            x = step.y;
        }
        Ok(result)
    }

    /// A response with room for every sample, zero so far.
    fn empty_response(&self, times: &[f64]) -> TimeResponse {
        TimeResponse {
            times: times.to_vec(),
            states: DMatrix::zeros(times.len(), self.states().len()),
            outputs: DMatrix::zeros(times.len(), self.outputs().len()),
            state_names: self.states().to_vec(),
            output_names: self.outputs().to_vec(),
            speed: self.speed(),
            nominal_rates: self.nominal_rates(),
        }
    }

    /// Row k: the state x and the outputs C x + D u.
    fn record(&self, result: &mut TimeResponse, k: usize, x: &DVector<f64>, u: &DVector<f64>) {
        let y = self.c() * x + self.d() * u;
        result.states.row_mut(k).copy_from(&x.transpose());
        result.outputs.row_mut(k).copy_from(&y.transpose());
    }
}

/// The exact response of ẋ = A x + B u, y = C x + D u (the matrices in that order) from
/// `initial` at t = 0 to the piecewise-linear `inputs` (one per column of B), sampled at
/// `times`: the states and the outputs, one row per time. The engine behind
/// [`LinearSystem::response`], for any system (a closed loop with its command filter, say).
/// Errors name `initial state`, `inputs`, `times` or `knots`.
pub(crate) fn exact_response(
    (a, b, c, d): (&DMatrix<f64>, &DMatrix<f64>, &DMatrix<f64>, &DMatrix<f64>),
    initial: &[f64],
    inputs: &[InputSignal],
    times: &[f64],
) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let n = a.nrows();
    if initial.len() != n || initial.iter().any(|x| !x.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "initial state",
            rule: format!("{n} finite values, one per state, got {:?}", initial),
        });
    }
    check_times(times, n + c.nrows())?;
    let m = b.ncols();
    if inputs.len() != m {
        return Err(Error::InvalidArgument {
            what: "inputs",
            rule: format!(
                "one signal per input of the system ({m}), got {}",
                inputs.len()
            ),
        });
    }
    let total_knots = inputs.iter().map(|s| s.knots.len()).sum::<usize>();
    if total_knots > MAX_KNOTS {
        return Err(Error::LimitExceeded {
            what: "knots",
            rule: format!("at most {MAX_KNOTS} knots in all the inputs, got {total_knots}"),
        });
    }
    let t_end = times[times.len() - 1];
    // The knots strictly inside (0, t_end): where an input may bend or jump.
    let mut knots: Vec<f64> = inputs
        .iter()
        .flat_map(|s| s.knots.iter().copied())
        .filter(|t| *t > 0.0 && *t < t_end)
        .collect();
    knots.sort_by(f64::total_cmp);
    knots.dedup();

    let mut states = DMatrix::zeros(times.len(), a.nrows());
    let mut outputs = DMatrix::zeros(times.len(), c.nrows());
    let mut exponentials = Exponentials {
        a,
        cached: Vec::new(),
    };
    let u_at = |t: f64, before: bool| -> DVector<f64> {
        DVector::from_iterator(
            m,
            inputs.iter().map(|s| {
                if before {
                    s.value_before(t)
                } else {
                    s.value(t)
                }
            }),
        )
    };
    let mut x = DVector::from_column_slice(initial);
    let mut t = 0.0;
    let mut next_knot = 0;
    for (k, &sample) in times.iter().enumerate() {
        while t < sample {
            let end = match knots.get(next_knot) {
                Some(&knot) if knot < sample => {
                    next_knot += 1;
                    knot
                }
                _ => sample,
            };
            if end <= t {
                continue;
            }
            let h = end - t;
            let (u0, u1) = (u_at(t, false), u_at(end, true));
            let bu0 = b * &u0;
            let b_slope = b * ((&u1 - &u0) / h);
            x = exponentials.with(h, end, |e| {
                let mut next = &e.phi * &x + &e.psi1 * &bu0 + &e.psi2 * &b_slope;
                // The length used may differ from h by round-off of the times: one Euler
                // step over the rest, at the end's input.
                let delta = h - e.h;
                if delta != 0.0 {
                    let slope = a * &next + b * &u1;
                    next += slope * delta;
                }
                next
            })?;
            t = end;
        }
        let y = c * &x + d * u_at(sample, false);
        states.row_mut(k).copy_from(&x.transpose());
        outputs.row_mut(k).copy_from(&y.transpose());
    }
    if !states.iter().all(|x| x.is_finite()) {
        return Err(Error::NonFinite {
            context: "the time response (it grows beyond double precision)".into(),
        });
    }
    Ok((states, outputs))
}

/// Checks sample times (at least one, finite, increasing, the first ≥ 0) and the size of a
/// result holding `width` numbers per time.
fn check_times(times: &[f64], width: usize) -> Result<()> {
    let bad = |what: &'static str, rule: String| Err(Error::InvalidArgument { what, rule });
    if times.is_empty() {
        return bad("times", "at least one sample time is needed".into());
    }
    if times.len() > MAX_RESPONSE_TIMES {
        return Err(Error::LimitExceeded {
            what: "times",
            rule: format!(
                "at most {MAX_RESPONSE_TIMES} sample times, got {}",
                times.len()
            ),
        });
    }
    let values = width.saturating_mul(times.len());
    if values > MAX_RESPONSE_VALUES {
        return Err(Error::LimitExceeded {
            what: "times",
            rule: format!(
                "{} sample times of {width} states and outputs are {values} numbers (about {} MB); at most {MAX_RESPONSE_VALUES}",
                times.len(),
                values / 125_000
            ),
        });
    }
    for (k, t) in times.iter().enumerate() {
        if !t.is_finite() {
            return bad("times", format!("time {} is not finite ({t})", k + 1));
        }
        if k == 0 && *t < 0.0 {
            return bad(
                "times",
                format!(
                    "the initial state is at t = 0: the first time must be >= 0, got {}",
                    short_number(*t)
                ),
            );
        }
        if k > 0 && *t <= times[k - 1] {
            return bad(
                "times",
                format!(
                    "must increase: time {} ({} s) is not after time {k} ({} s)",
                    k + 1,
                    short_number(*t),
                    short_number(times[k - 1])
                ),
            );
        }
    }
    Ok(())
}
