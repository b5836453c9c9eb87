//! HumanControl's lane change (`lane_change.m`, as `generate_data.m` sets it up), ridden by
//! Hess's controller on the linear bicycle (exactly) and on the non-linear one.
//!
//! # The path
//!
//! The lateral position of the lane against the distance x travelled, piecewise linear: zero up
//! to `start` (35 m), a ramp of gradient `slope` (0.2) up to `width` (2 m, right positive),
//! then for the single lane change `width` for ever; for the double one `width` until a ramp
//! back down ends at `start + lane_length` (60 m), then zero. HumanControl samples it at 501
//! points 0.5 m apart over `path_length` (250 m); its corners (35, 45, 85 and 95 m) are among
//! them, so the sampled path is this one. At a speed v the rider meets the path as the signal
//! r(t) = y(v t), until t = path_length / v, the stop time.
//!
//! # How the rider reads it
//!
//! As HumanControl's Simulink model does: the command to the lateral loop is r(t) through the
//! path filter ω_p²/(s² + 2ω_p s + ω_p²), ω_p = 2.4 rad/s (critically damped), and the path the
//! bicycle is judged against is r delayed by the preview time τ = 2.75 s (the rider looks that
//! far ahead: the road's lane change starts 35 m + v τ from the start). Both hold at every
//! speed; only the time scale x/v changes with it. The loop's error is y_c − y_Q, the command
//! less the front contact's lateral position.
//!
//! # Exact on the linear model
//!
//! The closed loop ([`HumanLoop`], lateral task) with the path filter's two states appended is
//! a linear system driven by the piecewise-linear r(t): its response is exact, through the same
//! Van Loan exponential as [`LinearSystem::response`](super::LinearSystem::response).
//!
//! # The same rider on the non-linear bicycle
//!
//! The neuromuscular filter's states (T_δ, Ṫ_δ) and the path filter's are integrated together
//! with the non-linear bicycle's; the rider measures ψ, φ, δ, φ̇ and y_Q from the non-linear
//! state (the front contact's lateral position from the contact point itself), and the steer
//! torque is T_δ. Mirroring the path left for right mirrors both motions, so lean, steer, yaw,
//! y_Q and the torque are odd in the path's amplitude, and the models differ by O(a³): the
//! tests fit the order.

use nalgebra::DMatrix;

use super::human::{HumanController, HumanLoop, LoopState, Task};
use super::response::{InputSignal, exact_response};
use super::system::{Output, StateVariable};
use crate::error::{Error, Result, short_number};
use crate::nonlinear::carried::{CARRIED, simulate_carrying};
use crate::nonlinear::{DEFAULT_FALL_ANGLE, InitialConditions, Inputs, Model, Outcome};
use crate::parameters::BenchmarkParameters;

/// HumanControl's path filter natural frequency ω_p \[rad/s\] (`generate_data.m`).
pub(crate) const PATH_FILTER_FREQUENCY: f64 = 2.4;
/// HumanControl's preview time τ for steer control \[s\] (`generate_data.m`).
pub(crate) const PREVIEW_TIME: f64 = 2.75;
/// The most sample intervals one lane change may have.
pub const MAX_LANE_CHANGE_SAMPLES: usize = 100_000;

/// Single or double lane change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LaneKind {
    /// Over to `width` and stay there.
    Single,
    /// Over to `width` and back within `lane_length`.
    Double,
}

impl LaneKind {
    /// `single` or `double`, as HumanControl names them.
    pub fn name(self) -> &'static str {
        match self {
            LaneKind::Single => "single",
            LaneKind::Double => "double",
        }
    }

    /// The kind of a name (`single`, `double`).
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "single" => Ok(LaneKind::Single),
            "double" => Ok(LaneKind::Double),
            other => Err(Error::InvalidArgument {
                what: "lane",
                rule: format!("`{other}` is not a lane change: use single or double"),
            }),
        }
    }
}

/// A lane change path and how the rider reads it (see the module documentation); SI units.
///
/// ```
/// use whipple::advanced::control::{LaneChange, LaneKind};
/// let lane = LaneChange::humancontrol(LaneKind::Double);
/// assert_eq!((lane.lateral(40.0), lane.lateral(60.0), lane.lateral(90.0), lane.lateral(100.0)), (1.0, 2.0, 1.0, 0.0));
/// assert_eq!(lane.duration(5.0)?, 50.0);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneChange {
    /// Single or double.
    pub kind: LaneKind,
    /// Where the first ramp starts \[m\], ≥ 0.
    pub start: f64,
    /// The lateral offset of the lane \[m\], right positive, non-zero.
    pub width: f64,
    /// The ramps' gradient |dy/dx|, positive: each ramp is |width| / slope long.
    pub slope: f64,
    /// Double lane change: from the start of the first ramp to the end of the second \[m\], at
    /// least two ramps long.
    pub lane_length: f64,
    /// The distance simulated \[m\], positive.
    pub path_length: f64,
    /// The number of sample intervals over `path_length`, 1 to [`MAX_LANE_CHANGE_SAMPLES`].
    pub samples: usize,
    /// τ: how far ahead in time the rider reads the path \[s\], ≥ 0.
    pub preview: f64,
    /// ω_p: the path filter's natural frequency \[rad/s\], positive.
    pub path_filter_frequency: f64,
}

impl LaneChange {
    /// HumanControl's lane change as `generate_data.m` asks `lane_change.m` for it: start
    /// 35 m, width 2 m, slope 0.2, lane 60 m, path 250 m in 500 intervals; preview 2.75 s,
    /// path filter 2.4 rad/s.
    pub fn humancontrol(kind: LaneKind) -> Self {
        LaneChange {
            kind,
            start: 35.0,
            width: 2.0,
            slope: 0.2,
            lane_length: 60.0,
            path_length: 250.0,
            samples: 500,
            preview: PREVIEW_TIME,
            path_filter_frequency: PATH_FILTER_FREQUENCY,
        }
    }

    /// The same path with its lateral positions multiplied by `factor` (width and slope
    /// together, the corners where they were).
    pub fn scaled(&self, factor: f64) -> Self {
        LaneChange {
            width: self.width * factor,
            slope: self.slope * factor.abs(),
            ..*self
        }
    }

    /// Checks every field; errors name it (`width`, `lane length`, …).
    pub fn check(&self) -> Result<()> {
        let bad = |field: &str, value: f64, rule: &str| {
            Err(Error::InvalidParameter {
                field: field.into(),
                value,
                rule: rule.into(),
            })
        };
        let checks = [
            ("start", self.start, self.start >= 0.0, "must be >= 0 m"),
            ("width", self.width, self.width != 0.0, "must be non-zero"),
            ("slope", self.slope, self.slope > 0.0, "must be positive"),
            (
                "path length",
                self.path_length,
                self.path_length > 0.0,
                "must be positive",
            ),
            (
                "preview",
                self.preview,
                self.preview >= 0.0,
                "must be >= 0 s",
            ),
            (
                "path filter frequency",
                self.path_filter_frequency,
                self.path_filter_frequency > 0.0,
                "must be positive",
            ),
        ];
        for (field, value, ok, rule) in checks {
            if !value.is_finite() {
                return bad(field, value, "must be finite");
            }
            if !ok {
                return bad(field, value, rule);
            }
        }
        let ramp = self.ramp_length();
        if !ramp.is_finite() {
            return bad(
                "slope",
                self.slope,
                "the ramp |width| / slope must be finite",
            );
        }
        if self.kind == LaneKind::Double
            && (self.lane_length.is_nan() || self.lane_length < 2.0 * ramp)
        {
            return Err(Error::InvalidParameter {
                field: "lane length".into(),
                value: self.lane_length,
                rule: format!(
                    "a double lane change needs room for both ramps: at least 2 |width| / slope = {} m",
                    short_number(2.0 * ramp)
                ),
            });
        }
        if !(1..=MAX_LANE_CHANGE_SAMPLES).contains(&self.samples) {
            return Err(Error::LimitExceeded {
                what: "samples",
                rule: format!(
                    "1 to {MAX_LANE_CHANGE_SAMPLES} sample intervals, got {}",
                    self.samples
                ),
            });
        }
        Ok(())
    }

    /// The length of one ramp, |width| / slope \[m\].
    pub fn ramp_length(&self) -> f64 {
        self.width.abs() / self.slope
    }

    /// The corners of the path: (x \[m\], y \[m\]) from x = 0, the path constant after the last.
    pub fn corners(&self) -> Vec<(f64, f64)> {
        let ramp = self.ramp_length();
        let mut corners = vec![
            (0.0, 0.0),
            (self.start, 0.0),
            (self.start + ramp, self.width),
        ];
        if self.kind == LaneKind::Double {
            let end = self.start + self.lane_length;
            corners.push((end - ramp, self.width));
            corners.push((end, 0.0));
        }
        corners.dedup_by(|b, a| b.0 == a.0);
        corners
    }

    /// The path's lateral position y(x) at a distance x \[m\] (zero before x = 0).
    pub fn lateral(&self, x: f64) -> f64 {
        let ramp = self.ramp_length();
        let up = self.start + ramp;
        if x <= self.start {
            return 0.0;
        }
        if x <= up {
            return self.width * ((x - self.start) / ramp);
        }
        match self.kind {
            LaneKind::Single => self.width,
            LaneKind::Double => {
                let end = self.start + self.lane_length;
                if x <= end - ramp {
                    self.width
                } else if x <= end {
                    self.width * ((end - x) / ramp)
                } else {
                    0.0
                }
            }
        }
    }

    /// The stop time, `path_length` / v \[s\]; errors name `speed` (positive and finite).
    pub fn duration(&self, speed: f64) -> Result<f64> {
        if !(speed.is_finite() && speed > 0.0) {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!(
                    "a lane change needs a positive finite speed, got {}",
                    short_number(speed)
                ),
            });
        }
        Ok(self.path_length / speed)
    }

    /// The sample times at `speed`: the path's sample points x_k = k · path_length / samples
    /// over v \[s\].
    pub fn times(&self, speed: f64) -> Result<Vec<f64>> {
        self.duration(speed)?;
        let dx = self.path_length / self.samples as f64;
        Ok((0..=self.samples)
            .map(|k| (k as f64 * dx) / speed)
            .collect())
    }

    /// r(t) = y(v t): the path as the rider meets it at `speed`, before the path filter.
    pub fn signal(&self, speed: f64) -> Result<InputSignal> {
        self.duration(speed)?;
        let (knots, values) = self
            .corners()
            .into_iter()
            .map(|(x, y)| (x / speed, y))
            .unzip();
        InputSignal::piecewise_linear(knots, values)
    }

    /// The road at time t: the path delayed by the preview, y(v (t − τ)) \[m\].
    pub fn road(&self, speed: f64, t: f64) -> f64 {
        self.lateral(speed * (t - self.preview))
    }
}

/// A lane change ridden: the path, the command and what the bicycle did, at the path's sample
/// times.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LaneChangeRun {
    /// The sample times \[s\].
    pub times: Vec<f64>,
    /// The road's lateral position, the path delayed by the preview \[m\].
    pub path: Vec<f64>,
    /// y_c: the command into the lateral loop, the path through the path filter \[m\].
    pub command: Vec<f64>,
    /// The front contact's distance along x from its start \[m\] (the linear model: v t).
    pub front_x: Vec<f64>,
    /// y_Q: the front contact's lateral position \[m\].
    pub front_y: Vec<f64>,
    /// y_c − y_Q: the lateral loop's error \[m\].
    pub error: Vec<f64>,
    /// φ: lean \[rad\].
    pub lean: Vec<f64>,
    /// δ: steer \[rad\].
    pub steer: Vec<f64>,
    /// ψ: yaw \[rad\].
    pub yaw: Vec<f64>,
    /// T_δ: the rider's steer torque \[N m\].
    pub steer_torque: Vec<f64>,
}

impl LaneChangeRun {
    /// The quantities by name, in the order of the fields.
    pub fn columns(&self) -> [(&'static str, &[f64]); 10] {
        [
            ("time", &self.times),
            ("path", &self.path),
            ("command", &self.command),
            ("front_x", &self.front_x),
            ("front_y", &self.front_y),
            ("error", &self.error),
            ("lean", &self.lean),
            ("steer", &self.steer),
            ("yaw", &self.yaw),
            ("steer_torque", &self.steer_torque),
        ]
    }

    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        lane: &LaneChange,
        speed: f64,
        t: f64,
        command: f64,
        front_x: f64,
        front_y: f64,
        [lean, steer, yaw, steer_torque]: [f64; 4],
    ) {
        self.times.push(t);
        self.path.push(lane.road(speed, t));
        self.command.push(command);
        self.front_x.push(front_x);
        self.front_y.push(front_y);
        self.error.push(command - front_y);
        self.lean.push(lean);
        self.steer.push(steer);
        self.yaw.push(yaw);
        self.steer_torque.push(steer_torque);
    }
}

/// Checks what both models need: the lateral task and the lane change.
fn check_request(controller: &HumanController, lane: &LaneChange, speed: f64) -> Result<()> {
    if controller.task() != Task::Lateral {
        return Err(Error::InvalidArgument {
            what: "task",
            rule: format!(
                "a lane change is followed by the lateral task, not the {} task",
                controller.task()
            ),
        });
    }
    lane.check()?;
    lane.duration(speed)?;
    Ok(())
}

/// The lane change on the linear bicycle at `speed`, ridden by `controller` (the lateral task):
/// the closed loop with the path filter, exactly (see the module documentation). Errors name
/// `task`, `speed` or the lane change's field, or come from [`HumanLoop::new`].
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::{HumanController, HumanGains, LaneChange, LaneKind, Neuromuscular, Task, lane_change_linear};
/// let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
/// let rider = HumanController::new(Task::Lateral, gains, Neuromuscular::default())?;
/// let lane = LaneChange::humancontrol(LaneKind::Double);
/// let run = lane_change_linear(&BenchmarkParameters::meijaard2007(), 5.0, &rider, &lane)?;
/// assert_eq!(run.times.len(), 501);
/// // Two metres over and back: the front contact keeps within 0.34 m of the road (the rider's
/// // error, against the path previewed 2.75 s ahead, is larger by design: 1.48 m).
/// let road = run.path.iter().zip(&run.front_y).fold(0.0_f64, |m, (p, y)| m.max((p - y).abs()));
/// assert!(road < 0.34, "{road}");
/// assert!(run.front_y.iter().any(|&y| y > 1.95));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn lane_change_linear(
    bike: &BenchmarkParameters,
    speed: f64,
    controller: &HumanController,
    lane: &LaneChange,
) -> Result<LaneChangeRun> {
    check_request(controller, lane, speed)?;
    let ridden = HumanLoop::new(bike, speed, controller, &[])?;
    let open = ridden.open_loop();
    let n = ridden.states().len();
    let nb = open.states().len();
    let total = n + 2;
    let w = lane.path_filter_frequency;
    // The closed loop, its command now the path filter's first state.
    let mut a = DMatrix::zeros(total, total);
    a.view_mut((0, 0), (n, n)).copy_from(ridden.a());
    a.view_mut((0, n), (n, 1)).copy_from(&ridden.b().column(0));
    a[(n, n + 1)] = 1.0;
    a[(n + 1, n)] = -w * w;
    a[(n + 1, n + 1)] = -2.0 * w;
    let mut b = DMatrix::zeros(total, 1);
    b[(n + 1, 0)] = w * w;
    let state = |s: LoopState| {
        ridden
            .states()
            .iter()
            .position(|x| *x == s)
            .ok_or_else(|| Error::InvalidArgument {
                what: "states",
                rule: format!("the ridden bicycle lacks {}", s.name()),
            })
    };
    let front = open
        .outputs()
        .iter()
        .position(|o| *o == Output::FrontContactY)
        .ok_or_else(|| Error::InvalidArgument {
            what: "outputs",
            rule: "the ridden bicycle lacks the front contact's lateral position".into(),
        })?;
    // Outputs: y_c, y_Q, φ, δ, ψ, T_δ.
    let mut c = DMatrix::zeros(6, total);
    c[(0, n)] = 1.0;
    c.view_mut((1, 0), (1, nb)).copy_from(&open.c().row(front));
    c[(2, state(LoopState::Bicycle(StateVariable::Lean))?)] = 1.0;
    c[(3, state(LoopState::Bicycle(StateVariable::Steer))?)] = 1.0;
    c[(4, state(LoopState::Bicycle(StateVariable::Yaw))?)] = 1.0;
    c[(5, state(LoopState::SteerTorque)?)] = 1.0;
    let d = DMatrix::zeros(6, 1);
    let times = lane.times(speed)?;
    let (_, y) = exact_response(
        (&a, &b, &c, &d),
        &vec![0.0; total],
        &[lane.signal(speed)?],
        &times,
    )?;
    let mut run = LaneChangeRun::default();
    for (k, &t) in times.iter().enumerate() {
        run.push(
            lane,
            speed,
            t,
            y[(k, 0)],
            speed * t,
            y[(k, 1)],
            [y[(k, 2)], y[(k, 3)], y[(k, 4)], y[(k, 5)]],
        );
    }
    Ok(run)
}

/// The lane change on the non-linear bicycle from upright straight running at `speed`, ridden
/// by the same controller: its two states and the path filter's integrated with the bicycle's
/// (Dormand–Prince 5(4) at relative tolerance `rtol`, absolute `rtol`·1e-2, projected onto the
/// constraints after every step, from sample to sample and corner to corner). Errors as
/// [`lane_change_linear`], and a run that does not complete (the bicycle fell: `lane change`,
/// with the outcome).
pub fn lane_change_nonlinear(
    bike: &BenchmarkParameters,
    speed: f64,
    controller: &HumanController,
    lane: &LaneChange,
    rtol: f64,
) -> Result<LaneChangeRun> {
    check_request(controller, lane, speed)?;
    let model = Model::new(bike)?;
    let initial = model.initial_state(&InitialConditions::upright(speed))?;
    let times = lane.times(speed)?;
    let t_end = times[times.len() - 1];
    let corners: Vec<f64> = lane
        .corners()
        .iter()
        .map(|(x, _)| x / speed)
        .filter(|t| *t > 0.0 && *t < t_end)
        .collect();
    let mut ends: Vec<f64> = times[1..].iter().copied().chain(corners).collect();
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    let signal = lane.signal(speed)?;
    let weights = controller.weights();
    let reference = controller.reference_weight();
    let k_delta = controller.gains().k_delta;
    let (omega, zeta) = (
        controller.neuromuscular().frequency,
        controller.neuromuscular().damping,
    );
    let w = lane.path_filter_frequency;
    // Carried: T_δ, Ṫ_δ, y_c, ẏ_c.
    let rhs = |t: f64, view: &crate::nonlinear::StateView, c: &[f64; CARRIED]| {
        let [torque, torque_rate, command, command_rate] = *c;
        let measured = [
            view.yaw,
            view.lean,
            view.steer,
            view.lean_rate,
            view.front_contact_y,
        ];
        let feedback: f64 = weights.iter().zip(measured).map(|(w, y)| w * y).sum();
        let torque_acceleration = -omega * omega * torque - 2.0 * zeta * omega * torque_rate
            + omega * omega * k_delta * (reference * command - feedback);
        let command_acceleration =
            -w * w * command - 2.0 * w * command_rate + w * w * signal.value(t);
        (
            [
                torque_rate,
                torque_acceleration,
                command_rate,
                command_acceleration,
            ],
            Inputs {
                steer_torque: torque,
                lean_torque: 0.0,
            },
        )
    };
    let simulated = simulate_carrying(
        &model,
        initial,
        [0.0; CARRIED],
        rhs,
        &ends,
        rtol,
        DEFAULT_FALL_ANGLE,
    )?;
    if simulated.outcome != Outcome::Completed {
        return Err(Error::InvalidArgument {
            what: "lane change",
            rule: format!(
                "the non-linear bicycle did not complete it: {}",
                simulated.outcome
            ),
        });
    }
    let x0 = simulated.views[0].front_contact_x;
    let mut run = LaneChangeRun::default();
    // The break points reached, t = 0 first: keep those at the sample times.
    let reached = std::iter::once(0.0).chain(ends.iter().copied());
    let mut next = 0;
    for (k, t) in reached.enumerate() {
        if times.get(next) != Some(&t) {
            continue;
        }
        next += 1;
        let (view, c) = (&simulated.views[k], &simulated.carried[k]);
        run.push(
            lane,
            speed,
            t,
            c[2],
            view.front_contact_x - x0,
            view.front_contact_y,
            [view.lean, view.steer, view.yaw, c[0]],
        );
    }
    Ok(run)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::{HumanGains, Neuromuscular};

    /// HumanControl's benchmark gains at 5 m/s (`gains/BenchmarkSteerGains.txt`, MIT licence).
    fn rider() -> HumanController {
        let gains = HumanGains::from_array([46.5457, -0.0522, 12.6611, 0.1849, 0.0959]);
        HumanController::new(Task::Lateral, gains, Neuromuscular::default()).unwrap()
    }

    /// `lane_change.m` transcribed on its samples: the lateral position at x_k.
    fn sampled(kind: LaneKind, x: f64) -> f64 {
        let (start, width, slope, lane) = (35.0, 2.0, 0.2, 60.0);
        let end_of_slope = width / slope + start;
        if x > start && x <= end_of_slope {
            return slope * (x - start);
        }
        if x <= start {
            return 0.0;
        }
        match kind {
            LaneKind::Single => width,
            LaneKind::Double => {
                let start_of_slope = start + lane - width / slope;
                if x > end_of_slope && x <= start_of_slope {
                    width
                } else if x > start_of_slope && x <= start + lane {
                    slope * (start + lane - x)
                } else {
                    0.0
                }
            }
        }
    }

    #[test]
    fn the_path_is_humancontrols_at_its_samples_and_between_them() {
        for kind in [LaneKind::Single, LaneKind::Double] {
            let lane = LaneChange::humancontrol(kind);
            lane.check().unwrap();
            let times = lane.times(5.0).unwrap();
            assert_eq!(times.len(), 501);
            assert_eq!(times[500], 50.0);
            let signal = lane.signal(5.0).unwrap();
            for (k, t) in times.iter().enumerate() {
                let x = 0.5 * k as f64;
                let expected = sampled(kind, x);
                assert!(
                    (lane.lateral(x) - expected).abs() < 1e-14,
                    "{kind:?} at {x} m"
                );
                assert!(
                    (signal.value(*t) - expected).abs() < 1e-14,
                    "{kind:?} at {t} s"
                );
                // The road: the path 2.75 s later.
                assert!((lane.road(5.0, t + 2.75) - expected).abs() < 1e-14);
            }
        }
        let double = LaneChange::humancontrol(LaneKind::Double);
        let corners: Vec<f64> = double.corners().iter().map(|c| c.0).collect();
        assert_eq!(corners, [0.0, 35.0, 45.0, 85.0, 95.0]);
        // Scaling moves no corner.
        let small = double.scaled(-0.1);
        assert_eq!(
            small.corners().iter().map(|c| c.0).collect::<Vec<_>>(),
            corners
        );
        assert!((small.lateral(60.0) + 0.2).abs() < 1e-15);
    }

    #[test]
    fn a_single_lane_change_ends_in_the_new_lane() {
        let lane = LaneChange::humancontrol(LaneKind::Single);
        let bike = BenchmarkParameters::meijaard2007();
        let run = lane_change_linear(&bike, 5.0, &rider(), &lane).unwrap();
        let last = run.times.len() - 1;
        // The integrators in the loop: at 50 s (40 s after the ramp) command, y_Q and the
        // road all sit at 2 m, the bicycle upright and straight.
        assert!(
            (run.command[last] - 2.0).abs() < 1e-9,
            "{}",
            run.command[last]
        );
        assert!(
            (run.front_y[last] - 2.0).abs() < 1e-4,
            "{}",
            run.front_y[last]
        );
        assert_eq!(run.path[last], 2.0);
        assert!(run.lean[last].abs() < 1e-4 && run.yaw[last].abs() < 1e-4);
        // Before the ramp reaches the rider nothing moves.
        let k = run.times.iter().position(|t| *t >= 6.9).unwrap();
        assert_eq!(run.front_y[k], 0.0);
        // Going right, the bicycle leans right (positive).
        let peak = run.lean.iter().fold(0.0_f64, |m, x| m.max(*x));
        assert!(peak > 0.01, "{peak}");
    }

    /// The order p of a ≈ C aᵖ, by least squares on the logarithms.
    fn order(amplitudes: &[f64], differences: &[f64]) -> f64 {
        let n = amplitudes.len() as f64;
        let (x, y): (Vec<f64>, Vec<f64>) = amplitudes
            .iter()
            .zip(differences)
            .map(|(a, d)| (crate::math::ln(*a), crate::math::ln(*d)))
            .unzip();
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
        let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
        sxy / sxx
    }

    fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
    }

    #[test]
    fn linear_and_nonlinear_lane_changes_differ_by_the_amplitude_cubed() {
        let bike = BenchmarkParameters::meijaard2007();
        // The double lane change over 120 m: 95 m of path and the preview's 14 m after it.
        let lane = LaneChange {
            path_length: 120.0,
            samples: 240,
            ..LaneChange::humancontrol(LaneKind::Double)
        };
        let amplitudes = [0.4, 0.2, 0.1, 0.05];
        let mut front = Vec::new();
        let mut lean = Vec::new();
        let mut torque = Vec::new();
        for a in amplitudes {
            let scaled = lane.scaled(a);
            let linear = lane_change_linear(&bike, 5.0, &rider(), &scaled).unwrap();
            let nonlinear = lane_change_nonlinear(&bike, 5.0, &rider(), &scaled, 1e-11).unwrap();
            assert_eq!(linear.times, nonlinear.times);
            front.push(largest_difference(&linear.front_y, &nonlinear.front_y));
            lean.push(largest_difference(&linear.lean, &nonlinear.lean));
            torque.push(largest_difference(
                &linear.steer_torque,
                &nonlinear.steer_torque,
            ));
            // The command is the same signal through the same filter on both.
            assert!(largest_difference(&linear.command, &nonlinear.command) < 1e-9 * a);
            eprintln!(
                "amplitude {a}: width {} m, max |y_Q| {:.4e} m, Δy_Q {:.4e} m, Δφ {:.4e} rad, ΔT_δ {:.4e} N m",
                scaled.width,
                linear.front_y.iter().fold(0.0_f64, |m, x| m.max(x.abs())),
                front.last().unwrap(),
                lean.last().unwrap(),
                torque.last().unwrap()
            );
        }
        let orders = [
            order(&amplitudes, &front),
            order(&amplitudes, &lean),
            order(&amplitudes, &torque),
        ];
        eprintln!("fitted orders (y_Q, lean, steer torque): {orders:?}");
        for p in orders {
            assert!((p - 3.0).abs() < 0.1, "{orders:?}");
        }
        // Odd in the amplitude: the mirrored path gives the mirrored motion, so no a² term.
        let right = lane_change_nonlinear(&bike, 5.0, &rider(), &lane.scaled(0.2), 1e-11).unwrap();
        let left = lane_change_nonlinear(&bike, 5.0, &rider(), &lane.scaled(-0.2), 1e-11).unwrap();
        let mirrored: Vec<f64> = left.front_y.iter().map(|y| -y).collect();
        let asymmetry = largest_difference(&right.front_y, &mirrored);
        eprintln!("mirror asymmetry of y_Q at amplitude 0.2: {asymmetry:.3e} m");
        assert!(asymmetry < 1e-8, "{asymmetry}");
    }

    #[test]
    fn bad_requests_name_the_field() {
        let bike = BenchmarkParameters::meijaard2007();
        let lane = LaneChange::humancontrol(LaneKind::Double);
        let heading =
            HumanController::new(Task::Heading, *rider().gains(), Neuromuscular::default())
                .unwrap();
        let err = lane_change_linear(&bike, 5.0, &heading, &lane).unwrap_err();
        assert_eq!(
            err.to_string(),
            "invalid task: a lane change is followed by the lateral task, not the heading task"
        );
        let err = lane_change_linear(&bike, 0.0, &rider(), &lane).unwrap_err();
        assert!(err.to_string().contains("speed"), "{err}");
        let cramped = LaneChange {
            lane_length: 15.0,
            ..lane
        };
        let err = lane_change_linear(&bike, 5.0, &rider(), &cramped).unwrap_err();
        assert!(err.to_string().contains("`lane length` = 15"), "{err}");
        assert!(
            err.to_string()
                .contains("at least 2 |width| / slope = 20 m"),
            "{err}"
        );
        let err = LaneKind::from_name("triple").unwrap_err();
        assert!(
            err.to_string().contains("`triple` is not a lane change"),
            "{err}"
        );
        let flat = LaneChange { width: 0.0, ..lane };
        assert!(
            flat.check()
                .unwrap_err()
                .to_string()
                .contains("`width` = 0")
        );
    }
}
