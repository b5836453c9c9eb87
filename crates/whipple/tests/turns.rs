//! Steady turns of the non-linear bicycle: residuals, the forward-speed equation,
//! symmetry, contact-force balance, the small-lean limit against the linear model, the branch
//! of hands-free turns from straight running, stability, continuation, and simulations started
//! on a turn.

use nalgebra::{SVector, Vector3};
use whipple::Canonical;
use whipple::advanced::eigen;
use whipple::advanced::integrate::{Dopri5Settings, Integrator};
use whipple::advanced::nonlinear::{FRONT_WHEEL, Simulation};
use whipple::advanced::turns::{
    FamilyEnd, FamilySettings, Held, SteadyTurn, TurnSettings, branch_family, branch_from_straight,
    hands_free_turn_near, held_turn, stability, turn_jacobian,
};
use whipple::{
    BenchmarkParameters, Error, InitialConditions, Model, Result, SimulationSettings, simulate,
};

fn benchmark() -> Model {
    Model::new(&BenchmarkParameters::meijaard2007()).expect("the benchmark bicycle")
}

fn held(model: &Model, speed: f64, lean_deg: f64) -> Result<SteadyTurn> {
    held_turn(
        model,
        speed,
        Held::Lean(lean_deg.to_radians()),
        &TurnSettings::default(),
    )
}

/// The example: 5 m/s, 11.5° of lean. Both solved equations and the forward-speed rate
/// (never solved for) at round-off.
#[test]
fn held_turn_residuals_at_round_off() -> Result<()> {
    let model = benchmark();
    let turn = held(&model, 5.0, 11.5)?;
    println!("{turn:#?}");
    assert!(turn.residuals.lean_acceleration.abs() < 1e-12);
    assert!(turn.residuals.steer_acceleration.abs() < 1e-12);
    // The forward-speed equation holds by itself once lean and steer hold.
    assert!(
        turn.residuals.speed_rate.abs() < 1e-12,
        "{:e}",
        turn.residuals.speed_rate
    );
    assert!(
        turn.steer > 0.0 && turn.yaw_rate > 0.0,
        "a right lean turns right"
    );
    let r = turn.rear_radius.expect("a turn");
    assert!((r * turn.yaw_rate - turn.speed).abs() < 1e-12 * turn.speed);
    // Roughly the point-mass balance tan φ ≈ v²/(gR) (the bicycle is not a point mass, so loose).
    let tan = whipple::math::tan(11.5f64.to_radians());
    let balance = turn.speed * turn.speed / (9.81 * turn.mass_centre_radius.expect("turn"));
    assert!((balance / tan - 1.0).abs() < 0.1, "{balance} vs {tan}");
    Ok(())
}

/// Away from a turn the forward speed does change: the identity above is not trivial.
#[test]
fn speed_rate_is_not_identically_zero_off_a_turn() -> Result<()> {
    let model = benchmark();
    let turn = held(&model, 5.0, 11.5)?;
    let a = turn_jacobian(&model, &turn)?;
    // ∂v̇/∂φ̇ (rates couple into the speed) is not zero in a turn.
    assert!(a[(4, 2)].abs() + a[(4, 3)].abs() > 1e-6, "{a}");
    Ok(())
}

/// (φ, δ) → (−φ, −δ): steer, torque and yaw rate change sign, everything else stays.
#[test]
fn mirror_symmetry() -> Result<()> {
    let model = benchmark();
    let right = held(&model, 6.0, 25.0)?;
    let left = held(&model, 6.0, -25.0)?;
    assert!((right.steer + left.steer).abs() < 1e-13);
    assert!((right.steer_torque + left.steer_torque).abs() < 1e-12);
    assert!((right.yaw_rate + left.yaw_rate).abs() < 1e-13);
    assert!((right.pitch - left.pitch).abs() < 1e-13);
    for k in 0..2 {
        assert!((right.contact[k].normal - left.contact[k].normal).abs() < 1e-9);
        assert!((right.contact[k].lateral + left.contact[k].lateral).abs() < 1e-9);
    }
    Ok(())
}

/// The ground's forces carry the weight and give the mass centre its centripetal acceleration.
#[test]
fn contact_forces_balance_gravity_and_centripetal_force() -> Result<()> {
    let model = benchmark();
    for (speed, lean) in [(5.0, 11.5), (3.0, 20.0), (8.0, 40.0), (5.0, -20.0)] {
        let turn = held(&model, speed, lean)?;
        let state = model.initial_state(&turn.initial_conditions())?;
        let poses = model.body_poses(&state);
        let mass: f64 = model.bodies().body.iter().map(|b| b.mass).sum();
        let centre_of_mass = poses
            .iter()
            .zip(&model.bodies().body)
            .map(|(p, b)| p.position * b.mass)
            .sum::<Vector3<f64>>()
            / mass;
        // Rolling directions f = a × e_z / |a × e_z|, n = e_z × f (a: the wheel's axle).
        let direction = |axle: Vector3<f64>| {
            let f = axle.cross(&Vector3::z()).normalize();
            (f, Vector3::z().cross(&f))
        };
        let mut force = Vector3::zeros();
        for (k, body) in [(0, 0), (1, FRONT_WHEEL)] {
            let (f, n) = direction(poses[body].rotation.column(1).into_owned());
            let c = turn.contact[k];
            force += f * c.longitudinal + n * c.lateral - Vector3::z() * c.normal;
        }
        let g = model.parameters().g;
        assert!(
            (force.z + mass * g).abs() < 1e-9,
            "vertical: {}",
            force.z + mass * g
        );
        let [cx, cy] = turn.centre.expect("a turn");
        let to_centre = Vector3::new(cx - centre_of_mass.x, cy - centre_of_mass.y, 0.0);
        let centripetal = to_centre * (turn.yaw_rate * turn.yaw_rate * mass);
        assert!(
            (force.xy() - centripetal.xy()).amax() < 1e-9,
            "{speed} m/s, {lean}°: {force} vs {centripetal}"
        );
        assert!((to_centre.norm() - turn.mass_centre_radius.expect("turn").abs()).abs() < 1e-12);
    }
    Ok(())
}

/// Held by steer and by radius land where they were asked to, and agree with held by lean.
#[test]
fn held_by_steer_and_by_radius() -> Result<()> {
    let model = benchmark();
    let settings = TurnSettings::default();
    let by_lean = held(&model, 5.0, 20.0)?;
    let by_steer = held_turn(&model, 5.0, Held::Steer(by_lean.steer), &settings)?;
    assert!((by_steer.lean - by_lean.lean).abs() < 1e-11);
    assert!((by_steer.steer_torque - by_lean.steer_torque).abs() < 1e-10);
    let radius = by_lean.rear_radius.expect("turn");
    let by_radius = held_turn(&model, 5.0, Held::Radius(radius), &settings)?;
    assert!((by_radius.lean - by_lean.lean).abs() < 1e-11);
    assert!((by_radius.rear_radius.expect("turn") - radius).abs() < 1e-10);
    let left = held_turn(&model, 5.0, Held::Radius(-radius), &settings)?;
    assert!((left.lean + by_lean.lean).abs() < 1e-11);
    Ok(())
}

/// A turn that does not exist is said not to exist: a circle smaller than the wheelbase allows
/// at speed, and nonsense input.
#[test]
fn impossible_turns_are_errors() {
    let model = benchmark();
    let settings = TurnSettings::default();
    let tight = held_turn(&model, 8.0, Held::Radius(0.05), &settings);
    assert!(
        matches!(tight, Err(Error::NoSteadyTurn { .. })),
        "{tight:?}"
    );
    for bad in [
        held_turn(&model, f64::NAN, Held::Lean(0.1), &settings),
        held_turn(&model, -1.0, Held::Lean(0.1), &settings),
        held_turn(&model, 5.0, Held::Lean(1.6), &settings),
        held_turn(&model, 5.0, Held::Radius(0.0), &settings),
        held_turn(&model, 5.0, Held::Steer(4.0), &settings),
    ] {
        assert!(matches!(bad, Err(Error::InvalidArgument { .. })), "{bad:?}");
    }
}

/// Small leans: the steer and torque per lean approach the linear model's static solution, and
/// the four stability eigenvalues approach the linear model's.
#[test]
fn small_lean_limit_is_the_linear_model() -> Result<()> {
    let model = benchmark();
    let canonical = Canonical::new(model.parameters())?;
    for speed in [2.0, 5.0, 7.0] {
        let lean = 1e-5;
        let turn = held_turn(&model, speed, Held::Lean(lean), &TurnSettings::default())?;
        let k = canonical.k0 * canonical.g + canonical.k2 * (speed * speed);
        let steer = -k[(0, 0)] / k[(0, 1)] * lean;
        let torque = k[(1, 0)] * lean + k[(1, 1)] * steer;
        assert!(
            (turn.steer / steer - 1.0).abs() < 1e-7,
            "{} vs {steer}",
            turn.steer
        );
        assert!((turn.steer_torque / torque - 1.0).abs() < 1e-7);
        let linear = eigen::eigenvalues(&canonical, speed)?;
        let ours = stability(&model, &turn)?;
        let mut lin: Vec<_> = linear.to_vec();
        lin.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        for (a, b) in ours.eigenvalues.iter().zip(&lin) {
            assert!(
                (a.re - b.re).abs() + (a.im - b.im).abs() < 1e-6,
                "{speed} m/s: {a:?} vs {b}"
            );
        }
        assert!(ours.family_eigenvalue.abs() < 1e-9);
    }
    Ok(())
}

/// The 5 × 5 Jacobian's zero eigenvalue is the family: the tangent of the curve of turns at the
/// same torque, (dφ, dδ, 0, 0, dv_hub), is its null vector, the speed row included (the
/// forward-speed equation holds along the whole curve).
#[test]
fn zero_eigenvalue_is_the_family_tangent() -> Result<()> {
    let model = benchmark();
    let turn = held(&model, 5.0, 11.5)?;
    let a = turn_jacobian(&model, &turn)?;
    // The tangent from the equilibrium rows (2, 3) in the columns (φ, δ, v_hub).
    let r0 = Vector3::new(a[(2, 0)], a[(2, 1)], a[(2, 4)]);
    let r1 = Vector3::new(a[(3, 0)], a[(3, 1)], a[(3, 4)]);
    let t = r0.cross(&r1).normalize();
    let x = SVector::<f64, 5>::from([t.x, t.y, 0.0, 0.0, t.z]);
    let image = a * x;
    assert!(image.amax() < 1e-9 * a.amax(), "{image}");
    assert!(image[4].abs() < 1e-10, "speed row {:e}", image[4]);
    Ok(())
}

/// The branch from straight running: the non-linear small-lean limit is exactly where
/// det(g K₀ + v² K₂) = 0, with δ/φ the null vector's ratio.
#[test]
fn branch_from_straight_running_is_the_linear_prediction() -> Result<()> {
    let model = benchmark();
    let branch = branch_from_straight(&model, &TurnSettings::default())?.expect("a branch");
    let canonical = Canonical::new(model.parameters())?;
    let k = canonical.k0 * canonical.g + canonical.k2 * (branch.speed * branch.speed);
    let scale = (canonical.k0 * canonical.g).amax();
    println!(
        "branch {branch:?}, det {:e}",
        k.determinant() / (scale * scale)
    );
    assert!(k.determinant().abs() < 1e-10 * scale * scale);
    // The null vector [1, s]: both rows vanish.
    let s = branch.steer_per_lean;
    assert!((k[(0, 0)] + k[(0, 1)] * s).abs() < 1e-10 * scale);
    assert!((k[(1, 0)] + k[(1, 1)] * s).abs() < 1e-10 * scale);
    // The hands-free turn at a small lean is near v_b; Richardson on φ² removes the leading term.
    let settings = TurnSettings::default();
    let at = |lean: f64| hands_free_turn_near(&model, [lean, s * lean, branch.speed], 0, &settings);
    let (a, b) = (at(1e-3)?, at(2e-3)?);
    let extrapolated = (4.0 * a.speed - b.speed) / 3.0;
    println!(
        "v(1e-3) {} v(2e-3) {} extrapolated {extrapolated}",
        a.speed, b.speed
    );
    assert!(
        (extrapolated - branch.speed).abs() < 1e-9,
        "{extrapolated} vs {}",
        branch.speed
    );
    assert!((a.steer / a.lean - s).abs() < 1e-5);
    Ok(())
}

/// The family from straight running, traced by pseudo-arclength continuation: every point a turn
/// at round-off, bounded, ending for a stated reason.
#[test]
fn branch_family_is_traced() -> Result<()> {
    let model = benchmark();
    let settings = FamilySettings::default();
    let family = branch_family(&model, &settings)?.expect("a family");
    let first = &family.points[0].turn;
    let last = &family.points.last().expect("points").turn;
    println!(
        "{} points, end {:?}; first {:.4} m/s lean {:.3}°, last {:.4} m/s lean {:.3}° steer {:.3}°",
        family.points.len(),
        family.end,
        first.speed,
        first.lean.to_degrees(),
        last.speed,
        last.lean.to_degrees(),
        last.steer.to_degrees()
    );
    assert!(family.points.len() > 10);
    assert!(family.end != FamilyEnd::StepTooSmall);
    for p in &family.points {
        assert!(p.turn.residuals.max() < 1e-10, "{:?}", p.turn.residuals);
        assert!(p.turn.steer_torque == 0.0);
    }
    let stable = family
        .points
        .iter()
        .filter(|p| p.stability.as_ref().is_some_and(|s| s.stable))
        .count();
    println!("{stable} stable points");
    Ok(())
}

/// The families found by the grid scan besides the branch from straight running.
#[test]
fn hands_free_families_are_found() -> Result<()> {
    let model = benchmark();
    let start = std::time::Instant::now();
    let families =
        whipple::advanced::turns::hands_free_families(&model, &FamilySettings::default())?;
    println!("{} families in {:?}", families.len(), start.elapsed());
    for f in &families {
        let p = &f.points;
        let (lo, hi) = p.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), q| {
            (lo.min(q.turn.speed), hi.max(q.turn.speed))
        });
        println!(
            "  {} points, end {:?}, speeds {lo:.3}..{hi:.3}, lean {:.2}°..{:.2}°, steer {:.2}°..{:.2}°, stable points {}",
            p.len(),
            f.end,
            p[0].turn.lean.to_degrees(),
            p[p.len() - 1].turn.lean.to_degrees(),
            p[0].turn.steer.to_degrees(),
            p[p.len() - 1].turn.steer.to_degrees(),
            p.iter()
                .filter(|q| q.stability.as_ref().is_some_and(|s| s.stable))
                .count()
        );
        for q in p {
            let r = q.turn.residuals;
            let scale = 1.0 + q.turn.speed * q.turn.speed;
            assert!(
                r.lean_acceleration.abs().max(r.steer_acceleration.abs()) < 1e-10 * scale,
                "{q:?}"
            );
            assert!(r.speed_rate.abs() < 1e-10 * scale, "{q:?}");
            assert!(q.turn.steer.abs() <= std::f64::consts::PI);
        }
    }
    assert!(!families.is_empty());
    Ok(())
}

/// A run from `initial` with the turn's steer torque held, adaptive (atol = rtol / 100).
fn run_holding(
    model: &Model,
    turn: &SteadyTurn,
    initial: &InitialConditions,
    duration: f64,
    rtol: f64,
) -> Result<Simulation> {
    let torque = turn.steer_torque;
    simulate(
        model,
        model.initial_state(initial)?,
        &SimulationSettings {
            duration,
            integrator: Integrator::Dopri5(Dopri5Settings {
                rtol,
                atol: rtol / 100.0,
                ..Dopri5Settings::default()
            }),
            steer_torque: Some(Box::new(move |_, _| torque)),
            ..SimulationSettings::default()
        },
    )
}

/// A simulation started exactly on a held turn stays on it, and its rear contact runs round the
/// turn's circle at the turn's speed (an independent check of the speed and radius).
#[test]
fn simulation_started_on_a_held_turn_stays_on_it() -> Result<()> {
    let model = benchmark();
    let turn = held(&model, 5.0, 11.5)?;
    println!("{:?}", stability(&model, &turn)?);
    let run = run_holding(&model, &turn, &turn.initial_conditions(), 3.0, 1e-11)?;
    let [cx, cy] = turn.centre.expect("turn");
    let radius = turn.rear_radius.expect("turn").abs();
    let mut worst = 0.0f64;
    for s in &run.samples {
        worst = worst
            .max((s.lean - turn.lean).abs())
            .max((s.steer - turn.steer).abs())
            .max((whipple::math::hypot(s.x - cx, s.y - cy) - radius).abs() / radius);
    }
    let last = run.samples.last().expect("samples");
    let angle =
        whipple::math::atan2(last.y - cy, last.x - cx) - whipple::math::atan2(0.0 - cy, 0.0 - cx);
    let travelled = angle.rem_euclid(std::f64::consts::TAU) * radius;
    println!("deviation {worst:e}, travelled {travelled} in {} s", last.t);
    assert!(worst < 1e-7, "{worst:e}");
    assert!((travelled / last.t - turn.speed).abs() < 1e-6 * turn.speed);
    Ok(())
}

/// A turn perturbed along one real eigenvector of its exact Jacobian leaves or returns to it at
/// exactly that eigenvalue's rate: the non-linear simulation's lean deviation at time t is the
/// initial one times e^{λt}. Checked on a stable turn (5 m/s, 11.5°: the slowest mode decays)
/// and on an unstable one (7 m/s, 5°: above the capsize speed, a real eigenvalue grows).
#[test]
fn perturbations_grow_or_decay_at_the_eigenvalue_rate() -> Result<()> {
    let model = benchmark();
    for (speed, lean_deg, grows) in [(5.0, 11.5, false), (7.0, 5.0, true)] {
        let turn = held(&model, speed, lean_deg)?;
        let s = stability(&model, &turn)?;
        let lambda = s.eigenvalues[0];
        assert!(
            lambda.im.abs() < 1e-9,
            "the slowest mode should be real: {lambda:?}"
        );
        assert_eq!(
            lambda.re > 0.0,
            grows,
            "{speed} m/s, {lean_deg} deg: {lambda:?}"
        );
        // The eigenvector: the right singular vector of J − λI for its smallest singular value.
        let a = turn_jacobian(&model, &turn)?;
        let shifted = a - nalgebra::SMatrix::<f64, 5, 5>::identity() * lambda.re;
        let svd = shifted.svd(false, true);
        let v_t = svd.v_t.expect("asked for V^T");
        let k = svd.singular_values.imin();
        let e: SVector<f64, 5> = v_t.row(k).transpose();
        assert!((a * e - e * lambda.re).amax() < 1e-9 * a.amax());
        let eps = 1e-5 / e[0].abs().max(1e-3);
        let mut initial = turn.initial_conditions();
        initial.lean += eps * e[0];
        initial.steer += eps * e[1];
        initial.lean_rate = eps * e[2];
        initial.steer_rate = eps * e[3];
        initial.speed += eps * e[4];
        let run = run_holding(&model, &turn, &initial, 4.0, 1e-12)?;
        let d0 = eps * e[0];
        let mut checked = 0;
        let mut worst = 0.0f64;
        for sample in run.samples.iter().filter(|x| x.t >= 1.0) {
            let predicted = d0 * whipple::math::exp(lambda.re * sample.t);
            let measured = sample.lean - turn.lean;
            worst = worst.max((measured / predicted - 1.0).abs());
            checked += 1;
        }
        println!(
            "{speed} m/s, {lean_deg} deg: lambda = {:.6} 1/s, {checked} samples from 1 s to {} s, \
             largest relative difference from e^(lambda t) {worst:.2e}",
            lambda.re,
            run.samples.last().map_or(0.0, |x| x.t)
        );
        assert!(checked > 10);
        assert!(worst < 2e-4, "{worst:e}");
    }
    Ok(())
}

/// A 0.5 m circle at 5 m/s solved with the rear normal force at −1448 N and was
/// returned as a turn; the ground would have to pull the wheel down. Refused, naming the wheel
/// and the force.
#[test]
fn a_turn_that_pulls_a_wheel_down_is_refused() {
    let model = benchmark();
    let result = held_turn(&model, 5.0, Held::Radius(0.5), &TurnSettings::default());
    let Err(Error::NoSteadyTurn { given, reason }) = result else {
        panic!("a turn with a negative normal force: {result:?}")
    };
    assert!(given.contains("radius 0.5 m"), "{given}");
    assert!(
        reason.contains("the rear wheel's normal force would be -1448."),
        "{reason}"
    );
    // A turn with both wheels pressed onto the ground is still one.
    let turn = held_turn(&model, 5.0, Held::Radius(12.0), &TurnSettings::default())
        .expect("a 12 m circle at 5 m/s");
    assert!(turn.contact.iter().all(|c| c.normal > 0.0));
}

/// `--radius 1e200` gave "a computed result is not a finite number". Past
/// `MAX_RADIUS` the radius is refused, naming it and the bound; at the bound the turn is
/// computed, finite, and is straight running to round-off.
#[test]
fn a_radius_beyond_the_bound_is_refused_and_the_bound_is_computed() -> Result<()> {
    use whipple::advanced::turns::MAX_RADIUS;
    let model = benchmark();
    for r in [1e200, -1e200, 2.0 * MAX_RADIUS] {
        let result = held_turn(&model, 5.0, Held::Radius(r), &TurnSettings::default());
        let Err(Error::InvalidArgument { what, rule }) = result else {
            panic!("radius {r}: {result:?}")
        };
        assert_eq!(what, "radius");
        assert!(rule.contains("1e9 m"), "{rule}");
    }
    // Lean, steer and torque are proportional to the curvature in the large-radius limit: the
    // turn at the bound is the one at 10 km scaled, to the accuracy of that limit.
    let near = held_turn(&model, 5.0, Held::Radius(1e4), &TurnSettings::default())?;
    for r in [MAX_RADIUS, -MAX_RADIUS] {
        let turn = held_turn(&model, 5.0, Held::Radius(r), &TurnSettings::default())?;
        let radius = turn.rear_radius.expect("a turning bicycle");
        assert!((radius / r - 1.0).abs() < 1e-9, "{radius}");
        assert!(turn.lateral_acceleration.is_finite() && turn.centre.is_some());
        for (far, near) in [
            (turn.lean, near.lean),
            (turn.steer, near.steer),
            (turn.steer_torque, near.steer_torque),
        ] {
            assert!(
                (far * r / (near * 1e4) - 1.0).abs() < 1e-6,
                "{far} at {r} m, {near} at 10 km"
            );
        }
    }
    Ok(())
}
