"""Gravity-gradient stability: which bodies rest stably in the orbiting (LVLH) frame.

The orbit, the orbiting frame and a body's roll, pitch and yaw axes are those of
:mod:`tumble.dynamics.models.gravity` (the torque model and the frame); this module classifies
the linear stability of a body at rest in that frame.

**Gravity-gradient ratios** (Hughes, *Spacecraft Attitude Dynamics*, Wiley 1986, ch. 9,
gravitational stabilization; DeBra & Delp, J. Astronaut. Sci. 8 (1961) 14):
``k_R = (I_pitch - I_yaw) / I_roll``, ``k_P = (I_roll - I_yaw) / I_pitch``,
``k_Y = (I_pitch - I_roll) / I_yaw`` (dimensionless; :func:`gravity_gradient_ratios`). They are
not the body's moment ratios ``(I1/I3, I2/I3)`` used elsewhere in tumble. The linearised
equations (in units of the mean motion n, rad/s; derived for this frame in
docs/gravity-gradient.md) are

- pitch: ``theta'' + 3 n^2 k_P theta = 0``, stable iff ``k_P > 0`` (``I_roll > I_yaw``;
  ``k_P (1 - k_R k_Y) = k_R - k_Y``, so ``k_R > k_Y`` but at the corners ``k_R = k_Y = +-1``),
- roll-yaw: ``s^4 + (1 + 3 k_R + k_R k_Y) n^2 s^2 + 4 k_R k_Y n^4 = 0``, stable iff
  ``k_R k_Y > 0`` and ``1 + 3 k_R + k_R k_Y > 4 sqrt(k_R k_Y)``.

Both hold in the Lagrange region (``k_R > k_Y > 0``: ``I_pitch > I_roll > I_yaw``, where the
orbiting-frame energy is a minimum) and in the DeBra-Delp region (``k_Y < k_R < 0``, near
``k_R = 0``: stable only by the gyroscopic coupling of roll and yaw).

A body symmetric about one of the three axes (two equal moments, within ``1e-9`` of the trace as
docs/conventions.md counts them; the ratio of that axis exactly 0) has no torque that turns it
about that axis: a root ``s = 0`` there, neither stable nor unstable in the strict sense, and
nothing physical either, as the turn leaves the body where it was. Where the rest is stable
(a boom along the vertical, ``I_pitch = I_roll > I_yaw``; a disk with its face to the orbit
normal, ``I_pitch > I_roll = I_yaw``; or to the velocity, ``I_roll > I_pitch = I_yaw``; a sphere)
the region is ``"symmetric"``: stable but for a free turn about its symmetry axis.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..dynamics.euler import energy_momentum_gaps
from ..dynamics.models.gravity import rpy_axes
from ..typing import ArrayLike
from ..validation import INERTIA_RTOL, check_moments, check_vectors, refuse_first
from . import _display

__all__ = [
    "FREE_BODY_SPIN",
    "RATIO_ATOL",
    "SEPARATRIX_REACH",
    "STABILITY_REGIONS",
    "StabilityClass",
    "gravity_gradient_ratios",
    "gravity_gradient_stability",
    "separatrix_offset",
    "spin_beside_orbit",
]


def gravity_gradient_ratios(moments: ArrayLike, *, pitch_axis: int | str = 3, yaw_axis: int | str = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The gravity-gradient ratios ``(k_R, k_P, k_Y)`` of bodies whose pitch and yaw axes are given.

    ``k_R = (I_pitch - I_yaw) / I_roll``, ``k_P = (I_roll - I_yaw) / I_pitch``,
    ``k_Y = (I_pitch - I_roll) / I_yaw`` (Hughes ch. 9; module docstring).

    Parameters
    ----------
    moments : array_like, shape (..., 3)
        Principal moments ``I1 <= I2 <= I3``, kg m^2.
    pitch_axis, yaw_axis : {1, 2, 3, "minor", "intermediate", "major"}
        Principal axes along the orbit normal and the local vertical
        (:func:`tumble.dynamics.models.gravity.rpy_axes`); the third is the roll axis.

    Returns
    -------
    tuple of three ndarrays, shape (...)
        ``k_R``, ``k_P``, ``k_Y``, dimensionless, each in [-1, 1] for a real body.

    Examples
    --------
    >>> from tumble.analysis.gravity_stability import gravity_gradient_ratios
    >>> k_roll, k_pitch, k_yaw = gravity_gradient_ratios([1.0, 2.0, 2.5])  # roll 2, pitch 2.5, yaw 1
    >>> float(k_roll), float(k_pitch), float(k_yaw)   # (2.5 - 1) / 2, (2 - 1) / 2.5, (2.5 - 2) / 1
    (0.75, 0.4, 0.5)
    >>> float(gravity_gradient_ratios([1.0, 10.0, 10.0 + 5e-9])[2])   # moments equal within 1e-9 of the trace
    0.0
    """
    I = check_moments("moments", moments)
    (a, b, c), _ = rpy_axes(pitch_axis, yaw_axis)
    Ir, Ip, Iy = I[..., a], I[..., b], I[..., c]
    equal = INERTIA_RTOL * np.sum(I, axis=-1)  # two moments this close are one (docs/conventions.md): a ratio 0
    Ir = np.where(np.abs(Ip - Ir) <= equal, Ip, Ir)  # made equal, not only their ratio zeroed: the three stay one body's
    Iy = np.where(np.abs(Ip - Iy) <= equal, Ip, Iy)
    Iy = np.where(np.abs(Ir - Iy) <= equal, Ir, Iy)
    return (Ip - Iy) / Ir, (Ir - Iy) / Ip, (Ip - Ir) / Iy


class StabilityClass(NamedTuple):
    """Linear stability about the orbiting frame (see :func:`gravity_gradient_stability`).

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.gravity_stability import gravity_gradient_ratios, gravity_gradient_stability
    >>> moments = tumble.t_handle().principal_moments
    >>> cls = gravity_gradient_stability(*gravity_gradient_ratios(moments))   # pitch about the major axis
    >>> bool(cls.pitch), bool(cls.roll_yaw), str(cls.region)
    (True, True, 'lagrange')
    >>> cls = gravity_gradient_stability(*gravity_gradient_ratios(moments, pitch_axis=2))   # about the intermediate
    >>> bool(cls.pitch), bool(cls.roll_yaw), str(cls.region)
    (True, False, 'roll-yaw unstable')
    """

    #: Pitch stable: ``k_P > 0`` (``I_roll > I_yaw``).
    pitch: np.ndarray
    #: Roll-yaw stable: ``k_R k_Y > 0`` and ``1 + 3 k_R + k_R k_Y > 4 sqrt(k_R k_Y)``.
    roll_yaw: np.ndarray
    #: One of :data:`STABILITY_REGIONS`.
    region: np.ndarray

    def __repr__(self) -> str:
        return _display.regions_repr(self)

    def _repr_html_(self) -> str:
        return _display.regions_html(self)


#: The names :func:`gravity_gradient_stability` gives a region: both stable with ``k_R > 0``,
#: both stable with ``k_R < 0``, one of the two unstable, both unstable, and stable but for a
#: free turn about a symmetry axis (module docstring).
STABILITY_REGIONS = ("lagrange", "debra-delp", "pitch unstable", "roll-yaw unstable", "unstable", "symmetric")
#: How far ``k_P (1 - k_R k_Y)`` may be from ``k_R - k_Y`` for three ratios of one body.
RATIO_ATOL = 1e-9


def gravity_gradient_stability(k_roll: ArrayLike, k_pitch: ArrayLike, k_yaw: ArrayLike) -> StabilityClass:
    """Linear stability of a body at rest in the orbiting frame, from its gravity-gradient ratios.

    The conditions (Hughes ch. 9; DeBra & Delp 1961; derived for this frame in
    docs/gravity-gradient.md): pitch ``k_P > 0``; roll-yaw ``k_R k_Y > 0`` and
    ``1 + 3 k_R + k_R k_Y > 4 sqrt(k_R k_Y)``. Strict inequalities: a boundary point counts as
    unstable, but where a ratio is exactly 0 (a symmetry axis: :func:`gravity_gradient_ratios`
    makes it so for moments equal within ``1e-9`` of the trace) and the other motions are stable,
    the region is ``"symmetric"`` (module docstring). Stable in both with ``k_R > 0`` is the
    Lagrange region (``I_pitch > I_roll > I_yaw``), with ``k_R < 0`` the DeBra-Delp region.
    ``gravity_gradient_stability(*gravity_gradient_ratios(moments))`` classifies bodies.

    Parameters
    ----------
    k_roll, k_pitch, k_yaw : float or array_like
        ``k_R = (I_pitch - I_yaw) / I_roll``, ``k_P = (I_roll - I_yaw) / I_pitch``,
        ``k_Y = (I_pitch - I_roll) / I_yaw`` (:func:`gravity_gradient_ratios`), each in [-1, 1] for a
        real body (triangle inequality), broadcasting together. One body's ratios satisfy
        ``k_P (1 - k_R k_Y) = k_R - k_Y`` (checked to :data:`RATIO_ATOL`), so ``k_P`` has the
        sign of ``k_R - k_Y`` except at the corner ``k_R = k_Y = 1`` (planar bodies with
        ``I_pitch = I_roll + I_yaw``), where ``k_R`` and ``k_Y`` alone do not decide pitch (the
        other corner, ``-1``, would need ``I_pitch = 0``).

    Returns
    -------
    StabilityClass
        Boolean arrays ``pitch``, ``roll_yaw`` and the string array ``region``.

    Raises
    ------
    ValueError
        Naming the ratio and its value: outside [-1, 1], not finite, not broadcasting, or
        ``k_pitch`` not belonging with ``k_roll`` and ``k_yaw``.

    Examples
    --------
    >>> from tumble.analysis.gravity_stability import gravity_gradient_ratios, gravity_gradient_stability
    >>> cls = gravity_gradient_stability(*gravity_gradient_ratios([2.0, 3.0, 4.0]))  # pitch major, yaw minor
    >>> bool(cls.pitch), bool(cls.roll_yaw), str(cls.region)
    (True, True, 'lagrange')
    >>> str(gravity_gradient_stability(*gravity_gradient_ratios([2.25, 87.32, 87.32])).region)  # a boom, yaw minor
    'symmetric'
    """
    ks = {name: check_vectors(name, k, "dimensionless", size=None)
          for name, k in (("k_roll", k_roll), ("k_pitch", k_pitch), ("k_yaw", k_yaw))}
    for name, k in ks.items():  # a planar body's ratio is 1 but may round to 1 + 2e-16 (gravity_gradient_ratios)
        refuse_first(name, k, np.abs(k) > 1.0 + RATIO_ATOL, "must be from -1 to 1 (the triangle inequality of the moments)")
        ks[name] = np.clip(k, -1.0, 1.0)
    try:
        kr, kp, ky = np.broadcast_arrays(*ks.values())
    except ValueError:
        shapes = ", ".join(f"{name} (shape {k.shape})" for name, k in ks.items())
        raise ValueError(f"{shapes} must broadcast together") from None
    off = np.abs(kp * (1.0 - kr * ky) - (kr - ky)) > RATIO_ATOL
    if np.any(off):
        i = tuple(int(j) for j in np.argwhere(off)[0])
        raise ValueError(
            f"k_pitch{list(i) if i else ''} = {float(kp[i])!r} does not belong with k_roll = {float(kr[i])!r} "
            f"and k_yaw = {float(ky[i])!r}: one body has k_pitch (1 - k_roll k_yaw) = k_roll - k_yaw (use gravity_gradient_ratios)"
        )
    pitch = kp > 0
    prod = kr * ky
    roll_yaw = (prod > 0) & (1.0 + 3.0 * kr + prod > 4.0 * np.sqrt(np.maximum(prod, 0.0)))
    # free about a symmetry axis, the rest stable: yaw (a boom) or roll with pitch stable (the roll-yaw
    # equation then s^2 (s^2 + 1 + 3 k_R) = 0 or s^2 (s^2 + 1) = 0), pitch with roll-yaw stable, or all (a sphere)
    free_pitch = (kp == 0.0) & (roll_yaw | ((kr == 0.0) & (ky == 0.0)))
    symmetric = (pitch & (((ky == 0.0) & (1.0 + 3.0 * kr > 0.0)) | (kr == 0.0))) | free_pitch
    region = np.select(
        [symmetric, pitch & roll_yaw & (kr > 0), pitch & roll_yaw, ~pitch & roll_yaw, pitch & ~roll_yaw],
        [STABILITY_REGIONS[5], *STABILITY_REGIONS[:4]], default=STABILITY_REGIONS[4],
    )
    return StabilityClass(pitch, roll_yaw, region)


#: Most ratio of the gravity gradient's torque beside a spin's gyroscopic terms, ``3 (n / omega)^2``
#: (Hughes, *Spacecraft Attitude Dynamics*, 1986, sec. 8.1), to the spin's :func:`separatrix_offset`
#: at which a run follows the free body's flips. Near the separatrix the flip interval goes as
#: ``ln(1 / offset)`` (Landau & Lifshitz, *Mechanics*, sec. 37), and the gradient moves the offset.
#: Measured on the T-handle in a 5,400 s orbit over 60,000 s (benchmarks/results/gravity_free_body.md),
#: the mean flip interval against the free body's closed form: at a ratio of 1-9, 0.2-2 % off; 38, 5 %;
#: 100, 10 %; 940 (spun at 10 n, 0.01 rad from the intermediate axis), 31 %.
SEPARATRIX_REACH = 10.0


def separatrix_offset(moments: ArrayLike, omega: ArrayLike) -> float | None:
    """How far a free body's spin ``omega`` (rad/s, principal frame) lies from the separatrix,
    relative: ``|2 T I2 - L^2| / L^2 = |sum_i I_i (I2 - I_i) omega_i^2| / L^2`` (0 on it; the
    polhodes through the intermediate axis, Landau & Lifshitz, *Mechanics*, sec. 37). None for a
    body with two equal moments (no separatrix) or a spin of 0.

    Examples
    --------
    >>> from tumble.analysis.gravity_stability import separatrix_offset
    >>> round(separatrix_offset([1.0, 2.0, 3.0], [0.01, 1.0, 0.01]), 10)   # |1 * 1 - 3 * 1| 1e-4 / (4 + 1e-3)
    4.99875e-05
    >>> separatrix_offset([1.0, 2.0, 2.0], [0.0, 1.0, 0.0]) is None
    True
    """
    I, w = np.asarray(moments, float), np.asarray(omega, float)
    L2 = float(np.sum((I * w) ** 2))
    if L2 == 0.0 or min(I[1] - I[0], I[2] - I[1]) <= INERTIA_RTOL * float(np.sum(I)):
        return None
    return abs(float(energy_momentum_gaps(w, I)[1])) / L2  # L^2 - 2 E I2, without cancellation


#: Least spin, in units of the orbit's mean motion ``n`` (``|omega0| / n``), at which a run under the
#: gravity gradient follows the free body's prediction for its initial spin. The gradient's torque is
#: of order ``3 n^2 (I_k - I_j)`` (Hughes, *Spacecraft Attitude Dynamics*, 1986, sec. 8.1), against
#: the gyroscopic ``omega^2 (I_k - I_j)`` of Euler's equations: 3 % of it at ten times the orbit rate.
#: Measured on the T-handle spun near its intermediate axis (60,000 s in a 5,400 s orbit), the mean
#: flip interval against the free body's closed form: 1.5 % off at 10 n, 4 % at 5 n, 9 % at 2 n,
#: 35 % at n; tumble simulate said "predicted unstable" of all of them alike.
FREE_BODY_SPIN = 10.0


def spin_beside_orbit(moments: ArrayLike, omega0: ArrayLike, mean_motion: float) -> dict[str, float | bool | None]:
    """A run's initial spin ``omega0`` (rad/s) against the orbit's ``mean_motion`` (rad/s), as its
    summary gives it: ``spin_over_n`` (``|omega0| / n``), ``separatrix_offset`` (:func:`separatrix_offset`)
    and ``free_body``, whether the free body's flips say what the run does: the spin at least
    :data:`FREE_BODY_SPIN` times ``n``, and the gradient's ``3 (n / omega)^2`` at most
    :data:`SEPARATRIX_REACH` times the offset (a walkthrough of docs/gravity-gradient.md,
    2026-12-03: a T-handle spun at 10 n, 0.01 rad from its intermediate axis, was called a free
    body and flipped 31 % faster than one).

    Examples
    --------
    >>> import math
    >>> from tumble.analysis.gravity_stability import spin_beside_orbit
    >>> n = 2 * math.pi / 5400.0
    >>> spin_beside_orbit([1.0, 2.0, 3.0], [0.25 * 10 * n, 10 * n, 0.0], n)["free_body"]
    True
    >>> out = spin_beside_orbit([1.0, 2.0, 3.0], [0.01 * 10 * n, 10 * n, 0.01 * 10 * n], n)
    >>> round(out["spin_over_n"], 3), out["free_body"]   # 3 % of the gyroscopic terms, but 5e-5 from the separatrix
    (10.001, False)
    """
    spin = float(np.linalg.norm(omega0)) / mean_motion
    off = separatrix_offset(moments, omega0)
    follows = spin >= FREE_BODY_SPIN * (1.0 - 1e-12) and (off is None or 3.0 / spin**2 <= SEPARATRIX_REACH * off)  # 10 n as written
    return {"spin_over_n": spin, "free_body": follows, "separatrix_offset": off}
