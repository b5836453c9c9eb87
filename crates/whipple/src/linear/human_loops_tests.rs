use super::*;

/// HumanControl's `gains/BenchmarkSteerGains.txt` at 5 m/s (MIT licence, J. K. Moore).
const GAINS_5: [f64; 5] = [46.5457, -0.0522, 12.6611, 0.1849, 0.0959];

fn ridden(task: Task, gains: [f64; 5], speed: f64) -> HumanLoop {
    let rider = HumanController::new(
        task,
        HumanGains::from_array(gains),
        Neuromuscular::default(),
    )
    .unwrap();
    HumanLoop::new(&BenchmarkParameters::meijaard2007(), speed, &rider, &[]).unwrap()
}

fn c(re: f64, im: f64) -> Complex64 {
    Complex64::new(re, im)
}

/// C (sI − A)⁻¹ B of a state-space system at s.
fn state_space_at(a: &nalgebra::DMatrix<f64>, b: &[f64], row: &[f64], s: Complex64) -> Complex64 {
    let n = a.nrows();
    let m = nalgebra::DMatrix::<Complex64>::from_fn(n, n, |i, j| {
        let d = if i == j { s } else { c(0.0, 0.0) };
        d - c(a[(i, j)], 0.0)
    });
    let rhs = nalgebra::DVector::<Complex64>::from_fn(n, |i, _| c(b[i], 0.0));
    let x = m.lu().solve(&rhs).unwrap();
    (0..n).map(|j| x[j] * row[j]).sum()
}

const POINTS: [(f64, f64); 5] = [
    (0.0, 0.3),
    (0.0, 2.0),
    (0.5, 7.0),
    (-1.0, 15.0),
    (0.0, 60.0),
];

#[test]
fn the_outermost_closed_loop_is_the_ridden_bicycles_transfer_function() {
    // Independent of the polynomial algebra: the closed loop's A and B (HumanLoop, the
    // transcription of system_state_space.m) give y/y_c = C (sI − A)⁻¹ B directly.
    for task in [Task::Heading, Task::Lateral] {
        for v in [3.0, 5.0, 8.0] {
            let ridden = ridden(task, GAINS_5, v);
            let loops = ridden.loops().unwrap();
            let outer = loops.last().unwrap();
            let open = ridden.open_loop();
            let row = open
                .outputs()
                .iter()
                .position(|o| *o == outer.rider_loop.output())
                .unwrap();
            let n = ridden.a().nrows();
            let mut crow = vec![0.0; n];
            for (j, x) in open.c().row(row).iter().enumerate() {
                crow[j] = *x;
            }
            let b: Vec<f64> = ridden.b().column(0).iter().copied().collect();
            for (re, im) in POINTS {
                let s = c(re, im);
                let expected = state_space_at(ridden.a(), &b, &crow, s);
                let got = outer.closed.eval(s);
                assert!(
                    crate::math::norm(got - expected)
                        <= 1e-9 * crate::math::norm(expected).max(1e-12),
                    "{task} {v} m/s at {s}: {got} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn each_closed_loop_is_its_open_loop_closed_and_the_steer_loop_is_the_bicycles() {
    let ridden = ridden(Task::Lateral, GAINS_5, 5.0);
    let loops = ridden.loops().unwrap();
    assert_eq!(
        loops
            .iter()
            .map(|l| l.rider_loop.name())
            .collect::<Vec<_>>(),
        ["delta", "phi_dot", "phi", "psi", "y"]
    );
    for l in &loops {
        for (re, im) in POINTS {
            let s = c(re, im);
            let lo = l.open.eval(s);
            let t = l.closed.eval(s);
            assert!(
                crate::math::norm(t - lo / (lo + 1.0)) <= 1e-10 * crate::math::norm(t).max(1e-12),
                "{}: T = {t}, L/(1+L) = {}",
                l.rider_loop,
                lo / (lo + 1.0)
            );
        }
    }
    // L_δ = k_δ ω²/(s² + 2ζωs + ω²) G_{δ,T_δ}(s), from the bicycle's own transfer function.
    let open = ridden.open_loop();
    let steer = open
        .outputs()
        .iter()
        .position(|o| *o == RiderLoop::Steer.output())
        .unwrap();
    let g = open.transfer_function(steer, 0).unwrap();
    for (re, im) in POINTS {
        let s = c(re, im);
        let q = s * s + s * (2.0 * 0.707 * 30.0) + 900.0;
        let expected = g.eval(s) * 900.0 * GAINS_5[0] / q;
        let got = loops[0].open.eval(s);
        assert!(
            crate::math::norm(got - expected) <= 1e-10 * crate::math::norm(expected),
            "{got} vs {expected}"
        );
    }
    // The heading task's loops are the lateral task's first four.
    let heading = self::ridden(Task::Heading, GAINS_5, 5.0).loops().unwrap();
    assert_eq!(heading.len(), 4);
    for (h, l) in heading.iter().zip(&loops) {
        let s = c(0.0, 1.3);
        assert!(
            crate::math::norm(h.open.eval(s) - l.open.eval(s))
                <= 1e-10 * crate::math::norm(l.open.eval(s))
        );
    }
}

#[test]
fn every_crossover_is_found_and_is_one() {
    for v in [2.5, 5.0, 12.0] {
        let loops = ridden(Task::Lateral, GAINS_5, v).loops().unwrap();
        for l in &loops {
            for x in &l.crossovers {
                let m = l.open.magnitude(&[x.frequency])[0];
                assert!((m - 1.0).abs() < 1e-9, "{} at {v}: |L| = {m}", l.rider_loop);
                assert!(x.certified && x.lo <= x.frequency && x.frequency <= x.hi);
            }
            // No crossing missed: on a dense grid |L| − 1 changes sign only across a crossover.
            let grid: Vec<f64> = (0..4000)
                .map(|k| crate::math::powf(10f64, -2.0 + k as f64 * 1e-3))
                .collect();
            let m = l.open.magnitude(&grid);
            for k in 1..grid.len() {
                if (m[k - 1] - 1.0).signum() != (m[k] - 1.0).signum() {
                    assert!(
                        l.crossovers
                            .iter()
                            .any(|x| x.frequency >= grid[k - 1] && x.frequency <= grid[k]),
                        "{} at {v}: a crossing between {} and {} not reported",
                        l.rider_loop,
                        grid[k - 1],
                        grid[k]
                    );
                }
            }
        }
    }
}

#[test]
fn tabulated_benchmark_gains_at_5_mps_cross_over_near_the_rules_frequencies() {
    // HumanControl tuned φ, ψ, y to 2, 1, 0.5 rad/s on a log grid of 1000 points (interp1):
    // the tabulated gains (four digits) put the crossovers within a few per cent of them.
    let loops = ridden(Task::Lateral, GAINS_5, 5.0).loops().unwrap();
    for (l, w) in loops[2..].iter().zip([2.0, 1.0, 0.5]) {
        let got = l.crossover().unwrap();
        assert!((got - w).abs() < 0.02 * w, "{}: {got}", l.rider_loop);
    }
}

#[test]
fn hess_gains_meet_their_rules_and_match_humancontrols_table_at_5_mps() {
    let bike = BenchmarkParameters::meijaard2007();
    let nm = Neuromuscular::default();
    let rules = CrossoverRules::default();
    let k = hess_gains(&bike, 5.0, &nm, &rules).unwrap();
    // HumanControl's fsolve gave 46.5457 and -0.0522 (four digits) at this speed.
    assert!((k.k_delta - 46.5457).abs() < 0.01, "{}", k.k_delta);
    assert!((k.k_phi_dot + 0.0522).abs() < 1e-4, "{}", k.k_phi_dot);
    for (got, table) in [k.k_phi, k.k_psi, k.k_y]
        .iter()
        .zip([12.6611, 0.1849, 0.0959])
    {
        assert!((got - table).abs() < 0.03 * table, "{got} vs {table}");
    }
    let loops = ridden(Task::Lateral, k.to_array(), 5.0).loops().unwrap();
    // The outer loops cross over exactly at 2, 1, 0.5 rad/s.
    for (l, w) in loops[2..].iter().zip(rules.crossovers) {
        assert!(
            (l.crossover().unwrap() - w).abs() < 1e-9,
            "{}",
            l.rider_loop
        );
    }
    // The steer and roll-rate loops closed have a pair of the rules' damping.
    for (l, zeta) in loops[..2]
        .iter()
        .zip([rules.steer_damping, rules.roll_rate_damping])
    {
        let d = &l.closed.denominator;
        let mut z = vec![Complex64::new(0.0, 0.0); d.len() - 1];
        crate::analysis::roots::approximate(d, &mut z);
        let best = z
            .iter()
            .filter(|r| r.im > 1e-6)
            .map(|r| (-r.re / crate::math::norm(r) - zeta).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(
            best < 1e-9,
            "{}: closest damping off by {best}",
            l.rider_loop
        );
    }
    // And the closed loop is stable.
    let ridden = ridden(Task::Lateral, k.to_array(), 5.0);
    assert!(ridden.eigenvalues().unwrap()[0].re < 0.0);
}

#[test]
fn hess_gains_refuse_rules_that_cannot_hold_naming_them() {
    let bike = BenchmarkParameters::meijaard2007();
    let nm = Neuromuscular::default();
    let bad = CrossoverRules {
        steer_damping: 1.5,
        ..CrossoverRules::default()
    };
    let err = hess_gains(&bike, 5.0, &nm, &bad).unwrap_err().to_string();
    assert!(err.contains("`steer damping` = 1.5"), "{err}");
    let bad = CrossoverRules {
        crossovers: [2.0, -1.0, 0.5],
        ..CrossoverRules::default()
    };
    let err = hess_gains(&bike, 5.0, &nm, &bad).unwrap_err().to_string();
    assert!(err.contains("`psi crossover` = -1"), "{err}");
    // A neuromuscular filter so slow that no steer pair reaches the damping below it.
    let slow = Neuromuscular {
        frequency: 0.5,
        damping: 0.707,
    };
    let err = hess_gains(&bike, 5.0, &slow, &CrossoverRules::default()).unwrap_err();
    assert!(
        matches!(err, Error::GainRuleUnmet { ref gain, .. } if gain == "kDelta"),
        "{err}"
    );
    assert!(
        err.to_string().starts_with("no `kDelta` meets its rule"),
        "{err}"
    );
}

#[test]
fn the_sweep_takes_gains_from_a_table_fixed_or_by_the_rules() {
    let bike = BenchmarkParameters::meijaard2007();
    let nm = Neuromuscular::default();
    let table = GainTable::new(
        vec![4.8, 5.0],
        vec![
            HumanGains::from_array([44.6406, -0.0529, 13.2253, 0.172, 0.1001]),
            HumanGains::from_array(GAINS_5),
        ],
    )
    .unwrap();
    let rows = human_eigen_sweep(
        &bike,
        Task::Lateral,
        &GainSchedule::Table(&table),
        &nm,
        &[4.9, 5.0, 5.5],
    )
    .unwrap();
    assert_eq!(
        rows.iter().map(|r| r.extrapolated).collect::<Vec<_>>(),
        [false, false, true]
    );
    let direct = ridden(Task::Lateral, GAINS_5, 5.0).eigenvalues().unwrap();
    assert_eq!(rows[1].eigenvalues, direct);
    assert_eq!(rows[1].eigenvalues.len(), 8);
    let fixed = human_eigen_sweep(
        &bike,
        Task::Heading,
        &GainSchedule::Fixed(HumanGains::from_array(GAINS_5)),
        &nm,
        &[5.0],
    )
    .unwrap();
    assert_eq!(fixed[0].eigenvalues.len(), 7);
    let ruled = human_eigen_sweep(
        &bike,
        Task::Lateral,
        &GainSchedule::Rules(CrossoverRules::default()),
        &nm,
        &[5.0],
    )
    .unwrap();
    assert!((ruled[0].gains.k_delta - 46.5457).abs() < 0.01);
    let many = vec![5.0; MAX_HUMAN_SWEEP_SPEEDS + 1];
    let err = human_eigen_sweep(
        &bike,
        Task::Heading,
        &GainSchedule::Fixed(HumanGains::from_array(GAINS_5)),
        &nm,
        &many,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("at most 100000 speeds"), "{err}");
}
