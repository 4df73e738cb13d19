"""
Montgomery's phase
==================

After one period of the body-frame motion, ``L`` is back where it was in the body, but the body
has turned about the fixed ``L_world`` by an angle that is not 0. Montgomery (1991) gave it in
closed form, ``Delta theta = 2 E T / |L| - Omega (mod 2 pi)``, with ``Omega`` the solid angle the
polhode encloses: a geometric phase. Here the closed form against the rotation measured on a
simulated run, for spins that start ever closer to the intermediate axis.
"""

import matplotlib.pyplot as plt
import numpy as np

import tumble
from tumble.analysis import montgomery_angle, period, rotation_per_period

body = tumble.t_handle()
wobbles = np.array([0.05, 0.2, 0.5, 1.0, 2.0])  # rad/s about the minor axis
closed, measured = [], []
for wobble in wobbles:
    omega0 = [wobble, 10.0, 0.1]  # rad/s, near the intermediate axis
    T = float(period(omega0, body.principal_moments))  # s, one body-frame period
    traj = tumble.simulate(body, omega0, times=[0.0, T])  # the exact solution at 0 and T
    closed.append(float(montgomery_angle(omega0, body.principal_moments)) % (2 * np.pi))
    measured.append(rotation_per_period(traj, T))
    print(f"wobble {wobble:4.2f} rad/s: closed form {closed[-1]:.6f} rad, measured {measured[-1]:.6f} rad")

# %%
# The closed form and the measured rotation per period, wobble by wobble.

fig, ax = plt.subplots(layout="constrained")
ax.plot(wobbles, closed, "x", markersize=12, label="closed form (Montgomery 1991)")
ax.plot(wobbles, measured, "o", label="measured on the run")
ax.set(xlabel="initial rate about the minor axis, rad/s", ylabel="rotation per period, rad (mod 2 pi)")
ax.legend()
plt.show()
