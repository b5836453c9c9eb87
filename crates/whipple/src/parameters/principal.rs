//! BicycleParameters' principal parameterization (Moore & Hubbard 2019, "Expanded optimization
//! for discovering optimal lateral handling bicycles", BMD 2019, doi:10.6084/m9.figshare.9942938):
//! each body of the plane of symmetry by its mass, mass centre and radii of gyration about its
//! principal axes, the axes turned by an angle; the rear frame D and a rigid rider P are apart,
//! where the benchmark has their combination B.

use crate::math::Real;

use super::BenchmarkParameters;
use super::jbike6::PlaneBody;
use crate::error::{Error, Result};

/// A body of the plane of symmetry in Moore 2019's principal form, in the benchmark's axes (x
/// forward, z down, origin at the rear contact) \[kg, m, rad\]: mass, mass centre, and radii of
/// gyration about the principal axes through the mass centre: `k_yy` about the lateral axis,
/// `k_aa` and `k_bb` about the two in the plane, the axis of `k_aa` turned by `alpha` from x
/// about y (towards −z, up, for a positive angle), the axis of `k_bb` at right angles to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipalBody<T = f64> {
    /// m \[kg\].
    pub m: T,
    /// x of the mass centre \[m\].
    pub x: T,
    /// z of the mass centre \[m\] (negative above the ground).
    pub z: T,
    /// k_aa, radius of gyration about the first in-plane principal axis \[m\].
    pub k_aa: T,
    /// k_bb, radius of gyration about the second in-plane principal axis \[m\].
    pub k_bb: T,
    /// k_yy, radius of gyration about the lateral axis \[m\].
    pub k_yy: T,
    /// α, angle of the axis of k_aa from x \[rad\].
    pub alpha: T,
}

/// The parameters of BicycleParameters' `Moore2019` (`principal`) parameterization, SI units:
/// the geometry and gravity as in the benchmark, the wheels by radius, mass and radii of
/// gyration (`k_raa` diametral, `k_ryy` about the axle), the rear frame D, the front frame H and
/// the rigid rider P as [`PrincipalBody`]s, and the rider's drawing dimensions `l_p`, `w_p`
/// (the diamond BicycleParameters draws; no part of the dynamics).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipalParameters<T = f64> {
    /// w, wheelbase \[m\].
    pub w: T,
    /// c, trail \[m\].
    pub c: T,
    /// λ, steer axis tilt from the vertical \[rad\] (`lam`).
    pub lambda: T,
    /// g, gravity \[m/s²\].
    pub g: T,
    /// r_R, rear wheel radius \[m\].
    pub r_r: T,
    /// m_R, rear wheel mass \[kg\].
    pub m_r: T,
    /// k_Raa, rear wheel radius of gyration about a diameter \[m\].
    pub k_raa: T,
    /// k_Ryy, rear wheel radius of gyration about its axle \[m\].
    pub k_ryy: T,
    /// r_F, front wheel radius \[m\].
    pub r_f: T,
    /// m_F, front wheel mass \[kg\].
    pub m_f: T,
    /// k_Faa, front wheel radius of gyration about a diameter \[m\].
    pub k_faa: T,
    /// k_Fyy, front wheel radius of gyration about its axle \[m\].
    pub k_fyy: T,
    /// D, the rear frame without the rider (keys `mD`, `xD`, `zD`, `kDaa`, `kDbb`, `kDyy`, `alphaD`).
    pub d: PrincipalBody<T>,
    /// H, the front frame (`mH`, ..., `alphaH`).
    pub h: PrincipalBody<T>,
    /// P, the rigid rider (`mP`, ..., `alphaP`).
    pub p: PrincipalBody<T>,
    /// l_P, the rider diamond's length \[m\] (drawing only).
    pub l_p: T,
    /// w_P, the rider diamond's width \[m\] (drawing only).
    pub w_p: T,
}

/// The keys of a principal parameter set, as BicycleParameters names them, in the order of
/// [`PrincipalParameters::to_array`].
pub const PRINCIPAL_KEYS: [&str; 35] = [
    "w", "c", "lam", "g", "rR", "mR", "kRaa", "kRyy", "rF", "mF", "kFaa", "kFyy", "mD", "xD", "zD",
    "kDaa", "kDbb", "kDyy", "alphaD", "mH", "xH", "zH", "kHaa", "kHbb", "kHyy", "alphaH", "mP",
    "xP", "zP", "kPaa", "kPbb", "kPyy", "alphaP", "lP", "wP",
];

/// `x > 0`, false for NaN.
fn positive<T: Real>(x: T) -> bool {
    x > T::zero()
}

fn to_f64<T: Real>(x: T) -> f64 {
    x.to_subset().unwrap_or(f64::NAN)
}

impl<T: Real> PrincipalBody<T> {
    fn to_array(self) -> [T; 7] {
        [
            self.m, self.x, self.z, self.k_aa, self.k_bb, self.k_yy, self.alpha,
        ]
    }

    fn from_array(v: [T; 7]) -> Self {
        PrincipalBody {
            m: v[0],
            x: v[1],
            z: v[2],
            k_aa: v[3],
            k_bb: v[4],
            k_yy: v[5],
            alpha: v[6],
        }
    }

    /// The body as a mass, centre and central inertia tensor (the rotation of Moore 2019's
    /// principal moments by α, shared with JBike6's bodies).
    fn plane_body(&self) -> PlaneBody<T> {
        let m = self.m;
        PlaneBody::principal(
            m,
            self.x,
            self.z,
            [
                m * self.k_aa * self.k_aa,
                m * self.k_bb * self.k_bb,
                m * self.k_yy * self.k_yy,
            ],
            self.alpha,
        )
    }

    /// The principal form of a body with a positive mass: the in-plane axis of the larger
    /// moment is `aa`, α in (−π/2, π/2]; α = 0 where the two moments are equal. `prefix` names
    /// the body in errors (`D`, `H`).
    fn from_plane_body(b: &PlaneBody<T>, prefix: &str) -> Result<Self> {
        if !positive(b.m) {
            return Err(Error::InvalidParameter {
                field: format!("m{prefix}"),
                value: to_f64(b.m),
                rule: "must be positive to have radii of gyration".into(),
            });
        }
        let ([i_aa, i_bb, _], alpha) = b.principal_axes();
        for (key, moment) in [("bb", i_bb), ("yy", b.i_yy)] {
            if !positive(moment) {
                return Err(Error::InvalidBicycle {
                    fields: format!("k{prefix}{key}"),
                    rule: format!(
                        "the body {prefix} has a principal moment of inertia {} ≤ 0, so no \
                         real radius of gyration",
                        crate::error::short_number(to_f64(moment))
                    ),
                });
            }
        }
        Ok(PrincipalBody {
            m: b.m,
            x: b.x,
            z: b.z,
            k_aa: (i_aa / b.m).sqrt(),
            k_bb: (i_bb / b.m).sqrt(),
            k_yy: (b.i_yy / b.m).sqrt(),
            alpha,
        })
    }
}

impl<T: Real> PrincipalParameters<T> {
    /// The values in the order of [`PRINCIPAL_KEYS`].
    pub fn to_array(&self) -> [T; 35] {
        let mut out = [T::zero(); 35];
        let head = [
            self.w,
            self.c,
            self.lambda,
            self.g,
            self.r_r,
            self.m_r,
            self.k_raa,
            self.k_ryy,
            self.r_f,
            self.m_f,
            self.k_faa,
            self.k_fyy,
        ];
        out[..12].copy_from_slice(&head);
        out[12..19].copy_from_slice(&self.d.to_array());
        out[19..26].copy_from_slice(&self.h.to_array());
        out[26..33].copy_from_slice(&self.p.to_array());
        out[33] = self.l_p;
        out[34] = self.w_p;
        out
    }

    /// From the values in the order of [`PRINCIPAL_KEYS`].
    pub fn from_array(v: [T; 35]) -> Self {
        let body = |k: usize| {
            let mut b = [T::zero(); 7];
            b.copy_from_slice(&v[k..k + 7]);
            PrincipalBody::from_array(b)
        };
        PrincipalParameters {
            w: v[0],
            c: v[1],
            lambda: v[2],
            g: v[3],
            r_r: v[4],
            m_r: v[5],
            k_raa: v[6],
            k_ryy: v[7],
            r_f: v[8],
            m_f: v[9],
            k_faa: v[10],
            k_fyy: v[11],
            d: body(12),
            h: body(19),
            p: body(26),
            l_p: v[33],
            w_p: v[34],
        }
    }

    /// The benchmark parameters, exactly (no check; see [`BenchmarkParameters::check`]): the
    /// wheels' moments m k², the frame D and the rider P combined into the rear frame B by
    /// the one parallel-axis combination of the crate, the front frame H rotated into the
    /// benchmark's axes. What BicycleParameters' `Moore2019ParameterSet.to_parameterization
    /// ("Meijaard2007")` computes.
    pub fn to_benchmark(&self) -> BenchmarkParameters<T> {
        let b = PlaneBody::combine(&[self.d.plane_body(), self.p.plane_body()]);
        let h = self.h.plane_body();
        BenchmarkParameters {
            w: self.w,
            c: self.c,
            lambda: self.lambda,
            g: self.g,
            r_r: self.r_r,
            m_r: self.m_r,
            i_rxx: self.m_r * self.k_raa * self.k_raa,
            i_ryy: self.m_r * self.k_ryy * self.k_ryy,
            x_b: b.x,
            z_b: b.z,
            m_b: b.m,
            i_bxx: b.i_xx,
            i_byy: b.i_yy,
            i_bzz: b.i_zz,
            i_bxz: b.i_xz,
            x_h: h.x,
            z_h: h.z,
            m_h: h.m,
            i_hxx: h.i_xx,
            i_hyy: h.i_yy,
            i_hzz: h.i_zz,
            i_hxz: h.i_xz,
            r_f: self.r_f,
            m_f: self.m_f,
            i_fxx: self.m_f * self.k_faa * self.k_faa,
            i_fyy: self.m_f * self.k_fyy * self.k_fyy,
        }
    }

    /// The principal form of benchmark parameters, given the rider.
    ///
    /// The benchmark's rear frame B is the frame and the rider together; how it splits is not
    /// in the 25 numbers, so the rider P (and its drawing dimensions `l_p`, `w_p`) is an
    /// argument, never guessed, and the frame D is B with P taken out (the same parallel-axis
    /// combination with P's mass and inertia negated). Each body's principal axes are chosen
    /// so that `aa` is the in-plane axis of the larger moment and α lies in (−π/2, π/2] (α = 0
    /// where the two in-plane moments are equal); BicycleParameters' sets follow the same
    /// choice, so its files round-trip. The wheels' diametral radii of gyration are the
    /// benchmark's I_xx (the model takes wheels as axisymmetric).
    ///
    /// Errors: a rider as heavy as B or heavier (`mP`), or one whose removal leaves D with a
    /// principal moment ≤ 0 (`kDbb`, `kDyy`); non-positive wheel or front-frame masses.
    pub fn from_benchmark(
        b: &BenchmarkParameters<T>,
        rider: &PrincipalBody<T>,
        l_p: T,
        w_p: T,
    ) -> Result<Self> {
        let zero = T::zero();
        let lighter = rider.m < b.m_b; // false for NaN too
        if !lighter {
            return Err(Error::InvalidParameter {
                field: "mP".into(),
                value: to_f64(rider.m),
                rule: format!(
                    "the rider must be lighter than the rear frame with rider, mB = {} kg, to \
                     leave a frame D",
                    crate::error::short_number(to_f64(b.m_b))
                ),
            });
        }
        let p = rider.plane_body();
        let negated = PlaneBody {
            m: -p.m,
            x: p.x,
            z: p.z,
            i_xx: -p.i_xx,
            i_yy: -p.i_yy,
            i_zz: -p.i_zz,
            i_xz: -p.i_xz,
        };
        let whole = PlaneBody {
            m: b.m_b,
            x: b.x_b,
            z: b.z_b,
            i_xx: b.i_bxx,
            i_yy: b.i_byy,
            i_zz: b.i_bzz,
            i_xz: b.i_bxz,
        };
        let d = PlaneBody::combine(&[whole, negated]);
        let h = PlaneBody {
            m: b.m_h,
            x: b.x_h,
            z: b.z_h,
            i_xx: b.i_hxx,
            i_yy: b.i_hyy,
            i_zz: b.i_hzz,
            i_xz: b.i_hxz,
        };
        let radius = |field: &str, m: T, i: T| -> Result<T> {
            let non_negative = i >= zero;
            if !positive(m) || !non_negative {
                return Err(Error::InvalidParameter {
                    field: field.into(),
                    value: to_f64(if m > zero { i } else { m }),
                    rule: "needs a positive mass and a non-negative moment for a radius of \
                           gyration"
                        .into(),
                });
            }
            Ok((i / m).sqrt())
        };
        Ok(PrincipalParameters {
            w: b.w,
            c: b.c,
            lambda: b.lambda,
            g: b.g,
            r_r: b.r_r,
            m_r: b.m_r,
            k_raa: radius("IRxx", b.m_r, b.i_rxx)?,
            k_ryy: radius("IRyy", b.m_r, b.i_ryy)?,
            r_f: b.r_f,
            m_f: b.m_f,
            k_faa: radius("IFxx", b.m_f, b.i_fxx)?,
            k_fyy: radius("IFyy", b.m_f, b.i_fyy)?,
            d: PrincipalBody::from_plane_body(&d, "D")?,
            h: PrincipalBody::from_plane_body(&h, "H")?,
            p: *rider,
            l_p,
            w_p,
        })
    }
}
