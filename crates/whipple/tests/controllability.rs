//! Controllability: the certified speeds where one input loses a lean–steer mode, checked
//! against a closed form from the published matrices, the Kalman matrix's rank and the modes'
//! left eigenvectors computed independently.

use nalgebra::{Complex, DMatrix};
use whipple::advanced::control::uncontrollable_speeds;
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use whipple::advanced::roots::RealRoot;
use whipple::advanced::side_view::side_view;
use whipple::{BenchmarkParameters, presets};
use whipple_reference::meijaard2007 as published;

fn system(bike: &BenchmarkParameters, speed: f64, input: Input) -> LinearSystem {
    let request = SystemRequest {
        states: vec![],
        inputs: vec![input],
        outputs: vec![Output::State(StateVariable::Lean)],
    };
    LinearSystem::new(bike, speed, &request).unwrap()
}

/// σ_min / σ_max of the Kalman matrix of the single input at `speed`.
fn relative_smallest(bike: &BenchmarkParameters, speed: f64, input: Input) -> f64 {
    let c = system(bike, speed, input).controllability(Some(0)).unwrap();
    c.singular_values[3] / c.singular_values[0]
}

/// Steer torque on the benchmark: f = (0, 1), so the lean equation's row must vanish at a common
/// λ. With the benchmark's C₁₁ = K₂₁₁ = 0 that row is M₁₁λ² + gK₀₁₁, so λ = ±μ with
/// μ² = −gK₀₁₁/M₁₁ (the steer-locked bicycle falling over), and v solves the other entry,
/// K₂₁₂ v² ± C₁₁₂ μ v + (M₁₂ μ² + gK₀₁₂) = 0: a closed form from the published §5 matrices.
#[test]
fn steer_torque_loses_the_falling_mode_at_two_speeds_given_in_closed_form() {
    let g = 9.81;
    let (m, c1, k0, k2) = (published::M, published::C1, published::K0, published::K2);
    let mu = (-g * k0[0][0] / m[0][0]).sqrt();
    let mut expected = Vec::new();
    for sign in [1.0, -1.0] {
        let (a, b, c) = (
            k2[0][1],
            sign * c1[0][1] * mu,
            m[0][1] * mu * mu + g * k0[0][1],
        );
        let d = (b * b - 4.0 * a * c).sqrt();
        for v in [(-b + d) / (2.0 * a), (-b - d) / (2.0 * a)] {
            if v > 0.0 {
                expected.push((v, sign * mu));
            }
        }
    }
    expected.sort_by(|x, y| x.0.total_cmp(&y.0));
    assert_eq!(expected.len(), 2);

    let bike = BenchmarkParameters::meijaard2007();
    let lost = uncontrollable_speeds(&bike, &Input::SteerTorque).unwrap();
    assert!(!lost.everywhere);
    assert_eq!(lost.speeds.len(), 2, "{lost:?}");
    for (found, (v, lambda)) in lost.speeds.iter().zip(&expected) {
        let RealRoot::Simple { value, lo, hi } = found.speed else {
            panic!("not resolved: {found:?}");
        };
        // The published matrices carry 14 decimals; ours are computed from Table 1.
        assert!((value - v).abs() < 1e-11 * v, "{value} vs {v}");
        assert!(lo <= value && value <= hi && hi - lo < 1e-11 * v);
        assert!((found.eigenvalue.re - lambda).abs() < 1e-10 * mu);
        assert_eq!(found.eigenvalue.im, 0.0);
    }
    // Schwab & Kooijman 2010 ("Controllability of a bicycle"): the modes steering alone cannot
    // reach are lost either at an extremely low speed or are stable.
    assert!(lost.speeds[0].speed.value() < 0.05 && lost.speeds[0].eigenvalue.re > 0.0);
    assert!(lost.speeds[1].eigenvalue.re < 0.0);
    println!("steer torque loses modes at {expected:?}");
}

/// At every certified speed, for each input, the Kalman matrix loses rank (σ_min/σ_max at
/// round-off) and regains it a little away; the lost mode's modal controllability is zero
/// there and the others' are not.
#[test]
fn the_kalman_matrix_and_the_modes_agree_with_the_certified_speeds() {
    let mut bikes = vec![BenchmarkParameters::meijaard2007()];
    for preset in presets::PRESETS {
        if let Ok(b) = preset.bicycle().benchmark() {
            bikes.push(b);
        }
    }
    let mut checked = 0;
    for bike in &bikes {
        // Two pushes inside the bicycle (the box its side view occupies): high at the back,
        // low at the front.
        let [lo, hi] = side_view(bike, None).extent();
        let at = |s: f64, h: f64| Input::LateralForce {
            x: lo[0] + s * (hi[0] - lo[0]),
            z: -h * hi[1],
        };
        let inputs = [
            Input::SteerTorque,
            Input::LeanTorque,
            at(0.25, 0.8),
            at(0.85, 0.3),
        ];
        for input in inputs {
            let lost = uncontrollable_speeds(bike, &input).unwrap();
            for speed in &lost.speeds {
                let RealRoot::Simple { value: v, .. } = speed.speed else {
                    continue;
                };
                if v > 100.0 {
                    continue;
                }
                let at = relative_smallest(bike, v, input);
                let near = relative_smallest(bike, v * (1.0 + 1e-3), input).min(relative_smallest(
                    bike,
                    v * (1.0 - 1e-3),
                    input,
                ));
                assert!(at < 1e-11, "{input} at {v}: {at:e}");
                assert!(
                    near > 1e3 * at.max(1e-16),
                    "{input} near {v}: {near:e} vs {at:e}"
                );
                let modes = system(bike, v, input).modal_controllability(0).unwrap();
                let (lost_mode, others): (
                    Vec<&whipple::advanced::control::ModalControllability>,
                    Vec<_>,
                ) = modes
                    .iter()
                    .partition(|m| whipple::math::norm(m.eigenvalue - speed.eigenvalue) < 1e-6);
                assert_eq!(lost_mode.len(), 1, "{input} at {v}: {modes:?} vs {speed:?}");
                assert!(lost_mode[0].measure < 1e-12, "{modes:?}");
                assert!(others.iter().all(|m| m.measure > 1e-6), "{modes:?}");
                checked += 1;
            }
        }
    }
    assert!(checked >= 8, "only {checked} speeds checked");
}

/// Nothing is missed: between the certified speeds the resultant keeps its sign, so the Kalman
/// matrix's smallest singular value has no dip to round-off on a fine grid anywhere else.
#[test]
fn no_loss_of_rank_between_the_certified_speeds() {
    let bike = BenchmarkParameters::meijaard2007();
    let input = Input::SteerTorque;
    let lost = uncontrollable_speeds(&bike, &input).unwrap();
    let roots: Vec<f64> = lost.speeds.iter().map(|s| s.speed.value()).collect();
    for k in 1..=2000 {
        let v = k as f64 * 0.005;
        if roots.iter().any(|r| (v - r).abs() < 0.004) {
            continue;
        }
        assert!(relative_smallest(&bike, v, input) > 1e-9, "at {v}");
    }
}

/// The modal measure from the second-order left null vector equals the one from a left
/// eigenvector found independently (the null space of (A − λI)ᵀ by a complex SVD).
#[test]
fn modal_controllability_matches_independent_left_eigenvectors() {
    let bike = BenchmarkParameters::meijaard2007();
    for input in [
        Input::SteerTorque,
        Input::LeanTorque,
        Input::LateralForce { x: 0.5, z: -1.1 },
    ] {
        for v in [0.3, 1.0, 3.0, 5.0, 8.0] {
            let s = system(&bike, v, input);
            let a: DMatrix<Complex<f64>> = s.a().map(|x| Complex::new(x, 0.0));
            let b: Vec<Complex<f64>> = s
                .b()
                .column(0)
                .iter()
                .map(|x| Complex::new(*x, 0.0))
                .collect();
            let b_norm = s.b().column(0).norm();
            for mode in s.modal_controllability(0).unwrap() {
                let shifted = a.transpose() - DMatrix::identity(4, 4) * mode.eigenvalue;
                let svd = shifted.svd(false, true);
                let (k, _) = svd
                    .singular_values
                    .iter()
                    .enumerate()
                    .min_by(|x, y| x.1.total_cmp(y.1))
                    .unwrap();
                let v_t = svd.v_t.unwrap();
                // The right singular vector of the smallest singular value (conjugated row).
                let ell: Vec<Complex<f64>> = v_t.row(k).iter().map(|z| z.conj()).collect();
                let ell_norm = ell.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
                let dot: Complex<f64> = ell.iter().zip(&b).map(|(l, x)| l * x).sum();
                let independent = whipple::math::norm(dot) / (ell_norm * b_norm);
                assert!(
                    (independent - mode.measure).abs() < 1e-9,
                    "{input} at {v}: {} vs {independent}",
                    mode.measure
                );
            }
        }
    }
}

#[test]
fn the_ignorable_coordinates_show_their_own_losses() {
    let bike = BenchmarkParameters::meijaard2007();
    let request = SystemRequest {
        states: vec![
            StateVariable::Yaw,
            StateVariable::RearContactX,
            StateVariable::RearContactY,
            StateVariable::RearWheelAngle,
            StateVariable::FrontWheelAngle,
        ],
        inputs: vec![Input::SteerTorque, Input::LeanTorque],
        outputs: vec![Output::State(StateVariable::Lean)],
    };
    let s = LinearSystem::new(&bike, 5.0, &request).unwrap();
    // x and the wheels' angles are deviations no input changes to first order; ψ and y are
    // steered through δ.
    for input in [Some(0), Some(1), None] {
        let c = s.controllability(input).unwrap();
        assert_eq!((c.rank, c.states), (6, 9), "{input:?}: {c:?}");
        assert!(!c.is_full_rank() && c.condition.is_infinite());
    }
    let lean_steer = system(&bike, 5.0, Input::SteerTorque)
        .controllability(Some(0))
        .unwrap();
    assert!(lean_steer.is_full_rank() && lean_steer.condition.is_finite());
}

#[test]
fn an_input_that_does_no_work_is_lost_everywhere_and_bad_indices_are_named() {
    let bike = BenchmarkParameters::meijaard2007();
    // A push at the rear contact itself does no virtual work on lean or steer.
    let at_contact = Input::LateralForce { x: 0.0, z: 0.0 };
    let lost = uncontrollable_speeds(&bike, &at_contact).unwrap();
    assert!(lost.everywhere && lost.speeds.is_empty());
    let e = uncontrollable_speeds(
        &bike,
        &Input::LateralForce {
            x: f64::NAN,
            z: 0.0,
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("inputs") && e.contains("finite"), "{e}");
    let s = system(&bike, 5.0, Input::SteerTorque);
    for e in [
        s.controllability(Some(1)).unwrap_err().to_string(),
        s.modal_controllability(3).unwrap_err().to_string(),
    ] {
        assert!(e.contains("inputs") && e.contains("does not exist"), "{e}");
    }
    let mut bad = bike;
    bad.m_r = -1.0;
    assert!(uncontrollable_speeds(&bad, &Input::SteerTorque).is_err());
}
