//! Named bicycles from the literature: the one home of published parameter values.

use super::{
    BenchmarkParameters, Bicycle, Description, JBIKE6_GRAVITY, Jbike6FrontBody, Jbike6Parameters,
    Jbike6RearBody, Jbike6Wheel,
};
use crate::error::{Error, Result};

/// A named bicycle with its citation.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    /// The name used on the command line (`--bike NAME`).
    pub name: &'static str,
    /// The name a reader knows it by, with its source in short (the web page's picker).
    pub title: &'static str,
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
            ..Bicycle::default()
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

/// The two-mass-skate (TMS) bicycle of Kooijman, Meijaard, Papadopoulos, Ruina & Schwab 2011,
/// "A bicycle can be self-stable without gyroscopic or caster effects", Science 332:339–342
/// (doi:10.1126/science.1201959): two point masses, massless skates of zero radius instead of
/// wheels, zero trail, 5° steer axis tilt. Digits as transcribed in BicycleParameters
/// (data/bicycles/Tms/Parameters/TmsBenchmark.txt); the Science supplement's own table was not
/// at hand to check them against.
pub fn two_mass_skate() -> BenchmarkParameters {
    BenchmarkParameters {
        w: 1.0,
        c: 0.0,
        lambda: 5f64.to_radians(),
        g: 9.81,
        r_r: 0.0,
        m_r: 0.0,
        i_rxx: 0.0,
        i_ryy: 0.0,
        x_b: 1.2,
        z_b: -0.4,
        m_b: 10.0,
        i_bxx: 0.0,
        i_byy: 0.0,
        i_bzz: 0.0,
        i_bxz: 0.0,
        x_h: 1.02,
        z_h: -0.2,
        m_h: 1.0,
        i_hxx: 0.0,
        i_hyy: 0.0,
        i_hzz: 0.0,
        i_hxz: 0.0,
        r_f: 0.0,
        m_f: 0.0,
        i_fxx: 0.0,
        i_fyy: 0.0,
    }
}

/// A measured city bicycle, the Batavus Browser, with its rider Jason seated rigidly, from
/// Moore 2012, "Human Control of a Bicycle", PhD dissertation, University of California, Davis
/// (measurements of Moore, Hubbard, Kooijman & Schwab). Digits as published with the
/// dissertation's software: HumanControl `parameters/BrowserPar.txt`, identical to
/// BicycleParameters' `meijaard2007_browser_jason` set (whose I_Rxx and I_Fxx appear swapped
/// relative to the dissertation's bicycle table; kept as published).
pub fn browser_jason() -> BenchmarkParameters {
    BenchmarkParameters {
        w: 1.121,
        c: 0.0685808540382,
        lambda: 0.399680398707,
        g: 9.81,
        r_r: 0.340958858855,
        m_r: 3.11,
        i_rxx: 0.0883819364527,
        i_ryy: 0.152467620286,
        x_b: 0.289099434117,
        z_b: -1.04029228321,
        m_b: 81.86,
        i_bxx: 11.3557360401,
        i_byy: 12.2177848012,
        i_bzz: 3.12354397008,
        i_bxz: -1.96756380745,
        x_h: 0.866949640247,
        z_h: -0.748236400835,
        m_h: 3.22,
        i_hxx: 0.253379594731,
        i_hyy: 0.246138810935,
        i_hzz: 0.0955770796289,
        i_hxz: -0.0720452391817,
        r_f: 0.34352982332,
        m_f: 2.02,
        i_fxx: 0.0904106601579,
        i_fyy: 0.149389340425,
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
        title: "Benchmark bicycle (Meijaard et al. 2007)",
        summary: "the benchmark bicycle with rider of Meijaard et al. 2007",
        source: "Meijaard, Papadopoulos, Ruina & Schwab 2007, Proc. R. Soc. A 463:1955-1982, Table 1 (doi:10.1098/rspa.2007.1857)",
        description: || Description::Benchmark(BenchmarkParameters::meijaard2007()),
    },
    Preset {
        name: "schwinn-crown",
        title: "Schwinn Crown (JBike6 default)",
        summary: "JBike6's default bike (JBike6 form: rider, frame, rack, fork, basket)",
        source: "Dressel, Benchmarking a Fully Non-Linear Bicycle Model with JBike6, Cornell University (2003-2015); JBike6, Schwab & Papadopoulos 2003",
        description: || Description::Jbike6(schwinn_crown_jbike6()),
    },
    Preset {
        name: "two-mass-skate",
        title: "Two-mass skate (Kooijman et al. 2011)",
        summary: "two point masses on skates: self-stable without gyroscopic or trail effects",
        source: "Kooijman, Meijaard, Papadopoulos, Ruina & Schwab 2011, Science 332:339-342 (doi:10.1126/science.1201959); digits as transcribed in BicycleParameters data/bicycles/Tms",
        description: || Description::Benchmark(two_mass_skate()),
    },
    Preset {
        name: "browser-jason",
        title: "Batavus Browser with rider Jason (Moore 2012)",
        summary: "a measured Batavus Browser city bicycle with its rider Jason (72 kg) seated rigidly",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; digits of HumanControl parameters/BrowserPar.txt = BicycleParameters meijaard2007_browser_jason",
        description: || Description::Benchmark(browser_jason()),
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
/// let bike = whipple::presets::find("benchmark")?.bicycle();
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
