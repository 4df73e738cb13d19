"""The multiplicative extended Kalman filter (MEKF): attitude and gyroscope bias from a gyroscope,
vector sensors and a star tracker.

Lefferts, Markley & Shuster, "Kalman filtering for spacecraft attitude estimation", *J. Guidance*
5(5), 1982, 417-429; Markley & Crassidis, *Fundamentals of Spacecraft Attitude Determination and
Control*, Springer 2014, sec. 6.2 (cited below as M&C).

**State.** The reference attitude ``q`` (body to world, scalar last as scipy) and bias ``b``
(rad/s) are held outside the filter; the filter's state is the error ``x = (dtheta, db)``, with
``A_true = A(q) exp([dtheta x])`` (the error about the body axes, M&C eq. 6.57 in its body-frame
form) and ``b_true = b + db``; its covariance ``P`` is 6 x 6, rad^2 and (rad/s)^2.

**Gyroscope** (M&C eqs. 4.31; Farrenkopf 1978): ``omega_m = omega + b + eta_v``,
``b' = eta_u``, white noises of densities ``gyro_noise`` (``sigma_v``, rad/s^0.5, the angle random
walk; a sampled gyroscope of per-sample standard deviation ``s`` at period ``dt`` has
``sigma_v = s sqrt(dt)``) and ``bias_walk`` (``sigma_u``, rad/s^1.5).

**Propagation** over ``dt`` with the rate ``w = omega_m - b`` held (M&C sec. 6.2.4):
``q <- q (x) exp(w dt / 2)``; ``P <- Phi P Phi^T + Q`` with

``Phi = [[exp(-[w x] dt), -J], [0, I]]``,
``J = I dt - [w x] (1 - cos(|w| dt)) / |w|^2 + [w x]^2 (|w| dt - sin(|w| dt)) / |w|^3``

(the exact transition of ``dtheta' = -w x dtheta - db``; M&C eqs. 6.83-6.85) and
``Q = [[(sigma_v^2 dt + sigma_u^2 dt^3 / 3) I, -sigma_u^2 dt^2 / 2 I], [-sigma_u^2 dt^2 / 2 I, sigma_u^2 dt I]]``
(M&C eq. 6.93; Crassidis & Junkins, *Optimal Estimation of Dynamic Systems*, 2nd ed., eq. 7.44).

**Vector update** (M&C sec. 6.2.3; Shuster's measurement model, see
:mod:`~tumble.dynamics.estimation.static`): a unit vector ``b_m`` measured in the body of a
known world direction ``r``, with angular noise ``sigma`` across it. Predicted ``b = A^T r``;
``A_true^T r = b + [b x] dtheta``; the innovation is taken in the plane across ``b`` (two
components on an orthonormal pair ``E`` across it, so that its covariance is not singular),
``y = E^T (b_m - b)``, ``H = [E^T [b x], 0]``, ``R = sigma^2 I_2``.

**Attitude update** (a star tracker): ``A_m = A_true exp([v x])``, ``v`` of covariance ``R``
(3 x 3, body axes); ``y = rotvec(A^T A_m)``, ``H = [I, 0]``.

**Update and reset**: ``S = H P H^T + R``, ``K = P H^T S^-1``, ``x = K y``, Joseph's form
``P <- (I - K H) P (I - K H)^T + K R K^T``; then the reset ``q <- q (x) (dtheta / 2, 1)``,
normalised (``dtheta`` read as twice the Gibbs vector, which keeps the reset exact to second
order: Markley, "Attitude error representations for Kalman filtering", *J. Guidance, Control,
and Dynamics* 26(2), 2003; M&C sec. 6.2.2), ``b <- b + db`` and ``x <- 0`` (``P`` unchanged to
first order). The normalised innovation squared ``y^T S^-1 y`` is returned with
each update: chi-square with 2 (vector) or 3 (attitude) degrees of freedom when the filter is
consistent.

Every array broadcasts over leading axes: one filter object runs a batch of independent filters
(the consistency tests run 200 at once). The two steps run compiled
(:mod:`~tumble.dynamics.estimation.mekf_kernels`), the kernels the compiled closed loop calls too
(:mod:`~tumble.dynamics.control.estimated_loop`).

Examples
--------
A body at rest, its gyroscope reading a bias of 1 mrad/s that the filter does not know; two
fixed directions, read each second, let it find the bias:

>>> import numpy as np
>>> from scipy.spatial.transform import Rotation
>>> from tumble.dynamics.estimation.mekf import MEKF
>>> f = MEKF.start(Rotation.identity(), attitude_sigma=0.1, bias_sigma=0.01, gyro_noise=1e-5, bias_walk=1e-7)
>>> for k in range(300):
...     f = f.propagate([1e-3, 0.0, 0.0], 0.1)
...     if k % 10 == 9:
...         f, _ = f.update_vector([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1e-3)
...         f, _ = f.update_vector([0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 1e-3)
>>> np.round(f.bias * 1e3, 3).tolist(), bool(f.attitude.magnitude() < 1e-3)
([1.0, 0.0, 0.0], True)
"""

from __future__ import annotations

from dataclasses import dataclass

import math
import warnings

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import field_repr
from ...jit import kernel_array
from ...typing import ArrayLike, FloatArray
from ...validation import check_covariance, check_positive, check_quaternions, check_vectors, refuse_first, short_repr
from ...validation.rotations import ScalarFirstWarning
from ..models.sensors import MAX_GYRO_ERROR

__all__ = ["MEKF"]


def _rows(a: FloatArray, shape: tuple[int, ...], tail: tuple[int, ...]) -> FloatArray:
    """``a`` broadcast to ``shape + tail`` with the batch flattened, as the kernels take it
    (:func:`~tumble.jit.kernel_array`: float, C-contiguous, writable; ``a`` itself where it is that)."""
    whole = a.shape == shape + tail
    return kernel_array(a.reshape((-1, *tail)) if whole else np.broadcast_to(a, shape + tail).reshape((-1, *tail)))


def _batch(name: str, v: FloatArray, shape: tuple[int, ...]) -> FloatArray:
    """``v`` (..., 3) broadcast to the filters' batch ``shape``, or a ValueError naming ``name`` (numpy's
    own broadcast error named no argument)."""
    try:
        return np.broadcast_to(v, shape + (3,)).copy()
    except ValueError:
        raise ValueError(f"{name} has shape {v.shape}: it must be (3,) or the filters' batch {shape} + (3,) (rad/s)") from None


@dataclass(frozen=True)
class MEKF:
    """The state of a multiplicative extended Kalman filter (module docstring), or of a batch of them.

    Parameters
    ----------
    quaternion : ndarray, shape (..., 4)
        Estimated attitude, body to world, scalar last.
    bias : ndarray, shape (..., 3)
        Estimated gyroscope bias, rad/s.
    covariance : ndarray, shape (..., 6, 6)
        Of the attitude error about the body axes (rad^2) and the bias error ((rad/s)^2).
    gyro_noise : float
        The gyroscope's angle random walk ``sigma_v``, rad/s^0.5 (>= 0).
    bias_walk : float
        The bias's rate random walk ``sigma_u``, rad/s^1.5 (>= 0).

    Examples
    --------
    :meth:`start` makes one; each step returns a new one:

    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.estimation.mekf import MEKF
    >>> f = MEKF.start(Rotation.identity(), attitude_sigma=0.01, bias_sigma=1e-3, gyro_noise=1e-4, bias_walk=1e-6)
    >>> f.sigma.round(4).tolist()
    [0.01, 0.01, 0.01, 0.001, 0.001, 0.001]
    >>> g = f.propagate([0.0, 0.0, 0.1], 1.0)
    >>> round(float(g.attitude.magnitude()), 12), bool(g.sigma[0] > f.sigma[0])
    (0.1, True)
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    quaternion: FloatArray
    bias: FloatArray
    covariance: FloatArray
    gyro_noise: float
    bias_walk: float

    def __post_init__(self) -> None:
        check_positive("gyro_noise", self.gyro_noise, "rad/s^0.5", allow_zero=True)
        check_positive("bias_walk", self.bias_walk, "rad/s^1.5", allow_zero=True)
        # a zero quaternion (NaN) and a covariance not positive definite were taken (a walkthrough, 2026-12-03)
        object.__setattr__(self, "quaternion", check_quaternions("quaternion", self.quaternion))
        object.__setattr__(self, "bias", check_vectors("bias", self.bias, "rad/s"))
        object.__setattr__(self, "covariance", check_covariance("covariance", self.covariance, 6, "rad^2, (rad/s)^2"))

    @classmethod
    def start(cls, attitude: Rotation | ArrayLike, *, attitude_sigma: float, bias_sigma: float, gyro_noise: float,
              bias_walk: float, bias: ArrayLike = (0.0, 0.0, 0.0)) -> MEKF:
        """A filter from a first guess and its standard deviations.

        Parameters
        ----------
        attitude : scipy Rotation or quaternion(s), shape (..., 4)
            First guess, body to world (a stack of rotations starts a batch).
        attitude_sigma : float
            Its error's standard deviation about each body axis, rad (> 0).
        bias_sigma : float
            The bias guess's standard deviation on each axis, rad/s (> 0).
        gyro_noise, bias_walk : float
            The gyroscope's noise densities (class docstring).
        bias : array_like, shape (..., 3)
            The bias guess, rad/s.

        Examples
        --------
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF.start(Rotation.random(5, random_state=0), attitude_sigma=0.1, bias_sigma=1e-3,
        ...                gyro_noise=1e-4, bias_walk=1e-6)
        >>> f.quaternion.shape, f.covariance.shape
        ((5, 4), (5, 6, 6))
        """
        q = attitude.as_quat() if isinstance(attitude, Rotation) else check_quaternions("attitude", attitude)
        s_att = check_positive("attitude_sigma", attitude_sigma, "rad", at_most=math.pi)
        # past any gyroscope's bias (sensors' MAX_GYRO_ERROR, 11 deg/s): deg/s written as rad/s (a walkthrough's 2)
        s_b = check_positive("bias_sigma", bias_sigma, "rad/s", at_most=MAX_GYRO_ERROR)
        P = np.diag([s_att**2] * 3 + [s_b**2] * 3) * np.ones(q.shape[:-1] + (1, 1))
        b = _batch("bias", check_vectors("bias", bias, "rad/s"), q.shape[:-1])
        with warnings.catch_warnings():  # a scalar-first guess is warned of once, as attitude
            warnings.simplefilter("ignore", ScalarFirstWarning)
            return cls(q, b, P, gyro_noise, bias_walk)

    @property
    def attitude(self) -> Rotation:
        """The estimated attitude, body to world (scipy Rotation).

        Examples
        --------
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF.start(Rotation.from_rotvec([0.0, 0.0, 0.5]), attitude_sigma=0.1, bias_sigma=1e-3, gyro_noise=0.0, bias_walk=0.0)
        >>> round(float(f.attitude.magnitude()), 12)
        0.5
        """
        return Rotation.from_quat(self.quaternion)

    @property
    def sigma(self) -> FloatArray:
        """Standard deviations of the attitude error (rad, 3) and the bias error (rad/s, 3), shape (..., 6).

        Examples
        --------
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> MEKF.start(Rotation.identity(), attitude_sigma=0.1, bias_sigma=1e-3, gyro_noise=0.0, bias_walk=0.0).sigma.tolist()
        [0.1, 0.1, 0.1, 0.001, 0.001, 0.001]
        """
        return np.asarray(np.sqrt(np.diagonal(self.covariance, axis1=-2, axis2=-1)), float)

    def _new(self, q: FloatArray, b: FloatArray, P: FloatArray) -> MEKF:
        out = object.__new__(MEKF)
        object.__setattr__(out, "quaternion", q)
        object.__setattr__(out, "bias", b)
        object.__setattr__(out, "covariance", P)
        object.__setattr__(out, "gyro_noise", self.gyro_noise)
        object.__setattr__(out, "bias_walk", self.bias_walk)
        return out

    def propagate(self, gyro: ArrayLike, dt: float) -> MEKF:
        """Propagate over ``dt`` (s, > 0) with the gyroscope's reading ``gyro`` (rad/s, shape (..., 3)) held.

        Examples
        --------
        Without noise densities and with the bias known the covariance only turns with the
        body; a quarter turn about z swaps the x and y variances:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF(Rotation.identity().as_quat(), np.zeros(3), np.diag([1e-4, 4e-4, 1e-4, 0.0, 0.0, 0.0]), 0.0, 0.0)
        >>> g = f.propagate([0.0, 0.0, np.pi / 2], 1.0)
        >>> np.round(np.diag(g.covariance)[:3] * 1e4, 9).tolist()
        [4.0, 1.0, 1.0]
        """
        h = check_positive("dt", dt, "s")
        w = np.asarray(gyro, float)
        if w.ndim == 0 or w.shape[-1] != 3:
            raise ValueError(f"gyro = {short_repr(gyro)} must be the gyroscope's rates about the 3 body axes, "
                             f"shape (3,) or (..., 3) (rad/s)")
        shape = self.quaternion.shape[:-1]
        if w.shape[:-1] != shape:
            shape = np.broadcast_shapes(shape, w.shape[:-1])
        q, b, P = self._flat(shape)
        w = w.reshape(-1, 3) if w.shape[:-1] == shape else np.broadcast_to(w, shape + (3,)).reshape(-1, 3)
        from .mekf_kernels import propagate  # compiled at import: numba only when a filter steps

        propagate(q, b, P, np.ascontiguousarray(w), h, float(self.gyro_noise), float(self.bias_walk))
        return self._new(q.reshape(shape + (4,)), b.reshape(shape + (3,)), P.reshape(shape + (6, 6)))

    def _flat(self, shape: tuple[int, ...]) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Copies of the state broadcast to ``shape`` and flattened, for the kernels to write."""
        if self.quaternion.shape[:-1] == shape and self.bias.shape[:-1] == shape:
            return self.quaternion.reshape(-1, 4).copy(), self.bias.reshape(-1, 3).copy(), self.covariance.reshape(-1, 6, 6).copy()
        return (np.array(np.broadcast_to(self.quaternion, shape + (4,)).reshape(-1, 4)),
                np.array(np.broadcast_to(self.bias, shape + (3,)).reshape(-1, 3)),
                np.array(np.broadcast_to(self.covariance, shape + (6, 6)).reshape(-1, 6, 6)))

    def _update(self, y: FloatArray, H: FloatArray, R: FloatArray, valid: ArrayLike | None,
                vectors: FloatArray = np.zeros((0, 7)), shape: tuple[int, ...] | None = None) -> tuple[MEKF, FloatArray]:
        """The Kalman update of the kernel; ``vectors`` (n, 7) for the vector update, ``shape`` its batch."""
        if shape is None:
            shape = np.broadcast_shapes(self.quaternion.shape[:-1], y.shape[:-1], H.shape[:-2], R.shape[:-2],
                                        np.shape(valid) if valid is not None else ())
        m = y.shape[-1]
        q, b, P = self._flat(shape)
        ok = np.ones(shape, bool) if valid is None else np.broadcast_to(np.asarray(valid, bool), shape)
        nis = np.empty(int(np.prod(shape, dtype=int)))
        if vectors.shape[0] == 0:
            y, H, R = _rows(y, shape, (m,)), _rows(H, shape, (m, 6)), _rows(R, shape, (m, m))
        from .mekf_kernels import update  # compiled at import: numba only when a filter steps

        update(q, b, P, y, H, R, kernel_array(ok.reshape(-1), dtype=bool), nis, vectors)
        return (self._new(q.reshape(shape + (4,)), b.reshape(shape + (3,)), P.reshape(shape + (6, 6))),
                nis.reshape(shape))

    def update_vector(self, body: ArrayLike, reference: ArrayLike, sigma: ArrayLike,
                      valid: ArrayLike | None = None) -> tuple[MEKF, FloatArray]:
        """Update with a measured direction: ``body`` (body frame) of the world direction ``reference``.

        Parameters
        ----------
        body, reference : array_like, shape (..., 3)
            The measured direction and the known one (any length; normalised here).
        sigma : float or array_like, shape (...)
            The measurement's angular noise across the direction, rad (> 0).
        valid : array_like of bool, shape (...), optional
            Which filters of a batch take the measurement (the others are returned as they were,
            with a NaN NIS): a sun sensor in eclipse, say.

        Returns
        -------
        filter : MEKF
        nis : ndarray, shape (...)
            The normalised innovation squared (chi-square with 2 degrees of freedom).

        Examples
        --------
        One direction fixes two axes, not the turn about it:

        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF.start(Rotation.identity(), attitude_sigma=0.1, bias_sigma=1e-3, gyro_noise=0.0, bias_walk=0.0)
        >>> g, nis = f.update_vector([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], 1e-3)
        >>> g.sigma[:3].round(4).tolist(), float(nis)
        ([0.001, 0.001, 0.1], 0.0)
        """
        bm, r, s = np.asarray(body, dtype=float), np.asarray(reference, dtype=float), np.asarray(sigma, dtype=float)
        if not (bm.shape[-1:] == r.shape[-1:] == (3,) and np.isfinite(bm).all() and np.isfinite(r).all()):
            check_vectors("body", body, "direction")   # the one-line message naming the argument
            check_vectors("reference", reference, "direction")
        if not np.all(np.isfinite(s) & (s > 0.0) & (s <= math.pi)):
            raise ValueError(f"sigma = {s.tolist()!r} must be positive finite numbers, at most pi (rad): an angle")
        if s.ndim > 0 and bm.ndim == r.ndim == 1 and self.quaternion.ndim == 1 and valid is None:
            # one filter, one direction: three sigmas made a batch of three filters (a walkthrough, 2026-12-03)
            raise ValueError(f"sigma = {s.tolist()!r} must be one angle (rad), the noise across the direction, for one "
                             "filter and one direction: not one per axis (a batch takes one per filter)")
        for name, vec in (("body", bm), ("reference", r)):
            refuse_first(name, vec, np.sum(vec * vec, axis=-1) == 0.0, "must not be zero: a direction is needed")
        shape = self.quaternion.shape[:-1]
        if not (bm.shape[:-1] == r.shape[:-1] == shape and s.ndim == 0 and valid is None):
            shape = np.broadcast_shapes(shape, bm.shape[:-1], r.shape[:-1], s.shape,
                                        np.shape(np.asarray(valid, bool)) if valid is not None else ())
        v = np.empty(shape + (7,))
        v[..., :3], v[..., 3:6], v[..., 6] = bm, r, s
        n = v.size // 7
        return self._update(np.empty((n, 2)), np.empty((n, 2, 6)), np.empty((n, 2, 2)), valid, v.reshape(n, 7), shape)

    def update_attitude(self, measured: Rotation | ArrayLike, covariance: ArrayLike,
                        valid: ArrayLike | None = None) -> tuple[MEKF, FloatArray]:
        """Update with a measured attitude (a star tracker's, body to world) of ``covariance`` (3 x 3, rad^2, body axes).

        Returns the filter and the NIS (chi-square with 3 degrees of freedom).

        Examples
        --------
        Two equal informations halve the variance:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF.start(Rotation.identity(), attitude_sigma=1e-3, bias_sigma=1e-3, gyro_noise=0.0, bias_walk=0.0)
        >>> g, nis = f.update_attitude(Rotation.from_rotvec([2e-3, 0.0, 0.0]), np.eye(3) * 1e-6)
        >>> np.round(g.attitude.as_rotvec() * 1e3, 6).tolist(), round(float(g.sigma[0] ** 2 * 1e6), 9), round(float(nis), 6)
        ([1.0, 0.0, 0.0], 0.5, 2.0)
        """
        qm = measured.as_quat() if isinstance(measured, Rotation) else check_quaternions("measured", measured)
        R = check_covariance("covariance", covariance, 3, "rad^2")
        shape = np.broadcast_shapes(self.quaternion.shape[:-1], qm.shape[:-1], R.shape[:-2],
                                    np.shape(np.asarray(valid, bool)) if valid is not None else ())
        n = int(np.prod(shape, dtype=int))
        # the kernel forms y = rotvec(q* (x) q_m) and H = [I, 0] from the measured quaternions
        return self._update(np.empty((n, 3)), np.empty((n, 3, 6)), _rows(R, shape, (3, 3)), valid, _rows(qm, shape, (4,)), shape)

    def error(self, truth: Rotation | ArrayLike) -> FloatArray:
        """The attitude error ``dtheta`` with ``A_true = A_est exp([dtheta x])``, body axes, rad, shape (..., 3).

        Examples
        --------
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF.start(Rotation.identity(), attitude_sigma=0.1, bias_sigma=1e-3, gyro_noise=0.0, bias_walk=0.0)
        >>> f.error(Rotation.from_rotvec([0.0, 0.02, 0.0])).round(12).tolist()
        [0.0, 0.02, 0.0]
        """
        qt = truth.as_quat() if isinstance(truth, Rotation) else np.asarray(truth, float)
        shape = np.broadcast_shapes(self.quaternion.shape[:-1], qt.shape[:-1])
        n = int(np.prod(shape, dtype=int))
        y = np.empty((n, 3))   # the attitude update's innovation rotvec(q* (x) q_true), formed by the kernel, no update
        self._update(y, np.empty((n, 3, 6)), np.zeros((n, 3, 3)), np.zeros(shape, bool), _rows(qt, shape, (4,)), shape)
        return y.reshape(shape + (3,))

    def nees(self, truth: Rotation | ArrayLike, bias: ArrayLike | None = None) -> FloatArray:
        """The normalised estimation error squared: of the attitude (chi-square 3) or, given the
        true ``bias`` (rad/s), of attitude and bias (chi-square 6); shape (...).

        Examples
        --------
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.estimation.mekf import MEKF
        >>> f = MEKF.start(Rotation.identity(), attitude_sigma=0.1, bias_sigma=1e-3, gyro_noise=0.0, bias_walk=0.0)
        >>> round(float(f.nees(Rotation.from_rotvec([0.0, 0.2, 0.0]))), 9), round(float(f.nees(Rotation.identity(), [0.0, 0.0, 2e-3])), 9)
        (4.0, 4.0)
        """
        e = self.error(truth)
        if bias is None:
            return np.asarray(np.einsum("...i,...ij,...j->...", e, np.linalg.inv(self.covariance[..., :3, :3]), e), float)
        x = np.concatenate([e, _batch("bias", check_vectors("bias", bias, "rad/s"), e.shape[:-1]) - self.bias], axis=-1)
        return np.asarray(np.einsum("...i,...ij,...j->...", x, np.linalg.inv(self.covariance), x), float)
