"""Delimited text, as the readers of recordings and throws start: the data lines, the separator,
the header's cells, the rows of numbers and the order of the times.

Written here rather than with :func:`numpy.loadtxt` or :mod:`csv`: the readers name the file,
the line and the column of every error in one line, take a decimal comma where ``;``, a tab or
spaces separate (phyphox's five CSV exports: comma or tab or semicolon, decimal point or comma),
merge a space-separated ``t (ms)`` into one header cell and skip ``#`` comments anywhere, which
neither does with such messages.
"""

from __future__ import annotations

import re
import warnings

import numpy as np

_NUMBER = re.compile(r"^[+-]?(\d+([.,]\d*)?|[.,]\d+)([eE][+-]?\d+)?$|^[+-]?(nan|inf|infinity)$", re.IGNORECASE)


def _split(line: str, sep: str | None) -> list[str]:
    cells = line.split(sep) if sep else line.split()
    return [c.strip().strip('"').strip("'").strip() for c in cells]


def _separator(line: str) -> str | None:
    for sep in ("\t", ";", ","):
        if sep in line:
            return sep
    return None


def _data_lines(raw: bytes, label: str) -> list[tuple[int, str]]:
    """A text's lines as ``(line number, text)``, blank and ``#`` lines left out; one line naming
    the file for bytes that are not UTF-8."""
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        # an Excel workbook (.xlsx a zip, .xls an OLE2 file: their magic numbers), which phyphox also exports
        if raw[:4] == b"PK\x03\x04" or raw[:8] == b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1":
            raise ValueError(f"{label}: an Excel workbook or a zip, not text: export the recording as CSV") from None
        raise ValueError(f"{label}: not a text file (UTF-8): byte {err.start} cannot be decoded") from None
    return [(i + 1, line) for i, line in enumerate(text.splitlines()) if line.strip() and not line.lstrip().startswith("#")]


def _first_lines(raw: bytes, label: str, expected: str) -> tuple[list[tuple[int, str]], str | None, list[str]]:
    """A delimited text's data lines (line number, text; blank and ``#`` lines left out), its
    separator (None: white space) and its first line's cells: what every table reader starts with.
    Space-separated, ``t (ms)`` is one header cell (a name and its unit)."""
    lines = _data_lines(raw, label)
    if not lines:
        raise ValueError(f"{label}: no data; expected {expected}")
    sep = _separator(lines[0][1])
    head = _split(lines[0][1], sep)
    while len(head) > 1 and head[-1] == "":  # a trailing separator
        head.pop()
    if sep is None:
        merged: list[str] = []
        for cell in head:
            if merged and cell[:1] in ("(", "[") and not _NUMBER.match(merged[-1]):
                merged[-1] += " " + cell
            else:
                merged.append(cell)
        head = merged
    return lines, sep, head


def _rows(lines, sep, columns, width, label, head=None, decimal_comma=None, expected="") -> np.ndarray:
    """The numbers of ``columns`` in each data line (``(line number, text)``), a decimal comma
    wherever the separator is not ``,`` (unless ``decimal_comma`` says otherwise); one line naming the
    file and the line for a row of the wrong length or a cell that is not a number (and its
    column's name in ``head``, when given)."""
    comma = sep != "," if decimal_comma is None else decimal_comma
    rows = np.empty((len(lines), len(columns)))
    for k, (no, line) in enumerate(lines):
        cells = _split(line, sep)
        while len(cells) > width and cells[-1] == "":  # a trailing separator
            cells.pop()
        if len(cells) != width:
            raise ValueError(f"{label}, line {no}: {len(cells)} columns; expected {width}{expected}")
        for j, c in enumerate(columns):
            cell = cells[c]
            if not _NUMBER.match(cell) or ("," in cell and not comma):
                name = "" if head is None else f"{head[c]} = "
                raise ValueError(f"{label}, line {no}, column {c + 1}: {name}{cell[:40]!r} is not a number")
            rows[k, j] = float(cell.replace(",", ".") if comma else cell)
    return rows


def _refuse_cell(bad, rows, lines, columns, names, label, rule) -> None:
    """Raise for the first cell where ``bad`` (shaped as ``rows``) holds, naming the file, its line and
    column, the column's name in ``names`` (one per column of ``rows``) and the value as read:
    ``rule(k, j)`` says what is wrong with cell ``(k, j)`` ("is not a finite number", ...)."""
    if bad.any():
        k, j = np.argwhere(bad)[0]
        raise ValueError(f"{label}, line {lines[k][0]}, column {columns[j] + 1}: {names[j]} = {rows[k, j]:.6g} "
                         f"{rule(k, j)}")


def _check_order(t, lines, label) -> None:
    """Times must increase (irregular steps are fine): name the first line that goes back or repeats,
    and, where it goes back by more than a second, a clock that wrapped or a second log joined on
    (a walkthrough, 2026-12-03). Times that are no number or absurd are left to the fit's checks,
    which say so."""
    from ..analysis.fit.single import MAX_TIME

    if not np.all(np.abs(t) <= MAX_TIME):
        return
    bad = np.flatnonzero(~(np.diff(t) > 0))
    if bad.size:
        k = int(bad[0]) + 1
        word = "repeats" if t[k] == t[k - 1] else "goes back before"
        wrap = 2.0**32 / 1e6  # s: a 32-bit microsecond clock's turn
        why = ("" if t[k - 1] - t[k] <= 1.0 else  # a large jump back: the clock wrapped, or another log begins
               f" (a 32-bit microsecond clock wraps at {wrap:.6f} s: add it to the times from this line on)"
               if abs((t[k - 1] - t[k]) - wrap) < 1.0 else " (a second log section from this line on? Give each its "
               "own file)")
        raise ValueError(f"{label}, line {lines[k][0]}: time {t[k]:.9g} s {word} the time {t[k - 1]:.9g} s of line "
                         f"{lines[k - 1][0]}; times must increase{why}")


class CutLogWarning(UserWarning):
    """A log's last line left out, half written: the logger stopped while writing it (the command
    line says it in one line).

    Examples
    --------
    >>> from tumble.io.throwfile import CutLogWarning   # its public home
    >>> CutLogWarning.cli_one_line
    True
    """

    cli_one_line = True


def _without_a_cut_last_line(lines: list, sep: str, width: int, label: str) -> list:
    """``lines`` (``(line number, text)``) without a last line that holds fewer cells than ``width``:
    a logger that stops in flight, as the device's does, can leave its last row half written; that
    row is left out with a warning, not the whole log refused. A short line elsewhere stays an
    error (:func:`_rows`)."""
    if not lines:
        return lines
    no, text = lines[-1]
    cells = _split(text, sep)
    while cells and cells[-1] == "":
        cells.pop()
    if len(cells) >= width:
        return lines
    warnings.warn(f"{label}, line {no}: the last line holds {len(cells)} of {width} columns, a log cut while it was "
                  "written: left out", CutLogWarning, stacklevel=4)
    return lines[:-1]
