# %% [markdown]
# # Time responses, feedback and the non-linear check
# The benchmark bicycle as a linear system: a steer-torque pulse simulated exactly, an LQR
# controller (at one speed and scheduled over speed) and a steer-into-the-fall controller with
# their closed-loop eigenvalues and transfer functions, the speeds where steer torque loses a
# mode, and the linear model beside the non-linear one through the same pulse. Run it as a script or open it in Jupyter (percent format). Figures
# go to the working directory (or $WHIPPLE_EXAMPLES_OUT).

# %%
import os

import numpy as np

import whipple

out = os.environ.get("WHIPPLE_EXAMPLES_OUT", ".")
bike = whipple.Bicycle.preset("benchmark")

# %% A 0.5 s pulse of 0.1 N m of steer torque at 5 m/s, and where the bicycle goes
system = bike.linear_system(5.0, "steer_torque", ("lean", "steer"),
                            states=("yaw", "rear_contact_x", "rear_contact_y"))
t = np.linspace(0.0, 5.0, 501)
torque = np.where(t < 0.5, 0.1, 0.0)
run = system.simulate(t, torque)
print(f"largest lean {np.max(np.abs(run.states['lean'])):.4f} rad")
if run.path is not None:
    print(f"after 5 s: x = {run.path.rear_x[-1]:.3f} m, y = {run.path.rear_y[-1]:.4f} m")

# %% LQR at 2 m/s (below the weave speed, unstable uncontrolled)
slow = bike.linear_system(2.0)
lqr = slow.lqr(np.diag([10.0, 1.0, 1.0, 0.1]), np.diag([1.0, 1.0]))
print("LQR gains K:\n", np.round(lqr.K, 3))
print("closed-loop poles:", np.round(lqr.poles, 3))

# %% Steering into the fall: where does the closed loop become stable?
k = np.array([[0.0, 0.0, 0.0, 0.0], [-20.0, 5.0, -3.0, 0.5]])
loop = bike.closed_loop(k)
print("closed-loop stable ranges:", loop.critical_speeds(0.0, 10.0)["stable_speed_ranges"])

# %% An LQR steer controller scheduled over speed: from which speed is it stable?
# One gain per design speed, interpolated between them; the stable range is certified between
# the design speeds too, not sampled.
scheduled = bike.lqr_schedule([0.5, 1.0, 2.0, 4.0, 8.0], np.eye(4), [[1.0]])
assert scheduled.residuals is not None  # set by lqr_schedule
print("largest Riccati residual:", float(scheduled.residuals.max()))
print("scheduled LQR stable ranges:",
      scheduled.critical_speeds(0.5, 8.0)["stable_speed_ranges"])

# %% The steer torque the loop applies, as a transfer function of the closed loop
# r → u is the loop's sensitivity 1/(1 + L); formed exactly from the closed loop's polynomials.
steer_loop = bike.closed_loop([[-100.0, 10.0, -20.0, 0.0]], inputs="steer_torque")
g = steer_loop.system(5.0, ["lean", "steer_torque"]).transfer_function("steer_torque",
                                                                       "steer_torque")
print("closed-loop poles at 5 m/s:", np.round(g.poles, 4))
print("static gain of r → steer torque:", g.static_gain)

# %% Steer torque loses a mode at these speeds (certified)
print(bike.uncontrollable_speeds("steer_torque"))

# %% The linear and non-linear models through the same pulse
both = bike.compare_manoeuvre(5.0, t, steer_torque=(np.array([0.0, 0.5, 0.5, 5.0]),
                                                    np.array([0.1, 0.1, 0.0, 0.0])))
print(f"largest lean difference {np.max(np.abs(both.difference['lean'])):.2e} rad")

# %% Both paths in the plane (matplotlib)
try:
    import matplotlib.pyplot as plt  # the figure needs matplotlib (in Jupyter it shows inline)
except ImportError:
    print("matplotlib is not installed: no figure")
else:
    fig, ax = plt.subplots()
    both.plot_paths(ax)
    fig.savefig(os.path.join(out, "control_paths.png"), dpi=120)
    plt.close(fig)
