"""Time responses, the non-linear comparison, feedback, LQR, pole placement and
controllability from Python, each checked against an independent computation on the same
A, B, C, D: scipy.signal.lsim and python-control's forced_response (their own matrix
exponentials), scipy.linalg.solve_continuous_are (its own Riccati solver),
scipy.signal.place_poles, numpy's eig(A − B K), BicycleParameters'
Meijaard2007WithFeedbackModel (its own A − B K from its own A and B), python-control's ctrb
with numpy's rank. All from PyPI in the test environment only, never dependencies."""

import numpy as np
import pytest

import whipple
from conftest import optional

SPEEDS = (2.0, 3.0, 5.0, 7.0)


def relative(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


def sorted_eig(values):
    values = np.asarray(values).reshape(-1)
    return values[np.lexsort((values.imag, values.real))]


def smooth_input(t):
    """Two torques on the sample times: a steer pulse and a lean ramp with a kink."""
    steer = 0.5 * np.sin(2 * t) * (t < 2.0)
    lean = np.interp(t, [0.0, 1.0, 3.0, 5.0], [0.0, 0.3, -0.2, 0.0])
    return np.column_stack([lean, steer])


def test_simulate_matches_lsim(benchmark):
    optional("scipy")
    import scipy.signal

    s = benchmark.linear_system(5.0)
    t = np.linspace(0.0, 5.0, 501)
    u = smooth_input(t)
    x0 = [0.01, -0.02, 0.1, 0.0]
    ours = s.simulate(t, u, x0)
    _, y, x = scipy.signal.lsim(s.to_scipy(), u, t, X0=x0, interp=True)
    assert relative(ours.x, x) < 1e-10
    assert relative(ours.y, y) < 1e-10
    assert np.array_equal(ours.states["lean"], ours.x[:, 0])
    assert np.array_equal(ours.output("steer_rate"), ours.y[:, 3])


def test_simulate_matches_python_control(benchmark):
    control = optional("control")
    s = benchmark.linear_system(5.0, "steer_torque", ("lean", "steer"))
    t = np.linspace(0.0, 4.0, 401)
    u = 0.3 * np.cos(3 * t)
    ours = s.simulate(t, u)
    theirs = control.forced_response(s.to_control(), T=t, U=u, return_x=True)
    assert relative(ours.x, np.asarray(theirs.states).T) < 1e-9
    assert relative(ours.y, np.asarray(theirs.outputs).T) < 1e-9


def test_simulate_callable_matches_exact(benchmark):
    # A function input through DOPRI5 against the exact piecewise-linear solution of the same
    # input on a fine grid where it is linear (a ramp: exact either way).
    s = benchmark.linear_system(5.0, "steer_torque")
    t = np.linspace(0.0, 3.0, 61)
    exact = s.simulate(t, 0.2 * t)
    integrated = s.simulate(t, lambda tt: [0.2 * tt])
    assert relative(integrated.x, exact.x) < 1e-8


def test_step_impulse_initial_identities(benchmark):
    s = benchmark.linear_system(5.0, "steer_torque", "lean")
    t = np.linspace(0.0, 80.0, 8001)
    step = s.step("steer_torque", t)
    # Stable at 5 m/s (capsize −0.32 /s the slowest): the step settles at the static gain.
    g0 = s.transfer_function().static_gain
    assert abs(step.y[-1, 0] - g0) < 1e-6 * abs(g0)
    # The impulse response is the free response from B and the derivative of the step's.
    impulse = s.impulse(0, t)
    free = s.initial(s.B[:, 0], t)
    assert np.allclose(impulse.x, free.x, rtol=0, atol=1e-14)
    assert np.allclose(np.gradient(step.y[:, 0], t)[1:-1], impulse.y[1:-1, 0], atol=2e-4)


def test_ground_path(benchmark):
    s = benchmark.linear_system(5.0, "steer_torque", "lean",
                                states=("yaw", "rear_contact_x", "rear_contact_y"))
    t = np.linspace(0.0, 2.0, 21)
    r = s.step("steer_torque", t)
    assert r.path is not None
    assert np.allclose(r.path.rear_x, 5.0 * t + r.states["rear_contact_x"])
    assert np.array_equal(r.path.yaw, r.states["yaw"])
    assert benchmark.linear_system(5.0).simulate(t).path is None


def test_simulate_bad_input_raises(benchmark):
    s = benchmark.linear_system(5.0)
    t = np.linspace(0.0, 1.0, 11)
    with pytest.raises(whipple.ArgumentError) as e:
        s.simulate(t, np.zeros((11, 3)))
    assert e.value.field == "u"
    with pytest.raises(whipple.ArgumentError) as e:
        s.simulate(t, x0=[0.0, 0.0])
    assert e.value.field == "x0"
    with pytest.raises(whipple.ArgumentError):
        s.simulate(t[::-1])
    with pytest.raises(whipple.ArgumentError):
        s.simulate(t, lambda tt: [0.0])
    with pytest.raises(ZeroDivisionError):
        s.simulate(t, lambda tt: [1 / 0, 0.0])
    with pytest.raises(whipple.ArgumentError) as e:
        s.step("lateral_force", t)
    assert e.value.field == "input"


@pytest.mark.parametrize("speed", SPEEDS)
def test_lqr_matches_scipy(benchmark, speed):
    optional("scipy")
    import scipy.linalg

    s = benchmark.linear_system(speed)
    q = np.diag([10.0, 1.0, 1.0, 0.1])
    r = np.diag([1.0, 0.5])
    ours = s.lqr(q, r)
    x = scipy.linalg.solve_continuous_are(s.A, s.B, q, r)
    k = np.linalg.solve(r, s.B.T @ x)
    assert relative(ours.X, x) < 1e-9
    assert relative(ours.K, k) < 1e-9
    assert ours.residual < 1e-12
    assert np.max(np.abs(sorted_eig(ours.poles) - sorted_eig(np.linalg.eigvals(s.A - s.B @ k)))) < 1e-9
    assert np.all(ours.poles.real < 0)


def test_lqr_bad_weights_raise(benchmark):
    s = benchmark.linear_system(5.0)
    with pytest.raises(whipple.ArgumentError) as e:
        s.lqr(np.eye(3), np.eye(2))
    assert e.value.field == "Q"
    with pytest.raises(whipple.ArgumentError) as e:
        s.lqr(np.eye(4), -np.eye(2))
    assert e.value.field == "R"


@pytest.mark.parametrize("speed", (2.0, 5.0))
def test_place_poles_matches_scipy(benchmark, speed):
    optional("scipy")
    import scipy.signal

    s = benchmark.linear_system(speed, "steer_torque")
    poles = np.array([-2.0 + 3.0j, -2.0 - 3.0j, -4.0, -6.0])
    k = s.place_poles(poles)
    theirs = scipy.signal.place_poles(s.A, s.B, poles)
    assert np.max(np.abs(sorted_eig(np.linalg.eigvals(s.A - s.B @ k)) - sorted_eig(poles))) < 1e-9
    assert relative(k, theirs.gain_matrix) < 1e-9
    with pytest.raises(whipple.ArgumentError):
        benchmark.linear_system(speed).place_poles(poles)


K_STEER = np.array([[0.0, 0.0, 0.0, 0.0], [-20.0, 5.0, -3.0, 0.5]])


@pytest.mark.parametrize("speed", SPEEDS)
def test_closed_loop_eig_matches_numpy(benchmark, speed):
    loop = benchmark.closed_loop(K_STEER)
    ours = loop.eig(speed)
    s = benchmark.linear_system(speed)
    theirs = np.linalg.eigvals(s.A - s.B @ K_STEER)
    assert np.max(np.abs(sorted_eig(ours.values) - sorted_eig(theirs))) < 1e-12 * np.max(np.abs(theirs)) * 10
    system = loop.system(speed)
    assert np.allclose(system.A, s.A - s.B @ K_STEER, rtol=0, atol=1e-14)


def test_closed_loop_labels_and_critical_speeds(benchmark):
    loop = benchmark.closed_loop(K_STEER)
    e = loop.eig(np.linspace(0.5, 10.0, 40))
    assert e.modes is not None and len(e.modes) == 4 and e.values.shape == (40, 4)
    speeds = loop.critical_speeds(0.0, 10.0)
    assert "stable_speed_ranges" in speeds
    # Zero gains: the open loop's certified weave and capsize speeds.
    open_loop = benchmark.closed_loop(np.zeros((2, 4))).critical_speeds(0.0, 10.0)
    v = benchmark.critical_speeds()
    assert abs(open_loop["weave_speed"] - v.v_w) < 1e-9
    assert abs(open_loop["capsize_speed"] - v.v_c) < 1e-9


def test_closed_loop_schedule_and_yaw(benchmark):
    k0 = np.array([[-10.0, 2.0, -1.0, 0.0]])
    k1 = np.array([[-30.0, 6.0, -3.0, 0.0]])
    loop = benchmark.closed_loop(([1.0, 5.0], [k0, k1]), inputs="steer_torque")
    s = benchmark.linear_system(3.0, "steer_torque")
    k = 0.5 * (k0 + k1)
    theirs = np.linalg.eigvals(s.A - s.B @ k)
    assert np.max(np.abs(sorted_eig(loop.eig(3.0).values) - sorted_eig(theirs))) < 1e-11
    with pytest.raises(whipple.ArgumentError):
        loop.eig(6.0)
    # A gain on yaw: the general eigensolver, unlabelled, five eigenvalues.
    yaw = benchmark.closed_loop([[-20.0, 5.0, -3.0, 0.5, 2.0]], inputs="steer_torque",
                                states="yaw")
    e = yaw.eig([3.0, 4.0])
    assert e.modes is None and e.values.shape == (2, 5)
    with pytest.raises(whipple.ArgumentError) as err:
        yaw.critical_speeds()
    assert err.value.field == "gains"


def test_closed_loop_eigenvectors(benchmark):
    """The closed loop's eigenvectors satisfy (A − B K) x = λ x, for gains on the lean–steer
    states (4 components) and with a gain on yaw (5), as numpy's would, up to scale."""
    for loop, states in ((benchmark.closed_loop(K_STEER), 4),
                         (benchmark.closed_loop([[-20.0, 5.0, -3.0, 0.5, 2.0]],
                                                inputs="steer_torque", states="yaw"), 5)):
        e = loop.eig([2.0, 5.0])
        assert e.vectors.shape == (2, states, states)
        assert np.all(np.isfinite(e.vectors))
        for i, v in enumerate((2.0, 5.0)):
            a = loop.system(v).A[:states, :states]
            for j in range(states):
                x = e.vectors[i, :, j]
                assert abs(np.linalg.norm(x) - 1.0) < 1e-14
                residual = np.linalg.norm(a @ x - e.values[i, j] * x)
                assert residual < 1e-12 * (1 + np.linalg.norm(a)), residual


def test_lqr_schedule_matches_scipy_and_is_certified(benchmark):
    optional("scipy")
    import scipy.linalg

    speeds = [1.0, 2.0, 4.0, 8.0]
    q, r = np.diag([10.0, 1.0, 1.0, 0.1]), np.array([[1.0]])
    loop = benchmark.lqr_schedule(speeds, q, r)
    assert loop.speeds == speeds and loop.residuals is not None
    assert np.all(loop.residuals < 1e-12)
    for v in speeds:
        s = benchmark.linear_system(v, "steer_torque")
        x = scipy.linalg.solve_continuous_are(s.A, s.B, q, r)
        k = np.linalg.solve(r, s.B.T @ x)
        assert relative(loop.system(v).A, s.A - s.B @ k) < 1e-9
    # Between the design speeds the gains are interpolated: certified stable all through.
    ranges = loop.critical_speeds(1.0, 8.0)["stable_speed_ranges"]
    assert len(ranges) == 1 and ranges[0][0] == 1.0 and ranges[0][1] == 8.0
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.lqr_schedule([2.0, 1.0], q, r)
    assert e.value.field == "speeds"
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.lqr_schedule(speeds, -q, r)
    assert e.value.field == "Q"


@pytest.mark.parametrize("speed", (1.0, 5.0))
def test_closed_loop_transfer_functions_match_python_control(benchmark, speed):
    """The closed loop's transfer functions (exact, from its polynomial matrix) against
    python-control's ``feedback`` of the open loop, steer torque in the loop included."""
    control = optional("control")
    k = np.array([[-100.0, 10.0, -20.0, 0.0]])
    loop = benchmark.closed_loop(k, inputs="steer_torque")
    closed = loop.system(speed, ["lean", "steer", "steer_torque"])
    open_loop = benchmark.linear_system(speed, "steer_torque",
                                        ["lean", "steer", "lean_rate", "steer_rate"])
    plant = control.ss(open_loop.A, open_loop.B, np.eye(4), np.zeros((4, 1)))
    theirs = control.feedback(plant, control.ss([], [], [], k), sign=-1)
    omega = np.logspace(-1, 2, 60)
    response = closed.frequency_response(omega)
    g = theirs(1j * omega)  # (outputs, inputs, n)
    for row, expected in ((0, g[0, 0]), (1, g[1, 0])):
        ours = response.response[row, 0]
        assert np.max(np.abs(ours - expected) / np.abs(expected)) < 1e-10
    # The torque the loop applies: r − K x, that is 1 − K G_x(iω).
    applied = 1.0 - (k @ g[:, 0, :])[0]
    ours = response.response[2, 0]
    assert np.max(np.abs(ours - applied) / np.abs(applied)) < 1e-10
    tf = closed.transfer_function("lean", "steer_torque")
    assert np.max(np.abs(np.sort_complex(tf.poles) -
                         np.sort_complex(loop.eig([speed]).values[0]))) < 1e-10
    with pytest.raises(whipple.ArgumentError) as e:
        loop.system(speed, ["lean_torque"])
    assert e.value.field == "outputs"


def test_closed_loop_bad_gains_raise(benchmark):
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.closed_loop(np.zeros((2, 3)))
    assert e.value.field == "gains"
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.closed_loop([[np.nan, 0, 0, 0], [0, 0, 0, 0]])
    assert e.value.field == "gains"
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.closed_loop(([2.0, 1.0], [np.zeros((2, 4))] * 2))
    assert e.value.field == "speeds"


@pytest.mark.parametrize("speed", (2.0, 4.0, 6.0))
def test_closed_loop_matches_bicycleparameters(benchmark, speed):
    optional("bicycleparameters")
    from bicycleparameters.models import Meijaard2007WithFeedbackModel
    from bicycleparameters.parameter_sets import Meijaard2007ParameterSet

    ps = Meijaard2007ParameterSet({**benchmark.to_dict(), "v": speed}, True)
    model = Meijaard2007WithFeedbackModel(ps)
    names = ["kTphi_phi", "kTphi_del", "kTphi_phid", "kTphi_deld",
             "kTdel_phi", "kTdel_del", "kTdel_phid", "kTdel_deld"]
    a, _ = model.form_state_space_matrices(v=speed, **dict(zip(names, K_STEER.reshape(-1))))
    theirs = np.linalg.eigvals(a)
    ours = benchmark.closed_loop(K_STEER).eig(speed).values
    # The tolerance: closed-loop eigenvalues to 1e-12 (relative to max(1, |λ|)).
    scale = np.maximum(1.0, np.abs(sorted_eig(theirs)))
    assert np.max(np.abs(sorted_eig(ours) - sorted_eig(theirs)) / scale) < 1e-12


@pytest.mark.parametrize("speed", SPEEDS)
def test_controllability_rank_matches_ctrb(benchmark, speed):
    control = optional("control")
    s = benchmark.linear_system(speed, states=("yaw", "rear_contact_y"))
    for input in (None, "lean_torque", "steer_torque"):
        c = s.controllability(input)
        b = s.B if input is None else s.B[:, [0 if input == "lean_torque" else 1]]
        assert c.rank == np.linalg.matrix_rank(control.ctrb(s.A, b))
        assert c.states == 6


def test_modal_and_uncontrollable_speeds(benchmark):
    lost = benchmark.uncontrollable_speeds("steer_torque")
    assert len(lost.speeds) == 2 and not lost.everywhere
    for v in lost.speeds:
        if v <= 0:
            continue
        s = benchmark.linear_system(v, "steer_torque")
        assert s.controllability().rank < 4
        m = s.modal_controllability("steer_torque")
        assert m.measures.min() < 1e-6 * m.measures.max()
    s = benchmark.linear_system(5.0, "steer_torque")
    assert s.controllability("steer_torque").full
    assert s.modal_controllability(0).measures.min() > 0


def test_compare_manoeuvre_cubic_scaling(benchmark):
    t = np.linspace(0.0, 2.0, 21)

    def lean_difference(amplitude):
        pulse = ([0.0, 0.5, 0.5 + 1e-9, 2.0], [amplitude, amplitude, 0.0, 0.0])
        both = benchmark.compare_manoeuvre(5.0, t, steer_torque=pulse, rtol=1e-12)
        assert np.allclose(both.difference["lean"], both.nonlinear["lean"] - both.linear["lean"])
        return np.max(np.abs(both.difference["lean"]))

    ratio = lean_difference(0.1) / lean_difference(0.05)
    assert 7.0 < ratio < 9.0


def test_compare_manoeuvre_arrays_and_errors(benchmark):
    t = np.linspace(0.0, 1.0, 11)
    both = benchmark.compare_manoeuvre(4.0, t, lean_torque=0.05 * t, lean0=0.01)
    assert both.linear["lean"][0] == 0.01 and both.nonlinear_steps > 0
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.compare_manoeuvre(4.0, t, steer_torque=np.zeros(5))
    assert e.value.field == "steer_torque"


def test_compare_manoeuvre_plot(benchmark):
    optional("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    t = np.linspace(0.0, 1.0, 11)
    both = benchmark.compare_manoeuvre(5.0, t, steer_torque=([0.0, 1.0], [0.1, 0.1]))
    ax = both.plot_paths()
    assert len(ax.lines) == 4
