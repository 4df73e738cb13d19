"""What a trajectory says about stability: the summary written by ``tumble simulate``."""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from .._html import fmt, plural, result_html, result_repr
from ..dynamics import BatchTrajectory, Trajectory
from ..mass import AXIS_ROLES, moment_degeneracy
from ..validation import short_repr
from .stability import SpinPrediction, flip_interval, flip_interval_asymptotic, flip_times, linearised_rate, spin_prediction

__all__ = ["SAMPLES_PER_FLIP", "StabilityReport", "axis_role", "stability_report", "trajectory_summary"]

#: Fewest samples per flip interval at which flips are counted (a sign change of a component between
#: samples): below it the count and the measured period are aliased (:func:`stability_report`'s
#: ``samples_per_flip``; 0.04 s samples on 0.031 s flips counted 357 of ~640, the period 80 % off).
SAMPLES_PER_FLIP = 4.0
#: Off-axis share of omega (``|omega_perp| / |omega_axis|``) at or below which a spin about an
#: unstable axis is said to be there but for round-off (a start turned from the design frame).
ROUND_OFF_AXIS = 1e-12


class StabilityReport(dict):  # type: ignore[type-arg]
    """What :func:`stability_report` returns: a dict of its keys (written to JSON as it is), shown
    as one line, ``StabilityReport(axis 2 (intermediate): unstable, 11 flips, one every 1.786 s)``,
    and as a table in a notebook.

    Examples
    --------
    >>> import tumble
    >>> report = tumble.stability_report(tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=20.0))
    >>> report
    StabilityReport(axis 2 (intermediate): unstable, 11 flips, one every 1.786 s)
    >>> report["flips"], isinstance(report, dict)
    (11, True)
    >>> "1.786 s" in report._repr_html_()   # the notebook's table: the numbers with their units
    True
    """

    __slots__ = ()

    def __getattr__(self, name: str) -> Any:
        """Its keys as attributes too (``report.flips``, as ``report["flips"]``); a name that is no key is
        refused naming the keys (a walkthrough's ``report.flips`` met a bare AttributeError).

        Examples
        --------
        >>> import tumble
        >>> report = tumble.stability_report(tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=20.0))
        >>> report.flips, report.role
        (11, 'intermediate')
        """
        if name.startswith("__") or name not in self:
            raise AttributeError(f"StabilityReport has no {name!r}; its keys: {', '.join(self)}")
        return self[name]

    def _parts(self) -> list[str]:
        if self.get("axis") is None:
            return ["at rest: no spin axis", plural(int(self.get("flips") or 0), "flip")]
        why = "" if self.get("theory") in ("rigid body", None) else f" ({self['theory']})"
        parts = [f"axis {self['axis']} ({self['role']}): {self.get('predicted') or 'no prediction'}{why}"]
        if self.get("flips") is not None:
            parts.append(plural(int(self["flips"]), "flip"))
        if self.get("flip_period") is not None:
            parts.append(f"one every {fmt(self['flip_period'])} s")  # the flip interval: half omega's period
        if self.aliased:
            parts.append(f"too few samples to count flips ({fmt(self['samples_per_flip'], 2)} per flip)")
        if self.get("note"):
            parts.append(self["note"])
        return parts

    @property
    def aliased(self) -> bool:
        """Whether the samples are too sparse to count the flips (:data:`SAMPLES_PER_FLIP`).

        Examples
        --------
        >>> import tumble
        >>> run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=20.0, samples=11)   # flips every 1.8 s
        >>> report = tumble.stability_report(run)
        >>> report.aliased, round(report["samples_per_flip"], 2)
        (True, 0.89)
        """
        n = self.get("samples_per_flip")
        return n is not None and n < SAMPLES_PER_FLIP

    def __repr__(self) -> str:
        return result_repr("StabilityReport", self._parts())

    #: The unit of each key that has one.
    UNITS: ClassVar[dict[str, str]] = {"growth_rate": "1/s", "wobble_frequency": "rad/s", "flip_period": "s",
                                       "flip_period_exact": "s", "flip_period_asymptotic": "s", "samples_per_flip": ""}

    def _repr_html_(self) -> str:
        return result_html("StabilityReport", [
            (key, "none" if value is None else f"{fmt(value)} {self.UNITS[key]}".rstrip() if key in self.UNITS else value)
            for key, value in self.items()])


def stability_report(traj: Trajectory | BatchTrajectory) -> StabilityReport | list[StabilityReport]:
    """Prediction against observation for the spin axis, classified by the motion itself.

    The spin axis is the principal axis nearest the initial angular momentum and a rigid body's
    prediction follows its circulation (from the energy and ``|L|``), as a sweep's columns do
    (:func:`tumble.analysis.stability.spin_prediction`; docs/conventions.md, "Spin axis,
    circulation and flips"): a spin axis that is not the circulation axis turns over, even when
    it carries the largest component of omega.

    Parameters
    ----------
    traj : Trajectory or BatchTrajectory
        A run of :func:`tumble.simulate`, or a batch of :func:`tumble.simulate_batch` (then one
        report per body, a list in the batch's order).

    Returns
    -------
    StabilityReport (a list of them for a batch)
        A dict, shown on one line (:class:`StabilityReport`).
        Keys: ``axis`` (1, 2 or 3, principal, ascending moments: the largest ``|I_j omega_j|`` at
        the start; None for a body starting at rest, and then every prediction is None),
        ``role``, ``circulation`` (1 or 3, the axis omega circulates about, torque-free theory of
        the initial state; for a symmetric body "transverse, I2 = I3" or the symmetry axis, as
        it has no intermediate axis), ``predicted`` ("stable" or "unstable"), ``growth_rate`` (1/s) or
        ``wobble_frequency`` (rad/s) of the linearised theory about the spin axis (None where it
        does not say what the motion does), ``flips`` (sign changes of that component in the
        run; None where the samples are too few to count them, below), ``flip_period`` (measured
        mean time between flips, s, or None with fewer than two flips or too few samples),
        ``flip_period_exact`` (the elliptic-function interval, s, when the spin axis is
        not the circulation axis; torque-free only), ``flip_period_asymptotic`` (its
        small-perturbation logarithmic form), ``samples_per_flip`` (the flip interval, exact, or
        under a torque the shorter of the measured one and the start's torque-free one, over the widest
        sample spacing; below :data:`SAMPLES_PER_FLIP` the sign changes
        seen are aliased, not the flips: ``flips`` and ``flip_period`` are None and the repr says
        so), ``theory`` (what the prediction rests on:
        ``"rigid body"`` (the circulation; with a torque that of the initial state),
        ``"gyrostat"`` for rotors whose momentum lies along the spin axis (the linearised
        theory), ``"energy sink"`` with a damper (the major-axis rule: only spin about the major
        axis is stable), or None when no theory applies, e.g. rotor momentum across the spin
        axis; then ``predicted`` is None), ``note`` (None, or what the numbers do not say: a
        symmetric body's turning over is its slow roll, not the tennis-racket flip; a spin exactly
        about the intermediate axis flips only once perturbed).
        Flip periods from the elliptic closed form are given for a rigid, torque-free body only.

    Examples
    --------
    >>> import tumble
    >>> traj = tumble.simulate(tumble.t_handle(), [0.0, 10.0, 0.0], frame="design", t_end=5.0, samples=100)
    >>> report = tumble.stability_report(traj)   # a spin about the crossbar-normal y: the major axis
    >>> report["axis"], report["role"], report["predicted"], report["flips"]
    (3, 'major', 'stable', 0)
    >>> traj = tumble.simulate(tumble.t_handle(), [10.0, 0.1, 0.1], frame="design", t_end=5.0, samples=1000)
    >>> report = tumble.stability_report(traj)   # about the crossbar x: the intermediate axis
    >>> report["role"], report["predicted"], report["flips"] > 2
    ('intermediate', 'unstable', True)
    >>> abs(report["flip_period"] - report["flip_period_exact"]) / report["flip_period_exact"] < 0.01
    True
    >>> batch = tumble.simulate_batch([1.0, 2.0, 3.0], [[0.01, 1.0, 0.0], [0.0, 0.0, 1.0]], t_end=30.0, samples=301)
    >>> [r["predicted"] for r in tumble.stability_report(batch)]   # one report per body
    ['unstable', 'stable']

    Far from every axis the largest component of omega does not say what the motion does:

    >>> traj = tumble.simulate(tumble.t_handle(), [8.3, 8.2, 7.5], t_end=5.0, samples=500)   # principal frame
    >>> report = tumble.stability_report(traj)
    >>> report["axis"], report["circulation"], report["predicted"], report["flips"]
    (3, 3, 'stable', 0)
    >>> tumble.stability_report(tumble.t_handle())   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    TypeError: traj = Body('T-handle', ...) is not a run: give what tumble.simulate or tumble.simulate_batch returns (a Trajectory or a BatchTrajectory)
    """
    if isinstance(traj, BatchTrajectory):  # each body as a run of its own (batch[i] is its Trajectory)
        return [stability_report(traj[i]) for i in range(len(traj))]
    if not isinstance(traj, Trajectory):
        raise TypeError(f"traj = {short_repr(traj)} is not a run: give what tumble.simulate or tumble.simulate_batch "
                        f"returns (a Trajectory or a BatchTrajectory)")
    w0 = traj.omega[0]
    if not np.any(w0):
        return StabilityReport(axis=None, role=None, circulation=None, predicted=None, growth_rate=None,
                               wobble_frequency=None, flips=0, flip_period=None, flip_period_exact=None,
                               flip_period_asymptotic=None, theory=None, samples_per_flip=None, note=None)
    I = traj.moments
    motion = spin_prediction(w0, I)
    a, circulation = int(motion.axis), int(motion.circulation)  # 1, 2 or 3; 1 or 3
    theory, predicted, growth, wobble = _prediction(traj, motion)
    degeneracy = moment_degeneracy(I)
    distinct = degeneracy == "asymmetric"
    times = flip_times(traj.t, traj.omega[:, a - 1])
    note = None
    if not distinct and traj.rigid:
        note = ("a spherical body: every axis is principal" if degeneracy == "spherical" else
                "a symmetric body: what turns over is its slow roll about the symmetry axis, not the tennis-racket "
                "flip" if len(times) else _roll_note(w0, I, a))
    elif predicted == "unstable" and not len(times) and np.count_nonzero(w0) == 1:
        note = "a spin exactly about the axis: an unstable equilibrium, which flips only once perturbed"
    elif predicted == "unstable" and (off := float(np.hypot(*np.delete(w0, a - 1)))) <= ROUND_OFF_AXIS * abs(w0[a - 1]):
        # a spin meant to be exact, turned from the design frame (a teacher's box turned 30 deg: 8.9e-16 off), flips
        note = (f"a spin within round-off of the axis ({off / abs(w0[a - 1]):.1e} of it off): it flips as a perturbed one "
                "does, the perturbation the round-off of its start")
    exact = asymptotic = free = None
    if traj.rigid and distinct and a != circulation:
        # the component about which omega circulates never changes sign; the other two flip
        value = float(flip_interval(w0, I))
        free = value if np.isfinite(value) else None
        if traj.torque_free and free is not None:
            exact = free
            asymptotic = float(flip_interval_asymptotic(w0, I))
    measured = float(np.mean(np.diff(times))) if len(times) >= 2 else None
    # under a torque, the start's torque-free interval too, the shorter: aliased samples count few sign changes
    # and give no interval (reduce_cases' rule)
    interval = exact if exact is not None else min((x for x in (measured, free) if x is not None), default=None)
    spacing = float(np.max(np.diff(traj.t))) if len(traj.t) >= 2 else None
    per_flip = interval / spacing if interval is not None and spacing else None
    # aliased: the sign changes seen are not the flips (a 1e9 s run wrote "flips": 43 of ~5.6e8), so neither is given
    counted = per_flip is None or per_flip >= SAMPLES_PER_FLIP
    return StabilityReport({
        "axis": a,
        "role": axis_role(I, a, degeneracy),
        "circulation": circulation,
        "predicted": predicted,
        "growth_rate": growth if growth > 0 else None,
        "wobble_frequency": wobble if wobble > 0 else None,
        "flips": len(times) if counted else None,
        "flip_period": float(np.mean(np.diff(times))) if len(times) >= 2 and counted else None,
        "flip_period_exact": exact,
        "flip_period_asymptotic": asymptotic,
        "theory": theory,
        # the flip interval over the widest sample spacing: below SAMPLES_PER_FLIP the flips counted are aliased
        "samples_per_flip": per_flip,
        "note": note,
    })


def _symmetry_axis(I: Any) -> int:
    """The symmetry axis (1 or 3) of a symmetric body of moments ``I`` (ascending): 1 where I2 = I3 (prolate),
    else 3 (oblate, I1 = I2): the pair nearer equal decides."""
    return 1 if I[1] - I[0] > I[2] - I[1] else 3


def _roll_note(w0: Any, I: Any, a: int) -> str | None:
    """For a symmetric body spun across its symmetry axis with no flip seen: that nothing grows, and when its
    spin turns over, rolling about the symmetry axis at the body rate of a free top (Landau & Lifshitz
    sec. 33; a teacher's walkthrough found a rod's end-over-end spin called "unstable, 0 flips" with no word)."""
    from .periods import symmetric_top_rates

    if a == _symmetry_axis(I):  # about the symmetry axis itself: nothing to say
        return None
    rate = abs(float(symmetric_top_rates(w0, I)[1]))
    when = f"every {np.pi / rate:.4g} s" if rate > 0 else "never"
    return (f"a symmetric body spun across its symmetry axis: no perturbation grows; the spin rolls about the "
            f"symmetry axis and turns over {when}, not the tennis-racket flip")


def axis_role(I: Any, a: int, degeneracy: str) -> str:
    """Principal axis ``a``'s role (1, 2 or 3, moments ``I`` ascending, kg m^2, of
    :func:`tumble.mass.moment_degeneracy` ``degeneracy``): ``AXIS_ROLES``' for an asymmetric body;
    a symmetric one's symmetry axis or a transverse axis (two equal moments: no intermediate axis);
    any axis of a spherical one.

    Examples
    --------
    >>> from tumble.analysis.summary import axis_role
    >>> [axis_role([1.0, 2.0, 3.0], a, "asymmetric") for a in (1, 2, 3)]
    ['minor', 'intermediate', 'major']
    >>> [axis_role([2.0, 2.0, 3.0], a, "symmetric") for a in (1, 2, 3)]
    ['transverse, I1 = I2', 'transverse, I1 = I2', 'major, the symmetry axis']
    """
    if degeneracy == "asymmetric":
        return AXIS_ROLES[a - 1]
    if degeneracy == "spherical":
        return "any axis: spherical"
    if a == _symmetry_axis(I):
        return f"{AXIS_ROLES[a - 1]}, the symmetry axis"
    return "transverse, " + ("I2 = I3" if _symmetry_axis(I) == 1 else "I1 = I2")


def _prediction(traj: Trajectory, motion: SpinPrediction) -> tuple[str | None, str | None, float, float]:
    """``(theory, predicted, growth, wobble)`` for spin about ``motion.axis`` (1-based)."""
    a = int(motion.axis)
    W = traj.omega[0, a - 1]
    if traj.damper_omega is not None:  # energy sink: the major-axis rule (Likins 1966)
        return "energy sink", "stable" if a == 3 else "unstable", 0.0, 0.0
    h = 0.0
    if traj.internal_momentum is not None:
        h0 = traj.internal_momentum[0]
        across = np.delete(h0, a - 1)
        if np.max(np.abs(across)) > 1e-12 * max(float(np.linalg.norm(h0)), 1e-300):
            return None, None, 0.0, 0.0  # rotor momentum across the spin: no steady spin to perturb
        h = float(h0[a - 1])
    if traj.rigid:  # the circulation says what the motion does; the linear theory where it agrees
        return "rigid body", ("stable" if motion.stable else "unstable"), float(motion.growth), float(motion.wobble)
    growth, wobble = (float(x) for x in linearised_rate(traj.moments, a, W, h))
    return "gyrostat", ("unstable" if growth > 0 else "stable"), growth, wobble


def trajectory_summary(traj: Trajectory) -> dict:
    """The JSON summary of a run (``summary.json``): inputs, invariants, drift and stability.

    Parameters
    ----------
    traj : Trajectory
        A run of :func:`tumble.simulate`.

    Returns
    -------
    dict
        Keys: ``body``, ``principal_moments`` ([I1, I2, I3] ascending, kg m^2), ``principal_axes``
        (the 3x3 matrix ``traj.principal_axes`` as nested lists, row by row: principal -> design,
        its *columns* are the axes of I1, I2, I3 in the design frame, so
        ``np.array(summary["principal_axes"]) == traj.principal_axes``), ``method``, ``t_end`` (s),
        ``samples``, ``omega0`` (rad/s, principal frame), ``torque_free``, ``energy`` (J),
        ``L_norm`` (kg m^2/s), ``drift`` (relative) and ``stability`` (:func:`stability_report`);
        with rotors ``rotors`` (``internal_momentum0``, kg m^2/s, principal frame; ``motor_work``, J),
        with a damper ``damper`` (``inertia``, ``dissipated`` J, ``nutation_angle`` [start, end] rad,
        ``flat_spin_rate`` ``|L| / (I3 + J)`` the major-axis rule predicts and ``final_spin_rate``,
        rad/s). Energy, L and drift are totals over body, rotors and damper.

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.summary import trajectory_summary
    >>> summary = trajectory_summary(tumble.simulate(tumble.t_handle(), [0.0, 0.0, 2.0], t_end=1.0, samples=11))
    >>> summary["body"], summary["samples"], summary["principal_moments"], round(summary["energy"], 6)
    ('T-handle', 11, [0.125, 0.3125, 0.4375], 0.875)
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
        **_budgets(traj),
    }


def _budgets(traj: Trajectory) -> dict:
    """The internal models' part of the summary: what the motors did and the damper spent."""
    out = {}
    if traj.internal_momentum is not None:
        out["rotors"] = {
            "internal_momentum0": traj.internal_momentum[0].tolist(),
            "motor_work": None if traj.motor_work is None else float(traj.motor_work[-1]),
        }
    if traj.damper_omega is not None:
        L = float(traj.angular_momentum_norm[0])
        out["damper"] = {
            "inertia": traj.damper_inertia,
            "dissipated": float(traj.dissipated[-1]),
            "nutation_angle": [float(traj.nutation_angle[0]), float(traj.nutation_angle[-1])],
            # the major-axis rule's end state: a flat spin about axis 3 with the sphere locked
            "flat_spin_rate": L / (traj.moments[2] + traj.damper_inertia),
            "final_spin_rate": float(np.linalg.norm(traj.omega[-1])),
        }
    return out
