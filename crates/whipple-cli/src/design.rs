//! `whipple map`, `whipple study` and `whipple merge`: design studies over one or two
//! parameters, streamed to CSV or JSON, sharded across machines and merged back bit for bit.

use std::fmt::Write as _;
use std::io::{BufRead, IsTerminal};
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use rayon::prelude::*;
use whipple::advanced::design::{DesignRow, DesignStatus, Parameter, Shard, StudySettings};
use whipple_front::design::{AxisSpec, DesignStudy};
use whipple_report::{MapData, StudyData, design_map, design_study};

use crate::bike::{RunContext, load};
use crate::output;
use crate::speeds::{parse_range, parse_range_in};
use whipple_front::units::SpeedUnit;

/// Output formats of a design study.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DesignFormat {
    /// Comma-separated values, one row per design (mergeable).
    Csv,
    /// One JSON document: the study and its rows.
    Json,
}

/// The quantities a map can show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Quantity {
    /// Total width of the self-stable speed ranges [m/s].
    StableWidth,
    /// The weave speed v_w [m/s].
    WeaveSpeed,
    /// The capsize speed v_c [m/s].
    CapsizeSpeed,
    /// The double-root speed v_d [m/s].
    DoubleRootSpeed,
    /// The weave frequency at v_w [rad/s].
    WeaveFrequency,
    /// The largest real part of the eigenvalues at --speed [1/s].
    MaxReal,
    /// Self-stable at every speed of --band A:B: the smaller margin [m/s] by which the
    /// self-stable range reaches past the band's ends (the designs that qualify outlined).
    StableOver,
}

impl Quantity {
    fn column(self) -> &'static str {
        match self {
            Quantity::StableWidth => "stable_width",
            Quantity::WeaveSpeed => "v_w",
            Quantity::CapsizeSpeed => "v_c",
            Quantity::DoubleRootSpeed => "v_d",
            Quantity::WeaveFrequency => "weave_frequency",
            Quantity::MaxReal => "max_real",
            Quantity::StableOver => "band_margin",
        }
    }
    fn label(self) -> &'static str {
        match self {
            Quantity::StableWidth => "width of the self-stable speed range [m/s]",
            Quantity::WeaveSpeed => "weave speed v_w [m/s]",
            Quantity::CapsizeSpeed => "capsize speed v_c [m/s]",
            Quantity::DoubleRootSpeed => "double-root speed v_d [m/s]",
            Quantity::WeaveFrequency => "weave frequency at v_w [rad/s]",
            Quantity::MaxReal => "largest real part of the eigenvalues [1/s]",
            Quantity::StableOver => "margin of self-stability over the band [m/s]",
        }
    }
    fn from_column(name: &str) -> Option<Quantity> {
        [
            Quantity::StableWidth,
            Quantity::WeaveSpeed,
            Quantity::CapsizeSpeed,
            Quantity::DoubleRootSpeed,
            Quantity::WeaveFrequency,
            Quantity::MaxReal,
            Quantity::StableOver,
        ]
        .into_iter()
        .find(|q| q.column() == name)
    }
    /// Whether the map outlines design `row`: it has a self-stable range, or (stable-over) it
    /// is self-stable over the band.
    fn outlined(self, row: &DesignRow) -> bool {
        match self {
            Quantity::StableOver => row.quantities.stable_over == Some(true),
            _ => row.quantities.stable,
        }
    }

    /// The legend's two lines for the outline, the band in the unit it was typed in (its ends
    /// short enough for the legend: 16–23 km/h, not 4.444444444444445–6.388888888888889 m/s).
    fn outline(self, band: Option<(f64, f64)>, unit: SpeedUnit) -> [String; 2] {
        match (self, band) {
            (Quantity::StableOver, Some((a, b))) => [
                "self-stable over".to_string(),
                format!(
                    "{}–{} {} (inside)",
                    legend_speed(unit.from_si(a)),
                    legend_speed(unit.from_si(b)),
                    unit.symbol()
                ),
            ],
            _ => [
                "self-stable range".to_string(),
                "exists (inside)".to_string(),
            ],
        }
    }

    fn of(self, row: &DesignRow) -> Option<f64> {
        let q = &row.quantities;
        if row.status != DesignStatus::Ok {
            return None;
        }
        match self {
            // A design with no self-stable speed has no width: "none", never 0.
            Quantity::StableWidth => q.stable.then_some(q.stable_width),
            Quantity::StableOver => Some(q.band_margin_below?.min(q.band_margin_above?)),
            Quantity::WeaveSpeed => q.weave_speed,
            Quantity::CapsizeSpeed => q.capsize_speed,
            Quantity::DoubleRootSpeed => q.double_root_speed,
            Quantity::WeaveFrequency => q.weave_frequency,
            Quantity::MaxReal => q.max_real,
        }
    }
}

/// The options `map` and `study` share.
#[derive(clap::Args, Debug)]
pub struct StudyArgs {
    /// The speed [m/s, or km/h after it: 18km/h] at which max_real (largest real part) is read.
    #[arg(value_parser = crate::typed_speed_arg, long, allow_hyphen_values = true)]
    pub speed: Option<crate::TypedSpeed>,
    /// Speed range LO:HI [m/s, or km/h after them] for the critical speeds (default: every speed v >= 0).
    #[arg(long, allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Also compute the double-root speed v_d (about twice the time).
    #[arg(long)]
    pub double_root: bool,
    /// A band of speeds A:B [m/s, or km/h after them] inside the range: is each design self-stable at every speed
    /// of it, and by what margin (the columns stable_over, band_margin_below and
    /// band_margin_above; --quantity stable-over maps it).
    #[arg(long, allow_hyphen_values = true)]
    pub band: Option<String>,
    /// Output format of the rows.
    #[arg(long, value_enum, default_value = "csv")]
    pub format: DesignFormat,
    /// Write the rows to this file instead of standard output.
    #[arg(long)]
    pub out: Option<std::path::PathBuf>,
    /// Compute only part I of N (0-based, I/N) for a job array; `whipple merge` joins them.
    #[arg(long)]
    pub shard: Option<String>,
}

impl StudyArgs {
    /// The arguments of a map (`y` given) or a one-parameter study.
    pub fn args<'a>(
        &'a self,
        bike: &'a str,
        x: &'a str,
        y: Option<&'a str>,
        quantity: Quantity,
        plot: Option<&'a Path>,
    ) -> DesignArgs<'a> {
        DesignArgs {
            bike,
            x,
            y,
            quantity,
            speed: self.speed.map(|t| t.si),
            range: self.range.as_deref(),
            double_root: self.double_root,
            band: self.band.as_deref(),
            format: self.format,
            out: self.out.as_deref(),
            plot,
            shard: self.shard.as_deref(),
        }
    }
}

/// What `map` and `study` run with.
pub struct DesignArgs<'a> {
    pub bike: &'a str,
    pub x: &'a str,
    pub y: Option<&'a str>,
    pub quantity: Quantity,
    pub speed: Option<f64>,
    pub range: Option<&'a str>,
    pub double_root: bool,
    pub band: Option<&'a str>,
    pub format: DesignFormat,
    pub out: Option<&'a Path>,
    pub plot: Option<&'a Path>,
    pub shard: Option<&'a str>,
}

/// The most cells a plot holds in memory (a 5000 × 5000 map: 200 MB).
const MAX_PLOT_CELLS: u64 = 25_000_000;

const COLUMNS: &str = "v_d,v_w,v_c,weave_frequency,stable,stable_width,stable_from,stable_to,\
max_real,max_real_mode,unresolved,";

/// The columns of a study with a band (--band), between `unresolved` and `status`.
const BAND_COLUMNS: &str = "stable_over,band_margin_below,band_margin_above,";

const LAST_COLUMNS: &str = "status,reason";

/// A number as the CSV holds it: shortest round-trip digits, `inf` for an unbounded end, empty
/// for none (a NaN is never written).
fn num(out: &mut String, x: Option<f64>) {
    match x {
        Some(v) if v == f64::INFINITY => out.push_str("inf"),
        Some(v) if v.is_finite() => {
            let _ = write!(out, "{v}");
        }
        _ => {}
    }
}

fn csv_text(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\"").replace(['\n', '\r'], " "))
    } else {
        s.to_string()
    }
}

/// One design as a CSV line, written straight into `out` (no text allocated per field: a map
/// writes a million of them).
fn csv_row(out: &mut String, r: &DesignRow, two: bool, band: bool) {
    let q = &r.quantities;
    let _ = write!(out, "{},{},", r.index, r.ix);
    if two {
        let _ = write!(out, "{},", r.iy);
    }
    let _ = write!(out, "{},", r.x);
    if two {
        let _ = write!(out, "{},", r.y);
    }
    let ok = r.status == DesignStatus::Ok;
    let flag = |out: &mut String, b: bool| {
        if ok {
            out.push(if b { '1' } else { '0' });
        }
    };
    for x in [
        q.double_root_speed,
        q.weave_speed,
        q.capsize_speed,
        q.weave_frequency,
    ] {
        num(out, x);
        out.push(',');
    }
    flag(out, q.stable);
    out.push(',');
    if ok {
        num(out, Some(q.stable_width));
    }
    out.push(',');
    for x in [q.stable_from, q.stable_to, q.max_real] {
        num(out, x);
        out.push(',');
    }
    out.push_str(q.max_real_mode.map_or("", |m| m.name()));
    out.push(',');
    flag(out, q.unresolved);
    out.push(',');
    if band {
        // Empty where undecided (round-off left speeds of the band open) or not computed.
        if let Some(b) = q.stable_over {
            out.push(if b { '1' } else { '0' });
        }
        out.push(',');
        for x in [q.band_margin_below, q.band_margin_above] {
            num(out, x);
            out.push(',');
        }
    }
    out.push_str(match r.status {
        DesignStatus::Ok => "ok",
        DesignStatus::Invalid => "invalid",
        DesignStatus::AccuracyLost => "accuracy_lost",
    });
    out.push(',');
    out.push_str(&csv_text(r.reason.as_deref().unwrap_or("")));
    out.push('\n');
}

/// The study's description line (a JSON object), identical in every shard.
fn study_line(label: &str, study: &DesignStudy) -> Result<String> {
    let options = &study.study.options;
    let doc = serde_json::json!({
        "bike": label,
        "x": study.x,
        "y": study.y,
        "range": [finite(options.range.0), finite(options.range.1)],
        "speed": options.speed,
        "double_root": options.double_root,
        "designs": study.study.len(),
    });
    let mut doc = doc;
    // Only a study with a band says so: the description of every other study is as it was.
    if let (Some((a, b)), Some(map)) = (options.band, doc.as_object_mut()) {
        map.insert("band".into(), serde_json::json!([a, b]));
    }
    Ok(serde_json::to_string(&doc)?)
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

fn header(study: &DesignStudy) -> String {
    let mut h = String::from("index,ix,");
    if let Some(y) = &study.y {
        let _ = write!(h, "iy,{},{},", csv_text(&study.x.name), csv_text(&y.name));
    } else {
        let _ = write!(h, "{},", csv_text(&study.x.name));
    }
    h.push_str(COLUMNS);
    if study.study.options.band.is_some() {
        h.push_str(BAND_COLUMNS);
    }
    h.push_str(LAST_COLUMNS);
    h.push('\n');
    h
}

/// Where the rows go: `--out` through [`crate::output`] (checked before the work, written to a
/// temporary file beside it, renamed into place by `finish`, through symbolic links, devices
/// in place), or standard output (a reader that goes away ends the run quietly, or beside a
/// plot only the rows: the plot is still drawn).
struct Sink(output::Sink);

impl Sink {
    fn open(out: Option<&Path>, beside_plot: bool) -> Result<Sink> {
        Ok(Sink(match out {
            None if beside_plot => output::Sink::stdout_beside_files(),
            None => output::Sink::stdout(),
            Some(path) => output::Target::check("--out", path)?.open()?,
        }))
    }

    fn write(&mut self, text: &str) -> Result<()> {
        self.0.text(text)
    }

    /// Puts the rows in place. Dropped unfinished (an error, Ctrl-C), the temporary file goes.
    fn finish(self) -> Result<()> {
        output::commit(vec![self.0.finish()?])
    }
}

fn progress(total: u64) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::hidden();
    bar.set_length(total);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "designs {bar:40} {percent:>3}% {human_pos}/{human_len} {per_sec} eta {eta}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

/// Runs `map` (two axes) or `study` (one).
pub fn run(cx: &RunContext, args: &DesignArgs<'_>) -> Result<()> {
    let bike = load(cx, args.bike)?;
    let x = AxisSpec::parse(args.x, &bike.bicycle).context(if args.y.is_some() {
        "--x"
    } else {
        "--vary"
    })?;
    let y = match args.y {
        Some(spec) => Some(AxisSpec::parse(spec, &bike.bicycle).context("--y")?),
        None => None,
    };
    let (lo, hi) = match args.range {
        Some(text) => parse_range(text, "--range")?,
        None => (0.0, f64::INFINITY),
    };
    let speed_axis = x.axis.parameter == Parameter::Speed
        || y.as_ref()
            .is_some_and(|a| a.axis.parameter == Parameter::Speed);
    if args.quantity == Quantity::MaxReal && args.speed.is_none() && !speed_axis {
        bail!("--quantity max-real needs --speed V (or an axis named speed)");
    }
    let (band, band_unit) = match args.band {
        Some(text) => {
            let (band, unit) = parse_range_in(text, "--band")?;
            (Some(band), unit)
        }
        None => (None, SpeedUnit::MetresPerSecond),
    };
    if args.quantity == Quantity::StableOver && band.is_none() {
        bail!("--quantity stable-over needs --band A:B (for example --band 4:8)");
    }
    let options = StudySettings {
        range: (lo, hi),
        speed: args.speed,
        double_root: args.double_root || args.quantity == Quantity::DoubleRootSpeed,
        band,
    };
    let study = DesignStudy::new(bike.bicycle.clone(), x, y, options)
        .with_context(|| format!("the study of {}", bike.label))?;
    let shard = match args.shard {
        Some(text) => Shard::parse(text).context("--shard")?,
        None => Shard::WHOLE,
    };
    if args.plot.is_some() && shard != Shard::WHOLE {
        bail!("--plot draws a whole study: plot after `whipple merge` (merge --plot)");
    }
    if args.plot.is_some() && study.study.len() > MAX_PLOT_CELLS {
        bail!(
            "--plot holds every design in memory: at most {MAX_PLOT_CELLS} designs, the study has {}",
            study.study.len()
        );
    }
    if let Some(p) = args.plot {
        whipple_report::Format::from_path(p)?;
        let dir = p
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        if !dir.is_dir() {
            bail!(
                "cannot write {}: the directory {} does not exist",
                p.display(),
                dir.display()
            );
        }
    }
    let label = bike.label.clone();
    let two = study.y.is_some();
    let with_band = band.is_some();
    let mut sink = Sink::open(args.out, args.plot.is_some())?;
    let (first, end) = shard.indices(study.study.len());
    let mut head = String::new();
    match args.format {
        DesignFormat::Csv => {
            writeln!(
                head,
                "# whipple design study: {}",
                study_line(&label, &study)?
            )?;
            if shard != Shard::WHOLE {
                writeln!(
                    head,
                    "# shard {}/{}: designs {first}..{end}",
                    shard.index, shard.count
                )?;
            }
            head.push_str(&header(&study));
        }
        DesignFormat::Json => {
            write!(
                head,
                "{{\"study\": {},\n\"shard\": [{}, {}],\n\"rows\": [\n",
                study_line(&label, &study)?,
                shard.index,
                shard.count
            )?;
        }
    }
    sink.write(&head)?;
    let keep = args.plot.is_some();
    let mut values: Vec<f64> = Vec::new();
    let mut stable: Vec<bool> = Vec::new();
    let mut study_rows: Vec<DesignRow> = Vec::new();
    // Set by a signal (crate::interrupt), whose handler then ends the process; the study
    // stops at its next piece meanwhile.
    let stop = crate::interrupt::flag();
    let bar = progress(end - first);
    let started = Instant::now();
    let on_terminal = std::io::stderr().is_terminal();
    let mut shown = false;
    let mut written = 0u64;
    let mut text = String::new();
    let mut closed = false;
    let result = study.study.run(shard, stop, |rows| {
        text.clear();
        if args.format == DesignFormat::Csv {
            // Formatting the numbers costs as much as computing the designs: it runs on every
            // core too, in pieces joined in order.
            let pieces: Vec<String> = rows
                .par_chunks(2048)
                .map(|piece| {
                    let mut t = String::with_capacity(160 * piece.len());
                    for r in piece {
                        csv_row(&mut t, r, two, with_band);
                    }
                    t
                })
                .collect();
            for piece in &pieces {
                text.push_str(piece);
            }
        }
        for r in rows {
            if args.format == DesignFormat::Json {
                if written > 0 {
                    text.push_str(",\n");
                }
                text.push_str(&serde_json::to_string(&JsonRow(r, with_band)).map_err(|e| {
                    whipple::Error::NonFinite {
                        context: e.to_string(),
                    }
                })?);
            }
            written += 1;
            if keep {
                if two {
                    values.push(args.quantity.of(r).unwrap_or(f64::NAN));
                    stable.push(args.quantity.outlined(r));
                } else {
                    study_rows.push(r.clone());
                }
            }
        }
        sink.write(&text).map_err(|e| {
            // A reader that went away (`whipple map ... | head`) ends the run quietly.
            closed = output::is_closed_stdout(&e);
            whipple::Error::InvalidArgument {
                what: "output",
                rule: format!("{e:#}"),
            }
        })?;
        bar.inc(rows.len() as u64);
        if on_terminal && !shown && started.elapsed().as_secs_f64() > 1.0 {
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            shown = true;
        }
        Ok(())
    });
    bar.finish_and_clear();
    if let Err(e) = result {
        if closed {
            return Ok(());
        }
        // The sink's temporary file is removed when it is dropped: nothing half-written.
        if stop.load(Ordering::Relaxed) {
            bail!(
                "stopped by Ctrl-C after {written} designs; nothing was written to the output file"
            );
        }
        return Err(anyhow!(e)).context(format!("the study of {label}"));
    }
    if args.format == DesignFormat::Json {
        sink.write("\n]}\n")?;
    }
    sink.finish()?;
    if let Some(path) = args.plot {
        let figure = if let Some(y) = &study.y {
            let (bx, by) = study.base_point();
            design_map(&MapData {
                title: format!("{label}: {}", args.quantity.label()),
                x_label: axis_label(&study.x),
                y_label: axis_label(y),
                x: (study.x.axis.start, study.x.axis.stop, study.x.axis.count),
                y: (y.axis.start, y.axis.stop, y.axis.count),
                values,
                stable,
                outline: args.quantity.outline(band, band_unit),
                diverging: args.quantity == Quantity::MaxReal,
                quantity: args.quantity.label().to_string(),
                base: bx.zip(by),
            })?
        } else {
            let (bx, _) = study.base_point();
            study_figure(&label, &study.x, &study_rows, bx)?
        };
        let bytes = figure.render_for_path(path)?;
        output::Target::check("--plot", path)?.write_whole(&bytes)?;
    }
    Ok(())
}

fn axis_label(a: &AxisSpec) -> String {
    format!("{} [{}]", a.name, a.unit())
}

fn study_figure(
    label: &str,
    x: &AxisSpec,
    rows: &[DesignRow],
    base: Option<f64>,
) -> Result<whipple_report::Figure> {
    let mut data = StudyData {
        title: format!("{label}: critical speeds against {}", x.name),
        x_label: axis_label(x),
        x: Vec::with_capacity(rows.len()),
        weave: Vec::with_capacity(rows.len()),
        capsize: Vec::with_capacity(rows.len()),
        stable_from: Vec::with_capacity(rows.len()),
        stable_to: Vec::with_capacity(rows.len()),
        base,
    };
    for r in rows {
        let q = &r.quantities;
        let ok = r.status == DesignStatus::Ok;
        data.x.push(r.x);
        data.weave.push(if ok { q.weave_speed } else { None });
        data.capsize.push(if ok { q.capsize_speed } else { None });
        data.stable_from.push(if ok { q.stable_from } else { None });
        data.stable_to.push(if ok { q.stable_to } else { None });
    }
    Ok(design_study(&data)?)
}

/// A row as JSON, with unbounded values as null and the quantities flattened (and the band's
/// answer where the study has a band).
struct JsonRow<'a>(&'a DesignRow, bool);

impl serde::Serialize for JsonRow<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let r = self.0;
        let q = &r.quantities;
        let f = |x: Option<f64>| x.filter(|v| v.is_finite());
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("index", &r.index)?;
        m.serialize_entry("ix", &r.ix)?;
        m.serialize_entry("iy", &r.iy)?;
        m.serialize_entry("x", &r.x)?;
        m.serialize_entry("y", &r.y)?;
        m.serialize_entry("status", &r.status)?;
        if let Some(reason) = &r.reason {
            m.serialize_entry("reason", reason)?;
        }
        if r.status == DesignStatus::Ok {
            m.serialize_entry("v_d", &f(q.double_root_speed))?;
            m.serialize_entry("v_w", &f(q.weave_speed))?;
            m.serialize_entry("v_c", &f(q.capsize_speed))?;
            m.serialize_entry("weave_frequency", &f(q.weave_frequency))?;
            m.serialize_entry("stable", &q.stable)?;
            m.serialize_entry("stable_width", &f(Some(q.stable_width)))?;
            m.serialize_entry("stable_unbounded", &(q.stable_width == f64::INFINITY))?;
            m.serialize_entry("stable_from", &f(q.stable_from))?;
            m.serialize_entry("stable_to", &f(q.stable_to))?;
            m.serialize_entry("max_real", &f(q.max_real))?;
            m.serialize_entry("max_real_mode", &q.max_real_mode)?;
            m.serialize_entry("unresolved", &q.unresolved)?;
            if self.1 {
                m.serialize_entry("stable_over", &q.stable_over)?;
                m.serialize_entry("band_margin_below", &f(q.band_margin_below))?;
                m.serialize_entry("band_margin_above", &f(q.band_margin_above))?;
                m.serialize_entry(
                    "band_margin_above_unbounded",
                    &(q.band_margin_above == Some(f64::INFINITY)),
                )?;
            }
        }
        m.end()
    }
}

/// `whipple merge`: shards' CSV files back into the one-machine file, bit for bit.
pub fn merge(
    files: &[PathBuf],
    out: Option<&Path>,
    plot: Option<&Path>,
    quantity: Quantity,
) -> Result<()> {
    if files.is_empty() {
        bail!("merge needs the shards' CSV files");
    }
    struct Part {
        path: PathBuf,
        index: u64,
        count: u64,
        first: u64,
        end: u64,
    }
    let mut study: Option<(String, String)> = None;
    let mut parts = Vec::new();
    for path in files {
        let file =
            std::fs::File::open(path).with_context(|| format!("reading {}", path.display()))?;
        let mut lines = std::io::BufReader::new(file).lines();
        let line = |l: Option<std::io::Result<String>>| -> Result<String> {
            Ok(l.transpose()?.unwrap_or_default())
        };
        let first_line = line(lines.next())?;
        let shard_line = line(lines.next())?;
        let header_line = line(lines.next())?;
        let Some(description) = first_line.strip_prefix("# whipple design study: ") else {
            bail!(
                "{} is not a CSV file written by `whipple map` or `whipple study`",
                path.display()
            );
        };
        let Some(rest) = shard_line.strip_prefix("# shard ") else {
            bail!(
                "{} is not a shard (no `# shard I/N` line): it is a whole study already",
                path.display()
            );
        };
        let parse = || -> Option<(u64, u64, u64, u64)> {
            let (ik, range) = rest.split_once(": designs ")?;
            let (i, n) = ik.split_once('/')?;
            let (a, b) = range.split_once("..")?;
            Some((
                i.parse().ok()?,
                n.parse().ok()?,
                a.parse().ok()?,
                b.parse().ok()?,
            ))
        };
        let (index, count, first, end) = parse()
            .ok_or_else(|| anyhow!("{}: unreadable shard line `{shard_line}`", path.display()))?;
        match &study {
            None => study = Some((description.to_string(), header_line.clone())),
            Some((d, h)) => {
                if d != description || *h != header_line {
                    bail!(
                        "{} belongs to another study than {}",
                        path.display(),
                        files[0].display()
                    );
                }
            }
        }
        parts.push(Part {
            path: path.clone(),
            index,
            count,
            first,
            end,
        });
    }
    parts.sort_by_key(|p| p.index);
    let count = parts[0].count;
    let designs: u64 = serde_json::from_str::<serde_json::Value>(
        &study.as_ref().map(|s| s.0.clone()).unwrap_or_default(),
    )
    .ok()
    .and_then(|d| d["designs"].as_u64())
    .ok_or_else(|| anyhow!("unreadable study line"))?;
    for (k, p) in parts.iter().enumerate() {
        if p.count != count || p.index != k as u64 {
            bail!(
                "the shards do not make a whole: expected shard {k}/{count}, found {}/{} ({})",
                p.index,
                p.count,
                p.path.display()
            );
        }
        let want = Shard {
            index: p.index,
            count,
        }
        .indices(designs);
        if (p.first, p.end) != want {
            bail!(
                "{}: its design range does not match its shard",
                p.path.display()
            );
        }
    }
    if parts.len() as u64 != count {
        bail!(
            "{} of {count} shards given: missing {}",
            parts.len(),
            (parts.len() as u64..count)
                .map(|k| format!("{k}/{count}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let (description, header_line) = study.unwrap_or_default();
    let mut sink = Sink::open(out, plot.is_some())?;
    sink.write(&format!(
        "# whipple design study: {description}\n{header_line}\n"
    ))?;
    let columns: Vec<&str> = header_line.split(',').collect();
    let col = columns.iter().position(|c| *c == quantity.column());
    // The outline: designs with a self-stable range, or for stable-over those that qualify.
    let stable_col = columns.iter().position(|c| {
        *c == if quantity == Quantity::StableOver {
            "stable_over"
        } else {
            "stable"
        }
    });
    // stable-over's value is the smaller of the two margins.
    let margins = (
        columns.iter().position(|c| *c == "band_margin_below"),
        columns.iter().position(|c| *c == "band_margin_above"),
    );
    if plot.is_some() && quantity == Quantity::StableOver && margins.0.is_none() {
        bail!("--quantity stable-over needs shards computed with --band");
    }
    let mut values = Vec::new();
    let mut stable = Vec::new();
    for p in &parts {
        let file = std::fs::File::open(&p.path)?;
        let mut rows = 0u64;
        for (n, l) in std::io::BufReader::new(file).lines().enumerate() {
            let l = l.with_context(|| format!("reading {}", p.path.display()))?;
            if n < 3 {
                continue;
            }
            rows += 1;
            if plot.is_some() {
                let fields: Vec<&str> = l.split(',').collect();
                let get = |c: Option<usize>| c.and_then(|c| fields.get(c)).copied().unwrap_or("");
                let value = |text: &str| match text {
                    "inf" => f64::INFINITY,
                    t => t.parse().unwrap_or(f64::NAN),
                };
                values.push(if quantity == Quantity::StableOver {
                    value(get(margins.0)).min(value(get(margins.1)))
                } else {
                    value(get(col))
                });
                stable.push(get(stable_col) == "1");
            }
            sink.write(&l)?;
            sink.write("\n")?;
        }
        if rows != p.end - p.first {
            bail!(
                "{} holds {rows} rows, its shard {} (was it cut short?)",
                p.path.display(),
                p.end - p.first
            );
        }
    }
    sink.finish()?;
    if let Some(path) = plot {
        let d: serde_json::Value = serde_json::from_str(&description)?;
        let axis = |a: &serde_json::Value| -> Option<(String, f64, f64, usize, bool)> {
            Some((
                a["name"].as_str()?.to_string(),
                a["start"].as_f64()?,
                a["stop"].as_f64()?,
                a["count"].as_u64()? as usize,
                a["degrees"].as_bool()?,
            ))
        };
        let x = axis(&d["x"]).ok_or_else(|| anyhow!("unreadable x axis"))?;
        let Some(y) = axis(&d["y"]) else {
            bail!("merge --plot draws maps; for a one-parameter study plot the whole study");
        };
        let unit = |(name, _, _, _, deg): &(String, f64, f64, usize, bool)| {
            format!("{name} [{}]", if *deg { "deg" } else { "SI" })
        };
        let figure = design_map(&MapData {
            title: format!("{}: {}", d["bike"].as_str().unwrap_or(""), quantity.label()),
            x_label: unit(&x),
            y_label: unit(&y),
            x: (x.1, x.2, x.3),
            y: (y.1, y.2, y.3),
            values,
            stable,
            // The shards' header keeps the band in m/s.
            outline: quantity.outline(
                d["band"]
                    .as_array()
                    .and_then(|b| Some((b.first()?.as_f64()?, b.get(1)?.as_f64()?))),
                SpeedUnit::MetresPerSecond,
            ),
            diverging: quantity == Quantity::MaxReal,
            quantity: quantity.label().to_string(),
            base: None,
        })?;
        output::Target::check("--plot", path)?.write_whole(&figure.render_for_path(path)?)?;
    }
    let _ = Quantity::from_column;
    Ok(())
}

/// A speed for a legend: as typed when that is short (`4`, `6.5`), else to four decimals.
fn legend_speed(v: f64) -> String {
    let typed = format!("{v}");
    if typed.len() <= 7 {
        typed
    } else {
        let rounded = format!("{v:.4}");
        rounded
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::legend_speed;

    #[test]
    fn legend_speeds_are_short() {
        assert_eq!(legend_speed(4.0), "4");
        assert_eq!(legend_speed(6.5), "6.5");
        assert_eq!(legend_speed(16.0 / 3.6), "4.4444");
        assert_eq!(legend_speed(23.0 / 3.6), "6.3889");
        assert_eq!(legend_speed(20.0 / 3.6), "5.5556");
        assert_eq!(legend_speed(25.2 / 3.6), "7");
    }
}
