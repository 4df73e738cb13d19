"""Sweeps and Monte Carlo (layer 4): dispersions, sampling, per-case results, statistics.

On top of :mod:`tumble.dynamics` and :mod:`tumble.analysis`; never imports the files, figures
or command line (:mod:`tumble.io.sweepfile` reads sweep files, :mod:`tumble.commands.sweep` runs them
and writes their results).

Examples
--------
>>> import tumble
>>> from tumble.ensemble import BodySampler, Dispersion, Ensemble, InitialRates, RunSettings, Sweep, run_chunks, summarize
>>> bodies = BodySampler(tumble.t_handle(), (Dispersion("preset", 0.05, field="crossbar_length",
...                                                      distribution="uniform"),), "t-handle")
>>> cases = Ensemble(bodies, InitialRates(omega=(10.0, 0.1, 0.1), frame="design"), 8, seed=1)
>>> sweep = Sweep(cases, RunSettings(t_end=20.0, samples=400))
>>> summary = summarize(run_chunks(sweep, chunk=4), seed=1)
>>> summary.as_dict()["counts"]["predicted"]
{'unstable': 8}
"""

from .backends import DaskBackend, InProcess, make_backend
from .cases import FRAMES, CaseInputs, Ensemble, InitialRates
from .dispersions import TARGETS, BodySampler, Dispersion, Sampled
from .reductions import RESULT_COLUMNS, StabilityMap, input_columns, nutation_angle, reduce_cases, stability_map
from .sampling import DISTRIBUTIONS, SAMPLINGS, Design, case_generator, deviates
from .statistics import (
    Counts,
    KeyedSample,
    RunningMoments,
    case_keys,
    fraction_interval,
    runs_needed,
    success_lower_bound,
    success_statement,
)
from .sweep import (
    DEFAULT_CHUNK,
    ChunkStore,
    Criterion,
    RunSettings,
    Sweep,
    SweepSummary,
    base_name,
    chunk_ranges,
    compute_chunk,
    run_chunks,
    summarize,
)

__all__ = [
    "DEFAULT_CHUNK",
    "DISTRIBUTIONS",
    "FRAMES",
    "RESULT_COLUMNS",
    "SAMPLINGS",
    "TARGETS",
    "BodySampler",
    "CaseInputs",
    "ChunkStore",
    "Counts",
    "Criterion",
    "DaskBackend",
    "Design",
    "Dispersion",
    "Ensemble",
    "InProcess",
    "InitialRates",
    "KeyedSample",
    "RunSettings",
    "RunningMoments",
    "Sampled",
    "StabilityMap",
    "Sweep",
    "SweepSummary",
    "base_name",
    "case_generator",
    "case_keys",
    "chunk_ranges",
    "compute_chunk",
    "deviates",
    "fraction_interval",
    "input_columns",
    "make_backend",
    "nutation_angle",
    "reduce_cases",
    "run_chunks",
    "runs_needed",
    "stability_map",
    "success_lower_bound",
    "success_statement",
    "summarize",
]
