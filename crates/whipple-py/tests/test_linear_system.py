"""The bicycle as a linear system: A, B, C, D with named signals, transfer functions and
frequency responses, checked against identities and against independent evaluations —
scipy.signal and python-control on the same A, B, C, D (their own state-space arithmetic,
where ours goes through the polynomial matrix and its adjugate), and BicycleParameters'
Bode path (``Bicycle.plot_bode``, on its own A and B) on the benchmark bicycle.
All three from PyPI in the test environment only, never dependencies of the package."""

import os
import shutil
import warnings

import numpy as np
import pytest

import whipple
from conftest import DATA, optional

SPEEDS = (3.0, 5.0, 7.0)
OMEGA = np.logspace(-1, 2, 301)


def scipy_signal():
    optional("scipy")
    import scipy.signal

    return scipy.signal


def direct_response(system, omega):
    """C (iωI − A)⁻¹ B + D by solving at each frequency: (outputs, inputs, frequencies)."""
    n = system.A.shape[0]
    out = np.empty((system.C.shape[0], system.B.shape[1], len(omega)), dtype=complex)
    for k, w in enumerate(omega):
        out[:, :, k] = system.C @ np.linalg.solve(1j * w * np.eye(n) - system.A, system.B) + system.D
    return out


def test_matrices_names_and_units(benchmark):
    s = benchmark.linear_system(5.0)
    a, b = benchmark.state_space(5.0)
    assert np.array_equal(s.A, a) and np.array_equal(s.B, b)
    assert np.array_equal(s.C, np.eye(4)) and not s.D.any()
    assert [x.name for x in s.states] == ["lean", "steer", "lean_rate", "steer_rate"]
    assert [x.unit for x in s.inputs] == ["N m", "N m"]
    assert [str(x) for x in s.outputs] == ["lean", "steer", "lean_rate", "steer_rate"]
    assert s.speed == 5.0
    assert not s.A.flags.writeable


def test_outputs_bring_the_states_they_need(benchmark):
    s = benchmark.linear_system(4.0, "lateral_force:0.3,-1.0",
                                ["front_contact_y", "rear_frame_point_y:0.5,-1.2", "yaw_rate"])
    assert [x.name for x in s.states][4:] == ["yaw", "rear_contact_y"]
    assert s.inputs[0].unit == "N" and "x = 0.3 m" in s.inputs[0].label
    assert [x.unit for x in s.outputs] == ["m", "m", "rad/s"]
    assert s.A.shape == (6, 6) and s.B.shape == (6, 1) and s.C.shape == (3, 6)
    # By label or by name where the name is unique.
    g = s.transfer_function("front_contact_y", "lateral_force")
    assert g.integrators == 2 and g.static_gain is None


def test_poles_are_the_eigenvalues_and_static_gain_is_minus_c_a_inverse_b(benchmark):
    for v in SPEEDS:
        s = benchmark.linear_system(v, ["lean_torque", "steer_torque"], ["lean", "steer"])
        assert np.allclose(np.sort_complex(s.poles()), np.sort_complex(np.linalg.eigvals(s.A)),
                           rtol=1e-12, atol=1e-12)
        static = -s.C @ np.linalg.solve(s.A, s.B)
        for o in range(2):
            for i in range(2):
                g = s.transfer_function(o, i)
                assert np.allclose(np.sort_complex(g.poles), np.sort_complex(s.poles()), rtol=1e-12)
                assert g.static_gain == pytest.approx(static[o, i], rel=1e-11)
                # G = K Π(s − z) / Π(s − p) at a test point.
                z = 0.7 + 1.3j
                zpk = g.gain * np.prod(z - g.zeros) / np.prod(z - g.poles)
                assert zpk == pytest.approx(np.polyval(g.numerator, z) / np.polyval(g.denominator, z),
                                            rel=1e-11)


def test_frequency_response_against_scipy_state_space_and_direct_solve(benchmark):
    signal = scipy_signal()
    outputs = ["lean", "steer", "yaw_rate", "front_contact_y", "rear_contact_lateral_acceleration"]
    worst = worst_scipy = 0.0
    for v in SPEEDS:
        s = benchmark.linear_system(v, ["lean_torque", "steer_torque"], outputs)
        ours = s.frequency_response(OMEGA)
        direct = direct_response(s, OMEGA)
        worst = max(worst, np.max(np.abs(ours.response - direct) / np.abs(direct)))
        for o in range(len(outputs)):
            for i in range(2):
                sys = signal.StateSpace(s.A, s.B[:, [i]], s.C[[o]], s.D[[o]][:, [i]])
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", signal.BadCoefficients)
                    _, h = signal.freqresp(sys, OMEGA)
                rel = np.abs(ours.response[o, i] - h) / np.abs(h)
                worst_scipy = max(worst_scipy, rel.max())
        # Magnitude and phase are those of the complex response; the phase is continuous.
        assert np.allclose(ours.magnitude, np.abs(ours.response), rtol=1e-15)
        assert np.allclose(ours.magnitude_db, 20 * np.log10(np.abs(ours.response)), atol=1e-12)
        assert np.allclose(np.exp(1j * ours.phase), ours.response / np.abs(ours.response), atol=1e-12)
        assert np.all(np.abs(np.diff(ours.phase, axis=-1)) < np.pi)
    print(f"frequency response: worst relative difference {worst:.1e} from C (iωI − A)⁻¹ B, "
          f"{worst_scipy:.1e} from scipy.signal.freqresp")
    assert worst < 1e-10, worst
    # scipy evaluates the state space through its transfer function (ss2tf, then zeros and
    # poles): the conditioning of that conversion bounds the agreement, not ours.
    assert worst_scipy < 1e-8, worst_scipy


def test_zeros_against_scipy_ss2zpk(benchmark):
    signal = scipy_signal()
    for v in SPEEDS:
        s = benchmark.linear_system(v, ["lean_torque", "steer_torque"],
                                    ["lean", "steer", "front_contact_y", "yaw_rate"])
        for o in range(4):
            for i in range(2):
                g = s.transfer_function(o, i)
                z, p, k = signal.ss2zpk(s.A, s.B, s.C[[o]], s.D[[o]], input=i)
                # The realization's integrators that the output does not see (yaw and y for
                # lean) come back from ss2zpk as zeros at 0 cancelling poles at 0: drop them.
                for _ in range(len(p) - len(g.poles)):
                    z = np.delete(z, np.argmin(np.abs(z)))
                    p = np.delete(p, np.argmin(np.abs(p)))
                # A numerator coefficient that vanishes exactly (front_contact_y from the lean
                # torque) comes out of ss2tf as round-off: spurious zeros beyond 1e7: dropped,
                # and the gain (then that round-off) not compared.
                spurious = np.abs(z) > 1e6
                z = z[~spurious]
                assert len(z) == len(g.zeros), (v, o, i, z, g.zeros)
                assert np.allclose(np.sort_complex(z), np.sort_complex(g.zeros), rtol=1e-7, atol=1e-9)
                if not spurious.any():
                    assert k == pytest.approx(g.gain, rel=1e-9)
                assert np.allclose(np.sort_complex(p), np.sort_complex(g.poles), rtol=1e-9, atol=1e-9)


def test_against_python_control(benchmark):
    control = optional("control")
    for v in SPEEDS:
        s = benchmark.linear_system(v, ["lean_torque", "steer_torque"], ["lean", "steer", "front_contact_y"])
        sys = s.to_control()
        assert list(sys.input_labels) == ["lean_torque", "steer_torque"]
        assert list(sys.output_labels) == ["lean", "steer", "front_contact_y"]
        assert list(sys.state_labels)[-2:] == ["yaw", "rear_contact_y"]
        theirs = control.frequency_response(sys, OMEGA)
        h = np.asarray(theirs.complex).reshape(3, 2, len(OMEGA))
        ours = s.frequency_response(OMEGA).response
        rel = np.max(np.abs(ours - h) / np.abs(h))
        print(f"python-control at {v} m/s: worst relative difference {rel:.1e}")
        assert rel < 1e-10
        assert np.allclose(np.sort_complex(sys.poles()), np.sort_complex(s.poles()), atol=1e-9)
        lean = benchmark.linear_system(v, "steer_torque", "lean")
        z = np.asarray(lean.to_control().zeros())
        assert np.allclose(np.sort_complex(z), np.sort_complex(lean.transfer_function().zeros),
                           rtol=1e-9, atol=1e-9)


def test_to_scipy_is_the_same_system(benchmark):
    scipy_signal()
    s = benchmark.linear_system(5.0, "steer_torque", "lean")
    ss = s.to_scipy()
    assert np.array_equal(ss.A, s.A) and np.array_equal(ss.C, s.C)
    tf = s.transfer_function().to_scipy()
    assert np.allclose(tf.num / tf.num[0], s.transfer_function().numerator / s.transfer_function().numerator[0])


def test_the_counter_steering_zero_and_its_speed(benchmark):
    """Steer torque → lean: a right-half-plane zero below the speed where the numerator's constant
    term −(g K₀₁₂ + v² K₂₁₂) vanishes, none above (Meijaard 2007's K₀, K₂ from canonical())."""
    _, _, k0, k2 = benchmark.canonical()
    g = 9.81
    v0 = np.sqrt(-g * k0[0, 1] / k2[0, 1])
    speeds = benchmark.origin_zero_speeds("steer_torque", "lean")
    assert speeds[-1] == pytest.approx(v0, rel=1e-13) and speeds[0] == pytest.approx(-v0, rel=1e-13)
    for v, rhp in [(0.3, 1), (0.5, 1), (0.65, 0), (3.0, 0), (5.0, 0), (7.0, 0)]:
        tf = benchmark.linear_system(v, "steer_torque", "lean").transfer_function()
        assert len(tf.rhp_zeros) == rhp, (v, tf.zeros)
    # Steer torque → front contact's lateral position: the steer's zero at +√(g K₀₂₂… ) stays in
    # the right half-plane at every speed (the front contact first moves the wrong way).
    for v in SPEEDS:
        tf = benchmark.linear_system(v, "steer_torque", "front_contact_y").transfer_function()
        assert len(tf.rhp_zeros) == 1


def test_batch_over_speeds_equals_one_at_a_time(benchmark):
    speeds = np.linspace(0.5, 9.5, 37)
    batch = benchmark.frequency_response(speeds, OMEGA, ["lean_torque", "steer_torque"], ["lean", "steer"])
    serial = benchmark.frequency_response(speeds, OMEGA, ["lean_torque", "steer_torque"], ["lean", "steer"],
                                          parallel=False)
    assert batch.response.shape == (37, 2, 2, len(OMEGA))
    assert np.array_equal(batch.response, serial.response)
    for k in (0, 18, 36):
        one = benchmark.linear_system(speeds[k], ["lean_torque", "steer_torque"], ["lean", "steer"])
        f = one.frequency_response(OMEGA)
        assert np.array_equal(batch.response[k], f.response)
        assert np.array_equal(batch.phase[k], f.phase)
    single = benchmark.frequency_response(5.0, OMEGA)
    assert single.response.shape == (1, 1, len(OMEGA)) and single.speeds is None
    # Many speeds, enough to be shared among the cores.
    many = benchmark.frequency_response(np.linspace(1, 8, 300), OMEGA)
    assert np.isfinite(many.magnitude_db).all()


def test_bad_input_names_the_field(benchmark):
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.linear_system(5.0, "steer_torque", "heading")
    assert e.value.field == "outputs" and "yaw_rate" in str(e.value)
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.linear_system(5.0, "lateral_force", "lean")
    assert e.value.field == "inputs"
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.linear_system(5.0, "steer_torque", "lean", states=["phi"])
    assert e.value.field == "states"
    s = benchmark.linear_system(5.0, "steer_torque", ["lean", "front_contact_y"])
    with pytest.raises(whipple.ArgumentError) as e:
        s.frequency_response([1.0, np.nan])
    assert e.value.field == "frequencies"
    with pytest.raises(whipple.ArgumentError) as e:
        s.frequency_response([0.0, 1.0])  # a pole of the lateral position
    assert e.value.field == "frequencies"
    with pytest.raises(whipple.ArgumentError) as e:
        s.transfer_function("steer", 0)
    assert e.value.field == "output"
    with pytest.raises(whipple.ArgumentError) as e:
        s.transfer_function(0, 3)
    assert e.value.field == "input"
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.frequency_response([3.0, np.inf], OMEGA)
    with pytest.raises(whipple.ArgumentError) as e:
        benchmark.frequency_response([3.0], [1.0, np.inf])
    assert e.value.field == "frequencies"


def test_missing_optional_package_names_the_extra(benchmark, monkeypatch):
    # A None entry in sys.modules makes `import control` fail as if it were not installed.
    monkeypatch.setitem(__import__("sys").modules, "control", None)
    with pytest.raises(ImportError, match=r"whipple\[control\]"):
        benchmark.linear_system(5.0).to_control()


def test_bode_plot_draws_every_speed(benchmark):
    optional("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    f = benchmark.frequency_response(SPEEDS, OMEGA, "steer_torque", "lean")
    fig = f.plot()
    magnitude, phase = fig.axes[:2]
    assert len(magnitude.lines) == 3 and len(phase.lines) == 3
    assert magnitude.get_xscale() == "log"
    assert [t.get_text() for t in magnitude.get_legend().get_texts()] == ["3 m/s", "5 m/s", "7 m/s"]
    assert np.allclose(phase.lines[1].get_ydata(), f.phase_deg[1, 0, 0])
    import matplotlib.pyplot as plt

    plt.close(fig)


# BicycleParameters' Bode path ---------------------------------------------------------------

def _bp_benchmark(tmp_path):
    bp = optional("bicycleparameters")
    target = tmp_path / "bicycles" / "Benchmark" / "Parameters"
    target.mkdir(parents=True)
    shutil.copy(DATA / "bicycleparameters" / "BenchmarkBenchmark.txt", target)
    cwd = os.getcwd()
    try:
        os.chdir(tmp_path)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return bp.Bicycle("Benchmark", pathToData=str(tmp_path))
    finally:
        os.chdir(cwd)


def test_against_bicycleparameters_plot_bode(tmp_path):
    """BicycleParameters' ``Bicycle.plot_bode(speed, u, y)`` (magnitude [dB] and unwrapped phase
    [deg] on ω = logspace(0, 2, 1000), by inverting iωI − A at each ω) at 3, 5 and 7 m/s, for
    both torques and lean and steer, on the same file read by both."""
    optional("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    theirs = _bp_benchmark(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        ours = whipple.Bicycle.from_file(DATA / "bicycleparameters" / "BenchmarkBenchmark.txt")
    omega = np.logspace(0, 2, 1000)
    mine = ours.frequency_response(SPEEDS, omega, ["lean_torque", "steer_torque"], ["lean", "steer"])
    worst_magnitude = worst_phase = 0.0
    for k, v in enumerate(SPEEDS):
        for u in range(2):
            for y in range(2):
                db, phase, fig = theirs.plot_bode(v, u, y)
                plt.close(fig)
                rel = np.abs(10 ** ((mine.magnitude_db[k, y, u] - db) / 20) - 1)
                worst_magnitude = max(worst_magnitude, rel.max())
                worst_phase = max(worst_phase, np.abs(mine.phase_deg[k, y, u] - phase).max())
    print(f"BicycleParameters plot_bode: |G| within {worst_magnitude:.1e} relative, phase within "
          f"{worst_phase:.1e} deg")
    assert worst_magnitude < 1e-10, worst_magnitude
    assert worst_phase < 1e-8, worst_phase
