//! Writing results: whole files or nothing, and number formatting.

use std::io::Write;
use std::path::Path;

use anyhow::{bail, Context, Result};

/// Writes `bytes` to `path` whole or not at all: a temporary file beside it, then a rename.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        bail!(
            "cannot write {}: the directory {} does not exist",
            path.display(),
            dir.display()
        );
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| -> Result<()> {
        let mut file =
            std::fs::File::create(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
        file.write_all(bytes)
            .with_context(|| format!("writing {}", tmp.display()))?;
        file.sync_all().ok();
        std::fs::rename(&tmp, path).with_context(|| format!("writing {}", path.display()))?;
        Ok(())
    })();
    if result.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    result
}

/// Writes `text` to standard output. A reader that went away (`whipple eig ... | head`) is not
/// an error: the output it wanted has been delivered.
pub fn print_stdout(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(e).context("writing to standard output"),
    }
}

/// Shortest text that reads back as the same f64; refuses NaN and infinities.
pub fn number(x: f64) -> Result<String> {
    if !x.is_finite() {
        bail!("a computed result is not a finite number ({x})");
    }
    // Print negative zero as 0: it carries no meaning in a table of results.
    // Very large and very small magnitudes in exponent form (also shortest round-trip).
    if x != 0.0 && (x.abs() >= 1e16 || x.abs() < 1e-5) {
        return Ok(format!("{x:e}"));
    }
    Ok(format!("{}", if x == 0.0 { 0.0 } else { x }))
}

/// Parses `START:STOP:STEP` into three finite numbers.
pub fn parse_triple(text: &str, option: &str) -> Result<(f64, f64, f64)> {
    let parts: Vec<&str> = text.split(':').collect();
    if parts.len() != 3 {
        bail!("{option} expects START:STOP:STEP, got `{text}`");
    }
    Ok((
        parse_finite(parts[0], option)?,
        parse_finite(parts[1], option)?,
        parse_finite(parts[2], option)?,
    ))
}

fn parse_finite(text: &str, option: &str) -> Result<f64> {
    let x: f64 = text
        .trim()
        .parse()
        .with_context(|| format!("{option}: `{text}` is not a number"))?;
    if !x.is_finite() {
        bail!("{option}: `{text}` is not a finite number");
    }
    Ok(x)
}
