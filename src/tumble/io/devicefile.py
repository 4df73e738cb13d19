"""Device files (TOML): the throwing device of ``tumble calibrate`` and ``tumble tensor``.

The device is a flight controller logging its gyroscope and accelerometer, with a flywheel that
a motor spins up from the moment of release (Blaha, Kuijper, Pop & Smeur, arXiv:2503.13137)::

    [device]
    mass = 0.10067                 # kg
    rotor_axis = [0.0, 0.0, -1.0]  # sensor frame: the rotor's angular velocity for positive speed
    # rotor_inertia = 1.7e-6       # kg m^2 when known; otherwise calibrated
    [proof]                        # a body of known mass properties fixed to the device
    mass = 0.346                   # kg
    inertia = [1.675805e-4, 1.300972e-4, 2.450833e-4]   # kg m^2 about its centre of mass, sensor axes

``tumble calibrate`` writes the same file with ``rotor_inertia`` (kg m^2), ``inertia`` (3 x 3,
kg m^2, about the device's centre of mass, sensor frame), ``center_of_mass`` (m, sensor frame)
and their standard uncertainties ``rotor_inertia_std``, ``inertia_std`` (3 x 3) and
``center_of_mass_std`` added to ``[device]`` (:func:`write_device`), with the gyroscope's
distortion ``gyro_distortion`` and ``gyro_distortion_std`` (3 x 3) and the rotor's axis as
calibrated (``rotor_axis``, ``rotor_axis_std``).

How the device's own log, a Betaflight blackbox CSV (:mod:`tumble.io.blackbox`), is read takes
five optional keys of ``[device]``: ``motor_poles`` (the rotor's motor's magnet poles, even,
default 14), ``motor_index`` (the rotor's motor in the log, ``eRPM[motor_index]``, default 0),
``gyro_full_scale`` (deg/s, default 2000), ``gyro_resolution`` (deg/s per count of the log's
gyroscope, default ``gyro_full_scale / 32768``) and ``sensor_axes`` (the sensor frame's x, y, z
as signed axes of the log, the board's mounting, e.g. ``["x", "-y", "-z"]``; default
``["x", "y", "z"]``). :func:`device_toml` writes them where they are not their defaults.

The keys are those of :data:`DEVICE_FORMAT` (:mod:`tumble.io.keys`; docs/formats/device.md renders
the same tables), checked strictly here: an unknown key or table, a missing one, an uncertainty
without its value raise ``ValueError`` with one line naming the file and the table. The values are
checked by the value objects themselves (:class:`tumble.analysis.tensor.Device`,
:class:`~tumble.analysis.tensor.Proof`), so Python and files give the same message: the field,
the value as written and what is allowed, after the file and the table.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from dataclasses import fields
from pathlib import Path
from typing import Any

import numpy as np

from ..analysis.tensor import Device, Proof
from ..validation import short_repr, unknown_name
from .atomic import atomic_write_text
from .bodyfile import read_toml
from .keys import FileFormat, Key, Table

__all__ = ["DEVICE_FORMAT", "device_from_table", "device_toml", "load_calibration", "load_device", "proof_from_table",
           "write_device"]

_TENSOR = "3 numbers or 3 rows of 3"
_INERTIA_ALLOWED = "a physical tensor: symmetric, positive definite, its moments obeying the triangle inequality"
#: The tables of a device file and their keys: what :func:`load_device` accepts and what
#: docs/formats/device.md lists.
DEVICE_FORMAT = FileFormat("device", (
    Table("top level", (
        Key("device", "table", required=True, example="{mass = 0.10067, rotor_axis = [0.0, 0.0, -1.0]}",
            doc="[device]: the throwing device"),
        Key("proof", "table", example="{mass = 0.346, inertia = [1.675805e-4, 1.300972e-4, 2.450833e-4]}",
            doc="[proof]: a body of known mass properties fixed to the device, for the calibration"),
        Key("calibration", "table", example="{adequate = true, chi2_dof = 1.2}",
            doc="[calibration]: how the calibration checked itself (tumble calibrate writes it)"),
    )),
    Table("[device]", (
        Key("mass", "number", "kg", required=True, example="0.10067", low=0.0, high=10.0,
            doc="the device with its rotor"),
        Key("rotor_axis", "3 numbers", "", required=True, allowed="not zero (its length does not matter)",
            example="[0.0, 0.0, -1.0]", doc="sensor frame: the rotor's angular velocity for a positive logged speed"),
        Key("rotor_inertia", "number", "kg m^2", "(none: calibrate the device)", example="1.7e-6", low=0.0,
            doc="``J_r``, the rotor's axial moment of inertia"),
        Key("rotor_inertia_std", "number", "kg m^2", allowed=">= 0; only with rotor_inertia", example="2e-8",
            low=0.0, low_included=True, doc="its standard uncertainty"),
        Key("inertia", _TENSOR, "kg m^2", "(none: calibrate the device)", allowed=_INERTIA_ALLOWED,
            example="[[3e-5, 0.0, 0.0], [0.0, 3e-5, 0.0], [0.0, 0.0, 5e-5]]",
            doc="the device's tensor about its own centre of mass, sensor frame"),
        Key("inertia_std", "3 rows of 3", "kg m^2", allowed=">= 0 each; only with inertia",
            example="[[1e-7, 0.0, 0.0], [0.0, 1e-7, 0.0], [0.0, 0.0, 1e-7]]",
            doc="the standard uncertainty of each entry"),
        Key("center_of_mass", "3 numbers", "m", "(none: calibrate the device)", example="[0.001, 0.0, 0.002]",
            doc="the device's centre of mass, sensor frame (from the accelerometer)"),
        Key("center_of_mass_std", "3 numbers", "m", allowed=">= 0 each; only with center_of_mass",
            example="[1e-4, 1e-4, 1e-4]", doc="its standard uncertainty"),
        Key("motor_poles", "whole number", "", "14", allowed=">= 2 and even", example="12", low=2, low_included=True,
            doc="the rotor's motor's magnet poles: a blackbox log's eRPM / (poles / 2) is its speed in rev/min"),
        Key("motor_index", "whole number", "", "0", example="1", low=0, low_included=True, high=7,
            doc="which motor of a blackbox log drives the rotor: its column eRPM[motor_index]"),
        Key("gyro_full_scale", "number", "deg/s", "2000.0", example="2000.0", low=0.0,
            doc="the gyroscope's full scale (its range, +-); a blackbox log's gyroADC beyond it is refused"),
        Key("gyro_resolution", "number", "deg/s", "gyro_full_scale / 32768 (the sensor's 16-bit LSB)",
            allowed="> 0 and <= gyro_full_scale", example="1.0", low=0.0,
            doc="deg/s per count of a blackbox log's gyroADC; 1.0 where the firmware logs whole deg/s"),
        Key("sensor_axes", "3 strings", "", '["x", "y", "z"]',
            allowed='each "x", "-x", "y", "-y", "z" or "-z", each log axis once, a proper rotation (determinant +1)',
            example='["x", "-y", "-z"]',
            doc="the sensor frame's x, y, z as signed axes of a blackbox log: the board's mounting"),
        Key("gyro_scale_std", "number", "", "0.003", allowed=">= 0", example="0.002", low=0.0, low_included=True,
            doc="the gyroscope's scale factor's standard uncertainty per axis (relative), carried into the tensors'"),
        Key("gyro_misalignment_std", "number", "rad", "0.005", allowed=">= 0", example="0.003", low=0.0,
            low_included=True, doc="the gyroscope's misalignment's standard uncertainty per pair of axes"),
        Key("rotor_axis_std", "number", "rad", "0.0175", allowed=">= 0", example="0.01", low=0.0, low_included=True,
            doc="the rotor axis's direction's standard uncertainty (about each axis normal to it)"),
        Key("gyro_distortion", "3 rows of 3", "", "(none: calibrate the device)",
            allowed="symmetric, trace-free, entries within +-0.1; only with gyro_distortion_std",
            example="[[0.002, 0.001, 0.0], [0.001, -0.001, 0.0], [0.0, 0.0, -0.001]]",
            doc="the gyroscope's distortion as calibrated, omega_read = (E + D) omega; the readings are corrected "
                "by it before every fit, and rotor_axis is then the calibrated axis"),
        Key("gyro_distortion_std", "3 rows of 3", "", allowed=">= 0 each; only with gyro_distortion",
            example="[[2e-4, 1e-4, 1e-4], [1e-4, 2e-4, 1e-4], [1e-4, 1e-4, 3e-4]]",
            doc="the standard uncertainty of each entry"),
        Key("rotor_speed_range", "2 numbers", "rad/s", "(none: calibrate the device)", allowed="0 < low <= high",
            example="[1230.0, 1360.0]",
            doc="the lowest and highest of the rotor's top speeds in the calibration's throws; tumble tensor leaves out a "
                "throw whose top speed is more than 1.5 times beyond them (rpm or eRPM logged as rad/s)"),
    ), "The device: ``mass`` and ``rotor_axis`` are required; ``tumble calibrate`` writes the inertias and the "
       "centre of mass. The motor, gyroscope and mounting keys are how a flight controller's own log (a Betaflight "
       "blackbox CSV: the page on blackbox logs) is read; throw files in the sensor frame do not need them."),
    Table("[proof]", (
        Key("mass", "number", "kg", required=True, example="0.346", low=0.0, high=100.0, doc="the proof body's mass"),
        Key("inertia", _TENSOR, "kg m^2", required=True, allowed=_INERTIA_ALLOWED,
            example="[1.675805e-4, 1.300972e-4, 2.450833e-4]",
            doc="about its own centre of mass, along the sensor axes; 3 numbers: the moments along them"),
    ), "A body of known mass properties fixed to the device, for ``tumble calibrate``."),
    Table("[calibration]", (
        Key("adequate", "true or false", example="true",
            doc="whether the calibration checked out; tumble tensor refuses a device whose calibration did not"),
        Key("chi2_dof", "number", example="1.2", doc="chi^2/dof of the parallel-axis equations for the rotor's inertia"),
        Key("alone_chi2_dof", "number", example="0.9",
            doc="the device-alone throws' tensors about their joint fit (chi^2/dof)"),
        Key("proof_chi2_dof", "number", example="1.1", doc="the proof throws' tensors about their joint fit (chi^2/dof)"),
        Key("alone_used", "whole number", example="5", doc="the device-alone throws used"),
        Key("proof_used", "whole number", example="5", doc="the throws with the proof used"),
        Key("max_bias", "number", "rad/s", example="0.02", doc="the largest gyroscope bias a used throw needed"),
        Key("left_out", "list of strings", example='["a3.csv: no accelerometer in the throw"]',
            doc="each throw not used, with why"),
        Key("problems", "list of strings", example="[]", doc="what the checks found wrong, with the likely cause"),
    ), "Written by ``tumble calibrate``: the calibration's checks of itself (its consistency, each set's "
       "agreement, the gyroscope's bias), for the record and for ``tumble tensor``, which refuses a device whose "
       "calibration did not check out unless ``--accept-inadequate``."),
), "A throwing device with a rotor: ``tumble calibrate`` reads it with ``[proof]`` and writes it back "
   "calibrated; ``tumble tensor --device`` reads the calibrated one.")
_TOP, _DEVICE, _PROOF, _CALIBRATION = DEVICE_FORMAT.tables

_WHAT = "a device file (TOML)"


def _checked(keys: Table, table: object, where: str) -> dict:
    """``table`` when it is a table with only ``keys``' keys and all their required ones; else one line."""
    if not isinstance(table, dict):
        raise ValueError(f"{where} must be a table, got {short_repr(table)}")  # noqa: TRY004 - one error type for bad input
    keys.check(where, table)
    for key in keys.keys:
        if key.required and key.name not in table:
            raise ValueError(f"{where}: missing key {key.name!r} ({', '.join(filter(None, (key.unit, key.doc)))})")
    return table


def _built(make, values: dict, where: str, prefix: str):
    """``make(**values)``, its message put in the file's words: ``[device] mass = ...``."""
    try:
        return make(**values)
    except ValueError as exc:
        message = str(exc)
        message = message[len(prefix):] if message.startswith(prefix) else message
        raise ValueError(f"{where} {message}") from None


def device_from_table(table: object, *, where: str = "[device]") -> Device:
    """A :class:`~tumble.analysis.tensor.Device` from the contents of a ``[device]`` table.

    The keys are checked here; the values by :class:`~tumble.analysis.tensor.Device` itself, so
    Python and files give the same message.

    Parameters
    ----------
    table : dict
        ``mass`` (kg, > 0) and ``rotor_axis`` (3 numbers, a direction; made a unit vector), and
        optionally ``rotor_inertia`` (kg m^2, > 0), ``inertia`` (3 rows of 3, kg m^2, a physical
        tensor), ``center_of_mass`` (3 numbers, m), ``gyro_distortion`` (3 rows of 3, symmetric and
        trace-free), each with its ``_std`` (>= 0, the same shape); a ``_std`` only with its
        value; and how a blackbox log is read:
        ``motor_poles``, ``motor_index``, ``gyro_full_scale``, ``gyro_resolution``,
        ``sensor_axes`` (module docstring).
    where : str
        How the messages name the table.

    Raises
    ------
    ValueError
        One line naming the table, the field, the value as written and what is allowed.

    Examples
    --------
    >>> from tumble.io.devicefile import device_from_table
    >>> device = device_from_table({"mass": 0.10067, "rotor_axis": [0, 0, -2]})
    >>> device.mass, device.rotor_axis.tolist(), device.rotor_inertia   # the axis made a unit vector
    (0.10067, [0.0, 0.0, -1.0], None)
    >>> device_from_table({"mass": 0.1, "rotor_axis": [0, 0, 1], "rotor_inertia_std": 1e-8})
    Traceback (most recent call last):
    ...
    ValueError: [device]: rotor_inertia_std = 1e-08 given without rotor_inertia; give both or neither
    >>> device_from_table({"mass": "100 g", "rotor_axis": [0, 0, 1]})
    Traceback (most recent call last):
    ...
    ValueError: [device] mass = '100 g' must be a number (kg)
    >>> device_from_table({"mass": 0.1, "rotor_axis": [0, 0, 1], "sensor_axes": ["x", "-y", "-z"]}).sensor_axes
    ('x', '-y', '-z')
    """
    table = _checked(_DEVICE, table, where)
    for key in ("rotor_inertia", "inertia", "center_of_mass", "gyro_distortion"):
        if f"{key}_std" in table and key not in table:
            raise ValueError(f"{where}: {key}_std = {short_repr(table[f'{key}_std'])} given without {key}; "
                             "give both or neither")
    return _built(Device, dict(table), where, "device.")


def proof_from_table(table: object, *, where: str = "[proof]") -> Proof:
    """A :class:`~tumble.analysis.tensor.Proof` (the calibration's body of known mass properties)
    from the contents of a ``[proof]`` table; the values checked by the class itself.

    Parameters
    ----------
    table : dict
        ``mass`` (kg, > 0) and ``inertia`` (kg m^2 about the proof body's centre of mass, along
        the sensor axes: 3 numbers, the moments along the sensor axes, or 3 rows of 3).
    where : str
        How the messages name the table.

    Examples
    --------
    >>> from tumble.io.devicefile import proof_from_table
    >>> proof = proof_from_table({"mass": 0.346, "inertia": [1.675805e-4, 1.300972e-4, 2.450833e-4]})
    >>> proof.mass, proof.inertia.shape
    (0.346, (3, 3))
    >>> proof_from_table({"mass": 0.346, "inertia": [1e-4, 1e-4, 3e-4]})   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: [proof] inertia: principal moments (0.0001, 0.0001, 0.0003) kg m^2 violate the triangle inequality ...
    """
    table = _checked(_PROOF, table, where)
    return _built(Proof, dict(table), where, "proof.")


def load_device(path: str | os.PathLike[str], *, proof: bool = False) -> tuple[Device, Proof | None]:
    """The device (and its proof body) of a device file.

    Parameters
    ----------
    path : str or os.PathLike
        A device file (TOML) with ``[device]`` and, optionally, ``[proof]`` (module docstring).
    proof : bool
        Require ``[proof]`` (``tumble calibrate`` does).

    Returns
    -------
    device : Device
    proof : Proof or None
        None when the file has no ``[proof]``.

    Raises
    ------
    ValueError
        One line naming the file, the table and the field.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.devicefile import load_device
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "device.toml")
    ...     _ = path.write_text("[device]\\nmass = 0.1\\nrotor_axis = [0, 0, -1]\\n[proof]\\nmass = 0.346\\n"
    ...                         "inertia = [1.675805e-4, 1.300972e-4, 2.450833e-4]\\n")
    ...     device, proof = load_device(path, proof=True)
    ...     _ = path.write_text("[device]\\nmass = -0.1\\nrotor_axis = [0, 0, -1]\\n")
    ...     try:
    ...         load_device(path)
    ...     except ValueError as exc:
    ...         error = str(exc)
    >>> device.mass, proof.mass
    (0.1, 0.346)
    >>> error.split(": ", 1)[1]   # the file, the table, the field, the value and what is allowed
    '[device] mass = -0.1 must be a positive finite number (kg)'
    """
    path = Path(path)
    data = read_toml(path, what=_WHAT)
    unknown = sorted(set(data) - set(_TOP.names()))
    if unknown:
        what = "table" if isinstance(data[unknown[0]], dict) else "key"
        raise ValueError(unknown_name(str(path), unknown[0], sorted(_TOP.names()), what=what))
    for name, needed in (("device", True), ("proof", proof)):
        if needed and name not in data:
            keys = DEVICE_FORMAT.table(f"[{name}]")
            required = ", ".join(k.name for k in keys.keys if k.required)
            raise ValueError(f"{path}: missing table [{name}] ({required}: {_TOP.key(name).doc.split(': ', 1)[1]})")
    try:
        device = device_from_table(data["device"])
        body = proof_from_table(data["proof"]) if "proof" in data else None
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    return device, body


def _number(x: float) -> str:
    """A float as TOML that reads back as the same float (``repr`` round-trips)."""
    return repr(float(x))


def _row(values) -> str:
    return "[" + ", ".join(_number(v) for v in np.asarray(values, float).ravel()) + "]"


def _rows(matrix) -> str:
    m = np.asarray(matrix, float).reshape(3, 3)
    return "[\n" + "".join(f"    {_row(r)},\n" for r in m) + "]"


def _toml_value(value: object) -> str:
    """A TOML value of a [calibration] entry: a boolean, a number (``repr``) or a list of strings
    (TOML's basic strings take JSON's escapes)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value) if isinstance(value, int) else _number(float(value))
    return "[" + ", ".join(json.dumps(str(x)) for x in value) + "]"  # type: ignore[attr-defined]


def load_calibration(path: str | os.PathLike[str]) -> dict | None:
    """The ``[calibration]`` table of a device file (its checks of itself), or None when it has none.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.devicefile import load_calibration
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "cal.toml")
    ...     _ = path.write_text('[device]\\nmass = 0.1\\nrotor_axis = [0, 0, 1]\\n[calibration]\\nadequate = false\\n'
    ...                         'problems = ["the sets swapped"]\\n')
    ...     load_calibration(path)
    {'adequate': False, 'problems': ['the sets swapped']}
    """
    path = Path(path)
    data = read_toml(path, what=_WHAT)
    if "calibration" not in data:
        return None
    table = _checked(_CALIBRATION, data["calibration"], f"{path}: [calibration]")
    if not isinstance(table.get("adequate", True), bool):
        raise ValueError(f"{path}: [calibration] adequate = {short_repr(table['adequate'])} must be true or false")
    for key in ("left_out", "problems"):
        if not isinstance(table.get(key, []), list) or not all(isinstance(x, str) for x in table.get(key, [])):
            raise ValueError(f"{path}: [calibration] {key} = {short_repr(table[key])} must be a list of strings")
    return dict(table)


def _axes(axes: tuple[str, ...]) -> str:
    return "[" + ", ".join(f'"{a}"' for a in axes) + "]"


#: The keys with defaults (how a blackbox log is read, the sensors' stated uncertainties): how :func:`device_toml` writes them, their comment.
_OPTIONAL_KEYS: tuple[tuple[str, Callable[[Any], str], str], ...] = (("motor_poles", str, "the motor's magnet poles"),
                  ("motor_index", str, "the rotor's motor in a blackbox log: eRPM[motor_index]"),
                  ("gyro_full_scale", _number, "deg/s, the gyroscope's range"),
                  ("gyro_resolution", _number, "deg/s per count of a blackbox log's gyroADC"),
                  ("sensor_axes", _axes, "the sensor frame's x, y, z as axes of a blackbox log"),
                  ("gyro_scale_std", _number, "the gyroscope's scale factor's standard uncertainty"),
                  ("gyro_misalignment_std", _number, "rad, the gyroscope's misalignment's standard uncertainty"),
                  ("rotor_axis_std", _number, "rad, the rotor axis's standard uncertainty"))
_DEFAULTS = {f.name: f.default for f in fields(Device)}


def device_toml(device: Device, proof: Proof | None = None, *, header: str = "",
                calibration: dict | None = None) -> str:
    """The text of a device file: ``[device]`` with every value the device holds, and ``[proof]``.

    Every number is written so that it reads back as the same float (``repr``).

    Parameters
    ----------
    device : Device
    proof : Proof, optional
    header : str
        Comment lines put first (each prefixed with ``#`` and a space).
    calibration : dict, optional
        ``[calibration]``: how the calibration checked itself
        (:meth:`tumble.analysis.tensor.calibrate.Calibration.as_dict`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.io.devicefile import device_toml
    >>> print(device_toml(Device(mass=0.1, rotor_axis=np.array([0.0, 0.0, -1.0]), rotor_inertia=1.7e-6,
    ...                          rotor_inertia_std=2e-8), header="made by hand"))
    # made by hand
    [device]
    mass = 0.1                                # kg
    rotor_axis = [0.0, 0.0, -1.0]             # sensor frame, the rotor's angular velocity for positive speed
    rotor_inertia = 1.7e-06                   # kg m^2
    rotor_inertia_std = 2e-08                 # kg m^2, standard uncertainty
    <BLANKLINE>
    """
    lines = [f"# {line}".rstrip() for line in header.splitlines()]

    def item(key: str, text: str, comment: str) -> None:
        lines.append(f"{f'{key} = {text}':<41} # {comment}" if "\n" not in text else f"{key} = {text}  # {comment}")

    lines.append("[device]")
    item("mass", _number(device.mass), "kg")
    item("rotor_axis", _row(device.rotor_axis), "sensor frame, the rotor's angular velocity for positive speed")
    for key, write, comment in _OPTIONAL_KEYS:  # only where not the default
        value = getattr(device, key)
        if value != _DEFAULTS[key]:
            item(key, write(value), comment)
    for key, unit, write in (("rotor_inertia", "kg m^2", _number), ("inertia", "kg m^2, about the device's centre "
                             "of mass, sensor frame", _rows), ("center_of_mass", "m, sensor frame", _row),
                             ("gyro_distortion", "1, omega_read = (E + D) omega", _rows)):
        value = getattr(device, key, None)
        if value is not None:
            item(key, write(value), unit)
        std = getattr(device, f"{key}_std", None)
        if std is not None:
            item(f"{key}_std", write(std), f"{unit.split(',')[0]}, standard uncertainty")
    if device.rotor_speed_range is not None:
        item("rotor_speed_range", _row(device.rotor_speed_range), "rad/s, the calibration throws' rotor top speeds")
    if proof is not None:
        lines.append("")
        lines.append("[proof]")
        item("mass", _number(proof.mass), "kg")
        item("inertia", _rows(proof.inertia), "kg m^2 about its centre of mass, sensor axes")
    if calibration is not None:
        lines.append("")
        lines.append("[calibration]")
        for key, value in calibration.items():
            lines.append(f"{key} = {_toml_value(value)}")
    return "\n".join(lines) + "\n"


def write_device(path: str | os.PathLike[str], device: Device, proof: Proof | None = None, *,
                 header: str = "", calibration: dict | None = None) -> Path:
    """Write a device file (:func:`device_toml`) whole or not at all (:mod:`tumble.io.atomic`).

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.io.devicefile import load_device, write_device
    >>> device = Device(mass=0.1, rotor_axis=np.array([0.0, 0.0, -1.0]), center_of_mass=np.array([1e-3, 0.0, 2e-3]),
    ...                 center_of_mass_std=np.array([1e-4, 1e-4, 1e-4]))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     again, _ = load_device(write_device(pathlib.Path(folder, "calibrated.toml"), device))
    >>> again.center_of_mass.tolist() == device.center_of_mass.tolist()   # read back exactly
    True
    """
    return atomic_write_text(path, device_toml(device, proof, header=header, calibration=calibration))
