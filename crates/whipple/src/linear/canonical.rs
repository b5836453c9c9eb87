//! The canonical matrices of the linearized Whipple bicycle from the closed-form expressions of
//! Meijaard et al. 2007, Appendix A, with the paper's intermediate names.

use crate::math::Real;
use nalgebra::Matrix2;

use crate::error::Result;
use crate::parameters::BenchmarkParameters;

/// The linearized equations of motion `M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f` for
/// q = [lean φ, steer δ] and f = [lean torque T_φ, steer torque T_δ] (Meijaard 2007, eq. 5.3),
/// benchmark sign convention (lean right and steer right positive). `g` travels with the
/// matrices because K₀ excludes it.
///
/// Generic over the scalar: `Canonical` is the `f64` one; `Canonical<Dual64>` (built by
/// [`Canonical::from_parameters`] from dual-number parameters) carries the exact derivatives of
/// every entry, which is how sensitivities and uncertainties are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canonical<T = f64> {
    /// M: mass matrix [kg m², kg m²; kg m², kg m²].
    pub m: Matrix2<T>,
    /// C₁: velocity-dependent (damping-like) matrix, multiplied by v.
    pub c1: Matrix2<T>,
    /// K₀: gravity-dependent stiffness matrix, multiplied by g.
    pub k0: Matrix2<T>,
    /// K₂: velocity-dependent stiffness matrix, multiplied by v².
    pub k2: Matrix2<T>,
    /// g: gravitational acceleration of the bicycle's parameters [m/s²].
    pub g: T,
}

/// The intermediate quantities of Meijaard 2007 Appendix A, in the paper's order.
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(missing_docs)] // each field is named after the paper's symbol, documented in the paper
pub(crate) struct Intermediates<T = f64> {
    pub m_t: T,
    pub x_t: T,
    pub z_t: T,
    pub i_txx: T,
    pub i_txz: T,
    pub i_tzz: T,
    pub m_a: T,
    pub x_a: T,
    pub z_a: T,
    pub i_axx: T,
    pub i_axz: T,
    pub i_azz: T,
    pub u_a: T,
    pub i_all: T,
    pub i_alx: T,
    pub i_alz: T,
    pub mu: T,
    pub s_r: T,
    pub s_f: T,
    pub s_t: T,
    pub s_a: T,
}

impl<T: Real> Intermediates<T> {
    /// Appendix A of Meijaard 2007 (eqs. A1–A22), line by line. A wheel of zero radius (a skate)
    /// has no spin inertia (validation guarantees it) and contributes no gyroscopic term.
    #[inline]
    pub(crate) fn new(p: &BenchmarkParameters<T>) -> Self {
        let two: T = nalgebra::convert(2.0);
        let zero = T::zero();
        let (sin_l, cos_l) = crate::math::sin_cos(p.lambda);
        let m_t = p.m_r + p.m_b + p.m_h + p.m_f;
        let x_t = (p.x_b * p.m_b + p.x_h * p.m_h + p.w * p.m_f) / m_t;
        let z_t = (-p.r_r * p.m_r + p.z_b * p.m_b + p.z_h * p.m_h - p.r_f * p.m_f) / m_t;
        let i_rzz = p.i_rxx;
        let i_fzz = p.i_fxx;
        let i_txx = p.i_rxx
            + p.i_bxx
            + p.i_hxx
            + p.i_fxx
            + p.m_r * p.r_r * p.r_r
            + p.m_b * p.z_b * p.z_b
            + p.m_h * p.z_h * p.z_h
            + p.m_f * p.r_f * p.r_f;
        let i_txz =
            p.i_bxz + p.i_hxz - p.m_b * p.x_b * p.z_b - p.m_h * p.x_h * p.z_h + p.m_f * p.w * p.r_f;
        let i_tzz = i_rzz
            + p.i_bzz
            + p.i_hzz
            + i_fzz
            + p.m_b * p.x_b * p.x_b
            + p.m_h * p.x_h * p.x_h
            + p.m_f * p.w * p.w;
        let m_a = p.m_h + p.m_f;
        let x_a = (p.x_h * p.m_h + p.w * p.m_f) / m_a;
        let z_a = (p.z_h * p.m_h - p.r_f * p.m_f) / m_a;
        let sq = |x: T| x * x;
        let i_axx = p.i_hxx + p.i_fxx + p.m_h * sq(p.z_h - z_a) + p.m_f * sq(p.r_f + z_a);
        let i_axz =
            p.i_hxz - p.m_h * (p.x_h - x_a) * (p.z_h - z_a) + p.m_f * (p.w - x_a) * (p.r_f + z_a);
        let i_azz = p.i_hzz + i_fzz + p.m_h * sq(p.x_h - x_a) + p.m_f * sq(p.w - x_a);
        let u_a = (x_a - p.w - p.c) * cos_l - z_a * sin_l;
        let i_all = m_a * u_a * u_a
            + i_axx * sin_l * sin_l
            + two * i_axz * sin_l * cos_l
            + i_azz * cos_l * cos_l;
        let i_alx = -m_a * u_a * z_a + i_axx * sin_l + i_axz * cos_l;
        let i_alz = m_a * u_a * x_a + i_axz * sin_l + i_azz * cos_l;
        let mu = p.c / p.w * cos_l;
        let s_r = if p.r_r > zero { p.i_ryy / p.r_r } else { zero };
        let s_f = if p.r_f > zero { p.i_fyy / p.r_f } else { zero };
        let s_t = s_r + s_f;
        let s_a = m_a * u_a + mu * m_t * x_t;
        Intermediates {
            m_t,
            x_t,
            z_t,
            i_txx,
            i_txz,
            i_tzz,
            m_a,
            x_a,
            z_a,
            i_axx,
            i_axz,
            i_azz,
            u_a,
            i_all,
            i_alx,
            i_alz,
            mu,
            s_r,
            s_f,
            s_t,
            s_a,
        }
    }
}

impl Canonical {
    /// The canonical matrices of a bicycle, after validating its parameters.
    ///
    /// ```
    /// use whipple::{BenchmarkParameters, Canonical};
    /// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    /// assert!((canonical.m[(0, 0)] - 80.81722).abs() < 1e-12);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn new(p: &BenchmarkParameters) -> Result<Self> {
        p.validate()?;
        Ok(Self::from_unchecked(p))
    }

    /// The canonical matrices without validation (used by validation itself to test M).
    pub(crate) fn from_unchecked(p: &BenchmarkParameters) -> Self {
        Canonical::from_parameters(p)
    }
}

impl<T: Real> Canonical<T> {
    /// The canonical matrices of parameters on any scalar, without validation: the f64 path is
    /// [`Canonical::new`] (which validates first); dual-number parameters give the exact
    /// derivatives of every entry.
    #[inline]
    pub fn from_parameters(p: &BenchmarkParameters<T>) -> Self {
        let two: T = nalgebra::convert(2.0);
        let zero = T::zero();
        let a = Intermediates::new(p);
        let (sin_l, cos_l) = crate::math::sin_cos(p.lambda);
        let m = Matrix2::new(
            a.i_txx,
            a.i_alx + a.mu * a.i_txz,
            a.i_alx + a.mu * a.i_txz,
            a.i_all + two * a.mu * a.i_alz + a.mu * a.mu * a.i_tzz,
        );
        let k0 = Matrix2::new(a.m_t * a.z_t, -a.s_a, -a.s_a, -a.s_a * sin_l);
        let k2 = Matrix2::new(
            zero,
            (a.s_t - a.m_t * a.z_t) / p.w * cos_l,
            zero,
            (a.s_a + a.s_f * sin_l) / p.w * cos_l,
        );
        let c1 = Matrix2::new(
            zero,
            a.mu * a.s_t + a.s_f * cos_l + a.i_txz / p.w * cos_l - a.mu * a.m_t * a.z_t,
            -(a.mu * a.s_t + a.s_f * cos_l),
            a.i_alz / p.w * cos_l + a.mu * (a.s_a + a.i_tzz / p.w * cos_l),
        );
        Canonical {
            m,
            c1,
            k0,
            k2,
            g: p.g,
        }
    }

    /// The coefficients of the characteristic quartic det(M λ² + v C₁ λ + g K₀ + v² K₂) at
    /// speed v, lowest power of λ first, on any scalar (the derivatives of the critical speeds
    /// and eigenvalues come from evaluating it on dual numbers).
    #[inline]
    pub fn quartic_at(&self, v: T) -> [T; 5] {
        // det of [[a x² + b x + c, d x² + e x + f], [g x² + h x + i, j x² + k x + l]].
        let entry = |i: usize, j: usize| {
            (
                self.m[(i, j)],
                v * self.c1[(i, j)],
                self.g * self.k0[(i, j)] + v * v * self.k2[(i, j)],
            )
        };
        let (a, b, c) = entry(0, 0);
        let (j, k, l) = entry(1, 1);
        let (d, e, f) = entry(0, 1);
        let (g, h, i) = entry(1, 0);
        [
            c * l - f * i,
            b * l + c * k - e * i - f * h,
            a * l + b * k + c * j - d * i - e * h - f * g,
            a * k + b * j - d * h - e * g,
            a * j - d * g,
        ]
    }
}

impl Canonical {
    /// The matrices in JBike6's printed convention: q = [lean right +, steer left +] and g inside
    /// K₀, i.e. `M₀ q̈ + v C₁ q̇ + (K₀ + v² K₂) q = 0`. Returns (M, C₁, K₀ (with g), K₂).
    pub fn jbike6_convention(&self) -> [Matrix2<f64>; 4] {
        let flip = Matrix2::new(1.0, -1.0, -1.0, 1.0);
        [
            self.m.component_mul(&flip),
            self.c1.component_mul(&flip),
            (self.k0 * self.g).component_mul(&flip),
            self.k2.component_mul(&flip),
        ]
    }
}
