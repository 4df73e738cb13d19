"""Structure-preserving fixed-step integrators: splitting of the free rigid body.

The free rigid body's Hamiltonian ``H = L1^2/(2 I1) + L2^2/(2 I2) + L3^2/(2 I3)`` splits into
three terms whose flows are exact rotations (McLachlan, Nonlinearity 6 (1993) 585; Touma &
Wisdom, Astron. J. 107 (1994) 1189; Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107
(1997) 5840): under ``H_i`` the body-frame momentum turns about ``e_i`` by ``-a`` and the
attitude by ``+a``, ``a = tau L_i / I_i``, so ``R L`` is untouched. Every sub-step is a
rotation, hence

- |L| is kept to round-off and ``L_world = R L`` too (each sub-step leaves it unchanged),
- the map is symplectic and time-reversible, so the energy error stays bounded (no drift) over
  very long runs (Hairer, Lubich & Wanner, *Geometric Numerical Integration*, ch. VII.5, IX).

Methods: ``S2``, the symmetric (Strang) composition
``phi_1(h/2) phi_2(h/2) phi_3(h) phi_2(h/2) phi_1(h/2)``, second order; and Yoshida's
compositions of it (Phys. Lett. A 150 (1990) 262): 4th order (triple jump) and 6th order
(his solution A, 7 stages). A torque enters as two half kicks around the free flow,
``L += (h/2) tau``, inside the composed step (Celledoni et al. 2008, sec. 5), which keeps the
order of the composition for torques that depend on time and attitude only.

Everything is vectorised over a leading batch axis: N bodies in one call (``(N, 3)`` arrays),
so a sweep of 10,000 bodies costs little more than one. Written by hand because no library
offers a Lie-group splitting integrator for rigid bodies on numpy arrays.

Rotors and the spherical damper (:mod:`tumble.dynamics.models.internal`, :func:`propagate_internal`).
With the total momentum ``L = I w + h + J w_d`` the conservative part of the motion is
``L' = L x w``, ``w_d' = w_d x w`` (the sphere's momentum is fixed in space), with
``w = I^-1 (L - h - J w_d)``. It splits the same way: ``H_i = (L_i - h_i - J w_d,i)^2 / (2 I_i)``
turns L, ``w_d`` and the attitude about ``e_i`` at the rate ``(L_i - h_i - J w_d,i) / I_i``,
which that flow leaves constant, so each sub-flow is again an exact rotation and keeps
``R L`` to round-off. A time-varying ``h(t)`` makes the Hamiltonian depend on time: with the
time as an extra coordinate, the symmetric step "advance t by h/2, rotate with h frozen, advance
t by h/2" evaluates ``h`` at the middle of each Strang stage and keeps the composition's order.
The damper's coupling alone (L and attitude fixed) is linear and separable,
``w_d,i' = -k_i (w_d,i - w_inf,i)``, and is solved exactly with its dissipated energy
(:meth:`~tumble.dynamics.models.internal.SphericalDamper.relax`); it enters like the torque, as two
half steps around the rotations, and so does the integral ``integral h'.w dt`` of the motors'
work. Each piece is exact (or symmetric) and the step is their symmetric (Strang) composition,
composed again by Yoshida's coefficients; the order is measured in ``tests/test_gyrostat.py``
and ``tests/test_damper.py``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, FloatOrArray
from ...validation import check_increasing, short_repr
from ..engine.stepsize import equal_steps
from ..models.internal import InternalModel, InternalSamples, Rotors
from ..models.torques import TorqueModel, body_torque
from .bounds import spin_gain
from .compiled import compiled_model, run_split

__all__ = ["COMPOSITIONS", "MAX_STEP_ANGLE", "default_step", "free_flow_substeps", "propagate", "propagate_internal"]

#: Largest rotation per step, rad, of the default step. Measured on the seed's 20 s flip run
#: (|omega| = 10 rad/s) against the exact solution: omega errors of 3e-5 (4th order), 1e-9
#: (6th order) and 5e-3 (2nd order) relative to |omega|; pass ``step`` for more.
MAX_STEP_ANGLE = 0.05


def default_step(spin: float, gain: float = 0.0, rate: float = 0.0) -> float:
    """The default largest step, s: ``MAX_STEP_ANGLE`` of rotation at the fastest spin the run
    can reach, ``spin + gain`` (rad/s), where ``gain`` bounds what a torque adds over the run
    (``|tau| t_end / I1`` for a constant torque), and as fine against a damper's relaxation
    ``rate`` (1/s, :meth:`~tumble.dynamics.models.internal.SphericalDamper.rates`). ``inf`` for a body
    at rest without torque or damper.

    A torque that grows during the run (a function of time or state) is estimated from its
    value at the start: give such a run an explicit ``step``.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.methods.geometric import MAX_STEP_ANGLE, default_step
    >>> default_step(10.0) == MAX_STEP_ANGLE / 10.0, default_step(8.0, gain=2.0) == default_step(10.0)
    (True, True)
    >>> default_step(1.0, rate=5.0) == MAX_STEP_ANGLE / 5.0, default_step(0.0)   # a damper; a body at rest
    (True, inf)
    """
    top = max(spin + gain, rate)
    return MAX_STEP_ANGLE / top if top > 0 else math.inf

_CBRT2 = 2.0 ** (1.0 / 3.0)
_Y4 = (1.0 / (2.0 - _CBRT2), -_CBRT2 / (2.0 - _CBRT2), 1.0 / (2.0 - _CBRT2))
_W6 = (0.784513610477560, 0.235573213359357, -1.17767998417887)  # Yoshida 1990, solution A
_Y6 = (*_W6, 1.0 - 2.0 * sum(_W6), *_W6[::-1])

#: Composition coefficients of the Strang step, by order.
COMPOSITIONS = {2: (1.0,), 4: _Y4, 6: _Y6}

# The Strang step as (axis, fraction of the step): symmetric, so compositions merge the ends.
_STRANG = ((0, 0.5), (1, 0.5), (2, 1.0), (1, 0.5), (0, 0.5))


def free_flow_substeps(order: int) -> list[tuple[int, float]]:
    """The flattened sequence of exact sub-flows ``(axis, fraction of h)`` for one step.

    Examples
    --------
    >>> from tumble.dynamics.methods.geometric import free_flow_substeps
    >>> free_flow_substeps(2)   # Strang: half, half, whole, half, half
    [(0, 0.5), (1, 0.5), (2, 1.0), (1, 0.5), (0, 0.5)]
    >>> steps = free_flow_substeps(4)   # Yoshida's triple jump, the ends merged
    >>> len(steps), [round(sum(f for a, f in steps if a == axis), 12) for axis in range(3)]   # each flow for h in all
    (13, [1.0, 1.0, 1.0])
    """
    seq: list[tuple[int, float]] = []
    for gamma in COMPOSITIONS[order]:
        for axis, frac in _STRANG:
            if seq and seq[-1][0] == axis:
                seq[-1] = (axis, seq[-1][1] + gamma * frac)
            else:
                seq.append((axis, gamma * frac))
    return seq


def _rotate(L: FloatArray, q: FloatArray, axis: int, tau: float, inv_I: FloatArray, h: FloatArray | None = None,
            J: float = 0.0, wd: FloatArray | None = None) -> None:
    """Exact flow of ``H_axis`` for time ``tau``, in place on (3, N) and (4, N) arrays.

    Components are rows (structure of arrays) so every operation runs on contiguous memory.
    With internal momentum ``h`` (rows, frozen) and a damper (``J``, its rates ``wd``, turned
    along with L) the rate is ``(L_axis - h_axis - J wd_axis) / I_axis``.
    """
    j, k = (axis + 1) % 3, (axis + 2) % 3
    free = L[axis]
    if h is not None:
        free = free - h[axis]
    if wd is not None:
        free = free - J * wd[axis]
    half = free * (0.5 * tau * inv_I[axis])  # half the angle a
    ch, sh = np.cos(half), np.sin(half)
    c, s = 1.0 - 2.0 * sh * sh, 2.0 * sh * ch  # cos a, sin a: two transcendental calls, not four
    Lj, Lk = L[j], L[k]
    # body momentum (and the damper's rate) turn by -a about e_axis
    L[j], L[k] = c * Lj + s * Lk, c * Lk - s * Lj
    if wd is not None:
        Wj, Wk = wd[j], wd[k]
        wd[j], wd[k] = c * Wj + s * Wk, c * Wk - s * Wj
    # attitude q <- q (x) (sin(a/2) e_axis, cos(a/2)), Hamilton product, scalar last
    qa, qj, qk, qw = q[axis], q[j], q[k], q[3]
    q[axis], q[j], q[k], q[3] = ch * qa + sh * qw, ch * qj + sh * qk, ch * qk - sh * qj, ch * qw - sh * qa


def _body_torque(torque: TorqueModel, t: float, omega: FloatArray, q: FloatArray) -> FloatArray:
    """Torque on every body in its principal frame, shape (3, N) (rows: components); ``omega``
    and ``q`` are rows too."""
    return body_torque(torque, t, omega.T, Rotation.from_quat(q.T)).T


def propagate(moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *, order: int = 4,
              step: float | None = None, torque: TorqueModel | None = None,
              compiled: bool = True) -> tuple[FloatArray, FloatArray]:
    """Integrate N bodies with the composed splitting, sampled at times ``t``.

    Parameters
    ----------
    moments : array_like, shape (N, 3) or (3,)
        Principal moments, kg m^2.
    omega0 : array_like, shape (N, 3) or (3,)
        Initial angular velocity, principal frame, rad/s.
    quat0 : array_like, shape (N, 4) or (4,)
        Initial attitude quaternions, body to world, scalar last.
    t : array_like, shape (n,)
        Increasing sample times starting at the initial time, s.
    order : {2, 4, 6}
        Order of the composition.
    step : float, optional
        Largest step, s; each sample interval is cut into equal steps no longer than this.
        Default (:func:`default_step`): a sample interval, and no more than 0.05 rad of
        rotation per step at the fastest spin the run can reach, counting what the torque adds.
    torque : torque model, optional
        ``tau(t, omega, attitude)`` (see :mod:`tumble.dynamics.models.torques`); called with arrays of
        N bodies and may return shape (3,) or (N, 3).

    compiled : bool
        Run a built-in torque (constant in the body or the world, gravity gradient) in the
        compiled kernel (:mod:`tumble.dynamics.methods.compiled`), the default; False keeps the
        numpy path, which calls the model from Python at every kick (the reference the tests
        compare with).

    Returns
    -------
    omega : ndarray, shape (n, N, 3)
    quat : ndarray, shape (n, N, 4)

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.methods.exact import FreeRotation
    >>> from tumble.dynamics.methods.geometric import propagate
    >>> I, w0, t = np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1]), np.linspace(0.0, 10.0, 3)
    >>> omega, quat = propagate(I, w0, [0.0, 0.0, 0.0, 1.0], t, order=6)
    >>> omega.shape, quat.shape   # (samples, bodies, 3 or 4)
    ((3, 1, 3), (3, 1, 4))
    >>> exact = FreeRotation(I, w0, Rotation.identity())
    >>> bool(np.allclose(omega[:, 0], exact.omega(t), atol=1e-8))   # the exact solution
    True
    >>> L_world = Rotation.from_quat(quat[:, 0]).apply(I * omega[:, 0])   # kept to round-off by every sub-step
    >>> bool(np.allclose(L_world, I * w0, atol=1e-14))
    True
    """
    I = np.atleast_2d(np.asarray(moments, float))
    L = np.atleast_2d(np.asarray(omega0, float)) * I
    q = np.atleast_2d(np.array(quat0, dtype=float))
    N = max(len(I), len(L), len(q))
    I, L, q = (np.broadcast_to(a, (N, a.shape[1])).copy() for a in (I, L, q))
    t = np.asarray(t, float)
    _check_batch(I, L, q, t, step)
    inv_I = 1.0 / I
    if order not in COMPOSITIONS:
        raise ValueError(f"order = {order!r} is not available; allowed: {', '.join(map(str, COMPOSITIONS))}")
    if step is None:
        spin = float(np.max(np.linalg.norm(L * inv_I, axis=1), initial=0.0))
        gain = spin_gain(torque, t[0], L * inv_I, Rotation.from_quat(q), I, t[-1] - t[0])
        step = default_step(spin, gain)
    q /= np.linalg.norm(q, axis=1, keepdims=True)

    if torque is None:  # every batch size the same arithmetic: a body's run does not depend on its batch
        return _propagate_free(I, L, q, t, free_flow_substeps(order), step)
    builtin = compiled_model(torque)
    if builtin is not None and compiled:  # a built-in torque: the whole run compiled
        return run_split(I, L, q, t, step, COMPOSITIONS[order], builtin)
    run = _propagate_split(I, L, q, t, order, step, torque)
    return run.omega, run.quat


def propagate_internal(model: InternalModel, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *, order: int = 4,
                       step: float | None = None, torque: TorqueModel | None = None,
                       compiled: bool = True) -> InternalSamples:
    """Integrate one body with rotors and/or a damper by the composed splitting.

    Parameters
    ----------
    model : InternalModel
        The body's moments, rotors and damper (:mod:`tumble.dynamics.models.internal`).
    omega0 : array_like, shape (3,)
        Initial angular velocity of the body, principal frame, rad/s (the damper starts with it).
    quat0 : array_like, shape (4,)
        Initial attitude, body to world, scalar last.
    t : array_like, shape (n,)
        Increasing sample times starting at the initial time, s.
    order : {2, 4, 6}
        Order of the composition.
    step : float, optional
        Largest step, s; default :func:`default_step` at the spin bound of
        :meth:`~tumble.dynamics.models.internal.InternalModel.spin_bound`, the torque's gain and the
        damper's relaxation rate.
    torque : torque model, optional
        External torque (see :mod:`tumble.dynamics.models.torques`).
    compiled : bool
        With wheels at constant rates, no damper and a built-in torque, run in the compiled
        kernel (:mod:`tumble.dynamics.methods.compiled`), the default; False keeps the numpy path.

    Returns
    -------
    InternalSamples
        omega (n, 3), quat (n, 4), and the damper's rate, the dissipated energy and the
        integral of ``h'.w`` where the model has them.

    Examples
    --------
    >>> import numpy as np
    >>> import tumble
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.methods.geometric import propagate_internal
    >>> from tumble.dynamics.models.internal import InternalModel, Rotors
    >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(1, 0, 0), spin_rate=300.0)
    >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
    >>> model = InternalModel(body.principal_moments, Rotors.of(body))
    >>> h = model.momentum(0.0)
    >>> run = propagate_internal(model, [0.1, 0.5, 0.2], [0.0, 0.0, 0.0, 1.0], np.linspace(0.0, 20.0, 5))
    >>> L_world = Rotation.from_quat(run.quat).apply(body.principal_moments * run.omega + h)   # I w + h fixed in space
    >>> bool(np.allclose(L_world, L_world[0], atol=1e-13))
    True
    >>> H = 0.5 * np.sum(body.principal_moments * run.omega**2, axis=1)   # the gyrostat's Hamiltonian w.I w / 2
    >>> bool(np.allclose(H, H[0], rtol=1e-6))
    True
    """
    I = np.atleast_2d(np.asarray(model.moments, float))
    w0 = np.atleast_2d(np.asarray(omega0, float))
    q = np.atleast_2d(np.array(quat0, dtype=float))
    t = np.asarray(t, float)
    h0 = model.momentum(t[0])[None]
    L = I * w0 + h0 + model.damper_inertia * w0
    _check_batch(I, L, q, t, step)
    if order not in COMPOSITIONS:
        raise ValueError(f"order = {order!r} is not available; allowed: {', '.join(map(str, COMPOSITIONS))}")
    if step is None:
        gain = spin_gain(torque, t[0], w0, Rotation.from_quat(q), I, t[-1] - t[0])
        step = default_step(model.spin_bound(w0[0], t), gain, model.relaxation_rate)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    constant = model.rotors is None or model.rotors.constant
    if torque is None and model.damper is None and constant:
        omega, quat = _propagate_free(I, L, q, t, free_flow_substeps(order), step, offset=h0)
        return InternalSamples(omega[:, 0], quat[:, 0], None, None, None)
    builtin = compiled_model(torque) if torque is not None else None
    if compiled and builtin is not None and model.damper is None and constant:  # constant wheels, a built-in torque
        omega, quat = run_split(I, L, q, t, step, COMPOSITIONS[order], builtin, offset=h0)
        return InternalSamples(omega[:, 0], quat[:, 0], None, None, None)
    run = _propagate_split(I, L, q, t, order, step, torque, model, w0)
    wd, D, A = (None if a is None else a[:, 0] for a in (run.damper_omega, run.dissipated, run.work_integral))
    return InternalSamples(run.omega[:, 0], run.quat[:, 0], wd, D, A)


def _propagate_split(I: FloatArray, L: FloatArray, q: FloatArray, t: FloatArray, order: int, step: float,
                     torque: TorqueModel | None, model: InternalModel | None = None,
                     wd0: FloatArray | None = None) -> InternalSamples:
    """The composed splitting, all pieces: arrays of N bodies, ``(n, N, ...)`` samples out.

    Each Yoshida stage of length ``g`` from time ``tc`` is the symmetric step: half pieces at
    ``tc`` (motor-work integral, damper relaxation, torque kick), the Strang rotations with
    ``h`` frozen at ``tc + g / 2``, half pieces at ``tc + g`` in the reverse order.
    """
    N = len(I)
    Ib = I.T.copy()
    inv_I = 1.0 / Ib
    L, q = L.T.copy(), q.T.copy()  # rows: components, columns: bodies
    rotors = model is not None and model.rotors is not None
    # model, its rotors, wd0 and the damper's arrays are read only where they are given (casts: for mypy)
    varying = rotors and not cast(Rotors, cast(InternalModel, model).rotors).constant
    damper = None if model is None else model.damper
    track = model is not None and model.tracks_work
    J = 0.0 if damper is None else damper.inertia
    wd = None if damper is None else cast(FloatArray, wd0).T.copy()
    A, D = np.zeros(N), np.zeros(N)

    def h_at(time: float) -> FloatArray | None:
        return cast(InternalModel, model).momentum(time)[:, None] if rotors else None

    def omega(h: FloatArray | None) -> FloatArray:
        free = L if h is None else L - h
        return (free if wd is None else free - J * wd) * inv_I

    def half(tk: float, d: float, first: bool) -> None:
        hk = h_at(tk)
        for piece in ((0, 1, 2) if first else (2, 1, 0)):
            if piece == 0 and track:
                A[:] += d * (cast(InternalModel, model).momentum_rate(tk) @ omega(hk))
            elif piece == 1 and damper is not None:
                cast(FloatArray, wd)[:], lost = damper.relax(L if hk is None else L - hk, cast(FloatArray, wd), Ib, d)
                D[:] += lost
            elif piece == 2 and torque is not None:
                L[:] += d * _body_torque(torque, tk, omega(hk), q)

    n = len(t)
    omega_out, quat_out = np.empty((n, N, 3)), np.empty((n, N, 4))
    wd_out = None if wd is None else np.empty((n, N, 3))
    A_out = np.zeros((n, N)) if track else None
    D_out = np.zeros((n, N)) if damper is not None else None
    omega_out[0], quat_out[0] = omega(h_at(t[0])).T, q.T
    if wd_out is not None:
        wd_out[0] = cast(FloatArray, wd).T
    hm = h_at(t[0])
    for s in range(1, n):
        n_steps, h = equal_steps(t[s] - t[s - 1], step)
        for m in range(n_steps):
            tc = t[s - 1] + m * h
            for gamma in COMPOSITIONS[order]:
                hg = gamma * h
                half(tc, 0.5 * hg, True)
                if varying:
                    hm = h_at(tc + 0.5 * hg)
                for axis, frac in _STRANG:
                    _rotate(L, q, axis, frac * hg, inv_I, hm, J, wd)
                tc += hg
                half(tc, 0.5 * hg, False)
        # renormalise once per sample: the rotations keep |q| = 1 up to round-off growth only
        q /= np.linalg.norm(q, axis=0)
        omega_out[s], quat_out[s] = omega(h_at(t[s])).T, q.T
        if wd_out is not None:
            wd_out[s], cast(FloatArray, D_out)[s] = cast(FloatArray, wd).T, D
        if A_out is not None:
            A_out[s] = A
    return InternalSamples(omega_out, quat_out, wd_out, D_out, A_out)


def _check_batch(I: FloatArray, L: FloatArray, q: FloatArray, t: FloatArray, step: float | None) -> None:
    """Refuse what would give silently wrong numbers (``simulate`` checks its own arguments)."""
    # the arrays' own .all() / .any(): numpy's module functions add ~2 us each, a tenth of this
    if not (np.isfinite(I).all() and (I > 0).all()):
        raise ValueError("moments must be finite and positive (kg m^2)")
    if not (np.isfinite(L).all() and np.isfinite(q).all()):
        raise ValueError("omega0 and quat0 must be finite")
    if ((q * q).sum(axis=1) == 0).any():  # |q| = sqrt of this sum (numpy's norm)
        raise ValueError("quat0 must be unit quaternions [x, y, z, w], not zero")
    if t.ndim != 1 or len(t) < 2 or not np.isfinite(t).all():
        raise ValueError(f"t = {short_repr(t)} must be at least two finite times (s)")
    check_increasing("t", t)
    if step is not None and not (np.isfinite(step) and step > 0):
        raise ValueError(f"step = {step!r} must be a positive finite number (s)")




_NEXT = {0: (1, 2), 1: (2, 0), 2: (0, 1)}


def _propagate_free(I: FloatArray, L: FloatArray, q: FloatArray, t: FloatArray, subflows: list[tuple[int, float]],
                    step: float, offset: FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    """Torque-free: each sub-flow turns the body momentum by ``-a`` and the attitude by ``+a``
    about ``e_axis``, ``a = frac h (L_axis - h_axis) / I_axis``, in place; the attitude is
    renormalised once per sample. ``offset``: a constant internal momentum h, shape (N, 3).

    The same operations for every batch size: one body runs on plain floats (numpy's per-call
    overhead would dominate) with numpy's own ``cos`` and ``sin``, many on rows of bodies, so
    a body's run is bit for bit the same alone or in any batch (tested) and a sweep's rows do
    not depend on its chunks. The momentum's arithmetic is that of the browser's port
    (``tumble/viz/assets/splitting.js``).
    """
    N = len(I)
    offset = np.zeros((N, 3)) if offset is None else np.broadcast_to(offset, (N, 3))
    one = N == 1
    sqrt: Callable[[FloatOrArray], FloatOrArray]
    if one:  # plain floats: numpy's trigonometry on each, every other operation IEEE alike
        def rows(a: FloatArray) -> list[FloatOrArray]:
            return [float(x) for x in a[0]]

        def trig(x: FloatOrArray) -> tuple[FloatOrArray, FloatOrArray]:
            return float(np.cos(x)), float(np.sin(x))

        sqrt = math.sqrt
    else:
        def rows(a: FloatArray) -> list[FloatOrArray]:
            return [a[:, i].copy() for i in range(a.shape[1])]

        def trig(x: FloatOrArray) -> tuple[FloatOrArray, FloatOrArray]:
            return np.cos(x), np.sin(x)

        sqrt = np.sqrt
    inv_I, comps, off, quat = rows(1.0 / I), rows(L), rows(np.asarray(offset, float)), rows(q)

    def sample() -> tuple[FloatArray, FloatArray]:
        omega = [(comps[i] - off[i]) * inv_I[i] for i in range(3)]
        norm = sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3])
        quat[:] = [x / norm for x in quat]
        return np.stack(omega, axis=-1), np.stack(quat, axis=-1)

    omega_out = np.empty((len(t), N, 3))
    quat_out = np.empty((len(t), N, 4))
    omega_out[0], quat_out[0] = (L - offset) * (1.0 / I), q
    for s in range(1, len(t)):
        n, h = equal_steps(t[s] - t[s - 1], step)
        for _ in range(n):
            for axis, frac in subflows:
                j, k = _NEXT[axis]
                a = frac * h * (comps[axis] - off[axis]) * inv_I[axis]
                c, sn = trig(a)
                Lj, Lk = comps[j], comps[k]
                comps[j] = c * Lj + sn * Lk  # body momentum turns by -a about e_axis
                comps[k] = c * Lk - sn * Lj
                ch, sh = trig(0.5 * a)  # attitude q <- q (x) (sin(a/2) e_axis, cos(a/2))
                qa, qj, qk, qw = quat[axis], quat[j], quat[k], quat[3]
                quat[axis], quat[j] = ch * qa + sh * qw, ch * qj + sh * qk
                quat[k], quat[3] = ch * qk - sh * qj, ch * qw - sh * qa
        omega_out[s], quat_out[s] = sample()
    return omega_out, quat_out
