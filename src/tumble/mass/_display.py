"""Short plain reprs and Jupyter's rich HTML display of bodies and mass properties.

Numpy only (no plotting library): the physics layers may not import matplotlib. The small
helpers (numbers, vectors, names, tables, all text escaped) live in :mod:`tumble._html`, shared
with the display of trajectories (:mod:`tumble.dynamics._display`), the layer above.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol, cast

from .._html import fmt, html_table, short_name, vec
from .tensor import AXIS_ROLES

if TYPE_CHECKING:
    from ..typing import Matrix3, Vector3
    from .parts import Part

__all__ = ["body_html", "body_repr", "properties_html", "properties_repr"]

#: Most parts listed in the HTML table; the rest are counted.
MAX_PARTS_SHOWN = 20


class _Properties(Protocol):
    """What the display reads of :class:`~tumble.mass.body.MassProperties` (kg, m, kg m^2).

    A protocol, not the class: :mod:`tumble.mass.body` imports this module, and the import graph
    has no circles.
    """

    @property
    def mass(self) -> float: ...
    @property
    def com(self) -> Vector3: ...
    @property
    def principal_moments(self) -> Vector3: ...
    @property
    def principal_axes(self) -> Matrix3: ...
    @property
    def intermediate_axis(self) -> Vector3 | None: ...
    @property
    def degeneracy(self) -> str: ...


class _Body(Protocol):
    """What the display reads of :class:`~tumble.mass.body.Body`: its name, parts and mass properties."""

    @property
    def name(self) -> str: ...
    @property
    def parts(self) -> Sequence[Part]: ...
    @property
    def mass(self) -> float: ...
    @property
    def principal_moments(self) -> Vector3: ...
    @property
    def properties(self) -> _Properties: ...


def properties_repr(p: _Properties) -> str:
    """``MassProperties(m = 3 kg, COM = (0, 0, 0.25) m, I = (0.125, 0.3125, 0.4375) kg m^2)``.

    Examples
    --------
    >>> import tumble
    >>> from tumble.mass._display import properties_repr
    >>> properties_repr(tumble.t_handle().properties)
    'MassProperties(m = 3 kg, COM = (0, 0, 0.25) m, I = (0.125, 0.3125, 0.4375) kg m^2)'
    """
    return f"MassProperties(m = {fmt(p.mass)} kg, COM = {vec(p.com)} m, I = {vec(p.principal_moments)} kg m^2)"


def body_repr(body: _Body) -> str:
    """``Body('T-handle', 2 parts, m = 3 kg, I = (0.125, 0.3125, 0.4375) kg m^2)``.

    Examples
    --------
    >>> import tumble
    >>> from tumble.mass._display import body_repr
    >>> body_repr(tumble.t_handle())
    "Body('T-handle', 2 parts, m = 3 kg, I = (0.125, 0.3125, 0.4375) kg m^2)"
    """
    n = len(body.parts)
    return (f"Body({short_name(body.name)}, {n} part{'' if n == 1 else 's'}, m = {fmt(body.mass)} kg, "
            f"I = {vec(body.principal_moments)} kg m^2)")


def _properties_rows(p: _Properties) -> list[tuple[str, str]]:
    rows = [("mass", f"{fmt(p.mass, 6)} kg"), ("centre of mass (design frame)", f"{vec(p.com, 6)} m")]
    for j, role in enumerate(AXIS_ROLES):
        rows.append((f"I{j + 1} ({role}), axis in the design frame",
                     f"{fmt(p.principal_moments[j], 6)} kg m^2 along {vec(p.principal_axes[:, j])}"))
    if p.intermediate_axis is None:
        rows.append(("intermediate axis", f"none: a {p.degeneracy} body does not flip"))
    else:
        rows.append(("intermediate axis", f"{vec(p.intermediate_axis)}: spin about it is unstable (tennis-racket theorem)"))
    return rows


def properties_html(p: _Properties) -> str:
    """The mass properties as an HTML table (kg, m, kg m^2).

    Examples
    --------
    >>> import tumble
    >>> from tumble.mass._display import properties_html
    >>> html = properties_html(tumble.t_handle().properties)
    >>> html.startswith("<table"), "tennis-racket theorem" in html
    (True, True)
    """
    return html_table(_properties_rows(p), caption="MassProperties")


def _part_rows(parts: Sequence[Part]) -> list[tuple[object, ...]]:
    rows: list[tuple[object, ...]] = []
    for i, part in enumerate(parts[:MAX_PARTS_SHOWN]):
        rows.append((i, part.kind, fmt(cast(float, part.mass), 6), vec(part.com), "removed" if part.subtract else ""))
    if len(parts) > MAX_PARTS_SHOWN:
        rows.append(("...", f"and {len(parts) - MAX_PARTS_SHOWN} more parts", "", "", ""))
    return rows


def body_html(body: _Body) -> str:
    """A body's mass properties and its parts as HTML (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import tumble
    >>> from tumble.mass._display import body_html
    >>> html = body_html(tumble.t_handle())
    >>> html.startswith("<div>"), html.count("rod")   # the two rods in the parts table
    (True, 2)
    """
    n = len(body.parts)
    head = f"Body {body.name!s}: {n} part{'' if n == 1 else 's'}"
    return ("<div>" + html_table(_properties_rows(body.properties), caption=head)
            + html_table(_part_rows(body.parts), header=("#", "kind", "mass (kg)", "centre (m)", ""),
                         caption="parts")
            + "</div>")
