"""The gallery's machinery (docs/gallery/): published numbers that tumble reproduces.

Each entry lives in its own test module ``tests/test_gallery_<name>.py`` that defines
``ENTRY = Entry(...)``: its page's slug and title, a ``compute()`` that computes its quantities
with tumble, and a ``page(result)`` that writes the page (the published quantity, its source,
the conditions, tumble's value, the difference and the code that made it, pasted verbatim by
:func:`code`), plus its own tests of the result against the published value or range, and
``test_page_is_current = page_test(ENTRY)``. ``tests/test_gallery.py`` writes the index from every
such module. A page is rewritten only when its text changed, and then its test fails, so a stale
committed page fails the suite; run the test again (or commit the rewritten page) to pass.

Numbers on the pages are rounded so that they do not depend on the last bits of a platform's
arithmetic: values to 9 significant digits, differences to their power of ten.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import math
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import tumble
from tumble.io.atomic import atomic_path

GALLERY = Path(__file__).resolve().parents[1] / "docs" / "gallery"
TESTS = Path(__file__).resolve().parent


@dataclass(frozen=True)
class Entry:
    """One gallery page: ``slug`` names ``docs/gallery/<slug>.md``; ``order`` sorts the index."""

    slug: str
    title: str
    order: int
    compute: Callable[[], dict]
    page: Callable[[dict], str]

    def result(self) -> dict:
        return _result(self.compute)


@functools.cache
def _result(compute: Callable[[], dict]) -> dict:
    return compute()


def entries() -> list[Entry]:
    """Every entry, from the modules ``tests/test_gallery_*.py``, in index order."""
    found = []
    for path in sorted(TESTS.glob("test_gallery_*.py")):
        module = importlib.import_module(path.stem)
        found.append(module.ENTRY)
    return sorted(found, key=lambda e: (e.order, e.slug))


def write_if_changed(path: Path, text: str) -> None:
    """Rewrite ``path`` when its text differs from ``text``, and fail: the page was stale."""
    old = path.read_text() if path.exists() else None
    if old != text:
        path.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(path) as tmp:  # never a half-written page, even with two runs at once
            tmp.write_text(text)
    assert old == text, f"{path} was stale and has been rewritten: review and commit it"


def page_test(entry: Entry):
    """A test that the committed page of ``entry`` equals its rendered text."""

    def test_page_is_current():
        write_if_changed(GALLERY / f"{entry.slug}.md", entry.page(entry.result()))

    return test_page_is_current


def body(moments):
    """A 1 kg body with these principal moments (kg m^2) along the design axes: one that exists
    (``MassProperties.from_moments`` refuses moments beyond the triangle inequality, issue 27)."""
    return tumble.MassProperties.from_moments(moments)


def upward_crossings(t, y):
    """Times of upward zero crossings of a sampled component, linearly interpolated, s."""
    k = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])


def sig(x: float, digits: int = 9) -> str:
    """``x`` to ``digits`` significant digits."""
    return f"{x:.{digits}g}"


def to_tolerance(x: float, rel: float) -> str:
    """A measured ``x`` to the significant digits that the asserted relative tolerance ``rel`` fixes.

    The digits beyond it move with the platform (numpy's summation order, the libm): a page that
    printed them went stale on another machine with the same code.
    """
    return sig(x, max(1, math.floor(-math.log10(rel))))


def within(rel: float, unit: str = "relative") -> str:
    """The bound a test asserts on a difference, for the page: ``< 1e-8 relative``."""
    exponent = math.log10(rel)
    text = f"1e{round(exponent)}" if exponent == round(exponent) else f"{rel:g}"
    return f"< {text} {unit}".rstrip()


def magnitude(d: float) -> str:
    """A difference as the power of ten just above it: stable across platforms and versions only
    where the difference does not sit at the round-off of a computation (which moves by factors of
    a few when the compiled code rounds otherwise) near a power of ten; there, :func:`bound`."""
    d = abs(d)
    return "0" if d == 0 else f"< 1e{math.floor(math.log10(d)) + 1}"


def bound(d: float, limit: float) -> str:
    """A difference given as the bound ``limit`` its test holds it to, ``< limit`` (its own
    decade where it is beyond: the test then fails and says so)."""
    return f"< {limit:g}" if abs(d) < limit else magnitude(d)


def code(*functions) -> str:
    """The source of ``functions``, verbatim, as a fenced block, headed by the file they are in."""
    files = sorted({Path(inspect.getsourcefile(f)).name for f in functions})
    source = "\n\n".join(textwrap.dedent(inspect.getsource(f)).rstrip() for f in functions)
    where = ", ".join(f"`tests/{f}`" for f in files)
    run = " ".join(f"tests/{f}" for f in files)
    return (f"**Code**, verbatim from {where} (the module's constants and `tests/gallery.py`'s helpers are not shown "
            f"and are not part of tumble: in a checkout, `make .venv/.tumble-test && .venv/bin/python -m pytest {run}` "
            f"runs it and checks this page):\n\n```python\n{source}\n```\n")
