//! Moore's parameterization of the Whipple bicycle (Moore 2012, "Human control of a bicycle",
//! PhD dissertation, UC Davis, ch. 2; BicycleParameters' `Moore2012` parameter set): the same
//! four bodies as the benchmark, named C (rear frame with rider), D (rear wheel), E (front
//! frame) and F (front wheel), placed along the steer axis rather than from the ground.
//!
//! Geometry: `d1` the rear wheel centre's perpendicular distance from the steer axis, `d3` the
//! front wheel centre's (the offset, fork rake), `d2` the distance along the steer axis between
//! the feet of those two perpendiculars. Mass centres in axes turned by λ about y, so that the
//! third axis lies along the steer axis: (`l1`, `l2`) C's from the rear wheel centre, (`l3`,
//! `l4`) E's from the front wheel centre. Inertia tensors of C and E about their mass centres in
//! those turned axes (`ic11`, `ic22`, `ic31`, `ic33`; `ie..`), the wheels' diametral and spin
//! moments (`id11`, `id22`; `if11`, `if22`).
//!
//! The benchmark → Moore direction is BicycleParameters' (through `dtk.bicycle
//! .benchmark_to_moore`, written independently here); the reverse is ours: the wheelbase and the
//! tilt from the rear-to-front wheel centre vector, which the turn by λ maps from (w, r_R − r_F)
//! to (d1 + d3, d2).

use crate::math::Real;

use super::BenchmarkParameters;
use crate::error::{Error, Result, short_number};

/// Moore 2012's parameters, SI units: the benchmark's four bodies as C (rear frame with rider),
/// D (rear wheel), E (front frame) and F (front wheel), placed along the steer axis. `d1`, `d3`
/// are the rear and front wheel centres' perpendicular distances from the steer axis, `d2` the
/// distance along it between the feet of those perpendiculars; (`l1`, `l2`) C's mass centre from
/// the rear wheel centre and (`l3`, `l4`) E's from the front wheel centre, in axes turned by λ
/// about y so that the third runs down the steer axis; C's and E's tensors about their mass
/// centres in those axes; the wheels' diametral (`id11`, `if11`) and spin (`id22`, `if22`)
/// moments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Moore2012Parameters<T = f64> {
    /// r_F, front wheel radius \[m\].
    pub rf: T,
    /// r_R, rear wheel radius \[m\].
    pub rr: T,
    /// d1, rear wheel centre's perpendicular distance from the steer axis \[m\].
    pub d1: T,
    /// d2, along the steer axis between the feet of the wheel centres' perpendiculars \[m\].
    pub d2: T,
    /// d3, front wheel centre's perpendicular distance from the steer axis (fork offset) \[m\].
    pub d3: T,
    /// l1, C's mass centre from the rear wheel centre, perpendicular to the steer axis \[m\].
    pub l1: T,
    /// l2, C's mass centre from the rear wheel centre, along the steer axis (down) \[m\].
    pub l2: T,
    /// l3, E's mass centre from the front wheel centre, perpendicular to the steer axis \[m\].
    pub l3: T,
    /// l4, E's mass centre from the front wheel centre, along the steer axis (down) \[m\].
    pub l4: T,
    /// m_C, rear frame with rider mass \[kg\].
    pub mc: T,
    /// m_D, rear wheel mass \[kg\].
    pub md: T,
    /// m_E, front frame mass \[kg\].
    pub me: T,
    /// m_F, front wheel mass \[kg\].
    pub mf: T,
    /// I_C11, C's moment about its mass centre, first axis (perpendicular to the steer axis) \[kg m²\].
    pub ic11: T,
    /// I_C22, C's lateral moment about its mass centre \[kg m²\].
    pub ic22: T,
    /// I_C31, C's product of inertia in the steer-axis axes (the tensor's 31 entry) \[kg m²\].
    pub ic31: T,
    /// I_C33, C's moment about an axis through its mass centre parallel to the steer axis \[kg m²\].
    pub ic33: T,
    /// I_D11, rear wheel diametral moment \[kg m²\].
    pub id11: T,
    /// I_D22, rear wheel spin moment \[kg m²\].
    pub id22: T,
    /// I_E11, E's moment about its mass centre, first axis \[kg m²\].
    pub ie11: T,
    /// I_E22, E's lateral moment \[kg m²\].
    pub ie22: T,
    /// I_E31, E's product of inertia in the steer-axis axes \[kg m²\].
    pub ie31: T,
    /// I_E33, E's moment about an axis through its mass centre parallel to the steer axis \[kg m²\].
    pub ie33: T,
    /// I_F11, front wheel diametral moment \[kg m²\].
    pub if11: T,
    /// I_F22, front wheel spin moment \[kg m²\].
    pub if22: T,
    /// g, gravity \[m/s²\].
    pub g: T,
}

/// The keys of a Moore 2012 parameter set, as BicycleParameters names them, in the order of
/// [`Moore2012Parameters::to_array`].
pub const MOORE2012_KEYS: [&str; 26] = [
    "rf", "rr", "d1", "d2", "d3", "l1", "l2", "l3", "l4", "mc", "md", "me", "mf", "ic11", "ic22",
    "ic31", "ic33", "id11", "id22", "ie11", "ie22", "ie31", "ie33", "if11", "if22", "g",
];

fn to_f64<T: Real>(x: T) -> f64 {
    x.to_subset().unwrap_or(f64::NAN)
}

/// An in-plane tensor [xx, zz, xz] in axes turned by the angle whose sine and cosine are `s`,
/// `c` (R = [[c, −s], [s, c]] in the x-z plane, R I Rᵀ), as [11, 33, 31].
fn turn<T: Real>(xx: T, zz: T, xz: T, s: T, c: T) -> [T; 3] {
    let two: T = nalgebra::convert(2.0);
    [
        c * c * xx - two * c * s * xz + s * s * zz,
        s * s * xx + two * c * s * xz + c * c * zz,
        s * c * (xx - zz) + (c * c - s * s) * xz,
    ]
}

impl<T: Real> Moore2012Parameters<T> {
    /// The values in the order of [`MOORE2012_KEYS`].
    pub fn to_array(&self) -> [T; 26] {
        [
            self.rf, self.rr, self.d1, self.d2, self.d3, self.l1, self.l2, self.l3, self.l4,
            self.mc, self.md, self.me, self.mf, self.ic11, self.ic22, self.ic31, self.ic33,
            self.id11, self.id22, self.ie11, self.ie22, self.ie31, self.ie33, self.if11, self.if22,
            self.g,
        ]
    }

    /// From the values in the order of [`MOORE2012_KEYS`].
    pub fn from_array(v: [T; 26]) -> Self {
        let [
            rf,
            rr,
            d1,
            d2,
            d3,
            l1,
            l2,
            l3,
            l4,
            mc,
            md,
            me,
            mf,
            ic11,
            ic22,
            ic31,
            ic33,
            id11,
            id22,
            ie11,
            ie22,
            ie31,
            ie33,
            if11,
            if22,
            g,
        ] = v;
        Moore2012Parameters {
            rf,
            rr,
            d1,
            d2,
            d3,
            l1,
            l2,
            l3,
            l4,
            mc,
            md,
            me,
            mf,
            ic11,
            ic22,
            ic31,
            ic33,
            id11,
            id22,
            ie11,
            ie22,
            ie31,
            ie33,
            if11,
            if22,
            g,
        }
    }

    /// Moore 2012's parameters of a benchmark bicycle, exactly (no check): what
    /// BicycleParameters' `Meijaard2007ParameterSet.to_parameterization("Moore2012")` computes,
    /// with l3 and l4 from the front wheel centre.
    ///
    /// ```
    /// use whipple::BenchmarkParameters;
    /// use whipple::advanced::parameters::Moore2012Parameters;
    /// let m = Moore2012Parameters::from_benchmark(&BenchmarkParameters::meijaard2007());
    /// assert!((m.d1 - 0.9534570696121849).abs() < 1e-15); // dtk's docstring value
    /// ```
    pub fn from_benchmark(b: &BenchmarkParameters<T>) -> Self {
        let (s, c) = crate::math::sin_cos(b.lambda);
        let d1 = c * (b.c + b.w - b.r_r * s / c);
        let d3 = -c * (b.c - b.r_f * s / c);
        let d2 = (b.r_r + d1 * s - b.r_f + d3 * s) / c;
        let zr = b.z_b + b.r_r;
        let l1 = b.x_b * c - zr * s;
        let l2 = b.x_b * s + zr * c;
        let (x, z) = (b.x_h - b.w, b.z_h + b.r_f);
        let l4 = z * c + x * s;
        let l3 = (x - l4 * s) / c;
        let [ic11, ic33, ic31] = turn(b.i_bxx, b.i_bzz, b.i_bxz, s, c);
        let [ie11, ie33, ie31] = turn(b.i_hxx, b.i_hzz, b.i_hxz, s, c);
        Moore2012Parameters {
            rf: b.r_f,
            rr: b.r_r,
            d1,
            d2,
            d3,
            l1,
            l2,
            l3,
            l4,
            mc: b.m_b,
            md: b.m_r,
            me: b.m_h,
            mf: b.m_f,
            ic11,
            ic22: b.i_byy,
            ic31,
            ic33,
            id11: b.i_rxx,
            id22: b.i_ryy,
            ie11,
            ie22: b.i_hyy,
            ie31,
            ie33,
            if11: b.i_fxx,
            if22: b.i_fyy,
            g: b.g,
        }
    }

    /// The benchmark parameters (no check of the result; see [`BenchmarkParameters::check`]).
    ///
    /// The turn by λ maps the vector from the rear wheel centre to the front one, (w, r_R −
    /// r_F) in (forward, up), to (d1 + d3, d2); so w = √((d1 + d3)² + d2² − (r_R − r_F)²), the
    /// positive root, and λ is the angle between the two vectors. Then c, the mass centres and
    /// the tensors follow by turning back by −λ.
    ///
    /// Errors: wheel centres closer together than their height difference (no real wheelbase:
    /// `d1, d2, d3, rr, rf`), a tilt of ±π/2 or beyond (`d1, d2, d3`).
    pub fn to_benchmark(&self) -> Result<BenchmarkParameters<T>> {
        let zero = T::zero();
        let rise = self.rr - self.rf;
        let along = self.d1 + self.d3;
        let w2 = along * along + self.d2 * self.d2 - rise * rise;
        let positive = w2 > zero; // false for NaN
        if !positive {
            return Err(Error::InvalidBicycle {
                fields: "d1, d2, d3, rr, rf".into(),
                rule: format!(
                    "the wheel centres are {} m apart, no more than their height difference \
                     rr − rf = {} m: no positive wheelbase",
                    short_number(to_f64((along * along + self.d2 * self.d2).sqrt())),
                    short_number(to_f64(rise))
                ),
            });
        }
        let w = w2.sqrt();
        let lambda = crate::math::atan2(self.d2, along) - crate::math::atan2(rise, w);
        let (s, c) = crate::math::sin_cos(lambda);
        let upright = c > zero;
        if !upright {
            return Err(Error::InvalidBicycle {
                fields: "d1, d2, d3".into(),
                rule: format!(
                    "the steer axis tilt they give, {} rad, is not within ±π/2",
                    short_number(to_f64(lambda))
                ),
            });
        }
        let trail = (self.rf * s - self.d3) / c;
        let zr = -self.l1 * s + self.l2 * c;
        let x_h = self.l3 * c + self.l4 * s + w;
        let z_h = -self.l3 * s + self.l4 * c - self.rf;
        let [i_bxx, i_bzz, i_bxz] = turn(self.ic11, self.ic33, self.ic31, -s, c);
        let [i_hxx, i_hzz, i_hxz] = turn(self.ie11, self.ie33, self.ie31, -s, c);
        Ok(BenchmarkParameters {
            w,
            c: trail,
            lambda,
            g: self.g,
            r_r: self.rr,
            m_r: self.md,
            i_rxx: self.id11,
            i_ryy: self.id22,
            x_b: self.l1 * c + self.l2 * s,
            z_b: zr - self.rr,
            m_b: self.mc,
            i_bxx,
            i_byy: self.ic22,
            i_bzz,
            i_bxz,
            x_h,
            z_h,
            m_h: self.me,
            i_hxx,
            i_hyy: self.ie22,
            i_hzz,
            i_hxz,
            r_f: self.rf,
            m_f: self.mf,
            i_fxx: self.if11,
            i_fyy: self.if22,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;
    use num_dual::Dual64;

    fn close(a: f64, b: f64, scale: f64) -> bool {
        (a - b).abs() <= 1e-12 * scale.max(a.abs())
    }

    /// dtk's docstring of `benchmark_to_moore` for the benchmark bicycle (17 digits printed).
    #[test]
    fn benchmark_bicycle_as_dtk_prints_it() {
        let m = Moore2012Parameters::from_benchmark(&BenchmarkParameters::meijaard2007());
        let expected = [
            ("d1", m.d1, 0.9534570696121849),
            ("d2", m.d2, 0.2676445084476887),
            ("d3", m.d3, 0.03207142672761929),
            ("ic11", m.ic11, 7.178169776497895),
            ("ic31", m.ic31, 3.8225535938357873),
            ("ic33", m.ic33, 4.821830223502103),
            ("ie11", m.ie11, 0.05841337700152972),
            ("ie31", m.ie31, 0.009119225261946298),
            ("ie33", m.ie33, 0.007586622998470264),
            ("l1", m.l1, 0.4707271515135145),
            ("l2", m.l2, -0.47792881146460797),
            ("l3", m.l3, -0.00597083392418685),
            ("l4", m.l4, -0.3699518200282974),
        ];
        for (key, ours, theirs) in expected {
            assert!(close(ours, theirs, 1.0), "{key}: {ours} vs {theirs}");
        }
    }

    /// Benchmark → Moore → benchmark gives every preset back to 1e-12 (relative to the
    /// parameter, or to the body's largest moment for a tensor entry).
    #[test]
    fn round_trip_every_preset() {
        for preset in presets::PRESETS {
            let Ok(b) = preset.bicycle().benchmark() else {
                continue;
            };
            let back = Moore2012Parameters::from_benchmark(&b)
                .to_benchmark()
                .expect("a valid bicycle converts back");
            let scale_b = b.i_bxx.abs().max(b.i_bzz.abs());
            let scale_h = b.i_hxx.abs().max(b.i_hzz.abs());
            for ((p, x), y) in crate::parameters::BENCHMARK_TABLE
                .iter()
                .zip(b.to_array())
                .zip(back.to_array())
            {
                let scale = match p.key {
                    "IBxx" | "IBzz" | "IBxz" => scale_b,
                    "IHxx" | "IHzz" | "IHxz" => scale_h,
                    "xB" | "zB" | "xH" | "zH" | "c" => b.w,
                    _ => 0.0,
                };
                assert!(close(x, y, scale), "{} {}: {x} vs {y}", preset.name, p.key);
            }
        }
    }

    /// The conversion runs on dual numbers: d(d1)/d(w) = cos λ.
    #[test]
    fn dual_numbers_carry_derivatives() {
        let b = BenchmarkParameters::meijaard2007();
        let mut values = b.to_array().map(Dual64::from_re);
        values[0] = Dual64::new(b.w, 1.0);
        let m = Moore2012Parameters::from_benchmark(&BenchmarkParameters::from_array(values));
        assert!((m.d1.eps - crate::math::cos(b.lambda)).abs() < 1e-15);
        let back = m.to_benchmark().unwrap();
        assert!((back.w.eps - 1.0).abs() < 1e-12 && back.c.eps.abs() < 1e-12);
        assert!((back.w.re - b.w).abs() < 1e-15);
    }

    #[test]
    fn no_wheelbase_is_an_error() {
        let mut m = Moore2012Parameters::from_benchmark(&BenchmarkParameters::meijaard2007());
        (m.d1, m.d2, m.d3) = (0.0, 0.0, 0.0);
        let e = m.to_benchmark().unwrap_err().to_string();
        assert!(
            e.contains("d1, d2, d3, rr, rf") && e.contains("no positive wheelbase"),
            "{e}"
        );
    }
}
