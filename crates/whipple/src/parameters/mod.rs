//! What a bicycle is: numbers only. The benchmark form (Meijaard 2007), JBike6's seven-body
//! form and its conversion, named presets, and the parameter file formats.

pub(crate) mod benchmark;
pub(crate) mod check;
pub(crate) mod io;
pub(crate) mod jbike6;
pub(crate) mod measured;
pub(crate) mod moore2012;
pub mod presets;
pub(crate) mod principal;
pub(crate) mod rider_lean;
pub(crate) mod steer;
pub(crate) mod table;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub(crate) use benchmark::BENCHMARK_TABLE;
pub use benchmark::BenchmarkParameters;
pub use check::{Notice, Severity};
pub use jbike6::Jbike6Parameters;
pub(crate) use jbike6::{
    JBIKE6_GRAVITY, JBIKE6_TABLE, Jbike6FrontBody, Jbike6RearBody, Jbike6Wheel,
};
pub use moore2012::{MOORE2012_KEYS, Moore2012Parameters};
pub use principal::{PRINCIPAL_KEYS, PrincipalBody, PrincipalParameters};
pub use rider_lean::{
    MOORE_RIDER_LEAN2012_KEYS, MooreRiderLean2012Parameters, RiderLeanParameters, UpperBody,
};
pub(crate) use steer::STEER_INERTIA_KEY;
pub(crate) use table::Form;
pub(crate) use table::ParameterInfo;
pub(crate) use table::TypedUnit;

use crate::error::Result;

/// A bicycle as it was described: in the benchmark form or in JBike6's form.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Description {
    /// The 25 benchmark parameters of Meijaard 2007 plus g.
    Benchmark(BenchmarkParameters),
    /// JBike6's wheels and bodies.
    Jbike6(Jbike6Parameters),
}

impl Description {
    /// The form of this description.
    pub fn form(&self) -> Form {
        match self {
            Description::Benchmark(_) => Form::Benchmark,
            Description::Jbike6(_) => Form::Jbike6,
        }
    }

    /// The values of the form's parameters, in the order of its table
    /// ([`table::parameters`]).
    pub fn values(&self) -> Vec<f64> {
        match self {
            Description::Benchmark(p) => p.to_array().to_vec(),
            Description::Jbike6(p) => p.to_array().to_vec(),
        }
    }
}

/// A key of a parameter file that is not a parameter of the Whipple bicycle (an operating speed
/// `v`, redundant geometry `d1`, `d3`, another model's `xcl`, a separately measured fork `S`),
/// kept as written so that it is reported and written back.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Extra {
    /// The key as written.
    pub key: String,
    /// The value as written (a number, or the text of a YAML field).
    pub text: String,
    /// The number, where it is one.
    pub value: Option<f64>,
    /// Its standard deviation, where the file gave one.
    pub sigma: Option<f64>,
    /// What it means, from the owning project's documentation.
    pub meaning: String,
}

/// A described bicycle with an optional name and source (citation), the standard deviations of
/// its parameters where known, and what its file held besides.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Bicycle {
    /// A short name (a preset's name, or the file's `name` key).
    pub name: Option<String>,
    /// Where the numbers come from.
    pub source: Option<String>,
    /// The numbers.
    pub description: Description,
    /// Standard deviations σ of the parameters of the description's own form, by file key
    /// (`IBxx`; `mrider`, `Irider(1)`); a parameter not listed has σ = 0.
    pub sigma: BTreeMap<String, f64>,
    /// The file's keys that are not parameters of the Whipple model, in file order.
    pub extras: Vec<Extra>,
    /// What reading the file found worth saying (unused keys, redundant values that disagree).
    pub notices: Vec<Notice>,
    /// The unit each parameter was typed in where it was not SI, by file key as `sigma` is
    /// (`c` → millimetres for a TOML or JSON file's `c_mm`): the values themselves are SI; the
    /// TOML and JSON writers write these keys back in the unit read. Empty for SI.
    pub units: BTreeMap<String, TypedUnit>,
}

impl Default for Description {
    fn default() -> Self {
        Description::Benchmark(BenchmarkParameters::meijaard2007())
    }
}

/// A bicycle that passed its checks: its benchmark parameters and every warning and note.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    /// The benchmark parameters (JBike6 bodies combined).
    pub benchmark: BenchmarkParameters,
    /// The file's notes and the checks' warnings, in that order.
    pub notices: Vec<Notice>,
}

impl Checked {
    /// Fails on any warning (notes pass): a strict reading ([`crate::Error::WarningsRefused`]).
    pub fn strict(self) -> Result<Self> {
        check::strict(&self.notices)?;
        Ok(self)
    }

    /// The warnings only.
    pub fn warnings(&self) -> impl Iterator<Item = &Notice> {
        self.notices.iter().filter(|n| n.is_warning())
    }
}

impl Bicycle {
    /// A bicycle from its description, with no name or source.
    pub fn new(description: Description) -> Self {
        Bicycle {
            description,
            ..Bicycle::default()
        }
    }

    /// Checks the bicycle: an error where the equations would be meaningless, otherwise its
    /// benchmark parameters with every warning and note (see [`BenchmarkParameters::check`] and
    /// [`Jbike6Parameters::check`]).
    ///
    /// ```
    /// use whipple::presets;
    /// let checked = presets::find("benchmark")?.bicycle().check()?;
    /// assert_eq!(checked.notices.len(), 0);
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn check(&self) -> Result<Checked> {
        let mut notices = self.notices.clone();
        let benchmark = match &self.description {
            Description::Benchmark(p) => {
                notices.extend(p.check()?);
                *p
            }
            Description::Jbike6(p) => {
                let (b, more) = p.to_benchmark_checked()?;
                notices.extend(more);
                b
            }
        };
        Ok(Checked { benchmark, notices })
    }

    /// The standard deviation of a parameter of the bicycle's own form (0 where not given).
    pub fn sigma_of(&self, key: &str) -> f64 {
        self.sigma.get(key).copied().unwrap_or(0.0)
    }

    /// `true` when some parameter carries a non-zero standard deviation.
    pub fn has_uncertainty(&self) -> bool {
        self.sigma.values().any(|s| *s > 0.0)
    }

    /// The benchmark parameters, converted from JBike6's form where needed, checked (warnings
    /// do not fail it; see [`Bicycle::check`]).
    pub fn benchmark(&self) -> Result<BenchmarkParameters> {
        self.check().map(|c| c.benchmark)
    }

    /// The JBike6 form, where the bicycle was described that way.
    pub fn jbike6(&self) -> Option<&Jbike6Parameters> {
        match &self.description {
            Description::Jbike6(p) => Some(p),
            Description::Benchmark(_) => None,
        }
    }
}
