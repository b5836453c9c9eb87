//! Where results go, and number formatting.
//!
//! Every command writes through this module. An output is checked before any computing
//! ([`Target::check`]: its directory exists, nothing that is not a file stands in the way, an
//! existing file may be written), then opened ([`Target::open`], which proves the directory
//! writable by creating the temporary file), written as the results come ([`Sink`] is a
//! [`Write`]), and finished ([`Sink::finish`]). Nothing replaces anything until
//! [`commit`] renames every finished output into place together, so a command that fails
//! leaves no partial set of files behind (no plot without its table, no report directory
//! with half its figures).
//!
//! - A regular file, or a path where nothing is yet, is written to a temporary file beside its
//!   real target and renamed onto it (whole or not at all); the replaced file's permissions
//!   are kept.
//! - A symbolic link is followed: its target is written (and the link stays a link).
//! - Anything else — a device such as `/dev/null` or `/dev/full`, a named pipe, a terminal,
//!   `/dev/stdout` — is written directly, in place, never replaced.
//! - Standard output ([`Sink::stdout`]) is streamed; a reader that goes away
//!   (`whipple eig ... | head`) ends the run quietly ([`is_closed_stdout`]). Beside file
//!   outputs ([`Sink::stdout_beside_files`]) it ends only the table: the files are still
//!   written (`whipple eig ... --plot eig.png | head` puts the plot in place).
//!
//! ```text
//! let table = Target::check("--out", path)?;     // before computing
//! let mut sink = table.open()?;                   // temporary file created
//! writeln!(sink, "v,re1,...")?;                   // as the rows come
//! commit(vec![sink.finish()?])?;                  // renamed into place
//! ```

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use whipple_front::units::SpeedUnit;

use anyhow::{Context, Result, anyhow, bail};

/// How many symbolic links are followed before giving up (as the kernel's `ELOOP`).
const MAX_LINKS: usize = 40;

/// How an output is written.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Place {
    /// A regular file (or a new one) at `target`, symbolic links resolved: written to a
    /// temporary file in its directory and renamed onto it. `mode` is the permission bits of
    /// the file replaced, if any.
    Replace { target: PathBuf, mode: Option<u32> },
    /// Not a regular file: opened and written in place.
    Direct(PathBuf),
}

/// A checked output location: what the user named, with the option that named it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Target {
    option: String,
    shown: PathBuf,
    place: Place,
}

/// Follows the symbolic links of the last component of `path` (bounded). `None` when a link
/// points at something that is not a path (`/proc/self/fd/1` -> `pipe:[123]`), which is then
/// written directly.
fn resolve_links(path: &Path) -> Result<Option<PathBuf>> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match fs::symlink_metadata(&current) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = fs::read_link(&current)
                    .with_context(|| format!("reading the link {}", current.display()))?;
                if !link.is_absolute() && link.to_string_lossy().contains(":[") {
                    return Ok(None);
                }
                current = if link.is_absolute() {
                    link
                } else {
                    current
                        .parent()
                        .map_or_else(|| link.clone(), |dir| dir.join(&link))
                };
            }
            _ => return Ok(Some(current)),
        }
    }
    bail!(
        "{}: more than {MAX_LINKS} levels of symbolic links",
        path.display()
    )
}

/// The directory a file `path` lives in (`.` for a bare name).
fn directory_of(path: &Path) -> &Path {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

/// `/dev/stdout`, `/dev/fd/N`, `/proc/self/fd/N` and the like name an open descriptor: written
/// in place whatever they point at.
fn names_a_descriptor(path: &Path) -> bool {
    let text = path.to_string_lossy();
    ["/dev/stdout", "/dev/stderr", "/dev/fd/", "/proc/"]
        .iter()
        .any(|p| text.starts_with(p))
}

impl Target {
    /// Checks that `path` can take the output of `option` (`--out`, `--plot`, `--report`):
    /// the directory exists, the path is not a directory, an existing file may be written.
    /// Nothing is created or changed.
    pub fn check(option: &str, path: &Path) -> Result<Target> {
        let fail = |why: String| -> anyhow::Error {
            anyhow::anyhow!("{option} {}: {why}", path.display())
        };
        if path.as_os_str().is_empty() {
            bail!("{option}: the path is empty");
        }
        if names_a_descriptor(path) {
            return Ok(Target::direct(option, path));
        }
        let Some(resolved) = resolve_links(path).map_err(|e| fail(format!("{e:#}")))? else {
            return Ok(Target::direct(option, path));
        };
        if let Some(input) = is_input(&resolved) {
            return Err(fail(format!(
                "is the parameter file this command reads ({}): writing the output there \
                 would destroy it; give the output its own path",
                input.display()
            )));
        }
        match fs::metadata(&resolved) {
            Ok(meta) if meta.is_dir() => Err(fail("is a directory".into())),
            Ok(meta) if meta.is_file() => {
                // Writable as a shell's `>` would find it (root may write a read-only file).
                OpenOptions::new()
                    .write(true)
                    .open(&resolved)
                    .map_err(|e| fail(format!("cannot be written ({e})")))?;
                Ok(Target {
                    option: option.into(),
                    shown: path.into(),
                    place: Place::Replace {
                        mode: Some(permission_bits(&meta)),
                        target: resolved,
                    },
                })
            }
            Ok(_) => Ok(Target {
                option: option.into(),
                shown: path.into(),
                place: Place::Direct(resolved),
            }),
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                let dir = directory_of(&resolved);
                match fs::metadata(dir) {
                    Ok(meta) if meta.is_dir() => Ok(Target {
                        option: option.into(),
                        shown: path.into(),
                        place: Place::Replace {
                            target: resolved,
                            mode: None,
                        },
                    }),
                    Ok(_) => Err(fail(format!("{} is not a directory", dir.display()))),
                    Err(_) => Err(fail(format!(
                        "the directory {} does not exist",
                        dir.display()
                    ))),
                }
            }
            Err(e) => Err(fail(format!("cannot be reached ({e})"))),
        }
    }

    fn direct(option: &str, path: &Path) -> Target {
        Target {
            option: option.into(),
            shown: path.into(),
            place: Place::Direct(path.into()),
        }
    }

    /// The path as the user wrote it.
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// The file actually written (symbolic links followed).
    pub fn destination(&self) -> &Path {
        match &self.place {
            Place::Replace { target, .. } => target,
            Place::Direct(path) => path,
        }
    }

    /// `--out eig.csv`, for messages.
    pub fn describe(&self) -> String {
        format!("{} {}", self.option, self.shown.display())
    }

    /// Opens the output for writing: a temporary file beside a regular target (proving its
    /// directory writable), or the target itself when it is not a regular file. Nothing is
    /// replaced until [`commit`].
    pub fn open(&self) -> Result<Sink> {
        match &self.place {
            Place::Replace { target, mode } => {
                self.refuse_input()?;
                let (temp, file) = {
                    // Created and listed under one lock: a signal between the two cannot
                    // leave the file behind.
                    let mut guard = pending();
                    let (temp, file) = create_temporary(target)
                        .with_context(|| format!("cannot write {}", self.describe()))?;
                    guard.temporaries.push((temp.clone(), self.describe()));
                    (temp, file)
                };
                Ok(Sink {
                    target: self.clone(),
                    writer: Some(BufWriter::with_capacity(1 << 16, Writer::File(file))),
                    temp: Some(Temporary(temp)),
                    mode: *mode,
                })
            }
            Place::Direct(path) => {
                self.refuse_input()?;
                // No truncation and no creation: a device or pipe is written as it is.
                let file = OpenOptions::new()
                    .write(true)
                    .open(path)
                    .with_context(|| format!("cannot open {} for writing", self.describe()))?;
                Ok(Sink {
                    target: self.clone(),
                    writer: Some(BufWriter::with_capacity(1 << 16, Writer::File(file))),
                    temp: None,
                    mode: None,
                })
            }
        }
    }

    /// Refuses an output that is a parameter file this run read (directly or through a
    /// symbolic link or a hard link): writing it would destroy the input.
    fn refuse_input(&self) -> Result<()> {
        if let Some(input) = is_input(self.destination()) {
            bail!(
                "{} is the parameter file this command reads ({}): writing the output there \
                 would destroy it; give the output its own path",
                self.describe(),
                input.display()
            );
        }
        Ok(())
    }

    /// Writes `bytes` as the whole output now (open, write, finish, commit).
    pub fn write_whole(&self, bytes: &[u8]) -> Result<()> {
        let mut sink = self.open()?;
        sink.write_all(bytes)
            .with_context(|| format!("writing {}", self.describe()))?;
        commit(vec![sink.finish()?])
    }
}

#[cfg(unix)]
fn permission_bits(meta: &fs::Metadata) -> u32 {
    use std::os::unix::fs::PermissionsExt;
    meta.permissions().mode() & 0o7777
}

#[cfg(not(unix))]
fn permission_bits(_meta: &fs::Metadata) -> u32 {
    0o644
}

/// What this process has under way on disk: temporary files not yet renamed into place (with
/// the output each one is for), report directories it created and has not kept, and the
/// parameter files read (never to be written over). A signal handler
/// ([`abandon_and_exit`]) takes the same lock as [`commit`], so an output is either renamed
/// into place whole or removed, never left half-done.
#[derive(Default)]
struct Pending {
    temporaries: Vec<(PathBuf, String)>,
    directories: Vec<PathBuf>,
}

static PENDING: std::sync::Mutex<Pending> = std::sync::Mutex::new(Pending {
    temporaries: Vec::new(),
    directories: Vec::new(),
});

thread_local! {
    /// The parameter files read by the run on this thread. A run of the command is one call of
    /// `main_with_args`, which reads its inputs and checks its outputs on the calling thread;
    /// runs on other threads of the same process (the Python package's) keep lists of their
    /// own, so one run's start never forgets another's inputs.
    static INPUTS: std::cell::RefCell<Vec<PathBuf>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn pending() -> std::sync::MutexGuard<'static, Pending> {
    PENDING
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Forgets the inputs of an earlier run on this thread (the Python package runs the command
/// in-process).
pub fn begin_run() {
    INPUTS.with_borrow_mut(Vec::clear);
}

/// Records a parameter file read by this run: no output may be written onto it.
pub fn register_input(path: &Path) {
    let resolved = fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    INPUTS.with_borrow_mut(|inputs| inputs.push(resolved));
}

/// Whether `path` (an output's destination) is a file this run read.
fn is_input(path: &Path) -> Option<PathBuf> {
    INPUTS.with_borrow(|inputs| inputs.iter().find(|input| same_file(input, path)).cloned())
}

#[cfg(unix)]
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (fs::metadata(a), fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(a: &Path, b: &Path) -> bool {
    fs::canonicalize(a)
        .ok()
        .zip(fs::canonicalize(b).ok())
        .is_some_and(|(x, y)| x == y)
}

/// Called on SIGINT, SIGTERM or SIGHUP (from the handler's own thread): removes every pending
/// temporary file and every report directory this run created, says what was not written,
/// and ends the process with 128 + `signal`. The lock is held to the end, so no output is
/// renamed into place meanwhile.
pub fn abandon_and_exit(signal: i32, name: &str) -> ! {
    let guard = pending();
    let mut lost = Vec::new();
    for (temp, what) in &guard.temporaries {
        fs::remove_file(temp).ok();
        lost.push(what.clone());
    }
    for dir in guard.directories.iter().rev() {
        fs::remove_dir(dir).ok();
    }
    let _ = io::stdout().flush();
    if lost.is_empty() {
        eprintln!("\nwhipple: stopped by {name}");
    } else {
        eprintln!(
            "\nwhipple: stopped by {name}; not written (left as it was): {}",
            lost.join(", ")
        );
    }
    std::process::exit(128 + signal)
}

/// A new, uniquely named temporary file in the directory of `target`.
fn create_temporary(target: &Path) -> io::Result<(PathBuf, File)> {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = directory_of(target);
    let name = target
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{name}.{}.{n}.tmp", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => return Ok((temp, file)),
            // A leftover of an earlier run with the same process id: take the next number.
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && n < 1_000_000 => continue,
            Err(e) => return Err(e),
        }
    }
}

/// A temporary file, removed when dropped unless it was renamed into place; listed in
/// [`PENDING`] while it exists.
#[derive(Debug)]
struct Temporary(PathBuf);

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.0.as_os_str().is_empty() {
            let mut guard = pending();
            fs::remove_file(&self.0).ok();
            guard.temporaries.retain(|(t, _)| t != &self.0);
        }
    }
}

#[derive(Debug)]
enum Writer {
    File(File),
    Stdout(io::Stdout),
    /// Standard output beside file outputs: once its reader has gone, what follows is
    /// dropped and the files are still written.
    StdoutBeside {
        out: io::Stdout,
        closed: bool,
    },
}

impl Write for Writer {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        match self {
            Writer::File(f) => f.write(bytes),
            Writer::Stdout(s) => s.write(bytes).map_err(mark_stdout),
            Writer::StdoutBeside { out, closed } => {
                if !*closed {
                    match out.write(bytes) {
                        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => *closed = true,
                        other => return other,
                    }
                }
                Ok(bytes.len())
            }
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            Writer::File(f) => f.flush(),
            Writer::Stdout(s) => s.flush().map_err(mark_stdout),
            Writer::StdoutBeside { out, closed } => {
                if !*closed {
                    match out.flush() {
                        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => *closed = true,
                        other => return other,
                    }
                }
                Ok(())
            }
        }
    }
}

/// Standard output's reader went away.
#[derive(Debug)]
pub struct StdoutClosed;

impl std::fmt::Display for StdoutClosed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("standard output was closed by its reader")
    }
}

impl std::error::Error for StdoutClosed {}

fn mark_stdout(e: io::Error) -> io::Error {
    if e.kind() == io::ErrorKind::BrokenPipe {
        io::Error::new(io::ErrorKind::BrokenPipe, StdoutClosed)
    } else {
        e
    }
}

/// Whether `error` is standard output's reader going away (`| head`): the output it wanted
/// has been delivered, so the command ends quietly with success.
pub fn is_closed_stdout(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause.is::<StdoutClosed>()
            || cause
                .downcast_ref::<io::Error>()
                .and_then(|e| e.get_ref())
                .is_some_and(|inner| inner.is::<StdoutClosed>())
    })
}

/// An output being written: buffered, to a temporary file, the target in place, or standard
/// output. Dropped unfinished, it removes its temporary file.
#[derive(Debug)]
pub struct Sink {
    target: Target,
    writer: Option<BufWriter<Writer>>,
    temp: Option<Temporary>,
    mode: Option<u32>,
}

impl Sink {
    /// Standard output, streamed. A reader that goes away ends the command quietly
    /// ([`is_closed_stdout`]).
    pub fn stdout() -> Sink {
        Sink::stdout_with(Writer::Stdout(io::stdout()))
    }

    /// Standard output beside file outputs (`eig --plot eig.png | head`): a reader that goes
    /// away ends only the table (the rest of it is dropped), and the files are still written
    /// and put in place.
    pub fn stdout_beside_files() -> Sink {
        Sink::stdout_with(Writer::StdoutBeside {
            out: io::stdout(),
            closed: false,
        })
    }

    fn stdout_with(writer: Writer) -> Sink {
        Sink {
            target: Target {
                option: "standard output".into(),
                shown: PathBuf::from("-"),
                place: Place::Direct(PathBuf::from("-")),
            },
            writer: Some(BufWriter::with_capacity(1 << 16, writer)),
            temp: None,
            mode: None,
        }
    }

    /// `--out eig.csv` (or `standard output`), for messages.
    pub fn describe(&self) -> String {
        if self.target.shown == Path::new("-") {
            self.target.option.clone()
        } else {
            self.target.describe()
        }
    }

    fn writer(&mut self) -> io::Result<&mut BufWriter<Writer>> {
        self.writer
            .as_mut()
            .ok_or_else(|| io::Error::other("the output was already finished"))
    }

    /// Writes `text`, naming the output in the error.
    pub fn text(&mut self, text: &str) -> Result<()> {
        let what = self.describe();
        self.write_all(text.as_bytes())
            .with_context(|| format!("writing {what}"))
    }

    /// Writes `bytes`, naming the output in the error.
    pub fn bytes(&mut self, bytes: &[u8]) -> Result<()> {
        let what = self.describe();
        self.write_all(bytes)
            .with_context(|| format!("writing {what}"))
    }

    /// Flushes everything written, and for a temporary file makes it durable and gives it the
    /// replaced file's permissions; ready for [`commit`]. An output written in place is
    /// complete once this returns.
    pub fn finish(mut self) -> Result<Finished> {
        let what = self.describe();
        let writer = self
            .writer
            .take()
            .context("the output was already finished")?;
        let inner = writer
            .into_inner()
            .map_err(|e| anyhow::Error::new(e.into_error()))
            .with_context(|| format!("writing {what}"))?;
        match inner {
            Writer::File(file) => {
                if let Some(temp) = &self.temp {
                    file.sync_all().with_context(|| format!("writing {what}"))?;
                    if let Some(mode) = self.mode {
                        set_mode(&temp.0, mode)
                            .with_context(|| format!("keeping the permissions of {what}"))?;
                    }
                }
            }
            Writer::Stdout(mut out) => out
                .flush()
                .map_err(mark_stdout)
                .with_context(|| format!("writing {what}"))?,
            Writer::StdoutBeside { out, closed } => {
                let mut writer = Writer::StdoutBeside { out, closed };
                writer.flush().with_context(|| format!("writing {what}"))?;
            }
        }
        Ok(Finished {
            target: self.target.clone(),
            temp: self.temp.take(),
        })
    }
}

impl Write for Sink {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.writer()?.write(bytes)
    }

    fn write_all(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.writer()?.write_all(bytes)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer()?.flush()
    }
}

#[cfg(unix)]
fn set_mode(path: &Path, mode: u32) -> io::Result<()> {
    use std::os::unix::fs::PermissionsExt;
    fs::set_permissions(path, fs::Permissions::from_mode(mode))
}

#[cfg(not(unix))]
fn set_mode(_path: &Path, _mode: u32) -> io::Result<()> {
    Ok(())
}

/// A finished output waiting for [`commit`]; dropped instead, its temporary file goes.
#[derive(Debug)]
pub struct Finished {
    target: Target,
    temp: Option<Temporary>,
}

/// Puts every finished output into place: each temporary file renamed onto its target.
/// Outputs written in place are complete already.
pub fn commit(outputs: Vec<Finished>) -> Result<()> {
    for output in &outputs {
        output.target.refuse_input()?;
    }
    let mut outputs = outputs;
    let mut failure = None;
    // Under the lock a signal handler takes: every output renamed, or (signal first) none.
    let mut guard = pending();
    for output in outputs.iter_mut() {
        if let (Some(temp), Place::Replace { target, .. }) =
            (output.temp.as_mut(), &output.target.place)
        {
            match fs::rename(&temp.0, target) {
                Ok(()) => {
                    // Renamed: nothing left to remove.
                    guard.temporaries.retain(|(t, _)| t != &temp.0);
                    temp.0 = PathBuf::new();
                }
                Err(e) => {
                    failure = Some(
                        anyhow::Error::new(e)
                            .context(format!("writing {}", output.target.describe())),
                    );
                    break;
                }
            }
        }
    }
    // The lock is released before the outputs not renamed remove their temporary files.
    drop(guard);
    drop(outputs);
    match failure {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// The `--out` table and `--plot` figure of a command, checked before any work: the plot's
/// extension names a figure format, each location can be written, and the two are distinct.
pub fn table_and_plot(
    out: Option<&Path>,
    plot: Option<&Path>,
) -> Result<(Option<Target>, Option<Target>)> {
    let plot = plot
        .map(|p| {
            whipple_report::Format::from_path(p)
                .with_context(|| format!("--plot {}", p.display()))?;
            Target::check("--plot", p)
        })
        .transpose()?;
    let out = out.map(|p| Target::check("--out", p)).transpose()?;
    if let (Some(a), Some(b)) = (&out, &plot) {
        distinct(a, b)?;
    }
    Ok((out, plot))
}

/// Refuses two outputs of one command that name the same file (`--out x.svg --plot x.svg`),
/// which would silently keep only one of them.
pub fn distinct(a: &Target, b: &Target) -> Result<()> {
    let same = a.destination() == b.destination()
        || fs::canonicalize(a.destination())
            .ok()
            .zip(fs::canonicalize(b.destination()).ok())
            .is_some_and(|(x, y)| x == y);
    if same {
        bail!(
            "{} and {} name the same file: give each output its own path",
            a.describe(),
            b.describe()
        );
    }
    Ok(())
}

/// A directory of several outputs (`validate --report DIR`): checked before computing,
/// created when missing, and removed again if the command fails before [`ReportDir::keep`].
#[derive(Debug)]
pub struct ReportDir {
    option: String,
    path: PathBuf,
    created: bool,
    kept: bool,
}

impl ReportDir {
    /// Checks `path`: an existing directory, or a missing one whose parent is a directory
    /// (then created, and removed again on failure). Something else in the way is an error.
    pub fn prepare(option: &str, path: &Path) -> Result<ReportDir> {
        let fail = |why: String| -> anyhow::Error {
            anyhow::anyhow!("{option} {}: {why}", path.display())
        };
        match fs::metadata(path) {
            Ok(meta) if meta.is_dir() => Ok(ReportDir {
                option: option.into(),
                path: path.into(),
                created: false,
                kept: false,
            }),
            Ok(_) => Err(fail("exists and is not a directory".into())),
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                let parent = directory_of(path);
                match fs::metadata(parent) {
                    Ok(meta) if meta.is_dir() => {}
                    _ => {
                        return Err(fail(format!(
                            "the directory {} does not exist",
                            parent.display()
                        )));
                    }
                }
                {
                    let mut guard = pending();
                    fs::create_dir(path).map_err(|e| fail(format!("cannot be created ({e})")))?;
                    guard.directories.push(path.to_path_buf());
                }
                Ok(ReportDir {
                    option: option.into(),
                    path: path.into(),
                    created: true,
                    kept: false,
                })
            }
            Err(e) => Err(fail(format!("cannot be reached ({e})"))),
        }
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The output `name` inside the directory, checked.
    pub fn file(&self, name: &str) -> Result<Target> {
        Target::check(&self.option, &self.path.join(name))
    }

    /// The outputs are in place: the directory stays.
    pub fn keep(mut self) {
        self.kept = true;
    }
}

impl Drop for ReportDir {
    fn drop(&mut self) {
        if self.created {
            let mut guard = pending();
            if !self.kept {
                // Only an empty directory goes: the temporary files inside are removed first.
                fs::remove_dir(&self.path).ok();
            }
            guard.directories.retain(|d| d != &self.path);
        }
    }
}

/// Writes `text` to standard output. A reader that went away (`whipple eig ... | head`) is not
/// an error: the output it wanted has been delivered.
pub fn print_stdout(text: &str) -> Result<()> {
    let mut sink = Sink::stdout();
    let result = sink.text(text).and_then(|()| sink.finish().map(|_| ()));
    match result {
        Err(e) if is_closed_stdout(&e) => Ok(()),
        other => other,
    }
}

/// A result as the outputs print it ([`whipple_front::format::number`]); a NaN or an infinity
/// is an error (no result is printed as one).
pub fn number(x: f64) -> Result<String> {
    whipple_front::format::number(x)
        .ok_or_else(|| anyhow!("a computed result is not a finite number ({x})"))
}

/// Parses speeds `START:STOP:STEP` into three finite numbers of m/s: `km/h` after them
/// (`10:30:0.5km/h`) gives them in km/h (whipple-front's [`split_speed`](whipple_front::units::split_speed)).
pub fn parse_triple(text: &str, option: &str) -> Result<(f64, f64, f64)> {
    Ok(parse_triple_in(text, option)?.0)
}

/// [`parse_triple`], with the unit the speeds were typed in.
pub fn parse_triple_in(text: &str, option: &str) -> Result<((f64, f64, f64), SpeedUnit)> {
    let (numbers, unit) = whipple_front::units::split_speed(text)
        .map_err(|e| anyhow!("{option}: {}", crate::speeds::rule_of(e)))?;
    let parts: Vec<&str> = numbers.split(':').collect();
    if parts.len() != 3 {
        bail!("{option} expects START:STOP:STEP (km/h after them for km/h), got `{text}`");
    }
    Ok((
        (
            unit.to_si(parse_finite(parts[0], option)?),
            unit.to_si(parse_finite(parts[1], option)?),
            unit.to_si(parse_finite(parts[2], option)?),
        ),
        unit,
    ))
}

/// A speed in km/h as the outputs print it beside m/s: to twelve significant digits, so that
/// a speed typed in km/h reads back as typed (10 km/h is 2.7777777777777777 m/s, whose product
/// with 3.6 is not 10 in floating point).
pub fn kmh_number(v: f64) -> Result<String> {
    number(as_typed(v, SpeedUnit::KilometresPerHour))
}

/// A speed [m/s] in the unit it was typed in: itself, or in km/h to twelve significant digits
/// ([`kmh_number`]).
pub fn as_typed(v: f64, unit: SpeedUnit) -> f64 {
    match unit {
        SpeedUnit::MetresPerSecond => v,
        SpeedUnit::KilometresPerHour => {
            let kmh = unit.from_si(v);
            format!("{kmh:.11e}").parse().unwrap_or(kmh)
        }
    }
}

/// A speed [m/s] printed in the unit it was typed in, without the unit: `5`, `18`.
pub fn speed_number(v: f64, unit: SpeedUnit) -> Result<String> {
    number(as_typed(v, unit))
}

/// A speed as the text outputs print it: `5 m/s`, or `5 m/s (18 km/h)` where the speeds were
/// typed in km/h.
pub fn speed_words(v: f64, unit: SpeedUnit) -> Result<String> {
    Ok(format!("{} m/s{}", number(v)?, kmh_beside(v, unit)?))
}

/// A speed as a figure's legend names it, in the unit it was typed in: `3 m/s`, `10 km/h`.
pub fn speed_label(v: f64, unit: SpeedUnit) -> Result<String> {
    Ok(format!("{} {}", speed_number(v, unit)?, unit.symbol()))
}

/// What follows a speed printed in m/s where the speeds were typed in km/h: ` (15.4525771308
/// km/h)`; nothing for m/s.
pub fn kmh_beside(v: f64, unit: SpeedUnit) -> Result<String> {
    Ok(match unit {
        SpeedUnit::MetresPerSecond => String::new(),
        SpeedUnit::KilometresPerHour => format!(" ({} km/h)", kmh_number(v)?),
    })
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
