//! Rendering tests: every figure renders to non-empty SVG and PNG with the expected text.

use whipple::{
    Canonical, CriticalSpeeds, EigenSweep, critical_speeds, eigen_sweep, presets, speed_grid,
};
use whipple_report::{
    BikeEigen, EigenPlotOptions, Error, Figure, Format, Marker, Series, SimulationSeries,
    XyPlotOptions, eigen_comparison_plot, eigen_plot, line_plot, side_view, time_series_plot,
    xy_log_plot,
};

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn results(name: &str, speeds: &[f64]) -> Result<(EigenSweep, CriticalSpeeds), whipple::Error> {
    let bike = presets::find(name)?.bicycle().benchmark()?;
    let canonical = Canonical::new(&bike)?;
    Ok((
        eigen_sweep(&canonical, speeds)?,
        critical_speeds(&canonical, 0.0, 10.0)?,
    ))
}

fn check(figure: &Figure, expected: &[&str]) -> TestResult {
    let svg = figure.to_svg()?;
    assert!(svg.contains("<svg") && svg.contains("</svg>"));
    for text in expected {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }
    let png = figure.render(Format::Png)?;
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(png.len() > 1000);
    Ok(())
}

#[test]
fn benchmark_eigen_plot_names_modes_and_critical_speeds() -> TestResult {
    let (sweep, critical) = results("benchmark", &speed_grid(0.0, 10.0, 0.05)?)?;
    let figure = eigen_plot(&sweep, &critical, &EigenPlotOptions::default())?;
    check(
        &figure,
        &[
            "weave",
            "capsize",
            "castering",
            "v_d = 0.684 m/s",
            "v_w = 4.292 m/s",
            "v_c = 6.024 m/s",
            "4.292 – 6.024 m/s",
            "forward speed v [m/s]",
            "eigenvalue λ [1/s]",
        ],
    )
}

#[test]
fn curves_are_clipped_at_the_axis() -> TestResult {
    // With a narrow axis the castering curve (below −5 at every speed) must not appear at all:
    // no polyline point of the SVG may lie outside the plotting area.
    let (sweep, critical) = results("benchmark", &speed_grid(0.0, 10.0, 0.1)?)?;
    let options = EigenPlotOptions {
        y_range: (-2.0, 2.0),
        ..Default::default()
    };
    let svg = eigen_plot(&sweep, &critical, &options)?.to_svg()?;
    let green = "stroke=\"#009E73\"";
    let castering_lines = svg
        .lines()
        .filter(|l| l.contains("<polyline") && l.contains(green))
        .count();
    // One green line: the legend swatch.
    assert_eq!(
        castering_lines, 1,
        "castering drawn although it lies below the axis"
    );
    // The weave curves are drawn, and clipped: their y pixels stay within the plot's rows.
    let ys: Vec<f64> = svg
        .lines()
        .filter(|l| l.contains("<polyline") && l.contains("stroke=\"#0072B2\""))
        .flat_map(|l| {
            let pts = l
                .split("points=\"")
                .nth(1)
                .unwrap_or("")
                .split('"')
                .next()
                .unwrap_or("");
            pts.split_whitespace()
                .filter_map(|p| p.split(',').nth(1).and_then(|y| y.parse::<f64>().ok()))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(!ys.is_empty());
    let (top, bottom) = ys
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &y| (a.min(y), b.max(y)));
    // Many points sit exactly on the edges only if plotters clamped them; clipped runs touch the
    // edge once per crossing.
    let at_top = ys.iter().filter(|&&y| y == top).count();
    let at_bottom = ys.iter().filter(|&&y| y == bottom).count();
    assert!(
        at_top < 5 && at_bottom < 5,
        "points piled on the edge: {at_top}, {at_bottom}"
    );
    Ok(())
}

#[test]
fn empty_and_single_point_sweeps_render() -> TestResult {
    for speeds in [vec![], vec![3.0]] {
        let (sweep, critical) = results("benchmark", &speeds)?;
        let figure = eigen_plot(&sweep, &critical, &EigenPlotOptions::default())?;
        check(&figure, &["forward speed v [m/s]"])?;
    }
    Ok(())
}

#[test]
fn comparison_has_a_legend_entry_per_bike() -> TestResult {
    let speeds = speed_grid(0.0, 10.0, 0.1)?;
    let (a, ca) = results("benchmark", &speeds)?;
    let (b, cb) = results("schwinn-crown", &speeds)?;
    let bikes = [
        BikeEigen {
            name: "benchmark",
            sweep: &a,
            critical: &ca,
        },
        BikeEigen {
            name: "schwinn-crown",
            sweep: &b,
            critical: &cb,
        },
    ];
    let figure = eigen_comparison_plot(&bikes, &EigenPlotOptions::default())?;
    check(
        &figure,
        &["benchmark", "schwinn-crown", "v_w = 4.292 m/s (benchmark)"],
    )?;
    assert!(matches!(
        eigen_comparison_plot(&[], &EigenPlotOptions::default()),
        Err(Error::InvalidArgument { .. })
    ));
    Ok(())
}

#[test]
fn bad_options_are_errors_not_panics() -> TestResult {
    let (sweep, critical) = results("benchmark", &[1.0, 2.0])?;
    for y_range in [(1.0, -1.0), (f64::NAN, 1.0), (0.0, 0.0)] {
        let options = EigenPlotOptions {
            y_range,
            ..Default::default()
        };
        assert!(eigen_plot(&sweep, &critical, &options).is_err());
    }
    let options = EigenPlotOptions {
        size: (10, 10),
        ..Default::default()
    };
    assert!(eigen_plot(&sweep, &critical, &options).is_err());
    assert!(matches!(
        Format::from_path(std::path::Path::new("plot.pdf")),
        Err(Error::UnknownFormat { .. })
    ));
    assert_eq!(
        Format::from_path(std::path::Path::new("a/b.SVG"))?,
        Format::Svg
    );
    Ok(())
}

#[test]
fn side_views_show_masses_and_dimensions() -> TestResult {
    let benchmark = presets::find("benchmark")?.bicycle();
    let bike = benchmark.benchmark()?;
    check(
        &side_view(&bike, None, "benchmark"),
        &[
            "85 kg",
            "4 kg",
            "w = 1.020 m",
            "c = 0.080 m",
            "head angle 72.0°",
        ],
    )?;
    let crown = presets::find("schwinn-crown")?.bicycle();
    check(
        &side_view(&crown.benchmark()?, crown.jbike6(), "schwinn-crown"),
        &[
            "rider 80 kg",
            "frame 2.5 kg",
            "rack 2 kg",
            "fork 1.5 kg",
            "basket 1.5 kg",
        ],
    )?;
    // A skate (zero-radius wheels) without a rider still draws.
    let skate = whipple::BenchmarkParameters {
        r_r: 0.0,
        r_f: 0.0,
        m_b: 10.0,
        ..bike
    };
    check(&side_view(&skate, None, "skate"), &["B frame 10 kg"])
}

#[test]
fn synthetic_time_series_renders() -> TestResult {
    let t: Vec<f64> = (0..200).map(|i| i as f64 * 0.02).collect();
    let series = SimulationSeries {
        title: "synthetic".into(),
        lean: t
            .iter()
            .map(|t| 0.1 * whipple::math::sin(3.0 * t))
            .collect(),
        steer: t
            .iter()
            .map(|t| 0.05 * whipple::math::cos(3.0 * t))
            .collect(),
        speed: vec![4.0; t.len()],
        rear_contact: t.iter().map(|t| (4.0 * t, 0.1 * t * t)).collect(),
        front_contact: t.iter().map(|t| (4.0 * t + 1.0, 0.1 * t * t)).collect(),
        events: vec![(1.0, "kick".into())],
        outcome: Some("stayed upright".into()),
        t,
    };
    check(
        &time_series_plot(&series)?,
        &[
            "lean φ [rad]",
            "steer δ [rad]",
            "speed v [m/s]",
            "kick",
            "stayed upright",
            "[deg]",
        ],
    )?;
    check(
        &time_series_plot(&SimulationSeries::default())?,
        &["time t [s]"],
    )?;
    let bad = SimulationSeries {
        t: vec![0.0, 1.0],
        lean: vec![0.0],
        ..Default::default()
    };
    assert!(time_series_plot(&bad).is_err());
    Ok(())
}

#[test]
fn log_and_line_plots_render_with_markers() -> TestResult {
    let diff = Series::new(
        "|Δ Re λ|",
        (0..100)
            .map(|i| (i as f64 * 0.1, 1e-14 * (1.0 + i as f64)))
            .collect(),
    );
    let zero = Series::new("exact", vec![(0.0, 0.0), (5.0, 0.0)]);
    let markers = [
        Marker {
            x: 6.024,
            label: "v_c".into(),
        },
        Marker {
            x: 4.292,
            label: "v_w".into(),
        },
    ];
    let options = XyPlotOptions {
        y_label: "absolute difference [1/s]".into(),
        ..Default::default()
    };
    check(
        &xy_log_plot(&[diff.clone(), zero], &markers, &options)?,
        &["|Δ Re λ|", "v_c", "v_w"],
    )?;
    check(
        &line_plot(&[diff], &markers, &options)?,
        &["absolute difference [1/s]"],
    )?;
    check(&line_plot(&[], &[], &XyPlotOptions::default())?, &[])?;
    let bad = XyPlotOptions {
        y_range: Some((0.0, 1.0)),
        ..Default::default()
    };
    assert!(xy_log_plot(&[], &[], &bad).is_err());
    Ok(())
}

/// The legend names the shaded ranges as asked: "self-stable" for a bicycle on its own,
/// "stable" for a closed loop.
#[test]
fn the_stable_ranges_legend_takes_its_label() -> TestResult {
    let (sweep, critical) = results("benchmark", &speed_grid(0.0, 10.0, 0.1)?)?;
    let open = eigen_plot(&sweep, &critical, &EigenPlotOptions::default())?.to_svg()?;
    assert!(open.contains("\nself-stable\n"));
    let options = EigenPlotOptions {
        stable_label: "stable".into(),
        ..Default::default()
    };
    let closed = eigen_plot(&sweep, &critical, &options)?.to_svg()?;
    assert!(closed.contains("\nstable\n") && !closed.contains("self-stable"));
    Ok(())
}
