"""
Explorer 1's flat spin
======================

Explorer 1 (1958), a long thin cylinder, was spun about its long axis: the axis of *least*
moment. Its flexible whip antennas dissipated energy, and within one orbit it was turning end
over end about a major axis. An energy sink with the angular momentum held fixed drives any
spin to the one of least energy, ``|L|^2 / (2 I3)``: here a spherical nutation damper stands for
the antennas (illustrative, far stronger than the real ones), and the run is shortened.
"""

from importlib.resources import files

import numpy as np

import tumble
from tumble.viz import figure_nutation

body = tumble.load_body(files("tumble") / "examples" / "bodies" / "explorer1.toml")
damper = tumble.SphericalDamper(inertia=0.05, damping=0.1)  # kg m^2, N m s
# 750 rpm about the long axis (design z, the minor axis), a small wobble
traj = tumble.simulate(body, [0.05, 0.0, 78.54], frame="design", t_end=30.0, samples=301,
                       method="geometric", step=0.02, damper=damper)

L = np.linalg.norm(traj.angular_momentum_world, axis=1)  # kg m^2/s, conserved
flat = L[-1] / (body.principal_moments[2] + damper.inertia)  # rad/s, the flat spin's rate
print(f"nutation angle {np.degrees(traj.nutation_angle[0]):.1f} deg -> {np.degrees(traj.nutation_angle[-1]):.2g} deg")
print(f"|omega| at the end {np.linalg.norm(traj.omega[-1]):.4f} rad/s, |L| / (I3 + J) = {flat:.4f} rad/s")
print(f"energy {traj.energy[0]:.1f} J -> {traj.energy[-1]:.2f} J, dissipated {traj.dissipated[-1]:.1f} J")

# %%
# The nutation angle growing to the flat spin, drawn by ``figure_nutation``.

fig = figure_nutation(traj)
