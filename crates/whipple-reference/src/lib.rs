//! Published reference values, each with its source in words: the one copy of each number the
//! tests of the workspace's crates compare against (a dev-dependency only; never published).
//! The tolerances stay with the tests: how close is close enough depends on what is checked.
//! The Python tests read the same numbers from `crates/whipple-py/tests/reference.py`, the
//! browser tests from `crates/whipple-web/e2e/reference.mjs`.

#![warn(missing_docs)]

/// The benchmark bicycle of Meijaard, Papadopoulos, Ruina & Schwab 2007, "Linearized dynamics
/// equations for the balance and steer of a bicycle: a benchmark and review", Proc. R. Soc. A
/// 463:1955–1982 (doi:10.1098/rspa.2007.1857), with the parameters of its Table 1. The
/// published entries are the exact values rounded to 14 decimals; Table 2 carries round-off of
/// up to about 6e-13.
pub mod meijaard2007 {
    /// M, the mass matrix [[kg m², kg m²], [kg m², kg m²]], row by row (§5).
    pub const M: [[f64; 2]; 2] = [
        [80.81722, 2.31941332208709],
        [2.31941332208709, 0.29784188199686],
    ];
    /// C₁, the damping-like matrix multiplied by v [kg m] (§5).
    pub const C1: [[f64; 2]; 2] = [
        [0.0, 33.86641391492494],
        [-0.85035641456978, 1.6854039739756],
    ];
    /// K₀, the stiffness matrix multiplied by g [kg m] (§5).
    pub const K0: [[f64; 2]; 2] = [
        [-80.95, -2.59951685249872],
        [-2.59951685249872, -0.80329488458618],
    ];
    /// K₂, the stiffness matrix multiplied by v² [kg] (§5).
    pub const K2: [[f64; 2]; 2] = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]];

    /// The four real eigenvalues at v = 0 [1/s], largest first (Table 2).
    pub const EIGENVALUES_AT_REST: [f64; 4] = [
        5.53094371765393,
        3.13164324790656,
        -3.13164324790656,
        -5.53094371765393,
    ];

    /// Table 2, one row per speed: (v [m/s], weave real part, weave imaginary part (± that),
    /// capsize, castering) [1/s].
    pub const EIGENVALUES: [(f64, f64, f64, f64, f64); 10] = [
        (
            1.0,
            3.5269617099007,
            0.8077402751993,
            -3.13423125066578,
            -7.11008014637442,
        ),
        (
            2.0,
            2.68234517512745,
            1.68066296590675,
            -3.07158645641514,
            -8.67387984831735,
        ),
        (
            3.0,
            1.70675605663975,
            2.31582447384325,
            -2.63366137253667,
            -10.3510146724592,
        ),
        (
            4.0,
            0.41325331521125,
            3.07910818603206,
            -1.42944427361326,
            -12.1586142657645,
        ),
        (
            5.0,
            -0.77534188219585,
            4.46486771378823,
            -0.32286642900409,
            -14.0783896927982,
        ),
        (
            6.0,
            -1.52644486584142,
            5.87673060598709,
            -0.0040669007697,
            -16.0853712309803,
        ),
        (
            7.0,
            -2.13875644258362,
            7.19525913329805,
            0.10268170574766,
            -18.15788466125262,
        ),
        (
            8.0,
            -2.69348683581097,
            8.46037971396931,
            0.14327879765713,
            -20.27940894394569,
        ),
        (
            9.0,
            -3.21675402252485,
            9.69377351531791,
            0.15790184030917,
            -22.43788559040858,
        ),
        (
            10.0,
            -3.72016840437287,
            10.90681139476287,
            0.16105338653172,
            -24.62459635017404,
        ),
    ];

    /// v_d: the speed where the weave's two real eigenvalues meet and become a complex pair
    /// [m/s] (Table 2).
    pub const DOUBLE_ROOT_SPEED: f64 = 0.68428307889246;
    /// The double eigenvalue at v_d [1/s] (Table 2).
    pub const DOUBLE_ROOT_EIGENVALUE: f64 = 3.7829040512932;
    /// v_w: the weave speed, where the weave becomes stable [m/s] (Table 2).
    pub const WEAVE_SPEED: f64 = 4.29238253634111;
    /// The weave's frequency at v_w [rad/s] (Table 2).
    pub const WEAVE_FREQUENCY: f64 = 3.43503384866144;
    /// v_c: the capsize speed, where the capsize mode becomes unstable [m/s] (Table 2).
    pub const CAPSIZE_SPEED: f64 = 6.02426201538837;
}
