//! Any text as the linear system's signals as people type them (`whipple_front::system`): an
//! input, an output, a state, a frequency grid and an input signal of time. Never a panic; an
//! accepted grid is finite, positive and increasing with the count asked; an accepted signal is
//! finite wherever it is evaluated; a refusal is one line naming the field.
#![no_main]

use libfuzzer_sys::fuzz_target;
use whipple_front::system::{
    parse_input, parse_log_grid, parse_output, parse_signal, parse_state, request,
};

fn one_line(error: whipple::Error) {
    let message = error.to_string();
    assert!(!message.is_empty());
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = parse_input(text).map_err(one_line);
    let _ = parse_output(text).map_err(one_line);
    let _ = parse_state(text).map_err(one_line);
    let words: Vec<&str> = text.split_whitespace().take(8).collect();
    let _ = request(&words, &words).map_err(one_line);
    match parse_log_grid(text) {
        Ok(grid) => {
            assert!(!grid.is_empty());
            assert!(grid.iter().all(|w| w.is_finite() && *w > 0.0));
            assert!(grid.windows(2).all(|p| p[0] < p[1]), "{grid:?}");
        }
        Err(e) => one_line(e),
    }
    match parse_signal(text, "signal") {
        Ok(signal) => {
            for t in [-1.0, 0.0, 0.5, 1.0, 1e300, f64::MAX] {
                assert!(signal.value(t).is_finite(), "{text:?} at {t}");
                assert!(signal.value_before(t).is_finite(), "{text:?} at {t}");
            }
        }
        Err(e) => {
            assert!(e.to_string().contains("signal"), "{e}");
        }
    }
});
