"""Sweeps and Monte Carlo (layer 4): dispersions, sampling, per-case results, statistics.

On top of :mod:`tumble.dynamics` and :mod:`tumble.analysis`; never imports the files, figures
or command line (:mod:`tumble.io.sweepfile` reads sweep files and writes their results).
"""

from .cases import FRAMES, CaseInputs, Ensemble, InitialRates
from .dispersions import TARGETS, BodySampler, Dispersion, Sampled
from .sampling import DISTRIBUTIONS, SAMPLINGS, Design, case_generator, deviates

__all__ = [
    "DISTRIBUTIONS",
    "FRAMES",
    "SAMPLINGS",
    "TARGETS",
    "BodySampler",
    "CaseInputs",
    "Design",
    "Dispersion",
    "Ensemble",
    "InitialRates",
    "Sampled",
    "case_generator",
    "deviates",
]
