"""Bad part input: each gets a ValueError naming the field, the value and what is allowed."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import tumble


@pytest.mark.parametrize(
    ("make", "pattern"),
    [
        (lambda: tumble.Rod(mass=-1.0, length=1.0), r"mass = -1.0 must be a positive finite number \(kg\)"),
        (lambda: tumble.Rod(mass=0.0, length=1.0), r"mass = 0.0 must be a positive"),
        (lambda: tumble.Rod(mass=math.nan, length=1.0), r"mass = nan must be a finite number"),
        (lambda: tumble.Rod(mass=1.0, length=math.inf), r"length = inf must be a finite number \(m\)"),
        (lambda: tumble.Rod(mass="1", length=1.0), r"mass = '1' must be a number"),
        (lambda: tumble.Rod(mass=True, length=1.0), r"mass = True must be a number"),
        (lambda: tumble.Rod(density=1.0, length=1.0), r"rod has no volume"),
        (lambda: tumble.Cylinder(radius=1.0, length=1.0), r"exactly one of 'mass' \(kg\) or 'density'.*got neither"),
        (lambda: tumble.Cylinder(mass=1.0, density=1.0, radius=1.0, length=1.0), r"got mass and density"),
        (lambda: tumble.Cylinder(mass=1.0, radius=-0.1, length=1.0), r"radius = -0.1 must be a positive"),
        (lambda: tumble.Tube(mass=1.0, inner_radius=0.5, outer_radius=0.5, length=1.0), r"inner_radius = 0.5 must be smaller than outer_radius"),
        (lambda: tumble.Box(mass=1.0, size=(1.0, 0.0, 1.0)), r"size\[1\] = 0.0 must be a positive"),
        (lambda: tumble.Box(mass=1.0, size=(1.0, 1.0)), r"size = \(1.0, 1.0\) must be a list of 3 numbers"),
        (lambda: tumble.Box(mass=1.0, size=(1, 1, 1), rotation=(0, 0, 0, 2)), r"quaternion of norm 2"),
        (lambda: tumble.Box(mass=1.0, size=(1, 1, 1), rotation=np.diag([1.0, 1.0, -1.0])), r"rotoreflection"),
        (lambda: tumble.Box(mass=1.0, size=(1, 1, 1), rotation=np.diag([1.0, 2.0, 1.0])), r"not an orthonormal matrix"),
        (lambda: tumble.Box(mass=1.0, size=(1, 1, 1), rotation="x"), r"quaternion \[x, y, z, w\] or a 3x3"),
        (lambda: tumble.Rod(mass=1.0, length=1.0, axis=(0, 0, 0)), r"axis = \(0, 0, 0\) must be a non-zero vector"),
        (lambda: tumble.Rod(mass=1.0, length=1.0, center=(0, math.nan, 0)), r"center\[1\] = nan must be a finite"),
        (lambda: tumble.Rod(mass=1.0, length=1.0, center="abc"), r"center = 'abc' must be a list of 3 numbers"),
        (lambda: tumble.Shell(mass=1.0, radius=1.0, subtract=True), r"shell has no volume and cannot be subtracted"),
        (lambda: tumble.PointMass(mass=1.0, subtract="yes"), r"subtract = 'yes' must be true or false"),
    ],
)
def test_bad_part_input(make, pattern):
    with pytest.raises(ValueError, match=pattern):
        make()


def test_unit_quaternion_within_tolerance_is_accepted():
    box = tumble.Box(mass=1.0, size=(1, 1, 1), rotation=(0, 0, 0.7071, 0.7071))
    assert np.linalg.norm(box.rotation) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize(("spin", "said"), [
    ({"spin_rate": lambda: 5.0}, "spin_rate = <lambda>() cannot be called as s(t): it must take that argument"),
    ({"spin_rate": lambda t: 5.0 * t, "spin_acceleration": lambda t, u: 5.0},
     "spin_acceleration = <lambda>(t, u) cannot be called as a(t): it must take that argument"),
])
def test_a_rotors_spin_function_is_checked_where_it_is_given(spin, said):
    """A spin function that cannot take the time was accepted by Rotor and Body and failed only in
    simulate, with Python's own TypeError naming neither spin_rate nor the rotor."""
    with pytest.raises(ValueError, match=f"^{re.escape(said)}$"):
        tumble.Rotor(mass=1.0, radius=0.1, length=0.03, **spin)


def test_a_density_or_a_mesh_scale_no_solid_has_is_refused_naming_it():
    """tumble inertia --density 1e308 failed with numpy's "overflow encountered in multiply", --scale 1e-200 with
    "invalid value encountered in divide" (exit 1), and --density 1e-320 gave a centre of mass 0.249258 for 0.25
    (subnormal masses): a QA walkthrough, 2026-12-03."""
    import pathlib

    torus = pathlib.Path(tumble.__file__).parent / "examples" / "bodies" / "meshes" / "torus.stl"
    for rho in (1e308, 1e-320):
        with pytest.raises(ValueError, match=re.escape(f"density = {rho!r} kg/m^3 is beyond any solid's")):
            tumble.Box(density=rho, size=(0.1, 0.2, 0.3))
    with pytest.raises(ValueError, match=r"with scale = 1e-200 is 1e-201 m across: beyond what tumble weighs"):
        tumble.Mesh(mesh=str(torus), density=1000.0, scale=1e-200)
    assert tumble.Box(density=0.16, size=(1.0, 1.0, 1.0)).mass == pytest.approx(0.16)   # an aerogel
