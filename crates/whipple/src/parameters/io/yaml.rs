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
//! extras so that [`principal_yaml`](super::principal_yaml) can write it back. A set in Moore
//! 2012's parameterization (`parameterization: Moore2012`) is converted the same way
//! ([`Moore2012Parameters::to_benchmark`](crate::parameters::Moore2012Parameters::to_benchmark)).

use super::keyvalue::{Entry, assemble};
use super::{Format, error_at, parse_number, rounding_allowance};
use crate::error::{Result, shorten};
use crate::parameters::check::Notice;
use crate::parameters::{
    Extra, MOORE2012_KEYS, Moore2012Parameters, PRINCIPAL_KEYS, PrincipalParameters,
};

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
            return converted(&PRINCIPAL, values, &sigmas, &top, *line, description);
        }
        if p.eq_ignore_ascii_case("moore2012") {
            return converted(&MOORE2012, values, &sigmas, &top, *line, description);
        }
        if !(p.eq_ignore_ascii_case("benchmark") || p == "Meijaard2007") {
            return Err(error_at(
                F,
                *line,
                1,
                Some("parameterization"),
                format!(
                    "the parameter set is in BicycleParameters' `{}` parameterization; whipple \
                     reads the benchmark parameterization (`benchmark`, Meijaard2007), the \
                     principal one (`principal`, Moore2019) and Moore2012. \
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
const PRINCIPAL_REDUNDANT: &[(&str, Option<(&str, f64)>)] = &[
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
const PRINCIPAL_RIDER: &[&str] = &[
    "mP", "xP", "zP", "kPaa", "kPbb", "kPyy", "alphaP", "lP", "wP",
];

/// The keys of a Moore 2012 set that repeat what others say (`dtk.bicycle.benchmark_to_moore`
/// returns them): the products the model's symmetry makes zero, the wheels' second diametral
/// moments.
const MOORE2012_REDUNDANT: &[(&str, Option<(&str, f64)>)] = &[
    ("ic12", None),
    ("ic23", None),
    ("ie12", None),
    ("ie23", None),
    ("id33", Some(("id11", 1.0))),
    ("if33", Some(("if11", 1.0))),
];

/// A parameterization of BicycleParameters that whipple reads by converting it to the
/// benchmark form.
struct Converted {
    /// How messages name it.
    title: &'static str,
    /// Its keys, all required, in the order `convert` takes them.
    keys: &'static [&'static str],
    /// Keys that repeat others, checked.
    redundant: &'static [(&'static str, Option<(&'static str, f64)>)],
    /// Keys kept among the extras (besides `v`).
    kept: &'static [&'static str],
    /// The keys in words, for the message on an unknown one.
    listing: &'static str,
    convert: fn(&[f64]) -> Result<crate::parameters::BenchmarkParameters>,
    note: &'static str,
}

const PRINCIPAL: Converted = Converted {
    title: "principal",
    keys: &PRINCIPAL_KEYS,
    redundant: PRINCIPAL_REDUNDANT,
    kept: PRINCIPAL_RIDER,
    listing: "Moore 2019: w, c, lam, g, rR, mR, kRaa, kRyy, ..., mD, xD, zD, kDaa, kDbb, kDyy, \
              alphaD, the same for H and P, lP, wP, v",
    convert: |v| {
        let mut array = [0.0; 35];
        array.copy_from_slice(v);
        Ok(PrincipalParameters::from_array(array).to_benchmark())
    },
    note: "converted from BicycleParameters' principal parameterization (Moore 2019) to the \
           benchmark form: the rear frame B is the frame D and the rider P combined, each body's \
           inertia from its radii of gyration about its principal axes",
};

const MOORE2012: Converted = Converted {
    title: "Moore2012",
    keys: &MOORE2012_KEYS,
    redundant: MOORE2012_REDUNDANT,
    kept: &[],
    listing: "Moore 2012: rf, rr, d1, d2, d3, l1, l2, l3, l4, mc, md, me, mf, ic11, ic22, ic31, \
              ic33, id11, id22, ie11, ie22, ie31, ie33, if11, if22, g, v",
    convert: |v| {
        let mut array = [0.0; 26];
        array.copy_from_slice(v);
        Moore2012Parameters::from_array(array).to_benchmark()
    },
    note: "converted from Moore 2012's parameterization (BicycleParameters' Moore2012) to the \
           benchmark form: wheelbase and steer axis tilt from d1, d2, d3 and the wheel radii, \
           mass centres and tensors turned back by the tilt",
};

/// A set in a converted parameterization: every key required, the redundant ones checked, then
/// the benchmark parameters computed and assembled as a benchmark set's would be.
fn converted(
    set: &Converted,
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
            format!(
                "standard deviations of a {} set are not carried to the benchmark form yet: \
                 leave out `sigma:` or give the set in the benchmark parameterization",
                set.title
            ),
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
        let known = set.keys.contains(&e.key.as_str())
            || e.key == "v"
            || set.redundant.iter().any(|(k, _)| *k == e.key);
        if !known {
            return Err(error_at(
                F,
                e.line,
                e.column,
                Some(&e.key),
                format!(
                    "unknown key `{}` in a {} set ({})",
                    shorten(&e.key, 40),
                    set.title,
                    set.listing
                ),
            ));
        }
    }
    let find = |key: &str| values.iter().find(|e| e.key == key);
    let missing: Vec<&str> = set
        .keys
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
                "the {} set lacks {}",
                set.title,
                missing
                    .iter()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    for (key, source) in set.redundant {
        let Some(e) = find(key) else { continue };
        let (expected, allowance, what) = match source {
            None => (0.0, 0.0, "0 (the model is left-right symmetric, its wheels axisymmetric, the rear contact the origin)".to_string()),
            Some((k, sign)) => match find(k) {
                Some(s) => (sign * s.value, s.allowance, format!("{}{k}", if *sign < 0.0 { "−" } else { "" })),
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
    let numbers: Vec<f64> = set
        .keys
        .iter()
        .map(|key| find(key).map_or(0.0, |e| e.value))
        .collect();
    let benchmark = (set.convert)(&numbers)?;
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
            .filter(|e| e.key == "v" || set.kept.contains(&e.key.as_str()))
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
    bike.notices
        .insert(0, Notice::note("parameterization", set.note));
    Ok(bike)
}
