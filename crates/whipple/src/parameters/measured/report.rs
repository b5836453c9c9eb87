//! The report of the pipeline: every number derived from the measurements, in the order
//! computed, with the step function that computed it, its σ and the measurements it depends
//! on; and the largest correlations between the benchmark parameters (the covariance that
//! BicycleParameters drops).

use nalgebra::DMatrix;
use serde::Serialize;

use super::MeasuredParameters;
use crate::parameters::benchmark::BENCHMARK_TABLE;

/// One number as the pipeline computes it, on any scalar (the report's raw form).
#[derive(Debug, Clone)]
pub(crate) struct Record<T> {
    pub(crate) key: String,
    pub(crate) description: String,
    pub(crate) function: &'static str,
    pub(crate) unit: &'static str,
    pub(crate) value: T,
    /// Whether its σ is carried (a residual's derivative is undefined where it is zero).
    pub(crate) propagated: bool,
}

impl<T> Record<T> {
    pub(crate) fn new(
        key: &str,
        description: &str,
        function: &'static str,
        unit: &'static str,
        value: T,
    ) -> Self {
        Self::owned(key.into(), description.into(), function, unit, value)
    }

    pub(crate) fn owned(
        key: String,
        description: String,
        function: &'static str,
        unit: &'static str,
        value: T,
    ) -> Self {
        Record {
            key,
            description,
            function,
            unit,
            value,
            propagated: true,
        }
    }
}

/// One derived number of the pipeline, as `whipple measure` reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Step {
    /// Its name: a benchmark key (`rR`, `IBxx`) or an intermediate (`betaB1`, `k`, `xB12`).
    pub key: String,
    /// What it is and where it comes from.
    pub description: String,
    /// The function of [`super::steps`] that computed it (empty where a measurement is taken
    /// as it is: w, the masses, g).
    pub function: &'static str,
    /// SI unit (`m`, `rad`, `kg m^2`; empty for none).
    pub unit: &'static str,
    /// The value.
    pub value: f64,
    /// Its first-order standard deviation, `None` where it is not carried (the residuals).
    pub sigma: Option<f64>,
    /// The measurements (file keys) it depends on: those whose relative effect |∂q/∂mⱼ mⱼ| is
    /// more than 1e-10 of the largest (a derivative that is zero but for round-off, as the
    /// principal axes' angle's on the rod's mass, is left out).
    pub inputs: Vec<String>,
    /// Whether it is one of the benchmark parameters (the file written holds it).
    pub benchmark: bool,
}

/// The steps from the records of the f64 pass and their Jacobian (one row per record, one
/// column per measurement).
pub(crate) fn steps(
    records: Vec<Record<f64>>,
    jacobian: &DMatrix<f64>,
    inputs: &[String],
    values: &[f64],
    sigmas: &[f64],
) -> Vec<Step> {
    records
        .into_iter()
        .enumerate()
        .map(|(i, r)| {
            let row = (0..inputs.len()).map(|j| jacobian.get((i, j)).copied().unwrap_or(0.0));
            let effect: Vec<f64> = row
                .clone()
                .zip(values)
                .map(|(d, m)| if d.is_finite() { (d * m).abs() } else { 0.0 })
                .collect();
            let largest = effect.iter().fold(0.0f64, |a, b| a.max(*b));
            let depends: Vec<String> = effect
                .iter()
                .zip(inputs)
                .filter(|(e, _)| **e > 0.0 && **e > 1e-10 * largest)
                .map(|(_, k)| k.clone())
                .collect();
            let sigma = r.propagated.then(|| {
                row.zip(sigmas)
                    .map(|(d, s)| (d * s) * (d * s))
                    .sum::<f64>()
                    .sqrt()
            });
            let benchmark = r.propagated && BENCHMARK_TABLE.iter().any(|p| p.key == r.key);
            Step {
                key: r.key,
                description: r.description,
                function: r.function,
                unit: r.unit,
                value: r.value,
                sigma,
                inputs: depends,
                benchmark,
            }
        })
        .collect()
}

/// The correlation coefficient of two benchmark parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Correlation {
    /// One parameter's key (`xB`).
    pub a: &'static str,
    /// The other's (`IBxx`).
    pub b: &'static str,
    /// ρ = cov(a, b) / (σ_a σ_b), in [−1, 1].
    pub rho: f64,
}

impl MeasuredParameters {
    /// The `count` largest correlations (by |ρ|) between distinct benchmark parameters with
    /// σ > 0, each pair once, largest first. BicycleParameters keeps only the σ; parameters
    /// computed from the same measurements (a frame's mass centre and its inertia, both wheel
    /// radii through g) are correlated, which a study of the σ of a critical speed needs.
    ///
    /// ```
    /// use whipple::advanced::measured::{read_measurements, MeasuredParameters};
    /// # let text = include_str!("../../../tests/data/measured/BrowserMeasured.txt");
    /// let result = MeasuredParameters::new(&read_measurements(text)?.measurements)?;
    /// let top = result.largest_correlations(3);
    /// assert_eq!(top.len(), 3);
    /// assert!(top[0].rho.abs() >= top[2].rho.abs());
    /// # Ok::<(), whipple::Error>(())
    /// ```
    pub fn largest_correlations(&self, count: usize) -> Vec<Correlation> {
        let n = BENCHMARK_TABLE.len().min(self.covariance.nrows());
        let sigma: Vec<f64> = (0..n)
            .map(|i| self.covariance[(i, i)].max(0.0).sqrt())
            .collect();
        let mut all = Vec::with_capacity(n * n.saturating_sub(1) / 2);
        for i in 0..n {
            for j in i + 1..n {
                if sigma[i] > 0.0 && sigma[j] > 0.0 {
                    let rho = (self.covariance[(i, j)] / (sigma[i] * sigma[j])).clamp(-1.0, 1.0);
                    all.push(Correlation {
                        a: BENCHMARK_TABLE[i].key,
                        b: BENCHMARK_TABLE[j].key,
                        rho,
                    });
                }
            }
        }
        all.sort_by(|x, y| y.rho.abs().total_cmp(&x.rho.abs()));
        all.truncate(count);
        all
    }
}
