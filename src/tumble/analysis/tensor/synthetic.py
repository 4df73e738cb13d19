"""Synthetic throws of the device of issue #30, for tests, examples and the coverage benchmark.

The truth is integrated independently of the fit's model: Euler's equations of the gyrostat in
the angular-velocity form ``I w' = -w x (I w + h) - h' + tau_drag`` (Hughes, *Spacecraft Attitude
Dynamics*, 1986, ch. 7) with ``h' `` from the spin-up law in closed form, by scipy's DOP853 at
``rtol = 1e-12`` (the fit integrates the momentum form with RK4 on the samples).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...typing import ArrayLike, Matrix3, Vector3
from .device import Device, Proof, Throw

__all__ = ["DEVICE_MASS", "ROTOR_AXIS", "ROTOR_INERTIA", "Rigid", "box", "calibrated_device", "combine", "synthetic_throw", "true_device",
           "true_proof"]

#: The device of the issue: mass, kg; rotor axis, sensor frame; rotor inertia, kg m^2.
DEVICE_MASS = 0.10067
ROTOR_AXIS = (0.0, 0.0, -1.0)
ROTOR_INERTIA = 1.7e-6


@dataclass(frozen=True)
class Rigid:
    """A rigid body's true mass properties, sensor frame: mass (kg), tensor about its own centre
    of mass (kg m^2) and the centre's position from the accelerometer (m).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.synthetic import Rigid
    >>> Rigid(1.0, np.eye(3), np.zeros(3)).mass
    1.0
    """

    mass: float
    inertia: Matrix3 = field(repr=False)
    center: Vector3


def box(mass: float, size: ArrayLike, center: ArrayLike, rotvec: ArrayLike = (0.0, 0.0, 0.0)) -> Rigid:
    """A uniform box of ``size`` (m, its own axes) turned by ``rotvec`` (rad) relative to the
    sensor frame, its centre at ``center`` (m).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import box
    >>> callable(box)
    True
    """
    raise NotImplementedError


def combine(*parts: Rigid) -> Rigid:
    """The rigid union of parts (the parallel-axis theorem).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import combine
    >>> callable(combine)
    True
    """
    raise NotImplementedError


def true_device() -> Rigid:
    """The synthetic device's true mass properties (rotor included).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import true_device
    >>> callable(true_device)
    True
    """
    raise NotImplementedError


def true_proof() -> tuple[Proof, Rigid]:
    """The proof body of the issue (0.346 kg) and where it sits on the synthetic device.

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import true_proof
    >>> callable(true_proof)
    True
    """
    raise NotImplementedError


def synthetic_throw(seed: int, flown: Rigid, *, rotor_inertia: float = ROTOR_INERTIA,
                    rotor_axis: ArrayLike = ROTOR_AXIS, input: str = "") -> Throw:
    """A throw's log: hand-held swing, release, 0.5 s flight with the rotor spinning up, catch.

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import synthetic_throw
    >>> callable(synthetic_throw)
    True
    """
    raise NotImplementedError


def calibrated_device(std: float = 0.0) -> Device:
    """The synthetic device as a calibration would give it (true values, ``std`` relative std).

    Examples
    --------
    >>> from tumble.analysis.tensor.synthetic import calibrated_device
    >>> callable(calibrated_device)
    True
    """
    raise NotImplementedError
