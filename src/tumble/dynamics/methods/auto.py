"""``method="auto"``, the default of :func:`tumble.simulate`: the method chosen from what a run has.

- A rigid body without torque: ``"exact"``, the closed form (no steps, round-off accuracy).
- Rotors whose spin changes, a stiff damper, or a torque that is a Python function: ``"dop853"``,
  the one method that takes them all (scipy's DOP853, Radau for a stiff damper).
- A damper that is not stiff, under the built-in torque models: the engine's ``"rk8"``
  (:func:`damped_step`; the engine's ``dop853`` has no damper, scipy's costs a Python call a stage).
- The built-in torque models that have a compiled form
  (:class:`~tumble.dynamics.models.torques.KernelForm`), with or without rotors at constant spin:
  the compiled engine, either its adaptive ``"dop853"`` or its fixed-step ``"rk8"``
  (:func:`engine_choice`). The gravity gradient along an ellipse or a TLE's orbit and a residual
  dipole: the same choice on the closed loop's kernel (:mod:`~tumble.dynamics.control.free_loop`).

Both engine methods take the same 12-stage 8th-order steps (DOP853's weights); ``dop853`` chooses
each step by its error estimate and writes the samples from its dense output, ``rk8`` takes equal
steps and must land on every sample. ``dop853``'s steps are longer at the same accuracy but cost
twice as much; so ``rk8`` is the cheaper where the samples are far apart next to the step the
tolerance allows (a fast spin), ``dop853`` where they are close (a slow one) or where the spin
changes over the run. The rule and its constants come from the measurements
in docs/methods.md ("The default: auto"): errors against scipy's DOP853 at rtol 1e-13 and times
of both on the four one-body cases of ``benchmarks/bench_engine.py`` (20 s and 200 s, 101 to 2,000
samples).

Accuracy asked: ``rtol`` (default :data:`AUTO_RTOL`) in omega, relative to the largest |omega|,
and in attitude, relative to the angle turned (rad per rad, absolute for a run that turns less
than a radian). A motion that amplifies errors (near the separatrix of the tennis-racket flip,
over many flips) can lose more than any method's tolerance says; no method promises it there.
"""

from __future__ import annotations

import math

import numpy as np

from ...typing import FloatArray
from ..engine.stepsize import RTOL_RANGE
from ..models.internal import STIFF_RATIO, InternalModel

__all__ = ["AUTO_RTOL", "DOP853_SAFETY", "RK4_ANGLE", "RK_ANGLES", "RK_LOWEST_RTOL", "damped_step", "dop853_tolerances",
           "engine_choice", "rk_angle", "rk_step", "rk8_angle"]

#: The relative tolerance of an ``"auto"`` run when none is given.
AUTO_RTOL = 1e-10
#: ``dop853``'s tolerances under ``"auto"`` are the ones asked for over this factor at rtol 1e-10,
#: times ``(rtol / 1e-10) ** (1/4)`` above it (its global error grows faster than its tolerance)
#: and ``(1e-10 / rtol) ** (1/2)`` below it (round-off grows its global error past the tolerance),
#: and its ``atol`` 10 times tighter again: its local error control at rtol 1e-10 left 2.5e-9 in
#: omega on the T-handle at 10 rad/s (20 s, 214 rad turned), at rtol 3.3e-12 and atol 3.3e-13
#: 5.2e-11 (2026-12-03); at rtol 3.3e-8 2.3e-6, at 3.3e-10 1.0e-8 (measured against scipy's DOP853 at rtol
#: 1e-13). Below 1e-10 the same quarter power left 1.5 rtol in omega at rtol 1e-11 on the
#: T-handle under a constant torque (101 and 500 samples), the square root 0.43-0.49 rtol
#: (measured 2026-12-03 against scipy's DOP853 at rtol 1e-13, atol 1e-14 on Euler's equations
#: alone; against tests/test_simulate_auto.py's, atol 1e-16 with the quaternion, the quarter power
#: left 0.19-0.22 rtol: at 1e-11 the references differ by about that much).
DOP853_SAFETY = 30.0
#: ``rk8``'s rotation per step (rad) at rtol 1e-10, at the fastest spin the run can reach: on the
#: T-handle at 10 rad/s 0.3 rad left 2.4e-9 in omega, 0.2 rad 4.4e-11, 0.15 rad 4.5e-12 (measured;
#: errors go as the step to the 8th power and more near the flip). Scaled as ``rtol ** (1/8)``.
RK8_ANGLE = 0.15
#: ``dop853``'s rotation per step (rad) at rtol 1e-10 / :data:`DOP853_SAFETY` (scaled as ``rtol **
#: (1/8)``): scipy's DOP853
#: took 733 steps over the T-handle's 214 rad (measured; the engine takes scipy's steps).
DOP853_ANGLE = 0.29
#: A ``dop853`` step of the engine costs this many ``rk8`` steps (its error estimate and step
#: control): the T-handle's 733 steps took 178 us, ``rk8``'s 733 steps 85 us (measured, 2 samples).
DOP853_STEP_COST = 2.1
#: What writing the samples costs ``dop853``, in ``rk8`` steps: the dense output's 3 more stages of
#: 12 in each step that holds a sample, and ~0.2 of a step for each sample (measured: 500 samples
#: instead of 2 added 72 us to the T-handle's run, 12 us to the spacecraft's 42 steps).
DENSE_STAGES, SAMPLE_COST = 0.25, 0.2


#: ``rk4``'s rotation per step (rad) at rtol 1e-10, at the fastest spin the run can reach: on the
#: T-handle at 10 rad/s under a small constant torque 0.03 rad left 2.6e-7, 0.01 rad 2.9e-9 (omega and
#: attitude, measured against scipy's DOP853 at rtol 1e-13; the error goes as the step to the 4th
#: power), so 0.004 rad ~1e-10; the spacecraft at 1 rad/s 0.01 rad 6.8e-11. Scaled as ``rtol ** (1/4)``.
RK4_ANGLE = 0.004
#: Each fixed-step engine method's angle at rtol 1e-10, its order and the range of its angle (rad).
RK_ANGLES = {"rk4": (RK4_ANGLE, 4, 5e-4, 0.2), "rk8": (RK8_ANGLE, 8, 0.02, 0.5)}
#: The smallest rtol each meets by its step: below it the round-off of its many short steps wins
#: (measured against scipy's DOP853 at rtol 1e-13: rk4 at rtol 1e-11 left 1.9e-11 on a spacecraft at
#: 10 rad/s in the gravity gradient, at 3e-11 2.7e-12; rk8 at 1e-13 6.4e-13, at 1e-12 8.1e-13). The
#: round-off depends on the processor: on an AMD EPYC (2026-12-02) the same rk8 run at rtol 1e-12 left
#: 2.7e-12, at 1e-11 1.9e-12, at 1e-10 7.6e-13, and shorter steps more (step 1 ms 7.2e-12), the
#: reference itself within ~1.4e-12 there (the engine's dop853 at rtol 1e-13 against it): so rk8's
#: lowest is 1e-11, which both met with a margin.
RK_LOWEST_RTOL = {"rk4": 3e-11, "rk8": 1e-11}


def rk_angle(name: str, rtol: float) -> float:
    """The rotation per step (rad) at which the engine's fixed-step ``name`` (``"rk4"``, ``"rk8"``)
    meets ``rtol``: its angle at :data:`AUTO_RTOL` (:data:`RK4_ANGLE`, :data:`RK8_ANGLE`) scaled as
    ``rtol`` to the inverse of its order, within its range (:data:`RK_ANGLES`).

    Examples
    --------
    >>> from tumble.dynamics.methods.auto import rk_angle
    >>> rk_angle("rk8", 1e-10), rk_angle("rk4", 1e-10), round(rk_angle("rk4", 1e-6), 4)
    (0.15, 0.004, 0.04)
    """
    angle, order, low, high = RK_ANGLES[name]
    return min(high, max(low, angle * math.pow(rtol / AUTO_RTOL, 1.0 / order)))


def rk_step(name: str, rtol: float, top: float, internal: InternalModel | None = None, *,
            asked: bool = False) -> float | None:
    """The step (s) at which the engine's fixed-step ``name`` meets ``rtol``: :func:`rk_angle` of
    rotation at the fastest spin the run can reach, ``top`` (rad/s), or of relaxation at the
    damper's fastest rate (1/s), whichever is the shorter step; None for a body that does not turn.
    ``asked``: the user named the method and the rtol, which is refused below what the method meets
    (:data:`RK_LOWEST_RTOL`).

    Examples
    --------
    >>> from tumble.dynamics.methods.auto import rk_step
    >>> rk_step("rk8", 1e-10, 10.0), rk_step("rk4", 1e-10, 10.0), rk_step("rk8", 1e-10, 0.0)
    (0.015, 0.0004, None)
    >>> rk_step("rk4", 1e-12, 10.0, asked=True)
    Traceback (most recent call last):
    ...
    ValueError: rtol = 1e-12 is below what rk4's fixed steps meet (3e-11: below it the round-off of its many short steps wins); use method dop853 or a larger rtol
    """
    if asked and rtol < RK_LOWEST_RTOL[name]:
        raise ValueError(f"rtol = {rtol!r} is below what {name}'s fixed steps meet ({RK_LOWEST_RTOL[name]:g}: below it "
                         "the round-off of its many short steps wins); use method dop853 or a larger rtol")
    top = max(top, internal.relaxation_rate if internal is not None else 0.0)
    return rk_angle(name, rtol) / top if top > 0.0 and math.isfinite(top) else None


def rk8_angle(rtol: float) -> float:
    """``rk8``'s rotation per step (rad) meeting ``rtol``: :data:`RK8_ANGLE` at :data:`AUTO_RTOL`,
    as ``rtol ** (1/8)`` elsewhere, within 0.02 to 0.5 rad.

    Examples
    --------
    >>> from tumble.dynamics.methods.auto import rk8_angle
    >>> rk8_angle(1e-10), round(rk8_angle(1e-6), 3)
    (0.15, 0.474)
    """
    return rk_angle("rk8", rtol)


def dop853_tolerances(rtol: float, atol: float) -> tuple[float, float]:
    """The tolerances ``"auto"`` runs ``dop853`` at to meet ``rtol`` (:data:`DOP853_SAFETY`); ``atol``
    relative to the spin, as ``dop853``'s own.

    Examples
    --------
    >>> from tumble.dynamics.methods.auto import dop853_tolerances
    >>> [f"{x:.2g}" for x in dop853_tolerances(1e-10, 1e-10)], [f"{x:.2g}" for x in dop853_tolerances(1e-6, 1e-6)]
    (['3.3e-12', '3.3e-13'], ['3.3e-09', '3.3e-10'])
    >>> [f"{x:.2g}" for x in dop853_tolerances(1e-11, 1e-11)]   # below 1e-10: 30 sqrt(10) tighter
    ['1.1e-13', '1.1e-14']
    """
    ratio = rtol / AUTO_RTOL
    factor = DOP853_SAFETY * (math.pow(ratio, 0.25) if ratio >= 1.0 else math.pow(ratio, -0.5))
    return max(rtol / factor, RTOL_RANGE[0]), atol / factor / 10.0


def engine_choice(t: FloatArray, spin: float, gain: float, rtol: float,
                  internal: InternalModel | None = None) -> float | None:
    """The engine's method for a run: ``rk8``'s step (s), or None for ``dop853``.

    ``dop853`` below :data:`RK_LOWEST_RTOL` (what ``rk8`` refuses when asked for by name). With a damper (``internal``), :func:`damped_step`: ``dop853`` would run it in scipy.

    The cost of each in ``rk8`` steps, the cheaper chosen: ``rk8`` steps at :func:`rk8_angle` of
    rotation at the fastest spin the run can reach, ``spin + gain`` (rad/s), in equal steps within
    each sample interval (at least one); ``dop853`` takes :data:`DOP853_ANGLE` steps over the
    rotation, ``(spin + gain / 2) t_end`` (the bound ``simulate`` refuses long runs by), each
    :data:`DOP853_STEP_COST`, and writes the samples (:data:`DENSE_STAGES`, :data:`SAMPLE_COST`).

    Parameters
    ----------
    t : ndarray, shape (n,)
        The sample times, s, from 0.
    spin, gain : float
        The spin the run starts from and the bound on what its torque adds, rad/s.
    rtol : float
        The accuracy asked for.
    internal : InternalModel, optional
        The body's rotors (at constant spin) and damper.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.auto import engine_choice
    >>> engine_choice(np.linspace(0.0, 20.0, 101), 10.0, 0.0, 1e-10)   # 10 rad/s, samples 0.2 s apart: rk8
    0.015
    >>> engine_choice(np.linspace(0.0, 20.0, 500), 1.0, 0.0, 1e-10) is None   # 1 rad/s, 0.04 s apart: dop853
    True
    >>> engine_choice(np.linspace(0.0, 20.0, 101), 10.0, 0.0, 1e-12) is None   # below rk8's lowest rtol: dop853
    True
    """
    top = spin + gain
    t_end = float(t[-1])
    if rtol < RK_LOWEST_RTOL["rk8"]:  # below what rk8's steps meet (the rtol it refuses when asked by name)
        return None
    if internal is not None and internal.damper is not None:
        return damped_step(internal, spin, gain, t_end, rtol)
    if not (top > 0.0 and t_end > 0.0 and math.isfinite(top)):
        return None
    scale = math.pow(dop853_tolerances(rtol, rtol)[0] * DOP853_SAFETY / AUTO_RTOL, 0.125)  # its step, as its rtol
    h = rk8_angle(rtol) / top
    shrink = (1.0 - 1e-12) / h  # equal steps in each interval, at least one: Python's floats for a few
    if len(t) <= 32:
        times = t.tolist()
        rk8 = float(sum(max(1, math.ceil((b - a) * shrink)) for a, b in zip(times, times[1:])))
    else:
        rk8 = float(np.maximum(1.0, np.ceil(np.diff(t) * shrink)).sum())
    steps = max(1.0, (spin + 0.5 * gain) * t_end / (DOP853_ANGLE * scale))
    samples = len(t) - 1
    dop853 = DOP853_STEP_COST * steps * (1.0 + DENSE_STAGES * min(1.0, samples / steps)) + SAMPLE_COST * samples
    return h if rk8 <= dop853 else None


def damped_step(internal: InternalModel, spin: float, gain: float, t_end: float, rtol: float) -> float | None:
    """``rk8``'s step (s) for a body with a damper, or None where the damper is stiff
    (:data:`~tumble.dynamics.models.internal.STIFF_RATIO`: ``dop853`` hands it to Radau): :func:`rk8_angle`
    of rotation at the fastest spin the run can reach, ``spin + gain`` (rad/s), or of relaxation at the
    damper's fastest rate (1/s), whichever is the shorter step.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.dynamics.methods.auto import damped_step
    >>> from tumble.dynamics.models.internal import InternalModel
    >>> slow = InternalModel(np.array([1.0, 2.0, 3.0]), damper=tumble.SphericalDamper(inertia=0.1, damping=0.05))
    >>> damped_step(slow, 10.0, 0.0, 20.0, 1e-10)   # relaxing at ~0.55 1/s: the spin sets the step
    0.015
    >>> stiff = InternalModel(np.array([1.0, 2.0, 3.0]), damper=tumble.SphericalDamper(inertia=0.1, damping=1e3))
    >>> damped_step(stiff, 10.0, 0.0, 20.0, 1e-10) is None
    True
    """
    ratio, _ = internal.stiffness(spin + gain, t_end)
    if ratio > STIFF_RATIO:
        return None
    return rk_step("rk8", rtol, spin + gain, internal)
