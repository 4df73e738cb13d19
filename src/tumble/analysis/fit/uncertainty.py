"""Uncertainties that hold when the residuals are not white, and when the instrument is not perfect.

The textbook covariance of a least-squares fit, ``(J^T J)^-1 s^2`` (Press et al., *Numerical
Recipes*, 3rd ed., sec. 15.5), assumes independent residuals of equal variance. A real toss's
residuals are not: an unmodelled drag, a flexing body, a timing error or a bias that drifts
leave smooth, autocorrelated residuals, and the textbook covariance is then too small by about
the residuals' correlation length in samples. Three parts make the reported uncertainty:

1. **Statistical**, with the residuals' effective sample size (:func:`effective_covariance`):
   the textbook covariance times the residuals' integrated autocorrelation time
   (:func:`autocorrelation_time`: Geyer's initial positive sequence, and batch means beside it
   for a slow error under a fast oscillation). Tried and measured worse on the synthetic
   tosses: the HAC sandwich of Newey & West with Andrews' bandwidth (83 % coverage of nominal
   95 % on the racquet, against 95 % for this form): on a one-second flight the scores sum to
   zero at the optimum, so a long bandwidth cancels what it should count.
2. **Systematic**, the gyroscope's scale factor (:func:`scale_covariance`), propagated by the
   GUM's law of propagation of uncertainty; common to all the flights of a recording.
3. **Coverage factor**: Student's for the Welch-Satterthwaite effective degrees of freedom
   (:func:`effective_dof`, :func:`interval`); one-sided at an edge of the triangle.

Pooling flights whose ratios disagree beyond their uncertainties: the pooled covariance is
multiplied by the Birge ratio squared, ``chi^2 / dof`` of the flights' ratios about the pooled
value, when it exceeds one (Birge, Phys. Rev. 40 (1932) 207; the Particle Data Group's scale
factor, *Review of Particle Physics*, Introduction, sec. 5.2.2), so that the pooled uncertainty
does not shrink with the number of tosses while they scatter more than they should.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
from scipy import sparse

from ...typing import ArrayLike

__all__ = ["SCALE_UNCERTAINTY", "autocorrelation_time", "birge_chi2", "effective_covariance", "effective_dof",
           "interval", "noise_floor", "scale_covariance", "scale_effect"]

#: Standard uncertainty of a MEMS gyroscope's scale factor per axis (sensitivity tolerance,
#: dimensionless): phones do not calibrate it, and datasheets give about +-1 % as limits.
SCALE_UNCERTAINTY = 0.005

def noise_floor(omega: ArrayLike) -> float:
    """A robust estimate of the white noise per axis, rad/s, from second differences
    (``var(w[i+1] - 2 w[i] + w[i-1]) = 6 sigma^2`` for white noise on a smooth signal).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.uncertainty import noise_floor
    >>> t = np.linspace(0.0, 2.0, 2000)[:, None]
    >>> smooth = np.hstack([np.sin(3 * t), np.cos(2 * t), 0.5 * t])   # rad/s
    >>> noisy = smooth + np.random.default_rng(1).normal(0.0, 0.01, smooth.shape)
    >>> round(noise_floor(noisy), 2), noise_floor(smooth) < 1e-5   # the white noise's sigma; the signal does not count
    (0.01, True)
    """
    omega = np.asarray(omega, float)
    if len(omega) < 3:
        return 0.0
    d2 = omega[2:] - 2 * omega[1:-1] + omega[:-2]
    mad = np.median(np.abs(d2 - np.median(d2, axis=0)), axis=0) * 1.4826
    return float(np.sqrt(np.mean(mad ** 2) / 6.0))


def interval(value: float, std: float, lo: float, hi: float, *, on_low_edge: bool = False,
             on_high_edge: bool = False, dof: float = np.inf) -> tuple[float, float]:
    """A 95 % interval for a parameter confined to ``[lo, hi]``.

    Inside: ``value +- k std`` clipped to the range, ``k`` Student's 97.5 % point for ``dof``
    effective degrees of freedom (1.96 for infinitely many; the GUM's coverage factor for a
    standard uncertainty estimated from the data, JCGM 100:2008, G.3-G.4). On an edge (the
    optimum at a bound, where the estimator's distribution has a point mass): one-sided, from
    the edge to the 95 % point inside it (1.645 for infinitely many degrees of freedom: the
    likelihood-ratio statistic at a boundary is half chi^2_0, half chi^2_1, Chernoff, Ann.
    Math. Stat. 25 (1954) 573; Self & Liang, JASA 82 (1987) 605).

    Examples
    --------
    >>> from tumble.analysis.fit.uncertainty import interval
    >>> [round(v, 4) for v in interval(0.5, 0.1, 0.0, 1.0)]   # +- 1.96 sigma
    [0.304, 0.696]
    >>> [round(v, 4) for v in interval(0.5, 0.1, 0.0, 1.0, dof=5)]   # Student's 2.571 for 5 degrees of freedom
    [0.2429, 0.7571]
    >>> [round(v, 4) for v in interval(0.0, 0.1, 0.0, 1.0, on_low_edge=True)]   # one-sided from the edge: 1.645 sigma
    [0.0, 0.1645]
    """
    # Student's quantile from scipy.special (the same function scipy.stats.t.ppf calls), not
    # scipy.stats: importing scipy.stats costs a quarter of a second of `tumble fit`
    from scipy.special import stdtrit

    z = float(stdtrit(dof, 0.975)) if np.isfinite(dof) else 1.959963984540054
    one_sided = float(stdtrit(dof, 0.95)) if np.isfinite(dof) else 1.6448536269514722
    if on_low_edge:
        return lo, min(hi, value + one_sided * std)
    if on_high_edge:
        return max(lo, value - one_sided * std), hi
    return max(lo, value - z * std), min(hi, value + z * std)


def birge_chi2(values: ArrayLike, covariances: ArrayLike, pooled: ArrayLike | None = None,
               shared: ArrayLike | None = None) -> tuple[float, int]:
    """``chi^2`` of per-flight estimates about the pooled value, and its degrees of freedom.

    The flights' errors are their own (``covariances``, independent of one another) and, with
    ``shared``, an error common to them all that moves each flight's estimate differently: the
    gyroscope's scale factor ``e`` shifts flight ``f``'s estimate by ``B_f e`` (``B_f`` its
    :func:`scale_effect` carried to the estimates, per standard uncertainty of ``e``), so the
    stacked estimates have the covariance ``C = diag(C_f) + B B^T`` and ``chi^2 = d^T C^-1 d``
    for the stacked differences ``d`` (the generalised least squares of correlated
    measurements: Cowan, *Statistical Data Analysis*, 1998, sec. 7.6; the PDG's *Review of
    Particle Physics*, Introduction, sec. 5.2). Without it the flights' scatter by that common
    error, which differs from flight to flight as their motions differ, counts as disagreement:
    three consistent tosses of a phone had ``chi^2 / dof = 6.7e3``. ``pooled`` None: about the
    generalised least-squares mean ``(1^T C^-1 1)^-1 1^T C^-1 v``, the minimum of ``chi^2``,
    with ``k (F - 1)`` degrees of freedom.

    Parameters
    ----------
    values : ndarray, shape (F, k)
    covariances : ndarray, shape (F, k, k)
    pooled : ndarray, shape (k,), optional
    shared : ndarray, shape (F, k, q), optional
        Each flight's answer to ``q`` common errors of unit variance.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.uncertainty import birge_chi2
    >>> values = np.array([[1.0], [3.0]])   # two flights 2 sigma apart
    >>> birge_chi2(values, np.ones((2, 1, 1)), np.array([2.0]))   # chi^2 = 1 + 1, one degree of freedom
    (2.0, 1)
    >>> birge_chi2(values, np.ones((2, 1, 1)))   # about their mean, the same
    (2.0, 1)
    >>> both = np.array([[[1.0]], [[-1.0]]])   # a common error of 1 sigma moves them 1 and -1 apart
    >>> chi2, dof = birge_chi2(values, np.ones((2, 1, 1)), shared=both)
    >>> round(chi2, 12), dof   # 2^2 / (1 + 1 + 2^2): the difference's variance holds the common error's
    (0.666666666667, 1)
    """
    values = np.asarray(values, float)
    F, k = values.shape
    C = np.zeros((F * k, F * k))
    for f, c in enumerate(np.asarray(covariances, float)):
        C[f * k:(f + 1) * k, f * k:(f + 1) * k] = c
    if shared is not None:
        B = np.asarray(shared, float).reshape(F * k, -1)
        C = C + B @ B.T
    W = np.linalg.pinv(C, hermitian=True)
    v = values.reshape(-1)
    if pooled is None:
        ones = np.tile(np.eye(k), (F, 1))  # the stacked design: every flight measures the same k values
        pooled = np.linalg.pinv(ones.T @ W @ ones) @ (ones.T @ W @ v)
    d = v - np.tile(np.asarray(pooled, float), F)
    return float(d @ W @ d), max(k * (F - 1), 1)


def autocorrelation_time(R: np.ndarray, starts: Sequence[int], block: int = 5) -> float:
    """The residuals' integrated autocorrelation time, samples (at least 1): the larger of
    :func:`_geyer_time` on the residuals and on their means over blocks of ``block`` samples
    (times ``block`` and the ratio of the variances: the batch means of Flegal & Jones, Ann.
    Stat. 38 (2010) 1034). The blocks matter when a fast oscillation (a flexing body, 15-35 Hz)
    rides on a slow model error: its negative correlations end Geyer's sum before the slow
    part is counted; averaging over a block removes the oscillation and keeps the slow part.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.uncertainty import autocorrelation_time
    >>> rng = np.random.default_rng(1)
    >>> white = rng.normal(size=(20000, 1))
    >>> round(float(autocorrelation_time(white, [0, 20000])))   # independent samples
    1
    >>> ar = np.convolve(white[:, 0], 0.8 ** np.arange(80))[:20000, None]   # AR(1), rho_k = 0.8^k:
    >>> # tau = (1 + 0.8) / (1 - 0.8) = 9
    >>> round(float(autocorrelation_time(ar, [0, 20000])))
    9
    """
    R = np.asarray(R, float).reshape(len(R), -1)
    tau = _geyer_time(R, starts)
    means, bstarts, total = [], [0], 0
    for lo, hi in itertools.pairwise(starts):
        n = (hi - lo) // block
        if n >= 4:
            x = R[lo:lo + n * block] - R[lo:hi].mean(axis=0)
            means.append(x.reshape(n, block, -1).mean(axis=1))
            total += n
            bstarts.append(total)
    if means:
        M = np.concatenate(means)
        var_r = float(np.mean((R - R.mean(axis=0)) ** 2))
        if var_r > 0:
            tau = max(tau, block * float(np.mean(M ** 2)) / var_r * _geyer_time(M, np.array(bstarts)))
    return max(tau, 1.0)


def _geyer_time(R, starts) -> float:
    """The residuals' integrated autocorrelation time, samples (at least 1).

    ``tau = 1 + 2 sum_k rho_k`` with the autocorrelation ``rho_k`` pooled over the axes and the
    flights (lags within a flight), the sum cut by Geyer's initial positive sequence: pairs
    ``rho_{2k} + rho_{2k+1}`` are added while positive (Geyer, Stat. Sci. 7 (1992) 473, sec. 3.3).
    For white residuals it is 1; for the smooth residual a model error leaves, about the
    error's duration in samples. A mean of ``n`` such samples has the variance of ``n / tau``
    independent ones (Sokal, *Monte Carlo methods in statistical mechanics*, 1997, sec. 2)."""
    longest = int(np.max(np.diff(starts)))
    acov = np.zeros(longest)
    var = 0.0
    for lo, hi in itertools.pairwise(starts):
        x = R[lo:hi] - R[lo:hi].mean(axis=0)
        n = len(x)
        if n < 2:
            continue
        f = np.fft.rfft(x, 2 * n, axis=0)
        ac = np.fft.irfft(f * np.conj(f), 2 * n, axis=0)[:n].sum(axis=1)
        acov[:n] += ac
        var += ac[0]
    if var <= 0:
        return 1.0
    rho = acov / var
    tau = -1.0
    for k in range(0, longest - 1, 2):
        pair = rho[k] + rho[k + 1]
        if pair <= 0:
            break
        tau += 2.0 * pair
    return max(tau, 1.0)


def effective_covariance(J: np.ndarray | sparse.csr_matrix, r: np.ndarray, per_sample: np.ndarray,
                         starts: Sequence[int]) -> tuple[np.ndarray, float]:
    """The textbook covariance with the residual variance scaled for autocorrelation.

    ``cov = (J^T J)^-1 s^2 tau``: ``s^2 = SSR / (m - n)`` and ``tau`` the residuals' integrated
    autocorrelation time (:func:`autocorrelation_time`): the data hold ``m / tau`` independent
    residuals, not ``m`` (the effective sample size; von Storch & Zwiers, *Statistical Analysis
    in Climate Research*, 1999, sec. 6.6.8).

    Parameters
    ----------
    J : ndarray or sparse matrix, shape (m, n)
    r : ndarray, shape (m,)
        Residuals (the rows of ``J``).
    per_sample : ndarray, shape (n_samples, 3)
        The same residuals by sample and axis, flights one after another (0 where an axis was
        left out).
    starts : ndarray of int
        Each flight's first sample, and the total last.

    Returns
    -------
    cov : ndarray, shape (n, n)
    tau : float
        The factor applied, samples.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.uncertainty import effective_covariance
    >>> rng = np.random.default_rng(2)
    >>> x = np.linspace(0.0, 1.0, 400)
    >>> J = np.column_stack([np.ones_like(x), x])   # a straight line a + b x
    >>> r = rng.normal(0.0, 0.1, x.size)   # white residuals of sigma 0.1
    >>> cov, tau = effective_covariance(J, r, r[:, None], [0, x.size])
    >>> textbook = np.linalg.inv(J.T @ J) * (r @ r) / (x.size - 2)
    >>> bool(np.allclose(cov, textbook * tau)), bool(tau < 1.2)   # white: tau about 1, the textbook covariance
    (True, True)
    """
    m, n = J.shape
    JtJ = (J.T @ J).toarray() if sparse.issparse(J) else J.T @ J
    d = np.sqrt(np.diag(JtJ))
    d = np.where(d > 0, d, 1.0)
    B = np.linalg.pinv(JtJ / np.outer(d, d)) / np.outer(d, d)
    s2 = float(r @ r) / max(m - n, 1)
    tau = autocorrelation_time(per_sample, starts)
    cov = B * s2 * tau
    return 0.5 * (cov + cov.T), tau


def scale_effect(J: np.ndarray | sparse.csr_matrix, data: np.ndarray, mask: np.ndarray, sigma: float) -> np.ndarray:
    """The parameters' shift for a scale error of one standard uncertainty on each gyroscope axis.

    A scale error ``e_k`` on sensor axis ``k`` changes the samples by ``e_k omega_k``; the
    least-squares parameters answer linearly, ``dP = (J^T J)^-1 J^T D e`` with ``D`` the
    samples of each axis in its own column: the shift is ``sigma A``, ``A = (J^T J)^-1 J^T D``
    (the sensitivity coefficients of the GUM, JCGM 100:2008, sec. 5.1.3). Kept beside the
    covariance it makes (:func:`scale_covariance`) because the error is common to every flight
    of one gyroscope while its effect is each flight's own: flights pooled are compared with it
    (:func:`birge_chi2`).

    Parameters
    ----------
    J : ndarray or sparse matrix, shape (m, n)
    data : ndarray, shape (F, T, 3)
        The samples, rad/s.
    mask : ndarray of bool, shape (F, T, 3)
        The sample axes fitted (the rows of ``J``, in order).
    sigma : float
        Standard uncertainty of each axis's scale factor (dimensionless).

    Returns
    -------
    ndarray, shape (n, 3)
        In the parameters' units per standard uncertainty of each axis's scale factor.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.uncertainty import scale_effect
    >>> data = np.zeros((1, 50, 3))
    >>> data[0, :, 0] = 4.0   # a constant 4 rad/s on axis 1, fitted as one parameter
    >>> mask = np.zeros(data.shape, bool)
    >>> mask[0, :, 0] = True
    >>> scale_effect(np.ones((50, 1)), data, mask, 0.005).round(12).tolist()   # 0.5 % of 4 rad/s, axis 1 only
    [[0.02, 0.0, 0.0]]
    """
    m, _n = J.shape
    axis = np.broadcast_to(np.arange(3), mask.shape)[mask]
    values = data[mask]
    D = np.zeros((m, 3))
    D[np.arange(m), axis] = values
    JtJ = (J.T @ J).toarray() if sparse.issparse(J) else J.T @ J
    JtD = np.asarray(J.T @ D)
    d = np.sqrt(np.diag(JtJ))
    d = np.where(d > 0, d, 1.0)
    return sigma * ((np.linalg.pinv(JtJ / np.outer(d, d)) / np.outer(d, d)) @ JtD)


def scale_covariance(J: np.ndarray | sparse.csr_matrix, data: np.ndarray, mask: np.ndarray, sigma: float) -> np.ndarray:
    """The parameters' covariance from the gyroscope's unknown scale factor on each axis.

    With independent scale errors ``e_k`` of standard uncertainty ``sigma`` the covariance is
    ``B B^T``, ``B`` the :func:`scale_effect`: a type B evaluation, propagated by the law of
    propagation of uncertainty (JCGM 100:2008, the GUM, secs. 4.3 and 5.1). It does not shrink
    with more samples or more flights: a bias of the instrument is common to all of them.
    Near-planar bodies feel it most: their ``I3 - I2`` is small, so a per-mille error in a rate
    is a per-cent error in it. The parameters are :func:`scale_effect`'s.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.uncertainty import scale_covariance
    >>> for n in (10, 1000):   # 2 rad/s on two axes, fitted as one mean: 0.5 % / sqrt(2) of 2 rad/s, however many samples
    ...     data = np.full((1, n, 3), 2.0)
    ...     mask = np.zeros(data.shape, bool)
    ...     mask[0, :, :2] = True
    ...     print(np.sqrt(scale_covariance(np.ones((2 * n, 1)), data, mask, 0.005)).round(12).tolist())
    [[0.007071067812]]
    [[0.007071067812]]
    """
    B = scale_effect(J, data, mask, sigma)
    return B @ B.T


def effective_dof(var_stat: float, var_total: float, dof_stat: float) -> float:
    """Welch-Satterthwaite's effective degrees of freedom of a standard uncertainty made of a
    statistical part with ``dof_stat`` degrees of freedom and a systematic part known exactly
    (infinitely many): ``nu = var_total^2 / (var_stat^2 / dof_stat)`` (JCGM 100:2008, G.4.1).

    Examples
    --------
    >>> from tumble.analysis.fit.uncertainty import effective_dof
    >>> effective_dof(1.0, 1.0, 10.0), effective_dof(0.5, 1.0, 10.0), effective_dof(0.0, 1.0, 10.0)   # half systematic: 4 x
    (10.0, 40.0, inf)
    """
    if not (var_stat > 0 and dof_stat > 0):
        return np.inf
    return float(var_total ** 2 / (var_stat ** 2 / dof_stat))
