//! Feedback, LQR and pole placement (issue 29, item 4): closed forms, identities and
//! cross-checks between independent methods (the closed-loop polynomial against the general
//! eigensolver on A − B K; certified critical speeds against a fine sampled sweep).

use nalgebra::DMatrix;
use whipple::advanced::comparison::general_eigenvalues;
use whipple::advanced::control::{ClosedLoop, Gains, care, lqr_schedule};
use whipple::advanced::eigen::Complex64;
use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
use whipple::{BenchmarkParameters, Error};

fn steer_only(states: Vec<StateVariable>) -> SystemRequest {
    SystemRequest {
        states,
        inputs: vec![Input::SteerTorque],
        outputs: vec![Output::State(StateVariable::Lean)],
    }
}

fn both_torques() -> SystemRequest {
    SystemRequest::lean_steer()
}

/// Steer into the fall, against a steer spring: T_δ = 100 φ − 10 δ + 20 φ̇ [N m/rad,
/// N m s/rad], so K = −[100, −10, 20, 0] (found by a coarse scan of such gains for the lowest
/// stabilized speed).
fn steer_into_fall() -> DMatrix<f64> {
    DMatrix::from_row_slice(1, 4, &[-100.0, 10.0, -20.0, 0.0])
}

/// Largest distance between two sets of eigenvalues under the best matching (small sets).
fn set_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut taken = vec![false; b.len()];
    let mut worst = 0.0f64;
    for x in a {
        let (j, d) = b
            .iter()
            .enumerate()
            .filter(|(j, _)| !taken[*j])
            .map(|(j, y)| (j, whipple::math::norm(x - y)))
            .min_by(|p, q| p.1.total_cmp(&q.1))
            .expect("as many as a");
        taken[j] = true;
        worst = worst.max(d);
    }
    worst
}

#[test]
fn double_integrator_lqr_matches_its_closed_form() -> Result<(), Error> {
    // A = [[0, 1], [0, 0]], B = [0; 1], Q = I, R = 1: X = [[√3, 1], [1, √3]], K = [1, √3].
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    let lqr = care(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1))?;
    let s3 = 3f64.sqrt();
    let x = DMatrix::from_row_slice(2, 2, &[s3, 1.0, 1.0, s3]);
    assert!((&lqr.solution - &x).amax() < 1e-13, "{}", lqr.solution);
    assert!((lqr.gains[(0, 0)] - 1.0).abs() < 1e-13);
    assert!((lqr.gains[(0, 1)] - s3).abs() < 1e-13);
    assert!(lqr.residual < 1e-14, "{}", lqr.residual);
    // Closed loop s² + √3 s + 1: λ = (−√3 ± i) / 2.
    let expected = [
        Complex64::new(-s3 / 2.0, 0.5),
        Complex64::new(-s3 / 2.0, -0.5),
    ];
    assert!(set_distance(&lqr.closed_loop_eigenvalues, &expected) < 1e-13);
    Ok(())
}

#[test]
fn scalar_care_matches_its_closed_form() -> Result<(), Error> {
    // 2 a x − x² b² / r + q = 0, stabilizing root x = r (a + √(a² + b² q / r)) / b².
    for (a, b, q, r) in [
        (1.0, 1.0, 1.0, 1.0),
        (-2.0, 0.5, 3.0, 0.25),
        (0.0, 2.0, 0.0, 1.0),
    ] {
        let lqr = care(
            &DMatrix::from_element(1, 1, a),
            &DMatrix::from_element(1, 1, b),
            &DMatrix::from_element(1, 1, q),
            &DMatrix::from_element(1, 1, r),
        );
        if q == 0.0 && a == 0.0 {
            // λ = 0 is not weighted by Q and lies on the imaginary axis: no stabilizing X.
            let Err(Error::InvalidArgument { what, .. }) = lqr else {
                panic!("{lqr:?}")
            };
            assert_eq!(what, "Q");
            continue;
        }
        let lqr = lqr?;
        let x = r * (a + (a * a + b * b * q / r).sqrt()) / (b * b);
        assert!(
            (lqr.solution[(0, 0)] - x).abs() < 1e-14 * x.abs().max(1.0),
            "{a} {b} {q} {r}"
        );
        assert!((lqr.gains[(0, 0)] - b * x / r).abs() < 1e-13 * x.abs().max(1.0));
    }
    Ok(())
}

#[test]
fn benchmark_lqr_residual_is_round_off_and_the_loop_stable_from_1_to_10_m_s() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let mut worst = 0.0f64;
    for k in 1..=10 {
        let v = f64::from(k);
        let system = LinearSystem::new(&bike, v, &steer_only(vec![]))?;
        let lqr = system.lqr(&DMatrix::identity(4, 4), &DMatrix::identity(1, 1))?;
        worst = worst.max(lqr.residual);
        assert!(lqr.residual < 1e-12, "{v} m/s: residual {:e}", lqr.residual);
        // The residual recomputed here from A, B, X: AᵀX + XA − XBBᵀX + I.
        let (a, b, x) = (system.a(), system.b(), &lqr.solution);
        let r = a.transpose() * x + x * a - x * b * b.transpose() * x + DMatrix::identity(4, 4);
        assert!(r.amax() < 1e-10 * x.amax(), "{v} m/s: {}", r.amax());
        assert!((x - x.transpose()).amax() == 0.0);
        // X positive definite (Q = I > 0).
        assert!(nalgebra::SymmetricEigen::new(x.clone()).eigenvalues.min() > 0.0);
        // The closed loop, built by ClosedLoop, is stable.
        let closed = ClosedLoop::new(&bike, &steer_only(vec![]), Gains::Constant(lqr.gains))?;
        assert!(closed.eigenvalues(v)?.iter().all(|l| l.re < 0.0));
    }
    eprintln!("largest relative Riccati residual, 1..10 m/s: {worst:e}");
    Ok(())
}

#[test]
fn benchmark_lqr_gain_at_5_m_s() -> Result<(), Error> {
    let system = LinearSystem::new(
        &BenchmarkParameters::meijaard2007(),
        5.0,
        &steer_only(vec![]),
    )?;
    let lqr = system.lqr(&DMatrix::identity(4, 4), &DMatrix::identity(1, 1))?;
    let k: Vec<String> = lqr.gains.iter().map(|x| format!("{x:.15e}")).collect();
    eprintln!(
        "benchmark, 5 m/s, steer torque, Q = I, R = 1: K = [{}], residual {:e}, {} Newton steps",
        k.join(", "),
        lqr.residual,
        lqr.newton_steps
    );
    // Optimality, independently of how X was found: the cost matrix X is the unique
    // solution of the closed loop's Lyapunov equation A_Kᵀ X + X A_K = −(Q + KᵀK).
    let ak = system.a() - system.b() * &lqr.gains;
    let w = DMatrix::<f64>::identity(4, 4) + lqr.gains.transpose() * &lqr.gains;
    let lyap = ak.transpose() * &lqr.solution + &lqr.solution * &ak + w;
    assert!(lyap.amax() < 1e-10 * lqr.solution.amax(), "{}", lyap.amax());
    Ok(())
}

#[test]
fn lqr_schedule_is_stable_at_every_scheduled_speed_and_certified_between() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let request = steer_only(vec![]);
    let speeds: Vec<f64> = (1..=10).map(f64::from).collect();
    let schedule = lqr_schedule(
        &bike,
        &request,
        &speeds,
        &DMatrix::identity(4, 4),
        &DMatrix::identity(1, 1),
    )?;
    assert_eq!(schedule.solutions.len(), 10);
    let closed = ClosedLoop::new(&bike, &request, schedule.gains.clone())?;
    for (v, lqr) in speeds.iter().zip(&schedule.solutions) {
        assert!(lqr.closed_loop_eigenvalues.iter().all(|l| l.re < 0.0));
        // The schedule at its own speeds is the LQR gain there: the same closed loop.
        let values = closed.eigenvalues(*v)?;
        assert!(set_distance(&values, &lqr.closed_loop_eigenvalues) < 1e-12);
    }
    // Certified on every segment: stable over the whole schedule.
    let critical = closed.critical_speeds(1.0, 10.0)?;
    assert_eq!(critical.stable_speed_ranges, vec![(1.0, 10.0)]);
    assert!(critical.crossings.is_empty() && critical.unresolved.is_empty());
    // Outside the schedule: an error, never an extrapolation.
    for bad in [0.5, 10.5] {
        let Err(Error::InvalidArgument { what, .. }) = closed.system(bad) else {
            panic!("{bad} m/s accepted")
        };
        assert_eq!(what, "speed");
    }
    assert!(closed.critical_speeds(0.0, 10.0).is_err());
    // The tracked sweep over the schedule: certified eigenvalues equal A − BK(v)'s.
    let sweep_speeds: Vec<f64> = (0..=90).map(|k| 1.0 + 0.1 * f64::from(k)).collect();
    let sweep = closed.eigen_sweep(&sweep_speeds)?;
    for (v, row) in sweep.speeds.iter().zip(&sweep.eigenvalues) {
        let general = closed.eigenvalues(*v)?;
        let scale = general.iter().map(whipple::math::norm).fold(1.0, f64::max);
        assert!(set_distance(row, &general) < 1e-12 * scale, "{v} m/s");
    }
    Ok(())
}

#[test]
fn closed_loop_polynomial_eigenvalues_equal_those_of_a_minus_bk() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let k2 = DMatrix::from_row_slice(2, 4, &[3.0, -1.0, 0.5, 0.2, -20.0, 4.0, -5.0, 0.7]);
    let mut worst = 0.0f64;
    for (request, k) in [
        (steer_only(vec![]), steer_into_fall()),
        (both_torques(), k2),
        (
            SystemRequest {
                states: vec![],
                inputs: vec![Input::LateralForce { x: 0.3, z: -0.9 }],
                outputs: vec![Output::State(StateVariable::Lean)],
            },
            DMatrix::from_row_slice(1, 4, &[40.0, -10.0, 6.0, -1.0]),
        ),
        // Yaw and lateral position as states, but no gain on them: still the quartic.
        (
            steer_only(vec![StateVariable::Yaw, StateVariable::RearContactY]),
            DMatrix::from_row_slice(1, 6, &[-100.0, 10.0, -20.0, 0.0, 0.0, 0.0]),
        ),
    ] {
        let closed = ClosedLoop::new(&bike, &request, Gains::Constant(k))?;
        assert!(closed.is_lean_steer());
        let speeds: Vec<f64> = (0..=200).map(|i| -2.0 + 0.07 * f64::from(i)).collect();
        let sweep = closed.eigen_sweep(&speeds)?;
        let poly = closed.characteristic_polynomial()?;
        for (v, row) in speeds.iter().zip(&sweep.eigenvalues) {
            let system = closed.system(*v)?;
            // A − BK is block triangular (the ignorable states feed nothing back here): its
            // eigenvalues are its lean–steer block's and zeros (the ignorable states' Jordan
            // block, which round-off splits by √ε, so they are compared on that block).
            let block: nalgebra::Matrix4<f64> = system.a().fixed_view::<4, 4>(0, 0).into_owned();
            let general = general_eigenvalues(&block)?;
            if system.states().len() > 4 {
                let all = closed.eigenvalues(*v)?;
                assert_eq!(all.len(), system.states().len());
                let zeros = all
                    .iter()
                    .filter(|z| whipple::math::norm(**z) < 1e-5)
                    .count();
                assert_eq!(zeros, system.states().len() - 4, "{all:?}");
            }
            let scale = general.iter().map(whipple::math::norm).fold(1.0, f64::max);
            // Near a double root the eigenvalues themselves are ill-conditioned (they move
            // by ε scale² / gap): the tolerance widens there, and only there.
            let mut gap = f64::INFINITY;
            for i in 0..4 {
                for j in 0..i {
                    gap = gap.min(whipple::math::norm(row[i] - row[j]));
                }
            }
            let conditioning = (scale / gap).max(1.0);
            let d = set_distance(row, &general) / scale;
            worst = worst.max(d / conditioning);
            assert!(d < 1e-12 * conditioning, "{v} m/s: {d:e} (gap {gap:e})");
            // The polynomial's coefficients at v against those of det(λI − (A − BK)).
            let a = poly.at_speed(*v);
            let p: Vec<f64> = a.iter().map(|c| c / a[4]).collect();
            let am = system.a().view((0, 0), (4, 4)).into_owned();
            assert!((p[3] + am.trace()).abs() < 1e-11 * am.amax().max(1.0));
            assert!((p[0] - am.determinant()).abs() < 1e-10 * am.amax().max(1.0).powi(4));
        }
    }
    eprintln!(
        "closed-loop polynomial vs eig(A − BK): largest relative distance (over the \
         conditioning factor) {worst:e}"
    );
    Ok(())
}

/// Cross-checks a closed loop's certified critical speeds on [lo, hi] against a sampled sweep
/// of eig(A − B K(v)) every 1 mm/s: each certified crossing lies between the two grid speeds
/// where the sampled count of unstable eigenvalues changes, with the same counts, nowhere else
/// does it change, and the stable ranges hold exactly the stable samples.
fn cross_check(closed: &ClosedLoop, lo: f64, hi: f64) -> Result<Vec<f64>, Error> {
    let critical = closed.critical_speeds(lo, hi)?;
    assert!(critical.unresolved.is_empty(), "{critical:?}");
    let crossings: Vec<f64> = critical.crossings.iter().map(|c| c.speed).collect();
    let h = 1e-3;
    let unstable = |v: f64| -> Result<usize, Error> {
        Ok(closed.eigenvalues(v)?.iter().filter(|l| l.re > 0.0).count())
    };
    let steps = ((hi - lo) / h).round() as i32;
    let mut changes = Vec::new();
    let mut previous = unstable(lo)?;
    for i in 1..=steps {
        let v = (lo + h * f64::from(i)).min(hi);
        let now = unstable(v)?;
        if now != previous {
            changes.push((v - h, v, previous, now));
        }
        previous = now;
    }
    assert_eq!(
        changes.len(),
        crossings.len(),
        "{changes:?} vs {crossings:?}"
    );
    for ((a, b, before, after), c) in changes.iter().zip(&critical.crossings) {
        assert!(*a <= c.speed && c.speed <= *b, "{c:?} not in [{a}, {b}]");
        assert_eq!(
            (c.unstable_below, c.unstable_above),
            (*before as u8, *after as u8)
        );
    }
    for i in 0..=steps / 10 {
        let v = (lo + 10.0 * h * f64::from(i)).min(hi);
        if crossings.iter().any(|c| (c - v).abs() < 1e-9) {
            continue;
        }
        let inside = critical
            .stable_speed_ranges
            .iter()
            .any(|(a, b)| *a <= v && v <= *b);
        assert_eq!(inside, unstable(v)? == 0, "at {v} m/s: {critical:?}");
    }
    eprintln!(
        "crossings {:?}, stable {:?}",
        crossings, critical.stable_speed_ranges
    );
    Ok(crossings)
}

#[test]
fn steer_into_fall_certified_speeds_agree_with_a_sampled_sweep() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    for gain in [
        steer_into_fall(),
        DMatrix::from_row_slice(1, 4, &[-8.0, 0.0, -1.0, 0.0]),
        DMatrix::from_row_slice(1, 4, &[-60.0, 10.0, -3.0, 0.5]),
    ] {
        let closed = ClosedLoop::new(&bike, &steer_only(vec![]), Gains::Constant(gain))?;
        cross_check(&closed, 0.0, 12.0)?;
    }
    Ok(())
}

/// A schedule fading the controller out (steer into the fall at 0.5 m/s, no gain from 8 m/s):
/// certified segment by segment, it must agree with the sampled sweep of A − B K(v) and find
/// the open loop's capsize speed above the schedule's last point.
#[test]
fn scheduled_certified_speeds_agree_with_a_sampled_sweep() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let closed = ClosedLoop::new(
        &bike,
        &steer_only(vec![]),
        Gains::Scheduled {
            speeds: vec![0.5, 3.0, 8.0, 12.0],
            gains: vec![
                steer_into_fall(),
                DMatrix::from_row_slice(1, 4, &[-8.0, 0.0, -1.0, 0.0]),
                DMatrix::zeros(1, 4),
                DMatrix::zeros(1, 4),
            ],
        },
    )?;
    let crossings = cross_check(&closed, 0.5, 12.0)?;
    assert!(!crossings.is_empty());
    // From 8 m/s the loop is open, and the open loop is unstable beyond v_c = 6.02 m/s.
    let critical = closed.critical_speeds(0.5, 12.0)?;
    assert!(critical.stable_speed_ranges.iter().all(|(_, b)| *b < 8.0));
    assert!(critical.stable_speed_ranges[0].0 < 1.0, "{critical:?}");
    Ok(())
}

#[test]
fn steer_into_fall_stabilizes_the_benchmark_at_low_speed() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let closed = ClosedLoop::new(
        &bike,
        &steer_only(vec![]),
        Gains::Constant(steer_into_fall()),
    )?;
    let open = whipple::critical_speeds(&whipple::Canonical::new(&bike)?, 0.0, 12.0)?;
    let critical = closed.critical_speeds(0.0, 12.0)?;
    let (from, to) = critical.stable_speed_ranges[0];
    // Stable from 0.807 m/s, far below the open loop's weave speed, to past its capsize
    // speed: "this controller stabilizes from 0.81 m/s".
    assert!((from - 0.806_665_615_880).abs() < 1e-9, "{critical:?}");
    assert!(from < open.weave_speed.expect("v_w") - 3.0);
    assert!(open.capsize_speed.expect("v_c") < to);
    assert_eq!(to, 12.0);
    assert!(critical.double_root_unavailable.is_some());
    // The whole line, as the open loop's speeds allow.
    let whole = closed.critical_speeds(f64::NEG_INFINITY, f64::INFINITY)?;
    assert!(
        whole
            .crossings
            .iter()
            .any(|c| (c.speed - from).abs() < 1e-12)
    );
    Ok(())
}

#[test]
fn pole_placement_reproduces_the_poles() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let poles = vec![
        Complex64::new(-2.0, 0.0),
        Complex64::new(-3.5, 0.0),
        Complex64::new(-1.5, 2.0),
        Complex64::new(-1.5, -2.0),
    ];
    let mut worst = 0.0f64;
    for v in [1.0, 2.5, 4.0, 6.0, 8.0] {
        let system = LinearSystem::new(&bike, v, &steer_only(vec![]))?;
        let k = system.place_poles(&poles)?;
        let closed = ClosedLoop::new(&bike, &steer_only(vec![]), Gains::Constant(k))?;
        let placed = closed.eigenvalues(v)?;
        let d = set_distance(&placed, &poles);
        worst = worst.max(d);
        assert!(d < 1e-9, "{v} m/s: {d:e}");
        // And by the certified polynomial too.
        let sweep = closed.eigen_sweep(&[v])?;
        assert!(set_distance(&sweep.eigenvalues[0], &poles) < 1e-9);
    }
    eprintln!("pole placement: largest distance {worst:e}");
    Ok(())
}

/// The field an [`Error::InvalidArgument`] names, and its rule.
fn what<T: std::fmt::Debug>(r: Result<T, Error>) -> (&'static str, String) {
    match r {
        Err(Error::InvalidArgument { what, rule }) => (what, rule),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_gains_q_r_and_poles_are_errors_naming_the_field() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    // Wrong shape: named, with the shape expected and got.
    let (w, rule) = what(ClosedLoop::new(
        &bike,
        &steer_only(vec![]),
        Gains::Constant(DMatrix::zeros(2, 4)),
    ));
    assert_eq!(w, "gains");
    assert!(rule.contains("1 × 4") && rule.contains("2 × 4"), "{rule}");
    let mut k = steer_into_fall();
    k[(0, 2)] = f64::NAN;
    assert_eq!(
        what(ClosedLoop::new(
            &bike,
            &steer_only(vec![]),
            Gains::Constant(k)
        ))
        .0,
        "gains"
    );
    let schedule = Gains::Scheduled {
        speeds: vec![2.0, 1.0],
        gains: vec![steer_into_fall(), steer_into_fall()],
    };
    assert_eq!(
        what(ClosedLoop::new(&bike, &steer_only(vec![]), schedule)).0,
        "speeds"
    );
    // Q not symmetric, not positive semi-definite; R singular.
    let system = LinearSystem::new(&bike, 5.0, &steer_only(vec![]))?;
    let mut q = DMatrix::identity(4, 4);
    q[(0, 1)] = 0.5;
    assert_eq!(what(system.lqr(&q, &DMatrix::identity(1, 1))).0, "Q");
    q[(0, 1)] = 0.0;
    q[(2, 2)] = -1.0;
    assert_eq!(what(system.lqr(&q, &DMatrix::identity(1, 1))).0, "Q");
    assert_eq!(
        what(system.lqr(&DMatrix::identity(4, 4), &DMatrix::zeros(1, 1))).0,
        "R"
    );
    assert_eq!(
        what(system.lqr(&DMatrix::identity(3, 3), &DMatrix::identity(1, 1))).0,
        "Q"
    );
    // Yaw and lateral position unweighted: their λ = 0 is on the imaginary axis.
    let path = LinearSystem::new(
        &bike,
        5.0,
        &steer_only(vec![StateVariable::Yaw, StateVariable::RearContactY]),
    )?;
    let mut q6 = DMatrix::zeros(6, 6);
    q6.view_mut((0, 0), (4, 4)).fill_with_identity();
    let (w, rule) = what(path.lqr(&q6, &DMatrix::identity(1, 1)));
    assert_eq!(w, "Q");
    assert!(rule.contains("no stabilizing solution"), "{rule}");
    // Weighting them makes it solvable (path control): and the loop is then of order 6.
    let lqr = path.lqr(&DMatrix::identity(6, 6), &DMatrix::identity(1, 1))?;
    assert!(lqr.residual < 1e-10, "{}", lqr.residual);
    let closed = ClosedLoop::new(
        &bike,
        &steer_only(vec![StateVariable::Yaw, StateVariable::RearContactY]),
        Gains::Constant(lqr.gains.clone()),
    )?;
    assert!(!closed.is_lean_steer());
    assert!(set_distance(&closed.eigenvalues(5.0)?, &lqr.closed_loop_eigenvalues) < 1e-12);
    assert_eq!(what(closed.critical_speeds(0.0, 10.0)).0, "gains");
    assert_eq!(what(closed.eigen_sweep(&[5.0])).0, "gains");
    // The rear contact's x: no input reaches it, whatever Q.
    let x = LinearSystem::new(&bike, 5.0, &steer_only(vec![StateVariable::RearContactX]))?;
    assert_eq!(
        what(x.lqr(&DMatrix::identity(5, 5), &DMatrix::identity(1, 1))).0,
        "inputs"
    );
    // Poles: not closed under conjugation; wrong count; two inputs; uncontrollable.
    let poles = [
        Complex64::new(-1.0, 1.0),
        Complex64::new(-1.0, 1.0),
        Complex64::new(-2.0, 0.0),
        Complex64::new(-3.0, 0.0),
    ];
    assert_eq!(what(system.place_poles(&poles)).0, "poles");
    assert_eq!(what(system.place_poles(&poles[2..])).0, "poles");
    let two = LinearSystem::new(&bike, 5.0, &both_torques())?;
    let real = [-1.0, -2.0, -3.0, -4.0].map(|x| Complex64::new(x, 0.0));
    assert_eq!(what(two.place_poles(&real)).0, "inputs");
    let five = real
        .iter()
        .copied()
        .chain([Complex64::new(-5.0, 0.0)])
        .collect::<Vec<_>>();
    assert_eq!(what(x.place_poles(&five)).0, "inputs");
    // The closed loop of steer into the fall.
    let closed = ClosedLoop::new(
        &bike,
        &steer_only(vec![]),
        Gains::Constant(steer_into_fall()),
    )?;
    // A closed loop's transfer functions exist for gains on φ, δ, φ̇, δ̇ (checked against the
    // direct solve in linear_system.rs); a gain on yaw is refused naming `gains`.
    assert!(closed.system(5.0)?.transfer_function(0, 0).is_ok());
    let heading = ClosedLoop::new(
        &BenchmarkParameters::meijaard2007(),
        &steer_only(vec![StateVariable::Yaw]),
        Gains::Constant(DMatrix::from_row_slice(
            1,
            5,
            &[-100.0, 10.0, -20.0, 0.0, 5.0],
        )),
    )?;
    assert_eq!(
        what(heading.system(5.0)?.transfer_function(0, 0)).0,
        "gains"
    );
    Ok(())
}

#[test]
fn the_closed_loop_system_is_a_minus_bk_with_reference_inputs() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let request = SystemRequest {
        states: vec![StateVariable::Yaw],
        inputs: vec![Input::SteerTorque],
        outputs: vec![Output::YawRate, Output::State(StateVariable::Lean)],
    };
    let k = DMatrix::from_row_slice(1, 5, &[-20.0, 1.0, -5.0, 0.1, 0.3]);
    let closed = ClosedLoop::new(&bike, &request, Gains::Constant(k.clone()))?;
    let open = LinearSystem::new(&bike, 4.0, &request)?;
    let system = closed.system(4.0)?;
    assert_eq!(system.a(), &(open.a() - open.b() * &k));
    assert_eq!(system.b(), open.b());
    assert_eq!(system.c(), &(open.c() - open.d() * &k));
    assert_eq!(system.gains(), Some(&k));
    assert_eq!(open.gains(), None);
    // A gain on yaw: order 5, eigenvalues by the general solver only.
    assert!(!closed.is_lean_steer());
    assert_eq!(closed.eigenvalues(4.0)?.len(), 5);
    // A schedule interpolates linearly.
    let k1 = DMatrix::from_row_slice(1, 5, &[-10.0, 0.0, -2.0, 0.0, 0.0]);
    let scheduled = ClosedLoop::new(
        &bike,
        &request,
        Gains::Scheduled {
            speeds: vec![2.0, 6.0],
            gains: vec![k1.clone(), k.clone()],
        },
    )?;
    let mid = scheduled.gains().at(3.0)?;
    assert!((mid - (&k1 * 0.75 + &k * 0.25)).amax() < 1e-15);
    Ok(())
}

/// Zero gains: the closed loop is the open loop, so its certified critical speeds, found from
/// the Routh signs of polynomials in v (no parity used), equal those the open loop's even–odd
/// polynomials in v² give, for every preset: two routes to the same certified speeds.
#[test]
fn zero_gains_give_the_open_loop_critical_speeds_for_every_preset() -> Result<(), Error> {
    let mut unresolved = Vec::new();
    for preset in whipple::presets::PRESETS {
        let bike = preset.bicycle().benchmark()?;
        let closed = ClosedLoop::new(
            &bike,
            &both_torques(),
            Gains::Constant(DMatrix::zeros(2, 4)),
        )?;
        let (lo, hi) = (0.0, 20.0);
        let open = whipple::critical_speeds(&whipple::Canonical::new(&bike)?, lo, hi)?;
        let closed = closed.critical_speeds(lo, hi)?;
        let speeds = |c: &whipple::CriticalSpeeds| -> Vec<f64> {
            c.crossings.iter().map(|x| x.speed).collect()
        };
        if !closed.unresolved.is_empty() {
            unresolved.push(preset.name);
            continue;
        }
        let (a, b) = (speeds(&open), speeds(&closed));
        assert_eq!(a.len(), b.len(), "{}: {a:?} vs {b:?}", preset.name);
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(1.0),
                "{}: {x} vs {y}",
                preset.name
            );
        }
        assert_eq!(
            open.stable_speed_ranges.len(),
            closed.stable_speed_ranges.len()
        );
        assert_eq!(open.weave_speed.is_some(), closed.weave_speed.is_some());
        assert_eq!(open.capsize_speed.is_some(), closed.capsize_speed.is_some());
    }
    // The two-mass skate's a₀ has a coefficient of ν² that cancels to exactly zero within
    // its bound (det-like structure of K₀ and K₂): its sign beyond that is lost, and the root
    // finder's horizon for it collapses, so the closed-loop route says "unresolved" (never a
    // wrong speed) where the open loop's polynomials in v² resolve it.
    eprintln!("left unresolved by the closed-loop route: {unresolved:?}");
    assert!(
        unresolved.iter().all(|n| *n == "two-mass-skate"),
        "{unresolved:?}"
    );
    Ok(())
}

/// Path control (gains on yaw and lateral position, from LQR with them weighted): a loop of
/// order 6, swept by the general eigensolver and tracked by nearest assignment; each row is
/// the set of eigenvalues of A − BK at its speed, and the columns move continuously.
#[test]
fn a_path_control_loop_is_swept_by_the_general_solver() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let request = steer_only(vec![StateVariable::Yaw, StateVariable::RearContactY]);
    let lqr = LinearSystem::new(&bike, 5.0, &request)?
        .lqr(&DMatrix::identity(6, 6), &DMatrix::identity(1, 1))?;
    let closed = ClosedLoop::new(&bike, &request, Gains::Constant(lqr.gains))?;
    let speeds: Vec<f64> = (0..=180).map(|i| 1.0 + 0.05 * f64::from(i)).collect();
    let rows = closed.general_sweep(&speeds)?;
    assert_eq!(rows.len(), speeds.len());
    for (v, row) in speeds.iter().zip(&rows) {
        assert_eq!(row.len(), 6);
        assert!(set_distance(row, &closed.eigenvalues(*v)?) == 0.0);
    }
    // Tracking: each row follows the previous one at least as closely as the solver's own
    // order (sorted by real part) and as every transposition of the tracked order.
    for (k, pair) in rows.windows(2).enumerate() {
        let cost = |row: &[Complex64]| -> f64 {
            row.iter()
                .zip(&pair[0])
                .map(|(a, b)| whipple::math::norm(a - b))
                .sum()
        };
        let tracked = cost(&pair[1]);
        assert!(tracked <= cost(&closed.eigenvalues(speeds[k + 1])?) + 1e-12);
        for i in 0..6 {
            for j in 0..i {
                let mut swapped = pair[1].clone();
                swapped.swap(i, j);
                assert!(tracked <= cost(&swapped) + 1e-12);
            }
        }
    }
    // At the design speed the loop is the LQR's: stable.
    let at_design = &rows[80];
    assert!((speeds[80] - 5.0).abs() < 1e-12);
    assert!(at_design.iter().all(|l| l.re < 0.0));
    Ok(())
}

/// The closed loop's eigenvectors satisfy (A − B K) x = λ x: on the lean–steer block for gains
/// on φ, δ, φ̇, δ̇ (the second-order null vector, as the open loop's), on the whole state for
/// gains on yaw (the singular vector); unit length, largest component real.
#[test]
fn closed_loop_eigenvectors_satisfy_the_eigen_equation() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let heading = DMatrix::from_row_slice(1, 5, &[-100.0, 10.0, -20.0, 0.0, 5.0]);
    let mut worst = 0.0f64;
    for (request, k) in [
        (steer_only(vec![]), steer_into_fall()),
        (steer_only(vec![StateVariable::Yaw]), heading),
    ] {
        let closed = ClosedLoop::new(&bike, &request, Gains::Constant(k))?;
        for v in [0.5, 2.0, 5.0, 8.0] {
            let system = closed.system(v)?;
            let a = system.a();
            let n = if closed.is_lean_steer() { 4 } else { a.nrows() };
            let a = a.view((0, 0), (n, n)).map(|x| Complex64::new(x, 0.0));
            let values = if closed.is_lean_steer() {
                closed.eigen_sweep(&[v])?.eigenvalues[0].to_vec()
            } else {
                closed.eigenvalues(v)?
            };
            for value in values {
                let x = closed.eigenvector(v, value)?;
                assert_eq!(x.len(), n);
                assert!((x.norm() - 1.0).abs() < 1e-14);
                let pivot = x
                    .iter()
                    .max_by(|p, q| whipple::math::norm(**p).total_cmp(&whipple::math::norm(**q)))
                    .unwrap();
                assert!(pivot.im.abs() < 1e-15 && pivot.re > 0.0);
                let scale = 1.0 + whipple::math::norm(value) + a.norm();
                worst = worst.max((&a * &x - x.clone() * value).norm() / scale);
            }
        }
    }
    assert!(worst < 1e-13, "largest residual {worst:e}");
    Ok(())
}

/// LQR gains at 0, 1, …, 10 m/s interpolated between: the closed loop is unstable from about
/// 0.0101 to 0.9933 m/s (interpolated gains are not LQR gains), which the certified reading
/// finds; the crossing near 0.0101 m/s is enclosed only to 1.6e-8 of its speed, so it is listed
/// as unresolved with its enclosure instead of failing the whole answer. Checked against the
/// general eigensolver on both sides of each end.
#[test]
fn lqr_schedule_from_rest_is_read_with_its_unresolved_crossing() -> Result<(), Error> {
    let bike = BenchmarkParameters::meijaard2007();
    let request = steer_only(vec![]);
    let speeds: Vec<f64> = (0..=10).map(f64::from).collect();
    let schedule = lqr_schedule(
        &bike,
        &request,
        &speeds,
        &DMatrix::identity(4, 4),
        &DMatrix::identity(1, 1),
    )?;
    let closed = ClosedLoop::new(&bike, &request, schedule.gains)?;
    let critical = closed.critical_speeds(0.0, 10.0)?;
    assert_eq!(critical.unresolved.len(), 1, "{critical:?}");
    let (a, b) = critical.unresolved[0];
    assert!(a > 0.0100 && b < 0.0102 && b - a < 1e-9, "{a} .. {b}");
    let ranges = &critical.stable_speed_ranges;
    assert_eq!(ranges.len(), 2, "{ranges:?}");
    assert!(ranges[0].0 == 0.0 && ranges[0].1 >= a && ranges[0].1 <= b);
    assert_eq!(ranges[1].1, 10.0);
    let start = ranges[1].0;
    assert!((start - 0.9933).abs() < 1e-3, "{start}");
    let largest = |v: f64| -> Result<f64, Error> {
        Ok(closed
            .eigenvalues(v)?
            .iter()
            .map(|z| z.re)
            .fold(f64::NEG_INFINITY, f64::max))
    };
    assert!(largest(a * 0.99)? < 0.0);
    assert!(largest(b * 1.01)? > 0.0);
    assert!(largest(0.5)? > 10.0);
    assert!(largest(start - 1e-6)? > 0.0);
    assert!(largest(start + 1e-6)? < 0.0);
    Ok(())
}
