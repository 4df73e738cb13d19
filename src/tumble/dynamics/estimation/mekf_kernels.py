"""The MEKF's two steps as compiled loops over a batch of filters: propagation and the Kalman update.

The equations are :mod:`~tumble.dynamics.estimation.mekf`'s (Markley & Crassidis 2014, sec. 6.2),
written once here over plain arrays, ``n`` filters flattened on the first axis, and compiled with
numba through :func:`tumble.jit.jit` at import (this module is imported only when a filter steps,
as the engine's kernels are): a filter step is then a few microseconds, not
the ~0.3 ms of numpy's calls on 6 x 6 arrays. The update kernel forms the innovation ``y`` and
its Jacobian ``H`` itself for a vector (and its noise ``R``) or a measured attitude, else takes
them as given. :class:`~tumble.dynamics.estimation.mekf.MEKF` and the compiled closed loop
(:mod:`~tumble.dynamics.control.estimated_loop`, a 90-minute orbit with the filter at 10 Hz in
0.46 CPU-s) both call these kernels: each formula written once.

Examples
--------
>>> import numpy as np
>>> from tumble.dynamics.estimation.mekf_kernels import propagate
>>> q, b, P = np.array([[0.0, 0.0, 0.0, 1.0]]), np.zeros((1, 3)), np.eye(6)[None] * 1e-4
>>> propagate(q, b, P, np.array([[0.0, 0.0, 0.1]]), 1.0, 0.0, 0.0)
>>> np.round(q, 6).tolist()
[[0.0, 0.0, 0.049979, 0.99875]]
"""

from __future__ import annotations

import math

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from ..special.quaternion import hamilton_components

__all__: list[str] = []  # the kernels are the MEKF's (mekf.py) and the compiled loop's, not an API


@jit(error_model="numpy")
def propagate(q: FloatArray, b: FloatArray, P: FloatArray, gyro: FloatArray, dt: float, sv: float, su: float) -> None:
    """Propagate ``n`` filters in place over ``dt`` with the gyroscope readings ``gyro`` (n, 3).

    ``q`` (n, 4), ``b`` (n, 3), ``P`` (n, 6, 6); ``sv``, ``su`` the noise densities.
    """
    n = q.shape[0]
    Phi = np.zeros((6, 6))
    tmp = np.zeros((6, 6))
    for i in range(n):
        w0, w1, w2 = gyro[i, 0] - b[i, 0], gyro[i, 1] - b[i, 1], gyro[i, 2] - b[i, 2]
        a = math.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
        th = a * dt
        if th > 1e-4:
            k = math.sin(0.5 * th) / a
            s1 = math.sin(th) / a
            c1 = (1.0 - math.cos(th)) / (a * a)
            c2 = (th - math.sin(th)) / (a * a * a)
        else:  # the series, error below 1e-17 relative
            k = 0.5 * dt * (1.0 - th * th / 24.0)
            s1 = dt * (1.0 - th * th / 6.0)
            c1 = dt * dt * (0.5 - th * th / 24.0)
            c2 = dt * dt * dt * (1.0 / 6.0 - th * th / 120.0)
        # q <- q (x) (k w, cos(th / 2))  (Hamilton product, scalar last)
        nx, ny, nz, ns = hamilton_components(q[i, 0], q[i, 1], q[i, 2], q[i, 3], k * w0, k * w1, k * w2, math.cos(0.5 * th))
        norm = math.sqrt(nx * nx + ny * ny + nz * nz + ns * ns)
        q[i, 0], q[i, 1], q[i, 2], q[i, 3] = nx / norm, ny / norm, nz / norm, ns / norm
        # W = [w x], W2 = W W
        W = ((0.0, -w2, w1), (w2, 0.0, -w0), (-w1, w0, 0.0))
        for r in range(6):
            for c in range(6):
                Phi[r, c] = 1.0 if r == c else 0.0
        for r in range(3):
            for c in range(3):
                w2rc = W[r][0] * W[0][c] + W[r][1] * W[1][c] + W[r][2] * W[2][c]
                Phi[r, c] += -s1 * W[r][c] + c1 * w2rc
                Phi[r, 3 + c] = -((dt if r == c else 0.0) - c1 * W[r][c] + c2 * w2rc)
        # P <- Phi P Phi^T + Q
        for r in range(6):
            for c in range(6):
                acc = 0.0
                for m in range(6):
                    acc += Phi[r, m] * P[i, m, c]
                tmp[r, c] = acc
        for r in range(6):
            for c in range(r, 6):
                acc = 0.0
                for m in range(6):
                    acc += tmp[r, m] * Phi[c, m]
                P[i, r, c] = acc
                P[i, c, r] = acc
        qa = sv * sv * dt + su * su * dt * dt * dt / 3.0
        qab = -su * su * dt * dt / 2.0
        qb = su * su * dt
        for r in range(3):
            P[i, r, r] += qa
            P[i, r, 3 + r] += qab
            P[i, 3 + r, r] += qab
            P[i, 3 + r, 3 + r] += qb


@jit(error_model="numpy")
def update(q: FloatArray, b: FloatArray, P: FloatArray, y: FloatArray, H: FloatArray, R: FloatArray,
           valid: np.ndarray, nis: FloatArray, vectors: FloatArray) -> None:
    """The Kalman update and reset of ``n`` filters in place (Joseph's form); ``nis`` (n,) written, NaN where not ``valid``.

    ``y`` (n, m) innovations, ``H`` (n, m, 6), ``R`` (n, m, m). With ``vectors`` of shape (n, 7)
    (a measured direction in the body, its world direction, both of any length, and its noise in rad) they are
    first formed here for the vector update (m = 2; module docstring of ``mekf``); with shape
    (n, 4) (a measured attitude's quaternion, body to world) ``y`` and ``H`` of the attitude
    update (m = 3; ``R`` given; ``y`` formed for every row, valid or not: the attitude error
    :meth:`~tumble.dynamics.estimation.mekf.MEKF.error` reads); with shape (0, 7) they are taken as given.
    """
    n, m = y.shape
    PHt, K, S, Sinv = np.empty((6, m)), np.empty((6, m)), np.empty((m, m)), np.empty((m, m))
    IKH, tmp, x = np.empty((6, 6)), np.empty((6, 6)), np.empty(6)
    for i in range(n):
        if vectors.shape[0] > 0 and vectors.shape[1] == 4:
            # y = rotvec(q* (x) q_m), the short way round, H = [I, 0] (an attitude measurement; mekf)
            ex, ey, ez, es = hamilton_components(-q[i, 0], -q[i, 1], -q[i, 2], q[i, 3], vectors[i, 0], vectors[i, 1],
                                                 vectors[i, 2], vectors[i, 3])
            if es < 0.0:
                ex, ey, ez, es = -ex, -ey, -ez, -es
            sn = math.sqrt(ex * ex + ey * ey + ez * ez)
            k = 2.0 * math.atan2(sn, es) / sn if sn > 1e-8 else 2.0 / es
            y[i, 0], y[i, 1], y[i, 2] = k * ex, k * ey, k * ez
            for r in range(3):
                for c in range(6):
                    H[i, r, c] = 1.0 if r == c else 0.0
        if not valid[i]:
            nis[i] = np.nan
            continue
        if vectors.shape[0] > 0 and vectors.shape[1] == 7:
            # y = E^T (b_m - b), H = [E^T [b x], 0], R = sigma^2 I for b = A(q)^T r, E across b
            ux, uy, uz, w = -q[i, 0], -q[i, 1], -q[i, 2], q[i, 3]   # the conjugate turns world into body
            nr = math.sqrt(vectors[i, 3] ** 2 + vectors[i, 4] ** 2 + vectors[i, 5] ** 2)
            nm = math.sqrt(vectors[i, 0] ** 2 + vectors[i, 1] ** 2 + vectors[i, 2] ** 2)
            r0, r1, r2 = vectors[i, 3] / nr, vectors[i, 4] / nr, vectors[i, 5] / nr
            c0, c1, c2 = uy * r2 - uz * r1, uz * r0 - ux * r2, ux * r1 - uy * r0
            b0 = r0 + 2.0 * (w * c0 + uy * c2 - uz * c1)
            b1 = r1 + 2.0 * (w * c1 + uz * c0 - ux * c2)
            b2 = r2 + 2.0 * (w * c2 + ux * c1 - uy * c0)
            h0, h1, h2 = (1.0, 0.0, 0.0) if abs(b0) < 0.9 else (0.0, 1.0, 0.0)
            e0, e1, e2 = b1 * h2 - b2 * h1, b2 * h0 - b0 * h2, b0 * h1 - b1 * h0
            ne = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
            e0, e1, e2 = e0 / ne, e1 / ne, e2 / ne
            f0, f1, f2 = b1 * e2 - b2 * e1, b2 * e0 - b0 * e2, b0 * e1 - b1 * e0
            d0, d1, d2 = vectors[i, 0] / nm - b0, vectors[i, 1] / nm - b1, vectors[i, 2] / nm - b2
            y[i, 0] = e0 * d0 + e1 * d1 + e2 * d2
            y[i, 1] = f0 * d0 + f1 * d1 + f2 * d2
            # E^T [b x]: the row e^T [b x] is (e x b)^T
            H[i, 0, 0], H[i, 0, 1], H[i, 0, 2] = e1 * b2 - e2 * b1, e2 * b0 - e0 * b2, e0 * b1 - e1 * b0
            H[i, 1, 0], H[i, 1, 1], H[i, 1, 2] = f1 * b2 - f2 * b1, f2 * b0 - f0 * b2, f0 * b1 - f1 * b0
            for c in range(3, 6):
                H[i, 0, c] = 0.0
                H[i, 1, c] = 0.0
            s2 = vectors[i, 6] * vectors[i, 6]
            R[i, 0, 0], R[i, 0, 1], R[i, 1, 0], R[i, 1, 1] = s2, 0.0, 0.0, s2
        # S = H P H^T + R, K = P H^T S^-1, by loops (m <= 3; numba compiles them in a fraction
        # of the time its linear algebra takes)
        for r in range(6):
            for j in range(m):
                acc = 0.0
                for c in range(6):
                    acc += P[i, r, c] * H[i, j, c]
                PHt[r, j] = acc
        for a in range(m):
            for j in range(m):
                acc = R[i, a, j]
                for r in range(6):
                    acc += H[i, a, r] * PHt[r, j]
                S[a, j] = acc
        if m == 2:
            det = S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]
            Sinv[0, 0], Sinv[0, 1], Sinv[1, 0], Sinv[1, 1] = S[1, 1] / det, -S[0, 1] / det, -S[1, 0] / det, S[0, 0] / det
        else:  # the adjugate of a 3 x 3
            for a in range(3):
                for j in range(3):
                    a1, a2, j1, j2 = (j + 1) % 3, (j + 2) % 3, (a + 1) % 3, (a + 2) % 3
                    Sinv[a, j] = S[a1, j1] * S[a2, j2] - S[a1, j2] * S[a2, j1]
            det = S[0, 0] * Sinv[0, 0] + S[0, 1] * Sinv[1, 0] + S[0, 2] * Sinv[2, 0]
            for a in range(3):
                for j in range(3):
                    Sinv[a, j] /= det
        nis[i] = 0.0
        for a in range(m):
            for j in range(m):
                nis[i] += y[i, a] * Sinv[a, j] * y[i, j]
        for r in range(6):
            for a in range(m):
                acc = 0.0
                for j in range(m):
                    acc += PHt[r, j] * Sinv[j, a]
                K[r, a] = acc
            acc = 0.0
            for a in range(m):
                acc += K[r, a] * y[i, a]
            x[r] = acc
        # Joseph's form: P <- (I - K H) P (I - K H)^T + K R K^T
        for r in range(6):
            for c in range(6):
                acc = 1.0 if r == c else 0.0
                for a in range(m):
                    acc -= K[r, a] * H[i, a, c]
                IKH[r, c] = acc
        for r in range(6):
            for c in range(6):
                acc = 0.0
                for j in range(6):
                    acc += IKH[r, j] * P[i, j, c]
                tmp[r, c] = acc
        for r in range(6):
            for c in range(r, 6):
                acc = 0.0
                for j in range(6):
                    acc += tmp[r, j] * IKH[c, j]
                for a in range(m):
                    for j in range(m):
                        acc += K[r, a] * R[i, a, j] * K[c, j]
                P[i, r, c] = acc
                P[i, c, r] = acc
        # reset (Markley 2003): q <- (q + Xi(q) dtheta / 2) / |...|, dtheta read as twice the Gibbs vector
        hx, hy, hz = 0.5 * x[0], 0.5 * x[1], 0.5 * x[2]
        qx, qy, qz, qs = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        gx, gy, gz = qx + qs * hx + qy * hz - qz * hy, qy + qs * hy + qz * hx - qx * hz, qz + qs * hz + qx * hy - qy * hx
        gs = qs - qx * hx - qy * hy - qz * hz
        norm = math.sqrt(gx * gx + gy * gy + gz * gz + gs * gs)
        q[i, 0], q[i, 1], q[i, 2], q[i, 3] = gx / norm, gy / norm, gz / norm, gs / norm
        for r in range(3):
            b[i, r] += x[3 + r]
