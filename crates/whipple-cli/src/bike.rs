//! `--bike`: a preset name or a parameter file path.

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use whipple::parameters::io::{parse, Format};
use whipple::parameters::presets;
use whipple::{BenchmarkParameters, Bicycle, Error};

/// A loaded bicycle, validated, with a label for titles and messages.
pub struct LoadedBike {
    pub label: String,
    pub bicycle: Bicycle,
    pub benchmark: BenchmarkParameters,
}

/// Reads `--bike`: a file when the argument names an existing file or ends in .toml, .json or
/// .m; otherwise a preset.
pub fn load(arg: &str) -> Result<LoadedBike> {
    let path = Path::new(arg);
    let extension = path.extension().and_then(|e| e.to_str());
    let looks_like_file = path.is_file() || extension.and_then(Format::from_extension).is_some();
    let (label, bicycle) = if looks_like_file {
        let Some(format) = extension.and_then(Format::from_extension) else {
            bail!(
                "cannot tell the format of {}: use a .toml, .json or .m (JBike6) file",
                path.display()
            );
        };
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("reading parameters from {}", path.display()))?;
        let mut bicycle = parse(&text, format).map_err(|e| located(e, path, &text))?;
        if bicycle.name.is_none() {
            bicycle.name = path.file_stem().map(|s| s.to_string_lossy().into_owned());
        }
        let label = bicycle.name.clone().unwrap_or_else(|| arg.to_string());
        (label, bicycle)
    } else {
        let preset = presets::find(arg).map_err(|e| {
            anyhow!("{e}\n(--bike takes a preset name or a .toml, .json or .m parameter file)")
        })?;
        (preset.name.to_string(), preset.bicycle())
    };
    let benchmark = bicycle
        .benchmark()
        .with_context(|| format!("checking the parameters of {label}"))?;
    Ok(LoadedBike {
        label,
        bicycle,
        benchmark,
    })
}

/// A parse error with the file name and, where known, the offending line with a caret.
fn located(error: Error, path: &Path, text: &str) -> anyhow::Error {
    match &error {
        Error::Parse {
            format,
            line,
            column,
            message,
        } if *line > 0 => {
            let source_line = text.lines().nth(line - 1).unwrap_or("");
            let caret = format!("{}^", " ".repeat(column.saturating_sub(1)));
            anyhow!(
                "{}:{line}:{column}: {format} error: {message}\n  |\n  | {source_line}\n  | {caret}",
                path.display()
            )
        }
        Error::Parse {
            format, message, ..
        } => anyhow!("{}: {format} error: {message}", path.display()),
        _ => anyhow!("{}: {error}", path.display()),
    }
}
