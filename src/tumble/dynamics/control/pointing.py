"""Pointing targets for MRP feedback: a frame fixed in the world, or a moving reference such as nadir.

A *reference* is any object with ``attitude(t)`` (the reference frame R to world, a scipy
``Rotation``; a stack for an array of times), ``rate(t)`` (its angular velocity ``omega_r``,
world frame, rad/s) and optionally ``rate_derivative(t)`` (``d omega_r / dt``, world frame,
rad/s^2; zero when absent) (:class:`Reference`). A fixed ``Rotation`` is the special case
``omega_r = 0``.

**Tracking errors** (Schaub & Junkins, *Analytical Mechanics of Space Systems*, 4th ed., sec.
8.3, the MRP tracking problem): ``sigma = sigma_B/R`` the MRPs of the body frame B relative to R
(short set) and ``delta_omega = omega - [BR] omega_r`` in the body frame. The feed-forward of the
tracking law needs the reference's angular acceleration as the body sees it,
``B d(omega_r)/dt = omega_r' - omega x omega_r`` (all in B; ``omega_r'`` the inertial
derivative), so that with ``L_r = -K sigma - P delta_omega + I_RW (omega_r' - omega x omega_r)
+ omega x (I omega + h)`` the wheel-driven body obeys ``I_RW B d(delta_omega)/dt = -K sigma -
P delta_omega + tau_ext`` (:class:`~tumble.dynamics.control.controllers.MRPFeedback`): the Lyapunov
function ``V = 2 K ln(1 + |sigma|^2) + delta_omega . I_RW delta_omega / 2`` has
``V' = -delta_omega . P delta_omega`` without disturbance.

**The integral term** (sec. 8.4's integral feedback; Basilisk's ``mrpFeedback`` with ``Ki`` and
``integralLimit``): :class:`~tumble.dynamics.control.controllers.MRPFeedback` with ``Ki > 0`` (1/s) adds
``-z``, ``z = Ki K sum_j sigma_j dt`` over the earlier control steps (N m), each component held
within ``integral_limit`` (anti-windup). Per axis, linearised (``sigma ~ theta / 4``),
``I_RW theta'' + P theta' + (K / 4) (theta + Ki int theta dt) = tau``: stable for ``Ki < P / I_RW``
(Routh), and a constant disturbance ``tau`` leaves no steady error where PD leaves
``sigma = tau / K`` (``theta ~ 4 tau / K``). This ``z`` is the plain PID form: the book's (and
Basilisk's) integral variable also carries an inertia-weighted rate part, so their ``Ki`` is not
this one.

**Nadir** (:class:`NadirTarget`): on a circular orbit the world frame of a control run is the
orbit-plane frame (:mod:`~tumble.dynamics.environment.orbit`): the radius at ``t`` is
``(cos n t, sin n t, 0)``, the orbit normal +z. The target puts one body axis on nadir
(``-radius``) and another on the orbit normal: ``R(t) = R_z(n t) R(0)``, ``omega_r = n z``
(constant, ``omega_r' = 0``). The default, the minor axis on nadir and the major axis on the
orbit normal (the intermediate axis along the velocity), is the gravity-gradient stable
attitude (the Lagrange region; :mod:`~tumble.analysis.gravity_stability`): there the gravity
gradient exerts no torque and the wheels hold the body with none of their momentum. Along an
ellipse or a TLE's orbit (world frame ECI or TEME) the target follows the orbit's nadir frame
(:mod:`~tumble.dynamics.environment.local_frame`): ``R(t)`` from the position and velocity, the
rate ``h / |r|^2 + ((a . h) / |h|^2) r``, faster at the perigee, and its derivative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Protocol, TypeGuard, runtime_checkable

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import Headline, headline_html, headline_repr
from ...typing import ArrayLike, FloatArray
from ...validation import axis_index, check_positive, check_rotation
from ..environment.local_frame import nadir_frame, orbit_frame_acceleration, orbit_frame_rate
from ..environment.orbit import CircularOrbit
from ..special.mrp import mrp_from_quat

__all__ = ["NadirTarget", "Reference", "TrackingError", "axis_direction", "check_square", "is_reference", "reference_table",
           "target_attitude", "tracking_error"]


@runtime_checkable
class Reference(Protocol):
    """A moving target: ``attitude(t)`` (reference frame to world) and ``rate(t)`` (world frame, rad/s).

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.pointing import NadirTarget, Reference
    >>> isinstance(NadirTarget(1e-3), Reference), isinstance(Rotation.identity(), Reference)
    (True, False)
    """

    def attitude(self, t: ArrayLike) -> Rotation:
        """The reference frame to world at ``t`` (s).

        Examples
        --------
        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> NadirTarget(1e-3).attitude([0.0, 1.0]).single
        False
        """
        ...

    def rate(self, t: ArrayLike) -> FloatArray:
        """The reference's angular velocity ``omega_r`` at ``t`` (s), world frame, rad/s.

        Examples
        --------
        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> NadirTarget(1e-3).rate(0.0).tolist()
        [0.0, 0.0, 0.001]
        """
        ...


def is_reference(target: object) -> TypeGuard[Reference]:
    """Whether ``target`` is a moving reference (:class:`Reference`) rather than a fixed attitude.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.pointing import NadirTarget, is_reference
    >>> is_reference(NadirTarget(1e-3)), is_reference(Rotation.identity()), is_reference([0, 0, 0, 1])
    (True, False, False)
    """
    return not isinstance(target, Rotation) and isinstance(target, Reference)


def target_attitude(target: Rotation | Reference | ArrayLike, t: ArrayLike) -> Rotation:
    """The target frame to world at ``t`` (s): a fixed ``Rotation`` itself (a quaternion, scalar last,
    or a rotation matrix is made one, :func:`~tumble.validation.check_rotation`), or ``target.attitude(t)``.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.pointing import NadirTarget, target_attitude
    >>> fixed = Rotation.from_rotvec([0.0, 0.0, 0.3])
    >>> target_attitude(fixed, [0.0, 5.0]) is fixed
    True
    >>> nadir = NadirTarget(0.01)   # turns n t = 1 rad in 100 s
    >>> round(float((target_attitude(nadir, 100.0) * target_attitude(nadir, 0.0).inv()).magnitude()), 12)
    1.0
    >>> target_attitude([0.0, 0.0, 1.0, 0.0], 0.0).as_rotvec().round(6).tolist()   # half a turn about z
    [0.0, 0.0, 3.141593]
    """
    if is_reference(target):  # a TypeGuard: target is a Reference here
        return target.attitude(t)
    if isinstance(target, Rotation):
        return target
    return Rotation.from_quat(check_rotation("target", target))


@dataclass(frozen=True)
class TrackingError:
    """The errors and feed-forward of one control step, body frame (module docstring).

    Attributes
    ----------
    sigma : ndarray, shape (3,)
        MRPs of the body relative to the reference, short set.
    delta_omega : ndarray, shape (3,)
        ``omega - [BR] omega_r``, rad/s.
    omega_r : ndarray, shape (3,)
        ``[BR] omega_r``, the reference's rate in the body frame, rad/s.
    omega_r_dot : ndarray, shape (3,)
        The inertial derivative of ``omega_r``, body frame, rad/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.pointing import tracking_error
    >>> e = tracking_error(Rotation.identity(), 0.0, Rotation.identity(), np.array([0.0, 0.0, 0.1]))
    >>> e.sigma.tolist(), e.delta_omega.tolist(), e.omega_r.tolist()
    ([0.0, 0.0, 0.0], [0.0, 0.0, 0.1], [0.0, 0.0, 0.0])
    """

    HEADLINE: ClassVar[Headline] = (("sigma", "sigma", ""), ("delta_omega", "delta omega", "rad/s"),
                                    ("omega_r", "omega_r", "rad/s"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    sigma: FloatArray
    delta_omega: FloatArray
    omega_r: FloatArray
    omega_r_dot: FloatArray


def tracking_error(target: Rotation | Reference, t: float, attitude: Rotation, omega: FloatArray) -> TrackingError:
    """``sigma_B/R``, ``delta_omega``, ``omega_r`` and ``omega_r'`` (body frame) at ``t`` (s).

    Parameters
    ----------
    target : scipy Rotation or Reference
        A fixed target frame (to world) or a moving reference.
    t : float
        Time, s.
    attitude : scipy Rotation
        The body's principal frame to world.
    omega : ndarray, shape (3,)
        The body's angular velocity, principal frame, rad/s.

    Examples
    --------
    On the nadir reference and turning with it, both errors are zero:

    >>> import numpy as np
    >>> from tumble.dynamics.control.pointing import NadirTarget, tracking_error
    >>> nadir = NadirTarget(1e-3)
    >>> R = nadir.attitude(50.0)
    >>> e = tracking_error(nadir, 50.0, R, R.inv().apply(nadir.rate(50.0)))
    >>> bool(np.abs(e.sigma).max() < 1e-15), bool(np.abs(e.delta_omega).max() < 1e-18)
    (True, True)
    """
    w = np.asarray(omega, dtype=np.float64)
    if not is_reference(target):
        zero = np.zeros(3)
        fixed: Rotation = target
        return TrackingError(np.asarray(mrp_from_quat((fixed.inv() * attitude).as_quat()), dtype=np.float64), w, zero, zero)
    ref = target
    R = ref.attitude(t)
    sigma = np.asarray(mrp_from_quat((R.inv() * attitude).as_quat()), dtype=np.float64)
    to_body = attitude.inv()
    w_r = np.asarray(to_body.apply(ref.rate(t)), dtype=np.float64)
    derivative = getattr(ref, "rate_derivative", None)
    w_r_dot = np.zeros(3) if derivative is None else np.asarray(to_body.apply(derivative(t)), dtype=np.float64)
    return TrackingError(sigma, w - w_r, w_r, w_r_dot)


#: A fixed target's table: no rows (shared; writable, as a reference's own table is, so that the
#: kernels are compiled for one type of table).
_NO_REFERENCE = np.zeros((0, 10))


def reference_table(target: Reference | None, t: ArrayLike) -> FloatArray:
    """A moving reference at the instants ``t`` (s), a row each (the compiled loop's tracking law
    reads them): its frame to world as a unit quaternion (scalar last), its rate ``omega_r`` and its
    rate's derivative ``omega_r'`` (world frame, rad/s and rad/s^2; zero without
    ``rate_derivative``), shape ``(len(t), 10)``; no rows for None (a fixed target).

    Examples
    --------
    >>> from tumble.dynamics.control.pointing import NadirTarget, reference_table
    >>> table = reference_table(NadirTarget(1e-3), [0.0, 10.0, 20.0])
    >>> table.shape, table[:, 6].tolist()   # omega_r = n z
    ((3, 10), [0.001, 0.001, 0.001])
    >>> reference_table(None, [0.0, 1.0]).shape
    (0, 10)
    """
    if target is None:
        return _NO_REFERENCE
    times = np.atleast_1d(np.asarray(t, dtype=np.float64))
    try:  # the protocol's stacks for an array of times
        return _rows(target, times)
    except (ValueError, TypeError, IndexError):  # a reference of one's own that takes one time at a time
        return np.concatenate([_rows(target, float(ti)) for ti in times]) if len(times) else np.zeros((0, 10))


def _rows(target: Reference, times: ArrayLike) -> FloatArray:
    """:func:`reference_table`'s rows at ``times`` (an array, or one float)."""
    n = np.size(times)
    derivative = getattr(target, "rate_derivative", None)
    rows = np.zeros((n, 10))
    rows[:, :4] = np.reshape(np.asarray(target.attitude(times).as_quat(), dtype=np.float64), (n, 4))
    rows[:, 4:7] = np.broadcast_to(np.asarray(target.rate(times), dtype=np.float64), (n, 3))
    if derivative is not None:
        rows[:, 7:10] = np.broadcast_to(np.asarray(derivative(times), dtype=np.float64), (n, 3))
    return rows


def axis_direction(name: str, value: int | str | ArrayLike) -> FloatArray:
    """The unit vector of a principal axis label (1, 2, 3, "minor", "intermediate", "major") or of a
    nonzero 3-vector (normalised).

    Examples
    --------
    >>> from tumble.dynamics.control.pointing import axis_direction
    >>> axis_direction("nadir_axis", "major").tolist(), axis_direction("nadir_axis", [0.0, 3.0, 4.0]).tolist()
    ([0.0, 0.0, 1.0], [0.0, 0.6, 0.8])
    """
    if np.ndim(value) == 0:
        e = np.zeros(3)
        e[axis_index(name, value)] = 1.0
        return e
    v = np.asarray(value, float)
    if v.shape != (3,) or not np.all(np.isfinite(v)) or not np.linalg.norm(v) > 0.0:
        raise ValueError(f"{name} = {value!r} must be 1, 2, 3, minor, intermediate, major or a nonzero 3-vector "
                         "(principal frame)")
    return np.asarray(v / np.linalg.norm(v), dtype=np.float64)


def check_square(nadir: FloatArray, normal: FloatArray, nadir_given: object, normal_given: object) -> None:
    """Refuse a nadir and a normal axis (unit vectors, in one frame) that are not square to each
    other, naming each as the user gave it (``nadir_given``, ``normal_given``: a label or a vector
    in whatever frame the user wrote it).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.pointing import check_square
    >>> check_square(np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]), "minor", "major")   # square: nothing
    >>> check_square(np.array([1.0, 0.0, 0.0]), np.sqrt([0.5, 0.0, 0.5]), [1, 0, 0], [1, 0, 1])
    Traceback (most recent call last):
    ...
    ValueError: normal_axis = [1, 0, 1] must be square to nadir_axis = [1, 0, 0] (their angle is 45 deg)
    """
    cosine = float(nadir @ normal)
    if abs(cosine) > 1e-9:
        angle = math.degrees(math.acos(max(-1.0, min(1.0, cosine))))
        raise ValueError(f"normal_axis = {normal_given!r} must be square to nadir_axis = {nadir_given!r} "
                         f"(their angle is {angle:.3g} deg)")


@dataclass(frozen=True)
class NadirTarget:
    """A body axis on nadir and another on the orbit normal, along the orbit (module docstring).

    Parameters
    ----------
    orbit : float or orbit
        The orbit's mean motion ``n`` (rad/s, > 0) for a circular orbit in its orbit-plane frame; a
        :class:`~tumble.dynamics.environment.orbit.CircularOrbit` or
        :class:`~tumble.dynamics.models.gravity.GravityGradient` (its ``mean_motion``, the same);
        or any other orbit with ``position_world``, ``velocity_world`` and ``mean_motion`` (a
        :class:`~tumble.dynamics.environment.ephemeris.KeplerOrbit` or
        :class:`~tumble.dynamics.environment.ephemeris.TLEOrbit`, or a torque model on one, such as
        ``gravity_gradient_of(orbit)``), followed in its inertial world frame.
    nadir_axis : {1, 2, 3, "minor", "intermediate", "major"} or array_like, shape (3,)
        The body axis (principal frame) to point at nadir, ``-radius`` (default "minor").
    normal_axis : same
        The body axis along the orbit normal, ``r x v`` (default "major"); square to ``nadir_axis``.

    Examples
    --------
    The minor axis (1) looks down, the major (3) along the orbit normal; a quarter orbit on, nadir is -y:

    >>> import math
    >>> import numpy as np
    >>> from tumble.dynamics.control.pointing import NadirTarget
    >>> nadir = NadirTarget(2 * math.pi / 5400.0)
    >>> np.round(nadir.attitude(0.0).apply([[1.0, 0, 0], [0, 0, 1.0]]), 12).tolist()
    [[-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    >>> np.round(nadir.attitude(1350.0).apply([1.0, 0.0, 0.0]), 12).tolist()
    [-0.0, -1.0, 0.0]

    On an ellipse the minor axis stays on nadir, and the target turns faster at the perigee (t = 0
    here) than the mean motion:

    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> orbit = KeplerOrbit(8000e3, 0.1, 0.9)
    >>> nadir = NadirTarget(orbit)
    >>> r = orbit.position_world(2000.0)
    >>> bool(np.allclose(nadir.attitude(2000.0).apply([1.0, 0, 0]), -r / np.linalg.norm(r), atol=1e-14))
    True
    >>> round(float(np.linalg.norm(nadir.rate(0.0)) / orbit.mean_motion), 6)   # (1 + e)^2 / (1 - e^2)^1.5
    1.22838
    >>> NadirTarget(1e-3, nadir_axis=[1.0, 1.0, 0.0], normal_axis=[1.0, 0.0, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: normal_axis = [1.0, 0.0, 0.0] must be square to nadir_axis = [1.0, 1.0, 0.0] (their angle is 45 deg)
    """

    orbit: object
    nadir_axis: int | str | ArrayLike = "minor"
    normal_axis: int | str | ArrayLike = "major"

    def __post_init__(self) -> None:
        inner = getattr(self.orbit, "orbit", None)   # a torque model along an orbit: the orbit
        source = self.orbit if inner is None else inner
        follows = (not isinstance(source, CircularOrbit) and callable(getattr(source, "position_world", None))
                   and callable(getattr(source, "velocity_world", None)))
        n = self.orbit if isinstance(self.orbit, (int, float)) else getattr(source, "mean_motion", None)
        object.__setattr__(self, "_n", check_positive("orbit.mean_motion", n, "rad/s"))
        object.__setattr__(self, "_path", source if follows else None)   # None: the circle's closed form
        a = axis_direction("nadir_axis", self.nadir_axis)
        b = axis_direction("normal_axis", self.normal_axis)
        check_square(a, b, self.nadir_axis, self.normal_axis)
        # the target's axes (nadir, normal, nadir x normal) in the principal frame, as columns
        body = np.column_stack([a, b, np.cross(a, b)])
        object.__setattr__(self, "_body", body)
        # R(0) (principal to world) on the circle: a -> -x (nadir at t = 0), b -> +z, a x b -> (-x) x z = +y
        world = np.array([[-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]).T
        object.__setattr__(self, "_r0", Rotation.from_matrix(world @ body.T))

    @property
    def mean_motion(self) -> float:
        """The orbit's mean motion ``n``, rad/s.

        Examples
        --------
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> orbit = CircularOrbit(altitude=500e3)
        >>> NadirTarget(orbit).mean_motion == orbit.mean_motion
        True
        """
        return float(self._n)  # type: ignore[attr-defined]

    def attitude(self, t: ArrayLike) -> Rotation:
        """The target frame (the body's principal axes on target) to world: ``R_z(n t) R(0)`` on a
        circle, the orbit's nadir frame times the body's axes along any other orbit.

        Examples
        --------
        The nadir axis follows ``-(cos n t, sin n t, 0)``:

        >>> import numpy as np
        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> nadir = NadirTarget(1e-3, nadir_axis="major", normal_axis="minor")
        >>> t = np.array([0.0, 700.0])
        >>> np.allclose(nadir.attitude(t).apply([0.0, 0.0, 1.0]), -np.stack([np.cos(1e-3 * t), np.sin(1e-3 * t), 0 * t], -1))
        True
        """
        path = self._path  # type: ignore[attr-defined]
        if path is not None:
            axes = nadir_frame(path.position_world(t), path.velocity_world(t))
            return Rotation.from_matrix(axes @ self._body.T)  # type: ignore[attr-defined]
        nt = self.mean_motion * np.asarray(t, dtype=float)
        return Rotation.from_rotvec(nt[..., None] * np.array([0.0, 0.0, 1.0])) * self._r0  # type: ignore[attr-defined]

    def rate(self, t: ArrayLike) -> FloatArray:
        """``omega_r``, world frame, rad/s (shape ``t.shape + (3,)``): ``n z`` on a circle, the
        nadir frame's rate along any other orbit.

        Examples
        --------
        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> NadirTarget(1e-3).rate([0.0, 1.0]).tolist()
        [[0.0, 0.0, 0.001], [0.0, 0.0, 0.001]]
        """
        path = self._path  # type: ignore[attr-defined]
        if path is not None:
            return orbit_frame_rate(path, t)
        shape = np.shape(t)
        return np.broadcast_to(np.array([0.0, 0.0, self.mean_motion]), shape + (3,)).copy()

    def rate_derivative(self, t: ArrayLike) -> FloatArray:
        """``d omega_r / dt``, world frame, rad/s^2: zero on a circle, the nadir frame's angular
        acceleration along any other orbit.

        Examples
        --------
        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> NadirTarget(1e-3).rate_derivative(0.0).tolist()
        [0.0, 0.0, 0.0]
        """
        path = self._path  # type: ignore[attr-defined]
        if path is not None:
            return orbit_frame_acceleration(path, t)
        return np.zeros(np.shape(t) + (3,))
