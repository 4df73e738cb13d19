"""Sweep files (TOML) and the run that writes their results: ``tumble sweep SWEEP.toml --out DIR``.

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

:func:`run_sweep` writes into ``DIR``, all at once or not at all (:func:`tumble.io.output.output_dir`):

- ``cases.csv``: one row per case (:func:`tumble.ensemble.reduce_cases`): ``case``, ``I1 [kg m^2]``
  to ``I3``, ``omega0_1 [rad/s]`` to ``omega0_3`` (principal frame), the drawn values (one column
  per dispersed quantity, e.g. ``shaft_length [m]``), ``resampled``, then ``axis``, ``predicted``,
  ``growth_rate [1/s]``, ``wobble_frequency [rad/s]``, ``circulation``, ``flips``,
  ``flip_period [s]``, ``flip_period_exact [s]``, ``omega_end_1 [rad/s]`` to ``_3``, ``q_end_x``
  to ``q_end_w``, ``max_nutation [rad]``, ``energy_change``, ``L_world_angle [rad]``. Floats are
  written as Python's shortest round-trip repr (``nan`` where a quantity does not apply);
- ``cases.parquet``: the same table, when pyarrow is installed (``pip install 'tumble[table]'``);
- ``summary.json``: the sweep's settings, the streaming statistics
  (:meth:`tumble.ensemble.SweepSummary.as_dict`), the criterion's success statement and the
  provenance (:func:`tumble.io.provenance.provenance`);
- a figure, ``sweep.png``, when the caller passes the function that draws it (the command line
  passes :func:`tumble.viz.figure_sweep`; this layer draws nothing, it saves the figure).

Resume: each finished chunk is kept in ``DIR.resume/`` beside the output
(:class:`tumble.io.resume.ChunkFolder`). Run again after an interruption, the sweep computes
only the missing chunks, and since every case's row is the same in any chunk, ``cases.csv``
comes out byte for byte as an uninterrupted run's. A fingerprint of everything that changes a
result (the content hashes of the sweep file, the body file and its mesh files, the run's
settings, the chunk size, the versions of tumble, numpy and scipy) says which run the chunks
belong to: another run's are discarded. Each chunk records its cases and a checksum, and a bad
one (copied, cut, truncated) is named in a warning line and computed again; a run holds a lock
on the folder, so a second run into the same ``--out`` is refused while the first runs; a
``DIR.resume`` that is a symbolic link is refused. The folder is removed once the output is in
place.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

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
    compute_chunk,
    make_backend,
    run_chunks,
    summarize,
)
from ..mass import PRESETS, Body
from .bodyfile import body_from_table, mesh_files, read_toml
from .export import write_json
from .output import FIGURE_DPI, check_output_dir, output_dir
from .provenance import file_sha256, provenance
from .resume import ChunkFolder
from .scenario import DEFAULT_T_END, _torque

__all__ = ["SWEEP_WRITES", "ChunkFolder", "SweepFile", "load_sweep", "run_sweep", "run_sweep_command", "sweep_from_table"]

#: The files a sweep writes into its folder (an earlier run's are replaced as a set).
SWEEP_WRITES = ("cases.csv", "cases.parquet", "summary.json", "sweep.png")

_SECTIONS = {
    "sweep": {"cases", "seed", "sampling", "chunk", "max_resamples"},
    "initial": {"omega", "frame", "distribution", "spread", "grid"},
    "simulation": {"t_end", "samples", "times", "method", "step"},
    "torque": {"kind", "vector", "frame", "orbit_period", "orbit_radius", "mu"},
    "criterion": {"column", "min", "max", "confidence"},
}
_DISPERSION_KEYS = {"target", "field", "part", "relative", "absolute", "distribution"}


@dataclass(frozen=True, eq=False)
class SweepFile:
    """A parsed sweep file: the sweep and what the output records about it.

    Examples
    --------
    >>> parsed = sweep_from_table({"body": "t-handle", "sweep": {"cases": 4}, "initial": {"omega": [0.1, 5.0, 0.1]},
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


def _table(data: dict, section: str) -> dict:
    table = data.get(section, {})
    if not isinstance(table, dict):
        raise ValueError(f"{section} must be a table [{section}]")
    bad = sorted(set(table) - _SECTIONS[section])
    if bad:
        raise ValueError(f"{section}: unknown key {bad[0]!r}; allowed: {', '.join(sorted(_SECTIONS[section]))}")
    return table


def _nominal(spec, base_dir: Path | None) -> tuple[Body, str | None, dict, list[Path]]:
    """``(body, preset, parameters, files read)`` of the ``body`` key."""
    if isinstance(spec, str) and spec in PRESETS:
        return PRESETS[spec](), spec, {}, []
    if isinstance(spec, str):
        path = Path(spec) if base_dir is None else base_dir / spec
        if not path.exists():
            raise ValueError(f"body = {spec!r} is neither a preset ({', '.join(PRESETS)}) nor a file")
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
    bad = sorted(set(table) - _DISPERSION_KEYS)
    if bad:
        raise ValueError(f"{where}: unknown key {bad[0]!r}; allowed: {', '.join(sorted(_DISPERSION_KEYS))}")
    if ("relative" in table) == ("absolute" in table):
        raise ValueError(f"{where}: give relative = (a fraction) or absolute = (in the field's unit), one of them")
    relative = "relative" in table
    if "target" not in table:
        raise ValueError(f"{where}: missing key 'target' (preset, part, moments or axes)")
    try:
        return Dispersion(table["target"], table["relative" if relative else "absolute"], field=table.get("field"),
                          part=table.get("part"), relative=relative, distribution=table.get("distribution", "normal"))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None


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

    Case 0 is made and run as a check, so that a sweep that cannot run fails here, before any
    output.

    Examples
    --------
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
    unknown = sorted(set(data) - {"body", "dispersion", *_SECTIONS})
    if unknown:
        raise ValueError(f"unknown key {unknown[0]!r}; allowed: body, dispersion, {', '.join(_SECTIONS)}")
    if "body" not in data:
        raise ValueError("missing key 'body' (a preset name, a body file or a [body] table)")
    tables = {section: _table(data, section) for section in _SECTIONS}
    sweep, initial, sim = tables["sweep"], tables["initial"], tables["simulation"]
    if "cases" not in sweep:
        raise ValueError("sweep: missing key 'cases' (how many cases)")
    body, preset, parameters, files = _nominal(data["body"], base_dir)
    items = data.get("dispersion", [])
    if not isinstance(items, list):
        raise ValueError("dispersion must be a list of [[dispersion]] tables")
    dispersions = tuple(_dispersion(t, k) for k, t in enumerate(items))
    bodies = BodySampler(body, dispersions, preset, parameters)
    rates = _in("initial", lambda: InitialRates(**initial))
    ensemble = _in("sweep", lambda: Ensemble(bodies, rates, **{k: v for k, v in sweep.items() if k != "chunk"}))
    times = sim.get("times")
    t_end = sim.get("t_end", None if times is not None else DEFAULT_T_END)
    _in("simulation", lambda: sample_times(t_end, sim.get("samples"), None, times))
    settings = _in("simulation", lambda: RunSettings(t_end=t_end, samples=sim.get("samples"), times=times,
                                                      method=sim.get("method"), torque=_torque(tables["torque"]),
                                                      step=sim.get("step")))
    chunk = sweep.get("chunk", DEFAULT_CHUNK)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise ValueError(f"sweep: chunk = {chunk!r} must be a whole number >= 1 (cases per chunk)")
    result = Sweep(ensemble, settings, _criterion(tables["criterion"]))
    first = compute_chunk(result, 0, 1)  # case 0 runs: the sweep can run
    if result.criterion is not None:
        _in("criterion", lambda: result.criterion.passed(first))
    return SweepFile(result, name, chunk, tuple((str(f), file_sha256(f)) for f in files), dict(data))


def load_sweep(path: str | os.PathLike[str]) -> SweepFile:
    """Read and check a sweep file; errors are one line starting with the file's name.

    Examples
    --------
    >>> from importlib import resources
    >>> parsed = load_sweep(resources.files("tumble") / "examples/sweeps/t_handle_dimensions.toml")
    >>> parsed.name, parsed.sweep.ensemble.cases, parsed.sweep.ensemble.sampling, parsed.chunk
    ('t_handle_dimensions', 4096, 'sobol', 1024)
    """
    path = Path(path)
    data = read_toml(path)
    try:
        parsed = sweep_from_table(data, base_dir=path.parent, name=path.stem)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    return SweepFile(parsed.sweep, parsed.name, parsed.chunk, ((str(path), file_sha256(path)), *parsed.sources),
                     parsed.settings)


def _fingerprint(parsed: SweepFile) -> dict:
    """Everything that changes a result: the versions, the content hashes of every file read
    (sweep file, body file, mesh files), the run's settings as resolved and the chunk size."""
    import scipy

    from .._version import __version__

    ensemble, settings = parsed.sweep.ensemble, parsed.sweep.settings
    return {"tumble": __version__, "numpy": np.__version__, "scipy": scipy.__version__, "chunk": parsed.chunk,
            "inputs": [h for _, h in parsed.sources], "file": parsed.settings,
            "cases": ensemble.cases, "seed": ensemble.seed, "sampling": ensemble.sampling,
            "method": settings.method, "step": settings.step, "t_end": settings.t_end, "samples": settings.samples,
            "times": settings.times}


def _text(values: np.ndarray) -> list[str]:
    """A column as CSV fields: whole numbers as such, floats as their shortest repr."""
    kind = values.dtype.kind
    if kind == "f":
        return [repr(v) for v in values.tolist()]
    return [str(v) for v in values.tolist()]


class _Tables:
    """Writes the chunks to ``cases.csv`` (and ``cases.parquet`` with pyarrow) as they pass."""

    def __init__(self, folder: Path) -> None:
        self.csv = open(folder / "cases.csv", "w", encoding="utf-8", newline="")
        self.parquet_path = folder / "cases.parquet"
        self.parquet = None
        self.header = None

    def __call__(self, columns: dict) -> None:
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
        self.csv.close()
        if self.parquet is not None:
            self.parquet.close()


def run_sweep(path: str | os.PathLike[str], out: str | os.PathLike[str], *, workers: int | None = None, scheduler: str | None = None,
              argv: Sequence[str] | None = None, figure: Callable[..., Any] | None = None,
              warn: Callable[[str], None] | None = None) -> dict:
    """Run a sweep file and write its results into the folder ``out`` (module docstring).

    Parameters
    ----------
    path : str or Path
        The sweep file.
    out : str or Path
        The output folder (new, or a folder of plain files; checked before anything runs).
    workers : int, optional
        Run the chunks on a local Dask cluster of this many processes.
    scheduler : str, optional
        Run them on the Dask scheduler at this address.
    argv : list of str, optional
        The command line, for the provenance.
    figure : callable, optional
        ``figure(columns, title=..., cases=...)`` returns the figure of the sample of cases
        (a matplotlib Figure: :func:`tumble.viz.figure_sweep`), saved as ``sweep.png``.
    warn : callable, optional
        ``warn(message)`` for a resumed chunk that is not reused (:mod:`tumble.io.resume`);
        default a :class:`tumble.io.resume.ResumeWarning`.

    Returns
    -------
    dict
        What ``summary.json`` holds.

    Raises
    ------
    ValueError
        For a bad file, value or output path, or when another sweep is running into ``out``
        (its resume folder is locked): nothing is computed or written.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = Path(folder, "spin.toml").write_text('body = "t-handle"\\n[sweep]\\ncases = 8\\n[initial]\\n'
    ...                                              'omega = [0.1, 5.0, 0.1]\\n[criterion]\\ncolumn = "flips"\\nmin = 1\\n')
    ...     data = run_sweep(Path(folder, "spin.toml"), Path(folder, "out"))
    ...     written = sorted(p.name for p in Path(folder, "out").iterdir())
    >>> data["cases"], data["counts"]["predicted"], data["criterion"]["passed"]  # spun about the intermediate axis
    (8, {'unstable': 8}, 8)
    >>> written
    ['cases.csv', 'cases.parquet', 'summary.json']
    """
    parsed = load_sweep(path)
    out = check_output_dir(out).absolute()
    sweep = parsed.sweep
    store = ChunkFolder(out.parent / f"{out.name}.resume", _fingerprint(parsed), cases=sweep.ensemble.cases,
                        chunk=parsed.chunk, warn=warn)
    try:
        data = _run(parsed, path, out, store, workers, scheduler, argv, figure)
    except BaseException:
        store.close()  # the finished chunks stay for the next run
        raise
    store.remove()
    return data


def _run(parsed: SweepFile, path, out: Path, store: ChunkFolder, workers, scheduler, argv, figure) -> dict:
    """:func:`run_sweep` under the resume folder's lock."""
    resumed = sum(store.has(k) for k in range(store.chunks))
    backend = make_backend(workers, scheduler)
    sweep = parsed.sweep
    try:
        with output_dir(out, SWEEP_WRITES) as stage:
            tables = _Tables(stage)
            try:
                summary = summarize(run_chunks(sweep, chunk=parsed.chunk, store=store, backend=backend),
                                    sweep.ensemble.seed, sweep.criterion, on_chunk=tables)
            finally:
                tables.close()
            settings = sweep.settings
            data = {
                "sweep": str(path),
                "body": sweep.ensemble.bodies.body.name,
                "nominal_moments": sweep.ensemble.bodies.body.principal_moments.tolist(),
                "cases": sweep.ensemble.cases, "seed": sweep.ensemble.seed, "sampling": sweep.ensemble.sampling,
                "chunk": parsed.chunk, "method": settings.method, "step": settings.step,
                "t_end": None if settings.times is not None else settings.t_end,
                "settings": parsed.settings, "backend": backend.describe(), "resumed_chunks": resumed,
                **summary.as_dict(sweep.criterion),
                "provenance": provenance(argv, parsed.sources),
            }
            write_json(_plain(data), stage / "summary.json")
            if figure is not None:  # drawn by the caller's layer, written here into the staged folder
                drawn = figure(summary.sample_columns(), title=f"{parsed.name}: {data['body']}, {settings.method}",
                               cases=summary.cases)
                drawn.savefig(stage / "sweep.png", dpi=FIGURE_DPI)
    finally:
        backend.close()
    return data


def _plain(value):
    """``value`` with numpy scalars and arrays turned into plain Python (for JSON)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def run_sweep_command(path: str | os.PathLike[str], out: str | os.PathLike[str], *, workers: int | None = None, scheduler: str | None = None,
                      argv: Sequence[str] | None = None, figure: Callable[..., Any] | None = None) -> int:
    """``tumble sweep PATH --out OUT``: :func:`run_sweep`, then one line for people; returns 0.

    Errors propagate (``ValueError`` for bad input: the command line's exit status 2).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = Path(folder, "spin.toml").write_text('body = "t-handle"\\n[sweep]\\ncases = 4\\n[initial]\\n'
    ...                                              'omega = [0.1, 5.0, 0.1]\\n')
    ...     status = run_sweep_command(Path(folder, "spin.toml"), Path(folder, "out"))  # doctest: +ELLIPSIS
    4 cases (exact): 4 predicted unstable; 4 flipped twice or more, flip period median ...; wrote .../out/
    >>> status
    0
    """
    data = run_sweep(path, out, workers=workers, scheduler=scheduler, argv=argv, figure=figure,
                     warn=lambda message: print(f"warning: {message}", file=sys.stderr))
    print(sweep_line(data, out))
    return 0


def sweep_line(data: dict, out: str | os.PathLike[str]) -> str:
    """One line: how many cases flipped, the flip period's median and 5-95 % range, the criterion."""
    counts, stats = data["counts"], data["statistics"]
    unstable = counts["predicted"].get("unstable", 0)
    flips = stats["flips"]
    period = stats["flip_period"]
    text = f"{data['cases']} cases ({data['method']}): {unstable} predicted unstable"
    if period["count"]:
        q = period["quantiles"]
        text += (f"; {period['count']} flipped twice or more, flip period median {q['0.5']:.4g} s "
                 f"(5-95 %: {q['0.05']:.4g} to {q['0.95']:.4g} s)")
    else:
        text += f"; at most {flips['max']:g} flip(s) per case"
    if data.get("redraws"):
        text += f"; {data['redraws']} unphysical draws redrawn"
    if "criterion" in data:
        text += f"; {data['criterion']['statement']}"
    return f"{text}; wrote {out}/"
