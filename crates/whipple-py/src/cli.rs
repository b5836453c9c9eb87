//! The `whipple` command from the Python package: `pip install` puts a `whipple` script on PATH
//! (`[project.scripts]`, python/whipple/_cli.py) that calls this function, which runs the very
//! CLI of crates/whipple-cli (`whipple_cli::main_with_args`) in the interpreter's process.

use pyo3::prelude::*;

/// Runs the `whipple` command with `argv` (the program name first, as `sys.argv`) and returns its
/// exit status; its output and messages go to the process's standard output and error.
#[pyfunction]
pub fn cli_main(py: Python<'_>, argv: Vec<String>) -> i32 {
    // The command may run for long (a map, a simulation, the server): other Python threads go on.
    py.detach(|| whipple_cli::main_with_args(argv))
}
