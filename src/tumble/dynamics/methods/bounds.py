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

from ...typing import ArrayLike, FloatArray, Matrix3, Quaternion, Vector3
from ..models.dipole import ResidualDipole
from ..models.internal import InternalModel
from ..models.torques import (
    KERNEL_BODY,
    KERNEL_CIRCULAR_GRAVITY,
    KERNEL_NONE,
    KERNEL_SUM,
    KERNEL_WORLD,
    BoundsSpin,
    ConstantTorque,
    FunctionTorque,
    TorqueModel,
    TorqueSum,
    body_torque,
    conforms,
    kernel_form,
)
from ..models.torque_protocols import constant_terms

#: A torque's compiled form, ``(kind, parameters)``.
Form = tuple[int, tuple[float, ...]]

__all__ = ["design_torque", "linear_gain", "run_spin_gain", "spin_bound", "spin_gain", "spin_gains"]


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
    (:func:`spin_gain`); ``quat0`` the initial attitude (body to
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
    constant = constant_terms(kernel_form(model)) is not None  # reads no attitude
    return spin_gain(model, 0.0, omega0, None if constant else _rotation(quat0.tobytes()), moments, t_end)


def linear_gain(form: Form | None, moments: Vector3, t_end: float) -> float | None:
    """A bound on the spin (rad/s) a built-in torque adds over ``t_end`` (s) that reads no attitude,
    from its compiled form ``form`` (:func:`~tumble.dynamics.models.torques.kernel_form`; None: a
    Python torque),
    ``|tau|max t_end / I1`` (``|L(t) - L(0)| <= |tau|max t`` and ``|omega| <= |L| / I1``, as
    :func:`spin_gain` bounds a constant torque), or None where
    there is none to hand: a constant torque's ``|tau|``; the gravity gradient of a circular orbit,
    ``3 n^2 |r x I r| <= 3 n^2 (I3 - I1) / 2`` (Hughes, *Spacecraft Attitude Dynamics*, ch. 8:
    ``r x I r`` is largest, ``(I3 - I1) / 2``, for ``r`` halfway between the axes of I1 and I3).
    It grows with the run; the gravity gradient's own bound (its Jacobi integral) does not.
    A sum of models (``KERNEL_SUM``) adds its terms' bounds (``|a + b| <= |a| + |b|``), the
    gravity gradient's ``n^2`` summed in its slot.

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
    >>> both = (gg + tumble.ConstantTorque((0.0, 0.0, 0.5), "world")).kernel_form()   # the two bounds, added
    >>> bool(np.isclose(linear_gain(both, I, 10.0), 2.5 + 1.5 * n * n * (4.0 - 2.0) * 10.0 / 2.0))
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
    if form[0] == KERNEL_SUM:
        P = form[1]
        return (math.hypot(P[0], P[1], P[2]) + math.hypot(P[3], P[4], P[5]) + 1.5 * P[6] * (I3 - I1)) / I1 * t_end
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
    A function is called as it would be on the body's design frame: ``omega`` in design coordinates
    and ``attitude`` the design frame's rotation to the world.
    A constant torque stays a :class:`~tumble.dynamics.models.torques.ConstantTorque`, compiled, and a
    :class:`~tumble.dynamics.models.dipole.ResidualDipole` one with its dipole turned (its field is the
    world's); of a :class:`~tumble.dynamics.models.torques.TorqueSum`, the body-frame terms are turned
    and the world-frame ones kept.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.bounds import design_torque
    >>> A = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])   # principal x is design y, ...
    >>> design_torque(tumble.ConstantTorque((0.0, 2.0, 0.0)), A).kernel_form()   # design y: principal x
    (1, (2.0, 0.0, 0.0))
    >>> design_torque(tumble.ConstantTorque((0.0, 2.0, 0.0)) + tumble.ConstantTorque((0.0, 2.0, 0.0), "world"),
    ...               A).kernel_form()   # the body term turned, the world term kept: P and n of the sum
    (5, (2.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    """
    if isinstance(model, TorqueSum):
        return TorqueSum(*(design_torque(term, A) if term.frame == "body" else term for term in model.terms))
    if isinstance(model, ResidualDipole) and type(model).__call__ is ResidualDipole.__call__:  # its dipole turned once
        return ResidualDipole(tuple((np.asarray(model.dipole, float) @ A).tolist()), model.field)
    form = kernel_form(model)
    if form is not None and form[0] == KERNEL_BODY:  # a constant vector: turned once, and it stays compiled
        return ConstantTorque(tuple((np.asarray(form[1], float) @ A).tolist()))
    # the function reads omega and the attitude in design coordinates, as it returns its torque:
    # design -> world is (principal -> world)(design -> principal), A^T the second
    to_principal = Rotation.from_matrix(np.asarray(A, float).T)
    return FunctionTorque(lambda t, w, att: np.asarray(model(t, np.asarray(w) @ A.T, att * to_principal), float) @ A,
                          "body")


def spin_gain(
    model: TorqueModel | None, t: float, omega: ArrayLike, attitude: Rotation | None, moments: ArrayLike,
    duration: float,
) -> float:
    """Bound on the spin (rad/s) a torque can add to ``|omega|`` over ``duration`` (s), for
    bounding a run's work and choosing default steps: the largest of :func:`spin_gains` over
    a batch. ``attitude`` may be None for a constant torque, which does not read it.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.torques import ConstantTorque
    >>> from tumble.dynamics.methods.bounds import spin_gain
    >>> torque = ConstantTorque((0.0, 0.0, 0.5))   # |tau| t / I1: 0.5 N m for 10 s on I1 = 2 kg m^2
    >>> spin_gain(torque, 0.0, np.zeros(3), Rotation.identity(), [2.0, 3.0, 4.0], 10.0)
    2.5
    >>> spin_gain(None, 0.0, np.zeros(3), Rotation.identity(), [2.0, 3.0, 4.0], 10.0)
    0.0
    """
    if model is None:
        return 0.0
    form = kernel_form(model)
    if form is not None and form[0] in (KERNEL_BODY, KERNEL_WORLD):  # a constant vector: no attitude read
        gain = _constant_gain(form[1], np.asarray(moments, float), duration)
        return gain if isinstance(gain, float) else float(np.max(gain))
    gains = spin_gains(model, t, omega, attitude, moments, duration)
    return float(gains) if np.ndim(gains) == 0 else float(np.max(gains))  # one body's needs no reduction


def _constant_gain(vector: tuple[float, ...], moments: FloatArray, duration: float) -> float | FloatArray:
    """``|tau| duration / I1`` for a constant torque ``vector`` (N m): per body for moments (N, 3),
    the largest for one body's (3,) (Python floats: the same operations, fewer calls)."""
    if moments.ndim == 1:
        return float(math.hypot(*vector) / min(moments.tolist()) * duration)
    return cast(FloatArray, math.hypot(*vector) / np.min(moments, axis=-1) * duration)


def _term_gains(model: TorqueModel, t: float, omega: FloatArray, attitude: Rotation | None, moments: ArrayLike,
                duration: float) -> FloatArray:
    """One term's share of a sum's :func:`spin_gains`: a bound that holds beside other torques. A
    model's own bound on the whole motion (:class:`~tumble.dynamics.models.torques.BoundsSpin`, the
    gravity gradient's Jacobi integral) does not, so a compiled term takes its torque's largest
    size (:func:`linear_gain`, per body); any other its own gains."""
    form = kernel_form(model)
    if form is None or not conforms(model, BoundsSpin):
        return spin_gains(model, t, omega, attitude, moments, duration)
    I = np.atleast_2d(np.asarray(moments, float))
    gains = np.array([linear_gain(form, row, duration) for row in I])
    return cast(FloatArray, gains[0] if np.ndim(moments) == 1 else gains)


def spin_gains(
    model: TorqueModel | None, t: float, omega: ArrayLike, attitude: Rotation | None, moments: ArrayLike,
    duration: float,
) -> FloatArray:
    """Per body, a bound on the spin (rad/s) a torque can add to ``|omega|`` over ``duration`` (s).

    A model that knows a bound on ``|omega|`` for the whole motion says so through a method
    ``max_spin(t, omega, attitude)`` (:class:`~tumble.dynamics.models.torques.BoundsSpin`; the gravity gradient does, from its
    Jacobi integral);
    otherwise ``|tau(t)| duration / I1``, exact for a constant torque (``|L(t) - L(0)| <=
    |tau| t`` and ``|omega| <= |L| / I1``; no attitude needed) and an estimate from the start
    for any other. 0 without a torque. ``omega`` (3,) or (N, 3) and ``attitude`` as for
    :func:`~tumble.dynamics.models.torques.body_torque`; ``moments`` (3,) or (N, 3), kg m^2. Shape () or (N,).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.torques import ConstantTorque
    >>> from tumble.dynamics.methods.bounds import spin_gains
    >>> spin_gains(ConstantTorque((0.0, 0.0, 0.5)), 0.0, np.zeros((2, 3)), None, [[2.0, 3.0, 4.0], [1.0, 3.0, 4.0]],
    ...            10.0).tolist()
    [2.5, 5.0]
    """
    w = np.asarray(omega, float)
    if model is None:
        return np.zeros(w.shape[:-1])
    form = kernel_form(model)
    with np.errstate(over="ignore", invalid="ignore"):
        if form is not None and form[0] in (KERNEL_BODY, KERNEL_WORLD):  # a constant vector: |tau| in any frame
            return _constant_gain(form[1], np.asarray(moments, float), duration) + np.zeros(w.shape[:-1])
        if isinstance(model, TorqueSum):  # |a + b| <= |a| + |b|: each term's gain as if it acted alone
            return cast(FloatArray, sum(_term_gains(term, t, w, attitude, moments, duration) for term in model.terms))
        if attitude is None:
            raise ValueError(f"spin_gains needs the attitude for torque model {model!r}")
        if conforms(model, BoundsSpin):
            top = cast(BoundsSpin, model).max_spin(t, w, attitude)
            speed = math.hypot(*w.tolist()) if w.ndim == 1 else np.linalg.norm(w, axis=-1)  # |omega| of each body
            return cast(FloatArray, np.maximum(top - speed, 0.0))
        tau = body_torque(model, t, w, attitude)  # checks the model's answer
        return cast(FloatArray, np.linalg.norm(tau, axis=-1) / np.min(np.asarray(moments, float), axis=-1) * duration)
