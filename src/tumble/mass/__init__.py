"""Mass properties of rigid bodies built from parts (layer 1: numpy only, trimesh lazily)."""

from .body import AXIS_ROLES, Body, MassProperties, mass_properties
from .part_base import MAX_DENSITY, MIN_DENSITY, UnitSlipWarning
from .mesh import Mesh  # registers the 'mesh' kind; trimesh is imported on first use
from .parts import PART_KINDS, Box, Cone, Cylinder, Ellipsoid, Part, PointMass, Rod, Shell, Sphere, Tube
from .rotor import Rotor
from .presets import PRESETS, iss_t_handle, moments_body, t_handle
from .tensor import (
    INERTIA_RTOL,
    check_inertia,
    inertia_about_point,
    moment_degeneracy,
    parallel_axis,
    point_mass_inertia,
    principal_frame,
    rotate_inertia,
)


__all__ = [
    "AXIS_ROLES",
    "Body",
    "Box",
    "Cone",
    "Cylinder",
    "Ellipsoid",
    "INERTIA_RTOL",
    "MassProperties",
    "Mesh",
    "MAX_DENSITY",
    "MIN_DENSITY",
    "PART_KINDS",
    "PRESETS",
    "Part",
    "PointMass",
    "Rod",
    "Rotor",
    "Shell",
    "Sphere",
    "Tube",
    "UnitSlipWarning",
    "check_inertia",
    "inertia_about_point",
    "iss_t_handle",
    "moments_body",
    "mass_properties",
    "moment_degeneracy",
    "parallel_axis",
    "point_mass_inertia",
    "principal_frame",
    "rotate_inertia",
    "t_handle",
]
