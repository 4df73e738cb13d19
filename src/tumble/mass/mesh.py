"""A part given by a closed triangle mesh (STL, OBJ, PLY, ... via trimesh).

The mesh is read with trimesh (imported here only, so the rest of tumble runs without it) and
its volume, centre of mass and inertia come from trimesh's exact integration over the
triangles (Eberly, *Polyhedral Mass Properties (Revisited)*, 2003; Tonon, J. Math. Stat. 1,
2004). A mesh that does not enclose a volume has no such properties, so it is refused.
"""

from __future__ import annotations

import io
import os
from dataclasses import dataclass, field
from types import ModuleType
from typing import TYPE_CHECKING, Any, ClassVar, cast

import numpy as np

from .._optional import optional_import
from ..typing import ArrayLike, BoolArray, FloatArray, Matrix3, Vector3
from ..validation import check_motion, check_positive, check_vector, read_input_file
from .part_base import _Oriented
from .parts import PART_KINDS

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

__all__ = ["MAX_MESH_BYTES", "Mesh", "winding_number"]


def _trimesh() -> ModuleType:
    return optional_import("trimesh", "mesh", "a mesh part (Mesh)")


def winding_number(triangles: ArrayLike, points: ArrayLike) -> FloatArray:
    """The winding number of a closed, outward-wound triangle surface about each point: 1 inside, 0 outside.

    The sum of the solid angles the triangles subtend at the point over 4 pi, each from Van
    Oosterom & Strackee's formula (IEEE Trans. Biomed. Eng. 30(2), 125, 1983),
    ``tan(Omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)`` with a, b, c the
    corners less the point; the generalised winding number of Jacobson, Kavan & Sorkine-Hornung
    (ACM TOG 32(4), 2013). Written here because trimesh's ``contains`` needs the optional rtree
    package; this needs numpy only, at O(points x triangles), in chunks.

    Parameters
    ----------
    triangles : array_like, shape (m, 3, 3)
        The corners of each triangle, m, counter-clockwise seen from outside.
    points : array_like, shape (n, 3)
        Where to evaluate it, m.

    Returns
    -------
    ndarray, shape (n,)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.mass.mesh import winding_number
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)   # a tetrahedron
    >>> faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    >>> winding_number(v[faces], [[0.1, 0.1, 0.1], [1.0, 1.0, 1.0]]).round(12).tolist()
    [1.0, 0.0]
    """
    tri = np.asarray(triangles, dtype=float)
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    total = np.empty(len(p))
    chunk = max(1, 1_000_000 // max(len(tri), 1))  # ~1e6 point-triangle pairs at a time (~100 MB)
    for start in range(0, len(p), chunk):
        d = tri[None, :, :, :] - p[start:start + chunk, None, None, :]  # (n, m, corner, xyz)
        a, b, c = d[:, :, 0], d[:, :, 1], d[:, :, 2]
        la, lb, lc = (np.linalg.norm(v, axis=-1) for v in (a, b, c))
        det = np.einsum("...i,...i->...", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("...i,...i->...", a, b) * lc + np.einsum("...i,...i->...", a, c) * lb
               + np.einsum("...i,...i->...", b, c) * la)
        total[start:start + chunk] = np.arctan2(det, den).sum(axis=1) / (2.0 * np.pi)
    return total


def _check_shells(mesh: Any, name: object) -> None:
    """Refuse a mesh of several closed shells whose sum is not one solid: a shell wound inside out
    that is no cavity of another (trimesh's winding check is per edge, so a whole shell wound inward
    passed, and its volume was taken away: a walkthrough's box beside an inward cube came out 15 %
    light, its centre of mass on the wrong side), or an outward shell inside another (nested or
    overlapping shells, whose common volume would count twice). Each shell is judged at one point of
    its surface (the centre of its first face) by the other shells' summed winding number
    (:func:`winding_number`: an outward shell adds 1 inside it, an inward one -1), so two shells that
    cross without a tested point inside the other are not seen."""
    if mesh.body_count <= 1:
        return
    shells = mesh.split(only_watertight=False)
    for k, shell in enumerate(shells):
        point = shell.triangles[0].mean(axis=0)
        depth = sum(float(winding_number(other.triangles, point)[0]) for j, other in enumerate(shells) if j != k)
        volume = float(shell.volume)
        where = f"mesh {name!s}: shell {k + 1} of {len(shells)}"
        if volume < 0 and depth < 0.5:
            raise ValueError(f"{where} is wound inside out (its volume {volume:.6g} m^3 is negative) and is no cavity "
                             "inside another shell: fix its normals")
        if volume > 0 and depth > 0.5:
            raise ValueError(f"{where} lies inside another shell (nested or overlapping), so the volume they share "
                             "would count twice: join them into one solid first, or wind an inner cavity's faces inward")


#: The largest mesh file a :class:`Mesh` part reads, in bytes (200 MiB): about four million
#: triangles in binary STL, far more than mass properties need. The file is checked before it is
#: opened and read with a bounded read, so a device, a FIFO or a huge file is refused at once.
MAX_MESH_BYTES = 200 << 20


def _load(source: Any) -> Any:
    """A trimesh.Trimesh from a mesh object (copied) or a file (size and type checked first)."""
    trimesh = _trimesh()
    if isinstance(source, trimesh.Trimesh):
        return source.copy()
    path = os.fspath(source)
    label = f"mesh = {path!r}"
    data = read_input_file(path, limit=MAX_MESH_BYTES, what="a mesh file", label=label)
    file_type = os.path.splitext(path)[1].lstrip(".").lower()
    try:
        # processed below (process(): the duplicated vertices of STL files merged, without which no STL is
        # watertight), once its vertices are checked; the watertightness check catches what merging cannot mend.
        mesh = trimesh.load(io.BytesIO(data), file_type=file_type, force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for malformed files; its words named its internals
        why = (f"a vertex lacks the coordinate {exc}" if isinstance(exc, KeyError) else
               f"a face names a vertex the file does not have ({exc})" if isinstance(exc, IndexError) else str(exc))
        raise ValueError(f"{label} could not be read: {why}") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ValueError(f"{label} holds no triangles")
    if not np.all(np.isfinite(mesh.vertices)):  # processing drops them, and it was "not watertight (3 open edges)"
        raise ValueError(f"{label} has vertices that are not finite numbers (nan or inf): it bounds no solid")
    return mesh.process()


@dataclass(frozen=True, kw_only=True, eq=False)
class Mesh(_Oriented):
    """A solid bounded by a closed, consistently wound triangle mesh.

    Parameters
    ----------
    mesh : str, os.PathLike or trimesh.Trimesh
        The surface: a file trimesh can read (a regular file of at most
        :data:`MAX_MESH_BYTES`), or a mesh object.
    scale : float
        Factor from file units to metres (e.g. 0.001 for a file in mm). Default 1.
    origin : array_like, shape (3,)
        Where the mesh's own origin goes in the design frame, m. Default (0, 0, 0), so a
        file's coordinates are design coordinates.
    rotation : quaternion [x, y, z, w], 3x3 matrix or scipy Rotation
        Orientation of the mesh's own frame in the design frame (applied about its origin).
    mass or density : float
        Total mass (kg) or uniform density (kg/m^3), exactly one.

    Notes
    -----
    ``center`` is derived: the centre of mass of the placed mesh. Refused: meshes that are
    not watertight, not consistently wound, or enclose no positive volume (inward normals).

    Examples
    --------
    >>> import trimesh, tumble
    >>> cube = tumble.Mesh(mesh=trimesh.creation.box(extents=(1.0, 2.0, 3.0)), mass=12.0)
    >>> cube.inertia.round(6).diagonal().tolist()   # as the closed-form Box: m (b^2 + c^2) / 12 and cyclic
    [13.0, 10.0, 5.0]
    """

    kind: ClassVar[str] = "mesh"
    mesh: Any
    scale: float = 1.0
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    center: tuple[float, float, float] = field(default=(0.0, 0.0, 0.0), init=False)
    _volume: float = field(default=0.0, init=False, repr=False)
    _com_local: Any = field(default=None, init=False, repr=False)
    _unit_inertia: Any = field(default=None, init=False, repr=False)

    def _check_shape(self) -> None:
        super()._check_shape()
        scale = check_positive("scale", self.scale, "m per file unit")
        self._set("scale", scale)
        self._set("origin", check_vector("origin", self.origin, "m"))
        name = self.mesh if isinstance(self.mesh, (str, os.PathLike)) else "mesh"
        mesh = _load(self.mesh)
        if scale != 1.0:
            mesh.apply_scale(scale)
        size = float(np.max(mesh.extents)) if len(mesh.vertices) else 0.0
        if not 1e-6 <= size <= 1e7:  # 1e-200 made every product of its coordinates NaN (numpy's "invalid value")
            raise ValueError(f"mesh {self.mesh!s} with scale = {self.scale!r} is {size:.3g} m across: beyond what tumble "
                             "weighs (1 um to 10,000 km); scale is metres per file unit (1e-3 for a file in mm)")
        if not mesh.is_watertight:
            _, uses = np.unique(mesh.edges_sorted, axis=0, return_counts=True)
            if np.all(uses >= 2):  # no open edge: some edge has more than two faces (a walkthrough's two cubes on an edge)
                raise ValueError(f"mesh {name!s} is not a manifold: {int(np.sum(uses > 2))} of its edges have more than two "
                                 "faces (solids that touch along an edge), so it bounds no one solid; separate or join them")
            raise ValueError(
                f"mesh {name!s} is not watertight (it has {int(np.sum(uses == 1))} open edges), so it encloses no volume "
                f"and has no mass properties; close its holes first"
            )
        if not mesh.is_winding_consistent:
            raise ValueError(f"mesh {name!s} is not consistently wound; fix its face orientation")
        _check_shells(mesh, name)
        props = mesh.mass_properties  # density 1: inertia per unit density
        volume = float(props.volume)
        if not volume > 0:
            raise ValueError(
                f"mesh {name!s} encloses volume {volume:.6g} m^3; a negative volume means its "
                f"faces point inward (fix the normals)"
            )
        self._set("mesh", mesh)
        self._set("_volume", volume)
        self._set("_com_local", np.array(props.center_mass, dtype=float))
        self._set("_unit_inertia", np.array(props.inertia, dtype=float) / volume)
        com = self.orientation.apply(self._com_local) + np.array(self.origin)
        self._set("center", tuple(float(x) for x in com))

    @property
    def volume(self) -> float:
        """Volume enclosed by the placed mesh, m^3.

        Examples
        --------
        >>> import trimesh, tumble
        >>> round(tumble.Mesh(mesh=trimesh.creation.box(extents=(1.0, 2.0, 3.0)), density=1.0).volume, 6)
        6.0
        """
        return self._volume

    def _local_inertia(self) -> Matrix3:
        return cast(Matrix3, cast(float, self.mass) * self._unit_inertia)

    @property
    def _frame_origin(self) -> Vector3:
        return np.array(self.origin, dtype=float)  # the mesh's own origin, not its centre of mass

    @property
    def _triangles(self) -> int:
        return len(self.mesh.faces)

    def _local_bounds(self) -> tuple[Vector3, Vector3]:
        lo, hi = np.array(self.mesh.bounds, dtype=float)
        return lo, hi

    def _inside_local(self, x: FloatArray, slack: float) -> BoolArray:
        # a point on a face has winding number 1/2: a hole flush with the mesh's face samples
        # only points strictly inside itself, so the slack is not needed here
        return winding_number(np.array(self.mesh.vertices, dtype=float)[self.mesh.faces], x) > 0.5

    def moved(self, rotation: Rotation | ArrayLike, translation: ArrayLike = (0.0, 0.0, 0.0)) -> Mesh:
        """The same part after a rigid motion ``x -> R x + t`` of the design frame.

        Examples
        --------
        >>> import trimesh, tumble
        >>> cube = tumble.Mesh(mesh=trimesh.creation.box(extents=(1.0, 1.0, 1.0)), mass=1.0)
        >>> cube.moved((0, 0, 0, 1), translation=(0.0, 0.0, 2.0)).com.round(6).tolist()
        [0.0, 0.0, 2.0]
        """
        R, t = check_motion(rotation, translation)
        return Mesh(
            mesh=self.mesh,
            origin=tuple(R.apply(self.origin) + t),
            rotation=tuple((R * self.orientation).as_quat()),
            mass=None if self.density is not None else self.mass,
            density=self.density,
            subtract=self.subtract,
        )


PART_KINDS[Mesh.kind] = Mesh
