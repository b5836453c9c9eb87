//! The rider seated on the measured bicycle (BicycleParameters' `add_rider`): identities that
//! need no other tool — the feet on the bottom bracket and the hands on the grips, `LhbF` and
//! `LhbR` from the hubs as measured, the two sides mirror images, the combination's mass and
//! moments, the σ's derivatives against a solve at shifted measurements — and the messages of
//! bad input. BicycleParameters itself is compared in crates/whipple-py/tests/test_add_rider.py.

use nalgebra::{Matrix3, Vector3};
use whipple::Error;
use whipple::advanced::measured::{Geometry, MeasuredFile, MeasuredParameters, read_measurements};
use whipple::advanced::rider::{
    MEASUREMENT_NAMES, RiderGeometry, SeatedRider, YeadonConfiguration, YeadonMeasurements,
    read_yeadon_configuration, read_yeadon_measurements,
};

fn measured(name: &str) -> MeasuredFile {
    let text = std::fs::read_to_string(format!(
        "{}/tests/data/measured/{name}Measured.txt",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("raw file");
    read_measurements(&text).expect("reads")
}

fn yeadon(name: &str) -> String {
    std::fs::read_to_string(format!(
        "{}/tests/data/yeadon/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("rider file")
}

fn jason() -> YeadonMeasurements<f64> {
    read_yeadon_measurements(&yeadon("JasonYeadonMeas.txt")).expect("reads")
}

fn configuration(bike: &str) -> YeadonConfiguration<f64> {
    read_yeadon_configuration(&yeadon(&format!("Jason{bike}YeadonCFG.txt"))).expect("reads")
}

fn other(file: &MeasuredFile, key: &str) -> f64 {
    file.other
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, m)| m.value)
        .expect("key")
}

fn with_jason(file: &MeasuredFile, bike: &str) -> MeasuredParameters {
    MeasuredParameters::with_rider(file, &jason(), &configuration(bike)).expect("seats")
}

/// A measurement averaged left and right, as the body is built.
fn length(m: &YeadonMeasurements<f64>, left: &str) -> f64 {
    let right = left.replace("La", "Lb").replace("Lj", "Lk");
    let at = |n: &str| MEASUREMENT_NAMES.iter().position(|x| *x == n).unwrap();
    0.5 * (m.values[at(left)] + m.values[at(&right)])
}

/// Yeadon's axes (x left, y back, z up; origin the seat) to the benchmark's.
fn to_benchmark(seated: &SeatedRider<f64>, p: Vector3<f64>) -> Vector3<f64> {
    Vector3::new(seated.seat[0] - p.y, -p.x, seated.seat[1] - p.z)
}

#[test]
fn feet_and_hands_reach_what_the_bicycle_measures() {
    for bike in ["Browser", "Browserins"] {
        let file = measured(bike);
        let result = with_jason(&file, bike);
        let seated = result.rider.as_ref().expect("a rider");
        assert!(
            seated.solve.residual < 1e-13,
            "{bike}: {}",
            seated.solve.residual
        );
        assert!(
            seated.solve.iterations <= 20,
            "{bike}: {}",
            seated.solve.iterations
        );
        let m = jason();
        let bench = MeasuredParameters::new(&file.measurements)
            .unwrap()
            .benchmark;
        let segment = |n: &str| seated.body.segments.iter().find(|s| s.name == n).unwrap();
        for (hand, foot, sign) in [("A2", "J2", 1.0), ("B2", "K2", -1.0)] {
            let (a2, j2) = (segment(hand), segment(foot));
            let along = |s: &whipple::advanced::rider::YeadonSegment<f64>, l: f64| {
                s.origin + s.orientation * Vector3::new(0.0, 0.0, -l)
            };
            let hand_point = to_benchmark(
                seated,
                along(
                    a2,
                    length(&m, "La4L") - length(&m, "La2L") + length(&m, "La5L"),
                ),
            );
            let foot_point = to_benchmark(
                seated,
                along(
                    j2,
                    length(&m, "Lj5L") - length(&m, "Lj3L") + length(&m, "Lj6L"),
                ),
            );
            // Each hand LhbF from the front hub and LhbR from the rear one, whb/2 off the plane.
            let front = Vector3::new(bench.w, 0.0, -bench.r_f);
            let rear = Vector3::new(0.0, 0.0, -bench.r_r);
            assert!(((hand_point - front).norm() - other(&file, "LhbF")).abs() < 1e-12);
            assert!(((hand_point - rear).norm() - other(&file, "LhbR")).abs() < 1e-12);
            assert!((hand_point.y + sign * other(&file, "whb") / 2.0).abs() < 1e-12);
            // The foot on the bottom bracket in the side view: hbb high, lcs from the rear hub.
            assert!((foot_point.z + other(&file, "hbb")).abs() < 1e-12, "{bike}");
            let chain_stay = ((foot_point.x).powi(2) + (foot_point.z + bench.r_r).powi(2)).sqrt();
            assert!((chain_stay - other(&file, "lcs")).abs() < 1e-12, "{bike}");
        }
        // The seat lst + lsp up the seat tube from the bottom bracket.
        let tube = ((seated.seat[0] - seated.bottom_bracket[0]).powi(2)
            + (seated.seat[1] - seated.bottom_bracket[1]).powi(2))
        .sqrt();
        assert!((tube - other(&file, "lst") - other(&file, "lsp")).abs() < 1e-12);
        // Mirror images: the rider's centre on the plane, no products with y.
        let r = &seated.rider;
        assert!(
            r.center_of_mass.y.abs() < 1e-12,
            "{bike}: {}",
            r.center_of_mass.y
        );
        assert!(r.inertia[(0, 1)].abs() < 1e-12 && r.inertia[(1, 2)].abs() < 1e-12);
        assert!((r.inertia - r.inertia.transpose()).amax() < 1e-14 * r.inertia.amax());
    }
}

/// The rear frame with the rider: masses add, the mass centre is their mean, and the inertia
/// about it is each body's moved there (full 3-D parallel-axis theorem, computed here).
#[test]
fn the_rear_frame_and_the_rider_combine() {
    let file = measured("Browser");
    let alone = MeasuredParameters::new(&file.measurements)
        .unwrap()
        .benchmark;
    let result = with_jason(&file, "Browser");
    let b = result.benchmark;
    let r = &result.rider.as_ref().unwrap().rider;
    assert!((b.m_b - alone.m_b - r.mass).abs() < 1e-12);
    let frame_c = Vector3::new(alone.x_b, 0.0, alone.z_b);
    let c = (frame_c * alone.m_b + r.center_of_mass * r.mass) / (alone.m_b + r.mass);
    assert!((b.x_b - c.x).abs() < 1e-14 && (b.z_b - c.z).abs() < 1e-14);
    let shift = |m: f64, d: Vector3<f64>| (Matrix3::identity() * d.dot(&d) - d * d.transpose()) * m;
    let frame_i = Matrix3::new(
        alone.i_bxx,
        0.0,
        alone.i_bxz,
        0.0,
        alone.i_byy,
        0.0,
        alone.i_bxz,
        0.0,
        alone.i_bzz,
    );
    let total =
        frame_i + shift(alone.m_b, frame_c - c) + r.inertia + shift(r.mass, r.center_of_mass - c);
    for (got, want) in [
        (b.i_bxx, total[(0, 0)]),
        (b.i_byy, total[(1, 1)]),
        (b.i_bzz, total[(2, 2)]),
        (b.i_bxz, total[(0, 2)]),
    ] {
        assert!(
            (got - want).abs() < 1e-12 * want.abs().max(1.0),
            "{got} vs {want}"
        );
    }
    // Everything else as the bicycle alone.
    assert_eq!(b.w, alone.w);
    assert_eq!(b.i_hxx, alone.i_hxx);
    assert_eq!(b.r_f, alone.r_f);
    // The report: the frame alone renamed, the combined values are the parameters.
    let step = |k: &str| result.steps.iter().find(|s| s.key == k).unwrap();
    assert_eq!(step("mB_frame").value, alone.m_b);
    assert!(!step("mB_frame").benchmark && step("mB").benchmark);
    assert_eq!(step("xB").value, b.x_b);
    assert_eq!(step("mRider").value, r.mass);
}

/// σ: the Jacobian's columns of w and rR (through dR) against the same pipeline at shifted
/// measurements (central differences, an independent check of the implicit derivative of the
/// joint angles; agreement to the differences' own error).
#[test]
fn derivatives_through_the_seated_rider() {
    let file = measured("Browser");
    let result = with_jason(&file, "Browser");
    let x_b = whipple::advanced::table::parameters(whipple::advanced::table::Form::Benchmark)
        .iter()
        .position(|p| p.key == "xB")
        .unwrap();
    for (input, h) in [("w", 1e-6), ("dR", 1e-5), ("lsp", 1e-6)] {
        let j = result.inputs.iter().position(|k| k == input).unwrap();
        let shifted = |d: f64| {
            let mut f = file.clone();
            if input == "w" {
                let Geometry::Direct { w, .. } = &mut f.measurements.geometry else {
                    panic!("Browser's geometry is measured directly");
                };
                w.value += d;
            } else if input == "dR" {
                f.measurements.d_r.value += d;
            } else {
                f.other
                    .iter_mut()
                    .find(|(k, _)| k == input)
                    .unwrap()
                    .1
                    .value += d;
            }
            with_jason(&f, "Browser").benchmark.x_b
        };
        let difference = (shifted(h) - shifted(-h)) / (2.0 * h);
        let exact = result.jacobian[(x_b, j)];
        assert!(
            (difference - exact).abs() < 1e-6 * exact.abs().max(1e-3),
            "∂xB/∂{input}: {exact} vs {difference}"
        );
    }
    // Browser's seat keys have no σ: the rider's place carries rR's, rF's and w's.
    assert!(result.sigma["xB"] > 0.0 && result.sigma["IBxx"] > 0.0);
}

#[test]
fn a_rider_who_cannot_reach_is_refused_naming_what() {
    // Jason on Stratos: the grips are 0.6388 m from his shoulder, his arms 0.6130 m long
    // (BicycleParameters' fsolve stops there without converging, its residual 8 mm).
    let error =
        MeasuredParameters::with_rider(&measured("Stratos"), &jason(), &configuration("Stratos"))
            .unwrap_err();
    assert_eq!(
        error.to_string(),
        "invalid bicycle (La2L, La4L, La5L, LhbF, LhbR, whb, somersault): the rider cannot reach \
         the handlebar: it is 0.6388 m from the shoulder, and the rider's arms (La4L + La5L, \
         shoulder to the middle of the hand) reach 0.6130 m; a handlebar nearer the seat, or a \
         rider leaning further forward (somersault)"
    );

    let mut file = measured("Browser");
    for (k, m) in file.other.iter_mut() {
        if k == "LhbF" || k == "LhbR" {
            m.value += 1.0;
        }
    }
    let error =
        MeasuredParameters::with_rider(&file, &jason(), &configuration("Browser")).unwrap_err();
    let Error::InvalidBicycle { fields, rule } = &error else {
        panic!("{error:?}");
    };
    assert_eq!(fields, "La2L, La4L, La5L, LhbF, LhbR, whb, somersault");
    assert!(
        rule.starts_with("the rider cannot reach the handlebar: it is ")
            && rule.contains("from the shoulder, and the rider's arms (La4L + La5L"),
        "{rule}"
    );

    let mut file = measured("Browser");
    for (k, m) in file.other.iter_mut() {
        if k == "lsp" {
            m.value = 0.9;
        }
    }
    let error =
        MeasuredParameters::with_rider(&file, &jason(), &configuration("Browser")).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("the rider cannot reach the bottom bracket"),
        "{error}"
    );

    let mut file = measured("Browser");
    file.other.retain(|(k, _)| k != "whb");
    let error =
        MeasuredParameters::with_rider(&file, &jason(), &configuration("Browser")).unwrap_err();
    assert_eq!(
        error.to_string(),
        "BicycleParameters Measured .txt file, `whb`: whb is missing: seating a rider needs the \
         handlebar width, between the grips"
    );
}

#[test]
fn a_configuration_without_an_angle_is_refused_naming_it() {
    let text = yeadon("JasonBrowserYeadonCFG.txt");
    let without: String = text
        .lines()
        .filter(|l| !l.starts_with("somersault"))
        .map(|l| format!("{l}\n"))
        .collect();
    let error = read_yeadon_configuration(&without).unwrap_err();
    assert_eq!(
        error.to_string(),
        "Yeadon configuration .txt file, `somersault`: 1 of the 21 angles missing: somersault"
    );
    let bad = text.replace("twist: 0.0", "twist: zero");
    let error = read_yeadon_configuration(&bad).unwrap_err();
    assert!(error.to_string().contains("line 6"), "{error}");
}

/// The whole step on f64 (`rider_on_bicycle`) is the measured pipeline's f64 pass.
#[test]
fn rider_on_bicycle_is_the_pipeline_s_value() {
    let file = measured("Browser");
    let result = with_jason(&file, "Browser");
    let alone = MeasuredParameters::new(&file.measurements)
        .unwrap()
        .benchmark;
    let g = RiderGeometry::from_array(
        ["lcs", "hbb", "lsp", "lst", "lamst", "whb", "LhbF", "LhbR"].map(|k| other(&file, k)),
    );
    let (seated, combined) =
        whipple::advanced::rider::rider_on_bicycle(&alone, &g, &jason(), &configuration("Browser"))
            .unwrap();
    assert_eq!(combined, result.benchmark);
    assert_eq!(&seated, result.rider.as_ref().unwrap());
}
