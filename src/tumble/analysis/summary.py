"""What a trajectory says about stability: the summary written by ``tumble simulate``."""

from __future__ import annotations

import numpy as np

from ..dynamics import Trajectory
from ..mass import AXIS_ROLES, moment_degeneracy
from .stability import (
    axis_of,
    circulation_axis,
    flip_interval,
    flip_interval_asymptotic,
    flip_times,
    linearised_rate,
)

__all__ = ["stability_report", "trajectory_summary"]


def stability_report(traj: Trajectory) -> dict:
    """Prediction against observation for the axis that carries most of the initial spin.

    Keys: ``axis`` (1, 2 or 3, principal, ascending moments; None for a body starting at
    rest, and then every prediction is None), ``role``, ``predicted``
    ("stable" or "unstable", the linearised theory), ``growth_rate`` (1/s) or
    ``wobble_frequency`` (rad/s) of that theory, ``flips`` (sign changes of that component in
    the run), ``flip_period`` (measured mean time between flips, s, or None with fewer than two
    flips), ``flip_period_exact`` (the elliptic-function interval, s, when theory says this
    component flips; torque-free only), ``flip_period_asymptotic`` (its small-perturbation
    logarithmic form).
    """
    w0 = traj.omega[0]
    if not np.any(w0):
        return {"axis": None, "role": None, "predicted": None, "growth_rate": None,
                "wobble_frequency": None, "flips": 0, "flip_period": None, "flip_period_exact": None,
                "flip_period_asymptotic": None}
    a = int(axis_of(w0))  # 1, 2 or 3
    I = traj.moments
    growth, wobble = (float(x) for x in linearised_rate(I, a, w0[a - 1]))
    distinct = moment_degeneracy(I) == "asymmetric"
    times = flip_times(traj.t, traj.omega[:, a - 1])
    exact = asymptotic = None
    if traj.torque_free and distinct:
        # the component about which omega circulates never changes sign; the other two flip
        value = float(flip_interval(w0, I))
        if a != int(circulation_axis(w0, I)) and np.isfinite(value):
            exact = value
            asymptotic = float(flip_interval_asymptotic(w0, I))
    return {
        "axis": a,
        "role": AXIS_ROLES[a - 1],
        "predicted": "unstable" if growth > 0 else "stable",
        "growth_rate": growth if growth > 0 else None,
        "wobble_frequency": wobble if wobble > 0 else None,
        "flips": len(times),
        "flip_period": float(np.mean(np.diff(times))) if len(times) >= 2 else None,
        "flip_period_exact": exact,
        "flip_period_asymptotic": asymptotic,
    }


def trajectory_summary(traj: Trajectory) -> dict:
    """The JSON summary of a run (``summary.json``): inputs, invariants, drift and stability.

    Keys: ``body``, ``principal_moments`` ([I1, I2, I3] ascending, kg m^2), ``principal_axes``
    (the 3x3 matrix ``traj.principal_axes`` as nested lists, row by row: principal -> design,
    its *columns* are the axes of I1, I2, I3 in the design frame, so
    ``np.array(summary["principal_axes"]) == traj.principal_axes``), ``method``, ``t_end`` (s),
    ``samples``, ``omega0`` (rad/s, principal frame), ``torque_free``, ``energy`` (J),
    ``L_norm`` (kg m^2/s), ``drift`` (relative) and ``stability`` (:func:`stability_report`).
    """
    return {
        "body": traj.body_name,
        "principal_moments": traj.moments.tolist(),
        "principal_axes": traj.principal_axes.tolist(),
        "method": traj.method,
        "t_end": float(traj.t[-1]),
        "samples": len(traj),
        "omega0": traj.omega[0].tolist(),
        "torque_free": traj.torque_free,
        "energy": float(traj.energy[0]),
        "L_norm": float(traj.angular_momentum_norm[0]),
        "drift": traj.drift,
        "stability": stability_report(traj),
    }
