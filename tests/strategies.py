"""Hypothesis strategies: random parts, bodies and rotations."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import tumble

#: For tests of the mathematics over these wide draws: a part of 0.01 kg 10 m across is far lighter
#: than any solid, which tumble warns of (a likely slip of units, tests/test_bodyfile.py); here it
#: is the draw, not a slip.
ANY_SIZE = pytest.mark.filterwarnings("ignore::tumble.mass.UnitSlipWarning")

lengths = st.floats(min_value=0.01, max_value=10.0)
masses = st.floats(min_value=0.01, max_value=100.0)
coords = st.floats(min_value=-5.0, max_value=5.0)
vectors = st.tuples(coords, coords, coords)
directions = st.tuples(coords, coords, coords).filter(lambda v: np.linalg.norm(v) > 0.1)
quaternions = st.tuples(*[st.floats(-1, 1)] * 4).filter(lambda q: np.linalg.norm(q) > 0.1)


@st.composite
def rotations(draw):
    return Rotation.from_quat(draw(quaternions))


@st.composite
def parts(draw, planar: bool = False):
    """A random part; with ``planar`` only parts lying in the design xy plane (z = 0)."""
    m = draw(masses)
    if planar:
        x, y = draw(coords), draw(coords)
        kind = draw(st.sampled_from(["rod", "point"]))
        if kind == "point":
            return tumble.PointMass(mass=m, center=(x, y, 0.0))
        ang = draw(st.floats(0, 2 * np.pi))
        return tumble.Rod(mass=m, length=draw(lengths), center=(x, y, 0.0), axis=(np.cos(ang), np.sin(ang), 0.0))
    c = draw(vectors)
    kind = draw(st.sampled_from(["rod", "cylinder", "tube", "cone", "box", "ellipsoid", "sphere", "shell", "point"]))
    if kind == "rod":
        return tumble.Rod(mass=m, length=draw(lengths), center=c, axis=draw(directions))
    if kind == "cylinder":
        return tumble.Cylinder(mass=m, radius=draw(lengths), length=draw(lengths), center=c, axis=draw(directions))
    if kind == "tube":
        a, b = sorted(draw(st.lists(lengths, min_size=2, max_size=2, unique=True)))
        return tumble.Tube(mass=m, inner_radius=a, outer_radius=b, length=draw(lengths), center=c, axis=draw(directions))
    if kind == "cone":
        return tumble.Cone(mass=m, radius=draw(lengths), height=draw(lengths), center=c, axis=draw(directions))
    if kind == "box":
        return tumble.Box(mass=m, size=(draw(lengths), draw(lengths), draw(lengths)), center=c, rotation=draw(rotations()))
    if kind == "ellipsoid":
        return tumble.Ellipsoid(mass=m, semi_axes=(draw(lengths), draw(lengths), draw(lengths)), center=c, rotation=draw(rotations()))
    if kind == "sphere":
        return tumble.Sphere(mass=m, radius=draw(lengths), center=c)
    if kind == "shell":
        return tumble.Shell(mass=m, radius=draw(lengths), center=c)
    return tumble.PointMass(mass=m, center=c)


@st.composite
def bodies(draw, planar: bool = False, max_parts: int = 6):
    n = draw(st.integers(1, max_parts))
    return tumble.Body(tuple(draw(parts(planar=planar)) for _ in range(n)))
