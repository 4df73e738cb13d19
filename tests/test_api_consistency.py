"""One consistent public API: axis numbering, the principal-axes matrix in JSON, strict vectors.

docs/conventions.md, "Numbering the principal axes" and "Principal moments and axes".
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from strategies import rotations

import tumble
from tumble.analysis import axis_of, circulation_axis, linearised_rate, stability_report, trajectory_summary
from tumble.cli import main
from tumble.io.export import CSV_COLUMNS
from tumble.io.report import mass_properties_dict
from tumble.mass import AXIS_ROLES
from tumble.validation import check_vector


def random_box(seed: int) -> tumble.Body:
    rng = np.random.default_rng(seed)
    from scipy.spatial.transform import Rotation

    box = tumble.Box(mass=2.0, size=tuple(rng.uniform(0.1, 1.0, 3)), center=tuple(rng.normal(size=3)),
                     rotation=Rotation.random(random_state=seed))
    return tumble.Body([box, tumble.PointMass(mass=0.3, center=tuple(rng.normal(size=3)))], name=f"box{seed}")


BODIES = {"t_handle": tumble.t_handle, "iss_t_handle": tumble.iss_t_handle,
          "random_box": lambda: random_box(7), "another_box": lambda: random_box(11)}


def assert_columns_are_the_principal_axes(A, body):
    """Column j of A is the unit eigenvector of the inertia tensor for moment I_(j+1)."""
    I = body.principal_moments
    for j in range(3):
        np.testing.assert_allclose(body.inertia @ A[:, j], I[j] * A[:, j], atol=1e-12 * I.sum())
        assert np.linalg.norm(A[:, j]) == pytest.approx(1.0, abs=1e-12)
    assert np.linalg.det(A) == pytest.approx(1.0, abs=1e-12)


# -- principal_axes is one matrix, columns are the axes, in Python and in JSON ----------------------

@pytest.mark.parametrize("name", BODIES)
def test_inertia_json_principal_axes_is_the_python_matrix(name):
    body = BODIES[name]()
    data = json.loads(json.dumps(mass_properties_dict(body)))
    A = np.array(data["principal_axes"])
    np.testing.assert_array_equal(A, body.principal_axes)
    assert_columns_are_the_principal_axes(A, body)
    if data["intermediate_axis"] is not None:
        np.testing.assert_array_equal(data["intermediate_axis"], A[:, 1])


@pytest.mark.parametrize("preset", ["t-handle", "iss-t-handle"])
def test_cli_inertia_json_principal_axes_is_the_python_matrix(capsys, preset):
    assert main(["inertia", preset, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    body = tumble.load_body(preset)
    np.testing.assert_array_equal(np.array(data["principal_axes"]), body.principal_axes)
    assert_columns_are_the_principal_axes(np.array(data["principal_axes"]), body)


@pytest.mark.parametrize("name", BODIES)
def test_summary_json_principal_axes_is_the_python_matrix(name):
    body = BODIES[name]()
    traj = tumble.simulate(body, [0.1, 3.0, 0.1], t_end=1.0, samples=5)
    data = json.loads(json.dumps(trajectory_summary(traj)))
    np.testing.assert_array_equal(np.array(data["principal_axes"]), body.principal_axes)
    np.testing.assert_array_equal(np.array(data["principal_axes"]), traj.principal_axes)


def test_cli_simulate_summary_json_principal_axes(tmp_path):
    scenario = tmp_path / "run.toml"
    scenario.write_text('body = "t-handle"\n[initial]\nomega = [0.1, 10.0, 0.1]\n'
                        '[simulation]\nt_end = 2.0\nsamples = 50\nmethod = "exact"\n')
    assert main(["simulate", str(scenario), "--out", str(tmp_path / "out")]) == 0
    data = json.loads((tmp_path / "out" / "summary.json").read_text())
    body = tumble.t_handle()
    # the seed's T-handle: columns +z (minor), +x (intermediate), +y (major); not symmetric,
    # so rows and columns cannot be confused
    np.testing.assert_array_equal(np.array(data["principal_axes"]), body.principal_axes)
    np.testing.assert_allclose(np.array(data["principal_axes"])[:, 1], [1.0, 0.0, 0.0], atol=1e-15)
    assert data["stability"]["axis"] == 2 and data["stability"]["role"] == "intermediate"


# -- axes count from 1 in every output and every argument ----------------------------------------

@pytest.mark.parametrize("axis", [1, 2, 3])
def test_every_output_numbers_the_spin_axis_alike(axis):
    body = tumble.iss_t_handle()
    w0 = np.full(3, 0.05)
    w0[axis - 1] = 5.0
    traj = tumble.simulate(body, w0, t_end=2.0, samples=200)
    report = stability_report(traj)
    assert report["axis"] == axis == axis_of(w0)
    assert report["role"] == AXIS_ROLES[axis - 1]
    assert CSV_COLUMNS[axis].startswith(f"omega_{axis} ")  # column 0 is t
    growth, wobble = tumble.linearised_rate(body.principal_moments, report["axis"], 5.0)
    assert (report["growth_rate"] or 0.0) == pytest.approx(float(growth))
    assert (report["wobble_frequency"] or 0.0) == pytest.approx(float(wobble))
    assert linearised_rate(body.principal_moments, report["role"], 5.0) == (growth, wobble)
    # the circulation axis is 1 or 3, never the intermediate axis, and the unstable spin flips
    assert circulation_axis(w0, body.principal_moments) in (1, 3)
    assert (report["flip_period_exact"] is not None) == (axis == 2)


def test_top_level_linearised_rate_is_one_based():
    growth, wobble = tumble.linearised_rate(tumble.t_handle().principal_moments, 2, 10.0)
    assert growth > 0 and wobble == 0  # axis 2 is the intermediate one
    with pytest.raises(ValueError, match=r"^axis = -1 must be 1, 2 or 3"):
        tumble.linearised_rate(tumble.t_handle().principal_moments, -1, 10.0)


# -- a vector given by hand is a list, a tuple or an array of exactly 3 numbers --------------------

NOT_VECTORS = [
    {0: 1.0, 1: 2.0, 2: 3.0},  # a dict: its keys would become the vector
    {1.0, 2.0, 3.0},  # a set: no order
    frozenset({1.0, 2.0, 3.0}),
    "1,2",
    b"abc",
    [[1.0, 2.0, 3.0]],
    [[1.0], [2.0], [3.0]],
    np.zeros((1, 3)),
    np.zeros((3, 1)),
    np.zeros(4),
    np.float64(1.0),
    None,
]


@pytest.mark.parametrize("value", NOT_VECTORS, ids=lambda v: type(v).__name__)
def test_check_vector_refuses_anything_but_three_numbers(value):
    with pytest.raises(ValueError, match=r"^center(\[\d\])? = .* must be (a list of 3 numbers|a number) \(m\)$"):
        check_vector("center", value, "m")


def test_generators_are_refused():
    with pytest.raises(ValueError, match=r"^omega0 = <generator .* must be a list of 3 numbers \(rad/s\)"):
        tumble.simulate(tumble.t_handle(), (x for x in (0.1, 10.0, 0.1)), t_end=1.0)


@pytest.mark.parametrize("value", [[1.0, 2.0, 3.0], (1, 2, 3), np.array([1.0, 2.0, 3.0]), np.arange(1, 4), range(1, 4)])
def test_check_vector_accepts_sequences_and_arrays_of_three(value):
    assert check_vector("center", value, "m") == (1.0, 2.0, 3.0)


def test_a_dict_is_refused_where_users_give_vectors():
    d = {0: 0.1, 1: 10.0, 2: 0.1}
    with pytest.raises(ValueError, match=r"^omega0 = \{0: 0.1, 1: 10.0, 2: 0.1\} must be a list of 3 numbers"):
        tumble.simulate(tumble.t_handle(), d, t_end=1.0)
    with pytest.raises(ValueError, match=r"^center = \{0: 0.1, 1: 10.0, 2: 0.1\} must be a list of 3 numbers"):
        tumble.Sphere(mass=1.0, radius=0.1, center=d)
    with pytest.raises(ValueError, match=r"^torque vector = \{0.0, 1.0, 2.0\} must be a list of 3 numbers"):
        tumble.ConstantTorque({0.0, 1.0, 2.0})
    with pytest.raises(ValueError, match=r"^axis = \{0: 0.1, 1: 10.0, 2: 0.1\} must be a list of 3 numbers"):
        tumble.Rod(mass=1.0, length=1.0, axis=d)


non_sequences = st.one_of(
    st.dictionaries(st.integers(0, 10) | st.floats(allow_nan=False), st.floats(), min_size=3, max_size=3),
    st.sets(st.floats(allow_nan=False), min_size=3, max_size=3),
    st.frozensets(st.integers(), min_size=3, max_size=3),
    st.lists(st.floats(), min_size=3, max_size=3).map(iter),
    st.lists(st.floats(), min_size=3, max_size=3).map(lambda xs: (x for x in xs)),
    st.text(min_size=3, max_size=3),
    st.binary(min_size=3, max_size=3),
    st.integers() | st.floats() | st.none() | st.booleans(),
    st.lists(st.lists(st.floats(), min_size=1, max_size=3), min_size=3, max_size=3),
    st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=0, max_size=6).filter(lambda xs: len(xs) != 3),
)


@given(non_sequences)
def test_no_non_sequence_is_ever_accepted_as_a_vector(value):
    with pytest.raises(ValueError, match=r"^omega0"):
        check_vector("omega0", value, "rad/s")


@given(rotations())
def test_a_rotated_box_json_round_trip(rot):
    body = tumble.Body([tumble.Box(mass=1.0, size=(0.2, 0.5, 0.9), rotation=rot)])
    A = np.array(json.loads(json.dumps(mass_properties_dict(body)))["principal_axes"])
    np.testing.assert_array_equal(A, body.principal_axes)
    # the box's shortest edge (local x, 0.2 m) carries the largest moment: axis 3 is +-R e_x
    assert abs(A[:, 2] @ rot.apply([1.0, 0.0, 0.0])) == pytest.approx(1.0, abs=1e-9)
