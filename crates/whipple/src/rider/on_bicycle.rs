//! The rider seated on the bicycle: what BicycleParameters 1.5.2's `Bicycle.add_rider` computes
//! (its `rider.rider_on_bike`, `configure_rider` and `inertia.combine_bike_rider`), one step a
//! function, on any scalar so that dual numbers carry the bicycle's σ through every step.
//!
//! 1. [`bottom_bracket`]: where the bottom bracket is, from the chain stay `lcs`, the bottom
//!    bracket's height `hbb` and the rear wheel's radius `rR`.
//! 2. [`seat`]: where the rider sits (the origin of Yeadon's body, the centre of the hip level
//!    `Ls0`): up the seat tube from the bottom bracket by the seat tube and seat post,
//!    `lst + lsp`, at the seat tube's angle `lamst`.
//! 3. [`handlebar_grips`]: where the hands hold the handlebar: the grips are `whb` apart, each
//!    `LhbF` from the front hub and `LhbR` from the rear hub (hubs `rF` and `rR` above the
//!    ground, `w` apart); of the two points of the side view at those distances, the upper.
//! 4. [`solve_seated`]: the joint angles that put the feet on the bottom bracket and the hands
//!    on the grips — the hips' and knees' extension and flexion (`PJ1extension`,
//!    `J1J2flexion`) and the shoulders' and elbows' four angles (`CA1extension`,
//!    `CA1adduction`, `CA1rotation`, `A1A2extension`), the left side solved and the right its
//!    mirror image, with the upper arm's own x axis kept level as the sixth condition. Our own
//!    residual on the body's own kinematics ([`super::yeadon_body`]'s segments): the point of
//!    the foot `Lj5L + Lj6L` from the hip (the ankle, then the heel level) meets the bottom
//!    bracket in the side view, the point of the hand `La4L + La5L` from the shoulder (the
//!    wrist, then the hand's length) meets the left grip. Newton with a Jacobian by dual
//!    numbers and a backtracking line search, at most [`MAX_ITERATIONS`] iterations, from the
//!    start BicycleParameters uses (so that both find the same seat of the rider). The other
//!    angles (`somersault`, the trunk's, the hips' adduction) are the configuration file's.
//! 5. [`seated_configuration`]: the solved angles lifted to the scalar of the bicycle (one
//!    Newton step on that scalar from the f64 root, with the f64 Jacobian: for dual numbers
//!    the exact derivative of the root, by the implicit function theorem).
//! 6. [`rider_in_benchmark_frame`]: the body's mass, mass centre and inertia moved from
//!    Yeadon's axes (x to the rider's left, y back, z up the trunk, origin at the seat) to the
//!    benchmark's (x forward, y right, z down, origin at the rear contact).
//! 7. [`combine_with_rear_frame`]: the rider added to the rear frame B (the parallel-axis
//!    combination of [`crate::parameters::jbike6`]'s `PlaneBody`, the one home of it).
//!
//! The measured bicycle's keys used are BicycleParameters' ([`RIDER_GEOMETRY_KEYS`]): `lcs`,
//! `hbb`, `lsp`, `lst`, `lamst`, `whb`, `LhbF`, `LhbR`; and of the benchmark parameters `rR`,
//! `rF` and `w`.
//!
//! Against BicycleParameters: its equations take the trunk unbent (`PTsagittalFlexion`,
//! `PTbending`, `TCsagittalSpinalFlexion`, `TCspinalTorsion`, `tilt` and `twist` zero, as in
//! every configuration file of its data set), ours place the shoulders and hips wherever the
//! configuration puts them; the grips' place is solved in closed form here and by `fsolve`
//! there; and it computes the body with `yeadon` 2.0.1, whose three errors ([`super`]) move
//! the rider's mass centre and inertia — the differences are given in the guide.

use crate::math::Real;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use num_dual::Dual64;

use super::solids::c;
use super::{
    CONFIGURATION_ANGLES, MEASUREMENT_NAMES, YeadonBody, YeadonConfiguration, YeadonMeasurements,
    averaged, placed, to_f64, yeadon_body,
};
use crate::error::{Error, Result};
use crate::parameters::benchmark::BenchmarkParameters;
use crate::parameters::jbike6::PlaneBody;

/// The measured bicycle's keys that place the rider (BicycleParameters' `*Measured.txt`
/// names), with what each is.
pub const RIDER_GEOMETRY_KEYS: [(&str, &str); 8] = [
    ("lcs", "chain stay length, rear hub to bottom bracket [m]"),
    ("hbb", "bottom bracket height above the ground [m]"),
    ("lsp", "seat post length, out of the seat tube [m]"),
    ("lst", "seat tube length, from the bottom bracket [m]"),
    (
        "lamst",
        "seat tube angle with the ground, the tube rising backwards [rad]",
    ),
    ("whb", "handlebar width, between the grips [m]"),
    ("LhbF", "distance from the front hub to a grip [m]"),
    ("LhbR", "distance from the rear hub to a grip [m]"),
];

/// The joint angles the seated solve finds (the left side's; the right side mirrors them),
/// in the order of [`SeatedSolve::angles`].
pub const SEATED_ANGLES: [&str; 6] = [
    "PJ1extension",
    "J1J2flexion",
    "CA1extension",
    "CA1adduction",
    "CA1rotation",
    "A1A2extension",
];

/// The right side's angles, each the mirror image of [`SEATED_ANGLES`]' (sign +1 or −1).
const MIRRORED: [(&str, f64); 6] = [
    ("PK1extension", 1.0),
    ("K1K2flexion", 1.0),
    ("CB1extension", 1.0),
    ("CB1abduction", -1.0),
    ("CB1rotation", -1.0),
    ("B1B2extension", 1.0),
];

/// Where the solve starts (rad): hips bent forward 90°, knees 75°, the arms a little forward,
/// elbows bent 40° — the start BicycleParameters' `fsolve` takes, so both find the same seat.
const START_DEG: [f64; 6] = [-90.0, 75.0, -15.0, 2.0, 2.0, -40.0];

/// The most Newton iterations of [`solve_seated`].
pub const MAX_ITERATIONS: usize = 50;

/// The most halvings of one Newton step in the line search.
const MAX_HALVINGS: usize = 40;

/// The residual (m, and the upper arm's level) at which the solve is converged.
const TOLERANCE: f64 = 1e-10;

/// The measured bicycle's rider geometry ([`RIDER_GEOMETRY_KEYS`]), SI (m, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RiderGeometry<T> {
    /// `lcs`: chain stay length, rear hub to bottom bracket \[m\].
    pub lcs: T,
    /// `hbb`: bottom bracket height \[m\].
    pub hbb: T,
    /// `lsp`: seat post length \[m\].
    pub lsp: T,
    /// `lst`: seat tube length \[m\].
    pub lst: T,
    /// `lamst`: the seat tube's angle with the ground \[rad\].
    pub lamst: T,
    /// `whb`: handlebar width \[m\].
    pub whb: T,
    /// `LhbF`: front hub to a grip \[m\].
    pub lhbf: T,
    /// `LhbR`: rear hub to a grip \[m\].
    pub lhbr: T,
}

impl<T: Copy> RiderGeometry<T> {
    /// From the values in [`RIDER_GEOMETRY_KEYS`]' order.
    pub fn from_array(v: [T; 8]) -> Self {
        let [lcs, hbb, lsp, lst, lamst, whb, lhbf, lhbr] = v;
        RiderGeometry {
            lcs,
            hbb,
            lsp,
            lst,
            lamst,
            whb,
            lhbf,
            lhbr,
        }
    }

    /// The values in [`RIDER_GEOMETRY_KEYS`]' order.
    pub fn to_array(&self) -> [T; 8] {
        [
            self.lcs, self.hbb, self.lsp, self.lst, self.lamst, self.whb, self.lhbf, self.lhbr,
        ]
    }
}

/// The rider as one rigid body in the benchmark's axes (x forward, y right, z down; origin at
/// the rear contact): the body a leaning-rider model would move, and what is added to the rear
/// frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RiderBody<T> {
    /// Mass \[kg\].
    pub mass: T,
    /// Mass centre (x, y, z) \[m\].
    pub center_of_mass: Vector3<T>,
    /// Inertia about the mass centre, the tensor (products as its entries, as Table 1's
    /// `IBxz`) \[kg m²\].
    pub inertia: Matrix3<T>,
}

/// What [`solve_seated`] found: the left side's angles, how it got there, and the Jacobian's
/// inverse at the root (for [`seated_configuration`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SeatedSolve {
    /// The angles (rad) in [`SEATED_ANGLES`]' order.
    pub angles: [f64; 6],
    /// Newton iterations taken.
    pub iterations: usize,
    /// The residual's largest entry at the root (m).
    pub residual: f64,
    inverse: SMatrix<f64, 6, 6>,
}

/// The rider seated on the bicycle, every step's result.
#[derive(Debug, Clone, PartialEq)]
pub struct SeatedRider<T> {
    /// The f64 solve of the joint angles (iterations, residual).
    pub solve: SeatedSolve,
    /// The bottom bracket (x, z), benchmark axes \[m\].
    pub bottom_bracket: [T; 2],
    /// The seat, Yeadon's origin (x, z) \[m\].
    pub seat: [T; 2],
    /// The grips' centre (x, z) \[m\]; the grips are at y = ±whb/2.
    pub grips: [T; 2],
    /// The full configuration on the bicycle (the file's angles, the solved ones and their
    /// mirror images).
    pub configuration: YeadonConfiguration<T>,
    /// The body in Yeadon's axes, origin at the seat.
    pub body: YeadonBody<T>,
    /// The rider in the benchmark's axes.
    pub rider: RiderBody<T>,
}

fn invalid(fields: &str, rule: String) -> Error {
    Error::InvalidBicycle {
        fields: fields.to_string(),
        rule,
    }
}

/// Step 1: the bottom bracket's (x, z) in the benchmark's axes: `hbb` above the ground, `lcs`
/// from the rear hub (`rR` above the ground), ahead of it. Fails naming `lcs`, `hbb` and `rR`
/// where the chain stay is shorter than the hub's height above the bottom bracket.
pub fn bottom_bracket<T: Real>(g: &RiderGeometry<T>, r_r: T) -> Result<[T; 2]> {
    let rise = r_r - g.hbb;
    let run2 = g.lcs * g.lcs - rise * rise;
    let run2_f64 = to_f64(run2);
    if run2_f64.is_nan() || run2_f64 <= 0.0 {
        return Err(invalid(
            "lcs, hbb, rR",
            format!(
                "the chain stay lcs = {} m does not reach from the rear hub (rR = {} m high) to \
                 the bottom bracket (hbb = {} m high)",
                to_f64(g.lcs),
                to_f64(r_r),
                to_f64(g.hbb)
            ),
        ));
    }
    Ok([run2.sqrt(), -g.hbb])
}

/// Step 2: the seat, the origin of Yeadon's body (x, z): `lst + lsp` up the seat tube from the
/// bottom bracket, the tube rising backwards at `lamst` from the ground.
pub fn seat<T: Real>(g: &RiderGeometry<T>, bottom_bracket: [T; 2]) -> [T; 2] {
    let length = g.lsp + g.lst;
    let (s, cos) = crate::math::sin_cos(g.lamst);
    [
        bottom_bracket[0] - length * cos,
        bottom_bracket[1] - length * s,
    ]
}

/// Step 3: the grips' centre (x, z): in the side view the point `√(LhbR² − whb²/4)` from the
/// rear hub (0, −rR) and `√(LhbF² − whb²/4)` from the front hub (w, −rF), the upper of the two.
/// Fails naming the keys where a grip is nearer a hub than half the handlebar's width or the
/// two distances do not meet.
pub fn handlebar_grips<T: Real>(g: &RiderGeometry<T>, w: T, r_r: T, r_f: T) -> Result<[T; 2]> {
    let half = g.whb * c(0.5);
    let in_plane = |l: T, key: &str| -> Result<T> {
        let s = l * l - half * half;
        if to_f64(s) > 0.0 {
            Ok(s.sqrt())
        } else {
            Err(invalid(
                &format!("{key}, whb"),
                format!(
                    "a grip {key} = {} m from the hub cannot be half the handlebar's width \
                     (whb = {} m) from the bicycle's plane",
                    to_f64(l),
                    to_f64(g.whb)
                ),
            ))
        }
    };
    let a = in_plane(g.lhbr, "LhbR")?;
    let b = in_plane(g.lhbf, "LhbF")?;
    let (dx, dz) = (w, r_r - r_f);
    let d = (dx * dx + dz * dz).sqrt();
    let along = (a * a - b * b + d * d) / (c::<T>(2.0) * d);
    let across2 = a * a - along * along;
    let across2_f64 = to_f64(across2);
    if across2_f64.is_nan() || across2_f64 <= 0.0 {
        return Err(invalid(
            "LhbF, LhbR, w",
            format!(
                "no point is LhbR = {} m from the rear hub and LhbF = {} m from the front hub, \
                 {} m apart",
                to_f64(g.lhbr),
                to_f64(g.lhbf),
                to_f64(d)
            ),
        ));
    }
    let across = across2.sqrt();
    let (ex, ez) = (dx / d, dz / d);
    // The normal (ez, −ex) points up (−z) for a front hub ahead of the rear one.
    Ok([along * ex + across * ez, -r_r + along * ez - across * ex])
}

/// Yeadon's axes (x left, y back, z up) to the benchmark's (x forward, y right, z down):
/// `v_benchmark = R v_yeadon`; R is its own inverse.
fn yeadon_to_benchmark<T: Real>() -> Matrix3<T> {
    let (o, l) = (T::zero(), T::one());
    Matrix3::new(o, -l, o, -l, o, o, o, o, -l)
}

/// Where the left foot and hand must be, in Yeadon's axes: the bottom bracket's (y, z) and the
/// left grip's (x, y, z).
#[derive(Debug, Clone, Copy)]
struct Targets<T> {
    foot: [T; 2],
    hand: Vector3<T>,
}

fn targets<T: Real>(
    g: &RiderGeometry<T>,
    seat: [T; 2],
    bottom_bracket: [T; 2],
    grips: [T; 2],
) -> Targets<T> {
    let r = yeadon_to_benchmark::<T>();
    let yeadon = |x: T, y: T, z: T| r * Vector3::new(x - seat[0], y, z - seat[1]);
    let foot = yeadon(bottom_bracket[0], T::zero(), bottom_bracket[1]);
    // The left grip: y = −whb/2 in the benchmark's axes.
    let hand = yeadon(grips[0], -g.whb * c(0.5), grips[1]);
    Targets {
        foot: [foot.y, foot.z],
        hand,
    }
}

fn angle_index(name: &str) -> usize {
    CONFIGURATION_ANGLES
        .iter()
        .position(|(n, _, _)| *n == name)
        .unwrap_or(0)
}

fn measurement<T: Copy>(values: &[T; 95], name: &str) -> T {
    values[MEASUREMENT_NAMES
        .iter()
        .position(|n| *n == name)
        .unwrap_or(0)]
}

/// The configuration with the left side's solved angles and the right side's mirror images.
fn configure<T: Real>(base: &YeadonConfiguration<f64>, q: &[T; 6]) -> YeadonConfiguration<T> {
    let mut angles = base.angles.map(c::<T>);
    for (i, name) in SEATED_ANGLES.iter().enumerate() {
        angles[angle_index(name)] = q[i];
        let (mirror, sign) = MIRRORED[i];
        angles[angle_index(mirror)] = q[i] * c(sign);
    }
    YeadonConfiguration {
        angles,
        lines: base.lines,
    }
}

/// The six conditions at the angles `q`: the foot's (y, z) less the bottom bracket's, the
/// hand's (x, y, z) less the grip's (m), and the vertical component of the upper arm's x axis.
fn residual<T: Real>(
    q: &[T; 6],
    base: &YeadonConfiguration<f64>,
    measurements: &YeadonMeasurements<T>,
    t: &Targets<T>,
) -> Result<SVector<T, 6>> {
    let body = placed(measurements, &configure(base, q))?;
    let v = averaged(measurements);
    let l = |name: &str| measurement(&v, name);
    let segment = |name: &str| body.segments.iter().find(|s| s.name == name);
    let (Some(a1), Some(a2), Some(j2)) = (segment("A1"), segment("A2"), segment("J2")) else {
        return Err(Error::NonFinite {
            context: "the seated rider's segments".into(),
        });
    };
    let zero = T::zero();
    let foot =
        j2.origin + j2.orientation * Vector3::new(zero, zero, -(l("Lj5L") - l("Lj3L") + l("Lj6L")));
    let hand =
        a2.origin + a2.orientation * Vector3::new(zero, zero, -(l("La4L") - l("La2L") + l("La5L")));
    Ok(SVector::<T, 6>::from([
        foot.y - t.foot[0],
        foot.z - t.foot[1],
        hand.x - t.hand.x,
        hand.y - t.hand.y,
        hand.z - t.hand.z,
        a1.orientation[(2, 0)],
    ]))
}

fn jacobian(
    q: &[f64; 6],
    base: &YeadonConfiguration<f64>,
    measurements: &YeadonMeasurements<Dual64>,
    t: &Targets<Dual64>,
) -> Result<SMatrix<f64, 6, 6>> {
    let mut j = SMatrix::<f64, 6, 6>::zeros();
    for col in 0..6 {
        let seeded: [Dual64; 6] =
            std::array::from_fn(|i| Dual64::new(q[i], if i == col { 1.0 } else { 0.0 }));
        let f = residual(&seeded, base, measurements, t)?;
        for row in 0..6 {
            j[(row, col)] = f[row].eps;
        }
    }
    if j.iter().all(|x| x.is_finite()) {
        Ok(j)
    } else {
        Err(Error::NonFinite {
            context: "the Jacobian of the seated rider's joint-angle solve".into(),
        })
    }
}

fn lift<T: Real>(m: &YeadonMeasurements<f64>) -> YeadonMeasurements<T> {
    YeadonMeasurements {
        values: m.values.map(c::<T>),
        total_mass: m.total_mass.map(c::<T>),
        lines: m.lines,
    }
}

/// The reach of two links `a` and `b` (a thigh and a shank, an upper arm and a forearm-hand):
/// the distance `d` must lie between |a − b| and a + b.
#[allow(clippy::too_many_arguments)]
fn reach_error(
    d: f64,
    a: f64,
    b: f64,
    what: &str,
    target: &str,
    fields: &str,
    lengths: &str,
    mend: &str,
) -> Option<Error> {
    if d > a + b {
        Some(invalid(
            fields,
            format!(
                "the rider cannot reach {target}: it is {d:.4} m from the {what}, and the \
                 rider's {lengths} reach {:.4} m; {mend}",
                a + b
            ),
        ))
    } else if d < (a - b).abs() {
        Some(invalid(
            fields,
            format!(
                "{target} is too near the rider's {what} ({d:.4} m; the {lengths} fold to no \
                 less than {:.4} m)",
                (a - b).abs()
            ),
        ))
    } else {
        None
    }
}

/// Step 4: the joint angles that seat the rider (module documentation), by Newton on our
/// residual with its Jacobian by dual numbers. `base` gives every other angle. Fails naming
/// the measurements and keys where the feet cannot reach the bottom bracket or the hands the
/// grips (before any iteration), with [`Error::NoConvergence`] where Newton does not converge
/// in [`MAX_ITERATIONS`], and naming the angle where the seat found is outside `yeadon`'s
/// range for it.
pub fn solve_seated(
    measurements: &YeadonMeasurements<f64>,
    base: &YeadonConfiguration<f64>,
    geometry: &RiderGeometry<f64>,
    w: f64,
    r_r: f64,
    r_f: f64,
) -> Result<SeatedSolve> {
    // The measurements and the file's angles as yeadon_body checks them.
    let start: [f64; 6] = START_DEG.map(f64::to_radians);
    yeadon_body(measurements, &configure(base, &start))?;
    let bb = bottom_bracket(geometry, r_r)?;
    let seat_point = seat(geometry, bb);
    let grips = handlebar_grips(geometry, w, r_r, r_f)?;
    let t = targets(geometry, seat_point, bb, grips);

    // Reach: the shoulder and the hip do not move with the solved angles.
    let body = placed(measurements, &configure(base, &start))?;
    let v = averaged(measurements);
    let l = |name: &str| measurement(&v, name);
    let origin = |name: &str| {
        body.segments
            .iter()
            .find(|s| s.name == name)
            .map(|s| s.origin)
            .unwrap_or_else(Vector3::zeros)
    };
    let hip = origin("J1");
    let leg = ((hip.y - t.foot[0]).powi(2) + (hip.z - t.foot[1]).powi(2)).sqrt();
    let thigh = l("Lj3L");
    let shank = l("Lj5L") - l("Lj3L") + l("Lj6L");
    if let Some(e) = reach_error(
        leg,
        thigh,
        shank,
        "hip",
        "the bottom bracket",
        "Lj3L, Lj5L, Lj6L, lsp, lst, lamst, hbb",
        "legs (Lj5L + Lj6L, hip to heel)",
        "a shorter seat post (lsp) or a taller rider",
    ) {
        return Err(e);
    }
    let arm = (origin("A1") - t.hand).norm();
    let upper = l("La2L");
    let lower = l("La4L") - l("La2L") + l("La5L");
    if let Some(e) = reach_error(
        arm,
        upper,
        lower,
        "shoulder",
        "the handlebar",
        "La2L, La4L, La5L, LhbF, LhbR, whb, somersault",
        "arms (La4L + La5L, shoulder to the middle of the hand)",
        "a handlebar nearer the seat, or a rider leaning further forward (somersault)",
    ) {
        return Err(e);
    }

    let dual_measurements = lift::<Dual64>(measurements);
    let dual_targets = Targets {
        foot: t.foot.map(Dual64::from_re),
        hand: t.hand.map(Dual64::from_re),
    };
    let mut q = start;
    let mut f = residual(&q, base, measurements, &t)?;
    let mut norm = f.norm();
    let mut iterations = 0;
    let failed = |iterations, norm| Error::NoConvergence {
        method: "the seated rider's joint-angle solve (Newton)",
        iterations,
        residual: norm,
    };
    while iterations < MAX_ITERATIONS {
        if norm == 0.0 {
            break;
        }
        iterations += 1;
        let j = jacobian(&q, base, &dual_measurements, &dual_targets)?;
        let Some(inverse) = j.try_inverse() else {
            return Err(failed(iterations, norm));
        };
        let step = inverse * f;
        let mut lambda = 1.0;
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let trial: [f64; 6] = std::array::from_fn(|i| q[i] - lambda * step[i]);
            let f_trial = residual(&trial, base, measurements, &t)?;
            let n = f_trial.norm();
            if n.is_finite() && (n < norm || (n <= norm && norm < TOLERANCE)) {
                accepted = Some((trial, f_trial, n));
                break;
            }
            lambda *= 0.5;
        }
        let Some((trial, f_trial, n)) = accepted else {
            // No decrease: at the round-off floor when converged, else stuck.
            if norm < TOLERANCE {
                break;
            }
            return Err(failed(iterations, norm));
        };
        let small_step = (lambda * step.amax()) < 1e-15;
        q = trial;
        f = f_trial;
        norm = n;
        if small_step {
            break;
        }
    }
    if norm.is_nan() || norm >= TOLERANCE {
        return Err(failed(iterations, norm));
    }
    for (i, name) in SEATED_ANGLES.iter().enumerate() {
        let (_, low, high) = CONFIGURATION_ANGLES[angle_index(name)];
        if !(q[i] >= low && q[i] <= high) {
            return Err(invalid(
                name,
                format!(
                    "seating the rider on this bicycle needs {name} = {:.4} rad, outside the \
                     range [{low:.4}, {high:.4}] rad of the Yeadon model",
                    q[i]
                ),
            ));
        }
    }
    let j = jacobian(&q, base, &dual_measurements, &dual_targets)?;
    let inverse = j.try_inverse().ok_or_else(|| failed(iterations, norm))?;
    Ok(SeatedSolve {
        angles: q,
        iterations,
        residual: f.amax(),
        inverse,
    })
}

/// Step 5: the solved configuration on the scalar of the bicycle: one Newton step from the
/// f64 root `solve` with its f64 Jacobian, the residual evaluated on `T` (for `T = f64` a last
/// refinement; for dual numbers the root's exact derivative by the implicit function theorem).
pub fn seated_configuration<T: Real>(
    solve: &SeatedSolve,
    measurements: &YeadonMeasurements<f64>,
    base: &YeadonConfiguration<f64>,
    geometry: &RiderGeometry<T>,
    w: T,
    r_r: T,
    r_f: T,
) -> Result<YeadonConfiguration<T>> {
    let bb = bottom_bracket(geometry, r_r)?;
    let grips = handlebar_grips(geometry, w, r_r, r_f)?;
    let t = targets(geometry, seat(geometry, bb), bb, grips);
    let q0 = solve.angles.map(c::<T>);
    let f = residual(&q0, base, &lift::<T>(measurements), &t)?;
    let q: [T; 6] = std::array::from_fn(|i| {
        (0..6).fold(q0[i], |acc, k| acc - c::<T>(solve.inverse[(i, k)]) * f[k])
    });
    Ok(configure(base, &q))
}

/// Step 6: the body's mass, mass centre and inertia (Yeadon's axes, origin at the seat) in the
/// benchmark's axes, the seat at `seat` (x, z).
pub fn rider_in_benchmark_frame<T: Real>(body: &YeadonBody<T>, seat: [T; 2]) -> RiderBody<T> {
    let r = yeadon_to_benchmark::<T>();
    RiderBody {
        mass: body.mass,
        center_of_mass: Vector3::new(seat[0], T::zero(), seat[1]) + r * body.center_of_mass,
        inertia: r * body.inertia * r.transpose(),
    }
}

/// Step 7: the bicycle with the rider added to its rear frame B: masses added, the mass centre
/// their mean, the inertias moved to it by the parallel-axis theorem; everything else as it
/// was. The rider's y offset and its products Ixy, Iyz (zero for a rider seated symmetrically)
/// are not part of the benchmark's plane-symmetric rear frame.
pub fn combine_with_rear_frame<T: Real>(
    bicycle: &BenchmarkParameters<T>,
    rider: &RiderBody<T>,
) -> BenchmarkParameters<T> {
    let b = bicycle;
    let frame = PlaneBody {
        m: b.m_b,
        x: b.x_b,
        z: b.z_b,
        i_xx: b.i_bxx,
        i_yy: b.i_byy,
        i_zz: b.i_bzz,
        i_xz: b.i_bxz,
    };
    let i = &rider.inertia;
    let person = PlaneBody {
        m: rider.mass,
        x: rider.center_of_mass.x,
        z: rider.center_of_mass.z,
        i_xx: i[(0, 0)],
        i_yy: i[(1, 1)],
        i_zz: i[(2, 2)],
        i_xz: i[(0, 2)],
    };
    let t = PlaneBody::combine(&[person, frame]);
    BenchmarkParameters {
        m_b: t.m,
        x_b: t.x,
        z_b: t.z,
        i_bxx: t.i_xx,
        i_byy: t.i_yy,
        i_bzz: t.i_zz,
        i_bxz: t.i_xz,
        ..*b
    }
}

/// Steps 1–3 and 5–6 on the scalar of the bicycle, after [`solve_seated`] found the angles:
/// the rider seated, everything it took.
#[allow(clippy::too_many_arguments)]
pub fn seated_rider<T: Real>(
    solve: &SeatedSolve,
    measurements: &YeadonMeasurements<f64>,
    base: &YeadonConfiguration<f64>,
    geometry: &RiderGeometry<T>,
    w: T,
    r_r: T,
    r_f: T,
) -> Result<SeatedRider<T>> {
    let bb = bottom_bracket(geometry, r_r)?;
    let seat_point = seat(geometry, bb);
    let grips = handlebar_grips(geometry, w, r_r, r_f)?;
    let configuration = seated_configuration(solve, measurements, base, geometry, w, r_r, r_f)?;
    let body = yeadon_body(&lift::<T>(measurements), &configuration)?;
    let rider = rider_in_benchmark_frame(&body, seat_point);
    Ok(SeatedRider {
        solve: solve.clone(),
        bottom_bracket: bb,
        seat: seat_point,
        grips,
        configuration,
        body,
        rider,
    })
}

/// The whole of `add_rider` on f64: the rider of `measurements`, in the configuration `base`
/// (whose solved angles are replaced), seated on the bicycle of `geometry` and `bicycle`'s
/// `rR`, `rF` and `w`; the bicycle with the rider in its rear frame.
///
/// ```
/// use whipple::advanced::rider::{
///     read_yeadon_configuration, read_yeadon_measurements, rider_on_bicycle, RiderGeometry,
/// };
/// # let meas = include_str!("../../tests/data/yeadon/JasonYeadonMeas.txt");
/// # let cfg = include_str!("../../tests/data/yeadon/JasonBrowserYeadonCFG.txt");
/// let bicycle = whipple::BenchmarkParameters::meijaard2007();
/// // Browser's seat and handlebar (BrowserMeasured.txt).
/// let geometry = RiderGeometry::from_array([0.46, 0.295, 0.24, 0.53, 1.195550538, 0.58, 0.893, 0.9213]);
/// let (seated, with_rider) = rider_on_bicycle(
///     &bicycle, &geometry, &read_yeadon_measurements(meas)?, &read_yeadon_configuration(cfg)?)?;
/// assert!(seated.solve.residual < 1e-10);
/// assert!((with_rider.m_b - (bicycle.m_b + seated.rider.mass)).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn rider_on_bicycle(
    bicycle: &BenchmarkParameters,
    geometry: &RiderGeometry<f64>,
    measurements: &YeadonMeasurements<f64>,
    base: &YeadonConfiguration<f64>,
) -> Result<(SeatedRider<f64>, BenchmarkParameters)> {
    let (w, r_r, r_f) = (bicycle.w, bicycle.r_r, bicycle.r_f);
    let solve = solve_seated(measurements, base, geometry, w, r_r, r_f)?;
    let seated = seated_rider(&solve, measurements, base, geometry, w, r_r, r_f)?;
    let combined = combine_with_rear_frame(bicycle, &seated.rider);
    Ok((seated, combined))
}
