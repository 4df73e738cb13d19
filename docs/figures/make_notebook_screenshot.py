"""Make docs/figures/notebook.png: the key cells of the executed example notebook, as Jupyter shows them.

Runs examples/notebooks/tennis_racket.ipynb with nbclient (in a kernel of this interpreter),
writes the chosen cells -- their code and their outputs, the notebook's own HTML, PNG and text --
into a plain page, and photographs it with headless Chromium (playwright, the flags of
tests/test_page.py), after the embedded page's plotly figure has drawn. The picture is reduced to
a palette of 256 colours to stay small.

    .venv/bin/python docs/figures/make_notebook_screenshot.py [--out docs/figures/notebook.png]
"""

from __future__ import annotations

import argparse
import html
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOK = ROOT / "examples" / "notebooks" / "tennis_racket.ipynb"
#: The code cells shown, by the start of their source: the body's table, a run, the page.
SHOWN = ("body = tumble.t_handle()", "runs = {}", "tumble.viz.show(")
FLAGS = ["--no-sandbox", "--disable-gpu", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--disable-component-update", "--no-first-run", "--disable-sync",
         "--disable-quic"]
STYLE = """
body { font-family: sans-serif; max-width: 1040px; margin: 16px auto; color: #222; }
.cell { margin: 10px 0 18px; }
.in { background: #f5f5f5; border: 1px solid #e0e0e0; padding: 6px 10px; font: 13px monospace; white-space: pre; }
.prompt { color: #303f9f; font: 12px monospace; margin: 2px 0; }
.out { padding: 4px 10px; font-size: 13px; }
.out pre { margin: 0; }
h1 { font-size: 22px; margin: 4px 0; }
/* tables as JupyterLab draws them */
.out table { border-collapse: collapse; border: none; font-size: 12px; }
.out td, .out th { padding: 0.3em 0.8em 0.3em 0.3em; }
.out tbody tr:nth-child(odd) { background: #f5f5f5; }
.out caption { padding: 0.4em 0; }
"""


def execute(path: Path, workdir: Path):
    """The notebook, executed in a kernel of this interpreter (a kernelspec of our own)."""
    spec = workdir / "jupyter" / "kernels" / "tumble"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "tumble", "language": "python"}))
    os.environ["JUPYTER_PATH"] = str(workdir / "jupyter")
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, kernel_name="tumble", timeout=300, resources={"metadata": {"path": str(workdir)}}).execute()
    return nb


def render_output(out) -> str:
    if out.output_type == "stream":
        return f"<pre>{html.escape(out.text)}</pre>"
    if out.output_type == "error":
        raise RuntimeError(f"the notebook failed: {out.ename}: {out.evalue}")
    data = out.get("data", {})
    if "text/html" in data:
        return data["text/html"]
    if "image/png" in data:
        return f'<img src="data:image/png;base64,{data["image/png"].strip()}" style="max-width:100%">'
    return f"<pre>{html.escape(data.get('text/plain', ''))}</pre>"


def page(nb) -> str:
    title = next(c.source.splitlines()[0].lstrip("# ") for c in nb.cells if c.cell_type == "markdown")
    parts = [f"<!doctype html><html><head><meta charset='utf-8'><style>{STYLE}</style></head><body>",
             f"<h1>{html.escape(title)}</h1>"]
    for cell in nb.cells:
        if cell.cell_type != "code" or not cell.source.startswith(SHOWN):
            continue
        n = cell.execution_count
        parts.append(f"<div class='cell'><div class='prompt'>In [{n}]:</div><div class='in'>{html.escape(cell.source)}</div>")
        parts += [f"<div class='prompt'>Out[{n}]:</div><div class='out'>{render_output(o)}</div>" for o in cell.outputs]
        parts.append("</div>")
    return "".join(parts + ["</body></html>"])


def screenshot(page_file: Path, out: Path, browser: str) -> None:
    from PIL import Image
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=browser, headless=True, args=FLAGS)
        try:
            tab = chromium.new_page(viewport={"width": 1080, "height": 900})
            tab.goto(page_file.as_uri())
            # the whole page in the viewport: the embedded page's WebGL scenes draw only when on screen
            tab.set_viewport_size({"width": 1080, "height": tab.evaluate("document.documentElement.scrollHeight")})
            frame = tab.frame_locator("iframe")
            frame.locator(".js-plotly-plot").first.wait_for(timeout=60_000)
            tab.wait_for_timeout(6000)  # software WebGL finishes drawing the shaded 3-D scenes
            raw = page_file.with_suffix(".png")
            tab.screenshot(path=str(raw), full_page=True)
        finally:
            chromium.close()
    Image.open(raw).convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(out, optimize=True)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "figures" / "notebook.png")
    args = parser.parse_args(argv)
    browser = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    if browser is None:
        print("make_notebook_screenshot: no Chromium on PATH (apt-get install chromium)", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory(prefix="tumble-notebook-") as tmp:
        tmp = Path(tmp)
        nb = execute(NOTEBOOK, tmp)
        page_file = tmp / "notebook.html"
        page_file.write_text(page(nb), encoding="utf-8")
        screenshot(page_file, args.out, browser)
    print(f"wrote {args.out} ({args.out.stat().st_size / 1024:.0f} kB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
