//! BicycleParameters' YAML parameter sets: `parameterization: benchmark` (or `Meijaard2007`, the
//! name its `to_yaml` writes), `parameters` (the set's name), `rider`, `description` (a block
//! `|` or `>` or a plain line), `values:` (the benchmark keys, and `v`), and whipple's own
//! optional `sigma:` map of standard deviations, which BicycleParameters ignores; or, as in
//! several of its sets, a flat map of the benchmark keys. The subset of YAML those files use is
//! read here (mappings by indentation, plain and quoted scalars, block scalars, comments);
//! anything else gets a message naming its line.
//!
//! A set in the principal parameterization (`parameterization: principal` or `Moore2019`,
//! Moore 2019) is converted to the benchmark form on reading
//! ([`PrincipalParameters::to_benchmark`](crate::parameters::PrincipalParameters::to_benchmark)), with a note saying so; its rider P is kept among the
//! extras so that [`principal_yaml`](super::principal_yaml) can write it back.

use super::keyvalue::{Entry, assemble};
use super::{Format, error_at, parse_number, rounding_allowance};
use crate::error::{Result, shorten};
use crate::parameters::check::Notice;
use crate::parameters::{Extra, PRINCIPAL_KEYS, PrincipalParameters};

const F: Format = Format::Yaml;

fn unquote(s: &str) -> String {
    let s = s.trim();
    if s.len() >= 2 && s.starts_with('"') && s.ends_with('"') {
        serde_json::from_str::<String>(s).unwrap_or_else(|_| s[1..s.len() - 1].to_string())
    } else if s.len() >= 2 && s.starts_with('\'') && s.ends_with('\'') {
        s[1..s.len() - 1].replace("''", "'")
    } else {
        s.to_string()
    }
}

fn strip_comment(line: &str) -> &str {
    // A `#` starts a comment at the line's start or after a space (not inside quotes).
    let mut quote = None;
    let bytes = line.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        match (quote, b) {
            (None, b'"' | b'\'') => quote = Some(b),
            (Some(q), c) if c == q => quote = None,
            (None, b'#') if i == 0 || bytes[i - 1] == b' ' || bytes[i - 1] == b'\t' => {
                return &line[..i];
            }
            _ => {}
        }
    }
    line
}

pub(crate) fn parse(text: &str) -> Result<crate::parameters::Bicycle> {
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    let mut top: Vec<(String, String, usize)> = Vec::new();
    let mut values: Vec<Entry> = Vec::new();
    let mut sigmas: Vec<(String, f64, usize)> = Vec::new();
    let mut description = None;
    let mut section: Option<(String, usize)> = None;
    while i < lines.len() {
        let raw = lines[i];
        let line_no = i + 1;
        i += 1;
        if raw.contains('\t') && raw.trim_start().len() != raw.len() && raw.starts_with('\t') {
            return Err(error_at(
                F,
                line_no,
                1,
                None,
                "YAML indentation must use spaces, not tabs",
            ));
        }
        let code = strip_comment(raw);
        if code.trim().is_empty() || code.trim() == "---" {
            continue;
        }
        let indent = code.len() - code.trim_start().len();
        let body = code.trim();
        let Some((key, value)) = body.split_once(':') else {
            return Err(error_at(
                F,
                line_no,
                indent + 1,
                None,
                format!("expected `key: value`, found `{}`", shorten(body, 60)),
            ));
        };
        let key = unquote(key);
        let value = value.trim();
        let column = indent + key.len() + 3;
        if indent == 0 {
            section = None;
            if value.is_empty() {
                if key == "values" || key == "sigma" {
                    section = Some((key.clone(), line_no));
                    continue;
                }
                return Err(error_at(
                    F,
                    line_no,
                    1,
                    Some(&key),
                    format!("`{key}` has no value"),
                ));
            }
            if value == "|" || value == ">" || value.starts_with("|-") || value.starts_with(">-") {
                let mut block = Vec::new();
                while i < lines.len() {
                    let l = lines[i];
                    if !l.trim().is_empty() && !l.starts_with(' ') {
                        break;
                    }
                    block.push(l.trim());
                    i += 1;
                }
                let joined = if value.starts_with('|') {
                    block.join("\n")
                } else {
                    block.join(" ")
                };
                let joined = joined.trim().to_string();
                if key == "description" {
                    description = Some(joined.clone());
                }
                top.push((key, joined, line_no));
                continue;
            }
            if key == "description" {
                description = Some(unquote(value));
            }
            top.push((key, unquote(value), line_no));
            continue;
        }
        match &section {
            Some((name, _)) if name == "values" => {
                let number =
                    parse_number(value).map_err(|e| error_at(F, line_no, column, Some(&key), e))?;
                values.push(Entry {
                    key: key.clone(),
                    value: number,
                    sigma: None,
                    text: value.to_string(),
                    line: line_no,
                    column,
                    allowance: rounding_allowance(value),
                });
            }
            Some((name, _)) if name == "sigma" => {
                let number =
                    parse_number(value).map_err(|e| error_at(F, line_no, column, Some(&key), e))?;
                if number < 0.0 {
                    return Err(error_at(
                        F,
                        line_no,
                        column,
                        Some(&key),
                        "a standard deviation cannot be negative",
                    ));
                }
                sigmas.push((key, number, line_no));
            }
            _ => {
                return Err(error_at(
                    F,
                    line_no,
                    indent + 1,
                    Some(&key),
                    "unexpected indentation: only `values:` and `sigma:` hold indented keys",
                ));
            }
        }
    }
    let get = |k: &str| top.iter().find(|(key, _, _)| key == k);
    let has_values_section = !values.is_empty() || get("parameterization").is_some();
    if let Some((_, p, line)) = get("parameterization") {
        if p.eq_ignore_ascii_case("principal") || p == "Moore2019" {
            return principal(values, &sigmas, &top, *line, description);
        }
        if !(p.eq_ignore_ascii_case("benchmark") || p == "Meijaard2007") {
            return Err(error_at(
                F,
                *line,
                1,
                Some("parameterization"),
                format!(
                    "the parameter set is in BicycleParameters' `{}` parameterization; whipple \
                     reads the benchmark parameterization (`benchmark`, Meijaard2007) and the \
                     principal one (`principal`, Moore2019). \
                     BicycleParameters converts between them (ParameterSet.to_parameterization)",
                    shorten(p, 40)
                ),
            ));
        }
    }
    let mut extras = Vec::new();
    if has_values_section {
        for (key, value, line) in &top {
            match key.as_str() {
                "parameterization" | "parameters" | "rider" | "description" => {
                    extras.push(Extra {
                        key: key.clone(),
                        text: value.clone(),
                        value: None,
                        sigma: None,
                        meaning: "YAML metadata of a BicycleParameters parameter set".into(),
                    });
                }
                _ => {
                    return Err(error_at(
                        F,
                        *line,
                        1,
                        Some(key),
                        format!(
                            "unknown key `{}`: a parameter set holds parameterization, \
                             parameters, rider, description, values (and whipple's sigma)",
                            shorten(key, 40)
                        ),
                    ));
                }
            }
        }
    } else {
        // A flat map of the benchmark keys.
        for (key, value, line) in &top {
            let column = key.len() + 3;
            let number =
                parse_number(value).map_err(|e| error_at(F, *line, column, Some(key), e))?;
            values.push(Entry {
                key: key.clone(),
                value: number,
                sigma: None,
                text: value.clone(),
                line: *line,
                column,
                allowance: rounding_allowance(value),
            });
        }
    }
    for (key, sigma, line) in &sigmas {
        match values.iter_mut().find(|e| &e.key == key) {
            Some(e) => e.sigma = Some(*sigma),
            None => {
                return Err(error_at(
                    F,
                    *line,
                    1,
                    Some(key),
                    format!(
                        "`sigma` names `{}`, which `values` does not hold",
                        shorten(key, 40)
                    ),
                ));
            }
        }
    }
    let mut bike = assemble(values, F)?;
    bike.name = get("parameters").map(|(_, v, _)| v.clone());
    bike.source = description;
    let mut all = extras;
    all.extend(bike.extras);
    bike.extras = all;
    Ok(bike)
}

/// The keys of a principal set that repeat what others say (BicycleParameters writes them),
/// with the key and sign each must equal (`None`: zero), checked to the written digits.
const PRINCIPAL_REDUNDANT: [(&str, Option<(&str, f64)>); 13] = [
    ("yD", None),
    ("yH", None),
    ("yP", None),
    ("yR", None),
    ("yF", None),
    ("xR", None),
    ("alphaR", None),
    ("alphaF", None),
    ("xF", Some(("w", 1.0))),
    ("zR", Some(("rR", -1.0))),
    ("zF", Some(("rF", -1.0))),
    ("kRbb", Some(("kRaa", 1.0))),
    ("kFbb", Some(("kFaa", 1.0))),
];

/// The rider's keys, kept among the extras.
const PRINCIPAL_RIDER: [&str; 9] = [
    "mP", "xP", "zP", "kPaa", "kPbb", "kPyy", "alphaP", "lP", "wP",
];

/// A set in the principal parameterization: every key of [`PRINCIPAL_KEYS`] required, the
/// redundant ones checked, then the benchmark parameters computed and assembled as a benchmark
/// set's would be.
fn principal(
    values: Vec<Entry>,
    sigmas: &[(String, f64, usize)],
    top: &[(String, String, usize)],
    parameterization_line: usize,
    description: Option<String>,
) -> Result<crate::parameters::Bicycle> {
    if let Some((key, _, line)) = sigmas.first() {
        return Err(error_at(
            F,
            *line,
            1,
            Some(key),
            "standard deviations of a principal set are not carried to the benchmark form yet: \
             leave out `sigma:` or give the set in the benchmark parameterization",
        ));
    }
    for (key, _, line) in top {
        if !matches!(
            key.as_str(),
            "parameterization" | "parameters" | "rider" | "description"
        ) {
            return Err(error_at(
                F,
                *line,
                1,
                Some(key),
                format!(
                    "unknown key `{}`: a parameter set holds parameterization, parameters, \
                     rider, description, values",
                    shorten(key, 40)
                ),
            ));
        }
    }
    for (i, e) in values.iter().enumerate() {
        if let Some(first) = values[..i].iter().find(|f| f.key == e.key) {
            return Err(error_at(
                F,
                e.line,
                e.column,
                Some(&e.key),
                format!("`{}` is given twice (first on line {})", e.key, first.line),
            ));
        }
        let known = PRINCIPAL_KEYS.contains(&e.key.as_str())
            || e.key == "v"
            || PRINCIPAL_REDUNDANT.iter().any(|(k, _)| *k == e.key);
        if !known {
            return Err(error_at(
                F,
                e.line,
                e.column,
                Some(&e.key),
                format!(
                    "unknown key `{}` in a principal set (Moore 2019: w, c, lam, g, rR, mR, \
                     kRaa, kRyy, ..., mD, xD, zD, kDaa, kDbb, kDyy, alphaD, the same for H and P, \
                     lP, wP, v)",
                    shorten(&e.key, 40)
                ),
            ));
        }
    }
    let find = |key: &str| values.iter().find(|e| e.key == key);
    let missing: Vec<&str> = PRINCIPAL_KEYS
        .iter()
        .copied()
        .filter(|k| find(k).is_none())
        .collect();
    if !missing.is_empty() {
        return Err(error_at(
            F,
            parameterization_line,
            1,
            missing.first().copied(),
            format!(
                "the principal set lacks {}",
                missing
                    .iter()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    for (key, source) in PRINCIPAL_REDUNDANT {
        let Some(e) = find(key) else { continue };
        let (expected, allowance, what) = match source {
            None => (0.0, 0.0, "0 (the model is left-right symmetric, its wheels axisymmetric, the rear contact the origin)".to_string()),
            Some((k, sign)) => match find(k) {
                Some(s) => (sign * s.value, s.allowance, format!("{}{k}", if sign < 0.0 { "−" } else { "" })),
                None => continue,
            },
        };
        let tolerance = e.allowance + allowance + 1e-12 * expected.abs();
        if (e.value - expected).abs() > tolerance {
            return Err(error_at(
                F,
                e.line,
                e.column,
                Some(key),
                format!(
                    "`{key}` = {} must equal {what} = {}",
                    shorten(&e.text, 40),
                    crate::error::short_number(expected)
                ),
            ));
        }
    }
    let mut array = [0.0; 35];
    for (slot, key) in array.iter_mut().zip(PRINCIPAL_KEYS) {
        *slot = find(key).map_or(0.0, |e| e.value);
    }
    let benchmark = PrincipalParameters::from_array(array).to_benchmark();
    let mut entries: Vec<Entry> = crate::parameters::BENCHMARK_TABLE
        .iter()
        .zip(benchmark.to_array())
        .map(|(p, value)| Entry {
            key: p.key.to_string(),
            value,
            sigma: None,
            text: super::write::number(value),
            line: parameterization_line,
            column: 1,
            allowance: 0.0,
        })
        .collect();
    entries.extend(
        values
            .iter()
            .filter(|e| e.key == "v" || PRINCIPAL_RIDER.contains(&e.key.as_str()))
            .cloned(),
    );
    let mut bike = assemble(entries, F)?;
    bike.name = top
        .iter()
        .find(|(k, _, _)| k == "parameters")
        .map(|(_, v, _)| v.clone());
    bike.source = description;
    let mut extras: Vec<Extra> = top
        .iter()
        .filter(|(k, _, _)| matches!(k.as_str(), "parameters" | "rider" | "description"))
        .map(|(key, text, _)| Extra {
            key: key.clone(),
            text: text.clone(),
            value: None,
            sigma: None,
            meaning: "YAML metadata of a BicycleParameters parameter set".into(),
        })
        .collect();
    extras.append(&mut bike.extras);
    bike.extras = extras;
    bike.notices.insert(
        0,
        Notice::note(
            "parameterization",
            "converted from BicycleParameters' principal parameterization (Moore 2019) to the \
             benchmark form: the rear frame B is the frame D and the rider P combined, each \
             body's inertia from its radii of gyration about its principal axes",
        ),
    );
    Ok(bike)
}
