//! The linearized model from Python: M, C₁, K₀, K₂; A(v), B(v) and eigenpairs over arrays of
//! speeds (rayon, the GIL released); critical speeds with σ; sensitivities; the non-linear
//! model's exact A(v) and the comparison with the linear model.

use std::sync::atomic::AtomicBool;

use nalgebra::{Matrix2, Matrix4};
use numpy::{Complex64 as NpComplex, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use whipple::advanced::comparison::{ComparisonSettings, Linearization, lean_steer_matrix};
use whipple::advanced::comparison::{MAX_COMPARED_SPEEDS, compare_with_linear_until};
use whipple::advanced::eigen::{eigenvalues_with, eigenvector};
use whipple::advanced::linear::StateSpace;
use whipple::advanced::linear::{CharacteristicPolynomial, SpeedPolynomials};
use whipple::advanced::sensitivity;
use whipple::advanced::sensitivity::critical_speeds_sigma;
use whipple::advanced::sweep::track_modes;
use whipple::{Canonical, Error, Model};

use crate::bicycle::NativeBicycle;
use crate::errors::IntoPy;
use crate::guard::{
    SHORT, estimate, grow, interruptible, is_stopped, memory_error, reserve, stopped,
};
use crate::serialized;

fn matrix2<'py>(py: Python<'py>, m: &Matrix2<f64>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = vec![vec![m[(0, 0)], m[(0, 1)]], vec![m[(1, 0)], m[(1, 1)]]];
    PyArray2::from_vec2(py, &rows)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}

/// A flat row-major buffer as an array of shape `shape`.
fn shaped<'py, T: numpy::Element>(
    py: Python<'py>,
    data: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
}

fn complex(z: whipple::advanced::eigen::Complex64) -> NpComplex {
    NpComplex::new(z.re, z.im)
}

fn core_complex(z: NpComplex) -> whipple::advanced::eigen::Complex64 {
    whipple::advanced::eigen::Complex64::new(z.re, z.im)
}

impl NativeBicycle {
    fn canonical_matrices(&self, py: Python<'_>) -> PyResult<Canonical> {
        Canonical::new(&self.checked.benchmark).py_err(py)
    }
}

/// Speeds computed one after another by each parallel task: enough that rayon's cost per task
/// (about a microsecond) is amortized even for A(v) and B(v) (tens of nanoseconds a speed).
const BLOCK: usize = 1024;

/// Fewer speeds than this are computed on the calling thread even when `parallel` is asked
/// (measured, BENCHMARKS.md: below it waking the second core costs more than it saves).
const PARALLEL_FROM: usize = 4 * BLOCK;

/// Fills `a` (`wa` numbers a speed) and `b` (`wb` a speed, or none when `wb` is 0) speed by
/// speed with `f(speed, a_row, b_row)`, in parallel blocks of [`BLOCK`] speeds (each block's
/// rows a disjoint slice of the buffers) from [`PARALLEL_FROM`] speeds on, or in order,
/// checking `stop` before each speed; the first error in speed order is returned (a parallel
/// failure is redone in order to find it, as the serial path reports it).
#[allow(clippy::too_many_arguments)]
fn fill_rows<T: Send>(
    speeds: &[f64],
    a: &mut [T],
    wa: usize,
    b: &mut [T],
    wb: usize,
    parallel: bool,
    stop: &AtomicBool,
    f: impl Fn(usize, &mut [T], &mut [T]) -> Result<(), Error> + Sync,
) -> Result<(), Error> {
    let wa = wa.max(1);
    let block = |first: usize, x: &mut [T], y: &mut [T]| -> Result<(), Error> {
        for (k, row) in x.chunks_mut(wa).enumerate() {
            if is_stopped(stop) {
                return Err(stopped());
            }
            let other = if wb == 0 {
                &mut []
            } else {
                &mut y[k * wb..(k + 1) * wb]
            };
            f(first + k, row, other)?;
        }
        Ok(())
    };
    let parallel = parallel && speeds.len() >= PARALLEL_FROM;
    let failed = parallel && {
        let blocks_a = a.par_chunks_mut(wa * BLOCK);
        if wb == 0 {
            blocks_a
                .enumerate()
                .try_for_each(|(k, x)| block(k * BLOCK, x, &mut []))
                .is_err()
        } else {
            blocks_a
                .zip(b.par_chunks_mut(wb * BLOCK))
                .enumerate()
                .try_for_each(|(k, (x, y))| block(k * BLOCK, x, y))
                .is_err()
        }
    };
    if !parallel || failed {
        block(0, a, b)?;
    }
    Ok(())
}

/// The speeds of a call copied out of the caller's array (the work runs with the GIL released,
/// when Python could change the array), fallibly.
fn speeds_of(
    call: &str,
    speeds: &PyReadonlyArray1<'_, f64>,
    per_speed: usize,
) -> PyResult<Vec<f64>> {
    let slice = speeds.as_slice()?;
    let n = slice.len();
    let mut out = reserve(n, || {
        memory_error(call, n as u128, "speeds", estimate(n, per_speed))
    })?;
    out.extend_from_slice(slice);
    Ok(out)
}

/// Eigenvalues, eigenvectors and the column labels.
type EigResult<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Option<Vec<&'static str>>,
);

#[pymethods]
impl NativeBicycle {
    /// (M, C1, K0, K2, g): the benchmark's canonical matrices (Meijaard 2007, eq. A…).
    fn canonical<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let c = self.canonical_matrices(py)?;
        let t = (
            matrix2(py, &c.m)?,
            matrix2(py, &c.c1)?,
            matrix2(py, &c.k0)?,
            matrix2(py, &c.k2)?,
            c.g,
        );
        Ok(t.into_pyobject(py)?.into_any())
    }

    /// A (n, 4, 4) and B (n, 4, 2) at each speed.
    #[pyo3(signature = (speeds, parallel=true))]
    fn state_space<'py>(
        &self,
        py: Python<'py>,
        speeds: PyReadonlyArray1<'py, f64>,
        parallel: bool,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let c = self.canonical_matrices(py)?;
        // A and B: 24 numbers of 8 bytes a speed, and the speed copied.
        const PER_SPEED: usize = 24 * 8 + 8;
        let speeds = speeds_of("state_space", &speeds, PER_SPEED)?;
        let n = speeds.len();
        let too_big = || memory_error("state_space", n as u128, "speeds", estimate(n, PER_SPEED));
        let mut a = reserve(n.saturating_mul(16), too_big)?;
        let mut b = reserve(n.saturating_mul(8), too_big)?;
        interruptible(py, n <= SHORT, |stop| {
            grow(&mut a, n * 16, 0.0, stop)?;
            grow(&mut b, n * 8, 0.0, stop)?;
            fill_rows(&speeds, &mut a, 16, &mut b, 8, parallel, stop, |i, a, b| {
                let ss = StateSpace::new(&c, speeds[i])?;
                for r in 0..4 {
                    for j in 0..4 {
                        a[4 * r + j] = ss.a[(r, j)];
                    }
                    for j in 0..2 {
                        b[2 * r + j] = ss.b[(r, j)];
                    }
                }
                Ok(())
            })
        })?
        .py_err(py)?;
        Ok((shaped(py, a, &[n, 4, 4])?, shaped(py, b, &[n, 4, 2])?))
    }

    /// Eigenvalues (n, 4) and eigenvectors (n, 4, 4) (columns as the eigenvalues) at each
    /// speed, and the four column labels. `tracked`: columns follow the modes over the sorted
    /// speeds (weave, weave, capsize, castering), as the command line's `eig`; otherwise each
    /// speed's eigenvalues by decreasing real part and the labels `None`.
    #[pyo3(signature = (speeds, tracked=true, parallel=true))]
    fn eig<'py>(
        &self,
        py: Python<'py>,
        speeds: PyReadonlyArray1<'py, f64>,
        tracked: bool,
        parallel: bool,
    ) -> PyResult<EigResult<'py>> {
        let c = self.canonical_matrices(py)?;
        // Values (4) and vectors (16) of 16 bytes a speed and the speed copied; tracked, the
        // sorted order (8), the sorted speeds (8) and the columns' order (4, twice when the
        // speeds are not sorted) besides.
        let per_speed = 20 * 16 + 8 + if tracked { 24 } else { 0 };
        let speeds = speeds_of("eig", &speeds, per_speed)?;
        let n = speeds.len();
        let too_big = || memory_error("eig", n as u128, "speeds", estimate(n, per_speed));
        // The precision check of the characteristic polynomial once, not per speed.
        SpeedPolynomials::new(&c).py_err(py)?;
        let poly = CharacteristicPolynomial::new(&c);
        let zero = NpComplex::new(0.0, 0.0);
        let mut values = reserve(n.saturating_mul(4), too_big)?;
        let mut vectors = reserve(n.saturating_mul(16), too_big)?;
        let unsorted = speeds.windows(2).any(|w| w[0].total_cmp(&w[1]).is_gt());
        // Tracked: the core follows the modes over the speeds sorted (`grid`, speed
        // `sorted[k]` at `grid[k]`) through the eigenvalues computed here and gives, for each
        // speed, which eigenvalue goes to which column (`columns`, by speed).
        let mut sorted = Vec::new();
        let mut grid = Vec::new();
        let mut columns = Vec::new();
        let mut by_speed = Vec::new();
        if tracked && n > 0 {
            columns = reserve::<[u8; 4]>(n, too_big)?;
            if unsorted {
                sorted = reserve::<usize>(n, too_big)?;
                grid = reserve::<f64>(n, too_big)?;
                by_speed = reserve::<[u8; 4]>(n, too_big)?;
            }
        }
        let labels = interruptible(py, n <= SHORT, |stop| {
            grow(&mut values, n * 4, zero, stop)?;
            // Each speed's eigenvalues, then (once the columns are known) its eigenvectors,
            // written straight into the output buffers (no array of pairs in between: at 10⁶
            // speeds that was 320 MB copied once more; nor the vectors moved into the columns'
            // order afterwards).
            // In parallel (from `PARALLEL_FROM` speeds: waking a second thread costs a few µs),
            // the vectors' buffer (256 MB at 10⁶ speeds) is zeroed meanwhile:
            // memory-bound work beside the eigenvalues' arithmetic.
            let mut zero_vectors = || grow(&mut vectors, n * 16, zero, stop);
            let mut find_values = || {
                fill_rows(
                    &speeds,
                    &mut values,
                    4,
                    &mut [],
                    0,
                    parallel,
                    stop,
                    |i, row, _| {
                        let found = eigenvalues_with(&poly, speeds[i])?;
                        for (out, value) in row.iter_mut().zip(found) {
                            *out = complex(value);
                        }
                        Ok(())
                    },
                )
            };
            let (zeroed, found) = if parallel && n >= PARALLEL_FROM {
                rayon::join(zero_vectors, find_values)
            } else {
                (zero_vectors(), find_values())
            };
            found?;
            zeroed?;
            let modes = if tracked && n > 0 {
                grow(&mut columns, n, [0u8; 4], stop)?;
                let (order, walk): (&[usize], &[f64]) = if unsorted {
                    sorted.extend(0..n);
                    sorted.par_sort_by(|&i, &j| speeds[i].total_cmp(&speeds[j]));
                    grid.extend(sorted.iter().map(|&i| speeds[i]));
                    (&sorted, &grid)
                } else {
                    (&[], &speeds)
                };
                let found = &values;
                // The eigenvalues of the k-th sorted speed, as the core computed them.
                let roots = |k: usize| {
                    let i = if unsorted { order[k] } else { k };
                    Ok(std::array::from_fn(|j| core_complex(found[4 * i + j])))
                };
                let modes = track_modes(&c, walk, roots, &mut columns, parallel, stop)?;
                if unsorted {
                    grow(&mut by_speed, n, [0u8; 4], stop)?;
                    for (k, &i) in order.iter().enumerate() {
                        by_speed[i] = columns[k];
                    }
                }
                Some(modes)
            } else {
                None
            };
            let columns: &[[u8; 4]] = if unsorted { &by_speed } else { &columns };
            fill_rows(
                &speeds,
                &mut values,
                4,
                &mut vectors,
                16,
                parallel,
                stop,
                |i, values, vectors| {
                    if modes.is_some() {
                        let was: [NpComplex; 4] = std::array::from_fn(|j| values[j]);
                        for (out, k) in values.iter_mut().zip(columns[i]) {
                            *out = was[usize::from(k)];
                        }
                    }
                    for (col, value) in values.iter().enumerate() {
                        let x = eigenvector(&c, speeds[i], core_complex(*value));
                        for row in 0..4 {
                            vectors[4 * row + col] = complex(x[row]);
                        }
                    }
                    Ok(())
                },
            )?;
            Ok::<_, Error>(modes)
        })?
        .py_err(py)?;
        drop((sorted, grid, columns, by_speed));
        let labels: Option<Vec<&'static str>> =
            labels.map(|m| m.iter().map(|m| m.name()).collect());
        Ok((
            shaped(py, values, &[n, 4])?,
            shaped(py, vectors, &[n, 4, 4])?,
            labels,
        ))
    }

    /// Critical speeds in [lo, hi] with first-order σ from the parameters' σ: the core's
    /// `CriticalSpeedsSigma` as a dict (the keys of `whipple speeds --format json`); the σ are
    /// None for a bicycle without uncertainties.
    #[pyo3(signature = (lo=0.0, hi=f64::INFINITY))]
    fn critical_speeds<'py>(
        &self,
        py: Python<'py>,
        lo: f64,
        hi: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let bicycle = self.bicycle.clone();
        let mut s = py
            .detach(|| critical_speeds_sigma(&bicycle, lo, hi))
            .py_err(py)?;
        if !self.bicycle.has_uncertainty() {
            s.double_root_speed_sigma = None;
            s.weave_speed_sigma = None;
            s.capsize_speed_sigma = None;
            for ends in &mut s.stable_speed_ranges_sigma {
                *ends = (None, None);
            }
        }
        serialized(py, &s)
    }

    /// Exact sensitivities of v_w, v_c and the stable width to every parameter of the
    /// bicycle's own form over [lo, hi], and of the weave's and capsize's real parts at
    /// `speed`: the core's `Sensitivities` as a dict (`parameters` a list of records).
    #[pyo3(signature = (speed=None, lo=0.0, hi=f64::INFINITY))]
    fn sensitivities<'py>(
        &self,
        py: Python<'py>,
        speed: Option<f64>,
        lo: f64,
        hi: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let bicycle = self.bicycle.clone();
        let s = py
            .detach(|| sensitivity::sensitivities(&bicycle, lo, hi, speed))
            .py_err(py)?;
        serialized(py, &s)
    }

    /// Whether any parameter carries a positive σ (then `critical_speeds` gives σ).
    #[getter]
    fn uncertain(&self) -> bool {
        self.bicycle.has_uncertainty()
    }

    /// The non-linear model's own A(v) about upright straight running, exact (dual numbers):
    /// (n, 4, 4).
    #[pyo3(signature = (speeds, parallel=true))]
    fn nonlinear_state_matrix<'py>(
        &self,
        py: Python<'py>,
        speeds: PyReadonlyArray1<'py, f64>,
        parallel: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let model = Model::new(&self.checked.benchmark).py_err(py)?;
        const PER_SPEED: usize = 16 * 8 + 8;
        let speeds = speeds_of("nonlinear_state_matrix", &speeds, PER_SPEED)?;
        let n = speeds.len();
        let too_big = || {
            let bytes = estimate(n, PER_SPEED);
            memory_error("nonlinear_state_matrix", n as u128, "speeds", bytes)
        };
        let mut a = reserve(n.saturating_mul(16), too_big)?;
        interruptible(py, n <= SHORT, |stop| {
            grow(&mut a, n * 16, 0.0, stop)?;
            fill_rows(
                &speeds,
                &mut a,
                16,
                &mut [],
                0,
                parallel,
                stop,
                |i, a, _| {
                    let m: Matrix4<f64> = lean_steer_matrix(&model, speeds[i])?;
                    for r in 0..4 {
                        for j in 0..4 {
                            a[4 * r + j] = m[(r, j)];
                        }
                    }
                    Ok(())
                },
            )
        })?
        .py_err(py)?;
        shaped(py, a, &[n, 4, 4])
    }

    /// `whipple validate`'s comparison of the non-linear model with the linear one over sorted
    /// speeds, by the methods named (`ad`, `fd`, `ad_full`): a dict of arrays.
    #[pyo3(signature = (speeds, methods=vec!["ad".to_string(), "fd".to_string()]))]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        speeds: PyReadonlyArray1<'py, f64>,
        methods: Vec<String>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let count = speeds.as_slice()?.len();
        if count > MAX_COMPARED_SPEEDS {
            return Err(Error::LimitExceeded {
                what: "v",
                rule: format!(
                    "{count} speeds is more than the limit of {MAX_COMPARED_SPEEDS} a comparison \
                     takes (each speed linearizes the non-linear model by every method, about \
                     10 ms of one core); use fewer speeds"
                ),
            })
            .py_err(py);
        }
        let speeds = speeds.as_slice()?.to_vec();
        let all = [
            Linearization::Exact,
            Linearization::FiniteDifferences,
            Linearization::FullStateExact,
        ];
        let mut chosen = Vec::new();
        for name in &methods {
            match all.iter().find(|m| m.name() == name) {
                Some(m) => chosen.push(*m),
                None => {
                    return Err(Error::InvalidArgument {
                        what: "methods",
                        rule: format!("unknown method `{name}` (ad, fd, ad_full)"),
                    })
                    .py_err(py);
                }
            }
        }
        let bike = self.checked.benchmark;
        let settings = ComparisonSettings::default();
        // Each speed takes milliseconds: always watched.
        let sweep = interruptible(py, false, |stop| {
            compare_with_linear_until(&bike, &speeds, &chosen, &settings, stop)
        })?
        .py_err(py)?;
        let n = sweep.speeds.len();
        let flat = |rows: &[[whipple::advanced::eigen::Complex64; 4]]| -> Vec<NpComplex> {
            rows.iter()
                .flat_map(|r| r.iter().map(|z| complex(*z)))
                .collect()
        };
        let d = PyDict::new(py);
        d.set_item("speeds", PyArray1::from_vec(py, sweep.speeds.clone()))?;
        d.set_item("linear", shaped(py, flat(&sweep.linear), &[n, 4])?)?;
        d.set_item(
            "modes",
            sweep.modes.iter().map(|m| m.name()).collect::<Vec<_>>(),
        )?;
        for m in &sweep.methods {
            let e = PyDict::new(py);
            e.set_item("eigenvalues", shaped(py, flat(&m.eigenvalues), &[n, 4])?)?;
            e.set_item(
                "max_abs_diff",
                PyArray1::from_vec(py, m.max_abs_diff.clone()),
            )?;
            e.set_item(
                "matrix_rel_diff",
                m.matrix_rel_diff.clone().map(|v| PyArray1::from_vec(py, v)),
            )?;
            e.set_item("description", m.method.description())?;
            d.set_item(m.method.name(), e)?;
        }
        Ok(d)
    }
}
