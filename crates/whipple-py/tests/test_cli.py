"""The package against the command line binary on the same inputs: the same library behind
both, so the numbers agree to the last digit the CLI prints (shortest round trip)."""

import io
import json
import subprocess

import numpy as np
import pytest

import whipple
from conftest import DATA


def run(cli, *args):
    done = subprocess.run([cli, *args], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def csv(text):
    lines = text.strip().splitlines()
    header = lines[0].split(",")
    return header, np.array([[float(x) for x in line.split(",")] for line in lines[1:]])


@pytest.mark.parametrize("bike", ["benchmark", "schwinn-crown",
                                  str(DATA / "bicycleparameters" / "FisherBenchmark.txt")])
def test_eig_csv(cli, bike):
    header, rows = csv(run(cli, "eig", "--bike", bike, "--speeds", "0:10:0.25", "--format", "csv"))
    assert header == ["v", "re1", "im1", "re2", "im2", "re3", "im3", "re4", "im4"]
    b = whipple.Bicycle.preset(bike) if "/" not in bike else whipple.Bicycle.from_file(bike)
    e = b.eig(rows[:, 0])
    ours = np.column_stack([e.values.real[:, k // 2] if k % 2 == 0 else e.values.imag[:, k // 2]
                            for k in range(8)])
    assert np.array_equal(ours, rows[:, 1:])


@pytest.mark.parametrize("bike", ["benchmark", "two-mass-skate",
                                  str(DATA / "bicycleparameters" / "FisherBenchmark.txt")])
def test_speeds_json(cli, bike):
    doc = json.loads(run(cli, "speeds", "--bike", bike, "--format", "json"))
    b = whipple.Bicycle.preset(bike) if "/" not in bike else whipple.Bicycle.from_file(bike)
    s = b.critical_speeds()
    assert s.v_d == doc["double_root_speed"]
    assert s.v_w == doc["weave_speed"]
    assert s.v_c == doc["capsize_speed"]
    theirs = [(lo, float("inf") if hi is None else hi) for lo, hi in doc["stable_speed_ranges"]]
    assert s.stable_ranges == theirs
    if "weave_speed_sigma" in doc:
        assert s.v_w_sigma == doc["weave_speed_sigma"]
        assert s.v_c_sigma == doc["capsize_speed_sigma"]
    # to_dict() is the library's record itself: the CLI's (and the server's) keys and values;
    # the σ are there always, None for a bicycle without uncertainties (the CLI leaves them out).
    mine = json.loads(json.dumps(s.to_dict()))
    theirs = {k: v for k, v in doc.items() if k not in ("bike", "warnings")}
    if "weave_speed_sigma" not in doc:
        for key in ("double_root_speed_sigma", "weave_speed_sigma", "capsize_speed_sigma"):
            assert mine.pop(key) is None, key
        assert all(ends == [None, None] for ends in mine.pop("stable_speed_ranges_sigma"))
    assert mine == theirs


def test_simulate_csv(cli, benchmark):
    text = run(cli, "simulate", "--bike", "benchmark", "--speed", "3", "--lean-rate", "0.5",
               "--duration", "1", "--steer-torque", "10*lean + 20*lean_rate", "--format", "csv")
    header, rows = csv(text)
    r = benchmark.simulate(3.0, 1.0, lean_rate=0.5, steer_torque="10*lean + 20*lean_rate")
    assert header == r.csv_columns
    ours = np.column_stack([r.columns[name] for name in header])
    assert ours.shape == rows.shape
    assert np.array_equal(ours, rows)


def test_matrices_json(cli, benchmark):
    doc = json.loads(run(cli, "matrices", "--bike", "benchmark", "--format", "json"))
    m, c1, k0, k2 = benchmark.canonical()
    for name, ours in (("M", m), ("C1", c1), ("K0", k0), ("K2", k2)):
        key = next(k for k in doc if k.lower() == name.lower())
        assert np.array_equal(np.array(doc[key]), ours)
