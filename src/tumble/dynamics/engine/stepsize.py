"""DOP853's step-size control as scipy runs it, over plain floats: written once, compiled by the
engine's stepper (:func:`tumble.dynamics.engine.kernels.dop853`) and by the closed loop's
(:mod:`tumble.dynamics.control.compiled_loop`), both through the one loop of tries that calls them
(:func:`~tumble.dynamics.engine.unrolled.dop853_accept_source`).

Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., sec. II.4 and
II.10, in the form of :class:`scipy.integrate.DOP853` (``_estimate_error_norm`` and
``RungeKutta._step_impl``): the 5th- and 3rd-order error estimates combined into one norm, and
a step accepted below 1, grown or shrunk by ``0.9 error^(-1/8)`` within [0.2, 10], never grown
right after a rejection. With it, the range a relative tolerance may take (:data:`RTOL_RANGE`,
:func:`check_rtol`), which every stepping method, the batch and the closed loop check against.
Imports no numba, so numba is not loaded with it.

Examples
--------
>>> from tumble.dynamics.engine.stepsize import error_norm, next_step
>>> error_norm(0.0, 0.0, 0.1, 7), next_step(0.0, 0.1, False)   # a perfect step: ten times longer
(0.0, (True, 1.0))
>>> accepted, h = next_step(4.0, 0.1, False)   # too large an error: rejected, shrunk
>>> accepted, round(h, 6)
(False, 0.075681)
"""

import math
import sys
from typing import Any

from ...jit import formula
from ...validation import check_positive

__all__ = ["ATOL_MAX", "RTOL_RANGE", "check_atol", "check_rtol", "equal_steps", "error_norm", "first_trial_step", "initial_step", "next_step", "rms"]

#: The range of a relative tolerance (every stepping method's, and the closed loop's): scipy clips
#: rtol below 100 eps (with a warning), and above 0.1 an adaptive step control no longer controls
#: anything.
RTOL_RANGE = (100 * sys.float_info.epsilon, 0.1)
#: The largest absolute tolerance: the quaternion's components, of size 1, take the same ``atol``
#: as omega, so above 0.1 the attitude is no longer controlled (and omega's error, relative to the
#: spin for ``dop853`` and ``"auto"``, no more than rtol's upper end allows).
ATOL_MAX = 0.1
#: :func:`tumble.simulate`'s ``atol``, in words.
ATOL_UNIT = "rad/s, relative to the spin for dop853 and auto; the quaternion's components take it too"


def check_rtol(field: str, value: object) -> float:
    """A relative tolerance in :data:`RTOL_RANGE`, as a float; else one ValueError naming ``field``.

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import check_rtol
    >>> check_rtol("rtol", 1e-10)
    1e-10
    >>> check_rtol("simulation.rtol", 5.0)
    Traceback (most recent call last):
    ...
    ValueError: simulation.rtol = 5.0 must be from 2.22e-14 to 0.1 (relative)
    """
    rtol = check_positive(field, value, "relative")
    if not RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]:
        raise ValueError(f"{field} = {rtol!r} must be from {RTOL_RANGE[0]:.3g} to {RTOL_RANGE[1]:g} (relative)")
    return rtol


def check_atol(field: str, value: object, unit: str = ATOL_UNIT) -> float:
    """An absolute tolerance above 0 and at most :data:`ATOL_MAX`, as a float; else one ValueError
    naming ``field`` and ``unit``: by default :func:`tumble.simulate`'s, rad/s for omega (relative
    to the spin for ``dop853`` and ``"auto"``) and 1 for the quaternion's components.

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import check_atol
    >>> check_atol("atol", 1e-12)
    1e-12
    >>> check_atol("atol", 1e3)
    Traceback (most recent call last):
    ...
    ValueError: atol = 1000.0 must be above 0 and at most 0.1 (rad/s, relative to the spin for dop853 and auto; the quaternion's components take it too)
    """
    atol = check_positive(field, value, unit)
    if not atol <= ATOL_MAX:
        raise ValueError(f"{field} = {value!r} must be above 0 and at most {ATOL_MAX:g} ({unit})")
    return atol


def error_norm(e5: float, e3: float, h_abs: float, n: int) -> float:
    """The error norm of a step of length ``h_abs`` (s) from ``e5`` and ``e3``, the sums of
    squares of the scaled 5th- and 3rd-order estimates over the ``n`` components; a NaN (an
    overflow in the stages) counts as an infinite error, so the step is refused and shrinks.

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import error_norm
    >>> round(error_norm(1.0, 1.0, 0.5, 4), 6)
    0.248759
    >>> error_norm(float("nan"), 1.0, 0.5, 4)
    inf
    """
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    error = h_abs * e5 / math.sqrt((e5 + 0.01 * e3) * n)
    return math.inf if error != error else error


def next_step(error: float, h_abs: float, rejected: bool) -> tuple[bool, float]:
    """Whether the step is accepted, and the next step length (s) after it or in its place.

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import next_step
    >>> next_step(0.1, 1.0, True)   # accepted after a rejection: not grown (it would be 1.2 times)
    (True, 1.0)
    """
    if error < 1.0:
        factor = 10.0 if error == 0.0 else min(10.0, 0.9 * error ** -0.125)
        if rejected:
            factor = min(1.0, factor)
        return True, h_abs * factor
    return False, h_abs * max(0.2, 0.9 * error ** -0.125)


def rms(x: Any, scale: Any) -> float:
    """scipy's ``norm(x / scale)``: the root mean square of ``x / scale`` over a 1-D array (a loop,
    so numba compiles it as it is).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.engine.stepsize import rms
    >>> rms(np.array([3.0, 4.0]), np.array([1.0, 1.0])) == 5.0 / 2.0 ** 0.5
    True
    """
    total = 0.0
    for i in range(x.shape[0]):
        v = x[i] / scale[i]
        total += v * v
    return math.sqrt(total) / math.sqrt(x.shape[0])


def first_trial_step(d0: float, d1: float, interval: float) -> float:
    """scipy's ``select_initial_step``, first part (HNW sec. II.4): the trial step from the RMS
    sizes of the state ``d0`` and of its slope ``d1``, no longer than the interval (s).

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import first_trial_step
    >>> first_trial_step(1.0, 2.0, 10.0), first_trial_step(1e-6, 2.0, 10.0)
    (0.005, 1e-06)
    """
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    return min(h0, interval)


def initial_step(h0: float, d1: float, d2: float, interval: float) -> float:
    """scipy's ``select_initial_step``, second part: the first step (s) from the trial step ``h0``,
    the slope's size ``d1`` and the second derivative's ``d2``, for an error estimator of order 7.

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import initial_step
    >>> initial_step(0.01, 2.0, 0.0, 10.0) == (0.01 / 2.0) ** (1.0 / 8.0)   # below 100 h0 = 1 s
    True
    """
    h1 = max(1e-6, h0 * 1e-3) if (d1 <= 1e-15 and d2 <= 1e-15) else (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, interval)


@formula
def equal_steps(interval: float, step: float) -> tuple[int, float]:
    """The fixed-step methods' rule: the fewest equal steps no longer than ``step`` (s) that fill a
    sample ``interval`` (s; negative backward in time, the steps then negative), and their length; a
    step within 1e-9 of dividing it is not split again.

    Examples
    --------
    >>> from tumble.dynamics.engine.stepsize import equal_steps
    >>> equal_steps(1.0, 0.3), equal_steps(1.0, 0.25), equal_steps(-1.0, 0.3)
    ((4, 0.25), (4, 0.25), (4, -0.25))
    """
    n = max(1, math.ceil(abs(interval) / step - 1e-9))
    return n, interval / n
