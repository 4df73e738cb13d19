"""A ``tumble fit`` output folder read back (:func:`read_fit_folder`), and its recordings found again.

``DIR/fit.json`` holds ``"flight_models"`` (:class:`~tumble.analysis.fit.flightmodel.FlightModel`,
one per used flight, with the ``"input"`` it came from); ``tumble view DIR`` replays them next
to the measured rates, read again from the recording (:func:`find_recording`: the path as given
to ``tumble fit``, checked against the hash fit.json's provenance holds).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..analysis.fit.flightmodel import FlightModel
from ..validation import NoSuchFileError, json_object, read_input_file
from .provenance import input_sha256

__all__ = ["FIT_FILE", "FitFolder", "find_recording", "read_fit_folder"]

#: The file of a fit's output folder that :func:`read_fit_folder` reads.
FIT_FILE = "fit.json"
#: Largest fit.json read, bytes.
MAX_FIT_BYTES = 64 << 20


@dataclass(frozen=True)
class FitFolder:
    """What :func:`read_fit_folder` read.

    Attributes
    ----------
    path : Path
        The folder.
    models : tuple of FlightModel
        fit.json's ``"flight_models"``: each used flight's model.
    inputs : tuple of str
        Each model's recording, as given to ``tumble fit``.
    record : dict
        The whole of fit.json.

    Examples
    --------
    >>> from pathlib import Path
    >>> from tumble.io.fitfolder import FitFolder
    >>> fit = FitFolder(Path("fitted"), (), (), {"I1_over_I3": 0.3})
    >>> fit.path.name, fit.models, fit.record["I1_over_I3"]
    ('fitted', (), 0.3)
    """

    path: Path
    models: tuple[FlightModel, ...]
    inputs: tuple[str, ...]
    record: dict[str, Any] = field(repr=False)


def read_fit_folder(path: str | os.PathLike[str]) -> FitFolder:
    """Read a ``tumble fit`` output folder's fit.json and its flight models.

    Raises ``ValueError`` with one line naming the path: not a folder, no fit.json, a damaged
    fit.json, or one written before fit.json held ``"flight_models"`` (run ``tumble fit`` again).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.io.fitfolder import read_fit_folder
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "fit.json").write_text('{"I1_over_I3": 0.3, "tosses": []}')
    ...     try:
    ...         read_fit_folder(folder)
    ...     except ValueError as error:
    ...         message = str(error)
    >>> message.endswith('fit.json has no "flight_models": it was written by an older tumble; run tumble fit again to replay its flights')
    True
    """
    folder = Path(path)
    if not folder.is_dir():
        why = "not a folder" if folder.exists() else "no such folder"
        raise (ValueError if folder.exists() else NoSuchFileError)(
            f"{os.fspath(path)}: {why}; give the output folder of tumble fit (tumble fit REC --out DIR)")
    file = folder / FIT_FILE
    if not file.is_file():
        raise ValueError(f"{os.fspath(path)}: a folder without {FIT_FILE}; give the output folder of tumble fit "
                         "(tumble fit REC --out DIR)")
    raw = read_input_file(file, limit=MAX_FIT_BYTES, what="a fit result (fit.json)")
    record = json_object(raw, file, writer="tumble fit")
    if "flight_models" not in record:
        raise ValueError(f'{file} has no "flight_models": it was written by an older tumble; run tumble fit again to '
                         "replay its flights")
    entries = record["flight_models"]
    if not isinstance(entries, list) or not entries:
        raise ValueError(f'{file}: damaged: "flight_models" = {str(entries)[:40]} must be a list of one entry per used flight')
    models, inputs = [], []
    for i, entry in enumerate(entries):
        where = f"{file}: flight_models[{i}]"
        models.append(FlightModel.from_summary(entry, where))
        label = entry.get("input")
        if not isinstance(label, str) or not label:
            raise ValueError(f"{where}.input = {label!r} must be the recording's path as given to tumble fit")
        inputs.append(label)
    return FitFolder(folder, tuple(models), tuple(inputs), record)


def find_recording(fit: FitFolder, label: str) -> tuple[Path | None, str]:
    """The recording ``label`` (a path as given to ``tumble fit``) and ``""``, or None and why not.

    Looked for as given (relative to the current folder) and relative to the folder above the
    fit's output folder; one whose content differs from the hash in fit.json's provenance is
    not taken (the measured rates would not be those fitted).

    Examples
    --------
    >>> import json, tempfile
    >>> from pathlib import Path
    >>> from tumble.io.fitfolder import FitFolder, find_recording
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     fit = FitFolder(Path(folder) / "fit", (), (), {"provenance": {"inputs": {}}})
    ...     print(find_recording(fit, "no-such-recording.csv")[1])
    not found (looked for no-such-recording.csv here and beside the fit's folder)
    """
    expected = (fit.record.get("provenance") or {}).get("inputs") or {}
    digest = expected.get(str(Path(label))) if isinstance(expected, dict) else None
    changed = False
    for candidate in dict.fromkeys([Path(label), fit.path.parent / label]):
        if not candidate.exists():
            continue
        try:
            same = digest is None or input_sha256(candidate) == digest
        except OSError:
            continue
        if same:
            return candidate, ""
        changed = True
    if changed:
        return None, f"{label} has changed since the fit (its content differs from the hash in fit.json's provenance)"
    return None, f"not found (looked for {label} here and beside the fit's folder)"
