"""Integrators as interchangeable strategies behind :func:`tumble.simulate`.

Every method takes the same arguments and returns the sampled angular velocity (principal
frame) and attitude quaternions (body to world, scalar last). One registry, :data:`METHODS`,
maps a method's name to it; the CLI, scenario files and ``simulate()`` all read it, so a new
method is added here and nowhere else. A :class:`Method` declares what the runs need to know
(``supports_torque``, ``supports_internal``, ``fixed_step``, ``closed_form``,
``splitting_order``, ``stiff_solver``): ``simulate`` and ``simulate_batch`` read these fields,
never a method's name.

- ``"dop853"``: Euler's equations and the quaternion kinematics integrated together with
  scipy's 8th-order Dormand-Prince (Hairer, Norsett & Wanner, *Solving ODEs I*, sec. II.10) at
  tight tolerances, rtol = 1e-12 by default. The accurate default. Under a built-in torque model
  (:class:`~tumble.dynamics.models.torques.KernelForm`) it runs in the compiled engine
  (:mod:`tumble.dynamics.engine`), taking scipy's steps.
- ``"rk4"``, ``"rk8"``: the engine's fixed-step Runge-Kutta (the classical RK4; DOP853's 8th-order
  weights without error control) at ``step``, compiled; built-in torque models only, rotors at
  constant spin and a (not stiff) damper.
- ``"rk45"``: the same state with scipy's RK45 at scipy's *default* tolerances (rtol 1e-3,
  atol 1e-6), as the seed study ran it. For comparison.
- ``"seed"``: the seed's whole computation: RK45 at default tolerances for omega alone, then
  the attitude by ``R <- R exp([omega] dt)`` from the sampled omega (seed sec. 5). This update
  is first order in the sample spacing dt (the rate is frozen over each interval), so its
  attitude error shrinks only in proportion to dt.
- ``"exact"``: the closed-form torque-free motion, omega and attitude
  (:mod:`tumble.dynamics.methods.exact`); the default when there is no torque.
- ``"geometric"`` (4th order), ``"geometric2"``, ``"geometric6"``: fixed-step splitting into
  exact rotations (:mod:`tumble.dynamics.methods.geometric`): |L| and L_world kept to round-off, energy
  error bounded; torques allowed.
- ``"exact_split2"``, ``"exact_split4"``, ``"exact_split6"``: fixed-step splitting into the exact
  free flow and torque kicks (:mod:`tumble.dynamics.methods.exact_split`, Celledoni et al. 2008):
  the free motion costs no error, so a weak torque allows steps longer than a flip; torques
  allowed, rotors and dampers not.

Rotors and dampers (:mod:`tumble.dynamics.models.internal`) go through ``Method.integrate_internal``,
which takes the :class:`~tumble.dynamics.models.internal.InternalModel` and returns its samples:
``"dop853"`` and ``"rk45"`` integrate the model's ODE (total momentum, attitude, the damper's
state and energy budgets), ``"rk4"`` and ``"rk8"`` step the same state compiled
(:mod:`tumble.dynamics.engine.damped`; rotors at constant spin), the ``"geometric"`` methods split
it into exact rotations and the damper's exact relaxation. ``"exact"`` and ``"seed"`` have none
and refuse such runs.

A stiff damper (:data:`~tumble.dynamics.models.internal.STIFF_RATIO`: relaxing more than 500 times
faster than the body spins) would hold an explicit method to steps of its relaxation time, not
the rotation's: ``"dop853"`` then hands the run to scipy's Radau IIA (implicit, order 5,
L-stable; Hairer & Wanner, *Solving ODEs II*, sec. IV.8) at the same tolerances, with the
model's analytic Jacobian (:meth:`~tumble.dynamics.models.internal.InternalModel.jacobian`), and
the run's ``Trajectory.method`` says ``"radau"``; ``simulate`` refuses such a run for ``"rk45"``, ``"rk4"``,
``"rk8"`` and the splitting methods, naming the ratio.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from importlib import import_module
from typing import Any, Protocol, TypeAlias, cast

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, Quaternion, Vector3
from ..engine.front import run_body  # imports no numba: the kernels load on a run's first call
from ..engine.status import MAX_EVALUATIONS  # the work budget of every adaptive method, compiled or not
from ..euler import euler_rhs
from ..models.internal import STIFF_RATIO, InternalModel, InternalSamples
from ..models.torques import TorqueModel, body_torque, kernel_form
from .bounds import spin_gain
from ..special.quaternion import quaternion_rate
from .engine_rk import engine_rk, engine_rk_internal, gyrostat_on_engine, on_the_loop, rk_step
from .names import METHOD_NAMES

__all__ = ["MAX_EVALUATIONS", "METHODS", "Method", "get_method"]



#: ``integrate(moments, omega0, quat0, t, torque, rtol, atol, step)`` -> ``(omega, quat)`` at ``t``.
Integrate: TypeAlias = Callable[
    [ArrayLike, ArrayLike, ArrayLike, FloatArray, "TorqueModel | None", "float | None", "float | FloatArray | None",
     "float | None"],
    tuple[Vector3, Quaternion],
]
#: ``integrate_internal(model, omega0, quat0, t, torque, rtol, atol, step)`` -> the samples of a run
#: with rotors or a damper.
IntegrateInternal: TypeAlias = Callable[
    [InternalModel, ArrayLike, ArrayLike, FloatArray, "TorqueModel | None", "float | None", "float | FloatArray | None",
     "float | None"],
    InternalSamples,
]
class StepRule(Protocol):
    """``default_step(spin, gain, rate)`` -> the largest step, s, of a fixed-step method."""

    def __call__(self, spin: float, gain: float = 0.0, rate: float = 0.0) -> float: ...


class Propagate(Protocol):
    """A splitting's propagator over N bodies: ``(omega, quat)`` of shapes (n, N, 3), (n, N, 4)."""

    def __call__(self, moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *,
                 step: float | None = None, torque: TorqueModel | None = None) -> tuple[FloatArray, FloatArray]: ...


class _Budget:
    """Counts right-hand-side evaluations and gives up, with a clear message, past the budget."""

    def __init__(self, method: str, t_end: float) -> None:
        self.method, self.t_end, self.limit, self.count = method, t_end, MAX_EVALUATIONS, 0

    def __call__(self, time: float) -> None:
        self.count += 1
        if self.count > self.limit:
            raise RuntimeError(
                f"{self.method} gave up after {self.limit:,} evaluations at t = {time:.6g} s of "
                f"{self.t_end:g} s: the motion is too fast to follow (a torque spinning the body up?)"
            )


@dataclass(frozen=True)
class Method:
    """An integration method: its function, capabilities and default tolerances.

    Examples
    --------
    >>> from tumble.dynamics import METHODS
    >>> exact = METHODS["exact"]
    >>> exact.closed_form, exact.supports_torque, METHODS["dop853"].supports_torque
    (True, False, True)
    """

    name: str
    integrate: Integrate
    supports_torque: bool
    rtol: float | None
    atol: float | None
    description: str
    #: Whether ``atol`` is relative to the size of omega (rad/s) rather than absolute.
    atol_scaled: bool = False
    #: Whether the method steps with a fixed ``step`` (s) instead of tolerances.
    fixed_step: bool = False
    #: ``integrate_internal(model, omega0, quat0, t, torque, rtol, atol, step)`` ->
    #: :class:`~tumble.dynamics.models.internal.InternalSamples` for rotors and dampers; None if the
    #: method cannot take them.
    integrate_internal: IntegrateInternal | None = None
    #: Whether the method is a closed form: it evaluates the motion at the times asked for, with
    #: no steps from t = 0 (``simulate`` bounds only its phase, not its rotation, and
    #: ``simulate_batch`` evaluates it for every body at once, at those times alone).
    closed_form: bool = False
    #: Order of the composition of a splitting into exact rotations (2, 4 or 6), which
    #: ``simulate_batch`` advances for every body together; None for the other methods.
    splitting_order: int | None = None
    #: A splitting's propagator over N bodies, ``propagate(moments, omega0, quat0, t, *, step,
    #: torque)`` -> ``(omega, quat)`` of shapes (n, N, 3) and (n, N, 4); None for the others.
    propagate: Propagate | None = None
    #: A fixed-step method's default largest step, ``default_step(spin, gain, rate)`` in s
    #: (:func:`tumble.dynamics.methods.geometric.default_step`); None for the others.
    default_step: StepRule | None = None
    #: Whether the compiled engine (:mod:`tumble.dynamics.engine`) runs it when the torque is a
    #: built-in model (:class:`~tumble.dynamics.models.torques.KernelForm`) and there are no rotors
    #: or damper; ``simulate_batch`` then runs every body there, on every core.
    engine: bool = False
    #: Whether it runs only there: a torque that is a Python function is refused.
    compiled_only: bool = False
    #: Whether ``integrate_internal`` takes only rotors spinning at constant rates (their momentum
    #: one more term of the engine's equations) and a damper, no changing spin.
    constant_rotors_only: bool = False

    def takes(self, internal: InternalModel | None) -> bool:
        """Whether the method takes these rotors and damper (None: a rigid body, always).

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics import METHODS
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> body = tumble.Body([tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2)),
        ...                     tumble.Rotor(mass=0.2, radius=0.05, length=0.01, spin_rate=300.0)])
        >>> steady = InternalModel(body.principal_moments, Rotors.of(body))
        >>> METHODS["rk8"].takes(steady), METHODS["exact"].takes(steady)   # constant spin: a term of the engine
        (True, False)
        >>> damped = InternalModel(body.principal_moments, damper=tumble.SphericalDamper(inertia=0.01, damping=0.1))
        >>> METHODS["rk8"].takes(damped), METHODS["exact"].takes(damped)
        (True, False)
        """
        if internal is None:
            return True
        if self.integrate_internal is None:
            return False
        return not self.constant_rotors_only or internal.rotors is None or internal.rotors.constant

    @property
    def stiff_solver(self) -> bool:
        """Whether the method hands a stiff damper to an implicit solver (so ``simulate`` lets it
        take one); the others refuse a stiff damper. Read off its integrator, which does it.

        Examples
        --------
        >>> from tumble.dynamics import METHODS
        >>> sorted(name for name, m in METHODS.items() if m.stiff_solver)   # doctest: +ELLIPSIS
        [...]
        >>> METHODS["rk45"].stiff_solver
        False
        """
        return bool(getattr(self.integrate_internal, "stiff_solver", False))

    @property
    def supports_internal(self) -> bool:
        """Whether the method takes rotors and a damper, whatever they do (:meth:`takes` for one body's).

        Examples
        --------
        >>> from tumble.dynamics import METHODS
        >>> METHODS["dop853"].supports_internal, METHODS["exact"].supports_internal   # rotors and dampers
        (True, False)
        """
        return self.integrate_internal is not None and not self.constant_rotors_only

    @property
    def batched(self) -> bool:
        """Whether ``simulate_batch`` runs every body together (the closed form and the
        splittings) rather than a loop of ``simulate``, one body at a time.

        Examples
        --------
        >>> from tumble.dynamics import METHODS
        >>> METHODS["exact"].batched, METHODS["rk45"].batched
        (True, False)
        """
        return self.closed_form or self.splitting_order is not None


def _solve(
    method: str, rhs: Callable[[float, FloatArray], FloatArray], y0: FloatArray, t: FloatArray,
    rtol: float | None, atol: float | FloatArray | None, jac: Callable[[float, FloatArray], FloatArray] | None = None,
) -> FloatArray:
    """solve_ivp under the work budget; the states at ``t``, shape (n, len(y0)); ``jac`` for
    the implicit methods."""
    budget = _Budget(method, t[-1])

    def counted(time: float, y: FloatArray) -> FloatArray:
        budget(time)
        return rhs(time, y)

    extra: dict[str, Any] = {} if jac is None else {"jac": jac}
    sol = solve_ivp(counted, (t[0], t[-1]), y0, method=method, t_eval=t, rtol=rtol, atol=atol, **extra)
    if not sol.success:
        raise RuntimeError(f"{method} integration failed: {sol.message}")
    return cast(FloatArray, sol.y.T)


def _solve_full(method: str) -> Integrate:
    def integrate(
        moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
        rtol: float | None, atol: float | FloatArray | None, step: float | None = None,
    ) -> tuple[Vector3, Quaternion]:
        form = kernel_form(torque) if method == "DOP853" else None
        if form is not None:  # a built-in model (or none): the compiled engine takes scipy's steps
            tol = atol if isinstance(atol, np.ndarray) and atol.shape == (7,) else np.full(7, atol, dtype=float)
            return run_body("dop853", np.asarray(moments, float), np.asarray(omega0, float), np.asarray(quat0, float),
                            t, form, rtol=rtol, atol=tol)
        if method == "DOP853" and on_the_loop(torque):  # an ellipse's gravity gradient, a dipole in a field
            from ..control.free_loop import run_free  # the compiled loop, loaded when needed

            return run_free(np.asarray(moments, float), np.asarray(omega0, float), np.asarray(quat0, float), t,
                            torque, cast(float, rtol), cast(float, atol))
        moments = np.asarray(moments, float)

        def rhs(time: float, y: FloatArray) -> FloatArray:
            w, q = y[:3], y[3:]
            tau: float | Vector3 = 0.0 if torque is None else body_torque(torque, time, w, Rotation.from_quat(q))
            return np.concatenate([euler_rhs(w, moments, tau), quaternion_rate(q, w)])

        Y = _solve(method, rhs, np.concatenate([omega0, quat0]), t, rtol, atol)
        return Y[:, :3], Y[:, 3:] / np.linalg.norm(Y[:, 3:], axis=1, keepdims=True)

    return integrate


def stiffness(
    model: InternalModel, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None
) -> tuple[float, float]:
    """A run's damper stiffness ratio and the spin it is measured against (rad/s):
    :meth:`~tumble.dynamics.models.internal.InternalModel.stiffness` at the run's fastest spin, its
    spin bound plus what the torque can add (:func:`~tumble.dynamics.methods.bounds.spin_gain`)."""
    t_end = float(t[-1] - t[0])
    with np.errstate(over="ignore", invalid="ignore"):
        gain = spin_gain(torque, float(t[0]), omega0, Rotation.from_quat(quat0), model.moments, t_end)
    return model.stiffness(model.spin_bound(omega0, t) + gain, t_end)


def _solve_internal(method: str, stiff: str | None = None) -> IntegrateInternal:
    """The internal-model integrator with scipy's ``method``; ``stiff``: the implicit method a
    stiff damper's run is handed to (:data:`~tumble.dynamics.models.internal.STIFF_RATIO`),
    read back as :attr:`Method.stiff_solver` by the entry that uses it."""

    def integrate(
        model: InternalModel, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
        rtol: float | None, atol: float | FloatArray | None, step: float | None = None,
    ) -> InternalSamples:
        form = kernel_form(torque) if method == "DOP853" else None
        steady = model.damper is None and model.rotors is not None and model.rotors.constant
        if steady and (form is not None or method == "DOP853" and on_the_loop(torque)):  # compiled: engine or loop
            return gyrostat_on_engine(model, form, omega0, quat0, t, rtol, atol, torque)
        tau = None if torque is None else (lambda time, w, q: body_torque(torque, time, w, Rotation.from_quat(q)))
        y0 = model.initial_state(omega0, quat0)

        def rhs(time: float, y: FloatArray) -> FloatArray:
            return model.rhs(time, y, tau)

        if stiff is not None and stiffness(model, omega0, quat0, t, torque)[0] > STIFF_RATIO:
            Y = _solve(stiff, rhs, y0, t, rtol, atol, jac=model.jacobian)
            return model.samples(t, Y)._replace(solver=stiff.lower())  # the run says who integrated it
        Y = _solve(method, rhs, y0, t, rtol, atol)
        return model.samples(t, Y)

    integrate.stiff_solver = stiff is not None  # type: ignore[attr-defined]  # read by Method.stiff_solver
    return integrate


def _integrate_seed(
    moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
    rtol: float | None, atol: float | FloatArray | None, step: float | None = None,
) -> tuple[Vector3, Quaternion]:
    """The seed's computation: RK45 for omega, then ``R <- R exp([omega] dt)`` (seed sec. 5)."""
    moments = np.asarray(moments, float)
    budget = _Budget("RK45", t[-1])

    def rhs(time: float, w: Vector3) -> Vector3:
        budget(time)
        return euler_rhs(w, moments)

    sol = solve_ivp(
        rhs, (t[0], t[-1]), omega0, method="RK45", t_eval=t,
        **({} if rtol is None else {"rtol": rtol}), **({} if atol is None else {"atol": atol}),
    )
    if not sol.success:
        raise RuntimeError(f"RK45 integration failed: {sol.message}")
    omega: Vector3 = sol.y.T
    # exp([w] dt) is the rotation by the vector w dt; scipy's from_rotvec is that exponential.
    steps = Rotation.from_rotvec(omega[:-1] * np.diff(t)[:, None])
    quats = np.empty((len(t), 4))
    R = Rotation.from_quat(quat0)
    quats[0] = R.as_quat()
    for k in range(len(t) - 1):
        R = R * steps[k]
        quats[k + 1] = R.as_quat()
    return omega, quats


def _integrate_exact(
    moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
    rtol: float | None, atol: float | FloatArray | None, step: float | None = None,
) -> tuple[Vector3, Quaternion]:
    from .exact import FreeRotation

    motion = FreeRotation(moments, omega0, Rotation.from_quat(quat0))
    return motion.omega(t), motion.attitude(t).as_quat()


def _geometric_internal(order: int) -> IntegrateInternal:
    def integrate(
        model: InternalModel, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
        rtol: float | None, atol: float | FloatArray | None, step: float | None = None,
    ) -> InternalSamples:
        from .geometric import propagate_internal

        return propagate_internal(model, omega0, quat0, t, order=order, step=step, torque=torque)

    return integrate


def _splitting(name: str, order: int, description: str, family: str = "geometric") -> Method:
    """A splitting method of composition ``order`` from the module ``family`` (``geometric``:
    exact rotations, or ``exact_split``: the exact free flow): one value for its integrators,
    its batch propagator and its default step."""

    def module() -> Any:
        return import_module(f".{family}", __package__)

    def propagate(moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *,
                  step: float | None = None, torque: TorqueModel | None = None) -> tuple[FloatArray, FloatArray]:
        return cast(tuple[FloatArray, FloatArray],
                    module().propagate(moments, omega0, quat0, t, order=order, step=step, torque=torque))

    def integrate(moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: FloatArray, torque: TorqueModel | None,
                  rtol: float | None, atol: float | FloatArray | None, step: float | None = None) -> tuple[Vector3, Quaternion]:
        omega, quat = propagate(moments, omega0, quat0, t, step=step, torque=torque)
        return omega[:, 0], quat[:, 0]

    def default_step(spin: float, gain: float = 0.0, rate: float = 0.0) -> float:
        return float(module().default_step(spin, gain, rate))

    internal = _geometric_internal(order) if family == "geometric" else None
    return Method(name, integrate, True, None, None, description, fixed_step=True, integrate_internal=internal,
                  splitting_order=order, propagate=propagate, default_step=default_step)


#: The integration methods by name: what ``simulate(method=...)`` accepts (docs/methods.md compares them).
METHODS: dict[str, Method] = {
    "exact": Method("exact", _integrate_exact, False, None, None,
                    "closed form (Jacobi elliptic functions, elliptic integral of the third kind)",
                    closed_form=True),
    "dop853": Method("dop853", _solve_full("DOP853"), True, 1e-12, 1e-12,
                     "DOP853, omega and attitude together, tight tolerances (rtol 1e-12); Radau for a stiff damper",
                     atol_scaled=True, engine=True,
                     integrate_internal=_solve_internal("DOP853", stiff="Radau")),
    "rk45": Method("rk45", _solve_full("RK45"), True, 1e-3, 1e-6,
                   "RK45 at scipy's default tolerances (rtol 1e-3, atol 1e-6), as the seed ran it",
                   integrate_internal=_solve_internal("RK45")),
    "seed": Method("seed", _integrate_seed, False, None, None,
                   "the seed's computation: RK45 defaults for omega, then R <- R exp([w] dt) (first order)"),
    "geometric": _splitting("geometric", 4, "splitting into exact rotations, 4th-order Yoshida composition, fixed step"),
    "geometric2": _splitting("geometric2", 2, "splitting into exact rotations, 2nd order (Strang), fixed step"),
    "geometric6": _splitting("geometric6", 6, "splitting into exact rotations, 6th-order Yoshida composition, fixed step"),
    "exact_split2": _splitting("exact_split2", 2, "exact free flow and torque kicks, 2nd order (Strang), fixed step",
                               "exact_split"),
    "exact_split4": _splitting("exact_split4", 4, "exact free flow and torque kicks, 4th-order Yoshida composition, "
                               "fixed step", "exact_split"),
    "exact_split6": _splitting("exact_split6", 6, "exact free flow and torque kicks, 6th-order Yoshida composition, "
                               "fixed step", "exact_split"),
    "rk4": Method("rk4", engine_rk("rk4"), True, None, None,
                  "classical RK4 at a fixed step, compiled (built-in torques, rotors at constant spin)",
                  fixed_step=True, default_step=rk_step("rk4"), engine=True, compiled_only=True,
                  integrate_internal=engine_rk_internal("rk4"), constant_rotors_only=True),
    "rk8": Method("rk8", engine_rk("rk8"), True, None, None,
                  "DOP853's 8th-order weights at a fixed step, compiled (built-in torques, rotors at constant spin)",
                  fixed_step=True, default_step=rk_step("rk8"), engine=True, compiled_only=True,
                  integrate_internal=engine_rk_internal("rk8"), constant_rotors_only=True),
}


if tuple(METHODS) != METHOD_NAMES:  # the one list the help texts read (names.py): never out of step
    raise ImportError(f"the method registry {tuple(METHODS)} and tumble.dynamics.methods.names.METHOD_NAMES differ")


def get_method(name: str) -> Method:
    """The registered method called ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`METHODS`.

    Returns
    -------
    Method

    Raises
    ------
    ValueError
        For an unknown name; the message lists the known ones.

    Examples
    --------
    >>> from tumble.dynamics.methods.integrators import get_method
    >>> get_method("dop853").name
    'dop853'
    >>> get_method("euler")   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: method = 'euler' ...
    """
    try:
        return METHODS[name]
    except (KeyError, TypeError):
        raise ValueError(f"method = {name!r} is unknown; allowed: {', '.join(METHODS)}") from None
