"""The inverse problem from periods: the bodies and motions consistent with two observed periods.

A tumbling (non-principal-axis) body seen from afar, an asteroid's light curve say, shows two
periods, ``P_phi`` and ``P_psi`` (:func:`tumble.analysis.npa_periods`). They fix two of the four
numbers of a torque-free motion beyond the orientation of L; :func:`periods_consistent` finds
every inertia ratio pair, energy and momentum that gives them: a two-parameter family, not a
unique answer. From a gyroscope record instead: :func:`tumble.analysis.fit_rotation`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..typing import ArrayLike
from ..validation import triangle_excess
from . import _display
from .periods import npa_periods

__all__ = ["PeriodFamily", "periods_consistent"]

#: Most grid points along each ratio, and most angles per body.
MAX_RESOLUTION = 400
MAX_ANGLES = 20000
#: Most motions searched at once (bodies times angles, each a few arrays of doubles): about 1 GB.
MAX_MOTIONS = 10_000_000


@dataclass(frozen=True)
class PeriodFamily:
    """The torque-free motions whose two periods match an observed pair (:func:`periods_consistent`).

    Each row is one motion. Attributes: ``ratios`` (k, 2) ``I1/I3, I2/I3``; ``energy`` (k,) the
    dimensionless energy ``2 E I3 / |L|^2`` (from 1, a spin about the major axis, to ``I3/I1``,
    about the minor axis); ``L_over_I3`` (k,) ``|L| / I3``, rad/s (the angular speed of a spin
    about the major axis with the same momentum); ``mode`` (k,) ``"SAM"`` or ``"LAM"``.

    Examples
    --------
    >>> from tumble.analysis.periods import npa_periods
    >>> from tumble.analysis.period_inversion import periods_consistent
    >>> P_phi, P_psi, _ = npa_periods([0.3, 0.2, 1.0], [1.0, 2.0, 3.0])
    >>> family = periods_consistent(float(P_phi), float(P_psi), resolution=10)
    >>> family.ratios.shape[1], len(family.energy) == len(family.mode) == len(family.L_over_I3) > 0
    (2, True)
    """

    ratios: np.ndarray
    energy: np.ndarray
    L_over_I3: np.ndarray
    mode: np.ndarray

    def __repr__(self) -> str:
        return _display.family_repr(self)

    def _repr_html_(self) -> str:
        return _display.family_html(self)


def _periods_at(x, y, beta):
    """``(P_phi, P_psi, mode)`` at ``|L| = I3 = 1`` for the motion whose L crosses the body's
    1-3 plane at angle ``beta`` from the major axis (every motion crosses it once per half period)."""
    I = np.stack([x, y, np.ones_like(x)], axis=-1)
    w = np.stack([np.sin(beta) / x, np.zeros_like(x), np.cos(beta)], axis=-1)
    with np.errstate(all="ignore"):
        return npa_periods(w, I)


def periods_consistent(P_phi: float, P_psi: float, *, ratios: ArrayLike | None = None, resolution: int = 40,
                       angles: int = 400) -> PeriodFamily:
    """Inertia ratios, energies and momenta consistent with an observed pair of periods.

    A tumbling (non-principal-axis) body, e.g. an asteroid's light curve, shows two periods:
    ``P_phi``, the mean precession about L of the axis the body circulates about (the long
    axis in LAM, the short axis in SAM), and ``P_psi``, the period of the
    body-frame motion (definitions and conventions of :func:`tumble.analysis.npa_periods`).
    A torque-free motion has four free numbers beyond the orientation of L (``I1/I3``,
    ``I2/I3``, the dimensionless energy ``2 E I3 / |L|^2`` and ``|L| / I3``); two periods fix two
    of them. **The answer is not unique**: for every pair of ratios there are zero, one or more
    energies whose periods' quotient ``P_psi / P_phi`` is the observed one (in SAM, in LAM, or
    both), and ``|L| / I3`` then follows from the periods' scale. The ratios come only with a
    shape model (light-curve inversion, radar) or more data (amplitudes, the nutation angle).

    Parameters
    ----------
    P_phi, P_psi : float
        The observed periods, s, positive and finite.
    ratios : array_like, shape (k, 2), optional
        Solve only at these ``(I1/I3, I2/I3)`` (e.g. a shape model's); default a grid over the
        triangle of physical bodies with ``resolution`` points along ``I2/I3``.
    resolution : int
        Grid points along each ratio (default grid only).
    angles : int
        Points along the family of polhodes of each body where the periods' quotient is
        bracketed; the roots are then refined by regula falsi (the Illinois variant).

    Returns
    -------
    PeriodFamily
        Every solution found, one per row (empty when none).

    Notes
    -----
    At ``|L| = I3 = 1`` each motion of a body is labelled by the angle ``beta`` between L and the
    major axis where L crosses the body's 1-3 plane (``omega = (sin beta / (I1/I3), 0, cos beta)``):
    ``beta`` from 0 to pi/2 covers SAM, the separatrix and LAM. The quotient ``P_psi / P_phi``
    is computed on a grid of ``beta`` with :func:`tumble.analysis.npa_periods`, its crossings
    of the observed quotient bracketed and refined; ``|L| / I3 = P_psi(beta; |L| = 1) / P_psi``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.periods import npa_periods
    >>> from tumble.analysis.period_inversion import periods_consistent
    >>> P_phi, P_psi, _ = npa_periods([0.3, 0.2, 1.0], [1.0, 2.0, 3.0])   # a body with I1/I3 = 1/3, I2/I3 = 2/3
    >>> family = periods_consistent(float(P_phi), float(P_psi), ratios=[[1 / 3, 2 / 3]])
    >>> bool(np.any(np.isclose(family.L_over_I3, np.linalg.norm([0.3, 0.4, 3.0]) / 3.0, rtol=1e-6)))   # |L| / I3 found again
    True
    """
    try:
        P_phi, P_psi = float(P_phi), float(P_psi)
    except (TypeError, ValueError):
        raise ValueError(f"periods P_phi = {P_phi!r}, P_psi = {P_psi!r} must be positive and finite (s)") from None
    if not (np.isfinite(P_phi) and np.isfinite(P_psi) and P_phi > 0 and P_psi > 0):
        raise ValueError(f"periods P_phi = {P_phi}, P_psi = {P_psi} must be positive and finite (s)")
    for name, value, low, high in (("resolution", resolution, 1, MAX_RESOLUTION), ("angles", angles, 2, MAX_ANGLES)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
            raise ValueError(f"{name} = {value!r} must be a whole number from {low} to {high}")
    bodies = resolution ** 2 if ratios is None else np.size(ratios) // 2
    if bodies * angles > MAX_MOTIONS:
        raise ValueError(f"{bodies} bodies x angles = {angles} is {bodies * angles} motions, more than "
                         f"{MAX_MOTIONS:,} at once: lower resolution or angles")
    if ratios is None:
        y = np.linspace(0.5, 1.0, resolution + 2)[1:-1]
        f = np.linspace(0.0, 1.0, resolution + 2)[1:-1]
        Y, F = np.meshgrid(y, f, indexing="ij")
        xy = np.stack([(1.0 - Y + (2 * Y - 1) * F).ravel(), Y.ravel()], axis=1)
    else:
        xy = np.asarray(ratios, float).reshape(-1, 2)
        bad = np.flatnonzero(~((xy[:, 0] > 0) & (xy[:, 0] < xy[:, 1]) & (xy[:, 1] < 1.0)
                               & (triangle_excess(np.column_stack([xy, np.ones(len(xy))])) <= 0.0)))
        if bad.size:
            raise ValueError(f"ratios[{bad[0]}] = {xy[bad[0]].tolist()} must satisfy 0 < I1/I3 < I2/I3 < 1 and "
                             "I1/I3 + I2/I3 >= 1")
    target = P_psi / P_phi
    beta = np.linspace(0.0, 0.5 * np.pi, angles + 2)[1:-1]
    X, B = np.meshgrid(xy[:, 0], beta, indexing="ij")
    Yg = np.broadcast_to(xy[:, 1:2], X.shape)
    pphi, ppsi, _ = _periods_at(X, Yg, B)
    g = ppsi / pphi - target
    ok = np.isfinite(g[:, :-1]) & np.isfinite(g[:, 1:])
    i, j = np.nonzero(ok & (np.sign(g[:, :-1]) != np.sign(g[:, 1:])))
    # the quotient jumps at the separatrix (P_psi -> inf): keep brackets where it is continuous
    lo, hi = B[i, j], B[i, j + 1]
    glo, ghi = g[i, j], g[i, j + 1]
    xs, ys = xy[i, 0], xy[i, 1]
    for _ in range(40):  # regula falsi, the retained end's value halved (Illinois)
        b = hi - ghi * (hi - lo) / (ghi - glo)
        pp, ps, _ = _periods_at(xs, ys, b)
        gb = ps / pp - target
        left = np.sign(gb) == np.sign(glo)  # the root lies in [b, hi]
        lo, glo, hi, ghi = (np.where(left, b, lo), np.where(left, gb, 0.5 * glo),
                            np.where(left, hi, b), np.where(left, 0.5 * ghi, gb))
    b = np.where(np.abs(glo) < np.abs(ghi), lo, hi)
    pp, ps, mode = _periods_at(xs, ys, b)
    keep = np.isfinite(ps) & (np.abs(ps / pp - target) < 1e-9 * max(1.0, abs(target)))
    xs, ys, b, ps, mode = xs[keep], ys[keep], b[keep], ps[keep], mode[keep]
    w1, w3 = np.sin(b) / xs, np.cos(b)
    return PeriodFamily(ratios=np.stack([xs, ys], axis=1), energy=xs * w1 ** 2 + w3 ** 2,
                        L_over_I3=ps / P_psi, mode=np.asarray(mode, str))
