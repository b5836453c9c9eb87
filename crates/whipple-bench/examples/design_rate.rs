//! Designs per second of a 2-D design map (whole-process timing for `farm-bench`).
//!
//! `cargo run --release -p whipple-bench --example design_rate -- BIKE XSPEC YSPEC [THREADS]`

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use whipple::Study;
use whipple::advanced::design::{Shard, StudySettings};
use whipple::presets;
use whipple_front::design::AxisSpec;

fn main() -> Result<(), whipple::Error> {
    let args: Vec<String> = std::env::args().collect();
    let bike = presets::find(args.get(1).map_or("benchmark", |s| s.as_str()))?.bicycle();
    let x = AxisSpec::parse(
        args.get(2).map_or("trail=0:0.2:1000", |s| s.as_str()),
        &bike,
    )?
    .axis;
    let y = AxisSpec::parse(
        args.get(3)
            .map_or("head_angle_deg=60:80:1000", |s| s.as_str()),
        &bike,
    )?
    .axis;
    if let Some(t) = args.get(4).and_then(|t| t.parse::<usize>().ok()) {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build_global()
            .ok();
    }
    let study = Study::new(bike, x, Some(y), StudySettings::default())?;
    let stop = AtomicBool::new(false);
    let start = Instant::now();
    let mut stable = 0u64;
    let mut invalid = 0u64;
    study.run(Shard::WHOLE, &stop, |rows| {
        for r in rows {
            stable += u64::from(r.quantities.stable);
            invalid += u64::from(r.status != whipple::advanced::design::DesignStatus::Ok);
        }
        Ok(())
    })?;
    let t = start.elapsed().as_secs_f64();
    println!(
        "{} designs in {t:.3} s: {:.0} designs/s ({stable} self-stable, {invalid} not computed)",
        study.len(),
        study.len() as f64 / t
    );
    Ok(())
}
