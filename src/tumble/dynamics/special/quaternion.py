"""Quaternion algebra, scalar last as scipy (``[x, y, z, w]``), written out over arrays.

Written by hand rather than through scipy's ``Rotation``: the kernels call these on raw arrays
thousands of times (``Rotation``'s object costs tens of microseconds a call), and ``Rotation``
takes other arithmetic for one rotation than for a stack, whereas these do the same operations
element by element for any batch size (a body's run does not depend on its batch). Each is
tested against scipy. All broadcast over leading axes.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...jit import formula
from ...typing import ArrayLike, FloatOrArray, Quaternion, Vector3

__all__ = ["hamilton_components", "quat_conjugate", "quat_multiply", "quat_zxz", "quaternion_rate", "quaternion_rate_components", "rotate_by_quaternion",
           "rotate_components", "to_body", "turned_by"]


def rotate_by_quaternion(quat: ArrayLike, v: ArrayLike) -> Vector3:
    """``v`` rotated by unit quaternions ``quat`` (scalar last, as scipy): ``q v q*``.

    ``v' = v + 2 w (u x v) + 2 u x (u x v)`` for ``q = (u, w)`` (Shuster, J. Astronaut. Sci. 41
    (1993) 439, the rotation formula expanded); broadcasts over leading axes.

    Parameters
    ----------
    quat : array_like, shape (..., 4)
        Unit quaternions ``[x, y, z, w]``.
    v : array_like, shape (..., 3)
        Vectors.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.quaternion import rotate_by_quaternion
    >>> quarter_z = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]   # 90 degrees about z
    >>> rotate_by_quaternion(quarter_z, [1.0, 0.0, 0.0]).round(6).tolist()
    [0.0, 1.0, 0.0]
    """
    q = np.asarray(quat, float)
    x = np.asarray(v, float)
    q, x = np.broadcast_arrays(q, x[..., [0, 1, 2, 0]])
    return np.stack(rotate_components(q[..., 0], q[..., 1], q[..., 2], q[..., 3], x[..., 0], x[..., 1], x[..., 2]),
                    axis=-1)


def rotate_components(x: Any, y: Any, z: Any, w: Any, v0: Any, v1: Any, v2: Any) -> tuple[Any, Any, Any]:
    """``v`` turned by the unit quaternion ``(x, y, z, w)`` component by component, the one writing
    of :func:`rotate_by_quaternion`'s formula ``v + 2 w (u x v) + 2 u x (u x v)`` (Shuster 1993),
    over floats (the compiled kernels; the conjugate ``(-x, -y, -z, w)`` gives ``R^T v``) or
    arrays of one shape.

    Examples
    --------
    >>> from tumble.dynamics.special.quaternion import rotate_components
    >>> c = 0.5 ** 0.5   # 90 degrees about z
    >>> [round(u, 12) + 0.0 for u in rotate_components(0.0, 0.0, c, c, 1.0, 0.0, 0.0)]
    [0.0, 1.0, 0.0]
    """
    c0, c1, c2 = y * v2 - z * v1, z * v0 - x * v2, x * v1 - y * v0  # u x v
    d0, d1, d2 = y * c2 - z * c1, z * c0 - x * c2, x * c1 - y * c0  # u x (u x v)
    return v0 + 2.0 * (w * c0 + d0), v1 + 2.0 * (w * c1 + d1), v2 + 2.0 * (w * c2 + d2)


def quat_multiply(a: ArrayLike, b: ArrayLike) -> Quaternion:
    """Hamilton product ``a (x) b`` of quaternions, scalar last (scipy: ``Ra * Rb``).

    ``(u, w)(v, s) = (w v + s u + u x v, w s - u . v)`` (Shuster, J. Astronaut. Sci. 41 (1993)
    439); broadcasts over leading axes; shapes (..., 4).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.special.quaternion import quat_multiply
    >>> a, b = Rotation.from_euler("x", 30, degrees=True), Rotation.from_euler("y", 40, degrees=True)
    >>> bool(np.allclose(quat_multiply(a.as_quat(), b.as_quat()), (a * b).as_quat()))   # scipy's a * b
    True
    """
    qa, qb = np.asarray(a, float), np.asarray(b, float)
    out = np.empty(np.broadcast_shapes(qa.shape, qb.shape))
    out[..., 0], out[..., 1], out[..., 2], out[..., 3] = hamilton_components(*np.moveaxis(qa, -1, 0), *np.moveaxis(qb, -1, 0))
    return out


@formula
def hamilton_components(x1: FloatOrArray, y1: FloatOrArray, z1: FloatOrArray, s1: FloatOrArray, x2: FloatOrArray,
                        y2: FloatOrArray, z2: FloatOrArray, s2: FloatOrArray) -> tuple[Any, Any, Any, Any]:
    """The Hamilton product of two quaternions by components, scalar last.

    ``(x1, y1, z1, s1) (x2, y2, z2, s2)``, as ``(u, w)(v, s) = (w v + s u + u x v, w s - u.v)``
    (Shuster, J. Astronaut. Sci. 41 (1993) 439). Plain floats or arrays (element by element); compiled code calls it by name (:func:`tumble.jit.formula`):
    :func:`quat_multiply`, :func:`turned_by` and the kernels' products are this one writing.

    Examples
    --------
    >>> from tumble.dynamics.special.quaternion import hamilton_components
    >>> hamilton_components(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0)   # i j = k
    (0.0, 0.0, 1.0, 0.0)
    """
    return (s1 * x2 + s2 * x1 + y1 * z2 - z1 * y2, s1 * y2 + s2 * y1 + z1 * x2 - x1 * z2,
            s1 * z2 + s2 * z1 + x1 * y2 - y1 * x2, s1 * s2 - x1 * x2 - y1 * y2 - z1 * z2)


def quat_conjugate(q: ArrayLike) -> Quaternion:
    """The inverse of unit quaternions, scalar last.

    Examples
    --------
    >>> from tumble.dynamics.special.quaternion import quat_conjugate, quat_multiply
    >>> q = [0.5, 0.5, 0.5, 0.5]
    >>> quat_conjugate(q).tolist(), quat_multiply(q, quat_conjugate(q)).tolist()   # q q* = 1
    ([-0.5, -0.5, -0.5, 0.5], [0.0, 0.0, 0.0, 1.0])
    """
    out = np.array(q, float)
    out[..., :3] *= -1.0
    return out


def quat_zxz(phi: FloatOrArray, theta: FloatOrArray, psi: FloatOrArray) -> Quaternion:
    """``Rz(phi) Rx(theta) Rz(psi)`` (intrinsic z-x-z Euler angles, rad) as quaternions, scalar
    last: the product of the three elementary quaternions written out,
    ``(sb (ca cc + sa sc), sb (sa cc - ca sc), cb (sa cc + ca sc), cb (ca cc - sa sc))`` with
    ``sa, ca = sin, cos(phi/2)``, ``sb, cb`` of ``theta/2``, ``sc, cc`` of ``psi/2`` (each angle
    on its own, so a large ``phi`` costs no more than its own rounding); shape
    ``broadcast(phi, theta, psi) + (4,)``.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.special.quaternion import quat_zxz
    >>> q = quat_zxz(0.3, 0.5, 0.7)
    >>> bool(np.allclose(Rotation.from_quat(q).as_matrix(), Rotation.from_euler("ZXZ", [0.3, 0.5, 0.7]).as_matrix()))
    True
    """
    sa, ca = np.sin(0.5 * phi), np.cos(0.5 * phi)
    sb, cb = np.sin(0.5 * theta), np.cos(0.5 * theta)
    sc, cc = np.sin(0.5 * psi), np.cos(0.5 * psi)
    return np.stack([sb * (ca * cc + sa * sc), sb * (sa * cc - ca * sc), cb * (sa * cc + ca * sc), cb * (ca * cc - sa * sc)],
                    axis=-1)


def quaternion_rate(quat: ArrayLike, omega: ArrayLike) -> Quaternion:
    """Time derivative of the attitude quaternion for body-frame angular velocity.

    ``q' = q (x) (omega, 0) / 2``, written out for scalar-last quaternions ``(v, s)``:
    ``v' = (s omega + v x omega) / 2``, ``s' = -(v . omega) / 2`` (Shuster 1993).
    With ``R(q)`` mapping body to world this is ``R' = R [omega]_x``.

    Parameters
    ----------
    quat : array_like, shape (..., 4)
        Unit quaternion ``[x, y, z, w]``, body to world.
    omega : array_like, shape (..., 3)
        Angular velocity in the body frame, rad/s.

    Examples
    --------
    >>> from tumble.dynamics.special.quaternion import quaternion_rate
    >>> quaternion_rate([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 2.0]).tolist()   # q' = q (x) (omega, 0) / 2
    [0.0, 0.0, 1.0, -0.0]
    """
    q = np.asarray(quat, float)
    w = np.asarray(omega, float)
    if q.shape == (4,) and w.shape == (3,):  # one instant (a Python right-hand side's every call): the
        # same formula over plain floats, bit for bit, numpy's broadcasting left out
        return np.array(quaternion_rate_components(*q.tolist(), *w.tolist()))
    q, w = np.broadcast_arrays(q, w[..., [0, 1, 2, 0]])
    return np.stack(quaternion_rate_components(q[..., 0], q[..., 1], q[..., 2], q[..., 3],
                                               w[..., 0], w[..., 1], w[..., 2]), axis=-1)


@formula
def quaternion_rate_components(x: Any, y: Any, z: Any, s: Any, w0: Any, w1: Any,
                               w2: Any) -> tuple[Any, Any, Any, Any]:
    """``q' = q (x) (omega, 0) / 2`` component by component, the one writing of the kinematics.

    For ``q = (v, s)`` (scalar last) and body-frame ``omega``: ``v' = (s omega + v x omega) / 2``,
    ``s' = -(v . omega) / 2`` (Shuster, J. Astronaut. Sci. 41 (1993) 439, eq. 305). Floats (the
    compiled engine) or arrays of one shape (:func:`quaternion_rate` calls it on columns).

    Examples
    --------
    >>> from tumble.dynamics.special.quaternion import quaternion_rate_components
    >>> quaternion_rate_components(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 2.0)
    (0.0, 0.0, 1.0, -0.0)
    """
    return (0.5 * (s * w0 + (y * w2 - z * w1)), 0.5 * (s * w1 + (z * w0 - x * w2)),
            0.5 * (s * w2 + (x * w1 - y * w0)), -0.5 * (x * w0 + y * w1 + z * w2))


@formula
def to_body(x: Any, y: Any, z: Any, s: Any, v0: Any, v1: Any, v2: Any) -> tuple[Any, Any, Any]:
    """``R^T v``, the world vector ``v`` in the body frame of the quaternion ``(x, y, z, s)``.

    ``R`` (body to world) from the quaternion, scalar last, Shuster 1993 eq. 161, here
    transposed, in its homogeneous form (the diagonal ``s^2 + x^2 - y^2 - z^2``, ..., not
    ``1 - 2 (y^2 + z^2)``): for a quaternion that is not normalised it is exactly ``|q|^2`` times
    the rotation of ``q / |q|``, so a caller divides by ``|q|^2`` (or ``|q|^4`` for a product of
    two) instead of normalising ``q`` first. Floats (the compiled kernels) or arrays of one shape.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.quaternion import to_body
    >>> c = float(np.sqrt(0.5))   # 90 degrees about z: world x is body -y
    >>> [round(float(u), 12) + 0.0 for u in to_body(0.0, 0.0, c, c, 1.0, 0.0, 0.0)]   # + 0.0: no -0.0
    [0.0, -1.0, 0.0]
    """
    ss, xx, yy, zz = s * s, x * x, y * y, z * z
    return ((ss + xx - yy - zz) * v0 + 2 * (x * y + z * s) * v1 + 2 * (x * z - y * s) * v2,
            2 * (x * y - z * s) * v0 + (ss - xx + yy - zz) * v1 + 2 * (y * z + x * s) * v2,
            2 * (x * z + y * s) * v0 + 2 * (y * z - x * s) * v1 + (ss - xx - yy + zz) * v2)


def turned_by(x: float, y: float, z: float, s: float, r0: float, r1: float, r2: float) -> tuple[float, float, float, float]:
    """``q (x) exp(r / 2)``: the unit quaternion ``(x, y, z, s)`` (scalar last, body to world) turned
    by the rotation vector ``r`` (rad) about its own (body) axes, as scipy's ``attitude *
    Rotation.from_rotvec(r)``. The rotation vector's quaternion is ``(sin(a/2) r / a, cos(a/2))``,
    ``a = |r|``, its series ``1/2 - a^2 / 48`` below 1e-4 rad, and the Hamilton product (Markley &
    Crassidis 2014, eqs. 2.82 and 2.126). Plain floats: the sensors in Python and the compiled
    loops call it (a small noise rotation of a reading).

    Examples
    --------
    >>> from tumble.dynamics.special.quaternion import turned_by
    >>> [round(v, 12) for v in turned_by(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1)]   # 0.1 rad about z
    [0.0, 0.0, 0.049979169271, 0.998750260395]
    """
    a = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
    k = math.sin(0.5 * a) / a if a > 1e-4 else 0.5 - a * a / 48.0
    return hamilton_components(x, y, z, s, k * r0, k * r1, k * r2, math.cos(0.5 * a))
