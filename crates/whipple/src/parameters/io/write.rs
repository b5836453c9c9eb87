//! Writers: every number in its shortest round-trip form, every standard deviation and every
//! extra key kept, names and sources escaped so that no text can break the file's syntax.

use super::Format;
use crate::error::{Error, Result};
use crate::parameters::{
    BENCHMARK_TABLE, Bicycle, Description, Extra, JBIKE6_TABLE, Jbike6Parameters, MOORE2012_KEYS,
    Moore2012Parameters, PRINCIPAL_KEYS, ParameterInfo, PrincipalBody, PrincipalParameters,
    TypedUnit,
};

pub(crate) fn write(bike: &Bicycle, format: Format) -> Result<String> {
    for (key, value) in bike
        .description
        .values()
        .iter()
        .zip(table_of(bike))
        .map(|(v, p)| (p.key, *v))
    {
        if !value.is_finite() {
            return Err(Error::InvalidParameter {
                field: key.to_string(),
                value,
                rule: "must be a finite number to be written to a file".into(),
            });
        }
    }
    match format {
        Format::Toml => Ok(toml(bike)),
        Format::Json => Ok(json(bike)),
        Format::Jbike6M => match &bike.description {
            Description::Jbike6(_) => Ok(matlab(bike)),
            // The benchmark form as JBike6's bodies: frame = B, fork = H, the rest absent.
            Description::Benchmark(b) => Ok(matlab(&Bicycle {
                description: Description::Jbike6(Jbike6Parameters::from_benchmark(b)),
                sigma: Default::default(),
                ..bike.clone()
            })),
        },
        Format::BicycleParametersTxt | Format::HumanControlTxt | Format::Yaml => {
            match &bike.description {
                Description::Benchmark(_) => Ok(if format == Format::Yaml {
                    yaml(bike)
                } else {
                    key_value(bike, format)
                }),
                Description::Jbike6(_) => Err(Error::InvalidArgument {
                    what: "format",
                    rule: format!(
                        "{} holds the benchmark form only: convert the JBike6 bodies to it first",
                        format.label()
                    ),
                }),
            }
        }
    }
}

fn table_of(bike: &Bicycle) -> &'static [ParameterInfo] {
    match bike.description {
        Description::Benchmark(_) => &BENCHMARK_TABLE,
        Description::Jbike6(_) => &JBIKE6_TABLE,
    }
}

/// Shortest text that reads back as the same f64, with a decimal point or exponent (TOML and
/// YAML would read `2` as an integer).
pub(crate) fn number(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

/// A TOML basic string: quotes, backslashes and every control character (U+0000–U+001F and
/// U+007F, which TOML forbids raw) escaped.
fn toml_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                out.push_str(&format!("\\u{:04X}", c as u32))
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Text for a one-line comment: line breaks and control characters become spaces, so a name
/// cannot start a new line of code.
fn comment_text(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

fn value_toml((x, sigma): (f64, Option<f64>)) -> String {
    match sigma {
        Some(s) => format!("{{ value = {}, sigma = {} }}", number(x), number(s)),
        None => number(x),
    }
}

fn value_json((x, sigma): (f64, Option<f64>)) -> String {
    match sigma {
        Some(s) => format!("{{ \"value\": {}, \"sigma\": {} }}", number(x), number(s)),
        None => number(x),
    }
}

/// One parameter as the TOML and JSON writers write it: the suffix of its name, its value and
/// its σ (when > 0), in the unit it was read in ([`Bicycle::units`]: `c_mm = 80.0`) where value
/// and σ both read back bit for bit, otherwise in SI.
fn entry(bike: &Bicycle, key: &str, x: f64) -> (&'static str, (f64, Option<f64>)) {
    let sigma = bike.sigma.get(key).copied().filter(|s| *s > 0.0);
    if let Some(&unit) = bike.units.get(key) {
        let value = typed_back(unit, x);
        let typed_sigma = sigma.map(|s| typed_back(unit, s));
        if let (Some(v), None | Some(Some(_))) = (value, typed_sigma) {
            return (unit.suffix(), (v, typed_sigma.flatten()));
        }
    }
    ("", (x, sigma))
}

/// The comment of a key written in a typed unit: `trail [mm]`.
fn doc_in(p: &ParameterInfo, suffix: &str) -> String {
    match TypedUnit::strip(suffix) {
        ("", Some(unit)) => format!("{} [{}]", p.description, unit.symbol()),
        _ => p.doc(),
    }
}

/// The shortest decimal in `unit` that reads back as `si` bit for bit (`0.08` m is `80` mm),
/// if one of at most 17 significant digits does.
pub(crate) fn typed_back(unit: TypedUnit, si: f64) -> Option<f64> {
    let u = unit.from_si(si);
    if !u.is_finite() {
        return None;
    }
    // The digits of `u` rounded to 1, 2, … 17 significant digits, and the last one ±1 (u may be
    // an ulp away from the decimal typed).
    (0..17).find_map(|digits| {
        let text = format!("{u:.digits$e}");
        let (mantissa, exponent) = text.split_once('e')?;
        let exponent: i32 = exponent.parse().ok()?;
        let integer: i64 = mantissa.replace('.', "").parse().ok()?;
        [
            integer,
            integer - integer.signum(),
            integer + integer.signum(),
        ]
        .into_iter()
        .find_map(|m| {
            let d: f64 = format!("{m}e{}", exponent - digits as i32).parse().ok()?;
            (unit.to_si(d).to_bits() == si.to_bits()).then_some(d)
        })
    })
}

fn extra_toml(e: &Extra) -> String {
    match (e.value, e.sigma) {
        (Some(v), Some(s)) if s > 0.0 => {
            format!("{{ value = {}, sigma = {} }}", number(v), number(s))
        }
        (Some(v), _) => number(v),
        (None, _) => toml_string(&e.text),
    }
}

/// The TOML comment of a file with keys in the units people use.
const TYPED_NOTE: &str =
    "# Keys ending in _mm are in millimetres, in _deg in degrees; all others SI.\n";

/// TOML written by hand (rather than by serde) so that every key carries its unit and meaning,
/// read from the parameter table.
fn toml(bike: &Bicycle) -> String {
    let mut out = String::new();
    if let Some(name) = &bike.name {
        out.push_str(&format!("name = {}\n", toml_string(name)));
    }
    if let Some(source) = &bike.source {
        out.push_str(&format!("source = {}\n", toml_string(source)));
    }
    if !out.is_empty() {
        out.push('\n');
    }
    let values = bike.description.values();
    match &bike.description {
        Description::Benchmark(_) => {
            if !bike.units.is_empty() {
                out.push_str(TYPED_NOTE);
            }
            out.push_str(
                "# Benchmark parameters (Meijaard et al. 2007, Table 1). SI units, radians.\n\
                 # Axes: x forward, y right, z down, origin at the rear contact (z < 0 is above ground).\n\
                 [benchmark]\n",
            );
            for (p, x) in BENCHMARK_TABLE.iter().zip(&values) {
                let (suffix, value) = entry(bike, p.key, *x);
                out.push_str(&format!(
                    "{}{suffix} = {} # {}\n",
                    p.key,
                    value_toml(value),
                    doc_in(p, suffix)
                ));
            }
        }
        Description::Jbike6(_) => {
            if !bike.units.is_empty() {
                out.push_str(TYPED_NOTE);
            }
            out.push_str(
                "# JBike6 form. SI units, radians. Axes: x forward from the rear contact, y up.\n\
                 # I = [I11, I22, Izz]: principal moments about the centre of mass, axis 1 at alpha\n\
                 # from x (counter-clockwise); Izz about the lateral axis (a wheel's spin axis).\n\
                 [jbike6]\n",
            );
            let mut current = "";
            let mut k = 0;
            while k < JBIKE6_TABLE.len() {
                let p = &JBIKE6_TABLE[k];
                let (table, field) = p.path.split_once('.').unwrap_or(("", p.path));
                if table != current {
                    out.push_str(&format!("\n[jbike6.{table}]\n"));
                    current = table;
                }
                if field.starts_with("I[") {
                    let items: Vec<String> = (0..3)
                        .map(|i| value_toml(entry(bike, JBIKE6_TABLE[k + i].key, values[k + i]).1))
                        .collect();
                    out.push_str(&format!("I = [{}] # [kg m^2]\n", items.join(", ")));
                    k += 3;
                    continue;
                }
                let (suffix, value) = entry(bike, p.key, values[k]);
                out.push_str(&format!(
                    "{field}{suffix} = {} # {}\n",
                    value_toml(value),
                    doc_in(p, suffix)
                ));
                k += 1;
            }
        }
    }
    if !bike.extras.is_empty() {
        out.push_str(
            "\n# Keys of other models, not used by the Whipple model (kept as written).\n[extra]\n",
        );
        for e in &bike.extras {
            out.push_str(&format!(
                "{} = {} # {}\n",
                e.key,
                extra_toml(e),
                comment_text(&e.meaning)
            ));
        }
    }
    out
}

fn json_string(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
}

/// JSON in the files' layout, keys in table order.
fn json(bike: &Bicycle) -> String {
    let mut fields: Vec<String> = Vec::new();
    if let Some(name) = &bike.name {
        fields.push(format!("  \"name\": {}", json_string(name)));
    }
    if let Some(source) = &bike.source {
        fields.push(format!("  \"source\": {}", json_string(source)));
    }
    let values = bike.description.values();
    match &bike.description {
        Description::Benchmark(_) => {
            let items: Vec<String> = BENCHMARK_TABLE
                .iter()
                .zip(&values)
                .map(|(p, x)| {
                    let (suffix, value) = entry(bike, p.key, *x);
                    format!("    \"{}{suffix}\": {}", p.key, value_json(value))
                })
                .collect();
            fields.push(format!("  \"benchmark\": {{\n{}\n  }}", items.join(",\n")));
        }
        Description::Jbike6(_) => {
            let mut groups: Vec<(String, Vec<String>)> = Vec::new();
            let mut top: Vec<String> = Vec::new();
            let mut k = 0;
            while k < JBIKE6_TABLE.len() {
                let p = &JBIKE6_TABLE[k];
                match p.path.split_once('.') {
                    None => {
                        let (suffix, value) = entry(bike, p.key, values[k]);
                        top.push(format!("    \"{}{suffix}\": {}", p.path, value_json(value)));
                        k += 1;
                    }
                    Some((table, field)) => {
                        if groups.last().is_none_or(|g| g.0 != table) {
                            groups.push((table.to_string(), Vec::new()));
                        }
                        let entry = if field.starts_with("I[") {
                            let items: Vec<String> = (0..3)
                                .map(|i| {
                                    value_json(
                                        entry(bike, JBIKE6_TABLE[k + i].key, values[k + i]).1,
                                    )
                                })
                                .collect();
                            k += 3;
                            format!("      \"I\": [{}]", items.join(", "))
                        } else {
                            k += 1;
                            let (suffix, value) = entry(bike, p.key, values[k - 1]);
                            format!("      \"{field}{suffix}\": {}", value_json(value))
                        };
                        if let Some(g) = groups.last_mut() {
                            g.1.push(entry);
                        }
                    }
                }
            }
            for (table, items) in groups {
                top.push(format!(
                    "    \"{table}\": {{\n{}\n    }}",
                    items.join(",\n")
                ));
            }
            fields.push(format!("  \"jbike6\": {{\n{}\n  }}", top.join(",\n")));
        }
    }
    if !bike.extras.is_empty() {
        let items: Vec<String> = bike
            .extras
            .iter()
            .map(|e| {
                let v = match (e.value, e.sigma) {
                    (Some(v), Some(s)) if s > 0.0 => {
                        format!("{{ \"value\": {}, \"sigma\": {} }}", number(v), number(s))
                    }
                    (Some(v), _) => number(v),
                    (None, _) => json_string(&e.text),
                };
                format!("    {}: {v}", json_string(&e.key))
            })
            .collect();
        fields.push(format!("  \"extra\": {{\n{}\n  }}", items.join(",\n")));
    }
    format!("{{\n{}\n}}\n", fields.join(",\n"))
}

/// JBike6's MATLAB assignments, in the layout printed in the original study, with shortest
/// round-trip numbers.
fn matlab(bike: &Bicycle) -> String {
    let mut out = String::new();
    if let Some(name) = &bike.name {
        out.push_str(&format!("% {}\n", comment_text(name)));
    }
    let values = bike.description.values();
    let mut k = 0;
    let mut group = "";
    while k < JBIKE6_TABLE.len() {
        let p = &JBIKE6_TABLE[k];
        let table = p.path.split_once('.').map_or("", |(t, _)| t);
        if table != group {
            out.push_str(&format!("\n% {}\n", table.replace('_', " ")));
            group = table;
        }
        if let Some(base) = p.key.strip_suffix("(1)") {
            out.push_str(&format!(
                "{base} = [{} {} {}];\n",
                number(values[k]),
                number(values[k + 1]),
                number(values[k + 2])
            ));
            k += 3;
            continue;
        }
        out.push_str(&format!("{} = {};\n", p.key, number(values[k])));
        k += 1;
    }
    out
}

/// BicycleParameters' `<Name>Benchmark.txt` (keys sorted as BicycleParameters writes them, every
/// value with `+/-sigma`), or HumanControl's `<Name>Par.txt` (`key = value`, `+/-sigma` where
/// known); name and source as leading `#` comments, which both readers skip.
fn key_value(bike: &Bicycle, format: Format) -> String {
    let mut out = String::new();
    if let Some(name) = &bike.name {
        out.push_str(&format!("# name: {}\n", comment_text(name)));
    }
    if let Some(source) = &bike.source {
        out.push_str(&format!("# source: {}\n", comment_text(source)));
    }
    let values = bike.description.values();
    let mut lines: Vec<(String, String)> = BENCHMARK_TABLE
        .iter()
        .zip(&values)
        .map(|(p, x)| {
            let sigma = bike.sigma.get(p.key).copied().unwrap_or(0.0);
            let text = if format == Format::BicycleParametersTxt || sigma > 0.0 {
                format!("{}+/-{}", number(*x), number(sigma))
            } else {
                number(*x)
            };
            (p.key.to_string(), text)
        })
        .collect();
    for e in &bike.extras {
        if matches!(
            e.key.as_str(),
            "parameterization" | "parameters" | "description" | "rider"
        ) {
            continue;
        }
        let text = match (e.value, e.sigma) {
            (Some(v), Some(s)) => format!("{}+/-{}", number(v), number(s)),
            (Some(v), None) => number(v),
            (None, _) => continue,
        };
        lines.push((e.key.clone(), text));
    }
    if format == Format::BicycleParametersTxt {
        lines.sort_by(|a, b| a.0.cmp(&b.0));
    }
    for (k, v) in lines {
        out.push_str(&format!("{k} = {v}\n"));
    }
    out
}

fn yaml_scalar(s: &str) -> String {
    json_string(s)
}

/// A BicycleParameters parameter set in the benchmark parameterization, with whipple's
/// `sigma:` map (which BicycleParameters ignores) where standard deviations are known.
fn yaml(bike: &Bicycle) -> String {
    let mut out = String::from("parameterization: benchmark\n");
    if let Some(name) = &bike.name {
        out.push_str(&format!("parameters: {}\n", yaml_scalar(name)));
    }
    for e in &bike.extras {
        if e.key == "rider" {
            out.push_str(&format!("rider: {}\n", yaml_scalar(&e.text)));
        }
    }
    if let Some(source) = &bike.source {
        out.push_str(&format!("description: {}\n", yaml_scalar(source)));
    }
    out.push_str("values:\n");
    let values = bike.description.values();
    let mut lines: Vec<(String, f64)> = BENCHMARK_TABLE
        .iter()
        .zip(&values)
        .map(|(p, x)| (p.key.to_string(), *x))
        .collect();
    for e in &bike.extras {
        if let Some(v) = e.value {
            lines.push((e.key.clone(), v));
        }
    }
    lines.sort_by(|a, b| a.0.cmp(&b.0));
    for (k, v) in &lines {
        out.push_str(&format!("  {k}: {}\n", number(*v)));
    }
    let sigmas: Vec<(String, f64)> = bike
        .sigma
        .iter()
        .map(|(k, s)| (k.clone(), *s))
        .chain(
            bike.extras
                .iter()
                .filter_map(|e| e.sigma.filter(|s| *s > 0.0).map(|s| (e.key.clone(), s))),
        )
        .collect();
    if !sigmas.is_empty() {
        out.push_str("sigma:\n");
        for (k, s) in sigmas {
            out.push_str(&format!("  {k}: {}\n", number(s)));
        }
    }
    out
}

/// A BicycleParameters parameter set in the principal parameterization (Moore 2019,
/// `parameterization: principal`), from the bicycle's benchmark parameters
/// ([`PrincipalParameters::from_benchmark`]). The rear frame B splits into the frame D and the
/// rider P only with the rider given: the bicycle must carry the rider's `mP`, `xP`, `zP`,
/// `kPaa`, `kPbb`, `kPyy`, `alphaP`, `lP`, `wP` among its extras, as a principal set read by
/// whipple does (also through a TOML or JSON file written from it). The keys BicycleParameters
/// repeats (`yD`, `xF`, `zR`, `kRbb`, ...) are written too, and `v` where the bicycle has one
/// (BicycleParameters requires it). Standard deviations are refused: they are not carried to
/// the principal form yet.
pub fn principal_yaml(bike: &Bicycle) -> Result<String> {
    if bike.has_uncertainty() {
        return Err(Error::InvalidArgument {
            what: "format",
            rule: "the principal form does not carry standard deviations yet: write the \
                   benchmark form to keep them"
                .into(),
        });
    }
    let b = bike.benchmark()?;
    let extra = |key: &str| {
        bike.extras
            .iter()
            .find(|e| e.key == key)
            .and_then(|e| e.value)
    };
    let rider_keys = [
        "mP", "xP", "zP", "kPaa", "kPbb", "kPyy", "alphaP", "lP", "wP",
    ];
    let missing: Vec<&str> = rider_keys
        .iter()
        .copied()
        .filter(|k| extra(k).is_none())
        .collect();
    let given: Vec<f64> = rider_keys.iter().filter_map(|k| extra(k)).collect();
    let [m, x, z, k_aa, k_bb, k_yy, alpha, l_p, w_p] = given[..] else {
        return Err(Error::InvalidArgument {
            what: "format",
            rule: format!(
                "the principal form keeps the rider P apart from the frame D, but the benchmark's \
                 rear frame B does not say how it splits; the bicycle lacks the rider's {} (a \
                 principal set read by whipple keeps them)",
                missing.join(", ")
            ),
        });
    };
    let rider = PrincipalBody {
        m,
        x,
        z,
        k_aa,
        k_bb,
        k_yy,
        alpha,
    };
    let p = PrincipalParameters::from_benchmark(&b, &rider, l_p, w_p)?;
    let mut lines: Vec<(&str, f64)> = PRINCIPAL_KEYS.iter().copied().zip(p.to_array()).collect();
    lines.extend([
        ("yD", 0.0),
        ("yH", 0.0),
        ("yP", 0.0),
        ("yR", 0.0),
        ("yF", 0.0),
        ("xR", 0.0),
        ("xF", p.w),
        ("zR", -p.r_r),
        ("zF", -p.r_f),
        ("kRbb", p.k_raa),
        ("kFbb", p.k_faa),
    ]);
    if let Some(v) = extra("v") {
        lines.push(("v", v));
    }
    lines.sort_by(|a, b| a.0.cmp(b.0));
    let mut out = String::from("parameterization: principal\n");
    if let Some(name) = &bike.name {
        out.push_str(&format!("parameters: {}\n", yaml_scalar(name)));
    }
    let rider_text = bike
        .extras
        .iter()
        .find(|e| e.key == "rider")
        .map_or("True", |e| e.text.as_str());
    out.push_str(&format!("rider: {}\n", yaml_scalar(rider_text)));
    if let Some(source) = &bike.source {
        out.push_str(&format!("description: {}\n", yaml_scalar(source)));
    }
    out.push_str("values:\n");
    for (k, v) in lines {
        out.push_str(&format!("  {k}: {}\n", number(v)));
    }
    Ok(out)
}

/// A BicycleParameters parameter set in Moore 2012's parameterization (`parameterization:
/// Moore2012`, the name of its `Moore2012ParameterSet`), from the bicycle's benchmark parameters
/// ([`Moore2012Parameters::from_benchmark`]): the 26 keys sorted, and `v` where the bicycle has
/// one, as whipple's YAML reader (and `--bike`) reads it back. Standard deviations are refused:
/// they are not carried to Moore's form yet.
pub fn moore2012_yaml(bike: &Bicycle) -> Result<String> {
    if bike.has_uncertainty() {
        return Err(Error::InvalidArgument {
            what: "format",
            rule: "Moore 2012's form does not carry standard deviations yet: write the \
                   benchmark form to keep them"
                .into(),
        });
    }
    let b = bike.benchmark()?;
    let m = Moore2012Parameters::from_benchmark(&b);
    let mut lines: Vec<(&str, f64)> = MOORE2012_KEYS.iter().copied().zip(m.to_array()).collect();
    if let Some(v) = bike
        .extras
        .iter()
        .find(|e| e.key == "v")
        .and_then(|e| e.value)
    {
        lines.push(("v", v));
    }
    lines.sort_by(|a, b| a.0.cmp(b.0));
    let mut out = String::from("parameterization: Moore2012\n");
    if let Some(name) = &bike.name {
        out.push_str(&format!("parameters: {}\n", yaml_scalar(name)));
    }
    if let Some(rider) = bike.extras.iter().find(|e| e.key == "rider") {
        out.push_str(&format!("rider: {}\n", yaml_scalar(&rider.text)));
    }
    if let Some(source) = &bike.source {
        out.push_str(&format!("description: {}\n", yaml_scalar(source)));
    }
    out.push_str("values:\n");
    for (k, v) in lines {
        if !v.is_finite() {
            return Err(Error::InvalidParameter {
                field: k.to_string(),
                value: v,
                rule: "must be a finite number to be written to a file".into(),
            });
        }
        out.push_str(&format!("  {k}: {}\n", number(v)));
    }
    Ok(out)
}
