"""Per-case results, not trajectories: what each case's motion did, in a few numbers.

:func:`reduce_cases` turns a chunk of cases (:class:`~tumble.ensemble.cases.CaseInputs`) and
their motions (:func:`tumble.dynamics.simulate_batch`) into columns, one value per case, the
same quantities :func:`tumble.analysis.stability_report` gives for one trajectory:

- the *spin axis* ``axis`` (1, 2, 3): the principal axis nearest the angular momentum at the
  start (the largest ``|I_j omega_j|``), and the axis omega circulates about, ``circulation``
  (1 or 3, from the energy and ``|L|``: 3 when ``L^2 >= 2 E I2``, Landau & Lifshitz sec. 37,
  :func:`tumble.analysis.circulation_axis`). ``predicted`` follows the motion: ``stable`` when
  the spin axis is the circulation axis (its component never changes sign: it stays on its side
  of L), ``unstable`` when it is not (it turns over, twice a period of omega; always so for axis 2
  of an asymmetric body); a sphere's spin is stable. ``growth_rate`` and ``wobble_frequency``
  are the linearised theory of a spin about that axis (:func:`tumble.analysis.linearised_rate`),
  given where it agrees with ``predicted`` (the one that does not apply is 0; both are NaN for a
  motion far from its axis, which turns over though the axis is 1 or 3). All four are the torque-free theory of the initial state;
- ``flips``: sign changes of the spin-axis component ``omega_axis`` over the samples, i.e.
  reversals of the spin axis relative to L (docs/conventions.md, "Flips"): 0 for a ``stable``
  torque-free case, 2 a period for an ``unstable`` one, whatever a torque does with one (a flip
  faster than the sampling is missed: sample a few times per flip); the measured mean time
  between flips (the first to the last crossing, linearly interpolated, over ``flips - 1``; as
  :func:`tumble.analysis.flip_times`); the exact interval (:func:`tumble.analysis.flip_interval`,
  elliptic K) for a torque-free asymmetric body whose spin axis turns over;
- the final omega (principal frame) and attitude (the *design* frame to world, a quaternion
  ``[x, y, z, w]`` with ``w >= 0``; the design frame starts aligned with the world);
- the largest nutation angle over the samples: the angle between L and the nearest major axis,
  as :attr:`tumble.Trajectory.nutation_angle`;
- ``energy_change`` ``(E(t_end) - E0) / E0`` and ``L_world_angle``, the angle (rad) between
  ``L_world`` at the end and at t = 0: round-off without a torque (the run's error), the
  torque's work and how far it turned the angular momentum with one.

:func:`stability_map` evaluates the flip interval and the circulation axis over the triangle
of inertia ratios for a perturbed spin about the intermediate axis.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy.spatial.transform import Rotation

from ..analysis import circulation_axis, energy_momentum_gaps, flip_interval, linearised_rate, spin_prediction
from ..dynamics.special.quaternion import rotate_by_quaternion
from ..mass import INERTIA_RTOL
from ..typing import ArrayLike
from ..validation import triangle_excess
from . import _display
from .cases import CaseInputs

if TYPE_CHECKING:
    from ..dynamics.batch import BatchTrajectory

__all__ = ["RESULT_COLUMNS", "StabilityMap", "input_columns", "nutation_angle", "reduce_cases", "stability_map"]

#: The result columns of :func:`reduce_cases` (after the inputs), with their units.
RESULT_COLUMNS = (
    "axis", "predicted", "growth_rate [1/s]", "wobble_frequency [rad/s]", "circulation", "flips",
    "flip_period [s]", "flip_period_exact [s]", "omega_end_1 [rad/s]", "omega_end_2 [rad/s]",
    "omega_end_3 [rad/s]", "q_end_x", "q_end_y", "q_end_z", "q_end_w", "max_nutation [rad]",
    "energy_change", "L_world_angle [rad]", "samples_per_flip",
)


def input_columns(inputs: CaseInputs, names: Sequence[str]) -> dict[str, np.ndarray]:
    """The inputs of each case as columns: ``case``, ``I1..I3 [kg m^2]``, ``omega0_1..3 [rad/s]``
    (principal frame), the drawn values (``names``) and ``resampled``.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Ensemble, InitialRates
    >>> from tumble.ensemble.reductions import input_columns
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    >>> inputs = Ensemble(BodySampler(box), InitialRates(omega=(0.01, 1.0, 0.01)), cases=3).inputs()
    >>> cols = input_columns(inputs, ())
    >>> list(cols)
    ['case', 'I1 [kg m^2]', 'I2 [kg m^2]', 'I3 [kg m^2]', 'omega0_1 [rad/s]', 'omega0_2 [rad/s]', 'omega0_3 [rad/s]', 'resampled']
    >>> cols["I3 [kg m^2]"].round(12).tolist()  # m (a^2 + b^2) / 12 of the box
    [13.0, 13.0, 13.0]
    """
    cols = {"case": inputs.index}
    cols.update({f"I{j + 1} [kg m^2]": inputs.moments[:, j] for j in range(3)})
    cols.update({f"omega0_{j + 1} [rad/s]": inputs.omega0[:, j] for j in range(3)})
    cols.update({name: inputs.values[:, k] for k, name in enumerate(names)})
    cols["resampled"] = inputs.resampled
    return cols


def nutation_angle(omega: ArrayLike, moments: ArrayLike) -> np.ndarray:
    """Angle between ``L = I omega`` and the nearest major axis, rad, in [0, pi/2].

    The rule of :attr:`tumble.Trajectory.nutation_angle`, for a batch: ``arctan(hypot(L1, L2) /
    |L3|)`` for ``I2 < I3``; for a prolate symmetric body (``I2 = I3`` within
    :data:`~tumble.mass.INERTIA_RTOL` of the trace) the angle to the plane of axes 2 and 3,
    ``arctan(|L1| / hypot(L2, L3))``; 0 for a sphere; NaN where L = 0.

    Parameters
    ----------
    omega : ndarray, shape (N, T, 3)
        Principal-frame angular velocities, rad/s.
    moments : ndarray, shape (N, 3)
        Ascending principal moments, kg m^2.

    Returns
    -------
    ndarray, shape (N, T)

    Examples
    --------
    >>> from tumble.ensemble.reductions import nutation_angle
    >>> omega = [[[0.0, 0.0, 2.0], [1.0, 0.0, 1.0]]]  # one case, two samples, rad/s
    >>> nutation_angle(omega, [[1.0, 2.0, 3.0]]).round(4).tolist()  # arctan(1 / 3) for L = (1, 0, 3)
    [[0.0, 0.3218]]
    """
    I = np.asarray(moments, float)[:, None, :]
    L = I * np.asarray(omega, float)
    tol = INERTIA_RTOL * np.sum(I, axis=-1)
    prolate = I[..., 2] - I[..., 1] <= tol
    sphere = I[..., 2] - I[..., 0] <= tol
    angle = np.where(prolate, np.arctan2(np.abs(L[..., 0]), np.hypot(L[..., 1], L[..., 2])),
                     np.arctan2(np.hypot(L[..., 0], L[..., 1]), np.abs(L[..., 2])))
    angle = np.where(sphere, 0.0, angle)
    return np.where(np.any(L != 0, axis=-1), angle, np.nan)


def _crossing(t, y, k) -> np.ndarray:
    """Time where ``y[n]`` changes sign between samples ``k[n]`` and ``k[n] + 1`` (linear)."""
    n = np.arange(len(y))
    y0, y1 = y[n, k], y[n, k + 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        return t[k] - y0 * (t[k + 1] - t[k]) / (y1 - y0)


def _flips(t, component) -> tuple[np.ndarray, np.ndarray]:
    """Number of sign changes of each row of ``component`` (N, T) and the mean time between
    them (NaN with fewer than two)."""
    change = np.signbit(component[:, :-1]) != np.signbit(component[:, 1:])
    flips = change.sum(axis=1)
    if change.shape[1] == 0:
        return flips, np.full(len(flips), np.nan)
    first = np.argmax(change, axis=1)
    last = change.shape[1] - 1 - np.argmax(change[:, ::-1], axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        period = (_crossing(t, component, last) - _crossing(t, component, first)) / (flips - 1)
    return flips, np.where(flips >= 2, period, np.nan)


def reduce_cases(inputs: CaseInputs, batch: BatchTrajectory, names: Sequence[str] = ()) -> dict[str, np.ndarray]:
    """The per-case columns of a chunk: its inputs (:func:`input_columns`) and results.

    Parameters
    ----------
    inputs : CaseInputs
        The chunk's m cases.
    batch : BatchTrajectory
        Their motions, from :func:`tumble.dynamics.simulate_batch` with ``inputs.moments``,
        ``inputs.omega0`` and ``attitude0=inputs.quat0``.
    names : sequence of str
        Names of ``inputs.values`` (:attr:`Ensemble.names`).

    Returns
    -------
    dict of str to ndarray, each of shape (m,)
        :func:`input_columns`, then :data:`RESULT_COLUMNS` (module docstring). ``predicted``
        holds strings; ``axis``, ``circulation`` and ``flips`` integers; a quantity that does
        not apply is NaN.

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Ensemble, InitialRates
    >>> import numpy as np
    >>> from tumble.ensemble.reductions import reduce_cases
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))  # moments 5, 10, 13 kg m^2
    >>> inputs = Ensemble(BodySampler(box), InitialRates(omega=(0.01, 1.0, 0.01)), cases=2).inputs()
    >>> batch = tumble.simulate_batch(inputs.moments, inputs.omega0, t_end=60.0, samples=600, attitude0=inputs.quat0)
    >>> cols = reduce_cases(inputs, batch)
    >>> cols["axis"].tolist(), cols["predicted"].tolist(), cols["flips"].tolist()
    ([2, 2], ['unstable', 'unstable'], [2, 2])
    >>> round(float(cols["growth_rate [1/s]"][0]), 4)  # sqrt((I2 - I1) (I3 - I2) / (I1 I3)) = sqrt(15 / 65)
    0.4804
    >>> bool(np.isclose(cols["flip_period [s]"][0], cols["flip_period_exact [s]"][0], rtol=1e-4))  # measured vs exact
    True
    """
    I, w0 = inputs.moments, inputs.omega0
    m = len(inputs)
    axis, circulation, stable, growth, wobble = spin_prediction(w0, I)  # axis 1 at rest
    tol = INERTIA_RTOL * np.sum(I, axis=1)
    asymmetric = (I[:, 1] - I[:, 0] > tol) & (I[:, 2] - I[:, 1] > tol)
    spin = batch.omega[np.arange(m), :, axis - 1]
    flips, period = _flips(batch.t, spin)
    at_rest = ~np.any(w0 != 0.0, axis=1)  # no spin axis: neither stable nor unstable (stability_report's None)
    free = flip_interval(w0, I)
    free = np.where(asymmetric & (axis != circulation) & np.isfinite(free) & ~at_rest, free, np.nan)
    exact = np.where(batch.torque_free, free, np.nan)
    # the flip interval (exact, else counted) over the widest sample spacing, as stability_report's: below
    # SAMPLES_PER_FLIP the flips counted are aliased (a walkthrough's 0.05 s flips at 0.067 s samples: 123 of 475).
    # Under a torque, the torque-free interval of the start too, the shorter of the two: aliased samples count
    # few sign changes, and no interval (a walkthrough's torqued T-handles at 2 samples: 9 of 16 "flipped", no
    # warning, where each flipped 10-13 times)
    spacing = float(np.max(np.diff(batch.t))) if len(batch.t) >= 2 else np.nan
    per_flip = np.where(np.isfinite(exact), exact, np.fmin(period, free)) / spacing
    end = Rotation.from_quat(batch.quat[:, -1]) * Rotation.from_matrix(inputs.axes).inv()
    E0 = 0.5 * np.sum(I * w0 * w0, axis=1)
    E1 = 0.5 * np.sum(I * batch.omega[:, -1] ** 2, axis=1)
    L0 = rotate_by_quaternion(inputs.quat0, I * w0)
    L1 = rotate_by_quaternion(batch.quat[:, -1], I * batch.omega[:, -1])
    with np.errstate(invalid="ignore", divide="ignore"):
        energy_change = np.where(E0 > 0, (E1 - E0) / E0, np.nan)
    turned = np.arctan2(np.linalg.norm(np.cross(L0, L1), axis=1), np.sum(L0 * L1, axis=1))
    cols = input_columns(inputs, names)
    results = [
        np.where(at_rest, 0, axis), np.where(at_rest, "at rest", np.where(stable, "stable", "unstable")), growth, wobble,
        np.where(at_rest, 0, circulation), flips, period, exact,
        *batch.omega[:, -1].T, *end.as_quat(canonical=True).reshape(m, 4).T,
        np.fmax.reduce(nutation_angle(batch.omega, I), axis=1), energy_change,
        np.where(np.any(L0 != 0, axis=1), turned, np.nan), per_flip,
    ]
    cols.update(zip(RESULT_COLUMNS, results))
    return cols


@dataclass(frozen=True, eq=False)
class StabilityMap:
    """Flip interval and circulation over the triangle of inertia ratios.

    Attributes
    ----------
    x : ndarray, shape (nx,)
        ``I1 / I3`` at the cell centres.
    y : ndarray, shape (ny,)
        ``I2 / I3`` at the cell centres.
    inside : ndarray of bool, shape (ny, nx)
        Points of a physical asymmetric body: ``x < y < 1`` and ``x + y > 1`` (the triangle
        inequality).
    flip_interval : ndarray, shape (ny, nx)
        Exact time between sign changes of omega_2, s (NaN outside).
    circulation : ndarray of int, shape (ny, nx)
        Axis omega circulates about, 1 (minor) or 3 (major); 0 outside.
    growth_rate : ndarray, shape (ny, nx)
        Linearised growth exponent of the intermediate-axis spin, 1/s (NaN outside).
    separatrix_gap : ndarray, shape (ny, nx)
        ``(L^2 - 2 E I2) / L^2``: positive where omega circulates about the major axis, 0 on
        the separatrix (NaN outside; :func:`tumble.analysis.energy_momentum_gaps`).
    omega0 : ndarray, shape (3,)
        The initial spin, rad/s, principal frame.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.reductions import stability_map
    >>> m = stability_map(10.0, resolution=40)
    >>> inside = m.inside
    >>> bool(np.all((m.separatrix_gap[inside] > 0) == (m.circulation[inside] == 3)))  # major axis above the separatrix
    True
    """

    x: np.ndarray
    y: np.ndarray
    inside: np.ndarray
    flip_interval: np.ndarray
    circulation: np.ndarray
    growth_rate: np.ndarray
    separatrix_gap: np.ndarray
    omega0: np.ndarray

    def __repr__(self) -> str:
        return _display.map_repr(self)

    def _repr_html_(self) -> str:
        return _display.map_html(self)


def stability_map(spin: float = 10.0, perturbation: tuple[float, float] = (0.01, 0.01), *, resolution: int = 200) -> StabilityMap:
    """Flip interval and circulation axis over ``(I1/I3, I2/I3)`` for a perturbed intermediate spin.

    The spin is ``omega0 = spin * (p1, 1, p3)`` (principal frame), the moments
    ``(x, y, 1) I3``: every quantity here is homogeneous of degree 0 in the moments, so the
    ratios decide it (:func:`tumble.analysis.flip_interval`, Landau & Lifshitz sec. 37). The
    triangle: ``0 < x <= y <= 1`` with ``x + y >= 1``; its edges are the planar bodies
    (``x + y = 1``), the oblate (``x = y``: a disc) and the prolate (``y = 1``: a rod) symmetric ones.

    Parameters
    ----------
    spin : float
        The spin about the intermediate axis, rad/s (> 0).
    perturbation : (float, float)
        ``(p1, p3)``: the components along the minor and major axes as fractions of ``spin``.
    resolution : int
        Cells along ``I1/I3`` (0 to 1); half as many along ``I2/I3`` (0.5 to 1). 10 to 2000.

    Returns
    -------
    StabilityMap

    Raises
    ------
    ValueError
        For a spin that is not a positive finite number, a perturbation that is not two finite
        numbers, or a resolution outside 10 to 2000.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.reductions import stability_map
    >>> m = stability_map(10.0, resolution=20)
    >>> m.flip_interval.shape, sorted(set(m.circulation[m.inside].tolist()))
    ((10, 20), [1, 3])
    >>> j, i = np.argwhere(m.inside)[0]
    >>> x, y = m.x[i], m.y[j]  # I1 / I3, I2 / I3
    >>> bool(np.isclose(m.growth_rate[j, i], 10.0 * np.sqrt((y - x) * (1.0 - y) / x)))
    True
    """
    if isinstance(spin, bool) or not isinstance(spin, (int, float, np.integer, np.floating)) or not (
            np.isfinite(spin) and spin > 0):
        raise ValueError(f"spin = {spin!r} must be a positive finite number (rad/s)")
    p = np.asarray(perturbation, dtype=float) if not isinstance(perturbation, (str, bytes)) else np.empty(0)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValueError(f"perturbation = {perturbation!r} must be two finite numbers (fractions of the spin)")
    if np.any(np.abs(p) >= 1.0):  # the map's title and its flips are those of a spin about the intermediate axis
        raise ValueError(f"perturbation = {perturbation!r} must be fractions of the spin below 1: the map is of a spin "
                         "about the intermediate axis, perturbed")
    if not np.any(p):
        raise ValueError(f"perturbation = {perturbation!r}: a spin exactly about the intermediate axis is an unstable "
                         f"equilibrium that never flips; give a small perturbation along the minor or the major axis")
    if isinstance(resolution, bool) or not isinstance(resolution, (int, np.integer)) or not 10 <= resolution <= 2000:
        raise ValueError(f"resolution = {resolution!r} must be a whole number from 10 to 2000")
    x = (np.arange(resolution) + 0.5) / resolution
    ny = resolution // 2
    y = 0.5 + 0.5 * (np.arange(ny) + 0.5) / ny
    X, Y = np.meshgrid(x, y)
    tol = INERTIA_RTOL * (X + Y + 1.0)  # two moments equal to round-off: a symmetric body, which has no
    # intermediate axis to flip about (the cells on the diagonal x = y had intervals of ~1e4 s, stretching the scale)
    inside = (Y - X > tol) & (1.0 - Y > tol) & (triangle_excess(np.stack([X, Y, np.ones_like(X)], axis=-1)) < 0.0)
    moments = np.stack([X[inside], Y[inside], np.ones(inside.sum())], axis=-1)
    w0 = float(spin) * np.array([p[0], 1.0, p[1]])
    interval, growth, gap = (np.full(X.shape, np.nan) for _ in range(3))
    circulation = np.zeros(X.shape, dtype=int)
    interval[inside] = flip_interval(w0, moments)
    circulation[inside] = circulation_axis(w0, moments)
    growth[inside] = linearised_rate(moments, 2, float(spin))[0]
    gap[inside] = energy_momentum_gaps(w0, moments)[:, 1] / np.sum((moments * w0) ** 2, axis=1)
    return StabilityMap(x, y, inside, interval, circulation, growth, gap, w0)
