"""Every ``tumble.`` name the guides, the gallery and the README write has a page in the API
reference, and every name of every public ``__all__`` is on one (#28).

The listing is the one the site is built from (docs/_ext/tumble_api.py: docs/conf.py writes the
reference's sources with it), so a name that passes here is on the built site;
tests/test_docs.py checks the built pages for the anchors. No Sphinx needed here: this runs in
the plain test set-up, in seconds.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "docs" / "_ext"))

import tumble_api  # noqa: E402  (docs/_ext, put on the path above)

#: Generated sources (the API pages, autosummary's, sphinx-gallery's), not text anyone wrote.
GENERATED = ("docs/api/generated", "docs/api/modules", "docs/api/backreferences", "docs/examples")


def text_files() -> list[Path]:
    """The guides (docs/**/*.md, docs/**/*.rst), the gallery's scripts and the README."""
    found = [ROOT / "README.md", *ROOT.glob("docs/**/*.md"), *ROOT.glob("docs/**/*.rst"), *ROOT.glob("gallery/*.py")]
    written = []
    for path in found:
        relative = path.relative_to(ROOT).as_posix()
        if relative.startswith(GENERATED) or (path.parent == ROOT / "docs" / "api" and path.suffix == ".rst"):
            continue
        written.append(path)
    return sorted(set(written))


def written_names() -> list[tuple[str, str]]:
    """``("file:line", name)`` of every dotted ``tumble.`` name in :func:`text_files`."""
    return [(f"{path.relative_to(ROOT)}:{line}", name)
            for path in text_files() for line, name in tumble_api.names_in(path.read_text(encoding="utf-8"))]


def test_the_texts_are_found_and_name_many_things():
    files = {p.relative_to(ROOT).as_posix() for p in text_files()}
    assert {"README.md", "docs/tour.md", "docs/fitting.md", "docs/control.md"} <= files
    assert any(f.startswith("gallery/plot_") for f in files)
    assert len(written_names()) > 200


def test_every_name_the_guides_gallery_and_readme_write_has_a_page():
    documented = tumble_api.documented_names() | {e.full for e in tumble_api.listing() if e.inline}
    missing = []
    for where, name in written_names():
        page = tumble_api.page_for(name)
        if page is None:
            missing.append(f"{where}: {name} (no such public name)")
        elif page.startswith("obj:"):
            target = page.removeprefix("obj:")
            if not any(target == d or target.startswith(d + ".") for d in documented):
                missing.append(f"{where}: {name} -> {target}, which has no page")
    assert not missing, "\n".join(missing)


@pytest.mark.parametrize("name", [
    # the names #28 found without a page, where they live now
    "tumble.io.gyrodata.read_recording", "tumble.io.sweepfile.load_sweep", "tumble.commands.sweep.run_sweep",
    "tumble.io.examples.list_examples", "tumble.io.examples.copy_examples",
    "tumble.analysis.fit.synthetic.synthetic_recording", "tumble.analysis.fit.synthetic.example_recording",
    "tumble.dynamics.control.MomentumDumping", "tumble.dynamics.control.controllers.MomentumDumping",
])
def test_the_names_the_first_hour_missed_have_pages(name):
    page = tumble_api.page_for(name)
    assert page is not None and page.removeprefix("obj:") in tumble_api.documented_names(), (name, page)


def test_a_name_that_moved_or_is_private_has_no_page():
    # run_sweep moved from the file layer to the command layer; a guide naming the old place fails
    assert tumble_api.page_for("tumble.io.sweepfile.run_sweep") is None
    assert tumble_api.page_for("tumble.dynamics.controllers.MomentumDumping") is None
    assert tumble_api.page_for("tumble._html.script_json") is None


def test_every_name_of_every_public_all_has_a_page():
    modules = tumble_api.public_modules()
    assert {"tumble.mass", "tumble.io.gyrodata", "tumble.io.sweepfile", "tumble.commands.sweep",
            "tumble.analysis.fit.synthetic", "tumble.dynamics.control.controllers", "tumble.viz.plots"} <= set(modules)
    documented = tumble_api.documented_names()
    homeless = []
    for module_name in modules:
        for name in importlib.import_module(module_name).__all__:
            page = tumble_api.page_for(f"{module_name}.{name}")
            target = page.removeprefix("obj:") if page and page.startswith("obj:") else None
            inline = any(e.inline and e.full == target for e in tumble_api.listing())
            if page is None or (page.startswith("obj:") and target not in documented and not inline):
                homeless.append(f"{module_name}.{name}")
    assert not homeless, homeless


def test_each_object_is_documented_once_and_every_name_points_to_its_page():
    entries = tumble_api.listing()
    homes = [e.documented for e in entries if e.is_home]
    assert len(homes) == len(set(homes))
    for e in entries:
        obj = getattr(importlib.import_module(e.module), e.name)
        module_name, _, name = e.documented.rpartition(".")
        assert getattr(importlib.import_module(module_name), name) is obj, e  # the page shows this very object


def test_the_written_pages_list_every_name_they_document():
    """The sources docs/conf.py writes: each module's names in its page's autosummary table (a
    generated page each), the names it re-exports linked, and every module in a page's toctree."""
    for module_name in tumble_api.public_modules():
        stem = tumble_api.page_of(module_name)
        group = tumble_api.render_api_page(stem)
        entries = [e for e in tumble_api.listing() if e.module == module_name]
        if f".. automodule:: {module_name}\n" in group:
            text = group
        else:
            assert f"   modules/{module_name}\n" in group, f"api/{stem}.rst does not list {module_name}"
            text = tumble_api.render_module_page(module_name)
        for e in entries:
            if e.is_home and e.data:  # a constant: an entry of its module's page
                assert f".. autodata:: {e.name}\n" in text and f"\n   {e.name}\n" not in text, e
            elif e.alias:
                assert f".. py:data:: {e.name}\n" in text, e
            elif e.is_home:
                assert f"\n   {e.name}\n" in text, e
            else:
                assert f"<{e.documented}>`" in text, e


def test_the_scanner_reads_names_not_files_and_follows_imports():
    text = ("Run `tumble simulate run.toml`, see tumble.html and `tumble.io.sweepfile`.\n"
            "```python\nfrom tumble.io.gyrodata import read_recording, load_recording as load\n"
            "from tumble.analysis import (fit_recording,\n    fit_rotation)\n```\n"
            "src/tumble/io/bodyfile.py and tumble.viz.figure_* are not names; tumble.simulate(body) is.\n")
    assert sorted(tumble_api.names_in(text)) == sorted([
        (1, "tumble.io.sweepfile"), (7, "tumble.simulate"), (3, "tumble.io.gyrodata"),
        (3, "tumble.io.gyrodata.read_recording"), (3, "tumble.io.gyrodata.load_recording"),
        (4, "tumble.analysis"), (4, "tumble.analysis.fit_recording"), (4, "tumble.analysis.fit_rotation"),
    ])


def test_every_public_constant_says_what_it_is():
    """A constant is an entry of its module's page, shown with its ``#:`` comment; one without
    showed the docstring of its value's type (``int([x]) -> integer``), now its value alone. A
    comment above ``A, B = 1, 2`` or above the first of two lines belongs to the first name only."""
    from sphinx.pycode import ModuleAnalyzer

    constants = [e for e in tumble_api.listing() if e.is_home and e.data]
    assert len(constants) > 200
    silent = [e.full for e in constants if not ModuleAnalyzer.for_module(
        tumble_api.defining_module(e.module, e.name)).find_attr_docs().get(("", e.name))]
    assert not silent, f"public constants with no #: comment: {silent}"
