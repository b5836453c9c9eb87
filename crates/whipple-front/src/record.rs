//! Oscillation records read from files, for the period fit (`whipple::advanced::measured::period`):
//! CSV (a time column and a signal column, or a signal column and a sample rate) and MATLAB
//! v5 `.mat` as BicycleParameters' rate-gyro files are (the signal in `data`, the sample rate in
//! `ActualRate` or `sampleRate`, or the times in `time`).
//!
//! The `.mat` reader is a small one of our own: it reads the real numeric arrays of a level 5
//! file (compressed or not, either byte order; every other kind of variable is skipped), within
//! bounds on the file's size and what its compressed variables expand to. Files from MATLAB's
//! `-v7.3` (HDF5) are refused with that said.

use std::io::Read;

use whipple::Error;
use whipple::advanced::measured::period::MAX_SAMPLES;

/// The largest record file read \[bytes\] (64 MiB).
pub const MAX_RECORD_BYTES: usize = 64 << 20;
/// The most columns a CSV record may have.
pub const MAX_COLUMNS: usize = 1000;
/// The most a `.mat` file's compressed variables may expand to, together \[bytes\] (128 MiB).
pub const MAX_EXPANDED_BYTES: usize = 128 << 20;

const CSV: &str = "CSV";
const MAT: &str = "MATLAB .mat";

/// Which columns (CSV) or variables (`.mat`) hold the record, and its sample rate when no
/// times are given. `None` takes the defaults: for CSV the first column as time and the second
/// as the signal (the one column with a rate); for `.mat`, BicycleParameters' names.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RecordRequest {
    /// The signal's column: its header name, or its 1-based number; the `.mat` variable's name.
    pub signal: Option<String>,
    /// The time column or variable (CSV: name or 1-based number) \[s\].
    pub time: Option<String>,
    /// The sample rate \[Hz\], for a record without times.
    pub rate: Option<f64>,
}

/// A record as read: times \[s\] and the signal, with the names they were read under.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// tᵢ \[s\] (from the file, or i / rate from 0).
    pub time: Vec<f64>,
    /// yᵢ, in the file's unit.
    pub signal: Vec<f64>,
    /// The signal's column or variable name.
    pub signal_name: String,
    /// Where the times came from: a column's or variable's name, or `rate = … Hz`.
    pub time_source: String,
}

/// The format of a record file: `.mat` by its header (or its name), CSV otherwise.
pub fn is_mat(bytes: &[u8], file_name: &str) -> bool {
    bytes.starts_with(b"MATLAB") || file_name.to_ascii_lowercase().ends_with(".mat")
}

/// Reads a record from a file's bytes; `file_name` decides the format with the header
/// ([`is_mat`]).
pub fn read_record(
    bytes: &[u8],
    file_name: &str,
    request: &RecordRequest,
) -> Result<Record, Error> {
    if bytes.len() > MAX_RECORD_BYTES {
        return Err(Error::LimitExceeded {
            what: "record",
            rule: format!(
                "the file has {} bytes; records of at most {MAX_RECORD_BYTES} bytes are read",
                bytes.len()
            ),
        });
    }
    if let Some(rate) = request.rate
        && !(rate.is_finite() && rate > 0.0)
    {
        return Err(Error::InvalidParameter {
            field: "sample rate".into(),
            value: rate,
            rule: "must be finite and positive [Hz]".into(),
        });
    }
    if is_mat(bytes, file_name) {
        read_mat_record(bytes, request)
    } else {
        let text = std::str::from_utf8(bytes)
            .map_err(|e| parse_error(CSV, None, 0, format!("not UTF-8 text: {e}")))?;
        read_csv_record(text, request)
    }
}

fn parse_error(format: &'static str, field: Option<&str>, line: usize, message: String) -> Error {
    Error::Parse {
        format,
        field: field.map(str::to_string),
        line,
        column: 0,
        message,
    }
}

fn sampled(signal: Vec<f64>, name: String, rate: f64) -> Result<Record, Error> {
    let time = whipple::advanced::measured::period::uniform_time(signal.len(), rate)?;
    Ok(Record {
        time,
        signal,
        signal_name: name,
        time_source: format!("rate = {rate} Hz"),
    })
}

/// A CSV record: lines of numbers separated by commas (or, in a file without commas, by
/// semicolons, tabs or spaces), an optional first line of column names, `#` comments and blank
/// lines skipped.
pub fn read_csv_record(text: &str, request: &RecordRequest) -> Result<Record, Error> {
    let separator = if text.contains(',') {
        Some(',')
    } else if text.contains(';') {
        Some(';')
    } else {
        None
    };
    let split = |line: &str| -> Vec<String> {
        match separator {
            Some(c) => line.split(c).map(|s| s.trim().to_string()).collect(),
            None => line.split_whitespace().map(str::to_string).collect(),
        }
    };
    let mut header: Option<Vec<String>> = None;
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let mut width = 0;
    for (number, line) in text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields = split(line);
        if fields.len() > MAX_COLUMNS {
            return Err(parse_error(
                CSV,
                None,
                number,
                format!(
                    "{} columns; a record has at most {MAX_COLUMNS}",
                    fields.len()
                ),
            ));
        }
        let values: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        if columns.is_empty() && header.is_none() && values.iter().any(Option::is_none) {
            width = fields.len();
            header = Some(fields);
            continue;
        }
        if width == 0 {
            width = fields.len();
        }
        if columns.is_empty() {
            columns = vec![Vec::new(); width];
        }
        if fields.len() != width {
            return Err(parse_error(
                CSV,
                None,
                number,
                format!("{} values; the file's rows have {width}", fields.len()),
            ));
        }
        for (j, value) in values.iter().enumerate() {
            let Some(value) = value else {
                return Err(parse_error(
                    CSV,
                    header.as_ref().map(|h| h[j].as_str()),
                    number,
                    format!("`{}` in column {} is not a number", fields[j], j + 1),
                ));
            };
            columns[j].push(*value);
        }
        if columns[0].len() > MAX_SAMPLES {
            return Err(Error::LimitExceeded {
                what: "record",
                rule: format!(
                    "more than {MAX_SAMPLES} rows; at most {MAX_SAMPLES} samples are fitted"
                ),
            });
        }
    }
    if columns.is_empty() {
        return Err(parse_error(CSV, None, 0, "no rows of numbers".into()));
    }
    let name_of = |j: usize| -> String {
        header
            .as_ref()
            .map_or_else(|| format!("column {}", j + 1), |h| h[j].clone())
    };
    let find = |wanted: &str, option: &'static str| -> Result<usize, Error> {
        if let Some(j) = header
            .as_ref()
            .and_then(|h| h.iter().position(|n| n == wanted))
        {
            return Ok(j);
        }
        match wanted.parse::<usize>() {
            Ok(j) if (1..=width).contains(&j) => Ok(j - 1),
            _ => Err(Error::InvalidArgument {
                what: option,
                rule: format!(
                    "the CSV has no column `{wanted}` (its columns: {})",
                    (0..width).map(&name_of).collect::<Vec<_>>().join(", ")
                ),
            }),
        }
    };
    let signal = match &request.signal {
        Some(wanted) => find(wanted, "column")?,
        None if request.rate.is_some() && width == 1 => 0,
        None if request.rate.is_none() && width == 2 => 1,
        None => {
            return Err(Error::InvalidArgument {
                what: "column",
                rule: format!(
                    "the CSV has {width} column(s) ({}); name the signal's",
                    (0..width).map(&name_of).collect::<Vec<_>>().join(", ")
                ),
            });
        }
    };
    if let Some(rate) = request.rate {
        if request.time.is_some() {
            return Err(Error::InvalidArgument {
                what: "rate",
                rule: "a sample rate and a time column were both given; give one".into(),
            });
        }
        let column = std::mem::take(&mut columns[signal]);
        return sampled(column, name_of(signal), rate);
    }
    let time = match &request.time {
        Some(wanted) => find(wanted, "time")?,
        None if signal != 0 => 0,
        None => {
            return Err(Error::InvalidArgument {
                what: "time",
                rule:
                    "the signal is the first column: name the time column or give the sample rate"
                        .into(),
            });
        }
    };
    Ok(Record {
        time: std::mem::take(&mut columns[time]),
        signal: std::mem::take(&mut columns[signal]),
        signal_name: name_of(signal),
        time_source: name_of(time),
    })
}

/// The real numeric variables of a MATLAB level 5 `.mat` file, each flattened (column-major,
/// as MATLAB stores it), in the file's order.
pub fn mat_variables(bytes: &[u8]) -> Result<Vec<(String, Vec<f64>)>, Error> {
    if bytes.len() < 128 || !bytes.starts_with(b"MATLAB") {
        return Err(parse_error(
            MAT,
            None,
            0,
            "no MATLAB level 5 header (the file's first 128 bytes)".into(),
        ));
    }
    let text = String::from_utf8_lossy(&bytes[..116]);
    if text.contains("7.3 MAT-file") {
        return Err(parse_error(
            MAT,
            None,
            0,
            "a MATLAB -v7.3 (HDF5) file; save it with -v7 or as CSV".into(),
        ));
    }
    let big_endian = match &bytes[126..128] {
        b"IM" => false,
        b"MI" => true,
        other => {
            return Err(parse_error(
                MAT,
                None,
                0,
                format!("unknown byte order mark {other:?}"),
            ));
        }
    };
    let mut reader = MatReader {
        big_endian,
        expanded: 0,
        variables: Vec::new(),
    };
    reader.elements(&bytes[128..], true)?;
    Ok(reader.variables)
}

struct MatReader {
    big_endian: bool,
    expanded: usize,
    variables: Vec<(String, Vec<f64>)>,
}

const MI_MATRIX: u32 = 14;
const MI_COMPRESSED: u32 = 15;

fn truncated(what: &str) -> Error {
    parse_error(MAT, None, 0, format!("the file ends inside {what}"))
}

impl MatReader {
    fn u32_at(&self, bytes: &[u8], at: usize) -> Result<u32, Error> {
        let b: [u8; 4] = bytes
            .get(at..at + 4)
            .and_then(|s| s.try_into().ok())
            .ok_or_else(|| truncated("a tag"))?;
        Ok(if self.big_endian {
            u32::from_be_bytes(b)
        } else {
            u32::from_le_bytes(b)
        })
    }

    /// One element's tag at the start of `bytes`: (type, data, bytes taken including padding).
    fn element<'a>(&self, bytes: &'a [u8], padded: bool) -> Result<(u32, &'a [u8], usize), Error> {
        let first = self.u32_at(bytes, 0)?;
        if first >> 16 != 0 {
            // The small data element: type and size in one word, at most 4 bytes of data.
            let size = (first >> 16) as usize;
            if size > 4 {
                return Err(parse_error(
                    MAT,
                    None,
                    0,
                    format!("a small element of {size} bytes"),
                ));
            }
            let data = bytes
                .get(4..4 + size)
                .ok_or_else(|| truncated("a small element"))?;
            return Ok((first & 0xffff, data, 8));
        }
        let size = self.u32_at(bytes, 4)? as usize;
        let data = bytes
            .get(8..8usize.saturating_add(size))
            .ok_or_else(|| truncated("an element"))?;
        let taken = if padded {
            (8 + size).div_ceil(8) * 8
        } else {
            8 + size
        };
        Ok((first, data, taken.min(bytes.len())))
    }

    fn elements(&mut self, mut bytes: &[u8], top: bool) -> Result<(), Error> {
        while bytes.len() >= 8 {
            let first = self.u32_at(bytes, 0)?;
            // Compressed variables are not padded to 8 bytes; the others are.
            let (kind, data, taken) = self.element(bytes, first != MI_COMPRESSED)?;
            match kind {
                MI_COMPRESSED if top => {
                    let room = MAX_EXPANDED_BYTES - self.expanded;
                    let mut expanded = Vec::new();
                    flate2::read::ZlibDecoder::new(data)
                        .take(room as u64 + 1)
                        .read_to_end(&mut expanded)
                        .map_err(|e| {
                            parse_error(
                                MAT,
                                None,
                                0,
                                format!("a compressed variable does not expand: {e}"),
                            )
                        })?;
                    if expanded.len() > room {
                        return Err(Error::LimitExceeded {
                            what: "record",
                            rule: format!(
                                "the .mat's variables expand to more than {MAX_EXPANDED_BYTES} bytes"
                            ),
                        });
                    }
                    self.expanded += expanded.len();
                    self.elements(&expanded, false)?;
                }
                MI_MATRIX => {
                    if let Some(variable) = self.matrix(data)? {
                        self.variables.push(variable);
                    }
                }
                _ => {}
            }
            bytes = &bytes[taken..];
        }
        Ok(())
    }

    /// A miMATRIX: its name and values when it is a real numeric array, `None` otherwise.
    fn matrix(&self, mut bytes: &[u8]) -> Result<Option<(String, Vec<f64>)>, Error> {
        let next = |bytes: &mut &[u8]| -> Result<(u32, Vec<u8>), Error> {
            let (kind, data, taken) = self.element(bytes, true)?;
            let data = data.to_vec();
            *bytes = &bytes[taken..];
            Ok((kind, data))
        };
        let (_, flags) = next(&mut bytes)?;
        if flags.len() < 8 {
            return Err(truncated("a variable's flags"));
        }
        let flags = self.u32_at(&flags, 0)?;
        let class = flags & 0xff;
        let complex = flags & 0x0800 != 0;
        // Classes 6 to 15: double, single, and the integers; the others are not numeric arrays.
        if !(6..=15).contains(&class) || complex {
            return Ok(None);
        }
        let (_, dimensions) = next(&mut bytes)?;
        let count = dimensions
            .chunks_exact(4)
            .map(|c| self.u32_at(c, 0).map(|d| d as usize))
            .try_fold(1usize, |n, d| d.map(|d| n.saturating_mul(d)))?;
        let (_, name) = next(&mut bytes)?;
        let name = String::from_utf8_lossy(&name).into_owned();
        let (kind, real) = next(&mut bytes)?;
        let size = match kind {
            1 | 2 => 1,
            3 | 4 => 2,
            5..=7 => 4,
            9 | 12 | 13 => 8,
            other => {
                return Err(parse_error(
                    MAT,
                    Some(&name),
                    0,
                    format!("numbers of unknown type {other}"),
                ));
            }
        };
        if real.len() != count.saturating_mul(size) {
            return Err(parse_error(
                MAT,
                Some(&name),
                0,
                format!("{count} values declared, {} bytes of data", real.len()),
            ));
        }
        let values = real
            .chunks_exact(size)
            .map(|c| {
                let mut b = [0u8; 8];
                b[..size].copy_from_slice(c);
                if self.big_endian {
                    b[..size].reverse();
                }
                match kind {
                    1 => f64::from(b[0] as i8),
                    2 => f64::from(b[0]),
                    3 => f64::from(i16::from_le_bytes([b[0], b[1]])),
                    4 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                    5 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    6 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    7 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    9 => f64::from_le_bytes(b),
                    12 => i64::from_le_bytes(b) as f64,
                    _ => u64::from_le_bytes(b) as f64,
                }
            })
            .collect();
        Ok(Some((name, values)))
    }
}

/// A `.mat` record: the signal from the variable `request.signal` (default `data`), the times
/// from `request.time` (default `time` when the file has it), else the sample rate given, else
/// the file's `ActualRate` or `sampleRate` (BicycleParameters' order).
pub fn read_mat_record(bytes: &[u8], request: &RecordRequest) -> Result<Record, Error> {
    let mut variables = mat_variables(bytes)?;
    let names = || {
        variables
            .iter()
            .map(|(n, _)| n.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let position = |name: &str| variables.iter().position(|(n, _)| n == name);
    let signal_name = request.signal.clone().unwrap_or_else(|| "data".into());
    let Some(signal) = position(&signal_name) else {
        return Err(Error::InvalidArgument {
            what: "column",
            rule: format!(
                "the .mat has no numeric variable '{signal_name}' (its numeric variables: {})",
                names()
            ),
        });
    };
    let time = match (&request.time, request.rate) {
        (Some(_), Some(_)) => {
            return Err(Error::InvalidArgument {
                what: "rate",
                rule: "a sample rate and a time variable were both given; give one".into(),
            });
        }
        (Some(name), None) => Some(position(name).ok_or_else(|| Error::InvalidArgument {
            what: "time",
            rule: format!(
                "the .mat has no numeric variable '{name}' (its numeric variables: {})",
                names()
            ),
        })?),
        (None, None) => position("time"),
        (None, Some(_)) => None,
    };
    if let Some(time) = time {
        let (time_name, times) = std::mem::take(&mut variables[time]);
        let signal_values = if signal == time {
            times.clone()
        } else {
            std::mem::take(&mut variables[signal].1)
        };
        return Ok(Record {
            time: times,
            signal: signal_values,
            signal_name,
            time_source: time_name,
        });
    }
    let rate = match request.rate {
        Some(rate) => rate,
        None => {
            let Some(found) = ["ActualRate", "sampleRate"]
                .iter()
                .find_map(|k| position(k))
            else {
                return Err(Error::InvalidArgument {
                    what: "rate",
                    rule: format!(
                        "the .mat has no variable 'time', 'ActualRate' or 'sampleRate' (its numeric variables: {}); give the sample rate",
                        names()
                    ),
                });
            };
            match variables[found].1.as_slice() {
                [rate] => *rate,
                other => {
                    return Err(parse_error(
                        MAT,
                        Some(&variables[found].0),
                        0,
                        format!("a sample rate must be one number, not {}", other.len()),
                    ));
                }
            }
        }
    };
    let values = std::mem::take(&mut variables[signal].1);
    let mut record = sampled(values, signal_name, rate)?;
    if request.rate.is_none() {
        record.time_source = format!("rate = {rate} Hz (from the file)");
    }
    Ok(record)
}

/// The most trials of one period read from a directory (`<Name>FrameCompoundFirst1.mat` …
/// `…16.mat`).
pub const MAX_TRIALS: usize = 16;

/// A period a `*Measured.txt` lacks, fitted from the rate-gyro records in `dir` named as
/// BicycleParameters names them: `<bicycle><record_name(key)><trial>.mat`, trials 1, 2, …
/// while they exist (at most [`MAX_TRIALS`]). Each record is read as `whipple period` reads
/// it, trimmed as BicycleParameters trims a record without times (from the largest swing to
/// the last sample above a tenth of it; a record with times is fitted whole) and fitted by
/// the core; the trials' mean is the period, σ = √(Σσᵢ²)/n. The source names the files.
/// No first trial's file is an error naming the key and the file looked for.
pub fn period_from_records(
    dir: &std::path::Path,
    bicycle: &str,
    key: &str,
) -> Result<(whipple::advanced::measured::Measured, String), Error> {
    use whipple::advanced::measured::period::{decay_window, fit_period};
    use whipple::advanced::measured::{Measured, record_name};
    let missing = |looked: String| Error::InvalidParameter {
        field: key.into(),
        value: f64::NAN,
        rule: looked,
    };
    let Some(name) = record_name(key) else {
        return Err(missing(format!(
            "is missing from the file, and BicycleParameters names no record for it \
             (periods from records: Tc/Tt of B, H, S, G, F, R, D, P, orientations 1 to 6) in {}",
            dir.display()
        )));
    };
    let mut fits: Vec<(f64, f64)> = Vec::new();
    let mut files: Vec<String> = Vec::new();
    for trial in 1..=MAX_TRIALS {
        let file = format!("{bicycle}{name}{trial}.mat");
        let path = dir.join(&file);
        if !path.is_file() {
            break;
        }
        let bytes = read_capped(&path).map_err(|e| Error::InvalidParameter {
            field: key.into(),
            value: f64::NAN,
            rule: format!("its record {} cannot be read: {e}", path.display()),
        })?;
        let record = read_record(&bytes, &file, &RecordRequest::default())?;
        let window = if record.time_source.starts_with("rate") {
            decay_window(&record.signal, 0.1)?
        } else {
            0..record.signal.len()
        };
        let (Some(time), Some(signal)) =
            (record.time.get(window.clone()), record.signal.get(window))
        else {
            return Err(missing(format!(
                "its record {} has no samples to fit",
                path.display()
            )));
        };
        let fit = fit_period(time, signal)?;
        fits.push((fit.period, fit.period_sigma));
        files.push(file);
    }
    if fits.is_empty() {
        return Err(missing(format!(
            "is missing from the file and has no record: looked for {}",
            dir.join(format!("{bicycle}{name}1.mat")).display()
        )));
    }
    let n = fits.len() as f64;
    let period = fits.iter().map(|f| f.0).sum::<f64>() / n;
    let sigma = fits.iter().map(|f| f.1 * f.1).sum::<f64>().sqrt() / n;
    Ok((
        Measured::new(period, sigma),
        format!("fitted from {}", files.join(", ")),
    ))
}

/// A file's bytes, at most [`MAX_RECORD_BYTES`] + 1 read.
fn read_capped(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(MAX_RECORD_BYTES as u64 + 1)
        .read_to_end(&mut bytes)?;
    Ok(bytes)
}
