//! The leaning rider (Moore 2012, "Human control of a bicycle", PhD dissertation, UC Davis,
//! the rider-lean extension; BicycleParameters' `MooreRiderLean2012` parameter set): a fifth
//! rigid body, the rider's upper body G, hinged to the rear frame B.
//!
//! The bicycle is a benchmark bicycle whose rear frame B holds the frame and the rider's lower
//! body (the legs: BicycleParameters' `meijaard2007_browser_jasonlegs` is the Browser with only
//! Jason's legs in B); G holds the rest of the rider (torso, arms and head). G turns relative to
//! B about the hinge line: the line through (·, 0, z_hinge) parallel to B's x axis, which in the
//! upright reference configuration (zero lean and steer, the nominal pitch) is the benchmark's
//! x axis, horizontal and forward. That is Moore's axis: his G frame is his C frame (whose third
//! axis runs down the steer axis) turned back by the nominal pitch λ about the second axis
//! (`dircos(c, g, body212, -lam, q9, 0)`), then by the lean angle q9 about its first axis; so at
//! q9 = 0 its axes are the roll frame's, and q9 turns about the rear frame's roll axis. The lean
//! angle is positive to the right, as the roll φ; a lean torque acts on G from B about that axis,
//! with the passive torque −(k φ_r + c φ̇_r) of the hinge's stiffness and damping.
//!
//! Moore's keys for G: `d4` the hinge line's distance below the rear wheel centre (the hinge
//! point `cg` lies straight above or below the hub: `−d4 sin λ c1 + d4 cos λ c3` is `d4` down
//! in the roll frame), (`l5`, `l6`) G's mass centre from that point, forward and down, `mg`, the
//! tensor `ig11`, `ig22`, `ig33`, `ig31` about G's mass centre in G's axes (the benchmark axes
//! at zero lean; `ig31` the tensor's entry, as `IBxz`), `k9` and `c9`. The other keys are
//! Moore 2012's four bodies ([`Moore2012Parameters`]) with C the rear frame B.

use crate::math::Real;

use super::benchmark::upper_body_inertia;
use super::jbike6::PlaneBody;
use super::{BenchmarkParameters, MOORE2012_KEYS, Moore2012Parameters, Notice};
use crate::error::{Error, Result, short_number};

/// The rider's upper body G and its hinge, SI units, benchmark axes (x forward, z down, origin
/// at the rear contact) in the upright reference configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UpperBody<T = f64> {
    /// m_G, mass \[kg\] (`mG`).
    pub m: T,
    /// x_G, mass centre forward of the rear contact \[m\] (`xG`).
    pub x: T,
    /// z_G, mass centre, down from the ground (negative above it) \[m\] (`zG`).
    pub z: T,
    /// I_Gxx, moment about the mass centre, x axis \[kg m²\] (`IGxx`).
    pub i_xx: T,
    /// I_Gyy, moment about the mass centre, y axis \[kg m²\] (`IGyy`).
    pub i_yy: T,
    /// I_Gzz, moment about the mass centre, z axis \[kg m²\] (`IGzz`).
    pub i_zz: T,
    /// I_Gxz, the tensor's xz entry about the mass centre \[kg m²\] (`IGxz`).
    pub i_xz: T,
    /// z of the hinge line, which runs parallel to the rear frame's x axis through y = 0 \[m\]
    /// (`zHinge`; negative above the ground).
    pub z_hinge: T,
    /// k, the hinge's passive stiffness \[N m/rad\] (`kLean`; Moore's `k9`).
    pub stiffness: T,
    /// c, the hinge's passive damping \[N m s/rad\] (`cLean`; Moore's `c9`).
    pub damping: T,
}

/// The keys of [`UpperBody`], in the order of [`UpperBody::to_array`].
pub(crate) const UPPER_BODY_KEYS: [&str; 10] = [
    "mG", "xG", "zG", "IGxx", "IGyy", "IGzz", "IGxz", "zHinge", "kLean", "cLean",
];

impl<T: Real> UpperBody<T> {
    /// The values in the order of the fields (keys `mG`, `xG`, `zG`, `IGxx`, `IGyy`, `IGzz`,
    /// `IGxz`, `zHinge`, `kLean`, `cLean`).
    pub fn to_array(&self) -> [T; 10] {
        [
            self.m,
            self.x,
            self.z,
            self.i_xx,
            self.i_yy,
            self.i_zz,
            self.i_xz,
            self.z_hinge,
            self.stiffness,
            self.damping,
        ]
    }

    /// From the values in the order of [`Self::to_array`].
    pub fn from_array(v: [T; 10]) -> Self {
        let [m, x, z, i_xx, i_yy, i_zz, i_xz, z_hinge, stiffness, damping] = v;
        UpperBody {
            m,
            x,
            z,
            i_xx,
            i_yy,
            i_zz,
            i_xz,
            z_hinge,
            stiffness,
            damping,
        }
    }

    fn plane_body(&self) -> PlaneBody<T> {
        PlaneBody {
            m: self.m,
            x: self.x,
            z: self.z,
            i_xx: self.i_xx,
            i_yy: self.i_yy,
            i_zz: self.i_zz,
            i_xz: self.i_xz,
        }
    }
}

/// A bicycle with a leaning rider: the benchmark bicycle whose rear frame B holds the frame and
/// the rider's lower body, and the rider's upper body G hinged to B.
///
/// ```
/// use whipple::advanced::parameters::{MooreRiderLean2012Parameters, RiderLeanParameters};
/// let p = RiderLeanParameters::browser_jason();
/// p.check()?;
/// // A rigid rider: G combined into B is the Browser with the whole of Jason in B.
/// assert!((p.rigid().m_b - 81.86).abs() < 1e-12);
/// let moore = MooreRiderLean2012Parameters::from_rider_lean(&p);
/// assert!((moore.to_rider_lean()?.upper_body.z_hinge - p.upper_body.z_hinge).abs() < 1e-15);
/// # Ok::<(), whipple::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RiderLeanParameters<T = f64> {
    /// The bicycle, its rear frame B holding the rider's lower body.
    pub bicycle: BenchmarkParameters<T>,
    /// The rider's upper body G and its hinge.
    pub upper_body: UpperBody<T>,
}

impl<T: Real> RiderLeanParameters<T> {
    /// The rigid rider: the hinge locked, G combined into B by the parallel-axis theorem (the
    /// crate's one combination), a benchmark bicycle (no check; see
    /// [`BenchmarkParameters::check`]).
    pub fn rigid(&self) -> BenchmarkParameters<T> {
        let b = &self.bicycle;
        let rear = PlaneBody {
            m: b.m_b,
            x: b.x_b,
            z: b.z_b,
            i_xx: b.i_bxx,
            i_yy: b.i_byy,
            i_zz: b.i_bzz,
            i_xz: b.i_bxz,
        };
        let whole = PlaneBody::combine(&[rear, self.upper_body.plane_body()]);
        BenchmarkParameters {
            m_b: whole.m,
            x_b: whole.x,
            z_b: whole.z,
            i_bxx: whole.i_xx,
            i_byy: whole.i_yy,
            i_bzz: whole.i_zz,
            i_bxz: whole.i_xz,
            ..*b
        }
    }
}

impl RiderLeanParameters<f64> {
    /// The bicycle `rigid`, whose rear frame B holds the whole rider, with `upper_body` freed to
    /// lean: B less G (the inverse of [`RiderLeanParameters::rigid`]: the remainder's mass
    /// m_B − m_G, its centre the mass-weighted difference, its tensor by the parallel-axis
    /// theorem), then [`RiderLeanParameters::check`]ed. The rear frame then holds the frame and
    /// the rider's lower body. Refused (naming `mG`) when G is not lighter than B or B less G
    /// is not a body (its tensor not positive semi-definite: G does not fit inside B).
    ///
    /// ```
    /// use whipple::advanced::parameters::RiderLeanParameters;
    /// let p = RiderLeanParameters::browser_jason();
    /// let again = RiderLeanParameters::split(&p.rigid(), p.upper_body)?;
    /// assert!((again.bicycle.i_bxz - p.bicycle.i_bxz).abs() < 1e-12);
    /// // A heavier upper body than the whole rear frame is refused.
    /// let heavy = whipple::advanced::parameters::UpperBody { m: 500.0, ..p.upper_body };
    /// assert!(RiderLeanParameters::split(&p.rigid(), heavy).is_err());
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn split(rigid: &BenchmarkParameters, upper_body: UpperBody) -> Result<Self> {
        let g = upper_body;
        if !(g.m.is_finite() && g.m > 0.0) {
            return Err(invalid(
                "mG",
                g.m,
                "the rider's upper body must have a positive mass".into(),
            ));
        }
        if g.m >= rigid.m_b {
            return Err(invalid(
                "mG",
                g.m,
                format!(
                    "the upper body must be lighter than the rear frame it leaves (mB = {} kg)",
                    short_number(rigid.m_b)
                ),
            ));
        }
        let whole = PlaneBody {
            m: rigid.m_b,
            x: rigid.x_b,
            z: rigid.z_b,
            i_xx: rigid.i_bxx,
            i_yy: rigid.i_byy,
            i_zz: rigid.i_bzz,
            i_xz: rigid.i_bxz,
        };
        let less = PlaneBody {
            m: -g.m,
            i_xx: -g.i_xx,
            i_yy: -g.i_yy,
            i_zz: -g.i_zz,
            i_xz: -g.i_xz,
            ..g.plane_body()
        };
        let rest = PlaneBody::combine(&[whole, less]);
        // A plane body's tensor is positive semi-definite when its yy entry and its xz block
        // are; a little slack for the round-off of the subtraction.
        let slack = 1e-12 * (rigid.i_bxx.abs() + rigid.i_byy.abs() + rigid.i_bzz.abs());
        let block = rest.i_xx * rest.i_zz - rest.i_xz * rest.i_xz;
        if rest.i_xx < -slack || rest.i_zz < -slack || rest.i_yy < -slack || block < -slack * slack
        {
            return Err(invalid(
                "mG",
                g.m,
                format!(
                    "the rear frame less this upper body is not a body (its inertia tensor \
                     IBxx {}, IByy {}, IBzz {}, IBxz {} kg m² is not positive semi-definite): \
                     the upper body does not fit inside the rear frame's rider",
                    short_number(rest.i_xx),
                    short_number(rest.i_yy),
                    short_number(rest.i_zz),
                    short_number(rest.i_xz)
                ),
            ));
        }
        let p = RiderLeanParameters {
            bicycle: BenchmarkParameters {
                m_b: rest.m,
                x_b: rest.x,
                z_b: rest.z,
                i_bxx: rest.i_xx.max(0.0),
                i_byy: rest.i_yy.max(0.0),
                i_bzz: rest.i_zz.max(0.0),
                i_bxz: rest.i_xz,
                ..*rigid
            },
            upper_body: g,
        };
        p.check()?;
        Ok(p)
    }

    /// The Browser bicycle with Jason seated, his legs in the rear frame and his upper body
    /// free to lean: BicycleParameters' `mooreriderlean2012_browser_jason` (Moore 2012, from
    /// his inertia model of Jason on the Browser; BicycleParameters 1.5, BSD-2-Clause),
    /// converted exactly.
    pub fn browser_jason() -> Self {
        MooreRiderLean2012Parameters::browser_jason()
            .to_rider_lean()
            .unwrap_or_else(|_| unreachable!("published values convert"))
    }

    /// Checks the bicycle ([`BenchmarkParameters::check`]) and the upper body, and returns the
    /// warnings. Refused, naming the key: a number that is not finite; `mG` not positive (a
    /// massless upper body leaves its lean undetermined); a tensor that is not positive
    /// semi-definite (as B's); a negative `kLean` or `cLean` (passive: they take energy, never
    /// give it); a hinge on or below the ground (`zHinge` ≥ 0) or above the bicycle's top — the
    /// highest of the wheels' tops and the mass centres of B, H and G. Warned about: G's
    /// principal moments breaking the triangle inequality.
    pub fn check(&self) -> Result<Vec<Notice>> {
        let mut notices = self.bicycle.check()?;
        let g = &self.upper_body;
        for (field, value) in UPPER_BODY_KEYS.iter().zip(g.to_array()) {
            if !value.is_finite() {
                return Err(invalid(field, value, "must be a finite number".into()));
            }
        }
        if g.m <= 0.0 {
            return Err(invalid(
                "mG",
                g.m,
                "the rider's upper body must have a positive mass (a massless body leaves its \
                 lean undetermined)"
                    .into(),
            ));
        }
        upper_body_inertia(g.i_xx, g.i_yy, g.i_zz, g.i_xz, &mut notices)?;
        for (field, value) in [("kLean", g.stiffness), ("cLean", g.damping)] {
            if value < 0.0 {
                return Err(invalid(
                    field,
                    value,
                    "the hinge's stiffness and damping are passive and must not be negative".into(),
                ));
            }
        }
        if g.z_hinge >= 0.0 {
            return Err(invalid(
                "zHinge",
                g.z_hinge,
                "the hinge must lie above the ground (z points down: zHinge < 0)".into(),
            ));
        }
        let b = &self.bicycle;
        let top = [-2.0 * b.r_r, -2.0 * b.r_f, b.z_b, b.z_h, g.z]
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        if g.z_hinge < top {
            return Err(invalid(
                "zHinge",
                g.z_hinge,
                format!(
                    "the hinge, {} m above the ground, is above the bicycle's top, {} m (the \
                     highest of the wheels' tops and the mass centres of B, H and G)",
                    short_number(-g.z_hinge),
                    short_number(-top)
                ),
            ));
        }
        Ok(notices)
    }
}

fn invalid(field: &str, value: f64, rule: String) -> Error {
    Error::InvalidParameter {
        field: field.to_string(),
        value,
        rule,
    }
}

/// BicycleParameters' `MooreRiderLean2012` parameter set, SI units: Moore 2012's four bodies
/// ([`Moore2012Parameters`], C the rear frame with the rider's lower body) and the upper body G
/// with its hinge (see the module's documentation for `d4`, `l5`, `l6`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MooreRiderLean2012Parameters<T = f64> {
    /// The four bodies C, D, E, F.
    pub whipple: Moore2012Parameters<T>,
    /// d4, the hinge line's distance below the rear wheel centre \[m\] (negative above).
    pub d4: T,
    /// l5, G's mass centre forward of the hinge point above the rear wheel centre \[m\].
    pub l5: T,
    /// l6, G's mass centre below the hinge point \[m\] (negative above).
    pub l6: T,
    /// m_G, the upper body's mass \[kg\].
    pub mg: T,
    /// I_G11, G's moment about its mass centre, forward axis \[kg m²\].
    pub ig11: T,
    /// I_G22, G's lateral moment \[kg m²\].
    pub ig22: T,
    /// I_G31, G's tensor entry 31 \[kg m²\].
    pub ig31: T,
    /// I_G33, G's moment about its mass centre, downward axis \[kg m²\].
    pub ig33: T,
    /// k9, the hinge's stiffness \[N m/rad\].
    pub k9: T,
    /// c9, the hinge's damping \[N m s/rad\].
    pub c9: T,
}

/// The keys of a `MooreRiderLean2012` parameter set, as BicycleParameters orders them (its
/// `par_strings`, less the speed `v`), in the order of [`MooreRiderLean2012Parameters::to_array`].
pub const MOORE_RIDER_LEAN2012_KEYS: [&str; 36] = [
    "c9", "d1", "d2", "d3", "d4", "g", "ic11", "ic22", "ic31", "ic33", "id11", "id22", "ie11",
    "ie22", "ie31", "ie33", "if11", "if22", "ig11", "ig22", "ig31", "ig33", "k9", "l1", "l2", "l3",
    "l4", "l5", "l6", "mc", "md", "me", "mf", "mg", "rf", "rr",
];

/// The keys of [`MOORE_RIDER_LEAN2012_KEYS`] beyond [`MOORE2012_KEYS`]: the upper body's and
/// its hinge's, in the order of `MooreRiderLean2012Parameters::rider_array`.
const RIDER_KEYS: [&str; 10] = [
    "d4", "l5", "l6", "mg", "ig11", "ig22", "ig31", "ig33", "k9", "c9",
];

/// The position of `key` in [`MOORE_RIDER_LEAN2012_KEYS`] (each of [`MOORE2012_KEYS`] and
/// [`RIDER_KEYS`] is there).
fn rider_lean_index(key: &str) -> Option<usize> {
    MOORE_RIDER_LEAN2012_KEYS.iter().position(|k| *k == key)
}

impl<T: Real> MooreRiderLean2012Parameters<T> {
    /// The values of [`RIDER_KEYS`], in its order.
    fn rider_array(&self) -> [T; 10] {
        [
            self.d4, self.l5, self.l6, self.mg, self.ig11, self.ig22, self.ig31, self.ig33,
            self.k9, self.c9,
        ]
    }

    /// The values in the order of [`MOORE_RIDER_LEAN2012_KEYS`]: the four bodies' by
    /// [`Moore2012Parameters::to_array`], then the upper body's and its hinge's, each put at its
    /// key's place.
    pub fn to_array(&self) -> [T; 36] {
        let mut out = [T::zero(); 36];
        let whipple = MOORE2012_KEYS.iter().zip(self.whipple.to_array());
        for (key, value) in whipple.chain(RIDER_KEYS.iter().zip(self.rider_array())) {
            if let Some(i) = rider_lean_index(key) {
                out[i] = value;
            }
        }
        out
    }

    /// From the values in the order of [`MOORE_RIDER_LEAN2012_KEYS`]: the four bodies by
    /// [`Moore2012Parameters::from_array`], each value taken from its key's place.
    pub fn from_array(v: [T; 36]) -> Self {
        let at = |key: &str| rider_lean_index(key).map_or(T::zero(), |i| v[i]);
        let [d4, l5, l6, mg, ig11, ig22, ig31, ig33, k9, c9] = RIDER_KEYS.map(at);
        MooreRiderLean2012Parameters {
            whipple: Moore2012Parameters::from_array(MOORE2012_KEYS.map(at)),
            d4,
            l5,
            l6,
            mg,
            ig11,
            ig22,
            ig31,
            ig33,
            k9,
            c9,
        }
    }

    /// Moore's parameters of a bicycle with a leaning rider, exactly (no check): the four bodies
    /// by [`Moore2012Parameters::from_benchmark`], then d4 = z_hinge + r_R, l5 = x_G,
    /// l6 = z_G − z_hinge, G's tensor as it is (G's axes are the benchmark's at zero lean).
    pub fn from_rider_lean(p: &RiderLeanParameters<T>) -> Self {
        let g = &p.upper_body;
        MooreRiderLean2012Parameters {
            whipple: Moore2012Parameters::from_benchmark(&p.bicycle),
            d4: g.z_hinge + p.bicycle.r_r,
            l5: g.x,
            l6: g.z - g.z_hinge,
            mg: g.m,
            ig11: g.i_xx,
            ig22: g.i_yy,
            ig31: g.i_xz,
            ig33: g.i_zz,
            k9: g.stiffness,
            c9: g.damping,
        }
    }

    /// Our form (no check of the result; see [`RiderLeanParameters::check`]): the bicycle by
    /// [`Moore2012Parameters::to_benchmark`] (whose errors it returns), the upper body by
    /// z_hinge = d4 − r_R, x_G = l5, z_G = d4 + l6 − r_R.
    pub fn to_rider_lean(&self) -> Result<RiderLeanParameters<T>> {
        let bicycle = self.whipple.to_benchmark()?;
        let z_hinge = self.d4 - self.whipple.rr;
        Ok(RiderLeanParameters {
            bicycle,
            upper_body: UpperBody {
                m: self.mg,
                x: self.l5,
                z: z_hinge + self.l6,
                i_xx: self.ig11,
                i_yy: self.ig22,
                i_zz: self.ig33,
                i_xz: self.ig31,
                z_hinge,
                stiffness: self.k9,
                damping: self.c9,
            },
        })
    }
}

impl MooreRiderLean2012Parameters<f64> {
    /// From (key, value) pairs of BicycleParameters' `MooreRiderLean2012` set: every one of the
    /// 36 keys once, `v` accepted and ignored, other keys refused. Errors are
    /// [`Error::Parse`] of `format` naming the key (unknown, given twice, missing).
    pub fn from_pairs(pairs: &[(String, f64)], format: &'static str) -> Result<Self> {
        let fail = |field: &str, message: String| Error::Parse {
            format,
            field: Some(field.to_string()),
            line: 0,
            column: 0,
            message,
        };
        let mut values: [Option<f64>; 36] = [None; 36];
        for (key, value) in pairs {
            if key == "v" {
                continue;
            }
            let Some(i) = MOORE_RIDER_LEAN2012_KEYS.iter().position(|k| k == key) else {
                return Err(fail(
                    key,
                    format!(
                        "`{key}` is not a key of Moore 2012's rider-lean parameterization ({})",
                        MOORE_RIDER_LEAN2012_KEYS.join(", ")
                    ),
                ));
            };
            if values[i].replace(*value).is_some() {
                return Err(fail(key, format!("`{key}` is given twice")));
            }
        }
        let missing: Vec<&str> = MOORE_RIDER_LEAN2012_KEYS
            .iter()
            .zip(&values)
            .filter(|(_, v)| v.is_none())
            .map(|(k, _)| *k)
            .collect();
        if let Some(first) = missing.first() {
            return Err(fail(first, format!("missing keys: {}", missing.join(", "))));
        }
        Ok(Self::from_array(values.map(|v| v.unwrap_or(0.0))))
    }

    /// BicycleParameters' `mooreriderlean2012_browser_jason` (`parameter_dicts.py`,
    /// BicycleParameters 1.5, BSD-2-Clause; from Moore's dissertation source,
    /// `src/extensions/lean/riderlean.py`): the Browser with Jason's legs in C and his upper
    /// body as G, k9 = c9 = 0. Its `d4` and `l6` are written there as the sums shown.
    pub fn browser_jason() -> Self {
        let rr = 0.340958858855;
        let d4 = -1.011421527346159 + rr;
        Self::from_array([
            0.0,
            0.9631492634872098,
            0.4338396131640938,
            0.0705000000001252,
            d4,
            9.81,
            2.296859222953584,
            2.9922715238,
            0.01594448114273473,
            1.5101858377464155,
            0.0904106601579,
            0.152467620286,
            0.2811355367159554,
            0.246138810935,
            0.0063377219110826045,
            0.06782113764394461,
            0.0883819364527,
            0.149389340425,
            2.038073562525466,
            1.692108544034995,
            0.002113501449812,
            1.100753962972129,
            0.0,
            0.47759794513190806,
            -0.1680324796714025,
            -0.07654646159268344,
            -0.47166687226492093,
            0.231223496809401,
            -1.283035074598082 + rr - d4,
            33.044,
            3.11,
            3.22,
            2.02,
            48.816,
            0.34352982332,
            rr,
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual64;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    /// The keys are Moore 2012's and the upper body's, each once; from_array puts each value
    /// at its key's field and to_array reads it back.
    #[test]
    fn arrays_follow_the_keys() {
        let mut keys: Vec<&str> = MOORE2012_KEYS.iter().chain(&RIDER_KEYS).copied().collect();
        let mut expected = MOORE_RIDER_LEAN2012_KEYS.to_vec();
        keys.sort_unstable();
        expected.sort_unstable();
        assert_eq!(keys, expected);
        let v: [f64; 36] = std::array::from_fn(|i| i as f64);
        let p = MooreRiderLean2012Parameters::from_array(v);
        assert_eq!(p.to_array(), v);
        for (key, x) in MOORE2012_KEYS.iter().zip(p.whipple.to_array()) {
            assert_eq!(MOORE_RIDER_LEAN2012_KEYS[x as usize], *key);
        }
        assert_eq!(MOORE_RIDER_LEAN2012_KEYS[p.d4 as usize], "d4");
        assert_eq!(MOORE_RIDER_LEAN2012_KEYS[p.c9 as usize], "c9");
    }

    /// Moore → ours → Moore gives every key back to 1e-12.
    #[test]
    fn moore_round_trip() {
        let moore = MooreRiderLean2012Parameters::browser_jason();
        let back = MooreRiderLean2012Parameters::from_rider_lean(&moore.to_rider_lean().unwrap());
        for ((key, x), y) in MOORE_RIDER_LEAN2012_KEYS
            .iter()
            .zip(moore.to_array())
            .zip(back.to_array())
        {
            assert!(close(y, x, 1e-12), "{key}: {x} vs {y}");
        }
    }

    /// Ours → Moore → ours, on a bicycle of another shape (the benchmark bicycle with an upper
    /// body moved forward and tilted), to 1e-12.
    #[test]
    fn ours_round_trip() {
        let p = RiderLeanParameters {
            bicycle: BenchmarkParameters::meijaard2007(),
            upper_body: UpperBody {
                m: 40.0,
                x: 0.4,
                z: -1.3,
                i_xx: 2.0,
                i_yy: 1.8,
                i_zz: 0.9,
                i_xz: -0.3,
                z_hinge: -1.0,
                stiffness: 128.0,
                damping: 50.0,
            },
        };
        p.check().unwrap();
        let back = MooreRiderLean2012Parameters::from_rider_lean(&p)
            .to_rider_lean()
            .unwrap();
        for ((x, y), key) in p
            .bicycle
            .to_array()
            .iter()
            .zip(back.bicycle.to_array())
            .zip(crate::parameters::BENCHMARK_TABLE.iter().map(|r| r.key))
        {
            assert!(close(y, *x, 1e-12), "{key}: {x} vs {y}");
        }
        for ((key, x), y) in UPPER_BODY_KEYS
            .iter()
            .zip(p.upper_body.to_array())
            .zip(back.upper_body.to_array())
        {
            assert!(close(y, x, 1e-12), "{key}: {x} vs {y}");
        }
    }

    /// The parameter set's C is BicycleParameters' Moore 2012 form of
    /// `meijaard2007_browser_jasonlegs` (checked there exactly): our bicycle is that benchmark
    /// bicycle, and G sits where Moore's inertia model put it.
    #[test]
    fn browser_jason_is_the_browser_with_jasons_legs() {
        let p = RiderLeanParameters::browser_jason();
        let b = &p.bicycle;
        // BicycleParameters' meijaard2007_browser_jasonlegs (BSD-2-Clause).
        let legs = [
            ("w", b.w, 1.121),
            ("c", b.c, 0.0685808540382),
            ("lam", b.lambda, 0.399680398707),
            ("xB", b.x_b, 0.374570794542),
            ("zB", b.z_b, -0.681592725778),
            ("IBxx", b.i_bxx, 2.18917391377),
            ("IBzz", b.i_bzz, 1.61787114693),
            ("IBxz", b.i_bxz, -0.27087131147),
            ("xH", b.x_h, 0.866949640247),
            ("zH", b.z_h, -0.748236400835),
            ("IHxx", b.i_hxx, 0.253379594731),
            ("IHzz", b.i_hzz, 0.0955770796289),
            ("IHxz", b.i_hxz, -0.0720452391817),
        ];
        for (key, ours, theirs) in legs {
            assert!(close(ours, theirs, 1e-10), "{key}: {ours} vs {theirs}");
        }
        let g = &p.upper_body;
        assert!(close(g.z_hinge, -1.011421527346159, 1e-15));
        assert!(close(g.z, -1.283035074598082, 1e-15));
        assert!(close(g.x, 0.231223496809401, 1e-15));
        assert!(p.check().unwrap().is_empty());
    }

    /// G combined into B gives a valid benchmark bicycle: the mass and the first moments
    /// exactly, and BicycleParameters' `meijaard2007_browser_jason` (Jason's whole body in B,
    /// from the same inertia model by another path) to its agreement with Moore's split,
    /// 5e-5 relative; with the sign of IGxz turned it would miss IBxz by 2e-3.
    #[test]
    fn rigid_rider_is_the_whole_rider_in_b() {
        let p = RiderLeanParameters::browser_jason();
        let rigid = p.rigid();
        rigid.check().unwrap();
        let (b, g) = (&p.bicycle, &p.upper_body);
        assert!(close(rigid.m_b, b.m_b + g.m, 1e-15));
        assert!(close(
            rigid.m_b * rigid.x_b,
            b.m_b * b.x_b + g.m * g.x,
            1e-14
        ));
        assert!(close(
            rigid.m_b * rigid.z_b,
            b.m_b * b.z_b + g.m * g.z,
            1e-14
        ));
        let whole = [
            ("mB", rigid.m_b, 81.86, 1e-15),
            ("xB", rigid.x_b, 0.289099434117, 5e-5),
            ("zB", rigid.z_b, -1.04029228321, 5e-5),
            ("IBxx", rigid.i_bxx, 11.3557360401, 5e-5),
            ("IByy", rigid.i_byy, 12.2177848012, 5e-5),
            ("IBzz", rigid.i_bzz, 3.12354397008, 5e-5),
            ("IBxz", rigid.i_bxz, -1.96756380745, 5e-5),
        ];
        for (key, ours, theirs, tol) in whole {
            assert!(
                (ours - theirs).abs() <= tol * theirs.abs(),
                "{key}: {ours} vs {theirs}"
            );
        }
        // Unchanged: everything but B.
        assert_eq!(rigid.i_hxz, b.i_hxz);
        assert_eq!(rigid.w, b.w);
    }

    /// The conversion runs on dual numbers: d(d4)/d(zHinge) = 1, d(z_G)/d(l6) = 1.
    #[test]
    fn dual_numbers_carry_derivatives() {
        let mut v = MooreRiderLean2012Parameters::browser_jason()
            .to_array()
            .map(Dual64::from_re);
        let l6 = MOORE_RIDER_LEAN2012_KEYS
            .iter()
            .position(|k| *k == "l6")
            .unwrap();
        v[l6].eps = 1.0;
        let ours = MooreRiderLean2012Parameters::from_array(v)
            .to_rider_lean()
            .unwrap();
        assert_eq!(
            (ours.upper_body.z.eps, ours.upper_body.z_hinge.eps),
            (1.0, 0.0)
        );
        let rigid = ours.rigid();
        let share = 48.816 / 81.86;
        assert!((rigid.z_b.eps - share).abs() < 1e-15);
    }

    fn message(p: &RiderLeanParameters) -> String {
        p.check().unwrap_err().to_string()
    }

    #[test]
    fn a_hinge_above_the_bicycles_top_is_refused() {
        let mut p = RiderLeanParameters::browser_jason();
        p.upper_body.z_hinge = -1.5;
        assert_eq!(
            message(&p),
            "invalid parameter `zHinge` = -1.5: the hinge, 1.5 m above the ground, is above the \
             bicycle's top, 1.283035074598082 m (the highest of the wheels' tops and the mass centres of B, \
             H and G)"
        );
        p.upper_body.z_hinge = 0.1;
        assert_eq!(
            message(&p),
            "invalid parameter `zHinge` = 0.1: the hinge must lie above the ground (z points \
             down: zHinge < 0)"
        );
    }

    #[test]
    fn bad_upper_bodies_are_refused_by_key() {
        let base = RiderLeanParameters::browser_jason();
        let mut p = base;
        p.upper_body.m = -1.0;
        assert_eq!(
            message(&p),
            "invalid parameter `mG` = -1: the rider's upper body must have a positive mass (a \
             massless body leaves its lean undetermined)"
        );
        let mut p = base;
        p.upper_body.damping = -2.0;
        assert_eq!(
            message(&p),
            "invalid parameter `cLean` = -2: the hinge's stiffness and damping are passive and \
             must not be negative"
        );
        let mut p = base;
        p.upper_body.x = f64::NAN;
        assert_eq!(
            message(&p),
            "invalid parameter `xG` = NaN: must be a finite number"
        );
        let mut p = base;
        p.upper_body.i_xz = 3.0;
        let e = message(&p);
        assert!(
            e.starts_with(
                "invalid bicycle (IGxx, IGzz, IGxz): the inertia tensor is not positive \
                 semi-definite: IGxz² = 9 exceeds IGxx·IGzz = "
            ),
            "{e}"
        );
        // The bicycle's own checks come first, under its keys.
        let mut p = base;
        p.bicycle.m_b = -1.0;
        assert!(message(&p).contains("`mB`"));
    }
}
