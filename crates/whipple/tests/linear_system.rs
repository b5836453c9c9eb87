//! The bicycle as a linear system: its transfer functions against independent computations —
//! the poles against faer's eigenvalues of A, G(0) against −C A⁻¹ B, G(iω) from the
//! polynomials against a direct complex solve of (iωI − A) X = B, the counter-steering zero
//! against the closed form on Meijaard 2007's published matrices — and the typed errors of bad
//! requests.

use nalgebra::{Complex, DMatrix};
use whipple::advanced::linear::{
    Input, LinearSystem, Output, StateVariable, SystemRequest, origin_zero_speeds,
};
use whipple::advanced::side_view::side_view;
use whipple::{BenchmarkParameters, Error, Result};
use whipple_reference::meijaard2007 as published;

type C64 = Complex<f64>;

fn bike() -> BenchmarkParameters {
    BenchmarkParameters::meijaard2007()
}

/// Every state, every input (a push at the rider's back), every kind of output.
fn everything() -> SystemRequest {
    SystemRequest {
        states: StateVariable::IGNORABLE.to_vec(),
        inputs: vec![
            Input::LeanTorque,
            Input::SteerTorque,
            Input::LateralForce { x: 0.3, z: -0.9 },
        ],
        outputs: vec![
            Output::State(StateVariable::Lean),
            Output::State(StateVariable::Steer),
            Output::State(StateVariable::LeanRate),
            Output::State(StateVariable::SteerRate),
            Output::State(StateVariable::Yaw),
            Output::State(StateVariable::RearContactX),
            Output::State(StateVariable::RearContactY),
            Output::State(StateVariable::RearWheelAngle),
            Output::YawRate,
            Output::FrontContactY,
            Output::RearFramePointY { x: 0.3, z: -0.9 },
            Output::FrontFramePointY { x: 0.85, z: -0.75 },
            Output::RearContactLateralAcceleration,
        ],
    }
}

fn faer_eigenvalues(a: &DMatrix<f64>) -> Vec<C64> {
    let m = faer::Mat::<f64>::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)]);
    let values = m
        .eigenvalues()
        .expect("faer's eigenvalues of a finite matrix");
    values.iter().map(|z| C64::new(z.re, z.im)).collect()
}

/// The poles of every pair are the eigenvalues of A: the four of the lean–steer block
/// (certified, from the quartic) equal faer's eigenvalues of the system's A (Hessenberg QR, an
/// independent method) to 1e-12 relative, and A's other eigenvalues, those of the ignorable
/// coordinates, are zero, as are the integrators' poles.
#[test]
fn poles_are_the_eigenvalues_of_a() -> Result<()> {
    for speed in [0.0, 0.5, 2.0, 4.0, 5.0, 7.5, 10.0] {
        let system = LinearSystem::new(&bike(), speed, &everything())?;
        let mut from_a = faer_eigenvalues(system.a());
        // Nine eigenvalues: five zeros (the ignorable coordinates), then the four.
        from_a.sort_by(|x, y| whipple::math::norm(x).total_cmp(&whipple::math::norm(y)));
        let scale = from_a.iter().map(whipple::math::norm).fold(1.0, f64::max);
        // ψ → y is a Jordan chain (A is defective there), so faer's computed zeros move by
        // up to about √ε of A's scale.
        for zero in &from_a[..5] {
            assert!(
                whipple::math::norm(zero) <= 1e-7 * scale,
                "v = {speed}: {zero}"
            );
        }
        for i in 0..system.outputs().len() {
            for j in 0..system.inputs().len() {
                let g = system.transfer_function(i, j)?;
                let poles = g.poles();
                assert_eq!(poles.len(), 4 + g.integrators);
                for p in &poles[..4] {
                    let nearest = from_a[5..]
                        .iter()
                        .map(|z| whipple::math::norm(z - p))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        nearest <= 1e-12 * whipple::math::norm(p).max(1.0),
                        "v = {speed}: pole {p} is {nearest:e} from faer's nearest eigenvalue"
                    );
                }
                assert!(poles[4..].iter().all(|p| whipple::math::norm(p) == 0.0));
            }
        }
    }
    Ok(())
}

/// G(0) = −C A⁻¹ B wherever A is invertible (the lean–steer system, away from the capsize
/// speed, where det(g K₀ + v² K₂) = 0).
#[test]
fn static_gain_is_minus_c_a_inverse_b() -> Result<()> {
    let request = SystemRequest {
        states: vec![],
        inputs: vec![
            Input::LeanTorque,
            Input::SteerTorque,
            Input::LateralForce { x: 0.5, z: -1.1 },
        ],
        outputs: vec![
            Output::State(StateVariable::Lean),
            Output::State(StateVariable::Steer),
            Output::State(StateVariable::LeanRate),
            Output::YawRate,
            Output::RearContactLateralAcceleration,
        ],
    };
    for speed in [0.0, 1.0, 3.0, 5.0, 8.0] {
        let system = LinearSystem::new(&bike(), speed, &request)?;
        let a_inv = system
            .a()
            .clone()
            .try_inverse()
            .expect("A invertible off v_c");
        let expected = -(system.c() * a_inv * system.b()) + system.d();
        for i in 0..system.outputs().len() {
            for j in 0..system.inputs().len() {
                let g0 = system
                    .transfer_function(i, j)?
                    .static_gain()
                    .expect("no integrator, no pole at 0");
                let e = expected[(i, j)];
                assert!(
                    (g0 - e).abs() <= 1e-12 * e.abs().max(1e-300) || (g0 - e).abs() <= 1e-14,
                    "v = {speed}, {} / {}: G(0) = {g0} vs −C A⁻¹ B = {e}",
                    system.outputs()[i],
                    system.inputs()[j]
                );
            }
        }
    }
    Ok(())
}

/// G(iω) evaluated from the polynomials equals C (iωI − A)⁻¹ B + D solved directly (complex
/// LU on the 9-state realization) at 200 frequencies from 0.01 to 1000 rad/s, for every pair,
/// to 1e-12 relative (to the largest |G| of the pair, so that a notch's near-zero values are
/// held to the same absolute accuracy as its neighbours, the direct solve's own error being
/// relative to ‖(iωI − A)⁻¹‖).
#[test]
fn polynomial_response_equals_the_direct_solve() -> Result<()> {
    let omegas: Vec<f64> = (0..200)
        .map(|k| whipple::math::powf(10f64, -2.0 + 5.0 * k as f64 / 199.0))
        .collect();
    let mut worst = 0.0f64;
    for speed in [0.3, 2.0, 4.6, 6.0, 9.0] {
        let system = LinearSystem::new(&bike(), speed, &everything())?;
        let n = system.states().len();
        let a = system.a().map(|x| C64::new(x, 0.0));
        let b = system.b().map(|x| C64::new(x, 0.0));
        let c = system.c().map(|x| C64::new(x, 0.0));
        let direct: Vec<DMatrix<C64>> = omegas
            .iter()
            .map(|&w| {
                let lhs = DMatrix::<C64>::identity(n, n) * C64::new(0.0, w) - &a;
                let x = lhs.lu().solve(&b).expect("iω is not an eigenvalue");
                &c * x
            })
            .collect();
        let responses = system.frequency_responses(&omegas)?;
        for (i, row) in responses.iter().enumerate() {
            for (j, response) in row.iter().enumerate() {
                let size = direct
                    .iter()
                    .map(|g| whipple::math::norm(g[(i, j)]))
                    .fold(0.0, f64::max);
                for (k, g) in response.response.iter().enumerate() {
                    let error = whipple::math::norm(g - direct[k][(i, j)]);
                    if size > 0.0 {
                        worst = worst.max(error / size);
                    }
                    assert!(
                        error <= 1e-12 * size,
                        "v = {speed}, {} / {}, ω = {}: {g} vs {}",
                        system.outputs()[i],
                        system.inputs()[j],
                        omegas[k],
                        direct[k][(i, j)]
                    );
                }
            }
        }
    }
    println!("largest relative difference: {worst:e}");
    Ok(())
}

/// The phase is unwrapped along the grid (steps below π), magnitude and dB agree, and the
/// integrators show: yaw per steer torque falls off as 1/ω at low frequency with its phase
/// near −90° plus the static lean-steer phase.
#[test]
fn magnitude_db_and_unwrapped_phase() -> Result<()> {
    let system = LinearSystem::new(&bike(), 5.0, &everything())?;
    let omegas: Vec<f64> = (0..400)
        .map(|k| whipple::math::powf(10f64, -3.0 + 6.0 * k as f64 / 399.0))
        .collect();
    for i in 0..system.outputs().len() {
        for j in 0..system.inputs().len() {
            let r = system
                .transfer_function(i, j)?
                .frequency_response(&omegas)?;
            for k in 0..omegas.len() {
                if r.magnitude[k] > 0.0 {
                    assert!(
                        (whipple::math::powf(10f64, r.magnitude_db[k] / 20.0) / r.magnitude[k]
                            - 1.0)
                            .abs()
                            < 1e-12
                    );
                    let wrapped = whipple::math::arg(r.response[k]);
                    let turns = (r.phase[k] - wrapped) / std::f64::consts::TAU;
                    assert!((turns - turns.round()).abs() < 1e-9);
                }
                if k > 0 {
                    assert!((r.phase[k] - r.phase[k - 1]).abs() <= std::f64::consts::PI);
                }
            }
        }
    }
    // ψ / T_δ = (v + c s) cos λ / (w s) · δ / T_δ: one integrator.
    let yaw = system.transfer_function(4, 1)?;
    let steer = system.transfer_function(1, 1)?;
    assert_eq!((yaw.integrators, steer.integrators), (1, 0));
    let p = bike();
    for w in [0.01, 0.7, 3.0, 40.0] {
        let s = C64::new(0.0, w);
        let expected = (s * p.c + 5.0) * whipple::math::cos(p.lambda) / (s * p.w) * steer.eval(s);
        assert!(
            whipple::math::norm(yaw.eval(s) - expected) <= 1e-13 * whipple::math::norm(expected)
        );
    }
    Ok(())
}

/// Steer torque → lean: G(s) = −(M₁₂ s² + v C₁₁₂ s + g K₀₁₂ + v² K₂₁₂) / det P(s), whose
/// zeros are those of the quadratic with Meijaard 2007's published entries (§5); below
/// v₀ = √(−g K₀₁₂ / K₂₁₂) one is in the right half-plane (counter-steering), beyond it neither.
#[test]
fn counter_steering_zero_of_the_benchmark() -> Result<()> {
    let (m12, c12, k012, k212) = (
        published::M[0][1],
        published::C1[0][1],
        published::K0[0][1],
        published::K2[0][1],
    );
    let g = bike().g;
    let request = SystemRequest {
        states: vec![],
        inputs: vec![Input::SteerTorque],
        outputs: vec![Output::State(StateVariable::Lean)],
    };
    let crossing = (-g * k012 / k212).sqrt();
    for speed in [0.0, 0.3, 1.0, 3.0, 5.0, 10.0] {
        let tf = LinearSystem::new(&bike(), speed, &request)?.transfer_function(0, 0)?;
        // The closed form on the published entries.
        let (a, b, c) = (m12, speed * c12, g * k012 + speed * speed * k212);
        let disc = b * b - 4.0 * a * c;
        assert!(disc > 0.0, "two real zeros at {speed} m/s");
        let q = -0.5 * (b + disc.sqrt().copysign(b));
        let mut expected = [q / a, c / q];
        expected.sort_by(|x, y| y.total_cmp(x));
        let zeros = tf.zeros()?;
        assert_eq!(zeros.len(), 2);
        for (z, e) in zeros.iter().zip(expected) {
            // The published entries are rounded to 14 decimals.
            assert!(
                z.im == 0.0 && (z.re - e).abs() <= 1e-11 * e.abs().max(1.0),
                "{z} vs {e}"
            );
        }
        assert_eq!(zeros[0].re > 0.0, speed < crossing, "v = {speed}");
        // The gain K = −M₁₂ / det M: the adjugate's −p₁₂ over det P, leading terms.
        assert!((tf.gain() + m12 / tf.characteristic[4]).abs() < 1e-12);
    }
    let speeds = origin_zero_speeds(&bike(), &Input::SteerTorque, StateVariable::Lean)?;
    assert_eq!(speeds.len(), 2);
    let (lo, hi) = speeds[1].enclosure();
    assert!(lo <= crossing + 1e-12 && crossing - 1e-12 <= hi && hi - lo < 1e-12);
    assert!(
        (speeds[1].value() - crossing).abs() < 1e-12
            && (speeds[0].value() + crossing).abs() < 1e-12
    );
    // Lean torque → steer: −p₂₁ = −(M₂₁ s² + v C₁₂₁ s + g K₀₂₁), K₂₁₂ = 0: its zero stays put.
    assert!(origin_zero_speeds(&bike(), &Input::LeanTorque, StateVariable::Steer)?.is_empty());
    Ok(())
}

/// The front contact's s² terms cancel exactly (y_F = cos λ (v² / w + v (1 + c / w) s) δ / s²
/// per unit of δ), so its transfer function has no spurious huge zero; with v = 0 the
/// integrators cancel against the numerator's factors of s.
#[test]
fn exact_cancellations() -> Result<()> {
    let system = LinearSystem::new(&bike(), 4.0, &everything())?;
    let front = system.transfer_function(9, 1)?;
    let steer = system.transfer_function(1, 1)?;
    assert_eq!(front.integrators, 2);
    assert_eq!(front.numerator.len(), steer.numerator.len() + 1);
    let at_rest = LinearSystem::new(&bike(), 0.0, &everything())?;
    // ψ = c cos λ δ / w at rest: no integrator left.
    assert_eq!(at_rest.transfer_function(4, 1)?.integrators, 0);
    // φ̇ = s φ: the lean rate's zeros are the lean's and one at the origin.
    let (lean, lean_rate) = (
        system.transfer_function(0, 1)?,
        system.transfer_function(2, 1)?,
    );
    let (mut z, z_rate) = (lean.zeros()?, lean_rate.zeros()?);
    z.push(C64::new(0.0, 0.0));
    z.sort_by(|x, y| y.re.total_cmp(&x.re));
    assert_eq!(z.len(), z_rate.len());
    for (a, b) in z.iter().zip(&z_rate) {
        assert!(
            whipple::math::norm(a - b) <= 1e-12 * whipple::math::norm(a).max(1.0),
            "{a} vs {b}"
        );
    }
    // x_P and θ_R are not reached to first order.
    for i in [5, 7] {
        let g = system.transfer_function(i, 1)?;
        assert!(g.numerator.is_empty() && g.gain() == 0.0 && g.zeros()?.is_empty());
    }
    Ok(())
}

fn refused(request: SystemRequest, field: &str, words: &str) {
    match LinearSystem::new(&bike(), 5.0, &request) {
        Err(Error::InvalidArgument { what, rule }) => {
            assert_eq!(what, field, "{rule}");
            assert!(rule.contains(words), "{rule}");
        }
        other => panic!("expected an error naming {field}, got {other:?}"),
    }
}

#[test]
fn bad_requests_name_their_field() -> Result<()> {
    let base = SystemRequest::lean_steer();
    refused(
        SystemRequest {
            outputs: vec![],
            ..base.clone()
        },
        "outputs",
        "at least one",
    );
    refused(
        SystemRequest {
            outputs: vec![Output::YawRate, Output::YawRate],
            ..base.clone()
        },
        "outputs",
        "yaw_rate is listed twice",
    );
    refused(
        SystemRequest {
            inputs: vec![Input::SteerTorque, Input::SteerTorque],
            ..base.clone()
        },
        "inputs",
        "listed twice",
    );
    refused(
        SystemRequest {
            inputs: vec![Input::LateralForce {
                x: f64::NAN,
                z: -1.0,
            }],
            ..base.clone()
        },
        "inputs",
        "finite",
    );
    refused(
        SystemRequest {
            states: vec![StateVariable::Yaw, StateVariable::RearContactY],
            outputs: vec![Output::FrontFramePointY {
                x: 1.0,
                z: f64::INFINITY,
            }],
            ..base.clone()
        },
        "outputs",
        "finite",
    );
    // A point inside nothing: below the ground, or outside the box the bicycle occupies.
    let track = vec![StateVariable::Yaw, StateVariable::RearContactY];
    refused(
        SystemRequest {
            inputs: vec![Input::LateralForce { x: 0.3, z: 0.2 }],
            ..base.clone()
        },
        "inputs",
        "input 1 (lateral_force(x = 0.3 m, z = 0.2 m)) is below the ground",
    );
    refused(
        SystemRequest {
            inputs: vec![Input::SteerTorque, Input::LateralForce { x: 3.0, z: -1.0 }],
            ..base.clone()
        },
        "inputs",
        "input 2 (lateral_force(x = 3 m, z = -1 m)) lies outside the bicycle, which spans x \
         from -0.300 to 1.370 m",
    );
    refused(
        SystemRequest {
            states: track.clone(),
            outputs: vec![Output::RearFramePointY { x: 0.5, z: -4.0 }],
            ..base.clone()
        },
        "outputs",
        "output 1 (rear_frame_point_y(x = 0.5 m, z = -4 m)) lies outside the bicycle",
    );
    refused(
        SystemRequest {
            states: track.clone(),
            outputs: vec![Output::FrontFramePointY { x: -0.5, z: -0.5 }],
            ..base.clone()
        },
        "outputs",
        "lies outside the bicycle",
    );
    refused(
        SystemRequest {
            states: track.clone(),
            outputs: vec![Output::FrontFramePointY { x: 1.0, z: 1e-9 }],
            ..base.clone()
        },
        "outputs",
        "below the ground",
    );
    // On the box's edges (the rear wheel's back, the front wheel's front, the ground) and at
    // the rider's head (the top of B's ellipsoid, z = -0.9 - 0.723…) the points are the
    // bicycle's.
    let [lo, hi] = side_view(&bike(), None).extent();
    assert_eq!((lo, hi[0]), ([-0.3, 0.0], 1.02 + 0.35));
    assert!((1.55..1.7).contains(&hi[1]), "{hi:?}");
    LinearSystem::new(
        &bike(),
        5.0,
        &SystemRequest {
            states: track.clone(),
            inputs: vec![
                Input::LateralForce { x: -0.3, z: 0.0 },
                Input::LateralForce {
                    x: hi[0],
                    z: -hi[1],
                },
            ],
            outputs: vec![
                Output::RearFramePointY { x: 0.3, z: -hi[1] },
                Output::FrontFramePointY { x: hi[0], z: 0.0 },
            ],
        },
    )?;
    refused(
        SystemRequest {
            states: vec![StateVariable::Lean],
            ..base.clone()
        },
        "states",
        "always",
    );
    refused(
        SystemRequest {
            states: vec![StateVariable::Yaw, StateVariable::Yaw],
            ..base.clone()
        },
        "states",
        "twice",
    );
    refused(
        SystemRequest {
            states: vec![StateVariable::RearContactY],
            ..base.clone()
        },
        "states",
        "needs yaw",
    );
    refused(
        SystemRequest {
            states: vec![StateVariable::Yaw],
            outputs: vec![Output::FrontContactY],
            ..base.clone()
        },
        "outputs",
        "needs rear_contact_y",
    );
    refused(
        SystemRequest {
            outputs: vec![Output::State(StateVariable::Yaw)],
            ..base.clone()
        },
        "outputs",
        "needs yaw",
    );
    let many = (0..=whipple::advanced::linear::MAX_SIGNALS)
        .map(|k| Output::State(StateVariable::LEAN_STEER[k % 4]))
        .collect();
    assert!(matches!(
        LinearSystem::new(
            &bike(),
            5.0,
            &SystemRequest {
                outputs: many,
                ..base.clone()
            }
        ),
        Err(Error::LimitExceeded {
            what: "outputs",
            ..
        })
    ));
    let system = LinearSystem::new(&bike(), 5.0, &everything())?;
    assert!(matches!(
        system.transfer_function(13, 0),
        Err(Error::InvalidArgument { what: "output", .. })
    ));
    assert!(matches!(
        system.transfer_function(0, 3),
        Err(Error::InvalidArgument { what: "input", .. })
    ));
    let yaw = system.transfer_function(4, 1)?;
    for bad in [[1.0, f64::NAN], [0.0, 1.0]] {
        assert!(matches!(
            yaw.frequency_response(&bad),
            Err(Error::InvalidArgument {
                what: "frequencies",
                ..
            })
        ));
    }
    assert!(LinearSystem::new(&bike(), f64::INFINITY, &base).is_err());
    let bad_bike = BenchmarkParameters {
        m_b: -1.0,
        ..bike()
    };
    assert!(matches!(
        LinearSystem::new(&bad_bike, 5.0, &base),
        Err(Error::InvalidParameter { .. })
    ));
    Ok(())
}

/// Rows that are derivatives of others: the yaw rate output is A's row of ψ, and the rear
/// contact's lateral acceleration is the derivative of ẏ = (A x)_y along ẋ = A x + B u, that
/// is (A A)_y (with B's rows of ψ and y zero, no input enters) — the identity ÿ = v ψ̇.
#[test]
fn derived_output_rows() -> Result<()> {
    for speed in [0.0, 2.0, 6.0] {
        let system = LinearSystem::new(&bike(), speed, &everything())?;
        let (a, b, c) = (system.a(), system.b(), system.c());
        let index = |s| system.state_index(s).expect("requested");
        let (yaw, y) = (
            index(StateVariable::Yaw),
            index(StateVariable::RearContactY),
        );
        let a2 = a * a;
        for j in 0..system.states().len() {
            assert_eq!(c[(8, j)], a[(yaw, j)], "ψ̇ at v = {speed}");
            assert!((c[(12, j)] - a2[(y, j)]).abs() <= 1e-15 * (1.0 + a2[(y, j)].abs()));
        }
        assert!(b.row(yaw).iter().chain(b.row(y).iter()).all(|x| *x == 0.0));
    }
    Ok(())
}

/// Closed-loop transfer functions (u = r − K x, gains on φ, δ, φ̇, δ̇) from the closed loop's
/// polynomial matrix, against a direct complex solve of the closed loop's state space
/// (C − D K)(iω I − A + B K)⁻¹ B + D; their poles are the closed loop's eigenvalues; and the
/// steer torque in the loop (`Output::Input`) follows the loop's sensitivity: u / r =
/// 1 / (1 + L(iω)), L the open loop's K (iω I − A)⁻¹ B formed from the open loop's own
/// transfer functions.
#[test]
fn closed_loop_transfer_functions_equal_the_direct_solve() -> Result<()> {
    use whipple::advanced::control::{ClosedLoop, Gains};
    let request = SystemRequest {
        states: vec![StateVariable::Yaw, StateVariable::RearContactY],
        inputs: vec![Input::SteerTorque],
        outputs: vec![
            Output::State(StateVariable::Lean),
            Output::State(StateVariable::Steer),
            Output::YawRate,
            Output::FrontContactY,
            Output::Input(Input::SteerTorque),
        ],
    };
    let k = DMatrix::from_row_slice(1, 6, &[-100.0, 10.0, -20.0, 0.0, 0.0, 0.0]);
    let closed = ClosedLoop::new(&bike(), &request, Gains::Constant(k.clone()))?;
    let omegas: Vec<f64> = (0..120)
        .map(|i| whipple::math::powf(10f64, -1.5 + 4.0 * i as f64 / 119.0))
        .collect();
    let mut worst = 0.0f64;
    for speed in [0.5, 2.0, 5.0, 8.0] {
        let system = closed.system(speed)?;
        let open = LinearSystem::new(&bike(), speed, &request)?;
        let n = system.states().len();
        let a = system.a().map(|x| C64::new(x, 0.0));
        let b = system.b().map(|x| C64::new(x, 0.0));
        let c = system.c().map(|x| C64::new(x, 0.0));
        let d = system.d().map(|x| C64::new(x, 0.0));
        // The poles: the closed loop's certified eigenvalues (and the integrators' zeros).
        let g = system.transfer_function(0, 0)?;
        let mut poles = g.poles();
        let mut expected = closed.eigen_sweep(&[speed])?.eigenvalues[0].to_vec();
        let key = |z: &C64| (z.re, z.im);
        poles.sort_by(|p, q| key(p).partial_cmp(&key(q)).unwrap());
        expected.sort_by(|p, q| key(p).partial_cmp(&key(q)).unwrap());
        for (p, q) in poles.iter().zip(&expected) {
            assert!(
                whipple::math::norm(p - q) <= 1e-12 * (1.0 + whipple::math::norm(q)),
                "{p} vs {q}"
            );
        }
        // Each state's open-loop response to steer torque, for L(iω) = Σ K_j G_j(iω).
        let states_request = SystemRequest {
            states: request.states.clone(),
            inputs: vec![Input::SteerTorque],
            outputs: open.states().iter().map(|s| Output::State(*s)).collect(),
        };
        let per_state = LinearSystem::new(&bike(), speed, &states_request)?;
        for (i, output) in system.outputs().iter().enumerate() {
            let response = system
                .transfer_function(i, 0)?
                .frequency_response(&omegas)?;
            for (w, got) in omegas.iter().zip(&response.response) {
                let lhs = DMatrix::<C64>::identity(n, n) * C64::new(0.0, *w) - &a;
                let x = lhs.lu().solve(&b).expect("iω is not an eigenvalue");
                let direct = (&c * x + &d)[(i, 0)];
                let error =
                    whipple::math::norm(got - direct) / whipple::math::norm(direct).max(1e-300);
                worst = worst.max(error);
                assert!(
                    error < 1e-10,
                    "v = {speed}, {output}, ω = {w}: {got} vs {direct}"
                );
                if let Output::Input(_) = output {
                    let mut loop_gain = C64::new(0.0, 0.0);
                    for j in 0..per_state.outputs().len() {
                        let gj = per_state.transfer_function(j, 0)?.eval(C64::new(0.0, *w));
                        loop_gain += gj * k[(0, j)];
                    }
                    let sensitivity = C64::new(1.0, 0.0) / (C64::new(1.0, 0.0) + loop_gain);
                    assert!(
                        whipple::math::norm(got - sensitivity)
                            < 1e-9 * whipple::math::norm(sensitivity)
                    );
                }
            }
        }
        // The open loop's u → u is exactly 1.
        let u = LinearSystem::new(&bike(), speed, &request)?.transfer_function(4, 0)?;
        assert_eq!(
            u.frequency_response(&[1.0])?.response[0],
            C64::new(1.0, 0.0)
        );
    }
    println!("largest relative difference: {worst:e}");
    // Output::Input needs the input among the inputs; gains on yaw are refused by name.
    let err = LinearSystem::new(
        &bike(),
        5.0,
        &SystemRequest {
            states: vec![],
            inputs: vec![Input::SteerTorque],
            outputs: vec![Output::Input(Input::LeanTorque)],
        },
    )
    .unwrap_err();
    assert!(
        matches!(&err, Error::InvalidArgument { what: "outputs", rule } if rule.contains("lean_torque")),
        "{err:?}"
    );
    let heading = DMatrix::from_row_slice(1, 6, &[-100.0, 10.0, -20.0, 0.0, 5.0, 0.0]);
    let err = ClosedLoop::new(&bike(), &request, Gains::Constant(heading))?
        .system(5.0)?
        .transfer_function(0, 0)
        .unwrap_err();
    assert!(
        matches!(&err, Error::InvalidArgument { what: "gains", .. }),
        "{err:?}"
    );
    Ok(())
}
