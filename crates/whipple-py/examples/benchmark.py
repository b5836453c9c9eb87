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
    import matplotlib.pyplot as plt  # the figures need matplotlib (in Jupyter they show inline)

    sweep = bike.eig(np.linspace(0.0, 10.0, 1001))
    ax = sweep.plot()
    ax.set_ylim(-10, 10)
    ax.set_title("benchmark bicycle (Meijaard 2007): eigenvalues against speed")
    plt.savefig(os.path.join(out, "benchmark-eig.png"), dpi=120)
    print("wrote", os.path.join(out, "benchmark-eig.png"))
except ImportError:
    print("matplotlib is not installed: no figure")

# %% [markdown]
# ## Mode shapes, and two bicycles compared
# Each mode's eigenvector, its lean and steer components scaled so the larger is 1 and lean's
# phase is 0: the magnitudes and the phase of steer relative to lean against speed, and the
# components as arrows in the complex plane at 5 m/s. Then the
# benchmark bicycle's eigenvalues beside those of the same bicycle with a 12 cm trail.

# %%
at5 = bike.eig(5.0)
lean5, steer5 = at5.mode_shapes()
for k, mode in enumerate(at5.modes or []):
    if at5.values[k].imag < 0:
        continue  # the weave's conjugate: the same magnitudes, the phase negated
    print(f"{mode:>10} at 5 m/s: |steer/lean| = {abs(steer5[k] / lean5[k]):.4f}, phase of steer "
          f"relative to lean {np.degrees(np.angle(steer5[k])):+7.2f} deg")

# %% Mode shapes, phasors and the comparison (matplotlib)
try:
    import matplotlib.pyplot as plt

    shapes = bike.eig(np.linspace(0.0, 10.0, 201))
    shapes.plot_vectors()
    plt.savefig(os.path.join(out, "benchmark-mode-shapes.png"), dpi=110)
    shapes.plot_phasors(5.0)
    plt.savefig(os.path.join(out, "benchmark-phasors.png"), dpi=110)
    longer = bike.replace(c=0.12)
    ax = whipple.plot_eigenvalues([bike, longer], np.linspace(0.0, 10.0, 201),
                                  labels=["benchmark (c = 0.08 m)", "trail c = 0.12 m"])
    ax.set_ylim(-10, 10)
    plt.savefig(os.path.join(out, "benchmark-compared.png"), dpi=110)
    for name in ("benchmark-mode-shapes.png", "benchmark-phasors.png", "benchmark-compared.png"):
        print("wrote", os.path.join(out, name))
except ImportError:
    print("matplotlib is not installed: no figure")
