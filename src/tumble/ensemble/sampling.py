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

from ..typing import ArrayLike

__all__ = ["DISTRIBUTIONS", "MAX_CASES", "SAMPLINGS", "Design", "case_generator", "case_uniforms", "check_seed", "deviates"]

#: The samplings of the unit cube.
SAMPLINGS = ("random", "lhs", "sobol")
#: The distributions a unit number is mapped to.
DISTRIBUTIONS = ("normal", "uniform")
#: The most cases a sweep may have (1e8: about a day's work on one core with the exact method;
#: a larger count is almost surely a typo, and 1e18 made the resume bookkeeping run forever).
MAX_CASES = 100_000_000

#: Unit numbers are kept this far inside (0, 1), so that the normal deviate stays finite
#: (|z| <= 8.3): a Sobol' point may be exactly 0.
_EDGE = 2.0**-53


def check_seed(seed: object) -> int:
    """A seed: a whole number from 0 to 2^64 - 1; anything else is refused with one line.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.sampling import check_seed
    >>> check_seed(np.uint64(2**63))
    9223372036854775808
    >>> check_seed(-1)
    Traceback (most recent call last):
    ...
    ValueError: seed = -1 must be a whole number from 0 to 2^64 - 1
    """
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**64:
        raise ValueError(f"seed = {seed!r} must be a whole number from 0 to 2^64 - 1")
    return int(seed)


def case_generator(seed: int, index: int) -> np.random.Generator:
    """Case ``index``'s own generator: ``SeedSequence(seed).spawn(index + 1)[index]``, made directly.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.sampling import case_generator
    >>> a = case_generator(42, 5).random(3)
    >>> b = np.random.default_rng(np.random.SeedSequence(42).spawn(6)[5]).random(3)
    >>> bool(np.array_equal(a, b))  # case 5 made again alone, the same draws
    True
    """
    return np.random.default_rng(np.random.SeedSequence(check_seed(seed), spawn_key=(int(index),)))


def deviates(u: ArrayLike, distribution: str) -> np.ndarray:
    """Map unit numbers ``u`` in (0, 1) to standard deviates.

    ``"normal"``: ``z = Phi^-1(u)`` (mean 0, standard deviation 1; the inverse normal CDF,
    ``scipy.special.ndtri``); ``"uniform"``: ``z = 2 u - 1`` (uniform on [-1, 1]). A spread
    ``s`` then makes ``s z`` one standard deviation or the half-width.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.sampling import deviates
    >>> deviates([0.5, 0.975], "normal").round(4).tolist()
    [0.0, 1.96]
    >>> deviates([0.25, 0.75], "uniform").tolist()
    [-0.5, 0.5]
    >>> bool(np.all(np.isfinite(deviates([0.0, 1.0], "normal"))))  # ends kept just inside (0, 1)
    True
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

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.sampling import Design
    >>> design = Design("lhs", seed=1, cases=10, dims=2)
    >>> points = design.rows(0, 10)
    >>> points.shape, sorted(np.floor(points[:, 0] * 10).astype(int).tolist()) == list(range(10))  # one per stratum
    ((10, 2), True)
    """

    sampling: str
    seed: int
    cases: int
    dims: int

    def __post_init__(self) -> None:
        if not isinstance(self.sampling, str) or self.sampling not in SAMPLINGS:
            raise ValueError(f"sampling = {self.sampling!r} is unknown; allowed: {', '.join(SAMPLINGS)}")
        check_seed(self.seed)
        cases = self.cases
        if isinstance(cases, bool) or not isinstance(cases, (int, np.integer)) or not 1 <= cases <= MAX_CASES:
            raise ValueError(f"cases = {cases!r} must be a whole number from 1 to {MAX_CASES}")
        dims = self.dims
        if isinstance(dims, bool) or not isinstance(dims, (int, np.integer)) or dims < 0:
            raise ValueError(f"dims = {dims!r} must be a whole number >= 0")

    def rows(self, start: int, stop: int) -> np.ndarray:
        """The points of cases ``start`` to ``stop - 1``, shape (stop - start, dims), in (0, 1).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.sampling import Design
        >>> design = Design("sobol", seed=3, cases=8, dims=2)
        >>> bool(np.array_equal(design.rows(4, 8), design.rows(0, 8)[4:]))  # any chunk, the same points
        True
        >>> Design("random", 0, 5, 3).rows(2, 3).shape
        (1, 3)
        """
        if not 0 <= start <= stop <= self.cases:
            raise ValueError(f"cases {start} to {stop - 1} are not among the {self.cases} of this sweep")
        if self.dims == 0:
            return np.empty((stop - start, 0))
        if self.sampling == "random":
            return case_uniforms(self.seed, np.arange(start, stop), self.dims)
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
        (redraws of a refused case) continue from there.

        Examples
        --------
        >>> from tumble.ensemble.sampling import Design, case_generator
        >>> design = Design("random", seed=9, cases=4, dims=2)
        >>> rng = design.generator(1)  # after case 1's two unit numbers
        >>> bool(rng.random() == case_generator(9, 1).random(3)[2])
        True
        """
        rng = case_generator(self.seed, index)
        if self.sampling == "random" and self.dims:
            rng.random(self.dims)
        return rng

    @functools.cached_property
    def _lhs(self) -> np.ndarray:
        """The whole Latin hypercube (it needs n): n x d numbers, made once per design."""
        from scipy.stats import qmc

        return qmc.LatinHypercube(self.dims, rng=np.random.default_rng(self.seed)).random(self.cases)


# --- case_generator's streams for many cases at once -------------------------------------
# numpy's SeedSequence (bit_generator.pyx) and PCG64 (pcg64.h, XSL-RR output), written over
# arrays of case numbers, so that the first draws of every case of a chunk come out bit for bit
# as ``case_generator(seed, i).random(k)`` without making a generator per case (~17 us each).
_M32 = 0xFFFFFFFF
_INIT_A, _MULT_A, _INIT_B, _MULT_B = 0x43B0D7E5, 0x931E8875, 0x8B51F9DD, 0x58F38DED
_MIX_L, _MIX_R, _POOL = 0xCA01F9DD, 0x4973F715, 4
_PCG_MULT = (2549297995355413924, 4865540595714422341)  # (high, low) of the 128-bit multiplier
_U64 = np.uint64


def _words(n: int) -> list[int]:
    """A whole number >= 0 as 32-bit words, least significant first ([0] for 0)."""
    out = []
    while True:
        out.append(n & _M32)
        n >>= 32
        if not n:
            return out


def _seed_pools(seed: int, index: np.ndarray) -> list[np.ndarray]:
    """The 4 pool words of ``SeedSequence(seed, spawn_key=(i,))`` for each case ``i < 2^32``."""
    ones = np.ones(len(index), dtype=np.uint32)
    words = _words(seed)
    words += [0] * (_POOL - len(words))
    entropy = [ones * np.uint32(w) for w in words] + [index.astype(np.uint32)]
    const = [_INIT_A]

    def hashmix(value):
        value = value ^ np.uint32(const[0])
        const[0] = (const[0] * _MULT_A) & _M32
        value = value * np.uint32(const[0])
        return value ^ (value >> np.uint32(16))

    def mix(x, y):
        r = np.uint32(_MIX_L) * x - np.uint32(_MIX_R) * y
        return r ^ (r >> np.uint32(16))

    pool = [hashmix(entropy[i]) for i in range(_POOL)]
    for src in range(_POOL):
        for dst in range(_POOL):
            if src != dst:
                pool[dst] = mix(pool[dst], hashmix(pool[src]))
    for src in range(_POOL, len(entropy)):
        for dst in range(_POOL):
            pool[dst] = mix(pool[dst], hashmix(entropy[src]))
    return pool


def _generate_state(pool: list[np.ndarray]) -> list[np.ndarray]:
    """``generate_state(4, uint64)`` of each pool: 4 arrays of uint64."""
    const = _INIT_B
    out32 = []
    for k in range(8):
        value = pool[k % _POOL] ^ np.uint32(const)
        const = (const * _MULT_B) & _M32
        value = value * np.uint32(const)
        out32.append(value ^ (value >> np.uint32(16)))
    return [out32[2 * k].astype(_U64) | (out32[2 * k + 1].astype(_U64) << _U64(32)) for k in range(4)]


def _mul64(a, b):
    """The full product of uint64 arrays: (high, low)."""
    a0, a1, b0, b1 = a & _U64(_M32), a >> _U64(32), b & _U64(_M32), b >> _U64(32)
    p00, p01, p10 = a0 * b0, a0 * b1, a1 * b0
    mid = (p00 >> _U64(32)) + (p01 & _U64(_M32)) + (p10 & _U64(_M32))
    return a1 * b1 + (p01 >> _U64(32)) + (p10 >> _U64(32)) + (mid >> _U64(32)), (mid << _U64(32)) | (p00 & _U64(_M32))


def _add128(ah, al, bh, bl):
    low = al + bl
    return ah + bh + (low < al).astype(_U64), low


def _step(h, l, ih, il):
    """The LCG step ``state * multiplier + inc`` (mod 2^128)."""
    mh, ml = _U64(_PCG_MULT[0]), _U64(_PCG_MULT[1])
    hi, lo = _mul64(l, ml)
    hi = hi + h * ml + l * mh
    return _add128(hi, lo, ih, il)


def case_uniforms(seed: int, index: ArrayLike, count: int) -> np.ndarray:
    """The first ``count`` draws of ``case_generator(seed, i).random()`` for each case ``i``.

    Bit for bit those of the generators (tested), computed for all the cases at once.

    Parameters
    ----------
    seed : int
        The sweep's seed, 0 to 2^64 - 1.
    index : array_like of int, shape (m,)
        Case numbers, >= 0.
    count : int
        Draws per case, >= 0.

    Returns
    -------
    ndarray, shape (m, count)
        Uniform numbers in [0, 1).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.sampling import case_generator, case_uniforms
    >>> u = case_uniforms(42, [0, 7], 3)
    >>> bool(np.array_equal(u[1], case_generator(42, 7).random(3)))  # bit for bit
    True
    """
    index = np.asarray(index, dtype=np.int64).reshape(-1)
    out = np.empty((len(index), count))
    if not count or not len(index):
        return out
    wide = index >= 2**32
    if np.any(wide):  # spawn keys of two words: the generators themselves (never in practice)
        out[wide] = [case_generator(seed, int(i)).random(count) for i in index[wide]]
    narrow = ~wide
    s0, s1, q0, q1 = _generate_state(_seed_pools(check_seed(seed), index[narrow]))
    ih = (q0 << _U64(1)) | (q1 >> _U64(63))
    il = (q1 << _U64(1)) | _U64(1)
    h, l = _step(*_add128(ih, il, s0, s1), ih, il)  # srandom: state 0 stepped is inc; + initstate; step
    for k in range(count):
        h, l = _step(h, l, ih, il)
        x = h ^ l
        rot = h >> _U64(58)
        x = (x >> rot) | (x << ((_U64(64) - rot) & _U64(63)))
        out[narrow, k] = (x >> _U64(11)).astype(float) * 2.0**-53
    return out
