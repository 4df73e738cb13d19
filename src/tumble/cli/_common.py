"""What the command modules share: the exit statuses, the options' number type and the spinner."""

from __future__ import annotations

import argparse
import math
import re
import sys

#: The command line's exit status when the command did what it was asked.
EXIT_OK = 0
#: The exit status of a computation that failed (the input was valid).
EXIT_FAILURE = 1
#: The exit status of bad input: one line naming the field, the value and what is allowed.
EXIT_USAGE = 2


class Written(float):
    """A number of the command line that shows itself as it was written: a message about it reads
    ``--t-end = -5`` (the value as the user wrote it), not ``-5.0``; a float everywhere else
    (arithmetic, numpy, numba, JSON and ``str`` see the float). Made by :func:`number`.

    Examples
    --------
    >>> from tumble.cli._common import number
    >>> t = number("1e3")
    >>> repr(t), str(t), t + 1.0, f"{t:g}"
    ('1e3', '1000.0', 1001.0, '1000')
    """

    text: str

    def __new__(cls, text: str) -> Written:
        value = super().__new__(cls, text)
        value.text = str(text)
        return value

    def __repr__(self) -> str:
        return self.text

    __str__ = float.__repr__


class NotANumber(argparse.ArgumentTypeError, ValueError):
    """Text given for a number that is none: argparse shows its message for an option, and a
    command that reads a number itself (``--mass``) takes it as the bad input a ValueError is."""


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


#: A number as the docs write one: ASCII digits, a point, an exponent; inf and nan in any case (refused later,
#: naming the option).
_PLAIN = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(inf|infinity|nan)", re.IGNORECASE | re.ASCII)


def number(text: str) -> float:
    """argparse's type of a numeric option: the float of ``text`` that shows itself as written
    (:class:`Written`); for text that is no number a :class:`NotANumber` saying what a number is, and where a decimal comma was written, the decimal point (argparse's own was only
    "invalid number value: '1,5'": a walkthrough).

    Examples
    --------
    >>> from tumble.cli._common import number
    >>> number("1.5"), number(" 2e3 ")
    (1.5, 2e3)
    >>> number("1,5")
    Traceback (most recent call last):
    ...
    tumble.cli._common.NotANumber: '1,5' is not a number: write a decimal point, 1.5
    """
    try:
        if not _PLAIN.fullmatch(text.strip()):  # Python's float takes "1_0" and full-width digits: not the docs' numbers
            raise ValueError(text)
        return Written(text.strip())
    except ValueError:
        comma = text.strip().replace(",", ".", 1) if text.count(",") == 1 else ""
        if _is_float(comma):  # a decimal comma
            raise NotANumber(f"{text!r} is not a number: write a decimal point, {comma}") from None
        raise NotANumber(f"{text!r} is not a number (digits, a decimal point, an exponent: 2.5, 1e-3)") from None


def _working(message: str):
    """A spinner on stderr while a long computation runs on a terminal; silent when piped."""
    import contextlib

    if not sys.stderr.isatty():
        return contextlib.nullcontext()
    from rich.console import Console

    return Console(stderr=True).status(message)


def _run_title(scenario, traj) -> str:
    """``scenario: body, method``, without the body when the scenario is named after it."""
    name = scenario.name if scenario.name != traj.body_name else None
    return ", ".join(filter(None, (f"{name}: {traj.body_name}" if name else traj.body_name,
                                getattr(traj, "method_label", traj.method))))


def _positive(option: str, text: str, unit: str) -> float:
    """An option's positive finite number, the error quoting the value as written (here and in the
    checks after it: :func:`~tumble.cli._common.number`)."""
    try:
        value = number(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{option} = {text} must be a positive finite number ({unit})")
    return value


def _saturation(text: str | float | None) -> float | None:
    """``--saturation``: a gyroscope's range in rad/s, or None. Past any MEMS gyroscope's range
    (:data:`~tumble.analysis.fit.recording.DEG_S_HINT_RATE`, 4000 deg/s) it is most likely deg/s,
    which the device file's ``gyro_full_scale`` takes: 2000 was taken as rad/s without a word."""
    if text is None:
        return None
    from ..analysis.fit.recording import DEG_S_HINT_RATE

    value = _positive("--saturation", str(text), "rad/s")
    if value > DEG_S_HINT_RATE:
        raise ValueError(f"--saturation = {text} rad/s is beyond any MEMS gyroscope's range (4000 deg/s = "
                         f"{DEG_S_HINT_RATE:.4g} rad/s): is it in deg/s? --saturation takes rad/s (a device file's "
                         f"gyro_full_scale deg/s)")
    return value
