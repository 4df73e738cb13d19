"""Mesh files (STL, OBJ, PLY) read directly as a body: one closed triangle mesh, one solid part.

``tumble inertia part.stl --units mm`` and :func:`body_from_mesh` read such a file (a body
file's ``kind = "mesh"`` part reads it through :class:`tumble.Mesh` too); a solid whose size is
implausible for its units is reported (:class:`MeshScaleWarning`), since a file exported in
millimetres and read as metres is the usual slip. Re-exported by :mod:`tumble.io.bodyfile`.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

from ..mass import Body, Mesh, Part, UnitSlipWarning
from ..validation import NoSuchFileError

__all__ = ["LIGHTEST_WRITTEN", "MESH_SUFFIXES", "MESH_UNITS", "MeshScaleWarning", "body_from_mesh", "is_mesh_file",
           "mesh_part", "mesh_scale_note", "written_density_note"]


#: The mesh files that :func:`body_from_mesh` (and ``tumble inertia``) read directly, by suffix
#: (any case): a solid whose whole surface is one closed triangle mesh.
MESH_SUFFIXES = (".stl", ".obj", ".ply")

#: The length units of a mesh file, as factors to metres (``tumble inertia part.stl --units mm``).
MESH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}


#: A mesh solid smaller or larger than this, across (m), is most likely read in the wrong unit.
PLAUSIBLE_SIZE = (1e-3, 20.0)


class MeshScaleWarning(UnitSlipWarning):
    """A mesh read at a size no hand-made solid has: most likely its file's unit was given wrongly
    (:func:`mesh_scale_note` says which).

    Examples
    --------
    A script that must not go on with a slipped unit makes the warning an error:

    >>> import warnings
    >>> from tumble.io.meshfile import MeshScaleWarning
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("error", MeshScaleWarning)
    ...     try:
    ...         warnings.warn("case.stl: the solid is 0.05 mm across", MeshScaleWarning)
    ...     except MeshScaleWarning as slip:
    ...         print(f"refused: {slip}")
    refused: case.stl: the solid is 0.05 mm across
    """


def mesh_scale_note(path: str | os.PathLike[str], part: Mesh, scale: float, *, key: str = "units") -> str | None:
    """One line when a mesh read at ``scale`` (m per file unit) is implausibly small or large.

    Its size is the cube root of its volume; below 1 mm or above 20 m across (:data:`PLAUSIBLE_SIZE`)
    the likely slip is named: a file already in metres read with ``units = "mm"`` weighs
    2e-10 kg at a plastic's density, a millimetre file read in metres is a building. ``key``: what
    the fix names, ``"units"`` (the command line's ``--units``) or ``"scale"`` (a body file's mesh
    part, which takes ``scale``, metres per file unit).

    Examples
    --------
    >>> import trimesh
    >>> from tumble import Mesh
    >>> from tumble.io.meshfile import mesh_scale_note
    >>> part = Mesh(mesh=trimesh.creation.box(extents=(0.05, 0.05, 0.05)), scale=0.001, density=1600.0)
    >>> print(mesh_scale_note("case.stl", part, 0.001))   # a 5 cm box exported in metres, read as mm
    case.stl: the solid is 0.05 mm across (the cube root of its volume; 2e-10 kg), read at 0.001 m per file unit: if the file's coordinates are metres, read it in metres (units = "m", or no --units)
    >>> mesh_scale_note("case.stl", Mesh(mesh=trimesh.creation.box(extents=(50.0, 50.0, 50.0)), scale=0.001, density=1600.0), 0.001) is None
    True
    """
    size = part.volume ** (1.0 / 3.0)
    read = f"read at {scale:g} m per file unit"
    body = key == "scale"
    if size < PLAUSIBLE_SIZE[0]:
        fix = (("metres, read it in metres (scale = 1)" if body else 'metres, read it in metres (units = "m", or no --units)')
               if scale < 1.0 else ("not metres, give scale = metres per file unit" if body
                                    else "not metres, give their unit (units)"))
        return (f"{path}: the solid is {size * 1e3:.3g} mm across (the cube root of its volume; {part.mass:.3g} kg), "
                f"{read}: if the file's coordinates are {fix}")
    if size > PLAUSIBLE_SIZE[1]:
        give = "scale = 0.001" if body else 'units = "mm" (--units mm)'
        return (f"{path}: the solid is {size:.3g} m across (the cube root of its volume; {part.mass:.3g} kg), {read}: if "
                f"the file's coordinates are millimetres, give {give}")
    return None


#: A density written in a file or on the command line below this (kg/m^3) is most likely in g/cm^3
#: (steel's 7.85, aluminium's 2.7, water's 1): a warning, since foams and aerogels are lighter still.
LIGHTEST_WRITTEN = 25.0


def written_density_note(density: float) -> str | None:
    """One line when a density as written (kg/m^3) is below :data:`LIGHTEST_WRITTEN`, else None.

    Examples
    --------
    >>> from tumble.io.meshfile import written_density_note
    >>> written_density_note(7850.0) is None, written_density_note(7.85)[:34]
    (True, 'density = 7.85 kg/m^3 is below any')
    """
    if density >= LIGHTEST_WRITTEN:
        return None
    return (f"density = {density!r} kg/m^3 is below any solid's but a foam's or an aerogel's (expanded polystyrene "
            f"15-30 kg/m^3): is it in g/cm^3? Write kg/m^3 (7.85 g/cm^3 = 7850 kg/m^3)")


def mesh_part(path: str | os.PathLike[str], *, key: str = "units", **kwargs: object) -> Part:
    """A :class:`tumble.Mesh` part, ``Mesh(mesh=path, **kwargs)``, with its unit slips said once each: a size
    no hand-made solid has (:func:`mesh_scale_note`, ``key`` as there), else the density its
    mass gives (the part's own :class:`~tumble.mass.UnitSlipWarning`: grams for kg), and a
    density written in g/cm^3 (:func:`written_density_note`). A mesh read in the wrong unit
    also has a density no solid has; only its size is named then. A ValueError of the part as it
    came.

    Examples
    --------
    >>> import pathlib, tempfile, trimesh, warnings
    >>> from tumble.io.meshfile import mesh_part
    >>> with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     path = pathlib.Path(folder, "box.stl")
    ...     _ = trimesh.creation.box(extents=(100.0, 200.0, 300.0)).export(path)   # in mm
    ...     part = mesh_part(path, scale=0.001, mass=2000.0)   # 2 kg written as grams
    >>> round(part.mass), [str(w.message)[:47] for w in caught]
    (2000, ['a mesh of 2e+03 kg in 0.006 m^3 is 3.33e+05 kg/'])
    """
    with warnings.catch_warnings(record=True) as slips:
        warnings.simplefilter("always", UnitSlipWarning)
        part = Mesh(mesh=os.fspath(path), **kwargs)  # type: ignore[arg-type]
    note = mesh_scale_note(path, part, part.scale, key=key)
    if note:
        warnings.warn(note, MeshScaleWarning, stacklevel=2)
    for slip in slips:
        if not (note and issubclass(slip.category, UnitSlipWarning)):
            warnings.warn(slip.message, slip.category, stacklevel=2)
    written = None if part.density is None else written_density_note(part.density)
    if written:
        warnings.warn(written, UnitSlipWarning, stacklevel=2)
    return part


def is_mesh_file(source: str | os.PathLike[str]) -> bool:
    """Whether ``source`` names a mesh file (by its suffix, any case: .stl, .obj, .ply).

    Examples
    --------
    >>> from tumble.io.meshfile import is_mesh_file
    >>> is_mesh_file("parts/bracket.STL"), is_mesh_file("bodies/t_handle.toml"), is_mesh_file("t-handle")
    (True, False, False)
    """
    return Path(source).suffix.lower() in MESH_SUFFIXES


def body_from_mesh(
    path: str | os.PathLike[str],
    *,
    density: float | None = None,
    mass: float | None = None,
    scale: float | None = None,
    units: str | None = None,
) -> Body:
    """A one-part body from a mesh file (STL, OBJ, PLY): a uniform solid, named after the file.

    The same body as a body file with one ``kind = "mesh"`` part, without writing that file.

    Parameters
    ----------
    path : str or os.PathLike
        The mesh file: a closed, consistently wound triangle mesh (see :class:`tumble.Mesh`).
    density, mass : float
        Uniform density (kg/m^3) or total mass (kg), exactly one.
    scale : float, optional
        Factor from file units to metres (e.g. 0.001 for a file in mm).
    units : {"m", "cm", "mm", "in"}, optional
        The file's length unit, instead of ``scale``. Default: metres.

    Raises
    ------
    ValueError
        One line: neither or both of ``density`` and ``mass``, both ``scale`` and ``units``, an
        unknown unit, or a mesh that cannot be read or encloses no volume (open, inconsistently
        wound, inside out), naming the file.

    Examples
    --------
    >>> import pathlib, tempfile, trimesh
    >>> from tumble.io.meshfile import body_from_mesh
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "brick.stl")
    ...     _ = trimesh.creation.box(extents=(10.0, 20.0, 30.0)).export(path)   # in cm
    ...     body = body_from_mesh(path, mass=12.0, units="cm")
    >>> body.name, body.principal_moments.round(6).tolist()   # m (b^2 + c^2) / 12 and cyclic, ascending
    ('brick', [0.05, 0.1, 0.13])
    """
    given = [k for k, v in (("density", density), ("mass", mass)) if v is not None]
    if len(given) != 1:
        raise ValueError(
            f"{path}: a mesh needs exactly one of density (kg/m^3) or mass (kg), "
            f"got {' and '.join(given) if given else 'neither'}"
        )
    if scale is not None and units is not None:
        raise ValueError(f"{path}: give scale = {scale!r} or units = {units!r}, not both")
    if units is not None:
        if units not in MESH_UNITS:
            raise ValueError(f"{path}: units = {units!r} is unknown; allowed: {', '.join(MESH_UNITS)}")
        scale = MESH_UNITS[units]
    try:
        part = mesh_part(path, scale=1.0 if scale is None else scale, density=density, mass=mass)
    except ValueError as exc:
        message = str(exc)
        raise (NoSuchFileError if isinstance(exc, FileNotFoundError) else ValueError)(message if os.fspath(path) in message else f"{path}: {message}") from None
    return Body((part,), name=Path(path).stem)
