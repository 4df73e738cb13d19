"""Omega alone of many free rigid bodies in double precision, each on its own times, for inner loops.

The closed form is that of :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz, *Mechanics*,
sec. 37; its module docstring states it, with ``g_j = sum_i I_i (I_i - I_j) w_i^2``)::

    g2 > 0:  w1 = s a1 cn(u),  w2 = a2 sn(u),  w3 = s a3 dn(u)          (about the major axis)
    g2 < 0:  w1 = s a1 dn(u),  w2 = a2 sn(u),  w3 = s a3 cn(u)          (about the minor axis)
    u = u0 + p t,  p > 0 (Euler's equation for w2),  s = the sign of the dn component,

evaluated here in plain double precision with :func:`scipy.special.ellipj` and
:func:`scipy.special.ellipkinc` (Cephes: the AGM and descending Landen transformation), on
arrays of bodies **each with its own times**. Why a second evaluation of the same formula:
:func:`tumble.dynamics.methods.exact_batch.free_rotation_batch` carries the phase in double-double and
matches the one-body solution to a few ulps at any phase (1e24 rad), which costs about 3 ms for
12 bodies x 100 samples; a least-squares fit of a one-second gyroscope record evaluates the model
hundreds of times at phases below 1e3 rad, where this form agrees with it to ~1e-13 relative
(tests/test_exact_omega.py) at about a fifth of the cost, and it takes per-body times.
"""

from __future__ import annotations

import numpy as np
from scipy.special import ellipj, ellipkinc

from ...typing import ArrayLike, Vector3

__all__ = ["free_omega"]

#: Largest parameter m used (the separatrix m = 1 has no period; a body exactly on it is
#: evaluated at m = 1 - 2^-52, within round-off of it over a record of a few periods).
_M_MAX = 1.0 - 2.0 ** -52


def _g(I: Vector3, w: Vector3) -> Vector3:
    """``g_j = L^2 - 2 E I_j = sum_i I_i (I_i - I_j) w_i^2`` (no cancellation), shape (N, 3)."""
    return np.stack([np.sum(I * (I - I[:, j:j + 1]) * w * w, axis=1) for j in range(3)], axis=1)


def free_omega(moments: ArrayLike, omega0: ArrayLike, t: ArrayLike) -> Vector3:
    """Angular velocity of N torque-free rigid bodies, principal frame, rad/s.

    Parameters
    ----------
    moments : array_like, shape (N, 3)
        Principal moments, ascending and positive (any common unit: only ratios enter), kg m^2.
    omega0 : array_like, shape (N, 3)
        Angular velocity at t = 0, principal frame, rad/s.
    t : array_like, shape (T,) or (N, T)
        Times, s: common to all bodies or one row per body.

    Returns
    -------
    ndarray, shape (N, T, 3)
        ``omega(t)``, rad/s, within ~1e-13 of :func:`tumble.dynamics.methods.exact_batch.free_rotation_batch`
        relative to ``|omega|`` at phases ``p t`` up to 1e3 rad.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> w = free_omega([[1.0, 2.0, 3.0]], [[0.1, 1.0, 0.1]], np.linspace(0, 10, 5))
    >>> w.shape
    (1, 5, 3)
    >>> I = np.array([1.0, 2.0, 3.0])
    >>> bool(np.allclose(np.sum((I * w[0]) ** 2, axis=1), np.sum((I * [0.1, 1.0, 0.1]) ** 2)))
    True
    """
    I = np.atleast_2d(np.asarray(moments, float))
    w = np.atleast_2d(np.asarray(omega0, float))
    t = np.asarray(t, float)
    N = len(I)
    tt = np.broadcast_to(t, (N, t.shape[-1])) if t.ndim == 1 else t
    out = np.empty((N, tt.shape[1], 3))
    with np.errstate(divide="ignore", invalid="ignore"):
        g = _g(I, w)
        upper = g[:, 1] >= 0.0
        c = np.where(upper, 0, 2)  # the cn axis
        r = 2 - c                  # the dn axis
        rows = np.arange(N)
        Ic, I2, Ir = I[rows, c], I[:, 1], I[rows, r]
        gc, gr = g[rows, c], g[rows, r]
        span = Ir - Ic  # I3 - I1 (upper) or I1 - I3 (lower): the signs cancel below
        ac = np.sqrt(np.abs(gr / (Ic * span)))
        a2 = np.sqrt(np.abs(gr / (I2 * (Ir - I2))))
        ar = np.sqrt(np.abs(gc / (Ir * span)))
        p = np.sqrt(np.abs((Ir - I2) * gc / (I[:, 0] * I[:, 1] * I[:, 2])))
        m = np.abs((I2 - Ic) * gr / ((Ir - I2) * gc))
    s = np.where(w[rows, r] < 0.0, -1.0, 1.0)
    moving = (a2 > 0) & (p > 0) & np.isfinite(a2) & np.isfinite(p) & np.isfinite(m) & (ac > 0)
    steady = ~moving
    if np.any(steady):
        out[steady] = w[steady, None, :]
    k = np.flatnonzero(moving)
    if k.size:
        m_k = np.minimum(m[k], _M_MAX)[:, None]
        sn0 = np.clip(w[k, 1] / a2[k], -1.0, 1.0)
        cn0 = w[k, c[k]] / (s[k] * ac[k])
        u0 = ellipkinc(np.arctan2(sn0, cn0), m_k[:, 0])
        sn, cn, dn, _ = ellipj(u0[:, None] + p[k, None] * tt[k], m_k)
        wc = s[k, None] * ac[k, None] * cn
        wr = s[k, None] * ar[k, None] * dn
        up = upper[k, None]
        out[k, :, 0] = np.where(up, wc, wr)
        out[k, :, 1] = a2[k, None] * sn
        out[k, :, 2] = np.where(up, wr, wc)
    return out
