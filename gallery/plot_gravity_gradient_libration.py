"""
Gravity-gradient libration
==========================

A boom with a tip mass in a circular orbit, started at rest in the orbiting (LVLH) frame and
pitched by 0.05 rad: the gravity-gradient torque ``3 n^2 r_b x (I r_b)`` pulls its long axis
back to the local vertical, and it librates about it. Small pitch oscillations have the period
``2 pi / (n sqrt(3 k_P))`` with ``k_P = (I_roll - I_yaw) / I_pitch`` (Hughes, *Spacecraft
Attitude Dynamics*, ch. 9).
"""

from importlib.resources import files

import numpy as np

import tumble
from tumble.viz import figure_orbit_angles

body = tumble.load_body(files("tumble") / "examples" / "bodies" / "gravity_boom.toml")
gg = tumble.GravityGradient(orbit_period=5400.0)  # s, a low Earth orbit
start = tumble.lvlh_state(gg, body, pitch=0.05, pitch_axis=3, yaw_axis=1)  # rad
traj = tumble.simulate(body, start.omega0, attitude0=start.attitude0, torque=gg,
                       t_end=3 * 5400.0, samples=601, method="dop853")
angles = tumble.orbit_frame_angles(traj, gg, pitch_axis=3, yaw_axis=1)

I1, I2, I3 = body.principal_moments  # yaw (boom, minor), roll, pitch (major)
n = 2 * np.pi / 5400.0  # rad/s, the orbit rate
predicted = 2 * np.pi / (n * np.sqrt(3 * (I2 - I1) / I3))  # s
crossings = traj.t[1:][np.diff(np.sign(angles.pitch)) > 0]  # upward zero crossings of pitch
print(f"pitch within {np.abs(angles.pitch).max():.3f} rad; period measured {np.mean(np.diff(crossings)):.0f} s, "
      f"predicted {predicted:.0f} s")

# %%
# Roll, pitch and yaw against the orbiting frame, drawn by ``figure_orbit_angles``.

fig = figure_orbit_angles(traj, gg, pitch_axis=3, yaw_axis=1)
