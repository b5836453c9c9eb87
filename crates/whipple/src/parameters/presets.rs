//! Named bicycles from the literature: the one home of published parameter values.

use super::{
    BenchmarkParameters, Bicycle, Description, Jbike6FrontBody, Jbike6Parameters, Jbike6RearBody,
    Jbike6Wheel, JBIKE6_GRAVITY,
};
use crate::error::{Error, Result};

/// A named bicycle with its citation.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    /// The name used on the command line (`--bike NAME`).
    pub name: &'static str,
    /// One line on what the bicycle is.
    pub summary: &'static str,
    /// Where the numbers come from.
    pub source: &'static str,
    /// The numbers, in the form they were published in.
    pub description: fn() -> Description,
}

impl Preset {
    /// The preset as a [`Bicycle`] carrying its name and source.
    pub fn bicycle(&self) -> Bicycle {
        Bicycle {
            name: Some(self.name.to_string()),
            source: Some(self.source.to_string()),
            description: (self.description)(),
        }
    }
}

impl BenchmarkParameters {
    /// The benchmark bicycle of Meijaard, Papadopoulos, Ruina & Schwab 2007, Proc. R. Soc. A
    /// 463:1955–1982, Table 1 (doi:10.1098/rspa.2007.1857), with g = 9.81. Exact values.
    pub fn meijaard2007() -> Self {
        BenchmarkParameters {
            w: 1.02,
            c: 0.08,
            lambda: std::f64::consts::PI / 10.0,
            g: 9.81,
            r_r: 0.3,
            m_r: 2.0,
            i_rxx: 0.0603,
            i_ryy: 0.12,
            x_b: 0.3,
            z_b: -0.9,
            m_b: 85.0,
            i_bxx: 9.2,
            i_byy: 11.0,
            i_bzz: 2.8,
            i_bxz: 2.4,
            x_h: 0.9,
            z_h: -0.7,
            m_h: 4.0,
            i_hxx: 0.05892,
            i_hyy: 0.06,
            i_hzz: 0.00708,
            i_hxz: -0.00756,
            r_f: 0.35,
            m_f: 3.0,
            i_fxx: 0.1405,
            i_fyy: 0.28,
        }
    }
}

/// JBike6's default bicycle, the Schwinn Crown, in JBike6's form as listed in Dressel's
/// "Benchmarking a Fully Non-Linear Bicycle Model with JBike6" (Cornell, 2003–2015), with
/// JBike6's default gravity 9.80665 m/s².
pub fn schwinn_crown_jbike6() -> Jbike6Parameters {
    let wheel = Jbike6Wheel {
        diameter: 0.6858,
        m: 1.818182,
        inertia: [0.085513, 0.085513, 0.171026],
        alpha: 0.0,
    };
    Jbike6Parameters {
        wheelbase: 1.016,
        head_angle: 1.23879599,
        trail: 0.090968,
        gravity: JBIKE6_GRAVITY,
        rear_wheel: wheel,
        front_wheel: wheel,
        rider: Jbike6RearBody {
            m: 80.0,
            xcm: 0.3,
            ycm: 1.2,
            inertia: [10.531129, 2.468871, 12.0],
            alpha: -0.25957299,
        },
        frame: Jbike6RearBody {
            m: 2.5,
            xcm: 0.3,
            ycm: 0.5,
            inertia: [0.058579, 0.341421, 0.4],
            alpha: 0.39269899,
        },
        rack: Jbike6RearBody {
            m: 2.0,
            xcm: -0.1,
            ycm: 0.8,
            inertia: [0.02, 0.02, 0.02],
            alpha: 0.0,
        },
        fork: Jbike6FrontBody {
            m: 1.5,
            ucm: 0.0,
            vcm: 0.6858,
            inertia: [0.05879, 0.000588, 0.05879],
            alpha: 0.332,
        },
        basket: Jbike6FrontBody {
            m: 1.5,
            ucm: 0.15,
            vcm: 0.8,
            inertia: [0.01, 0.01, 0.01],
            alpha: 0.0,
        },
    }
}

/// Every preset, in the order `whipple presets` lists them.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "benchmark",
        summary: "the benchmark bicycle with rider of Meijaard et al. 2007",
        source: "Meijaard, Papadopoulos, Ruina & Schwab 2007, Proc. R. Soc. A 463:1955-1982, Table 1 (doi:10.1098/rspa.2007.1857)",
        description: || Description::Benchmark(BenchmarkParameters::meijaard2007()),
    },
    Preset {
        name: "schwinn-crown",
        summary: "JBike6's default bike (JBike6 form: rider, frame, rack, fork, basket)",
        source: "Dressel, Benchmarking a Fully Non-Linear Bicycle Model with JBike6, Cornell University (2003-2015); JBike6, Schwab & Papadopoulos 2003",
        description: || Description::Jbike6(schwinn_crown_jbike6()),
    },
];

/// The names of all presets, comma separated.
pub fn names() -> String {
    PRESETS
        .iter()
        .map(|p| p.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The preset of that name.
///
/// ```
/// let bike = whipple::parameters::presets::find("benchmark")?.bicycle();
/// assert_eq!(bike.benchmark()?.w, 1.02);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn find(name: &str) -> Result<&'static Preset> {
    PRESETS
        .iter()
        .find(|p| p.name == name)
        .ok_or_else(|| Error::UnknownPreset {
            name: name.to_string(),
            known: names(),
        })
}
