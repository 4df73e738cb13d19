"""The orbiting (LVLH) frame of a circular orbit, a body's roll-pitch-yaw axes, and its attitude relative
to the frame.

The orbit is that of :class:`tumble.dynamics.models.gravity.GravityGradient`: radius
``(cos n t, sin n t, 0)`` in the world frame, normal +z, mean motion ``n`` (rad/s).

**Orbiting frame (LVLH).** Its axes, as columns in the world frame at time t:
roll ``x_o`` along the orbital velocity ``(-sin n t, cos n t, 0)``, pitch ``y_o`` along the
orbit normal ``(0, 0, 1)``, yaw ``z_o`` along the local vertical (the radius, pointing away from
the Earth) ``(cos n t, sin n t, 0)``; ``x_o x y_o = z_o``, so the frame is right-handed. (The
usual aerospace LVLH has z towards the Earth and y along the negative orbit normal; the
moments of inertia about an axis do not depend on its sign, so every result here holds there.)
The frame turns at ``n`` about +z: a body at rest in it has ``omega_world = n e_z``.

A body's *roll, pitch and yaw axes* are three of its principal axes: ``pitch_axis`` and
``yaw_axis`` (1, 2, 3 or "minor", "intermediate", "major") and the remaining one for roll.
Their moments are ``I_roll``, ``I_pitch``, ``I_yaw``. When (roll, pitch, yaw) is an odd
permutation of (1, 2, 3) the body's roll direction is *minus* its roll principal axis, so the
body's roll-pitch-yaw frame is right-handed. Its attitude relative to the orbiting frame is
given by a pitch-roll-yaw (2-1-3) sequence: a rotation by ``pitch`` about the orbit normal,
then by ``roll`` about the once-turned roll axis, then by ``yaw`` about the body's yaw axis
(scipy ``from_euler("YXZ", [pitch, roll, yaw])``); roll is the middle angle, so the sequence is
regular wherever ``|roll| < pi/2``, and a pure pitch libration is a pure pitch angle.
"""

from __future__ import annotations

import numbers
import warnings
from typing import TYPE_CHECKING, NamedTuple, Protocol

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import field_repr, fmt, plural, result_html, result_repr
from ...mass.body import properties_of
from ...typing import ArrayLike, FloatArray, Matrix3, Vector3
from ...validation import (
    AXES_ALLOWED,
    axis_index,
    check_vectors,
    short_repr,
)

if TYPE_CHECKING:
    from ...mass import Body, MassProperties

__all__ = ["LVLHState", "OrbitAngles", "lvlh_state", "orbit_frame_angles", "relative_attitude", "rpy_axes"]

#: The orbiting frame at t = 0: roll along +y_world (velocity), pitch along +z_world (orbit
#: normal), yaw along +x_world (radius).
_LVLH0 = Rotation.from_matrix([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


class _CircularOrbit(Protocol):
    """What this module reads of a :class:`~tumble.dynamics.models.gravity.GravityGradient`: the
    circular orbit's mean motion (rad/s) and its orbiting frame at ``t`` (s).

    A protocol, not the class: :mod:`tumble.dynamics.models.gravity` imports this module (and
    re-exports its names), and the import graph has no circles.
    """

    @property
    def mean_motion(self) -> float: ...
    def orbit_frame(self, t: ArrayLike) -> Rotation: ...


class _Run(Protocol):
    """What :func:`orbit_frame_angles` reads of a :class:`~tumble.dynamics.trajectory.Trajectory`:
    the sample times ``t`` (s) and the ``attitude`` (principal -> world). A protocol, not the
    class: the models lie below the trajectories (the import graph has no circles).
    """

    @property
    def t(self) -> FloatArray: ...
    @property
    def attitude(self) -> Rotation: ...


def _is_circular_orbit(gg: object) -> bool:
    """Whether ``gg`` gives what :class:`_CircularOrbit` lists: a number ``mean_motion`` and a
    callable ``orbit_frame`` (by duck typing; among tumble's models only a GravityGradient has both).

    Examples
    --------
    >>> from tumble.dynamics.models.gravity import GravityGradient
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.models.lvlh import _is_circular_orbit
    >>> _is_circular_orbit(GravityGradient(orbit_period=5400.0)), _is_circular_orbit(GravityGradient)
    (True, False)
    >>> _is_circular_orbit(CircularOrbit(altitude=500e3)), _is_circular_orbit(None)
    (False, False)
    """
    return isinstance(getattr(gg, "mean_motion", None), numbers.Real) and callable(getattr(gg, "orbit_frame", None))


def _axis(name: str, value: int | str) -> int:
    """0-based index of one public axis label (1, 2, 3 or a name), by :func:`~tumble.validation.axis_index`."""
    if np.ndim(value) != 0:
        raise ValueError(f"{name} = {short_repr(value)} must be {AXES_ALLOWED}")
    return int(axis_index(name, value))


def rpy_axes(pitch_axis: int | str, yaw_axis: int | str) -> tuple[tuple[int, int, int], Matrix3]:
    """The body's roll, pitch and yaw axes: principal indices and directions.

    The roll axis is the principal axis left over; when (roll, pitch, yaw) is an odd
    permutation of (1, 2, 3) the roll direction is minus that axis, so the three directions
    form a right-handed frame (module docstring).

    Parameters
    ----------
    pitch_axis, yaw_axis : {1, 2, 3, "minor", "intermediate", "major"}
        Principal axes along the orbit normal and the local vertical; they must differ.

    Returns
    -------
    indices : tuple of three ints
        0-based principal indices of the roll, pitch and yaw axes.
    matrix : ndarray, shape (3, 3)
        Columns: the roll, pitch and yaw directions in principal coordinates (a proper
        rotation, dimensionless).

    Raises
    ------
    ValueError
        If an axis is not one of the labels above, or the two are the same axis.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.lvlh import rpy_axes
    >>> (roll, pitch, yaw), P = rpy_axes(pitch_axis="major", yaw_axis="minor")
    >>> (roll, pitch, yaw)
    (1, 2, 0)
    >>> float(round(np.linalg.det(P)))
    1.0
    """
    b, c = _axis("pitch_axis", pitch_axis), _axis("yaw_axis", yaw_axis)
    if b == c:
        raise ValueError(
            f"pitch_axis = {pitch_axis!r} and yaw_axis = {yaw_axis!r} must be different principal axes "
            f"(together with the roll axis, a permutation of 1, 2, 3)"
        )
    a = 3 - b - c
    P = np.zeros((3, 3))
    P[a, 0], P[b, 1], P[c, 2] = 1.0, 1.0, 1.0
    P[a, 0] = np.linalg.det(P)  # -1 for an odd permutation: roll along minus its axis
    return (a, b, c), P


def _angles(name: str, value: ArrayLike) -> FloatArray:
    a = check_vectors(name, value, "rad", size=None)
    if a.ndim > 1:
        raise ValueError(f"{name} has shape {a.shape}; allowed: a number or a 1-d array (rad)")
    return a


class LVLHState(NamedTuple):
    """A body at rest in the orbiting frame at t = 0 (see :func:`lvlh_state`).

    Examples
    --------
    >>> import numpy as np
    >>> import tumble
    >>> from tumble.dynamics.models.gravity import GravityGradient, lvlh_state
    >>> gg = GravityGradient(orbit_period=5400.0)
    >>> s = lvlh_state(gg, tumble.t_handle(), yaw=0.4)
    >>> s._fields
    ('omega0', 'attitude0', 'attitude')
    >>> bool(np.allclose(s.attitude.apply(s.omega0), [0.0, 0.0, gg.mean_motion]))   # turning with the frame: n e_z
    True
    """

    #: Initial angular velocity, principal frame, rad/s: ``n e_z`` in the world frame.
    omega0: Vector3
    #: Design frame to world: what ``simulate(..., attitude0=...)`` takes.
    attitude0: Rotation
    #: Principal body frame to world (a Trajectory's ``attitude`` convention).
    attitude: Rotation

    def __repr__(self) -> str:  # one line: arrays by value when short, by shape otherwise
        return field_repr(self)


def lvlh_state(
    gg: _CircularOrbit, body: Body | MassProperties, *, roll: ArrayLike = 0.0, pitch: ArrayLike = 0.0,
    yaw: ArrayLike = 0.0, pitch_axis: int | str = 3, yaw_axis: int | str = 1,
) -> LVLHState:
    """Attitude and angular velocity of ``body`` at rest in the orbiting (LVLH) frame at t = 0.

    The body's roll, pitch and yaw axes (principal axes, module docstring) point along the
    orbital velocity, the orbit normal and the local vertical, turned by the pitch-roll-yaw
    sequence ``(pitch, roll, yaw)``; the body turns with the frame, ``omega_world = n e_z``.
    With all angles zero this is an equilibrium of the gravity-gradient torque for every choice
    of axes; the default (pitch = major, yaw = minor) is the Lagrange-stable one.

    Parameters
    ----------
    gg : GravityGradient
        The orbit (its mean motion n, rad/s).
    body : Body or MassProperties
        Gives the principal axes (principal -> design) for ``attitude0``.
    roll, pitch, yaw : float or ndarray, shape (N,)
        Offsets from the orbiting frame, rad; arrays broadcast and give stacks of N states.
    pitch_axis, yaw_axis : {1, 2, 3, "minor", "intermediate", "major"}
        Principal axes along the orbit normal and the radius; the third is the roll axis.

    Returns
    -------
    LVLHState
        ``omega0`` (principal frame, rad/s), ``attitude0`` (design -> world, for
        :func:`tumble.simulate`'s ``attitude0``) and ``attitude`` (principal -> world).

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics.models.gravity import GravityGradient
    >>> from tumble.dynamics.models.lvlh import lvlh_state
    >>> body = tumble.t_handle()
    >>> gg = GravityGradient(orbit_period=5400.0)
    >>> s = lvlh_state(gg, body, pitch=0.01)
    >>> traj = tumble.simulate(body, s.omega0, attitude0=s.attitude0, torque=gg.bind(body),
    ...                        t_end=5400.0, method="dop853")
    """
    if not _is_circular_orbit(gg):  # by its attributes: gravity.py imports this module, not the reverse
        raise ValueError(f"gg = {short_repr(gg)} must be a GravityGradient (a circular orbit's)")
    axes = properties_of(body).principal_axes
    _, P = rpy_axes(pitch_axis, yaw_axis)
    r, p, y = np.broadcast_arrays(_angles("roll", roll), _angles("pitch", pitch), _angles("yaw", yaw))
    rel = Rotation.from_euler("YXZ", np.stack([p, r, y], axis=-1))
    principal = _LVLH0 * rel * Rotation.from_matrix(P.T)
    omega0 = principal.inv().apply([0.0, 0.0, gg.mean_motion])
    design = principal * Rotation.from_matrix(np.asarray(axes, dtype=float)).inv()
    return LVLHState(omega0, design, principal)


def relative_attitude(
    gg: _CircularOrbit, t: ArrayLike, attitude: Rotation, *, pitch_axis: int | str = 3, yaw_axis: int | str = 1
) -> Rotation:
    """The body's roll-pitch-yaw frame to the orbiting frame at times ``t`` (s).

    ``attitude`` maps the principal frame to world (one rotation, or a stack matching ``t``).
    The identity means the body's yaw axis is on the local vertical, its pitch axis on the
    orbit normal.

    Examples
    --------
    >>> import numpy as np
    >>> import tumble
    >>> from tumble.dynamics.models.gravity import GravityGradient, lvlh_state, relative_attitude
    >>> gg, body = GravityGradient(orbit_period=5400.0), tumble.t_handle()
    >>> s = lvlh_state(gg, body, roll=0.1, pitch=0.2, yaw=0.3)
    >>> relative_attitude(gg, 0.0, s.attitude).as_euler("YXZ").round(12).tolist()   # pitch, roll, yaw back
    [0.2, 0.1, 0.3]
    >>> t = 1000.0   # carried round with the orbiting frame: the same relative attitude
    >>> moved = gg.orbit_frame(t) * gg.orbit_frame(0.0).inv() * s.attitude
    >>> relative_attitude(gg, t, moved).as_euler("YXZ").round(12).tolist()
    [0.2, 0.1, 0.3]
    """
    if not _is_circular_orbit(gg):  # an OrbitGravityGradient has no orbit_frame: an AttributeError named nothing
        raise ValueError(f"gg = {short_repr(gg)} must be a GravityGradient (a circular orbit's)")
    _, P = rpy_axes(pitch_axis, yaw_axis)
    return gg.orbit_frame(t).inv() * attitude * Rotation.from_matrix(P)


class OrbitAngles(NamedTuple):
    """Roll, pitch and yaw of a body relative to the orbiting frame, rad (pitch-roll-yaw sequence).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.gravity import OrbitAngles
    >>> angles = OrbitAngles(roll=np.zeros(2), pitch=np.array([0.01, -0.01]), yaw=np.zeros(2))
    >>> angles._fields, angles.pitch.tolist()
    (('roll', 'pitch', 'yaw'), [0.01, -0.01])
    """

    roll: FloatArray
    pitch: FloatArray
    yaw: FloatArray

    def _ranges(self) -> list[tuple[str, str]]:
        """(angle, its smallest to largest in deg) of each angle that has samples."""
        out: list[tuple[str, str]] = []
        for name in self._fields:
            x = np.degrees(np.asarray(getattr(self, name), float))
            if x.size:
                out.append((name, f"{fmt(np.min(x), 3)}..{fmt(np.max(x), 3)} deg"))
        return out

    def __repr__(self) -> str:
        """``OrbitAngles(3 samples, roll 0..0 deg, pitch -0.573..0.573 deg, yaw 0..0 deg)``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.lvlh import OrbitAngles
        >>> OrbitAngles(roll=np.zeros(3), pitch=np.array([0.01, 0.0, -0.01]), yaw=np.full(3, 0.5))
        OrbitAngles(3 samples, roll 0..0 deg, pitch -0.573..0.573 deg, yaw 28.6..28.6 deg)
        """
        return result_repr("OrbitAngles", [plural(np.size(self.pitch), "sample")]
                           + [f"{name} {span}" for name, span in self._ranges()])

    def _repr_html_(self) -> str:
        """Each angle's range as an HTML table (Jupyter).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.lvlh import OrbitAngles
        >>> "-0.573..0.573 deg" in OrbitAngles(np.zeros(2), np.array([0.01, -0.01]), np.zeros(2))._repr_html_()
        True
        """
        return result_html("OrbitAngles", [("samples", str(np.size(self.pitch))),
                                           *((f"{name}, smallest to largest", span) for name, span in self._ranges())])


def orbit_frame_angles(
    traj: _Run, gg: _CircularOrbit, *, pitch_axis: int | str = 3, yaw_axis: int | str = 1
) -> OrbitAngles:
    """Roll, pitch and yaw of a run relative to the orbiting (LVLH) frame, against ``traj.t``.

    Parameters
    ----------
    traj : Trajectory
        A run (its ``t``, s, and ``attitude``, principal -> world).
    gg : GravityGradient
        The orbit the run followed.
    pitch_axis, yaw_axis : {1, 2, 3, "minor", "intermediate", "major"}
        As in :func:`lvlh_state`.

    Returns
    -------
    OrbitAngles
        Arrays of shape (n,), rad: ``pitch`` and ``yaw`` in (-pi, pi], ``roll`` in
        [-pi/2, pi/2] (the sequence is singular at |roll| = pi/2).

    Examples
    --------
    >>> import numpy as np, tumble
    >>> body, gg = tumble.t_handle(), tumble.GravityGradient(orbit_period=5400.0)
    >>> s = tumble.lvlh_state(gg, body, pitch=0.01)   # 0.01 rad of pitch from the orbiting frame
    >>> traj = tumble.simulate(body, s.omega0, attitude0=s.attitude0, torque=gg, t_end=600.0, samples=3)
    >>> angles = tumble.orbit_frame_angles(traj, gg)
    >>> round(float(angles.pitch[0]), 6), round(float(angles.roll[0]), 6)
    (0.01, 0.0)
    >>> float(np.max(np.abs(angles.pitch))) < 0.011   # a pitch libration: bounded
    True
    """
    with warnings.catch_warnings():  # a tumbling body passes |roll| = pi/2; the docstring says so
        warnings.filterwarnings("ignore", message="Gimbal lock detected")
        pry = relative_attitude(gg, traj.t, traj.attitude, pitch_axis=pitch_axis, yaw_axis=yaw_axis).as_euler("YXZ")
    return OrbitAngles(pry[..., 1], pry[..., 0], pry[..., 2])
