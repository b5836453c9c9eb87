//! Linearization of the non-linear bicycle about upright straight running: one exact reduced
//! A(v) (4 dual-number passes), one exact full-state Jacobian (48 passes), one study-style
//! finite-difference Jacobian (step decimation, projection), at 4.6 m/s.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use whipple::advanced::comparison::{
    ComparisonSettings, full_state_jacobian, full_state_jacobian_fd, lean_steer_matrix,
};
use whipple::{BenchmarkParameters, Model};

fn linearize(c: &mut Criterion) {
    let model =
        Model::new(&BenchmarkParameters::meijaard2007()).expect("benchmark bicycle is valid");
    c.bench_function("exact reduced A(v) (4x4, dual numbers)", |b| {
        b.iter(|| lean_steer_matrix(black_box(&model), black_box(4.6)))
    });
    c.bench_function("exact full-state Jacobian (48x48, dual numbers)", |b| {
        b.iter(|| full_state_jacobian(black_box(&model), black_box(4.6)))
    });
    let study = ComparisonSettings::default();
    c.bench_function("study finite-difference Jacobian (48x48)", |b| {
        b.iter(|| full_state_jacobian_fd(black_box(&model), black_box(4.6), &study))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = linearize
}
criterion_main!(benches);
