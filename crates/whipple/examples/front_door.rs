//! The front door in a dozen lines: the benchmark bicycle's eigenvalues over speed, its
//! critical speeds, and a 5 s simulation of the non-linear bicycle after a lean-rate kick.
//!
//! `cargo run -p whipple --example front_door`

use whipple::speed_grid;
use whipple::{
    BenchmarkParameters, Canonical, InitialConditions, Model, SimulationSettings, critical_speeds,
    eigen_sweep, simulate,
};

fn main() -> whipple::Result<()> {
    let bike = BenchmarkParameters::meijaard2007();
    let linear = Canonical::new(&bike)?;
    let sweep = eigen_sweep(&linear, &speed_grid(0.0, 10.0, 1.0)?)?;
    let critical = critical_speeds(&linear, 0.0, 10.0)?;
    let model = Model::new(&bike)?;
    let kicked = InitialConditions {
        lean_rate: 0.5,
        ..InitialConditions::upright(4.6)
    };
    let settings = SimulationSettings {
        duration: 5.0,
        ..SimulationSettings::default()
    };
    let run = simulate(&model, model.initial_state(&kicked)?, &settings)?;

    for (v, eigenvalues) in sweep.speeds.iter().zip(&sweep.eigenvalues) {
        let shown: Vec<String> = eigenvalues.iter().map(|l| format!("{l:.4}")).collect();
        println!("v = {v:4.1} m/s: {}", shown.join(", "));
    }
    println!("modes: {:?}", sweep.modes.map(|m| m.name()));
    println!(
        "weave speed {:?} m/s, capsize speed {:?} m/s, self-stable {:?}",
        critical.weave_speed, critical.capsize_speed, critical.stable_speed_ranges
    );
    let last = run.samples.last().map_or(0.0, |s| s.lean);
    println!(
        "simulation: {} after {} steps, final lean {last:.2e} rad",
        run.outcome, run.steps
    );
    Ok(())
}
