"""Hess's human controller against an independent transcription of HumanControl's
`system_state_space.m` (MIT licence, J. K. Moore; github.com/moorepants/HumanControl), written
here in numpy from the MATLAB source: fed whipple's own open-loop A, B, C in HumanControl's
state, input and output order (mapped by name), it must give whipple's closed loop to 1e-12.
The loops' transfer functions are checked against the block diagram of `WhippleModel.mdl`
evaluated numerically from the same open-loop matrices."""

import warnings

import numpy as np
import pytest

import whipple
from conftest import DATA

GAINS = DATA / "humancontrol" / "gains"

#: HumanControl's names (bicycle_state_space.m) → whipple's.
NAMES = {"yP": "rear_contact_y", "psi": "yaw", "phi": "lean", "delta": "steer",
         "phiDot": "lean_rate", "deltaDot": "steer_rate", "yQ": "front_contact_y",
         "tPhi": "lean_torque", "tDelta": "steer_torque", "tDeltaDot": "steer_torque_rate",
         "yQc": "lateral_command", "psic": "heading_command"}
WHIPPLE_TO_HC = {**{v: k for k, v in NAMES.items()}, "steer_torque": "tDelta"}

#: The order bicycle_state_space.m gives its states and outputs (the subset the loops need,
#: in the relative order of its full lists).
HC_STATES = ["yP", "psi", "phi", "delta", "phiDot", "deltaDot"]
HC_OUTPUTS = ["psi", "phi", "delta", "phiDot", "yQ"]
HC_INPUTS = ["tPhi", "tDelta"]


def hc_bicycle(bike, speed, stype):
    """whipple's open loop as HumanControl's `bicycle` ss: A, B, C with state, input and
    output names in its order."""
    lateral = stype == "lateral"
    states = HC_STATES if lateral else HC_STATES[1:]
    outputs = HC_OUTPUTS if lateral else HC_OUTPUTS[:4]
    system = bike.linear_system(speed, inputs=[NAMES[i] for i in HC_INPUTS],
                                outputs=[NAMES[o] for o in outputs],
                                states=["yaw"] + (["rear_contact_y"] if lateral else []))
    s_names = [s.name for s in system.states]
    i_names = [s.name for s in system.inputs]
    o_names = [s.name for s in system.outputs]
    ps = [s_names.index(NAMES[s]) for s in states]
    pi = [i_names.index(NAMES[i]) for i in HC_INPUTS]
    po = [o_names.index(NAMES[o]) for o in outputs]
    assert sorted(ps) == list(range(len(s_names)))
    return {"A": system.A[np.ix_(ps, ps)], "B": system.B[np.ix_(ps, pi)],
            "C": system.C[np.ix_(po, ps)], "StateName": states, "InputName": HC_INPUTS,
            "OutputName": outputs}


def system_state_space(stype, bicycle, gains, neuro, inputs):
    """HumanControl's system_state_space.m, transcribed: the closed loop's A and B."""
    states = bicycle["StateName"] + ["tDelta", "tDeltaDot"]
    m = len(bicycle["StateName"])
    A = np.zeros((m + 2, m + 2))
    A[:m, :m] = bicycle["A"]
    A[:m, states.index("tDelta")] = bicycle["B"][:, bicycle["InputName"].index("tDelta")]
    wnm, zetanm = neuro
    A[m:, m:] = [[0.0, 1.0], [-wnm ** 2, -2.0 * zetanm * wnm]]
    if stype == "lateral":
        min_outputs = ["psi", "phi", "delta", "phiDot", "yQ"]
        min_states = ["yP", "psi", "phi", "delta", "phiDot", "deltaDot"]
    else:
        min_outputs = ["psi", "phi", "delta", "phiDot"]
        min_states = ["psi", "phi", "delta", "phiDot", "deltaDot"]
    # The bicycle's C without the rows and columns of other outputs and states (kept in the
    # bicycle's order, as MATLAB's deletion keeps them).
    rows = [k for k, o in enumerate(bicycle["OutputName"]) if o in min_outputs]
    cols = [k for k, s in enumerate(bicycle["StateName"]) if s in min_states]
    min_c = bicycle["C"][np.ix_(rows, cols)]
    row = states.index("tDeltaDot")
    k_delta, k_phi_dot, k_phi, k_psi = gains[:4]
    for i, name in enumerate(min_states):
        coef = -k_delta * wnm ** 2 * (min_c[0, i] * k_phi * k_phi_dot * k_psi
                                      + min_c[1, i] * k_phi * k_phi_dot
                                      + min_c[2, i]
                                      + min_c[3, i] * k_phi_dot)
        if stype == "lateral":
            coef += -k_delta * wnm ** 2 * min_c[4, i] * k_phi * k_phi_dot * k_psi * gains[4]
        A[row, states.index(name)] = coef
    B = np.zeros((m + 2, len(inputs)))
    for i, name in enumerate(inputs):
        if name == "yQc" and stype == "lateral":
            B[-1, i] = wnm ** 2 * np.prod(gains)
        elif name == "psic" and stype == "heading":
            B[-1, i] = wnm ** 2 * np.prod(gains[:4])
        else:
            B[:m, i] = bicycle["B"][:, bicycle["InputName"].index(name)]
    return A, B, states


def benchmark_table():
    return whipple.read_gains(GAINS / "BenchmarkSteerGains.txt")


@pytest.mark.parametrize("stype", ["heading", "lateral"])
@pytest.mark.parametrize("speed", [2.5, 3.6, 5.0, 8.34, 12.0])
def test_closed_loop_matches_a_transcription_of_system_state_space(benchmark, stype, speed):
    gains = benchmark_table().at(speed).gains
    neuro = (30.0, 0.707)
    command = "yQc" if stype == "lateral" else "psic"
    A, B, states = system_state_space(stype, hc_bicycle(benchmark, speed, stype), gains, neuro,
                                      [command, "tPhi"])
    rider = whipple.HumanController(stype, gains, *neuro)
    ridden = rider.closed_loop(benchmark, speed, disturbances=["lean_torque"])
    # whipple's states and inputs in HumanControl's order, mapped by name.
    ps = [ridden.states.index(NAMES[s]) for s in states]
    pi = [ridden.inputs.index(NAMES[i]) for i in (command, "tPhi")]
    a = ridden.a[np.ix_(ps, ps)]
    b = ridden.b[np.ix_(ps, pi)]
    assert a.shape == A.shape and b.shape == B.shape
    np.testing.assert_allclose(a, A, rtol=1e-12, atol=1e-12 * np.abs(A).max())
    np.testing.assert_allclose(b, B, rtol=1e-12, atol=1e-12 * np.abs(B).max())
    # The eigenvalues are A's, to the eigenproblem's conditioning: two eigensolvers (faer's,
    # LAPACK's) on matrices equal to 1e-12 agree to ~1e-9 relative on the 8 × 8 closed loop
    # at 12 m/s (measured 1.5e-9), so the bound is the condition-aware 1e-8.
    np.testing.assert_allclose(np.sort_complex(ridden.eigenvalues),
                               np.sort_complex(np.linalg.eigvals(A)), rtol=1e-8, atol=1e-9)


def test_the_neuromuscular_filter_and_gains_reach_the_matrices(benchmark):
    # Not the defaults, so that a binding that dropped them would show.
    gains = [40.0, -0.06, 11.0, 0.2, 0.09]
    neuro = (25.0, 0.5)
    A, B, states = system_state_space("lateral", hc_bicycle(benchmark, 6.0, "lateral"), gains,
                                      neuro, ["yQc"])
    ridden = whipple.HumanController("lateral", gains, *neuro).closed_loop(benchmark, 6.0)
    ps = [ridden.states.index(NAMES[s]) for s in states]
    np.testing.assert_allclose(ridden.a[np.ix_(ps, ps)], A, rtol=1e-12,
                               atol=1e-12 * np.abs(A).max())
    np.testing.assert_allclose(ridden.b[ps, 0], B[:, 0], rtol=1e-12)


def test_tabulated_benchmark_gains_stabilize_both_tasks(benchmark):
    table = benchmark_table()
    for task in ("heading", "lateral"):
        result = whipple.human_eigenvalues(benchmark, task, table.speeds, table=table)
        assert not result.extrapolated.any()
        assert (result.eigenvalues.real.max(axis=1) < 0).all(), task
        np.testing.assert_array_equal(result.gains, table.gains)
        assert result.eigenvalues.shape == (len(table.speeds), 7 if task == "heading" else 8)


def test_read_gains_gives_arrays_and_warns_when_extrapolating():
    table = benchmark_table()
    assert table.speeds.shape == (8,) and table.gains.shape == (8, 5)
    assert table.gains[4].tolist() == [46.5457, -0.0522, 12.6611, 0.1849, 0.0959]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        inside = table.at(4.9)
    assert not inside.extrapolated
    np.testing.assert_allclose(inside.gains, 0.5 * (table.gains[3] + table.gains[4]), rtol=1e-14)
    with pytest.warns(whipple.ExtrapolationWarning, match="13 m/s is outside"):
        beyond = table.at(13.0)
    assert beyond.extrapolated
    slope = (table.gains[7] - table.gains[6]) / (12.0 - 8.34)
    np.testing.assert_allclose(beyond.gains, table.gains[7] + slope, rtol=1e-12)
    with pytest.warns(whipple.ExtrapolationWarning, match="1 of 2 speeds"):
        whipple.human_eigenvalues(whipple.Bicycle.preset("benchmark"), "heading", [5.0, 13.0],
                                  table=table)


def test_bad_gains_files_and_controllers_name_the_field(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("speed,kDelta,kPhiDot,kPhi,kPsi\n5.0,46.5,-0.05,12.6,0.18\n")
    with pytest.raises(whipple.ParseError, match="kY"):
        whipple.read_gains(bad)
    with pytest.raises(whipple.ParameterError, match="`neuromuscular frequency` = -30"):
        whipple.HumanController("lateral", [46.5, -0.05, 12.6, 0.18, 0.09], -30.0)
    with pytest.raises(whipple.ParameterError, match="`kY` = 0"):
        whipple.HumanController("lateral", [46.5, -0.05, 12.6, 0.18, 0.0])
    with pytest.raises(whipple.ArgumentError, match="task"):
        whipple.HumanController("weave", [46.5, -0.05, 12.6, 0.18, 0.09])


def open_loop_response(bicycle, omega):
    """G(iω) from steer torque to each of HumanControl's outputs, numerically from A, B, C."""
    n = bicycle["A"].shape[0]
    b = bicycle["B"][:, bicycle["InputName"].index("tDelta")]
    x = np.linalg.solve(1j * omega * np.eye(n) - bicycle["A"], b)
    return dict(zip(bicycle["OutputName"], bicycle["C"] @ x))


@pytest.mark.parametrize("speed", [3.0, 5.0, 9.0])
def test_loop_transfer_functions_follow_the_block_diagram(benchmark, speed):
    # WhippleModel.mdl: the neuromuscular filter then the bicycle, loops δ, φ̇, φ, ψ, y_Q
    # nested; "open" at loop i cuts its feedback, the inner loops closed; "closed" closes it.
    gains = benchmark_table().at(speed).gains
    wnm, zeta = 30.0, 0.707
    bicycle = hc_bicycle(benchmark, speed, "lateral")
    loops = whipple.HumanController("lateral", gains).loops(benchmark, speed)
    assert [l.name for l in loops] == ["delta", "phi_dot", "phi", "psi", "y"]
    outputs = ["delta", "phiDot", "phi", "psi", "yQ"]
    for omega in (0.3, 1.0, 2.0, 7.0, 40.0):
        s = 1j * omega
        g = open_loop_response(bicycle, omega)
        neuro = wnm ** 2 / (s ** 2 + 2 * zeta * wnm * s + wnm ** 2)
        forward = np.cumprod(gains)  # k_δ, k_δ k_φ̇, …
        for i, loop in enumerate(loops):
            inner = sum(forward[m] * neuro * g[outputs[m]] for m in range(i))
            expected_open = forward[i] * neuro * g[outputs[i]] / (1 + inner)
            expected_closed = expected_open / (1 + expected_open)
            assert loop.open(s) == pytest.approx(expected_open, rel=1e-9), (loop.name, omega)
            assert loop.closed(s) == pytest.approx(expected_closed, rel=1e-9), (loop.name, omega)


def test_every_crossover_has_unit_magnitude_and_none_is_missed(benchmark):
    loops = whipple.HumanController("lateral", benchmark_table().at(5.0).gains).loops(benchmark,
                                                                                       5.0)
    omega = np.logspace(-2, 2, 20001)
    for loop in loops:
        magnitude = np.abs(loop.open(1j * omega))
        np.testing.assert_allclose(np.abs(loop.open(1j * loop.crossovers)), 1.0, rtol=1e-9)
        changes = np.flatnonzero(np.diff(np.sign(magnitude - 1.0)))
        assert len(changes) == len(loop.crossovers), loop.name
        np.testing.assert_allclose(omega[changes], loop.crossovers, rtol=1e-3)
    # HumanControl tuned φ, ψ, y to cross over at 2, 1 and 0.5 rad/s.
    np.testing.assert_allclose([l.crossover for l in loops[2:]], [2.0, 1.0, 0.5], rtol=0.02)


def test_hess_gains_meet_the_rules(benchmark):
    gains = whipple.hess_gains(benchmark, 5.0)
    # HumanControl's BenchmarkSteerGains.txt at 5 m/s.
    np.testing.assert_allclose(gains, [46.5457, -0.0522, 12.6611, 0.1849, 0.0959], rtol=0.03)
    loops = whipple.HumanController("lateral", gains).loops(benchmark, 5.0)
    np.testing.assert_allclose([l.crossover for l in loops[2:]], [2.0, 1.0, 0.5], rtol=1e-9)
    # The steer and roll-rate loops' closed-loop pairs at the rules' damping ratios.
    for loop, zeta in zip(loops[:2], (0.1289, 0.0855)):
        poles = np.roots(loop.closed.denominator)
        poles = poles[poles.imag > 1e-6]
        assert np.min(np.abs(-poles.real / np.abs(poles) - zeta)) < 1e-8, loop.name
    with pytest.raises(whipple.WhippleError, match="no `kDelta` meets its rule"):
        whipple.hess_gains(benchmark, 5.0, neuro_frequency=0.5)
