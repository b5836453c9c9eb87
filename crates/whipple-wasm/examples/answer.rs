//! One API request answered natively by the handlers the module runs: `answer METHOD PATH`,
//! the body on standard input; prints the HTTP status on one line, then the JSON body.
//! `bench/native-vs-wasm` compares these bytes with the WebAssembly module's.

use std::io::{Read, Write};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use whipple_web::{Answer, Limits, answer};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [method, path] = args.as_slice() else {
        eprintln!("usage: answer METHOD PATH < BODY");
        return ExitCode::from(2);
    };
    let mut body = Vec::new();
    if let Err(e) = std::io::stdin().read_to_end(&mut body) {
        eprintln!("answer: cannot read the body: {e}");
        return ExitCode::FAILURE;
    }
    let Answer { status, body } = answer(
        method,
        path,
        &body,
        &Limits::default(),
        Arc::new(AtomicBool::new(false)),
    );
    let mut out = std::io::stdout().lock();
    let written = writeln!(out, "{status}")
        .and_then(|()| out.write_all(&body))
        .and_then(|()| out.flush());
    match written {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("answer: cannot write the answer: {e}");
            ExitCode::FAILURE
        }
    }
}
