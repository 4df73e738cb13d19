"""Text and JSON pasted into HTML, escaped, and the small text helpers of every repr (numbers,
vectors, names, tables): the one place every page and display of tumble uses.

A user's strings (a body's name, a scenario file's name, a title) reach HTML in two ways:

* as text or an attribute value: :func:`escape_text` (``&``, ``<``, ``>``, ``"`` and ``'`` as
  character references);
* inside a ``<script type="application/json">`` element: :func:`script_json`. A script's text
  ends at the first ``</script``, and after ``<!--`` a ``<script`` makes the parser swallow the
  rest of the document up to a second ``</script>`` (the HTML standard's "script data double
  escaped" state): the viewer's own scripts would be eaten and the page left blank. JSON
  allows any character as ``\\uXXXX``, so ``<``, ``>`` and ``&`` are written so and the element
  cannot hold markup at all (the escaping of the OWASP XSS prevention cheat sheet, rule 3.1).
"""

from __future__ import annotations

import dataclasses
import html
import json
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from .typing import ArrayLike

__all__ = ["NAME_CHARS", "REPR_CHARS", "Headline", "escape_text", "field_repr", "fmt", "headline_html", "headline_repr",
           "html_table", "plural", "result_html", "result_repr", "script_json", "short_name", "vec", "with_std"]

#: A result's headline: ``(attribute, label, unit)`` for each value its repr and table show, most
#: important first (:func:`headline_repr`).
Headline = tuple[tuple[str, str, str], ...]

#: Characters written as JSON escapes in :func:`script_json`: markup (``<``, ``>``, ``&``) and the
#: two line separators that end a line in JavaScript before ES2019.
_SCRIPT_ESCAPES = {ord(c): f"\\u{ord(c):04x}" for c in "<>&\u2028\u2029"}


def escape_text(value: object) -> str:
    """``str(value)`` as HTML text or a quoted attribute value (``html.escape``, quotes too).

    Examples
    --------
    >>> from tumble._html import escape_text
    >>> escape_text('a <b> & "c"')
    'a &lt;b&gt; &amp; &quot;c&quot;'
    """
    return html.escape(str(value), quote=True)


def script_json(data: Any) -> str:
    """Compact JSON of ``data`` to paste inside ``<script type="application/json">``: it holds no
    ``<``, ``>`` or ``&`` (each written as its ``\\uXXXX`` escape), so no text of the data can
    end or change the element; ``JSON.parse`` of the element's text gives ``data`` back.

    Examples
    --------
    >>> from tumble._html import script_json
    >>> script_json({"name": "</script><!--<script>"})
    '{"name":"\\\\u003c/script\\\\u003e\\\\u003c!--\\\\u003cscript\\\\u003e"}'
    """
    return json.dumps(data, separators=(",", ":")).translate(_SCRIPT_ESCAPES)


#: Longest body name shown in a plain repr; longer names are cut with an ellipsis.
NAME_CHARS = 40
_STYLE = "border-collapse:collapse;font-size:0.9em;margin:0.3em 0"
_CELL = "text-align:left;padding:1px 14px 1px 2px"


def fmt(x: float | np.floating[Any] | np.integer[Any], digits: int = 4) -> str:
    """A number in ``digits`` significant figures; ``-0`` printed as ``0``.

    Examples
    --------
    >>> from tumble._html import fmt
    >>> fmt(3.14159265), fmt(0.000123456, 2), fmt(-0.0), fmt(-1e-20), fmt(12345678)
    ('3.142', '0.00012', '0', '-1e-20', '1.235e+07')
    """
    value = float(x)
    return f"{value + 0.0:.{digits}g}" if value != 0 else "0"


def vec(v: ArrayLike, digits: int = 4) -> str:
    """A vector as ``(a, b, c)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble._html import vec
    >>> vec([1.0, -0.0, 2 / 3]), vec(np.eye(2), digits=2)   # flattened
    ('(1, 0, 0.6667)', '(1, 0, 0, 1)')
    """
    return "(" + ", ".join(fmt(x, digits) for x in np.ravel(v)) + ")"


def short_name(name: object) -> str:
    """The name for a plain repr: quoted as ``repr`` does, cut to :data:`NAME_CHARS` characters.

    Examples
    --------
    >>> from tumble._html import NAME_CHARS, short_name
    >>> short_name("T-handle"), short_name(42)   # any object, as its text
    ("'T-handle'", "'42'")
    >>> long = short_name("x" * 100)
    >>> len(long) == NAME_CHARS + 2, long[-4:]   # the quotes, and the cut ends with "..."
    (True, "...'")
    """
    text = str(name)
    return repr(text if len(text) <= NAME_CHARS else text[: NAME_CHARS - 3] + "...")


def _cell(tag: str, text: object) -> str:
    return f'<{tag} style="{_CELL}">{escape_text(text)}</{tag}>'


def html_table(
    rows: Iterable[Sequence[object]], header: Sequence[object] | None = None, caption: str | None = None
) -> str:
    """An HTML table of plain-text cells; every cell, header and caption is escaped.

    Parameters
    ----------
    rows : iterable of sequences
        The cells of each row (anything ``str`` turns into text).
    header : sequence, optional
        Column headings.
    caption : str, optional
        A caption above the table.

    Examples
    --------
    >>> from tumble._html import html_table
    >>> page = html_table([["I1", 0.5], ["<b>", "a & b"]], header=["axis", "kg m^2"], caption="moments")
    >>> page.count("<tr>"), page.count("<th "), page.count("<td ")   # a header row, two rows of two cells
    (3, 2, 4)
    >>> "&lt;b&gt;" in page and "a &amp; b" in page and "<b>" not in page   # the cells are text, not markup
    True
    """
    out = [f'<table style="{_STYLE}">']
    if caption is not None:
        out.append(f'<caption style="text-align:left;font-weight:bold">{escape_text(caption)}</caption>')
    if header is not None:
        out.append("<thead><tr>" + "".join(_cell("th", h) for h in header) + "</tr></thead>")
    out.append("<tbody>")
    out += ["<tr>" + "".join(_cell("td", c) for c in row) + "</tr>" for row in rows]
    out.append("</tbody></table>")
    return "".join(out)


#: Most characters in a result's plain repr (:func:`result_repr`): one line a reader takes in.
REPR_CHARS = 240


def plural(n: int, word: str, many: str | None = None) -> str:
    """``n`` and ``word``, in the plural unless ``n`` is 1 (``many``: an irregular plural).

    Examples
    --------
    >>> from tumble._html import plural
    >>> plural(1, "sample"), plural(5401, "sample"), plural(2, "body", "bodies")
    ('1 sample', '5401 samples', '2 bodies')
    """
    return f"{n} {word if n == 1 else (many or word + 's')}"


def with_std(value: float | np.floating[Any], std: float | np.floating[Any] | None, digits: int = 4) -> str:
    """``value +- std`` (the standard uncertainty in 2 figures); ``value`` alone when it has none.

    Examples
    --------
    >>> from tumble._html import with_std
    >>> with_std(0.51234, 0.0123), with_std(2.0, float("nan")), with_std(2.0, None)
    ('0.5123 +- 0.012', '2', '2')
    """
    if std is None or not np.isfinite(float(std)):
        return fmt(value, digits)
    return f"{fmt(value, digits)} +- {fmt(std, 2)}"


def result_repr(kind: str, parts: Iterable[str]) -> str:
    """A result's plain repr, ``Kind(part, part, ...)``: one line of at most :data:`REPR_CHARS`
    characters (the parts that do not fit are left out and counted as ``...``).

    Parameters
    ----------
    kind : str
        The class's name.
    parts : iterable of str
        What it is, its size and its headline numbers, most important first.

    Examples
    --------
    >>> from tumble._html import REPR_CHARS, result_repr
    >>> result_repr("Run", ["5401 samples over 5400 s", "final rate 0.01 deg/s"])
    'Run(5401 samples over 5400 s, final rate 0.01 deg/s)'
    >>> long = result_repr("Run", ["x" * 100] * 5)
    >>> len(long) <= REPR_CHARS, long.endswith(", ...)")
    (True, True)
    """
    shown: list[str] = []
    width = len(kind) + 2
    for part in (" ".join(str(p).split()) for p in parts):  # one line: no newline of a message survives
        if width + len(part) + 2 > REPR_CHARS - 5:
            shown.append("...")
            break
        shown.append(part)
        width += len(part) + 2
    return f"{kind}({', '.join(shown)})"


def result_html(caption: str, rows: Iterable[Sequence[object]], *more: str) -> str:
    """A result's rich display for Jupyter (``_repr_html_``): a table of ``(what, value)`` rows
    under ``caption``, then any further HTML (``more``: other tables, made by :func:`html_table`).

    Examples
    --------
    >>> from tumble._html import result_html
    >>> page = result_html("Run", [("samples", 11), ("final rate", "0.1 rad/s")])
    >>> page.startswith("<div><table"), page.count("<tr>")
    (True, 2)
    """
    return "<div>" + html_table(rows, caption=caption) + "".join(more) + "</div>"


def _shown(value: Any) -> str:
    """A headline value as text: a number by :func:`fmt`, a vector of up to three by :func:`vec`,
    a longer array by its size (never its values), a flag as yes/no, a text as it is."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return fmt(value)
    if isinstance(value, np.ndarray) or isinstance(value, (tuple, list)) and value and not isinstance(value[0], str):
        a = np.asarray(value)
        if a.ndim == 1 and a.size <= 3 and np.issubdtype(a.dtype, np.number):
            return vec(a)
        return f"{' x '.join(str(n) for n in a.shape)} values"
    if isinstance(value, (tuple, list)):
        return ", ".join(str(v) for v in value) or "none"
    return str(value) if value not in (None, "") else "none"


def _headline(obj: Any) -> list[tuple[str, str]]:
    """``(label, value with its unit)`` for each entry of ``obj.HEADLINE`` (:data:`Headline`), but an
    empty text ("file none" said of a throw made in Python)."""
    rows = []
    for name, label, unit in obj.HEADLINE:
        value = getattr(obj, name)
        if isinstance(value, str) and not value:  # a text not given (a throw made in Python has no file): left out
            continue
        text = _shown(value)
        rows.append((label, text + (f" {unit}" if unit and not text.endswith(" values") else "")))  # a size has no unit
    return rows


def headline_repr(obj: Any) -> str:
    """A result's plain repr from its headline (``obj.HEADLINE``, :data:`Headline`): one line,
    ``Kind(label value unit, ...)``, arrays by their size. For a class, ``__repr__ = headline_repr``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble._html import headline_repr
    >>> class Span:
    ...     HEADLINE = (("stop", "stop", ""), ("offset", "offset", "m"), ("t", "times", "s"))
    ...     stop, offset, t = 90, np.array([0.03, 0.0, 0.05]), np.zeros(400)
    >>> headline_repr(Span())
    'Span(stop 90, offset (0.03, 0, 0.05) m, times 400 values)'
    >>> class Log:
    ...     HEADLINE = (("input", "file", ""), ("samples", "samples", ""))
    ...     input, samples = "", 3582
    >>> headline_repr(Log())   # a text not given is left out, not "file none"
    'Log(samples 3582)'
    """
    return result_repr(type(obj).__name__, [f"{label} {value}" for label, value in _headline(obj)])


def headline_html(obj: Any) -> str:
    """A result's Jupyter table (``_repr_html_``) from its headline (:func:`headline_repr`): a row
    for each value, under the class's name.

    Examples
    --------
    >>> from tumble._html import headline_html
    >>> class Verdict:
    ...     HEADLINE = (("adequate", "adequate", ""), ("misfit", "misfit", ""))
    ...     adequate, misfit = True, 0.0098
    >>> headline_html(Verdict()).count("<tr>")
    2
    """
    return result_html(type(obj).__name__, _headline(obj))


def _field_value(value: Any) -> str:
    """A setting as :func:`field_repr` shows it: numbers and short vectors by value (six at most),
    a longer or 2-D array by its shape, a rotation by its rotation vector, anything else by its repr."""
    if isinstance(value, (bool, np.bool_, str)) or value is None:
        return repr(value)
    if isinstance(value, (int, np.integer, float, np.floating)):
        return fmt(value)
    if isinstance(value, np.ndarray):
        if value.ndim == 1 and value.size <= 6 and np.issubdtype(value.dtype, np.number):
            return vec(value)
        return f"<{' x '.join(str(n) for n in value.shape)} array>"
    if type(value).__name__ == "Rotation" and hasattr(value, "as_rotvec"):  # scipy's, one or a stack
        return f"Rotation(rotvec={vec(value.as_rotvec())})" if getattr(value, "single", False) else \
            f"<{len(value)} rotations>"
    if type(value).__repr__ is field_repr:  # a setting inside a setting: named, its own repr is a line of its own
        return f"{type(value).__name__}(...)"
    return " ".join(repr(value).split())


def field_repr(obj: Any) -> str:
    """A model's or a setting's repr on one line: its class and its fields (a dataclass's shown ones,
    or a named tuple's) as ``name=value``, arrays by value when short and by shape otherwise, and
    never more than :data:`REPR_CHARS` characters. For a class, ``__repr__ = field_repr``.

    Examples
    --------
    >>> import numpy as np
    >>> from dataclasses import dataclass
    >>> from tumble._html import field_repr
    >>> @dataclass(frozen=True, repr=False)
    ... class Wheels:
    ...     axes: np.ndarray
    ...     inertia: np.ndarray
    ...     __repr__ = field_repr
    >>> Wheels(np.eye(3), np.full(3, 1e-4))
    Wheels(axes=<3 x 3 array>, inertia=(0.0001, 0.0001, 0.0001))
    """
    if dataclasses.is_dataclass(obj):
        names = [f.name for f in dataclasses.fields(obj) if f.repr]
    else:
        names = list(getattr(obj, "_fields", ()))
    return result_repr(type(obj).__name__, [f"{name}={_field_value(getattr(obj, name))}" for name in names])
