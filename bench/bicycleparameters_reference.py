"""BicycleParameters' own results for every parameter file shipped in whipple's tests.

Run in a throw-away environment (never a dependency of whipple):

    python3 -m venv /tmp/bp && /tmp/bp/bin/pip install bicycleparameters==1.5.2 scipy pyyaml
    /tmp/bp/bin/python bench/bicycleparameters_reference.py > crates/whipple/tests/data/bicycleparameters/reference.json

For each file: BicycleParameters' canonical matrices (bicycleparameters.bicycle.benchmark_par_to_canonical)
and, from its state matrix (bicycle.ab_matrix), the self-stable speed range in 0..20 m/s, the ends
found where the largest real part of its eigenvalues crosses zero (numpy eigenvalues, scipy's
brentq to 1e-14). Benchmark.txt files are read by BicycleParameters' own reader
(io.load_parameter_text_file); HumanControl's Par.txt by MATLAB's rule (str2num of the value,
here Python arithmetic with pi); YAML with PyYAML.
"""
import glob
import json
import math
import os
import sys

import numpy as np
import yaml
from scipy.optimize import brentq

import bicycleparameters as bp
from bicycleparameters import bicycle, io

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "crates", "whipple", "tests", "data")


def nominal(d):
    out = {}
    for k, v in d.items():
        out[k] = float(getattr(v, "nominal_value", v))
    return out


def read_hc(path):
    p = {}
    with open(path, encoding="utf-8-sig") as f:
        for line in f:
            line = line.split("#")[0].strip()
            if not line:
                continue
            k, v = line.split("=", 1) if "=" in line else line.split(",", 1)
            v = v.split("+/-")[0]
            p[k.strip()] = float(eval(v, {"__builtins__": {}}, {"pi": math.pi}))
    return p


def stable_range(p, lo=0.0, hi=20.0, n=4000):
    M, C1, K0, K2 = bicycle.benchmark_par_to_canonical(p)
    g = p["g"]

    def f(v):
        A, _ = bicycle.ab_matrix(M, C1, K0, K2, v, g)
        return max(np.linalg.eigvals(A).real)

    vs = np.linspace(lo, hi, n + 1)
    fs = [f(v) for v in vs]
    ranges = []
    start = None
    for i in range(n):
        if fs[i] >= 0 > fs[i + 1]:
            start = brentq(f, vs[i], vs[i + 1], xtol=1e-14, rtol=1e-15)
        if fs[i] < 0 <= fs[i + 1] and start is not None:
            ranges.append([start, brentq(f, vs[i], vs[i + 1], xtol=1e-14, rtol=1e-15)])
            start = None
    if start is not None:
        ranges.append([start, hi])
    return [np.asarray(M).tolist(), np.asarray(C1).tolist(), np.asarray(K0).tolist(), np.asarray(K2).tolist()], ranges


def main():
    out = {"bicycleparameters": bp.__version__, "files": {}}
    files = []
    for path in sorted(glob.glob(os.path.join(DATA, "bicycleparameters", "*Benchmark.txt"))):
        files.append(("bicycleparameters/" + os.path.basename(path), nominal(io.load_parameter_text_file(path))))
    for path in sorted(glob.glob(os.path.join(DATA, "humancontrol", "*Par.txt"))):
        files.append(("humancontrol/" + os.path.basename(path), read_hc(path)))
    for path in sorted(glob.glob(os.path.join(DATA, "bicycleparameters-yaml", "*.yml"))):
        with open(path) as f:
            d = yaml.safe_load(f)
        if "values" in d:
            if d.get("parameterization") != "benchmark":
                continue
            d = d["values"]
        files.append(("bicycleparameters-yaml/" + os.path.basename(path), {k: float(v) for k, v in d.items()}))
    for name, p in files:
        if "w" not in p:
            continue  # a rider's file, not a bicycle
        p.setdefault("IByy", 0.0)
        p.setdefault("IHyy", 0.0)
        try:
            canonical, ranges = stable_range(p)
        except ZeroDivisionError as e:
            # The two-mass skate's wheels have zero radius; BicycleParameters divides by it.
            out["files"][name] = {"bicycleparameters_error": "ZeroDivisionError: " + str(e)}
            continue
        out["files"][name] = {"M": canonical[0], "C1": canonical[1], "K0": canonical[2], "K2": canonical[3], "stable_speed_ranges": ranges}
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
