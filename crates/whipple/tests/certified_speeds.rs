//! The certified critical speeds, never a wrong answer given without a word: regression
//! tests named after each misbehaviour they guard against, and property tests against dense eigenvalue scans.

use std::sync::atomic::AtomicBool;

use approx::assert_abs_diff_eq;
use proptest::prelude::*;
use whipple::advanced::design::{Axis, DesignStatus, Parameter, Shard, StudySettings};
use whipple::advanced::parameters::Description;
use whipple::advanced::{eigen, stability};
use whipple::presets;
use whipple::Canonical;
use whipple::Study;
use whipple::{BenchmarkParameters, Bicycle, Error, Result};
use whipple_reference::meijaard2007 as published;

fn preset(name: &str) -> Result<Canonical> {
    Canonical::new(&presets::find(name)?.bicycle().benchmark()?)
}

/// Meijaard et al. 2007, Table 2 (doi:10.1098/rspa.2007.1857): (v_d, v_w, v_c), on the whole
/// half-line.
const TABLE_2: (f64, f64, f64) = (
    published::DOUBLE_ROOT_SPEED,
    published::WEAVE_SPEED,
    published::CAPSIZE_SPEED,
);

/// The grid scan of 4,000 cells missed the benchmark's weave and capsize speeds on 0..20000 and
/// 0..1e5 and reported "self-stable nowhere".
#[test]
fn speeds_range_0_20000_finds_the_weave() -> Result<()> {
    for hi in [20.0, 20000.0, 1e5, 1e6, f64::INFINITY] {
        let s = whipple::critical_speeds(&preset("benchmark")?, 0.0, hi)?;
        assert_abs_diff_eq!(
            s.double_root_speed.unwrap_or(0.0),
            TABLE_2.0,
            epsilon = 1e-12
        );
        assert_abs_diff_eq!(s.weave_speed.unwrap_or(0.0), TABLE_2.1, epsilon = 1e-12);
        assert_abs_diff_eq!(s.capsize_speed.unwrap_or(0.0), TABLE_2.2, epsilon = 1e-12);
        assert_eq!(s.stable_speed_ranges.len(), 1, "{hi}");
        assert!(s.unresolved.is_empty());
    }
    Ok(())
}

/// The same misbehaviour for the Schwinn Crown and the Browser with Jason: every range reports
/// what the whole half-line reports.
#[test]
fn speeds_range_0_1e5_finds_the_weave_of_schwinn_crown_and_browser_jason() -> Result<()> {
    for name in ["schwinn-crown", "browser-jason"] {
        let c = preset(name)?;
        let all = whipple::critical_speeds(&c, 0.0, f64::INFINITY)?;
        assert!(
            all.weave_speed.is_some() && all.capsize_speed.is_some(),
            "{name}"
        );
        for hi in [20.0, 20000.0, 1e5] {
            let s = whipple::critical_speeds(&c, 0.0, hi)?;
            assert_eq!(s.weave_speed, all.weave_speed, "{name} 0..{hi}");
            assert_eq!(s.capsize_speed, all.capsize_speed, "{name} 0..{hi}");
            assert_eq!(
                s.stable_speed_ranges, all.stable_speed_ranges,
                "{name} 0..{hi}"
            );
        }
    }
    // Dressel's Schwinn Crown capsize speed, 7.9807 m/s with JBike6's gravity.
    let crown = whipple::critical_speeds(&preset("schwinn-crown")?, 0.0, f64::INFINITY)?;
    assert_abs_diff_eq!(crown.capsize_speed.unwrap_or(0.0), 7.9807, epsilon = 5e-5);
    Ok(())
}

/// The two-mass skate has no capsize speed: self-stable above its weave speed, an unbounded
/// range (its upper end is where round-off in the stored matrices leaves the answer open).
#[test]
fn an_unbounded_stable_range_is_reported_as_such() -> Result<()> {
    let s = whipple::critical_speeds(&preset("two-mass-skate")?, 0.0, f64::INFINITY)?;
    assert!(s.capsize_speed.is_none());
    let vw = s.weave_speed.unwrap_or(0.0);
    assert_abs_diff_eq!(vw, 2.841008323370, epsilon = 1e-9);
    assert_eq!(s.stable_speed_ranges.len(), 1);
    let (lo, hi) = s.stable_speed_ranges[0];
    assert_eq!(lo, vw);
    // Either truly unbounded or open above a horizon far beyond any physical speed.
    assert!(
        hi == f64::INFINITY
            || (hi > 1e6 && s.unresolved.last().map(|u| u.1) == Some(f64::INFINITY))
    );
    let json = serde_json::to_value(&s).map_err(|e| Error::NonFinite {
        context: e.to_string(),
    })?;
    assert_eq!(json["range"], serde_json::json!([0.0, null]));
    Ok(())
}

fn modified(f: impl Fn(&mut BenchmarkParameters)) -> Result<Canonical> {
    let mut b = BenchmarkParameters::meijaard2007();
    f(&mut b);
    Canonical::new(&b)
}

/// With g = 1e300 `speeds` printed "none" (overflow in the coefficients) while `eig` errored:
/// gravity is scaled out, so the critical speeds are those of g = 9.81 times √(g / 9.81).
#[test]
fn g_1e300_scales_the_critical_speeds_instead_of_printing_none() -> Result<()> {
    let s = whipple::critical_speeds(&modified(|b| b.g = 1e300)?, 0.0, f64::INFINITY)?;
    let scale = (1e300f64 / 9.81).sqrt();
    let rel = |x: Option<f64>, want: f64| (x.unwrap_or(0.0) / scale - want).abs() / want;
    assert!(rel(s.weave_speed, TABLE_2.1) < 1e-12, "{s:?}");
    assert!(rel(s.capsize_speed, TABLE_2.2) < 1e-12, "{s:?}");
    assert!(rel(s.double_root_speed, TABLE_2.0) < 1e-11, "{s:?}");
    Ok(())
}

/// With mB = 1e18 the eigenvalues were garbage (det M lost to cancellation): now both the
/// eigenvalues and the critical speeds say that the accuracy is lost.
#[test]
fn mb_1e18_reports_accuracy_lost_instead_of_garbage_eigenvalues() -> Result<()> {
    let c = modified(|b| b.m_b = 1e18)?;
    assert!(matches!(
        eigen::eigenvalues(&c, 5.0),
        Err(Error::AccuracyLost { .. })
    ));
    assert!(matches!(
        whipple::critical_speeds(&c, 0.0, f64::INFINITY),
        Err(Error::AccuracyLost { .. })
    ));
    // An ordinary heavy rider is not refused.
    let heavy = modified(|b| b.m_b = 250.0)?;
    assert!(whipple::critical_speeds(&heavy, 0.0, f64::INFINITY).is_ok());
    Ok(())
}

/// Negative speeds: the eigenvalues at −v are those at v negated, so the benchmark bicycle is
/// unstable at every negative speed, and the half-line answer is unchanged.
#[test]
fn the_whole_line_includes_riding_backwards() -> Result<()> {
    let c = preset("benchmark")?;
    let s = whipple::critical_speeds(&c, f64::NEG_INFINITY, f64::INFINITY)?;
    assert_eq!(s.stable_speed_ranges.len(), 1);
    assert_abs_diff_eq!(s.stable_speed_ranges[0].0, TABLE_2.1, epsilon = 1e-12);
    Ok(())
}

/// The largest real part of the eigenvalues of A(v) and the spectral radius, by faer's general
/// (Hessenberg QR) eigensolver: independent of the characteristic polynomial, backward stable.
fn max_real(c: &Canonical, v: f64) -> Result<(f64, f64)> {
    let a = whipple::advanced::linear::StateSpace::new(c, v)?.a;
    let m = faer::Mat::<f64>::from_fn(4, 4, |i, j| a[(i, j)]);
    let values = m.eigenvalues().map_err(|e| Error::NonFinite {
        context: format!("faer's eigenvalues at {v}: {e:?}"),
    })?;
    let re = values
        .iter()
        .map(|z| z.re)
        .fold(f64::NEG_INFINITY, f64::max);
    let scale = values.iter().map(|z| z.norm()).fold(1.0, f64::max);
    Ok((re, scale))
}

/// Checks the certified answer against a dense scan of max Re λ on [lo, hi]: every scan point
/// outside the enclosures agrees with the certified verdict, and every change of sign between
/// neighbouring scan points has a certified crossing (or an unresolved interval) between them.
/// The scan is uniform over the first 50 m/s (10,000 points), log-spaced beyond (2,000 points),
/// and adds the middle of every certified interval, so every interval is visited.
fn agrees_with_a_dense_scan(c: &Canonical, lo: f64, hi: f64) -> Result<usize> {
    let s = whipple::critical_speeds(c, lo, hi)?;
    let mut scan: Vec<f64> = Vec::new();
    let top = hi.min(50.0);
    for k in 0..=10_000 {
        let v = lo + (top - lo) * k as f64 / 10_000.0;
        if v >= lo && v <= hi {
            scan.push(v);
        }
    }
    if hi > 50.0 {
        let end = hi.min(1e6);
        for k in 1..=2000 {
            scan.push(50.0 * (end / 50.0).powf(k as f64 / 2000.0));
        }
    }
    let mut cuts: Vec<f64> = s.crossings.iter().map(|x| x.speed).collect();
    cuts.extend(s.stable_speed_ranges.iter().flat_map(|r| [r.0, r.1]));
    cuts.push(lo);
    cuts.push(hi.min(1e6));
    cuts.sort_by(f64::total_cmp);
    for w in cuts.windows(2) {
        if w[1] > w[0] {
            scan.push(0.5 * (w[0] + w[1]));
        }
    }
    scan.retain(|v| v.is_finite() && *v >= lo && *v <= hi);
    scan.sort_by(f64::total_cmp);
    let near = |v: f64| {
        s.crossings
            .iter()
            .any(|x| (v - x.speed).abs() <= 1e-7 * x.speed.abs().max(1.0))
            || s.unresolved
                .iter()
                .any(|u| v >= u.0 - 1e-7 && v <= u.1 + 1e-7)
    };
    let mut checked = 0;
    let mut previous: Option<(f64, bool)> = None;
    for &v in &scan {
        if near(v) || v == 0.0 {
            previous = None;
            continue;
        }
        let (m, scale) = max_real(c, v)?;
        // Where |max Re λ| is below 1e-5 of the spectral radius the scan cannot decide: a
        // backward-stable eigensolver is accurate to about ε‖A‖ times the eigenvalue's
        // condition, and at high speed the two smallest eigenvalues (of size 1/v) form a
        // near-double pair beside two of size v (the two-mass skate at 1.6e5 m/s: faer finds
        // Re λ = +2.55 where the asymptotic pair has Re λ ≈ −3e-6). Those points are skipped.
        if m.abs() <= 1e-5 * scale {
            previous = None;
            continue;
        }
        let stable_scan = m < 0.0;
        let stable_certified = s
            .stable_speed_ranges
            .iter()
            .any(|&(a, b)| (v > a || (v == a && a == lo)) && (v < b || (v == b && b == hi)));
        assert_eq!(
            stable_scan, stable_certified,
            "at v = {v}: max Re λ = {m}, certified {:?}",
            s.stable_speed_ranges
        );
        if let Some((u, was)) = previous {
            if was != stable_scan {
                let between = s.crossings.iter().any(|x| x.speed > u && x.speed < v)
                    || s.unresolved.iter().any(|r| r.1 > u && r.0 < v);
                assert!(
                    between,
                    "a change between {u} and {v} without a certified crossing"
                );
            }
        }
        previous = Some((v, stable_scan));
        checked += 1;
    }
    Ok(checked)
}

/// Every preset up to 1e4 m/s (beyond, the two-mass skate's smallest eigenvalues, of size 1/v
/// beside ones of size v, are below what the dense eigensolver resolves; the random bicycles
/// below go to 1e6 m/s).
#[test]
fn presets_agree_with_a_dense_scan() -> Result<()> {
    for p in presets::PRESETS {
        let c = Canonical::new(&p.bicycle().benchmark()?)?;
        assert!(
            agrees_with_a_dense_scan(&c, 0.0, 1e4)? > 10_000,
            "{}",
            p.name
        );
    }
    Ok(())
}

fn random_bicycle() -> impl Strategy<Value = BenchmarkParameters> {
    (
        (
            0.8f64..1.3,
            -0.05f64..0.3,
            -0.2f64..0.7,
            0.25f64..0.4,
            0.25f64..0.4,
        ),
        (40.0f64..130.0, 0.1f64..0.7, -1.3f64..-0.5, 0.5f64..2.0),
        (0.5f64..8.0, -0.9f64..-0.4, 0.0f64..1.5, 0.2f64..3.0),
    )
        .prop_map(
            |((w, c, lam, r_r, r_f), (m_b, x_b, z_b, s_b), (m_h, z_h, x_h, spin))| {
                let mut b = BenchmarkParameters::meijaard2007();
                b.w = w;
                b.c = c;
                b.lambda = lam;
                b.r_r = r_r;
                b.r_f = r_f;
                b.m_b = m_b;
                b.x_b = x_b;
                b.z_b = z_b;
                b.i_bxx *= s_b;
                b.i_bzz *= s_b;
                b.i_bxz *= s_b;
                b.i_byy *= s_b;
                b.m_h = m_h;
                b.z_h = z_h;
                b.x_h = x_h * w;
                b.i_ryy *= spin;
                b.i_rxx *= spin;
                b.i_fyy *= spin;
                b.i_fxx *= spin;
                b
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Random bicycles and ranges up to 1e6 m/s: the certified verdict equals a dense
    /// eigenvalue scan's at every scan point, and every sign change of the scan has a certified
    /// crossing.
    #[test]
    fn certified_speeds_equal_a_dense_scan(
        bike in random_bicycle(),
        lo in 0.0f64..5.0,
        span in prop_oneof![Just(f64::INFINITY), 1.0f64..1e6],
    ) {
        let Ok(c) = Canonical::new(&bike) else {
            return Ok(()); // an invalid random design (M not positive definite, …)
        };
        match agrees_with_a_dense_scan(&c, lo, lo + span) {
            Ok(_) | Err(Error::AccuracyLost { .. }) => {}
            Err(e) => prop_assert!(false, "{e}"),
        }
    }

    /// Random cells of random maps: each design's critical speeds equal the single-bicycle
    /// answer (`whipple speeds`) to 1e-10 m/s.
    #[test]
    fn map_cells_equal_single_bicycle_speeds(
        trail in (-0.05f64..0.1, 0.15f64..0.3),
        head in (60.0f64..68.0, 72.0f64..80.0),
        cells in proptest::collection::vec((0usize..41, 0usize..31), 8),
    ) {
        let bike = presets::find("benchmark").map_err(|e| TestCaseError::fail(e.to_string()))?.bicycle();
        let x = Axis::new(Parameter::Benchmark("c".into()), trail.0, trail.1, 41).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let y = Axis::scaled(Parameter::Benchmark("head_angle".into()), head.0, head.1, 31, 1f64.to_radians()).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let study = Study::new(bike, x.clone(), Some(y.clone()), StudySettings::default()).map_err(|e| TestCaseError::fail(e.to_string()))?;
        for (ix, iy) in cells {
            let row = study.design((iy * 41 + ix) as u64);
            let mut b = BenchmarkParameters::meijaard2007();
            b.c = x.value(ix);
            b.lambda = std::f64::consts::FRAC_PI_2 - y.value(iy).to_radians();
            let single = Canonical::new(&b).and_then(|c| stability::summary(&whipple::advanced::linear::SpeedPolynomials::new(&c)?, 0.0, f64::INFINITY).and(whipple::critical_speeds(&c, 0.0, f64::INFINITY)));
            match single {
                Ok(s) => {
                    prop_assert_eq!(row.status, DesignStatus::Ok);
                    let q = row.quantities;
                    for (a, b) in [(q.weave_speed, s.weave_speed), (q.capsize_speed, s.capsize_speed)] {
                        match (a, b) {
                            (Some(a), Some(b)) => prop_assert!((a - b).abs() <= 1e-10, "{a} {b}"),
                            (None, None) => {}
                            other => prop_assert!(false, "{other:?}"),
                        }
                    }
                    prop_assert_eq!(q.stable, !s.stable_speed_ranges.is_empty());
                }
                Err(_) => prop_assert!(row.status != DesignStatus::Ok),
            }
        }
    }
}

/// Sharded runs concatenate to the whole run, row for row.
#[test]
fn shards_reassemble_the_whole_study() -> Result<()> {
    let bike: Bicycle = presets::find("schwinn-crown")?.bicycle();
    assert!(matches!(bike.description, Description::Jbike6(_)));
    let x = Axis::new(Parameter::Jbike6("trail".into()), 0.0, 0.2, 23)?;
    let y = Axis::new(Parameter::Jbike6("ycmrider".into()), 0.8, 1.4, 7)?;
    let study = Study::new(bike, x, Some(y), StudySettings::default())?;
    let stop = AtomicBool::new(false);
    let mut whole = Vec::new();
    study.run(Shard::WHOLE, &stop, |rows| {
        whole.extend_from_slice(rows);
        Ok(())
    })?;
    let mut parts = Vec::new();
    for index in 0..5 {
        study.run(Shard { index, count: 5 }, &stop, |rows| {
            parts.extend_from_slice(rows);
            Ok(())
        })?;
    }
    assert_eq!(whole.len(), 161);
    assert_eq!(whole, parts);
    Ok(())
}

/// A study's design as a bicycle (what the page loads when a map cell is clicked): the same
/// numbers the study computed with, for a JBike6-form bicycle too; an index past the study is
/// refused.
#[test]
fn a_designs_bicycle_is_the_one_computed() -> Result<()> {
    let bike: Bicycle = presets::find("schwinn-crown")?.bicycle();
    let x = Axis::new(Parameter::Jbike6("trail".into()), 0.0, 0.2, 23)?;
    let y = Axis::new(Parameter::Jbike6("ycmrider".into()), 0.8, 1.4, 7)?;
    let study = Study::new(bike, x, Some(y), StudySettings::default())?;
    let index = 5 * 23 + 9;
    let design = study.bicycle_at(index)?;
    let Description::Jbike6(j) = &design.description else {
        panic!("the Crown stays in the JBike6 form");
    };
    assert_abs_diff_eq!(j.trail, 9.0 * 0.2 / 22.0, epsilon = 1e-15);
    assert_abs_diff_eq!(j.rider.ycm, 0.8 + 5.0 * 0.1, epsilon = 1e-15);
    assert_eq!(design.name.as_deref(), Some("schwinn-crown"));
    let row = study.design(index);
    let speeds =
        whipple::critical_speeds(&Canonical::new(&design.benchmark()?)?, 0.0, f64::INFINITY)?;
    assert_eq!(row.quantities.weave_speed, speeds.weave_speed);
    assert!(matches!(
        study.bicycle_at(study.len()),
        Err(Error::InvalidArgument { what: "index", .. })
    ));
    Ok(())
}

/// A parameter of a JBike6-form bicycle may be named by its TOML path as well as its `.m` key:
/// `rider.ycm` is `ycmrider`, `rider.I[1]` is `Irider(1)`, `rider.alpha` is `alphaIrider`; the
/// study computes the same rows either way.
#[test]
fn jbike6_parameters_take_toml_paths() -> Result<()> {
    let bike: Bicycle = presets::find("schwinn-crown")?.bicycle();
    for (path, key, (start, stop, count)) in [
        ("rider.ycm", "ycmrider", (0.8, 1.4, 7)),
        ("rider.I[1]", "Irider(1)", (5.0, 15.0, 3)),
        ("rider.alpha", "alphaIrider", (-0.35, 0.35, 5)),
    ] {
        let by_path = Parameter::named(path, &bike);
        let by_key = Parameter::named(key, &bike);
        assert_eq!(by_path, by_key, "{path}");
        let Some(parameter) = by_path else {
            panic!("{path} names no parameter of the Crown");
        };
        let study = Study::new(
            bike.clone(),
            Axis::new(parameter, start, stop, count)?,
            None,
            StudySettings::default(),
        )?;
        let speeds: Vec<Option<f64>> = (0..study.len())
            .map(|i| study.design(i).quantities.weave_speed)
            .collect();
        assert!(
            speeds.iter().any(Option::is_some),
            "{path}: no weave speed at all"
        );
    }
    assert_eq!(Parameter::named("rider.height", &bike), None);
    Ok(())
}

/// A design that breaks a rule is marked with the rule and never stops the study.
#[test]
fn invalid_designs_are_marked_not_computed() -> Result<()> {
    let bike = presets::find("benchmark")?.bicycle();
    let x = Axis::new(Parameter::Benchmark("mB".into()), -10.0, 10.0, 3)?;
    let study = Study::new(bike, x, None, StudySettings::default())?;
    let first = study.design(0);
    assert_eq!(first.status, DesignStatus::Invalid);
    assert!(first.reason.as_deref().unwrap_or("").contains("mB"));
    assert_eq!(study.design(2).status, DesignStatus::Ok);
    Ok(())
}
