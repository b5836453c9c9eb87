//! Published values reproduced. Each test cites its source; the numbers live in the
//! `whipple-reference` crate (the one copy the workspace's tests share), copied from the
//! publications with their citations.

use approx::assert_abs_diff_eq;
use nalgebra::Matrix2;
use whipple::Canonical;
use whipple::advanced::eigen;
use whipple::advanced::modes::Mode;
use whipple::{BenchmarkParameters, Result, presets};
use whipple_reference::meijaard2007 as published;

fn matrix(rows: [[f64; 2]; 2]) -> Matrix2<f64> {
    Matrix2::new(rows[0][0], rows[0][1], rows[1][0], rows[1][1])
}

/// Meijaard, Papadopoulos, Ruina & Schwab 2007, Proc. R. Soc. A 463:1955–1982, §5
/// (doi:10.1098/rspa.2007.1857). The published entries are the exact values rounded to 14
/// decimals.
#[test]
fn canonical_matrices_match_meijaard_2007() -> Result<()> {
    let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    let (m, c1, k0, k2) = (
        matrix(published::M),
        matrix(published::C1),
        matrix(published::K0),
        matrix(published::K2),
    );
    assert_abs_diff_eq!(c.m, m, epsilon = 1e-13);
    assert_abs_diff_eq!(c.c1, c1, epsilon = 1e-13);
    assert_abs_diff_eq!(c.k0, k0, epsilon = 1e-13);
    assert_abs_diff_eq!(c.k2, k2, epsilon = 1e-13);
    Ok(())
}

/// Meijaard et al. 2007, Table 2, eigenvalues at 0 … 10 m/s, to 1e-12.
#[test]
fn eigenvalues_match_meijaard_2007_table_2() -> Result<()> {
    let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    let at_rest = eigen::eigenvalues(&c, 0.0)?;
    for (l, p) in at_rest.iter().zip(published::EIGENVALUES_AT_REST) {
        assert_abs_diff_eq!(l.re, p, epsilon = 1e-12);
        assert_eq!(l.im, 0.0);
    }
    let speeds: Vec<f64> = published::EIGENVALUES.iter().map(|row| row.0).collect();
    let s = whipple::eigen_sweep(&c, &speeds)?;
    assert_eq!(
        s.modes,
        [Mode::Weave, Mode::Weave, Mode::Capsize, Mode::Castering]
    );
    for (row, values) in published::EIGENVALUES.iter().zip(&s.eigenvalues) {
        let (v, re, im, capsize, castering) = *row;
        let direct = eigen::eigenvalues(&c, v)?;
        assert!(direct.iter().all(|d| values.contains(d)), "v = {v}");
        assert_abs_diff_eq!(values[0].re, re, epsilon = 1e-12);
        assert_abs_diff_eq!(values[0].im, im, epsilon = 1e-12);
        assert_abs_diff_eq!(values[1].re, re, epsilon = 1e-12);
        assert_abs_diff_eq!(values[1].im, -im, epsilon = 1e-12);
        assert_abs_diff_eq!(values[2].re, capsize, epsilon = 1e-12);
        assert_abs_diff_eq!(values[3].re, castering, epsilon = 1e-12);
    }
    Ok(())
}

/// Meijaard et al. 2007, Table 2: v_d (with its double root), v_w (with the weave frequency)
/// and v_c, to 1e-12.
#[test]
fn critical_speeds_match_meijaard_2007() -> Result<()> {
    let c = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    let s = whipple::critical_speeds(&c, 0.0, 10.0)?;
    let get = |x: Option<f64>| x.expect("the benchmark bicycle has every critical speed");
    assert_abs_diff_eq!(
        get(s.double_root_speed),
        published::DOUBLE_ROOT_SPEED,
        epsilon = 1e-12
    );
    assert_abs_diff_eq!(
        get(s.double_root_eigenvalue),
        published::DOUBLE_ROOT_EIGENVALUE,
        epsilon = 1e-9
    );
    assert_abs_diff_eq!(get(s.weave_speed), published::WEAVE_SPEED, epsilon = 1e-12);
    assert_abs_diff_eq!(
        get(s.weave_frequency),
        published::WEAVE_FREQUENCY,
        epsilon = 1e-12
    );
    assert_abs_diff_eq!(
        get(s.capsize_speed),
        published::CAPSIZE_SPEED,
        epsilon = 1e-12
    );
    assert_eq!(s.stable_speed_ranges.len(), 1);
    assert_abs_diff_eq!(
        s.stable_speed_ranges[0].0,
        published::WEAVE_SPEED,
        epsilon = 1e-12
    );
    assert_abs_diff_eq!(
        s.stable_speed_ranges[0].1,
        published::CAPSIZE_SPEED,
        epsilon = 1e-12
    );
    Ok(())
}

/// Dressel, "Benchmarking a Fully Non-Linear Bicycle Model with JBike6" (Cornell, 2003–2015):
/// the Schwinn Crown's capsize speed is 7.9807 m/s with JBike6's default gravity.
#[test]
fn schwinn_crown_capsize_speed_matches_dressel() -> Result<()> {
    let bike = presets::find("schwinn-crown")?.bicycle().benchmark()?;
    assert_eq!(bike.g, 9.80665);
    let c = Canonical::new(&bike)?;
    let s = whipple::critical_speeds(&c, 0.0, 20.0)?;
    let vc = s
        .capsize_speed
        .expect("the Schwinn Crown has a capsize speed");
    assert_abs_diff_eq!(vc, 7.9807, epsilon = 5e-5);
    Ok(())
}

/// The Browser with rider Jason (Moore 2012) against an independent implementation: the state
/// matrix at 5 m/s printed in BicycleParameters' `Bicycle.ab_matrix` documentation for the same
/// parameter set (8 significant digits).
#[test]
fn browser_jason_state_matrix_matches_bicycleparameters() -> Result<()> {
    let bike = presets::find("browser-jason")?.bicycle().benchmark()?;
    let ss = whipple::advanced::linear::StateSpace::new(&Canonical::new(&bike)?, 5.0)?;
    let published = [
        [8.26150335, -17.52187211, -0.1488979, -1.07153674],
        [17.66475151, -22.88692074, 9.96449204, -14.22097935],
    ];
    for (i, row) in published.iter().enumerate() {
        for (j, &value) in row.iter().enumerate() {
            assert_abs_diff_eq!(ss.a[(i + 2, j)], value, epsilon = 6e-8);
        }
    }
    let b = [[0.01071772, -0.06613267], [-0.06613267, 4.42570676]];
    for (i, row) in b.iter().enumerate() {
        for (j, &value) in row.iter().enumerate() {
            assert_abs_diff_eq!(ss.b[(i + 2, j)], value, epsilon = 6e-9);
        }
    }
    Ok(())
}

/// The two-mass-skate bicycle (Kooijman et al. 2011): its canonical matrices against an
/// independent derivation — Meijaard et al. 2007, Appendix A, transcribed by hand in
/// `bench/trajectory_references.py` (the transcription checked there against the benchmark
/// bicycle's published matrices) and equal to BicycleParameters' `benchmark_par_to_canonical`
/// to the last bit — stored in `data/references.json`, to 1e-14. Zero-radius massless skates
/// give finite matrices (no 0/0 gyroscopic terms); with zero trail det(g K₀ + v² K₂) does not
/// depend on speed, so there is no capsize speed; it is self-stable above its weave speed,
/// which the reference locates by bisection on numpy's eigenvalues of A(v) (2.8410083233664
/// m/s), to 1e-11.
#[test]
fn two_mass_skate_matches_an_independent_derivation() -> Result<()> {
    let bike = presets::find("two-mass-skate")?.bicycle().benchmark()?;
    let doc: serde_json::Value =
        serde_json::from_str(include_str!("data/references.json")).expect("valid JSON");
    let reference = &doc["two_mass_skate"];
    let listed = serde_json::json!({ "benchmark": reference["bicycle"] }).to_string();
    let listed =
        whipple::advanced::io::parse(&listed, whipple::advanced::io::Format::Json)?.benchmark()?;
    assert_eq!(
        listed, bike,
        "the reference is computed for the preset's numbers"
    );
    let c = Canonical::new(&bike)?;
    let matrix = |key: &str| {
        let m = &reference[key];
        let x = |i: usize, j: usize| m[i][j].as_f64().expect("a number");
        Matrix2::new(x(0, 0), x(0, 1), x(1, 0), x(1, 1))
    };
    assert_abs_diff_eq!(c.m, matrix("M"), epsilon = 1e-14);
    assert_abs_diff_eq!(c.c1, matrix("C1"), epsilon = 1e-14);
    assert_abs_diff_eq!(c.k0, matrix("K0"), epsilon = 1e-14);
    assert_abs_diff_eq!(c.k2, matrix("K2"), epsilon = 1e-14);
    let s = whipple::critical_speeds(&c, 0.0, 20.0)?;
    assert!(s.capsize_speed.is_none());
    let vw = s.weave_speed.expect("the TMS has a weave speed");
    let expected = reference["weave_speed"].as_f64().expect("a number");
    assert_abs_diff_eq!(vw, expected, epsilon = 1e-11);
    assert_eq!(s.stable_speed_ranges, vec![(vw, 20.0)]);
    Ok(())
}
