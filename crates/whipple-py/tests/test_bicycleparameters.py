"""Against BicycleParameters (Moore; from PyPI, in the test environment only, never a
dependency of the package) on the same bicycles: its canonical matrices and eigenvalues, and
its own objects read through Bicycle.from_bicycleparameters."""

import os
import shutil
import warnings

import numpy as np
import pytest

import whipple
from conftest import DATA, optional

# Required under ci-test (WHIPPLE_PY_REQUIRED=1): missing, the run fails here rather than
# skipping these cross-checks unseen.
bp = optional("bicycleparameters", module_level=True)

NAMES = ["Benchmark", "Fisher", "Pista", "Crescendo", "Browser", "Silver", "Yellow", "Rigid"]
SPEEDS = np.linspace(0.0, 10.0, 41)


@pytest.fixture(scope="module")
def data_dir(tmp_path_factory):
    """BicycleParameters' data layout (bicycles/<Name>/Parameters/<Name>Benchmark.txt) around
    the files shipped with the core's tests."""
    root = tmp_path_factory.mktemp("bp-data")
    for name in NAMES:
        target = root / "bicycles" / name / "Parameters"
        target.mkdir(parents=True)
        shutil.copy(DATA / "bicycleparameters" / f"{name}Benchmark.txt", target)
    return root


def load(data_dir, name):
    cwd = os.getcwd()
    try:
        os.chdir(data_dir)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return bp.Bicycle(name, pathToData=str(data_dir))
    finally:
        os.chdir(cwd)


def ours(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        return whipple.Bicycle.from_file(DATA / "bicycleparameters" / f"{name}Benchmark.txt")


@pytest.mark.parametrize("name", NAMES)
def test_canonical_matrices(data_dir, name):
    theirs = load(data_dir, name).canonical(nominal=True)
    for a, b in zip(ours(name).canonical(), theirs):
        assert np.allclose(a, np.asarray(b, dtype=float), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_eigenvalues(data_dir, name):
    values, vectors = load(data_dir, name).eig(SPEEDS)
    mine = ours(name).eig(SPEEDS)
    assert mine.values.shape == values.shape and mine.vectors.shape == vectors.shape
    for i in range(len(SPEEDS)):
        a, b = np.sort_complex(mine.values[i]), np.sort_complex(np.asarray(values[i]))
        assert np.allclose(a, b, rtol=1e-9, atol=1e-9), SPEEDS[i]


@pytest.mark.parametrize("name", NAMES)
def test_from_bicycleparameters_object(data_dir, name):
    theirs = load(data_dir, name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        mine = whipple.Bicycle.from_bicycleparameters(theirs)
    file = ours(name)
    for key, value in file.to_dict().items():
        assert mine.to_dict()[key] == pytest.approx(value, rel=1e-14, abs=1e-15), key
    for key, s in mine.sigma.items():
        assert s >= 0.0
    s = mine.critical_speeds()
    assert s.uncertain == bool(mine.sigma) and (s.v_w is None or s.v_w > 0)


def test_parameter_set(benchmark):
    from bicycleparameters.parameter_sets import Meijaard2007ParameterSet

    ps = Meijaard2007ParameterSet({**benchmark.to_dict(), "v": 5.0}, True)
    mine = whipple.Bicycle.from_bicycleparameters(ps)
    assert mine.to_dict() == benchmark.to_dict()
    # Its operating speed `v` is kept as a key the Whipple parameters do not hold.
    assert [e["key"] for e in mine.extras] == ["v"] and mine.extras[0]["value"] == 5.0


def test_principal_set_equals_bicycleparameters_conversion():
    """A set in the principal parameterization (Moore 2019), read by whipple (converted to the
    benchmark form on reading) and converted by BicycleParameters' own
    Moore2019ParameterSet.to_parameterization('Meijaard2007'): the same 25 numbers and g to
    1e-12 relative."""
    import yaml
    from bicycleparameters.parameter_sets import Moore2019ParameterSet

    path = DATA / "bicycleparameters-yaml" / "principal-browserjason.yml"
    with open(path) as f:
        values = yaml.safe_load(f)["values"]
    theirs = Moore2019ParameterSet({k: float(v) for k, v in values.items()}).to_parameterization(
        "Meijaard2007").parameters
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        mine = whipple.Bicycle.from_file(path).to_dict()
    assert len(mine) == 26
    for key, value in mine.items():
        assert value == pytest.approx(float(theirs[key]), rel=1e-12, abs=1e-300), key
