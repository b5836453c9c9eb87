//! A fixed workload for instruction-count profiling (`valgrind --tool=callgrind`), repeatable
//! even on a loaded machine where wall time is not:
//!
//! ```text
//! cargo build --release -p whipple-bench --example profile_nonlinear
//! valgrind --tool=callgrind target/release/examples/profile_nonlinear forward   # 10 000 forward()
//! valgrind --tool=callgrind target/release/examples/profile_nonlinear project   # 10 000 project()
//! valgrind --tool=callgrind target/release/examples/profile_nonlinear simulate  # 1 s RK4, 1 ms
//! target/release/examples/profile_nonlinear simulate 10                         # 10 s, for timing
//! perf record target/release/examples/profile_nonlinear forward 2000000         # for sampling
//! ```
//!
//! The states are those of the criterion bench `nonlinear`.

use std::hint::black_box;

use whipple::BenchmarkParameters;
use whipple::advanced::nonlinear::Inputs;
use whipple::{InitialConditions, Model, SimulationSettings, simulate};

fn main() -> Result<(), whipple::Error> {
    let what = std::env::args().nth(1).unwrap_or_else(|| "simulate".into());
    let model = Model::new(&BenchmarkParameters::meijaard2007())?;
    match what.as_str() {
        "forward" | "project" => {
            let state = model.initial_state(&InitialConditions {
                lean: 0.1,
                steer: 0.05,
                lean_rate: 0.5,
                steer_rate: -0.2,
                ..InitialConditions::upright(4.6)
            })?;
            let inputs = Inputs::default();
            let mut projected = state;
            let calls: usize = std::env::args()
                .nth(2)
                .and_then(|text| text.parse().ok())
                .unwrap_or(10_000);
            for _ in 0..calls {
                if what == "forward" {
                    black_box(model.forward(black_box(&state), black_box(&inputs))?);
                } else {
                    projected.q[0] += 1e-12;
                    black_box(model.project(black_box(&mut projected), &Default::default())?);
                }
            }
        }
        _ => {
            let start = model.initial_state(&InitialConditions {
                lean_rate: 0.5,
                ..InitialConditions::upright(4.6)
            })?;
            let duration = match std::env::args().nth(2) {
                Some(text) => text.parse().map_err(|_| whipple::Error::InvalidArgument {
                    what: "duration",
                    rule: format!("must be a number of seconds, got {text}"),
                })?,
                None => 1.0,
            };
            let settings = SimulationSettings {
                duration,
                ..SimulationSettings::default()
            };
            let run = simulate(&model, black_box(start), &settings)?;
            let last = run.samples.last().copied().unwrap_or_default();
            println!(
                "{} steps, lean {:.15e}, energy {:.15e}",
                run.steps, last.lean, last.energy
            );
        }
    }
    Ok(())
}
