//! Critical speeds and self-stable speed ranges, certified on any range of speeds, including the
//! whole line.
//!
//! With p(λ) = a₄λ⁴ + a₃λ³ + a₂λ² + a₁λ + a₀ and a₄ = det M > 0, the number of eigenvalues with
//! positive real part is the number of sign changes in Routh's first column
//! (a₄, a₃, Δ₂/a₃, Δ₃/Δ₂, a₀), Δ₂ = a₃a₂ − a₄a₁ and Δ₃ = a₃a₂a₁ − a₄a₁² − a₀a₃² the Hurwitz
//! determinants; all four have negative real parts exactly when every entry is positive. In
//! the scaled speed ν = v/√g and u = ν² (see [`SpeedPolynomials`]) these entries are, up to
//! powers of ν, the polynomials α (degree 0), E(u) (1), D(u) (2) and a₀(u) (2). An eigenvalue
//! crosses the imaginary axis only where a₀ = 0 (a real one through zero: capsize-like) or
//! Δ₃ = 0 (a pair λ, −λ: a complex pair through the imaginary axis, weave-like, when the count
//! changes there; Orlando's formula Δ₃ = a₄³ Π(λᵢ + λⱼ)).
//!
//! So the method is: certify every real root of a₀, D and E (closed forms, then the inclusion
//! discs of [`super::roots`]: no root can be missed and each comes with an enclosure); between
//! consecutive enclosures every polynomial has a sign that follows from its roots alone, so the
//! number of unstable eigenvalues on each interval of speed is *exact*, not sampled; a
//! critical speed is a root at which that number changes. The double-root speed v_d comes the
//! same way from the discriminant in λ (degree 6 in u) with the quartic's P and D₄, whose signs
//! give the number of real eigenvalues.
//!
//! What is certified: for the linear model given by the stored f64 matrices M, C₁, K₀, K₂ and g,
//! every critical speed lies in its reported enclosure, and the stability verdict is exact on
//! every interval between enclosures. Where round-off cannot separate two roots (a
//! near-tangency: a self-stable range that is about to open or close, or a double root) the
//! speeds concerned are listed as `unresolved` instead of being guessed. Not covered: the
//! round-off in forming M, C₁, K₀, K₂ from the parameters (about 1e-16 relative per entry).
//!
//! A closed loop (full-state feedback on φ, δ, φ̇, δ̇: `linear::feedback`) keeps the degrees
//! in λ and v but loses the parity p(λ, −v) = p(−λ, v): its Routh entries are polynomials in ν
//! itself ([`GeneralSpeedPolynomials`]: a₃ of degree 1, Δ₂ of 3, Δ₃ of 6, a₀ of 4), whose
//! certified roots cut the same line, counted the same way ([`Structure::general`]), one
//! segment of a gain schedule at a time ([`closed_loop_critical_speeds`]).

use serde::ser::SerializeSeq;
use serde::{Serialize, Serializer};

use super::eigen::quartic_roots;
use super::roots::{RealRoot, RealRoots, UNIT_ROUNDOFF, real_roots};
use crate::error::{Error, Result};
use crate::linear::{Canonical, GeneralSpeedPolynomials, SpeedPolynomials};

/// A reported speed is refused ([`Error::AccuracyLost`]) when its certified enclosure is wider
/// than this, relative to the speed (ordinary bicycles give about 1e-15).
pub(crate) const MAX_RELATIVE_ENCLOSURE: f64 = 1e-8;

/// The critical speeds of a bicycle within a speed range. `None` where no such speed lies in the
/// range.
///
/// JSON: speeds are numbers in m/s or `null`; a range is `[lo, hi]` with `hi = null` when it
/// has no upper end (for example `"stable_speed_ranges": [[2.841, null]]`: self-stable at every
/// speed above 2.841 m/s), and likewise `lo = null` for no lower end.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalSpeeds {
    /// The range searched [m/s]; either end may be infinite.
    #[serde(serialize_with = "serialize_range")]
    pub range: (f64, f64),
    /// v_d: the lowest forward speed (v ≥ 0) where two real eigenvalues meet and leave as a
    /// complex (weave) pair [m/s].
    pub double_root_speed: Option<f64>,
    /// The double eigenvalue at v_d [1/s].
    pub double_root_eigenvalue: Option<f64>,
    /// v_w: the lowest forward speed (v ≥ 0) where a complex (weave) pair crosses into the left
    /// half plane as speed rises [m/s].
    pub weave_speed: Option<f64>,
    /// The weave's angular frequency at v_w, |Im λ| [rad/s].
    pub weave_frequency: Option<f64>,
    /// v_c: the lowest forward speed (v ≥ 0) where a real (capsize) eigenvalue crosses from
    /// negative to positive as speed rises [m/s].
    pub capsize_speed: Option<f64>,
    /// Every interval of speeds in the range where all eigenvalues have negative real parts,
    /// [lo, hi] in increasing order (hi = +∞ when it has no upper end); empty when there is none.
    #[serde(serialize_with = "serialize_ranges")]
    pub stable_speed_ranges: Vec<(f64, f64)>,
    /// Every speed in the range where an eigenvalue crosses the imaginary axis, in increasing
    /// order.
    pub crossings: Vec<Crossing>,
    /// Speed intervals that round-off could not classify (near-double roots, or speeds beyond
    /// which a coefficient's sign is lost), in increasing order; normally empty.
    #[serde(serialize_with = "serialize_ranges")]
    pub unresolved: Vec<(f64, f64)>,
    /// Why v_d could not be given, where round-off in the discriminant (degree 12 in v) does not
    /// allow it; the other speeds are unaffected. `None` normally.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub double_root_unavailable: Option<String>,
}

/// Where an eigenvalue crosses the imaginary axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Crossing {
    /// The speed [m/s] (polished to round-off).
    pub speed: f64,
    /// Its certified enclosure [m/s].
    pub enclosure: (f64, f64),
    /// Which kind of eigenvalue crosses.
    pub kind: CrossingKind,
    /// Eigenvalues with positive real part just below the speed.
    pub unstable_below: u8,
    /// Eigenvalues with positive real part just above the speed.
    pub unstable_above: u8,
    /// |Im λ| of a crossing pair [rad/s] (None for a real crossing).
    pub frequency: Option<f64>,
}

/// The kind of eigenvalue that crosses the imaginary axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CrossingKind {
    /// A real eigenvalue through zero (a₀ = 0): capsize-like.
    Real,
    /// A complex pair through the imaginary axis (Δ₃ = 0): weave-like.
    Pair,
}

fn json_end(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

fn serialize_range<S: Serializer>(r: &(f64, f64), s: S) -> Result<S::Ok, S::Error> {
    (json_end(r.0), json_end(r.1)).serialize(s)
}

/// An optional range as [`CriticalSpeeds`]' ranges are written: an infinite end as `null`
/// (what serde_json writes for it anyway; other serializers, Python's among them, get `None`).
pub(crate) fn serialize_option_range<S: Serializer>(
    r: &Option<(f64, f64)>,
    s: S,
) -> Result<S::Ok, S::Error> {
    r.map(|r| (json_end(r.0), json_end(r.1))).serialize(s)
}

fn serialize_ranges<S: Serializer>(ranges: &[(f64, f64)], s: S) -> Result<S::Ok, S::Error> {
    let mut seq = s.serialize_seq(Some(ranges.len()))?;
    for r in ranges {
        seq.serialize_element(&(json_end(r.0), json_end(r.1)))?;
    }
    seq.end()
}

/// Checks a speed range: not NaN, LO < HI; LO may be −∞ and HI +∞.
pub(crate) fn check_range(lo: f64, hi: f64) -> Result<()> {
    if lo.is_nan() || hi.is_nan() || lo >= hi || lo == f64::INFINITY || hi == f64::NEG_INFINITY {
        return Err(Error::InvalidArgument {
            what: "range",
            rule: format!("needs LO < HI (HI may be unbounded), got {lo}:{hi}"),
        });
    }
    Ok(())
}

const A0: u8 = 1;
const PAIR: u8 = 2;
const AUX: u8 = 4;
const ZERO: u8 = 8;
const CROSSING: u8 = A0 | PAIR;

/// Most breakpoints on the speed line: each of three polynomials of degree ≤ 6 in u gives at
/// most two speeds per root and two horizon groups, plus v = 0.
const MAX_BREAKS: usize = 3 * 2 * 7 + 1;

/// A root's enclosure on the scaled-speed line ν, or a group of overlapping ones.
#[derive(Debug, Clone, Copy, Default)]
struct Group {
    lo: f64,
    hi: f64,
    value: f64,
    kinds: u8,
    crossing_members: u8,
    cluster: bool,
    /// Beyond a polynomial's certified horizon (see [`RealRoots::horizon`]).
    beyond: bool,
}

impl Group {
    fn point(value: f64, kinds: u8) -> Self {
        Group {
            lo: value,
            hi: value,
            value,
            kinds,
            ..Group::default()
        }
    }

    fn unresolved(&self) -> bool {
        let near_zero = self.kinds & ZERO != 0 && self.crossing_members > 0 && self.hi > self.lo;
        (self.cluster && self.kinds & CROSSING != 0)
            || self.crossing_members > 1
            || near_zero
            || self.beyond
    }
}

/// The speed line cut at every root enclosure, with a count on every gap between them.
#[derive(Debug, Clone, Copy)]
struct Line {
    groups: [Group; MAX_BREAKS],
    n: usize,
    /// counts[i] holds the gap left of group i; counts[n] the gap right of the last.
    counts: [Option<u8>; MAX_BREAKS + 1],
}

impl Line {
    /// The line of an even–odd polynomial set ([`SpeedPolynomials`]): ν = 0 is a breakpoint.
    fn new() -> Self {
        let mut line = Line::empty();
        line.push(Group::point(0.0, ZERO));
        line
    }

    fn empty() -> Self {
        Line {
            groups: [Group::default(); MAX_BREAKS],
            n: 0,
            counts: [None; MAX_BREAKS + 1],
        }
    }

    /// Adds the roots in ν of one polynomial in ν itself (no mirroring: a closed loop's
    /// polynomials have no parity).
    fn add_speed_roots(&mut self, roots: &RealRoots, kind: u8) {
        let crossing = u8::from(kind & CROSSING != 0);
        if roots.zero_multiplicity > 0 {
            self.push(Group::point(0.0, kind));
        }
        for root in roots.as_slice() {
            let (lo, hi) = root.enclosure();
            self.push(Group {
                lo,
                hi,
                value: root.value().clamp(lo, hi),
                kinds: kind,
                crossing_members: crossing,
                cluster: matches!(root, RealRoot::Cluster { .. }),
                beyond: false,
            });
        }
        if roots.horizon.is_finite() {
            self.push_beyond(roots.horizon, kind, crossing);
        }
    }

    /// The speeds beyond a certified horizon `h` on both sides, |v| ≥ h: undecided there.
    fn push_beyond(&mut self, h: f64, kind: u8, crossing: u8) {
        for (lo, hi, value) in [(h, f64::INFINITY, h), (f64::NEG_INFINITY, -h, -h)] {
            self.push(Group {
                lo,
                hi,
                value,
                kinds: kind,
                crossing_members: crossing,
                cluster: true,
                beyond: true,
            });
        }
    }

    fn push(&mut self, g: Group) {
        if self.n < MAX_BREAKS {
            self.groups[self.n] = g;
            self.n += 1;
        }
    }

    /// Adds the speeds ν = ±√u of every root in u of one polynomial.
    fn add_roots(&mut self, roots: &RealRoots, kind: u8) {
        let crossing = u8::from(kind & CROSSING != 0);
        if roots.zero_multiplicity > 0 {
            self.push(Group::point(0.0, kind));
        }
        for root in roots.as_slice() {
            let (ul, uh) = root.enclosure();
            if uh < 0.0 {
                continue;
            }
            let cluster = matches!(root, RealRoot::Cluster { .. });
            if ul > 0.0 {
                let lo = ul.sqrt() * (1.0 - 2.0 * UNIT_ROUNDOFF);
                let hi = uh.sqrt() * (1.0 + 2.0 * UNIT_ROUNDOFF);
                let value = root.value().max(0.0).sqrt().clamp(lo, hi);
                for (a, b, v) in [(lo, hi, value), (-hi, -lo, -value)] {
                    self.push(Group {
                        lo: a,
                        hi: b,
                        value: v,
                        kinds: kind,
                        crossing_members: crossing,
                        cluster,
                        beyond: false,
                    });
                }
            } else {
                // Straddles u = 0: a root at a speed too small to tell from rest.
                let h = uh.sqrt() * (1.0 + 2.0 * UNIT_ROUNDOFF);
                self.push(Group {
                    lo: -h,
                    hi: h,
                    value: 0.0,
                    kinds: kind | ZERO,
                    crossing_members: crossing,
                    cluster: true,
                    beyond: false,
                });
            }
        }
        if roots.horizon.is_finite() {
            self.push_beyond(
                roots.horizon.sqrt() * (1.0 - 2.0 * UNIT_ROUNDOFF),
                kind,
                crossing,
            );
        }
    }

    /// Sorts and merges overlapping enclosures, then counts on every gap.
    fn finish(&mut self, count: impl Fn(f64) -> Option<u8>) {
        let groups = &mut self.groups[..self.n];
        groups.sort_by(|a, b| a.lo.total_cmp(&b.lo));
        let mut merged = 0;
        for i in 0..self.n {
            let g = self.groups[i];
            if merged > 0 && g.lo <= self.groups[merged - 1].hi {
                let last = &mut self.groups[merged - 1];
                if last.kinds & ZERO != 0 || g.kinds & ZERO != 0 {
                    last.value = 0.0;
                } else if g.beyond {
                    last.value = last.value.min(g.value);
                } else if g.kinds & CROSSING != 0 && last.kinds & CROSSING == 0 {
                    last.value = g.value;
                }
                last.hi = last.hi.max(g.hi);
                last.crossing_members += g.crossing_members;
                last.cluster |= g.cluster;
                last.beyond |= g.beyond;
                last.kinds |= g.kinds;
            } else {
                self.groups[merged] = g;
                merged += 1;
            }
        }
        self.n = merged;
        for i in 0..=self.n {
            let left = if i == 0 {
                f64::NEG_INFINITY
            } else {
                self.groups[i - 1].hi
            };
            let right = if i == self.n {
                f64::INFINITY
            } else {
                self.groups[i].lo
            };
            let x = if left == f64::NEG_INFINITY && right == f64::INFINITY {
                1.0
            } else if left == f64::NEG_INFINITY {
                2.0 * right - 1.0
            } else if right == f64::INFINITY {
                2.0 * left + 1.0
            } else {
                0.5 * (left + right)
            };
            // A gap symmetric about zero (only on a closed loop's line, where zero is no
            // breakpoint) is counted at another of its points.
            let x = if x == 0.0 && right.is_finite() {
                0.5 * right
            } else {
                x
            };
            self.counts[i] = if x > left && x < right && x != 0.0 {
                count(x)
            } else {
                None
            };
        }
    }
}

/// Sign changes in a sequence of signs (±1).
fn sign_changes(s: &[f64]) -> u8 {
    s.windows(2).filter(|w| w[0] != w[1]).count() as u8
}

/// The certified stability structure of one bicycle on the whole speed line.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Structure {
    line: Line,
    sqrt_g: f64,
}

/// One step of a walk along the speed line.
enum Event<'a> {
    /// A gap [a, b] (m/s) and its count.
    Gap(f64, f64, Option<u8>),
    /// A group at speed v with the counts left and right of it.
    Group(&'a Group, f64, Option<u8>, Option<u8>),
}

impl Structure {
    /// Unstable-eigenvalue counts on the speed line from the Routh signs of α, E, D, a₀.
    pub(crate) fn stability(sp: &SpeedPolynomials) -> Result<Self> {
        let alpha = sp.alpha.coefficients[0];
        if alpha != 0.0 && alpha.abs() <= sp.alpha.bounds[0] {
            return Err(Error::AccuracyLost {
                quantity: "critical speeds".into(),
                reason: format!(
                    "the coefficient of λ³ per unit speed, {alpha:e}, is within its round-off \
                     bound {:e}",
                    sp.alpha.bounds[0]
                ),
            });
        }
        let a0 = real_roots(&sp.a0, "critical speeds (the coefficient a0)")?;
        let d = real_roots(&sp.d, "critical speeds (the Hurwitz determinant)")?;
        let e = real_roots(&sp.e, "critical speeds (the Hurwitz determinant Δ2)")?;
        let mut line = Line::new();
        line.add_roots(&a0, A0);
        line.add_roots(&d, PAIR);
        line.add_roots(&e, AUX);
        let s_alpha = alpha.signum();
        line.finish(|nu| {
            if alpha == 0.0 {
                return None;
            }
            let u = nu * nu;
            let (se, sd, s0) = (e.sign_at(u)?, d.sign_at(u)?, a0.sign_at(u)?);
            let sv = nu.signum();
            Some(sign_changes(&[
                1.0,
                sv * s_alpha,
                s_alpha * se,
                sv * sd * se,
                s0,
            ]))
        });
        Ok(Structure {
            line,
            sqrt_g: sp.sqrt_g,
        })
    }

    /// Unstable-eigenvalue counts on the speed line of any pencil (a closed loop) from the
    /// Routh signs of a₃, Δ₂, Δ₃, a₀ as polynomials in ν: the first column is (a₄, a₃,
    /// Δ₂/a₃, Δ₃/Δ₂, a₀), and between the roots of those four polynomials none is zero.
    pub(crate) fn general(gp: &GeneralSpeedPolynomials) -> Result<Self> {
        let a3 = real_roots(&gp.a3, "closed-loop critical speeds (the coefficient a3)")?;
        let a0 = real_roots(&gp.a0, "closed-loop critical speeds (the coefficient a0)")?;
        let d3 = real_roots(
            &gp.delta3,
            "closed-loop critical speeds (the Hurwitz determinant Δ3)",
        )?;
        let d2 = real_roots(
            &gp.delta2,
            "closed-loop critical speeds (the Hurwitz determinant Δ2)",
        )?;
        let mut line = Line::empty();
        line.add_speed_roots(&a0, A0);
        line.add_speed_roots(&d3, PAIR);
        line.add_speed_roots(&d2, AUX);
        line.add_speed_roots(&a3, AUX);
        line.finish(|nu| {
            let (s3, s2, sd, s0) = (
                a3.sign_at(nu)?,
                d2.sign_at(nu)?,
                d3.sign_at(nu)?,
                a0.sign_at(nu)?,
            );
            Some(sign_changes(&[1.0, s3, s2 * s3, sd * s2, s0]))
        });
        Ok(Structure {
            line,
            sqrt_g: gp.sqrt_g,
        })
    }

    /// Real-eigenvalue counts on the speed line from the signs of the discriminant, P and D₄.
    pub(crate) fn real_count(canonical: &Canonical, sqrt_g: f64) -> Result<Self> {
        let (disc, p, d4) = SpeedPolynomials::discriminant(canonical)?;
        let disc = real_roots(&disc, "the double-root speed (the discriminant)")?;
        let p = real_roots(&p, "the double-root speed")?;
        let d4 = real_roots(&d4, "the double-root speed")?;
        let mut line = Line::new();
        // The discriminant's roots are the candidates; P and D₄ only cut the gaps.
        line.add_roots(&disc, A0);
        line.add_roots(&p, AUX);
        line.add_roots(&d4, AUX);
        line.finish(|nu| {
            let u = nu * nu;
            let sd = disc.sign_at(u)?;
            if sd < 0.0 {
                return Some(2);
            }
            let (sp, s4) = (p.sign_at(u)?, d4.sign_at(u)?);
            Some(if sp < 0.0 && s4 < 0.0 { 4 } else { 0 })
        });
        Ok(Structure { line, sqrt_g })
    }

    /// The gaps and groups inside [lo, hi] (m/s), in increasing speed.
    fn walk(&self, lo: f64, hi: f64, mut visit: impl FnMut(Event<'_>)) {
        let s = self.sqrt_g;
        let to_v = |nu: f64| nu * s;
        let line = &self.line;
        for i in 0..=line.n {
            let left = if i == 0 {
                f64::NEG_INFINITY
            } else {
                to_v(line.groups[i - 1].value)
            };
            let right = if i == line.n {
                f64::INFINITY
            } else {
                to_v(line.groups[i].value)
            };
            let (a, b) = (left.max(lo), right.min(hi));
            if a < b {
                visit(Event::Gap(a, b, line.counts[i]));
            }
            if i < line.n {
                let g = &line.groups[i];
                let v = to_v(g.value);
                if v >= lo && v <= hi {
                    visit(Event::Group(g, v, line.counts[i], line.counts[i + 1]));
                }
            }
        }
    }
}

/// The speed enclosure of a group [m/s].
fn enclosure(g: &Group, sqrt_g: f64) -> (f64, f64) {
    let widen = |x: f64, up: bool| {
        let y = x * sqrt_g;
        if !y.is_finite() {
            return y;
        }
        let pad = 4.0 * UNIT_ROUNDOFF * y.abs();
        if up { y + pad } else { y - pad }
    };
    (widen(g.lo, false), widen(g.hi, true))
}

/// What a design study reads of one bicycle, computed without allocating.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilitySummary {
    /// v_w [m/s], as in [`CriticalSpeeds::weave_speed`].
    pub weave_speed: Option<f64>,
    /// The weave's angular frequency at v_w [rad/s].
    pub weave_frequency: Option<f64>,
    /// v_c [m/s], as in [`CriticalSpeeds::capsize_speed`].
    pub capsize_speed: Option<f64>,
    /// The lowest self-stable speed in the range [m/s].
    pub stable_from: Option<f64>,
    /// The upper end of the first self-stable range [m/s] (+∞ when it has none).
    pub stable_to: Option<f64>,
    /// Total width of the self-stable ranges inside the range [m/s] (+∞ when unbounded, 0 when
    /// there is none).
    pub stable_width: f64,
    /// Number of separate self-stable ranges.
    pub stable_ranges: u32,
    /// Whether some speeds in the range could not be classified (see
    /// [`CriticalSpeeds::unresolved`]).
    pub unresolved: bool,
    /// Whether it is self-stable over the band asked for, and by how much (`None` when no
    /// band was asked for).
    pub band: Option<BandAnswer>,
}

/// Whether a bicycle is self-stable at every speed of a band [a, b] (m/s): one self-stable
/// range holds the whole band, its ends strictly outside it (or at the end of the range
/// searched, where the margin is then measured to). Certified: yes or no only where the
/// stability line is; undecided where round-off leaves speeds of the band unclassified and no
/// self-stable range holds it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BandAnswer {
    /// Yes, no, or `None` when undecided.
    pub stable: Option<bool>,
    /// How far the self-stable range reaches below a: a − its lower end [m/s] (when stable).
    pub margin_below: Option<f64>,
    /// How far it reaches above b: its upper end − b [m/s] (+∞ when it has none; when stable).
    pub margin_above: Option<f64>,
}

impl BandAnswer {
    /// The smaller margin [m/s]: how much the band could widen at its nearer end (when
    /// stable).
    pub fn margin(&self) -> Option<f64> {
        Some(self.margin_below?.min(self.margin_above?))
    }
}

/// Checks a band [a, b] of speeds inside the range [lo, hi]: finite, a < b.
pub(crate) fn check_band((a, b): (f64, f64), (lo, hi): (f64, f64)) -> Result<()> {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::InvalidArgument {
            what: "band",
            rule: format!("needs A < B, both finite, got {a}:{b}"),
        });
    }
    if a < lo || b > hi {
        return Err(Error::InvalidArgument {
            what: "band",
            rule: format!("{a}:{b} must lie inside the speed range {lo}:{hi}"),
        });
    }
    Ok(())
}

fn check_enclosure(name: &str, v: f64, enc: (f64, f64)) -> Result<()> {
    if enc.1 - enc.0 > MAX_RELATIVE_ENCLOSURE * v.abs().max(f64::MIN_POSITIVE) {
        return Err(Error::AccuracyLost {
            quantity: name.to_string(),
            reason: format!("it is certified only to lie in [{}, {}] m/s", enc.0, enc.1),
        });
    }
    Ok(())
}

/// The weave frequency at a pair crossing at scaled speed ν: ω² = a₁/a₃ = β(u)/α.
fn pair_frequency(sp: &SpeedPolynomials, nu: f64) -> Option<f64> {
    let w2 = sp.beta.eval(nu * nu) / sp.alpha.coefficients[0];
    (w2 > 0.0).then(|| sp.sqrt_g * w2.sqrt())
}

/// What a walk along the stability line finds inside a speed range, in increasing speed.
enum Finding {
    /// A self-stable range [a, b] (m/s): adjacent stable gaps joined.
    Stable(f64, f64),
    /// Speeds [a, b] (m/s) that round-off could not classify.
    Unresolved(f64, f64),
    /// A change of the number of unstable eigenvalues, with its enclosure (not yet checked
    /// against [`MAX_RELATIVE_ENCLOSURE`]: each caller decides which crossings it reports).
    Crossing(Crossing),
}

/// v_w's rule: a pair crossing at a forward speed that lowers the unstable count.
fn is_weave(c: &Crossing) -> bool {
    c.speed >= 0.0 && c.kind == CrossingKind::Pair && c.unstable_above < c.unstable_below
}

/// v_c's rule: a real crossing at a forward speed that raises the unstable count.
fn is_capsize(c: &Crossing) -> bool {
    c.speed >= 0.0 && c.kind == CrossingKind::Real && c.unstable_above > c.unstable_below
}

impl Structure {
    /// The one reading of the stability line: stable ranges, unresolved speeds and crossings
    /// inside [lo, hi] (m/s), in increasing speed, without allocating. Both
    /// [`critical_speeds`] and [`summary`] are projections of it.
    fn findings(
        &self,
        frequency: impl Fn(f64) -> Option<f64>,
        lo: f64,
        hi: f64,
        mut visit: impl FnMut(Finding),
    ) {
        let s = self.sqrt_g;
        let mut open: Option<(f64, f64)> = None;
        self.walk(lo, hi, |event| match event {
            Event::Gap(a, b, count) => {
                if count == Some(0) {
                    open = Some(open.map_or((a, b), |(start, _)| (start, b)));
                } else if let Some((a, b)) = open.take() {
                    visit(Finding::Stable(a, b));
                }
            }
            Event::Group(g, v, left, right) => {
                let enc = enclosure(g, s);
                if g.unresolved() {
                    if let Some((a, b)) = open.take() {
                        visit(Finding::Stable(a, b));
                    }
                    visit(Finding::Unresolved(enc.0.max(lo), enc.1.min(hi)));
                    return;
                }
                let (Some(l), Some(r)) = (left, right) else {
                    return;
                };
                if l == r || g.kinds & CROSSING == 0 || g.kinds & ZERO != 0 {
                    return;
                }
                let kind = if g.kinds & PAIR != 0 {
                    CrossingKind::Pair
                } else {
                    CrossingKind::Real
                };
                visit(Finding::Crossing(Crossing {
                    speed: v,
                    enclosure: enc,
                    kind,
                    unstable_below: l,
                    unstable_above: r,
                    frequency: match kind {
                        CrossingKind::Pair => frequency(g.value),
                        CrossingKind::Real => None,
                    },
                }));
            }
        });
        if let Some((a, b)) = open {
            visit(Finding::Stable(a, b));
        }
    }
}

/// The stability summary of a bicycle on [lo, hi] (m/s; hi may be +∞), as a design study
/// needs it: no allocation, no eigenvalue computation.
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical};
/// use whipple::advanced::linear::SpeedPolynomials;
/// use whipple::advanced::stability::summary;
/// let sp = SpeedPolynomials::new(&Canonical::new(&BenchmarkParameters::meijaard2007())?)?;
/// let s = summary(&sp, 0.0, f64::INFINITY, Some((4.5, 5.5)))?;
/// assert!((s.stable_width - (6.02426201538837 - 4.29238253634111)).abs() < 1e-12);
/// let band = s.band.unwrap();
/// assert_eq!(band.stable, Some(true)); // self-stable at every speed from 4.5 to 5.5 m/s
/// assert!((band.margin_below.unwrap() - (4.5 - 4.29238253634111)).abs() < 1e-12);
/// assert!((band.margin_above.unwrap() - (6.02426201538837 - 5.5)).abs() < 1e-12);
/// let wide = summary(&sp, 0.0, f64::INFINITY, Some((4.0, 8.0)))?.band.unwrap();
/// assert_eq!((wide.stable, wide.margin()), (Some(false), None));
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn summary(
    sp: &SpeedPolynomials,
    lo: f64,
    hi: f64,
    band: Option<(f64, f64)>,
) -> Result<StabilitySummary> {
    check_range(lo, hi)?;
    if let Some(band) = band {
        check_band(band, (lo, hi))?;
    }
    let structure = Structure::stability(sp)?;
    // The band: held by one self-stable range, or touched by speeds round-off left open.
    let mut holding: Option<(f64, f64)> = None;
    let mut band_unresolved = false;
    let mut out = StabilitySummary {
        weave_speed: None,
        weave_frequency: None,
        capsize_speed: None,
        stable_from: None,
        stable_to: None,
        stable_width: 0.0,
        stable_ranges: 0,
        unresolved: false,
        band: None,
    };
    let mut weave: Option<Crossing> = None;
    let mut capsize: Option<Crossing> = None;
    let mut failure: Option<Error> = None;
    structure.findings(
        |nu| pair_frequency(sp, nu),
        lo,
        hi,
        |finding| match finding {
            Finding::Stable(a, b) => {
                out.stable_width += b - a;
                out.stable_ranges += 1;
                if out.stable_from.is_none() {
                    out.stable_from = Some(a);
                    out.stable_to = Some(b);
                }
                // An end of the range searched holds the band's end there (the self-stable range
                // may go on beyond it).
                if band.is_some_and(|(low, high)| (a < low || a == lo) && (high < b || b == hi)) {
                    holding = Some((a, b));
                }
            }
            Finding::Unresolved(a, b) => {
                out.unresolved = true;
                if band.is_some_and(|(low, high)| a <= high && low <= b) {
                    band_unresolved = true;
                }
            }
            Finding::Crossing(c) => {
                if weave.is_none() && is_weave(&c) {
                    if failure.is_none() {
                        failure = check_enclosure("the weave speed", c.speed, c.enclosure).err();
                    }
                    weave = Some(c);
                }
                if capsize.is_none() && is_capsize(&c) {
                    if failure.is_none() {
                        failure = check_enclosure("the capsize speed", c.speed, c.enclosure).err();
                    }
                    capsize = Some(c);
                }
            }
        },
    );
    if let Some(e) = failure {
        return Err(e);
    }
    out.weave_speed = weave.map(|c| c.speed);
    out.weave_frequency = weave.and_then(|c| c.frequency);
    out.capsize_speed = capsize.map(|c| c.speed);
    out.band = band.map(|(low, high)| match holding {
        Some((a, b)) => BandAnswer {
            stable: Some(true),
            margin_below: Some(low - a),
            margin_above: Some(b - high),
        },
        // Every speed of the band is classified and no one self-stable range holds it: some
        // speed of it is unstable or critical.
        None => BandAnswer {
            stable: (!band_unresolved).then_some(false),
            margin_below: None,
            margin_above: None,
        },
    });
    Ok(out)
}

/// The critical speeds of a bicycle in [lo, hi] (m/s); `hi` may be `f64::INFINITY` (and `lo`
/// `f64::NEG_INFINITY`): the answer is certified on the whole range, however large.
///
/// ```
/// use whipple::{BenchmarkParameters, Canonical};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
/// let speeds = whipple::critical_speeds(&canonical, 0.0, f64::INFINITY)?;
/// assert!((speeds.weave_speed.unwrap() - 4.29238253634111).abs() < 1e-12);
/// assert!((speeds.capsize_speed.unwrap() - 6.02426201538837).abs() < 1e-12);
/// assert_eq!(speeds.stable_speed_ranges.len(), 1);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn critical_speeds(canonical: &Canonical, lo: f64, hi: f64) -> Result<CriticalSpeeds> {
    check_range(lo, hi)?;
    let sp = SpeedPolynomials::new(canonical)?;
    let structure = Structure::stability(&sp)?;
    let (stable, crossings, mut unresolved) = read_line(
        &structure,
        |nu| pair_frequency(&sp, nu),
        lo,
        hi,
        WideCrossing::Fail,
    )?;
    // v_d, v_w and v_c are speeds of forward riding: a range reaching below zero has their
    // mirror images there (p(λ, −v) = p(−λ, v)), where nothing turns stable.
    let weave = crossings.iter().find(|c| is_weave(c));
    let capsize = crossings.iter().find(|c| is_capsize(c));
    let mut double_root_unavailable = None;
    let (double_root_speed, double_root_eigenvalue) = if hi < 0.0 {
        (None, None)
    } else {
        match double_root(canonical, &sp, lo.max(0.0), hi, &mut unresolved) {
            Ok(found) => found,
            Err(e @ Error::AccuracyLost { .. }) => {
                double_root_unavailable = Some(e.to_string());
                (None, None)
            }
            Err(e) => return Err(e),
        }
    };
    unresolved.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(CriticalSpeeds {
        range: (lo, hi),
        double_root_speed,
        double_root_eigenvalue,
        weave_speed: weave.map(|c| c.speed),
        weave_frequency: weave.and_then(|c| c.frequency),
        capsize_speed: capsize.map(|c| c.speed),
        stable_speed_ranges: stable,
        crossings,
        unresolved,
        double_root_unavailable,
    })
}

/// The stable ranges, crossings and unresolved speeds of a stability line inside [lo, hi],
/// each crossing's enclosure checked.
type LineReading = (Vec<(f64, f64)>, Vec<Crossing>, Vec<(f64, f64)>);

/// What [`read_line`] does with a crossing whose enclosure is wider than
/// [`MAX_RELATIVE_ENCLOSURE`]: fail the whole reading (the open loop, whose named speeds are
/// what the user asked for), or list its enclosure among the unresolved speeds and keep the
/// rest (a closed loop, whose crossings are only where its stable ranges end).
#[derive(Clone, Copy, PartialEq)]
enum WideCrossing {
    Fail,
    Unresolved,
}

fn read_line(
    structure: &Structure,
    frequency: impl Fn(f64) -> Option<f64>,
    lo: f64,
    hi: f64,
    wide: WideCrossing,
) -> Result<LineReading> {
    let mut stable: Vec<(f64, f64)> = Vec::new();
    let mut crossings: Vec<Crossing> = Vec::new();
    let mut unresolved = Vec::new();
    let mut failure: Option<Error> = None;
    structure.findings(frequency, lo, hi, |finding| match finding {
        Finding::Stable(a, b) => stable.push((a, b)),
        Finding::Unresolved(a, b) => unresolved.push((a, b)),
        Finding::Crossing(c) => {
            let check = check_enclosure("a critical speed", c.speed, c.enclosure);
            match (check, wide) {
                (Ok(()), _) => crossings.push(c),
                (Err(_), WideCrossing::Unresolved) => {
                    unresolved.push((c.enclosure.0.max(lo), c.enclosure.1.min(hi)));
                }
                (Err(e), WideCrossing::Fail) => {
                    if failure.is_none() {
                        failure = Some(e);
                    }
                    crossings.push(c);
                }
            }
        }
    });
    match failure {
        Some(e) => Err(e),
        None => Ok((stable, crossings, unresolved)),
    }
}

/// The certified critical speeds of a closed loop's pencils on [lo, hi] (m/s): `pieces` are
/// the pencils of consecutive speed intervals [start, end] (one piece over the whole line for
/// constant gains; one per segment of a gain schedule, which must cover [lo, hi]), each read
/// on its own interval and the readings joined (a stable range running across a segment's end
/// is one range). The double-root speed is not computed for a closed loop (its discriminant
/// has degree 12 in v, beyond the certified root finder): `double_root_unavailable` says so.
pub(crate) fn closed_loop_critical_speeds(
    pieces: &[(f64, f64, GeneralSpeedPolynomials)],
    lo: f64,
    hi: f64,
) -> Result<CriticalSpeeds> {
    check_range(lo, hi)?;
    let mut stable: Vec<(f64, f64)> = Vec::new();
    let mut crossings: Vec<Crossing> = Vec::new();
    let mut unresolved: Vec<(f64, f64)> = Vec::new();
    for (start, end, gp) in pieces {
        let (a, b) = (start.max(lo), end.min(hi));
        if a >= b {
            continue;
        }
        let structure = Structure::general(gp)?;
        let frequency = |nu: f64| {
            let w2 = gp.a1.eval(nu) / gp.a3.eval(nu);
            (w2 > 0.0).then(|| gp.sqrt_g * w2.sqrt())
        };
        let (s, c, u) = read_line(&structure, frequency, a, b, WideCrossing::Unresolved)?;
        for range in s {
            match stable.last_mut() {
                Some(last) if last.1 == range.0 => last.1 = range.1,
                _ => stable.push(range),
            }
        }
        crossings.extend(c);
        unresolved.extend(u);
    }
    let weave = crossings.iter().find(|c| is_weave(c));
    let capsize = crossings.iter().find(|c| is_capsize(c));
    Ok(CriticalSpeeds {
        range: (lo, hi),
        double_root_speed: None,
        double_root_eigenvalue: None,
        weave_speed: weave.map(|c| c.speed),
        weave_frequency: weave.and_then(|c| c.frequency),
        capsize_speed: capsize.map(|c| c.speed),
        stable_speed_ranges: stable,
        crossings,
        unresolved,
        double_root_unavailable: Some(
            "not computed for a closed loop: its discriminant in λ has degree 12 in the speed"
                .into(),
        ),
    })
}

/// v_d and the double eigenvalue: the lowest root of the discriminant in [lo, hi] where the
/// number of real eigenvalues drops by two or more as speed rises.
fn double_root(
    canonical: &Canonical,
    sp: &SpeedPolynomials,
    lo: f64,
    hi: f64,
    unresolved: &mut Vec<(f64, f64)>,
) -> Result<(Option<f64>, Option<f64>)> {
    let sqrt_g = sp.sqrt_g;
    let structure = Structure::real_count(canonical, sqrt_g)?;
    let mut found: Option<(f64, f64)> = None;
    let mut failure = None;
    structure.walk(lo, hi, |event| {
        let Event::Group(g, v, left, right) = event else {
            return;
        };
        if found.is_some() || g.kinds & A0 == 0 {
            return;
        }
        let enc = enclosure(g, sqrt_g);
        if g.unresolved() {
            if g.kinds & ZERO == 0 || g.beyond {
                unresolved.push((enc.0.max(lo), enc.1.min(hi)));
            }
            return;
        }
        if g.kinds & ZERO != 0 {
            return;
        }
        if let (Some(l), Some(r)) = (left, right) {
            if l >= r + 2 {
                failure = check_enclosure("the double-root speed", v, enc).err();
                found = Some((v, g.value));
            }
        }
    });
    if let Some(e) = failure {
        return Err(e);
    }
    let Some((vd, nu)) = found else {
        return Ok((None, None));
    };
    Ok((Some(vd), double_eigenvalue(sp, nu)?.map(|mu| mu * sqrt_g)))
}

/// The double eigenvalue at v_d, scaled (μ = λ/√g, at ν = v_d/√g): the root of ∂p/∂μ between
/// the two closest real (or nearly real) eigenvalues, by bounded Newton steps on the cubic.
fn double_eigenvalue(sp: &SpeedPolynomials, nu: f64) -> Result<Option<f64>> {
    let u = nu * nu;
    let a = [
        sp.a0.eval(u),
        nu * sp.beta.eval(u),
        sp.a2.eval(u),
        nu * sp.alpha.coefficients[0],
        sp.a4.coefficients[0],
    ];
    let roots = quartic_roots(&a)?;
    let mut best = None;
    let mut gap = f64::INFINITY;
    for i in 0..4 {
        for j in 0..i {
            let d = crate::math::norm(roots[i] - roots[j]);
            if d < gap {
                gap = d;
                best = Some(0.5 * (roots[i].re + roots[j].re));
            }
        }
    }
    let Some(mut l) = best else {
        return Ok(None);
    };
    for _ in 0..20 {
        let dp = ((4.0 * a[4] * l + 3.0 * a[3]) * l + 2.0 * a[2]) * l + a[1];
        let ddp = (12.0 * a[4] * l + 6.0 * a[3]) * l + 2.0 * a[2];
        if ddp == 0.0 {
            break;
        }
        let step = dp / ddp;
        if !step.is_finite() || step.abs() > gap.max(1e-3 * l.abs()) {
            break;
        }
        l -= step;
        if step.abs() <= 2.0 * f64::EPSILON * l.abs() {
            break;
        }
    }
    Ok(Some(l))
}
