"""Several throws of one flown body: :func:`pool_throws` (issue #42 item 4).

1. Each throw is fitted on its own (:func:`~tumble.analysis.tensor.throw.fit_flown`): where its
   flight lies, its own tensor and centre of mass with their covariances (kept as diagnostics).
2. A throw is **left out with its reason** when its fit cannot be trusted
   (:func:`~tumble.analysis.tensor.verdicts.throw_verdict`): no flight found, no accelerometer, or what
   the caller's check says (the object's tensor not physical: :func:`tumble.fit_tensor`).
3. The throws left are **fitted jointly** (:mod:`~tumble.analysis.tensor.joint`): one tensor
   and one centre of mass, each throw its own motion, bias, drag and rotor lag; from
   :data:`SENSOR_THROWS` throws on, the gyroscope's distortion and the rotor's tilt too (a
   single throw of a calibrated device, :attr:`~tumble.analysis.tensor.sensors.SensorErrors.calibrated`,
   holds them at the calibration's values, their uncertainties carried). A throw whose part of it has
   residuals well above the gyroscope's noise (measured from the throw itself) or needs a gyroscope
   bias beyond :data:`~tumble.analysis.tensor.verdicts.MAX_BIAS` is left out
   (:func:`~tumble.analysis.tensor.verdicts.joint_verdict`; a single throw's own fit may need a
   large bias to mimic the distortion that the joint fit explains), the one furthest beyond its limits
   first, and the rest refitted from the joint fit before; where only biases are beyond it and the fit
   with every bias held at 0 explains the throws as well, that fit is taken instead (:func:`_without_biases`:
   the rotor's tilt trades with the biases). Once the others agree, a throw so left out is judged again
   against their fit (its own motion fitted, the tensor and the sensors held: :func:`_against`) and taken
   back where that explains it, once: a throw of another body pulls the joint tensor off, and a good
   throw's residuals can then be the worst.
4. A throw whose own estimate lies more than :data:`OUTLIER_SIGMA` standard uncertainties from the joint one (in
   its principal moments) is left out, naming that, and the rest refitted (3 or more throws: with two, neither
   can be called the outlier).
5. ``chi^2 / dof`` of the throws' own tensors about the joint one (:func:`agreement`, each throw refitted with the
   sensors held at the joint fit's): above 1, the throws disagree beyond their uncertainties, and the joint
   covariance's statistical part is multiplied by it (the Birge ratio, as the ratio fit pools its flights; the
   sensors' parts, the same in every throw of the device, are not: the throws' scatter says nothing of them). Below
   1, from :data:`SHRINK_DOF` degrees of freedom on, that part shrinks, but no further than the ratio's 95 % upper
   confidence bound (:func:`birge_factor`). Of the centre's covariance only the part from the fitted rates (their
   parameters' covariance, which the throws' scatter measures) is inflated by it, never shrunk; the accelerometer's
   part is its own residuals' and a jackknife's over the flights
   (:func:`~tumble.analysis.tensor.center.center_of_mass`), of which the tensors' scatter says nothing. Inflated
   whole, the device-alone centre's std along the rotor's axis came out 0.15-2.1 mm over 25 realistic devices (8
   sets with an agreement of 1.8-9.5) where its errors were 0.004-0.74 mm, 0.61 std rms; with the rates' part alone
   inflated, 0.15-0.75 mm, 0.74 std rms, all within 1.96 std.

Systematic parts common to all the throws beyond the sensors' (the rotor's inertia, the
device's own tensor) are added by the caller: averaging does not reduce them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from scipy.special import gammaincinv

from ..._html import headline_html, headline_repr
from ...typing import FloatArray
from .center import center_of_mass, sensor_columns
from .throwlog import Throw
from .estimate import NOT_A_BODY, principal_uncertainty, vector_of
from .joint import JointFit, JointModel, fit_joint
from .sensors import SensorErrors
from .model import cholesky_of, inertia_of
from .throw import RESIDUAL_LIMIT, FlownFit, fit_flown
from .verdicts import (_BIAS_REASON, MAX_BIAS, accel_hint, duplicate_throws, join_reasons, joint_verdict, rail_hint,
                       residual_verdict, throw_verdict)

__all__ = ["BIAS_FREE_RMS", "OUTLIER_SIGMA", "SENSOR_THROWS", "SHRINK_DOF", "NoThrowError", "Pooled", "agreement",
           "birge_factor", "outlier", "own_fits", "pool_throws"]

#: A throw this many standard uncertainties from the joint fit is an outlier.
OUTLIER_SIGMA = 5.0
#: From this many throws on the joint fit determines the gyroscope's distortion and the rotor's
#: tilt too (:class:`~tumble.analysis.tensor.joint.JointModel`); with fewer they are left to
#: the stated uncertainties.
SENSOR_THROWS = 2
#: A joint fit with the biases held at 0 explains the throws as well as the free one when each
#: throw's residuals' rms is within this factor of the free fit's (:func:`_without_biases`).
BIAS_FREE_RMS = 1.1
#: From this many degrees of freedom of the throws' agreement on (:func:`agreement`: ``6 (n - 1)``
#: for ``n`` throws, so 5 throws and more) an agreement below 1 shrinks the statistical covariance
#: (:func:`birge_factor`).
SHRINK_DOF = 24


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
    ``J_r``) and centre (m) with their covariances (the tensor's sensors' part included; the statistical
    part scaled by the throws' agreement, :func:`birge_factor`), ``chi^2 / dof`` of the throws about them (NaN for one throw)
    and the throws used; each used throw's gyroscope bias in the joint fit (rad/s); the sensors'
    part as columns (:attr:`~tumble.analysis.tensor.joint.JointFit.sensor_columns`), and the
    centre's, not in ``center_cov`` (:func:`~tumble.analysis.tensor.center.sensor_columns`: the
    accelerometer's scale factors, the gyroscope's turn; None without the sensors' errors); the sensors' seven :data:`~tumble.analysis.tensor.sensors.SENSOR_NAMES` as the
    joint fit found them with their covariance (None where it did not fit them).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.pool import Pooled
    >>> Pooled(np.ones(6), np.eye(6), np.zeros(3), np.eye(3), float("nan"), 1).adequate
    True
    """

    HEADLINE = (("used", "throws", ""), ("chi2_dof", "chi2/dof", ""), ("adequate", "adequate", ""),
                ("inertia", "tensor xx, yy, zz, xy, xz, yz", ""), ("center", "centre", "m"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    inertia: FloatArray
    inertia_cov: FloatArray
    center: FloatArray
    center_cov: FloatArray
    chi2_dof: float
    used: int
    adequate: bool = True
    biases: FloatArray | None = None
    sensor_columns: FloatArray | None = None
    sensor: FloatArray | None = None
    sensor_cov: FloatArray | None = None
    center_columns: FloatArray | None = None


def _own_start(f: FlownFit, inertia: FloatArray) -> FloatArray:
    """A throw's own parameters in a joint fit (``L(t_0)``, bias, drag, lag), started from its lone fit:
    its initial rate with the joint ``inertia`` makes ``L(t_0) = I omega_0 + h_0``."""
    assert f.model is not None and f.P is not None
    w0 = f.model.omega(f.P[None])[0][0]
    return np.r_[inertia @ w0 + f.model.h[0], f.P[9:]]


def _joint(fits: list[FlownFit], errors: SensorErrors | None, start: FloatArray | None = None):
    """The joint fit of the throws ``fits`` (their models and optima as the start); the sensors
    fitted from :data:`SENSOR_THROWS` throws on (on readings a calibrated device has corrected:
    what is left of its distortion), one throw's held at the calibration's. ``start``: the tensor's
    ``C`` and the sensors' of an earlier joint fit of more of these throws, to start from instead
    (a refit without a throw left out: started afresh from the lone fits, whose tensors the
    gyroscope's distortion and a rotor tilted 2-3 degrees shift by per cents, it fell into an optimum
    with biases of several rad/s and left every throw of two realistic devices in 100 out)."""
    C0 = (cholesky_of(np.median(np.array([f.inertia for f in fits]), axis=0)) if start is None
          else np.asarray(start[:6], float))
    I0 = inertia_of(C0)
    rest = [_own_start(f, I0) for f in fits]
    fitted = len(fits) >= SENSOR_THROWS
    joint = JointModel([f.model for f in fits], sensor=fitted or (errors is not None and errors.calibrated))  # type: ignore[misc]
    held = None
    if joint.sensor and not fitted:  # one throw of a calibrated device: the calibration's, held
        held = np.zeros(joint.n, bool)
        held[6:joint.base] = True
    sensor = start[6:] if start is not None and joint.sensor and len(start) == joint.base else None
    return joint, fit_joint(joint, joint.pack(C0, rest, sensor), errors, held)


def _without_biases(joint: JointModel, jf: JointFit, errors: SensorErrors | None) -> JointFit:
    """The joint fit ``jf`` refitted with every throw's gyroscope bias held at 0, if that explains
    each throw as well (its residuals' rms within :data:`BIAS_FREE_RMS` of the free fit's); else
    ``jf``. For a fit whose biases exceed :data:`~tumble.analysis.tensor.verdicts.MAX_BIAS` while its
    residuals are at the noise: the rotor's tilt and the gyroscope's distortion trade with the biases, and a rotor tilted
    beyond its stated uncertainty left the fit in an optimum where biases of 0.3-0.7 rad/s stand
    in for a part of the tilt (device 78 of benchmarks/calibration_coverage.py, tilted 2.7 degrees
    against the stated 1: held at 0 its throws' residuals were 1.24-1.49 times the noise, free
    1.24-1.54; leaving out the throw of 0.66 rad/s drove the others' refit to 0.9-4 rad/s and left
    every throw out). A flight controller zeroes its gyroscope at rest (the residual bias about
    0.05 rad/s, :data:`~tumble.analysis.tensor.verdicts.MAX_BIAS`'s sources), which the biases held at 0
    leave out of the covariance. A throw with a real offset (a bias of 0.8 rad/s) is not explained without it, and
    stays judged by its bias.

    Examples
    --------
    >>> from tumble.analysis.tensor.pool import BIAS_FREE_RMS
    >>> BIAS_FREE_RMS
    1.1
    """
    held = np.zeros(joint.n, bool)
    for k in range(len(joint.models)):
        held[joint.base + joint.per * k + 3: joint.base + joint.per * k + 6] = True
    P0 = np.where(held, 0.0, jf.P)
    zero = fit_joint(joint, P0, errors, held)
    return zero if bool(np.all(zero.rms <= BIAS_FREE_RMS * jf.rms)) else jf


def _against(joint: JointModel, jf: JointFit, f: FlownFit) -> str:
    """Why a throw left out of a joint fit is not explained by the fit of the others, ``jf``, or ``""``:
    its own motion (``L(t_0)``, bias, drag, lag) fitted with the tensor and the sensors held at ``jf``'s
    and judged as in the joint fit (:func:`~tumble.analysis.tensor.verdicts.joint_verdict`). A throw of
    another body in the joint fit pulls the tensor off, and the residuals of a good throw can then be
    the worst: of three throws of an object and one of the proof body, the object's first was left
    out before the proof body's, and then never judged again (a walkthrough of docs/tensor.md,
    2026-12-02: 2 of 4 throws used, where the object's three alone agree at chi2/dof 0.57)."""
    one = JointModel([f.model], sensor=joint.sensor)  # type: ignore[list-item]
    rest = _own_start(f, jf.inertia)
    held = np.zeros(one.n, bool)
    held[:one.base] = True
    P0 = one.pack(jf.P[:6], [rest], jf.P[6:joint.base] if joint.sensor else None)
    g = fit_joint(one, P0, None, held)
    return joint_verdict(one.throw_parameters(g.P, 0)[9:12], float(g.rms[0]), f.noise)


def own_fits(joint: JointModel, jf: JointFit) -> list[JointFit]:
    """Each throw of a joint fit refitted alone with the sensors held at the joint fit's values:
    its own tensor, differing from the joint one by what varies from throw to throw, not by the
    gyroscope's distortion (which shifts a lone throw's tensor differently for each spin).

    Examples
    --------
    >>> from tumble.analysis.tensor.pool import own_fits
    >>> callable(own_fits)
    True
    """
    out = []
    for k, model in enumerate(joint.models):
        one = JointModel([model], sensor=joint.sensor)
        held = np.zeros(one.n, bool)
        held[6:one.base] = True
        out.append(fit_joint(one, np.r_[jf.P[:joint.base], joint.throw_parameters(jf.P, k)[6:]], None, held))
    return out


def agreement(own: Sequence[JointFit], inertia: FloatArray) -> float:
    """``chi^2 / dof`` of the throws' own tensors (:func:`own_fits`) about the joint one
    ``inertia``, each with its statistical covariance; NaN for one throw. About 1 when the throws
    are of one rigid body; well above, when they are not (the mount moved, another object), or
    when something the model leaves out varies between throws. (The centres of mass are not
    compared: a lone throw's centre from the accelerometer has a covariance dominated by its
    rates' uncertainty, which a refit like this one does not state.)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.pool import agreement
    >>> agreement([], np.eye(3))
    nan
    """
    if len(own) < 2:
        return float("nan")
    target = vector_of(inertia)
    chi2 = 0.0
    for f in own:
        d = vector_of(f.inertia) - target
        chi2 += float(d @ np.linalg.pinv(f.inertia_cov_stat) @ d)
    return chi2 / (6 * (len(own) - 1))


def birge_factor(chi2_dof: float, throws: int) -> float:
    """The factor on a joint fit's statistical covariance from the agreement ``chi2_dof``
    (:func:`agreement`, ``dof = 6 (throws - 1)``) of its throws.

    - Above 1: ``chi2_dof``, the Birge ratio (R. T. Birge, *Phys. Rev.* 40, 207 (1932); the
      Particle Data Group's scale factor, *Review of Particle Physics*, Introduction, sec. 5.2.2).
    - Below 1 with at least :data:`SHRINK_DOF` degrees of freedom: the ratio's one-sided 95 %
      upper confidence bound ``chi2_dof dof / chi2_{dof}(0.05)`` (``chi2`` about the truth is
      ``chi2_{dof}``-distributed times the true ratio; the bound's quantile from
      :func:`scipy.stats.chi2.ppf`), at most 1: the throws' scatter shows the stated variance
      too large, and the covariance shrinks only as far as the scatter shows at 95 % confidence.
    - Else 1 (NaN: one throw; fewer degrees of freedom: the bound is too loose to shrink by).

    Why: each throw's statistical covariance is the textbook one times its residuals'
    autocorrelation time, which the rotor's vibration lengthens (colour far from the tensor's
    columns in frequency). The calibration's proof throws scattered about their joint fit by a
    fifth of the variance the fits state (benchmarks/calibration_coverage.py, 40 devices), and
    the rotor inertia's 95 % intervals held in 40 of 40 devices with a median error of 0.39 std.
    Replayed on the pooled sets of devices 0-19, 40 and 41 (with the centres' shared parts of
    :func:`~tumble.analysis.tensor.equations.rotor_inertia_from`): shrinking by the ratio itself
    went too far (13 of the first 17 intervals held; the joint fit's statistical part holds the
    sensors' fitted errors too, which the throws' own refits, the sensors held, do not scatter
    by); by its 95 % bound 21 of 22 held, the errors' rms 1.02 std.

    Examples
    --------
    >>> from tumble.analysis.tensor.pool import birge_factor
    >>> birge_factor(2.5, 3), birge_factor(0.2, 3), round(birge_factor(0.2, 5), 3), birge_factor(0.9, 5)
    (2.5, 1.0, 0.347, 1.0)
    >>> birge_factor(float("nan"), 1)
    1.0
    """
    if not np.isfinite(chi2_dof):
        return 1.0
    if chi2_dof >= 1.0:
        return float(chi2_dof)
    dof = 6 * (int(throws) - 1)
    if dof < SHRINK_DOF:
        return 1.0
    return float(min(1.0, chi2_dof * dof / (2.0 * gammaincinv(dof / 2, 0.05))))  # scipy.stats' chi2.ppf(0.05, dof)


def outlier(own: Sequence[JointFit], inertia: FloatArray) -> tuple[int, float]:
    """The throw whose own tensor (:func:`own_fits`) lies farthest from the joint one in its
    principal moments, and how many of its standard uncertainties.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.joint import JointFit
    >>> from tumble.analysis.tensor.pool import outlier
    >>> one = lambda m: JointFit(None, None, np.diag(m), np.eye(6) * 1e-4, np.eye(6) * 1e-4, np.zeros((6, 6)), None)
    >>> k, z = outlier([one([1.0, 2.0, 3.0]), one([1.0, 2.0, 3.5])], np.diag([1.0, 2.0, 3.0]))
    >>> k, round(z, 6)   # 0.5 off where its std is 0.01
    (1, 50.0)
    """
    moments = np.linalg.eigvalsh(inertia)
    z = []
    for f in own:
        m, s, _ = principal_uncertainty(f.inertia, f.inertia_cov_stat)
        z.append(float(np.max(np.abs(m - moments) / np.maximum(s, 1e-300))))
    k = int(np.argmax(z))
    return k, z[k]


def pool_throws(throws: Sequence[Throw], rotor_axis: FloatArray, rotor_inertia: float, *,
                saturation: float | None = None, errors: SensorErrors | None = None,
                check: Callable[[FlownFit, Throw], str] | None = None, gyro: FloatArray | None = None,
                which: str = "") -> tuple[Pooled, list[FlownFit]]:
    """Fit every throw and the usable ones jointly (module docstring).

    Parameters
    ----------
    throws : sequence of Throw
    rotor_axis : ndarray, shape (3,)
    rotor_inertia : float
        ``J_r``, kg m^2 (1: the tensors in units of ``J_r``).
    saturation : float, optional
        The gyroscope's range, rad/s.
    errors : SensorErrors, optional
        The sensors' stated uncertainties (type B; none by default).
    check : callable, optional
        ``check(fit, throw)`` -> a reason to leave a fitted throw out, or ``""``.
    gyro : ndarray, shape (3, 3), optional
        The gyroscope's calibrated response (:func:`~tumble.analysis.tensor.throw.fit_flown`).
    which : str
        What the throws are, in :class:`NoThrowError`'s message (``"with the proof body"``).

    Returns
    -------
    pooled : Pooled
    fits : list of FlownFit
        One per throw, ``reason`` non-empty for those not pooled.

    Raises
    ------
    ValueError
        ``throws`` empty, not throws, or one log given twice.
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
    if twice := duplicate_throws(throws):
        raise ValueError(twice)
    fits = [fit_flown(throw, rotor_axis, rotor_inertia, saturation=saturation, errors=errors, gyro=gyro)
            for throw in throws]
    for k, (throw, f) in enumerate(zip(throws, fits)):
        why = throw_verdict(f, throw) or (check(f, throw) if check is not None and not f.reason else "")
        if why:
            fits[k] = replace(f, reason=why)
    start = None
    lone = list(fits)  # each throw as its own fit left it: one left out by a joint fit may come back (below)
    joint_out: list[int] = []  # left out by their part of a joint fit, in that order
    readmitted: set[int] = set()
    while True:
        used = [k for k, f in enumerate(fits) if not f.reason]
        if not used:
            why = join_reasons([(throw.input or f"throw {k}", f.reason + accel_hint(throw) + rail_hint(throw, f, saturation))
                                for k, (throw, f) in enumerate(zip(throws, fits))])
            alone = len(throws) < SENSOR_THROWS and not (errors is not None and errors.calibrated)  # no tilt fitted
            hint = ("; one throw cannot fit the rotor's tilt, for which its bias then stands in: give more throws" if alone
                    and any(f.reason.startswith(_BIAS_REASON) for f in fits) else "") + ("; every throw's tensor is no "
                    "body's: check the object's mass (tumble tensor's --mass; a tenth of the real one does this) and the "
                    "device's mass, center_of_mass and rotor_inertia, which enter each of them" if all(
                        f.reason.startswith(NOT_A_BODY) for f in fits) else "")
            raise NoThrowError(f"no throw{' ' + which if which else ''} could be fitted ({why}){hint}")
        joint, jf = _joint([fits[k] for k in used], errors, start)
        noises = [fits[k].noise for k in used]
        judged = [joint_verdict(joint.throw_parameters(jf.P, j)[9:12], float(jf.rms[j]), noises[j]) for j in range(len(used))]
        if any(judged) and joint.sensor and not any(residual_verdict(float(r), n) for r, n in zip(jf.rms, noises)):
            jf = _without_biases(joint, jf, errors)
            judged = [joint_verdict(joint.throw_parameters(jf.P, j)[9:12], float(jf.rms[j]), noises[j])
                      for j in range(len(used))]
        start = jf.P[:joint.base]
        if any(judged):  # the one furthest beyond its limits left out, the rest refitted (one throw's pull
            # can put another's bias beyond the limit: leaving all out at once lost every throw of a device)
            def beyond(j: int) -> float:
                bias = float(np.max(np.abs(joint.throw_parameters(jf.P, j)[9:12]))) / MAX_BIAS
                return max(bias, float(jf.rms[j]) / (RESIDUAL_LIMIT * fits[used[j]].noise)) if judged[j] else -1.0
            j = max(range(len(used)), key=beyond)
            fits[used[j]] = replace(fits[used[j]], reason=judged[j])
            joint_out.append(used[j])
            continue
        own = own_fits(joint, jf) if len(used) > 1 else []
        worst, z = outlier(own, jf.inertia) if len(used) >= 3 else (-1, 0.0)
        if z > OUTLIER_SIGMA:
            fits[used[worst]] = replace(fits[used[worst]], reason=f"its tensor lies {z:.3g} standard uncertainties from "
                                                                  f"the other throws' joint fit (at most {OUTLIER_SIGMA:g})")
            continue
        back = [k for k in joint_out if k not in readmitted and fits[k].reason and not _against(joint, jf, lone[k])]
        if not back:
            break
        for k in back:  # each at most once: a throw that the refit leaves out again stays out
            fits[k] = lone[k]
            readmitted.add(k)
    chosen = [fits[k] for k in used]
    rates = joint.rates(jf.P)
    models, accels = [f.model for f in chosen], [f.accel for f in chosen]
    center, center_cov, _, cutoff = center_of_mass(models, rates, accels)  # type: ignore[arg-type]
    # the rates' part: each throw's (from its own fit), averaged down as independent estimates
    rates_cov = np.linalg.pinv(sum(np.linalg.pinv(f.center_cov_rates) for f in chosen))
    I = vector_of(jf.inertia)
    cov_I = jf.inertia_cov_stat
    chi2_dof = agreement(own, jf.inertia)
    birge = birge_factor(chi2_dof, len(chosen))
    # the statistical parts only: the sensors' errors are the device's, the same in every throw, and the
    # throws' scatter says nothing of them; of the centre's, the rates' part only, and only inflated (step 5)
    cov_I, center_cov = cov_I * birge, center_cov + rates_cov * max(1.0, birge)
    S = jf.sensor_columns
    cov_I = cov_I + jf.inertia_cov_sensor
    Sc = None  # the centre's sensors' part, for the caller to add (fit_tensor does; the calibration not yet)
    if errors is not None:
        Sc = sensor_columns(models, rates, accels, cutoff, errors.gyro_misalignment / np.sqrt(2.0))  # type: ignore[arg-type]
    biases = np.array([joint.throw_parameters(jf.P, j)[9:12] for j in range(len(chosen))])
    sensor = sensor_cov = None
    if joint.sensor and len(chosen) >= SENSOR_THROWS:
        sensor, sensor_cov = jf.P[6:joint.base], jf.cov_P[6:joint.base, 6:joint.base]
        sensor_cov = sensor_cov * birge
    fits = [replace(f, reason=f.reason + accel_hint(throw) + rail_hint(throw, f, saturation)) if f.reason else f
            for throw, f in zip(throws, fits)]
    return Pooled(I, cov_I, center, center_cov, chi2_dof, len(chosen), True, biases, S, sensor, sensor_cov, Sc), fits
