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
    /// A measured bicycle's published measurements (key, value, σ), from which its
    /// description and its σ come; empty for the others.
    pub measurements: Measurements,
}

/// Published measurements of a bicycle in the benchmark form: (file key, value, σ), SI units
/// and radians.
pub type Measurements = &'static [(&'static str, f64, f64)];

/// The benchmark parameters of a measured bicycle (every key of the form is in the table; a
/// unit test checks it).
fn measured(table: Measurements) -> BenchmarkParameters {
    let mut b = BenchmarkParameters::meijaard2007();
    for (key, value, _) in table {
        b.set(key, *value);
    }
    b
}

impl Preset {
    /// The preset as a [`Bicycle`] carrying its name and source.
    pub fn bicycle(&self) -> Bicycle {
        Bicycle {
            name: Some(self.name.to_string()),
            source: Some(self.source.to_string()),
            description: (self.description)(),
            sigma: self
                .measurements
                .iter()
                .filter(|(_, _, sigma)| *sigma > 0.0)
                .map(|(key, _, sigma)| (key.to_string(), *sigma))
                .collect(),
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
        measurements: &[],
    },
    Preset {
        name: "schwinn-crown",
        title: "Schwinn Crown (JBike6 default)",
        summary: "JBike6's default bike (JBike6 form: rider, frame, rack, fork, basket)",
        source: "Dressel, Benchmarking a Fully Non-Linear Bicycle Model with JBike6, Cornell University (2003-2015); JBike6, Schwab & Papadopoulos 2003",
        description: || Description::Jbike6(schwinn_crown_jbike6()),
        measurements: &[],
    },
    Preset {
        name: "two-mass-skate",
        title: "Two-mass skate (Kooijman et al. 2011)",
        summary: "two point masses on skates: self-stable without gyroscopic or trail effects",
        source: "Kooijman, Meijaard, Papadopoulos, Ruina & Schwab 2011, Science 332:339-342 (doi:10.1126/science.1201959); digits as transcribed in BicycleParameters data/bicycles/Tms",
        description: || Description::Benchmark(two_mass_skate()),
        measurements: &[],
    },
    Preset {
        name: "browser-jason",
        title: "Batavus Browser with rider Jason (Moore 2012)",
        summary: "a measured Batavus Browser city bicycle with its rider Jason (72 kg) seated rigidly",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; digits of HumanControl parameters/BrowserPar.txt = BicycleParameters meijaard2007_browser_jason",
        description: || Description::Benchmark(browser_jason()),
        measurements: &[],
    },
    Preset {
        name: "browser",
        title: "Batavus Browser, the bicycle alone (Moore 2012)",
        summary: "the measured Batavus Browser city bicycle without a rider, with the measurements' σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Browser/Parameters/BrowserBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(BROWSER)),
        measurements: BROWSER,
    },
    Preset {
        name: "browserins",
        title: "Batavus Browser, instrumented (Moore 2012)",
        summary: "the measured Batavus Browser with its measurement instruments, without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Browserins/Parameters/BrowserinsBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(BROWSERINS)),
        measurements: BROWSERINS,
    },
    Preset {
        name: "crescendo",
        title: "Crescendo, the bicycle alone (Moore 2012)",
        summary: "BicycleParameters' measured Crescendo bicycle without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Crescendo/Parameters/CrescendoBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(CRESCENDO)),
        measurements: CRESCENDO,
    },
    Preset {
        name: "fisher",
        title: "Fisher, the bicycle alone (Moore 2012)",
        summary: "BicycleParameters' measured Fisher bicycle without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Fisher/Parameters/FisherBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(FISHER)),
        measurements: FISHER,
    },
    Preset {
        name: "pista",
        title: "Pista, the bicycle alone (Moore 2012)",
        summary: "BicycleParameters' measured Pista bicycle without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Pista/Parameters/PistaBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(PISTA)),
        measurements: PISTA,
    },
    Preset {
        name: "rigid",
        title: "Rigid, the bicycle alone (Moore 2012)",
        summary: "BicycleParameters' measured Rigid bicycle without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Rigid/Parameters/RigidBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(RIGID)),
        measurements: RIGID,
    },
    Preset {
        name: "silver",
        title: "Silver, the bicycle alone (Moore 2012)",
        summary: "BicycleParameters' Silver bicycle without a rider (its file gives no σ)",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Silver/Parameters/SilverBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(SILVER)),
        measurements: SILVER,
    },
    Preset {
        name: "yellow",
        title: "Yellow, the bicycle alone (Moore 2012)",
        summary: "BicycleParameters' measured Yellow bicycle without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Yellow/Parameters/YellowBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(YELLOW)),
        measurements: YELLOW,
    },
    Preset {
        name: "yellowrev",
        title: "Yellow with its fork reversed (Moore 2012)",
        summary: "BicycleParameters' measured Yellowrev bicycle (the Yellow, fork reversed) without a rider, with σ",
        source: "Moore 2012, Human Control of a Bicycle, PhD dissertation, UC Davis; published with BicycleParameters (data/bicycles/Yellowrev/Parameters/YellowrevBenchmark.txt, BSD-2-Clause, see THIRD-PARTY.md)",
        description: || Description::Benchmark(measured(YELLOWREV)),
        measurements: YELLOWREV,
    },
];

// The measurements below are BicycleParameters' (github.com/moorepants/BicycleParameters,
// data/bicycles/<Name>/Parameters/<Name>Benchmark.txt; Moore 2012), redistributed under its
// licence (also in THIRD-PARTY.md at the repository's root):
//
// Copyright (c) 2011-2025, BicycleParameters Authors
// All rights reserved.
//
// Redistribution and use in source and binary forms, with or without
// modification, are permitted provided that the following conditions are met:
//
//   1. Redistributions of source code must retain the above copyright notice, this
//      list of conditions and the following disclaimer.
//
//   2. Redistributions in binary form must reproduce the above copyright notice,
//      this list of conditions and the following disclaimer in the documentation
//      and/or other materials provided with the distribution.
//
// THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND
// ANY EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED
// WARRANTIES OF MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE
// DISCLAIMED. IN NO EVENT SHALL THE COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE
// FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL, EXEMPLARY, OR CONSEQUENTIAL
// DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF SUBSTITUTE GOODS OR
// SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION) HOWEVER
// CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY,
// OR TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE
// OF THIS SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
//
// The views and conclusions contained in the software and documentation are those
// of the authors and should not be interpreted as representing official policies,
// either expressed or implied, of Jason Keith Moore.

/// BicycleParameters' `BrowserBenchmark.txt`: key, value, σ (SI units, radians).
const BROWSER: Measurements = &[
    ("w", 1.121, 0.002),
    ("c", 0.0686, 0.00169464113488),
    ("lam", 0.399680398707, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.341, 0.000122426879301),
    ("mR", 3.1, 0.02),
    ("IRxx", 0.0904, 0.000367953786506),
    ("IRyy", 0.1524, 0.00113908424669),
    ("xB", 0.274, 0.00309782583552),
    ("zB", -0.538, 0.00265022978777),
    ("mB", 9.9, 0.02),
    ("IBxx", 0.5296, 0.00247550148476),
    ("IByy", 1.3164, 0.00400774617153),
    ("IBzz", 0.7568, 0.00330394515109),
    ("IBxz", -0.1163, 0.00114783359707),
    ("xH", 0.867, 0.003842300035),
    ("zH", -0.748, 0.00263543623177),
    ("mH", 3.2, 0.02),
    ("IHxx", 0.2534, 0.00126852786611),
    ("IHyy", 0.2458, 0.00299166644562),
    ("IHzz", 0.0956, 0.000737521114809),
    ("IHxz", -0.072, 0.000790281755242),
    ("rF", 0.344, 0.000122426879301),
    ("mF", 2.0, 0.02),
    ("IFxx", 0.0884, 0.00035969731805),
    ("IFyy", 0.1492, 0.00151585483097),
];

/// BicycleParameters' `BrowserinsBenchmark.txt`: key, value, σ (SI units, radians).
const BROWSERINS: Measurements = &[
    ("w", 1.121, 0.002),
    ("c", 0.068, 0.00169155184938),
    ("lam", 0.399680398707, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.341, 0.000122426879301),
    ("mR", 3.1, 0.02),
    ("IRxx", 0.0904, 0.000367953786506),
    ("IRyy", 0.1524, 0.00113908424669),
    ("xB", 0.217, 0.00260084278255),
    ("zB", -0.622, 0.00294167899872),
    ("mB", 14.7, 0.02),
    ("IBxx", 1.0451, 0.00504180663254),
    ("IByy", 2.403, 0.00678076158267),
    ("IBzz", 1.8501, 0.0076900136829),
    ("IBxz", -0.1123, 0.00342792103562),
    ("xH", 0.867, 0.003842300035),
    ("zH", -0.747, 0.00263543623177),
    ("mH", 3.2, 0.02),
    ("IHxx", 0.2534, 0.00126852786611),
    ("IHyy", 0.2458, 0.00299166644562),
    ("IHzz", 0.0956, 0.000737521114809),
    ("IHxz", -0.072, 0.000790281755242),
    ("rF", 0.343, 0.000122426879301),
    ("mF", 2.0, 0.02),
    ("IFxx", 0.0884, 0.00035969731805),
    ("IFyy", 0.1492, 0.00151585483097),
];

/// BicycleParameters' `CrescendoBenchmark.txt`: key, value, σ (SI units, radians).
const CRESCENDO: Measurements = &[
    ("w", 1.101, 0.002),
    ("c", 0.083, 0.0016907620071),
    ("lam", 0.366519142919, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.34, 0.000122426879301),
    ("mR", 4.0, 0.02),
    ("IRxx", 0.0966, 0.000393325323081),
    ("IRyy", 0.1438, 0.00112425225803),
    ("xB", 0.312, 0.00284415365691),
    ("zB", -0.526, 0.00341340590315),
    ("mB", 9.1, 0.02),
    ("IBxx", 0.4997, 0.00218886827509),
    ("IByy", 1.1174, 0.00350925696921),
    ("IBzz", 0.7393, 0.00309105815486),
    ("IBxz", -0.0148, 0.0011316149926),
    ("xH", 0.907, 0.00503272487149),
    ("zH", -0.803, 0.00253087563355),
    ("mH", 4.6, 0.02),
    ("IHxx", 0.384, 0.0017423135025),
    ("IHyy", 0.3631, 0.00410499482239),
    ("IHzz", 0.1664, 0.00132747251116),
    ("IHxz", -0.0778, 0.00114110113858),
    ("rF", 0.343, 0.000122426879301),
    ("mF", 3.5, 0.02),
    ("IFxx", 0.0954, 0.000388267862788),
    ("IFyy", 0.1656, 0.00117747774467),
];

/// BicycleParameters' `FisherBenchmark.txt`: key, value, σ (SI units, radians).
const FISHER: Measurements = &[
    ("w", 1.07, 0.002),
    ("c", 0.072, 0.00162907266827),
    ("lam", 0.329867228627, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.339, 0.000113682102208),
    ("mR", 1.9, 0.02),
    ("IRxx", 0.063, 0.000256485390265),
    ("IRyy", 0.1008, 0.00107522785415),
    ("xB", 0.367, 0.00248108393213),
    ("zB", -0.499, 0.0030479185727),
    ("mB", 4.5, 0.02),
    ("IBxx", 0.2825, 0.00127383578938),
    ("IByy", 0.4697, 0.00284777713914),
    ("IBzz", 0.2677, 0.00118544629608),
    ("IBxz", 0.0559, 0.00032406554195),
    ("xH", 0.96, 0.00631607383256),
    ("zH", -0.719, 0.00351009078132),
    ("mH", 2.5, 0.02),
    ("IHxx", 0.1147, 0.00096842589825),
    ("IHyy", 0.1, 0.00368850446069),
    ("IHzz", 0.0226, 0.00059383598588),
    ("IHxz", -0.0182, 0.00120624722635),
    ("rF", 0.33, 0.000113682102208),
    ("mF", 1.5, 0.02),
    ("IFxx", 0.0631, 0.000256982558173),
    ("IFyy", 0.1062, 0.00143256408253),
];

/// BicycleParameters' `PistaBenchmark.txt`: key, value, σ (SI units, radians).
const PISTA: Measurements = &[
    ("w", 0.989, 0.002),
    ("c", 0.062, 0.00160776211474),
    ("lam", 0.275762021815, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.332, 0.000113682102208),
    ("mR", 1.4, 0.02),
    ("IRxx", 0.0552, 0.000224760513182),
    ("IRyy", 0.0764, 0.00113609058577),
    ("xB", 0.383, 0.0167166513945),
    ("zB", -0.477, 0.00737825561617),
    ("mB", 4.5, 0.02),
    ("IBxx", 0.29, 0.00157896728396),
    ("IByy", 0.4758, 0.00928289658533),
    ("IBzz", 0.2494, 0.0012401842031),
    ("IBxz", 0.0502, 0.00104541145109),
    ("xH", 0.906, 0.00453451662332),
    ("zH", -0.733, 0.00234292942429),
    ("mH", 2.3, 0.02),
    ("IHxx", 0.098, 0.000400797112661),
    ("IHyy", 0.0692, 0.00207906543331),
    ("IHzz", 0.0396, 0.000166321860227),
    ("IHxz", -0.0044, 0.000293006332405),
    ("rF", 0.334, 0.000113682102208),
    ("mF", 1.6, 0.02),
    ("IFxx", 0.0553, 0.000225252175919),
    ("IFyy", 0.1062, 0.00137178526192),
];

/// BicycleParameters' `RigidBenchmark.txt`: key, value, σ (SI units, radians).
const RIGID: Measurements = &[
    ("w", 1.064, 0.000166142163674),
    ("c", 0.06, 0.000144359307346),
    ("lam", 0.317489078499, 0.000324568695876),
    ("g", 9.81, 0.01),
    ("rR", 0.333, 9.1888149237e-06),
    ("mR", 4.9, 0.01),
    ("IRxx", 0.0701, 0.000225450850594),
    ("IRyy", 0.1293, 0.000591786942138),
    ("xB", 0.335, 0.00690189995787),
    ("zB", -0.736, 0.00476533104829),
    ("mB", 22.9, 0.01),
    ("IBxx", 2.6375, 0.011141147301),
    ("IByy", 4.2768, 0.0117267758886),
    ("IBzz", 1.9428, 0.0194143157306),
    ("IBxz", 0.6536, 0.00257157016663),
    ("xH", 0.818, 0.00132894376927),
    ("zH", -0.986, 0.00164933184028),
    ("mH", 5.4, 0.0141421356237),
    ("IHxx", 0.3439, 0.00300081291905),
    ("IHyy", 0.3399, 0.00401223893069),
    ("IHzz", 0.1031, 0.000713162568858),
    ("IHxz", -0.0919, 0.00137845404385),
    ("rF", 0.336, 9.1888149237e-06),
    ("mF", 1.6, 0.01),
    ("IFxx", 0.0524, 0.000168690908608),
    ("IFyy", 0.0984, 0.000678080004122),
];

/// BicycleParameters' `SilverBenchmark.txt`: key, value, σ (SI units, radians).
const SILVER: Measurements = &[
    ("w", 1.01, 0.0),
    ("c", 0.19, 0.0),
    ("lam", 0.366519143, 0.0),
    ("g", 9.81, 0.0),
    ("rR", 0.35, 0.0),
    ("mR", 2.6, 0.0),
    ("IRxx", 0.078, 0.0),
    ("IRyy", 0.156, 0.0),
    ("xB", 0.32, 0.0),
    ("zB", -0.627, 0.0),
    ("mB", 12.1, 0.0),
    ("IBxx", 0.8155, 0.0),
    ("IByy", 1.2, 0.0),
    ("IBzz", 1.0825, 0.0),
    ("IBxz", 0.0327, 0.0),
    ("xH", 0.907, 0.0),
    ("zH", -0.8, 0.0),
    ("mH", 2.5, 0.0),
    ("IHxx", 0.086, 0.0),
    ("IHyy", 0.1, 0.0),
    ("IHzz", 0.0169, 0.0),
    ("IHxz", -0.0311, 0.0),
    ("rF", 0.349, 0.0),
    ("mF", 2.05, 0.0),
    ("IFxx", 0.081, 0.0),
    ("IFyy", 0.162, 0.0),
];

/// BicycleParameters' `YellowBenchmark.txt`: key, value, σ (SI units, radians).
const YELLOW: Measurements = &[
    ("w", 1.089, 0.002),
    ("c", 0.0473, 0.00162727102983),
    ("lam", 0.301941960595, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.341, 0.000122426879301),
    ("mR", 2.6, 0.02),
    ("IRxx", 0.0877, 0.000356796414278),
    ("IRyy", 0.1487, 0.0012536133519),
    ("xB", 0.422, 0.00384241188261),
    ("zB", -0.603, 0.00365196117253),
    ("mB", 3.3, 0.02),
    ("IBxx", 0.224, 0.000924337136702),
    ("IByy", 0.3879, 0.00457262650146),
    ("IBzz", 0.216, 0.000899957967889),
    ("IBxz", 0.0182, 0.000123765736234),
    ("xH", 0.948, 0.00438045273196),
    ("zH", -0.788, 0.00232630323345),
    ("mH", 2.5, 0.02),
    ("IHxx", 0.1452, 0.000640851479448),
    ("IHyy", 0.12, 0.00250714868146),
    ("IHzz", 0.0292, 0.00034384832588),
    ("IHxz", -0.0194, 0.000517327473538),
    ("rF", 0.342, 0.000122426879301),
    ("mF", 1.9, 0.02),
    ("IFxx", 0.0852, 0.000346541216905),
    ("IFyy", 0.1466, 0.00158129157014),
];

/// BicycleParameters' `YellowrevBenchmark.txt`: key, value, σ (SI units, radians).
const YELLOWREV: Measurements = &[
    ("w", 0.985, 0.002),
    ("c", 0.18, 0.00176864639495),
    ("lam", 0.338593874887, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.341, 0.000122426879301),
    ("mR", 2.6, 0.02),
    ("IRxx", 0.0877, 0.000356796414278),
    ("IRyy", 0.1487, 0.0012536133519),
    ("xB", 0.412, 0.00379563686367),
    ("zB", -0.618, 0.00370055269932),
    ("mB", 3.3, 0.02),
    ("IBxx", 0.2254, 0.00092916150614),
    ("IByy", 0.3879, 0.00457262650146),
    ("IBzz", 0.2147, 0.000893315075898),
    ("IBxz", 0.0179, 0.000129627296249),
    ("xH", 0.919, 0.00455107965017),
    ("zH", -0.816, 0.00225140598256),
    ("mH", 2.5, 0.02),
    ("IHxx", 0.1475, 0.000640700256464),
    ("IHyy", 0.1195, 0.00245444440384),
    ("IHzz", 0.0294, 0.000366277717216),
    ("IHxz", -0.0172, 0.000527993839439),
    ("rF", 0.342, 0.000122426879301),
    ("mF", 1.9, 0.02),
    ("IFxx", 0.0852, 0.000346541216905),
    ("IFyy", 0.1466, 0.00158129157014),
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
