//! JBike6's MATLAB assignments (`.m`): `name = number;` or `name = [a b c];` (a row, or the
//! column `[a; b; c]`), `%` starting a comment, `...` continuing a statement on the next line.

use std::collections::HashMap;

use super::{Format, error_at, parse_number};
use crate::error::{Result, shorten};
use crate::parameters::{
    JBIKE6_GRAVITY, JBIKE6_TABLE, Jbike6FrontBody, Jbike6Parameters, Jbike6RearBody, Jbike6Wheel,
};

const F: Format = Format::Jbike6M;

/// One value on the right of a `.m` assignment.
#[derive(Debug, Clone)]
enum MValue {
    Scalar(f64),
    Vector(Vec<f64>),
}

/// The variable names of a `.m` file: the scalars and the three-element inertia vectors, read
/// from the parameter table.
fn is_vector(name: &str) -> bool {
    name.starts_with('I') && !name.starts_with("alphaI")
}

fn known_names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = Vec::new();
    for p in JBIKE6_TABLE.iter() {
        let name = p.key.split('(').next().unwrap_or(p.key);
        if !names.contains(&name) {
            names.push(name);
        }
    }
    names
}

/// A statement with the line and column where it starts.
struct Statement {
    text: String,
    line: usize,
    column: usize,
}

/// Splits the text into statements: comments removed, `...` continuations joined, `;` and
/// newlines ending statements outside brackets.
fn statements(text: &str) -> Result<Vec<Statement>> {
    let mut out = Vec::new();
    let mut current = String::new();
    let mut start = (0, 0);
    let mut depth = 0usize;
    let mut bracket_line = 0;
    for (index, raw_line) in text.lines().enumerate() {
        let line_no = index + 1;
        let code = match raw_line.find('%') {
            Some(p) => &raw_line[..p],
            None => raw_line,
        };
        let (code, continues) = match code.trim_end().strip_suffix("...") {
            Some(c) => (c, true),
            None => (code, false),
        };
        for (col, ch) in code.char_indices() {
            if current.trim().is_empty() && !ch.is_whitespace() && ch != ';' {
                start = (line_no, code[..col].chars().count() + 1);
                current.clear();
            }
            match ch {
                '[' => {
                    depth += 1;
                    bracket_line = line_no;
                    current.push(ch);
                }
                ']' => {
                    depth = depth.saturating_sub(1);
                    current.push(ch);
                }
                ';' if depth == 0 => {
                    if !current.trim().is_empty() {
                        out.push(Statement {
                            text: std::mem::take(&mut current),
                            line: start.0,
                            column: start.1,
                        });
                    }
                    current.clear();
                }
                ';' => current.push('\n'), // a row separator inside brackets
                _ => current.push(ch),
            }
        }
        if continues {
            current.push(' ');
            continue;
        }
        if depth > 0 {
            // MATLAB lets a bracket span lines; a newline inside it separates rows.
            current.push('\n');
            continue;
        }
        if !current.trim().is_empty() {
            out.push(Statement {
                text: std::mem::take(&mut current),
                line: start.0,
                column: start.1,
            });
        }
        current.clear();
    }
    if depth > 0 {
        return Err(error_at(
            F,
            bracket_line,
            1,
            None,
            "missing `]`: a `[` is never closed",
        ));
    }
    if !current.trim().is_empty() {
        out.push(Statement {
            text: current,
            line: start.0,
            column: start.1,
        });
    }
    Ok(out)
}

/// Reads JBike6's MATLAB assignments: `name = number;` or `name = [a b c];` (or the column
/// `[a; b; c]`), `%` starting a comment, `...` continuing a line, blank lines ignored. Every
/// variable of the original study's listing is required except `gravity` (JBike6's default
/// 9.80665); unknown names, repeated assignments and matrices are errors.
pub(crate) fn parse_jbike6_m(text: &str) -> Result<Jbike6Parameters> {
    let text = super::strip_bom(text);
    let names = known_names();
    let mut values: HashMap<&'static str, (MValue, usize)> = HashMap::new();
    for st in statements(text)? {
        let (line_no, column) = (st.line, st.column);
        let Some(eq) = st.text.find('=') else {
            return Err(error_at(
                F,
                line_no,
                column,
                None,
                format!(
                    "expected `name = value;`, found `{}`",
                    shorten(st.text.trim(), 60)
                ),
            ));
        };
        let name = st.text[..eq].trim();
        let rhs = st.text[eq + 1..].trim();
        let Some(key) = names.iter().find(|k| **k == name).copied() else {
            return Err(error_at(
                F,
                line_no,
                column,
                Some(name),
                format!(
                    "unknown variable `{}` (JBike6 names such as `wheelbase`, `Drearwheel`, `Irider`, `ucmfork` are expected)",
                    shorten(name, 40)
                ),
            ));
        };
        let at = |message: String| error_at(F, line_no, column, Some(key), message);
        let value = if let Some(inner) = rhs.strip_prefix('[') {
            let Some(inner) = inner.strip_suffix(']') else {
                return Err(at("missing `]` at the end of the list".into()));
            };
            let rows: Vec<Vec<&str>> = inner
                .split('\n')
                .map(|r| {
                    r.split(|c: char| c.is_whitespace() || c == ',')
                        .filter(|t| !t.is_empty())
                        .collect::<Vec<_>>()
                })
                .filter(|r| !r.is_empty())
                .collect();
            if rows.len() > 1 && rows.iter().any(|r| r.len() > 1) {
                return Err(at(format!(
                    "`{key}` is a matrix ({} rows); JBike6 gives principal moments as three numbers, a row [I11 I22 Izz] or a column [I11; I22; Izz]",
                    rows.len()
                )));
            }
            let numbers = rows
                .iter()
                .flatten()
                .map(|t| parse_number(t).map_err(&at))
                .collect::<Result<Vec<f64>>>()?;
            MValue::Vector(numbers)
        } else {
            MValue::Scalar(parse_number(rhs).map_err(&at)?)
        };
        match (&value, is_vector(key)) {
            (MValue::Vector(v), true) if v.len() != 3 => {
                return Err(at(format!(
                    "`{key}` needs three numbers [I11 I22 Izz], found {}",
                    v.len()
                )));
            }
            (MValue::Scalar(_), true) => {
                return Err(at(format!(
                    "`{key}` needs three numbers in brackets: [I11 I22 Izz]"
                )));
            }
            (MValue::Vector(_), false) => {
                return Err(at(format!("`{key}` is a single number, not a list")));
            }
            _ => {}
        }
        if let Some((_, first)) = values.get(key) {
            return Err(at(format!(
                "`{key}` is assigned twice (first on line {first})"
            )));
        }
        values.insert(key, (value, line_no));
    }
    let missing: Vec<&str> = names
        .iter()
        .filter(|k| **k != "gravity" && !values.contains_key(*k))
        .copied()
        .collect();
    if let Some(first) = missing.first() {
        return Err(error_at(
            F,
            0,
            0,
            Some(first),
            format!("missing variables: {}", missing.join(", ")),
        ));
    }
    let scalar = |k: &str| match values.get(k) {
        Some((MValue::Scalar(x), _)) => *x,
        _ => JBIKE6_GRAVITY, // only `gravity` may be absent, checked above
    };
    let vector = |k: &str| match values.get(k) {
        Some((MValue::Vector(v), _)) if v.len() == 3 => [v[0], v[1], v[2]],
        _ => [0.0; 3], // unreachable: presence and length checked above
    };
    let wheel = |n: &str| Jbike6Wheel {
        diameter: scalar(&format!("D{n}")),
        m: scalar(&format!("m{n}")),
        inertia: vector(&format!("I{n}")),
        alpha: scalar(&format!("alphaI{n}")),
    };
    let rear = |n: &str| Jbike6RearBody {
        m: scalar(&format!("m{n}")),
        xcm: scalar(&format!("xcm{n}")),
        ycm: scalar(&format!("ycm{n}")),
        inertia: vector(&format!("I{n}")),
        alpha: scalar(&format!("alphaI{n}")),
    };
    let front = |n: &str| Jbike6FrontBody {
        m: scalar(&format!("m{n}")),
        ucm: scalar(&format!("ucm{n}")),
        vcm: scalar(&format!("vcm{n}")),
        inertia: vector(&format!("I{n}")),
        alpha: scalar(&format!("alphaI{n}")),
    };
    Ok(Jbike6Parameters {
        wheelbase: scalar("wheelbase"),
        head_angle: scalar("head_angle"),
        trail: scalar("trail"),
        gravity: scalar("gravity"),
        rear_wheel: wheel("rearwheel"),
        front_wheel: wheel("frontwheel"),
        rider: rear("rider"),
        frame: rear("frame"),
        rack: rear("rack"),
        fork: front("fork"),
        basket: front("basket"),
    })
}
