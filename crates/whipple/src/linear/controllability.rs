//! Controllability of the linearized bicycle: can an input steer every mode?
//!
//! # Three answers
//!
//! - **The Kalman matrix** W = [B, AB, …, Aⁿ⁻¹B] of one input or of all, at one speed: its
//!   singular values, numerical rank and condition ([`LinearSystem::controllability`]). A
//!   numerical answer, sampled at the speed asked: the rank is decided against a tolerance,
//!   and the condition depends on the states' units (radians and radians per second here).
//! - **Modal controllability** of each lean–steer mode ([`LinearSystem::modal_controllability`]):
//!   the cosine of the angle between the mode's left eigenvector ℓ (ℓᵀA = λℓᵀ) and the input's
//!   column b, |ℓᵀb| / (‖ℓ‖ ‖b‖) (Hamdan & Nayfeh 1989, J. Guid. Control Dyn. 12:421): 0 for a
//!   mode the input cannot reach, 1 for one it reaches best.
//! - **The speeds where an input loses a mode**, certified ([`uncontrollable_speeds`]): found as
//!   the real roots of a polynomial in v, so none can be missed.
//!
//! # Where a single input cannot control the bicycle
//!
//! With P(λ) = M λ² + v C₁ λ + g K₀ + v² K₂ and the input's generalized forces f (per unit
//! input), the pair (A, b) loses a mode λ exactly when a left eigenvector is orthogonal to b
//! (the Popov–Belevitch–Hautus test). For the second-order form the left eigenvectors are
//! ℓ = [λ Mᵀu + v C₁ᵀu; Mᵀu] with uᵀP(λ) = 0 (substitute into ℓᵀA = λℓᵀ), and ℓᵀb = uᵀf. So
//! with two degrees of freedom u must be f⊥ = (−f₂, f₁) and the mode is lost when both
//! entries of f⊥ᵀP(λ) vanish at one λ: two quadratics in λ,
//!
//! r_j(λ) = α_j λ² + v β_j λ + (γ_j + κ_j v²),  j = 1, 2,
//!
//! with α_j = f⊥ᵀMe_j, β_j = f⊥ᵀC₁e_j, γ_j = g f⊥ᵀK₀e_j and κ_j = f⊥ᵀK₂e_j, have a common
//! root. Their resultant (Sylvester's 4 × 4 determinant, in closed form
//! (a₂b₀ − a₀b₂)² − (a₂b₁ − a₁b₂)(a₁b₀ − a₀b₁)) is
//!
//! R(v) = p² + (2pq − st) v² + (q² − su) v⁴,
//!
//! with p = α₁γ₂ − α₂γ₁, q = α₁κ₂ − α₂κ₁, s = α₁β₂ − α₂β₁ and t + u v² the bracket of
//! β₁(γ₂ + κ₂v²) − β₂(γ₁ + κ₁v²). Since M is positive definite, α₁ and α₂ are not both zero, so
//! R(v) = 0 exactly when the quadratics share a root (complex or real). R is even in v (riding
//! backwards loses the same modes), a quadratic in v²: its real roots are certified with the
//! crate's root finder ([`crate::analysis::roots::real_roots`]), the coefficients' round-off
//! bounded by the same expansion with absolute values. For steer torque on the benchmark
//! bicycle (f = (0, 1): u = (−1, 0), the lean equation's row) it has two positive roots: at
//! those two speeds the lean equation alone has a solution e^{λt}, a motion steer torque
//! cannot excite or suppress.
//!
//! The ignorable coordinates (yaw, the rear contact's position, the wheels' angles) add only
//! zero eigenvalues; the certified speeds concern the four lean–steer modes. The Kalman matrix
//! of a system with those states shows their own losses (the forward position and the wheels'
//! angles cannot be changed by any input to first order).

use nalgebra::{DMatrix, DVector, Vector2};

use super::{Canonical, LinearSystem};
use crate::analysis::eigen::{Complex64, eigenvalues};
use crate::analysis::roots::{BoundedPolynomial, RealRoot, UNIT_ROUNDOFF, real_roots};
use crate::error::{Error, Result};
use crate::linear::system::{Geometry, Input, SystemRequest};
use crate::parameters::BenchmarkParameters;

/// The Kalman controllability matrix's numerical answer at one speed.
#[derive(Debug, Clone, PartialEq)]
pub struct Controllability {
    /// Its singular values, largest first.
    pub singular_values: Vec<f64>,
    /// The numerical rank: how many singular values exceed [`Self::tolerance`].
    pub rank: usize,
    /// The tolerance the rank is decided against: max(rows, columns) · ε · σ_max.
    pub tolerance: f64,
    /// σ_max / σ_min (+∞ when σ_min is zero); depends on the states' units.
    pub condition: f64,
    /// The number of states: the rank of a controllable pair.
    pub states: usize,
}

impl Controllability {
    /// Whether the numerical rank is full.
    pub fn is_full_rank(&self) -> bool {
        self.rank == self.states
    }
}

/// How well one input reaches one lean–steer mode at one speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalControllability {
    /// The mode's eigenvalue λ [1/s].
    pub eigenvalue: Complex64,
    /// |ℓᵀb| / (‖ℓ‖ ‖b‖) in [0, 1], ℓ the mode's left eigenvector and b the input's column.
    pub measure: f64,
}

/// A speed where one input cannot control one lean–steer mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UncontrollableSpeed {
    /// The speed, certified: a simple root with its enclosure, or an unresolved cluster
    /// (near-double root) whose extent holds the speed(s) [m/s].
    pub speed: RealRoot,
    /// The eigenvalue of the mode the input cannot reach there [1/s] (from the lean–steer
    /// equations at the root's value).
    pub eigenvalue: Complex64,
}

/// The positive speeds where an input loses a lean–steer mode ([`uncontrollable_speeds`]).
#[derive(Debug, Clone, PartialEq)]
pub struct UncontrollableSpeeds {
    /// The input.
    pub input: Input,
    /// The speeds, increasing (their negatives are lost too: R(v) is even).
    pub speeds: Vec<UncontrollableSpeed>,
    /// Whether the input cannot control the bicycle at any speed (it does no work on lean or
    /// steer, or its resultant is zero within round-off).
    pub everywhere: bool,
}

/// A value with a bound on the absolute values of every term that formed it, so that its
/// round-off is at most `depth · u · magnitude` (depth: the longest chain of operations).
#[derive(Debug, Clone, Copy)]
struct Bounded {
    value: f64,
    magnitude: f64,
}

impl Bounded {
    fn new(value: f64) -> Self {
        Bounded {
            value,
            magnitude: value.abs(),
        }
    }
    fn add(self, other: Bounded) -> Bounded {
        Bounded {
            value: self.value + other.value,
            magnitude: self.magnitude + other.magnitude,
        }
    }
    fn sub(self, other: Bounded) -> Bounded {
        Bounded {
            value: self.value - other.value,
            magnitude: self.magnitude + other.magnitude,
        }
    }
    fn mul(self, other: Bounded) -> Bounded {
        Bounded {
            value: self.value * other.value,
            magnitude: self.magnitude * other.magnitude,
        }
    }
    fn scale(self, k: f64) -> Bounded {
        Bounded {
            value: self.value * k,
            magnitude: self.magnitude * k.abs(),
        }
    }
}

/// The longest chain of roundings in the resultant's coefficients (a generous count: f⊥ᵀX e_j
/// two, the differences p … u three more, the products and sums of R four more).
const RESULTANT_DEPTH: f64 = 16.0;

/// The resultant R(v) = ρ₀ + ρ₁ v² + ρ₂ v⁴ of the module documentation as a bounded
/// polynomial in w = v², for generalized forces `f`.
fn resultant(canonical: &Canonical, f: Vector2<f64>) -> BoundedPolynomial<3> {
    let perp = [Bounded::new(-f[1]), Bounded::new(f[0])];
    let row = |x: &nalgebra::Matrix2<f64>, j: usize, k: f64| -> Bounded {
        perp[0]
            .mul(Bounded::new(x[(0, j)]))
            .add(perp[1].mul(Bounded::new(x[(1, j)])))
            .scale(k)
    };
    let g = canonical.g;
    let (a1, a2) = (row(&canonical.m, 0, 1.0), row(&canonical.m, 1, 1.0));
    let (b1, b2) = (row(&canonical.c1, 0, 1.0), row(&canonical.c1, 1, 1.0));
    let (g1, g2) = (row(&canonical.k0, 0, g), row(&canonical.k0, 1, g));
    let (k1, k2) = (row(&canonical.k2, 0, 1.0), row(&canonical.k2, 1, 1.0));
    let p = a1.mul(g2).sub(a2.mul(g1));
    let q = a1.mul(k2).sub(a2.mul(k1));
    let s = a1.mul(b2).sub(a2.mul(b1));
    let t = b1.mul(g2).sub(b2.mul(g1));
    let u = b1.mul(k2).sub(b2.mul(k1));
    let rho = [
        p.mul(p),
        p.mul(q).scale(2.0).sub(s.mul(t)),
        q.mul(q).sub(s.mul(u)),
    ];
    BoundedPolynomial {
        coefficients: rho.map(|r| r.value),
        bounds: rho.map(|r| RESULTANT_DEPTH * UNIT_ROUNDOFF * r.magnitude),
    }
}

/// The positive speeds at which `input` alone cannot control one of the bicycle's lean–steer
/// modes, certified (see the module documentation): each a root of a polynomial in v, with an
/// enclosure, so none is missed; and the eigenvalue of the mode lost there.
///
/// Errors: invalid parameters, a lateral force at a point that is not finite or lies inside
/// nothing (as [`LinearSystem::new`] refuses it), and
/// [`Error::AccuracyLost`] when round-off leaves the polynomial's roots undecided.
///
/// ```
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::uncontrollable_speeds;
/// use whipple::advanced::linear::Input;
/// let lost = uncontrollable_speeds(&BenchmarkParameters::meijaard2007(), &Input::SteerTorque)?;
/// assert_eq!(lost.speeds.len(), 2);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn uncontrollable_speeds(
    bike: &BenchmarkParameters,
    input: &Input,
) -> Result<UncontrollableSpeeds> {
    let canonical = Canonical::new(bike)?;
    if let Input::LateralForce { x, z } = input
        && !(x.is_finite() && z.is_finite())
    {
        return Err(Error::InvalidArgument {
            what: "inputs",
            rule: format!("the point of {input} must have finite coordinates"),
        });
    }
    SystemRequest {
        states: Vec::new(),
        inputs: vec![*input],
        outputs: Vec::new(),
    }
    .check_points(bike)?;
    let geometry = Geometry::of(bike);
    let f = Vector2::from(geometry.generalized_forces(input));
    let none = |everywhere| UncontrollableSpeeds {
        input: *input,
        speeds: Vec::new(),
        everywhere,
    };
    if f == Vector2::zeros() {
        return Ok(none(true));
    }
    let r = resultant(&canonical, f);
    let roots = real_roots(&r, "the controllability resultant")?;
    if roots.degree.is_none() {
        return Ok(none(true));
    }
    if roots.horizon.is_finite() {
        return Err(Error::AccuracyLost {
            quantity: format!("the speeds where {input} cannot control the bicycle"),
            reason: format!(
                "the resultant's leading coefficient is lost to round-off (its roots in v² are \
                 certified below {:e} only)",
                roots.horizon
            ),
        });
    }
    let mut speeds = Vec::new();
    for root in roots.as_slice() {
        let (lo, hi) = root.enclosure();
        if hi <= 0.0 {
            continue; // a negative v²: no real speed
        }
        let sqrt = |w: f64| w.max(0.0).sqrt();
        let speed = match *root {
            RealRoot::Simple { value, .. } if lo > 0.0 => RealRoot::Simple {
                value: sqrt(value),
                lo: sqrt(lo),
                hi: sqrt(hi),
            },
            // A root at or through v² = 0 (or a cluster): its extent in v, unresolved.
            _ => RealRoot::Cluster {
                lo: sqrt(lo),
                hi: sqrt(hi),
                count: match *root {
                    RealRoot::Cluster { count, .. } => count,
                    RealRoot::Simple { .. } => 1,
                },
            },
        };
        speeds.push(UncontrollableSpeed {
            speed,
            eigenvalue: common_root(&canonical, f, speed.value()),
        });
    }
    Ok(UncontrollableSpeeds {
        input: *input,
        speeds,
        everywhere: false,
    })
}

/// The root λ of f⊥ᵀP(λ)e_j (the better-conditioned of the two quadratics) nearer to a root of
/// the other at `speed`: the mode lost there.
fn common_root(canonical: &Canonical, f: Vector2<f64>, speed: f64) -> Complex64 {
    let perp = Vector2::new(-f[1], f[0]);
    let coefficients = |j: usize| -> [f64; 3] {
        let col = |x: &nalgebra::Matrix2<f64>| perp.dot(&x.column(j));
        [
            canonical.g * col(&canonical.k0) + speed * speed * col(&canonical.k2),
            speed * col(&canonical.c1),
            col(&canonical.m),
        ]
    };
    let quadratics = [coefficients(0), coefficients(1)];
    let roots_of = |c: [f64; 3]| -> Vec<Complex64> {
        if c[2] == 0.0 {
            return if c[1] == 0.0 {
                Vec::new()
            } else {
                vec![Complex64::new(-c[0] / c[1], 0.0)]
            };
        }
        let disc = crate::math::complex_sqrt(Complex64::new(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0));
        // The root of larger magnitude first, the other from the product (no cancellation).
        let sign = if c[1] >= 0.0 { 1.0 } else { -1.0 };
        let big = -(c[1] + sign * disc) / (2.0 * c[2]);
        let small = if crate::math::norm(big) > 0.0 {
            Complex64::new(c[0] / c[2], 0.0) / big
        } else {
            Complex64::new(0.0, 0.0)
        };
        vec![big, small]
    };
    let value = |c: [f64; 3], z: Complex64| (z * c[2] + c[1]) * z + c[0];
    let scale = |c: [f64; 3], z: Complex64| {
        c[2].abs() * z.norm_sqr() + c[1].abs() * crate::math::norm(z) + c[0].abs()
    };
    let mut best = (f64::INFINITY, Complex64::new(f64::NAN, f64::NAN));
    for (j, c) in quadratics.iter().enumerate() {
        let other = quadratics[1 - j];
        for z in roots_of(*c) {
            let misfit =
                crate::math::norm(value(other, z)) / scale(other, z).max(f64::MIN_POSITIVE);
            if misfit < best.0 {
                best = (misfit, z);
            }
        }
    }
    // A real common root of a real pair: drop the round-off's imaginary part.
    let z = best.1;
    if z.im.abs() <= 1e-8 * crate::math::norm(z) {
        Complex64::new(z.re, 0.0)
    } else {
        z
    }
}

impl LinearSystem {
    /// The Kalman controllability matrix [b, Ab, …, Aⁿ⁻¹b] of input `input` (its index), or of
    /// all inputs together when `None`: singular values, numerical rank and condition. A
    /// numerical answer at this speed; [`uncontrollable_speeds`] finds, certified, the speeds
    /// where a lean–steer mode is lost.
    ///
    /// Errors: an input index out of range, a system without inputs.
    pub fn controllability(&self, input: Option<usize>) -> Result<Controllability> {
        let b = match input {
            Some(j) => {
                DMatrix::from_column_slice(self.a().nrows(), 1, self.input_column(j)?.as_slice())
            }
            None if self.b().ncols() > 0 => self.b().clone(),
            None => {
                return Err(Error::InvalidArgument {
                    what: "inputs",
                    rule: "the system has no inputs to control it with".into(),
                });
            }
        };
        let n = self.a().nrows();
        let m = b.ncols();
        let mut w = DMatrix::zeros(n, n * m);
        let mut block = b;
        for k in 0..n {
            w.view_mut((0, k * m), (n, m)).copy_from(&block);
            block = self.a() * block;
        }
        let mut singular_values: Vec<f64> = w.singular_values().iter().copied().collect();
        singular_values.sort_by(|x, y| y.total_cmp(x));
        let largest = singular_values.first().copied().unwrap_or(0.0);
        let tolerance = (n.max(n * m) as f64) * f64::EPSILON * largest;
        let rank = singular_values.iter().filter(|s| **s > tolerance).count();
        let smallest = if singular_values.len() >= n {
            singular_values[n - 1]
        } else {
            0.0
        };
        let condition = if smallest > 0.0 {
            largest / smallest
        } else {
            f64::INFINITY
        };
        Ok(Controllability {
            singular_values,
            rank,
            tolerance,
            condition,
            states: n,
        })
    }

    /// How well input `input` (its index) reaches each of the four lean–steer modes at this
    /// speed: |ℓᵀb| / (‖ℓ‖ ‖b‖) with ℓ the mode's left eigenvector (see the module
    /// documentation), in the order of the certified eigenvalues. The ignorable coordinates do
    /// not change it: a left eigenvector of a non-zero eigenvalue is zero on them.
    ///
    /// Errors: an input index out of range; eigenvalues that cannot be certified.
    pub fn modal_controllability(&self, input: usize) -> Result<Vec<ModalControllability>> {
        let column = self.input_column(input)?;
        let f = self.forces.column(input).into_owned();
        let canonical = self.canonical();
        let v = self.speed();
        let b_norm = column.norm();
        let values = eigenvalues(canonical, v)?;
        let cx = |x: f64| Complex64::new(x, 0.0);
        Ok(values
            .iter()
            .map(|&lambda| {
                let p = |i: usize, j: usize| {
                    lambda * lambda * canonical.m[(i, j)]
                        + lambda * (v * canonical.c1[(i, j)])
                        + cx(canonical.g * canonical.k0[(i, j)] + v * v * canonical.k2[(i, j)])
                };
                // A left null vector of P(λ): the larger of its two adjugate rows.
                let first = [p(1, 1), -p(0, 1)];
                let second = [-p(1, 0), p(0, 0)];
                let size = |u: &[Complex64; 2]| u[0].norm_sqr() + u[1].norm_sqr();
                let u = if size(&first) >= size(&second) {
                    first
                } else {
                    second
                };
                // ℓ = [λ Mᵀu + v C₁ᵀu; Mᵀu].
                let times_transpose = |x: &nalgebra::Matrix2<f64>, k: usize| {
                    cx(x[(0, k)]) * u[0] + cx(x[(1, k)]) * u[1]
                };
                let lower = [
                    times_transpose(&canonical.m, 0),
                    times_transpose(&canonical.m, 1),
                ];
                let upper = [
                    lambda * lower[0] + times_transpose(&canonical.c1, 0) * v,
                    lambda * lower[1] + times_transpose(&canonical.c1, 1) * v,
                ];
                let ell_norm = upper
                    .iter()
                    .chain(&lower)
                    .map(|z| z.norm_sqr())
                    .sum::<f64>()
                    .sqrt();
                let projection = u[0] * f[0] + u[1] * f[1];
                let measure = if ell_norm > 0.0 && b_norm > 0.0 {
                    (crate::math::norm(projection) / (ell_norm * b_norm)).min(1.0)
                } else {
                    0.0
                };
                ModalControllability {
                    eigenvalue: lambda,
                    measure,
                }
            })
            .collect())
    }

    /// B's column of input `j`, or an error naming `inputs`.
    fn input_column(&self, j: usize) -> Result<DVector<f64>> {
        if j >= self.b().ncols() {
            return Err(Error::InvalidArgument {
                what: "inputs",
                rule: format!(
                    "input {} does not exist: the system has {}",
                    j + 1,
                    self.b().ncols()
                ),
            });
        }
        Ok(self.b().column(j).into_owned())
    }
}
