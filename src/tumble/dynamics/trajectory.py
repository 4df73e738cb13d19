"""The result of a simulation: a sampled rigid-body motion and what it conserves."""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from .euler import angular_momentum, kinetic_energy

__all__ = ["Trajectory"]


def _array(a) -> np.ndarray:
    # writeable on purpose: scipy's Rotation.apply refuses read-only arrays (see mass.body)
    return np.asarray(a, dtype=float)


@dataclass(frozen=True, eq=False)
class Trajectory:
    """A sampled motion of a rigid body. Frozen; derived quantities are computed once, so
    its arrays must not be modified in place.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Sample times, s.
    omega : ndarray, shape (n, 3)
        Angular velocity in the principal frame, rad/s.
    attitude : scipy.spatial.transform.Rotation, n rotations
        Body (principal) frame to world: ``x_world = attitude[k].apply(x_body)``.
    moments : ndarray, shape (3,)
        Principal moments ``I1 <= I2 <= I3``, kg m^2.
    principal_axes : ndarray, shape (3, 3)
        Principal -> design rotation of the body (columns are the axes in the design frame).
    method : str
        Name of the integration method.
    torque_free : bool
        Whether no external torque acted (then energy, |L| and L_world are conserved).
    body_name : str
        Label of the body.
    """

    t: np.ndarray
    omega: np.ndarray
    attitude: Rotation
    moments: np.ndarray
    principal_axes: np.ndarray
    method: str
    torque_free: bool = True
    body_name: str = "body"

    def __post_init__(self) -> None:
        for name in ("t", "omega", "moments", "principal_axes"):
            object.__setattr__(self, name, _array(getattr(self, name)))

    def __len__(self) -> int:
        return len(self.t)

    @functools.cached_property
    def quat(self) -> np.ndarray:
        """Attitude quaternions ``[x, y, z, w]`` (scalar last), body to world; shape (n, 4)."""
        return _array(self.attitude.as_quat())

    @functools.cached_property
    def angular_momentum(self) -> np.ndarray:
        """``L = I omega`` in the principal frame, kg m^2/s; shape (n, 3)."""
        return _array(angular_momentum(self.omega, self.moments))

    @functools.cached_property
    def angular_momentum_world(self) -> np.ndarray:
        """L in the world frame, kg m^2/s; constant without torque; shape (n, 3)."""
        return _array(self.attitude.apply(self.angular_momentum))

    @functools.cached_property
    def omega_world(self) -> np.ndarray:
        """Angular velocity in the world frame, rad/s; shape (n, 3)."""
        return _array(self.attitude.apply(self.omega))

    @functools.cached_property
    def energy(self) -> np.ndarray:
        """Rotational kinetic energy, J; shape (n,)."""
        return _array(kinetic_energy(self.omega, self.moments))

    @functools.cached_property
    def angular_momentum_norm(self) -> np.ndarray:
        """|L|, kg m^2/s; shape (n,)."""
        return _array(np.linalg.norm(self.angular_momentum, axis=1))

    @functools.cached_property
    def drift(self) -> dict[str, float | None]:
        """Largest relative departure from the initial value over the run.

        ``energy``: max |E - E0| / E0; ``L_norm``: max ||L| - |L0|| / |L0|; ``L_world``:
        max |L_world - L_world(0)| / |L0|. Meaningful as errors only when ``torque_free``.
        None where the initial value is zero (a body starting at rest): no relative drift.
        """
        E, Ln, Lw = self.energy, self.angular_momentum_norm, self.angular_momentum_world

        def rel(dev, ref):
            return float(np.max(dev) / ref) if ref > 0 else None

        return {
            "energy": rel(np.abs(E - E[0]), E[0]),
            "L_norm": rel(np.abs(Ln - Ln[0]), Ln[0]),
            "L_world": rel(np.linalg.norm(Lw - Lw[0], axis=1), Ln[0]),
        }

    def design_attitude(self) -> Rotation:
        """Rotation of the *design* frame to world: ``attitude * principal_axes^T``."""
        return self.attitude * Rotation.from_matrix(self.principal_axes).inv()
