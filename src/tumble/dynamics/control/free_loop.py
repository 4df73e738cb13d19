"""Torques the engine's terms do not hold, compiled: the closed loop's kernel with nothing to control.

:func:`tumble.simulate` runs a torque on the compiled engine when the model has a form among the
engine's torque terms (:mod:`tumble.dynamics.engine.kernels`): constant torques and the gravity
gradient of a circular orbit, whose direction the engine turns from stage to stage. Two models
have none there, and the compiled closed loop (:mod:`~tumble.dynamics.control.compiled_loop`)
evaluates both:

- the gravity gradient along a Keplerian or TLE orbit
  (:class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`), whose radius changes
  along the orbit: the loop reads the orbit's position from a table of cubics
  (:func:`~tumble.dynamics.environment.tabulated.position_table`, relative error below 1e-11) and
  takes ``3 mu / r^3 r_b x (I r_b)`` there;
- a dipole fixed in the body in a magnetic field
  (:class:`~tumble.dynamics.models.dipole.ResidualDipole`): the loop's residual dipole, beside
  the magnetorquers' (none here), in the field's own compiled form, ``m x B_b``
  (:func:`~tumble.dynamics.control.loop_terms.external_torque`).

Beside them the loop takes a circular orbit's gravity gradient and constant body and world
torques (its disturbance slots). With no wheels, no magnetorquers and B-dot's law at zero gain,
which commands nothing, that loop is the rigid body alone: DOP853 with scipy's error norm and step control (Hairer, Norsett & Wanner,
*Solving ODEs I*, sec. II.10), each step continuing from the one the last proposed (``carry``)
and ending on every sample time; or the engine's fixed steps, RK4 or RK8, at equal steps in each
sample interval (``method="rk4"``, ``"rk8"``). A body's rotors spinning at constant rates add their
constant momentum to the body's (``rotor_momentum``: the gyrostat, as the engine takes it).

Before, such a run called the model from Python at every stage: ten orbits of an ellipse
(e = 0.1) at 0.1 rad/s took 28 s, against 11 ms for the circle on the engine, and take 27 ms here
(measured 2026-11-30, the kernel cached).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from ...typing import FloatArray
from ..models.dipole import ResidualDipole
from ..models.gravity import GravityGradient
from ..models.orbit_gravity import OrbitGravityGradient
from ..models.torques import TorqueSum
from ._front import locked_inverse
from .control_kernel import ControlKernel, disturbance_form

__all__ = ["FreeTerms", "free_terms", "run_free"]

#: No law (None: the loop's kernel then compiles none, ``compiled_loop._loop``) and no rods: nothing commanded.
_NO_LAW, _NO_RODS, _NO_LIMITS = (None, np.zeros(3), np.zeros((0, 3)), None), np.zeros((0, 3)), np.zeros(0)


class FreeTerms(NamedTuple):
    """A torque's terms for the loop (:func:`free_terms`): its gravity gradient (or None), the
    field of its residual dipoles (or None), and the rest of it (constant torques and those
    dipoles, one torque model or None), which the loop takes as its disturbance
    (:func:`~tumble.dynamics.control.control_kernel.disturbance_form`).

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, ResidualDipole, UniformField
    >>> from tumble.dynamics.control.free_loop import free_terms
    >>> field = UniformField((0.0, 3e-5, 0.0))
    >>> dipole, push = ResidualDipole((0.2, 0.0, 0.0), field), ConstantTorque((0.0, 0.0, 1e-6))
    >>> terms = free_terms(dipole + push)
    >>> terms.gravity_gradient is None, terms.field is field, terms.rest.terms == (dipole, push)
    (True, True, True)
    """

    gravity_gradient: GravityGradient | OrbitGravityGradient | None
    field: Any
    rest: Any


def free_terms(torque: Any) -> FreeTerms | None:
    """The loop's terms of a torque that holds the gravity gradient along a Keplerian or TLE orbit
    or a :class:`~tumble.dynamics.models.dipole.ResidualDipole` (module docstring): at most one
    gravity gradient (a circle's or an orbit's), and the rest, constant body and world torques and
    residual dipoles in one field, as the loop's disturbance takes them
    (:func:`~tumble.dynamics.control.control_kernel.disturbance_form`, the one test of what it
    takes); None for a torque with anything else, a model whose law a subclass changed, or
    neither of the two (the engine's).

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, KeplerOrbit, OrbitGravityGradient, ResidualDipole, UniformField
    >>> from tumble.dynamics.control.free_loop import free_terms
    >>> gg = OrbitGravityGradient(KeplerOrbit(8000e3, 0.1))
    >>> push = ConstantTorque((0.0, 0.0, 1e-6))
    >>> terms = free_terms(gg + push)
    >>> terms.gravity_gradient is gg, terms.field, terms.rest is push
    (True, None, True)
    >>> free_terms(ResidualDipole((0.2, 0.0, 0.0), UniformField((0.0, 3e-5, 0.0))) + gg).field
    UniformField(vector=(0.0, 3e-05, 0.0))
    >>> free_terms(push) is None   # the engine's own
    True
    """
    terms = getattr(torque, "terms", (torque,))
    gravity = [term for term in terms if isinstance(term, (GravityGradient, OrbitGravityGradient))]
    dipoles = [term for term in terms if isinstance(term, ResidualDipole)]
    rest = [term for term in terms if not isinstance(term, (GravityGradient, OrbitGravityGradient))]
    if len(gravity) > 1 or any(g.loop_form() is None for g in gravity) or not (
            dipoles or any(isinstance(g, OrbitGravityGradient) for g in gravity)):
        return None
    field = dipoles[0].field if dipoles else None
    others = TorqueSum(*rest) if len(rest) > 1 else rest[0] if rest else None
    if disturbance_form(others, field) is None:
        return None
    return FreeTerms(gravity[0] if gravity else None, field, others)


def run_free(moments: FloatArray, omega0: FloatArray, quat0: FloatArray, t: FloatArray, torque: Any,
             rtol: float, atol: float | FloatArray, method: str = "dop853",
             step: float | None = None, rotor_momentum: FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    """The body of principal ``moments`` (kg m^2) from ``omega0`` (rad/s, principal frame) and
    ``quat0`` (body to the run's world frame, scalar last) through the samples ``t`` (s,
    increasing, from ``t[0] >= 0``) under ``torque`` (:func:`free_terms`), on the compiled closed
    loop (module docstring): DOP853 at ``rtol`` and ``atol`` (the smallest of an array's), or
    ``method`` ``"rk4"`` or ``"rk8"`` (the classical RK4, DOP853's 8th-order weights) at equal
    steps no longer than ``step`` (s) in each sample interval, the engine's fixed-step rule
    (``rtol`` and ``atol`` unused). ``rotor_momentum``: the constant momentum (kg m^2/s,
    principal frame) of rotors spinning at constant rates relative to the body, whose mass
    ``moments`` hold: the gyrostat ``I omega' = (I omega + h_r) x omega + tau``.

    Returns
    -------
    omega, quat : ndarray, shapes (n, 3) and (n, 4)
        The rate (rad/s) and the unit quaternion at the samples.

    Examples
    --------
    A body with two equal moments, spinning about its axis of symmetry set along the orbit's
    normal: the gradient's torque ``r_b x (I r_b)`` is zero there, so the spin and the axis stay:

    >>> import numpy as np
    >>> from tumble.dynamics import KeplerOrbit, OrbitGravityGradient
    >>> from tumble.dynamics.control.free_loop import run_free
    >>> gg = OrbitGravityGradient(KeplerOrbit(8000e3, 0.2)).bind([1.0, 1.0, 2.0])
    >>> omega, quat = run_free(np.array([1.0, 1.0, 2.0]), np.array([0.0, 0.0, 0.1]),
    ...                        np.array([0.0, 0.0, 0.0, 1.0]), np.linspace(0.0, 600.0, 4), gg, 1e-10, 1e-12)
    >>> bool(np.abs(omega - [0.0, 0.0, 0.1]).max() < 1e-14), bool(np.abs(quat[:, :2]).max() < 1e-14)
    (True, True)

    The same at RK8's fixed steps of at most 1 s; the spin turns the body by 0.1 rad/s:

    >>> omega, quat = run_free(np.array([1.0, 1.0, 2.0]), np.array([0.0, 0.0, 0.1]), np.array([0.0, 0.0, 0.0, 1.0]),
    ...                        np.linspace(0.0, 600.0, 4), gg, 0.0, 0.0, method="rk8", step=1.0)
    >>> bool(np.abs(quat[-1] - [0.0, 0.0, np.sin(30.0), np.cos(30.0)]).max() < 1e-12)
    True
    """
    terms = free_terms(torque)
    if terms is None:
        raise ValueError(f"torque = {torque!r} holds neither the gravity gradient along a Keplerian or TLE orbit nor "
                         "a ResidualDipole, or something besides them and constant torques")
    I = np.asarray(moments, float)
    kernel = ControlKernel(I, locked_inverse(I, None), None, terms.field, terms.gravity_gradient, float(rtol),
                           float(np.min(atol)), float(t[-1]), method, step, checked=True, torque=terms.rest,
                           rotor_momentum=rotor_momentum)
    y0 = np.concatenate([quat0, omega0, np.zeros(3)])  # (q, omega, the external impulse)
    Y = kernel.run(y0, t, _NO_LAW, _NO_RODS, _NO_LIMITS, carry=True)[0]
    return Y[:, 4:7], Y[:, :4]
