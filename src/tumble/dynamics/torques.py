"""External torques about the centre of mass.

A torque model is called as ``model(t, omega, attitude) -> tau`` with ``t`` in s, ``omega`` the
principal-frame angular velocity (rad/s, shape (3,)) and ``attitude`` a scipy ``Rotation``
(principal body frame to world); it returns a torque in N m, shape (3,), in the frame named by
its ``frame`` attribute: ``"body"`` (the principal frame) or ``"world"``. A plain Python
callable is taken as a body-frame torque.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..mass._checks import check_vector

__all__ = ["ConstantTorque", "FunctionTorque", "as_torque"]

TORQUE_FRAMES = ("body", "world")


def _check_frame(frame: str) -> str:
    if not isinstance(frame, str) or frame not in TORQUE_FRAMES:
        raise ValueError(f"torque frame = {frame!r} is not allowed; allowed: body, world")
    return frame


@dataclass(frozen=True)
class ConstantTorque:
    """A constant torque vector (N m), fixed in the body or in the world frame.

    A constant *body-frame* torque models a thruster fixed to the body; a constant
    *world-frame* torque changes L at a constant rate, ``dL_world/dt = tau``.
    """

    vector: tuple[float, float, float]
    frame: str = "body"

    def __post_init__(self) -> None:
        object.__setattr__(self, "vector", check_vector("torque vector", self.vector, "N m"))
        _check_frame(self.frame)

    def __call__(self, t, omega, attitude) -> np.ndarray:
        return np.array(self.vector)


@dataclass(frozen=True)
class FunctionTorque:
    """Wraps ``fn(t, omega, attitude) -> tau`` with the frame its result is expressed in."""

    fn: Callable
    frame: str = "body"

    def __post_init__(self) -> None:
        if not callable(self.fn):
            raise ValueError(f"torque = {self.fn!r} is not callable")
        _check_frame(self.frame)

    def __call__(self, t, omega, attitude) -> np.ndarray:
        return np.asarray(self.fn(t, omega, attitude), dtype=float)


def as_torque(torque):
    """``None``, a torque model, or a plain callable (body frame) -> a model or None."""
    if torque is None:
        return None
    if hasattr(torque, "frame") and callable(torque):
        _check_frame(torque.frame)
        return torque
    return FunctionTorque(torque, "body")
