"""What tumble's messages share: a value shown short, the nearest of a list of names, an unknown
key or table named with its nearest and what is allowed, and a value shown beside a limit it
passes with the digits that tell them apart.

Re-exported by :mod:`tumble.validation`.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

import numpy as np

__all__ = ["beyond", "nearest", "short_repr", "unknown_name"]


def short_repr(value: object, limit: int = 80) -> str:
    """``repr(value)`` on one line and at most ``limit`` characters, for error messages.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import short_repr
    >>> short_repr(np.array([[1.0, 2.0],
    ...                      [3.0, 4.0]]))
    'array([[1.0, 2.0], [3.0, 4.0]])'
    >>> short_repr(list(range(100)), limit=20)
    '[0, 1, 2, 3, 4, 5...'
    """
    text = f"array({value.tolist()!r})" if isinstance(value, np.ndarray) else repr(value)
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


def nearest(word: str, choices: Iterable[str], cutoff: float = 0.6) -> str | None:
    """The one of ``choices`` nearest to a misspelt ``word`` (difflib's ratio at least ``cutoff``),
    or None: what every "did you mean" of tumble's messages names.

    Examples
    --------
    >>> from tumble.validation import nearest
    >>> nearest("perido", ["period", "gain", "form"]), nearest("bogus", ["period", "gain"])
    ('period', None)
    >>> nearest("--framse", ["--frame", "--frames"])   # two letters swapped: the same letters first
    '--frames'
    """
    found = difflib.get_close_matches(word, list(choices), n=3, cutoff=cutoff)
    # a typist's swap of two letters keeps them all: "--framse" is "--frames", though difflib ranks "--frame" nearer
    swapped = [c for c in found if sorted(c) == sorted(word)]
    return (swapped or found or [None])[0]


def unknown_name(where: str, name: object, allowed: Iterable[str], *, what: str = "key", after: str = "",
                 allowed_label: str = "allowed", listed: str | None = None) -> str:
    """The one line for an unknown key or table of an input file: where, the name as written, the
    allowed name nearest to it (:func:`nearest`) and what is allowed, one home for every file
    reader's message (the device file's ``mas`` was answered with eighteen names and not ``mass``).

    ``where`` is the table or file ("" for a file's top level), ``after`` words that follow the name,
    ``allowed_label`` the words before the list, ``listed`` the list as text (``allowed`` joined by
    default).

    Examples
    --------
    >>> from tumble.validation import unknown_name
    >>> unknown_name("[device]", "mas", ["mass", "rotor_axis"])
    "[device]: unknown key 'mas' (did you mean 'mass'?); allowed: mass, rotor_axis"
    >>> unknown_name("", "bogus", ["body", "initial"], what="table")
    "unknown table 'bogus'; allowed: body, initial"
    """
    allowed = [str(a) for a in allowed]
    near = nearest(str(name), allowed) if isinstance(name, str) else None
    hint = f" (did you mean {near!r}?)" if near is not None else ""
    head = f"{where}: " if where else ""
    return f"{head}unknown {what} {name!r}{after}{hint}; {allowed_label}: {', '.join(allowed) if listed is None else listed}"


def beyond(value: float, limit: float) -> str:
    """``value`` written as ``{:.3g}`` would, with more digits where that reads the same as ``limit``
    written as ``{:g}``: a message saying "up to 1.0001e+06, at most 1e+06" where three digits gave
    "up to 1e+06, at most 1e+06".

    Examples
    --------
    >>> from tumble.validation import beyond
    >>> beyond(2.5e6, 1e6), beyond(1.0001e6, 1e6), f"{1e6:g}"
    ('2.5e+06', '1.0001e+06', '1e+06')
    """
    shown = f"{value:.3g}"
    for digits in range(4, 18):
        if shown != f"{limit:g}" and float(shown) != float(f"{limit:g}"):
            break
        shown = f"{value:.{digits}g}"
    return shown
