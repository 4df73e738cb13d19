"""
An object's whole inertia tensor from throws with a flywheel
============================================================

A small device (a flight controller logging its gyroscope and accelerometer at 4 kHz, and a
flywheel a motor spins up from the moment of release) is strapped to an object and thrown. The
rotor's reaction torque, with its calibrated inertia, fixes the absolute scale that a free tumble
alone cannot give: the gyrostat's Euler equations then yield all six entries of the tensor in
kg m^2 (the setting of Blaha, Kuijper, Pop & Smeur, arXiv:2503.13137). The throws here are
synthetic, as the real device logs them (:mod:`tumble.analysis.tensor.synthetic`: a hand-held
swing, the fingers' last touch, the firmware's rotor schedule of idle, spin-up to ~1300 rad/s and
brake, the log ending in flight; the gyroscope's scale, misalignment, noise, bias and range, the
rotor's axis off its nominal, the accelerometer's jolts and smoothing, the air's drag). First the
device is calibrated (`tumble calibrate`): throws of the device alone and with a proof body of
known tensor give the rotor's inertia, the device's tensor and its centre of mass. Then an
object, a 0.482 kg box 16 x 9 x 4 cm turned against the sensor's axes and off its centre, is
thrown four times (`tumble tensor`).
"""

# %%
# Calibrating the device
# ----------------------
# Throws of the device alone and with the proof body give the rotor's inertia, the device's tensor
# and its centre of mass (``tumble calibrate DEVICE.toml --alone ... --proof ...``).

import numpy as np

import tumble
from tumble.analysis.tensor import Device
from tumble.analysis.tensor.synthetic import box, combine, synthetic_throw, true_device, true_proof
from tumble.viz.tensor import figure_tensor

# the device as its file gives it: mass (kg) and the rotor's axis in the sensor frame
device_file = Device(mass=0.10067, rotor_axis=[0.0, 0.0, -1.0])
truth = true_device()  # the synthetic device's true mass properties (rotor included)
proof, proof_on_device = true_proof()  # the proof body (0.346 kg) and where it sits on the device
# the device alone is light and thrown gently: its rotor's spin-up turns it by ~30 rad/s
alone = [synthetic_throw(seed, truth, spin=(3.0, 8.0)) for seed in (1, 2, 3)]
with_proof = [synthetic_throw(seed, combine(truth, proof_on_device)) for seed in (11, 12, 13)]
device = tumble.calibrate_device(device_file, alone, with_proof, proof)
print(f"rotor inertia {device.rotor_inertia:.4g} +- {device.rotor_inertia_std:.2g} kg m^2 (true 1.7e-06); "
      f"device centre of mass {np.round(1e3 * device.center_of_mass, 2).tolist()} mm "
      f"(true {np.round(1e3 * truth.center, 2).tolist()})")

# %%
# The object
# ----------
# Four throws of the box with the calibrated device (``tumble tensor ... --device ... --mass``):
# each throw's rates against the fitted model, and each principal moment per throw with the pooled
# value and its 95 % interval.

bracket = box(0.482, (0.16, 0.09, 0.04), center=(0.012, -0.008, 0.035), rotvec=(0.2, -0.1, 0.35))
throws = [synthetic_throw(seed, combine(truth, bracket)) for seed in (21, 22, 23, 24)]
fit = tumble.fit_tensor(throws, device, bracket.mass)
true_moments = np.linalg.eigvalsh(bracket.inertia)
for k, (I, s, true) in enumerate(zip(fit.object.principal_moments, fit.object.principal_moments_std, true_moments)):
    print(f"I{k + 1} = {I:.5g} +- {s:.2g} kg m^2 (true {true:.5g}, {100 * (I / true - 1):+.2f} %)")

fig = figure_tensor(fit)
