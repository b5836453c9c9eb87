//! `whipple examples --out DIR`: the field's example files the user guide's commands read,
//! written into a folder, so that every example of the guide runs as written from an install
//! (the files are bundled at build time by build.rs, with their sources and licences).

use std::path::Path;

use anyhow::{Result, bail};

use crate::output::{self, ReportDir};

include!(concat!(env!("OUT_DIR"), "/examples.rs"));

/// Writes every bundled file into `dir` (created when missing), all or none: each is written
/// to a temporary file first, then all are put in place.
pub fn examples(dir: &Path) -> Result<()> {
    if FILES.is_empty() {
        bail!(
            "this build bundles no example files (it was built outside whipple's repository); \
             they are in crates/whipple/tests/data of the repository"
        );
    }
    let folder = ReportDir::prepare("--out", dir)?;
    let mut staged = Vec::with_capacity(FILES.len());
    for (name, bytes) in FILES {
        let target = folder.file(name)?;
        let mut sink = target.open()?;
        sink.bytes(bytes)?;
        staged.push(sink.finish()?);
    }
    output::commit(staged)?;
    eprintln!(
        "wrote {} example files to {} (BicycleParameters, HumanControl and yeadon data; their \
         sources and licences in the README-*.md and THIRD-PARTY.md files there)",
        FILES.len(),
        folder.path().display()
    );
    folder.keep();
    Ok(())
}
