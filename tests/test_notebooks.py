"""The example notebooks run from top to bottom, and tumble.viz.show embeds the page.

Each ``examples/notebooks/*.ipynb`` is executed by nbclient in a kernel of *this* interpreter
(a kernelspec written to a temporary folder on ``JUPYTER_PATH``, so an unrelated ``python`` on
PATH or a user's own kernels never answer); any cell error fails the test.
"""

from __future__ import annotations

import html
import json
import re
import sys
from html.parser import HTMLParser
from pathlib import Path

import pytest

import tumble
from tumble.viz.notebook import show
from limits import HANG_MS, HANG_S

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "examples" / "notebooks").glob("*.ipynb"))
#: A line of plotly.js's own licence header: once per copy of the bundle.
PLOTLY_BUNDLE = "plotly.js v"


class _Frames(HTMLParser):
    """The attributes of every <iframe>, and every other tag's name."""

    def __init__(self):
        super().__init__()
        self.iframes, self.tags = [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        if tag == "iframe":
            self.iframes.append(dict(attrs))


def frames_of(html_text: str) -> _Frames:
    parser = _Frames()
    parser.feed(html_text)
    parser.close()
    return parser


@pytest.fixture(scope="module")
def run():
    body = tumble.t_handle()
    return body, tumble.simulate(body, [0.1, 10.0, 0.1], t_end=4.0, samples=101)


# tumble.viz.show --------------------------------------------------------------------------

def test_show_embeds_the_page_in_an_isolated_frame(run):
    body, traj = run
    out = show(traj, body, frames=10, height=700)
    text = out._repr_html_() if hasattr(out, "_repr_html_") else out.data
    found = frames_of(text)
    assert found.tags == ["div", "iframe"]  # nothing outside the frame: no script runs in the notebook's page
    (frame,) = found.iframes
    assert frame["height"] == "700" and frame["sandbox"] == "allow-scripts"
    page = frame["srcdoc"]  # the parser has undone the escaping
    assert page.lstrip().lower().startswith("<html") or page.lstrip().lower().startswith("<!doctype html")
    assert page.count(PLOTLY_BUNDLE) == 1  # plotly.js inside, once: plays offline
    assert "T-handle" in page
    assert html.escape(page, quote=True) in text


def test_show_plays_in_its_sandboxed_frame(run, tmp_path, new_page):
    """The sandbox (scripts only: no same-origin, no storage) leaves the page working: it draws and plays."""
    body, traj = run
    notebook_page = tmp_path / "notebook.html"
    notebook_page.write_text(f"<!doctype html><html><body>{show(traj, body, frames=20).data}</body></html>")
    watched = new_page(viewport={"width": 1100, "height": 1200})
    page = watched.page
    page.goto(notebook_page.as_uri())
    page.wait_for_function("document.querySelector('iframe').contentWindow !== null")
    frame = page.frames[1]
    frame.wait_for_function("window.tumbleViewer !== undefined", timeout=HANG_MS)
    assert frame.evaluate("tumbleViewer.state()") == {"playing": False, "frame": 0, "frames": 20}
    frame.click("#tumble-play")
    frame.wait_for_function("tumbleViewer.state().frame >= 5", timeout=HANG_MS)
    assert frame.evaluate("document.querySelectorAll('.js-plotly-plot').length") >= 2
    assert page.evaluate("typeof window.tumbleViewer") == "undefined"  # nothing leaks into the notebook
    assert watched.errors == [] and watched.outside == []


def test_show_needs_the_body_that_was_simulated(run):
    body, traj = run
    with pytest.raises(TypeError):
        show(traj)  # a trajectory does not hold the parts the page draws
    with pytest.raises(ValueError, match=r"body = .* must be the tumble Body that was simulated"):
        show(traj, None)
    with pytest.raises(ValueError, match=r"is not the body of this trajectory: its principal moments"):
        show(traj, tumble.iss_t_handle())
    with pytest.raises(ValueError, match=r"trajectory = .* must be a tumble Trajectory"):
        show(body, body)
    with pytest.raises(ValueError, match=r"height = 0 must be a whole number of pixels > 0"):
        show(traj, body, height=0)


def test_show_without_ipython_says_which_extra(run, monkeypatch):
    for name in [m for m in sys.modules if m == "IPython" or m.startswith("IPython.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "IPython", None)  # import IPython now raises ImportError
    with pytest.raises(ImportError, match=r"needs IPython: pip install 'tumble\[notebook\]'"):
        show(*reversed(run))


# The notebooks ----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def kernel_name(tmp_path_factory):
    """A kernelspec that starts ipykernel with this interpreter, found through JUPYTER_PATH."""
    mp = pytest.MonkeyPatch()
    root = tmp_path_factory.mktemp("jupyter")
    name = "tumble-test"
    spec = root / "kernels" / name
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": f"tumble tests ({sys.executable})", "language": "python",
    }))
    mp.setenv("JUPYTER_PATH", str(root))
    yield name
    mp.undo()


def outputs_of(nb) -> list[dict]:
    return [out for cell in nb.cells if cell.cell_type == "code" for out in cell.get("outputs", [])]


def test_notebooks_are_found():
    assert [p.name for p in NOTEBOOKS] == ["tennis_racket.ipynb"]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_is_committed_without_outputs(path):
    nbformat = pytest.importorskip("nbformat")
    nb = nbformat.read(path, as_version=4)
    nbformat.validate(nb)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code and all(not c.outputs and c.execution_count is None for c in code)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, kernel_name, tmp_path):
    nbformat = pytest.importorskip("nbformat")
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, kernel_name=kernel_name, timeout=HANG_S, resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = outputs_of(nb)
    assert not [o for o in outputs if o.output_type == "error"]
    rich = [o.data for o in outputs if o.output_type in ("display_data", "execute_result")]
    htmls = [d["text/html"] for d in rich if "text/html" in d]
    if path.stem == "tennis_racket":
        assert any("<table" in h and "Body T-handle: 2 parts" in h and "I2 (intermediate)" in h for h in htmls)  # the body's table
        assert any("Trajectory: T-handle" in h and "<svg" in h for h in htmls)  # a run's summary
        assert sum("image/png" in d for d in rich) >= 3  # the figures
        # the flip against the closed form, as printed: the run's flips every 2 K / p (Landau & Lifshitz sec. 37)
        printed = "".join(o.text for o in outputs if o.output_type == "stream" and o.name == "stdout")
        numbers = {m[0]: float(m[1]) for m in re.findall(r"^([a-z ]+?):\s+([0-9.]+) s$", printed, flags=re.M)}
        assert numbers["measured time between flips"] == pytest.approx(numbers["closed form"], abs=2e-4)
        pages = [f for h in htmls for f in frames_of(h).iframes]
        assert len(pages) == 1 and pages[0]["srcdoc"].count(PLOTLY_BUNDLE) == 1  # the page


def test_kernel_is_this_interpreter(kernel_name, tmp_path):
    nbformat = pytest.importorskip("nbformat")
    from nbclient import NotebookClient

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("import sys; print(sys.executable)")])
    NotebookClient(nb, kernel_name=kernel_name, timeout=HANG_S, resources={"metadata": {"path": str(tmp_path)}}).execute()
    assert nb.cells[0].outputs[0].text.strip() == sys.executable
