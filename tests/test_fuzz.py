"""Hundreds of malformed body and scenario files: each one line on stderr, exit 2, nothing written.

Mutations of valid files, drawn with a fixed seed so that a failure is reproducible: keys
deleted or renamed, values replaced by wrong types, NaN, inf, negative, zero and huge numbers,
unknown kinds, truncated and corrupted TOML, empty files and binary junk, impossible inertia.
A mutation that happens to leave the file valid may succeed (exit 0); nothing may fail with a
traceback or as a "computation failure" (exit 1), and a failed command writes no file.
"""

from __future__ import annotations

import random
import re

import pytest

from tumble.cli import main

BODY = """[body]
name = "fuzz"

[[body.parts]]
kind = "cylinder"
mass = 1.5
radius = 0.05
length = 1.0
center = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]

[[body.parts]]
kind = "box"
density = 800.0
size = [0.3, 0.1, 0.05]
center = [0.0, 0.0, 0.5]
rotation = [0.0, 0.0, 0.0, 1.0]

[[body.parts]]
kind = "sphere"
density = 800.0
radius = 0.02
center = [0.0, 0.0, 0.5]
subtract = true
"""

SCENARIO = """body = "t-handle"

[initial]
omega = [0.1, 3.0, 0.1]
frame = "principal"

[simulation]
t_end = 0.5
samples = 5
method = "exact"
"""

BAD_VALUES = ['"text"', "true", "[]", "{}", "nan", "inf", "-inf", "-1.0", "0.0", "0", "1e308", "-1e308",
              "1e-320", "[1.0, 2.0]", "[nan, 0.0, 0.0]", "[1e308, 1e308, 1e308]", "100000000000000000000000000000",
              '"t-handle"', "[[1.0, 0.0], [0.0, 1.0]]", "2024-01-01", '"dop853"', "-0.0"]

KEY = re.compile(r"^(\w+)\s*=\s*(.+)$", re.M)


def mutations(text: str, rng: random.Random, n: int) -> list[str]:
    lines = text.splitlines(keepends=True)
    keys = [i for i, line in enumerate(lines) if KEY.match(line)]
    out = []
    for _ in range(n):
        kind = rng.choice(["value", "value", "value", "delete", "rename", "truncate", "corrupt", "kind", "duplicate"])
        new = list(lines)
        i = rng.choice(keys)
        name = KEY.match(lines[i]).group(1)
        if kind == "value":
            new[i] = f"{name} = {rng.choice(BAD_VALUES)}\n"
        elif kind == "delete":
            del new[i]
        elif kind == "rename":
            new[i] = new[i].replace(name, name + "x", 1)
        elif kind == "truncate":
            flat = "".join(lines)
            out.append(flat[: rng.randrange(len(flat))])
            continue
        elif kind == "corrupt":
            flat = bytearray("".join(lines).encode())
            for _ in range(rng.randint(1, 5)):
                flat[rng.randrange(len(flat))] = rng.randrange(256)
            out.append(flat)
            continue
        elif kind == "kind":
            new[i] = f'kind = "{rng.choice(["blob", "Rod", "", "mesh", "shell", "point"])}"\n' if name == "kind" else new[i]
        elif kind == "duplicate":
            new.insert(i, lines[i])
        out.append("".join(new))
    return out


SPECIALS = ["", b"\x00" * 64,
            "[[body.parts]]\nkind='sphere'\nmass=1.0\nradius=1e200\n",
            "[[body.parts]]\nkind='rod'\nmass=1e308\nlength=1e200\n",
            "[[body.parts]]\nkind='box'\ndensity=1e300\nsize=[1e10, 1e10, 1e10]\n",
            "[[body.parts]]\nkind='point'\nmass=1.0\ncenter=[1e300, 0.0, 0.0]\n[[body.parts]]\nkind='point'\nmass=1.0\n",
            "[[body.parts]]\nkind='tube'\nmass=1.0\ninner_radius=0.2\nouter_radius=0.1\nlength=1.0\n", bytes(range(256)), "[body", "[[body.parts]]\n", "=\n", "body = \n", "\ufeff[body]\n",
            # impossible inertia: a hole with more axial inertia than the body
            "[[body.parts]]\nkind='sphere'\nmass=1.0\nradius=0.1\n[[body.parts]]\nkind='cylinder'\nmass=0.5\nradius=0.5\nlength=0.01\nsubtract=true\n"]


def cases():
    rng = random.Random(20261122)
    body = [("inertia", m) for m in mutations(BODY, rng, 150)] + [("inertia", s) for s in SPECIALS]
    scen = [("simulate", m) for m in mutations(SCENARIO, rng, 150)] + [("simulate", s) for s in SPECIALS]
    return body + scen


def test_most_mutations_are_refused(tmp_path, capsys):
    """The generator really produces bad input (else the fuzz test below would prove little)."""
    codes = []
    for command, content in cases()[::5]:
        path = tmp_path / "f.toml"
        path.write_bytes(content if isinstance(content, (bytes, bytearray)) else content.encode())
        codes.append(main([command, str(path)] + (["--out", str(tmp_path / "o")] if command == "simulate" else [])))
        capsys.readouterr()
    assert codes.count(2) > 0.6 * len(codes)


@pytest.mark.parametrize(("command", "content"), cases())
def test_malformed_input_gets_one_line_and_exit_2(tmp_path, capsys, command, content):
    path = tmp_path / "input.toml"
    if isinstance(content, (bytes, bytearray)):
        path.write_bytes(bytes(content))
    else:
        path.write_text(content, encoding="utf-8")
    out = tmp_path / "out"
    argv = ["inertia", str(path)] if command == "inertia" else ["simulate", str(path), "--out", str(out)]
    code = main(argv)
    _, err = capsys.readouterr()
    assert code in (0, 2), err
    assert "Traceback" not in err
    if code == 2:
        assert err.count("\n") == 1 and err.startswith("tumble: error: "), err
        assert not out.exists()
