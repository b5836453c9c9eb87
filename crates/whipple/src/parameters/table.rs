//! The one table of every parameter: name, file key, symbol, unit, description and form. The
//! serde names and `fields()` of [`BenchmarkParameters`](super::BenchmarkParameters) and
//! [`Jbike6Parameters`](super::Jbike6Parameters), the comments of the TOML writer, the `.m`
//! variables, the CLI's `show` and the web API's `GET /api/parameters` are all read from here.

use serde::Serialize;

/// Which description of a bicycle a parameter belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Form {
    /// The 25 benchmark parameters of Meijaard et al. 2007 (Table 1) plus g.
    Benchmark,
    /// JBike6's seven-body description (wheels, rider, frame, rack, fork, basket).
    Jbike6,
}

/// One parameter of a bicycle description.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct ParameterInfo {
    /// The Rust field (`i_bxx`; for JBike6 the path of fields, `rider.inertia[0]`).
    pub name: &'static str,
    /// The key in files and messages: the benchmark keys of Meijaard 2007 and BicycleParameters
    /// (`IBxx`), JBike6's `.m` variables (`mrider`, `Irider(1)`).
    pub key: &'static str,
    /// The path inside the form's TOML/JSON table (`IBxx`; `rider.m`, `rider.I[1]`).
    pub path: &'static str,
    /// The paper's symbol (`I_Bxx`, `λ`).
    pub symbol: &'static str,
    /// SI unit (`kg m^2`, `rad`; empty for none).
    pub unit: &'static str,
    /// What it is, in a few words.
    pub description: &'static str,
    /// The description it belongs to.
    pub form: Form,
    /// Whether the linearized model (M, C₁, K₀, K₂) depends on it (I_Byy and I_Hyy it does
    /// not: they enter only the non-linear model).
    pub linear: bool,
}

/// The unit of every angle in the table (and of every angle inside the library).
pub(crate) const ANGLE_UNIT: &str = "rad";

impl ParameterInfo {
    /// Whether the parameter is an angle (its unit is `"rad"`): the one a front end may
    /// take in degrees.
    pub fn is_angle(&self) -> bool {
        self.unit == ANGLE_UNIT
    }

    /// `description [unit]`, as the TOML writer's comments and tables print it.
    pub fn doc(&self) -> String {
        if self.unit.is_empty() {
            self.description.to_string()
        } else {
            format!("{} [{}]", self.description, self.unit)
        }
    }
}

/// The parameters of a form, in file order (Meijaard 2007 Table 1 for the benchmark form; the
/// original study's listing for JBike6).
pub fn parameters(form: Form) -> &'static [ParameterInfo] {
    match form {
        Form::Benchmark => &super::benchmark::BENCHMARK_TABLE,
        Form::Jbike6 => &super::jbike6::JBIKE6_TABLE,
    }
}

/// The parameter with this file key in either form (`IBxx`, `mrider`, `Irider(1)`), or with this
/// TOML path in the JBike6 form (`rider.m`).
pub(crate) fn find(key: &str) -> Option<&'static ParameterInfo> {
    parameters(Form::Benchmark)
        .iter()
        .chain(parameters(Form::Jbike6))
        .find(|p| p.key == key || (p.form == Form::Jbike6 && p.path == key))
}

/// The position of a key in its form's table.
pub fn index_of(form: Form, key: &str) -> Option<usize> {
    parameters(form).iter().position(|p| p.key == key)
}

/// Meaning and unit of a benchmark or JBike6 key (`"wheelbase [m]"`), for comments and tables;
/// `None` for a key that is neither.
pub fn key_doc(key: &str) -> Option<String> {
    find(key).map(ParameterInfo::doc)
}
