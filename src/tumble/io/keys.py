"""The keys of tumble's input files, each format's in one table: what the parser accepts and what
its reference page lists.

Each file format's module holds its tables of :class:`Key` (``BODY_FORMAT`` in
:mod:`tumble.io.bodyfile`, ``SCENARIO_FORMAT`` in :mod:`tumble.io.scenario`, ...); its parser
refuses a key that is not in the table (:meth:`Table.check`), and the documentation renders the
same tables (docs/_ext/tumble_keys.py), so the page and the parser cannot disagree about which
keys there are. A key's type, unit, default and range are stated here and enforced by the
constructor the value feeds (one message for a bad value from Python, a file or the command
line); tests/test_file_keys.py feeds each stated bound to the parser.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..validation import short_repr, unknown_name

__all__ = ["FileFormat", "Key", "Table"]


@dataclass(frozen=True)
class Key:
    """One key of a table of an input file.

    Attributes
    ----------
    name : str
        The key as written in the file.
    type : str
        Its TOML type in words: ``"number"``, ``"whole number"``, ``"string"``, ``"true or false"``,
        ``"3 numbers"``, ``"table"``, ...
    unit : str
        The SI unit of its value (``"rad/s"``), empty for none.
    default : str
        The value taken when the key is absent, as TOML or in words; empty when there is none.
    allowed : str
        The values allowed, in words (empty: any value of the type); see :meth:`allowed_text`.
    example : str
        One value, as written in a file (TOML).
    doc : str
        What it is, in one line.
    required : bool
        Whether a table without it is refused.
    low, high : float or None
        Bounds of a number, if any (checked against the parser by the tests).
    low_included, high_included : bool
        Whether the bound itself is allowed.
    choices : tuple of str
        The strings allowed, for a key that takes one of a few.

    Examples
    --------
    >>> from tumble.io.keys import Key
    >>> t_end = Key("t_end", "number", "s", "20.0", example="20.0", doc="duration of the run", low=0.0)
    >>> t_end.allowed_text(), Key("frame", "string", choices=("body", "world")).allowed_text()
    ('> 0', '"body", "world"')
    """

    name: str
    type: str
    unit: str = ""
    default: str = ""
    allowed: str = ""
    example: str = ""
    doc: str = ""
    required: bool = False
    low: float | None = None
    low_included: bool = False
    high: float | None = None
    high_included: bool = True
    choices: tuple[str, ...] = ()

    def allowed_text(self) -> str:
        """The values allowed, in words: :attr:`allowed`, else the bounds or the choices.

        Examples
        --------
        >>> from tumble.io.keys import Key
        >>> Key("confidence", "number", low=0.0, high=1.0, high_included=False).allowed_text()
        '> 0 and < 1'
        """
        if self.allowed:
            return self.allowed
        if self.choices:
            return ", ".join(f'"{c}"' for c in self.choices)
        parts = []
        if self.low is not None:
            parts.append(f"{'>=' if self.low_included else '>'} {_number(self.low)}")
        if self.high is not None:
            parts.append(f"{'<=' if self.high_included else '<'} {_number(self.high)}")
        return " and ".join(parts)


def _number(x: float) -> str:
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else (repr(x) if math.isfinite(x) else str(x))


@dataclass(frozen=True, repr=False)
class Table:
    """The keys of one table of an input file (``[simulation]``, ``[[dispersion]]``, the top level).

    Examples
    --------
    >>> from tumble.io.keys import Key, Table
    >>> damper = Table("damper", (Key("inertia", "number", "kg m^2", required=True),
    ...                           Key("damping", "number", "N m s", required=True)))
    >>> damper.names()
    ('inertia', 'damping')
    >>> damper.check("damper", {"inertia": 0.01, "dampin": 0.05})
    Traceback (most recent call last):
    ...
    ValueError: damper: unknown key 'dampin' (did you mean 'damping'?); allowed: damping, inertia
    """

    #: How the file writes the table (``"[simulation]"``); a heading on the page.
    title: str
    keys: tuple[Key, ...]
    #: What the table is for, one or two sentences (reStructuredText).
    doc: str = ""

    def __repr__(self) -> str:
        return f"Table({self.title!r}: {', '.join(self.names())})"

    def names(self) -> tuple[str, ...]:
        """The keys' names, in the table's order.

        Examples
        --------
        >>> from tumble.io.scenario import SCENARIO_FORMAT
        >>> SCENARIO_FORMAT.table("[initial]").names()
        ('omega', 'frame', 'orbit_frame')
        """
        return tuple(k.name for k in self.keys)

    def key(self, name: str) -> Key:
        """The key of that name.

        Examples
        --------
        >>> from tumble.io.keys import Key, Table
        >>> Table("[torque]", (Key("vector", "3 numbers", "N m"),)).key("vector").unit
        'N m'
        """
        for k in self.keys:
            if k.name == name:
                return k
        raise KeyError(name)

    def check(self, where: str, table: object, *, kind: str = "") -> dict:
        """``table`` when it is a table whose keys are all in this one; else one line naming
        ``where``, the first unknown key and the keys allowed (sorted).

        ``kind`` names the table's kind in the message where the keys depend on it
        (``torque: key 'vector' does not go with kind = 'gravity_gradient'; allowed: ...``).

        Examples
        --------
        >>> from tumble.io.keys import Key, Table
        >>> Table("[initial]", (Key("omega", "3 numbers", "rad/s"),)).check("initial", [1, 2])
        Traceback (most recent call last):
        ...
        ValueError: initial must be a table [initial], not [1, 2]
        """
        if not isinstance(table, dict):
            raise ValueError(f"{where} must be a table [{where}], not {short_repr(table)}")  # noqa: TRY004 - one error type for bad input
        names = self.names()
        for key in sorted(table):
            if key not in names:
                allowed = ", ".join(sorted(names))
                if kind:
                    raise ValueError(f"{where}: key {key!r} does not go with kind = {kind!r}; allowed: {allowed}")
                raise ValueError(unknown_name(where, key, sorted(names)))
        return table


@dataclass(frozen=True, repr=False)
class FileFormat:
    """An input file format: its tables, in the order its reference page shows them.

    Examples
    --------
    >>> from tumble.io.scenario import SCENARIO_FORMAT
    >>> [t.title for t in SCENARIO_FORMAT.tables][:3]
    ['top level', '[initial]', '[initial.orbit_frame]']
    """

    name: str
    tables: tuple[Table, ...]
    #: What files of this format are and which command reads them (reStructuredText).
    doc: str = ""

    def __repr__(self) -> str:
        return f"FileFormat({self.name!r}: {', '.join(t.title for t in self.tables)})"

    def table(self, title: str) -> Table:
        """The table of that title (``"[simulation]"``).

        Examples
        --------
        >>> from tumble.io.scenario import SCENARIO_FORMAT
        >>> SCENARIO_FORMAT.table("[damper]").names()
        ('inertia', 'damping')
        """
        for t in self.tables:
            if t.title == title:
                return t
        raise KeyError(title)
