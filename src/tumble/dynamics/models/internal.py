"""Internal models: rotors (the gyrostat) and a spherical nutation damper.

Both exchange angular momentum with the body through internal torques only, so the total
angular momentum is conserved without an external torque. Every vector is in the body's
principal frame (``I1 <= I2 <= I3``); units kg m^2, rad/s, kg m^2/s, N m, J, W.

The pieces live in their own modules: the rotors (the gyrostat) in
:mod:`tumble.dynamics.models.rotors`, the spherical damper in
:mod:`tumble.dynamics.models.damper`; this module joins them into the equations of the whole
(:class:`InternalModel`) and holds the samples of a run (:class:`InternalSamples`). Their names
are re-exported here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple, cast

import numpy as np

from ...typing import ArrayLike, FloatArray, Matrix3, Quaternion, Vector3
from ..special.quaternion import quaternion_rate
from .damper import MAX_DAMPER_RATIO, SphericalDamper, damper_rate_components
from ..euler import momentum_rate_components
from .rotors import Rotors, gyrostat_rate

__all__ = ["MAX_DAMPER_RATIO", "STIFF_RATIO", "InternalModel", "InternalSamples", "Rotors", "SphericalDamper", "gyrostat_rate"]

#: A damper that relaxes faster than this many times the run's spin rate makes the equations
#: stiff: an explicit method's step is then set by the relaxation (stability), not by the
#: rotation. Measured on the (1, 2, 3) kg m^2 tumble at 1.6 rad/s and rtol 1e-12: once stiff,
#: DOP853 takes about 2 k right-hand sides per second of run (``k`` the relaxation rate, 1/s),
#: Radau about 1,200 per radian of rotation whatever ``k``; they cost the same near k / spin = 500.
STIFF_RATIO = 500.0


class InternalSamples(NamedTuple):
    """What an integrator returns for a run with internal models, at the sample times.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.geometric import propagate_internal
    >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
    >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.1, damping=0.5))
    >>> run = propagate_internal(model, [0.1, 1.0, 0.1], [0.0, 0.0, 0.0, 1.0], np.linspace(0.0, 10.0, 6))
    >>> run._fields
    ('omega', 'quat', 'damper_omega', 'dissipated', 'work_integral', 'solver')
    >>> run.omega.shape, run.damper_omega.shape, run.work_integral is None   # no rotors: no motor work
    ((6, 3), (6, 3), True)
    >>> bool(np.all(np.diff(run.dissipated) > 0))
    True
    """

    omega: Vector3  # (n, 3) rad/s
    quat: Quaternion  # (n, 4) body -> world, scalar last
    damper_omega: Vector3 | None  # (n, 3) rad/s
    dissipated: FloatArray | None  # (n,) J
    work_integral: FloatArray | None  # (n,) J: integral of h'.w dt
    solver: str | None = None  # the integrator that ran, where not the method asked for ("radau": a stiff damper)


@dataclass(frozen=True, eq=False)
class InternalModel:
    """Rotors and/or a damper on a body of principal ``moments``: the equations every
    integrator that supports them uses.

    ODE state (DOP853, RK45): ``[L (3), q (4), w_d (3, with a damper), A (1, with varying spins
    of known rate), D (1, with a damper)]``: total momentum, attitude, the damper's rate, the
    integral ``A = integral h'.w dt`` and the energy dissipated.

    Examples
    --------
    >>> import numpy as np
    >>> import tumble
    >>> from tumble.dynamics.models.internal import InternalModel, Rotors
    >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
    >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
    >>> model = InternalModel(body.principal_moments, Rotors.of(body))
    >>> y0 = model.initial_state([0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0])
    >>> dy = model.rhs(0.0, y0, None)   # L' = L x w: the total momentum only turns in the body frame
    >>> bool(np.isclose(dy[:3] @ y0[:3], 0.0))
    True
    """

    moments: Vector3
    rotors: Rotors | None = None
    damper: SphericalDamper | None = None

    def __post_init__(self) -> None:
        if self.damper is None:
            return
        I1 = float(np.min(self.moments))
        if not self.damper.inertia <= MAX_DAMPER_RATIO * I1:
            raise ValueError(f"damper: inertia = {self.damper.inertia!r} kg m^2 is more than {MAX_DAMPER_RATIO:g} times "
                             f"the body's smallest moment {I1:.6g} kg m^2; the body's rate would lose "
                             f"{np.log10(self.damper.inertia / I1):.0f} digits")

    @property
    def tracks_work(self) -> bool:
        """Whether ``A = integral h'.w dt`` must be integrated (spins that vary at a known rate).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> box = tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0))
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> body = tumble.Body([box, ramp])
        >>> InternalModel(body.principal_moments, Rotors.of(body)).tracks_work, InternalModel(np.ones(3)).tracks_work
        (True, False)
        """
        return self.rotors is not None and not self.rotors.constant and self.rotors.derivative_known

    @property
    def damper_inertia(self) -> float:
        """The damper sphere's moment of inertia ``J``, kg m^2 (0 without a damper).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> InternalModel(np.ones(3), damper=SphericalDamper(inertia=0.2, damping=1.0)).damper_inertia, InternalModel(np.ones(3)).damper_inertia
        (0.2, 0.0)
        """
        return 0.0 if self.damper is None else self.damper.inertia

    @property
    def relaxation_rate(self) -> float:
        """The damper's fastest relaxation rate ``max_i k_i``, 1/s (0 without a damper).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 5.0]), damper=SphericalDamper(inertia=0.5, damping=2.0))
        >>> model.relaxation_rate   # (c / J)(1 + J / I1), the largest rate
        6.0
        """
        return 0.0 if self.damper is None else float(np.max(self.damper.rates(self.moments)))

    def stiffness(self, spin: float, t_end: float) -> tuple[float, float]:
        """The damper's stiffness ratio and the rate it is measured against.

        Parameters
        ----------
        spin : float
            The fastest spin of the run, rad/s (:meth:`spin_bound`, plus what a torque adds).
        t_end : float
            The run's duration, s: ``1 / t_end`` stands for the spin of a body at rest.

        Returns
        -------
        ratio : float
            ``max_i k_i / max(spin, 1 / t_end)``: 0 without a damper; above :data:`STIFF_RATIO`
            the run is stiff.
        slow : float
            ``max(spin, 1 / t_end)``, rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 5.0]), damper=SphericalDamper(inertia=0.5, damping=2.0))
        >>> model.stiffness(spin=3.0, t_end=100.0)   # 6 / s against 3 rad/s
        (2.0, 3.0)
        >>> model.stiffness(spin=0.0, t_end=0.5)   # at rest: 1 / t_end stands for the spin
        (3.0, 2.0)
        """
        slow = max(float(spin), 1.0 / float(t_end))
        return self.relaxation_rate / slow, slow

    def spin_bound(self, omega0: ArrayLike, t: ArrayLike) -> float:
        """An estimate of the fastest body spin of a run, rad/s: ``|w0| + 2 max |h| / I1`` over
        the sample times ``t`` (the rotors can hand the body their momentum and reverse it).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> I1 = body.principal_moments[0]
        >>> bool(np.isclose(model.spin_bound([0.0, 0.0, 1.0], [0.0, 1.0]), 1.0 + 2 * 0.5 / I1))   # |w0| + 2 |h| / I1
        True
        """
        spin = math.hypot(*np.asarray(omega0, dtype=float).ravel())
        if self.rotors is None:
            return spin
        constant = self.rotors.constant_rates is not None  # then h is h(0) at every sample
        h = np.linalg.norm(self.rotors.momentum(0.0 if constant else np.asarray(t, float)), axis=-1)
        return spin + 2.0 * float(np.max(h)) / min(float(i) for i in self.moments)

    def tolerance_spin(self, omega0: ArrayLike, t: ArrayLike) -> float:
        """The scale of the body's own spin, rad/s, that a run's ``atol`` is relative to.

        With rotors at constant spin and no damper, the body's kinetic energy ``omega . I omega / 2``
        is an integral of the torque-free gyrostat (Hughes, *Spacecraft Attitude Dynamics*, sec.
        3.4: ``I omega' = (I omega + h) x omega`` is perpendicular to ``omega``), so ``|omega| <=
        sqrt(omega0 . I omega0 / I1)``: a slow body carrying a large wheel keeps a slow spin, where
        :meth:`spin_bound`, ``|w0| + 2 |h| / I1``, the rate of its nutation, is a thousand times more
        (the T-handle with its wheel at 0.02 rad/s: 0.04 against 39 rad/s). An ``atol`` relative to
        that bound let ``dop853`` leave 4.4e-8 in omega at rtol 1e-12 over 20 s, 7.3e-11 relative to
        this one (tests/test_gyrostat_tolerance.py). Otherwise (rotors whose spin
        changes hand the body their momentum; a damper) :meth:`spin_bound`.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=500.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> w0 = np.array([0.0, 0.0, 0.02])   # rad/s, about the major axis; |h| = J s = 2.5 kg m^2/s
        >>> I = body.principal_moments
        >>> bool(np.isclose(model.tolerance_spin(w0, [0.0, 1.0]), np.sqrt(w0 @ (I * w0) / I[0])))
        True
        >>> round(model.tolerance_spin(w0, [0.0, 1.0]), 3), round(model.spin_bound(w0, [0.0, 1.0]), 3)   # |w0| + 2 |h| / I1
        (0.032, 1.219)
        """
        if self.damper is not None or self.rotors is None or not self.rotors.constant:
            return self.spin_bound(omega0, t)
        w = np.asarray(omega0, dtype=float).ravel()
        return math.sqrt(float(w @ (self.moments * w)) / float(np.min(self.moments)))

    def momentum(self, t: ArrayLike) -> Vector3:
        """``h(t)``, kg m^2/s, shape ``np.shape(t) + (3,)`` (zeros without rotors).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> InternalModel(body.principal_moments, Rotors.of(body)).momentum(0.0).round(12).tolist()   # J s along axis 1
        [0.5, 0.0, 0.0]
        >>> InternalModel(np.ones(3)).momentum([0.0, 1.0]).tolist()
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
        """
        if self.rotors is None:
            return np.zeros(np.shape(t) + (3,))
        return self.rotors.momentum(t)

    def momentum_rate(self, t: ArrayLike) -> Vector3:
        """``h'(t)``, N m, shape ``np.shape(t) + (3,)`` (zeros unless :attr:`tracks_work`).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp])
        >>> InternalModel(body.principal_moments, Rotors.of(body)).momentum_rate(3.0).round(12).tolist()   # J s' along axis 1
        [0.01, 0.0, 0.0]
        """
        return cast(Rotors, self.rotors).momentum_rate(t) if self.tracks_work else np.zeros(np.shape(t) + (3,))

    def initial_state(self, omega0: ArrayLike, quat0: ArrayLike) -> FloatArray:
        """The ODE state at t = 0 (the damper turning with the body).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.5, damping=1.0))
        >>> model.initial_state([1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]).tolist()   # L = (I + J) w, q, w_d = w, D = 0
        [1.5, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0]
        """
        w0 = np.asarray(omega0, float)
        J = self.damper_inertia
        parts: list[ArrayLike] = [self.moments * w0 + self.momentum(0.0) + J * w0, quat0]
        if self.damper is not None:
            parts.append(w0)
        parts += [[0.0]] * (int(self.tracks_work) + int(self.damper is not None))
        return np.concatenate(parts)

    def atol(self, atol: float, spin: float) -> FloatArray:
        """Absolute tolerances per state component for a relative ``atol`` and a spin scale (rad/s).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel
        >>> InternalModel(np.array([1.0, 2.0, 4.0])).atol(1e-9, 2.0).tolist()   # L to atol spin I3, q to atol
        [8e-09, 8e-09, 8e-09, 1e-09, 1e-09, 1e-09, 1e-09]
        """
        I = float(np.max(self.moments)) + self.damper_inertia
        n_energy = int(self.tracks_work) + int(self.damper is not None)
        wd = [atol * spin] * (3 if self.damper is not None else 0)
        return np.array([atol * spin * I] * 3 + [atol] * 4 + wd + [atol * spin * spin * I] * n_energy)

    def rhs(self, t: float, y: FloatArray, torque: Callable[[float, Vector3, Quaternion], Vector3] | None) -> FloatArray:
        """``dy/dt``; ``torque(t, w, q)`` returns the external torque in the body frame (N m).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel
        >>> I, w = np.array([1.0, 2.0, 3.0]), np.array([0.3, 1.0, 0.2])
        >>> model = InternalModel(I)
        >>> dy = model.rhs(0.0, model.initial_state(w, [0.0, 0.0, 0.0, 1.0]), None)
        >>> bool(np.allclose(dy[:3], np.cross(I * w, w)))   # no rotor, no damper: Euler's L' = L x w
        True
        """
        damper = cast(SphericalDamper, self.damper)  # read only where wd is set, i.e. with a damper
        L, q = y[:3], y[3:7]
        h = self.momentum(t)
        wd = y[7:10] if self.damper is not None else None
        free = L - h
        w = (free if wd is None else free - damper.inertia * wd) / self.moments
        tau = torque(t, w, q) if torque is not None else (0.0, 0.0, 0.0)
        dL = np.array(momentum_rate_components(L[0], L[1], L[2], w[0], w[1], w[2], tau[0], tau[1], tau[2]))
        out: list[ArrayLike] = [dL, quaternion_rate(q, w)]
        if wd is not None:
            *dwd, dissipation = damper_rate_components(wd[0], wd[1], wd[2], w[0], w[1], w[2], damper.damping, damper.inertia)
            out.append(dwd)
        if self.tracks_work:
            out.append([self.momentum_rate(t) @ w])
        if wd is not None:
            out.append([dissipation])
        return np.concatenate(out)

    def jacobian(self, t: float, y: FloatArray) -> FloatArray:
        """``d(rhs)/dy`` of the torque-free part of :meth:`rhs`, shape (m, m), for implicit methods.

        With ``M = diag(1 / I)``, ``w = M (L - h - J w_d)`` and the slip ``s = w_d - w``:
        ``d(L x w) = -[w]x dL + [L]x dw``; the quaternion rate ``v' = (s_q w + v x w) / 2``,
        ``s_q' = -v.w / 2`` is bilinear in ``q`` and ``w``; ``w_d' = w_d x w - (c / J) s``; the
        work and dissipation rates ``h'.w`` and ``c |s|^2``. An external torque's own dependence
        on the state is left out (the Newton iterations of an implicit method converge with it
        all the same; only the step's error estimate decides the accuracy).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.2, damping=0.5))
        >>> y = model.initial_state([0.3, 1.0, 0.2], [0.1, 0.2, 0.3, 0.927])
        >>> y[7:10] += [0.05, -0.02, 0.01]   # the sphere slipping
        >>> eps = 1e-6   # against central differences of rhs
        >>> numeric = np.array([(model.rhs(0.0, y + e, None) - model.rhs(0.0, y - e, None)) / (2 * eps) for e in eps * np.eye(len(y))]).T
        >>> bool(np.allclose(model.jacobian(0.0, y), numeric, atol=1e-8))
        True
        """
        L, q = y[:3], y[3:7]
        m = len(y)
        M = np.diag(1.0 / self.moments)
        damper = cast(SphericalDamper, self.damper)  # read only where wd is set, i.e. with a damper
        wd = y[7:10] if self.damper is not None else None
        free = L - self.momentum(t)
        w = (free if wd is None else free - damper.inertia * wd) / self.moments
        dw = np.zeros((3, m))  # dw/dy
        dw[:, :3] = M
        if wd is not None:
            dw[:, 7:10] = -damper.inertia * M
        out = np.zeros((m, m))
        out[:3] = _cross_matrix(L) @ dw
        out[:3, :3] -= _cross_matrix(w)
        v, s = q[:3], q[3]
        out[3:6] = 0.5 * (s * np.eye(3) + _cross_matrix(v)) @ dw
        out[3:6, 3:6] -= 0.5 * _cross_matrix(w)
        out[3:6, 6] = 0.5 * w
        out[6] = -0.5 * (v @ dw)
        out[6, 3:6] -= 0.5 * w
        if wd is not None:
            k0 = damper.damping / damper.inertia
            ds = -dw
            ds[:, 7:10] += np.eye(3)  # d(slip)/dy
            out[7:10] = _cross_matrix(wd) @ dw - k0 * ds
            out[7:10, 7:10] -= _cross_matrix(w)
            out[-1] = 2.0 * damper.damping * ((wd - w) @ ds)
        if self.tracks_work:
            out[10 if wd is not None else 7] = self.momentum_rate(t) @ dw
        return out

    def samples(self, t: FloatArray, Y: FloatArray) -> InternalSamples:
        """Unpack ODE states ``Y`` (shape (n, m)) at the times ``t`` (shape (n,)).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.5, damping=1.0))
        >>> Y = model.initial_state([1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 2.0])[None, :]   # one state, q not unit
        >>> run = model.samples(np.zeros(1), Y)
        >>> run.omega.tolist(), run.quat.tolist(), run.dissipated.tolist()   # w = (L - J w_d) / I; q normalised
        ([[1.0, 0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]], [0.0])
        """
        L, q = Y[:, :3], Y[:, 3:7]
        wd = Y[:, 7:10] if self.damper is not None else None
        k = 10 if self.damper is not None else 7
        A = Y[:, k] if self.tracks_work else None
        D = Y[:, -1] if self.damper is not None else None
        return InternalSamples(self.omega(t, L, wd), q / np.linalg.norm(q, axis=1, keepdims=True), wd, D, A)

    def omega(self, t: ArrayLike, L: Vector3, omega_d: Vector3 | None = None) -> Vector3:
        """``w = I^-1 (L - h(t) - J w_d)``, rad/s; ``L`` and ``w_d`` of shape (n, 3).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> model.omega(0.0, np.array([[0.5, 0.0, 0.0]])).round(12).tolist() == [[0.0, 0.0, 0.0]]   # L = h: the body at rest
        True
        """
        free = L - self.momentum(t)
        if omega_d is not None:
            free = free - cast(SphericalDamper, self.damper).inertia * omega_d
        return free / self.moments

    def trajectory_fields(self, t: FloatArray, run: InternalSamples) -> dict[str, Any]:
        """The optional :class:`~tumble.dynamics.trajectory.Trajectory` fields of a run.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.methods.geometric import propagate_internal
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=0.0, spin_acceleration=10.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> t = np.linspace(0.0, 2.0, 3)
        >>> fields = model.trajectory_fields(t, propagate_internal(model, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], t))
        >>> sorted(fields)
        ['internal_momentum', 'motor_work', 'rotor_axial_moments', 'rotor_spin']
        >>> J, I1, s = 0.005, body.principal_moments[0], 20.0   # spun up from rest: I w = -h, so the work is
        >>> bool(np.isclose(fields["motor_work"][-1], 0.5 * J * s**2 * (1.0 - J / I1)))   # T = J s^2 / 2 - (J s)^2 / (2 I1)
        True
        """
        fields: dict[str, Any] = {}
        if self.rotors is not None:
            h = self.rotors.momentum(t)
            fields.update(internal_momentum=h, rotor_spin=self.rotors.spins(t),
                          rotor_axial_moments=self.rotors.axial_moments.copy())
            if self.rotors.derivative_known:
                # W(t) = [w.h + sum J s^2 / 2]_0^t - integral h'.w dt (module docstring)
                boundary = np.sum(run.omega * h, axis=1) + self.rotors.spin_energy(t)
                boundary = boundary - (np.sum(run.omega[0] * h[0]) + self.rotors.spin_energy(t[:1])[0])
                A = np.zeros(len(t)) if run.work_integral is None else run.work_integral - run.work_integral[0]
                fields["motor_work"] = boundary - A
        if self.damper is not None:
            fields.update(damper_inertia=self.damper.inertia, damper_omega=run.damper_omega,
                          dissipated=cast(FloatArray, run.dissipated) - cast(FloatArray, run.dissipated)[0])
        return fields


def _cross_matrix(v: Vector3) -> Matrix3:
    """``[v]x``, the matrix of ``u -> v x u``."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
