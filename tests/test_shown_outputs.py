"""What the guides show a command printing is what it prints (issue 40, item 2: "a changed output
fails a test, not a reader").

:mod:`shown_commands` reads the lines right after a command in a page's code block as its output;
each such command is run here from an empty folder where the examples are copied, as a reader
would after ``tumble examples --copy examples``, and what it prints is compared word for word
(the page wraps long lines). docs/tensor.md's are run by tests/test_tensor_cli.py, which checks
their results too; tests/test_wheel_commands.py compares them all again with the wheel.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from shown_commands import PAGES, ROOT, page_commands, run_shown_outputs, same_output

from tumble.io.examples import copy_examples

#: Pages whose shown output another test runs (it runs the commands for more checks): the test.
ELSEWHERE = {"docs/tensor.md": "tests/test_tensor_cli.py"}


def _pages_with_output() -> list[str]:
    return sorted({c.where.split(":")[0] for page in PAGES for c in page_commands(page) if c.output})


def test_the_pages_that_show_a_commands_output_are_all_checked():
    pages = _pages_with_output()
    assert {"docs/tour.md", "docs/tensor.md"} <= set(pages)
    for page, test in ELSEWHERE.items():
        assert "shown_commands import" in (ROOT / test).read_text(encoding="utf-8") and page in (
            ROOT / test).read_text(encoding="utf-8"), (page, test)


@pytest.mark.parametrize("page", [p for p in _pages_with_output() if p not in ELSEWHERE])
def test_a_command_prints_what_the_page_shows(page, tmp_path):
    copy_examples(tmp_path / "examples")
    ran = run_shown_outputs(ROOT / page, tmp_path)
    assert ran
    for shown, code, printed in ran:
        assert code == 0, (shown.where, printed)
        assert same_output(shown.output, printed), \
            f"{shown.where}: {shown.shown}\nshown:\n{shown.output}\nprinted:\n{printed}"


def test_a_wrapped_output_is_the_same_and_a_changed_number_is_not():
    printed = "fit x.csv: I1/I3 = 0.0649 +- 0.0045 from 12 of 12 flights, chi2/dof 6.5\n"
    assert same_output("fit x.csv: I1/I3 = 0.0649 +- 0.0045 from 12 of 12\nflights, chi2/dof 6.5", printed)
    assert not same_output("fit x.csv: I1/I3 = 0.0649 +- 0.0045 from 11 of 12\nflights, chi2/dof 6.5", printed)


def test_the_lines_after_a_command_in_its_block_are_its_output(tmp_path):
    page = tmp_path / "probe.md"
    page.write_text("Run\n\n```\ntumble examples\n  one line\ntwo\n\n# a comment\ntumble examples --copy mine\n"
                    "tumble inertia examples/bodies/t_handle.toml\nthree\n```\n\n```bash\nfor f in x; do\n"
                    "  tumble view $f --out $f.html\n  echo done; done\n```\n", encoding="utf-8")
    found = page_commands(page)
    assert [c.output for c in found] == ["  one line\ntwo", "", "three", ""]   # a synopsis ($f) is not run


def test_a_command_that_needs_anothers_output_runs_after_it_and_after_what_that_one_needs():
    """tests/test_wheel_commands.py runs ``tumble view bracket`` after ``tumble tensor ... --out
    bracket``, and that after ``tumble calibrate ... --out calibrated.toml``, as docs/tensor.md shows."""
    from test_wheel_commands import _producers

    calibrate = ("calibrate", "d.toml", "--alone", "a1.csv", "--proof", "p1.csv", "--out", "calibrated.toml")
    tensor = ("tensor", "o1.csv", "--device", "calibrated.toml", "--mass", "0.4", "--out", "bracket")
    view = ("view", "bracket", "--out", "bracket.html")
    outputs = {"calibrated.toml": calibrate, "bracket": tensor, "bracket.html": view}
    assert _producers(view, outputs) == [("calibrated.toml", calibrate), ("bracket", tensor)]
    assert _producers(tensor, outputs) == [("calibrated.toml", calibrate)] and _producers(calibrate, outputs) == []
    # a second command writing the same name reads nothing of the first's: it is not run before it
    # (``tumble plot examples/seed_flip.toml --out figures`` ran ``tumble plot examples/explorer1.toml
    # --out figures`` first)
    again = ("calibrate", "d.toml", "--alone", "a2.csv", "--out", "calibrated.toml")
    assert _producers(again, outputs) == [] and _producers(("plot", "x.toml", "--out", "bracket"), outputs) == []
