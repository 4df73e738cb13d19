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

The protocols and the engine's kinds live in :mod:`~tumble.dynamics.models.torque_protocols`
and are re-exported here. Models add: ``a + b`` (or ``torque=[a, b]``) is their
:class:`TorqueSum`, compiled when every term is.

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

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NoReturn, TypeAlias, cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, Vector3
from ...validation import check_torque_function, check_vector, is_vector, short_repr
from ..special.quaternion import quat_conjugate, rotate_by_quaternion
from .torque_protocols import (
    KERNEL_BODY,
    KERNEL_CIRCULAR_GRAVITY,
    KERNEL_NONE,
    KERNEL_ROTOR_MOMENTUM,
    KERNEL_SUM,
    KERNEL_WORLD,
    TORQUE_FRAMES,
    BoundsSpin,
    Form,
    KernelForm,
    NeedsBody,
    TorqueModel,
    check_frame,
    conforms,
    kernel_form,
    kernel_terms,
)

if TYPE_CHECKING:
    from ...mass import Body, MassProperties

__all__ = [
    "TORQUE_FRAMES",
    "AddsTorques",
    "BoundsSpin",
    "ConstantTorque",
    "FunctionTorque",
    "KERNEL_BODY",
    "KERNEL_CIRCULAR_GRAVITY",
    "KERNEL_NONE",
    "KERNEL_ROTOR_MOMENTUM",
    "KERNEL_SUM",
    "KERNEL_WORLD",
    "KernelForm",
    "NeedsBody",
    "TorqueModel",
    "TorqueSum",
    "as_torque",
    "bind_to_body",
    "body_torque",
    "conforms",
    "kernel_form",
    "terms_of",
]


class AddsTorques:
    """What makes ``a + b`` of torque models their :class:`TorqueSum` (the built-in models have it).

    ``sum([a, b, c])`` works too (it starts from 0, which a model's ``+`` takes as nothing), and
    a plain function ``tau(t, omega, attitude)`` (N m, body frame) may be one of the terms.

    Examples
    --------
    >>> import tumble
    >>> thrust = tumble.ConstantTorque((0.0, 0.0, 0.01))
    >>> gravity = tumble.GravityGradient(orbit_period=5400.0)
    >>> both = thrust + gravity
    >>> both.terms == (thrust, gravity), both.frame   # the sum returns the body-frame total
    (True, 'body')
    >>> sum([thrust, gravity]) == thrust + gravity
    True
    """

    __slots__ = ()

    def __add__(self, other: object) -> TorqueSum:
        return TorqueSum(self, other)

    def __radd__(self, other: object) -> TorqueModel:
        if type(other) is int and other == 0:  # sum() starts from 0
            return cast(TorqueModel, self)
        return TorqueSum(other, self)


@dataclass(frozen=True)
class ConstantTorque(AddsTorques):
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
        check_frame(self.frame)
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
class FunctionTorque(AddsTorques):
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
        check_torque_function("torque", self.fn)
        check_frame(self.frame)

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
        return _torque_array(self.fn(t, omega, attitude), t, np.shape(omega))


@dataclass(frozen=True, init=False, repr=False)
class TorqueSum(AddsTorques):
    """The sum of torque models, itself a torque model: ``a + b``, ``sum([a, b])``, ``TorqueSum(a, b)``
    or ``torque=[a, b]`` in a run.

    Each term keeps its own frame: the sum returns the body-frame torque (N m), each world-frame
    term turned into the body by ``R^T`` (:func:`body_torque`). A term that needs the body's moments
    is bound with the sum (:class:`NeedsBody`). When every term has a compiled form, so has the sum
    (:data:`KERNEL_SUM`: the engine's terms added, :func:`kernel_terms`) and it runs compiled; with
    a plain Python term it runs on the Python path, which calls every term. Euler's equations are
    linear in the torque, so the motion under a sum is the motion under the total torque.

    Parameters
    ----------
    *terms : torque model or callable
        The models (a sum among them adds its own terms), or functions ``tau(t, omega,
        attitude)`` returning N m in the body frame.

    Examples
    --------
    A world-fixed push beside a thruster fixed in the body; the sum runs on the compiled engine:

    >>> import numpy as np, tumble
    >>> from scipy.spatial.transform import Rotation
    >>> push, thruster = tumble.ConstantTorque((0.0, 0.0, 0.5), "world"), tumble.ConstantTorque((0.2, 0.0, 0.0))
    >>> both = push + thruster
    >>> both.frame, both.terms == (push, thruster), both.kernel_form()[0] == tumble.dynamics.models.torques.KERNEL_SUM
    ('body', True, True)
    >>> both(0.0, np.zeros(3), Rotation.from_euler("x", 90, degrees=True)).round(12).tolist()   # R^T (0, 0, 0.5) + (0.2, 0, 0)
    [0.2, 0.5, 0.0]
    >>> twice = tumble.ConstantTorque((0.0, 0.0, 1.0)) + tumble.ConstantTorque((1.0, 0.0, 0.0))
    >>> twice
    ConstantTorque(vector=(0.0, 0.0, 1.0), frame='body') + ConstantTorque(vector=(1.0, 0.0, 0.0), frame='body')
    >>> twice.kernel_form()   # body + body: one vector, as one ConstantTorque's form
    (1, (1.0, 0.0, 1.0))
    """

    terms: tuple[TorqueModel, ...]
    frame: str

    def __init__(self, *terms: object) -> None:
        models: list[TorqueModel] = []
        for i, term in enumerate(terms):
            if isinstance(term, TorqueSum):
                models.extend(term.terms)
                continue
            if not (conforms(term, TorqueModel) and callable(term)):
                try:
                    check_torque_function(f"torque[{i}]", term)
                except ValueError as err:
                    raise ValueError(f"{err} (a list is the sum of its torque models)") from None
            models.append(cast(TorqueModel, as_torque(cast(TorqueLike, term))))
        if not models:
            raise ValueError("torque = [] is an empty sum: give a torque model, a list of them, or None")
        object.__setattr__(self, "terms", tuple(models))
        object.__setattr__(self, "frame", "body")
        object.__setattr__(self, "_form", _sum_form(self.terms))  # made once: simulate reads it on every run

    def __repr__(self) -> str:
        return " + ".join(repr(term) for term in self.terms)

    def __call__(self, t: float, omega: np.ndarray, attitude: Rotation) -> Vector3:
        """The total torque, N m, principal (body) frame: every term's :func:`body_torque`, added.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.models.torques import TorqueSum
        >>> drag = TorqueSum(lambda t, omega, attitude: -0.1 * omega, lambda t, omega, attitude: [0.0, 0.0, t])
        >>> drag(2.0, np.array([1.0, 0.0, 0.0]), Rotation.identity()).tolist()
        [-0.1, 0.0, 2.0]
        """
        total = body_torque(self.terms[0], t, omega, attitude)
        for term in self.terms[1:]:
            total = total + body_torque(term, t, omega, attitude)
        return total

    def bind(self, body: Body | MassProperties | ArrayLike) -> TorqueSum:
        """The sum with each term that needs the body's moments bound to ``body`` (:class:`NeedsBody`).

        Examples
        --------
        >>> import tumble
        >>> bound = (tumble.GravityGradient(orbit_period=5400.0) + tumble.ConstantTorque((0.0, 0.0, 1e-6))).bind(
        ...     [1.0, 2.0, 3.0])
        >>> bound.terms[0].moments, bound.kernel_form() is not None   # bound: the engine runs it
        ((1.0, 2.0, 3.0), True)
        """
        bound = tuple(bind_to_body(term, body) for term in self.terms)
        return self if all(a is b for a, b in zip(bound, self.terms)) else TorqueSum(*bound)

    def kernel_form(self) -> Form | None:
        """The compiled engine's form (:class:`KernelForm`) of the sum, or None where a term has none
        (then the Python path calls every term): a sum of constant body torques, or of constant world
        torques, is one :class:`ConstantTorque`'s form, the vectors added; any other,
        ``(KERNEL_SUM, P + (n,))``, the engine's terms added (:func:`kernel_terms`).

        Examples
        --------
        >>> import tumble
        >>> (tumble.ConstantTorque((0.0, 0.0, 1.0), "world") + tumble.ConstantTorque((0.0, 2.0, 0.0), "world")).kernel_form()
        (2, (0.0, 2.0, 1.0))
        >>> (tumble.ConstantTorque((0.0, 0.0, 1.0)) + (lambda t, omega, attitude: -omega)).kernel_form() is None
        True
        """
        return self._form  # type: ignore[attr-defined, no-any-return]


def _sum_form(terms: tuple[TorqueModel, ...]) -> Form | None:
    """:meth:`TorqueSum.kernel_form` of ``terms``: None where one has no compiled form (or is not
    bound to a body yet); a ValueError for two circular orbits of different mean motions."""
    forms = [kernel_form(term) for term in terms]
    if any(form is None for form in forms):
        return None
    P, n = kernel_terms(tuple(cast(list[Form], forms)))
    kinds = {form[0] for form in cast(list[Form], forms)} - {KERNEL_NONE}
    if kinds == {KERNEL_BODY}:
        return KERNEL_BODY, P[0:3]
    if kinds == {KERNEL_WORLD}:
        return KERNEL_WORLD, P[3:6]
    return (KERNEL_SUM, P + (n,)) if kinds else (KERNEL_NONE, ())


def terms_of(model: TorqueModel | None) -> tuple[TorqueModel, ...]:
    """The models acting in ``model``: a sum's terms, a single model alone, none for None.

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics.models.torques import terms_of
    >>> gg, push = tumble.GravityGradient(orbit_period=5400.0), tumble.ConstantTorque((0.0, 0.0, 1e-6))
    >>> [type(term).__name__ for term in terms_of(gg + push)], terms_of(push) == (push,), terms_of(None)
    (['GravityGradient', 'ConstantTorque'], True, ())
    """
    if model is None:
        return ()
    return model.terms if isinstance(model, TorqueSum) else (model,)


#: What ``torque=`` accepts: a torque model, or a plain callable ``tau(t, omega, attitude)`` (N m,
#: body frame), or a list of them (their :class:`TorqueSum`).
TorqueLike: TypeAlias = ("TorqueModel | Callable[[float, np.ndarray, Rotation], ArrayLike] "
                         "| Sequence[TorqueModel | Callable[[float, np.ndarray, Rotation], ArrayLike]]")


def as_torque(torque: TorqueLike | None) -> TorqueModel | None:
    """The torque model for ``torque``: models pass through, a plain callable acts in the body frame,
    a list is the sum of its terms.

    Parameters
    ----------
    torque : None, torque model, callable or list of them
        A model (an object with a ``frame`` that is called as ``tau(t, omega, attitude)``, such as
        :class:`ConstantTorque`), a plain callable ``tau(t, omega, attitude)`` returning N m in
        the body (principal) frame, a list (or tuple) of them, their :class:`TorqueSum`, or None.

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
    >>> as_torque([model, ConstantTorque((1.0, 0.0, 0.0), "world")])   # a list: the sum of its models
    ConstantTorque(vector=(0.0, 0.0, 1.0), frame='body') + ConstantTorque(vector=(1.0, 0.0, 0.0), frame='world')
    """
    if torque is None:
        return None
    if conforms(torque, TorqueModel) and callable(torque):  # callable: a __call__ of the type, not the instance
        model = cast(TorqueModel, torque)
        check_frame(model.frame)
        return model
    if isinstance(torque, (list, tuple)) and not is_vector(torque):  # three numbers: a vector, refused below
        return TorqueSum(*torque)
    return FunctionTorque(cast(Callable[[float, np.ndarray, Rotation], ArrayLike], torque), "body")


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

def _refuse(got: str, t: float, shape: tuple[int, ...]) -> NoReturn:
    raise ValueError(f"the torque model returned {got} at t = {t:.6g} s; expected finite numbers "
                     f"of shape (3,){'' if shape == (3,) else f' or {shape}'} (N m)")


def _torque_array(value: object, t: float, shape: tuple[int, ...]) -> np.ndarray:
    """A torque function's result as floats, or the one-line refusal naming it as it came (None, text,
    a ragged list: numpy would make None a nan and say nothing of the torque for the others)."""
    try:
        raw = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raw = None
    if raw is None or raw.ndim == 0:
        _refuse(short_repr(value), t, shape)
    return raw


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
    >>> body_torque(lambda t, omega, attitude: np.ones((300, 3)), 0.0, np.zeros((2, 3)), quarter)   # not 2 bodies'
    Traceback (most recent call last):
    ...
    ValueError: the torque model returned an array of shape (300, 3) at t = 0 s; expected finite numbers of shape (3,) or (2, 3) (N m)
    >>> body_torque(lambda t, omega, attitude: None, 0.0, np.zeros(3), quarter)   # a function that forgot to return
    Traceback (most recent call last):
    ...
    ValueError: the torque model returned None at t = 0 s; expected finite numbers of shape (3,) (N m)
    """
    value = model(t, omega, attitude)
    shape = np.shape(omega)
    raw = _torque_array(value, t, shape)
    if raw.shape not in ((3,), shape) or not np.all(np.isfinite(raw)):
        bad = np.flatnonzero(~np.isfinite(raw).all(axis=-1)) if raw.ndim == 2 and raw.shape == shape else np.zeros(0, int)
        got = (f"{raw[bad[0]].tolist()!r} for body {bad[0]}" if len(bad) else  # one row of a batch
               repr(raw.tolist()) if raw.size <= 6 else f"an array of shape {raw.shape}")
        _refuse(got, t, shape)
    tau = np.array(np.broadcast_to(raw, shape))
    if model.frame != "world":
        return tau
    # world to body, R^T tau, by the conjugate quaternion written out element by element: scipy's
    # Rotation.apply takes other arithmetic for one rotation than for a stack, so a body's run
    # would depend on its batch (a sweep's rows on its chunk size) by ~1e-15 a step
    return rotate_by_quaternion(quat_conjugate(attitude.as_quat()), tau)
