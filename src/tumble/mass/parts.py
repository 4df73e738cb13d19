"""Parts of a rigid body, each with its closed-form inertia tensor.

What every part shares (mass or density, the design frame's ``center`` and orientation, removed
material with ``subtract=True``) is :class:`~tumble.mass.part_base.Part`'s, in
:mod:`tumble.mass.part_base`; this module holds the shapes. Axisymmetric parts (rod, cylinder,
tube, cone) take an ``axis`` direction; parts with three distinct axes (box, ellipsoid, mesh)
take a ``rotation`` that maps the part's own frame to the design frame (a quaternion
``[x, y, z, w]`` as in scipy, a 3x3 matrix, or a ``scipy.spatial.transform.Rotation``).
Thin parts (rod, thin shell, point) have no volume and take a mass.

Closed forms, about the part's own centre of mass in its own frame (axis of symmetry = local z),
from the standard table of homogeneous solids, Meriam & Kraige, *Engineering Mechanics:
Dynamics*, Appendix D, Table D/4, each re-derivable from ``I = integral rho (r^2 E - r r^T) dV``
(seed sec. 2.1) and cross-checked against meshes and quadrature in ``tests/``.

A rotor (:class:`tumble.mass.rotor.Rotor`) is a solid cylinder that also spins relative to the
body about its own axis.

All parts are immutable (frozen dataclasses, keyword-only arguments).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, cast

import numpy as np

from ..typing import BoolArray, FloatArray, Vector3
from ..validation import check_positive, check_vector
from .part_base import Part, _Axisymmetric, _Oriented

__all__ = [
    "PART_KINDS",
    "Box",
    "Cone",
    "Cylinder",
    "Ellipsoid",
    "Part",
    "PointMass",
    "Rod",
    "Shell",
    "Sphere",
    "Tube",
]


@dataclass(frozen=True, kw_only=True)
class Rod(_Axisymmetric):
    """Thin uniform rod of ``length`` (m) along ``axis``, centred at ``center``.

    ``I_perp = m L^2 / 12``, ``I_axial = 0`` (seed eqs. 2-3; Meriam & Kraige Table D/4).

    Examples
    --------
    >>> import tumble
    >>> rod = tumble.Rod(mass=3.0, length=2.0, axis=(0, 0, 1))
    >>> rod.inertia.round(6).diagonal().tolist()   # m L^2 / 12 across, 0 along
    [1.0, 1.0, 0.0]
    """

    kind: ClassVar[str] = "rod"
    solid: ClassVar[bool] = False
    length: float

    def _check_shape(self) -> None:
        super()._check_shape()
        self._set("length", check_positive("length", self.length, "m"))

    def _unit_moments(self) -> Vector3:
        p = self.length**2 / 12.0
        return np.array([p, p, 0.0])


@dataclass(frozen=True, kw_only=True)
class Cylinder(_Axisymmetric):
    """Solid uniform circular cylinder of ``radius`` and ``length`` (m) along ``axis``.

    ``I_axial = m r^2 / 2``, ``I_perp = m (3 r^2 + L^2) / 12`` (Meriam & Kraige Table D/4).

    Examples
    --------
    >>> import tumble
    >>> cyl = tumble.Cylinder(mass=12.0, radius=1.0, length=2.0, axis=(0, 0, 1))
    >>> cyl.inertia.round(6).diagonal().tolist()   # m (3 r^2 + L^2) / 12 across, m r^2 / 2 along
    [7.0, 7.0, 6.0]
    """

    kind: ClassVar[str] = "cylinder"
    radius: float
    length: float

    def _check_shape(self) -> None:
        super()._check_shape()
        self._set("radius", check_positive("radius", self.radius, "m"))
        self._set("length", check_positive("length", self.length, "m"))

    @property
    def volume(self) -> float:
        """Volume ``pi r^2 L``, m^3.

        Examples
        --------
        >>> import tumble
        >>> round(tumble.Cylinder(density=1000.0, radius=0.1, length=1.0).volume, 6)   # pi r^2 L, m^3
        0.031416
        """
        return math.pi * self.radius**2 * self.length

    def _unit_moments(self) -> Vector3:
        r2, L2 = self.radius**2, self.length**2
        p = (3.0 * r2 + L2) / 12.0
        return np.array([p, p, r2 / 2.0])

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        r, h = self.radius, 0.5 * self.length
        return np.array([-r, -r, -h]), np.array([r, r, h])

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        r2 = x[:, 0] ** 2 + x[:, 1] ** 2
        return (r2 <= (self.radius + slack) ** 2) & (np.abs(x[:, 2]) <= 0.5 * self.length + slack)


@dataclass(frozen=True, kw_only=True)
class Tube(_Axisymmetric):
    """Thick-walled circular tube: ``inner_radius < outer_radius`` (m), ``length`` (m).

    ``I_axial = m (a^2 + b^2) / 2``, ``I_perp = m (3 (a^2 + b^2) + L^2) / 12`` with inner radius
    a and outer radius b (the cylinder's forms for b minus a, Meriam & Kraige Table D/4).

    Examples
    --------
    >>> import tumble
    >>> tube = tumble.Tube(mass=2.0, inner_radius=1.0, outer_radius=2.0, length=1.0)
    >>> round(float(tube.inertia[2, 2]), 6)   # m (a^2 + b^2) / 2 about its axis
    5.0
    """

    kind: ClassVar[str] = "tube"
    inner_radius: float
    outer_radius: float
    length: float

    def _check_shape(self) -> None:
        super()._check_shape()
        a = check_positive("inner_radius", self.inner_radius, "m", allow_zero=True)
        b = check_positive("outer_radius", self.outer_radius, "m")
        if not a < b:
            raise ValueError(
                f"inner_radius = {a!r} must be smaller than outer_radius = {b!r} (m)"
            )
        self._set("inner_radius", a)
        self._set("outer_radius", b)
        self._set("length", check_positive("length", self.length, "m"))

    @property
    def volume(self) -> float:
        """Volume ``pi (b^2 - a^2) L``, m^3.

        Examples
        --------
        >>> import tumble
        >>> tube = tumble.Tube(density=1.0, inner_radius=1.0, outer_radius=2.0, length=1.0)
        >>> round(tube.volume, 6), round(tube.mass, 6)   # pi (b^2 - a^2) L = 3 pi m^3
        (9.424778, 9.424778)
        """
        return math.pi * (self.outer_radius**2 - self.inner_radius**2) * self.length

    def _unit_moments(self) -> Vector3:
        s = self.inner_radius**2 + self.outer_radius**2
        p = (3.0 * s + self.length**2) / 12.0
        return np.array([p, p, s / 2.0])

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        b, h = self.outer_radius, 0.5 * self.length
        return np.array([-b, -b, -h]), np.array([b, b, h])

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        r2 = x[:, 0] ** 2 + x[:, 1] ** 2
        a = max(self.inner_radius - slack, 0.0)
        return (r2 >= a * a) & (r2 <= (self.outer_radius + slack) ** 2) & (np.abs(x[:, 2]) <= 0.5 * self.length + slack)


@dataclass(frozen=True, kw_only=True)
class Cone(_Axisymmetric):
    """Solid right circular cone of base ``radius`` and ``height`` (m).

    ``axis`` points from the base to the apex; ``center`` is the centre of mass, which lies on
    the axis a quarter of the height above the base. About the COM:
    ``I_axial = 3 m r^2 / 10``, ``I_perp = 3 m (4 r^2 + h^2) / 80`` (Meriam & Kraige Table D/4,
    shifted from the apex by the parallel-axis theorem).

    Examples
    --------
    >>> import tumble
    >>> cone = tumble.Cone(mass=10.0, radius=1.0, height=4.0, axis=(0, 0, 1))
    >>> cone.inertia.round(6).diagonal().tolist()   # 3 m (4 r^2 + h^2) / 80 across, 3 m r^2 / 10 along
    [7.5, 7.5, 3.0]
    """

    kind: ClassVar[str] = "cone"
    radius: float
    height: float

    def _check_shape(self) -> None:
        super()._check_shape()
        self._set("radius", check_positive("radius", self.radius, "m"))
        self._set("height", check_positive("height", self.height, "m"))

    @property
    def volume(self) -> float:
        """Volume ``pi r^2 h / 3``, m^3.

        Examples
        --------
        >>> import math, tumble
        >>> cone = tumble.Cone(density=1.0, radius=1.0, height=3.0)
        >>> round(cone.volume / math.pi, 6)   # pi r^2 h / 3
        1.0
        """
        return math.pi * self.radius**2 * self.height / 3.0

    @property
    def base_center(self) -> Vector3:
        """Centre of the base disc in the design frame, m.

        Examples
        --------
        >>> import tumble
        >>> cone = tumble.Cone(mass=1.0, radius=1.0, height=4.0, axis=(0, 0, 1), center=(0, 0, 1))
        >>> cone.base_center.tolist()   # the COM is a quarter of the height above the base
        [0.0, 0.0, 0.0]
        """
        return np.array(self.center) - 0.25 * self.height * np.array(self.axis)

    def _unit_moments(self) -> Vector3:
        r2, h2 = self.radius**2, self.height**2
        p = 3.0 * (4.0 * r2 + h2) / 80.0
        return np.array([p, p, 0.3 * r2])

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        r, h = self.radius, self.height  # the base a quarter of the height below the centre of mass
        return np.array([-r, -r, -0.25 * h]), np.array([r, r, 0.75 * h])

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        r, h, z = self.radius, self.height, x[:, 2]
        rho = np.hypot(x[:, 0], x[:, 1])
        return (z >= -0.25 * h - slack) & (z <= 0.75 * h + slack) & (rho <= r * (0.75 * h - z) / h + slack)


@dataclass(frozen=True, kw_only=True)
class Box(_Oriented):
    """Solid uniform cuboid with edge lengths ``size = (a, b, c)`` (m) along its own x, y, z.

    ``I_x = m (b^2 + c^2) / 12`` and cyclic (Meriam & Kraige Table D/4).

    Examples
    --------
    >>> import tumble
    >>> box = tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0))
    >>> box.inertia.round(6).diagonal().tolist()   # m (b^2 + c^2) / 12 and cyclic
    [13.0, 10.0, 5.0]
    """

    kind: ClassVar[str] = "box"
    size: tuple[float, float, float]

    def _check_shape(self) -> None:
        super()._check_shape()
        check_vector("size", self.size, "m")
        self._set("size", tuple(check_positive(f"size[{i}]", s, "m") for i, s in enumerate(self.size)))

    @property
    def volume(self) -> float:
        """Volume ``a b c``, m^3.

        Examples
        --------
        >>> import tumble
        >>> box = tumble.Box(density=500.0, size=(1.0, 2.0, 3.0))
        >>> box.volume, box.mass
        (6.0, 3000.0)
        """
        a, b, c = self.size
        return a * b * c

    def _unit_moments(self) -> Vector3:
        s2: Vector3 = np.square(self.size)
        return cast(Vector3, (s2.sum() - s2) / 12.0)

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        half = 0.5 * np.array(self.size)
        return -half, half

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        return cast(BoolArray, np.all(np.abs(x) <= 0.5 * np.array(self.size) + slack, axis=1))


@dataclass(frozen=True, kw_only=True)
class Ellipsoid(_Oriented):
    """Solid uniform ellipsoid with semi-axes ``semi_axes = (a, b, c)`` (m) along its own x, y, z.

    ``I_x = m (b^2 + c^2) / 5`` and cyclic (Meriam & Kraige Table D/4).

    Examples
    --------
    >>> import tumble
    >>> egg = tumble.Ellipsoid(mass=5.0, semi_axes=(1.0, 2.0, 3.0))
    >>> egg.inertia.round(6).diagonal().tolist()   # m (b^2 + c^2) / 5 and cyclic
    [13.0, 10.0, 5.0]
    """

    kind: ClassVar[str] = "ellipsoid"
    semi_axes: tuple[float, float, float]

    def _check_shape(self) -> None:
        super()._check_shape()
        check_vector("semi_axes", self.semi_axes, "m")
        self._set(
            "semi_axes",
            tuple(check_positive(f"semi_axes[{i}]", s, "m") for i, s in enumerate(self.semi_axes)),
        )

    @property
    def volume(self) -> float:
        """Volume ``4 pi a b c / 3``, m^3.

        Examples
        --------
        >>> import math, tumble
        >>> round(tumble.Ellipsoid(density=1.0, semi_axes=(1.0, 2.0, 3.0)).volume / math.pi, 6)   # 4 pi a b c / 3
        8.0
        """
        a, b, c = self.semi_axes
        return 4.0 / 3.0 * math.pi * a * b * c

    def _unit_moments(self) -> Vector3:
        s2: Vector3 = np.square(self.semi_axes)
        return cast(Vector3, (s2.sum() - s2) / 5.0)

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        a = np.array(self.semi_axes)
        return -a, a

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        return cast(BoolArray, np.sum((x / (np.array(self.semi_axes) + slack)) ** 2, axis=1) <= 1.0)


@dataclass(frozen=True, kw_only=True)
class Sphere(Part):
    """Solid uniform sphere of ``radius`` (m): ``I = 2 m r^2 / 5`` (Meriam & Kraige Table D/4).

    Examples
    --------
    >>> import tumble
    >>> ball = tumble.Sphere(mass=5.0, radius=0.5)
    >>> round(float(ball.inertia[0, 0]), 6)   # 2 m r^2 / 5
    0.5
    """

    kind: ClassVar[str] = "sphere"
    radius: float

    def _check_shape(self) -> None:
        self._set("radius", check_positive("radius", self.radius, "m"))

    @property
    def volume(self) -> float:
        """Volume ``4 pi r^3 / 3``, m^3.

        Examples
        --------
        >>> import math, tumble
        >>> round(tumble.Sphere(density=1.0, radius=3.0).volume / math.pi, 6)   # 4 pi r^3 / 3
        36.0
        """
        return 4.0 / 3.0 * math.pi * self.radius**3

    def _unit_moments(self) -> Vector3:
        return np.full(3, 0.4 * self.radius**2)

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        return np.full(3, -self.radius), np.full(3, self.radius)

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        return cast(BoolArray, np.sum(x * x, axis=1) <= (self.radius + slack) ** 2)


@dataclass(frozen=True, kw_only=True)
class Shell(Part):
    """Thin uniform spherical shell of ``radius`` (m): ``I = 2 m r^2 / 3`` (Meriam & Kraige D/4).

    For a shell of finite thickness subtract a sphere from a sphere.

    Examples
    --------
    >>> import tumble
    >>> shell = tumble.Shell(mass=3.0, radius=1.0)
    >>> round(float(shell.inertia[0, 0]), 6)   # 2 m r^2 / 3
    2.0
    """

    kind: ClassVar[str] = "shell"
    solid: ClassVar[bool] = False
    radius: float

    def _check_shape(self) -> None:
        self._set("radius", check_positive("radius", self.radius, "m"))

    def _unit_moments(self) -> Vector3:
        return np.full(3, 2.0 / 3.0 * self.radius**2)


@dataclass(frozen=True, kw_only=True)
class PointMass(Part):
    """A point mass at ``center``: no inertia about its own position.

    Examples
    --------
    >>> import tumble
    >>> body = tumble.Body([tumble.PointMass(mass=1.0, center=(0, 0, 1)), tumble.PointMass(mass=1.0, center=(0, 0, -1))])
    >>> body.principal_moments.tolist()   # m d^2 twice across the line, nothing along it
    [0.0, 2.0, 2.0]
    """

    kind: ClassVar[str] = "point"
    solid: ClassVar[bool] = False

    def _unit_moments(self) -> Vector3:
        return np.zeros(3)


#: Every part class by its ``kind`` (the name used in body files). The mesh part lives in
#: :mod:`tumble.mass.mesh` (so trimesh is imported only when used) and the rotor in
#: :mod:`tumble.mass.rotor`; each registers itself there.
PART_KINDS: dict[str, type[Part]] = {
    cls.kind: cls for cls in (Rod, Cylinder, Tube, Cone, Box, Ellipsoid, Sphere, Shell, PointMass)
}
