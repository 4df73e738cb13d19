"""Throws of one rigid mount fitted together: one tensor, each throw its own motion (issue #42).

The throws of one object with the device fixed to it fly one rigid body: one tensor about one
centre of mass. :class:`JointModel` fits them together: the tensor's ``C`` (6, shared) and, per
throw, ``L(t_0)``, the gyroscope's bias, the per-axis drag, the rotor log's lag and its drag (11 each), each throw's samples
predicted by its own :class:`~tumble.analysis.tensor.model.ThrowModel` (the gyrostat's momentum
form with its measured rotor). One throw is the case of a single-throw fit, so a throw's own
estimate and the pooled one come from the same code. The centre of mass is likewise one
accelerometer offset for all the throws, each with its own accelerometer bias
(:func:`~tumble.analysis.tensor.center.center_of_mass`).

**Why jointly, not a weighted mean of per-throw estimates.** Each throw's estimate carries a
covariance that grows with the estimate (a throw that came out large states a large std), so an
inverse-covariance mean is pulled low; on the real device's throws it landed below every one
of its 12 throws on one object. The joint fit weighs the samples, not the estimates.

**Uncertainty.** Statistical: ``(J^T J)^-1 s^2 tau`` with each throw's residual autocorrelation
time (:func:`tumble.analysis.fit.uncertainty.effective_covariance`). Systematic, type B (JCGM
100:2008, sec. 4.3): the gyroscope's scale factors and misalignment and the rotor's axis, each
with its stated standard uncertainty (:class:`~tumble.analysis.tensor.sensors.SensorErrors`), propagated through the fit's
linear response ``dP = -(J^T J)^-1 J^T (dr/de) de`` (the first-order shift of a least-squares
optimum under a change ``de`` of the model; the implicit function theorem at the optimum). The
tensor's scale rests on the rotor's reaction, a 10-20 % change of a thrown object's momentum,
so a 0.5 % error of the rates moves it by up to 4 %: this term dominates a single throw's
uncertainty and is shared by all the throws of one device (it is added once, to the joint
fit's covariance, not averaged down). When the joint fit determines the gyroscope's distortion
and the rotor's tilt (:class:`JointModel` with ``sensor``), what it cannot see is left: the
rates' common scale, and the turn of the gyroscope's axes from the sensor frame (the
misalignment's antisymmetric part, std ``gyro_misalignment / sqrt 2`` about each axis), which
turns the tensor with them: ``dI = [e]x I - I [e]x``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.linalg import cho_factor, cho_solve
from scipy.spatial.transform import Rotation

from ..._html import headline_html, headline_repr
from ...typing import FloatArray
from ..fit.uncertainty import effective_covariance
from .estimate import vector_of
from .flight import skew
from .model import DYNAMIC, NONNEGATIVE, ThrowModel, inertia_jacobian, inertia_of
from .sensors import GYRO_BASIS, GYRO_ENTRIES, SENSOR_NAMES, SensorErrors, axis_normals, gyro_matrix, tilted_axis
from .solve import fit_held

__all__ = ["JointFit", "JointModel", "fit_joint"]


class JointModel:
    """Several throws' models sharing one tensor and, optionally, the sensors as built (module docstring).

    Parameters: ``C`` (6); with ``sensor``, the gyroscope's trace-free symmetric distortion (5:
    :data:`~tumble.analysis.tensor.sensors.GYRO_BASIS`) and the rotor axis's tilt from its nominal (2 angles about the two
    axes normal to it, rad); then for each throw ``L(t_0)``, bias, drag, the rotor's lag and
    drag (11). Residuals are the throws' in order.

    What the joint fit determines of the sensors: the gyroscope's misalignment has a symmetric
    part (a distortion of the rates) and an antisymmetric one (a turn of the gyroscope's axes
    against the rotor's, which is the rotor axis's tilt, and about it a turn of the whole frame,
    which no fit can see); the distortion's trace, a common scale of the rates, trades with the
    tensor's scale and is left to the stated uncertainty. One throw does not separate the
    distortion from the tensor (its own estimate then shifts by several per cent); throws
    spinning about different axes do, since they share one tensor.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.joint import JointModel
    >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
    >>> t = np.arange(400) / 4000.0
    >>> rotor = rotor_input(t, np.full(400, 1e3), 0, 1e-6, [0, 0, 1])
    >>> models = [ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor) for _ in range(2)]
    >>> joint = JointModel(models, sensor=True)
    >>> joint.n, joint.throw_parameters(np.arange(35.0), 1).tolist()[6:]
    (35, [24.0, 25.0, 26.0, 27.0, 28.0, 29.0, 30.0, 31.0, 32.0, 33.0, 34.0])
    """

    def __init__(self, models: Sequence[ThrowModel], sensor: bool = False) -> None:
        if not models or any(not m.drag for m in models):
            raise ValueError("a joint fit needs one or more throw models, each with its drag")
        self.models = list(models)
        self.sensor = bool(sensor)
        self.base = 6 + (len(SENSOR_NAMES) if self.sensor else 0)
        self.per = self.models[0].n - 6
        if any(m.n - 6 != self.per for m in self.models):
            raise ValueError("the throws' models of a joint fit must have the same parameters")
        self.n = self.base + self.per * len(self.models)
        self.rows = [int(np.count_nonzero(m.keep)) for m in self.models]
        a = self.models[0].rotor.axis
        self.axis0 = a / np.linalg.norm(a)
        self.normals = axis_normals(self.axis0)

    def throw_parameters(self, P: FloatArray, k: int) -> FloatArray:
        """Throw ``k``'s parameters (``C``, ``L(t_0)``, bias, drag, lag) of the joint vector ``P``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> joint.throw_parameters(np.arange(24.0), 0)[[0, 5, 6, 16]].tolist()   # C, then the throw's own past the sensors'
        [0.0, 5.0, 13.0, 23.0]
        """
        return np.r_[P[:6], P[self.base + self.per * k: self.base + self.per * (k + 1)]]

    def pack(self, c: FloatArray, rest: Sequence[FloatArray], sensor: FloatArray | None = None) -> FloatArray:
        """The joint vector of ``C``, the sensors' (zeros by default) and each throw's own (``L(t_0)``, bias, drag, lag).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> joint.pack(np.ones(6), [np.full(11, 2.0)]).tolist() == [1.0] * 6 + [0.0] * 7 + [2.0] * 11
        True
        """
        shared = np.zeros(self.base - 6) if sensor is None else np.asarray(sensor, float)
        return np.concatenate([np.asarray(c, float), shared, *[np.asarray(r, float)[:self.per] for r in rest]])

    def gyro(self, P: FloatArray) -> FloatArray:
        """``omega_read = gyro @ omega``: the identity plus the fitted distortion.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> P = joint.pack(np.ones(6), [np.zeros(11)], [0.01, 0.0, 0.002, 0.0, 0.0, 0.0, 0.0])
        >>> joint.gyro(P).round(6).tolist()   # xx - zz and xy: symmetric and trace-free
        [[1.01, 0.002, 0.0], [0.002, 1.0, 0.0], [0.0, 0.0, 0.99]]
        """
        return gyro_matrix(P[6:11]) if self.sensor else np.eye(3)

    def axis(self, P: FloatArray) -> FloatArray:
        """The rotor's axis, tilted by the fitted angles (unit, sensor frame).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> a = joint.axis(joint.pack(np.ones(6), [np.zeros(11)], [0, 0, 0, 0, 0, 0.01, 0.0]))
        >>> round(float(np.degrees(np.arccos(a[2]))), 4)   # tilted 0.01 rad from z
        0.573
        """
        if not self.sensor:
            return self.axis0
        return tilted_axis(self.axis0, P[11:13])

    def _rates(self, k: int, rows: FloatArray, axis: FloatArray) -> FloatArray:
        m = self.models[k]
        return m.omega(rows) if not self.sensor else m.omega(rows, axis)

    def rates(self, P: FloatArray) -> list[FloatArray]:
        """Each throw's body rates at its samples (the rotor tilted as fitted; not as read: no
        distortion, no bias), rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> m = ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor_input(t, np.zeros(400), 0, 1e-6, [0, 0, 1]))
        >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 0.0, 0.0, 4e-3, np.zeros(8)]   # 10 rad/s about z
        >>> JointModel([m]).rates(P)[0][-1].round(9).tolist()
        [0.0, 0.0, 10.0]
        """
        a = self.axis(P)
        return [self._rates(k, self.throw_parameters(P, k)[None], a)[0] for k in range(len(self.models))]

    def residuals(self, P: FloatArray) -> FloatArray:
        """Every throw's ``model - data`` on its kept samples, flat, rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> P = joint.pack(cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), [np.r_[0.0, 0.0, 4e-3, 0.1, 0.0, 0.0, np.zeros(5)]])
        >>> r = joint.residuals(P)
        >>> r.shape, bool(np.allclose(r[:3], [0.1, 0.0, 10.0]))   # 10 rad/s about z, 0.1 rad/s of bias on x
        ((1200,), True)
        """
        S, a = self.gyro(P), self.axis(P)
        out = []
        for k, m in enumerate(self.models):
            Pk = self.throw_parameters(P, k)
            out.append((self._rates(k, Pk[None], a)[0] @ S.T + Pk[9:12] - m.data)[m.keep])
        return np.concatenate(out)

    def jacobian(self, P: FloatArray) -> FloatArray:
        """``d residuals / dP`` (dense: rows of each throw, its own columns and the shared ones).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> P = joint.pack(cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), [np.r_[0.0, 0.0, 4e-3, np.zeros(8)]])
        >>> J = joint.jacobian(P)
        >>> J.shape, bool(np.allclose(J[:3, 16:19], np.eye(3)))   # the bias: 1 on its own axis
        ((1200, 24), True)
        """
        J = np.zeros((sum(self.rows), self.n))
        S, a = self.gyro(P), self.axis(P)
        row = 0
        for k, m in enumerate(self.models):
            Pk = self.throw_parameters(P, k)
            d = m.steps(Pk)
            batch = np.vstack([Pk, Pk + np.diag(d)[DYNAMIC]])
            w = self._rates(k, batch, a)
            cols = np.einsum("ij,ctj->cti", S, (w[1:] - w[0]) / d[DYNAMIC, None, None])
            rows = slice(row, row + self.rows[k])
            J[rows, :6] = cols[:6, m.keep].T
            own = self.base + self.per * k
            J[rows, own:own + 3] = cols[6:9, m.keep].T
            J[rows, own + 3:own + 6] = np.broadcast_to(np.eye(3), w[0].shape + (3,))[m.keep]
            J[rows, own + 6:own + self.per] = cols[9:, m.keep].T
            if self.sensor:
                for c, B in enumerate(GYRO_BASIS):
                    J[rows, 6 + c] = (w[0] @ B.T)[m.keep]
                for c in range(2):
                    step = np.zeros(P.size)
                    step[11 + c] = _TILT_STEP
                    tilted = self._rates(k, Pk[None], self.axis(P + step))[0]
                    J[rows, 11 + c] = ((tilted - w[0]) @ S.T / _TILT_STEP)[m.keep]
            row += self.rows[k]
        return J

    def error_columns(self, P: FloatArray) -> FloatArray:
        """``dr/de`` for what the fit leaves to the stated uncertainties (:meth:`~tumble.analysis.tensor.sensors.SensorErrors.variances`):
        without ``sensor``, the 9 gyroscope entries and the rotor axis's 2 angles; with it, the rates'
        common scale only.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.joint import JointModel
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.where(t > 0.02, 800.0, 0.0), 81, 1e-6, [0, 0, 1])
        >>> joint = JointModel([ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor)], sensor=True)
        >>> P = joint.pack(cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), [np.r_[0.0, 0.0, 4e-3, np.zeros(8)]])
        >>> E = joint.error_columns(P)
        >>> E.shape, E[:3, 0].round(9).tolist()   # a common scale of the rates moves the reading by the rates
        ((1200, 1), [0.0, 0.0, 10.0])
        """
        S, a = self.gyro(P), self.axis(P)
        cols = np.zeros((sum(self.rows), 1 if self.sensor else 11))
        row = 0
        for k, m in enumerate(self.models):
            Pk = self.throw_parameters(P, k)
            w = self._rates(k, Pk[None], a)[0]
            rows = slice(row, row + self.rows[k])
            if self.sensor:
                cols[rows, 0] = (w @ S.T)[m.keep]
                row += self.rows[k]
                continue
            for c, (i, j) in enumerate(GYRO_ENTRIES):
                col = np.zeros_like(w)
                col[:, i] = w[:, j]
                cols[rows, c] = col[m.keep]
            for c, u in enumerate(self.normals):
                tilted = m.omega(Pk[None], Rotation.from_rotvec(_TILT_STEP * u).apply(a))[0]
                cols[rows, 9 + c] = ((tilted - w) / _TILT_STEP)[m.keep]
            row += self.rows[k]
        return cols


#: The rotor axis's tilt for finite differences, rad.
_TILT_STEP = 1e-4


@dataclass(frozen=True)
class JointFit:
    """A joint fit's optimum and uncertainties.

    Attributes
    ----------
    P : ndarray
        The joint parameters (``C``, the sensors' when fitted, then each throw's own).
    cov_P : ndarray
        Their statistical covariance (rows and columns of parameters held on a bound are 0).
    inertia : ndarray, shape (3, 3)
        kg m^2 (or units of ``J_r``).
    inertia_cov, inertia_cov_stat, inertia_cov_sensor : ndarray, shape (6, 6)
        The tensor entries' covariance, its statistical and its sensors' (type B) parts.
    rms : ndarray
        Each throw's residual RMS, rad/s.
    sensor_columns : ndarray, shape (6, k), optional
        The sensors' part as columns, one per error source of the device (each the tensor's
        shift for one standard uncertainty of it): ``inertia_cov_sensor = S S^T``. Two fits on
        throws of one device share these errors, so their tensors' cross-covariance is
        ``S_1 S_2^T`` (:func:`~tumble.analysis.tensor.calibrate.calibrate`).

    Examples
    --------
    >>> from tumble.analysis.tensor.joint import JointFit
    >>> sorted(JointFit.__dataclass_fields__)[:3]
    ['P', 'cov_P', 'inertia']
    """

    HEADLINE = (("rms", "RMS residuals", "rad/s"), ("inertia", "tensor", "kg m^2"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    P: FloatArray
    cov_P: FloatArray
    inertia: FloatArray
    inertia_cov: FloatArray
    inertia_cov_stat: FloatArray
    inertia_cov_sensor: FloatArray
    rms: FloatArray
    sensor_columns: FloatArray | None = None


def _drag_index(joint: JointModel) -> np.ndarray:
    """The joint vector's drags (held non-negative: :data:`~tumble.analysis.tensor.model.NONNEGATIVE`)."""
    own = NONNEGATIVE[NONNEGATIVE < joint.models[0].n] - 6
    return np.concatenate([joint.base + joint.per * k + own for k in range(len(joint.models))])


def _normal_solver(J: sparse.csr_matrix):
    """``B -> (J^T J)^+ J^T B``, the least-squares answer to ``B`` through the normal equations scaled to
    a unit diagonal (as :func:`~tumble.analysis.fit.uncertainty.effective_covariance` inverts them):
    one product ``J^T J`` and a small inverse, where a dense least squares of the tall ``J`` for
    each ``B`` took seconds of a loaded machine (its threaded level-2 steps)."""
    JtJ = (J.T @ J).toarray()
    d = np.sqrt(np.diag(JtJ))
    d = np.where(d > 0, d, 1.0)
    scaled = JtJ / np.outer(d, d)
    try:  # a Cholesky factor (a few blocked steps: no threaded level-2 sweeps as an SVD's), else the pseudo-inverse
        factor = cho_factor(scaled)
        return lambda B: cho_solve(factor, np.asarray(J.T @ B) / d[:, None]) / d[:, None]
    except np.linalg.LinAlgError:
        inverse = np.linalg.pinv(scaled) / np.outer(d, d)
        return lambda B: inverse @ np.asarray(J.T @ B)


def fit_joint(joint: JointModel, P0: FloatArray, errors: SensorErrors | None = None,
              held: np.ndarray | None = None, optimize: bool = True) -> JointFit:
    """The joint optimum from ``P0``, drag never negative (held at 0 and refitted, the active set as
    :func:`tumble.analysis.tensor.throw.fit_flown`'s), with its uncertainties (module docstring);
    the parameters ``held`` (a mask) stay at ``P0``'s values; without ``optimize``, ``P0`` is taken
    as the optimum (its drags at 0 held there) and only the uncertainties are found.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.joint import JointModel, fit_joint
    >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
    >>> t = np.arange(2000) / 4000.0
    >>> speed = np.where(t > 0.1, 1000.0 * (1 - np.exp(-(t - 0.1) / 0.04)), 0.0)
    >>> rotor = rotor_input(t, speed, int(np.argmax(t > 0.1)), 2e-6, [0, 0, 1])
    >>> I = np.array([[2e-4, 1e-5, 0.0], [1e-5, 3e-4, 0.0], [0.0, 0.0, 4e-4]])
    >>> truth = [np.r_[cholesky_of(I), L, 0.01, -0.02, 0.0, 0, 0, 0, 3e-4, 0] for L in ([1e-3, 2e-3, 0], [0, -2e-3, 1e-3])]
    >>> models = [ThrowModel(t, np.zeros((2000, 3)), np.ones((2000, 3), bool), rotor) for _ in truth]
    >>> models = [ThrowModel(t, m.sensor(P[None])[0], m.keep, rotor) for m, P in zip(models, truth)]
    >>> joint = JointModel(models)
    >>> fit = fit_joint(joint, joint.pack(cholesky_of(1.1 * I), [P[6:] for P in truth]), None)
    >>> bool(np.allclose(fit.inertia, I, rtol=1e-6, atol=1e-12))
    True
    """
    free = np.ones(joint.n, bool) if held is None else ~np.asarray(held, bool)
    drag = _drag_index(joint)
    if optimize:
        P, free = fit_held(joint, np.asarray(P0, float), free, drag, max_nfev=200)
    else:
        P = np.asarray(P0, float).copy()
        free[drag[P[drag] <= 0]] = False
    J_all = joint.jacobian(P)
    J = sparse.csr_matrix(J_all[:, free])  # a throw's rows touch the shared columns and its own only
    r = joint.residuals(P)
    per_sample = np.zeros((sum(m.t.size for m in joint.models), 3))
    keep_all = np.concatenate([m.keep for m in joint.models])
    per_sample[keep_all] = r
    starts = np.cumsum([0] + [m.t.size for m in joint.models])
    cov_free, _ = effective_covariance(J, r, per_sample, list(starts))
    cov = np.zeros((joint.n, joint.n))
    cov[np.ix_(free, free)] = cov_free
    G = inertia_jacobian(P[:6])
    cov_stat = G @ cov[:6, :6] @ G.T
    S = np.zeros((6, 0))
    if errors is not None:
        E = joint.error_columns(P)
        solve = _normal_solver(J)
        shift = -solve(E)  # dP_free / de
        dC = np.zeros((6, E.shape[1]))
        dC[free[:6]] = shift[: int(np.count_nonzero(free[:6]))]
        S = G @ dC * np.sqrt(errors.variances(fitted=joint.sensor))
        held_sensor = joint.sensor and not free[6:joint.base].any()
        if held_sensor and errors.calibrated:  # held at a calibration's values: their uncertainty moves the tensor
            Jh = J_all[:, 6:joint.base]
            dh = np.zeros((6, Jh.shape[1]))
            dh[free[:6]] = -solve(Jh)[: int(np.count_nonzero(free[:6]))]
            S = np.hstack([S, G @ dh * errors.held_std()])
        if joint.sensor:  # the gyroscope's axes turned from the sensor frame: the tensor turns with them
            I = inertia_of(P[:6])
            turns = np.array([vector_of(skew(e) @ I - I @ skew(e)) for e in np.eye(3)]).T
            S = np.hstack([S, turns * errors.gyro_misalignment / np.sqrt(2.0)])
    cov_sensor = S @ S.T
    bounds = np.cumsum([0] + joint.rows)
    rms = np.array([np.sqrt(np.mean(r[a:b] ** 2)) for a, b in zip(bounds[:-1], bounds[1:])])
    return JointFit(P, cov, inertia_of(P[:6]), cov_stat + cov_sensor, cov_stat, cov_sensor, rms, S)
