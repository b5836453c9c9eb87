//! BicycleParameters' YAML parameter sets: `parameterization: benchmark` (or `Meijaard2007`, the
//! name its `to_yaml` writes), `parameters` (the set's name), `rider`, `description` (a block
//! `|` or `>` or a plain line), `values:` (the benchmark keys, and `v`), and whipple's own
//! optional `sigma:` map of standard deviations, which BicycleParameters ignores; or, as in
//! several of its sets, a flat map of the benchmark keys. The subset of YAML those files use is
//! read here (mappings by indentation, plain and quoted scalars, block scalars, comments);
//! anything else gets a message naming its line.

use super::keyvalue::{Entry, assemble};
use super::{Format, error_at, parse_number, rounding_allowance};
use crate::error::{Result, shorten};
use crate::parameters::Extra;

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
        if !(p.eq_ignore_ascii_case("benchmark") || p == "Meijaard2007") {
            return Err(error_at(
                F,
                *line,
                1,
                Some("parameterization"),
                format!(
                    "the parameter set is in BicycleParameters' `{}` parameterization; whipple \
                     reads the benchmark parameterization (`benchmark`, Meijaard2007). \
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
