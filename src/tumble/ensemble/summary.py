"""The streaming statistics of a sweep's cases: folded over fixed blocks, whatever the chunks.

:class:`SweepSummary` folds the chunks that :func:`tumble.ensemble.sweep.run_chunks` yields into
running moments, counts of the categorical columns and a keyed sample for the quantiles
(:mod:`tumble.ensemble.statistics`), over blocks of :data:`STATS_BLOCK` cases aligned on the
case numbers, in order, so the statistics come out bit for bit the same for any chunking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Iterable, Iterator, Protocol

import numpy as np

from ..analysis.summary import SAMPLES_PER_FLIP
from . import _display
from .statistics import (
    Counts,
    KeyedSample,
    RunningMoments,
    case_keys,
    fraction_interval,
    success_lower_bound,
    success_statement,
)

__all__ = ["CATEGORICAL", "FLIP_CONFIDENCE", "QUANTILES", "SAMPLE_SIZE", "STATS_BLOCK", "SweepSummary", "base_name", "summarize"]

#: Cases per block of the statistics (fixed, so the chunking does not change them).
STATS_BLOCK = 4096
#: Cases kept for quantiles (:class:`~tumble.ensemble.statistics.KeyedSample`): exact up to
#: this many cases, then a rank error of at most 0.0136 with 95 % probability.
SAMPLE_SIZE = 10_000
#: Quantiles reported.
QUANTILES = (0.01, 0.05, 0.25, 0.5, 0.75, 0.95, 0.99)
#: Columns counted by value instead of averaged.
CATEGORICAL = ("axis", "predicted", "circulation")
#: Confidence of the interval on the fraction of cases that flip (``summary.json``'s ``"flipped"``).
FLIP_CONFIDENCE = 0.95
#: Columns left out of the statistics: the case number and the quaternion's components.
_NOT_SUMMARISED = ("case", "q_end_x", "q_end_y", "q_end_z", "q_end_w")


def base_name(column: str) -> str:
    """A column's name without its unit: ``"flip_period [s]"`` -> ``"flip_period"``.

    Examples
    --------
    >>> from tumble.ensemble.summary import base_name
    >>> base_name("flip_period [s]"), base_name("flips")
    ('flip_period', 'flips')
    """
    return column.split(" [", 1)[0]


class _Criterion(Protocol):
    """What the summary reads of a :class:`~tumble.ensemble.sweep.Criterion`: its column, bounds
    and confidence, and which cases pass.

    A protocol, not the class: :mod:`tumble.ensemble.sweep` imports this module (and re-exports
    its names), and the import graph has no circles.
    """

    @property
    def column(self) -> str: ...
    @property
    def minimum(self) -> float | None: ...
    @property
    def maximum(self) -> float | None: ...
    @property
    def confidence(self) -> float: ...
    def passed(self, columns: dict) -> np.ndarray: ...


def criterion_text(criterion: _Criterion) -> str:
    """What a success is: ``flips >= 1``, ``max_nutation <= 0.2``, ``1 <= flips <= 3``.

    Examples
    --------
    >>> from tumble.ensemble.sweep import Criterion
    >>> from tumble.ensemble.summary import criterion_text
    >>> criterion_text(Criterion("flips", minimum=1)), criterion_text(Criterion("flips", minimum=1, maximum=3))
    ('flips >= 1', '1 <= flips <= 3')
    >>> criterion_text(Criterion("max_nutation", maximum=0.2))
    'max_nutation <= 0.2'
    """
    lo, hi = criterion.minimum, criterion.maximum
    if lo is not None and hi is not None:
        return f"{lo:g} <= {criterion.column} <= {hi:g}"
    return f"{criterion.column} >= {lo:g}" if lo is not None else f"{criterion.column} <= {hi:g}"


def _blocks(chunks: Iterable[dict], size: int) -> Iterator[dict]:
    """The columns re-cut into blocks of ``size`` consecutive cases (the last one shorter)."""
    pending: list[dict] = []
    held = 0
    for columns in chunks:
        pending.append(columns)
        held += len(columns["case"])
        while held >= size:
            joined = {k: np.concatenate([c[k] for c in pending]) for k in pending[0]}
            yield {k: v[:size] for k, v in joined.items()}
            pending, held = [{k: v[size:] for k, v in joined.items()}], held - size
    if held:
        yield {k: np.concatenate([c[k] for c in pending]) for k in pending[0]}


@dataclass(frozen=True, eq=False)
class SweepSummary:
    """Streaming statistics of a sweep's cases (memory independent of their number).

    Attributes
    ----------
    columns : tuple of str
        The summarised numeric columns (with units).
    moments : RunningMoments
        Count, mean, variance, extremes per column.
    sample : KeyedSample
        A bounded sample of the cases by key, for quantiles and figures.
    counts : Counts
        Cases per value of the :data:`CATEGORICAL` columns.
    passed, failed : int
        Cases meeting the criterion and not (0 and 0 without one).
    redraws : int
        Body draws refused as unphysical and drawn again, in all.
    flipped : int
        Cases that flipped at least once (``flips >= 1``; 0 without a ``flips`` column).
    aliased : int
        Cases sampled fewer than :data:`~tumble.analysis.summary.SAMPLES_PER_FLIP` times a flip
        (``samples_per_flip``): their flips and flip period are not what the motion did.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.summary import SweepSummary
    >>> cols = {"case": np.arange(4), "axis": np.array([2, 2, 2, 3]), "predicted": np.array(["unstable"] * 3 + ["stable"]),
    ...         "circulation": np.array([1, 3, 3, 3]), "flips": np.array([2, 4, 6, 0]), "resampled": np.zeros(4, int)}
    >>> summary = SweepSummary.of(cols, seed=0)
    >>> summary.columns, summary.moments.mean.tolist(), summary.counts.as_dict()["predicted"]
    (('flips', 'resampled'), [3.0, 0.0], {'stable': 1, 'unstable': 3})
    """

    columns: tuple
    moments: RunningMoments
    sample: KeyedSample
    counts: Counts
    passed: int = 0
    failed: int = 0
    redraws: int = 0
    flipped: int = 0
    aliased: int = 0

    def __repr__(self) -> str:
        return _display.sweep_repr(self)

    def _repr_html_(self) -> str:
        return _display.sweep_html(self)

    @classmethod
    def of(cls, columns: dict, seed: int, criterion: _Criterion | None = None,
           sample_size: int = SAMPLE_SIZE) -> SweepSummary:
        """The summary of one block of cases.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.summary import SweepSummary
        >>> cols = {"case": np.arange(3), "axis": np.array([2, 2, 2]), "predicted": np.array(["unstable"] * 3),
        ...         "circulation": np.array([1, 3, 3]), "flips": np.array([2, 4, 0]), "resampled": np.array([0, 1, 0])}
        >>> from tumble.ensemble.sweep import Criterion
        >>> summary = SweepSummary.of(cols, seed=0, criterion=Criterion("flips", minimum=1))
        >>> summary.passed, summary.failed, summary.redraws, summary.flipped
        (2, 1, 1, 2)
        """
        names = tuple(k for k in columns if base_name(k) not in (*CATEGORICAL, *_NOT_SUMMARISED))
        table = np.column_stack([np.asarray(columns[k], dtype=float) for k in names])
        ok = criterion.passed(columns) if criterion is not None else np.zeros(0, bool)
        return cls(names, RunningMoments.of(table), KeyedSample.of(case_keys(seed, columns["case"]), table, sample_size),
                   Counts.of({k: columns[k] for k in CATEGORICAL}), int(ok.sum()), int((~ok).sum()),
                   int(np.sum(columns["resampled"])), int(np.sum(columns["flips"] >= 1)) if "flips" in columns else 0,
                   int(np.sum(np.asarray(columns.get("samples_per_flip", ()), float) < SAMPLES_PER_FLIP)))

    def merge(self, other: SweepSummary) -> SweepSummary:
        """Both together (same columns).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.summary import SweepSummary
        >>> def block(start, flips):
        ...     n = len(flips)
        ...     return {"case": np.arange(start, start + n), "axis": np.full(n, 2), "predicted": np.array(["unstable"] * n),
        ...             "circulation": np.full(n, 3), "flips": np.array(flips), "resampled": np.zeros(n, int)}
        >>> both = SweepSummary.of(block(0, [1, 2]), seed=5).merge(SweepSummary.of(block(2, [3, 6]), seed=5))
        >>> both.cases, both.moments.mean.tolist()[0], bool(np.array_equal(both.sample.values, SweepSummary.of(block(0, [1, 2, 3, 6]), 5).sample.values))
        (4, 3.0, True)
        """
        if self.columns != other.columns:
            raise ValueError("summaries of different columns cannot be merged")
        return SweepSummary(self.columns, self.moments.merge(other.moments), self.sample.merge(other.sample),
                            self.counts.merge(other.counts), self.passed + other.passed,
                            self.failed + other.failed, self.redraws + other.redraws, self.flipped + other.flipped,
                            self.aliased + other.aliased)

    @property
    def cases(self) -> int:
        """Cases summarised.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.summary import SweepSummary
        >>> cols = {"case": np.arange(3), "axis": np.array([1, 2, 3]), "predicted": np.array(["stable", "unstable", "stable"]),
        ...         "circulation": np.array([1, 3, 3]), "flips": np.zeros(3), "resampled": np.zeros(3, int)}
        >>> SweepSummary.of(cols, seed=0).cases
        3
        """
        return int(sum(c for _, c in dict(self.counts.table)["axis"]))

    def sample_columns(self) -> dict[str, np.ndarray]:
        """The sample as columns (name -> values), for figures.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.summary import SweepSummary
        >>> cols = {"case": np.arange(3), "axis": np.full(3, 2), "predicted": np.array(["unstable"] * 3),
        ...         "circulation": np.full(3, 3), "flip_period [s]": np.array([20.0, 21.0, 22.0]), "resampled": np.zeros(3, int)}
        >>> sample = SweepSummary.of(cols, seed=0).sample_columns()
        >>> list(sample), sorted(sample["flip_period [s]"].tolist())  # every case, when fewer than the sample's size
        (['flip_period [s]', 'resampled'], [20.0, 21.0, 22.0])
        """
        return {k: self.sample.values[:, j] for j, k in enumerate(self.columns)}

    def as_dict(self, criterion: _Criterion | None = None) -> dict:
        """JSON-ready: ``cases``, ``redraws``, ``statistics`` (per column without its unit:
        ``unit``, ``count``, ``mean``, ``std``, ``min``, ``max``, ``quantiles`` {q: value},
        ``quantile_rank_error``: 0 when exact, else the 95 % bound), ``counts``, with a ``flips``
        column ``flipped`` (``cases`` that flipped at least once, their ``fraction``, its
        Clopper-Pearson ``interval`` at ``confidence`` :data:`FLIP_CONFIDENCE`, and a
        ``statement``; a flip as docs/conventions.md defines it) and, with a criterion,
        ``criterion`` (``column``, ``min``, ``max``, ``passed``, ``failed``, ``confidence``,
        ``success_lower_bound``, ``statement``).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.summary import SweepSummary
        >>> cols = {"case": np.arange(4), "axis": np.full(4, 2), "predicted": np.array(["unstable"] * 4),
        ...         "circulation": np.full(4, 3), "flip_period [s]": np.array([20.0, 21.0, 22.0, 23.0]),
        ...         "resampled": np.zeros(4, int)}
        >>> from tumble.ensemble.sweep import Criterion
        >>> criterion = Criterion("flip_period", maximum=22.5)
        >>> out = SweepSummary.of(cols, seed=0, criterion=criterion).as_dict(criterion)
        >>> stats = out["statistics"]["flip_period"]
        >>> stats["unit"], stats["mean"], stats["quantiles"]["0.5"], stats["quantile_rank_error"]
        ('s', 21.5, 21.5, 0.0)
        >>> out["criterion"]["passed"], out["criterion"]["failed"]
        (3, 1)
        >>> cols["flips"] = np.array([2, 0, 0, 0])   # one case of four flipped
        >>> flipped = SweepSummary.of(cols, seed=0).as_dict()["flipped"]
        >>> flipped["cases"], flipped["fraction"], [round(x, 4) for x in flipped["interval"]]
        (1, 0.25, [0.0063, 0.8059])
        >>> flipped["statement"]
        '1 of 4 cases flipped (25 %; 0.6309 % to 80.59 % at 95 % confidence, Clopper-Pearson)'
        """
        m, q, error = self.moments, self.sample.quantiles(QUANTILES), self.sample.rank_error(0.05)

        def num(x):
            x = float(x)
            return x if math.isfinite(x) else None

        stats = {}
        for j, name in enumerate(self.columns):
            unit = name[len(base_name(name)) + 2:-1] if " [" in name else ""
            stats[base_name(name)] = {
                "unit": unit, "count": int(m.count[j]), "mean": num(m.mean[j]), "std": num(m.std[j]),
                "min": num(m.minimum[j]), "max": num(m.maximum[j]),
                "quantiles": {f"{p:g}": num(q[i, j]) for i, p in enumerate(QUANTILES)},
                "quantile_rank_error": num(error[j]),
            }
        out = {"cases": self.cases, "redraws": self.redraws, "statistics": stats, "counts": self.counts.as_dict()}
        if "flips" in self.columns:
            n, k = self.cases, self.flipped
            low, high = fraction_interval(n, k, FLIP_CONFIDENCE)
            out["flipped"] = {
                "cases": k, "fraction": k / n, "confidence": FLIP_CONFIDENCE, "interval": [low, high],
                "aliased": self.aliased,
                "statement": (f"{k} of {n} cases flipped ({100 * k / n:.4g} %; {100 * low:.4g} % to {100 * high:.4g} % "
                              f"at {100 * FLIP_CONFIDENCE:.4g} % confidence, Clopper-Pearson)" + (
                                  f"; but {self.aliased} of the {n} cases were sampled fewer than {SAMPLES_PER_FLIP:g} "
                                  f"times a flip: their flips may be miscounted, give more samples" if self.aliased else "")),
            }
        if criterion is not None:
            n = self.passed + self.failed
            out["criterion"] = {
                "column": criterion.column, "min": criterion.minimum, "max": criterion.maximum,
                "passed": self.passed, "failed": self.failed, "confidence": criterion.confidence,
                "success_lower_bound": success_lower_bound(n, self.failed, criterion.confidence),
                "statement": success_statement(n, self.failed, criterion.confidence, criterion_text(criterion)),
            }
        return out


def summarize(chunks: Iterable[dict], seed: int, criterion: _Criterion | None = None, *,
              sample_size: int = SAMPLE_SIZE,
              on_chunk: Callable[[dict[str, np.ndarray]], object] | None = None) -> SweepSummary:
    """Fold chunks (in case order) into a :class:`SweepSummary`, block by block.

    ``on_chunk(columns)``, if given, sees every chunk as it passes (to write it to a file).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.summary import summarize
    >>> chunks = [{"case": np.arange(k, k + 2), "axis": np.full(2, 2), "predicted": np.array(["unstable"] * 2),
    ...            "circulation": np.full(2, 3), "flips": np.array([k, k + 1]), "resampled": np.zeros(2, int)}
    ...           for k in (0, 2, 4)]
    >>> seen = []
    >>> summary = summarize(chunks, seed=1, on_chunk=lambda c: seen.append(len(c["case"])))
    >>> summary.cases, float(summary.moments.mean[0]), seen  # flips 0 .. 5
    (6, 2.5, [2, 2, 2])
    """
    def watched():
        for columns in chunks:
            if on_chunk is not None:
                on_chunk(columns)
            yield columns

    total = None
    for block in _blocks(watched(), STATS_BLOCK):
        part = SweepSummary.of(block, seed, criterion, sample_size)
        total = part if total is None else total.merge(part)
    if total is None:
        raise ValueError("a sweep needs at least one case")
    return total
