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
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..dynamics.models.gravity import rpy_axes
from ..typing import ArrayLike
from ..validation import check_moments, check_vectors, refuse_first
from . import _display

__all__ = [
    "RATIO_ATOL",
    "STABILITY_REGIONS",
    "StabilityClass",
    "gravity_gradient_ratios",
    "gravity_gradient_stability",
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
    """
    I = check_moments("moments", moments)
    (a, b, c), _ = rpy_axes(pitch_axis, yaw_axis)
    Ir, Ip, Iy = I[..., a], I[..., b], I[..., c]
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
#: both stable with ``k_R < 0``, one of the two unstable, both unstable.
STABILITY_REGIONS = ("lagrange", "debra-delp", "pitch unstable", "roll-yaw unstable", "unstable")
#: How far ``k_P (1 - k_R k_Y)`` may be from ``k_R - k_Y`` for three ratios of one body.
RATIO_ATOL = 1e-9


def gravity_gradient_stability(k_roll: ArrayLike, k_pitch: ArrayLike, k_yaw: ArrayLike) -> StabilityClass:
    """Linear stability of a body at rest in the orbiting frame, from its gravity-gradient ratios.

    The conditions (Hughes ch. 9; DeBra & Delp 1961; derived for this frame in
    docs/gravity-gradient.md): pitch ``k_P > 0``; roll-yaw ``k_R k_Y > 0`` and
    ``1 + 3 k_R + k_R k_Y > 4 sqrt(k_R k_Y)``. Strict inequalities: a boundary point counts as
    unstable. Stable in both with ``k_R > 0`` is the Lagrange region (``I_pitch > I_roll >
    I_yaw``), with ``k_R < 0`` the DeBra-Delp region. ``gravity_gradient_stability(
    *gravity_gradient_ratios(moments))`` classifies bodies.

    Parameters
    ----------
    k_roll, k_pitch, k_yaw : float or array_like
        ``k_R = (I_pitch - I_yaw) / I_roll``, ``k_P = (I_roll - I_yaw) / I_pitch``,
        ``k_Y = (I_pitch - I_roll) / I_yaw`` (:func:`gravity_gradient_ratios`), each in [-1, 1] for a
        real body (triangle inequality), broadcasting together. One body's ratios satisfy
        ``k_P (1 - k_R k_Y) = k_R - k_Y`` (checked to :data:`RATIO_ATOL`), so ``k_P`` has the
        sign of ``k_R - k_Y`` except at the corners ``k_R = k_Y = +-1`` (planar bodies, e.g.
        ``I_pitch = I_roll + I_yaw``), where ``k_R`` and ``k_Y`` alone do not decide pitch.

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
    """
    ks = {name: check_vectors(name, k, "dimensionless", size=None)
          for name, k in (("k_roll", k_roll), ("k_pitch", k_pitch), ("k_yaw", k_yaw))}
    for name, k in ks.items():
        refuse_first(name, k, np.abs(k) > 1.0, "must be from -1 to 1 (the triangle inequality of the moments)")
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
    region = np.select(
        [pitch & roll_yaw & (kr > 0), pitch & roll_yaw, ~pitch & roll_yaw, pitch & ~roll_yaw],
        list(STABILITY_REGIONS[:4]), default=STABILITY_REGIONS[4],
    )
    return StabilityClass(pitch, roll_yaw, region)
