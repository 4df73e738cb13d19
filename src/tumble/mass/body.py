"""A rigid body built from parts, and its mass properties.

Seed sections 2.3-2.4 done right: total mass, centre of mass (seed eq. 1), and the inertia
tensor about the COM as the sum over parts of each part's own tensor, rotated into the design
frame (``R I R^T``) and shifted to the body's COM with the parallel-axis theorem (seed eq. 4)
-- *every* part shifted, including the shaft that the seed's printed total (sec. 2.4) forgot.

Rotors (:class:`~tumble.mass.rotor.Rotor`) count in the mass properties like any part (locked);
the body also exposes them and their internal angular momentum for the gyrostat's dynamics.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, cast

import numpy as np

from ..typing import ArrayLike, FloatArray, Matrix3, Vector3
from ..validation import check_moments, check_positive, check_vector, short_repr
from . import _display
from .holes import check_holes
from .parts import Part
from .rotor import Rotor
from .tensor import (
    AXIS_ROLES,
    check_inertia,
    inertia_about_point,
    moment_degeneracy,
    parallel_axis,
    principal_frame,
)

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

__all__ = ["AXIS_ROLES", "Body", "MassProperties", "mass_properties", "properties_of"]

def _array(a: ArrayLike) -> FloatArray:
    # Arrays are left writeable: scipy's Rotation.apply refuses read-only input, and users
    # apply rotations to these vectors. The dataclass is frozen; do not modify arrays in place.
    return np.array(a, dtype=float)


@dataclass(frozen=True, eq=False)
class MassProperties:
    """Mass properties of a rigid body, in the design frame, SI units.

    Attributes
    ----------
    mass : float
        Total mass, kg.
    com : ndarray, shape (3,)
        Centre of mass, m.
    inertia : ndarray, shape (3, 3)
        Inertia tensor about the COM, kg m^2.
    principal_moments : ndarray, shape (3,)
        ``I1 <= I2 <= I3``, kg m^2.
    principal_axes : ndarray, shape (3, 3)
        Proper rotation matrix whose *columns* are the axes of I1, I2, I3 (unit vectors in the
        design frame): column ``j - 1`` is principal axis ``j``. It maps principal coordinates
        to design coordinates, so
        ``inertia = principal_axes @ diag(principal_moments) @ principal_axes.T``. The JSON
        outputs (``tumble inertia --json``, ``summary.json``) hold this same matrix, row by row.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.mass import MassProperties
    >>> props = MassProperties.from_inertia(3.0, (0, 0, 0.25), np.diag([0.3125, 0.4375, 0.125]))
    >>> props.principal_moments.tolist()
    [0.125, 0.3125, 0.4375]
    >>> bool(np.allclose(props.principal_axes @ np.diag(props.principal_moments) @ props.principal_axes.T,
    ...                  props.inertia))
    True
    """

    mass: float
    com: Vector3
    inertia: Matrix3
    principal_moments: Vector3
    principal_axes: Matrix3

    @classmethod
    def from_inertia(cls, mass: float, com: ArrayLike, inertia: ArrayLike) -> MassProperties:
        """Validate ``inertia`` (about the COM) and decompose it.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.mass import MassProperties
        >>> props = MassProperties.from_inertia(2.0, (0, 0, 0), [[2, 1, 0], [1, 2, 0], [0, 0, 2]])
        >>> props.principal_moments.round(6).tolist()   # eigenvalues of the tensor, ascending
        [1.0, 2.0, 3.0]
        >>> round(float(np.linalg.det(props.principal_axes)), 6)   # a proper rotation
        1.0
        >>> MassProperties.from_inertia(-3.0, (0, 0, 0.25), np.diag([0.3125, 0.4375, 0.125]))
        Traceback (most recent call last):
        ...
        ValueError: mass = -3.0 must be a positive finite number (kg)
        """
        I = check_inertia(inertia, what="inertia tensor about the centre of mass")
        # as from_moments: a negative mass ran, and inertia_about's parallel axis turned the moments negative
        mass, center = check_positive("mass", mass, "kg"), check_vector("com", com, "m")
        moments, axes = principal_frame(I)
        return cls(mass, _array(center), _array(I), _array(moments), _array(axes))

    @classmethod
    def from_moments(cls, moments: ArrayLike, mass: float = 1.0, com: ArrayLike = (0.0, 0.0, 0.0)) -> MassProperties:
        """Mass properties of a body whose principal axes are the design axes.

        The inertia tensor about the COM is ``diag(moments)`` and ``principal_axes`` is the
        identity: the principal frame is the design frame. For a body known only by its
        principal moments (a published inertia, a fitted one, a test case).

        Parameters
        ----------
        moments : array_like, shape (3,)
            Principal moments ``I1 <= I2 <= I3`` about the COM, kg m^2: positive, ascending and
            within the triangle inequality ``I1 + I2 >= I3`` (Goldstein sec. 5.4).
        mass : float, optional
            Total mass, kg (> 0). Default 1 kg. Torque-free motion does not depend on it.
        com : array_like, shape (3,), optional
            Centre of mass in the design frame, m. Default the origin.

        Returns
        -------
        MassProperties

        Raises
        ------
        ValueError
            For moments that are not three positive ascending numbers within the triangle
            inequality, a mass that is not a positive number or a COM that is not three finite
            numbers; the message names the argument and the rule.

        Examples
        --------
        >>> from tumble.mass import MassProperties
        >>> props = MassProperties.from_moments([0.125, 0.3125, 0.4375], mass=3.0)
        >>> props.principal_moments.tolist(), props.principal_axes.tolist()[0]
        ([0.125, 0.3125, 0.4375], [1.0, 0.0, 0.0])
        >>> props.degeneracy
        'asymmetric'
        >>> MassProperties.from_moments([0.3, 0.2, 0.1])
        Traceback (most recent call last):
        ...
        ValueError: moments = [0.3, 0.2, 0.1] must be ascending, I1 <= I2 <= I3 (kg m^2)
        """
        I = check_moments("moments", moments)
        if I.shape != (3,):
            raise ValueError(f"moments = {short_repr(moments)} must be three numbers, one body's principal moments "
                             "I1 <= I2 <= I3 (kg m^2)")
        mass = check_positive("mass", mass, "kg")
        center = check_vector("com", com, "m")
        return cls(mass, _array(center), np.diag(I), _array(I), np.eye(3))

    @property
    def degeneracy(self) -> str:
        """``"asymmetric"``, ``"symmetric"`` (two equal moments) or ``"spherical"``.

        Examples
        --------
        >>> from tumble.mass import MassProperties
        >>> MassProperties.from_moments([1.0, 1.0, 1.5]).degeneracy
        'symmetric'
        >>> MassProperties.from_moments([2.0, 2.0, 2.0]).degeneracy
        'spherical'
        """
        return moment_degeneracy(self.principal_moments)

    @property
    def intermediate_axis(self) -> Vector3 | None:
        """Unit vector of the intermediate axis (design frame), or None for a symmetric body.

        Spin about this axis is unstable (the tennis-racket theorem); a body with two equal
        moments has no intermediate axis.

        Examples
        --------
        >>> import tumble
        >>> tumble.t_handle().properties.intermediate_axis.round(6).tolist()   # the crossbar, x
        [1.0, 0.0, 0.0]
        >>> tumble.MassProperties.from_moments([1.0, 1.0, 1.5]).intermediate_axis is None
        True
        """
        return self.principal_axes[:, 1].copy() if self.degeneracy == "asymmetric" else None

    def inertia_about(self, point: ArrayLike) -> Matrix3:
        """Inertia tensor about another point, kg m^2 (parallel-axis theorem).

        Parameters
        ----------
        point : array_like, shape (3,) or (..., 3)
            The reference point(s), design frame, m: finite real numbers.

        Returns
        -------
        ndarray, shape (3, 3) or (..., 3, 3)
            The tensor about each point, design frame, kg m^2.

        Raises
        ------
        ValueError
            If ``point`` is not finite numbers of shape (..., 3), e.g.
            ``point = [nan, 0.0, 0.0] must be finite numbers (m)``.

        Examples
        --------
        >>> from tumble.mass import MassProperties
        >>> props = MassProperties.from_moments([0.5, 0.5, 0.5], mass=2.0)
        >>> props.inertia_about((0, 0, 1)).round(6).tolist()   # adds m d^2 = 2 to I_x and I_y
        [[2.5, 0.0, 0.0], [0.0, 2.5, 0.0], [0.0, 0.0, 0.5]]
        """
        return inertia_about_point(self.inertia, self.mass, self.com, point)

    def __repr__(self) -> str:
        return _display.properties_repr(self)

    def _repr_html_(self) -> str:
        """An HTML table of the mass properties (Jupyter's rich display)."""
        return _display.properties_html(self)


def mass_properties(parts: Iterable[Part]) -> MassProperties:
    """Mass properties of a collection of parts (seed eqs. 1, 4 and 5, corrected).

    Raises
    ------
    ValueError
        If the total mass is not positive (more removed than present), or the resulting
        tensor is not physical.

    Examples
    --------
    >>> from tumble.mass import PointMass
    >>> from tumble.mass.body import mass_properties
    >>> props = mass_properties([PointMass(mass=1.0, center=(-1, 0, 0)), PointMass(mass=1.0, center=(1, 0, 0))])
    >>> props.mass, props.com.tolist(), props.principal_moments.tolist()   # a dumbbell along x
    (2.0, [0.0, 0.0, 0.0], [0.0, 2.0, 2.0])
    """
    parts = tuple(parts)
    if not parts:
        raise ValueError("a body needs at least one part")
    check_holes(parts)  # a hole removes material only where a solid has some
    m = np.array([p.signed_mass for p in parts])
    total = float(m.sum())
    scale = float(np.abs(m).sum())
    if not total > 1e-12 * scale:
        raise ValueError(
            f"total mass {total:.6g} kg is not positive: the subtracted parts remove as much "
            f"mass as the others hold, or more"
        )
    r = np.array([p.com for p in parts])
    with np.errstate(over="ignore", invalid="ignore"):  # overflow is caught as non-finite below
        com = (m[:, None] * r).sum(axis=0) / total  # seed eq. (1)
        own = np.array([p.inertia for p in parts])  # signed: holes count negative
        inertia = parallel_axis(own, m, r - com).sum(axis=0)  # seed eq. (4) for every part
    if not (np.isfinite(total) and np.all(np.isfinite(com))):
        raise ValueError("total mass or centre of mass overflows double precision; use SI units of a sensible size")
    return MassProperties.from_inertia(total, com, inertia)


@dataclass(frozen=True, eq=False)
class Body:
    """A rigid body: a named, immutable collection of parts with its mass properties.

    Parameters
    ----------
    parts : sequence of Part
        The parts, in the design frame.
    name : str
        A label for tables and files.

    Raises
    ------
    ValueError
        If the body is not physical (see :func:`mass_properties`).

    Examples
    --------
    >>> import tumble
    >>> body = tumble.Body([tumble.Rod(mass=1.5, length=1.0, axis=(0, 0, 1)),
    ...                     tumble.Rod(mass=1.5, length=1.0, axis=(1, 0, 0), center=(0, 0, 0.5))])
    >>> body.principal_moments.round(4).tolist()
    [0.125, 0.3125, 0.4375]
    """

    parts: tuple[Part, ...]
    name: str = "body"
    properties: MassProperties = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if isinstance(self.parts, Part) or not isinstance(self.parts, Iterable):
            raise ValueError(f"parts = {self.parts!r} must be a list of parts: Body([part, ...]), one part "
                             f"Body([part])")
        parts = tuple(self.parts)
        for i, p in enumerate(parts):
            if not isinstance(p, Part):
                raise ValueError(f"parts[{i}] = {p!r} is not a tumble part")
        object.__setattr__(self, "parts", parts)
        object.__setattr__(self, "properties", mass_properties(parts))

    # Shortcuts to the mass properties --------------------------------------------------
    @property
    def mass(self) -> float:
        """Total mass, kg.

        Examples
        --------
        >>> import tumble
        >>> tumble.t_handle().mass
        3.0
        """
        return self.properties.mass

    @property
    def com(self) -> Vector3:
        """Centre of mass in the design frame, m.

        Examples
        --------
        >>> import tumble
        >>> tumble.t_handle().com.round(6).tolist()   # a quarter of the shaft above its middle
        [0.0, 0.0, 0.25]
        """
        return self.properties.com

    @property
    def inertia(self) -> Matrix3:
        """Inertia tensor about the COM in the design frame, kg m^2.

        Examples
        --------
        >>> import tumble
        >>> tumble.t_handle().inertia.round(6).tolist()
        [[0.3125, 0.0, 0.0], [0.0, 0.4375, 0.0], [0.0, 0.0, 0.125]]
        """
        return self.properties.inertia

    @property
    def principal_moments(self) -> Vector3:
        """Principal moments ``I1 <= I2 <= I3``, kg m^2.

        Examples
        --------
        >>> import tumble
        >>> tumble.t_handle().principal_moments.round(6).tolist()
        [0.125, 0.3125, 0.4375]
        """
        return self.properties.principal_moments

    @property
    def principal_axes(self) -> Matrix3:
        """Rotation matrix principal -> design, shape (3, 3); columns are the axes of I1, I2, I3.

        Examples
        --------
        >>> import tumble
        >>> tumble.t_handle().principal_axes.round(6).tolist()   # columns: the shaft z, the crossbar x, then y
        [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
        """
        return self.properties.principal_axes

    def inertia_about(self, point: ArrayLike) -> Matrix3:
        """Inertia tensor about ``point`` (design frame, m), kg m^2; see
        :meth:`MassProperties.inertia_about` (shapes, and the ``ValueError`` for a bad point).

        Examples
        --------
        >>> import tumble
        >>> body = tumble.t_handle()
        >>> body.inertia_about((0, 0, 0)).round(6).tolist()   # about the shaft's middle: + 3 kg (0.25 m)^2 on x and y
        [[0.5, 0.0, 0.0], [0.0, 0.625, 0.0], [0.0, 0.0, 0.125]]
        """
        return self.properties.inertia_about(point)

    @property
    def rotors(self) -> tuple[Rotor, ...]:
        """The parts that spin relative to the body (:class:`~tumble.mass.rotor.Rotor`), in order.

        Examples
        --------
        >>> import tumble
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(0, 0, 1), spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 1.0, 1.0)), wheel])
        >>> body.rotors == (wheel,)
        True
        """
        return tuple(p for p in self.parts if isinstance(p, Rotor))

    def internal_momentum(self, t: ArrayLike = 0.0) -> Vector3:
        """Internal angular momentum of the rotors in the *principal* frame, kg m^2/s.

        ``h(t) = sum_k J_k s_k(t) n_k`` over the rotors (axial moment ``J_k``, relative spin
        ``s_k(t)``, axis ``n_k``), turned from the design frame by ``principal_axes^T``; zero for
        a body without rotors. This is what the gyrostat's equations add to ``I omega``
        (:mod:`tumble.dynamics.models.internal`).

        Parameters
        ----------
        t : float or array_like
            Time(s), s.

        Returns
        -------
        ndarray, shape ``np.shape(t) + (3,)``

        Examples
        --------
        >>> import tumble
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(0, 0, 1), spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> body.internal_momentum().round(6).tolist()   # J s = (0.005 kg m^2)(100 rad/s) along z, I1's axis
        [0.5, 0.0, 0.0]
        >>> body.internal_momentum([0.0, 1.0]).shape
        (2, 3)
        """
        times = np.asarray(t, dtype=float)
        h = np.zeros(times.shape + (3,))
        for rotor in self.rotors:
            h += rotor.momentum(times)
        return h @ self.principal_axes  # rows: (A^T h_design)^T

    def moved(self, rotation: Rotation | ArrayLike, translation: ArrayLike = (0.0, 0.0, 0.0)) -> Body:
        """The body after a rigid motion ``x -> R x + t`` of all its parts.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from scipy.spatial.transform import Rotation
        >>> body = tumble.t_handle()
        >>> moved = body.moved(Rotation.from_euler("x", 90, degrees=True), translation=(1.0, 0.0, 0.0))
        >>> moved.com.round(6).tolist()
        [1.0, -0.25, 0.0]
        >>> bool(np.allclose(moved.principal_moments, body.principal_moments))   # a rigid motion keeps the moments
        True
        """
        return Body(tuple(p.moved(rotation, translation) for p in self.parts), self.name)

    def __repr__(self) -> str:
        return _display.body_repr(self)

    def _repr_html_(self) -> str:
        """The mass properties and the parts as HTML tables (Jupyter's rich display)."""
        return _display.body_html(self)


def properties_of(body: object, name: str = "body") -> MassProperties:
    """The mass properties of a :class:`Body` (its :attr:`~Body.properties`) or of
    :class:`MassProperties` (themselves); a ValueError naming ``name`` for anything else, with the
    way to make them where it is three numbers.

    Examples
    --------
    >>> from tumble.mass.body import properties_of
    >>> properties_of([1.0, 2.0, 3.0])
    Traceback (most recent call last):
    ...
    ValueError: body = [1.0, 2.0, 3.0] must be a tumble Body or MassProperties; for principal moments alone: tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
    """
    props = body.properties if isinstance(body, Body) else body
    if isinstance(props, MassProperties):
        return props
    three = np.shape(body) == (3,) if isinstance(body, np.ndarray) else isinstance(body, (list, tuple)) and len(body) == 3
    shown = short_repr(body.tolist() if isinstance(body, np.ndarray) else body)
    hint = f"; for principal moments alone: tumble.MassProperties.from_moments({shown})" if three else ""
    raise ValueError(f"{name} = {short_repr(body)} must be a tumble Body or MassProperties{hint}")
