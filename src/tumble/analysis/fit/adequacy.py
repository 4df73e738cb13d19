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

from ..._html import headline_html, headline_repr

__all__ = ["MAX_ENERGY_RISE", "MAX_TAIL", "MAX_MOMENTUM_RISE", "MISFIT_LIMIT", "NOISE_FACTOR", "RIGID_SMOOTHING", "Adequacy",
           "InadequateFitWarning", "judge", "judge_flights", "rigid_body_check"]

#: The model's error (beyond the noise) allowed in the residuals, as a fraction of the rates'
#: RMS per axis (dimensionless). See the module docstring for the measurements behind it.
MISFIT_LIMIT = 0.03
#: Residuals within this factor of the noise are noise, whatever the rates.
NOISE_FACTOR = 3.0
#: The largest rise of ``|L|`` over a flight that a rigid body's samples show, as a fraction of
#: its mean: drag only lowers it (see :func:`rigid_body_check` for the measurements behind it).
MAX_MOMENTUM_RISE = 0.06
#: The same for the rotational energy ``2E = omega^T I omega``.
MAX_ENERGY_RISE = 0.1
#: The span over which ``|L|`` and ``2E`` are averaged before their rise is taken, s.
RIGID_SMOOTHING = 0.05


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

    HEADLINE = (("adequate", "adequate", ""), ("misfit", "misfit", ""), ("reason", "reason", ""))
    __repr__ = headline_repr
    _repr_html_ = headline_html

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
    >>> from tumble.analysis.fit.adequacy import judge
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


def _rise(x: np.ndarray) -> float:
    """The largest increase of ``x`` over an earlier value, as a fraction of its mean."""
    return float(np.max(x - np.minimum.accumulate(x)) / np.mean(x))


def rigid_body_check(t: np.ndarray, omega_principal: np.ndarray, moments: np.ndarray) -> str:
    """Whether a flight's motion is one a rigid body can make: ``""``, or the reason it is not.

    A rigid body in flight feels only the air's torque, which takes energy and angular momentum
    away: ``d|L|/dt = L . tau / |L| <= 0`` and ``dE/dt = omega . tau <= 0`` for a dissipative
    drag (Landau & Lifshitz, *Mechanics*, sec. 34). So ``|L| = |I omega|`` and
    ``2E = omega . I omega``, computed from the samples with the fitted moments and sensor
    mount, may only fall. A body with an internal torque, a rotor spinning up (the gyrostat,
    Hughes 1986, ch. 7), a flexing or sloshing body, or two bodies mixed, moves momentum between
    its parts, and the body's own ``|L|`` and ``E`` rise and fall: the drag terms of a fit can
    absorb part of that in the residuals, not in these two budgets. After a moving average over
    :data:`RIGID_SMOOTHING`, a rise of ``|L|`` beyond :data:`MAX_MOMENTUM_RISE` or of ``2E``
    beyond :data:`MAX_ENERGY_RISE` of its mean is refused.

    The limits are set from the synthetic tosses of :mod:`~tumble.analysis.fit.synthetic`
    (racquet and phone, flex, drag, coloured noise, bias, scale errors; caught, caught and
    turned, landed): over 476 fits of their flights the largest rises are 2.9 % of ``|L|`` and
    5.7 % of ``2E`` (99 % of them below 0.9 % and 1.6 %), and over the 880 flights of
    ``benchmarks/fit_coverage.py`` one reached 4.2 % of ``|L|``; a rotor reaching 5 % of ``|L|`` raises
    them by 20-40 % (median) once the fit has bent its ratios to follow it. A rotor that bends
    the fit less is found by :func:`~tumble.analysis.fit.find_flights` instead: its samples leave
    the fitted motion long before the impulse that ends the flight.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Times, s.
    omega_principal : ndarray, shape (n, 3)
        The samples in the principal frame, the bias removed, rad/s.
    moments : ndarray, shape (3,)
        The fitted moments (any scale: ``I / I3``).

    Returns
    -------
    str
        ``""`` for a motion a rigid body can make, else the reason, one sentence.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.adequacy import rigid_body_check
    >>> t = np.linspace(0.0, 1.0, 201)
    >>> I = np.array([0.2, 0.8, 1.0])
    >>> spin = np.column_stack([0.1 * np.cos(3 * t), 10.0 * np.exp(-0.05 * t), 0.1 * np.sin(3 * t)])   # slowed by drag
    >>> rigid_body_check(t, spin, I)
    ''
    >>> up = spin * (1.0 + 0.1 * np.sin(6.0 * t))[:, None]   # momentum flowing in and out
    >>> rigid_body_check(t, up, I).split(":")[0]
    'not a rigid body'
    """
    t = np.asarray(t, float)
    w = np.asarray(omega_principal, float)
    I = np.asarray(moments, float)
    if len(t) < 3:
        return ""
    k = max(1, int(round(0.5 * RIGID_SMOOTHING / float(np.median(np.diff(t))))))
    if len(t) <= 2 * k + 1:
        return ""
    box = np.ones(2 * k + 1) / (2 * k + 1)
    momentum = np.convolve(np.linalg.norm(w * I, axis=1), box, mode="valid")
    energy = np.convolve(np.sum(I * w * w, axis=1), box, mode="valid")
    for name, rise, limit in (("angular momentum |L|", _rise(momentum), MAX_MOMENTUM_RISE),
                              ("energy", _rise(energy), MAX_ENERGY_RISE)):
        if rise > limit:
            # one decimal: a rise just past the limit reads past it (".2g" wrote 10.4 % as "10 %")
            return (f"not a rigid body: its {name} rose by {100 * rise:.1f} % during the flight, where air drag "
                    f"only lowers it (a rigid body's samples show at most {100 * limit:.0f} %): an internal torque "
                    f"acts (a rotor spinning up, a flexing or sloshing body, or two bodies)")
    return ""


#: How long a flight's samples may go on after the fitted flight ends before the impulse that
#: ends it, s: a rigid body's free motion lasts until the catch or the impact (:mod:`~tumble.analysis.fit.flights`).
MAX_TAIL = 0.3


def _left_path(t, omega, b, b0) -> str:
    """The reason a flight is not a rigid body's when the samples leave the fitted motion well
    before the impulse that ends the stretch, still spinning fast; ``""`` otherwise."""
    tail = float(t[b0 - 1] - t[b - 1])
    if tail <= MAX_TAIL:
        return ""
    flight = np.median(np.linalg.norm(omega[max(b - 30, 0):b], axis=1))
    after = np.median(np.linalg.norm(omega[b:b0], axis=1))
    if after < 0.5 * flight:
        return ""
    return (f"not a rigid body: the samples leave the fitted free motion {tail:.2g} s before any impulse ends the "
            f"flight, still turning at {after:.2g} rad/s (a rigid body's free flight lasts until the catch or the "
            f"impact): an internal torque acts (a rotor spinning up, a flexing or sloshing body, or two bodies)")


def judge_flights(data: np.ndarray, model: np.ndarray, mask: np.ndarray, lengths: np.ndarray,
                  starts: list[float]) -> tuple[Adequacy, list[int]]:
    """A joint fit judged flight by flight: each flight's residuals under the shared model by
    :func:`judge` (its own noise, its own rates), and the flights it does not describe.

    A joint fit's residuals pooled over its flights mix a short, fast flight with a long, slow
    one, and one number says nothing about which fails; its rigidity is not judged again here:
    ``|L|`` and ``E`` of a flight taken with moments its own samples were not fitted with rise by
    the misfit of the moments, not by an internal torque (each flight's own fit has been judged
    rigid or not: :func:`rigid_body_check`).

    Parameters
    ----------
    data, model : ndarray, shape (F, T, 3)
        The flights' samples and the joint model at them, rad/s (padded to ``T``).
    mask : ndarray of bool, shape (F, T, 3)
        The kept sample axes.
    lengths : ndarray of int, shape (F,)
        Each flight's number of samples.
    starts : list of float
        Each flight's first sample's time, s (to name it).

    Returns
    -------
    (Adequacy, list of int)
        The verdict (adequate when every flight is described; its misfit the largest flight's)
        and the indices of the flights not described.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.adequacy import judge_flights
    >>> rng = np.random.default_rng(0)
    >>> data = np.ones((2, 100, 3)) * 5.0 + rng.normal(0.0, 0.01, (2, 100, 3))
    >>> model = np.ones((2, 100, 3)) * 5.0
    >>> model[1] += 0.5 * np.sin(np.arange(100) / 10.0)[:, None]   # the second flight's samples not followed
    >>> verdict, bad = judge_flights(data, model, np.ones(data.shape, bool), np.array([100, 100]), [1.0, 4.0])
    >>> verdict.adequate, bad, verdict.reason.split(":")[0]
    (False, [1], 'the joint fit does not describe 1 of its 2 flights (at 4.00 s)')
    """
    from .uncertainty import noise_floor

    verdicts, bad = [], []
    for j, n in enumerate(np.asarray(lengths, int)):
        d, r, k = data[j, :n], data[j, :n] - model[j, :n], mask[j, :n]
        rows = np.all(k, axis=1)
        v = judge(float(np.sqrt(np.mean(r[k] ** 2))), noise_floor(r[rows]), float(np.sqrt(np.mean(d[k] ** 2))))
        verdicts.append(v)
        if not v.adequate:
            bad.append(j)
    worst = max(range(len(verdicts)), key=lambda j: verdicts[j].misfit)
    if not bad:
        return Adequacy(True, verdicts[worst].misfit, f"each of its {len(verdicts)} flights described; the largest "
                                                       f"misfit: {verdicts[worst].reason}"), []
    where = ", ".join(f"{starts[j]:.2f} s" for j in bad)
    return Adequacy(False, verdicts[bad[0]].misfit, (
        f"the joint fit does not describe {len(bad)} of its {len(verdicts)} flights (at {where}): "
        f"{verdicts[bad[0]].reason.removeprefix('the model does not fit: ')}")), bad
