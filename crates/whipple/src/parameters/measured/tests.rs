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
                let intercept = z + crate::math::tan(beta) * x;
                let a = match frame {
                    HungFrame::Rear => -crate::math::cos(beta) * (intercept + p.r_r),
                    HungFrame::Front => {
                        -crate::math::cos(beta) * (intercept + p.r_f - p.w * crate::math::tan(beta))
                    }
                };
                let (s, c) = crate::math::sin_cos(beta);
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
        geometry: Geometry::Direct {
            w: exact(p.w),
            gamma: exact(90.0 - p.lambda * 180.0 / PI),
            f: exact(p.r_f * crate::math::sin(p.lambda) - p.c * crate::math::cos(p.lambda)),
        },
        m_r: exact(p.m_r),
        m_f: exact(p.m_f),
        m_b: exact(p.m_b),
        l_r: exact(lr),
        l_f: exact(lf),
        t_c_r: exact(compound(p.m_r, lr, p.i_ryy)),
        t_c_f: exact(compound(p.m_f, lf, p.i_fyy)),
        t_c_b: exact(compound(p.m_b, l_b, p.i_byy)),
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
        front_frame: FrontFrame::Whole(HungPart {
            mass: exact(p.m_h),
            compound_period: exact(compound(p.m_h, l_h, p.i_hyy)),
            hangings: hangings(
                HungFrame::Front,
                [346.7, 28.1, 287.0],
                p.x_h,
                p.z_h,
                [p.i_hxx, p.i_hxz, p.i_hzz],
            ),
        }),
        flywheel: None,
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
    let c: f64 = steps::trail(
        0.35,
        lambda,
        0.35 * crate::math::sin(lambda) - 0.08 * crate::math::cos(lambda),
    );
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
    assert!(
        message.contains("`h1`")
            && message.contains("line 52")
            && message.contains("the geometry is given twice"),
        "{message}"
    );
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
        let (s, c) = crate::math::sin_cos(theta);
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

const RIGID: &str = include_str!("../../../tests/data/measured/RigidMeasured.txt");
const GYRO: &str = include_str!("../../../tests/data/measured/GyroMeasured.txt");
const BALANCEASSIST: &str =
    include_str!("../../../tests/data/measured/Balanceassistv1Measured.txt");

/// `text` with `key`'s line replaced (or the line removed when `value` is `None`).
fn with(text: &str, key: &str, value: Option<&str>) -> String {
    text.lines()
        .filter_map(|l| {
            if l.split('=').next().map(str::trim) == Some(key) {
                value.map(|v| format!("{key} = {v}"))
            } else {
                Some(l.to_string())
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The perpendicular distances of a bicycle of known geometry: a = (w + c) cos λ − r_R sin λ,
/// b = r_F sin λ − c cos λ (the hubs' distances from the steer axis, which meets the ground
/// w + c ahead of the rear contact), and the span along the axis
/// w sin λ + (r_R − r_F) cos λ, written as h1 = a, h4 = b, d1…d4 = 0 and d the hubs'
/// distance √(span² + (a − b)²). The steps must give λ, w and c back.
#[test]
fn offsets_give_the_geometry_back() -> Result<()> {
    let p = BenchmarkParameters::meijaard2007();
    let (s, co) = crate::math::sin_cos(p.lambda);
    let a = (p.w + p.c) * co - p.r_r * s;
    let b = p.r_f * s - p.c * co;
    let span = p.w * s + (p.r_r - p.r_f) * co;
    let d = (span * span + (a - b) * (a - b)).sqrt();
    let (a2, b2, span2) = steps::steer_axis_offsets([a, 0.0, 0.0, b, 0.0], 0.0, 0.0, 0.0, 0.0, d);
    assert!((a2 - a).abs() < 1e-15 && (b2 - b).abs() < 1e-15);
    assert!((span2 - span).abs() < 1e-14, "{span2} vs {span}");
    let lambda = steps::steer_axis_tilt_from_offsets(p.r_f, p.r_r, a, b, span, "h1")?;
    assert!(
        (lambda - p.lambda).abs() < 1e-14,
        "{lambda} vs {}",
        p.lambda
    );
    let w = steps::wheelbase_from_offsets(a, b, span, lambda);
    assert!((w - p.w).abs() < 1e-14, "{w} vs {}", p.w);
    assert!((steps::trail(p.r_f, lambda, b) - p.c).abs() < 1e-14);
    // The whole file's form: Browser with its w, gamma, f replaced by these distances.
    let mut text: String = BROWSER
        .lines()
        .filter(|l| {
            !matches!(
                l.split('=').next().map(str::trim),
                Some("w" | "gamma" | "f")
            )
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let direct = MeasuredParameters::new(&read_measurements(BROWSER)?.measurements)?.benchmark;
    let (s, co) = crate::math::sin_cos(direct.lambda);
    let a = (direct.w + direct.c) * co - direct.r_r * s;
    let b = direct.r_f * s - direct.c * co;
    let span = direct.w * s + (direct.r_r - direct.r_f) * co;
    let d = (span * span + (a - b) * (a - b)).sqrt();
    for (key, value) in [
        ("h1", a),
        ("h2", 0.0),
        ("h3", 0.0),
        ("h4", b),
        ("h5", 0.0),
        ("d1", 0.0),
        ("d2", 0.0),
        ("d3", 0.0),
        ("d4", 0.0),
        ("d", d),
    ] {
        text.push_str(&format!("{key} = {value:.17e}+/-0.0001\n"));
    }
    let offsets = MeasuredParameters::new(&read_measurements(&text)?.measurements)?;
    for (key, want, got) in [
        ("lam", direct.lambda, offsets.benchmark.lambda),
        ("w", direct.w, offsets.benchmark.w),
        ("c", direct.c, offsets.benchmark.c),
        ("xH", direct.x_h, offsets.benchmark.x_h),
        ("IHxx", direct.i_hxx, offsets.benchmark.i_hxx),
    ] {
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "{key}: {got} vs {want}"
        );
    }
    Ok(())
}

/// λ's derivative through Newton's method is the implicit one: F(λ) = sin λ −
/// (rF − rR + c cos λ)/(a + b) = 0 gives ∂λ/∂d = −F_c ∂c/∂d / F_λ with F_c = −cos λ/(a + b),
/// F_λ = cos λ + c sin λ/(a + b) and ∂c/∂d = (d + (d2 + d3)/2)/c.
#[test]
fn tilt_from_offsets_has_the_implicit_derivative() -> Result<()> {
    let file = read_measurements(BALANCEASSIST)?;
    let result = MeasuredParameters::new(&file.measurements)?;
    let step = |key: &str| result.steps.iter().find(|s| s.key == key).unwrap().value;
    let (a, b, span, lambda) = (step("a"), step("b"), step("cAxis"), step("lam"));
    let Geometry::Offsets(o) = &file.measurements.geometry else {
        panic!("Balanceassistv1 measures its geometry as perpendicular distances")
    };
    let hubs = o.d.value + 0.5 * (o.d2.value + o.d3.value);
    let f_lambda = crate::math::cos(lambda) + span * crate::math::sin(lambda) / (a + b);
    let f_span = -crate::math::cos(lambda) / (a + b);
    let want = -f_span * (hubs / span) / f_lambda;
    let row = BENCHMARK_TABLE.iter().position(|p| p.key == "lam").unwrap();
    let col = result.inputs.iter().position(|k| k == "d").unwrap();
    let got = result.jacobian[(row, col)];
    assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
    Ok(())
}

/// A fork and a handlebar "measured" exactly, each hung from its own reference point, come
/// back to 1e-12, and the front frame is their parallel-axis combination.
#[test]
fn split_fork_round_trips() -> Result<()> {
    let p = BenchmarkParameters::meijaard2007();
    let mut m = measured_exactly(&p);
    // fork S and handlebar G: two bodies in the plane, the handlebar's reference circle at
    // (l1, l2) = (0.05, 0.4) from the front hub across and along the steer axis.
    let (h6, h7, d5, d6) = (0.3, 0.35, 0.01, 0.02);
    let l1: f64 = h7 - h6 + d5 / 2.0 - d6 / 2.0;
    let l2: f64 = 0.4;
    let l = (l1 * l1 + l2 * l2).sqrt() + d5 / 2.0 + d6 / 2.0;
    let (u1, u2) = steps::handlebar_reference_offset(p.lambda, l1, l2);
    let fork = (1.5, 0.95, -0.55, [0.08, -0.02, 0.03], 0.09);
    let bar = (2.5, 0.80, -1.05, [0.05, 0.01, 0.06], 0.02);
    let (m_p, l_p, d_p, t_p) = (5.56, 1.05, 0.03, 1.894);
    let rod = m_p / 12.0 * (3.0 * (d_p / 2.0) * (d_p / 2.0) + l_p * l_p);
    let k = 4.0 * PI * PI * rod / (t_p * t_p);
    let part = |(mass, x, z, i, iyy): (f64, f64, f64, [f64; 3], f64),
                reference: (f64, f64),
                alphas: [f64; 3]| {
        let hangings = alphas
            .iter()
            .map(|alpha| {
                let beta = p.lambda - alpha * PI / 180.0;
                let z0 = z + crate::math::tan(beta) * x;
                let a = crate::math::cos(beta)
                    * (reference.1 + reference.0 * crate::math::tan(beta) - z0);
                let (s, c) = crate::math::sin_cos(beta);
                let j = i[0] * c * c - 2.0 * i[1] * s * c + i[2] * s * s;
                Hanging {
                    alpha: exact(*alpha),
                    a: exact(a),
                    period: exact(2.0 * PI * (j / k).sqrt()),
                }
            })
            .collect();
        let length = ((x - reference.0).powi(2) + (z - reference.1).powi(2)).sqrt();
        let period = 2.0 * PI * ((iyy + mass * length * length) / (mass * p.g * length)).sqrt();
        HungPart {
            mass: exact(mass),
            compound_period: exact(period),
            hangings,
        }
    };
    m.front_frame = FrontFrame::Split {
        fork: part(fork, (p.w, -p.r_f), [346.7, 28.1, 287.0]),
        handlebar: part(bar, (p.w - u1, -p.r_f - u2), [57.3, 224.4, 332.3]),
        reference: HandlebarReference {
            h6: exact(h6),
            h7: exact(h7),
            d5: exact(d5),
            d6: exact(d6),
            l: exact(l),
        },
    };
    let back = MeasuredParameters::new(&m)?;
    let extra = |key: &str| {
        back.bicycle()
            .extras
            .iter()
            .find(|e| e.key == key)
            .unwrap()
            .value
            .unwrap()
    };
    for (key, want) in [
        ("mS", fork.0),
        ("xS", fork.1),
        ("zS", fork.2),
        ("ISxx", fork.3[0]),
        ("ISxz", fork.3[1]),
        ("ISzz", fork.3[2]),
        ("ISyy", fork.4),
        ("mG", bar.0),
        ("xG", bar.1),
        ("zG", bar.2),
        ("IGxx", bar.3[0]),
        ("IGxz", bar.3[1]),
        ("IGzz", bar.3[2]),
        ("IGyy", bar.4),
    ] {
        let got = extra(key);
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "{key}: {got} vs {want}"
        );
    }
    // The combination by hand: masses added, centre the weighted mean, parallel axes.
    let mh = fork.0 + bar.0;
    let xh = (fork.0 * fork.1 + bar.0 * bar.1) / mh;
    let zh = (fork.0 * fork.2 + bar.0 * bar.2) / mh;
    let shift = |(mass, x, z, i, iyy): (f64, f64, f64, [f64; 3], f64)| {
        let (dx, dz) = (x - xh, z - zh);
        [
            i[0] + mass * dz * dz,
            i[1] - mass * dx * dz,
            i[2] + mass * dx * dx,
            iyy + mass * (dx * dx + dz * dz),
        ]
    };
    let (sf, sb) = (shift(fork), shift(bar));
    let h = back.benchmark;
    for (key, want, got) in [
        ("mH", mh, h.m_h),
        ("xH", xh, h.x_h),
        ("zH", zh, h.z_h),
        ("IHxx", sf[0] + sb[0], h.i_hxx),
        ("IHxz", sf[1] + sb[1], h.i_hxz),
        ("IHzz", sf[2] + sb[2], h.i_hzz),
        ("IHyy", sf[3] + sb[3], h.i_hyy),
    ] {
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "{key}: {got} vs {want}"
        );
    }
    Ok(())
}

/// The flywheel's quantities are the wheel-with-flywheel's less the wheel's, kept as extras.
#[test]
fn flywheel_is_the_difference_kept_as_extras() -> Result<()> {
    let file = read_measurements(GYRO)?;
    let result = MeasuredParameters::new(&file.measurements)?;
    let v = file.measurements.values();
    let d = v.flywheel.unwrap();
    let bicycle = result.bicycle();
    let extra = |key: &str| bicycle.extras.iter().find(|e| e.key == key).unwrap();
    assert_eq!(extra("mD").value, Some(d.mass - v.m_f));
    let both = steps::compound_pendulum_inertia(d.mass, v.g, v.l_f, d.compound_period);
    let want = both - result.benchmark.i_fyy;
    let got = extra("IDyy").value.unwrap();
    assert!((got - want).abs() <= 1e-14 * want.abs(), "{got} vs {want}");
    // σ of mD: √(σ_mD² + σ_mF²).
    let sigma = extra("mD").sigma.unwrap();
    assert!(
        (sigma - (0.01f64.powi(2) * 2.0).sqrt()).abs() < 1e-15,
        "{sigma}"
    );
    Ok(())
}

/// Perpendicular distances that give no steer axis, handlebar references out of reach, and
/// forms given twice or half: each refused naming the key and its line.
#[test]
fn bad_offsets_and_parts_name_key_and_line() {
    let message = |text: &str| error_of(text).to_string();
    // The hubs 0.05 m apart cannot be joined by an axis with offsets differing by ~0.9 m.
    let e = message(&with(BALANCEASSIST, "d", Some("0.05+/-0.005")));
    assert!(e.contains("line 13") && e.contains("steer axis"), "{e}");
    let e = error_of(&with(BALANCEASSIST, "d", Some("0.05+/-0.005")));
    assert!(
        matches!(&e, Error::InvalidParameter { field, .. } if field == "d"),
        "{e}"
    );
    // Offsets adding up to a negative distance.
    let e = error_of(&with(BALANCEASSIST, "h1", Some("-1.5+/-0.001")));
    assert!(
        matches!(&e, Error::InvalidParameter { field, rule, .. }
        if field == "h1" && rule.contains("line 22") && rule.contains("positive")),
        "{e}"
    );
    // The handlebar's reference circle farther across the axis than the centres' distance.
    let e = error_of(&with(RIGID, "l", Some("0.02+/-0.002")));
    assert!(
        matches!(&e, Error::InvalidParameter { field, rule, .. }
        if field == "l" && rule.contains("line 19")),
        "{e}"
    );
    // Both geometries.
    let e = message(&format!("{BROWSER}\nd = 1.0"));
    assert!(
        e.contains("the geometry is given twice") && e.contains("line 52"),
        "{e}"
    );
    // Both front frames.
    let e = message(&format!("{RIGID}\nmH = 5.4"));
    assert!(e.contains("the front frame is given twice"), "{e}");
    // Half a split fork, half a flywheel, half the offsets.
    let e = message(&with(RIGID, "TcG1", None));
    assert!(
        e.contains("TcG1 is missing: the handlebar's IGyy needs it"),
        "{e}"
    );
    let e = message(&with(GYRO, "TtD1", None));
    assert!(e.contains("TtD1 is missing: the flywheel's IDxx"), "{e}");
    let e = message(&with(GYRO, "h3", None));
    assert!(
        e.contains("h3 is missing") && e.contains("perpendicular distances"),
        "{e}"
    );
    let e = message(&with(RIGID, "alphaG2", None));
    assert!(
        e.contains("alphaG2 is missing: the handlebar's hanging 2 needs it"),
        "{e}"
    );
    // A distance alone is no hanging (Gyro's aB4): kept with the other keys.
    let file = read_measurements(GYRO).unwrap();
    assert_eq!(file.measurements.rear_frame.len(), 3);
    assert!(
        file.other
            .iter()
            .any(|(k, m)| k == "aB4" && m.value == 0.192)
    );
}
