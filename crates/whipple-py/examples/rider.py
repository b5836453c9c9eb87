# %% [markdown]
# # A simulation with a Python rider
# Below its weave speed (4.29 m/s) the benchmark bicycle falls hands free. A rider who steers
# into the lean — a proportional-derivative controller written in Python, called by the
# non-linear model at every stage of every RK4 step — holds it up at 3 m/s.

# %%
import os

import numpy as np

import whipple

out = os.environ.get("WHIPPLE_EXAMPLES_OUT", ".")
bike = whipple.Bicycle.preset("benchmark")

# %% Hands free: it falls
free = bike.simulate(3.0, 10.0, lean_rate=0.5)
print("hands free:", free.outcome)


# %% A rider in Python: steer torque from lean and lean rate
def rider(t: float, state: dict[str, float]) -> float:
    return 10.0 * state["lean"] + 20.0 * state["lean_rate"]


held = bike.simulate(3.0, 10.0, lean_rate=0.5, steer_torque=rider)
print("with the rider:", held.outcome, f"(largest lean after 5 s: {np.degrees(np.abs(held.lean[held.t > 5]).max()):.3f} deg)")

# %% Plot (matplotlib) and a table (pandas)
try:
    import matplotlib.pyplot as plt  # the figures need matplotlib (in Jupyter they show inline)

    held.plot()
    plt.savefig(os.path.join(out, "rider.png"), dpi=120)
    print("wrote", os.path.join(out, "rider.png"))
except ImportError:
    print("matplotlib is not installed: no figure")
try:
    print(held.to_pandas()[["t", "lean", "steer", "speed"]].iloc[::2000])
except ImportError:
    print("pandas is not installed: no table")
