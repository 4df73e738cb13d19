"""Whether MRP feedback held between control steps is stable: the sampled-data loop, axis by axis.

Near its target the law ``L_r = -K sigma - P omega - z`` (``z = Ki K int sigma dt``) drives each
principal axis as ``I theta'' = -(K / 4) (theta + Ki s) - P theta'`` with ``sigma ~ theta / 4`` and
``s' = theta`` (Schaub & Junkins, *Analytical Mechanics of Space Systems*, 4th ed., secs. 8.2-8.4;
docs/control.md). The controller reads the state every ``T`` s and holds its torque in between:
the zero-order-hold equivalent of that double integrator (Franklin, Powell & Workman, *Digital
Control of Dynamic Systems*, 3rd ed., 1998: ``x_{k+1} = Phi x_k + Gamma u_k`` with ``Phi`` and
``Gamma`` of ``theta'' = u / I`` over ``T``), with the integral summed as the controller sums it
(``s_{k+1} = s_k + T theta_k``, used from the next step), is

    theta_{k+1} = theta_k + T omega_k + T^2 u_k / (2 I)
    omega_{k+1} = omega_k + T u_k / I
    s_{k+1}     = s_k + T theta_k,          u_k = -(K / 4) (theta_k + Ki s_k) - P omega_k,

stable when every eigenvalue of its matrix lies inside the unit circle. Too long a period makes
the rate loop overshoot (``omega_{k+1} ~ (1 - P T / I) omega_k``: unstable past ``P T / I = 2``); too
large an integral gain destabilises even the continuous loop (``Ki < P / I``, Routh-Hurwitz). A
walkthrough's 3U CubeSat held for 2.5 s (``P T / I1 = 2.24``) tumbled at 0.38 rad/s without a word
(issue 40); :class:`~tumble.dynamics.control.controllers.MRPFeedback` now warns
(:class:`UnstableLoopWarning`). Far from the target (saturated wheels, large angles) this linear
check says nothing either way.
"""

from __future__ import annotations

import warnings

import numpy as np

from ...typing import ArrayLike, FloatArray

__all__ = ["LongPeriodWarning", "OneStepWarning", "UnstableLoopWarning", "WeakLoopWarning", "check_bdot_loop",
           "check_held_loop", "check_period_in_orbit", "held_loop_radius"]

#: The longest control period, as a share of the orbit's, that :func:`check_period_in_orbit` takes
#: without a word: the field turns twice an orbit in the body of an inertially held spacecraft,
#: and control periods are 0.1-10 s against orbits of 5,400 s and more.
ORBIT_SHARE = 0.1

#: :class:`WeakLoopWarning` where B-dot's slowest time constant is more than this many runs long
#: and longer than :data:`WEAK_TIME`.
WEAK_RUNS = 100.0
#: A year, s: no detumble takes so long (Avanzini & Giulietti's gain: ``I3 / k`` ~ 500 ``I3 / I1``
#: s), while a normalised gain read as classic gives 1e11-1e13 s in low orbit. A short run of a
#: right gain (a few seconds of an hours-long detumble) is no slip.
WEAK_TIME = 365.25 * 86400.0


class UnstableLoopWarning(UserWarning):
    """MRP feedback whose gains and period make the held loop unstable (:func:`check_held_loop`).

    A command prints it on one line (``warning: ...``) and goes on: a study of an unstable loop is a
    study one may want.

    Examples
    --------
    >>> from tumble.dynamics.control.sampled import UnstableLoopWarning
    >>> issubclass(UnstableLoopWarning, UserWarning)
    True
    """

    cli_one_line = True


class WeakLoopWarning(UserWarning):
    """B-dot whose gain is too weak to change the rate within the run (:func:`check_bdot_loop`):
    most often a normalised gain (N m s, :func:`~tumble.dynamics.control.bdot.bdot_gain`'s) taken
    as classic (A m^2 s/T), ~1e9 times too weak in low orbit. A command prints it on one line.

    Examples
    --------
    >>> from tumble.dynamics.control.sampled import WeakLoopWarning
    >>> WeakLoopWarning.cli_one_line
    True
    """

    cli_one_line = True


class LongPeriodWarning(UserWarning):
    """A control period that is a large share of the orbit (:func:`check_period_in_orbit`): the
    field and an orbiting target turn far between commands. A command prints it on one line.

    Examples
    --------
    >>> from tumble.dynamics.control.sampled import LongPeriodWarning
    >>> LongPeriodWarning.cli_one_line
    True
    """

    cli_one_line = True


def check_period_in_orbit(period: float, orbit_period: float) -> None:
    """Warn (:class:`LongPeriodWarning`) where the control ``period`` (s) is more than
    :data:`ORBIT_SHARE` of the ``orbit_period`` (s). A walkthrough's B-dot held 6000 s on a 5677 s
    orbit, with a small gain, ran with no word of it.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics.control.sampled import check_period_in_orbit
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_period_in_orbit(1.0, 5677.0)
    ...     check_period_in_orbit(6000.0, 5677.0)
    >>> len(caught), str(caught[0].message)[:59]
    (1, 'period = 6000 s is more than a tenth of the orbit (5677 s):')
    """
    if period > ORBIT_SHARE * orbit_period:
        warnings.warn(f"period = {period:g} s is more than a tenth of the orbit ({orbit_period:.4g} s): the field and an "
                      f"orbiting target turn through {360.0 * period / orbit_period:.3g} deg of the orbit between "
                      "commands; give a period of seconds (one in ms written as s?)", LongPeriodWarning, stacklevel=3)


class OneStepWarning(UserWarning):
    """A controller whose period is not shorter than the run: it acts once, at t = 0, and the run
    (whose samples are the control instants) has two samples. Likely a period in milliseconds
    written as seconds; a command prints it on one line and goes on.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.sampled import OneStepWarning
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> with warnings.catch_warnings(record=True) as seen:
    ...     warnings.simplefilter("always")
    ...     run = simulate_controlled([0.03, 0.04, 0.05], [0.1, 0.2, 0.3], t_end=100.0, controller=BDot(gain=1e5, period=500.0),
    ...                               magnetorquers=Magnetorquers(0.2), field=UniformField((2e-5, 0.0, 0.0)))
    >>> [w.category.__name__ for w in seen], len(run.t)
    (['OneStepWarning'], 2)
    """

    cli_one_line = True


def _matrix(I: float, K: float, P: float, T: float, Ki: float) -> FloatArray:
    c, p = 0.25 * K / I, P / I
    return np.array([[1.0 - 0.5 * c * T * T, T - 0.5 * p * T * T, -0.5 * c * Ki * T * T],
                     [-c * T, 1.0 - p * T, -c * Ki * T],
                     [T, 0.0, 1.0]])


def held_loop_radius(moments: ArrayLike, K: float, P: float, period: float, Ki: float = 0.0) -> FloatArray:
    """The spectral radius of MRP feedback's held loop about each principal axis (module docstring).

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments, kg m^2.
    K, P : float
        The attitude (N m) and rate (N m s) gains.
    period : float
        The control period, s.
    Ki : float
        The integral gain, 1/s.

    Returns
    -------
    ndarray, shape (3,)
        Above 1 the loop about that axis diverges.

    Examples
    --------
    >>> from tumble.dynamics.control.sampled import held_loop_radius
    >>> I = [0.00667, 0.0419, 0.0419]   # a 3U CubeSat, kg m^2
    >>> bool(held_loop_radius(I, 1.1e-3, 6e-3, 2.0).max() < 1), bool(held_loop_radius(I, 1.1e-3, 6e-3, 2.5)[0] > 1)
    (True, True)
    """
    values = []
    for I in np.asarray(moments, float):
        A = _matrix(float(I), K, P, period, Ki)
        values.append(float(np.max(np.abs(np.linalg.eigvals(A if Ki > 0.0 else A[:2, :2])))))
    return np.array(values)


def check_held_loop(moments: ArrayLike, K: float, P: float, period: float, Ki: float = 0.0) -> None:
    """Warn (:class:`UnstableLoopWarning`) where MRP feedback's held loop is unstable about an axis,
    naming the setting to change: ``Ki`` where even the continuous loop is (``Ki >= P / I``), else
    ``period``, with the longest that is stable.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics.control.sampled import check_held_loop
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_held_loop([0.00667, 0.0419, 0.0419], 1.1e-3, 6e-3, 2.5)
    >>> print(caught[0].message)   # doctest: +NORMALIZE_WHITESPACE
    period = 2.5 s: MRP feedback held that long is unstable about principal axis 1 (I = 0.00667 kg m^2, a pole
    of magnitude 1.26 > 1: P T / I = 2.25, K T^2 / I = 1.03); the longest stable period is 2.22 s
    """
    I = np.asarray(moments, float)
    radius = held_loop_radius(I, K, P, period, Ki)
    if not np.any(radius > 1.0 + 1e-12):
        return
    axis = int(np.argmax(radius))
    if Ki > 0.0 and Ki >= P / I[axis]:
        message = (f"Ki = {Ki:g} 1/s: MRP feedback's integral term makes the loop unstable about principal axis "
                   f"{axis + 1} (I = {I[axis]:.3g} kg m^2): it needs Ki < P / I = {P / I[axis]:.3g} 1/s")
        # the period too, judged without the integral term: both named, not the one that hides the other
        free = held_loop_radius(I, K, P, period)
        if np.any(free > 1.0 + 1e-12):
            worst = int(np.argmax(free))
            message += (f"; and period = {period:g} s is unstable even without it about principal axis {worst + 1} "
                        f"(the longest stable period without it is {_longest_period(I[worst], K, P, period, 0.0):.3g} s)")
    else:
        message = (f"period = {period:g} s: MRP feedback held that long is unstable about principal axis {axis + 1} "
                   f"(I = {I[axis]:.3g} kg m^2, a pole of magnitude {radius[axis]:.3g} > 1: P T / I = "
                   f"{P * period / I[axis]:.3g}, K T^2 / I = {K * period**2 / I[axis]:.3g}); the longest stable period is "
                   f"{_longest_period(I[axis], K, P, period, Ki):.3g} s")
    warnings.warn(message, UnstableLoopWarning, stacklevel=3)


def _longest_period(I: float, K: float, P: float, period: float, Ki: float) -> float:
    """The longest stable hold period below ``period`` (s) about an axis of moment ``I``, by
    bisection on :func:`held_loop_radius`."""
    lo, hi = 0.0, float(period)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if held_loop_radius([I], K, P, mid, Ki)[0] <= 1.0 else (lo, mid)
    return lo


def check_bdot_loop(moments: ArrayLike, gain: float, period: float, field_max: float | None = None,
                    t_end: float | None = None) -> None:
    """Warn (:class:`UnstableLoopWarning`) where B-dot held for ``period`` (s) overshoots, and
    (:class:`WeakLoopWarning`) where its slowest time constant, ``I3 / k`` (``I3 / (k_b |B|^2)``
    classic, at the largest ``|B|``: the longest it can be is longer still), is more than
    :data:`WEAK_RUNS` times the run's ``t_end`` (s) and longer than a year (:data:`WEAK_TIME`):
    the rate is then left as it was. Normalised
    (``field_max`` None), its torque ``-k omega_perp`` (:mod:`~tumble.dynamics.control.bdot`) held
    over ``T`` takes each rate across the field as ``omega_{k+1} ~ (1 - k T / I) omega_k``, which
    grows past ``k T / I = 2`` (the rate loop of the module docstring with ``P = k``); worst about
    the smallest moment. Classic (``m = -k_b dB/dt``, ``dB/dt = B x omega`` in the body), its torque
    ``m x B = -k_b |B|^2 omega_perp`` is the same loop with ``k = k_b |B|^2``: ``field_max`` is the
    largest ``|B|`` along the run, T. A walkthrough's normalised gain of 300 N m s on a 3U CubeSat,
    held 1 s (``k T / I1 = 4.5e4``), spun it from 0.017 to 92 rad/s and was reported only as "not
    detumbled"; a classic gain past the bound (``k_b |B|^2 T / I1 = 2.1``, a field of 30 uT across
    the axis) spun one from 0.017 to 1.4 rad/s in a minute. Saturated magnetorquers (far from rest)
    hide it until the rate is small. A walkthrough's Avanzini & Giulietti gain (normalised, 6.7e-3
    N m s) given to ``BDot`` without its form was read as classic: a dipole of 2.4e-10 A m^2, the
    rate 10 deg/s at the start and the end, and no word.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics.control.sampled import check_bdot_loop
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_bdot_loop([0.00667, 0.0419, 0.0419], 4.4e-5, 1.0)   # Avanzini & Giulietti's gain: stable
    ...     check_bdot_loop([0.00667, 0.0419, 0.0419], 300.0, 1.0)
    ...     check_bdot_loop([0.00667, 0.0419, 0.0419], 1e4, 1.0, field_max=5e-5)   # classic, A m^2 s/T: stable
    ...     check_bdot_loop([0.00667, 0.0419, 0.0419], 1e8, 1.0, field_max=5e-5)
    >>> len(caught), str(caught[0].message)[:83]
    (2, 'gain = 300 N m s: B-dot held for period = 1 s is unstable about principal axis 1 (I')
    >>> str(caught[1].message)[:90]
    'gain = 1e+08 A m^2 s/T: classic B-dot held for period = 1 s is unstable about principal ax'
    >>> with warnings.catch_warnings(record=True) as caught:   # a normalised gain taken as classic
    ...     warnings.simplefilter("always")
    ...     check_bdot_loop([0.00667, 0.0419, 0.0419], 6.7e-3, 1.0, field_max=4.7e-5, t_end=3000.0)
    >>> str(caught[0].message)[:84]
    'gain = 0.0067 A m^2 s/T: classic B-dot changes the rate about principal axis 3 (I = '
    """
    I = np.asarray(moments, float)
    axis = int(np.argmin(I))
    if field_max is None:
        ratio, unit, form, effective, beside = gain * period / float(I[axis]), "N m s", "", "k T / I", ""
    else:
        ratio, unit, form = gain * field_max**2 * period / float(I[axis]), "A m^2 s/T", "classic "
        effective, beside = "k_b |B|^2 T / I", f" with |B| up to {field_max:.3g} T along the run"
    k = gain if field_max is None else gain * field_max**2  # N m s: the torque -k omega_perp
    slowest = float(I[-1]) / k if k > 0 else np.inf  # s, about the largest moment (the moments ascend)
    if t_end is not None and slowest > max(WEAK_RUNS * t_end, WEAK_TIME):
        other = (' a normalised gain (N m s, bdot_gain\'s) given as classic? Give form = "normalized"'
                 if field_max is not None else " a gain in other units?")
        field = "" if field_max is None else f" (|B| up to {field_max:.3g} T along the run)"
        warnings.warn(f"gain = {gain:g} {unit}: {form}B-dot changes the rate about principal axis 3 (I = {I[-1]:.3g} "
                      f"kg m^2) with a time constant of {slowest:.3g} s or more{field}, over {WEAK_RUNS:g} times the "
                      f"run's t_end = {t_end:g} s and a year: it leaves the rate as it was;{other}", WeakLoopWarning, stacklevel=3)
    if ratio <= 2.0:
        return
    bound = 2.0 * float(I[axis]) / period / (1.0 if field_max is None else field_max**2)
    warnings.warn(f"gain = {gain:g} {unit}: {form}B-dot held for period = {period:g} s is unstable about principal axis "
                  f"{axis + 1} (I = {I[axis]:.3g} kg m^2: {effective} = {ratio:.3g} > 2{beside}), each step overshooting "
                  f"the rate it damps; give a gain below {bound:.3g} {unit} or a shorter period (a gain in other units?)",
                  UnstableLoopWarning, stacklevel=3)
