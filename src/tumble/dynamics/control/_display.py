"""Short plain reprs and Jupyter's HTML tables of the control runs (:class:`ControlledRun`,
:class:`DetumbleBatch`): what each is, its size and its headline numbers, never its arrays.

Numpy only; the text helpers are :mod:`tumble._html`'s. The runs are read through small
protocols: :mod:`~tumble.dynamics.control.controlled` and :mod:`~tumble.dynamics.control.detumble`
import this module, and the import graph has no circles.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

from ..._html import fmt, plural, result_html, result_repr, vec
from ...typing import FloatArray

__all__ = ["batch_html", "batch_repr", "run_html", "run_repr"]


class _Run(Protocol):
    """What the display reads of a :class:`~tumble.dynamics.control.controlled.ControlledRun`."""

    @property
    def t(self) -> FloatArray: ...
    @property
    def omega(self) -> FloatArray: ...
    @property
    def moments(self) -> FloatArray: ...
    @property
    def wheel_speed(self) -> FloatArray: ...
    @property
    def dipole(self) -> FloatArray: ...
    @property
    def rate(self) -> FloatArray: ...
    def budget_error(self) -> FloatArray: ...


class _Batch(Protocol):
    """What the display reads of a :class:`~tumble.dynamics.control.detumble.DetumbleBatch`."""

    @property
    def t(self) -> FloatArray: ...
    @property
    def rate(self) -> FloatArray: ...


def _deg(rate: float) -> str:
    return f"{fmt(math.degrees(rate), 3)} deg/s"


def _span(t: FloatArray) -> str:
    return f"{plural(len(t), 'sample')} over {fmt(t[-1] - t[0])} s" if len(t) else "no samples"


def _largest(a: FloatArray) -> float:
    return float(np.max(np.abs(a))) if a.size else 0.0


def _actuators(run: _Run) -> list[str]:
    parts = []
    if run.wheel_speed.shape[1]:
        parts.append(f"{plural(run.wheel_speed.shape[1], 'wheel')} up to {fmt(_largest(run.wheel_speed), 3)} rad/s")
    if np.any(run.dipole):
        parts.append(f"dipole up to {fmt(_largest(run.dipole), 3)} A m^2")
    return parts


def run_repr(run: _Run) -> str:
    """``ControlledRun(11 samples over 10 s, rate 5.73 -> 5.73 deg/s, budget error 0 kg m^2/s)``.

    Examples
    --------
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
    >>> repr(run)
    'ControlledRun(11 samples over 10 s, rate 5.73 -> 5.73 deg/s, budget error 0 kg m^2/s)'
    """
    parts = [_span(run.t)]
    if len(run.t):
        parts.append(f"rate {fmt(math.degrees(run.rate[0]), 3)} -> {_deg(run.rate[-1])}")
        parts += _actuators(run)
        parts.append(f"budget error {fmt(_largest(run.budget_error()), 2)} kg m^2/s")
    return result_repr("ControlledRun", parts)


def run_html(run: _Run) -> str:
    """A run's summary as an HTML table (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
    >>> page = run._repr_html_()
    >>> page.startswith("<div><table"), "5.73 deg/s" in page
    (True, True)
    """
    rows: list[tuple[str, str]] = [("samples", _span(run.t)), ("principal moments", f"{vec(run.moments)} kg m^2")]
    if len(run.t):
        rows += [("|omega| at the start", _deg(run.rate[0])), ("|omega| at the end", _deg(run.rate[-1])),
                 ("omega at the end, principal frame", f"{vec(run.omega[-1])} rad/s"),
                 ("wheels", f"{run.wheel_speed.shape[1]}, largest speed {fmt(_largest(run.wheel_speed))} rad/s"),
                 ("largest magnetorquer dipole", f"{fmt(_largest(run.dipole))} A m^2"),
                 ("momentum budget error, max |L_w - L_w(0) - impulse|", f"{fmt(_largest(run.budget_error()), 2)} kg m^2/s")]
    return result_html("ControlledRun", rows)


def batch_repr(batch: _Batch) -> str:
    """``DetumbleBatch(2 bodies, 3 samples over 2 s, final rate median 0.125 deg/s, max 0.2 deg/s)``.

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble import DetumbleBatch
    >>> out = DetumbleBatch(t=np.array([0.0, 1.0, 2.0]), rate=np.radians([[0.3, 0.1, 0.05], [0.3, 0.05, 0.2]]),
    ...                     omega=np.zeros((2, 3)), quat=np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)))
    >>> repr(out)
    'DetumbleBatch(2 bodies, 3 samples over 2 s, final rate median 0.125 deg/s, max 0.2 deg/s)'
    """
    parts = [plural(batch.rate.shape[0], "body", "bodies"), _span(batch.t)]
    if batch.rate.size:
        final = batch.rate[:, -1]
        parts += [f"final rate median {_deg(float(np.median(final)))}", f"max {_deg(float(final.max()))}"]
    return result_repr("DetumbleBatch", parts)


def batch_html(batch: _Batch) -> str:
    """A batch's summary as an HTML table (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble import DetumbleBatch
    >>> out = DetumbleBatch(t=np.array([0.0, 1.0]), rate=np.radians([[0.3, 0.1]]), omega=np.zeros((1, 3)),
    ...                     quat=np.array([[0.0, 0.0, 0.0, 1.0]]))
    >>> "0.1 deg/s" in out._repr_html_()
    True
    """
    rows: list[tuple[str, str]] = [("bodies", str(batch.rate.shape[0])), ("samples", _span(batch.t))]
    if batch.rate.size:
        start, final = batch.rate[:, 0], batch.rate[:, -1]
        rows += [("|omega| at the start, median / max", f"{_deg(float(np.median(start)))} / {_deg(float(start.max()))}"),
                 ("|omega| at the end, median / max", f"{_deg(float(np.median(final)))} / {_deg(float(final.max()))}")]
    return result_html("DetumbleBatch", rows)
