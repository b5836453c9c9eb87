# %% [markdown]
# # Design maps: where is the benchmark bicycle self-stable?
# The certified weave and capsize speeds over a grid of designs around the benchmark bicycle
# (Meijaard et al. 2007), as `whipple map` and `whipple study` compute them: the classic
# one-parameter study of the trail, and a map over trail and head angle. Run it as a script
# or open it in Jupyter (percent format). Figures go to the working directory (or
# $WHIPPLE_EXAMPLES_OUT).

# %%
import os

import numpy as np

import whipple

out = os.environ.get("WHIPPLE_EXAMPLES_OUT", ".")
bike = whipple.Bicycle.preset("benchmark")
print(bike)

# %% One parameter: the trail c from −5 cm to 25 cm
study = bike.design_map("c=-0.05:0.25:121")
print(study)
stable = study.stable_width > 0
print(f"self-stable at some speed for {np.sum(stable)} of {len(study.x)} trails, "
      f"from c = {study.x[stable].min():.3f} m to {study.x[stable].max():.3f} m")

# %% Two parameters: trail and head angle (degrees at the edge, as the command line)
grid = bike.design_map("c=-0.05:0.25:61", "head_angle_deg=60:85:51")
print(grid)
print(f"widest self-stable range: {np.nanmax(grid.stable_width):.3f} m/s")

# %% Figures (matplotlib)
try:
    import matplotlib.pyplot as plt  # the figures need matplotlib (in Jupyter they show inline)

    ax = study.plot()
    ax.set_title("benchmark bicycle: critical speeds against the trail")
    plt.savefig(os.path.join(out, "design-study.png"), dpi=110)
    ax = grid.plot(quantity="stable_width")
    ax.set_title("benchmark bicycle: width of the self-stable range")
    plt.savefig(os.path.join(out, "design-map.png"), dpi=110)
    ax = bike.plot_side_view()
    plt.savefig(os.path.join(out, "side-view.png"), dpi=110)
    for name in ("design-study.png", "design-map.png", "side-view.png"):
        print("wrote", os.path.join(out, name))
except ImportError:
    print("matplotlib is not installed: no figure")
