//! The leaning rider's parameters against BicycleParameters' linearized rider-lean model
//! (`MooreRiderLean2012Model`, generated from Moore's dissertation source), whose A(v) and B
//! for `mooreriderlean2012_browser_jason` are stored in `data/rider_lean_references.json` by
//! `bench/rider_lean_references.py` (BicycleParameters 1.5.2, BSD-2-Clause).
//!
//! Moore's linear model is M q̈ + v C₁ q̇ + (g K₀ + v² K₂) q = [T4, T7, T9] in q = [φ, δ, φ_r]
//! (roll q4, steer q7, lean q9), plus the hinge's c9 q̇₉ and k9 q₉. Its B rows of u4, u7, u9 are
//! M⁻¹ (the torques are the generalized forces of q4, q7, q9 exactly), so M = B⁻¹ and, at each
//! speed, −M A gives g K₀ + v² K₂ (the q columns) and v C₁ (the u columns).
//!
//! Locking the hinge (φ_r ≡ 0) leaves the (φ, δ) rows and columns of those matrices: the
//! hinge's torque does no work in φ or δ. So the (φ, δ) blocks must be the benchmark model
//! of the rigid rider, [`RiderLeanParameters::rigid`] (G combined into B) — which checks our
//! conversion of Moore's keys, the upper body's place and tensor and the combination against
//! an independent implementation, to 1e-10. The entries of M and K₀ that couple φ_r are
//! checked against their closed forms (derived below), which pins the hinge height and the sign
//! of IGxz; those of C₁ and K₂ wait for the five-body model's linearization.

use nalgebra::{Matrix3, SMatrix};
use whipple::Canonical;
use whipple::advanced::nonlinear::LeanModel;
use whipple::advanced::parameters::{
    MOORE_RIDER_LEAN2012_KEYS, MooreRiderLean2012Parameters, RiderLeanParameters,
};

const DATA: &str = include_str!("data/rider_lean_references.json");

/// Indices of Moore's states q4, q7, q9 and u4, u7, u9 in BicycleParameters' order.
const Q: [usize; 3] = [3, 5, 7];
const U: [usize; 3] = [8, 10, 11];

struct Speed {
    v: f64,
    a: SMatrix<f64, 12, 12>,
    b: SMatrix<f64, 12, 3>,
}

fn matrix<const R: usize, const C: usize>(value: &serde_json::Value) -> SMatrix<f64, R, C> {
    let rows = value.as_array().expect("rows");
    assert_eq!(rows.len(), R);
    SMatrix::from_fn(|i, j| {
        let row = rows[i].as_array().expect("a row");
        assert_eq!(row.len(), C);
        row[j].as_f64().expect("a number")
    })
}

/// The free hinge's matrices at every stored speed.
fn free_hinge() -> (serde_json::Value, Vec<Speed>) {
    stored_case(0, "free hinge")
}

/// One stored case's matrices at every stored speed.
fn stored_case(index: usize, name: &str) -> (serde_json::Value, Vec<Speed>) {
    let doc: serde_json::Value = serde_json::from_str(DATA).expect("valid JSON");
    let case = &doc["cases"][index];
    assert_eq!(case["name"], name);
    let speeds = case["speeds"]
        .as_array()
        .expect("speeds")
        .iter()
        .map(|s| Speed {
            v: s["v"].as_f64().expect("v"),
            a: matrix(&s["A"]),
            b: matrix(&s["B"]),
        })
        .collect();
    (doc, speeds)
}

fn block<const C: usize>(
    m: &SMatrix<f64, 12, C>,
    rows: [usize; 3],
    cols: [usize; 3],
) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| m[(rows[i], cols[j])])
}

/// M, g K₀ + v² K₂ and v C₁ of Moore's model at one speed.
fn second_order(s: &Speed) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) {
    let b = block(&s.b, U, [0, 1, 2]);
    let m = b.try_inverse().expect("B's lower block is invertible");
    let stiffness = -(m * block(&s.a, U, Q));
    let damping = -(m * block(&s.a, U, U));
    (m, stiffness, damping)
}

fn assert_close(what: &str, ours: f64, theirs: f64, scale: f64) {
    assert!(
        (ours - theirs).abs() <= 1e-10 * scale,
        "{what}: ours {ours} vs BicycleParameters {theirs} (scale {scale})"
    );
}

/// The stored parameter set is ours, key for key.
#[test]
fn the_stored_set_is_browser_jason() {
    let (doc, _) = free_hinge();
    let ours = MooreRiderLean2012Parameters::browser_jason().to_array();
    let theirs = doc["parameters"].as_object().expect("parameters");
    assert_eq!(theirs.len(), MOORE_RIDER_LEAN2012_KEYS.len());
    for (key, x) in MOORE_RIDER_LEAN2012_KEYS.iter().zip(ours) {
        let y = theirs[*key].as_f64().expect("a number");
        assert!((x - y).abs() <= 1e-15 * y.abs(), "{key}: {x} vs {y}");
    }
}

/// The hinge locked: Moore's M, C₁, K₀, K₂ restricted to (φ, δ) are the benchmark model of the
/// rigid rider, at every stored speed.
#[test]
fn locked_hinge_is_the_rigid_rider() {
    let (_, speeds) = free_hinge();
    let rigid = Canonical::new(&RiderLeanParameters::browser_jason().rigid()).unwrap();
    let scale_m = rigid.m.amax();
    for s in &speeds {
        let (m, stiffness, damping) = second_order(s);
        let expected_k = rigid.k0 * rigid.g + rigid.k2 * (s.v * s.v);
        let expected_c = rigid.c1 * s.v;
        for i in 0..2 {
            for j in 0..2 {
                let at = |what: &str| format!("{what}[{i}{j}] at {} m/s", s.v);
                assert_close(&at("M"), rigid.m[(i, j)], m[(i, j)], scale_m);
                assert_close(
                    &at("gK0 + v²K2"),
                    expected_k[(i, j)],
                    stiffness[(i, j)],
                    expected_k.amax(),
                );
                assert_close(
                    &at("vC1"),
                    expected_c[(i, j)],
                    damping[(i, j)],
                    expected_c.amax(),
                );
            }
        }
    }
}

/// The entries that couple the lean of G, in closed form. With d = z_G − z_hinge (G's centre
/// below the hinge; negative) and μ = c cos λ / w (the yaw rate per steer rate, ψ̇ = μ δ̇ at
/// v = 0): G's angular velocity about x is φ̇ + φ̇_r, about z μ δ̇; its centre moves sideways by
/// −z_G φ̇ − d φ̇_r + x_G μ δ̇. So its kinetic energy gives
/// M_φr = I_Gxx + m_G z_G d, M_δr = μ (I_Gxz − m_G x_G d), M_rr = I_Gxx + m_G d².
/// Its height −z′ with z′ = z_G − z_G φ²/2 − d φ_r²/2 − d φ φ_r (turned about the hinge, then
/// the ground line) gives g K₀ = ∂²(−m_G g z′): K₀_φr = K₀_rr = m_G d; steer does not move G's
/// height to second order with φ_r (the pitch is second order itself), K₀_δr = K₀_rδ = 0.
/// K₂ has no v-free part, so g K₀ is read where v² K₂ is small against it, as the difference
/// of two speeds.
#[test]
fn lean_couplings_in_closed_form() {
    let (_, speeds) = free_hinge();
    let p = RiderLeanParameters::browser_jason();
    let (b, g) = (&p.bicycle, &p.upper_body);
    let mu = b.c * whipple::math::cos(b.lambda) / b.w;
    let d = g.z - g.z_hinge;
    let m_expected = [
        ((0, 2), g.i_xx + g.m * g.z * d),
        ((1, 2), mu * (g.i_xz - g.m * g.x * d)),
        ((2, 2), g.i_xx + g.m * d * d),
    ];
    for s in &speeds {
        let (m, _, _) = second_order(s);
        let scale = m.amax();
        for ((i, j), value) in m_expected {
            assert_close(
                &format!("M[{i}{j}] at {} m/s", s.v),
                value,
                m[(i, j)],
                scale,
            );
            assert_close(
                &format!("M[{j}{i}] at {} m/s", s.v),
                value,
                m[(j, i)],
                scale,
            );
        }
    }
    // g K₀ + v² K₂ at 1 and 2 m/s: K₂ = (F(2) − F(1)) / 3, g K₀ = F(1) − K₂.
    let at = |v: f64| {
        let s = speeds.iter().find(|s| s.v == v).expect("a stored speed");
        second_order(s).1
    };
    let (f1, f2) = (at(1.0), at(2.0));
    let k2 = (f2 - f1) / 3.0;
    let g_k0 = f1 - k2;
    let scale = g_k0.amax();
    let gravity = b.g;
    for ((i, j), value) in [
        ((0, 2), g.m * d * gravity),
        ((2, 0), g.m * d * gravity),
        ((2, 2), g.m * d * gravity),
        ((1, 2), 0.0),
        ((2, 1), 0.0),
    ] {
        assert_close(&format!("gK0[{i}{j}]"), value, g_k0[(i, j)], scale);
    }
}

/// The yaw row (Moore's q3′): ψ̇ = (v δ + c δ̇) cos λ / w, the bicycle's geometry as we convert
/// Moore's d1, d2, d3.
#[test]
fn yaw_kinematics() {
    let (_, speeds) = free_hinge();
    let b = RiderLeanParameters::browser_jason().bicycle;
    let per = whipple::math::cos(b.lambda) / b.w;
    for s in &speeds {
        assert_close("q3' / q7", s.v * per, s.a[(2, 5)], s.v);
        assert_close("q3' / u7", b.c * per, s.a[(2, 10)], 1.0);
    }
}

/// Moore's state of each of ours, [φ, δ, φ_r, φ̇, δ̇, φ̇_r] → q4, q7, q9, u4, u7, u9.
const MOORE_OF_OURS: [usize; 6] = [3, 5, 7, 8, 10, 11];

/// Our five-body model's exact linearization (dual numbers through the non-linear forward
/// dynamics) against BicycleParameters' `MooreRiderLean2012Model`, every entry of A and B, at
/// every stored speed (0.5–10 m/s), with the hinge free and with Moore's stiff, damped hinge.
/// Moore's other rows and columns are the ignorable coordinates (positions, yaw, wheel angles,
/// the rear wheel's rate u6): their columns in the dynamic rows must be zero, and the yaw row
/// is [`yaw_kinematics`]'.
#[test]
fn linearization_is_moores() {
    for (index, name, stiffness, damping) in [
        (0, "free hinge", 0.0, 0.0),
        (1, "stiff, damped hinge (riderlean.py)", 128.0, 50.0),
    ] {
        let (_, speeds) = stored_case(index, name);
        let mut p = RiderLeanParameters::browser_jason();
        p.upper_body.stiffness = stiffness;
        p.upper_body.damping = damping;
        let model = LeanModel::new(&p).unwrap();
        let mut worst = 0.0f64;
        for s in &speeds {
            let (a, b) = model.linearize(s.v).unwrap();
            for (i, &mi) in MOORE_OF_OURS.iter().enumerate() {
                for (j, &mj) in MOORE_OF_OURS.iter().enumerate() {
                    let theirs = s.a[(mi, mj)];
                    let e = (a[(i, j)] - theirs).abs() / theirs.abs().max(1.0);
                    worst = worst.max(e);
                    assert!(
                        e <= 1e-10,
                        "{name}, {} m/s, A[{i}{j}]: {} vs {theirs}",
                        s.v,
                        a[(i, j)]
                    );
                }
                for j in 0..3 {
                    let theirs = s.b[(mi, j)];
                    let e = (b[(i, j)] - theirs).abs() / theirs.abs().max(1.0);
                    worst = worst.max(e);
                    assert!(
                        e <= 1e-10,
                        "{name}, {} m/s, B[{i}{j}]: {} vs {theirs}",
                        s.v,
                        b[(i, j)]
                    );
                }
                // The ignorable coordinates do not enter the dynamics.
                for j in [0, 1, 2, 4, 6, 9] {
                    assert!(s.a[(mi, j)].abs() < 1e-12, "{name}: Moore's A[{mi}][{j}]");
                }
            }
        }
        println!("{name}: largest difference from Moore's A and B {worst:e}");
    }
}

/// The hinge locked, in our own model: the (φ, δ) blocks of M, C₁, K₀, K₂ read from our
/// five-body linearization (M = B⁻¹ on the three torques, −M A the rest) are the benchmark
/// model of the rigid rider, to 1e-12.
#[test]
fn our_locked_hinge_is_the_rigid_rider() {
    let p = RiderLeanParameters::browser_jason();
    let model = LeanModel::new(&p).unwrap();
    let rigid = Canonical::new(&p.rigid()).unwrap();
    for v in [0.5, 1.0, 2.0, 4.6, 8.0] {
        let (a, b) = model.linearize(v).unwrap();
        let m = Matrix3::from_fn(|i, j| b[(3 + i, j)])
            .try_inverse()
            .unwrap();
        let stiffness = -(m * Matrix3::from_fn(|i, j| a[(3 + i, j)]));
        let damping = -(m * Matrix3::from_fn(|i, j| a[(3 + i, 3 + j)]));
        let expected_k = rigid.k0 * rigid.g + rigid.k2 * (v * v);
        let expected_c = rigid.c1 * v;
        for i in 0..2 {
            for j in 0..2 {
                for (what, ours, theirs, scale) in [
                    ("M", m[(i, j)], rigid.m[(i, j)], rigid.m.amax()),
                    (
                        "gK0 + v²K2",
                        stiffness[(i, j)],
                        expected_k[(i, j)],
                        expected_k.amax(),
                    ),
                    (
                        "vC1",
                        damping[(i, j)],
                        expected_c[(i, j)],
                        expected_c.amax(),
                    ),
                ] {
                    assert!(
                        (ours - theirs).abs() <= 1e-12 * scale,
                        "{what}[{i}{j}] at {v} m/s: {ours} vs {theirs}"
                    );
                }
            }
        }
    }
}

/// Splitting the upper body off the rigid rider gives back Moore's parameters to round-off, and
/// the split bicycle's model is the same model (the same A(v)).
#[test]
fn split_inverts_the_rigid_rider() {
    let p = RiderLeanParameters::browser_jason();
    let again = RiderLeanParameters::split(&p.rigid(), p.upper_body).expect("splits");
    let (ours, theirs) = (again.bicycle.to_array(), p.bicycle.to_array());
    for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
        assert!(
            (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
            "entry {k}: {a} vs {b}"
        );
    }
    let (a1, _) = LeanModel::new(&again)
        .expect("model")
        .linearize(5.0)
        .expect("A");
    let (a0, _) = LeanModel::new(&p)
        .expect("model")
        .linearize(5.0)
        .expect("A");
    assert!((a1 - a0).amax() < 1e-10 * a0.amax(), "{}", (a1 - a0).amax());
}

/// Jason's upper body split off another rigid rider (JBike6's Schwinn Crown with its rider,
/// the page's first bicycle): the rear frame keeps the frame and a lower body, lighter by mG;
/// the locked hinge is that bicycle again. Where Jason's upper body does not fit, the split is
/// refused naming mG: inside the benchmark bicycle's rear frame (its IBxz = 2.4 kg m² leaves
/// no room for an upright torso) and on a bicycle without a rider (lighter than mG).
#[test]
fn split_off_another_rider() {
    let jason = RiderLeanParameters::browser_jason().upper_body;
    let preset = |name: &str| {
        whipple::presets::find(name)
            .expect("preset")
            .bicycle()
            .benchmark()
            .expect("benchmark form")
    };
    let schwinn = preset("schwinn-crown");
    let p = RiderLeanParameters::split(&schwinn, jason).expect("fits");
    assert!((p.bicycle.m_b - (schwinn.m_b - jason.m)).abs() < 1e-12);
    for (k, (a, b)) in p
        .rigid()
        .to_array()
        .iter()
        .zip(schwinn.to_array())
        .enumerate()
    {
        assert!(
            (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
            "entry {k}: {a} vs {b}"
        );
    }
    let error = RiderLeanParameters::split(&preset("benchmark"), jason).expect_err("no room");
    let text = error.to_string();
    assert!(
        text.contains("`mG`") && text.contains("positive semi-definite"),
        "{text}"
    );
    let error = RiderLeanParameters::split(&preset("browser"), jason).expect_err("no rider");
    let text = error.to_string();
    assert!(text.contains("`mG`") && text.contains("lighter"), "{text}");
}

/// The five poses: the upright start puts G's centre at (xG, 0, zG) with the rear frame's
/// axes; a hinge angle turns G about the hinge line, which stays where it was.
#[test]
fn upper_body_pose() {
    let p = RiderLeanParameters::browser_jason();
    let model = LeanModel::new(&p).expect("model");
    let ic = whipple::InitialConditions::upright(5.0);
    let upright = model.initial_state(&ic, 0.0, 0.0).expect("state");
    let poses = model.body_poses(&upright);
    let g = poses[4];
    assert!((g.position.x - p.upper_body.x).abs() < 1e-12);
    assert!(g.position.y.abs() < 1e-12);
    assert!((g.position.z - p.upper_body.z).abs() < 1e-12);
    assert!((g.rotation - poses[1].rotation).amax() < 1e-12);
    let leaning = model.initial_state(&ic, 0.3, 0.0).expect("state");
    let poses = model.body_poses(&leaning);
    let hinge = poses[4].position + poses[4].rotation * model.hinge_in_upper_body();
    assert!((hinge.z - p.upper_body.z_hinge).abs() < 1e-12);
    assert!(hinge.y.abs() < 1e-12);
    // Leaning right (positive) moves the centre above the hinge to the right (+y).
    let d = poses[4].position - hinge;
    assert!(
        (d.y - (p.upper_body.z_hinge - p.upper_body.z) * whipple::math::sin(0.3_f64)).abs() < 1e-12
    );
}
