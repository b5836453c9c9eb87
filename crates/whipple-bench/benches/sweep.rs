//! Eigenvalue sweeps of the linearized model.
//!
//! `cargo bench -p whipple-bench --bench sweep`

use std::hint::black_box;
use std::sync::atomic::AtomicBool;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use whipple::advanced::eigen;
use whipple::advanced::linear::{CharacteristicPolynomial, StateSpace};
use whipple::advanced::sweep::track_modes;
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

    // Tracking alone, over eigenvalues computed beforehand (as Python's `eig` does): one chunk
    // against chunks on rayon's pool joined where they overlap (the same columns).
    let fine = whipple::speed_grid(0.0, 10.0, 1e-4).expect("valid grid");
    let roots: Vec<_> = fine
        .iter()
        .map(|&v| eigen::eigenvalues(&canonical, v).expect("valid speed"))
        .collect();
    let mut columns = vec![[0u8; 4]; fine.len()];
    let stop = AtomicBool::new(false);
    let mut group = c.benchmark_group("tracking");
    group.throughput(Throughput::Elements(fine.len() as u64));
    for (name, parallel) in [("serial", false), ("parallel", true)] {
        group.bench_function(format!("track_modes_100001_speeds_{name}"), |b| {
            b.iter(|| {
                track_modes(
                    &canonical,
                    black_box(&fine),
                    |i| Ok(roots[i]),
                    &mut columns,
                    parallel,
                    &stop,
                )
                .expect("tracks")
            })
        });
    }
    group.finish();

    c.bench_function("critical_speeds_0_to_10", |b| {
        b.iter(|| whipple::critical_speeds(&canonical, 0.0, black_box(10.0)).expect("finds"))
    });
}

criterion_group!(linear, benches);
criterion_main!(linear);
