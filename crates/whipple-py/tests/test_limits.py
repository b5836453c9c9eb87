"""Large inputs and Ctrl-C: a call too large for the memory raises MemoryError (the interpreter
lives on), a long call stops with KeyboardInterrupt soon after Ctrl-C, and the comparison takes
at most the library's one limit of speeds. Each case runs in a child Python process: under a
memory cap (RLIMIT_AS) for the first, sent SIGINT for the second."""

import os
import queue
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import whipple

linux = pytest.mark.skipif(not sys.platform.startswith("linux"),
                           reason="RLIMIT_AS and /proc/<pid>/stat are Linux's")

PRELUDE = """
import sys, time
import numpy as np
import whipple
bike = whipple.Bicycle.preset("benchmark")
"""

#: The cap of the memory tests: what a notebook on a small machine has.
CAP = 4 << 30


def child(code: str, cap: bool = False) -> subprocess.Popen:
    limit = (f"import resource\nresource.setrlimit(resource.RLIMIT_AS, ({CAP}, {CAP}))\n"
             if cap else "")
    return subprocess.Popen([sys.executable, "-u", "-c", limit + PRELUDE + textwrap.dedent(code)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


# Memory -------------------------------------------------------------------------------------

@linux
@pytest.mark.parametrize("call, says", [
    ("bike.state_space(np.zeros(10**8))", "state_space: 100000000 speeds need"),
    ("bike.eig(np.linspace(0.0, 10.0, 15 * 10**6))", "eig: 15000000 speeds need"),
    ("bike.eig(np.linspace(0.0, 10.0, 2 * 10**7), tracked=False)", "eig: 20000000 speeds need"),
    ("bike.nonlinear_state_matrix(np.zeros(10**8))", "nonlinear_state_matrix: 100000000 speeds"),
    ("bike.frequency_response(np.full(10**6, 5.0), np.ones(10**4))",
     "frequency_responses: 10000000000 points (speeds × pairs × frequencies) need 400000000000 bytes"),
    ("bike.design_map('c=0.0:0.2:100000', 'w=0.9:1.2:100000')",
     "design_map: 10000000000 designs need 670000000000 bytes"),
    ("bike.design_map_shard('c=0.0:0.2:100000', 'w=0.9:1.2:100000', shard=(0, 2))",
     "design_map: 5000000000 designs need 535000000000 bytes"),
])
def test_too_large_raises_memory_error_under_a_cap(call, says):
    p = child(f"""
        try:
            {call}
        except MemoryError as e:
            print("MemoryError:", e)
        else:
            print("no error")
        # The interpreter goes on: a small call still works.
        print(bike.eig(1.0).values.shape)
    """, cap=True)
    try:
        out, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        pytest.fail(f"{call} still running after 120 s under a {CAP >> 30} GiB cap")
    assert p.returncode == 0, (p.returncode, out, err[-2000:])
    assert f"MemoryError: {says}" in out, out
    assert "(4,)" in out, out


# Ctrl-C -------------------------------------------------------------------------------------

def cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def lines_of(p: subprocess.Popen) -> "queue.Queue[str]":
    q: "queue.Queue[str]" = queue.Queue()

    def read():
        for line in p.stdout:
            q.put(line.strip())
        q.put("<eof>")

    threading.Thread(target=read, daemon=True).start()
    return q


def interrupted_within(call: str, busy: float = 0.3) -> float:
    """Starts `call` in a child, waits until the child has spent `busy` s of CPU after saying
    it starts the call (bounded polling: the call is running), sends SIGINT and returns the
    seconds until the child reports KeyboardInterrupt. The child then makes a small design
    map: the module works after an interrupt."""
    p = child(f"""
        print("calling", flush=True)
        try:
            {call}
        except KeyboardInterrupt:
            print("KeyboardInterrupt", flush=True)
        except BaseException as e:
            print("raised", type(e).__name__, e, flush=True)
        else:
            print("finished", flush=True)
        m = bike.design_map("c=0.0:0.2:3")
        print("after", m.v_w.shape, flush=True)
    """)
    try:
        lines = lines_of(p)
        assert lines.get(timeout=60) == "calling"
        start = cpu_seconds(p.pid)
        deadline = time.monotonic() + 60
        while cpu_seconds(p.pid) - start < busy:
            assert time.monotonic() < deadline, "the call did not start"
            # Waits on the child: its end before the signal is a failure.
            try:
                p.wait(timeout=0.01)
            except subprocess.TimeoutExpired:
                continue
            pytest.fail(f"{call}: the child ended before it was interrupted")
        sent = time.monotonic()
        p.send_signal(signal.SIGINT)
        try:
            said = lines.get(timeout=10)
        except queue.Empty:
            pytest.fail(f"{call}: no KeyboardInterrupt 10 s after SIGINT")
        latency = time.monotonic() - sent
        assert said == "KeyboardInterrupt", said
        assert lines.get(timeout=60) == "after (3,)"
        return latency
    finally:
        p.kill()
        p.communicate()


@linux
@pytest.mark.parametrize("call", [
    # The first design map of the process: the interrupt once became a PanicException.
    "bike.design_map('c=0.0:0.2:2000', 'w=0.9:1.2:2000')",
    "bike.eig(np.linspace(0.0, 10.0, 4 * 10**6))",
    "bike.eig(np.linspace(0.0, 10.0, 4 * 10**6), tracked=False)",
    "bike.state_space(np.linspace(0.0, 10.0, 10**7), parallel=False)",
    "bike.nonlinear_state_matrix(np.linspace(0.0, 10.0, 10**6))",
    "bike.frequency_response(np.linspace(0.5, 10.0, 15000), np.logspace(-1, 2, 1000))",
    "bike.compare(np.linspace(0.0, 10.0, 100000))",
    # The closed loop's tracked sweep with eigenvectors, and a loop of order 5 (general).
    "bike.closed_loop([[-100.0, 10.0, -20.0, 0.0]], inputs='steer_torque')"
    ".eig(np.linspace(0.0, 10.0, 4 * 10**6))",
    "bike.closed_loop([[-100.0, 10.0, -20.0, 0.0, 1.0]], inputs='steer_torque', states='yaw')"
    ".eig(np.linspace(0.0, 10.0, 10**6))",
])
def test_ctrl_c_raises_keyboard_interrupt_promptly(call):
    latency = interrupted_within(call)
    # 0.1 s is the aim; the bound leaves room for a loaded machine.
    assert latency < 1.0, f"{call}: KeyboardInterrupt {latency:.2f} s after SIGINT"


# The limit of speeds ------------------------------------------------------------------------

def test_compare_takes_at_most_the_limit_of_speeds(benchmark):
    # The library's limit, the same as the command line's `validate --speeds`; refused before
    # any work (before, 100001 speeds ran for minutes).
    p = child("""
        try:
            bike.compare(np.linspace(0.0, 10.0, 100001))
        except whipple.LimitError as e:
            print("refused:", e)
    """)
    try:
        out, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        pytest.fail("compare of 100001 speeds still running after 60 s")
    assert "refused: v: 100001 speeds is more than the limit of 100000" in out, (out, err)
    assert len(benchmark.compare(np.linspace(1.0, 2.0, 3)).speeds) == 3


def test_a_max_steps_set_too_low_names_max_steps_and_a_sensible_time(benchmark):
    """max_steps=100 for a 1 s run at 1 ms steps named `dt` and "about 0 minutes"."""
    with pytest.raises(whipple.LimitError) as error:
        benchmark.simulate(5.0, 1.0, max_steps=100)
    assert error.value.field == "max_steps"
    message = str(error.value)
    assert "about 2.0 ms" in message and "raise max_steps" in message, message
    assert "0 minutes" not in message
