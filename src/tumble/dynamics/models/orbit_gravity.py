"""The gravity-gradient torque along any orbit of :mod:`tumble.dynamics.environment`, and the
one way from an orbit to its torque model, :func:`gravity_gradient_of`.

**Along an ellipse or a TLE** (:class:`OrbitGravityGradient`): the formula of
:class:`~tumble.dynamics.models.gravity.GravityGradient`, ``tau = 3 (mu / r^3) r_b x (I r_b)``
(Hughes, *Spacecraft Attitude Dynamics*, Wiley 1986, ch. 8; written once as
:func:`~tumble.dynamics.models.gravity.gradient_torque`), with the radius ``r(t)`` read from the
orbit's ``position_world(t)``, so that the radius and the rate ``mu / r^3`` change along the
orbit (a :class:`~tumble.dynamics.environment.ephemeris.KeplerOrbit` or
:class:`~tumble.dynamics.environment.ephemeris.TLEOrbit`; their world frame is ECI or TEME).

**From an orbit to its torque** (:func:`gravity_gradient_of`): a
:class:`~tumble.dynamics.environment.orbit.CircularOrbit` gets the closed-form circle,
:class:`~tumble.dynamics.models.gravity.GravityGradient` (whose world frame is the circle's
orbit-plane frame, and which the compiled engine runs), any other orbit the general model here.
The orbits themselves exert no torque and know nothing of the models: they live below them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, Vector3
from ...validation import check_moments, check_positive
from ..environment.earth import MU_EARTH, check_mu
from ..environment.ephemeris import KeplerOrbit, TLEOrbit
from ..environment.orbit import CircularOrbit
from .gravity import GravityGradient, gradient_torque
from .torques import AddsTorques

__all__ = ["OrbitGravityGradient", "gravity_gradient_of"]


def _as_tuples(I: FloatArray) -> tuple[float, ...] | tuple[tuple[float, ...], ...]:
    """Checked moments (3,) or (N, 3) as a tuple of floats or of rows (a frozen model's field); a
    ValueError for any other shape."""
    if I.ndim > 2:
        raise ValueError(f"moments has shape {I.shape}; it must be (3,) or (N, 3) (kg m^2)")
    return tuple(map(float, I)) if I.ndim == 1 else tuple(tuple(map(float, row)) for row in I)


def gravity_gradient_of(orbit: CircularOrbit | KeplerOrbit | TLEOrbit) -> GravityGradient | OrbitGravityGradient:
    """The gravity-gradient torque model of ``orbit`` (its world frame is the orbit's; unbound:
    ``simulate_controlled`` or the model's ``bind(body)`` gives it the body's moments).

    Parameters
    ----------
    orbit : CircularOrbit, KeplerOrbit or TLEOrbit
        The orbit (:mod:`tumble.dynamics.environment`).

    Returns
    -------
    GravityGradient or OrbitGravityGradient
        ``GravityGradient(orbit_radius=orbit.radius, mu=orbit.mu)`` for a circular orbit,
        ``OrbitGravityGradient(orbit)`` for a Keplerian or TLE orbit.

    Raises
    ------
    TypeError
        If ``orbit`` is none of these, naming the argument, its type and what is allowed.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
    >>> orbit = CircularOrbit(altitude=500e3)
    >>> gg = gravity_gradient_of(orbit)
    >>> type(gg).__name__, gg.radius == orbit.radius, math.isclose(gg.period, orbit.period)
    ('GravityGradient', True, True)
    >>> gravity_gradient_of(KeplerOrbit(7000e3, 0.01)).orbit.eccentricity
    0.01
    >>> gravity_gradient_of(7000e3)
    Traceback (most recent call last):
    ...
    TypeError: orbit = 7000000.0 is a float; allowed: a CircularOrbit, KeplerOrbit or TLEOrbit (tumble.dynamics.environment)
    """
    if isinstance(orbit, CircularOrbit):
        return GravityGradient(orbit_radius=orbit.radius, mu=orbit.mu)
    if isinstance(orbit, (KeplerOrbit, TLEOrbit)):
        return OrbitGravityGradient(orbit)
    raise TypeError(f"orbit = {orbit!r} is a {type(orbit).__name__}; allowed: a CircularOrbit, KeplerOrbit or TLEOrbit "
                    "(tumble.dynamics.environment)")


@dataclass(frozen=True, eq=False)
class OrbitGravityGradient(AddsTorques):
    """The gravity-gradient torque ``3 mu / r^3 R (r_b x I r_b)`` along an orbit's position (N m, world frame).

    The formula of :class:`~tumble.dynamics.models.gravity.GravityGradient` (Hughes ch. 8) with
    the radius ``r(t)`` read from ``orbit.position_world(t)``: for an ellipse or a TLE the
    radius and the rate ``mu / r^3`` change along the orbit.

    Parameters
    ----------
    orbit : KeplerOrbit or TLEOrbit (or any object with ``position_world(t)``, m)
        The orbit.
    mu : float
        Gravitational parameter, m^3/s^2 (default the orbit's, or the Earth's).
    moments : array_like, shape (3,) or (N, 3), optional
        Principal moments, kg m^2 (:meth:`bind` gives them); N rows for a batch of N bodies, whose
        torques are then (N, 3).

    Examples
    --------
    On a circle it is :class:`~tumble.dynamics.models.gravity.GravityGradient`:

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.models.gravity import GravityGradient
    >>> from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
    >>> k = KeplerOrbit(7000e3)
    >>> att = Rotation.from_rotvec([0.3, -0.2, 0.5])
    >>> a = OrbitGravityGradient(k).bind([1.0, 2.0, 3.0])(100.0, np.zeros(3), att)
    >>> b = GravityGradient(orbit_radius=7000e3, moments=[1.0, 2.0, 3.0])(100.0, np.zeros(3), att)
    >>> np.allclose(a, b, rtol=1e-12, atol=0.0)
    True
    """

    orbit: Any
    mu: float | None = None
    moments: tuple[float, ...] | tuple[tuple[float, ...], ...] | None = None
    frame: str = field(default="world", init=False)

    def __post_init__(self) -> None:
        if not callable(getattr(self.orbit, "position_world", None)):
            raise ValueError(f"orbit = {self.orbit!r} must give position_world(t) (m): a KeplerOrbit or TLEOrbit")  # noqa: TRY004
        own = getattr(self.orbit, "mu", None)  # a Keplerian orbit's own, which its positions obey
        mu = check_mu(self.mu if self.mu is not None else MU_EARTH if own is None else own)
        if own is not None and not math.isclose(mu, own, rel_tol=1e-12):
            raise ValueError(f"mu = {self.mu!r} m^3/s^2 differs from the orbit's mu = {own!r}, by which it moves: one body "
                             "attracts both; leave mu out (the orbit's is taken)")
        object.__setattr__(self, "mu", mu)
        if self.moments is not None:
            object.__setattr__(self, "moments", _as_tuples(check_moments("moments", self.moments)))

    def bind(self, body: object) -> OrbitGravityGradient:
        """The same orbit acting on ``body`` (a Body, MassProperties or principal moments, kg m^2,
        shape (3,) or (N, 3) for a batch).

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
        >>> OrbitGravityGradient(KeplerOrbit(7000e3)).bind([1.0, 2.0, 3.0]).moments
        (1.0, 2.0, 3.0)
        >>> OrbitGravityGradient(KeplerOrbit(7000e3)).bind([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]]).moments
        ((1.0, 2.0, 3.0), (2.0, 2.0, 3.0))
        """
        moments = getattr(body, "principal_moments", body)
        return replace(self, moments=_as_tuples(check_moments("moments", cast(ArrayLike, moments))))

    def __call__(self, t: float, omega: FloatArray, attitude: Rotation) -> Vector3:
        """World-frame torque at ``t`` (s), N m (``omega`` unused; ``attitude`` body to world); shape
        (3,), or (N, 3) for a batch's moments or N attitudes.

        Examples
        --------
        At perigee of an ellipse the rate ``mu / r^3`` is ``(1 - e)^-3`` times that of the circle of radius ``a``:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
        >>> k = KeplerOrbit(8000e3, 0.2)
        >>> att = Rotation.from_rotvec([0.0, 0.0, 0.4])
        >>> perigee = OrbitGravityGradient(k).bind([1.0, 2.0, 3.0])(0.0, np.zeros(3), att)
        >>> circle = OrbitGravityGradient(KeplerOrbit(8000e3)).bind([1.0, 2.0, 3.0])(0.0, np.zeros(3), att)
        >>> np.allclose(perigee, circle / 0.8**3)
        True
        """
        if self.moments is None:
            raise ValueError("this gravity gradient has no moments: use .bind(body)")
        r = np.asarray(self.orbit.position_world(float(t)), float)
        rn = float(np.linalg.norm(r))
        mu = float(cast(float, self.mu))
        r_b = attitude.inv().apply(r / rn)
        return np.asarray(attitude.apply(gradient_torque(r_b, np.asarray(self.moments), mu / rn**3)), float)

    def loop_form(self) -> tuple[float, float, Any] | None:
        """The compiled closed loop's form, ``(n, mu, orbit)``: no circle (``n`` 0), the
        gravitational parameter ``mu`` (m^3/s^2) and the orbit whose position the loop tabulates
        (:func:`~tumble.dynamics.environment.tabulated.position_table`); None for an orbit of one's
        own (not a CircularOrbit, KeplerOrbit or TLEOrbit) or a subclass with a law of its own.

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
        >>> orbit = KeplerOrbit(8000e3, 0.1)
        >>> n, mu, tabulated = OrbitGravityGradient(orbit).loop_form()
        >>> n, mu == orbit.mu, tabulated is orbit
        (0.0, True, True)
        """
        if type(self).__call__ is not OrbitGravityGradient.__call__ or \
                not isinstance(self.orbit, (CircularOrbit, KeplerOrbit, TLEOrbit)):
            return None
        return 0.0, float(cast(float, self.mu)), self.orbit
