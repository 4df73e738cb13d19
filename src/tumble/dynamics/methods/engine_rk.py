"""The methods that run on the compiled engine's fixed steps, and the gyrostat's way onto it.

:func:`engine_rk` and :func:`engine_rk_internal` are the ``integrate`` and ``integrate_internal``
of the ``"rk4"`` and ``"rk8"`` entries of :data:`~tumble.dynamics.methods.integrators.METHODS`;
:func:`gyrostat_on_engine` runs a body whose rotors spin at constant rates under a built-in torque
on the engine's DOP853 (their momentum one more term of Euler's equations,
:data:`~tumble.dynamics.models.torques.KERNEL_ROTOR_MOMENTUM`). Apart from the registry so that
each module stays short; imports no numba (the engine's front loads its kernels on a first run).

Examples
--------
>>> import numpy as np
>>> from tumble.dynamics.methods.engine_rk import engine_rk
>>> omega, quat = engine_rk("rk8")(np.array([1.0, 2.0, 3.0]), np.array([0.0, 0.0, 1.0]),
...                                np.array([0.0, 0.0, 0.0, 1.0]), np.array([0.0, 1.0]), None, None, None)
>>> omega[-1].tolist()   # a steady spin about a principal axis
[0.0, 0.0, 1.0]
"""

from __future__ import annotations

from collections.abc import Callable
from typing import cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, Quaternion, Vector3
from ..engine.front import run_body, run_damped
from ..models.dipole import ResidualDipole
from ..models.internal import InternalModel, InternalSamples
from ..models.orbit_gravity import OrbitGravityGradient
from ..models.torques import KERNEL_ROTOR_MOMENTUM, TorqueModel, kernel_form
from .bounds import spin_gain

__all__ = ["COMPILED_MODELS", "RK_STEP_ANGLE", "engine_rk", "engine_rk_internal", "gyrostat_on_engine", "on_the_loop", "rk_step"]


def on_the_loop(torque: object) -> bool:
    """Whether ``torque`` runs on the compiled closed loop's kernel
    (:mod:`~tumble.dynamics.control.free_loop`): it holds the gravity gradient along a Keplerian or
    TLE orbit or a dipole in a field, which the engine's terms do not, and the rest of it is
    compiled there too (:func:`~tumble.dynamics.control.free_loop.free_terms`). A torque with
    neither is told without importing the loop.

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, KeplerOrbit, OrbitGravityGradient
    >>> from tumble.dynamics.methods.engine_rk import on_the_loop
    >>> ellipse = OrbitGravityGradient(KeplerOrbit(8000e3, 0.1))
    >>> on_the_loop(ellipse + ConstantTorque((0.0, 0.0, 1e-6))), on_the_loop(ConstantTorque((0.0, 0.0, 1e-6)))
    (True, False)
    >>> on_the_loop(ellipse + (lambda t, w, R: [0.0, 0.0, 0.0]))   # a Python term: scipy's path
    False
    """
    if not any(isinstance(term, (OrbitGravityGradient, ResidualDipole)) for term in getattr(torque, "terms", (torque,))):
        return False
    from ..control.free_loop import free_terms  # the compiled loop, loaded when needed

    return free_terms(torque) is not None


def gyrostat_on_engine(model: InternalModel, form: tuple[int, tuple[float, ...]] | None, omega0: ArrayLike,
                       quat0: ArrayLike, t: FloatArray, rtol: float | None, atol: float | FloatArray | None,
                       torque: TorqueModel | None = None) -> InternalSamples:
    """A body whose rotors spin at constant rates under a built-in torque, on the compiled engine:
    their constant momentum ``h`` is one more term of its Euler's equations, ``h x omega``
    (:data:`~tumble.dynamics.models.torques.KERNEL_ROTOR_MOMENTUM`), and the state stays
    ``(omega, q)``. ``atol`` is the internal model's, momentum first (:meth:`InternalModel.atol`):
    its momentum components are read back as rates over the largest moment. ``form`` None: the
    ``torque`` runs on the closed loop's kernel (:func:`on_the_loop`), ``h`` its rotor momentum.

    Examples
    --------
    A rotor's momentum along the major axis of a body spinning about it: a steady spin.

    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.engine_rk import gyrostat_on_engine
    >>> from tumble.dynamics.models.internal import InternalModel, Rotors
    >>> from tumble.dynamics.models.torques import KERNEL_NONE
    >>> body = tumble.Body([tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2)),
    ...                     tumble.Rotor(mass=0.2, radius=0.05, length=0.01, axis=(0.0, 0.0, 1.0), spin_rate=300.0)])
    >>> model = InternalModel(body.principal_moments, Rotors.of(body))
    >>> run = gyrostat_on_engine(model, (KERNEL_NONE, ()), [0.0, 0.0, 2.0], [0.0, 0.0, 0.0, 1.0], np.array([0.0, 1.0]),
    ...                          1e-12, 1e-14)
    >>> run.omega[-1].round(12).tolist()
    [0.0, 0.0, 2.0]
    """
    h = model.momentum(0.0)
    tol = np.asarray(atol, dtype=float)
    if tol.shape == (7,):
        tol = np.concatenate([tol[:3] / float(np.max(model.moments)), tol[3:]])
    else:
        tol = np.full(7, float(tol))
    if form is None:  # an ellipse's or a TLE's gravity gradient, a dipole in a field
        from ..control.free_loop import run_free

        omega, quat = run_free(model.moments, np.asarray(omega0, float), np.asarray(quat0, float), t, torque,
                               cast(float, rtol), tol, rotor_momentum=h)
        return InternalSamples(omega, quat, None, None, None)
    omega, quat = run_body("dop853", model.moments, np.asarray(omega0, float), np.asarray(quat0, float), t,
                           (form, (KERNEL_ROTOR_MOMENTUM, tuple(float(v) for v in h))), rtol=rtol, atol=tol)
    return InternalSamples(omega, quat, None, None, None)


#: The built-in torque models the compiled methods take, as their refusals name them.
COMPILED_MODELS = "ConstantTorque, GravityGradient, OrbitGravityGradient, ResidualDipole, their sums"

#: Default largest step of the fixed-step Runge-Kutta methods, as rotation per step (rad) at
#: the fastest spin the run can reach: ~1e-13 of omega per step for RK8 and ~1e-10 for RK4
#: (local errors (omega h)^(p+1), measured on the bench cases); ``step`` overrides it.
RK_STEP_ANGLE = {"rk4": 0.01, "rk8": 0.2}


def engine_rk(name: str) -> Callable[..., tuple[Vector3, Quaternion]]:
    """The compiled engine's fixed-step Runge-Kutta ``name`` (``"rk4"``, ``"rk8"``): the ``integrate`` of
    its :class:`~tumble.dynamics.methods.integrators.Method`, its default step from :func:`rk_step`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.engine_rk import engine_rk
    >>> omega, quat = engine_rk("rk4")(np.array([1.0, 2.0, 3.0]), np.array([0.0, 0.0, 1.0]),
    ...                                np.array([0.0, 0.0, 0.0, 1.0]), np.array([0.0, 1.0]), None, None, None, 0.1)
    >>> err = abs(quat[-1, 2] - np.sin(0.5))   # turned 1 rad about z; RK4 at 0.1 s steps: ~2e-8 off
    >>> bool(1e-9 < err < 1e-7)
    True
    """

    def integrate(
        moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
        rtol: float | None, atol: float | FloatArray | None, step: float | None = None,
    ) -> tuple[Vector3, Quaternion]:
        form = kernel_form(torque)
        # none: an ellipse's gravity gradient or a dipole in a field runs on the loop; simulate refuses
        # anything else first (Method.compiled_only), a direct call gets the same words
        if form is None and not on_the_loop(torque):
            raise ValueError(f"method = {name!r} runs compiled: it takes a built-in torque model ({COMPILED_MODELS}) "
                             f"or none; use dop853 for {torque!r}")
        w0, q0, I = np.asarray(omega0, float), np.asarray(quat0, float), np.asarray(moments, float)
        if step is None:
            with np.errstate(over="ignore", invalid="ignore"):
                gain = spin_gain(torque, float(t[0]), w0, Rotation.from_quat(q0), I, float(t[-1] - t[0]))
            step = rk_step(name)(float(np.linalg.norm(w0)), gain)
        if form is None:  # on the loop: its kernel at the same fixed steps (tumble.dynamics.control.free_loop)
            from ..control.free_loop import run_free

            return run_free(I, w0, q0, t, torque, 0.0, 0.0, method=name, step=step)
        return run_body(name, I, w0, q0, t, form, step=step)

    return integrate


def engine_rk_internal(name: str) -> Callable[..., InternalSamples]:
    """The compiled engine's fixed-step ``name`` for a body whose rotors spin at constant rates (their
    momentum one more term, :func:`gyrostat_on_engine`) and for a body with a spherical damper (its
    state ``(L, q, w_d, D)`` stepped by :mod:`~tumble.dynamics.engine.damped`); rotors whose spin
    changes are refused. ``simulate`` refuses it a stiff damper first.

    Examples
    --------
    A damper takes out the energy of a spin about the minor axis, and the momentum stays:

    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.engine_rk import engine_rk_internal
    >>> from tumble.dynamics.models.internal import InternalModel
    >>> damped = InternalModel(np.array([1.0, 2.0, 3.0]), damper=tumble.SphericalDamper(inertia=0.1, damping=0.5))
    >>> run = engine_rk_internal("rk8")(damped, [1.0, 0.1, 0.0], [0.0, 0.0, 0.0, 1.0], np.linspace(0.0, 20.0, 3), None,
    ...                                 None, None)
    >>> bool(np.all(np.diff(run.dissipated) > 0)), run.damper_omega.shape
    (True, (3, 3))
    >>> ramp = tumble.Body([tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2)),
    ...                     tumble.Rotor(mass=0.2, radius=0.05, length=0.01, spin_rate=0.0, spin_acceleration=5.0)])
    >>> from tumble.dynamics.models.internal import Rotors
    >>> engine_rk_internal("rk8")(InternalModel(ramp.principal_moments, Rotors.of(ramp)), [0.0, 0.0, 1.0],
    ...                           [0.0, 0.0, 0.0, 1.0], np.array([0.0, 1.0]), None, None, None)
    Traceback (most recent call last):
    ...
    ValueError: method = 'rk8' runs compiled and takes rotors spinning at constant rates, a damper and the built-in torques; for rotors whose spin changes use dop853
    """

    def integrate(model: InternalModel, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
                  rtol: float | None, atol: float | FloatArray | None, step: float | None = None) -> InternalSamples:
        form = kernel_form(torque)
        loop = form is None and model.damper is None and on_the_loop(torque)  # the loop takes a gyrostat, no damper
        if (model.rotors is not None and not model.rotors.constant) or (form is None and not loop):
            what = "rotors whose spin changes" if form is not None or loop else f"torque = {torque!r}"
            raise ValueError(f"method = {name!r} runs compiled and takes rotors spinning at constant rates, a damper and "
                             f"the built-in torques; for {what} use dop853")
        w0, q0 = np.asarray(omega0, float), np.asarray(quat0, float)
        if step is None:
            with np.errstate(over="ignore", invalid="ignore"):
                gain = spin_gain(torque, float(t[0]), w0, Rotation.from_quat(q0), model.moments, float(t[-1] - t[0]))
            step = rk_step(name)(float(model.spin_bound(w0, t)), gain, model.relaxation_rate)
        h = tuple(float(v) for v in model.momentum(0.0))
        if form is None:  # on the loop (checked above): its kernel at the same fixed steps
            from ..control.free_loop import run_free

            omega, quat = run_free(model.moments, w0, q0, t, torque, 0.0, 0.0, method=name, step=step,
                                   rotor_momentum=np.array(h))
            return InternalSamples(omega, quat, None, None, None)
        if model.damper is not None:
            body = np.array([*model.moments, model.damper.inertia, model.damper.damping, *h])
            Y = run_damped(name, body, model.initial_state(w0, q0), t, form, step=step)
            return model.samples(t, Y)
        omega, quat = run_body(name, model.moments, w0, q0, t, (form, (KERNEL_ROTOR_MOMENTUM, h)), step=step)
        return InternalSamples(omega, quat, None, None, None)

    return integrate


def rk_step(name: str) -> Callable[..., float]:
    """The default step rule of ``name`` (``"rk4"``, ``"rk8"``): ``default_step(spin, gain, rate)`` (s),
    :data:`RK_STEP_ANGLE` of rotation at the fastest spin the run can reach (rad/s).

    Examples
    --------
    >>> from tumble.dynamics.methods.engine_rk import rk_step
    >>> rk_step("rk8")(2.0, 0.0), rk_step("rk4")(0.0)   # 0.2 rad at 2 rad/s; no spin: no limit
    (0.1, inf)
    """

    def default_step(spin: float, gain: float = 0.0, rate: float = 0.0) -> float:
        top = max(spin + gain, rate)
        return RK_STEP_ANGLE[name] / top if top > 0 else float(np.inf)

    return default_step
