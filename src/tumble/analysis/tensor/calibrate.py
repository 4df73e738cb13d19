"""Calibrating the device: the rotor's inertia, the device's tensor and its centre of mass
(:func:`calibrate_device`).

Without a known rotor inertia the throws determine tensors in units of ``J_r`` only: the
gyrostat's equations are unchanged when ``I``, ``h`` (so ``J_r``) and ``L`` are multiplied by
one factor. So both sets of throws are fitted with ``J_r = 1``:

- the device **alone** gives ``D = I_d / J_r`` and its centre ``c_d`` (the accelerometer gives
  centres in metres, whatever ``J_r``);
- the device with the **proof** body gives ``P = I_dp / J_r`` and the centre ``c_dp`` of both,
  hence the proof's centre ``c_p = (M c_dp - m_d c_d) / m_p``, ``M = m_d + m_p``.

The parallel-axis theorem about the accelerometer (Goldstein, Poole & Safko, *Classical
Mechanics*, 3rd ed., sec. 5.3; ``S(d) = |d|^2 E - d d^T``),
``J_r P + M S(c_dp) = J_r D + m_d S(c_d) + I_p + m_p S(c_p)``, gives six equations for ``J_r``:

    ``J_r (P - D) = B``,  ``B = I_p + m_p S(c_p) + m_d S(c_d) - M S(c_dp)``,

solved with ``J_r`` by weighted least squares (weights the inverse covariance of
``J_r (P - D) - B``, two passes) with ``chi^2`` on 5 degrees of freedom, and ``D`` and ``c_d``
**adjusted** to them (a Gauss-Helmert adjustment: :mod:`~tumble.analysis.tensor.equations`); a
``chi^2 / 5 > 1`` inflates the results' variance (Birge, as in :mod:`~tumble.analysis.tensor.pool`).
Then ``I_d = J_r D``. The equations fix the device's centre along the rotor's axis, which its
own throws, spinning about that axis, hardly show the accelerometer: the proof's known tensor
fixes the offset between the two sets' centres, and the proof set's centre is well seen. All the
uncertainties (the pooled ``D``, ``P``, ``c_d``, ``c_dp``, the tensors' sensors' parts shared by
the two sets: :func:`shared_sensor_covariance`; the centres' sensors' parts, the accelerometer's
scale factors and the gyroscope's turn, likewise shared: :func:`shared_center_covariance`; the
proof taken as exact) are propagated to ``(J_r, I_d, c_d)`` through the map's Jacobian (central
differences; the law of propagation of uncertainty, JCGM 100:2008, sec. 5.1).

**Two chi^2.** The weights, ``J_r``'s variance and its Birge ratio use the whole covariance,
the centres' sensors' parts in it: without them the centres stated 1/3 (``c_d``) and 1/2
(``c_dp``) of their errors on realistic devices, the equations' ``chi^2 / 5`` came out 1.6
(median of 13) and its Birge ratio widened ``J_r``'s interval for what the centres, not ``J_r``,
lacked. The **consistency check** (:data:`MAX_CHI2_DOF`) is the ``chi^2`` with the centres'
statistical covariance only: a 1 % error of the accelerometer's scale along the proof's offset
moves ``B`` in the pattern a mis-stated proof does (the parallel-axis terms' share of
``B``), so with it a proof stated 10 % high passed unflagged; the check's threshold is set
from realistic devices, whose accelerometers carry such errors (below).

**A calibration that checks itself** (:func:`calibrate`, issue #42): the equations' ``chi^2 / 5``
(above :data:`MAX_CHI2_DOF` the proof is not what was stated or not mounted as stated, or the
proof throws are of another object), each set's agreement about its joint fit (above
:data:`MAX_SET_CHI2_DOF` its throws are not of one rigid body), a rotor inertia that is not
positive (the sets swapped), and each throw's fitted gyroscope bias (a throw that needs more
than a gyroscope has is left out: :func:`~tumble.analysis.tensor.verdicts.throw_verdict`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ...typing import FloatArray
from .. import _display
from .device import MAX_ROTOR_SPEED, ROTOR_SPEED_RATIO, Device, Proof
from .throwlog import Throw
from .equations import rotor_inertia_from
from .estimate import tensor_of
from .sensors import gyro_matrix, tilted_axis
from .fit import full_scale, sensor_errors
from .pool import Pooled, pool_throws
from .verdicts import duplicate_throws

__all__ = ["MAX_CHI2_DOF", "MAX_SET_CHI2_DOF", "Calibration", "CalibrationError", "calibrate", "calibrate_device",
           "calibrated_sensors", "shared_center_covariance", "shared_sensor_covariance"]


#: The calibration's consistency (``chi^2 / 5`` of its parallel-axis equations) above which it is
#: refused: the equations hold to their uncertainties when the proof is what was stated, mounted as
#: stated (25 realistic calibrations of benchmarks/tensor_coverage.py: median 1.48, largest 3.8; of
#: 100 of benchmarks/calibration_coverage.py, 3 above it, up to 6.2;
#: ``chi^2`` on 5 degrees of freedom exceeds 4 x 5 with probability 0.1 %); a proof mounted turned
#: 90 degrees or another object's throws give ~10^4, a proof tensor stated 10 % high ~5.
MAX_CHI2_DOF = 4.0
#: The throws of one set (device alone, or with the proof) whose tensors' ``chi^2 / dof`` about their
#: joint fit (:func:`~tumble.analysis.tensor.pool.agreement`) exceeds this disagree: they are not
#: throws of one rigid body with this device. Realistic sets reach 10 (median 0.9 alone, 0.2 with the
#: proof; the lone refits' statistical covariances do not hold all that varies from throw to throw,
#: which the Birge ratio then carries; one device-alone set of the 100 of
#: benchmarks/calibration_coverage.py 36, a false alarm), throws of two bodies 10^3 and more.
MAX_SET_CHI2_DOF = 20.0


@dataclass(frozen=True)
class Calibration:
    """A calibration and how well it checks itself (issue #42 item 3).

    Attributes
    ----------
    device : Device
        The calibrated device.
    chi2_dof : float
        ``chi^2 / 5`` of the parallel-axis equations for the rotor's inertia (1 when they hold to
        their uncertainties).
    alone_chi2_dof, proof_chi2_dof : float
        Each set's throws about their joint fit (NaN for one throw).
    alone_used, proof_used : int
        The throws fitted and used, of each set.
    max_bias : float
        The largest gyroscope bias any used throw's fit needed, rad/s.
    left_out : tuple of str
        ``"FILE: reason"`` of each throw not used.
    problems : tuple of str
        What makes the calibration not to be trusted, each with its likely cause; empty when it
        checks out.

    Examples
    --------
    >>> from tumble.analysis.tensor.calibrate import Calibration
    >>> sorted(Calibration.__dataclass_fields__)[:3]
    ['alone_chi2_dof', 'alone_used', 'chi2_dof']
    """

    device: Device
    chi2_dof: float
    alone_chi2_dof: float
    proof_chi2_dof: float
    alone_used: int
    proof_used: int
    max_bias: float
    left_out: tuple[str, ...]
    problems: tuple[str, ...]

    def __repr__(self) -> str:
        return _display.calibration_repr(self)

    def _repr_html_(self) -> str:
        return _display.calibration_html(self)

    @property
    def adequate(self) -> bool:
        """Whether the calibration checks out (no problem found).

        Examples
        --------
        >>> from tumble.analysis.tensor import Device
        >>> from tumble.analysis.tensor.calibrate import Calibration
        >>> Calibration(Device(0.1, [0, 0, 1]), 9.0, 1.0, 1.0, 3, 3, 0.01, (), ("the proof turned",)).adequate
        False
        """
        return not self.problems

    def as_dict(self) -> dict[str, Any]:
        """The numbers for ``[calibration]`` of a device file (NaN left out).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor import Device
        >>> from tumble.analysis.tensor.calibrate import Calibration
        >>> c = Calibration(Device(0.1, [0, 0, 1]), 1.2, float("nan"), 0.8, 1, 3, 0.02, (), ())
        >>> c.as_dict()["adequate"], "alone_chi2_dof" in c.as_dict()
        (True, False)
        """
        out: dict[str, Any] = {"adequate": self.adequate}
        for key in ("chi2_dof", "alone_chi2_dof", "proof_chi2_dof", "max_bias"):
            value = float(getattr(self, key))
            if np.isfinite(value):
                out[key] = value
        out.update(alone_used=int(self.alone_used), proof_used=int(self.proof_used), left_out=list(self.left_out),
                   problems=list(self.problems))
        return out


def _physical(inertia: FloatArray) -> bool:
    """Whether a tensor's principal moments are positive and keep the triangle inequality."""
    m = np.linalg.eigvalsh(inertia)
    return bool(m[0] > 0 and m[0] + m[1] >= m[2])


def _problems(J: float, ratio: float, a, p) -> list[str]:
    """What the calibration's own numbers say is wrong, with the likely cause."""
    out = []
    if not J > 0:
        out.append(f"the rotor's inertia comes out {J:.3g} kg m^2, not positive: the throws with the proof turn less "
                   "than the device's alone would, so the device-alone and proof throws (--alone, --proof) are likely swapped")
        return out
    if ratio > MAX_CHI2_DOF:
        out.append(f"the parallel-axis equations disagree with the proof body as stated: chi2/dof {ratio:.3g} (at most "
                   f"{MAX_CHI2_DOF:g}); the proof may be mounted turned from the sensor axes, its mass or tensor "
                   "mis-stated, or the proof throws (--proof) are of another object")
    for name, pooled in (("device-alone", a), ("proof", p)):
        if np.isfinite(pooled.chi2_dof) and pooled.chi2_dof > MAX_SET_CHI2_DOF:
            out.append(f"the {name} throws disagree with each other: one tensor for all of them fits with chi2/dof "
                       f"{pooled.chi2_dof:.3g} against each its own (at most {MAX_SET_CHI2_DOF:g}); they may not be "
                       "throws of one rigid body, or the mount moved between them")
    return out


def calibrate(device: Device, alone: Sequence[Throw], proof_throws: Sequence[Throw], proof: Proof, *,
              saturation: float | None = None) -> Calibration:
    """The device calibrated (:func:`calibrate_device`) and the calibration's checks of itself
    (:class:`Calibration`: ``problems`` says what is inconsistent and why).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.analysis.tensor.calibrate import calibrate
    >>> from tumble.analysis.tensor.synthetic import combine, synthetic_throw, true_device, true_proof

    Two throws of the device alone and two with the proof (a real calibration wants more: the
    benchmarks take 5 + 5; tests/test_tensor_device.py shows each check finding what it is for):


    >>> proof, placed = true_proof()
    >>> alone = [synthetic_throw(s, true_device(), spin=(3.0, 6.0)) for s in (1, 2)]
    >>> with_proof = [synthetic_throw(s, combine(true_device(), placed)) for s in (4, 5)]
    >>> cal = calibrate(Device(0.10067, [0, 0, -1]), alone, with_proof, proof)
    >>> cal.problems, cal.alone_used, cal.proof_used, bool(cal.chi2_dof < 4)
    ((), 2, 2, True)
    """
    if not isinstance(device, Device):
        raise ValueError(f"device must be a Device, got {type(device).__name__}")
    if not isinstance(proof, Proof):
        raise ValueError(f"proof must be a Proof, got {type(proof).__name__}")
    for k, a_throw in enumerate(alone):
        for j, p_throw in enumerate(proof_throws):
            if isinstance(a_throw, Throw) and isinstance(p_throw, Throw) and duplicate_throws([a_throw, p_throw]):
                raise ValueError(f"device-alone throw {a_throw.input or k} (--alone) and proof throw {p_throw.input or j} "
                                 "(--proof) are the same log: a throw is of the device alone or with the proof body, not both")
    # the sets fit the gyroscope's distortion and the rotor's tilt themselves: a calibration before this one is not used
    errors = sensor_errors(replace(device, gyro_distortion=None, gyro_distortion_std=None))
    rail = full_scale(device, saturation)
    # each set named in NoThrowError's message: the other's throws may all have fitted
    a, fits_a = pool_throws(alone, device.rotor_axis, 1.0, saturation=rail, errors=errors, which="of the device alone")
    p, fits_p = pool_throws(proof_throws, device.rotor_axis, 1.0, saturation=rail, errors=errors,
                            which="with the proof body")
    x = np.concatenate([a.inertia, a.center, p.inertia, p.center])
    cov = np.zeros((18, 18))
    cov[:6, :6], cov[6:9, 6:9], cov[9:15, 9:15], cov[15:, 15:] = a.inertia_cov, a.center_cov, p.inertia_cov, p.center_cov
    cov[:6, 9:15] = shared_sensor_covariance(a, p)
    cov[9:15, :6] = cov[:6, 9:15].T
    shared = shared_center_covariance(a, p)
    y, cov_y, ratio, cov_c = rotor_inertia_from(x, cov, device.mass, proof, shared)
    if ratio > MAX_CHI2_DOF or not _physical(tensor_of(y[1:7])):  # equations that do not hold adjust nothing
        y, cov_y, ratio, cov_c = rotor_inertia_from(x, cov, device.mass, proof, shared, adjust=False)
    std = np.sqrt(np.maximum(np.diag(cov_y), 0.0))
    # c_d's std its statistical one: an object's centre carries the accelerometer's and gyroscope's parts through
    # its flown centre's own columns (Pooled.center_columns), the same device's
    std[7:10] = np.sqrt(np.maximum(np.diag(cov_c), 0.0))
    problems = _problems(float(y[0]), ratio, a, p)
    speeds = [t.top_speed for t, f in zip((*alone, *proof_throws), (*fits_a, *fits_p)) if not f.reason]
    if max(speeds) > ROTOR_SPEED_RATIO * min(speeds):  # the firmware's plateau is the same in every throw
        problems.append(f"the rotor's top speeds differ from throw to throw: {min(speeds):.5g} to {max(speeds):.5g} rad/s, "
                        f"more than {ROTOR_SPEED_RATIO:g} times (the firmware's plateau is the same in every throw): some "
                        "logs' rotor speed in another unit (rpm, rev/s) or an eRPM turned with another pole count?")
    if max(speeds) > MAX_ROTOR_SPEED:  # every log in rpm read as rad/s agrees with itself: J_r 9.5 times too small
        problems.append(f"the rotor's top speed {max(speeds):.4g} rad/s ({round(max(speeds) * 30 / np.pi, -3):,.0f} rpm) "
                        f"is beyond any small motor's {MAX_ROTOR_SPEED:g} rad/s: the logs' rotor speed in rpm read as "
                        "rad/s (the rotor inertia then 9.5 times too small) or an eRPM?")
    if problems and not y[0] > 0:
        dev = device
    else:
        dev = replace(device, rotor_inertia=float(y[0]), rotor_inertia_std=float(std[0]), inertia=tensor_of(y[1:7]),
                      inertia_std=tensor_of(std[1:7]), center_of_mass=y[7:10], center_of_mass_std=std[7:10],
                      rotor_speed_range=(min(speeds), max(speeds)),
                      **calibrated_sensors([a, p], device.rotor_axis, device.gyro_scale_std))
    max_bias = float(max(np.abs(a.biases).max(), np.abs(p.biases).max()))  # type: ignore[union-attr]
    left = tuple(f"{t.input or f'throw {k}'}: {f.reason}" for k, (t, f) in enumerate(zip((*alone, *proof_throws),
                                                                                          (*fits_a, *fits_p))) if f.reason)
    return Calibration(dev, ratio, a.chi2_dof, p.chi2_dof, a.used, p.used, max_bias, left, tuple(problems))


def shared_sensor_covariance(a: Pooled, b: Pooled) -> FloatArray:
    """The cross-covariance of two pooled tensors from throws of one device: the sensors' errors
    (the gyroscope's scale and axes, the rotor's axis) are this device's in both, so their parts
    move both tensors together, ``S_a S_b^T``
    (:attr:`~tumble.analysis.tensor.joint.JointFit.sensor_columns`; JCGM 100:2008, sec. 5.2,
    correlated input quantities). Taken independent, they counted twice in ``P - D``: the
    rotor inertia's stated std came out 2.5 times its error's median (25 realistic devices).
    Zero when either has no columns or they are of other error sources (one set fitted the
    gyroscope's distortion, the other could not).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.calibrate import shared_sensor_covariance
    >>> from tumble.analysis.tensor.pool import Pooled
    >>> S = np.array([[1e-3], [2e-3], [0], [0], [0], [0]])
    >>> p = Pooled(np.ones(6), np.eye(6), np.zeros(3), np.eye(3), 1.0, 2, sensor_columns=S)
    >>> float(shared_sensor_covariance(p, p)[1, 0] * 1e6)
    2.0
    """
    Sa, Sb = a.sensor_columns, b.sensor_columns
    if Sa is None or Sb is None or Sa.shape != Sb.shape:
        return np.zeros((6, 6))
    return Sa @ Sb.T


def shared_center_covariance(a: Pooled, b: Pooled) -> FloatArray | None:
    """The covariance of two pooled centres ``(c_a, c_b)`` of one device from the sensors' errors
    they share (the accelerometer's scale factors, the gyroscope's turn from it:
    :attr:`~tumble.analysis.tensor.pool.Pooled.center_columns`), ``[[S_a S_a^T, S_a S_b^T],
    [S_b S_a^T, S_b S_b^T]]`` (JCGM 100:2008, sec. 5.2): a common scale moves both centres, so
    the difference the proof's centre rests on moves less than either. None without the columns.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.calibrate import shared_center_covariance
    >>> from tumble.analysis.tensor.pool import Pooled
    >>> S = np.zeros((3, 6)); S[2, 2] = 1e-4   # 0.1 mm along z for the accelerometer's z scale
    >>> p = Pooled(np.ones(6), np.eye(6), np.zeros(3), np.eye(3), 1.0, 2, center_columns=S)
    >>> c = shared_center_covariance(p, p)
    >>> c.shape, float(c[2, 5] * 1e8)
    ((6, 6), 1.0)
    """
    Sa, Sb = a.center_columns, b.center_columns
    if Sa is None or Sb is None or Sa.shape != Sb.shape:
        return None
    S = np.vstack([Sa, Sb])
    return S @ S.T


def calibrated_sensors(sets: Sequence[Pooled], rotor_axis: FloatArray, scale_std: float) -> dict[str, Any]:
    """The gyroscope's cross-axis distortion and the rotor's axis from the calibration's joint
    fits: each set's seven :data:`~tumble.analysis.tensor.sensors.SENSOR_NAMES`, combined by their
    inverse covariances (the two sets are throws of one device; a ``chi^2 / 7`` of their
    difference above 1 inflates the result's covariance, Birge), as
    :class:`~tumble.analysis.tensor.device.Device` fields: ``gyro_distortion`` and
    ``gyro_distortion_std`` (3 x 3), ``rotor_axis`` (the nominal tilted as fitted) and
    ``rotor_axis_std`` (the larger of the two angles' std, rad). Empty when no set fitted them.

    Only the distortion's **off-diagonal** part (the axes' cross-sensitivity) is kept: its
    diagonal (the axes' scale factors' differences) trades with the tensor along the rotor's
    axis: on the realistic synthetic devices of benchmarks/tensor_coverage.py the calibration's
    diagonal came out up to 15 of its std from the truth (device 5: a lone throw corrected by it
    then 5 % off) while the cross terms held to theirs. The diagonal is written as 0 with the stated scale's std (``scale_std``, per axis:
    ``scale_std * sqrt(2/3)`` for the trace-free part).

    Why: a lone throw cannot tell the gyroscope's distortion from the tensor (its estimate shifts
    by several per cent); the calibration's ten throws of two bodies can, and every later throw
    of the device is then corrected (:func:`~tumble.analysis.tensor.throw.fit_flown`'s ``gyro``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.calibrate import calibrated_sensors
    >>> from tumble.analysis.tensor.pool import Pooled
    >>> g = np.array([0.004, -0.002, 0.001, 0.0, 0.0, 0.01, 0.0])
    >>> one = Pooled(np.ones(6), np.eye(6), np.zeros(3), np.eye(3), 1.0, 5, sensor=g, sensor_cov=np.eye(7) * 1e-8)
    >>> out = calibrated_sensors([one, one], np.array([0.0, 0.0, 1.0]), 0.003)
    >>> out["gyro_distortion"][0].round(6).tolist(), round(float(out["rotor_axis_std"]), 6)   # the diagonal left out
    ([0.0, 0.001, 0.0], 7.1e-05)
    """
    have = [q for q in sets if q.sensor is not None and q.sensor_cov is not None]
    if not have:
        return {}
    infos = [np.linalg.pinv(q.sensor_cov) for q in have]  # type: ignore[arg-type]
    cov = np.linalg.pinv(sum(infos))
    x = cov @ sum(w @ q.sensor for w, q in zip(infos, have))  # type: ignore[operator]
    if len(have) > 1:
        chi2 = sum(float((q.sensor - x) @ w @ (q.sensor - x)) for w, q in zip(infos, have))  # type: ignore[operator]
        cov = cov * max(1.0, chi2 / (x.size * (len(have) - 1)))
    var = np.diag(cov)
    _, _, s2, s3, s4 = np.sqrt(np.maximum(var[:5], 0.0))
    sd = float(scale_std) * np.sqrt(2.0 / 3.0)
    D_std = np.array([[sd, s2, s3], [s2, sd, s4], [s3, s4, sd]])
    D = gyro_matrix(np.r_[0.0, 0.0, x[2:5]]) - np.eye(3)
    return {"gyro_distortion": D, "gyro_distortion_std": D_std,
            "rotor_axis": tilted_axis(rotor_axis, x[5:7]), "rotor_axis_std": float(np.sqrt(max(var[5], var[6], 0.0)))}


def calibrate_device(device: Device, alone: Sequence[Throw], proof_throws: Sequence[Throw], proof: Proof, *,
                     saturation: float | None = None) -> Device:
    """The device with ``rotor_inertia``, ``inertia``, ``center_of_mass`` and their ``_std`` estimated
    (module docstring); :func:`calibrate` also says how well the calibration checks itself.

    Parameters
    ----------
    device : Device
        Its mass and rotor axis (and how its logs are read, kept); its inertias are replaced.
    alone : sequence of Throw
        Throws of the device alone.
    proof_throws : sequence of Throw
        Throws of the device with the proof body fixed to it.
    proof : Proof
        The proof body's known mass and tensor (about its centre, sensor axes).
    saturation : float, optional
        The gyroscope's range, rad/s (default the device's ``gyro_full_scale``).

    Returns
    -------
    Device

    Raises
    ------
    ValueError
        Bad input (no throws, not throws, not a device or proof, a throw in both sets), or a
        calibration that does not check out (:attr:`Calibration.problems`).
    NoThrowError
        No throw of a set could be fitted (:class:`tumble.analysis.tensor.NoThrowError`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device, calibrate_device
    >>> from tumble.analysis.tensor.synthetic import ROTOR_INERTIA, combine, synthetic_throw, true_device, true_proof
    >>> proof, placed = true_proof()
    >>> alone = [synthetic_throw(s, true_device(), spin=(3.0, 6.0)) for s in (1, 2)]
    >>> with_proof = [synthetic_throw(s, combine(true_device(), placed)) for s in (4, 5)]
    >>> cal = calibrate_device(Device(0.10067, [0, 0, -1]), alone, with_proof, proof)   # two throws of each
    >>> bool(abs(cal.rotor_inertia / ROTOR_INERTIA - 1) < 0.02), bool(cal.rotor_inertia_std < 0.02 * ROTOR_INERTIA)
    (True, True)
    """
    result = calibrate(device, alone, proof_throws, proof, saturation=saturation)
    if result.problems:
        raise CalibrationError("; ".join(result.problems))
    return result.device


class CalibrationError(ValueError):
    """A calibration that does not check out (:attr:`Calibration.problems`): a failed computation,
    not bad input (``tumble calibrate`` exits with status 1).

    Examples
    --------
    >>> from tumble.analysis.tensor.calibrate import CalibrationError
    >>> issubclass(CalibrationError, ValueError)
    True
    """
