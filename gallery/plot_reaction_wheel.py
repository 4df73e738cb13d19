"""
A reaction wheel stops the flip
===============================

A wheel in the T-handle's crossbar (its intermediate axis) spinning at 500 rad/s carries
``h = J s = 2.5 kg m^2/s``, more than ``(I3 - I2) W = 1.23 kg m^2/s``: the gyrostat's spin about
that axis is stable and the handle no longer flips. With the wheel stopped (the same mass, now
rigid ballast) the seed's flip returns.
"""

import dataclasses

import numpy as np

import tumble
from tumble.analysis import flip_times
from tumble.viz import figure_omega_panels

wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.03, axis=(1, 0, 0), center=(0, 0, 0.5), spin_rate=500.0)
spinning = tumble.Body([*tumble.t_handle().parts, wheel])
stopped = tumble.Body([*tumble.t_handle().parts, dataclasses.replace(wheel, spin_rate=0.0)])

h = float(np.linalg.norm(spinning.internal_momentum(0.0)))  # kg m^2/s
margin = (spinning.principal_moments[2] - spinning.principal_moments[1]) * 10.0  # (I3 - I2) W
print(f"h = {h:.3f} kg m^2/s > (I3 - I2) W = {margin:.3f} kg m^2/s")

omega0 = [0.1, 10.0, 0.1]  # rad/s, principal frame
runs = {name: tumble.simulate(body, omega0, t_end=10.0, samples=1001)
        for name, body in [("wheel at 500 rad/s", spinning), ("wheel stopped", stopped)]}
flips = {name: len(flip_times(traj.t, traj.omega[:, 1])) for name, traj in runs.items()}
print(flips)

# %%
# omega(t) with the wheel spinning and with it stopped.

fig = figure_omega_panels([(f"{name}: {flips[name]} flips", traj) for name, traj in runs.items()])
