"""What a ``pip install`` user gets: the wheel's contents, the citation, the public namespace."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import tumble

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> zipfile.ZipFile:
    """The wheel built from a copy of the working tree (so the build leaves no trace in it)."""
    tree = tmp_path_factory.mktemp("tree")
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, tree / name)
    shutil.copytree(ROOT / "src", tree / "src", ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    out = tmp_path_factory.mktemp("wheel")
    proc = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(tree), "--no-deps", "--no-build-isolation", "-q", "-w", str(out)],
        capture_output=True, text=True, timeout=300,
    )
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    (path,) = out.glob("tumble-*.whl")
    with zipfile.ZipFile(path) as zf:
        yield zf


def test_wheel_ships_py_typed_and_the_license(wheel):
    names = set(wheel.namelist())
    assert "tumble/py.typed" in names
    (license_file,) = [n for n in names if re.fullmatch(r"tumble-[^/]+\.dist-info/licenses/LICENSE", n)]
    assert "MIT License" in wheel.read(license_file).decode()
    (metadata,) = [n for n in names if n.endswith(".dist-info/METADATA")]
    text = wheel.read(metadata).decode()
    assert re.search(r"^License-Expression: MIT$", text, flags=re.M)
    assert re.search(rf"^Version: {re.escape(tumble.__version__)}$", text, flags=re.M)


def test_license_is_mit_for_the_tumble_authors():
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License\n")
    assert "Copyright (c) 2026 the tumble authors" in text


def test_citation_names_this_version():
    text = (ROOT / "CITATION.cff").read_text()
    assert re.search(r"^cff-version: 1\.2\.0$", text, flags=re.M)
    (version,) = re.findall(r"^version:\s*['\"]?([^'\"\s]+)['\"]?\s*$", text, flags=re.M)
    assert version == tumble.__version__
    for key in ("title", "authors", "license", "abstract", "message"):
        assert re.search(rf"^{key}:", text, flags=re.M), key
    assert re.search(r"^license: MIT$", text, flags=re.M)
    assert re.search(r"^  - name: \"The tumble authors\"$", text, flags=re.M)


def test_changelog_has_an_unreleased_section_and_this_version():
    text = (ROOT / "CHANGELOG.md").read_text()
    assert "## [Unreleased]" in text
    assert f"## [{tumble.__version__}]" in text


def test_dir_lists_only_public_and_dunder_names():
    names = dir(tumble)
    private = [n for n in names if n.startswith("_") and not (n.startswith("__") and n.endswith("__"))]
    assert private == []
    assert "annotations" not in names and "importlib" not in names
    public = {n for n in names if not n.startswith("_")}
    submodules = {n for n in public if type(getattr(tumble, n)) is type(sys)}
    assert public - submodules == set(tumble.__all__) - {"__version__"}


def test_dir_and_import_stay_lazy():
    code = ("import sys, tumble; names = dir(tumble); "
            "print(sorted(m for m in ('numpy', 'scipy', 'matplotlib') if m in sys.modules), 'Body' in names)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.stdout.split() == ["[]", "True"], proc.stderr
