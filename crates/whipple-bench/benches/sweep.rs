//! Eigenvalue sweeps of the linearized model.
//!
//! `cargo bench -p whipple-bench --bench sweep`

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use whipple::advanced::eigen;
use whipple::advanced::linear::{CharacteristicPolynomial, StateSpace};
use whipple::{BenchmarkParameters, Canonical};

fn benches(c: &mut Criterion) {
    let canonical =
        Canonical::new(&BenchmarkParameters::meijaard2007()).expect("the benchmark bike is valid");
    let speeds = whipple::speed_grid(0.0, 10.0, 0.001).expect("valid grid");
    let poly = CharacteristicPolynomial::new(&canonical);

    let mut group = c.benchmark_group("linear");
    group.throughput(Throughput::Elements(speeds.len() as u64));
    group.bench_function("eigenvalues_10001_speeds", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for &v in &speeds {
                let roots = eigen::quartic_roots(&poly.at_speed(black_box(v)))
                    .expect("finite coefficients");
                sum += roots[0].re;
            }
            sum
        })
    });
    group.bench_function("state_matrix_and_eigenvalues_10001_speeds", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for &v in &speeds {
                let ss = StateSpace::new(&canonical, black_box(v)).expect("valid speed");
                let roots = eigen::quartic_roots(&poly.at_speed(v)).expect("finite");
                sum += roots[0].re + ss.a[(2, 0)];
            }
            sum
        })
    });
    group.bench_function("eigen_sweep_tracked_10001_speeds", |b| {
        b.iter(|| whipple::eigen_sweep(&canonical, black_box(&speeds)).expect("sweeps"))
    });
    group.finish();

    c.bench_function("critical_speeds_0_to_10", |b| {
        b.iter(|| whipple::critical_speeds(&canonical, 0.0, black_box(10.0)).expect("finds"))
    });
}

criterion_group!(linear, benches);
criterion_main!(linear);
