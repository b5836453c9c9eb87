//! `--bike`: a preset name or a parameter file path; `--bike-format` and `--strict` (global
//! options, carried by [`RunContext`]).

use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use whipple::advanced::io::{FORMATS, Format, MAX_FILE_BYTES, parse};
use whipple::advanced::parameters::Notice;
use whipple::{BenchmarkParameters, Bicycle, Error, presets};

/// What one run of the command was asked besides its subcommand: the global options, passed
/// to every command that reads a bicycle. Never kept in a global: runs may share a process
/// (the Python package runs the command in the interpreter's process, from any thread), each
/// with its own options.
#[derive(Debug, Clone, Default)]
pub struct RunContext {
    /// `--bike-format`: the file format, overriding extension and content.
    pub format: Option<Format>,
    /// `--strict`: warnings are errors.
    pub strict: bool,
    /// `--set NAME=VALUE`: the changes made to every `--bike` read, in the order given.
    pub changes: Vec<(String, f64)>,
}

/// A loaded bicycle, checked, with a label for titles and messages and its warnings and notes
/// (already printed to standard error).
pub struct LoadedBike {
    pub label: String,
    pub bicycle: Bicycle,
    pub benchmark: BenchmarkParameters,
    pub notices: Vec<Notice>,
}

impl LoadedBike {
    /// The notices as a JSON list (the `warnings` field of JSON outputs).
    pub fn warnings_json(&self) -> serde_json::Value {
        serde_json::to_value(&self.notices).unwrap_or(serde_json::Value::Null)
    }
}

/// Reads `--bike`: a preset when the argument names one (a file of the same name in the
/// working directory gets a note saying which was taken), otherwise a file whose format
/// follows from `--format`, its extension or its content. Warnings and notes go to standard
/// error; with `--strict` a warning is an error.
pub fn load(cx: &RunContext, arg: &str) -> Result<LoadedBike> {
    let path = Path::new(arg);
    let opts = cx;
    let preset = presets::find(arg).ok();
    let (label, bicycle) = match preset {
        Some(preset) if opts.format.is_none() || !path.is_file() => {
            if path.is_file() {
                eprintln!(
                    "note: `{arg}` names both a preset and a file in this directory; using the \
                     preset (write ./{arg} for the file)"
                );
            }
            (preset.name.to_string(), preset.bicycle())
        }
        _ => {
            let extension = path.extension().and_then(|e| e.to_str());
            let looks_like_file = path.is_file()
                || opts.format.is_some()
                || extension.is_some_and(|e| {
                    FORMATS
                        .iter()
                        .any(|(f, _, _)| f.extensions().iter().any(|x| x.eq_ignore_ascii_case(e)))
                });
            if !looks_like_file {
                let known = presets::names();
                let extensions = whipple_front::formats::extensions_in_words();
                bail!(
                    "unknown preset `{arg}` (known presets: {known}), and no parameter file of \
                     that name (--bike takes a preset name or a {extensions} file)"
                );
            }
            let bytes = read_capped(path)?;
            // No output of this run may be written onto the file it reads.
            crate::output::register_input(path);
            let text = String::from_utf8(bytes)
                .map_err(|_| anyhow!("{}: the file is not UTF-8 text", path.display()))?;
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let format = match opts.format {
                Some(f) => f,
                None => Format::detect(&name, &text).map_err(|e| located(e, path, &text))?,
            };
            let mut bicycle = parse(&text, format).map_err(|e| located(e, path, &text))?;
            if bicycle.name.is_none() {
                bicycle.name = whipple::advanced::io::name_from_file_name(&name, format);
            }
            let label = bicycle.name.clone().unwrap_or_else(|| arg.to_string());
            (label, bicycle)
        }
    };
    let (label, bicycle) = if opts.changes.is_empty() {
        (label, bicycle)
    } else {
        let changed = whipple_front::design::replace(&bicycle, &opts.changes)
            .map_err(|e| anyhow!(whipple_front::message::message(&e)))
            .with_context(|| format!("--set on {label}"))?;
        (format!("{label}{}", whipple_front::design::EDITED), changed)
    };
    let checked = bicycle
        .check()
        .with_context(|| format!("checking the parameters of {label}"))?;
    for notice in &checked.notices {
        eprintln!("{notice}");
    }
    let checked = if opts.strict {
        checked
            .strict()
            .map_err(|e| anyhow!(whipple_front::message::message(&e)))
            .with_context(|| format!("checking the parameters of {label} (--strict)"))?
    } else {
        checked
    };
    Ok(LoadedBike {
        label,
        bicycle,
        benchmark: checked.benchmark,
        notices: checked.notices,
    })
}

/// Reads a parameter file, at most [`MAX_FILE_BYTES`] of it: a longer file (or a device that
/// never ends, `/dev/zero`) is refused when the bound is passed, not read into memory.
pub(crate) fn read_capped(path: &Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let context = || format!("reading parameters from {}", path.display());
    let file = std::fs::File::open(path).with_context(context)?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .with_context(context)?;
    if bytes.len() > MAX_FILE_BYTES {
        bail!(
            "{}: longer than {} MiB, the most a parameter file may hold (the field's files are a \
             few kilobytes): is it the right file?",
            path.display(),
            MAX_FILE_BYTES >> 20
        );
    }
    Ok(bytes)
}

/// At most this many characters of a line are shown around an error's column.
const WINDOW: usize = 60;

/// The part of a (possibly huge) line around a column, and the caret's position in it.
fn window(line: &str, column: usize) -> (String, usize) {
    let chars: Vec<char> = line.chars().collect();
    let col = column.saturating_sub(1).min(chars.len());
    let start = col.saturating_sub(WINDOW / 2);
    let end = (start + WINDOW).min(chars.len());
    let mut shown: String = chars[start..end].iter().collect();
    let mut caret = col - start;
    if start > 0 {
        shown = format!("…{shown}");
        caret += 1;
    }
    if end < chars.len() {
        shown.push('…');
    }
    (shown, caret)
}

/// A parse error with the file name and, where known, the offending line with a caret.
/// A HumanControl gains file (`*SteerGains.txt`) read for `--gains`: capped in size like a
/// parameter file, UTF-8, registered as an input (never overwritten by an output), its errors
/// placed at the line and column.
pub(crate) fn read_gains_file(path: &Path) -> Result<whipple::advanced::control::GainTable> {
    let bytes = read_capped(path).with_context(|| format!("--gains {}", path.display()))?;
    crate::output::register_input(path);
    let text = String::from_utf8(bytes)
        .map_err(|_| anyhow!("--gains {}: the file is not UTF-8 text", path.display()))?;
    whipple::advanced::io::read_gains(&text)
        .map_err(|e| located(e, path, &text))
        .context("--gains")
}

pub(crate) fn located(error: Error, path: &Path, text: &str) -> anyhow::Error {
    match &error {
        Error::Parse { line, column, .. } if *line > 0 => {
            let source_line = text
                .trim_start_matches('\u{feff}')
                .lines()
                .nth(line - 1)
                .unwrap_or("");
            let (shown, caret) = window(source_line, *column);
            anyhow!(
                "{}:{line}:{column}: {error}\n  |\n  | {shown}\n  | {}^",
                path.display(),
                " ".repeat(caret)
            )
        }
        _ => anyhow!(
            "{}: {}",
            path.display(),
            whipple_front::message::message(&error)
        ),
    }
}
