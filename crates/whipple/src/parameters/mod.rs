//! What a bicycle is: numbers only. The benchmark form (Meijaard 2007), JBike6's seven-body
//! form and its conversion, named presets, and the parameter file formats.

pub mod benchmark;
pub mod io;
pub mod jbike6;
pub mod presets;

use serde::{Deserialize, Serialize};

pub use benchmark::BenchmarkParameters;
pub use jbike6::{Jbike6FrontBody, Jbike6Parameters, Jbike6RearBody, Jbike6Wheel, JBIKE6_GRAVITY};

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

/// A described bicycle with an optional name and source (citation).
#[derive(Debug, Clone, PartialEq)]
pub struct Bicycle {
    /// A short name (a preset's name, or the file's `name` key).
    pub name: Option<String>,
    /// Where the numbers come from.
    pub source: Option<String>,
    /// The numbers.
    pub description: Description,
}

impl Bicycle {
    /// A bicycle from its description, with no name or source.
    pub fn new(description: Description) -> Self {
        Bicycle {
            name: None,
            source: None,
            description,
        }
    }

    /// The benchmark parameters, converted from JBike6's form where needed, validated.
    pub fn benchmark(&self) -> Result<BenchmarkParameters> {
        match &self.description {
            Description::Benchmark(p) => {
                p.validate()?;
                Ok(*p)
            }
            Description::Jbike6(p) => p.to_benchmark(),
        }
    }

    /// The JBike6 form, where the bicycle was described that way.
    pub fn jbike6(&self) -> Option<&Jbike6Parameters> {
        match &self.description {
            Description::Jbike6(p) => Some(p),
            Description::Benchmark(_) => None,
        }
    }
}
