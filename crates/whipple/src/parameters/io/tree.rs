//! TOML and JSON: both parsed into one small tree with positions (TOML's from its spans;
//! JSON's, which serde_json does not keep, from the key's first appearance in the text), then
//! read against the parameter table, so that both formats give the same errors naming the key.

use std::collections::BTreeMap;

use super::keyvalue::extra_meaning;
use super::{Format, error_at, line_column, parse_number};
use crate::error::{Result, shorten};
use crate::parameters::table::{Form, TypedUnit, find_typed};
use crate::parameters::{
    BENCHMARK_TABLE, BenchmarkParameters, Bicycle, Description, Extra, JBIKE6_GRAVITY,
    JBIKE6_TABLE, Jbike6Parameters, Notice, STEER_INERTIA_KEY,
};

/// The note a bicycle read with `IAlamlam` carries: what was derived.
pub(crate) fn steer_note(i_a: f64, i_hzz: f64) -> Notice {
    Notice::note(
        "IHzz",
        format!(
            "IHzz = {} kg m^2 derived from {STEER_INERTIA_KEY} = {} kg m^2, the front \
             assembly's moment about the steer axis, keeping every other parameter as given",
            super::write::number(i_hzz),
            super::write::number(i_a)
        ),
    )
}

/// A value with its position (line and column 1-based; 0 when unknown).
#[derive(Debug, Clone)]
struct Node {
    line: usize,
    column: usize,
    value: Value,
}

#[derive(Debug, Clone)]
enum Value {
    Number(f64, String),
    Text(String),
    Bool,
    Array(Vec<Node>),
    Table(Vec<(String, Node)>),
    Other(&'static str),
    Bad(String),
}

impl Value {
    fn kind(&self) -> &'static str {
        match self {
            Value::Number(..) => "a number",
            Value::Text(_) => "a string",
            Value::Bool => "a boolean",
            Value::Array(_) => "an array",
            Value::Table(_) => "a table",
            Value::Other(k) => k,
            Value::Bad(_) => "a value that is not a finite number",
        }
    }
}

struct Reader {
    format: Format,
}

pub(crate) fn parse_toml(text: &str) -> Result<Bicycle> {
    let format = Format::Toml;
    let table = toml::de::DeTable::parse(text).map_err(|e| {
        let (line, column) = e
            .span()
            .map_or((0, 0), |span| line_column(text, span.start));
        error_at(format, line, column, None, e.message().trim().to_string())
    })?;
    let root = toml_node(text, table.get_ref(), table.span().start, false);
    Reader { format }.layout(&root)
}

fn toml_node(text: &str, table: &toml::de::DeTable<'_>, offset: usize, _inline: bool) -> Node {
    let (line, column) = line_column(text, offset);
    let entries = table
        .iter()
        .map(|(k, v)| {
            let mut node = toml_value(text, v);
            if node.line == 0 {
                let (l, c) = line_column(text, k.span().start);
                node.line = l;
                node.column = c;
            }
            (k.get_ref().to_string(), node)
        })
        .collect();
    Node {
        line,
        column,
        value: Value::Table(entries),
    }
}

fn toml_value(text: &str, v: &toml::Spanned<toml::de::DeValue<'_>>) -> Node {
    use toml::de::DeValue;
    let (line, column) = line_column(text, v.span().start);
    let value = match v.get_ref() {
        DeValue::Integer(i) => {
            let digits = i.as_str().replace('_', "");
            let digits = digits.trim_start_matches('+');
            let (negative, digits) = match digits.strip_prefix('-') {
                Some(d) => (true, d),
                None => (false, digits),
            };
            let digits = digits
                .trim_start_matches("0x")
                .trim_start_matches("0o")
                .trim_start_matches("0b");
            match i128::from_str_radix(digits, i.radix()) {
                Ok(n) => {
                    let x = n as f64;
                    Value::Number(if negative { -x } else { x }, i.as_str().to_string())
                }
                Err(_) => Value::Bad(format!("`{}` is not a number", shorten(i.as_str(), 40))),
            }
        }
        DeValue::Float(f) => {
            let s = f.as_str().replace('_', "");
            match parse_number(&s) {
                Ok(x) => Value::Number(x, s),
                Err(e) => Value::Bad(e),
            }
        }
        DeValue::String(s) => Value::Text(s.to_string()),
        DeValue::Boolean(_) => Value::Bool,
        DeValue::Datetime(_) => Value::Other("a date"),
        DeValue::Array(a) => Value::Array(a.iter().map(|e| toml_value(text, e)).collect()),
        DeValue::Table(t) => return toml_node(text, t, v.span().start, true),
    };
    Node {
        line,
        column,
        value,
    }
}

pub(crate) fn parse_json(text: &str) -> Result<Bicycle> {
    let format = Format::Json;
    let value = super::json_without_duplicates(text).map_err(|e| {
        let message = e.to_string();
        let message = match message.rfind(" at line ") {
            Some(p) => message[..p].to_string(),
            None => message,
        };
        error_at(format, e.line(), e.column(), None, message)
    })?;
    let root = json_node(text, &value, None);
    Reader { format }.layout(&root)
}

fn json_node(text: &str, v: &serde_json::Value, key: Option<&str>) -> Node {
    use serde_json::Value as J;
    // serde_json keeps no positions: place a value at its key's first appearance.
    let (line, column) = key
        .and_then(|k| {
            let quoted = serde_json::to_string(k).ok()?;
            text.find(&quoted).map(|p| line_column(text, p))
        })
        .unwrap_or((0, 0));
    let value = match v {
        J::Number(n) => match n.as_f64() {
            Some(x) if x.is_finite() => Value::Number(x, n.to_string()),
            _ => Value::Bad(format!(
                "`{}` is not a finite number",
                shorten(&n.to_string(), 40)
            )),
        },
        J::String(s) => Value::Text(s.clone()),
        J::Bool(_) => Value::Bool,
        J::Null => Value::Other("null"),
        J::Array(a) => Value::Array(a.iter().map(|e| json_node(text, e, None)).collect()),
        J::Object(o) => Value::Table(
            o.iter()
                .map(|(k, e)| (k.clone(), json_node(text, e, Some(k))))
                .collect(),
        ),
    };
    Node {
        line,
        column,
        value,
    }
}

fn entries(node: &Node) -> &[(String, Node)] {
    match &node.value {
        Value::Table(t) => t,
        _ => &[],
    }
}

impl Reader {
    fn err(&self, node: &Node, field: &str, message: impl Into<String>) -> crate::Error {
        error_at(self.format, node.line, node.column, Some(field), message)
    }

    fn layout(&self, root: &Node) -> Result<Bicycle> {
        let mut bike = Bicycle::default();
        let mut description = None;
        for (key, node) in entries(root) {
            match key.as_str() {
                "name" | "source" => {
                    let Value::Text(s) = &node.value else {
                        return Err(self.err(node, key, format!("`{key}` must be a string, not {}", node.value.kind())));
                    };
                    if key == "name" {
                        bike.name = Some(s.clone());
                    } else {
                        bike.source = Some(s.clone());
                    }
                }
                "benchmark" | "jbike6" => {
                    if matches!(node.value, Value::Array(_)) {
                        return Err(self.err(node, key, format!("`{key}` must be one table, `[{key}]`, not an array of tables `[[{key}]]`")));
                    }
                    if !matches!(node.value, Value::Table(_)) {
                        return Err(self.err(node, key, format!("`{key}` must be a table of parameters, not {}", node.value.kind())));
                    }
                    if description.is_some() {
                        return Err(self.err(node, key, "give either a `benchmark` table or a `jbike6` table, not both"));
                    }
                    description = Some(if key == "benchmark" {
                        Description::Benchmark(self.benchmark(node, &mut bike)?)
                    } else {
                        Description::Jbike6(self.jbike6(node, &mut bike)?)
                    });
                }
                "extra" => self.extra(node, &mut bike)?,
                other => {
                    return Err(self.err(node, other, format!(
                        "unknown key `{}` (a file holds `name`, `source`, one of `benchmark` or `jbike6`, and optionally `extra`)",
                        shorten(other, 40)
                    )))
                }
            }
        }
        match description {
            Some(d) => bike.description = d,
            None => {
                return Err(error_at(
                    self.format,
                    0,
                    0,
                    Some("benchmark"),
                    "missing the bicycle: a `benchmark` table or a `jbike6` table",
                ));
            }
        }
        Ok(bike)
    }

    /// A number, or `{ value, sigma }`.
    fn number(&self, node: &Node, field: &str, sigma: &mut BTreeMap<String, f64>) -> Result<f64> {
        match &node.value {
            Value::Number(x, _) => Ok(*x),
            Value::Bad(why) => Err(self.err(node, field, why.clone())),
            Value::Table(t) => {
                let mut value = None;
                let mut s = None;
                for (k, n) in t {
                    match (k.as_str(), &n.value) {
                        ("value", Value::Number(x, _)) => value = Some(*x),
                        ("sigma", Value::Number(x, _)) => s = Some(*x),
                        ("value" | "sigma", Value::Bad(why)) => return Err(self.err(n, field, why.clone())),
                        ("value" | "sigma", other) => {
                            return Err(self.err(n, field, format!("`{field}.{k}` must be a number, not {}", other.kind())))
                        }
                        (other, _) => {
                            return Err(self.err(n, field, format!(
                                "unknown key `{}` in `{field}` (a measured value is {{ value = ..., sigma = ... }})",
                                shorten(other, 40)
                            )))
                        }
                    }
                }
                let Some(value) = value else {
                    return Err(self.err(node, field, format!("`{field}` needs a `value`")));
                };
                if let Some(s) = s {
                    if s < 0.0 {
                        return Err(self.err(
                            node,
                            field,
                            format!("the standard deviation of `{field}` cannot be negative"),
                        ));
                    }
                    if s > 0.0 {
                        sigma.insert(field.to_string(), s);
                    }
                }
                Ok(value)
            }
            other => Err(self.err(
                node,
                field,
                format!(
                    "`{field}` must be a number (or {{ value, sigma }}), not {}",
                    other.kind()
                ),
            )),
        }
    }

    /// A parameter's value as written under `name` (`c`, `c_mm`, `rider.x_mm`), in SI units:
    /// value and σ converted from the suffix's unit, which is recorded under the file key `key`
    /// for the writers; σ is kept under `key`.
    fn typed(
        &self,
        node: &Node,
        name: &str,
        key: &str,
        unit: Option<TypedUnit>,
        bike: &mut Bicycle,
    ) -> Result<f64> {
        let mut sigma = BTreeMap::new();
        let x = self.number(node, name, &mut sigma)?;
        let convert = |x: f64| unit.map_or(x, |u| u.to_si(x));
        if let Some(s) = sigma.get(name) {
            bike.sigma.insert(key.to_string(), convert(*s));
        }
        match unit {
            Some(u) => bike.units.insert(key.to_string(), u),
            None => bike.units.remove(key),
        };
        Ok(convert(x))
    }

    /// Refuses a parameter given twice, in two units (`c` and `c_mm`), naming both.
    fn once(
        &self,
        written: &mut [Option<String>],
        i: usize,
        name: &str,
        node: &Node,
    ) -> Result<()> {
        if let Some(first) = &written[i] {
            return Err(self.err(
                node,
                name,
                format!(
                    "`{}` and `{}` give the same parameter twice: keep one",
                    shorten(first, 40),
                    shorten(name, 40)
                ),
            ));
        }
        written[i] = Some(name.to_string());
        Ok(())
    }

    fn benchmark(&self, node: &Node, bike: &mut Bicycle) -> Result<BenchmarkParameters> {
        let mut values: [Option<f64>; 26] = [None; 26];
        let mut written: Vec<Option<String>> = vec![None; BENCHMARK_TABLE.len()];
        let mut steer: Option<(f64, &Node)> = None;
        for (key, n) in entries(node) {
            if key == STEER_INERTIA_KEY {
                let mut sigma = BTreeMap::new();
                let value = self.number(n, key, &mut sigma)?;
                if !sigma.is_empty() {
                    return Err(self.err(
                        n,
                        key,
                        format!(
                            "a standard deviation of `{STEER_INERTIA_KEY}` is not carried to \
                             IHzz yet: give its value alone, or IHzz with its own"
                        ),
                    ));
                }
                steer = Some((value, n));
                continue;
            }
            let found = find_typed(Form::Benchmark, key)
                .map_err(|rule| self.err(n, key, format!("`{}`: {rule}", shorten(key, 40))))?;
            let Some((i, unit)) = found else {
                return Err(self.err(
                    n,
                    key,
                    format!(
                        "unknown key `{}` in the benchmark table (keys: {}; or \
                         {STEER_INERTIA_KEY}, the front assembly's moment about the steer axis, \
                         instead of IHzz)",
                        shorten(key, 40),
                        BENCHMARK_TABLE
                            .iter()
                            .map(|p| p.key)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            };
            self.once(&mut written, i, key, n)?;
            values[i] = Some(self.typed(n, key, BENCHMARK_TABLE[i].key, unit, bike)?);
        }
        if let Some((_, n)) = steer {
            let ihzz = BENCHMARK_TABLE
                .iter()
                .position(|p| p.key == "IHzz")
                .unwrap_or(20);
            if values[ihzz].is_some() {
                return Err(self.err(
                    n,
                    STEER_INERTIA_KEY,
                    format!(
                        "give either IHzz or {STEER_INERTIA_KEY} (the front assembly's moment \
                         about the steer axis, from which IHzz is derived), not both"
                    ),
                ));
            }
            values[ihzz] = Some(0.0);
        }
        let missing: Vec<&str> = BENCHMARK_TABLE
            .iter()
            .zip(values.iter())
            .filter(|(_, v)| v.is_none())
            .map(|(p, _)| p.key)
            .collect();
        if let Some(first) = missing.first() {
            return Err(self.err(
                node,
                first,
                format!(
                    "missing keys in the benchmark table: {}",
                    missing.join(", ")
                ),
            ));
        }
        let b = BenchmarkParameters::from_array(values.map(|v| v.unwrap_or(0.0)));
        match steer {
            None => Ok(b),
            Some((i_a, _)) => {
                let b = b.with_front_assembly_steer_inertia(i_a)?;
                bike.notices.push(steer_note(i_a, b.i_hzz));
                Ok(b)
            }
        }
    }

    fn jbike6(&self, node: &Node, bike: &mut Bicycle) -> Result<Jbike6Parameters> {
        let mut values: Vec<Option<f64>> = vec![None; JBIKE6_TABLE.len()];
        let mut written: Vec<Option<String>> = vec![None; JBIKE6_TABLE.len()];
        let bodies = [
            "rear_wheel",
            "front_wheel",
            "rider",
            "frame",
            "rack",
            "fork",
            "basket",
        ];
        for (key, n) in entries(node) {
            if bodies.contains(&key.as_str()) {
                if !matches!(n.value, Value::Table(_)) {
                    return Err(self.err(
                        n,
                        key,
                        format!("`{key}` must be a table, not {}", n.value.kind()),
                    ));
                }
                for (field, v) in entries(n) {
                    let path = format!("{key}.{field}");
                    if field == "I" {
                        let Value::Array(items) = &v.value else {
                            return Err(self.err(
                                v,
                                &path,
                                format!(
                                    "`{path}` must be three numbers [I11, I22, Izz], not {}",
                                    v.value.kind()
                                ),
                            ));
                        };
                        if items.len() != 3 {
                            return Err(self.err(v, &path, format!("`{path}` needs exactly three numbers [I11, I22, Izz], found {}", items.len())));
                        }
                        for (k, item) in items.iter().enumerate() {
                            let p = format!("{key}.I[{}]", k + 1);
                            let Some(i) = JBIKE6_TABLE.iter().position(|t| t.path == p) else {
                                continue;
                            };
                            let item = if item.line == 0 {
                                Node {
                                    line: v.line,
                                    column: v.column,
                                    ..item.clone()
                                }
                            } else {
                                item.clone()
                            };
                            values[i] =
                                Some(self.number(&item, JBIKE6_TABLE[i].key, &mut bike.sigma)?);
                        }
                        continue;
                    }
                    let found = find_typed(Form::Jbike6, &path).map_err(|rule| {
                        self.err(v, &path, format!("`{}`: {rule}", shorten(&path, 60)))
                    })?;
                    let Some((i, unit)) = found else {
                        let allowed: Vec<&str> = JBIKE6_TABLE
                            .iter()
                            .filter_map(|t| t.path.strip_prefix(&format!("{key}.")))
                            .map(|f| f.split('[').next().unwrap_or(f))
                            .fold(Vec::new(), |mut a, f| {
                                if !a.contains(&f) {
                                    a.push(f)
                                }
                                a
                            });
                        return Err(self.err(
                            v,
                            &path,
                            format!(
                                "unknown key `{}` in `{key}` (keys: {})",
                                shorten(field, 40),
                                allowed.join(", ")
                            ),
                        ));
                    };
                    self.once(&mut written, i, &path, v)?;
                    values[i] = Some(self.typed(v, &path, JBIKE6_TABLE[i].key, unit, bike)?);
                }
                continue;
            }
            let found = find_typed(Form::Jbike6, key)
                .map_err(|rule| self.err(n, key, format!("`{}`: {rule}", shorten(key, 40))))?;
            let Some((i, unit)) = found.filter(|(i, _)| !JBIKE6_TABLE[*i].path.contains('.'))
            else {
                return Err(self.err(n, key, format!(
                    "unknown key `{}` in the jbike6 table (keys: wheelbase, head_angle, trail, gravity, {})",
                    shorten(key, 40),
                    bodies.join(", ")
                )));
            };
            self.once(&mut written, i, key, n)?;
            values[i] = Some(self.typed(n, key, JBIKE6_TABLE[i].key, unit, bike)?);
        }
        if values[3].is_none() {
            values[3] = Some(JBIKE6_GRAVITY);
        }
        let missing: Vec<&str> = JBIKE6_TABLE
            .iter()
            .zip(values.iter())
            .filter(|(_, v)| v.is_none())
            .map(|(p, _)| p.path)
            .collect();
        if let Some(first) = missing.first() {
            return Err(self.err(
                node,
                first,
                format!("missing keys in the jbike6 table: {}", missing.join(", ")),
            ));
        }
        let mut array = [0.0; 51];
        for (a, v) in array.iter_mut().zip(values) {
            *a = v.unwrap_or(0.0);
        }
        Ok(Jbike6Parameters::from_array(array))
    }

    fn extra(&self, node: &Node, bike: &mut Bicycle) -> Result<()> {
        if !matches!(node.value, Value::Table(_)) {
            return Err(self.err(node, "extra", "`extra` must be a table"));
        }
        for (key, n) in entries(node) {
            let Some(meaning) = extra_meaning(key) else {
                return Err(self.err(n, key, format!(
                    "unknown key `{}` in `extra` (it holds the keys of other models that BicycleParameters and HumanControl files carry: v, d1, d3, xcl, zcl, ...)",
                    shorten(key, 40)
                )));
            };
            let mut sigma = BTreeMap::new();
            let (text, value) = match &n.value {
                Value::Text(s) => (s.clone(), None),
                _ => {
                    let x = self.number(n, key, &mut sigma)?;
                    let text = match &n.value {
                        Value::Number(_, t) => t.clone(),
                        _ => crate::error::short_number(x),
                    };
                    (text, Some(x))
                }
            };
            bike.notices
                .push(Notice::note(key.clone(), format!("`{key}`: {meaning}")));
            bike.extras.push(Extra {
                key: key.clone(),
                text,
                value,
                sigma: sigma.get(key).copied(),
                meaning: meaning.to_string(),
            });
        }
        Ok(())
    }
}

/// Which form a bicycle file's table describes.
#[allow(dead_code)]
pub(crate) fn form_of(bike: &Bicycle) -> Form {
    bike.description.form()
}
