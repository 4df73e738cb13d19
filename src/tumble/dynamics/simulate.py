"""One entry point for every integration method: :func:`simulate`."""

from __future__ import annotations

import numbers

import numpy as np
from scipy.spatial.transform import Rotation

from ..mass import Body, MassProperties
from ..mass._checks import check_positive, check_rotation, check_vector
from .integrators import METHODS, get_method
from .torques import as_torque, body_torque
from .trajectory import Trajectory

__all__ = ["DEFAULT_METHOD", "FRAMES", "simulate"]

#: The method used when none is named: chosen for accuracy, not faithfulness to the seed.
#: Without torque the exact solution; with a torque, DOP853 at tight tolerances.
DEFAULT_METHOD = "exact"
DEFAULT_TORQUE_METHOD = "dop853"
#: Frames in which ``omega0`` (and a body-frame torque) may be given.
FRAMES = ("principal", "design")
#: Upper bound on samples, to refuse a typo such as 5e9 before allocating memory.
MAX_SAMPLES = 1_000_000
#: Longest run, s (about 30,000 years): beyond it the phase of any motion loses all its digits.
MAX_T_END = 1e12
#: Most rotation (|omega0| t_end, rad) a stepping method is asked to follow: ~1.6e7 turns, hours
#: of DOP853; the exact solution has no such limit.
MAX_ROTATION = 1e8
#: Most steps a fixed-step method is asked to take.
MAX_STEPS = 1e8


def simulate(
    body,
    omega0,
    *,
    t_end: float,
    samples: int = 500,
    method: str | None = None,
    frame: str = "principal",
    torque=None,
    rtol: float | None = None,
    atol: float | None = None,
    attitude0=None,
    step: float | None = None,
) -> Trajectory:
    """Integrate the rotation of a rigid body from an initial angular velocity.

    Parameters
    ----------
    body : Body or MassProperties
        The body; its principal frame (``I1 <= I2 <= I3``) is the body frame of the motion.
    omega0 : array_like, shape (3,)
        Initial angular velocity, rad/s, in ``frame``.
    t_end : float
        Duration, s. Samples are taken at ``samples`` equally spaced times in ``[0, t_end]``.
    samples : int
        Number of samples (>= 2), default 500 as in the seed study.
    method : str, optional
        A name from :data:`tumble.dynamics.METHODS`: ``"exact"``, ``"dop853"``, ``"rk45"``,
        ``"seed"``, ``"geometric"`` (``2``, ``6``). Default ``"exact"`` without torque,
        ``"dop853"`` with one.
    frame : {"principal", "design"}
        Frame of ``omega0``: the principal frame (axes ordered I1 <= I2 <= I3) or the body's
        design frame. A body-frame torque is read in the same frame.
    torque : callable or torque model, optional
        ``tau(t, omega, attitude)`` in N m (see :mod:`tumble.dynamics.torques`).
    rtol, atol : float, optional
        Tolerances; the method's defaults if not given. For ``"dop853"`` ``atol`` is relative
        to the size of omega.
    attitude0 : scipy Rotation, quaternion or matrix, optional
        Initial rotation of the *design* frame to the world frame; default identity (the body
        starts as it was designed).
    step : float, optional
        Largest step of the fixed-step ``"geometric"`` methods, s (default: at most 0.05 rad
        of rotation per step); ignored by the others.

    Returns
    -------
    Trajectory

    Raises
    ------
    ValueError
        For bad input, naming the argument and what is allowed.
    """
    props, spec, w0, t_end, rtol, atol, step, model = check_inputs(
        body, omega0, t_end=t_end, samples=samples, method=method, frame=frame, rtol=rtol, atol=atol,
        step=step, torque=torque,
    )
    name = body.name if isinstance(body, Body) else "body"

    A = props.principal_axes  # principal -> design
    if frame == "design":
        w0 = A.T @ w0
        if model is not None and model.frame == "body":
            model = _design_torque(model, A)
    design_to_world = Rotation.identity() if attitude0 is None else Rotation.from_quat(check_rotation("attitude0", attitude0))
    q0 = (design_to_world * Rotation.from_matrix(A)).as_quat()

    moments = props.principal_moments
    if spec.atol_scaled and atol is not None:
        scale = max(float(np.linalg.norm(w0)), _torque_scale(model, w0, q0, moments, t_end), 1e-300)
        atol = np.array([atol * scale] * 3 + [atol] * 4)
    t = np.linspace(0.0, t_end, samples)
    omega, quat = spec.integrate(moments, w0, q0, t, model, rtol, atol, step)
    if not (np.all(np.isfinite(omega)) and np.all(np.isfinite(quat))):
        raise RuntimeError(f"the {spec.name} integration produced non-finite values")
    return Trajectory(
        t=t, omega=omega, attitude=Rotation.from_quat(quat), moments=moments, principal_axes=A,
        method=spec.name, torque_free=model is None, body_name=name,
    )


def check_inputs(body, omega0, *, t_end, samples, method, frame, rtol=None, atol=None, step=None, torque=None):
    """Validate :func:`simulate`'s arguments (scenario files use it too, before anything runs).

    Returns ``(props, method, omega0, t_end, rtol, atol, step, torque model)`` with the
    defaults filled in: the method is ``"exact"`` without a torque, ``"dop853"`` with one.

    Raises ``ValueError`` whose message starts with the argument's name.
    """
    props = body.properties if isinstance(body, Body) else body
    if not isinstance(props, MassProperties):
        raise ValueError(f"body = {body!r} must be a tumble Body or MassProperties")
    model = as_torque(torque)
    if method is None:
        method = DEFAULT_METHOD if model is None else DEFAULT_TORQUE_METHOD
    spec = get_method(method)
    if model is not None and not spec.supports_torque:
        allowed = ", ".join(m for m, s in METHODS.items() if s.supports_torque)
        raise ValueError(f"method = {spec.name!r} cannot take a torque; use one of: {allowed}")
    if frame not in FRAMES:
        raise ValueError(f"frame = {frame!r} is not allowed; allowed: {', '.join(FRAMES)}")
    w0 = np.array(check_vector("omega0", omega0, "rad/s"))
    t_end = check_positive("t_end", t_end, "s")
    if t_end > MAX_T_END:
        raise ValueError(f"t_end = {t_end!r} must be at most {MAX_T_END:g} s")
    if isinstance(samples, bool) or not isinstance(samples, numbers.Integral) or not 2 <= samples <= MAX_SAMPLES:
        raise ValueError(f"samples = {samples!r} must be a whole number from 2 to {MAX_SAMPLES}")
    rtol = spec.rtol if rtol is None else check_positive("rtol", rtol, "relative")
    atol = spec.atol if atol is None else check_positive("atol", atol, "rad/s")
    step = None if step is None else check_positive("step", step, "s")
    moments = props.principal_moments
    with np.errstate(over="ignore", invalid="ignore"):
        energy = 0.5 * float(np.sum(moments * w0 * w0))
        momentum = float(np.linalg.norm(moments * w0))
        spin = float(np.linalg.norm(w0))
    if not (np.isfinite(energy) and np.isfinite(momentum) and np.isfinite(spin)):
        raise ValueError(f"omega0 = {w0.tolist()} rad/s is too large: the kinetic energy of this body overflows")
    if step is not None and spec.fixed_step and t_end / step > MAX_STEPS:
        raise ValueError(f"step = {step!r} s makes {t_end / step:.3g} steps of a {t_end:g} s run; at most {MAX_STEPS:g}")
    turns = spin * t_end
    if spec.name != "exact" and turns > MAX_ROTATION:
        raise ValueError(
            f"t_end = {t_end!r} s at |omega0| = {spin:.6g} rad/s is {turns:.3g} rad of rotation, "
            f"more than method {spec.name!r} follows (at most {MAX_ROTATION:g} rad); use method 'exact' or a shorter run"
        )
    if np.any(moments <= 0):
        raise ValueError(
            f"principal moments {moments.tolist()} kg m^2: a body with a zero moment (a thin rod, "
            f"a point) has no well-posed rotation about that axis; give it some thickness"
        )
    return props, spec, w0, t_end, rtol, atol, step, model


def _design_torque(model, A):
    """Wrap a body-frame torque given in design coordinates so it returns principal ones."""
    from .torques import FunctionTorque

    return FunctionTorque(lambda t, w, att: A.T @ np.asarray(model(t, A @ w, att), float), "body")


def _torque_scale(model, w0, q0, moments, t_end) -> float:
    """Size of omega a torque can build up over the run, rad/s (for absolute tolerances)."""
    if model is None:
        return 0.0
    tau = body_torque(model, 0.0, w0, Rotation.from_quat(q0))  # checks the model's answer
    return float(np.linalg.norm(tau) / moments.min() * t_end)

