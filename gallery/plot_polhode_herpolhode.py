"""
The polhode and the herpolhode
==============================

Poinsot's construction of the torque-free motion. In the body frame the angular momentum ``L``
runs along a polhode: a curve where the momentum sphere (``|L|`` fixed) meets the energy
ellipsoid (``E`` fixed). In the ground frame the tip of ``omega`` rolls over the invariable
plane (normal to the fixed ``L_world``) and draws the herpolhode.
"""

import numpy as np

import tumble
from tumble.viz import figure_herpolhode, figure_polhode

body = tumble.t_handle()
traj = tumble.simulate(body, [0.3, 5.0, 0.2], t_end=6.0, samples=601)  # rad/s, s

# the two invariants that define the polhode, held by the exact solution to round-off
L_norm = np.linalg.norm(traj.angular_momentum, axis=1)
print(f"|L| varies by {np.ptp(L_norm) / L_norm[0]:.1e} (relative), E by {np.ptp(traj.energy) / traj.energy[0]:.1e}")

# %%
# The polhode on the momentum sphere and the herpolhode in the invariable plane.

polhode = figure_polhode(traj, title="L on the momentum sphere: the polhode")
herpolhode = figure_herpolhode(traj, title="omega in the invariable plane: the herpolhode")
