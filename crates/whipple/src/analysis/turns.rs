//! Steady turns of the non-linear bicycle: circular motions at constant lean φ, steer δ and
//! (holonomically determined) pitch, with no lean or steer rate and constant wheel spin and yaw
//! rates given by the rolling constraints; *hands-free* with no applied torque, *held* with a
//! constant steer torque T_δ. Definitions, conventions and the reasoning are in `docs/turns.md`.
//!
//! - The speed v of a turn is the **rear contact's** speed (the speed of the point where the rear
//!   wheel touches the ground, along its circle); the model's own forward speed (the rear hub's)
//!   is reported beside it. Benchmark signs: lean right, steer right, yaw right positive.
//! - At φ̇ = δ̇ = 0 every speed is proportional to v, so the lean and steer accelerations are
//!   `E(φ, δ, v, T_δ) = f(φ, δ) + v² g(φ, δ) + T_δ h(φ, δ)`. A steady turn is a zero of these
//!   two equations; the third, the rate of the forward speed, then vanishes by itself (energy:
//!   at φ̇ = δ̇ = 0 the steer torque does no work, and dE/dt = m_vv(φ, δ) v v̇ once φ̈ = δ̈ = 0),
//!   which [`SteadyTurn::residuals`] reports and the tests check.
//! - Solutions by Newton iteration with exact Jacobians (dual numbers through the model), bounded,
//!   reached by a homotopy from straight running in steps of at most [`TurnSettings::max_step`];
//!   a turn that Newton cannot reach, or that leaves the region where the model is defined, is
//!   [`Error::NoSteadyTurn`], never an approximate answer.
//! - Stability: the exact Jacobian of the reduced equations on [φ, δ, φ̇, δ̇, v_hub] (the yaw,
//!   position and wheel angles are ignorable). Steady turns at a given T_δ form a curve
//!   (one per energy level), so this 5 × 5 Jacobian always has one zero eigenvalue whose
//!   eigenvector is the curve's tangent; the other four decide stability ([`Stability`]).
//! - Families of hands-free turns by pseudo-arclength continuation in (φ, δ, v) ([`trace_family`],
//!   [`hands_free_families`]), and the branching from straight running
//!   ([`branch_from_straight`]).
//!
//! ```
//! use whipple::{BenchmarkParameters, Model};
//! use whipple::advanced::turns::{held_turn, Held, TurnSettings};
//! let model = Model::new(&BenchmarkParameters::meijaard2007())?;
//! let turn = held_turn(&model, 5.0, Held::Lean(11.5f64.to_radians()), &TurnSettings::default())?;
//! assert!(turn.steer > 0.0 && turn.rear_radius.is_some());
//! assert!(turn.residuals.max() < 1e-9);
//! # Ok::<(), whipple::Error>(())
//! ```

use crate::math::Real;
use nalgebra::{DMatrix, DVector, Matrix2x3, SMatrix, SVector, Vector3, Vector4};
use num_dual::Dual64;
use serde::Serialize;

use crate::analysis::comparison::general_eigenvalues;
use crate::analysis::eigen::Complex64;
use crate::analysis::linearize::{VectorField, jacobian};
use crate::error::{Error, Result};
use crate::linear::Canonical;
use crate::nonlinear::{
    BODIES, BODY_YAW, ContactForce, InitialConditions, Inputs, Model, REAR_FRAME, REAR_WHEEL,
    State, StateRates,
};

#[inline]
fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

fn re<T: Real>(x: T) -> f64 {
    nalgebra::try_convert::<T, f64>(x).unwrap_or(f64::NAN)
}

/// Largest lean a turn may have \[rad\] (89°): the orientation angles are singular at 90°.
pub(crate) const MAX_LEAN: f64 = 89.0 * std::f64::consts::PI / 180.0;

/// Largest turn radius a held turn may be asked for \[m\] (a million kilometres): beyond it the
/// turn is straight running to within 1e-9 of any length of a bicycle, and the radius is the
/// quotient of two numbers each near round-off. [`held_turn`] refuses a larger one
/// ([`Error::InvalidArgument`] naming `radius`).
pub const MAX_RADIUS: f64 = 1e9;

/// Settings of the turn solvers, with their defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnSettings {
    /// Newton stops when a step changes no unknown by more than this, relative to 1 + |x|.
    /// Default 1e-13.
    pub step_tolerance: f64,
    /// A point is accepted as a steady turn when the lean and steer accelerations there are below
    /// this [rad/s²]. Default 1e-9 (round-off is about 1e-14).
    pub residual_tolerance: f64,
    /// Newton iterations allowed per solve. Default 30.
    pub max_iterations: usize,
    /// Largest change of the given quantity per homotopy step from straight running (lean or
    /// steer in rad; curvature in 1/m is stepped in ten equal parts). Default 0.05 rad.
    pub max_step: f64,
}

impl Default for TurnSettings {
    fn default() -> Self {
        TurnSettings {
            step_tolerance: 1e-13,
            residual_tolerance: 1e-9,
            max_iterations: 30,
            max_step: 0.05,
        }
    }
}

/// What is given of a held turn besides its speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Held {
    /// φ: lean \[rad\].
    Lean(f64),
    /// δ: steer \[rad\].
    Steer(f64),
    /// The rear contact's turn radius \[m\], positive for a right turn, negative for a left one.
    Radius(f64),
}

/// The equations' values at a solved turn (all should be at round-off).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TurnResiduals {
    /// φ̈ [rad/s²].
    pub lean_acceleration: f64,
    /// δ̈ [rad/s²].
    pub steer_acceleration: f64,
    /// v̇ of the rear hub's forward speed [m/s²]: not one of the equations solved, it vanishes by
    /// itself once the other two do.
    pub speed_rate: f64,
}

impl TurnResiduals {
    /// The largest of the three in absolute value.
    pub fn max(&self) -> f64 {
        self.lean_acceleration
            .abs()
            .max(self.steer_acceleration.abs())
            .max(self.speed_rate.abs())
    }
}

/// The ground's force on one wheel and the friction it needs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WheelContact {
    /// Normal force, up positive \[N\].
    pub normal: f64,
    /// Friction along the wheel's rolling direction, forward positive \[N\].
    pub longitudinal: f64,
    /// Friction across the wheel, right positive \[N\].
    pub lateral: f64,
    /// √(longitudinal² + lateral²) / normal: the friction coefficient the contact needs
    /// (infinite when the normal force is not positive: the wheel would lift off).
    pub friction_ratio: f64,
}

impl From<ContactForce<f64>> for WheelContact {
    fn from(f: ContactForce<f64>) -> Self {
        let tangential = crate::math::hypot(f.longitudinal, f.lateral);
        WheelContact {
            normal: f.normal,
            longitudinal: f.longitudinal,
            lateral: f.lateral,
            friction_ratio: if f.normal > 0.0 {
                tangential / f.normal
            } else {
                f64::INFINITY
            },
        }
    }
}

/// One steady turn and everything a rider or a designer asks of it. Angles in radians, benchmark
/// signs; radii positive for right turns (yaw rate positive), `None` when running straight.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadyTurn {
    /// v: speed of the rear contact point [m/s].
    pub speed: f64,
    /// φ: lean \[rad\].
    pub lean: f64,
    /// δ: steer \[rad\].
    pub steer: f64,
    /// T_δ: the steer torque that holds the turn (zero for a hands-free one) [N m].
    pub steer_torque: f64,
    /// θ: rear frame pitch \[rad\] (the model's third Euler angle of the rear frame).
    pub pitch: f64,
    /// The rear hub's forward speed, the model's own speed coordinate [m/s].
    pub hub_speed: f64,
    /// ψ̇: yaw rate [rad/s].
    pub yaw_rate: f64,
    /// Rear and front wheel spin rates relative to their frames (negative rolling forward) [rad/s].
    pub wheel_rates: [f64; 2],
    /// Radius of the rear contact's circle \[m\].
    pub rear_radius: Option<f64>,
    /// Radius of the front contact's circle \[m\].
    pub front_radius: Option<f64>,
    /// Radius of the whole bicycle's mass centre's circle \[m\].
    pub mass_centre_radius: Option<f64>,
    /// Centre of the circles, horizontal world coordinates (x, y) \[m\] of the start of
    /// [`SteadyTurn::initial_conditions`] (rear contact at the origin, heading along +x).
    pub centre: Option<[f64; 2]>,
    /// Centripetal acceleration of the mass centre, right positive [m/s²].
    pub lateral_acceleration: f64,
    /// Ground forces on the rear and front wheels.
    pub contact: [WheelContact; 2],
    /// The equations at the solution.
    pub residuals: TurnResiduals,
    /// Newton iterations of the last solve.
    pub iterations: usize,
}

impl SteadyTurn {
    /// Whether no torque holds it.
    pub fn is_hands_free(&self) -> bool {
        self.steer_torque == 0.0
    }

    /// The initial conditions of a simulation that starts exactly on this turn (heading along
    /// +x from the origin; the model's speed coordinate is the rear hub's).
    pub fn initial_conditions(&self) -> InitialConditions {
        InitialConditions {
            speed: self.hub_speed,
            lean: self.lean,
            steer: self.steer,
            ..InitialConditions::upright(self.hub_speed)
        }
    }
}

/// The model evaluated at (φ, δ, v, T_δ) with φ̇ = δ̇ = 0.
struct Evaluation<T: Real> {
    state: State<T>,
    d: StateRates<T>,
    /// φ̈, δ̈.
    accelerations: [T; 2],
    /// The rear hub's forward acceleration.
    speed_rate: T,
    /// The rear contact's curvature ψ̇ / v (signed).
    curvature: T,
    hub_speed: T,
}

/// The rear hub's forward acceleration d/dt (v_hub · h(ψ)) with h the horizontal heading.
fn hub_speed_rate<T: Real>(state: &State<T>, d: &StateRates<T>) -> T {
    let yaw = state.q[6 * REAR_FRAME + BODY_YAW];
    let (s, co) = crate::math::sin_cos(yaw);
    let v = state.velocity(REAR_WHEEL);
    let a = d.u_dot.fixed_rows::<3>(6 * REAR_WHEEL).into_owned();
    let yaw_rate = d.q_dot[6 * REAR_FRAME + BODY_YAW];
    a.x * co + a.y * s + (v.y * co - v.x * s) * yaw_rate
}

/// The rear frame's angular velocity in world axes.
fn frame_rate_world<T: Real>(model: &Model, state: &State<T>) -> Vector3<T> {
    let _ = model;
    let ang = state.angles(REAR_FRAME);
    crate::nonlinear::rotation::matrix(ang.x, ang.y, ang.z) * state.angular_velocity(REAR_FRAME)
}

fn evaluate<T: Real>(
    model: &Model,
    lean: T,
    steer: T,
    speed: T,
    torque: T,
) -> Result<Evaluation<T>> {
    let unit = model.reduced_state(&Vector4::new(lean, steer, T::zero(), T::zero()), T::one())?;
    // The rear contact's velocity for a unit hub speed: the contact point is fixed in the rear
    // frame, which turns about the vertical at ψ̇ (φ̇ = 0 and the pitch is constant).
    let omega = frame_rate_world(model, &unit);
    let [rear, _] = model.contact_points(&unit.q);
    let hub = unit.position(REAR_WHEEL);
    let contact_velocity = unit.velocity(REAR_WHEEL) + omega.cross(&(rear - hub));
    let per_hub = contact_velocity.x;
    let per_hub_value = re(per_hub);
    if per_hub_value.is_nan() || per_hub_value <= 0.0 {
        return Err(Error::NoSteadyTurn {
            given: format!("lean {:.4} rad, steer {:.4} rad", re(lean), re(steer)),
            reason: "the rear contact does not move forward in this configuration".into(),
        });
    }
    let hub_speed = speed / per_hub;
    let state = State {
        q: unit.q,
        u: unit.u * hub_speed,
    };
    let d = model.forward(
        &state,
        &Inputs {
            lean_torque: T::zero(),
            steer_torque: torque,
        },
    )?;
    let accelerations = model.lean_steer_accelerations(&state, &d);
    Ok(Evaluation {
        speed_rate: hub_speed_rate(&state, &d),
        curvature: omega.z / per_hub,
        accelerations,
        state,
        d,
        hub_speed,
    })
}

/// The variables of the turn equations: z = [φ, δ, v, T_δ].
type Point = [f64; 4];
// Indices into a `Point` (not the linear state's `linear::LEAN`, … nor a body's `BODY_LEAN`).
const TURN_LEAN: usize = 0;
const TURN_STEER: usize = 1;
const TURN_SPEED: usize = 2;
const TURN_TORQUE: usize = 3;

/// The equations (φ̈, δ̈ and, when a curvature is given, κ − κ₀) and their exact Jacobian in
/// the unknowns, by one dual-number pass per unknown.
fn equations(
    model: &Model,
    z: &Point,
    unknowns: &[usize],
    curvature: Option<f64>,
) -> Result<(DVector<f64>, DMatrix<f64>)> {
    let rows = if curvature.is_some() { 3 } else { 2 };
    let mut value = DVector::zeros(rows);
    let mut jac = DMatrix::zeros(rows, unknowns.len());
    for (j, &k) in unknowns.iter().enumerate() {
        let d = |i: usize| Dual64::new(z[i], if i == k { 1.0 } else { 0.0 });
        let e = evaluate(
            model,
            d(TURN_LEAN),
            d(TURN_STEER),
            d(TURN_SPEED),
            d(TURN_TORQUE),
        )?;
        let mut out = vec![e.accelerations[0], e.accelerations[1]];
        if let Some(k0) = curvature {
            out.push(e.curvature - Dual64::from_re(k0));
        }
        for (i, x) in out.iter().enumerate() {
            value[i] = x.re;
            jac[(i, j)] = x.eps;
        }
    }
    if value.iter().chain(jac.iter()).any(|x| !x.is_finite()) {
        return Err(Error::NonFinite {
            context: "the steady-turn equations".into(),
        });
    }
    Ok((value, jac))
}

/// Newton on the chosen unknowns of z, the rest held. Returns the iterations made.
fn newton(
    model: &Model,
    z: &mut Point,
    unknowns: &[usize],
    curvature: Option<f64>,
    settings: &TurnSettings,
) -> Result<usize> {
    let mut last = f64::INFINITY;
    for iteration in 1..=settings.max_iterations {
        let (value, jac) = equations(model, z, unknowns, curvature)?;
        last = value.amax();
        let step = jac
            .lu()
            .solve(&(-value))
            .ok_or_else(|| Error::SingularDynamics {
                context: "the steady-turn equations have a singular Jacobian here".into(),
            })?;
        let mut small = true;
        for (j, &k) in unknowns.iter().enumerate() {
            if !step[j].is_finite() {
                return Err(Error::NonFinite {
                    context: "a Newton step of the steady-turn equations".into(),
                });
            }
            z[k] += step[j];
            small &= step[j].abs() <= settings.step_tolerance * (1.0 + z[k].abs());
        }
        if z[TURN_LEAN].abs() > MAX_LEAN || z[TURN_SPEED] < 0.0 {
            break;
        }
        if small {
            return Ok(iteration);
        }
    }
    Err(Error::NoConvergence {
        method: "Newton iteration of the steady-turn equations",
        iterations: settings.max_iterations,
        residual: last,
    })
}

/// The full description of the turn at z (which must solve the equations).
fn describe(
    model: &Model,
    z: &Point,
    iterations: usize,
    settings: &TurnSettings,
) -> Result<SteadyTurn> {
    // The configuration is 2π-periodic in steer: report the steer in (−π, π].
    let mut z = *z;
    let tau = std::f64::consts::TAU;
    z[TURN_STEER] -= tau * (z[TURN_STEER] / tau).round();
    let z = &z;
    let e = evaluate(
        model,
        z[TURN_LEAN],
        z[TURN_STEER],
        z[TURN_SPEED],
        z[TURN_TORQUE],
    )?;
    let residuals = TurnResiduals {
        lean_acceleration: e.accelerations[0],
        steer_acceleration: e.accelerations[1],
        speed_rate: e.speed_rate,
    };
    let given = || {
        format!(
            "speed {} m/s, lean {:.3}°, steer {:.3}°, steer torque {} N m",
            z[TURN_SPEED],
            z[TURN_LEAN].to_degrees(),
            z[TURN_STEER].to_degrees(),
            z[TURN_TORQUE]
        )
    };
    let finite = [
        residuals.lean_acceleration,
        residuals.steer_acceleration,
        residuals.speed_rate,
    ]
    .iter()
    .all(|x| x.is_finite());
    if !finite
        || residuals
            .lean_acceleration
            .abs()
            .max(residuals.steer_acceleration.abs())
            > settings.residual_tolerance
    {
        return Err(Error::NoSteadyTurn {
            given: given(),
            reason: format!(
                "the equations are not satisfied (residual {:e})",
                residuals.max()
            ),
        });
    }
    if z[TURN_LEAN].abs() > MAX_LEAN {
        return Err(Error::NoSteadyTurn {
            given: given(),
            reason: "the lean is beyond 89°: the bicycle would lie on the ground".into(),
        });
    }
    let state = &e.state;
    let omega = frame_rate_world(model, state);
    let yaw_rate = omega.z;
    let [rear, front] = model.contact_points(&state.q);
    let v_rear = state.velocity(REAR_WHEEL) + omega.cross(&(rear - state.position(REAR_WHEEL)));
    let mut mass = 0.0;
    let mut centre = Vector3::zeros();
    for k in 0..BODIES {
        let m = model.bodies().body[k].mass;
        mass += m;
        centre += state.position(k) * m;
    }
    centre /= mass;
    let horizontal = |p: Vector3<f64>| Vector3::new(p.x, p.y, 0.0);
    let (radii, lateral_acceleration, centre_xy) = if yaw_rate != 0.0 {
        // The centre of the circles: ω × (P − C) = v_P for the rear contact P.
        let axis = Vector3::new(0.0, 0.0, yaw_rate);
        // ω × v / ω², divided once by ω each (ω² underflows for very large radii).
        let turn_centre = horizontal(rear) + axis.cross(&horizontal(v_rear)) / yaw_rate / yaw_rate;
        let sign = yaw_rate.signum();
        let radius = |p: Vector3<f64>| Some(sign * (horizontal(p) - turn_centre).norm());
        let r_cm = (horizontal(centre) - turn_centre).norm();
        (
            [radius(rear), radius(front), radius(centre)],
            sign * yaw_rate * (yaw_rate * r_cm),
            Some([turn_centre.x, turn_centre.y]),
        )
    } else {
        ([None; 3], 0.0, None)
    };
    Ok(SteadyTurn {
        speed: z[TURN_SPEED],
        lean: z[TURN_LEAN],
        steer: z[TURN_STEER],
        steer_torque: z[TURN_TORQUE],
        pitch: state.q[6 * REAR_FRAME + crate::nonlinear::BODY_PITCH],
        hub_speed: e.hub_speed,
        yaw_rate,
        wheel_rates: model.wheel_rates(state),
        rear_radius: radii[0],
        front_radius: radii[1],
        mass_centre_radius: radii[2],
        centre: centre_xy,
        lateral_acceleration,
        contact: [e.d.contact[0].into(), e.d.contact[1].into()],
        residuals,
        iterations,
    })
}

fn check_speed(speed: f64) -> Result<()> {
    if !(speed.is_finite() && speed >= 0.0) {
        return Err(Error::InvalidArgument {
            what: "speed",
            rule: format!("must be a finite number of at least 0 m/s, got {speed}"),
        });
    }
    Ok(())
}

/// The linear model's held turn at small lean: from the lean row of (g K₀ + v² K₂) q = [0, T_δ],
/// δ per unit lean, and the torque per unit lean from the steer row.
fn linear_ratios(model: &Model, speed: f64) -> Result<(f64, f64)> {
    let canonical = Canonical::new(model.parameters())?;
    let k = canonical.k0 * canonical.g + canonical.k2 * (speed * speed);
    if k[(0, 1)] == 0.0 {
        return Ok((0.0, k[(1, 0)]));
    }
    let steer_per_lean = -k[(0, 0)] / k[(0, 1)];
    Ok((steer_per_lean, k[(1, 0)] + k[(1, 1)] * steer_per_lean))
}

/// The held turn at `speed` (the rear contact's) with the lean, the steer or the radius given:
/// the rest and the steer torque T_δ that holds it.
///
/// Reached from straight running by a homotopy in the given quantity (steps of at most
/// `settings.max_step`), each step by Newton with exact Jacobians, so it finds the turn on the
/// branch that grows out of straight running (at a given lean and speed there may be others
/// with the front wheel turned far round; [`hands_free_families`] traces hands-free ones).
/// [`Error::NoSteadyTurn`] when no such turn is reached.
pub fn held_turn(
    model: &Model,
    speed: f64,
    given: Held,
    settings: &TurnSettings,
) -> Result<SteadyTurn> {
    check_speed(speed)?;
    let (target, index, unknowns, what): (f64, Option<usize>, &[usize], &'static str) = match given
    {
        Held::Lean(x) => (x, Some(TURN_LEAN), &[TURN_STEER, TURN_TORQUE], "lean"),
        Held::Steer(x) => (x, Some(TURN_STEER), &[TURN_LEAN, TURN_TORQUE], "steer"),
        Held::Radius(r) => (r, None, &[TURN_LEAN, TURN_STEER, TURN_TORQUE], "radius"),
    };
    if !target.is_finite() || (index.is_none() && target == 0.0) {
        return Err(Error::InvalidArgument {
            what,
            rule: format!("must be a finite, non-zero number, got {target}"),
        });
    }
    if index.is_none() && target.abs() > MAX_RADIUS {
        return Err(Error::InvalidArgument {
            what: "radius",
            rule: format!(
                "must be at most {MAX_RADIUS:e} m in size (beyond it the turn is straight running), got {}",
                crate::error::short_number(target)
            ),
        });
    }
    if index == Some(TURN_LEAN) && target.abs() > MAX_LEAN {
        return Err(Error::InvalidArgument {
            what: "lean",
            rule: format!("must lie within ±89°, got {:.3}°", target.to_degrees()),
        });
    }
    if index == Some(TURN_STEER) && target.abs() >= std::f64::consts::PI {
        return Err(Error::InvalidArgument {
            what: "steer",
            rule: format!(
                "must lie strictly within ±180°, got {:.3}°",
                target.to_degrees()
            ),
        });
    }
    let (steer_per_lean, torque_per_lean) = linear_ratios(model, speed)?;
    let p = model.parameters();
    let cos_lambda = crate::math::cos(p.lambda);
    let parts = match index {
        Some(_) => ((target.abs() / settings.max_step).ceil() as usize).clamp(1, 10_000),
        None => 10,
    };
    let fail = |reason: String| Error::NoSteadyTurn {
        given: format!(
            "held turn at {speed} m/s with {what} {}",
            describe_given(given)
        ),
        reason,
    };
    let mut z: Point = [0.0; 4];
    z[TURN_SPEED] = speed;
    let mut iterations = 0;
    for part in 1..=parts {
        let s = target * part as f64 / parts as f64;
        let curvature = match index {
            Some(i) => {
                if part == 1 {
                    // The linear model's prediction.
                    let lean = match i {
                        TURN_LEAN => s,
                        _ if steer_per_lean != 0.0 => s / steer_per_lean,
                        _ => 0.0,
                    };
                    z[TURN_LEAN] = lean;
                    z[TURN_STEER] = lean * steer_per_lean;
                    z[TURN_TORQUE] = lean * torque_per_lean;
                }
                z[i] = s;
                None
            }
            None => {
                let kappa = part as f64 / (parts as f64 * target);
                if part == 1 {
                    // Kinematic steer and the linear lean row.
                    z[TURN_STEER] = kappa * p.w / cos_lambda;
                    z[TURN_LEAN] = if steer_per_lean != 0.0 {
                        z[TURN_STEER] / steer_per_lean
                    } else {
                        0.0
                    };
                    z[TURN_TORQUE] = z[TURN_LEAN] * torque_per_lean;
                }
                Some(kappa)
            }
        };
        iterations = newton(model, &mut z, unknowns, curvature, settings).map_err(|e| {
            fail(format!(
                "Newton failed at {:.0}% of the way from straight running: {e}",
                100.0 * part as f64 / parts as f64
            ))
        })?;
    }
    let turn = describe(model, &z, iterations, settings).map_err(|e| match e {
        Error::NoSteadyTurn { reason, .. } => fail(reason),
        other => other,
    })?;
    check_contact(model, &turn).map_err(fail)?;
    Ok(turn)
}

/// A held turn the knife-edge model can hold: the ground pushes on both wheels. A wheel whose
/// normal force is negative in the turn would lift off (the contacts are bilateral constraints
/// in the equations, so they solve all the same), and the turn is refused, naming the wheel and
/// the force; a wheel already pulled down in straight running at the same speed (a skate whose
/// masses sit beyond its front contact) is left as the simulation leaves it.
fn check_contact(model: &Model, turn: &SteadyTurn) -> std::result::Result<(), String> {
    let negative: Vec<usize> = (0..2).filter(|&i| turn.contact[i].normal < 0.0).collect();
    if negative.is_empty() {
        return Ok(());
    }
    let straight = model
        .initial_state(&InitialConditions::upright(turn.hub_speed))
        .and_then(|state| model.forward(&state, &Inputs::default()))
        .map(|d| [d.contact[0].normal, d.contact[1].normal]);
    for i in negative {
        let pressed = straight.as_ref().map_or(true, |n| n[i] >= 0.0);
        if pressed {
            let wheel = ["rear", "front"][i];
            return Err(format!(
                "the {wheel} wheel's normal force would be {:.1} N: the ground would have to pull the wheel down, so it lifts off and the knife-edge model cannot hold this turn (ask for a larger radius, a smaller lean or steer, or a lower speed)",
                turn.contact[i].normal
            ));
        }
    }
    Ok(())
}

fn describe_given(given: Held) -> String {
    match given {
        Held::Lean(x) => format!("{:.4}°", x.to_degrees()),
        Held::Steer(x) => format!("{:.4}°", x.to_degrees()),
        Held::Radius(r) => format!("{r} m"),
    }
}

/// Polishes a hands-free turn near `guess` = [φ, δ, v] with one of them held (`held`: 0 lean,
/// 1 steer, 2 speed) by Newton, and describes it.
pub fn hands_free_turn_near(
    model: &Model,
    guess: [f64; 3],
    held: usize,
    settings: &TurnSettings,
) -> Result<SteadyTurn> {
    let mut z: Point = [guess[0], guess[1], guess[2], 0.0];
    let unknowns: Vec<usize> = [TURN_LEAN, TURN_STEER, TURN_SPEED]
        .into_iter()
        .filter(|&k| k != held)
        .collect();
    let iterations = newton(model, &mut z, &unknowns, None, settings)?;
    if z[TURN_SPEED] < 0.0 {
        return Err(Error::NoSteadyTurn {
            given: format!("hands-free turn near {guess:?}"),
            reason: "Newton went to a negative speed".into(),
        });
    }
    describe(model, &z, iterations, settings)
}

// ---------------------------------------------------------------------------------------------
// Stability

/// The reduced equations on x = [φ, δ, φ̇, δ̇, v_hub] at a constant steer torque: yaw, position
/// and wheel angles are ignorable, every other coordinate and speed follows from the
/// constraints. Its equilibria are the steady turns.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TurnField<'a> {
    /// The model.
    pub model: &'a Model,
    /// T_δ [N m], held constant.
    pub steer_torque: f64,
}

impl VectorField<5> for TurnField<'_> {
    fn eval<T: Real>(&self, x: &SVector<T, 5>) -> Result<SVector<T, 5>> {
        let state = self
            .model
            .reduced_state(&Vector4::new(x[0], x[1], x[2], x[3]), x[4])?;
        let d = self.model.forward(
            &state,
            &Inputs {
                lean_torque: T::zero(),
                steer_torque: c(self.steer_torque),
            },
        )?;
        let [a_lean, a_steer] = self.model.lean_steer_accelerations(&state, &d);
        Ok(SVector::<T, 5>::from([
            state.lean_rate(),
            self.model.steer_rate(&state),
            a_lean,
            a_steer,
            hub_speed_rate(&state, &d),
        ]))
    }
}

/// One eigenvalue λ = re + i·im [1/s].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Eigenvalue {
    /// Re λ.
    pub re: f64,
    /// Im λ.
    pub im: f64,
}

impl From<Complex64> for Eigenvalue {
    fn from(z: Complex64) -> Self {
        Eigenvalue { re: z.re, im: z.im }
    }
}

/// The linear stability of a steady turn.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Stability {
    /// The four eigenvalues that decide stability, largest real part first [1/s].
    pub eigenvalues: Vec<Eigenvalue>,
    /// The fifth eigenvalue, zero up to round-off: the direction along the curve of steady turns
    /// at the same steer torque (a neighbouring turn at another energy is also steady).
    pub family_eigenvalue: f64,
    /// max Re λ of the four [1/s].
    pub max_real: f64,
    /// Every one of the four has a negative real part.
    pub stable: bool,
}

/// The stability of a steady turn from the exact Jacobian of `TurnField` at it (dual numbers).
///
/// The Jacobian's eigenvalue nearest zero is the family's (its eigenvector is the tangent of the
/// curve of steady turns at this T_δ, (dφ, dδ, 0, 0, dv)); it is checked to be zero to
/// 1e-7 of the spectrum's scale, else [`Error::AccuracyLost`].
pub fn stability(model: &Model, turn: &SteadyTurn) -> Result<Stability> {
    let field = TurnField {
        model,
        steer_torque: turn.steer_torque,
    };
    let x0 = SVector::<f64, 5>::from([turn.lean, turn.steer, 0.0, 0.0, turn.hub_speed]);
    let a = jacobian(&field, &x0)?;
    let mut values = general_eigenvalues(&a)?;
    let scale = values.iter().map(crate::math::norm).fold(1.0, f64::max);
    let (k, zero) = values
        .iter()
        .enumerate()
        .min_by(|a, b| crate::math::norm(a.1).total_cmp(&crate::math::norm(b.1)))
        .map(|(k, z)| (k, *z))
        .ok_or_else(|| Error::NonFinite {
            context: "the eigenvalues of a steady turn".into(),
        })?;
    if crate::math::norm(zero) > 1e-7 * scale {
        return Err(Error::AccuracyLost {
            quantity: "the stability of a steady turn".into(),
            reason: format!(
                "the Jacobian's eigenvalue along the family of turns should be zero, it is {zero} \
                 (scale {scale:.3e})"
            ),
        });
    }
    values.remove(k);
    values.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
    let max_real = values.first().map_or(f64::NEG_INFINITY, |z| z.re);
    Ok(Stability {
        stable: max_real < 0.0,
        max_real,
        family_eigenvalue: zero.re,
        eigenvalues: values.into_iter().map(Eigenvalue::from).collect(),
    })
}

/// The Jacobian of `TurnField` at a steady turn (5 × 5, exact), for the tests and for users who
/// want the eigenvectors.
pub fn turn_jacobian(model: &Model, turn: &SteadyTurn) -> Result<SMatrix<f64, 5, 5>> {
    let field = TurnField {
        model,
        steer_torque: turn.steer_torque,
    };
    jacobian(
        &field,
        &SVector::<f64, 5>::from([turn.lean, turn.steer, 0.0, 0.0, turn.hub_speed]),
    )
}

// ---------------------------------------------------------------------------------------------
// Branching from straight running and families

/// Where hands-free turns branch from upright straight running.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Branch {
    /// v_b: the speed [m/s] (rear contact = rear hub when upright).
    pub speed: f64,
    /// δ/φ along the family as φ → 0.
    pub steer_per_lean: f64,
    /// Newton iterations.
    pub iterations: usize,
}

/// The small-lean limit of the hands-free turns, from the non-linear model itself: with
/// δ = s φ, E(φ, sφ, v, 0)/φ → ∂E/∂φ + s ∂E/∂δ at upright (exact, by dual numbers), and the
/// branch is the (v, s) where that vanishes (Newton from the linear model's prediction, where
/// det(g K₀ + v² K₂) = 0). `None` when the bicycle's det(g K₀ + v² K₂) has no positive root
/// (no hands-free turns leave straight running).
pub fn branch_from_straight(model: &Model, settings: &TurnSettings) -> Result<Option<Branch>> {
    let canonical = Canonical::new(model.parameters())?;
    let (g, k0, k2) = (canonical.g, canonical.k0, canonical.k2);
    // det(g K0 + v² K2) = a + b v² + c v⁴.
    let a = g * g * k0.determinant();
    let b = g
        * (k0[(0, 0)] * k2[(1, 1)] + k0[(1, 1)] * k2[(0, 0)]
            - k0[(0, 1)] * k2[(1, 0)]
            - k0[(1, 0)] * k2[(0, 1)]);
    let cc = k2.determinant();
    let mut roots: Vec<f64> = Vec::new();
    if cc == 0.0 {
        if b != 0.0 {
            roots.push(-a / b);
        }
    } else {
        let disc = b * b - 4.0 * a * cc;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            roots.push(q / cc);
            if q != 0.0 {
                roots.push(a / q);
            }
        }
    }
    let Some(v2) = roots
        .into_iter()
        .filter(|x| *x > 0.0 && x.is_finite())
        .min_by(f64::total_cmp)
    else {
        return Ok(None);
    };
    let mut v = v2.sqrt();
    let kk = k0 * g + k2 * v2;
    let mut s = if kk[(0, 1)] != 0.0 {
        -kk[(0, 0)] / kk[(0, 1)]
    } else {
        -kk[(1, 0)] / kk[(1, 1)]
    };
    // G(s, v) = ∂E/∂φ + s ∂E/∂δ at (0, 0, v, 0); Jacobian in (s, v) by a nested dual number.
    let limit = |s: Dual64, v: Dual64| -> Result<[Dual64; 2]> {
        let de = |k: usize| -> Result<[Dual64; 2]> {
            // One directional derivative in φ or δ; the outer dual carries d/d(s or v).
            use num_dual::HyperDual64;
            let h = |x: f64| HyperDual64::from_re(x);
            let dir = |i: usize| {
                if i == k {
                    HyperDual64::new(0.0, 1.0, 0.0, 0.0)
                } else {
                    h(0.0)
                }
            };
            let speed = HyperDual64::new(v.re, 0.0, v.eps, 0.0);
            let e = evaluate(model, dir(TURN_LEAN), dir(TURN_STEER), speed, h(0.0))?;
            Ok(e.accelerations.map(|x| Dual64::new(x.eps1, x.eps1eps2)))
        };
        let dl = de(TURN_LEAN)?;
        let ds = de(TURN_STEER)?;
        Ok([dl[0] + s * ds[0], dl[1] + s * ds[1]])
    };
    for iteration in 1..=settings.max_iterations {
        let fs = limit(Dual64::new(s, 1.0), Dual64::from_re(v))?;
        let fv = limit(Dual64::from_re(s), Dual64::new(v, 1.0))?;
        let jac = nalgebra::Matrix2::new(fs[0].eps, fv[0].eps, fs[1].eps, fv[1].eps);
        let r = nalgebra::Vector2::new(fs[0].re, fs[1].re);
        let step = jac
            .lu()
            .solve(&(-r))
            .ok_or_else(|| Error::SingularDynamics {
                context: "the small-lean limit of the hands-free turn equations".into(),
            })?;
        s += step[0];
        v += step[1];
        if !(s.is_finite() && v.is_finite()) {
            break;
        }
        if step[0].abs() <= settings.step_tolerance * (1.0 + s.abs())
            && step[1].abs() <= settings.step_tolerance * (1.0 + v.abs())
        {
            return Ok(Some(Branch {
                speed: v,
                steer_per_lean: s,
                iterations: iteration,
            }));
        }
    }
    Err(Error::NoConvergence {
        method: "Newton iteration for the branch of hands-free turns from straight running",
        iterations: settings.max_iterations,
        residual: f64::NAN,
    })
}

/// Settings of `trace_family`, with their defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FamilySettings {
    /// Newton settings of each corrector.
    pub turn: TurnSettings,
    /// Arclength step in (φ, δ, v / `speed_scale`) to start with and at most. Default 0.02 and 0.05.
    pub initial_step: f64,
    /// Largest step. Default 0.05.
    pub max_step: f64,
    /// Smallest step before giving up. Default 1e-6.
    pub min_step: f64,
    /// Points at most. Default 2000.
    pub max_points: usize,
    /// The tracing stops at this speed [m/s]. Default 20.
    pub max_speed: f64,
    /// Speed unit of the arclength [m/s]. Default 5.
    pub speed_scale: f64,
    /// Compute the stability of every point. Default true.
    pub stability: bool,
}

impl Default for FamilySettings {
    fn default() -> Self {
        FamilySettings {
            turn: TurnSettings::default(),
            initial_step: 0.02,
            max_step: 0.05,
            min_step: 1e-6,
            max_points: 2000,
            max_speed: 20.0,
            speed_scale: 5.0,
            stability: true,
        }
    }
}

/// One point of a family.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FamilyPoint {
    /// The turn.
    pub turn: SteadyTurn,
    /// Its stability (None when not asked for or not decidable: then `stability_error` says why).
    pub stability: Option<Stability>,
    /// Why the stability is missing, when asked for.
    pub stability_error: Option<String>,
}

/// Why a traced family ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FamilyEnd {
    /// The lean reached ±89°.
    Fell,
    /// The speed reached the maximum asked for.
    MaxSpeed,
    /// The speed reached zero: a static equilibrium (the family continues mirrored, v → −v).
    Standstill,
    /// The steer reached ±180°.
    SteerHalfTurn,
    /// The curve came back to its start.
    Closed,
    /// The maximum number of points.
    MaxPoints,
    /// The corrector failed even at the smallest step.
    StepTooSmall,
    /// Back at straight running (lean and steer zero).
    Straight,
}

/// A traced family of hands-free turns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Family {
    /// Its points in order along the curve.
    pub points: Vec<FamilyPoint>,
    /// Why it ends.
    pub end: FamilyEnd,
}

/// The hands-free equations and their 2 × 3 Jacobian in (φ, δ, v).
fn free_equations(model: &Model, y: &[f64; 3]) -> Result<(nalgebra::Vector2<f64>, Matrix2x3<f64>)> {
    let z = [y[0], y[1], y[2], 0.0];
    let (value, jac) = equations(model, &z, &[TURN_LEAN, TURN_STEER, TURN_SPEED], None)?;
    Ok((
        nalgebra::Vector2::new(value[0], value[1]),
        Matrix2x3::from_fn(|i, j| jac[(i, j)]),
    ))
}

/// Pseudo-arclength continuation of hands-free turns from `start` = [φ, δ, v] (a turn or close
/// to one) in the direction whose lean component has the sign of `direction` (or whose speed
/// grows, if the tangent has no lean component). The tangent is the null vector of the 2 × 3
/// Jacobian (the cross product of its rows, exact by dual numbers), the corrector Newton on the
/// two equations plus the arclength condition, so the tracing goes through folds in speed.
/// Steps adapt (halved on failure, grown after easy corrections), bounded by the settings.
pub(crate) fn trace_family(
    model: &Model,
    start: [f64; 3],
    direction: f64,
    settings: &FamilySettings,
) -> Result<Family> {
    let scale = Vector3::new(1.0, 1.0, 1.0 / settings.speed_scale);
    let unscale = |y: Vector3<f64>| [y.x, y.y, y.z * settings.speed_scale];
    // Correct the start with the lean held.
    let first = hands_free_turn_near(model, start, TURN_LEAN, &settings.turn)
        .or_else(|_| hands_free_turn_near(model, start, TURN_SPEED, &settings.turn))?;
    let mut y = Vector3::new(first.lean, first.steer, first.speed).component_mul(&scale);
    let mut points = Vec::new();
    let push = |points: &mut Vec<FamilyPoint>, turn: SteadyTurn| {
        let (stab, err) = if settings.stability {
            match stability(model, &turn) {
                Ok(s) => (Some(s), None),
                Err(e) => (None, Some(e.to_string())),
            }
        } else {
            (None, None)
        };
        points.push(FamilyPoint {
            turn,
            stability: stab,
            stability_error: err,
        });
    };
    push(&mut points, first);
    let tangent_at = |y: &Vector3<f64>| -> Result<Vector3<f64>> {
        let (_, j) = free_equations(model, &unscale(*y))?;
        // Columns in scaled variables: ∂/∂(v/V) = V ∂/∂v.
        let r0 = Vector3::new(j[(0, 0)], j[(0, 1)], j[(0, 2)] * settings.speed_scale);
        let r1 = Vector3::new(j[(1, 0)], j[(1, 1)], j[(1, 2)] * settings.speed_scale);
        let t = r0.cross(&r1);
        let n = t.norm();
        if !(n > 0.0 && n.is_finite()) {
            return Err(Error::SingularDynamics {
                context: "the family of hands-free turns has no tangent here (a branch point)"
                    .into(),
            });
        }
        Ok(t / n)
    };
    let mut t = tangent_at(&y)?;
    let sign = if t.x != 0.0 {
        t.x.signum() * direction.signum()
    } else {
        t.z.signum()
    };
    t *= if sign == 0.0 { 1.0 } else { sign };
    let start_y = y;
    let mut h = settings.initial_step.min(settings.max_step);
    let end = loop {
        if points.len() >= settings.max_points {
            break FamilyEnd::MaxPoints;
        }
        let predicted = y + t * h;
        let mut x = predicted;
        let mut ok = false;
        let mut its = 0;
        for it in 1..=settings.turn.max_iterations.min(12) {
            its = it;
            let Ok((f, j)) = free_equations(model, &unscale(x)) else {
                break;
            };
            let mut a = nalgebra::Matrix3::zeros();
            for col in 0..3 {
                let s = if col == 2 { settings.speed_scale } else { 1.0 };
                a[(0, col)] = j[(0, col)] * s;
                a[(1, col)] = j[(1, col)] * s;
                a[(2, col)] = t[col];
            }
            let rhs = Vector3::new(-f[0], -f[1], -t.dot(&(x - predicted)));
            let Some(dx) = a.lu().solve(&rhs) else { break };
            if !dx.iter().all(|v| v.is_finite()) {
                break;
            }
            x += dx;
            if dx.amax() <= settings.turn.step_tolerance * (1.0 + x.amax()) {
                ok = true;
                break;
            }
        }
        let turn = if ok {
            let [l, s, v] = unscale(x);
            describe(model, &[l, s, v, 0.0], its, &settings.turn).ok()
        } else {
            None
        };
        let Some(turn) = turn else {
            h *= 0.5;
            if h < settings.min_step {
                break FamilyEnd::StepTooSmall;
            }
            continue;
        };
        let Ok(mut t_new) = tangent_at(&x) else {
            break FamilyEnd::StepTooSmall;
        };
        if t_new.dot(&t) < 0.0 {
            t_new = -t_new;
        }
        // Reject steps that turn the tangent too much (a corner jumped, or another branch).
        if t_new.dot(&t) < 0.9 && h > settings.min_step {
            h *= 0.5;
            continue;
        }
        if turn.speed <= 0.0 {
            // Through standstill: the static equilibrium there ends the family (v → −v mirrors
            // it, the equations depend on v² only).
            if let Ok(rest) = hands_free_turn_near(
                model,
                [turn.lean, turn.steer, 0.0],
                TURN_SPEED,
                &settings.turn,
            ) {
                if (rest.lean - turn.lean).abs() + (rest.steer - turn.steer).abs() < 2.0 * h {
                    push(&mut points, rest);
                }
            }
            break FamilyEnd::Standstill;
        }
        let (lean, steer, speed) = (turn.lean, turn.steer, turn.speed);
        y = x;
        t = t_new;
        push(&mut points, turn);
        if its <= 3 {
            h = (h * 1.5).min(settings.max_step);
        }
        if lean.abs() > MAX_LEAN - 0.02 {
            break FamilyEnd::Fell;
        }
        if speed >= settings.max_speed {
            break FamilyEnd::MaxSpeed;
        }
        if steer.abs() >= std::f64::consts::PI - 0.02 {
            break FamilyEnd::SteerHalfTurn;
        }
        if lean.abs() < 1e-3 && steer.abs() < 1e-3 {
            break FamilyEnd::Straight;
        }
        if points.len() > 10 && (y - start_y).norm() < h {
            break FamilyEnd::Closed;
        }
    };
    Ok(Family { points, end })
}

/// The hands-free family that leaves straight running at the branch speed, traced to right
/// leans (the left-leaning one is its mirror image, (φ, δ) → (−φ, −δ)), from a lean of 0.5°.
/// `None` when no family branches off (see [`branch_from_straight`]).
pub fn branch_family(model: &Model, settings: &FamilySettings) -> Result<Option<Family>> {
    let Some(branch) = branch_from_straight(model, &settings.turn)? else {
        return Ok(None);
    };
    let lean = 0.5f64.to_radians();
    let start = [lean, branch.steer_per_lean * lean, branch.speed];
    trace_family(model, start, 1.0, settings).map(Some)
}

/// The hands-free families of a bicycle with right lean (left leans mirror them): the one from
/// straight running, and those found by scanning a grid of leans 2°…86° and steers −176°…176°
/// (every 6° and 8°) for sign changes of the hands-free condition f₁g₂ − f₂g₁ (with
/// v² = −f₁/g₁ ≥ 0, see the module docs) away from families already traced. A scan on a grid:
/// a family that never crosses a grid line is missed (say so when reporting).
pub fn hands_free_families(model: &Model, settings: &FamilySettings) -> Result<Vec<Family>> {
    let mut families = Vec::new();
    if let Some(f) = branch_family(model, settings)? {
        families.push(f);
    }
    let leans: Vec<f64> = (0..15)
        .map(|i| (2.0 + 6.0 * i as f64).to_radians())
        .collect();
    let steers: Vec<f64> = (0..45)
        .map(|j| (-176.0 + 8.0 * j as f64).to_radians())
        .collect();
    // f = E(v = 0), g = E(v = 1) − f at T = 0.
    let condition = |lean: f64, steer: f64| -> Option<(f64, f64)> {
        let f = evaluate(model, lean, steer, 0.0, 0.0).ok()?.accelerations;
        let e1 = evaluate(model, lean, steer, 1.0, 0.0).ok()?.accelerations;
        let g = [e1[0] - f[0], e1[1] - f[1]];
        let v2 = if g[0] != 0.0 {
            -f[0] / g[0]
        } else {
            -f[1] / g[1]
        };
        let h = f[0] * g[1] - f[1] * g[0];
        (h.is_finite() && v2.is_finite()).then_some((h, v2))
    };
    let grid: Vec<Vec<Option<(f64, f64)>>> = leans
        .iter()
        .map(|&l| steers.iter().map(|&s| condition(l, s)).collect())
        .collect();
    let near_traced = |families: &[Family], lean: f64, steer: f64| {
        families.iter().any(|f| {
            f.points
                .iter()
                .any(|p| (p.turn.lean - lean).abs() < 0.08 && (p.turn.steer - steer).abs() < 0.12)
        })
    };
    for (i, &lean) in leans.iter().enumerate() {
        for j in 0..steers.len().saturating_sub(1) {
            let (Some((h0, v0)), Some((h1, v1))) = (grid[i][j], grid[i][j + 1]) else {
                continue;
            };
            if h0.signum() == h1.signum() || v0 < 0.0 || v1 < 0.0 {
                continue;
            }
            // Bisect the sign change in steer at this lean.
            let (mut a, mut b, mut ha) = (steers[j], steers[j + 1], h0);
            for _ in 0..40 {
                let m = 0.5 * (a + b);
                let Some((hm, _)) = condition(lean, m) else {
                    break;
                };
                if hm.signum() == ha.signum() {
                    a = m;
                    ha = hm;
                } else {
                    b = m;
                }
            }
            let steer = 0.5 * (a + b);
            let Some((_, v2)) = condition(lean, steer) else {
                continue;
            };
            if v2.is_nan()
                || v2 < 0.0
                || v2.sqrt() > settings.max_speed
                || near_traced(&families, lean, steer)
            {
                continue;
            }
            let start = [lean, steer, v2.sqrt()];
            let mut points = Vec::new();
            let mut end = FamilyEnd::StepTooSmall;
            for direction in [-1.0, 1.0] {
                if let Ok(f) = trace_family(model, start, direction, settings) {
                    end = f.end;
                    let mut p = f.points;
                    if direction < 0.0 {
                        p.reverse();
                        points.extend(p);
                    } else {
                        points.extend(p.into_iter().skip(usize::from(!points.is_empty())));
                    }
                }
            }
            if points.len() > 1 {
                families.push(Family { points, end });
            }
        }
    }
    Ok(families)
}

/// Every hands-free turn at `speed` on the families of [`hands_free_families`]: the crossings of
/// that speed, polished by Newton with the speed held.
pub fn hands_free_turns_at_speed(
    model: &Model,
    speed: f64,
    families: &[Family],
    settings: &TurnSettings,
) -> Result<Vec<SteadyTurn>> {
    check_speed(speed)?;
    let mut out: Vec<SteadyTurn> = Vec::new();
    for f in families {
        for w in f.points.windows(2) {
            let (a, b) = (&w[0].turn, &w[1].turn);
            if (a.speed - speed) * (b.speed - speed) > 0.0 || a.speed == b.speed {
                continue;
            }
            let t = (speed - a.speed) / (b.speed - a.speed);
            let guess = [
                a.lean + t * (b.lean - a.lean),
                a.steer + t * (b.steer - a.steer),
                speed,
            ];
            if let Ok(turn) = hands_free_turn_near(model, guess, TURN_SPEED, settings) {
                if !out.iter().any(|o| {
                    (o.lean - turn.lean).abs() < 1e-8 && (o.steer - turn.steer).abs() < 1e-8
                }) {
                    out.push(turn);
                }
            }
        }
    }
    Ok(out)
}
