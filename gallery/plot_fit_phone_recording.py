"""
Fitting a phone recording
=========================

Toss a phone about its intermediate axis while an app records the gyroscope, and the tumble
gives away its ratios of inertia. The recording here is synthetic (a 15 x 7.5 x 0.8 cm box,
true ratios ``I1/I3 = 0.2023, I2/I3 = 0.8023``, with a gyroscope's noise, bias and jitter; its
header says how it was made); its first 6 s are fitted with the exact torque-free motion.
"""

from importlib.resources import files

import tumble
from tumble.io.gyrodata import read_gyro_csv
from tumble.viz import figure_recording

t, omega = read_gyro_csv(files("tumble") / "examples" / "data" / "phone_toss.csv")  # s, rad/s
keep = t < 6.0
fit = tumble.fit_recording(t[keep], omega[keep])
ratios, std = fit.pooled.ratios, fit.pooled.ratios_std
print(f"I1/I3 = {ratios[0]:.4f} +- {std[0]:.4f}, I2/I3 = {ratios[1]:.4f} +- {std[1]:.4f} "
      f"(true 0.2023, 0.8023) from {fit.tosses_used} flight(s)")

# %%
# The recording and the fitted flights, drawn by ``figure_recording``.

fig = figure_recording(fit)
