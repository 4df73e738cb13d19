"""The smaller items of issue 40 (the first hour III), each held by a test that fails without it."""

from __future__ import annotations

import contextlib
import io
import pydoc

import pytest

import tumble
from tumble.cli import main
from tumble.dynamics.methods.integrators import METHODS
from tumble.dynamics.methods.names import METHOD_NAMES


def _help(*argv: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        main([*argv, "--help"])
    return " ".join(out.getvalue().split())  # argparse wraps lines: a name is never cut, but may sit on the next


def test_the_help_lists_every_method_of_the_registry():
    """help(tumble.simulate) and the commands' --help named seven methods of twelve (no rk4, rk8,
    exact_split*); both now read the registry's names."""
    assert tuple(METHODS) == METHOD_NAMES  # the names the help texts read are the registry's
    doc = pydoc.render_doc(tumble.simulate, renderer=pydoc.plaintext)
    for text in (doc, _help("view"), _help("simulate"), _help("plot")):
        listed = {word.strip("`,.()") for word in text.split()}
        assert set(METHODS) <= listed, set(METHODS) - listed
