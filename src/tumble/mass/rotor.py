"""A rotor: a solid cylinder that spins relative to the body about its own axis.

A momentum or reaction wheel: its mass and (locked) inertia count like any part's
(:class:`tumble.mass.parts.Cylinder`, Meriam & Kraige Table D/4), and its internal angular
momentum ``h = J s axis`` enters the dynamics (:mod:`tumble.dynamics.models.internal`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from numbers import Real
from typing import ClassVar, cast

import numpy as np

from ..typing import ArrayLike, FloatArray, Vector3
from ..validation import MAX_RATE, check_at_most, check_callable, check_number
from .parts import PART_KINDS, Cylinder

__all__ = ["Rotor"]


@dataclass(frozen=True, kw_only=True)
class Rotor(Cylinder):
    """An axisymmetric rotor (a solid cylinder or disc) spinning about its own ``axis``.

    A momentum or reaction wheel: its mass and its inertia *as if locked to the body* count in
    the body's mass properties like a :class:`Cylinder`'s; its spin relative to the body,
    ``s(t)`` (rad/s, right-handed about ``axis``), adds the internal angular momentum
    ``h = J s(t) axis`` with ``J = m r^2 / 2`` the axial moment (kg m^2/s; Meriam & Kraige
    Table D/4), which enters Euler's equations of the gyrostat (:mod:`tumble.dynamics.models.internal`).

    Parameters
    ----------
    mass, density, radius, length, axis, center
        As for :class:`Cylinder` (kg, kg/m^3, m, m, a direction, m).
    spin_rate : float or callable
        The spin relative to the body, rad/s: a number (constant, or the value at t = 0 of a
        linear ramp, see ``spin_acceleration``) or a function ``s(t)`` of the time t (s)
        returning rad/s (a commanded reaction wheel; Python only, not in body files).
    spin_acceleration : float or callable, optional
        With a number ``spin_rate``: a constant ``ds/dt``, rad/s^2, so that
        ``s(t) = spin_rate + spin_acceleration t`` (default 0: constant spin). With a function
        ``spin_rate``: its derivative ``s'(t)`` (rad/s^2), which only the motor's power and work
        need; without it they are not reported.
        Spins are bounded by :data:`~tumble.validation.MAX_RATE` (1e15 rad/s, faster than
        any rotation of matter) at every time a run asks for, accelerations by its square
        (1e30 rad/s^2: that rate reached within one radian of turning).

    Raises
    ------
    ValueError
        As for :class:`Cylinder`, and for ``subtract=True`` (a hole cannot spin), a
        ``spin_rate`` that is neither a finite number nor a function, or a
        ``spin_acceleration`` of the other kind than ``spin_rate``.

    Examples
    --------
    >>> import tumble
    >>> wheel = tumble.Rotor(mass=2.0, radius=0.1, length=0.02, axis=(0, 0, 1), spin_rate=50.0)
    >>> round(float(wheel.axial_moment), 6), wheel.momentum(0.0).round(6).tolist()   # J = m r^2 / 2, h = J s axis
    (0.01, [0.0, 0.0, 0.5])
    """

    kind: ClassVar[str] = "rotor"
    spin_rate: float | Callable[[float], float]
    spin_acceleration: float | Callable[[float], float] | None = None

    def _check_shape(self) -> None:
        super()._check_shape()
        if self.subtract is True:
            raise ValueError("subtract = True is not allowed for a rotor: removed material cannot spin")
        rate, accel = self.spin_rate, self.spin_acceleration
        if callable(rate):
            if accel is not None and not callable(accel):
                raise ValueError(
                    f"spin_acceleration = {accel!r} must be a function of time (rad/s^2) when "
                    f"spin_rate is one, or be left out"
                )
            check_callable("spin_rate", rate, "s(t)")  # said here, not at the run that first calls it
            if accel is not None:
                check_callable("spin_acceleration", accel, "a(t)")
            return
        if isinstance(rate, (str, bytes)) or not _is_number(rate):
            raise ValueError(
                f"spin_rate = {rate!r} must be a number (rad/s) or a function of time t (s) returning rad/s"
            )
        self._set("spin_rate", check_number("spin_rate", rate, "rad/s", MAX_RATE))
        if callable(accel):
            raise ValueError(
                f"spin_acceleration = {accel!r} is a function but spin_rate = {rate!r} is a number; "
                f"give a number (rad/s^2) for a linear ramp, or make spin_rate a function too"
            )
        self._set("spin_acceleration", 0.0 if accel is None else check_number("spin_acceleration", accel, "rad/s^2",
                                                                         MAX_RATE**2))

    @property
    def axial_moment(self) -> float:
        """``J = m r^2 / 2``, the moment about the spin axis, kg m^2.

        Examples
        --------
        >>> import tumble
        >>> float(tumble.Rotor(mass=4.0, radius=0.5, length=0.1, spin_rate=0.0).axial_moment)   # m r^2 / 2
        0.5
        """
        return cast(float, cast(float, self.mass) * self._unit_moments()[2])

    @property
    def constant_spin(self) -> bool:
        """Whether the relative spin is a constant number (no ramp, no function).

        Examples
        --------
        >>> import tumble
        >>> tumble.Rotor(mass=1.0, radius=0.1, length=0.1, spin_rate=10.0).constant_spin
        True
        >>> tumble.Rotor(mass=1.0, radius=0.1, length=0.1, spin_rate=10.0, spin_acceleration=2.0).constant_spin
        False
        """
        return not callable(self.spin_rate) and self.spin_acceleration == 0.0

    def spin(self, t: ArrayLike) -> FloatArray:
        """The relative spin ``s(t)`` at the times ``t`` (s, any shape), rad/s; ``t``'s shape.

        Examples
        --------
        >>> import tumble
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.1, spin_rate=10.0, spin_acceleration=2.0)
        >>> ramp.spin([0.0, 1.0, 5.0]).tolist()   # s(t) = 10 + 2 t
        [10.0, 12.0, 20.0]
        """
        return self._evaluate(self.spin_rate, self.spin_acceleration, t, "spin_rate", "rad/s")

    def spin_derivative(self, t: ArrayLike) -> FloatArray | None:
        """``ds/dt`` at the times ``t`` (s), rad/s^2; None when ``spin_rate`` is a function given
        without its derivative.

        Examples
        --------
        >>> import math, tumble
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.1, spin_rate=10.0, spin_acceleration=2.0)
        >>> ramp.spin_derivative([0.0, 1.0]).tolist()
        [2.0, 2.0]
        >>> wave = tumble.Rotor(mass=1.0, radius=0.1, length=0.1, spin_rate=math.sin)
        >>> wave.spin_derivative(0.0) is None   # a function given without its derivative
        True
        """
        if callable(self.spin_rate):
            if self.spin_acceleration is None:
                return None
            return self._evaluate(self.spin_acceleration, None, t, "spin_acceleration", "rad/s^2")
        return np.full(np.shape(t), float(cast(float, self.spin_acceleration)))

    def momentum(self, t: ArrayLike) -> Vector3:
        """Internal angular momentum ``J s(t) axis`` in the design frame, kg m^2/s; shape
        ``t.shape + (3,)``.

        Examples
        --------
        >>> import tumble
        >>> wheel = tumble.Rotor(mass=2.0, radius=0.1, length=0.02, axis=(1, 0, 0), spin_rate=100.0)
        >>> wheel.momentum([0.0, 1.0]).round(6).tolist()   # J s along the axis, kg m^2/s
        [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
        """
        return cast(Vector3, (self.axial_moment * self.spin(t))[..., None] * np.array(self.axis))

    @staticmethod
    def _evaluate(
        fn: float | Callable[[float], float], slope: float | Callable[[float], float] | None, t_in: ArrayLike,
        field: str, unit: str,
    ) -> FloatArray:
        t = np.asarray(t_in, dtype=float)
        bound = MAX_RATE if field == "spin_rate" else MAX_RATE**2
        if not callable(fn):
            out: FloatArray = fn + cast(float, slope) * t  # a number: set to 0.0 when not given
            if out.size and not np.max(np.abs(out)) <= bound:
                k = np.unravel_index(np.argmax(np.abs(out)), out.shape)
                check_at_most(f"the rotor's {field} at t = {float(t[k]):.6g} s", float(out[k]), unit, bound)
            return out
        out = np.empty(t.shape)
        for k, tk in np.ndenumerate(t):
            value = fn(float(tk))
            if not _is_number(value) or not math.isfinite(float(value)):
                raise ValueError(
                    f"the rotor's {field} function returned {value!r} at t = {float(tk):.6g} s; "
                    f"expected a finite number ({unit})"
                )
            check_at_most(f"the rotor's {field} function's value at t = {float(tk):.6g} s", float(value), unit, bound)
            out[k] = float(value)
        return out


def _is_number(value: object) -> bool:
    return not isinstance(value, (bool, np.bool_)) and isinstance(value, (Real, np.integer, np.floating))


PART_KINDS[Rotor.kind] = Rotor
