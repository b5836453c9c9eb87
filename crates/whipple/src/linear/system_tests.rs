//! The ignorable coordinates' rows, the lateral positions and the lateral force's generalized
//! forces against the exact linearization of the non-linear multibody model (dual numbers):
//! an independent derivation of every row the module documentation derives by hand.

use crate::math::Real;
use nalgebra::Vector3;
use num_dual::{Dual64, HyperDual64};

use super::*;
use crate::nonlinear::{FRONT_FRAME, InitialConditions, Inputs, Model, REAR_FRAME, State};

/// The non-linear state at [φ, δ, φ̇, δ̇, ψ, x_P, y_P] and forward speed v: consistent with
/// every constraint, wheel angles zero.
fn nonlinear_state<T: Real>(model: &Model, x: [T; 7], speed: f64) -> Result<State<T>> {
    let upright = model.pitch_for(0.0, 0.0, 0.0)?;
    let pitch = model.ground_pitch(x[0], x[1], upright)?;
    model
        .consistent_state(
            [x[4], x[0], x[1]],
            [x[5], x[6]],
            pitch,
            [nalgebra::convert(speed), x[2], x[3]],
        )
        .ok_or_else(|| Error::SingularDynamics {
            context: "the test's state".into(),
        })
}

/// What the non-linear model says at upright straight running, differentiated along one
/// direction e_j of [φ, δ, φ̇, δ̇, ψ, x_P, y_P]: each quantity as (value, ∂/∂x_j).
struct Readout {
    yaw_rate: (f64, f64),
    rear_contact_x_rate: (f64, f64),
    rear_contact_y_rate: (f64, f64),
    wheel_rates: [(f64, f64); 2],
    front_contact_y: (f64, f64),
    /// Lateral position and lateral velocity of the rear frame's and the front frame's point.
    points: [((f64, f64), (f64, f64)); 2],
}

fn readout(model: &Model, speed: f64, j: usize, locals: &[Vector3<f64>; 2]) -> Result<Readout> {
    let x: [Dual64; 7] = std::array::from_fn(|i| Dual64::new(0.0, if i == j { 1.0 } else { 0.0 }));
    let state = nonlinear_state(model, x, speed)?;
    let rates = model.forward(&state, &Inputs::default())?;
    // Position along the motion (ε₁ = time) and along e_j (ε₂): ε₁ε₂ is ∂(d/dt)/∂x_j.
    let q = state.q.zip_map(&rates.q_dot, |q, q_dot| {
        HyperDual64::new(q.re, q_dot.re, q.eps, q_dot.eps)
    });
    let pair = |d: Dual64| (d.re, d.eps);
    let position = |h: HyperDual64| (h.re, h.eps2);
    let rate = |h: HyperDual64| (h.eps1, h.eps1eps2);
    let [rear, front] = model.contact_points(&q);
    let [rear_wheel, front_wheel] = model.wheel_rates(&state);
    let point = |body: usize, local: &Vector3<f64>| {
        let p = Model::body_point(&q, body, local);
        (position(p.y), rate(p.y))
    };
    Ok(Readout {
        yaw_rate: pair(state.yaw_rate()),
        rear_contact_x_rate: rate(rear.x),
        rear_contact_y_rate: rate(rear.y),
        wheel_rates: [pair(rear_wheel), pair(front_wheel)],
        front_contact_y: position(front.y),
        points: [
            point(REAR_FRAME, &locals[0]),
            point(FRONT_FRAME, &locals[1]),
        ],
    })
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
        "{what}: linear system {a} vs non-linear model {b}"
    );
}

/// ψ̇ = (v δ + c δ̇) cos λ / w, ẏ = v ψ, ẋ = v, θ̇ = −v / r; y_F = y + w ψ − c δ cos λ; a
/// point's lateral position; and the lateral force's generalized forces (the point's partial
/// velocities in φ̇ and δ̇, Kane's form of the virtual work): every one equal to the non-linear
/// model's exact linearization at upright straight running.
#[test]
fn ignorable_rows_match_the_nonlinear_model() -> Result<()> {
    let bike = BenchmarkParameters::meijaard2007();
    let model = Model::new(&bike)?;
    // A point on the rider's back and one on the handlebar.
    let (rear_point, front_point) = ((0.3, -0.9), (0.85, -0.75));
    for speed in [0.0, 1.5, 5.0, 9.0] {
        let request = SystemRequest {
            states: vec![
                StateVariable::Yaw,
                StateVariable::RearContactX,
                StateVariable::RearContactY,
                StateVariable::RearWheelAngle,
                StateVariable::FrontWheelAngle,
            ],
            inputs: vec![Input::LateralForce {
                x: rear_point.0,
                z: rear_point.1,
            }],
            outputs: vec![
                Output::FrontContactY,
                Output::RearFramePointY {
                    x: rear_point.0,
                    z: rear_point.1,
                },
                Output::FrontFramePointY {
                    x: front_point.0,
                    z: front_point.1,
                },
            ],
        };
        let system = LinearSystem::new(&bike, speed, &request)?;
        let (a, c) = (system.a(), system.c());
        let upright = model.body_poses(&model.initial_state(&InitialConditions::upright(speed))?);
        let local = |body: usize, (x, z): (f64, f64)| {
            upright[body].rotation.transpose() * (Vector3::new(x, 0.0, z) - upright[body].position)
        };
        let locals = [
            local(REAR_FRAME, rear_point),
            local(FRONT_FRAME, front_point),
        ];
        let nominal = system.nominal_rates();
        for j in 0..7 {
            let r = readout(&model, speed, j, &locals)?;
            let at = |what: &str| format!("v = {speed}, ∂{what}/∂{}", system.states()[j]);
            close(a[(4, j)], r.yaw_rate.1, &at("ψ̇"));
            close(a[(5, j)], r.rear_contact_x_rate.1, &at("ẋ_P"));
            close(a[(6, j)], r.rear_contact_y_rate.1, &at("ẏ_P"));
            close(a[(7, j)], r.wheel_rates[0].1, &at("θ̇_R"));
            close(a[(8, j)], r.wheel_rates[1].1, &at("θ̇_F"));
            close(c[(0, j)], r.front_contact_y.1, &at("y_F"));
            close(
                c[(1, j)],
                r.points[0].0.1,
                &at("y of the rear frame's point"),
            );
            close(
                c[(2, j)],
                r.points[1].0.1,
                &at("y of the front frame's point"),
            );
            // The nominal run: straight ahead at v, wheels rolling.
            close(
                nominal[5],
                r.rear_contact_x_rate.0,
                "ẋ_P of the nominal run",
            );
            close(nominal[7], r.wheel_rates[0].0, "θ̇_R of the nominal run");
            close(nominal[8], r.wheel_rates[1].0, "θ̇_F of the nominal run");
            close(
                0.0,
                r.yaw_rate.0 + r.rear_contact_y_rate.0,
                "ψ̇, ẏ of the nominal run",
            );
            // The lateral force: f = F ∂ẏ_point/∂[φ̇, δ̇].
            if j == 2 || j == 3 {
                close(
                    system.forces[(j - 2, 0)],
                    r.points[0].1.1,
                    &at("ẏ of the pushed point"),
                );
            }
        }
    }
    Ok(())
}
