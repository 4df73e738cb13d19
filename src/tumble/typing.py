"""The array types of tumble's signatures: one place for the aliases every layer uses.

Inputs are annotated with :data:`ArrayLike` (anything :func:`numpy.asarray` accepts: lists,
tuples, scalars, arrays); outputs with the aliases below, all ``float64`` (SI units) unless
the name says otherwise. numpy's type system does not check shapes, so the shape an alias
stands for is a promise of the docstrings, written into the name for the reader: a
:data:`Vector3` is a body-frame vector such as ``omega`` (rad/s) or ``L`` (kg m^2/s) of shape
``(3,)`` or a batch ``(..., 3)``; a :data:`Matrix3` is an inertia tensor (kg m^2) or a
rotation matrix of shape ``(3, 3)`` or ``(..., 3, 3)``; a :data:`Quaternion` is scalar-last
``(x, y, z, w)`` as in scipy, shape ``(4,)`` or ``(..., 4)``.

This module imports numpy only, so every layer (``tumble.validation`` and
``tumble.dynamics.special`` included) may import it.

Examples
--------
>>> import numpy as np
>>> from tumble.typing import ArrayLike, Vector3
>>> def spin_energy(moments: ArrayLike, omega: ArrayLike) -> float:
...     return 0.5 * float(np.sum(np.asarray(moments, float) * np.asarray(omega, float) ** 2))
>>> spin_energy([1.0, 2.0, 3.0], [0.0, 0.0, 1.0])
1.5
>>> def unit_z() -> Vector3:
...     return np.array([0.0, 0.0, 1.0])
>>> unit_z().dtype
dtype('float64')
"""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["ArrayLike", "BoolArray", "FloatArray", "FloatOrArray", "IntArray", "Matrix3", "NDArray", "Quaternion", "Vector3"]

#: An array of floats (float64) of any shape: times (s), angles (rad), energies (J), ...
FloatArray: TypeAlias = NDArray[np.float64]

#: A float64 array of shape ``(3,)`` or ``(..., 3)``: angular velocity (rad/s), angular
#: momentum (kg m^2/s), torque (N m), principal moments (kg m^2), a position (m).
Vector3: TypeAlias = NDArray[np.float64]

#: A float64 array of shape ``(3, 3)`` or ``(..., 3, 3)``: an inertia tensor (kg m^2) or a
#: rotation matrix (body to world).
Matrix3: TypeAlias = NDArray[np.float64]

#: A float64 array of shape ``(4,)`` or ``(..., 4)``: a unit quaternion, scalar last.
Quaternion: TypeAlias = NDArray[np.float64]

#: A float or a float64 array: the arguments of the kernels that serve one body (Python floats,
#: fast) and a batch (arrays, elementwise) alike.
FloatOrArray: TypeAlias = float | NDArray[np.float64]

#: An array of booleans (masks, per-case flags).
BoolArray: TypeAlias = NDArray[np.bool_]

#: An array of integers (indices, counts); any integer width.
IntArray: TypeAlias = NDArray[np.integer[Any]]
