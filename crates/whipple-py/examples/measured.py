# %% [markdown]
# # A measured bicycle with its uncertainty
# BicycleParameters' Fisher (Moore 2012; `FisherBenchmark.txt` from BicycleParameters' data set,
# shipped with whipple's tests) carries a standard deviation on every measured parameter:
# whipple propagates it to the critical speeds (first order, exact derivatives) and says which
# parameter matters most.

# %%
import os
from pathlib import Path

import whipple

# The file is in the clone: found from this script's folder, or (in Jupyter, which has no
# __file__) from the working directory, whether that is the examples folder or the clone's root.
here = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
data = Path("crates", "whipple", "tests", "data", "bicycleparameters", "FisherBenchmark.txt")
path = next((d / data for d in (here, *here.parents) if (d / data).is_file()), None)
if path is None:
    raise SystemExit(f"{data} not found above {here}: run this example inside a whipple clone")
fisher = whipple.Bicycle.from_file(path)
print(fisher)
print(fisher.critical_speeds())

# %% Which parameter moves the weave speed most (elasticities, ∂ln v_w / ∂ln p)
s = fisher.sensitivities()
order = sorted(range(len(s.key)), key=lambda i: -abs(s.elasticity_v_w[i]))
for i in order[:5]:
    print(f"{s.key[i]:>5} ({s.symbol[i]}): dv_w/dp = {s.d_v_w[i]:+.4g} m/s per {s.unit[i] or 'unit'}, elasticity {s.elasticity_v_w[i]:+.3f}")
