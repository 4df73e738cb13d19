"""The README's and the docs' Python examples run as written and do what their comments say
(:mod:`snippets`: ``# no flip``, ``# [0.125, 0.3125, 0.4375]``, ``# 11 flips`` are checked)."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest
from snippets import python_blocks, run_checked

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
#: The README's former body: everything tumble does, with code (a page of the site).
TOUR = ROOT / "docs" / "tour.md"
#: Guides whose examples are run here (docs/architecture.md's has its own test; the gallery's
#: pages are written by their tests).
GUIDES = ("docs/index.md", "docs/gravity-gradient.md", "docs/fitting.md", "docs/control.md", "docs/estimation.md",
          "docs/methods.md")
#: Claims a guide's comments make that must have been checked.
GUIDE_CLAIMS = {"docs/methods.md": ("rk8 (auto)", "~2e-13", "rk4", "~1e-9", "11 flips", "exact (auto)"),
                "docs/control.md": ("274.0", "325.0", "~0.07", "~1e-16", "151.1", "~1e-15", "~1e-8",
                                    "['attitude_error.png', 'rates.png', 'wheels.png', 'dipole.png', 'momentum.png']",
                                    "ControlledRun(601 samples over 600 s, rate 20 -> 0.000163 deg/s, 3 wheels up to 213 rad/s, ...)",
                                    "2.0", "[0.0, 0.0, 160.0]"),
                "docs/fitting.md": ("'12 flights found, 12 used (green), 0 skipped (grey)'",
                                    "RecordingFit(12 of 12 flights, I1/I3 = 0.06495 +- 0.004, I2/I3 = 0.9419 +- 0.0038, "
                                    "chi2/dof 2.3, ...)")}


def test_readme_python_blocks_run_and_hold_their_comments(monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = python_blocks(README.read_text(encoding="utf-8"))
    assert blocks
    checked = [claim for block in blocks for claim in run_checked(block, str(README))]
    for claim in ("[0.125, 0.3125, 0.4375]", "(500, 3)", "11 flips", "one every 1.786 s", "1.7864", "no flip",
                  "StabilityReport(axis 2 (intermediate): unstable, 11 flips, one every 1.786 s)"):
        assert claim in checked, (claim, checked)


def test_tour_python_blocks_run_and_hold_their_comments(monkeypatch):
    monkeypatch.chdir(ROOT)  # paths such as examples/data/... are relative to the repository
    blocks = python_blocks(TOUR.read_text(encoding="utf-8"))
    assert blocks
    checked = [claim for block in blocks for claim in run_checked(block, str(TOUR))]
    # the checker is not vacuous: the tour's claims about values and runs were all seen
    for claim in ("3.0", "[0, 0, 0.25]", "diag(0.3125, 0.4375, 0.125)", "[0.125, 0.3125, 0.4375]", "[1, 0, 0]",
                  "(500, 3)", "~1e-16", "11 flips", "one every 1.786 s", "1.7864", "no flip", "~0",
                  "['every_part_spin', 'explorer1']", "'dop853'", "rk8 (auto)",
                  "StabilityReport(axis 2 (intermediate): unstable, 11 flips, one every 1.786 s)"):
        assert claim in checked, (claim, checked)


@pytest.mark.parametrize("page", GUIDES)
def test_guide_python_blocks_run_and_hold_their_comments(page, monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = python_blocks((ROOT / page).read_text(encoding="utf-8"))
    assert blocks
    checked = [claim for block in blocks for claim in run_checked(block, page)]
    for claim in GUIDE_CLAIMS.get(page, ()):  # the checker is not vacuous where a page states values
        assert claim in checked, (claim, checked)


# the README's reaction wheel as it was (0.05 kg at 1000 rad/s: h = 0.25 kg m^2/s, below
# (I3 - I2) W): it flips 17 times, which its comment denied
OLD_WHEEL = """\
import tumble
wheel = tumble.Rotor(mass=0.05, radius=0.1, length=0.01, axis=(1, 0, 0), center=(0, 0, 0.5), spin_rate=1e3)
body = tumble.Body([*tumble.t_handle().parts, wheel])
traj = tumble.simulate(body, [0.1, 10, 0.1], t_end=20.0)          # dop853; no flip
"""


@pytest.mark.parametrize("code, message", [
    (OLD_WHEEL, "says 'no flip', the run flips 17 times"),
    ("import tumble\ntumble.t_handle().principal_moments   # [0.125, 0.3125, 0.4376]\n", "the value is"),
    ("import numpy as np\nnp.zeros((500, 3))   # (500, 2) rad/s\n", "the value is"),
    (("import tumble\ntumble.stability_report(tumble.simulate(tumble.t_handle(), [0.1, 10, 0.1], t_end=20.0))"
      "   # -> 3 flips\n"), "says '3 flips'"),
    ("x = 2e-15\nx   # ~1e-16\n", "the value is"),
    ("import tumble\ntumble.simulate(tumble.t_handle(), [0.1, 10, 0.1], t_end=20.0)   # dop853; 11 flips\n",
     "says 'dop853', the run's method is 'exact \\(auto\\)'"),
    ("import tumble\nprint(tumble.t_handle())   # Body('T-handle', 3 parts, ...)\n", "the repr is"),
    ("import tumble\ntumble.t_handle().properties   # MassProperties(m = 3 kg)\n", "the repr is"),
])
def test_a_comment_that_does_not_hold_fails(code, message):
    with pytest.raises(AssertionError, match=message):
        run_checked(code, "snippet")


def test_prose_comments_are_not_claims():
    assert run_checked("x = (1.0, 2.0)\nx   # totals, J\n# copy(...)   # -> the files written\n", "snippet") == []


def _commands_out():
    """(page, --out path) of every ``tumble`` command shown on the README and the guides."""
    pages = [README, *sorted((ROOT / "docs").glob("*.md"))]
    for page in pages:
        for line in page.read_text(encoding="utf-8").splitlines():
            match = re.match(r"\s*(?:\.venv/bin/)?tumble .*?--out (\S+)", line)
            if match:
                yield page.relative_to(ROOT), match.group(1).strip("`")


def test_the_commands_shown_write_where_git_does_not_look():
    """Trying the README's commands in a checkout leaves it clean: every --out is git-ignored (a
    folder or a file at the top), and no tracked file is ignored."""
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    outs = sorted(set(_commands_out()))
    assert len(outs) > 10 and any(out == "figures" for _, out in outs)
    for page, out in outs:
        if out.isupper() or out.startswith(("/", "$", '"')):  # placeholders, /tmp, a user's own files
            continue
        ignored = [subprocess.run(["git", "check-ignore", "-q", probe], cwd=ROOT, check=False).returncode == 0
                   for probe in (out, f"{out}/probe")]
        assert any(ignored), f"{page}: --out {out} writes into the repository where git would see it"
    tracked = subprocess.run(["git", "ls-files", "-ci", "--exclude-standard"], cwd=ROOT, check=True,
                             capture_output=True, text=True).stdout
    assert tracked == "", f"tracked files that .gitignore ignores: {tracked}"


def test_a_shown_repr_of_a_report_is_its_repr():
    """A stability report's comment that shows its repr is held to it, beside its flips and period."""
    code = ("import tumble\ntumble.stability_report(tumble.simulate(tumble.t_handle(), [0.1, 10, 0.1], t_end=20.0))"
            "   # StabilityReport(axis 2 (intermediate): unstable, 11 flips, one every 1.786 s)\n")
    assert run_checked(code, "snippet") == ["11 flips", "one every 1.786 s", "unstable", "axis 2",
                                            "StabilityReport(axis 2 (intermediate): unstable, 11 flips, one every 1.786 s)"]
    with pytest.raises(AssertionError, match="the repr is"):
        run_checked(code.replace("(intermediate)", "(minor)"), "snippet")


def test_every_scenario_a_guide_shows_runs_as_copied(tmp_path, capsys):
    """A ```toml block with an [initial] table is a scenario file a reader saves and runs: the tour's
    paired method = "exact" with a [torque], and `tumble simulate` refused it (a walkthrough, issue 40)."""
    from tumble.cli import main

    shown = [(page.name, block) for page in sorted((ROOT / "docs").glob("*.md"))
             for block in re.findall(r"```toml\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.DOTALL)
             if "[initial]" in block]
    assert shown
    for k, (page, block) in enumerate(shown):
        path = tmp_path / f"scenario_{k}.toml"
        path.write_text(block, encoding="utf-8")
        assert main(["simulate", str(path), "--out", str(tmp_path / f"run_{k}")]) == 0, (page, capsys.readouterr().err)
