//! HumanControl's gains files, `<Name>SteerGains.txt`: a header naming the columns
//! (`speed,kDelta,kPhiDot,kPhi,kPsi,kY`), then one comma-separated row per speed.

use super::MAX_FILE_BYTES;
use crate::error::{Error, Result};
use crate::linear::{GainTable, HumanGains};

const FORMAT: &str = "HumanControl gains .txt";

/// The columns a gains file must have: `speed`, then the gains in [`HumanGains::NAMES`].
const COLUMNS: [&str; 6] = ["speed", "kDelta", "kPhiDot", "kPhi", "kPsi", "kY"];

fn parse_error(line: usize, column: usize, field: Option<&str>, message: String) -> Error {
    Error::Parse {
        format: FORMAT,
        field: field.map(str::to_owned),
        line,
        column,
        message,
    }
}

/// Reads a HumanControl gains file (`gains/<Name>SteerGains.txt`). The header names the
/// columns, in any order (every one of `speed`, `kDelta`, `kPhiDot`, `kPhi`, `kPsi`, `kY`
/// present once, no other); each following non-blank line holds one number per column; the
/// speeds increase. Errors name the column and the line.
///
/// ```
/// let table = whipple::advanced::io::read_gains(
///     "speed,kDelta,kPhiDot,kPhi,kPsi,kY\n4.8,44.6406,-0.0529,13.2253,0.1720,0.1001\n5.0,46.5457,-0.0522,12.6611,0.1849,0.0959\n",
/// )?;
/// assert_eq!(table.speeds(), &[4.8, 5.0]);
/// assert!(!table.at(4.9)?.extrapolated);
/// # Ok::<(), whipple::Error>(())
/// ```
pub fn read_gains(text: &str) -> Result<GainTable> {
    if text.len() > MAX_FILE_BYTES {
        return Err(parse_error(
            0,
            0,
            None,
            format!("the file is larger than {} MiB", MAX_FILE_BYTES >> 20),
        ));
    }
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((header_line, header)) = lines.next() else {
        return Err(parse_error(
            0,
            0,
            None,
            format!("empty: expected a header `{}`", COLUMNS.join(",")),
        ));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let mut position = [usize::MAX; 6];
    for (k, name) in names.iter().enumerate() {
        let Some(c) = COLUMNS.iter().position(|c| c == name) else {
            return Err(parse_error(
                header_line,
                column_of(header, k),
                Some(name),
                format!(
                    "unknown column (a gains file has the columns {})",
                    COLUMNS.join(", ")
                ),
            ));
        };
        if position[c] != usize::MAX {
            return Err(parse_error(
                header_line,
                column_of(header, k),
                Some(name),
                "column named twice".into(),
            ));
        }
        position[c] = k;
    }
    if let Some(c) = position.iter().position(|p| *p == usize::MAX) {
        return Err(parse_error(
            header_line,
            header.chars().count() + 1,
            Some(COLUMNS[c]),
            format!(
                "missing column (the header must name {})",
                COLUMNS.join(", ")
            ),
        ));
    }
    let (mut speeds, mut gains) = (Vec::new(), Vec::new());
    for (line, row) in lines {
        if speeds.len() >= crate::linear::MAX_GAIN_SPEEDS {
            return Err(parse_error(
                line,
                0,
                None,
                format!("more than {} rows", crate::linear::MAX_GAIN_SPEEDS),
            ));
        }
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(parse_error(
                line,
                1,
                None,
                format!(
                    "{} values for {} columns ({})",
                    cells.len(),
                    names.len(),
                    names.join(", ")
                ),
            ));
        }
        let mut values = [0.0; 6];
        for (c, p) in position.iter().enumerate() {
            let cell = cells[*p];
            values[c] = match cell.parse::<f64>() {
                Ok(x) if x.is_finite() => x,
                _ => {
                    return Err(parse_error(
                        line,
                        column_of(row, *p),
                        Some(COLUMNS[c]),
                        format!("`{cell}` is not a finite number"),
                    ));
                }
            };
        }
        speeds.push(values[0]);
        gains.push(HumanGains::from_array([
            values[1], values[2], values[3], values[4], values[5],
        ]));
    }
    if speeds.is_empty() {
        return Err(parse_error(
            header_line,
            0,
            None,
            "no rows after the header: a gains file needs at least one speed".into(),
        ));
    }
    GainTable::new(speeds, gains).map_err(|e| match e {
        Error::InvalidArgument { rule, .. } => parse_error(0, 0, Some("speed"), rule),
        other => other,
    })
}

/// The 1-based column where the `k`-th comma-separated cell of `line` starts.
fn column_of(line: &str, k: usize) -> usize {
    let mut start = 0;
    for cell in line.split(',').take(k) {
        start += cell.len() + 1;
    }
    line[start.min(line.len())..]
        .chars()
        .take_while(|c| c.is_whitespace())
        .count()
        + line[..start.min(line.len())].chars().count()
        + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    const BENCHMARK: &str = "speed,kDelta,kPhiDot,kPhi,kPsi,kY\r\n2.500,22.0000,-0.0900,23.3000,0.0580,0.1950\r\n3.200,29.2830,-0.0490,25.6400,0.0870,0.1500\r\n";

    #[test]
    fn reads_humancontrol_gains() {
        let table = read_gains(BENCHMARK).unwrap();
        assert_eq!(table.speeds(), &[2.5, 3.2]);
        assert_eq!(table.gains()[1].k_phi, 25.64);
        // Columns in another order are read by name.
        let swapped =
            read_gains("kY,speed,kDelta,kPhiDot,kPhi,kPsi\n0.195,2.5,22,-0.09,23.3,0.058\n")
                .unwrap();
        assert_eq!(swapped.gains()[0], table.gains()[0]);
    }

    #[test]
    fn bad_files_name_the_column_and_line() {
        let cases = [
            (
                "speed,kDelta,kPhiDot,kPhi,kPsi\n2.5,22,-0.09,23.3,0.058\n",
                "line 1, column 31, `kY`: missing column",
            ),
            (
                "speed,kDelta,kPhiDot,kPhi,kPsi,kY\n2.5,22,-0.09,x,0.058,0.1\n",
                "line 2, column 14, `kPhi`: `x` is not a finite number",
            ),
            (
                "speed,kDelta,kPhiDot,kPhi,kPsi,kY\n2.5,22,-0.09,23.3,0.058\n",
                "syntax error at line 2, column 1: 5 values for 6 columns",
            ),
            (
                "speed,kDelta,kPhiDot,kPhi,kPsi,kY,kZ\n",
                "`kZ`: unknown column",
            ),
            (
                "speed,kDelta,kPhiDot,kPhi,kPsi,kY\n3,22,-0.09,23.3,0.058,0.1\n2,22,-0.09,23.3,0.058,0.1\n",
                "`speed`: must increase: speed 2",
            ),
            (
                "speed,kDelta,kPhiDot,kPhi,kPsi,kY\n",
                "no rows after the header",
            ),
            ("", "empty"),
        ];
        for (text, expected) in cases {
            let err = read_gains(text).unwrap_err().to_string();
            assert!(err.contains(expected), "{text:?}: {err}");
        }
    }
}
