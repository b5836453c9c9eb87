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
    ("c", 0.0685808540382, 0.00169464113488),
    ("lam", 0.399680398707, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.340958858855, 0.000122426879301),
    ("mR", 3.11, 0.02),
    ("IRxx", 0.0904114316323, 0.000367953786506),
    ("IRyy", 0.152391250767, 0.00113908424669),
    ("xB", 0.275951285677, 0.00309782583552),
    ("zB", -0.537842424305, 0.00265022978777),
    ("mB", 9.86, 0.02),
    ("IBxx", 0.52962890621, 0.00247550148476),
    ("IByy", 1.3163960125, 0.00400774617153),
    ("IBzz", 0.756786895402, 0.00330394515109),
    ("IBxz", -0.116285607878, 0.00114783359707),
    ("xH", 0.866949640247, 0.003842300035),
    ("zH", -0.748236400835, 0.00263543623177),
    ("mH", 3.22, 0.02),
    ("IHxx", 0.25335539588, 0.00126852786611),
    ("IHyy", 0.245827908036, 0.00299166644562),
    ("IHzz", 0.0955686343473, 0.000737521114809),
    ("IHxz", -0.0720217263293, 0.000790281755242),
    ("rF", 0.34352982332, 0.000122426879301),
    ("mF", 2.02, 0.02),
    ("IFxx", 0.0883826870796, 0.00035969731805),
    ("IFyy", 0.149221207336, 0.00151585483097),
];

/// BicycleParameters' `BrowserinsBenchmark.txt`: key, value, σ (SI units, radians).
const BROWSERINS: Measurements = &[
    ("w", 1.121, 0.002),
    ("c", 0.0681671329298, 0.00169155184938),
    ("lam", 0.399680398707, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.340775218536, 0.000122426879301),
    ("mR", 3.11, 0.02),
    ("IRxx", 0.0904114316323, 0.000367953786506),
    ("IRyy", 0.152391250767, 0.00113908424669),
    ("xB", 0.217194662529, 0.00260084278255),
    ("zB", -0.622313629343, 0.00294167899872),
    ("mB", 14.71, 0.02),
    ("IBxx", 1.04508307817, 0.00504180663254),
    ("IByy", 2.40302606561, 0.00678076158267),
    ("IBzz", 1.85009284121, 0.0076900136829),
    ("IBxz", -0.112576216156, 0.00342792103562),
    ("xH", 0.866949640247, 0.003842300035),
    ("zH", -0.7472569858, 0.00263543623177),
    ("mH", 3.22, 0.02),
    ("IHxx", 0.25335539588, 0.00126852786611),
    ("IHyy", 0.245827908036, 0.00299166644562),
    ("IHzz", 0.0955686343473, 0.000737521114809),
    ("IHxz", -0.0720217263293, 0.000790281755242),
    ("rF", 0.342550408285, 0.000122426879301),
    ("mF", 2.02, 0.02),
    ("IFxx", 0.0883826870796, 0.00035969731805),
    ("IFyy", 0.149221207336, 0.00151585483097),
];

/// BicycleParameters' `CrescendoBenchmark.txt`: key, value, σ (SI units, radians).
const CRESCENDO: Measurements = &[
    ("w", 1.101, 0.002),
    ("c", 0.0832912572138, 0.0016907620071),
    ("lam", 0.366519142919, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.339954958444, 0.000122426879301),
    ("mR", 3.96, 0.02),
    ("IRxx", 0.0966455697105, 0.000393325323081),
    ("IRyy", 0.143776919744, 0.00112425225803),
    ("xB", 0.312073833522, 0.00284415365691),
    ("zB", -0.525854751698, 0.00341340590315),
    ("mB", 9.18, 0.02),
    ("IBxx", 0.499733285449, 0.00218886827509),
    ("IByy", 1.11746960046, 0.00350925696921),
    ("IBzz", 0.73927170227, 0.00309105815486),
    ("IBxz", -0.0148407505732, 0.0011316149926),
    ("xH", 0.906569561251, 0.00503272487149),
    ("zH", -0.802835004591, 0.00253087563355),
    ("mH", 4.57, 0.02),
    ("IHxx", 0.3840330428, 0.0017423135025),
    ("IHyy", 0.363142461888, 0.00410499482239),
    ("IHzz", 0.166357442859, 0.00132747251116),
    ("IHxz", -0.0777986089409, 0.00114110113858),
    ("rF", 0.342550408285, 0.000122426879301),
    ("mF", 3.545, 0.02),
    ("IFxx", 0.0954028662773, 0.000388267862788),
    ("IFyy", 0.165623459942, 0.00117747774467),
];

/// BicycleParameters' `FisherBenchmark.txt`: key, value, σ (SI units, radians).
const FISHER: Measurements = &[
    ("w", 1.07, 0.002),
    ("c", 0.0723512958768, 0.00162907266827),
    ("lam", 0.329867228627, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.338636246059, 0.000113682102208),
    ("mR", 1.94, 0.02),
    ("IRxx", 0.0630220804753, 0.000256485390265),
    ("IRyy", 0.100831563132, 0.00107522785415),
    ("xB", 0.367006269532, 0.00248108393213),
    ("zB", -0.499035032101, 0.0030479185727),
    ("mB", 4.48, 0.02),
    ("IBxx", 0.282523843228, 0.00127383578938),
    ("IByy", 0.469714069753, 0.00284777713914),
    ("IBzz", 0.267736477961, 0.00118544629608),
    ("IBxz", 0.0559047839186, 0.00032406554195),
    ("xH", 0.959729631021, 0.00631607383256),
    ("zH", -0.719194693301, 0.00351009078132),
    ("mH", 2.52, 0.02),
    ("IHxx", 0.114653255231, 0.00096842589825),
    ("IHyy", 0.099999037681, 0.00368850446069),
    ("IHzz", 0.022649063255, 0.00059383598588),
    ("IHxz", -0.0182419196924, 0.00120624722635),
    ("rF", 0.330178297654, 0.000113682102208),
    ("mF", 1.5, 0.02),
    ("IFxx", 0.0631442259272, 0.000256982558173),
    ("IFyy", 0.106223925049, 0.00143256408253),
];

/// BicycleParameters' `PistaBenchmark.txt`: key, value, σ (SI units, radians).
const PISTA: Measurements = &[
    ("w", 0.989, 0.002),
    ("c", 0.0617300113263, 0.00160776211474),
    ("lam", 0.275762021815, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.332088156971, 0.000113682102208),
    ("mR", 1.38, 0.02),
    ("IRxx", 0.0552268228143, 0.000224760513182),
    ("IRyy", 0.0764034890242, 0.00113609058577),
    ("xB", 0.382963782674, 0.0167166513945),
    ("zB", -0.476798507146, 0.00737825561617),
    ("mB", 4.49, 0.02),
    ("IBxx", 0.289968529291, 0.00157896728396),
    ("IByy", 0.475817094274, 0.00928289658533),
    ("IBzz", 0.249418014295, 0.0012401842031),
    ("IBxz", 0.0502317583637, 0.00104541145109),
    ("xH", 0.906321313298, 0.00453451662332),
    ("zH", -0.732376356772, 0.00234292942429),
    ("mH", 2.27, 0.02),
    ("IHxx", 0.0979884309288, 0.000400797112661),
    ("IHyy", 0.0691907586693, 0.00207906543331),
    ("IHzz", 0.0396107377431, 0.000166321860227),
    ("IHxz", -0.00440828467861, 0.000293006332405),
    ("rF", 0.333838861345, 0.000113682102208),
    ("mF", 1.58, 0.02),
    ("IFxx", 0.0553476418952, 0.000225252175919),
    ("IFyy", 0.106185287785, 0.00137178526192),
];

/// BicycleParameters' `RigidBenchmark.txt`: key, value, σ (SI units, radians).
const RIGID: Measurements = &[
    ("w", 1.06378677685, 0.000166142163674),
    ("c", 0.0599399125715, 0.000144359307346),
    ("lam", 0.317489078499, 0.000324568695876),
    ("g", 9.81, 0.01),
    ("rR", 0.332528026978, 9.1888149237e-06),
    ("mR", 4.9, 0.01),
    ("IRxx", 0.0700963804567, 0.000225450850594),
    ("IRyy", 0.12934189355, 0.000591786942138),
    ("xB", 0.334844476225, 0.00690189995787),
    ("zB", -0.735628402212, 0.00476533104829),
    ("mB", 22.9, 0.01),
    ("IBxx", 2.63751918806, 0.011141147301),
    ("IByy", 4.27679806219, 0.0117267758886),
    ("IBzz", 1.94277851254, 0.0194143157306),
    ("IBxz", 0.65355108991, 0.00257157016663),
    ("xH", 0.818396445062, 0.00132894376927),
    ("zH", -0.98585673135, 0.00164933184028),
    ("mH", 5.4, 0.0141421356237),
    ("IHxx", 0.343873849682, 0.00300081291905),
    ("IHyy", 0.339925043172, 0.00401223893069),
    ("IHzz", 0.10310836332, 0.000713162568858),
    ("IHxz", -0.0918999164196, 0.00137845404385),
    ("rF", 0.335572561302, 9.1888149237e-06),
    ("mF", 1.55, 0.01),
    ("IFxx", 0.0524475128396, 0.000168690908608),
    ("IFyy", 0.0983720589324, 0.000678080004122),
];

/// BicycleParameters' `SilverBenchmark.txt`: key, value, σ (SI units, radians).
const SILVER: Measurements = &[
    ("w", 1.010, 0.0),
    ("c", 0.190, 0.0),
    ("lam", 0.366519143, 0.0),
    ("g", 9.81, 0.0),
    ("rR", 0.35, 0.0),
    ("mR", 2.56, 0.0),
    ("IRxx", 0.078, 0.0),
    ("IRyy", 0.156, 0.0),
    ("xB", 0.32, 0.0),
    ("zB", -0.627, 0.0),
    ("mB", 12.06, 0.0),
    ("IBxx", 0.8155, 0.0),
    ("IByy", 1.2, 0.0),
    ("IBzz", 1.0825, 0.0),
    ("IBxz", 0.0327, 0.0),
    ("xH", 0.907, 0.0),
    ("zH", -0.8, 0.0),
    ("mH", 2.54, 0.0),
    ("IHxx", 0.0860, 0.0),
    ("IHyy", 0.1, 0.0),
    ("IHzz", 0.0169, 0.0),
    ("IHxz", -0.0311, 0.0),
    ("rF", 0.3485, 0.0),
    ("mF", 2.05, 0.0),
    ("IFxx", 0.081, 0.0),
    ("IFyy", 0.162, 0.0),
];

/// BicycleParameters' `YellowBenchmark.txt`: key, value, σ (SI units, radians).
const YELLOW: Measurements = &[
    ("w", 1.089, 0.002),
    ("c", 0.0473057207886, 0.00162727102983),
    ("lam", 0.301941960595, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.341375110244, 0.000122426879301),
    ("mR", 2.57, 0.02),
    ("IRxx", 0.0876699101307, 0.000356796414278),
    ("IRyy", 0.148661417202, 0.0012536133519),
    ("xB", 0.422298296643, 0.00384241188261),
    ("zB", -0.602532173969, 0.00365196117253),
    ("mB", 3.31, 0.02),
    ("IBxx", 0.224032534273, 0.000924337136702),
    ("IByy", 0.387875498968, 0.00457262650146),
    ("IBzz", 0.216034304161, 0.000899957967889),
    ("IBxz", 0.0182183890667, 0.000123765736234),
    ("xH", 0.947882088454, 0.00438045273196),
    ("zH", -0.788217049637, 0.00232630323345),
    ("mH", 2.45, 0.02),
    ("IHxx", 0.145204096638, 0.000640851479448),
    ("IHyy", 0.120010862686, 0.00250714868146),
    ("IHzz", 0.0292310723185, 0.00034384832588),
    ("IHxz", -0.0193850131223, 0.000517327473538),
    ("rF", 0.341877060449, 0.000122426879301),
    ("mF", 1.9, 0.02),
    ("IFxx", 0.0851500332546, 0.000346541216905),
    ("IFyy", 0.146642875064, 0.00158129157014),
];

/// BicycleParameters' `YellowrevBenchmark.txt`: key, value, σ (SI units, radians).
const YELLOWREV: Measurements = &[
    ("w", 0.985, 0.002),
    ("c", 0.180294938773, 0.00176864639495),
    ("lam", 0.338593874887, 0.00349065850399),
    ("g", 9.81, 0.01),
    ("rR", 0.341375110244, 0.000122426879301),
    ("mR", 2.57, 0.02),
    ("IRxx", 0.0876699101307, 0.000356796414278),
    ("IRyy", 0.148661417202, 0.0012536133519),
    ("xB", 0.41244491511, 0.00379563686367),
    ("zB", -0.61783135503, 0.00370055269932),
    ("mB", 3.31, 0.02),
    ("IBxx", 0.225356076528, 0.00092916150614),
    ("IByy", 0.387875498968, 0.00457262650146),
    ("IBzz", 0.214710761906, 0.000893315075898),
    ("IBxz", 0.0178765751912, 0.000129627296249),
    ("xH", 0.918984961179, 0.00455107965017),
    ("zH", -0.816256856812, 0.00225140598256),
    ("mH", 2.45, 0.02),
    ("IHxx", 0.147496786888, 0.000640700256464),
    ("IHyy", 0.119511786484, 0.00245444440384),
    ("IHzz", 0.0293793112718, 0.000366277717216),
    ("IHxz", -0.0171836655309, 0.000527993839439),
    ("rF", 0.341877060449, 0.000122426879301),
    ("mF", 1.9, 0.02),
    ("IFxx", 0.0851500332546, 0.000346541216905),
    ("IFyy", 0.146642875064, 0.00158129157014),
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
