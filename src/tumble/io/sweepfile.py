"""Sweep files (TOML): ``tumble sweep SWEEP.toml --out DIR`` reads them.

::

    # The first comment line describes the sweep.
    body = "t-handle"            # a preset name, a body file (relative to this file), or a [body] table
                                 # (parts, or preset = "..." with its parameters)

    [sweep]
    cases = 4096                 # how many cases: a whole number from 1 to 1e8
    seed = 1                     # 0 to 2^64 - 1; case i draws from SeedSequence(seed).spawn(...)[i]
    sampling = "lhs"             # "random" (default), "lhs" (Latin hypercube), "sobol"
    chunk = 1024                 # cases per chunk: memory and resume granularity, not the results
    max_resamples = 100          # redraws of an unphysical body per case before the sweep is refused

    [[dispersion]]               # any number of them
    target = "preset"            # "preset" (a preset parameter), "part", "moments" or "axes"
    field = "shaft_length"       # the preset parameter or the part's field (not for moments or axes)
    # part = 0                   # target "part": index into the body's parts, from 0
    relative = 0.05              # a fraction; or absolute = 0.002 (the field's unit; rad for axes)
    distribution = "uniform"     # "normal" (default: the spread is one standard deviation) or
                                 # "uniform" (the spread is the half-width)

    [initial]
    omega = [10.0, 0.1, 0.1]     # rad/s, nominal
    frame = "design"             # "principal" (each case's own principal axes) or "design"
    distribution = "normal"      # optional: disperse each component ...
    spread = [0.0, 0.05, 0.05]   # ... by this much, rad/s (a spread needs the distribution)
    # grid = [[10.0], [0.05, 0.1], [0.1]]   # instead of omega: the Cartesian product, case i at point i mod G

    [simulation]
    t_end = 20.0                 # s (default 20), or times = [...]
    samples = 400                # default 500: a few per flip, to count the flips
    method = "exact"             # default exact; dop853 with a torque; a geometric method needs step (s, > 0)

    [torque]                     # optional, as in scenario files
    vector = [0.0, 0.0, 0.01]    # N m
    frame = "body"

    [criterion]                  # optional: what counts as success, for the order-statistics statement
    column = "flips"             # a column of cases.csv, without its unit
    min = 1                      # and/or max (min <= max); inclusive; a NaN value fails
    confidence = 0.9             # default 0.9

Running a sweep file and writing its results is :func:`tumble.commands.sweep.run_sweep`
(``tumble sweep``); this module reads and checks the file, and writes the case tables as the
chunks pass (:class:`CaseTables`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..dynamics.batch import MAX_BATCH_VALUES
from ..dynamics.simulate import sample_times
from ..ensemble import (
    DEFAULT_CHUNK,
    BodySampler,
    Criterion,
    Dispersion,
    Ensemble,
    InitialRates,
    RunSettings,
    Sweep,
)
from ..ensemble.sampling import MAX_CASES, SAMPLINGS
from ..mass import PRESETS, Body
from ..validation import unknown_name
from .bodyfile import body_from_table, body_path, mesh_files, preset_body, read_toml
from .provenance import file_sha256
from .resume import ChunkFolder
from .keys import FileFormat, Key, Table
from .scenario import _ATOL, _BODY, _METHOD, _OMEGA, _RTOL, _SAMPLES, _STEP, _T_END, _TIMES, DEFAULT_T_END
from .torquetables import TORQUE_TABLE, torque_of

#: Where a residual dipole is taken: a file with a magnetic field.
_DIPOLE_ELSEWHERE = "control files take a residual_dipole, in their [orbit]'s magnetic field"

__all__ = ["SWEEP_FORMAT", "SWEEP_WRITES", "CaseTables", "ChunkFolder", "SweepFile", "load_sweep", "sweep_from_table"]

#: The files a sweep writes into its folder (an earlier run's are replaced as a set).
SWEEP_WRITES = ("cases.csv", "cases.parquet", "summary.json", "sweep.png")

_DISTRIBUTION = ("normal", "uniform")
#: The tables of a sweep file and their keys.
SWEEP_FORMAT = FileFormat("sweep", (
    Table("top level", (
        _BODY,
        Key("sweep", "table", required=True, example="{cases = 4096}", doc="[sweep]"),
        Key("dispersion", "list of tables", example='[{target = "moments", relative = 0.02}]',
            doc="[[dispersion]], any number"),
        Key("initial", "table", required=True, example="{omega = [10.0, 0.1, 0.1]}", doc="[initial]"),
        Key("simulation", "table", example="{t_end = 20.0}", doc="[simulation]"),
        Key("torque", "table", example="{vector = [0.0, 0.0, 0.01]}",
            doc="[torque], or a [[torque]] table for each of several torques"),
        Key("criterion", "table", example='{column = "flips", min = 1}', doc="[criterion]"),
    ), "The first comment line of the file describes the sweep."),
    Table("[sweep]", (
        Key("cases", "whole number", required=True, example="4096", doc="how many cases",
            low=1, low_included=True, high=MAX_CASES),
        Key("seed", "whole number", "", "0", example="1", low=0, low_included=True, high=2**64 - 1,
            doc="case i draws from SeedSequence(seed).spawn(...)[i]"),
        Key("sampling", "string", "", '"random"', choices=tuple(SAMPLINGS), example='"sobol"',
            doc="random, Latin hypercube or Sobol' points"),
        Key("chunk", "whole number", "", f"{DEFAULT_CHUNK}", example="1024", low=1, low_included=True,
            doc="cases per chunk: memory and resume granularity, not the results"),
        Key("max_resamples", "whole number", "", "100", example="100", low=0, low_included=True,
            doc="redraws of an unphysical body per case before the sweep is refused"),
    ), "How many cases and how they are drawn."),
    Table("[[dispersion]]", (
        Key("target", "string", required=True, choices=("preset", "part", "moments", "axes"), example='"preset"',
            doc="a preset parameter, a part's field, the principal moments or the principal axes"),
        Key("field", "string", example='"shaft_length"', doc="the preset parameter or the part's field"),
        Key("part", "whole number", example="0", low=0, low_included=True,
            doc='target = "part": index into the body\'s parts, from 0'),
        Key("relative", "number", "", example="0.05", low=0.0, low_included=True, high=1.0, high_included=False,
            doc="the spread as a fraction, 0.05 for 5 % (or absolute, one of them)"),
        Key("absolute", "number", "(the field's; rad for axes)", example="0.002", low=0.0, low_included=True,
            doc="the spread in the field's unit"),
        Key("distribution", "string", "", '"normal"', choices=_DISTRIBUTION, example='"uniform"',
            doc="normal: the spread is one standard deviation; uniform: the half-width"),
    ), "One dispersed quantity each; any number of them."),
    Table("[initial]", (
        _OMEGA,
        Key("frame", "string", "", '"principal"', choices=("principal", "design"), example='"design"',
            doc="each case's own principal axes, or the body file's design frame"),
        Key("distribution", "string", "", "(none: not dispersed)", choices=_DISTRIBUTION, example='"normal"',
            doc="disperse each component of omega"),
        Key("spread", "3 numbers", "rad/s", "[0.0, 0.0, 0.0]", allowed=">= 0 each; needs the distribution",
            example="[0.0, 0.05, 0.05]", doc="the dispersion of each component"),
        Key("grid", "3 lists of numbers", "rad/s", example="[[10.0], [0.05, 0.1], [0.1]]",
            doc="instead of omega: the Cartesian product, case i at point i mod G"),
    ), "The nominal initial angular velocity, or a grid of them; ``omega`` or ``grid`` is required."),
    Table("[simulation]", (_T_END, _SAMPLES, replace(_TIMES, doc="the sample times, instead of t_end and samples"), _METHOD,
                           _RTOL, _ATOL, _STEP),
          "When to sample and how to integrate each case (no dt: every case shares its times)."),
    TORQUE_TABLE,
    Table("[criterion]", (
        Key("column", "string", required=True, example='"flips"', doc="a column of cases.csv, without its unit"),
        Key("min", "number", "(the column's)", example="1", doc="the least value that succeeds (inclusive)"),
        Key("max", "number", "(the column's)", example="10", doc="the largest value that succeeds (inclusive)"),
        Key("confidence", "number", "", "0.9", example="0.95", low=0.0, high=1.0, high_included=False,
            doc="of the order-statistics statement"),
    ), "Optional: what counts as success; a NaN value fails."),
), "A Monte Carlo sweep or a grid: ``tumble sweep SWEEP.toml --out DIR`` "
   "(:func:`tumble.commands.sweep.run_sweep`) runs it.")
_SECTIONS = {t.title.strip("[]"): t for t in SWEEP_FORMAT.tables[1:] if t.title != "[[dispersion]]"}
_DISPERSION = SWEEP_FORMAT.table("[[dispersion]]")


@dataclass(frozen=True, eq=False)
class SweepFile:
    """A parsed sweep file: the sweep and what the output records about it.

    Examples
    --------
    >>> from tumble.io.sweepfile import sweep_from_table
    >>> spread = {"omega": [0.1, 5.0, 0.1], "distribution": "normal", "spread": [0.01, 0.0, 0.01]}   # rad/s
    >>> parsed = sweep_from_table({"body": "t-handle", "sweep": {"cases": 4}, "initial": spread,
    ...                            "simulation": {"t_end": 5.0}}, name="spin")
    >>> parsed.name, parsed.chunk, parsed.sweep.ensemble.cases
    ('spin', 1024, 4)
    """

    sweep: Sweep
    name: str
    chunk: int
    #: ``(path, sha256)`` of the files read (provenance, and the resume fingerprint).
    sources: tuple = ()
    #: The file's tables as read (recorded in summary.json).
    settings: dict | None = None

    def fingerprint(self) -> dict:
        """Everything that changes a result: the versions, the content hashes of every file read
        (sweep file, body file, mesh files), the run's settings as resolved and the chunk size.

        A resumed sweep reuses only the chunks of a run with the same fingerprint
        (:class:`tumble.io.resume.ChunkFolder`).

        Examples
        --------
        >>> from tumble.io.sweepfile import sweep_from_table
        >>> spin = {"body": "t-handle", "initial": {"omega": [0.1, 5.0, 0.1], "distribution": "normal",
        ...                                         "spread": [0.01, 0.0, 0.01]}}   # rad/s
        >>> parsed = sweep_from_table({**spin, "sweep": {"cases": 4}})
        >>> other = sweep_from_table({**spin, "sweep": {"cases": 4, "chunk": 2}})
        >>> parsed.fingerprint()["cases"], parsed.fingerprint() == other.fingerprint()
        (4, False)
        """
        import scipy

        from .._version import __version__

        ensemble, settings = self.sweep.ensemble, self.sweep.settings
        return {"tumble": __version__, "numpy": np.__version__, "scipy": scipy.__version__, "chunk": self.chunk,
                "inputs": [h for _, h in self.sources], "file": self.settings,
                "cases": ensemble.cases, "seed": ensemble.seed, "sampling": ensemble.sampling,
                "method": settings.method, "step": settings.step, "t_end": settings.t_end, "samples": settings.samples,
                "times": settings.times, "rtol": settings.rtol, "atol": settings.atol}


def _table(data: dict, section: str) -> dict:
    return _SECTIONS[section].check(section, data.get(section, {}))


def _nominal(spec, base_dir: Path | None) -> tuple[Body, str | None, dict, list[Path]]:
    """``(body, preset, parameters, files read)`` of the ``body`` key."""
    if isinstance(spec, str) and spec in PRESETS:
        return preset_body(spec), spec, {}, []
    if isinstance(spec, str):
        path = body_path(spec, base_dir)
        data = read_toml(path)
        if set(data) != {"body"}:
            raise ValueError(f"body = {spec!r}: a body file has one table, [body]")
        try:
            body, preset, parameters, inner = _nominal(data["body"], path.parent)
        except ValueError as exc:
            raise ValueError(f"{path}: {exc}") from None
        return body, preset, parameters, [path, *inner]
    if not isinstance(spec, dict):
        raise ValueError(f"body = {spec!r} must be a preset name, a body file path or a [body] table")
    body = body_from_table(spec, base_dir=base_dir)
    if "preset" in spec:
        return body, spec["preset"], {k: v for k, v in spec.items() if k != "preset"}, []
    return body, None, {}, mesh_files(spec, base_dir)


def _dispersion(table, k: int) -> Dispersion:
    where = f"dispersion[{k}]"
    if not isinstance(table, dict):
        raise ValueError(f"{where} must be a table [[dispersion]]")
    _DISPERSION.check(where, table)
    if ("relative" in table) == ("absolute" in table):
        raise ValueError(f"{where}: give relative = (a fraction) or absolute = (in the field's unit), one of them")
    relative = "relative" in table
    if "target" not in table:
        raise ValueError(f"{where}: missing key 'target' (preset, part, moments or axes)")
    try:
        return Dispersion(table["target"], table["relative" if relative else "absolute"], field=table.get("field"),
                          part=table.get("part"), relative=relative, distribution=table.get("distribution", "normal"))
    except ValueError as exc:  # the constructor's spread is the file's relative or absolute
        text = str(exc)
        if text.startswith("spread = "):
            text = ("relative" if relative else "absolute") + text.removeprefix("spread")
        raise ValueError(f"{where}: {text}") from None


def _criterion(table: dict) -> Criterion | None:
    if not table:
        return None
    if "column" not in table:
        raise ValueError("criterion: missing key 'column' (a column of cases.csv, without its unit)")
    try:
        return Criterion(table["column"], table.get("min"), table.get("max"), table.get("confidence", 0.9))
    except ValueError as exc:
        raise ValueError(f"criterion: {exc}") from None


def _in(section: str, build):
    """``build()``, its ValueError prefixed with the section's name."""
    try:
        return build()
    except ValueError as exc:
        raise ValueError(f"{section}: {exc}") from None


def sweep_from_table(data: dict, *, base_dir: Path | None = None, name: str = "sweep") -> SweepFile:
    """Build (and check) a sweep from parsed TOML; errors are one line naming the key.

    The run (:func:`tumble.commands.sweep.run_sweep`) computes case 0 first, so that a sweep that
    cannot run, or whose criterion names no column, fails before any output.

    Examples
    --------
    >>> from tumble.io.sweepfile import sweep_from_table
    >>> parsed = sweep_from_table({"body": "t-handle", "sweep": {"cases": 16, "seed": 1},
    ...                            "dispersion": [{"target": "moments", "relative": 0.02}],
    ...                            "initial": {"omega": [0.1, 5.0, 0.1]}, "simulation": {"t_end": 5.0}})
    >>> parsed.sweep.ensemble.names
    ('moment_factor_1', 'moment_factor_2', 'moment_factor_3')
    >>> sweep_from_table({"body": "t-handle", "sweep": {"cases": 0}, "initial": {"omega": [0, 5, 0]}})
    Traceback (most recent call last):
    ...
    ValueError: sweep: cases = 0 must be a whole number from 1 to 100000000
    """
    unknown = sorted(set(data) - set(SWEEP_FORMAT.tables[0].names()))
    if unknown:
        raise ValueError(unknown_name("", unknown[0], ["body", "dispersion", *_SECTIONS]))
    if "body" not in data:
        raise ValueError("missing key 'body' (a preset name, a body file or a [body] table)")
    tables = {section: _table(data, section) for section in _SECTIONS if section != "torque"}  # torque_of checks it
    sweep, initial, sim = tables["sweep"], tables["initial"], tables["simulation"]
    if "sweep" not in data:  # a scenario given to 'tumble sweep'
        raise ValueError("no [sweep] table: a scenario is run with 'tumble simulate FILE --out DIR'; a sweep file adds "
                         "[sweep] (cases = ...) and [[dispersion]] tables (see 'tumble examples')")
    if "cases" not in sweep:
        raise ValueError("sweep: missing key 'cases' (how many cases)")
    body, preset, parameters, files = _nominal(data["body"], base_dir)
    items = data.get("dispersion", [])
    if not isinstance(items, list):
        raise ValueError("dispersion must be a list of [[dispersion]] tables")
    dispersions = tuple(_dispersion(t, k) for k, t in enumerate(items))
    try:
        bodies = BodySampler(body, dispersions, preset, parameters)
    except ValueError as exc:  # named as the file names them: its [[dispersion]] tables, not the Python argument
        raise ValueError(str(exc).replace("dispersions[", "dispersion[", 1)) from None
    rates = _in("initial", lambda: InitialRates(**initial))
    ensemble = _in("sweep", lambda: Ensemble(bodies, rates, **{k: v for k, v in sweep.items() if k != "chunk"}))
    if ensemble.design.dims == 0 and ensemble.cases > rates.points:  # nothing drawn: case i is point i mod G
        raise ValueError(f"sweep: cases = {ensemble.cases} repeats the {rates.points} initial rate(s) with nothing "
                         "dispersed: copies of one deterministic run are not trials, and the fraction flipped and its "
                         f"confidence would count them (1000 copies of 2 grid points: 99.63 to 100 %); give cases = "
                         f"{rates.points}, or a [[dispersion]] or an [initial] spread")
    torque = _in("simulation", lambda: torque_of(data.get("torque"), elsewhere=_DIPOLE_ELSEWHERE))
    terms = getattr(torque, "terms", (torque,)) if torque is not None else ()
    if rates.frame == "design" and any(getattr(term, "frame", None) == "body" for term in terms):
        # a scenario reads a body-frame vector in initial.frame; a sweep's batch takes one vector for every case, in
        # each case's principal frame, which its dispersions turn and reorder (a walkthrough, 2026-12-03: a
        # thruster's torque along design x in one case, along the shaft in another)
        raise ValueError('torque: a body-frame vector in a sweep acts along each case\'s principal axes (1 minor, 3 major), '
                         'not initial.frame = "design"\'s: give initial.frame = "principal" (omega too in principal '
                         'axes), or the torque in frame = "world"')
    times = sim.get("times")
    t_end = sim.get("t_end", None if times is not None else DEFAULT_T_END)
    n = len(_in("simulation", lambda: sample_times(t_end, sim.get("samples"), None, times))[0])
    settings = _in("simulation", lambda: RunSettings(t_end=t_end, samples=sim.get("samples"), times=times,
                                                      method=sim.get("method"), torque=torque,
                                                      step=sim.get("step"), rtol=sim.get("rtol"), atol=sim.get("atol")))
    chunk = sweep.get("chunk", DEFAULT_CHUNK)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise ValueError(f"sweep: chunk = {chunk!r} must be a whole number >= 1 (cases per chunk)")
    batch = min(chunk, ensemble.cases)  # a chunk's cases run as one batch: its samples are held at once
    if batch * n > MAX_BATCH_VALUES:
        raise ValueError(f"simulation: {n} samples a case with sweep.chunk = {chunk} is {batch * n:,} samples a chunk, more "
                         f"than {MAX_BATCH_VALUES:,}; give chunk = {max(1, MAX_BATCH_VALUES // n)} or less (it changes "
                         f"no result) or fewer samples")
    result = Sweep(ensemble, settings, _criterion(tables["criterion"]))
    return SweepFile(result, name, chunk, tuple((str(f), file_sha256(f)) for f in files), dict(data))


def load_sweep(path: str | os.PathLike[str]) -> SweepFile:
    """Read and check a sweep file; errors are one line starting with the file's name.

    Examples
    --------
    >>> from importlib import resources
    >>> from tumble.io.sweepfile import load_sweep
    >>> parsed = load_sweep(resources.files("tumble") / "examples/sweeps/t_handle_dimensions.toml")
    >>> parsed.name, parsed.sweep.ensemble.cases, parsed.sweep.ensemble.sampling, parsed.chunk
    ('t_handle_dimensions', 4096, 'sobol', 1024)
    """
    path = Path(path)
    data = read_toml(path, what="a sweep file (TOML)")  # named as such: it said "a body or scenario file"
    try:
        parsed = sweep_from_table(data, base_dir=path.parent, name=path.stem)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    return SweepFile(parsed.sweep, parsed.name, parsed.chunk, ((str(path), file_sha256(path)), *parsed.sources),
                     parsed.settings)


def _text(values: np.ndarray) -> list[str]:
    """A column as CSV fields: whole numbers as such, floats as their shortest repr."""
    kind = values.dtype.kind
    if kind == "f":
        return [repr(v) for v in values.tolist()]
    return [str(v) for v in values.tolist()]


class CaseTables:
    """Writes the chunks of a sweep to ``cases.csv`` (and ``cases.parquet`` with pyarrow) in
    ``folder`` as they pass: call it with each chunk's columns, then :meth:`CaseTables.close`.

    Examples
    --------
    >>> import tempfile
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from tumble.io.sweepfile import CaseTables
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     tables = CaseTables(Path(folder))
    ...     tables({"case": np.arange(2), "flips": np.array([1.0, 0.5])})
    ...     tables({"case": np.arange(2, 3), "flips": np.array([np.nan])})
    ...     tables.close()
    ...     print(Path(folder, "cases.csv").read_text(), end="")
    case,flips
    0,1.0
    1,0.5
    2,nan
    """

    def __init__(self, folder: Path) -> None:
        self.csv = open(folder / "cases.csv", "w", encoding="utf-8", newline="")
        self.parquet_path = folder / "cases.parquet"
        self.parquet = None
        self.header = None

    def __call__(self, columns: dict) -> None:
        """Append one chunk's columns (a dict of equal-length arrays; the first chunk's keys are the header).

        Examples
        --------
        >>> import tempfile
        >>> import numpy as np
        >>> from pathlib import Path
        >>> from tumble.io.sweepfile import CaseTables
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     tables = CaseTables(Path(folder))
        ...     tables({"case": np.arange(3), "flips": np.array([2.0, 0.0, 1.5])})
        ...     tables.close()
        ...     Path(folder, "cases.csv").read_text().splitlines()[1:]
        ['0,2.0', '1,0.0', '2,1.5']
        """
        if self.header is None:
            self.header = list(columns)
            self.csv.write(",".join(self.header) + "\n")
        fields = [_text(np.asarray(v)) for v in columns.values()]
        self.csv.write("".join(",".join(row) + "\n" for row in zip(*fields)))
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            return
        table = pa.table({k: np.asarray(v) for k, v in columns.items()})
        if self.parquet is None:
            self.parquet = pq.ParquetWriter(self.parquet_path, table.schema)
        self.parquet.write_table(table)

    def close(self) -> None:
        """Close the files (the last chunk is written).

        Examples
        --------
        >>> import tempfile
        >>> from pathlib import Path
        >>> from tumble.io.sweepfile import CaseTables
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     tables = CaseTables(Path(folder))
        ...     tables.close()
        ...     tables.csv.closed, Path(folder, "cases.csv").read_text()
        (True, '')
        """
        self.csv.close()
        if self.parquet is not None:
            self.parquet.close()
