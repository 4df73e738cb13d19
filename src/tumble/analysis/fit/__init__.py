"""The inverse problem: inertia ratios from a measured tumble (a gyroscope's angular velocity).

Rooms: :mod:`~tumble.analysis.fit.triangle` (the closed triangle of ratios and the fit's
coordinates), :mod:`~tumble.analysis.fit.model` (one or many flights of one body seen by a
rotated, biased sensor, with drag), :mod:`~tumble.analysis.fit.start` (starting values),
:mod:`~tumble.analysis.fit.solve` (least squares, undetermined parameters, the drag model),
:mod:`~tumble.analysis.fit.uncertainty` (the residuals' autocorrelation, the scale factor, intervals,
pooling), :mod:`~tumble.analysis.fit.adequacy` (whether the model fits at all),
:mod:`~tumble.analysis.fit.single` (one flight: :func:`fit_rotation`),
:mod:`~tumble.analysis.fit.segments` (where a whole recording is cut: pauses, gaps, impulses),
:mod:`~tumble.analysis.fit.flights` (finding the free flights of a whole recording),
:mod:`~tumble.analysis.fit.freefall` (an accelerometer's free fall: the flights' ends and the
sensor's offset from the centre of mass),
:mod:`~tumble.analysis.fit.recording` (fitting them one by one and jointly:
:func:`fit_recording`) and :mod:`~tumble.analysis.fit.synthetic` (realistic phone recordings,
for tests and examples; their accelerometer: :mod:`~tumble.analysis.fit.accelsynth`).

From periods instead of a gyroscope record: :func:`tumble.analysis.periods_consistent`
(:mod:`tumble.analysis.period_inversion`).
"""

from .adequacy import InadequateFitWarning
from .flights import Flight, find_flights
from .recording import NoFlightError, fit_recording
from .tosses import RecordingFit, Toss
from .result import RotationFit
from .single import MIN_SAMPLES, fit_rotation, saturation_mask
from .uncertainty import SCALE_UNCERTAINTY

__all__ = ["MIN_SAMPLES", "SCALE_UNCERTAINTY", "Flight", "InadequateFitWarning", "NoFlightError", "RecordingFit", "RotationFit", "Toss", "find_flights",
           "fit_recording", "fit_rotation", "saturation_mask"]
