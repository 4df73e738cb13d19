"""The fitting guide's figure (docs/figures/fit_recording.png): ``tumble fit``'s ``fit.png`` of a
whole recording of three tosses that end in a catch, in a hand that turns on, and on a table,
the phone swung about at 3-10 rad/s between them:

    .venv/bin/python docs/figures/make_fit_figure.py [--out DIR]

A synthetic phone recording (tumble.analysis.fit.synthetic.synthetic_recording, seed 41, the
racquet, ``ending="mixed"``, ``hand=(3, 10)``), fitted as ``tumble fit`` fits it
(tumble.analysis.fit.fit_recording) and drawn by tumble.viz.figure_recording: |omega| and each
axis, the flights found shaded, each skipped candidate marked with its reason. Writes
DIR/fit_recording.png (DIR: docs/figures by default); tests/test_fit_find.py runs it.
"""

from __future__ import annotations

import warnings
from pathlib import Path

from figure_script import main, write

from tumble.analysis.fit import InadequateFitWarning, fit_recording
from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.viz import figure_recording


def fitted():
    """The recording and its fit, as ``tumble fit`` makes it."""
    rec = synthetic_recording(41, body="racquet", tosses=3, ending="mixed", hand=(3.0, 10.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InadequateFitWarning)
        return rec, fit_recording(rec.t, rec.omega, events=rec.events)


def make(out: Path) -> Path:
    """Write ``out/fit_recording.png``; returns its path."""
    return write(figure_recording(fitted()[1]), out, "fit_recording.png")


if __name__ == "__main__":
    main(make, __doc__)
