"""The cases of a sweep: a nominal body with its dispersions, initial rates, a design.

:class:`Ensemble` says everything that defines the cases; :meth:`Ensemble.inputs` makes any
range of them, each from its own random numbers (:mod:`tumble.ensemble.sampling`), so a case
comes out the same whether made alone, in a chunk of 7 or in one of 10,000.

Case ``i`` takes point ``i`` of the design: the first 3 numbers (when the initial rates are
dispersed) give the rates, the rest the body's deviates (:class:`~tumble.ensemble.dispersions.BodySampler`). A body draw that is not physical is drawn again from the case's own generator,
up to ``max_resamples`` times (then the sweep is refused, naming the case); the rates keep
their draw, so a Latin hypercube stays stratified in them. How many redraws each case needed
is part of its inputs (``resampled``).

A chunk is made with arrays where it can be: the random numbers of all its cases at once
(:func:`~tumble.ensemble.sampling.case_uniforms`), the rates, and bodies dispersed by their
moments and axes (:meth:`~tumble.ensemble.dispersions.BodySampler.sample_many`); a body
dispersed by its parts or preset parameters, and a draw near a rule's edge, are made one case
at a time. Both ways give each case bit for bit the same inputs (tested).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..typing import ArrayLike
from ..validation import check_vector
from .dispersions import BodySampler
from .sampling import DISTRIBUTIONS, Design, check_seed, deviates

__all__ = ["FRAMES", "CaseInputs", "Ensemble", "InitialRates"]

#: Frames the initial rates may be given in.
FRAMES = ("principal", "design")


@dataclass(frozen=True)
class InitialRates:
    """The initial angular velocity of the cases: nominal, dispersed, or a grid.

    Parameters
    ----------
    omega : sequence of 3 floats, optional
        The nominal rate, rad/s, in ``frame`` (not with ``grid``).
    frame : {"principal", "design"}
        ``"principal"``: components along each case's own principal axes (ascending moments);
        ``"design"``: along the body's design axes, so that a case whose axes are turned
        (dispersions of parts or axes) is spun off its principal axes.
    distribution : {"normal", "uniform"}, optional
        Disperse each component by ``spread`` (one standard deviation, or the half-width).
    spread : sequence of 3 floats
        Per component, rad/s, >= 0; non-zero only with ``distribution``.
    grid : three sequences of floats, optional
        Instead of ``omega``: the values of each component, rad/s; the cases run through
        their Cartesian product, the third component fastest, case ``i`` at point ``i mod G``
        (``G`` points: take a multiple of ``G`` cases to give every point the same number).

    Examples
    --------
    >>> from tumble.ensemble.cases import InitialRates
    >>> InitialRates(omega=(0.1, 10.0, 0.1)).rate(0, [])  # the nominal rate, rad/s
    array([ 0.1, 10. ,  0.1])
    >>> InitialRates(grid=([0.0], [1.0, 2.0], [5.0, 6.0, 7.0])).points
    6
    """

    omega: tuple | None = None
    frame: str = "principal"
    distribution: str | None = None
    spread: tuple = (0.0, 0.0, 0.0)
    grid: tuple | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.frame, str) or self.frame not in FRAMES:
            raise ValueError(f"frame = {self.frame!r} is unknown; allowed: {', '.join(FRAMES)}")
        if (self.grid is None) == (self.omega is None):
            raise ValueError("initial rates need omega = [w1, w2, w3] (rad/s) or a grid of them, " +
                             ("not both" if self.grid is not None else "and neither is given"))
        if self.omega is not None:
            object.__setattr__(self, "omega", check_vector("omega", self.omega, "rad/s"))
        spread = check_vector("spread", self.spread, "rad/s")
        if min(spread) < 0:
            raise ValueError(f"spread = {list(spread)} must be >= 0 (rad/s)")
        object.__setattr__(self, "spread", spread)
        if self.distribution is None and any(spread):
            raise ValueError(f"spread = {list(spread)} needs distribution = (one of {', '.join(DISTRIBUTIONS)}): "
                             f"without it the rates are not dispersed")
        if self.distribution is not None:
            if not isinstance(self.distribution, str) or self.distribution not in DISTRIBUTIONS:
                raise ValueError(f"distribution = {self.distribution!r} is unknown; allowed: {', '.join(DISTRIBUTIONS)}")
            if self.grid is not None:
                raise ValueError("a grid of initial rates takes no distribution: give one or the other")
        if self.grid is not None:
            object.__setattr__(self, "grid", _grid(self.grid))

    @property
    def dims(self) -> int:
        """Deviates per case: 3 when dispersed, else 0.

        Examples
        --------
        >>> from tumble.ensemble.cases import InitialRates
        >>> InitialRates(omega=(0, 5, 0)).dims, InitialRates(omega=(0, 5, 0), distribution="normal", spread=(0.1, 0.1, 0.1)).dims
        (0, 3)
        """
        return 3 if self.distribution is not None else 0

    @property
    def points(self) -> int:
        """Points of the grid (1 without one).

        Examples
        --------
        >>> from tumble.ensemble.cases import InitialRates
        >>> InitialRates(grid=([1.0, 2.0], [0.0], [0.1, 0.2, 0.3])).points, InitialRates(omega=(0, 0, 1)).points
        (6, 1)
        """
        return int(np.prod([len(g) for g in self.grid])) if self.grid is not None else 1

    def rate(self, index: int, u: ArrayLike) -> np.ndarray:
        """Case ``index``'s rate in :attr:`frame`, rad/s, from its unit numbers ``u`` (shape (dims,)).

        Examples
        --------
        >>> from tumble.ensemble.cases import InitialRates
        >>> rates = InitialRates(omega=(0.0, 5.0, 0.0), distribution="uniform", spread=(0.0, 1.0, 0.0))
        >>> rates.rate(0, [0.5, 0.75, 0.5]).tolist()  # 5 + 1 * (2 * 0.75 - 1)
        [0.0, 5.5, 0.0]
        >>> InitialRates(grid=([1.0, 2.0], [0.0], [7.0, 8.0])).rate(3, []).tolist()  # the last component fastest
        [2.0, 0.0, 8.0]
        """
        if self.grid is not None:
            point = np.unravel_index(index % self.points, [len(g) for g in self.grid])
            return np.array([g[k] for g, k in zip(self.grid, point)])
        omega = np.array(self.omega)
        if self.distribution is None:
            return omega
        return omega + np.array(self.spread) * deviates(u, self.distribution)

    def rates(self, index: ArrayLike, u: ArrayLike) -> np.ndarray:
        """:meth:`rate` of many cases at once, bit for bit: ``index`` shape (m,), ``u`` shape
        (m, dims); returns shape (m, 3).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.cases import InitialRates
        >>> grid = InitialRates(grid=([1.0, 2.0], [0.0], [7.0, 8.0]))
        >>> out = grid.rates(np.arange(5), np.empty((5, 0)))
        >>> out.shape, out[4].tolist() == grid.rate(4, []).tolist()  # case 4 is point 0 again
        ((5, 3), True)
        """
        index = np.asarray(index)
        if self.grid is not None:
            point = np.unravel_index(index % self.points, [len(g) for g in self.grid])
            return np.stack([np.asarray(g)[k] for g, k in zip(self.grid, point)], axis=-1).reshape(len(index), 3)
        omega = np.array(self.omega)
        if self.distribution is None:
            return np.tile(omega, (len(index), 1))
        return omega + np.array(self.spread) * deviates(np.asarray(u).reshape(len(index), 3), self.distribution)


def _grid(grid) -> tuple:
    if not isinstance(grid, (list, tuple)) or len(grid) != 3:
        raise ValueError(f"grid = {grid!r} must be three lists of rates, one per component (rad/s)")
    out = []
    for j, values in enumerate(grid):
        if not isinstance(values, (list, tuple)) or not values:
            raise ValueError(f"grid[{j}] = {values!r} must be a non-empty list of rates (rad/s)")
        try:
            a = np.array(values, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"grid[{j}] = {values!r} must be a list of numbers (rad/s)") from None
        if any(isinstance(v, bool) for v in values) or a.ndim != 1 or not np.all(np.isfinite(a)):
            raise ValueError(f"grid[{j}] = {values!r} must be a list of finite numbers (rad/s)")
        out.append(tuple(float(v) for v in a))
    return tuple(out)


@dataclass(frozen=True, eq=False)
class CaseInputs:
    """The inputs of a range of cases, ``m`` of them.

    Attributes
    ----------
    index : ndarray of int, shape (m,)
        Case numbers, from 0.
    moments : ndarray, shape (m, 3)
        Principal moments, ascending, kg m^2.
    axes : ndarray, shape (m, 3, 3)
        Principal axes (columns) in the design frame.
    omega0 : ndarray, shape (m, 3)
        Initial angular velocity in each case's principal frame, rad/s.
    quat0 : ndarray, shape (m, 4)
        Initial attitude, principal frame to world, ``[x, y, z, w]``: the design frame starts
        aligned with the world.
    values : ndarray, shape (m, p)
        The drawn quantities (:attr:`BodySampler.names`).
    resampled : ndarray of int, shape (m,)
        How many body draws of each case were refused as unphysical and drawn again.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler
    >>> from tumble.ensemble.cases import Ensemble, InitialRates
    >>> inputs = Ensemble(BodySampler(tumble.t_handle()), InitialRates(omega=(0.1, 5.0, 0.1)), cases=4).inputs()
    >>> len(inputs), inputs.moments.shape, inputs.omega0.shape, inputs.quat0.shape
    (4, (4, 3), (4, 3), (4, 4))
    """

    index: np.ndarray
    moments: np.ndarray
    axes: np.ndarray
    omega0: np.ndarray
    quat0: np.ndarray
    values: np.ndarray
    resampled: np.ndarray

    def __len__(self) -> int:
        return len(self.index)


@dataclass(frozen=True, eq=False)
class Ensemble:
    """Everything that defines a sweep's cases.

    Parameters
    ----------
    bodies : BodySampler
        The nominal body and its dispersions.
    rates : InitialRates
        The initial angular velocities.
    cases : int
        How many cases, >= 1.
    seed : int
        The sweep's seed, 0 to 2^64 - 1.
    sampling : {"random", "lhs", "sobol"}
        How the unit cube is sampled (:mod:`tumble.ensemble.sampling`).
    max_resamples : int
        Redraws allowed per case before the sweep is refused (>= 0).

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Dispersion
    >>> from tumble.ensemble.cases import Ensemble, InitialRates
    >>> bodies = BodySampler(tumble.t_handle(), (Dispersion("moments", 0.02),))
    >>> cases = Ensemble(bodies, InitialRates(omega=(0.1, 5.0, 0.1)), cases=100, seed=7, sampling="lhs")
    >>> cases.design.dims, cases.inputs(10, 20).moments.shape
    (3, (10, 3))
    """

    bodies: BodySampler
    rates: InitialRates
    cases: int
    seed: int = 0
    sampling: str = "random"
    max_resamples: int = 100

    def __post_init__(self) -> None:
        if not isinstance(self.bodies, BodySampler):
            raise ValueError(f"bodies = {self.bodies!r} must be a tumble.ensemble.BodySampler")
        if not isinstance(self.rates, InitialRates):
            raise ValueError(f"rates = {self.rates!r} must be a tumble.ensemble.InitialRates")
        check_seed(self.seed)
        m = self.max_resamples
        if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or m < 0:
            raise ValueError(f"max_resamples = {m!r} must be a whole number >= 0")
        _ = self.design  # checks cases and sampling

    @functools.cached_property
    def design(self) -> Design:
        """The unit-cube design: rates first, then the body's deviates.

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble import BodySampler, Dispersion
        >>> rates = InitialRates(omega=(0, 5, 0), distribution="normal", spread=(0.1, 0.1, 0.1))
        >>> Ensemble(BodySampler(tumble.t_handle(), (Dispersion("moments", 0.02),)), rates, cases=8).design
        Design(sampling='random', seed=0, cases=8, dims=6)
        """
        return Design(self.sampling, self.seed, self.cases, self.rates.dims + self.bodies.dims)

    @property
    def names(self) -> tuple[str, ...]:
        """Names of :attr:`CaseInputs.values`.

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble import BodySampler, Dispersion
        >>> from tumble.ensemble.cases import Ensemble, InitialRates
        >>> bodies = BodySampler(tumble.t_handle(), (Dispersion("preset", 0.05, field="shaft_length"),), preset="t-handle")
        >>> Ensemble(bodies, InitialRates(omega=(0.1, 5.0, 0.1)), cases=8).names
        ('shaft_length [m]',)
        """
        return self.bodies.names

    def inputs(self, start: int = 0, stop: int | None = None) -> CaseInputs:
        """The inputs of cases ``start`` to ``stop - 1`` (default: all).

        Raises
        ------
        ValueError
            For a range outside the sweep, or a case whose body draws were refused
            ``max_resamples + 1`` times in a row (naming the case and the last reason).

        Examples
        --------
        >>> import tumble
        >>> from tumble.ensemble import BodySampler, Dispersion
        >>> import numpy as np
        >>> from tumble.ensemble.cases import Ensemble, InitialRates
        >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
        >>> cases = Ensemble(BodySampler(box, (Dispersion("moments", 0.05),)), InitialRates(omega=(0.0, 1.0, 0.0)),
        ...                  cases=50, seed=3)
        >>> whole, chunk = cases.inputs(), cases.inputs(20, 27)
        >>> bool(np.array_equal(whole.moments[20:27], chunk.moments)), chunk.index.tolist()[:3]  # the same alone
        (True, [20, 21, 22])
        """
        stop = self.cases if stop is None else stop
        rows = self.design.rows(start, stop)
        index = np.arange(start, stop)
        m, k = len(index), self.rates.dims
        given = self.rates.rates(index, rows[:, :k])
        moments, axes = np.empty((m, 3)), np.empty((m, 3, 3))
        values, resampled = np.empty((m, len(self.names))), np.zeros(m, dtype=np.int64)
        fast = self.bodies.sample_many(self.bodies.deviates(rows[:, k:])) if m else None
        slow = np.arange(m) if fast is None else np.flatnonzero(~fast[3])
        if fast is not None:
            moments[:], axes[:], values[:] = fast[:3]
        for j in slow:  # a body drawn part by part, or a draw near a rule's edge: one by one
            drawn, resampled[j] = self._body(start + int(j), rows[j, k:])
            moments[j], axes[j], values[j] = drawn.moments, drawn.axes, drawn.values
        omega0 = np.einsum("nji,nj->ni", axes, given) if self.rates.frame == "design" else given
        quat0 = Rotation.from_matrix(axes).as_quat().reshape(m, 4) if m else np.empty((0, 4))
        return CaseInputs(index, moments, axes, omega0, quat0, values, resampled)

    def _body(self, index: int, u: np.ndarray):
        """Case ``index``'s body from its unit numbers ``u``, drawn again while unphysical."""
        rng = None
        for redraws in range(self.max_resamples + 1):
            try:
                return self.bodies.sample(self.bodies.deviates(u)), redraws
            except ValueError as exc:
                reason = " ".join(str(exc).split())
            rng = rng or self.design.generator(index)
            u = rng.random(self.bodies.dims)
        raise ValueError(f"case {index}: no physical body in {self.max_resamples + 1} draw(s) (last: {reason}); "
                         f"narrow the dispersions or raise max_resamples = {self.max_resamples}")
