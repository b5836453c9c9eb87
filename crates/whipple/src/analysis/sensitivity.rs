//! Exact derivatives of what users quote — the canonical matrices, the eigenvalues at a speed,
//! the critical speeds and the stable range — with respect to every parameter of the bicycle's
//! own form (benchmark or JBike6), and from them first-order uncertainty (parameters
//! independent) and sensitivities.
//!
//! Nothing is differenced: each parameter's derivative comes from one pass of dual numbers
//! ([`num_dual::Dual64`]) through the same conversion (JBike6 → benchmark) and the same
//! Appendix A code that gives the f64 results ([`Canonical::from_parameters`]). An eigenvalue
//! λ, a root of p(λ) = Σ aₖ λᵏ, moves by dλ = −(∂p/∂pᵢ)/(∂p/∂λ); a critical speed v*, a root of
//! the polynomial F(v) whose sign change marks it (a₀ for capsize, the Hurwitz determinant Δ₃ for
//! weave, a₁ or a₃ at some stable-range ends), moves by dv* = −(∂F/∂pᵢ)/(∂F/∂v) (implicit
//! differentiation); the double-root speed, where p = ∂p/∂λ = 0, by dv = −(∂p/∂pᵢ)/(∂p/∂v).
//!
//! ```
//! use whipple::advanced::sensitivity::ParameterDerivatives;
//! use whipple::presets;
//! let bike = presets::find("benchmark")?.bicycle();
//! let d = ParameterDerivatives::new(&bike)?;
//! let critical = whipple::critical_speeds(&d.canonical, 0.0, 10.0)?;
//! let dv = d.weave_speed_derivatives(&critical).unwrap();
//! let trail = d.index("c").unwrap();
//! assert!((dv[trail] - 11.48).abs() < 0.01); // more trail, a higher weave speed
//! # Ok::<(), whipple::Error>(())
//! ```

use nalgebra::Matrix2;
use num_dual::Dual64;
use serde::Serialize;

use super::eigen::{Complex64, eigenvalues, horner};
use super::modes::Mode;
use super::stability::{CriticalSpeeds, critical_speeds};
use super::sweep::{eigen_sweep, speed_grid};
use crate::error::{Error, Result};
use crate::linear::Canonical;
use crate::parameters::table::{Form, ParameterInfo, parameters};
use crate::parameters::{BenchmarkParameters, Bicycle, Description, Jbike6Parameters};

/// The canonical matrices of a bicycle and their exact derivatives with respect to each
/// parameter of its own form, with the parameters' values and standard deviations.
#[derive(Debug, Clone)]
pub struct ParameterDerivatives {
    /// The form whose parameters are differentiated.
    pub form: Form,
    /// The parameters, in the form's table order.
    pub parameters: &'static [ParameterInfo],
    /// Their values.
    pub values: Vec<f64>,
    /// Their standard deviations (0 where not given).
    pub sigma: Vec<f64>,
    /// The canonical matrices at the values.
    pub canonical: Canonical,
    /// ∂(M, C₁, K₀, K₂, g)/∂pᵢ, one per parameter.
    pub d_canonical: Vec<Canonical>,
}

fn eps(m: &Matrix2<Dual64>) -> Matrix2<f64> {
    m.map(|x| x.eps)
}

fn re(m: &Matrix2<Dual64>) -> Matrix2<f64> {
    m.map(|x| x.re)
}

fn dual_matrix(m: &Matrix2<f64>, d: &Matrix2<f64>) -> Matrix2<Dual64> {
    Matrix2::from_fn(|i, j| Dual64::new(m[(i, j)], d[(i, j)]))
}

/// The benchmark parameters of a form's values, on any scalar.
fn benchmark_of(form: Form, values: &[Dual64]) -> Result<BenchmarkParameters<Dual64>> {
    let bad = || Error::InvalidArgument {
        what: "parameters",
        rule: "wrong number of values for the form".into(),
    };
    Ok(match form {
        Form::Benchmark => BenchmarkParameters::from_array(values.try_into().map_err(|_| bad())?),
        Form::Jbike6 => Jbike6Parameters::from_array(values.try_into().map_err(|_| bad())?)
            .to_benchmark_unchecked(),
    })
}

/// Which polynomial in v a critical speed is a root of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Root {
    A0,
    A1,
    A3,
    Delta3,
}

fn root_function(root: Root, a: &[Dual64; 5]) -> Dual64 {
    match root {
        Root::A0 => a[0],
        Root::A1 => a[1],
        Root::A3 => a[3],
        Root::Delta3 => a[3] * a[2] * a[1] - a[4] * a[1] * a[1] - a[0] * a[3] * a[3],
    }
}

impl ParameterDerivatives {
    /// Checks the bicycle (warnings do not stop it) and differentiates its canonical matrices
    /// with respect to every parameter of its own form: one dual-number pass per parameter.
    pub fn new(bike: &Bicycle) -> Result<Self> {
        let checked = bike.check()?;
        let form = bike.description.form();
        let table = parameters(form);
        let values = bike.description.values();
        let sigma = table.iter().map(|p| bike.sigma_of(p.key)).collect();
        let canonical = Canonical::new(&checked.benchmark)?;
        let mut d_canonical = Vec::with_capacity(values.len());
        for i in 0..values.len() {
            let seeded: Vec<Dual64> = values
                .iter()
                .enumerate()
                .map(|(j, v)| Dual64::new(*v, if i == j { 1.0 } else { 0.0 }))
                .collect();
            let b = benchmark_of(form, &seeded)?;
            let c = Canonical::from_parameters(&b);
            d_canonical.push(Canonical {
                m: eps(&c.m),
                c1: eps(&c.c1),
                k0: eps(&c.k0),
                k2: eps(&c.k2),
                g: c.g.eps,
            });
            debug_assert!((re(&c.m) - canonical.m).norm() <= 1e-9 * canonical.m.norm());
        }
        Ok(ParameterDerivatives {
            form,
            parameters: table,
            values,
            sigma,
            canonical,
            d_canonical,
        })
    }

    /// The position of a parameter (by file key) in [`ParameterDerivatives::parameters`].
    pub fn index(&self, key: &str) -> Option<usize> {
        self.parameters
            .iter()
            .position(|p| p.key == key || p.path == key)
    }

    /// The canonical matrices as dual numbers in the direction of parameter `i`.
    fn dual(&self, i: usize) -> Canonical<Dual64> {
        let (c, d) = (&self.canonical, &self.d_canonical[i]);
        Canonical {
            m: dual_matrix(&c.m, &d.m),
            c1: dual_matrix(&c.c1, &d.c1),
            k0: dual_matrix(&c.k0, &d.k0),
            k2: dual_matrix(&c.k2, &d.k2),
            g: Dual64::new(c.g, d.g),
        }
    }

    /// The canonical matrices as dual numbers with no parameter direction (for ∂/∂v).
    fn constant(&self) -> Canonical<Dual64> {
        let c = &self.canonical;
        let z = Matrix2::zeros();
        Canonical {
            m: dual_matrix(&c.m, &z),
            c1: dual_matrix(&c.c1, &z),
            k0: dual_matrix(&c.k0, &z),
            k2: dual_matrix(&c.k2, &z),
            g: Dual64::new(c.g, 0.0),
        }
    }

    /// ∂aₖ/∂pᵢ of the characteristic quartic's coefficients at speed v, for every parameter.
    pub fn quartic_derivatives(&self, v: f64) -> Vec<[f64; 5]> {
        (0..self.values.len())
            .map(|i| self.dual(i).quartic_at(Dual64::from(v)).map(|a| a.eps))
            .collect()
    }

    /// First-order standard deviation of a quantity from its derivatives: √Σ(∂f/∂pᵢ σᵢ)²,
    /// formed as a scaled norm (each term divided by the largest before squaring), so it
    /// overflows only where the true value is past `f64::MAX` (then it is +∞).
    pub fn sigma_of(&self, derivatives: &[f64]) -> f64 {
        let terms = || derivatives.iter().zip(&self.sigma).map(|(d, s)| d * s);
        let largest = terms().fold(0.0_f64, |m, t| m.max(t.abs()));
        if largest == 0.0 || !largest.is_finite() {
            return largest;
        }
        largest * terms().map(|t| (t / largest).powi(2)).sum::<f64>().sqrt()
    }

    /// [`ParameterDerivatives::sigma_of`] of a speed `what` [m/s] whose value is `value`,
    /// refused where first-order propagation says nothing: a σ that is not a finite number, or
    /// one larger than the speed's own size (its one-σ interval then reaches past zero: the parameters'
    /// σ are too large for a linear propagation, which assumes the quantity changes little
    /// over them). The error names the parameter that contributes most, by its file key, with
    /// its σ ([`Error::InvalidParameter`]).
    pub(crate) fn checked_sigma_of(
        &self,
        derivatives: &[f64],
        what: &str,
        value: f64,
    ) -> Result<f64> {
        let sigma = self.sigma_of(derivatives);
        if sigma.is_finite() && sigma <= value.abs() {
            return Ok(sigma);
        }
        Err(self.absurd_sigma(derivatives, what, value, sigma, "m/s"))
    }

    /// The error for a σ of `what` that first-order propagation cannot give (see
    /// [`ParameterDerivatives::checked_sigma_of`]).
    fn absurd_sigma(
        &self,
        derivatives: &[f64],
        what: &str,
        value: f64,
        sigma: f64,
        unit: &str,
    ) -> Error {
        let contribution = |i: usize| (derivatives[i] * self.sigma[i]).abs();
        let worst = (0..derivatives.len().min(self.sigma.len()))
            .max_by(|a, b| contribution(*a).total_cmp(&contribution(*b)))
            .unwrap_or(0);
        let (field, parameter_sigma) = (
            self.parameters.get(worst).map_or("?", |p| p.key),
            self.sigma.get(worst).copied().unwrap_or(f64::NAN),
        );
        let size = if sigma.is_finite() {
            format!(
                "σ of {what} = {} {unit}, more than {what} = {} {unit} itself",
                crate::error::short_number(sigma),
                crate::error::short_number(value)
            )
        } else {
            format!("σ of {what} past {:e} {unit}", f64::MAX)
        };
        Error::InvalidParameter {
            field: field.to_string(),
            value: parameter_sigma,
            rule: format!(
                "this standard deviation, the largest contribution, gives {size}: a first-order \
                 σ means nothing when the parameters' σ change the quantity by more than its size \
                 (is the σ in the parameter's unit?)"
            ),
        }
    }

    /// Standard deviations of the entries of M, C₁, K₀, K₂ (first order).
    pub fn canonical_sigma(&self) -> [Matrix2<f64>; 4] {
        let pick = |f: &dyn Fn(&Canonical) -> Matrix2<f64>| {
            Matrix2::from_fn(|r, c| {
                let d: Vec<f64> = self.d_canonical.iter().map(|dc| f(dc)[(r, c)]).collect();
                self.sigma_of(&d)
            })
        };
        [
            pick(&|c| c.m),
            pick(&|c| c.c1),
            pick(&|c| c.k0),
            pick(&|c| c.k2),
        ]
    }

    /// dλ/dpᵢ of each eigenvalue at speed v (in the order of [`eigenvalues`]); `None` for an
    /// eigenvalue at a double root, where it is not differentiable.
    pub fn eigenvalue_derivatives(
        &self,
        v: f64,
    ) -> Result<Vec<(Complex64, Option<Vec<Complex64>>)>> {
        let lambdas = eigenvalues(&self.canonical, v)?;
        let a = self.canonical.quartic_at(v);
        let da = self.quartic_derivatives(v);
        let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        Ok(lambdas
            .iter()
            .map(|&l| {
                let (_, dp) = horner(&a, l);
                let size = (0..5).fold(0.0, |s, k| {
                    s + a[k].abs() * crate::math::norm(l).powi(k as i32)
                });
                if crate::math::norm(dp) <= 1e-9 * size.max(scale) {
                    return (l, None);
                }
                let d = da
                    .iter()
                    .map(|dai| {
                        let (pi, _) = horner(dai, l);
                        -pi / dp
                    })
                    .collect();
                (l, Some(d))
            })
            .collect())
    }

    /// dv*/dpᵢ for a root v* of `root`'s polynomial; `None` where that polynomial has a
    /// multiple root there (∂F/∂v = 0).
    fn root_derivatives(&self, v: f64, root: Root) -> Option<Vec<f64>> {
        let fv = root_function(root, &self.constant().quartic_at(Dual64::new(v, 1.0))).eps;
        if fv == 0.0 || !fv.is_finite() {
            return None;
        }
        let d: Vec<f64> = (0..self.values.len())
            .map(|i| -root_function(root, &self.dual(i).quartic_at(Dual64::from(v))).eps / fv)
            .collect();
        d.iter().all(|x| x.is_finite()).then_some(d)
    }

    /// The polynomial (a₀, a₁, a₃ or Δ₃) of which v is the nearest root, by Newton step length.
    fn nearest_root(&self, v: f64) -> Root {
        let a = self.constant().quartic_at(Dual64::new(v, 1.0));
        [Root::A0, Root::A1, Root::A3, Root::Delta3]
            .into_iter()
            .min_by(|x, y| {
                let step = |r: Root| {
                    let f = root_function(r, &a);
                    (f.re / f.eps).abs()
                };
                step(*x).total_cmp(&step(*y))
            })
            .unwrap_or(Root::Delta3)
    }

    /// dv_w/dpᵢ of the weave speed (a root of Δ₃).
    pub fn weave_speed_derivatives(&self, critical: &CriticalSpeeds) -> Option<Vec<f64>> {
        self.root_derivatives(critical.weave_speed?, Root::Delta3)
    }

    /// dv_c/dpᵢ of the capsize speed (a root of a₀).
    pub fn capsize_speed_derivatives(&self, critical: &CriticalSpeeds) -> Option<Vec<f64>> {
        self.root_derivatives(critical.capsize_speed?, Root::A0)
    }

    /// dv_d/dpᵢ of the double-root speed: at (λ_d, v_d) both p and ∂p/∂λ vanish, so
    /// dv_d = −(∂p/∂pᵢ)/(∂p/∂v).
    pub fn double_root_speed_derivatives(&self, critical: &CriticalSpeeds) -> Option<Vec<f64>> {
        let (v, l) = (
            critical.double_root_speed?,
            critical.double_root_eigenvalue?,
        );
        let at = |a: [Dual64; 5]| {
            let mut p = a[4];
            for k in (0..4).rev() {
                p = p * Dual64::from(l) + a[k];
            }
            p.eps
        };
        let pv = at(self.constant().quartic_at(Dual64::new(v, 1.0)));
        if pv == 0.0 || !pv.is_finite() {
            return None;
        }
        let d: Vec<f64> = (0..self.values.len())
            .map(|i| -at(self.dual(i).quartic_at(Dual64::from(v))) / pv)
            .collect();
        d.iter().all(|x| x.is_finite()).then_some(d)
    }

    /// d(end)/dpᵢ of an end of a stable speed range, unless it is an end of the range searched
    /// (then `None`: it does not move with the bicycle).
    pub fn range_end_derivatives(&self, end: f64, critical: &CriticalSpeeds) -> Option<Vec<f64>> {
        if end == critical.range.0 || end == critical.range.1 || !end.is_finite() {
            return None;
        }
        self.root_derivatives(end, self.nearest_root(end))
    }
}

/// The critical speeds with their standard deviations (`None` where the speed does not exist or
/// is not differentiable).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalSpeedsSigma {
    /// The critical speeds themselves (serialized in line: one object with the σ fields, as
    /// `whipple speeds --format json` writes it).
    #[serde(flatten)]
    pub speeds: CriticalSpeeds,
    /// σ of v_d [m/s].
    pub double_root_speed_sigma: Option<f64>,
    /// σ of v_w [m/s].
    pub weave_speed_sigma: Option<f64>,
    /// σ of v_c [m/s].
    pub capsize_speed_sigma: Option<f64>,
    /// σ of each stable range's ends [m/s] (`None` at an end of the range searched).
    pub stable_speed_ranges_sigma: Vec<(Option<f64>, Option<f64>)>,
}

/// The critical speeds in [lo, hi] with first-order standard deviations from the bicycle's
/// parameter sigmas.
///
/// ```
/// use whipple::advanced::sensitivity::critical_speeds_sigma;
/// use whipple::advanced::io;
/// use whipple::presets;
/// let mut bike = presets::find("benchmark")?.bicycle();
/// bike.sigma.insert("c".into(), 0.001);
/// let s = critical_speeds_sigma(&bike, 0.0, 10.0)?;
/// assert!(s.weave_speed_sigma.unwrap() > 0.0);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn critical_speeds_sigma(bike: &Bicycle, lo: f64, hi: f64) -> Result<CriticalSpeedsSigma> {
    let d = ParameterDerivatives::new(bike)?;
    let speeds = critical_speeds(&d.canonical, lo, hi)?;
    let sig = |x: Option<Vec<f64>>, what: &str, value: Option<f64>| -> Result<Option<f64>> {
        match (x, value) {
            (Some(x), Some(value)) => d.checked_sigma_of(&x, what, value).map(Some),
            _ => Ok(None),
        }
    };
    // The named speeds first: an absurd σ is reported on v_d, v_w or v_c where it can be.
    let double_root_speed_sigma = sig(
        d.double_root_speed_derivatives(&speeds),
        "v_d",
        speeds.double_root_speed,
    )?;
    let weave_speed_sigma = sig(
        d.weave_speed_derivatives(&speeds),
        "v_w",
        speeds.weave_speed,
    )?;
    let capsize_speed_sigma = sig(
        d.capsize_speed_derivatives(&speeds),
        "v_c",
        speeds.capsize_speed,
    )?;
    let stable_speed_ranges_sigma = speeds
        .stable_speed_ranges
        .iter()
        .map(|(a, b)| {
            Ok((
                sig(
                    d.range_end_derivatives(*a, &speeds),
                    "a stable range's start",
                    Some(*a),
                )?,
                sig(
                    d.range_end_derivatives(*b, &speeds),
                    "a stable range's end",
                    Some(*b),
                )?,
            ))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(CriticalSpeedsSigma {
        double_root_speed_sigma,
        weave_speed_sigma,
        capsize_speed_sigma,
        stable_speed_ranges_sigma,
        speeds,
    })
}

/// Each eigenvalue at a speed with the standard deviations of its real and imaginary parts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EigenvalueSigma {
    /// Real part [1/s].
    pub re: f64,
    /// Imaginary part [rad/s].
    pub im: f64,
    /// σ of the real part (`None` at a double root).
    pub re_sigma: Option<f64>,
    /// σ of the imaginary part (`None` at a double root).
    pub im_sigma: Option<f64>,
}

/// The eigenvalues at speed v with first-order standard deviations.
pub fn eigenvalue_sigmas(d: &ParameterDerivatives, v: f64) -> Result<Vec<EigenvalueSigma>> {
    d.eigenvalue_derivatives(v)?
        .into_iter()
        .map(|(l, dl)| {
            let (re_sigma, im_sigma) = match dl {
                Some(dl) => {
                    let re: Vec<f64> = dl.iter().map(|z| z.re).collect();
                    let im: Vec<f64> = dl.iter().map(|z| z.im).collect();
                    let (re_sigma, im_sigma) = (d.sigma_of(&re), d.sigma_of(&im));
                    // Never an infinite σ: the parameter's σ that overflows it is named.
                    if !re_sigma.is_finite() {
                        return Err(d.absurd_sigma(&re, "Re λ", l.re, re_sigma, "1/s"));
                    }
                    if !im_sigma.is_finite() {
                        return Err(d.absurd_sigma(&im, "Im λ", l.im, im_sigma, "rad/s"));
                    }
                    (Some(re_sigma), Some(im_sigma))
                }
                None => (None, None),
            };
            Ok(EigenvalueSigma {
                re: l.re,
                im: l.im,
                re_sigma,
                im_sigma,
            })
        })
        .collect()
}

/// The sensitivities of one parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterSensitivity {
    /// File key (`c`, `mrider`).
    pub key: &'static str,
    /// Symbol (`c`, `m`).
    pub symbol: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Its value.
    pub value: f64,
    /// ∂v_w/∂p [m/s per unit of p].
    pub weave_speed: Option<f64>,
    /// ∂v_c/∂p.
    pub capsize_speed: Option<f64>,
    /// ∂(width of the first stable range)/∂p.
    pub stable_width: Option<f64>,
    /// Elasticity ∂ln v_w/∂ln p = (p / v_w) ∂v_w/∂p (dimensionless).
    pub weave_speed_elasticity: Option<f64>,
    /// Elasticity of v_c.
    pub capsize_speed_elasticity: Option<f64>,
    /// Elasticity of the stable range's width.
    pub stable_width_elasticity: Option<f64>,
    /// ∂ Re λ_weave/∂p at the speed asked for [1/s per unit of p].
    pub weave_real: Option<f64>,
    /// ∂ Re λ_capsize/∂p at the speed asked for.
    pub capsize_real: Option<f64>,
}

/// Exact sensitivities of a bicycle's critical speeds (and, at a speed, of its weave's and
/// capsize's real parts) to every parameter of its own form.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivities {
    /// The form whose parameters are listed.
    pub form: Form,
    /// The base design's critical speeds.
    pub critical: CriticalSpeeds,
    /// The first stable range (lo, hi), whose width is differentiated (hi = +∞, written
    /// `null`, when it has no upper end).
    #[serde(serialize_with = "crate::analysis::stability::serialize_option_range")]
    pub stable_range: Option<(f64, f64)>,
    /// The speed for the eigenvalue real parts, if asked.
    pub speed: Option<f64>,
    /// Re λ of the weave at that speed.
    pub weave_real: Option<f64>,
    /// Re λ of the capsize mode at that speed.
    pub capsize_real: Option<f64>,
    /// One entry per parameter of the form, in table order.
    pub parameters: Vec<ParameterSensitivity>,
}

/// The sensitivities of a bicycle over the speed range [lo, hi], and optionally at `speed`.
///
/// ```
/// use whipple::advanced::sensitivity::sensitivities;
/// use whipple::presets;
/// let s = sensitivities(&presets::find("benchmark")?.bicycle(), 0.0, 10.0, Some(5.0))?;
/// let trail = s.parameters.iter().find(|p| p.key == "c").unwrap();
/// assert!(trail.weave_speed.unwrap() > 0.0);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn sensitivities(
    bike: &Bicycle,
    lo: f64,
    hi: f64,
    speed: Option<f64>,
) -> Result<Sensitivities> {
    let d = ParameterDerivatives::new(bike)?;
    let critical = critical_speeds(&d.canonical, lo, hi)?;
    let dw = d.weave_speed_derivatives(&critical);
    let dc = d.capsize_speed_derivatives(&critical);
    let stable_range = critical.stable_speed_ranges.first().copied();
    let dwidth = stable_range.and_then(|(a, b)| {
        let da = d.range_end_derivatives(a, &critical)?;
        let db = d.range_end_derivatives(b, &critical)?;
        Some(db.iter().zip(&da).map(|(x, y)| x - y).collect::<Vec<f64>>())
    });
    let (mut weave_real, mut capsize_real, mut dwr, mut dcr) = (None, None, None, None);
    if let Some(v) = speed {
        if !v.is_finite() || v < 0.0 {
            return Err(Error::InvalidArgument {
                what: "speed",
                rule: format!("must be a finite speed ≥ 0, got {v}"),
            });
        }
        let top = v.max(1e-3);
        let mut grid = speed_grid(0.0, top, top / 2000.0)?;
        if grid.last().is_none_or(|l| *l != v) {
            grid.push(v);
        }
        let sweep = eigen_sweep(&d.canonical, &grid)?;
        let last = sweep.eigenvalues.last().copied().unwrap_or_default();
        let derivs = d.eigenvalue_derivatives(v)?;
        let find = |mode: Mode| -> Option<(f64, Option<Vec<f64>>)> {
            let k = (0..4)
                .find(|k| sweep.modes[*k] == mode && (mode != Mode::Weave || last[*k].im >= 0.0))?;
            let target = last[k];
            let (l, dl) = derivs.iter().min_by(|a, b| {
                crate::math::norm(a.0 - target).total_cmp(&crate::math::norm(b.0 - target))
            })?;
            Some((
                l.re,
                dl.as_ref().map(|dl| dl.iter().map(|z| z.re).collect()),
            ))
        };
        if let Some((r, dr)) = find(Mode::Weave) {
            weave_real = Some(r);
            dwr = dr;
        }
        if let Some((r, dr)) = find(Mode::Capsize) {
            capsize_real = Some(r);
            dcr = dr;
        }
    }
    let elasticity = |dv: Option<f64>, p: f64, base: Option<f64>| match (dv, base) {
        (Some(dv), Some(b)) if b != 0.0 => Some(dv * p / b),
        _ => None,
    };
    let width = stable_range.map(|(a, b)| b - a);
    let parameters = d
        .parameters
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let pick = |x: &Option<Vec<f64>>| x.as_ref().map(|x| x[i]);
            ParameterSensitivity {
                key: p.key,
                symbol: p.symbol,
                unit: p.unit,
                description: p.description,
                value: d.values[i],
                weave_speed: pick(&dw),
                capsize_speed: pick(&dc),
                stable_width: pick(&dwidth),
                weave_speed_elasticity: elasticity(pick(&dw), d.values[i], critical.weave_speed),
                capsize_speed_elasticity: elasticity(
                    pick(&dc),
                    d.values[i],
                    critical.capsize_speed,
                ),
                stable_width_elasticity: elasticity(pick(&dwidth), d.values[i], width),
                weave_real: pick(&dwr),
                capsize_real: pick(&dcr),
            }
        })
        .collect();
    Ok(Sensitivities {
        form: d.form,
        critical,
        stable_range,
        speed,
        weave_real,
        capsize_real,
        parameters,
    })
}

/// A bicycle with one parameter of its own form changed (for central differences in tests and
/// for design studies); `None` for an unknown key.
pub fn with_parameter(bike: &Bicycle, key: &str, value: f64) -> Option<Bicycle> {
    let form = bike.description.form();
    let i = parameters(form).iter().position(|p| p.key == key)?;
    let mut values = bike.description.values();
    values[i] = value;
    let description = match form {
        Form::Benchmark => {
            Description::Benchmark(BenchmarkParameters::from_array(values.try_into().ok()?))
        }
        Form::Jbike6 => Description::Jbike6(Jbike6Parameters::from_array(values.try_into().ok()?)),
    };
    Some(Bicycle {
        description,
        ..bike.clone()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameters::presets;

    /// The critical speeds with σ serialize as one object (the speeds' fields and the σ beside
    /// them, as `whipple speeds --format json` writes them), and an open end of a range as
    /// `null` wherever a range is written.
    #[test]
    fn sigma_and_sensitivities_serialize_with_the_speeds_names() -> Result<()> {
        let mut bike = presets::find("benchmark")?.bicycle();
        bike.sigma.insert("c".into(), 0.001);
        let json = |v: serde_json::Result<serde_json::Value>| v.expect("serializable");
        let s = json(serde_json::to_value(critical_speeds_sigma(
            &bike,
            0.0,
            f64::INFINITY,
        )?));
        for key in [
            "weave_speed",
            "stable_speed_ranges",
            "weave_speed_sigma",
            "range",
        ] {
            assert!(s.get(key).is_some(), "{key} in {s}");
        }
        assert!(s.get("speeds").is_none());
        assert_eq!(s["range"][1], serde_json::Value::Null);
        let t = json(serde_json::to_value(sensitivities(
            &bike,
            0.0,
            f64::INFINITY,
            None,
        )?));
        assert_eq!(t["stable_range"], s["stable_speed_ranges"][0]);
        assert_eq!(t["critical"]["weave_speed"], s["weave_speed"]);
        Ok(())
    }

    /// Issue 28: σ is homogeneous of degree one in the parameters' σ, so σ of v_w with every
    /// σ scaled by 1e280 is 1e280 times σ of v_w with the σ as given; the naive √Σ(dᵢσᵢ)²
    /// squared terms near 1e280 and gave +∞. The scaled σ is then refused for exceeding v_w.
    #[test]
    fn issue_28_sigma_is_a_scaled_norm_without_overflow() -> Result<()> {
        let mut bike = presets::find("benchmark")?.bicycle();
        bike.sigma.insert("c".into(), 0.001);
        bike.sigma.insert("mB".into(), 0.5);
        let d = ParameterDerivatives::new(&bike)?;
        let speeds = critical_speeds(&d.canonical, 0.0, 10.0)?;
        let dv = d.weave_speed_derivatives(&speeds).expect("a weave speed");
        let sigma = d.sigma_of(&dv);
        let mut huge = bike.clone();
        for s in huge.sigma.values_mut() {
            *s *= 1e280;
        }
        let h = ParameterDerivatives::new(&huge)?;
        let scaled = h.sigma_of(&dv);
        assert!(scaled.is_finite(), "{scaled}");
        assert!(
            (scaled / 1e280 - sigma).abs() <= 1e-14 * sigma,
            "{scaled} {sigma}"
        );
        let err = critical_speeds_sigma(&huge, 0.0, 10.0).expect_err("absurd σ");
        assert!(
            matches!(&err, Error::InvalidParameter { field, .. } if field == "mB" || field == "c"),
            "{err}"
        );
        Ok(())
    }
}
