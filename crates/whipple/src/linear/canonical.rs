//! The canonical matrices of the linearized Whipple bicycle from the closed-form expressions of
//! Meijaard et al. 2007, Appendix A, with the paper's intermediate names.

use nalgebra::Matrix2;

use crate::error::Result;
use crate::parameters::BenchmarkParameters;

/// The linearized equations of motion `M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = f` for
/// q = [lean φ, steer δ] and f = [lean torque T_φ, steer torque T_δ] (Meijaard 2007, eq. 5.3),
/// benchmark sign convention (lean right and steer right positive). `g` travels with the
/// matrices because K₀ excludes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canonical {
    /// M: mass matrix [kg m², kg m²; kg m², kg m²].
    pub m: Matrix2<f64>,
    /// C₁: velocity-dependent (damping-like) matrix, multiplied by v.
    pub c1: Matrix2<f64>,
    /// K₀: gravity-dependent stiffness matrix, multiplied by g.
    pub k0: Matrix2<f64>,
    /// K₂: velocity-dependent stiffness matrix, multiplied by v².
    pub k2: Matrix2<f64>,
    /// g: gravitational acceleration of the bicycle's parameters [m/s²].
    pub g: f64,
}

/// The intermediate quantities of Meijaard 2007 Appendix A, in the paper's order.
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(missing_docs)] // each field is named after the paper's symbol, documented in the paper
pub struct Intermediates {
    pub m_t: f64,
    pub x_t: f64,
    pub z_t: f64,
    pub i_txx: f64,
    pub i_txz: f64,
    pub i_tzz: f64,
    pub m_a: f64,
    pub x_a: f64,
    pub z_a: f64,
    pub i_axx: f64,
    pub i_axz: f64,
    pub i_azz: f64,
    pub u_a: f64,
    pub i_all: f64,
    pub i_alx: f64,
    pub i_alz: f64,
    pub mu: f64,
    pub s_r: f64,
    pub s_f: f64,
    pub s_t: f64,
    pub s_a: f64,
}

impl Intermediates {
    /// Appendix A of Meijaard 2007 (eqs. A1–A22), line by line. A wheel of zero radius (a skate)
    /// has no spin inertia (validation guarantees it) and contributes no gyroscopic term.
    pub fn new(p: &BenchmarkParameters) -> Self {
        let (sin_l, cos_l) = p.lambda.sin_cos();
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
        let i_axx =
            p.i_hxx + p.i_fxx + p.m_h * (p.z_h - z_a).powi(2) + p.m_f * (p.r_f + z_a).powi(2);
        let i_axz =
            p.i_hxz - p.m_h * (p.x_h - x_a) * (p.z_h - z_a) + p.m_f * (p.w - x_a) * (p.r_f + z_a);
        let i_azz = p.i_hzz + i_fzz + p.m_h * (p.x_h - x_a).powi(2) + p.m_f * (p.w - x_a).powi(2);
        let u_a = (x_a - p.w - p.c) * cos_l - z_a * sin_l;
        let i_all = m_a * u_a * u_a
            + i_axx * sin_l * sin_l
            + 2.0 * i_axz * sin_l * cos_l
            + i_azz * cos_l * cos_l;
        let i_alx = -m_a * u_a * z_a + i_axx * sin_l + i_axz * cos_l;
        let i_alz = m_a * u_a * x_a + i_axz * sin_l + i_azz * cos_l;
        let mu = p.c / p.w * cos_l;
        let s_r = if p.r_r > 0.0 { p.i_ryy / p.r_r } else { 0.0 };
        let s_f = if p.r_f > 0.0 { p.i_fyy / p.r_f } else { 0.0 };
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
    /// use whipple::{BenchmarkParameters, linear::Canonical};
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
        let a = Intermediates::new(p);
        let (sin_l, cos_l) = p.lambda.sin_cos();
        let m = Matrix2::new(
            a.i_txx,
            a.i_alx + a.mu * a.i_txz,
            a.i_alx + a.mu * a.i_txz,
            a.i_all + 2.0 * a.mu * a.i_alz + a.mu * a.mu * a.i_tzz,
        );
        let k0 = Matrix2::new(a.m_t * a.z_t, -a.s_a, -a.s_a, -a.s_a * sin_l);
        let k2 = Matrix2::new(
            0.0,
            (a.s_t - a.m_t * a.z_t) / p.w * cos_l,
            0.0,
            (a.s_a + a.s_f * sin_l) / p.w * cos_l,
        );
        let c1 = Matrix2::new(
            0.0,
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
