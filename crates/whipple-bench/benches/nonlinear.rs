//! The non-linear multibody bicycle: one forward() (right-hand side) and a 10 s RK4 run at
//! dt = 1 ms with projection after every step.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use whipple::BenchmarkParameters;
use whipple::advanced::nonlinear::Inputs;
use whipple::{InitialConditions, Model, SimulationSettings, simulate};

fn forward(c: &mut Criterion) {
    let model =
        Model::new(&BenchmarkParameters::meijaard2007()).expect("benchmark bicycle is valid");
    let state = model
        .initial_state(&InitialConditions {
            lean: 0.1,
            steer: 0.05,
            lean_rate: 0.5,
            steer_rate: -0.2,
            ..InitialConditions::upright(4.6)
        })
        .expect("consistent state");
    let inputs = Inputs::default();
    c.bench_function("nonlinear forward (f64)", |b| {
        b.iter(|| model.forward(black_box(&state), black_box(&inputs)))
    });
    let mut projected = state;
    c.bench_function("nonlinear project", |b| {
        b.iter(|| {
            projected.q[0] += 1e-12;
            model.project(black_box(&mut projected), &Default::default())
        })
    });
}

fn rk4_run(c: &mut Criterion) {
    let model =
        Model::new(&BenchmarkParameters::meijaard2007()).expect("benchmark bicycle is valid");
    let start = model
        .initial_state(&InitialConditions {
            lean_rate: 0.5,
            ..InitialConditions::upright(4.6)
        })
        .expect("consistent state");
    let settings = SimulationSettings::default();
    let mut group = c.benchmark_group("nonlinear simulate");
    group.sample_size(10);
    group.bench_function("10 s RK4 dt = 1 ms with projection", |b| {
        b.iter(|| simulate(&model, black_box(start), &settings))
    });
    group.finish();
}

criterion_group!(benches, forward, rk4_run);
criterion_main!(benches);
