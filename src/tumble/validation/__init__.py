"""The checks of input every layer of tumble uses: one place, one wording per rule.

Moments, axes, vectors, numbers (:mod:`~tumble.validation.values`), the messages' helpers
(:mod:`~tumble.validation.messages`), orientations
(:mod:`~tumble.validation.rotations`), input files (:mod:`~tumble.validation.files`) and functions
(:mod:`~tumble.validation.callables`). Each
checker returns the cleaned value or raises ``ValueError`` whose message names the field, the
value and what is allowed, e.g. ``radius = -0.1 must be a positive finite number (m)``; Python
constructors, the TOML loader and the CLI all surface these same messages. This package is the
lowest layer of tumble: it imports nothing of tumble but the array aliases (an import-linter
contract keeps it so). Units are SI.
"""

from __future__ import annotations

from .callables import check_callable, check_torque_function, is_vector
from .files import NoSuchFileError, json_object, read_input_file
from .messages import beyond, nearest, short_repr, unknown_name
from .rotations import MATRIX_ORTHO_TOL, QUAT_NORM_TOL, check_covariance, check_motion, check_quaternions, check_rotation
from .values import (
    AXES_ALLOWED,
    AXIS_ROLES,
    BOUND_REASONS,
    INERTIA_RTOL,
    MAX_INERTIA,
    MAX_RATE,
    axis_index,
    breaks_triangle,
    check_at_most,
    check_bool,
    check_direction,
    check_increasing,
    check_moments,
    check_noise,
    check_number,
    check_positive,
    check_vector,
    check_vectors,
    is_body,
    refuse_body,
    refuse_first,
    triangle_excess,
)

__all__ = [
    "AXES_ALLOWED",
    "AXIS_ROLES",
    "BOUND_REASONS",
    "INERTIA_RTOL",
    "MATRIX_ORTHO_TOL",
    "MAX_INERTIA",
    "MAX_RATE",
    "QUAT_NORM_TOL",
    "NoSuchFileError",
    "axis_index",
    "beyond",
    "breaks_triangle",
    "check_at_most",
    "check_bool",
    "check_callable",
    "check_covariance",
    "check_direction",
    "check_increasing",
    "check_moments",
    "check_motion",
    "check_noise",
    "check_number",
    "check_positive",
    "check_quaternions",
    "check_rotation",
    "check_torque_function",
    "check_vector",
    "check_vectors",
    "is_body",
    "is_vector",
    "json_object",
    "read_input_file",
    "refuse_body",
    "refuse_first",
    "nearest",
    "short_repr",
    "unknown_name",
    "triangle_excess",
]
