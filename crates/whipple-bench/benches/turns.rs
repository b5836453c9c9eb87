//! Steady turns of the non-linear bicycle: one held turn (5 m/s, 11.5° of lean, homotopy from
//! straight running and Newton with exact Jacobians), its stability (5 × 5 exact Jacobian and
//! eigenvalues), the branch from straight running, and the traced family that leaves it.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use whipple::advanced::turns::{
    FamilySettings, Held, TurnSettings, branch_family, branch_from_straight, held_turn, stability,
};
use whipple::{BenchmarkParameters, Model};

fn turns(c: &mut Criterion) {
    let model =
        Model::new(&BenchmarkParameters::meijaard2007()).expect("benchmark bicycle is valid");
    let settings = TurnSettings::default();
    let lean = Held::Lean(11.5f64.to_radians());
    c.bench_function("held turn (5 m/s, 11.5 deg)", |b| {
        b.iter(|| held_turn(black_box(&model), black_box(5.0), lean, &settings))
    });
    let turn = held_turn(&model, 5.0, lean, &settings).expect("the turn exists");
    c.bench_function("stability of a turn (5x5 exact Jacobian)", |b| {
        b.iter(|| stability(black_box(&model), black_box(&turn)))
    });
    c.bench_function("branch from straight running", |b| {
        b.iter(|| branch_from_straight(black_box(&model), &settings))
    });
    let family = FamilySettings::default();
    c.bench_function("family from straight running (with stability)", |b| {
        b.iter(|| branch_family(black_box(&model), &family))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = turns
}
criterion_main!(benches);
