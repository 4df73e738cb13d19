"""Each formula of issue 38, item 4, is written once: a test over the package's sources.

For each formula the characteristic writings (regular expressions over the code with its
comments, strings and blanks taken out, line by line) and its one home. Every other module
calls the home; a writing found anywhere else fails the test, unless it is one of the copies
listed in :data:`EXCEPTIONS` (in the rooms being moved onto the engine by their owners). As the
Earth-constants test of tests/test_architecture.py does for the constants, the check can fail:
each writing is matched on a sample of the copies it was written against.
"""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest

import tumble

SRC = Path(tumble.__file__).resolve().parent

#: A part of a name, or an index ``[...]`` after it.
_IX = r"(\[[^\]]*\])?"

#: formula -> (its home, relative to src/tumble; its writings; samples each writing must find).
FORMULAS: dict[str, tuple[str, tuple[str, ...], tuple[str, ...]]] = {
    "Euler's equations, angular-velocity form": (
        "dynamics/euler.py",
        (r"(?<![\w\]*])\(I\w*" + _IX + r"-I\w*" + _IX + r"\)\*w\w*" + _IX + r"\*w",  # (I2 - I3) w2 w3
         r"cross\((I|J|moments|inertia)\w*\*\w+(\+\w+)?,\w+\)",  # (I w) x w
         r"cross\(w\w*,([\w.]+\()?[\w.]*\b(I|moments)\)?\*w",  # w x (I w)
         r"cross\(w\w*,w@I\b",  # w x (w I)
         r"=I\w*(\[0\])?\*w\w*(\[0\])?,I\w*(\[1\])?\*w\w*(\[1\])?,I\w*(\[2\])?\*w\w*(\[2\])?"),  # I w by component
        ("out[0] = ((I[1] - I[2]) * w[1] * w[2] + tau) / I[0]", "return (np.cross(I * w, w) + tau) / I",
         "dw = I_rw_inv @ (tau - _cross(w, I * w + h))", "L_r = L_r + np.cross(w, np.asarray(self.moments) * w + h)",
         "return (-np.cross(w, w @ I + h)) @ Iinv", "h0, h1, h2 = I[0] * w0, I[1] * w1, I[2] * w2"),
    ),
    "Euler's equation, momentum form (L' = L x w)": (
        "dynamics/euler.py",
        (r"\bL\w*(\[1\]|1)\*w\w*(\[2\]|2)-L\w*(\[2\]|2)\*w\w*(\[1\]|1)", r"cross\(L\w*,w\w*\)"),
        ("out[0] = L[1] * w[2] - L[2] * w[1] + tau", "dL = _cross(L, w)"),
    ),
    "quaternion kinematics (q' = q (x) (w, 0) / 2)": (
        "dynamics/special/quaternion.py",
        (r"0\.5\*(np\.array\(\[|\()\w+\*w\w*\+\(?\w+\*w\w*-\w+\*w\w*",),
        ("out[0] = 0.5 * (c * w0 + yq * w2 - z * w1)", "dq = 0.5 * np.array([c * w0_ + y_ * w2 - z * w1, c * w1])"),
    ),
    "the Hamilton product of two quaternions": (
        "dynamics/special/quaternion.py",
        (r"(\w+" + _IX + r"\*\w+" + _IX + r"-){3}\w+" + _IX + r"\*\w+",  # s1 s2 - x1 x2 - y1 y2 - z1 z2
         r"\*\w+\+\w+\*\w+\+np\.cross\("),  # w v + s u + u x v
        ("w = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]", "ns = s * dw - x * dx - y * dy - z * dz",
         "out[..., :3] = w * v + s * u + np.cross(u, v)"),
    ),
    "the rotation of a vector by a quaternion (its matrix)": (
        "dynamics/special/quaternion.py",
        (r"1(\.0)?-2(\.0)?\*\((\w+)\*\3\+(\w+)\*\4\)",  # 1 - 2 (y^2 + z^2): the unit quaternion's diagonal
         r"\b(\w+)\*\1\+(\w+)\*\2-(\w+)\*\3-(\w+)\*\4\b"),  # s^2 + x^2 - y^2 - z^2: the homogeneous form's
        ("r00 = 1.0 - 2.0 * (yq * yq + z * z)", "return (1 - 2 * (y * y + z * z)) * v0",
         "r00 = s * s + x * x - y * y - z * z"),
    ),
    "the Earth's turn (theta0 + OMEGA_EARTH t)": (
        "dynamics/environment/earth.py",
        (r"OMEGA_EARTH\*", r"\*OMEGA_EARTH\b"),
        ("theta = gmst0 + OMEGA_EARTH * t", "c = math.cos(t * OMEGA_EARTH)"),
    ),
    "a circular orbit's direction over floats ((cos n t, sin n t))": (
        "dynamics/environment/orbit.py",
        (r"cos\((\w+)\*(\w+)\),\w*\.?sin\(\1\*\2\)",),
        ("return math.cos(n * t), math.sin(n * t)", "u0, u1 = (math.cos(n * t), math.sin(n * t)) if n != 0.0 else (1.0, 0.0)"),
    ),
    "DOP853's step control (an accepted step and its rejections, scipy's RungeKutta._step_impl)": (
        "dynamics/engine/unrolled.py",
        (r"np\.nextafter\(t\w*,np\.inf\)-t", r"_next_step\(_error_norm\("),
        ("min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)",
         "accepted, h_abs = _next_step(_error_norm(e5, e3, h_abs, _size(P)), h_abs, rejected)"),
    ),
    "the dipole field ((a/r)^3 (3 (g . r^) r^ - g))": (
        "dynamics/environment/magnetic.py",
        (r"3(\.0)?\*\(\w+\*g\w*\+\w+\*g\w*\+\w+\*g\w*\)", r"3(\.0)?\*\(\w+@g\w*\)"),
        ("gu = 3.0 * (u0 * g0 + u1 * g1 + u2 * g2)", "b = f * (3.0 * (u @ g)[..., None] * u - g)"),
    ),
    "the triangle inequality on principal moments": (
        "validation/values.py",
        (r"2(\.0)?\*np\.max\(", r"\[\.\.\.,2\]-\w+\[\.\.\.,0\]-\w+\[\.\.\.,1\]", r"\w+\[(:|\.\.\.),0\]\+\w+\[(:|\.\.\.),1\]>=?1",
         r"\b[xX]\+[yY]>=?1", r"\w+\[0\]\+\w+\[1\]-\w+\[2\]"),
        ("excess = moments[..., 2] - moments[..., 0] - moments[..., 1]", "ok = xy[:, 0] + xy[:, 1] >= 1.0",
         "inside = (X < Y) & (X + Y > 1.0)", "gap = float(m[0] + m[1] - m[2])", "2.0 * np.max(I, axis=-1) - total"),
    ),
}

#: The copies still written beside their homes: (formula, module) -> why.
EXCEPTIONS: dict[tuple[str, str], str] = {}


def code_lines(path: Path) -> dict[int, str]:
    """The code of a module line by line, without comments, strings (docstrings included) or blanks."""
    skip = {tokenize.COMMENT, tokenize.STRING, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT,
            tokenize.ENDMARKER}
    skip |= {getattr(tokenize, name) for name in ("FSTRING_START", "FSTRING_MIDDLE", "FSTRING_END")
             if hasattr(tokenize, name)}
    lines: dict[int, list[str]] = {}
    for tok in tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline):
        if tok.type not in skip:
            lines.setdefault(tok.start[0], []).append(tok.string)
    return {n: "".join(parts) for n, parts in lines.items()}


def writings() -> dict[tuple[str, str], list[str]]:
    """Every writing of every formula in the package: (formula, module) -> ["line: code", ...]."""
    found: dict[tuple[str, str], list[str]] = {}
    for path in sorted(SRC.rglob("*.py")):
        module = path.relative_to(SRC).as_posix()
        for n, line in code_lines(path).items():
            for formula, (_, patterns, _) in FORMULAS.items():
                if any(re.search(p, line) for p in patterns):
                    found.setdefault((formula, module), []).append(f"{module}:{n}: {line}")
    return found


def _squeeze(code: str) -> str:
    return re.sub(r"\s+", "", code)


@pytest.mark.parametrize("formula", sorted(FORMULAS))
def test_each_writing_finds_the_copies_it_was_written_against(formula):
    _, patterns, samples = FORMULAS[formula]
    for sample in samples:
        assert any(re.search(p, _squeeze(sample)) for p in patterns), (formula, sample)
    for pattern in patterns:  # and each writing finds at least one sample
        assert any(re.search(pattern, _squeeze(s)) for s in samples), (formula, pattern)


@pytest.mark.parametrize("formula", sorted(FORMULAS))
def test_each_formula_has_its_home(formula):
    home = FORMULAS[formula][0]
    assert (SRC / home).exists(), home


def test_each_formula_is_written_only_in_its_home():
    found = writings()
    stray = [line for (formula, module), lines in sorted(found.items())
             if module != FORMULAS[formula][0] and (formula, module) not in EXCEPTIONS for line in lines]
    assert not stray, ("formulas written again outside their homes (call the home instead):\n"
                       + "\n".join(f"{line}" for line in stray))


def test_the_exceptions_are_still_copies():
    """A copy moved onto its home is taken off the list."""
    found = writings()
    gone = [key for key in EXCEPTIONS if key not in found]
    assert not gone, f"no longer written there: take them off EXCEPTIONS: {gone}"
