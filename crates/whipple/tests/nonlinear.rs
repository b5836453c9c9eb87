//! The non-linear multibody bicycle checked against published values, physical invariants and
//! the linear model.

use std::f64::consts::PI;

use nalgebra::{SVector, Vector3};
use whipple::nonlinear::{
    rotation, InitialConditions, Inputs, Model, State, FRONT_FRAME, REAR_FRAME, REAR_WHEEL,
};
use whipple::{BenchmarkParameters, Result};

/// Basu-Mandal, Chatterjee & Papadopoulos 2007, Proc. R. Soc. A 463:1983–2003, Table 1: a
/// general state of the benchmark bicycle and its accelerations from the fully non-linear
/// equations (digits as transcribed in moorepants/DynamicistToolKit, dtk/bicycle.py).
/// Their coordinates: x, y, z rear wheel centre (z up, x backward when θ = 0); θ yaw, ψ lean
/// (π/2 upright), φ rear frame pitch (π upright), ψ_f steer, β_r, β_f wheel rotations; all
/// with the opposite sense of this model's (yaw right, lean right, nose up, steer right,
/// wheel rotation about the axle pointing right).
mod basu_mandal_2007 {
    pub const X: f64 = 0.0;
    pub const Y: f64 = 0.0;
    pub const Z: f64 = 0.2440472102925;
    pub const THETA: f64 = 0.0;
    pub const PSI: f64 = 0.9501292851472;
    pub const PHI: f64 = 3.1257073014894;
    pub const PSIF: f64 = 0.2311385135743;
    pub const BETAR: f64 = 0.0;
    pub const BETAF: f64 = 0.0;
    pub const XD: f64 = -2.8069345714545;
    pub const YD: f64 = -0.1480982396001;
    pub const ZD: f64 = 0.1058778746261;
    pub const THETAD: f64 = 0.7830033527065;
    pub const PSID: f64 = 0.6068425835418;
    pub const PHID: f64 = -0.0119185528069;
    pub const PSIFD: f64 = 0.4859824687093;
    pub const BETARD: f64 = 8.912989661489;
    pub const BETAFD: f64 = 8.0133620584155;
    /// xdd, ydd, zdd, thetadd, psidd, phidd, psifdd, betardd, betafdd.
    pub const OUTPUT: [f64; 9] = [
        -0.5041626315047,
        -0.3449706619454,
        -1.460452833298,
        0.8353281706379,
        -7.8555281128244,
        0.1205543897884,
        -4.6198904039403,
        1.8472554144217,
        2.454807290455,
    ];
}

fn basu_state(model: &Model) -> State<f64> {
    use basu_mandal_2007::*;
    let r_r = model.parameters.r_r;
    let (yaw, lean, pitch, steer) = (-THETA, PI / 2.0 - PSI, PI - PHI, -PSIF);
    // Rear contact from the rear wheel centre (the contact is r_R cos ψ to the left of the
    // centre's ground projection, across the heading).
    let contact = [
        -X - r_r * THETA.sin() * PSI.cos(),
        Y - r_r * THETA.cos() * PSI.cos(),
    ];
    let q = model.configuration([yaw, lean, pitch], steer, [-BETAR, -BETAF], contact);
    let hub = Vector3::new(q[0], q[1], q[2]);
    assert!(
        (hub - Vector3::new(-X, Y, -Z)).amax() < 1e-12,
        "rear wheel centre {hub}"
    );
    let rates = Vector3::new(-THETAD, -PSID, -PHID);
    let omega_b = rotation::rates_to_body(lean, pitch) * rates;
    let u = model.tree_speeds(
        &q,
        &Vector3::new(-XD, YD, -ZD),
        &omega_b,
        -PSIFD,
        [-BETARD, -BETAFD],
    );
    State { q, u }
}

fn basu_accelerations(model: &Model, state: &State<f64>, forward: bool) -> Result<[f64; 9]> {
    let d = if forward {
        model.forward(state, &Inputs::default())?
    } else {
        model.forward_reference(state, &Inputs::default())?
    };
    let a = d.u_dot.fixed_rows::<3>(6 * REAR_WHEEL).into_owned();
    let rates = |k: usize| Model::time_derivative(state, &d, |s| s.angle_rates(REAR_FRAME)[k]);
    let steer = Model::time_derivative(state, &d, |s| model.steer_rate(s));
    let rear = Model::time_derivative(state, &d, |s| model.wheel_rates(s)[0]);
    let front = Model::time_derivative(state, &d, |s| model.wheel_rates(s)[1]);
    Ok([
        -a.x,
        a.y,
        -a.z,
        -rates(0),
        -rates(1),
        -rates(2),
        -steer,
        -rear,
        -front,
    ])
}

#[test]
fn basu_mandal_2007_table_1_accelerations() -> Result<()> {
    let model = Model::new(&BenchmarkParameters::meijaard2007())?;
    let state = basu_state(&model);
    let residuals = model.residuals(&state);
    assert!(
        residuals.max_holonomic() < 1e-12,
        "{}",
        residuals.max_holonomic()
    );
    assert!(
        residuals.max_velocity() < 1e-12,
        "{}",
        residuals.max_velocity()
    );
    let out = basu_accelerations(&model, &state, true)?;
    let reference = basu_accelerations(&model, &state, false)?;
    for (i, published) in basu_mandal_2007::OUTPUT.iter().enumerate() {
        println!(
            "{i}: {:.13} published {:.13} diff {:e} dense {:e}",
            out[i],
            published,
            out[i] - published,
            out[i] - reference[i]
        );
    }
    for (i, published) in basu_mandal_2007::OUTPUT.iter().enumerate() {
        assert!(
            (out[i] - published).abs() < 1e-10,
            "output {i}: {} vs {published}",
            out[i]
        );
        assert!((out[i] - reference[i]).abs() < 1e-10);
    }
    Ok(())
}
