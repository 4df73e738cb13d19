"""A ``tumble tensor`` output folder: its throws' time series written (``throws.npz``) and the
folder read back (:func:`read_tensor_folder`) for ``tumble view DIR``.

``DIR/tensor.json`` holds the estimates (:meth:`tumble.analysis.tensor.TensorFit.as_dict`) but
not the samples; ``DIR/throws.npz`` holds, for each throw in ``tensor.json``'s ``"throws"``
order (``K`` = 0, 1, ...), what was fitted (NumPy's ``.npz``: a zip of ``.npy`` arrays, NEP 1;
``numpy.load(path)`` reads it, no pickles):

============================  ==========  ===================================================
key                           shape       what
============================  ==========  ===================================================
``count``                     ()          the number of throws (int64), = len(tensor.json's "throws")
``t_K``                       (n,)        the fitted samples' times on the throw file's clock, s (float64)
                                          (the means of the log's samples over 1 ms, as the fit takes them)
``omega_measured_K``          (n, 3)      the gyroscope's samples (their means), sensor frame, rad/s (float32)
``omega_model_K``             (n, 3)      the fitted model's rates, bias included, rad/s (float32)
``rotor_K``                   (n,)        the rotor's logged speed at those times, rad/s (float32)
============================  ==========  ===================================================

``n`` is 0 for a throw skipped before it was fitted (no flight found). The rates and the
rotor's speed are stored in single precision (about 7 significant digits, as the throw files
write them): about 75 kB a throw of 0.65 s at 4 kHz.
"""

from __future__ import annotations

import io
import os
import zipfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..typing import ArrayLike, FloatArray
from ..validation import json_object, read_input_file

__all__ = ["TENSOR_FILE", "THROWS_FILE", "TensorFolder", "ThrowSeries", "read_tensor_folder", "throw_series",
           "write_throw_series"]

#: The files of a tensor output folder that :func:`read_tensor_folder` reads.
TENSOR_FILE = "tensor.json"
#: The throws' time series in a tensor output folder (NumPy's ``.npz``; the module's table).
THROWS_FILE = "throws.npz"
#: Largest tensor.json and throws.npz read, bytes.
MAX_TENSOR_BYTES = 64 << 20
MAX_THROWS_BYTES = 1 << 30
#: The keys of an estimate (``"object"``, ``"flown"``, each throw's) that the view reads.
ESTIMATE_KEYS = ("mass", "inertia", "principal_moments", "principal_moments_std", "principal_axes", "center_of_mass",
                 "center_of_mass_std")
_SHAPES = {"mass": (), "inertia": (3, 3), "principal_moments": (3,), "principal_moments_std": (3,),
           "principal_axes": (3, 3), "center_of_mass": (3,), "center_of_mass_std": (3,)}


class _FittedThrow(Protocol):
    """What is read of a :class:`tumble.analysis.tensor.ThrowFit`."""

    @property
    def t(self) -> FloatArray: ...
    @property
    def omega_measured(self) -> FloatArray: ...
    @property
    def omega_model(self) -> FloatArray: ...


class _LoggedThrow(Protocol):
    """What is read of a :class:`tumble.analysis.tensor.Throw`."""

    @property
    def t(self) -> FloatArray: ...
    @property
    def rotor(self) -> FloatArray: ...


@dataclass(frozen=True)
class ThrowSeries:
    """One throw's fitted samples (module docstring's table; empty arrays when none).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.io.tensorfolder import ThrowSeries
    >>> ThrowSeries(np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0)).t.size
    0
    """

    t: FloatArray = field(repr=False)
    omega_measured: FloatArray = field(repr=False)
    omega_model: FloatArray = field(repr=False)
    rotor: FloatArray = field(repr=False)


def throw_series(fitted: Sequence[_FittedThrow], logged: Sequence[_LoggedThrow]) -> dict[str, np.ndarray]:
    """The arrays of ``throws.npz`` (module docstring) from each throw's fit and its log.

    Parameters
    ----------
    fitted : sequence of ThrowFit
        ``TensorFit.throws``: each throw's fitted times, measured and model rates.
    logged : sequence of Throw
        The throws as read, in the same order: the rotor's logged speed is interpolated at the
        fitted times (the means of the log's samples over 1 ms).

    Returns
    -------
    dict of str to ndarray

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from tumble.io.tensorfolder import throw_series
    >>> t = np.arange(10) / 4000.0
    >>> logged = SimpleNamespace(t=t, rotor=100.0 * np.arange(10))
    >>> fitted = SimpleNamespace(t=t[3:6], omega_measured=np.ones((3, 3)), omega_model=np.ones((3, 3)))
    >>> arrays = throw_series([fitted], [logged])
    >>> sorted(arrays), arrays["rotor_0"].tolist(), int(arrays["count"])
    (['count', 'omega_measured_0', 'omega_model_0', 'rotor_0', 't_0'], [300.0, 400.0, 500.0], 1)
    """
    if len(fitted) != len(logged):
        raise ValueError(f"{len(fitted)} fitted throws for {len(logged)} logs: give one log per throw, in order")
    arrays: dict[str, np.ndarray] = {"count": np.array(len(fitted), dtype=np.int64)}
    for k, (fit, log) in enumerate(zip(fitted, logged)):
        t = np.asarray(fit.t, float).reshape(-1)
        rotor = np.interp(t, np.asarray(log.t, float), np.asarray(log.rotor, float)) if t.size else np.zeros(0)
        arrays[f"t_{k}"] = t
        arrays[f"omega_measured_{k}"] = np.asarray(fit.omega_measured, np.float32).reshape(-1, 3)
        arrays[f"omega_model_{k}"] = np.asarray(fit.omega_model, np.float32).reshape(-1, 3)
        arrays[f"rotor_{k}"] = rotor.astype(np.float32)
    return arrays


def write_throw_series(path: str | os.PathLike[str], arrays: Mapping[str, ArrayLike]) -> Path:
    """Write :func:`throw_series`'s arrays to ``path`` (compressed ``.npz``); returns the path.

    Written in place: the command writes it into its staging folder (:func:`tumble.io.output.output_dir`).

    Examples
    --------
    >>> import tempfile
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from tumble.io.tensorfolder import write_throw_series
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_throw_series(Path(folder) / "throws.npz", {"count": np.array(0)})
    ...     with np.load(path) as data:
    ...         print(int(data["count"]))
    0
    """
    path = Path(path)
    with open(path, "wb") as fh:
        named: dict[str, Any] = {key: np.asarray(value) for key, value in arrays.items()}
        np.savez_compressed(fh, **named)
    return path


@dataclass(frozen=True)
class TensorFolder:
    """What :func:`read_tensor_folder` read.

    Attributes
    ----------
    path : Path
        The folder.
    record : dict
        The whole of tensor.json.
    series : tuple of ThrowSeries
        One per entry of ``record["throws"]``, from throws.npz.

    Examples
    --------
    >>> from pathlib import Path
    >>> from tumble.io.tensorfolder import TensorFolder
    >>> TensorFolder(Path("bracket"), {"throws": []}, ()).path.name
    'bracket'
    """

    path: Path
    record: dict[str, Any] = field(repr=False)
    series: tuple[ThrowSeries, ...] = field(repr=False)


def _damaged(file: Path, why: str) -> ValueError:
    return ValueError(f"{file}: damaged: {why}; run tumble tensor again")


def _check_estimate(file: Path, where: str, value: object) -> None:
    if not isinstance(value, dict):
        raise _damaged(file, f"{where} = {str(value)[:40]} must be an object with {', '.join(ESTIMATE_KEYS)}")
    for key, shape in _SHAPES.items():
        try:
            a = np.asarray(value.get(key), dtype=float)
        except (TypeError, ValueError):
            a = np.zeros(0)
        if a.shape != shape or not np.all(np.isfinite(a)):
            raise _damaged(file, f"{where}.{key} = {str(value.get(key))[:40]} must be "
                                 + ("a number" if shape == () else f"finite numbers of shape {shape}"))


def _check_record(file: Path, record: dict[str, Any]) -> dict[str, Any]:
    if "object" not in record or "throws" not in record:
        raise _damaged(file, 'no "object" or no "throws"')
    _check_estimate(file, "object", record["object"])
    throws = record["throws"]
    if not isinstance(throws, list) or not throws:
        raise _damaged(file, f'"throws" = {str(throws)[:40]} must be a list of one entry per throw')
    for k, entry in enumerate(throws):
        if not isinstance(entry, dict) or entry.get("status") not in ("used", "skipped") \
                or not isinstance(entry.get("input"), str):
            raise _damaged(file, f"throws[{k}] = {str(entry)[:40]} must hold input and status (used or skipped)")
        if entry["status"] == "used":
            _check_estimate(file, f"throws[{k}].object", entry.get("object"))
    return record


def _read_series(file: Path, count: int) -> tuple[ThrowSeries, ...]:
    raw = read_input_file(file, limit=MAX_THROWS_BYTES, what="the throws' time series (throws.npz)")
    try:
        with np.load(io.BytesIO(raw), allow_pickle=False) as data:
            arrays = {key: data[key] for key in data.files}
    except (zipfile.BadZipFile, ValueError, OSError, EOFError, KeyError) as err:
        raise _damaged(file, f"not a NumPy .npz file ({' '.join(str(err).split())[:80]})") from None
    found = arrays.get("count")
    if found is None or found.shape != () or int(found) != count:
        raise _damaged(file, f"count = {None if found is None else found.tolist()} must be the {count} throws of "
                             f"{TENSOR_FILE}")
    out = []
    for k in range(count):
        keys = (f"t_{k}", f"omega_measured_{k}", f"omega_model_{k}", f"rotor_{k}")
        missing = [key for key in keys if key not in arrays]
        if missing:
            raise _damaged(file, f"no {', '.join(missing)}")
        t, measured, model, rotor = (np.asarray(arrays[key], float) for key in keys)
        n = t.shape[0] if t.ndim == 1 else -1
        if n < 0 or measured.shape != (n, 3) or model.shape != (n, 3) or rotor.shape != (n,):
            raise _damaged(file, f"throw {k}'s arrays have shapes {t.shape}, {measured.shape}, {model.shape}, "
                                 f"{rotor.shape}; expected (n,), (n, 3), (n, 3), (n,)")
        if not all(np.all(np.isfinite(a)) for a in (t, measured, model, rotor)):
            raise _damaged(file, f"throw {k}'s arrays hold a number that is not finite")
        out.append(ThrowSeries(t, measured, model, rotor))
    return tuple(out)


def read_tensor_folder(path: str | os.PathLike[str]) -> TensorFolder:
    """Read a ``tumble tensor`` output folder: tensor.json and throws.npz (module docstring).

    Raises ``ValueError`` with one line naming the path: not a folder, no tensor.json, no
    throws.npz (a folder written by an older tumble), a damaged file, or one that does not
    match the other.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.io.tensorfolder import read_tensor_folder
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "tensor.json").write_text('{"object": {}, "throws": []}')
    ...     try:
    ...         read_tensor_folder(folder)
    ...     except ValueError as error:
    ...         message = str(error)
    >>> message.split("/")[-1]
    'tensor.json: damaged: object.mass = None must be a number; run tumble tensor again'
    """
    folder = Path(path)
    if not folder.is_dir():
        raise ValueError(f"{os.fspath(path)}: not a folder; give the output folder of tumble tensor "
                         "(tumble tensor THROW... --out DIR)")
    file = folder / TENSOR_FILE
    if not file.is_file():
        raise ValueError(f"{os.fspath(path)}: a folder without {TENSOR_FILE}; give the output folder of tumble tensor "
                         "(tumble tensor THROW... --out DIR)")
    raw = read_input_file(file, limit=MAX_TENSOR_BYTES, what="a tensor result (tensor.json)")
    record = _check_record(file, json_object(raw, file, writer="tumble tensor"))
    series_file = folder / THROWS_FILE
    if not series_file.is_file():
        raise ValueError(f"{os.fspath(path)}: no {THROWS_FILE} beside {TENSOR_FILE}: the folder was written by an "
                         "older tumble; run tumble tensor again to view its throws")
    return TensorFolder(folder, record, _read_series(series_file, len(record["throws"])))
