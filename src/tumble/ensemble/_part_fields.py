"""The fields of a part or a preset that a dispersion may act on: their units and widths, how a
value is perturbed and a part rebuilt with it (:mod:`tumble.ensemble.dispersions`)."""

from __future__ import annotations

import dataclasses

import numpy as np

#: Part fields that are orientations, not numbers: not dispersed (use target "axes").
_NOT_NUMBERS = ("axis", "rotation", "subtract", "spin_acceleration")


def _unit(field: str) -> str:
    """The SI unit of a part field or preset parameter, from its name."""
    if "density" in field:
        return "kg/m^3"
    if "mass" in field:
        return "kg"
    if "spin" in field:
        return "rad/s"
    return "m"


def _is_number(v) -> bool:
    return not isinstance(v, (bool, np.bool_)) and isinstance(v, (int, float, np.integer, np.floating))


def _width(value) -> int:
    """1 for a number, 3 for a vector of 3 numbers, 0 for anything else."""
    if _is_number(value):
        return 1
    if isinstance(value, tuple) and len(value) == 3 and all(_is_number(v) for v in value):
        return 3
    return 0


def _perturb(value, spread: float, relative: bool, z: np.ndarray):
    """``value`` (a number or a 3-vector) times ``1 + spread z`` (relative) or plus ``spread z``."""
    v = np.asarray(value, dtype=float)
    out = v * (1.0 + spread * z) if relative else v + spread * z
    return float(out[0]) if out.shape == (1,) and np.ndim(value) == 0 else tuple(float(x) for x in out)


def _replace(part, field: str, value):
    """``part`` with ``field = value``: by density its mass follows, by mass its mass stays."""
    if field == "mass":
        return dataclasses.replace(part, mass=value, density=None)
    if field == "density":
        return dataclasses.replace(part, density=value, mass=None)
    if part.density is not None:
        return dataclasses.replace(part, **{field: value, "mass": None})
    return dataclasses.replace(part, **{field: value})
