"""
A stability map
===============

Which bodies flip, and how often? For a spin of 10 rad/s about the intermediate axis with
0.01 rad/s about each of the others, the exact flip interval over the whole triangle of
inertia ratios ``(I1/I3, I2/I3)`` (physical bodies: ``I1 <= I2 <= I3`` and ``I1 + I2 >= I3``).
Near the edges ``I2 = I1`` or ``I2 = I3`` the body is nearly symmetric and the flips slow down
without bound; the seed's T-handle is marked.
"""

import numpy as np

import tumble
from tumble.ensemble import stability_map
from tumble.viz import figure_stability_map

handle = tumble.t_handle().principal_moments  # kg m^2
ratios = (handle[0] / handle[2], handle[1] / handle[2])
perturbation = (0.01 / 10.0, 0.01 / 10.0)  # 0.01 rad/s about each other axis, as fractions of the spin
grid = stability_map(10.0, perturbation, resolution=120)
interval = grid.flip_interval[grid.inside]
print(f"{grid.inside.sum()} physical bodies on the grid; flip interval {np.nanmin(interval):.2f} to {np.nanmax(interval):.1f} s")
print(f"the T-handle at I1/I3 = {ratios[0]:.3f}, I2/I3 = {ratios[1]:.3f}: "
      f"{float(tumble.flip_interval([0.01, 10.0, 0.01], handle)):.3f} s")

# %%
# The map, with the T-handle marked.

fig = figure_stability_map(10.0, perturbation, resolution=120, points={"T-handle": ratios})
