//! The rider: Hess's gains by the rules, the closed loop's A and B (HumanControl's
//! `system_state_space.m`), the handling quality metric and its certified peak, the double lane
//! change on the linear and the non-linear bicycle, the leaning rider pushed (Browser with
//! Jason), and BMD 2016's optimal-handling search;
//! all for the benchmark bicycle at 5 m/s. HumanControl's README reports, in MATLAB, A, B, C, D
//! in 0.029 s and a lane change simulated in 0.185 s; BMD 2016's CMA-ES search ran on Simulink.
//!
//! `cargo bench -p whipple-bench --bench rider`

use std::hint::black_box;
use std::sync::atomic::AtomicBool;

use criterion::{Criterion, criterion_group, criterion_main};
use whipple::BenchmarkParameters;
use whipple::advanced::control::{
    CrossoverRules, HandlingBound, HandlingQuality, HumanController, HumanGains, HumanLoop,
    LaneChange, LaneKind, Neuromuscular, OptimalHandlingSettings, Task, hess_gains,
    lane_change_linear, lane_change_nonlinear, optimal_handling,
};
use whipple::advanced::design::Parameter;
use whipple::advanced::integrate::Integrator;
use whipple::advanced::nonlinear::{LeanForcing, LeanModel, TorqueFn};
use whipple::advanced::parameters::RiderLeanParameters;
use whipple::{InitialConditions, SimulationSettings};

fn benches(c: &mut Criterion) {
    let bike = BenchmarkParameters::meijaard2007();
    let nm = Neuromuscular::default();
    // HumanControl's BenchmarkSteerGains.txt at 5 m/s.
    let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
    let controller = HumanController::new(Task::Lateral, gains, nm).expect("a controller");
    let lane = LaneChange::humancontrol(LaneKind::Double);

    let mut group = c.benchmark_group("rider");
    group.bench_function("hess_gains_by_the_rules_5ms", |b| {
        b.iter(|| {
            hess_gains(black_box(&bike), 5.0, &nm, &CrossoverRules::default()).expect("gains")
        })
    });
    group.bench_function("closed_loop_a_b_lateral_5ms", |b| {
        b.iter(|| HumanLoop::new(black_box(&bike), 5.0, &controller, &[]).expect("a loop"))
    });
    group.bench_function("hqm_and_certified_peak_5ms", |b| {
        b.iter(|| {
            HandlingQuality::new(black_box(&bike), 5.0, &gains, &nm)
                .expect("HQM")
                .peak()
                .expect("a peak")
        })
    });
    group.sample_size(10);
    group.bench_function("double_lane_change_linear_5ms", |b| {
        b.iter(|| lane_change_linear(black_box(&bike), 5.0, &controller, &lane).expect("a run"))
    });
    group.bench_function("double_lane_change_nonlinear_5ms", |b| {
        b.iter(|| {
            lane_change_nonlinear(black_box(&bike), 5.0, &controller, &lane, 1e-9).expect("a run")
        })
    });
    // The leaning rider (Browser with Jason, a stiff damped hinge): a 20 N m, 0.5 s push of the
    // upper body and 5 s of motion, as `whipple rider --simulate 5` (Dormand–Prince, rtol 1e-9).
    let mut lean = RiderLeanParameters::browser_jason();
    (lean.upper_body.stiffness, lean.upper_body.damping) = (800.0, 50.0);
    let lean = LeanModel::new(&lean).expect("a model");
    let start = lean
        .initial_state(&InitialConditions::upright(5.0), 0.0, 0.0)
        .expect("a state");
    let push: TorqueFn = Box::new(|t, _| if t <= 0.5 { 20.0 } else { 0.0 });
    group.bench_function("leaning_rider_push_5s", |b| {
        b.iter(|| {
            let settings = SimulationSettings {
                integrator: Integrator::adaptive(1e-9),
                duration: 5.0,
                ..SimulationSettings::default()
            };
            let forcing = LeanForcing {
                hinge_torque: Some(&push),
                ..LeanForcing::default()
            };
            lean.simulate(black_box(&start), &settings, &forcing)
                .expect("a run")
        })
    });
    let base = whipple::presets::find("benchmark")
        .expect("the preset")
        .bicycle();
    let bound = |name: &str, low: f64, high: f64| HandlingBound {
        parameter: Parameter::find(name, &base).expect("a parameter"),
        low,
        high,
    };
    // BMD 2016's four parameters (objective.m: c, w, lam, rF) within wide bounds.
    let bounds = [
        bound("trail", -0.5, 0.5),
        bound("head_angle", 30f64.to_radians(), 90f64.to_radians()),
        bound("w", 0.33, 2.0),
        bound("rF", 0.05, 1.0),
    ];
    let settings = OptimalHandlingSettings::at(5.0);
    let stop = AtomicBool::new(false);
    group.bench_function("optimal_handling_4_parameters_6_starts", |b| {
        b.iter(|| optimal_handling(black_box(&base), &bounds, &settings, &stop).expect("a design"))
    });
    group.finish();
}

criterion_group!(rider, benches);
criterion_main!(rider);
