"""Uncertainties that hold when the residuals are not white: the sandwich covariance.

The textbook covariance of a least-squares fit, ``(J^T J)^-1 s^2`` (Press et al., *Numerical
Recipes*, 3rd ed., sec. 15.5), assumes independent residuals of equal variance. A real toss's
residuals are not: an unmodelled drag, a flexing body, a timing error or a bias that drifts
leave smooth, autocorrelated residuals, and the textbook covariance is then too small by about
the residuals' correlation length in samples. The covariance used here is the
heteroskedasticity and autocorrelation consistent (HAC) sandwich of Newey & West (Econometrica
55 (1987) 703)::

    cov = B M B,   B = (J^T J)^-1,   M = sum_flights sum_{|l| <= S} w(l) sum_t g_t g_{t-l}^T,

with ``g_t = J_t^T r_t`` the score of sample ``t`` (its three axes together), Bartlett weights
``w(l) = 1 - |l| / (S + 1)``, and the bandwidth ``S`` chosen from the data by Andrews' AR(1)
plug-in rule (Econometrica 59 (1991) 817, eq. 6.4 and sec. 6): ``S = 1.1447 (alpha T)^(1/3)``,
``alpha = sum_a 4 rho_a^2 s_a^4 / ((1 - rho_a)^6 (1 + rho_a)^2) / sum_a s_a^4 / (1 - rho_a)^4``
over the scores' components ``a`` with lag-one autocorrelation ``rho_a`` and innovation
variance ``s_a^2``. Flights are independent: lags never cross from one flight to the next, so
for a recording the sandwich is also the cluster-robust covariance over flights (Liang & Zeger,
Biometrika 73 (1986) 13). The factor ``m / (m - n)`` (``m`` residuals, ``n`` parameters)
corrects the sandwich's small-sample bias (MacKinnon & White's HC1, J. Econometrics 29 (1985) 305).
For white residuals the sandwich reduces to the textbook form.

Pooling flights whose ratios disagree beyond their uncertainties: the pooled covariance is
multiplied by the Birge ratio squared, ``chi^2 / dof`` of the flights' ratios about the pooled
value, when it exceeds one (Birge, Phys. Rev. 40 (1932) 207; the Particle Data Group's scale
factor, *Review of Particle Physics*, Introduction, sec. 5.2.2), so that the pooled uncertainty
does not shrink with the number of tosses while they scatter more than they should.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse

__all__ = ["SCALE_UNCERTAINTY", "andrews_bandwidth", "autocorrelation_time", "birge_chi2", "effective_covariance",
           "effective_dof", "interval",
           "noise_floor", "sandwich_covariance", "scale_covariance"]

#: Standard uncertainty of a MEMS gyroscope's scale factor per axis (sensitivity tolerance,
#: dimensionless): phones do not calibrate it, and datasheets give about +-1 % as limits.
SCALE_UNCERTAINTY = 0.005

#: Largest lag-one autocorrelation used in the bandwidth rule (a smooth residual has rho -> 1,
#: where the rule's alpha diverges; the bandwidth is capped at the flight's length anyway).
_RHO_MAX = 0.97


def noise_floor(omega) -> float:
    """A robust estimate of the white noise per axis, rad/s, from second differences
    (``var(w[i+1] - 2 w[i] + w[i-1]) = 6 sigma^2`` for white noise on a smooth signal)."""
    omega = np.asarray(omega, float)
    if len(omega) < 3:
        return 0.0
    d2 = omega[2:] - 2 * omega[1:-1] + omega[:-2]
    mad = np.median(np.abs(d2 - np.median(d2, axis=0)), axis=0) * 1.4826
    return float(np.sqrt(np.mean(mad ** 2) / 6.0))


def andrews_bandwidth(scores, starts) -> float:
    """Andrews' AR(1) plug-in bandwidth for the Bartlett kernel (module docstring), in samples.

    Parameters
    ----------
    scores : ndarray, shape (n_samples, n)
        Per-sample scores, flights one after another.
    starts : ndarray of int
        Index of each flight's first sample in ``scores`` (and the total length last).
    """
    num = den = 0.0
    T = np.diff(starts)
    for a in range(scores.shape[1]):
        x0, x1 = [], []
        for lo, hi in zip(starts[:-1], starts[1:]):
            g = scores[lo:hi, a]
            x0.append(g[:-1]), x1.append(g[1:])
        x0, x1 = np.concatenate(x0), np.concatenate(x1)
        ss = float(x0 @ x0)
        if ss <= 0:
            continue
        rho = float(np.clip(x0 @ x1 / ss, -_RHO_MAX, _RHO_MAX))
        s2 = float(np.mean((x1 - rho * x0) ** 2))
        num += 4 * rho ** 2 * s2 ** 2 / ((1 - rho) ** 6 * (1 + rho) ** 2)
        den += s2 ** 2 / (1 - rho) ** 4
    if den <= 0:
        return 0.0
    return float(min(1.1447 * (num / den * np.mean(T)) ** (1.0 / 3.0), np.mean(T) / 4))


def sandwich_covariance(J, r, sample, starts) -> tuple[np.ndarray, float]:
    """The HAC sandwich covariance of least-squares parameters (module docstring).

    Parameters
    ----------
    J : ndarray or sparse matrix, shape (m, n)
        Jacobian of the residuals at the optimum (columns of the parameters kept).
    r : ndarray, shape (m,)
        Residuals, rad/s.
    sample : ndarray of int, shape (m,)
        The sample (0 .. n_samples - 1, flights one after another) each residual belongs to.
    starts : ndarray of int
        Each flight's first sample and the total number of samples last.

    Returns
    -------
    cov : ndarray, shape (n, n)
    bandwidth : float
        The Bartlett bandwidth used, samples.
    """
    m, n = J.shape
    n_samples = int(starts[-1])
    if sparse.issparse(J):
        JtJ = (J.T @ J).toarray()
        scores = sparse.csr_matrix((r, (sample, np.arange(m))), shape=(n_samples, m)) @ J
        scores = scores.toarray() if sparse.issparse(scores) else np.asarray(scores)
    else:
        JtJ = J.T @ J
        scores = np.zeros((n_samples, n))
        np.add.at(scores, sample, J * r[:, None])
    d = np.sqrt(np.diag(JtJ))
    d = np.where(d > 0, d, 1.0)
    B = np.linalg.pinv(JtJ / np.outer(d, d)) / np.outer(d, d)
    S = andrews_bandwidth(scores, starts)
    L = int(np.floor(S))
    M = scores.T @ scores
    for lag in range(1, L + 1):
        w = 1.0 - lag / (S + 1.0)
        G = np.zeros((n, n))
        for lo, hi in zip(starts[:-1], starts[1:]):
            if hi - lo > lag:
                G += scores[lo + lag:hi].T @ scores[lo:hi - lag]
        M += w * (G + G.T)
    cov = B @ M @ B * (m / max(m - n, 1))
    return 0.5 * (cov + cov.T), S


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
    """
    from scipy.stats import t as student

    z = float(student.ppf(0.975, dof)) if np.isfinite(dof) else 1.959963984540054
    one_sided = float(student.ppf(0.95, dof)) if np.isfinite(dof) else 1.6448536269514722
    if on_low_edge:
        return lo, min(hi, value + one_sided * std)
    if on_high_edge:
        return max(lo, value - one_sided * std), hi
    return max(lo, value - z * std), min(hi, value + z * std)


def birge_chi2(values, covariances, pooled) -> tuple[float, int]:
    """``chi^2`` of per-flight estimates about the pooled value, and its degrees of freedom.

    Parameters
    ----------
    values : ndarray, shape (F, k)
    covariances : ndarray, shape (F, k, k)
    pooled : ndarray, shape (k,)
    """
    chi2 = 0.0
    for v, c in zip(values, covariances):
        dv = v - pooled
        chi2 += float(dv @ np.linalg.pinv(c) @ dv)
    k = values.shape[1]
    return chi2, max(k * (len(values) - 1), 1)


def autocorrelation_time(r, starts, axes: int = 3, block: int = 5) -> float:
    """The residuals' integrated autocorrelation time, samples (at least 1): the larger of
    :func:`_geyer_time` on the residuals and on their means over blocks of ``block`` samples
    (times ``block`` and the ratio of the variances: the batch means of Flegal & Jones, Ann.
    Stat. 38 (2010) 1034). The blocks matter when a fast oscillation (a flexing body, 15-35 Hz)
    rides on a slow model error: its negative correlations end Geyer's sum before the slow
    part is counted; averaging over a block removes the oscillation and keeps the slow part."""
    R = r.reshape(-1, axes) if r.size % axes == 0 else r[:, None]
    tau = _geyer_time(R, starts)
    means, bstarts, total = [], [0], 0
    for lo, hi in zip(starts[:-1], starts[1:]):
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
    for lo, hi in zip(starts[:-1], starts[1:]):
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


def effective_covariance(J, r, starts, axes: int = 3) -> tuple[np.ndarray, float]:
    """The textbook covariance with the residual variance scaled for autocorrelation.

    ``cov = (J^T J)^-1 s^2 tau``: ``s^2 = SSR / (m - n)`` and ``tau`` the residuals' integrated
    autocorrelation time (:func:`autocorrelation_time`): the data hold ``m / tau`` independent
    residuals, not ``m`` (the effective sample size; von Storch & Zwiers, *Statistical Analysis
    in Climate Research*, 1999, sec. 6.6.8).

    Parameters
    ----------
    J : ndarray or sparse matrix, shape (m, n)
    r : ndarray, shape (m,)
        Residuals, sample-major (``axes`` per sample, flights one after another).
    starts : ndarray of int
        Each flight's first sample, and the total last.

    Returns
    -------
    cov : ndarray, shape (n, n)
    tau : float
        The factor applied, samples.
    """
    m, n = J.shape
    JtJ = (J.T @ J).toarray() if sparse.issparse(J) else J.T @ J
    d = np.sqrt(np.diag(JtJ))
    d = np.where(d > 0, d, 1.0)
    B = np.linalg.pinv(JtJ / np.outer(d, d)) / np.outer(d, d)
    s2 = float(r @ r) / max(m - n, 1)
    tau = autocorrelation_time(r, starts, axes)
    cov = B * s2 * tau
    return 0.5 * (cov + cov.T), tau


def scale_covariance(J, data, mask, sigma: float) -> np.ndarray:
    """The parameters' covariance from the gyroscope's unknown scale factor on each axis.

    A scale error ``e_k`` on sensor axis ``k`` changes the samples by ``e_k omega_k``; the
    least-squares parameters answer linearly, ``dP = (J^T J)^-1 J^T D e`` with ``D`` the
    samples of each axis in its own column. With independent ``e_k`` of standard uncertainty
    ``sigma`` the covariance is ``sigma^2 A A^T``, ``A = (J^T J)^-1 J^T D``: a type B
    evaluation, propagated by the law of propagation of uncertainty (JCGM 100:2008, the GUM,
    secs. 4.3 and 5.1). It does not shrink with more samples or more flights: a bias of the
    instrument is common to all of them. Near-planar bodies feel it most: their ``I3 - I2`` is
    small, so a per-mille error in a rate is a per-cent error in it.

    Parameters
    ----------
    J : ndarray or sparse matrix, shape (m, n)
    data : ndarray, shape (F, T, 3)
        The samples, rad/s.
    mask : ndarray of bool, shape (F, T, 3)
        The sample axes fitted (the rows of ``J``, in order).
    sigma : float
        Standard uncertainty of each axis's scale factor.
    """
    m, n = J.shape
    axis = np.broadcast_to(np.arange(3), mask.shape)[mask]
    values = data[mask]
    D = np.zeros((m, 3))
    D[np.arange(m), axis] = values
    JtJ = (J.T @ J).toarray() if sparse.issparse(J) else J.T @ J
    JtD = np.asarray(J.T @ D)
    d = np.sqrt(np.diag(JtJ))
    d = np.where(d > 0, d, 1.0)
    A = (np.linalg.pinv(JtJ / np.outer(d, d)) / np.outer(d, d)) @ JtD
    return sigma ** 2 * (A @ A.T)


def effective_dof(var_stat: float, var_total: float, dof_stat: float) -> float:
    """Welch-Satterthwaite's effective degrees of freedom of a standard uncertainty made of a
    statistical part with ``dof_stat`` degrees of freedom and a systematic part known exactly
    (infinitely many): ``nu = var_total^2 / (var_stat^2 / dof_stat)`` (JCGM 100:2008, G.4.1)."""
    if not (var_stat > 0 and dof_stat > 0):
        return np.inf
    return float(var_total ** 2 / (var_stat ** 2 / dof_stat))
