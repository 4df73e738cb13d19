"""Gravity-gradient torque on a rigid body in a circular orbit, and its orbiting frame.

The body's centre of mass moves on a circular orbit of radius ``r`` (m) in the world x-y
plane, about a point mass ``mu`` (m^3/s^2) at the world origin: its unit radius vector is
``(cos n t, sin n t, 0)`` (t in s, from t = 0), the orbit normal is +z and the mean motion is
``n = sqrt(mu / r^3) = 2 pi / period`` (rad/s). The orbit is not disturbed by the attitude
(the restricted problem). Expanding the gravitational potential of the body to second order in
its size gives, in the principal (body) frame,

``tau = 3 n^2 r_b x (I r_b)``,  ``V = (3/2) n^2 r_b . I r_b`` (+ a constant)

with ``r_b`` the unit radius vector in body coordinates and ``I = diag(I1, I2, I3)`` (N m, J):
Hughes, *Spacecraft Attitude Dynamics* (Wiley 1986; Dover 2004), ch. 8 (gravitational
torques); Kane, Likins & Levinson, *Spacecraft Dynamics* (McGraw-Hill 1983). The torque is
``-dV/d(theta)`` for a small rotation ``theta`` of the body: ``dr_b = -theta x r_b`` gives
``dV = -3 n^2 theta . (r_b x I r_b)``.

**Orbiting frame (LVLH)**, roll-pitch-yaw axes and the attitude relative to it:
:mod:`tumble.dynamics.models.lvlh` (its names are re-exported here). The torque along an
elliptic or TLE orbit, and the torque model of any orbit of :mod:`tumble.dynamics.environment`
(:func:`~tumble.dynamics.models.orbit_gravity.gravity_gradient_of`), are
:mod:`tumble.dynamics.models.orbit_gravity`; the Earth's ``mu`` and radius are
:mod:`tumble.dynamics.environment.earth`.

The linear stability of a body at rest in this frame (the Lagrange and DeBra-Delp regions) is
:mod:`tumble.analysis.gravity_stability`.

**Energy budget.** The Lagrangian in coordinates relative to the orbiting frame does not depend
on time, so its energy function (the Jacobi integral; Goldstein, *Classical Mechanics*, ch. 2,
the energy function ``h``) is conserved:
``h = T2 - T0 + V = (1/2) w_r . I w_r - (1/2) n^2 o_b . I o_b + (3/2) n^2 r_b . I r_b`` (J),
with ``w_r = omega - n o_b`` the angular velocity relative to the orbiting frame and ``o_b`` the
orbit normal, both in the body frame (Hughes ch. 9 uses it as the Liapunov function of the
Lagrange region).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, Vector3
from ...validation import check_moments, check_positive, check_vectors

if TYPE_CHECKING:
    from ...mass import Body, MassProperties

from ..environment.earth import MU_EARTH, R_EARTH, check_mu, is_earth
from ..special.quaternion import to_body
from .torques import KERNEL_CIRCULAR_GRAVITY, AddsTorques, as_torque, terms_of
from .lvlh import (
    _LVLH0,
    LVLHState,
    OrbitAngles,
    lvlh_state,
    orbit_frame_angles,
    relative_attitude,
    rpy_axes,
)

__all__ = [
    "GravityGradient",
    "LVLHState",
    "OrbitAngles",
    "gradient_components",
    "gradient_torque",
    "gravity_gradient_in",
    "lvlh_state",
    "orbit_frame_angles",
    "relative_attitude",
    "rpy_axes",
]


def gradient_torque(r_b: ArrayLike, moments: ArrayLike, rate2: ArrayLike) -> Vector3:
    """The gravity-gradient torque ``3 (mu / r^3) r_b x (I r_b)`` in the body frame, N m (module docstring).

    Parameters
    ----------
    r_b : array_like, shape (..., 3)
        Unit radius vector (from the attracting centre to the body), principal frame.
    moments : array_like, shape (..., 3)
        Principal moments, kg m^2.
    rate2 : array_like, shape (...)
        ``mu / r^3`` (``n^2`` on a circle), 1/s^2.

    Examples
    --------
    Along a principal axis there is no torque; at 45 deg between axes 1 and 2 it is
    ``(3/2) n^2 (I2 - I1)`` about axis 3:

    >>> import math
    >>> import numpy as np
    >>> from tumble.dynamics.models.gravity import gradient_torque
    >>> gradient_torque([1.0, 0.0, 0.0], [1.0, 2.0, 3.0], 1e-6).tolist()
    [0.0, 0.0, 0.0]
    >>> s = math.sqrt(0.5)
    >>> np.allclose(gradient_torque([s, s, 0.0], [1.0, 2.0, 3.0], 1e-6), [0.0, 0.0, 1.5e-6])
    True
    """
    r, I = np.broadcast_arrays(np.asarray(r_b, float), np.asarray(moments, float))
    rate = np.asarray(rate2, float)
    return np.stack(gradient_components(rate, I[..., 0], I[..., 1], I[..., 2], r[..., 0], r[..., 1], r[..., 2]), axis=-1)


def gradient_components(rate2: Any, I0: Any, I1: Any, I2: Any, b0: Any, b1: Any, b2: Any) -> tuple[Any, Any, Any]:
    """``3 rate2 r_b x (I r_b)`` component by component (N m, body frame): the one writing of
    the gravity-gradient torque (Hughes, *Spacecraft Attitude Dynamics*, ch. 8, eq. 8.1.21),
    over floats (the compiled kernels) or arrays of one shape (:func:`gradient_torque`).

    ``rate2`` is ``mu / r^3`` (``n^2`` on a circle, 1/s^2), ``I0, I1, I2`` the principal moments
    (kg m^2), ``b0, b1, b2`` the unit radius vector in the principal frame.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.models.gravity import gradient_components
    >>> s = math.sqrt(0.5)
    >>> [round(float(x), 12) for x in gradient_components(1e-6, 1.0, 2.0, 3.0, s, s, 0.0)]
    [0.0, 0.0, 1.5e-06]
    """
    g = 3.0 * rate2
    c0, c1, c2 = I0 * b0, I1 * b1, I2 * b2
    return g * (b1 * c2 - b2 * c1), g * (b2 * c0 - b0 * c2), g * (b0 * c1 - b1 * c0)



@dataclass(frozen=True)
class GravityGradient(AddsTorques):
    """The gravity-gradient torque of a circular orbit (a torque model, world frame).

    A *description* of the orbit; :meth:`bind` gives it the principal moments of the body it
    acts on (``simulate`` does that itself), or pass ``moments`` here. Called as
    ``model(t, omega, attitude)`` it returns ``3 n^2 r x (I r)`` (N m) in the world frame; see
    the module docstring for the orbit, the formula and its sources.

    Parameters
    ----------
    orbit_period : float, optional
        Orbital period, s. Exactly one of ``orbit_period`` and ``orbit_radius``.
    orbit_radius : float, optional
        Orbit radius, m (from the centre of the attracting body).
    mu : float
        Gravitational parameter, m^3/s^2; default the Earth's,
        :data:`~tumble.dynamics.environment.earth.MU_EARTH`, and then the orbit must lie above the
        Earth's equatorial radius :data:`~tumble.dynamics.environment.earth.R_EARTH` (6378.1 km).
    moments : array_like, shape (3,) or (N, 3), optional
        Principal moments ``I1 <= I2 <= I3`` of the body (kg m^2), or of N bodies (a batch).

    Raises
    ------
    ValueError
        Naming the field, the value and what is allowed.

    Examples
    --------
    >>> from tumble.dynamics.models.gravity import GravityGradient
    >>> gg = GravityGradient(orbit_period=5400.0)
    >>> round(gg.radius / 1e3)   # km
    6653
    """

    orbit_period: float | None = None
    orbit_radius: float | None = None
    mu: float = MU_EARTH
    moments: tuple[float, ...] | None = None
    #: Frame of the returned torque: the world frame, so a ``frame="design"`` run leaves it as it is.
    frame: str = field(default="world", init=False)
    _n: float = field(default=0.0, init=False, repr=False, compare=False)
    _r: float = field(default=0.0, init=False, repr=False, compare=False)
    _I: np.ndarray | None = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        mu = check_mu(self.mu)
        given = [name for name in ("orbit_period", "orbit_radius") if getattr(self, name) is not None]
        if len(given) != 1:
            both = f": orbit_period = {self.orbit_period!r}, orbit_radius = {self.orbit_radius!r}" if given else ""
            raise ValueError("give exactly one of orbit_period (s) and orbit_radius (m)" + (", not both" + both if given else ""))
        if given == ["orbit_period"]:  # Kepler's third law, n^2 r^3 = mu, n = 2 pi / T
            T = check_positive("orbit_period", self.orbit_period, "s")
            n = 2.0 * math.pi / T
            r = math.cbrt(mu) * (T / (2.0 * math.pi)) ** (2.0 / 3.0)  # cannot overflow: power < 1
        else:
            r = check_positive("orbit_radius", self.orbit_radius, "m")
            n = math.sqrt(mu / r) / r  # sqrt(mu / r^3) without overflowing r^3
        name, value = given[0], getattr(self, given[0])
        if not (0.0 < n < math.inf and 0.0 < r < math.inf):
            raise ValueError(f"{name} = {value!r} gives a mean motion of {n!r} rad/s; it must be a positive finite number")
        if is_earth(mu) and r <= R_EARTH:
            shortest = 2.0 * math.pi * math.sqrt(R_EARTH**3 / mu)
            raise ValueError(
                f"{name} = {value!r} puts the orbit at radius {r:.6g} m, inside the Earth (equatorial "
                f"radius R_E = {R_EARTH:g} m); allowed: orbit_radius > {R_EARTH:g} m, orbit_period > "
                f"{shortest:.6g} s (or give another mu)"
            )
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "_n", n)
        object.__setattr__(self, "_r", r)
        if self.moments is not None:
            I = check_moments("moments", self.moments)
            if I.ndim > 2:
                raise ValueError(f"moments has shape {I.shape}; allowed: (3,) or (N, 3) (kg m^2)")
            object.__setattr__(self, "moments", tuple(map(float, I)) if I.ndim == 1 else tuple(map(tuple, I.tolist())))
            object.__setattr__(self, "_I", I)

    @property
    def mean_motion(self) -> float:
        """Mean motion ``n = sqrt(mu / r^3) = 2 pi / period``, rad/s.

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.environment.earth import MU_EARTH
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> gg = GravityGradient(orbit_radius=7.0e6)
        >>> math.isclose(gg.mean_motion, math.sqrt(MU_EARTH / 7.0e6**3)), math.isclose(gg.mean_motion * gg.period, 2 * math.pi)
        (True, True)
        """
        return self._n

    @property
    def period(self) -> float:
        """Orbital period ``2 pi / n``, s.

        Examples
        --------
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> round(GravityGradient(orbit_radius=7.0e6).period, 1)   # 2 pi sqrt(r^3 / mu), s
        5828.5
        """
        return 2.0 * math.pi / self._n

    @property
    def radius(self) -> float:
        """Orbit radius ``(mu / n^2)^(1/3)``, m.

        Examples
        --------
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> round(GravityGradient(orbit_period=86164.1).radius / 1e3)   # one sidereal day: the geostationary radius, km
        42164
        """
        return self._r

    def bind(self, body: Body | MassProperties | ArrayLike) -> GravityGradient:
        """The same orbit acting on ``body``: a Body, MassProperties or principal moments (kg m^2).

        Raises ``ValueError`` if this model already holds other moments (more than 1e-9
        relative apart): the torque would belong to another body.

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
        >>> gg = GravityGradient(orbit_period=5400.0).bind(body)
        >>> gg.moments, gg.bind([1.0, 2.0, 3.0]) is gg   # the same body again: unchanged
        ((1.0, 2.0, 3.0), True)
        >>> gg.bind([1.0, 2.0, 2.5])
        Traceback (most recent call last):
        ...
        ValueError: this GravityGradient holds moments [1.0, 2.0, 3.0] kg m^2, not the body's [1.0, 2.0, 2.5]: leave moments out and let simulate bind it
        """
        moments = cast(ArrayLike, getattr(body, "principal_moments", body))
        if self._I is not None:
            I = check_vectors("moments", moments, "kg m^2")
            if I.shape != self._I.shape or not np.allclose(I, self._I, rtol=1e-9, atol=0.0):
                raise ValueError(
                    f"this GravityGradient holds moments {self._I.tolist()} kg m^2, not the body's "
                    f"{I.tolist()}: leave moments out and let simulate bind it"
                )
            return self
        try:
            key = np.asarray(moments, dtype=float)
        except (TypeError, ValueError):  # the constructor's checks name what is wrong
            return replace(self, moments=cast("tuple[float, ...]", moments))
        return _bound(self, key.tobytes(), key.shape)

    def radial_direction(self, t: ArrayLike) -> Vector3:
        """Unit radius vector ``(cos n t, sin n t, 0)`` in the world frame at ``t`` (s); shape ``t.shape + (3,)``.

        Examples
        --------
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> gg = GravityGradient(orbit_period=5400.0)
        >>> gg.radial_direction([0.0, 1350.0, 2700.0]).round(12).tolist()   # a quarter and half an orbit on
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]
        """
        nt = self._n * np.asarray(t, dtype=float)
        return np.stack([np.cos(nt), np.sin(nt), np.zeros_like(nt)], axis=-1)

    def orbit_frame(self, t: ArrayLike) -> Rotation:
        """The orbiting (LVLH) frame to world at ``t`` (s): columns roll (velocity), pitch
        (orbit normal), yaw (radius); one rotation, or a stack for an array of times.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> gg = GravityGradient(orbit_period=5400.0)
        >>> gg.orbit_frame(0.0).as_matrix().round(12).tolist()   # columns: roll (velocity), pitch (normal), yaw (radius)
        [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        >>> t = np.array([100.0, 2000.0])
        >>> bool(np.allclose(gg.orbit_frame(t).apply([0.0, 0.0, 1.0]), gg.radial_direction(t)))   # yaw on the radius
        True
        """
        nt = self._n * np.asarray(t, dtype=float)
        return Rotation.from_rotvec(nt[..., None] * np.array([0.0, 0.0, 1.0])) * _LVLH0

    def __call__(self, t: float, omega: np.ndarray, attitude: Rotation) -> Vector3:
        """World-frame torque ``3 n^2 R (r_b x I r_b)``, N m, shape of ``omega`` (or (N, 3)).

        Parameters
        ----------
        t : float
            Time, s.
        omega : ndarray, shape (3,) or (N, 3)
            Angular velocity, principal frame, rad/s (the torque does not depend on it).
        attitude : scipy Rotation, one or a stack of N
            Principal body frame to world.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.gravity import GravityGradient, lvlh_state
        >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
        >>> gg = GravityGradient(orbit_period=5400.0, moments=[1.0, 2.0, 3.0])
        >>> at_rest = lvlh_state(gg, body)   # major axis on the orbit normal, minor on the radius: no torque
        >>> bool(np.abs(gg(0.0, at_rest.omega0, at_rest.attitude)).max() < 1e-20)
        True
        >>> theta = 0.3   # pitched: 3 n^2 (I2 - I1) sin(theta) cos(theta) back about the orbit normal (-z)
        >>> s = lvlh_state(gg, body, pitch=theta)
        >>> tau = gg(0.0, s.omega0, s.attitude)
        >>> bool(np.allclose(tau, [0.0, 0.0, -3 * gg.mean_motion**2 * (2.0 - 1.0) * np.sin(theta) * np.cos(theta)]))
        True
        """
        I = self._moments()
        r_b = attitude.inv().apply(self.radial_direction(float(t)))
        tau_b = gradient_torque(r_b, I, self._n**2)
        return cast(Vector3, attitude.apply(tau_b))

    def jacobi_integral(self, t: ArrayLike, omega: ArrayLike, attitude: Rotation) -> FloatArray:
        """The orbiting-frame energy (Jacobi integral) ``h``, J; conserved along the motion.

        ``h = (1/2) w_r . I w_r - (1/2) n^2 o_b . I o_b + (3/2) n^2 r_b . I r_b`` with
        ``w_r = omega - n o_b`` (module docstring; Goldstein ch. 2, Hughes ch. 9).

        Parameters
        ----------
        t : float or ndarray, shape (n,)
            Times, s.
        omega : ndarray, shape (3,) or (n, 3)
            Angular velocity, principal frame, rad/s.
        attitude : scipy Rotation, one or a stack of n
            Principal body frame to world.

        Returns
        -------
        ndarray, shape () or (n,)

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.gravity import GravityGradient, lvlh_state
        >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
        >>> gg = GravityGradient(orbit_period=5400.0, moments=[1.0, 2.0, 3.0])
        >>> n, s = gg.mean_motion, lvlh_state(gg, body)   # at rest: h = -(1/2) n^2 I3 + (3/2) n^2 I1
        >>> bool(np.isclose(gg.jacobi_integral(0.0, s.omega0, s.attitude), n**2 * (-0.5 * 3.0 + 1.5 * 1.0)))
        True
        >>> s = lvlh_state(gg, body, pitch=0.5, roll=0.2)   # conserved along a libration
        >>> traj = tumble.simulate(body, s.omega0, attitude0=s.attitude0, torque=gg, t_end=3000.0, samples=4, method="dop853")
        >>> h = gg.jacobi_integral(traj.t, traj.omega, traj.attitude)
        >>> bool(np.allclose(h, h[0], rtol=1e-8))
        True
        """
        I, n = self._moments(), self._n
        q, w = attitude.as_quat(), np.asarray(omega, dtype=float)
        c: Any
        si: Any
        if q.ndim == 1 and w.shape == (3,) and I.ndim == 1 and np.ndim(t) == 0:  # one state: float arithmetic
            (x, y, z, s), (w0, w1, w2), (I0, I1, I2) = q.tolist(), w.tolist(), I.tolist()
            c, si = math.cos(n * float(cast(float, t))), math.sin(n * float(cast(float, t)))
        else:
            x, y, z, s, w0, w1, w2 = q[..., 0], q[..., 1], q[..., 2], q[..., 3], w[..., 0], w[..., 1], w[..., 2]
            I0, I1, I2 = I[..., 0], I[..., 1], I[..., 2]
            nt = n * np.asarray(t, dtype=float)
            c, si = np.cos(nt), np.sin(nt)
        r0, r1, r2 = to_body(x, y, z, s, c, si, 0.0)  # R^T r, r in the orbit plane
        o0, o1, o2 = to_body(x, y, z, s, 0.0, 0.0, 1.0)  # R^T (orbit normal)
        u0, u1, u2 = w0 - n * o0, w1 - n * o1, w2 - n * o2  # omega relative to the orbiting frame
        kinetic = I0 * u0 * u0 + I1 * u1 * u1 + I2 * u2 * u2
        potential = 3.0 * (I0 * r0 * r0 + I1 * r1 * r1 + I2 * r2 * r2) - (I0 * o0 * o0 + I1 * o1 * o1 + I2 * o2 * o2)
        return cast(FloatArray, np.asarray(0.5 * kinetic + 0.5 * n**2 * potential, dtype=float))

    def max_spin(self, t: float, omega: np.ndarray, attitude: Rotation) -> FloatArray:
        """An upper bound on ``|omega|`` (rad/s) over the whole motion from this state.

        The Jacobi integral ``h`` is conserved and ``o_b . I o_b <= I3``, ``r_b . I r_b >= I1``,
        so the relative kinetic energy ``T2 = (1/2) w_r . I w_r <= h + (1/2) n^2 I3 - (3/2) n^2 I1``
        for ever, and ``|omega| <= n + sqrt(2 T2_max / I1)``: at rest in the orbiting frame with
        the minor axis on the radius and the major axis on the orbit normal, exactly ``n``.
        Arguments as :meth:`jacobi_integral`; for bounding the work of a run.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.gravity import GravityGradient, lvlh_state
        >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
        >>> gg = GravityGradient(orbit_period=5400.0, moments=[1.0, 2.0, 3.0])
        >>> s = lvlh_state(gg, body)   # the stable equilibrium: the bound is exactly n
        >>> bool(np.isclose(gg.max_spin(0.0, s.omega0, s.attitude), gg.mean_motion))
        True
        >>> s = lvlh_state(gg, body, pitch=0.5)
        >>> bool(gg.max_spin(0.0, s.omega0, s.attitude) > np.linalg.norm(s.omega0))
        True
        """
        I, n = self._moments(), self._n
        h: Any = self.jacobi_integral(t, omega, attitude)
        # I1, I3 and h of each body (Python floats for one state: the same formula, ~10 us fewer)
        if I.ndim == 1 and np.ndim(h) == 0:
            h, low, high = float(h), min(I.tolist()), max(I.tolist())
        else:
            low, high = np.min(I, axis=-1), np.max(I, axis=-1)
        t2_max = h + 0.5 * n**2 * high - 1.5 * n**2 * low
        return cast(FloatArray, n + (2.0 * np.maximum(t2_max, 0.0) / low) ** 0.5)

    def kernel_form(self) -> tuple[int, tuple[float, ...]] | None:
        """The compiled engine's form (:class:`~tumble.dynamics.models.torques.KernelForm`): the
        mean motion (rad/s) of the circle; the engine reads the moments from the body it runs,
        the ones this model is bound to. None before :meth:`bind` (a model with no moments).

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> from tumble.dynamics.models.torques import KERNEL_CIRCULAR_GRAVITY
        >>> gg = GravityGradient(orbit_period=5400.0, moments=[1.0, 2.0, 3.0])
        >>> kind, (n,) = gg.kernel_form()
        >>> kind == KERNEL_CIRCULAR_GRAVITY, round(n * 5400.0 / math.pi, 12)
        (True, 2.0)
        """
        if self._I is None:
            return None
        return KERNEL_CIRCULAR_GRAVITY, (float(self._n),)

    def loop_form(self) -> tuple[float, float, Any] | None:
        """The compiled closed loop's form, ``(n, mu, orbit)``: the circle's mean motion ``n``
        (rad/s), no orbit to tabulate (``mu`` 0, ``orbit`` None; the loop reads the run's moments);
        None for a subclass with a law of its own.

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> n, mu, orbit = GravityGradient(orbit_period=5400.0).loop_form()
        >>> round(n * 5400.0 / math.pi, 12), mu, orbit
        (2.0, 0.0, None)
        """
        if type(self).__call__ is not GravityGradient.__call__:
            return None
        return float(self.mean_motion), 0.0, None

    def _moments(self) -> Vector3:
        if self._I is None:
            raise ValueError("this GravityGradient has no moments: use gg.bind(body) or give moments=[I1, I2, I3] (kg m^2)")
        return self._I


@functools.lru_cache(maxsize=64)
def _bound(model: GravityGradient, moments: bytes, shape: tuple[int, ...]) -> GravityGradient:
    """``model`` bound to the moments of these float64 bytes, kept for repeated runs of a body
    (the constructor's checks cost ~60 us); the models are frozen, so one can be shared."""
    I = np.frombuffer(moments).reshape(shape).copy()
    return replace(model, moments=cast("tuple[float, ...]", I.tolist() if I.ndim == 1 else I))


def gravity_gradient_in(torque: Any) -> GravityGradient | None:
    """The :class:`GravityGradient` acting in ``torque`` (itself, or a term of a sum or a list), or None.

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics.models.gravity import gravity_gradient_in
    >>> gg = tumble.GravityGradient(orbit_period=5400.0)
    >>> gravity_gradient_in([tumble.ConstantTorque((0.0, 0.0, 1e-6)), gg]) is gg, gravity_gradient_in(None)
    (True, None)
    """
    return next((term for term in terms_of(as_torque(torque)) if isinstance(term, GravityGradient)), None)
