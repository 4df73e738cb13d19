"""Build tumble's wheel from a copy of the working tree (so the build leaves no trace in it).

Used by tests/test_packaging.py (the wheel's contents) and tests/test_wheel_commands.py (the
wheel installed in a fresh virtualenv). The build runs ``pip wheel --no-deps --no-build-isolation``:
setuptools comes from the test extra, nothing is downloaded.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path
from limits import HANG_S

ROOT = Path(__file__).resolve().parents[1]


def build_wheel(tree: Path, out: Path) -> Path:
    """Copy what the build reads into ``tree``, build the wheel into ``out``; its path."""
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, tree / name)
    shutil.copytree(ROOT / "src", tree / "src", ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    proc = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(tree), "--no-deps", "--no-build-isolation", "-q", "-w", str(out)],
        capture_output=True, text=True, timeout=HANG_S,
    )
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    (path,) = out.glob("tumble-*.whl")
    return path
