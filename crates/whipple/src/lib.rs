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
//!               Canonical, InitialConditions, Model, SimulationSettings};
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
//! assert_eq!(run.outcome.to_string(), "completed");               // 4.6 m/s is self-stable
//! # Ok::<(), whipple::Error>(())
//! ```
//!
//! The same program, printing what it finds, is `examples/front_door.rs` (`cargo run -p whipple
//! --example front_door`).
//!
//! ## The front door, and what lies behind it
//!
//! The crate's root holds what a user of the model needs: a bicycle ([`Bicycle`],
//! [`BenchmarkParameters`], [`presets`]), the linear model ([`Canonical`]), its eigenvalues over
//! speed ([`speed_grid`], [`eigen_sweep`], [`EigenSweep`]), the critical speeds ([`critical_speeds`],
//! [`CriticalSpeeds`]), the non-linear model ([`Model`], [`InitialConditions`]) and its simulation
//! ([`simulate`], [`SimulationSettings`]), design studies ([`Study`]) and the [`Error`].
//! Everything else the front ends (the command, the server, the Python package) need is in
//! [`advanced`], one module per area; the rest of the crate is private.
//!
//! | to … | open |
//! |---|---|
//! | describe a bicycle: benchmark form, JBike6's form, presets, files | [`presets`], [`advanced::parameters`], [`advanced::io`], [`advanced::table`] |
//! | get the linearized equations M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f, A(v), p(λ, v) | [`Canonical`], [`advanced::linear`] |
//! | the bicycle as a linear system (named states, inputs, outputs; A, B, C, D), transfer functions, poles and zeros, frequency response | [`advanced::linear::LinearSystem`] |
//! | eigenvalues, eigenvectors, modes, speed sweeps | [`eigen_sweep`], [`advanced::eigen`], [`advanced::modes`], [`advanced::sweep`] |
//! | critical speeds and self-stable ranges, their σ and sensitivities | [`critical_speeds`], [`advanced::stability`], [`advanced::sensitivity`] |
//! | design studies over one or two parameters | [`Study`], [`advanced::design`] |
//! | the non-linear multibody bicycle: states, forward dynamics, simulation | [`Model`], [`simulate`], [`advanced::nonlinear`] |
//! | steady turns | [`advanced::turns`] |
//! | integrate any ẏ = f(t, y) (RK4, Dormand–Prince) | [`advanced::integrate`] |
//! | linearize any model exactly (dual numbers) or by the study's differences | [`advanced::linearize`] |
//! | compare the non-linear model with the linear one (Dressel's benchmark) | [`advanced::comparison`] |
//! | where the parts of the drawn bicycle are (JBike6's side view) | [`advanced::side_view`] |
//! | what can go wrong | [`Error`] |
//!
//! Words: *validate* means checking input against rules ([`BenchmarkParameters::validate`],
//! [`SimulationSettings::validate`]); comparing one model with another is
//! *compare* ([`advanced::comparison::compare_with_linear`]). Settings structs are named
//! `…Settings`, each with a `Default`. The benchmark bicycle is
//! [`BenchmarkParameters::meijaard2007`]; every named bicycle, that one included, is also found by
//! name with [`presets::find`].
#![deny(missing_docs)]
#![warn(unreachable_pub)]
mod analysis;
mod error;
mod expression;
mod integrate;
mod linear;
pub mod math;
mod nonlinear;
mod parameters;
mod rider;
mod side_view;

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

/// A bicycle as it was described (benchmark or JBike6 form), with its name and source.
///
/// ```
/// use whipple::advanced::io;
/// use whipple::{presets, Bicycle};
/// use whipple::advanced::parameters::Description;
/// use whipple::advanced::io::Format;
/// let crown: Bicycle = presets::find("schwinn-crown")?.bicycle();        // from a preset
/// let text = io::write(&crown, Format::Toml)?;
/// let again = io::parse(&text, Format::Toml)?;                           // from file text
/// let mine = Bicycle::new(Description::Benchmark(crown.benchmark()?));   // from a struct
/// assert_eq!(again.benchmark()?, mine.benchmark()?);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::Bicycle;

/// The 25 benchmark parameters of Meijaard et al. 2007 (Table 1) plus g.
///
/// ```
/// use whipple::BenchmarkParameters;
/// let heavier = BenchmarkParameters { m_b: 100.0, ..BenchmarkParameters::meijaard2007() };
/// heavier.validate()?;
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::BenchmarkParameters;

/// Named bicycles from the literature.
///
/// ```
/// let bike = whipple::presets::find("browser-jason")?.bicycle().benchmark()?;
/// assert!(bike.m_b > 0.0);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use parameters::presets;

/// The linearized model M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f (Meijaard 2007, Appendix A).
///
/// ```
/// let c = whipple::Canonical::new(&whipple::BenchmarkParameters::meijaard2007())?;
/// assert!((c.m[(0, 0)] - 80.81722).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use linear::Canonical;

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
/// use whipple::{BenchmarkParameters, InitialConditions, Model};
/// use whipple::advanced::nonlinear::Inputs;
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
/// use whipple::advanced::integrate::Integrator;
/// use whipple::SimulationSettings;
/// let settings = SimulationSettings { integrator: Integrator::adaptive(1e-9), ..SimulationSettings::default() };
/// settings.validate()?;
/// # Ok::<(), whipple::Error>(())
/// ```
pub use nonlinear::SimulationSettings;

/// A design study: the critical speeds of a bicycle as one or two parameters vary (rows streamed
/// in order, computed in parallel).
///
/// ```
/// use whipple::advanced::design::{Axis, Parameter, Shard, StudySettings};
/// use whipple::{presets, Study};
/// let bike = presets::find("benchmark")?.bicycle();
/// let x = Axis::new(Parameter::find("c", &bike)?, 0.05, 0.1, 3)?; // trail c [m]
/// let study = Study::new(bike, x, None, StudySettings::default())?;
/// let mut rows = Vec::new();
/// study.run(Shard::WHOLE, &Default::default(), |chunk| { rows.extend_from_slice(chunk); Ok(()) })?;
/// assert_eq!(rows.len(), 3);
/// # Ok::<(), whipple::Error>(())
/// ```
pub use analysis::design::Study;

/// What the front ends (the command, the server, the Python package) and advanced users need
/// beyond the front door, by area. Everything else in the crate is private.
pub mod advanced {
    /// A number for a message: shortest round-trip text, in exponent form when very large or small
    /// (the library's messages and the front ends' write numbers the same way).
    ///
    /// ```
    /// assert_eq!((whipple::advanced::short_number(0.25), whipple::advanced::short_number(1e300)), ("0.25".into(), "1e300".into()));
    /// ```
    pub use crate::error::short_number;
    /// A piece of a user's input cut for a message (the library's messages and the front ends'
    /// quote input the same way).
    ///
    /// ```
    /// assert_eq!(whipple::advanced::shorten("abcdef", 4), "abc…");
    /// ```
    pub use crate::error::shorten;
    #[doc = "The non-linear model against the linear one (Dressel's benchmark)."]
    pub mod comparison {
        /// Settings of the study's finite-difference linearization.
        ///
        /// ```
        /// assert!(whipple::advanced::comparison::ComparisonSettings::default().projection.is_some());
        /// ```
        pub use crate::analysis::comparison::ComparisonSettings;
        /// The result of [`compare_with_linear`].
        ///
        /// ```
        /// use whipple::advanced::comparison::{compare_with_linear, ComparisonSweep, Linearization, ComparisonSettings};
        /// use whipple::BenchmarkParameters;
        /// let sweep: ComparisonSweep = compare_with_linear(&BenchmarkParameters::meijaard2007(), &[5.0],
        ///                                                  &[Linearization::Exact], &ComparisonSettings::default())?;
        /// assert!(sweep.method(Linearization::Exact).is_some());
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::analysis::comparison::ComparisonSweep;
        /// A way to linearize the non-linear model: the study's differences, exact, exact full state.
        ///
        /// ```
        /// assert_eq!(whipple::advanced::comparison::Linearization::Exact.name(), "ad");
        /// ```
        pub use crate::analysis::comparison::Linearization;
        /// Compares the non-linear model with the linear one over a sweep of speeds.
        ///
        /// ```
        /// use whipple::advanced::comparison::{compare_with_linear, Linearization, ComparisonSettings};
        /// use whipple::BenchmarkParameters;
        /// let sweep = compare_with_linear(&BenchmarkParameters::meijaard2007(), &[2.0, 6.0],
        ///                                 &[Linearization::Exact], &ComparisonSettings::default())?;
        /// assert!(sweep.methods[0].max_abs_diff.iter().all(|d| *d < 1e-11));
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::analysis::comparison::compare_with_linear;
        /// The non-linear model's own A(v) about upright straight running, exact (dual numbers).
        ///
        /// ```
        /// use whipple::advanced::comparison::lean_steer_matrix;
        /// use whipple::{BenchmarkParameters, Canonical, Model};
        /// use whipple::advanced::linear::StateSpace;
        /// let bike = BenchmarkParameters::meijaard2007();
        /// let a = lean_steer_matrix(&Model::new(&bike)?, 5.0)?;
        /// let linear = StateSpace::new(&Canonical::new(&bike)?, 5.0)?.a;
        /// assert!((a - linear).amax() < 1e-12 * linear.amax());
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::analysis::comparison::lean_steer_matrix;
        pub use crate::analysis::comparison::{
            LinearizationSweep, MAX_COMPARED_SPEEDS, capsize_spike, compare_with_linear_until,
            double_root_conditioning, full_state_jacobian, full_state_jacobian_fd,
            general_eigenvalues, lean_steer_eigenvalues, max_abs_diff, pick, zero_cluster,
        };
    }
    #[doc = "Feedback and controllability: the closed loop u = r − K x (gains constant or scheduled with speed), its tracked eigenvalues and certified critical speeds; LQR gains (the continuous algebraic Riccati equation) and single-input pole placement (`LinearSystem::lqr`, `LinearSystem::place_poles`); the Kalman matrix, modal controllability and the certified speeds where an input loses a mode."]
    pub mod control {
        pub use crate::linear::{
            ClosedLoop, Gains, Lqr, LqrSchedule, MAX_GENERAL_SWEEP_SPEEDS, MAX_RICCATI_RESIDUAL,
            MAX_RICCATI_STATES, MAX_SCHEDULE_SPEEDS, care, lqr_schedule,
        };
        /// Controllability: the Kalman matrix at a speed, each mode's modal controllability,
        /// and the speeds where one input loses a mode, certified.
        pub use crate::linear::{
            Controllability, ModalControllability, UncontrollableSpeed, UncontrollableSpeeds,
            uncontrollable_speeds,
        };
        /// Hess's loops one at a time (open- and closed-loop transfer functions, crossover
        /// frequencies), gains by Hess 2012's rules, and the ridden bicycle's eigenvalues
        /// against speed.
        pub use crate::linear::{
            Crossover, CrossoverRules, GainSchedule, HumanSweepRow, LoopResponse,
            LoopTransferFunction, MAX_HUMAN_SWEEP_SPEEDS, RiderLoop, hess_gains, human_eigen_sweep,
        };
        /// The rider as Hess, Moore & Hubbard 2012's controller: nested loops (steer angle, roll
        /// rate, roll angle, heading, lateral deviation) and a neuromuscular filter, the closed
        /// loop of HumanControl's `system_state_space.m`, and gains tabulated against speed.
        pub use crate::linear::{
            GainLookup, GainTable, HumanController, HumanGains, HumanLoop, LoopInput, LoopState,
            MAX_GAIN_SPEEDS, NEUROMUSCULAR_DAMPING, NEUROMUSCULAR_FREQUENCY, Neuromuscular, Task,
        };
        /// The optimal-handling search of BMD 2016: the peak HQM minimized over chosen
        /// parameters within bounds at a design speed, the gains by Hess 2012's rules for each
        /// candidate (Nelder–Mead from several starts; local, not certified global).
        pub use crate::linear::{
            HandlingBound, HandlingCandidate, HandlingStart, MAX_HANDLING_ITERATIONS,
            MAX_HANDLING_PARAMETERS, MAX_HANDLING_STARTS, OptimalHandling, OptimalHandlingSettings,
            judge_handling, optimal_handling,
        };
        /// Hess's handling quality metric as HumanControl computes it: its exact transfer
        /// function, magnitude and certified peak over frequency, against speed and against a
        /// parameter.
        pub use crate::linear::{
            HandlingPeak, HandlingQuality, HandlingRow, MAX_HANDLING_POINTS,
            handling_against_parameter, handling_against_speed,
        };
        /// HumanControl's single and double lane change, ridden by Hess's controller on the
        /// linear bicycle (exactly) and on the non-linear one.
        pub use crate::linear::{
            LaneChange, LaneChangeRun, LaneKind, MAX_LANE_CHANGE_SAMPLES, lane_change_linear,
            lane_change_nonlinear,
        };
    }
    #[doc = "Design studies over one or two parameters."]
    pub mod design {
        pub use crate::analysis::design::{
            Axis, DesignQuantities, DesignRow, DesignStatus, MAX_AXIS_POINTS, Parameter, Shard,
            StudySettings, aliases,
        };
    }
    #[doc = "Eigenvalues and eigenvectors of the linear model at one speed."]
    pub mod eigen {
        /// A complex number of f64 (an eigenvalue).
        ///
        /// ```
        /// let z = whipple::advanced::eigen::Complex64::new(-0.5, 3.0);
        /// assert_eq!(z.conj().im, -3.0);
        /// ```
        pub use crate::analysis::eigen::Complex64;
        /// The four eigenvalues of the linearized model at one speed.
        ///
        /// ```
        /// use whipple::advanced::eigen::eigenvalues;
        /// use whipple::{BenchmarkParameters, Canonical};
        /// let lambda = eigenvalues(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 5.0)?;
        /// assert!(lambda.iter().all(|l| l.re < 0.0)); // 5 m/s is self-stable
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::analysis::eigen::eigenvalues;
        pub use crate::analysis::eigen::{
            eigenpairs, eigenpairs_with, eigenvalues_with, eigenvector, quartic_roots,
        };
    }
    #[doc = "Integration of ODEs: RK4 and Dormand–Prince 5(4)."]
    pub mod integrate {
        /// The integration method and its step settings.
        ///
        /// ```
        /// use whipple::advanced::integrate::Integrator;
        /// assert_eq!(Integrator::default(), Integrator::Rk4 { dt: 1e-3 });
        /// assert!(Integrator::Rk4 { dt: 0.0 }.validate().is_err());
        /// ```
        pub use crate::integrate::Integrator;
        pub use crate::integrate::{DEFAULT_DT, DEFAULT_RTOL, Dopri5Settings, OdeSystem, Stepper};
    }
    #[doc = "Parameter files from and to text: TOML, JSON, JBike6's `.m`, BicycleParameters' and HumanControl's `.txt`, YAML."]
    pub mod io {
        /// A parameter file's format.
        ///
        /// ```
        /// assert_eq!(whipple::advanced::io::Format::from_extension("toml"), Some(whipple::advanced::io::Format::Toml));
        /// ```
        pub use crate::parameters::io::Format;
        /// A parameter set in Moore 2012's parameterization (BicycleParameters' `Moore2012`).
        pub use crate::parameters::io::moore2012_yaml;
        /// A principal parameter set (Moore 2019) of a bicycle that carries its rider P.
        pub use crate::parameters::io::principal_yaml;
        /// HumanControl's gains file (`<Name>SteerGains.txt`) as a gain table.
        pub use crate::parameters::io::read_gains;
        /// BicycleParameters' `MooreRiderLean2012` set, as a JSON object of its keys.
        pub use crate::parameters::io::read_moore_rider_lean2012;
        pub use crate::parameters::io::{
            FORMATS, MAX_FILE_BYTES, UNDETERMINED_FORMAT, json_slice_without_duplicates,
            json_without_duplicates, name_from_file_name, parse, write,
        };
    }
    #[doc = "The linearized model: canonical matrices, state space, characteristic polynomial, the linear system with named inputs and outputs, transfer functions, time responses (exact and integrated), one manoeuvre on the linear and the non-linear model."]
    pub mod linear {
        /// The characteristic polynomial p(λ, v) = det(M λ² + v C₁ λ + g K₀ + v² K₂).
        ///
        /// ```
        /// use whipple::{BenchmarkParameters, Canonical};
        /// use whipple::advanced::linear::CharacteristicPolynomial;
        /// let p = CharacteristicPolynomial::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?);
        /// assert_eq!(p.at_speed(5.0).len(), 5);
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::linear::CharacteristicPolynomial;
        /// The bicycle as a linear system ẋ = A x + B u, y = C x + D u at a speed, with named
        /// states (lean, steer, their rates, and on request yaw, the rear contact, the wheel
        /// angles), inputs (lean and steer torque, a lateral force) and outputs; its transfer
        /// functions exactly from the polynomial matrix.
        ///
        /// ```
        /// use whipple::BenchmarkParameters;
        /// use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
        /// let request = SystemRequest {
        ///     states: vec![],
        ///     inputs: vec![Input::SteerTorque],
        ///     outputs: vec![Output::State(StateVariable::Lean)],
        /// };
        /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 3.0, &request)?;
        /// let g = system.transfer_function(0, 0)?;
        /// assert_eq!(g.poles().len(), 4);
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::linear::LinearSystem;
        pub use crate::linear::SpeedPolynomials;
        /// The state-space form ẋ = A x + B u at a speed, x = [φ, δ, φ̇, δ̇].
        ///
        /// ```
        /// use whipple::{BenchmarkParameters, Canonical};
        /// use whipple::advanced::linear::StateSpace;
        /// let ss = StateSpace::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?, 5.0)?;
        /// assert_eq!(ss.a[(0, 2)], 1.0);
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::linear::StateSpace;
        pub use crate::linear::{
            FrequencyResponse, Input, MAX_SIGNALS, Output, StateVariable, SystemRequest,
            TransferFunction, origin_zero_speeds,
        };
        pub use crate::linear::{
            GroundPath, InputSignal, MAX_KNOTS, MAX_MANOEUVRE_BREAKS, MAX_RESPONSE_TIMES,
            MAX_RESPONSE_VALUES, Manoeuvre, ManoeuvreComparison, ManoeuvreMotion, TimeResponse,
            compare_manoeuvre,
        };
    }
    #[doc = "Jacobians of any vector field: exact (dual numbers) and by central differences."]
    pub mod linearize {
        pub use crate::analysis::linearize::{
            FdSettings, VectorField, central_differences, jacobian,
        };
    }
    #[doc = "Modes: tracking, labels (weave, capsize, castering) and mode shapes."]
    pub mod modes {
        /// The name of a tracked mode: weave, capsize, castering, or unclassified.
        ///
        /// ```
        /// use whipple::{eigen_sweep, speed_grid, BenchmarkParameters, Canonical};
        /// use whipple::advanced::modes::Mode;
        /// let sweep = eigen_sweep(&Canonical::new(&BenchmarkParameters::meijaard2007())?, &speed_grid(0.0, 10.0, 0.1)?)?;
        /// assert!(sweep.modes.contains(&Mode::Capsize));
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::analysis::modes::Mode;
        pub use crate::analysis::modes::mode_shapes;
    }
    #[doc = "The non-linear multibody bicycle: states, forward dynamics, simulation and its settings."]
    pub mod nonlinear {
        /// How a simulation ended.
        ///
        /// ```
        /// assert_eq!(whipple::advanced::nonlinear::Outcome::Completed.to_string(), "completed");
        /// ```
        pub use crate::nonlinear::Outcome;
        /// One recorded instant of a simulation.
        ///
        /// ```
        /// use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, SimulationSettings};
        /// use whipple::advanced::nonlinear::Sample;
        /// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
        /// let start = model.initial_state(&InitialConditions::upright(4.6))?;
        /// let run = simulate(&model, start, &SimulationSettings { duration: 0.1, ..SimulationSettings::default() })?;
        /// let last: &Sample = &run.samples[run.samples.len() - 1];
        /// assert!((last.speed - 4.6).abs() < 1e-9 && last.is_finite());
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::nonlinear::Sample;
        /// The result of [`simulate`](crate::simulate): samples, outcome, counts.
        ///
        /// ```
        /// use whipple::{simulate, BenchmarkParameters, InitialConditions, Model, SimulationSettings};
        /// use whipple::advanced::nonlinear::Simulation;
        /// let model = Model::new(&BenchmarkParameters::meijaard2007())?;
        /// let start = model.initial_state(&InitialConditions::upright(4.6))?;
        /// let run: Simulation = simulate(&model, start, &SimulationSettings { duration: 0.1, ..SimulationSettings::default() })?;
        /// assert_eq!((run.steps, run.samples.len()), (100, 101));
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::nonlinear::Simulation;
        pub use crate::nonlinear::rotation;
        pub use crate::nonlinear::{
            BODY_NAMES, BodyPose, ContactForce, DEFAULT_FALL_ANGLE, FRONT_WHEEL, HINGE_LIMIT,
            Inputs, LeanForcing, LeanModel, LeanRates, LeanSimulation, LeanState,
            MAX_EXPRESSION_DEPTH, MAX_EXPRESSION_LENGTH, MAX_SAMPLES, MAX_STEPS, Progress,
            ProjectionMethod, ProjectionSettings, REAR_FRAME, REAR_WHEEL, STATE_LEN, State,
            StateView, TorqueExpression, TorqueFn, Wheel, check_rk4_step, fastest_mode,
            samples_kept,
        };
    }
    #[doc = "Bicycle descriptions: the benchmark and JBike6 forms, checks and their notices."]
    pub mod parameters {
        /// The form a bicycle was described in.
        ///
        /// ```
        /// use whipple::presets;
        /// use whipple::advanced::parameters::Description;
        /// assert!(matches!(presets::find("benchmark")?.bicycle().description, Description::Benchmark(_)));
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::parameters::Description;
        /// JBike6's seven bodies (wheels, rider, frame, rack, fork, basket).
        ///
        /// ```
        /// let crown = whipple::presets::schwinn_crown_jbike6();
        /// assert!((crown.to_benchmark()?.m_b - 84.5).abs() < 1e-12);
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::parameters::Jbike6Parameters;
        pub use crate::parameters::jbike6::BENCHMARK_FROM_JBIKE6;
        pub use crate::parameters::{Checked, Notice, Severity};
        /// Moore 2012's leaning rider: the bicycle with the rider's lower body in its rear
        /// frame, the upper body G hinged to it, and BicycleParameters' `MooreRiderLean2012`
        /// keys both ways.
        ///
        /// ```
        /// use whipple::advanced::parameters::RiderLeanParameters;
        /// let p = RiderLeanParameters::browser_jason();
        /// assert!((p.upper_body.z_hinge + 1.011421527346159).abs() < 1e-15);
        /// ```
        pub use crate::parameters::{
            MOORE_RIDER_LEAN2012_KEYS, MooreRiderLean2012Parameters, RiderLeanParameters, UpperBody,
        };
        /// Moore 2012's parameterization (BicycleParameters' `Moore2012`) and its conversion
        /// to and from the benchmark form.
        ///
        /// ```
        /// use whipple::BenchmarkParameters;
        /// use whipple::advanced::parameters::Moore2012Parameters;
        /// let b = BenchmarkParameters::meijaard2007();
        /// let back = Moore2012Parameters::from_benchmark(&b).to_benchmark()?;
        /// assert!((back.w - b.w).abs() < 1e-15 && (back.c - b.c).abs() < 1e-15);
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::parameters::{MOORE2012_KEYS, Moore2012Parameters};
        /// BicycleParameters' principal parameterization (Moore 2019) and its conversion to
        /// and from the benchmark form.
        ///
        /// ```
        /// use whipple::BenchmarkParameters;
        /// use whipple::advanced::parameters::{PrincipalBody, PrincipalParameters};
        /// let b = BenchmarkParameters::meijaard2007();
        /// // A 20 kg rider inside the benchmark's 85 kg rear frame B; D is B without it.
        /// let rider = PrincipalBody { m: 20.0, x: 0.3, z: -0.9, k_aa: 0.2, k_bb: 0.1, k_yy: 0.2, alpha: 0.2 };
        /// let p = PrincipalParameters::from_benchmark(&b, &rider, 1.7, 0.5)?;
        /// assert!((p.to_benchmark().i_bxz - b.i_bxz).abs() < 1e-12);
        /// # Ok::<(), whipple::Error>(())
        /// ```
        pub use crate::parameters::{PRINCIPAL_KEYS, PrincipalBody, PrincipalParameters};
    }
    #[doc = "Bicycles from bench measurements: BicycleParameters' `*Measured.txt` read, and the steps (Moore 2012 ch. 2) to benchmark parameters with exact first-order σ and covariance."]
    pub mod measured {
        /// Pendulum periods from oscillation records: a decaying oscillation fitted by
        /// Levenberg–Marquardt, the period's σ from the fit's covariance.
        pub use crate::parameters::measured::period;
        pub use crate::parameters::measured::report::{Correlation, Step};
        pub use crate::parameters::measured::steps;
        pub use crate::parameters::measured::{
            FittedPeriod, Flywheel, FrontFrame, Geometry, HandlebarReference, Hanging, HungPart,
            MAX_HANGINGS, Measured, MeasuredFile, MeasuredParameters, Measurements, Offsets,
            PeriodSource, benchmark_from_measurements, read_measurements,
            read_measurements_with_records, record_name,
        };
    }
    #[doc = "The Yeadon human body model (Yeadon 1990): a rider's 11 segments from the 95 anthropometric measurements and the 21 joint angles, with `yeadon`'s files read; the rider seated on a measured bicycle and added to its rear frame (BicycleParameters' `add_rider`)."]
    pub mod rider {
        pub use crate::rider::{
            CONFIGURATION_ANGLES, MAX_ITERATIONS, MEASUREMENT_NAMES, RIDER_GEOMETRY_KEYS,
            RiderBody, RiderGeometry, SEATED_ANGLES, SEGMENT_NAMES, SeatedRider, SeatedSolve,
            YeadonBody, YeadonConfiguration, YeadonMeasurements, YeadonSegment, bottom_bracket,
            combine_with_rear_frame, handlebar_grips, read_yeadon_configuration,
            read_yeadon_measurements, rider_in_benchmark_frame, rider_on_bicycle, seat,
            seated_configuration, seated_rider, solve_seated, yeadon_body,
        };
    }
    #[doc = "Certified real roots of low-degree polynomials."]
    pub mod roots {
        pub use crate::analysis::roots::{BoundedPolynomial, RealRoot, real_roots};
    }
    #[doc = "Exact derivatives by dual numbers: sensitivities and first-order σ."]
    pub mod sensitivity {
        pub use crate::analysis::sensitivity::{
            CriticalSpeedsSigma, ParameterDerivatives, ParameterSensitivity, Sensitivities,
            critical_speeds_sigma, eigenvalue_sigmas, sensitivities, with_parameter,
        };
    }
    #[doc = "Where the parts of the drawn bicycle are (JBike6's side view)."]
    pub mod side_view {
        pub use crate::side_view::{Ellipse, Part, Point, SideView, side_view};
    }
    #[doc = "Certified critical speeds and self-stable ranges."]
    pub mod stability {
        pub use crate::analysis::stability::{BandAnswer, CrossingKind, StabilitySummary, summary};
    }
    #[doc = "Speed grids and eigenvalue sweeps."]
    pub mod sweep {
        pub use crate::analysis::sweep::{SpeedGrid, SweepPlan};
        pub use crate::analysis::track::track_modes;
    }
    #[doc = "The one parameter table: names, keys, symbols, units and meanings of every parameter."]
    pub mod table {
        pub use crate::parameters::table::{
            Form, MILLIMETRES_PER_METRE, ParameterInfo, RADIANS_PER_DEGREE, TypedUnit, find_typed,
            index_of, key_doc, parameters,
        };
    }
    #[doc = "Steady turns of the non-linear model: held and hands-free."]
    pub mod turns {
        pub use crate::analysis::turns::{
            Family, FamilyEnd, FamilyPoint, FamilySettings, Held, MAX_RADIUS, Stability,
            SteadyTurn, TurnSettings, branch_family, branch_from_straight, hands_free_families,
            hands_free_turn_near, hands_free_turns_at_speed, held_turn, stability, turn_jacobian,
        };
    }
}
