"""A rotor spinning up inside the body: the rigid fit tested against a gyrostat's.

A body that carries a rotor (a flywheel device, a vibration motor) is a gyrostat: with the
rotor's angular momentum ``h(t)`` relative to the body, the whole's momentum ``L = I w + h``
obeys ``L' = L x w + tau`` in the body's frame (Hughes, *Spacecraft Attitude Dynamics*, 1986,
ch. 7; :mod:`tumble.dynamics.models.gyrostat`). The whole's ``|L|`` stays (the air aside) while
the body's ``|I w|`` gives or takes what the rotor takes or gives. A rotor that takes momentum
along ``L`` looks like drag to the budgets of
:func:`~tumble.analysis.fit.adequacy.rigid_body_check`, and a rigid fit with drag bends its
ratios to follow it, well within the 3 % misfit a free rigid body is allowed: on synthetic
tosses whose rotor spins up to 5 % of ``|L|`` six of 32 were fitted as rigid flights (#39).

What a rotor's spin-up shows that no drag does: its torque on the body, ``h x w - h'``, depends
on time, not on ``w``; the part ``-h'`` is fixed in the body and keeps its sign when a tumble
reverses ``w``, while a drag torque always opposes ``w`` (Landau & Lifshitz, *Mechanics*,
sec. 34). So :func:`rotor_check` fits
the flight again as a gyrostat whose rotor spins up along a fixed body axis ``a`` at a constant
rate from some time before the flight's first sample, ``h(t) = v (t - t_0 + s_0)`` (four
parameters more than the rigid fit: ``v``, ``s_0``), with the rigid fit's ratios, sensor
rotation, bias, quadratic drag and ``L`` at the first sample free again, started from the rigid
fit's. The momentum the rotor gains during the flight, ``|v| T / |L|`` (``T`` the flight's
length), is the statistic, with its standard uncertainty ``sigma`` from the fit's covariance
widened for the residuals' autocorrelation
(:func:`~tumble.analysis.fit.uncertainty.effective_covariance`).

A rigid body's model error lets the gyrostat fake a gain: a flexing racquet, and above all a
plate's drag, which is not the fit's per-axis law. Strip theory gives a racquet spun about its
intermediate axis a damping of its wobble (``w_1``) in proportion to the spin ``|w_2|``, which
no per-axis law has; the fitted rotor then lies across ``L`` and stands in for it. On the 180
rigid flights of the synthetic recordings measured for it (67 phone, 113 racquet; 100-400 Hz,
every ending, seeds 0-23 with 3 tosses each and the 45-toss racquet recording of seed 13) the
gain less two ``sigma`` exceeds 0.5 % of ``|L|`` in six racquet flights, up to 2.5 %, each with
an axis that stays within 16 deg of the plane across ``L`` (``max |L . a| / |L| <= 0.27``)
and a gyrostat that leaves its residuals 3.8-7.8 times their noise floor. The spin-down along
``L``, which the per-axis law describes, fakes little: in the 54 flights whose axis reaches
``|L . a| >= 0.5 |L|`` at some time, 0.48 % at most. So the decision:

- the rotor's axis reaches :data:`MIN_ALONG` of ``|L|`` during the flight: ``sigma`` as it is;
- it stays across ``L``: ``sigma`` times the gyrostat's own misfit over its noise floor
  (``rms / noise``, at least 1), as the model error it leaves biases the gain as much;

and the flight is refused when the gain less :data:`K_SIGMA` such ``sigma`` exceeds
:data:`MIN_GAIN`: over the 180 rigid flights at most 0.5 %, a third of it, and none of 133 more
(seeds 24-47, kept out of the choice) is refused. Of the synthetic
rotor tosses that the other tests let through (28 flights, rotor 5-20 % of ``|L|``), 12 are
refused, as many as by the bare ``sigma`` (whose threshold a racquet crossed: issue #39's
review). A flight whose rigid fit lies within :data:`MIN_MISFIT` times the noise floor of its
residuals is not refitted: a rotor it hid leaves the rigid fit that close only when its effect
is within the noise (every refused rotor toss's rigid fit was 7.7 times its noise floor or
more), and the gyrostat's fit is most of the check's cost.

A rotor that spins up and brakes again within the flight (a flywheel device's firmware: idle,
spin-up in a tenth of a second, hold, brake) nets out to no gain, and a steady spin-up does not
describe it: :func:`rotor_check` first asks :func:`~tumble.analysis.fit.budget.step_check`, the
world-frame momentum budget with an internal momentum that steps, which needs no refit.

This is a likelihood-ratio comparison of nested models made with a physical threshold rather
than the bare F-test: with hundreds of samples and a right model's smooth error the F-test
prefers the larger model for rigid flights too (F up to 450 on the rigid flights above), so
the size of the effect, not its mere significance, decides.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._html import headline_html, headline_repr
from ...dynamics.models.gyrostat import gyrostat_omega
from scipy.optimize import least_squares

from .budget import step_check
from .model import rotvec_matrix
from .solve import Solution
from .triangle import S_MIN, ratios
from .uncertainty import effective_covariance, noise_floor

__all__ = ["K_SIGMA", "MIN_ALONG", "MIN_GAIN", "MIN_MISFIT", "RotorFit", "fit_rotor", "rotor_check", "widening"]

#: The rotor's momentum gain over the flight, as a fraction of ``|L|``, beyond which (less
#: :data:`K_SIGMA` standard uncertainties, widened across ``L``) a flight is not a rigid body's
#: (module docstring: a rigid body's model error fakes at most 0.5 % on the 180 synthetic
#: flights measured).
MIN_GAIN = 0.015
#: Standard uncertainties taken off the gain before it is compared with :data:`MIN_GAIN`.
K_SIGMA = 2.0
#: The share of ``|L|`` along the rotor's axis (``max |dot(L, a)| / |L|`` over the flight) below
#: which the rotor stands across ``L``, where a plate's drag fakes one: its uncertainty is then
#: widened by the gyrostat's misfit over the noise (module docstring).
MIN_ALONG = 0.5
#: A rigid fit within this many times the noise floor of its residuals is not refitted as a
#: gyrostat (module docstring).
MIN_MISFIT = 3.0
#: The largest turn of one integration step, rad: the sample interval is divided into equal
#: substeps so that ``|omega| dt`` stays below it (an RK4 local error of ~(0.1)^5 / 120 of
#: ``|omega|``).
TURN_PER_STEP = 0.1
#: The most evaluations of the gyrostat's residuals (:func:`scipy.optimize.least_squares`).
MAX_NFEV = 200
#: Where the rotor's start ``s_0`` (s before the flight's first sample) is first put: inside its
#: range [0, 0.5] s, as the throw's release lies tens of milliseconds before the fitted flight.
S0_START = 0.05
#: The most samples fitted: a longer flight is taken every k-th sample. The trust-region solver
#: takes an SVD of the Jacobian each step, which LAPACK threads beyond a few hundred rows (a fifth
#: of a second each on a loaded two-core machine, against a tenth of a millisecond); and a
#: rotor's spin-up is slow beside a 100 Hz sampling.
MAX_SAMPLES = 100
#: The least squares stop when a step lowers the sum of squares by less than this fraction.
FTOL = 1e-8


@dataclass(frozen=True)
class RotorFit:
    """The gyrostat fit of a flight (:func:`fit_rotor`).

    Attributes
    ----------
    gain, gain_std : float
        The rotor's momentum gain during the flight over the whole's ``|L|``, and its standard
        uncertainty (dimensionless).
    rms, rms_rigid : float
        The residuals' RMS of the gyrostat and of the rigid fit, rad/s.
    axis : ndarray, shape (3,)
        The rotor's axis, principal frame of the rigid fit.
    along : float
        The largest share of the whole's ``|L|`` along the rotor's axis during the flight,
        ``max |L . a| / |L|`` (0: the axis stays perpendicular to ``L``).
    noise : float
        The noise floor of the gyrostat's residuals, rad/s
        (:func:`~tumble.analysis.fit.uncertainty.noise_floor`).

    Examples
    --------
    A rotor that gained 4 +- 0.8 % of ``|L|``, its axis along ``L`` (nothing widened):

    >>> import numpy as np
    >>> from tumble.analysis.fit.rotor import RotorFit
    >>> fit = RotorFit(0.04, 0.008, 0.006, 0.051, np.array([0.0, 1.0, 0.0]), along=0.9, noise=0.0063)
    >>> round(fit.gain - 2 * fit.gain_std, 3)   # its gain less two standard uncertainties
    0.024
    """

    HEADLINE = (("gain", "momentum gain over |L|", ""), ("gain_std", "its std", ""), ("rms", "RMS residual", "rad/s"),
                ("rms_rigid", "rigid fit's", "rad/s"), ("along", "along L", ""), ("noise", "noise floor", "rad/s"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    gain: float
    gain_std: float
    rms: float
    rms_rigid: float
    axis: np.ndarray
    along: float = 1.0
    noise: float = 0.0


class _Gyrostat:
    """The gyrostat's samples in sensor axes for parameters ``x`` = ``s, g`` (the ratios' square
    coordinates), a rotation vector (sensor frame relative to the rigid fit's), the bias, the
    quadratic drag over ``I3``, ``L / I3`` at the first sample (principal frame, rad/s), ``v / I3``
    (rad/s^2) and ``s_0`` (s)."""

    def __init__(self, t: np.ndarray, R0: np.ndarray, speed: float) -> None:
        self.R0 = R0
        dt = np.diff(t)
        n = max(1, int(np.ceil(speed * float(dt.max()) / TURN_PER_STEP)))
        fine = np.r_[(t[:-1, None] + dt[:, None] * (np.arange(n) / n)).ravel(), t[-1]]
        self.tau, self.mid = fine - t[0], 0.5 * (fine[1:] + fine[:-1]) - t[0]
        self.fine, self.rows = fine, np.arange(len(t)) * n

    def principal(self, X: np.ndarray, v: np.ndarray, s0: float) -> np.ndarray:
        """Principal-frame rates of the bodies in the rows of ``X`` sharing the rotor ``v, s0``."""
        x1, x2 = ratios(X[:, 0], X[:, 1])
        inertia = np.zeros((len(X), 3, 3))
        inertia[:, 0, 0], inertia[:, 1, 1], inertia[:, 2, 2] = x1, x2, 1.0
        h, hm = np.outer(self.tau + s0, v), np.outer(self.mid + s0, v)
        return gyrostat_omega(inertia, X[:, 11:14] + h[0], self.fine, h, hm, quadratic=X[:, 8:11])[:, self.rows]

    def sensor(self, x: np.ndarray, wp: np.ndarray) -> np.ndarray:
        return wp @ (rotvec_matrix(x[2:5]) @ self.R0) + x[5:8]

    def jacobian(self, x: np.ndarray, keep: np.ndarray, step: np.ndarray) -> np.ndarray:
        base = self.principal(x[None], x[14:17], x[17])[0]
        f0 = self.sensor(x, base)
        cols = np.zeros((f0.size, len(x)))
        dyn = [0, 1, 8, 9, 10, 11, 12, 13]  # the parameters that change the body's motion
        X = np.repeat(x[None], len(dyn), axis=0)
        X[np.arange(len(dyn)), dyn] += step[dyn]
        for k, wp in zip(dyn, self.principal(X, x[14:17], x[17]), strict=True):
            cols[:, k] = (self.sensor(x, wp) - f0).ravel() / step[k]
        for k in (2, 3, 4):
            y = x.copy()
            y[k] += step[k]
            cols[:, k] = (self.sensor(y, base) - f0).ravel() / step[k]
        for k in (5, 6, 7):
            cols[:, k] = np.tile(np.eye(3)[k - 5], len(base))
        for k in (14, 15, 16, 17):
            y = x.copy()
            y[k] += step[k]
            cols[:, k] = (self.sensor(y, self.principal(y[None], y[14:17], y[17])[0]) - f0).ravel() / step[k]
        return cols * keep.reshape(-1, 1)


def fit_rotor(t: np.ndarray, omega: np.ndarray, keep: np.ndarray, sol: Solution) -> RotorFit | None:
    """Fit one flight as a gyrostat whose rotor spins up (module docstring), from its rigid fit.

    Parameters
    ----------
    t : ndarray, shape (n,)
        The flight's times, s (those of ``sol``).
    omega : ndarray, shape (n, 3)
        Its gyroscope samples, sensor axes, rad/s.
    keep : ndarray of bool, shape (n, 3)
        The sample axes fitted (not saturated).
    sol : Solution
        Its rigid fit (one flight, :func:`~tumble.analysis.fit.single.fit_solution`).

    Returns
    -------
    RotorFit or None
        None when the gyrostat's least squares fail numerically.

    Examples
    --------
    A phone whose rotor spins up to 5 % of ``|L|`` during a 0.9 s toss (100 Hz, 0.01 rad/s of
    noise): the gyrostat's gain, less two standard uncertainties, is over the 1.5 % of ``|L|`` a
    rigid body's drag and flex can fake, and it fits the samples better than the rigid body.

    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import gyrostat_flight
    >>> from tumble.analysis.fit.rotor import fit_rotor
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES
    >>> body = TOSS_BODIES["phone"]
    >>> t, w0 = np.arange(0.0, 0.9, 0.01), np.array([0.3, 14.0, 0.4])
    >>> h = 0.05 * np.linalg.norm(np.array(body.moments) * w0)
    >>> w = gyrostat_flight(body, w0, 0.9, t, np.array([0.6, 0.0, 0.8]), h, 0.9, lambda x: np.zeros(3))
    >>> w = w + np.random.default_rng(3).normal(0.0, 0.01, w.shape)
    >>> keep = np.ones(w.shape, bool)
    >>> fit = fit_rotor(t, w, keep, fit_solution(t, w, keep, drag="quadratic"))
    >>> bool(fit.gain - 2 * fit.gain_std > 0.015) and fit.rms < fit.rms_rigid
    True
    >>> bool(abs(fit.gain - 0.05) < 2 * fit.gain_std)   # the 5 % it gained, within its uncertainty
    True
    """
    m, P = sol.model, sol.P
    t, omega = np.asarray(t, float), np.asarray(omega, float)
    mask = np.asarray(keep, bool).astype(float)
    wp0 = m.principal(P)[0, :len(t)]
    I = m.moments(P)
    drag = m.drag_vector(P) if m.drag == "quadratic" else np.zeros(3)
    every = -(-len(t) // MAX_SAMPLES)
    t, omega, mask = t[::every], omega[::every], mask[::every]
    g = _Gyrostat(t, m.rotation_matrix(P), float(np.max(np.linalg.norm(omega, axis=1))))
    x0 = np.r_[P[0], P[1], np.zeros(3), m.bias_vector(P), drag, I * wp0[0], np.zeros(3), S0_START]
    lo = np.r_[S_MIN, 0.0, np.full(3, -np.inf), np.full(3, -1.0), np.zeros(3), np.full(6, -np.inf), 0.0]
    hi = np.r_[1.0, 1.0, np.full(3, np.inf), np.full(3, 1.0), np.full(9, np.inf), 0.5]
    x0 = np.clip(x0, lo, hi)
    L = float(np.linalg.norm(x0[11:14]))
    step = np.r_[1e-6, 1e-6, np.full(3, 1e-6), np.full(3, 1e-6), np.full(3, 1e-6), np.full(3, 1e-6 * L),
                 np.full(3, 1e-6 * L), 1e-6]

    def residuals(x):
        return ((g.sensor(x, g.principal(x[None], x[14:17], x[17])[0]) - omega) * mask).ravel()

    def jac(x):
        return g.jacobian(x, mask, step * np.where(x + step > hi, -1.0, 1.0))

    try:
        fit = least_squares(residuals, x0, jac=jac, bounds=(lo, hi), x_scale="jac", max_nfev=MAX_NFEV, ftol=FTOL)
    except (ValueError, np.linalg.LinAlgError):
        return None
    x, J, r = np.clip(fit.x, lo, hi), fit.jac, fit.fun
    if not np.all(np.isfinite(r)):
        return None
    per_sample = r.reshape(-1, 3)
    cov, _ = effective_covariance(J, r, per_sample, [0, len(t)])
    v = x[14:17]
    speed = float(np.linalg.norm(v))
    length = float(t[-1] - t[0])
    L = float(np.linalg.norm(x[11:14]))
    u = v / speed if speed > 0 else np.zeros(3)
    var = float(u @ cov[14:17, 14:17] @ u) if speed > 0 else float(np.trace(cov[14:17, 14:17]))
    kept = mask.ravel() > 0
    x1, x2 = ratios(x[0], x[1])
    whole = g.principal(x[None], v, x[17])[0] * np.array([x1, x2, 1.0]) + np.outer(g.tau[g.rows] + x[17], v)
    along = float(np.max(np.abs(whole @ u) / np.linalg.norm(whole, axis=1)))
    return RotorFit(speed * length / L, np.sqrt(max(var, 0.0)) * length / L,
                    float(np.sqrt(np.mean(r[kept] ** 2))), float(sol.rms), u, along,
                    noise_floor(per_sample[np.all(mask > 0, axis=1)]))


def rotor_check(t: np.ndarray, omega: np.ndarray, keep: np.ndarray, sol: Solution) -> str:
    """The reason a flight is not a rigid body's, or an empty string: an internal momentum that steps
    explains its world-frame budget (:func:`~tumble.analysis.fit.budget.step_check`), or a rotor
    spinning up inside explains its samples (:func:`fit_rotor`, refused by :data:`MIN_GAIN` and
    :data:`K_SIGMA`: module docstring).

    Examples
    --------
    A phone whose internal rotor spins up to 5 % of ``|L|`` during a 0.9 s toss, sampled at
    100 Hz with 0.01 rad/s of noise, fitted as a rigid body with drag (adequately: the model's
    error is under 3 % of the rates), and its rigid twin:

    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import gyrostat_flight
    >>> from tumble.analysis.fit.rotor import rotor_check
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES
    >>> body = TOSS_BODIES["phone"]
    >>> t = np.arange(0.0, 0.9, 0.01)
    >>> w0 = np.array([0.3, 14.0, 0.4])
    >>> noise = np.random.default_rng(3).normal(0.0, 0.01, (len(t), 3))
    >>> I = np.array(body.moments)
    >>> for gain in (0.0, 0.05):
    ...     w = gyrostat_flight(body, w0, 0.9, t, np.array([0.6, 0.0, 0.8]), gain * np.linalg.norm(I * w0), 0.9,
    ...                         lambda x: np.zeros(3)) + noise
    ...     keep = np.ones(w.shape, bool)
    ...     sol = fit_solution(t, w, keep, drag="quadratic")
    ...     print(gain, rotor_check(t, w, keep, sol)[:50] or "rigid")
    0.0 rigid
    0.05 not a rigid body: a rotor spinning up inside expla
    """
    keep = np.asarray(keep, bool)
    stepped = step_check(t, omega, keep, sol)  # a rotor spun up and braked within the flight
    if stepped:
        return stepped
    rows = np.all(keep, axis=1)
    if sol.rms <= MIN_MISFIT * noise_floor((np.asarray(omega, float) - sol.omega_model[0, :len(omega)])[rows]):
        return ""
    fit = fit_rotor(t, omega, keep, sol)
    if fit is None or fit.gain - K_SIGMA * fit.gain_std * widening(fit) <= MIN_GAIN:
        return ""
    return (f"not a rigid body: a rotor spinning up inside explains the samples (an internal angular momentum "
            f"growing by {100 * fit.gain:.2g} +- {100 * fit.gain_std * widening(fit):.2g} % of |L| during the flight, "
            f"residual {fit.rms:.2g} rad/s against the rigid fit's {fit.rms_rigid:.2g}; a rigid body's drag and flex "
            f"fake at most {100 * MIN_GAIN:.2g} %): an internal torque acts")


def widening(fit: RotorFit) -> float:
    """The factor on the gain's standard uncertainty (module docstring): 1 for a rotor whose axis
    reaches :data:`MIN_ALONG` of ``|L|``, else the gyrostat's misfit over its noise floor (at least 1).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.rotor import RotorFit, widening
    >>> across = RotorFit(0.04, 0.008, 0.024, 0.051, np.array([1.0, 0.0, 0.0]), along=0.27, noise=0.0063)
    >>> round(widening(across), 2), widening(RotorFit(0.04, 0.008, 0.024, 0.051, np.array([0.0, 1.0, 0.0]), 0.9, 0.0063))
    (3.81, 1.0)
    """
    if fit.along >= MIN_ALONG or fit.noise <= 0.0:
        return 1.0
    return max(1.0, fit.rms / fit.noise)
