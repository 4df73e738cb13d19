"""The ``tumble`` commands that a user is shown: in the README, the guides (``docs/*.md``) and
the ``--help`` texts (every subcommand's ``Example:`` / ``Examples:`` epilog, ``|``-separated).

Read from the files and the parser, never copied into a list, so that a command added to a guide
or a help text is run by ``tests/test_wheel_commands.py`` without anyone adding it there.

- A fenced code block's lines that start with ``tumble `` are commands (a trailing ``# ...``
  comment is dropped), and so are the epilogs' examples; each must parse.
- An inline code span ``tumble ...`` is a command if it parses; one that does not
  (``tumble inertia --json``, ``tumble simulate``) names a command or an option in the prose.
- ``[--json]``, an optional part, is run with the part.
- An upper-case placeholder (``DIR``, ``SCENARIO``, ``SWEEP.toml``, ``A.csv``, ``S``): as an output
  (after ``--out`` or ``--copy``) it becomes a fresh folder name; as an input it marks a synopsis
  (``tumble simulate SCENARIO --out DIR``), which is not run (:attr:`Shown.synopsis`). So does
  ``...`` and a shell variable (``$f``).
- An absolute output path (``--out /tmp/x``) becomes a relative one: the test writes only in its folder.
- The lines right after a command (not a synopsis) in its code block, up to the next command, a blank line or a
  comment line, are what it prints, as shown (:attr:`Shown.output`; wrapped to the page's width):
  ``tests/test_shown_outputs.py`` runs it and compares.
"""

from __future__ import annotations

import re
import shlex
from dataclasses import dataclass, replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The pages whose commands are collected: the README and every guide.
PAGES = (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")))

_FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})(.*)$")
_INLINE = re.compile(r"(?<!`)`(tumble [^`]+)`(?!`)")
_PLACEHOLDER = re.compile(r"[A-Z][A-Z0-9_]*(\.[A-Za-z0-9]+)?/?")
_OUTPUT_OPTIONS = ("--out", "--copy")


@dataclass(frozen=True)
class Shown:
    """One command as shown, and as it is run.

    ``where`` is ``"docs/tour.md:601"`` or ``"tumble sweep --help"``; ``shown`` the text as
    written; ``argv`` the arguments after ``tumble`` as run (placeholders filled), or ``None`` for
    a synopsis (an input placeholder, ``...`` or a shell variable); ``inline`` whether it was an
    inline code span (run only if it parses); ``output`` what the page shows it printing (the lines
    after it in its code block, joined by newlines; ``""`` for none).
    """

    where: str
    shown: str
    argv: tuple[str, ...] | None
    inline: bool = False
    output: str = ""

    @property
    def synopsis(self) -> bool:
        return self.argv is None


def _argv(text: str) -> tuple[str, ...] | None:
    """The arguments after ``tumble`` of one shown command, or ``None`` for a synopsis."""
    words = shlex.split(text.replace("[", " ").replace("]", " "), comments=True)
    assert words[0] == "tumble", text
    words = words[1:]
    if any(w == "..." or "$" in w for w in words):
        return None
    out: list[str] = []
    for i, word in enumerate(words):
        is_output = i > 0 and words[i - 1] in _OUTPUT_OPTIONS
        if _PLACEHOLDER.fullmatch(word):
            if not is_output:
                return None
            word = f"out-{word.strip('/').lower().replace('.', '-')}-{i}"
        elif is_output and word.startswith("/"):
            word = word.lstrip("/").replace("/", "-")
        out.append(word)
    return tuple(out)


def _fenced_lines(text: str):
    """(line number, line) of every line inside a fenced code block (any language)."""
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        match = _FENCE.match(line)
        if fence is None:
            if match:
                fence = match.group(2)
            continue
        if match and match.group(2).startswith(fence[0] * len(fence)) and not match.group(3).strip():
            fence = None
            continue
        yield number, line


def page_commands(page: Path) -> list[Shown]:
    """Every command a page shows, in the page's order."""
    text = page.read_text(encoding="utf-8")
    name = page.relative_to(ROOT).as_posix() if page.is_relative_to(ROOT) else page.name
    found = []
    fenced = dict(_fenced_lines(text))
    printed: dict[int, list[str]] = {}  # index in found -> the lines shown after the command
    last = None  # (index of the last fenced command, the number of the line its output has reached)
    for number, line in enumerate(text.splitlines(), 1):
        if number in fenced:
            stripped = line.strip().removeprefix("$ ").removeprefix(".venv/bin/")
            if stripped.startswith("tumble "):
                found.append(Shown(f"{name}:{number}", stripped, _argv(stripped)))
                last = (len(found) - 1, number)
            elif last and last[1] == number - 1 and stripped and not stripped.startswith("#"):
                printed.setdefault(last[0], []).append(line.rstrip())
                last = (last[0], number)
            continue
        for span in _INLINE.findall(line):
            found.append(Shown(f"{name}:{number}", span, _argv(span), inline=True))
    # a synopsis is not run: what follows it in a shell block (``printf ...``) is more script
    return [replace(c, output="\n".join(printed[i])) if i in printed and not c.synopsis else c
            for i, c in enumerate(found)]


def same_output(shown: str, printed: str) -> bool:
    """Whether a command printed what a page shows it printing: the same words, whatever the
    wrapping (the page wraps long lines to its width)."""
    return shown.split() == printed.split()


def _parser_epilogs() -> dict[str, str]:
    """The epilogs of ``tumble --help`` and of every ``tumble COMMAND --help``, from the parser."""
    from tumble.cli.parser import build_parser

    parser = build_parser()
    texts = {"tumble --help": parser.epilog or ""}
    for action in parser._subparsers._group_actions:  # the subcommands, in their order
        texts.update({f"tumble {name} --help": sub.epilog or "" for name, sub in action.choices.items()})
    return texts


def help_commands(texts: dict[str, str] | None = None) -> list[Shown]:
    """The examples of ``tumble --help`` and of every subcommand's ``--help``.

    ``texts`` maps ``"tumble fit --help"`` to what that prints (an installed tumble's, with
    ``COLUMNS`` wide enough not to wrap); by default the parser's epilogs.
    """
    texts = _parser_epilogs() if texts is None else texts
    found = []
    for where, text in texts.items():
        match = re.search(r"^Examples?: (.*)", text, flags=re.S | re.M)
        assert match, f"{where}: shows no example: {text[-300:]!r}"
        for example in match.group(1).split(" | "):
            example = " ".join(example.split())
            found.append(Shown(where, example, _argv(example)))
    return found


def shown_commands() -> list[Shown]:
    """Every command of the README, the guides and the help texts (pages first, in order)."""
    return [c for page in PAGES for c in page_commands(page)] + help_commands()


def run_here(folder: Path, argv: tuple[str, ...]) -> tuple[int, str]:
    """Run ``tumble ARGV`` in this process from ``folder``: its exit status and what it printed
    (its standard output, then its standard error)."""
    import contextlib
    import io
    import os

    from tumble.cli import main

    out, err = io.StringIO(), io.StringIO()
    here = os.getcwd()
    os.chdir(folder)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(list(argv))
    finally:
        os.chdir(here)
    return code, out.getvalue() + err.getvalue()


def run_shown_outputs(page: Path, folder: Path) -> list[tuple[Shown, int, str]]:
    """Run, in page order from ``folder`` (where ``examples/`` has been copied), every command of
    ``page`` that the page shows printing something: each with its exit status and what it printed."""
    return [(c, *run_here(folder, c.argv)) for c in page_commands(page) if c.output and c.argv is not None]
