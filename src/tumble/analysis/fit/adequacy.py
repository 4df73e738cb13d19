"""Whether a fitted model describes the data at all: :func:`judge`.

A least-squares fit always returns numbers, and its covariance is small whenever the residuals
are small against the Jacobian, whether or not the model is right: a sine wave fitted with the
torque-free model gives ``I2/I3 = 0.99998 +- 1e-5``. The residuals say which it is. They hold
the gyroscope's noise plus the model's error; the noise is estimated from the data's own
high-frequency part (the residuals' second differences,
:func:`~tumble.analysis.fit.uncertainty.noise_floor`), and what the residuals hold beyond it,
``sqrt(rms^2 - noise^2)``, is the model's error. A fit is **inadequate** when

- the residuals lie clearly above the noise (``rms > NOISE_FACTOR x noise``: not noise alone),
- and the model's error exceeds :data:`MISFIT_LIMIT` of the rates (per axis, RMS).

The limit is set from what a right model leaves on realistic data: on the synthetic tosses of
:mod:`~tumble.analysis.fit.synthetic` (a racquet and a phone, quadratic drag, a flexing handle,
a sensor off the centre of mass, coloured noise and bias; 210 flights) the model's error is at
most 1.4 % of the rates (median 0.4 %); a sensor taken as the principal axes when it is not, a
clipped gyroscope that went unnoticed, a random walk or a sine wave leave 10-100 %.

Why not a test of the residuals' structure (a runs test, their autocorrelation time): a right
model on real tosses leaves structured residuals too (drag and flex are smooth): on the same
210 flights the residuals' autocorrelation time reaches 22 samples at 100 Hz, as much as a sine
wave's misfit. The structure is what :mod:`~tumble.analysis.fit.uncertainty` widens the
uncertainties for; it says how far to trust a right model, not whether the model is right.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["MISFIT_LIMIT", "NOISE_FACTOR", "Adequacy", "InadequateFitWarning", "judge"]

#: The model's error (beyond the noise) allowed in the residuals, as a fraction of the rates'
#: RMS per axis (dimensionless). See the module docstring for the measurements behind it.
MISFIT_LIMIT = 0.03
#: Residuals within this factor of the noise are noise, whatever the rates.
NOISE_FACTOR = 3.0


class InadequateFitWarning(UserWarning):
    """The fitted model does not describe the data: its ratios are not to be trusted.

    Examples
    --------
    >>> import warnings
    >>> import numpy as np
    >>> from tumble.analysis.fit import InadequateFitWarning, fit_rotation
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = np.column_stack([np.sin(7 * t), 2 + np.cos(3 * t), np.sin(11 * t)])   # no rigid body's tumble
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     fit = fit_rotation(t, w, sensor_rotation="identity", bias=False, drag="none")
    >>> fit.adequate, [c.category.__name__ for c in caught]
    (False, ['InadequateFitWarning'])
    """


@dataclass(frozen=True)
class Adequacy:
    """The verdict on a fit's residuals.

    Attributes
    ----------
    adequate : bool
    misfit : float
        The model's error (the residuals' RMS beyond the noise) as a fraction of the rates'
        RMS per axis, dimensionless.
    reason : str
        One sentence: what the residuals show, and for an inadequate fit what to check.

    Examples
    --------
    >>> from tumble.analysis.fit.adequacy import Adequacy, judge
    >>> verdict = judge(0.05, 0.01, 5.0)   # residuals 5 x the noise, but 1 % of the rates: a right model's drag and flex
    >>> isinstance(verdict, Adequacy), verdict.adequate, round(verdict.misfit, 4)   # sqrt(0.05^2 - 0.01^2) / 5
    (True, True, 0.0098)
    >>> judge(0.5, 0.01, 5.0).reason.startswith("the model does not fit")
    True
    """

    adequate: bool
    misfit: float
    reason: str


def judge(residual_rms: float, noise: float, rates_rms: float, *, sensor_rotation_fitted: bool = True) -> Adequacy:
    """Judge a fit by its residuals (module docstring).

    Parameters
    ----------
    residual_rms : float
        RMS of the residuals over the samples and axes fitted, rad/s.
    noise : float
        The data's white noise per axis, rad/s.
    rates_rms : float
        RMS of the measured rates per axis, ``sqrt(mean |omega|^2 / 3)``, rad/s.
    sensor_rotation_fitted : bool
        Whether the sensor's rotation to the principal axes was fitted (a hint in the reason).

    Returns
    -------
    Adequacy

    Examples
    --------
    >>> judge(0.005, 0.005, 10.0).adequate
    True
    >>> v = judge(1.2, 0.005, 10.0)
    >>> v.adequate, round(v.misfit, 3)
    (False, 0.12)
    """
    residual_rms, noise, rates_rms = float(residual_rms), float(noise), float(rates_rms)
    excess = float(np.sqrt(max(residual_rms ** 2 - noise ** 2, 0.0)))
    misfit = excess / rates_rms if rates_rms > 0 else float("inf")
    said = (f"residuals {residual_rms:.3g} rad/s against noise {noise:.3g} rad/s: the model's error is "
            f"{100 * misfit:.2g} % of the rates ({rates_rms:.3g} rad/s)")
    if residual_rms <= NOISE_FACTOR * noise or misfit <= MISFIT_LIMIT:
        return Adequacy(True, misfit, f"{said}, within the {100 * MISFIT_LIMIT:.0f} % a free rigid body leaves")
    hint = ("the sensor's axes were taken as the principal axes: fit the sensor's rotation"
            if not sensor_rotation_fitted else
            "check that the samples are a free flight (no hand, no impact), that the gyroscope did not clip "
            "(give its range) and that the body is rigid")
    return Adequacy(False, misfit, f"the model does not fit: {said}, above the {100 * MISFIT_LIMIT:.0f} % a free "
                                   f"rigid body leaves; {hint}")
