"""A sympy/PyDy Whipple bicycle, timed on the motion that `cargo bench --bench nonlinear` times.

Run it in a throw-away virtual environment (PyDy is never a dependency of whipple), from the
repository root:

    python3 -m venv /tmp/pydyvenv
    /tmp/pydyvenv/bin/pip install pydy sympy numpy scipy cython
    /tmp/pydyvenv/bin/python bench/pydy_whipple.py [/tmp/pydy_traj.csv]

and compare with whipple's trajectory of the same motion:

    cargo build --release -p whipple-cli
    target/release/whipple simulate --bike benchmark --speed 4.6 --lean-rate 0.5 \
        --duration 10 --format csv --out /tmp/whipple_traj.csv
    /tmp/pydyvenv/bin/python bench/compare_trajectories.py /tmp/pydy_traj.csv /tmp/whipple_traj.csv

The model (Moore's formulation of the Whipple bicycle, derived here with Kane's method in
sympy.physics.mechanics; z down, benchmark signs):

    frames  A = N rotated by the yaw q3 about N.z, B = A by the lean q4 about A.x,
            C (rear frame) = B by the pitch q5 about B.y, D (rear wheel) = C by q6 about C.y,
            E (front frame) = C by the steer q7 about C.z (the steer axis), F (front wheel)
            = E by q8 about E.y
    points  rear contact (q1, q2), rear hub do = contact - rR B.z, steer-axis point
            ce = do + d1 C.x, front hub fo = ce + d2 E.z + d3 E.x, front contact
            fo + rF * unit(E.y x (A.z x E.y)); mass centres co = do + l1 C.x + l2 C.z,
            eo = ce + l3 E.x + l4 E.z
    speeds  u_i = q_i' for i = 3..8; the rear contact moves at -rR (u5 + u6) A.x;
            independent u4 (lean rate), u6 (rear wheel rate), u7 (steer rate); dependent
            u3, u5, u8 from the front contact's velocity (no slip along A.y and A.x, and the
            time derivative of the holonomic constraint along A.z); dependent coordinate q5
            (pitch)
    nominal upright pitch q5 = lambda (C.z along the steer axis).

Benchmark parameters (Meijaard et al. 2007, Table 1) mapped to it:

    d1 = cos(lam) (c + w - rR tan(lam)),   d3 = -cos(lam) (c - rF tan(lam)),
    d2 = (rR - rF + (d1 + d3) sin(lam)) / cos(lam),
    (l1, l2) = (x cos(lam) - z' sin(lam), x sin(lam) + z' cos(lam)) with (x, z') the benchmark
    mass centre relative to the rear hub (B) or to ce (H), and the benchmark inertia tensors
    rotated into C/E axes: I_C[i, j] = c_i . I . c_j with c_x = (cos lam, 0, -sin lam),
    c_z = (sin lam, 0, cos lam).

The right-hand side is PyDy's Cython code (generate_ode_function(..., generator="cython")) of
Kane's mass matrix and forcing for the six speeds (three dynamic rows, three constraint rows)
with q' given explicitly; the 6 x 6 system is solved either by an LU decomposition generated
into the C code (linear_sys_solver="sympy", the faster, used for the runs) or by
numpy.linalg.solve after it (PyDy's default, timed for comparison).

It prints: the time to derive and compile the model; the eigenvalues at v = 5 m/s from central
differences of the generated right-hand side against Table 2; right-hand sides per second
(100,000 calls at the state of whipple's `nonlinear forward` bench, best of 5); the wall time of
a 10 s fixed-step RK4 run at dt = 1 ms (a plain Python loop, 40,000 right-hand sides, no
projection) from upright at 4.6 m/s with lean rate 0.5 rad/s; the same run with
scipy.integrate.solve_ivp (RK45) and odeint (LSODA), rtol = atol = 1e-10; and it writes the RK4
trajectory (t, lean, steer, lean_rate, steer_rate, speed, yaw, rear contact x, y, pitch) to the CSV
path given (default /tmp/pydy_traj.csv). `--lambdify` uses PyDy's lambdify generator (numpy
solve) instead of Cython.
"""

import math
import sys
import time

import numpy as np
import sympy as sm
import sympy.physics.mechanics as me
from pydy.codegen.ode_function_generators import generate_ode_function
from scipy.integrate import odeint, solve_ivp

# Meijaard et al. 2007, Table 1.
BENCH = {
    "w": 1.02, "c": 0.08, "lam": math.pi / 10, "g": 9.81,
    "rR": 0.3, "mR": 2.0, "IRxx": 0.0603, "IRyy": 0.12,
    "xB": 0.3, "zB": -0.9, "mB": 85.0,
    "IBxx": 9.2, "IByy": 11.0, "IBzz": 2.8, "IBxz": 2.4,
    "xH": 0.9, "zH": -0.7, "mH": 4.0,
    "IHxx": 0.05892, "IHyy": 0.06, "IHzz": 0.00708, "IHxz": -0.00756,
    "rF": 0.35, "mF": 3.0, "IFxx": 0.1405, "IFyy": 0.28,
}

# Table 2 at v = 5 m/s.
TABLE2_V5 = {
    "weave": complex(-0.77534188219585, 4.46486771378823),
    "capsize": -0.32286642900409,
    "castering": -14.0783896927982,
}


def derive(with_torques=False):
    """Kane's equations of the Whipple bicycle; returns what the rest of the script needs.

    With `with_torques`, the rider's lean torque T4 (on the rear frame C about A.x, the
    horizontal line of the heading) and steer torque T7 (on the front frame E about the steer
    axis C.z, its reaction on C) are added as PyDy specifieds, and a seventh value, [T4, T7],
    is returned."""
    q1, q2, q3, q4, q5, q6, q7, q8 = me.dynamicsymbols("q1:9")
    u3, u4, u5, u6, u7, u8 = me.dynamicsymbols("u3:9")
    (d1, d2, d3, rR, rF, l1, l2, l3, l4, g, mc, md, me_, mf,
     id11, id22, ic11, ic22, ic33, ic31, ie11, ie22, ie33, ie31, if11, if22) = sm.symbols(
        "d1 d2 d3 rR rF l1 l2 l3 l4 g mc md me mf id11 id22 ic11 ic22 ic33 ic31 "
        "ie11 ie22 ie33 ie31 if11 if22")

    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (q3, N.z))
    B = A.orientnew("B", "Axis", (q4, A.x))
    C = B.orientnew("C", "Axis", (q5, B.y))
    D = C.orientnew("D", "Axis", (q6, C.y))
    E = C.orientnew("E", "Axis", (q7, C.z))
    F = E.orientnew("F", "Axis", (q8, E.y))
    A.set_ang_vel(N, u3 * N.z)
    B.set_ang_vel(A, u4 * A.x)
    C.set_ang_vel(B, u5 * B.y)
    D.set_ang_vel(C, u6 * C.y)
    E.set_ang_vel(C, u7 * C.z)
    F.set_ang_vel(E, u8 * E.y)

    # Rear contact: the wheel's material point there has zero velocity (rolling).
    dn = me.Point("dn")
    dn.set_vel(N, 0)
    do = dn.locatenew("do", -rR * B.z)
    co = do.locatenew("co", l1 * C.x + l2 * C.z)
    ce = do.locatenew("ce", d1 * C.x)
    eo = ce.locatenew("eo", l3 * E.x + l4 * E.z)
    fo = ce.locatenew("fo", d2 * E.z + d3 * E.x)
    down_in_wheel_plane = E.y.cross(A.z.cross(E.y)).normalize()
    fn = fo.locatenew("fn", rF * down_in_wheel_plane)
    do.v2pt_theory(dn, N, D)
    co.v2pt_theory(do, N, C)
    ce.v2pt_theory(do, N, C)
    eo.v2pt_theory(ce, N, E)
    fo.v2pt_theory(ce, N, E)
    fn.v2pt_theory(fo, N, F)

    holonomic = fn.pos_from(dn).dot(A.z)
    # Ordered so that each row's pivot (u3, u5, u8) is non-zero upright: sympy eliminates the
    # dependent speeds symbolically by LU without pivoting.
    nonholonomic = [fn.vel(N).dot(A.y), fn.vel(N).dot(A.z), fn.vel(N).dot(A.x)]

    t = me.dynamicsymbols._t
    kd = [q3.diff(t) - u3, q4.diff(t) - u4, q5.diff(t) - u5, q6.diff(t) - u6,
          q7.diff(t) - u7, q8.diff(t) - u8,
          q1.diff(t) + rR * (u5 + u6) * sm.cos(q3),
          q2.diff(t) + rR * (u5 + u6) * sm.sin(q3)]

    bodies = [
        me.RigidBody("C", co, C, mc, (me.inertia(C, ic11, ic22, ic33, 0, 0, ic31), co)),
        me.RigidBody("D", do, D, md, (me.inertia(D, id11, id22, id11), do)),
        me.RigidBody("E", eo, E, me_, (me.inertia(E, ie11, ie22, ie33, 0, 0, ie31), eo)),
        me.RigidBody("F", fo, F, mf, (me.inertia(F, if11, if22, if11), fo)),
    ]
    loads = [(co, mc * g * A.z), (do, md * g * A.z), (eo, me_ * g * A.z), (fo, mf * g * A.z)]
    inputs = []
    if with_torques:
        T4, T7 = me.dynamicsymbols("T4 T7")
        inputs = [T4, T7]
        loads += [(C, T4 * A.x - T7 * C.z), (E, T7 * C.z)]

    kane = me.KanesMethod(
        N,
        q_ind=[q1, q2, q3, q4, q6, q7, q8], q_dependent=[q5],
        configuration_constraints=[holonomic],
        u_ind=[u4, u6, u7], u_dependent=[u3, u5, u8],
        velocity_constraints=nonholonomic,
        kd_eqs=kd)
    kane.kanes_equations(bodies, loads)

    coordinates = list(kane.q)  # [q1, q2, q3, q4, q6, q7, q8, q5]
    speeds = list(kane.u)  # [u4, u6, u7, u3, u5, u8]
    kdd = kane.kindiffdict()
    qdot = sm.Matrix([kdd[q.diff(t)] for q in coordinates])
    constants = [d1, d2, d3, rR, rF, l1, l2, l3, l4, g, mc, md, me_, mf,
                 id11, id22, ic11, ic22, ic33, ic31, ie11, ie22, ie33, ie31, if11, if22]

    # Numeric helpers (lambdify) for the initial state and the linearization: the holonomic
    # constraint and its derivative in the pitch, the velocity constraints as
    # Bd u_dep + Bi u_ind = 0, the forward speed of the rear hub along A.x.
    cvec = sm.Matrix(nonholonomic)
    u_ind, u_dep = [u4, u6, u7], [u3, u5, u8]
    Bd = cvec.jacobian(u_dep)
    Bi = cvec.jacobian(u_ind)
    speed = do.vel(N).dot(A.x)
    args = (coordinates, constants)
    helpers = {
        "hol": sm.lambdify(args, holonomic, cse=True),
        "dhol": sm.lambdify(args, holonomic.diff(q5), cse=True),
        "Bd": sm.lambdify(args, Bd, cse=True),
        "Bi": sm.lambdify(args, Bi, cse=True),
        "speed": sm.lambdify((coordinates, speeds, constants), speed, cse=True),
        # Front contact relative to the rear contact, along N.x and N.y.
        "front_contact": sm.lambdify(
            args, [fn.pos_from(dn).dot(N.x), fn.pos_from(dn).dot(N.y)], cse=True),
    }
    if with_torques:
        return kane, coordinates, speeds, qdot, constants, helpers, inputs
    return kane, coordinates, speeds, qdot, constants, helpers


def parameter_values(p):
    """The model's constants from the benchmark parameters (order of derive()'s constants)."""
    lam, rR, rF, w, c = p["lam"], p["rR"], p["rF"], p["w"], p["c"]
    cl, sl = math.cos(lam), math.sin(lam)
    d1 = cl * (c + w - rR * math.tan(lam))
    d3 = -cl * (c - rF * math.tan(lam))
    d2 = (rR - rF + (d1 + d3) * sl) / cl
    # Rear frame mass centre relative to the rear hub, in C axes.
    x, z = p["xB"], p["zB"] + rR
    l1, l2 = x * cl - z * sl, x * sl + z * cl
    # Front frame mass centre relative to ce (= rear hub + d1 C.x), in E axes.
    x, z = p["xH"] - d1 * cl, p["zH"] + rR + d1 * sl
    l3, l4 = x * cl - z * sl, x * sl + z * cl
    cx = np.array([cl, 0.0, -sl])
    cz = np.array([sl, 0.0, cl])

    def rotated(ixx, iyy, izz, ixz):
        inertia = np.array([[ixx, 0.0, ixz], [0.0, iyy, 0.0], [ixz, 0.0, izz]])
        return cx @ inertia @ cx, iyy, cz @ inertia @ cz, cz @ inertia @ cx

    ic = rotated(p["IBxx"], p["IByy"], p["IBzz"], p["IBxz"])
    ie = rotated(p["IHxx"], p["IHyy"], p["IHzz"], p["IHxz"])
    return np.array([d1, d2, d3, rR, rF, l1, l2, l3, l4, p["g"],
                     p["mB"], p["mR"], p["mH"], p["mF"], p["IRxx"], p["IRyy"],
                     *ic, *ie, p["IFxx"], p["IFyy"]], dtype=float)


class Layout:
    """Indices of the named states in PyDy's state vector x = [coordinates, speeds]."""

    def __init__(self, coordinates, speeds):
        names = [str(s.func) for s in coordinates + speeds]
        self.n_q = len(coordinates)
        self.i = {n: k for k, n in enumerate(names)}

    def __getitem__(self, name):
        return self.i[name]


def consistent_state(helpers, lay, par, lean, steer, lean_rate, steer_rate, speed, yaw=0.0):
    """A state satisfying the constraints: pitch by Newton on the front contact height,
    dependent speeds from the velocity constraints, the rear wheel rate so that the rear hub
    moves at `speed` along the heading (the quantity whipple holds)."""
    x = np.zeros(len(lay.i))
    x[lay["q3"]], x[lay["q4"]], x[lay["q7"]] = yaw, lean, steer
    x[lay["q5"]] = BENCH["lam"]
    for _ in range(50):
        q = x[:lay.n_q]
        step = helpers["hol"](q, par) / helpers["dhol"](q, par)
        x[lay["q5"]] -= step
        if abs(step) < 1e-15:
            break
    q = x[:lay.n_q]
    bd, bi = np.array(helpers["Bd"](q, par), float), np.array(helpers["Bi"](q, par), float)

    def fill(u6):
        u_ind = np.array([lean_rate, u6, steer_rate])
        u_dep = np.linalg.solve(bd, -bi @ u_ind)
        x[lay["u4"]], x[lay["u6"]], x[lay["u7"]] = u_ind
        x[lay["u3"]], x[lay["u5"]], x[lay["u8"]] = u_dep
        return helpers["speed"](x[:lay.n_q], x[lay.n_q:], par)

    # The speed is affine in u6 once the other independent speeds are fixed.
    s0, s1 = fill(0.0), fill(1.0)
    fill((speed - s0) / (s1 - s0))
    return x


def constraint_residuals(helpers, lay, par, x):
    q, u = x[:lay.n_q], x[lay.n_q:]
    hol = helpers["hol"](q, par)
    bd, bi = np.array(helpers["Bd"](q, par), float), np.array(helpers["Bi"](q, par), float)
    u_ind = u[[lay["u4"] - lay.n_q, lay["u6"] - lay.n_q, lay["u7"] - lay.n_q]]
    u_dep = u[[lay["u3"] - lay.n_q, lay["u5"] - lay.n_q, lay["u8"] - lay.n_q]]
    return abs(hol), np.max(np.abs(bd @ u_dep + bi @ u_ind))


def eigenvalues(rhs, helpers, lay, par, v, h=1e-6):
    """Eigenvalues of [lean, steer, lean rate, steer rate] about upright running at v, by
    central differences of the generated right-hand side on constraint-consistent states."""
    names = ["lean", "steer", "lean_rate", "steer_rate"]
    a = np.zeros((4, 4))
    for j, name in enumerate(names):
        cols = []
        for sign in (1.0, -1.0):
            ic = dict.fromkeys(names, 0.0)
            ic[name] = sign * h
            x = consistent_state(helpers, lay, par, speed=v, **ic)
            xd = rhs(x, 0.0, par)
            cols.append(np.array([xd[lay["q4"]], xd[lay["q7"]], xd[lay["u4"]], xd[lay["u7"]]]))
        a[:, j] = (cols[0] - cols[1]) / (2 * h)
    return np.linalg.eigvals(a)


def rk4(rhs, x0, par, dt, n):
    """Classical RK4, fixed step, a plain Python loop; returns all states.

    PyDy's generated function returns the same output array on every call, so the slopes are
    copied (without the copies all four slopes are the last one and the method is first order).
    """
    out = np.empty((n + 1, len(x0)))
    out[0] = x = x0.copy()
    t, h2, h6 = 0.0, 0.5 * dt, dt / 6.0
    for k in range(n):
        k1 = rhs(x, t, par).copy()
        k2 = rhs(x + h2 * k1, t + h2, par).copy()
        k3 = rhs(x + h2 * k2, t + h2, par).copy()
        k4 = rhs(x + dt * k3, t + dt, par)
        x = x + h6 * (k1 + 2.0 * (k2 + k3) + k4)
        t = (k + 1) * dt
        out[k + 1] = x
    return out


def main():
    out_path = "/tmp/pydy_traj.csv"
    generator = "cython"
    for arg in sys.argv[1:]:
        if arg == "--lambdify":
            generator = "lambdify"
        else:
            out_path = arg

    t0 = time.perf_counter()
    kane, coordinates, speeds, qdot, constants, helpers = derive()
    t_derive = time.perf_counter() - t0
    print(f"sympy {sm.__version__}; Kane's equations derived in {t_derive:.1f} s")
    print(f"state vector: {[str(s.func) for s in coordinates + speeds]}")
    # Cython: with the mass matrix solved by an LU decomposition generated into the C code
    # (linear_sys_solver="sympy", PyDy's fastest option; used for everything below) and with
    # PyDy's default, numpy.linalg.solve after the C code (only timed).
    solvers = ["sympy", "numpy"] if generator == "cython" else ["numpy"]
    rhs_by_solver = {}
    for solver in solvers:
        t0 = time.perf_counter()
        rhs_by_solver[solver] = generate_ode_function(
            kane.forcing, coordinates, speeds, constants,
            mass_matrix=kane.mass_matrix, coordinate_derivatives=qdot,
            generator=generator, linear_sys_solver=solver, constants_arg_type="array")
        print(f"{generator} right-hand side, linear_sys_solver={solver!r}, generated in "
              f"{time.perf_counter() - t0:.1f} s")
    rhs = rhs_by_solver[solvers[0]]

    lay = Layout(coordinates, speeds)
    par = parameter_values(BENCH)

    # Check against Table 2 at 5 m/s.
    ev = eigenvalues(rhs, helpers, lay, par, 5.0)
    ev = ev[np.argsort(ev.real)]
    print("eigenvalues at v = 5 m/s (central differences of the generated RHS, h = 1e-6):")
    weave = [e for e in ev if e.imag > 0][0]
    real = sorted(e.real for e in ev if e.imag == 0)
    for name, mine, ref in (("weave", weave, TABLE2_V5["weave"]),
                            ("capsize", real[1], TABLE2_V5["capsize"]),
                            ("castering", real[0], TABLE2_V5["castering"])):
        print(f"  {name:9} {mine:.10f}  Table 2 {ref:.10f}  |diff| {abs(mine - ref):.2e}")

    # Right-hand sides per second at the state of whipple's `nonlinear forward` bench.
    x_bench = consistent_state(helpers, lay, par, lean=0.1, steer=0.05, lean_rate=0.5,
                               steer_rate=-0.2, speed=4.6)
    calls = 100_000
    for solver, f in rhs_by_solver.items():
        best = math.inf
        for _ in range(5):
            t0 = time.perf_counter()
            for _ in range(calls):
                f(x_bench, 0.0, par)
            best = min(best, time.perf_counter() - t0)
        print(f"RHS ({generator}, linear_sys_solver={solver!r}): {best / calls * 1e6:.2f} us "
              f"per call, {calls / best:,.0f} right-hand sides/s (best of 5 x {calls:,} calls)")
    if len(rhs_by_solver) > 1:
        d = np.max(np.abs(rhs_by_solver["sympy"](x_bench, 0.0, par)
                          - rhs_by_solver["numpy"](x_bench, 0.0, par)))
        print(f"  the two agree to {d:.1e}")

    # The 10 s run: upright, 4.6 m/s, lean rate 0.5 rad/s.
    x0 = consistent_state(helpers, lay, par, lean=0.0, steer=0.0, lean_rate=0.5,
                          steer_rate=0.0, speed=4.6)
    dt, n = 1e-3, 10_000
    times = []
    for _ in range(3):
        t0 = time.perf_counter()
        traj = rk4(rhs, x0, par, dt, n)
        times.append(time.perf_counter() - t0)
    print(f"RK4 10 s, dt = 1 ms (4 x {n:,} RHS, Python loop): best {min(times):.3f} s, "
          f"runs {', '.join(f'{s:.3f}' for s in times)} s")
    hol, vel = constraint_residuals(helpers, lay, par, traj[-1])
    print(f"  constraint drift at 10 s (no projection): holonomic {hol:.1e} m, "
          f"velocity {vel:.1e} m/s")

    t_eval = np.arange(n + 1) * dt
    t0 = time.perf_counter()
    sol = solve_ivp(lambda t, x: rhs(x, t, par), (0.0, 10.0), x0, method="RK45",
                    rtol=1e-10, atol=1e-10, t_eval=t_eval)
    t_ivp = time.perf_counter() - t0
    d_ivp = np.max(np.abs(sol.y.T[:, [lay["q4"], lay["q7"]]] - traj[:, [lay["q4"], lay["q7"]]]))
    print(f"solve_ivp RK45 rtol = atol = 1e-10: {t_ivp:.3f} s, {sol.nfev:,} RHS; "
          f"max |d lean|, |d steer| vs RK4 {d_ivp:.1e} rad")
    t0 = time.perf_counter()
    ys, info = odeint(rhs, x0, t_eval, args=(par,), rtol=1e-10, atol=1e-10, full_output=True)
    t_ode = time.perf_counter() - t0
    d_ode = np.max(np.abs(ys[:, [lay["q4"], lay["q7"]]] - traj[:, [lay["q4"], lay["q7"]]]))
    print(f"odeint (LSODA) rtol = atol = 1e-10: {t_ode:.3f} s, {info['nfe'][-1]:,} RHS; "
          f"max |d lean|, |d steer| vs RK4 {d_ode:.1e} rad")

    speed = [helpers["speed"](x[:lay.n_q], x[lay.n_q:], par) for x in traj]
    with open(out_path, "w") as f:
        f.write("t,lean,steer,lean_rate,steer_rate,speed,yaw,x,y,pitch\n")
        for k, x in enumerate(traj):
            f.write(",".join(repr(float(v)) for v in (
                k * dt, x[lay["q4"]], x[lay["q7"]], x[lay["u4"]], x[lay["u7"]], speed[k],
                x[lay["q3"]], x[lay["q1"]], x[lay["q2"]], x[lay["q5"]])) + "\n")
    print(f"trajectory written to {out_path}")


if __name__ == "__main__":
    main()
