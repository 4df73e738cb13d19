"""Why a throw is left out of a pooled tensor: the reasons :func:`~tumble.analysis.tensor.pool.pool_throws`
gives, each a line for the user (``""``: no reason). A throw's own fit (:func:`throw_verdict`), its part of
the joint fit (:func:`joint_verdict`: residuals above the gyroscope's noise, :func:`residual_verdict`, or a
bias no gyroscope has), and a log given twice (:func:`duplicate_throws`).
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Sequence

import numpy as np

from ...dynamics.environment.earth import STANDARD_GRAVITY
from ...typing import FloatArray
from .device import ROTOR_SPEED_RATIO
from .model import MEAN_SPAN
from .throw import RESIDUAL_LIMIT, FlownFit
from .throwlog import Throw, running_peak

__all__ = ["MAX_BIAS", "RAIL_SHARE", "accel_hint", "duplicate_throws", "join_reasons", "joint_verdict", "rail_hint",
           "residual_verdict", "speed_verdict", "throw_verdict"]

#: The largest gyroscope bias a fit may find, rad/s: a MEMS gyroscope's zero-rate offset is
#: about 3 deg/s, 0.05 rad/s (the data sheets :data:`tumble.analysis.fit.model` cites for its own
#: bound), and a flight controller removes it at rest; on realistic throws the joint fit needs at
#: most 0.3 rad/s (benchmarks/tensor_coverage.py). A fit that needs more is explaining something
#: else (a wrong unit, a mount that flexes, a rotor axis that is wrong).
MAX_BIAS = 0.6
_BIAS_REASON = "the fit needs a gyroscope bias of"  # how joint_verdict begins that refusal (pool_throws reads it)


def throw_verdict(f: FlownFit, throw: Throw) -> str:
    """Why a throw's own fit leaves it out, or ``""`` (:mod:`~tumble.analysis.tensor.pool`, step 2; the residuals and
    the bias are judged on the joint fit, where the gyroscope's distortion and the rotor's tilt
    are explained: :func:`joint_verdict`; a lone throw's own fit at 35 rad/s leaves residuals 4-9
    times the noise from a 0.9 % misalignment and a 2 degree tilt).

    Examples
    --------
    >>> from tumble.analysis.tensor.verdicts import throw_verdict
    >>> from tumble.analysis.tensor.throw import FlownFit
    >>> from tumble.analysis.tensor.flight import Window
    >>> throw_verdict(FlownFit(Window(0, 0, 0, 0.0, 0.0, "no rotor"), "no rotor"), None)
    'no rotor'
    """
    if f.reason:
        return f.reason
    if f.center is None or throw.accel is None:
        return "no accelerometer in the throw: its centre of mass is unknown"
    return ""


def speed_verdict(speed: float, calibrated: tuple[float, float] | None) -> str:
    """Why a throw whose rotor's top speed is ``speed`` (rad/s, :attr:`Throw.top_speed
    <tumble.analysis.tensor.Throw.top_speed>`) cannot be the calibrated device's, or ``""``: more
    than :data:`~tumble.analysis.tensor.device.ROTOR_SPEED_RATIO` times beyond the calibration
    throws' range ``calibrated`` (``Device.rotor_speed_range``; None: not known, nothing judged).
    The tensor's scale is the rotor's momentum's: a speed in rpm read as rad/s gave an object's
    moments 10-14 times too large, and the fit's residuals, bias and chi2/dof no sign of it.

    Examples
    --------
    >>> from tumble.analysis.tensor.verdicts import speed_verdict
    >>> speed_verdict(1290.0, (1230.0, 1360.0)), speed_verdict(1290.0, None)
    ('', '')
    >>> speed_verdict(12400.0, (1230.0, 1360.0))[:60]
    "the rotor's top speed 1.24e+04 rad/s is 9.1 times the calibr"
    """
    if calibrated is None:
        return ""
    low, high = calibrated
    if low / ROTOR_SPEED_RATIO <= speed <= high * ROTOR_SPEED_RATIO:
        return ""
    times = speed / high if speed > high else speed / low
    why = ("its speed in another unit than the header says (rpm for rad/s is 9.5 times) or an eRPM turned with half "
           "the poles (2 times)?") if speed > high else (
        "the log stops before the rotor's spin-up (its idle is ~200 rad/s), or its speed is in another unit than the "
        "header says (rev/s for rad/s is 0.16 times) or an eRPM turned with twice the poles (0.5 times)?")
    return (f"the rotor's top speed {speed:.3g} rad/s is {times:.2g} times the calibration throws': at most "
            f"{ROTOR_SPEED_RATIO:g} times beyond their {low:.4g}-{high:.4g} rad/s is the device's; {why}")


#: The shortest hint :func:`join_reasons` writes once for all the throws that end with it, characters.
SHARED_HINT = 40


def join_reasons(named: Sequence[tuple[str, str]]) -> str:
    """The reasons of several left-out throws, ``"NAME: REASON"`` joined by ``"; "``, with the hint
    that every one of them ends with (the text after a ``": "`` they share, at least
    :data:`SHARED_HINT` characters, outside any parenthesis) written once at the end, not once a throw: four throws in
    rpm gave a line of ~950 characters, the same 110-character question four times.

    Examples
    --------
    >>> from tumble.analysis.tensor.verdicts import join_reasons
    >>> hint = "its speed in another unit than the header says (rpm for rad/s is 9.5 times)?"
    >>> join_reasons([("o1.csv", f"top speed 9.9 times: {hint}"), ("o2.csv", f"top speed 9.4 times: {hint}")])
    'o1.csv: top speed 9.9 times; o2.csv: top speed 9.4 times; for each: its speed in another unit than the header says (rpm for rad/s is 9.5 times)?'
    >>> join_reasons([("o1.csv", "no rotor"), ("o2.csv", "no rotor")])
    'o1.csv: no rotor; o2.csv: no rotor'
    """
    reasons = [reason for _, reason in named]
    shared = os.path.commonprefix([reason[::-1] for reason in reasons])[::-1] if len(reasons) > 1 else ""
    colon = shared.find(": ")
    while colon >= 0 and len(shared) - colon - 2 >= SHARED_HINT:
        heads = [reason[:len(reason) - len(shared) + colon] for reason in reasons]
        if all(head.count("(") == head.count(")") for head in heads):  # not a colon inside a parenthesis
            hint = shared[colon + 2:]
            return "; ".join(f"{name}: {head}" for (name, _), head in zip(named, heads)) + f"; for each: {hint}"
        colon = shared.find(": ", colon + 2)
    return "; ".join(f"{name}: {reason}" for name, reason in named)


def accel_hint(throw: Throw) -> str:
    """``""``, or a clause for a left-out throw's reason where its accelerometer reads in g what the
    header says is m/s^2: never half of g in the whole log (its magnitude's
    :func:`~tumble.analysis.tensor.throwlog.running_peak`), though a hand holding and throwing the
    device pushes it with 9.8 m/s^2 and more (the examples' throws: 14-22 m/s^2; in g they read
    1.4-2.3). Read so, the free fall the flight
    is found by starts in the hand, and the throw's residuals are blamed on the gyroscope.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Throw
    >>> from tumble.analysis.tensor.verdicts import accel_hint
    >>> t = np.arange(100) / 4000.0
    >>> accel_hint(Throw(t, np.zeros((100, 3)), np.zeros(100), np.full((100, 3), 0.6)))[:61]
    '; its accelerometer reads at most 1.04 m/s^2 in the whole log'
    """
    if throw.accel is None:
        return ""
    top = running_peak(np.linalg.norm(throw.accel, axis=1))
    if top >= 0.5 * STANDARD_GRAVITY:
        return ""
    return (f"; its accelerometer reads at most {top:.3g} m/s^2 in the whole log, never the 9.8 of a hand holding the "
            "device: in g under an m/s^2 header?")


#: The share of a left-out throw's flight samples at the gyroscope's range above which its reason
#: says so (:func:`rail_hint`).
RAIL_SHARE = 0.1


def rail_hint(throw: Throw, f: FlownFit, saturation: float | None) -> str:
    """``""``, or a clause for a left-out throw's reason where more than :data:`RAIL_SHARE` of its
    flight's samples lie at the gyroscope's range (``saturation``, rad/s, or the rail the samples
    show: :func:`~tumble.analysis.fit.single.saturation_mask`): a throw spun faster than the
    gyroscope reads. A walkthrough's throws at 36-40 rad/s with 4-36 % of their samples at a
    2000 deg/s rail were blamed on units, a rotor axis or a mount; the same throws unclipped fit.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Throw
    >>> from tumble.analysis.tensor.flight import Window
    >>> from tumble.analysis.tensor.throw import FlownFit
    >>> from tumble.analysis.tensor.verdicts import rail_hint
    >>> t = np.arange(100) / 1000.0
    >>> omega = np.clip(40.0 * np.sin(np.c_[t, t, t] * 60.0), -34.9, 34.9)
    >>> thrown = Throw(t, omega, np.zeros(100), None)
    >>> rail_hint(thrown, FlownFit(Window(0, 100, 0, 0.0, 0.099, "x"), "x"), 34.9)[:38]   # |sin| >= 0.87: a third
    '; 35 % of its flight samples at the gy'
    """
    from ..fit.single import saturation_mask

    if "gyroscope's range" in f.reason:  # the reason says it already (the flight not found for it)
        return ""
    keep, rail = saturation_mask(throw.omega, saturation)
    w = f.window
    inside = keep[w.first:w.stop] if w.stop > w.first else keep
    share = 1.0 - float(np.mean(np.all(inside, axis=1))) if inside.size else 0.0
    if rail is None or share <= RAIL_SHARE:
        return ""
    return (f"; {100 * share:.0f} % of its flight samples at the gyroscope's range ({rail:.3g} rad/s): thrown faster "
            "than it reads? Throw it slower, or set a wider range on the device")


def residual_verdict(rms: float, noise: float) -> str:
    """Why residuals ``rms`` (rad/s) against the ``noise`` of the fitted data, the rates' means over
    :data:`~tumble.analysis.tensor.model.MEAN_SPAN` (a 4 kHz gyroscope's noise over 2), say the model does not
    explain a flight, or ``""``.

    Examples
    --------
    >>> from tumble.analysis.tensor.verdicts import residual_verdict
    >>> residual_verdict(0.012, 0.01), residual_verdict(0.047, 0.01)[:40]
    ('', 'the free motion does not explain the fli')
    """
    if rms <= RESIDUAL_LIMIT * noise:
        return ""
    return (f"the free motion does not explain the flight: residuals {rms:.3g} rad/s, {rms / noise:.1f} times the "
            f"noise {noise:.2g} rad/s of the rates' {1e3 * MEAN_SPAN:g} ms means that are fitted (at most "
            f"{RESIDUAL_LIMIT:g}; rates in another unit than the header "
            f"says, deg/s for rad/s or the reverse, a rotor axis or speed that is wrong, a mount or body that is not "
            f"rigid)")


def joint_verdict(bias: FloatArray, rms: float, noise: float) -> str:
    """Why a throw's part of the joint fit leaves it out, or ``""``: its residuals
    (:func:`residual_verdict`) or a gyroscope bias beyond :data:`MAX_BIAS`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.verdicts import joint_verdict
    >>> joint_verdict(np.array([0.01, 0.0, -0.8]), 0.012, 0.01)[:44]
    'the fit needs a gyroscope bias of 0.8 rad/s,'
    """
    why = residual_verdict(rms, noise)
    if why:
        return why
    size = float(np.max(np.abs(bias)))
    if size > MAX_BIAS:
        return (f"{_BIAS_REASON} {size:.3g} rad/s, more than a gyroscope has ({MAX_BIAS:g}): the "
                f"model explains the flight only by distorting it (a wrong unit, rotor axis or sign)")
    return ""


def duplicate_throws(throws: Sequence[Throw]) -> str:
    """``""``, or a line naming two throws whose logs are the same samples (one throw given twice
    counts twice and halves the stated std).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Throw
    >>> from tumble.analysis.tensor.verdicts import duplicate_throws
    >>> t = np.arange(100) / 4000.0
    >>> a = Throw(t, np.ones((100, 3)), np.zeros(100), None, "a.csv")
    >>> duplicate_throws([a, Throw(t, np.ones((100, 3)), np.zeros(100), None, "copy.csv")])
    'throws[1] (copy.csv) is the same log as throws[0] (a.csv): give each throw once'
    """
    seen: dict[str, int] = {}
    for k, th in enumerate(throws):
        digest = hashlib.sha256(b"".join(np.ascontiguousarray(x, float).tobytes() for x in (th.t, th.omega, th.rotor)))
        key = digest.hexdigest()
        if key in seen:
            j = seen[key]
            return (f"throws[{k}] ({throws[k].input or 'unnamed'}) is the same log as throws[{j}] "
                    f"({throws[j].input or 'unnamed'}): give each throw once")
        seen[key] = k
    return ""
