"""External torques about the centre of mass, and the interface every torque model follows.

A torque model is any object that satisfies :class:`TorqueModel`:

- ``model(t, omega, attitude) -> tau``, with ``t`` in s, ``omega`` the principal-frame angular
  velocity (rad/s, shape (3,), or (N, 3) when a batched method calls it for N bodies at once)
  and ``attitude`` a scipy ``Rotation`` (principal body frame to world; one, or a stack of N);
  it returns a torque in N m, shape (3,) or that of ``omega``;
- ``frame``: the frame of that torque, ``"body"`` (the principal frame) or ``"world"``.

A plain Python callable is taken as a body-frame torque (:func:`as_torque` wraps it in a
:class:`FunctionTorque`). Two methods are optional, each declared by its own protocol and
looked for by the runs through ``isinstance``, never by name:

- ``bind(body) -> TorqueModel`` (:class:`NeedsBody`): a model whose torque depends on the
  body's principal moments (kg m^2), such as the gravity gradient, is bound to the body (a
  Body, MassProperties or the moments, shape (3,) or (N, 3)) before a run starts
  (:func:`bind_to_body`, used by ``simulate`` and ``simulate_batch`` alike);
- ``max_spin(t, omega, attitude) -> ndarray`` (:class:`BoundsSpin`): an upper bound on
  ``|omega|`` (rad/s) over the whole motion from this state, shape () or (N,); the runs then
  bound their work and choose default steps from it (:func:`~tumble.dynamics.methods.bounds.spin_gain`) instead of from
  ``|tau| t / I1``.

Examples
--------
>>> import numpy as np
>>> from tumble.dynamics.models.torques import ConstantTorque, TorqueModel, as_torque
>>> isinstance(ConstantTorque((0.0, 0.0, 1.0), "world"), TorqueModel)
True
>>> as_torque(lambda t, omega, attitude: np.zeros(3)).frame
'body'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol, TypeAlias, cast, runtime_checkable

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, Vector3
from ...validation import check_callable, check_vector
from ..special.quaternion import quat_conjugate, rotate_by_quaternion

if TYPE_CHECKING:
    from ...mass import Body, MassProperties

__all__ = [
    "BoundsSpin",
    "ConstantTorque",
    "FunctionTorque",
    "KERNEL_BODY",
    "KERNEL_CIRCULAR_GRAVITY",
    "KERNEL_NONE",
    "KERNEL_ROTOR_MOMENTUM",
    "KERNEL_WORLD",
    "KernelForm",
    "NeedsBody",
    "TorqueModel",
    "as_torque",
    "bind_to_body",
    "body_torque",
    "conforms",
    "kernel_form",
]

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


def _check_frame(frame: str) -> str:
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


@dataclass(frozen=True)
class ConstantTorque:
    """A constant torque vector (N m), fixed in the body or in the world frame.

    A constant *body-frame* torque models a thruster fixed to the body; a constant
    *world-frame* torque changes L at a constant rate, ``dL_world/dt = tau``.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
    >>> push = tumble.ConstantTorque((0.0, 0.0, 0.5), "world")   # dL_world/dt = tau
    >>> traj = tumble.simulate(body, [1.0, 0.2, 0.3], t_end=4.0, samples=5, torque=push)
    >>> bool(np.allclose(traj.angular_momentum_world[-1] - traj.angular_momentum_world[0], [0.0, 0.0, 2.0]))
    True
    """

    vector: tuple[float, float, float]
    frame: str = "body"

    def __post_init__(self) -> None:
        object.__setattr__(self, "vector", check_vector("torque vector", self.vector, "N m"))
        _check_frame(self.frame)
        # the compiled form, made once: simulate reads it on every run
        object.__setattr__(self, "_form", (KERNEL_WORLD if self.frame == "world" else KERNEL_BODY,
                                           tuple(float(v) for v in self.vector)))

    def __call__(self, t: float, omega: np.ndarray, attitude: Rotation) -> Vector3:
        """The torque, N m, in ``frame``: ``vector`` at every time ``t`` (s) and state.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble import ConstantTorque
        >>> ConstantTorque((1.0, 0.0, 0.0))(0.0, np.zeros(3), None).tolist()   # the same at every time and state, N m
        [1.0, 0.0, 0.0]
        """
        return np.array(self.vector)

    def kernel_form(self) -> tuple[int, tuple[float, ...]]:
        """The compiled engine's form (:class:`KernelForm`): the vector (N m) in its frame.

        Examples
        --------
        >>> from tumble.dynamics.models.torques import ConstantTorque, KERNEL_BODY
        >>> ConstantTorque((1.0, 0.0, 0.0)).kernel_form() == (KERNEL_BODY, (1.0, 0.0, 0.0))
        True
        """
        return self._form  # type: ignore[attr-defined, no-any-return]


@dataclass(frozen=True)
class FunctionTorque:
    """Wraps ``fn(t, omega, attitude) -> tau`` with the frame its result is expressed in.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.torques import FunctionTorque
    >>> damping = FunctionTorque(lambda t, omega, attitude: -0.1 * omega)   # body frame by default
    >>> damping.frame, damping(0.0, np.array([1.0, 2.0, 0.0]), Rotation.identity()).tolist()
    ('body', [-0.1, -0.2, -0.0])
    >>> FunctionTorque((0.0, 0.0, 0.01))   # a vector is no torque model: the message says which one
    Traceback (most recent call last):
    ...
    ValueError: torque = (0.0, 0.0, 0.01) is a vector, not a torque model: for a constant torque give tumble.ConstantTorque((0.0, 0.0, 0.01)) (N m, body frame; frame="world" for a world-fixed one)
    """

    fn: Callable[[float, np.ndarray, Rotation], ArrayLike]
    frame: str = "body"

    def __post_init__(self) -> None:
        given: Any = self.fn  # what the user passed, which may be no function at all
        if (isinstance(given, (list, tuple)) or getattr(given, "ndim", None) == 1) and len(given) == 3 and all(
                isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) for v in given):
            raise ValueError(f"torque = {given!r} is a vector, not a torque model: for a constant torque give "
                             f"tumble.ConstantTorque({tuple(float(v) for v in given)}) (N m, body frame; "
                             'frame="world" for a world-fixed one)')  # three numbers: the constant torque meant
        check_callable("torque", self.fn, "tau(t, omega, attitude)")
        _check_frame(self.frame)

    def __call__(self, t: float, omega: np.ndarray, attitude: Rotation) -> Vector3:
        """``fn(t, omega, attitude)`` as a float array, N m, in :attr:`frame`.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.models.torques import FunctionTorque
        >>> spin_up = FunctionTorque(lambda t, omega, attitude: [0, 0, t], "world")   # a list in, floats out
        >>> spin_up(2.0, np.zeros(3), Rotation.identity()).tolist()
        [0.0, 0.0, 2.0]
        """
        return np.asarray(self.fn(t, omega, attitude), dtype=float)


#: What ``torque=`` accepts: a torque model, or a plain callable ``tau(t, omega, attitude)`` (N m,
#: body frame).
TorqueLike: TypeAlias = "TorqueModel | Callable[[float, np.ndarray, Rotation], ArrayLike]"


def as_torque(torque: TorqueLike | None) -> TorqueModel | None:
    """The torque model for ``torque``: models pass through, a plain callable acts in the body frame.

    Parameters
    ----------
    torque : None, torque model or callable
        A model (an object with a ``frame`` that is called as ``tau(t, omega, attitude)``, such as
        :class:`ConstantTorque`), a plain callable ``tau(t, omega, attitude)`` returning N m in
        the body (principal) frame, or None.

    Returns
    -------
    torque model or None

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.torques import ConstantTorque, FunctionTorque, as_torque
    >>> model = ConstantTorque((0.0, 0.0, 1.0))
    >>> as_torque(model) is model, as_torque(None)
    (True, None)
    >>> wrapped = as_torque(lambda t, omega, attitude: np.zeros(3))
    >>> isinstance(wrapped, FunctionTorque), wrapped.frame
    (True, 'body')
    """
    if torque is None:
        return None
    if conforms(torque, TorqueModel) and callable(torque):  # callable: a __call__ of the type, not the instance
        model = cast(TorqueModel, torque)
        _check_frame(model.frame)
        return model
    return FunctionTorque(torque, "body")


def bind_to_body(model: TorqueModel | None, body: Body | MassProperties | ArrayLike) -> TorqueModel | None:
    """``model`` bound to ``body`` if it needs the body's moments (:class:`NeedsBody`), else itself.

    Parameters
    ----------
    model : torque model or None
        As returned by :func:`as_torque`.
    body : Body, MassProperties or array_like, shape (3,) or (N, 3)
        The body, or the principal moments of each body of a batch, kg m^2.

    Returns
    -------
    torque model or None

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, GravityGradient
    >>> from tumble.dynamics.models.torques import bind_to_body
    >>> bind_to_body(GravityGradient(orbit_period=5400.0), [1.0, 2.0, 3.0]).moments
    (1.0, 2.0, 3.0)
    >>> torque = ConstantTorque((0.0, 0.0, 1.0))
    >>> bind_to_body(torque, [1.0, 2.0, 3.0]) is torque
    True
    """
    return cast(NeedsBody, model).bind(body) if model is not None and conforms(model, NeedsBody) else model

def body_torque(model: TorqueModel, t: float, omega: np.ndarray, attitude: Rotation) -> Vector3:
    """Evaluate a torque model and return the torque in the principal (body) frame, N m.

    Parameters
    ----------
    model : torque model
        See the module docstring; its result is checked here, for every integrator.
    t : float
        Time, s.
    omega : ndarray, shape (3,) or (N, 3)
        Angular velocity in the principal frame, rad/s.
    attitude : scipy Rotation (one, or a stack of N)
        Principal body frame to world.

    Raises
    ------
    ValueError
        If the model returns anything but finite numbers of omega's shape (or shape (3,)).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.torques import ConstantTorque, body_torque
    >>> quarter = Rotation.from_euler("z", 90, degrees=True)   # body x is world y
    >>> body_torque(ConstantTorque((1.0, 0.0, 0.0), "world"), 0.0, np.zeros(3), quarter).round(12).tolist()   # R^T tau
    [0.0, -1.0, 0.0]
    >>> body_torque(lambda t, omega, attitude: [np.nan, 0, 0], 0.0, np.zeros(3), quarter)
    Traceback (most recent call last):
    ...
    ValueError: the torque model returned [nan, 0.0, 0.0] at t = 0 s; expected finite numbers of shape (3,) (N m)
    """
    raw = np.asarray(model(t, omega, attitude), dtype=float)
    shape = np.shape(omega)
    if raw.shape not in ((3,), shape) or not np.all(np.isfinite(raw)):
        raise ValueError(
            f"the torque model returned {raw.tolist()!r} at t = {t:.6g} s; expected finite numbers "
            f"of shape (3,){'' if shape == (3,) else f' or {shape}'} (N m)"
        )
    tau = np.array(np.broadcast_to(raw, shape))
    if model.frame != "world":
        return tau
    # world to body, R^T tau, by the conjugate quaternion written out element by element: scipy's
    # Rotation.apply takes other arithmetic for one rotation than for a stack, so a body's run
    # would depend on its batch (a sweep's rows on its chunk size) by ~1e-15 a step
    return rotate_by_quaternion(quat_conjugate(attitude.as_quat()), tau)
