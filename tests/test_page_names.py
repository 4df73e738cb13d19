"""A user's text on the interactive page (body name, scenario file name, title) stays text.

The page holds it twice: in HTML (``<title>``, the heading, the notebook frame's attributes),
where it must be HTML-escaped, and in the JSON of ``<script id="tumble-data">``, where ``<!--``
followed by ``<script`` would make the HTML parser swallow the viewer's own scripts (a blank
page) unless ``<``, ``>`` and ``&`` are written as ``\\u003c``, ``\\u003e`` and ``\\u0026``.
"""

from __future__ import annotations

import html
import json

import pytest
from test_page import open_viewer

import tumble
from tumble._html import escape_text, script_json
from tumble.cli import main
from tumble.viz.notebook import show
from tumble.viz.page import page_html

#: Breaks out of HTML wherever pasted unescaped: "<!--<script" turns the rest of a script
#: element into one that swallows the next ones, "</script>" ends it, "&amp;" is an entity,
#: quotes end attributes; U+2028 ends a line in old JavaScript.
HOSTILE = "x<!--<script>&amp;</script><b>\"'</b>\u2028y"
#: The same for a file name (no "/").
HOSTILE_FILE = "s<!--<script>&amp;<b>\"' z"
START = '<script type="application/json" id="tumble-data">'


def data_element(page: str) -> str:
    """The raw text of the page's data element, as far as the first ``</script``."""
    start = page.index(START) + len(START)
    return page[start : page.index("</script", start)]


@pytest.fixture(scope="module")
def hostile_page(tmp_path_factory):
    """``tumble view`` of a scenario file with a hostile name whose body has a hostile name."""
    folder = tmp_path_factory.mktemp("names")
    scenario = folder / f"{HOSTILE_FILE}.toml"
    scenario.write_text(f"[body]\nname = {json.dumps(HOSTILE)}\n"
                        '[[body.parts]]\nkind = "box"\nmass = 1.0\nsize = [0.3, 0.2, 0.1]\n'
                        "[initial]\nomega = [0.1, 5.0, 0.1]\n[simulation]\nt_end = 2.0\nsamples = 41\n",
                        encoding="utf-8")
    out = folder / "page.html"
    assert main(["view", str(scenario), "--out", str(out), "--frames", "10"]) == 0
    return out


def title_of(method: str) -> str:
    """The page's title: the scenario names no method, so ``auto`` chose it and the title says so."""
    return f"{HOSTILE_FILE}: {HOSTILE}, {method} (auto)"


@pytest.mark.parametrize("text", [HOSTILE, HOSTILE_FILE, "<!--", "-->", "]]>", "a & b < c > d", "\u2028\u2029", ""])
def test_script_json_holds_no_markup_and_reads_back(text):
    data = {"name": text, "list": [text, {"k": text}], "n": 1.5}
    blob = script_json(data)
    assert not {"<", ">", "&", "\u2028", "\u2029"} & set(blob)
    assert json.loads(blob) == data


def test_escape_text_is_html_escaping_with_quotes():
    assert escape_text(HOSTILE) == html.escape(HOSTILE, quote=True)
    assert html.unescape(escape_text(HOSTILE)) == HOSTILE
    assert not {"<", ">", '"', "'"} & set(escape_text(HOSTILE))


def test_hostile_names_stay_inside_the_data_element(hostile_page):
    page = hostile_page.read_text(encoding="utf-8")
    raw = data_element(page)
    assert not {"<", ">", "&"} & set(raw)  # no "<!--", no "</script": the HTML parser cannot leave it
    data = json.loads(raw)
    assert data["body_name"] == HOSTILE and data["title"] == title_of(data["method"])
    escaped = html.escape(data["title"], quote=True)
    assert f"<title>{escaped}</title>" in page and f'<h1 id="tumble-title">{escaped}</h1>' in page


def test_page_with_hostile_names_plays_in_chromium(hostile_page, new_page):
    """The viewer ran (its plots drawn, the form filled) and the names read as they were given."""
    watched = open_viewer(new_page, hostile_page.as_uri())
    page = watched.page
    method = page.evaluate("JSON.parse(document.getElementById('tumble-data').textContent).method")
    assert page.title() == title_of(method)
    assert page.text_content("#tumble-title") == title_of(method)
    assert page.evaluate("tumbleViewer.state()") == {"playing": False, "frame": 0, "frames": 10}
    # the page's own scripts only (plotly, splitting, live, viewer, data): none swallowed, none added
    assert page.evaluate("document.scripts.length") == 5
    for plot in ("#tumble-ground", "#tumble-body", "#tumble-omega"):
        assert page.locator(f"{plot} .main-svg").count() >= 1, plot
    assert page.locator("#tumble-ground canvas").count() >= 1  # WebGL scene
    options = page.evaluate("Array.from(document.querySelectorAll('#tumble-live-preset option'),"
                            " (o) => o.textContent)")
    assert f"this body ({HOSTILE})" in options[0]
    assert watched.errors == [] and watched.outside == []


def test_notebook_frame_with_hostile_names():
    body = tumble.Body([tumble.Box(mass=1.0, size=(0.3, 0.2, 0.1))], name=HOSTILE)
    traj = tumble.simulate(body, [0.1, 5.0, 0.1], t_end=1.0, samples=21)
    from test_notebooks import frames_of

    text = show(traj, body, frames=5, title=HOSTILE).data
    found = frames_of(text)
    assert found.tags == ["div", "iframe"]  # nothing of the names became a tag of the notebook
    (frame,) = found.iframes
    assert frame["title"] == f"tumble: {HOSTILE}, {traj.method}"
    page = frame["srcdoc"]
    assert page == page_html(body, traj, frames=5, title=HOSTILE)
    assert not {"<", ">", "&"} & set(data_element(page))
    assert json.loads(data_element(page))["title"] == HOSTILE
