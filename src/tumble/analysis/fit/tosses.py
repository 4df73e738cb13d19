"""The result of a recording's fit: each flight found (:class:`Toss`) and the pooled fit of the
flights used (:class:`RecordingFit`), as :func:`~tumble.analysis.fit.recording.fit_recording`
returns them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ...typing import ArrayLike
from .. import _display
from .flightmodel import FlightModel
from .result import RotationFit

__all__ = ["RecordingFit", "Toss"]


@dataclass(frozen=True)
class Toss:
    """One flight of a recording: where it is, and its own fit or why it was skipped.

    Attributes
    ----------
    start, end : float
        First and last sample's time, s.
    samples : int
    status : str
        ``"ok"`` (fitted and used in the pooled fit) or ``"skipped"``.
    reason : str
    fit : RotationFit or None
        The flight's own fit (None when there was none).
    recording : int
        The recording it is in: its index in the list given to :func:`fit_recording` (0 for one).
    sensor_offset, sensor_offset_std : tuple of float or None
        With an accelerometer: the sensor's position from the centre of mass fitted to the free
        fall and its standard uncertainty, sensor axes, m
        (:func:`~tumble.analysis.fit.freefall.fit_offset`); None without one.

    Examples
    --------
    >>> from tumble.analysis.fit import Toss, fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(22, tosses=2, flight=(0.5, 0.8))
    >>> ok, skipped = fit_recording(rec.t, rec.omega, events=rec.events).tosses
    >>> ok.status, ok.fit is not None, skipped.status, skipped.reason.startswith(("the model does not fit", "no free flight"))
    ('ok', True, 'skipped', True)
    """

    start: float
    end: float
    samples: int
    status: str
    reason: str
    fit: RotationFit | None = field(default=None, repr=False)
    recording: int = 0
    sensor_offset: tuple | None = None
    sensor_offset_std: tuple | None = None

    def __repr__(self) -> str:
        return _display.toss_repr(self)

    def summary(self) -> dict:
        """The row of ``tosses.csv`` and of fit.json's ``"tosses"`` (NaN written as None), with
        ``"sensor_offset"`` and ``"sensor_offset_std"`` (m) where the accelerometer gave them.

        Examples
        --------
        >>> from tumble.analysis.fit.tosses import Toss
        >>> row = Toss(start=1.0, end=1.8, samples=81, status="skipped", reason="too short").summary()
        >>> row["samples"], row["I1_over_I3"], row["status"]   # no fit: its numbers are None
        (81, None, 'skipped')
        """
        f = self.fit

        def num(v):
            return None if v is None or not np.isfinite(v) else float(v)

        return {"start": self.start, "end": self.end, "samples": self.samples,
                "I1_over_I3": num(f.ratios[0]) if f else None, "I2_over_I3": num(f.ratios[1]) if f else None,
                "I1_over_I3_std": num(f.ratios_std[0]) if f else None,
                "I2_over_I3_std": num(f.ratios_std[1]) if f else None,
                "edge": f.edge if f else None,  # a flight on the triangle's edge: its intervals one-sided
                "residual_rms": num(f.residual_rms) if f else None, "status": self.status, "reason": self.reason,
                **({} if self.sensor_offset is None else {"sensor_offset": list(self.sensor_offset),
                                                          "sensor_offset_std": list(self.sensor_offset_std or ())})}


@dataclass(frozen=True)
class RecordingFit:
    """The flights of a recording and the body's ratios pooled over them.

    Attributes
    ----------
    tosses : tuple of Toss
        Every flight found, usable or not, in time order (recording after recording).
    pooled : RotationFit
        The joint fit's ratios, sensor rotation, bias and drag (its ``omega0`` and
        ``omega_model`` are those of the first flight used, its rotation and bias those of that
        flight's recording).
    chi2_dof : float
        ``chi^2 / dof`` of the flights' ratios about the pooled ones (statistical uncertainties).
    tosses_used : int
    t, omega : ndarray
        The whole recording (s; rad/s, sensor axes); of several, the first.
    omega_models : tuple of ndarray
        The joint model at each used flight's samples, sensor axes, rad/s.
    recordings : tuple of (ndarray, ndarray)
        Every recording's ``(t, omega)`` (one for a single recording).
    ssr : float
        The joint fit's sum of squared residuals over the used flights' samples, (rad/s)^2 (the
        flights' own fits' sum where no joint fit was made); its minus log-likelihood up to the
        noise's variance, to compare fits of the same samples.
    residuals : int
        The number of residuals in ``ssr`` (samples times kept axes).
    flight_models : tuple of FlightModel
        The model of each used flight, in time order (:mod:`~tumble.analysis.fit.flightmodel`):
        of the joint fit (shared ratios and drag, the flight's own ``omega0``, its recording's
        rotation and bias), or each flight's own fit where no joint fit was made.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.recording import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> fit = fit_recording(rec.t, rec.omega, events=rec.events)
    >>> fit.tosses_used, len(fit.omega_models), bool(np.all(np.abs(fit.pooled.ratios - rec.ratios) < 3 * fit.pooled.ratios_std))
    (2, 2, True)
    """

    tosses: tuple
    pooled: RotationFit
    chi2_dof: float
    tosses_used: int
    t: np.ndarray = field(repr=False)
    omega: np.ndarray = field(repr=False)
    omega_models: tuple = field(default=(), repr=False)
    recordings: tuple = field(default=(), repr=False)
    ssr: float = field(default=float("nan"), repr=False)
    residuals: int = field(default=0, repr=False)
    flight_models: tuple = field(default=(), repr=False)

    def __repr__(self) -> str:
        return _display.recording_repr(self)

    def _repr_html_(self) -> str:
        return _display.recording_html(self)

    def flights_used(self) -> str:
        """How many flights the pooled fit used, of how many found, and why the others were left
        out in brief (each reason's head and its count; :attr:`tosses` hold the whole reasons).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit import RecordingFit, Toss
        >>> tosses = (Toss(0.0, 1.0, 100, "ok", ""), Toss(2.0, 2.03, 3, "skipped", "too short (0.03 s, 3 samples)"))
        >>> RecordingFit(tosses, None, 1.0, 1, np.zeros(0), np.zeros((0, 3))).flights_used()
        '1 of 2 flights (1 skipped: too short)'
        """
        return _display.flights_used(self.tosses, self.tosses_used)

    def unused_recordings(self) -> list[int]:
        """The recordings (their indices in the list given to :func:`fit_recording`) that had flights
        of which none entered the pooled fit: another body's recording among this one's, say.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit import RecordingFit, Toss
        >>> tosses = (Toss(0.0, 1.0, 100, "ok", ""), Toss(2.0, 3.0, 100, "skipped", "disagrees", recording=1))
        >>> RecordingFit(tosses, None, 1.0, 1, np.zeros(0), np.zeros((0, 3))).unused_recordings()
        [1]
        """
        found = sorted({toss.recording for toss in self.tosses})
        return [k for k in found if not any(t.status == "ok" for t in self.tosses if t.recording == k)]

    def summary(self) -> dict:
        """JSON-ready: the pooled fit's keys (as :meth:`RotationFit.summary`), ``"tosses"``, ``"pooled"``
        and ``"flight_models"`` (:meth:`FlightModel.summary <tumble.analysis.fit.flightmodel.FlightModel.summary>`
        of each used flight: what replays it).

        ``"pooled"`` says what the joint fit shares: ``"shared"`` by every flight,
        ``"per_recording"`` (the sensor's rotation and bias, when several recordings are pooled)
        and ``"per_flight"``.

        Examples
        --------
        >>> import json
        >>> from tumble.analysis.fit.recording import fit_recording
        >>> from tumble.analysis.fit.synthetic import synthetic_recording
        >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
        >>> summary = fit_recording(rec.t, rec.omega, events=rec.events).summary()
        >>> summary["pooled"]["tosses_used"], [toss["status"] for toss in summary["tosses"]], summary["pooled"]["I1_over_I3"] == summary["I1_over_I3"]
        (2, ['ok', 'ok'], True)
        >>> json.loads(json.dumps(summary)) == summary
        True
        """
        p = self.pooled
        out = p.summary()
        out["tosses"] = [toss.summary() for toss in self.tosses]
        out["pooled"] = {"I1_over_I3": float(p.ratios[0]), "I2_over_I3": float(p.ratios[1]),
                         "I1_over_I3_std": float(p.ratios_std[0]), "I2_over_I3_std": float(p.ratios_std[1]),
                         "I1_over_I3_interval": [float(v) for v in p.ratios_interval[0]],
                         "I2_over_I3_interval": [float(v) for v in p.ratios_interval[1]],
                         "edge": p.edge, "tosses_used": int(self.tosses_used),
                         "chi2_dof": float(self.chi2_dof) if np.isfinite(self.chi2_dof) else None}
        mount = ["sensor_rotation"] if p.rotvec_std is not None else []
        mount += ["bias"] if p.bias_std is not None else []
        several = len(self.recordings) > 1
        out["pooled"].update({"recordings": max(1, len(self.recordings)),
                              "shared": ["I1_over_I3", "I2_over_I3", "drag", *([] if several else mount)],
                              "per_recording": mount if several else [], "per_flight": ["omega0"]})
        out["flight_models"] = [m.summary() for m in self.flight_models]
        return out
