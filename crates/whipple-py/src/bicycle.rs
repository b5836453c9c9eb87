//! Bicycles: presets, parameter-file text (every format the library reads), and dictionaries with
//! BicycleParameters' keys. The parsing and every check are the library's.

use std::collections::BTreeMap;

use pyo3::prelude::*;
use whipple::advanced::io;
use whipple::advanced::io::Format;
use whipple::advanced::parameters::{Checked, Description, MOORE2012_KEYS, Moore2012Parameters};
use whipple::advanced::table;
use whipple::advanced::table::Form;
use whipple::presets as library_presets;
use whipple::{Bicycle, Error};

use crate::errors::IntoPy;

/// An extra key as Python sees it: (key, text, value, sigma, meaning).
type ExtraRow = (String, String, Option<f64>, Option<f64>, String);

/// A row of the parameter table: (key, symbol, unit, description, linear).
type TableRow = (&'static str, &'static str, &'static str, &'static str, bool);

/// A checked bicycle (the native half of `whipple.Bicycle`).
#[pyclass(name = "NativeBicycle", module = "whipple._whipple", frozen)]
pub struct NativeBicycle {
    pub bicycle: Bicycle,
    pub checked: Checked,
}

impl NativeBicycle {
    pub(crate) fn new(py: Python<'_>, bicycle: Bicycle, strict: bool) -> PyResult<Self> {
        let checked = bicycle.check().py_err(py)?;
        let checked = if strict {
            checked.strict().py_err(py)?
        } else {
            checked
        };
        Ok(NativeBicycle { bicycle, checked })
    }
}

/// A number as BicycleParameters' text form reads it back exactly (shortest round trip).
fn number(x: f64) -> String {
    format!("{x:?}")
}

#[pymethods]
impl NativeBicycle {
    /// The preset of that name.
    #[staticmethod]
    fn preset(py: Python<'_>, name: &str) -> PyResult<Self> {
        let preset = library_presets::find(name).py_err(py)?;
        Self::new(py, preset.bicycle(), false)
    }

    /// A bicycle from the text of a parameter file. `format` is a `--format` name (`toml`,
    /// `json`, `m`, `bp-txt`, `hc-txt`, `yaml`) or None to detect it from `file_name` and the
    /// text, as the command line does.
    #[staticmethod]
    #[pyo3(signature = (text, file_name, format=None, strict=false))]
    fn parse(
        py: Python<'_>,
        text: &str,
        file_name: &str,
        format: Option<&str>,
        strict: bool,
    ) -> PyResult<Self> {
        let format = match format {
            Some(name) => Format::from_name(name).ok_or_else(|| Error::InvalidArgument {
                what: "format",
                rule: format!(
                    "unknown format `{name}` (known: {})",
                    whipple_front::formats::names()
                ),
            }),
            None => Format::detect(file_name, text),
        }
        .py_err(py)?;
        let mut bicycle = io::parse(text, format).py_err(py)?;
        if bicycle.name.is_none() {
            bicycle.name = io::name_from_file_name(file_name, format);
        }
        Self::new(py, bicycle, strict)
    }

    /// A bicycle in the benchmark form from (key, value, sigma) triples with BicycleParameters'
    /// keys (`w`, `c`, `lam`, `g`, `rR`, `mR`, `IRxx`, …; its optional `yB`, `IBxy`, `IRzz`, …
    /// too): read by the library's BicycleParameters reader, so the same rules apply as to a
    /// `<Name>Benchmark.txt` file. Keys take `_mm` after a length and `_deg` after an angle
    /// (`c_mm`, `lam_deg`; σ in the same unit), as TOML and JSON files do.
    #[staticmethod]
    #[pyo3(signature = (items, name=None, source=None, strict=false))]
    fn from_items(
        py: Python<'_>,
        items: Vec<(String, f64, f64)>,
        name: Option<String>,
        source: Option<String>,
        strict: bool,
    ) -> PyResult<Self> {
        // `c_mm`, `lam_deg`, …: in SI by whipple-front, the one reading of the units people use.
        let (items, units) =
            whipple_front::units::si_items(&items, whipple::advanced::table::Form::Benchmark)
                .py_err(py)?;
        let mut text = String::new();
        for (key, value, sigma) in &items {
            if key.is_empty() || key.contains(['=', '#', '\n', '\r']) || key.trim() != key {
                return Err(Error::InvalidParameter {
                    field: key.clone(),
                    value: *value,
                    rule: "not a parameter name".into(),
                })
                .py_err(py);
            }
            text.push_str(key);
            text.push_str(" = ");
            text.push_str(&number(*value));
            if *sigma != 0.0 {
                text.push_str("+/-");
                text.push_str(&number(*sigma));
            }
            text.push('\n');
        }
        let mut bicycle = io::parse(&text, Format::BicycleParametersTxt)
            .map_err(|e| match e {
                // A dictionary has no lines: the key and the rule are what matter.
                Error::Parse { field, message, .. } => {
                    let value = field
                        .as_ref()
                        .and_then(|f| items.iter().find(|(k, _, _)| k == f))
                        .map_or(f64::NAN, |(_, v, _)| *v);
                    Error::InvalidParameter {
                        field: field.unwrap_or_default(),
                        value,
                        rule: message,
                    }
                }
                other => other,
            })
            .py_err(py)?;
        bicycle.name = name.or(bicycle.name);
        bicycle.source = source.or(bicycle.source);
        bicycle.units = units.into_iter().collect();
        Self::new(py, bicycle, strict)
    }

    /// The benchmark parameters (JBike6 bodies combined) as (key, value) pairs in the order of
    /// Meijaard 2007 Table 1.
    fn benchmark(&self) -> Vec<(&'static str, f64)> {
        self.checked.benchmark.fields().to_vec()
    }

    /// Moore 2012's parameters (BicycleParameters' `Moore2012` keys) of the checked bicycle,
    /// in the order of `MOORE2012_KEYS`.
    fn moore2012(&self) -> Vec<(&'static str, f64)> {
        MOORE2012_KEYS
            .iter()
            .copied()
            .zip(Moore2012Parameters::from_benchmark(&self.checked.benchmark).to_array())
            .collect()
    }

    /// A benchmark-form bicycle from Moore 2012's parameters ((key, value) pairs; every one of
    /// the 26 keys required once, `v` accepted and ignored as BicycleParameters' sets carry
    /// it, other keys refused).
    #[staticmethod]
    #[pyo3(signature = (items, name=None, source=None, strict=false))]
    fn from_moore2012(
        py: Python<'_>,
        items: Vec<(String, f64)>,
        name: Option<String>,
        source: Option<String>,
        strict: bool,
    ) -> PyResult<Self> {
        let mut values: [Option<f64>; 26] = [None; 26];
        for (key, value) in &items {
            if key == "v" {
                continue;
            }
            let Some(i) = MOORE2012_KEYS.iter().position(|k| k == key) else {
                return Err(Error::InvalidParameter {
                    field: key.clone(),
                    value: *value,
                    rule: format!(
                        "not a key of Moore 2012's parameterization ({})",
                        MOORE2012_KEYS.join(", ")
                    ),
                })
                .py_err(py);
            };
            if values[i].replace(*value).is_some() {
                return Err(Error::InvalidParameter {
                    field: key.clone(),
                    value: *value,
                    rule: "is given twice".into(),
                })
                .py_err(py);
            }
        }
        let missing: Vec<&str> = MOORE2012_KEYS
            .iter()
            .zip(&values)
            .filter(|(_, v)| v.is_none())
            .map(|(k, _)| *k)
            .collect();
        if let Some(first) = missing.first() {
            return Err(Error::InvalidParameter {
                field: first.to_string(),
                value: f64::NAN,
                rule: format!("missing: {}", missing.join(", ")),
            })
            .py_err(py);
        }
        let benchmark = Moore2012Parameters::from_array(values.map(|v| v.unwrap_or(0.0)))
            .to_benchmark()
            .py_err(py)?;
        let bicycle = Bicycle {
            name,
            source,
            ..Bicycle::new(Description::Benchmark(benchmark))
        };
        Self::new(py, bicycle, strict)
    }

    /// The front assembly's moment of inertia about the steer axis, I_Aλλ \[kg m²\].
    fn front_assembly_steer_inertia(&self) -> f64 {
        self.checked.benchmark.front_assembly_steer_inertia()
    }

    /// Standard deviations by key of the bicycle's own form (only those given).
    fn sigma(&self) -> BTreeMap<String, f64> {
        self.bicycle.sigma.clone()
    }

    /// `benchmark` or `jbike6`: the form the bicycle was described in.
    fn form(&self) -> &'static str {
        match self.bicycle.description.form() {
            Form::Benchmark => "benchmark",
            Form::Jbike6 => "jbike6",
        }
    }

    /// The parameters of the bicycle's own form as (key, value) pairs (JBike6's `.m` names for
    /// a JBike6-form bicycle).
    fn own_form(&self) -> Vec<(&'static str, f64)> {
        let form = self.bicycle.description.form();
        table::parameters(form)
            .iter()
            .zip(self.bicycle.description.values())
            .map(|(p, v)| (p.key, v))
            .collect()
    }

    #[getter]
    fn name(&self) -> Option<String> {
        self.bicycle.name.clone()
    }

    #[getter]
    fn source(&self) -> Option<String> {
        self.bicycle.source.clone()
    }

    /// The file's notes and the checks' warnings: the core's `Notice`s as dicts (severity,
    /// field, message, violation_percent where one applies, affects).
    fn notices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::serialized(py, &self.checked.notices)
    }

    /// The keys of the file that are not Whipple parameters: (key, text, value, sigma, meaning).
    fn extras(&self) -> Vec<ExtraRow> {
        self.bicycle
            .extras
            .iter()
            .map(|e| {
                (
                    e.key.clone(),
                    e.text.clone(),
                    e.value,
                    e.sigma,
                    e.meaning.clone(),
                )
            })
            .collect()
    }

    /// The bicycle as the text of a parameter file in `format` (a `--format` name).
    fn write(&self, py: Python<'_>, format: &str) -> PyResult<String> {
        let format = Format::from_name(format)
            .ok_or_else(|| Error::InvalidArgument {
                what: "format",
                rule: format!(
                    "unknown format `{format}` (known: {})",
                    whipple_front::formats::names()
                ),
            })
            .py_err(py)?;
        io::write(&self.bicycle, format).py_err(py)
    }

    /// The same bicycle with some parameters changed ((name, value) pairs), by the names a
    /// design axis takes (whipple-front's `design::replace`: keys, aliases such as `trail`,
    /// `_deg` after an angle), their standard deviations dropped, named `… (edited)`.
    fn replace(&self, py: Python<'_>, changes: Vec<(String, f64)>) -> PyResult<Self> {
        let mut bicycle = whipple_front::design::replace(&self.bicycle, &changes).py_err(py)?;
        // The checks' warnings are redone on the new values.
        bicycle.notices.clear();
        Self::new(py, bicycle, false)
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.bicycle == other.bicycle
    }
}

/// The presets: (name, summary, source).
#[pyfunction]
pub fn presets() -> Vec<(&'static str, &'static str, &'static str)> {
    library_presets::PRESETS
        .iter()
        .map(|p| (p.name, p.summary, p.source))
        .collect()
}

/// The file formats: (`--format` name, description).
#[pyfunction]
pub fn formats() -> Vec<(&'static str, &'static str)> {
    io::FORMATS.iter().map(|(_, n, d)| (*n, *d)).collect()
}

/// The parameter table of a form (`benchmark` or `jbike6`): (key, symbol, unit, description,
/// linear).
#[pyfunction]
#[pyo3(signature = (form="benchmark"))]
pub fn parameter_table(form: &str) -> PyResult<Vec<TableRow>> {
    let form = match form {
        "benchmark" => Form::Benchmark,
        "jbike6" => Form::Jbike6,
        other => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "unknown form `{other}` (benchmark or jbike6)"
            )));
        }
    };
    Ok(table::parameters(form)
        .iter()
        .map(|p| (p.key, p.symbol, p.unit, p.description, p.linear))
        .collect())
}
