"""One entry point for every integration method: :func:`simulate`."""

from __future__ import annotations

import functools
import math
import numbers
from typing import Any, NamedTuple, cast

import numpy as np
from scipy.spatial.transform import Rotation

from ..mass import INERTIA_RTOL, Body, MassProperties
from ..mass.body import properties_of
from ..typing import ArrayLike, FloatArray, Quaternion, Vector3
from ..validation import MAX_INERTIA, MAX_RATE, beyond, check_increasing, check_positive, check_rotation, check_vector
from .engine.front import ENGINE_METHODS
from .engine.stepsize import RTOL_RANGE, check_atol, check_rtol
from .methods.arguments import warn_ignored
from .methods.auto import AUTO_RTOL, dop853_tolerances, engine_choice, rk_step
from .methods.bounds import design_torque, linear_gain, run_spin_gain, spin_bound
from .methods.engine_rk import COMPILED_MODELS, on_the_loop
from .methods.integrators import METHODS, IntegrateInternal, Method, StepRule, get_method
from .methods.names import AUTO, method_list, unknown_method
from .models.internal import STIFF_RATIO, InternalModel, Rotors, SphericalDamper
from .models.torques import TorqueLike, TorqueModel, as_torque, bind_to_body, kernel_form
from .trajectory import Trajectory

__all__ = ["DEFAULT_METHOD", "FRAMES", "RunInputs", "check_inputs", "sample_times", "simulate"]

#: The method used when none is named: ``"auto"``, chosen from what the run has
#: (:mod:`tumble.dynamics.methods.auto`): the exact solution without torque, else the fastest of
#: the methods that take the run at ``rtol`` (default 1e-10).
DEFAULT_METHOD = AUTO
#: Default number of samples when neither ``samples``, ``dt`` nor ``times`` is given (the seed's).
DEFAULT_SAMPLES = 500
#: Frames in which ``omega0`` (and a body-frame torque) may be given.
FRAMES = ("principal", "design")
#: Upper bound on samples, to refuse a typo such as 5e9 before allocating memory.
MAX_SAMPLES = 1_000_000
#: Longest run, s (about 30,000 years): beyond it the phase of any motion loses all its digits.
MAX_T_END = 1e12
#: Most rotation (rad) a stepping method is asked to follow, counting the spin a torque can build up:
#: 1e6 rad is ~4e7 right-hand sides of DOP853 at rtol 1e-12, ~45 min with a Python torque (2.9 s a
#: 1e3 rad, 2026-12-02); the exact solution has no such limit, the compiled engine the next one.
MAX_ROTATION = 1e6
#: The same on the compiled engine (dop853, rk4, rk8, the built-in torques, no rotors or damper): 1e6
#: rad took it 1.0 s (the T-handle at 10 rad/s, rtol 1e-12), 1e8 a minute or two; steps: MAX_STEPS.
MAX_COMPILED_ROTATION = 1e8
#: Most rotation (rad) a run with a stiff damper is asked to follow (``"dop853"`` hands it to
#: Radau, :data:`~tumble.dynamics.models.internal.STIFF_RATIO`): Radau at rtol 1e-12 takes ~1,200
#: right-hand sides per radian (measured), so 1e4 rad is about a quarter of an hour here.
MAX_STIFF_ROTATION = 1e4
#: Most steps a fixed-step method is asked to take.
MAX_STEPS = 2e7
class RunInputs(NamedTuple):
    """The checked inputs of one run, defaults filled in (see :func:`check_inputs`).

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics.simulate import check_inputs
    >>> run = check_inputs(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 0.0, 0.0], t_end=1.0, samples=3)
    >>> run.method.name, run.t.tolist(), run.torque is None, run.internal is None
    ('exact', [0.0, 0.5, 1.0], True, True)
    """

    props: MassProperties
    method: Method
    omega0: Vector3  # principal frame, rad/s
    quat0: Quaternion  # principal body frame -> world, scalar last
    t: FloatArray  # times the integrator is sampled at, s, starting at 0
    keep: slice  # the samples returned (all but a leading t = 0 the caller did not ask for)
    rtol: float | None
    atol: float | None
    step: float | None
    torque: TorqueModel | None  # a torque model in the principal frame, or None
    internal: InternalModel | None = None  # rotors and/or a damper, or None
    spin: float = 0.0  # the spin the run starts from, rad/s (spin_bound; 0 for the closed form)
    gain: float = 0.0  # bound on the spin the torque adds over the run, rad/s (run_spin_gain; 0 for the closed form)
    atol_scaled: bool = False  # atol relative to the spin: the method's (dop853), or an rtol given alone
    auto: bool = False  # the method was chosen ("auto")
    form: tuple[int, tuple[float, ...]] | None = None  # the torque's compiled form (kernel_form), None: Python's


def simulate(
    body: Body | MassProperties,
    omega0: ArrayLike,
    *,
    t_end: float | None = None,
    samples: int | None = None,
    dt: float | None = None,
    times: ArrayLike | None = None,
    method: str | None = None,
    frame: str = "principal",
    torque: TorqueLike | None = None,
    rtol: float | None = None,
    atol: float | None = None,
    attitude0: Rotation | ArrayLike | None = None,
    step: float | None = None,
    damper: SphericalDamper | None = None,
) -> Trajectory:
    """Integrate the rotation of a rigid body from an initial angular velocity.

    Parameters
    ----------
    body : Body or MassProperties
        The body; its principal frame (``I1 <= I2 <= I3``) is the body frame of the motion.
        A body with :class:`~tumble.mass.Rotor` parts is a gyrostat: their internal momentum
        enters Euler's equations (:mod:`tumble.dynamics.models.internal`).
    omega0 : array_like, shape (3,)
        Initial angular velocity at t = 0, rad/s, in ``frame``; each component at most 1e15
        rad/s (:data:`~tumble.validation.MAX_RATE`), the body's moments at most 1e50 kg m^2.
    t_end : float, optional
        Duration, s. Samples are taken at ``samples`` equally spaced times in ``[0, t_end]``,
        or every ``dt`` seconds from 0 up to ``t_end``.
    samples : int, optional
        Number of samples (>= 2) with ``t_end``; default 500.
    dt : float, optional
        Sample spacing, s, with ``t_end`` (instead of ``samples``): samples at ``0, dt, 2 dt,
        ...`` up to ``t_end`` (the last one is ``t_end`` when ``t_end / dt`` is whole).
    times : array_like, shape (n,), optional
        The sample times themselves, s: finite, strictly increasing, ``times[0] >= 0``
        (instead of ``t_end``). The motion starts at t = 0 in every case.
    method : str, optional
        ``"auto"`` or a name from :data:`tumble.dynamics.METHODS` (docs/methods.md compares them):
        {methods}.
        ``"auto"`` (the default) chooses: ``exact`` without torque, rotors or damper; the engine's
        ``dop853`` or ``rk8``, the faster at ``rtol``, for the built-in torques, rotors at constant spin and
        a damper (``rk8``); ``dop853`` for a Python torque, a stiff damper or rotors whose spin
        changes (:mod:`~tumble.dynamics.methods.auto`). The run's ``method`` says which.
    frame : {"principal", "design"}
        Frame of ``omega0``: the principal frame (axes ordered I1 <= I2 <= I3) or the body's
        design frame. A body-frame torque is read in the same frame: a function is called with
        omega in that frame and that frame's attitude (design to world for ``"design"``).
    torque : callable or torque model, optional
        ``tau(t, omega, attitude)`` in N m (see :mod:`tumble.dynamics.models.torques`).
    rtol, atol : float, optional
        Tolerances; the method's defaults if not given. ``"auto"`` meets rtol (1e-10) in the answer's omega and attitude,
        atol = rtol relative to |omega|; to ``"dop853"`` and ``"rk45"`` they bound each step's error, and the end's is
        10-1000 times larger (docs/methods.md). ``rtol`` from 100 eps to 0.1, ``atol`` up to 0.1 (``"dop853"``: relative
        to |omega|); an ``rtol`` given alone to ``"rk45"`` (or below 1e-12 to ``"dop853"``) brings ``atol`` down with it.
    attitude0 : scipy Rotation, quaternion or matrix, optional
        Initial rotation of the *design* frame to the world frame; default identity (the body
        starts as it was designed).
    step : float, optional
        Largest step of the fixed-step methods (``"rk4"``, ``"rk8"``, the ``"geometric"`` and
        ``"exact_split"`` splittings), s (default: a rotation per step that depends on the method,
        counting the spin a torque builds up; for ``"rk4"`` and ``"rk8"`` given ``rtol``, the step
        that meets it, :func:`~tumble.dynamics.methods.auto.rk_angle`). The others choose their own
        steps. An argument the method does not read (``step`` given to an adaptive method or
        ``"auto"``, ``rtol`` or ``atol`` to a splitting, ``rtol`` beside a ``step`` or ``atol`` to
        ``"rk4"`` and ``"rk8"``) has no effect and warns
        (:class:`~tumble.dynamics.methods.arguments.IgnoredArgumentWarning`).
    damper : SphericalDamper, optional
        A spherical nutation damper inside the body
        (:class:`~tumble.dynamics.models.internal.SphericalDamper`), starting with the body's
        angular velocity.

    Returns
    -------
    Trajectory

    Raises
    ------
    ValueError
        For bad input, naming the argument and what is allowed, and for a run that would turn
        the body more than a stepping method can follow (:data:`MAX_ROTATION`).
    RuntimeError
        When an integration fails or exceeds its work budget.

    Examples
    --------
    >>> import numpy as np
    >>> import tumble
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
    >>> traj = tumble.simulate(body, [0.01, 1.0, 0.0], t_end=20.0, samples=201)   # near the intermediate axis
    >>> traj.method, traj.auto, traj.omega.shape   # the method "auto" chose
    ('exact', True, (201, 3))
    >>> bool(traj.omega[:, 1].min() < -0.9)   # the tennis-racket flip: omega_2 turns round
    True
    >>> traj.drift["energy"] < 1e-12, traj.drift["L_world"] < 1e-12   # conserved, torque-free
    (True, True)
    >>> spun = tumble.simulate(body, [0.0, 0.0, 0.0], t_end=2.0, samples=3,
    ...                        torque=tumble.ConstantTorque((0.0, 0.0, 3.0), "body"))
    >>> spun, spun.omega[-1].round(6).tolist()   # omega_3 = tau t / I3
    (Trajectory('body', dop853 (auto), 3 samples, t = 0..2 s, torqued), [0.0, 0.0, 2.0])
    """
    run = check_inputs(body, omega0, t_end=t_end, samples=samples, dt=dt, times=times, method=method, frame=frame,
                       rtol=rtol, atol=atol, step=step, torque=torque, attitude0=attitude0, damper=damper)
    tol: float | FloatArray | None  # atol; per component where the method scales it
    spec, model, tol, internal = run.method, run.torque, run.atol, run.internal
    moments = run.props.principal_moments
    if run.atol_scaled and tol is not None:
        # relative to the body's own spin: a gyrostat's nutation (run.spin) can be far faster
        spin = run.spin if internal is None else internal.tolerance_spin(run.omega0, run.t)
        scale = max(spin, run.gain, 1e-300)
        tol = np.array([tol * scale] * 3 + [tol] * 4) if internal is None else internal.atol(tol, scale)
    extra: dict[str, Any] = {}  # the rotors' and the damper's fields of the Trajectory
    label = spec.name  # the integrator that ran: "radau" where "dop853" handed it a stiff damper
    if internal is None:
        omega, quat = spec.integrate(moments, run.omega0, run.quat0, run.t, model, run.rtol, tol, run.step)
    else:
        # a method that takes rotors and a damper has integrate_internal (check_inputs)
        out = cast(IntegrateInternal, spec.integrate_internal)(internal, run.omega0, run.quat0, run.t, model, run.rtol, tol, run.step)
        omega, quat, label = out.omega, out.quat, out.solver or spec.name
        extra = {k: (v[run.keep] if k not in ("rotor_axial_moments", "damper_inertia") else v)
                 for k, v in internal.trajectory_fields(run.t, out).items()}
    # one sum each: a NaN or inf makes it non-finite; the engine's kernels check their states (status NON_FINITE)
    if not (internal is None and spec.name in ENGINE_METHODS and run.form is not None) \
            and not math.isfinite(float(omega.sum()) + float(quat.sum())):
        raise RuntimeError(f"the {label} integration produced non-finite values")
    keep = run.keep
    return Trajectory.of_samples(  # the quaternions: the Rotation is built when first asked for
        run.t[keep] if keep.start else run.t, omega[keep] if keep.start else omega, quat[keep] if keep.start else quat,
        moments, run.props.principal_axes, label, model is None, body.name if isinstance(body, Body) else "body",
        auto=run.auto, **extra)


if simulate.__doc__:  # every method of the registry, as help(tumble.simulate) and the API page list them
    simulate.__doc__ = simulate.__doc__.replace("{methods}", method_list("``", width=88, indent=" " * 8))


def sample_times(t_end: float | None = None, samples: int | None = None, dt: float | None = None,
                 times: ArrayLike | None = None) -> tuple[FloatArray, slice]:
    """The times to sample, from exactly one of ``t_end`` (with ``samples`` or ``dt``) or ``times``.

    Returns the grid the integrator follows (always starting at t = 0) and the slice of it
    that the caller asked for. Raises ``ValueError`` naming the argument.

    Examples
    --------
    >>> from tumble.dynamics.simulate import sample_times
    >>> t, keep = sample_times(t_end=1.0, samples=5)
    >>> t.tolist(), t[keep].tolist()
    ([0.0, 0.25, 0.5, 0.75, 1.0], [0.0, 0.25, 0.5, 0.75, 1.0])
    >>> t, keep = sample_times(times=[0.5, 1.0])   # the run starts at 0; the caller gets its own times
    >>> t.tolist(), t[keep].tolist()
    ([0.0, 0.5, 1.0], [0.5, 1.0])
    """
    if times is not None:
        if t_end is not None or samples is not None or dt is not None:
            raise ValueError("times = [...] replaces t_end, samples and dt: give times alone")
        if isinstance(times, (str, bytes, dict, set)) or np.ndim(times) != 1:
            raise ValueError(f"times = {times!r} must be a list of sample times (s)")
        try:
            t = np.array(times, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"times = {times!r} must be a list of numbers (s)") from None
        if not 1 <= len(t) <= MAX_SAMPLES:
            raise ValueError(f"times has {len(t)} entries; allowed: 1 to {MAX_SAMPLES}")
        if not np.all(np.isfinite(t)):
            raise ValueError(f"times[{int(np.flatnonzero(~np.isfinite(t))[0])}] is not a finite number (s)")
        if t[0] < 0:
            raise ValueError(f"times[0] = {float(t[0])!r} must be >= 0 s: the motion starts at t = 0")
        check_increasing("times", t)
        if not 0 < t[-1] <= MAX_T_END:
            raise ValueError(f"times[-1] = {float(t[-1])!r} must be after 0 and at most {MAX_T_END:g} s")
        if t[0] > 0:  # the integrator starts from the initial state at t = 0
            return np.concatenate([[0.0], t]), slice(1, None)
        return t, slice(None)
    if t_end is None:
        raise ValueError("t_end (s) or times = [...] is needed: how long to run")
    t_end = check_positive("t_end", t_end, "s")
    if t_end > MAX_T_END:
        raise ValueError(f"t_end = {t_end!r} must be at most {MAX_T_END:g} s")
    if dt is not None:
        if samples is not None:
            raise ValueError("give samples or dt, not both")
        dt = check_positive("dt", dt, "s")
        n = math.floor(t_end / dt * (1 + 1e-12)) + 1 if t_end / dt < MAX_SAMPLES else MAX_SAMPLES + 1
        if not 2 <= n <= MAX_SAMPLES:
            raise ValueError(f"dt = {dt!r} s gives {n} sample{'s' if n != 1 else ''} over {t_end:g} s; allowed: 2 to {MAX_SAMPLES}")
        t = dt * np.arange(n)
        t[-1] = min(t[-1], t_end)  # a whole t_end / dt ends exactly at t_end
        return cast(FloatArray, t), slice(None)
    samples = DEFAULT_SAMPLES if samples is None else samples
    if type(samples) is not int and (isinstance(samples, bool) or not isinstance(samples, numbers.Integral)) \
            or not 2 <= samples <= MAX_SAMPLES:
        raise ValueError(f"samples = {samples!r} must be a whole number from 2 to {MAX_SAMPLES}")
    return _grid(t_end, int(samples)).copy(), slice(None)


@functools.lru_cache(maxsize=64)
def _grid(t_end: float, samples: int) -> FloatArray:
    """``linspace(0, t_end, samples)``, kept for repeated runs (numpy's linspace costs ~10 us);
    callers get a copy."""
    return np.linspace(0.0, t_end, samples)


def check_inputs(body: Body | MassProperties, omega0: ArrayLike, *, t_end: float | None = None, samples: int | None = None,
                 dt: float | None = None, times: ArrayLike | None = None, method: str | None = None,
                 frame: str = "principal", rtol: float | None = None, atol: float | None = None,
                 step: float | None = None, torque: TorqueLike | None = None,
                 attitude0: Rotation | ArrayLike | None = None, damper: SphericalDamper | None = None) -> RunInputs:
    """Validate :func:`simulate`'s arguments (scenario files use it too, before anything runs).

    Fills in the defaults (``"auto"`` resolved to a method, :mod:`~tumble.dynamics.methods.auto`),
    converts ``omega0`` and a body-frame torque to the principal frame, and bounds the work:
    a run that would turn the body more than :data:`MAX_ROTATION` rad under a stepping method,
    counting the spin the torque builds up (``|omega| <= |omega0| + |tau| t / I1``), is refused
    before it starts.

    Raises ``ValueError`` whose message starts with the argument's name.

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics.simulate import check_inputs
    >>> run = check_inputs(tumble.t_handle(), [0.0, 10.0, 0.0], t_end=1.0, frame="design")
    >>> run.method.name, run.omega0.round(6).tolist(), len(run.t)   # design y is the major axis, I3
    ('exact', [0.0, 0.0, 10.0], 500)
    >>> check_inputs(tumble.t_handle(), [0.0, 10.0, 0.0], t_end=-1.0)   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: t_end = -1.0 ...
    """
    props = properties_of(body)
    model = as_torque(torque)
    model = bind_to_body(model, props)  # a torque that needs the body's moments (NeedsBody)
    if damper is not None and not isinstance(damper, SphericalDamper):
        raise ValueError(f"damper = {damper!r} must be a tumble.SphericalDamper(inertia=..., damping=...) or None")
    rotors = Rotors.of(body)
    internal = None
    if rotors is not None or damper is not None:
        internal = InternalModel(props.principal_moments, rotors, damper)
    auto = method is None or isinstance(method, str) and method == AUTO
    asked = {"rtol": rtol, "atol": atol, "step": step}  # as given: the method may not read some (below)
    if auto and model is None and internal is None:
        method = "exact"
    elif auto:  # refined between the engine's dop853 and rk8 once the spin is known
        method, rtol = "dop853", AUTO_RTOL if rtol is None else rtol
        atol = rtol if atol is None else atol
    elif not isinstance(method, str) or method not in METHODS:
        raise ValueError(unknown_method(method))
    spec = get_method(method)
    form = kernel_form(model)  # the torque's compiled form, None: Python's (again below if the frame turns it)
    if model is not None and not spec.supports_torque:  # those that take this torque: a Python one, not compiled only
        allowed = ", ".join(m for m, s in METHODS.items() if s.supports_torque and (
            not s.compiled_only or form is not None or on_the_loop(model)))
        raise ValueError(f"method = {spec.name!r} cannot take a torque; use one of: auto (the default), {allowed}")
    if spec.compiled_only and form is None:
        loop = on_the_loop(model)  # an ellipse's or a TLE's gravity gradient, a dipole in a field
        if loop and internal is not None and (internal.damper is not None or not cast(Rotors, rotors).constant):
            raise ValueError(f"method = {spec.name!r} takes an ellipse's or a TLE's gravity gradient and a ResidualDipole "
                             f"with rotors at constant spin, not with a damper or rotors whose spin changes; use method "
                             f"dop853")
        if not loop:
            allowed = ", ".join(m for m, s in METHODS.items() if s.supports_torque and not s.compiled_only)
            raise ValueError(f"method = {spec.name!r} runs compiled and takes only the built-in torque models "
                             f"({COMPILED_MODELS}); for torque = {torque!r} use one of: {allowed}")
    if not spec.takes(internal):
        what = f"rotors ({len(rotors.parts)} in this body)" if rotors is not None else "a damper"
        if spec.constant_rotors_only:  # it takes rotors at constant spin and a damper: say what else it is given
            what = f"rotors whose spin changes ({len(cast(Rotors, rotors).parts)} in this body)"
        allowed = ", ".join(m for m, s in METHODS.items() if s.takes(internal))
        raise ValueError(f"method = {spec.name!r} cannot take {what}; use one of: {allowed}")
    if not isinstance(frame, str) or frame not in FRAMES:
        raise ValueError(f"frame = {frame!r} is not allowed; allowed: {', '.join(FRAMES)}")
    w0 = np.array(check_vector("omega0", omega0, "rad/s", at_most=MAX_RATE))
    t, keep = sample_times(t_end, samples, dt, times)
    t_end = float(t[-1])
    if rtol is not None and not (type(rtol) is float and RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]):  # else checked here
        rtol = check_rtol("rtol", rtol)
    # an rtol given alone is honoured by every adaptive method: its atol follows it, relative to the spin (rk45's
    # scipy default 1e-6 rad/s capped a slow body's run; dop853's 1e-12 of the spin at rtol 1e-13 left 2e-10)
    follows = atol is None and rtol is not None and spec.rtol is not None and not (spec.atol_scaled and rtol >= (spec.atol or 0.0))
    atol_scaled = spec.atol_scaled or follows
    if atol is not None:
        atol = check_atol("atol", atol)
    atol = rtol if follows else spec.atol if atol is None else atol
    rtol = spec.rtol if rtol is None else rtol
    if step is not None:
        step = check_positive("step", step, "s")
    warn_ignored(spec, auto=auto, stacklevel=4, **asked)  # the user's line: simulate, check_inputs, warn_ignored
    moments = props.principal_moments
    I = moments.tolist()  # float arithmetic: these checks cost nothing for plain inputs
    if not max(I) <= MAX_INERTIA:
        raise ValueError(f"principal moments {moments.tolist()} kg m^2: beyond {MAX_INERTIA:g} kg m^2, more than any "
                         f"star's; use SI units of a sensible size")
    # a moment within the validity checks' tolerance of zero is a zero moment (a single thin
    # rod's eigh gives ~1e-17, not 0): the rotation about that axis is not well posed
    if min(I) <= INERTIA_RTOL * (I[0] + I[1] + I[2]):
        raise ValueError(
            f"principal moments {moments.tolist()} kg m^2: a body with a zero moment (a thin rod, "
            f"a point) has no well-posed rotation about that axis; give it some thickness"
        )
    w = w0.tolist()  # Python floats overflow to inf (no warning, no error), refused below
    energy = 0.5 * (I[0] * w[0] * w[0] + I[1] * w[1] * w[1] + I[2] * w[2] * w[2])
    momentum = math.hypot(I[0] * w[0], I[1] * w[1], I[2] * w[2])
    if not (math.isfinite(energy) and math.isfinite(momentum)):
        raise ValueError(f"omega0 = {w0.tolist()} rad/s is too large: the kinetic energy of this body overflows")
    A = props.principal_axes  # principal -> design
    if frame == "design":
        w0 = A.T @ w0
        if model is not None and model.frame == "body":
            model = design_torque(model, A)
            form = kernel_form(model)
    axes = A.tobytes() if A.dtype == np.float64 and A.flags.c_contiguous else np.asarray(A, float).tobytes()
    if type(attitude0) is np.ndarray and attitude0.shape == (4,) and attitude0.dtype == np.float64:
        q0 = np.array(_initial_quat_of(attitude0.tobytes(), axes))  # the check once for the same bytes
    else:
        design_to_world = None if attitude0 is None else np.array(check_rotation("attitude0", attitude0)).tobytes()
        q0 = np.array(_initial_quat(design_to_world, axes))
    spin = gain = 0.0
    if not spec.closed_form:  # a stepping method: its work is bounded by the spin it follows
        spin = spin_bound(internal, w0, t)
        # a bound linear in time (no attitude read) where it passes the work check: alone for a given
        # step of a fixed-step method (which reads it only there) and for "auto" where it is small
        # beside the spin; else the model's own, and for "auto" the smaller of the two
        quick = linear_gain(form, moments, t_end) if auto or spec.fixed_step and step is not None else None
        if quick is not None and (not auto or quick <= 0.01 * spin) and (spin + 0.5 * quick) * t_end <= MAX_ROTATION:
            gain = quick
        else:
            gain = run_spin_gain(model, w0, q0, moments, t_end)
            gain = min(gain, quick) if auto and quick is not None else gain
    if asked["rtol"] is not None and step is None and spec.fixed_step and spec.engine and not auto:
        step = rk_step(spec.name, cast(float, rtol), spin + gain, internal, asked=True)  # meeting rtol, as auto's rk8
    if auto and not spec.closed_form:
        engine = METHODS["rk8"]  # the engine's fixed step takes what its dop853 takes, and a damper
        # and the closed loop's kernel (an ellipse, a TLE, a dipole) takes both at the same steps
        compiled = form is not None or ((internal is None or internal.damper is None) and on_the_loop(model))
        h = engine_choice(t, spin, gain, cast(float, rtol), internal) if engine.takes(internal) and compiled else None
        if h is not None:
            spec, step = engine, h
        else:  # dop853's local error control, tighter than the accuracy asked for (methods.auto)
            rtol, atol = dop853_tolerances(cast(float, rtol), cast(float, atol))
    run = RunInputs(props, spec, w0, q0, t, keep, rtol, atol, step, model, internal, spin, gain, atol_scaled, auto, form)
    _check_work(run)
    return run


@functools.lru_cache(maxsize=256)
def _initial_quat_of(attitude0: bytes, axes: bytes) -> tuple[float, ...]:
    """:func:`_initial_quat` of ``attitude0`` given as a float64 quaternion's raw bytes, checked
    (:func:`~tumble.validation.check_rotation`) the first time these bytes are seen."""
    design_to_world = np.array(check_rotation("attitude0", np.frombuffer(attitude0).copy())).tobytes()
    return _initial_quat(design_to_world, axes)


@functools.lru_cache(maxsize=256)
def _initial_quat(design_to_world: bytes | None, axes: bytes) -> tuple[float, ...]:
    """The principal frame's initial attitude, ``(design -> world) * (principal -> design)``, as a
    quaternion (scalar last), from the raw float64 bytes of the first's quaternion (None: the
    identity) and of the body's principal axes (3 x 3). Kept for repeated runs of one body and
    attitude: scipy's ``Rotation.from_matrix`` and product cost ~0.15 ms a call."""
    A = Rotation.from_matrix(np.frombuffer(axes).reshape(3, 3))
    R = Rotation.identity() if design_to_world is None else Rotation.from_quat(np.frombuffer(design_to_world))
    return tuple((R * A).as_quat().tolist())


def _check_work(run: RunInputs) -> None:
    """Refuse a run whose rotation or step count no stepping method can follow in bounded time."""
    spec, t_end = run.method, float(run.t[-1])
    if spec.closed_form:  # no steps; only its phase is bounded (MAX_PHASE)
        from .methods.exact import check_phase_limit

        check_phase_limit(run.props.principal_moments, run.omega0, t_end)
        return
    spin, gain = run.spin, run.gain  # the spin the run starts from, and what the torque can add, rad/s
    turns = spin * t_end + 0.5 * gain * t_end  # Python floats: an overflow is inf, refused below
    compiled = spec.name in ENGINE_METHODS and run.internal is None and run.form is not None
    limit = MAX_COMPILED_ROTATION if compiled else MAX_ROTATION
    if not turns <= limit:
        what = "|omega0|" if run.internal is None or run.internal.rotors is None else "|omega0| + 2 max|h| / I1"
        cause = f"{what} = {spin:.6g} rad/s" if gain == 0 else (
            f"{what} = {spin:.6g} rad/s and a torque that can spin it up by {gain:.3g} rad/s")
        more = "" if compiled else f"; {MAX_COMPILED_ROTATION:g} on the compiled engine: dop853, rk4 or rk8, built-in torques"
        raise ValueError(f"t_end = {t_end:g} s with {cause} is up to {beyond(turns, limit)} rad of rotation, more than method "
                         f"{spec.name!r} follows (at most {limit:g} rad{more}); "
                         f"{'shorten the run or weaken the torque' if gain else 'use method exact or a shorter run'}")
    if run.internal is not None and run.internal.damper is not None:
        _check_stiffness(run, spin + gain, turns)
    if spec.fixed_step:
        rate = 0.0 if run.internal is None else run.internal.relaxation_rate
        h = run.step or cast(StepRule, spec.default_step)(spin, gain, rate)  # a fixed-step method has one
        if t_end / h > MAX_STEPS:
            raise ValueError(f"step = {h:.3g} s makes {t_end / h:.3g} steps of a {t_end:g} s run; at most {MAX_STEPS:g}")


def _check_stiffness(run: RunInputs, spin: float, turns: float) -> None:
    """Refuse a stiff damper (:data:`~tumble.dynamics.models.internal.STIFF_RATIO`) to the methods that
    cannot follow it, and a longer run than :data:`MAX_STIFF_ROTATION` to the one that can."""
    spec, t_end = run.method, float(run.t[-1])
    internal = cast(InternalModel, run.internal)  # called with a damper only
    ratio, slow = internal.stiffness(spin, t_end)
    if not ratio > STIFF_RATIO:
        return
    stiff = (f"damper: its relaxation rate (c / J)(1 + J / I1) = {internal.relaxation_rate:.3g} 1/s is "
             f"{ratio:.3g} times the spin rate {slow:.3g} rad/s (stiff above {STIFF_RATIO:g})")
    if not spec.stiff_solver:
        why = ("an explicit method's steps would be held to the relaxation time" if not spec.fixed_step else
               "its fixed steps would have to resolve the relaxation" if spec.engine else
               "the splitting's step would have to resolve the relaxation")
        able = ", ".join(m for m, s in METHODS.items() if s.stiff_solver)
        raise ValueError(f"{stiff}: method {spec.name!r} cannot follow it ({why}); use method {able}, which "
                         f"integrates a stiff damper with the implicit Radau")
    if turns > MAX_STIFF_ROTATION:
        raise ValueError(f"{stiff}: t_end = {t_end:g} s is up to {beyond(turns, MAX_STIFF_ROTATION)} rad of rotation, more than the implicit "
                         f"Radau that {spec.name} hands it to follows (at most {MAX_STIFF_ROTATION:g} rad); shorten the run")
