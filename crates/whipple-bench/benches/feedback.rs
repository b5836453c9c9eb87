//! The closed loop's certified, tracked and labelled eigenvalue sweep
//! (`ClosedLoop::eigen_sweep`) over 10⁶ speeds, constant gains.
//!
//! `cargo bench -p whipple-bench --bench feedback`

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::DMatrix;
use whipple::BenchmarkParameters;
use whipple::advanced::control::{ClosedLoop, Gains};
use whipple::advanced::linear::{Input, Output, StateVariable, SystemRequest};

fn benches(c: &mut Criterion) {
    let request = SystemRequest {
        states: vec![],
        inputs: vec![Input::SteerTorque],
        outputs: StateVariable::LEAN_STEER.map(Output::State).to_vec(),
    };
    // Steering into the fall, T_δ = 100 φ − 10 δ + 20 φ̇.
    let k = DMatrix::from_row_slice(1, 4, &[-100.0, 10.0, -20.0, 0.0]);
    let closed = ClosedLoop::new(
        &BenchmarkParameters::meijaard2007(),
        &request,
        Gains::Constant(k),
    )
    .expect("a valid closed loop");
    let speeds = whipple::speed_grid(0.0, 10.0, 1e-5).expect("valid grid");
    assert_eq!(speeds.len(), 1_000_001);

    let mut group = c.benchmark_group("feedback");
    group.sample_size(10);
    group.throughput(Throughput::Elements(speeds.len() as u64));
    group.bench_function("closed_loop_eigen_sweep_1000001_speeds", |b| {
        b.iter(|| closed.eigen_sweep(black_box(&speeds)).expect("sweeps"))
    });
    group.finish();
    let mut group = c.benchmark_group("feedback");
    group.bench_function("closed_loop_critical_speeds_0_10", |b| {
        b.iter(|| {
            closed
                .critical_speeds(black_box(0.0), 10.0)
                .expect("certified")
        })
    });
    group.finish();
}

criterion_group!(feedback, benches);
criterion_main!(feedback);
