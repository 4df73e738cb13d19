"""Stability of free rotation about the principal axes: the tennis-racket theorem, quantified.

Three routes that the tests hold against each other:

1. *Linearised* (Marion & Thornton, *Classical Dynamics*, 5th ed., sec. 11.12; Landau &
   Lifshitz, *Mechanics*, sec. 37, problem 1): spin ``W`` about principal axis ``a`` with small
   components along the other two axes ``b, c``. Euler's equations give
   ``eps_b'' = s eps_b`` with ``s = W^2 (I_a - I_b)(I_c - I_a) / (I_b I_c)``. For the
   intermediate axis ``s > 0``: the perturbation grows as ``exp(lambda t)``,
   ``lambda = sqrt(s)``; for the minor and major axes ``s < 0``: it wobbles at ``sqrt(-s)``.
2. *Exact* (Landau & Lifshitz sec. 37): omega(t) is a Jacobi elliptic motion
   whose period is ``4 K(k^2) / p``; the components that change sign do so every ``2 K / p``,
   the *flip interval* (:func:`flip_interval`).
3. *Measured*: sign changes of the spin component in a simulated trajectory
   (:func:`flip_times`).

Principal axes are numbered as everywhere a user sees them (docs/conventions.md, "Numbering
the principal axes"): 1, 2, 3 in ascending order of moment, or by name, ``"minor"``,
``"intermediate"``, ``"major"``. Every function here takes and returns axes that way; 0, -1,
floats and booleans are refused, never read as Python indices. Moments are ``(..., 3)``
arrays, positive and ascending (``I1 <= I2 <= I3``) and those of a body that exists (the
triangle inequality ``I1 + I2 >= I3``, Goldstein sec. 5.4: the formulas would take any positive
triple, but no body has one beyond it), and every array argument is checked as a whole by one
validator (:func:`tumble.validation.check_moments`), whose message names the first bad index.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..dynamics.euler import energy_momentum_gaps
from ..dynamics.methods.exact import elliptic_parameters
from ..dynamics.special.elliptic import ellipk_kp
from ..typing import ArrayLike, FloatOrArray
from ..validation import INERTIA_RTOL, axis_index, check_moments, check_vectors, is_body, short_repr
from . import _display

__all__ = [
    "axis_of",
    "circulation_axis",
    "energy_momentum_gaps",
    "flip_interval",
    "flip_interval_asymptotic",
    "flip_times",
    "linearised_rate",
    "perturbation_exponent",
    "SpinPrediction",
    "spin_prediction",
    "stable_spin_range",
]

def _axis_index(axis) -> np.ndarray:
    """0-based indices (0, 1, 2) of public axis labels, by :func:`~tumble.validation.axis_index`."""
    return axis_index("axis", axis)


def _check_moments(moments) -> np.ndarray:
    """Principal moments as a float array (..., 3): finite, positive, ascending, within the triangle inequality."""
    return check_moments("moments", moments)


def _check_motion(omega: ArrayLike, moments: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The shared validator of ``(omega, moments)``: finite omega (..., 3), moments as
    :func:`_check_moments`, batch shapes that broadcast together."""
    if is_body(omega):  # simulate's order, (body, omega), given to an (omega, moments) function
        raise ValueError(f"omega = {short_repr(omega)} is a body: these functions take (omega, moments), omega (rad/s) "
                         "first, then body.principal_moments (kg m^2)")
    w = check_vectors("omega", omega, "rad/s")
    I = _check_moments(moments)
    _broadcast(omega=w.shape[:-1], moments=I.shape[:-1])
    return w, I


def _broadcast(**shapes) -> tuple[int, ...]:
    """The broadcast batch shape of named arguments, or a ``ValueError`` naming them."""
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:
        given = ", ".join(f"{name} (batch shape {shape})" for name, shape in shapes.items())
        raise ValueError(f"{given} must broadcast together") from None


def axis_of(omega: ArrayLike) -> np.ndarray:
    """Principal axis (1, 2 or 3) carrying most of ``omega``: its largest |component|.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame (axes ordered I1 <= I2 <= I3), rad/s.

    Returns
    -------
    ndarray of int, shape (...)
        1, 2 or 3; on a tie the lower axis (and 1 for ``omega = 0``).

    Examples
    --------
    >>> from tumble.analysis.stability import axis_of
    >>> axis_of([[0.1, 5.0, 0.2], [3.0, 0.0, -4.0]]).tolist()
    [2, 3]
    """
    return np.argmax(np.abs(check_vectors("omega", omega, "rad/s")), axis=-1) + 1


def perturbation_exponent(moments: ArrayLike, axis: int | str, spin: ArrayLike, momentum: ArrayLike = 0.0) -> np.ndarray:
    """``s = W^2 (I_a - I_b)(I_c - I_a) / (I_b I_c)`` of the linearised equations (see module).

    With a rotor's momentum ``h`` along the spin axis (a gyrostat, rotors locked into the
    moments), ``s = ((I_a - I_b) W + h)((I_c - I_a) W - h) / (I_b I_c)`` for ``(a, b, c)`` in
    cyclic order: Euler's equations ``I w' + w x (I w + h) = 0`` linearised about ``W e_a``
    (Hughes, *Spacecraft Attitude Dynamics*, the gyrostat chapter; for the intermediate axis it
    is ``((I3 - I2) W - h)((I2 - I1) W + h) / (I1 I3)``, the form of
    :func:`tumble.dynamics.models.internal.gyrostat_rate`). A large enough ``h`` along the spin makes
    any axis stable; one against it can make the minor or major axis unstable.

    Parameters
    ----------
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending (I1 <= I2 <= I3), I1 + I2 >= I3, kg m^2.
    axis : {1, 2, 3, 'minor', 'intermediate', 'major'} or array_like of them, shape (...)
        Spin axis ``a``: 1 minor, 2 intermediate, 3 major.
    spin : array_like, shape (...)
        Spin rate W about that axis, rad/s.
    momentum : array_like, shape (...), optional
        Rotor momentum ``h`` along that axis (positive along the spin), kg m^2/s; default 0.

    Returns
    -------
    ndarray, shape (...)
        ``s`` in 1/s^2 (the batch shapes of the three arguments broadcast): positive means
        exponential growth, negative means a wobble.

    Raises
    ------
    ValueError
        For an axis other than those, moments that are not positive, finite and ascending or break ``I1 + I2 >= I3``, a
        non-finite spin, or batch shapes that do not broadcast; naming the first bad index.

    Examples
    --------
    >>> from tumble.analysis.stability import perturbation_exponent
    >>> perturbation_exponent([1.0, 2.0, 3.0], "intermediate", 1.0).round(6)   # > 0: a small tilt grows
    np.float64(0.333333)
    >>> float(perturbation_exponent([1.0, 2.0, 3.0], "major", 1.0)) < 0   # < 0: it wobbles
    True
    """
    I = _check_moments(moments)
    a = _axis_index(axis)
    W = check_vectors("spin", spin, "rad/s", size=None)
    h = check_vectors("momentum", momentum, "kg m^2/s", size=None)
    shape = _broadcast(moments=I.shape[:-1], axis=a.shape, spin=W.shape, momentum=h.shape)
    I = np.broadcast_to(I, shape + (3,))
    a = np.broadcast_to(a, shape)[..., None]
    Ia = np.take_along_axis(I, a, axis=-1)[..., 0]
    Ib = np.take_along_axis(I, (a + 1) % 3, axis=-1)[..., 0]
    Ic = np.take_along_axis(I, (a + 2) % 3, axis=-1)[..., 0]
    return ((Ia - Ib) * W + h) * ((Ic - Ia) * W - h) / (Ib * Ic)


def linearised_rate(moments: ArrayLike, axis: int | str, spin: ArrayLike, momentum: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Growth exponent (1/s) and wobble angular frequency (rad/s) for spin about ``axis``.

    Exactly one of the two is non-zero for an asymmetric body: the growth exponent for the
    intermediate axis (2), the wobble frequency for the minor (1) and major (3) axes.

    Parameters
    ----------
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending (I1 <= I2 <= I3), I1 + I2 >= I3, kg m^2.
    axis : {1, 2, 3, 'minor', 'intermediate', 'major'} or array_like of them, shape (...)
        Spin axis: 1 minor, 2 intermediate, 3 major.
    spin : array_like, shape (...)
        Spin rate about that axis, rad/s.
    momentum : array_like, shape (...), optional
        Rotor momentum along that axis, kg m^2/s (a gyrostat; :func:`perturbation_exponent`).

    Returns
    -------
    growth : ndarray, shape (...)
        Exponent ``lambda`` of ``exp(lambda t)`` growth of a perturbation, 1/s (0 if stable).
    wobble : ndarray, shape (...)
        Angular frequency of the wobble, rad/s (0 if unstable).

    Raises
    ------
    ValueError
        As :func:`perturbation_exponent`.

    Examples
    --------
    >>> from tumble.analysis.stability import linearised_rate
    >>> growth, wobble = linearised_rate([1.0, 2.0, 2.5], "intermediate", 3.0)
    >>> round(float(growth), 6), float(wobble)
    (1.341641, 0.0)
    """
    s = perturbation_exponent(moments, axis, spin, momentum)
    return np.sqrt(np.maximum(s, 0.0)), np.sqrt(np.maximum(-s, 0.0))


def stable_spin_range(moments: ArrayLike, momentum: float) -> tuple[float, float]:
    """Spin rates about the intermediate axis that a rotor momentum along it keeps stable.

    The zeros of :func:`perturbation_exponent` for the intermediate axis,
    ``s = ((I3 - I2) W - h)((I2 - I1) W + h) / (I1 I3)``: a parabola in ``W`` that opens upwards,
    so spin is stable (``s < 0``, a wobble) strictly between ``-h / (I2 - I1)`` and
    ``h / (I3 - I2)`` and flips outside (Hughes, *Spacecraft Attitude Dynamics*, the gyrostat
    chapter). Without a rotor (``h = 0``) the range is empty: the tennis-racket theorem.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments (locked rotors included), positive and ascending with ``I1 < I2 < I3 <= I1 + I2``,
        kg m^2.
    momentum : float
        The rotors' momentum ``h`` along the intermediate axis (its sign along that axis's
        direction), kg m^2/s.

    Returns
    -------
    (float, float)
        ``(W_low, W_high)`` in rad/s, signed along the same direction as ``h``: spin ``W`` about
        the axis is stable (linearised) for ``W_low < W < W_high``; ``(0.0, 0.0)`` for ``h = 0``.

    Raises
    ------
    ValueError
        For moments that are not positive, finite and ascending or break ``I1 + I2 >= I3``, two
        equal moments (no intermediate axis), or a non-finite momentum.

    Examples
    --------
    >>> from tumble.analysis.stability import stable_spin_range
    >>> stable_spin_range([1.0, 2.0, 2.5], 3.0)   # h / (I3 - I2) = 6, -h / (I2 - I1) = -3
    (-3.0, 6.0)
    """
    I = _check_moments(moments)
    if I.shape != (3,):
        raise ValueError(f"moments must be one body's three principal moments, got shape {I.shape} (kg m^2)")
    if not I[0] < I[1] < I[2]:
        raise ValueError(f"moments = {I.tolist()} have two equal: no intermediate axis (kg m^2)")
    h = float(check_vectors("momentum", momentum, "kg m^2/s", size=None))
    ends = sorted((h / (I[2] - I[1]), -h / (I[1] - I[0])))
    return float(ends[0]) + 0.0, float(ends[1]) + 0.0


def flip_interval(omega: ArrayLike, moments: ArrayLike) -> FloatOrArray:
    """Exact time between sign changes of the oscillating components of omega, s.

    Torque-free motion with ``I1 < I2 < I3`` (Landau & Lifshitz sec. 37): for
    ``L^2 > 2 E I2`` omega circulates about axis 3 (``omega_3`` keeps its sign, ``omega_1`` and
    ``omega_2`` change sign); for ``L^2 < 2 E I2`` about axis 1. Either way the period of omega
    is ``4 K(k^2) / p`` and the sign changes come every ``2 K / p`` with

    - ``L^2 > 2 E I2``: ``p^2 = (I3 - I2)(L^2 - 2 E I1) / (I1 I2 I3)``,
      ``1 - k^2 = (I3 - I1)(L^2 - 2 E I2) / ((I3 - I2)(L^2 - 2 E I1))``;
    - ``L^2 < 2 E I2``: indices 1 and 3 exchanged.

    ``k' = sqrt(1 - k^2)`` is formed directly, without cancellation or underflow
    (:func:`tumble.dynamics.methods.exact.elliptic_parameters`; ``k' = 1e-160`` where ``1 - k^2`` is
    not a double), and ``K`` comes from it by the AGM (:func:`tumble.dynamics.special.elliptic.ellipk_kp`),
    so the interval stays accurate as the motion nears the separatrix, where it diverges
    logarithmically.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity at any instant (principal frame), finite, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending (I1 <= I2 <= I3), I1 + I2 >= I3, kg m^2.

    Returns
    -------
    float, or ndarray of shape (...) for a batch
        The flip interval, s; ``inf`` on the separatrix (``L^2 = 2 E I2``) and at rest. Near
        a stable axis it tends to half the wobble period, ``pi / sqrt(-s)``. One body gives a
        float.

    Raises
    ------
    ValueError
        If ``omega`` is not finite numbers of shape (..., 3), ``moments`` are not positive,
        finite and ascending within ``I1 + I2 >= I3``, or their batch shapes do not broadcast;
        the message names the first bad index, e.g. ``moments[3] = [1.0, 3.0, 2.0] must be ascending, ...``.

    Examples
    --------
    >>> import numpy as np, tumble
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
    >>> omega0 = [0.01, 1.0, 0.0]   # near the intermediate axis
    >>> T = float(tumble.flip_interval(omega0, body.principal_moments))
    >>> round(T, 4)
    20.7546
    >>> traj = tumble.simulate(body, omega0, t_end=3.5 * T, samples=3001)
    >>> from tumble.analysis.stability import flip_times
    >>> bool(np.allclose(np.diff(flip_times(traj.t, traj.omega[:, 1])), T, rtol=1e-4))   # the run agrees
    True
    """
    e = elliptic_parameters(*_check_motion(omega, moments))
    p, kp = e.p, e.kp
    with np.errstate(divide="ignore", invalid="ignore"):
        interval = 2.0 * ellipk_kp(kp) / p
    return _float_if_one(np.where((kp == 0) | ~np.isfinite(interval) | ~(p > 0), np.inf, interval))


def _float_if_one(x: np.ndarray) -> FloatOrArray:
    """A float for one body (a 0-d result), the array for a batch."""
    return float(x) if np.ndim(x) == 0 else x


def flip_interval_asymptotic(omega: ArrayLike, moments: ArrayLike) -> FloatOrArray:
    """Small-perturbation form of :func:`flip_interval`: ``2 ln(4 / k') / p = ln(16 / (1 - k^2)) / p``, s.

    From ``K(k) = ln(4 / k') + O(k'^2 ln k')`` (Abramowitz & Stegun ch. 17, the limit m -> 1) with
    ``k'^2 = 1 - k^2``, which is proportional to the square of the perturbation of a spin about
    the intermediate axis: the interval grows like ``(2 / lambda) ln(1 / eps)`` as the spin
    nears the axis, with ``p -> lambda``, the linearised growth exponent. Relative error
    ``O(1 - k^2)``.

    Parameters, errors and the result's type as :func:`flip_interval`, s.

    Examples
    --------
    >>> from tumble.analysis.stability import flip_interval, flip_interval_asymptotic
    >>> exact = float(flip_interval([1e-4, 1.0, 0.0], [1.0, 2.0, 3.0]))
    >>> approx = float(flip_interval_asymptotic([1e-4, 1.0, 0.0], [1.0, 2.0, 3.0]))
    >>> abs(approx - exact) / exact < 1e-6   # O(1 - k^2): tiny this close to the axis
    True
    """
    e = elliptic_parameters(*_check_motion(omega, moments))
    with np.errstate(divide="ignore"):
        return _float_if_one(2.0 * np.log(4.0 / e.kp) / e.p)


def circulation_axis(omega: ArrayLike, moments: ArrayLike) -> np.ndarray:
    """Principal axis (1 or 3) about which omega circulates: its component never changes sign.

    That is the dn component in Landau & Lifshitz sec. 37: axis 3 (major) when
    ``L^2 >= 2 E I2`` (the separatrix and rest included), else axis 1 (minor). The other two
    components flip.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame, finite, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending (I1 <= I2 <= I3), I1 + I2 >= I3, kg m^2.

    Returns
    -------
    ndarray of int, shape (...)
        1 or 3.

    Raises
    ------
    ValueError
        As :func:`flip_interval`.

    Examples
    --------
    >>> from tumble.analysis.stability import circulation_axis
    >>> circulation_axis([[1.0, 0.1, 0.0], [0.0, 0.1, 1.0]], [1.0, 2.0, 3.0]).tolist()   # about minor, about major
    [1, 3]
    """
    return np.where(elliptic_parameters(*_check_motion(omega, moments)).upper, 3, 1)


class SpinPrediction(NamedTuple):
    """What the initial state of a free rigid motion says about its spin axis (:func:`spin_prediction`).

    Examples
    --------
    >>> from tumble.analysis.stability import spin_prediction
    >>> p = spin_prediction([0.01, 1.0, 0.0], [1.0, 2.0, 3.0])   # near the intermediate axis
    >>> int(p.axis), int(p.circulation), bool(p.stable), round(float(p.growth), 6)   # sqrt((2 - 1)(3 - 2) / 3)
    (2, 1, False, 0.57735)
    """

    axis: np.ndarray
    """Spin axis (1, 2 or 3): the principal axis nearest L, the largest ``|I_j omega_j|``."""
    circulation: np.ndarray
    """The axis omega circulates about (1 or 3, :func:`circulation_axis`)."""
    stable: np.ndarray
    """Whether the spin axis keeps its side of L: it is the circulation axis (or the body a sphere)."""
    growth: np.ndarray
    """The linearised growth exponent about the spin axis, 1/s, where it agrees with ``stable``, else NaN."""
    wobble: np.ndarray
    """The linearised wobble frequency about the spin axis, rad/s, where it agrees with ``stable``, else NaN."""

    def __repr__(self) -> str:
        return _display.spin_repr(self)

    def _repr_html_(self) -> str:
        return _display.spin_html(self)


def spin_prediction(omega: ArrayLike, moments: ArrayLike) -> SpinPrediction:
    """Classify a free rigid motion by the motion itself: its spin axis, circulation and stability.

    The spin axis is the principal axis nearest the angular momentum (the largest
    ``|L_j| = I_j |omega_j|``); omega circulates about axis 3 when ``L^2 >= 2 E I2``, else about
    axis 1 (Landau & Lifshitz sec. 37, :func:`circulation_axis`), and that component never
    changes sign while the other two do, twice a period. So the spin axis is *stable* (it stays
    on its side of L, never flips) exactly when it is the circulation axis, and for a sphere;
    otherwise it turns over (always for axis 2 of an asymmetric body; also for a motion far from
    every axis, e.g. omega = (8.3, 8.2, 7.5) rad/s on the T-handle, whose largest component is on
    axis 1 but which circulates about axis 3). The linearised rates
    (:func:`linearised_rate`) are given where they say the same, NaN where the motion is too far
    from its axis for them (docs/conventions.md, "Spin axis, circulation and flips"). One home
    for the rule of a sweep's columns (:func:`tumble.ensemble.reductions.reduce_cases`) and of
    :func:`tumble.analysis.stability_report`.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity at the start, principal frame, finite, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, positive and ascending (I1 <= I2 <= I3), I1 + I2 >= I3, kg m^2.

    Returns
    -------
    SpinPrediction
        ``axis``, ``circulation`` (int), ``stable`` (bool), ``growth`` (1/s) and ``wobble``
        (rad/s), each of the broadcast batch shape (...).

    Raises
    ------
    ValueError
        As :func:`flip_interval`.

    Examples
    --------
    >>> from tumble.analysis.stability import spin_prediction
    >>> I = [0.125, 0.3125, 0.4375]   # the T-handle's moments, kg m^2
    >>> p = spin_prediction([[8.3, 8.2, 7.5], [10.0, 0.1, 0.1]], I)
    >>> p.axis.tolist(), p.circulation.tolist(), p.stable.tolist()   # far from every axis; near the minor axis
    ([3, 1], [3, 1], [True, True])
    >>> bool(p.wobble[1] > 0), float(p.growth[1])
    (True, 0.0)
    """
    w, I = _check_motion(omega, moments)
    w, I = np.broadcast_arrays(w, I)
    axis = axis_of(I * w)
    circulation = circulation_axis(w, I)
    sphere = I[..., 2] - I[..., 0] <= INERTIA_RTOL * np.sum(I, axis=-1)
    stable = (axis == circulation) | sphere
    spin = np.take_along_axis(w, (axis - 1)[..., None], axis=-1)[..., 0]
    growth, wobble = linearised_rate(I, axis, spin)
    agree = np.where(stable, growth == 0, growth > 0)  # the linear theory, where it says what the motion does
    return SpinPrediction(axis, circulation, stable, np.where(agree, growth, np.nan), np.where(agree, wobble, np.nan))


def flip_times(t: ArrayLike, component: ArrayLike) -> np.ndarray:
    """Times at which a sampled component changes sign (linear interpolation), s.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s.
    component : array_like, shape (n,)
        The sampled quantity, e.g. ``omega[:, axis]``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.stability import flip_times
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> flip_times(t, np.cos(t)).round(4).tolist()   # pi/2, 3 pi/2, 5 pi/2
    [1.5708, 4.7124, 7.854]
    """
    t = np.asarray(t, float)
    y = np.asarray(component, float)
    k = np.flatnonzero(np.signbit(y[:-1]) != np.signbit(y[1:]))
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])
