"""Many rigid bodies at once: :func:`simulate_batch` and its result, :class:`BatchTrajectory`.

N bodies, each with its own principal moments, initial angular velocity and attitude, sampled
at the same times. The methods are those of :func:`tumble.simulate` (:data:`METHODS`):

- ``"exact"``: the closed-form torque-free motion of :mod:`tumble.dynamics.methods.exact`, vectorised
  over bodies and times (:mod:`tumble.dynamics.methods.exact_batch`);
- ``"geometric"``, ``"geometric2"``, ``"geometric6"``: the splitting integrators, which
  already advance every body together (:func:`tumble.dynamics.methods.geometric.propagate`); torques
  allowed, called with arrays of N bodies;
- ``"dop853"``, ``"rk4"``, ``"rk8"`` under a built-in torque model (or none): the compiled engine
  (:mod:`tumble.dynamics.engine`), every body on every core, each as a lone run would go;
- ``"dop853"`` with a Python torque, ``"rk45"``, ``"seed"``: a loop of :func:`tumble.simulate`, one
  body at a time;
- ``"auto"``, the default: ``"exact"`` without torque, else ``"dop853"`` at the tolerances that
  meet ``rtol`` (:mod:`tumble.dynamics.methods.auto`).

Each body's moments, omega and attitude are checked before anything runs; a bad one is named
by its index (``omega0[3] = [nan, 1.0, 0.0] must be three finite numbers (rad/s)``).
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, replace
from typing import Any, cast, overload

import numpy as np
from scipy.spatial.transform import Rotation

from ..mass import INERTIA_RTOL, MassProperties
from ..typing import ArrayLike, FloatArray, Quaternion, Vector3
from ..validation import (
    BOUND_REASONS, MAX_RATE, QUAT_NORM_TOL, beyond, check_moments, check_positive, check_rotation, refuse_body,
    refuse_first, short_repr,
)
from . import _display
from .euler import angular_momentum, kinetic_energy, relative_drift
from .engine.stepsize import check_atol, check_rtol
from .methods.arguments import IgnoredArgumentWarning, warn_ignored
from .methods.auto import AUTO_RTOL, dop853_tolerances, rk_step
from .methods.bounds import spin_gain, spin_gains
from .methods.integrators import METHODS, Method, Propagate, StepRule, get_method
from .methods.names import AUTO, unknown_method
from .models.torques import TorqueLike, TorqueModel, as_torque, bind_to_body, kernel_form
from .simulate import MAX_ROTATION, MAX_STEPS, sample_times, simulate
from .special.quaternion import rotate_by_quaternion
from .trajectory import Trajectory

__all__ = ["MAX_BATCH_VALUES", "BatchTrajectory", "rotate_by_quaternion", "simulate_batch"]

#: Most samples a batch may hold, bodies x times (``omega`` and ``quat`` take 56 bytes per
#: sample: 2.8 GB here), to refuse a typo before allocating memory.
MAX_BATCH_VALUES = 50_000_000


@dataclass(frozen=True, eq=False)
class BatchTrajectory:
    """The sampled motions of N rigid bodies at common times. Frozen; derived quantities are
    computed once, so its arrays must not be modified in place.

    Attributes
    ----------
    t : ndarray, shape (T,)
        Sample times, s.
    omega : ndarray, shape (N, T, 3)
        Angular velocities, principal frame of each body, rad/s.
    quat : ndarray, shape (N, T, 4)
        Attitude quaternions ``[x, y, z, w]`` (scalar last), principal body frame to world.
    moments : ndarray, shape (N, 3)
        Principal moments ``I1 <= I2 <= I3`` of each body, kg m^2.
    method : str
        Name of the integration method.
    torque_free : bool
        Whether no external torque acted.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> batch = tumble.simulate_batch([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]], [1.0, 0.1, 0.1], t_end=2.0, samples=5)
    >>> batch
    BatchTrajectory(2 bodies, exact (auto), 5 samples, t = 0..2 s, torque-free)
    >>> batch.omega.shape, batch.quat.shape
    ((2, 5, 3), (2, 5, 4))
    >>> bool(np.allclose(batch[1].omega, tumble.simulate(tumble.MassProperties.from_moments([2.0, 2.0, 3.0]),
    ...                                                  [1.0, 0.1, 0.1], t_end=2.0, samples=5).omega))
    True
    """

    t: FloatArray
    omega: Vector3
    quat: Quaternion
    moments: Vector3
    method: str
    torque_free: bool = True
    auto: bool = False  # the method was chosen ("auto"), as a Trajectory's

    def __len__(self) -> int:
        """The number of bodies, N."""
        return len(self.moments)

    def __repr__(self) -> str:
        return _display.batch_repr(self)

    def _repr_html_(self) -> str:
        """The batch's size, method and ranges as an HTML table (Jupyter's rich display)."""
        return _display.batch_html(self)

    @overload
    def __getitem__(self, i: int | np.integer[Any]) -> Trajectory: ...

    @overload
    def __getitem__(self, i: slice | ArrayLike) -> BatchTrajectory: ...

    def __getitem__(self, i: int | np.integer[Any] | slice | ArrayLike) -> Trajectory | BatchTrajectory:
        """The ``i``-th body's motion as a :class:`~tumble.dynamics.trajectory.Trajectory` (its
        principal frame is its design frame); a slice, a boolean mask over the bodies or an array
        of indices selects a smaller batch.

        Examples
        --------
        >>> import tumble
        >>> batch = tumble.simulate_batch([1.0, 2.0, 3.0], [[1.0, 0.1, 0.1], [0.1, 1.0, 0.1], [0.1, 0.1, 1.0]],
        ...                               t_end=10.0, samples=50)
        >>> batch[1]
        Trajectory('body 1', exact (auto), 50 samples, t = 0..10 s, torque-free)
        >>> batch[batch.omega[:, 0, 1] < 0.5]   # the bodies not spun about the intermediate axis
        BatchTrajectory(2 bodies, exact (auto), 50 samples, t = 0..10 s, torque-free)
        """
        if isinstance(i, (bool, np.bool_)) or isinstance(i, str):
            raise TypeError(f"a BatchTrajectory is indexed by a whole number, a slice, a mask or indices, not {i!r}")
        if not isinstance(i, (int, np.integer)):
            return self._select(i)
        n = len(self)
        if not -n <= i < n:
            raise IndexError(f"body {i} is out of range: this batch holds {n}")
        return Trajectory(
            t=self.t, omega=self.omega[i], attitude=Rotation.from_quat(self.quat[i]), moments=self.moments[i],
            principal_axes=np.eye(3), method=self.method, torque_free=self.torque_free, body_name=f"body {int(i) % n}",
            auto=self.auto,
        )

    def _select(self, index: slice | ArrayLike) -> BatchTrajectory:
        """The bodies ``index`` picks (a slice, a mask of N booleans or whole numbers), as a batch."""
        n, index = len(self), index if isinstance(index, slice) else np.asarray(index)
        if isinstance(index, np.ndarray) and index.dtype == bool and index.shape != (n,):
            raise IndexError(f"a mask over the bodies has {n} entries, not shape {index.shape}")
        if isinstance(index, np.ndarray) and index.dtype != bool and (index.dtype.kind not in "iu" or index.ndim != 1):
            raise TypeError(f"a BatchTrajectory is indexed by a whole number, a slice, a mask or indices, not {index!r}")
        if isinstance(index, np.ndarray) and index.dtype != bool and index.size and not -n <= index.min() <= index.max() < n:
            raise IndexError(f"bodies {short_repr(index.tolist())} are out of range: this batch holds {n}")
        if len(self.moments[index]) == 0:
            raise IndexError(f"{short_repr(index)} selects no body of the {n}")
        return replace(self, omega=self.omega[index], quat=self.quat[index], moments=self.moments[index])

    @functools.cached_property
    def drift(self) -> dict[str, FloatArray]:
        """Each body's largest relative departure from its initial energy, ``|L|`` and ``L_world``
        (:func:`~tumble.dynamics.euler.relative_drift`, as :attr:`Trajectory.drift
        <tumble.dynamics.trajectory.Trajectory.drift>`); arrays of shape (N,), NaN for a body at
        rest. The integration's errors where the run is torque-free. It makes a few arrays of the
        batch's size (measured: a 100,000-body, 250-sample batch of 1.5 GB peaked at 5 GB here).

        Examples
        --------
        >>> import tumble
        >>> batch = tumble.simulate_batch([1.0, 2.0, 3.0], [[1.0, 0.1, 0.1], [0.1, 1.0, 0.1]], t_end=20.0,
        ...                               samples=100, method="rk4", step=0.01)
        >>> {k: v.shape for k, v in batch.drift.items()}
        {'energy': (2,), 'L_norm': (2,), 'L_world': (2,)}
        >>> bool((batch.drift["energy"] < 1e-8).all())   # RK4 at 0.01 s: small, not zero
        True
        """
        norm = np.linalg.norm(self.angular_momentum, axis=-1)
        return relative_drift(self.energy, norm, self.angular_momentum_world)

    @functools.cached_property
    def energy(self) -> FloatArray:
        """Kinetic energy ``omega . I omega / 2``, J; shape (N, T).

        Examples
        --------
        >>> import numpy as np, tumble
        >>> batch = tumble.simulate_batch([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]], [1.0, 1.0, 1.0], t_end=2.0, samples=5)
        >>> batch.energy.shape, batch.energy[:, 0].round(6).tolist()   # omega . I omega / 2
        ((2, 5), [3.0, 3.5])
        >>> bool(np.allclose(batch.energy, batch.energy[:, :1]))
        True
        """
        return kinetic_energy(self.omega, self.moments[:, None, :])

    @functools.cached_property
    def angular_momentum(self) -> Vector3:
        """``L = I omega``, principal frame, kg m^2/s; shape (N, T, 3).

        Examples
        --------
        >>> import tumble
        >>> batch = tumble.simulate_batch([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]], [1.0, 1.0, 1.0], t_end=2.0, samples=5)
        >>> batch.angular_momentum[:, 0].round(6).tolist()   # I omega at t = 0
        [[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]]
        """
        return angular_momentum(self.omega, self.moments[:, None, :])

    @functools.cached_property
    def angular_momentum_world(self) -> Vector3:
        """L in the world frame, kg m^2/s; constant without torque; shape (N, T, 3).

        Examples
        --------
        >>> import numpy as np, tumble
        >>> batch = tumble.simulate_batch([1.0, 2.0, 3.0], [[1.0, 1.0, 1.0], [0.0, 2.0, 0.1]], t_end=5.0, samples=20)
        >>> L = batch.angular_momentum_world
        >>> bool(np.allclose(L, L[:, :1]))   # each body's L is fixed in space
        True
        """
        return rotate_by_quaternion(self.quat, self.angular_momentum)


def simulate_batch(moments: ArrayLike, omega0: ArrayLike, *, t_end: float | None = None, times: ArrayLike | None = None,
                   samples: int | None = None, attitude0: ArrayLike | None = None, method: str = AUTO,
                   torque: TorqueLike | None = None, step: float | None = None, rtol: float | None = None,
                   atol: float | None = None) -> BatchTrajectory:
    """Integrate the rotation of N rigid bodies, sampled at the same times.

    Parameters
    ----------
    moments : array_like, shape (N, 3) or (3,)
        Principal moments of each body, ascending (``I1 <= I2 <= I3``), positive, within the
        triangle inequality ``I1 + I2 >= I3`` and at most 1e50 kg m^2; one row is used for
        every body. Used as given: moments that are equal only to
        round-off are not a symmetric top (:func:`tumble.mass.principal_frame` makes them so).
    omega0 : array_like, shape (N, 3) or (3,)
        Initial angular velocities at t = 0, principal frame, rad/s (at most 1e15 rad/s per
        component, :data:`~tumble.validation.MAX_RATE`); one row for every body.
    t_end : float, optional
        Duration, s: ``samples`` equally spaced times in ``[0, t_end]``.
    times : array_like, shape (T,), optional
        The sample times themselves, s (instead of ``t_end``): finite, strictly increasing,
        ``times[0] >= 0``; the motion starts at t = 0.
    samples : int, optional
        Number of samples with ``t_end`` (default 500).
    attitude0 : scipy Rotation (one or N), array_like, shape (N, 4), (4,) or (3, 3), optional
        Initial attitudes, principal frame to world (the bodies are their moments: their principal
        frame is their body frame, where :func:`simulate` turns a Body's design frame): unit quaternions
        ``[x, y, z, w]`` (scalar last), a rotation matrix, or scipy Rotations; default identity. Norms
        within 1e-3 of 1 are accepted and renormalised.
    method : str
        ``"auto"`` (the default) or a name from :data:`tumble.dynamics.METHODS`. ``"auto"`` runs
        ``"exact"`` without torque, else ``"dop853"`` at the tolerances that meet ``rtol`` in omega
        and attitude (default 1e-10, :func:`~tumble.dynamics.methods.auto.dop853_tolerances`, as
        :func:`tumble.simulate`'s ``"auto"`` takes them): compiled on every core for the built-in
        models, and for a torque of one's own each body as :func:`tumble.simulate` runs it.
    torque : callable or torque model, optional
        ``tau(t, omega, attitude)``, N m, in the principal frame or the world frame as the model
        says (:mod:`tumble.dynamics.models.torques`). The geometric methods call it once per kick with
        ``omega`` of shape (N, 3) and a stack of N rotations, and it may return (3,) or (N, 3);
        the loop methods call it per body. A model with ``bind`` (the gravity gradient) is bound
        to the moments of the bodies.
    step : float, optional
        Largest step of the fixed-step methods (the splittings, ``"rk4"``, ``"rk8"``), s; by
        default the method's rotation per step (0.05 rad for the splittings) at the fastest spin
        of the batch (so each body gets at most the step a lone run would).
    rtol, atol : float, optional
        Tolerances of ``"dop853"`` (and ``"rk45"``), as :func:`tumble.simulate` takes them; the
        method's defaults if not given. ``"rk4"`` and ``"rk8"`` given ``rtol`` and no ``step`` take
        each body's step that meets it, as a lone run does; what a method does not read warns.

    Returns
    -------
    BatchTrajectory

    Raises
    ------
    ValueError
        For bad input, with one line naming the argument and the first bad body's index, and
        for a run no method can follow (the limits of :func:`tumble.simulate`).

    Examples
    --------
    >>> import numpy as np, tumble
    >>> rng = np.random.default_rng(1)
    >>> omega0 = np.column_stack([rng.normal(0.0, 0.1, 100), np.full(100, 1.0), rng.normal(0.0, 0.1, 100)])
    >>> batch = tumble.simulate_batch([1.0, 2.0, 3.0], omega0, t_end=30.0, samples=301)   # 100 near-intermediate spins
    >>> batch.omega.shape
    (100, 301, 3)
    >>> int(np.sum(batch.omega[:, :, 1].min(axis=1) < 0))   # every one flips
    100
    >>> bool(np.allclose(batch.energy, batch.energy[:, :1]))
    True
    """
    model = as_torque(torque)
    auto = isinstance(method, str) and method == AUTO
    if not auto and not (isinstance(method, str) and method in METHODS):
        raise ValueError(unknown_method(method))
    spec = get_method(("exact" if model is None else "dop853") if auto else method)
    step = None if step is None else check_positive("step", step, "s")  # once, for every method that steps
    warn_ignored(spec, auto=auto, rtol=rtol, atol=atol, step=step)  # as simulate does (its loop below says nothing)
    asked = rtol, atol  # what a lone simulate(method="auto") takes, for a torque of one's own
    if auto and model is not None:  # the engine's dop853, its local error control tighter than the accuracy asked for
        r = AUTO_RTOL if rtol is None else check_rtol("rtol", rtol)
        rtol, atol = dop853_tolerances(r, r if atol is None else check_atol("atol", atol))
    if model is not None and not spec.supports_torque:
        allowed = ", ".join(m for m, s in METHODS.items() if s.supports_torque)
        raise ValueError(f"method = {spec.name!r} cannot take a torque; use one of: auto (the default), {allowed}")
    I, w0, q0 = check_batch(moments, omega0, attitude0)
    t, keep = sample_times(t_end, samples, None, times)
    if len(I) * len(t) > MAX_BATCH_VALUES:
        raise ValueError(f"{len(I)} bodies x {len(t)} samples is more than {MAX_BATCH_VALUES:,} samples in all; "
                         f"split the batch or sample fewer times")
    if spec.closed_form:  # only the times asked for (no steps from t = 0)
        from .methods.exact_batch import free_rotation_batch

        t, keep = t[keep], slice(None)
        omega, quat = free_rotation_batch(I, w0, q0, t)
    elif spec.splitting_order is not None:  # every body together
        omega, quat = _splitting(spec, I, w0, q0, t, model, step)
    elif spec.engine and kernel_form(bind_to_body(model, I)) is not None:  # compiled, every body on every core
        omega, quat = _engine(spec, I, w0, q0, t, bind_to_body(model, I), step, rtol, atol)
    else:
        omega, quat = _loop(AUTO if auto else spec.name, I, w0, q0, t, torque, step, *(asked if auto else (rtol, atol)))
    return BatchTrajectory(t=t[keep], omega=omega[:, keep], quat=quat[:, keep], moments=I, method=spec.name,
                           torque_free=model is None, auto=auto)


def _first(bad: np.ndarray) -> int:
    return int(np.flatnonzero(bad)[0])


def _rows(name: str, value: Any, width: int, unit: str) -> FloatArray:
    """``value`` as an array of shape (n, width), n >= 1 (a single row is (1, width)), of finite
    real numbers, or one line naming the first bad row and saying what it must be."""
    if isinstance(value, (str, bytes, dict, set)):
        raise ValueError(f"{name} = {short_repr(value)} must be an array of shape (N, {width}) or ({width},) ({unit})")
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        raise ValueError(f"{name} must be an array of numbers of shape (N, {width}) or ({width},) ({unit})") from None
    if a.ndim == 1 and a.shape == (width,):
        a = a[None, :]
    if a.ndim != 2 or a.shape[1] != width:
        raise ValueError(f"{name} has shape {a.shape}; it must be (N, {width}) or ({width},) ({unit})")
    if len(a) == 0:
        raise ValueError(f"{name} has no rows (shape {a.shape}): a batch needs at least one body")
    # booleans, complex numbers, strings (numpy turns [[1, 0, 0], [True, 0, 0]] into integers):
    # scan the rows as given unless they are already a real array
    if a.dtype.kind not in "iuf" or not isinstance(value, np.ndarray):
        rows = a.tolist() if isinstance(value, np.ndarray) or np.ndim(value) != 2 else list(value)
        bad = [not all(_real(x) for x in row) for row in rows]
        if any(bad):
            imag = [any(isinstance(x, complex) and x.imag != 0 for x in row) for row in rows]
            i = imag.index(True) if any(imag) else bad.index(True)
            raise ValueError(f"{name}[{i}] = {list(rows[i])!r} must be {width} real numbers ({unit}); "
                             f"booleans, complex numbers and strings are not")
    a = a.astype(float)
    bad = ~np.all(np.isfinite(a), axis=1)
    if np.any(bad):
        i = _first(bad)
        raise ValueError(f"{name}[{i}] = {a[i].tolist()} must be {width} finite numbers ({unit})")
    return a


def _real(x: object) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def check_batch(moments: ArrayLike, omega0: ArrayLike, attitude0: ArrayLike | None = None) -> tuple[Vector3, Vector3, Quaternion]:
    """Validate a batch's moments, omega and attitudes and broadcast them to N bodies.

    Parameters
    ----------
    moments, omega0, attitude0
        As :func:`simulate_batch`.

    Returns
    -------
    moments : ndarray, shape (N, 3)
    omega0 : ndarray, shape (N, 3)
    quat0 : ndarray, shape (N, 4)
        Unit quaternions (renormalised).

    Raises
    ------
    ValueError
        One line naming the argument and the first bad index.
    """
    refuse_body("moments", moments)
    I = _rows("moments", moments, 3, "kg m^2")
    w = _rows("omega0", omega0, 3, "rad/s")
    if isinstance(attitude0, Rotation):  # one rotation or a stack, as simulate takes one
        attitude0 = attitude0.as_quat()
    elif attitude0 is not None and np.shape(cast(Any, attitude0)) == (3, 3):  # one matrix, checked as simulate does
        attitude0 = check_rotation("attitude0", attitude0)
    q = _rows("attitude0", [0.0, 0.0, 0.0, 1.0] if attitude0 is None else attitude0, 4, "unit quaternions [x, y, z, w]")
    sizes = {len(a) for a in (I, w, q) if len(a) > 1}
    if len(sizes) > 1:
        given = [("moments", I), ("omega0", w)] + ([("attitude0", q)] if attitude0 is not None else [])
        listed = ", ".join(f"{name} ({len(a)})" for name, a in given[:-1]) + f" and {given[-1][0]} ({len(given[-1][1])})"
        raise ValueError(f"{listed} hold different numbers of bodies; give each N rows, or one row for all")
    n = sizes.pop() if sizes else 1
    check_moments("moments", I)
    refuse_first("omega0", w, np.any(np.abs(w) > MAX_RATE, axis=1), f"is beyond {MAX_RATE:g} rad/s: {BOUND_REASONS[MAX_RATE]}")
    bad = I[:, 0] <= INERTIA_RTOL * np.sum(I, axis=1)
    if np.any(bad):
        i = _first(bad)
        raise ValueError(f"moments[{i}] = {I[i].tolist()} kg m^2: a body with a zero moment (a thin rod, a point) "
                         f"has no well-posed rotation about that axis; give it some thickness")
    norms = np.linalg.norm(q, axis=1)
    bad = ~(np.abs(norms - 1.0) <= QUAT_NORM_TOL)
    if np.any(bad):
        i = _first(bad)
        raise ValueError(f"attitude0[{i}] = {q[i].tolist()} is a quaternion of norm {norms[i]:.6g}; a rotation needs "
                         f"a unit quaternion [x, y, z, w] (scalar last)")
    q = q / norms[:, None]
    I, w, q = (np.ascontiguousarray(np.broadcast_to(a, (n, a.shape[1]))) for a in (I, w, q))
    with np.errstate(over="ignore", invalid="ignore"):
        energy = 0.5 * np.sum(I * w * w, axis=1)  # as simulate checks it
    bad = ~np.isfinite(energy)
    if np.any(bad):
        i = _first(bad)
        raise ValueError(f"omega0[{i}] = {w[i].tolist()} rad/s is too large: the kinetic energy of this body overflows")
    return I, w, q


def _splitting(spec: Method, I: Vector3, w0: Vector3, q0: Quaternion, t: FloatArray, model: TorqueModel | None,
               step: float | None) -> tuple[Vector3, Quaternion]:
    """The splitting integrators, every body together; the work bounds of :func:`tumble.simulate`."""
    model = bind_to_body(model, I)  # a torque that needs the bodies' moments (NeedsBody)
    t_end = float(t[-1])
    spin = float(np.max(np.linalg.norm(w0, axis=1)))
    with np.errstate(over="ignore", invalid="ignore"):
        gain = spin_gain(model, 0.0, w0, Rotation.from_quat(q0), I, t_end)
    # a splitting method has both default_step and propagate (integrators.py)
    h = step if step is not None else cast(StepRule, spec.default_step)(spin, gain)  # what propagate takes by default
    _bound_work(spec, spin, gain, t_end, h)
    omega, quat = cast(Propagate, spec.propagate)(I, w0, q0, t, step=step, torque=model)
    return np.ascontiguousarray(omega.transpose(1, 0, 2)), np.ascontiguousarray(quat.transpose(1, 0, 2))


def _bound_work(spec: Method, spin: float, gain: float, t_end: float, h: float | None) -> None:
    """Refuse a batch run that turns a body more than :data:`~tumble.dynamics.simulate.MAX_ROTATION`
    (fastest spin ``spin`` and torque gain ``gain``, rad/s) or takes more than
    :data:`~tumble.dynamics.simulate.MAX_STEPS` steps of ``h`` (s; None: an adaptive method)."""
    with np.errstate(over="ignore", invalid="ignore"):
        turns = spin * t_end + 0.5 * gain * t_end
    if not turns <= MAX_ROTATION:
        raise ValueError(f"t_end = {t_end:g} s with max |omega0| = {spin:.6g} rad/s (and a torque gain of {gain:.3g} rad/s) is "
                         f"up to {beyond(turns, MAX_ROTATION)} rad of rotation, more than method {spec.name!r} follows (at most "
                         f"{MAX_ROTATION:g} rad); use method exact or a shorter run")
    if h is not None and t_end / h > MAX_STEPS:
        raise ValueError(f"step = {h:.3g} s makes {t_end / h:.3g} steps of a {t_end:g} s run; at most {MAX_STEPS:g}")


def _engine(spec: Method, I: Vector3, w0: Vector3, q0: Quaternion, t: FloatArray, model: TorqueModel | None,
            step: float | None, rtol: float | None, atol: float | None) -> tuple[Vector3, Quaternion]:
    """The compiled engine's steppers (:mod:`tumble.dynamics.engine`), every body on every core,
    each body with the tolerances or the step a lone :func:`tumble.simulate` run gives it."""
    from .engine import run_bodies

    t_end = float(t[-1])
    spin = np.array([math.hypot(*w) for w in w0.tolist()])  # as simulate takes it, to the last bit
    gains = np.broadcast_to(spin_gains(model, 0.0, w0, Rotation.from_quat(q0), I, t_end), spin.shape)  # per body
    form = cast(tuple[int, tuple[float, ...]], kernel_form(model))
    if spec.fixed_step:  # each body's own step as a lone run takes it: the default, or the one meeting a given rtol
        rule = cast(StepRule, spec.default_step) if rtol is None else (
            lambda s, g, r=check_rtol("rtol", rtol): rk_step(spec.name, r, s + g, asked=True) or math.inf)
        h = np.full(len(I), step) if step is not None else np.array([rule(s, g) for s, g in zip(spin.tolist(),
                                                                                                 gains.tolist())])
        _bound_work(spec, float(np.max(spin)), float(np.max(gains)), t_end, float(np.min(h)))
        omega, quat = run_bodies(spec.name, I, w0, q0, t, form, step=h)
    else:
        _bound_work(spec, float(np.max(spin)), float(np.max(gains)), t_end, None)
        r = spec.rtol if rtol is None else check_rtol("rtol", rtol)
        # an rtol given alone brings the atol down with it, as simulate's
        a = min(cast(float, spec.atol), cast(float, r)) if atol is None else check_atol("atol", atol)
        scale = np.maximum(np.maximum(spin, gains), 1e-300)  # atol relative to each body's omega, as simulate's
        tol = np.column_stack([np.outer(a * scale, np.ones(3)), np.full((len(I), 4), a)])
        omega, quat = run_bodies(spec.name, I, w0, q0, t, form, rtol=r, atol=tol)
    return omega, quat


def _loop(name: str, I: Vector3, w0: Vector3, q0: Quaternion, t: FloatArray, torque: TorqueLike | None,
          step: float | None, rtol: float | None = None, atol: float | None = None) -> tuple[Vector3, Quaternion]:
    """A loop of :func:`tumble.simulate`, a body at a time (adaptive methods, the seed's, "auto" with a Python torque)."""
    omega, quat = np.empty((len(I), len(t), 3)), np.empty((len(I), len(t), 4))
    for i in range(len(I)):
        props = MassProperties(1.0, np.zeros(3), np.diag(I[i]), I[i].copy(), np.eye(3))
        with warnings.catch_warnings():  # what the method does not read: said once, by simulate_batch
            warnings.simplefilter("ignore", IgnoredArgumentWarning)
            traj = simulate(props, w0[i], times=t, method=name, torque=torque, attitude0=q0[i], step=step, rtol=rtol,
                            atol=atol)
        omega[i], quat[i] = traj.omega, traj.quat
    return omega, quat
