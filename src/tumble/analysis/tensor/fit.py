"""The object's absolute tensor from throws with the device: :func:`fit_tensor`.

Each throw is fitted on its own (:mod:`~tumble.analysis.tensor.throw`): the flown body's tensor
(object and device, about their common centre of mass) and its centre of mass, with their
statistical covariances. The throws are pooled by their inverse-covariance weighted mean; when
they scatter about it more than their uncertainties allow, the statistical covariance is
multiplied by the Birge ratio ``chi^2 / dof`` (:func:`tumble.analysis.fit.uncertainty.birge_chi2`,
as the ratio fit pools flights). Then the systematic parts common to every throw are added: the
rotor inertia's relative uncertainty scales the whole tensor (the gyrostat's equations are
unchanged when ``I`` and ``J_r`` are multiplied by the same factor, so ``I`` is proportional to
``J_r``), and the device's own tensor and centre are subtracted with the parallel-axis theorem
(:func:`~tumble.analysis.tensor.estimate.subtract_body`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...typing import FloatArray
from .device import Device, Throw
from .estimate import MassEstimate

__all__ = ["NoThrowError", "TensorFit", "ThrowFit", "fit_tensor"]


class NoThrowError(ValueError):
    """Well-formed throws of which none could be fitted (the computation failed, not the input:
    ``tumble tensor`` exits with status 1); each throw's reason is in the message.

    Examples
    --------
    >>> from tumble.analysis.tensor import NoThrowError
    >>> issubclass(NoThrowError, ValueError)
    True
    """


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
        Whether every used throw's model fits its samples (residuals near the noise).
    chi2_dof : float
        The throws' scatter about the pooled values over what their uncertainties allow
        (NaN for one throw).

    Examples
    --------
    >>> from tumble.analysis.tensor import TensorFit
    >>> sorted(TensorFit.__dataclass_fields__)
    ['adequate', 'chi2_dof', 'flown', 'object', 'throws']
    """

    object: MassEstimate
    flown: MassEstimate
    throws: tuple[ThrowFit, ...]
    adequate: bool
    chi2_dof: float

    def as_dict(self) -> dict[str, Any]:
        """The content of ``tensor.json``: ``object``, ``flown``, ``throws``, ``adequate``, ``chi2_dof``.

        Examples
        --------
        >>> from tumble.analysis.tensor import TensorFit
        >>> TensorFit.as_dict.__name__
        'as_dict'
        """
        return {"object": self.object.as_dict(), "flown": self.flown.as_dict(),
                "throws": [t.as_dict() for t in self.throws], "adequate": bool(self.adequate),
                "chi2_dof": _num(self.chi2_dof)}


def fit_tensor(throws: Sequence[Throw], device: Device, mass: float) -> TensorFit:
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

    Returns
    -------
    TensorFit

    Raises
    ------
    ValueError
        Bad input (a device not calibrated, a mass not positive, no throw given).
    tumble.analysis.tensor.NoThrowError
        No throw could be fitted (a ValueError too; each throw's reason in the message).

    Examples
    --------
    >>> from tumble.analysis.tensor import fit_tensor
    >>> callable(fit_tensor)
    True
    """
    raise NotImplementedError
