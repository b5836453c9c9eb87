//! Optimal handling: the design search of Moore, Hubbard & Hess 2016 ("An optimal handling
//! bicycle", BMD 2016; HumanControl's `optimal_bicycle.m` and `objective.m`). The search
//! changes chosen parameters of a bicycle within bounds and minimizes the peak of the handling
//! quality metric ([`HandlingQuality`]) at a design speed, the rider's gains set for each
//! candidate by Hess 2012's rules ([`hess_gains`]).
//!
//! # The objective
//!
//! For a candidate x: the bicycle with the parameters set to x, its gains by the crossover
//! rules at the design speed, and
//!
//! - the peak of |HQM(jω)| over every frequency, certified ([`HandlingQuality::peak`]), when
//!   the roll loop and the full lateral closed loop ([`HumanLoop`], the five loops closed) are
//!   both stable;
//! - otherwise a penalty above every stable candidate's peak: `UNSTABLE_PENALTY` plus 100
//!   times the largest real part of the lateral loop's eigenvalues (as `objective.m` does,
//!   lifted so that it cannot be mistaken for a peak); a candidate the library refuses (an
//!   invalid bicycle, a gain rule no gain meets) costs `INFEASIBLE_PENALTY`.
//!
//! `objective.m` samples |HQM| at 200 frequencies between 0.01 and 40 rad/s; here the peak is
//! the certified maximum over all frequencies, so no narrow resonance is missed.
//!
//! # The search
//!
//! BMD 2016 ran CMA-ES on the Simulink model. Here each start runs the Nelder–Mead simplex
//! method of the `argmin` crate (derivative-free: the gains' rules pick among branches, so the
//! objective is not smooth everywhere) on bounded variables mapped to the whole line by
//! x = lo + (hi − lo)(1 + sin z)/2. The first start is the base bicycle's own values (clamped
//! into the bounds), the others the points of a Halton sequence in the box, so a run is
//! reproducible. The best start wins; every start's result is returned, so a user sees whether
//! they agree. A search is a local method from several starts, not a certified global minimum:
//! the documentation and every front end say so.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use argmin::core::{CostFunction, Executor, State, TerminationReason};
use argmin::solver::neldermead::NelderMead;
use rayon::prelude::*;

use super::handling::{HandlingPeak, HandlingQuality};
use super::human::{HumanController, HumanGains, HumanLoop, Neuromuscular, Task};
use super::human_loops::{CrossoverRules, hess_gains};
use crate::analysis::design::Parameter;
use crate::error::{Error, Result, short_number};
use crate::parameters::Bicycle;

/// The cost of a candidate whose roll loop or lateral loop is unstable, before the term in its
/// largest real part: above any stable candidate's peak HQM in the field's bicycles.
pub(crate) const UNSTABLE_PENALTY: f64 = 1.0e3;

/// The cost of a candidate the library refuses (an invalid bicycle, no gain meeting a rule).
pub(crate) const INFEASIBLE_PENALTY: f64 = 1.0e6;

/// The most starts one search takes.
pub const MAX_HANDLING_STARTS: usize = 256;

/// The most Nelder–Mead iterations one start takes (each evaluates 1 to n + 2 candidates, n
/// the number of varied parameters).
pub const MAX_HANDLING_ITERATIONS: usize = 100_000;

/// The most parameters one search varies.
pub const MAX_HANDLING_PARAMETERS: usize = 16;

/// One varied parameter and its bounds (SI, as [`Parameter::set`] takes them).
#[derive(Debug, Clone)]
pub struct HandlingBound {
    /// The parameter.
    pub parameter: Parameter,
    /// Its least value.
    pub low: f64,
    /// Its greatest value.
    pub high: f64,
}

/// How the search runs.
#[derive(Debug, Clone, Copy)]
pub struct OptimalHandlingSettings {
    /// The design speed \[m/s\].
    pub speed: f64,
    /// The rider's neuromuscular filter.
    pub neuromuscular: Neuromuscular,
    /// The rules that set the gains of each candidate.
    pub rules: CrossoverRules,
    /// How many starts (the base bicycle, then Halton points in the box).
    pub starts: usize,
    /// The most Nelder–Mead iterations of each start.
    pub max_iterations: usize,
    /// A start has converged when the standard deviation of the simplex's costs falls below
    /// this.
    pub tolerance: f64,
}

impl OptimalHandlingSettings {
    /// At `speed`: the default neuromuscular filter and rules, 6 starts of at most 2000
    /// iterations each, tolerance 1e-10.
    pub fn at(speed: f64) -> Self {
        OptimalHandlingSettings {
            speed,
            neuromuscular: Neuromuscular::default(),
            rules: CrossoverRules::default(),
            starts: 6,
            max_iterations: 2000,
            tolerance: 1e-10,
        }
    }
}

/// One candidate bicycle judged.
#[derive(Debug, Clone)]
pub struct HandlingCandidate {
    /// The varied parameters' values (SI).
    pub values: Vec<f64>,
    /// The objective: the peak HQM when stable, else a penalty.
    pub cost: f64,
    /// The gains the rules give; `None` when the library refused the candidate.
    pub gains: Option<HumanGains>,
    /// The certified peak of |HQM|; `None` when refused.
    pub peak: Option<HandlingPeak>,
    /// The roll loop and the lateral closed loop are both stable.
    pub stable: bool,
    /// Why the library refused the candidate, if it did.
    pub refused: Option<String>,
}

/// One start's result.
#[derive(Debug, Clone)]
pub struct HandlingStart {
    /// Where it started (SI).
    pub start: Vec<f64>,
    /// The best candidate it found.
    pub best: HandlingCandidate,
    /// The objective evaluations it took.
    pub evaluations: usize,
    /// The simplex's costs agreed to the tolerance (else the iterations ran out).
    pub converged: bool,
}

/// The result of [`optimal_handling`].
#[derive(Debug, Clone)]
pub struct OptimalHandling {
    /// The varied parameters, in the order of the bounds.
    pub parameters: Vec<Parameter>,
    /// The base bicycle judged as it is (its values clamped into the bounds are the first
    /// start).
    pub base: HandlingCandidate,
    /// The best candidate over every start.
    pub best: HandlingCandidate,
    /// The best candidate's bicycle.
    pub bicycle: Bicycle,
    /// Every start's result, in order.
    pub starts: Vec<HandlingStart>,
}

impl OptimalHandling {
    /// Objective evaluations over every start.
    pub fn evaluations(&self) -> usize {
        self.starts.iter().map(|s| s.evaluations).sum()
    }
}

/// The value of `parameter` in `bike` (SI), or an error naming it when the bicycle's form lacks
/// it.
fn current_value(bike: &Bicycle, parameter: &Parameter) -> Result<f64> {
    parameter
        .get(&bike.description)
        .ok_or_else(|| Error::InvalidArgument {
            what: "parameter",
            rule: format!(
                "`{}` has no single value in this bicycle (not of its form, or its two \
                 wheels differ)",
                parameter.name()
            ),
        })
}

/// `base` with the parameters set to `values`.
fn with_values(base: &Bicycle, bounds: &[HandlingBound], values: &[f64]) -> Result<Bicycle> {
    let mut bike = base.clone();
    for (b, &x) in bounds.iter().zip(values) {
        if !b.parameter.set(&mut bike.description, x) {
            return Err(Error::InvalidArgument {
                what: "parameter",
                rule: format!(
                    "`{}` is not a parameter of this bicycle's form",
                    b.parameter.name()
                ),
            });
        }
    }
    Ok(bike)
}

/// Judges one candidate: its gains by the rules, its certified peak HQM, the stability of its
/// roll and lateral loops, and the cost the search minimizes (see the module documentation).
pub fn judge_handling(
    base: &Bicycle,
    bounds: &[HandlingBound],
    values: &[f64],
    settings: &OptimalHandlingSettings,
) -> HandlingCandidate {
    let refused = |error: Error| HandlingCandidate {
        values: values.to_vec(),
        cost: INFEASIBLE_PENALTY,
        gains: None,
        peak: None,
        stable: false,
        refused: Some(error.to_string()),
    };
    let judged = (|| -> Result<(HumanGains, HandlingPeak, bool, f64)> {
        let bike = with_values(base, bounds, values)?.benchmark()?;
        let gains = hess_gains(
            &bike,
            settings.speed,
            &settings.neuromuscular,
            &settings.rules,
        )?;
        let hqm = HandlingQuality::new(&bike, settings.speed, &gains, &settings.neuromuscular)?;
        let peak = hqm.peak()?;
        let controller = HumanController::new(Task::Lateral, gains, settings.neuromuscular)?;
        let closed = HumanLoop::new(&bike, settings.speed, &controller, &[])?;
        let eigenvalues = closed.eigenvalues()?;
        if eigenvalues
            .iter()
            .any(|z| !(z.re.is_finite() && z.im.is_finite()))
        {
            return Err(Error::NonFinite {
                context: "the lateral closed loop's eigenvalues".into(),
            });
        }
        let largest = eigenvalues
            .iter()
            .map(|z| z.re)
            .fold(f64::NEG_INFINITY, f64::max);
        Ok((gains, peak, hqm.is_stable() && largest < 0.0, largest))
    })();
    match judged {
        Err(e) => refused(e),
        Ok((gains, peak, stable, largest)) => {
            let cost = if stable {
                peak.magnitude
            } else {
                UNSTABLE_PENALTY + 100.0 * largest.max(0.0)
            };
            if !cost.is_finite() {
                return refused(Error::NonFinite {
                    context: "the peak handling quality metric".into(),
                });
            }
            HandlingCandidate {
                values: values.to_vec(),
                cost,
                gains: Some(gains),
                peak: Some(peak),
                stable,
                refused: None,
            }
        }
    }
}

/// The k-th point (k ≥ 1) of the Halton sequence in dimension `d` (bases the first primes).
fn halton(k: usize, d: usize) -> f64 {
    const PRIMES: [usize; MAX_HANDLING_PARAMETERS] =
        [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53];
    let base = PRIMES[d % PRIMES.len()];
    let (mut f, mut r, mut i) = (1.0, 0.0, k);
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r
}

struct Problem<'a> {
    base: &'a Bicycle,
    bounds: &'a [HandlingBound],
    settings: &'a OptimalHandlingSettings,
    stop: &'a AtomicBool,
    /// The evaluations of this start.
    evaluations: &'a AtomicUsize,
}

impl Problem<'_> {
    fn values(&self, z: &[f64]) -> Vec<f64> {
        self.bounds
            .iter()
            .zip(z)
            .map(|(b, z)| b.low + (b.high - b.low) * 0.5 * (1.0 + crate::math::sin(*z)))
            .collect()
    }

    fn unmapped(&self, x: &[f64]) -> Vec<f64> {
        self.bounds
            .iter()
            .zip(x)
            .map(|(b, &x)| {
                let u = if b.high > b.low {
                    ((x - b.low) / (b.high - b.low)).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                crate::math::asin(2.0 * u - 1.0)
            })
            .collect()
    }
}

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, z: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        // Never an error: argmin's Nelder–Mead unwraps the costs of its first simplex. A set
        // stop flag makes every cost the same constant, which ends the simplex at once (its
        // costs agree); the search then reports the stop.
        if self.stop.load(Ordering::Relaxed) {
            return Ok(INFEASIBLE_PENALTY);
        }
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        Ok(judge_handling(self.base, self.bounds, &self.values(z), self.settings).cost)
    }
}

fn stopped() -> Error {
    Error::InvalidArgument {
        what: "stopped",
        rule: "the search was stopped before it finished".into(),
    }
}

fn check(
    base: &Bicycle,
    bounds: &[HandlingBound],
    settings: &OptimalHandlingSettings,
) -> Result<()> {
    if bounds.is_empty() || bounds.len() > MAX_HANDLING_PARAMETERS {
        return Err(Error::InvalidArgument {
            what: "parameters",
            rule: format!(
                "vary between 1 and {MAX_HANDLING_PARAMETERS} parameters, got {}",
                bounds.len()
            ),
        });
    }
    for (i, b) in bounds.iter().enumerate() {
        if matches!(b.parameter, Parameter::Speed) {
            return Err(Error::InvalidArgument {
                what: "parameters",
                rule: "the speed is the design speed, not a design parameter".into(),
            });
        }
        if bounds[..i]
            .iter()
            .any(|o| o.parameter.name() == b.parameter.name())
        {
            return Err(Error::InvalidArgument {
                what: "parameters",
                rule: format!("`{}` is varied twice", b.parameter.name()),
            });
        }
        if !(b.low.is_finite() && b.high.is_finite() && b.low <= b.high) {
            return Err(Error::InvalidParameter {
                field: b.parameter.name().into(),
                value: if b.low.is_finite() { b.high } else { b.low },
                rule: format!(
                    "its bounds must be finite with low ≤ high, got {} to {}",
                    short_number(b.low),
                    short_number(b.high)
                ),
            });
        }
        current_value(base, &b.parameter)?;
    }
    if !(settings.speed.is_finite() && settings.speed > 0.0) {
        return Err(Error::InvalidArgument {
            what: "speed",
            rule: format!(
                "the design speed must be positive and finite, got {}",
                short_number(settings.speed)
            ),
        });
    }
    if settings.starts == 0 || settings.starts > MAX_HANDLING_STARTS {
        return Err(Error::LimitExceeded {
            what: "starts",
            rule: format!(
                "between 1 and {MAX_HANDLING_STARTS}, got {}",
                settings.starts
            ),
        });
    }
    if settings.max_iterations == 0 || settings.max_iterations > MAX_HANDLING_ITERATIONS {
        return Err(Error::LimitExceeded {
            what: "iterations",
            rule: format!(
                "between 1 and {MAX_HANDLING_ITERATIONS} per start, got {}",
                settings.max_iterations
            ),
        });
    }
    if !(settings.tolerance.is_finite() && settings.tolerance >= 0.0) {
        return Err(Error::InvalidArgument {
            what: "tolerance",
            rule: format!(
                "must be finite and not negative, got {}",
                short_number(settings.tolerance)
            ),
        });
    }
    Ok(())
}

/// One start of the search from `x0` (SI).
fn run_start(
    base: &Bicycle,
    bounds: &[HandlingBound],
    settings: &OptimalHandlingSettings,
    stop: &AtomicBool,
    x0: Vec<f64>,
) -> Result<HandlingStart> {
    let evaluations = AtomicUsize::new(0);
    let problem = Problem {
        base,
        bounds,
        settings,
        stop,
        evaluations: &evaluations,
    };
    let n = bounds.len();
    let z0 = problem.unmapped(&x0);
    // The simplex: z0 and one step of 0.5 rad along each variable (towards the box's middle
    // when z0 sits at a bound, where the map is flat).
    let mut simplex = vec![z0.clone()];
    for i in 0..n {
        let mut z = z0.clone();
        z[i] += if z0[i] > 0.0 { -0.5 } else { 0.5 };
        simplex.push(z);
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(problem.settings.tolerance)
        .map_err(|e| Error::InvalidArgument {
            what: "tolerance",
            rule: e.to_string(),
        })?;
    let iterations = settings.max_iterations as u64;
    let outcome = Executor::new(problem_ref(&problem), solver)
        .configure(|state| state.max_iters(iterations))
        .run();
    let result = match outcome {
        Ok(r) => r,
        Err(_) if problem.stop.load(Ordering::Relaxed) => return Err(stopped()),
        Err(e) => {
            return Err(Error::InvalidArgument {
                what: "search",
                rule: e.to_string(),
            });
        }
    };
    if problem.stop.load(Ordering::Relaxed) {
        return Err(stopped());
    }
    let state = result.state();
    let converged = matches!(
        state.get_termination_reason(),
        Some(TerminationReason::SolverConverged)
    );
    let best_z = state.get_best_param().cloned().unwrap_or(z0);
    let best = judge_handling(
        problem.base,
        problem.bounds,
        &problem.values(&best_z),
        problem.settings,
    );
    Ok(HandlingStart {
        start: x0,
        best,
        evaluations: evaluations.load(Ordering::Relaxed),
        converged,
    })
}

/// The executor takes the problem by value: a copy of the references.
fn problem_ref<'a>(p: &Problem<'a>) -> Problem<'a> {
    Problem {
        base: p.base,
        bounds: p.bounds,
        settings: p.settings,
        stop: p.stop,
        evaluations: p.evaluations,
    }
}

/// Minimizes the peak HQM of `base` at `settings.speed` over the parameters of `bounds` (see
/// the module documentation), the starts run in parallel. `stop` set by another thread ends
/// the search with an error (checked at every evaluation). Errors name the parameter, its
/// bounds, `speed`, `starts`, `evaluations` or `tolerance`.
///
/// A local search from several starts: the best of them, not a certified global minimum.
pub fn optimal_handling(
    base: &Bicycle,
    bounds: &[HandlingBound],
    settings: &OptimalHandlingSettings,
    stop: &AtomicBool,
) -> Result<OptimalHandling> {
    check(base, bounds, settings)?;
    let own: Vec<f64> = bounds
        .iter()
        .map(|b| current_value(base, &b.parameter))
        .collect::<Result<_>>()?;
    let base_candidate = judge_handling(base, bounds, &own, settings);
    let mut starts = vec![
        bounds
            .iter()
            .zip(&own)
            .map(|(b, &x)| x.clamp(b.low, b.high))
            .collect::<Vec<f64>>(),
    ];
    for k in 1..settings.starts {
        starts.push(
            bounds
                .iter()
                .enumerate()
                .map(|(d, b)| b.low + (b.high - b.low) * halton(k, d))
                .collect(),
        );
    }
    let results = starts
        .into_par_iter()
        .map(|x0| run_start(base, bounds, settings, stop, x0))
        .collect::<Result<Vec<HandlingStart>>>()?;
    if stop.load(Ordering::Relaxed) {
        return Err(stopped());
    }
    // Among the starts only: the base may lie outside the bounds, and the first start (the
    // base clamped into them) keeps its start whenever nothing better was found.
    let best = results
        .iter()
        .map(|s| &s.best)
        .min_by(|a, b| a.cost.total_cmp(&b.cost))
        .cloned()
        .unwrap_or_else(|| base_candidate.clone());
    let bicycle = with_values(base, bounds, &best.values)?;
    Ok(OptimalHandling {
        parameters: bounds.iter().map(|b| b.parameter).collect(),
        base: base_candidate,
        best,
        bicycle,
        starts: results,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;

    fn bound(bike: &Bicycle, name: &str, low: f64, high: f64) -> HandlingBound {
        HandlingBound {
            parameter: Parameter::find(name, bike).unwrap(),
            low,
            high,
        }
    }

    #[test]
    fn halton_points_lie_in_the_unit_interval_and_differ() {
        let pts: Vec<f64> = (1..50).map(|k| halton(k, 1)).collect();
        assert!(pts.iter().all(|&x| (0.0..1.0).contains(&x)));
        assert_eq!(
            (halton(1, 0), halton(2, 0), halton(3, 1)),
            (0.5, 0.25, 1.0 / 9.0)
        );
    }

    #[test]
    fn the_search_lowers_the_benchmarks_peak_over_trail_and_head_angle() {
        let bike = presets::find("benchmark").unwrap().bicycle();
        let bounds = [
            bound(&bike, "trail", 0.0, 0.2),
            bound(&bike, "head_angle", 60f64.to_radians(), 85f64.to_radians()),
        ];
        let mut settings = OptimalHandlingSettings::at(5.0);
        settings.starts = 3;
        let stop = AtomicBool::new(false);
        let result = optimal_handling(&bike, &bounds, &settings, &stop).unwrap();
        assert!(result.base.stable);
        assert!(result.best.stable);
        assert!(result.best.cost <= result.base.cost);
        assert!(result.best.cost < 0.9 * result.base.cost, "{result:?}");
        // Every value in its bounds, and the bicycle carries them.
        for (b, &x) in bounds.iter().zip(&result.best.values) {
            assert!((b.low..=b.high).contains(&x));
            assert_eq!(b.parameter.get(&result.bicycle.description), Some(x));
        }
        // The reported cost is the candidate's certified peak, judged again.
        let again = judge_handling(&bike, &bounds, &result.best.values, &settings);
        assert_eq!(again.cost, result.best.cost);
        // The simplex's first n + 1 points, then at most n + 2 an iteration.
        assert!(result.evaluations() <= settings.starts * (3 + 4 * settings.max_iterations));
    }

    #[test]
    fn bad_searches_are_refused_naming_what_is_wrong() {
        let bike = presets::find("benchmark").unwrap().bicycle();
        let stop = AtomicBool::new(false);
        let settings = OptimalHandlingSettings::at(5.0);
        let message = |bounds: &[HandlingBound], s: &OptimalHandlingSettings| {
            optimal_handling(&bike, bounds, s, &stop)
                .unwrap_err()
                .to_string()
        };
        assert!(message(&[], &settings).contains("parameters"));
        let trail = bound(&bike, "trail", 0.1, 0.0);
        assert!(message(std::slice::from_ref(&trail), &settings).contains("c"));
        let twice = [bound(&bike, "trail", 0.0, 0.1), bound(&bike, "c", 0.0, 0.1)];
        assert!(message(&twice, &settings).contains("twice"));
        let ok = [bound(&bike, "trail", 0.0, 0.1)];
        let mut s = settings;
        s.speed = -1.0;
        assert!(message(&ok, &s).contains("speed"));
        let mut s = settings;
        s.starts = 0;
        assert!(message(&ok, &s).contains("starts"));
        let mut s = settings;
        s.max_iterations = usize::MAX;
        assert!(message(&ok, &s).contains("iterations"));
        let speed = [HandlingBound {
            parameter: Parameter::Speed,
            low: 1.0,
            high: 2.0,
        }];
        assert!(message(&speed, &settings).contains("design speed"));
    }

    #[test]
    fn the_best_design_lies_within_the_bounds_even_when_the_bicycle_does_not() {
        let bike = presets::find("benchmark").unwrap().bicycle();
        // The benchmark's trail, 0.08 m, is outside [0.1, 0.2].
        let bounds = [bound(&bike, "trail", 0.1, 0.2)];
        let mut settings = OptimalHandlingSettings::at(5.0);
        settings.starts = 2;
        let stop = AtomicBool::new(false);
        let result = optimal_handling(&bike, &bounds, &settings, &stop).unwrap();
        assert_eq!(result.base.values, vec![0.08]);
        assert_eq!(result.starts[0].start, vec![0.1]);
        assert!(
            (0.1..=0.2).contains(&result.best.values[0]),
            "{:?}",
            result.best
        );
    }

    #[test]
    fn a_set_stop_flag_ends_the_search() {
        let bike = presets::find("benchmark").unwrap().bicycle();
        let stop = AtomicBool::new(true);
        let bounds = [bound(&bike, "trail", 0.0, 0.2)];
        let error =
            optimal_handling(&bike, &bounds, &OptimalHandlingSettings::at(5.0), &stop).unwrap_err();
        assert!(error.to_string().contains("stopped"));
    }
}
