"""The interface every torque model follows, and the kinds of torque the compiled engine evaluates:
the protocols :class:`TorqueModel`, :class:`NeedsBody`, :class:`BoundsSpin` and
:class:`KernelForm`, and :func:`kernel_terms`, the one sum of compiled forms into the engine's
terms (:mod:`tumble.dynamics.models.torques` re-exports all of it beside the models).

Examples
--------
>>> from tumble.dynamics.models.torque_protocols import KERNEL_BODY, KERNEL_WORLD, kernel_terms
>>> kernel_terms(((KERNEL_BODY, (0.0, 0.0, 1.0)), (KERNEL_WORLD, (1.0, 0.0, 0.0))))
((0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 0.0)
"""

from __future__ import annotations

import dataclasses
import functools
from typing import TYPE_CHECKING, Protocol, runtime_checkable

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike

if TYPE_CHECKING:
    from ...mass import Body, MassProperties

__all__ = [
    "BoundsSpin",
    "KERNEL_BODY",
    "KERNEL_CIRCULAR_GRAVITY",
    "KERNEL_NONE",
    "KERNEL_ROTOR_MOMENTUM",
    "KERNEL_SUM",
    "KERNEL_WORLD",
    "KernelForm",
    "NeedsBody",
    "TORQUE_FRAMES",
    "TorqueModel",
    "check_frame",
    "conforms",
    "constant_terms",
    "kernel_form",
    "kernel_terms",
]

#: The frames a torque may be given in: the body's principal frame or the world (inertial) frame.
TORQUE_FRAMES = ("body", "world")


@runtime_checkable
class TorqueModel(Protocol):
    """What every torque model is: called as ``model(t, omega, attitude)``, with a ``frame``.

    Attributes
    ----------
    frame : str
        ``"body"`` (the principal frame) or ``"world"``: the frame of the returned torque.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics import ConstantTorque, TorqueModel
    >>> isinstance(ConstantTorque((0.0, 0.0, 1.0)), TorqueModel)
    True
    >>> isinstance(lambda t, omega, attitude: np.zeros(3), TorqueModel)  # no frame: as_torque wraps it
    False
    """

    @property
    def frame(self) -> str:
        """``"body"`` or ``"world"`` (read-only: models are frozen dataclasses).

        Examples
        --------
        >>> from tumble.dynamics.models.torques import ConstantTorque, as_torque
        >>> ConstantTorque((0.0, 0.0, 1.0), "world").frame, as_torque(lambda t, omega, attitude: (0.0, 0.0, 1.0)).frame
        ('world', 'body')
        """

    def __call__(self, t: float, omega: np.ndarray, attitude: Rotation) -> np.ndarray:
        """The torque at time ``t`` (s) for ``omega`` (rad/s, principal frame, (3,) or (N, 3)) and
        ``attitude`` (principal frame to world), N m, in :attr:`frame`; shape (3,) or omega's.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.models.torques import ConstantTorque
        >>> torque = ConstantTorque((0.0, 0.0, 2.0))
        >>> torque(0.0, np.zeros(3), Rotation.identity()).tolist()   # N m, in torque.frame
        [0.0, 0.0, 2.0]
        >>> torque(0.0, np.zeros((2, 3)), Rotation.identity(2)).shape   # (3,) serves every body of a batch
        (3,)
        """


@runtime_checkable
class NeedsBody(Protocol):
    """An optional part of :class:`TorqueModel`: a model whose torque depends on the body's moments.

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, GravityGradient
    >>> from tumble.dynamics.models.torques import NeedsBody
    >>> isinstance(GravityGradient(orbit_period=5400.0), NeedsBody), isinstance(ConstantTorque((0, 0, 1)), NeedsBody)
    (True, False)
    """

    def bind(self, body: Body | MassProperties | ArrayLike) -> TorqueModel:
        """The model acting on ``body`` (a Body, MassProperties or principal moments, kg m^2,
        shape (3,) or (N, 3)); raises ``ValueError`` if it already holds other moments.

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> from tumble.dynamics.models.torques import NeedsBody
        >>> gg = GravityGradient(orbit_period=5400.0)
        >>> isinstance(gg, NeedsBody), gg.bind(tumble.MassProperties.from_moments([1.0, 2.0, 3.0])).moments
        (True, (1.0, 2.0, 3.0))
        """


@runtime_checkable
class BoundsSpin(Protocol):
    """An optional part of :class:`TorqueModel`: a model that bounds the spin of the whole motion.

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, GravityGradient
    >>> from tumble.dynamics.models.torques import BoundsSpin
    >>> isinstance(GravityGradient(orbit_period=5400.0), BoundsSpin), isinstance(ConstantTorque((0, 0, 1)), BoundsSpin)
    (True, False)
    """

    def max_spin(self, t: float, omega: np.ndarray, attitude: Rotation) -> np.ndarray:
        """An upper bound on ``|omega|`` (rad/s) over the whole motion from this state (``omega``
        (3,) or (N, 3), principal frame, rad/s); shape () or (N,).

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.models.gravity import GravityGradient
        >>> from tumble.dynamics.models.torques import BoundsSpin
        >>> gg = GravityGradient(orbit_period=5400.0, moments=[1.0, 2.0, 3.0])
        >>> omega = np.array([0.01, 0.0, 0.0])
        >>> isinstance(gg, BoundsSpin), bool(gg.max_spin(0.0, omega, Rotation.identity()) >= np.linalg.norm(omega))
        (True, True)
        """


#: The members of each protocol, for :func:`conforms`.
_MEMBERS: dict[type, tuple[str, ...]] = {TorqueModel: ("frame", "__call__"), NeedsBody: ("bind",), BoundsSpin: ("max_spin",)}
#: ``(class, protocol) -> answer`` for the classes whose every instance gives the same answer.
_CONFORMS: dict[tuple[type, type], bool] = {}


def conforms(obj: object, protocol: type) -> bool:
    """``isinstance(obj, protocol)`` for :class:`TorqueModel`, :class:`NeedsBody` or
    :class:`BoundsSpin`, remembered per class where that class decides it.

    typing's runtime protocol check looks up every member at each call (~25 us, a tenth of a
    short compiled run). Its answer depends on the class alone when the class itself has every
    member (an instance cannot lose a class attribute), or when it lacks one and is a frozen
    dataclass (whose instances take no new attributes): those answers are kept.

    Examples
    --------
    >>> from tumble.dynamics.models.torques import BoundsSpin, ConstantTorque, TorqueModel, conforms
    >>> conforms(ConstantTorque((0.0, 0.0, 1.0)), TorqueModel), conforms(ConstantTorque((0.0, 0.0, 1.0)), BoundsSpin)
    (True, False)
    >>> conforms(lambda t, omega, attitude: omega, TorqueModel)   # no frame
    False
    """
    key = (type(obj), protocol)
    known = _CONFORMS.get(key)
    if known is not None:
        return known
    answer = isinstance(obj, protocol)
    cls = type(obj)
    if all(hasattr(cls, name) for name in _MEMBERS[protocol]) or (
            dataclasses.is_dataclass(cls) and cls.__dataclass_params__.frozen):  # type: ignore[attr-defined]
        _CONFORMS[key] = answer
    return answer


def check_frame(frame: str) -> str:
    """``frame`` if it is a torque's frame (:data:`TORQUE_FRAMES`), else a ValueError naming it.

    Examples
    --------
    >>> from tumble.dynamics.models.torque_protocols import check_frame
    >>> check_frame("world")
    'world'
    >>> check_frame("inertial")
    Traceback (most recent call last):
    ...
    ValueError: torque frame = 'inertial' is not allowed; allowed: body, world
    """
    if not isinstance(frame, str) or frame not in TORQUE_FRAMES:
        raise ValueError(f"torque frame = {frame!r} is not allowed; allowed: body, world")
    return frame


#: The kinds of torque the compiled engine evaluates itself (:mod:`tumble.dynamics.engine`),
#: named by a model's :meth:`KernelForm.kernel_form`: none, a constant body-frame torque, a
#: constant world-frame torque, the gravity gradient of a circular orbit.
KERNEL_NONE, KERNEL_BODY, KERNEL_WORLD, KERNEL_CIRCULAR_GRAVITY = 0, 1, 2, 3
#: The constant internal momentum ``h`` (kg m^2/s, principal frame) of rotors spinning at constant
#: rates: its term of Euler's equations, ``h x omega`` (a gyrostat, Hughes, *Spacecraft Attitude
#: Dynamics*, sec. 3.4: ``I omega' + omega x (I omega + h) = tau``), for the engine.
KERNEL_ROTOR_MOMENTUM = 4
#: A sum of models (:class:`~tumble.dynamics.models.torques.TorqueSum`): its parameters are the
#: engine's terms already added up, the 10 slots of ``P`` and the orbit's mean motion ``n``
#: (:func:`kernel_terms`), so a sum is one form like any model's.
KERNEL_SUM = 5
#: The number of the engine's torque terms ``P`` (:mod:`tumble.dynamics.engine.kernels`).
TERMS = 10


@runtime_checkable
class KernelForm(Protocol):
    """A torque model the compiled engine evaluates itself: the one declared interface.

    ``kernel_form()`` returns ``(kind, parameters)``: a kind from ``KERNEL_*`` and the floats the
    engine's formula for that kind reads (:func:`tumble.dynamics.engine.kernels.external_torque`),
    or None when this instance cannot be compiled (then the run keeps the Python path, which
    calls the model). A subclass that changes ``__call__`` must change or drop ``kernel_form``.

    Examples
    --------
    >>> from tumble.dynamics.models.torques import ConstantTorque, KERNEL_WORLD
    >>> ConstantTorque((0.0, 0.0, 1.0), "world").kernel_form() == (KERNEL_WORLD, (0.0, 0.0, 1.0))
    True
    """

    def kernel_form(self) -> tuple[int, tuple[float, ...]] | None:
        """``(kind, parameters)`` for the compiled engine, or None (then the Python path calls the model).

        Examples
        --------
        >>> from tumble.dynamics.models.torques import ConstantTorque, KERNEL_BODY
        >>> kind, vector = ConstantTorque((0.0, 0.5, 0.0)).kernel_form()   # a constant body torque, N m
        >>> kind == KERNEL_BODY, vector
        (True, (0.0, 0.5, 0.0))
        """
        ...


def kernel_form(model: object) -> tuple[int, tuple[float, ...]] | None:
    """``model.kernel_form()`` for a model that declares one (:class:`KernelForm`), else None.

    Examples
    --------
    >>> from tumble.dynamics.models.torques import FunctionTorque, KERNEL_NONE, kernel_form
    >>> kernel_form(None) == (KERNEL_NONE, ())
    True
    >>> kernel_form(FunctionTorque(lambda t, omega, attitude: -omega)) is None   # Python's to call
    True
    """
    if model is None:
        return KERNEL_NONE, ()
    form = getattr(model, "kernel_form", None)
    return form() if callable(form) else None


#: A model's compiled form, ``(kind, parameters)``.
Form = tuple[int, tuple[float, ...]]


@functools.lru_cache(maxsize=256)
def kernel_terms(forms: tuple[Form, ...]) -> tuple[tuple[float, ...], float]:
    """The engine's torque terms ``(P, n)`` of a sum of models' compiled forms: each kind's
    parameters added in its slot of ``P`` (:mod:`tumble.dynamics.engine.kernels`: ``P[0:3]`` the
    body torque, N m; ``P[3:6]`` the world torque, N m; ``P[6]`` the gravity gradient's ``n^2``,
    1/s^2; ``P[7:10]`` the rotors' momentum, kg m^2/s), and ``n`` the circular orbit's mean
    motion (rad/s; 0 without one). The sum of torques is the torque of the sum (Euler's equations
    are linear in the torque), and the gravity gradient ``3 n^2 r_b x (I r_b)`` is linear in
    ``n^2``; two orbits of different mean motions cannot share one run (ValueError).

    Examples
    --------
    >>> from tumble.dynamics.models.torque_protocols import KERNEL_BODY, KERNEL_CIRCULAR_GRAVITY, kernel_terms
    >>> kernel_terms(((KERNEL_BODY, (0.0, 0.0, 1.0)), (KERNEL_BODY, (1.0, 0.0, 0.0)), (KERNEL_CIRCULAR_GRAVITY, (0.5,))))
    ((1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0), 0.5)
    >>> kernel_terms(((KERNEL_CIRCULAR_GRAVITY, (0.5,)), (KERNEL_CIRCULAR_GRAVITY, (0.25,))))
    Traceback (most recent call last):
    ...
    ValueError: two circular orbits of mean motions 0.5 and 0.25 rad/s in one run
    """
    P = [0.0] * TERMS
    n = 0.0
    for kind, params in forms:
        if kind == KERNEL_SUM:
            forms_n = params[TERMS]
            if n and forms_n and n != forms_n:
                raise ValueError(f"two circular orbits of mean motions {n!r} and {forms_n!r} rad/s in one run")
            P = [a + b for a, b in zip(P, params[:TERMS])]
            n = n or forms_n
        elif kind == KERNEL_BODY:
            P[0], P[1], P[2] = P[0] + params[0], P[1] + params[1], P[2] + params[2]
        elif kind == KERNEL_WORLD:
            P[3], P[4], P[5] = P[3] + params[0], P[4] + params[1], P[5] + params[2]
        elif kind == KERNEL_CIRCULAR_GRAVITY:
            if n and n != params[0]:
                raise ValueError(f"two circular orbits of mean motions {n!r} and {params[0]!r} rad/s in one run")
            n = params[0]
            P[6] += n * n
        elif kind == KERNEL_ROTOR_MOMENTUM:
            P[7], P[8], P[9] = P[7] + params[0], P[8] + params[1], P[9] + params[2]
        elif kind != KERNEL_NONE:
            raise ValueError(f"the engine has no torque of kind {kind!r}")
    return tuple(P), n


def constant_terms(form: Form | None) -> tuple[float, ...] | None:
    """The constant body and world torques ``P[0:6]`` (N m, :func:`kernel_terms`) of a compiled form
    that holds nothing else: a torque fixed in its frames, which reads neither the time nor omega
    (zeros for no torque); None for any other form (a gravity gradient's, a rotor's) or for None.

    Examples
    --------
    >>> from tumble.dynamics.models.torque_protocols import KERNEL_CIRCULAR_GRAVITY, KERNEL_WORLD, constant_terms
    >>> constant_terms((KERNEL_WORLD, (0.0, 0.0, 1.0)))
    (0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    >>> constant_terms((KERNEL_CIRCULAR_GRAVITY, (0.001,))) is None
    True
    """
    if form is None:
        return None
    P, _ = kernel_terms((form,))
    return None if any(P[6:]) else P[:6]
