# %% [markdown]
# # Steady turns of the benchmark bicycle
# Circular motions of the non-linear benchmark bicycle (Meijaard et al. 2007): a turn held by a
# steer torque at a given speed and lean, its stability, the hands-free turns that branch from
# straight running at the capsize speed (Basu-Mandal, Chatterjee & Papadopoulos 2007, Proc. R.
# Soc. A 463:1983–2003), and a simulation started on a turn. Run it as a script or open it in
# Jupyter (percent format). Figures go to the working directory (or $WHIPPLE_EXAMPLES_OUT).

# %%
import math
import os

import numpy as np

import whipple

out = os.environ.get("WHIPPLE_EXAMPLES_OUT", ".")
bike = whipple.Bicycle.preset("benchmark")

# %% A held turn: 5 m/s, leaning 11.5° right (`whipple turn --speed 5 --lean 11.5`)
turn = bike.turn(5.0, lean=math.radians(11.5))
print(turn)

# %% The same circle asked for by its radius, and its mirror image
print("by radius: lean", math.degrees(bike.turn(5.0, radius=turn.rear_radius).lean), "deg")
left = bike.turn(5.0, lean=-math.radians(11.5))
print("left turn: steer", math.degrees(left.steer), "deg, torque", left.steer_torque, "N m")

# %% A turn that cannot be ridden is an error, not an approximate answer
try:
    bike.turn(8.0, radius=0.05)
except whipple.NoSteadyTurnError as error:
    print("no such turn:", error)

# %% The families of hands-free turns (`whipple turns`)
turns = bike.turns(max_speed=12.0)
print(turns)
print("capsize speed of the linear model:", bike.critical_speeds().v_c, "m/s")
for t in bike.hands_free_turns(8.0):
    print(f"hands-free at 8 m/s: lean {math.degrees(t.lean):+.3f} deg, steer "
          f"{math.degrees(t.steer):+.3f} deg, radius {t.rear_radius:+.3f} m, "
          f"{'stable' if t.stable else 'unstable'}")

# %% A simulation that starts on the held turn (`whipple simulate --from-turn`)
run = bike.simulate(5.0, 2.0, lean=math.radians(11.5), from_turn=True)
print(run)
print("lean drift over 2 s:", float(np.max(np.abs(run.lean - turn.lean))), "rad")

# %% Figures (matplotlib)
try:
    import matplotlib.pyplot as plt  # the figures need matplotlib (in Jupyter they show inline)

    axes = turns.plot()
    plt.savefig(os.path.join(out, "turns.png"), dpi=110)
    print("wrote", os.path.join(out, "turns.png"))
except ImportError:
    print("matplotlib is not installed: no figure")
