// Published reference values the browser tests compare against, each with its source in words:
// the one copy of each number in the e2e scripts (the Rust tests read the same numbers from the
// `whipple-reference` crate, the Python tests from crates/whipple-py/tests/reference.py).
//
// Meijaard, Papadopoulos, Ruina & Schwab 2007, "Linearized dynamics equations for the balance
// and steer of a bicycle: a benchmark and review", Proc. R. Soc. A 463:1955–1982
// (doi:10.1098/rspa.2007.1857), the benchmark bicycle of its Table 1.

/** Meijaard 2007, Table 2: v_w, the weave speed [m/s]. */
export const WEAVE_SPEED = 4.29238253634111;
/** Meijaard 2007, Table 2: v_c, the capsize speed [m/s]. */
export const CAPSIZE_SPEED = 6.02426201538837;
/** Meijaard 2007, Table 2: the weave's eigenvalues at 5 m/s, re ± im·i [1/s]. */
export const WEAVE_AT_5 = { re: -0.77534188219585, im: 4.46486771378823 };

/** A speed as the page prints it in its table of critical speeds (four decimals). */
export const asShown = (speed) => speed.toFixed(4);
