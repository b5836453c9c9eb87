//! Time responses of the linear bicycle against independent methods — the modal solution
//! (faer's eigen-decomposition of A, each mode's convolution with a piecewise-linear input in
//! closed form) and Dormand–Prince 5(4) — and identities (a step's final value is the static
//! gain G(0) of the transfer functions; superposition; zero in, exactly zero out; the impulse
//! response is the step response's derivative); the same manoeuvre on the non-linear model,
//! whose difference from the linear one scales as the amplitude cubed (x's as its square);
//! and the typed errors of bad requests.

use nalgebra::{Complex, DMatrix, DVector};
use whipple::advanced::integrate::Dopri5Settings;
use whipple::advanced::linear::{
    Input, InputSignal, LinearSystem, Manoeuvre, Output, StateVariable, SystemRequest,
    TimeResponse, compare_manoeuvre,
};
use whipple::{BenchmarkParameters, Error, Result};

type C64 = Complex<f64>;

fn bike() -> BenchmarkParameters {
    BenchmarkParameters::meijaard2007()
}

fn grid(step: f64, end: f64) -> Vec<f64> {
    let n = (end / step).round() as usize;
    (0..=n).map(|k| step * k as f64).collect()
}

/// Both torques and a push at the rider's back in; the path in the plane among the states.
fn with_path(speed: f64) -> Result<LinearSystem> {
    LinearSystem::new(
        &bike(),
        speed,
        &SystemRequest {
            states: vec![
                StateVariable::Yaw,
                StateVariable::RearContactX,
                StateVariable::RearContactY,
            ],
            inputs: vec![
                Input::LeanTorque,
                Input::SteerTorque,
                Input::LateralForce { x: 0.3, z: -0.9 },
            ],
            outputs: vec![
                Output::State(StateVariable::Lean),
                Output::FrontContactY,
                Output::YawRate,
            ],
        },
    )
}

/// A lean torque ramping up and down, a steer torque held in steps (jumps), a push: knots that
/// the sample times do not meet.
fn inputs() -> Result<Vec<InputSignal>> {
    Ok(vec![
        InputSignal::piecewise_linear(vec![0.13, 0.71, 1.4], vec![0.0, 2.0, -0.5])?,
        InputSignal::piecewise_constant(vec![0.05, 0.333, 0.9, 2.2], vec![1.0, -0.7, 0.4, 0.0])?,
        InputSignal::pulse(1.01, 0.27, 15.0)?,
    ])
}

/// The largest difference of two matrices relative to the larger's largest entry.
fn relative_difference(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    let scale = a.amax().max(b.amax()).max(f64::MIN_POSITIVE);
    (a - b).amax() / scale
}

/// The modal solution of the lean–steer system: A = V Λ V⁻¹ from faer (an eigen-solver
/// independent of the matrix exponential), each mode z = (V⁻¹ x) integrated exactly over each
/// piece of a piecewise-linear input, ∫₀ʰ e^{λ(h−s)} (u₀ + r s) ds =
/// u₀ (e^{λh} − 1)/λ + r (e^{λh} − 1 − λh)/λ², at every sample time from t = 0.
fn modal_solution(
    system: &LinearSystem,
    x0: &[f64],
    signals: &[InputSignal],
    times: &[f64],
) -> DMatrix<f64> {
    let n = system.states().len();
    let a = system.a();
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)]);
    let evd = m
        .eigen()
        .expect("faer's eigen-decomposition of a finite matrix");
    let lambda: Vec<C64> = (0..n)
        .map(|k| {
            let z = evd.S().column_vector()[k];
            C64::new(z.re, z.im)
        })
        .collect();
    let v = DMatrix::<C64>::from_fn(n, n, |i, j| {
        let z = evd.U()[(i, j)];
        C64::new(z.re, z.im)
    });
    let v_inv = v.clone().try_inverse().expect("diagonalizable A");
    let b = system.b().map(|x| C64::new(x, 0.0));
    let mut z = &v_inv * DVector::from_iterator(n, x0.iter().map(|x| C64::new(*x, 0.0)));
    let mut breaks: Vec<f64> = signals
        .iter()
        .flat_map(|s| s.knots().iter().copied())
        .chain(times.iter().copied())
        .filter(|t| *t > 0.0)
        .collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut out = DMatrix::zeros(times.len(), n);
    let mut t = 0.0;
    let mut k = 0;
    let mut record = |k: &mut usize, t: f64, z: &DVector<C64>| {
        while *k < times.len() && times[*k] == t {
            let x = &v * z;
            for i in 0..n {
                out[(*k, i)] = x[i].re;
            }
            *k += 1;
        }
    };
    record(&mut k, 0.0, &z);
    for &end in breaks.iter().filter(|b| **b <= times[times.len() - 1]) {
        let h = end - t;
        let u0 = DVector::from_iterator(signals.len(), signals.iter().map(|s| s.value(t)));
        let u1 = DVector::from_iterator(signals.len(), signals.iter().map(|s| s.value_before(end)));
        let r = (&u1 - &u0) / h;
        let bu0 = &v_inv * (&b * u0.map(|x| C64::new(x, 0.0)));
        let br = &v_inv * (&b * r.map(|x| C64::new(x, 0.0)));
        for i in 0..n {
            let l = lambda[i];
            let e = whipple::math::complex_exp(l * h);
            let phi1 = (e - 1.0) / l;
            let phi2 = (e - 1.0 - l * h) / (l * l);
            z[i] = e * z[i] + phi1 * bu0[i] + phi2 * br[i];
        }
        t = end;
        record(&mut k, t, &z);
    }
    out
}

/// The exact response equals the modal solution to 1e-12 of its size, at speeds below, inside
/// and above the self-stable range, with two torques of many pieces (ramps and jumps).
#[test]
fn exact_response_equals_the_modal_solution() -> Result<()> {
    for speed in [2.0, 5.0, 8.0] {
        let system = LinearSystem::new(&bike(), speed, &SystemRequest::lean_steer())?;
        let signals = &inputs()?[..2];
        let times = grid(0.01, 3.0);
        let x0 = [0.02, -0.01, 0.3, 0.1];
        let exact = system.response(&x0, signals, &times)?;
        let modal = modal_solution(&system, &x0, signals, &times);
        let error = relative_difference(&exact.states, &modal);
        println!(
            "v = {speed} m/s: exact vs modal, largest difference {error:.2e} of the response's size"
        );
        assert!(error < 1e-12, "v = {speed}: {error:e}");
        // Uneven sample times, which meet no knot.
        let uneven: Vec<f64> = (0..200)
            .map(|k| 0.0137 * k as f64 + 1e-3 * (k % 7) as f64)
            .collect();
        let exact = system.response(&x0, signals, &uneven)?;
        let error = relative_difference(
            &exact.states,
            &modal_solution(&system, &x0, signals, &uneven),
        );
        assert!(error < 1e-12, "v = {speed}, uneven times: {error:e}");
    }
    Ok(())
}

/// With the path among the states (A is defective there: the ψ → y chain, so no modal
/// solution), the exact response of three inputs with ramps and jumps equals the response to
/// the same input given as a function and integrated by Dormand–Prince 5(4) (dense output),
/// an independent method, within 100 rtol of the integrator's tolerance (rtol 1e-12, 1e-10, 1e-8).
#[test]
fn exact_response_equals_the_integrated_one() -> Result<()> {
    let system = with_path(5.0)?;
    let signals = inputs()?;
    let times = grid(0.05, 4.0);
    let x0 = [0.01, 0.0, -0.2, 0.0, 0.0, 0.0, 0.0];
    let exact = system.response(&x0, &signals, &times)?;
    let as_function = |t: f64, u: &mut [f64]| {
        for (u, s) in u.iter_mut().zip(&signals) {
            *u = s.value(t);
        }
        Ok(())
    };
    for (rtol, bound) in [(1e-12, 1e-9), (1e-10, 1e-8), (1e-8, 1e-6)] {
        let integrated = system.response_to_function(
            &x0,
            as_function,
            &times,
            &Dopri5Settings::with_rtol(rtol),
        )?;
        let error = relative_difference(&exact.states, &integrated.states);
        println!("DOPRI5 rtol {rtol:e}: largest difference {error:.2e} of the response's size");
        assert!(error < bound, "rtol {rtol:e}: {error:e}");
        let error = relative_difference(&exact.outputs, &integrated.outputs);
        assert!(error < bound, "outputs, rtol {rtol:e}: {error:e}");
    }
    Ok(())
}

/// At 5 m/s (inside the self-stable range, 4.29–6.02 m/s) a unit step of either torque
/// settles at the static gain G(0) of the transfer functions (polynomials, not A): lean, and
/// the yaw rate; 200 s is 31 times the slowest mode's time constant (capsize, −0.155 1/s).
#[test]
fn step_settles_at_the_static_gain() -> Result<()> {
    let system = with_path(5.0)?;
    let times = grid(5.0, 200.0);
    for input in 0..3 {
        let step = system.step_response(input, &times)?;
        for (output, name) in [(0, "lean"), (2, "yaw rate")] {
            let g0 = system
                .transfer_function(output, input)?
                .static_gain()
                .expect("no integrator from a torque to lean or the yaw rate");
            let last = step.outputs[(times.len() - 1, output)];
            println!(
                "{name} per {}: step's final value {last:.12e}, G(0) {g0:.12e}",
                system.inputs()[input]
            );
            assert!(
                (last - g0).abs() <= 1e-11 * g0.abs(),
                "{name}: {last} vs {g0}"
            );
        }
    }
    Ok(())
}

/// The response to the sum of two inputs from the sum of two initial states is the sum of the
/// responses; zero in from rest is zero out, exactly.
#[test]
fn superposition_and_zero() -> Result<()> {
    let system = with_path(4.0)?;
    let times = grid(0.07, 5.0);
    let first = inputs()?;
    let second = vec![
        InputSignal::pulse(0.2, 1.0, -3.0)?,
        InputSignal::piecewise_linear(vec![0.0, 2.0, 2.0, 3.3], vec![0.5, -0.5, 1.0, 0.0])?,
        InputSignal::step(0.77, 4.0)?,
    ];
    let sum: Vec<InputSignal> = first
        .iter()
        .zip(&second)
        .map(|(a, b)| {
            let mut knots: Vec<f64> = a.knots().iter().chain(b.knots()).copied().collect();
            knots.sort_by(f64::total_cmp);
            knots.dedup();
            // Sample the sum on both sides of every knot: a jump of either is a jump of the sum.
            let (mut ks, mut vs) = (Vec::new(), Vec::new());
            for t in knots {
                let (before, after) = (
                    a.value_before(t) + b.value_before(t),
                    a.value(t) + b.value(t),
                );
                ks.push(t);
                vs.push(before);
                if after != before {
                    ks.push(t);
                    vs.push(after);
                }
            }
            InputSignal::piecewise_linear(ks, vs)
        })
        .collect::<Result<_>>()?;
    let x1 = [0.01, 0.02, 0.0, -0.1, 0.0, 0.0, 0.0];
    let x2 = [0.0, -0.01, 0.2, 0.0, 0.1, 0.5, -0.3];
    let x12: Vec<f64> = x1.iter().zip(&x2).map(|(a, b)| a + b).collect();
    let r1 = system.response(&x1, &first, &times)?;
    let r2 = system.response(&x2, &second, &times)?;
    let r12 = system.response(&x12, &sum, &times)?;
    let error = relative_difference(&r12.states, &(&r1.states + &r2.states));
    println!("superposition: largest difference {error:.2e}");
    assert!(error < 1e-13, "{error:e}");
    assert!(relative_difference(&r12.outputs, &(&r1.outputs + &r2.outputs)) < 1e-13);

    let zero = vec![InputSignal::zero(); 3];
    let rest = system.response(&[0.0; 7], &zero, &times)?;
    assert!(
        rest.states
            .iter()
            .chain(rest.outputs.iter())
            .all(|x| *x == 0.0)
    );
    Ok(())
}

/// The impulse response is the step response's derivative: x_impulse(t) = A x_step(t) + B eᵢ
/// (to round-off), and the response to a pulse of area 1 and width Δ approaches it as Δ → 0
/// (to O(Δ): 1e-4 of its size for Δ = 1e-5 s).
#[test]
fn impulse_is_the_derivative_of_the_step() -> Result<()> {
    let system = with_path(5.0)?;
    let times = grid(0.1, 4.0);
    for input in 0..3 {
        let impulse = system.impulse_response(input, &times)?;
        let step = system.step_response(input, &times)?;
        let b = system.b().column(input).transpose();
        let derivative = DMatrix::from_fn(times.len(), 7, |k, i| {
            (system.a().row(i) * step.states.row(k).transpose())[0] + b[i]
        });
        let error = relative_difference(&impulse.states, &derivative);
        assert!(error < 1e-12, "input {input}: {error:e}");
        let delta = 1e-5;
        let mut signals = vec![InputSignal::zero(); 3];
        signals[input] = InputSignal::pulse(0.0, delta, 1.0 / delta)?;
        let later: Vec<f64> = times.iter().map(|t| t + delta).collect();
        let pulse = system.response(&[0.0; 7], &signals, &later)?;
        let error = relative_difference(&impulse.states, &pulse.states);
        println!("input {input}: impulse vs Δ-pulse {error:.2e}");
        assert!(error < 1e-4, "input {input}: {error:e}");
        // At t = 0⁺ the impulse has given the rates their jump B eᵢ.
        assert_eq!(impulse.states.row(0), b);
    }
    Ok(())
}

/// The path in the plane: x is the nominal run plus its deviation, y and ψ the states, the
/// front contact's y the output; counter-steering (a steer torque to the right turns the
/// bicycle left), and a uniform grid needs one exponential (the same numbers as a grid whose
/// intervals are not all bit-equal).
#[test]
fn ground_path() -> Result<()> {
    let system = with_path(5.0)?;
    let times = grid(0.01, 3.0);
    let signals = vec![
        InputSignal::zero(),
        InputSignal::pulse(0.0, 0.5, 1.0)?,
        InputSignal::zero(),
    ];
    let response = system.response(&[0.0; 7], &signals, &times)?;
    let path = response.ground_path().expect("ψ and y are states");
    let x = response.state(StateVariable::RearContactX).expect("x_P");
    for (k, t) in times.iter().enumerate() {
        assert_eq!(path.rear_x[k], x[k] + 5.0 * t);
    }
    assert_eq!(path.front_y, response.output(&Output::FrontContactY));
    assert!(
        path.yaw[300] < -0.05 && path.rear_y[300] < -0.1,
        "{} {}",
        path.yaw[300],
        path.rear_y[300]
    );
    // The same times built another way (an accumulated sum), intervals differing in their
    // last bits: the same response to round-off.
    let mut summed = vec![0.0];
    for _ in 0..300 {
        summed.push(summed[summed.len() - 1] + 0.01);
    }
    let again = system.response(&[0.0; 7], &signals, &summed)?;
    let error = relative_difference(&response.states, &again.states);
    assert!(error < 1e-12, "{error:e}");
    // Without ψ and y there is no path.
    let plain = LinearSystem::new(&bike(), 5.0, &SystemRequest::lean_steer())?;
    let r = plain.initial_response(&[0.1, 0.0, 0.0, 0.0], &times)?;
    assert!(r.ground_path().is_none());
    Ok(())
}

fn pulse_manoeuvre(amplitude: f64) -> Result<Manoeuvre> {
    Ok(Manoeuvre {
        speed: 5.0,
        lean: 0.0,
        steer: 0.0,
        inputs: vec![(Input::SteerTorque, InputSignal::pulse(0.0, 0.5, amplitude)?)],
    })
}

/// Issue 29: a steer-torque pulse of 0.5 s on the benchmark at 5 m/s, over 3 s, on the linear
/// and the non-linear model. The difference is odd in the amplitude for lean, steer, yaw and
/// the lateral positions, so O(a³): halving a divides it by 8; x's is even, O(a²): by 4. Two
/// consecutive halvings (0.1 → 0.05 → 0.025 N m), each ratio within 1% (measured: 7.992 and
/// 7.998 for lean; 4.005 and 4.001 for x; at 1 → 0.5 N m the lean's is still 7.3). And the
/// models agree to first order, which a sign error (of ψ, y or a torque) would break.
#[test]
fn issue_29_nonlinear_difference_scales_as_amplitude_cubed() -> Result<()> {
    let times = grid(0.05, 3.0);
    let mut maxima = Vec::new();
    for a in [0.1, 0.05, 0.025] {
        let both = compare_manoeuvre(&bike(), &pulse_manoeuvre(a)?, &times, 1e-13)?;
        let (linear, difference) = (both.linear.max_abs(), both.difference.max_abs());
        println!(
            "a = {a} N m: linear max {linear:.3?}; difference max {difference:.3?}; {} steps",
            both.nonlinear_steps
        );
        for i in [0, 1, 2, 4, 5] {
            assert!(
                difference[i] < 0.05 * linear[i],
                "quantity {i}: {difference:?} vs {linear:?}"
            );
        }
        maxima.push(difference);
    }
    let names = ["lean", "steer", "yaw", "rear_x", "rear_y", "front_y"];
    for pair in maxima.windows(2) {
        for (i, name) in names.iter().enumerate() {
            let ratio = pair[0][i] / pair[1][i];
            println!("{name}: ratio {ratio:.4}");
            let expected = if *name == "rear_x" { 4.0 } else { 8.0 };
            assert!(
                (ratio / expected - 1.0).abs() < 0.01,
                "{name}: ratio {ratio} where {expected} is expected"
            );
        }
    }
    Ok(())
}

/// An initial lean, no torque: the same scaling (the models agree to first order from a
/// leaned start too), and a lateral force is refused by name.
#[test]
fn initial_lean_and_refused_lateral_force() -> Result<()> {
    let times = grid(0.1, 2.0);
    let mut maxima = Vec::new();
    for lean in [0.02, 0.01] {
        let start = Manoeuvre {
            speed: 5.0,
            lean,
            steer: 0.0,
            inputs: vec![],
        };
        let both = compare_manoeuvre(&bike(), &start, &times, 1e-13)?;
        assert_eq!(both.linear.lean[0], lean);
        assert!((both.nonlinear.lean[0] - lean).abs() < 1e-14);
        maxima.push(both.difference.max_abs());
    }
    let ratio = maxima[0][0] / maxima[1][0];
    println!("initial lean: lean difference ratio {ratio:.4}");
    assert!((ratio / 8.0 - 1.0).abs() < 0.05, "{ratio}");

    let pushed = Manoeuvre {
        speed: 5.0,
        lean: 0.0,
        steer: 0.0,
        inputs: vec![(
            Input::LateralForce { x: 0.3, z: -0.9 },
            InputSignal::pulse(0.0, 0.1, 50.0)?,
        )],
    };
    match compare_manoeuvre(&bike(), &pushed, &times, 1e-10) {
        Err(Error::InvalidArgument {
            what: "inputs",
            rule,
        }) => {
            assert!(
                rule.contains("lateral_force") && rule.contains("no lateral force"),
                "{rule}"
            )
        }
        other => panic!("a lateral force on the non-linear model: {other:?}"),
    }
    Ok(())
}

fn invalid(result: Result<impl std::fmt::Debug>, field: &str, words: &str) {
    match result {
        Err(Error::InvalidArgument { what, rule }) | Err(Error::LimitExceeded { what, rule }) => {
            assert_eq!(what, field, "{rule}");
            assert!(rule.contains(words), "{field}: {rule}");
        }
        other => panic!("{field}: expected an error, got {other:?}"),
    }
}

/// Bad times, knots, values, inputs and initial states: each refused, naming the field.
#[test]
fn bad_requests_name_their_field() -> Result<()> {
    let system = with_path(5.0)?;
    let zero = vec![InputSignal::zero(); 3];
    let x0 = [0.0; 7];
    invalid(
        system.response(&x0, &zero, &[0.0, 2.0, 1.0]),
        "times",
        "must increase",
    );
    invalid(
        system.response(&x0, &zero, &[0.0, 1.0, 1.0]),
        "times",
        "must increase",
    );
    invalid(
        system.response(&x0, &zero, &[0.0, f64::NAN]),
        "times",
        "not finite",
    );
    invalid(
        system.response(&x0, &zero, &[0.0, f64::INFINITY]),
        "times",
        "not finite",
    );
    invalid(system.response(&x0, &zero, &[-1.0, 0.0]), "times", ">= 0");
    invalid(system.response(&x0, &zero, &[]), "times", "at least one");
    let many = vec![0.0; whipple::advanced::linear::MAX_RESPONSE_TIMES + 1];
    invalid(system.response(&x0, &zero, &many), "times", "at most");
    invalid(
        system.response(&x0, &zero, &[0.0, 1e300]),
        "times",
        "too long for the matrix exponential",
    );
    invalid(
        system.response(&x0, &zero[..2], &[0.0]),
        "inputs",
        "one signal per input",
    );
    invalid(
        system.response(&[0.0; 4], &zero, &[0.0]),
        "initial state",
        "one value per state",
    );
    invalid(
        system.response(&[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0], &zero, &[0.0]),
        "initial state",
        "steer is not finite",
    );
    invalid(system.step_response(3, &[0.0]), "input", "3 input(s)");
    invalid(
        InputSignal::piecewise_linear(vec![0.0, 2.0, 1.0], vec![0.0; 3]),
        "knots",
        "must not decrease",
    );
    invalid(
        InputSignal::piecewise_linear(vec![1.0, 1.0, 1.0], vec![0.0; 3]),
        "knots",
        "three times",
    );
    invalid(
        InputSignal::piecewise_linear(vec![0.0, f64::NAN], vec![0.0; 2]),
        "knots",
        "not finite",
    );
    invalid(
        InputSignal::piecewise_linear(vec![], vec![]),
        "knots",
        "at least one",
    );
    invalid(
        InputSignal::piecewise_linear(vec![0.0, 1.0], vec![0.0]),
        "values",
        "one value per knot",
    );
    invalid(
        InputSignal::piecewise_linear(vec![0.0, 1.0], vec![0.0, f64::NAN]),
        "values",
        "not finite",
    );
    invalid(
        InputSignal::piecewise_constant(vec![0.0, 1.0, 1.0], vec![0.0; 3]),
        "knots",
        "must increase",
    );
    invalid(InputSignal::pulse(0.0, 0.0, 1.0), "duration", "positive");
    // The integrated response: the input function's own error comes back, and a value that
    // is not finite is named.
    let failing = |t: f64, _: &mut [f64]| {
        if t > 0.5 {
            Err(Error::InvalidArgument {
                what: "torque",
                rule: "the user's function failed".into(),
            })
        } else {
            Ok(())
        }
    };
    invalid(
        system.response_to_function(&x0, failing, &[0.0, 1.0], &Dopri5Settings::default()),
        "torque",
        "user's function",
    );
    let nan = |_: f64, u: &mut [f64]| {
        u[1] = f64::NAN;
        Ok(())
    };
    match system.response_to_function(&x0, nan, &[0.0, 1.0], &Dopri5Settings::default()) {
        Err(Error::NonFinite { context }) => assert!(context.contains("steer_torque"), "{context}"),
        other => panic!("{other:?}"),
    }
    Ok(())
}

/// Piecewise-constant signals are piecewise-linear ones with a jump at every knot.
#[test]
fn signals() -> Result<()> {
    let held = InputSignal::piecewise_constant(vec![0.5, 1.0], vec![2.0, -1.0])?;
    assert_eq!(held.knots(), &[0.5, 1.0, 1.0]);
    assert_eq!(
        (held.value(0.0), held.value(0.99), held.value(1.0)),
        (2.0, 2.0, -1.0)
    );
    assert_eq!(
        (held.value_before(1.0), held.value_before(1.5)),
        (2.0, -1.0)
    );
    let step = InputSignal::step(1.0, 3.0)?;
    assert_eq!((step.value_before(1.0), step.value(1.0)), (0.0, 3.0));
    // A constant response to a constant input: the response of a piecewise-constant signal
    // with one value equals that of the constant.
    let system = with_path(5.0)?;
    let times = grid(0.25, 2.0);
    let constant = vec![
        InputSignal::zero(),
        InputSignal::constant(0.5)?,
        InputSignal::zero(),
    ];
    let pieces = vec![
        InputSignal::zero(),
        InputSignal::piecewise_constant(vec![0.0, 0.3, 1.1], vec![0.5; 3])?,
        InputSignal::zero(),
    ];
    let (a, b): (TimeResponse, TimeResponse) = (
        system.response(&[0.0; 7], &constant, &times)?,
        system.response(&[0.0; 7], &pieces, &times)?,
    );
    assert!(relative_difference(&a.states, &b.states) < 1e-13);
    Ok(())
}
