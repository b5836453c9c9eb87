//! Independent methods that must agree: the quartic eigen-solver against faer's general
//! eigensolver on A(v); eigenpairs against A·x = λ·x; JBike6 and benchmark forms of one bike;
//! critical speeds against the eigenvalues on either side of them.

use faer::Mat;
use whipple::Canonical;
use whipple::advanced::eigen;
use whipple::advanced::linear::StateSpace;
use whipple::presets;
use whipple::presets::PRESETS;
use whipple::{BenchmarkParameters, Result};

fn faer_eigenvalues(a: &nalgebra::Matrix4<f64>) -> Vec<(f64, f64)> {
    let m = Mat::<f64>::from_fn(4, 4, |i, j| a[(i, j)]);
    let values = m
        .eigenvalues()
        .expect("faer's eigensolver converges on a 4x4 matrix");
    let mut out: Vec<(f64, f64)> = values.iter().map(|z| (z.re, z.im)).collect();
    out.sort_by(|x, y| y.0.total_cmp(&x.0).then(y.1.total_cmp(&x.1)));
    out
}

fn all_bikes() -> Result<Vec<(String, BenchmarkParameters)>> {
    PRESETS
        .iter()
        .map(|p| Ok((p.name.to_string(), p.bicycle().benchmark()?)))
        .collect()
}

#[test]
fn quartic_roots_agree_with_faer_on_every_preset() -> Result<()> {
    for (name, bike) in all_bikes()? {
        let c = Canonical::new(&bike)?;
        for i in 0..=200 {
            let v = -5.0 + 0.1 * i as f64;
            let ours = eigen::eigenvalues(&c, v)?;
            let a = StateSpace::new(&c, v)?.a;
            let theirs = faer_eigenvalues(&a);
            let scale = a.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (l, (re, im)) in ours.iter().zip(theirs) {
                // Away from multiple roots both solvers are backward stable; the allowance
                // covers the conditioning of nearly double roots (close to v_d).
                let gap = ours
                    .iter()
                    .filter(|o| *o != l)
                    .map(|o| whipple::math::norm(o - l))
                    .fold(f64::INFINITY, f64::min);
                let tol = if gap > 0.05 {
                    1e-11 * scale
                } else {
                    1e-6 * scale
                };
                assert!(
                    (l.re - re).abs() <= tol && (l.im - im).abs() <= tol,
                    "{name} at v = {v}: ours {l}, faer {re} + {im}i"
                );
            }
        }
    }
    Ok(())
}

#[test]
fn eigenpairs_satisfy_a_x_equals_lambda_x() -> Result<()> {
    for (name, bike) in all_bikes()? {
        let c = Canonical::new(&bike)?;
        for v in [0.0, 0.5, 1.0, 3.0, 4.6, 6.0, 8.0, 12.0] {
            let a = StateSpace::new(&c, v)?
                .a
                .map(|x| nalgebra::Complex::new(x, 0.0));
            for pair in eigen::eigenpairs(&c, v)? {
                let residual = (a * pair.vector - pair.vector * pair.value).norm();
                let norm = pair.vector.norm();
                assert!((norm - 1.0).abs() < 1e-14, "{name}: unit eigenvector");
                assert!(
                    residual < 1e-12 * (1.0 + whipple::math::norm(pair.value)) * a.norm(),
                    "{name} at v = {v}: |A x - λ x| = {residual:e} for λ = {}",
                    pair.value
                );
            }
        }
    }
    Ok(())
}

/// Every one of the 26 benchmark parameters the Schwinn Crown converts to, against an
/// independent conversion by hand (`bench/trajectory_references.py`: masses added,
/// mass-weighted centres, each in-plane tensor R(α) diag(I11, I22) R(α)ᵀ moved to the combined
/// centre by the parallel-axis theorem, fork and basket placed from the steer axis' ground
/// point), stored in `data/references.json`, to 1e-12 relative.
#[test]
fn jbike6_conversion_matches_an_independent_hand_conversion() -> Result<()> {
    let doc: serde_json::Value =
        serde_json::from_str(include_str!("data/references.json")).expect("valid JSON");
    let crown = doc["trajectories"]
        .as_array()
        .and_then(|t| {
            t.iter().find(|s| {
                s["name"]
                    .as_str()
                    .is_some_and(|n| n.contains("Schwinn Crown"))
            })
        })
        .expect("the Crown's scenario");
    let converted = presets::schwinn_crown_jbike6().to_benchmark()?;
    for (name, ours) in converted.fields() {
        let theirs = crown["bicycle"][name].as_f64().expect("every field");
        assert!(
            (ours - theirs).abs() <= 1e-12 * theirs.abs().max(1.0),
            "{name}: {ours} vs the hand conversion's {theirs}"
        );
    }
    // The preset is that conversion.
    assert_eq!(
        presets::find("schwinn-crown")?.bicycle().benchmark()?,
        converted
    );
    Ok(())
}

/// The Schwinn Crown written both ways (JBike6 bodies, and the benchmark parameters they
/// convert to) gives the same matrices; and the combination obeys the parallel-axis theorem
/// checked by hand for the rear body's mass and centre of mass.
#[test]
fn jbike6_and_benchmark_forms_agree() -> Result<()> {
    let jbike6 = presets::schwinn_crown_jbike6();
    let converted = jbike6.to_benchmark()?;
    // Rear body = rider (80 kg at 0.3, 1.2) + frame (2.5 kg at 0.3, 0.5) + rack (2 kg at -0.1, 0.8).
    assert_eq!(converted.m_b, 84.5);
    let x_b = (80.0 * 0.3 + 2.5 * 0.3 - 2.0 * 0.1) / 84.5;
    let y_b = (80.0 * 1.2 + 2.5 * 0.5 + 2.0 * 0.8) / 84.5;
    assert!((converted.x_b - x_b).abs() < 1e-15);
    assert!((converted.z_b + y_b).abs() < 1e-15);
    // Write the converted bike in the benchmark form and read it back: same matrices, bit for bit.
    let text = whipple::advanced::io::write(
        &whipple::Bicycle::new(whipple::advanced::parameters::Description::Benchmark(
            converted,
        )),
        whipple::advanced::io::Format::Toml,
    )?;
    let back =
        whipple::advanced::io::parse(&text, whipple::advanced::io::Format::Toml)?.benchmark()?;
    assert_eq!(Canonical::new(&back)?, Canonical::new(&converted)?);
    // The JBike6 convention is the benchmark one with the steer sign flipped and g in K0.
    let c = Canonical::new(&converted)?;
    let [m0, c1, k0, k2] = c.jbike6_convention();
    assert_eq!(m0[(0, 1)], -c.m[(0, 1)]);
    assert_eq!(c1[(1, 0)], -c.c1[(1, 0)]);
    assert_eq!(k0[(1, 1)], c.k0[(1, 1)] * c.g);
    assert_eq!(k2[(0, 1)], -c.k2[(0, 1)]);
    Ok(())
}

/// A single rider body with a rotated principal frame, converted by hand: the in-plane tensor
/// R(α) diag(I11, I22) R(α)ᵀ and the sign flips of the benchmark axes (z down).
#[test]
fn jbike6_inertia_rotation_matches_a_hand_calculation() -> Result<()> {
    let mut j = presets::schwinn_crown_jbike6();
    for body in [&mut j.frame, &mut j.rack] {
        body.m = 0.0;
        body.inertia = [0.0; 3];
    }
    let b = j.to_benchmark()?;
    let (i11, i22, izz, alpha) = (10.531129, 2.468871, 12.0, -0.25957299f64);
    let (s, c) = whipple::math::sin_cos(alpha);
    assert!((b.i_bxx - (i11 * c * c + i22 * s * s)).abs() < 1e-13);
    assert!((b.i_bzz - (i11 * s * s + i22 * c * c)).abs() < 1e-13);
    assert!((b.i_bxz + (i11 - i22) * s * c).abs() < 1e-13);
    assert_eq!(b.i_byy, izz);
    assert!(
        b.i_bxz > 0.0,
        "a rider leaning forward has I_Bxz > 0 with z down"
    );
    Ok(())
}

/// Each critical speed separates the behaviour it names: just below v_w the weave grows, just
/// above it decays; just below v_c the capsize mode decays, just above it grows.
#[test]
fn critical_speeds_separate_the_eigenvalues() -> Result<()> {
    for (name, bike) in all_bikes()? {
        let c = Canonical::new(&bike)?;
        let s = whipple::critical_speeds(&c, 0.0, 20.0)?;
        let max_re = |v: f64| -> Result<f64> {
            Ok(eigen::eigenvalues(&c, v)?
                .iter()
                .map(|l| l.re)
                .fold(f64::NEG_INFINITY, f64::max))
        };
        for (lo, hi) in &s.stable_speed_ranges {
            assert!(max_re(0.5 * (lo + hi))? < 0.0, "{name}");
            assert!(max_re(lo - 1e-7)? > 0.0, "{name}: unstable just below {lo}");
            if *hi < 20.0 {
                assert!(max_re(hi + 1e-7)? > 0.0, "{name}: unstable just above {hi}");
            }
        }
        if let Some(vw) = s.weave_speed {
            let weave_re = |v: f64| -> Result<f64> {
                Ok(eigen::eigenvalues(&c, v)?
                    .iter()
                    .filter(|l| l.im != 0.0)
                    .map(|l| l.re)
                    .fold(f64::NEG_INFINITY, f64::max))
            };
            assert!(
                weave_re(vw - 1e-6)? > 0.0 && weave_re(vw + 1e-6)? < 0.0,
                "{name}"
            );
        }
    }
    Ok(())
}

/// Tracking keeps each column continuous over a fine sweep: no jump larger than the motion of
/// the eigenvalues themselves (away from the double root, where the pair turns a corner).
#[test]
fn tracked_modes_are_continuous() -> Result<()> {
    let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    let s = whipple::eigen_sweep(&c, &whipple::speed_grid(0.0, 10.0, 0.01)?)?;
    let vd = whipple_reference::meijaard2007::DOUBLE_ROOT_SPEED;
    for i in 1..s.speeds.len() {
        if (s.speeds[i] - vd).abs() < 0.05 {
            continue;
        }
        for k in 0..4 {
            let jump = whipple::math::norm(s.eigenvalues[i][k] - s.eigenvalues[i - 1][k]);
            assert!(
                jump < 0.5,
                "column {k} jumps by {jump} at v = {}",
                s.speeds[i]
            );
        }
    }
    Ok(())
}

/// Modes are labelled only where the spectrum shows the benchmark's pattern (one complex pair,
/// two real eigenvalues): a sweep that stays below the double-root speed, where all four
/// eigenvalues are real, is reported unclassified rather than guessed; the same speeds inside a
/// wider sweep inherit the labels of their tracks.
#[test]
fn modes_are_labelled_only_from_evidence() -> Result<()> {
    use whipple::advanced::modes::Mode;
    let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    let low = whipple::eigen_sweep(&c, &whipple::speed_grid(0.0, 0.5, 0.05)?)?;
    assert_eq!(low.modes, [Mode::Unclassified; 4]);
    let wide = whipple::eigen_sweep(&c, &whipple::speed_grid(0.0, 10.0, 0.05)?)?;
    assert_eq!(
        wide.modes,
        [Mode::Weave, Mode::Weave, Mode::Capsize, Mode::Castering]
    );
    // At rest the weave columns hold the two positive roots that meet at v_d.
    assert!(wide.eigenvalues[0][0].re > 0.0 && wide.eigenvalues[0][1].re > 0.0);
    assert!((wide.eigenvalues[0][2].re + 3.13164324790656).abs() < 1e-12);
    for preset in ["two-mass-skate", "browser-jason", "schwinn-crown"] {
        let bike = presets::find(preset)?.bicycle().benchmark()?;
        let s = whipple::eigen_sweep(
            &Canonical::new(&bike)?,
            &whipple::speed_grid(0.0, 10.0, 0.05)?,
        )?;
        assert_eq!(s.modes[0], Mode::Weave, "{preset}");
        assert_eq!(s.modes[1], Mode::Weave, "{preset}");
    }
    Ok(())
}

/// A coarse sweep is tracked through intermediate speeds: its columns at 0, 5 and 10 m/s are
/// those of a fine sweep at the same speeds.
#[test]
fn coarse_sweeps_are_tracked_like_fine_ones() -> Result<()> {
    let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    let coarse = whipple::eigen_sweep(&c, &[0.0, 5.0, 10.0])?;
    let fine = whipple::eigen_sweep(&c, &whipple::speed_grid(0.0, 10.0, 0.01)?)?;
    assert_eq!(coarse.modes, fine.modes);
    for (k, index) in [0usize, 500, 1000].into_iter().enumerate() {
        assert_eq!(coarse.eigenvalues[k], fine.eigenvalues[index]);
    }
    Ok(())
}
