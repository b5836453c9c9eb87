"""`whipple rider-inertia` against the Python package yeadon (Dembia & Moore; from PyPI, in the
test environment only, never a dependency of the package), run here on every rider file the
core's tests ship (BicycleParameters' riders), with the three corrections that
crates/whipple/tests/data/yeadon/expected.py explains and the core's tests check on their own:
every segment's and the whole body's mass, mass centre and inertia to 1e-12 relative."""

import importlib.util
import json
import subprocess

import numpy as np
import pytest

from conftest import DATA, optional

# Required under ci-test (WHIPPLE_PY_REQUIRED=1) unless it could not be installed there.
yeadon = optional("yeadon", module_level=True)

RIDERS = DATA / "yeadon"


def _generator():
    spec = importlib.util.spec_from_file_location("yeadon_expected", RIDERS / "expected.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


CASES = _generator().cases()


def close(got, expected, what):
    got, expected = np.asarray(got, dtype=float).ravel(), np.asarray(expected, dtype=float).ravel()
    scale = np.abs(expected).max()
    worst = np.abs(got - expected).max() / scale
    assert worst < 1e-12, f"{what}: {got} vs {expected} ({worst:.2e})"


@pytest.mark.parametrize(
    "case", CASES, ids=[f"{c['measurements']}-{c['configuration']}" for c in CASES]
)
def test_rider_inertia_agrees_with_yeadon(cli, case):
    args = [cli, "rider-inertia", "--measurements", str(RIDERS / case["measurements"]),
            "--format", "json"]
    if case["configuration"] is not None:
        args += ["--configuration", str(RIDERS / case["configuration"])]
    done = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    ours = json.loads(done.stdout)
    close(ours["body"]["mass_kg"], case["mass"], "mass")
    close(ours["body"]["center_of_mass_m"], case["center_of_mass"], "mass centre")
    close(ours["body"]["inertia_kg_m2"], case["inertia"], "inertia")
    assert [s["name"] for s in ours["segments"]] == [s["name"] for s in case["segments"]]
    for mine, theirs in zip(ours["segments"], case["segments"]):
        name = mine["name"]
        close(mine["mass_kg"], theirs["mass"], f"{name} mass")
        close(mine["center_of_mass_m"], theirs["center_of_mass"], f"{name} mass centre")
        close(mine["orientation"], theirs["orientation"], f"{name} orientation")
        close(mine["local_inertia_kg_m2"], theirs["local_inertia"], f"{name} local inertia")
        close(mine["inertia_kg_m2"], theirs["inertia"], f"{name} inertia")
