"""A rigid body along an ellipse or a TLE's orbit, compiled: the closed loop's kernel with nothing to control.

:func:`tumble.simulate` runs a torque on the compiled engine when the model has a form among the
engine's torque terms (:mod:`tumble.dynamics.engine.kernels`): constant torques and the gravity
gradient of a circular orbit, whose direction the engine turns from stage to stage. The gravity
gradient along a Keplerian or TLE orbit
(:class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`) has none there: its
radius changes along the orbit. The compiled closed loop has it
(:mod:`~tumble.dynamics.control.compiled_loop`): the orbit's position tabulated as cubics
(:func:`~tumble.dynamics.environment.tabulated.position_table`, relative error below 1e-11) and
the gravity gradient ``3 mu / r^3 r_b x (I r_b)`` read from it
(:func:`~tumble.dynamics.control.loop_terms.external_torque`), beside the constant body and world
torques of its disturbance slots. With no wheels, no magnetorquers, no field and B-dot's law
(which commands nothing where there is no field) that loop is the rigid body alone: DOP853 with
scipy's error norm and step control (Hairer, Norsett & Wanner, *Solving ODEs I*, sec. II.10),
each step continuing from the one the last proposed (``carry``) and ending on every sample time.

Before, such a run called the model from Python at every stage: 28 s for ten orbits of an
ellipse (e = 0.1) at 0.1 rad/s, against 11 ms for the circle on the engine (measured 2026-11-30).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...typing import FloatArray
from ..models.orbit_gravity import OrbitGravityGradient
from ..models.torques import ConstantTorque
from ._front import locked_inverse
from .compiled_loop import LAW_BDOT
from .control_kernel import ControlKernel, disturbance_form

__all__ = ["orbit_terms", "run_in_orbit"]

#: B-dot's law with no gain, no field and no rods: it commands nothing.
_NO_LAW = (LAW_BDOT, np.zeros(3), np.zeros((0, 3)))
_NO_RODS, _NO_LIMITS = np.zeros((0, 3)), np.zeros(0)


def orbit_terms(torque: Any) -> tuple[OrbitGravityGradient, tuple[float, ...]] | None:
    """``(gravity_gradient, disturbance)`` of a torque that is the gravity gradient along a
    Keplerian or TLE orbit (:class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`,
    its law not changed by a subclass), alone or summed with constant body and world torques
    (their terms, N m, :func:`~tumble.dynamics.control.control_kernel.disturbance_form`); None for
    any other torque.

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque
    >>> from tumble.dynamics.control.free_loop import orbit_terms
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
    >>> gg = OrbitGravityGradient(KeplerOrbit(8000e3, 0.1))
    >>> found, disturbance = orbit_terms(gg + ConstantTorque((0.0, 0.0, 1e-6)))
    >>> found is gg, disturbance
    (True, (0.0, 0.0, 1e-06, 0.0, 0.0, 0.0))
    >>> orbit_terms(ConstantTorque((0.0, 0.0, 1e-6))) is None   # the engine's own
    True
    """
    terms = getattr(torque, "terms", (torque,))
    orbits = [term for term in terms if isinstance(term, OrbitGravityGradient)]
    if len(orbits) != 1 or orbits[0].loop_form() is None:
        return None
    disturbance: tuple[float, ...] = (0.0,) * 6
    for term in terms:
        if term is not orbits[0]:
            form = disturbance_form(term)
            if form is None:
                return None
            disturbance = tuple(a + b for a, b in zip(disturbance, form))
    return orbits[0], disturbance


def run_in_orbit(moments: FloatArray, omega0: FloatArray, quat0: FloatArray, t: FloatArray, torque: Any,
                 rtol: float, atol: float | FloatArray) -> tuple[FloatArray, FloatArray]:
    """The body of principal ``moments`` (kg m^2) from ``omega0`` (rad/s, principal frame) and
    ``quat0`` (body to the orbit's world frame, ECI or TEME; scalar last) through the samples ``t``
    (s, increasing, from ``t[0] >= 0``) under ``torque`` (:func:`orbit_terms`), DOP853 at ``rtol``
    and ``atol`` (the smallest of an array's), on the compiled closed loop (module docstring).

    Returns
    -------
    omega, quat : ndarray, shapes (n, 3) and (n, 4)
        The rate (rad/s) and the unit quaternion at the samples.

    Examples
    --------
    A body with two equal moments, spinning about its axis of symmetry set along the orbit's
    normal: the gradient's torque ``r_b x (I r_b)`` is zero there, so the spin and the axis stay:

    >>> import numpy as np
    >>> from tumble.dynamics.control.free_loop import run_in_orbit
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
    >>> gg = OrbitGravityGradient(KeplerOrbit(8000e3, 0.2)).bind([1.0, 1.0, 2.0])
    >>> omega, quat = run_in_orbit(np.array([1.0, 1.0, 2.0]), np.array([0.0, 0.0, 0.1]),
    ...                            np.array([0.0, 0.0, 0.0, 1.0]), np.linspace(0.0, 600.0, 4), gg, 1e-10, 1e-12)
    >>> bool(np.abs(omega - [0.0, 0.0, 0.1]).max() < 1e-14), bool(np.abs(quat[:, :2]).max() < 1e-14)
    (True, True)
    """
    terms = orbit_terms(torque)
    if terms is None:
        raise ValueError(f"torque = {torque!r} is not the gravity gradient along a Keplerian or TLE orbit "
                         "(with constant torques)")
    gravity_gradient, (b0, b1, b2, w0, w1, w2) = terms
    pushes = ConstantTorque((b0, b1, b2)) + ConstantTorque((w0, w1, w2), "world")
    I = np.asarray(moments, float)
    kernel = ControlKernel(I, locked_inverse(I, None), None, None, gravity_gradient, float(rtol),
                           float(np.min(atol)), float(t[-1]), checked=True, torque=pushes)
    y0 = np.concatenate([quat0, omega0, np.zeros(3)])  # (q, omega, the external impulse)
    Y = kernel.run(y0, t, _NO_LAW, _NO_RODS, _NO_LIMITS, carry=True)[0]
    return Y[:, 4:7], Y[:, :4]
