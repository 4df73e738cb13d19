"""What a ``pip install`` user gets: the wheel's contents, the citation, the public namespace."""

from __future__ import annotations

import dataclasses
import email
import os
import re
import shutil
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest
from wheelbuild import build_wheel

import tumble
from tumble.commands import run_scenario
from tumble.io.examples import copy_examples, list_examples
from limits import HANG_S

ROOT = Path(__file__).resolve().parents[1]
PACKAGED = ROOT / "src" / "tumble" / "examples"


def _tree(folder: Path) -> dict[str, bytes]:
    """Every file below ``folder``: relative path -> content."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> zipfile.ZipFile:
    """The wheel built from a copy of the working tree (so the build leaves no trace in it)."""
    path = build_wheel(tmp_path_factory.mktemp("tree"), tmp_path_factory.mktemp("wheel"))
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


# --- what an index shows: metadata, the long description, the citation --------------------------

#: A link or image whose target has no scheme (``docs/tour.md``, ``#install``): it resolves in a
#: checkout and breaks on an index, which shows README.md alone.
_RELATIVE = re.compile(r"\]\((?![a-z][a-z0-9+.-]*:)([^)\s]*)[^)]*\)|(?:src|href)=[\"'](?![a-z][a-z0-9+.-]*:)([^\"']*)", re.I)


def _relative_links(markdown: str) -> list[str]:
    return [a or b for a, b in _RELATIVE.findall(markdown)]


def test_the_link_check_sees_relative_links():
    assert _relative_links("[tour](docs/tour.md), ![f](figures/a.png), <img src='x.png'>, [i](#install)") == [
        "docs/tour.md", "figures/a.png", "x.png", "#install"]
    assert _relative_links("[site](https://example.org/tumble) and `docs/tour.md` and [x][ref]") == []


def test_readme_links_nothing_relative():
    """README.md is the long description (pyproject ``readme``): an index shows it without the files."""
    assert _relative_links((ROOT / "README.md").read_text(encoding="utf-8")) == []


def test_pyproject_names_the_authors_the_citation_and_license_name():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert project["readme"] == "README.md" and project["license"] == "MIT"
    assert project["authors"] == [{"name": "The tumble authors"}]
    classifiers = project["classifiers"]
    assert classifiers == sorted(classifiers) and len(set(classifiers)) == len(classifiers)
    assert all(re.fullmatch(r"[A-Z][^:]*( :: [^:]+)+", c) for c in classifiers), classifiers
    assert not [c for c in classifiers if c.startswith("License ::")]  # PEP 639: the expression says it
    floor = re.fullmatch(r">=(3\.\d+)", project["requires-python"]).group(1)
    assert f"Programming Language :: Python :: {floor}" in classifiers
    assert "Typing :: Typed" in classifiers and (ROOT / "src" / "tumble" / "py.typed").is_file()


def test_citation_date_is_this_versions_release_date():
    citation = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    (date,) = re.findall(r"^date-released:\s*['\"]?(\d{4}-\d{2}-\d{2})['\"]?\s*$", citation, flags=re.M)
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert f"## [{tumble.__version__}] - {date}" in changelog


def test_wheel_metadata_carries_classifiers_authors_keywords_and_the_readme(wheel):
    (metadata,) = [n for n in wheel.namelist() if n.endswith(".dist-info/METADATA")]
    message = email.message_from_bytes(wheel.read(metadata))
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert message.get_all("Classifier") == project["classifiers"]
    assert message["Author"] == "The tumble authors"
    assert message["Keywords"].split(",") == project["keywords"]
    assert message["Requires-Python"] == project["requires-python"]
    assert message["Description-Content-Type"] == "text/markdown"
    description = message.get_payload()
    assert description.strip() == (ROOT / "README.md").read_text(encoding="utf-8").strip()
    assert _relative_links(description) == []


def test_dir_lists_only_public_and_dunder_names():
    names = dir(tumble)
    private = [n for n in names if n.startswith("_") and not (n.startswith("__") and n.endswith("__"))]
    assert private == []
    assert "annotations" not in names and "importlib" not in names
    public = {n for n in names if not n.startswith("_")}
    submodules = {n for n in public if isinstance(getattr(tumble, n), type(sys))}
    assert public - submodules == set(tumble.__all__) - {"__version__"}


def test_the_subpackages_are_attributes_after_import_tumble():
    """``import tumble`` then ``tumble.viz.figure_omega(run)``, as numpy's and scipy's subpackages
    are used: it said "module 'tumble' has no attribute 'viz'" (and 'io', which an error message
    names); each is imported on first use, and only then."""
    code = ("import sys, tumble; before = 'tumble.viz' in sys.modules; f = tumble.viz.figure_omega; "
            "r = tumble.io.gyrodata.read_recording; print(before, f.__module__, r.__name__, "
            "all(n in dir(tumble) for n in ('mass', 'dynamics', 'analysis', 'ensemble', 'io', 'viz')))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=HANG_S)
    assert proc.stdout.split() == ["False", "tumble.viz.plots", "read_recording", "True"], proc.stderr


def test_dir_and_import_stay_lazy():
    code = ("import sys, tumble; names = dir(tumble); "
            "print(sorted(m for m in ('numpy', 'scipy', 'matplotlib') if m in sys.modules), 'Body' in names)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=HANG_S)
    assert proc.stdout.split() == ["[]", "True"], proc.stderr


# --- the examples ship in the package ----------------------------------------------------------

def test_wheel_ships_every_example(wheel):
    shipped = {n[len("tumble/examples/"):]: wheel.read(n) for n in wheel.namelist() if n.startswith("tumble/examples/")}
    assert shipped == _tree(PACKAGED)
    assert {"seed_flip.toml", "bodies/t_handle.toml", "bodies/meshes/torus.stl"} <= set(shipped)
    assert not [n for n in wheel.namelist() if n.startswith("tumble/examples/") and n.endswith(".py")]


def test_repository_examples_is_a_relative_link_to_the_packaged_ones():
    link = ROOT / "examples"
    assert link.is_symlink() and os.readlink(link) == "src/tumble/examples"
    assert link.resolve() == PACKAGED.resolve()
    if (ROOT / ".git").exists():
        proc = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-s", "examples"], capture_output=True, text=True)
        assert proc.stdout.startswith("120000 "), proc.stdout  # git keeps the link, not a copy


def test_list_examples_names_every_file_it_copies_with_its_description():
    """``tumble examples`` lists everything ``--copy`` copies (issue 28 item 3): the TOML files by
    their first comment line, the mesh by the body file that names it, the recordings by their
    first sentence, the notebook by its title."""
    examples = list_examples()
    by_path = {e.path: e for e in examples}
    assert set(by_path) == set(_tree(PACKAGED)) and len(by_path) == len(examples)
    kinds = {"bodies": "body", "sweeps": "sweep", "control": "control", "devices": "device", "bodies/meshes": "mesh", "data": "data",
             "throws": "throw", "notebooks": "notebook"}
    for e in examples:
        assert e.kind == kinds.get(Path(e.path).parent.as_posix(), "scenario"), e
        assert e.name == Path(e.path).stem
        text = (PACKAGED / e.path).read_text(encoding="utf-8", errors="replace")
        if e.path.endswith(".toml"):
            assert text.splitlines()[0] == f"# {e.description}"
            # a whole clause, not a line cut mid-sentence (nadir.toml's ended "points its long (minor) axis at nadir")
            assert e.description.endswith((".", ":", ")")), e.path
    assert by_path["bodies/meshes/torus.stl"].description == "A triangle mesh (STL) that bodies/every_part.toml names"
    assert 'mesh = "meshes/torus.stl"' in (PACKAGED / "bodies" / "every_part.toml").read_text()
    assert by_path["data/racquet_tosses.csv"].description == (
        "SYNTHETIC phone recording of 12 hand tosses of a tennis racquet about its intermediate axis: not a measurement.")
    assert by_path["notebooks/tennis_racket.ipynb"].description == "The tennis-racket effect with tumble"
    assert by_path["throws/a1.csv"].description == (
        "SYNTHETIC throw of the example device alone, thrown gently (3-8 rad/s): not a measurement.")
    assert [e.kind for e in examples][: sum(e.kind == "scenario" for e in examples)] == ["scenario"] * sum(
        e.kind == "scenario" for e in examples)  # scenarios first
    assert by_path["seed_flip.toml"].description.startswith("The seed's first run")


def test_list_examples_falls_back_to_the_name(monkeypatch, tmp_path):
    from tumble.io import examples as module

    for folder in ("bodies/meshes", "data", "notebooks", "extra"):
        (tmp_path / folder).mkdir(parents=True)
    (tmp_path / "no_comment.toml").write_text("body = 't-handle'\n# a comment further down\n")
    (tmp_path / "bodies" / "plain_box.toml").write_text("\n#\n[body]\n")
    (tmp_path / "bodies" / "meshes" / "spare.obj").write_text("v 0 0 0\n")
    (tmp_path / "data" / "bare_log.csv").write_text("t,wx,wy,wz\n0,1,2,3\n")
    (tmp_path / "notebooks" / "untitled.ipynb").write_text('{"cells": [{"cell_type": "code", "source": ["1"]}]}')
    (tmp_path / "extra" / "notes_file.txt").write_text("x")
    monkeypatch.setattr(module, "_root", lambda: tmp_path)
    assert [(e.name, e.kind, e.description) for e in list_examples()] == [
        ("no_comment", "scenario", "no comment"), ("spare", "mesh", "A triangle mesh (OBJ) for a body file"),
        ("plain_box", "body", "plain box"), ("bare_log", "data", "bare log"),
        ("notes_file", "file", "notes file"), ("untitled", "notebook", "untitled")]


def test_copied_examples_run_from_anywhere(tmp_path, monkeypatch):
    dest = tmp_path / "new" / "examples"
    written = copy_examples(dest)
    assert written == sorted(dest / p for p in _tree(PACKAGED))
    assert _tree(dest) == _tree(PACKAGED)
    assert not [p for p in dest.parent.iterdir() if p != dest]  # no temporary folder left
    monkeypatch.chdir(tmp_path)  # relative paths must resolve against the files, not the cwd
    scenarios = [e for e in list_examples() if e.kind == "scenario"]
    assert len(scenarios) >= 5
    for e in scenarios:
        scenario = tumble.load_scenario(dest / e.path)
        traj = run_scenario(dataclasses.replace(scenario, t_end=0.5, samples=20))
        assert traj.omega.shape == (20, 3), e.path
    for e in list_examples():
        if e.kind == "body":
            assert tumble.load_body(dest / e.path).mass > 0, e.path


def test_copy_fills_an_existing_folder_without_overwriting(tmp_path):
    dest = tmp_path / "mine"
    dest.mkdir()
    assert len(copy_examples(dest)) == len(_tree(PACKAGED))
    assert _tree(dest) == _tree(PACKAGED)

    other = tmp_path / "other"
    (other / "bodies").mkdir(parents=True)
    (other / "bodies" / "t_handle.toml").write_text("mine")
    (other / "notes.txt").write_text("keep")
    with pytest.raises(ValueError, match=r"other/bodies/t_handle\.toml: already exists; the examples are never copied over a file: give a new folder"):
        copy_examples(other)
    assert _tree(other) == {"bodies/t_handle.toml": b"mine", "notes.txt": b"keep"}  # nothing written


def test_copy_alone_copies_into_the_folder_the_guides_name(tmp_path, monkeypatch, capsys):
    """The guides say "tumble examples --copy examples" and run examples/...; issue 40 says "after tumble examples
    --copy", which argparse refused ("expected one argument": a walkthrough of docs/control.md, 2026-12-03)."""
    from tumble.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["examples", "--copy"]) == 0
    assert _tree(tmp_path / "examples") == _tree(PACKAGED)
    assert capsys.readouterr().out.startswith(f"copied {len(_tree(PACKAGED))} files to examples/")


def test_copy_refuses_a_file_as_destination(tmp_path):
    target = tmp_path / "a_file"
    target.write_text("x")
    with pytest.raises(ValueError, match=r"a_file: exists and is not a folder"):
        copy_examples(target)


def _make_dry_run(folder: Path, target: str) -> list[str]:
    proc = subprocess.run(["make", "-n", "-C", str(folder), target], capture_output=True, text=True, check=True)
    return [line for line in proc.stdout.splitlines() if not line.startswith("make")]


def test_make_demo_installs_only_what_the_demo_needs(tmp_path):
    """On a fresh clone ``make demo`` installs tumble with its own extras (the video extra), not
    the test, cluster and docs tool chains that ``make test`` adds; after ``make test`` it
    installs nothing more."""
    if shutil.which("make") is None:
        pytest.skip("make is not installed")
    for name in ("Makefile", "pyproject.toml"):
        shutil.copy2(ROOT / name, tmp_path / name)
    extras = {"test", "cluster", "docs"}
    demo = [line for line in _make_dry_run(tmp_path, "demo") if "pip install" in line and "-e" in line]
    assert demo, "make demo installs tumble"
    for line in demo:
        named = set(re.findall(r"\[([^\]]*)\]", line)[0].split(",")) if "[" in line else set()
        assert not named & extras, f"make demo installs {sorted(named & extras)}: {line}"
    assert any("tumble demo" in line for line in _make_dry_run(tmp_path, "demo"))
    test = _make_dry_run(tmp_path, "test")
    assert any("pip install" in line and all(e in line for e in extras) for line in test)
    assert any("pytest" in line for line in test)
    # what make test would do, done: its stamps; make demo then only runs the demo
    stamps = [word for line in test if line.startswith("touch ") for word in line.split()[1:]]
    for stamp in stamps:
        (tmp_path / stamp).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / stamp).touch()
    assert _make_dry_run(tmp_path, "demo") == [".venv/bin/tumble demo"]


@pytest.mark.parametrize("failing", [None, "lint-imports", "mypy", "pytest"])
def test_make_test_fails_when_the_suite_or_a_static_check_fails(tmp_path, failing):
    """``make test`` runs the import contracts and mypy beside the suite: it exits 0 only where
    all three pass, prints the checks' output after the suite's, and names the checks where they
    failed (the tools stood in for by scripts that pass or fail, the set-up up to date)."""
    if shutil.which("make") is None:
        pytest.skip("make is not installed")
    for name in ("Makefile", "pyproject.toml"):
        shutil.copy2(ROOT / name, tmp_path / name)
    bin_ = tmp_path / ".venv" / "bin"
    bin_.mkdir(parents=True)
    for tool in ("lint-imports", "mypy", "python"):
        name = "pytest" if tool == "python" else tool
        (bin_ / tool).write_text(f"#!/bin/sh\necho {name} ran\nexit {int(name == failing)}\n", encoding="utf-8")
        (bin_ / tool).chmod(0o755)
    for stamp in (".tumble-demo", ".tumble-docs", ".tumble-test"):
        (tmp_path / ".venv" / stamp).touch()
    proc = subprocess.run(["make", "-s", "-C", str(tmp_path), "test"], capture_output=True, text=True, timeout=HANG_S)
    assert (proc.returncode == 0) == (failing is None), proc.stdout + proc.stderr
    ran = [line for line in proc.stdout.splitlines() if line.endswith(" ran")]
    assert ran[0] == "pytest ran" and set(ran) == {"pytest ran", "lint-imports ran"} | (
        set() if failing == "lint-imports" else {"mypy ran"})
    assert ("the import contracts or mypy failed" in proc.stderr) == (failing in ("lint-imports", "mypy"))


def test_make_docs_installs_only_the_docs_extra(tmp_path):
    """``make docs`` on a fresh clone installs tumble with the docs extra alone (issue 28 item 5):
    Sphinx and its extensions and the extras the gallery runs, not the test tool chain; after
    ``make test`` (whose set-up holds the docs extra) it only builds."""
    if shutil.which("make") is None:
        pytest.skip("make is not installed")
    for name in ("Makefile", "pyproject.toml"):
        shutil.copy2(ROOT / name, tmp_path / name)
    docs = _make_dry_run(tmp_path, "docs")
    installs = [line for line in docs if "pip install" in line and "-e" in line]
    assert len(installs) == 1 and re.findall(r"\[([^\]]*)\]", installs[0]) == ["docs"], installs
    assert any(line.startswith(".venv/bin/sphinx-build -W ") for line in docs)
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]
    names = {re.match(r"[A-Za-z0-9_.-]+", r).group(0).lower() for r in extras["docs"]}
    assert {"sphinx", "pydata-sphinx-theme", "numpydoc", "myst-parser", "sphinx-gallery"} <= names
    assert not names & {"pytest", "hypothesis", "playwright", "mypy", "import-linter", "pytest-xdist"}
    # what the gallery's scripts import beyond tumble's own dependencies comes with it
    assert "tumble[mesh,cluster,notebook]" in extras["docs"]
    gallery = " ".join(p.read_text(encoding="utf-8") for p in (ROOT / "gallery").glob("plot_*.py"))
    assert "tumble.Mesh(" in gallery and "DaskBackend(" in gallery
    test = _make_dry_run(tmp_path, "test")
    for stamp in (word for line in test if line.startswith("touch ") for word in line.split()[1:]):
        (tmp_path / stamp).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / stamp).touch()
    assert [line for line in _make_dry_run(tmp_path, "docs") if "pip" in line] == []


@pytest.mark.parametrize("command", [["fit", "examples/data/racquet_tosses.csv", "--out", "fitted"],
                                     ["simulate", "examples/seed_flip.toml", "--out", "run"],
                                     ["inertia", "examples/bodies/wing_nut.toml"]])
def test_an_example_path_outside_a_checkout_says_how_to_get_it(tmp_path, monkeypatch, capsys, command):
    """From a wheel (no examples/ folder here), the commands the README and --help show stop with
    one line that says how to get the example (issue 28 item 3); a path that is no example does not."""
    from tumble.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(command) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no such file" in err
    assert err.rstrip().endswith("'tumble examples --copy examples' copies them here")
    assert main([command[0], "examples/not_an_example.toml", *command[2:]]) == 2
    assert "tumble examples --copy" not in capsys.readouterr().err


@pytest.mark.parametrize("read, path", [
    ("tumble.io.gyrodata.read_recording", "examples/data/racquet_tosses.csv"),
    ("tumble.load_scenario", "examples/seed_flip.toml"),
    ("tumble.load_body", "examples/bodies/t_handle.toml"),
    ("tumble.io.sweepfile.load_sweep", "examples/sweeps/t_handle_dimensions.toml"),
    ("tumble.io.throwfile.read_throw", "examples/throws/a1.csv"),
])
def test_a_python_reader_on_an_example_path_outside_a_checkout_says_how_to_get_it(tmp_path, monkeypatch, read, path):
    """The Python blocks of the guides (``read_recording("examples/data/racquet_tosses.csv")`` in
    docs/fitting.md) say it too, not only the command line; a path that is no example does not."""
    import importlib

    module, _, name = read.rpartition(".")
    reader = getattr(importlib.import_module(module), name)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError) as caught:
        reader(path)
    assert str(caught.value) == (f"{path}: no such file; it is one of tumble's examples: "
                                 "'tumble examples --copy examples' copies them here")
    with pytest.raises(ValueError) as caught:
        reader(path.replace("examples/", "examples/no_"))
    assert str(caught.value).endswith(": no such file")


# --- packages whose names load on first use (tumble._lazy) -------------------------------------

LAZY_PACKAGES = ("tumble.analysis", "tumble.dynamics", "tumble.io", "tumble.viz")


@pytest.mark.parametrize("name", LAZY_PACKAGES)
def test_a_lazy_package_offers_exactly_its_public_names_and_each_resolves(name):
    import importlib

    package = importlib.import_module(name)
    exports = package.__dict__["_exports"]
    assert set(exports) == set(package.__all__)
    for public in package.__all__:
        value = getattr(package, public)
        assert value is getattr(importlib.import_module(exports[public], name), public)
        assert not isinstance(value, type(sys)), public  # a function named as its module stays the function


def test_the_fit_of_a_recording_loads_neither_integrators_nor_controllers_nor_plotting():
    code = ("import sys; import tumble.analysis.fit; "
            "print(sorted(m for m in ('tumble.dynamics.batch', 'tumble.dynamics.control', 'scipy.integrate', "
            "'tumble.io.scenario', 'matplotlib') if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=HANG_S)
    assert proc.stdout.split() == ["[]"], proc.stdout + proc.stderr
