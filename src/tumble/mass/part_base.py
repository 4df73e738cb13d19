"""The base of every part: its mass or density, its place and orientation, removed material.

A part sits in the body's *design frame*: its centre of mass at ``center`` (m) and an
orientation. Axisymmetric parts (:class:`_Axisymmetric`: rod, cylinder, tube, cone) take an
``axis`` direction; parts with three distinct axes (:class:`_Oriented`: box, ellipsoid, mesh)
take a ``rotation`` that maps the part's own frame to the design frame (a quaternion
``[x, y, z, w]`` as in scipy, a 3x3 matrix, or a ``scipy.spatial.transform.Rotation``).

The mass is given directly (``mass``, kg) or as ``density`` (kg/m^3) times the closed-form
volume: exactly one of the two. Thin parts (rod, thin shell, point) have no volume and take a
mass. A solid part with ``subtract=True`` is material *removed* from the body (a hole): it
contributes negative mass and negative inertia; the body checks that the whole stays physical.

Each kind of part (:mod:`tumble.mass.parts`, :mod:`tumble.mass.mesh`, :mod:`tumble.mass.rotor`)
gives its shape's checks and its principal moments per unit mass; this module turns them into
the tensor in the design frame, ``R I R^T`` (seed sec. 2.1).
"""

from __future__ import annotations

import dataclasses
import functools
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, cast

import numpy as np

from ..typing import ArrayLike, BoolArray, FloatArray, Matrix3, Vector3
from ..validation import check_direction, check_motion, check_positive, check_rotation, check_vector

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

__all__ = ["MAX_DENSITY", "MIN_DENSITY", "Part", "UnitSlipWarning"]

_Z = np.array([0.0, 0.0, 1.0])


#: A solid part given by its mass whose density comes out below this (kg/m^3), under the lightest
#: solid made (a graphene aerogel, 0.16 kg/m^3), is most likely sized in mm or cm and written as
#: metres: that makes a part 1e9 (1e6) times lighter than it is, 2.7e-6 (2.7e-3) kg/m^3 for
#: aluminium (a walkthrough's phone in cm passed the earlier bound, a thousandth of air's). A
#: textbook's unit example (1 kg, 1 m) stays far above it.
MIN_DENSITY = 0.1
#: A solid part given by its mass whose density comes out above this (kg/m^3), past osmium's 22,590
#: (the densest element), most likely has its mass in grams: a 200 g phone written ``mass = 200``
#: is 2.2e6 kg/m^3. A concentrated mass drawn as a small solid is better a ``PointMass``.
MAX_DENSITY = 3e4


class UnitSlipWarning(UserWarning):
    """A value whose size no real object or sensor has: a part's or a mesh's sizes most likely written in
    mm or cm (or a mesh file read in the wrong unit), its mass in grams, a gyroscope's rates in deg/s; the
    message says how to write them.

    Examples
    --------
    >>> import warnings
    >>> import tumble
    >>> from tumble.mass import UnitSlipWarning
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always", UnitSlipWarning)
    ...     _ = tumble.Cylinder(mass=0.2, radius=12.0, length=80.0)   # mm written as m
    >>> print(caught[0].message)
    a cylinder of 0.2 kg in 3.62e+04 m^3 is 5.53e-06 kg/m^3, less than the lightest solid's (an aerogel, 0.16 kg/m^3): are its sizes in mm or cm? Write them in metres (SI units)
    """


@dataclass(frozen=True, kw_only=True)
class Part:
    """Base class of all parts. Not instantiated directly.

    Attributes
    ----------
    mass : float
        Mass in kg (after construction always set, from ``density * volume`` if need be).
    density : float or None
        Density in kg/m^3 if the mass was given that way.
    center : tuple of 3 floats
        Centre of mass of the part in the design frame, m.
    subtract : bool
        The part is removed material (a hole).

    Examples
    --------
    >>> import tumble
    >>> rod = tumble.Rod(mass=1.5, length=1.0, center=(0, 0, 0.5))
    >>> isinstance(rod, tumble.Part), rod.signed_mass, rod.com.tolist()
    (True, 1.5, [0.0, 0.0, 0.5])
    """

    kind: ClassVar[str] = "part"
    #: Whether the part has a volume (and so may be given by density, or subtracted).
    solid: ClassVar[bool] = True

    mass: float | None = None
    density: float | None = None
    center: tuple[float, float, float] = (0.0, 0.0, 0.0)
    subtract: bool = False

    def __post_init__(self) -> None:
        self._set("center", check_vector("center", self.center, "m"))
        self._check_shape()
        if not isinstance(self.subtract, bool):
            raise ValueError(f"subtract = {self.subtract!r} must be true or false")
        if self.subtract and not self.solid:
            raise ValueError(f"a {self.kind} has no volume and cannot be subtracted")
        given = [k for k in ("mass", "density") if getattr(self, k) is not None]
        if len(given) != 1:
            allowed = "'mass' (kg) or 'density' (kg/m^3)" if self.solid else "'mass' (kg)"
            said = " and ".join(given) if given else "neither"
            raise ValueError(f"a {self.kind} needs exactly one of {allowed}; got {said}")
        if self.density is not None:
            if not self.solid:
                raise ValueError(
                    f"a {self.kind} has no volume, so 'density' cannot give its mass; give 'mass' (kg)"
                )
            rho = check_positive("density", self.density, "kg/m^3")
            if not 1e-3 <= rho <= 1e5:  # 1e-320 lost the centre's digits to subnormal masses; 1e308 overflowed
                raise ValueError(f"density = {self.density!r} kg/m^3 is beyond any solid's (1e-3 to 1e5 kg/m^3: aerogels "
                                 "0.16, osmium 22,590); give it in kg/m^3")
            self._set("density", rho)
            try:
                mass = rho * self.volume
            except OverflowError:
                mass = float("inf")
            self._set("mass", mass)
        else:
            self._set("mass", check_positive("mass", self.mass, "kg"))
        self._check_representable()
        if self.solid and self.density is None:  # a mesh's file read in the wrong unit: io.meshfile says that instead
            volume = self.volume
            of_mass: float | None = cast(float, self.mass) / volume if volume > 0.0 else None
            if of_mass is not None and of_mass < MIN_DENSITY:
                warnings.warn(f"a {self.kind} of {self.mass:.3g} kg in {volume:.3g} m^3 is {of_mass:.3g} kg/m^3, less than the "
                              "lightest solid's (an aerogel, 0.16 kg/m^3): are its sizes in mm or cm? Write them in "
                              "metres (SI units)", UnitSlipWarning, stacklevel=3)
            elif of_mass is not None and of_mass > MAX_DENSITY:
                warnings.warn(f"a {self.kind} of {self.mass:.3g} kg in {volume:.3g} m^3 is {of_mass:.3g} kg/m^3, more than "
                              "osmium's (22,590 kg/m^3, the densest element): is its mass in grams? Write it in kg (SI "
                              "units); a concentrated mass is a PointMass", UnitSlipWarning, stacklevel=3)

    def _check_representable(self) -> None:
        """Sizes and masses so large that volume or inertia overflow double precision."""
        try:
            with np.errstate(over="raise", invalid="raise"):
                finite = np.isfinite(cast(float, self.mass)) and np.all(np.isfinite(self.inertia))
        except (OverflowError, FloatingPointError):
            finite = False
        if not finite:
            raise ValueError(
                f"a {self.kind} of mass {self.mass!r} kg with these sizes has an inertia beyond double "
                f"precision (overflow); use SI units of a sensible size"
            )

    # -- helpers for subclasses -------------------------------------------------------------
    def _set(self, name: str, value: object) -> None:
        object.__setattr__(self, name, value)

    def _check_shape(self) -> None:
        """Validate and normalise the geometric fields (subclasses)."""

    # -- geometry -------------------------------------------------------------------------
    @property
    def volume(self) -> float:
        """Volume in m^3 (0 for thin parts).

        Examples
        --------
        >>> import tumble
        >>> tumble.Box(mass=1.0, size=(1.0, 2.0, 3.0)).volume
        6.0
        >>> tumble.Rod(mass=1.0, length=2.0).volume   # thin: no volume
        0.0
        """
        return 0.0

    @property
    def orientation(self) -> Rotation:
        """Rotation from the part's own frame to the design frame (scipy Rotation).

        Examples
        --------
        >>> import tumble
        >>> rod = tumble.Rod(mass=1.0, length=1.0, axis=(1, 0, 0))
        >>> rod.orientation.apply([0, 0, 1]).round(6).tolist()   # the part's own z goes to its axis
        [1.0, 0.0, 0.0]
        """
        from scipy.spatial.transform import Rotation

        return Rotation.identity()

    @property
    def com(self) -> Vector3:
        """Centre of mass in the design frame, shape (3,), m.

        Examples
        --------
        >>> import tumble
        >>> tumble.Sphere(mass=1.0, radius=0.1, center=(1, 2, 3)).com.tolist()
        [1.0, 2.0, 3.0]
        """
        return np.array(self.center)

    def _unit_moments(self) -> Vector3:
        """Principal moments per unit mass in the part's own frame, m^2 (subclasses)."""
        raise NotImplementedError

    # -- where the material is (a solid part's; tumble.mass.holes) ------------------------------
    @property
    def _frame_origin(self) -> Vector3:
        """Where the part's own frame's origin lies in the design frame, m (its ``center``)."""
        return np.array(self.center, dtype=float)

    @property
    def _triangles(self) -> int:
        """How many triangles its inside test works through (a mesh's; 0 for a closed form)."""
        return 0

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        """The corners (low, high) of a box in the part's own frame that holds it, m (solids)."""
        raise NotImplementedError(f"a {self.kind} has no volume")

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        """Whether points ``x`` (n, 3) in the part's own frame lie in its solid, widened by
        ``slack`` (m) so that a point on a shared face counts as inside (solids)."""
        raise NotImplementedError(f"a {self.kind} has no volume")

    def _inside(self, points: FloatArray, slack: float = 0.0) -> BoolArray:
        """Whether design-frame points (n, 3), m, lie in the part's solid (widened by ``slack``, m)."""
        local = self.orientation.inv().apply(np.asarray(points, dtype=float) - self._frame_origin)
        return self._inside_local(np.atleast_2d(local), slack)

    def _local_inertia(self) -> Matrix3:
        """Tensor about the part's COM in its own frame, kg m^2 (positive mass)."""
        return np.diag(cast(float, self.mass) * self._unit_moments())

    @property
    def signed_mass(self) -> float:
        """Mass contributed to the body, kg: negative for removed material.

        Examples
        --------
        >>> import tumble
        >>> tumble.Cylinder(mass=2.0, radius=0.1, length=0.5, subtract=True).signed_mass   # a hole
        -2.0
        """
        mass = cast(float, self.mass)  # always set by __post_init__
        return -mass if self.subtract else mass

    @functools.cached_property
    def inertia(self) -> Matrix3:
        """Tensor about the part's own COM in the design frame, ``R I R^T`` (kg m^2).

        Negative for removed material. Computed once (the part is immutable).

        Examples
        --------
        >>> import tumble
        >>> tumble.Sphere(mass=5.0, radius=1.0).inertia.round(6).tolist()   # 2 m r^2 / 5
        [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]]
        """
        I = self._design_inertia()
        return -I if self.subtract else I

    def _design_inertia(self) -> Matrix3:
        R: Matrix3 = self.orientation.as_matrix()
        return R @ self._local_inertia() @ R.T

    def moved(self, rotation: Rotation | ArrayLike, translation: ArrayLike = (0.0, 0.0, 0.0)) -> Part:
        """The same part after a rigid motion ``x -> R x + t`` of the design frame.

        Parameters
        ----------
        rotation : scipy Rotation, quaternion [x, y, z, w] or 3x3 matrix
            The rotation R.
        translation : array_like, shape (3,)
            The translation t, m.

        Examples
        --------
        >>> import tumble
        >>> from scipy.spatial.transform import Rotation
        >>> rod = tumble.Rod(mass=1.0, length=1.0, axis=(0, 0, 1), center=(0, 0, 1))
        >>> turned = rod.moved(Rotation.from_euler("y", 90, degrees=True))
        >>> turned.com.round(6).tolist(), [round(x, 6) for x in turned.axis]
        ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0])
        """
        R, t = check_motion(rotation, translation)
        changes: dict[str, Any] = {"center": tuple(R.apply(self.center) + t)}
        if self.density is not None:
            changes["mass"] = None  # recomputed from the density
        changes.update(self._moved_orientation(R))
        return dataclasses.replace(self, **changes)

    def _moved_orientation(self, rotation: Rotation) -> dict[str, Any]:
        return {}


@dataclass(frozen=True, kw_only=True)
class _Axisymmetric(Part):
    """A part symmetric about ``axis`` (its local z axis)."""

    axis: tuple[float, float, float] = (0.0, 0.0, 1.0)

    def _check_shape(self) -> None:
        self._set("axis", check_direction("axis", self.axis))

    @property
    def orientation(self) -> Rotation:
        """Shortest-arc rotation taking local z to ``axis`` (the roll about it is immaterial)."""
        from scipy.spatial.transform import Rotation

        rot, _ = Rotation.align_vectors([self.axis], [_Z])
        return rot

    def _design_inertia(self) -> Matrix3:
        # For a body of revolution R diag(p, p, a) R^T = p (E - n n^T) + a n n^T whatever the
        # roll about n; this form is exact for axis-aligned parts (no round-off from R).
        p, _, a = cast(float, self.mass) * self._unit_moments()
        n = np.array(self.axis)
        nn = np.outer(n, n)
        return cast(Matrix3, p * (np.eye(3) - nn) + a * nn)

    def _moved_orientation(self, rotation: Rotation) -> dict[str, Any]:
        return {"axis": tuple(rotation.apply(self.axis))}


@dataclass(frozen=True, kw_only=True)
class _Oriented(Part):
    """A part whose own frame is placed by ``rotation`` (local -> design)."""

    rotation: tuple[float, ...] = (0.0, 0.0, 0.0, 1.0)

    def _check_shape(self) -> None:
        self._set("rotation", check_rotation("rotation", self.rotation))

    @property
    def orientation(self) -> Rotation:
        from scipy.spatial.transform import Rotation

        return Rotation.from_quat(self.rotation)

    def _moved_orientation(self, rotation: Rotation) -> dict[str, Any]:
        return {"rotation": tuple((rotation * self.orientation).as_quat())}
