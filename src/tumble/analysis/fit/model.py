"""The model a gyroscope's samples are fitted with: one or many free flights of one body.

A flight ``j`` is a torque-free motion (the exact solution, :mod:`tumble.dynamics.methods.exact_omega`),
or one slowed by an aerodynamic drag about each principal axis (``drag_1..3``, linear or
quadratic in omega, :mod:`tumble.dynamics.models.drag`), seen by a sensor fixed in the body::

    omega_sensor(t) = R^T omega_principal(t - t_j0) + b

with the body's ratios ``(I1/I3, I2/I3)`` (square coordinates ``(s, g)`` of
:mod:`tumble.analysis.fit.triangle`), the rotation ``R`` from the sensor's axes to the principal
axes (a rotation vector, rad), the sensor's constant bias ``b`` (rad/s) and the drag
coefficients divided by ``I3`` (linear: 1/s; quadratic: 1/rad) shared by every flight, and each
flight's own
``omega0`` (principal frame, rad/s, at its first sample). One flight is the case ``F = 1``.

Flights from several recordings (``groups``, each flight's recording): the ratios and the drag
stay shared by all, while ``R`` and ``b`` are the recording's own (a phone strapped on again, a
gyroscope started again): recording 0's are named ``rotvec_x`` ... ``bias_z`` as for one
recording, recording ``r``'s ``rotvec_x[rec r]`` ... ``bias_z[rec r]``.

The Jacobian is taken by forward differences, all columns in one vectorised evaluation: the
ratios, the drag and each flight's ``omega0`` need the elliptic functions again (one body per
perturbed parameter and flight); the rotation and the bias act on the principal-frame motion
already computed (the bias exactly). For many flights it is sparse (a flight's rows touch the
shared columns and its own three), and returned as such.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy import sparse

from ...dynamics.methods.exact_omega import free_omega
from ...dynamics.models.drag import drag_omega
from ...typing import ArrayLike
from .triangle import S_MIN, ratios

__all__ = ["BIAS_MAX", "DRAG_MODELS", "Model", "principal_rates", "rotvec_matrix"]

#: The drag models and their parameters (per principal axis, divided by I3).
DRAG_MODELS = {"none": (), "linear": ("drag_1", "drag_2", "drag_3"), "quadratic": ("drag_1", "drag_2", "drag_3")}
#: Largest gyroscope bias fitted, rad/s: 20 times a phone's zero-rate offset (about 3 deg/s,
#: 0.05 rad/s; Bosch BMI160/BMI270, ST LSM6DSO datasheets), so that the search has room. The bound
#: matters: a free bias
#: lets a near-spherical body spinning at a thousand rad/s, its spin cancelled by the bias,
#: mimic a tumble at ten (seen on real and synthetic tosses); so does the bound on omega0.
BIAS_MAX = 1.0
#: The largest RK4 step, as a turn of the fastest sample: an error of ~(0.04)^4 / 120 per step.
_TURN_PER_STEP = 0.04


def rotvec_matrix(rv: ArrayLike) -> np.ndarray:
    """The rotation matrix of a rotation vector (rad), by Rodrigues' formula
    ``R = I + sin(a) K + (1 - cos(a)) K^2`` with ``K`` the cross-product matrix of the unit axis
    (Shuster, J. Astronaut. Sci. 41 (1993) 439, sec. 3); equal to scipy's
    ``Rotation.from_rotvec(rv).as_matrix()`` (tested), written out because the fit's Jacobian
    calls it thousands of times and scipy's object costs 60 us a call.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.analysis.fit.model import rotvec_matrix
    >>> rv = [0.3, -1.2, 0.7]
    >>> bool(np.allclose(rotvec_matrix(rv), Rotation.from_rotvec(rv).as_matrix(), atol=1e-15))   # scipy's
    True
    >>> rotvec_matrix([0.0, 0.0, np.pi / 2]).round(12).tolist()   # a quarter turn about z
    [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    """
    rv = np.asarray(rv, float)
    a = float(np.sqrt(rv @ rv))
    if a < 1e-8:  # second order: sin(a)/a = 1, (1 - cos a)/a^2 = 1/2 to ~1e-17
        s1, s2 = 1.0, 0.5
    else:
        s1, s2 = np.sin(a) / a, (1.0 - np.cos(a)) / (a * a)
    x, y, z = rv
    K = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + s1 * K + s2 * (K @ K)


def principal_rates(moments: ArrayLike, omega0: ArrayLike, tau: ArrayLike, drag: str = "none",
                    coefficients: ArrayLike | None = None, *, max_step: ArrayLike | None = None) -> np.ndarray:
    """The model's omega in the principal frame, rad/s, shape (N, T, 3): the exact torque-free
    motion (``drag = "none"``) or Euler's equations with per-axis drag (module docstring).

    ``moments`` (N, 3) in units of ``I3`` (any common unit), ``omega0`` (N, 3) rad/s at
    ``tau = 0``, ``tau`` (T,) or (N, T) s (negative: backward), ``coefficients`` (N, 3) the drag
    divided by ``I3`` (1/s linear, 1/rad quadratic), ``max_step`` the drag integrator's largest
    step per body, s (:func:`~tumble.dynamics.models.drag.drag_omega`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.model import principal_rates
    >>> w = principal_rates([[0.5, 0.5, 1.0]], [[0.0, 0.0, 2.0]], [0.0, 1.0], "quadratic", [[0.0, 0.0, 1.5]])
    >>> bool(np.isclose(w[0, 1, 2], 2.0 / (1.0 + 1.5 * 2.0)))   # w3' = -(b3/I3) w3^2
    True
    """
    if drag == "none":
        return np.asarray(free_omega(moments, omega0, tau), float)
    lin, quad = (coefficients, None) if drag == "linear" else (None, coefficients)
    return np.asarray(drag_omega(moments, omega0, tau, lin, quad, max_step=max_step), float)


class Model:
    """The parameter vector's layout, its bounds, the model's samples and their Jacobian.

    Parameters
    ----------
    taus : list of ndarray
        Each flight's times since its first sample, s.
    rotation, bias : bool
        Whether the sensor's rotation and bias are fitted.
    drag : {"none", "linear", "quadratic"}
        Which drag is fitted.
    speeds : list of float, optional
        Each flight's largest measured ``|omega|``, rad/s: it sets the integrator's step (the
        same for every parameter vector, so that finite differences are clean); given, it bounds
        each component of ``omega0`` by ``2 speed + BIAS_MAX`` and the bias by ``BIAS_MAX``
        (without, they are free: the start's search for the right basin goes through values
        beyond them).
    groups : sequence of int, optional
        Each flight's recording, ``0 .. G-1`` (module docstring); default all in one.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.model import Model
    >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=True, bias=True)
    >>> model.names
    ('s', 'g', 'rotvec_x', 'rotvec_y', 'rotvec_z', 'bias_x', 'bias_y', 'bias_z', 'omega0_1', 'omega0_2', 'omega0_3')
    >>> two = Model([np.linspace(0.0, 1.0, 50), np.linspace(0.0, 0.8, 40)], rotation=False, bias=False, drag="linear")
    >>> two.names[2:], two.n, two.tau.shape   # the drag shared, omega0 per flight
    (('drag_1', 'drag_2', 'drag_3', 'omega0_1[0]', 'omega0_2[0]', 'omega0_3[0]', 'omega0_1[1]', 'omega0_2[1]', 'omega0_3[1]'), 11, (2, 50))
    >>> apart = Model([np.linspace(0.0, 1.0, 50)] * 2, rotation=False, bias=True, groups=[0, 1])
    >>> apart.shared   # two recordings: a bias each
    ('s', 'g', 'bias_x', 'bias_y', 'bias_z', 'bias_x[rec 1]', 'bias_y[rec 1]', 'bias_z[rec 1]')
    """

    def __init__(self, taus: Sequence[np.ndarray], rotation: bool, bias: bool, drag: str = "none",
                 speeds: Sequence[float] | None = None, groups: Sequence[int] | None = None) -> None:
        self.F = len(taus)
        self.groups = np.zeros(self.F, int) if groups is None else np.asarray(groups, int).reshape(self.F)
        self.G = int(self.groups.max()) + 1 if self.F else 1
        self.lengths = np.array([len(t) for t in taus])
        T = int(self.lengths.max())
        self.tau = np.empty((self.F, T))
        self.valid = np.zeros((self.F, T), bool)
        for j, t in enumerate(taus):
            self.tau[j, :len(t)] = t
            self.tau[j, len(t):] = t[-1]
            self.valid[j, :len(t)] = True
        self.rotation, self.bias, self.drag = bool(rotation), bool(bias), drag
        bounded = speeds is not None
        speeds = np.ones(self.F) if speeds is None else np.maximum(np.asarray(speeds, float), 1e-3)
        self.speeds = speeds
        self.hmax = _TURN_PER_STEP / speeds
        shared = ["s", "g"]
        for on, base in ((rotation, ("rotvec_x", "rotvec_y", "rotvec_z")), (bias, ("bias_x", "bias_y", "bias_z"))):
            if on:
                shared += [n if r == 0 else f"{n}[rec {r}]" for r in range(self.G) for n in base]
        shared += list(DRAG_MODELS[drag])
        self.shared = tuple(shared)
        self.ns = len(shared)
        per = ("omega0_1", "omega0_2", "omega0_3")
        self.names = self.shared + (per if self.F == 1 else tuple(f"{p}[{j}]" for j in range(self.F) for p in per))
        self.n = self.ns + 3 * self.F
        self.index = {name: i for i, name in enumerate(self.shared)}
        lo, hi = np.full(self.n, -np.inf), np.full(self.n, np.inf)
        lo[0], hi[0], lo[1], hi[1] = S_MIN, 1.0, 0.0, 1.0
        for name in DRAG_MODELS[drag]:
            lo[self.index[name]] = 0.0
        if bias and bounded:
            k = self.index["bias_x"]
            lo[k:k + 3 * self.G], hi[k:k + 3 * self.G] = -BIAS_MAX, BIAS_MAX
        if bounded:  # omega0 within twice the largest rate measured
            cap = np.repeat(2.0 * self.speeds + BIAS_MAX, 3)
            lo[self.ns:], hi[self.ns:] = -cap, cap
        self.bounds = (lo, hi)

    # -- the parameter vector ------------------------------------------------------------------
    def pack(self, s: float, g: float, rotvec: ArrayLike, bias: ArrayLike, omega0: ArrayLike,
             drag: ArrayLike = (0.0, 0.0, 0.0)) -> np.ndarray:
        """A parameter vector from its parts (``omega0`` of shape (F, 3), ``drag`` 3 numbers;
        ``rotvec`` and ``bias`` 3 numbers, or shape (G, 3) for several recordings).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=True, bias=True)
        >>> model.pack(0.7, 0.4, [0.0, 0.0, 0.1], [0.01, 0.0, 0.0], [[1.0, 2.0, 3.0]]).tolist()   # in model.names' order
        [0.7, 0.4, 0.0, 0.0, 0.1, 0.01, 0.0, 0.0, 1.0, 2.0, 3.0]
        """
        P = [s, g]
        if self.rotation:
            P += list(np.broadcast_to(np.asarray(rotvec, float).reshape(-1, 3), (self.G, 3)).ravel())
        if self.bias:
            P += list(np.broadcast_to(np.asarray(bias, float).reshape(-1, 3), (self.G, 3)).ravel())
        if self.drag != "none":
            P += list(np.asarray(drag, float))
        return np.concatenate([np.array(P, float), np.asarray(omega0, float).reshape(-1)])

    def get(self, P: np.ndarray, name: str, default: float = 0.0) -> float:
        """One named shared parameter of ``P`` (a name of ``Model.shared``), or ``default`` where it is not fitted.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=False, bias=True)
        >>> P = model.pack(0.7, 0.4, None, [0.01, 0.02, 0.03], [[1.0, 2.0, 3.0]])
        >>> model.get(P, "bias_y"), model.get(P, "drag_1"), model.get(P, "rotvec_x", default=-1.0)
        (0.02, 0.0, -1.0)
        """
        return float(P[self.index[name]]) if name in self.index else default

    def rotation_matrix(self, P: np.ndarray, group: int = 0) -> np.ndarray:
        """The rotation from the sensor's axes to the principal axes (the identity where it is not
        fitted), of recording ``group``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=True, bias=False)
        >>> P = model.pack(0.7, 0.4, [0.0, 0.0, np.pi], None, [[1.0, 2.0, 3.0]])   # half a turn about z
        >>> (model.rotation_matrix(P).round(12) + 0.0).tolist()   # + 0.0: no signed zeros
        [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]
        """
        if not self.rotation:
            return np.eye(3)
        k = self.index["rotvec_x"] + 3 * group
        return rotvec_matrix(P[k:k + 3])

    def bias_vector(self, P: np.ndarray, group: int = 0) -> np.ndarray:
        """The sensor's bias, rad/s (zeros where it is not fitted), of recording ``group``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=False, bias=True)
        >>> model.bias_vector(model.pack(0.7, 0.4, None, [0.01, 0.02, 0.03], [[1.0, 2.0, 3.0]])).tolist()
        [0.01, 0.02, 0.03]
        """
        if not self.bias:
            return np.zeros(3)
        k = self.index["bias_x"] + 3 * group
        return np.asarray(P[k:k + 3], float)

    def drag_vector(self, P: np.ndarray) -> np.ndarray:
        """The drag coefficients per principal axis divided by ``I3`` (linear: 1/s; quadratic: 1/rad); zeros without drag.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=False, bias=False, drag="quadratic")
        >>> model.drag_vector(model.pack(0.7, 0.4, None, None, [[1.0, 2.0, 3.0]], drag=[0.1, 0.2, 0.3])).tolist()
        [0.1, 0.2, 0.3]
        """
        if self.drag == "none":
            return np.zeros(3)
        k = self.index["drag_1"]
        return np.asarray(P[k:k + 3], float)

    def omega0(self, P: np.ndarray) -> np.ndarray:
        """Each flight's ``omega0``, principal frame, rad/s, shape (F, 3).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50), np.linspace(0.0, 1.0, 30)], rotation=False, bias=False)
        >>> model.omega0(model.pack(0.7, 0.4, None, None, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])).tolist()
        [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]
        """
        return np.asarray(P[self.ns:], float).reshape(self.F, 3)

    def moments(self, P: np.ndarray) -> np.ndarray:
        """The moments ``(I1/I3, I2/I3, 1)`` of the square coordinates ``(s, g)`` of ``P``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=False, bias=False)
        >>> model.moments(model.pack(0.5, 0.0, None, None, [[1.0, 2.0, 3.0]])).tolist()   # g = 0: planar, I1 + I2 = I3
        [0.25, 0.75, 1.0]
        """
        x, y = ratios(P[0], P[1])
        return np.array([float(x), float(y), 1.0])

    # -- evaluation ----------------------------------------------------------------------------
    def _principal(self, physics, omega0, rows) -> np.ndarray:
        """omega_principal for parameter sets ``physics`` (K, 5: s, g, drag_1..3) and ``omega0``
        (K, 3) at the times of flights ``rows`` (K,); shape (K, T, 3)."""
        x, y = ratios(physics[:, 0], physics[:, 1])
        I = np.stack([x, y, np.ones_like(x)], axis=1)
        with np.errstate(all="ignore"):
            return principal_rates(I, omega0, self.tau[rows], self.drag, physics[:, 2:5], max_step=self.hmax[rows])

    def _physics(self, P) -> np.ndarray:
        return np.concatenate([[P[0], P[1]], self.drag_vector(P)])

    def principal(self, P: np.ndarray) -> np.ndarray:
        """omega in the principal frame of every flight, shape (F, T, 3), rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.analysis.fit.model import Model
        >>> from tumble.dynamics.methods.exact import FreeRotation
        >>> tau = np.linspace(0.0, 1.0, 50)
        >>> model = Model([tau], rotation=False, bias=False)
        >>> P = model.pack(0.7, 0.4, None, None, [[3.0, 1.0, 6.0]])
        >>> w = model.principal(P)
        >>> exact = FreeRotation(model.moments(P), [3.0, 1.0, 6.0], Rotation.identity()).omega(tau)
        >>> w.shape, bool(np.allclose(w[0], exact, atol=1e-12))   # the exact solution
        ((1, 50, 3), True)
        """
        phys = np.tile(self._physics(P), (self.F, 1))
        return self._principal(phys, self.omega0(P), np.arange(self.F))

    def sensor(self, P: np.ndarray, principal: np.ndarray | None = None) -> np.ndarray:
        """The model's samples along the sensor's axes, bias included, shape (F, T, 3), rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)], rotation=True, bias=True)
        >>> P = model.pack(0.7, 0.4, [0.1, 0.2, 0.3], [0.01, -0.02, 0.03], [[3.0, 1.0, 6.0]])
        >>> wp = model.principal(P)
        >>> bool(np.allclose(model.sensor(P, wp), wp @ model.rotation_matrix(P) + [0.01, -0.02, 0.03]))   # R^T w + b
        True
        >>> bool(np.allclose(np.linalg.norm(model.sensor(P) - [0.01, -0.02, 0.03], axis=-1), np.linalg.norm(wp, axis=-1)))
        True
        """
        wp = self.principal(P) if principal is None else principal
        if self.G == 1:
            return wp @ self.rotation_matrix(P) + self.bias_vector(P)
        R, b = self._per_flight(P)
        return np.einsum("ftk,fkl->ftl", wp, R) + b[:, None, :]

    def _per_flight(self, P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each flight's rotation (F, 3, 3) and bias (F, 3), from its recording's."""
        R = np.array([self.rotation_matrix(P, r) for r in range(self.G)])
        b = np.array([self.bias_vector(P, r) for r in range(self.G)])
        return R[self.groups], b[self.groups]

    def flight_parameters(self, j: int) -> np.ndarray:
        """The indices into ``P`` of flight ``j``'s parameters as a one-flight model's (its
        recording's rotation and bias, the shared ratios and drag, its ``omega0``).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 50)] * 3, rotation=False, bias=True, groups=[0, 1, 1])
        >>> [model.names[i] for i in model.flight_parameters(2)]
        ['s', 'g', 'bias_x[rec 1]', 'bias_y[rec 1]', 'bias_z[rec 1]', 'omega0_1[2]', 'omega0_2[2]', 'omega0_3[2]']
        """
        r = int(self.groups[j])
        idx = [0, 1]
        for on, name in ((self.rotation, "rotvec_x"), (self.bias, "bias_x")):
            if on:
                idx += list(range(self.index[name] + 3 * r, self.index[name] + 3 * r + 3))
        idx += [self.index[n] for n in DRAG_MODELS[self.drag]]
        return np.array(idx + list(range(self.ns + 3 * j, self.ns + 3 * j + 3)))

    def jacobian(self, P: np.ndarray, mask: np.ndarray,
                 principal: np.ndarray | None = None) -> np.ndarray | sparse.csr_matrix:
        """d(model samples[mask]) / dP by forward differences (module docstring).

        Returns a dense array for one flight and a CSR matrix for several.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> model = Model([np.linspace(0.0, 1.0, 40)], rotation=True, bias=True)
        >>> P = model.pack(0.7, 0.4, [0.1, 0.2, 0.3], [0.0, 0.0, 0.0], [[3.0, 1.0, 6.0]])
        >>> mask = np.ones((1, 40, 3), bool)
        >>> J = model.jacobian(P, mask)
        >>> J.shape, J[:3, 5:8].tolist()   # the bias columns: exactly one on their own axis
        ((120, 11), [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        >>> h = np.zeros(11); h[0] = 1e-6   # the s column against a central difference
        >>> central = (model.sensor(P + h) - model.sensor(P - h))[mask] / 2e-6
        >>> bool(np.allclose(J[:, 0], central, atol=1e-5 * np.abs(central).max()))
        True
        """
        F, T = self.F, self.tau.shape[1]
        _lo, hi = self.bounds
        h = 1e-7 * np.maximum(1.0, np.abs(P))
        h = np.where(P + h > hi, -h, h)  # step into the box at an upper bound
        one = self.G == 1
        R = self.rotation_matrix(P) if one else self._per_flight(P)[0]

        def turn(x, M):  # x (F', T, 3) into the sensor's axes by M (3, 3) or per flight (F', 3, 3)
            return x @ M if M.ndim == 2 else np.einsum("ftk,fkl->ftl", x, M)

        wp = self.principal(P) if principal is None else principal
        base_phys = self._physics(P)
        w0 = self.omega0(P)
        # the parameters that need the elliptic functions again: s, g, the drag, omega0
        phys_cols = [0, 1] + [self.index[n] for n in DRAG_MODELS[self.drag]]
        phys_slot = {col: i for i, col in enumerate(phys_cols)}
        sets_phys, sets_w0, rows = [], [], []
        for col in phys_cols:
            ph = base_phys.copy()
            ph[phys_slot[col]] += h[col]
            sets_phys.append(np.tile(ph, (F, 1)))
            sets_w0.append(w0)
            rows.append(np.arange(F))
        for k in range(3):
            dw = w0.copy()
            dw[:, k] += h[self.ns + 3 * np.arange(F) + k]
            sets_phys.append(np.tile(base_phys, (F, 1)))
            sets_w0.append(dw)
            rows.append(np.arange(F))
        out = self._principal(np.vstack(sets_phys), np.vstack(sets_w0), np.concatenate(rows))
        out = out.reshape(len(phys_cols) + 3, F, T, 3)
        every = np.arange(F)
        cols = {}  # column -> (its flights, derivative of their sensor samples (F', T, 3))
        for i, col in enumerate(phys_cols):
            cols[col] = (every, turn(out[i] - wp, R) / h[col])
        for r in range(self.G):
            mine = every if one else np.flatnonzero(self.groups == r)
            if self.rotation:
                k0 = self.index["rotvec_x"] + 3 * r
                Rr = self.rotation_matrix(P, r)
                for k in range(3):
                    Pk = P.copy()
                    Pk[k0 + k] += h[k0 + k]
                    cols[k0 + k] = (mine, (wp[mine] @ (self.rotation_matrix(Pk, r) - Rr)) / h[k0 + k])
            if self.bias:
                k0 = self.index["bias_x"] + 3 * r
                for k in range(3):
                    d = np.zeros((len(mine), T, 3))
                    d[:, :, k] = 1.0
                    cols[k0 + k] = (mine, d)
        d_w0 = [turn(out[len(phys_cols) + k] - wp, R) / h[self.ns + 3 * np.arange(F) + k][:, None, None]
                for k in range(3)]
        if F == 1:
            J = np.empty((int(mask.sum()), self.n))
            for col, (_, d) in cols.items():
                J[:, col] = d[mask]
            for k in range(3):
                J[:, self.ns + k] = d_w0[k][mask]
            return J
        # sparse: shared columns on their flights' rows, a flight's omega0 columns on its own rows
        flight = np.broadcast_to(np.arange(F)[:, None, None], mask.shape)[mask]
        m = int(mask.sum())
        row_of = np.full(mask.shape, -1)
        row_of[mask] = np.arange(m)
        data, ri, ci = [], [], []
        row = np.arange(m)
        for col, (fl, d) in cols.items():
            sub = mask[fl]
            data.append(d[sub]), ri.append(row if len(fl) == F else row_of[fl][sub]), ci.append(np.full(int(sub.sum()), col))
        for k in range(3):
            data.append(d_w0[k][mask]), ri.append(row), ci.append(self.ns + 3 * flight + k)
        return sparse.csr_matrix((np.concatenate(data), (np.concatenate(ri), np.concatenate(ci))), shape=(m, self.n))
