"""Published reference values the Python tests compare against, each with its source in words:
the one copy of each number in the Python tests (the Rust tests read the same numbers from the
`whipple-reference` crate, the browser tests from crates/whipple-web/e2e/reference.mjs). The
tolerances stay with the tests. The guide's validation chapter (docs/hooks/validation.py) shows
the same numbers beside whipple's.

Meijaard, Papadopoulos, Ruina & Schwab 2007, "Linearized dynamics equations for the balance and
steer of a bicycle: a benchmark and review", Proc. R. Soc. A 463:1955–1982
(doi:10.1098/rspa.2007.1857), the benchmark bicycle of its Table 1. The published entries are
the exact values rounded to 14 decimals; Table 2 carries round-off of up to about 6e-13."""

#: Meijaard 2007, section 5: the canonical matrices M, C1, K0, K2, row by row.
M = [[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]]
C1 = [[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]]
K0 = [[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]]
K2 = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]]

#: Meijaard 2007, Table 2: (v [m/s], weave re, weave im (± that), capsize, castering) [1/s].
TABLE_2 = [
    (1.0, 3.5269617099007, 0.8077402751993, -3.13423125066578, -7.11008014637442),
    (2.0, 2.68234517512745, 1.68066296590675, -3.07158645641514, -8.67387984831735),
    (3.0, 1.70675605663975, 2.31582447384325, -2.63366137253667, -10.3510146724592),
    (4.0, 0.41325331521125, 3.07910818603206, -1.42944427361326, -12.1586142657645),
    (5.0, -0.77534188219585, 4.46486771378823, -0.32286642900409, -14.0783896927982),
    (6.0, -1.52644486584142, 5.87673060598709, -0.0040669007697, -16.0853712309803),
    (7.0, -2.13875644258362, 7.19525913329805, 0.10268170574766, -18.15788466125262),
    (8.0, -2.69348683581097, 8.46037971396931, 0.14327879765713, -20.27940894394569),
    (9.0, -3.21675402252485, 9.69377351531791, 0.15790184030917, -22.43788559040858),
    (10.0, -3.72016840437287, 10.90681139476287, 0.16105338653172, -24.62459635017404),
]
#: Meijaard 2007, Table 2: the four real eigenvalues at rest [1/s], largest first.
AT_REST = [5.53094371765393, 3.13164324790656, -3.13164324790656, -5.53094371765393]

#: Meijaard 2007, Table 2: v_d, where the weave's two real eigenvalues meet [m/s].
DOUBLE_ROOT_SPEED = 0.68428307889246
#: Meijaard 2007, Table 2: the double eigenvalue at v_d [1/s].
DOUBLE_ROOT_EIGENVALUE = 3.7829040512932
#: Meijaard 2007, Table 2: v_w, the weave speed [m/s].
WEAVE_SPEED = 4.29238253634111
#: Meijaard 2007, Table 2: the weave's frequency at v_w [rad/s].
WEAVE_FREQUENCY = 3.43503384866144
#: Meijaard 2007, Table 2: v_c, the capsize speed [m/s].
CAPSIZE_SPEED = 6.02426201538837


# Basu-Mandal, Chatterjee & Papadopoulos 2007, "Hands-free circular motions of a benchmark
# bicycle", Proc. R. Soc. A 463:1983–2003 (doi:10.1098/rspa.2007.1849), Table 1: the non-linear
# benchmark bicycle's accelerations at one general state (digits as transcribed in
# moorepants/DynamicistToolKit, dtk/bicycle.py). Their coordinates: x, y, z of the rear wheel
# centre (z up, x backward when θ = 0); θ yaw, ψ lean (π/2 upright), φ rear frame pitch (π
# upright), ψ_f steer, β_r, β_f wheel rotations; all with the opposite sense of whipple's (yaw
# right, lean right, nose up, steer right, wheel rotation about the axle pointing right).
BASU_MANDAL_STATE = {
    "x": 0.0, "y": 0.0, "z": 0.2440472102925,
    "theta": 0.0, "psi": 0.9501292851472, "phi": 3.1257073014894, "psif": 0.2311385135743,
    "betar": 0.0, "betaf": 0.0,
    "xd": -2.8069345714545, "yd": -0.1480982396001, "zd": 0.1058778746261,
    "thetad": 0.7830033527065, "psid": 0.6068425835418, "phid": -0.0119185528069,
    "psifd": 0.4859824687093, "betard": 8.912989661489, "betafd": 8.0133620584155,
}
#: Basu-Mandal 2007, Table 1's output, in their names and senses.
BASU_MANDAL_NAMES = ["ẍ", "ÿ", "z̈", "θ̈", "ψ̈", "φ̈", "ψ̈_f", "β̈_r", "β̈_f"]
BASU_MANDAL_OUTPUT = [-0.5041626315047, -0.3449706619454, -1.460452833298, 0.8353281706379,
                      -7.8555281128244, 0.1205543897884, -4.6198904039403, 1.8472554144217,
                      2.454807290455]


def basu_mandal_accelerations(bike):
    """whipple's accelerations of `bike` (the benchmark) at Basu-Mandal's Table 1 state, in their
    names' order and senses; with the largest holonomic and velocity residual of the state and
    the rear wheel centre (whipple's axes), which their state puts at (-x, y, -z)."""
    import math

    s = BASU_MANDAL_STATE
    r_r = bike.to_dict()["rR"]
    # Their rear contact from the wheel centre: r_R cos ψ to the left across the heading.
    contact = (-s["x"] - r_r * math.sin(s["theta"]) * math.cos(s["psi"]),
               s["y"] - r_r * math.cos(s["theta"]) * math.cos(s["psi"]))
    out = bike.accelerations(
        yaw=-s["theta"], lean=math.pi / 2 - s["psi"], pitch=math.pi - s["phi"], steer=-s["psif"],
        wheel_angles=(-s["betar"], -s["betaf"]), rear_contact=contact,
        hub_velocity=(-s["xd"], s["yd"], -s["zd"]), yaw_rate=-s["thetad"],
        lean_rate=-s["psid"], pitch_rate=-s["phid"], steer_rate=-s["psifd"],
        wheel_rates=(-s["betard"], -s["betafd"]))
    a = out["hub_acceleration"]
    yaw, lean, pitch = out["angle_accelerations"]
    rear, front = out["wheel_accelerations"]
    ours = [-a[0], a[1], -a[2], -yaw, -lean, -pitch, -out["steer_acceleration"], -rear, -front]
    return [float(x) for x in ours], out

# Dressel, "Benchmarking a fully non-linear bicycle model with JBike6" (Cornell, 2003-2015): the
# largest difference between the eigenvalues of the non-linear model differenced about upright
# running and JBike6's linear ones, over 0-10 m/s, just under this, near the capsize speed.
DRESSEL_FD_PEAK = 1.5e-5

# Moore, Hubbard & Hess, "An optimal handling bicycle", Proc. BMD 2016: the design speeds [m/s]
# of the optimal bicycles whose parameters and gains HumanControl publishes
# (Optimal<NN>Par.txt, Optimal<NN>SteerGains.txt), each reported to handle better (a lower peak
# of Hess's handling quality metric) than the benchmark bicycle at its design speed.
BMD2016_DESIGN_SPEEDS = [2, 4, 5, 6, 8]
