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
from collections.abc import Sequence
from typing import TYPE_CHECKING, Iterator, Protocol, overload

import numpy as np

from ..dynamics import simulate_batch
from ..dynamics.batch import BatchTrajectory
from ..dynamics.engine.stepsize import check_atol, check_rtol
from ..dynamics.methods.integrators import get_method
from ..dynamics.methods.names import AUTO
from ..dynamics.models.torques import as_torque
from .backends import InProcess
from .cases import Ensemble
from .reductions import reduce_cases
from .statistics import success_lower_bound

if TYPE_CHECKING:
    from .backends import DaskBackend
    from .cases import CaseInputs

from .summary import (  # the statistics, re-exported
    CATEGORICAL,
    QUANTILES,
    SAMPLE_SIZE,
    STATS_BLOCK,
    SweepSummary,
    base_name,
    summarize,
)

__all__ = [
    "CATEGORICAL",
    "DEFAULT_CHUNK",
    "QUANTILES",
    "SAMPLE_SIZE",
    "STATS_BLOCK",
    "ChunkRanges",
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
        ``"auto"`` (the default): ``"exact"`` without a torque, ``"dop853"`` with one.
    torque : torque model, optional
        :class:`tumble.ConstantTorque`, :class:`tumble.GravityGradient` or any
        ``tau(t, omega, attitude)``.
    step : float, optional
        Step of the fixed-step methods, s, positive and finite: needed with them (see the
        module docstring).
    rtol, atol : float, optional
        The adaptive methods' tolerances, as :func:`tumble.simulate_batch` takes them (the
        method's defaults if not given).

    Raises
    ------
    ValueError
        For an unknown method, a torque the method cannot take, a fixed-step method without
        ``step``, or a ``step`` that is not a positive finite number.

    Examples
    --------
    >>> from tumble.ensemble.sweep import RunSettings
    >>> import tumble
    >>> RunSettings(t_end=10.0).method, RunSettings(t_end=10.0, torque=tumble.ConstantTorque((0, 0, 0.1))).method
    ('exact', 'dop853')
    >>> RunSettings(t_end=10.0, method="auto").method   # as a sweep file's method = "auto" says it
    'exact'
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
    rtol: float | None = None
    atol: float | None = None

    def __post_init__(self) -> None:
        if self.times is not None:
            object.__setattr__(self, "times", tuple(self.times))
        if self.method is None or self.method == AUTO:  # "auto", the default: what a sweep's every case can take
            object.__setattr__(self, "method", "exact" if self.torque is None else "dop853")
        spec = get_method(self.method)
        if self.step is not None and (isinstance(self.step, bool) or not isinstance(self.step, (int, float))
                                      or not math.isfinite(self.step) or self.step <= 0):
            raise ValueError(f"step = {self.step!r} must be a positive finite number (s)")
        if self.rtol is not None:
            object.__setattr__(self, "rtol", check_rtol("rtol", self.rtol))
        if self.atol is not None:
            object.__setattr__(self, "atol", check_atol("atol", self.atol))
        if as_torque(self.torque) is not None and not spec.supports_torque:
            raise ValueError(f"method = {self.method!r} cannot take a torque")
        if spec.fixed_step and self.step is None:
            raise ValueError(f"method = {self.method!r} needs a step (s) in a sweep: its default step follows the "
                             f"fastest body of each chunk, and the results must not depend on the chunking")

    def run(self, inputs: CaseInputs) -> BatchTrajectory:
        """The motions of the cases ``inputs`` (:class:`~tumble.ensemble.cases.CaseInputs`).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.sweep import RunSettings
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
                              torque=self.torque, step=self.step, rtol=self.rtol, atol=self.atol)


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
    >>> from tumble.ensemble.sweep import Criterion
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
        >>> import numpy as np
        >>> from tumble.ensemble.sweep import Criterion
        >>> Criterion("max_nutation", maximum=0.2).passed({"max_nutation [rad]": np.array([0.1, 0.3, np.nan])}).tolist()
        [True, False, False]
        """
        found = {base_name(k): k for k in columns}
        if self.column not in found:
            raise ValueError(f"column = {self.column!r} is not a column of the cases; allowed: {', '.join(found)}")
        values = np.asarray(columns[found[self.column]])
        if values.dtype.kind not in "biuf":  # numpy's "could not convert string to float" named no column
            numbers = [base_name(k) for k in columns if np.asarray(columns[k]).dtype.kind in "biuf"]
            raise ValueError(f"column = {self.column!r} holds text ({', '.join(sorted(set(map(str, values)))[:4])}), "
                             f"not numbers to bound with min and max; allowed: {', '.join(numbers)}")
        x = values.astype(float)
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
    >>> from tumble.ensemble.sweep import Criterion
    >>> from tumble.ensemble.sweep import RunSettings
    >>> from tumble.ensemble.sweep import Sweep
    >>> from tumble.ensemble.sweep import run_chunks
    >>> from tumble.ensemble.sweep import summarize
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


class ChunkRanges(Sequence[tuple[int, int]]):
    """The chunks ``(start, stop)`` of ``cases`` cases, ``chunk`` at a time, computed when asked for.

    A sequence (``len``, indexing, iteration) that holds two numbers, never the list: a sweep of
    1e8 cases in chunks of one is 1e8 chunks, and this object is as small as for one chunk.

    Examples
    --------
    >>> from tumble.ensemble.sweep import ChunkRanges
    >>> ranges = ChunkRanges(10, 4)
    >>> len(ranges), ranges[0], ranges[-1], list(ranges)
    (3, (0, 4), (8, 10), [(0, 4), (4, 8), (8, 10)])
    """

    __slots__ = ("cases", "chunk")

    def __init__(self, cases: int, chunk: int) -> None:
        self.cases, self.chunk = int(cases), int(chunk)

    def __len__(self) -> int:
        return -(-max(self.cases, 0) // self.chunk)

    @overload
    def __getitem__(self, k: int) -> tuple[int, int]: ...

    @overload
    def __getitem__(self, k: slice) -> list[tuple[int, int]]: ...

    def __getitem__(self, k: int | slice) -> tuple[int, int] | list[tuple[int, int]]:
        if isinstance(k, slice):
            return [self[j] for j in range(len(self))[k]]
        start = range(0, max(self.cases, 0), self.chunk)[k]  # an IndexError past either end
        return start, min(start + self.chunk, self.cases)

    def __iter__(self) -> Iterator[tuple[int, int]]:
        for start in range(0, max(self.cases, 0), self.chunk):
            yield start, min(start + self.chunk, self.cases)

    def __repr__(self) -> str:
        return f"ChunkRanges(cases={self.cases}, chunk={self.chunk})"


def chunk_ranges(cases: int, chunk: int) -> ChunkRanges:
    """The ``(start, stop)`` of consecutive chunks of ``chunk`` cases (the last one shorter).

    A lazy sequence (:class:`ChunkRanges`): its length and each chunk are computed when asked
    for, so ``chunk_ranges(10**8, 1)`` costs no more memory than ``chunk_ranges(10, 4)``.

    Examples
    --------
    >>> from tumble.ensemble.sweep import chunk_ranges
    >>> list(chunk_ranges(10, 4))
    [(0, 4), (4, 8), (8, 10)]
    >>> ranges = chunk_ranges(10**8, 1)
    >>> len(ranges), ranges[12345]
    (100000000, (12345, 12346))
    """
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk = {chunk!r} must be a whole number >= 1 (cases per chunk)")
    return ChunkRanges(cases, chunk)


def compute_chunk(sweep: Sweep, start: int, stop: int) -> dict[str, np.ndarray]:
    """The columns of cases ``start`` to ``stop - 1`` (:func:`~tumble.ensemble.reductions.reduce_cases`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.sweep import RunSettings
    >>> from tumble.ensemble.sweep import Sweep
    >>> from tumble.ensemble.sweep import compute_chunk
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
    >>> from tumble.ensemble.sweep import RunSettings
    >>> from tumble.ensemble.sweep import Sweep
    >>> from tumble.ensemble.sweep import run_chunks
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
        >>> import numpy as np
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
        >>> import numpy as np
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
        >>> import numpy as np
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
    >>> from tumble.ensemble.sweep import RunSettings
    >>> from tumble.ensemble.sweep import Sweep
    >>> from tumble.ensemble.sweep import run_chunks
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Ensemble, InitialRates
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> sweep = Sweep(Ensemble(BodySampler(box), InitialRates(omega=(0.01, 1.0, 0.01)), 5), RunSettings(t_end=10.0))
    >>> [chunk["case"].tolist() for chunk in run_chunks(sweep, chunk=2)]
    [[0, 1], [2, 3], [4]]
    """
    ranges = chunk_ranges(sweep.ensemble.cases, chunk)
    # without a store nothing is listed per chunk: every chunk is missing, in order, lazily
    stored = set() if store is None else {k for k in range(len(ranges)) if store.has(k)}
    missing: Sequence[int] = range(len(ranges)) if not stored else [k for k in range(len(ranges)) if k not in stored]
    backend = InProcess() if backend is None else backend
    done = backend.map(compute_chunk, ((sweep, *ranges[k]) for k in missing))
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
