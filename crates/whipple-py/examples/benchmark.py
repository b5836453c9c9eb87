# %% [markdown]
# # The benchmark bicycle reproduced
# Meijaard, Papadopoulos, Ruina & Schwab 2007 (Proc. R. Soc. A 463:1955–1982): the eigenvalues
# of Table 2 and the critical speeds, from Python. Run it as a script or open it in Jupyter
# (percent format). Figures go to the working directory (or $WHIPPLE_EXAMPLES_OUT).

# %%
import os

import numpy as np

import whipple

out = os.environ.get("WHIPPLE_EXAMPLES_OUT", ".")
bike = whipple.Bicycle.preset("benchmark")
print(bike)

# %% The critical speeds: v_d, v_w, v_c and the self-stable range
speeds = bike.critical_speeds()
print(speeds)

# %% Table 2: the eigenvalues at 0, 1, …, 10 m/s
e = bike.eig(np.arange(0.0, 11.0))
for v, lam in zip(e.speeds, e.values):
    print(f"v = {v:4.1f} m/s  " + "  ".join(f"{z.real:+.12f}{z.imag:+.12f}j" for z in lam))

# %% Eigenvalues against speed (matplotlib)
try:
    import matplotlib  # noqa: F401  (the figures need it; in Jupyter they also show inline)

    sweep = bike.eig(np.linspace(0.0, 10.0, 1001))
    ax = sweep.plot()
    ax.set_ylim(-10, 10)
    ax.set_title("benchmark bicycle (Meijaard 2007): eigenvalues against speed")
    ax.figure.savefig(os.path.join(out, "benchmark-eig.png"), dpi=120)
    print("wrote", os.path.join(out, "benchmark-eig.png"))
except ImportError:
    print("matplotlib is not installed: no figure")
