"""The absolute inertia tensor of a thrown object, from a device with a rotor (issue #30).

A small device (a flight controller logging its gyroscope and accelerometer at ~4 kHz, and a
flywheel a motor spins up from the moment of release, its speed logged) is fixed to the object
and thrown. The rotor's reaction torque, with its calibrated inertia, fixes the absolute scale
of the tensor that the torque-free motion alone determines only up to a factor (Blaha, Kuijper,
Pop & Smeur, arXiv:2503.13137). Rooms:

- :mod:`~tumble.analysis.tensor.device`: the inputs (:class:`Device`, :class:`Proof`, :class:`Throw`);
- :mod:`~tumble.analysis.tensor.estimate`: :class:`MassEstimate`, principal moments' uncertainty,
  the parallel-axis subtraction;
- :mod:`~tumble.analysis.tensor.fit`: :func:`fit_tensor` (the object from throws);
- :mod:`~tumble.analysis.tensor.calibrate`: :func:`calibrate_device` (the rotor and the device);
- :mod:`~tumble.analysis.tensor.synthetic`: realistic throws for tests and examples.
"""

from .calibrate import calibrate_device
from .device import Device, Proof
from .throwlog import Throw
from .estimate import MassEstimate
from .fit import TensorFit, ThrowFit, fit_tensor
from .pool import NoThrowError

__all__ = ["Device", "MassEstimate", "NoThrowError", "Proof", "TensorFit", "Throw", "ThrowFit", "calibrate_device", "fit_tensor"]
