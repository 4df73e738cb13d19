"""Streaming statistics of many cases, in memory independent of the number of cases.

Every summary here is a frozen value built from one block of cases (``of``) and combined with
another (``merge``); a sweep folds its chunks into one summary in any order and grouping.

- :class:`RunningMoments`: count, mean, variance, min and max per column. A block's mean and
  sum of squared deviations are taken in two passes, and blocks are combined by the pairwise
  formulae of Chan, Golub & LeVeque ("Algorithms for computing the sample variance: analysis
  and recommendations", Am. Stat. 37 (1983) 242, eqs. 1.5): with ``d = mean_b - mean_a``,
  ``n = n_a + n_b``, ``mean = mean_a + d n_b / n`` and ``M2 = M2_a + M2_b + d^2 n_a n_b / n``,
  Welford's update (Technometrics 4 (1962) 419) for blocks. Merging in any order gives the
  same result to round-off (a few ulps of the mean, relative 1e-15 or so of the variance).
- :class:`KeyedSample`: a bounded uniform random sample of the cases for quantiles, chosen
  *by key*: each case gets a pseudo-random 64-bit key from ``(seed, index)`` (SplitMix64's
  finaliser, Steele, Lea & Flood, OOPSLA 2014), and the sample is the ``size`` cases with the
  smallest keys ("bottom-k" sampling). The sample is thus a function of the set of cases alone:
  merging in any order or grouping gives it *exactly*, bit for bit. With ``n <= size`` cases
  it holds them all and the quantiles are exact. Otherwise it is a simple random sample of
  ``m = size`` cases drawn without replacement, and the rank of each quantile estimate is off
  by at most ``eps = sqrt(ln(2 / alpha) / (2 m))`` with probability ``1 - alpha``
  (Hoeffding's inequality, which holds for sampling without replacement too: Hoeffding,
  J. Am. Stat. Assoc. 58 (1963) 13, sec. 6): ``m = 10,000``, ``alpha = 0.05`` give
  ``eps = 0.0136``, so the estimated median lies between the true 48.6 % and 51.4 % points
  (:meth:`KeyedSample.rank_error`).
- :class:`Counts`: how often each value of a categorical column occurs (sums, exact).

What the counts of a sweep allow one to say (the confidence statements on a fraction of
successes) is in :mod:`tumble.ensemble.confidence`; its names are re-exported here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..typing import ArrayLike
from .confidence import fraction_interval, runs_needed, success_lower_bound, success_statement

__all__ = [
    "Counts",
    "KeyedSample",
    "RunningMoments",
    "case_keys",
    "fraction_interval",
    "runs_needed",
    "success_lower_bound",
    "success_statement",
]

_MASK = (1 << 64) - 1


def _splitmix(x: np.ndarray) -> np.ndarray:
    """SplitMix64's finaliser on uint64 (a bijection; Steele, Lea & Flood 2014, fig. 3)."""
    with np.errstate(over="ignore"):
        x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        return x ^ (x >> np.uint64(31))


def case_keys(seed: int, index: ArrayLike) -> np.ndarray:
    """Pseudo-random 64-bit keys of cases: SplitMix64 of ``seed_mix + index * golden``.

    Distinct indices get distinct keys (the finaliser is a bijection and ``index * golden`` is
    one modulo 2^64 for an odd constant), so the order of a sample by key has no ties.

    Parameters
    ----------
    seed : int
        The sweep's seed (any non-negative integer).
    index : array_like of int, shape (n,)
        Case indices, >= 0.

    Returns
    -------
    ndarray of uint64, shape (n,)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.statistics import case_keys
    >>> keys = case_keys(7, np.arange(1000))
    >>> keys.dtype, len(np.unique(keys))  # distinct indices, distinct keys
    (dtype('uint64'), 1000)
    >>> bool(np.all(case_keys(7, [3, 5]) == keys[[3, 5]]))  # a key depends on (seed, index) alone
    True
    """
    mixed = int(_splitmix(np.array([seed & _MASK], dtype=np.uint64))[0])
    idx = np.asarray(index, dtype=np.uint64)
    with np.errstate(over="ignore"):
        return _splitmix(np.uint64(mixed) + idx * np.uint64(0x9E3779B97F4A7C15))


def _as_table(values) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.ndim != 2:
        raise ValueError(f"values has shape {a.shape}; it must be (cases, columns)")
    return a


@dataclass(frozen=True, eq=False)
class RunningMoments:
    """Count, mean, sum of squared deviations, min and max of each column, NaN ignored.

    Attributes
    ----------
    count : ndarray of int, shape (k,)
        Finite values seen per column.
    mean : ndarray, shape (k,)
        Their mean (NaN for a column with none).
    m2 : ndarray, shape (k,)
        Sum of squared deviations from the mean.
    minimum, maximum : ndarray, shape (k,)
        Extremes (NaN for a column with none).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.statistics import RunningMoments
    >>> m = RunningMoments.of([[1.0, 10.0], [2.0, np.nan], [3.0, 30.0]])
    >>> m.count.tolist(), m.mean.tolist(), m.maximum.tolist()  # NaN ignored
    ([3, 2], [2.0, 20.0], [3.0, 30.0])
    """

    count: np.ndarray
    mean: np.ndarray
    m2: np.ndarray
    minimum: np.ndarray
    maximum: np.ndarray

    @classmethod
    def of(cls, values: ArrayLike) -> RunningMoments:
        """The moments of one block, ``values`` of shape (cases, columns); two passes.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import RunningMoments
        >>> m = RunningMoments.of(np.array([[1.0], [2.0], [4.0]]))
        >>> bool(np.isclose(m.mean[0], 7 / 3)), bool(np.isclose(m.m2[0], 42 / 9)), float(m.minimum[0])
        (True, True, 1.0)
        """
        a = _as_table(values)
        finite = np.isfinite(a)
        count = finite.sum(axis=0)
        x = np.where(finite, a, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            mean = np.where(count > 0, x.sum(axis=0) / count, np.nan)
        dev = np.where(finite, a - mean, 0.0)
        m2 = np.sum(dev * dev, axis=0)
        some = count > 0
        lo = np.where(some, np.min(np.where(finite, a, np.inf), axis=0, initial=np.inf), np.nan)
        hi = np.where(some, np.max(np.where(finite, a, -np.inf), axis=0, initial=-np.inf), np.nan)
        return cls(count.astype(np.int64), mean, m2, lo, hi)

    def merge(self, other: RunningMoments) -> RunningMoments:
        """The moments of both blocks together (Chan, Golub & LeVeque 1983).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import RunningMoments
        >>> x = np.random.default_rng(0).normal(5.0, 2.0, size=(1000, 2))
        >>> merged = RunningMoments.of(x[:300]).merge(RunningMoments.of(x[300:]))
        >>> bool(np.allclose(merged.mean, x.mean(axis=0), rtol=1e-14, atol=0)), merged.count.tolist()
        (True, [1000, 1000])
        >>> bool(np.allclose(merged.variance, x.var(axis=0, ddof=1), rtol=1e-13, atol=0))
        True
        """
        na, nb = self.count, other.count
        n = na + nb
        with np.errstate(invalid="ignore", divide="ignore"):
            d = np.where(nb > 0, other.mean, 0.0) - np.where(na > 0, self.mean, 0.0)
            frac = np.where(n > 0, nb / np.maximum(n, 1), 0.0)
            mean = np.where(na == 0, other.mean, np.where(nb == 0, self.mean, self.mean + d * frac))
            m2 = self.m2 + other.m2 + np.where((na > 0) & (nb > 0), d * d * na * frac, 0.0)
        return RunningMoments(n, mean, m2, np.fmin(self.minimum, other.minimum), np.fmax(self.maximum, other.maximum))

    @property
    def variance(self) -> np.ndarray:
        """Sample variance (``M2 / (n - 1)``), NaN with fewer than two values; shape (k,).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import RunningMoments
        >>> RunningMoments.of([[1.0, 5.0], [3.0, np.nan]]).variance.tolist()  # one value: no variance
        [2.0, nan]
        """
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(self.count > 1, self.m2 / np.maximum(self.count - 1, 1), np.nan)

    @property
    def std(self) -> np.ndarray:
        """Sample standard deviation, shape (k,).

        Examples
        --------
        >>> from tumble.ensemble.statistics import RunningMoments
        >>> RunningMoments.of([[2.0], [4.0], [4.0], [4.0], [5.0], [5.0], [7.0], [9.0]]).std.round(4).tolist()  # sqrt(32 / 7)
        [2.1381]
        """
        return np.sqrt(self.variance)


@dataclass(frozen=True, eq=False)
class KeyedSample:
    """The ``size`` cases with the smallest keys (see the module docstring), for quantiles.

    Attributes
    ----------
    size : int
        Capacity.
    keys : ndarray of uint64, shape (m,)
        Keys held, ascending, ``m <= size``.
    values : ndarray, shape (m, k)
        The cases' values, in the order of ``keys``.
    seen : int
        Cases offered to the sample in all (``m = min(seen, size)``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.statistics import KeyedSample, case_keys
    >>> sample = KeyedSample.of(case_keys(1, np.arange(50)), np.arange(50.0)[:, None], size=20)
    >>> sample.values.shape, sample.seen, sample.exact
    ((20, 1), 50, False)
    """

    size: int
    keys: np.ndarray
    values: np.ndarray
    seen: int

    @classmethod
    def of(cls, keys: ArrayLike, values: ArrayLike, size: int) -> KeyedSample:
        """The sample of one block: ``keys`` (uint64, distinct) and ``values`` (cases, columns).

        Examples
        --------
        >>> from tumble.ensemble.statistics import KeyedSample
        >>> KeyedSample.of([30, 10, 20], [[3.0], [1.0], [2.0]], size=2).values.ravel().tolist()  # smallest keys
        [1.0, 2.0]
        """
        if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 1:
            raise ValueError(f"size = {size!r} must be a whole number >= 1 (cases kept for quantiles)")
        keys = np.asarray(keys, dtype=np.uint64)
        a = _as_table(values)
        order = np.argsort(keys, kind="stable")[:size]
        return cls(int(size), keys[order], a[order], len(keys))

    def merge(self, other: KeyedSample) -> KeyedSample:
        """The sample of both blocks: the same whatever the order or grouping, bit for bit.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import KeyedSample, case_keys
        >>> keys, values = case_keys(3, np.arange(100)), np.arange(100.0)[:, None]
        >>> a, b = KeyedSample.of(keys[:40], values[:40], 25), KeyedSample.of(keys[40:], values[40:], 25)
        >>> bool(np.array_equal(a.merge(b).values, b.merge(a).values)), a.merge(b).seen
        (True, 100)
        >>> bool(np.array_equal(a.merge(b).values, KeyedSample.of(keys, values, 25).values))
        True
        """
        both = KeyedSample.of(np.concatenate([self.keys, other.keys]),
                              np.concatenate([self.values, other.values]), min(self.size, other.size))
        return KeyedSample(both.size, both.keys, both.values, self.seen + other.seen)

    def quantiles(self, q: ArrayLike) -> np.ndarray:
        """Quantiles ``q`` (in [0, 1]) of each column over its finite values, linear
        interpolation between order statistics (numpy's default); NaN for an empty column.

        Returns
        -------
        ndarray, shape (len(q), k)

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import KeyedSample
        >>> sample = KeyedSample.of(np.arange(5), [[1.0], [2.0], [3.0], [4.0], [5.0]], size=10)
        >>> sample.quantiles([0.0, 0.5, 1.0]).ravel().tolist()  # all cases held: exact
        [1.0, 3.0, 5.0]
        """
        q = np.atleast_1d(np.asarray(q, dtype=float))
        out = np.full((len(q), self.values.shape[1]), np.nan)
        for j in range(self.values.shape[1]):
            column = self.values[:, j]
            column = column[np.isfinite(column)]
            if column.size:
                out[:, j] = np.quantile(column, q)
        return out

    def rank_error(self, alpha: float = 0.05) -> np.ndarray:
        """Bound on the rank error of each column's quantiles, with probability ``1 - alpha``.

        0 where the sample holds every case (:attr:`exact`); else ``sqrt(ln(2 / alpha) / (2 m))``
        with ``m`` the finite values in the sample (Hoeffding 1963); NaN for an empty column.
        Shape (k,).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import KeyedSample, case_keys
        >>> n = 20_000
        >>> sample = KeyedSample.of(case_keys(0, np.arange(n)), np.zeros((n, 1)), size=10_000)
        >>> sample.rank_error(0.05).round(4).tolist()  # the median lies within the 48.6 % .. 51.4 % points
        [0.0136]
        """
        m = np.isfinite(self.values).sum(axis=0)
        with np.errstate(divide="ignore"):
            eps = np.sqrt(math.log(2.0 / alpha) / (2.0 * m)) if not self.exact else np.zeros(len(m))
        return np.where(m > 0, eps, np.nan)

    @property
    def exact(self) -> bool:
        """Whether the sample holds every case offered (then its quantiles are exact).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import KeyedSample
        >>> KeyedSample.of(np.arange(3), np.zeros((3, 1)), size=3).exact
        True
        >>> KeyedSample.of(np.arange(4), np.zeros((4, 1)), size=3).exact
        False
        """
        return self.seen <= self.size


@dataclass(frozen=True, eq=False)
class Counts:
    """How often each value occurs in categorical columns.

    Attributes
    ----------
    table : tuple of (str, tuple of (value, int))
        Per column, its values (sorted) and their counts.

    Examples
    --------
    >>> from tumble.ensemble.statistics import Counts
    >>> Counts.of({"outcome": ["flip", "stable", "flip"]}).table
    (('outcome', (('flip', 2), ('stable', 1))),)
    """

    table: tuple

    @classmethod
    def of(cls, columns: dict) -> Counts:
        """Counts of each column of ``columns`` (name -> array of ints or strings).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.statistics import Counts
        >>> Counts.of({"axis": np.array([3, 1, 3, 3])}).as_dict()
        {'axis': {'1': 1, '3': 3}}
        """
        rows = []
        for name, values in columns.items():
            found, counts = np.unique(np.asarray(values), return_counts=True)
            rows.append((name, tuple((v.item(), int(c)) for v, c in zip(found, counts))))
        return cls(tuple(rows))

    def merge(self, other: Counts) -> Counts:
        """Sums of both (columns matched by name).

        Examples
        --------
        >>> from tumble.ensemble.statistics import Counts
        >>> a = Counts.of({"axis": [1, 3]})
        >>> a.merge(Counts.of({"axis": [3, 2]})).as_dict()
        {'axis': {'1': 1, '2': 1, '3': 2}}
        """
        mine, theirs = dict(self.table), dict(other.table)
        rows = []
        for name in dict.fromkeys([*mine, *theirs]):
            total: dict = {}
            for value, count in (*mine.get(name, ()), *theirs.get(name, ())):
                total[value] = total.get(value, 0) + count
            rows.append((name, tuple(sorted(total.items()))))
        return Counts(tuple(rows))

    def as_dict(self) -> dict:
        """``{column: {str(value): count}}`` (JSON-ready).

        Examples
        --------
        >>> import json
        >>> from tumble.ensemble.statistics import Counts
        >>> json.dumps(Counts.of({"ok": [True, True, False]}).as_dict())
        '{"ok": {"False": 1, "True": 2}}'
        """
        return {name: {str(v): c for v, c in values} for name, values in self.table}
