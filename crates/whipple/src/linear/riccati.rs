//! Gains by design: the linear–quadratic regulator (the continuous algebraic Riccati equation)
//! and pole placement for one input.
//!
//! # The Riccati solver
//!
//! The stabilizing solution X of AᵀX + XA − X G X + Q = 0, G = B R⁻¹ Bᵀ, spans the stable
//! invariant subspace of the Hamiltonian matrix H = [[A, −G], [−Q, −Aᵀ]]: if the columns of
//! [U₁; U₂] span the eigenvectors of H's n eigenvalues of negative real part, X = U₂ U₁⁻¹
//! (complex arithmetic, the conjugate pairs making X real up to round-off; its real part is
//! kept and symmetrized). H's eigenvalues come in pairs λ, −λ̄, so there are exactly n stable
//! ones unless some lie on the imaginary axis: then no stabilizing solution exists, because
//! either (A, B) is not stabilizable (a mode of non-negative real part that no input moves),
//! or (Q, A) has an unobservable mode on the imaginary axis (a mode that Q does not weigh,
//! such as yaw ψ or the lateral position y at λ = 0 when Q leaves them out). The solver tells
//! which, naming the field to change.
//!
//! That first X is then refined by Newton–Kleinman steps (Kleinman 1968): with K = R⁻¹BᵀX and
//! A_K = A − BK, the next X solves the Lyapunov equation A_Kᵀ X + X A_K = −(Q + KᵀRK), here by
//! its Kronecker form (n² unknowns; n ≤ [`MAX_RICCATI_STATES`]). The X of smallest residual is
//! kept; the solver checks its relative residual
//! ‖AᵀX + XA − XGX + Q‖ / (‖AᵀX‖ + ‖XA‖ + ‖XGX‖ + ‖Q‖) (Frobenius norms) and that every
//! eigenvalue of A − BK has negative real part, and reports both.

use nalgebra::DMatrix;

use super::feedback::{Gains, matrix_eigenvalues};
use super::system::{LinearSystem, SystemRequest};
use crate::analysis::eigen::Complex64;
use crate::error::{Error, Result, short_number};
use crate::parameters::BenchmarkParameters;

/// The most states the Riccati solver takes (its Lyapunov steps solve n² unknowns).
pub const MAX_RICCATI_STATES: usize = 16;

/// A relative residual above this is refused ([`Error::AccuracyLost`]).
pub const MAX_RICCATI_RESIDUAL: f64 = 1e-8;

/// Newton–Kleinman steps at most.
const MAX_NEWTON_STEPS: usize = 30;

/// An eigenvalue of the Hamiltonian this close to the imaginary axis, relative to its norm,
/// counts as on it.
const AXIS_TOLERANCE: f64 = 1e-9;

/// The stabilizing solution of a continuous algebraic Riccati equation and what it gives.
#[derive(Debug, Clone, PartialEq)]
pub struct Lqr {
    /// K = R⁻¹ Bᵀ X (inputs × states): u = −K x minimizes ∫ xᵀQx + uᵀRu dt.
    pub gains: DMatrix<f64>,
    /// X, symmetric (states × states).
    pub solution: DMatrix<f64>,
    /// The relative residual of the Riccati equation at X (see the module documentation).
    pub residual: f64,
    /// The eigenvalues of A − B K, every one of negative real part (sorted by decreasing real
    /// part).
    pub closed_loop_eigenvalues: Vec<Complex64>,
    /// Newton–Kleinman steps taken after the invariant subspace.
    pub newton_steps: usize,
}

fn bad(what: &'static str, rule: String) -> Error {
    Error::InvalidArgument { what, rule }
}

fn frobenius(m: &DMatrix<f64>) -> f64 {
    m.norm()
}

/// Q: n × n, finite, symmetric (to 1e-12 of its size), positive semi-definite.
fn check_q(q: &DMatrix<f64>, n: usize) -> Result<()> {
    if q.shape() != (n, n) {
        return Err(bad(
            "Q",
            format!(
                "must be states × states = {n} × {n}, got {} × {}",
                q.nrows(),
                q.ncols()
            ),
        ));
    }
    check_finite("Q", q)?;
    check_symmetric("Q", q)?;
    let size = q.amax();
    let eig = nalgebra::SymmetricEigen::new(q.clone());
    let least = eig.eigenvalues.min();
    if least < -1e-12 * size {
        return Err(bad(
            "Q",
            format!(
                "must be positive semi-definite: it has the eigenvalue {}",
                short_number(least)
            ),
        ));
    }
    Ok(())
}

/// R: m × m, finite, symmetric, positive definite (every eigenvalue above 1e-12 of the
/// largest).
fn check_r(r: &DMatrix<f64>, m: usize) -> Result<()> {
    if r.shape() != (m, m) {
        return Err(bad(
            "R",
            format!(
                "must be inputs × inputs = {m} × {m}, got {} × {}",
                r.nrows(),
                r.ncols()
            ),
        ));
    }
    check_finite("R", r)?;
    check_symmetric("R", r)?;
    let eig = nalgebra::SymmetricEigen::new(r.clone());
    let (least, largest) = (eig.eigenvalues.min(), eig.eigenvalues.amax());
    if least.is_nan() || least <= 1e-12 * largest {
        return Err(bad(
            "R",
            format!(
                "must be positive definite (so that it can be inverted): its smallest \
                 eigenvalue is {}",
                short_number(least)
            ),
        ));
    }
    Ok(())
}

fn check_finite(what: &'static str, m: &DMatrix<f64>) -> Result<()> {
    if let Some(x) = m.iter().find(|x| !x.is_finite()) {
        return Err(bad(what, format!("every entry must be finite, got {x}")));
    }
    Ok(())
}

fn check_symmetric(what: &'static str, m: &DMatrix<f64>) -> Result<()> {
    let n = m.nrows();
    for i in 0..n {
        for j in 0..i {
            let (a, b) = (m[(i, j)], m[(j, i)]);
            if (a - b).abs() > 1e-12 * m.amax() {
                return Err(bad(
                    what,
                    format!("must be symmetric: entry ({i}, {j}) is {a}, entry ({j}, {i}) is {b}"),
                ));
            }
        }
    }
    Ok(())
}

/// The residual AᵀX + XA − XGX + Q and its relative size.
fn residual(a: &DMatrix<f64>, g: &DMatrix<f64>, q: &DMatrix<f64>, x: &DMatrix<f64>) -> f64 {
    let atx = a.transpose() * x;
    let xa = x * a;
    let xgx = x * g * x;
    let r = &atx + &xa - &xgx + q;
    let scale = frobenius(&atx) + frobenius(&xa) + frobenius(&xgx) + frobenius(q);
    if scale == 0.0 {
        0.0
    } else {
        frobenius(&r) / scale
    }
}

/// Solves A_Kᵀ X + X A_K = −W by the Kronecker form (column-major vec).
fn lyapunov(ak: &DMatrix<f64>, w: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = ak.nrows();
    let at = ak.transpose();
    let mut big = DMatrix::zeros(n * n, n * n);
    // vec(Aᵀ X) = (I ⊗ Aᵀ) vec X; vec(X A) = (Aᵀ ⊗ I) vec X.
    for col in 0..n {
        for i in 0..n {
            for k in 0..n {
                big[(col * n + i, col * n + k)] += at[(i, k)];
                big[(col * n + i, k * n + i)] += ak[(k, col)];
            }
        }
    }
    let rhs = DMatrix::from_iterator(n * n, 1, w.iter().map(|x| -x));
    let sol = big.lu().solve(&rhs)?;
    let x = DMatrix::from_iterator(n, n, sol.iter().copied());
    Some((&x + x.transpose()) * 0.5)
}

/// Why the Hamiltonian has eigenvalues on the imaginary axis: an uncontrollable mode of
/// non-negative real part (naming `inputs`), or else a mode Q does not see (naming `Q`).
fn no_solution(a: &DMatrix<f64>, b: &DMatrix<f64>, states: &[String]) -> Result<Error> {
    let n = a.nrows();
    let scale = a.amax().max(b.amax()).max(f64::MIN_POSITIVE);
    for lambda in matrix_eigenvalues(a)? {
        if lambda.re < -AXIS_TOLERANCE * scale.max(1.0) {
            continue;
        }
        // Popov–Belevitch–Hautus: rank [A − λI, B] < n ⇔ the mode is uncontrollable.
        let m = DMatrix::from_fn(n, n + b.ncols(), |i, j| {
            if j < n {
                Complex64::new(a[(i, j)], 0.0)
                    - if i == j {
                        lambda
                    } else {
                        Complex64::new(0.0, 0.0)
                    }
            } else {
                Complex64::new(b[(i, j - n)], 0.0)
            }
        });
        let sv = m.singular_values();
        if sv.min() <= 1e-10 * sv.max() {
            return Ok(bad(
                "inputs",
                format!(
                    "no stabilizing solution: the mode λ = {} is not stabilizable (no input \
                     moves it; the states {} include ones no input reaches, such as the rear \
                     contact's x or the wheel angles): remove such states from the system or \
                     add an input that reaches them",
                    text(lambda),
                    states.join(", ")
                ),
            ));
        }
    }
    Ok(bad(
        "Q",
        "no stabilizing solution: a mode on the imaginary axis is not weighted by Q (for \
         example yaw ψ or the rear contact's y at λ = 0, when their diagonal entries of Q are \
         zero): give those states a positive weight in Q, or leave them out of the system"
            .into(),
    ))
}

fn text(z: Complex64) -> String {
    if z.im == 0.0 {
        short_number(z.re)
    } else {
        format!(
            "{} {} {}i",
            short_number(z.re),
            if z.im < 0.0 { "−" } else { "+" },
            short_number(z.im.abs())
        )
    }
}

/// The stabilizing solution of AᵀX + XA − X B R⁻¹ Bᵀ X + Q = 0 and the gain K = R⁻¹BᵀX, for
/// any A (n × n, n ≤ [`MAX_RICCATI_STATES`]), B (n × m), Q (symmetric positive semi-definite)
/// and R (symmetric positive definite); `states` names the states for messages. Errors name
/// `Q` or `R` (shape, symmetry, definiteness), `inputs` (the pair is not stabilizable) or `Q`
/// (an unobservable mode on the imaginary axis); [`Error::AccuracyLost`] when the residual
/// exceeds [`MAX_RICCATI_RESIDUAL`] or A − BK is not stable.
///
/// ```
/// use nalgebra::DMatrix;
/// use whipple::advanced::control::care;
/// // The double integrator with Q = I, R = 1: X = [[√3, 1], [1, √3]], K = [1, √3].
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
/// let lqr = care(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1))?;
/// assert!((lqr.gains[(0, 1)] - 3f64.sqrt()).abs() < 1e-12);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn care(a: &DMatrix<f64>, b: &DMatrix<f64>, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr> {
    if a.nrows() != a.ncols() || b.nrows() != a.nrows() {
        return Err(bad(
            "A",
            format!(
                "A must be square and B have as many rows: A is {} × {}, B {} × {}",
                a.nrows(),
                a.ncols(),
                b.nrows(),
                b.ncols()
            ),
        ));
    }
    check_finite("A", a)?;
    check_finite("B", b)?;
    let names: Vec<String> = (1..=a.nrows()).map(|k| format!("x{k}")).collect();
    care_named(a, b, q, r, &names)
}

/// [`care`] with the states named for messages.
fn care_named(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    states: &[String],
) -> Result<Lqr> {
    let (n, m) = (a.nrows(), b.ncols());
    if n > MAX_RICCATI_STATES {
        return Err(bad(
            "states",
            format!("the Riccati solver takes at most {MAX_RICCATI_STATES} states, got {n}"),
        ));
    }
    if m == 0 {
        return Err(bad("inputs", "LQR needs at least one input".into()));
    }
    check_q(q, n)?;
    check_r(r, m)?;
    let r_inv = r
        .clone()
        .try_inverse()
        .ok_or_else(|| bad("R", "must be invertible".into()))?;
    let g = b * &r_inv * b.transpose();
    let g = (&g + g.transpose()) * 0.5;
    let mut h = DMatrix::zeros(2 * n, 2 * n);
    h.view_mut((0, 0), (n, n)).copy_from(a);
    h.view_mut((0, n), (n, n)).copy_from(&(-&g));
    h.view_mut((n, 0), (n, n)).copy_from(&(-q));
    h.view_mut((n, n), (n, n)).copy_from(&(-a.transpose()));
    let hf = faer::Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| h[(i, j)]);
    let evd = hf
        .eigen()
        .map_err(crate::analysis::comparison::faer_failure)?;
    let (u, s) = (evd.U(), evd.S().column_vector());
    let size = h.amax().max(f64::MIN_POSITIVE);
    let mut stable = Vec::with_capacity(n);
    for k in 0..2 * n {
        let re = s[k].re;
        if re.abs() <= AXIS_TOLERANCE * size {
            return Err(no_solution(a, b, states)?);
        }
        if re < 0.0 {
            stable.push(k);
        }
    }
    if stable.len() != n {
        return Err(no_solution(a, b, states)?);
    }
    let at = |i: usize, j: usize| {
        let z = u[(i, j)];
        Complex64::new(z.re, z.im)
    };
    let u1 = DMatrix::from_fn(n, n, |i, j| at(i, stable[j]));
    let u2 = DMatrix::from_fn(n, n, |i, j| at(n + i, stable[j]));
    let x0 = u1
        .transpose()
        .lu()
        .solve(&u2.transpose())
        .ok_or_else(|| no_solution(a, b, states).unwrap_or_else(|e| e))?
        .transpose();
    let x0 = x0.map(|z| z.re);
    let mut x = (&x0 + x0.transpose()) * 0.5;
    let mut best = residual(a, &g, q, &x);
    let mut steps = 0;
    for _ in 0..MAX_NEWTON_STEPS {
        let k = &r_inv * b.transpose() * &x;
        let ak = a - b * &k;
        let w = q + k.transpose() * r * &k;
        let Some(next) = lyapunov(&ak, &w) else {
            break;
        };
        let res = residual(a, &g, q, &next);
        if res.is_nan() || res >= best {
            break;
        }
        let gain = best / res;
        x = next;
        best = res;
        steps += 1;
        if gain < 1.5 {
            break;
        }
    }
    if best.is_nan() || best > MAX_RICCATI_RESIDUAL {
        return Err(Error::AccuracyLost {
            quantity: "the Riccati solution".into(),
            reason: format!("its relative residual is {best:e}, above {MAX_RICCATI_RESIDUAL:e}"),
        });
    }
    let gains = &r_inv * b.transpose() * &x;
    let mut values = matrix_eigenvalues(&(a - b * &gains))?;
    values.sort_by(|p, q| q.re.total_cmp(&p.re).then(q.im.total_cmp(&p.im)));
    if let Some(worst) = values.iter().find(|z| z.re.is_nan() || z.re >= 0.0) {
        return Err(Error::AccuracyLost {
            quantity: "the Riccati solution".into(),
            reason: format!(
                "A − BK keeps the eigenvalue {} (not of negative real part)",
                text(*worst)
            ),
        });
    }
    Ok(Lqr {
        gains,
        solution: x,
        residual: best,
        closed_loop_eigenvalues: values,
        newton_steps: steps,
    })
}

fn state_names(system: &LinearSystem) -> Vec<String> {
    system.states().iter().map(|s| s.to_string()).collect()
}

impl LinearSystem {
    /// The linear–quadratic regulator of this system: the K of u = −K x minimizing
    /// ∫ xᵀQx + uᵀRu dt, from the stabilizing solution of the continuous algebraic Riccati
    /// equation (see `linear::riccati`'s documentation), with its residual and the closed
    /// loop's eigenvalues.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
    /// let request = SystemRequest {
    ///     states: vec![],
    ///     inputs: vec![Input::SteerTorque],
    ///     outputs: vec![Output::State(StateVariable::Lean)],
    /// };
    /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 2.0, &request)?;
    /// let lqr = system.lqr(&DMatrix::identity(4, 4), &DMatrix::identity(1, 1))?;
    /// assert!(lqr.residual < 1e-12);
    /// assert!(lqr.closed_loop_eigenvalues.iter().all(|l| l.re < 0.0)); // 2 m/s, stabilized
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn lqr(&self, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr> {
        care_named(self.a(), self.b(), q, r, &state_names(self))
    }

    /// Single-input pole placement: the K (1 × states) for which A − B K has the eigenvalues
    /// `poles` (one per state, closed under conjugation to 1e-12 of their size), by
    /// Ackermann's formula K = e_nᵀ 𝒞⁻¹ φ(A) (𝒞 the controllability matrix, φ the polynomial
    /// with the poles as roots), then checked by the eigenvalues of A − B K (refused with
    /// [`Error::AccuracyLost`] when one lies further than 1e-6 of its size from its pole).
    /// Errors: more than one input (`inputs`), the wrong number of poles or a set not closed
    /// under conjugation (`poles`), an uncontrollable pair at this speed (`inputs`).
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::eigen::Complex64;
    /// use whipple::advanced::linear::{Input, LinearSystem, Output, StateVariable, SystemRequest};
    /// let request = SystemRequest {
    ///     states: vec![],
    ///     inputs: vec![Input::SteerTorque],
    ///     outputs: vec![Output::State(StateVariable::Lean)],
    /// };
    /// let system = LinearSystem::new(&BenchmarkParameters::meijaard2007(), 3.0, &request)?;
    /// let poles = [-2.0, -3.0].map(|re| Complex64::new(re, 0.0)).into_iter()
    ///     .chain([Complex64::new(-1.0, 2.0), Complex64::new(-1.0, -2.0)]).collect::<Vec<_>>();
    /// let k = system.place_poles(&poles)?;
    /// assert_eq!(k.shape(), (1, 4));
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn place_poles(&self, poles: &[Complex64]) -> Result<DMatrix<f64>> {
        place(self.a(), self.b(), poles)
    }
}

/// Ackermann's formula with its checks (see [`LinearSystem::place_poles`]).
pub(crate) fn place(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    poles: &[Complex64],
) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    if b.ncols() != 1 {
        return Err(bad(
            "inputs",
            format!(
                "pole placement takes a single input, the system has {}",
                b.ncols()
            ),
        ));
    }
    if poles.len() != n {
        return Err(bad(
            "poles",
            format!(
                "one pole per state is needed: {} for {n} states",
                poles.len()
            ),
        ));
    }
    if let Some(p) = poles
        .iter()
        .find(|p| !(p.re.is_finite() && p.im.is_finite()))
    {
        return Err(bad("poles", format!("every pole must be finite, got {p}")));
    }
    // Closed under conjugation: each pole matched with a distinct conjugate.
    let mut used = vec![false; n];
    for (i, p) in poles.iter().enumerate() {
        let tol = 1e-12 * crate::math::norm(p).max(1.0);
        if p.im.abs() <= tol {
            continue;
        }
        if used[i] {
            continue;
        }
        let partner =
            (0..n).find(|&j| j != i && !used[j] && crate::math::norm(poles[j] - p.conj()) <= tol);
        let Some(j) = partner else {
            return Err(bad(
                "poles",
                format!(
                    "the set must be closed under conjugation: {} has no conjugate",
                    text(*p)
                ),
            ));
        };
        used[i] = true;
        used[j] = true;
    }
    // φ(s) = Π (s − p), real coefficients, highest first.
    let mut phi = vec![Complex64::new(1.0, 0.0)];
    for p in poles {
        let mut next = vec![Complex64::new(0.0, 0.0); phi.len() + 1];
        for (k, c) in phi.iter().enumerate() {
            next[k] += c;
            next[k + 1] -= c * p;
        }
        phi = next;
    }
    let mut phi_a = DMatrix::<f64>::zeros(n, n);
    for c in &phi {
        phi_a = &phi_a * a + DMatrix::identity(n, n) * c.re;
    }
    let mut ctrb = DMatrix::zeros(n, n);
    let mut column = b.column(0).into_owned();
    for k in 0..n {
        ctrb.set_column(k, &column);
        column = a * column;
    }
    // Scale-free test of rank: the columns normalized, then the singular values.
    let normalized = DMatrix::from_fn(n, n, |i, j| {
        let norm = ctrb.column(j).norm();
        if norm > 0.0 { ctrb[(i, j)] / norm } else { 0.0 }
    });
    let sv = normalized.singular_values();
    if (sv.min() / sv.max()).is_nan() || sv.min() <= 1e-12 * sv.max() {
        return Err(bad(
            "inputs",
            format!(
                "the pair (A, B) is not controllable here (the controllability matrix's \
                 normalized singular values reach {:e}): the poles cannot be placed",
                sv.min() / sv.max()
            ),
        ));
    }
    let mut e = DMatrix::zeros(n, 1);
    e[(n - 1, 0)] = 1.0;
    let w = ctrb
        .transpose()
        .lu()
        .solve(&e)
        .ok_or_else(|| bad("inputs", "the controllability matrix is singular".into()))?;
    let k = w.transpose() * phi_a;
    let placed = matrix_eigenvalues(&(a - b * &k))?;
    let mut taken = vec![false; n];
    for p in poles {
        let best = (0..n).filter(|&j| !taken[j]).min_by(|&i, &j| {
            crate::math::norm(placed[i] - p).total_cmp(&crate::math::norm(placed[j] - p))
        });
        let Some(j) = best else { break };
        taken[j] = true;
        let d = crate::math::norm(placed[j] - p);
        if d.is_nan() || d > 1e-6 * crate::math::norm(p).max(1.0) {
            return Err(Error::AccuracyLost {
                quantity: "the placed poles".into(),
                reason: format!(
                    "A − BK has the eigenvalue {} for the pole {} (Ackermann's formula is \
                     ill-conditioned here)",
                    text(placed[j]),
                    text(*p)
                ),
            });
        }
    }
    Ok(k)
}

/// LQR gains scheduled over speeds, with each speed's solution.
#[derive(Debug, Clone, PartialEq)]
pub struct LqrSchedule {
    /// The gains, ready for [`super::feedback::ClosedLoop`] (interpolated linearly between the
    /// speeds).
    pub gains: Gains,
    /// The Riccati solution at each speed.
    pub solutions: Vec<Lqr>,
}

/// The LQR gains of the system `request` asks for at each of `speeds` (strictly increasing,
/// at least two) for the same Q and R: a gain schedule.
///
/// ```
/// use nalgebra::DMatrix;
/// use whipple::BenchmarkParameters;
/// use whipple::advanced::control::{ClosedLoop, lqr_schedule};
/// use whipple::advanced::linear::{Input, Output, StateVariable, SystemRequest};
/// let bike = BenchmarkParameters::meijaard2007();
/// let request = SystemRequest {
///     states: vec![],
///     inputs: vec![Input::SteerTorque],
///     outputs: vec![Output::State(StateVariable::Lean)],
/// };
/// let speeds = [1.0, 2.0, 4.0, 8.0];
/// let schedule = lqr_schedule(&bike, &request, &speeds, &DMatrix::identity(4, 4), &DMatrix::identity(1, 1))?;
/// let closed = ClosedLoop::new(&bike, &request, schedule.gains)?;
/// assert!(closed.eigenvalues(3.0)?.iter().all(|l| l.re < 0.0));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn lqr_schedule(
    bike: &BenchmarkParameters,
    request: &SystemRequest,
    speeds: &[f64],
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<LqrSchedule> {
    if speeds.len() > super::feedback::MAX_SCHEDULE_SPEEDS {
        return Err(bad(
            "speeds",
            format!(
                "at most {} speeds in a schedule, got {}",
                super::feedback::MAX_SCHEDULE_SPEEDS,
                speeds.len()
            ),
        ));
    }
    let mut solutions = Vec::with_capacity(speeds.len());
    for v in speeds {
        solutions.push(LinearSystem::new(bike, *v, request)?.lqr(q, r)?);
    }
    let gains = Gains::Scheduled {
        speeds: speeds.to_vec(),
        gains: solutions.iter().map(|s| s.gains.clone()).collect(),
    };
    // The schedule's own checks (speeds increasing, at least two).
    super::feedback::ClosedLoop::new(bike, request, gains.clone())?;
    Ok(LqrSchedule { gains, solutions })
}
