//! The pipeline's identities and bad inputs; the files are checked in `tests/measured.rs`.

use std::f64::consts::PI;

use super::steps::{self, HungFrame};
use super::*;
use crate::parameters::BenchmarkParameters;

const BROWSER: &str = include_str!("../../../tests/data/measured/BrowserMeasured.txt");

fn exact(value: f64) -> Measured {
    Measured::new(value, 0.0)
}

/// The measurements a perfect bench would give for `p`: every period and hanging computed
/// from the inertias and mass centres (the pipeline's steps run backwards).
fn measured_exactly(p: &BenchmarkParameters) -> Measurements<Measured> {
    let (lr, lf, n) = (0.29, 0.31, 13.0);
    let (m_p, l_p, d_p, t_p) = (5.56, 1.05, 0.03, 1.894);
    let rod = m_p / 12.0 * (3.0 * (d_p / 2.0) * (d_p / 2.0) + l_p * l_p);
    let k = 4.0 * PI * PI * rod / (t_p * t_p);
    let compound = |m: f64, l: f64, i: f64| 2.0 * PI * ((i + m * l * l) / (m * p.g * l)).sqrt();
    let torsional = |i: f64| 2.0 * PI * (i / k).sqrt();
    let l_b = (p.x_b * p.x_b + (p.z_b + p.r_r).powi(2)).sqrt();
    let l_h = ((p.x_h - p.w).powi(2) + (p.z_h + p.r_f).powi(2)).sqrt();
    let hangings = |frame: HungFrame, alphas: [f64; 3], x: f64, z: f64, i: [f64; 3]| {
        alphas
            .iter()
            .map(|alpha| {
                let beta = p.lambda - alpha * PI / 180.0;
                let intercept = z + beta.tan() * x;
                let a = match frame {
                    HungFrame::Rear => -beta.cos() * (intercept + p.r_r),
                    HungFrame::Front => -beta.cos() * (intercept + p.r_f - p.w * beta.tan()),
                };
                let (s, c) = beta.sin_cos();
                let j = i[0] * c * c - 2.0 * i[1] * s * c + i[2] * s * s;
                Hanging {
                    alpha: exact(*alpha),
                    a: exact(a),
                    period: exact(torsional(j)),
                }
            })
            .collect()
    };
    Measurements {
        g: exact(p.g),
        d_r: exact(2.0 * PI * n * p.r_r),
        n_r: exact(n),
        d_f: exact(2.0 * PI * n * p.r_f),
        n_f: exact(n),
        w: exact(p.w),
        gamma: exact(90.0 - p.lambda * 180.0 / PI),
        f: exact(p.r_f * p.lambda.sin() - p.c * p.lambda.cos()),
        m_r: exact(p.m_r),
        m_f: exact(p.m_f),
        m_b: exact(p.m_b),
        m_h: exact(p.m_h),
        l_r: exact(lr),
        l_f: exact(lf),
        t_c_r: exact(compound(p.m_r, lr, p.i_ryy)),
        t_c_f: exact(compound(p.m_f, lf, p.i_fyy)),
        t_c_b: exact(compound(p.m_b, l_b, p.i_byy)),
        t_c_h: exact(compound(p.m_h, l_h, p.i_hyy)),
        t_t_r: exact(torsional(p.i_rxx)),
        t_t_f: exact(torsional(p.i_fxx)),
        m_p: exact(m_p),
        l_p: exact(l_p),
        d_p: exact(d_p),
        t_t_p: exact(t_p),
        rear_frame: hangings(
            HungFrame::Rear,
            [3.4, 138.7, 229.8],
            p.x_b,
            p.z_b,
            [p.i_bxx, p.i_bxz, p.i_bzz],
        ),
        front_frame: hangings(
            HungFrame::Front,
            [346.7, 28.1, 287.0],
            p.x_h,
            p.z_h,
            [p.i_hxx, p.i_hxz, p.i_hzz],
        ),
    }
}

/// A bicycle "measured" exactly comes back to 1e-12 (Meijaard 2007's benchmark bicycle).
#[test]
fn exact_measurements_round_trip() -> Result<()> {
    let p = BenchmarkParameters::meijaard2007();
    let back = MeasuredParameters::new(&measured_exactly(&p))?;
    for (info, (want, got)) in BENCHMARK_TABLE
        .iter()
        .zip(p.to_array().iter().zip(back.benchmark.to_array()))
    {
        let scale = want.abs().max(1e-3);
        assert!(
            (got - want).abs() <= 1e-12 * scale,
            "{}: {got} vs {want}",
            info.key
        );
    }
    assert!(back.sigma.is_empty(), "no σ in, no σ out: {:?}", back.sigma);
    Ok(())
}

/// Each pendulum step inverted recovers its input.
#[test]
fn pendulum_steps_invert() {
    let (m, g, l, i): (f64, f64, f64, f64) = (3.22, 9.81, 0.37, 0.2458);
    let period = 2.0 * PI * ((i + m * l * l) / (m * g * l)).sqrt();
    assert!((steps::compound_pendulum_inertia(m, g, l, period) - i).abs() < 1e-14);
    let k: f64 = steps::torsion_constant(0.51, 1.9);
    let t: f64 = 1.9;
    assert!((steps::torsional_pendulum_inertia(k, t) - 0.51).abs() < 1e-14);
    let r: f64 = steps::wheel_radius(2.0 * PI * 13.0 * 0.34, 13.0);
    assert!((r - 0.34).abs() < 1e-15);
    let lambda: f64 = 0.3;
    let c: f64 = steps::trail(0.35, lambda, 0.35 * lambda.sin() - 0.08 * lambda.cos());
    assert!((c - 0.08).abs() < 1e-15);
    let tilt: f64 = steps::steer_axis_tilt(90.0 - 0.3 * 180.0 / PI);
    assert!((tilt - 0.3).abs() < 1e-15);
}

/// Dual numbers through the pipeline give the derivative of a closed form: ∂rR/∂dR = 1/(2π nR).
#[test]
fn jacobian_matches_closed_forms() -> Result<()> {
    let file = read_measurements(BROWSER)?;
    let result = MeasuredParameters::new(&file.measurements)?;
    let row = |key: &str| BENCHMARK_TABLE.iter().position(|p| p.key == key).unwrap();
    let col = |key: &str| result.inputs.iter().position(|k| k == key).unwrap();
    let d = result.jacobian[(row("rR"), col("dR"))];
    assert!((d - 1.0 / (2.0 * PI * 13.0)).abs() < 1e-15);
    // λ = (90° − γ) π/180: ∂λ/∂γ = −π/180.
    assert!((result.jacobian[(row("lam"), col("gamma"))] + PI / 180.0).abs() < 1e-15);
    // the mass centre's σ correlates x and z of one frame; different frames share λ only.
    let rho = result.correlation("xB", "zB").unwrap();
    assert!(rho.abs() > 0.0 && rho.abs() < 1.0, "{rho}");
    assert!((result.correlation("w", "w").unwrap() - 1.0).abs() < 1e-12);
    Ok(())
}

fn browser_with(key: &str, value: &str) -> String {
    BROWSER
        .lines()
        .map(|l| {
            if l.split('=').next().map(str::trim) == Some(key) {
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn error_of(text: &str) -> Error {
    match read_measurements(text).and_then(|f| MeasuredParameters::new(&f.measurements)) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

#[test]
fn negative_period_is_refused_naming_it() {
    let e = error_of(&browser_with("TcB1", "-1.71730688911+/-4.98313880734e-06"));
    let Error::InvalidParameter { field, rule, .. } = &e else {
        panic!("{e}")
    };
    assert_eq!(field, "TcB1");
    assert!(
        rule.contains("a period must be positive") && rule.contains("line 38"),
        "{rule}"
    );
}

#[test]
fn zero_length_calibration_rod_is_refused() {
    let e = error_of(&browser_with("lP", "0+/-0.001"));
    assert!(
        matches!(&e, Error::InvalidParameter { field, .. } if field == "lP"),
        "{e}"
    );
    assert!(e.to_string().contains("calibration rod's length"), "{e}");
}

#[test]
fn parallel_hanging_lines_are_refused() {
    // 3.4° + 180°: the same wire direction, so lines 1 and 2 are parallel.
    let e = error_of(&browser_with("alphaB2", "183.4+/-0.2"));
    assert!(
        matches!(&e, Error::InvalidParameter { field, .. } if field == "alphaB1 and alphaB2"),
        "{e}"
    );
    assert!(e.to_string().contains("parallel"), "{e}");
}

#[test]
fn missing_measurement_names_what_it_feeds() {
    let silver = include_str!("../../../tests/data/measured/SilverMeasured.txt");
    let e = error_of(silver);
    assert!(
        matches!(&e, Error::Parse { field: Some(f), .. } if f == "g"),
        "{e}"
    );
    let without_df: String = BROWSER
        .lines()
        .filter(|l| !l.starts_with("dF"))
        .collect::<Vec<_>>()
        .join("\n");
    let message = error_of(&without_df).to_string();
    assert!(
        message.contains("dF is missing: the front wheel's radius needs it"),
        "{message}"
    );
}

#[test]
fn file_errors_name_key_and_line() {
    let twice = format!("{BROWSER}\nmB = 9.0");
    let message = error_of(&twice).to_string();
    assert!(
        message.contains("`mB`") && message.contains("given twice"),
        "{message}"
    );
    let unknown = format!("{BROWSER}\nmX = 1.0");
    let message = error_of(&unknown).to_string();
    assert!(
        message.contains("line 52") && message.contains("unknown key"),
        "{message}"
    );
    let message = error_of(&browser_with("mB", "9.86+/-0.02, 9.9")).to_string();
    assert!(message.contains("+/-"), "{message}");
    let message = error_of(&browser_with("mB", "heavy")).to_string();
    assert!(message.contains("`heavy` is not a number"), "{message}");
    for sigma in ["-0.003", "nan"] {
        let message = error_of(&browser_with("mB", &format!("9.86+/-{sigma}"))).to_string();
        assert!(
            message.contains("mB")
                && message.contains(&format!("`{sigma}` must be zero or positive")),
            "{message}"
        );
    }
    let message = error_of(&format!("{BROWSER}\nh1 = 0.9")).to_string();
    assert!(message.contains("not supported yet"), "{message}");
    let missing = BROWSER
        .lines()
        .filter(|l| !l.starts_with("TtB2"))
        .collect::<Vec<_>>()
        .join("\n");
    let message = error_of(&missing).to_string();
    assert!(message.contains("TtB2 is missing"), "{message}");
}

/// A list of repeated measurements is their mean, σ = √(Σσᵢ²)/n.
#[test]
fn repeated_measurements_are_averaged() -> Result<()> {
    let file = read_measurements(&browser_with("dF", "28.0+/-0.01, 28.1+/-0.02"))?;
    let d_f = file.measurements.d_f;
    assert!((d_f.value - 28.05).abs() < 1e-12);
    assert!((d_f.sigma - (0.0001f64 + 0.0004).sqrt() / 2.0).abs() < 1e-15);
    Ok(())
}

/// The principal moments and angle rebuild the tensor they came from, and the moments are the
/// eigenvalues of the 2 × 2 tensor (trace and determinant kept).
#[test]
fn principal_axes_rebuild_the_tensor() -> Result<()> {
    let file = read_measurements(BROWSER)?;
    let p = MeasuredParameters::new(&file.measurements)?.benchmark;
    for (ixx, ixz, izz) in [
        (p.i_bxx, p.i_bxz, p.i_bzz),
        (p.i_hxx, p.i_hxz, p.i_hzz),
        (1.0, 0.0, 2.0),
        (2.0, 0.3, 2.0),
    ] {
        let (i1, i2, theta) = steps::principal_planar(ixx, ixz, izz);
        let (s, c) = theta.sin_cos();
        assert!(i1 >= i2);
        assert!((i1 * c * c + i2 * s * s - ixx).abs() < 1e-14);
        assert!((i1 * s * s + i2 * c * c - izz).abs() < 1e-14);
        assert!(((i2 - i1) * s * c - ixz).abs() < 1e-14);
        assert!((i1 * i2 - (ixx * izz - ixz * ixz)).abs() < 1e-14);
    }
    Ok(())
}

/// The report's steps are the pipeline's numbers: each benchmark step equals the parameter
/// and its σ; a bicycle measured exactly has hanging lines meeting in one point (residual 0)
/// and its torsion constant from the rod's closed form.
#[test]
fn report_steps_are_the_pipeline() -> Result<()> {
    let file = read_measurements(BROWSER)?;
    let result = MeasuredParameters::new(&file.measurements)?;
    let bicycle = result.bicycle();
    let values = result.benchmark.to_array();
    let mut seen = 0;
    for step in result.steps.iter().filter(|s| s.benchmark) {
        let i = BENCHMARK_TABLE
            .iter()
            .position(|p| p.key == step.key)
            .unwrap();
        assert_eq!(step.value, values[i], "{}", step.key);
        let sigma = step.sigma.unwrap();
        assert!(
            (sigma - bicycle.sigma_of(&step.key)).abs() <= 1e-14 * sigma.max(1e-300),
            "{}",
            step.key
        );
        seen += 1;
    }
    assert_eq!(seen, BENCHMARK_TABLE.len());
    let step = |key: &str| result.steps.iter().find(|s| s.key == key).unwrap();
    assert_eq!(step("rR").inputs, ["dR", "nR"]);
    assert_eq!(step("k").inputs, ["mP", "lP", "dP", "TtP1"]);
    assert!(step("residualB").value > 0.0 && step("residualB").sigma.is_none());

    let exact = MeasuredParameters::new(&measured_exactly(&BenchmarkParameters::meijaard2007()))?;
    let exact_step = |key: &str| exact.steps.iter().find(|s| s.key == key).unwrap().value;
    assert!(exact_step("residualB") < 1e-12 && exact_step("residualH") < 1e-12);
    let rod: f64 = 5.56 / 12.0 * (3.0 * 0.015 * 0.015 + 1.05 * 1.05);
    let k = rod * (2.0 * PI / 1.894).powi(2);
    assert!((exact_step("k") - k).abs() < 1e-14 * k);
    Ok(())
}

/// The largest correlations come sorted by |ρ|, each pair once, within [−1, 1], and agree
/// with `correlation`.
#[test]
fn largest_correlations_are_sorted() -> Result<()> {
    let result = MeasuredParameters::new(&read_measurements(BROWSER)?.measurements)?;
    let all = result.largest_correlations(usize::MAX);
    let with_sigma = result.sigma.len();
    assert_eq!(all.len(), with_sigma * (with_sigma - 1) / 2);
    for pair in all.windows(2) {
        assert!(pair[0].rho.abs() >= pair[1].rho.abs());
    }
    for c in &all {
        assert!(c.rho.abs() <= 1.0 && c.a != c.b);
        assert!((result.correlation(c.a, c.b).unwrap() - c.rho).abs() < 1e-12);
    }
    Ok(())
}
