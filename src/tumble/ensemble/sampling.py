"""Where each case's random numbers come from: seeds, designs and deviates.

A sweep of ``n`` cases draws, for case ``i``, a point of the unit cube ``(0, 1)^d`` (one
dimension per uncertain scalar), then maps it to the distributions it needs
(:func:`deviates`). Three samplings:

- ``"random"``: independent uniform numbers from case ``i``'s own generator;
- ``"lhs"``: Latin hypercube sampling (McKay, Beckman & Conover, Technometrics 21 (1979) 239),
  :class:`scipy.stats.qmc.LatinHypercube`: each dimension's ``n`` values fall one in each of
  its ``n`` equal strata. The design is a function of ``(seed, n, d)``, and case ``i`` takes
  row ``i``;
- ``"sobol"``: scrambled Sobol' points (Sobol', USSR Comput. Math. Math. Phys. 7 (1967) 86;
  Owen scrambling), :class:`scipy.stats.qmc.Sobol`: case ``i`` takes point ``i`` of the
  sequence of ``(seed, d)``; balanced when ``n`` is a power of two.

**Seeds.** Case ``i``'s generator is ``numpy.random.default_rng(SeedSequence(seed,
spawn_key=(i,)))``, which is ``SeedSequence(seed).spawn(n)[i]`` made directly, without the
``i`` before it (:func:`case_generator`); the designs take theirs from ``SeedSequence(seed)``
itself, which no case shares. So any case can be made again alone, and gives the same draws:
for ``"random"`` from ``(seed, i)``; for ``"lhs"`` from ``(seed, i, n)`` (the design needs
``n``); for ``"sobol"`` from ``(seed, i)`` (and ``d``). A case whose draw is refused (an
unphysical body, :mod:`tumble.ensemble.dispersions`) draws again from its own generator.
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass

import numpy as np

__all__ = ["DISTRIBUTIONS", "SAMPLINGS", "Design", "case_generator", "check_seed", "deviates"]

#: The samplings of the unit cube.
SAMPLINGS = ("random", "lhs", "sobol")
#: The distributions a unit number is mapped to.
DISTRIBUTIONS = ("normal", "uniform")

#: Unit numbers are kept this far inside (0, 1), so that the normal deviate stays finite
#: (|z| <= 8.3): a Sobol' point may be exactly 0.
_EDGE = 2.0**-53


def check_seed(seed) -> int:
    """A seed: a whole number from 0 to 2^64 - 1; anything else is refused with one line."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**64:
        raise ValueError(f"seed = {seed!r} must be a whole number from 0 to 2^64 - 1")
    return int(seed)


def case_generator(seed: int, index: int) -> np.random.Generator:
    """Case ``index``'s own generator: ``SeedSequence(seed).spawn(index + 1)[index]``, made directly."""
    return np.random.default_rng(np.random.SeedSequence(check_seed(seed), spawn_key=(int(index),)))


def deviates(u, distribution: str) -> np.ndarray:
    """Map unit numbers ``u`` in (0, 1) to standard deviates.

    ``"normal"``: ``z = Phi^-1(u)`` (mean 0, standard deviation 1; the inverse normal CDF,
    ``scipy.special.ndtri``); ``"uniform"``: ``z = 2 u - 1`` (uniform on [-1, 1]). A spread
    ``s`` then makes ``s z`` one standard deviation or the half-width.
    """
    u = np.clip(np.asarray(u, dtype=float), _EDGE, 1.0 - _EDGE)
    if distribution == "normal":
        from scipy.special import ndtri

        return ndtri(u)
    if distribution == "uniform":
        return 2.0 * u - 1.0
    raise ValueError(f"distribution = {distribution!r} is unknown; allowed: {', '.join(DISTRIBUTIONS)}")


@dataclass(frozen=True)
class Design:
    """The unit-cube points of a sweep's cases.

    Parameters
    ----------
    sampling : {"random", "lhs", "sobol"}
        How the points are drawn (module docstring).
    seed : int
        The sweep's seed, 0 to 2^64 - 1.
    cases : int
        Number of cases n, >= 1.
    dims : int
        Dimensions d, >= 0 (0: every case is the nominal one).
    """

    sampling: str
    seed: int
    cases: int
    dims: int

    def __post_init__(self) -> None:
        if not isinstance(self.sampling, str) or self.sampling not in SAMPLINGS:
            raise ValueError(f"sampling = {self.sampling!r} is unknown; allowed: {', '.join(SAMPLINGS)}")
        check_seed(self.seed)
        for name in ("cases", "dims"):
            value = getattr(self, name)
            low = 1 if name == "cases" else 0
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
                raise ValueError(f"{name} = {value!r} must be a whole number >= {low}")

    def rows(self, start: int, stop: int) -> np.ndarray:
        """The points of cases ``start`` to ``stop - 1``, shape (stop - start, dims), in (0, 1)."""
        if not 0 <= start <= stop <= self.cases:
            raise ValueError(f"cases {start} to {stop - 1} are not among the {self.cases} of this sweep")
        if self.dims == 0:
            return np.empty((stop - start, 0))
        if self.sampling == "random":
            return np.array([case_generator(self.seed, i).random(self.dims) for i in range(start, stop)]).reshape(
                stop - start, self.dims)
        if self.sampling == "lhs":
            return self._lhs[start:stop]
        from scipy.stats import qmc

        engine = qmc.Sobol(self.dims, scramble=True, rng=np.random.default_rng(self.seed))
        if start:  # scipy's fast_forward(0) fails
            engine.fast_forward(start)
        with warnings.catch_warnings():  # "balance properties ... power of 2": documented above
            warnings.simplefilter("ignore", UserWarning)
            return engine.random(stop - start)

    def generator(self, index: int) -> np.random.Generator:
        """Case ``index``'s generator, positioned after the draws of its point: further draws
        (redraws of a refused case) continue from there."""
        rng = case_generator(self.seed, index)
        if self.sampling == "random" and self.dims:
            rng.random(self.dims)
        return rng

    @functools.cached_property
    def _lhs(self) -> np.ndarray:
        """The whole Latin hypercube (it needs n): n x d numbers, made once per design."""
        from scipy.stats import qmc

        return qmc.LatinHypercube(self.dims, rng=np.random.default_rng(self.seed)).random(self.cases)
