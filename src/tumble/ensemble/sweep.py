"""Running a sweep: chunks of cases, computed anywhere, resumed, summarised as they stream.

A sweep (:class:`Sweep`) is an :class:`~tumble.ensemble.cases.Ensemble` of cases, how to run
each (:class:`RunSettings`) and optionally a :class:`Criterion` of success. :func:`run_chunks`
splits the cases into chunks of ``chunk`` cases, takes each finished chunk from a store
(resume), computes the others with a backend (:mod:`tumble.ensemble.backends`), saves each to
the store as it finishes, and yields the chunks *in order*. :class:`SweepSummary` folds them
into streaming statistics (:mod:`tumble.ensemble.statistics`).

Results do not depend on the chunking. Each case's inputs come from its own random numbers
(:mod:`tumble.ensemble.sampling`), and the motions of a batch are computed body by body, so a
case's row is the same in any chunk (with a fixed-step method the step must then be given:
:func:`tumble.dynamics.simulate_batch`'s default follows the fastest body *of the batch*).
The statistics are folded over blocks of :data:`STATS_BLOCK` cases aligned on the case
numbers, in order, whatever the chunks, so they too come out bit for bit the same.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Iterable, Iterator, Protocol

import numpy as np

from ..dynamics import simulate_batch
from ..dynamics.batch import BatchTrajectory
from ..dynamics.methods.integrators import get_method
from ..dynamics.models.torques import as_torque
from .backends import InProcess
from .cases import Ensemble
from .reductions import reduce_cases
from .statistics import Counts, KeyedSample, RunningMoments, case_keys, success_lower_bound, success_statement

if TYPE_CHECKING:
    from .backends import DaskBackend
    from .cases import CaseInputs

__all__ = [
    "CATEGORICAL",
    "DEFAULT_CHUNK",
    "QUANTILES",
    "SAMPLE_SIZE",
    "STATS_BLOCK",
    "ChunkStore",
    "Criterion",
    "RunSettings",
    "Sweep",
    "SweepSummary",
    "base_name",
    "chunk_ranges",
    "compute_chunk",
    "run_chunks",
    "summarize",
]

#: Cases per chunk unless told: ~30 MB of samples at 500 samples per case.
DEFAULT_CHUNK = 1024
#: Cases per block of the statistics (fixed, so the chunking does not change them).
STATS_BLOCK = 4096
#: Cases kept for quantiles (:class:`~tumble.ensemble.statistics.KeyedSample`): exact up to
#: this many cases, then a rank error of at most 0.0136 with 95 % probability.
SAMPLE_SIZE = 10_000
#: Quantiles reported.
QUANTILES = (0.01, 0.05, 0.25, 0.5, 0.75, 0.95, 0.99)
#: Columns counted by value instead of averaged.
CATEGORICAL = ("axis", "predicted", "circulation")
#: Columns left out of the statistics: the case number and the quaternion's components.
_NOT_SUMMARISED = ("case", "q_end_x", "q_end_y", "q_end_z", "q_end_w")


def base_name(column: str) -> str:
    """A column's name without its unit: ``"flip_period [s]"`` -> ``"flip_period"``.

    Examples
    --------
    >>> base_name("flip_period [s]"), base_name("flips")
    ('flip_period', 'flips')
    """
    return column.split(" [", 1)[0]


@dataclass(frozen=True)
class RunSettings:
    """How each case is run: :func:`tumble.dynamics.simulate_batch`'s arguments.

    Parameters
    ----------
    t_end : float, optional
        Duration, s (or ``times``).
    samples : int, optional
        Samples with ``t_end`` (default 500): a few per flip, to count flips and measure
        their period. ``samples = 2`` asks only for the final state: the exact method is then
        evaluated at ``t_end`` alone (the t = 0 sample is the case's initial state, as the
        method returns it), which makes the run of a torque-free sweep of final states and exact
        flip intervals (``flip_period_exact``) about a fifth faster (measured: 0.44 s against
        0.55 s for 100,000 cases); ``flips``, ``flip_period`` and
        ``max_nutation`` then see only t = 0 and ``t_end`` (``flip_period`` is NaN).
    times : sequence of float, optional
        The sample times, s, instead of ``t_end``.
    method : str, optional
        Default ``"exact"`` without a torque, ``"dop853"`` with one.
    torque : torque model, optional
        :class:`tumble.ConstantTorque`, :class:`tumble.GravityGradient` or any
        ``tau(t, omega, attitude)``.
    step : float, optional
        Step of the fixed-step methods, s, positive and finite: needed with them (see the
        module docstring).

    Raises
    ------
    ValueError
        For an unknown method, a torque the method cannot take, a fixed-step method without
        ``step``, or a ``step`` that is not a positive finite number.

    Examples
    --------
    >>> import tumble
    >>> RunSettings(t_end=10.0).method, RunSettings(t_end=10.0, torque=tumble.ConstantTorque((0, 0, 0.1))).method
    ('exact', 'dop853')
    >>> RunSettings(t_end=10.0, method="geometric")
    Traceback (most recent call last):
    ...
    ValueError: method = 'geometric' needs a step (s) in a sweep: its default step follows the fastest body of each chunk, and the results must not depend on the chunking
    """

    t_end: float | None = None
    samples: int | None = None
    times: tuple | None = None
    method: str | None = None
    torque: object = None
    step: float | None = None

    def __post_init__(self) -> None:
        if self.times is not None:
            object.__setattr__(self, "times", tuple(self.times))
        if self.method is None:
            object.__setattr__(self, "method", "exact" if self.torque is None else "dop853")
        spec = get_method(self.method)
        if self.step is not None and (isinstance(self.step, bool) or not isinstance(self.step, (int, float))
                                      or not math.isfinite(self.step) or self.step <= 0):
            raise ValueError(f"step = {self.step!r} must be a positive finite number (s)")
        if as_torque(self.torque) is not None and not spec.supports_torque:
            raise ValueError(f"method = {self.method!r} cannot take a torque")
        if spec.fixed_step and self.step is None:
            raise ValueError(f"method = {self.method!r} needs a step (s) in a sweep: its default step follows the "
                             f"fastest body of each chunk, and the results must not depend on the chunking")

    def run(self, inputs: CaseInputs) -> BatchTrajectory:
        """The motions of the cases ``inputs`` (:class:`~tumble.ensemble.cases.CaseInputs`).

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble import BodySampler, Ensemble, InitialRates
        >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
        >>> inputs = Ensemble(BodySampler(box), InitialRates(omega=(0.0, 0.0, 2.0)), cases=3).inputs()
        >>> end = RunSettings(t_end=5.0, samples=2).run(inputs)  # the final state only
        >>> end.omega.shape, bool(np.allclose(end.omega[:, -1], [0.0, 0.0, 2.0]))  # a steady spin about the major axis
        ((3, 2, 3), True)
        """
        # a closed form is evaluated at the times asked for, with no steps from t = 0
        closed_form = get_method(self.method).closed_form
        if self.samples == 2 and self.times is None and closed_form and as_torque(self.torque) is None:
            end = simulate_batch(inputs.moments, inputs.omega0, times=[self.t_end], attitude0=inputs.quat0,
                                 method=self.method)
            return BatchTrajectory(t=np.array([0.0, end.t[-1]]), omega=np.stack([inputs.omega0, end.omega[:, -1]], 1),
                                   quat=np.stack([inputs.quat0, end.quat[:, -1]], 1), moments=end.moments,
                                   method=end.method, torque_free=end.torque_free)
        return simulate_batch(inputs.moments, inputs.omega0, t_end=self.t_end, times=self.times,
                              samples=self.samples, attitude0=inputs.quat0, method=self.method,
                              torque=self.torque, step=self.step)


@dataclass(frozen=True)
class Criterion:
    """A case succeeds when ``minimum <= value <= maximum`` for one column (NaN fails).

    Parameters
    ----------
    column : str
        A column's name without its unit (``"flips"``, ``"max_nutation"``, ...).
    minimum, maximum : float, optional
        Bounds, inclusive; at least one, and ``minimum <= maximum``.
    confidence : float
        Of the success statement, in (0, 1); default 0.9.

    Examples
    --------
    >>> Criterion("max_nutation", maximum=0.2, confidence=0.95).minimum is None
    True
    >>> Criterion("flips", minimum=3, maximum=1)
    Traceback (most recent call last):
    ...
    ValueError: min = 3 is above max = 1: no case could succeed; allowed: min <= max
    """

    column: str
    minimum: float | None = None
    maximum: float | None = None
    confidence: float = 0.9

    def __post_init__(self) -> None:
        if not isinstance(self.column, str) or not self.column:
            raise ValueError(f"column = {self.column!r} must name a column of cases.csv")
        if self.minimum is None and self.maximum is None:
            raise ValueError("a criterion needs min or max (or both)")
        for name in ("minimum", "maximum"):
            v = getattr(self, name)
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or math.isnan(v)):
                raise ValueError(f"{name[:3]} = {v!r} must be a number")
        if self.minimum is not None and self.maximum is not None and self.minimum > self.maximum:
            raise ValueError(f"min = {self.minimum!r} is above max = {self.maximum!r}: no case could succeed; "
                             f"allowed: min <= max")
        success_lower_bound(1, 0, self.confidence)  # checks the confidence

    def passed(self, columns: dict) -> np.ndarray:
        """Which cases of ``columns`` succeed, shape (m,).

        Examples
        --------
        >>> Criterion("max_nutation", maximum=0.2).passed({"max_nutation [rad]": np.array([0.1, 0.3, np.nan])}).tolist()
        [True, False, False]
        """
        found = {base_name(k): k for k in columns}
        if self.column not in found:
            raise ValueError(f"column = {self.column!r} is not a column of the cases; allowed: {', '.join(found)}")
        x = np.asarray(columns[found[self.column]], dtype=float)
        ok = np.isfinite(x)
        if self.minimum is not None:
            ok &= x >= self.minimum
        if self.maximum is not None:
            ok &= x <= self.maximum
        return ok


@dataclass(frozen=True, eq=False)
class Sweep:
    """A sweep: the cases, how to run them, and what counts as success.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Dispersion, Ensemble, InitialRates
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> cases = Ensemble(BodySampler(box, (Dispersion("moments", 0.02),)), InitialRates(omega=(0.01, 1.0, 0.01)), 8, seed=2)
    >>> sweep = Sweep(cases, RunSettings(t_end=60.0, samples=600), Criterion("flips", minimum=1))
    >>> summary = summarize(run_chunks(sweep, chunk=3), seed=2, criterion=sweep.criterion)
    >>> summary.cases, summary.passed, summary.failed  # every intermediate-axis spin flips
    (8, 8, 0)
    """

    ensemble: Ensemble
    settings: RunSettings
    criterion: Criterion | None = None


def chunk_ranges(cases: int, chunk: int) -> list[tuple[int, int]]:
    """``[(start, stop), ...]`` of consecutive chunks of ``chunk`` cases (the last one shorter).

    Examples
    --------
    >>> chunk_ranges(10, 4)
    [(0, 4), (4, 8), (8, 10)]
    """
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk = {chunk!r} must be a whole number >= 1 (cases per chunk)")
    return [(s, min(s + chunk, cases)) for s in range(0, cases, chunk)]


def compute_chunk(sweep: Sweep, start: int, stop: int) -> dict[str, np.ndarray]:
    """The columns of cases ``start`` to ``stop - 1`` (:func:`~tumble.ensemble.reductions.reduce_cases`).

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Dispersion, Ensemble, InitialRates
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> cases = Ensemble(BodySampler(box, (Dispersion("moments", 0.02),)), InitialRates(omega=(0.01, 1.0, 0.01)), 6)
    >>> sweep = Sweep(cases, RunSettings(t_end=30.0, samples=300))
    >>> alone, whole = compute_chunk(sweep, 4, 6), compute_chunk(sweep, 0, 6)
    >>> alone["case"].tolist(), bool(np.array_equal(alone["flip_period_exact [s]"], whole["flip_period_exact [s]"][4:]))
    ([4, 5], True)
    """
    inputs = sweep.ensemble.inputs(start, stop)
    return reduce_cases(inputs, sweep.settings.run(inputs), sweep.ensemble.names)


class ChunkStore(Protocol):
    """Where finished chunks are kept between runs (resume): by chunk number.

    Examples
    --------
    >>> class Memory(dict):  # a store in memory: these three methods are all a store needs
    ...     def has(self, number): return number in self
    ...     def load(self, number): return self[number]
    ...     def save(self, number, columns): self[number] = columns
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Ensemble, InitialRates
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> sweep = Sweep(Ensemble(BodySampler(box), InitialRates(omega=(0.01, 1.0, 0.01)), 5), RunSettings(t_end=10.0))
    >>> store = Memory()
    >>> first = list(run_chunks(sweep, chunk=2, store=store))
    >>> sorted(store), all(a is b for a, b in zip(run_chunks(sweep, chunk=2, store=store), first))  # resumed
    ([0, 1, 2], True)
    """

    def has(self, number: int) -> bool:
        """Whether the chunk is there.

        Examples
        --------
        >>> import tempfile
        >>> from tumble.io.resume import ChunkFolder  # the store on disk of tumble sweep
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=5, chunk=2)
        ...     store.save(2, {"case": np.array([4])})
        ...     print(store.has(1), store.has(2))
        ...     store.close()
        False True
        """

    def load(self, number: int) -> dict:
        """The chunk's columns.

        Examples
        --------
        >>> import tempfile
        >>> from tumble.io.resume import ChunkFolder  # the store on disk of tumble sweep
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=4, chunk=2)
        ...     store.save(0, {"case": np.arange(2), "flips": np.array([2, 4])})
        ...     print(store.load(0)["flips"].tolist())
        ...     store.close()
        [2, 4]
        """

    def save(self, number: int, columns: dict) -> None:
        """Keep the chunk's columns.

        Examples
        --------
        >>> import tempfile
        >>> from tumble.io.resume import ChunkFolder  # the store on disk of tumble sweep
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=4, chunk=2)
        ...     store.save(1, {"case": np.arange(2, 4)})
        ...     print(sorted(p.name for p in store.folder.glob("chunk-*")))
        ...     store.close()
        ['chunk-000001.npz']
        """


def run_chunks(sweep: Sweep, *, chunk: int = DEFAULT_CHUNK, store: ChunkStore | None = None,
               backend: InProcess | DaskBackend | None = None) -> Iterator[dict[str, np.ndarray]]:
    """Yield the columns of each chunk, in case order, computing only what ``store`` lacks.

    Parameters
    ----------
    sweep : Sweep
        What to run.
    chunk : int
        Cases per chunk (resume granularity and memory; it does not change the results).
    store : ChunkStore, optional
        Finished chunks are loaded from it, and each new one saved to it as it finishes.
    backend : optional
        Where chunks are computed (:mod:`tumble.ensemble.backends`); default in this process.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Ensemble, InitialRates
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> sweep = Sweep(Ensemble(BodySampler(box), InitialRates(omega=(0.01, 1.0, 0.01)), 5), RunSettings(t_end=10.0))
    >>> [chunk["case"].tolist() for chunk in run_chunks(sweep, chunk=2)]
    [[0, 1], [2, 3], [4]]
    """
    ranges = chunk_ranges(sweep.ensemble.cases, chunk)
    stored = {k for k in range(len(ranges)) if store is not None and store.has(k)}
    missing = [k for k in range(len(ranges)) if k not in stored]
    backend = InProcess() if backend is None else backend
    done = backend.map(compute_chunk, [(sweep, *ranges[k]) for k in missing])
    waiting: dict[int, dict] = {}
    for k in range(len(ranges)):
        if k in stored:
            yield store.load(k)
            continue
        while k not in waiting:
            position, columns = next(done)
            number = missing[position]
            if store is not None:
                store.save(number, columns)
            waiting[number] = columns
        yield waiting.pop(k)


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

    Examples
    --------
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

    @classmethod
    def of(cls, columns: dict, seed: int, criterion: Criterion | None = None,
           sample_size: int = SAMPLE_SIZE) -> SweepSummary:
        """The summary of one block of cases.

        Examples
        --------
        >>> cols = {"case": np.arange(3), "axis": np.array([2, 2, 2]), "predicted": np.array(["unstable"] * 3),
        ...         "circulation": np.array([1, 3, 3]), "flips": np.array([2, 4, 0]), "resampled": np.array([0, 1, 0])}
        >>> summary = SweepSummary.of(cols, seed=0, criterion=Criterion("flips", minimum=1))
        >>> summary.passed, summary.failed, summary.redraws
        (2, 1, 1)
        """
        names = tuple(k for k in columns if base_name(k) not in (*CATEGORICAL, *_NOT_SUMMARISED))
        table = np.column_stack([np.asarray(columns[k], dtype=float) for k in names])
        ok = criterion.passed(columns) if criterion is not None else np.zeros(0, bool)
        return cls(names, RunningMoments.of(table), KeyedSample.of(case_keys(seed, columns["case"]), table, sample_size),
                   Counts.of({k: columns[k] for k in CATEGORICAL}), int(ok.sum()), int((~ok).sum()),
                   int(np.sum(columns["resampled"])))

    def merge(self, other: SweepSummary) -> SweepSummary:
        """Both together (same columns).

        Examples
        --------
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
                            self.failed + other.failed, self.redraws + other.redraws)

    @property
    def cases(self) -> int:
        """Cases summarised.

        Examples
        --------
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
        >>> cols = {"case": np.arange(3), "axis": np.full(3, 2), "predicted": np.array(["unstable"] * 3),
        ...         "circulation": np.full(3, 3), "flip_period [s]": np.array([20.0, 21.0, 22.0]), "resampled": np.zeros(3, int)}
        >>> sample = SweepSummary.of(cols, seed=0).sample_columns()
        >>> list(sample), sorted(sample["flip_period [s]"].tolist())  # every case, when fewer than the sample's size
        (['flip_period [s]', 'resampled'], [20.0, 21.0, 22.0])
        """
        return {k: self.sample.values[:, j] for j, k in enumerate(self.columns)}

    def as_dict(self, criterion: Criterion | None = None) -> dict:
        """JSON-ready: ``cases``, ``redraws``, ``statistics`` (per column without its unit:
        ``unit``, ``count``, ``mean``, ``std``, ``min``, ``max``, ``quantiles`` {q: value},
        ``quantile_rank_error``: 0 when exact, else the 95 % bound), ``counts`` and, with a
        criterion, ``criterion`` (``column``, ``min``, ``max``, ``passed``, ``failed``,
        ``confidence``, ``success_lower_bound``, ``statement``).

        Examples
        --------
        >>> cols = {"case": np.arange(4), "axis": np.full(4, 2), "predicted": np.array(["unstable"] * 4),
        ...         "circulation": np.full(4, 3), "flip_period [s]": np.array([20.0, 21.0, 22.0, 23.0]),
        ...         "resampled": np.zeros(4, int)}
        >>> criterion = Criterion("flip_period", maximum=22.5)
        >>> out = SweepSummary.of(cols, seed=0, criterion=criterion).as_dict(criterion)
        >>> stats = out["statistics"]["flip_period"]
        >>> stats["unit"], stats["mean"], stats["quantiles"]["0.5"], stats["quantile_rank_error"]
        ('s', 21.5, 21.5, 0.0)
        >>> out["criterion"]["passed"], out["criterion"]["failed"]
        (3, 1)
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
        if criterion is not None:
            n = self.passed + self.failed
            out["criterion"] = {
                "column": criterion.column, "min": criterion.minimum, "max": criterion.maximum,
                "passed": self.passed, "failed": self.failed, "confidence": criterion.confidence,
                "success_lower_bound": success_lower_bound(n, self.failed, criterion.confidence),
                "statement": success_statement(n, self.failed, criterion.confidence),
            }
        return out


def summarize(chunks: Iterable[dict], seed: int, criterion: Criterion | None = None, *,
              sample_size: int = SAMPLE_SIZE,
              on_chunk: Callable[[dict[str, np.ndarray]], object] | None = None) -> SweepSummary:
    """Fold chunks (in case order) into a :class:`SweepSummary`, block by block.

    ``on_chunk(columns)``, if given, sees every chunk as it passes (to write it to a file).

    Examples
    --------
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
