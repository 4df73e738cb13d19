"""A tossed body's principal moments and the flat plate the air drags on: :class:`TossBody`, the
bodies of the synthetic recordings (:data:`TOSS_BODIES`) and the strip-theory drag on the plate
(:func:`plate_drag_torque`), for :func:`tumble.analysis.fit.synthetic.synthetic_recording`.

A plate's drag coefficient broadside to the flow is about 1.17 whatever its shape: 1.17 for a
circular disk and for a square plate, a little more for long rectangles (Hoerner,
*Fluid-Dynamic Drag*, 1965, ch. 3, "flat plates normal to the flow"): :data:`PLATE_DRAG_COEFFICIENT`,
the default, with a phone's face, :data:`PHONE_SIZE`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ...typing import ArrayLike

__all__ = ["PHONE_SIZE", "PLATE_DRAG_COEFFICIENT", "RHO_AIR", "TOSS_BODIES", "TossBody", "plate_drag_force",
           "plate_drag_torque"]

#: Density of air at 20 C and sea level, kg/m^3.
RHO_AIR = 1.204
#: A flat plate's drag coefficient broadside to the flow (Hoerner 1965, ch. 3; module docstring).
PLATE_DRAG_COEFFICIENT = 1.17
#: A large phone's face, length and width, m (158 x 77 mm; 8 mm thick and 0.19 kg in :data:`TOSS_BODIES`).
PHONE_SIZE = (0.158, 0.077)


@dataclass(frozen=True)
class TossBody:
    """A body to toss: principal moments (kg m^2, ascending) and its drag plate.

    The plate lies in the principal 1-2 plane, ``length`` along axis 1 and ``width`` along
    axis 2 (m), with a normal-force coefficient ``drag_coefficient`` (dimensionless): each element
    of it is pushed back by ``0.5 rho C_D v_n^2`` per unit area (:func:`plate_drag_torque`). The
    defaults are a phone's: its face, :data:`PHONE_SIZE` (158 x 77 mm), and a flat plate's
    coefficient broadside to the flow, :data:`PLATE_DRAG_COEFFICIENT` (1.17, Hoerner 1965). Give
    another body its own largest face (a book's cover, a racquet's head) and a smaller coefficient
    when its face is open or rounded (Brody's racquet in :data:`TOSS_BODIES`: 0.48, the value that
    gives a measured torque); :meth:`box` makes a uniform box with its largest face as the plate.

    Parameters
    ----------
    name : str
    moments : tuple of 3 float
        Principal moments, kg m^2, ascending and positive.
    length, width : float
        The plate's sides along principal axes 1 and 2, m (default a phone's, :data:`PHONE_SIZE`).
    drag_coefficient : float
        ``C_D`` of the plate, >= 0 (default :data:`PLATE_DRAG_COEFFICIENT`; 0: no air).

    Examples
    --------
    A phone-sized body needs only its moments:

    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES, TossBody, plate_drag_torque
    >>> mine = TossBody("my phone", (2.4e-4, 4.0e-4, 6.3e-4))
    >>> phone = TOSS_BODIES["phone"]
    >>> (mine.length, mine.width, mine.drag_coefficient) == (phone.length, phone.width, phone.drag_coefficient)
    True
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> synthetic_recording(1, body=mine, tosses=2).ratios.round(3).tolist()   # its tosses, with a phone's drag
    [0.381, 0.635]
    >>> TossBody("upside down", (6.3e-4, 4.0e-4, 2.4e-4))
    Traceback (most recent call last):
    ...
    ValueError: TossBody 'upside down': moments = (0.00063, 0.0004, 0.00024) must be three positive principal moments, kg m^2, ascending
    >>> racquet = TOSS_BODIES["racquet"]
    >>> I1, I2, I3 = racquet.moments
    >>> round((I1 + I2) / I3, 3)   # near-planar: I1 + I2 = I3 within 0.6 %
    1.006
    >>> card = TossBody("card", (1e-5, 2e-5, 3e-5), 0.09, 0.06, 1.17)   # a 9 x 6 cm plate
    >>> round(float(plate_drag_torque(card, [0.0, 10.0, 0.0])[1] / plate_drag_torque(card, [0.0, 5.0, 0.0])[1]), 6)   # quadratic
    4.0
    """

    name: str
    moments: tuple[float, ...]
    length: float = PHONE_SIZE[0]
    width: float = PHONE_SIZE[1]
    drag_coefficient: float = PLATE_DRAG_COEFFICIENT

    def __post_init__(self) -> None:
        moments = tuple(float(m) for m in self.moments)
        valid = all(math.isfinite(m) and m > 0 for m in moments) and list(moments) == sorted(moments)
        if len(moments) != 3 or not valid:
            raise ValueError(f"TossBody {self.name!r}: moments = {self.moments!r} must be three positive principal "
                             "moments, kg m^2, ascending")
        for key in ("length", "width"):
            if not (math.isfinite(getattr(self, key)) and getattr(self, key) > 0):
                raise ValueError(f"TossBody {self.name!r}: {key} = {getattr(self, key)!r} must be a positive "
                                 "length, m")
        if not (math.isfinite(self.drag_coefficient) and self.drag_coefficient >= 0):
            raise ValueError(f"TossBody {self.name!r}: drag_coefficient = {self.drag_coefficient!r} must be >= 0")
        object.__setattr__(self, "moments", moments)

    @classmethod
    def box(cls, name: str, mass: float, length: float, width: float, thickness: float,
            drag_coefficient: float = PLATE_DRAG_COEFFICIENT) -> TossBody:
        """A uniform box of ``mass`` kg and sides ``length >= width >= thickness`` (m) along
        principal axes 1, 2, 3, its largest face the plate.

        Examples
        --------
        >>> from tumble.analysis.fit.synthetic import TOSS_BODIES, TossBody
        >>> TossBody.box("phone", 0.19, 0.158, 0.077, 0.008) == TOSS_BODIES["phone"]
        True
        >>> [round(m * 1e4, 2) for m in TossBody.box("book", 0.6, 0.24, 0.17, 0.03).moments]   # kg m^2 x 1e4
        [14.9, 29.25, 43.25]
        """
        if not length >= width >= thickness > 0:
            raise ValueError(f"TossBody.box {name!r}: sides {length!r} >= {width!r} >= {thickness!r} > 0 (m) needed")
        return cls(name, _box(mass, length, width, thickness), length, width, drag_coefficient)


def _box(m: float, a: float, b: float, c: float) -> tuple[float, ...]:
    """Moments of a solid box (kg, m), ascending (a >= b >= c along axes 1, 2, 3)."""
    return tuple(sorted((m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)))


#: Brody's racquet (Ashbaugh, Chicone & Cushman 1991, footnote 4; I1 + I2 = I3 within 0.6 %),
#: drag tuned to 0.05 N m at 10 rad/s about axis 2; a 0.19 kg phone of 158 x 77 x 8 mm.
TOSS_BODIES = {
    "racquet": TossBody("racquet", (0.00121, 0.01638, 0.01748), 0.68, 0.26, 0.48),
    "phone": TossBody.box("phone", 0.19, *PHONE_SIZE, 0.008),
}

_GAUSS = np.polynomial.legendre.leggauss(8)


@functools.lru_cache(maxsize=64)
def _plate_points(length: float, width: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The plate's Gauss-Legendre points ``U`` (along axis 1), ``V`` (axis 2), m, and their
    weights ``W`` (m^2), 8 x 8, read-only: made once per plate, not at every call of
    :func:`plate_drag_torque` (a synthetic recording calls it some 10,000 times, and making them
    was half its cost)."""
    x, wt = _GAUSS
    U, V = np.meshgrid(0.5 * length * x, 0.5 * width * x, indexing="ij")
    W = np.outer(wt, wt) * 0.25 * length * width
    for a in (U, V, W):
        a.flags.writeable = False
    return U, V, W


def plate_drag_torque(body: TossBody, w: ArrayLike) -> np.ndarray:
    """Strip-theory drag on the body's plate, principal frame, N m (the synthetic recordings' air).

    Each element of the plate (``length`` along axis 1, ``width`` along axis 2, Gauss-Legendre
    points) is pushed back along the normal by ``0.5 rho C_D |v_n| v_n`` per unit area, ``v_n``
    its normal speed ``w1 y - w2 x``; about the normal itself only a small skin friction acts.

    Parameters
    ----------
    body : TossBody
    w : ndarray, shape (3,)
        Angular velocity, principal frame, rad/s.

    Returns
    -------
    ndarray, shape (3,)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES
    >>> from tumble.analysis.fit.synthetic import plate_drag_torque
    >>> body = TOSS_BODIES["racquet"]
    >>> tau = plate_drag_torque(body, np.array([0.0, 10.0, 0.0]))
    >>> round(float(tau[1]), 3)  # the racquet's 0.05 N m at 10 rad/s about its axis 2
    -0.05
    """
    w = np.asarray(w, float)
    U, V, W = _plate_points(body.length, body.width)
    vn = w[0] * V - w[1] * U
    f = -0.5 * RHO_AIR * body.drag_coefficient * np.abs(vn) * vn * W
    skin = -0.02 * RHO_AIR * body.drag_coefficient * body.width * body.length ** 4 / 64 * abs(w[2]) * w[2]
    return np.array([np.sum(V * f), -np.sum(U * f), skin])


#: The plate's drag along itself against its drag across, per unit of ``0.5 rho v^2`` and of the
#: plate's area: its edges and skin (a phone's 8 mm edge against its 77 mm width; Hoerner 1965,
#: ch. 3, a plate's drag at zero incidence is a few hundredths of that broadside).
EDGE_FRACTION = 0.1


def plate_drag_force(body: TossBody, v: ArrayLike) -> np.ndarray:
    """The air's force on the plate moving at ``v`` (its centre's velocity, principal frame, m/s),
    per unit of the body's mass: m/s^2, principal frame.

    Across the plate, ``0.5 rho C_D L W |v_n| v_n`` along the normal (axis 3; the element law of
    :func:`plate_drag_torque` on the whole plate), so the force turns with the body and follows
    its attitude, broadside or edge-on; along the plate, :data:`EDGE_FRACTION` of that law on the
    speed along it. The mass is the uniform plate's of the body's largest moment,
    ``m = 12 I3 / (L^2 + W^2)`` (a box's moment about its shortest side neglects its thickness:
    0.19 kg for the phone).

    Parameters
    ----------
    body : TossBody
    v : array_like, shape (..., 3)
        Velocity of the centre of mass relative to the air, principal frame, m/s.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    A phone falling broadside at 4 m/s: ``1.204 x 1.17 x 0.0122 x 16 / (2 x 0.19)``, some 0.7 m/s^2,
    and a tenth of it edge-on:

    >>> import numpy as np
    >>> from tumble.analysis.fit.tossbody import TOSS_BODIES, plate_drag_force
    >>> phone = TOSS_BODIES["phone"]
    >>> round(float(plate_drag_force(phone, [0.0, 0.0, -4.0])[2]), 3)   # against the fall, along the normal
    0.722
    >>> round(float(plate_drag_force(phone, [-4.0, 0.0, 0.0])[0]), 4)
    0.0722
    """
    v = np.asarray(v, float)
    L, W = body.length, body.width
    mass = 12.0 * body.moments[2] / (L * L + W * W)
    k = 0.5 * RHO_AIR * body.drag_coefficient * L * W / mass
    along = v * np.array([1.0, 1.0, 0.0])
    return -k * (np.abs(v[..., 2:3]) * v * np.array([0.0, 0.0, 1.0])
                 + EDGE_FRACTION * np.linalg.norm(along, axis=-1, keepdims=True) * along)
