"""BicycleParameters' linearized rider-lean model, pinned for `cargo test`
(crates/whipple/tests/data/rider_lean_references.json).

Moore 2012's Whipple bicycle with a leaning rider (the rider's upper body G hinged to the rear
frame about its roll axis) as BicycleParameters ships it: `MooreRiderLean2012Model`, whose
linear equations were generated from the Autolev source of Moore's dissertation
(moorepants/dissertation, src/extensions/lean/RiderLean.al), evaluated for the parameter set
`mooreriderlean2012_browser_jason` (the Browser with Jason's legs in the rear frame C and his
upper body as G) at several speeds, with the hinge free (k9 = c9 = 0, as the set gives it) and
with Moore's stiff, damped hinge (k9 = 128 N m/rad, c9 = 50 N m s/rad, riderlean.py).

Nothing of whipple runs here. Run it once in a throw-away virtual environment, from the
repository root:

    python3 -m venv /tmp/bpvenv && /tmp/bpvenv/bin/pip install bicycleparameters
    /tmp/bpvenv/bin/python bench/rider_lean_references.py \
        crates/whipple/tests/data/rider_lean_references.json

The output is JSON: the parameter set (every key as BicycleParameters holds it, the speed `v`
left out), the state and input names in BicycleParameters' order (states q1 q2 q3 q4 q6 q7 q8
q9 u4 u6 u7 u9, inputs T4 T7 T9; Moore's signs: z down, roll q4 and lean q9 about the forward
axis, steer q7 about the steer axis pointing down, u6 = −v/rr the rear wheel's rate), and
for each case and speed A (12 × 12) and B (12 × 3) as nested lists, every float as Python's
round-trip repr.
"""

import json
import sys

import bicycleparameters
from bicycleparameters.models import MooreRiderLean2012Model
from bicycleparameters.parameter_dicts import mooreriderlean2012_browser_jason
from bicycleparameters.parameter_sets import MooreRiderLean2012ParameterSet

SPEEDS = [0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0]
CASES = [
    ("free hinge", {}),
    ("stiff, damped hinge (riderlean.py)", {"k9": 128.0, "c9": 50.0}),
]


def main():
    out_path = sys.argv[1] if len(sys.argv) > 1 else \
        "crates/whipple/tests/data/rider_lean_references.json"
    par = dict(mooreriderlean2012_browser_jason)
    model = MooreRiderLean2012Model(MooreRiderLean2012ParameterSet(par))
    cases = []
    for name, overrides in CASES:
        rows = []
        for v in SPEEDS:
            a, b = model.form_state_space_matrices(v=v, **overrides)
            rows.append({"v": v, "A": a.tolist(), "B": b.tolist()})
        cases.append({"name": name, "overrides": overrides, "speeds": rows})
        print(f"{name}: {len(rows)} speeds")
    doc = {
        "generated_by": "bench/rider_lean_references.py (BicycleParameters "
                        f"{bicycleparameters.__version__}, MooreRiderLean2012Model; "
                        "BSD-2-Clause)",
        "parameter_set": "mooreriderlean2012_browser_jason",
        "parameters": {k: x for k, x in par.items() if k != "v"},
        "states": MooreRiderLean2012Model.state_vars,
        "inputs": MooreRiderLean2012Model.input_vars,
        "cases": cases,
    }
    with open(out_path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"written to {out_path}")


if __name__ == "__main__":
    main()
