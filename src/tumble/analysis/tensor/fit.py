"""The object's absolute tensor from throws with the device: :func:`fit_tensor`.

Each throw is fitted on its own (:mod:`~tumble.analysis.tensor.throw`): the flown body's tensor
(object and device, about their common centre of mass) and its centre of mass, with their
covariances (the sensors' stated uncertainties included: :func:`sensor_errors`). A throw whose
object, the device taken away, is no body's (:func:`~tumble.analysis.tensor.estimate.not_physical`)
is left out, named, with the throws that the fit cannot explain
(:func:`~tumble.analysis.tensor.verdicts.throw_verdict`). The rest are fitted jointly, one tensor
and one centre of mass for all (:mod:`~tumble.analysis.tensor.pool`). Then the systematic parts
common to every throw are added: the rotor inertia's relative uncertainty scales the whole
tensor (the gyrostat's equations are unchanged when ``I`` and ``J_r`` are multiplied by the same
factor, so ``I`` is proportional to ``J_r``), and the device's own tensor and centre are
subtracted with the parallel-axis theorem (:func:`~tumble.analysis.tensor.estimate.subtract_body`).
An object's pooled tensor that is no body's is never written: :class:`NoThrowError` (the
command's exit status 1) says why.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ...typing import FloatArray
from .. import _display
from .device import Device, check_thrown_mass
from .throwlog import Throw
from .estimate import MassEstimate, mass_estimate, not_physical, onto_triangle, subtract_body, tensor_of, vector_of
from .sensors import SensorErrors, distortion_coefficients
from .pool import NoThrowError, Pooled, pool_throws
from .throw import FlownFit
from .verdicts import speed_verdict

__all__ = ["TensorFit", "ThrowFit", "device_covariances", "fit_tensor", "flown_estimate", "full_scale", "gyro_response",
           "sensor_errors"]


def _num(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


@dataclass(frozen=True)
class ThrowFit:
    """One throw's fit: where its flight lies, its own estimates, or why it was skipped.

    Attributes
    ----------
    input : str
        The throw's ``input`` (its file as given).
    status : str
        ``"used"`` (fitted and pooled) or ``"skipped"``.
    reason : str
        Why skipped, or ``""``.
    object, flown : MassEstimate or None
        This throw's own estimates (None when skipped); ``object`` with the device taken away.
    t : ndarray, shape (n,)
        The fitted samples' times, s.
    omega_measured, omega_model : ndarray, shape (n, 3)
        The gyroscope's samples and the fitted model's (bias included) at ``t``, rad/s.
    t_release, t_end : float
        The flight's start found from the data (the release) and its end (the catch), s.
    residual_rms : float
        RMS of the fitted residuals, rad/s.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import ThrowFit
    >>> skipped = ThrowFit("b.csv", "skipped", "no free flight found", None, None, np.zeros(0), np.zeros((0, 3)),
    ...                    np.zeros((0, 3)), float("nan"), float("nan"), float("nan"))
    >>> skipped.as_dict()["object"] is None, skipped.as_dict()["t_release"] is None
    (True, True)
    """

    input: str
    status: str
    reason: str
    object: MassEstimate | None
    flown: MassEstimate | None
    t: FloatArray = field(repr=False)
    omega_measured: FloatArray = field(repr=False)
    omega_model: FloatArray = field(repr=False)
    t_release: float = float("nan")
    t_end: float = float("nan")
    residual_rms: float = float("nan")

    def __repr__(self) -> str:
        return _display.throw_repr(self)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: ``input``, ``status``, ``reason``, ``object``, ``flown`` (dicts or None),
        ``t_release``, ``t_end``, ``residual_rms`` (None for NaN).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor import ThrowFit
        >>> ThrowFit("a.csv", "skipped", "why", None, None, np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3))).as_dict()["reason"]
        'why'
        """
        return {"input": self.input, "status": self.status, "reason": self.reason,
                "object": None if self.object is None else self.object.as_dict(),
                "flown": None if self.flown is None else self.flown.as_dict(),
                "t_release": _num(self.t_release), "t_end": _num(self.t_end), "residual_rms": _num(self.residual_rms)}


@dataclass(frozen=True)
class TensorFit:
    """The object's tensor pooled over the throws, and each throw's own fit.

    Attributes
    ----------
    object : MassEstimate
        The object alone, about its own centre of mass, sensor frame.
    flown : MassEstimate
        Object and device together, about their centre of mass.
    throws : tuple of ThrowFit
        One per throw given, in order.
    adequate : bool
        Whether the answer was made from the throws that pass (those left out say why in
        ``throws``; an answer that is no body's tensor is never returned:
        :class:`~tumble.analysis.tensor.pool.NoThrowError`).
    chi2_dof : float
        The throws' own tensors' scatter about the joint one over what their uncertainties
        allow (:func:`~tumble.analysis.tensor.pool.agreement`; NaN for one throw).
    on_edge : float
        How many standard uncertainties the object's estimate was moved on to the triangle
        inequality's edge ``I1 + I2 = I3`` (a flat body's estimate beyond it:
        :func:`~tumble.analysis.tensor.estimate.onto_triangle`); 0 where it kept the inequality.

    Examples
    --------
    >>> from tumble.analysis.tensor import TensorFit
    >>> sorted(TensorFit.__dataclass_fields__)
    ['adequate', 'chi2_dof', 'flown', 'object', 'on_edge', 'throws']
    """

    object: MassEstimate
    flown: MassEstimate
    throws: tuple[ThrowFit, ...]
    adequate: bool
    chi2_dof: float
    on_edge: float = 0.0

    def __repr__(self) -> str:
        return _display.tensor_repr(self)

    def _repr_html_(self) -> str:
        return _display.tensor_html(self)

    def as_dict(self) -> dict[str, Any]:
        """The content of ``tensor.json``: ``object``, ``flown``, ``throws``, ``adequate``, ``chi2_dof``, ``on_edge``.

        Examples
        --------
        >>> from tumble.analysis.tensor import TensorFit
        >>> TensorFit.as_dict.__name__
        'as_dict'
        """
        return {"object": self.object.as_dict(), "flown": self.flown.as_dict(),
                "throws": [t.as_dict() for t in self.throws], "adequate": bool(self.adequate),
                "chi2_dof": _num(self.chi2_dof), "on_edge": float(self.on_edge)}


def fit_tensor(throws: Sequence[Throw], device: Device, mass: float, *, saturation: float | None = None) -> TensorFit:
    """The absolute inertia tensor and centre of mass of an object thrown with the device.

    Parameters
    ----------
    throws : sequence of Throw
        One or more throws of the object with the device fixed to it (in the same place).
    device : Device
        A calibrated device (:func:`~tumble.analysis.tensor.calibrate.calibrate_device`):
        ``rotor_inertia``, ``inertia`` and ``center_of_mass`` known.
    mass : float
        The object's mass, kg (weighed).
    saturation : float, optional
        The gyroscope's range, rad/s (default the device's ``gyro_full_scale``).

    Returns
    -------
    TensorFit
        A throw that cannot be trusted is skipped with its reason, the others fitted jointly.

    Raises
    ------
    ValueError
        Bad input (not a Device, a device not calibrated, a mass not positive, no throw given).
    NoThrowError
        No throw could be fitted (:class:`tumble.analysis.tensor.NoThrowError`, a ValueError
        too); each throw's reason is in the message.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import fit_tensor
    >>> from tumble.analysis.tensor.synthetic import calibrated_device, combine, example_object, synthetic_throw, true_device
    >>> box = example_object()
    >>> flown = combine(true_device(), box)
    >>> fit = fit_tensor([synthetic_throw(seed, flown) for seed in (1, 2)], calibrated_device(), box.mass)
    >>> [t.status for t in fit.throws], fit.adequate
    (['used', 'used'], True)
    >>> err = fit.object.principal_moments / np.linalg.eigvalsh(box.inertia) - 1   # within 1 %
    >>> bool(np.all(np.abs(err) < 0.01))
    True
    """
    if isinstance(throws, (str, os.PathLike)) or isinstance(throws, (list, tuple)) and any(
            isinstance(x, (str, os.PathLike)) for x in throws):
        raise ValueError("throws are Throw objects, not files' names: read each log with "
                         "tumble.io.throwfile.read_throw(path, device)")
    mass = check_thrown_mass("mass", mass)
    if not isinstance(device, Device):
        raise ValueError(f"device must be a Device, got {type(device).__name__}")
    if not device.calibrated:
        raise ValueError("the device is not calibrated: its rotor_inertia, inertia and center_of_mass are needed "
                         "(tumble calibrate, or calibrate_device)")
    J = float(device.rotor_inertia)  # type: ignore[arg-type]
    rel = float(device.rotor_inertia_std or 0.0) / J
    cov_d, cov_c = device_covariances(device)

    def of_throw(f: FlownFit) -> tuple[MassEstimate, MassEstimate]:
        """A throw's own flown body and object."""
        one = flown_estimate(mass + device.mass, Pooled(vector_of(f.inertia), f.inertia_cov, f.center, f.center_cov,
                                                        float("nan"), 1), rel)
        return one, _object(one, mass, device, cov_d, cov_c)

    def check(f: FlownFit, throw: Throw) -> str:
        return speed_verdict(throw.top_speed, device.rotor_speed_range) or (
            "" if f.center is None else not_physical(of_throw(f)[1]))

    pooled, fits = pool_throws(throws, device.rotor_axis, J, saturation=full_scale(device, saturation),
                               errors=sensor_errors(device), check=check, gyro=gyro_response(device))
    flown = flown_estimate(mass + device.mass, pooled, rel)
    obj = _object(flown, mass, device, cov_d, cov_c)
    why = not_physical(obj)
    if why:
        raise NoThrowError(f"the object's tensor from {pooled.used} throw(s) is {why.split(': ', 1)[0]}: "
                           f"{why.split(': ', 1)[1]}; the device's calibration or the mass given may be wrong")
    # within TRIANGLE_SIGMA of the edge but over it, the estimate is written on the edge: nothing non-physical is
    # written as an answer (a 40 g box's was, 1.8 standard uncertainties over; a walkthrough, 2026-12-03)
    obj, on_edge = onto_triangle(obj)
    flown = onto_triangle(flown)[0]
    rows = []
    for throw, f in zip(throws, fits):
        if f.reason:
            rows.append(_skipped(throw, f))
            continue
        one, own = of_throw(f)
        rows.append(ThrowFit(throw.input, "used", "", own, one, f.t, f.omega_measured, f.omega_model,
                             f.window.t_release, f.window.t_end, f.residual_rms))
    return TensorFit(obj, flown, tuple(rows), pooled.adequate, pooled.chi2_dof, on_edge)


def _object(flown: MassEstimate, mass: float, device: Device, cov_d: FloatArray, cov_c: FloatArray) -> MassEstimate:
    """The object: the flown body less the device (:func:`~tumble.analysis.tensor.estimate.subtract_body`),
    its mass the one given (``(m + m_d) - m_d`` is 0.48200000000000004 for 0.482)."""
    rest = subtract_body(flown, device.mass, device.inertia, cov_d, device.center_of_mass, cov_c)
    return replace(rest, mass=float(mass))


def full_scale(device: Device, saturation: float | None = None) -> float:
    """The gyroscope's rail, rad/s: ``saturation`` when given, else the device's ``gyro_full_scale``.

    Examples
    --------
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.analysis.tensor.fit import full_scale
    >>> round(full_scale(Device(0.1, [0, 0, 1])), 4)   # 2000 deg/s
    34.9066
    """
    return float(saturation) if saturation is not None else float(np.deg2rad(device.gyro_full_scale))


def sensor_errors(device: Device) -> SensorErrors:
    """The device's sensors' stated uncertainties (:class:`~tumble.analysis.tensor.sensors.SensorErrors`),
    with the calibrated distortion's where the device has one.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.analysis.tensor.fit import sensor_errors
    >>> sensor_errors(Device(0.1, [0, 0, 1], gyro_scale_std=0.001)).gyro_scale
    0.001
    >>> D = np.diag([0.01, 0.0, -0.01])
    >>> sensor_errors(Device(0.1, [0, 0, 1], gyro_distortion=D, gyro_distortion_std=np.full((3, 3), 1e-4))).distortion
    array([0.0001, 0.0001, 0.0001, 0.0001, 0.0001])
    """
    std = None if device.gyro_distortion_std is None else distortion_coefficients(device.gyro_distortion_std)
    return SensorErrors(device.gyro_scale_std, device.gyro_misalignment_std, device.rotor_axis_std, std)


def gyro_response(device: Device) -> FloatArray | None:
    """The device's calibrated gyroscope response ``E + gyro_distortion`` (``omega_read = M omega``),
    or None where it has none.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.analysis.tensor.fit import gyro_response
    >>> D = np.diag([0.01, 0.0, -0.01])
    >>> gyro_response(Device(0.1, [0, 0, 1], gyro_distortion=D, gyro_distortion_std=np.zeros((3, 3)))).diagonal().tolist()
    [1.01, 1.0, 0.99]
    >>> gyro_response(Device(0.1, [0, 0, 1])) is None
    True
    """
    return None if device.gyro_distortion is None else np.eye(3) + device.gyro_distortion


def _skipped(throw: Throw, f: FlownFit) -> ThrowFit:
    """A throw not pooled, with what is known of it."""
    empty = np.zeros((0, 3))
    t = f.t if f.t is not None else np.zeros(0)
    return ThrowFit(throw.input, "skipped", f.reason, None, None, t,
                    f.omega_measured if f.omega_measured is not None else empty,
                    f.omega_model if f.omega_model is not None else empty, f.window.t_release, f.window.t_end,
                    f.residual_rms)


def device_covariances(device: Device) -> tuple[FloatArray, FloatArray]:
    """The device's tensor entries' and centre's covariances from their std (independent entries).

    Examples
    --------
    >>> from tumble.analysis.tensor.fit import device_covariances
    >>> from tumble.analysis.tensor.synthetic import calibrated_device
    >>> cov_I, cov_c = device_covariances(calibrated_device(0.01, 1e-3))
    >>> cov_I.shape, float(cov_c[0, 0])
    ((6, 6), 1e-06)
    """
    sI = np.zeros((3, 3)) if device.inertia_std is None else device.inertia_std
    sc = np.zeros(3) if device.center_of_mass_std is None else device.center_of_mass_std
    return np.diag(vector_of(sI) ** 2), np.diag(sc ** 2)


def flown_estimate(mass: float, pooled: Pooled, rotor_relative_std: float) -> MassEstimate:
    """The flown body's estimate: the pooled tensor with the rotor inertia's systematic part
    ``(s_J / J)^2 v v^T`` added (``I`` is proportional to ``J_r``: module docstring), its centre
    with the sensors' part (:attr:`~tumble.analysis.tensor.pool.Pooled.center_columns`) added.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.fit import flown_estimate
    >>> from tumble.analysis.tensor.pool import Pooled
    >>> p = Pooled(np.array([1e-3, 2e-3, 3e-3, 0, 0, 0]), np.zeros((6, 6)), np.zeros(3), np.zeros((3, 3)), 1.0, 1)
    >>> flown_estimate(0.7, p, 0.01).principal_moments_std.round(9).tolist()   # 1 % of each
    [1e-05, 2e-05, 3e-05]
    """
    v = pooled.inertia
    cov = pooled.inertia_cov + rotor_relative_std ** 2 * np.outer(v, v)
    center_cov = pooled.center_cov
    if pooled.center_columns is not None:  # the accelerometer's scale factors, the gyroscope's turn: the device's
        center_cov = center_cov + pooled.center_columns @ pooled.center_columns.T
    return mass_estimate(mass, tensor_of(v), cov, pooled.center, center_cov)
