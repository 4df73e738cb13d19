"""What the scripts that make the docs' figures share: ``--out DIR`` (default docs/figures), the
figure written there as PNG, and one line naming it (tests run them and read that line)."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from tumble.viz import save_figure

ROOT = Path(__file__).resolve().parents[2]


def write(figure, out: Path, name: str) -> Path:
    """Save ``figure`` as ``out/name`` (the folder made if needed); returns the path."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / name
    save_figure(figure, path)
    return path


def main(make: Callable[[Path], Path], doc: str) -> None:
    """The command line of a figure script: ``make(--out)``, then ``wrote PATH``."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "figures", help="folder (default docs/figures)")
    print(f"wrote {make(parser.parse_args().out)}")
