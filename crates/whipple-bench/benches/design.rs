//! Design maps: one design's whole analysis (validation, canonical matrices, the certified
//! stability structure on every speed v ≥ 0), against the single-bicycle path a user would
//! otherwise loop over (`Canonical::new` + `whipple::critical_speeds`, as `whipple speeds`
//! runs it). One core; a 64 × 64 map of trail against head angle.
//!
//! `cargo bench -p whipple-bench --bench design`

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use whipple::advanced::design::StudySettings;
use whipple::presets;
use whipple::{Canonical, Study};
use whipple_front::design::AxisSpec;

fn study(preset: &str, x: &str, y: &str) -> Study {
    let bike = presets::find(preset).expect("a preset").bicycle();
    let x = AxisSpec::parse(x, &bike).expect("a valid axis").axis;
    let y = AxisSpec::parse(y, &bike).expect("a valid axis").axis;
    Study::new(bike, x, Some(y), StudySettings::default()).expect("a valid study")
}

fn benches(c: &mut Criterion) {
    let maps = [
        (
            "benchmark",
            study("benchmark", "trail=0:0.2:64", "head_angle_deg=60:80:64"),
        ),
        (
            "schwinn_crown",
            study(
                "schwinn-crown",
                "trail=-0.05:0.25:64",
                "head_angle_deg=60:85:64",
            ),
        ),
    ];
    let mut group = c.benchmark_group("design_map");
    for (name, map) in &maps {
        let n = map.len();
        group.throughput(Throughput::Elements(n));
        group.bench_function(format!("{name}_64x64_study_design"), |b| {
            b.iter(|| {
                let mut stable = 0u64;
                for i in 0..n {
                    stable += u64::from(map.design(black_box(i)).quantities.stable);
                }
                stable
            })
        });
        // The path before design maps: each design as a bicycle, validated and analysed by
        // the single-bicycle critical speeds (which also lists every crossing and enclosure).
        let bikes: Vec<_> = (0..n)
            .map(|i| map.bicycle_at(i).expect("in the study"))
            .collect();
        group.bench_function(format!("{name}_64x64_critical_speeds"), |b| {
            b.iter(|| {
                let mut ranges = 0usize;
                for bike in &bikes {
                    if let Ok(p) = black_box(bike).benchmark() {
                        if let Ok(canonical) = Canonical::new(&p) {
                            if let Ok(s) = whipple::critical_speeds(&canonical, 0.0, f64::INFINITY)
                            {
                                ranges += s.stable_speed_ranges.len();
                            }
                        }
                    }
                }
                ranges
            })
        });
    }
    group.finish();
}

criterion_group!(design, benches);
criterion_main!(design);
