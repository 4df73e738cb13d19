"""The ``tumble calibrate`` and ``tumble tensor`` commands: a flywheel device's throws to an
absolute inertia tensor, the result written whole or not at all.

- ``tumble calibrate DEVICE.toml --alone A1.csv ... --proof P1.csv ... --out CALIBRATED.toml``:
  the rotor's inertia, the device's own tensor (about its centre of mass, sensor frame) and its
  centre of mass, each with its standard uncertainty, from throws of the device alone and with
  the proof body of ``[proof]`` (:func:`tumble.analysis.tensor.calibrate_device`); written into
  ``[device]`` of CALIBRATED.toml (:mod:`tumble.io.devicefile`), the inputs and their SHA-256
  in its first comment lines.
- ``tumble tensor THROW... --device CALIBRATED.toml --mass KG --out DIR``: each throw fitted and
  all of them jointly (:func:`tumble.analysis.tensor.fit_tensor`); ``DIR/tensor.json`` holds
  :meth:`~tumble.analysis.tensor.TensorFit.as_dict` (``"object"``, ``"flown"``, ``"throws"``,
  ``"adequate"``, ``"chi2_dof"``) with the inputs, the columns read from each
  (:meth:`tumble.io.throwfile.ThrowRead.summary`) and the provenance, ``DIR/tensor.png`` the
  figure (:func:`tumble.viz.tensor.figure_tensor`), ``DIR/throws.npz`` each throw's fitted
  samples, model rates and rotor speed (:mod:`tumble.io.tensorfolder`; ``tumble view DIR`` shows
  them), and the object as a simulator's inertial element, ``DIR/inertial.urdf`` (URDF) and
  ``DIR/inertial.xml`` (MuJoCo's MJCF), sensor frame (:mod:`tumble.io.inertial`).

The throw files are :mod:`tumble.io.throwfile`'s; the method is the gyrostat's output-error fit
of :mod:`tumble.analysis.tensor` (Blaha, Kuijper, Pop & Smeur, arXiv:2503.13137, with the
differences that docs/tensor.md lists).
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..analysis.tensor import Device, NoThrowError, fit_tensor
from ..analysis.tensor.calibrate import calibrate
from ..analysis.tensor.device import check_thrown_mass
from ..io.devicefile import load_calibration, load_device, write_device
from ..io.inertial import mjcf_inertial, urdf_inertial
from ..io.output import FIGURE_DPI, check_output_dir, check_output_file, output_dir
from ..io.provenance import file_sha256, provenance
from ..io.tensorfolder import THROWS_FILE, throw_series, write_throw_series
from ..io.throwfile import load_throw

__all__ = ["TENSOR_WRITES", "run_calibrate_command", "run_tensor_command"]

#: The files ``tumble tensor`` writes into its folder (tensor.png only with a figure).
TENSOR_WRITES = ("tensor.json", "tensor.png", THROWS_FILE, "inertial.urdf", "inertial.xml")

_METHOD = ("output-error least squares on the gyrostat's equations in the momentum form (Hughes, Spacecraft Attitude "
           "Dynamics, 1986, ch. 7) with the measured rotor speed as input, integrated at the real sample times, over "
           "physical tensors only (Wensing, Kim & Slotine 2018); the flight, the gyroscope's bias and the drag from the "
           "data; centres of mass from the accelerometer's specific force (Goldstein sec. 4.10); the device subtracted "
           "with the parallel-axis theorem (Goldstein sec. 5.3); uncertainties: (J^T J)^-1 s^2 times the residuals' "
           "autocorrelation time, propagated to first order (GUM 5.1), the rotor inertia's a systematic part common to "
           "all throws; pooled: inverse-covariance mean, its statistical part scaled by the Birge ratio chi^2/dof when "
           "above 1. The device: Blaha, Kuijper, Pop & Smeur, arXiv:2503.13137")


def _throws(paths: Sequence[str | os.PathLike[str]], option: str, device: Device | None = None) -> list:
    """The throws of ``paths`` and what was read of each (:func:`load_throw`), a blackbox log read
    with the device's motor, gyroscope and mounting."""
    if not paths:
        raise ValueError(f"{option}: no throw given; name one or more throw files (CSV)")
    return [load_throw(p, device) for p in paths]


def _failed(err: BaseException, loaded: Sequence, device: Device) -> str:
    """The one line of a fit that used no throw; where it suspects the rotor's axis and a throw
    came from a blackbox log, it names the device file's ``sensor_axes`` too: a board mounted
    otherwise than they say turns the rotor's axis in the sensor frame (a walkthrough's logs of a
    board upside down failed as "degenerate: the rotor's axis or the sign of its speed may be
    wrong", and turned a third about a diagonal as residuals 15-87 times the noise, the key never
    named)."""
    line = _one_line(err)
    if "rotor's axis" in line or "rotor axis" in line:
        if any(read.axes for _, read in loaded):
            line += (f"; the blackbox logs were turned by the device file's sensor_axes = {json.dumps(list(device.sensor_axes))}: "
                     "a board mounted otherwise turns the rotor's axis too")
    return line


def _missing_calibration(device: Device) -> list[str]:
    return [key for key in ("rotor_inertia", "inertia", "center_of_mass") if getattr(device, key) is None]


def _one_line(err: BaseException) -> str:
    return " ".join(str(err).split())


def _mm(v) -> str:
    return "[" + ", ".join(f"{1e3 * x:.3g}" for x in np.asarray(v, float)) + "] mm"


def run_calibrate_command(device: str | os.PathLike[str], alone: Sequence[str | os.PathLike[str]],
                          proof: Sequence[str | os.PathLike[str]], out: str | os.PathLike[str], *,
                          argv: Sequence[str] | None = None, saturation: float | None = None,
                          accept_inadequate: bool = False) -> int:
    """``tumble calibrate``: the device calibrated from its throws, written to ``out`` (module
    docstring); prints one line.

    Parameters
    ----------
    device : str or Path
        The device file (TOML) with ``[device]`` and ``[proof]`` (:mod:`tumble.io.devicefile`).
    alone, proof : list of str or Path
        Throw files of the device alone and of the device with the proof body fixed to it.
    out : str or Path
        The calibrated device file to write (``.toml``): the input's ``[device]`` with
        ``rotor_inertia``, ``inertia``, ``center_of_mass`` and their ``_std``, and its ``[proof]``.
    argv : list of str, optional
        The command line after ``tumble``, for the comment lines of the file written.
    saturation : float, optional
        The gyroscope's full scale, rad/s (default: the device's ``gyro_full_scale``).
    accept_inadequate : bool
        Return 0 for a calibration that does not check itself out
        (:class:`tumble.analysis.tensor.calibrate.Calibration`); by default it is written with
        ``[calibration] adequate = false``, each problem printed and 1 returned.

    Returns
    -------
    int
        0 on success; 1 when none of the throws could be fitted or the rotor's inertia is not
        positive (one line on stderr, nothing written), or the calibration does not check out
        (written, unless accepted). Bad input raises ``ValueError`` with one line (nothing is
        written).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.commands.tensor import run_calibrate_command
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     try:
    ...         run_calibrate_command(Path(folder) / "device.toml", ["a1.csv"], ["p1.csv"], Path(folder) / "out.toml")
    ...     except ValueError as exc:
    ...         print(str(exc).split(": ", 1)[1])   # the device file is read before anything else
    no such file
    """
    out = check_output_file(out, ".toml")
    if Path(out).resolve() == Path(device).resolve():  # a walkthrough's --out over the input: its comments lost, no word
        raise ValueError(f"--out {os.fspath(out)}: the device file itself; write the calibrated device to a new file "
                         "(the device file is an input, and the calibration's record names it)")
    dev, body = load_device(device, proof=True)
    assert body is not None  # required above
    alone_loaded = _throws(alone, "--alone", dev)
    proof_loaded = _throws(proof, "--proof", dev)
    inputs = [(os.fspath(p), file_sha256(p)) for p in (device, *alone, *proof)]
    try:
        result = calibrate(dev, [t for t, _ in alone_loaded], [t for t, _ in proof_loaded], body, saturation=saturation)
    except NoThrowError as err:  # well-formed throws, none of them fitted: the computation failed
        print(f"tumble: calibration failed: {_failed(err, alone_loaded + proof_loaded, dev)}; nothing written",
              file=sys.stderr)
        return 1
    calibrated = result.device
    if calibrated.rotor_inertia is None:  # no rotor inertia to write: the sets swapped
        print(f"tumble: calibration failed: {'; '.join(result.problems)}; nothing written", file=sys.stderr)
        return 1
    record = provenance(argv, inputs)
    lines = [f"Calibrated by tumble {record['tumble']} on {record['created']}: {len(alone)} throw(s) of the device "
             f"alone, {len(proof)} with the proof body"]
    if record["command"]:
        lines.append(f"command: {json.dumps(record['command'])}")
    lines += [f"input {json.dumps(p)} sha256 {h}" for p, h in inputs]  # quoted: a name holds no line break here
    write_device(out, calibrated, body, header="\n".join(lines), calibration=result.as_dict())
    J, Jstd = calibrated.rotor_inertia, calibrated.rotor_inertia_std
    rotor = f"{J:.4g}" + ("" if Jstd is None else f" +- {Jstd:.2g}")
    moments = np.linalg.eigvalsh(np.asarray(calibrated.inertia, float))
    agree = ", ".join(f"{name} {x:.2g}" for name, x in (("alone", result.alone_chi2_dof), ("proof", result.proof_chi2_dof))
                      if np.isfinite(x))
    # a calibration that does not check out is written (adequate = false) but not called calibrated
    print(f"{'not calibrated' if result.problems else 'calibrated'} {os.fspath(device)}: rotor inertia {rotor} kg m^2, "
          f"device principal moments "
          f"{', '.join(f'{x:.4g}' for x in moments)} kg m^2, centre of mass {_mm(calibrated.center_of_mass)} "
          f"from {result.alone_used} + {result.proof_used} of {len(alone)} + {len(proof)} throws; chi2/dof "
          f"{result.chi2_dof:.2g}" + (f" (sets: {agree})" if agree else "") + f", largest gyroscope bias "
          f"{result.max_bias:.2g} rad/s; wrote {os.fspath(out)}" + (", adequate = false" if result.problems else ""))
    if dev.rotor_inertia is not None:  # a value given in the file: estimated again, never used (a walkthrough, 2026-12-03)
        apart = J / dev.rotor_inertia - 1.0
        print(f"note: the device file's rotor_inertia {dev.rotor_inertia:.4g} kg m^2 is replaced by the calibration's "
              f"{J:.4g} ({100 * apart:+.2g} %" + ("" if not Jstd else f", {abs(J - dev.rotor_inertia) / Jstd:.2g} std")
              + "), which the proof body's known tensor fixes", file=sys.stderr)
    for why in result.left_out:
        print(f"warning: left out {why}", file=sys.stderr)
    if result.problems:
        for why in result.problems:
            print(f"warning: the calibration does not check out: {why}", file=sys.stderr)
        print(f"warning: {os.fspath(out)} says [calibration] adequate = false; tumble tensor refuses it" +
              ("" if accept_inadequate else "; --accept-inadequate to accept the calibration"), file=sys.stderr)
        return 0 if accept_inadequate else 1
    return 0


def run_tensor_command(throws: Sequence[str | os.PathLike[str]], device: str | os.PathLike[str], mass: float,
                       out: str | os.PathLike[str], *, argv: Sequence[str] | None = None,
                       figure: Callable[[Any], Any] | None = None, accept_inadequate: bool = False,
                       saturation: float | None = None) -> int:
    """``tumble tensor``: an object's tensor from its throws, written to the folder ``out`` (module
    docstring); prints one line.

    Parameters
    ----------
    throws : list of str or Path
        Throw files (CSV, :mod:`tumble.io.throwfile`) of the object with the device fixed to it.
    device : str or Path
        A calibrated device file (``tumble calibrate``'s output).
    mass : float
        The object's mass, kg (weighed).
    out : str or Path
        The output folder (written whole or not at all).
    argv : list of str, optional
        The command line after ``tumble``, for the provenance.
    figure : callable, optional
        ``figure(tensor_fit)`` -> matplotlib Figure (:func:`tumble.viz.tensor.figure_tensor`);
        without it no tensor.png is written.
    accept_inadequate : bool
        Return 0 for a fit whose model does not describe the throws; by default such a fit is
        written (``"adequate": false``), a warning printed and 1 returned.
    saturation : float, optional
        The gyroscope's full scale, rad/s (default: found from the data).

    Returns
    -------
    int
        0 on success; 1 for an inadequate fit unless accepted (written), or when none of the
        throws could be fitted (one line on stderr, nothing written). Bad input raises
        ``ValueError`` with one line (nothing is written).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.commands.tensor import run_tensor_command
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     try:
    ...         run_tensor_command(["o1.csv"], "calibrated.toml", -1.0, Path(folder) / "out")
    ...     except ValueError as exc:
    ...         print(exc)   # the options are checked before any file is read
    --mass = -1.0 must be a positive finite number (kg)
    """
    out = check_output_dir(out)
    mass = check_thrown_mass("--mass", mass)
    dev, _ = load_device(device)
    missing = _missing_calibration(dev)
    if missing:
        raise ValueError(f"{os.fspath(device)}: [device] has no {', '.join(missing)}; calibrate the device first: "
                         f"tumble calibrate {os.fspath(device)} --alone ... --proof ... --out CALIBRATED.toml")
    if not throws:
        raise ValueError("THROW: no throw given; name one or more throw files (CSV)")
    checks = load_calibration(device)
    if checks is not None and not checks.get("adequate", True) and not accept_inadequate:
        print(f"tumble: tensor refused: the calibration of {os.fspath(device)} did not check out "
              f"({'; '.join(checks.get('problems', [])) or 'adequate = false'}); calibrate again, or "
              "--accept-inadequate to use it; nothing written", file=sys.stderr)
        return 1
    loaded = [load_throw(p, dev) for p in throws]
    thrown = [throw for throw, _ in loaded]
    inputs = [(os.fspath(p), file_sha256(p)) for p in (device, *throws)]
    try:
        fit = fit_tensor(thrown, dev, mass, saturation=saturation)
    except NoThrowError as err:  # well-formed throws, none of them fitted: the computation failed
        print(f"tumble: tensor failed: {_failed(err, loaded, dev)}; nothing written", file=sys.stderr)
        return 1
    record: dict[str, Any] = fit.as_dict()
    record["input"] = [os.fspath(p) for p in throws]
    record["read"] = [read.summary() for _, read in loaded]  # the columns taken and their units, a file each
    record["device"] = os.fspath(device)
    record["method"] = _METHOD
    record["provenance"] = provenance(argv, inputs)
    text = json.dumps(record, indent=2, allow_nan=False) + "\n"
    used = sum(1 for t in fit.throws if t.status == "used")
    note = f"from {used} of {len(fit.throws)} throws; tensor.json beside this file holds the covariances" + (
        "" if fit.adequate else "; the model did NOT describe the throws (tensor.json: adequate false)")
    series = throw_series(fit.throws, thrown)  # the fitted samples and the rotor's speed, for tumble view DIR
    with output_dir(out, owns=TENSOR_WRITES) as stage:
        (Path(stage) / "tensor.json").write_text(text, encoding="utf-8")
        write_throw_series(Path(stage) / THROWS_FILE, series)
        (Path(stage) / "inertial.urdf").write_text(urdf_inertial(fit.object, note=note), encoding="utf-8")
        (Path(stage) / "inertial.xml").write_text(mjcf_inertial(fit.object, note=note), encoding="utf-8")
        if figure is not None:
            figure(fit).savefig(Path(stage) / "tensor.png", dpi=FIGURE_DPI)
    obj = fit.object
    moments = ", ".join(f"{x:.4g} +- {s:.2g}" for x, s in zip(obj.principal_moments, obj.principal_moments_std))
    chi2 = f", chi2/dof {fit.chi2_dof:.2g}" if np.isfinite(fit.chi2_dof) else ""
    written = ", ".join(name for name in TENSOR_WRITES if figure is not None or name != "tensor.png")
    print(f"tensor: principal moments {moments} kg m^2, centre of mass {_mm(obj.center_of_mass)} from {used} of "
          f"{len(fit.throws)} throws{chi2}; wrote {written} in {os.fspath(out)}")
    for row in fit.throws:
        if row.status != "used":
            print(f"warning: left out {row.input}: {row.reason}", file=sys.stderr)
    if fit.on_edge > 0:
        print(f"note: the object's estimate broke the triangle inequality I1 + I2 >= I3 by {fit.on_edge:.2g} standard "
              "uncertainties (a flat body's lies on either side of it): the tensor written is its nearest on the edge "
              "I1 + I2 = I3 (tensor.json's \"on_edge\")", file=sys.stderr)
    if not fit.adequate:
        print("warning: the model does not describe the throws (tensor.json says \"adequate\": false; see each "
              "throw's reason)" + ("" if accept_inadequate else "; --accept-inadequate to accept the fit"),
              file=sys.stderr)
        return 0 if accept_inadequate else 1
    return 0
