"""The torque of a magnetic dipole fixed in the body in a magnetic field: a spacecraft's residual moment.

A spacecraft's currents and magnetised parts make a dipole ``m`` (A m^2) fixed in the body; in
the Earth's field ``B`` (T) it feels

``tau = m x B_b``,  ``B_b = R^T B_world(t)``

(N m, principal frame; Wertz, *Spacecraft Attitude Determination and Control*, Reidel 1978,
sec. 17.2.3; Markley & Crassidis, *Fundamentals of Spacecraft Attitude Determination and
Control*, Springer 2014, sec. 3.3.6.3), one of the four classic disturbance torques beside the
gravity gradient, drag and the Sun's pressure. Typical residual moments are 0.1 to 1 A m^2 for a
small satellite and up to tens for a large one; at 3e-5 T they give 1e-6 to 1e-4 N m.

The field is any model of :mod:`tumble.dynamics.environment` (its ``world(t)``, in the run's
world frame): :class:`~tumble.dynamics.environment.magnetic.UniformField`, the tilted
:class:`~tumble.dynamics.environment.magnetic.DipoleField` along a circular orbit, or the full
:class:`~tumble.dynamics.environment.igrf.IGRFField`. ``simulate`` runs it compiled
(:mod:`tumble.dynamics.control.free_loop`: the closed loop's kernel holding the dipole, with the
field's own compiled form), alone or beside the gravity gradient and constant torques.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import FloatArray, Vector3
from ...validation import check_vector
from .torques import AddsTorques

__all__ = ["ResidualDipole"]


@dataclasses.dataclass(frozen=True)
class ResidualDipole(AddsTorques):
    """The torque ``m x (R^T B_world(t))`` of a dipole ``m`` fixed in the body (N m, body frame; module docstring).

    Parameters
    ----------
    dipole : array_like, shape (3,)
        The dipole ``m``, A m^2, principal frame.
    field : magnetic field model
        Gives ``world(t)``: B (T) in the run's world frame at ``t`` (s).

    Examples
    --------
    A dipole of 1 A m^2 along body x in 3e-5 T along world y, the body unturned: 3e-5 N m about z.

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics import ResidualDipole, UniformField
    >>> torque = ResidualDipole((1.0, 0.0, 0.0), UniformField((0.0, 3e-5, 0.0)))
    >>> torque(0.0, np.zeros(3), Rotation.identity()).tolist(), torque.frame
    ([0.0, 0.0, 3e-05], 'body')
    """

    dipole: tuple[float, float, float]
    field: Any
    frame: str = dataclasses.field(default="body", init=False)

    def __post_init__(self) -> None:
        m = check_vector("dipole", self.dipole, "A m^2")
        object.__setattr__(self, "dipole", (float(m[0]), float(m[1]), float(m[2])))
        if not callable(getattr(self.field, "world", None)):
            raise ValueError(f"field = {self.field!r} must give world(t), the field (T) in the world frame: a "
                             "UniformField, DipoleField or IGRFField")
        B = np.asarray(self.field.world(0.0))  # a field of one's own asked once, so a wrong one is named here
        if B.shape != (3,) or B.dtype.kind not in "iuf" or not np.all(np.isfinite(B)):
            raise ValueError(f"field.world(0.0) = {B.tolist()!r} must be 3 finite numbers (T, world frame)")

    def __call__(self, t: float, omega: FloatArray, attitude: Rotation) -> Vector3:
        """Body-frame torque at ``t`` (s), N m (``omega`` unused; ``attitude`` body to world); shape
        (3,), or (N, 3) for N attitudes.

        Examples
        --------
        Turned by 90 degrees about z, the body sees the world's y field along its -x: a dipole along
        x then feels no torque.

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics import ResidualDipole, UniformField
        >>> torque = ResidualDipole((1.0, 0.0, 0.0), UniformField((0.0, 3e-5, 0.0)))
        >>> bool(np.abs(torque(0.0, np.zeros(3), Rotation.from_rotvec([0.0, 0.0, np.pi / 2]))).max() < 1e-20)
        True
        """
        B_body = attitude.inv().apply(np.asarray(self.field.world(float(t)), float))
        return np.asarray(np.cross(np.asarray(self.dipole), B_body), float)
