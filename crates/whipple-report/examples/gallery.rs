//! Renders every figure for the benchmark bicycle and the Schwinn Crown into a directory given
//! as the first argument (default: the system's temporary directory), for looking at them.

use std::path::PathBuf;

use whipple::{Canonical, presets};
use whipple_report::{BikeEigen, EigenPlotOptions, Format, eigen_comparison_plot, eigen_plot};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(std::env::temp_dir);
    let mut results = Vec::new();
    for name in ["benchmark", "schwinn-crown"] {
        let bicycle = presets::find(name)?.bicycle();
        let bike = bicycle.benchmark()?;
        let canonical = Canonical::new(&bike)?;
        let eig = whipple::eigen_sweep(&canonical, &whipple::speed_grid(0.0, 10.0, 0.01)?)?;
        let critical = whipple::critical_speeds(&canonical, 0.0, 10.0)?;
        let figure = eigen_plot(&eig, &critical, &EigenPlotOptions::default())?;
        for format in [Format::Png, Format::Svg] {
            let path = dir.join(format!("eigen-{name}.{}", format.extension()));
            std::fs::write(&path, figure.render(format)?)?;
        }
        let side = whipple_report::side_view(&bike, bicycle.jbike6(), name);
        std::fs::write(
            dir.join(format!("side-{name}.png")),
            side.render(Format::Png)?,
        )?;
        results.push((name, eig, critical));
    }
    let bikes: Vec<BikeEigen> = results
        .iter()
        .map(|(name, sweep, critical)| BikeEigen {
            name,
            sweep,
            critical,
        })
        .collect();
    let figure = eigen_comparison_plot(&bikes, &EigenPlotOptions::default())?;
    std::fs::write(dir.join("eigen-compare.png"), figure.render(Format::Png)?)?;
    // A synthetic simulation: a decaying weave at 5 m/s with a slow turn.
    let t: Vec<f64> = (0..=600).map(|i| i as f64 * 0.01).collect();
    let lean: Vec<f64> = t
        .iter()
        .map(|t| 0.08 * whipple::math::exp(-0.4 * t) * whipple::math::sin(4.5 * t))
        .collect();
    let steer: Vec<f64> = t
        .iter()
        .map(|t| 0.05 * whipple::math::exp(-0.4 * t) * whipple::math::cos(4.5 * t + 1.0))
        .collect();
    let heading: Vec<f64> = t.iter().map(|t| 0.15 * t).collect();
    let rear: Vec<(f64, f64)> = t
        .iter()
        .zip(&heading)
        .map(|(t, h)| {
            (
                5.0 / 0.15 * whipple::math::sin(*h),
                5.0 / 0.15 * (1.0 - whipple::math::cos(*h)) + 0.0 * t,
            )
        })
        .collect();
    let front = rear
        .iter()
        .zip(&heading)
        .map(|(p, h)| {
            (
                p.0 + 1.02 * whipple::math::cos(*h),
                p.1 + 1.02 * whipple::math::sin(*h),
            )
        })
        .collect();
    let series = whipple_report::SimulationSeries {
        title: "benchmark, 5 m/s, lean 0.08 rad (synthetic)".into(),
        speed: t.iter().map(|t| 5.0 - 0.05 * t).collect(),
        t,
        lean,
        steer,
        rear_contact: rear,
        front_contact: front,
        events: vec![(2.0, "push".into()), (4.5, "weave settled".into())],
        outcome: Some("upright after 6 s".into()),
    };
    let figure = whipple_report::time_series_plot(&series)?;
    std::fs::write(dir.join("time-series.png"), figure.render(Format::Png)?)?;
    Ok(())
}
