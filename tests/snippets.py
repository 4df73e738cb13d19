"""Run the README's and the docs' Python examples and hold them to what their comments claim.

A snippet that runs is not enough: its comments tell a reader what to expect (``# no flip``,
``# [0.125, 0.3125, 0.4375]``, ``# ~1e-16``), and a comment that no longer matches the code
misleads as surely as a failing example. :func:`run_checked` executes a block one statement at a
time and checks the trailing comment of each statement:

- a comment on a run (a :class:`tumble.Trajectory`) or on a stability report (a dict with
  ``"flips"``) that says ``no flip`` or ``N flips`` (``-> 3 flips`` too), ``period X s``,
  ``stable`` / ``unstable`` or ``axis N`` is compared with :func:`tumble.stability_report`, and
  one that starts with a method's name (``# rk8 (auto); no flip``) with the method that ran;
- a comment on a bare expression (or a ``print``) that starts with a Python literal, or has one
  after its last ``": "`` (``# [0, 0, 0.25] m``, ``# (500, 3) rad/s``, ``# diag(1, 2, 3)``,
  ``# exact: 1.7864 s``, ``# True``), is compared with the value: a tuple of integers with an
  array's shape, numbers to half a unit in the last digit printed, ``~X`` to within a factor
  of 10 (``~0`` below 1e-3), anything else for equality. A tuple value whose comment has as many
  ``;``-separated parts is checked part by part.

A comment on a bare expression or a ``print`` that starts with the value's class name and ``(``
shows its repr (``# RecordingFit(12 of 12 flights, I1/I3 = ...)``): the repr must be that text, or
start with it up to the ``...)`` that ends a shortened one.

Comments that state no such claim (``# totals, J``) are prose and are left alone.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize

import numpy as np

import tumble

_FLIPS = re.compile(r"\b(no|\d+) flips?\b")
_PERIOD = re.compile(r"\b(?:period|one every) (\d+\.\d+) s\b")  # a report's flip interval
_PREDICTED = re.compile(r"\b(unstable|stable)\b")
_AXIS = re.compile(r"\baxis (\d)\b")
_DIAG = re.compile(r"diag\(([^()]*)\)")
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
#: A comment that starts with a method's name (``# dop853; ...``, ``# rk8 (auto); ...``) names the
#: method that ran (``radau``: where dop853 hands a stiff damper to scipy's Radau).
_METHOD = re.compile(rf"({'|'.join(re.escape(m) for m in sorted([*tumble.METHODS, 'radau'], key=len, reverse=True))})"
                     r"( \(auto\))?(?=[;,:]|$)")


def _comments(code: str) -> dict[int, str]:
    """Line number -> text of the comment that ends that line (without ``#``)."""
    found = {}
    for tok in tokenize.generate_tokens(io.StringIO(code).readline):
        if tok.type == tokenize.COMMENT:
            found[tok.start[0]] = tok.string.lstrip("#").strip()
    return found


def _literal(text: str):
    """The longest prefix of ``text`` that is a Python literal (or ``diag(...)``): (value, its text), or None."""
    text = text.strip()
    if text.startswith("->"):
        text = text[2:].strip()
    match = _DIAG.match(text)
    if match:
        return np.diag(ast.literal_eval(f"[{match.group(1)}]")), match.group(0)
    for end in range(len(text), 0, -1):
        head = text[:end]
        if head[-1].isspace():
            continue
        try:
            return ast.literal_eval(head), head
        except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError):
            continue
    return None


def _close(value, claim, text: str) -> bool:
    """``value`` agrees with ``claim`` as printed in ``text`` (see the module)."""
    approx = text.lstrip().startswith("~")
    if isinstance(claim, tuple) and all(isinstance(c, int) for c in claim) and hasattr(value, "shape"):
        return tuple(value.shape) == claim
    if isinstance(value, dict) and approx:
        return all(_close(v, claim, text) for v in value.values())
    numbers = _NUMBER.findall(text.lstrip("~-> "))
    try:
        got, want = np.asarray(value, dtype=float), np.asarray(claim, dtype=float)
    except (TypeError, ValueError):
        return value == claim
    if isinstance(claim, bool) or got.shape != want.shape:
        return bool(np.all(got == want)) if got.shape == want.shape else False
    if approx:
        bound = np.where(want == 0, 1e-3, 10 * np.abs(want))
        return bool(np.all(np.abs(got) <= bound))
    decimals = max((len(n.split(".")[1].split("e")[0].split("E")[0]) if "." in n else 0) for n in numbers)
    return bool(np.all(np.abs(got - want) <= 0.5 * 10.0 ** -decimals * (1 + 1e-9)))


def _check_run(value, comment: str, where: str) -> list[str]:
    """Claims about a run or a stability report; returns those checked."""
    report = tumble.stability_report(value) if isinstance(value, tumble.Trajectory) else value
    checked = []
    match = _FLIPS.search(comment)
    if match:
        flips = 0 if match.group(1) == "no" else int(match.group(1))
        assert report["flips"] == flips, f"{where}: the comment says {match.group(0)!r}, the run flips {report['flips']} times"
        checked.append(match.group(0))
    match = _PERIOD.search(comment)
    if match:
        assert _close(report["flip_period"], float(match.group(1)), match.group(1)), (
            f"{where}: the comment says {match.group(0)!r}, the measured period is {report['flip_period']} s")
        checked.append(match.group(0))
    match = _PREDICTED.search(comment)
    if match and checked:
        assert report["predicted"] == match.group(1), f"{where}: the comment says {match.group(1)}, predicted {report['predicted']}"
        checked.append(match.group(1))
    match = _AXIS.search(comment)
    if match and checked:
        assert report["axis"] == int(match.group(1)), f"{where}: the comment says {match.group(0)!r}, the axis is {report['axis']}"
        checked.append(match.group(0))
    match = _METHOD.match(comment)
    if match and isinstance(value, tumble.Trajectory):  # "# rk8 (auto); no flip": the method that ran
        assert match.group(1) == value.method and (match.group(2) is None or value.auto), (
            f"{where}: the comment says {match.group(0)!r}, the run's method is {value.method_label!r}")
        checked.append(match.group(0))
    return checked


def _check_repr(value, comment: str, where: str) -> list[str]:
    """A comment that shows a result's repr (``# RecordingFit(12 of 12 flights, ...)``): the repr
    itself, or up to the ``...)`` that ends a shortened one; returns the claim checked."""
    shown, claim = repr(value), comment.strip()
    head = claim[:-4].rstrip(", ") if claim.endswith("...)") else claim
    assert shown.startswith(head) if claim.endswith("...)") else shown == claim, (
        f"{where}: the comment says {claim!r}, the repr is {shown!r}")
    return [claim]


def _check_value(value, comment: str, where: str) -> list[str]:
    """A literal claim about a bare expression's value; returns those checked."""
    if isinstance(value, tuple) and comment.count(";") == len(value) - 1 and len(value) > 1:
        return [c for v, part in zip(value, comment.split(";")) for c in _check_value(v, part, where)]
    text = comment.strip()
    parsed = _literal(text.lstrip("~")) if text.startswith("~") else _literal(text)
    if parsed is None and ": " in text:
        text = text.rsplit(": ", 1)[1].strip()
        parsed = _literal(text.lstrip("~")) if text.startswith("~") else _literal(text)
    if parsed is None:
        return []
    claim, shown = parsed
    shown = ("~" if text.startswith("~") else "") + shown
    assert _close(value, claim, shown), f"{where}: the comment says {shown!r}, the value is {value!r}"
    return [shown]


def run_checked(code: str, filename: str) -> list[str]:
    """Execute ``code`` statement by statement, checking each trailing comment's claims.

    Returns the claims checked (as they appear in the comments); raises AssertionError naming
    ``filename``'s line when one does not hold.
    """
    comments = _comments(code)
    scope: dict = {}
    checked = []
    for stmt in ast.parse(code).body:
        comment = comments.get(stmt.end_lineno, "")
        where = f"{filename}, snippet line {stmt.end_lineno}"
        if isinstance(stmt, ast.Expr):
            call = stmt.value
            if isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and call.func.id == "print":
                exec(compile(ast.Module([stmt], []), filename, "exec"), scope)  # noqa: S102 - the snippet is ours
                args = [eval(compile(ast.Expression(a), filename, "eval"), scope) for a in call.args]
                value = args[0] if len(args) == 1 else tuple(args)
            else:
                value = eval(compile(ast.Expression(call), filename, "eval"), scope)
        else:
            exec(compile(ast.Module([stmt], []), filename, "exec"), scope)  # noqa: S102 - the snippet is ours
            targets = stmt.targets if isinstance(stmt, ast.Assign) else []
            value = scope[targets[0].id] if len(targets) == 1 and isinstance(targets[0], ast.Name) else None
        if not comment:
            continue
        if isinstance(value, tumble.Trajectory) or (isinstance(value, dict) and "flips" in value):
            checked += _check_run(value, comment, where)
            if isinstance(stmt, ast.Expr) and comment.startswith(type(value).__name__ + "("):  # a report's repr
                checked += _check_repr(value, comment, where)
        elif isinstance(stmt, ast.Expr) and value is not None and comment.startswith(type(value).__name__ + "("):
            checked += _check_repr(value, comment, where)
        elif isinstance(stmt, ast.Expr):
            checked += _check_value(value, comment, where)
    return checked


def python_blocks(text: str) -> list[str]:
    """The ```` ```python ```` blocks of a Markdown text."""
    return re.findall(r"```python\n(.*?)```", text, flags=re.DOTALL)
