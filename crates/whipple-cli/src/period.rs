//! `whipple period RECORD`: a pendulum's period (with σ) and damping fitted to an oscillation
//! record (CSV or MATLAB `.mat`), and a figure of the record with the fitted curve.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use whipple::advanced::measured::period::{PeriodFit, decay_window, fit_period};
use whipple_front::record::{MAX_RECORD_BYTES, Record, RecordRequest, read_record};
use whipple_report::{Dash, Series, XyPlotOptions, line_plot};

use crate::output::{Target, print_stdout, register_input};

/// The most points of the record drawn (every k-th sample beyond it; the fitted curve is drawn
/// at as many points).
const MAX_DRAWN: usize = 4000;

/// The options of `whipple period`.
#[derive(Debug, Args)]
pub struct PeriodArgs {
    /// The oscillation record: a CSV file (a time column and a signal column, or one column
    /// with --rate) or a MATLAB v5 .mat file (BicycleParameters' rate-gyro files: `data`, with
    /// `ActualRate`, `sampleRate` or `time`).
    record: PathBuf,
    /// The signal's column (header name or 1-based number) or .mat variable (default: the CSV's
    /// second of two columns; the .mat's `data`).
    #[arg(long)]
    column: Option<String>,
    /// The time column or .mat variable, in seconds (default: the CSV's first column; the
    /// .mat's `time` when it has one).
    #[arg(long)]
    time: Option<String>,
    /// The sample rate in Hz, for a record without times (a .mat's own rate is used otherwise).
    #[arg(long)]
    rate: Option<f64>,
    /// Fit only the samples from the largest swing to the last above this fraction of it, as
    /// BicycleParameters does with 0.1 (default: every sample).
    #[arg(long)]
    trim: Option<f64>,
    /// Also draw the record and the fitted curve to this .svg or .png file.
    #[arg(long)]
    plot: Option<PathBuf>,
}

fn read_capped(path: &Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let context = || format!("reading the record {}", path.display());
    let file = std::fs::File::open(path).with_context(context)?;
    let mut bytes = Vec::new();
    file.take(MAX_RECORD_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .with_context(context)?;
    if bytes.len() > MAX_RECORD_BYTES {
        bail!(
            "{}: longer than {} MiB, the most a record may hold",
            path.display(),
            MAX_RECORD_BYTES >> 20
        );
    }
    Ok(bytes)
}

/// Runs `whipple period`.
pub fn run(args: PeriodArgs) -> Result<()> {
    let plot = args
        .plot
        .as_deref()
        .map(|p| {
            whipple_report::Format::from_path(p)
                .with_context(|| format!("--plot {}", p.display()))?;
            Target::check("--plot", p)
        })
        .transpose()?;
    let path = &args.record;
    let bytes = read_capped(path)?;
    register_input(path);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let request = RecordRequest {
        signal: args.column.clone(),
        time: args.time.clone(),
        rate: args.rate,
    };
    let record = read_record(&bytes, &name, &request)
        .map_err(|e| anyhow::anyhow!(whipple_front::message::message(&e)))
        .with_context(|| format!("reading the record {}", path.display()))?;
    let window = match args.trim {
        Some(fraction) => decay_window(&record.signal, fraction)
            .map_err(|e| anyhow::anyhow!(whipple_front::message::message(&e)))
            .context("--trim")?,
        None => 0..record.signal.len(),
    };
    let fit = fit_period(&record.time[window.clone()], &record.signal[window.clone()])
        .map_err(|e| anyhow::anyhow!(whipple_front::message::message(&e)))
        .with_context(|| format!("fitting the period of {}", path.display()))?;
    print_stdout(&report(&name, &record, &window, &fit))?;
    if let Some(target) = plot {
        let figure = figure(&name, &record, &window, &fit)?;
        let bytes = figure
            .render_for_path(target.path())
            .with_context(|| format!("drawing {}", target.path().display()))?;
        target.write_whole(&bytes)?;
    }
    Ok(())
}

fn report(name: &str, record: &Record, window: &std::ops::Range<usize>, fit: &PeriodFit) -> String {
    let samples = if window.len() == record.signal.len() {
        format!("{} samples", record.signal.len())
    } else {
        format!(
            "samples {} to {} of {}",
            window.start + 1,
            window.end,
            record.signal.len()
        )
    };
    format!(
        "record: {name} (signal {}, time from {}; {samples})\n\
         period T = {:.10} ± {:.3e} s\n\
         damping ratio ζ = {:.6e} ± {:.3e}\n\
         natural frequency ω_n = {:.8} rad/s\n\
         fit: y = c + e^(−ζ ω_n t) (a sin ω_d t + b cos ω_d t), amplitude {:.6}, r² = {:.8}, \
         residual rms {:.4e} (σ {:.4e}), {} iterations\n",
        record.signal_name,
        record.time_source,
        fit.period,
        fit.period_sigma,
        fit.damping_ratio,
        fit.damping_ratio_sigma,
        fit.natural_frequency,
        fit.amplitude,
        fit.r_squared,
        fit.residual_rms,
        fit.residual_sigma,
        fit.iterations,
    )
}

fn figure(
    name: &str,
    record: &Record,
    window: &std::ops::Range<usize>,
    fit: &PeriodFit,
) -> Result<whipple_report::Figure> {
    let stride = record.signal.len().div_ceil(MAX_DRAWN).max(1);
    let measured: Vec<(f64, f64)> = record
        .time
        .iter()
        .zip(&record.signal)
        .step_by(stride)
        .map(|(t, y)| (*t, *y))
        .collect();
    let fitted: Vec<(f64, f64)> = record.time[window.clone()]
        .iter()
        .step_by(stride)
        .map(|t| (*t, fit.evaluate(*t)))
        .collect();
    let options = XyPlotOptions {
        title: Some(format!(
            "{name}: T = {:.6} ± {:.2e} s, ζ = {:.4e}",
            fit.period, fit.period_sigma, fit.damping_ratio
        )),
        x_label: "time t [s]".into(),
        y_label: format!("{} [the record's unit]", record.signal_name),
        ..XyPlotOptions::default()
    };
    let series = [
        Series::new("record", measured).coloured(0),
        Series::new("fitted decaying oscillation", fitted)
            .coloured(1)
            .dashed(Dash::Dashed),
    ];
    Ok(line_plot(&series, &[], &options)?)
}
