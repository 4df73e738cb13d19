"""What a run under a torque did beside the free body's summary (:mod:`tumble.analysis.summary`):
the gravity gradient's (relative to the orbiting frame), and the budgets of momentum and energy
against the torque itself, as ``tumble simulate`` writes them into summary.json."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics import Trajectory

if TYPE_CHECKING:
    from ..dynamics.models.gravity import GravityGradient
    from ..dynamics.models.torques import TorqueModel

__all__ = ["BUDGET_SAMPLES", "BUDGET_TURN", "gravity_gradient_summary", "orbit_gradient_summary", "torque_budget"]

#: Most samples :func:`torque_budget` calls a torque that varies in time at, one call each (~10 us).
BUDGET_SAMPLES = 100_000
#: Most rotation between samples (rad, ``max |omega| max dt``) at which :func:`torque_budget`'s
#: quadrature resolves a torque that turns with the body: a T-handle spun up by a world torque in the
#: gravity gradient gave a gap of 2e-9 of the impulse against an estimate of 3e-9 at 0.33 rad per
#: sample, and 1.1e-4 against 1e-5 at 3.3 rad (the estimate no longer holds; measured).
BUDGET_TURN = 0.5


def gravity_gradient_summary(traj: Trajectory, gg: GravityGradient, *, pitch_axis: int | str = 3,
                             yaw_axis: int | str = 1, alone: bool = True) -> dict[str, Any]:
    """What a run under the gravity gradient did, relative to the orbiting frame.

    Energy and L are not conserved under this torque; the orbiting-frame energy (the Jacobi
    integral, :meth:`tumble.GravityGradient.jacobi_integral`) is, and its relative drift is the
    run's error measure. Keys: ``orbit_period`` (s), ``orbits`` (run length in orbits),
    ``jacobi_drift`` (max |h - h0| over ``n^2 (I1 + I2 + I3)``, the scale of the potential),
    ``max_angle`` (rad: the largest |roll|, |pitch|, |yaw| from the orbiting frame, with
    ``pitch_axis`` and ``yaw_axis`` as in :func:`tumble.lvlh_state`), ``pitch_axis`` and ``yaw_axis`` (as
    given), ``region`` (the linear stability of the body at rest in the orbiting frame with those axes,
    :func:`~tumble.analysis.gravity_stability.gravity_gradient_stability`: ``"lagrange"``, ...),
    ``spin_over_n`` (``|omega0| / n``, the initial spin in units of the orbit's mean motion: 1 for a
    body at rest in the orbiting frame) and ``free_body`` (whether that spin is fast enough,
    :data:`~tumble.analysis.gravity_stability.FREE_BODY_SPIN` times ``n`` or more, for the free body's prediction in ``stability`` to
    say what the run does; below it the gradient's torque is not small beside the spin's
    gyroscopic terms; nor where the spin starts so near the separatrix, ``separatrix_offset``,
    that the gradient moves it: ``3 / spin_over_n^2`` at most
    :data:`~tumble.analysis.gravity_stability.SEPARATRIX_REACH` times the offset), ``symmetry_axis`` (``"roll"``, ``"pitch"`` or ``"yaw"`` where the body is
    symmetric about it, region ``"symmetric"``, else None) and ``symmetry_axis_tilt`` (rad, the
    largest angle of that axis from its place in the orbiting frame; the turn about it, free,
    shows in ``max_angle``). With other torques beside it
    (``alone=False``, a :class:`~tumble.dynamics.TorqueSum`) the Jacobi integral is not conserved and
    ``jacobi_drift`` is None; the run's budgets are :func:`torque_budget`'s.

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.torque_summary import gravity_gradient_summary
    >>> body, gg = tumble.t_handle(), tumble.GravityGradient(orbit_period=5400.0)
    >>> s = tumble.lvlh_state(gg, body)   # at rest in the orbiting frame, shaft along the local vertical
    >>> traj = tumble.simulate(body, s.omega0, attitude0=s.attitude0, torque=gg, t_end=2700.0, samples=50)
    >>> out = gravity_gradient_summary(traj, gg)
    >>> out["orbit_period"], round(out["orbits"], 6), out["jacobi_drift"] < 1e-12
    (5400.0, 0.5, True)
    >>> max(out["max_angle"].values()) < 1e-9   # it stays at rest in the orbiting frame
    True
    >>> out["region"]   # the shaft (axis 1, minor) along the vertical, pitch about the major axis: I_pitch > I_roll > I_yaw
    'lagrange'
    >>> round(out["spin_over_n"], 9), out["free_body"]   # turning with the orbiting frame: once an orbit
    (1.0, False)
    """
    from ..dynamics.models.gravity import orbit_frame_angles, relative_attitude
    from .gravity_stability import gravity_gradient_ratios, gravity_gradient_stability, spin_beside_orbit

    gg = gg.bind(traj.moments)
    h = gg.jacobi_integral(traj.t, traj.omega, traj.attitude)
    scale = gg.mean_motion**2 * float(np.sum(traj.moments))
    angles = orbit_frame_angles(traj, gg, pitch_axis=pitch_axis, yaw_axis=yaw_axis)
    ratios = gravity_gradient_ratios(traj.moments, pitch_axis=pitch_axis, yaw_axis=yaw_axis)
    region = str(gravity_gradient_stability(*ratios).region)
    k = [j for j in (2, 0, 1) if ratios[j] == 0.0][0] if region == "symmetric" else None  # yaw, roll, pitch: the first free
    tilt = None if k is None else float(np.max(np.arccos(np.clip(  # the rpy frame's axis k against the orbiting frame's
        relative_attitude(gg, traj.t, traj.attitude, pitch_axis=pitch_axis, yaw_axis=yaw_axis).as_matrix()[:, k, k], -1, 1))))
    return {
        "orbit_period": gg.period,
        "orbits": float(traj.t[-1] / gg.period),
        "jacobi_drift": float(np.max(np.abs(h - h[0])) / scale) if alone else None,
        "max_angle": {name: float(np.max(np.abs(getattr(angles, name)))) for name in ("roll", "pitch", "yaw")},
        "pitch_axis": pitch_axis,
        "yaw_axis": yaw_axis,
        "region": region,
        **spin_beside_orbit(traj.moments, traj.omega[0], gg.mean_motion),
        "symmetry_axis": None if k is None else ("roll", "pitch", "yaw")[k],
        "symmetry_axis_tilt": tilt,
    }


def orbit_gradient_summary(traj: Trajectory, orbit: Any) -> dict[str, Any]:
    """What a run under the gravity gradient of an ellipse or a TLE's orbit (``orbit``: its
    :class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`'s, with ``mean_motion``
    and ``period``) did: ``orbit_period`` (s), ``orbits``, ``spin_over_n`` and ``free_body`` as in
    :func:`gravity_gradient_summary`, ``n`` the mean motion; ``jacobi_drift``, ``max_angle`` and
    ``region`` None (on an orbit whose radius changes there is no Jacobi integral, and the
    circular orbit's frame and linear stability do not apply).

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.torque_summary import orbit_gradient_summary
    >>> from tumble.dynamics import KeplerOrbit
    >>> orbit = KeplerOrbit(8.0e6, 0.1, 0.9)   # a (m), e, inclination (rad)
    >>> traj = tumble.simulate(tumble.t_handle(), [0.0, 0.0, 0.002], t_end=100.0, samples=3)
    >>> out = orbit_gradient_summary(traj, orbit)
    >>> round(out["spin_over_n"], 2), out["free_body"], out["jacobi_drift"]   # twice the orbit rate
    (2.27, False, None)
    """
    from .gravity_stability import spin_beside_orbit

    return {"orbit_period": float(orbit.period), "orbits": float(traj.t[-1] / orbit.period), "jacobi_drift": None,
            "max_angle": None, "region": None, **spin_beside_orbit(traj.moments, traj.omega[0], orbit.mean_motion),
            "symmetry_axis": None, "symmetry_axis_tilt": None}


def torque_budget(traj: Trajectory, torque: TorqueModel) -> dict[str, Any] | None:
    """The momentum and energy budgets of a torqued run, against the torque along its own samples.

    Euler's equations give ``dL_world/dt = R tau`` and, for a rigid body, ``dT/dt = omega . tau``
    (Goldstein, *Classical Mechanics*, 3rd ed., sec. 5.5): the changes of ``L_world`` (body, rotors
    and damper together) and of the kinetic energy over the run must equal the torque's impulse and
    its work. Both integrals are taken over the samples by Simpson's rule
    (:func:`scipy.integrate.cumulative_simpson`), whose own error is estimated by Richardson's rule
    from every other sample (``|S_2h - S_h| / 15``): a ``gap`` within a few times ``quadrature``
    is a budget that closes as far as the samples can tell.

    Parameters
    ----------
    traj : Trajectory
        A run of :func:`tumble.simulate` under ``torque``.
    torque : torque model
        The run's torque, bound to the body (:func:`~tumble.dynamics.models.torques.bind_to_body`).

    Returns
    -------
    dict or None
        ``momentum`` and, for a rigid body, ``energy``: each ``gap`` (the largest difference of
        change and integral over the run; kg m^2/s or J), ``change`` (the largest integral, the
        scale), ``quadrature`` (the estimate of Simpson's error; None below 5 samples);
        ``turn_per_sample`` (rad, ``max |omega| max dt``) and ``resolved``, whether it is at most
        :data:`BUDGET_TURN` (else the quadrature, and its estimate, do not hold: more samples
        would). None below 3 samples, and for a torque that varies in time over more than
        :data:`BUDGET_SAMPLES` samples.

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.torque_summary import torque_budget
    >>> push = tumble.ConstantTorque((0.0, 0.0, 0.5), "world")
    >>> run = tumble.simulate(tumble.t_handle(), [0.1, 3.0, 0.1], t_end=10.0, torque=push)
    >>> budget = torque_budget(run, push)
    >>> momentum = budget["momentum"]
    >>> round(momentum["change"], 12), momentum["gap"] < 1e-9 * momentum["change"], budget["resolved"]   # |tau| t
    (5.0, True, True)
    """
    from scipy.integrate import cumulative_simpson

    from ..dynamics.models.torque_protocols import constant_terms
    from ..dynamics.models.torques import body_torque, kernel_form

    t, omega, attitude = traj.t, traj.omega, traj.attitude
    if len(t) < 3:  # Simpson's rule needs three samples; one sample has no change to check
        return None
    if constant_terms(kernel_form(torque)) is not None:
        tau = np.array(np.broadcast_to(body_torque(torque, 0.0, omega, attitude), omega.shape))  # constant: one call
    elif len(t) <= BUDGET_SAMPLES:
        tau = np.array([body_torque(torque, float(ti), omega[i], attitude[i]) for i, ti in enumerate(t.tolist())])
    else:
        return None

    def budget(change: np.ndarray, rate: np.ndarray) -> dict[str, float | None]:
        integral = cumulative_simpson(rate, x=t, axis=0, initial=0.0)
        coarse = cumulative_simpson(rate[::2], x=t[::2], axis=0, initial=0.0) if len(t) >= 5 else None
        return {"gap": float(np.max(np.abs(change - integral))), "change": float(np.max(np.abs(integral))),
                "quadrature": None if coarse is None else float(np.max(np.abs(integral[::2] - coarse)) / 15.0)}

    L = traj.angular_momentum_world
    out: dict[str, Any] = {"momentum": budget(L - L[0], attitude.apply(tau))}
    if traj.rigid:
        out["energy"] = budget(traj.energy - traj.energy[0], np.sum(omega * tau, axis=1))
    turn = float(np.max(np.linalg.norm(omega, axis=1)) * np.max(np.diff(t)))
    return {**out, "turn_per_sample": turn, "resolved": turn <= BUDGET_TURN}
