"""The ``tumble sweep`` command: run a sweep file and write its results, all or nothing.

The file's format is :mod:`tumble.io.sweepfile`'s; the cases are run by :mod:`tumble.ensemble`
(in this process or on a Dask cluster).

:func:`run_sweep` writes into ``DIR``, all at once or not at all (:func:`tumble.io.output.output_dir`):

- ``cases.csv``: one row per case (:func:`tumble.ensemble.reduce_cases`): ``case``, ``I1 [kg m^2]``
  to ``I3``, ``omega0_1 [rad/s]`` to ``omega0_3`` (principal frame), the drawn values (one column
  per dispersed quantity, e.g. ``shaft_length [m]``), ``resampled``, then ``axis``, ``predicted``,
  ``growth_rate [1/s]``, ``wobble_frequency [rad/s]``, ``circulation``, ``flips``,
  ``flip_period [s]``, ``flip_period_exact [s]``, ``omega_end_1 [rad/s]`` to ``_3``, ``q_end_x``
  to ``q_end_w``, ``max_nutation [rad]``, ``energy_change``, ``L_world_angle [rad]``,
  ``samples_per_flip`` (the flip interval, exact, or under a torque the shorter of the counted one and
  the start's torque-free one, over the widest sample spacing: below 4
  the flips counted are aliased, and ``summary.json``'s ``"flipped"`` counts those cases,
  ``aliased``). Floats are
  written as Python's shortest round-trip repr (``nan`` where a quantity does not apply);
- ``cases.parquet``: the same table, when pyarrow is installed (``pip install 'tumble[table]'``);
- ``summary.json``: the sweep's settings, the streaming statistics
  (:meth:`tumble.ensemble.SweepSummary.as_dict`), the fraction of cases that flipped with its
  95 % confidence interval (``"flipped"``; a flip as docs/conventions.md defines it), the
  criterion's success statement and the provenance (:func:`tumble.io.provenance.provenance`);
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
import time
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..ensemble import compute_chunk, make_backend, run_chunks, summarize
from ..io.export import write_json
from ..io.output import FIGURE_DPI, check_output_dir, output_dir
from ..io.provenance import provenance
from ..io.resume import ChunkFolder
from ..io.sweepfile import SWEEP_WRITES, CaseTables, SweepFile, load_sweep

__all__ = ["run_sweep", "run_sweep_command", "sweep_line"]


def _check_first_case(parsed: SweepFile, path) -> None:
    """Compute case 0, so that a sweep that cannot run, or whose criterion names no column of
    the cases, fails in one line naming the file before any output."""
    try:
        first = compute_chunk(parsed.sweep, 0, 1)
        if parsed.sweep.criterion is not None:
            try:
                parsed.sweep.criterion.passed(first)
            except ValueError as exc:
                raise ValueError(f"criterion: {exc}") from None
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


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
        ``warn(message)`` for a resumed chunk that is not reused (:mod:`tumble.io.resume`;
        default a :class:`tumble.io.resume.ResumeWarning`) and for a Sobol' set of other than 2^k
        cases (default a UserWarning).

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
    >>> from pathlib import Path
    >>> from tumble.commands.sweep import run_sweep
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = Path(folder, "spin.toml").write_text('body = "t-handle"\\n[sweep]\\ncases = 8\\n[initial]\\n'
    ...                                              'omega = [0.1, 5.0, 0.1]\\ndistribution = "normal"\\n'
    ...                                              'spread = [0.01, 0.0, 0.01]\\n[criterion]\\ncolumn = "flips"\\nmin = 1\\n')
    ...     data = run_sweep(Path(folder, "spin.toml"), Path(folder, "out"))
    ...     written = sorted(p.name for p in Path(folder, "out").iterdir())
    >>> data["cases"], data["counts"]["predicted"], data["criterion"]["passed"]  # spun about the intermediate axis
    (8, {'unstable': 8}, 8)
    >>> written
    ['cases.csv', 'cases.parquet', 'summary.json']
    """
    parsed = load_sweep(path)
    _check_first_case(parsed, path)
    out = check_output_dir(out).absolute()
    sweep = parsed.sweep
    n = sweep.ensemble.cases
    if sweep.ensemble.sampling == "sobol" and n & (n - 1):  # scipy's own warning is silenced: chunks draw parts of it
        (warn or (lambda message: warnings.warn(message, stacklevel=3)))(
            f"cases = {n} is not a power of 2: a Sobol' set is balanced at {1 << (n.bit_length() - 1)} or "
            f"{1 << n.bit_length()} cases, and {n} cover the space less evenly")
    store = ChunkFolder(out.parent / f"{out.name}.resume", parsed.fingerprint(), cases=sweep.ensemble.cases,
                        chunk=parsed.chunk, warn=warn)
    try:
        data = _run(parsed, path, out, store, workers, scheduler, argv, figure)
    except BaseException as exc:
        if any(store.has(k) for k in range(store.chunks)):  # they stay for the next run, and the message says where
            store.close()
            exc.add_note(f"the finished chunks are kept in {store.folder}/: the same sweep run again resumes")
        else:  # none finished: "nothing written" left DIR.resume/ (its fingerprint and lock) behind
            store.remove()
        raise
    store.remove()
    return data


#: A sweep whose first chunk says the rest will take longer than this (s) says so, with how to stop it.
LONG_SWEEP_S = 120.0


def _timed(write: Callable[[dict], object], chunks: int, size: int, folder: Path) -> Callable[[dict], None]:
    """``write`` for each chunk's columns; after the first, a note on stderr when the ``chunks`` to
    compute will take more than :data:`LONG_SWEEP_S` at its pace (a walkthrough's 67 million cases
    ran silently towards ~27 h)."""
    start, seen = time.perf_counter(), [0]

    def passed(columns: dict) -> None:
        write(columns)
        seen[0] += 1
        spent = time.perf_counter() - start
        left = (chunks - 1) * spent
        if seen[0] == 1 and left > LONG_SWEEP_S:
            print(f"note: a chunk of {size} cases took {spent:.2g} s: the other {chunks - 1:,} take about "
                  f"{_duration(left)} more; Ctrl-C keeps the finished chunks in {folder}/, and the same command "
                  "resumes", file=sys.stderr)

    return passed


def _duration(seconds: float) -> str:
    """``seconds`` as a reader says it: ``"3 min"``, ``"27 h"``.

    Examples
    --------
    >>> from tumble.commands.sweep import _duration
    >>> _duration(200.0), _duration(97000.0), _duration(4e6)
    ('3.3 min', '27 h', '46 days')
    """
    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= 2 * size or unit == "min":
            return f"{seconds / size:.2g} {unit}" if seconds / size < 10 else f"{seconds / size:.0f} {unit}"
    return f"{seconds:.0f} s"


def _run(parsed: SweepFile, path, out: Path, store: ChunkFolder, workers, scheduler, argv, figure) -> dict:
    """:func:`run_sweep` under the resume folder's lock."""
    resumed = sum(store.has(k) for k in range(store.chunks))
    backend = make_backend(workers, scheduler)
    sweep = parsed.sweep
    try:
        with output_dir(out, SWEEP_WRITES) as stage:
            tables = CaseTables(stage)
            try:
                summary = summarize(run_chunks(sweep, chunk=parsed.chunk, store=store, backend=backend),
                                    sweep.ensemble.seed, sweep.criterion,
                                    on_chunk=_timed(tables, store.chunks - resumed, parsed.chunk, store.folder))
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
    >>> from pathlib import Path
    >>> from tumble.commands.sweep import run_sweep_command
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = Path(folder, "spin.toml").write_text('body = "t-handle"\\n[sweep]\\ncases = 4\\n[initial]\\n'
    ...                                              'omega = [0.1, 5.0, 0.1]\\ndistribution = "normal"\\n'
    ...                                              'spread = [0.01, 0.0, 0.01]\\n')
    ...     status = run_sweep_command(Path(folder, "spin.toml"), Path(folder, "out"))  # doctest: +ELLIPSIS
    4 cases (exact): 4 predicted unstable; 4 flipped (100 %, 95 % interval 39.76 to 100 %); flip period median ...; wrote .../out/
    >>> status
    0
    """
    data = run_sweep(path, out, workers=workers, scheduler=scheduler, argv=argv, figure=figure,
                     warn=lambda message: print(f"warning: {message}", file=sys.stderr))
    print(sweep_line(data, out))
    return 0


def sweep_line(data: dict, out: str | os.PathLike[str]) -> str:
    """One line: how many cases flipped (with the fraction's confidence interval), the flip
    period's median and 5-95 % range, the criterion.

    Examples
    --------
    >>> from tumble.commands.sweep import sweep_line
    >>> data = {"cases": 4, "method": "exact", "counts": {"predicted": {"unstable": 4}},
    ...         "flipped": {"cases": 4, "fraction": 1.0, "confidence": 0.95, "interval": [0.3976, 1.0]},
    ...         "statistics": {"flips": {"max": 3.0}, "flip_period": {"count": 4, "quantiles":
    ...                        {"0.05": 1.21, "0.5": 1.25, "0.95": 1.3}}}}
    >>> sweep_line(data, "out")
    '4 cases (exact): 4 predicted unstable; 4 flipped (100 %, 95 % interval 39.76 to 100 %); flip period median 1.25 s over 4 flipping twice or more (5-95 %: 1.21 to 1.3 s); wrote out/'
    >>> sweep_line({**data, "resumed_chunks": 3}, "out").split("; ")[-2]   # an interrupted run's chunks taken over
    '3 chunks resumed'
    """
    counts, stats = data["counts"], data["statistics"]
    unstable = counts["predicted"].get("unstable", 0)
    flips = stats["flips"]
    period = stats["flip_period"]
    text = f"{data['cases']} cases ({data['method']}): {unstable} predicted unstable"
    if rest := counts["predicted"].get("at rest", 0):  # no spin axis: neither stable nor unstable
        text += f" ({rest} at rest)"
    if "flipped" in data:
        f = data["flipped"]
        low, high = f["interval"]
        text += (f"; {f['cases']} flipped ({100 * f['fraction']:.4g} %, {100 * f['confidence']:.4g} % interval "
                 f"{100 * low:.4g} to {100 * high:.4g} %)")
        if f.get("aliased"):  # flips shorter than the samples resolve: the counts and periods are not the motion's
            text += (f" but {f['aliased']} case{'' if f['aliased'] == 1 else 's'} sampled fewer than 4 times a flip "
                     f"(min {stats['samples_per_flip']['min']:.2g}): their flips may be miscounted, give more samples")
    if period["count"]:
        q = period["quantiles"]
        text += (f"; flip period median {q['0.5']:.4g} s over {period['count']} flipping twice or more "
                 f"(5-95 %: {q['0.05']:.4g} to {q['0.95']:.4g} s)")
    else:
        text += f"; at most {flips['max']:g} flip(s) per case"
    if data.get("redraws"):
        text += f"; {data['redraws']} unphysical draws redrawn"
    if "criterion" in data:
        text += f"; {data['criterion']['statement']}"
    if data.get("resumed_chunks"):  # an interrupted run's finished chunks, checked and taken over
        text += f"; {data['resumed_chunks']} chunk{'' if data['resumed_chunks'] == 1 else 's'} resumed"
    return f"{text}; wrote {out}/"
