"""The documentation site: `mkdocs build --strict` passes, offline, and the API reference is whole.

One build (about 5 s) serves every test here; `make docs` runs the same command into site/.
"""

from __future__ import annotations

import ast
import importlib.util
import os
import re
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import pytest

pytest.importorskip("mkdocs")
pytest.importorskip("material")
pytest.importorskip("mkdocstrings_handlers.python")

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "tumble"
SUBPACKAGES = ("mass", "dynamics", "analysis", "ensemble", "io", "viz")
# griffe keeps the module tumble/dynamics/simulate.py under the name `simulate`
# (mkdocstrings/griffe#124), so docs/api/dynamics.md shows the function from there.
RENDERED_AS = {"tumble.dynamics.simulate": "tumble.dynamics.simulate.simulate"}


def _literal(path: Path, name: str):
    """The literal value assigned to ``name`` at the top of a module, read without importing it."""
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == name for t in node.targets):
            return ast.literal_eval(node.value)
    raise AssertionError(f"{path} assigns no {name}")


def _anchor(path: str) -> str:
    return RENDERED_AS.get(path, path)


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    site = tmp_path_factory.mktemp("site")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                          cwd=ROOT, capture_output=True, text=True, timeout=300, env=env)
    return proc, site


@pytest.fixture(scope="module")
def site(build):
    proc, site = build
    if proc.returncode != 0:
        pytest.fail(f"mkdocs build --strict failed (exit {proc.returncode}):\n{proc.stderr[-4000:]}")
    return site


def test_the_strict_build_passes_without_a_warning(build):
    proc, _ = build
    output = proc.stdout + proc.stderr
    problems = [line for line in output.splitlines() if line.startswith(("WARNING", "ERROR"))]
    assert proc.returncode == 0 and not problems, "\n".join(problems) or output[-4000:]


@pytest.mark.parametrize("package", SUBPACKAGES)
def test_each_api_page_shows_every_name_of_its_subpackage(site, package):
    html = (site / "api" / f"{package}.html").read_text(encoding="utf-8")
    names = _literal(SRC / package / "__init__.py", "__all__")
    assert names
    missing = [n for n in names if f'id="{_anchor(f"tumble.{package}.{n}")}"' not in html]
    assert not missing, f"api/{package}.html lacks {missing}"


@pytest.mark.parametrize(("page", "name"), [
    ("dynamics", "tumble.dynamics.simulate.simulate"),
    ("dynamics", "tumble.dynamics.Trajectory"),
    ("kernels", "tumble.dynamics.methods.exact.FreeRotation"),
    ("kernels", "tumble.dynamics.methods.exact_batch.free_rotation_batch"),
    ("analysis", "tumble.analysis.fit_rotation"),
    ("mass", "tumble.mass.Body"),
])
def test_key_names_have_an_entry_with_their_docstring(site, page, name):
    html = (site / "api" / f"{page}.html").read_text(encoding="utf-8")
    start = html.index(f'id="{name}"')
    assert "doc-contents" in html[start:start + 20000]


def test_the_api_index_links_every_top_level_name_to_its_entry(site):
    html = (site / "api" / "index.html").read_text(encoding="utf-8")
    exports = _literal(SRC / "__init__.py", "_EXPORTS")
    unlinked = [name for name, module in exports.items()
                if not re.search(rf'href="[a-z]+\.html#{re.escape(_anchor(f"{module}.{name}"))}"', html)]
    assert not unlinked, f"api/index.html does not link {unlinked}"


def test_every_gallery_page_is_built_and_in_the_navigation(site):
    index = (site / "index.html").read_text(encoding="utf-8")
    pages = sorted((ROOT / "docs" / "gallery").glob("*.md"))
    assert len(pages) >= 2
    for page in pages:
        assert (site / "gallery" / f"{page.stem}.html").is_file()
        assert f'href="gallery/{page.stem}.html"' in index, f"{page.name} is not in the navigation"


def test_sphinx_markup_is_read_not_printed(site):
    api = {p.stem: p.read_text(encoding="utf-8") for p in (site / "api").glob("*.html")}
    roles = re.compile(r":(?:func|class|mod|data|meth|attr):")
    assert not [page for page, html in api.items() if roles.search(html)]
    # a role in a docstring becomes a link to the entry (tumble.analysis.stability's docstrings
    # cite :func:`flip_interval`), a `#:` comment the constant's text, `::` a code block
    assert re.search(r'<a class="autorefs autorefs-internal"[^>]*href="#tumble\.analysis\.flip_interval"',
                     api["analysis"])
    rtol = api["mass"][api["mass"].index('id="tumble.mass.INERTIA_RTOL"'):]
    assert "round-off" in rtol[:3000]
    assert re.search(r"<code>[^<]*w1 = s a1 cn\(u\)", api["kernels"])


class _Resources(HTMLParser):
    """Every address a page loads by itself: scripts, styles, icons, images, frames."""

    def __init__(self):
        super().__init__()
        self.urls: list[str] = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag in ("script", "img", "iframe", "source", "video", "audio") and attrs.get("src"):
            self.urls.append(attrs["src"])
        if tag == "link" and attrs.get("href"):
            self.urls.append(attrs["href"])


def test_the_site_loads_nothing_from_the_network(site):
    remote = re.compile(r"^(?:https?:)?//")
    found = {}
    for page in site.rglob("*.html"):
        parser = _Resources()
        parser.feed(page.read_text(encoding="utf-8"))
        found.update({url: page.relative_to(site) for url in parser.urls if remote.match(url)})
    for sheet in site.rglob("*.css"):
        for url in re.findall(r"url\(\s*['\"]?([^'\")]+)", sheet.read_text(encoding="utf-8")):
            if remote.match(url):
                found[url] = sheet.relative_to(site)
    assert not found, f"remote resources: {found}"
    assert (site / "search" / "search_index.js").is_file()  # the offline plugin's inlined index


def test_the_site_works_from_file_with_no_network_search_included(site, new_page):
    watched = new_page()
    page = watched.page
    page.goto((site / "api" / "analysis.html").as_uri())
    assert page.locator('[id="tumble.analysis.fit_rotation"]').count() == 1
    page.goto((site / "index.html").as_uri())
    page.locator(".md-search__input").click()
    page.keyboard.type("free_rotation_batch")  # typed: the search listens to key events
    results = page.locator(".md-search-result__item")
    results.first.wait_for(timeout=15_000)  # the search index runs in the iframe-worker shim
    assert "kernels.html" in results.first.locator("a").first.get_attribute("href")
    assert not watched.outside, f"requests that left file://: {watched.outside}"
    assert not watched.errors, watched.errors


def _markup_module():
    spec = importlib.util.spec_from_file_location("sphinx_markup", ROOT / "docs" / "hooks" / "sphinx_markup.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_literal_blocks_become_fenced_code_in_lists_and_paragraphs():
    blocks = _markup_module()._literal_blocks
    text = "Intro\n\n- case one::\n\n      a = b\n        c\n\n- case two\n\nTail ::\n\n    x\n\n::\n\n    y\nend"
    assert blocks(text).split("\n") == [
        "Intro", "", "- case one:", "", "    ```text", "    a = b", "      c", "    ```", "", "- case two", "",
        "Tail", "", "```text", "x", "```", "", "", "```text", "y", "```", "end"]
    assert blocks("no block::\nsame level") == "no block::\nsame level"


def test_attribute_comments_are_read_from_the_lines_above():
    above = _markup_module()._comment_above
    lines = ["x = 1", "#: first line", "#: second", "NAME = 2", "", "OTHER = 3"]
    assert above(lines, 4) == "first line\nsecond"
    assert above(lines, 6) is None


def test_roles_resolve_in_their_scope_and_through_the_top_level_names():
    griffe = pytest.importorskip("griffe")
    markup = _markup_module()
    tumble = griffe.load("tumble", search_paths=[str(ROOT / "src")],
                         extensions=griffe.load_extensions(markup.SphinxMarkup()))
    assert markup._top_level_exports(tumble)["t_handle"] == "tumble.mass"
    # dispersions.py cites :func:`tumble.t_handle` (a lazy top-level name): to mass's entry
    assert 'identifier="tumble.mass.t_handle"' in tumble["ensemble.dispersions"].docstring.value
    # a bare name resolves through the module's imports, to the object's own path
    assert markup._target(tumble["analysis.summary"], "flip_interval", {}) == "tumble.analysis.stability.flip_interval"
    assert markup._target(tumble["analysis.summary"], "os", {}) is None  # not tumble's: plain code
