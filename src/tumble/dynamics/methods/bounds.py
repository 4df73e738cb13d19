"""The spin a run can reach, which bounds a stepping method's work and sets its steps and tolerances,
and a body-frame torque given in design coordinates turned to principal ones: the parts of
:func:`tumble.simulate`'s checks that read the torque models (:mod:`tumble.dynamics.simulate`).

Examples
--------
>>> import numpy as np
>>> from tumble.dynamics.methods.bounds import spin_bound
>>> spin_bound(None, np.array([3.0, 4.0, 0.0]), np.array([0.0, 1.0]))   # |omega0|, rad/s
5.0
"""

from __future__ import annotations

import functools
import math
from typing import cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import FloatArray, Matrix3, Quaternion, Vector3
from ..models.internal import InternalModel
from ..models.torques import (
    KERNEL_BODY,
    KERNEL_CIRCULAR_GRAVITY,
    KERNEL_NONE,
    KERNEL_WORLD,
    ConstantTorque,
    FunctionTorque,
    TorqueModel,
    kernel_form,
    spin_gain,
)

#: A torque's compiled form, ``(kind, parameters)``.
Form = tuple[int, tuple[float, ...]]

__all__ = ["design_torque", "linear_gain", "run_spin_gain", "spin_bound"]


def spin_bound(internal: InternalModel | None, omega0: Vector3, t: FloatArray) -> float:
    """The spin (rad/s) a run starts from, with what rotors can hand the body
    (:meth:`~tumble.dynamics.models.internal.InternalModel.spin_bound`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.bounds import spin_bound
    >>> spin_bound(None, np.array([3.0, 0.0, 4.0]), np.linspace(0.0, 1.0, 5))   # no rotors: |omega0|
    5.0
    """
    if internal is None:
        return math.hypot(*omega0.tolist())
    return float(internal.spin_bound(omega0, t))


def run_spin_gain(model: TorqueModel | None, omega0: Vector3, quat0: Quaternion, moments: Vector3, t_end: float) -> float:
    """Bound on the spin (rad/s) the torque adds over the run
    (:func:`~tumble.dynamics.models.torques.spin_gain`); ``quat0`` the initial attitude (body to
    world, scalar last), read only by a model that needs it.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.bounds import run_spin_gain
    >>> run_spin_gain(tumble.ConstantTorque((0.0, 0.0, 0.5)), np.zeros(3), np.array([0.0, 0.0, 0.0, 1.0]),
    ...               np.array([2.0, 3.0, 4.0]), 10.0)   # |tau| t / I1
    2.5
    """
    if model is None:
        return 0.0
    form = kernel_form(model)
    constant = form is not None and form[0] in (KERNEL_BODY, KERNEL_WORLD)  # reads no attitude
    return spin_gain(model, 0.0, omega0, None if constant else _rotation(quat0.tobytes()), moments, t_end)


def linear_gain(form: Form | None, moments: Vector3, t_end: float) -> float | None:
    """A bound on the spin (rad/s) a built-in torque adds over ``t_end`` (s) that reads no attitude,
    from its compiled form ``form`` (:func:`~tumble.dynamics.models.torques.kernel_form`; None: a
    Python torque),
    ``|tau|max t_end / I1`` (``|L(t) - L(0)| <= |tau|max t`` and ``|omega| <= |L| / I1``, as
    :func:`~tumble.dynamics.models.torques.spin_gain` bounds a constant torque), or None where
    there is none to hand: a constant torque's ``|tau|``; the gravity gradient of a circular orbit,
    ``3 n^2 |r x I r| <= 3 n^2 (I3 - I1) / 2`` (Hughes, *Spacecraft Attitude Dynamics*, ch. 8:
    ``r x I r`` is largest, ``(I3 - I1) / 2``, for ``r`` halfway between the axes of I1 and I3).
    It grows with the run; the gravity gradient's own bound (its Jacobi integral) does not.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.bounds import linear_gain
    >>> I = np.array([2.0, 3.0, 4.0])
    >>> linear_gain(tumble.ConstantTorque((0.0, 0.0, 0.5)).kernel_form(), I, 10.0)   # 0.5 * 10 / 2
    2.5
    >>> gg = tumble.GravityGradient(orbit_period=5400.0, moments=[2.0, 3.0, 4.0])
    >>> n = gg.mean_motion
    >>> bool(np.isclose(linear_gain(gg.kernel_form(), I, 10.0), 1.5 * n * n * (4.0 - 2.0) * 10.0 / 2.0))
    True
    """
    if form is None:
        return None
    I1, _, I3 = cast("list[float]", moments.tolist())
    if form[0] in (KERNEL_BODY, KERNEL_WORLD):
        return math.hypot(*form[1]) / I1 * t_end  # spin_gain's arithmetic
    if form[0] == KERNEL_CIRCULAR_GRAVITY:
        n = form[1][0]
        return 1.5 * n * n * (I3 - I1) * t_end / I1
    return 0.0 if form[0] == KERNEL_NONE else None


@functools.lru_cache(maxsize=256)
def _rotation(quat: bytes) -> Rotation:
    """The scipy Rotation of a quaternion's float64 bytes, kept for repeated runs (~10 us each);
    Rotation objects are not changed in place, so one can be shared."""
    return Rotation.from_quat(np.frombuffer(quat))


def design_torque(model: TorqueModel, A: Matrix3) -> TorqueModel:
    """Wrap a body-frame torque given in design coordinates so it returns principal ones; ``A`` the
    principal -> design rotation (columns: the principal axes); ``w`` is one angular velocity (3,)
    or the (n, 3) stack the splitting methods pass (row vectors: ``w A^T`` is ``A w`` for each row).
    A constant torque stays a :class:`~tumble.dynamics.models.torques.ConstantTorque`, compiled.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.bounds import design_torque
    >>> A = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])   # principal x is design y, ...
    >>> design_torque(tumble.ConstantTorque((0.0, 2.0, 0.0)), A).kernel_form()   # design y: principal x
    (1, (2.0, 0.0, 0.0))
    """
    form = kernel_form(model)
    if form is not None and form[0] == KERNEL_BODY:  # a constant vector: turned once, and it stays compiled
        return ConstantTorque(tuple((np.asarray(form[1], float) @ A).tolist()))
    return FunctionTorque(lambda t, w, att: np.asarray(model(t, np.asarray(w) @ A.T, att), float) @ A, "body")
