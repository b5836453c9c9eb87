//! Renders every figure for the benchmark bicycle and the Schwinn Crown into a directory given
//! as the first argument (default: the system's temporary directory), for looking at them.

use std::path::PathBuf;

use whipple::analysis::{stability, sweep};
use whipple::linear::Canonical;
use whipple::parameters::presets;
use whipple_report::{eigen_comparison_plot, eigen_plot, BikeEigen, EigenPlotOptions, Format};

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
        let eig = sweep::eigen_sweep(&canonical, &sweep::speed_grid(0.0, 10.0, 0.01)?)?;
        let critical = stability::critical_speeds(&canonical, 0.0, 10.0)?;
        let figure = eigen_plot(&eig, &critical, &EigenPlotOptions::default())?;
        for format in [Format::Png, Format::Svg] {
            let path = dir.join(format!("eigen-{name}.{}", format.extension()));
            std::fs::write(&path, figure.render(format)?)?;
        }
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
    Ok(())
}
