//! Tables of eigenvalues: CSV for files, fixed-width text for the terminal.

use whipple::EigenSweep;
use whipple::advanced::eigen::Complex64;
use whipple::advanced::modes::Mode;

/// The eigenvalue sweep as CSV: header `v,re1,im1,re2,im2,re3,im3,re4,im4`, one row per speed,
/// columns in the sweep's mode order, numbers in Rust's shortest round-trip form (`{}` of f64).
///
/// ```
/// use whipple::advanced::sweep;
/// use whipple::{Canonical, BenchmarkParameters};
/// let canonical = Canonical::new(&BenchmarkParameters::meijaard2007()).unwrap();
/// let s = whipple::eigen_sweep(&canonical, &[0.0, 5.0]).unwrap();
/// let csv = whipple_report::eigen_csv(&s);
/// assert_eq!(csv.lines().count(), 3);
/// assert!(csv.lines().nth(2).unwrap().starts_with("5,"));
/// ```
pub fn eigen_csv(sweep: &EigenSweep) -> String {
    let mut out = String::from(EIGEN_CSV_HEADER);
    for (v, values) in sweep.speeds.iter().zip(&sweep.eigenvalues) {
        out.push_str(&eigen_csv_row(*v, values));
    }
    out
}

/// The header line of [`eigen_csv`], newline included.
pub const EIGEN_CSV_HEADER: &str = "v,re1,im1,re2,im2,re3,im3,re4,im4\n";

/// One row of [`eigen_csv`], newline included (for writing a sweep as it is computed).
pub fn eigen_csv_row(v: f64, values: &[Complex64; 4]) -> String {
    let mut out = v.to_string();
    for l in values {
        out.push_str(&format!(",{},{}", l.re, l.im));
    }
    out.push('\n');
    out
}

/// The eigenvalue sweep as a fixed-width text table for the terminal: speed, then each column
/// headed by its mode name, a complex eigenvalue written `re ± im i`, ten decimals.
pub fn eigen_table(sweep: &EigenSweep) -> String {
    let mut out = eigen_table_header(&sweep.modes);
    for (v, values) in sweep.speeds.iter().zip(&sweep.eigenvalues) {
        out.push_str(&eigen_table_row(*v, values));
    }
    out
}

/// The header line of [`eigen_table`] for columns of these modes, newline included.
pub fn eigen_table_header(modes: &[Mode; 4]) -> String {
    let mut out = format!("{:>8}", "v");
    for (k, mode) in modes.iter().enumerate() {
        out.push_str(&format!(" {:>30}", format!("{} ({})", mode.name(), k + 1)));
    }
    out.push('\n');
    out
}

/// One row of [`eigen_table`], newline included.
pub fn eigen_table_row(v: f64, values: &[Complex64; 4]) -> String {
    let mut out = format!("{v:>8.4}");
    for l in values {
        let cell = if l.im == 0.0 {
            format!("{:.10}", l.re)
        } else {
            format!(
                "{:.10} {} {:.10}i",
                l.re,
                if l.im < 0.0 { '-' } else { '+' },
                l.im.abs()
            )
        };
        out.push_str(&format!(" {cell:>30}"));
    }
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use whipple::{BenchmarkParameters, Canonical, eigen_sweep};

    #[test]
    fn csv_header_and_round_trip() -> Result<(), whipple::Error> {
        let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
        let s = eigen_sweep(&canonical, &[0.0, 0.1, 4.5])?;
        let csv = eigen_csv(&s);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "v,re1,im1,re2,im2,re3,im3,re4,im4");
        assert_eq!(lines.len(), 4);
        assert!(csv.ends_with('\n'));
        let row: Vec<f64> = lines[3]
            .split(',')
            .map(|x| x.parse::<f64>().unwrap_or(f64::NAN))
            .collect();
        assert_eq!(row.len(), 9);
        assert_eq!(row[0], 4.5);
        for (k, l) in s.eigenvalues[2].iter().enumerate() {
            assert_eq!(row[1 + 2 * k].to_bits(), l.re.to_bits());
            assert_eq!(row[2 + 2 * k].to_bits(), l.im.to_bits());
        }
        assert_eq!(lines[1].split(',').next(), Some("0"));
        Ok(())
    }

    #[test]
    fn empty_sweep_gives_header_only() -> Result<(), whipple::Error> {
        let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
        let s = eigen_sweep(&canonical, &[])?;
        assert_eq!(eigen_csv(&s), "v,re1,im1,re2,im2,re3,im3,re4,im4\n");
        assert_eq!(eigen_table(&s).lines().count(), 1);
        Ok(())
    }

    #[test]
    fn table_columns_align() -> Result<(), whipple::Error> {
        let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
        let s = eigen_sweep(&canonical, &[0.0, 5.0, 10.0])?;
        let t = eigen_table(&s);
        let widths: Vec<usize> = t.lines().map(|l| l.chars().count()).collect();
        assert!(widths.iter().all(|&w| w == widths[0]), "{t}");
        assert!(t.contains("weave (1)") && t.contains("castering (4)"));
        Ok(())
    }
}
