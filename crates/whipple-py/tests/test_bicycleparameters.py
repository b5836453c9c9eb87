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


def _benchmark_files():
    """Every bicycle of the data set in the benchmark form: BicycleParameters' <Name>Benchmark.txt
    (both copies) and benchmark YAML sets; the rider's file (a rider alone) is not a bicycle."""
    files = sorted((DATA / "bicycleparameters").glob("*Benchmark.txt"))
    files += sorted((DATA / "bicycleparameters-full").glob("*Benchmark.txt"))
    files += sorted((DATA / "bicycleparameters-yaml").glob("benchmark-*.yml"))
    return [f for f in files if f.name != "JasonBrowserBenchmark.txt"]


# The keys of Moore 2012's tensor entries, by body, whose tolerance is the body's largest moment
# (a product or a turned moment can be far smaller than the tensor it comes from).
_MOORE_TENSORS = {"c": ("ic11", "ic22", "ic31", "ic33"), "e": ("ie11", "ie22", "ie31", "ie33")}


def _moore_close(mine, theirs, key):
    scale = abs(theirs[key])
    for keys in _MOORE_TENSORS.values():
        if key in keys:
            scale = max(abs(theirs[k]) for k in keys)
    if key in ("l1", "l2", "l3", "l4", "d1", "d2", "d3"):
        scale = max(scale, abs(theirs["d1"]))
    return abs(mine - theirs[key]) <= 1e-12 * scale


@pytest.mark.parametrize("path", _benchmark_files(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_moore2012_equals_bicycleparameters_conversion(path):
    """Bicycle.to_moore2012 equals BicycleParameters' own conversion,
    Meijaard2007ParameterSet.to_parameterization('Moore2012') (dtk's benchmark_to_moore), to
    1e-12 relative (a tensor entry relative to its body's largest moment, a length to d1), for
    every benchmark-form bicycle of the data set; and from_moore2012 of BicycleParameters'
    numbers gives the same 26 benchmark numbers back to 1e-12."""
    from bicycleparameters.parameter_sets import Meijaard2007ParameterSet

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        bike = whipple.Bicycle.from_file(path)
    benchmark = bike.to_dict()
    theirs = Meijaard2007ParameterSet({**benchmark, "v": 1.0}, True).to_parameterization(
        "Moore2012").parameters
    theirs = {k: float(v) for k, v in theirs.items()}
    mine = bike.to_moore2012()
    assert len(mine) == 26
    for key, value in mine.items():
        assert _moore_close(value, theirs, key), (key, value, theirs[key])
    # Their extra keys are the redundant ones whipple's YAML reader checks, and v.
    assert set(theirs) - set(mine) == {"ic12", "ic23", "ie12", "ie23", "id33", "if33", "v"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", whipple.ParameterWarning)
        back = whipple.Bicycle.from_moore2012(
            {k: theirs[k] for k in list(mine) + ["v"]}).to_dict()
    tensors = {"B": ("IBxx", "IBzz", "IBxz"), "H": ("IHxx", "IHzz", "IHxz")}
    for key, value in benchmark.items():
        scale = abs(value)
        for keys in tensors.values():
            if key in keys:
                scale = max(abs(benchmark[k]) for k in keys)
        if key in ("xB", "zB", "xH", "zH", "c"):
            scale = max(scale, benchmark["w"])
        assert abs(back[key] - value) <= 1e-12 * scale, (key, back[key], value)


def test_front_assembly_steer_inertia_identity():
    """I_Aλλ computed from a bicycle, entered as IAlamlam instead of IHzz, gives the bicycle
    back; it equals the canonical mass matrix's steer entry; an impossible one is refused."""
    import math

    bike = whipple.Bicycle.preset("benchmark")
    i_a = bike.front_assembly_steer_inertia()
    d = bike.to_dict()
    # By parts: each body's own moment about the parallel axis, plus mass times distance².
    s, c = math.sin(d["lam"]), math.cos(d["lam"])

    def distance(x, z):
        return (x - d["w"] - d["c"]) * c - z * s

    parts = (d["IFxx"] + d["mF"] * distance(d["w"], -d["rF"]) ** 2
             + d["mH"] * distance(d["xH"], d["zH"]) ** 2
             + d["IHxx"] * s * s + 2 * d["IHxz"] * s * c + d["IHzz"] * c * c)
    assert i_a == pytest.approx(parts, rel=1e-13)
    ihzz = d.pop("IHzz")
    again = whipple.Bicycle.from_dict({**d, "IAlamlam": i_a})
    assert again.to_dict()["IHzz"] == pytest.approx(ihzz, rel=1e-12)
    assert any(n["field"] == "IHzz" and "IAlamlam" in n["message"] for n in again.notices)
    with pytest.raises(whipple.ParameterError) as error:
        whipple.Bicycle.from_dict({**d, "IAlamlam": -0.1})
    assert error.value.field == "IAlamlam" and "must not be negative" in str(error.value)
    with pytest.raises(whipple.ParameterError) as error:
        whipple.Bicycle.from_dict({**d, "IAlamlam": 0.01})
    assert "the least the front assembly can have" in str(error.value)
