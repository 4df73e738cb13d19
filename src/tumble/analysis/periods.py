"""Periods and angles of torque-free motion: the body-frame period, Montgomery's rotation per
period, the symmetric top's two rates and the periods of tumbling (non-principal-axis) rotation.

Notation as :mod:`tumble.analysis.stability` and :mod:`tumble.dynamics.methods.exact` (Landau &
Lifshitz, *Mechanics*, sec. 37): principal moments ``I1 <= I2 <= I3``; omega circulates about
axis ``r`` = 3 (major) when ``L^2 >= 2 E I2``, about ``r`` = 1 (minor) otherwise; ``o`` is the
other extreme axis; ``u = u0 + p t`` the elliptic argument and ``m = k^2`` its parameter.

- **Period of the body-frame motion** ``T = 4 K(m) / p`` (Landau & Lifshitz sec. 37): after
  ``T`` omega, L_body and the energy ellipsoid's polhode are back where they were; the flip
  interval of :func:`tumble.analysis.flip_interval` is ``T / 2``. For a symmetric top ``m = 0``
  and ``T = 2 pi / p`` with ``p = |(I_s - I_perp) w_s / I_perp|`` (Landau & Lifshitz sec. 36).
- **Precession per period.** The exact solution writes the attitude as ``Rz(phi) Rx(theta)
  Rz(psi)`` about L (z-x-z Euler angles, Landau & Lifshitz sec. 35) with
  ``phi' = |L| / I_r + |L| (I_r - I_o) / (I1 I3) / (1 - n sn^2 u)``,
  ``n = -I_r (I2 - I_o) / (I_o (I_r - I2))`` (:mod:`tumble.dynamics.methods.exact`, derived from Landau &
  Lifshitz sec. 37). Over one period ``am u`` advances by ``2 pi`` and Legendre's integral of
  the third kind by ``4 Pi(n | m)`` (complete), so

      Delta phi = |L| T / I_r + 4 |L| (I_r - I_o) Pi(n | m) / (I1 I3 p).

  ``Pi(n | m) = R_F(0, 1 - m, 1) + (n / 3) R_J(0, 1 - m, 1, 1 - n)`` (DLMF 19.25.2, Carlson's
  symmetric integrals, evaluated by scipy).
- **Montgomery's formula** (R. Montgomery, "How much does the rigid body rotate? A Berry's
  phase from the 18th century", Am. J. Phys. 59 (1991) 394): after one period the body has
  turned about L by ``Delta theta = 2 E T / |L| - Omega (mod 2 pi)``, ``Omega`` the solid angle
  that L_body / |L| sweeps on the unit sphere. Here ``Omega`` is the oriented area of the cap the
  polhode encloses around the circulation axis on L's side, positive when L circulates
  counter-clockwise seen from outside that cap: positive for circulation about the major axis,
  negative about the minor axis, ``|Omega| < 2 pi``. It follows from the same Euler angles: the
  component of omega along L is ``2 E / |L| = phi' + psi' cos theta``; with the azimuth of L in
  the body ``alpha = pi / 2 - psi`` (which turns by ``+-2 pi`` per period),
  ``Delta phi = 2 E T / |L| + Delta alpha - Omega``, i.e. the closed form

      Omega = 2 E T / |L| - Delta phi + 2 pi sigma,   sigma = +1 (major axis), -1 (minor axis),

  which is :func:`polhode_solid_angle`; ``Delta theta = Delta phi mod 2 pi`` is
  :func:`montgomery_angle`. The tests hold ``Omega`` against the solid-angle integral
  ``oint (1 - cos theta) d alpha`` of the polhode computed with mpmath (an independent route) and
  ``Delta theta`` against the rotation measured on DOP853 runs (:func:`rotation_per_period`).
- **Tumbling (NPA) rotation**: see :func:`npa_periods`.
"""

from __future__ import annotations

import numpy as np
from scipy.special import elliprf, elliprj

from ..dynamics import Trajectory
from ..dynamics.methods.exact import elliptic_parameters
from ..mass import INERTIA_RTOL
from ..mass.tensor import refuse_first
from ..typing import ArrayLike
from ..validation import AXES_ALLOWED
from .stability import _axis_index, _check_motion, circulation_axis, flip_interval

__all__ = [
    "axis_precession_period",
    "montgomery_angle",
    "npa_periods",
    "npa_periods_measured",
    "period",
    "polhode_solid_angle",
    "precession_per_period",
    "rotation_per_period",
    "symmetric_top_rates",
]

TWO_PI = 2.0 * np.pi


def period(omega: ArrayLike, moments: ArrayLike) -> np.ndarray:
    """Period of the body-frame motion, ``T = 4 K(m) / p``, s (module docstring).

    Twice :func:`tumble.analysis.flip_interval`. For a symmetric top ``2 pi / p``, the period of
    omega's precession about the symmetry axis in the body (Landau & Lifshitz sec. 36).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity at any instant, principal frame (``I1 <= I2 <= I3``), rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending, I1 + I2 >= I3, kg m^2.

    Returns
    -------
    ndarray, shape (...)
        ``T`` in s; ``inf`` on the separatrix (``L^2 = 2 E I2``), at rest, for a sphere and for a
        symmetric top spinning steadily in its degenerate plane.

    Raises
    ------
    ValueError
        As :func:`tumble.analysis.flip_interval` (the shared validator names the first bad index).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.periods import period
    >>> from tumble.analysis.stability import flip_interval
    >>> omega, moments = [0.3, 0.2, 1.0], [1.0, 2.0, 3.0]
    >>> bool(np.isclose(period(omega, moments), 2 * flip_interval(omega, moments)))
    True
    >>> round(float(period([0.0, 0.1, 1.0], [1.0, 1.0, 2.0])), 6) == round(2 * np.pi / 1.0, 6)   # symmetric: 2 pi / ((I3 - I1) w3 / I1)
    True
    """
    return 2.0 * flip_interval(omega, moments)


def _precession(w: np.ndarray, I: np.ndarray):
    """``(T, Delta phi, 2 E T / |L|, sigma)`` of the motion through ``w`` (module docstring)."""
    e = elliptic_parameters(w, I)
    T = 2.0 * flip_interval(w, I)
    w, I = np.broadcast_arrays(w, I)
    I1, I2, I3 = I[..., 0], I[..., 1], I[..., 2]
    upper = np.asarray(e.upper)
    Ir, Io = np.where(upper, I3, I1), np.where(upper, I1, I3)
    L = np.linalg.norm(I * w, axis=-1)
    twoE = np.sum(I * w * w, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        n = -Ir * (I2 - Io) / (Io * (Ir - I2))
        n = np.where(Ir == I2, 0.0, n)  # a prolate/oblate top about its symmetry axis: n = 0
        m1 = np.asarray(e.kp, float) ** 2
        K = elliprf(0.0, m1, 1.0)
        Pi = K + np.where(n == 0, 0.0, n / 3.0 * elliprj(0.0, m1, 1.0, 1.0 - n))
        dphi = L * T / Ir + 4.0 * L * (Ir - Io) * Pi / (I1 * I3 * e.p)
        dphi = np.where(Ir == Io, L * T / Ir, dphi)  # sphere (T is inf there anyway)
        secular = twoE * T / L
    finite = np.isfinite(T) & (L > 0)
    sigma = np.where(upper, 1.0, -1.0)
    return (T, np.where(finite, dphi, np.nan), np.where(finite, secular, np.nan), sigma)


def precession_per_period(omega: ArrayLike, moments: ArrayLike) -> np.ndarray:
    """``Delta phi``: the angle the circulation axis precesses about L in one period, rad.

    ``|L| T / I_r + 4 |L| (I_r - I_o) Pi(n | m) / (I1 I3 p)`` (module docstring), not reduced;
    ``|L| T / I_perp`` for a symmetric top (Landau & Lifshitz sec. 33). NaN where the period is
    infinite.

    Parameters and errors as :func:`period`; returns an ndarray of shape (...), rad.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.periods import period, precession_per_period
    >>> omega, moments = np.array([0.0, 0.1, 1.0]), np.array([1.0, 1.0, 2.0])   # a symmetric top
    >>> L = np.linalg.norm(moments * omega)
    >>> bool(np.isclose(precession_per_period(omega, moments), L * period(omega, moments) / moments[0]))   # |L| T / I_perp
    True
    """
    return _precession(*_check_motion(omega, moments))[1]


def montgomery_angle(omega: ArrayLike, moments: ArrayLike) -> np.ndarray:
    """Montgomery's rotation per period ``Delta theta = 2 E T / |L| - Omega (mod 2 pi)``, rad.

    Computed by the closed form of the module docstring: ``Delta theta = Delta phi mod 2 pi``
    with ``Delta phi`` from the complete elliptic integral of the third kind (the solid angle
    ``Omega`` is :func:`polhode_solid_angle`). The angle by which the body, after one period
    ``T`` of its body-frame motion (:func:`period`), has turned about L (R. Montgomery, Am. J.
    Phys. 59 (1991) 394); measured on a trajectory by :func:`rotation_per_period`.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity at any instant, principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending, I1 + I2 >= I3, kg m^2.

    Returns
    -------
    ndarray, shape (...)
        ``Delta theta`` in ``[0, 2 pi)``, rad, counter-clockwise about L; NaN where the period is
        infinite (separatrix, rest, sphere).

    Raises
    ------
    ValueError
        As :func:`period`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.periods import montgomery_angle, precession_per_period
    >>> omega, moments = [0.3, 0.2, 1.0], [1.0, 2.0, 3.0]
    >>> bool(np.isclose(montgomery_angle(omega, moments), precession_per_period(omega, moments) % (2 * np.pi)))
    True
    """
    dphi = _precession(*_check_motion(omega, moments))[1]
    return np.mod(dphi, TWO_PI)


def polhode_solid_angle(omega: ArrayLike, moments: ArrayLike) -> np.ndarray:
    """Oriented solid angle ``Omega`` enclosed by the path of L_body / |L| in one period, sr.

    ``Omega = 2 E T / |L| - Delta phi + 2 pi sigma`` (module docstring; ``sigma = +1`` for
    circulation about the major axis, ``-1`` about the minor axis): the cap around the
    circulation axis on L's side, positive (counter-clockwise seen from outside the cap) about
    the major axis, negative about the minor axis; ``|Omega| < 2 pi``. For a symmetric top
    ``2 pi sigma (1 - |cos theta|)``, theta the angle between L and the symmetry axis.

    Parameters and errors as :func:`period`; returns an ndarray of shape (...), sr (NaN where
    the period is infinite).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.periods import polhode_solid_angle
    >>> omega, moments = np.array([0.0, 0.1, 1.0]), np.array([1.0, 1.0, 2.0])   # a symmetric top, about the major axis
    >>> L = moments * omega
    >>> cos_theta = L[2] / np.linalg.norm(L)
    >>> bool(np.isclose(polhode_solid_angle(omega, moments), 2 * np.pi * (1 - cos_theta)))   # the cap
    True
    """
    T, dphi, secular, sigma = _precession(*_check_motion(omega, moments))
    return secular - dphi + TWO_PI * sigma


def _check_trajectory(traj) -> None:
    if not isinstance(traj, Trajectory):
        raise TypeError(f"traj must be a tumble Trajectory, got {type(traj).__name__}")
    if not (traj.torque_free and traj.rigid):
        raise ValueError("traj must be a torque-free rigid body (no torque, rotors or damper): "
                         "the periods are those of free rotation")
    if len(traj.t) < 2:
        raise ValueError(f"traj has {len(traj.t)} sample(s); at least 2 are needed")


def rotation_per_period(traj: Trajectory, period_s: float | None = None) -> float:
    """Rotation of the body about L_world over one body-frame period, measured, rad.

    The angle of ``R(t0 + T) R(t0)^-1`` about ``L_world`` (counter-clockwise), in ``[0, 2 pi)``,
    where ``t0 = traj.t[0]``. After one period the body-frame state is back, so that rotation
    leaves L_world fixed and is a rotation about it by Montgomery's ``Delta theta``
    (:func:`montgomery_angle`).

    Parameters
    ----------
    traj : Trajectory
        A torque-free rigid motion sampled at ``t0`` and at ``t0 + T`` (e.g.
        ``tumble.simulate(body, w0, times=[0, T], method="dop853")``).
    period_s : float, optional
        ``T`` in s; default :func:`period` of ``traj.omega[0]``.

    Returns
    -------
    float
        The angle in rad.

    Raises
    ------
    ValueError
        If the trajectory is not torque-free and rigid, the period is not finite, or no sample
        lies at ``t0 + T`` (within ``1e-9 T``).

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.analysis.periods import montgomery_angle, period, rotation_per_period
    >>> body, omega0 = tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [0.3, 0.2, 1.0]
    >>> T = float(period(omega0, body.principal_moments))
    >>> traj = tumble.simulate(body, omega0, times=[0.0, T])
    >>> bool(np.isclose(rotation_per_period(traj, T), montgomery_angle(omega0, body.principal_moments)))   # measured = closed form
    True
    """
    _check_trajectory(traj)
    T = float(period(traj.omega[0], traj.moments)) if period_s is None else float(period_s)
    if not (np.isfinite(T) and T > 0):
        raise ValueError(f"period = {T!r} s: the rotation per period needs a finite positive period")
    target = traj.t[0] + T
    k = int(np.argmin(np.abs(traj.t - target)))
    if not abs(traj.t[k] - target) <= 1e-9 * T:
        raise ValueError(f"traj has no sample at t0 + T = {target!r} s (nearest {traj.t[k]!r} s); "
                         "sample it there, e.g. times=[0, T]")
    Q = (traj.attitude[k] * traj.attitude[0].inv()).as_quat()  # [x, y, z, w]
    Lw = traj.angular_momentum_world[0]
    axis = Lw / np.linalg.norm(Lw)
    return float(np.mod(2.0 * np.arctan2(np.dot(Q[:3], axis), Q[3]), TWO_PI))


def symmetric_top_rates(omega: ArrayLike, moments: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The two rates of a free symmetric top (Landau & Lifshitz, *Mechanics*, secs. 33, 36), rad/s.

    For moments ``I_perp, I_perp, I_s`` (oblate, ``I1 = I2``, symmetry axis 3) or ``I_s,
    I_perp, I_perp`` (prolate, ``I2 = I3``, symmetry axis 1): the symmetry axis precesses about
    L at ``|L| / I_perp``, and in the body omega and L precess about the symmetry axis at
    ``(I_s - I_perp) w_s / I_perp`` (for an oblate top ``(I3 - I1) w3 / I1``: the Eulerian free
    nutation of a rigid Earth). Two moments count as equal within ``1e-9`` of the trace
    (:data:`tumble.mass.INERTIA_RTOL`, the principal frame's rule); a sphere counts as oblate.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending, I1 + I2 >= I3, two of them equal, kg m^2.

    Returns
    -------
    precession : ndarray, shape (...)
        ``|L| / I_perp``, rad/s (>= 0).
    body_rate : ndarray, shape (...)
        ``(I_s - I_perp) w_s / I_perp``, rad/s, signed: counter-clockwise about the symmetry
        axis' positive direction when positive.

    Raises
    ------
    ValueError
        As :func:`period`, or for moments with no two equal (naming the first such index).

    Examples
    --------
    >>> from tumble.analysis.periods import symmetric_top_rates
    >>> precession, body_rate = symmetric_top_rates([0.0, 0.1, 1.0], [1.0, 1.0, 2.0])
    >>> round(float(precession), 6), round(float(body_rate), 6)   # |L| / I_perp, (I3 - I1) w3 / I1
    (2.002498, 1.0)
    """
    w, I = _check_motion(omega, moments)
    tol = INERTIA_RTOL * np.sum(I, axis=-1)
    oblate = I[..., 1] - I[..., 0] <= tol
    prolate = I[..., 2] - I[..., 1] <= tol
    refuse_first("moments", I, ~(oblate | prolate), "must be a symmetric top: I1 == I2 or I2 == I3 "
                 f"(within {INERTIA_RTOL:g} of the trace)")
    w, I = np.broadcast_arrays(w, I)
    oblate = np.broadcast_to(oblate, w.shape[:-1])
    I_perp = np.where(oblate, I[..., 0], I[..., 2])
    I_s = np.where(oblate, I[..., 2], I[..., 0])
    w_s = np.where(oblate, w[..., 2], w[..., 0])
    L = np.linalg.norm(I * w, axis=-1)
    return L / I_perp, (I_s - I_perp) * w_s / I_perp


def npa_periods(omega: ArrayLike, moments: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Periods of non-principal-axis rotation (a tumbling asteroid) from moments and omega.

    Conventions: the names are those of Samarasinha & A'Hearn, Icarus 93 (1991) 194, and
    Kaasalainen, A&A 376 (2001) 302. The *long-axis mode* (LAM) is circulation about the minor
    axis (the body's long axis, ``L^2 < 2 E I2``), the *short-axis mode* (SAM) about the major
    axis (the short axis, ``L^2 > 2 E I2``);

    - ``P_psi`` is the period of the body-frame motion, ``T = 4 K / p`` (:func:`period`): that of
      the rotation angle psi about the circulation axis and of the nutation theta;
    - ``P_phi`` is the mean precession period about L of the *circulation axis* (the long axis in
      LAM, the short axis in SAM): ``P_phi = 2 pi T / Delta phi`` (``Delta phi``:
      :func:`precession_per_period`). In SAM the long axis turns about L once per period less,
      with the mean period ``1 / (1 / P_phi - 1 / P_psi)``.

    Which axis's precession the asteroid literature calls ``P_phi`` in SAM is established here
    from published numbers, not from the papers' definitions (which were not read): Pravec et
    al., Icarus 233 (2014) 48, give for (99942) Apophis (SAM) ``P_phi = 27.38`` h, ``P_psi = 263``
    h and the strongest light-curve harmonic ``P1 = 30.56`` h, and ``1 / (1/27.38 - 1/263) =
    30.56`` h is the long axis's period only if ``P_phi`` is the short axis's
    (docs/gallery/tumbling-asteroids.md checks it).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending, I1 + I2 >= I3, kg m^2.

    Returns
    -------
    P_phi : ndarray, shape (...)
        Mean precession period of the circulation axis about L, s.
    P_psi : ndarray, shape (...)
        Period of the body-frame motion, s (``inf`` on the separatrix).
    mode : ndarray of str, shape (...)
        ``"SAM"`` or ``"LAM"``.

    Raises
    ------
    ValueError
        As :func:`period`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.periods import npa_periods, period
    >>> P_phi, P_psi, mode = npa_periods([0.3, 0.2, 1.0], [1.0, 2.0, 3.0])
    >>> str(mode), bool(np.isclose(P_psi, period([0.3, 0.2, 1.0], [1.0, 2.0, 3.0])))   # short-axis mode
    ('SAM', True)
    """
    T, dphi, _, sigma = _precession(*_check_motion(omega, moments))
    with np.errstate(divide="ignore", invalid="ignore"):
        P_phi = TWO_PI * T / dphi
    return P_phi, T, np.where(sigma > 0, "SAM", "LAM")


def _upward_crossings(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    k = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])


def axis_precession_period(traj: Trajectory, axis: int) -> float:
    """Mean precession period of a principal axis about L, measured on a sampled free motion, s.

    ``2 pi`` over the mean rate of the azimuth of body axis ``axis`` about L_world, unwrapped and
    linearly interpolated, between the first and last upward zero crossings of ``omega_2`` (the
    component along the intermediate axis changes sign in both modes, once upward per period): a
    whole number of body-frame periods, so the bounded part of the precession cancels.

    Parameters
    ----------
    traj : Trajectory
        Torque-free rigid motion, sampled densely (tens of samples per period or more) over at
        least two periods.
    axis : {1, 2, 3, 'minor', 'intermediate', 'major'}
        One principal axis (``I1 <= I2 <= I3``).

    Returns
    -------
    float
        s (negative if the axis turns against L).

    Raises
    ------
    ValueError
        If the trajectory is not torque-free and rigid, spans fewer than two upward crossings,
        or ``axis`` is not one principal axis.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.analysis.periods import axis_precession_period, npa_periods
    >>> body, omega0 = tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [0.3, 0.2, 1.0]
    >>> P_phi, P_psi, mode = npa_periods(omega0, body.principal_moments)
    >>> traj = tumble.simulate(body, omega0, t_end=5 * float(P_psi), samples=2001)
    >>> bool(np.isclose(axis_precession_period(traj, 3), P_phi, rtol=1e-4))   # the short axis, in SAM
    True
    """
    index = _axis_index(axis)
    if index.ndim:
        raise ValueError(f"axis = {axis!r} must be one axis: {AXES_ALLOWED}")
    up = _whole_periods(traj)
    t = traj.t
    Lw = traj.angular_momentum_world[0]
    z = Lw / np.linalg.norm(Lw)
    x = np.cross(z, [1.0, 0.0, 0.0] if abs(z[0]) < 0.9 else [0.0, 1.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    a = traj.attitude.apply(np.eye(3)[int(index)])
    az = np.unwrap(np.arctan2(a @ y, a @ x))
    rate = (np.interp(up[-1], t, az) - np.interp(up[0], t, az)) / (up[-1] - up[0])
    return float(TWO_PI / rate)


def _whole_periods(traj) -> np.ndarray:
    """Upward zero crossings of omega_2 on a checked free rigid trajectory, at least two, s."""
    _check_trajectory(traj)
    up = _upward_crossings(traj.t, traj.omega[:, 1])
    if len(up) < 2:
        raise ValueError(f"traj shows {len(up)} upward crossing(s) of omega_2; at least 2 (one full "
                         "period) are needed: run it longer or sample it more densely")
    return up


def npa_periods_measured(traj: Trajectory) -> tuple[float, float, str]:
    """``P_phi`` and ``P_psi`` measured on a sampled torque-free trajectory (:func:`npa_periods`).

    ``P_psi``: the mean interval between upward zero crossings of ``omega_2`` (the component
    along the intermediate axis changes sign in both modes, once upward per period), linearly
    interpolated. ``P_phi``: :func:`axis_precession_period` of the circulation axis (axis 1 in
    LAM, axis 3 in SAM).

    Parameters
    ----------
    traj : Trajectory
        Torque-free rigid motion, sampled densely (tens of samples per period or more) over at
        least two periods.

    Returns
    -------
    P_phi, P_psi : float
        s.
    mode : str
        ``"SAM"`` or ``"LAM"`` (from the initial state).

    Raises
    ------
    ValueError
        If the trajectory is not torque-free and rigid, or spans fewer than two upward crossings.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> from tumble.analysis.periods import npa_periods, npa_periods_measured
    >>> body, omega0 = tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [0.3, 0.2, 1.0]
    >>> P_phi, P_psi, mode = npa_periods(omega0, body.principal_moments)
    >>> traj = tumble.simulate(body, omega0, t_end=5 * float(P_psi), samples=2001)
    >>> phi, psi, measured_mode = npa_periods_measured(traj)
    >>> bool(np.isclose(phi, P_phi, rtol=1e-4)), bool(np.isclose(psi, P_psi, rtol=1e-4)), measured_mode
    (True, True, 'SAM')
    """
    up = _whole_periods(traj)
    mode = "SAM" if int(circulation_axis(traj.omega[0], traj.moments)) == 3 else "LAM"
    P_phi = axis_precession_period(traj, 3 if mode == "SAM" else 1)
    return P_phi, float((up[-1] - up[0]) / (len(up) - 1)), mode

