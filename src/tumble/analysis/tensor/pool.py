"""Several throws of one flown body pooled: :func:`pool_throws`.

Each throw is fitted on its own (:func:`~tumble.analysis.tensor.throw.fit_flown`); the tensor's
six entries and the centre of mass are each pooled by the inverse-covariance weighted mean
(the maximum-likelihood estimate of a common value from independent Gaussian estimates;
e.g. Cowan, *Statistical Data Analysis*, 1998, sec. 7.6). When the throws scatter about it
more than their statistical uncertainties allow, ``chi^2 / dof > 1``
(:func:`tumble.analysis.fit.uncertainty.birge_chi2`), the pooled covariance is multiplied by
that Birge ratio, as the ratio fit pools its flights (:mod:`tumble.analysis.fit.recording`):
something the model leaves out varies from throw to throw, and the spread shows how much.
Systematic parts common to all the throws (the rotor's inertia, the device) are added after
pooling by the caller: averaging does not reduce them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from ...typing import FloatArray
from ..fit.uncertainty import birge_chi2
from .device import Throw
from .estimate import vector_of
from .throw import FlownFit, fit_flown

__all__ = ["NoThrowError", "Pooled", "pool_throws", "weighted_mean"]


class NoThrowError(ValueError):
    """Well-formed throws of which none could be fitted (the computation failed, not the input:
    ``tumble tensor`` exits with status 1); each throw's reason is in the message.

    Examples
    --------
    >>> from tumble.analysis.tensor import NoThrowError
    >>> issubclass(NoThrowError, ValueError)
    True
    """


@dataclass(frozen=True)
class Pooled:
    """The pooled flown body: tensor entries ``xx, yy, zz, xy, xz, yz`` (kg m^2 or units of
    ``J_r``) and centre (m) with their statistical covariances (inflated by the Birge ratio),
    ``chi^2 / dof`` of the throws about them (NaN for one throw) and the throws used.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.pool import Pooled
    >>> Pooled(np.ones(6), np.eye(6), np.zeros(3), np.eye(3), float("nan"), 1).adequate
    True
    """

    inertia: FloatArray
    inertia_cov: FloatArray
    center: FloatArray
    center_cov: FloatArray
    chi2_dof: float
    used: int
    adequate: bool = True


def weighted_mean(values: FloatArray, covs: FloatArray) -> tuple[FloatArray, FloatArray, float, int]:
    """Inverse-covariance weighted mean of ``values (F, k)``, its covariance inflated by
    ``max(1, chi^2 / dof)``, and ``chi^2``, ``dof`` (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.pool import weighted_mean
    >>> mean, cov, chi2, dof = weighted_mean(np.array([[1.0], [3.0]]), np.ones((2, 1, 1)))
    >>> mean.tolist(), cov.tolist(), chi2, dof   # 2 sigma apart: chi^2 = 2 on 1 dof, variance 1/2 doubled
    ([2.0], [[1.0]], 2.0, 1)
    """
    W = np.array([np.linalg.pinv(c) for c in covs])
    cov = np.linalg.pinv(W.sum(axis=0))
    mean = cov @ np.einsum("fij,fj->i", W, values)
    if len(values) < 2:
        return mean, cov, float("nan"), 0
    chi2, dof = birge_chi2(values, covs, mean)
    return mean, cov * max(1.0, chi2 / dof), chi2, dof


def _usable(f: FlownFit, throw: Throw) -> FlownFit:
    """The fit, with a reason when it cannot be pooled."""
    if f.reason:
        return f
    if f.adequacy is not None and not f.adequacy.adequate:
        return replace(f, reason=f.adequacy.reason)
    if f.center is None or throw.accel is None:
        return replace(f, reason="no accelerometer in the throw: its centre of mass is unknown")
    return f


def pool_throws(throws: Sequence[Throw], rotor_axis: FloatArray, rotor_inertia: float, *,
                saturation: float | None = None) -> tuple[Pooled, list[FlownFit]]:
    """Fit every throw and pool those that fit (module docstring).

    Parameters
    ----------
    throws : sequence of Throw
    rotor_axis : ndarray, shape (3,)
    rotor_inertia : float
        ``J_r``, kg m^2 (1: the tensors in units of ``J_r``).
    saturation : float, optional
        The gyroscope's range, rad/s.

    Returns
    -------
    pooled : Pooled
    fits : list of FlownFit
        One per throw, ``reason`` non-empty for those not pooled.

    Raises
    ------
    ValueError
        ``throws`` empty or not throws.
    NoThrowError
        None could be pooled.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.pool import pool_throws
    >>> from tumble.analysis.tensor.synthetic import ROTOR_INERTIA, combine, example_object, synthetic_throw, true_device
    >>> flown = combine(true_device(), example_object())
    >>> pooled, fits = pool_throws([synthetic_throw(s, flown) for s in (1, 2)], np.array([0, 0, -1.0]), ROTOR_INERTIA)
    >>> pooled.used, [f.reason for f in fits]
    (2, ['', ''])
    """
    if isinstance(throws, Throw) or not isinstance(throws, Sequence) or len(throws) == 0:
        raise ValueError(f"throws must be a non-empty list of Throw, got {type(throws).__name__}")
    for k, throw in enumerate(throws):
        if not isinstance(throw, Throw):
            raise ValueError(f"throws[{k}] must be a Throw, got {type(throw).__name__}")
    fits = [_usable(fit_flown(throw, rotor_axis, rotor_inertia, saturation=saturation), throw) for throw in throws]
    used = [f for f in fits if not f.reason]
    if not used:
        why = "; ".join(f"{throw.input or f'throw {k}'}: {f.reason}" for k, (throw, f) in enumerate(zip(throws, fits)))
        raise NoThrowError(f"no throw could be fitted ({why})")
    I, cov_I, chi2_I, dof_I = weighted_mean(np.array([vector_of(f.inertia) for f in used]),
                                            np.array([f.inertia_cov for f in used]))
    c, cov_c, chi2_c, dof_c = weighted_mean(np.array([f.center for f in used]), np.array([f.center_cov for f in used]))
    chi2_dof = (chi2_I + chi2_c) / (dof_I + dof_c) if len(used) > 1 else float("nan")
    inadequate = any(f.adequacy is not None and not f.adequacy.adequate for f in fits)
    return Pooled(I, cov_I, c, cov_c, chi2_dof, len(used), not inadequate), fits
