"""What a Monte Carlo's counts allow one to say: confidence statements on a fraction of successes.

- :func:`success_lower_bound`: the order-statistics (Clopper-Pearson) confidence statement on
  a fraction of successes; :func:`runs_needed` its inverse (Hanson & Beard, "Applying Monte
  Carlo simulation to launch vehicle design and requirements verification", NASA/TP-2010-216447,
  sec. 4); :func:`fraction_interval` the two-sided interval on a fraction (what fraction of a
  sweep's cases flip); :func:`success_statement` the sentence a report prints.

Pure functions of whole numbers (scipy's beta distribution, imported when called).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["fraction_interval", "runs_needed", "success_lower_bound", "success_statement"]


def _check_confidence(confidence) -> float:
    if isinstance(confidence, bool) or not isinstance(confidence, (int, float, np.floating)) \
            or not 0.0 < float(confidence) < 1.0:
        raise ValueError(f"confidence = {confidence!r} must be a number strictly between 0 and 1")
    return float(confidence)


def _check_count(name: str, value, low: int = 0) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} = {value!r} must be a whole number >= {low}")
    return int(value)


def _check_counts(part: str, k, n) -> tuple[int, int]:
    """``n`` runs (``cases``, >= 1) and ``k`` of them with a property (named ``part``), ``k <= n``."""
    n = _check_count("cases", n, 1)
    k = _check_count(part, k)
    if k > n:
        raise ValueError(f"{part} = {k} must be at most cases = {n}")
    return k, n


def success_lower_bound(cases: int, failures: int, confidence: float) -> float:
    """Lower confidence bound on the probability of success from ``cases`` independent runs.

    The one-sided Clopper-Pearson bound (Clopper & Pearson, Biometrika 26 (1934) 404): the
    smallest ``p`` for which ``cases - failures`` or more successes are at least ``1 -
    confidence`` probable, ``p = B^-1(1 - confidence; n - k, k + 1)`` with ``B^-1`` the inverse
    of the beta distribution's CDF (``scipy.stats.beta.ppf``). With no failure it is
    ``(1 - confidence)^(1 / n)``, the order-statistics statement of Hanson & Beard
    (NASA/TP-2010-216447, sec. 4): 852 runs without failure show 99.73 % success at 90 %
    confidence, 2,995 runs show 99.9 % at 95 %.

    Parameters
    ----------
    cases : int
        Number of runs n, >= 1.
    failures : int
        Number of failures k, ``0 <= k <= n``.
    confidence : float
        Confidence level, in (0, 1), e.g. 0.9.

    Returns
    -------
    float
        The bound, in [0, 1) (0 when every run failed).

    Raises
    ------
    ValueError
        For counts that are not whole numbers in range or a confidence outside (0, 1).

    Examples
    --------
    >>> from tumble.ensemble.confidence import success_lower_bound
    >>> round(success_lower_bound(852, 0, 0.9), 4)  # Hanson & Beard: 99.73 % at 90 %
    0.9973
    >>> p = success_lower_bound(100, 2, 0.95)
    >>> round(p, 4)
    0.9384
    >>> from scipy.stats import binom
    >>> round(float(binom.sf(97, 100, p)), 9)  # at the bound, P(98 or more successes) = 1 - 0.95
    0.05
    """
    k, n = _check_counts("failures", failures, cases)
    c = _check_confidence(confidence)
    if k == n:
        return 0.0
    if k == 0:
        return (1.0 - c) ** (1.0 / n)
    from scipy.stats import beta

    return float(beta.ppf(1.0 - c, n - k, k + 1))


def fraction_interval(cases: int, hits: int, confidence: float = 0.95) -> tuple[float, float]:
    """Two-sided confidence interval on a probability from ``hits`` in ``cases`` independent runs.

    The exact (Clopper-Pearson) interval (Clopper & Pearson, Biometrika 26 (1934) 404): each end
    leaves ``(1 - confidence) / 2`` on its side, ``B^-1((1 - c) / 2; k, n - k + 1)`` to
    ``B^-1((1 + c) / 2; k + 1, n - k)`` (``scipy.stats.beta.ppf``), 0 for ``k = 0`` and 1 for
    ``k = n``. It covers the true probability at least ``confidence`` of the time.

    Parameters
    ----------
    cases : int
        Number of runs n, >= 1.
    hits : int
        Number of runs with the property, ``0 <= k <= n``.
    confidence : float, default 0.95
        Confidence level, in (0, 1).

    Returns
    -------
    (float, float)
        The lower and upper ends, in [0, 1].

    Raises
    ------
    ValueError
        For counts that are not whole numbers in range or a confidence outside (0, 1).

    Examples
    --------
    >>> from tumble.ensemble.confidence import fraction_interval
    >>> [round(x, 4) for x in fraction_interval(100, 30)]   # 30 of 100: 21.2 % to 39.9 % at 95 %
    [0.2124, 0.3998]
    >>> fraction_interval(10, 0)[0], round(fraction_interval(10, 0)[1], 4)   # none of 10: up to 30.8 %
    (0.0, 0.3085)
    """
    k, n = _check_counts("hits", hits, cases)
    c = _check_confidence(confidence)
    from scipy.stats import beta

    low = 0.0 if k == 0 else float(beta.ppf((1.0 - c) / 2, k, n - k + 1))
    high = 1.0 if k == n else float(beta.ppf((1.0 + c) / 2, k + 1, n - k))
    return low, high


def runs_needed(success: float, confidence: float, failures: int = 0) -> int:
    """Fewest runs whose :func:`success_lower_bound` with ``failures`` failures reaches ``success``.

    With no failure ``n = ceil(ln(1 - confidence) / ln(success))`` (Hanson & Beard,
    NASA/TP-2010-216447, sec. 4): 852 runs for 99.73 % at 90 %, 2,995 for 99.9 % at 95 %.

    Raises
    ------
    ValueError
        For ``success`` outside (0, 1), a confidence outside (0, 1) or a bad count.

    Examples
    --------
    >>> from tumble.ensemble.confidence import runs_needed, success_lower_bound
    >>> runs_needed(0.999, 0.95), runs_needed(0.9973, 0.9)
    (2995, 852)
    >>> n = runs_needed(0.99, 0.9, failures=1)
    >>> success_lower_bound(n, 1, 0.9) >= 0.99 > success_lower_bound(n - 1, 1, 0.9)
    True
    """
    if isinstance(success, bool) or not isinstance(success, (int, float, np.floating)) or not 0.0 < success < 1.0:
        raise ValueError(f"success = {success!r} must be a number strictly between 0 and 1")
    c = _check_confidence(confidence)
    k = _check_count("failures", failures)
    n = max(k + 1, math.ceil(math.log(1.0 - c) / math.log(success)))
    while success_lower_bound(n, k, c) < success:  # k > 0: the bound rises with n; a short search
        n = max(n + 1, int(n * 1.01))
    lo = max(k + 1, math.ceil(math.log(1.0 - c) / math.log(success)))
    while lo < n:  # bisect down to the fewest
        mid = (lo + n) // 2
        if success_lower_bound(mid, k, c) >= success:
            n = mid
        else:
            lo = mid + 1
    return n


def success_statement(cases: int, failures: int, confidence: float, criterion: str | None = None) -> str:
    """One line: ``"852 cases, 0 failures: success probability >= 99.73 % at 90 % confidence"``.

    ``criterion``, when given, says what a success is (``"flips >= 1"``), so that the failures
    are not a bare count.

    Examples
    --------
    >>> from tumble.ensemble.confidence import success_statement
    >>> success_statement(852, 0, 0.9)
    '852 cases, 0 failures: success probability >= 99.73 % at 90 % confidence (Clopper-Pearson; Hanson & Beard, NASA/TP-2010-216447)'
    >>> success_statement(1000, 319, 0.9, "flips >= 1")[:60]
    '1000 cases, 319 failures of the criterion flips >= 1: succes'
    """
    bound = success_lower_bound(cases, failures, confidence)
    of = f" of the criterion {criterion}" if criterion else ""
    return (f"{cases} cases, {failures} failure{'s' if failures != 1 else ''}{of}: success probability >= "
            f"{100 * bound:.4g} % at {100 * confidence:.4g} % confidence (Clopper-Pearson; Hanson & Beard, "
            f"NASA/TP-2010-216447)")
