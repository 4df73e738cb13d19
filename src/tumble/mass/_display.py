"""Short plain reprs and Jupyter's rich HTML display of bodies and mass properties.

Numpy only (no plotting library): the physics layers may not import matplotlib. The small
HTML helpers here (numbers, vectors, tables, all text escaped) are shared with the display of
trajectories (:mod:`tumble.dynamics._display`), the layer above.
"""

from __future__ import annotations

import numpy as np

from .._html import escape_text
from .tensor import AXIS_ROLES

__all__ = ["body_html", "body_repr", "fmt", "html_table", "properties_html", "properties_repr", "short_name",
           "vec"]

#: Longest body name shown in a plain repr; longer names are cut with an ellipsis.
NAME_CHARS = 40
#: Most parts listed in the HTML table; the rest are counted.
MAX_PARTS_SHOWN = 20
_STYLE = "border-collapse:collapse;font-size:0.9em;margin:0.3em 0"
_CELL = "text-align:left;padding:1px 14px 1px 2px"


def fmt(x, digits: int = 4) -> str:
    """A number in ``digits`` significant figures; ``-0`` printed as ``0``."""
    x = float(x)
    return f"{x + 0.0:.{digits}g}" if x != 0 else "0"


def vec(v, digits: int = 4) -> str:
    """A vector as ``(a, b, c)``."""
    return "(" + ", ".join(fmt(x, digits) for x in np.ravel(v)) + ")"


def short_name(name) -> str:
    """The name for a plain repr: quoted as ``repr`` does, cut to :data:`NAME_CHARS` characters."""
    name = str(name)
    return repr(name if len(name) <= NAME_CHARS else name[: NAME_CHARS - 3] + "...")


def _cell(tag: str, text) -> str:
    return f'<{tag} style="{_CELL}">{escape_text(text)}</{tag}>'


def html_table(rows, header=None, caption=None) -> str:
    """An HTML table of plain-text cells; every cell, header and caption is escaped.

    Parameters
    ----------
    rows : iterable of sequences
        The cells of each row (anything ``str`` turns into text).
    header : sequence, optional
        Column headings.
    caption : str, optional
        A caption above the table.
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


def properties_repr(p) -> str:
    """``MassProperties(m = 3 kg, COM = (0, 0, 0.25) m, I = (0.125, 0.3125, 0.4375) kg m^2)``."""
    return f"MassProperties(m = {fmt(p.mass)} kg, COM = {vec(p.com)} m, I = {vec(p.principal_moments)} kg m^2)"


def body_repr(body) -> str:
    """``Body('T-handle', 2 parts, m = 3 kg, I = (0.125, 0.3125, 0.4375) kg m^2)``."""
    n = len(body.parts)
    return (f"Body({short_name(body.name)}, {n} part{'' if n == 1 else 's'}, m = {fmt(body.mass)} kg, "
            f"I = {vec(body.principal_moments)} kg m^2)")


def _properties_rows(p) -> list[tuple[str, str]]:
    rows = [("mass", f"{fmt(p.mass, 6)} kg"), ("centre of mass (design frame)", f"{vec(p.com, 6)} m")]
    for j, role in enumerate(AXIS_ROLES):
        rows.append((f"I{j + 1} ({role}), axis in the design frame",
                     f"{fmt(p.principal_moments[j], 6)} kg m^2 along {vec(p.principal_axes[:, j])}"))
    if p.intermediate_axis is None:
        rows.append(("intermediate axis", f"none: a {p.degeneracy} body does not flip"))
    else:
        rows.append(("intermediate axis", f"{vec(p.intermediate_axis)}: spin about it is unstable (tennis-racket theorem)"))
    return rows


def properties_html(p) -> str:
    """The mass properties as an HTML table (kg, m, kg m^2)."""
    return html_table(_properties_rows(p), caption="MassProperties")


def _part_rows(parts) -> list[tuple]:
    rows = []
    for i, part in enumerate(parts[:MAX_PARTS_SHOWN]):
        rows.append((i, part.kind, fmt(part.mass, 6), vec(part.com), "removed" if part.subtract else ""))
    if len(parts) > MAX_PARTS_SHOWN:
        rows.append(("...", f"and {len(parts) - MAX_PARTS_SHOWN} more parts", "", "", ""))
    return rows


def body_html(body) -> str:
    """A body's mass properties and its parts as HTML (Jupyter's ``_repr_html_``)."""
    n = len(body.parts)
    head = f"Body {body.name!s}: {n} part{'' if n == 1 else 's'}"
    return ("<div>" + html_table(_properties_rows(body.properties), caption=head)
            + html_table(_part_rows(body.parts), header=("#", "kind", "mass (kg)", "centre (m)", ""),
                         caption="parts")
            + "</div>")
