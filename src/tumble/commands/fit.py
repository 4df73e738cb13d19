"""The ``tumble fit`` command: fit a gyroscope recording and write the result, all or nothing.

- **A whole recording** (a CSV, or phyphox's export: its folder or its ``.zip``): the free
  flights are found, each fitted, and all fitted jointly (:func:`tumble.analysis.fit.fit_recording`).
  ``DIR/fit.json`` has the pooled values under the one-flight keys, plus ``"tosses"`` (one entry
  a flight, its ``"input"`` the recording as given), ``"pooled"`` and ``"read"`` (which columns of the file were taken,
  :class:`tumble.io.gyrocolumns.ColumnsRead`); ``DIR/tosses.csv`` is the table of the flights;
  ``DIR/fit.png`` the figure. When the recording has a raw accelerometer (its own columns, or
  phyphox's ``Accelerometer.csv``), the flights are cut to its free fall and fit.json says
  ``"accelerometer": true`` (a list, one per recording, for several), each toss its
  ``"sensor_offset"`` from the centre of mass (m, sensor axes) and ``"sensor_offset_std"`` (keys
  absent without an accelerometer, as before).
- **Several recordings of one body** (files, folders and zips mixed): all their flights in one
  joint fit, the ratios and the drag shared, the sensor's rotation and bias each recording's own
  (fit.json's ``"pooled"`` says so under ``"shared"`` and ``"per_recording"``). ``"input"`` and
  ``"read"`` are lists, one entry an input as given; each toss in ``"tosses"`` and in
  ``tosses.csv`` carries its ``"input"``; the provenance hashes every input.
- **One flight** (``--start``/``--end``): the samples between are fitted as one free flight
  (:func:`tumble.analysis.fit.fit_rotation`); ``DIR/fit.json`` and ``DIR/fit.png``.

Every fit.json holds ``"flight_models"``: one entry per used flight (its ``"input"``, its index in
``"tosses"`` as ``"toss"``, and the fit's model of it,
:class:`tumble.analysis.fit.flightmodel.FlightModel`), from which ``tumble view DIR`` replays it.

``--body FILE`` adds the ratios the body file predicts and how many standard uncertainties they
lie from the fit.
"""

from __future__ import annotations

import csv
import io
import json
import os
import sys
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..analysis.fit import (
    SCALE_UNCERTAINTY,
    InadequateFitWarning,
    NoFlightError,
    fit_recording,
    fit_rotation,
)
from ..analysis.fit.flightmodel import FlightModel
from ..analysis.fit.single import MIN_SAMPLES
from ..analysis.fit.recording import samples_sha256, unit_hint
from ..io.gyrodata import load_recording
from ..io.throwfile import is_rotor_column
from ..io.output import FIGURE_DPI, check_output_dir, output_dir
from ..io.provenance import input_sha256, provenance
from ..validation import check_number

__all__ = ["OFFSET_COLUMNS", "TOSS_COLUMNS", "run_fit_command"]

#: The columns of ``tosses.csv`` (and the keys of fit.json's ``"tosses"`` entries, which add
#: ``"sensor_offset"`` and ``"sensor_offset_std"`` where the recording has an accelerometer).
TOSS_COLUMNS = ("input", "start", "end", "samples", "I1_over_I3", "I2_over_I3", "I1_over_I3_std", "I2_over_I3_std",
                "edge", "residual_rms", "status", "reason")

_METHOD = ("least squares on the exact torque-free solution (Landau & Lifshitz sec. 37) or Euler's equations "
           "with per-axis drag (RK4); uncertainties: (J^T J)^-1 s^2 times the residuals' integrated "
           "autocorrelation time (Geyer's initial positive sequence), plus the gyroscope's scale-factor tolerance "
           "(GUM 5.1); pooled: joint fit, statistical covariance times chi^2/dof when above 1 (the std times the Birge ratio, its square root); "
           "adequacy: the model's error beyond the noise at most 3 % of the rates")


def _body_comparison(body_source, ratios, std) -> dict:
    from ..io.bodyfile import load_body  # here: the body's modules load only when --body is given

    body = load_body(body_source)
    I = np.asarray(body.principal_moments, float)
    pred = I[:2] / I[2]
    z = (pred - np.asarray(ratios)) / np.asarray(std)
    return {"source": os.fspath(body_source), "I1_over_I3": float(pred[0]), "I2_over_I3": float(pred[1]),
            "I1_over_I3_sigmas": float(z[0]), "I2_over_I3_sigmas": float(z[1])}


#: The columns ``tosses.csv`` adds where an accelerometer gave a toss's sensor offset from the
#: centre of mass (m, sensor axes; blank for a toss without one).
OFFSET_COLUMNS = tuple(f"sensor_offset_{a}{std}" for std in ("", "_std") for a in "xyz")


def _tosses_csv(rows) -> str:
    offsets = any("sensor_offset" in row for row in rows)
    columns = TOSS_COLUMNS + (OFFSET_COLUMNS if offsets else ())
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        cells = {k: ("" if row[k] is None else row[k]) for k in TOSS_COLUMNS}
        if offsets:
            values = [*(row.get("sensor_offset") or [""] * 3), *(row.get("sensor_offset_std") or [""] * 3)]
            cells.update(zip(OFFSET_COLUMNS, values))
        writer.writerow(cells)
    return buf.getvalue()


def run_fit_command(path: str | os.PathLike[str] | Sequence[str | os.PathLike[str]], out: str | os.PathLike[str], *, argv: Sequence[str] | None = None,
                    figure: Callable[..., Any] | None = None, recording_figure: Callable[..., Any] | None = None,
                    start: float | None = None, end: float | None = None, body: str | os.PathLike[str] | None = None,
                    progress: Callable[[int, int], None] | None = None, accept_inadequate: bool = False,
                    **options: Any) -> int:
    """``tumble fit RECORDING --out DIR`` (module docstring); prints one line.

    Parameters
    ----------
    path : str or Path, or a list of them
        A gyroscope CSV or a phyphox export (folder or ``.zip``):
        :func:`tumble.io.gyrodata.load_recording`; several (a list of two or more): recordings
        of one body, pooled (module docstring).
    out : str or Path
        The output folder (written whole or not at all).
    argv : list of str, optional
        The command line after ``tumble``, for the provenance.
    figure : callable, optional
        ``figure(fit, omega_measured)`` -> matplotlib Figure for one flight
        (:func:`tumble.viz.figure_fit`).
    recording_figure : callable, optional
        ``recording_figure(recording_fit)`` -> Figure for a whole recording
        (:func:`tumble.viz.figure_recording`).
    start, end : float, optional
        Fit only the samples with ``start <= t <= end`` as one flight, s (one recording only).
    body : str or Path, optional
        A body file or preset whose ratios are compared with the fit.
    progress : callable, optional
        ``progress(done, total)`` while the flights of a recording are fitted.
    accept_inadequate : bool
        Return 0 for a fit whose model does not describe the data (:mod:`tumble.analysis.fit.adequacy`);
        by default such a fit is written (``"adequate": false`` and the reason in fit.json, for the
        figure to show what is wrong), a warning line printed, and 1 returned.
    **options
        Passed to the fit (``sensor_rotation``, ``bias``, ``drag``, ``saturation``, ``scale_uncertainty``:
        None for the default :data:`~tumble.analysis.fit.SCALE_UNCERTAINTY`, which fit.json records).

    Returns
    -------
    int
        0 on success; 1 for an inadequate fit unless accepted, or for a recording in which no
        flight could be fitted (one line on stderr, nothing written); bad input raises
        ``ValueError`` with one line (nothing is written).

    Examples
    --------
    >>> import json, tempfile
    >>> from importlib import resources
    >>> from pathlib import Path
    >>> from tumble.commands.fit import run_fit_command
    >>> record = resources.files("tumble") / "examples/data/phone_toss.csv"  # a box 15 x 7.5 x 0.8 cm
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     status = run_fit_command(record, Path(folder) / "fit", end=2.0)  # doctest: +ELLIPSIS
    ...     fit = json.loads((Path(folder) / "fit" / "fit.json").read_text())
    fit ...: I1/I3 = 0.2023 +- 0.0023, I2/I3 = 0.8023 +- 0.0031 from 200 samples, ...
    >>> status, round(fit["I1_over_I3"], 3), round((7.5**2 + 0.8**2) / (15**2 + 7.5**2), 3)  # fitted vs true
    (0, 0.202, 0.202)
    """
    check_output_dir(out)
    if options.get("scale_uncertainty", SCALE_UNCERTAINTY) is None:  # the command line's option not given
        options.pop("scale_uncertainty")
    elif not 0.0 <= check_number("--scale-uncertainty", options.get("scale_uncertainty", SCALE_UNCERTAINTY), "") < 0.5:
        raise ValueError(f"--scale-uncertainty {options['scale_uncertainty']!r} must be a fraction from 0 to 0.5 (0.01 for "
                         "1 % per axis)")
    paths = list(path) if isinstance(path, (list, tuple)) else [path]
    if not paths:
        raise ValueError("no recording given; name one or more files, phyphox folders or .zip exports")
    if len(paths) > 1 and (start is not None or end is not None):
        raise ValueError(f"--start/--end select one flight of one recording; {len(paths)} recordings given")
    recs = [load_recording(p) for p in paths]
    labels = [os.fspath(p) for p in paths]
    if body is not None:
        from ..io.bodyfile import load_body

        try:  # a bad body file is bad input before anything is computed, named as --body's (a walkthrough)
            load_body(body)
        except (ValueError, FileNotFoundError) as exc:  # the same kind (a missing file stays a FileNotFoundError)
            raise type(exc)(f"--body: {exc}") from None
    digests = [input_sha256(p) for p in paths]
    first: dict[str, int] = {}
    for k, r in enumerate(recs):  # by content, not name: a copy, a symlink, a zip and its folder
        j = first.setdefault(samples_sha256(r.t, r.omega), k)
        if j != k:
            same = "given twice" if labels[k] == labels[j] else f"the same recording as {labels[j]} (identical samples)"
            raise ValueError(f"{labels[k]}: {same}; a recording given twice counts its flights twice: give each "
                             "recording once")
    for lab, r in zip(labels, recs):  # said at once, not only after a fit of some seconds fails
        if hint := unit_hint(r.omega):
            print(f"warning: {lab}: {hint[2:]}", file=sys.stderr)
    several = len(paths) > 1
    label = labels[0] if not several else f"{len(paths)} recordings"
    t, omega, events = recs[0].t, recs[0].omega, list(recs[0].events)
    record: dict[str, Any] = {"input": labels if several else labels[0],
                              "read": [r.read.summary() for r in recs] if several else recs[0].read.summary()}
    files = {}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", InadequateFitWarning)  # said below in one line
            if start is not None or end is not None:
                # a time that is no finite number is refused as such, before the two are compared
                lo = -np.inf if start is None else check_number("--start", start, "s")
                hi = np.inf if end is None else check_number("--end", end, "s")
                if not lo < hi:
                    raise ValueError(f"--start {start!r} must be before --end {end!r} (s)")
                sel = (t >= lo) & (t <= hi)
                if np.count_nonzero(sel) < MIN_SAMPLES:  # a window outside the recording: say where it is
                    window = (f"--start {start!r}" if start is not None else "the start") + " to " + \
                        (f"--end {end!r}" if end is not None else "the end")  # an option not given: the recording's own
                    raise ValueError(f"{window} holds {np.count_nonzero(sel)} samples (at least "
                                     f"{MIN_SAMPLES} fit a flight); the recording runs from {t[0]:.6g} to {t[-1]:.6g} s")
                fit = fit_rotation(t[sel], omega[sel], **options)
                record.update({"start": start, "end": end, **fit.summary()})
                record["flight_models"] = [{"input": labels[0], **FlightModel.of_fit(fit).summary()}]
                pooled, line = fit, f"{fit.samples} samples"
                draw = (lambda: figure(fit, omega[sel])) if figure is not None else None
            else:
                data = (t, omega) if not several else ([(r.t, r.omega, list(r.events), r.accel) for r in recs], None)
                rec = fit_recording(*data, events=events if not several else None, progress=progress,
                                    accel=recs[0].accel if not several else None, **options)
                record.update({"start": None, "end": None, **rec.summary()})
                used = [r.accel is not None for r in recs]  # the flights cut to the accelerometer's free fall
                record["accelerometer"] = used if several else used[0]
                record["tosses"] = [{"input": labels[toss.recording], **row}  # the recording as given
                                    for toss, row in zip(rec.tosses, record["tosses"])]
                files["tosses.csv"] = _tosses_csv(record["tosses"])
                record["flight_models"] = [{"input": labels[m["recording"]], **m} for m in record["flight_models"]]
                pooled = rec.pooled
                line = (rec.flights_used()
                        + (f" in {len(paths)} recordings (sensor mount and bias per recording)" if several else "")
                        + (f", chi2/dof {rec.chi2_dof:.2g}" if np.isfinite(rec.chi2_dof) else ""))
                draw = (lambda: recording_figure(rec)) if recording_figure is not None else None
    except NoFlightError as err:  # a readable recording without a flight to fit: the fit failed
        rotor = any(is_rotor_column(name) for r in recs for name in r.read.ignored)
        hint = " (its rotor column says it is a throw of the flywheel device: 'tumble tensor' fits those)" if rotor else ""
        print(f"tumble: fit failed: {label}: {err}{hint}; nothing written", file=sys.stderr)
        return 1
    except ValueError as err:
        text = str(err)
        if several and text.startswith("recording "):  # "recording 2: ..." named by its input
            number, _, rest = text[len("recording "):].partition(": ")
            if number.isdigit() and int(number) < len(labels):
                raise ValueError(f"{labels[int(number)]}: {rest}") from None
        raise ValueError(f"{label}: {text}") from None
    if body is not None:
        record["body"] = _body_comparison(body, pooled.ratios, pooled.ratios_std)
    # the gyroscope's scale tolerance assumed: it sets the systematic part of the uncertainties (a walkthrough
    # found no word of the 0.5 % in fit.json, nor a way to give 1 % on the command line; 2026-12-03)
    record["scale_uncertainty"] = float(options.get("scale_uncertainty", SCALE_UNCERTAINTY))
    record["method"] = _METHOD
    record["provenance"] = provenance(argv, list(zip(labels, digests)))
    owns = ("fit.json", "fit.png", "tosses.csv")
    with output_dir(out, owns=owns) as stage:
        (Path(stage) / "fit.json").write_text(json.dumps(record, indent=2, allow_nan=False) + "\n", encoding="utf-8")
        for name, text in files.items():
            (Path(stage) / name).write_text(text, encoding="utf-8")
        if draw is not None:  # drawn by the caller's layer, written here into the staged folder
            draw().savefig(Path(stage) / "fit.png", dpi=FIGURE_DPI)
    written = ", ".join(["fit.json", *files, *(["fit.png"] if draw is not None else [])])
    (x, y), (sx, sy) = pooled.ratios, pooled.ratios_std
    edge = f" [{pooled.edge}]" if pooled.edge else ""
    read = recs[0].read.brief() if not several else f"{sum(r.read.rows for r in recs)} rows from {len(recs)} files"
    compared = ""  # --body: what it predicts and how far from the fit, as fit.json's "body" says
    if body is not None:
        b = record["body"]
        compared = (f"; {b['source']} predicts I1/I3 = {b['I1_over_I3']:.4f} ({b['I1_over_I3_sigmas']:+.1f} sigma), "
                    f"I2/I3 = {b['I2_over_I3']:.4f} ({b['I2_over_I3_sigmas']:+.1f} sigma)")
    # an inadequate fit's line says so itself: read without stderr's warning, it looked like an answer (a walkthrough)
    verdict = "" if pooled.adequate else " (not adequate: see the warning)"
    print(f"fit {label}{verdict}: I1/I3 = {x:.4f} +- {sx:.2g}, I2/I3 = {y:.4f} +- {sy:.2g}{edge} from {line}, drag "
          f"{pooled.drag}, residual {pooled.residual_rms:.3g} rad/s{compared}; read {read}; wrote {written} in "
          f"{os.fspath(out)}")
    if pooled.caveat:
        print(f"warning: {pooled.caveat}", file=sys.stderr)
    for k in rec.unused_recordings() if several else ():  # a recording whose every flight was left out
        own = [toss for toss in rec.tosses if toss.recording == k]  # one at least (unused_recordings)
        which = f"none of its {len(own)} flights entered" if len(own) > 1 else "its one flight did not enter"
        print(f"warning: {labels[k]}: {which} the pooled fit "
              f"({own[0].reason}; tosses.csv has each one's reason): is it a recording of this body?", file=sys.stderr)
    if not pooled.adequate:
        print(f"warning: {pooled.adequacy}" + ("" if accept_inadequate else
              " (fit.json says \"adequate\": false; --accept-inadequate to accept the fit)"), file=sys.stderr)
        return 0 if accept_inadequate else 1
    return 0
