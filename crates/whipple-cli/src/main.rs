//! The `whipple` binary: the command lives in the library ([`whipple_cli::main_with_args`]).

use std::process::ExitCode;

fn main() -> ExitCode {
    let status = whipple_cli::main_with_args(std::env::args_os());
    ExitCode::from(u8::try_from(status).unwrap_or(1))
}
