"""Screenshots of the interactive page (docs/page.md, README): ground frame playing, the body-frame
view, and live mode after a run in the browser.

    .venv/bin/python docs/figures/make_page_screenshots.py

Needs Chromium (as tests/test_page.py: /usr/bin/chromium or TUMBLE_CHROMIUM) and playwright.
Writes docs/figures/page-ground.png, page-body.png and (when live mode is installed)
page-live.png, each reduced to a 256-colour palette to stay small.
"""

from __future__ import annotations

import io
import os
import sys
import tempfile
from pathlib import Path

from PIL import Image
from playwright.sync_api import sync_playwright

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))

from test_page import FLAGS  # noqa: E402  (the flags headless Chromium needs here)

from tumble.cli import main  # noqa: E402

OUT = ROOT / "docs" / "figures"


def save(png: bytes, name: str) -> None:
    image = Image.open(io.BytesIO(png)).convert("RGB").quantize(256, method=Image.Quantize.MEDIANCUT)
    image.save(OUT / name, optimize=True)
    print(f"wrote docs/figures/{name} ({(OUT / name).stat().st_size // 1000} kB)")


def main_() -> None:
    with tempfile.TemporaryDirectory(prefix="tumble-page-") as tmp:
        page_path = Path(tmp) / "flip.html"
        if main(["view", str(ROOT / "examples" / "seed_flip.toml"), "--out", str(page_path)]) != 0:
            raise SystemExit("tumble view failed")
        chromium = os.environ.get("TUMBLE_CHROMIUM", "/usr/bin/chromium")
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=chromium, headless=True, args=FLAGS)
            page = browser.new_page(viewport={"width": 1280, "height": 1000})
            page.goto(page_path.as_uri())
            page.wait_for_function("window.tumbleViewer && window.tumbleViewer.ready", timeout=60_000)
            page.click("#tumble-play")
            page.wait_for_function("tumbleViewer.state().frame >= 14", timeout=60_000)
            page.click("#tumble-play")  # pause, so that both pictures show the same moment
            save(page.screenshot(full_page=True), "page-ground.png")
            save(page.locator("#tumble-body").screenshot(), "page-body.png")
            if page.locator("#tumble-live-run").count():
                page.select_option("#tumble-live-preset", index=5)  # the tennis racket: a flat box
                page.click("#tumble-live-run")
                page.wait_for_function("window.tumbleLive.drawn >= 1", timeout=60_000)
                page.click("#tumble-play")
                page.wait_for_function("tumbleViewer.state().frame >= 40", timeout=60_000)
                page.click("#tumble-play")
                save(page.screenshot(full_page=True), "page-live.png")
            browser.close()


if __name__ == "__main__":
    main_()
