//! # whipple
//!
//! Dynamics of the Whipple bicycle: the benchmark parameters of Meijaard et al. 2007 and
//! JBike6's seven-body description, the linearized model (M, C₁, K₀, K₂), eigenvalues, modes,
//! critical speeds and the self-stable speed range; the fully non-linear multibody bicycle, its
//! simulation, and its comparison with the linear model.
//!
//! Data flows one way: parameters → model → analysis. The whole pipeline through the front
//! door (the names re-exported here):
//!
//! ```
//! use whipple::{critical_speeds, eigen_sweep, simulate, speed_grid, BenchmarkParameters,
//!               Canonical, InitialConditions, Model, Outcome, SimulationSettings};
//!
//! let bike = BenchmarkParameters::meijaard2007();                  // Meijaard 2007, Table 1
//! let linear = Canonical::new(&bike)?;                              // M, C₁, K₀, K₂
//! let sweep = eigen_sweep(&linear, &speed_grid(0.0, 10.0, 0.1)?)?;  // eigenvalues, modes tracked
//! let critical = critical_speeds(&linear, 0.0, 10.0)?;             // v_d, v_w, v_c, stable ranges
//! let model = Model::new(&bike)?;                                   // the non-linear bicycle
//! let kicked = InitialConditions { lean_rate: 0.5, ..InitialConditions::upright(4.6) };
//! let settings = SimulationSettings { duration: 5.0, ..SimulationSettings::default() };
//! let run = simulate(&model, model.initial_state(&kicked)?, &settings)?; // 5 s, RK4, projected
//!
//! assert_eq!((sweep.speeds.len(), sweep.modes[0].name()), (101, "weave"));
//! assert!(critical.weave_speed.is_some_and(|v| (v - 4.29238253634111).abs() < 1e-12));
//! assert_eq!(run.outcome, Outcome::Completed);                     // 4.6 m/s is self-stable
//! # Ok::<(), whipple::Error>(())
//! ```
//!
//! The same program, printing what it finds, is `examples/front_door.rs` (`cargo run -p whipple
//! --example front_door`).
//!
//! ## Which module to open for what
//!
//! | to … | open |
//! |---|---|
//! | describe a bicycle: benchmark form, JBike6's form, presets, files (TOML, JSON, `.m`) | [`parameters`] ([`presets`], [`io`]) |
//! | get the linearized equations M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f, A(v), p(λ, v) | [`linear`] |
//! | eigenvalues, eigenvectors, modes, speed sweeps | [`analysis::eigen`], [`analysis::modes`], [`analysis::sweep`] |
//! | critical speeds and self-stable ranges | [`analysis::stability`] (root finding in [`analysis::roots`]) |
//! | the non-linear multibody bicycle: states, forward dynamics, projection, simulation | [`nonlinear`] |
//! | integrate any ẏ = f(t, y) (RK4, Dormand–Prince) | [`integrate`] |
//! | linearize any model exactly (dual numbers) or by the study's differences | [`analysis::linearize`] |
//! | compare the non-linear model with the linear one (Dressel's benchmark) | [`analysis::comparison`] |
//! | where the parts of the drawn bicycle are (JBike6's side view) | [`side_view`] |
//! | what can go wrong | [`Error`] |
//!
//! Words: *validate* means checking input against rules ([`BenchmarkParameters::validate`],
//! [`SimulationSettings::validate`], [`Integrator::validate`]); comparing one model with another
//! is *compare* ([`compare_with_linear`]). Settings structs are named `…Settings`
//! ([`SimulationSettings`], [`StudySettings`], `ProjectionSettings`, `Dopri5Settings`, …), each
//! with a `Default`. The benchmark bicycle is [`BenchmarkParameters::meijaard2007`]; every
//! named bicycle, that one included, is also found by name with [`presets::find`].
#![deny(missing_docs)]

pub mod analysis;
mod error;
pub mod integrate;
pub mod linear;
pub mod nonlinear;
pub mod parameters;
pub mod side_view;

/// The library's error: one variant per kind of failure, naming the field, value and rule.
///
/// ```
/// let bad = whipple::BenchmarkParameters { m_b: -1.0, ..whipple::BenchmarkParameters::meijaard2007() };
/// let error = whipple::Model::new(&bad).unwrap_err();
/// assert!(matches!(error, whipple::Error::InvalidParameter { ref field, .. } if field == "mB"));
/// ```
pub use error::Error;

/// `Result<T, whipple::Error>`.
///
/// ```
/// fn speed_range() -> whipple::Result<Vec<f64>> {
///     whipple::speed_grid(0.0, 1.0, 0.5)
/// }
/// assert_eq!(speed_range()?, [0.0, 0.5, 1.0]);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use error::Result;

/// A piece of a user's input cut for a message (the library's messages and the front ends'
/// quote input the same way).
///
/// ```
/// assert_eq!(whipple::shorten("abcdef", 4), "abc…");
/// ```
pub use error::shorten;

/// A number for a message: shortest round-trip text, in exponent form when very large or small
/// (the library's messages and the front ends' write numbers the same way).
///
/// ```
/// assert_eq!((whipple::short_number(0.25), whipple::short_number(1e300)), ("0.25".into(), "1e300".into()));
/// ```
pub use error::short_number;

/// A bicycle as it was described (benchmark or JBike6 form), with its name and source.
///
/// ```
/// use whipple::{io, presets, Bicycle, Description, Format};
/// let crown: Bicycle = presets::find("schwinn-crown")?.bicycle();        // from a preset
/// let text = io::write(&crown, Format::Toml)?;
/// let again = io::parse(&text, Format::Toml)?;                           // from file text
/// let mine = Bicycle::new(Description::Benchmark(crown.benchmark()?));   // from a struct
/// assert_eq!(again.benchmark()?, mine.benchmark()?);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::Bicycle;

/// The form a bicycle was described in.
///
/// ```
/// use whipple::{presets, Description};
/// assert!(matches!(presets::find("benchmark")?.bicycle().description, Description::Benchmark(_)));
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::Description;

/// The 25 benchmark parameters of Meijaard et al. 2007 (Table 1) plus g.
///
/// ```
/// use whipple::BenchmarkParameters;
/// let heavier = BenchmarkParameters { m_b: 100.0, ..BenchmarkParameters::meijaard2007() };
/// heavier.validate()?;
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::BenchmarkParameters;

/// JBike6's seven bodies (wheels, rider, frame, rack, fork, basket).
///
/// ```
/// let crown = whipple::presets::schwinn_crown_jbike6();
/// assert!((crown.to_benchmark()?.m_b - 84.5).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::Jbike6Parameters;

/// Named bicycles from the literature.
///
/// ```
/// let bike = whipple::presets::find("browser-jason")?.bicycle().benchmark()?;
/// assert!(bike.m_b > 0.0);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::presets;

/// Parameter files from and to text: TOML, JSON, JBike6's `.m`.
///
/// ```
/// use whipple::{io, Format};
/// let bike = io::parse("[benchmark]\nw = 1.02\n", Format::Toml);
/// assert!(bike.is_err()); // every key is required
/// ```
pub use parameters::io;

/// A parameter file's format.
///
/// ```
/// assert_eq!(whipple::Format::from_extension("toml"), Some(whipple::Format::Toml));
/// ```
pub use parameters::io::Format;

/// The linearized model M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f (Meijaard 2007, Appendix A).
///
/// ```
/// let c = whipple::Canonical::new(&whipple::BenchmarkParameters::meijaard2007())?;
/// assert!((c.m[(0, 0)] - 80.81722).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use linear::Canonical;

/// The state-space form ẋ = A x + B u at a speed, x = [φ, δ, φ̇, δ̇].
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical, StateSpace};
/// let ss = StateSpace::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 5.0)?;
/// assert_eq!(ss.a[(0, 2)], 1.0);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use linear::StateSpace;

/// The characteristic polynomial p(λ, v) = det(M λ² + v C₁ λ + g K₀ + v² K₂).
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical, CharacteristicPolynomial};
/// let p = CharacteristicPolynomial::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?);
/// assert_eq!(p.at_speed(5.0).len(), 5);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use linear::CharacteristicPolynomial;

/// The four eigenvalues of the linearized model at one speed.
///
/// ```
/// use whipple::{eigenvalues, BenchmarkParameters, Canonical};
/// let lambda = eigenvalues(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 5.0)?;
/// assert!(lambda.iter().all(|l| l.re < 0.0)); // 5 m/s is self-stable
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::eigen::eigenvalues;

/// A complex number of f64 (an eigenvalue).
///
/// ```
/// let z = whipple::Complex64::new(-0.5, 3.0);
/// assert_eq!(z.conj().im, -3.0);
/// ```
pub use analysis::eigen::Complex64;

/// Eigenvalues over a sweep of speeds, modes tracked and labelled.
///
/// ```
/// use whipple::{eigen_sweep, speed_grid, BenchmarkParameters, Canonical};
/// let sweep = eigen_sweep(&Canonical::new(&BenchmarkParameters::meijaard2007())?, &speed_grid(0.0, 10.0, 1.0)?)?;
/// assert_eq!(sweep.eigenvalues.len(), 11);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::sweep::eigen_sweep;

/// The result of [`eigen_sweep`].
///
/// ```
/// use whipple::{eigen_sweep, BenchmarkParameters, Canonical, EigenSweep};
/// let sweep: EigenSweep = eigen_sweep(&Canonical::new(&BenchmarkParameters::meijaard2007())?, &[4.0, 5.0])?;
/// assert_eq!(sweep.speeds, [4.0, 5.0]);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::sweep::EigenSweep;

/// Speeds START, START + STEP, …, STOP (both ends included).
///
/// ```
/// assert_eq!(whipple::speed_grid(0.0, 1.0, 0.25)?.len(), 5);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::sweep::speed_grid;

/// The name of a tracked mode: weave, capsize, castering, or unclassified.
///
/// ```
/// use whipple::{eigen_sweep, speed_grid, BenchmarkParameters, Canonical, Mode};
/// let sweep = eigen_sweep(&Canonical::new(&BenchmarkParameters::meijaard2007())?, &speed_grid(0.0, 10.0, 0.1)?)?;
/// assert!(sweep.modes.contains(&Mode::Capsize));
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::modes::Mode;

/// The double-root, weave and capsize speeds and the self-stable ranges within a range.
///
/// ```
/// use whipple::{critical_speeds, BenchmarkParameters, Canonical};
/// let c = critical_speeds(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 0.0, 10.0)?;
/// let (lo, hi) = c.stable_speed_ranges[0];
/// assert!((lo - 4.29238253634111).abs() < 1e-12 && (hi - 6.02426201538837).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::stability::critical_speeds;

/// The result of [`critical_speeds`].
///
/// ```
/// use whipple::{critical_speeds, BenchmarkParameters, Canonical, CriticalSpeeds};
/// let c: CriticalSpeeds = critical_speeds(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 0.0, 10.0)?;
/// assert!(c.capsize_speed.is_some());
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::stability::CriticalSpeeds;

/// The non-linear multibody bicycle (four rigid bodies, 24 coordinates, constraint rows).
///
/// ```
/// use whipple::{BenchmarkParameters, InitialConditions, Model, nonlinear::Inputs};
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// let state = model.initial_state(&InitialConditions::upright(5.0))?;
/// assert!(model.forward(&state, &Inputs::default())?.u_dot.amax() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::Model;

/// A few numbers from which the model builds a consistent state.
///
/// ```
/// use whipple::{BenchmarkParameters, InitialConditions, Model};
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// let state = model.initial_state(&InitialConditions { lean: 0.1, ..InitialConditions::upright(4.0) })?;
/// assert!((model.observe(&state).lean - 0.1).abs() < 1e-15);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::InitialConditions;

/// Simulates the non-linear bicycle: step, project onto the constraints, events, samples.
///
/// ```
/// use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, SimulationSettings};
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// let start = model.initial_state(&InitialConditions { lean_rate: 0.5, ..InitialConditions::upright(3.0) })?;
/// let run = simulate(&model, start, &SimulationSettings { duration: 10.0, ..SimulationSettings::default() })?;
/// assert_eq!(run.outcome.kind(), "wheel_lifted"); // below the weave speed it falls
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::simulate;

/// What a simulation runs with (defaults: RK4 at 1 ms, 10 s, fall at 60°).
///
/// ```
/// use whipple::{Integrator, SimulationSettings};
/// let settings = SimulationSettings { integrator: Integrator::adaptive(1e-9), ..SimulationSettings::default() };
/// settings.validate()?;
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::SimulationSettings;

/// The result of [`simulate`]: samples, outcome, counts.
///
/// ```
/// use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, Simulation, SimulationSettings};
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// let start = model.initial_state(&InitialConditions::upright(4.6))?;
/// let run: Simulation = simulate(&model, start, &SimulationSettings { duration: 0.1, ..SimulationSettings::default() })?;
/// assert_eq!((run.steps, run.samples.len()), (100, 101));
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::Simulation;

/// One recorded instant of a simulation.
///
/// ```
/// use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, Sample, SimulationSettings};
/// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
/// let start = model.initial_state(&InitialConditions::upright(4.6))?;
/// let run = simulate(&model, start, &SimulationSettings { duration: 0.1, ..SimulationSettings::default() })?;
/// let last: &Sample = &run.samples[run.samples.len() - 1];
/// assert!((last.speed - 4.6).abs() < 1e-9 && last.is_finite());
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::Sample;

/// How a simulation ended.
///
/// ```
/// assert_eq!(whipple::Outcome::Completed.to_string(), "completed");
/// ```
pub use nonlinear::Outcome;

/// The integration method and its step settings.
///
/// ```
/// use whipple::Integrator;
/// assert_eq!(Integrator::default(), Integrator::Rk4 { dt: 1e-3 });
/// assert!(Integrator::Rk4 { dt: 0.0 }.validate().is_err());
/// ```
pub use integrate::Integrator;

/// The non-linear model's own A(v) about upright straight running, exact (dual numbers).
///
/// ```
/// use whipple::{lean_steer_matrix, BenchmarkParameters, Canonical, Model, StateSpace};
/// let bike = BenchmarkParameters::meijaard2007();
/// let a = lean_steer_matrix(&Model::new(&bike)?, 5.0)?;
/// let linear = StateSpace::new(&Canonical::new(&bike)?, 5.0)?.a;
/// assert!((a - linear).amax() < 1e-12 * linear.amax());
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::comparison::lean_steer_matrix;

/// Compares the non-linear model with the linear one over a sweep of speeds.
///
/// ```
/// use whipple::{compare_with_linear, BenchmarkParameters, Linearization, StudySettings};
/// let sweep = compare_with_linear(&BenchmarkParameters::meijaard2007(), &[2.0, 6.0],
///                                 &[Linearization::Exact], &StudySettings::default())?;
/// assert!(sweep.methods[0].max_abs_diff.iter().all(|d| *d < 1e-11));
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::comparison::compare_with_linear;

/// A way to linearize the non-linear model: the study's differences, exact, exact full state.
///
/// ```
/// assert_eq!(whipple::Linearization::Exact.name(), "ad");
/// ```
pub use analysis::comparison::Linearization;

/// Settings of the study's finite-difference linearization.
///
/// ```
/// assert!(whipple::StudySettings::default().projection.is_some());
/// ```
pub use analysis::comparison::StudySettings;

/// The result of [`compare_with_linear`].
///
/// ```
/// use whipple::{compare_with_linear, BenchmarkParameters, ComparisonSweep, Linearization, StudySettings};
/// let sweep: ComparisonSweep = compare_with_linear(&BenchmarkParameters::meijaard2007(), &[5.0],
///                                                  &[Linearization::Exact], &StudySettings::default())?;
/// assert!(sweep.method(Linearization::Exact).is_some());
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::comparison::ComparisonSweep;
