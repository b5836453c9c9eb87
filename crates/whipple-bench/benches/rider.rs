//! The rider: Hess's gains by the rules, the closed loop's A and B (HumanControl's
//! `system_state_space.m`), the handling quality metric and its certified peak, the double lane
//! change on the linear and the non-linear bicycle, and BMD 2016's optimal-handling search;
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
