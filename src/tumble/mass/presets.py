"""Ready-made bodies: the seed's T-handle, the one that flips on the space station, and a body of
given principal moments.

Design frame of the handles: the shaft along z with its centre at the origin, the crossbar along
x, y normal to the plane of the T.
"""

from __future__ import annotations

import numpy as np

from ..typing import ArrayLike
from ..validation import check_moments, check_positive
from .body import Body
from .parts import Cylinder, Rod

__all__ = ["PRESETS", "iss_t_handle", "moments_body", "t_handle"]

#: Density of steel used for the space-station handle, kg/m^3 (Peterson & Schwalm 2021).
STEEL_DENSITY = 8050.0


def t_handle(
    *,
    shaft_length: float = 1.0,
    crossbar_length: float = 1.0,
    shaft_mass: float | None = None,
    crossbar_mass: float | None = None,
    shaft_radius: float = 0.0,
    crossbar_radius: float = 0.0,
    density: float | None = None,
    name: str = "T-handle",
) -> Body:
    """A T-handle: a shaft along z with a crossbar along x across its top end.

    The defaults are the seed study's: two thin rods of 1 m and 1.5 kg, the crossbar centred on
    the shaft's top end. Its tensor about the COM (0, 0, 0.25) m is
    diag(0.3125, 0.4375, 0.125) kg m^2, so the shaft (z) is the *minor* axis and the crossbar
    (x) the intermediate one (docs/seed-errata.md).

    With radii > 0 the rods become solid cylinders. The crossbar's axis then sits one crossbar
    radius above the shaft's top end, so the two solids touch instead of overlapping (overlap
    would count the shared material twice); for thin rods this is the seed's geometry.

    Parameters
    ----------
    shaft_length, crossbar_length : float
        Lengths, m.
    shaft_mass, crossbar_mass : float, optional
        Masses, kg (default 1.5 each unless ``density`` is given).
    shaft_radius, crossbar_radius : float
        Radii of solid cylinders, m; 0 for a thin rod.
    density : float, optional
        Uniform density, kg/m^3, instead of masses (needs both radii > 0).
    name : str
        Label of the body.

    Examples
    --------
    >>> import tumble
    >>> body = tumble.t_handle()
    >>> body.mass, body.principal_moments.round(6).tolist()
    (3.0, [0.125, 0.3125, 0.4375])
    >>> solid = tumble.t_handle(shaft_radius=0.01, crossbar_radius=0.01, density=7800.0)
    >>> len(solid.parts), round(solid.mass, 3)   # two steel cylinders, 2 pi (0.01 m)^2 (1 m) 7800 kg/m^3
    (2, 4.901)
    """
    if density is not None and (shaft_mass is not None or crossbar_mass is not None):
        raise ValueError("t_handle takes either 'density' or the masses, not both")
    try:
        shaft_radius = check_positive("shaft_radius", shaft_radius, "m", allow_zero=True)
        crossbar_radius = check_positive("crossbar_radius", crossbar_radius, "m", allow_zero=True)
    except ValueError as exc:
        raise ValueError(f"t_handle: {exc}") from None
    if density is None:
        shaft_mass = 1.5 if shaft_mass is None else shaft_mass
        crossbar_mass = 1.5 if crossbar_mass is None else crossbar_mass

    def bar(
        label: str, length: float, mass: float | None, radius: float,
        center: tuple[float, float, float], axis: tuple[float, float, float],
    ) -> Rod | Cylinder:
        try:
            if radius == 0:
                if density is not None:
                    raise ValueError(
                        f"a thin rod has no volume; give {label}_radius > 0 to use 'density'"
                    )
                return Rod(mass=mass, length=length, center=center, axis=axis)
            return Cylinder(
                mass=mass, density=density, radius=radius, length=length, center=center, axis=axis
            )
        except ValueError as exc:
            text = str(exc)
            if text.startswith(("length = ", "mass = ")):  # the argument's own name: shaft_length = -2.0 ...
                raise ValueError(f"{label}_{text}") from None
            raise ValueError(f"{label}: {text}") from None

    shaft = bar("shaft", shaft_length, shaft_mass, shaft_radius, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    top = 0.5 * shaft.length + crossbar_radius
    crossbar = bar(
        "crossbar", crossbar_length, crossbar_mass, crossbar_radius, (0.0, 0.0, top), (1.0, 0.0, 0.0)
    )
    return Body((shaft, crossbar), name=name)


def iss_t_handle(*, name: str = "ISS T-handle") -> Body:
    """The T-handle that flips on the International Space Station (the Dzhanibekov effect).

    Geometry estimated by Peterson & Schwalm, "Euler's rigid rotators, Jacobi elliptic
    functions, and the Dzhanibekov or tennis racket effect", Am. J. Phys. 89, 349 (2021):
    steel (8050 kg/m^3), a shaft of radius 4 mm and length 50 mm, a crossbar of radius 7.5 mm and
    length 100 mm. Here the shaft axis (z) is the *intermediate* axis: spun about the shaft,
    the handle flips.

    Parameters
    ----------
    name : str
        Label of the body.

    Returns
    -------
    Body
        The handle, in :func:`t_handle`'s design frame.

    Examples
    --------
    >>> import tumble
    >>> handle = tumble.iss_t_handle()
    >>> round(handle.mass * 1000, 1)   # grams of steel
    162.5
    >>> handle.properties.intermediate_axis.round(6).tolist()   # the shaft: spun about it, it flips
    [0.0, 0.0, 1.0]
    """
    return t_handle(
        shaft_length=0.050,
        shaft_radius=0.004,
        crossbar_length=0.100,
        crossbar_radius=0.0075,
        density=STEEL_DENSITY,
        name=name,
    )


def moments_body(moments: ArrayLike, *, mass: float = 1.0, name: str = "body of given moments") -> Body:
    """A body whose principal moments are ``moments`` along the design x, y, z, for a body known
    only by them (a textbook's ``I = 1, 2, 3``, a published inertia) in a body file: three thin rods
    crossing at the centre of mass, one along each axis.

    A rod of mass ``m_k`` and length ``l_k`` along axis ``k`` adds ``s_k = m_k l_k^2 / 12`` to the
    two other moments (Meriam & Kraige Table D/4), so ``I1 = s2 + s3`` and its cyclic companions
    give ``s_k = (I_i + I_j - I_k) / 2``: non-negative by the triangle inequality, and zero (no rod)
    on its boundary, a flat plate's ``I1 + I2 = I3``, which a uniform box would draw with no
    thickness. The mass is shared evenly among the rods there are.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments ``I1 <= I2 <= I3``, kg m^2, within the triangle inequality.
    mass : float, optional
        Total mass, kg (default 1 kg; torque-free motion does not depend on it).
    name : str, optional
        Label of the body.

    Returns
    -------
    Body
        Its principal frame the design frame, its moments ``moments`` to round-off.

    Examples
    --------
    >>> import tumble
    >>> body = tumble.moments_body([1.0, 2.0, 3.0])   # a plate's moments: rods along x and y only
    >>> body.principal_moments.round(12).tolist(), len(body.parts), body.mass
    ([1.0, 2.0, 3.0], 2, 1.0)
    """
    I = check_moments("moments", moments)
    mass = check_positive("mass", mass, "kg")
    d = I[2] - I[1]  # s_k = (I_i + I_j - I_k) / 2, kg m^2, the small I1's through I3 - I2 (no cancellation)
    shares = 0.5 * np.array([I[1] + I[2] - I[0], I[0] + d, I[0] - d])
    present = [k for k in range(3) if shares[k] > 0.0]
    rods = tuple(Rod(mass=mass / len(present), length=float(np.sqrt(12.0 * shares[k] * len(present) / mass)),
                     axis=tuple(np.eye(3)[k])) for k in present)
    return Body(rods, name=name)


#: Presets by the name used on the command line and in body files.
PRESETS = {"t-handle": t_handle, "iss-t-handle": iss_t_handle, "moments": moments_body}
