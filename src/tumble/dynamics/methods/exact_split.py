"""Exact-flow splitting: the free rigid body advanced exactly, a torque entering as kicks.

Celledoni, Fasso, Safstrom & Zanna, "The exact computation of the free rigid body motion and its
use in splitting methods", SIAM J. Sci. Comput. 30 (2008) 2084, sec. 5: split the motion under a
torque into the torque-free motion, advanced by its closed form
(:mod:`tumble.dynamics.methods.exact_kernel`: Jacobi elliptic functions and Legendre's integral of
the third kind, exact to round-off at any step), and the kick ``L <- L + d tau`` with the attitude
held. The symmetric (Strang) step

    kick(h/2) . free(h) . kick(h/2)

is second order; Yoshida's compositions of it (Phys. Lett. A 150 (1990) 262, the coefficients
:data:`tumble.dynamics.methods.geometric.COMPOSITIONS`) give orders 4 and 6; their negative
sub-steps run the free flow backwards, which the closed form does exactly. As for the geometric
methods, the order holds for torques that depend on time and attitude (constant body or world
torques, gravity gradient); a torque that depends on omega gets kicks that are Euler steps.

Why it pays: the free motion costs it no error, so its error is proportional to the torque
(``O(h^2 |tau|)`` for Strang), where the geometric splitting's is not: on the seed's T-handle
spun near its major axis under a weak body torque (|tau| / I3 ~ 4e-4 rad/s^2 against |omega|^2 ~
100 rad/s^2) the 6th-order composition reaches 4e-11 at a step of 0.1 s, where ``geometric6``
needs 0.005 s for 1e-9 (``benchmarks/bench_exact_split.py``, the work-precision figure). The
step must still resolve how fast the torque changes along the motion (a torque fixed in a body
spinning at 10 rad/s turns with it), and near the separatrix every method's error is amplified
by the flip's sensitivity to the invariants. Without a torque the step is the sample interval
and the run is the closed form.

Two free flows: under a built-in torque (constant in the body or the world, gravity gradient)
the whole run is compiled, with the free flow in double precision
(:mod:`tumble.dynamics.methods.compiled_flow`, ~1 us a step); a user's torque function keeps the
double-double kernel (:mod:`tumble.dynamics.methods.exact_kernel`) called from Python, ~1.3 ms
a step for one body. The two agree to ~5e-14 (tests/test_compiled.py).

What it keeps: each free flow keeps the energy, ``|L|`` and ``L_world`` to round-off, each kick
changes ``L_world`` by exactly ``d R tau`` (the impulse), so the momentum budget
``L_world(t) - L_world(0) = integral R tau dt`` is kept to the order of the method.

Rotors and dampers are not taken: with internal momentum the free part is a gyrostat, whose
closed form (Volterra; Wittenburg, *Dynamics of Multibody Systems*, sec. 4.2) is not
implemented, and a damper's relaxation is not a kick; the ``"geometric"`` methods take both.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray
from ..engine.stepsize import equal_steps
from ..models.torques import TorqueModel, body_torque
from .bounds import spin_gain
from . import geometric
from .compiled import compiled_model, run_split
from .exact_batch import free_rotation_batch

__all__ = ["default_step", "propagate"]


def default_step(spin: float, gain: float = 0.0, rate: float = 0.0) -> float:
    """The default largest step, s: without a torque (``gain = 0``) the sample interval
    (``inf``: the free flow is exact at any step); with one, that of the geometric methods
    (:func:`tumble.dynamics.methods.geometric.default_step`: 0.05 rad of rotation at
    ``spin + gain``, rad/s), which is safe; a weak torque allows far longer steps, which a
    caller asks for with ``step``.

    Examples
    --------
    >>> from tumble.dynamics.methods.exact_split import default_step
    >>> default_step(10.0), default_step(10.0, gain=1.0)
    (inf, 0.004545454545454546)
    """
    if gain == 0.0 and rate == 0.0:
        return math.inf
    return geometric.default_step(spin, gain, rate)


def propagate(moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *, order: int = 4,
              step: float | None = None, torque: TorqueModel | None = None,
              compiled: bool = True) -> tuple[FloatArray, FloatArray]:
    """Integrate N bodies by exact-flow splitting, sampled at times ``t``.

    Parameters
    ----------
    moments, omega0, quat0 : array_like
        Principal moments (ascending, kg m^2), angular velocity at ``t[0]`` (principal frame,
        rad/s) and attitude (body to world, scalar last) of N bodies, shapes (N, 3), (N, 3),
        (N, 4), or of one body, (3,), (3,), (4,): the arguments of
        :func:`tumble.dynamics.methods.geometric.propagate`.
    t : array_like, shape (n,)
        Sample times, s, increasing.
    order : {2, 4, 6}
        Order of the composition.
    step : float, optional
        Largest step, s (default :func:`default_step`); each sample interval is cut into equal
        steps no longer than this.
    torque : torque model, optional
        ``tau(t, omega, attitude)`` (:mod:`tumble.dynamics.models.torques`), called with arrays
        of N bodies; shape (3,) or (N, 3).
    compiled : bool
        Run a built-in torque (constant in the body or the world, gravity gradient) with the
        compiled double-precision free flow (:mod:`tumble.dynamics.methods.compiled_flow`), the
        default; False (or any other torque, or no torque and no step) keeps the double-double
        kernel called from Python, the reference the tests compare with.

    Returns
    -------
    omega : ndarray, shape (n, N, 3)
        rad/s, principal frame.
    quat : ndarray, shape (n, N, 4)
        Body to world, scalar last.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.torques import ConstantTorque
    >>> from tumble.dynamics.methods.exact_split import propagate
    >>> t = np.linspace(0.0, 2.0, 3)
    >>> omega, quat = propagate([1.0, 2.0, 3.0], [0.1, 1.0, 0.1], [0.0, 0.0, 0.0, 1.0], t,
    ...                         order=4, step=0.1, torque=ConstantTorque([0.0, 0.0, 0.01]))
    >>> omega.shape, quat.shape
    ((3, 1, 3), (3, 1, 4))
    """
    I, w, q = (np.atleast_2d(np.asarray(a, float)) for a in (moments, omega0, quat0))
    N = max(len(I), len(w), len(q))
    I, w, q = (np.broadcast_to(a, (N, a.shape[1])).copy() for a in (I, w, q))
    t = np.asarray(t, float)
    geometric._check_batch(I, I * w, q, t, step)
    if np.any(np.diff(I, axis=1) < 0):  # the closed form's case analysis needs them ordered
        i = int(np.flatnonzero(np.any(np.diff(I, axis=1) < 0, axis=1))[0])
        raise ValueError(f"moments[{i}] = {I[i].tolist()} must be ascending, I1 <= I2 <= I3 (kg m^2): principal "
                         "moments for the exact free flow")
    if order not in geometric.COMPOSITIONS:
        allowed = ", ".join(map(str, geometric.COMPOSITIONS))
        raise ValueError(f"order = {order!r} is not available; allowed: {allowed}")
    if step is None:
        spin = float(np.max(np.linalg.norm(w, axis=1), initial=0.0))
        gain = spin_gain(torque, t[0], w, Rotation.from_quat(q), I, t[-1] - t[0]) if torque is not None else 0.0
        step = default_step(spin, gain)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    builtin = compiled_model(torque) if torque is not None else None
    if compiled and (torque is None or builtin is not None) and math.isfinite(step):
        return run_split(I, I * w, q, t, step, geometric.COMPOSITIONS[order], builtin, exact=True)
    L = I * w
    omega_out, quat_out = np.empty((len(t), len(I), 3)), np.empty((len(t), len(I), 4))
    omega_out[0], quat_out[0] = w, q

    def kick(model: TorqueModel, time: float, d: float) -> None:
        L[:] += d * body_torque(model, time, L / I, Rotation.from_quat(q))

    for s in range(1, len(t)):
        n_steps, h = equal_steps(t[s] - t[s - 1], step)
        for m in range(n_steps):
            tc = t[s - 1] + m * h
            for gamma in geometric.COMPOSITIONS[order]:
                hg = gamma * h
                if torque is not None:
                    kick(torque, tc, 0.5 * hg)
                omega, quat = free_rotation_batch(I, L / I, q, np.array([hg]))
                L[:], q[:] = I * omega[:, 0], quat[:, 0]
                tc += hg
                if torque is not None:
                    kick(torque, tc, 0.5 * hg)
        q /= np.linalg.norm(q, axis=1, keepdims=True)
        omega_out[s], quat_out[s] = L / I, q
    return omega_out, quat_out
