//! Every way a simulation or a numerical method can fail, produced on purpose: each is a typed
//! error or an [`Outcome`] with its time, and a run that fails keeps the samples computed
//! before. (The CLI's messages and exit status, and the web API's kinds, are tested in those
//! crates with the same inputs.)

use std::f64::consts::FRAC_PI_2;

use whipple::advanced::integrate::{Dopri5Settings, Integrator};
use whipple::advanced::nonlinear::{
    Inputs, Outcome, ProjectionMethod, ProjectionSettings, Simulation, State, StateView, TorqueFn,
};
use whipple::{
    BenchmarkParameters, Error, InitialConditions, Model, Result, SimulationSettings, simulate,
};

fn benchmark() -> Result<Model> {
    Model::new(&BenchmarkParameters::meijaard2007())
}

fn upright(model: &Model, speed: f64) -> Result<State<f64>> {
    model.initial_state(&InitialConditions::upright(speed))
}

fn torque(f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Option<TorqueFn> {
    Some(Box::new(move |t: f64, _: &StateView| f(t)))
}

/// What every run that ends early must keep: the samples up to the last good step, in time
/// order, all finite, the last one the final state, one per accepted step.
fn assert_samples_kept(run: &Simulation, last_t: f64) {
    assert_eq!(run.samples.len(), run.steps + 1, "one sample per step");
    let last = run.samples.last().expect("the initial sample at least");
    assert!((last.t - last_t).abs() < 1e-12, "last sample at {}", last.t);
    assert!(
        run.samples
            .windows(2)
            .all(|w| w[1].t > w[0].t && w[1].lean.is_finite() && w[1].rear.normal.is_finite())
    );
    assert_eq!(run.final_state.lean(), last.lean);
}

/// A steer torque of 5000 N m and steps of 50 ms: the first step lands so far off the
/// constraints that Newton's method does not bring it back within its 10 iterations.
#[test]
fn a_diverging_projection_ends_the_run_as_projection_failed() -> Result<()> {
    let model = benchmark()?;
    let settings = SimulationSettings {
        integrator: Integrator::Rk4 { dt: 0.05 },
        duration: 1.0,
        steer_torque: torque(|_| 5000.0),
        ..SimulationSettings::default()
    };
    let run = simulate(&model, upright(&model, 5.0)?, &settings)?;
    match run.outcome {
        Outcome::ProjectionFailed {
            t,
            iterations,
            residual,
        } => {
            assert!((t - 0.05).abs() < 1e-12, "{t}");
            assert_eq!(iterations, ProjectionSettings::default().max_iterations);
            assert!(residual > 1e-3, "{residual}");
        }
        other => panic!("expected a failed projection, got {other:?}"),
    }
    assert_samples_kept(&run, 0.0);
    Ok(())
}

/// A torque that is infinite at t = 0.5 s (`1/(t - 0.5)`, which RK4 evaluates there): the run
/// ends as a non-finite state at that time, keeping the 49 steps before (not as a "singular"
/// system, which it is not).
#[test]
fn an_infinite_torque_ends_the_run_as_a_non_finite_state() -> Result<()> {
    let model = benchmark()?;
    let settings = SimulationSettings {
        integrator: Integrator::Rk4 { dt: 0.01 },
        duration: 1.0,
        steer_torque: torque(|t| 1.0 / (t - 0.5)),
        ..SimulationSettings::default()
    };
    let run = simulate(&model, upright(&model, 5.0)?, &settings)?;
    match run.outcome {
        Outcome::NonFiniteState { t } => assert!((t - 0.5).abs() < 1e-12, "{t}"),
        other => panic!("expected a non-finite state, got {other:?}"),
    }
    assert_eq!(run.steps, 49);
    assert_samples_kept(&run, 0.49);
    // The same torque as a lean torque.
    let settings = SimulationSettings {
        lean_torque: torque(|t| 1.0 / (t - 0.5)),
        steer_torque: None,
        ..settings
    };
    let run = simulate(&model, upright(&model, 5.0)?, &settings)?;
    assert!(
        matches!(run.outcome, Outcome::NonFiniteState { t } if (t - 0.5).abs() < 1e-12),
        "{:?}",
        run.outcome
    );
    Ok(())
}

/// The adaptive integrator meets the same singularity by shrinking its step until it passes
/// its minimum: `StepSizeTooSmall` just before t = 0.5 s, after rejected steps.
#[test]
fn a_singular_torque_makes_the_adaptive_step_too_small() -> Result<()> {
    let model = benchmark()?;
    let settings = SimulationSettings {
        integrator: Integrator::Dopri5(Dopri5Settings::default()),
        duration: 1.0,
        steer_torque: torque(|t| 1.0 / (t - 0.5)),
        stop_on_lift_off: false,
        ..SimulationSettings::default()
    };
    let run = simulate(&model, upright(&model, 5.0)?, &settings)?;
    let Outcome::StepSizeTooSmall { t } = run.outcome else {
        panic!(
            "expected the step size to become too small, got {:?}",
            run.outcome
        );
    };
    assert!(t < 0.5 && t > 0.5 - 1e-6, "{t}");
    assert!(run.rejected_steps > 0);
    assert_samples_kept(&run, t);
    Ok(())
}

/// The adaptive integrator's bound on step attempts ends a run as `StepSizeTooSmall` too,
/// counting rejected attempts.
#[test]
fn the_adaptive_step_limit_ends_the_run() -> Result<()> {
    let model = benchmark()?;
    let settings = SimulationSettings {
        integrator: Integrator::Dopri5(Dopri5Settings {
            rtol: 1e-12,
            atol: 1e-14,
            max_steps: 25,
            ..Dopri5Settings::default()
        }),
        duration: 5.0,
        ..SimulationSettings::default()
    };
    let start = model.initial_state(&InitialConditions {
        lean_rate: 0.5,
        ..InitialConditions::upright(4.6)
    })?;
    let run = simulate(&model, start, &settings)?;
    let Outcome::StepSizeTooSmall { t } = run.outcome else {
        panic!("expected the step limit, got {:?}", run.outcome);
    };
    assert!(t > 0.0 && t < 5.0, "{t}");
    assert_eq!(run.steps + run.rejected_steps, 25);
    assert_samples_kept(&run, t);
    Ok(())
}

/// An initial state that cannot be projected (a lean a hair's breadth from 90°, where the
/// orientation angles are singular) is refused before the run starts: an error, not an
/// outcome.
#[test]
fn an_initial_state_off_the_constraints_is_refused() -> Result<()> {
    let model = benchmark()?;
    let start = model.initial_state(&InitialConditions {
        lean: 89.999999f64.to_radians(),
        ..InitialConditions::upright(5.0)
    })?;
    let settings = SimulationSettings {
        fall_angle: 89.9999999f64.to_radians(),
        ..SimulationSettings::default()
    };
    match simulate(&model, start, &settings) {
        Err(Error::ProjectionDiverged { .. }) => {}
        other => panic!("expected the initial projection to diverge, got {other:?}"),
    }
    // A NaN anywhere in the state is refused at once.
    let mut bad = upright(&model, 5.0)?;
    bad.u[7] = f64::NAN;
    assert_eq!(
        simulate(&model, bad, &SimulationSettings::default()).err(),
        Some(Error::NonFiniteState { t: 0.0 })
    );
    Ok(())
}

/// Newton's method on the positions gives up with `ProjectionDiverged` (iterations and
/// residual reached) when it cannot reach the tolerance within its bound.
#[test]
fn position_projection_reports_divergence() -> Result<()> {
    let model = benchmark()?;
    let mut q = upright(&model, 5.0)?.q;
    for (i, x) in q.iter_mut().enumerate() {
        *x += 0.3 * whipple::math::sin((i as f64) * 0.9);
    }
    for method in [ProjectionMethod::LeastNorm, ProjectionMethod::Coordinates] {
        let params = ProjectionSettings {
            method,
            tolerance: 1e-13,
            min_iterations: 1,
            max_iterations: 1,
        };
        let mut moved = q;
        match model.project_positions(&mut moved, &params) {
            Err(Error::ProjectionDiverged {
                iterations,
                residual,
            }) => {
                assert!(iterations <= 1, "{method:?}: {iterations}");
                assert!(residual > 1e-13, "{method:?}: {residual}");
            }
            other => panic!("{method:?}: expected divergence, got {other:?}"),
        }
        // With its default bound the same start converges.
        let mut moved = q;
        let report = model.project_positions(
            &mut moved,
            &ProjectionSettings {
                method,
                ..ProjectionSettings::default()
            },
        )?;
        assert!(
            report.residual <= 1e-13 && report.iterations >= 2,
            "{report:?}"
        );
    }
    Ok(())
}

/// The projection always makes at least one Newton iteration, even from a state exactly on
/// the constraints (the study found one necessary), and a simulation refuses settings that
/// would skip it.
#[test]
fn the_projection_always_makes_at_least_one_iteration() -> Result<()> {
    let model = benchmark()?;
    let start = model.initial_state(&InitialConditions {
        lean: 0.2,
        steer: -0.1,
        lean_rate: 0.5,
        ..InitialConditions::upright(4.0)
    })?;
    assert!(model.residuals(&start).max_holonomic() < 1e-15);
    assert_eq!(ProjectionSettings::default().min_iterations, 1);
    for method in [ProjectionMethod::LeastNorm, ProjectionMethod::Coordinates] {
        let mut state = start;
        let report = model.project(
            &mut state,
            &ProjectionSettings {
                method,
                ..ProjectionSettings::default()
            },
        )?;
        assert_eq!(report.iterations, 1, "{method:?}");
    }
    let settings = SimulationSettings {
        projection: ProjectionSettings {
            min_iterations: 0,
            ..ProjectionSettings::default()
        },
        ..SimulationSettings::default()
    };
    match simulate(&model, start, &settings) {
        Err(Error::InvalidArgument { what, rule }) => {
            assert_eq!(what, "projection");
            assert!(rule.contains("1 <= min_iterations"), "{rule}");
        }
        other => panic!("expected the settings to be refused, got {other:?}"),
    }
    Ok(())
}

/// Lying on its side (lean exactly 90°, which `initial_state` refuses) the front wheel's
/// height no longer depends on the pitch: Newton's method for the pitch has no slope to follow
/// and says so with `NoConvergence`.
#[test]
fn the_pitch_of_a_bicycle_lying_on_its_side_does_not_converge() -> Result<()> {
    let model = benchmark()?;
    match model.pitch_for(FRAC_PI_2, 0.3, 0.0) {
        Err(Error::NoConvergence { method, .. }) => {
            assert!(method.contains("pitch"), "{method}")
        }
        other => panic!("expected no convergence, got {other:?}"),
    }
    let refused = model.initial_state(&InitialConditions {
        lean: FRAC_PI_2,
        ..InitialConditions::upright(1.0)
    });
    assert!(
        matches!(refused, Err(Error::InvalidArgument { .. })),
        "{refused:?}"
    );
    Ok(())
}

/// Speeds far out of range overflow the accelerations: reported as a non-finite result, not
/// as a singular system (the saddle-point matrix is regular there). No validated bicycle and
/// no state found makes the matrix itself singular (`SingularDynamics`): validation refuses
/// massless assemblies and a mass matrix that is not positive definite, massless wheels are
/// handled by the augmented solve, and the orientation angles are not numerically singular
/// even at a lean of exactly 90°.
#[test]
fn overflowing_accelerations_are_non_finite_not_singular() -> Result<()> {
    let model = benchmark()?;
    let fast = model.initial_state(&InitialConditions {
        lean: 0.1,
        steer: 0.1,
        lean_rate: 0.5,
        ..InitialConditions::upright(1e200)
    })?;
    match model.forward(&fast, &Inputs::default()) {
        Err(Error::NonFinite { context }) => assert!(context.contains("overflow"), "{context}"),
        other => panic!("expected a non-finite result, got {other:?}"),
    }
    assert!(matches!(
        simulate(&model, fast, &SimulationSettings::default()),
        Err(Error::NonFinite { .. })
    ));
    // At a lean of exactly 90 degrees the equations are still solved.
    let mut side = upright(&model, 1.0)?;
    side.q = model.configuration([0.0, FRAC_PI_2, 0.0], 0.0, [0.0, 0.0], [0.0, 0.0]);
    assert!(model.forward(&side, &Inputs::default()).is_ok());
    Ok(())
}
