//! Eigenpairs per second of the benchmark bicycle (one core), the batch path of `eig`.
//!
//! `cargo run --release -p whipple-bench --example eigenpair_rate -- [N]`

use std::time::Instant;

use whipple::advanced::eigen::eigenpairs_with;
use whipple::advanced::linear::{CharacteristicPolynomial, SpeedPolynomials};
use whipple::{BenchmarkParameters, Canonical};

fn main() -> Result<(), whipple::Error> {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let canonical = Canonical::new(&BenchmarkParameters::meijaard2007())?;
    SpeedPolynomials::new(&canonical)?;
    let poly = CharacteristicPolynomial::new(&canonical);
    let start = Instant::now();
    let mut sum = 0.0;
    for i in 0..n {
        let v = 10.0 * i as f64 / n as f64;
        let pairs = eigenpairs_with(&canonical, &poly, v)?;
        sum += pairs[0].vector[0].re;
    }
    let t = start.elapsed().as_secs_f64();
    println!(
        "{n} speeds in {t:.3} s: {:.0} eigenpairs/s (checksum {sum:.6})",
        n as f64 / t
    );
    Ok(())
}
